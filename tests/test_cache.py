"""The facts cache: hits skip extraction, anything that changes facts misses, damage heals."""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import io
import mmap
import multiprocessing
import os
import pickle
import shutil
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from roslint_names import cache as cache_module
from roslint_names import model
from roslint_names.cache import FactsCache, default_directory
from roslint_names.model import (
    Compact,
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    ParameterAccess,
    Role,
    Span,
    rebuilder,
    replaced,
)
from roslint_names.workspace.graph import (
    EdgeKind,
    Endpoint,
    Graph,
    Location,
    NodeInstance,
    NodeRemap,
    Reach,
)
from roslint_names.workspace.index import Package
from roslint_names.workspace.parameters import Incomplete, NodeParameters, ParameterUse
from tests.conftest import write, write_package

LAUNCH = """<launch>
  <node pkg="robot_base" type="driver_node" name="base-driver">
    <remap from="Cmd_Vel" to="/cmd_vel/"/>
  </node>
</launch>
"""
FACTS = FileFacts(
    path="robot.launch",
    language=Language.LAUNCH_XML,
    generation=Generation.ROS1,
    names=(NameUse(Kind.TOPIC, "/cmd_vel", Span(3, 18, 3, 27), Role.REMAP_TO, "<remap to>"),),
)


@pytest.fixture
def check(run_cli: Any, tmp_path: Path) -> Callable[..., Any]:
    """Run `check --format json --jobs 1` over the tree in ``tmp_path/ws``."""
    workspace = tmp_path / "ws"
    workspace.mkdir()

    def run(*options: str) -> Any:
        return run_cli(["check", "--format", "json", "--jobs", "1", *options, "."], workspace)

    return run


def pack(root: Path) -> Path:
    """The one pack there is (of the sixteen a cache may hold)."""
    [found] = root.glob("facts-v*/facts-?.pack")
    return found


def records(root: Path) -> list[str]:
    """The keys of the facts records (not the logs' lines, not whole-run results)."""
    packs = root.glob("facts-v*/facts-?.pack")
    return sorted(key for found in packs for key in cache_module._index(found.read_bytes()))


def forget_runs(root: Path) -> None:
    """Delete the whole-run results and the replays (a run over the same facts takes
    the last one's), so that the next run goes to the facts entries."""
    for kept in (*root.glob("facts-v*/runs"), *root.glob("facts-v*/replays")):
        shutil.rmtree(kept)


def log_lines(root: Path) -> list[str]:
    return [
        line for log in root.glob("facts-v*/empty-?.log") for line in log.read_text().splitlines()
    ]


def test_a_hit_returns_the_same_facts_without_extracting(
    check: Callable[..., Any], tmp_path: Path, extractions: list[str], private_cache: Path
) -> None:
    write_package(tmp_path / "ws", ros=1)
    write(tmp_path / "ws", "launch/robot.launch", LAUNCH)
    write(tmp_path / "ws", "launch/clean.launch", "<launch/>\n")
    cold = check()
    assert sorted(extractions) == ["launch/clean.launch", "launch/robot.launch"]
    assert len(records(private_cache)) == 1  # robot.launch; clean.launch is a log line
    assert len(log_lines(private_cache)) == 1
    extractions.clear()
    forget_runs(private_cache)
    warm = check()
    assert extractions == []
    assert warm == cold and cold.codes()


def test_store_then_load_gives_equal_facts(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path / "cache")
    key = cache.key(b"<launch/>", "robot.launch", Language.LAUNCH_XML, None, Generation.ROS2)
    assert cache.load(key, FACTS.path) is None
    cache.store(key, FACTS)
    assert cache.load(key, FACTS.path) == FACTS  # stored by this process, not yet written
    cache.flush()
    assert (cache.stats.hits, cache.stats.misses, cache.stats.written) == (1, 1, 1)
    assert FactsCache(tmp_path / "cache").load(key, FACTS.path) == FACTS  # from the pack


def test_empty_facts_are_a_log_line_and_come_back_equal(tmp_path: Path) -> None:
    empty = FileFacts("scripts/setup.py", Language.LAUNCH_PYTHON, Generation.ROS1)
    writer = FactsCache(tmp_path)
    key = writer.key(b"", empty.path, Language.PYTHON, None, Generation.ROS1)
    writer.store(key, empty)
    writer.flush()
    assert records(tmp_path) == [] and len(log_lines(tmp_path)) == 1
    assert FactsCache(tmp_path).load(key, empty.path) == empty


