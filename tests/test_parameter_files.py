"""Parameter files (issue 28): read, linked from launch files, and RN405.

ROS 2 files are parameter files by their ``ros__parameters``; a ROS 1 package's YAML is
one when a launch file loads it. Launch files hand files to nodes (``parameters=[path]``,
``ParameterFile``, ``<param from>``, ``<rosparam load>``); the graph links each to the
workspace's file and the names it sets; RN405 reports a node key no node it is handed to
has, where the key was evidently meant for one of them.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write

from roslint_names.extract import parameter_file
from roslint_names.extract.launch import xml_launch, yaml_launch
from roslint_names.extract.python import extract as python_extract
from roslint_names.model import FileFacts, Generation, Kind, Language, LaunchArguments, Span
from roslint_names.workspace.build import build
from roslint_names.workspace.graph import Graph
from roslint_names.workspace.index import Package
from roslint_names.workspace.parameter_files import key_matches

ROS1, ROS2 = Generation.ROS1, Generation.ROS2

# navigation2's params file, reduced: a server, its plugin's parameters, and the costmap
# node the server creates itself.
NAV2_PARAMS = """\
controller_server:
  ros__parameters:
    controller_frequency: 20.0
    controller_plugins: ["FollowPath"]
    FollowPath:
      plugin: "dwb_core::DWBLocalPlanner"
      max_vel_x: 0.26
local_costmap:
  local_costmap:
    ros__parameters:
      update_frequency: 5.0
"""

NAV2_LAUNCH_PY = """\
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterFile
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    nav2_params = PathJoinSubstitution(
        [FindPackageShare("nav_bringup"), "config", "nav2_params.yaml"]
    )
    ekf_params = os.path.join(get_package_share_directory("nav_bringup"), "config", "ekf.yaml")
    return LaunchDescription([
        DeclareLaunchArgument(
            "fusion_params",
            default_value=PathJoinSubstitution(
                [FindPackageShare("nav_bringup"), "config", "fusion.yaml"]
            ),
        ),
        Node(
            package="nav2_controller",
            executable="controller_server",
            name="controller_server",
            parameters=[nav2_params, {"use_sim_time": True}],
        ),
        Node(
            package="robot_localization",
            executable="ekf_node",
            name="ekf_filter_node",
            parameters=[ParameterFile(ekf_params, allow_substs=True)],
        ),
        Node(
            package="fusion",
            executable="fusion_node",
            name="fusion_core",
            parameters=[LaunchConfiguration("fusion_params")],
        ),
    ])
