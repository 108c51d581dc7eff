"""A run after an edit that leaves the edited files' facts as they were takes the last
run's graph findings instead of loading every file's facts and building the graph again
(``same_facts``, issue 30); its output is byte for byte a fresh run's, over a sequence of
edits of the example workspace that do and do not move names."""

from __future__ import annotations

import json
import os
import re
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from conftest import AMENT_PACKAGE
from test_unused_remap_bases import ground_filter, pointcloud_filters

from roslint_names import cache as cache_module
from roslint_names import graph_patch, run_checks, same_facts, shifts
from roslint_names import session as session_module
from roslint_names.config import load_settings
from roslint_names.model import FileFacts, Generation, Kind, Language, NameUse, Role, Span
from roslint_names.registry import load_registry
from roslint_names.session import Session

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FLEET = "src/fleet_bringup"
MONITOR = f"{FLEET}/src/fleet_monitor.cpp"  # a graph finding (RN401) at line 22
DOCK = f"{FLEET}/src/dock_manager.cpp"  # RN204 waits for the run; RN407 at line 18
RECORDER = f"{FLEET}/fleet_bringup/pose_recorder.py"  # the other side of the RN401
REPORTER = f"{FLEET}/fleet_bringup/battery_reporter.py"  # launched by fleet.launch.py
PARAMETERS = f"{FLEET}/config/waypoint_follower.yaml"  # RN405
LOCALIZATION = f"{FLEET}/launch/localization.launch.xml"
TURTLE_BUILD = "src/turtle_bringup/CMakeLists.txt"
TURTLE_LAUNCH = "src/turtle_bringup/launch"
TELEOP = f"{TURTLE_LAUNCH}/teleop.launch"
BASE = f"{TURTLE_LAUNCH}/base.launch"  # included four times by robots.launch
ROBOT7 = """<launch>
  <include file="$(find turtle_bringup)/launch/teleop.launch">
    <arg name="robot" value="robot7"/>
  </include>
</launch>
"""


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    root = tmp_path / "ws"
    shutil.copytree(EXAMPLES, root)
    return root


@pytest.fixture
def replayed(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[list[int]]]:
    """The edited files of each run that took a replay."""
    seen: list[list[int]] = []
    original = run_checks.RunChecks.resume

    def recording(checks: Any, replay: Any, edited: Any, paths: Any) -> None:
        seen.append(list(edited))
        original(checks, replay, edited, paths)

    monkeypatch.setattr(run_checks.RunChecks, "resume", recording)
    yield seen


@pytest.fixture
def taken(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[str]]:
    """What each run that took facts did: "replay" (the last graph's findings stand),
    "patch" (the last graph patched, ``workspace.patch``) or "build"; a run served its
    stored result ("stored") takes none."""
    seen: list[str] = []
    patched: list[bool] = []
    original = graph_patch.take_facts  # engine imports it when a run takes facts
    patch = graph_patch.GraphPatch.__call__

    def recording(*arguments: Any, **keywords: Any) -> Any:
        patched.clear()
        found = original(*arguments, **keywords)
        seen.append("build" if found is None else "patch" if any(patched) else "replay")
        return found

    def patching(*arguments: Any, **keywords: Any) -> Any:
        found = patch(*arguments, **keywords)
        patched.append(found is not None)
        return found

    monkeypatch.setattr(graph_patch, "take_facts", recording)
    monkeypatch.setattr(graph_patch.GraphPatch, "__call__", patching)
    yield seen


def outputs(run_cli: Any, root: Path, cache: Path) -> tuple[str, str]:
    """A cached run's JSON and a fresh run's."""
    arguments = ["check", "--format", "json", "--jobs", "1", "--exit-zero"]
    cached = run_cli([*arguments, "--cache-dir", str(cache), "."], root)
    fresh = run_cli([*arguments, "--no-cache", "."], root)
    assert cached.exit_code == fresh.exit_code == 0, cached.stderr
    return cached.stdout, fresh.stdout


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text(encoding="utf-8")
    assert old in text, (path, old)
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    stamp = path.stat().st_mtime + 2  # another time than the digests remember
    os.utime(path, (stamp, stamp))


def append(path: Path, text: str) -> None:
    edit(path, path.read_text(encoding="utf-8"), path.read_text(encoding="utf-8") + text)


def change(path: Path, old: str | None, new: str | None) -> None:
    """A step's change: ``old`` None, the file made with ``new``; ``new`` None, the file
    removed; ``old`` "", ``new`` appended; else ``old`` edited into ``new``."""
    if old is None:
        assert new is not None and not path.exists(), path
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(new, encoding="utf-8")
    elif new is None:
        path.unlink()
    elif old:
        edit(path, old, new)
    else:
        append(path, new)


LINE_18 = 'get_parameter("dockframe").as_string().c_str());'
STATUS = 'auto status = create_publisher<std_msgs::msg::String>("fleet_status", 1);'
RELAY = "src/turtle_bringup/src/odom_relay.cpp"  # ROS 1, launched in robot namespaces
OWN_STATUS = (
    '    auto own = create_publisher<std_msgs::msg::String>("~/Status", 1);\n'
    '    auto all = create_publisher<std_msgs::msg::String>("/fleet_monitor/status", 1);\n'
)

# Files added and removed (``shifts``)
HEADER = f"{FLEET}/include/fleet_bringup/angles.hpp"
ANGLES = """#pragma once

namespace fleet_bringup
{
// An angle in (-pi, pi].
inline double wrapped(double angle)
{
  while (angle > 3.14159265358979) angle -= 6.28318530717959;
  while (angle <= -3.14159265358979) angle += 6.28318530717959;
  return angle;
}
}  // namespace fleet_bringup
"""
UNITS = f"{FLEET}/include/fleet_bringup/units.hpp"
MODULE = f"{FLEET}/fleet_bringup/geometry.py"
GEOMETRY = """\"\"\"Plane geometry for the fleet's poses.\"\"\"

import math


def heading(dx: float, dy: float) -> float:
    return math.atan2(dy, dx)
"""
NODE_IMPORTS = "from rclpy.node import Node\nfrom std_msgs.msg import String\n"
ANNOUNCE = """

def announce(node: Node) -> None:
    node.create_publisher(String, "geometry_ready", 1)
"""
BEACON = f"{FLEET}/fleet_bringup/beacon.py"
BEACON_NODE = """import rclpy
from rclpy.node import Node
from std_msgs.msg import String


def main() -> None:
    rclpy.init()
    node = Node("beacon")
    node.create_publisher(String, "fleet_beacon", 10)
    rclpy.spin(node)
"""
FLEET_MANIFEST = f"{FLEET}/package.xml"
SPARE_LAUNCH = f"{TURTLE_LAUNCH}/spare.launch"
SPARE_SMOOTHER = """<launch>
  <node name="spare_smoother" pkg="turtle_bringup" type="velocity_smoother">
    <rosparam command="load" file="$(find turtle_bringup)/config/spare.yaml"/>
  </node>
  <node name="spare_smoother" pkg="turtle_bringup" type="battery_monitor"/>
</launch>
"""
SPARE_SETTINGS = "src/turtle_bringup/config/spare.yaml"
SPARE_SETTING_TEXT = "speed_lim_v: 0.8\nnever_read: 1\n"
# A script named after an executable a launch file runs, which no build file makes
SMOOTHER_SCRIPT = "src/turtle_bringup/scripts/velocity_smoother.py"

# A class of the fleet's package whose method declares a parameter, for the nodes
# deriving from it.
REPORTING = """#pragma once
#include <rclcpp/rclcpp.hpp>

namespace fleet_bringup
{
class Reporting
{
public:
  void declare_reporting(rclcpp::Node & node) { node.declare_parameter("report_period", 5.0); }
};
}  // namespace fleet_bringup
"""
DOCK_CLIENT = """void call_dock(rclcpp::Node & node)
{
  auto dock = node.create_client<std_srvs::srv::Trigger>("trigger");
}
"""
PROBE_SOURCE = f"{FLEET}/src/dock_probe.cpp"
PROBE_NODE = """#include <rclcpp/rclcpp.hpp>
#include <std_srvs/srv/trigger.hpp>

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("dock_probe");
  auto dock = node->create_client<std_srvs::srv::Trigger>("dock");
  rclcpp::spin(node);
  return 0;
}
"""
TOPICS = f"{FLEET}/include/fleet_bringup/topics.hpp"
TOPICS_HEADER = """#pragma once
#include <string>

namespace fleet_bringup
{
static const std::string DOCK_STATUS_TOPIC = "dock_status";
}  // namespace fleet_bringup
"""
STATUS_SOURCE = f"{FLEET}/src/dock_status.cpp"
STATUS_NODE = """#include <fleet_bringup/topics.hpp>
#include <rclcpp/rclcpp.hpp>
#include <std_msgs/msg/string.hpp>

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("dock_status");
  auto publisher = node->create_publisher<std_msgs::msg::String>(
    fleet_bringup::DOCK_STATUS_TOPIC, 10);
  rclcpp::spin(node);
  return 0;
}
"""

