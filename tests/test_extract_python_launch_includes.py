"""ROS 2 launch.py includes: where the included file is, and the scope it gets (issue 5).

Fixtures follow nav2_bringup (ros-navigation/navigation2), turtlebot3_bringup and
turtlebot3_gazebo (ROBOTIS-GIT); short sources pin one form or one semantic each.
"""

from __future__ import annotations

import gc
from pathlib import Path

import pytest

from roslint_names.extract.python.extract import extract
from roslint_names.model import FileFacts, Generation, InPackage, LaunchInclude, ParseError, Span

FIXTURES = Path(__file__).parent / "fixtures" / "python"
HEADER = """import os
from pathlib import Path

import launch
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction, IncludeLaunchDescription
from launch.actions import SetLaunchConfiguration
from launch.conditions import IfCondition
from launch.launch_description_sources import AnyLaunchDescriptionSource
from launch.launch_description_sources import FrontendLaunchDescriptionSource
from launch.launch_description_sources import LaunchDescriptionSource
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch.substitutions import ThisLaunchFileDir
from launch_ros.actions import Node, PushRosNamespace, SetRemap
from launch_ros.substitutions import FindPackageShare
from launch_xml.launch_description_sources import XMLLaunchDescriptionSource
from launch_yaml.launch_description_sources import YAMLLaunchDescriptionSource
"""

Arguments = tuple[tuple[str, str], ...]


def launch(body: str, arguments: Arguments = (), path: str = "robot.launch.py") -> FileFacts:
    data = (HEADER + body).encode()
    return extract(path, data, Generation.ROS2, Generation.ROS2, arguments=arguments)


def fixture(name: str, arguments: Arguments = ()) -> FileFacts:
    path = FIXTURES / name
    return extract(str(path), path.read_bytes(), None, Generation.ROS2, arguments=arguments)


def where(include: LaunchInclude) -> tuple[str | None, str | None, str, bool]:
    return (include.package, include.path, include.namespace, include.anchored)


def located(facts: FileFacts) -> list[tuple[str | None, str | None]]:
    return [(include.package, include.path) for include in facts.includes]


def source(expression: str, prelude: str = "") -> tuple[str | None, str | None]:
    """(package, path) of one include whose launch_description_source is ``expression``."""
    facts = launch(
        f"""
{prelude}
def generate_launch_description():
    return LaunchDescription([IncludeLaunchDescription({expression})])
"""
    )
    assert len(facts.includes) == 1
    return facts.includes[0].package, facts.includes[0].path


# -- real launch files -------------------------------------------------------------------


def test_nav2_humble_bringup_includes_in_their_group() -> None:
    facts = fixture("nav2_humble_bringup_launch.py")
    # slam_launch.py is left out: IfCondition(slam) with slam's default 'False'; the push
    # is left out too: IfCondition(use_namespace) with 'false'.
    assert [where(include) for include in facts.includes] == [
        ("nav2_bringup", "launch/localization_launch.py", "/", False),
        ("nav2_bringup", "launch/navigation_launch.py", "/", False),
    ]
    localization = facts.includes[0]
    assert localization.span == Span(85, 17, 85, 98)  # the source argument
    # The explicit arguments and every configuration of the includer, sorted; 'map' has
    # no default; params_file is nav2_bringup's params/nav2_params.yaml (its default, built
    # with os.path.join from the package's share directory), handed over as that file.
    assert localization.arguments == (
        ("autostart", "true"),
        ("container_name", "nav2_container"),
        ("map", None),
        ("namespace", ""),
        ("params_file", InPackage("nav2_bringup", "params/nav2_params.yaml")),
        ("slam", "False"),
        ("use_composition", "True"),
        ("use_namespace", "false"),
        ("use_sim_time", "false"),
    )
    assert localization.remaps == ()  # the node's own remappings are not the group's


