"""Which ROS generation a file belongs to, as far as its package says.

The nearest ``package.xml`` decides: a catkin build tool means ROS 1, an ament build type or
build tool means ROS 2. A package that declares both under ``$ROS_VERSION`` conditions
(packages built for both generations) decides nothing, and the file's own evidence does.

package.xml is read with a regular expression rather than lxml on purpose: a one-file
pre-commit run over a C++ or Python file must not pay for importing an XML parser.
"""

from __future__ import annotations

import re
from pathlib import Path

from .model import Generation

_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)
_DEPEND = re.compile(
    r"<(buildtool_depend|build_type)(\s[^>]*)?>\s*([A-Za-z0-9_]+)\s*</\1>", re.DOTALL
)
_CONDITION = re.compile(r"""condition\s*=\s*["']([^"']*)["']""")


def package_xml_generation(text: str) -> Generation | None:
    found: set[Generation] = set()
    for match in _DEPEND.finditer(_COMMENT.sub("", text)):
        attributes, tool = match.group(2) or "", match.group(3)
        condition = _CONDITION.search(attributes)
        if condition and "ROS_VERSION" in condition.group(1):
            continue  # built for both generations: the condition decides, not the package
        if tool == "catkin":
            found.add(Generation.ROS1)
        elif tool.startswith("ament"):
            found.add(Generation.ROS2)
    return found.pop() if len(found) == 1 else None


class PackageGenerations:
    """Nearest-package.xml lookup with one read per directory for the whole run."""

    def __init__(self) -> None:
        self._by_directory: dict[Path, Generation | None] = {}

    def for_file(self, path: Path) -> Generation | None:
        return self._for_directory(path.parent)

    def _for_directory(self, directory: Path) -> Generation | None:
        if directory in self._by_directory:
            return self._by_directory[directory]
        manifest = directory / "package.xml"
        generation: Generation | None
        if manifest.is_file():
            try:
                text = manifest.read_text(encoding="utf-8", errors="replace")
            except OSError:
                text = ""
            generation = package_xml_generation(text)
        elif directory.parent == directory:
            generation = None
        else:
            generation = self._for_directory(directory.parent)
        self._by_directory[directory] = generation
        return generation