"""

EKF_PARAMS = """\
/**:
  ros__parameters:
    use_sim_time: true
ekf_filter_node:
  ros__parameters:
    frequency: 30.0
    two_d_mode: true
"""

FUSION_PARAMS = """\
fusioncore:
  ros__parameters:
    publish_tf: true
    world_frame: odom
"""


def nav_workspace(root: Path, fusion: str = FUSION_PARAMS) -> None:
    write(root, "src/nav_bringup/package.xml", AMENT_PACKAGE.format(name="nav_bringup"))
    write(root, "src/nav_bringup/launch/bringup.launch.py", NAV2_LAUNCH_PY)
    write(root, "src/nav_bringup/config/nav2_params.yaml", NAV2_PARAMS)
    write(root, "src/nav_bringup/config/ekf.yaml", EKF_PARAMS)
    write(root, "src/nav_bringup/config/fusion.yaml", fusion)


def rn405(run_cli: Any, root: Path, *paths: str) -> list[dict[str, Any]]:
    result = run_cli(["check", "--format", "json", "--select", "RN405", *(paths or ["."])], root)
    assert result.exit_code in (0, 1), result.stderr
    found: list[dict[str, Any]] = result.findings()
    return found


def all_findings(run_cli: Any, root: Path) -> list[dict[str, Any]]:
    result = run_cli(["check", "--format", "json", "--select", "ALL", "."], root)
    assert result.exit_code in (0, 1), result.stderr
    found: list[dict[str, Any]] = result.findings()
    return found


# ---------------------------------------------------------------------------------------
# Reading parameter files


def read(text: str, package: Generation | None = ROS2, path: str = "params.yaml") -> FileFacts:
    return parameter_file.extract(path, text.encode(), package, ROS2)


def test_ros2_node_keys_and_dotted_parameter_names() -> None:
    facts = read(NAV2_PARAMS)
    assert facts.language is Language.PARAMETERS and facts.generation is ROS2
    blocks = {block.key: block for block in facts.parameter_blocks}
    assert sorted(blocks) == ["controller_server", "local_costmap/local_costmap"]
    server = blocks["controller_server"]
    assert server.span == Span(1, 1, 1, 18)
    assert [name for name, _ in server.parameters] == [
        "controller_frequency",
        "controller_plugins",
        "FollowPath.plugin",
        "FollowPath.max_vel_x",
    ]
    # The span is the key's characters: `max_vel_x` on line 7.
    assert dict(server.parameters)["FollowPath.max_vel_x"] == Span(7, 7, 7, 16)
    # The nested node key's span is its last part, the node's own name.
    assert blocks["local_costmap/local_costmap"].span == Span(9, 3, 9, 16)


def test_ros2_parameter_names_are_name_uses_for_the_per_name_rules() -> None:
    facts = read(NAV2_PARAMS)
    assert {use.kind for use in facts.names} == {Kind.PARAMETER}
    assert "FollowPath.max_vel_x" in {use.value for use in facts.names}


def test_wildcard_and_absolute_keys_as_rcl_reads_them() -> None:
    text = (
        '"/**":\n  ros__parameters:\n    a: 1\n'
        "/robot1:\n  amcl:\n    ros__parameters:\n      b: 2\n"
    )
    assert [block.key for block in read(text).parameter_blocks] == ["/**", "/robot1/amcl"]


def test_ros1_yaml_gives_blocks_only_never_name_uses() -> None:
    text = "gains:\n  p: 1.0\n  i: 0.1\nrate: 10\n"
    facts = read(text, ROS1)
    assert facts.generation is ROS1 and facts.names == ()
    (block,) = facts.parameter_blocks
    assert block.key is None
    assert [name for name, _ in block.parameters] == ["gains/p", "gains/i", "rate"]


def test_a_ros2_package_yaml_without_ros_parameters_is_no_parameter_file() -> None:
    facts = read("robot_radius: 0.2\nplugins: [a, b]\n", ROS2)
    assert facts.parameter_blocks == () and facts.names == ()


def test_only_a_parameter_file_by_content_reports_broken_yaml() -> None:
    assert read("a: [1, 2\nros__parameters: x\n").parse_errors
    assert read("a: [1, 2\n", ROS1).parse_errors == ()  # may be no parameter file at all


def test_parameter_names_in_a_parameter_file_are_not_style_findings(
    run_cli: Any, tmp_path: Path
) -> None:
    """navigation2's `controller_plugins: ["FollowPath"]`, gmapping-style `maxUrange`: the
    file spells names the node's code declares, and cannot rename them alone."""
    write(tmp_path, "package.xml", AMENT_PACKAGE.format(name="nav_bringup"))
    write(tmp_path, "config/params.yaml", "slam:\n  ros__parameters:\n    maxUrange: 8.0\n")
    assert all_findings(run_cli, tmp_path) == []


# ---------------------------------------------------------------------------------------
# Links from launch files


def test_python_launch_hands_files_to_its_nodes() -> None:
    facts = python_extract.extract(
        "src/nav_bringup/launch/bringup.launch.py", NAV2_LAUNCH_PY.encode(), ROS2, ROS2
    )
    handed = {node.name: node.parameter_files for node in facts.launch_nodes}
    assert [(f.package, f.path) for f in handed["controller_server"]] == [
        ("nav_bringup", "config/nav2_params.yaml")
    ]
    assert [(f.package, f.path) for f in handed["ekf_filter_node"]] == [
        ("nav_bringup", "config/ekf.yaml")
    ]
    assert [(f.package, f.path) for f in handed["fusion_core"]] == [
        ("nav_bringup", "config/fusion.yaml")
    ]


def test_launch_xml_and_yaml_param_from() -> None:
    xml = """\
<launch>
  <node pkg="robot_localization" exec="ekf_node" name="ekf_filter_node">
    <param from="$(find-pkg-share nav_bringup)/config/ekf.yaml"/>
    <param name="frequency" value="30.0"/>
  </node>
</launch>
"""
    (node,) = xml_launch.extract("a.launch.xml", xml.encode(), ROS2, ROS2).launch_nodes
    assert [(f.package, f.path) for f in node.parameter_files] == [
        ("nav_bringup", "config/ekf.yaml")
    ]
    assert node.parameter_files[0].span == Span(3, 18, 3, 63)  # the value, as for names
    yaml_text = """\
launch:
- node:
    pkg: robot_localization
    exec: ekf_node
    name: ekf_filter_node
    param:
    - from: $(find-pkg-share nav_bringup)/config/ekf.yaml
"""
    (node,) = yaml_launch.extract("a.launch.yaml", yaml_text.encode(), ROS2, ROS2).launch_nodes
    assert [(f.package, f.path) for f in node.parameter_files] == [
        ("nav_bringup", "config/ekf.yaml")
    ]


ROS1_LAUNCH = """\
<launch>
  <group ns="robot1">
    <rosparam command="load" file="$(find robot_bringup)/config/base.yaml" ns="base"/>
    <node pkg="robot_base" type="base_driver" name="driver">
      <rosparam file="$(find robot_bringup)/config/driver.yaml"/>
    </node>
  </group>
  <rosparam command="dump" file="/tmp/dump.yaml"/>
</launch>
"""


def test_ros1_rosparam_load_in_a_group_and_in_a_node() -> None:
    facts = xml_launch.extract("robot.launch", ROS1_LAUNCH.encode(), ROS1, ROS1)
    (load,) = facts.parameter_loads  # the dump loads nothing
    assert (load.package, load.path, load.namespace) == (
        "robot_bringup",
        "config/base.yaml",
        "/robot1/base",
    )
    (node,) = facts.launch_nodes
    assert [(f.path, f.namespace) for f in node.parameter_files] == [("config/driver.yaml", "")]


def _graph(files: dict[str, tuple[str, Generation]], packages: list[Package]) -> Graph:
    facts = []
    for path, (text, generation) in files.items():
        data = text.encode()
        if path.endswith(".launch"):
            facts.append(xml_launch.extract(path, data, generation, generation))
        elif path.endswith(".launch.py"):
            facts.append(python_extract.extract(path, data, generation, generation))
        else:
            facts.append(parameter_file.extract(path, data, generation, generation))

    def specialise(path: str, arguments: LaunchArguments) -> FileFacts | None:
        return None

    return build(facts, packages, specialise)


def test_the_graph_reads_a_ros1_load_under_its_group_namespace() -> None:
    graph = _graph(
        {
            "src/robot_bringup/launch/robot.launch": (ROS1_LAUNCH, ROS1),
            "src/robot_bringup/config/base.yaml": ("wheel_radius: 0.1\npid:\n  p: 2.0\n", ROS1),
            "src/robot_bringup/config/driver.yaml": ("port: /dev/ttyUSB0\n", ROS1),
        },
        [Package("robot_bringup", "src/robot_bringup", generation=ROS1)],
    )
    (load,) = graph.parameter_loads
    assert load.path == "src/robot_bringup/config/base.yaml"
    assert load.names == ("/robot1/base/pid/p", "/robot1/base/wheel_radius")
    (node,) = graph.nodes
    (handed,) = node.parameter_files
    assert (handed.namespace, handed.names) == ("/robot1/driver", ("/robot1/driver/port",))


def test_the_graph_links_a_nav2_style_bringup() -> None:
    graph = _graph(
        {
            "src/nav_bringup/launch/bringup.launch.py": (NAV2_LAUNCH_PY, ROS2),
            "src/nav_bringup/config/nav2_params.yaml": (NAV2_PARAMS, ROS2),
            "src/nav_bringup/config/ekf.yaml": (EKF_PARAMS, ROS2),
            "src/nav_bringup/config/fusion.yaml": (FUSION_PARAMS, ROS2),
        },
        [Package("nav_bringup", "src/nav_bringup", generation=ROS2)],
    )
    nodes = {node.name: node for node in graph.nodes}
    (server,) = nodes["/controller_server"].parameter_files
    assert server.path == "src/nav_bringup/config/nav2_params.yaml"
    assert server.names == (
        "FollowPath.max_vel_x",
        "FollowPath.plugin",
        "controller_frequency",
        "controller_plugins",
    )
    (ekf,) = nodes["/ekf_filter_node"].parameter_files
    assert ekf.names == ("frequency", "two_d_mode", "use_sim_time")  # `/**` and its own
    (fusion,) = nodes["/fusion_core"].parameter_files
    assert fusion.names == ()  # keyed `fusioncore`: nothing reaches the node
    assert sorted(graph.parameter_files) == [
        "src/nav_bringup/config/ekf.yaml",
        "src/nav_bringup/config/fusion.yaml",
        "src/nav_bringup/config/nav2_params.yaml",
    ]


# nav2_bringup's navigation_launch.py, reduced: every server gets the parameter file through
# nav2_common's RewrittenYaml, under the namespace argument as root key.
REWRITTEN_LAUNCH_PY = """\
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from launch_ros.descriptions import ParameterFile
from nav2_common.launch import RewrittenYaml


def generate_launch_description():
    bringup_dir = get_package_share_directory("nav_bringup")
    namespace = LaunchConfiguration("namespace")
    params_file = LaunchConfiguration("params_file")
    configured_params = ParameterFile(
        RewrittenYaml(
            source_file=params_file,
            root_key=namespace,
            param_rewrites={"autostart": "true"},
            convert_types=True,
        ),
        allow_substs=True,
    )
    return LaunchDescription([
        DeclareLaunchArgument("namespace", default_value=""),
        DeclareLaunchArgument(
            "params_file",
            default_value=os.path.join(bringup_dir, "config", "nav2_params.yaml"),
        ),
        Node(
            package="nav2_controller",
            executable="controller_server",
            name="controller_server",
            parameters=[configured_params],
        ),
    ])
"""


def test_the_graph_reads_the_file_nav2s_rewritten_yaml_rewrites() -> None:
    """Before, the RewrittenYaml call was no file: none of nav2_bringup's servers had
    a parameter file, and RN405/RN406 never judged nav2_params.yaml."""
    files = {
        "src/nav_bringup/launch/navigation.launch.py": (REWRITTEN_LAUNCH_PY, ROS2),
        "src/nav_bringup/config/nav2_params.yaml": (NAV2_PARAMS, ROS2),
    }
    graph = _graph(files, [Package("nav_bringup", "src/nav_bringup", generation=ROS2)])
    (server,) = graph.nodes[0].parameter_files
    assert server.path == "src/nav_bringup/config/nav2_params.yaml"
    assert "FollowPath.max_vel_x" in server.names
    # Keys renamed, or nested under a namespace of the call's own: no file to read.
    for old, new in (
        ("convert_types=True,", 'key_rewrites={"a": "b"},'),
        ("root_key=namespace,", 'root_key="robot9",'),
    ):
        rewritten = REWRITTEN_LAUNCH_PY.replace(old, new)
        files["src/nav_bringup/launch/navigation.launch.py"] = (rewritten, ROS2)
        graph = _graph(files, [Package("nav_bringup", "src/nav_bringup", generation=ROS2)])
        assert all(not handed.names for handed in graph.nodes[0].parameter_files)


# ---------------------------------------------------------------------------------------
# How keys match (rclcpp's is_node_name_matched, launch_ros's to_parameters_list)


def test_key_matching_follows_rclcpp() -> None:
    assert key_matches("controller_server", "/controller_server")
    assert key_matches("/controller_server", "/controller_server")
    assert not key_matches("controller_server", "/robot1/controller_server")
    assert key_matches("robot1/controller_server", "/robot1/controller_server")
    assert key_matches("/**", "/robot1/controller_server")
    assert key_matches("/**/controller_server", "/robot1/controller_server")
    assert key_matches("/**/controller_server", "/controller_server")
    assert key_matches("*", "/amcl") and not key_matches("*", "/robot1/amcl")
    assert key_matches("/robot1/*", "/robot1/amcl")


