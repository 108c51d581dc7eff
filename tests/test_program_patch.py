"""A graph patched after a node was added to a package is the graph a build gives
(``workspace.program_patch``, issue 30): each step adds a source, an executable to a
build file or both, as a developer adds a node (a roscpp node and its
``add_executable``; a script a launch file finds by its name; an rclpy node no launch
file starts; a source no build compiles), or makes code start or stop declaring
endpoints; the last build's graph with the package's programs made again, the trees
that start them walked again (``launch_patch``) and the parameters of its code gathered
again (``parameter_patch``) must equal the graph built from every file's facts, and the
parts too (a patched run may keep them as a build's). An edit that reaches past the
package is refused."""

from __future__ import annotations

import posixpath
from itertools import pairwise
from pathlib import Path

import pytest
from conftest import ExampleCopy, assert_patched

from roslint_names.gather import extract_file
from roslint_names.model import FileFacts, Generation, Language
from roslint_names.workspace.build import _TestFiles
from roslint_names.workspace.built import BuiltSources
from roslint_names.workspace.graph import Graph
from roslint_names.workspace.index import CODE_LANGUAGES, PackageFiles, WorkspaceIndex
from roslint_names.workspace.launch_parts import CodeParameterParts, LaunchParts
from roslint_names.workspace.launch_patch import LazyFacts, launch_edit, launch_patched
from roslint_names.workspace.parameter_patch import parameters_patched
from roslint_names.workspace.patch import edits_of
from roslint_names.workspace.patch import patched as patch_graph
from roslint_names.workspace.program_patch import program_edit, programs_anew

CMAKE = "src/turtle_bringup/CMakeLists.txt"
BASE = "src/turtle_bringup/launch/base.launch"
FILTER = "src/turtle_bringup/src/odom_filter.cpp"
FILTER_MATH = "src/turtle_bringup/src/odom_filter_math.cpp"
IMU_RELAY = "src/turtle_bringup/src/imu_relay.cpp"
PROBE = "src/turtle_bringup/src/probe_node.cpp"
HEADING = "src/turtle_bringup/scripts/heading_logger.py"
LEGACY = "src/turtle_bringup/src/legacy_driver.cpp"
DOCK_STATUS = "src/fleet_bringup/fleet_bringup/dock_status.py"
DOCK_PROBE = "src/fleet_bringup/src/dock_probe.cpp"

ODOM_FILTER = """// Smooths the odometry the base publishes before the planners read it.
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

class OdomFilter
{
public:
  OdomFilter() : private_nh_("~")
  {
    private_nh_.param("alpha", alpha_, 0.2);
    odom_sub_ = nh_.subscribe("odom", 10, &OdomFilter::odomCallback, this);
    filtered_pub_ = nh_.advertise<nav_msgs::Odometry>("odom_filtered", 10);
  }

private:
  void odomCallback(const nav_msgs::Odometry::ConstPtr & odom)
  {
    filtered_pub_.publish(*odom);
  }

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  ros::Subscriber odom_sub_;
  ros::Publisher filtered_pub_;
  double alpha_;
};

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "odom_filter");
  OdomFilter filter;
  ros::spin();
  return 0;
}
"""

FILTER_HELPER = """// The filter's arithmetic, apart from its topics.
#include <ros/ros.h>

double filter_gain()
{
  double gain = 1.0;
  ros::param::get("~gain", gain);
  return gain;
}
"""

RELAY_NODE = """// Republishes the IMU under the name the localization expects.
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>

ros::Publisher relayed;

void relay(const sensor_msgs::Imu::ConstPtr & imu) { relayed.publish(*imu); }

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "imu_relay");
  ros::NodeHandle nh;
  relayed = nh.advertise<sensor_msgs::Imu>("imu_relayed", 10);
  ros::Subscriber sub = nh.subscribe("imu", 10, relay);
  ros::spin();
  return 0;
}
"""

PROBE_NODE = """// Reports what the base sees, for the bench.
#include <ros/ros.h>
#include <std_msgs/String.h>

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "probe");
  ros::NodeHandle nh;
  ros::Publisher status = nh.advertise<std_msgs::String>("probe/status", 1);
  ros::spin();
  return 0;
}
"""

