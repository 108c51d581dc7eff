"""RN202 hard-coded-absolute-name: an absolute literal handed to an endpoint API in code.

An absolute name escapes the node's namespace: ``<group ns="robot1">`` and ``__ns:=`` no
longer separate robots, and two of them fight over one topic. Launch files and URDF are
not judged: there an absolute name is a deliberate wiring decision made where the robot
is assembled, not a default baked into a reusable node.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..model import ENDPOINT_ROLES, FileFacts, Finding, Fix, Kind, Severity
from ..names import is_valid
from ..rule import Rule, RuleContext
from .common import in_code, label, static_uses

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
    allowed = set(_names(context.options.get("allow", GLOBAL_BY_DESIGN)))
    allowed.update(_names(context.options.get("extend-allow", ())))
    for use in static_uses(facts):
        if (
            not in_code(use, facts)
            or use.role not in ENDPOINT_ROLES
            or use.kind not in _ENDPOINT_KINDS
            or not use.value.startswith("/")
            or use.value in allowed
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
        )


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
)
