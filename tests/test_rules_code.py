"""RN202, RN204 and RN301 on hand-built facts: the rules alone, whatever extractor feeds them."""

from __future__ import annotations

from roslint_names.model import (
    EventKind,
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    Role,
    RuntimeEvent,
    Span,
)
from roslint_names.rule import RuleContext
from roslint_names.rules import handle_before_init, hard_coded_absolute_name
from roslint_names.rules import service_name_equals_type as rn204

ADVERTISE = "ros::NodeHandle::advertise"


def span(line: int) -> Span:
    return Span(line, 5, line, 15)


def use(value: str, role: Role, kind: Kind = Kind.TOPIC, **fields: object) -> NameUse:
    return NameUse(kind, value, span(len(value)), role, api=ADVERTISE, **fields)  # type: ignore[arg-type]


def facts(*names: NameUse, language: Language = Language.CPP, **fields: object) -> FileFacts:
    return FileFacts(
        "src/node.cpp",
        language,
        Generation.ROS1,
        names=names,
        **fields,  # type: ignore[arg-type]
    )


def messages(check: object, file_facts: FileFacts, **options: object) -> list[str]:
    context = RuleContext(options=options)  # type: ignore[arg-type]
    return [finding.message for finding in check(file_facts, context)]  # type: ignore[operator]


def test_rn202_reports_absolute_endpoints_in_code_only() -> None:
    rn202 = hard_coded_absolute_name.check
    assert messages(rn202, facts(use("/cmd_vel", Role.PUBLISH))) == [
        "absolute topic '/cmd_vel' passed to ros::NodeHandle::advertise escapes the node's "
        "namespace, so <group ns> and __ns:= cannot separate robots; use 'cmd_vel'"
    ]
    assert messages(rn202, facts(use("cmd_vel", Role.PUBLISH))) == []
    assert messages(rn202, facts(use("/cmd_vel", Role.PARAMETER_DEFAULT))) == []
    assert messages(rn202, facts(use("/cmd_vel", Role.PUBLISH, dynamic=True))) == []
    assert messages(rn202, facts(use("/cmd_vel", Role.REMAP_TO))) == []
    launch = facts(use("/cmd_vel", Role.PUBLISH), language=Language.LAUNCH_PYTHON)
    assert messages(rn202, launch) == []


def test_rn202_ros1_topic_statistics_are_global_by_design() -> None:
    # Found over ros_comm: roscpp and rospy publish topic statistics on /statistics.
    rn202 = hard_coded_absolute_name.check
    assert messages(rn202, facts(use("/statistics", Role.PUBLISH))) == []


def test_rn202_allow_lists() -> None:
    rn202 = hard_coded_absolute_name.check
    file_facts = facts(use("/tf", Role.PUBLISH), use("/joy", Role.SUBSCRIBE))
    assert len(messages(rn202, file_facts, allow=hard_coded_absolute_name.GLOBAL_BY_DESIGN)) == 1
    assert messages(rn202, file_facts, **{"extend-allow": ("/joy",)}) == []
    assert len(messages(rn202, file_facts, allow=("/joy",))) == 1  # /tf no longer allowed


def test_rn202_allow_patterns_name_global_trees() -> None:
    """autoware's /api/** and moveit's /rviz/moveit/* are global interfaces by design."""
    rn202 = hard_coded_absolute_name.check
    file_facts = facts(
        use("/api/autoware/get/engage", Role.CALL, Kind.SERVICE),
        use("/rviz/moveit/update_goal_state", Role.SUBSCRIBE),
        use("/rviz/moveit/move_marker/goal", Role.SUBSCRIBE),
        use("/apis", Role.PUBLISH),
    )
    allowed = {"extend-allow": ("/api/**", "/rviz/moveit/*")}
    assert messages(rn202, file_facts, **allowed) == [
        "absolute topic '/rviz/moveit/move_marker/goal' passed to ros::NodeHandle::advertise "
        "escapes the node's namespace, so <group ns> and __ns:= cannot separate robots; "
        "use 'rviz/moveit/move_marker/goal'",
        "absolute topic '/apis' passed to ros::NodeHandle::advertise escapes the node's "
        "namespace, so <group ns> and __ns:= cannot separate robots; use 'apis'",
    ]


def service(value: str, type_name: str | None, role: Role = Role.SERVE) -> NameUse:
    return use(value, role, Kind.SERVICE, type_name=type_name)


def test_rn204_spelled_as_type() -> None:
    assert messages(rn204.check, facts(service("SetBool", "std_srvs/SetBool"))) == [
        "service 'SetBool' is spelled like a type ('SetBool'); "
        "name it after what it does, in snake_case"
    ]


def test_rn204_named_after_another_type() -> None:
    found = messages(rn204.check, facts(service("/set_bool", "std_srvs::srv::Trigger")))
    assert found == [
        "service '/set_bool' is served with std_srvs/Trigger but named after "
        "std_srvs/SetBool; rename it after what it does"
    ]
    # A type the file itself uses counts as well as the well-known ones.
    file_facts = facts(
        service("dock_robot", "docking_msgs/srv/DockRobot"),
        service("dock_robot", "std_srvs/Trigger", Role.CALL),
    )
    assert messages(rn204.check, file_facts) == [
        "service 'dock_robot' is called with std_srvs/Trigger but named after "
        "docking_msgs/DockRobot; check that the server serves std_srvs/Trigger"
    ]


