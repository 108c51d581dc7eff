"""What identifies a finding across edits: its rule, its file and the code on its line.

Line numbers shift whenever lines are inserted above; the line's own text (whitespace
removed, so re-indenting does not count) moves with the finding. SARIF's
``primaryLocationLineHash`` and the baseline both match findings by it.
"""

from __future__ import annotations

import hashlib

from .model import Diagnostic


def line_fingerprint(diagnostic: Diagnostic) -> str:
    """A short hash of the code, the path and the finding's source line (its message when
    the line is unknown)."""
    if diagnostic.source_line is not None:
        anchor = "line:" + "".join(diagnostic.source_line.split())
    else:
        anchor = "message:" + diagnostic.message
    material = "\0".join((diagnostic.code, diagnostic.path, anchor))
    return hashlib.sha256(material.encode("utf-8")).hexdigest()[:16]


def spelled_name(diagnostic: Diagnostic) -> str:
    """The text the finding points at (the name literal), when its line is known."""
    span, line = diagnostic.span, diagnostic.source_line
    if line is None or span.line != span.end_line:
        return ""
    return line[span.column - 1 : span.end_column - 1]
