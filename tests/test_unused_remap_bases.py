"""RN404 and base classes of other packages' code.

autoware.universe's ground filters (``autoware_ground_segmentation``) derive from
``autoware::pointcloud_preprocessor::Filter``, of another package, whose constructor
subscribes ``input`` and publishes ``output`` for them; their launch files remap both.
Their own sources name neither: a remap of a name that code runs in the node is no
unused remap, and a base class whose code the linter does not read for the node's names
(another package's, or one the workspace does not hold) leaves the node unjudged.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import ament_package, findings_of, line_places, write

FILTER_HPP = """\
#pragma once
#include <string>

#include "rclcpp/rclcpp.hpp"
#include "sensor_msgs/msg/point_cloud2.hpp"

namespace pointcloud_filters
{
class Filter : public rclcpp::Node
{
public:
  Filter(const std::string & name, const rclcpp::NodeOptions & options);

protected:
  virtual void filter(const sensor_msgs::msg::PointCloud2 & input) = 0;
  rclcpp::Publisher<sensor_msgs::msg::PointCloud2>::SharedPtr pub_output_;
  rclcpp::Subscription<sensor_msgs::msg::PointCloud2>::SharedPtr sub_input_;
};
}  // namespace pointcloud_filters
"""

FILTER_CPP = """\
#include "pointcloud_filters/filter.hpp"

namespace pointcloud_filters
{
Filter::Filter(const std::string & name, const rclcpp::NodeOptions & options)
: rclcpp::Node(name, options)
{
  pub_output_ = create_publisher<sensor_msgs::msg::PointCloud2>("output", 10);
  sub_input_ = create_subscription<sensor_msgs::msg::PointCloud2>(
    "input", 10, [this](const sensor_msgs::msg::PointCloud2 & msg) { filter(msg); });
}
}  // namespace pointcloud_filters
"""

NODE_HPP = """\
#pragma once
#include "{include}"

namespace ground_filter
{{
class RayGroundFilter : public {base}
{{
public:
  explicit RayGroundFilter(const rclcpp::NodeOptions & options);

private:
  void filter(const sensor_msgs::msg::PointCloud2 & input) override;
  rclcpp::Publisher<sensor_msgs::msg::PointCloud2>::SharedPtr debug_pub_;
}};
}}  // namespace ground_filter
"""

NODE_CPP = """\
#include "ground_filter/node.hpp"

namespace ground_filter
{
RayGroundFilter::RayGroundFilter(const rclcpp::NodeOptions & options)
: Filter("RayGroundFilter", options)
{
  debug_pub_ = create_publisher<sensor_msgs::msg::PointCloud2>("debug/ground", 1);
}

void RayGroundFilter::filter(const sensor_msgs::msg::PointCloud2 & input)
{
  debug_pub_->publish(input);
}
}  // namespace ground_filter

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::spin(std::make_shared<ground_filter::RayGroundFilter>(rclcpp::NodeOptions()));
  rclcpp::shutdown();
}
"""

LAUNCH = """\
<launch>
  <node pkg="ground_filter" exec="ray_ground_filter" name="ray_ground_filter">
    <remap from="input" to="/sensing/lidar/concatenated/pointcloud"/>
    <remap from="output" to="/perception/obstacle_segmentation/pointcloud"/>
    <remap from="debug/grund" to="/perception/debug/ground"/>
  </node>
</launch>
"""


def ground_filter(root: Path, *, own_base: bool) -> str:
    """The ground filter's package; its base class in it (``own_base``), else in
    ``pointcloud_filters``. Returns the launch file's path."""
    package = "src/ground_filter"
    ament_package(
        root,
        "ground_filter",
        _cmake("ground_filter", "add_executable(ray_ground_filter src/node.cpp)"),
    )
    if own_base:
        include, base = "ground_filter/filter.hpp", "Filter"
        write(root, f"{package}/include/ground_filter/filter.hpp", FILTER_HPP)
        write(
            root,
            f"{package}/src/filter.cpp",
            FILTER_CPP.replace("pointcloud_filters/", "ground_filter/"),
        )
    else:
        include, base = "pointcloud_filters/filter.hpp", "pointcloud_filters::Filter"
    write(
        root,
        f"{package}/include/ground_filter/node.hpp",
        NODE_HPP.format(include=include, base=base),
    )
    write(root, f"{package}/src/node.cpp", NODE_CPP)
    write(root, f"{package}/launch/ray_ground_filter.launch.xml", LAUNCH)
    return f"{package}/launch/ray_ground_filter.launch.xml"


def pointcloud_filters(root: Path) -> None:
    package = "src/pointcloud_filters"
    ament_package(
        root,
        "pointcloud_filters",
        _cmake("pointcloud_filters", "add_library(filter SHARED src/filter.cpp)"),
    )
    write(root, f"{package}/include/pointcloud_filters/filter.hpp", FILTER_HPP)
    write(root, f"{package}/src/filter.cpp", FILTER_CPP)


def _cmake(project: str, target: str) -> str:
    """A package's CMakeLists.txt building ``target``, one command."""
    return (
        f"cmake_minimum_required(VERSION 3.5)\nproject({project})\n"
        f"find_package(ament_cmake REQUIRED)\n{target}\nament_package()\n"
    )


def unused_remaps(run_cli: Any, root: Path) -> list[tuple[str, int]]:
    return line_places(findings_of(run_cli, root, "RN404"))


def test_a_base_class_of_another_package_leaves_the_node_unjudged(
    run_cli: Any, tmp_path: Path
) -> None:
    ground_filter(tmp_path, own_base=False)
    pointcloud_filters(tmp_path)
    assert unused_remaps(run_cli, tmp_path) == []


def test_a_base_class_the_workspace_does_not_hold_leaves_the_node_unjudged(
    run_cli: Any, tmp_path: Path
) -> None:
    ground_filter(tmp_path, own_base=False)
    assert unused_remaps(run_cli, tmp_path) == []


def test_a_base_class_of_the_nodes_own_package_is_read_with_it(
    run_cli: Any, tmp_path: Path
) -> None:
    # The package's code spells 'input' and 'output' (``Graph.mentions``); the misspelled
    # debug topic is still found.
    launch = ground_filter(tmp_path, own_base=True)
    assert unused_remaps(run_cli, tmp_path) == [(launch, 5)]
