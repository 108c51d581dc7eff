"""RN203 not-snake-case: a name token that is not lower snake_case.

Frame ids are left out: URDF link names follow the robot's own conventions (``FL_hip``),
and tf2 does not care.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..model import FileFacts, Finding, Fix, Generation, Kind, NameUse, Severity
from ..names import check_name, is_snake_case, rename_tokens, snake_case, tokens
from ..rule import Rule, RuleContext
from .common import chosen_here, label, spelled_as_type, static_uses

# Last tokens that ROS packages spell themselves, so no author can choose another spelling:
# image_transport names a subtopic after its transport plugin (`image_raw/compressedDepth`).
TRANSPORT_SUFFIXES = frozenset({"compressedDepth"})


def check(facts: FileFacts, context: RuleContext) -> Iterator[Finding]:
    for use in static_uses(facts):
        if use.kind is Kind.FRAME or not chosen_here(use, facts):
            continue
        problem = check_name(use.value, use.kind, facts.generation)
        if problem is not None and problem.fatal:
            continue  # RN101 / RN102 report it; one problem, one finding
        name_tokens = tokens(_own_part(use, facts), use.kind)
        if name_tokens and (name_tokens[-1] in TRANSPORT_SUFFIXES or spelled_as_type(use)):
            name_tokens = name_tokens[:-1]  # image_transport's spelling; RN204's finding
        bad = [token for token in name_tokens if not is_snake_case(token)]
        if not bad:
            continue
        quoted = ", ".join(f"'{token}'" for token in bad)
        renamed = tuple((token, snake_case(token)) for token in dict.fromkeys(bad))
        fixed = rename_tokens(use.value, dict(renamed))
        yield Finding(
            use.span,
            f"{label(use)} '{use.value}' is not lower snake_case ({quoted}); use '{fixed}'",
            # Unsafe: a renamed parameter or node is a changed interface, and only the
            # workspace's uses of it are known (``renames``).
            fix=Fix(use.value, fixed, safe=False, tokens=renamed)
            if all(new for _, new in renamed)
            else None,
        )


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
    judges_test_code=False,
)
