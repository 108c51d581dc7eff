"""A node name rostest gives: the name a ROS 1 test hands ``ros::init`` where only rostest
starts the executable (``workspace.built``, ``checks.rostest_replaces``)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest
from conftest import CATKIN_PACKAGE, write

from roslint_names import graph_patch
from roslint_names.extract.build import cmake
from roslint_names.model import Generation

# gazebo_ros_pkgs' gazebo_plugins, reduced: the test executable is built only by
# add_rostest_gtest, and its .test file starts it under the test-name.
GAZEBO_PLUGINS_CMAKE = """cmake_minimum_required(VERSION 2.8.3)
project(gazebo_plugins)

find_package(catkin REQUIRED COMPONENTS roscpp gazebo_msgs tf)
catkin_package(LIBRARIES gazebo_ros_p3d CATKIN_DEPENDS roscpp gazebo_msgs)
include_directories(include ${catkin_INCLUDE_DIRS})

add_library(gazebo_ros_p3d src/gazebo_ros_p3d.cpp)
target_link_libraries(gazebo_ros_p3d ${catkin_LIBRARIES})

install(DIRECTORY test
  DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}
  )

# Tests
# These need to be run with -j1 flag because gazebo can't be run
# in parallel.
if (CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)

  add_rostest_gtest(set_model_state-test
                    test/set_model_state_test/set_model_state_test.test
                    test/set_model_state_test/set_model_state_test.cpp)
  target_link_libraries(set_model_state-test ${catkin_LIBRARIES})

  add_rostest(test/range/range_plugin.test)
endif()
"""
SET_MODEL_STATE_LAUNCH = """<!-- Launch file for ekf_localization_node_test-interfaces -->

<launch>
    <param name="/use_sim_time" value="true" />

    <!-- gazebo server-->
    <node name="gazebo" pkg="gazebo_ros" type="gzserver" respawn="false" output="screen"
          args="--verbose $(find gazebo_plugins)/test/set_model_state_test/p2dx.world" />

    <test test-name="set_model_state_test" pkg="gazebo_plugins" type="set_model_state-test"
          clear_params="true" time-limit="100.0" />
</launch>
"""
SET_MODEL_STATE_TEST = """#include <ros/ros.h>
#include <gazebo_msgs/ModelState.h>
#include <gazebo_msgs/ModelStates.h>

#include <gtest/gtest.h>

bool vehicleSpawned_;

void modelStatesCallback(const gazebo_msgs::ModelStatesConstPtr &msg)
{
  vehicleSpawned_ = !msg->name.empty();
}

TEST (ModelStateTest, FrameTest)
{
  ros::NodeHandle nh;
  ros::Subscriber modelStatesSub = nh.subscribe("model_states", 1, &modelStatesCallback);
  while(!vehicleSpawned_)
  {
    ros::spinOnce();
    ros::Duration(0.1).sleep();
  }
  EXPECT_TRUE(vehicleSpawned_);
}

int main(int argc, char **argv)
{
  testing::InitGoogleTest(&argc, argv);

  ros::init(argc, argv, "set_model_state-test");
  ros::Time::init();

  return RUN_ALL_TESTS();
}
"""
P3D_CPP = """#include <ros/ros.h>