def test_nav2_humble_bringup_specialised_for_a_namespaced_robot() -> None:
    arguments = (
        ("namespace", "robot3"),
        ("slam", "True"),
        ("use_composition", "False"),
        ("use_namespace", "true"),
    )
    facts = fixture("nav2_humble_bringup_launch.py", arguments)
    assert [where(include) for include in facts.includes] == [
        ("nav2_bringup", "launch/slam_launch.py", "/robot3", False),
        ("nav2_bringup", "launch/localization_launch.py", "/robot3", False),
        ("nav2_bringup", "launch/navigation_launch.py", "/robot3", False),
    ]
    assert dict(facts.includes[2].arguments)["namespace"] == "robot3"
    assert dict(facts.includes[2].arguments)["use_composition"] == "False"
    assert facts.launch_nodes == ()  # the container: IfCondition(use_composition) now false


def test_turtlebot3_robot_includes_this_directory_and_a_driver_package() -> None:
    facts = fixture("tb3_robot.launch.py")
    assert [where(include) for include in facts.includes] == [
        (None, "turtlebot3_state_publisher.launch.py", "/", False),
        ("hls_lfcd_lds_driver", "launch/hlds_laser.launch.py", "/", False),
    ]
    assert facts.includes[1].arguments == (
        ("frame_id", "base_scan"),
        ("namespace", ""),
        ("port", "/dev/ttyUSB0"),
        ("usb_port", "/dev/ttyACM0"),
        ("use_sim_time", "false"),
    )
    specialised = fixture("tb3_robot.launch.py", (("namespace", "tb3_1"),))
    assert [include.namespace for include in specialised.includes] == ["/tb3_1", "/tb3_1"]
    assert dict(specialised.includes[0].arguments)["namespace"] == "tb3_1"
    assert [node.namespace for node in specialised.launch_nodes] == ["/tb3_1"]


def test_turtlebot3_world_directory_variables_fstrings_and_plus() -> None:
    facts = fixture("tb3_world.launch.py")
    assert located(facts) == [
        ("ros_gz_sim", "launch/gz_sim.launch.py"),  # os.path.join(module constant, ...)
        ("ros_gz_sim", "launch/gz_sim.launch.py"),  # f"{ROS_GZ_SIM}/launch/..."
        ("turtlebot3_gazebo", "launch/spawn_turtlebot3.launch.py"),  # dir + "/name"
        ("turtlebot3_gazebo", "launch/robot_state_publisher.launch.py"),
    ]
    # gz_args of the first include holds a package path: handed over as unknown.
    assert facts.includes[0].arguments == (("gz_args", None), ("on_exit_shutdown", "true"))
    spawn = dict(facts.includes[2].arguments)
    assert (spawn["x_pose"], spawn["y_pose"]) == ("-2.0", "-0.5")


def test_multi_robot_includes_one_file_in_two_namespaces() -> None:
    facts = fixture("multi_robot.launch.py")
    assert [where(include) for include in facts.includes] == [
        ("nav2_bringup", "launch/bringup_launch.py", "/robot1", False),
        ("nav2_bringup", "launch/bringup_launch.py", "/fleet/robot2", True),  # pushed '/fleet'
    ]
    first, second = facts.includes
    assert [(remap.source, remap.target) for remap in first.remaps] == [("/tf", "tf")]
    assert second.remaps == ()  # SetRemap stays in robot1's group
    assert first.arguments == (
        ("namespace", "robot1"),
        ("use_namespace", "True"),
        ("use_sim_time", "true"),
    )
    assert dict(second.arguments)["namespace"] == "robot2"  # a list of tuples
    assert first.span.line != second.span.line
    # The namespaces handed over are still names of this file.
    namespaces = [use.value for use in facts.names if use.kind.value == "namespace"]
    assert namespaces == ["robot1", "robot1", "/fleet", "robot2", "robot2"]


