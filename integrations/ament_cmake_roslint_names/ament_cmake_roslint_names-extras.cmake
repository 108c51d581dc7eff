# Loaded by find_package(ament_cmake_roslint_names): the function, and the hook that
# ament_lint_auto_find_test_dependencies() runs for every package that test-depends on us.

find_package(ament_cmake_test QUIET REQUIRED)

include("${ament_cmake_roslint_names_DIR}/ament_roslint_names.cmake")

ament_register_extension("ament_lint_auto" "ament_cmake_roslint_names"
  "ament_cmake_roslint_names_lint_hook.cmake")
