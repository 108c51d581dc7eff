"""Build files: the programs and component plugins a package builds, and their sources.

Fixtures in ``fixtures/build/`` follow ros2/demos (composition, demo_nodes_cpp,
demo_nodes_py), ros/ros_tutorials (roscpp_tutorials), ros2/geometry2 (examples_tf2_py),
navigation2 (nav2_controller, nav2_simple_commander), autoware (ament_cmake_auto) and
ros2_control (controller_manager's setup.cfg).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from roslint_names.extract.build import cmake, setup_py
from roslint_names.extract.build.cmake_syntax import ArgKind, VarRef, lex
from roslint_names.model import ExecutableKind, FileFacts, Generation, Language, Span

FIXTURES = Path(__file__).parent / "fixtures" / "build"
PROGRAM, PLUGIN = ExecutableKind.PROGRAM, ExecutableKind.PLUGIN
ROS1, ROS2 = Generation.ROS1, Generation.ROS2

Row = tuple[str, str, tuple[str, ...]]


def of_cmake(text: str | bytes, package: Generation | None = None) -> FileFacts:
    data = text.encode() if isinstance(text, str) else text
    return cmake.extract("pkg/CMakeLists.txt", data, package, ROS2)


def of_setup(text: str | bytes, name: str = "setup.py") -> FileFacts:
    data = text.encode() if isinstance(text, str) else text
    return setup_py.extract(f"pkg/{name}", data, None, ROS2)


def fixture(relative: str) -> FileFacts:
    path = FIXTURES / relative
    module = cmake if path.name == "CMakeLists.txt" else setup_py
    return module.extract(f"fixtures/build/{relative}", path.read_bytes(), None, ROS2)


def rows(facts: FileFacts) -> list[Row]:
    return [(item.kind.value, item.name, item.sources) for item in facts.executables]


def names(facts: FileFacts) -> list[str]:
    return [item.name for item in facts.executables]


def sources(facts: FileFacts, name: str, kind: ExecutableKind = PROGRAM) -> tuple[str, ...]:
    (found,) = [item for item in facts.executables if item.name == name and item.kind is kind]
    return found.sources


def span(facts: FileFacts, name: str, kind: ExecutableKind = PROGRAM) -> Span:
    (found,) = [item for item in facts.executables if item.name == name and item.kind is kind]
    return found.span


# ---------------------------------------------------------------------------------------
# Realistic CMake files


def test_composition_components_and_the_programs_linking_them() -> None:
    facts = fixture("composition/CMakeLists.txt")
    assert facts.language is Language.CMAKE
    assert facts.parse_errors == ()
    assert rows(facts) == [
        ("plugin", "composition::Talker", ("src/talker_component.cpp",)),
        ("plugin", "composition::Listener", ("src/listener_component.cpp",)),
        ("plugin", "composition::Server", ("src/server_component.cpp",)),
        ("plugin", "composition::Client", ("src/client_component.cpp",)),
        (
            "program",
            "manual_composition",
            (
                "src/manual_composition.cpp",
                "src/talker_component.cpp",
                "src/listener_component.cpp",
            ),
        ),
        (
            "program",
            "linktime_composition",
            (
                "src/linktime_composition.cpp",
                "src/talker_component.cpp",
                "src/server_component.cpp",
                "src/client_component.cpp",
            ),
        ),
        ("program", "dlopen_composition", ("src/dlopen_composition.cpp",)),
    ]


def test_composition_spans_cover_the_name_as_written() -> None:
    facts = fixture("composition/CMakeLists.txt")
    # rclcpp_components_register_nodes(talker_component "composition::Talker"): quotes too
    assert span(facts, "composition::Talker", PLUGIN) == Span(29, 51, 29, 72)
    # RESOURCE_INDEX and its value are not plugins; the plugins are on their own lines
    assert span(facts, "composition::Server", PLUGIN) == Span(45, 3, 45, 24)
    assert span(facts, "manual_composition") == Span(48, 16, 48, 34)


def test_register_node_makes_a_program_and_a_plugin() -> None:
    facts = fixture("demo_nodes_cpp/CMakeLists.txt")
    library = (
        "src/topics/talker.cpp",
        "src/topics/listener.cpp",
        "src/topics/listener_best_effort.cpp",
        "include/demo_nodes_cpp/visibility_control.h",
    )
    assert rows(facts) == [
        # made by the file's own function: custom_executable(parameters list_parameters_async)
        ("program", "list_parameters_async", ("src/parameters/list_parameters_async.cpp",)),
        # listener.cpp is named after no class the file registers: the library's code
        # beside the class's own, as a helper would be; listener_best_effort.cpp is not
        # the talker's (``plugin_sources``)
        (
            "plugin",
            "demo_nodes_cpp::Talker",
            (
                "src/topics/talker.cpp",
                "src/topics/listener.cpp",
                "include/demo_nodes_cpp/visibility_control.h",
            ),
        ),
        ("program", "talker", library),
        (
            "plugin",
            "demo_nodes_cpp::ListenerBestEffort",
            (
                "src/topics/listener.cpp",
                "src/topics/listener_best_effort.cpp",
                "include/demo_nodes_cpp/visibility_control.h",
            ),
        ),
        ("program", "listener_best_effort", library),
        # no file is named after the class: every source of the library
        ("plugin", "demo_nodes_cpp::ContentFilteringPublisher", library),
        ("program", "content_filtering_publisher", library),
        # OneOffTimerNode -> one_off_timer_node, also one_off_timer: one_off_timer.cpp
        ("plugin", "demo_nodes_cpp::OneOffTimerNode", ("src/timers/one_off_timer.cpp",)),
        ("program", "one_off_timer", ("src/timers/one_off_timer.cpp",)),
    ]
    assert span(facts, "demo_nodes_cpp::Talker", PLUGIN) == Span(33, 10, 33, 34)
    assert span(facts, "talker") == Span(34, 14, 34, 20)


def test_catkin_package_programs_scripts_and_renames() -> None:
    facts = fixture("roscpp_tutorials/CMakeLists.txt")
    assert rows(facts) == [
        # rostutorial(${dir}) in a foreach: the macro's add_executable(${T} ${T}/${T}.cpp)
        # per item; listener_single_message is commented out. The installed script
        # nodes/listener has the same name.
        ("program", "listener", ("listener/listener.cpp", "nodes/listener")),
        ("program", "talker", ("talker/talker.cpp",)),
        ("program", "time_api_sleep", ("time_api/sleep/sleep.cpp",)),
        # OUTPUT_NAME node: launch files say type="node"; ${GENERATED_SOURCES} is unknown
        (
            "program",
            "node",
            (
                "src/node_main.cpp",
                "src/node_options.cpp",
                "src/tutorial_utils.cpp",
                "include/roscpp_tutorials/tutorial_utils.h",
            ),
        ),
        ("program", "add_two_ints_server", ("add_two_ints_server/add_two_ints_server.cpp",)),
        ("program", "talker.py", ("scripts/talker.py",)),
        ("program", "teleop", ("scripts/teleop_key.py",)),
    ]


def test_catkin_package_spans() -> None:
    facts = fixture("roscpp_tutorials/CMakeLists.txt")
    assert span(facts, "node") == Span(43, 67, 43, 71)  # the OUTPUT_NAME value
    assert span(facts, "add_two_ints_server") == Span(45, 16, 45, 37)  # quotes included
    assert span(facts, "talker.py") == Span(48, 3, 48, 20)
    assert span(facts, "teleop") == Span(54, 10, 54, 16)  # the RENAME value


def test_macro_and_foreach_bodies_give_no_target_with_a_parameter_name() -> None:
    facts = fixture("roscpp_tutorials/CMakeLists.txt")
    assert not {"T", "dir", "listener_single_message"} & set(names(facts))
    assert sources(facts, "talker") == ("talker/talker.cpp",)  # rostutorial(talker)


def test_nav2_executable_gets_its_core_library_sources() -> None:
    facts = fixture("nav2_controller/CMakeLists.txt")
    assert rows(facts) == [
        (
            "program",
            "controller_server",
            ("src/main.cpp", "src/parameter_handler.cpp", "src/controller_server.cpp"),
        ),
        # the parameter handler is the server's: it declares the server's parameters
        (
            "plugin",
            "nav2_controller::ControllerServer",
            ("src/parameter_handler.cpp", "src/controller_server.cpp"),
        ),
    ]
    assert span(facts, "controller_server") == Span(29, 16, 29, 34)  # ${executable_name}
    assert span(facts, "nav2_controller::ControllerServer", PLUGIN) == Span(49, 50, 49, 85)


def test_ament_auto_targets_link_the_auto_libraries_before_them() -> None:
    facts = fixture("autoware_pure_pursuit/CMakeLists.txt")
    core = (
        "src/autoware_pure_pursuit_core/planning_utils.cpp",
        "src/autoware_pure_pursuit_core/interpolate.cpp",
    )
    lateral = "src/autoware_pure_pursuit/autoware_pure_pursuit_lateral_controller.cpp"
    node = "src/autoware_pure_pursuit/autoware_pure_pursuit_node.cpp"
    assert rows(facts) == [
        # the node library links core and lateral: ament_auto_add_library links what came
        # before it; no source is named pure_pursuit[_node], so the plugin gets them all
        ("plugin", "autoware::pure_pursuit::PurePursuitNode", (node, *core, lateral)),
        ("program", "autoware_pure_pursuit_node_exe", (node, *core, lateral)),
        ("program", "pure_pursuit_checker", ("src/checker/main.cpp", *core, lateral, node)),
        ("program", "standalone_tool", ("src/tools/standalone_tool.cpp",)),
    ]
    assert span(facts, "autoware_pure_pursuit_node_exe") == Span(22, 14, 22, 38)


def test_a_file_that_stops_lexing_keeps_what_came_before_and_reports_nothing() -> None:
    facts = fixture("broken_cmake/CMakeLists.txt")
    assert rows(facts) == [("program", "talker", ("src/talker.cpp",))]
    assert facts.parse_errors == ()


# ---------------------------------------------------------------------------------------
# The lexer


def test_lexer_commands_are_case_insensitive_and_arguments_keep_their_form() -> None:
    lexed = lex('ADD_Executable(talker "src/a b.cpp" [[raw ${x}]] ${y}_z)\n')
    (command,) = lexed.commands
    assert (command.name, command.start, lexed.error) == ("add_executable", 0, None)
    kinds = [argument.kind for argument in command.arguments]
    assert kinds == [ArgKind.UNQUOTED, ArgKind.QUOTED, ArgKind.BRACKET, ArgKind.UNQUOTED]
    assert command.arguments[1].pieces == ("src/a b.cpp",)
    assert command.arguments[2].pieces == ("raw ${x}",)
    assert command.arguments[3].pieces == (VarRef("", ("y",)), "_z")
    assert (command.arguments[1].start, command.arguments[1].end) == (22, 35)


def test_lexer_nested_parentheses_are_arguments() -> None:
    (command,) = lex("if((A OR B) AND C)").commands
    texts = [argument.pieces for argument in command.arguments]
    assert texts == [("(",), ("A",), ("OR",), ("B",), (")",), ("AND",), ("C",)]


def test_lexer_comments_and_brackets() -> None:
    text = (
        "# add_executable(hidden a.cpp)\n"
        "#[[ add_executable(hidden2 b.cpp)\n ) ( ]]\n"
        "#[==[ ]] still a comment ]==]\n"
        "set(x [=[first ]] still\n]=] y) # trailing (comment\n"
    )
    (command,) = lex(text).commands
    assert command.name == "set"
    assert [argument.pieces for argument in command.arguments] == [
        ("x",),
        ("first ]] still\n",),
        ("y",),
    ]


def test_lexer_bracket_drops_the_newline_after_its_opening() -> None:
    (command,) = lex("set(x [[\nline]] [=[\r\ncrlf\n]=] [[ \nkept]])").commands
    assert [argument.pieces for argument in command.arguments[1:]] == [
        ("line",),
        ("crlf\n",),
        (" \nkept",),
    ]


def test_lexer_escapes_continuations_and_nested_references() -> None:
    (command,) = lex(
        'set(x "a\\tb\\"c\\\nd\\;e" f\\ g ${${PROJECT_NAME}_SRCS} $ENV{HOME})'
    ).commands
    arguments = command.arguments
    assert arguments[1].pieces == ('a\tb"cd\\;e',)
    assert arguments[2].pieces == ("f g",)
    assert arguments[3].pieces == (VarRef("", (VarRef("", ("PROJECT_NAME",)), "_SRCS")),)
    assert arguments[4].pieces == (VarRef("ENV", ("HOME",)),)


@pytest.mark.parametrize(
    ("text", "error"),
    [
        ("project(p)\nadd_executable(talker src/talker.cpp\n", 11),  # unbalanced
        ('project(p)\nset(x "open)\n', 11),  # unterminated quote
        ("project(p)\nset(x [[open)\n", 11),  # unterminated bracket
        ("project(p)\nadd_executable talker\n", 11),  # no parenthesis
        ("project(p)\n+\n", 11),  # not a command
        ("project(p)\nset(x ${a b})\n", 11),  # CMake rejects a space in a name
    ],
)
def test_lexer_stops_at_the_first_error(text: str, error: int) -> None:
    lexed = lex(text)
    assert [command.name for command in lexed.commands] == ["project"]
    assert lexed.error == error


def test_lexer_deeply_nested_references_are_an_error_not_a_crash() -> None:
    lexed = lex("set(x " + "${" * 5000 + "a" + "}" * 5000 + ")")
    assert lexed.commands == ()
    assert lexed.error is not None


# ---------------------------------------------------------------------------------------
# Variables


def test_variables_expand_in_names_and_sources() -> None:
    facts = of_cmake(
        "project(demo)\n"
        "set(demo_SOURCES src/talker.cpp src/util.cpp)\n"
        "add_executable(${PROJECT_NAME}_talker ${${PROJECT_NAME}_SOURCES})\n"
    )
    assert rows(facts) == [("program", "demo_talker", ("src/talker.cpp", "src/util.cpp"))]
    assert span(facts, "demo_talker") == Span(3, 16, 3, 38)


def test_unknown_variables_drop_sources_and_skip_names() -> None:
    facts = of_cmake(
        "add_executable(talker src/talker.cpp ${EXTRA_SOURCES} ${DIR}/a.cpp)\n"
        "add_executable(${NODE_NAME} src/node.cpp)\n"
        "add_executable(${NODE_NAME}_node src/node.cpp)\n"
    )
    assert rows(facts) == [("program", "talker", ("src/talker.cpp",))]


def test_a_list_keeps_its_known_elements() -> None:
    facts = of_cmake(
        "set(SRCS src/a.cpp)\n"
        "list(APPEND SRCS ${GENERATED} src/b.cpp)\n"
        "list(PREPEND SRCS src/main.cpp)\n"
        "list(APPEND NEW src/c.cpp)\n"
        "add_executable(a ${SRCS} ${NEW})\n"
    )
    assert sources(facts, "a") == ("src/main.cpp", "src/a.cpp", "src/b.cpp", "src/c.cpp")


def test_list_remove_item_and_computed_lists() -> None:
    facts = of_cmake(
        "set(SRCS src/a.cpp src/b.cpp)\n"
        "list(REMOVE_ITEM SRCS src/b.cpp)\n"
        "add_executable(a ${SRCS})\n"
        "set(GLOBBED src/old.cpp)\n"
        "file(GLOB GLOBBED src/*.cpp)\n"
        "list(APPEND GLOBBED src/extra.cpp)\n"
        "add_executable(b ${GLOBBED})\n"
        "set(FILTERED src/f.cpp)\n"
        "list(FILTER FILTERED EXCLUDE REGEX f)\n"
        "add_executable(c src/c.cpp ${FILTERED})\n"
    )
    assert rows(facts) == [
        ("program", "a", ("src/a.cpp",)),
        ("program", "b", ("src/extra.cpp",)),
        ("program", "c", ("src/c.cpp",)),
    ]


def test_string_commands_make_the_variables_they_write_unknown() -> None:
    facts = of_cmake(
        "set(NAME talker)\n"
        'string(REPLACE "t" "w" NAME "${NAME}")\n'
        "add_executable(${NAME} src/talker.cpp)\n"
    )
    assert rows(facts) == []


def test_cache_and_parent_scope() -> None:
    facts = of_cmake(
        "set(A normal)\n"
        'set(A cached CACHE STRING "doc")\n'
        'set(B cached CACHE STRING "doc" FORCE)\n'
        "set(C parent PARENT_SCOPE)\n"
        "add_executable(${A} a.cpp)\n"
        "add_executable(${B} b.cpp)\n"
        "add_executable(${C} c.cpp)\n"
    )
    assert names(facts) == ["normal", "cached"]


def test_set_without_value_and_unset_make_a_variable_empty() -> None:
    facts = of_cmake(
        "set(EXTRA)\nset(MORE src/more.cpp)\nunset(MORE)\n"
        "add_executable(talker src/talker.cpp ${EXTRA} ${MORE})\n"
    )
    assert sources(facts, "talker") == ("src/talker.cpp",)


def test_both_branches_of_an_if_are_read_and_the_last_set_wins() -> None:
    facts = of_cmake(
        "if(WIN32)\n"
        "  add_executable(talker src/talker_win.cpp)\n"
        "  set(impl src/impl_win.cpp)\n"
        "else()\n"
        "  add_executable(talker src/talker_posix.cpp)\n"
        "  set(impl src/impl_posix.cpp)\n"
        "endif()\n"
        "add_executable(listener ${impl})\n"
    )
    assert rows(facts) == [
        ("program", "talker", ("src/talker_win.cpp", "src/talker_posix.cpp")),
        ("program", "listener", ("src/impl_posix.cpp",)),
    ]
    assert span(facts, "talker") == Span(2, 18, 2, 24)  # where it is first named


def test_a_script_installed_in_both_branches_has_both_sources() -> None:
    facts = of_cmake(
        "if(PYTHON3)\n"
        "  catkin_install_python(PROGRAMS nodes3/talker DESTINATION bin)\n"
        "else()\n"
        "  install(PROGRAMS nodes2/talker DESTINATION bin)\n"
        "endif()\n"
    )
    assert rows(facts) == [("program", "talker", ("nodes3/talker", "nodes2/talker"))]
    assert span(facts, "talker") == Span(2, 34, 2, 47)


def test_function_parameters_hide_globals_and_its_variables_stay_inside() -> None:
    facts = of_cmake(
        "set(target global_target)\n"
        "function(add_node target)\n"
        "  set(helper ${target}_helper)\n"
        "  set(fixed src/fixed.cpp)\n"
        "  add_executable(${target} src/${target}.cpp)\n"
        "  add_executable(fixed_in_function ${fixed})\n"
        "endfunction()\n"
        "add_executable(${target} src/main.cpp ${fixed})\n"
    )
    assert rows(facts) == [
        ("program", "fixed_in_function", ("src/fixed.cpp",)),
        ("program", "global_target", ("src/main.cpp",)),
    ]


def test_foreach_runs_per_item_and_its_variable_is_restored_after() -> None:
    facts = of_cmake(
        "set(name before)\n"
        "foreach(name talker listener)\n"
        "  add_executable(${name} src/${name}.cpp)\n"
        "  set(seen src/seen.cpp)\n"
        "endforeach()\n"
        "add_executable(${name} ${seen})\n"
    )
    # Both come from one place in the file: in name order there.
    assert rows(facts) == [
        ("program", "listener", ("src/listener.cpp",)),
        ("program", "talker", ("src/talker.cpp",)),
        ("program", "before", ("src/seen.cpp",)),
    ]


def test_foreach_over_what_the_file_does_not_tell_runs_once_unknown() -> None:
    facts = of_cmake(
        "file(GLOB demos src/*.cpp)\n"
        "foreach(demo ${demos})\n"
        "  add_executable(${demo} ${demo})\n"
        "endforeach()\n"
        "foreach(i RANGE 3)\n"
        "  add_executable(node_${i} src/node.cpp)\n"
        "endforeach()\n"
        "set(NODES a b)\n"
        "foreach(node IN LISTS NODES ITEMS c)\n"
        "  add_executable(${node}_node src/${node}.cpp)\n"
        "endforeach()\n"
    )
    assert rows(facts) == [
        ("program", "a_node", ("src/a.cpp",)),
        ("program", "b_node", ("src/b.cpp",)),
        ("program", "c_node", ("src/c.cpp",)),
    ]


def test_functions_and_macros_run_at_each_call_with_their_arguments() -> None:
    facts = of_cmake(
        "project(demo_nodes)\n"
        "macro(demo_program name)\n"
        "  set(last ${name})\n"  # a macro's variables are its caller's
        "  add_executable(${name} src/${name}.cpp ${ARGN})\n"
        "endmacro()\n"
        "function(demo_pair first second)\n"
        "  demo_program(${first})\n"  # a helper calling a helper
        "  demo_program(${second} src/common.cpp)\n"
        "endfunction()\n"
        "function(recurse)\n"
        "  recurse()\n"
        "endfunction()\n"
        "DEMO_PAIR(talker listener)\n"  # command names ignore case
        "recurse()\n"
        "add_executable(${PROJECT_NAME}_last src/${last}.cpp)\n"
    )
    assert rows(facts) == [
        ("program", "listener", ("src/listener.cpp", "src/common.cpp")),
        ("program", "talker", ("src/talker.cpp",)),
        # set in the macro, inside a function: the function's, not the file's
        ("program", "demo_nodes_last", ()),
    ]


# ---------------------------------------------------------------------------------------
# Targets and sources


def test_sources_are_normalised_and_only_code_is_kept() -> None:
    facts = of_cmake(
        "project(p)\n"
        "add_executable(a WIN32 MACOSX_BUNDLE EXCLUDE_FROM_ALL\n"
        "  ./src/a.cpp\n"
        "  ${CMAKE_CURRENT_SOURCE_DIR}/src/b.cc\n"
        "  ${PROJECT_SOURCE_DIR}/src/../src/c.cxx\n"
        "  ${p_SOURCE_DIR}//include/p/d.hpp\n"
        "  ${CMAKE_CURRENT_LIST_DIR}/src/e.c\n"
        "  src/kernel.cu\n"
        "  scripts/helper.py\n"
        "  $<TARGET_OBJECTS:objects>\n"
        "  $<$<PLATFORM_ID:Linux>:src/linux.cpp>\n"
        "  /usr/src/outside.cpp\n"
        "  config/params.yaml\n"
        "  src/node.cpp.in\n"
        "  src/a.cpp)\n"
    )
    assert sources(facts, "a") == (
        "src/a.cpp",
        "src/b.cc",
        "src/c.cxx",
        "include/p/d.hpp",
        "src/e.c",
        "src/kernel.cu",
        "scripts/helper.py",
    )


def test_target_sources_adds_to_a_target_even_before_it_is_linked() -> None:
    facts = of_cmake(
        "add_library(core STATIC)\n"
        "add_executable(talker)\n"
        "target_link_libraries(talker PRIVATE core)\n"
        "target_sources(talker PRIVATE src/main.cpp PUBLIC\n"
        "  FILE_SET HEADERS BASE_DIRS include FILES include/talker.hpp)\n"
        "target_sources(core PRIVATE src/core.cpp)\n"
        "target_sources(unknown_target PRIVATE src/lost.cpp)\n"
    )
    assert rows(facts) == [
        ("program", "talker", ("src/main.cpp", "include/talker.hpp", "src/core.cpp"))
    ]


def test_links_are_transitive_through_libraries_only() -> None:
    facts = of_cmake(
        "add_library(base src/base.cpp)\n"
        "add_library(mid src/mid.cpp)\n"
        "target_link_libraries(mid PUBLIC base)\n"
        "target_link_libraries(base PUBLIC mid)\n"  # a cycle must not loop
        "add_executable(tool src/tool.cpp)\n"
        "add_executable(talker src/talker.cpp)\n"
        "target_link_libraries(talker mid tool ${UNKNOWN} rclcpp::rclcpp)\n"
    )
    assert sources(facts, "talker") == ("src/talker.cpp", "src/mid.cpp", "src/base.cpp")


def test_a_library_defined_after_the_link_still_counts() -> None:
    facts = of_cmake(
        "add_executable(talker src/main.cpp)\n"
        "target_link_libraries(talker talker_lib)\n"
        "add_library(talker_lib src/talker.cpp)\n"
    )
    assert sources(facts, "talker") == ("src/main.cpp", "src/talker.cpp")


def test_imported_and_alias_targets() -> None:
    facts = of_cmake(
        "add_executable(protoc IMPORTED)\n"
        "add_executable(tool ALIAS protoc)\n"
        "add_library(ext SHARED IMPORTED GLOBAL)\n"
        "add_library(core src/core.cpp)\n"
        "add_library(demo::core ALIAS core)\n"
        "add_executable(talker src/talker.cpp)\n"
        "target_link_libraries(talker demo::core ext)\n"
    )
    assert rows(facts) == [("program", "talker", ("src/talker.cpp", "src/core.cpp"))]


def test_other_program_commands() -> None:
    facts = of_cmake(
        "cuda_add_executable(gpu_node src/gpu_node.cu src/kernels.cuh OPTIONS -arch=sm_60)\n"
        "rosbuild_add_executable(legacy_node src/legacy.cpp)\n"
        "add_rostest_gtest(test_talker test/talker.test test/test_talker.cpp)\n"
        "catkin_add_executable_with_gtest(test_listener test/test_listener.cpp)\n"
        "ament_add_gtest(test_unit test/test_unit.cpp)\n"
    )
    assert rows(facts) == [
        ("program", "gpu_node", ("src/gpu_node.cu", "src/kernels.cuh")),
        ("program", "legacy_node", ("src/legacy.cpp",)),
        ("program", "test_talker", ("test/test_talker.cpp",)),
        ("program", "test_listener", ("test/test_listener.cpp",)),
    ]


def test_output_name_renames_programs_not_libraries() -> None:
    facts = of_cmake(
        "add_library(lib src/lib.cpp)\n"
        "add_executable(pkg_node src/node.cpp)\n"
        "add_executable(pkg_tool src/tool.cpp)\n"
        'set_target_properties(lib pkg_node PROPERTIES PREFIX "" OUTPUT_NAME node)\n'
        "set_target_properties(pkg_tool PROPERTIES OUTPUT_NAME ${TOOL_NAME})\n"
    )
    assert rows(facts) == [("program", "node", ("src/node.cpp",))]


def test_register_node_with_unknown_parts() -> None:
    facts = of_cmake(
        "add_library(lib SHARED src/talker.cpp)\n"
        "rclcpp_components_register_node(lib PLUGIN ${PLUGIN} EXECUTABLE talker)\n"
        'rclcpp_components_register_node(lib PLUGIN "p::Talker" EXECUTABLE ${EXE})\n'
        'rclcpp_components_register_node(${LIB} PLUGIN "p::Listener" EXECUTABLE listener)\n'
        'rclcpp_components_register_nodes(elsewhere "p::Relay")\n'
    )
    assert rows(facts) == [
        ("program", "talker", ("src/talker.cpp",)),
        ("plugin", "p::Talker", ("src/talker.cpp",)),
        # the library is not known here: the names are, the sources are not
        ("plugin", "p::Listener", ()),
        ("program", "listener", ()),
        ("plugin", "p::Relay", ()),
    ]


@pytest.mark.parametrize(
    ("plugin", "expected"),
    [
        ("pkg::Talker", ("src/talker.cpp", "include/pkg/talker.hpp")),
        ("pkg::TalkerComponent", ("src/talker.cpp", "include/pkg/talker.hpp")),
        ("pkg::ImageViewNode", ("src/image_view_component.cpp",)),
        ("pkg::AMCLNode", ("src/amcl_node.cpp",)),
        ("pkg::sub::Listener", ("src/Listener.cpp",)),
        # underscores aside: PointCloudMapLoaderNode is point_cloud_map_loader_node
        ("pkg::PointCloudMapLoaderNode", ("src/pointcloud_map_loader_node.cpp",)),
        ("pkg::Relay", None),  # nothing named after it: the whole library
    ],
)
def test_plugin_sources_are_the_files_named_after_the_class_and_the_helpers(
    plugin: str, expected: tuple[str, ...] | None
) -> None:
    library = (
        "src/talker.cpp",
        "include/pkg/talker.hpp",
        "src/image_view_component.cpp",
        "src/amcl_node.cpp",
        "src/Listener.cpp",
        "src/pointcloud_map_loader_node.cpp",
        "src/utils.cpp",
        "src/parameter_handler.cpp",
    )
    others = [other for other in ("pkg::Talker", "pkg::sub::Listener") if other != plugin]
    facts = of_cmake(
        f"add_library(lib SHARED {' '.join(library)})\n"
        f'rclcpp_components_register_nodes(lib "{plugin}")\n'
        f"add_library(other SHARED src/other.cpp)\n"
        f"rclcpp_components_register_nodes(other {' '.join(others)})\n"
    )
    # The helpers run in whichever component calls them; the files named after another
    # class registered in the file, or as another node (``*_node``, ``*_component``),
    # hold that one.
    helpers = ("src/utils.cpp", "src/parameter_handler.cpp")
    found = sources(facts, plugin, PLUGIN)
    if expected is None:
        assert found == library
    else:
        assert found == tuple(path for path in library if path in (*expected, *helpers))


def test_a_library_of_one_component_runs_its_helpers_in_it() -> None:
    """autoware.universe's reaction_analyzer: the node reads its parameters and publishes
    through ``TopicPublisher`` and ``SubscriberBase``, files of its library that name no
    class; they are the node's code, not a program of their own."""
    facts = of_cmake(
        "ament_auto_add_library(reaction_analyzer SHARED\n"
        "  include/reaction_analyzer_node.hpp src/reaction_analyzer_node.cpp\n"
        "  include/subscriber.hpp src/subscriber.cpp\n"
        "  include/topic_publisher.hpp src/topic_publisher.cpp)\n"
        "rclcpp_components_register_node(reaction_analyzer\n"
        '  PLUGIN "reaction_analyzer::ReactionAnalyzerNode"\n'
        "  EXECUTABLE reaction_analyzer_exe)\n"
    )
    assert sources(facts, "reaction_analyzer::ReactionAnalyzerNode", PLUGIN) == sources(
        facts, "reaction_analyzer_exe"
    )


