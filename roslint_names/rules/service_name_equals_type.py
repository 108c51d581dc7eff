"""RN204 service-name-equals-type: a service named like a type, or after the wrong one.

Two mistakes, both seen in real code: a service spelled as its type (``"SetBool"``), which
says what it carries instead of what it does; and a service whose name is the snake_case
of a different type than it serves or calls (``/set_bool`` with ``std_srvs/Trigger``),
usually left over after the type changed, and a trap for every client written against
the name. Option ``strict`` also reports a name equal to its own type (``add_two_ints``
served with ``AddTwoInts``): half of real services follow that convention, so it is off
by default.
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import lru_cache

from ..model import FileFacts, Finding, Generation, Kind, NameUse, Role, Severity
from ..names import is_valid, snake_case, tokens
from ..rule import Rule, RuleContext
from ..types import InterfaceType, parse_type
from .common import chosen_here, spelled_as_type, static_uses

# Service types every ROS developer meets, per generation, so a name after one of them is
# recognised even when the file does not use that type. A ROS 1 service is never named
# after a ROS 2-only type (roscpp's tutorial serves `add_two_ints` with TwoInts, long before
# example_interfaces/AddTwoInts existed). Only multi-word names count: a service called
# "reset" or "spawn" is named after what it does, not after std_srvs/Empty or turtlesim/Spawn.
_BOTH = (
    "std_srvs/SetBool",
    "std_srvs/Trigger",
    "std_srvs/Empty",
    "nav_msgs/GetMap",
    "nav_msgs/GetPlan",
    "nav_msgs/SetMap",
    "nav_msgs/LoadMap",
    "turtlesim/SetPen",
    "turtlesim/TeleportAbsolute",
    "turtlesim/TeleportRelative",
    "controller_manager_msgs/SwitchController",
    "controller_manager_msgs/LoadController",
    "controller_manager_msgs/ListControllers",
    "robot_localization/SetPose",
    "robot_localization/SetDatum",
    "sensor_msgs/SetCameraInfo",
    "moveit_msgs/GetPositionIK",
    "moveit_msgs/GetPositionFK",
    "moveit_msgs/GetMotionPlan",
)
_ROS1_ONLY = (
    "gazebo_msgs/SpawnModel",
    "gazebo_msgs/DeleteModel",
    "gazebo_msgs/GetModelState",
    "gazebo_msgs/SetModelState",
)
_ROS2_ONLY = (
    "example_interfaces/AddTwoInts",
    "lifecycle_msgs/ChangeState",
    "lifecycle_msgs/GetState",
    "rcl_interfaces/GetParameters",
    "rcl_interfaces/SetParameters",
    "rcl_interfaces/ListParameters",
    "rcl_interfaces/DescribeParameters",
    "gazebo_msgs/SpawnEntity",
    "gazebo_msgs/DeleteEntity",
    "gazebo_msgs/GetEntityState",
    "gazebo_msgs/SetEntityState",
)
WELL_KNOWN_SERVICE_TYPES: dict[Generation, tuple[InterfaceType, ...]] = {
    generation: tuple(InterfaceType(*spelling.split("/")) for spelling in spellings)
    for generation, spellings in (
        (Generation.ROS1, _BOTH + _ROS1_ONLY),
        (Generation.ROS2, _BOTH + _ROS2_ONLY),
    )
}
_SERVICE_ROLES = frozenset({Role.SERVE, Role.CALL})


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    strict = bool(context.options.get("strict", False))
    services = [
        use
        for use in static_uses(facts)
        if use.kind is Kind.SERVICE
        and use.role in _SERVICE_ROLES
        and is_valid(use.value, use.kind, facts.generation)
    ]
    if not services:
        return  # nearly every file: do not even gather the types of the run
    known = _known_types(services, facts.generation, context.known_service_types)
    for use in services:
        name_tokens = tokens(use.value, use.kind)
        if not name_tokens:
            continue
        last = name_tokens[-1]
        if spelled_as_type(use) and chosen_here(use, facts):
            yield Finding(
                use.span,
                f"service '{use.value}' is spelled like a type ('{last}'); "
                "name it after what it does, in snake_case",
            )
            continue
        own = parse_type(use.type_name) if use.type_name else None
        if own is None:
            continue
        own_name = snake_case(own.name)
        if last == own_name:
            if strict:
                yield Finding(use.span, f"service '{use.value}' is named after its own type {own}")
            continue
        if last.endswith("_" + own_name):
            continue  # a verb and its own type ('add' + 'two_ints' with TwoInts)
        for other, other_name in known:
            if other.name != own.name and "_" in other_name and last == other_name:
                yield Finding(use.span, _wrong_type_message(use, own, other))
                break


def _known_types(
    services: list[NameUse], generation: Generation, of_the_run: frozenset[str]
) -> tuple[tuple[InterfaceType, str], ...]:
    """Every type a service could be named after, with its snake_case name, sorted."""
    known = _run_types(generation, of_the_run)
    own = {parsed for use in services if use.type_name and (parsed := parse_type(use.type_name))}
    extra = own - _run_type_set(generation, of_the_run)
    if not extra:  # the usual case: the run's types include the file's own
        return known
    return _with_names(*(known_type for known_type, _ in known), *extra)


@lru_cache(maxsize=32)
def _run_types(
    generation: Generation, of_the_run: frozenset[str]
) -> tuple[tuple[InterfaceType, str], ...]:
    """The run's service types and the well-known ones, parsed, named and sorted once per
    run, not once per file: a large workspace has a thousand."""
    parsed = {found for spelling in of_the_run if (found := parse_type(spelling))}
    return _with_names(*parsed, *WELL_KNOWN_SERVICE_TYPES[generation])


@lru_cache(maxsize=32)
def _run_type_set(generation: Generation, of_the_run: frozenset[str]) -> frozenset[InterfaceType]:
    """The types of ``_run_types``, as a set: built once per run, not once per file."""
    return frozenset(known_type for known_type, _ in _run_types(generation, of_the_run))


def _with_names(*types: InterfaceType) -> tuple[tuple[InterfaceType, str], ...]:
    return tuple(sorted(((found, _snake_name(found.name)) for found in set(types)), key=_by_text))


@lru_cache(maxsize=4096)
def _snake_name(name: str) -> str:
    """``snake_case`` of a type's name, once per name: the types of a run are named again
    for each set of packages a file can see (one list per set), a thousand names each."""
    return snake_case(name)


def _by_text(item: tuple[InterfaceType, str]) -> str:
    return str(item[0])


def _wrong_type_message(use: NameUse, own: InterfaceType, other: InterfaceType) -> str:
    if use.role is Role.SERVE:
        return (
            f"service '{use.value}' is served with {own} but named after {other}; "
            "rename it after what it does"
        )
    # A client uses the name its server chose: what it can fix is the type it calls with.
    return (
        f"service '{use.value}' is called with {own} but named after {other}; "
        f"check that the server serves {own}"
    )


RULE = Rule(
    code="RN204",
    name="service-name-equals-type",
    summary="A service named like a type, or after a different type than it serves",
    severity=Severity.WARNING,
    check=check,
    options={"strict": False},
    judges_test_code=False,
)
