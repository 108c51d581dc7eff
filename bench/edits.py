"""Random edit sequences on a copy of a workspace: after each step, the run that patches or
replays the last one and a run without a cache must print the same bytes (issue 30: a
stale cache must never change a result).

    python bench/edits.py WORKSPACE [--seed N] [--steps K] [--out DIR]

The workspace is copied (hard links, as ``growth`` does: an edit replaces the edited file,
the original keeps its bytes; the workspace must not be written to while the sequence
runs) into a temporary directory, with a cache of its own. Each
step makes one to three edits chosen at random (the seed makes a sequence again), of the
kinds a ROS developer makes and the cache's incremental paths take apart:

- a name in a C++ or Python call that declares an endpoint or a parameter, changed to a
  valid name or an invalid one (``graph_patch``: nodes' code patched);
- a string constant a C++ file defines changed (the files taking it resolved anew);
- a node's ``name``, a group's ``ns`` or a remap's ``from`` or ``to`` in a launch file
  changed, a remap added to a node, or a node started once more, under its name or
  another (``launch_patch``: trees walked again);
- a key of a ROS 2 parameter file renamed (``launch_patch``: the trees handed it);
- a dependency added to or dropped from a ``package.xml`` (the packages patched);
- an executable of a ``CMakeLists.txt`` renamed (``program_patch``: programs made again);
- a launch file or C++ source removed, a file copied beside itself, or moved (renamed
  in its directory: ``shifts``, the replay renumbered);
- a name, namespace or executable in a Python or YAML launch file changed;
- an argument's default, or the value an include hands it, changed; an ``<include>``
  removed or given twice (the files included read again under other arguments);
- a local ``#include`` dropped or added, a class's base changed (what a node's code
  spans: parameters gathered again), a source a target compiles replaced by another;
- a package renamed in its manifest;
- a file moved into another directory of its kind's files (another package's);
- an earlier edit of a file undone (a replay of a run long ago taken up again).

Then the CLI runs twice, ``--format json``: with the cache, and with ``--no-cache``. A
step whose outputs or exit codes differ is written to ``--out`` (both outputs, what both
runs printed on standard error, and the edits so far); the sequence goes on from an
emptied cache. With ``--memory``, each step builds instead, in this process, the graph the
language server builds (with the ``GraphMemory`` every step before left) and the graph a
run without one builds: a step whose graphs differ is written to ``--out`` (the first
nodes and endpoints that differ, and the edits so far), and the sequence goes on with a
new memory. Exit 1 when a step differed or a run crashed, 0 otherwise. The summary
says how many steps changed the output at all: a sequence whose edits change nothing
tests nothing.
"""

from __future__ import annotations

import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Callable
from dataclasses import fields
from functools import partial
from pathlib import Path
from typing import Any

from growth import grown, text_of

# Names the edits write: valid ones, and ones a rule reports (RN101 to RN203).
VALID_NAMES = ("cmd_vel", "odom", "scan", "chatter", "map", "foo/bar", "/abs_topic", "image_raw")
INVALID_NAMES = ("Bad-Name", "trailing/", "1abc", "a//b", "Cmd_Vel", "a/b/c/d/e/f/g", "~private")
_STRING = re.compile(r'"([A-Za-z_/~][A-Za-z0-9_/]*)"')
_CPP_CALLS = re.compile(
    r"(create_(publisher|subscription|service|client)|advertise|subscribe|serviceClient"
    r"|advertiseService|declare_parameter|get_parameter|param)[<(].*\""
)
_PYTHON_CALLS = re.compile(
    r"create_(publisher|subscription|service|client)|Publisher\(|Subscriber\(|remappings"
    r"|declare_parameter|get_param"
)
_CONSTANTS = re.compile(r"(constexpr|const)\s.*(char|string|string_view)\b.*=\s*\"")
_DEPEND = re.compile(r"\n\s*<(build_|exec_|build_export_|test_)?depend>[^<]*</\w*depend>")
_ATTRIBUTE_OF = {"name": "node", "ns": "(?:node|group)", "from": "remap", "to": "remap"}
# A Python launch description's keyword naming a node, its namespace or its program
_PYTHON_LAUNCH = re.compile(
    r"\b(?:name|namespace|executable|node_name|node_namespace)\s*=\s*['\"]([^'\"$]*)['\"]"
)
# A YAML launch file's node name, namespace or remap end
_YAML_LAUNCH = re.compile(
    r"^\s*-?\s*(?:name|namespace|from|to):\s*[\"']?([A-Za-z_/~][^\"'\n$]*)", re.M
)
_ARGUMENT = re.compile(r'<arg\b[^>]*?\b(?:default|value)="([^"$]*)"')
_INCLUDE_ELEMENT = re.compile(r"[ \t]*<include\b(?:[^>]*/>|.*?</include>)[ \t]*\n", re.S)
_LOCAL_INCLUDE = re.compile(r'^#include "([^"]+)"[ \t]*\n', re.M)
_BASE = re.compile(r"\bclass\s+\w+\s*(?:final\s*)?:\s*(?:public|protected|private)?\s*([\w:]+)")
_BASES = ("rclcpp::Node", "rclcpp_lifecycle::LifecycleNode", "nav2_util::LifecycleNode", "Unknown")
_SOURCES = re.compile(r"add_(?:executable|library)\(\s*[\w$-]+[^)]*?\b([\w/.-]+\.cpp)\b")
_PACKAGE_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")


