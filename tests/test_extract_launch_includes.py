"""Launch includes: where the included file is, the scope and arguments it gets, and the
included file extracted again under the arguments its includer passes (issue 5)."""

from __future__ import annotations

from pathlib import Path

import pytest

from roslint_names.extract.launch import include as launch_include
from roslint_names.extract.launch import xml_launch as launch_xml
from roslint_names.extract.launch import yaml_launch as launch_yaml
from roslint_names.extract.launch.substitution import ARG, Dialect, Lookup, Value
from roslint_names.model import (
    FileFacts,
    Generation,
    InPackage,
    LaunchInclude,
    LaunchNode,
    Remap,
    Span,
)

FIXTURES = Path(__file__).parent / "fixtures" / "launch"

Arguments = tuple[tuple[str, str], ...]


def fixture(name: str, arguments: Arguments = ()) -> FileFacts:
    data = (FIXTURES / name).read_bytes()
    if name.endswith(".yaml"):
        return launch_yaml.extract(name, data, None, Generation.ROS1, arguments=arguments)
    return launch_xml.extract(name, data, None, Generation.ROS1, arguments=arguments)


def ros1(xml: str, arguments: Arguments = ()) -> FileFacts:
    return launch_xml.extract("a.launch", xml.encode(), None, Generation.ROS1, arguments=arguments)


def ros2(xml: str, arguments: Arguments = ()) -> FileFacts:
    data = xml.encode()
    return launch_xml.extract("a.launch.xml", data, None, Generation.ROS2, arguments=arguments)


def yaml(text: str, arguments: Arguments = ()) -> FileFacts:
    data = text.encode()
    return launch_yaml.extract("a.launch.yaml", data, None, Generation.ROS2, arguments=arguments)


def include(facts: FileFacts) -> LaunchInclude:
    [found] = facts.includes
    return found


def where(found: LaunchInclude) -> tuple[str | None, str | None]:
    return found.package, found.path


def nodes(facts: FileFacts) -> dict[str, LaunchNode]:
    return {launched.name or "?": launched for launched in facts.launch_nodes}


# -- ROS 1: the multi-robot fixture ------------------------------------------------------


def test_same_include_twice_in_two_groups_with_different_arguments() -> None:
    first, second = fixture("fleet.launch").includes[:2]
    assert where(first) == where(second) == ("fleet_bringup", "launch/robot.launch")
    assert (first.namespace, second.namespace) == ("/tb3_0", "/tb3_1")
    # tb3_0: a child guarded by a true `if` is passed, one guarded by `unless` true is not.
    assert first.arguments == (("robot_name", "tb3_0"), ("use_fake", "true"), ("x_pos", "-2.0"))
    # tb3_1: `default` on an include child is a value roslaunch passes; $(arg) substituted.
    assert second.arguments == (("model", "burger"), ("robot_name", "tb3_1"), ("x_pos", "2.0"))
    assert not first.anchored and not second.anchored


def test_group_and_file_level_remaps_reach_the_include_in_order() -> None:
    first, second = fixture("fleet.launch").includes[:2]
    assert [(r.source, r.target) for r in first.remaps] == [
        ("clock", "/sim/clock"),
        ("scan", "base_scan"),
    ]
    assert [(r.source, r.target) for r in second.remaps] == [("clock", "/sim/clock")]
    assert first.remaps[1].span == Span(15, 18, 15, 22)


def test_pass_all_args_hands_over_every_argument_children_win() -> None:
    gazebo = fixture("fleet.launch").includes[2]
    assert where(gazebo) == ("gazebo_ros", "launch/empty_world.launch")
    # model: the child's value is dynamic ($(env)), so the inherited "burger" is not what
    # the included file gets; robot_model is not static at all. Unknown values are handed
    # over as unknown: the included file must not take its defaults. launch_dir is a
    # folder of a package ($(find fleet_bringup)/launch): handed over as that.
    assert gazebo.arguments == (
        ("launch_dir", InPackage("fleet_bringup", "launch")),
        ("model", None),
        ("robot_model", None),
        ("use_sim", "true"),
        ("world", "empty.world"),
    )


def test_dirname_path_is_relative_to_the_including_file_and_normalised() -> None:
    sensors = fixture("fleet.launch").includes[3]
    assert where(sensors) == (None, "../config/sensors.launch")
    assert sensors.namespace == "/sensors"