FILTER_SOURCE = "src/turtle_bringup/src/odom_filter.cpp"
FILTER_NODE = """// Smooths the odometry before the planners read it.
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

ros::Publisher filtered;

void filter(const nav_msgs::Odometry::ConstPtr & odom) { filtered.publish(*odom); }

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "odom_filter");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  double alpha = private_nh.param("alpha", 0.2);
  filtered = nh.advertise<nav_msgs::Odometry>("odom_filtered", 10);
  ros::Subscriber odom = nh.subscribe("odom", 10, filter);
  ros::spin();
  return 0;
}
"""

FILTER_ENDPOINTS = """  filtered = nh.advertise<nav_msgs::Odometry>("odom_filtered", 10);
  ros::Subscriber odom = nh.subscribe("odom", 10, filter);
"""

# (file, text before, text after, what the run after it does: ``taken``): ``change``.
STEPS: list[tuple[str, str | None, str | None, str]] = [
    # A comment below everything: the facts are the same.
    (MONITOR, "", "\n// Reviewed: the pose is republished as is.\n", "replay"),
    # A line above the names moves them, and the other side of the RN401 says where.
    (MONITOR, "#include", "// Fleet monitor.\n#include", "replay"),
    # A file whose own check waits for the run's service types (RN204), with a graph
    # finding (RN407).
    (DOCK, "", "\n// Docking is refused while charging.\n", "replay"),
    # A suppression of the graph finding; main()'s events move below it.
    (DOCK, LINE_18, f"{LINE_18}  // NOLINT(RN407)", "replay"),
    # The same marker, now naming another rule: the graph finding is back, the
    # suppression silences nothing. Only the text changed.
    (DOCK, "NOLINT(RN407)", "NOLINT(RN204)", "replay"),
    # The bytes of two runs ago: that run's stored result, nothing replayed.
    (DOCK, "NOLINT(RN204)", "NOLINT(RN407)", "stored"),
    # A release: the manifest says nothing else the run reads (its name, build type,
    # dependencies, plugin descriptions), so the run is the last one.
    (FLEET_MANIFEST, "<version>0.1.0</version>", "<version>0.2.0</version>", "stored"),
    (RECORDER, "", "\n# Poses are recorded as they come.\n", "replay"),
    (RECORDER, "import rclpy", "# Records poses.\nimport rclpy", "replay"),  # names move
    (PARAMETERS, "waypoint_follower:", "# The follower's tuning.\nwaypoint_follower:", "replay"),
    # A comment holding a suppression marker at the end: the file is read by every run
    # now (a fact), the graph is the same.
    (MONITOR, "", "\n// A bare NOLINT is cpplint's, not ours.\n", "replay"),
    (PARAMETERS, "", "\n# Tuned on the warehouse floor.\n", "replay"),
    (TURTLE_BUILD, "", "\n# Nodes of the turtle robot.\n", "replay"),
    # A dependency found above the executables: their places move, what they compile and
    # what the graph is made of do not (``RunWide.built`` keeps no place).
    (TURTLE_BUILD, "catkin_package()", "find_package(Boost REQUIRED)\ncatkin_package()", "replay"),
    # A header and a Python module that say nothing the graph reads: the last run's
    # replay, its files renumbered; the next patch patches the last build's graph.
    (HEADER, None, ANGLES, "replay"),
    (MODULE, None, GEOMETRY, "replay"),
    (MODULE, "import math\n", "import math\n\nTURN = math.pi\n", "replay"),
    # The module starts declaring a publisher: code no launch file starts is a program
    # of its own where it declares endpoints (``launch_parts.Programs``), its package's
    # programs made again. Then it declares none again (it logs instead).
    (MODULE, "import math\n", f"import math\n\n{NODE_IMPORTS}", "replay"),
    (MODULE, "", ANNOUNCE, "patch"),
    (MODULE, 'create_publisher(String, "geometry_ready", 1)', "get_logger().info(TURN)", "patch"),
    # A name changed: the RN401 pair is gone. A parameter file moved since the last
    # build: the tree that hands it to its node is walked again (its settings' places).
    (MONITOR, '"robot_pose"', '"robot_pose_estimate"', "patch"),
    # Since, code alone: the last graph, the monitor's node resolved again.
    (MONITOR, '"robot_pose_estimate", 10);', '"robot_pose", 10);  // as it was', "patch"),
    (MONITOR, "", "\n// Back as it was.\n", "replay"),
    # Gone again: its files renumbered once more, from the last run's.
    (MODULE, "", None, "replay"),
    # A parameter file no launch file names yet, then a launch file nothing includes
    # handing it to a node: a tree of its own, walked (RN406 in the parameter file, a
    # duplicate node name, RN402); edited, walked again (the pair gone).
    (SPARE_SETTINGS, None, SPARE_SETTING_TEXT, "patch"),
    (SPARE_LAUNCH, None, SPARE_SMOOTHER, "patch"),
    (SPARE_LAUNCH, 'name="spare_smoother"', 'name="velocity_smoother"', "patch"),
    (HEADER, "", None, "replay"),
    # A publisher added in the middle of the node (the names below it move), and the
    # recorder's subscription renamed to it: a new RN401 pair, the old one gone.
    (MONITOR, "    odom_sub_ =", f"    {STATUS}\n    odom_sub_ =", "patch"),
    (RECORDER, '"Robot_Pose"', '"Fleet_Status"', "patch"),
    # The parameter file removed while the launch file still loads it.
    (SPARE_SETTINGS, "", None, "patch"),
    # ROS 1 code launched in each robot's namespace: a relative name renamed.
    (RELAY, '<nav_msgs::Odometry>("odom"', '<nav_msgs::Odometry>("odometry"', "patch"),
    # The publisher taken out again, and a parameter renamed (the graph is built).
    (MONITOR, f"    {STATUS}\n", "", "patch"),
    # A service renamed below a new comment line: the RN407 of the line below is the
    # kept graph's, moved (a rule that reads no code name: ``Rule.reads_code_names``).
    (DOCK, "what it does.\n", "what it does.\n    // Renamed.\n", "replay"),
    (DOCK, '"StartDocking"', '"start_docking"', "patch"),
    # A file that holds a node is a program of its own; one a launch file runs by name
    # is that node's code (``WorkspaceIndex.sources_of``): each makes its package's
    # programs again (``workspace.program_patch``). Then the first taken out again
    # (the last build never had it: the patch is of the script alone).
    (BEACON, None, BEACON_NODE, "patch"),
    (SMOOTHER_SCRIPT, None, GEOMETRY, "patch"),
    (BEACON, "", None, "patch"),
    # The files of three runs ago, as they were: that run's stored result.
    (SMOOTHER_SCRIPT, "", None, "stored"),
    # A private topic and the one its name resolves to in another case (RN401, by the
    # node's name), and a node of fleet.launch.py started without a name (its code's).
    (MONITOR, "    odom_sub_ =", f"{OWN_STATUS}    odom_sub_ =", "patch"),
    (f"{FLEET}/launch/fleet.launch.py", '                name="batteryReporter",\n', "", "patch"),
    # A service of another type: the set of service types the files use (RN204)
    # changes (SetBool gone, Empty new): every file comparing with it is checked again
    # (``Replay.typed``), the graph patched.
    (
        MONITOR,
        "create_service<std_srvs::srv::SetBool>",
        "create_service<std_srvs::srv::Empty>",
        "patch",
    ),
    # A client of a type another file serves (the dock manager's Trigger), named after
    # its type (RN204): the set of types the files use stays the same (``RunWide.
    # typed_uses``). Then of the type the monitor serves (Empty); then of a type no
    # file uses any more (SetBool); then of Trigger again, named otherwise (the last
    # file using SetBool changed): each patched.
    (MONITOR, "", f"\n{DOCK_CLIENT}", "patch"),
    (MONITOR, 'std_srvs::srv::Trigger>("trigger"', 'std_srvs::srv::Empty>("trigger"', "patch"),
    (MONITOR, 'std_srvs::srv::Empty>("trigger"', 'std_srvs::srv::SetBool>("trigger"', "patch"),
    (MONITOR, 'std_srvs::srv::SetBool>("trigger"', 'std_srvs::srv::Trigger>("docking"', "patch"),
    # A node calling the dock manager's service added, a header that says nothing,
    # then the node taken out: files no run had, renumbered from the last run's, its
    # count of Trigger's users less the file gone (``graph_patch._typed_uses_without``).
    (PROBE_SOURCE, None, PROBE_NODE, "patch"),
    (f"{FLEET}/include/fleet_bringup/probe.hpp", None, "#pragma once\n", "replay"),
    (PROBE_SOURCE, "", None, "patch"),
    # The parameter file back, named by a launch file the build read: the trees that
    # read that file walked again find it. Then the launch file removed: its tree gone
    # (``launch_patch``, its ``removed``).
    (SPARE_SETTINGS, None, SPARE_SETTING_TEXT, "patch"),
    (SPARE_LAUNCH, "", None, "patch"),
    # A header added, then the launch file back in a list of files no run had (the
    # build's file again, through two renumberings: ``Renumbering.after``), then the
    # header removed (the files of an earlier run: its replay, the launch file edited).
    (UNITS, None, ANGLES.replace("wrapped", "unit"), "replay"),
    (SPARE_LAUNCH, None, SPARE_SMOOTHER, "patch"),
    (UNITS, "", None, "patch"),
    # A parameter renamed: the parameters of the code spanning its package gathered
    # again (``workspace.parameter_patch``).
    # Since that build, the node names their code gives themselves changed
    # (``patch.name_edit``): the monitor's program of its own made again (its RN401 pair
    # gone), the tree that starts the reporter walked again (its RN406 names it anew).
    (MONITOR, 'Node("fleet_monitor", options)', 'Node("fleet_watch", options)', "patch"),
    (REPORTER, 'super().__init__("battery_reporter")', 'super().__init__("battery")', "patch"),
    (MONITOR, '"map_frame"', '"map_frame_id"', "patch"),
    # A launch file nothing includes, which wires no absolute name.
    (LOCALIZATION, "</launch>", "</launch>\n<!-- localization -->", "replay"),
    # Nodes added, renamed and remapped in launch files: the trees that read the file
    # walked again (``workspace.launch_patch``), here four trees of robots.launch.
    (
        BASE,
        "</launch>",
        '  <node name="spare" pkg="turtle_bringup" type="velocity_smoother"/>\n</launch>',
        "patch",
    ),
    (BASE, 'name="spare"', 'name="spare_smoother"', "patch"),
    (
        LOCALIZATION,
        '<remap from="scan" to="~scan"/>',
        '<remap from="scan" to="~/scan_filtered"/>',
        "patch",
    ),
    # Code edited since: both patches, the launch trees' and the code's.
    (RELAY, '<nav_msgs::Odometry>("odometry"', '<nav_msgs::Odometry>("odom_in"', "patch"),
    # The node named as the other robot's base: a duplicate node name (RN301) in one tree.
    (BASE, 'name="spare_smoother"', 'name="velocity_smoother"', "patch"),
    # An include added: one more tree reads base.launch.
    (
        TELEOP,
        "</launch>",
        '  <include file="$(find turtle_bringup)/launch/base.launch" ns="teleop"/>\n</launch>',
        "patch",
    ),
    # Code no launch file started, started in five trees: a program of its own no more;
    # its code was edited since the last build, and it runs twice under one name in
    # robots.launch's tree (robot2 is included twice): the code patch resolves both
    # namesakes again (``patch._touched``). Then the only node of other code taken out: a
    # program of its own again.
    (
        BASE,
        "</launch>",
        '  <node name="relay" pkg="turtle_bringup" type="odom_relay"/>\n</launch>',
        "patch",
    ),
    (
        BASE,
        '  <node name="battery_monitor" pkg="turtle_bringup" type="battery_monitor"/>\n',
        "",
        "patch",
    ),
    # A script no launch file started, started by one: a program of its own no more.
    (
        TELEOP,
        "</launch>",
        '  <node name="pose_logger" pkg="turtle_bringup" type="pose_logger.py"/>\n</launch>',
        "patch",
    ),
    # teleop.launch included with an argument: a root no more, and read under it; an
    # edit of it then walks again the trees that read it (never patched from its own
    # facts: they read it under the argument again).
    (
        f"{TURTLE_LAUNCH}/multi_robot.launch",
        "</launch>",
        '  <include file="$(find turtle_bringup)/launch/teleop.launch">\n'
        '    <arg name="robot" value="robot9"/>\n'
        "  </include>\n</launch>",
        "patch",
    ),
    (TELEOP, 'name="teleop"', 'name="teleop_keyboard"', "patch"),
    # The parameter file's key made to match the node in any namespace (RN405 fixed),
    # then a setting added: the tree that hands it to the node is walked again.
    (PARAMETERS, "waypoint_follower:\n", "/**/waypoint_follower:\n", "patch"),
    (
        PARAMETERS,
        "    loop_rate: 10.0\n",
        "    loop_rate: 10.0\n    stop_on_arrival: true\n",
        "patch",
    ),
    # The node's code declares one of the settings now: its RN406 is gone.
    (
        f"{FLEET}/fleet_bringup/waypoint_follower.py",
        '        self.declare_parameter("map_frame", "map")\n',
        '        self.declare_parameter("map_frame", "map")\n'
        '        self.declare_parameter("loop_rate", 10.0)\n',
        "patch",
    ),
    # What a node's parameters are gathered through (``patch.gathering_edit``): a header
    # of its package included, a class deriving from the client library's node added
    # (the growth benchmark's ``edit_class``), and a base of the dock manager's class
    # its own package now defines in a header added (its code spans another file; the
    # package's programs made again, ``workspace.program_patch``).
    (
        MONITOR,
        "#include <std_srvs/srv/set_bool.hpp>\n",
        "#include <std_srvs/srv/set_bool.hpp>\n\n#include <fleet_bringup/units.hpp>\n",
        "patch",
    ),
    (MONITOR, "", "\nclass MonitorProbe : public rclcpp::Node\n{\n};\n", "patch"),
    (UNITS, None, REPORTING, "patch"),
    (DOCK, "public rclcpp::Node", "public rclcpp::Node, public fleet_bringup::Reporting", "patch"),
    # A header whose constant names a topic (no file takes it yet: patched, its package
    # resolving its names as before), and code taking it added: resolved as the whole
    # run resolves it, patched (and kept as a build keeps it). Then an include changed
    # in that package: the code resolves its names as before
    # (``graph_patch._Constants.anew``), the graph is patched.
    (TOPICS, None, TOPICS_HEADER, "patch"),
    (STATUS_SOURCE, None, STATUS_NODE, "patch"),
    (MONITOR, "\n#include <fleet_bringup/units.hpp>\n", "", "patch"),
    # A parameter declared beside that code: the package's files are read as the run
    # reads them, the constant's name resolved (``graph_patch.GraphPatch``), and patched.
    (
        MONITOR,
        "",
        "\nvoid declare_rate(rclcpp::Node & node)\n{\n"
        '  node.declare_parameter("status_rate", 1.0);\n}\n',
        "patch",
    ),
    # The file taking the constant edited: a comment, then a topic of its own added (its
    # names resolved from its package's headers then and now, ``graph_patch.GraphPatch``).
    # Then the constant's value changed: what every file taking it names changes (each
    # resolved then and now, an edit of its own, checked again).
    (STATUS_SOURCE, "", "\n// Reviewed with the fleet team.\n", "patch"),
    (
        STATUS_SOURCE,
        "  rclcpp::spin(node);",
        '  auto beacon = node->create_publisher<std_msgs::msg::String>("dock_beacon", 10);\n'
        "  rclcpp::spin(node);",
        "patch",
    ),
    (TOPICS, '"dock_status"', '"dock_state"', "patch"),
    # The code taking it taken out: as the build resolved it, its package's programs
    # made again.
    (STATUS_SOURCE, "", None, "patch"),
    # A roscpp node added as a developer adds one: its executable first (no source yet:
    # the build keeps no program of it), then its source, then a launch file starting it;
    # then the source taken out (``workspace.program_patch``: the package's programs made
    # again, the trees starting a node of it walked again).
    (TURTLE_BUILD, "", "add_executable(odom_filter src/odom_filter.cpp)\n", "patch"),
    (FILTER_SOURCE, None, FILTER_NODE, "patch"),
    # Its endpoints taken out: its program, which no launch file starts, is none of its
    # own any more (the package's programs made again).
    (FILTER_SOURCE, FILTER_ENDPOINTS, "", "patch"),
    (
        BASE,
        "</launch>",
        '  <node name="odom_filter" pkg="turtle_bringup" type="odom_filter"/>\n</launch>',
        "patch",
    ),
    # And put back, the node launched now.
    (FILTER_SOURCE, "  ros::spin();", f"{FILTER_ENDPOINTS}  ros::spin();", "patch"),
    (FILTER_SOURCE, "", None, "patch"),
]