def test_a_helper_called_per_robot_binds_its_parameters_per_call() -> None:
    """Multi-robot launch files build each robot's group in a helper of the file."""
    facts = launch(
        """
def robot(name, x_pose='0.0', namespace_prefix=''):
    return GroupAction([
        PushRosNamespace(namespace_prefix + name),
        SetRemap(src='/tf', dst='tf'),
        IncludeLaunchDescription(
            PathJoinSubstitution([FindPackageShare('tb3_sim'), 'launch', 'spawn.launch.py']),
            launch_arguments={'x_pose': x_pose, 'robot_name': f'{name}_bot'}.items()),
        Node(package='tb3', executable='driver', name=f'{name}_driver'),
    ])

def generate_launch_description():
    return LaunchDescription([
        robot('robot1'),
        robot('robot2', x_pose='1.5'),
        robot(LaunchConfiguration('unknown')),
    ])
"""
    )
    assert [(include.namespace, dict(include.arguments)) for include in facts.includes] == [
        ("/robot1", {"robot_name": "robot1_bot", "x_pose": "0.0"}),
        ("/robot2", {"robot_name": "robot2_bot", "x_pose": "1.5"}),
        ("", {"robot_name": None, "x_pose": "0.0"}),
    ]
    assert [(node.name, node.namespace) for node in facts.launch_nodes] == [
        ("robot1_driver", "/robot1"),
        ("robot2_driver", "/robot2"),
        (None, ""),
    ]


# -- path forms --------------------------------------------------------------------------

SHARE = "get_package_share_directory('pkg')"


@pytest.mark.parametrize(
    ("expression", "expected"),
    [
        (
            "PythonLaunchDescriptionSource(PathJoinSubstitution("
            "[FindPackageShare('pkg'), 'launch', 'a.launch.py']))",
            ("pkg", "launch/a.launch.py"),
        ),
        (
            "PythonLaunchDescriptionSource([FindPackageShare('pkg'), '/launch/a.launch.py'])",
            ("pkg", "launch/a.launch.py"),
        ),
        (
            "PythonLaunchDescriptionSource(PathJoinSubstitution("
            "[FindPackageShare(package='pkg'), 'launch', 'sub/../a.launch.py']))",
            ("pkg", "launch/a.launch.py"),
        ),
        (
            f"PythonLaunchDescriptionSource(os.path.join({SHARE}, 'launch', 'a.py'))",
            ("pkg", "launch/a.py"),
        ),
        (
            f"XMLLaunchDescriptionSource({SHARE} + '/launch/a.launch.xml')",
            ("pkg", "launch/a.launch.xml"),
        ),
        (f"YAMLLaunchDescriptionSource(f'{{{SHARE}}}/a.launch.yaml')", ("pkg", "a.launch.yaml")),
        (f"FrontendLaunchDescriptionSource(os.path.join({SHARE}, 'a.xml'))", ("pkg", "a.xml")),
        (f"AnyLaunchDescriptionSource(os.path.join({SHARE}, 'a.py'))", ("pkg", "a.py")),
        # Humble and later: a bare path or substitution list
        ("[FindPackageShare('pkg'), '/launch/a.launch.py']", ("pkg", "launch/a.launch.py")),
        (
            "launch_description_source=PathJoinSubstitution([FindPackageShare('pkg'), 'a.py'])",
            ("pkg", "a.py"),
        ),
        (
            "PythonLaunchDescriptionSource(os.path.join(ThisLaunchFileDir(), 'b.py'))",
            (None, "b.py"),
        ),
        (
            "PythonLaunchDescriptionSource([ThisLaunchFileDir(), '/../b.launch.py'])",
            (None, "../b.launch.py"),
        ),
        (
            "PythonLaunchDescriptionSource("
            "os.path.join(os.path.dirname(os.path.realpath(__file__)), 'sub', 'c.py'))",
            (None, "sub/c.py"),
        ),
        ("PythonLaunchDescriptionSource(str(Path(__file__).parent / 'c.py'))", (None, "c.py")),
        (
            "PythonLaunchDescriptionSource(str(Path(__file__).parent.parent / 'c.py'))",
            (None, "../c.py"),
        ),
        (
            "PythonLaunchDescriptionSource('/opt/ros/share/x/a.launch.py')",
            (None, "/opt/ros/share/x/a.launch.py"),
        ),
        # Relative to launch's working directory, not to this file: not locatable.
        ("PythonLaunchDescriptionSource('a.launch.py')", (None, None)),
        # A name glued to the share directory's own is no file of the package.
        ("PythonLaunchDescriptionSource([FindPackageShare('pkg'), 'a.launch.py'])", ("pkg", None)),
        # The share directory itself, or above it: not a file we locate.
        ("PythonLaunchDescriptionSource(FindPackageShare('pkg'))", ("pkg", None)),
        (f"PythonLaunchDescriptionSource(os.path.join({SHARE}, '..', 'x', 'a.py'))", ("pkg", None)),
    ],
)
def test_include_path_forms(expression: str, expected: tuple[str | None, str | None]) -> None:
    assert source(expression) == expected


