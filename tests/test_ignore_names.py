"""RN203's ``ignore-names``: a project's CamelCase names stated once, and proposed where a
package has many of one kind (image_pipeline's component nodes, gmapping's parameters)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import write, write_package

# An image_pipeline-shaped ROS 2 component (depth_image_proc/src/convert_metric.cpp,
# reduced): the node's default name is its class name, as in all ten of that package.
COMPONENT = """#include <memory>
#include <string>

#include <rclcpp/rclcpp.hpp>
#include <sensor_msgs/msg/image.hpp>

namespace depth_image_proc
{{

class {name} : public rclcpp::Node
{{
public:
  explicit {name}(const rclcpp::NodeOptions & options)
  : Node("{name}", options)
  {{
    this->declare_parameter<std::string>("image_transport", "raw");
    pub_ = create_publisher<sensor_msgs::msg::Image>("image", 10);
  }}

private:
  rclcpp::Publisher<sensor_msgs::msg::Image>::SharedPtr pub_;
}};

}}  // namespace depth_image_proc

#include "rclcpp_components/register_node_macro.hpp"
RCLCPP_COMPONENTS_REGISTER_NODE(depth_image_proc::{name})
"""

DEPTH_NODES = (
    "ConvertMetricNode",
    "CropForemostNode",
    "DisparityNode",
    "PointCloudXyzNode",
    "PointCloudXyziNode",
    "RegisterNode",
)


def _image_pipeline(root: Path) -> None:
    """depth_image_proc's six components, and image_publisher's one CamelCase node."""
    write_package(root / "depth_image_proc", 2, "depth_image_proc")
    for name in DEPTH_NODES:
        write(root, f"depth_image_proc/src/{name.lower()}.cpp", COMPONENT.format(name=name))
    write_package(root / "image_publisher", 2, "image_publisher")
    write(
        root,
        "image_publisher/src/image_publisher.cpp",
        COMPONENT.format(name="ImagePublisher").replace("depth_image_proc", "image_publisher"),
    )


def test_a_package_of_camel_case_components_is_proposed_one_pattern(
    run_cli: Any, tmp_path: Path
) -> None:
    _image_pipeline(tmp_path)
    result = run_cli(["check", "--no-cache", "."], tmp_path)
    assert result.exit_code == 1
    assert result.stdout.count("[RN203 not-snake-case]") == 7
    assert result.stderr.splitlines()[1:] == [
        "7 findings are one decision: if the names are this project's convention, state it "
        "in roslint-names.toml ([tool.roslint-names] in pyproject.toml), else fix them:",
        "  [rules.RN203]",
        '  ignore-names = ["*Node", "ImagePublisher"]    # RN203: 7 findings',
    ]
    # image_publisher, beside the packages that state the convention, follows it too;
    # stated, the seven are gone.
    stated_names = '[rules.RN203]\nignore-names = ["*Node", "ImagePublisher"]\n'
    write(tmp_path, "roslint-names.toml", stated_names)
    stated = run_cli(["check", "--no-cache", "--format", "json", "."], tmp_path)
    assert stated.findings() == []
    assert "one decision" not in stated.stderr


# ros2/demos: CamelCase node names here and there, among dozens of snake_case ones.
CLIENT = """#include <rclcpp/rclcpp.hpp>
#include <example_interfaces/srv/add_two_ints.hpp>

namespace composition
{{
class {name} : public rclcpp::Node
{{
public:
  explicit {name}(const rclcpp::NodeOptions & options)
  : Node("{name}", options)
  {{
    client_ = create_client<example_interfaces::srv::AddTwoInts>("add_two_ints");
  }}

private:
  rclcpp::Client<example_interfaces::srv::AddTwoInts>::SharedPtr client_;
}};
}}  // namespace composition
"""

TALKER = """import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class {cls}(Node):
    def __init__(self):
        super().__init__("{name}")
        self.pub = self.create_publisher(String, "chatter", 10)


def main():
    rclpy.init()
    rclpy.spin({cls}())
"""

# ros2/demos' node names, in product packages (demo code itself is judged as test code):
# six CamelCase names over four packages.
PRODUCTS = {
    "composition": ["Client", "Server", "talker", "listener"],
    "robot_nodes_cpp": ["TestNode", "add_two_ints_client", "add_two_ints_server", "talker"],
    "robot_nodes_py": ["LoggerServiceNode", "TestNode", "listener_qos", "talker_qos"],
    "quality_of_service": ["MessageLostListener", "deadline", "lifespan", "liveliness"],
    "topic_monitor": ["topic_monitor", "data_publisher"],
}


def test_camel_case_names_spread_over_packages_are_slips_not_a_convention(
    run_cli: Any, tmp_path: Path
) -> None:
    for package, names in PRODUCTS.items():
        write_package(tmp_path / package, 2, package)
        for index, name in enumerate(names):
            if package.endswith("_py"):
                text = TALKER.format(cls=f"Node{index}", name=name)
                write(tmp_path, f"{package}/{package}/node_{index}.py", text)
            else:
                write(tmp_path, f"{package}/src/node_{index}.cpp", CLIENT.format(name=name))
    result = run_cli(["check", "--no-cache", "."], tmp_path)
    assert result.exit_code == 1
    # robot_nodes_cpp's and robot_nodes_py's TestNode are one name: one finding (``decisions``)
    assert result.stdout.count("[RN203 not-snake-case]") == 5
    assert "one decision" not in result.stderr
    statistics = run_cli(["check", "--no-cache", "--statistics", "."], tmp_path)
    assert "ignore-names" not in statistics.stdout + statistics.stderr


# gmapping's slam_gmapping.cpp, reduced: its parameter API since 2008, camelCase where
# OpenSLAM's GMapping named them so, snake_case where ROS added them.
GMAPPING = """#include <ros/ros.h>
#include <nav_msgs/OccupancyGrid.h>

