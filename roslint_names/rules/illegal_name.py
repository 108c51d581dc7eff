"""RN101 illegal-name: a name the ROS runtime of its generation rejects.

The namespace of a child handle, ``ros::NodeHandle(parent, "2")``, is judged as roscpp
judges it: joined to the parent's namespace. The constructor calls
``NodeHandle::construct(ns, false)``, which skips validating ``ns`` alone and resolves it
through ``NodeHandle::resolveName(ns, true, no_validate())``: appended to the parent's
namespace, which roscpp always holds resolved (absolute), and then validated whole by
``names::resolve`` (``names::validate``) (ros/ros_comm, ``clients/roscpp/src/libros/
node_handle.cpp`` and ``names.cpp``). The joined name starts with '/', so the child's
first character is never judged as a first character; a character illegal anywhere
('-', '!', ' ') still is, whatever the parent.

An empty frame in a launch file is a parameter's value (``<param name="fixed_frame"
value="$(arg fixed_frame)"/>`` with the argument defaulting to ""), and a parameter
holding "" is unset: what that means is the node's choice (velodyne_pointcloud's
``DataContainerBase`` reads an empty ``fixed_frame`` as "use the sensor frame"). It is
not judged as a name; an empty frame handed to tf2 in code (``lookupTransform("", ...)``)
still is (``BufferCore::validateFrameId``: "frame_ids cannot be empty").
"""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Fix, Generation, Kind, Language, NameUse, Severity
from ..names import Problem, check_name
from ..rule import Rule, RuleContext
from .common import decision, fix_hint, grammar_problems, label, suggested_fix


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    ros = f"ROS {facts.generation.value}"
    for use, problem in grammar_problems(facts, RULE.code):
        if _legal_once_joined(use, facts.generation) or _unset_parameter(use, facts):
            continue
        message = f"{label(use)} '{use.value}' {problem.reason} ({ros}){fix_hint(problem)}"
        fix = _private_name_fix(use, problem, facts) or _separator_fix(use, problem)
        yield Finding(use.span, message, fix=fix, decision=decision(use, facts))


# The API the C++ extractor names on a child handle's namespace (extract/cpp/handles.py's
# CHILD_HANDLE_API; not imported: a rule must not import the C++ parser).
_CHILD_HANDLE_API = "ros::NodeHandle(parent, ns)"


def _legal_once_joined(use: NameUse, generation: Generation) -> bool:
    """A child handle's relative namespace that is legal joined to any parent namespace:
    roscpp validates only the joined, absolute name (module docstring)."""
    if use.api != _CHILD_HANDLE_API or use.value.startswith(("/", "~")):
        return False
    return check_name(f"/{use.value}", use.kind, generation) is None


# Launch files hand frames to nodes only as parameter values (``<param value>``,
# ``parameters=``, ``-p name:=value``): they look up no transform themselves.
_LAUNCH_LANGUAGES = frozenset({Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.LAUNCH_PYTHON})


def _unset_parameter(use: NameUse, facts: FileFacts) -> bool:
    """An empty frame parameter in a launch file: "" means unset (module docstring)."""
    return use.kind is Kind.FRAME and not use.value and facts.language in _LAUNCH_LANGUAGES


def _separator_fix(use: NameUse, problem: Problem) -> Fix | None:
    """A node or topic name with '-' or ' ' where '_' belongs: unsafe, since every other
    use of the name (a launch file, another node) must be renamed with it."""
    if use.kind not in (Kind.NODE, Kind.TOPIC) or problem.suggestion is None:
        return None
    if problem.suggestion != use.value.replace("-", "_").replace(" ", "_"):
        return None
    return suggested_fix(use, problem, safe=False)


def _private_name_fix(use: NameUse, problem: Problem, facts: FileFacts) -> Fix | None:
    """ROS 2 ``~name`` to ``~/name``: rcl refuses ``~name`` (or, for two characters, makes
    it ``<ns>/<node>a``, a name nobody meant), so the fix is safe."""
    value = use.value
    if (
        facts.generation is Generation.ROS2
        and value.startswith("~")
        and not value.startswith("~/")
        and problem.suggestion == f"~/{value[1:]}"
    ):
        return suggested_fix(use, problem, safe=True)
    return None


RULE = Rule(
    code="RN101",
    name="illegal-name",
    summary="A name the ROS runtime rejects for its kind and generation",
    severity=Severity.ERROR,
    check=check,
)
