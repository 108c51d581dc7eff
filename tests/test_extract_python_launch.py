"""ROS 2 Python launch files: the facts launch XML and YAML produce, from launch.py.

The fixture follows nav2_bringup's launch files (ros-navigation/navigation2); short
sources pin one launch semantic each.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from roslint_names.extract.python.extract import extract
from roslint_names.model import FileFacts, Generation, Language, LaunchNode

FIXTURES = Path(__file__).parent / "fixtures" / "python"
HEADER = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction, IncludeLaunchDescription
from launch.actions import OpaqueFunction, SetLaunchConfiguration
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution, TextSubstitution
from launch_ros.actions import LoadComposableNodes, Node, PushRosNamespace, SetParameter
from launch_ros.descriptions import ComposableNode
"""


def launch(body: str, path: str = "robot.launch.py") -> FileFacts:
    return extract(path, (HEADER + body).encode(), Generation.ROS2, Generation.ROS2)


def node_tuple(node: LaunchNode) -> tuple[Any, ...]:
    remaps = tuple((remap.source, remap.target) for remap in node.remaps)
    return (node.package, node.executable, node.name, node.namespace, remaps, node.parameters)


def nodes(facts: FileFacts) -> list[tuple[Any, ...]]:
    return [node_tuple(node) for node in facts.launch_nodes]


def names(facts: FileFacts) -> list[tuple[str, str, str, str | None]]:
    """(kind, role, value, namespace) of the static names, in file order."""
    return [
        (use.kind.value, use.role.value, use.value, use.namespace)
        for use in facts.names
        if not use.dynamic
    ]


def test_nav2_style_bringup_launch_nodes() -> None:
    path = FIXTURES / "nav2_style_bringup.launch.py"
    facts = extract(str(path), path.read_bytes(), None, Generation.ROS2)
    assert facts.language is Language.LAUNCH_PYTHON
    assert facts.generation is Generation.ROS2
    tf = (("/tf", "tf"), ("/tf_static", "tf_static"))
    scan = (("scan", "scan_filtered"),)
    assert nodes(facts) == [
        (
            "nav2_amcl",
            "amcl",
            "amcl",
            "/robot1",  # PushRosNamespace(LaunchConfiguration) -> the declared default
            scan + tf,  # SetRemap of the group first, then the node's own
            ("use_sim_time", "base_frame_id", "global_frame_id"),
        ),
        (
            "nav2_map_server",
            "map_server",
            "map_server",
            "/robot1",
            scan + tf,
            ("yaml_filename", "topic.name"),
        ),
        ("rclcpp_components", "component_container", "nav2_container", "/robot1", scan, ()),
        # a composable node gets the pushed namespace, not its container's
        (
            "nav2_controller",
            "nav2_controller::ControllerServer",
            "controller_server",
            "/robot1",
            (*scan, ("cmd_vel", "cmd_vel_nav")),
            (),
        ),
        # rviz2 is left out: IfCondition(use_rviz) whose default is 'false'
        ("nav2_lifecycle_manager", "lifecycle_manager", "lifecycle_manager", "/global", (), ()),
    ]