class EditSequence:
    """The edits of one seeded sequence, on the workspace at ``root``: each remembers the
    bytes it replaced, so that a later step can undo it."""

    def __init__(self, root: Path, seed: int) -> None:
        self.root = root
        self.random = random.Random(seed)
        self.original: dict[Path, bytes | None] = {}  # None: the file was not there

    def step(self) -> list[str]:
        """One to three edits; what each did, a line each."""
        done: list[str] = []
        for _ in range(self.random.choice((1, 1, 1, 2, 3))):
            edit = None
            while edit is None:
                edit = self.random.choice(self._edits())()
            done.append(edit)
        return done

    def _edits(self) -> list[Callable[[], str | None]]:
        return [
            lambda: self._string((".cpp", ".hpp", ".h"), _CPP_CALLS),
            lambda: self._string((".py",), _PYTHON_CALLS),
            lambda: self._string((".hpp", ".h", ".cpp"), _CONSTANTS),
            self._node,
            lambda: self._attribute(self.random.choice(sorted(_ATTRIBUTE_OF))),
            self._remap,
            self._parameter_key,
            self._depend,
            self._executable,
            lambda: self._remove((".launch", ".launch.xml", ".launch.py", ".cpp")),
            lambda: self._copy((".launch", ".launch.xml", ".cpp", ".yaml")),
            lambda: self._move((".cpp", ".launch.xml", ".launch.py", ".yaml")),
            self._python_launch,
            self._yaml_launch,
            self._argument,
            self._include_element,
            self._include_line,
            self._base_class,
            self._compiled_source,
            self._package_renamed,
            lambda: self._move_away((".cpp", ".hpp", ".launch.xml", ".launch.py", ".yaml")),
            self._undo,
            self._undo,
        ]

    def _files(self, suffixes: tuple[str, ...], holding: str | re.Pattern[str] = "") -> list[Path]:
        found: list[Path] = []
        for directory, names, files in os.walk(self.root):
            names[:] = sorted(name for name in names if not name.startswith("."))
            for name in sorted(files):
                path = Path(directory) / name
                if name.endswith(suffixes) and (
                    not holding
                    or (
                        holding.search(text_of(path))
                        if isinstance(holding, re.Pattern)
                        else holding in text_of(path)
                    )
                ):
                    found.append(path)
        return found

    def _pick(self, suffixes: tuple[str, ...], holding: str | re.Pattern[str] = "") -> Path | None:
        """One of the files ``_files`` finds, at random; None where there is none."""
        candidates = self._files(suffixes, holding)
        return self.random.choice(candidates) if candidates else None

    def _pick_match(
        self, suffixes: tuple[str, ...], pattern: re.Pattern[str]
    ) -> tuple[Path, str, re.Match[str]] | None:
        """A file holding ``pattern`` (``_pick``), its text, and one match in it, each at
        random; None where no file holds it."""
        path = self._pick(suffixes, pattern)
        if path is None:
            return None
        text = text_of(path)
        return path, text, self.random.choice(list(pattern.finditer(text)))

    def _name(self) -> str:
        names = INVALID_NAMES if self.random.random() < 0.4 else VALID_NAMES
        return self.random.choice(names)

    def _write(self, path: Path, data: bytes | None) -> None:
        """``path`` given ``data`` (None: removed), its first bytes remembered; a new file
        renamed over the old, which keeps its bytes for the workspace it is linked from."""
        if path not in self.original:
            self.original[path] = _now(path)
        if data is None:
            path.unlink()
            return
        replacement = path.with_name(f".{path.name}.edit")
        replacement.write_bytes(data)
        os.replace(replacement, path)

    def _shown(self, path: Path) -> str:
        return path.relative_to(self.root).as_posix()

    def _string(self, suffixes: tuple[str, ...], calls: re.Pattern[str]) -> str | None:
        path = self._pick(suffixes, calls)
        if path is None:
            return None
        lines = text_of(path).split("\n")
        found = [at for at, line in enumerate(lines) if calls.search(line) and _STRING.search(line)]
        if not found:
            return None
        at = self.random.choice(found)
        name = self._name()
        lines[at] = _STRING.sub(f'"{name}"', lines[at], count=1)
        self._write(path, "\n".join(lines).encode())
        return f"{self._shown(path)}:{at + 1}: a string made {name!r}"

    def _attribute(self, attribute: str) -> str | None:
        element = _ATTRIBUTE_OF[attribute]
        pattern = re.compile(rf'<{element}\b[^>]*?\b{attribute}="([^"$]*)"')
        return self._value((".launch", ".launch.xml", ".test"), pattern, f"a {attribute}=")

    def _remap(self) -> str | None:
        picked = self._pick_match((".launch", ".launch.xml"), re.compile(r"<node\b[^>]*[^/]>"))
        if picked is None:
            return None
        path, text, node = picked
        remap = f'\n<remap from="{self._name()}" to="{self._name()}"/>'
        self._write(path, (text[: node.end()] + remap + text[node.end() :]).encode())
        return f"{self._shown(path)}: a remap added: {remap.strip()}"

    def _node(self) -> str | None:
        element = re.compile(r"[ \t]*<node\b[^>]*/>[ \t]*\n")
        picked = self._pick_match((".launch", ".launch.xml", ".test"), element)
        if picked is None:
            return None
        path, text, node = picked
        copy = node.group()
        if self.random.random() < 0.5:  # the same name twice, or the copy renamed
            copy = re.sub(r'\bname="[^"]*"', f'name="{self._name()}"', copy, count=1)
        self._write(path, (text[: node.end()] + copy + text[node.end() :]).encode())
        return f"{self._shown(path)}: a node started once more: {copy.strip()}"

    def _parameter_key(self) -> str | None:
        path = self._pick((".yaml",), "ros__parameters")
        if path is None:
            return None
        lines = text_of(path).split("\n")
        keys = [at for at, line in enumerate(lines) if re.match(r"^\s+[a-z_]+:\s*\S", line)]
        if not keys:
            return None
        at = self.random.choice(keys)
        lines[at] = re.sub(r"^(\s+)([a-z_]+):", r"\1\2_renamed:", lines[at])
        self._write(path, "\n".join(lines).encode())
        return f"{self._shown(path)}:{at + 1}: a parameter key renamed"

    def _depend(self) -> str | None:
        path = self._pick(("package.xml",))
        if path is None:
            return None
        text = text_of(path)
        depends = list(_DEPEND.finditer(text))
        if depends and self.random.random() < 0.5:
            gone = self.random.choice(depends)
            self._write(path, (text[: gone.start()] + text[gone.end() :]).encode())
            return f"{self._shown(path)}: a dependency dropped"
        other = self.random.choice(("rclcpp", "roscpp", "nav_msgs", "std_srvs"))
        at = text.rfind("</package>")
        if at < 0:
            return None
        self._write(path, (text[:at] + f"  <depend>{other}</depend>\n" + text[at:]).encode())
        return f"{self._shown(path)}: a dependency on {other} added"

    def _executable(self) -> str | None:
        picked = self._pick_match(("CMakeLists.txt",), re.compile(r"add_executable\(\s*(\w+)"))
        if picked is None:
            return None
        path, text, found = picked
        renamed = text[: found.end(1)] + "_renamed" + text[found.end(1) :]
        self._write(path, renamed.encode())
        return f"{self._shown(path)}: executable {found.group(1)} renamed"

    def _python_launch(self) -> str | None:
        return self._value((".launch.py", "_launch.py"), _PYTHON_LAUNCH, "a launch keyword")

    def _yaml_launch(self) -> str | None:
        return self._value((".launch.yaml",), _YAML_LAUNCH, "a YAML launch value")

    def _argument(self) -> str | None:
        """An argument's default, or the value an include hands it, changed: the files
        included read again under other arguments (``speculation``, ``launch_patch``)."""

        def plain() -> str:  # an argument's value is no name: no leading or trailing slash
            return self._name().strip("/") or "x"

        return self._value((".launch", ".launch.xml"), _ARGUMENT, "an argument's value", plain)

    def _value(
        self,
        suffixes: tuple[str, ...],
        pattern: re.Pattern[str],
        what: str,
        name_of: Callable[[], str] | None = None,
    ) -> str | None:
        """The first group of a match of ``pattern`` (``_pick_match``) made a name
        (``name_of``'s, drawn after the match; ``_name``'s where none is given)."""
        picked = self._pick_match(suffixes, pattern)
        if picked is None:
            return None
        path, text, value = picked
        name = (name_of or self._name)()
        self._write(path, (text[: value.start(1)] + name + text[value.end(1) :]).encode())
        return f"{self._shown(path)}: {what} made {name!r}"

    def _include_element(self) -> str | None:
        """An ``<include>`` removed, or given twice: a tree loses or doubles a subtree."""
        picked = self._pick_match((".launch", ".launch.xml"), _INCLUDE_ELEMENT)
        if picked is None:
            return None
        path, text, include = picked
        if self.random.random() < 0.5:
            self._write(path, (text[: include.start()] + text[include.end() :]).encode())
            return f"{self._shown(path)}: an include removed"
        doubled = text[: include.end()] + include.group() + text[include.end() :]
        self._write(path, doubled.encode())
        return f"{self._shown(path)}: an include given twice"

    def _include_line(self) -> str | None:
        """A local ``#include`` dropped, or one of another file of the directory added:
        what a node's code spans, and the constants it takes, change."""
        picked = self._pick_match((".cpp", ".hpp", ".h"), _LOCAL_INCLUDE)
        if picked is None:
            return None
        path, text, line = picked
        if self.random.random() < 0.5:
            self._write(path, (text[: line.start()] + text[line.end() :]).encode())
            return f"{self._shown(path)}: #include {line.group(1)!r} dropped"
        headers = sorted(
            found.name
            for found in path.parent.iterdir()
            if found.suffix in (".h", ".hpp") and found != path
        )
        if not headers:
            return None
        header = self.random.choice(headers)
        added = f'#include "{header}"\n'
        self._write(path, (text[: line.start()] + added + text[line.start() :]).encode())
        return f"{self._shown(path)}: #include {header!r} added"

    def _base_class(self) -> str | None:
        """A class's first base changed: the parameters of its nodes' code gathered
        through other classes (``ParameterSets._own_code``), plugins judged again."""
        picked = self._pick_match((".cpp", ".hpp", ".h"), _BASE)
        if picked is None:
            return None
        path, text, base = picked
        new = self.random.choice([b for b in _BASES if b != base.group(1)])
        self._write(path, (text[: base.start(1)] + new + text[base.end(1) :]).encode())
        return f"{self._shown(path)}: a base {base.group(1)!r} made {new!r}"

    def _compiled_source(self) -> str | None:
        """A source a target compiles replaced by another ``.cpp`` of its package: a
        program's code changes (``program_patch``) and one source may be built no more."""
        picked = self._pick_match(("CMakeLists.txt",), _SOURCES)
        if picked is None:
            return None
        path, text, source = picked
        others = sorted(
            found.relative_to(path.parent).as_posix()
            for found in path.parent.rglob("*.cpp")
            if found.relative_to(path.parent).as_posix() != source.group(1)
        )
        if not others:
            return None
        other = self.random.choice(others)
        self._write(path, (text[: source.start(1)] + other + text[source.end(1) :]).encode())
        return f"{self._shown(path)}: compiles {other!r} for {source.group(1)!r}"

    def _package_renamed(self) -> str | None:
        """A package's name changed: ``$(find ...)`` of it, its dependents' lookups and
        the names a file's package decides all move."""
        picked = self._pick_match(("package.xml",), _PACKAGE_NAME)
        if picked is None:
            return None
        path, text, name = picked
        renamed = text[: name.end(1)] + "_renamed" + text[name.end(1) :]
        self._write(path, renamed.encode())
        return f"{self._shown(path)}: package {name.group(1)} renamed"

    def _move_away(self, suffixes: tuple[str, ...]) -> str | None:
        """A file moved into the directory of another file of its kind (another package,
        most often): its package, and the display paths keyed by it, change."""
        candidates = self._files(suffixes)
        if len(candidates) < 2:
            return None
        path, beside = self.random.sample(candidates, 2)
        moved = beside.with_name(f"away_{path.name}")
        if moved.exists() or beside.parent == path.parent:
            return None
        data = path.read_bytes()
        self._write(moved, data)
        self._write(path, None)
        return f"{self._shown(path)}: moved to {self._shown(moved)}"

    def _remove(self, suffixes: tuple[str, ...]) -> str | None:
        path = self._pick(suffixes)
        if path is None:
            return None
        self._write(path, None)
        return f"{self._shown(path)}: removed"

    def _copy(self, suffixes: tuple[str, ...]) -> str | None:
        path = self._pick(suffixes)
        if path is None:
            return None
        stem = path.name.split(".")[0]
        copy = path.with_name(path.name.replace(stem, f"{stem}_copy{len(self.original)}", 1))
        if copy.exists():
            return None
        self._write(copy, path.read_bytes())
        return f"{self._shown(path)}: copied to {copy.name}"

    def _move(self, suffixes: tuple[str, ...]) -> str | None:
        path = self._pick(suffixes)
        if path is None:
            return None
        moved = path.with_name(f"moved_{path.name}")
        if moved.exists():
            return None
        data = path.read_bytes()
        self._write(moved, data)
        self._write(path, None)
        return f"{self._shown(path)}: moved to {moved.name}"

    def _undo(self) -> str | None:
        edited = [path for path, data in sorted(self.original.items()) if _now(path) != data]
        if not edited:
            return None
        path = self.random.choice(edited)
        self._write(path, self.original[path])
        return f"{self._shown(path)}: back as it was"


