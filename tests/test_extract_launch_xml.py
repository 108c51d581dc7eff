"""ROS 1 and ROS 2 launch XML extraction: source in, names out."""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from roslint_names.extract import evidence
from roslint_names.extract.launch import xml_launch as launch_xml
from roslint_names.extract.launch.substitution import (
    ARG,
    Dialect,
    Located,
    Value,
    mapping_lookup,
    ros2_assignments,
    split_words,
    substitute,
)
from roslint_names.model import FileFacts, Generation, Kind, LaunchNode, Role, Span

FIXTURES = Path(__file__).parent / "fixtures" / "launch"


def ros1(xml: str, path: str = "test.launch", package: Generation | None = None) -> FileFacts:
    return launch_xml.extract(path, xml.encode(), package, Generation.ROS2)


def ros2(xml: str, path: str = "test.launch.xml", package: Generation | None = None) -> FileFacts:
    return launch_xml.extract(path, xml.encode(), package, Generation.ROS1)


def values(facts: FileFacts) -> list[tuple[Kind, str]]:
    return [(use.kind, use.value) for use in facts.names]


def static(facts: FileFacts) -> list[tuple[Kind, str]]:
    return [(use.kind, use.value) for use in facts.names if not use.dynamic]


def roles(facts: FileFacts) -> list[tuple[Role, str]]:
    return [(use.role, use.value) for use in facts.names]


def namespaces(facts: FileFacts) -> list[tuple[str, str | None]]:
    return [(use.value, use.namespace) for use in facts.names]


def node(facts: FileFacts) -> LaunchNode:
    [launched] = facts.launch_nodes
    return launched


# -- ROS 1: nodes and namespaces ---------------------------------------------------------


def test_node_name() -> None:
    assert values(ros1('<launch><node name="a" pkg="p" type="t"/></launch>')) == [(Kind.NODE, "a")]


def test_node_ns() -> None:
    facts = ros1('<launch><node ns="robot" name="a" pkg="p" type="t"/></launch>')
    assert values(facts) == [(Kind.NAMESPACE, "robot"), (Kind.NODE, "a")]
    assert namespaces(facts) == [("robot", "/"), ("a", "/robot")]


def test_test_element_is_a_node() -> None:
    facts = ros1('<launch><test test-name="t1" pkg="p" type="hz" name="hz" ns="x"/></launch>')
    assert values(facts) == [(Kind.NODE, "hz"), (Kind.NAMESPACE, "x")]  # in source order
    assert node(facts).executable == "hz"


def test_nested_groups_push_namespaces() -> None:
    facts = ros1(
        '<launch><group ns="a"><group ns="b"><node name="n" pkg="p" type="t"/></group>'
        '<node name="m" pkg="p" type="t"/></group></launch>'
    )
    assert namespaces(facts) == [("a", "/"), ("b", "/a"), ("n", "/a/b"), ("m", "/a")]
    assert [launched.namespace for launched in facts.launch_nodes] == ["/a/b", "/a"]


def test_absolute_group_ns_replaces_the_enclosing_one() -> None:
    facts = ros1(
        '<launch><group ns="a"><group ns="/b"><node name="n" pkg="p" type="t"/>'
        "</group></group></launch>"
    )
    assert node(facts).namespace == "/b"


def test_dynamic_group_ns_makes_namespace_unknown() -> None:
    facts = ros1(
        '<launch><group ns="$(env ROBOT)"><node name="n" pkg="p" type="t"/></group></launch>'
    )
    assert [(use.value, use.dynamic, use.namespace) for use in facts.names] == [
        ("$(env ROBOT)", True, "/"),
        ("n", False, None),
    ]
    assert node(facts).namespace == ""


def test_include_ns_and_its_args_are_not_declarations() -> None:
    facts = ros1(
        '<launch><arg name="robot" default="r1"/>'
        '<include file="$(find p)/x.launch" ns="nav"><arg name="robot" value="r2"/></include>'
        '<group ns="$(arg robot)"/></launch>'
    )
    assert values(facts) == [(Kind.NAMESPACE, "nav"), (Kind.NAMESPACE, "r1")]