def test_composable_nodes_match_as_launch_ros_does() -> None:
    assert key_matches("/**", "/camera/rectify", composable=True)
    assert key_matches("camera/rectify", "/camera/rectify", composable=True)
    assert not key_matches("/**/rectify", "/camera/rectify", composable=True)
    assert key_matches("/**", "", composable=True)  # a node the launch file names not


# ---------------------------------------------------------------------------------------
# RN405


def test_a_key_one_underscore_away_from_the_node_it_is_handed_to(
    run_cli: Any, tmp_path: Path
) -> None:
    nav_workspace(tmp_path)
    (found,) = rn405(run_cli, tmp_path)
    assert (found["path"], found["line"]) == ("src/nav_bringup/config/fusion.yaml", 1)
    assert "node key 'fusioncore'" in found["message"]
    assert "did you mean 'fusion_core'" in found["message"]
    related = {(r["path"], r["line"]) for r in found["related"]}
    assert ("src/nav_bringup/launch/bringup.launch.py", 39) in related


def test_the_right_key_and_wildcards_are_fine(run_cli: Any, tmp_path: Path) -> None:
    nav_workspace(tmp_path, FUSION_PARAMS.replace("fusioncore", "fusion_core"))
    assert rn405(run_cli, tmp_path) == []


def test_a_key_for_a_node_the_server_creates_itself_is_left_alone(
    run_cli: Any, tmp_path: Path
) -> None:
    """`local_costmap/local_costmap` matches no launched node: controller_server creates
    it, under a name the linter does not see."""
    nav_workspace(tmp_path, FUSION_PARAMS.replace("fusioncore", "fusion_core"))
    found = rn405(run_cli, tmp_path)
    assert not [f for f in found if "local_costmap" in f["message"]]