def test_installed_scripts() -> None:
    facts = of_cmake(
        "project(p)\n"
        "catkin_install_python(PROGRAMS\n"
        "  scripts/talker.py\n"
        "  ${CMAKE_CURRENT_SOURCE_DIR}/nodes/listener\n"
        "  ${SCRIPTS_DIR}/relay.py\n"
        "  ${UNKNOWN_SCRIPT}\n"
        "  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})\n"
        "install(PROGRAMS scripts/a.sh scripts/b.sh DESTINATION lib/${PROJECT_NAME} RENAME c)\n"
        "install(PROGRAMS $<TARGET_FILE:talker> DESTINATION bin)\n"
        "install(FILES scripts/data.py DESTINATION share/${PROJECT_NAME})\n"
        "install(TARGETS talker DESTINATION lib/${PROJECT_NAME})\n"
    )
    assert rows(facts) == [
        ("program", "talker.py", ("scripts/talker.py",)),
        ("program", "listener", ("nodes/listener",)),
        ("program", "relay.py", ()),  # its name is known, where it lives is not
        ("program", "a.sh", ("scripts/a.sh",)),  # RENAME needs a single file
        ("program", "b.sh", ("scripts/b.sh",)),
    ]
    assert span(facts, "listener") == Span(4, 3, 4, 45)