def test_a_sequence_of_edits_gives_what_a_fresh_run_gives(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # Every patch from the last build, as the steps' comments say (none kept as the next
    # runs' graph: the test below).
    monkeypatch.setattr(graph_patch, "REBASE_EDITS", len(STEPS))
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    for step, (relative, old, new, how) in enumerate(STEPS):
        taken.clear()
        change(workspace / relative, old, new)
        cached, fresh = outputs(run_cli, workspace, cache)
        assert cached == fresh, (step, relative, old, new)
        # The cached run, then the fresh one (which builds).
        assert taken == [*([] if how == "stored" else [how]), "build"], (step, relative, taken)


def test_a_sequence_of_edits_each_kept_as_the_next_runs_graph_gives_what_a_fresh_run_gives(
    run_cli: Any, workspace: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Every patched run keeps what it patched as a build keeps it (``REBASE_EDITS`` of
    one): the next run patches that graph with the launch and code parameter parts the
    patches made, and must print what a fresh run prints at every step."""
    monkeypatch.setattr(graph_patch, "REBASE_EDITS", 1)
    kept: list[int] = []
    patch = graph_patch.GraphPatch.__call__

    def patching(self: Any, *arguments: Any) -> Any:
        found = patch(self, *arguments)
        kept.append(self.rebased is not None)
        return found

    monkeypatch.setattr(graph_patch.GraphPatch, "__call__", patching)
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    # Then a setting the follower ignores declared by its code (its RN406 gone), then
    # the tree that hands it the file walked again: the node's parameters are those
    # the first run kept (``LaunchParts.parameters``), not the build's.
    follower = f"{FLEET}/fleet_bringup/waypoint_follower.py"
    declared = (
        follower,
        '        self.declare_parameter("loop_rate", 10.0)\n',
        '        self.declare_parameter("loop_rate", 10.0)\n'
        '        self.declare_parameter("stop_on_arrival", False)\n',
        "patch",
    )
    walked = (f"{FLEET}/launch/fleet.launch.py", '("/tf", "tf")', '("/tf", "tf_fleet")', "patch")
    for step, (relative, old, new, _) in enumerate([*STEPS, declared, walked]):
        change(workspace / relative, old, new)
        cached, fresh = outputs(run_cli, workspace, cache)
        assert cached == fresh, (step, relative, old, new)
    assert sum(kept) >= 20, kept


THRESHOLD = '        self.threshold = self.declare_parameter("low_threshold", 0.2).value\n'
REPORTER_ENDPOINTS = """        self.low_pub = self.create_publisher(Bool, "battery/low", 10)
        self.create_subscription(BatteryState, "battery/state", self.on_state, 10)
"""
LOGGER = "src/turtle_bringup/scripts/pose_logger.py"  # installed, launched by none
LOGGER_SUBSCRIPTION = "        rospy.Subscriber('turtle1/pose', Pose, self.on_pose, queue_size=1)\n"


def test_code_that_starts_or_stops_declaring_endpoints_is_patched(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """Code no launch file starts is a program of its own where it declares endpoints
    (``launch_parts.Programs``): a file the build had that starts or stops declaring
    any makes its package's programs again (``graph_patch.GraphPatch``'s ``flipping``),
    the graph is patched: a module that starts, a launched node's code that stops (its
    node runs on), a script no launch file starts that stops (its program gone), and
    the last two starting again."""
    change(workspace / MODULE, None, f"{GEOMETRY}\n{NODE_IMPORTS}")
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    steps = [
        (MODULE, "", ANNOUNCE),
        (REPORTER, REPORTER_ENDPOINTS, ""),
        (LOGGER, LOGGER_SUBSCRIPTION, ""),
        # Each starting again: the reporter as the build had it, the logger's topic
        # another (as it was, the files would be those of the run after the first step).
        (REPORTER, THRESHOLD, f"{THRESHOLD}{REPORTER_ENDPOINTS}"),
        (
            LOGGER,
            "        rospy.Timer(",
            LOGGER_SUBSCRIPTION.replace("turtle1/pose", "turtle2/pose") + "        rospy.Timer(",
        ),
    ]
    for relative, old, new in steps:
        taken.clear()
        change(workspace / relative, old, new)
        cached, fresh = outputs(run_cli, workspace, cache)
        assert cached == fresh, relative
        assert taken == ["patch", "build"], (relative, taken)


def test_the_step_that_holds_a_graph_finding_shows_it_moved(
    run_cli: Any, workspace: Path, tmp_path: Path, replayed: list[list[int]]
) -> None:
    """The replayed run makes the edited file's graph findings again under its text:
    a suppression renamed to another rule lets the graph finding out."""
    cache = tmp_path / "cache"
    dock = workspace / DOCK
    edit(dock, LINE_18, f"{LINE_18}  // NOLINT(RN407)")
    before, _ = outputs(run_cli, workspace, cache)
    assert '"RN407"' not in before
    edit(dock, "NOLINT(RN407)", "NOLINT(RN204)")
    after, fresh = outputs(run_cli, workspace, cache)
    assert replayed and after == fresh
    assert '"RN407"' in after and '"RN002"' in after


def test_an_edit_of_a_launch_file_included_with_arguments_walks_the_trees_that_read_it(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """A launch file extracted again under its includer's arguments is read for that,
    not only for its facts: an edit of it is never replayed, even one its own facts do
    not show; the trees that read it are walked again, reading it so again."""
    cache = tmp_path / "cache"
    (workspace / TURTLE_LAUNCH / "robot7.launch").write_text(ROBOT7, encoding="utf-8")
    outputs(run_cli, workspace, cache)
    edit(workspace / TELEOP, "</launch>", "</launch>\n<!-- one robot's teleop -->")
    taken.clear()
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["patch", "build"]


LEGACY = """#include <ros/ros.h>
#include <std_msgs/String.h>