def test_argument_holding_a_find_locates_the_package() -> None:
    rviz = fixture("fleet.launch").includes[4]
    assert where(rviz) == ("fleet_bringup", "launch/rviz.launch")


def test_absolute_include_ns_and_absolute_group_ns_anchor() -> None:
    facts = fixture("fleet.launch")
    rviz, manager = facts.includes[4], facts.includes[5]
    assert (rviz.namespace, rviz.anchored) == ("/visualisation", True)
    assert (manager.namespace, manager.anchored) == ("/fleet/manager", True)
    assert [found.anchored for found in facts.includes].count(True) == 2


def test_dynamic_package_and_dynamic_path() -> None:
    facts = fixture("fleet.launch")
    extra, by_model = facts.includes[6], facts.includes[7]
    assert where(extra) == (None, None)  # $(find $(env FLEET_PKG))
    assert where(by_model) == ("fleet_bringup", None)  # $(arg robot_model) is $(env ...)
    assert by_model.remaps == extra.remaps != ()  # still emitted with their scope


def test_include_span_is_the_file_value() -> None:
    first = fixture("fleet.launch").includes[0]
    assert first.span == Span(16, 20, 16, 61)


def test_include_without_file_points_at_the_tag() -> None:
    found = include(ros1('<launch>\n  <include ns="x"/>\n</launch>'))
    assert (found.package, found.path, found.namespace) == (None, None, "/x")
    assert found.span == Span(2, 3, 2, 11)  # the tag name


def test_path_parts_substituted_with_static_arguments() -> None:
    facts = ros1(
        '<launch><arg name="robot" default="husky"/>'
        '<include file="$(find husky_gazebo)/launch/$(arg robot)/spawn_$(arg robot).launch"/>'
        "</launch>"
    )
    assert where(include(facts)) == ("husky_gazebo", "launch/husky/spawn_husky.launch")


def test_argument_without_default_in_path_keeps_the_package() -> None:
    facts = ros1(
        '<launch><arg name="r"/><include file="$(find p)/launch/$(arg r).launch"/></launch>'
    )
    assert where(include(facts)) == ("p", None)


def test_statically_skipped_include_is_not_emitted() -> None:
    facts = ros1(
        '<launch><arg name="gui" default="false"/>'
        '<include file="$(find rviz)/launch/rviz.launch" if="$(arg gui)"/></launch>'
    )
    assert facts.includes == ()


def test_pass_all_args_false_passes_only_children() -> None:
    facts = ros1(
        '<launch><arg name="a" default="1"/><arg name="b" default="2"/>'
        '<include file="$(find p)/x.launch" pass_all_args="false"><arg name="b" value="3"/>'
        "</include></launch>"
    )
    assert include(facts).arguments == (("b", "3"),)


def test_remap_after_the_include_does_not_reach_it() -> None:
    facts = ros1('<launch><include file="$(find p)/x.launch"/><remap from="a" to="b"/></launch>')
    assert include(facts).remaps == ()


# -- ROS 1: launch nodes' own remaps and anchoring ---------------------------------------


def test_own_remaps_count_the_trailing_node_remaps() -> None:
    facts = ros1(
        '<launch><remap from="clock" to="/clock"/><group ns="g"><remap from="a" to="b"/>'
        '<node pkg="p" type="t" name="n" args="x:=y"><remap from="c" to="d"/></node>'
        "</group></launch>"
    )
    [launched] = facts.launch_nodes
    assert [r.source for r in launched.remaps] == ["clock", "a", "c", "x"]
    assert launched.own_remaps == 2
    assert not launched.anchored


def test_node_anchoring_ros1() -> None:
    found = nodes(fixture("robot.launch", (("robot_name", "tb3_0"),)))
    assert found["diagnostics"].anchored  # ns="/diagnostics"
    assert (found["relay"].namespace, found["relay"].anchored) == ("/tb3_0/relay", True)
    assert not found["lidar"].anchored  # a relative group ns
    facts = ros1(
        '<launch><group ns="/abs"><node pkg="p" type="t" name="n" ns="x"/></group></launch>'
    )
    assert (facts.launch_nodes[0].namespace, facts.launch_nodes[0].anchored) == ("/abs/x", True)


