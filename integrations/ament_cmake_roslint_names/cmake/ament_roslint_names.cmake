#
# Add a test that checks the package's ROS names with roslint-names.
#
# :param TESTNAME: the name of the test, default: "roslint_names"
# :type TESTNAME: string
# :param CONFIG_FILE: the roslint-names.toml to use; default: the nearest one above the
#   package, or the global variable 'ament_cmake_roslint_names_CONFIG_FILE'
# :type CONFIG_FILE: string
# :param ROS: the ROS generation to assume where a file does not tell ("1" or "2")
# :type ROS: string
# :param EXCLUDE: files or directories to skip (gitignore patterns)
# :type EXCLUDE: list
# :param ARGN: the files or directories to check, default: the package
# :type ARGN: list of strings
#
# @public
#
function(ament_roslint_names)
  cmake_parse_arguments(ARG "" "TESTNAME;CONFIG_FILE;ROS" "EXCLUDE" ${ARGN})
  if(NOT ARG_TESTNAME)
    set(ARG_TESTNAME "roslint_names")
  endif()

  find_program(ament_roslint_names_BIN NAMES "ament_roslint_names")
  if(NOT ament_roslint_names_BIN)
    message(FATAL_ERROR "ament_roslint_names() could not find program 'ament_roslint_names'")
  endif()

  set(result_file "${AMENT_TEST_RESULTS_DIR}/${PROJECT_NAME}/${ARG_TESTNAME}.xunit.xml")
  # The paths first: --exclude takes every argument after it.
  set(cmd "${ament_roslint_names_BIN}" ${ARG_UNPARSED_ARGUMENTS} "--xunit-file" "${result_file}")
  if(ARG_CONFIG_FILE)
    list(APPEND cmd "--config" "${ARG_CONFIG_FILE}")
  elseif(DEFINED ament_cmake_roslint_names_CONFIG_FILE)
    list(APPEND cmd "--config" "${ament_cmake_roslint_names_CONFIG_FILE}")
  endif()
  if(ARG_ROS)
    list(APPEND cmd "--ros" "${ARG_ROS}")
  endif()
  if(ARG_EXCLUDE)
    list(APPEND cmd "--exclude" ${ARG_EXCLUDE})
  endif()

  file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/ament_roslint_names")
  ament_add_test(
    "${ARG_TESTNAME}"
    COMMAND ${cmd}
    OUTPUT_FILE "${CMAKE_BINARY_DIR}/ament_roslint_names/${ARG_TESTNAME}.txt"
    RESULT_FILE "${result_file}"
    WORKING_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}"
  )
  set_tests_properties(
    "${ARG_TESTNAME}"
    PROPERTIES
    LABELS "roslint_names;linter"
  )
endfunction()
