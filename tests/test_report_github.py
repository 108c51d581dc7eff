"""GitHub Actions workflow commands (annotations)."""

from __future__ import annotations

import os
import re
from dataclasses import replace
from pathlib import Path

import pytest
import report_sample as sample

from roslint_names.model import Diagnostic
from roslint_names.report import render
from roslint_names.report.github import escape_data, escape_property

FIXTURES = Path(__file__).parent / "fixtures" / "report"
COMMAND = re.compile(r"^::(error|warning) ([^:]*)::(.*)$")


def github(diagnostics: tuple[Diagnostic, ...] = sample.DIAGNOSTICS) -> str:
    return render("github", diagnostics, sample.RULES, sample.context())


def unescape(value: str) -> str:
    """What the runner does with an escaped value (the reverse of @actions/core)."""
    for escaped, raw in (("%0D", "\r"), ("%0A", "\n"), ("%3A", ":"), ("%2C", ","), ("%25", "%")):
        value = value.replace(escaped, raw)
    return value


def parse(line: str) -> tuple[str, dict[str, str], str]:
    match = COMMAND.match(line)
    assert match is not None, line
    properties = dict(item.split("=", 1) for item in match.group(2).split(","))
    return (
        match.group(1),
        {key: unescape(value) for key, value in properties.items()},
        unescape(match.group(3)),
    )


def test_an_error_annotation() -> None:
    assert github((sample.RN101,)) == (
        "::error file=src/robot_bringup/launch/robot.launch,line=12,col=15,endLine=12,"
        "endColumn=26,title=RN101 illegal-name::node name 'base-driver' contains '-' at index 4;"
        " use 'base_driver'\n"
    )


def test_warnings_use_the_warning_command() -> None:
    assert github((sample.RN202_UNICODE,)).startswith("::warning file=src/ünïcode pkg/src/")


def test_one_command_per_finding_that_parses_back() -> None:
    shown = [d for d in sample.DIAGNOSTICS if not d.suppressed]
    lines = github().splitlines()
    assert len(lines) == len(shown)
    for line, diagnostic in zip(lines, shown, strict=True):
        command, properties, message = parse(line)
        assert command == diagnostic.severity.value
        assert properties == {
            "file": diagnostic.path,
            "line": str(diagnostic.span.line),
            "col": str(diagnostic.span.column),
            "endLine": str(diagnostic.span.end_line),
            "endColumn": str(diagnostic.span.end_column),
            "title": f"{diagnostic.code} {diagnostic.rule_name}",
        }
        assert message.splitlines()[0] == diagnostic.message


def test_related_locations_are_extra_lines_of_the_message() -> None:
    (line,) = github((sample.RN401,)).splitlines()
    assert line.endswith(
        "::topic '/cmd_vel' differs only in case from '/Cmd_Vel'"
        "%0Asrc/teleop/scripts/joy teleop.py:9:23: note: '/Cmd_Vel' is used here"
    )


@pytest.mark.parametrize(
    ("raw", "data", "prop"),
    [
        ("100%", "100%25", "100%25"),
        ("a\nb", "a%0Ab", "a%0Ab"),
        ("a\r\nb", "a%0D%0Ab", "a%0D%0Ab"),
        ("a:b,c", "a:b,c", "a%3Ab%2Cc"),
        ("%0A", "%250A", "%250A"),  # an already escaped-looking value stays literal
        ("plain é", "plain é", "plain é"),
    ],
)
def test_escaping_like_actions_core(raw: str, data: str, prop: str) -> None:
    assert escape_data(raw) == data
    assert escape_property(raw) == prop
    assert unescape(data) == raw
    assert unescape(prop) == raw


def test_hostile_values_are_escaped_in_place() -> None:
    hostile = replace(
        sample.RN101,
        path="weird,dir/a:b%.launch",
        message="50% of names\nhave '::' in them, sadly",
    )
    (line,) = github((hostile,)).splitlines()
    assert "file=weird%2Cdir/a%3Ab%25.launch," in line
    assert line.endswith("::50%25 of names%0Ahave '::' in them, sadly")
    _, properties, message = parse(line)
    assert properties["file"] == hostile.path
    assert message == hostile.message


def test_suppressed_findings_are_left_out() -> None:
    assert github((sample.RN101_SUPPRESSED,)) == ""
    assert "lidar.front" not in github()


def test_order_and_determinism() -> None:
    assert github() == github()
    backwards = github(tuple(reversed(sample.DIAGNOSTICS))).splitlines()
    assert backwards == list(reversed(github().splitlines()))


def test_snapshot() -> None:
    path = FIXTURES / "expected-github.txt"
    actual = github()
    if os.environ.get("ROSLINT_UPDATE_SNAPSHOTS"):
        path.write_text(actual, encoding="utf-8", newline="\n")
    assert actual == path.read_text(encoding="utf-8"), "expected-github.txt changed"
