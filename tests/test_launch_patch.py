"""A graph patched after an edit of launch files is the graph a build gives
(``workspace.launch_patch``, issue 30): each step edits the example workspace's launch
files as a developer would, and the last build's graph with the trees that read the
edited files walked again must equal the graph built from every file's facts; an edit
the patch cannot follow is refused, never patched wrong."""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import ExampleCopy, assert_patched

from roslint_names.model import FileFacts
from roslint_names.workspace.graph import Graph
from roslint_names.workspace.launch_parts import LaunchParts
from roslint_names.workspace.launch_patch import (
    LazyFacts,
    launch_edit,
    launch_patched,
    parameter_edit,
)

BASE = "src/turtle_bringup/launch/base.launch"  # ROS 1, included four times by robots.launch
ROBOTS = "src/turtle_bringup/launch/robots.launch"  # ROS 1, includes base.launch four times
TELEOP = "src/turtle_bringup/launch/teleop.launch"  # ROS 1, a root with an argument
MULTI = "src/turtle_bringup/launch/multi_robot.launch"  # ROS 1, a root with groups
LOCALIZATION = "src/fleet_bringup/launch/localization.launch.xml"  # ROS 2 XML
FLEET = "src/fleet_bringup/launch/fleet.launch.py"  # ROS 2 Python
WAYPOINTS = "src/fleet_bringup/config/waypoint_follower.yaml"  # ROS 2, fleet.launch.py's
# ROS 1 parameter files the steps' workspace holds besides the examples' (``_Workspace``)
SMOOTHER = "config/smoother.yaml"
SMOOTHER_PATH = f"src/turtle_bringup/{SMOOTHER}"
UNLOADED = "src/turtle_bringup/config/unloaded.yaml"
EXTRA_FILES = {
    SMOOTHER_PATH: "# The velocity smoother's limits.\nspeed_lim_v: 0.8\nspeed_lim_w: 5.4\n"
    "decel_factor: 1.0\n",
    UNLOADED: "max_speed: 1.0\n",
}

# (file, text before, text after); each step's graph is patched from the step before's.
PATCHED = [
    # A node whose package the workspace does not hold, added to an included file: four
    # trees start it, in four namespaces.
    (BASE, "</launch>", '  <node name="bench_node" pkg="bench" type="bench_node"/>\n</launch>'),
    # A second instance of launched code, under a name of its own.
    (
        BASE,
        '  <node name="battery_monitor"',
        '  <node name="spare_smoother" pkg="turtle_bringup" type="velocity_smoother"/>\n'
        '  <node name="battery_monitor"',
    ),
    # A node renamed: RN301's duplicate pair and every endpoint follow it.
    (BASE, 'name="battery_monitor"', 'name="battery_watch"'),
    # A remap added: the node's endpoint renamed in every namespace.
    (
        BASE,
        '<remap from="cmd_vel_raw"',
        '<remap from="cmd_vel" to="smooth/cmd_vel"/>\n    <remap from="cmd_vel_raw"',
    ),
    # A node in a group's namespace with parameters of its own.
    (
        MULTI,
        '    <node name="odometry_filter"',
        '    <node name="imu_filter" pkg="imu_filter_madgwick" type="imu_filter_node">\n'
        '      <param name="use_mag" value="false"/>\n'
        "    </node>\n"
        '    <node name="odometry_filter"',
    ),
    # ROS 2 XML: a parameter set on a node, and the node moved out of its group.
    (
        LOCALIZATION,
        '<param name="odom_frame_id" value="odom"/>',
        '<param name="odom_frame_id" value="odom_combined"/>\n'
        '      <param name="scan_topic" value="scan"/>',
    ),
    (
        LOCALIZATION,
        '  <node pkg="rviz2" exec="rviz2" name="rviz" namespace="fleet/robot3"/>',
        '  <node pkg="rviz2" exec="rviz2" name="rviz" namespace="fleet/robot4"/>',
    ),
    # ROS 2 Python: a remap changed.
    (FLEET, '("/tf", "tf")', '("/tf", "tf2")'),
    # A node taken out (its code still runs in the other), and every line moved.
    (
        BASE,
        '  <node name="spare_smoother" pkg="turtle_bringup" type="velocity_smoother"/>\n',
        "",
    ),
    (BASE, "<launch>", "<!-- The base. -->\n<launch>"),
    # Code that no launch file started is started now: a program of its own no more.
    (BASE, "</launch>", '  <node name="relay" pkg="turtle_bringup" type="odom_relay"/>\n</launch>'),
    # The last node that starts some code taken out: a program of its own again.
    (BASE, '  <node name="battery_watch" pkg="turtle_bringup" type="battery_monitor"/>\n', ""),
    # An include's namespace changed: one tree's nodes move.
    (ROBOTS, 'ns="site_a/warehouse/robot3"', 'ns="site_b/robot3"'),
    # An include of a file three trees include already: one more tree reads it.
    (
        MULTI,
        "</launch>",
        '  <include file="$(find turtle_bringup)/launch/base.launch" ns="robot9"/>\n</launch>',
    ),
    # An include of a root, with an argument: teleop.launch is a root no more, its node
    # started by multi_robot.launch's tree, and teleop.launch read under the argument.
    (
        MULTI,
        "</launch>",
        '  <include file="$(find turtle_bringup)/launch/teleop.launch">\n'
        '    <arg name="robot" value="robot9"/>\n'
        "  </include>\n</launch>",
    ),
    # teleop.launch edited, read under the argument in that tree: its node renamed, then
    # every line of it moved (the places the graph keeps of it are of that read).
    (TELEOP, 'name="teleop"', 'name="teleop_keyboard"'),
    (TELEOP, "<launch>", "<!-- One robot's teleop. -->\n<launch>"),
    # Every include of base.launch taken out of robots.launch: base.launch is still
    # included (by multi_robot.launch), robots.launch starts nothing.
    (
        ROBOTS,
        '  <include file="$(find turtle_bringup)/launch/base.launch" ns="robot1"/>\n',
        "",
    ),
    # The include of the root taken out again: teleop.launch is a root again.
    (
        MULTI,
        '  <include file="$(find turtle_bringup)/launch/teleop.launch">\n'
        '    <arg name="robot" value="robot9"/>\n'
        "  </include>\n",
        "",
    ),
    # An include of a file the workspace does not hold.
    (MULTI, "</launch>", '  <include file="$(dirname)/absent.launch"/>\n</launch>'),
    # ROS 2 parameter files (``parameter_edit``): the key that misses the namespaced node
    # made one every node matches; a setting changed and one added; every line moved.
    (WAYPOINTS, "waypoint_follower:", "/**:"),
    (WAYPOINTS, "loop_rate: 10.0", "loop_rate: 20.0\n    max_robot_pose_search_dist: 10.0"),
    (WAYPOINTS, "# Written before", "# Tuned on the warehouse floor.\n# Written before"),
    # ROS 1: a file loaded inside a node of the file four trees include, and at group
    # level into that node's private namespace in one of them; then the file edited.
    (
        BASE,
        '    <remap from="cmd_vel_raw"',
        f'    <rosparam command="load" file="$(find turtle_bringup)/{SMOOTHER}"/>\n'
        '    <remap from="cmd_vel_raw"',
    ),
    (
        MULTI,
        "</launch>",
        f'  <rosparam command="load" file="$(find turtle_bringup)/{SMOOTHER}"'
        ' ns="robot9/velocity_smoother"/>\n</launch>',
    ),
    (SMOOTHER_PATH, "decel_factor: 1.0", "decel_factor: 1.5\naccel_lim_v: 0.3"),
    (SMOOTHER_PATH, "speed_lim_w: 5.4\n", ""),
    (SMOOTHER_PATH, "# The velocity", "# Limits measured on the robot.\n# The velocity"),
    # A parameter file no launch file loads: no tree reads it. (A value changed changes
    # no fact: a file's facts are the names it sets and where.)
    (UNLOADED, "max_speed: 1.0", "max_speed: 1.0\nmin_speed: 0.1"),
]

