"""The JSON report (``--output-format json``), version 1.

One UTF-8 JSON object, indented by two spaces, keys in the fixed order below, ending with a
line break::

    {
      "version": 1,
      "tool": {"name": "roslint-names", "version": "0.1.0"},
      "findings": [
        {
          "path": "src/robot_bringup/launch/robot.launch",
          "line": 12,
          "column": 15,
          "end_line": 12,
          "end_column": 28,
          "code": "RN101",
          "name": "illegal-name",
          "severity": "error",
          "message": "node name 'base-driver' contains '-' at index 4; use 'base_driver'",
          "related": [],
          "fix": null
        }
      ]
    }

Fields:

``version`` (integer)
    The version of this format. It changes only when a field is removed or changes meaning;
    new fields may be added within a version, so ignore the ones you do not know.
``tool.name``, ``tool.version`` (strings)
    ``"roslint-names"`` and the version that wrote the report.
``findings`` (array)
    One object per finding, in the order the text report shows them: by path, line, column,
    code. Findings silenced by a suppression comment are not listed.
``path`` (string)
    The file, relative to the directory roslint-names ran in, with ``/`` separators.
``line``, ``column`` (integers)
    Where the offending name starts: 1-based line, and 1-based column counted in Unicode
    code points (not bytes, not UTF-16 units).
``end_line``, ``end_column`` (integers)
    Where it ends; ``end_column`` is exclusive (the column just after the name).
``code`` (string)
    The rule code, ``RN`` and three digits (``RN101``); stable, never reused.
``name`` (string)
    The rule's kebab-case slug (``illegal-name``).
``severity`` (string)
    ``"error"`` or ``"warning"``, after configuration.
``message`` (string)
    One sentence saying what is wrong and, when there is one, the fix.
``related`` (array)
    Other locations the finding involves, for example the other half of a case collision
    (RN401), or the other places that write the name the finding judges: objects with
    ``path``, ``line``, ``column``, ``end_line``, ``end_column`` (as above) and
    ``message``. Empty when there are none.
``fix`` (object or null)
    The certain fix, when the rule has one and the file spells the name exactly: the text
    from ``line``:``column`` to ``end_line``:``end_column`` (exclusive) becomes
    ``replacement``.
    ``safe`` is true when it cannot change what the running system does (``--fix``
    applies it), false when it may (``--fix --unsafe-fixes``).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

from ..catalog import RuleMeta
from ..model import Diagnostic, RelatedLocation, Span
from .base import ReportContext, visible

FORMAT_VERSION = 1
TOOL_NAME = "roslint-names"


def render_json(
    diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta], context: ReportContext
) -> str:
    document = {
        "version": FORMAT_VERSION,
        "tool": {"name": TOOL_NAME, "version": context.tool_version},
        "findings": [_finding(diagnostic) for diagnostic in visible(diagnostics)],
    }
    return json.dumps(document, indent=2, ensure_ascii=False) + "\n"


def _finding(diagnostic: Diagnostic) -> dict[str, Any]:
    return {
        "path": diagnostic.path,
        **_span(diagnostic.span),
        "code": diagnostic.code,
        "name": diagnostic.rule_name,
        "severity": diagnostic.severity.value,
        "message": diagnostic.message,
        "related": [_related(related) for related in diagnostic.related],
        "fix": None if diagnostic.edit is None else _fix(diagnostic),
    }


def _fix(diagnostic: Diagnostic) -> dict[str, Any]:
    """The fix's own edit, and a rename's edits of the name's other uses (``also``)."""
    edit = diagnostic.edit
    assert edit is not None
    return {
        "safe": edit.safe,
        **_span(edit.span),
        "replacement": edit.text,
        "also": [
            {"path": other.path or diagnostic.path, **_span(other.span), "replacement": other.text}
            for other in diagnostic.also
        ],
    }


def _related(related: RelatedLocation) -> dict[str, Any]:
    return {"path": related.path, **_span(related.span), "message": related.message}


def _span(span: Span) -> dict[str, int]:
    return {
        "line": span.line,
        "column": span.column,
        "end_line": span.end_line,
        "end_column": span.end_column,
    }
