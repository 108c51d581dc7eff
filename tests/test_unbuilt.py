"""Files that never run: a C++ source no build file of its package compiles
(``workspace.built``), a roslaunch file left in a ROS 2 package (``launch_tree.runs``)."""

from __future__ import annotations

import json
import posixpath
from pathlib import Path
from typing import Any

import pytest
from conftest import AMENT_PACKAGE, write

from roslint_names.extract.build import cmake
from roslint_names.model import CompiledSources, FileFacts, Generation, Language
from roslint_names.workspace.built import BuiltSources

# moveit2's moveit_ros/perception, reduced: the package's CMakeLists.txt includes a
# .cmake file of its own and adds the mesh_filter directory, whose CMakeLists.txt builds
# the library and leaves the ROS 1 nodelet commented out ("TODO: Port to ROS2").
PERCEPTION_CMAKE = """cmake_minimum_required(VERSION 3.22)
project(moveit_ros_perception LANGUAGES CXX)

find_package(moveit_common REQUIRED)
moveit_package()
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
find_package(image_transport REQUIRED)

# Finds Boost Components
include(ConfigExtras.cmake)

set(THIS_PACKAGE_INCLUDE_DIRS mesh_filter/include)
include_directories(${THIS_PACKAGE_INCLUDE_DIRS})

add_subdirectory(mesh_filter)

install(TARGETS moveit_mesh_filter EXPORT moveit_ros_perceptionTargets
        LIBRARY DESTINATION lib)
ament_export_targets(moveit_ros_perceptionTargets HAS_LIBRARY_TARGET)
ament_package(CONFIG_EXTRAS ConfigExtras.cmake)
"""
CONFIG_EXTRAS = """set(THIS_PACKAGE_INCLUDE_DEPENDS Boost)
find_package(Boost REQUIRED system filesystem date_time thread)
"""
MESH_FILTER_CMAKE = """add_library(
  moveit_mesh_filter SHARED
  src/mesh_filter_base.cpp src/sensor_model.cpp)
include(GenerateExportHeader)
generate_export_header(moveit_mesh_filter)
target_include_directories(
  moveit_mesh_filter PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_BINARY_DIR}>)
set_target_properties(moveit_mesh_filter
                      PROPERTIES VERSION "${${PROJECT_NAME}_VERSION}")
target_link_libraries(moveit_mesh_filter ${GL_LIBS} rclcpp::rclcpp)

# TODO: Port to ROS2 add_library(moveit_depth_self_filter SHARED
# src/depth_self_filter_nodelet.cpp src/transform_provider.cpp )
# target_link_libraries(moveit_depth_self_filter ${catkin_LIBRARIES}
# moveit_mesh_filter)

install(DIRECTORY include/ DESTINATION include/moveit_ros_perception)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/moveit_mesh_filter_export.h
        DESTINATION include/moveit_ros_perception)
"""
# depth_self_filter_nodelet.cpp, reduced: absolute topics (RN202) in a file nothing builds.
NODELET_CPP = """#include <image_transport/image_transport.hpp>
#include <rclcpp/rclcpp.hpp>

namespace mesh_filter
{
void DepthSelfFiltering::onInit()
{
  auto nh = rclcpp::Node::make_shared("depth_self_filter");
  filtered_depth_transport_ = std::make_shared<image_transport::ImageTransport>(nh);
  pub_filtered_depth_image_ = filtered_depth_transport_->advertiseCamera("/filtered/depth", 1);
  pub_model_depth_image_ = filtered_depth_transport_->advertiseCamera("/model/depth", 1);
}
}  // namespace mesh_filter
"""
# The built library makes the same mistake: it is reported.
SENSOR_MODEL_CPP = """#include <rclcpp/rclcpp.hpp>
#include <sensor_msgs/msg/image.hpp>

namespace mesh_filter
{
void SensorModel::advertise(const rclcpp::Node::SharedPtr& node)
{
  publisher_ = node->create_publisher<sensor_msgs::msg::Image>("/model/depth", 1);
}
}  // namespace mesh_filter
"""
BASE_CPP = "#include <string>\n\nnamespace mesh_filter\n{\n}  // namespace mesh_filter\n"
NODELET = "moveit_ros/perception/mesh_filter/src/depth_self_filter_nodelet.cpp"
SENSOR_MODEL = "moveit_ros/perception/mesh_filter/src/sensor_model.cpp"