def test_include_paths_through_module_and_function_variables() -> None:
    """navigation2's nav2_bringup: directories in variables, joined with the file name."""
    prelude = f"""
BRINGUP_DIR = {SHARE}
LAUNCH_DIR = os.path.join(BRINGUP_DIR, 'launch')
"""
    expression = "PythonLaunchDescriptionSource(rviz_source)"
    facts = launch(
        f"""{prelude}
def generate_launch_description():
    rviz_launch = os.path.join(LAUNCH_DIR, 'rviz_launch.py')
    rviz_source = PythonLaunchDescriptionSource(rviz_launch)
    local_dir = os.path.join(get_package_share_directory('other'), 'launch')
    return LaunchDescription([
        IncludeLaunchDescription({expression}.launch_file_path),
        IncludeLaunchDescription(rviz_source),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(f'{{local_dir}}/x.launch.py')),
        launch.actions.IncludeLaunchDescription(os.path.join(local_dir, 'y.launch.py')),
    ])
"""
    )
    assert located(facts) == [
        (None, None),  # an attribute of the source: not evaluated
        ("pkg", "launch/rviz_launch.py"),
        ("other", "launch/x.launch.py"),
        ("other", "launch/y.launch.py"),
    ]


def test_launch_configurations_in_paths() -> None:
    facts = launch(
        """
def generate_launch_description():
    pkg = LaunchConfiguration('description_package')
    return LaunchDescription([
        DeclareLaunchArgument('description_package', default_value='robot_description'),
        DeclareLaunchArgument('launch_file', default_value=PathJoinSubstitution(
            [FindPackageShare('robot_bringup'), 'launch', 'default.launch.py'])),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(
            PathJoinSubstitution([FindPackageShare(pkg), 'launch', 'view.launch.py']))),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(
            [FindPackageShare('fixed'), '/launch/', LaunchConfiguration('unknown_file')])),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(
            PathJoinSubstitution([FindPackageShare(LaunchConfiguration('unknown_pkg')), 'a.py']))),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(LaunchConfiguration('launch_file'))),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(
            LaunchConfiguration('other_file', default=[FindPackageShare('d'), '/a.py']))),
    ])
"""
    )
    assert located(facts) == [
        ("robot_description", "launch/view.launch.py"),  # a static package configuration
        ("fixed", None),  # the package is known, the file is not
        (None, None),  # the package is not known: nothing is
        ("robot_bringup", "launch/default.launch.py"),  # a declared default that is a path
        ("d", "a.py"),  # LaunchConfiguration(default=)
    ]
    specialised = launch(
        """
def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('description_package', default_value='robot_description'),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(PathJoinSubstitution(
            [FindPackageShare(LaunchConfiguration('description_package')), 'view.launch.py']))),
    ])
""",
        arguments=(("description_package", "other_description"),),
    )
    assert located(specialised) == [("other_description", "view.launch.py")]


def test_dynamic_paths_stay_unknown() -> None:
    facts = launch(
        """
import sys

def generate_launch_description():
    if sys.argv:
        lidar_dir = os.path.join(get_package_share_directory('lds_01'), 'launch')
    else:
        lidar_dir = os.path.join(get_package_share_directory('lds_02'), 'launch')
    launch_file = os.getenv('TEST_LAUNCH_FILE', '')
    return LaunchDescription([
        IncludeLaunchDescription(PythonLaunchDescriptionSource([lidar_dir, '/lds.launch.py'])),
        IncludeLaunchDescription(PythonLaunchDescriptionSource([launch_file])),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(os.path.join(
            get_package_share_directory('pkg'), 'launch', sys.argv[1]))),
        IncludeLaunchDescription(**sys.modules),
    ])
"""
    )
    assert located(facts) == [(None, None), (None, None), ("pkg", None), (None, None)]


# -- namespaces, remaps, arguments -------------------------------------------------------