def test_launch_node_fields() -> None:
    facts = ros1(
        '<launch><group ns="g"><node pkg="amcl" type="amcl_node" name="amcl"/></group></launch>'
    )
    assert node(facts) == LaunchNode(
        package="amcl",
        executable="amcl_node",
        name="amcl",
        namespace="/g",
        span=Span(1, 63, 1, 67),
    )


def test_launch_node_without_name_points_at_the_tag() -> None:
    facts = ros1('<launch>\n  <node pkg="p" type="t"/></launch>')
    assert node(facts).name is None
    assert node(facts).span == Span(2, 3, 2, 8)


# -- ROS 1: node args --------------------------------------------------------------------


def test_args_name_ns_and_remaps() -> None:
    facts = ros1(
        '<launch><node pkg="p" type="t" args="-v __name:=drv __ns:=/r cmd:=/cmd"/></launch>'
    )
    assert roles(facts) == [
        (Role.NODE_NAME, "drv"),
        (Role.NAMESPACE, "/r"),
        (Role.REMAP_FROM, "cmd"),
        (Role.REMAP_TO, "/cmd"),
    ]
    assert (node(facts).name, node(facts).namespace) == ("drv", "/r")


def test_args_private_params_and_special_keys_are_not_names() -> None:
    facts = ros1(
        '<launch><node name="n" pkg="p" type="t" args="_rate:=10 __log:=/tmp/x"/></launch>'
    )
    assert values(facts) == [(Kind.NODE, "n")]
    assert node(facts).parameters == ("rate",)


def test_args_substitution_with_spaces_is_one_word() -> None:
    facts = ros1(
        '<launch><arg name="o" default="odom"/>'
        '<node name="n" pkg="p" type="t" args="$(arg o):=/odom"/></launch>'
    )
    assert static(facts)[1:] == [(Kind.TOPIC, "odom"), (Kind.TOPIC, "/odom")]


# -- ROS 1: remaps -------------------------------------------------------------------------


def test_remaps_at_every_level() -> None:
    facts = ros1(
        '<launch><remap from="a" to="b"/><group><remap from="c" to="d"/>'
        '<node name="n" pkg="p" type="t" args="e:=f"><remap from="g" to="h"/></node></group>'
        '<node name="m" pkg="p" type="t"/></launch>'
    )
    assert [(use.kind, use.role) for use in facts.names[:2]] == [
        (Kind.TOPIC, Role.REMAP_FROM),
        (Kind.TOPIC, Role.REMAP_TO),
    ]
    first, second = facts.launch_nodes
    assert [(remap.source, remap.target) for remap in first.remaps] == [
        ("a", "b"),
        ("c", "d"),
        ("g", "h"),
        ("e", "f"),
    ]
    assert [(remap.source, remap.target) for remap in second.remaps] == [("a", "b")]


def test_remap_after_a_node_does_not_apply_to_it() -> None:
    facts = ros1('<launch><node name="n" pkg="p" type="t"/><remap from="a" to="b"/></launch>')
    assert node(facts).remaps == ()


def test_dynamic_remap_is_a_dynamic_name_but_no_launch_remap() -> None:
    facts = ros1(
        '<launch><node name="n" pkg="p" type="t"><remap from="$(arg x)" to="b"/></node></launch>'
    )
    assert [(use.value, use.dynamic) for use in facts.names[1:]] == [
        ("$(arg x)", True),
        ("b", False),
    ]
    assert node(facts).remaps == ()


# -- ROS 1: parameters ---------------------------------------------------------------------


def test_param_names_and_frame_values() -> None:
    facts = ros1(
        '<launch><param name="base_frame" value="/base_link"/>'
        '<param name="rate" value="/not_a_frame"/>'
        '<param name="odom/frame_id" value="odom"/>'
        '<param name="frames" value="x"/></launch>'
    )
    assert values(facts) == [
        (Kind.PARAMETER, "base_frame"),
        (Kind.FRAME, "/base_link"),
        (Kind.PARAMETER, "rate"),
        (Kind.PARAMETER, "odom/frame_id"),
        (Kind.FRAME, "odom"),
        (Kind.PARAMETER, "frames"),
    ]