def perception(root: Path, *, mesh_filter_cmake: str = MESH_FILTER_CMAKE) -> Path:
    package = root / "moveit_ros/perception"
    write(package, "package.xml", AMENT_PACKAGE.format(name="moveit_ros_perception"))
    write(package, "CMakeLists.txt", PERCEPTION_CMAKE)
    write(package, "ConfigExtras.cmake", CONFIG_EXTRAS)
    write(package, "mesh_filter/CMakeLists.txt", mesh_filter_cmake)
    write(package, "mesh_filter/src/mesh_filter_base.cpp", BASE_CPP)
    write(package, "mesh_filter/src/sensor_model.cpp", SENSOR_MODEL_CPP)
    write(package, "mesh_filter/src/depth_self_filter_nodelet.cpp", NODELET_CPP)
    return package


def found(run_cli: Any, root: Path, *options: str) -> list[tuple[str, int, str]]:
    result = run_cli(["check", "--format", "json", *options, "."], root)
    assert result.exit_code in (0, 1), result.stderr
    return [(f["path"], f["line"], f["code"]) for f in result.findings()]


def test_a_source_no_target_compiles_is_not_reported(run_cli: Any, tmp_path: Path) -> None:
    """Before, the nodelet's two absolute topics were RN202s (moveit2: four)."""
    perception(tmp_path)
    assert found(run_cli, tmp_path) == [(SENSOR_MODEL, 8, "RN202")]


def test_verbose_names_the_files_judged_unbuilt(run_cli: Any, tmp_path: Path) -> None:
    """Also from a stored result, when nothing changed since the run that made it."""
    perception(tmp_path)
    for _ in range(2):
        result = run_cli(["check", "--verbose", "."], tmp_path)
        assert f"{NODELET}: no build file of its package compiles it" in result.stderr
        assert "sensor_model.cpp: no build file" not in result.stderr
    assert "its result reused" in result.stderr


def test_a_per_file_run_judges_by_the_workspace_build(run_cli: Any, tmp_path: Path) -> None:
    """pre-commit names the file; the CMakeLists.txt of its package is in the context."""
    perception(tmp_path)
    (tmp_path / ".git").mkdir()
    result = run_cli(["check", "--format", "json", NODELET], tmp_path)
    assert result.findings() == []
    result = run_cli(["check", "--format", "json", SENSOR_MODEL], tmp_path)
    assert result.codes() == ["RN202"]


@pytest.mark.parametrize(
    "cmake_text",
    [
        # A glob: the file may be any source it finds.
        MESH_FILTER_CMAKE
        + "file(GLOB NODELET_SOURCES src/*_nodelet.cpp)\n"
        + "add_library(moveit_depth_self_filter SHARED ${NODELET_SOURCES})\n",
        # A variable this file never sets (the parent directory's).
        MESH_FILTER_CMAKE + "add_library(moveit_depth_self_filter SHARED ${NODELET_SOURCES})\n",
        # A macro of another package, handed the file, or only its name.
        MESH_FILTER_CMAKE
        + "cs_add_library(moveit_depth_self_filter src/depth_self_filter_nodelet.cpp)\n",
        MESH_FILTER_CMAKE + "moveit_add_nodelet(depth_self_filter_nodelet)\n",
        # ament_cmake_auto globs the directory.
        MESH_FILTER_CMAKE
        + "ament_auto_add_library(moveit_depth_self_filter SHARED DIRECTORY src)\n",
        # A function of this file, called: its body runs with the arguments.
        MESH_FILTER_CMAKE
        + "function(add_nodelet name)\n"
        + "  add_library(${name} SHARED src/${name}.cpp)\n"
        + "endfunction()\n"
        + "add_nodelet(depth_self_filter_nodelet)\n",
        # A generator expression may name anything.
        MESH_FILTER_CMAKE
        + "target_sources(moveit_mesh_filter PRIVATE\n"
        + "  $<$<BOOL:${WITH_ROS1}>:src/depth_self_filter_nodelet.cpp>)\n",
        # A .cmake file of the package the run does not hold.
        MESH_FILTER_CMAKE + "include(${CMAKE_CURRENT_SOURCE_DIR}/cmake/nodelets.cmake)\n",
        # A file that does not lex to its end.
        MESH_FILTER_CMAKE + 'add_library(moveit_depth_self_filter SHARED "src/\n',
    ],
    ids=[
        "glob",
        "unknown-variable",
        "foreign-macro-path",
        "foreign-macro-stem",
        "ament-auto-directory",
        "function-called",
        "generator-expression",
        "missing-include",
        "broken-file",
    ],
)
def test_a_build_the_linter_cannot_read_whole_keeps_the_findings(
    run_cli: Any, tmp_path: Path, cmake_text: str
) -> None:
    perception(tmp_path, mesh_filter_cmake=cmake_text)
    assert (NODELET, 10, "RN202") in found(run_cli, tmp_path)