NAMESPACED_LAUNCH_PY = """\
from launch import LaunchDescription
from launch.actions import GroupAction
from launch.substitutions import PathJoinSubstitution
from launch_ros.actions import Node, PushRosNamespace
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    params = PathJoinSubstitution([FindPackageShare("nav_bringup"), "config", "fusion.yaml"])
    return LaunchDescription([
        GroupAction([
            PushRosNamespace("robot1"),
            Node(
                package="fusion",
                executable="fusion_node",
                name="fusion_core",
                parameters=[params],
            ),
        ]),
    ])
"""


def namespaced_workspace(root: Path, key: str) -> None:
    write(root, "src/nav_bringup/package.xml", AMENT_PACKAGE.format(name="nav_bringup"))
    write(root, "src/nav_bringup/launch/robot.launch.py", NAMESPACED_LAUNCH_PY)
    write(root, "src/nav_bringup/config/fusion.yaml", FUSION_PARAMS.replace("fusioncore", key))


def test_a_namespaced_node_and_the_key_that_names_its_namespace(
    run_cli: Any, tmp_path: Path
) -> None:
    for right in ("robot1/fusion_core", "/robot1/fusion_core", "/**/fusion_core", "/**"):
        namespaced_workspace(tmp_path, right)
        assert rn405(run_cli, tmp_path) == [], right


