"""Where an edit moved a file's places (``moves``): found from the facts alone, and never
guessed: a value that differs, or a place no fact starts at, is no move."""

from __future__ import annotations

import pytest

from roslint_names.model import (
    Diagnostic,
    EventKind,
    FileFacts,
    Finding,
    Generation,
    Kind,
    Language,
    NameUse,
    RelatedLocation,
    Role,
    RuntimeEvent,
    Severity,
    Span,
)
from roslint_names.moves import Moves, UnplacedError, moved_spans

MONITOR = "src/fleet/src/monitor.cpp"


def _facts(line: int, value: str = "robot_pose", order: int = 100) -> FileFacts:
    use = NameUse(Kind.TOPIC, value, Span(line, 67, line, 79), Role.PUBLISH, "create_publisher")
    init = RuntimeEvent(
        EventKind.INIT,
        "rclcpp::init",
        Span(line + 30, 3, line + 30, 27),
        f"main@{line + 28}",
        order,
    )
    return FileFacts(MONITOR, Language.CPP, Generation.ROS2, names=(use,), events=(init,))


def test_a_line_above_moves_every_span_and_the_event_s_offset_and_scope() -> None:
    spans = moved_spans(_facts(22), _facts(23, order=118))
    assert spans == {
        Span(22, 67, 22, 79): Span(23, 67, 23, 79),
        Span(52, 3, 52, 27): Span(53, 3, 53, 27),
    }


def test_a_changed_value_is_no_move() -> None:
    assert moved_spans(_facts(22), _facts(23, value="robot_pose_estimate")) is None


def test_a_fact_more_is_no_move() -> None:
    before = _facts(22)
    now = FileFacts(
        MONITOR, Language.CPP, Generation.ROS2, names=before.names * 2, events=before.events
    )
    assert moved_spans(before, now) is None


def _moves() -> Moves:
    spans = moved_spans(_facts(22), _facts(23))
    assert spans is not None
    return Moves(MONITOR, spans)


def test_a_kept_finding_of_the_file_and_its_places_in_messages_move() -> None:
    finding = Finding(
        Span(22, 67, 22, 79),
        f"topic '/robot_pose' differs only in case from '/Robot_Pose' (also at {MONITOR}:22:67)",
        related=(RelatedLocation(MONITOR, Span(22, 67, 22, 79), "topic '/robot_pose'"),),
    )
    moved = _moves().finding(finding, MONITOR)
    assert moved.span == Span(23, 67, 23, 79)
    assert moved.message.endswith(f"(also at {MONITOR}:23:67)")
    assert moved.related[0].span == Span(23, 67, 23, 79)


def test_another_file_s_finding_moves_only_its_places_in_the_edited_file() -> None:
    diagnostic = Diagnostic(
        "src/fleet/fleet/recorder.py",
        Span(12, 47, 12, 59),
        "RN401",
        "case-collision",
        Severity.WARNING,
        f"topic '/Robot_Pose' differs only in case from '/robot_pose' at {MONITOR}:22:67; "
        f"not at other/{MONITOR}:22:67",
        related=(RelatedLocation(MONITOR, Span(22, 67, 22, 79), "topic '/robot_pose'"),),
    )
    moved = _moves().diagnostic(diagnostic)
    assert moved.span == diagnostic.span
    assert f"at {MONITOR}:23:67;" in moved.message
    assert f"other/{MONITOR}:22:67" in moved.message  # a path that ends alike is another
    assert moved.related[0].span == Span(23, 67, 23, 79)


@pytest.mark.parametrize(
    "finding",
    [
        Finding(Span(22, 70, 22, 79), "a place inside the name, no fact's"),
        Finding(Span(22, 67, 22, 79), f"at {MONITOR}:22:70, where no fact starts"),
    ],
)
def test_a_place_no_fact_gives_is_refused(finding: Finding) -> None:
    with pytest.raises(UnplacedError):
        _moves().finding(finding, MONITOR)
