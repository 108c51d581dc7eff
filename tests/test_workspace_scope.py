"""Which nodes of a workspace can meet, and what the graph rules may judge.

A workspace holds many systems that never run together: tutorials, demos, the tests of
other packages. The graph rules compare names only between nodes that can be in one ROS
graph (one launch tree, or packages the package.xml files tie together), and only names
the linter knows. Each test writes a small realistic workspace and runs the real CLI.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import AMENT_PACKAGE, CATKIN_PACKAGE, write
from test_workspace import findings, graph_of

from roslint_names.extract.literals import name_literals
from roslint_names.generation import package_xml_depends
from roslint_names.workspace.index import Package, WorkspaceIndex

TALKER_PY = """\
#!/usr/bin/env python
import rospy
from std_msgs.msg import String


def main():
    rospy.init_node("talker")
    pub = rospy.Publisher("chatter", String, queue_size=10)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        pub.publish(String(data="hello"))
        rate.sleep()


if __name__ == "__main__":
    main()
"""

COUNTER_PY = """\
#!/usr/bin/env python
import rospy
from std_msgs.msg import Int32


def on_count(msg):
    rospy.loginfo("count %d", msg.data)


def main():
    rospy.init_node("counter")
    rospy.Subscriber("chatter", Int32, on_count)
    rospy.spin()


if __name__ == "__main__":
    main()
