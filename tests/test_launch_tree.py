"""Launch trees hand each depth's specialisations over before they ask for them.

The engine extracts those together (in worker processes when the run has them); the walk
must then ask for nothing it did not announce, and start the same nodes in the same order
as a walk that announces nothing.
"""

from __future__ import annotations

from collections.abc import Sequence

from roslint_names.extract.launch import xml_launch as launch_xml
from roslint_names.model import FileFacts, Generation, LaunchArguments
from roslint_names.workspace.index import Package, WorkspaceIndex
from roslint_names.workspace.launch_tree import LaunchTrees

# Two robots from one bringup file; each robot's base file hands its sensors file a frame
# prefix built from the robot's name; the sensors file starts one driver per robot.
LAUNCH = {
    "src/fleet_bringup/launch/fleet.launch": """\
<launch>
  <include file="$(find fleet_bringup)/launch/robot.launch" ns="robot1">
    <arg name="robot" value="robot1"/>
  </include>
  <include file="$(find fleet_bringup)/launch/robot.launch" ns="robot2">
    <arg name="robot" value="robot2"/>
  </include>
  <node pkg="fleet_manager" type="fleet_manager_node" name="fleet_manager"/>
</launch>
""",
    "src/fleet_bringup/launch/robot.launch": """\
<launch>
  <arg name="robot" default="robot"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="$(arg robot)_state"/>
  <include file="$(find fleet_bringup)/launch/sensors.launch">
    <arg name="frame_prefix" value="$(arg robot)"/>
  </include>
</launch>
""",
    "src/fleet_bringup/launch/sensors.launch": """\
<launch>
  <arg name="frame_prefix" default=""/>
  <node pkg="urg_node" type="urg_node" name="laser_driver">
    <param name="frame_id" value="$(arg frame_prefix)/laser"/>
  </node>
</launch>
""",
}
PACKAGES = [Package("fleet_bringup", "src/fleet_bringup")]


def _extract(path: str, arguments: LaunchArguments = ()) -> FileFacts:
    data = LAUNCH[path].encode()
    return launch_xml.extract(path, data, Generation.ROS1, Generation.ROS1, arguments=arguments)


def _trees(events: list[tuple[str, object]], announce: bool) -> LaunchTrees:
    index = WorkspaceIndex([_extract(path) for path in LAUNCH], PACKAGES)

    def specialise(path: str, arguments: LaunchArguments) -> FileFacts | None:
        events.append(("asked", (path, arguments)))
        return _extract(path, arguments)

    def prepare(wanted: Sequence[tuple[str, LaunchArguments]]) -> None:
        events.append(("announced", list(wanted)))

    return LaunchTrees(index, specialise, prepare if announce else None)


def test_each_depth_is_announced_before_any_of_it_is_asked_for() -> None:
    events: list[tuple[str, object]] = []
    launched = list(_trees(events, announce=True).launched())
    announced = [wanted for kind, wanted in events if kind == "announced"]
    robot, sensors = (
        "src/fleet_bringup/launch/robot.launch",
        "src/fleet_bringup/launch/sensors.launch",
    )
    assert announced == [
        [],  # the roots: extracted already
        [(robot, (("robot", "robot1"),)), (robot, (("robot", "robot2"),))],
        [(sensors, (("frame_prefix", "robot1"),)), (sensors, (("frame_prefix", "robot2"),))],
    ]
    seen: set[object] = set()
    for kind, what in events:
        if kind == "announced":
            seen.update(what)  # type: ignore[arg-type]
        else:
            assert what in seen, f"asked for {what} before announcing it"
    assert [(item.namespace, item.node.name) for item in launched] == [
        ("/", "fleet_manager"),
        ("/robot1", "robot1_state"),
        ("/robot1", "laser_driver"),
        ("/robot2", "robot2_state"),
        ("/robot2", "laser_driver"),
    ]


def test_announcing_changes_nothing_the_walk_starts() -> None:
    with_announcing = list(_trees([], announce=True).launched())
    without = list(_trees([], announce=False).launched())
    assert with_announcing == without