HEADING_LOGGER = """#!/usr/bin/env python
# Logs the heading the odometry reports.
import rospy
from nav_msgs.msg import Odometry


def log_heading(odom):
    rospy.loginfo("heading %f", odom.pose.pose.orientation.z)


if __name__ == "__main__":
    rospy.init_node("heading_logger")
    rospy.Subscriber("odom", Odometry, log_heading)
    rospy.spin()
"""

LEGACY_DRIVER = """// The driver of the first base, kept for reference; no target builds it.
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "legacy_driver");
  ros::NodeHandle nh;
  ros::Publisher wheels = nh.advertise<geometry_msgs::Twist>("wheel_cmd", 1);
  ros::spin();
  return 0;
}
"""

DOCK_STATUS_NODE = """# Tells the fleet whether the dock is free.
import rclpy
from rclpy.node import Node
from std_msgs.msg import Bool


class DockStatus(Node):
    def __init__(self):
        super().__init__("dock_status")
        self.declare_parameter("dock_id", "dock_1")
        self.publisher = self.create_publisher(Bool, "dock/free", 1)


def main():
    rclpy.init()
    rclpy.spin(DockStatus())


if __name__ == "__main__":
    main()
"""

FILTER_ENDPOINTS = """    odom_sub_ = nh_.subscribe("odom", 10, &OdomFilter::odomCallback, this);
    filtered_pub_ = nh_.advertise<nav_msgs::Odometry>("odom_filtered", 10);
"""
DOCK_PUBLISHER = '        self.publisher = self.create_publisher(Bool, "dock/free", 1)\n'
DOCK_LOG = '        self.get_logger().info("dock status up")\n'

_Edit = tuple[str, str, str]  # a file, text in it, the text put in its place ("": appended)
# Each step: the files added (None: removed), then the edits; patched from the step
# before's build.
PATCHED: list[tuple[dict[str, str | None], list[_Edit]]] = [
    # A roscpp node and its executable: no launch file starts it yet.
    (
        {FILTER: ODOM_FILTER},
        [(CMAKE, "", "\nadd_executable(odom_filter src/odom_filter.cpp)\n")],
    ),
    # A launch file starts a program no build makes yet; then its source and executable.
    (
        {},
        [
            (
                BASE,
                "</launch>",
                '  <node name="imu_relay" pkg="turtle_bringup" type="imu_relay">\n'
                '    <remap from="imu" to="imu/data"/>\n'
                "  </node>\n</launch>",
            )
        ],
    ),
    (
        {IMU_RELAY: RELAY_NODE},
        [(CMAKE, "", "add_executable(imu_relay src/imu_relay.cpp)\n")],
    ),
    # A second source of a target, which reads a parameter.
    (
        {FILTER_MATH: FILTER_HELPER},
        [
            (
                CMAKE,
                "add_executable(odom_filter src/odom_filter.cpp)",
                "add_executable(odom_filter src/odom_filter.cpp src/odom_filter_math.cpp)",
            )
        ],
    ),
    # An executable whose source is not there yet; then the source.
    ({}, [(CMAKE, "", "add_executable(probe_node src/probe_node.cpp)\n")]),
    ({PROBE: PROBE_NODE}, []),
    # A script a launch file starts by its name (rosrun's rule), no build file names it.
    (
        {},
        [
            (
                BASE,
                "</launch>",
                '  <node name="heading_logger" pkg="turtle_bringup" type="heading_logger.py"/>\n'
                "</launch>",
            )
        ],
    ),
    ({HEADING: HEADING_LOGGER}, []),
    # A source no build compiles: it joins no node.
    ({LEGACY: LEGACY_DRIVER}, []),
    # An rclpy node of a package without a build file that names it: a program of its own.
    ({DOCK_STATUS: DOCK_STATUS_NODE}, []),
    # Code that stops declaring endpoints, then starts again (``patch.edits_of``'s
    # flipping): the filter's program, which no launch file starts, and the rclpy node's
    # program of its own go, then come back.
    ({}, [(FILTER, FILTER_ENDPOINTS, "")]),
    ({}, [(DOCK_STATUS, DOCK_PUBLISHER, DOCK_LOG)]),
    ({}, [(FILTER, "  }\n\nprivate:", f"{FILTER_ENDPOINTS}  }}\n\nprivate:")]),
    ({}, [(DOCK_STATUS, DOCK_LOG, DOCK_PUBLISHER)]),
    # Taken out again (``None``: the file removed): the rclpy node; the filter's second
    # source and its place in the target; the script a launch file starts by name; the
    # relay and its executable, whose node a launch file starts (it runs no code now).
    ({DOCK_STATUS: None}, []),
    (
        {FILTER_MATH: None},
        [
            (
                CMAKE,
                "add_executable(odom_filter src/odom_filter.cpp src/odom_filter_math.cpp)",
                "add_executable(odom_filter src/odom_filter.cpp)",
            )
        ],
    ),
    ({HEADING: None}, []),
    ({IMU_RELAY: None}, [(CMAKE, "add_executable(imu_relay src/imu_relay.cpp)\n", "")]),
]