"""


def catkin_package(name: str, *depends: str) -> str:
    """A format-2 catkin package.xml depending on ``depends``."""
    lines = "".join(f"  <exec_depend>{dependency}</exec_depend>\n" for dependency in depends)
    return CATKIN_PACKAGE.format(name=name).replace("</package>", lines + "</package>")


def two_tutorial_packages(root: Path, *listener_depends: str) -> None:
    """``talker_tutorial`` publishes ``chatter`` as String, ``counter_tutorial`` subscribes
    to it as Int32; neither is launched."""
    write(root, "src/talker_tutorial/package.xml", catkin_package("talker_tutorial", "rospy"))
    write(root, "src/talker_tutorial/scripts/talker.py", TALKER_PY)
    write(
        root,
        "src/counter_tutorial/package.xml",
        catkin_package("counter_tutorial", "rospy", *listener_depends),
    )
    write(root, "src/counter_tutorial/scripts/counter.py", COUNTER_PY)


def codes(found: list[dict[str, Any]]) -> list[tuple[str, str]]:
    return sorted((f["code"], f["path"]) for f in found)


# ---------------------------------------------------------------------------------------
# Which nodes meet


def test_programs_of_unrelated_packages_never_meet(run_cli: Any, tmp_path: Path) -> None:
    two_tutorial_packages(tmp_path)
    assert findings(run_cli, tmp_path, ".") == []


def test_a_dependency_ties_two_packages_together(run_cli: Any, tmp_path: Path) -> None:
    two_tutorial_packages(tmp_path, "talker_tutorial")
    assert codes(findings(run_cli, tmp_path, ".")) == [
        ("RN403", "src/counter_tutorial/scripts/counter.py"),
        ("RN403", "src/talker_tutorial/scripts/talker.py"),
    ]


def test_a_metapackage_ties_the_packages_it_gathers(run_cli: Any, tmp_path: Path) -> None:
    two_tutorial_packages(tmp_path)
    write(
        tmp_path,
        "src/tutorials/package.xml",
        catkin_package("tutorials", "talker_tutorial", "counter_tutorial"),
    )
    assert [f["code"] for f in findings(run_cli, tmp_path, ".")] == ["RN403", "RN403"]


def test_two_unlaunched_publishers_of_one_relative_name_are_not_a_mismatch(
    run_cli: Any, tmp_path: Path
) -> None:
    """perception_pcl, reduced: two tools of one package each publish 'output', one a
    point cloud, one an image. Nothing starts them together, and each is remapped by hand;
    a subscriber of 'output' with a third type would still meet both."""
    write(tmp_path, "src/pcl_tools/package.xml", catkin_package("pcl_tools", "rospy"))
    publisher = (
        "import rospy\nfrom sensor_msgs.msg import {kind}\n\n"
        'rospy.init_node("{node}")\n'
        'pub = rospy.Publisher("output", {kind}, queue_size=1)\n'
    )
    write(
        tmp_path,
        "src/pcl_tools/scripts/bag_to_cloud.py",
        publisher.format(kind="PointCloud2", node="bag_to_cloud"),
    )
    write(
        tmp_path,
        "src/pcl_tools/scripts/pcd_to_image.py",
        publisher.format(kind="Image", node="pcd_to_image"),
    )
    assert findings(run_cli, tmp_path, ".") == []
    write(
        tmp_path,
        "src/pcl_tools/scripts/viewer.py",
        "import rospy\nfrom sensor_msgs.msg import Image\n\n"
        'rospy.init_node("viewer")\nrospy.Subscriber("output", Image, print)\n',
    )
    assert codes(findings(run_cli, tmp_path, ".")) == [
        ("RN403", "src/pcl_tools/scripts/bag_to_cloud.py"),
        ("RN403", "src/pcl_tools/scripts/viewer.py"),
    ]


def test_one_launch_tree_is_one_system_whatever_the_packages(run_cli: Any, tmp_path: Path) -> None:
    two_tutorial_packages(tmp_path)
    write(tmp_path, "src/demo_bringup/package.xml", catkin_package("demo_bringup"))
    write(
        tmp_path,
        "src/demo_bringup/launch/demo.launch",
        "<launch>\n"
        '  <node name="talker" pkg="talker_tutorial" type="talker.py"/>\n'
        '  <node name="counter" pkg="counter_tutorial" type="counter.py"/>\n'
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".")
    assert [f["code"] for f in found] == ["RN403", "RN403"]
    assert "'/chatter'" in found[0]["message"]


def test_each_rostest_file_runs_with_its_own_master(run_cli: Any, tmp_path: Path) -> None:
    """rostest starts a master per .test file: nodes of two tests never meet, even in
    one package; nodes of one test do."""
    write(tmp_path, "src/chatter_tests/package.xml", catkin_package("chatter_tests"))
    write(tmp_path, "src/chatter_tests/scripts/talker.py", TALKER_PY)
    write(tmp_path, "src/chatter_tests/scripts/counter.py", COUNTER_PY)
    write(
        tmp_path,
        "src/chatter_tests/test/talker.test",
        '<launch>\n  <node name="talker" pkg="chatter_tests" type="talker.py"/>\n</launch>\n',
    )
    write(
        tmp_path,
        "src/chatter_tests/test/counter.test",
        '<launch>\n  <node name="counter" pkg="chatter_tests" type="counter.py"/>\n</launch>\n',
    )
    assert findings(run_cli, tmp_path, ".") == []
    write(
        tmp_path,
        "src/chatter_tests/test/both.test",
        "<launch>\n"
        '  <node name="talker" pkg="chatter_tests" type="talker.py"/>\n'
        '  <node name="counter" pkg="chatter_tests" type="counter.py"/>\n'
        "</launch>\n",
    )
    assert [f["code"] for f in findings(run_cli, tmp_path, ".")] == ["RN403", "RN403"]


def test_a_ros1_client_never_meets_a_ros2_server(run_cli: Any, tmp_path: Path) -> None:
    """Both programs are called ``add_two_ints_client`` and sit in tied packages: the
    ROS 1 one used to be taken for the ROS 2 one and compared with ROS 2 servers."""
    write(
        tmp_path,
        "src/ros1_tutorials/package.xml",
        catkin_package("ros1_tutorials", "ros2_tutorials"),
    )
    write(
        tmp_path,
        "src/ros1_tutorials/src/add_two_ints_client.cpp",
        "#include <ros/ros.h>\n"
        '#include "ros1_tutorials/TwoInts.h"\n'
        "int main(int argc, char** argv)\n{\n"
        '  ros::init(argc, argv, "add_two_ints_client");\n'
        "  ros::NodeHandle n;\n"
        "  ros::ServiceClient client =\n"
        '      n.serviceClient<ros1_tutorials::TwoInts>("add_two_ints");\n'
        "  return 0;\n}\n",
    )
    write(tmp_path, "src/ros2_tutorials/package.xml", AMENT_PACKAGE.format(name="ros2_tutorials"))
    write(
        tmp_path,
        "src/ros2_tutorials/src/add_two_ints_server.cpp",
        "#include <rclcpp/rclcpp.hpp>\n"
        '#include "example_interfaces/srv/add_two_ints.hpp"\n'
        "int main(int argc, char** argv)\n{\n"
        "  rclcpp::init(argc, argv);\n"
        '  auto node = rclcpp::Node::make_shared("add_two_ints_client");\n'
        "  auto server = node->create_service<example_interfaces::srv::AddTwoInts>(\n"
        '      "add_two_ints", [](auto, auto) {});\n'
        "  rclcpp::spin(node);\n  return 0;\n}\n",
    )
    assert findings(run_cli, tmp_path, ".") == []


def test_case_collisions_only_between_nodes_that_meet(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "src/driver/package.xml", catkin_package("driver"))
    write(
        tmp_path,
        "src/driver/scripts/driver.py",
        TALKER_PY.replace('"chatter"', '"cmd_vel"').replace('"talker"', '"driver"'),
    )
    write(tmp_path, "src/teleop/package.xml", catkin_package("teleop"))
    write(
        tmp_path,
        "src/teleop/scripts/teleop.py",
        TALKER_PY.replace('"chatter"', '"Cmd_Vel"').replace('"talker"', '"teleop"'),
    )
    assert findings(run_cli, tmp_path, ".") == []
    write(tmp_path, "src/teleop/package.xml", catkin_package("teleop", "driver"))
    assert codes(findings(run_cli, tmp_path, ".")) == [
        ("RN401", "src/driver/scripts/driver.py"),
        ("RN401", "src/teleop/scripts/teleop.py"),
    ]


# ---------------------------------------------------------------------------------------
# What the rules may judge

PLANNER_CPP = """\
#include <ros/ros.h>
#include <{type_header}>