def test_a_source_another_source_includes_is_compiled(run_cli: Any, tmp_path: Path) -> None:
    """moveit2's ikfast plugin ``#include``s its solver's .cpp."""
    package = perception(tmp_path)
    write(
        package,
        "mesh_filter/src/mesh_filter_base.cpp",
        '#include "depth_self_filter_nodelet.cpp"\n',
    )
    assert (NODELET, 10, "RN202") in found(run_cli, tmp_path)


def test_a_subdirectory_the_run_does_not_hold_may_compile_it(run_cli: Any, tmp_path: Path) -> None:
    """``add_subdirectory(mesh_filter)``, its CMakeLists.txt excluded from the run."""
    perception(tmp_path)
    write(tmp_path, "roslint-names.toml", 'exclude = ["**/mesh_filter/CMakeLists.txt"]\n')
    assert (NODELET, 10, "RN202") in found(run_cli, tmp_path)


def test_a_package_without_a_cmake_build_keeps_its_findings(run_cli: Any, tmp_path: Path) -> None:
    package = perception(tmp_path)
    (package / "CMakeLists.txt").unlink()
    assert (NODELET, 10, "RN202") in found(run_cli, tmp_path)


def test_the_linter_s_own_findings_stay(run_cli: Any, tmp_path: Path) -> None:
    """A suppression in an unbuilt file that silences nothing is still one to remove."""
    package = perception(tmp_path)
    nodelet = package / "mesh_filter/src/depth_self_filter_nodelet.cpp"
    nodelet.write_text(NODELET_CPP.replace("onInit()", "onInit()  // NOLINT(RN203)"))
    everything = found(run_cli, tmp_path, "--extend-select", "RN002")
    codes = [code for path, _, code in everything if path == NODELET]
    assert codes == ["RN002"]


# moveit_ros/planning/moveit_cpp, reduced: its test's CMake lines are commented out; the
# copy in planning_interface/test is built by ament_add_gtest and keeps its finding.
MOVEIT_CPP_CMAKE = """add_library(moveit_cpp SHARED src/moveit_cpp.cpp src/planning_component.cpp)
target_link_libraries(moveit_cpp moveit_planning_scene_monitor)

# TODO: Port MoveItCpp test if (BUILD_TESTING)
# find_package(rostest REQUIRED)
# add_rostest_gtest(moveit_cpp_test test/moveit_cpp_test.test
# test/moveit_cpp_test.cpp) target_link_libraries(moveit_cpp_test moveit_cpp
# ${catkin_LIBRARIES}) endif()
"""
PLANNING_CMAKE = """cmake_minimum_required(VERSION 3.22)
project(moveit_ros_planning LANGUAGES CXX)
find_package(ament_cmake REQUIRED)
add_subdirectory(moveit_cpp)
ament_package()
"""
PLANNING_INTERFACE_CMAKE = """cmake_minimum_required(VERSION 3.22)
project(moveit_ros_planning_interface LANGUAGES CXX)
find_package(ament_cmake REQUIRED)
if(BUILD_TESTING)
  find_package(ament_cmake_gtest REQUIRED)
  ament_add_gtest_executable(moveit_cpp_test test/moveit_cpp_test.cpp)
  target_link_libraries(moveit_cpp_test moveit_cpp)
endif()
ament_package()
"""
MOVEIT_CPP_TEST = """#include <gtest/gtest.h>
#include <rclcpp/rclcpp.hpp>

class MoveItCppTest : public ::testing::Test
{
public:
  void SetUp() override
  {
    node_ = rclcpp::Node::make_shared("/moveit_cpp_test");
  }

protected:
  rclcpp::Node::SharedPtr node_;
};
"""