def test_include_namespace_remaps_and_anchoring() -> None:
    facts = launch(
        """
def generate_launch_description():
    path = [FindPackageShare('pkg'), '/a.launch.py']
    return LaunchDescription([
        IncludeLaunchDescription(path),
        GroupAction([
            PushRosNamespace('team'),
            SetRemap(src='cmd_vel', dst='/mux/cmd_vel'),
            IncludeLaunchDescription(PythonLaunchDescriptionSource(path)),
            PushRosNamespace(LaunchConfiguration('unknown')),
            IncludeLaunchDescription(PythonLaunchDescriptionSource(path)),
        ]),
        PushRosNamespace('/'),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(path)),
    ])
"""
    )
    assert [(include.namespace, include.anchored) for include in facts.includes] == [
        ("/", False),
        ("/team", False),
        ("", False),  # dynamic
        ("/", True),  # an absolute push, even to the root, is not prefixed by an includer
    ]
    team = facts.includes[1]
    assert [(remap.source, remap.target) for remap in team.remaps] == [("cmd_vel", "/mux/cmd_vel")]
    assert facts.includes[3].remaps == ()


def test_include_arguments_explicit_win_and_dynamic_hide() -> None:
    facts = launch(
        """
def generate_launch_description():
    shared = {'use_sim_time': 'true', 'robot': LaunchConfiguration('robot')}
    return LaunchDescription([
        DeclareLaunchArgument('robot', default_value='tb3'),
        DeclareLaunchArgument('world', default_value='house'),
        DeclareLaunchArgument('map', default_value='house.yaml'),
        DeclareLaunchArgument('no_default'),
        SetLaunchConfiguration('world', 'warehouse'),
        SetLaunchConfiguration('rate', LaunchConfiguration('unknown')),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource([FindPackageShare('sim'), '/a.launch.py']),
            launch_arguments={'map': LaunchConfiguration('unknown'), 'level': '2'}.items()),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource([FindPackageShare('sim'), '/b.launch.py']),
            launch_arguments=shared.items()),
        GroupAction(
            [IncludeLaunchDescription([FindPackageShare('sim'), '/c.launch.py'])],
            launch_configurations={'robot': 'burger'}),
    ])
"""
    )
    first, second, third = (dict(include.arguments) for include in facts.includes)
    # 'map' is handed over unknown: the declared default no longer holds; 'rate' likewise.
    assert first == {"level": "2", "map": None, "rate": None, "robot": "tb3", "world": "warehouse"}
    assert list(facts.includes[0].arguments) == sorted(facts.includes[0].arguments)
    # launch sets an include's arguments in the including scope: 'level' stays set.
    assert second == {
        "level": "2",
        "map": None,
        "rate": None,
        "robot": "tb3",
        "use_sim_time": "true",
        "world": "warehouse",
    }
    assert third["robot"] == "burger"


def test_include_arguments_leak_out_of_an_unscoped_include_only() -> None:
    facts = launch(
        """
def generate_launch_description():
    robot = LaunchConfiguration('robot', default='none')
    return LaunchDescription([
        GroupAction([IncludeLaunchDescription(
            PythonLaunchDescriptionSource([ThisLaunchFileDir(), '/a.launch.py']),
            launch_arguments={'robot': 'grouped'}.items())]),
        Node(package='p', executable='e', name=robot),
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource([ThisLaunchFileDir(), '/b.launch.py']),
            launch_arguments={'robot': 'leaked'}.items()),
        Node(package='p', executable='e', name=robot),
    ])
"""
    )
    assert [node.name for node in facts.launch_nodes] == ["none", "leaked"]


def test_inline_description_is_walked_here() -> None:
    facts = launch(
        """
def generate_launch_description():
    inner = LaunchDescription([Node(package='p', executable='e',
                                    name=LaunchConfiguration('who'))])
    return LaunchDescription([
        PushRosNamespace('outer'),
        IncludeLaunchDescription(LaunchDescriptionSource(inner),
                                 launch_arguments={'who': 'inline'}.items()),
    ])
"""
    )
    assert facts.includes == ()
    assert [(node.name, node.namespace) for node in facts.launch_nodes] == [("inline", "/outer")]