# ---------------------------------------------------------------------------------------
# Text, positions, generations


def test_columns_count_code_points_and_a_bom_is_not_a_column() -> None:
    text = (
        "\ufeffadd_library(lib SHARED src/talker.cpp)\n"
        'rclcpp_components_register_node(lib PLUGIN "ñandú::Talker" EXECUTABLE talker)\n'
    )
    facts = of_cmake(text.encode("utf-8"))
    assert span(facts, "ñandú::Talker", PLUGIN) == Span(2, 44, 2, 59)
    assert span(facts, "talker") == Span(2, 71, 2, 77)
    assert of_cmake("\ufeffadd_executable(a a.cpp)".encode()).executables[0].span == Span(
        1, 16, 1, 17
    )


def test_crlf_lines_and_invalid_utf8() -> None:
    facts = of_cmake(
        b"project(p)\r\n# caf\xe9\r\nadd_executable(talker src/t\xe9.cpp src/a.cpp)\r\n"
    )
    assert rows(facts) == [("program", "talker", ("src/t\ufffd.cpp", "src/a.cpp"))]
    assert span(facts, "talker") == Span(3, 16, 3, 22)


def test_marker_characters_in_the_file_mean_nothing() -> None:
    facts = of_cmake("add_executable(a\x00b src/\x01a.cpp src/b.cpp)\n")
    assert rows(facts) == [("program", "a\ufffdb", ("src/\ufffda.cpp", "src/b.cpp"))]


