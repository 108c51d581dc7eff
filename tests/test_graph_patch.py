"""A graph patched after an edit of a node's code is the graph a build gives
(``workspace.patch``, issue 30): each step edits the example workspace's code as a
developer would, and the last graph with the edited files' nodes resolved again must
equal the graph built from every file's facts; an edit the patch cannot follow is
refused, never patched wrong."""

from __future__ import annotations

import itertools
from dataclasses import replace
from pathlib import Path

import pytest
from conftest import ExampleCopy, assert_patched

from roslint_names.model import FileFacts
from roslint_names.rule import Rule, RuleContext
from roslint_names.workspace.graph import Graph
from roslint_names.workspace.index import PackageFiles
from roslint_names.workspace.patch import (
    Moved,
    code_edit,
    for_patching,
    kept_parts,
    parameter_part,
    patched,
)

MONITOR = "src/fleet_bringup/src/fleet_monitor.cpp"  # ROS 2, launched by fleet.launch.py
RECORDER = "src/fleet_bringup/fleet_bringup/pose_recorder.py"
RELAY = "src/turtle_bringup/src/odom_relay.cpp"  # ROS 1, launched in robot namespaces
DOCK = "src/fleet_bringup/src/dock_manager.cpp"
SMOOTHER = "src/turtle_bringup/src/velocity_smoother.cpp"  # ROS 1, base.launch starts it

# (file, text before, text after); each step's graph is patched from the step before's.
PATCHED = [
    # A topic renamed: the RN401 pair with the recorder is gone.
    (MONITOR, '"robot_pose"', '"robot_pose_estimate"'),
    # A publisher added in the middle: the names below it move, the parameters above not.
    (
        MONITOR,
        "    odom_sub_ =",
        '    auto status = create_publisher<std_msgs::msg::String>("status", 1);\n    odom_sub_ =',
    ),
    # A line above everything: every parameter use moves with the new endpoints.
    (MONITOR, "#include <chrono>", "// Fleet monitor.\n#include <chrono>"),
    # A message type changed.
    (MONITOR, "PoseStamped>(", "Pose>("),
    # ROS 1: a name through the node's handle, launched in each robot's namespace.
    (RELAY, 'advertise<nav_msgs::Odometry>("odom"', 'advertise<nav_msgs::Odometry>("odometry"'),
    (RELAY, "nh.subscribe(odom_topic_", 'private_nh.subscribe("wheel_odom"'),
    # ROS 1 code robots.launch starts twice under one name (robot2's base included
    # twice): both namesakes resolved again.
    (SMOOTHER, '"/mobile_base/commands/velocity"', '"mobile_base/commands/velocity"'),
    # Python: the subscription renamed to what the monitor publishes now.
    (RECORDER, '"Robot_Pose"', '"robot_pose_estimate"'),
    # A comment: the facts are those of the step before.
    (RECORDER, "", "\n# Recorded as they come.\n"),
]

# Edits a patch cannot follow: the graph is built.
REFUSED = [
    (MONITOR, '"map_frame"', '"map_frame_id"'),  # a parameter renamed
    (RECORDER, '__init__("pose_recorder")', '__init__("pose_logger")'),  # the node renamed
    # Its only endpoint gone: a program no launch file starts is one that has some.
    (
        RECORDER,
        'self.create_subscription(PoseStamped, "Robot_Pose", self.poses.append, 10)',
        "pass",
    ),
]


class _Workspace(ExampleCopy):
    def built(self) -> tuple[Graph, dict[str, FileFacts]]:
        graph, _, _, facts = self.built_parts()
        return graph, facts

    def patched(
        self, graph: Graph, edits: dict[str, Moved], now: dict[str, FileFacts]
    ) -> Graph | None:
        return patched(graph, edits, now.get, lambda: PackageFiles(list(now), self.packages))


@pytest.fixture(scope="module")
def steps(tmp_path_factory: pytest.TempPathFactory) -> list[tuple[str, Graph, Graph | None]]:
    """Each step: the file edited, the graph built after it, and the graph patched."""
    workspace = _Workspace(tmp_path_factory.mktemp("patch") / "ws")
    graph, facts = workspace.built()
    found: list[tuple[str, Graph, Graph | None]] = []
    for relative, old, new in PATCHED:
        workspace.edit(relative, old, new)
        built, now = workspace.built()
        moves = code_edit(facts[relative], now[relative])
        patch = None if moves is None else workspace.patched(graph, {relative: moves}, now)
        found.append((relative, built, patch))
        graph, facts = built, now
    return found


@pytest.mark.parametrize("step", range(len(PATCHED)))
def test_a_patched_graph_is_the_built_graph(
    steps: list[tuple[str, Graph, Graph | None]], step: int
) -> None:
    assert_patched(steps, step)


def test_the_steps_change_what_the_graph_rules_read(
    steps: list[tuple[str, Graph, Graph | None]],
) -> None:
    """Not a sequence of edits the graph never sees: most steps change endpoints."""
    changed = sum(
        1
        for (_, before, _), (_, after, _) in itertools.pairwise(steps)
        if before.endpoints != after.endpoints
    )
    assert changed >= 5


@pytest.mark.parametrize(("relative", "old", "new"), REFUSED)
def test_an_edit_of_more_than_endpoints_is_refused(
    tmp_path: Path, relative: str, old: str, new: str
) -> None:
    workspace = _Workspace(tmp_path / "ws")
    _, before = workspace.built()
    workspace.edit(relative, old, new)
    _, after = workspace.built()
    assert code_edit(before[relative], after[relative]) is None


