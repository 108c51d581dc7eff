"""The text report, the summary line and the statistics."""

from __future__ import annotations

import os
import re
from dataclasses import replace
from pathlib import Path

import pytest
import report_sample as sample

from roslint_names.model import Diagnostic, Severity, Span
from roslint_names.report import FORMATS, render, statistics, summary
from roslint_names.report.text import excerpt

FIXTURES = Path(__file__).parent / "fixtures" / "report"
# VS Code's $gcc problem matcher, verbatim.
GCC = re.compile(r"^(.*?):(\d+):(\d*):?\s+(?:fatal\s+)?(warning|error):\s+(.*)$")
ANSI = re.compile(r"\x1b\[[0-9;]*m")


def text(diagnostics: tuple[Diagnostic, ...] = sample.DIAGNOSTICS, **changes: object) -> str:
    return render("text", diagnostics, sample.RULES, sample.context(**changes))


def check_snapshot(name: str, actual: str) -> None:
    path = FIXTURES / name
    if os.environ.get("ROSLINT_UPDATE_SNAPSHOTS"):
        path.write_text(actual, encoding="utf-8", newline="\n")
    assert actual == path.read_text(encoding="utf-8"), f"{name} changed; review the diff"


def test_formats_are_the_six_agreed() -> None:
    assert FORMATS == ("text", "json", "sarif", "github", "junit", "gitlab")


def test_unknown_format_is_a_value_error() -> None:
    with pytest.raises(ValueError, match="'xml'"):
        render("xml", sample.DIAGNOSTICS, sample.RULES, sample.context())


def test_one_gcc_line_per_finding() -> None:
    assert text((sample.RN101,)) == (
        "src/robot_bringup/launch/robot.launch:12:15: error: node name 'base-driver' contains "
        "'-' at index 4; use 'base_driver' [RN101 illegal-name]\n"
    )


def test_the_gcc_problem_matcher_reads_every_finding() -> None:
    lines = text().splitlines()
    findings = [line for line in lines if ": note: " not in line]
    shown = [d for d in sample.DIAGNOSTICS if not d.suppressed]
    assert len(findings) == len(shown)
    for line, diagnostic in zip(findings, shown, strict=True):
        match = GCC.match(line)
        assert match is not None, line
        assert match.group(1) == diagnostic.path  # spaces and non-ASCII included
        assert int(match.group(2)) == diagnostic.span.line
        assert int(match.group(3)) == diagnostic.span.column
        assert match.group(4) == diagnostic.severity.value
        assert match.group(5) == f"{diagnostic.message} [{diagnostic.code} {diagnostic.rule_name}]"


def test_paths_with_spaces_and_non_ascii_messages() -> None:
    line = text((sample.RN202_UNICODE,)).rstrip("\n")
    match = GCC.match(line)
    assert match is not None
    assert match.group(1) == "src/ünïcode pkg/src/bras_robot.py"
    assert "'/bras/état'" in match.group(5)


def test_related_locations_are_gcc_notes_after_their_finding() -> None:
    lines = text((sample.RN401,)).splitlines()
    assert lines == [
        "src/teleop/src/teleop_node.cpp:18:29: warning: topic '/cmd_vel' differs only in case "
        "from '/Cmd_Vel' [RN401 case-collision]",
        "src/teleop/scripts/joy teleop.py:9:23: note: '/Cmd_Vel' is used here",
    ]
    assert GCC.match(lines[1]) is None  # $gcc ignores notes, as it should


def test_suppressed_findings_are_left_out() -> None:
    assert "lidar.front" not in text()
    assert text((sample.RN101_SUPPRESSED,)) == ""


def test_no_findings_no_output() -> None:
    assert text(()) == ""


def test_order_is_the_order_given() -> None:
    lines = [line for line in text().splitlines() if ": note: " not in line]
    assert [line.split(":")[1] for line in lines] == ["12", "21", "18", "7"]
    backwards = tuple(reversed(sample.DIAGNOSTICS))
    assert text(backwards).splitlines()[0].startswith("src/ünïcode pkg/")


def test_two_renders_are_identical() -> None:
    assert text(show_source=True) == text(show_source=True)


def test_a_message_with_a_line_break_stays_on_one_line() -> None:
    diagnostic = replace(sample.RN101, message="first line\nsecond line")
    assert text((diagnostic,)).count("\n") == 1
    assert "first line second line [RN101" in text((diagnostic,))