def test_node_own_remaps_and_anchoring() -> None:
    facts = launch(
        """
def generate_launch_description():
    return LaunchDescription([
        SetRemap(src='/tf', dst='tf'),
        Node(package='p', executable='e', name='plain'),
        Node(package='p', executable='e', name='own', remappings=[('a', 'b'), ('c', 'd')]),
        Node(package='p', executable='e', name='absolute', namespace='/abs'),
        Node(package='p', executable='e', name='relative', namespace='rel'),
        GroupAction([
            PushRosNamespace('/fleet'),
            Node(package='p', executable='e', name='pushed', namespace='rel'),
        ]),
        Node(package='p', executable='e', name='after_group'),
    ])
"""
    )
    found = [
        (node.name, node.namespace, len(node.remaps), node.own_remaps, node.anchored)
        for node in facts.launch_nodes
    ]
    assert found == [
        ("plain", "/", 1, 0, False),
        ("own", "/", 3, 2, False),
        ("absolute", "/abs", 1, 0, True),
        ("relative", "/rel", 1, 0, False),
        ("pushed", "/fleet/rel", 1, 0, True),
        ("after_group", "/", 1, 0, False),
    ]
    own = facts.launch_nodes[1]
    assert [(r.source, r.target) for r in own.remaps[-own.own_remaps :]] == [("a", "b"), ("c", "d")]


# -- specialised extraction --------------------------------------------------------------

SPECIALISED = """
def generate_launch_description():
    robot = LaunchConfiguration('robot')
    return LaunchDescription([
        DeclareLaunchArgument('robot', default_value='tb3'),
        DeclareLaunchArgument('namespace', default_value=''),
        DeclareLaunchArgument('use_lidar', default_value='false'),
        PushRosNamespace(LaunchConfiguration('namespace')),
        Node(package='drv', executable='drv', name=[robot, '_driver']),
        Node(package='lds', executable='lds', name='lidar',
             condition=IfCondition(LaunchConfiguration('use_lidar'))),
        SetLaunchConfiguration('robot', 'set_later'),
        Node(package='drv', executable='drv', name=[robot, '_after']),
    ])
"""


def test_specialised_extraction_changes_names_namespaces_and_conditions() -> None:
    default = launch(SPECIALISED)
    assert [(node.name, node.namespace) for node in default.launch_nodes] == [
        ("tb3_driver", "/"),
        ("set_later_after", "/"),
    ]
    given = (("namespace", "robot2"), ("robot", "burger"), ("use_lidar", "true"))
    specialised = launch(SPECIALISED, arguments=given)
    assert [(node.name, node.namespace) for node in specialised.launch_nodes] == [
        ("burger_driver", "/robot2"),  # arguments win over declared defaults
        ("lidar", "/robot2"),  # the IfCondition is now true
        ("set_later_after", "/robot2"),  # SetLaunchConfiguration still overrides them
    ]
    names = [use.value for use in specialised.names if use.kind.value == "node"]
    assert "burger_driver" in names


def test_specialised_extraction_hands_arguments_on_to_includes() -> None:
    body = """
def generate_launch_description():
    return LaunchDescription([
        IncludeLaunchDescription([FindPackageShare('pkg'), '/inner.launch.py'],
                                 launch_arguments={'level': '1'}.items()),
    ])
"""
    facts = launch(body, arguments=(("robot", "tb4"), ("level", "0")))
    assert facts.includes[0].arguments == (("level", "1"), ("robot", "tb4"))


def test_plain_node_file_ignores_arguments() -> None:
    source = b"""import rclpy
from rclpy.node import Node

class Talker(Node):
    def __init__(self):
        super().__init__('talker')
        self.create_publisher(String, 'chatter', 10)
"""
    plain = extract("talker.py", source, None, Generation.ROS2)
    given = extract("talker.py", source, None, Generation.ROS2, arguments=(("robot", "x"),))
    assert plain == given
    assert [use.value for use in given.names] == ["talker", "chatter"]


