# What ament_lint_auto runs: the package's ROS names checked, minus the files the package
# excludes from every linter (AMENT_LINT_AUTO_FILE_EXCLUDE).

message(STATUS "Added test 'roslint_names' to check ROS node, topic, service and parameter names")
if(AMENT_LINT_AUTO_FILE_EXCLUDE)
  message(STATUS "Configured 'roslint_names' exclude dirs and/or files: ${AMENT_LINT_AUTO_FILE_EXCLUDE}")
endif()
ament_roslint_names(EXCLUDE ${AMENT_LINT_AUTO_FILE_EXCLUDE})
