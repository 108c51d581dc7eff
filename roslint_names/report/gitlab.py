"""GitLab Code Quality: the JSON array a ``codequality`` report artifact holds.

Each finding is one issue with the fields GitLab requires: ``description``, ``check_name``
(the rule code and slug), ``fingerprint``, ``severity`` and ``location`` (``path`` relative
to the project root, ``lines.begin``). GitLab compares the fingerprints of a merge
request's report with its target branch's to show what is new and what is fixed, so a
fingerprint must survive lines inserted above the finding: it is made of the rule, the
path, the name and the code on the finding's line (``fingerprint``), and the occurrence
count among findings alike, never of the line number.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..catalog import RuleMeta
from ..fingerprint import line_fingerprint, spelled_name
from ..model import Diagnostic, Severity
from .base import ReportContext, visible

# GitLab's scale is info, minor, major, critical, blocker; ruff and others put their
# errors at major.
SEVERITY = {Severity.ERROR: "major", Severity.WARNING: "minor"}


def render_gitlab(
    diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta], context: ReportContext
) -> str:
    seen: Counter[tuple[str, ...]] = Counter()
    issues: list[dict[str, Any]] = []
    for diagnostic in visible(diagnostics):
        path = project_path(diagnostic.path, context.root)
        key = (diagnostic.code, path, spelled_name(diagnostic), line_fingerprint(diagnostic))
        seen[key] += 1
        material = "\0".join((*key, str(seen[key])))
        issues.append(
            {
                "type": "issue",
                "description": f"{diagnostic.code} {diagnostic.message}",
                "check_name": f"{diagnostic.code} {diagnostic.rule_name}",
                "fingerprint": hashlib.sha256(material.encode("utf-8")).hexdigest(),
                "severity": SEVERITY[diagnostic.severity],
                "location": {"path": path, "lines": {"begin": diagnostic.span.line}},
            }
        )
    return json.dumps(issues, indent=2, ensure_ascii=False) + "\n"


def project_path(path: str, root: Path) -> str:
    """``path`` relative to the project root, '/'-separated, as GitLab links files."""
    if os.path.isabs(path):
        try:
            path = os.path.relpath(path, root)
        except ValueError:  # another drive on Windows: leave it absolute
            return Path(path).as_posix()
    return Path(path).as_posix()
