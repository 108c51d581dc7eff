"""JUnit XML, as ``colcon test-result``, Jenkins and GitLab read it.

One ``testsuite`` for the run; one ``testcase`` per checked file, named by its path, that
passes when the file has no finding. Each finding is a ``failure`` of its file's testcase
(an ``error`` for RN001: the file could not be checked), whose ``type`` is the rule code,
whose ``message`` is the location and message on one line, and whose text is the finding
as the text report writes it, related locations included. The suite's ``failures`` and
``errors`` count testcases, as JUnit does, so that ``tests`` is never less than their sum.

Valid against the Jenkins xunit plugin's ``junit-10.xsd``, the schema pytest checks its
own JUnit output with. No timestamps and no durations: the same findings give the same
bytes.
"""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import replace

from ..catalog import RuleMeta
from ..model import Diagnostic
from .base import ReportContext, visible
from .text import render_text

SUITE_NAME = "roslint_names"  # what ament_lint names its suites: the linter, underscored
PARSE_ERROR = "RN001"

# Characters XML 1.0 cannot hold at all, not even escaped: a name with a control
# character (RN101 reports them) would make the whole report unreadable.
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]")


def render_junit(
    diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta], context: ReportContext
) -> str:
    import xml.etree.ElementTree as ET  # only a JUnit report pays for the import

    by_file: dict[str, list[Diagnostic]] = defaultdict(list)
    for diagnostic in visible(diagnostics):
        by_file[diagnostic.path].append(diagnostic)
    files = sorted({*context.files, *by_file})
    errors = sum(1 for path in files if any(d.code == PARSE_ERROR for d in by_file[path]))
    failures = sum(1 for path in files if by_file[path]) - errors
    suite = ET.Element(
        "testsuite",
        {
            "name": SUITE_NAME,
            "tests": str(len(files)),
            "failures": str(failures),
            "errors": str(errors),
            "skipped": "0",
        },
    )
    plain = replace(context, color=False)
    for path in files:
        case = ET.SubElement(suite, "testcase", {"name": _xml(path), "classname": SUITE_NAME})
        for diagnostic in by_file[path]:
            kind = "error" if diagnostic.code == PARSE_ERROR else "failure"
            span = diagnostic.span
            message = f"{span.line}:{span.column}: {diagnostic.message} [{diagnostic.code}]"
            result = ET.SubElement(
                case, kind, {"type": diagnostic.code, "message": _xml(" ".join(message.split()))}
            )
            result.text = _xml(render_text([diagnostic], rules, plain))
    ET.indent(suite, space="  ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suite, "unicode") + "\n"


def _xml(text: str) -> str:
    """``text`` with what XML cannot carry written as ``\\uXXXX``."""
    return _NOT_XML.sub(lambda found: f"\\u{ord(found.group()):04x}", text)