def test_a_test_whose_build_is_commented_out_is_not_reported(run_cli: Any, tmp_path: Path) -> None:
    """Before, both copies were RN101 (a node name holding '/')."""
    planning = tmp_path / "moveit_ros/planning"
    write(planning, "package.xml", AMENT_PACKAGE.format(name="moveit_ros_planning"))
    write(planning, "CMakeLists.txt", PLANNING_CMAKE)
    write(planning, "moveit_cpp/CMakeLists.txt", MOVEIT_CPP_CMAKE)
    write(planning, "moveit_cpp/src/moveit_cpp.cpp", BASE_CPP)
    write(planning, "moveit_cpp/test/moveit_cpp_test.cpp", MOVEIT_CPP_TEST)
    interface = tmp_path / "moveit_ros/planning_interface"
    write(interface, "package.xml", AMENT_PACKAGE.format(name="moveit_ros_planning_interface"))
    write(interface, "CMakeLists.txt", PLANNING_INTERFACE_CMAKE)
    write(interface, "test/moveit_cpp_test.cpp", MOVEIT_CPP_TEST)
    assert found(run_cli, tmp_path) == [
        ("moveit_ros/planning_interface/test/moveit_cpp_test.cpp", 9, "RN101")
    ]


# moveit2's moveit_ros/planning_interface, reduced: the root CMakeLists.txt adds its
# library directories and leaves ``add_subdirectory(test)`` commented out, so CMake never
# reads test/CMakeLists.txt, and its ament_add_gtest builds nothing.
INTERFACE_ROOT_CMAKE = """cmake_minimum_required(VERSION 3.22)
project(moveit_ros_planning_interface LANGUAGES CXX)
find_package(moveit_common REQUIRED)
moveit_package()
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)

include_directories(${THIS_PACKAGE_INCLUDE_DIRS})

add_subdirectory(move_group_interface)
# add_subdirectory(test)

if(BUILD_TESTING)
  find_package(ament_cmake_gtest REQUIRED)
endif()

ament_package()
"""
MOVE_GROUP_INTERFACE_CMAKE = """add_library(moveit_move_group_interface SHARED
            src/move_group_interface.cpp)
target_link_libraries(moveit_move_group_interface rclcpp::rclcpp)
"""
INTERFACE_TEST_CMAKE = """if(BUILD_TESTING)
  find_package(moveit_resources REQUIRED)
  find_package(ament_cmake_gtest REQUIRED)

  ament_add_gtest(moveit_cpp_test moveit_cpp_test.test moveit_cpp_test.cpp)
  target_link_libraries(moveit_cpp_test moveit_cpp)
endif()
"""
INTERFACE_TEST = "moveit_ros/planning_interface/test/moveit_cpp_test.cpp"


def planning_interface(root: Path, *, root_cmake: str = INTERFACE_ROOT_CMAKE) -> Path:
    package = root / "moveit_ros/planning_interface"
    write(package, "package.xml", AMENT_PACKAGE.format(name="moveit_ros_planning_interface"))
    write(package, "CMakeLists.txt", root_cmake)
    write(package, "move_group_interface/CMakeLists.txt", MOVE_GROUP_INTERFACE_CMAKE)
    write(package, "move_group_interface/src/move_group_interface.cpp", BASE_CPP)
    write(package, "test/CMakeLists.txt", INTERFACE_TEST_CMAKE)
    write(package, "test/moveit_cpp_test.cpp", MOVEIT_CPP_TEST)
    return package


def test_a_cmake_file_whose_add_subdirectory_is_commented_out_builds_nothing(
    run_cli: Any, tmp_path: Path
) -> None:
    """Before, the test was an RN101 (a node name holding '/'): test/CMakeLists.txt, which
    names it, was taken for part of the build, though no file CMake reads adds it."""
    planning_interface(tmp_path)
    assert found(run_cli, tmp_path) == []
    result = run_cli(["check", "--verbose", "."], tmp_path)
    assert f"{INTERFACE_TEST}: no build file of its package compiles it" in result.stderr


