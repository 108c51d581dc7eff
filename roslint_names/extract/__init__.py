"""Extractors: one file's bytes in, its ``model.FileFacts`` out. They only extract.

- ``cpp``: roscpp and rclcpp code, through tree-sitter-cpp;
- ``python``: rospy and rclpy code, through libcst (a Python launch file goes on to
  ``launch``);
- ``launch``: launch files in every format (ROS 1 XML, ROS 2 XML, YAML and Python), their
  substitutions and includes, and the robot descriptions (URDF, XACRO) they load;
- ``build``: what a package builds and installs (CMakeLists.txt, setup.py, setup.cfg),
  which maps a launch file's executables to their sources;
- ``literals`` and ``evidence``: text-level evidence that more than one extractor uses.

``EXTRACTOR_MODULES`` names each language's entry module, which ``gather`` imports on
first use; parsers are imported only by the modules that need them, on first use. This
module imports nothing more: a run that takes its stored result asks it only which
languages are extracted.
"""

from __future__ import annotations

from ..model import Language

EXTRACTOR_MODULES: dict[Language, str] = {
    Language.CPP: "cpp.extract",
    Language.PYTHON: "python.extract",
    Language.LAUNCH_XML: "launch.xml_launch",
    Language.LAUNCH_YAML: "launch.yaml_launch",
    Language.URDF: "launch.urdf",
    Language.CMAKE: "build.cmake",
    Language.SETUP_PY: "build.setup_py",
    Language.SETUP_CFG: "build.setup_py",
    Language.PARAMETERS: "parameter_file",
    Language.RECONFIGURE: "build.reconfigure",
}
