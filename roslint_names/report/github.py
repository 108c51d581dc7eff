"""GitHub Actions workflow commands: each finding becomes an annotation on the pull request.

::

    ::error file=src/a.launch,line=3,col=9,endLine=3,endColumn=20,title=RN101 illegal-name::...

``::warning`` for warnings. Values are escaped as GitHub's ``@actions/core`` does: in the
message ``%``, CR and LF become ``%25``, ``%0D`` and ``%0A``; in properties ``:`` and ``,``
also become ``%3A`` and ``%2C``. Related locations are appended to the message, one line
each, in the text report's ``path:line:col: note: message`` form.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..catalog import RuleMeta
from ..model import Diagnostic
from .base import ReportContext, visible


def render_github(
    diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta], context: ReportContext
) -> str:
    return "".join(format_command(diagnostic) + "\n" for diagnostic in visible(diagnostics))


def format_command(diagnostic: Diagnostic) -> str:
    span = diagnostic.span
    properties = (
        ("file", diagnostic.path),
        ("line", str(span.line)),
        ("col", str(span.column)),
        ("endLine", str(span.end_line)),
        ("endColumn", str(span.end_column)),
        ("title", f"{diagnostic.code} {diagnostic.rule_name}"),
    )
    rendered = ",".join(f"{key}={escape_property(value)}" for key, value in properties)
    message = diagnostic.message
    for related in diagnostic.related:
        location = f"{related.path}:{related.span.line}:{related.span.column}"
        message += f"\n{location}: note: {related.message}"
    return f"::{diagnostic.severity.value} {rendered}::{escape_data(message)}"


def escape_data(value: str) -> str:
    """Escape a command's message as ``@actions/core`` ``escapeData`` does."""
    return value.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(value: str) -> str:
    """Escape a property value as ``@actions/core`` ``escapeProperty`` does."""
    return escape_data(value).replace(":", "%3A").replace(",", "%2C")
