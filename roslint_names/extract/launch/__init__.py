"""Launch files and robot descriptions: the nodes they start and the names they spell.

ROS 1 and ROS 2 XML (``xml_launch``), YAML (``yaml_launch``) and Python launch files
(``python_launch``, with ``python_values`` and ``python_paths``), their ``$(...)``
``substitution`` and ``include`` handling, what the formats share (``common``), URDF and
XACRO (``urdf``), and lxml kept safe on hostile input (``xmlsafe``).
"""
