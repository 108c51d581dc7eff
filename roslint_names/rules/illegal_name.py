"""RN101 illegal-name: a name the ROS runtime of its generation rejects."""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Fix, Generation, Kind, NameUse, Severity
from ..names import Problem
from ..rule import Rule, RuleContext
from .common import fix_hint, grammar_problems, label, suggested_fix


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    ros = f"ROS {facts.generation.value}"
    for use, problem in grammar_problems(facts, RULE.code):
        message = f"{label(use)} '{use.value}' {problem.reason} ({ros}){fix_hint(problem)}"
        fix = _private_name_fix(use, problem, facts) or _separator_fix(use, problem)
        yield Finding(use.span, message, fix=fix)


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
