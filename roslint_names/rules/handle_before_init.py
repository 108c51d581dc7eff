"""RN301 handle-before-init: a node handle or node built before the runtime is initialised.

roscpp aborts ("You must call ros::init() before creating the first NodeHandle"), rclcpp
and rclpy throw. rospy is the lenient one: it lets topics be created before ``init_node``,
but a service or service proxy made then ignores the launch file's remaps and a ``~private``
name fails or lands under ``/unnamed``; the Python extractor emits only those as handles. A
global or static object is built before ``main()`` runs, so no init can come first; inside
one function the statement order decides.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..model import EventKind, FileFacts, Finding, RuntimeEvent, Severity
from ..rule import Rule, RuleContext


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    first_init: dict[str, RuntimeEvent] = {}
    for event in sorted(facts.events, key=lambda event: event.order):
        if event.kind is EventKind.INIT:
            first_init.setdefault(event.scope, event)
    for event in facts.events:
        if event.kind is not EventKind.HANDLE:
            continue
        if event.static_storage:
            yield Finding(
                event.span,
                f"{event.api} is built before main() runs, so before any init call; "
                "create it in main() after init (or hold it by pointer and create it there)",
            )
            continue
        init = first_init.get(event.scope)
        if init is not None and init.order > event.order:
            yield Finding(
                event.span,
                f"{event.api} is created before {init.api} (line {init.span.line}); "
                "initialise first",
            )


RULE = Rule(
    code="RN301",
    name="handle-before-init",
    summary="A node handle, node or endpoint created before the ROS runtime is initialised",
    severity=Severity.ERROR,
    check=check,
)