def test_node_params_live_under_the_node() -> None:
    facts = ros1(
        '<launch><group ns="r"><node name="n" pkg="p" type="t">'
        '<param name="gain" value="1"/><rosparam ns="pid" param="p"/></node></group>'
        "</launch>"
    )
    assert namespaces(facts)[2:] == [("gain", "/r/n"), ("pid", "/r/n"), ("p", "/r/n/pid")]
    assert node(facts).parameters == ("gain", "pid/p")


def test_rosparam_ns_and_param() -> None:
    facts = ros1('<launch><rosparam command="load" file="x.yaml" ns="costmap"/></launch>')
    assert values(facts) == [(Kind.NAMESPACE, "costmap")]


# -- ROS 1: arguments and conditions -------------------------------------------------------


def test_arg_default_and_value_are_substituted() -> None:
    facts = ros1(
        '<launch><arg name="a" default="x"/><arg name="b" value="y"/>'
        '<group ns="$(arg a)_$(arg b)"/></launch>'
    )
    assert values(facts) == [(Kind.NAMESPACE, "x_y")]


def test_args_are_file_global() -> None:
    facts = ros1('<launch><group ns="$(arg a)"/><arg name="a" default="late"/></launch>')
    assert static(facts) == [(Kind.NAMESPACE, "late")]


def test_arg_without_default_is_dynamic() -> None:
    facts = ros1('<launch><arg name="a"/><node name="$(arg a)" pkg="p" type="t"/></launch>')
    assert [(use.value, use.dynamic) for use in facts.names] == [("$(arg a)", True)]


def test_nested_arg_resolves_when_fully_known() -> None:
    facts = ros1(
        '<launch><arg name="which" default="b"/><arg name="b" default="robot_b"/>'
        '<group ns="$(arg $(arg which))"/></launch>'
    )
    assert values(facts) == [(Kind.NAMESPACE, "robot_b")]


def test_arg_cycle_is_dynamic() -> None:
    facts = ros1(
        '<launch><arg name="a" default="$(arg b)"/><arg name="b" default="$(arg a)"/>'
        '<group ns="$(arg a)"/></launch>'
    )
    assert [use.dynamic for use in facts.names] == [True]


def test_conditional_arg_pair_resolves() -> None:
    facts = ros1(
        '<launch><arg name="sim" default="true"/>'
        '<arg name="ns" value="sim" if="$(arg sim)"/>'
        '<arg name="ns" value="real" unless="$(arg sim)"/>'
        '<group ns="$(arg ns)"/></launch>'
    )
    assert values(facts) == [(Kind.NAMESPACE, "sim")]


def test_statically_false_conditions_start_nothing_but_their_names_are_read() -> None:
    facts = ros1(
        '<launch><arg name="on" default="false"/>'
        '<group if="false"><node name="a" pkg="p" type="t"/></group>'
        '<node name="b" pkg="p" type="t" unless="true"/>'
        '<node name="c" pkg="p" type="t" if="$(arg on)"/>'
        '<node name="d" pkg="p" type="t" unless="$(arg on)"/>'
        '<node name="e" pkg="p" type="t" if="$(optenv USE_E true)"/>'
        "</launch>"
    )
    assert [node.name for node in facts.launch_nodes] == ["d", "e"]
    # Per-file rules see every branch's names: a typo in an off branch is still a typo.
    assert values(facts) == [(Kind.NODE, name) for name in "abcde"]


def test_unresolvable_substitutions_are_dynamic() -> None:
    for raw in (
        "$(find p)/x",
        "$(env R)",
        "$(optenv R r)",
        "$(anon n)",
        "$(eval 1 + 1)",
        "$(dirname)",
        "$(arg undefined)",
        "$(arg unclosed",
    ):
        [use] = ros1(f'<launch><node name="{raw}" pkg="p" type="t"/></launch>').names
        assert (use.value, use.dynamic) == (raw, True)


# -- ROS 2 ----------------------------------------------------------------------------------


def test_ros2_node() -> None:
    facts = ros2('<launch><node pkg="p" exec="e" name="n" namespace="ns"/></launch>')
    assert values(facts) == [(Kind.NODE, "n"), (Kind.NAMESPACE, "ns")]
    assert (node(facts).executable, node(facts).namespace) == ("e", "/ns")