@pytest.mark.parametrize(
    "root_cmake",
    [
        INTERFACE_ROOT_CMAKE.replace("# add_subdirectory(test)", "add_subdirectory(test)"),
        INTERFACE_ROOT_CMAKE.replace(
            "# add_subdirectory(test)", "add_subdirectory(${CMAKE_CURRENT_SOURCE_DIR}/test)"
        ),
        # Reached through a directory it adds, and a .cmake file of the package.
        INTERFACE_ROOT_CMAKE.replace("# add_subdirectory(test)", "include(cmake/tests.cmake)"),
        # Unknown: a variable the file never sets, a macro of another package handed the
        # directory, a function of the file whose body adds one, a file that stops lexing.
        INTERFACE_ROOT_CMAKE.replace("# add_subdirectory(test)", "add_subdirectory(${TESTS})"),
        INTERFACE_ROOT_CMAKE.replace("# add_subdirectory(test)", "moveit_add_tests(test)"),
        INTERFACE_ROOT_CMAKE.replace(
            "# add_subdirectory(test)",
            "function(add_tests directory)\n  add_subdirectory(${directory})\nendfunction()",
        ),
        INTERFACE_ROOT_CMAKE.replace("# add_subdirectory(test)", 'add_subdirectory("test\n'),
    ],
    ids=[
        "added",
        "added-by-source-dir",
        "included-module",
        "unknown-variable",
        "foreign-macro",
        "function-body",
        "broken-file",
    ],
)
def test_a_cmake_file_the_build_may_reach_keeps_its_findings(
    run_cli: Any, tmp_path: Path, root_cmake: str
) -> None:
    package = planning_interface(tmp_path, root_cmake=root_cmake)
    if "tests.cmake" in root_cmake:
        write(package, "cmake/tests.cmake", "add_subdirectory(test)\n")
    assert found(run_cli, tmp_path) == [(INTERFACE_TEST, 9, "RN101")]


def test_a_subdirectory_is_reached_through_the_directories_between(
    run_cli: Any, tmp_path: Path
) -> None:
    """move_group_interface/CMakeLists.txt adds its own test directory."""
    package = planning_interface(tmp_path)
    write(
        package,
        "move_group_interface/CMakeLists.txt",
        MOVE_GROUP_INTERFACE_CMAKE + "add_subdirectory(../test ${CMAKE_BINARY_DIR}/tests)\n",
    )
    assert found(run_cli, tmp_path) == [(INTERFACE_TEST, 9, "RN101")]


def compiled(text: str, path: str = "CMakeLists.txt") -> CompiledSources:
    facts = cmake.extract(path, text.encode(), Generation.ROS2, Generation.ROS2)
    assert facts.compiled is not None
    return facts.compiled


def test_what_a_cmake_file_compiles_and_leaves_open() -> None:
    found = compiled(
        """project(demo)
set(SOURCES src/a.cpp ${CMAKE_CURRENT_SOURCE_DIR}/src/b.cpp)
add_library(${PROJECT_NAME} SHARED ${SOURCES})
ament_add_gtest(test_a test/test_a.cpp TIMEOUT 60 WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
add_executable(tool src/tools/${TOOL}.cpp)
nav2_add_gtest(test_b test/test_b.cpp)
install(FILES src/c.cpp DESTINATION share)
add_subdirectory(plugins)
include(GNUInstallDirs)
include(cmake/extras.cmake)
function(never_called name)
  add_executable(${name} ${ARGN})
endfunction()
"""
    )
    assert found.paths == ("src/a.cpp", "src/b.cpp", "test/test_a.cpp")
    assert found.patterns == ("src/tools/*.cpp",)  # never_called's body is no target
    assert found.words == ("test_b", "test/test_b.cpp")
    assert (found.subdirectories, found.includes) == (("plugins",), ("cmake/extras.cmake",))