// Left from the ROS 1 port; no build file names it.
int main(int argc, char** argv)
{
  ros::init(argc, argv, "legacyRelay");
  ros::NodeHandle node;
  ros::Publisher publisher = node.advertise<std_msgs::String>("Legacy-Out", 1);
  ros::spin();
  return 0;
}
"""


def test_an_edited_unbuilt_source_is_judged_unbuilt_again(
    run_cli: Any, workspace: Path, tmp_path: Path, replayed: list[list[int]]
) -> None:
    """The replay keeps the findings as the workspace spared them; an edited file's own
    are spared again, and ``--verbose`` names the files judged unbuilt as a fresh run
    does."""
    cache = tmp_path / "cache"
    legacy = workspace / "src/turtle_bringup/src/legacy_relay.cpp"
    legacy.write_text(LEGACY, encoding="utf-8")
    arguments = ["check", "--format", "json", "--jobs", "1", "--exit-zero", "--verbose"]
    run_cli([*arguments, "--cache-dir", str(cache), "."], workspace)
    append(legacy, "\n// Kept for reference.\n")
    cached = run_cli([*arguments, "--cache-dir", str(cache), "."], workspace)
    fresh = run_cli([*arguments, "--no-cache", "."], workspace)
    assert replayed
    assert cached.stdout == fresh.stdout
    assert "Legacy-Out" not in cached.stdout
    unbuilt = [line for line in cached.stderr.splitlines() if "legacy_relay.cpp" in line]
    assert unbuilt
    assert unbuilt == [line for line in fresh.stderr.splitlines() if "legacy_relay.cpp" in line]


def test_a_replayed_run_keeps_every_file_s_facts_in_the_cache(
    run_cli: Any,
    workspace: Path,
    tmp_path: Path,
    replayed: list[list[int]],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A pack past its limit is rewritten with the facts the run used: a replayed run
    loads almost none, yet stands on all of them. Once they were dropped, the next run
    that needed them all (a build: here, other rules chosen, which no replay serves)
    extracted the whole workspace again (69 s at 77,000 files)."""
    monkeypatch.setattr(cache_module, "PACK_LIMIT", 2048)
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    append(workspace / MONITOR, "\n// Reviewed.\n")
    outputs(run_cli, workspace, cache)
    assert replayed
    arguments = ["check", "--format", "json", "--jobs", "1", "--exit-zero", "--verbose"]
    run = run_cli([*arguments, "--ignore", "RN101", "--cache-dir", str(cache), "."], workspace)
    taken = re.search(r"(\d+) of (\d+) files from the cache, 0 extracted by", run.stderr)
    assert taken is not None, run.stderr
    assert taken[1] == taken[2]


def test_a_damaged_replay_is_a_run_like_any(
    run_cli: Any, workspace: Path, tmp_path: Path, replayed: list[list[int]]
) -> None:
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    kept = list(cache.glob("*/replays/*"))
    assert kept
    for entry in kept:
        entry.write_bytes(entry.read_bytes()[:-40])
    append(workspace / MONITOR, "\n// Reviewed.\n")
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert not replayed
    append(workspace / MONITOR, "\n// Reviewed again.\n")  # the run above kept a new one
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert replayed


# One file, nothing found
EMPTY = ("replay 7", ("k1",), 1, (), (), (), (), (), (), (), (), (), (), (), (), (), (), None)


def test_an_empty_stored_replay_reads_back() -> None:
    assert same_facts.loaded(EMPTY, files=1, reported=1) is not None


@pytest.mark.parametrize(
    ("value", "files"),
    [
        (None, 1),
        ((), 1),
        (("replay 0", *EMPTY[1:]), 1),  # another format
        (EMPTY, 2),  # kept for one file, asked for two
        ((*EMPTY[:3], ((3, ()),), *EMPTY[4:]), 1),  # findings of a file not reported
        ((*EMPTY[:3], ((0, ("x",)),), *EMPTY[4:]), 1),  # a finding that is not one
        ((*EMPTY[:4], ((0, (("RN401", "x"),)),), *EMPTY[5:]), 1),
        ((*EMPTY[:6], ((7, "srv"),), *EMPTY[7:]), 1),  # a generation that is not one
        ((*EMPTY[:8], (("x", None),), *EMPTY[9:]), 1),  # built sources that are not facts
        ((*EMPTY[:11], (3,), *EMPTY[12:]), 1),  # an unbuilt file that is not reported
        ((*EMPTY[:11], ("src/a.cpp",), *EMPTY[12:]), 1),  # one that is not an index
        ((*EMPTY[:13], (3,), *EMPTY[14:]), 1),  # a typed file that is not reported
        ((*EMPTY[:14], (7,), (), (), None), 1),  # a name that is not a string
        ((*EMPTY[:15], (("a.yaml", ("x",)),), (), None), 1),  # a digest that is not one
        ((*EMPTY[:17], (((None, "std_srvs/Empty"), 0),)), 1),  # a type no file uses
        ((*EMPTY[:17], (((7, "std_srvs/Empty"), 1),)), 1),  # a generation that is not one
    ],
)
def test_a_stored_replay_of_another_shape_is_none(value: object, files: int) -> None:
    assert same_facts.loaded(value, files=files, reported=1) is None


