"""Worker processes and the cache change how fast a run is, never what it prints.

Also the worker dispatcher on its own, and when the progress line is drawn. No test here
measures time: the benchmark in bench/ does that.
"""

from __future__ import annotations

import io
import os
import pickle
import re
import shutil
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import pytest
from conftest import write

from roslint_names import cache as cache_module
from roslint_names import gather, reading, run_inputs, same_facts, workers
from roslint_names.cache import FactsCache
from roslint_names.gather import OnDisk
from roslint_names.progress import DELAY_SECONDS, ProgressBar, wanted
from roslint_names.workers import Dispatcher, worker_count

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


# Two robots from the example fleet's launch file: the engine extracts fleet.launch.py
# again under each robot's name (a specialisation), in the workers when there are some.
TWO_ROBOTS_LAUNCH = """\
<launch>
  <include file="$(dirname)/fleet.launch.py">
    <arg name="robot" value="robot1"/>
  </include>
  <include file="$(dirname)/fleet.launch.py">
    <arg name="robot" value="robot3"/>
  </include>
</launch>
"""


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """The example workspace twice over (C++, Python, launch XML/YAML, XACRO), with one
    launch file that includes another under two sets of arguments."""
    root = tmp_path / "ws"
    shutil.copytree(EXAMPLES, root)
    shutil.copytree(EXAMPLES / "src", root / "src" / "copy")
    launch = root / "src" / "fleet_bringup" / "launch" / "two_robots.launch.xml"
    launch.write_text(TWO_ROBOTS_LAUNCH)
    return root


@pytest.fixture
def small_chunks(monkeypatch: pytest.MonkeyPatch) -> None:
    """Start workers from the second file on and send two files per chunk, so that even a
    small workspace is spread over several chunks and both workers."""
    monkeypatch.setattr(workers, "MIN_ITEMS", 2)
    monkeypatch.setattr(workers, "CHUNK_ITEMS", 2)


@pytest.mark.usefixtures("small_chunks")
@pytest.mark.parametrize("output_format", ["text", "json", "sarif"])
def test_output_bytes_do_not_depend_on_jobs_or_cache(
    run_cli: Any, workspace: Path, tmp_path: Path, output_format: str
) -> None:
    def run(*options: str) -> Any:
        arguments = ["check", "--format", output_format, "--show-source", "--verbose", *options]
        return run_cli([*arguments, "."], workspace)

    def details(result: Any) -> str:
        return str(result.stderr.splitlines()[0])

    cache = ["--cache-dir", str(tmp_path / "cache")]
    reference = run("--jobs", "1", "--no-cache")
    assert reference.exit_code == 1 and reference.stdout
    cold_parallel = run("--jobs", "2", *cache)
    assert "extracted by 2 worker processes" in details(cold_parallel)
    warm_parallel = run("--jobs", "2", *cache)
    assert "its result reused" in details(warm_parallel)
    for runs in (tmp_path / "cache").glob("facts-v*/runs"):
        shutil.rmtree(runs)  # the next run builds its result from the cached facts
    warm_single = run("--jobs", "1", *cache)
    assert re.search(r" (\d+) of \1 files from the cache, 0 extracted", details(warm_single))
    other_cache = ["--cache-dir", str(tmp_path / "other")]
    cold_single = run("--jobs", "1", *other_cache)
    assert "extracted by this process" in details(cold_single)
    for result in (cold_parallel, warm_parallel, warm_single, cold_single):
        assert result.stdout == reference.stdout
        assert result.exit_code == reference.exit_code
        assert result.stderr.splitlines()[1:] == reference.stderr.splitlines()[1:]