def test_generation_is_the_packages_else_the_fallback() -> None:
    assert of_cmake("project(p)", ROS1).generation is ROS1
    assert of_cmake("project(p)").generation is ROS2
    assert setup_py.extract("setup.py", b"", ROS1, ROS2).generation is ROS1
    assert setup_py.extract("setup.cfg", b"", None, ROS1).generation is ROS1


# ---------------------------------------------------------------------------------------
# setup.py


def test_setup_py_console_scripts() -> None:
    facts = fixture("demo_nodes_py/setup.py")
    assert facts.language is Language.SETUP_PY
    assert rows(facts) == [
        ("program", "listener", ("demo_nodes_py/topics/listener.py",)),
        ("program", "talker", ("demo_nodes_py/topics/talker.py",)),
        ("program", "add_two_ints_server", ("demo_nodes_py/services/add_two_ints_server.py",)),
    ]  # "not an entry" and gui_scripts are not console scripts
    assert span(facts, "listener") == Span(27, 13, 27, 60)  # the literal, quotes included


def test_setup_py_f_strings_and_concatenation_over_module_strings() -> None:
    facts = fixture("examples_tf2_py/setup.py")
    assert rows(facts) == [
        ("program", "static_broadcaster", ("examples_tf2_py/static_broadcaster.py",)),
        ("program", "dynamic_broadcaster", ("examples_tf2_py/dynamic_broadcaster.py",)),
        ("program", "frame_dumper", ("examples_tf2_py/nodes/frame_dumper.py",)),
        # {package_name!r} adds quotes and str() is a call: neither is followed
        ("program", "examples_tf2_py_listener", ("examples_tf2_py/listener.py",)),
    ]
    assert span(facts, "dynamic_broadcaster") == Span(26, 13, 26, 82)