def _serving(path: str, *types: str) -> FileFacts:
    """A ROS 2 C++ file serving a service of each of ``types``."""
    uses = tuple(
        NameUse(Kind.SERVICE, "reset", Span(1, 1, 1, 8), Role.SERVE, "create_service", False, t)
        for t in types
    )
    return FileFacts(path, Language.CPP, Generation.ROS2, names=uses)


def test_a_renumbered_replay_counts_the_service_types_less_the_files_removed() -> None:
    """``RunWide.typed_uses`` less the files removed since (``shifted_replay``): unknown
    where a removed file's facts are not kept; a type whose last user went counted 0 (the
    set other files' RN204 compared with, which a patch compares its own with)."""
    trigger, empty = (Generation.ROS2, "std_srvs/Trigger"), (Generation.ROS2, "std_srvs/Empty")
    uses = {trigger: 2, empty: 1}
    without = graph_patch._typed_uses_without
    assert without(uses, []) == uses
    assert without(None, [_serving("a.cpp", "std_srvs/Trigger")]) is None
    assert without(uses, [None]) is None
    assert without(uses, [_serving("a.cpp", "std_srvs/srv/Trigger")]) == {trigger: 1, empty: 1}
    assert without(uses, [_serving("a.cpp", "std_srvs/Empty")]) == {trigger: 2, empty: 0}
    assert without(uses, [_serving(path, "std_srvs/Empty") for path in ("a", "b")]) is None