namespace {name}
{{
void Planner::initialize(std::string name)
{{
  // The handle's namespace is the plugin's name, known only at run time.
  ros::NodeHandle private_nh("~/" + name);
  potential_pub_ = private_nh.advertise<{type_name}>("potential", 1);
}}
}}  // namespace {name}
"""


def test_names_through_a_handle_of_unknown_namespace_are_not_compared(
    run_cli: Any, tmp_path: Path
) -> None:
    """navfn and global_planner both publish ``potential`` through ``"~/" + name``: the
    two names are not known, so their types are not held against each other."""
    write(tmp_path, "src/planners/package.xml", catkin_package("planners"))
    for name, header, type_name in (
        ("navfn", "sensor_msgs/PointCloud2.h", "sensor_msgs::PointCloud2"),
        ("global_planner", "nav_msgs/OccupancyGrid.h", "nav_msgs::OccupancyGrid"),
    ):
        write(
            tmp_path,
            f"src/planners/src/{name}.cpp",
            PLANNER_CPP.format(name=name, type_header=header, type_name=type_name),
        )
    assert findings(run_cli, tmp_path, ".") == []


def test_rostest_tests_of_one_name_run_one_after_the_other(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "src/master_tests/package.xml", catkin_package("master_tests"))
    write(tmp_path, "src/master_tests/scripts/talker.py", TALKER_PY)
    test_tags = (
        '  <test test-name="simple_api" name="talker" pkg="master_tests" type="talker.py"/>\n'
        '  <test test-name="register" name="talker" pkg="master_tests" type="talker.py"/>\n'
    )
    write(tmp_path, "src/master_tests/test/api.test", f"<launch>\n{test_tags}</launch>\n")
    assert findings(run_cli, tmp_path, ".") == []
    # Without a name each test runs as its test-name (roslaunch's XmlLoader._node_tag):
    # beside a node named as the code names it, nothing clashes.
    unnamed = test_tags.replace(' name="talker"', "")
    write(
        tmp_path,
        "src/master_tests/test/api.test",
        '<launch>\n  <node name="talker" pkg="master_tests" type="talker.py"/>\n'
        f"{unnamed}</launch>\n",
    )
    assert findings(run_cli, tmp_path, ".") == []
    # A node runs the whole time: a test of its name clashes with it, and is reported
    # (the node, started first, is named beside each).
    write(
        tmp_path,
        "src/master_tests/test/api.test",
        '<launch>\n  <node name="talker" pkg="master_tests" type="talker.py"/>\n'
        f"{test_tags}</launch>\n",
    )
    assert [(f["code"], f["line"]) for f in findings(run_cli, tmp_path, ".")] == [
        ("RN402", 3),
        ("RN402", 4),
    ]


def test_anonymous_launch_names_are_never_duplicates(run_cli: Any, tmp_path: Path) -> None:
    """``$(anon x)`` makes each name unique; it used to fall back to the code's name."""
    write(tmp_path, "src/viz/package.xml", catkin_package("viz"))
    write(tmp_path, "src/viz/scripts/talker.py", TALKER_PY)
    write(
        tmp_path,
        "src/viz/launch/view.launch",
        "<launch>\n"
        '  <node name="$(anon talker)" pkg="viz" type="talker.py"/>\n'
        '  <node name="$(anon talker)" pkg="viz" type="talker.py"/>\n'
        "</launch>\n",
    )
    assert findings(run_cli, tmp_path, ".") == []