def test_two_nodes_of_one_name_in_one_tree_running_one_file_are_both_patched(
    steps: list[tuple[str, Graph, Graph | None]],
) -> None:
    """Whose endpoints are whose is known by the node's name, tree and code: where two
    namesakes run the edited file, both are resolved again (``patch._touched``), their
    endpoints there all made anew (the step is ``test_a_patched_graph_is_the_built_graph``'s)."""
    step = next(index for index, (relative, _, _) in enumerate(steps) if relative == SMOOTHER)
    _, built, patch = steps[step]
    running = [node for node in built.nodes if SMOOTHER in node.sources]
    names = [(node.name, node.root) for node in running]
    assert len(set(names)) < len(names), "no two namesakes run the edited file"
    assert patch == built


def _findings(graph: Graph, rule: Rule) -> list[object]:
    assert rule.check_workspace is not None
    return list(rule.check_workspace(graph, RuleContext()))


def test_a_rule_that_reads_no_code_name_finds_the_same_without_them(tmp_path: Path) -> None:
    """``Rule.reads_code_names``: a patch that changes only the nodes' endpoints, the names
    their code uses and their packages' literals keeps the findings of the rules that say
    they read none of them; the example graph stripped of all three must give those rules
    the same findings (and each of them finds something there)."""
    workspace = _Workspace(tmp_path / "ws")
    graph, _ = workspace.built()
    stripped = replace(
        graph,
        endpoints=(),
        mentions={},
        nodes=tuple(
            replace(node, uses=(), uses_relative=(), uses_complete=not node.uses_complete)
            for node in graph.nodes
        ),
    )
    rules = [rule for rule in workspace.registry.rules if rule.check_workspace is not None]
    blind = [rule for rule in rules if not rule.reads_code_names]
    assert {rule.code for rule in blind} == {"RN402", "RN405", "RN406", "RN407"}
    for rule in blind:
        found = _findings(graph, rule)
        assert found, rule.code
        assert _findings(stripped, rule) == found, rule.code
    # The stripping is one the other rules see.
    assert any(
        _findings(stripped, rule) != _findings(graph, rule)
        for rule in rules
        if rule.reads_code_names
    )


def test_the_rules_run_over_a_patched_graph_read_nothing_it_does_not_keep(tmp_path: Path) -> None:
    """The CLI keeps a build's graph without the parameters' declarations, settings and
    files (``for_patching``): the rules it runs over a patched graph must find the same
    there, and each finds something; the rules that read those find less."""
    workspace = _Workspace(tmp_path / "ws")
    graph, _ = workspace.built()
    kept = for_patching(graph)
    rules = [rule for rule in workspace.registry.rules if rule.check_workspace is not None]
    for rule in rules:
        if rule.reads_code_names:
            found = _findings(graph, rule)
            assert found, rule.code
            assert _findings(kept, rule) == found, rule.code
    blind = [rule for rule in rules if not rule.reads_code_names]
    assert any(_findings(kept, rule) != _findings(graph, rule) for rule in blind)


def test_the_kept_graph_holds_each_name_and_reach_once(tmp_path: Path) -> None:
    """Each file's facts bring their own copy of a name (a package's, once per node of
    it; a node's, once more in each of its endpoints): the graph the CLI keeps
    (``for_patching``) pickles one of each, and equals the graph it was made from but
    for what it leaves out."""
    workspace = _Workspace(tmp_path / "ws")
    graph, _ = workspace.built()
    kept = for_patching(graph)
    assert len({id(node.reach) for node in graph.nodes}) > len({node.reach for node in graph.nodes})
    for found in (graph, kept):
        names = {node.name: node.name for node in found.nodes}
        shared = [endpoint.node is names[endpoint.node] for endpoint in found.endpoints]
        packages = {}
        for node in found.nodes:
            packages.setdefault(node.package, set()).add(id(node.package))
        reaches = {node.reach: set() for node in found.nodes}
        for node in found.nodes:
            reaches[node.reach].add(id(node.reach))
        once = all(shared) and all(len(ids) == 1 for ids in (*packages.values(), *reaches.values()))
        assert once is (found is kept)
    stripped = tuple(
        replace(node, code_parameters=None, parameter_settings=(), parameter_files=())
        for node in graph.nodes
    )
    assert kept.nodes == stripped and kept.endpoints == graph.endpoints


def test_the_kept_launch_parts_hold_each_name_once(tmp_path: Path) -> None:
    """What the CLI keeps beside the graph for a launch patch (``kept_parts``): equal to
    what the build left, each program a tree starts and each name a launch file sets
    one object."""
    graph, parts, _, _ = _Workspace(tmp_path / "ws").built_parts()
    kept_part, kept_launch = kept_parts(graph, parts)
    assert kept_part == parameter_part(graph) and kept_launch == parts

    def copies(found: list[str]) -> int:
        return len({id(name) for name in found}) - len(set(found))

    for launch, part in ((parts, parameter_part(graph)), (kept_launch, kept_part)):
        started = [name for tree in launch.trees.values() for pair in tree.started for name in pair]
        settings = [setting.name for _, kept, _ in part.nodes for setting in kept]
        assert (copies(started) + copies(settings) == 0) is (launch is kept_launch)
