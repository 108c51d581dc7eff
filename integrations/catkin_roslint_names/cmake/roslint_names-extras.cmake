# roslint_names_add_test(): for catkin packages what roslint_add_test() is for roslint.
#
#   find_package(catkin REQUIRED COMPONENTS catkin_roslint_names)
#   if(CATKIN_ENABLE_TESTING)
#     roslint_names_add_test()            # or: roslint_names_add_test(launch src CONFIG ...)
#   endif()
#
# `catkin run_tests` (or `make run_tests`) then checks the package's ROS names and writes
# ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/roslint_names-${PROJECT_NAME}.xml, which
# catkin_test_results reads. A target `roslint_names_${PROJECT_NAME}` runs the same check
# with the report on the console.
#
# :param CONFIG: the roslint-names.toml to use (default: the nearest one above the package)
# :param ROS: the generation to assume where a file does not tell, default "1"
# :param ARGN: the files or directories to check, relative to the package; default: all of it

function(roslint_names_add_test)
  cmake_parse_arguments(ARG "" "CONFIG;ROS" "" ${ARGN})
  if(NOT ARG_ROS)
    set(ARG_ROS "1")
  endif()
  find_program(roslint_names_BIN NAMES "roslint-names")
  if(NOT roslint_names_BIN)
    message(FATAL_ERROR "roslint_names_add_test() could not find program 'roslint-names'; "
      "install it with: pip install \"roslint-names @ git+https://github.com/roslint-names/roslint-names\"")
  endif()

  set(options "--ros" "${ARG_ROS}")
  if(ARG_CONFIG)
    list(APPEND options "--config" "${ARG_CONFIG}")
  endif()
  set(paths ${ARG_UNPARSED_ARGUMENTS})
  if(NOT paths)
    set(paths ".")
  endif()

  set(result_name "roslint_names-${PROJECT_NAME}.xml")
  set(result_file "${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/${result_name}")
  # catkin_run_tests_target joins COMMAND into one shell command line.
  set(command "${roslint_names_BIN}" "check" ${options}
    "--format" "junit" "--output" "${result_file}" ${paths})
  string(REPLACE ";" " " command "${command}")
  catkin_run_tests_target("roslint_names" "package" "${result_name}"
    COMMAND "${command}"
    WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")

  add_custom_target("roslint_names_${PROJECT_NAME}"
    COMMAND "${roslint_names_BIN}" "check" ${options} ${paths}
    WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
    VERBATIM)
endfunction()