POLLING_NODE_HPP = """\
#pragma once
#include <rclcpp/rclcpp.hpp>
#include <autoware_utils/ros/polling_subscriber.hpp>
#include <geometry_msgs/msg/accel_with_covariance_stamped.hpp>

namespace planner
{
class PlannerNode : public rclcpp::Node
{
public:
  explicit PlannerNode(const rclcpp::NodeOptions & options);

private:
  // A wrapper the linter does not know: only the string says which topic it reads.
  autoware_utils::InterProcessPollingSubscriber<geometry_msgs::msg::AccelWithCovarianceStamped>
    sub_acceleration_{this, "~/input/accel"};
  rclcpp::Publisher<std_msgs::msg::String>::SharedPtr path_pub_;
};
}  // namespace planner
"""

POLLING_NODE_CPP = """\
#include "planner/node.hpp"

namespace planner
{
PlannerNode::PlannerNode(const rclcpp::NodeOptions & options)
: rclcpp::Node("planner", options)
{
  path_pub_ = create_publisher<std_msgs::msg::String>("~/output/path", 1);
}
}  // namespace planner

#include <rclcpp_components/register_node_macro.hpp>
RCLCPP_COMPONENTS_REGISTER_NODE(planner::PlannerNode)
"""


def test_a_remap_of_a_name_only_a_header_spells_is_not_unused(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "src/planner/package.xml", AMENT_PACKAGE.format(name="planner"))
    write(
        tmp_path,
        "src/planner/CMakeLists.txt",
        "cmake_minimum_required(VERSION 3.14)\nproject(planner)\n"
        "add_library(planner_lib SHARED src/node.cpp)\n"
        "rclcpp_components_register_node(planner_lib\n"
        '  PLUGIN "planner::PlannerNode"\n  EXECUTABLE planner_node)\n',
    )
    write(tmp_path, "src/planner/include/planner/node.hpp", POLLING_NODE_HPP)
    write(tmp_path, "src/planner/src/node.cpp", POLLING_NODE_CPP)
    write(
        tmp_path,
        "src/planner/launch/planner.launch.xml",
        "<launch>\n"
        '  <node pkg="planner" exec="planner_node" name="planner">\n'
        '    <remap from="~/input/accel" to="/localization/acceleration"/>\n'
        '    <remap from="~/output/path" to="/planning/path"/>\n'
        '    <remap from="~/output/trajectory" to="/planning/trajectory"/>\n'
        "  </node>\n"
        "</launch>\n",
    )
    found = findings(run_cli, tmp_path, ".")
    assert [(f["code"], f["line"]) for f in found] == [("RN404", 5)]
    assert "'/planner/output/trajectory'" in found[0]["message"]