def test_a_node_another_package_s_build_file_names_is_patched(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """turtle_bringup's build compiles a node whose source is fleet_bringup's (which has
    no build file): the source added, then taken out, makes the programs of both
    packages again (``GraphPatch._builders``), as a fresh run has them."""
    target = "add_executable(dock_probe ../fleet_bringup/src/dock_probe.cpp)\n"
    change(workspace / TURTLE_BUILD, "", target)
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    # Then a header that names nothing (the last run's findings, renumbered), so that the
    # files are no earlier run's once the source is taken out again.
    steps = [
        (PROBE_SOURCE, None, PROBE_NODE, "patch"),
        (HEADER, None, ANGLES, "replay"),
        (PROBE_SOURCE, "", None, "patch"),
    ]
    for relative, old, new, how in steps:
        taken.clear()
        change(workspace / relative, old, new)
        cached, fresh = outputs(run_cli, workspace, cache)
        assert cached == fresh, relative
        assert taken == [how, "build"], relative


CHARGER = f"{FLEET}/src/charger.cpp"
CHARGER_NODE = """#include <fleet_msgs/srv/charge_battery.hpp>
#include <rclcpp/rclcpp.hpp>

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("charger");
  auto charge = node->create_service<fleet_msgs::srv::ChargeBattery>(
    "charge",
    [](const std::shared_ptr<fleet_msgs::srv::ChargeBattery::Request>,
       std::shared_ptr<fleet_msgs::srv::ChargeBattery::Response>) {});
  rclcpp::spin(node);
  return 0;
}
"""
CHARGE_CLIENT = """
void call_charge(rclcpp::Node & node)
{
  node.create_client<std_srvs::srv::Trigger>("charge_battery");
}
"""


def test_the_last_user_of_a_service_type_removed_is_patched(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """A node serving the only ChargeBattery of the workspace, and the monitor calling a
    Trigger named after that type (RN204). The node removed: the run's replay is the
    last one renumbered past the file gone (``shifted_replay``), its count of
    ChargeBattery's users 0; the patch finds the set of types changed and checks every
    file comparing with it again: the RN204 goes, as in a fresh run."""
    change(workspace / CHARGER, None, CHARGER_NODE)
    change(workspace / MONITOR, "", CHARGE_CLIENT)
    depends = "<exec_depend>nav2_amcl</exec_depend>"  # the types it may use: fleet_msgs'
    change(workspace / FLEET_MANIFEST, depends, f"{depends}\n  <depend>fleet_msgs</depend>")
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh and "ChargeBattery" in fresh
    taken.clear()
    change(workspace / CHARGER, "", None)
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh and "ChargeBattery" not in fresh
    assert taken == ["patch", "build"]


def test_a_stored_replay_reads_back_as_it_was() -> None:
    built = FileFacts("src/a/CMakeLists.txt", Language.CMAKE, Generation.ROS2)
    replay = same_facts.Replay(
        tags=("k1", "skipped: too large"),
        reported=2,
        found={},
        graph={},
        specialised=frozenset({"src/a/launch/a.launch.xml"}),
        run_wide=same_facts.RunWide(
            frozenset({(Generation.ROS2, "std_srvs/srv/Trigger"), (None, "Empty")}),
            frozenset({"/cmd_vel"}),
            ((built, "src/a"),),
            {"src/a": frozenset({"bad.launch"})},
            frozenset({"params.yaml", "talker"}),
            {"params.yaml": frozenset({7})},
            {1 << 63: 5, 7: shifts.SEVERAL},
            {(Generation.ROS2, "std_srvs/srv/Trigger"): 2},
        ),
        skipped=(("src/a/big.cpp", "too large"),),
        unbuilt=(1,),
        typed=(0,),
    )
    assert same_facts.loaded(replay.stored(), files=2, reported=2) == replay
    assert same_facts.loaded(replay.stored(), files=3, reported=2) is None


# The language server: a graph refresh after edits that leave every file's facts as they
# were takes the last graph's findings; the documents' diagnostics are a fresh session's.


def _session(root: Path) -> Session:
    registry = load_registry()
    session = Session(root, load_settings(None, root, registry), registry, None)
    session.load()
    return session


@pytest.fixture
def builds(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """One entry per graph the language server builds."""
    seen: list[int] = []
    original = session_module.build

    def counting(*arguments: Any, **keywords: Any) -> Any:
        seen.append(1)
        return original(*arguments, **keywords)

    monkeypatch.setattr(session_module, "build", counting)
    return seen


# (file, text before, text after, whether the refresh builds the graph)
SESSION_STEPS: list[tuple[str, str, str, bool]] = [
    (DOCK, "", "\n// Docking is refused while charging.\n", False),
    (DOCK, LINE_18, f"{LINE_18}  // NOLINT(RN407)", False),  # main()'s events move
    (MONITOR, "", "\n// A bare NOLINT is cpplint's, not ours.\n", False),  # a marker only
    (DOCK, "NOLINT(RN407)", "NOLINT(RN204)", False),  # the graph finding is back
    (MONITOR, "#include", "// Fleet monitor.\n#include", False),  # names moved
    (RECORDER, "import rclpy", "# Records poses.\nimport rclpy", False),  # the other side
    (MONITOR, "", "\n// Reviewed.\n", False),
    # A name changed: the monitor's node resolved again in the last graph.
    (MONITOR, '"robot_pose"', '"robot_pose_estimate"', False),
    (RECORDER, '"Robot_Pose"', '"robot_pose_estimate"', False),  # the other side renamed
    (MONITOR, '"map_frame"', '"map_frame_id"', True),  # a parameter renamed: built
    (TELEOP, "</launch>", "</launch>\n<!-- one robot's teleop -->", True),  # specialised
]


def test_the_language_server_refreshes_the_graph_of_moved_names_without_building_it(
    workspace: Path, builds: list[int]
) -> None:
    (workspace / TURTLE_LAUNCH / "robot7.launch").write_text(ROBOT7, encoding="utf-8")
    session = _session(workspace)
    texts = {
        relative: (workspace / relative).read_text(encoding="utf-8")
        for relative in {step[0] for step in SESSION_STEPS}
    }
    for relative, text in texts.items():
        session.check(workspace / relative, text)
    session.check_graph()
    for relative, old, new, rebuilds in SESSION_STEPS:
        builds.clear()
        text = texts[relative]
        assert not old or old in text
        texts[relative] = text.replace(old, new, 1) if old else text + new
        session.check(workspace / relative, texts[relative])
        found = session.check_graph()
        assert bool(builds) == rebuilds, (relative, old, new)
        # A fresh session over the same texts, saved: the same diagnostics everywhere.
        for other, content in texts.items():
            (workspace / other).write_text(content, encoding="utf-8")
        fresh = _session(workspace)
        for other, content in texts.items():
            fresh.check(workspace / other, content)
        assert found == fresh.check_graph(), (relative, old, new)


def test_the_language_server_says_nothing_of_a_suppression_a_graph_finding_uses(
    workspace: Path,
) -> None:
    """``// NOLINT(RN407)`` on the line of an RN407 (a graph finding) silences it: the
    per-file check's RN002 "silences nothing" on it is withdrawn once the graph's
    findings are in, as a run does. The server showed that RN002 beside the silenced
    finding."""
    session = _session(workspace)
    text = (workspace / DOCK).read_text(encoding="utf-8")
    session.check(workspace / DOCK, text.replace(LINE_18, f"{LINE_18}  // NOLINT(RN407)"))
    shown = [d.code for d in session.check_graph()[DOCK] if not d.suppressed]
    assert "RN407" not in shown
    assert "RN002" not in shown
    assert "RN204" in shown  # the file's other finding stays


def test_a_damaged_kept_graph_is_a_build(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """An edit of a node's endpoints patches the graph the last build kept; a torn one is
    no graph: the run builds, and says what a fresh run says."""
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    (kept,) = cache.glob("*/graphs/*")
    kept.write_bytes(kept.read_bytes()[:-40])
    taken.clear()
    edit(workspace / MONITOR, '"robot_pose"', '"robot_pose_estimate"')
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["build", "build"]
    edit(workspace / MONITOR, '"robot_pose_estimate"', '"robot_pose_stamped"')
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken[2:] == ["patch", "build"]  # the build above kept a graph again


def test_a_launch_file_whose_facts_only_moved_walks_no_tree(
    run_cli: Any,
    workspace: Path,
    tmp_path: Path,
    taken: list[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A comment in a launch file since the last build changes no tree: a code edit
    after it patches the kept graph alone (at 8 copies, walking the trees again and
    running every rule cost 0.8 s of a 2.9 s run)."""
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    walked: list[object] = []
    real = graph_patch.launch_patched

    def walking(*arguments: Any, **keywords: Any) -> Any:
        walked.append(arguments[2])
        return real(*arguments, **keywords)

    monkeypatch.setattr(graph_patch, "launch_patched", walking)
    append(workspace / BASE, "\n<!-- Reviewed for the second robot. -->\n")
    edit(workspace / MONITOR, '"robot_pose"', '"robot_pose_estimate"')
    taken.clear()
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["patch", "build"]
    assert walked == []
    edit(workspace / BASE, 'name="battery_monitor"', 'name="battery_watch"')
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert walked == [[BASE]]


@pytest.mark.parametrize("damage", ["torn", "another build's"])
def test_a_launch_edit_without_its_launch_parts_is_a_build(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str], damage: str
) -> None:
    """A launch edit walks the trees again from the parts the last build kept beside its
    graph (``same_facts.KeptLaunch``); torn, or kept by another build (a copy of the
    cache's, say), they are none: the run builds, and says what a fresh run says."""
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    (parts,) = cache.glob("*/launch-parts/*")
    blob = parts.read_bytes()
    edit(workspace / BASE, 'name="battery_monitor"', 'name="battery_watch"')
    taken.clear()
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["patch", "build"]
    if damage == "torn":
        parts.write_bytes(blob[:-40])
    else:  # the parts of the first build, under the key of the second's graph
        # A remap to another absolute name: what RN202 compares with changes, a build.
        edit(workspace / LOCALIZATION, 'to="~scan"', 'to="/scan_wired"')
        taken.clear()
        outputs(run_cli, workspace, cache)
        assert taken == ["build", "build"]
        (now,) = cache.glob("*/launch-parts/*")
        now.write_bytes(blob)
    edit(workspace / BASE, 'name="battery_watch"', 'name="battery_guard"')
    taken.clear()
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["build", "build"]


def test_the_language_server_patches_a_graph_whose_findings_moved_since(
    workspace: Path, builds: list[int]
) -> None:
    """Names moved in one file keep the last graph's findings, moved, but not the graph:
    a name changed in another file then patches that graph with both files' edits, and
    the case collision between them is shown where each name is now."""
    session = _session(workspace)
    texts = {
        relative: (workspace / relative).read_text(encoding="utf-8")
        for relative in (MONITOR, RECORDER)
    }
    for relative, text in texts.items():
        session.check(workspace / relative, text)
    session.check_graph()
    builds.clear()
    texts[RECORDER] = texts[RECORDER].replace("import rclpy", "# Records poses.\nimport rclpy")
    session.check(workspace / RECORDER, texts[RECORDER])
    session.check_graph()
    texts[MONITOR] = texts[MONITOR].replace('"robot_pose"', '"ROBOT_POSE"')
    session.check(workspace / MONITOR, texts[MONITOR])
    found = session.check_graph()
    assert not builds
    for relative, text in texts.items():
        (workspace / relative).write_text(text, encoding="utf-8")
    fresh = _session(workspace)
    for relative, text in texts.items():
        fresh.check(workspace / relative, text)
    expected = fresh.check_graph()
    assert any(d.code == "RN401" for d in expected[RECORDER])
    assert found == expected


def test_the_language_server_keeps_the_findings_of_rules_that_read_no_code_names(
    workspace: Path, builds: list[int], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A name changed in code patches the graph: the rules that read no code's names
    (``Rule.reads_code_names``: RN402, RN405, RN406, RN407) keep the last graph's
    findings, moved with the lines of the edited file, as the CLI's patch keeps them;
    the others find anew. The diagnostics are a fresh session's."""
    session = _session(workspace)
    text = (workspace / DOCK).read_text(encoding="utf-8")
    session.check(workspace / DOCK, text)
    session.check_graph()
    asked: list[list[str]] = []
    original = session_module.graph_findings

    def recording(graph: Any, rules: Any, settings: Any) -> Any:
        asked.append([rule.code for rule in rules])
        return original(graph, rules, settings)

    monkeypatch.setattr(session_module, "graph_findings", recording)
    builds.clear()
    text = text.replace('"StartDocking"', '"start_docking"').replace(
        '    declare_parameter("dock_frame"',
        '    // The frame docking ends in.\n    declare_parameter("dock_frame"',
    )
    session.check(workspace / DOCK, text)
    found = session.check_graph()
    assert not builds
    assert asked and not {"RN402", "RN405", "RN406", "RN407"} & set(asked[-1])
    assert [d.span.line for d in found[DOCK] if d.code == "RN407"] == [19]  # line 18 before
    (workspace / DOCK).write_text(text, encoding="utf-8")
    fresh = _session(workspace)
    fresh.check(workspace / DOCK, text)
    assert found == fresh.check_graph()


# pre-commit's runs, each naming the files staged: (files named, the edit before the
# run or None, what the run with the cache does: ``taken``).
FOCUSED_STEPS: list[tuple[tuple[str, ...], tuple[str, str | None, str | None] | None, str]] = [
    # The whole workspace's run, taken up whatever files are named.
    ((MONITOR, RECORDER), None, "replay"),
    ((DOCK,), None, "replay"),
    # A topic renamed in a node's code: the graph the workspace's run kept, patched.
    ((MONITOR, DOCK), (MONITOR, '"robot_pose"', '"robot_pose_estimate"'), "patch"),
    # A node renamed in a launch file four trees include: those trees walked again.
    ((BASE, RELAY), (BASE, 'name="battery_monitor"', 'name="battery_watch"'), "patch"),
    # The same files again, nothing changed: their own stored result.
    ((BASE, RELAY), None, "stored"),
    # A parameter file's key fixed (RN405), then the node's code declaring a setting.
    ((PARAMETERS,), (PARAMETERS, "waypoint_follower:\n", "/**/waypoint_follower:\n"), "patch"),
    (
        (f"{FLEET}/fleet_bringup/waypoint_follower.py", PARAMETERS),
        (
            f"{FLEET}/fleet_bringup/waypoint_follower.py",
            '        self.declare_parameter("map_frame", "map")\n',
            '        self.declare_parameter("map_frame", "map")\n'
            '        self.declare_parameter("loop_rate", 10.0)\n',
        ),
        "patch",
    ),
    # A comment in a file not named: the edited file checked, nothing reported in it.
    ((DOCK,), (RECORDER, "import rclpy", "# Records poses.\nimport rclpy"), "replay"),
    # A header added in a commit: the last run's replay, its files renumbered (``shifts``).
    ((HEADER, DOCK), (HEADER, None, ANGLES), "replay"),
]


def test_runs_over_some_files_are_the_workspace_s_run(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """pre-commit names the files staged, a new set each commit: each such run is the run
    over the whole workspace reported in those files (``engine._whole_workspace``), so it
    takes up what the last run over the workspace, or over any files of it, kept (its
    replay, its graph to patch) instead of building the graph for each new set; and says
    exactly what a run over the same files without a cache says."""
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)  # the workspace's run: the graph built and kept
    arguments = ["check", "--format", "json", "--jobs", "1", "--exit-zero"]
    for named, step, how in FOCUSED_STEPS:
        if step is not None:
            change(workspace / step[0], step[1], step[2])
        taken.clear()
        cached = run_cli([*arguments, "--cache-dir", str(cache), *named], workspace)
        fresh = run_cli([*arguments, "--no-cache", *named], workspace)
        assert (cached.stdout, cached.stderr) == (fresh.stdout, fresh.stderr), named
        assert json.loads(cached.stdout)["findings"], named  # findings to compare
        assert taken == [*([] if how == "stored" else [how]), "build"], (named, taken)
    # And the workspace's run takes up what the last of them left.
    taken.clear()
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["replay", "build"]


def test_edits_of_two_nodes_in_one_run_patch_the_graph_once(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """A commit that renames a topic on both sides: one run, both nodes resolved again."""
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    taken.clear()
    edit(workspace / MONITOR, '"robot_pose"', '"fleet/robot_pose"')
    edit(workspace / RECORDER, '"Robot_Pose"', '"fleet/robot_pose"')
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["patch", "build"]
    assert '"RN401"' not in cached  # the case collision between them is gone


def test_a_damaged_file_list_is_written_again_by_the_next_run_over_those_files(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """The files of a run the next run renumbers from (``shifts.Base``): damaged, the
    next run over them writes them again, so a file added after it still takes the
    replay."""
    cache = tmp_path / "cache"
    outputs(run_cli, workspace, cache)
    lists = sorted((cache).glob("facts-v*/file-lists/*"))
    assert len(lists) == 1
    change(workspace / HEADER, None, ANGLES)
    outputs(run_cli, workspace, cache)
    lists[0].write_bytes(b"damaged")
    change(workspace / HEADER, "", None)
    append(workspace / MONITOR, "\n// Reviewed.\n")
    outputs(run_cli, workspace, cache)
    taken.clear()
    change(workspace / UNITS, None, ANGLES.replace("wrapped", "unit"))
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    assert taken == ["replay", "build"]


NAMES = "src/fleet_names"  # a package of headers and their test: no node's code


def test_an_include_that_gives_test_code_a_constant_is_patched(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """A header's include changed reaches a test through it: the constant the test's
    topic takes, which only the whole run resolves (``symbols``). No node's code is of
    that package, so no parameter gathered again reads its files: the patch resolves
    every file of the package that takes a constant then and now, and one that resolves
    otherwise now is an edit of its own, checked again (``graph_patch._Constants.anew``),
    or the test's illegal topic would stay unreported. Then the constant's value changed
    back, and its header taken out of the include again."""
    status = workspace / NAMES / "include/fleet_names/status.hpp"
    change(workspace / NAMES / "package.xml", None, AMENT_PACKAGE.format(name="fleet_names"))
    change(
        workspace / NAMES / "include/fleet_names/topics.hpp",
        None,
        TOPICS_HEADER.replace("fleet_bringup", "fleet_names").replace(
            '"dock_status"', '"dock status"'
        ),
    )
    change(status, None, "#pragma once\n#include <string>\n")
    test = STATUS_NODE.replace("fleet_bringup/topics.hpp", "fleet_names/status.hpp")
    test = test.replace("fleet_bringup", "fleet_names")
    change(workspace / NAMES / "test/test_status.cpp", None, test)
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh and "dock status" not in fresh
    taken.clear()
    edit(status, "#include <string>\n", "#include <string>\n\n#include <fleet_names/topics.hpp>\n")
    cached, fresh = outputs(run_cli, workspace, cache)
    assert "dock status" in fresh
    assert cached == fresh
    assert taken == ["patch", "build"]
    topics = workspace / NAMES / "include/fleet_names/topics.hpp"
    header = topics.read_text(encoding="utf-8").replace('"dock status"', '"dock station"')
    steps: list[tuple[Path, str | None, str | None]] = [
        (topics, '"dock status"', '"dock_status"'),
        (topics, '"dock_status"', '"dock state"'),
        (topics, "", None),  # the header taken out, then brought back
        (topics, None, header),
        (status, "\n#include <fleet_names/topics.hpp>\n", ""),
    ]
    for step, (path, old, new) in enumerate(steps):
        taken.clear()
        change(path, old, new)
        cached, fresh = outputs(run_cli, workspace, cache)
        assert cached == fresh, (step, path, old, new)
        assert taken == ["patch", "build"], (step, path, old, new)
        assert ("dock state" in fresh, "dock station" in fresh) == (step == 1, step == 3), step


DOCK_DRIVER = """#include <rclcpp/rclcpp.hpp>
#include <std_msgs/msg/string.hpp>

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("dock_driver");
  auto state = node->create_publisher<std_msgs::msg::String>("dock_state", 10);
  rclcpp::spin(node);
  rclcpp::shutdown();
  return 0;
}
"""
DOCK_PANEL = """#include <rclcpp/rclcpp.hpp>
#include <std_msgs/msg/string.hpp>

#include "dock_panel/reset.hpp"

void shown(std_msgs::msg::String::ConstSharedPtr) {}

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("dock_panel");
  auto state = node->create_subscription<std_msgs::msg::String>("Dock_State", 10, shown);
  auto service = dock_panel::serve_reset(*node);
  rclcpp::spin(node);
  rclcpp::shutdown();
  return 0;
}
"""
# The panel's service, in a file of its own: no graph finding there, its RN204 the
# per-file rules' alone.
DOCK_RESET = """#include "dock_panel/reset.hpp"

#include <memory>

namespace dock_panel
{
void reset(
  const std::shared_ptr<std_srvs::srv::Trigger::Request>,
  std::shared_ptr<std_srvs::srv::Trigger::Response> response)
{
  response->success = true;
}

rclcpp::Service<std_srvs::srv::Trigger>::SharedPtr serve_reset(rclcpp::Node & node)
{
  return node.create_service<std_srvs::srv::Trigger>("reset_odometry", reset);
}
}  // namespace dock_panel
"""
DOCK_RESET_HEADER = """#pragma once
#include <rclcpp/rclcpp.hpp>
#include <std_srvs/srv/trigger.hpp>

namespace dock_panel
{
rclcpp::Service<std_srvs::srv::Trigger>::SharedPtr serve_reset(rclcpp::Node & node);
}  // namespace dock_panel
"""


def _dock_package(root: Path, name: str, sources: dict[str, str]) -> None:
    """``src/<name>``: an ament package building one program of ``sources`` (file name
    in ``src/``: text)."""
    package = root / "src" / name
    (package / "src").mkdir(parents=True)
    (package / "package.xml").write_text(AMENT_PACKAGE.format(name=name), encoding="utf-8")
    compiled = " ".join(f"src/{source}" for source in sources)
    (package / "CMakeLists.txt").write_text(
        f"cmake_minimum_required(VERSION 3.8)\nproject({name})\n"
        "find_package(ament_cmake REQUIRED)\n"
        f"add_executable({name} {compiled})\nament_package()\n",
        encoding="utf-8",
    )
    for source, text in sources.items():
        (package / "src" / source).write_text(text, encoding="utf-8")


def test_a_dependency_added_or_taken_out_patches_the_graph(
    run_cli: Any, tmp_path: Path, taken: list[str]
) -> None:
    """Two packages no launch file starts, one subscribing to the other's topic in
    another case, and serving a service named after the other's ``.srv`` type: once
    it depends on the other, they are meant to run together (RN401, ``Graph.can_meet``)
    and it can use that type (RN204, a per-file finding): the graph of the last build is
    patched, its packages as they are now; taken out again, the findings are gone."""
    root = tmp_path / "ws"
    _dock_package(root, "dock_driver", {"dock_driver.cpp": DOCK_DRIVER})
    (root / "src/dock_driver/srv").mkdir()
    (root / "src/dock_driver/srv/ResetOdometry.srv").write_text("---\nbool success\n")
    _dock_package(root, "dock_panel", {"dock_panel.cpp": DOCK_PANEL, "reset.cpp": DOCK_RESET})
    header = root / "src/dock_panel/include/dock_panel/reset.hpp"
    header.parent.mkdir(parents=True)
    header.write_text(DOCK_RESET_HEADER, encoding="utf-8")
    manifest = root / "src/dock_panel/package.xml"
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, root, cache)
    assert cached == fresh
    assert json.loads(fresh)["findings"] == []
    depend = "<buildtool_depend>ament_cmake</buildtool_depend>"
    panel = root / "src/dock_panel/src/dock_panel.cpp"
    together = ["RN204", "RN401", "RN401"]
    for path, old, new, codes, how in [
        (
            manifest,
            depend,
            f"{depend}\n  <exec_depend>dock_driver</exec_depend>",
            together,
            "patch",
        ),
        (manifest, "exec_depend>dock_driver</exec", "exec_depend>std_srvs</exec", [], "patch"),
        # A release, then the first dependency again in other words: runs made before.
        (manifest, "<version>0.1.0</version>", "<version>0.2.0</version>", [], "stored"),
        (
            manifest,
            "<exec_depend>std_srvs</exec_depend>",
            "<depend>dock_driver</depend>",
            together,
            "stored",
        ),
        # Code edited since: the graph built before the dependency, patched with both.
        (panel, '"Dock_State"', '"DOCK_STATE"', together, "patch"),
        (manifest, "  <depend>dock_driver</depend>\n", "", [], "patch"),
    ]:
        taken.clear()
        edit(path, old, new)
        cached, fresh = outputs(run_cli, root, cache)
        assert cached == fresh, (old, new)
        assert sorted(f["code"] for f in json.loads(fresh)["findings"]) == codes, fresh
        assert taken == [*([] if how == "stored" else [how]), "build"], (old, new)


PROBE = """#include <rclcpp/rclcpp.hpp>
#include <std_msgs/msg/float64.hpp>

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("probe");
  auto rate = node->get_parameter("probe_rate").as_double();
  auto reading = node->create_publisher<std_msgs::msg::Float64>("probe_reading", 10);
  rclcpp::spin(node);
  rclcpp::shutdown();
  return 0;
}
"""
RELAY = (
    PROBE.replace('"probe"', '"relay"')
    .replace('  auto rate = node->get_parameter("probe_rate").as_double();\n', "")
    .replace('"probe_reading"', '"relayed"')
)
PROBE_LAUNCH = """<launch>
  <node pkg="relay_pkg" exec="relay" name="relay"/>
</launch>
"""


def test_a_kept_patch_keeps_the_parameters_of_code_moved_since_where_they_are(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A line put above the probe's code moves its undeclared read (RN407, replayed);
    the relay's topic renamed is patched, and kept as the next runs' graph
    (``REBASE_EDITS`` of one): the probe's code parameters it keeps are where they are
    now (``patch.moved_code_parameters``), so a launch file that starts the probe
    afterwards, which takes them from there, reports the read where it is."""
    monkeypatch.setattr(graph_patch, "REBASE_EDITS", 1)
    root = tmp_path / "ws"
    for name, executable, source in (("probe_pkg", "probe", PROBE), ("relay_pkg", "relay", RELAY)):
        package = root / "src" / name
        (package / "src").mkdir(parents=True)
        (package / "package.xml").write_text(AMENT_PACKAGE.format(name=name), encoding="utf-8")
        (package / "CMakeLists.txt").write_text(
            f"cmake_minimum_required(VERSION 3.8)\nproject({name})\n"
            "find_package(ament_cmake REQUIRED)\nfind_package(rclcpp REQUIRED)\n"
            f"add_executable({executable} src/{executable}.cpp)\nament_package()\n",
            encoding="utf-8",
        )
        (package / "src" / f"{executable}.cpp").write_text(source, encoding="utf-8")
    launch = root / "src/probe_pkg/launch/probe.launch.xml"
    launch.parent.mkdir()
    launch.write_text(PROBE_LAUNCH, encoding="utf-8")
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, root, cache)
    assert cached == fresh
    steps = [
        (root / "src/probe_pkg/src/probe.cpp", "#include", "// Probe.\n#include"),
        (root / "src/relay_pkg/src/relay.cpp", '"relayed"', '"relayed_out"'),
        (launch, "</launch>", '  <node pkg="probe_pkg" exec="probe" name="probe"/>\n</launch>'),
    ]
    for path, old, new in steps:
        edit(path, old, new)
        cached, fresh = outputs(run_cli, root, cache)
        assert cached == fresh, path
    assert [(f["code"], f["line"]) for f in json.loads(fresh)["findings"]] == [("RN407", 9)]


def test_a_file_checked_again_resolves_its_names_from_its_package_s_headers(
    run_cli: Any, workspace: Path, tmp_path: Path, taken: list[str]
) -> None:
    """A file taking another file's constant, whose graph findings an edit of another
    file changes, is checked again with the patch (``_GraphPatch``'s ``again``): its
    names resolved from its package's headers, as a run without a cache resolves them.
    They were resolved from the few files the patch took: the RN203 of the constant's
    value, which no edit touched, was lost."""
    change(workspace / TOPICS, None, TOPICS_HEADER.replace('"dock_status"', '"DockStatus"'))
    change(workspace / STATUS_SOURCE, None, STATUS_NODE)
    subscription = (
        "    status_sub_ = create_subscription<std_msgs::msg::Bool>(\n"
        '      "OtherStatus", 10, [](std_msgs::msg::Bool::SharedPtr) {});\n'
        "    pose_pub_ ="
    )
    change(workspace / MONITOR, "    pose_pub_ =", subscription)
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, workspace, cache)
    assert cached == fresh
    # The monitor subscribes to the node's topic now, as another type (RN403 in both).
    change(workspace / MONITOR, '"OtherStatus"', '"DockStatus"')
    taken.clear()
    cached, fresh = outputs(run_cli, workspace, cache)
    assert taken == ["patch", "build"]
    assert cached == fresh
    codes = [f["code"] for f in json.loads(cached)["findings"] if f["path"] == STATUS_SOURCE]
    assert codes == ["RN203", "RN403"]


@pytest.mark.usefixtures("old_tree")
def test_a_base_class_that_stops_declaring_endpoints_is_followed_after_an_edit(
    run_cli: Any, tmp_path: Path, taken: list[str]
) -> None:
    """Whether the base class's code of another package declares endpoints decides; an
    edit that flips it gathers again the code spanning its package (``patch.edits_of``'s
    ``flipping``, ``parameter_patch``): the run after it patches the last graph and
    prints what a run without a cache prints, each time."""
    root = tmp_path / "ws"
    launch = ground_filter(root, own_base=False)
    pointcloud_filters(root)
    cache = tmp_path / "cache"

    def judged() -> list[tuple[str, int]]:
        cached, fresh = outputs(run_cli, root, cache)
        assert cached == fresh
        found = json.loads(cached)["findings"]
        return sorted((f["path"], f["line"]) for f in found if f["code"] == "RN404")

    assert judged() == []
    filter_cpp = root / "src/pointcloud_filters/src/filter.cpp"
    publish = 'pub_output_ = create_publisher<sensor_msgs::msg::PointCloud2>("output", 10);'
    subscribe = (
        "sub_input_ = create_subscription<sensor_msgs::msg::PointCloud2>(\n"
        '    "input", 10, [this](const sensor_msgs::msg::PointCloud2 & msg) { filter(msg); });'
    )
    edit(filter_cpp, f"{publish}\n  {subscribe}", "(void)name;")
    assert judged() == [(launch, 3), (launch, 4), (launch, 5)]
    # back, a comment beside (else the first run's stored result serves it)
    edit(filter_cpp, "(void)name;", f"// Both again.\n  {publish}\n  {subscribe}")
    assert judged() == []
    # each cached run, then its run without a cache (built)
    assert taken == ["build", "build", "patch", "build", "patch", "build"]


SCALER = """#include <rclcpp/rclcpp.hpp>
#include <std_msgs/msg/float64.hpp>

#include "scale_pkg/filter.hpp"

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("scaler");
  auto gain = node->declare_parameter("gain", 1.0);
  auto scaled = node->create_publisher<std_msgs::msg::Float64>("scaled", 10);
  rclcpp::spin(node);
  rclcpp::shutdown();
  return 0;
}
"""
FILTER_HEADER = "#pragma once\n\nclass Filter\n{\npublic:\n  int scale() const;\n};\n"
FILTER = '#include "scale_pkg/filter.hpp"\n\nint Filter::scale() const { return 2; }\n'


def test_a_source_moved_while_the_replay_stood_is_not_followed_by_a_later_patch(
    run_cli: Any, tmp_path: Path, taken: list[str]
) -> None:
    """The scaler includes ``filter.hpp``, whose implementation ``filter.cpp`` (a library
    source a glob compiles, with no ROS code: its facts say nothing) is followed as the
    node's code. Moved to ``moved_filter.cpp``, the last run's findings stand (``shifts``)
    and the kept graph's lookups still name ``filter.cpp``; a parameter declared in the
    scaler then gathers the node's parameters again over them: the moved file is not the
    run's, and is not followed (it stopped that run with an internal error, a
    ``KeyError``, found by ``bench/edits.py`` on moveit2's ``message_checks.cpp``)."""
    root = tmp_path / "ws"
    package = root / "src/scale_pkg"
    (package / "src/lib").mkdir(parents=True)
    (package / "include/scale_pkg").mkdir(parents=True)
    (package / "package.xml").write_text(AMENT_PACKAGE.format(name="scale_pkg"), "utf-8")
    (package / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.8)\nproject(scale_pkg)\n"
        "find_package(ament_cmake REQUIRED)\nfind_package(rclcpp REQUIRED)\n"
        "file(GLOB FILTER_SOURCES src/lib/*.cpp)\nadd_library(filter ${FILTER_SOURCES})\n"
        "add_executable(scaler src/scaler.cpp)\n"
        "target_link_libraries(scaler filter)\nament_package()\n",
        encoding="utf-8",
    )
    (package / "include/scale_pkg/filter.hpp").write_text(FILTER_HEADER, encoding="utf-8")
    (package / "src/lib/filter.cpp").write_text(FILTER, encoding="utf-8")
    scaler = package / "src/scaler.cpp"
    scaler.write_text(SCALER, encoding="utf-8")
    cache = tmp_path / "cache"
    cached, fresh = outputs(run_cli, root, cache)
    assert cached == fresh
    taken.clear()
    (package / "src/lib/filter.cpp").rename(package / "src/lib/moved_filter.cpp")
    cached, fresh = outputs(run_cli, root, cache)
    assert cached == fresh
    assert taken == ["replay", "build"]
    taken.clear()
    edit(
        scaler,
        "  auto scaled",
        '  auto offset = node->declare_parameter("offset", 0.0);\n  auto scaled',
    )
    cached, fresh = outputs(run_cli, root, cache)
    assert cached == fresh
    assert taken == ["patch", "build"]