# -- ROS 1: specialised extraction -------------------------------------------------------


def test_passed_arguments_change_names_namespaces_and_conditions() -> None:
    plain = nodes(fixture("robot.launch"))
    assert set(plain) == {"core", "lidar", "diagnostics", "relay"}
    assert plain["lidar"].namespace == ""  # robot_name has no default
    passed = nodes(
        fixture("robot.launch", (("model", "waffle"), ("robot_name", "tb3_0"), ("use_fake", "1")))
    )
    assert set(passed) == {"waffle_fake", "lidar", "diagnostics", "relay"}  # if/unless flip
    assert passed["lidar"].namespace == "/tb3_0_sensors"


def test_fixed_arg_value_is_not_overridden_and_undeclared_ones_are_ignored() -> None:
    facts = fixture("robot.launch", (("robot_name", "r"), ("frame_prefix", "x"), ("junk", "j")))
    frames = [use.value for use in facts.names if use.kind.value == "frame"]
    assert frames == ["r/base_scan"]  # frame_prefix keeps value="$(arg robot_name)"


def test_passed_arguments_reach_the_includes_of_the_included_file() -> None:
    xml = (
        '<launch><arg name="robot" default="r0"/>'
        '<include file="$(find p)/launch/$(arg robot).launch" ns="$(arg robot)" '
        'pass_all_args="true"/></launch>'
    )
    plain, passed = include(ros1(xml)), include(ros1(xml, (("robot", "r7"),)))
    assert (plain.path, plain.namespace, plain.arguments) == (
        "launch/r0.launch",
        "/r0",
        (("robot", "r0"),),
    )
    assert (passed.path, passed.namespace, passed.arguments) == (
        "launch/r7.launch",
        "/r7",
        (("robot", "r7"),),
    )


def test_passed_argument_applies_to_every_guarded_declaration() -> None:
    xml = (
        '<launch><arg name="sim" default="false"/>'
        '<arg name="rate" default="10" if="$(arg sim)"/>'
        '<arg name="rate" default="50" unless="$(arg sim)"/>'
        '<node pkg="p" type="t" name="n_$(arg rate)"/></launch>'
    )
    assert [n.name for n in ros1(xml).launch_nodes] == ["n_50"]
    assert [n.name for n in ros1(xml, (("rate", "5"),)).launch_nodes] == ["n_5"]


# -- ROS 2 XML ---------------------------------------------------------------------------


def test_ros2_include_in_group_with_pushed_namespace_and_set_remap() -> None:
    navigation = fixture("fleet_bringup.launch.xml").includes[0]
    assert where(navigation) == ("nav2_bringup", "launch/navigation_launch.py")
    assert (navigation.namespace, navigation.anchored) == ("/robot1", False)
    assert [(r.source, r.target) for r in navigation.remaps] == [("/tf", "tf")]
    # Explicit <arg>s win over the configurations in scope (use_sim_time), a <let> in the
    # group is seen, and the dynamic `map` is handed over as unknown.
    assert navigation.arguments == (
        ("autostart", "true"),
        ("map", None),
        ("namespace", "robot1"),
        ("params_file", "nav2_params.yaml"),
        ("use_sim_time", "false"),
    )


def test_ros2_group_scope_ends_for_later_includes() -> None:
    lidar = fixture("fleet_bringup.launch.xml").includes[1]
    assert where(lidar) == ("fleet_sensors", "launch/lidar.launch.xml")  # find-pkg-prefix
    assert (lidar.namespace, lidar.remaps) == ("/", ())
    assert lidar.arguments == (("map", None), ("namespace", "robot1"), ("use_sim_time", "true"))


def test_ros2_dirname_include_and_anchored_push() -> None:
    facts = fixture("fleet_bringup.launch.xml")
    sensors, manager = facts.includes[2], facts.includes[3]
    assert where(sensors) == (None, "sensors.launch.xml")
    assert ("ns", "front") in sensors.arguments
    assert where(manager) == ("fleet_manager", "launch/manager.launch.yaml")
    assert (manager.namespace, manager.anchored) == ("/fleet/manager", True)