def test_setup_py_entry_points_through_variables_and_dict() -> None:
    facts = fixture("nav2_simple_commander/setup.py")
    assert rows(facts) == [
        ("program", "demo_picking", ("nav2_simple_commander/demo_picking.py",)),
        ("program", "demo_inspection", ("nav2_simple_commander/demo_inspection.py",)),
        ("program", "example_nav_to_pose", ("nav2_simple_commander/example_nav_to_pose.py",)),
    ]
    assert span(facts, "demo_picking") == Span(9, 5, 9, 61)  # where the entry is written


def test_setup_py_keyword_mapping_and_attribute_call() -> None:
    facts = of_setup(
        "import setuptools\n"
        "package = 'pkg'\n"
        "kwargs = {'name': package, 'entry_points': {'console_scripts': (\n"
        "    'talker = %s.talker:main' % package,\n"
        "    f'listener = {package}.listener',\n"
        "    *['relay=pkg.relay:main [extra]'],\n"
        ")}}\n"
        "setuptools.setup(**kwargs)\n"
    )
    assert rows(facts) == [
        ("program", "listener", ("pkg/listener.py",)),
        ("program", "relay", ("pkg/relay.py",)),
    ]


def test_setup_py_strings_are_taken_when_assigned() -> None:
    facts = of_setup(
        "from setuptools import setup\n"
        "package_name = 'old'\n"
        "talker = package_name + '.talker:main'\n"
        "package_name = 'new'\n"
        "package_name += '_pkg'\n"
        "setup(entry_points={'console_scripts': [\n"
        "    'talker = ' + talker,\n"
        "    f'listener = {package_name}.listener:main',\n"
        "]})\n"
    )
    assert rows(facts) == [
        ("program", "talker", ("old/talker.py",)),
        ("program", "listener", ("new_pkg/listener.py",)),
    ]