def test_a_cmake_module_is_read_from_its_includer_s_directory() -> None:
    built = BuiltSources()
    module = FileFacts(
        "pkg/cmake/nodes.cmake",
        Language.CMAKE,
        Generation.ROS2,
        compiled=CompiledSources(paths=("src/a.cpp",), words=("b",)),
    )
    lists = FileFacts(
        "pkg/CMakeLists.txt", Language.CMAKE, Generation.ROS2, compiled=CompiledSources()
    )
    built.add(module, "pkg")
    built.add(lists, "pkg")
    assert built.unbuilt("pkg/src/c.cpp", "pkg")
    assert not built.unbuilt("pkg/src/b.cpp", "pkg")  # a word from the package's directory
    assert not built.unbuilt("pkg/src/c.hpp", "pkg")  # headers are included, never named
    assert not built.unbuilt("other/src/c.cpp", "other")  # no CMake build of its own


# moveit2's ompl_interface, reduced: a roslaunch file left in the ament package, for the
# program the package builds from ROS 2 code that reads parameters.
OMPL_CMAKE = """cmake_minimum_required(VERSION 3.22)
project(moveit_planners_ompl LANGUAGES CXX)
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)
add_executable(moveit_generate_state_database scripts/generate_state_database.cpp)
set_target_properties(moveit_generate_state_database
                      PROPERTIES OUTPUT_NAME "generate_state_database")
install(DIRECTORY launch DESTINATION share/${PROJECT_NAME})
ament_package()
"""
GENERATE_STATE_DATABASE_CPP = """#include <rclcpp/rclcpp.hpp>

int main(int argc, char** argv)
{
  rclcpp::init(argc, argv);
  rclcpp::NodeOptions node_options;
  node_options.automatically_declare_parameters_from_overrides(true);
  auto node = rclcpp::Node::make_shared("generate_state_database", node_options);
  bool use_current_scene;
  node->get_parameter_or("use_current_scene", use_current_scene, false);
  std::string output_folder;
  node->get_parameter_or("output_folder", output_folder,
                         std::string("constraint_approximation_database"));
  std::string planning_group;
  node->get_parameter("planning_group", planning_group);
  rclcpp::shutdown();
  return 0;
}
"""
ROSLAUNCH_FILE = """<launch>
  <arg name="use_current_scene" default="false"/>
  <arg name="planning_group"/>

  <node name="generate_state_database" pkg="moveit_planners_ompl"
        type="generate_state_database" output="screen">
    <param name="use_current_scene" value="$(arg use_current_scene)"/>
    <param name="planning_group" value="$(arg planning_group)"/>
    <remap from="~output_folder" to="move_group/constraint_approximations_path"/>
  </node>
</launch>
"""
ROS2_LAUNCH_FILE = """<launch>
  <node name="generate_state_database" pkg="moveit_planners_ompl" exec="generate_state_database">
    <remap from="~/output_folder" to="move_group/constraint_approximations_path"/>
  </node>
</launch>
"""


def ompl_interface(root: Path) -> Path:
    package = root / "moveit_planners/ompl"
    write(package, "package.xml", AMENT_PACKAGE.format(name="moveit_planners_ompl"))
    write(package, "CMakeLists.txt", OMPL_CMAKE)
    write(package, "scripts/generate_state_database.cpp", GENERATE_STATE_DATABASE_CPP)
    return package


def test_a_roslaunch_file_in_a_ros2_package_starts_no_ros2_node(
    run_cli: Any, tmp_path: Path
) -> None:
    """Before, its remap was an RN404 against the ROS 2 program's parameters: but ros2
    launch stops at ``<node type=>`` (launch_ros reads ``exec``) and no ROS 1 build makes
    the package's programs for roslaunch, so the file starts nothing."""
    package = ompl_interface(tmp_path)
    write(package, "launch/generate_state_database.launch", ROSLAUNCH_FILE)
    assert found(run_cli, tmp_path) == []
    graph = json.loads(run_cli(["graph", "--format", "json", "."], tmp_path).stdout)
    assert graph["nodes"] == []  # before, /generate_state_database, launched from it


def test_the_same_remap_in_ros2_launch_xml_is_reported(run_cli: Any, tmp_path: Path) -> None:
    package = ompl_interface(tmp_path)
    write(package, "launch/generate_state_database.launch.xml", ROS2_LAUNCH_FILE)
    assert found(run_cli, tmp_path) == [
        ("moveit_planners/ompl/launch/generate_state_database.launch.xml", 3, "RN404")
    ]