def test_rn204_own_type_only_when_strict_and_single_words_never() -> None:
    own = facts(service("add_two_ints", "rospy_tutorials.srv.AddTwoInts"))
    assert messages(rn204.check, own) == []
    assert len(messages(rn204.check, own, strict=True)) == 1
    assert messages(rn204.check, facts(service("empty", "std_srvs/Trigger"))) == []
    assert messages(rn204.check, facts(service("set_bool", None))) == []


def event(kind: EventKind, api: str, line: int, scope: str, **fields: object) -> RuntimeEvent:
    return RuntimeEvent(kind, api, span(line), scope, order=line, **fields)  # type: ignore[arg-type]


def test_rn301_static_storage_and_statement_order() -> None:
    events = (
        event(EventKind.HANDLE, "ros::NodeHandle", 4, "", static_storage=True),
        event(EventKind.HANDLE, "ros::NodeHandle", 8, "main@6"),
        event(EventKind.INIT, "ros::init", 9, "main@6"),
        event(EventKind.HANDLE, "ros::NodeHandle", 10, "main@6"),
        event(EventKind.HANDLE, "ros::NodeHandle", 20, "helper@19"),  # no init there
    )
    assert messages(handle_before_init.check, facts(events=events)) == [
        "ros::NodeHandle is built before main() runs, so before any init call; create it in "
        "main() after init (or hold it by pointer and create it there)",
        "ros::NodeHandle is created before ros::init (line 9); initialise first",
    ]


def ros1(*names: NameUse) -> FileFacts:
    return facts(*names)


def ros2(*names: NameUse) -> FileFacts:
    return FileFacts("src/node.cpp", Language.CPP, Generation.ROS2, names=names)


def test_rn204_well_known_types_belong_to_their_generation() -> None:
    # Found over ros_tutorials and navigation: ROS 1's roscpp tutorial serves add_two_ints
    # with roscpp_tutorials/TwoInts, and dynamic_reconfigure serves set_parameters;
    # example_interfaces/AddTwoInts and rcl_interfaces/SetParameters are ROS 2 types.
    assert messages(rn204.check, ros1(service("add_two_ints", "roscpp_tutorials::TwoInts"))) == []
    reconfigure = service("set_parameters", "dynamic_reconfigure::Reconfigure")
    assert messages(rn204.check, ros1(reconfigure)) == []
    assert len(messages(rn204.check, ros2(service("add_two_ints", "std_srvs/srv/Trigger")))) == 1
    assert len(messages(rn204.check, ros1(service("set_bool", "std_srvs::Trigger")))) == 1


def test_rn204_knows_the_workspace_service_types() -> None:
    # A type defined by a .srv file of the workspace, or used by another file of the run,
    # counts like a well-known one: `start_docking` served with Trigger is named after it.
    docking = facts(service("start_docking", "std_srvs::srv::Trigger"))
    assert messages(rn204.check, docking) == []
    context = RuleContext(known_service_types=frozenset({"docking_msgs/StartDocking"}))
    found = [finding.message for finding in rn204.check(docking, context)]
    assert found == [
        "service 'start_docking' is served with std_srvs/Trigger but named after "
        "docking_msgs/StartDocking; rename it after what it does"
    ]


def test_rn204_a_name_ending_in_its_own_type_is_named_after_it() -> None:
    # Found over ros_tutorials: roscpp serves add_two_ints with roscpp_tutorials/TwoInts
    # while rospy_tutorials/AddTwoInts.srv sits in the same workspace. 'add' + 'two_ints'
    # names the service after its own type, with a verb; it is not named after AddTwoInts.
    context = RuleContext(known_service_types=frozenset({"rospy_tutorials/AddTwoInts"}))
    tutorial = facts(service("add_two_ints", "roscpp_tutorials::TwoInts"))
    assert list(rn204.check(tutorial, context)) == []
    bad = facts(service("add_two_ints", "rospy_tutorials/BadTwoInts", Role.CALL))
    assert len(list(rn204.check(bad, context))) == 1
    strict = RuleContext(options={"strict": True})
    assert list(rn204.check(tutorial, strict)) == []  # strict is about equal names only


def test_rn202_reports_a_name_joined_from_an_absolute_literal() -> None:
    """autoware.core's ``"/planning/planning_factors/" + name``: dynamic, but certainly
    absolute; reported by its literal start, with no fix (the rest is not known)."""
    joined = use("", Role.PUBLISH, dynamic=True, absolute_prefix="/planning/planning_factors/")
    relative = use("", Role.PUBLISH, dynamic=True)  # "~/debug/" + name
    found = list(hard_coded_absolute_name.check(facts(joined, relative), RuleContext()))
    assert [(f.span, f.fix) for f in found] == [(joined.span, None)]
    assert "built from the absolute '/planning/planning_factors/'" in found[0].message
    # A global tree the project allows.
    for pattern in ("/planning/**", "/planning/planning_factors/*"):
        allowed = RuleContext(options={"extend-allow": [pattern]})
        assert list(hard_coded_absolute_name.check(facts(joined), allowed)) == []