# Edits that reach past the package (each from the examples' build): refused.
REFUSED: list[tuple[dict[str, str | None], list[_Edit]]] = [
    # A source added to a package that another package's target names (fleet_bringup
    # holds no build file: turtle_bringup's is what names it).
    (
        {DOCK_PROBE: PROBE_NODE},
        [(CMAKE, "", "add_executable(dock_probe ../fleet_bringup/src/dock_probe.cpp)\n")],
    ),
    # A target naming another package's source beside one of its own.
    (
        {},
        [
            (
                CMAKE,
                "add_executable(odom_relay src/odom_relay.cpp)",
                "add_executable(odom_relay src/odom_relay.cpp"
                " ../fleet_bringup/src/dock_manager.cpp)",
            )
        ],
    ),
]


class _Workspace(ExampleCopy):
    def built(self) -> tuple[Graph, LaunchParts, CodeParameterParts, dict[str, FileFacts]]:
        built: tuple[Graph, LaunchParts, CodeParameterParts, dict[str, FileFacts]]
        built = self.built_parts()
        return built

    def step(self, files: dict[str, str | None], edits: list[_Edit]) -> None:
        self.add({path: text for path, text in files.items() if text is not None})
        for path, text in files.items():
            if text is None:
                (self.root / path).unlink()
        for edit in edits:
            self.edit(*edit)

    def patched(
        self,
        built: tuple[Graph, LaunchParts, CodeParameterParts, dict[str, FileFacts]],
        now: dict[str, FileFacts],
    ) -> tuple[Graph, LaunchParts, CodeParameterParts] | None:
        """What ``graph_patch.GraphPatch`` does for these edits."""
        graph, parts, code, before = built
        added = sorted(now.keys() - before.keys())
        removed = sorted(before.keys() - now.keys())
        changed = [path for path in before if path in now and before[path] != now[path]]
        launch = [path for path in changed if launch_edit(before[path], now[path])]
        build = [path for path in changed if program_edit(before[path], now[path])]
        edited_code = [path for path in changed if now[path].language in CODE_LANGUAGES]
        # Code edits, as ``graph_patch.GraphPatch`` takes them: those that start or stop
        # declaring endpoints make their packages' programs again (``flipping``).
        declaring: set[str] = set()
        flipping: set[str] = set()
        edits = edits_of(
            [(path, before[path], now[path]) for path in edited_code], declaring, set(), flipping
        )
        if edits is None or set(changed) - set(launch) - set(build) - set(edited_code):
            return None
        facts = LazyFacts(now.keys(), now.get)
        index = WorkspaceIndex.restored(facts, self.packages, parts.executables)
        added_code = [path for path in added if now[path].language in CODE_LANGUAGES]
        removed_code = [path for path in removed if before[path].language in CODE_LANGUAGES]
        owners = {
            index.package_of(path) for path in (*build, *added_code, *removed_code, *flipping)
        }
        # The packages of the build files naming a source added or removed (as
        # ``GraphPatch._builders`` finds them)
        owners.update(
            index.package_of(builder)
            for facts in (before, now)
            for builder, found in facts.items()
            for path in (*added_code, *removed_code)
            if _names(found, path)
        )
        packages = sorted(
            (package for package in owners if package is not None), key=lambda p: p.directory
        )
        compiled = BuiltSources()
        for path, found in now.items():
            if found.compiled is not None or found.included_sources:
                owner = index.package_of(path)
                compiled.add(found, None if owner is None else owner.directory)
        programs = programs_anew(
            parts.programs,
            parts.executables,
            parts.unbuilt,
            index=index,
            packages=packages,
            language_of=lambda path: now[path].language,
            then={path: before[path] for path in build},
            added=added,
            removed=removed,
            flipped=flipping,
            compiled=compiled,
            is_test=_TestFiles(index, {}),
            named_elsewhere=lambda path, own: any(
                builder not in own and _names(found, path)
                for facts in (before, now)
                for builder, found in facts.items()
            ),
        )
        if programs is None:
            return None
        assert self.specialiser is not None
        walked = launch_patched(
            graph,
            parts,
            launch,
            facts=facts,
            packages=self.packages,
            specialise=self.specialiser,
            prepare=self.specialiser.prepare,
            programs=programs,
        )
        if walked is None:
            return None
        graph = patch_graph(
            walked[0],
            edits,
            now.get,
            lambda: PackageFiles(sorted(now), self.packages),
            declaring=bool(declaring),
        )
        if graph is None:
            return None
        edited = {path: (before[path], now[path]) for path in edits}
        edited.update({path: (_empty(now[path]), now[path]) for path in added_code})
        edited.update({path: (before[path], _empty(before[path])) for path in removed_code})
        return parameters_patched(
            graph,
            walked[1],
            code,
            edited,
            facts=facts,
            packages=self.packages,
            programs=programs,
            added=added_code,
            removed=removed_code,
        )