def test_rospy_wait_for_message_uses_its_topic(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "src/checks/package.xml", catkin_package("checks"))
    write(
        tmp_path,
        "src/checks/scripts/check_value.py",
        "#!/usr/bin/env python\n"
        "import rospy\nfrom std_msgs.msg import Float32\n\n\n"
        "def main():\n"
        '    rospy.init_node("check_value")\n'
        '    msg = rospy.wait_for_message("input", Float32, 1.0)\n'
        '    rospy.loginfo("got %f", msg.data)\n\n\n'
        'if __name__ == "__main__":\n    main()\n',
    )
    write(
        tmp_path,
        "src/checks/launch/check.launch",
        "<launch>\n"
        '  <node name="check_value" pkg="checks" type="check_value.py">\n'
        '    <remap from="input" to="/num2"/>\n'
        "  </node>\n"
        "</launch>\n",
    )
    assert findings(run_cli, tmp_path, ".") == []
    edges = graph_of(run_cli, tmp_path)["edges"]
    assert [(e["node"], e["edge"], e["resource"]) for e in edges] == [
        ("/check_value", "subscribe", "/num2")
    ]


# ---------------------------------------------------------------------------------------
# The pieces


def test_package_xml_dependencies_of_every_format() -> None:
    text = """<package format="3">
      <name>demo</name>
      <buildtool_depend>ament_cmake</buildtool_depend>
      <depend>rclcpp</depend>
      <build_depend>std_msgs</build_depend>
      <exec_depend condition="$ROS_VERSION == 2">launch_ros</exec_depend>
      <run_depend>rospy</run_depend>
      <test_depend>ament_lint_auto</test_depend>
      <doc_depend>doxygen</doc_depend>
      <!-- <depend>commented_out</depend> -->
    </package>"""
    assert package_xml_depends(text) == {
        "rclcpp",
        "std_msgs",
        "launch_ros",
        "rospy",
        "ament_lint_auto",
    }


def test_companions_are_dependencies_dependents_and_siblings() -> None:
    packages = [
        Package(
            "turtlebot3", "src/turtlebot3", frozenset({"turtlebot3_node", "turtlebot3_teleop"})
        ),
        Package("turtlebot3_node", "src/turtlebot3_node", frozenset({"rclcpp"})),
        Package("turtlebot3_teleop", "src/turtlebot3_teleop"),
        Package("nav2_system_tests", "src/nav2_system_tests", frozenset({"nav2_util"})),
        Package("nav2_util", "src/nav2_util"),
    ]
    companions = WorkspaceIndex([], packages).companions()
    assert companions["turtlebot3_teleop"] == {"turtlebot3", "turtlebot3_node", "turtlebot3_teleop"}
    assert companions["nav2_util"] == {"nav2_util", "nav2_system_tests"}
    assert "rclcpp" not in companions["turtlebot3_node"]  # not a package of the workspace


def test_name_shaped_literals() -> None:
    source = (
        'sub_{this, "~/input/accel"}; pub("/planning/path"); log("hello world");'
        ' name = \'scan\'; url = "http://x"; empty = ""; n = "9lives";'
    )
    assert name_literals(source) == ("/planning/path", "scan", "~/input/accel")
    assert name_literals(source.encode("utf-8")) == name_literals(source)


