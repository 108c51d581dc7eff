"""URDF/XACRO extraction: link frames, gazebo plugin names, XACRO substitution."""

from __future__ import annotations

from pathlib import Path

from roslint_names.extract.launch import urdf
from roslint_names.model import FileFacts, Generation, Kind, Role, Span

FIXTURES = Path(__file__).parent / "fixtures" / "urdf"
XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def extract(xml: str, path: str = "r.urdf.xacro", package: Generation | None = None) -> FileFacts:
    return urdf.extract(path, xml.encode(), package, Generation.ROS1)


def values(facts: FileFacts) -> list[tuple[Kind, str]]:
    return [(use.kind, use.value) for use in facts.names]


def dynamic(facts: FileFacts) -> list[tuple[str, bool]]:
    return [(use.value, use.dynamic) for use in facts.names]


def plugin(body: str) -> str:
    return f'<robot><gazebo><plugin name="p" filename="libp.so">{body}</plugin></gazebo></robot>'


# -- links and XACRO ----------------------------------------------------------------------


def test_link_names_are_frames() -> None:
    facts = extract('<robot name="r"><link name="base_link"/><joint name="j"/></robot>')
    assert values(facts) == [(Kind.FRAME, "base_link")]
    assert facts.names[0].role is Role.FRAME


def test_property_and_arg_are_substituted() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:property name="base" value="base"/>'
        '<xacro:arg name="prefix" default="tb3_"/>'
        '<link name="$(arg prefix)${base}_link"/></robot>'
    )
    assert dynamic(facts) == [("tb3_base_link", False)]


def test_properties_may_refer_to_later_properties() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:property name="a" value="${{b}}_link"/>'
        '<link name="${a}"/><xacro:property name="b" value="base"/></robot>'
    )
    assert dynamic(facts) == [("base_link", False)]


def test_expressions_and_unknowns_are_dynamic() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:property name="n" value="2"/><xacro:property name="block">'
        "<origin/></xacro:property>"
        '<link name="wheel_${n*2}"/><link name="${missing}"/><link name="$(find pkg)"/>'
        '<link name="${block}"/></robot>'
    )
    assert [use.dynamic for use in facts.names] == [True, True, True, True]


def test_macro_parameters_are_dynamic_inside_the_macro() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:property name="base" value="base_link"/>'
        '<xacro:macro name="wheel" params="prefix *origin radius:=0.1">'
        '<xacro:property name="wheel" value="${prefix}_wheel"/>'
        '<xacro:property name="fixed" value="caster"/>'
        '<link name="${prefix}_link"/><link name="${wheel}"/><link name="${base}"/>'
        '<link name="${fixed}"/></xacro:macro>'
        '<xacro:wheel prefix="left"><origin/></xacro:wheel></robot>'
    )
    assert dynamic(facts) == [
        ("${prefix}_link", True),
        ("${wheel}", True),
        ("base_link", False),
        ("caster", False),
    ]


def test_macro_parameter_shadows_a_global_property() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:property name="prefix" value="global"/>'
        '<xacro:macro name="m" params="prefix"><link name="${prefix}"/></xacro:macro>'
        '<link name="${prefix}"/></robot>'
    )
    assert dynamic(facts) == [("${prefix}", True), ("global", False)]


def test_static_xacro_conditions_prune() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:arg name="lidar" default="false"/>'
        '<xacro:if value="$(arg lidar)"><link name="lidar_link"/></xacro:if>'
        '<xacro:unless value="$(arg lidar)"><link name="camera_link"/></xacro:unless>'
        '<xacro:if value="${x > 1}"><link name="maybe_link"/></xacro:if></robot>'
    )
    assert values(facts) == [(Kind.FRAME, "camera_link"), (Kind.FRAME, "maybe_link")]


def test_xacro_elements_are_not_links() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:link name="x"/><xacro:property name="link" value="y"/></robot>'
    )
    assert facts.names == ()


def test_old_xacro_namespace_uri() -> None:
    facts = extract(
        '<robot xmlns:xacro="http://ros.org/wiki/xacro">'
        '<xacro:property name="a" value="b"/><link name="${a}"/></robot>'
    )
    assert dynamic(facts) == [("b", False)]


def test_undeclared_xacro_prefix_is_a_parse_error() -> None:
    facts = extract('<robot><xacro:property name="a" value="b"/></robot>')
    assert len(facts.parse_errors) == 1


# -- gazebo_ros 1 -------------------------------------------------------------------------


def test_ros1_plugin_names() -> None:
    facts = extract(
        plugin(
            "<robotNamespace>/r1</robotNamespace><commandTopic>cmd_vel</commandTopic>"
            "<imageTopicName>image_raw</imageTopicName><topicName>imu</topicName>"
            "<serviceName>imu_service</serviceName><frameName>imu_link</frameName>"
            "<odometryFrame>odom</odometryFrame><leftJoint>wheel</leftJoint>"
            "<bodyName>imu_link</bodyName><updateRate>30</updateRate>"
        )
    )
    assert values(facts) == [
        (Kind.NAMESPACE, "/r1"),
        (Kind.TOPIC, "cmd_vel"),
        (Kind.TOPIC, "image_raw"),
        (Kind.TOPIC, "imu"),
        (Kind.SERVICE, "imu_service"),
        (Kind.FRAME, "imu_link"),
        (Kind.FRAME, "odom"),
    ]
    assert [use.namespace for use in facts.names if use.kind is Kind.TOPIC] == ["/r1"] * 3
    assert facts.generation is Generation.ROS1