def _empty(facts: FileFacts) -> FileFacts:
    return FileFacts(facts.path, facts.language, facts.generation)


def _names(build_file: FileFacts, path: str) -> bool:
    """Whether a build file's executables name ``path`` as a source."""
    directory = posixpath.dirname(build_file.path)
    return any(
        posixpath.normpath(posixpath.join(directory, source)) == path
        for executable in build_file.executables
        for source in executable.sources
    )


_Parts = tuple[Graph, LaunchParts, CodeParameterParts]
_Step = tuple[str, _Parts, _Parts | None]


@pytest.fixture(scope="module")
def steps(tmp_path_factory: pytest.TempPathFactory) -> list[_Step]:
    """Each step: what it added, the graph and parts built after it, and those patched."""
    workspace = _Workspace(tmp_path_factory.mktemp("program_patch") / "ws")
    built = workspace.built()
    found: list[_Step] = []
    for added, edits in PATCHED:
        workspace.step(added, edits)
        now = workspace.built()
        patched = workspace.patched(built, now[3])
        found.append((", ".join([*added, *(path for path, _, _ in edits)]), now[:3], patched))
        built = now
    return found


@pytest.mark.parametrize("step", range(len(PATCHED)))
def test_a_patched_graph_and_its_parts_are_the_built_ones(steps: list[_Step], step: int) -> None:
    assert_patched(steps, step)


def test_the_steps_change_the_graph(steps: list[_Step]) -> None:
    """Each step changes the graph (a step that changed nothing would test nothing) but
    the executable whose source is not there yet (the build keeps no program of no
    source). The source no build compiles joins no node, but its literals are its
    package's (``Graph.mentions``: a node there has remaps of its own)."""
    graphs = [built[0] for _, built, _ in steps]
    unchanged = [
        steps[at + 1][0] for at, (one, other) in enumerate(pairwise(graphs)) if one == other
    ]
    assert unchanged == [CMAKE]


@pytest.mark.parametrize("step", range(len(REFUSED)))
def test_an_edit_past_the_package_is_refused(tmp_path: Path, step: int) -> None:
    workspace = _Workspace(tmp_path / "ws")
    built = workspace.built()
    workspace.step(*REFUSED[step])
    now = workspace.built()
    assert now[0] != built[0]
    assert workspace.patched(built, now[3]) is None


