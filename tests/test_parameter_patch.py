"""A graph patched after an edit of what code declares is the graph a build gives
(``workspace.parameter_patch``, issue 30): each step edits the example workspace's code
as a developer would (a parameter declared, read, renamed or taken out, with or without
an endpoint beside it), and the last build's graph with the code patched
(``workspace.patch``) and the parameters of the code spanning the edited packages
gathered again must equal the graph built from every file's facts; an edit the patches
cannot follow is refused, never patched wrong."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from itertools import pairwise
from pathlib import Path

import pytest
from conftest import AMENT_PACKAGE, ExampleCopy, assert_patched
from hypothesis import given, settings
from hypothesis import strategies as st

from roslint_names.model import FileFacts, Generation, Language
from roslint_names.workspace.graph import Graph
from roslint_names.workspace.index import PackageFiles, WorkspaceIndex, companions, named_once
from roslint_names.workspace.launch_parts import CodeParameterParts, LaunchParts
from roslint_names.workspace.launch_patch import LazyFacts
from roslint_names.workspace.parameter_patch import parameters_patched
from roslint_names.workspace.parameters import ParameterTables, TableLookups
from roslint_names.workspace.patch import edits_of, patched

FOLLOWER = "src/fleet_bringup/fleet_bringup/waypoint_follower.py"  # ROS 2 Python
REPORTER = "src/fleet_bringup/fleet_bringup/battery_reporter.py"  # ROS 2 Python, RN406
DOCK = "src/fleet_bringup/src/dock_manager.cpp"  # ROS 2 C++, reads an undeclared name
MONITOR = "src/fleet_bringup/src/fleet_monitor.cpp"  # ROS 2 C++
RELAY = "src/turtle_bringup/src/odom_relay.cpp"  # ROS 1 C++, no launch file starts it
SQUARE = "src/turtle_bringup/scripts/draw_square.py"  # ROS 1 Python script
# A package of the steps' workspace besides the examples' (``_Workspace``): the base class
# the dock manager derives from, which declares a parameter of its own.
MANAGED = "src/fleet_core/include/fleet_core/managed_node.hpp"
# The dock manager's package: a helper that reads a parameter, and the base of the
# sensors it loads as plugins with one of them; a third package with another of them.
APPROACH = "src/fleet_bringup/include/fleet_bringup/approach.hpp"
DOCK_SENSOR = "src/fleet_bringup/include/fleet_bringup/dock_sensor.hpp"
SONAR = "src/fleet_sensors/include/fleet_sensors/sonar_dock_sensor.hpp"
EXTRA_FILES = {
    "src/fleet_core/package.xml": """<?xml version="1.0"?>
<package format="3">
  <name>fleet_core</name>
  <version>0.1.0</version>
  <description>What every node of the fleet is</description>
  <maintainer email="dev@example.com">Example Maintainer</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <export>
    <build_type>ament_cmake</build_type>
  </export>
</package>
""",
    MANAGED: """#pragma once
#include <string>

#include <rclcpp/rclcpp.hpp>

namespace fleet_core
{
class ManagedNode : public rclcpp::Node
{
public:
  explicit ManagedNode(const std::string & name) : rclcpp::Node(name)
  {
    declare_parameter("heartbeat_period", 1.0);
  }
};
}  // namespace fleet_core
""",
    APPROACH: """#pragma once
#include <rclcpp/rclcpp.hpp>

namespace fleet_bringup
{
inline double approach_speed(rclcpp::Node & node)
{
  return node.get_parameter("approach_speed").as_double();
}
}  // namespace fleet_bringup
""",
    DOCK_SENSOR: """#pragma once

namespace fleet_bringup
{
class DockSensor
{
public:
  virtual ~DockSensor() = default;
};

class LidarDockSensor : public fleet_bringup::DockSensor
{
};
}  // namespace fleet_bringup
""",
    "src/fleet_sensors/package.xml": AMENT_PACKAGE.format(name="fleet_sensors"),
    SONAR: """#pragma once
#include <fleet_bringup/dock_sensor.hpp>

