"""How the cost of a run grows with the workspace: ``bench/run.py WORKSPACE --copies N``.

The workspace is copied N times under one root (hard links: no disk is spent and each
copy's files are the originals' bytes; an edit replaces the edited file, so the other
copies keep theirs), then measured with the real CLI, one cache for the whole sequence:

- ``cold``: an empty cache; its wall and CPU time, the main process's own CPU (the serial
  part: what it computed rather than waited for) and the peak memory of the process tree;
- ``unchanged``: the same again (the stored result; the copies were left past the
  2 s racy window first, so the cold run could keep its key: ``unchanged``);
- ``edit_cpp``, ``edit_launch``: one C++ source, then one launch file of one copy given
  a comment at its end, as pre-commit and CI see a change: what the run after an edit
  that moves no name costs (``same_facts``: the last run's graph findings stand);
- ``edit_moves``: a line put above everything in that C++ source, so that every name in
  it moves (the last run's graph findings stand, their places in the file moved);
- ``edit_names``: a function that publishes a new topic appended to that source: the
  graph the last build kept, patched (``workspace.patch``: the nodes running the file
  resolved again), the graph rules over it;
- ``edit_graph``: a node added to that launch file: the graph the last build kept, with
  the launch trees that read the file walked again (``workspace.launch_patch``);
- ``edit_settings``: a setting added to the parameter file launch files name most often
  (a ROS 2 one): the trees whose nodes are handed it walked again
  (``workspace.launch_patch``);
- ``edit_parameter``: a parameter declared in that C++ source: the parameters of the
  code spanning its package gathered again (``workspace.parameter_patch``);
- ``add_file``, ``add_launch``, ``remove_file``: a header that names nothing put
  beside that source (the last run's findings stand, its files renumbered:
  ``shifts``), a launch file starting a node put beside that launch file (a tree of
  its own walked), then the header removed;
- ``edit_class``: a class deriving from ``rclcpp::Node`` added to that source: what
  the parameters of nodes' code are gathered through changes (the classes' lookups),
  the parameters of the code spanning its package gathered again
  (``patch.gathering_edit``);
- ``edit_endpoints``: a publisher given to a C++ source of rclcpp code, no test, that
  declared no endpoint (code no launch file starts is a program of its own where it declares some):
  its package's programs made again (``patch.edits_of``'s ``flipping``), the trees that
  start a node of it walked again;
- ``edit_constant``: the value of a string constant a header defines changed, in the
  header whose constants the most C++ sources of its package take (moveit's
  ``capability_names``): the files taking it resolve their names otherwise, each an
  edit of its own (``graph_patch``'s ``resolved_anew``), and the run keeps what it
  patched as a build keeps it;
- ``edit_release``: a URL added to a package's manifest, which says nothing a run reads
  (its name, build type, dependencies, plugin descriptions): the last run's result;
- ``edit_depend``: a dependency added to that manifest: which packages run together and
  which service types its files can use change, the graph the last build kept is
  patched with the packages as they are now;
- ``add_node``: a node added to a package: its source written to the ``src/`` beside a
  mid-sized ``CMakeLists.txt`` and an executable compiling it added there (what the
  package builds changes: its programs made again, ``workspace.program_patch``, the
  trees that start a node of it walked again);
- ``edit_included``: a node added to the launch file other launch files include, with
  arguments, most often (Autoware's ``pointcloud_container.launch.xml`` on the
  benchmark's workspace): the graph read it under those arguments, and the trees that
  read it are walked again, reading it so again (at 8 copies the includes name a
  package eight folders claim: a launch edit as ``edit_graph``'s);
- ``identical_after_edits``: whether the last edited run printed what a run with an
  empty cache prints over the same tree (a stale cache must never change a result);
- ``commit``: pre-commit's run, naming the edited C++ source and launch file, the
  source given another topic first (``engine._whole_workspace``: the run over the
  workspace reported in those files, its graph patched); ``commit_identical``: whether
  it printed what a run over those files without a cache prints;
- ``lsp`` (with ``--lsp-edits``): the language server's latencies on the grown workspace
  (``bench/lsp.py``), the graph findings' refresh after an edit among them.

Package names repeat in every copy: a name two folders claim is no package the linter
finds files in (``workspace.index``), so the copies' launch files resolve less than one
real workspace of that size would; the per-file work and the graph's size grow as the
files do. Numbers are this machine's: the table says which.
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
import time
from pathlib import Path
from typing import Any

import run as bench

from roslint_names.discover import discover
from roslint_names.engine import lintable
from roslint_names.reading import RACY_NANOSECONDS

# An edit that changes the graph: a function publishing a topic no file names yet.
_NEW_TOPIC = b"""
void bench_probe(rclcpp::Node & node)
{
  node.create_publisher<std_msgs::msg::Empty>("bench_probe", 1);
}
"""
# An edit the launch trees that read the file are walked again for: a node the launch
# file starts (put before the end of its root element).
_NEW_NODE = b"""  <node pkg="bench" exec="bench_node" name="bench_node"/>
"""
# An edit of what the code declares: a parameter.
_NEW_PARAMETER = b"""
void bench_parameter(rclcpp::Node & node)
{
  node.declare_parameter("bench_parameter", 1);
}
"""
# A setting of a ROS 2 parameter file (put below its ``ros__parameters:``, indented as
# the settings there are).
_NEW_SETTING = b"bench_setting: 1\n"
_NEW_DEPENDENCY = b"find_package(bench_probe REQUIRED)\n"
# A file added that names nothing (a header), as a new file and then removed
_NEW_HEADER = b"""#pragma once