def test_the_language_server_judges_an_open_file_as_the_cli_does(tmp_path: Path) -> None:
    """An edited buffer of the nodelet has no finding about names; once the build file
    names it, it has (a build file's change is seen on its next check)."""
    from roslint_names.config import load_settings
    from roslint_names.registry import load_registry
    from roslint_names.session import Session

    package = perception(tmp_path)
    registry = load_registry()
    session = Session(tmp_path, load_settings(None, tmp_path, registry), registry, None)
    session.load()
    nodelet = package / "mesh_filter/src/depth_self_filter_nodelet.cpp"
    edited = NODELET_CPP.replace('"/model/depth"', '"/model/depth_image"')
    assert session.check(nodelet, edited) == []
    built = (
        MESH_FILTER_CMAKE + "add_library(depth_filter SHARED src/depth_self_filter_nodelet.cpp)\n"
    )
    session.check(package / "mesh_filter/CMakeLists.txt", built)
    found = session.check(nodelet, edited) or []
    # Both its names are absolute: one decision, the node bound to the root namespace.
    assert [(d.code, d.span.line, [r.span.line for r in d.related]) for d in found] == [
        ("RN202", 10, [11])
    ]


def test_what_a_build_file_leaves_open_is_looked_up_as_it_was_compared() -> None:
    """``_Opening`` answers from sets what comparing each word, pattern, subdirectory and
    include with each source answered (the way every source of a package was judged
    before, ``reference``): the same for every word form, from a package at the run's
    root, below it, and outside the current directory."""
    import itertools
    from fnmatch import fnmatchcase

    from roslint_names.model import CompiledSources
    from roslint_names.workspace import built
    from roslint_names.workspace.index import join

    def names(word: str, path: str) -> bool:
        """A word names a file by its path, a directory above it, its name or its stem."""
        name = posixpath.basename(path)
        return (
            path == word
            or path.startswith(word + "/")
            or posixpath.basename(word) in (name, name.rpartition(".")[0])
        )

    def reference(
        compiled: CompiledSources, base: str, path: str, inside: str, held: set[str]
    ) -> bool:
        for pattern in compiled.patterns:
            if pattern.startswith("*"):
                if fnmatchcase(inside, pattern) or fnmatchcase(path, pattern):
                    return True
            elif fnmatchcase(path, join(base, pattern)):
                return True
        if any(names(join(base, word), path) for word in compiled.words):
            return True
        for directory in compiled.subdirectories:
            below = join(base, directory)
            if join(below, "CMakeLists.txt") not in held and path.startswith(below + "/"):
                return True
        return any(join(base, included) not in held for included in compiled.includes)

    words = [
        "src/talker.cpp",
        "src",
        "talker",
        "talker.cpp",
        "nodes",
        ".",
        "..",
        "../common",
        "src/talk",
        "tal",
        "",
    ]
    for package in ("", "robot", "/tmp/ws/robot"):
        base = package
        held = {join(package, "CMakeLists.txt"), join(package, "nodes/CMakeLists.txt")}
        paths = [
            join(package, relative)
            for relative in (
                "src/talker.cpp",
                "src/talker/main.cpp",
                "nodes/listener.cc",
                "tools/x.cpp",
                "src/.cpp",
                "talker",
                "common/a.cpp",
            )
        ]
        for size in (0, 1, 2):
            for chosen in itertools.combinations(words, size):
                for subdirectories, includes, patterns in (
                    ((), (), ()),
                    (("nodes",), (), ()),
                    (("tools",), (), ()),
                    ((), ("cmake/extra.cmake",), ()),
                    ((), (), ("src/*.cpp",)),
                    ((), (), ("*main.cpp",)),
                ):
                    compiled = CompiledSources(
                        words=chosen,
                        subdirectories=subdirectories,
                        includes=includes,
                        patterns=patterns,
                    )
                    opening = built._Opening.of(compiled, base, held)
                    for path in paths:
                        inside = path[len(package) :].lstrip("/") if package else path
                        expected = reference(compiled, base, path, inside, held)
                        assert opening.may_be(path, inside) == expected, (
                            chosen,
                            subdirectories,
                            includes,
                            patterns,
                            package,
                            path,
                            posixpath.basename(path),
                        )