def test_ros2_push_namespace_lasts_until_the_group_ends() -> None:
    facts = ros2(
        '<launch><group><push-ros-namespace namespace="a"/><push_ros_namespace namespace="b"/>'
        '<node pkg="p" exec="e" name="n1"/></group><node pkg="p" exec="e" name="n2"/></launch>'
    )
    assert namespaces(facts) == [("a", "/"), ("b", "/a"), ("n1", "/a/b"), ("n2", "/")]


def test_ros2_unscoped_group_leaks_namespace_and_variables() -> None:
    facts = ros2(
        '<launch><group scoped="false"><push-ros-namespace namespace="a"/>'
        '<let name="x" value="n"/></group><node pkg="p" exec="e" name="$(var x)"/></launch>'
    )
    assert namespaces(facts)[1:] == [("n", "/a")]


def test_ros2_let_is_visible_after_its_declaration_only() -> None:
    facts = ros2(
        '<launch><node pkg="p" exec="e" name="$(var x)"/><let name="x" value="a"/>'
        '<node pkg="p" exec="e" name="$(var x)"/></launch>'
    )
    assert [(use.value, use.dynamic) for use in facts.names] == [("$(var x)", True), ("a", False)]


def test_ros2_group_scopes_let() -> None:
    facts = ros2(
        '<launch><let name="x" value="out"/><group><let name="x" value="in"/></group>'
        '<node pkg="p" exec="e" name="$(var x)"/></launch>'
    )
    assert values(facts) == [(Kind.NODE, "out")]


def test_ros2_arg_default_does_not_override_let() -> None:
    facts = ros2(
        '<launch><let name="x" value="set"/><arg name="x" default="default"/>'
        '<node pkg="p" exec="e" name="$(var x)"/></launch>'
    )
    assert values(facts) == [(Kind.NODE, "set")]


def test_ros2_nested_params_join_with_dots() -> None:
    facts = ros2(
        '<launch><node pkg="p" exec="e" name="n"><param name="a"><param name="b" value="1"/>'
        '<param name="c"><param name="odom_frame" value="odom"/></param></param>'
        '<param from="$(find-pkg-share p)/params.yaml"/></node></launch>'
    )
    assert values(facts) == [
        (Kind.NODE, "n"),
        (Kind.PARAMETER, "a.b"),
        (Kind.PARAMETER, "a.c.odom_frame"),
        (Kind.FRAME, "odom"),
    ]
    assert node(facts).parameters == ("a.b", "a.c.odom_frame")


def test_ros2_ros_args_and_args() -> None:
    facts = ros2(
        '<launch><node pkg="p" exec="e" args="plain:=ignored --ros-args -r a:=b -- x:=y"'
        ' ros_args="--log-level rclcpp:=debug -r n:c:=d --remap __node:=m -p frame_id:=map"/>'
        "</launch>"
    )
    assert roles(facts) == [
        (Role.REMAP_FROM, "a"),
        (Role.REMAP_TO, "b"),
        (Role.REMAP_FROM, "c"),
        (Role.REMAP_TO, "d"),
        (Role.NODE_NAME, "m"),
        (Role.PARAMETER, "frame_id"),
        (Role.FRAME, "map"),
    ]
    assert node(facts).name == "m"


def test_ros2_set_remap_applies_to_later_nodes_in_the_group() -> None:
    facts = ros2(
        '<launch><group><set_remap from="/tf" to="tf"/><node pkg="p" exec="e"/></group>'
        '<node pkg="p" exec="e"/></launch>'
    )
    inside, outside = facts.launch_nodes
    assert [(remap.source, remap.target) for remap in inside.remaps] == [("/tf", "tf")]
    assert outside.remaps == ()


def test_ros2_composable_nodes_use_the_pushed_namespace() -> None:
    facts = ros2(
        '<launch><push-ros-namespace namespace="r"/>'
        '<node_container pkg="rclcpp_components" exec="component_container" name="c"'
        ' namespace="box"><composable_node pkg="p" plugin="p::A" name="a" namespace="cam">'
        '<remap from="in" to="out"/></composable_node></node_container>'
        '<load_composable_node target="c"><composable_node pkg="p" plugin="p::B" name="b"/>'
        "</load_composable_node></launch>"
    )
    assert [
        (launched.name, launched.executable, launched.namespace) for launched in facts.launch_nodes
    ] == [
        ("c", "component_container", "/r/box"),
        ("a", "p::A", "/r/cam"),
        ("b", "p::B", "/r"),
    ]
    assert [(remap.source, remap.target) for remap in facts.launch_nodes[1].remaps] == [
        ("in", "out")
    ]


