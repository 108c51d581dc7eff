"""A graph built with the last build's memory is the graph built without it.

The language server builds the graph again after every edit with one ``GraphMemory``
(``workspace.memory``); each step here edits the example workspace as a developer
would (code, launch files, parameter files, build files; files added, renamed and
deleted), then builds with the memory of every step before and without any memory, and
the two graphs must be equal.
"""

from __future__ import annotations

import random
import shutil
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import pytest

from roslint_names.config import load_settings
from roslint_names.discover import discover
from roslint_names.engine import RunOptions, lint, lintable, workspace_packages
from roslint_names.gather import Specialiser, extract_batch
from roslint_names.generation import DEFAULT_GENERATION, PackageGenerations
from roslint_names.model import FileFacts
from roslint_names.registry import load_registry
from roslint_names.workers import Dispatcher
from roslint_names.workspace.build import _Sorting, _unique, build
from roslint_names.workspace.graph import Graph
from roslint_names.workspace.memory import GraphMemory

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
TURTLE = "src/turtle_bringup"
FLEET = "src/fleet_bringup"


class _Workspace:
    """The example workspace in a temporary directory, its facts kept from step to step
    as the language server keeps them: a file whose facts did not change keeps its
    object."""

    def __init__(self, root: Path) -> None:
        shutil.copytree(EXAMPLES, root)
        self.root = root
        self.memory = GraphMemory()
        self._facts: dict[str, FileFacts] = {}
        self._registry = load_registry()
        self._settings = load_settings(None, root, self._registry)

    def edit(self, relative: str, old: str, new: str) -> None:
        path = self.root / relative
        text = path.read_text(encoding="utf-8")
        assert old in text, f"{old!r} is not in {relative}"
        path.write_text(text.replace(old, new, 1), encoding="utf-8")

    def graphs(self) -> tuple[Graph, Graph]:
        """The graph built with the memory, and the graph a run without one builds."""
        root = self.root
        sources = lintable(discover([root], (), root, root))
        result = lint(sources, self._settings, self._registry, RunOptions(), want_graph=True)
        assert result.graph is not None
        facts = [
            kept if (kept := self._facts.get(found.path)) == found else found
            for found in result.facts
        ]
        self._facts = {found.path: found for found in facts}
        packages = PackageGenerations()
        specialiser = Specialiser(
            sources,
            packages,
            DEFAULT_GENERATION,
            None,
            self._settings.max_file_size,
            dispatcher=Dispatcher(partial(extract_batch, None), 1),
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


_NEW_NODE = """#include <ros/ros.h>
#include <std_msgs/Float32.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "charge_reporter");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<std_msgs::Float32>("charge", 1);
  ros::spin();
  return 0;
}
"""

# A node only its includer's argument turns on: the file's own facts (under its default
# arguments) do not hold it, and stay equal when it is edited.
_OPTIONAL = """<launch>
  <arg name="use_spare" default="false"/>
  <group if="$(arg use_spare)">
    <node name="spare" pkg="turtle_bringup" type="velocity_smoother"/>
  </group>
</launch>
"""

_WITH_SPARE = """<launch>
  <include file="$(find turtle_bringup)/launch/optional.launch">
    <arg name="use_spare" value="true"/>
  </include>
</launch>
"""

_SOLO = """<launch>
  <include file="$(find turtle_bringup)/launch/base.launch" ns="solo"/>
  <node name="charge_reporter" pkg="turtle_bringup" type="charge_reporter">
    <remap from="charge" to="battery/charge"/>
  </node>
</launch>
"""


def _steps(ws: _Workspace) -> list[tuple[str, Callable[[], None]]]:
    def add(relative: str, text: str) -> Callable[[], None]:
        return lambda: (ws.root / relative).write_text(text, encoding="utf-8")

    def rename(relative: str, to: str) -> Callable[[], None]:
        return lambda: (ws.root / relative).rename(ws.root / to)

    def delete(relative: str) -> Callable[[], None]:
        return (ws.root / relative).unlink

    return [
        (
            "a topic renamed in C++ code",
            lambda: ws.edit(f"{TURTLE}/src/odom_relay.cpp", '("odom"', '("odometry"'),
        ),
        (
            "a topic renamed in the code of a node four launch trees start",
            lambda: ws.edit(f"{TURTLE}/src/velocity_smoother.cpp", '"cmd_vel"', '"cmd_vel_in"'),
        ),
        (
            "a parameter read added in Python code a launch file starts",
            lambda: ws.edit(
                f"{FLEET}/fleet_bringup/waypoint_follower.py",
                'self.declare_parameter("map_frame", "map")',
                'self.declare_parameter("map_frame", "map")\n'
                '        self.declare_parameter("loop_rate", 10.0)',
            ),
        ),
        (
            "a line inserted above every name of a file",
            lambda: ws.edit(f"{TURTLE}/src/odom_relay.cpp", "#include", "// relays\n#include"),
        ),
        (
            "a remap added to a launched node",
            lambda: ws.edit(
                f"{TURTLE}/launch/base.launch",
                '<remap from="cmd_vel_raw"',
                '<remap from="cmd_vel" to="smooth/cmd_vel"/>\n    <remap from="cmd_vel_raw"',
            ),
        ),
        ("a node's code added", add(f"{TURTLE}/src/charge_reporter.cpp", _NEW_NODE)),
        (
            "its executable added to the build",
            lambda: ws.edit(
                f"{TURTLE}/CMakeLists.txt",
                "add_executable(odom_relay",
                "add_executable(charge_reporter src/charge_reporter.cpp)\n"
                "add_executable(odom_relay",
            ),
        ),
        ("a launch file added that includes another", add(f"{TURTLE}/launch/single.launch", _SOLO)),
        (
            "the launch file renamed",
            rename(f"{TURTLE}/launch/single.launch", f"{TURTLE}/launch/solo.launch"),
        ),
        (
            "an include deleted",
            lambda: ws.edit(
                f"{TURTLE}/launch/robots.launch",
                '<include file="$(find turtle_bringup)/launch/base.launch" ns="robot2"/>\n',
                "",
            ),
        ),
        (
            "a node taken out of a launch file",
            lambda: ws.edit(
                f"{TURTLE}/launch/base.launch",
                '<node name="battery_monitor" pkg="turtle_bringup" type="battery_monitor"/>',
                "",
            ),
        ),
        (
            "an executable taken out of the build",
            lambda: ws.edit(
                f"{TURTLE}/CMakeLists.txt",
                "add_executable(battery_monitor",
                "# add_executable(battery_monitor",
            ),
        ),
        (
            "a parameter file's node key changed",
            lambda: ws.edit(
                f"{FLEET}/config/waypoint_follower.yaml",
                "waypoint_follower:",
                "/**:",
            ),
        ),
        (
            "a parameter declared in ROS 2 code",
            lambda: ws.edit(
                f"{FLEET}/src/dock_manager.cpp",
                'declare_parameter("dock_frame", "charging_dock");',
                'declare_parameter("dock_frame", "charging_dock");\n'
                '    declare_parameter("dockframe", "charging_dock");',
            ),
        ),
        (
            "a base no file defines given to a class of a node's code",
            lambda: ws.edit(
                f"{FLEET}/src/fleet_monitor.cpp",
                "public rclcpp::Node\n",
                "public rclcpp::Node, public Reporting\n",
            ),
        ),
        (
            "a class of that name defined in another package's code",
            lambda: ws.edit(
                f"{TURTLE}/src/velocity_smoother.cpp",
                "int main(",
                "class Reporting\n{\npublic:\n  void read_reporting(ros::NodeHandle & nh)\n"
                '  {\n    nh.param("report_period", period_, 5.0);\n  }\n\n'
                "  double period_;\n};\n\nint main(",
            ),
        ),
        (
            "a class deriving from the client library's node added",
            lambda: ws.edit(
                f"{FLEET}/src/fleet_monitor.cpp",
                "int main(",
                "class MonitorProbe : public rclcpp::Node\n{\n  void probe()\n  {\n"
                '    declare_parameter("probe_rate", 2.0);\n  }\n};\n\nint main(',
            ),
        ),
        (
            "a plugin loader added to a node's code, its plugins' base and one plugin beside",
            lambda: ws.edit(
                f"{FLEET}/src/dock_manager.cpp",
                "class DockManager",
                "namespace fleet_bringup\n{\nclass DockSensor\n{\n};\n\n"
                "class LidarDockSensor : public fleet_bringup::DockSensor\n{\n};\n}\n\n"
                "class DockManager",
            ),
        ),
        (
            "the loader itself",
            lambda: ws.edit(
                f"{FLEET}/src/dock_manager.cpp",
                "private:\n",
                "private:\n  pluginlib::ClassLoader<fleet_bringup::DockSensor> sensors_{\n"
                '    "fleet_bringup", "fleet_bringup::DockSensor"};\n',
            ),
        ),
        (
            "a plugin of that base in another package's code",
            lambda: ws.edit(
                f"{TURTLE}/src/velocity_smoother.cpp",
                "int main(",
                "class SonarDockSensor : public fleet_bringup::DockSensor\n{\n};\n\nint main(",
            ),
        ),
        (
            "the defined class renamed",
            lambda: ws.edit(
                f"{TURTLE}/src/velocity_smoother.cpp", "class Reporting\n", "class Reports\n"
            ),
        ),
        (
            "a remap changed in a Python launch file",
            lambda: ws.edit(f"{FLEET}/launch/fleet.launch.py", '("/tf", "tf")', '("/tf", "tf2")'),
        ),
        (
            "a launch file added that an argument turns on",
            add(f"{TURTLE}/launch/optional.launch", _OPTIONAL),
        ),
        ("its includer added", add(f"{TURTLE}/launch/with_spare.launch", _WITH_SPARE)),
        (
            "a node edited where only the includer's argument starts it",
            lambda: ws.edit(
                f"{TURTLE}/launch/optional.launch",
                'type="velocity_smoother"',
                'type="battery_monitor"',
            ),
        ),
        ("a node's code deleted", delete(f"{TURTLE}/src/odom_relay.cpp")),
        ("the included launch file deleted", delete(f"{TURTLE}/launch/base.launch")),
    ]


def test_every_edit_gives_the_graph_a_build_without_memory_gives(tmp_path: Path) -> None:
    ws = _Workspace(tmp_path / "ws")
    remembered, fresh = ws.graphs()
    assert remembered == fresh
    assert fresh.nodes and fresh.endpoints  # the example workspace has a graph to keep
    for what, step in _steps(ws):
        step()
        remembered, fresh = ws.graphs()
        assert remembered == fresh, what


def test_an_edit_of_one_file_changes_that_file_only(tmp_path: Path) -> None:
    """The memory tells one changed file from the rest, whose pieces it keeps."""
    ws = _Workspace(tmp_path / "ws")
    ws.graphs()
    trees = dict(ws.memory.reads("launch trees"))
    assert trees
    ws.edit(f"{TURTLE}/src/odom_relay.cpp", '("odom"', '("odometry"')
    remembered, fresh = ws.graphs()
    assert remembered == fresh
    assert not ws.memory.moved
    assert ws.memory.changed == {f"{TURTLE}/src/odom_relay.cpp"}
    # No launch file changed: every tree is the last build's, not walked again.
    assert all(ws.memory.reads("launch trees")[root] is kept for root, kept in trees.items())


@pytest.mark.parametrize("relative", [f"{TURTLE}/package.xml"])
def test_a_changed_manifest_keeps_nothing(tmp_path: Path, relative: str) -> None:
    ws = _Workspace(tmp_path / "ws")
    ws.graphs()
    ws.edit(relative, "<name>turtle_bringup</name>", "<name>turtle_base</name>")
    remembered, fresh = ws.graphs()
    assert ws.memory.moved
    assert remembered == fresh


def _never() -> object:
    raise AssertionError("made again: the memory did not keep it")


_LAUNCH_PIECES = (
    "launch files",
    "launch includers",
    "programs",
    "workspace declarations",
    "sorted nodes",
    "sorted endpoints",
)


def _spare_relay_added(ws: _Workspace, launch: str) -> None:
    """A node added to ``launch``: the graph built with the memory is the one built
    without, and starts it (under each namespace the file is included in)."""
    ws.edit(
        launch,
        "</launch>",
        '  <node name="spare_relay" pkg="turtle_bringup" type="odom_relay"/>\n</launch>',
    )
    remembered, fresh = ws.graphs()
    assert remembered == fresh
    assert any(node.name.endswith("/spare_relay") for node in fresh.nodes)


def test_a_node_added_to_a_launch_file_keeps_what_no_launch_file_makes(tmp_path: Path) -> None:
    """The code's programs and declarations, which files are launch files and which are
    roots: the last build's while no changed file differs in what each is made from."""
    ws = _Workspace(tmp_path / "ws")
    ws.graphs()
    kept = {name: ws.memory.piece(name, (), _never) for name in _LAUNCH_PIECES}
    _spare_relay_added(ws, f"{TURTLE}/launch/base.launch")
    for name, piece in kept.items():
        assert ws.memory.piece(name, (), _never) is piece, name


def test_a_launch_file_edited_walks_its_tree_and_takes_up_the_others(tmp_path: Path) -> None:
    """The nodes a tree starts, their code and instances: the last build's for every
    tree the edit does not reach (``build._TreeLaunches``), made again for the one it
    does, and the graph as a build without memory makes it."""
    ws = _Workspace(tmp_path / "ws")
    ws.graphs()
    before = dict(ws.memory.piece("tree launches", (), _never))
    assert f"{TURTLE}/launch/teleop.launch" in before and len(before) > 2
    _spare_relay_added(ws, f"{TURTLE}/launch/teleop.launch")
    after = ws.memory.piece("tree launches", (), _never)
    assert after.keys() == before.keys()
    for root, made in after.items():
        assert (made is before[root]) is (root != f"{TURTLE}/launch/teleop.launch"), root


def test_a_parameter_declared_in_code_makes_the_declarations_again(tmp_path: Path) -> None:
    ws = _Workspace(tmp_path / "ws")
    ws.graphs()
    before = ws.memory.piece("workspace declarations", (), _never)
    ws.edit(
        f"{FLEET}/src/dock_manager.cpp",
        'declare_parameter("dock_frame", "charging_dock");',
        'declare_parameter("dock_frame", "charging_dock");\n'
        '    declare_parameter("undock_speed", 0.1);',
    )
    remembered, fresh = ws.graphs()
    assert remembered == fresh
    assert fresh.parameter_declarations is not None
    assert "undock_speed" in fresh.parameter_declarations.names
    assert ws.memory.piece("workspace declarations", (), _never) is not before


@pytest.mark.parametrize(
    ("relative", "endpoints", "without", "node"),
    [
        (  # a built C++ program no launch file starts
            f"{TURTLE}/src/odom_relay.cpp",
            (
                '    odom_pub_ = nh.advertise<nav_msgs::Odometry>("odom", 50);\n'
                "    wheel_sub_ = nh.subscribe(odom_topic_, 50, &OdomRelay::wheelCallback, this);\n"
            ),
            "    // relayed by the driver now\n",
            "/odom_relay",
        ),
        (  # a Python script no launch file starts
            f"{TURTLE}/scripts/pose_logger.py",
            "rospy.Subscriber('turtle1/pose', Pose, self.on_pose, queue_size=1)",
            "self.on_pose(None)",
            "/pose_logger",
        ),
    ],
)
def test_code_that_stops_and_starts_declaring_endpoints_keeps_the_programs(
    tmp_path: Path, relative: str, endpoints: str, without: str, node: str
) -> None:
    """Code no launch file starts is a program where it declares endpoints: the last
    build's programs are taken up with that file's answer changed (the same built
    programs), not made again by asking every code file."""
    ws = _Workspace(tmp_path / "ws")
    _, before = ws.graphs()
    assert any(found.name == node for found in before.nodes)
    built = ws.memory.piece("programs", (), _never).built
    for old, new, declared in ((endpoints, without, False), (without, endpoints, True)):
        ws.edit(relative, old, new)
        remembered, fresh = ws.graphs()
        assert remembered == fresh
        assert any(found.name == node for found in fresh.nodes) is declared
        assert ws.memory.piece("programs", (), _never).built is built
    assert fresh == before


@dataclass(frozen=True)
class _Item:
    key: int
    label: str  # items of one key with other labels are not equal: both kept, in order

    def sort_key(self) -> int:
        return self.key


@pytest.mark.parametrize("seed", range(12))
def test_a_sorting_kept_between_builds_sorts_as_unique_does(seed: int) -> None:
    """``_Sorting`` takes the last sort where few items are new or gone, and must give
    exactly what ``_unique`` gives: shared keys, equal items, items of one key in their
    order of arrival, the kept items reordered."""
    chance = random.Random(seed)
    # Keys mostly distinct, as a graph's are; some shared, with equal items and not.
    items = [_Item(chance.randrange(20_000), chance.choice("ab")) for _ in range(400)]
    items += [_Item(item.key, chance.choice("ab")) for item in items[:20]]
    chance.shuffle(items)
    sorting: _Sorting[_Item] = _Sorting(_Item.sort_key)
    taken = 0
    for _ in range(40):
        edited = list(items)
        for _ in range(chance.randrange(1, 6)):
            what = chance.random()
            at = chance.randrange(len(edited))
            if what < 0.3:  # made again: a new object of the same value
                edited[at] = _Item(edited[at].key, edited[at].label)
            elif what < 0.5:
                del edited[at]
            elif what < 0.8:
                known = chance.random() < 0.2  # the key of another item
                key = chance.choice(edited).key if known else chance.randrange(20_000)
                edited.insert(at, _Item(key, chance.choice("ab")))
            elif what < 0.81:  # the same item twice: sorted anew while it stays
                edited.insert(at, edited[chance.randrange(len(edited))])
            elif what < 0.86:  # the kept items in another order
                other = chance.randrange(len(edited))
                edited[at], edited[other] = edited[other], edited[at]
        expected = _unique(edited, _Item.sort_key)
        updated = sorting._updated(edited)  # the kept sort, where it can be taken
        if updated is not None:
            assert updated.items == expected
            taken += 1
        assert sorting(edited) == expected
        items = edited
    assert taken >= 3  # the kept sort was taken, not only made anew


def test_the_index_of_what_pieces_read_made_anew_forgets_as_before(tmp_path: Path) -> None:
    """The index by which an edit forgets pieces is made anew once its entries are mostly
    of pieces gone; made anew, it must know every piece kept."""
    ws = _Workspace(tmp_path / "ws")
    ws.graphs()
    ws.edit(f"{TURTLE}/launch/base.launch", '<remap from="cmd_vel_raw"', '<remap from="cmd_raw"')
    ws.graphs()
    ws.memory._index_reads()
    ws.edit(f"{TURTLE}/src/velocity_smoother.cpp", '"cmd_vel"', '"cmd_vel_in"')
    remembered, fresh = ws.graphs()
    assert remembered == fresh
    assert any(e.written == "cmd_vel_in" for e in fresh.endpoints)


def test_tables_taken_up_edit_after_edit_keep_one_answer_per_file(tmp_path: Path) -> None:
    """A memory's parameter tables follow each class edit (``with_classes``) without
    wrapping what they ask of each file again: a session of many edits would otherwise
    call through one more cache per edit."""
    ws = _Workspace(tmp_path / "ws")
    ws.graphs()
    tables = ws.memory.piece("parameter tables", (), dict)
    for count in range(3):
        ws.edit(
            f"{FLEET}/src/fleet_monitor.cpp",
            "int main(",
            f"class Probe{count} : public Reporting\n{{\n}};\n\nint main(",
        )
        ws.graphs()
        followed = ws.memory.piece("parameter tables", (), dict)
        assert followed is not tables and followed.excluded is tables.excluded