def test_setup_py_ini_string_and_single_string_entry_points() -> None:
    facts = of_setup(
        "from setuptools import setup\n"
        "setup(entry_points='''\n"
        "[console_scripts]\n"
        "talker = pkg.talker:main\n"
        "[gui_scripts]\n"
        "viewer = pkg.viewer:main\n"
        "''')\n"
        "setup(entry_points={'console_scripts': 'listener = pkg.listener:main'})\n"
    )
    assert rows(facts) == [
        ("program", "talker", ("pkg/talker.py",)),
        ("program", "listener", ("pkg/listener.py",)),
    ]
    assert span(facts, "talker") == Span(2, 20, 7, 4)  # the whole string


def test_setup_py_columns_count_code_points() -> None:
    facts = of_setup(
        "from setuptools import setup\n"
        "setup(author='José Ñandú', entry_points={'console_scripts': ['a = pkg.a:main']})\n"
    )
    assert span(facts, "a") == Span(2, 62, 2, 78)


def test_setup_py_without_setup_call_or_entry_points() -> None:
    assert rows(of_setup("from setuptools import setup\nsetup(name='pkg')\n")) == []
    assert rows(of_setup("entry_points = {'console_scripts': ['a = b:c']}\n")) == []
    assert rows(of_setup("setup(entry_points=make_entry_points())\n")) == []