# Edits a patch cannot follow: the graph is built.
REFUSED = [
    # A parameter file made a launch file: which files are parameter files changes.
    (WAYPOINTS, "# Written before", "launch: []\n# Written before"),
]


class _Workspace(ExampleCopy):
    def built(self) -> tuple[Graph, LaunchParts, dict[str, FileFacts]]:
        graph, parts, _, facts = self.built_parts()
        return graph, parts, facts

    def patched(
        self,
        graph: Graph,
        parts: LaunchParts,
        before: dict[str, FileFacts],
        now: dict[str, FileFacts],
    ) -> tuple[Graph, LaunchParts] | None:
        changed = [path for path in now if before.get(path) != now[path]]
        assert changed and before.keys() == now.keys()
        if not all(
            launch_edit(before[path], now[path]) or parameter_edit(before[path], now[path])
            for path in changed
        ):
            return None
        assert self.specialiser is not None
        return launch_patched(
            graph,
            parts,
            changed,
            facts=LazyFacts(now.keys(), now.get),
            packages=self.packages,
            specialise=self.specialiser,
            prepare=self.specialiser.prepare,
        )


_Step = tuple[str, tuple[Graph, LaunchParts], tuple[Graph, LaunchParts] | None]


@pytest.fixture(scope="module")
def steps(tmp_path_factory: pytest.TempPathFactory) -> list[_Step]:
    """Each step: the file edited, the graph and launch parts built after it, and those
    patched."""
    workspace = _Workspace(tmp_path_factory.mktemp("launch_patch") / "ws")
    workspace.add(EXTRA_FILES)
    graph, parts, facts = workspace.built()
    found: list[_Step] = []
    for relative, old, new in PATCHED:
        workspace.edit(relative, old, new)
        built, built_parts, now = workspace.built()
        patched = workspace.patched(graph, parts, facts, now)
        found.append((relative, (built, built_parts), patched))
        graph, parts, facts = built, built_parts, now
    return found


@pytest.mark.parametrize("step", range(len(PATCHED)))
def test_a_patched_graph_and_its_parts_are_the_built_ones(steps: list[_Step], step: int) -> None:
    """The parts too: a patched run keeps them as the next runs' (``engine``'s
    ``REBASE_EDITS``), which patch from them as from a build's."""
    assert_patched(steps, step)


@pytest.mark.parametrize("step", range(len(REFUSED)))
def test_an_edit_the_patch_cannot_follow_is_refused(tmp_path: Path, step: int) -> None:
    workspace = _Workspace(tmp_path / "ws")
    graph, parts, facts = workspace.built()
    workspace.edit(*REFUSED[step])
    built, _, now = workspace.built()
    assert built != graph
    assert workspace.patched(graph, parts, facts, now) is None