def test_nav2_style_bringup_names_and_spans() -> None:
    path = FIXTURES / "nav2_style_bringup.launch.py"
    facts = extract(str(path), path.read_bytes(), None, Generation.ROS2)
    found = [
        (use.kind.value, use.role.value, use.value, use.namespace, use.span.line, use.span.column)
        for use in facts.names
    ]
    assert found == [
        # the shared remappings list: one fact per literal, not one per node using it
        ("topic", "remap-from", "/tf", "/robot1", 14, 20),
        ("topic", "remap-to", "tf", "/robot1", 14, 27),
        ("topic", "remap-from", "/tf_static", "/robot1", 14, 35),
        ("topic", "remap-to", "tf_static", "/robot1", 14, 49),
        ("namespace", "namespace", "robot1", "/", 24, 30),  # at the argument `namespace`
        ("topic", "remap-from", "scan", "/robot1", 25, 26),
        ("topic", "remap-to", "scan_filtered", "/robot1", 25, 38),
        ("node", "node-name", "amcl", "/robot1", 29, 22),
        ("parameter", "parameter", "use_sim_time", "/robot1/amcl", 32, 25),
        ("parameter", "parameter", "base_frame_id", "/robot1/amcl", 33, 25),
        ("frame", "frame", "base_footprint", "/robot1/amcl", 33, 42),
        ("parameter", "parameter", "global_frame_id", "/robot1/amcl", 34, 25),
        ("frame", "frame", "/map", "/robot1/amcl", 34, 44),
        ("node", "node-name", "map_server", "/robot1", 42, 22),
        ("parameter", "parameter", "yaml_filename", "/robot1/map_server", 43, 30),
        ("parameter", "parameter", "topic.name", "/robot1/map_server", 43, 69),
        ("node", "node-name", "nav2_container", "/robot1", 47, 22),
        ("namespace", "namespace", "", "/robot1", 48, 27),
        ("node", "node-name", "controller_server", "/robot1", 55, 30),
        ("topic", "remap-from", "cmd_vel", "/robot1", 56, 38),
        ("topic", "remap-to", "cmd_vel_nav", "/robot1", 56, 49),
        # off by default (IfCondition(use_rviz)): it starts nothing, its name is checked
        ("node", "node-name", "rviz2", "/", 67, 14),
        ("node", "node-name", "lifecycle_manager", "/global", 80, 18),
        ("namespace", "namespace", "/global", "/", 81, 23),
    ]


def test_group_scopes_pushed_namespaces_and_remaps() -> None:
    facts = launch(
        """
def generate_launch_description():
    return LaunchDescription([
        GroupAction([
            PushRosNamespace('robot1'),
            PushRosNamespace('arm'),
            Node(package='a', executable='a', name='inner'),
        ]),
        Node(package='b', executable='b', name='outer'),
        PushRosNamespace('/abs'),
        Node(package='c', executable='c', name='after_push', namespace='rel'),
        Node(package='d', executable='d', name='absolute', namespace='/top'),
    ])
"""
    )
    assert [(node[2], node[3]) for node in nodes(facts)] == [
        ("inner", "/robot1/arm"),
        ("outer", "/"),
        ("after_push", "/abs/rel"),
        ("absolute", "/top"),
    ]


def test_launch_configurations_resolve_or_stay_dynamic() -> None:
    facts = launch(
        """
def generate_launch_description():
    robot = LaunchConfiguration('robot')
    return LaunchDescription([
        DeclareLaunchArgument('robot', default_value='tb3'),
        DeclareLaunchArgument('undeclared_default'),
        DeclareLaunchArgument('twice', default_value='a'),
        DeclareLaunchArgument('twice', default_value='b'),
        Node(package='p', executable='e', name=[robot, '_driver']),
        Node(package='p', executable='e', name=LaunchConfiguration('undeclared_default')),
        Node(package='p', executable='e', name=LaunchConfiguration('twice')),
        Node(package='p', executable='e', name=LaunchConfiguration('nope', default='fallback')),
        Node(package='p', executable='e', name=TextSubstitution(text='texty')),
        Node(package='p', executable='e', name=PathJoinSubstitution(['a', 'b'])),
        GroupAction([Node(package='p', executable='e', name=robot)],
                    launch_configurations={'robot': 'in_group'}),
        SetLaunchConfiguration('robot', 'let'),
        Node(package='p', executable='e', name=robot),
    ])
"""
    )
    assert [node[2] for node in nodes(facts)] == [
        "tb3_driver",
        None,
        None,
        "fallback",
        "texty",
        None,
        "in_group",
        "let",
    ]
    dynamic = [use.value for use in facts.names if use.dynamic]
    assert dynamic == [
        "LaunchConfiguration('undeclared_default')",
        "LaunchConfiguration('twice')",
        "PathJoinSubstitution(['a', 'b'])",
    ]