def _now(path: Path) -> bytes | None:
    return path.read_bytes() if path.exists() else None


def _lint(root: Path, cache: Path, *options: str) -> tuple[int, bytes, bytes]:
    """The CLI over ``root``, ``--format json``: exit code, output, errors."""
    environment = dict(os.environ, XDG_CACHE_HOME=str(cache))
    command = [sys.executable, "-m", "roslint_names", "--format", "json", *options, "."]
    done = subprocess.run(command, cwd=root, env=environment, capture_output=True, check=False)
    return done.returncode, done.stdout, done.stderr


class MemoryBuilds:
    """The language server's graph builds over the workspace at ``root``: each with the
    memory of the builds before and the facts objects of the files whose facts are
    equal (as the session keeps them), beside the graph a run without memory builds."""

    def __init__(self, root: Path, cache: Path) -> None:
        from roslint_names.cache import FactsCache
        from roslint_names.config import load_settings
        from roslint_names.registry import load_registry
        from roslint_names.workspace.memory import GraphMemory

        self.root = root
        self.memory = GraphMemory()
        self._cache = FactsCache(cache)
        self._facts: dict[str, Any] = {}
        self._registry = load_registry()
        self._settings = load_settings(None, root, self._registry)

    def graphs(self) -> tuple[Any, Any]:
        """The graph built with the memory, and the graph a run without one builds."""
        from roslint_names.discover import discover
        from roslint_names.engine import RunOptions, lint, lintable, workspace_packages
        from roslint_names.gather import Specialiser, extract_batch
        from roslint_names.generation import DEFAULT_GENERATION, PackageGenerations
        from roslint_names.workers import Dispatcher
        from roslint_names.workspace.build import build

        root, settings = self.root, self._settings
        sources = lintable(discover([root], settings.exclude, settings.root, root))
        run = RunOptions(cache=self._cache)
        result = lint(sources, settings, self._registry, run, want_graph=True)
        facts = [
            kept if (kept := self._facts.get(found.path)) == found else found
            for found in result.facts
        ]
        self._facts = {found.path: found for found in facts}
        packages = PackageGenerations()
        specialiser = Specialiser(
            sources,
            packages,
            settings.ros or DEFAULT_GENERATION,
            self._cache,
            settings.max_file_size,
            dispatcher=Dispatcher(partial(extract_batch, self._cache), 1),
            ros1_python2=False,
        )
        remembered = build(
            facts,
            workspace_packages(sources, packages),
            specialiser,
            specialiser.prepare,
            self.memory,
        )
        return remembered, result.graph