namespace bench
{
inline int twice(int value) { return 2 * value; }
}  // namespace bench
"""
_ADDED_NAME = "bench_added.hpp"
_NEW_LAUNCH = b"""<launch>
  <node pkg="bench" exec="bench_node" name="bench_added"/>
</launch>
"""
_ADDED_LAUNCH = "bench_added.launch.xml"
# A class of the code that derives from the client library's node.
_NEW_CLASS = b"""
class BenchProbe : public rclcpp::Node
{
};
"""
# A manifest's edit that says nothing a run reads, then one that does: a package
# depends on another.
_NEW_MANIFEST_URL = b"""  <url type="repository">https://example.com/bench_probe</url>
"""
_NEW_MANIFEST_DEPENDENCY = b"""  <depend>bench_probe</depend>
"""
# A node added to a package: its source, and the executable that compiles it.
_NEW_EXECUTABLE = b"add_executable(bench_probe_node src/bench_probe_node.cpp)\n"
_NODE_SOURCE = "bench_probe_node.cpp"
_NEW_NODE_SOURCE = {
    "ROS 2": b"""// The bench's probe: what the package's nodes publish, summed up.
#include <rclcpp/rclcpp.hpp>
#include <std_msgs/msg/string.hpp>

class BenchProbeNode : public rclcpp::Node
{
public:
  BenchProbeNode() : rclcpp::Node("bench_probe_node")
  {
    declare_parameter("report_period", 1.0);
    status_ = create_publisher<std_msgs::msg::String>("bench_probe/status", 1);
  }

private:
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr status_;
};

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<BenchProbeNode>());
  return 0;
}
""",
    "ROS 1": b"""// The bench's probe: what the package's nodes publish, summed up.
