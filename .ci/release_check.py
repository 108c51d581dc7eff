"""Checks a release tag before anything is built: ``release_check.py vX.Y.Z [--notes]``.

The tag must name the version ``roslint_names/__init__.py`` holds (the one source of the
package's version) and CHANGELOG.md must have a ``## [X.Y.Z]`` section; with ``--notes``
that section is printed, for the GitHub release. Exit 1 with the reason otherwise.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main(argv: list[str]) -> int:
    if not argv or not argv[0].startswith("v"):
        print("usage: release_check.py vX.Y.Z [--notes]", file=sys.stderr)
        return 2
    version = argv[0][1:]
    source = (ROOT / "roslint_names" / "__init__.py").read_text(encoding="utf-8")
    found = re.search(r'^__version__ = "([^"]+)"', source, re.MULTILINE)
    if found is None or found.group(1) != version:
        held = found.group(1) if found else "none"
        print(f"tag {argv[0]} is not the package's version ({held})", file=sys.stderr)
        return 1
    changelog = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    section = re.search(
        rf"^## \[{re.escape(version)}\][^\n]*\n(.*?)(?=^## |\Z)",
        changelog,
        re.MULTILINE | re.DOTALL,
    )
    if section is None or not section.group(1).strip():
        print(f"CHANGELOG.md has no section for {version}", file=sys.stderr)
        return 1
    if "--notes" in argv[1:]:
        print(section.group(1).strip())
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