def test_static_conditions_skip_like_launch_xml() -> None:
    facts = launch(
        """
def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('use_a', default_value='true'),
        Node(package='p', executable='e', name='on', condition=IfCondition('true')),
        Node(package='p', executable='e', name='off', condition=IfCondition('false')),
        Node(package='p', executable='e', name='unless_on',
             condition=UnlessCondition(LaunchConfiguration('use_a'))),
        Node(package='p', executable='e', name='maybe',
             condition=IfCondition(LaunchConfiguration('unknown'))),
    ])
"""
    )
    assert [node[2] for node in nodes(facts)] == ["on", "maybe"]


def test_lists_built_in_steps_helpers_and_opaque_functions() -> None:
    facts = launch(
        """
def make_driver(name):
    return Node(package='drv', executable='drv', name=name)

def launch_setup(context):
    return [Node(package='os', executable='os', name='from_opaque')]

def generate_launch_description():
    declared = []
    declared.append(DeclareLaunchArgument('ns', default_value='fleet'))
    nodes = [PushRosNamespace(LaunchConfiguration('ns'))]
    nodes.append(make_driver('driver'))
    nodes += []
    return LaunchDescription(declared + nodes + [OpaqueFunction(function=launch_setup)])
"""
    )
    # `nodes += []` rebinds `nodes`: its contents are no longer known, so the push and the
    # helper's node are walked as unreached (unknown namespace; the helper's `name` is its
    # parameter, dynamic); the opaque function's node is reached.
    assert [(node[2], node[3]) for node in nodes(facts)] == [("from_opaque", "/"), (None, "")]


def test_add_action_order_matters_for_pushes() -> None:
    facts = launch(
        """
def generate_launch_description():
    ld = LaunchDescription()
    ld.add_action(Node(package='p', executable='e', name='before'))
    ld.add_action(PushRosNamespace('pushed'))
    ld.add_action(Node(package='p', executable='e', name='after'))
    return ld
"""
    )
    assert [(node[2], node[3]) for node in nodes(facts)] == [
        ("before", "/"),
        ("after", "/pushed"),
    ]


def test_composable_nodes_loaded_later_and_set_parameter() -> None:
    facts = launch(
        """
def generate_launch_description():
    return LaunchDescription([
        PushRosNamespace('cam'),
        SetParameter(name='use_sim_time', value=True),
        SetParameter('frame_id', '/camera'),
        LoadComposableNodes(
            target_container='container',
            composable_node_descriptions=[
                ComposableNode(package='image_proc', plugin='image_proc::RectifyNode',
                               name='rectify', namespace='left',
                               parameters=[{'queue_size': 5, 'camera.frame_id': 'cam_link'}]),
            ]),
    ])
"""
    )
    assert nodes(facts) == [
        (
            "image_proc",
            "image_proc::RectifyNode",
            "rectify",
            "/cam/left",
            (),
            ("queue_size", "camera.frame_id"),
        ),
    ]
    assert names(facts) == [
        ("namespace", "namespace", "cam", "/"),
        ("parameter", "parameter", "use_sim_time", "/cam"),
        ("parameter", "parameter", "frame_id", "/cam"),
        ("frame", "frame", "/camera", "/cam"),
        ("node", "node-name", "rectify", "/cam/left"),
        ("namespace", "namespace", "left", "/cam"),
        ("parameter", "parameter", "queue_size", "/cam/left/rectify"),
        ("parameter", "parameter", "camera.frame_id", "/cam/left/rectify"),
        ("frame", "frame", "cam_link", "/cam/left/rectify"),
    ]