#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "bench_probe_node");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  double period = private_nh.param("report_period", 1.0);
  ros::Publisher status = nh.advertise<std_msgs::String>("bench_probe/status", 1);
  ros::spin();
  return 0;
}
""",
}
# What a C++ test holds: its code is no program of its own, declaring endpoints or not.
_TESTS = ("TEST(", "TEST_F(", "gtest")
# One edit each, in this order. The first three are comments: at the end, where they move
# no name, or at the start, where it moves every name of the file; so that the run
# measures what an edit costs, not what a new finding does. No word of a suppression in them
# (``suppress``'s markers: the tool's name, NOLINT, noqa): a file holding one is read by
# every run, a fact of its own.
_EDITS = {
    "edit_cpp": ((".cpp",), "create_publisher", b"\n// bench edit: nothing renamed\n", "end"),
    "edit_launch": (
        (".launch.xml", ".launch"),
        "<node",
        b"\n<!-- bench edit: nothing renamed -->\n",
        "end",
    ),
    "edit_moves": ((".cpp",), "create_publisher", b"// bench edit: every name moves\n", "start"),
    "edit_names": ((".cpp",), "create_publisher", _NEW_TOPIC, "end"),
    "edit_graph": ((".launch.xml", ".launch"), "<node", _NEW_NODE, "inside"),
    "edit_settings": ((".yaml",), "ros__parameters:", _NEW_SETTING, "below"),
    "edit_parameter": ((".cpp",), "create_publisher", _NEW_PARAMETER, "end"),
    # A dependency found at the top of a package's build: every target moves, what it
    # compiles does not.
    "edit_cmake": (("CMakeLists.txt",), "add_executable(", _NEW_DEPENDENCY, "start"),
    "add_file": ((".cpp",), "create_publisher", _NEW_HEADER, "beside"),
    "add_launch": ((".launch.xml", ".launch"), "<node", _NEW_LAUNCH, "beside"),
    "remove_file": ((".cpp",), "create_publisher", b"", "removed"),
    "edit_class": ((".cpp",), "create_publisher", _NEW_CLASS, "end"),
    "edit_endpoints": ((".cpp",), "rclcpp::Node", _NEW_TOPIC, "endpoints"),
    "edit_constant": ((".h", ".hpp"), "", b"_bench", "constant"),
    "edit_release": (("package.xml",), "<depend>", _NEW_MANIFEST_URL, "inside"),
    "edit_depend": (("package.xml",), "<depend>", _NEW_MANIFEST_DEPENDENCY, "inside"),
    "add_node": (("CMakeLists.txt",), "add_executable(", _NEW_EXECUTABLE, "node"),
    "edit_included": ((".launch.xml",), "<node", _NEW_NODE, "included"),
}


def growth(workspace: Path, copies: int, lsp_edits: int) -> dict[str, Any]:
    from lsp import ENDPOINT_CALLS, latency, pick  # pygls only where the server is measured

    results: dict[str, Any] = {
        "machine": bench.machine(),
        "workspace": str(workspace),
        "copies": copies,
    }
    with tempfile.TemporaryDirectory(prefix="roslint-names-growth-") as scratch_name:
        scratch = Path(scratch_name)
        bench.snapshot_package(scratch / "snapshot")
        root = grown(workspace, copies, scratch / "workspace")
        # Past the racy window of the copies' new directories: what a run finds then it
        # may keep for the next (``unchanged``), as on a tree not written that instant.
        time.sleep(RACY_NANOSECONDS / 1e9)
        sources = lintable(discover([root], (), root, root))
        results["files"] = len(sources)
        # The cache where the language server finds it too (``$XDG_CACHE_HOME``).
        cache = scratch / "xdg" / "roslint-names"
        arguments = ["--format", "json", "."]
        runs = {"cold": bench.cli(root, arguments, cache)}
        runs["unchanged"] = bench.cli(root, arguments, cache)
        for name, (suffixes, marker, text, where) in _EDITS.items():
            if where == "below":
                edited = named_most(root / "src", suffixes, marker)
                _add_below(edited, marker.encode(), text)
            elif where in ("beside", "removed"):
                added = _ADDED_LAUNCH if text is _NEW_LAUNCH else _ADDED_NAME
                edited = pick(root / "src", suffixes, marker).with_name(added)
                if where == "beside":
                    edited.write_bytes(text)
                else:
                    edited.unlink()
            elif where == "included":
                edited = included_most(root / "src", marker)
                _add(edited, text, "inside")
            elif where == "constant":
                edited, value_end = taken_most(root / "src", suffixes)
                data = edited.read_bytes()
                _replace(edited, data[:value_end] + text + data[value_end:])
            elif where == "endpoints":
                edited = pick(root / "src", suffixes, marker, (*ENDPOINT_CALLS, *_TESTS))
                _add(edited, text, "end")
            elif where == "node":  # its source, then the executable that compiles it
                edited = pick(root / "src", suffixes, marker)
                generation = "ROS 2" if b"ament" in edited.read_bytes() else "ROS 1"
                source = edited.parent / "src" / _NODE_SOURCE
                source.parent.mkdir(exist_ok=True)
                source.write_bytes(_NEW_NODE_SOURCE[generation])
                _add(edited, text, "end")
            else:
                edited = pick(root / "src", suffixes, marker)
                _add(edited, text, where)
            runs[name] = bench.cli(root, arguments, cache)
            results.setdefault("edited", {})[name] = edited.relative_to(root).as_posix()
        fresh = bench.cli(root, arguments, scratch / "fresh-cache")
        results["identical_after_edits"] = fresh.stdout == runs[list(_EDITS)[-1]].stdout
        # pre-commit's run: the files of a commit named, the C++ source among them given
        # another topic (the run over the workspace underneath, its graph patched).
        named = [results["edited"]["edit_names"], results["edited"]["edit_graph"]]
        _add(root / named[0], _NEW_TOPIC.replace(b"bench_probe", b"bench_commit"), "end")
        runs["commit"] = bench.cli(root, ["--format", "json", *named], cache)
        alone = bench.cli(root, ["--format", "json", "--no-cache", *named], cache)
        results["commit_identical"] = alone.stdout == runs["commit"].stdout
        results["runs"] = {name: run.summary() for name, run in runs.items()}
        if lsp_edits:
            snapshot = None if bench.SNAPSHOT is None else str(bench.SNAPSHOT)
            results["lsp"] = latency(root, lsp_edits, cache, snapshot)
    return results


def grown(workspace: Path, copies: int, root: Path) -> Path:
    """A colcon workspace at ``root``: ``src/c{i}-{entry}`` for each entry of the workspace
    (a repository, a package) and each copy ``i``, hard-linked. Laid out as a workspace so
    that the language server, opened at ``root``, reads it whole
    (``discover.editor_workspace``: packages one or two levels below ``src``)."""
    entries = sorted(entry for entry in workspace.iterdir() if not entry.name.startswith("."))
    for index in range(copies):
        for entry in entries:
            target = root / "src" / f"c{index}-{entry.name}"
            if entry.is_dir():
                shutil.copytree(entry, target, symlinks=True, copy_function=os.link)
            else:
                target.parent.mkdir(parents=True, exist_ok=True)
                os.link(entry, target)
    return root


def named_most(workspace: Path, suffixes: tuple[str, ...], marker: str) -> Path:
    """The file with ``marker`` in it whose directory and name (``config/x.yaml``) the
    launch files of the workspace hold most often (the first by path of those): a
    parameter file launch files hand their nodes, where a file of the same suffix picked
    by size is often one no tree reads (and a name alone, ``params.yaml``, is many
    files')."""
    launch = [
        text_of(path)
        for suffix in (".launch", ".launch.xml", ".launch.py")
        for path in workspace.rglob(f"*{suffix}")
        if path.is_file()
    ]
    named = sorted(
        (-sum(f"{path.parent.name}/{path.name}" in text for text in launch), path)
        for suffix in suffixes
        for path in workspace.rglob(f"*{suffix}")
        if path.is_file() and marker in text_of(path)
    )
    if not named:
        raise SystemExit(f"no {suffixes} file with {marker!r} in {workspace}")
    return named[0][1]


# An include of a launch file, with what it holds (its arguments, where it hands some)
_INCLUDE = re.compile(r'<include\s+file="([^"]+)"\s*>(.*?)</include>', re.DOTALL)


def included_most(workspace: Path, marker: str) -> Path:
    """The launch XML file with ``marker`` in it whose name the includes that hand
    arguments name most often (the first by path of those): one the graph reads under
    its includers' arguments."""
    named: dict[str, int] = {}
    launch = sorted(path for path in workspace.rglob("*.launch.xml") if path.is_file())
    for path in launch:
        for include in _INCLUDE.finditer(text_of(path)):
            if "<arg " in include.group(2):
                name = include.group(1).rsplit("/", 1)[-1]
                named[name] = named.get(name, 0) + 1
    found = sorted(
        (-named[path.name], path)
        for path in launch
        if named.get(path.name) and marker in text_of(path)
    )
    if not found:
        raise SystemExit(f"no launch file included with arguments in {workspace}")
    return found[0][1]


# A string constant a header defines: ``static const std::string NAME = "value";``.
_CONSTANT = re.compile(rb'const\s+std::string\s+([A-Z_][A-Z0-9_]*)\s*=\s*"[^"\n]*(")')


def taken_most(workspace: Path, suffixes: tuple[str, ...]) -> tuple[Path, int]:
    """The header whose string constant the most C++ sources of its package that include
    it name (the first by path of those), and where the value of its first such constant ends: a
    header whose value other files take (``symbols``), not one no file reads."""
    best: tuple[int, str, Path, int] | None = None
    for suffix in suffixes:
        for header in sorted(workspace.rglob(f"*{suffix}")):
            data = header.read_bytes() if header.is_file() else b""
            found = {match.group(1): match.start(2) for match in _CONSTANT.finditer(data)}
            package = next((p for p in header.parents if (p / "package.xml").is_file()), None)
            if not found or package is None:
                continue
            sources = [
                source
                for path in package.rglob("*.cpp")
                if path.is_file() and header.name.encode() in (source := path.read_bytes())
            ]  # those that include it
            for name, end in found.items():
                word = re.compile(rb"\b%s\b" % name)
                taking = sum(bool(word.search(source)) for source in sources)
                key = (-taking, str(header), header, end)
                if taking and (best is None or key[:2] < best[:2]):
                    best = key
    if best is None:
        raise SystemExit(f"no {suffixes} file defines a constant a source takes in {workspace}")
    return best[2], best[3]


def text_of(path: Path) -> str:
    """A file's text, undecodable bytes replaced; "" where it cannot be read."""
    try:
        return path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return ""


def _add_below(path: Path, marker: bytes, text: bytes) -> None:
    """``text`` put on a line of its own below the first line holding ``marker``,
    indented two more spaces than that line (``_add``)."""
    data = path.read_bytes()
    start = data.rfind(b"\n", 0, data.index(marker)) + 1
    end = data.index(b"\n", start) + 1
    indent = len(data[start:end]) - len(data[start:end].lstrip(b" ")) + 2
    _replace(path, data[:end] + b" " * indent + text + data[end:])


def _add(path: Path, text: bytes, where: str) -> None:
    """``text`` put at the "end", the "start", or "inside" the root element (before the
    last end tag), as a new file renamed over the old: the copies that share the old
    file's bytes through a hard link keep them."""
    data = path.read_bytes()
    at = {"end": len(data), "start": 0, "inside": data.rfind(b"</")}[where]
    _replace(path, data[:at] + text + data[at:])


def _replace(path: Path, data: bytes) -> None:
    replacement = path.with_name(f".{path.name}.bench")
    replacement.write_bytes(data)
    os.replace(replacement, path)


def table(results: dict[str, Any]) -> str:
    machine = results["machine"]
    lines = [
        f"Growth: {results['copies']} copies of {results['workspace']}, "
        f"{results['files']} files; {machine['cpu_model']}, {machine['nproc']} cores",
        f"{'run':<12} {'wall s':>8} {'CPU s':>8} {'serial s':>9} {'peak MB':>8}",
    ]
    for name, run in results["runs"].items():
        serial = run["main_cpu_s"]
        peak = run["tree_rss_mb"] or run["max_rss_mb"]
        lines.append(
            f"{name:<12} {run['wall_s']:>8.2f} {run['cpu_s']:>8.2f} "
            f"{'-' if serial is None else f'{serial:.2f}':>9} {peak:>8.0f}"
        )
    lines.append(
        f"identical to a run with an empty cache after the edits: "
        f"{results['identical_after_edits']}; the commit's run to one without a cache: "
        f"{results.get('commit_identical')}"
    )
    lsp = results.get("lsp")
    if lsp:
        graph = ", ".join(f"{k} {v['median_s']:.2f} s" for k, v in lsp.get("graph", {}).items())
        lines.append(
            f"language server: workspace loaded in {lsp.get('load_s')} s, first graph at "
            f"{lsp.get('first_graph_s')} s; graph findings after an edit (median): {graph}"
        )
    return "\n".join(lines)