def test_ros2_include_args_are_not_declarations() -> None:
    facts = ros2(
        '<launch><include file="x.launch.xml"><arg name="ns" value="a"/></include>'
        '<node pkg="p" exec="e" name="$(var ns)"/></launch>'
    )
    assert [use.dynamic for use in facts.names] == [True]


def test_ros2_conditions() -> None:
    facts = ros2(
        '<launch><arg name="sim" default="False"/>'
        '<node pkg="p" exec="e" name="a" if="$(var sim)"/>'
        '<node pkg="p" exec="e" name="b" unless="$(var sim)"/></launch>'
    )
    assert [node.name for node in facts.launch_nodes] == ["b"]
    assert values(facts) == [(Kind.NODE, "a"), (Kind.NODE, "b")]


def test_ros1_substitutions_are_dynamic_in_ros2_and_back() -> None:
    [use] = ros2(
        '<launch><let name="x" value="a"/><node pkg="p" exec="e" name="$(arg x)"/></launch>'
    ).names
    assert use.dynamic
    [use] = ros1(
        '<launch><arg name="x" default="a"/><node pkg="p" type="t" name="$(var x)"/></launch>'
    ).names
    assert use.dynamic


# -- syntax and generation -----------------------------------------------------------------


def test_xml_file_is_sniffed_as_ros2() -> None:
    facts = launch_xml.extract(
        "x.xml",
        b'<launch><node pkg="p" exec="e" namespace="n"/></launch>',
        None,
        Generation.ROS1,
    )
    assert facts.generation is Generation.ROS2
    assert values(facts) == [(Kind.NAMESPACE, "n")]


def test_plain_launch_extension_is_ros1_without_evidence() -> None:
    assert ros1("<launch/>").generation is Generation.ROS1
    assert ros2("<launch/>").generation is Generation.ROS2
    assert launch_xml.extract("x.xml", b"<launch/>", None, Generation.ROS2).generation is (
        Generation.ROS2
    )


def test_markers_decide_over_the_package() -> None:
    """Only roslaunch runs <node type=>: a ROS 1 file left in a ROS 2 package (moveit2's
    generate_state_database.launch) is judged by ROS 1's grammar, '~output_folder' too."""
    facts = ros1(
        '<launch><group ns="g"><node name="n" pkg="p" type="t">'
        '<remap from="~output_folder" to="out"/></node></group></launch>',
        package=Generation.ROS2,
    )
    assert facts.generation is Generation.ROS1
    assert node(facts).namespace == "/g"
    # Without markers the package decides.
    unmarked = ros1('<launch><group ns="g"/></launch>', package=Generation.ROS2)
    assert unmarked.generation is Generation.ROS2


def test_non_launch_root_yields_nothing() -> None:
    assert ros1('<robot><node name="n" pkg="p" type="t"/></robot>').names == ()


def test_evidence_votes() -> None:
    def vote(xml: str) -> Generation | None:
        return evidence.launch_xml_evidence(etree.fromstring(xml))

    assert vote('<launch><node type="t"/></launch>') is Generation.ROS1
    assert vote('<launch><include file="$(find p)/a.launch"/></launch>') is Generation.ROS1
    assert vote('<launch><let name="a" value="b"/></launch>') is Generation.ROS2
    assert vote('<launch><node exec="e" name="$(var n)"/></launch>') is Generation.ROS2
    assert vote('<launch><node type="t" exec="e"/></launch>') is None
    assert vote("<launch/>") is None


def test_extension_generation() -> None:
    assert evidence.extension_generation("a/b.launch") is Generation.ROS1
    assert evidence.extension_generation("a/b.test") is Generation.ROS1
    assert evidence.extension_generation("b.launch.xml") is Generation.ROS2
    assert evidence.extension_generation("b_launch.xml") is Generation.ROS2
    assert evidence.extension_generation("b.xml") is None


