"""RN203 not-snake-case: a name token that is not lower snake_case.

Frame ids are left out: URDF link names follow the robot's own conventions (``FL_hip``),
and tf2 does not care.

A project whose names are CamelCase by design states it once: ``ignore-names`` (ruff's
pep8-naming option of that name, for ROS names) lists glob patterns, ``*`` for any
characters. image_pipeline names its component nodes ``DebayerNode``,
``PointCloudXyzNode``...: ``ignore-names = ["*Node"]``. Each finding answers with the
name that would silence it, and ``conventions`` proposes the list where a package has
many.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from functools import lru_cache

from ..model import Answer, FileFacts, Finding, Fix, Generation, Kind, NameUse, Severity
from ..names import check_name, is_snake_case, rename_tokens, snake_case, tokens
from ..rule import OptionValue, Rule, RuleContext
from .common import chosen_here, decision, label, spelled_as_type, static_uses

# Last tokens that ROS packages spell themselves, so no author can choose another spelling:
# image_transport names a subtopic after its transport plugin (`image_raw/compressedDepth`).
TRANSPORT_SUFFIXES = frozenset({"compressedDepth"})

IGNORE_NAMES = "ignore-names"
SETTING = f"rules.RN203.{IGNORE_NAMES}"  # what a finding's answer names
# A pattern holds a name's characters (a '{substitution}' too) and '*'. Other glob syntax
# ('?', '[...]') is refused, not taken literally: it would silently match nothing.
_PATTERN = re.compile(r"[A-Za-z0-9_/~.{}*]+")


_PLUGIN_SCOPES = frozenset({Kind.NAMESPACE, Kind.PARAMETER})


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    ignored = _ignored(_patterns(context.options.get(IGNORE_NAMES, ())))
    written = {(use.kind, use.value) for use in static_uses(facts)}
    for use in static_uses(facts):
        if use.kind is Kind.FRAME or not chosen_here(use, facts):
            continue
        problem = check_name(use.value, use.kind, facts.generation)
        if problem is not None and problem.fatal:
            continue  # RN101 / RN102 report it; one problem, one finding
        name_tokens = tokens(_own_part(use, facts), use.kind)
        if name_tokens and (name_tokens[-1] in TRANSPORT_SUFFIXES or spelled_as_type(use)):
            name_tokens = name_tokens[:-1]  # image_transport's spelling; RN204's finding
        # A plugin's name where pluginlib gives it, a namespace of the parameters a plugin
        # reads (``~/TrajectoryPlannerROS``), is its class's: not chosen here. A node or a
        # topic named like the class is the writer's choice.
        plugins = context.plugin_names if use.kind in _PLUGIN_SCOPES else frozenset()
        bad = [token for token in name_tokens if not is_snake_case(token) and token not in plugins]
        if not bad or (ignored is not None and _covered(ignored, use.value, bad)):
            continue
        quoted = ", ".join(f"'{token}'" for token in bad)
        renamed = tuple((token, snake_case(token)) for token in dict.fromkeys(bad))
        fixed = rename_tokens(use.value, dict(renamed))
        if (use.kind, fixed) in written:
            # The file reads the snake_case spelling too: the other is an alias kept for
            # old configurations (amcl reads ``beam_skip_error_threshold_`` only where
            # ``hasParam`` says a user still sets it), a decision already made.
            continue
        yield Finding(
            use.span,
            f"{label(use)} '{use.value}' is not lower snake_case ({quoted}); use '{fixed}'",
            # Unsafe: a renamed parameter or node is a changed interface, and only the
            # workspace's uses of it are known (``renames``).
            fix=Fix(use.value, fixed, safe=False, tokens=renamed)
            if all(new for _, new in renamed)
            else None,
            answer=_answer(use, bad),
            decision=decision(use, facts),
        )


def _answer(use: NameUse, bad: list[str]) -> Answer:
    """The ``ignore-names`` entry that would silence the finding: its one CamelCase token
    (``DebayerNode``, gmapping's ``minimumScore``), else the whole name."""
    distinct = list(dict.fromkeys(bad))
    return Answer(SETTING, distinct[0] if len(distinct) == 1 else use.value, use.kind)


def _covered(ignored: re.Pattern[str], value: str, bad: list[str]) -> bool:
    """Whether ``ignore-names`` covers the name: the whole of it, or each of its tokens
    that is not snake_case."""
    return bool(ignored.fullmatch(value)) or all(ignored.fullmatch(token) for token in bad)


@lru_cache(maxsize=8)  # one configuration per run: compiled once, not once per file
def _ignored(patterns: tuple[str, ...]) -> re.Pattern[str] | None:
    if not patterns:
        return None
    return re.compile("|".join(_regex(pattern) for pattern in patterns))


def _regex(pattern: str) -> str:
    return "(?:" + ".*".join(re.escape(part) for part in pattern.split("*")) + ")"


def _patterns(option: OptionValue) -> tuple[str, ...]:
    return tuple(option) if isinstance(option, tuple | list) else ()


def pattern_error(pattern: str) -> str | None:
    """Why an ``ignore-names`` pattern is refused, or None."""
    if not _PATTERN.fullmatch(pattern):
        return f"invalid pattern {pattern!r}: a name's characters, with '*' for any characters"
    if not pattern.strip("*"):
        return f"pattern {pattern!r} matches every name; to turn RN203 off, ignore it"
    return None


def option_error(option: str, value: OptionValue) -> str | None:
    if option != IGNORE_NAMES:
        return None
    for pattern in _patterns(value):
        reason = pattern_error(pattern)
        if reason is not None:
            return reason
    return None


def _own_part(use: NameUse, facts: FileFacts) -> str:
    """The part of the name this rule judges.

    A ROS 2 parameter's ``.``-separated prefix names the instance it belongs to, chosen
    where that instance is configured: navigation2's plugin ids (``FollowPath``,
    ``SmoothPath``) come from the parameter file's plugin list, so ``SmoothPath.w_smooth``
    is judged by its own token, ``w_smooth``.
    """
    if use.kind is Kind.PARAMETER and facts.generation is Generation.ROS2:
        return use.value.rpartition(".")[2]
    return use.value


RULE = Rule(
    code="RN203",
    name="not-snake-case",
    summary="A name token that is not lower snake_case",
    severity=Severity.WARNING,
    check=check,
    options={IGNORE_NAMES: ()},
    option_error=option_error,
    judges_test_code=False,
    reads_plugins=True,
)
