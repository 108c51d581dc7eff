"""RN203 and pluginlib: a namespace that is a plugin's name is its class's, not the
writer's choice (``plugins``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from conftest import CATKIN_PACKAGE, write

from roslint_names.generation import PackageGenerations
from roslint_names.plugins import exported_descriptions, plugin_names

# ROS 1 navigation, reduced: base_local_planner exports TrajectoryPlannerROS to nav_core,
# and rotate_recovery reads the planner's parameters under the name move_base gives it.
BLP_MANIFEST = CATKIN_PACKAGE.format(name="base_local_planner").replace(
    "</package>",
    '  <export>\n    <nav_core plugin="${prefix}/blp_plugin.xml" />\n  </export>\n</package>',
)
BLP_PLUGIN_XML = """\
<library path="lib/libtrajectory_planner_ros">
  <class name="base_local_planner/TrajectoryPlannerROS"
         type="base_local_planner::TrajectoryPlannerROS"
         base_class_type="nav_core::BaseLocalPlanner">
    <description>A local planner using either a DWA or Trajectory Rollout approach.</description>
  </class>
</library>
"""
ROTATE_RECOVERY_CPP = """\
#include <ros/ros.h>
#include <rotate_recovery/rotate_recovery.h>

namespace rotate_recovery
{
void RotateRecovery::initialize(std::string name, tf2_ros::Buffer*,
                                costmap_2d::Costmap2DROS*, costmap_2d::Costmap2DROS* local_costmap)
{
  ros::NodeHandle private_nh("~/" + name);
  ros::NodeHandle blp_nh("~/TrajectoryPlannerROS");
  private_nh.param("sim_granularity", sim_granularity_, 0.017);
  blp_nh.param("acc_lim_th", acc_lim_th_, 3.2);
}
}  // namespace rotate_recovery
"""
RECOVERY = "src/navigation/rotate_recovery/src/rotate_recovery.cpp"


def navigation(root: Path, plugin_xml: str = BLP_PLUGIN_XML) -> None:
    blp = root / "src/navigation/base_local_planner"
    write(blp, "package.xml", BLP_MANIFEST)
    write(blp, "blp_plugin.xml", plugin_xml)
    recovery = root / "src/navigation/rotate_recovery"
    write(recovery, "package.xml", CATKIN_PACKAGE.format(name="rotate_recovery"))
    write(root, RECOVERY, ROTATE_RECOVERY_CPP)


def rn203(run_cli: Any, root: Path, *paths: str) -> list[tuple[str, int]]:
    result = run_cli(["check", "--format", "json", "--select", "RN203", *(paths or ".")], root)
    assert result.exit_code in (0, 1), result.stderr
    return [(f["path"], f["line"]) for f in result.findings()]


def test_a_plugins_name_as_a_namespace_is_not_the_writers(run_cli: Any, tmp_path: Path) -> None:
    """Before, RN203 asked for '~/trajectory_planner_ros', where nothing would be read."""
    navigation(tmp_path)
    assert rn203(run_cli, tmp_path) == []
    assert rn203(run_cli, tmp_path, RECOVERY) == []  # a pre-commit run over the file


def test_without_the_plugin_the_name_is_the_writers(run_cli: Any, tmp_path: Path) -> None:
    navigation(tmp_path, BLP_PLUGIN_XML.replace('TrajectoryPlannerROS"\n', 'Planner"\n'))
    assert rn203(run_cli, tmp_path) == [(RECOVERY, 10)]


def test_an_edited_description_is_read_again(run_cli: Any, tmp_path: Path) -> None:
    """The stored result of a run depends on the descriptions too: no stale answer."""
    navigation(tmp_path)
    assert rn203(run_cli, tmp_path) == []
    renamed = BLP_PLUGIN_XML.replace("base_local_planner/TrajectoryPlannerROS", "blp/Planner")
    renamed = renamed.replace("base_local_planner::TrajectoryPlannerROS", "blp::Planner")
    write(tmp_path, "src/navigation/base_local_planner/blp_plugin.xml", renamed)
    assert rn203(run_cli, tmp_path) == [(RECOVERY, 10)]


def test_descriptions_and_names_as_pluginlib_reads_them() -> None:
    manifest = BLP_MANIFEST.replace(
        "</export>", '<!-- <rviz plugin="${prefix}/old.xml"/> -->\n  </export>'
    )
    assert exported_descriptions(manifest) == ["blp_plugin.xml"]
    assert plugin_names(BLP_PLUGIN_XML) == {"TrajectoryPlannerROS"}
    # ROS 2: a class without a name is looked up by its type.
    ros2 = (
        '<library path="x"><class type="nav2_mppi_controller::MPPIController" '
        'base_class_type="nav2_core::Controller"/></library>'
    )
    assert plugin_names(ros2) == {"MPPIController"}


def test_a_node_named_like_a_plugin_class_is_the_writers_choice(
    run_cli: Any, tmp_path: Path
) -> None:
    """slam_toolbox's RViz panel names its own node 'SlamToolboxPlugin', the class's name:
    pluginlib gives that name to no node, so the writer chose it."""
    navigation(tmp_path)
    node = ROTATE_RECOVERY_CPP.replace(
        '  ros::NodeHandle private_nh("~/" + name);',
        '  auto node = rclcpp::Node::make_shared("TrajectoryPlannerROS");',
    )
    write(tmp_path, RECOVERY, node)
    assert rn203(run_cli, tmp_path) == [(RECOVERY, 9)]


@pytest.mark.usefixtures("old_tree")
def test_a_run_after_an_edit_knows_the_plugins_without_reading_a_manifest(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """It takes up the last run's package lookups (``unchanged``), the plugin names with
    them; an edited description is read again (its status is one they were kept with)."""
    navigation(tmp_path)
    assert rn203(run_cli, tmp_path) == []
    looked_for: list[str] = []
    is_manifest = PackageGenerations._is_manifest

    def counted(self: PackageGenerations, directory: str, manifest: str) -> bool:
        looked_for.append(manifest)
        return is_manifest(self, directory, manifest)

    monkeypatch.setattr(PackageGenerations, "_is_manifest", counted)
    recovery = tmp_path / RECOVERY
    recovery.write_text(recovery.read_text().replace("3.2", "3.25"))
    assert rn203(run_cli, tmp_path) == []
    assert looked_for == []
    renamed = BLP_PLUGIN_XML.replace("base_local_planner/TrajectoryPlannerROS", "blp/Planner")
    write(tmp_path, "src/navigation/base_local_planner/blp_plugin.xml", renamed)
    recovery.write_text(recovery.read_text().replace("3.25", "3.3"))
    assert rn203(run_cli, tmp_path) == [(RECOVERY, 10)]
    assert looked_for