namespace fleet_sensors
{
class SonarDockSensor : public fleet_bringup::DockSensor
{
};
}  // namespace fleet_sensors
""",
}
# The dock manager started under a name the launch file is handed: a node of unknown
# name keeps of its parameter file what its code may take (``UnnamedReceiver``), which
# an edit of that code changes.
RECEIVING_FILES = {
    "src/fleet_bringup/launch/docking.launch.xml": """<launch>
  <arg name="dock_name"/>
  <node pkg="fleet_bringup" exec="dock_manager" name="$(var dock_name)">
    <param from="$(find-pkg-share fleet_bringup)/config/dock.yaml"/>
  </node>
</launch>
""",
    "src/fleet_bringup/config/dock.yaml": """/**:
  ros__parameters:
    dock_frame: charging_dock
    approach_speed: 0.2
""",
}
# The edits that make the dock manager one, and the fleet monitor report through a class
# no file defines yet (before the first build).
SETUP = [
    (DOCK, "#include <rclcpp/rclcpp.hpp>", "#include <fleet_core/managed_node.hpp>"),
    (DOCK, "public rclcpp::Node", "public fleet_core::ManagedNode"),
    (DOCK, ': Node("dock_manager")', ': fleet_core::ManagedNode("dock_manager")'),
    (MONITOR, "public rclcpp::Node\n", "public rclcpp::Node, public fleet_core::Reporter\n"),
]

# (file, text before, text after); each step's graph is patched from the step before's.
PATCHED = [
    # The parameter file's settings the node dropped: one declared now (RN406 gone).
    (
        FOLLOWER,
        '        self.declare_parameter("map_frame", "map")\n',
        '        self.declare_parameter("map_frame", "map")\n'
        '        self.declare_parameter("loop_rate", 10.0)\n',
    ),
    # The declaration renamed to the name the launch file sets.
    (REPORTER, '"low_threshold"', '"low_treshold"'),
    # A read of an undeclared name fixed.
    (DOCK, 'get_parameter("dockframe")', 'get_parameter("dock_frame")'),
    # A declaration added above the others: every name below it moves.
    (
        MONITOR,
        "    map_frame_ = declare_parameter",
        '    declare_parameter<double>("publish_rate", 1.0);\n    map_frame_ = declare_parameter',
    ),
    # ROS 1: a private parameter read added and one renamed in code no launch file
    # starts (code four trees start runs twice under one name in one of them: the code
    # patch cannot tell the two apart, ``workspace.patch``); a script's read renamed.
    (
        RELAY,
        '    private_nh.param<std::string>("odom_topic", odom_topic_, "wheel/odom");\n',
        '    private_nh.param<std::string>("odom_topic", odom_topic_, "wheel/odom");\n'
        '    private_nh.param("rate", rate_, 10.0);\n',
    ),
    (RELAY, '"odom_topic"', '"input_topic"'),
    (SQUARE, "'~side'", "'~side_length'"),
    # A parameter and a service renamed in one edit: both patches.
    (
        DOCK,
        '"dock_frame", "charging_dock");\n'
        "    // Named after what it carries, not after what it does.\n"
        "    dock_service_ = create_service<std_srvs::srv::Trigger>(\n"
        '      "StartDocking"',
        '"dock_frame_id", "charging_dock");\n'
        "    // Named after what it carries, not after what it does.\n"
        "    dock_service_ = create_service<std_srvs::srv::Trigger>(\n"
        '      "start_docking"',
    ),
    # A declaration taken out.
    (FOLLOWER, '        self.declare_parameter("loop_rate", 10.0)\n', ""),
    # A declaration of the base class, another package's, renamed: the dock manager's.
    (MANAGED, '"heartbeat_period"', '"heartbeat_interval"'),
    # A header of its own package included: the parameter it reads is the node's.
    (
        DOCK,
        "#include <std_srvs/srv/trigger.hpp>\n",
        "#include <std_srvs/srv/trigger.hpp>\n\n#include <fleet_bringup/approach.hpp>\n",
    ),
    # The class the fleet monitor reports through defined in another package: its
    # declarations are the monitor's, and its bases all known (the monitor's code spans
    # none of that package's files before: found by the classes deriving from it).
    (
        MANAGED,
        "}  // namespace fleet_core\n",
        "class Reporter\n{\npublic:\n  void declare_reporting(rclcpp::Node & node)\n  {\n"
        '    node.declare_parameter("report_period", 5.0);\n  }\n};\n'
        "}  // namespace fleet_core\n",
    ),
    # A loader of sensor plugins, one of them of another package: the node's
    # declarations may hide there (plugins left open).
    (
        DOCK,
        "private:\n",
        "private:\n  pluginlib::ClassLoader<fleet_bringup::DockSensor> sensors_{\n"
        '    "fleet_bringup", "fleet_bringup::DockSensor"};\n',
    ),
    # That sensor taken out of the other package: every plugin is the package's own.
    (SONAR, "class SonarDockSensor : public fleet_bringup::DockSensor", "class SonarDockSensor"),
    # The monitor reports no more: a base taken out of its class.
    (MONITOR, ", public fleet_core::Reporter\n", "\n"),
    # A class that derives from the client library's node added to the monitor's code
    # (the growth benchmark's ``edit_class``).
    (
        MONITOR,
        "",
        "\nclass MonitorProbe : public rclcpp::Node\n{\n  void probe()\n  {\n"
        '    declare_parameter("probe_rate", 2.0);\n  }\n};\n',
    ),
]

# Edits the patches cannot follow: the graph is built.
REFUSED = [
    # A base class the linter does not know: the class is no node of the code's now (its
    # handle and its name go with it).
    (DOCK, "class DockManager : public rclcpp::Node", "class DockManager : public nav2::Node"),
]


class _Workspace(ExampleCopy):
    def built(self) -> tuple[Graph, LaunchParts, CodeParameterParts, dict[str, FileFacts]]:
        built: tuple[Graph, LaunchParts, CodeParameterParts, dict[str, FileFacts]]
        built = self.built_parts()
        return built

    def patched(
        self,
        built: tuple[Graph, LaunchParts, CodeParameterParts, dict[str, FileFacts]],
        now: dict[str, FileFacts],
        load: Callable[[str], FileFacts | None] | None = None,
    ) -> tuple[Graph, LaunchParts, CodeParameterParts] | None:
        """``load``: a file's facts for the patch (``now``'s by default)."""
        graph, parts, code, before = built
        changed = [path for path in now if before.get(path) != now[path]]
        assert changed and before.keys() == now.keys()
        declaring: set[str] = set()
        edits = edits_of([(path, before[path], now[path]) for path in changed], declaring)
        if edits is None:
            return None
        assert declaring, "no step here is the code patch's alone"
        found = patched(
            graph,
            edits,
            now.get,
            lambda: PackageFiles(list(now), self.packages),
            declaring=True,
        )
        if found is None:
            return None
        return parameters_patched(
            found,
            parts,
            code,
            {path: (before[path], now[path]) for path in changed},
            facts=LazyFacts(now.keys(), now.get if load is None else load),
            packages=self.packages,
        )


_Parts = tuple[Graph, LaunchParts, CodeParameterParts]
_Step = tuple[str, _Parts, _Parts | None]


def _steps(root: Path, extra: dict[str, str]) -> list[_Step]:
    """Each step: the file edited, the graph and the parts built after it, and those
    patched."""
    workspace = _Workspace(root)
    workspace.add(extra)
    for edit in SETUP:
        workspace.edit(*edit)
    last = workspace.built()
    found: list[_Step] = []
    for relative, old, new in PATCHED:
        workspace.edit(relative, old, new)
        now = workspace.built()
        found.append((relative, now[:3], workspace.patched(last, now[3])))
        last = now
    return found


@pytest.fixture(scope="module")
def steps(tmp_path_factory: pytest.TempPathFactory) -> list[_Step]:
    return _steps(tmp_path_factory.mktemp("parameter_patch") / "ws", EXTRA_FILES)


@pytest.fixture(scope="module")
def received_steps(tmp_path_factory: pytest.TempPathFactory) -> list[_Step]:
    """The steps where a launch file hands the dock manager a parameter file and a name
    the linter does not know."""
    root = tmp_path_factory.mktemp("parameter_patch_received") / "ws"
    return _steps(root, {**EXTRA_FILES, **RECEIVING_FILES})


@pytest.mark.parametrize("step", range(len(PATCHED)))
def test_a_patched_graph_and_its_parts_are_the_built_ones(steps: list[_Step], step: int) -> None:
    """The parts too: the parameters of each node's code, the lookups, the spans and
    the counts, which a patched run keeps as the next runs' (``engine``'s
    ``REBASE_EDITS``)."""
    assert_patched(steps, step)


@pytest.mark.parametrize("step", range(len(PATCHED)))
def test_a_node_of_unknown_name_handed_a_parameter_file_keeps_its_code_s_parameters_now(
    received_steps: list[_Step], step: int
) -> None:
    """What it may take of the file is its code's parameters as the edit left them
    (``parameter_patch._receivers``): patched, where the graph was built before."""
    assert_patched(received_steps, step)


def test_the_dock_manager_s_edits_change_what_its_parameter_file_s_receiver_takes(
    received_steps: list[_Step],
) -> None:
    graphs = [built[0] for _, built, _ in received_steps]
    changed = {
        received_steps[step][0]
        for step, (before, now) in enumerate(pairwise(graphs), start=1)
        if before.unnamed_parameter_files != now.unnamed_parameter_files
    }
    assert graphs[0].unnamed_parameter_files
    assert {DOCK, MANAGED} <= changed


def test_the_steps_change_what_code_declares(steps: list[_Step]) -> None:
    """Each step's graph differs from the one before in its parameters: a step whose edit
    changed nothing there would test nothing."""
    graphs = [built[0] for _, built, _ in steps]
    for step, (before, now) in enumerate(pairwise(graphs), start=1):
        assert _parameters(before) != _parameters(now), f"step {step}"


def _parameters(graph: Graph) -> tuple[object, ...]:
    nodes = [(node.name, node.code_parameters, node.parameters) for node in graph.nodes]
    return tuple(nodes), graph.parameter_declarations


@pytest.mark.parametrize("step", range(len(REFUSED)))
def test_an_edit_the_patches_cannot_follow_is_refused(tmp_path: Path, step: int) -> None:
    workspace = _Workspace(tmp_path / "ws")
    last = workspace.built()
    workspace.edit(*REFUSED[step])
    now = workspace.built()
    assert now[0] != last[0]
    assert workspace.patched(last, now[3]) is None


def test_a_file_whose_facts_cannot_be_loaded_refuses_the_patch(tmp_path: Path) -> None:
    """A file of the edited package the patch cannot load (one taking another file's
    constant: only the whole run resolves it, ``graph_patch.GraphPatch``): the graph is
    built, never an internal error (a node renamed in moveit_ros_planning raised one)."""
    workspace = _Workspace(tmp_path / "ws")
    workspace.add(EXTRA_FILES)
    for edit in SETUP:
        workspace.edit(*edit)
    last = workspace.built()
    workspace.edit(*PATCHED[0])
    now = workspace.built()[3]
    edited = PATCHED[0][0]
    assert workspace.patched(last, now) is not None
    assert workspace.patched(last, now, lambda path: now[path] if path == edited else None) is None


# A package of the fleet's first nodes, with a class of the name the dock manager
# derives from (``SETUP``): a package depending on neither means both.
LEGACY_FILES = {
    "src/fleet_legacy/package.xml": AMENT_PACKAGE.format(name="fleet_legacy"),
    "src/fleet_legacy/include/fleet_legacy/managed_node.hpp": """#pragma once
#include <string>

#include <rclcpp/rclcpp.hpp>

namespace fleet_legacy
{
class ManagedNode : public rclcpp::Node
{
public:
  explicit ManagedNode(const std::string & name) : rclcpp::Node(name)
  {
    declare_parameter("watchdog_period", 0.5);
  }
};
}  // namespace fleet_legacy
""",
}


def test_a_dependency_added_gathers_the_parameters_of_its_package_s_code_again(
    tmp_path: Path,
) -> None:
    """The dock manager derives from a ``ManagedNode`` two packages define; its package
    depending on neither, its code spans both (``ParameterSets._defined``). A dependency
    on one of them changes no file's facts, yet the dock manager's parameters: the
    build's graph, its companions made anew and the parameters of the code spanning that
    package gathered again under the packages as they are now, is the graph built."""
    workspace = _Workspace(tmp_path / "ws")
    workspace.add({**EXTRA_FILES, **LEGACY_FILES})
    for edit in SETUP:
        workspace.edit(*edit)
    graph, parts, code, facts = workspace.built()
    workspace.edit(
        "src/fleet_bringup/package.xml",
        "<exec_depend>nav2_amcl</exec_depend>",
        "<exec_depend>nav2_amcl</exec_depend>\n  <exec_depend>fleet_core</exec_depend>",
    )
    *built, now = workspace.built()
    assert now == facts and _parameters(built[0]) != _parameters(graph)
    found = parameters_patched(
        replace(graph, companions=companions(named_once(workspace.packages))),
        parts,
        code,
        {},
        facts=LazyFacts(facts.keys(), facts.get),
        packages=workspace.packages,
        depending={"fleet_bringup"},
    )
    assert found == tuple(built)


# Files for ``with_classes``' property: a few paths, class and base names, some of them
# qualified, plugin loaders; each file's classes in the order written.
_PATHS = [f"src/pkg_{p}/include/pkg_{p}/{n}.hpp" for p in "ab" for n in ("base", "node", "z")]
_CLASS_NAMES = st.sampled_from(["Base", "Node", "Sensor", "Probe"])
_BASES = st.sampled_from(
    ["Base", "a::Base", "rclcpp::Node", "Node", "Sensor", "b::Sensor", "Probe"]
)
_CLASSES = st.lists(st.tuples(_CLASS_NAMES, st.lists(_BASES, max_size=2).map(tuple)), max_size=3)
_LOADERS = st.lists(st.sampled_from(["a::Sensor", "Base", ""]), max_size=1)


def _class_facts(
    path: str, classes: list[tuple[str, tuple[str, ...]]], loaders: list[str]
) -> FileFacts:
    return FileFacts(
        path,
        Language.CPP,
        Generation.ROS2,
        class_bases=tuple(classes),
        plugin_loaders=tuple(loaders),
    )


@settings(max_examples=300, deadline=None)
@given(
    st.fixed_dictionaries({path: st.tuples(_CLASSES, _LOADERS) for path in _PATHS}),
    st.lists(st.tuples(st.sampled_from(_PATHS), _CLASSES, _LOADERS), min_size=1, max_size=3),
    st.sets(st.sampled_from(_PATHS), max_size=2),
)
def test_classes_edited_in_the_lookups_are_the_lookups_made_anew(
    files: dict[str, tuple[list[tuple[str, tuple[str, ...]]], list[str]]],
    edits: list[tuple[str, list[tuple[str, tuple[str, ...]]], list[str]]],
    excluded: set[str],
) -> None:
    """``TableLookups.with_classes`` over a build's lookups gives the lookups made from
    the edited files' facts, entries in the same order (a memory's builds take it up
    edit after edit); and reports every file whose classes' lookups changed beneath it
    (``deriving``, ``loading``)."""
    before = {path: _class_facts(path, *found) for path, found in files.items()}
    now = dict(before)
    for path, classes, loaders in edits:
        now[path] = _class_facts(path, classes, loaders)

    def lookups(facts: dict[str, FileFacts]) -> TableLookups:
        index = WorkspaceIndex(facts.values(), [])
        return ParameterTables.of(index, excluded.__contains__).lookups

    built = lookups(before)
    edited = [(path, before[path], now[path]) for path in now if now[path] != before[path]]
    found, reached = built.with_classes(edited, excluded.__contains__)
    made = lookups(now)
    assert found == replace(made, by_name=found.by_name)  # its classes and loaders alike
    defined, bases = (
        {
            key
            for key in getattr(built, table).keys() | getattr(made, table).keys()
            if getattr(built, table).get(key) != getattr(made, table).get(key)
        }
        for table in ("classes", "derived")
    )
    assert reached == {
        *(path for key in defined for path in built.deriving.get(key, ())),
        *(path for key in defined | bases for path in built.loading.get(key, ())),
    }