@pytest.mark.usefixtures("small_chunks")
def test_a_first_run_keeps_what_its_workers_extracted_when_it_rewrites_the_packs(
    run_cli: Any, workspace: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A run stands on every checked file's facts, whichever process extracted them:
    the main process of a first run read packs (the included launch file's arguments
    looked up) after its workers had appended to them, and rewrote those past the limit
    with what it had used alone (a fifth of the files extracted again after the first
    edit at 8 copies of the benchmark's workspace)."""
    monkeypatch.setattr(cache_module, "PACK_LIMIT", 1)  # every pack read is past it
    finish = FactsCache.finish

    def read_late(cache: FactsCache) -> None:  # every pack and log read after the workers
        for shard in cache_module.SHARDS:
            cache.load(shard * 40, "never.launch")
        finish(cache)

    monkeypatch.setattr(FactsCache, "finish", read_late)
    arguments = ["check", "--format", "json", "--verbose", "--cache-dir", str(tmp_path / "c")]
    cold = run_cli([*arguments, "--jobs", "2", "."], workspace)
    assert "extracted by 2 worker processes" in cold.stderr.splitlines()[0]
    for kept in (
        *(tmp_path / "c").glob("facts-v*/runs"),
        *(tmp_path / "c").glob("facts-v*/replays"),
    ):
        shutil.rmtree(kept)  # the next run loads every file's facts
    warm = run_cli([*arguments, "--jobs", "1", "."], workspace)
    assert re.search(r" (\d+) of \1 files from the cache, 0 extracted", warm.stderr), warm.stderr
    assert warm.stdout == cold.stdout


@pytest.mark.usefixtures("small_chunks", "old_tree")
def test_a_first_run_reads_each_file_where_it_is_extracted(
    run_cli: Any, workspace: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With no facts to look up by content, the main process reads no file to key it: the
    worker extracting it does, and hands back what the main process keys it by, and the
    bytes of the files it judges itself. Files too large or not text are said as ever,
    in the order of the files; the next run reads none of them again."""
    write(workspace, "roslint-names.toml", "max-file-size = 2000\n")
    launch = workspace / "src" / "fleet_bringup" / "launch"
    write(launch, "zz_generated.launch", "<launch>\n" + "<!-- padding -->\n" * 200 + "</launch>\n")
    write(launch, "aa_generated.launch", "<launch>\n" + "<!-- padding -->\n" * 300 + "</launch>\n")
    (launch / "blob.launch").write_bytes(b"<launch>\0</launch>\n")
    keyed_here: list[str] = []
    for module in (reading, run_inputs):
        real = module.read_file

        def counted(path: Any, max_size: int, real: Any = real) -> Any:
            keyed_here.append(os.path.basename(path))
            return real(path, max_size)

        monkeypatch.setattr(module, "read_file", counted)
    arguments = ["check", "--format", "json", "--verbose", "--cache-dir", str(tmp_path / "c")]
    first = run_cli([*arguments, "--jobs", "2", "."], workspace)
    assert "extracted by 2 worker processes" in first.stderr
    assert keyed_here == []
    reference = run_cli(["check", "--format", "json", "--verbose", "--no-cache", "."], workspace)
    assert (first.stdout, first.exit_code) == (reference.stdout, reference.exit_code)
    assert first.stderr.splitlines()[1:] == reference.stderr.splitlines()[1:]
    skipped = [
        line.split(":")[1].removeprefix(" skipped ")
        for line in first.stderr.splitlines()
        if line.startswith("roslint-names: skipped")
    ]
    assert skipped == sorted(skipped)
    assert {f"src/fleet_bringup/launch/{name}_generated.launch" for name in ("aa", "zz")} <= {
        *skipped
    }
    again = run_cli([*arguments, "--jobs", "2", "."], workspace)
    assert "its result reused" in again.stderr and keyed_here == []
    assert again.stdout == first.stdout


# A long rclpy module: 26 KB, counted eight times over (``gather.PYTHON_WEIGHT``).
BIG_NODE = "import rclpy\nfrom std_msgs.msg import String\n\n" + "".join(
    f"def advertise_{i}(node):\n    return node.create_publisher(String, 'topic_{i}', 10)\n\n"
    for i in range(300)
)


def test_a_first_run_hands_out_the_heaviest_files_first(
    run_cli: Any, workspace: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Handed out in the order of the files, the longest one to extract held the end of a
    first run while every other worker waited (realws on 16 cores: rclpy's 115 KB
    ``test_node.py``, 32nd from the end, came 0.52 s after all the rest). Where the run
    took the files' statuses, the heaviest go first; the output is the same."""
    big = "src/fleet_bringup/fleet_bringup/zz_big_node.py"
    write(workspace, big, BIG_NODE)
    handed: list[str] = []
    real = workers.Dispatcher.put

    def recorded(self: Dispatcher[Any, Any], item: Any, size: int) -> list[Any]:
        handed.append(item[0].display)
        return list(real(self, item, size))

    monkeypatch.setattr(workers.Dispatcher, "put", recorded)
    arguments = ["check", "--format", "json", "--jobs", "1", "."]
    first = run_cli([*arguments[:-1], "--cache-dir", str(tmp_path / "c"), "."], workspace)
    assert handed[0] == big
    handed.clear()
    uncached = run_cli([*arguments[:-1], "--no-cache", "."], workspace)
    assert handed[0] != big and big in handed  # no statuses taken: in the files' order
    assert (first.stdout, first.exit_code) == (uncached.stdout, uncached.exit_code)


@pytest.mark.usefixtures("small_chunks")
def test_includes_are_extracted_under_their_arguments_while_the_files_are(
    run_cli: Any, workspace: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A first run with workers hands out the launch and Python files first and, once
    their facts are in, sends the launch files an includer hands arguments to (depth by
    depth, ``speculation``) between the other files: the build's walk then waits on the
    workers for none of them. It reads the same files as a run in one process, and
    prints the same."""
    sent_by_the_build: list[str] = []
    building = False
    real_prepare = gather.Specialiser.prepare
    real_put = workers.Dispatcher.put

    def prepare(self: gather.Specialiser, wanted: Any) -> None:
        nonlocal building
        building = True
        try:
            real_prepare(self, wanted)
        finally:
            building = False

    def put(self: Dispatcher[Any, Any], item: Any, size: int) -> list[Any]:
        if building:
            sent_by_the_build.append(item[0].display)
        return list(real_put(self, item, size))

    monkeypatch.setattr(gather.Specialiser, "prepare", prepare)
    monkeypatch.setattr(workers.Dispatcher, "put", put)

    def run(cache: str, jobs: str) -> Any:
        arguments = ["check", "--format", "json", "--verbose", "--jobs", jobs, "."]
        return run_cli([*arguments[:-1], "--cache-dir", str(tmp_path / cache), "."], workspace)

    parallel = run("a", "2")
    assert "extracted by 2 worker processes" in parallel.stderr
    assert sent_by_the_build == []
    alone = run("b", "1")
    assert sent_by_the_build  # in one process nothing goes ahead: the build extracts them
    assert (parallel.stdout, parallel.exit_code) == (alone.stdout, alone.exit_code)
    assert parallel.stderr.splitlines()[1:] == alone.stderr.splitlines()[1:]
    specialised = []  # what each run's replay says the graph read under arguments
    for name in ("a", "b"):
        kept = next((tmp_path / name).glob("facts-v*/replays/*"))
        stored: Any = FactsCache(tmp_path / name).load_replay(kept.name)
        replay = same_facts.loaded(stored, len(stored[1]), stored[2])
        assert replay is not None
        specialised.append(replay.specialised)
    assert specialised[0] == specialised[1] == {"src/fleet_bringup/launch/fleet.launch.py"}
    # A build from cached facts extracts no file to go beside: nothing goes ahead.
    for kept in (
        *(tmp_path / "a").glob("facts-v*/runs"),
        *(tmp_path / "a").glob("facts-v*/replays"),
    ):
        shutil.rmtree(kept)
    sent_ahead: list[object] = []
    monkeypatch.setattr(gather.Specialiser, "ahead", lambda *given: sent_ahead.append(given))
    again = run("a", "2")
    assert sent_ahead == [] and again.stdout == parallel.stdout


def test_a_file_goes_to_a_worker_as_where_it_is(tmp_path: Path) -> None:
    """The worker reads the bytes the main process read; edited since, it gets None."""
    launch = tmp_path / "bringup.launch"
    launch.write_text(TWO_ROBOTS_LAUNCH)
    data = launch.read_bytes()
    sent = pickle.dumps(OnDisk(str(launch), data))
    assert b"fleet.launch.py" not in sent
    assert pickle.loads(sent) == data
    launch.write_text(TWO_ROBOTS_LAUNCH.replace("robot3", "robot4"))  # the same size
    assert pickle.loads(sent) is None
    launch.unlink()
    assert pickle.loads(sent) is None


def test_a_file_keyed_already_is_sent_without_hashing_it_again(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The main process hashed the bytes to key them: the digest it sends is that one."""
    launch = tmp_path / "bringup.launch"
    launch.write_text(TWO_ROBOTS_LAUNCH)
    data = launch.read_bytes()
    digest = gather.content_digest(data)

    def hashed_again(data: bytes) -> str:
        raise AssertionError("hashed again")

    monkeypatch.setattr(gather, "content_digest", hashed_again)
    sent = pickle.dumps(OnDisk(str(launch), data, digest))
    monkeypatch.undo()
    assert pickle.loads(sent) == data


def _edited_since(path: str, size: int, digest: str) -> bytes | None:
    return None  # module-level: the main process pickles it by name


@pytest.mark.usefixtures("small_chunks")
def test_files_edited_before_a_worker_reads_them_are_extracted_as_read(
    run_cli: Any, workspace: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Every file edited between the main process's read and its worker's (the workers,
    forked, see the patch): each is extracted in the main process from the bytes it read,
    the bytes the run is keyed by and its findings point into. The main process reads
    them where the cache holds facts: here, of every file before a line was added."""
    cache = str(workspace.parent / "cache")
    arguments = ["check", "--format", "json", "--cache-dir", cache, "."]
    run_cli(arguments, workspace)
    for path in workspace.rglob("*"):
        if path.suffix in {".launch", ".xml", ".py", ".cpp", ".yaml"}:
            path.write_bytes(path.read_bytes() + b"\n")
    reference = run_cli(["check", "--format", "json", "--no-cache", "--jobs", "1", "."], workspace)
    monkeypatch.setattr(gather, "_read_again", _edited_since)
    edited = run_cli([*arguments, "--jobs", "2", "--verbose"], workspace)
    assert "extracted by 2 worker processes" in edited.stderr
    assert (edited.stdout, edited.exit_code) == (reference.stdout, reference.exit_code)


def test_few_files_start_no_worker(run_cli: Any, tmp_path: Path) -> None:
    shutil.copytree(EXAMPLES / "src" / "turtle_bringup", tmp_path / "ws")
    result = run_cli(["check", "--jobs", "2", "--verbose", "--no-cache", "."], tmp_path / "ws")
    assert " extracted by this process" in result.stderr


@pytest.mark.usefixtures("small_chunks")
def test_workers_started_for_specialisations_are_not_said_to_extract_the_files(
    run_cli: Any, workspace: Path, tmp_path: Path
) -> None:
    """After an edit to an included launch file, the one file is extracted in-process and
    its two specialisations start the workers: the files were extracted by this process."""
    cache = ["--cache-dir", str(tmp_path / "cache")]
    arguments = ["check", "--jobs", "2", "--verbose", *cache, "."]
    run_cli(arguments, workspace)
    included = workspace / "src" / "fleet_bringup" / "launch" / "fleet.launch.py"
    included.write_text(included.read_text() + "# reviewed\n")
    result = run_cli(arguments, workspace)
    assert "files from the cache, 1 extracted by this process" in result.stderr.splitlines()[0]


def test_zero_jobs_means_every_core(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(workers, "available_cores", lambda: 6)
    assert (worker_count(0), worker_count(1), worker_count(3)) == (6, 1, 3)


def _square_all(items: Iterable[int]) -> list[tuple[int, int]]:
    return [(item, item * item) for item in items]


def _fail_on_seven(items: Iterable[int]) -> list[int]:
    taken = list(items)  # work is handed an iterable: a worker marks each item as taken
    if 7 in taken:
        raise ValueError("seven")
    return taken


def run_all(dispatcher: Dispatcher[int, Any], items: range) -> list[Any]:
    results: list[Any] = []
    with dispatcher:
        for item in items:
            results.extend(dispatcher.put(item, size=1000))
        results.extend(dispatcher.finish())
    return results


@pytest.mark.usefixtures("small_chunks")
@pytest.mark.parametrize(("jobs", "count", "started"), [(1, 50, 0), (2, 1, 0), (2, 50, 2)])
def test_dispatcher_returns_every_result_once(jobs: int, count: int, started: int) -> None:
    dispatcher: Dispatcher[int, tuple[int, int]] = Dispatcher(_square_all, jobs)
    results = run_all(dispatcher, range(count))
    assert sorted(results) == [(item, item * item) for item in range(count)]
    assert dispatcher.workers == 0  # closed
    probe: Dispatcher[int, tuple[int, int]] = Dispatcher(_square_all, jobs)
    with probe:
        for item in range(count):
            probe.put(item, size=1)
        assert probe.workers == started
        list(probe.finish())


def _chunk_sizes(items: Iterable[int]) -> list[tuple[int, int]]:
    taken = list(items)
    return [(item, len(taken)) for item in taken]


@pytest.mark.parametrize(
    ("expected", "largest"),
    [
        (5_000, workers.CHUNK_ITEMS),  # a workspace: few messages
        (160, 10),  # a few files: each of the two workers gets eight chunks or so
        (40, 2),
    ],
)
def test_chunks_are_large_where_there_are_items_enough(expected: int, largest: int) -> None:
    """Each chunk costs the main process a message each way: as large as keeps every
    worker given several, and the items each worker takes as they come."""
    dispatcher: Dispatcher[int, tuple[int, int]] = Dispatcher(
        _chunk_sizes, 2, min_items=1, expected_items=expected
    )
    results = run_all(dispatcher, range(expected))
    assert sorted(item for item, _ in results) == list(range(expected))
    sizes = {size for _, size in results}
    assert max(sizes) == largest


def test_a_batch_waited_for_whole_is_spread_over_every_worker() -> None:
    """A depth of the launch trees (``gather.Specialiser``) is waited for whole: in
    chunks that give each worker two at least, not the stream's 32 items, which left
    most of 16 workers idle on a depth of 229 files. The stream after it is chunked as
    before."""
    dispatcher: Dispatcher[int, tuple[int, int]] = Dispatcher(_chunk_sizes, 4, min_items=1)
    with dispatcher:
        batch: list[tuple[int, int]] = []
        with dispatcher.batch(40):
            for item in range(40):
                batch.extend(dispatcher.put(item, size=1))
            batch.extend(dispatcher.finish())
        stream: list[tuple[int, int]] = []
        for item in range(40, 140):
            stream.extend(dispatcher.put(item, size=1))
        stream.extend(dispatcher.finish())
    assert sorted(item for item, _ in batch) == list(range(40))
    assert max(size for _, size in batch) == 5  # 40 items, 4 workers, 2 chunks each
    assert sorted(item for item, _ in stream) == list(range(40, 140))
    assert max(size for _, size in stream) == workers.CHUNK_ITEMS


def test_the_last_chunks_of_a_stream_are_small() -> None:
    """Where the items to come are known, the chunks shrink as they run out: each worker
    gets two at least of what is left, and no worker is left alone on a last chunk of 32
    files while the others wait (the end of a cold run on 16 cores)."""
    expected = 1_000
    dispatcher: Dispatcher[int, tuple[int, int]] = Dispatcher(
        _chunk_sizes, 2, min_items=1, expected_items=expected
    )
    size_of = dict(run_all(dispatcher, range(expected)))
    assert size_of[0] == workers.CHUNK_ITEMS
    assert [size_of[item] for item in range(expected - 4, expected)] == [1, 1, 1, 1]
    # never more than a quarter of what was left when a chunk was started
    start = 0
    while start < expected:
        assert size_of[start] <= max(1, -(-(expected - start) // 4))
        start += size_of[start]


def test_the_futures_are_looked_at_as_chunks_go_out(monkeypatch: pytest.MonkeyPatch) -> None:
    """Which chunks came back is asked as a chunk is sent, not after every item: looking
    at each future in flight takes its lock, 0.44 s of a first run's main process at 8
    copies of the benchmark's workspace, once per file."""
    import concurrent.futures

    looks = 0
    real = concurrent.futures.Future.done

    def counted(future: concurrent.futures.Future[Any]) -> bool:
        nonlocal looks
        looks += 1
        return real(future)

    monkeypatch.setattr(concurrent.futures.Future, "done", counted)
    count = 2_000
    results = run_all(Dispatcher(_square_all, 2, min_items=1), range(count))
    assert sorted(results) == [(item, item * item) for item in range(count)]
    chunks = -(-count // workers.CHUNK_ITEMS)
    assert looks <= chunks * 2 * workers.CHUNKS_PER_WORKER  # the futures in flight, per chunk


@pytest.mark.usefixtures("small_chunks")
def test_putting_an_item_waits_on_no_future(monkeypatch: pytest.MonkeyPatch) -> None:
    """The main process asks after every item it puts which chunks came back: by each
    future's state, not ``concurrent.futures.wait``, which installs a waiter on every
    future in flight (0.25 s of a cold run's 3 s serial part). It waits only where it
    must: the workers' queue full, or every item put."""
    import concurrent.futures

    waits: list[object] = []
    real = concurrent.futures.wait

    def counted(futures: Any, timeout: float | None = None, **options: Any) -> Any:
        waits.append(timeout)
        return real(futures, timeout=timeout, **options)

    monkeypatch.setattr(concurrent.futures, "wait", counted)
    count = 400
    results = run_all(Dispatcher(_square_all, 2, min_items=1), range(count))
    assert sorted(results) == [(item, item * item) for item in range(count)]
    assert waits and 0 not in waits  # it waited, never only to poll


@pytest.mark.usefixtures("small_chunks")
@pytest.mark.parametrize("jobs", [1, 2])
def test_a_worker_error_reaches_the_caller(jobs: int) -> None:
    with pytest.raises(ValueError, match="seven"):
        run_all(Dispatcher(_fail_on_seven, jobs), range(20))


class FakeTerminal(io.StringIO):
    def __init__(self, terminal: bool) -> None:
        super().__init__()
        self.terminal = terminal

    def isatty(self) -> bool:
        return self.terminal


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def make_bar(terminal: bool = True) -> tuple[ProgressBar, FakeTerminal, Clock]:
    stream, clock = FakeTerminal(terminal), Clock()
    bar = ProgressBar(stream, enabled=wanted(stream, {"TERM": "xterm"}), clock=clock, width=60)
    return bar, stream, clock


def test_progress_is_drawn_only_on_a_terminal() -> None:
    assert wanted(FakeTerminal(True), {"TERM": "xterm"})
    assert not wanted(FakeTerminal(False), {"TERM": "xterm"})
    assert not wanted(FakeTerminal(True), {"TERM": "dumb"})
    bar, stream, clock = make_bar(terminal=False)
    clock.now += 10
    bar(5, 10)
    bar.close()
    assert stream.getvalue() == ""


def test_a_short_run_draws_nothing() -> None:
    bar, stream, clock = make_bar()
    for done in range(1, 11):
        clock.now += DELAY_SECONDS / 20
        bar(done, 10)
    bar.close()
    assert stream.getvalue() == ""


def test_a_long_run_draws_one_line_and_erases_it() -> None:
    bar, stream, clock = make_bar()
    clock.now += DELAY_SECONDS + 0.5
    bar(1, 4)
    bar(2, 4)  # within the refresh interval: not drawn
    clock.now += 1
    bar(3, 4)
    drawn = stream.getvalue()
    assert drawn.count("\r") == 2 and "\n" not in drawn
    assert "1/4 files" in drawn and "3/4 files" in drawn and "2/4" not in drawn
    assert bar.shown
    bar.close()
    assert stream.getvalue().endswith("\r\x1b[K") and not bar.shown


def test_the_progress_line_fits_its_width() -> None:
    bar, _, _ = make_bar()
    line: Callable[[int, int, float], str] = bar.line
    assert len(line(0, 8123, 0.0)) == 60
    assert len(line(8123, 8123, 12.0)) == 60
    half = line(4000, 8000, 3.0)
    assert abs(half.count("#") - half.count(".")) <= 1
