"""RN202 hard-coded-absolute-name: an absolute literal handed to an endpoint API in code.

An absolute name escapes the node's namespace: ``<group ns="robot1">`` and ``__ns:=`` no
longer separate robots, and two of them fight over one topic. Launch files and URDF are
not judged: there an absolute name is a deliberate wiring decision made where the robot
is assembled, not a default baked into a reusable node.

A name joined at run time from an absolute literal (``"/planning/planning_factors/" +
name``) is as certainly absolute (``NameUse.absolute_prefix``): it is reported by that
literal, without a fix, since the rest of the name is not known.

A name the workspace's launch files remap a node to (``RuleContext.wired_names``) is one of
the system's global interfaces, chosen where the system is assembled: code that writes it
follows that choice, and is left alone. For a prefix, a wired name it starts will do. So
is a name under a first level the launch files wire many names into (``wiring.
wired_trees``: Autoware's ``/map/map_projector_info`` beside the ``/map/...`` remaps).

A file that writes every endpoint name absolute binds its node to the root namespace by
design (moveit_joy's ``/joy``, ``/joy_pose`` and RViz's marker topic; a Gazebo plugin
standing in for PR2's projector controller): that is one decision, reported once at its
first name with the others related (``Decision.bound``), not once per name. A relative or
private ``~`` name makes the file not bound; a name built at run time from no literal
start says nothing either way (moveit_joy's end-effector topics, read from the SRDF).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from dataclasses import replace

from ..model import ENDPOINT_ROLES, Answer, FileFacts, Finding, Fix, Kind, Severity
from ..names import is_valid
from ..rule import Rule, RuleContext
from ..wiring import in_wired_tree, wired_trees
from .common import decision, in_code, label, static_uses

GLOBAL_BY_DESIGN = (
    "/tf",
    "/tf_static",
    "/clock",
    "/rosout",
    "/rosout_agg",
    "/parameter_events",
    "/diagnostics",
    "/diagnostics_agg",
    "/statistics",  # ROS 1 topic statistics, published by roscpp and rospy themselves
)
_ENDPOINT_KINDS = frozenset({Kind.TOPIC, Kind.SERVICE, Kind.ACTION})


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    findings = list(_findings(facts, context))
    if len(findings) < 2 or not _bound_to_root(facts):
        yield from findings
        return
    for finding in findings:
        assert finding.decision is not None
        yield replace(finding, decision=replace(finding.decision, bound=True))


def _bound_to_root(facts: FileFacts) -> bool:
    """Whether every endpoint name the file's code writes, where its start is known, is
    absolute."""
    return all(
        use.value.startswith("/")
        for use in static_uses(facts)
        if in_code(use, facts) and use.role in ENDPOINT_ROLES and use.kind in _ENDPOINT_KINDS
    )


def _findings(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    allowed = _Allowed(
        (
            *_names(context.options.get("allow", GLOBAL_BY_DESIGN)),
            *_names(context.options.get("extend-allow", ())),
        )
    )
    trees = wired_trees(context.wired_names)
    yield from _joined_at_run_time(facts, allowed, context.wired_names, trees)
    for use in static_uses(facts):
        if (
            not in_code(use, facts)
            or use.role not in ENDPOINT_ROLES
            or use.kind not in _ENDPOINT_KINDS
            or not use.value.startswith("/")
            or allowed.covers(use.value)
            or use.value in context.wired_names
            or in_wired_tree(use.value, trees)
            or not is_valid(use.value, use.kind, facts.generation)
        ):
            continue
        relative = use.value.lstrip("/")
        yield Finding(
            use.span,
            f"absolute {label(use)} '{use.value}' passed to {use.api} escapes the node's "
            f"namespace, so <group ns> and __ns:= cannot separate robots; use '{relative}'",
            # Unsafe: under a namespace the name then resolves elsewhere, which is the
            # point, but whoever used the absolute name must follow.
            fix=Fix(use.value, relative, safe=False),
            answer=Answer(_SETTING, use.value),
            decision=decision(use, facts),
        )


_SETTING = "rules.RN202.extend-allow"


class _Allowed:
    """Names global by design: exact names, or patterns where ``*`` stands for one level
    and ``**`` for any number (``/api/**``, ``/rviz/moveit/*``)."""

    def __init__(self, entries: Iterable[str]) -> None:
        self._names = {entry for entry in entries if "*" not in entry}
        patterns = [entry for entry in entries if "*" in entry]
        self._pattern = re.compile("|".join(_regex(p) for p in patterns)) if patterns else None

    def covers(self, name: str) -> bool:
        return name in self._names or bool(self._pattern and self._pattern.fullmatch(name))


def _regex(pattern: str) -> str:
    parts = re.split(r"(\*\*|\*)", pattern)
    return (
        "(?:"
        + "".join(
            ".+" if part == "**" else "[^/]+" if part == "*" else re.escape(part) for part in parts
        )
        + ")"
    )


def _joined_at_run_time(
    facts: FileFacts, allowed: _Allowed, wired: frozenset[str], trees: frozenset[str]
) -> Iterator[Finding]:
    """Names built at run time whose absolute start is a literal: certain to escape."""
    for use in facts.names:
        prefix = use.absolute_prefix
        if (
            not use.dynamic
            or prefix is None
            or not in_code(use, facts)
            or use.role not in ENDPOINT_ROLES
            or use.kind not in _ENDPOINT_KINDS
            or allowed.covers(prefix + "x")  # a name it starts: "/api/**" covers "/api/"
            or _starts_wired(prefix, wired)
            or in_wired_tree(prefix, trees)
        ):
            continue
        yield Finding(
            use.span,
            f"{label(use)} built from the absolute '{prefix}' and passed to {use.api} "
            "escapes the node's namespace, so <group ns> and __ns:= cannot separate robots; "
            "drop the leading '/'",
            answer=Answer(_SETTING, prefix.rstrip("/") + "/**"),
            decision=decision(use, facts, prefix=prefix),
        )


def _starts_wired(prefix: str, wired: frozenset[str]) -> bool:
    """Whether ``prefix`` starts a wired name and fixes a whole level of it: ``"/"`` or
    ``"/plan"`` (gazebo_ros_harness' ``"/" + _parent->GetName()``) say nothing of which
    interface the name is."""
    return "/" in prefix[1:] and any(name.startswith(prefix) for name in wired)


def _names(option: object) -> tuple[str, ...]:
    return tuple(option) if isinstance(option, tuple | list) else ()


RULE = Rule(
    code="RN202",
    name="hard-coded-absolute-name",
    summary="An absolute name hard-coded in a publisher, subscriber, service or action call",
    severity=Severity.WARNING,
    check=check,
    options={"allow": GLOBAL_BY_DESIGN, "extend-allow": ()},
    judges_test_code=False,
    reads_wiring=True,
)