def test_everything_an_extractor_sees_is_in_the_key(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    base = (b"<launch/>", "a.launch", Language.LAUNCH_XML, Generation.ROS1, Generation.ROS2)
    variants = [
        (b"<launch />", *base[1:]),
        (base[0], "b.launch", *base[2:]),
        (*base[:2], Language.URDF, *base[3:]),
        (*base[:3], None, base[4]),
        (*base[:3], Generation.ROS2, base[4]),
        (*base[:4], Generation.ROS1),
    ]
    keys = {cache.key(*base), *(cache.key(*variant) for variant in variants)}
    assert len(keys) == 1 + len(variants)


def test_a_changed_file_misses(
    check: Callable[..., Any], tmp_path: Path, extractions: list[str]
) -> None:
    write(tmp_path / "ws", "robot.launch", LAUNCH)
    write(tmp_path / "ws", "other.launch", "<launch/>\n")
    check()
    extractions.clear()
    write(tmp_path / "ws", "robot.launch", LAUNCH.replace("base-driver", "base_driver"))
    result = check()
    assert extractions == ["robot.launch"]
    assert "RN101" not in result.codes()


def test_a_changed_package_generation_misses(
    check: Callable[..., Any], tmp_path: Path, extractions: list[str]
) -> None:
    write_package(tmp_path / "ws", ros=1)
    # No marker of either generation (type=, exec=): the package decides.
    write(tmp_path / "ws", "robot.launch", LAUNCH.replace(' type="driver_node"', ""))
    ros1 = check()
    extractions.clear()
    write_package(tmp_path / "ws", ros=2)
    ros2 = check()
    assert extractions == ["robot.launch"]
    assert ros1.stdout != ros2.stdout  # RN102 is an error in ROS 2, a warning in ROS 1


def test_a_changed_fallback_generation_misses(
    check: Callable[..., Any], tmp_path: Path, extractions: list[str]
) -> None:
    write(tmp_path / "ws", "robot.launch", LAUNCH)
    check("--ros", "1")
    extractions.clear()
    check("--ros", "2")
    assert extractions == ["robot.launch"]
    extractions.clear()
    check("--ros", "1")
    assert extractions == []


def test_a_corrupt_record_is_skipped_and_written_again(
    check: Callable[..., Any], tmp_path: Path, extractions: list[str], private_cache: Path
) -> None:
    write(tmp_path / "ws", "robot.launch", LAUNCH)
    good = check()
    blob = pack(private_cache).read_bytes()
    for damage in (blob[: len(blob) // 2], b"", b"garbage", blob[:-1] + bytes([blob[-1] ^ 1])):
        pack(private_cache).write_bytes(damage)
        extractions.clear()
        forget_runs(private_cache)
        assert check() == good
        assert extractions == ["robot.launch"]  # the damaged record is skipped
        extractions.clear()
        forget_runs(private_cache)
        assert check() == good
        assert extractions == []  # the record appended after the damage is found


def test_a_record_naming_anything_but_facts_is_never_unpickled(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    key = cache.key(b"x", "a.launch", Language.LAUNCH_XML, None, Generation.ROS2)
    cache.store(key, FACTS)
    cache.flush()
    record = cache_module._record(key, pickle.dumps(os.getcwd))  # a global outside model
    assert record is not None
    pack(tmp_path).write_bytes(record)
    fresh = FactsCache(tmp_path)
    assert fresh.load(key, FACTS.path) is None
    assert fresh.stats.corrupt == 1


@pytest.mark.parametrize(
    ("name", "first", "second", "stored"),
    [
        # Facts with names are records of the pack; facts without are lines of the log.
        ("robot.launch", LAUNCH, LAUNCH.replace("base-driver", "base_driver"), "records"),
        ("empty.launch", "<launch/>\n", "<launch>\n</launch>\n", "log_lines"),
    ],
)
def test_past_the_limit_only_what_the_run_used_is_kept(  # noqa: PLR0917 - fixtures
    check: Callable[..., Any],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    private_cache: Path,
    extractions: list[str],
    name: str,
    first: str,
    second: str,
    stored: str,
) -> None:
    kept_in: Callable[[Path], list[str]] = {"records": records, "log_lines": log_lines}[stored]
    path = write(tmp_path / "ws", name, first)
    check()
    [first_key] = [found.split(" ")[0] for found in kept_in(private_cache)]
    # A run rewrites only the packs and logs it reads or appends to: the old version's
    # one only where the new version's key is in it too.
    path.write_text(in_shard(name, second, first_key[0], generation_keyed(name, first, first_key)))
    check()
    assert len(kept_in(private_cache)) == 2  # the file's old version and its new one
    limit = cache_module.PACK_LIMIT
    monkeypatch.setattr(cache_module, "PACK_LIMIT", 1)
    forget_runs(private_cache)
    check()
    [kept] = kept_in(private_cache)
    monkeypatch.setattr(cache_module, "PACK_LIMIT", limit)
    path.write_text(first)
    forget_runs(private_cache)
    extractions.clear()
    check()
    assert extractions == [name]  # the old version's entry is gone
    assert kept in kept_in(private_cache)


def launch_key(name: str, text: str, generation: Generation) -> str:
    """The key of a launch file of no package, linted with ``generation`` as fallback."""
    cache = FactsCache(Path("never-created"))
    return cache.key(text.encode(), name, Language.LAUNCH_XML, None, generation)


def generation_keyed(name: str, text: str, key: str) -> Generation:
    """The fallback generation the run keyed a launch file of no package with."""
    [generation] = [found for found in Generation if launch_key(name, text, found) == key]
    return generation


def in_shard(name: str, text: str, shard: str, generation: Generation) -> str:
    """``text`` with a comment after it that makes its key start with ``shard``: its
    facts in that pack or log (``cache.SHARDS``)."""
    candidates = (f"{text}<!-- {number} -->\n" for number in range(256))
    return next(found for found in candidates if launch_key(name, found, generation)[0] == shard)


def test_only_the_packs_and_logs_a_run_reads_are_rewritten(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A run after an edit looks up a few keys: it reads their packs, not the others
    (66 MB, 0.08 s to index at 8 copies of the benchmark's workspace), and rewrites only
    those past the limit, with what it used."""
    cache = FactsCache(tmp_path)
    looked_up, stale, elsewhere = "a" + "1" * 39, "a" + "2" * 39, "b" + "1" * 39
    empty = FileFacts("empty.py", Language.PYTHON, Generation.ROS2)
    for key in (looked_up, stale, elsewhere):
        cache.store(key, FACTS)
        cache.store(key[::-1], empty)  # a log line each, in the shards "1" and "2"
    cache.finish()
    entries = {found.name: found for found in tmp_path.glob("facts-v*/*-?.*")}
    assert sorted(entries) == ["empty-1.log", "empty-2.log", "facts-a.pack", "facts-b.pack"]
    before = {name: found.stat() for name, found in entries.items()}
    monkeypatch.setattr(cache_module, "PACK_LIMIT", 1)
    fresh = FactsCache(tmp_path)
    assert fresh.load(looked_up, FACTS.path) == FACTS
    assert fresh.load(looked_up[::-1], "empty.py") == empty
    # The key's log is looked in first: the one of "a" is read too (there is none).
    assert sorted(fresh._records) == ["a"] and sorted(fresh._empty) == ["1", "a"]
    fresh.finish()
    assert records(tmp_path) == [looked_up, elsewhere]  # the stale one dropped
    # The log of "1" past the limit: only the line the run used is left.
    assert sorted(line.split(" ")[0] for line in log_lines(tmp_path)) == [
        looked_up[::-1],
        stale[::-1],
    ]
    for name in ("facts-b.pack", "empty-2.log"):  # neither read nor appended to
        after = entries[name].stat()
        assert (after.st_ino, after.st_size) == (before[name].st_ino, before[name].st_size)


def test_what_is_appended_after_a_run_read_a_pack_or_log_is_kept_when_it_is_rewritten(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A cold run's main process reads the packs and logs early (an included launch
    file looked up under its includer's arguments) while its workers append every
    file's facts: rewritten with what the main process used of what it read, the packs
    lost all the workers had stored (15,253 files extracted again after the first edit
    at 8 copies of the benchmark's workspace)."""
    early, stale = "a" + "1" * 39, "a" + "2" * 39  # records of the pack "a"
    early_line, stale_line = "1" + "a" * 39, "1" + "b" * 39  # lines of the log "1"
    empty = FileFacts("empty.py", Language.PYTHON, Generation.ROS2)
    first = FactsCache(tmp_path)
    for key in (early, stale):
        first.store(key, FACTS)
    for key in (early_line, stale_line):
        first.store(key, empty)
    first.finish()
    monkeypatch.setattr(cache_module, "PACK_LIMIT", 1)
    main = FactsCache(tmp_path)
    assert main.load(early, FACTS.path) == FACTS
    assert main.load(early_line, "empty.py") == empty
    worker = FactsCache(tmp_path)  # appends after the main process read
    stored = [f"a{number:039x}" for number in range(3, 6)]
    stored_lines = [f"1{number:039x}" for number in range(3, 6)]
    for key, line_key in zip(stored, stored_lines, strict=True):
        worker.store(key, FACTS)
        worker.store(line_key, empty)
    worker.flush()
    main.finish()
    assert records(tmp_path) == sorted([early, *stored])  # the stale one dropped
    assert sorted(line.split(" ")[0] for line in log_lines(tmp_path)) == sorted(
        [early_line, *stored_lines]
    )
    fresh = FactsCache(tmp_path)
    assert all(fresh.load(key, FACTS.path) == FACTS for key in stored)
    assert all(fresh.load(key, "empty.py") == empty for key in stored_lines)
    assert fresh.stats.corrupt == 0


def test_a_pack_past_the_limit_that_the_run_used_whole_is_not_rewritten(
    check: Callable[..., Any],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    private_cache: Path,
) -> None:
    """A workspace whose facts alone outgrow the limit (eight copies of the benchmark's
    workspace: a 104 MB pack) had its whole pack rewritten by every run."""
    workspace = tmp_path / "ws"
    write(workspace, "robot1.launch", LAUNCH.replace("base-driver", "robot1-driver"))
    check()
    [key] = records(private_cache)
    generation = generation_keyed("robot1.launch", (workspace / "robot1.launch").read_text(), key)
    for robot in ("robot2", "robot3"):  # all three in one pack
        text = LAUNCH.replace("base-driver", f"{robot}-driver")
        write(workspace, f"{robot}.launch", in_shard(f"{robot}.launch", text, key[0], generation))
    check()
    assert len(records(private_cache)) == 3
    before = pack(private_cache).stat()
    monkeypatch.setattr(cache_module, "PACK_LIMIT", before.st_size // 2)
    forget_runs(private_cache)
    check()
    after = pack(private_cache).stat()
    assert (after.st_ino, after.st_size) == (before.st_ino, before.st_size)
    # Once most of it is stale, it is rewritten with what the run used.
    monkeypatch.setattr(cache_module, "PACK_LIMIT", before.st_size // 3)
    (workspace / "robot1.launch").unlink()
    (workspace / "robot2.launch").unlink()
    forget_runs(private_cache)
    check()
    assert len(records(private_cache)) == 1


def _store_repeatedly(root: str, key: str, rounds: int) -> None:
    cache = FactsCache(Path(root))
    for round_ in range(rounds):
        cache.store(key, FACTS)
        empty = FileFacts(f"{os.getpid()}-{round_}.py", Language.PYTHON, Generation.ROS2)
        cache.store(f"{os.getpid():08x}{round_:032x}", empty)
        if round_ % 7 == 0:
            cache.flush()  # appends of different sizes, racing with the other writer's
    cache.flush()


def test_two_writers_racing_leave_a_valid_entry(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    key = cache.key(b"race", "robot.launch", Language.LAUNCH_XML, None, Generation.ROS1)
    cache.writable()
    context = multiprocessing.get_context("spawn")
    writers = [
        context.Process(target=_store_repeatedly, args=(str(tmp_path), key, 200)) for _ in range(2)
    ]
    for writer in writers:
        writer.start()
    while any(writer.is_alive() for writer in writers):
        reader = FactsCache(tmp_path)  # reads the pack as it is now
        assert reader.load(key, FACTS.path) in (None, FACTS)  # absent or whole, never half
        assert reader.stats.corrupt == 0
    for writer in writers:
        writer.join()
        assert writer.exitcode == 0
    assert FactsCache(tmp_path).load(key, FACTS.path) == FACTS
    data = pack(tmp_path).read_bytes()
    record = cache_module._record(key, pickle.dumps(FACTS, protocol=pickle.HIGHEST_PROTOCOL))
    assert record is not None and data == record * 400  # every append whole, none lost
    lines = log_lines(tmp_path)
    assert len(lines) == 2 * 200  # every append whole, none lost
    logs = tmp_path.glob("facts-v*/empty-?.log")
    assert sum(len(cache_module._read_log_as(str(log))[0]) for log in logs) == 400


def test_a_torn_or_damaged_log_line_is_skipped(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    keys = [f"c{number:039x}" for number in range(4)]  # one log's
    for key in keys:
        cache.store(key, FileFacts("x.py", Language.PYTHON, Generation.ROS2))
    cache.flush()
    [log] = tmp_path.glob("facts-v*/empty-c.log")
    first, second, third, fourth = log.read_bytes().splitlines(keepends=True)
    damaged = second.replace(b" python ", b" launch-xml ")  # checksum no longer matches
    log.write_bytes(first + b"garbage line\n" + damaged + b"\xff\xfe\n" + third + fourth[:-1])
    fresh = FactsCache(tmp_path)
    found = [fresh.load(key, "x.py") is not None for key in keys]
    assert found == [True, False, True, False]  # the last one lacks its line break


def test_no_cache_neither_creates_nor_reads_the_directory(
    check: Callable[..., Any], tmp_path: Path, extractions: list[str], private_cache: Path
) -> None:
    write(tmp_path / "ws", "robot.launch", LAUNCH)
    check("--no-cache")
    assert not private_cache.exists()
    check()
    extractions.clear()
    check("--no-cache")
    assert extractions == ["robot.launch"]


def test_cache_dir_option_is_used(check: Callable[..., Any], tmp_path: Path) -> None:
    write(tmp_path / "ws", "robot.launch", LAUNCH)
    check("--cache-dir", str(tmp_path / "mine"))
    assert len(records(tmp_path / "mine")) == 1
    assert (tmp_path / "mine" / "CACHEDIR.TAG").is_file()


def tree_digest(root: Path) -> dict[str, str]:
    return {
        path.relative_to(root).as_posix(): (
            "dir" if path.is_dir() else hashlib.sha256(path.read_bytes()).hexdigest()
        )
        for path in sorted(root.rglob("*"))
    }


def test_the_cache_never_writes_under_the_linted_tree(
    check: Callable[..., Any], tmp_path: Path, private_cache: Path
) -> None:
    workspace = tmp_path / "ws"
    write_package(workspace, ros=1)
    write(workspace, "launch/robot.launch", LAUNCH)
    write(workspace, "urdf/robot.urdf", '<robot name="r"><link name="base_link"/></robot>\n')
    before = tree_digest(workspace)
    check()
    check()
    assert tree_digest(workspace) == before
    assert records(private_cache)


def test_an_unwritable_cache_directory_only_slows_the_run(
    check: Callable[..., Any], tmp_path: Path
) -> None:
    write(tmp_path / "ws", "robot.launch", LAUNCH)
    expected = check("--no-cache")
    blocked = tmp_path / "not-a-directory"
    blocked.write_text("a file where the cache directory should be\n")
    quiet = check("--cache-dir", str(blocked))
    assert (quiet.exit_code, quiet.stdout, quiet.stderr) == (
        expected.exit_code,
        expected.stdout,
        expected.stderr,
    )
    verbose = check("--cache-dir", str(blocked), "--verbose")
    assert verbose.stdout == expected.stdout
    assert verbose.stderr.count("cache disabled") == 1


def test_default_directory_follows_xdg() -> None:
    assert default_directory({"XDG_CACHE_HOME": "/x/cache"}) == Path("/x/cache/roslint-names")
    home = Path.home() / ".cache" / "roslint-names"
    assert default_directory({"XDG_CACHE_HOME": "relative/cache"}) == home  # spec: ignore
    assert default_directory({}) == home


def test_the_fingerprint_covers_the_extractors_and_the_model() -> None:
    package = Path(cache_module.__file__).parent
    sources = {
        path.relative_to(package).as_posix() for path in cache_module._extractor_sources(package)
    }
    # Every extractor subpackage's modules, and what they import from the package.
    assert {
        "extract/cpp/source.py",
        "extract/python/walk.py",
        "extract/launch/xml_launch.py",
        "extract/launch/substitution.py",
        "extract/build/cmake_syntax.py",
        "model.py",
        "names.py",
        "reading.py",
    } <= sources
    assert cache_module.run_fingerprint() == cache_module.run_fingerprint()


def test_stale_directories_of_other_versions_are_pruned(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Directories the cache made for other versions (another fingerprint), tagged as
    its own when they were made: deleted once unused for a day."""
    directories = {}
    for fingerprint in ("0123456789abcdef", "fedcba9876543210"):
        monkeypatch.setattr(cache_module, "run_fingerprint", lambda f=fingerprint: f)
        other_version = FactsCache(tmp_path)
        assert other_version.writable()
        directories[fingerprint] = other_version.directory
    monkeypatch.undo()
    old, recent = directories["0123456789abcdef"], directories["fedcba9876543210"]
    unrelated = tmp_path / "my-notes"
    (unrelated / "ab").mkdir(parents=True)
    long_ago = 1_000_000_000
    os.utime(old, (long_ago, long_ago))
    os.utime(unrelated, (long_ago, long_ago))
    assert FactsCache(tmp_path).writable()
    assert not old.exists()
    assert recent.exists() and unrelated.exists()


def test_pruning_spares_folders_the_cache_did_not_create(
    check: Callable[..., Any], tmp_path: Path
) -> None:
    """``--cache-dir`` on a folder the user keeps things in: its ``facts-v1`` (untagged),
    older than a day, was deleted with everything in it; and the folder itself got a
    CACHEDIR.TAG, which tells backup tools to skip all of it."""
    mine = tmp_path / "mine"
    thesis = write(mine, "facts-v1/chapter-1/results.csv", "run,error\n1,0.25\n")
    symlinked = tmp_path / "elsewhere" / "facts-v2-0123456789abcdef"
    write(symlinked, "CACHEDIR.TAG", cache_module._CACHEDIR_TAG)
    (mine / "facts-v2-0123456789abcdef").symlink_to(symlinked, target_is_directory=True)
    long_ago = 1_000_000_000
    for directory in (thesis.parent.parent, symlinked):
        os.utime(directory, (long_ago, long_ago))
    write(tmp_path / "ws", "robot.launch", LAUNCH)
    assert check("--cache-dir", str(mine)).exit_code == 1
    assert thesis.read_text() == "run,error\n1,0.25\n"
    assert symlinked.is_dir()  # a link is never followed into, whatever it holds
    assert not (mine / "CACHEDIR.TAG").exists()
    [entries] = (path for path in mine.glob("facts-v2-*") if not path.is_symlink())
    assert (entries / "CACHEDIR.TAG").read_text() == cache_module._CACHEDIR_TAG


def test_a_cache_sent_to_a_worker_carries_where_it_is_not_what_was_read(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    key = cache.key(b"x", "a.launch", Language.LAUNCH_XML, None, Generation.ROS2)
    cache.store(key, FACTS)
    cache.flush()
    reader = FactsCache(tmp_path)
    assert reader.load(key, FACTS.path) == FACTS  # the pack is now in its memory
    copy = pickle.loads(pickle.dumps(reader))
    assert copy.root == tmp_path and copy.directory == reader.directory
    assert len(pickle.dumps(reader)) < 200  # neither the pack nor the keys it looked up
    assert copy.load(key, FACTS.path) == FACTS


class _Python3112Pickler(pickle.Pickler):
    """Enum members as Python 3.11.0 to 3.11.4 pickle them (Debian 12's 3.11.2):
    ``getattr(Language, "CPP")``."""

    def reducer_override(self, obj: Any) -> Any:
        if isinstance(obj, enum.Enum):
            return getattr, (type(obj), obj.name)
        return NotImplemented


def _pickled_as_by_python_3_11_2(value: Any) -> bytes:
    stream = io.BytesIO()
    _Python3112Pickler(stream, protocol=pickle.HIGHEST_PROTOCOL).dump(value)
    return stream.getvalue()


def test_facts_pickled_by_python_3_11_2_are_read() -> None:
    blob = _pickled_as_by_python_3_11_2(FACTS)
    assert b"getattr" in blob
    assert cache_module._unpickle_facts(blob) == FACTS


@pytest.mark.parametrize(
    "reduced",
    [
        (getattr, (FileFacts, "__init__")),  # a model class, but no enum
        (getattr, (Language, "__class__")),  # a model enum, but no member
        (getattr, (enum.Enum, "__new__")),  # an enum outside the model
    ],
)
def test_getattr_in_a_record_reaches_nothing_but_an_enum_member(reduced: Any) -> None:
    class Hostile:
        def __reduce__(self) -> Any:
            return reduced

    assert cache_module._unpickle(pickle.dumps(Hostile())) is None


def _records(count: int, size: int) -> list[tuple[str, bytes]]:
    """``count`` records of about ``size`` bytes each, as (key, record)."""
    made = []
    for number in range(count):
        key = f"{number:040x}"
        facts = FileFacts(f"src/{number}/a.launch", Language.LAUNCH_XML, Generation.ROS1)
        facts = FileFacts(facts.path, facts.language, facts.generation, literals=("x" * size,))
        record = cache_module._record(key, pickle.dumps(facts, protocol=pickle.HIGHEST_PROTOCOL))
        assert record is not None
        made.append((key, record))
    return made


@pytest.mark.parametrize(
    "damage",
    [
        "none",
        "torn tail",  # a writer stopped mid-record
        "flipped payload",  # looks whole: indexed, a miss where loaded
        "torn middle",  # the next record follows a torn one
        "marker in payload",
    ],
)
def test_a_mapped_pack_indexes_and_loads_as_its_bytes(tmp_path: Path, damage: str) -> None:
    """The pack is mapped and its pages handed back as it is indexed (``_released``):
    every record, damaged or not, is found or missed as in the pack's bytes, across
    more than one release."""
    made = _records(40, 400_000)  # 16 MB: two releases
    records = [record for _, record in made]
    if damage == "torn tail":
        records[-1] = records[-1][:1000]
    elif damage == "flipped payload":
        records[5] = records[5][:-10] + bytes([records[5][-10] ^ 1]) + records[5][-9:]
    elif damage == "torn middle":
        records[7] = records[7][:5000]
    elif damage == "marker in payload":
        records[3] = records[3] + cache_module._RECORD + b"garbage"
    data = b"".join(records)
    path = tmp_path / "facts.pack"
    path.write_bytes(data)
    mapped, _, opened = cache_module._map_as(str(path))
    assert opened is not None
    opened.close()
    assert isinstance(mapped, mmap.mmap)
    indexed = cache_module._index(mapped)
    assert indexed == cache_module._index(data)
    for key, _ in made:
        where = indexed.get(key)
        loaded = where is not None and cache_module._intact(mapped, *where)
        assert loaded == (where is not None and cache_module._intact(data, *where))
        expected_missing = (damage, key) in {
            ("torn tail", made[-1][0]),
            ("flipped payload", made[5][0]),
            ("torn middle", made[7][0]),
        }
        assert loaded != expected_missing, key
        if loaded:
            assert where is not None
            assert mapped[where[0] : where[1]] == data[where[0] : where[1]]
    mapped.close()


def test_only_a_mapped_pack_s_pages_are_handed_back(tmp_path: Path) -> None:
    path = tmp_path / "facts.pack"
    path.write_bytes(b"\0" * (10 * 1024 * 1024))
    mapped, _, opened = cache_module._map_as(str(path))
    assert opened is not None
    opened.close()
    assert isinstance(mapped, mmap.mmap)
    step = cache_module._RELEASED_EVERY
    assert cache_module._released(mapped, 0, step - 1) == 0  # not yet a step indexed
    released = cache_module._released(mapped, 0, step + 100)
    assert released == step + 100 - (step + 100) % mmap.PAGESIZE
    assert cache_module._released(mapped, released, -1) == released  # the end: under a step
    assert mapped[:10] == b"\0" * 10  # handed back, read again from the file
    mapped.close()
    assert cache_module._released(b"\0" * (2 * step), 0, 2 * step) == 0  # bytes: nothing


def test_a_pack_under_a_step_is_handed_back_once_indexed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A pack is a sixteenth of the facts (4 MB at 8 copies of the benchmark's
    workspace): under a step, it was never handed back, and a run reading all sixteen
    held 50 MB more."""
    made = _records(12, 250_000)  # 3 MB
    path = tmp_path / "facts-0.pack"
    path.write_bytes(b"".join(record for _, record in made))
    mapped, _, opened = cache_module._map_as(str(path))
    assert opened is not None
    opened.close()
    assert isinstance(mapped, mmap.mmap)
    handed_back: list[int] = []
    released = cache_module._released

    def spied(pack: Any, start: int, position: int, **options: int) -> int:
        handed_back.append(released(pack, start, position, **options))
        return handed_back[-1]

    monkeypatch.setattr(cache_module, "_released", spied)
    assert len(cache_module._index(mapped)) == len(made)
    assert handed_back[-1] == path.stat().st_size  # its last page too, partly the pack's
    mapped.close()


def _pages_mapped(path: Path) -> int:
    """How many kB of the file at ``path`` this process's mappings hold in memory."""
    held, inside = 0, False
    for line in Path("/proc/self/smaps").read_text().splitlines():
        fields = line.split()
        if "-" in fields[0] and len(fields) >= 5:  # a mapping's first line
            inside = fields[-1] == str(path)
        elif inside and fields[0] == "Rss:":
            held += int(fields[1])
    return held


@pytest.mark.skipif(not Path("/proc/self/smaps").exists(), reason="no /proc/self/smaps")
@pytest.mark.parametrize("reads_at_offsets", [True, False])
def test_loaded_records_leave_no_page_of_their_pack_in_memory(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, reads_at_offsets: bool
) -> None:
    """A patch at 8 copies of the benchmark's workspace loads 2,000 files' facts: read
    from the mapping, each load kept the pages the kernel maps around the record, half
    of every pack (31 MB of a 313 MB peak). Read from the file, none; where the platform
    cannot read at an offset, from the mapping."""
    if not reads_at_offsets:
        monkeypatch.delattr(os, "pread")
    made = _records(200, 20_000)  # 4 MB, as a pack at 8 copies
    cache = FactsCache(tmp_path)
    pack = cache.directory / "facts-0.pack"
    pack.parent.mkdir(parents=True)
    pack.write_bytes(b"".join(record for _, record in made))
    for key, _ in made[::7]:
        facts = cache.load(key, "src/a.launch")
        assert facts is not None and facts.literals == ("x" * 20_000,)
    assert cache.stats.corrupt == 0
    held = _pages_mapped(pack)
    assert (held == 0) if reads_at_offsets else (held > 0)


@pytest.mark.skipif(not Path("/proc/self/fd").exists(), reason="no /proc/self/fd")
def test_a_finished_run_lets_its_packs_go_and_a_later_one_reads_them_again(
    tmp_path: Path,
) -> None:
    """What a run read of the packs (their indexes, the keys it used: 27 MB at 81,000
    files) was held through the stores after ``finish``, the peak of a run that keeps a
    rebased graph. ``finish`` closes the packs; the language server's cache, used again,
    reads them again."""
    made = _records(50, 1_000)
    cache = FactsCache(tmp_path)
    pack = cache.directory / "facts-0.pack"
    pack.parent.mkdir(parents=True)
    pack.write_bytes(b"".join(record for _, record in made))
    empty = FileFacts("src/b.launch", Language.LAUNCH_XML, Generation.ROS1)
    cache.store("1" + "0" * 39, empty)
    cache.flush()

    def opened() -> int:
        return sum(
            os.path.realpath(f"/proc/self/fd/{fd}") == str(pack)
            for fd in os.listdir("/proc/self/fd")
        )

    assert cache.load(made[3][0], "src/a.launch") is not None
    assert cache.load("1" + "0" * 39, "src/b.launch") == empty
    assert opened() > 0  # the file as opened, and its mapping's own descriptor
    cache.finish()
    assert opened() == 0
    assert "facts-0.pack" not in Path("/proc/self/maps").read_text()
    facts = cache.load(made[7][0], "src/a.launch")
    assert facts is not None and facts.literals == ("x" * 1_000,)
    assert cache.load("1" + "0" * 39, "src/b.launch") == empty
    assert cache.stats.corrupt == 0
    cache.finish()


def test_a_kept_graph_reads_back_as_it_was(tmp_path: Path) -> None:
    """The graph a build keeps for a later patch (``workspace.patch``): its classes, enums
    and the facts' own, through the unpickler that builds nothing else."""
    location = Location("src/a/src/talker.cpp", Span(3, 5, 3, 12))
    node = NodeInstance(
        "/talker",
        Generation.ROS2,
        "a",
        "talker",
        "",
        (),
        ("src/a/src/talker.cpp",),
        code_parameters=NodeParameters(
            declared=("rate",),
            incomplete=(Incomplete.RUN_TIME_READ,),
            uses=(ParameterUse("rate", ParameterAccess.DECLARE, location, "declare_parameter"),),
        ),
        reach=Reach(Generation.ROS2, packages=("a",)),
    )
    endpoint = Endpoint(
        "/chatter", Kind.TOPIC, EdgeKind.PUBLISH, "/talker", "", None, location, "chatter"
    )
    graph = Graph((node,), (endpoint,), {"a": frozenset({"a"})})
    cache = FactsCache(tmp_path)
    # The packages the graph was built with, kept with it (``same_facts.KeptGraph``).
    package = Package("a", "src/a", frozenset({"rclcpp"}), generation=Generation.ROS2)
    cache.store_graph("k", ("graph 1", ("t",), graph, (package,)))
    assert FactsCache(tmp_path).load_graph("k") == ("graph 1", ("t",), graph, (package,))


def test_a_kept_graph_holds_no_state_dict_per_object(tmp_path: Path) -> None:
    """The graph's classes keep their fields in slots and pickle as their class and
    values (``model.Compact``): a dict per node, endpoint and place, held by the
    unpickler to the end of a load, was the peak of a run that patched the graph."""
    location = Location("src/a/src/talker.cpp", Span(3, 5, 3, 12))
    remap = NodeRemap("/a", "/b", Span(1, 1, 1, 4), path="a.launch", own=True)
    node = NodeInstance(
        "/talker", Generation.ROS2, "a", "talker", "a.launch", (location,), (), remaps=(remap,)
    )
    endpoint = Endpoint(
        "/chatter", Kind.TOPIC, EdgeKind.PUBLISH, "/talker", "", None, location, "chatter"
    )
    graph = Graph((node,), (endpoint,))
    for value in (location, location.span, remap, node, node.reach, endpoint, graph):
        assert not hasattr(value, "__dict__"), type(value)
    blob = pickle.dumps(graph, protocol=5)
    assert b"launch_namespaces" not in blob and b"resource_kind" not in blob  # no field names
    cache = FactsCache(tmp_path)
    cache.store_graph("k", ("graph 1", (), graph, ()))
    loaded = FactsCache(tmp_path).load_graph("k")
    assert loaded == ("graph 1", (), graph, ())
    assert isinstance(loaded, tuple) and hash(loaded[2].nodes[0]) == hash(node)


def test_facts_hold_no_state_dict_per_object(tmp_path: Path) -> None:
    """The facts' classes too (``model.Compact``): a run after a launch edit loads every
    file's facts, hundreds of thousands of name uses at 77,000 files."""
    use = NameUse(Kind.TOPIC, "chatter", Span(3, 5, 3, 12), Role.PUBLISH, "create_publisher")
    facts = FileFacts("src/a/talker.cpp", Language.CPP, Generation.ROS2, names=(use,))
    assert not hasattr(use, "__dict__") and not hasattr(facts, "__dict__")
    assert b"type_name" not in pickle.dumps(facts, protocol=5)  # no field names
    cache = FactsCache(tmp_path)
    key = cache.key(b"x", "src/a/talker.cpp", Language.CPP, None, Generation.ROS2)
    cache.store(key, facts)
    cache.finish()
    assert FactsCache(tmp_path).load(key, "src/a/talker.cpp") == facts


@pytest.mark.parametrize("value", [os.getcwd, Path("x"), pickle.loads])
def test_a_kept_graph_naming_anything_but_graph_classes_is_never_unpickled(
    tmp_path: Path, value: object
) -> None:
    cache = FactsCache(tmp_path)
    cache.store_graph("k", ("graph 1", (), value))
    assert FactsCache(tmp_path).load_graph("k") is None


def _compact_classes() -> list[Any]:
    import roslint_names.workspace.graph
    import roslint_names.workspace.launch_parts
    import roslint_names.workspace.parameters  # noqa: F401 - their classes are found below

    found: list[Any] = []
    pending = list(Compact.__subclasses__())
    while pending:
        cls = pending.pop()
        pending.extend(cls.__subclasses__())
        if dataclasses.is_dataclass(cls):
            found.append(cls)
    return sorted(found, key=lambda cls: (cls.__module__, cls.__qualname__))


@pytest.mark.parametrize("cls", _compact_classes(), ids=lambda cls: cls.__qualname__)
def test_a_compact_class_is_rebuilt_as_its_init_builds_it(cls: Any) -> None:
    """The unpicklers build a ``Compact`` with ``model.rebuilder``, which sets its slots
    without the frozen ``__init__``: the same object, each field's value in its place."""
    values = [object() for _ in dataclasses.fields(cls)]
    rebuilt, made = rebuilder(cls)(*values), cls(*values)
    assert type(rebuilt) is cls
    assert rebuilt == made
    assert [getattr(rebuilt, item.name) for item in dataclasses.fields(cls)] == values
    with pytest.raises(dataclasses.FrozenInstanceError):
        rebuilt.__setattr__(dataclasses.fields(cls)[0].name, None)


@pytest.mark.parametrize("cls", _compact_classes(), ids=lambda cls: cls.__qualname__)
def test_a_compact_value_replaced_is_what_dataclasses_replace_gives(cls: Any) -> None:
    names = [item.name for item in dataclasses.fields(cls)]
    value = cls(*(object() for _ in names))
    for name in (names[0], names[-1]):
        changed = object()
        assert replaced(value, **{name: changed}) == dataclasses.replace(value, **{name: changed})
        assert getattr(replaced(value, **{name: changed}), name) is changed
    with pytest.raises(TypeError, match="no field 'nonexistent'"):
        replaced(value, nonexistent=1)


def test_compact_values_pickle_as_their_rebuilder_and_values(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """What a worker sends the main process, which unpickles it with pickle's own
    unpickler: the values and ``Span._rebuilt``, built again without ``__init__``."""
    use = NameUse(Kind.TOPIC, "chatter", Span(3, 5, 3, 12), Role.PUBLISH, "create_publisher")
    facts = FileFacts("src/a/talker.cpp", Language.CPP, Generation.ROS2, names=(use,))
    blob = pickle.dumps(facts, protocol=5)
    assert b"Span._rebuilt" in blob and b"NameUse._rebuilt" in blob

    def refused(*_: object) -> None:
        raise AssertionError("built through __init__")

    monkeypatch.setattr(Span, "__init__", refused)
    assert pickle.loads(blob) == facts
    # A process that never pickled one finds ``_rebuilt`` too (a worker's facts, read by
    # the main process: before, each pool broke and was started again, without end).
    fresh = subprocess.run(
        [sys.executable, "-c", "import pickle, sys; print(pickle.load(sys.stdin.buffer))"],
        input=blob,
        capture_output=True,
        check=True,
    )
    assert fresh.stdout.decode().startswith("FileFacts(path='src/a/talker.cpp'")


def _pickled_classes() -> list[Any]:
    """The Compact classes of their modules (a dataclass with slots is a class made
    again: the first one, a subclass still, is never instantiated)."""
    return [
        cls
        for cls in _compact_classes()
        if getattr(sys.modules[cls.__module__], cls.__qualname__, None) is cls
    ]


@pytest.mark.parametrize("cls", _pickled_classes(), ids=lambda cls: cls.__qualname__)
def test_the_fast_pickler_writes_what_pickle_writes(cls: Any) -> None:
    """``model.dumps`` reduces a Compact value in one call (``_Reducers``): the bytes of
    ``pickle.dumps``, so that a cache written by either reads the same."""
    value = cls(*range(len(dataclasses.fields(cls))))
    assert model.dumps(value) == pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    assert model.dumps([value, value]) == pickle.dumps([value, value], protocol=5)


def test_the_fast_pickler_writes_facts_and_other_classes_as_pickle_does() -> None:
    use = NameUse(Kind.TOPIC, "chatter", Span(3, 5, 3, 12), Role.PUBLISH, "create_publisher")
    facts = FileFacts("src/a/talker.cpp", Language.CPP, Generation.ROS2, names=(use, use))
    # ``complex`` is reduced by copyreg's table, a path by its own ``__reduce__``
    for value in (facts, (facts, Language.CPP, 1 + 2j, Path("src/a"), {"k": [use]})):
        blob = model.dumps(value)
        assert blob == pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        assert pickle.loads(blob) == value


def test_the_unpicklers_build_compact_values_through_their_rebuilder() -> None:
    """``find_class`` hands the unpickler a Compact class's rebuilder, by the class's
    name (what older pickles give) or its ``_rebuilt``; an enum stays its class; any
    other attribute is refused."""
    stream = io.BytesIO()
    for unpickler in (cache_module._FactsUnpickler, cache_module._GraphUnpickler):
        for name in ("Span", "Span._rebuilt"):
            found = unpickler(stream).find_class("roslint_names.model", name)
            assert found is rebuilder(Span) and found is not Span
        assert unpickler(stream).find_class("roslint_names.model", "Language") is Language
        for name in ("Language._rebuilt", "Span.__init__", "Span._values", "Span.x._rebuilt"):
            with pytest.raises(pickle.UnpicklingError):
                unpickler(stream).find_class("roslint_names.model", name)
