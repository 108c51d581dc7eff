"""Which sources a CMake file compiles, and what it leaves open (``CompiledSources``).

The engine leaves unreported a C++ source that no build file of its package compiles
(``workspace.built``): a ROS 1 nodelet left in a ported package, a test whose
``ament_add_gtest`` is commented out. That is only safe where the build files tell the
whole story, so everything here errs towards "may be compiled":

* the targets' sources (``add_executable``, ``add_library``, the test executables of
  gtest, gmock and benchmarks, ``target_sources``...), after the target's name and without
  the values of keywords such as ``WORKING_DIRECTORY``, are ``paths`` (``rostest`` for
  the test executables only rostest starts: ``add_rostest_gtest``); a source with a
  part the file does not determine (a variable it never sets, ``file(GLOB)``'s output, a
  generator expression) is a pattern with ``*`` for that part, and ``ament_auto``'s
  ``DIRECTORY src`` the pattern ``src/*``;
* a command the linter does not know (a macro of another package: ``nav2_add_gtest``,
  ``pybind11_add_module``, ``cs_add_executable``) may compile what it is given: each of
  its arguments is a word that may name a file by its path, directory, name or stem, and
  an argument the file does not determine a pattern;
* ``add_custom_command``, ``add_custom_target`` and ``execute_process`` make no target:
  their known arguments are words, the unknown ones programs and generated files;
* commands known to compile nothing (``find_package``, ``install``,
  ``target_link_libraries``, ``ament_package``, message generation, linters...) are
  skipped, whatever their arguments;
* ``add_subdirectory`` and ``include`` of a file of the package name build files that
  must be in the run too, and the only ones of the package CMake reads besides its root
  ``CMakeLists.txt`` (``workspace.built``): they are recorded from the bodies of
  functions and macros too, a parameter there unknown. ``include`` of a module
  (``include(GNUInstallDirs)``) or of a file of another package
  (``include(${moveit_common_DIR}/...)``) defines macros, whose calls are judged as above;
* a body of a function or macro read where it is defined (its parameters unknown) records
  no other command, since each call records its own: a call in this file runs the body
  with its arguments, a call in another file is a command that file does not know. A call
  too deep to follow, a file that stops lexing and a replay cut short leave ``*``: anything.
"""

from __future__ import annotations

import posixpath
import re
from collections.abc import Sequence

from roslint_names.extract.build.cmake_eval import DYNAMIC, SOURCE_DIR, Value
from roslint_names.extract.build.cmake_sources import CODE_SUFFIXES, normalise
from roslint_names.model import CompiledSources

ANYTHING = "*"

# Commands whose first argument names a target and whose other arguments are its sources
# (and keywords).
_TARGETS = frozenset(
    {
        "add_executable",
        "add_library",
        "cuda_add_executable",
        "cuda_add_library",
        "ament_auto_add_executable",
        "ament_auto_add_library",
        "ament_auto_add_gtest",
        "ament_auto_add_gmock",
        "ament_add_gtest",
        "ament_add_gmock",
        "ament_add_gtest_executable",
        "ament_add_gmock_executable",
        "ament_add_ros_isolated_gtest",
        "ament_add_ros_isolated_gmock",
        "ament_add_google_benchmark",
        "ament_add_google_benchmark_executable",
        "catkin_add_gtest",
        "catkin_add_gmock",
        "catkin_add_executable_with_gtest",
        "catkin_add_executable_with_gmock",
        "rosbuild_add_executable",
        "rosbuild_add_library",
        "rosbuild_add_library_module",
        "rosbuild_add_gtest",
        "target_sources",
    }
)
# Test executables only rostest starts, by the name a .test file gives them: rostest's
# ``_add_rostest_google_test`` (ros_comm ``tools/rostest/cmake/rostest-extras.cmake.em``)
# makes them ``add_executable(${target} EXCLUDE_FROM_ALL ${ARGN})`` and hands the .test
# file to ``add_rostest(... DEPENDENCIES ${target})``. Arguments as for ``_TARGETS``; the
# second is the .test file, a path with no source suffix, harmless among the sources.
_ROSTEST_TARGETS = frozenset({"add_rostest_gtest", "add_rostest_gmock"})
# Keywords of those commands whose values are no sources (ament_cmake_gtest's
# ``cmake_parse_arguments``: RUNNER, TIMEOUT, WORKING_DIRECTORY; ENV, APPEND_ENV,
# APPEND_LIBRARY_DIRS; benchmarks' RESULTS_FILE; add_library's ALIAS target).
_VALUE_KEYWORDS = frozenset(
    {
        "RUNNER",
        "TIMEOUT",
        "WORKING_DIRECTORY",
        "ENV",
        "APPEND_ENV",
        "APPEND_LIBRARY_DIRS",
        "RESULTS_FILE",
        "ALIAS",
        "BASE_DIRS",
        "TYPE",
    }
)
_FLAG_KEYWORDS = frozenset(
    {
        "SHARED",
        "STATIC",
        "MODULE",
        "OBJECT",
        "INTERFACE",
        "UNKNOWN",
        "IMPORTED",
        "GLOBAL",
        "EXCLUDE_FROM_ALL",
        "WIN32",
        "MACOSX_BUNDLE",
        "PUBLIC",
        "PRIVATE",
        "FILE_SET",
        "FILES",
        "SKIP_LINKING_MAIN_LIBRARIES",
        "SKIP_TEST",
        "SKIP_RUN_FAIL",
        "NO_TARGET_LINK_LIBRARIES",
    }
)
_DIRECTORY_KEYWORD = "DIRECTORY"  # ament_auto_add_*(... DIRECTORY src): a recursive glob