def test_ros2_include_args_use_the_including_scope() -> None:
    facts = ros2(
        '<launch><let name="x" value="1"/><include file="$(find-pkg-share p)/a.launch.xml">'
        '<arg name="y" value="$(var x)"/><arg name="x" value="$(env X)"/></include></launch>'
    )
    # x: the explicit, unknown value wins over the 1 in scope
    assert include(facts).arguments == (("x", None), ("y", "1"))


def test_ros2_node_anchoring_and_own_remaps() -> None:
    found = nodes(fixture("sensors.launch.xml"))
    assert (found["aggregator"].namespace, found["aggregator"].anchored) == ("/diagnostics", True)
    assert not found["sensors_lidar"].anchored
    assert found["sensors_lidar"].own_remaps == 1
    facts = ros2(
        '<launch><push-ros-namespace namespace="/top"/><set_remap from="a" to="b"/>'
        '<node pkg="p" exec="e" name="n" namespace="x" args="--ros-args -r c:=d"/></launch>'
    )
    [launched] = facts.launch_nodes
    assert (launched.namespace, launched.anchored, launched.own_remaps) == ("/top/x", True, 1)
    assert len(launched.remaps) == 2


def test_ros2_ns_on_the_command_line_anchors() -> None:
    facts = ros2('<launch><node pkg="p" exec="e" name="n" ros_args="-r __ns:=/front"/></launch>')
    assert (facts.launch_nodes[0].namespace, facts.launch_nodes[0].anchored) == ("/front", True)


# -- ROS 2: specialised extraction -------------------------------------------------------


def test_ros2_passed_configurations_beat_arg_defaults() -> None:
    plain = nodes(fixture("sensors.launch.xml"))
    assert set(plain) == {"sensors_lidar", "aggregator"}
    assert plain["sensors_lidar"].namespace == "/sensors"
    passed = nodes(
        fixture("sensors.launch.xml", (("driver", "other"), ("ns", "front"), ("use_imu", "true")))
    )
    assert set(passed) == {"front_lidar", "imu", "aggregator"}  # name and condition
    assert passed["front_lidar"].namespace == "/front"
    assert passed["front_lidar"].executable == "urg_node_driver"  # <let> still overrides


def test_ros2_passed_configuration_flows_into_includes() -> None:
    facts = ros2(
        '<launch><arg name="robot" default="r0"/>'
        '<include file="$(find-pkg-share p)/launch/$(var robot).launch.xml"/></launch>',
        (("robot", "r3"), ("extra", "e")),
    )
    assert include(facts).path == "launch/r3.launch.xml"
    assert include(facts).arguments == (("extra", "e"), ("robot", "r3"))


# -- ROS 2 YAML --------------------------------------------------------------------------


def test_yaml_include_with_arg_list_in_a_group() -> None:
    first, second = fixture("fleet_bringup.launch.yaml").includes
    assert where(first) == ("fleet_bringup", "launch/sensors.launch.xml")
    assert (first.namespace, first.anchored) == ("/robot1", False)
    assert [(r.source, r.target) for r in first.remaps] == [("/tf", "tf")]
    assert first.arguments == (
        ("frame", "robot1/laser"),
        ("ns", "lidar"),
        ("robot", "robot1"),
        ("use_sim_time", "true"),
    )
    assert first.span == Span(10, 13, 10, 72)  # the quoted file value
    assert where(second) == (None, "../other/robot1.launch.yaml")
    assert (second.namespace, second.remaps) == ("/", ())


def test_yaml_specialised_extraction() -> None:
    facts = fixture("fleet_bringup.launch.yaml", (("robot", "robot9"),))
    [manager] = facts.launch_nodes
    assert manager.name == "robot9_manager"
    assert facts.includes[0].namespace == "/robot9"
    assert facts.includes[1].path == "../other/robot9.launch.yaml"


def test_yaml_include_without_file() -> None:
    facts = yaml("launch:\n- include: {arg: [{name: a, value: b}]}\n")
    assert (include(facts).path, include(facts).arguments) == (None, (("a", "b"),))


# -- locate and normalise ----------------------------------------------------------------


def lookup(values: dict[str, Value]) -> Lookup:
    return lambda space, name: values.get(name) if space == ARG else None