def test_odd_include_shapes_never_raise() -> None:
    facts = launch(
        """
def generate_launch_description():
    x = PathJoinSubstitution()
    return LaunchDescription([
        IncludeLaunchDescription(),
        IncludeLaunchDescription(PythonLaunchDescriptionSource()),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(x)),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(f'{x!r}/a{{b}}.py')),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(os.path.join())),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(Path().joinpath(*x))),
        IncludeLaunchDescription(LaunchDescriptionSource()),
        IncludeLaunchDescription(x, launch_arguments=[1, (2,), {3: 4}]),
        IncludeLaunchDescription(launch_arguments=x.items()),
    ])
"""
    )
    assert isinstance(facts, FileFacts)
    assert all(include.path is None for include in facts.includes)


def test_extractions_of_one_file_under_several_arguments_share_nothing_but_the_parse() -> None:
    """An includer's arguments re-run only the launch part (the parse, the walk and the
    code's names are kept per file): each set must give what a fresh extraction gives."""
    from roslint_names.extract.python import parsed as python_extract

    sets: list[Arguments] = [
        (),
        (("namespace", "robot2"), ("robot", "burger"), ("use_lidar", "true")),
        (("namespace", "robot3"),),
        (),
    ]
    shared = [launch(SPECIALISED, arguments=arguments) for arguments in sets]
    fresh = []
    for arguments in sets:
        python_extract._LAUNCH_FILES.clear()
        fresh.append(launch(SPECIALISED, arguments=arguments))
    assert shared == fresh
    assert shared[0] == shared[3] != shared[1] != shared[2]
    nav2 = [fixture("nav2_style_bringup.launch.py", arguments) for arguments in sets]
    python_extract._LAUNCH_FILES.clear()
    assert nav2[2] == fixture("nav2_style_bringup.launch.py", sets[2])


def test_only_launch_files_keep_their_tree_for_extractions_under_arguments() -> None:
    """A library or test module is never extracted again under arguments: its tree (tens
    of megabytes for a large module) is not kept; a launch file's is."""
    from roslint_names.extract.python import parsed as python_extract
    from roslint_names.model import Generation

    node = b"import rclpy\nfrom rclpy.node import Node\n\nclass Talker(Node):\n    pass\n"
    python_extract.extract_parsed("talker.py", node, None, Generation.ROS2, False)
    launch(SPECIALISED)
    kept = python_extract._LAUNCH_FILES
    assert ((HEADER + SPECIALISED).encode(), Generation.ROS2, Generation.ROS2, False) in kept
    assert (node, None, Generation.ROS2, False) not in kept


def test_launch_trees_pushed_out_of_the_memo_leave_no_cycle_for_the_collector() -> None:
    """The memo keeps the last 16 launch files' trees; one pushed out must be freed by
    reference counting, not left as cyclic garbage for the collector to walk (a third of
    a cold run's collection work on realws)."""
    from roslint_names.extract.python import parsed as python_extract

    python_extract._LAUNCH_FILES.clear()
    launch(SPECIALISED)  # imports and module-level caches stay out of the count
    gc.collect()
    gc.disable()
    try:
        for copy in range(20):  # more than the memo keeps
            launch(f"{SPECIALISED}\n# copy {copy}\n")
        python_extract._LAUNCH_FILES.clear()
        assert gc.collect() == 0
    finally:
        gc.enable()


def test_a_launch_tree_being_extracted_is_not_released_when_pushed_out() -> None:
    """The language server extracts in two threads: a tree another extraction pushes out
    of the memo stays whole until the extraction using it ends."""
    from roslint_names.extract.python import parsed as python_extract

    memo = python_extract._LAUNCH_FILES
    key = ((HEADER + SPECIALISED).encode(), Generation.ROS2, Generation.ROS2, False)
    memo.clear()
    launch(SPECIALISED)
    prepared = memo.begin(key)  # one thread starts on the kept tree...
    assert not isinstance(prepared, ParseError)
    walk = prepared[0]
    for copy in range(20):  # ...while the other pushes it out
        launch(f"{SPECIALISED}\n# copy {copy}\n")
    assert key not in memo
    assert walk.root.bindings  # still whole for the first thread
    memo.end(key, prepared, keep=False)
    assert not walk.root.bindings  # released once its last extraction ended