def test_plugin_tags_outside_gazebo_are_ignored() -> None:
    assert (
        extract("<robot><topicName>imu</topicName><frame_name>x</frame_name></robot>").names == ()
    )


# -- gazebo_ros 2 -------------------------------------------------------------------------


def test_ros2_plugin_names() -> None:
    facts = extract(
        plugin(
            "<ros><namespace>demo</namespace><remapping>cmd_vel:=cmd_demo</remapping>"
            '<parameter name="use_sim_time" type="bool">true</parameter></ros>'
            "<odometry_frame>odom</odometry_frame><frame_name>chassis</frame_name>"
            "<publish_odom>true</publish_odom>"
        )
    )
    assert [(use.kind, use.role, use.value) for use in facts.names] == [
        (Kind.NAMESPACE, Role.NAMESPACE, "demo"),
        (Kind.TOPIC, Role.REMAP_FROM, "cmd_vel"),
        (Kind.TOPIC, Role.REMAP_TO, "cmd_demo"),
        (Kind.PARAMETER, Role.PARAMETER, "use_sim_time"),
        (Kind.FRAME, Role.FRAME, "odom"),
        (Kind.FRAME, Role.FRAME, "chassis"),
    ]
    assert [use.namespace for use in facts.names if use.kind is Kind.TOPIC] == ["/demo"] * 2
    assert facts.generation is Generation.ROS2


def test_remapping_spans_each_side() -> None:
    facts = extract(plugin("<ros>\n  <remapping> ~/out:=scan </remapping></ros>"))
    assert [(use.value, use.span) for use in facts.names] == [
        ("~/out", Span(2, 15, 2, 20)),
        ("scan", Span(2, 22, 2, 26)),
    ]


def test_legacy_argument_forms() -> None:
    facts = extract(
        plugin(
            "<ros><argument>--ros-args -r odom:=odom_demo --remap n:a:=b</argument>"
            "<argument>__ns:=/demo</argument><argument>/demo/cmd:=cmd_demo</argument></ros>"
        )
    )
    assert [(use.role, use.value) for use in facts.names] == [
        (Role.REMAP_FROM, "odom"),
        (Role.REMAP_TO, "odom_demo"),
        (Role.REMAP_FROM, "a"),
        (Role.REMAP_TO, "b"),
        (Role.NAMESPACE, "/demo"),
        (Role.REMAP_FROM, "/demo/cmd"),
        (Role.REMAP_TO, "cmd_demo"),
    ]


def test_xacro_substitution_in_plugin_text() -> None:
    facts = extract(
        f'<robot {XACRO}><xacro:arg name="ns" default="tb3"/>'
        '<xacro:property name="odom" value="odom"/>'
        '<xacro:macro name="drive" params="prefix"><gazebo><plugin name="d" filename="d.so">'
        "<ros><namespace>$(arg ns)</namespace><remapping>odom:=${prefix}odom</remapping></ros>"
        "<odometry_frame>${odom}</odometry_frame></plugin></gazebo></xacro:macro></robot>"
    )
    assert dynamic(facts) == [
        ("tb3", False),
        ("odom", False),
        ("${prefix}odom", True),
        ("odom", False),
    ]


# -- generation -----------------------------------------------------------------------------


def test_generation_order() -> None:
    ros1_file = plugin("<robotNamespace>r</robotNamespace>")
    assert extract(ros1_file, package=Generation.ROS2).generation is Generation.ROS2
    assert extract(ros1_file).generation is Generation.ROS1
    no_evidence = '<robot><link name="a"/></robot>'
    assert urdf.extract("r.urdf", no_evidence.encode(), None, Generation.ROS2).generation is (
        Generation.ROS2
    )


# -- fixtures -------------------------------------------------------------------------------


def test_diff_drive_fixture() -> None:
    facts = urdf.extract(
        "diff_drive.urdf", (FIXTURES / "diff_drive.urdf").read_bytes(), None, Generation.ROS2
    )
    assert facts.generation is Generation.ROS1
    frames = [use.value for use in facts.names if use.kind is Kind.FRAME]
    assert frames == [
        "base_footprint",
        "base_link",
        "wheel_left_link",
        "wheel_right_link",
        "imu_link",
        "odom",
        "base_footprint",
        "/imu_link",
    ]
    topics = [(use.value, use.namespace) for use in facts.names if use.kind is Kind.TOPIC]
    assert topics == [("cmd_vel", "/burger"), ("odom", "/burger"), ("imu", None)]
    [service] = [use for use in facts.names if use.kind is Kind.SERVICE]
    assert (service.value, service.span) == ("imu_service", Span(42, 20, 42, 31))


def test_xacro_fixture() -> None:
    facts = urdf.extract(
        "robot.urdf.xacro", (FIXTURES / "robot.urdf.xacro").read_bytes(), None, Generation.ROS1
    )
    assert facts.generation is Generation.ROS2
    assert dynamic(facts) == [
        ("base_footprint", False),
        ("base_link", False),
        ("${prefix}_wheel_link", True),
        ("caster_base_link", False),
        ("/waffle", False),
        ("cmd_vel", False),
        ("cmd_demo", False),
        ("odom", False),
        ("odom_demo", False),
        ("odom", False),
        ("base_link", False),
        ("~/out", False),
        ("scan", False),
        ("/sensors", False),
        ("base_scan", False),
    ]  # never_built is under <xacro:if value="false">
    [namespace] = [use for use in facts.names if use.kind is Kind.NAMESPACE][:1]
    assert (namespace.value, namespace.span) == ("/waffle", Span(37, 20, 37, 37))