def test_include_launch_arguments_namespace_and_frames() -> None:
    facts = launch(
        """
from launch.launch_description_sources import PythonLaunchDescriptionSource

def generate_launch_description():
    return LaunchDescription([
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource('nav.launch.py'),
            launch_arguments={'namespace': 'robot2', 'use_namespace': 'true',
                              'base_frame': '/base_link', 'map': 'map.yaml'}.items()),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource('arm.launch.py'),
            launch_arguments=[('robot_namespace', 'arm')]),
    ])
"""
    )
    assert names(facts) == [
        ("namespace", "namespace", "robot2", "/"),
        ("frame", "frame", "/base_link", "/"),
        ("namespace", "namespace", "arm", "/"),
    ]


def test_pre_foxy_keywords_and_unreached_nodes() -> None:
    facts = launch(
        """
def helper_nodes(robots):
    return [Node(package='p', node_executable='e', node_name='old', node_namespace='/legacy')
            for robot in robots]

def generate_launch_description():
    return LaunchDescription([])
""",
        path="helpers.py",
    )
    assert nodes(facts) == [("p", "e", "old", "/legacy", (), ())]
    assert facts.language is Language.LAUNCH_PYTHON  # defines generate_launch_description


def test_launch_helper_module_is_a_launch_file() -> None:
    """A module building launch_ros actions without rospy/rclpy code is launch code."""
    source = "from launch_ros.actions import Node\n\ndef nodes():\n"
    source += "    return [Node(package='p', executable='e', remappings=[('a', 'b')])]\n"
    facts = extract("helpers.py", source.encode(), None, Generation.ROS2)
    assert facts.language is Language.LAUNCH_PYTHON
    assert nodes(facts) == [("p", "e", None, "", (("a", "b"),), ())]


def test_rules_treat_launch_python_like_launch_xml(lint_text: Any) -> None:
    """RN202 never fires on launch remaps; parameter names and remap sources are spelled
    by the node's code, so RN203 leaves them alone; frame ids and node names are judged."""
    source = (
        HEADER
        + """
def generate_launch_description():
    return LaunchDescription([
        Node(package='robot_localization', executable='ekf_node', name='ekf',
             parameters=[{'odomFrame': 'odom', 'frame_id': '/world'}],
             remappings=[('/odometry/filtered', '/odom'), ('cmdVel', 'cmd_vel')]),
    ])
"""
    )
    codes = lint_text(source, "src/robot_bringup/launch/ekf.launch.py", 2, "--select", "ALL")
    assert codes == ["RN205"]


def test_launch_py_never_raises_on_odd_shapes() -> None:
    facts = launch(
        """
def generate_launch_description():
    x = LaunchDescription(*args)
    y = GroupAction(actions=y)
    Node(**kwargs)
    Node(package=1, name=None, remappings=[1, (2,), ('a',)], parameters=[{1: 2}, 'f.yaml'])
    return LaunchDescription([x, y, GroupAction(), PushRosNamespace(), SetParameter()])
"""
    )
    assert isinstance(facts, FileFacts)


def test_undecodable_escape_in_an_argument_name_does_not_raise() -> None:
    """libcst parses ``"\\N{bogus}"``; evaluating it raises, which escaped the extractor."""
    facts = launch(
        "def generate_launch_description():\n"
        '    return LaunchDescription([DeclareLaunchArgument("\\N{bogus}", default_value="r"),\n'
        '        Node(package="p", executable="e", name="n")])\n'
    )
    assert nodes(facts) == [("p", "e", "n", "/", (), ())]


@pytest.mark.parametrize(
    "action",
    [
        "IncludeLaunchDescription(())",
        'Node(package="p", executable="e", name=())',
        'Node(package="p", executable="e", remappings=[((), "b")])',
    ],
)
def test_empty_tuple_argument_does_not_raise(action: str) -> None:
    """A span starts inside an expression's own parentheses, but ``()`` cannot lose them:
    libcst's CSTValidationError escaped the extractor (found by atheris)."""
    facts = launch(
        f"def generate_launch_description():\n    return LaunchDescription([{action}])\n"
    )
    assert facts.parse_errors == ()