def _graph_differences(remembered: Any, fresh: Any) -> str:
    """What differs between two graphs: each field, and for the nodes and endpoints the
    first items of each that the other has not."""
    lines: list[str] = []
    for field in fields(fresh):
        mine, theirs = getattr(remembered, field.name), getattr(fresh, field.name)
        if mine == theirs:
            continue
        lines.append(f"{field.name} differs")
        if isinstance(theirs, tuple):
            only_mine = [item for item in mine if item not in theirs][:3]
            only_theirs = [item for item in theirs if item not in mine][:3]
            lines += [f"  with memory only: {item!r}" for item in only_mine]
            lines += [f"  without memory only: {item!r}" for item in only_theirs]
    return "\n".join(lines)


def _memory_steps(
    root: Path, cache: Path, sequence: EditSequence, *, steps: int, seed: int, out: Path
) -> tuple[int, int]:
    """``steps`` steps of ``sequence``, each graph built with the memory compared with the
    graph built without: how many steps changed the graph and how many differed."""
    builds = MemoryBuilds(root, cache)
    last = builds.graphs()[1]
    differed = changed = 0
    edits: list[str] = []
    for step in range(steps):
        done = sequence.step()
        edits.extend(f"{step}: {edit}" for edit in done)
        remembered, fresh = builds.graphs()
        same = remembered == fresh
        moved = fresh != last
        changed += moved
        last = fresh
        mark = "same" if same else "DIFFERENT"
        print(f"{step:3} {mark:9} {'changed' if moved else '':7} {'; '.join(done)}", flush=True)
        if not same:
            differed += 1
            out.mkdir(parents=True, exist_ok=True)
            (out / f"{seed}-{step}-graphs.txt").write_text(_graph_differences(remembered, fresh))
            (out / f"{seed}-{step}-edits.txt").write_text("\n".join(edits))
            builds = MemoryBuilds(root, cache)  # the next steps from a new memory
            builds.graphs()
    return changed, differed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("workspace", type=Path)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--steps", type=int, default=40)
    parser.add_argument("--out", type=Path, default=Path("edits-differ"))
    parser.add_argument(
        "--memory",
        action="store_true",
        help="compare the language server's graph builds (with memory) instead of CLI runs",
    )
    parser.add_argument(
        "--into", type=Path, help="make the copy and its cache here and keep them (a new directory)"
    )
    options = parser.parse_args()
    if options.into is not None:
        options.into.mkdir(parents=True)
    with tempfile.TemporaryDirectory(prefix="roslint-names-edits-") as temporary:
        scratch = temporary if options.into is None else options.into
        root = Path(scratch) / "workspace"
        grown(options.workspace.resolve(), 1, root)
        cache = Path(scratch) / "cache"
        sequence = EditSequence(root, options.seed)
        if options.memory:
            changed, differed = _memory_steps(
                root, cache, sequence, steps=options.steps, seed=options.seed, out=options.out
            )
            print(
                f"{options.steps} steps (seed {options.seed}): {changed} changed the graph, "
                f"{differed} built otherwise with the memory than without"
            )
            return 1 if differed else 0
        last = _lint(root, cache)[1]
        differed = crashed = changed = 0
        edits: list[str] = []
        for step in range(options.steps):
            done = sequence.step()
            edits.extend(f"{step}: {edit}" for edit in done)
            cached, fresh = _lint(root, cache), _lint(root, cache, "--no-cache")
            same = cached[:2] == fresh[:2]
            moved = fresh[1] != last
            changed += moved
            last = fresh[1]
            mark = "same" if same else "DIFFERENT"
            print(f"{step:3} {mark:9} {'changed' if moved else '':7} {'; '.join(done)}", flush=True)
            if fresh[0] not in (0, 1) or cached[0] not in (0, 1):
                crashed += 1
                print((cached[2] + fresh[2]).decode(errors="replace")[-2000:])
            if not same:
                differed += 1
                options.out.mkdir(parents=True, exist_ok=True)
                (options.out / f"{options.seed}-{step}-cached.json").write_bytes(cached[1])
                (options.out / f"{options.seed}-{step}-no-cache.json").write_bytes(fresh[1])
                (options.out / f"{options.seed}-{step}-edits.txt").write_text("\n".join(edits))
                # What each run printed on standard error: an internal error says where.
                errors = b"".join((b"# cached\n", cached[2], b"# without a cache\n", fresh[2]))
                (options.out / f"{options.seed}-{step}-stderr.txt").write_bytes(errors)
                shutil.rmtree(cache, ignore_errors=True)  # the next steps from a clean start
                _lint(root, cache)
        print(
            f"{options.steps} steps (seed {options.seed}): {changed} changed the output, "
            f"{differed} printed otherwise with the cache than without, {crashed} crashed"
        )
    return 1 if differed or crashed else 0


if __name__ == "__main__":
    sys.exit(main())
