"""Extractors: one file's bytes in, its ``model.FileFacts`` out. They only extract.

- ``cpp``: roscpp and rclcpp code, through tree-sitter-cpp;
- ``python``: rospy and rclpy code, through libcst (a Python launch file goes on to
  ``launch``);
- ``launch``: launch files in every format (ROS 1 XML, ROS 2 XML, YAML and Python), their
  substitutions and includes, and the robot descriptions (URDF, XACRO) they load;
- ``build``: what a package builds and installs (CMakeLists.txt, setup.py, setup.cfg),
  which maps a launch file's executables to their sources;
- ``literals`` and ``evidence``: text-level evidence that more than one extractor uses.

``gather.EXTRACTOR_MODULES`` names each language's entry module; parsers are imported
only by the modules that need them, on first use.
"""