@pytest.mark.parametrize(
    ("raw", "dialect", "expected"),
    [
        ("$(find p)/launch/a.launch", Dialect.ROS1, ("p", "launch/a.launch")),
        ("  $(find p)/launch/./x/../a.launch ", Dialect.ROS1, ("p", "launch/a.launch")),
        ("$(find-pkg-share p)/launch/a.launch.py", Dialect.ROS1, (None, None)),  # ROS 2 only
        ("$(find p)/a.launch", Dialect.ROS2, (None, None)),  # ROS 1 only
        ("$(find-pkg-share 'p')/a.launch.py", Dialect.ROS2, ("p", "a.launch.py")),
        ("$(find-pkg-prefix p)/share/p/launch/a.py", Dialect.ROS2, ("p", "launch/a.py")),
        ("$(find-pkg-prefix p)/lib/p/a.py", Dialect.ROS2, ("p", None)),
        ("$(find-pkg-prefix p)/share/q/a.py", Dialect.ROS2, ("p", None)),
        ("$(find p)launch/a.launch", Dialect.ROS1, ("p", None)),
        ("$(find p)", Dialect.ROS1, ("p", None)),
        ("$(dirname)/../../a.launch", Dialect.ROS1, (None, "../../a.launch")),
        ("$(dirname)/sub/../a.launch.xml", Dialect.ROS2, (None, "a.launch.xml")),
        ("/opt/ros//share/p/../q/a.launch", Dialect.ROS1, (None, "/opt/ros/share/q/a.launch")),
        ("//opt/a.launch", Dialect.ROS1, (None, "/opt/a.launch")),
        ("a.launch", Dialect.ROS1, (None, None)),  # relative to the working directory
        ("$(env HOME)/a.launch", Dialect.ROS1, (None, None)),
        ("$(find p/a.launch", Dialect.ROS1, (None, None)),  # unbalanced
        ("$(arg dir)/a.launch", Dialect.ROS1, ("q", "launch/a.launch")),
        ("$(arg deep)/a.launch", Dialect.ROS1, ("q", "launch/sub/a.launch")),
        ("$(arg cycle)/a.launch", Dialect.ROS1, (None, None)),
        ("$(arg unknown)/a.launch", Dialect.ROS1, (None, None)),
        ("$(find $(arg pkg))/a.launch", Dialect.ROS1, ("q", "a.launch")),
        ("$(var dir)/a.launch", Dialect.ROS2, (None, None)),  # ROS 1 $(find) in a ROS 2 var
    ],
)
def test_locate(raw: str, dialect: Dialect, expected: tuple[str | None, str | None]) -> None:
    values = {
        "pkg": Value("q"),
        "dir": Value("$(find $(arg pkg))/launch", dynamic=True),
        "deep": Value("$(arg dir)/sub", dynamic=True),
        "cycle": Value("$(arg cycle)/x", dynamic=True),
        "unknown": Value("", dynamic=True),
    }
    target = launch_include.locate(raw, dialect, lookup(values))
    assert (target.package, target.path) == expected


def test_unfold_bounds_exponential_references() -> None:
    bomb = Value("$(arg b)" * 10, dynamic=True)
    assert launch_include.unfold("$(arg b)", Dialect.ROS1, lookup({"b": bomb})) is None


def test_normalise() -> None:
    assert launch_include.normalise("a/./b//c") == "a/b/c"
    assert launch_include.normalise("../a/../../b") == "../../b"
    assert launch_include.normalise("a/..") is None
    assert launch_include.normalise("") is None


def test_handed_over_explicit_unknown_hides_inherited() -> None:
    inherited = {"a": "1", "b": "2", "c": None}
    assert launch_include.handed_over(inherited, {"b": None, "d": "4"}) == (
        ("a", "1"),
        ("b", None),
        ("c", None),
        ("d", "4"),
    )


def test_real_style_include_chain_remap_objects() -> None:
    """A whole LaunchInclude, to pin every field at once."""
    facts = ros1(
        '<launch><remap from="a" to="b"/><group ns="g">'
        '<include file="$(find p)/x.launch" ns="h"><arg name="k" value="v"/></include>'
        "</group></launch>"
    )
    assert include(facts) == LaunchInclude(
        package="p",
        path="x.launch",
        namespace="/g/h",
        span=Span(1, 62, 1, 80),
        arguments=(("k", "v"),),
        remaps=(Remap("a", "b", Span(1, 22, 1, 23), Span(1, 29, 1, 30)),),
        anchored=False,
    )