def test_no_colour_unless_asked() -> None:
    assert "\x1b" not in text(show_source=True)


def test_colour_marks_path_and_severity() -> None:
    coloured = text(color=True)
    assert "\x1b[1msrc/robot_bringup/launch/robot.launch:12:15:\x1b[0m" in coloured
    assert "\x1b[1;31merror:\x1b[0m" in coloured
    assert "\x1b[1;33mwarning:\x1b[0m" in coloured
    assert ANSI.sub("", coloured) == text()


def test_show_source_prints_the_line_and_carets_under_the_span() -> None:
    assert text((sample.RN101,), show_source=True).splitlines()[1:] == [
        '      <node name="base-driver" pkg="base_driver" type="driver_node"/>',
        "    " + " " * 14 + "^" + "~" * 10,
    ]


def test_snapshot_with_source() -> None:
    check_snapshot("expected.txt", text(show_source=True))


def test_tabs_are_expanded_alike_in_both_lines() -> None:
    shown, carets = excerpt(sample.RN401.source_line, sample.RN401.span, Severity.WARNING)
    assert "\t" not in shown and "\t" not in carets
    start = carets.index("^")
    assert shown[start : start + len('"/cmd_vel"')] == '"/cmd_vel"'
    assert carets.strip() == "^" + "~" * 9


def test_wide_characters_take_two_cells() -> None:
    shown, carets = excerpt(
        sample.RN202_UNICODE.source_line, sample.RN202_UNICODE.span, Severity.WARNING
    )
    # three CJK characters (two cells each) precede the literal, which is 12 code points long
    assert carets == "    " + " " * (6 + 19) + "^" + "~" * 11
    assert shown == '    机械臂 = rospy.Publisher("/bras/état", Twist)'


def test_multi_line_spans_are_clipped_at_the_end_of_the_line() -> None:
    _, carets = excerpt('  name: "a\n', Span(3, 9, 4, 2), Severity.ERROR)
    assert carets == "    " + " " * 8 + "^~"


def test_a_span_past_the_end_of_the_line_gets_one_caret() -> None:
    _, carets = excerpt("abc\n", Span(1, 10, 1, 12), Severity.ERROR)
    assert carets == "    " + "   " + "^"
    _, carets = excerpt("abc\n", Span(1, 2, 1, 2), Severity.ERROR)
    assert carets == "    " + " " + "^"


def test_without_a_source_line_show_source_prints_just_the_finding() -> None:
    diagnostic = replace(sample.RN101, source_line=None)
    assert text((diagnostic,), show_source=True) == text((diagnostic,))


def test_summary_counts_problems_by_severity_and_the_files_they_are_in() -> None:
    """Before, 'in 12 files' counted the files checked, which read as files with problems."""
    assert summary(sample.DIAGNOSTICS, 12) == (
        "Found 4 problems (1 error, 3 warnings) in 3 files (12 files checked)."
    )
    assert summary((sample.RN101,), 1) == "Found 1 problem (1 error) in 1 file (1 file checked)."
    assert (
        summary((sample.RN401, sample.RN202_UNICODE), 3)
        == "Found 2 problems (2 warnings) in 2 files (3 files checked)."
    )


def test_summary_when_all_is_well() -> None:
    assert summary((), 12) == "All checks passed: 12 files checked, no problems."
    assert summary((sample.RN101_SUPPRESSED,), 1) == (
        "All checks passed: 1 file checked, no problems."
    )


def test_statistics_most_frequent_first_then_by_code() -> None:
    extra = replace(sample.RN202_UNICODE, span=Span(9, 1, 9, 5))
    diagnostics = (*sample.DIAGNOSTICS, extra, replace(extra, span=Span(10, 1, 10, 5)))
    assert statistics(diagnostics, sample.RULES) == (
        "3\tRN202\thard-coded-absolute-name\n"
        "1\tRN101\tillegal-name\n"
        "1\tRN203\tnot-snake-case\n"
        "1\tRN401\tcase-collision\n"
    )


def test_statistics_align_counts_and_skip_suppressed() -> None:
    many = tuple(replace(sample.RN401, span=Span(n, 1, n, 2)) for n in range(1, 11))
    assert statistics((*many, sample.RN101, sample.RN101_SUPPRESSED), sample.RULES) == (
        "10\tRN401\tcase-collision\n 1\tRN101\tillegal-name\n"
    )
    assert statistics((), sample.RULES) == ""