# Commands that compile nothing and name no file to compile, whatever their arguments:
# CMake's own that set variables, properties, flags, tests and installation; ROS's that
# find, export, generate interfaces, run launch tests or Python tests, and lint.
_COMPILE_NOTHING = frozenset(
    {
        # CMake
        "cmake_minimum_required",
        "cmake_policy",
        "cmake_parse_arguments",
        "cmake_path",
        "project",
        "set",
        "unset",
        "list",
        "string",
        "math",
        "option",
        "message",
        "if",
        "elseif",
        "else",
        "endif",
        "while",
        "endwhile",
        "foreach",
        "endforeach",
        "function",
        "endfunction",
        "macro",
        "endmacro",
        "block",
        "endblock",
        "return",
        "break",
        "continue",
        "file",
        "configure_file",
        "install",
        "export",
        "enable_testing",
        "enable_language",
        "include_directories",
        "link_directories",
        "link_libraries",
        "add_definitions",
        "remove_definitions",
        "add_compile_options",
        "add_compile_definitions",
        "add_link_options",
        "add_dependencies",
        "target_link_libraries",
        "target_include_directories",
        "target_compile_options",
        "target_compile_definitions",
        "target_compile_features",
        "target_link_options",
        "target_link_directories",
        "set_target_properties",
        "set_directory_properties",
        "set_tests_properties",
        "set_source_files_properties",
        "mark_as_advanced",
        "separate_arguments",
        "source_group",
        "pkg_check_modules",
        "pkg_search_module",
        "find_package_handle_standard_args",
        "generate_export_header",
        "add_test",  # runs a command; a program it runs is a target of its own
        # catkin
        "catkin_package",
        "catkin_metapackage",
        "catkin_python_setup",
        "catkin_install_python",
        "catkin_add_nosetests",
        "catkin_download_test_data",
        "catkin_destinations",
        "catkin_package_xml",
        "add_message_files",
        "add_service_files",
        "add_action_files",
        "generate_messages",
        "generate_dynamic_reconfigure_options",
        "add_rostest",
        "roslaunch_add_file_check",
        "roslint_cpp",
        "roslint_python",
        "roslint_add_test",
        "rosbuild_init",
        "rosbuild_gendeps",
        "rosbuild_genmsg",
        "rosbuild_gensrv",
        "rosbuild_find_ros_package",
        # ament
        "ament_package",
        "ament_package_xml",
        "ament_target_dependencies",
        "ament_lint_auto_find_test_dependencies",
        "ament_auto_find_build_dependencies",
        "ament_auto_find_test_dependencies",
        "ament_auto_package",
        "ament_python_install_package",
        "ament_environment_hooks",
        "ament_index_register_resource",
        "ament_add_test_label",
        "ament_find_gtest",
        "ament_find_gmock",
        "ament_add_pytest_test",
        "ament_add_ros_isolated_pytest_test",
        "add_launch_test",
        "add_ros_test",
        "add_ros_isolated_launch_test",
        "rosidl_generate_interfaces",
        "rosidl_get_typesupport_target",
        "rosidl_target_interfaces",
        "pluginlib_export_plugin_description_file",
        "rclcpp_components_register_node",
        "rclcpp_components_register_nodes",
        "generate_parameter_library",
    }
)
# Whole families: finders and getters, CheckXxx modules' compile probes, ament's
# exports and linters (``ament_cpplint(src/a.cpp)`` lints, never builds).
_COMPILE_NOTHING_PREFIXES = (
    "find_",
    "get_",
    "check_",
    "ament_export_",
    "ament_cppcheck",
    "ament_cpplint",
    "ament_clang_",
    "ament_copyright",
    "ament_flake8",
    "ament_lint_cmake",
    "ament_pep257",
    "ament_uncrustify",
    "ament_xmllint",
)
# Commands that run programs, at build or configure time, and make no target: a source
# they compile is named in them (``COMMAND g++ src/a.cpp``); what they leave unknown is a
# program, a directory or a generated file, not a source of the tree.
_RUN_PROGRAMS = frozenset({"add_custom_command", "add_custom_target", "execute_process"})
_MARKER = re.compile(f"[{DYNAMIC}]+")
_GENERATOR_EXPRESSION = "$<"