def test_setup_py_with_a_syntax_error_is_a_parse_error() -> None:
    facts = fixture("broken_setup_py/setup.py")
    assert facts.executables == ()
    (error,) = facts.parse_errors
    assert error.message == "not valid Python 3: '(' was never closed"
    assert error.span == Span(5, 6, 5, 7)


def test_setup_py_encodings() -> None:
    declared = "# -*- coding: latin-1 -*-\nsetup(entry_points={'console_scripts': ['é = p.a:m']})\n"
    assert names(of_setup(declared.encode("latin-1"))) == ["é"]
    (error,) = of_setup(b"setup(author='Jos\xe9')\n").parse_errors
    assert error.message.startswith("cannot decode Python source as utf-8")
    assert error.span == Span(1, 18, 1, 19)
    (error,) = of_setup(b"# coding: klingon\nsetup()\n").parse_errors
    assert error.message == "unknown source encoding 'klingon'"
    (error,) = of_setup(b"\xef\xbb\xbf# coding: latin-1\nsetup()\n").parse_errors
    assert error.message == "UTF-8 BOM contradicts the coding declaration 'latin-1'"


def test_setup_py_null_bytes_and_deep_nesting_are_parse_errors() -> None:
    (error,) = of_setup(b"setup(\x00)\n").parse_errors
    assert error.message.startswith("not valid Python 3")
    (error,) = of_setup(("x = " + "(" * 300 + ")" * 300 + "\n").encode()).parse_errors
    assert error.message.startswith("not valid Python 3")