class SlamGMapping
{
public:
  SlamGMapping() : private_nh_("~")
  {
    private_nh_.param("base_frame", base_frame_, std::string("base_link"));
    private_nh_.param("transform_publish_period", transform_publish_period_, 0.05);
    if(!private_nh_.getParam("minimumScore", minimum_score_))
      minimum_score_ = 0;
    if(!private_nh_.getParam("sigma", sigma_))
      sigma_ = 0.05;
    if(!private_nh_.getParam("kernelSize", kernelSize_))
      kernelSize_ = 1;
    if(!private_nh_.getParam("linearUpdate", linearUpdate_))
      linearUpdate_ = 1.0;
    if(!private_nh_.getParam("angularUpdate", angularUpdate_))
      angularUpdate_ = 0.5;
    if(!private_nh_.getParam("temporalUpdate", temporalUpdate_))
      temporalUpdate_ = -1.0;
    if(!private_nh_.getParam("resampleThreshold", resampleThreshold_))
      resampleThreshold_ = 0.5;
    if(!private_nh_.getParam("particles", particles_))
      particles_ = 30;
    sst_ = node_.advertise<nav_msgs::OccupancyGrid>("map", 1, true);
  }

  void initMapper(double range_max)
  {
    if(!private_nh_.getParam("maxRange", maxRange_))
      maxRange_ = range_max - 0.01;
    if(!private_nh_.getParam("maxUrange", maxUrange_))
      maxUrange_ = maxRange_;
  }

private:
  ros::NodeHandle node_;
  ros::NodeHandle private_nh_;
  ros::Publisher sst_;
  std::string base_frame_;
  double transform_publish_period_, sigma_, maxRange_, maxUrange_;
  double linearUpdate_, angularUpdate_, temporalUpdate_, resampleThreshold_;
  int minimum_score_, kernelSize_, particles_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "slam_gmapping");
  SlamGMapping gn;
  ros::spin();
  return 0;
}
"""

GMAPPING_NAMES = (
    '["*Update", "kernelSize", "maxRange", "maxUrange", "minimumScore", "resampleThreshold"]'
)


def test_a_ros1_nodes_camel_case_parameters_are_proposed_by_name(
    run_cli: Any, tmp_path: Path
) -> None:
    write_package(tmp_path / "gmapping", 1, "gmapping")
    write(tmp_path, "gmapping/src/slam_gmapping.cpp", GMAPPING)
    result = run_cli(["check", "--no-cache", "."], tmp_path)
    assert result.stdout.count("[RN203 not-snake-case]") == 8
    # Three end in "Update": one pattern; the others are listed as they are.
    assert f"  ignore-names = {GMAPPING_NAMES}  # RN203: 8 findings" in result.stderr
    write(
        tmp_path, "roslint-names.toml", f"[rules.not-snake-case]\nignore-names = {GMAPPING_NAMES}\n"
    )
    stated = run_cli(["check", "--no-cache", "."], tmp_path)
    assert stated.exit_code == 0, stated.stdout
    # --statistics proposes what a configuration leaves unstated.
    write(tmp_path, "roslint-names.toml", "max-depth = 4\n")
    statistics = run_cli(["check", "--no-cache", "--statistics", "."], tmp_path)
    assert f"  ignore-names = {GMAPPING_NAMES}  # RN203: 8 findings" in statistics.stdout


# A ROS 1 driver whose topics mix a CamelCase namespace with camelCase names.
DRIVER = """#include <ros/ros.h>
#include <std_msgs/Float64.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "base_driver");
  ros::NodeHandle nh;
  ros::Publisher speed = nh.advertise<std_msgs::Float64>("Base/motorSpeed", 10);
  ros::Publisher odom = nh.advertise<std_msgs::Float64>("Base/odom", 10);
  ros::spin();
  return 0;
}
"""


def _driver_findings(run_cli: Any, tmp_path: Path, patterns: str) -> list[str]:
    write_package(tmp_path, 1, "base_driver")
    write(tmp_path, "src/base_driver.cpp", DRIVER)
    write(tmp_path, "roslint-names.toml", f"[rules.RN203]\nignore-names = {patterns}\n")
    result = run_cli(["check", "--no-cache", "--format", "json", "src"], tmp_path)
    assert result.exit_code in (0, 1), result.stderr
    return [finding["message"].split("'")[1] for finding in result.findings()]


def test_a_name_is_silenced_when_each_of_its_camel_case_tokens_is_covered(
    run_cli: Any, tmp_path: Path
) -> None:
    assert _driver_findings(run_cli, tmp_path, '["Base"]') == ["Base/motorSpeed"]
    assert _driver_findings(run_cli, tmp_path, '["Base", "*Speed"]') == []
    assert _driver_findings(run_cli, tmp_path, '["motor*"]') == ["Base/motorSpeed", "Base/odom"]
    # The whole name matches: '*' crosses levels.
    assert _driver_findings(run_cli, tmp_path, '["Base/*"]') == []
    assert _driver_findings(run_cli, tmp_path, '["base*"]') == ["Base/motorSpeed", "Base/odom"]


def test_a_bad_pattern_ends_the_run_naming_the_key(run_cli: Any, tmp_path: Path) -> None:
    write_package(tmp_path / "gmapping", 1, "gmapping")
    write(tmp_path, "gmapping/src/slam_gmapping.cpp", GMAPPING)
    write(tmp_path, "roslint-names.toml", '[rules.RN203]\nignore-names = ["max?ange"]\n')
    result = run_cli(["check", "--no-cache", "."], tmp_path)
    assert result.exit_code == 2
    assert "rules.RN203.ignore-names: invalid pattern 'max?ange'" in result.stderr