def test_a_source_another_package_s_build_file_names_is_patched(tmp_path: Path) -> None:
    """turtle_bringup's build compiles a source of fleet_bringup (which has no build
    file) before it is there: the source added, then taken out, makes the programs of
    both packages again, the graph and parts a build's."""
    workspace = _Workspace(tmp_path / "ws")
    workspace.edit(CMAKE, "", "add_executable(dock_probe ../fleet_bringup/src/dock_probe.cpp)\n")
    built = workspace.built()
    for step in ({DOCK_PROBE: PROBE_NODE}, {DOCK_PROBE: None}):
        workspace.step(step, [])
        now = workspace.built()
        assert now[0] != built[0]
        assert workspace.patched(built, now[3]) == now[:3], step
        built = now


WATCHDOG = "src/turtle_bringup/src/watchdog.cpp"
# A node of a program not built yet, started under a name the includer hands over,
# with a parameter file: it keeps what its code may take of the file (none yet).
WATCHDOG_LAUNCH = {
    "src/turtle_bringup/launch/watchdog.launch": """<launch>
  <!-- One watchdog per base, named by the launch file that includes this one. -->
  <arg name="watchdog_name"/>
  <node name="$(arg watchdog_name)" pkg="turtle_bringup" type="watchdog">
    <rosparam command="load" file="$(find turtle_bringup)/config/watchdog.yaml"/>
  </node>
</launch>
""",
    "src/turtle_bringup/config/watchdog.yaml": "timeout: 2.0\nodom_topic: odom\n",
}
WATCHDOG_NODE = """// Stops the base when its odometry goes quiet.
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

int main(int argc, char ** argv)
{
  ros::init(argc, argv, "watchdog");
  ros::NodeHandle private_nh("~");
  double timeout = private_nh.param("timeout", 2.0);
  ros::spin();
  return 0;
}
"""


def test_a_node_of_unknown_name_takes_the_parameters_of_its_program_made_anew(
    tmp_path: Path,
) -> None:
    """The program of a node handed a parameter file under a name the linter does not
    know is added, then taken out: what the node may take of the file is its code's
    parameters, gathered by the parameter patch (``parameter_patch._receivers``), where
    the graph was built before."""
    workspace = _Workspace(tmp_path / "ws")
    workspace.add(WATCHDOG_LAUNCH)
    built = workspace.built()
    added = (
        {WATCHDOG: WATCHDOG_NODE},
        [(CMAKE, "", "add_executable(watchdog src/watchdog.cpp)\n")],
    )
    removed = ({WATCHDOG: None}, [(CMAKE, "add_executable(watchdog src/watchdog.cpp)\n", "")])
    for files, edits in (added, removed):
        workspace.step(files, edits)
        now = workspace.built()
        assert now[0].unnamed_parameter_files != built[0].unnamed_parameter_files
        assert workspace.patched(built, now[3]) == now[:3], files
        built = now


def test_a_built_source_once_unbuilt_is_refused(tmp_path: Path) -> None:
    """The parameter tables leave out code no build compiles: a source the build had
    that a target names now changes them past what the patch follows."""
    workspace = _Workspace(tmp_path / "ws")
    workspace.add({LEGACY: LEGACY_DRIVER})
    built = workspace.built()
    workspace.edit(CMAKE, "", "add_executable(legacy_driver src/legacy_driver.cpp)\n")
    now = workspace.built()
    assert now[0] != built[0]
    assert workspace.patched(built, now[3]) is None


def _cmake(text: str) -> FileFacts:
    return extract_file(Language.CMAKE, CMAKE, text.encode(), Generation.ROS1, Generation.ROS1)


def test_a_build_file_that_builds_the_same_is_no_program_edit() -> None:
    """A line put above every target moves them, and they build what they built: no
    program is made again (``patch.build_moves`` follows it); an executable added, or a
    source added to one, is a program edit."""
    text = (ExampleCopy.EXAMPLES / CMAKE).read_text(encoding="utf-8")
    before = _cmake(text)
    moved = _cmake("find_package(tf2_ros REQUIRED)\n" + text)
    assert moved.executables != before.executables  # their places
    assert not program_edit(before, moved)
    assert program_edit(before, _cmake(text + "add_executable(probe src/probe.cpp)\n"))
    grown = text.replace("src/odom_relay.cpp", "src/odom_relay.cpp src/odom_math.cpp")
    assert program_edit(before, _cmake(grown))
