"""Build metadata: the executables and component plugins a package builds or installs.

``cmake`` reads CMakeLists.txt: its commands from tree-sitter-cmake (``cmake_syntax``),
run by a small evaluator (``cmake_eval``) that follows variables, lists, functions and
both branches of an ``if``, into targets and their sources (``cmake_targets``,
``cmake_sources``). ``setup_py`` and ``setup_cfg`` read Python packages'
console_scripts (``setup_source``).
"""