def test_a_namespaced_node_and_a_key_without_or_with_another_namespace(
    run_cli: Any, tmp_path: Path
) -> None:
    for wrong, meant in (
        ("fusion_core", "robot1/fusion_core"),
        ("robot2/fusion_core", "robot1/fusion_core"),
        ("/robot2/fusion_core", "/robot1/fusion_core"),
        ("robot1/fusioncore", "robot1/fusion_core"),
        ("/**/fusioncore", "/**/fusion_core"),
    ):
        namespaced_workspace(tmp_path, wrong)
        (found,) = rn405(run_cli, tmp_path)
        assert f"did you mean '{meant}'" in found["message"], (wrong, found["message"])


def test_a_namespace_an_includer_may_still_push_is_left_alone(run_cli: Any, tmp_path: Path) -> None:
    """A node of a root launch file runs in `/` here, but a bringup outside the workspace
    may include the file under `robot1`: the key may be right there."""
    nav_workspace(tmp_path, FUSION_PARAMS.replace("fusioncore", "robot1/fusion_core"))
    assert rn405(run_cli, tmp_path) == []


def test_a_file_handed_to_a_node_of_unknown_name_is_not_judged(
    run_cli: Any, tmp_path: Path
) -> None:
    nav_workspace(tmp_path)
    launch = NAV2_LAUNCH_PY.replace('name="fusion_core"', 'name=LaunchConfiguration("name")')
    write(tmp_path, "src/nav_bringup/launch/bringup.launch.py", launch)
    assert rn405(run_cli, tmp_path) == []