# -- substitution and command lines --------------------------------------------------------


def test_substitute() -> None:
    lookup = mapping_lookup({"a": Value("x"), "d": Value("$(env D)", dynamic=True)})
    assert substitute("/$(var a)/b", Dialect.ROS2, lookup) == Value("/x/b")
    assert substitute("$(var 'a')", Dialect.ROS2, lookup) == Value("x")
    assert substitute("$(var d)", Dialect.ROS2, lookup) == Value("$(var d)", dynamic=True)
    assert substitute("$(var a", Dialect.ROS2, lookup) == Value("$(var a", dynamic=True)
    assert substitute("${a}", Dialect.ROS2, lookup) == Value("${a}")  # not ROS 2 syntax
    assert substitute("$${a}", Dialect.XACRO, lookup) == Value("${a}")
    assert substitute("${a}", Dialect.XACRO, lambda space, name: Value(space)) == Value("property")
    assert substitute("$(arg a)", Dialect.XACRO, lambda space, name: Value(space)) == Value(ARG)
    assert substitute("${a*2}", Dialect.XACRO, lookup).dynamic


def test_split_words_keeps_substitutions_whole() -> None:
    words = split_words(Located("a $(eval 1 + (2)) ${x y} b", Span(1, 1, 1, 1)))
    assert [word.text for word in words] == ["a", "$(eval 1 + (2))", "${x y}", "b"]


def test_ros2_assignments_only_inside_ros_args() -> None:
    line = Located("x:=1 --ros-args -r a:=b --params-file f.yaml -p p:=2 -- y:=3", Span(1, 1, 1, 1))
    found = ros2_assignments(line, all_ros_args=False, bare=False)
    assert [(a.flag, a.key.text, a.value.text) for a in found] == [
        ("-r", "a", "b"),
        ("-p", "p", "2"),
    ]


# -- fixtures -------------------------------------------------------------------------------


def test_multi_robot_fixture() -> None:
    facts = launch_xml.extract(
        "multi_robot.launch",
        (FIXTURES / "multi_robot.launch").read_bytes(),
        None,
        Generation.ROS2,
    )
    assert facts.generation is Generation.ROS1
    assert [(launched.name, launched.namespace) for launched in facts.launch_nodes] == [
        ("robot_state_publisher", "/tb3_0"),
        ("amcl", "/tb3_0"),
        ("fake_node", "/tb3_1"),
        (None, "/"),  # $(anon rviz)
        ("odom_hz", "/"),
    ]  # teleop is dropped: use_teleop defaults to false
    amcl = facts.launch_nodes[1]
    assert [(remap.source, remap.target) for remap in amcl.remaps] == [
        ("clock", "/sim/clock"),
        ("scan", "base_scan"),
        ("map", "/map"),
        ("odom", "/tb3_0/odom"),
    ]
    frames = [(use.value, use.span) for use in facts.names if use.kind is Kind.FRAME]
    assert frames == [
        ("tb3_0/base_footprint", Span(24, 42, 24, 73)),
        ("/map", Span(25, 44, 25, 61)),
    ]
    [localization] = [use for use in facts.names if use.value == "localization"]
    assert (localization.kind, localization.span) == (Kind.NODE, Span(22, 25, 22, 37))


def test_bringup_fixture() -> None:
    facts = launch_xml.extract(
        "bringup.launch.xml",
        (FIXTURES / "bringup.launch.xml").read_bytes(),
        None,
        Generation.ROS1,
    )
    assert facts.generation is Generation.ROS2
    assert [(launched.name, launched.namespace) for launched in facts.launch_nodes] == [
        ("map_server", "/robot1"),
        ("controller_server", "/robot1"),
        ("image_container", "/robot1/perception"),
        ("rectify", "/robot1/camera"),
        ("lidar", "/front"),
    ]
    params = [use.value for use in facts.names if use.kind is Kind.PARAMETER]
    assert params == [
        "use_sim_time",
        "frame_id",
        "FollowPath.plugin",
        "FollowPath.robot_base_frame",
        "queue_size",
        "laser_frame_id",
    ]
    frames = [use.value for use in facts.names if use.kind is Kind.FRAME]
    assert frames == ["map", "base_link", "laser"]
