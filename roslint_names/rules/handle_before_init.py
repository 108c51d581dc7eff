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

from ..model import EventKind, FileFacts, Finding, RuntimeEvent, Severity, Span
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
                deployment_only=_misses_remaps_only(event, facts),
            )


_LENIENT = frozenset({"rospy.Service", "rospy.ServiceProxy"})


def _misses_remaps_only(event: RuntimeEvent, facts: FileFacts) -> bool:
    """A rospy service or proxy of a name that is not private, made before
    ``init_node``: it works, resolved in the root namespace without the launch file's
    remaps (``rospy.names.resolve_name`` before ``initialize_mappings``). A test or an
    example runs it as written: ros_comm's test_service_order.py does so on purpose."""
    if event.api not in _LENIENT:
        return False
    # The first name of that API after the call's name: its first argument (spans order
    # by where they start).
    end = event.span.end_line, event.span.end_column
    after = Span(*end, *end)
    name = min(
        (use for use in facts.names if use.api == event.api and use.span >= after),
        key=lambda use: use.span,
        default=None,
    )
    return name is not None and not name.value.startswith("~")


RULE = Rule(
    code="RN301",
    name="handle-before-init",
    summary="A node handle, node or endpoint created before the ROS runtime is initialised",
    severity=Severity.ERROR,
    check=check,
)