def test_setup_py_long_concatenation_does_not_crash() -> None:
    """CPython parses this, but following it recursively would exhaust the stack."""
    entry = " + ".join(["'a'"] * 2000)
    facts = of_setup(f"setup(entry_points={{'console_scripts': [{entry}]}})\n")
    assert (facts.parse_errors, facts.executables) == ((), ())


# ---------------------------------------------------------------------------------------
# setup.cfg


def test_setup_cfg_console_scripts() -> None:
    facts = fixture("controller_manager/setup.cfg")
    assert facts.language is Language.SETUP_CFG
    assert rows(facts) == [
        ("program", "spawner", ("controller_manager/spawner.py",)),
        ("program", "unspawner", ("controller_manager/unspawner.py",)),
        ("program", "hardware_spawner", ("controller_manager/hardware_spawner.py",)),
    ]
    assert span(facts, "spawner") == Span(11, 5, 11, 46)
    assert span(facts, "unspawner") == Span(13, 5, 13, 50)  # after the comment line


def test_setup_cfg_without_entry_points() -> None:
    assert rows(fixture("demo_nodes_py/setup.cfg")) == []


def test_setup_cfg_that_configparser_rejects_gives_nothing_silently() -> None:
    facts = fixture("broken_setup_cfg/setup.cfg")
    assert (facts.executables, facts.parse_errors) == ((), ())
    facts = of_setup("console_scripts = a = b:c\n", "setup.cfg")  # no section header
    assert (facts.executables, facts.parse_errors) == ((), ())


def test_setup_cfg_entry_on_the_option_line_and_pbr_section() -> None:
    facts = of_setup(
        "[metadata]\nname = pkg\n\n[entry_points]\n"
        "console_scripts = talker = pkg.talker:main\n"
        "\tlistener=pkg.listener:main\n",
        "setup.cfg",
    )
    assert rows(facts) == [
        ("program", "talker", ("pkg/talker.py",)),
        ("program", "listener", ("pkg/listener.py",)),
    ]
    assert span(facts, "talker") == Span(5, 19, 5, 43)
    assert span(facts, "listener") == Span(6, 2, 6, 28)


# ---------------------------------------------------------------------------------------
# Never raises

ALL_FIXTURES = sorted(path for path in FIXTURES.glob("*/*") if path.is_file())


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(ALL_FIXTURES), st.integers(min_value=0, max_value=3000), st.data())
def test_truncated_and_spliced_fixtures_never_raise(path: Path, cut: int, data: Any) -> None:
    text = path.read_bytes()
    noise = data.draw(st.binary(max_size=20))
    module = cmake if path.name == "CMakeLists.txt" else setup_py
    for mangled in (text[:cut], text[:cut] + noise + text[cut:]):
        facts = module.extract(path.name, mangled, None, ROS2)
        if module is cmake or path.suffix == ".cfg":
            assert facts.parse_errors == ()
        for executable in facts.executables:
            assert executable.name
            assert 1 <= executable.span.line <= executable.span.end_line


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet='()[]=#"\\${}; \n\tab;', max_size=200))
def test_random_cmake_never_raises(text: str) -> None:
    facts = of_cmake("add_executable(x a.cpp)\n" + text)
    assert facts.parse_errors == ()


def test_setup_py_compiler_warnings_are_not_printed(recwarn: pytest.WarningsRecorder) -> None:
    facts = of_setup(
        "import re\nPATTERN = '\\d+'\nsetup(entry_points={'console_scripts': ['a = b:c']})\n"
    )
    assert names(facts) == ["a"]
    assert [str(warning.message) for warning in recwarn] == []


def test_nested_loops_and_calls_stop_rather_than_hang() -> None:
    items = " ".join(f"i{index}" for index in range(200))
    loops = "".join(f"foreach(v{depth} {items})\n" for depth in range(5))
    ends = "endforeach()\n" * 5
    facts = of_cmake(f"{loops}  add_executable(fixed src/fixed.cpp)\n{ends}")
    assert rows(facts) == [("program", "fixed", ("src/fixed.cpp",))]
