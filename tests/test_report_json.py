"""The JSON report: a documented, versioned object that round-trips."""

from __future__ import annotations

import json
import os
from dataclasses import replace
from pathlib import Path
from typing import Any

import report_sample as sample

from roslint_names.model import Diagnostic, Span
from roslint_names.report import json as json_report
from roslint_names.report import render

FIXTURES = Path(__file__).parent / "fixtures" / "report"
FINDING_KEYS = [
    "path",
    "line",
    "column",
    "end_line",
    "end_column",
    "code",
    "name",
    "severity",
    "message",
    "related",
    "fix",
]
RELATED_KEYS = ["path", "line", "column", "end_line", "end_column", "message"]


def output(diagnostics: tuple[Diagnostic, ...] = sample.DIAGNOSTICS) -> str:
    return render("json", diagnostics, sample.RULES, sample.context())


def document(diagnostics: tuple[Diagnostic, ...] = sample.DIAGNOSTICS) -> dict[str, Any]:
    loaded: dict[str, Any] = json.loads(output(diagnostics))
    return loaded


def test_versioned_envelope() -> None:
    loaded = document()
    assert list(loaded) == ["version", "tool", "findings"]
    assert loaded["version"] == 1
    assert loaded["tool"] == {"name": "roslint-names", "version": "0.1.0"}


def test_findings_round_trip() -> None:
    shown = [d for d in sample.DIAGNOSTICS if not d.suppressed]
    findings = document()["findings"]
    assert len(findings) == len(shown)
    for finding, diagnostic in zip(findings, shown, strict=True):
        assert list(finding) == FINDING_KEYS
        span = Span(finding["line"], finding["column"], finding["end_line"], finding["end_column"])
        assert finding["path"] == diagnostic.path
        assert span == diagnostic.span
        assert (finding["code"], finding["name"]) == (diagnostic.code, diagnostic.rule_name)
        assert finding["severity"] == diagnostic.severity.value
        assert finding["message"] == diagnostic.message


def test_related_locations() -> None:
    (finding,) = document((sample.RN401,))["findings"]
    (related,) = finding["related"]
    assert list(related) == RELATED_KEYS
    assert related == {
        "path": "src/teleop/scripts/joy teleop.py",
        "line": 9,
        "column": 23,
        "end_line": 9,
        "end_column": 33,
        "message": "'/Cmd_Vel' is used here",
    }
    assert document((sample.RN101,))["findings"][0]["related"] == []


def test_suppressed_findings_are_left_out() -> None:
    assert document((sample.RN101_SUPPRESSED,))["findings"] == []
    assert "lidar.front" not in output()


def test_layout_two_space_indent_utf8_and_trailing_newline() -> None:
    text = output()
    assert text.endswith("}\n") and not text.endswith("\n\n")
    assert '\n  "version": 1,\n' in text
    assert "ünïcode pkg" in text and "\\u" not in text  # readable, not \u-escaped
    assert text == json.dumps(json.loads(text), indent=2, ensure_ascii=False) + "\n"


def test_no_findings() -> None:
    assert document(())["findings"] == []


def test_order_is_the_order_given() -> None:
    backwards = tuple(reversed(sample.DIAGNOSTICS))
    lines = [finding["line"] for finding in document(backwards)["findings"]]
    assert lines == [7, 18, 21, 12]


def test_two_renders_are_identical() -> None:
    assert output() == output()


def test_escaping_survives_the_round_trip() -> None:
    tricky = replace(sample.RN101, message='name "a\\b"\tand\nnewline', path="dir/quote\"'.launch")
    (finding,) = document((tricky,))["findings"]
    assert finding["message"] == tricky.message
    assert finding["path"] == tricky.path


def test_every_field_is_documented_in_the_module_docstring() -> None:
    doc = json_report.__doc__ or ""
    for key in ["version", "tool.name", "tool.version", "findings", *FINDING_KEYS]:
        assert f"``{key}``" in doc, key
    assert "exclusive" in doc and "code points" in doc


def test_snapshot() -> None:
    path = FIXTURES / "expected.json"
    actual = output()
    if os.environ.get("ROSLINT_UPDATE_SNAPSHOTS"):
        path.write_text(actual, encoding="utf-8", newline="\n")
    assert actual == path.read_text(encoding="utf-8"), "expected.json changed; review the diff"