def test_a_key_that_names_another_node_of_the_workspace_is_no_mistake(
    run_cli: Any, tmp_path: Path
) -> None:
    """One file for the fusion node and its twin, each started by its own launch file."""
    nav_workspace(tmp_path, FUSION_PARAMS + FUSION_PARAMS.replace("fusioncore", "fusion_core"))
    twin = NAMESPACED_LAUNCH_PY.replace('PushRosNamespace("robot1"),', "").replace(
        '"fusion_core"', '"fusioncore"'
    )
    write(tmp_path, "src/nav_bringup/launch/twin.launch.py", twin)
    assert rn405(run_cli, tmp_path) == []


def test_ros1_loads_are_never_judged(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "src/robot_bringup/package.xml", CATKIN_PACKAGE.format(name="robot_bringup"))
    write(tmp_path, "src/robot_bringup/launch/robot.launch", ROS1_LAUNCH)
    write(tmp_path, "src/robot_bringup/config/base.yaml", "driverr:\n  port: 1\n")
    write(tmp_path, "src/robot_bringup/config/driver.yaml", "port: /dev/ttyUSB0\n")
    assert all_findings(run_cli, tmp_path) == []


def test_a_cached_rerun_reports_the_same(run_cli: Any, tmp_path: Path) -> None:
    nav_workspace(tmp_path)
    first = run_cli(["check", "--format", "json", "--select", "RN405", "."], tmp_path)
    again = run_cli(["check", "--format", "json", "--select", "RN405", "."], tmp_path)
    assert first.findings() == again.findings() and len(first.findings()) == 1
    write(
        tmp_path,
        "src/nav_bringup/config/fusion.yaml",
        FUSION_PARAMS.replace("fusioncore", "fusion_core"),
    )
    assert rn405(run_cli, tmp_path) == []


def test_a_one_file_run_on_the_parameter_file_sees_its_launch_files(
    run_cli: Any, tmp_path: Path
) -> None:
    nav_workspace(tmp_path)
    (found,) = rn405(run_cli, tmp_path, "src/nav_bringup/config/fusion.yaml")
    assert found["path"] == "src/nav_bringup/config/fusion.yaml"


# A ROS 2 controller with a camelCase parameter, and the parameter file that tunes it.
CONTROLLER_CPP = """\
#include "rclcpp/rclcpp.hpp"

class Controller : public rclcpp::Node
{
public:
  Controller() : rclcpp::Node("controller")
  {
    max_speed_ = declare_parameter("maxSpeed", 0.5);
  }

private:
  double max_speed_;
};
"""


def test_a_rename_of_a_declared_parameter_renames_the_parameter_file_key(
    run_cli: Any, tmp_path: Path
) -> None:
    """The file spells the code's name at a key the extractor knows exactly: RN203's
    rename edits it with the declaration, instead of being held back by it."""
    write(tmp_path, "src/controller/package.xml", AMENT_PACKAGE.format(name="controller"))
    write(tmp_path, "src/controller/src/controller.cpp", CONTROLLER_CPP)
    params = "controller:\n  ros__parameters:\n    maxSpeed: 1.2\n"
    write(tmp_path, "src/controller/config/controller.yaml", params)
    arguments = ["check", "--format", "json", "--unsafe-fixes", "--select", "RN203", "."]
    (found,) = run_cli(arguments, tmp_path).findings()
    assert found["path"] == "src/controller/src/controller.cpp"
    assert found["fix"]["also"] == [
        {
            "path": "src/controller/config/controller.yaml",
            "line": 3,
            "column": 5,
            "end_line": 3,
            "end_column": 13,
            "replacement": "max_speed",
        }
    ]