def test_facts_holding_only_literals_survive_the_cache(run_cli: Any, tmp_path: Path) -> None:
    """A header whose only evidence is a literal used to be cached as empty: the warm run
    then lost the literal and reported what the cold run did not."""
    test_a_remap_of_a_name_only_a_header_spells_is_not_unused(run_cli, tmp_path)
    cache = ["--cache-dir", str(tmp_path / "cache")]
    cold = run_cli(["check", "--select", "RN404", *cache, "."], tmp_path)
    warm = run_cli(["check", "--select", "RN404", *cache, "."], tmp_path)
    assert cold.stdout.count("RN404") == 1
    assert warm.stdout == cold.stdout


def test_a_package_name_two_directories_claim_is_not_guessed(run_cli: Any, tmp_path: Path) -> None:
    """A ROS 1 and a ROS 2 copy of tf2_ros: a ROS 2 launch file starting two unnamed
    static_transform_publishers used to get the ROS 1 program's fixed name, twice."""
    write(tmp_path, "src/ros1/tf2_ros/package.xml", catkin_package("tf2_ros"))
    write(
        tmp_path,
        "src/ros1/tf2_ros/src/static_transform_publisher.cpp",
        "#include <ros/ros.h>\nint main(int argc, char** argv)\n{\n"
        '  ros::init(argc, argv, "static_transform_publisher");\n  return 0;\n}\n',
    )
    write(tmp_path, "src/ros2/tf2_ros/package.xml", AMENT_PACKAGE.format(name="tf2_ros"))
    write(tmp_path, "src/ros2/bringup/package.xml", AMENT_PACKAGE.format(name="bringup"))
    node = "    Node(package='tf2_ros', executable='static_transform_publisher', arguments=[]),\n"
    write(
        tmp_path,
        "src/ros2/bringup/launch/frames.launch.py",
        "from launch import LaunchDescription\nfrom launch_ros.actions import Node\n\n\n"
        f"def generate_launch_description():\n    return LaunchDescription([\n{node}{node}    ])\n",
    )
    assert findings(run_cli, tmp_path, ".") == []


def test_an_include_argument_of_unknown_value_is_not_its_default(
    run_cli: Any, tmp_path: Path
) -> None:
    """Each robot's driver is named from an environment variable: the included file's
    default name is not what either include starts, so there is no duplicate."""
    write(tmp_path, "src/fleet/package.xml", catkin_package("fleet"))
    write(tmp_path, "src/fleet/scripts/talker.py", TALKER_PY)
    write(
        tmp_path,
        "src/fleet/launch/driver.launch",
        "<launch>\n"
        '  <arg name="driver_name" default="driver"/>\n'
        '  <node name="$(arg driver_name)" pkg="fleet" type="talker.py"/>\n'
        "</launch>\n",
    )
    write(
        tmp_path,
        "src/fleet/launch/fleet.launch",
        "<launch>\n"
        '  <include file="$(find fleet)/launch/driver.launch">\n'
        '    <arg name="driver_name" value="$(env FIRST_DRIVER)"/>\n'
        "  </include>\n"
        '  <include file="$(find fleet)/launch/driver.launch">\n'
        '    <arg name="driver_name" value="$(env SECOND_DRIVER)"/>\n'
        "  </include>\n"
        "</launch>\n",
    )
    assert findings(run_cli, tmp_path, ".") == []
    assert graph_of(run_cli, tmp_path)["nodes"] == []  # their names are unknown


def test_a_workspace_named_like_a_test_is_not_one(run_cli: Any, tmp_path: Path) -> None:
    """Only a package's own directories say "test": ~/test_ws/src/... is a workspace."""
    workspace = tmp_path / "test_ws"
    two_tutorial_packages(workspace, "talker_tutorial")
    found = findings(run_cli, tmp_path, "test_ws")
    assert [f["code"] for f in found] == ["RN403", "RN403"]
    write(workspace, "src/counter_tutorial/test/counter_test.py", COUNTER_PY)
    assert len(findings(run_cli, tmp_path, "test_ws")) == 2  # test/ of a package: left out
