"""Files that are templates: launch files and URDF a generator fills in before anyone
launches them, such as the MoveIt Setup Assistant's
``templates/moveit_config_pkg_template/launch/gazebo.launch`` with its
``<param name="robot_description" [GAZEBO_URDF_LOAD_ATTRIBUTE] />``.

Such a file's placeholders are not the project's mistakes: the XML does not parse where
one stands for an attribute (RN001) and a name holding one is not a ROS name yet. So a
finding on a line holding a placeholder is not reported in a file under a template
folder (``templates``, ``template``, ``*_template``, ``*_templates``); the rest of the
file is judged as any other, since the generated packages copy it as it is, and the
template is where its edit goes. Placeholders are the generators' spellings:
``[UPPER_CASE]`` (MoveIt Setup Assistant), ``@VAR@`` (CMake's ``configure_file``),
``{{ ... }}`` and ``{% ... %}`` (Jinja, empy-style generators).

Files named ``*.in``, ``*.em``, ``*.jinja`` or ``*.template`` are never linted: their
suffix is not one a linted language has (``discover``).
"""

from __future__ import annotations

import re

_TEMPLATE_DIRECTORY = re.compile(r"templates?|.+_templates?", re.IGNORECASE)
_PLACEHOLDER = re.compile(
    r"\[[A-Z][A-Z0-9_]*\]|@[A-Za-z_][A-Za-z0-9_]*@|\{\{[^{}\n]*\}\}|\{%[^%\n]*%\}"
)


def is_template(relative_path: str) -> bool:
    """Whether the file at ``relative_path`` ('/'-separated) lies in a template folder."""
    *directories, _ = relative_path.split("/")
    return any(_TEMPLATE_DIRECTORY.fullmatch(directory) for directory in directories)


def holds_placeholder(line: str) -> bool:
    """Whether a line of a template holds a placeholder."""
    return _PLACEHOLDER.search(line) is not None