def test_what_targets_name_is_asked_of_the_build_files_that_may_name_it() -> None:
    """``BuiltSources`` asks whether CMake reads a build file only of those whose targets
    name the source, not of every build file read (a patch asks about one package's
    sources): the same answers as the union of what every read build file's targets name
    (``reference``), for targets that stay below their directory, lead out of it
    (``../common``, an absolute path, ``.``), a package at the run's root, below it,
    inside another, outside the current directory, and a build file of no package."""
    from roslint_names.workspace.index import join, parent

    relatives = ("src/a.cpp", "../common/b.cpp", "sub/../c.cpp", "/opt/d.cpp", ".", "e.cpp")
    for outer in ("", "ws", "/tmp/ws", "../ws"):
        inner = join(outer, "inner")
        files = [  # (package directory, build file, target sources, rostest sources)
            (outer, join(outer, "CMakeLists.txt"), relatives[:3], relatives[5:]),
            (outer, join(outer, "cmake/nodes.cmake"), relatives[3:5], ()),
            (inner, join(inner, "CMakeLists.txt"), ("../src/f.cpp", "g.cpp"), ("src/a.cpp",)),
            (inner, join(inner, "tools/CMakeLists.txt"), ("h.cpp",), ()),  # read by none
            (None, join(outer, "loose/CMakeLists.txt"), ("../inner/g.cpp",), ("x.cpp",)),
        ]
        built = BuiltSources()
        for package, path, paths, rostest in files:
            compiled = CompiledSources(paths=paths, rostest=rostest)
            built.add(FileFacts(path, Language.CMAKE, Generation.ROS2, compiled=compiled), package)
        built._index()  # what ``unbuilt`` does first: the questions below are its parts
        targets: set[str] = set()
        rostest_named: set[str] = set()
        reached = {f.path for package in (outer, inner) for f in built._reached_files(package)}
        for package, path, paths, rostest in files:
            if package is None or path in reached:
                targets.update(join(parent(path), relative) for relative in paths)
                rostest_named.update(join(parent(path), relative) for relative in rostest)
        assert join(inner, "tools/CMakeLists.txt") not in reached
        asked = {*targets, *rostest_named, join(inner, "tools/h.cpp"), join(outer, "zz.cpp")}
        for path in sorted(asked):
            reference = (path in targets, path in rostest_named)
            assert built._named(path) == reference, (outer, path)


def test_parent_is_the_posix_dirname_of_a_display_path() -> None:
    """``index.parent``, asked of every file the graph reads, is ``posixpath.dirname``
    without its type checks: the same answer for relative, absolute, root, trailing and
    doubled separators, and paths above the run's root."""
    from roslint_names.workspace.index import parent

    relative = ("", "a", "a/b", "a/", "a/b/", "a//b", "a///b//c", "./a", "../x/y", "é/ü.cpp")
    absolute = ("/", "//", "///a", "/a", "/a/b", "//a//b//")
    for path in (*relative, *absolute):
        assert parent(path) == posixpath.dirname(path), path


def test_built_sources_index_what_was_added_when_asked() -> None:
    """A run after an edit takes what the last run gathered (``of``) and most often asks
    nothing of it: indexed only when asked, and again for what was added since."""
    package = "turtle"
    lists = FileFacts(
        "turtle/CMakeLists.txt",
        Language.CMAKE,
        Generation.ROS2,
        compiled=CompiledSources(paths=("src/teleop.cpp",)),
    )
    built = BuiltSources()
    built.add(lists, package)
    taken = BuiltSources.of(built.given())
    assert taken._indexed == 0 and taken.given() == built.given()
    for sources in (built, taken):
        assert not sources.unbuilt("turtle/src/teleop.cpp", package)
        assert sources.unbuilt("turtle/src/pose_logger.cpp", package)
    assert taken._indexed == 1
    tools = FileFacts(
        "turtle/tools.cmake",
        Language.CMAKE,
        Generation.ROS2,
        compiled=CompiledSources(paths=("src/pose_logger.cpp",)),
    )
    taken.add(tools, package)  # after a question: taken in at the next one
    assert not taken.unbuilt("turtle/src/pose_logger.cpp", package)