# What a body read where it is defined still records: the build files it may run.
RUNS_BUILD_FILES = frozenset({"add_subdirectory", "include"})


def compiles_nothing(command: str) -> bool:
    return command in _COMPILE_NOTHING or command.startswith(_COMPILE_NOTHING_PREFIXES)


class Compiled:
    """Collects one file's ``CompiledSources`` as its commands run (``cmake._Build``)."""

    def __init__(self) -> None:
        self._paths: dict[str, None] = {}
        self._patterns: dict[str, None] = {}
        self._words: dict[str, None] = {}
        self._subdirectories: dict[str, None] = {}
        self._includes: dict[str, None] = {}
        self._rostest: dict[str, None] = {}

    def command(self, name: str, values: Sequence[Value]) -> None:
        """What one command run (not a call of a function of this file) compiles."""
        if name in _TARGETS:
            self._target(values[1:], self._paths)
        elif name in _ROSTEST_TARGETS:
            self._target(values[1:], self._rostest)
        elif name == "add_subdirectory":
            self._subdirectory(values[:1])
        elif name == "include":
            self._include(values[:1])
        elif name in _RUN_PROGRAMS:
            for value in values:
                if (path := normalise(value.text)) is not None:
                    self._words[path] = None
        elif not compiles_nothing(name):
            for value in values:
                self._word(value.text)

    def anything(self) -> None:
        """The file may compile any source of its package: it was not read to the end."""
        self._patterns[ANYTHING] = None

    def result(self) -> CompiledSources:
        return CompiledSources(
            tuple(self._paths),
            tuple(self._patterns),
            tuple(self._words),
            tuple(self._subdirectories),
            tuple(self._includes),
            tuple(self._rostest),
        )

    def _target(self, values: Sequence[Value], paths: dict[str, None]) -> None:
        """A target's sources into ``paths``; its unknown ones are patterns."""
        skipping = directory = False
        for value in values:
            text = value.text
            if text in _FLAG_KEYWORDS:
                skipping = False
            elif text in _VALUE_KEYWORDS:
                skipping = True
            elif text == _DIRECTORY_KEYWORD:
                directory, skipping = True, False
            elif directory:
                directory = False
                self._pattern(text.rstrip("/") + "/" + DYNAMIC)
            elif not skipping or posixpath.splitext(text)[1] in CODE_SUFFIXES:
                self._source(text, paths)

    def _source(self, text: str, paths: dict[str, None]) -> None:
        path = normalise(text)
        if path is not None:
            paths[path] = None
        elif DYNAMIC in text or _GENERATOR_EXPRESSION in text:
            self._pattern(text)

    def _word(self, text: str) -> None:
        path = normalise(text)
        if path is not None:
            self._words[path] = None
        elif DYNAMIC in text or _GENERATOR_EXPRESSION in text:
            self._pattern(text)

    def _pattern(self, text: str) -> None:
        """``text`` with each unknown part a ``*``; a generator expression, or an unknown
        directory in the middle, is anything."""
        if _GENERATOR_EXPRESSION in text:
            self._patterns[ANYTHING] = None
            return
        if text.startswith(SOURCE_DIR):
            text = text[len(SOURCE_DIR) :].lstrip("/")
        if SOURCE_DIR in text or text.startswith("/"):
            self._patterns[ANYTHING] = None
            return
        pattern = _MARKER.sub("*", text)
        self._patterns[posixpath.normpath(pattern) if pattern else ANYTHING] = None

    def _subdirectory(self, values: Sequence[Value]) -> None:
        for value in values:
            path = normalise(value.text)
            if path is not None:
                self._subdirectories[path] = None
            else:
                self._pattern(value.text.rstrip("/") + "/" + DYNAMIC)

    def _include(self, values: Sequence[Value]) -> None:
        """A file of the package must be in the run; a module or another package's file
        (a path starting with what the file does not know) only defines macros."""
        for value in values:
            text = value.text
            if text.startswith(DYNAMIC) or ("/" not in text and not text.endswith(".cmake")):
                continue
            path = normalise(text)
            if path is not None:
                self._includes[path] = None
            else:
                self._patterns[ANYTHING] = None