namespace gazebo
{
void GazeboRosP3D::Load()
{
  rosnode_ = new ros::NodeHandle(robot_namespace_);
}
}  // namespace gazebo
"""
TEST_SOURCE = "gazebo_plugins/test/set_model_state_test/set_model_state_test.cpp"
INIT_LINE = 30
ROSTEST_GTEST = """add_rostest_gtest(set_model_state-test
                    test/set_model_state_test/set_model_state_test.test
"""


def gazebo_plugins(
    root: Path, *, cmake_text: str = GAZEBO_PLUGINS_CMAKE, test: str = SET_MODEL_STATE_TEST
) -> Path:
    package = root / "gazebo_plugins"
    write(package, "package.xml", CATKIN_PACKAGE.format(name="gazebo_plugins"))
    write(package, "CMakeLists.txt", cmake_text)
    write(package, "src/gazebo_ros_p3d.cpp", P3D_CPP)
    write(package, "test/set_model_state_test/set_model_state_test.test", SET_MODEL_STATE_LAUNCH)
    write(package, "test/set_model_state_test/set_model_state_test.cpp", test)
    return package


def found(run_cli: Any, root: Path) -> list[tuple[str, int, str]]:
    result = run_cli(["check", "--format", "json", "."], root)
    assert result.exit_code in (0, 1), result.stderr
    return [(f["path"], f["line"], f["code"]) for f in result.findings()]


def test_the_node_name_of_a_test_only_rostest_starts_is_not_judged(
    run_cli: Any, tmp_path: Path
) -> None:
    """Before, 'set_model_state-test' was an RN101 ('-' is illegal in ROS 1): but rostest
    starts the test as 'set_model_state_test', the name its .test file gives."""
    gazebo_plugins(tmp_path)
    assert found(run_cli, tmp_path) == []


def test_verbose_names_the_files_whose_node_name_rostest_gives(
    run_cli: Any, tmp_path: Path
) -> None:
    """Also from a stored result, when nothing changed since the run that made it."""
    gazebo_plugins(tmp_path)
    for _ in range(2):
        result = run_cli(["check", "--verbose", "."], tmp_path)
        assert f"{TEST_SOURCE}: only rostest starts what it is built into" in result.stderr
    assert "its result reused" in result.stderr


def test_a_per_file_run_judges_by_the_workspace_build(run_cli: Any, tmp_path: Path) -> None:
    """pre-commit names the test alone; the CMakeLists.txt of its package is context."""
    gazebo_plugins(tmp_path)
    (tmp_path / ".git").mkdir()
    result = run_cli(["check", "--format", "json", TEST_SOURCE], tmp_path)
    assert result.findings() == []


def test_a_camel_case_node_name_rostest_gives_is_not_judged(run_cli: Any, tmp_path: Path) -> None:
    """RN203 judges the name ros::init is handed too, in test code where a project asks
    for it: rostest replaces it the same."""
    write(tmp_path, "roslint-names.toml", '[test-code]\nextend-select = ["RN203"]\n')
    test = SET_MODEL_STATE_TEST.replace('"set_model_state-test"', '"setModelStateTest"')
    gazebo_plugins(tmp_path, test=test)
    assert found(run_cli, tmp_path) == []
    gazebo_plugins(
        tmp_path,
        cmake_text=GAZEBO_PLUGINS_CMAKE.replace("add_rostest_gtest", "add_executable"),
        test=test,
    )
    assert found(run_cli, tmp_path) == [(TEST_SOURCE, INIT_LINE, "RN203")]


@pytest.mark.parametrize(
    "cmake_text",
    [
        # rosrun starts a program with no __name: ros::init's name is the node's.
        GAZEBO_PLUGINS_CMAKE.replace(ROSTEST_GTEST, "add_executable(set_model_state-test\n"),
        # catkin's run_tests starts a gtest itself.
        GAZEBO_PLUGINS_CMAKE.replace(ROSTEST_GTEST, "catkin_add_gtest(set_model_state-test\n"),
        # Built for rostest, and into a program of its own.
        GAZEBO_PLUGINS_CMAKE
        + "add_executable(set_model_state_tool\n"
        + "               test/set_model_state_test/set_model_state_test.cpp)\n",
        # A macro of another package handed it.
        GAZEBO_PLUGINS_CMAKE + "gazebo_add_test(set_model_state_test)\n",
    ],
    ids=["add-executable", "catkin-add-gtest", "also-a-program", "foreign-macro"],
)
def test_a_source_anything_else_may_build_keeps_its_node_name_finding(
    run_cli: Any, tmp_path: Path, cmake_text: str
) -> None:
    gazebo_plugins(tmp_path, cmake_text=cmake_text)
    assert found(run_cli, tmp_path) == [(TEST_SOURCE, INIT_LINE, "RN101")]


def test_the_test_s_other_names_are_judged(run_cli: Any, tmp_path: Path) -> None:
    """Only the node name is rostest's to give: a topic the test subscribes to is not."""
    test = SET_MODEL_STATE_TEST.replace('"model_states"', '"model-states"')
    gazebo_plugins(tmp_path, test=test)
    assert found(run_cli, tmp_path) == [(TEST_SOURCE, 17, "RN101")]


def test_a_ros2_package_s_node_name_is_judged(run_cli: Any, tmp_path: Path) -> None:
    """rostest is ROS 1's: in a ROS 2 source the name is rclcpp's, whatever the build."""
    package = gazebo_plugins(tmp_path)
    write(
        package,
        "package.xml",
        CATKIN_PACKAGE.format(name="gazebo_plugins")
        .replace(
            "<buildtool_depend>catkin</buildtool_depend>",
            "<buildtool_depend>ament_cmake</buildtool_depend>\n"
            "  <export><build_type>ament_cmake</build_type></export>",
        )
        .replace('format="2"', 'format="3"'),
    )
    test = SET_MODEL_STATE_TEST.replace(
        "#include <ros/ros.h>", "#include <rclcpp/rclcpp.hpp>"
    ).replace(
        'ros::init(argc, argv, "set_model_state-test");',
        "rclcpp::init(argc, argv);\n"
        '  auto node = rclcpp::Node::make_shared("set_model_state-test");',
    )
    write(package, "test/set_model_state_test/set_model_state_test.cpp", test)
    assert [code for _, _, code in found(run_cli, tmp_path)] == ["RN101"]


def test_the_language_server_judges_it_as_the_cli_does(tmp_path: Path) -> None:
    from roslint_names.config import load_settings
    from roslint_names.registry import load_registry
    from roslint_names.session import Session

    package = gazebo_plugins(tmp_path)
    registry = load_registry()
    session = Session(tmp_path, load_settings(None, tmp_path, registry), registry, None)
    session.load()
    source = package / "test/set_model_state_test/set_model_state_test.cpp"
    assert session.check(source, SET_MODEL_STATE_TEST) == []
    cmake_file = package / "CMakeLists.txt"
    session.check(cmake_file, GAZEBO_PLUGINS_CMAKE.replace("add_rostest_gtest", "add_executable"))
    found = session.check(source, SET_MODEL_STATE_TEST) or []
    assert [(d.code, d.span.line) for d in found] == [("RN101", INIT_LINE)]


def test_what_rostest_starts_is_recorded_apart() -> None:
    facts = cmake.extract(
        "CMakeLists.txt", GAZEBO_PLUGINS_CMAKE.encode(), Generation.ROS1, Generation.ROS1
    )
    assert facts.compiled is not None
    assert facts.compiled.paths == ("src/gazebo_ros_p3d.cpp",)
    assert facts.compiled.rostest == (
        "test/set_model_state_test/set_model_state_test.test",
        "test/set_model_state_test/set_model_state_test.cpp",
    )


def test_a_cached_run_judges_again_the_sources_a_build_file_edit_hands_rostest(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The build file edited between cached runs, the test source not: the last build's
    graph is patched (its package's programs made again, ``workspace.program_patch``)
    and the source judged again, as a run without a cache judges it."""
    patched: list[bool] = []
    patch = graph_patch.GraphPatch.__call__

    def recording(*arguments: Any) -> Any:
        found = patch(*arguments)
        patched.append(found is not None)
        return found

    monkeypatch.setattr(graph_patch.GraphPatch, "__call__", recording)
    root = tmp_path / "ws"
    package = gazebo_plugins(root)
    built = GAZEBO_PLUGINS_CMAKE.replace(ROSTEST_GTEST, "add_executable(set_model_state-test\n")
    arguments = ["check", "--format", "json", "--exit-zero"]
    findings = []
    for cmake_text in (GAZEBO_PLUGINS_CMAKE, built, GAZEBO_PLUGINS_CMAKE):
        write(package, "CMakeLists.txt", cmake_text)
        stamp = (package / "CMakeLists.txt").stat().st_mtime + 2  # not the racy window
        os.utime(package / "CMakeLists.txt", (stamp, stamp))
        cached = run_cli([*arguments, "--cache-dir", str(tmp_path / "cache"), "."], root)
        fresh = run_cli([*arguments, "--no-cache", "."], root)
        assert cached.stdout == fresh.stdout
        findings.append([(f["path"], f["code"]) for f in cached.findings()])
    assert findings == [[], [(TEST_SOURCE, "RN101")], []]
    assert patched == [True]  # the last run's files are the first's: its stored result
