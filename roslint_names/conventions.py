"""A project's conventions, proposed: many findings that one line of configuration answers.

Autoware's topic tree is deep by design (38 RN201 findings on autoware_launch, all
answered by ``max-depth = 7``); MoveIt's ``/rviz/moveit/*`` topics are a global interface
by design (21 RN202 findings, answered by ``extend-allow = ["/rviz/moveit/**"]``). Such
findings are one decision, the project's, and the maintainer's answer is to state it,
or to fix the names: either way in one step. Rules say, finding by finding, which
setting would answer it (``Finding.answer``); this module groups those answers:

- ``max-depth``: proposed when at least ``MIN_DEEP`` findings would be answered by it,
  with the deepest level they need;
- RN202's ``extend-allow``: a tree (``/api/**``) proposed when at least ``MIN_TREE``
  findings name something in it; the tree is the levels all of them share;
- RN203's ``ignore-names``: proposed when one package has at least ``MIN_NAMES``
  distinct CamelCase names of one kind (image_pipeline's depth_image_proc names its ten
  component nodes ``DebayerNode``-style, gmapping has eight camelCase parameters). A few
  such names spread over packages among many snake_case ones (ros2/demos' ``Client``,
  ``TestNode``...) are slips, and stay findings. Names ending in one CamelCase word with
  at least ``MIN_SHARED - 1`` others are proposed as ``*Word``, the rest as they are.
"""

from __future__ import annotations

import json
import posixpath
import re
from collections import Counter, defaultdict
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass

from .model import Diagnostic, Kind

MIN_DEEP = 5
MIN_TREE = 3
MIN_NAMES = 5
MIN_SHARED = 3
_DEPTH = "max-depth"
_ALLOW = "rules.RN202.extend-allow"
_IGNORE_NAMES = "rules.RN203.ignore-names"
# The words of a CamelCase name: "PointCloudXyzNode" -> Point Cloud Xyz Node, an
# acronym one word ("TrajectoryPlannerROS" -> ... ROS).
_WORD = re.compile(r"[A-Z]+(?![a-z])|[A-Z][a-z0-9]*|[a-z0-9]+")


@dataclass(frozen=True)
class Proposal:
    table: str  # "" for a top-level key, else the TOML table ("rules.RN202")
    key: str
    value: str  # as TOML writes it
    code: str  # the rule whose findings it answers
    findings: int


def propose(diagnostics: Iterable[Diagnostic]) -> list[Proposal]:
    """The settings that would each answer many of the reported findings."""
    answers: dict[str, list[str]] = defaultdict(list)
    names: list[tuple[str | None, Kind | None, str]] = []  # RN203: package, kind, name
    for diagnostic in diagnostics:
        answer = diagnostic.answer
        if answer is None or diagnostic.suppressed or diagnostic.baselined:
            continue
        answers[answer.setting].append(answer.value)
        if answer.setting == _IGNORE_NAMES:
            names.append((diagnostic.package, answer.kind, answer.value))
    proposals = []
    depths = [int(value) for value in answers.get(_DEPTH, ())]
    if len(depths) >= MIN_DEEP:
        proposals.append(Proposal("", _DEPTH, str(max(depths)), "RN201", len(depths)))
    trees = _trees(answers.get(_ALLOW, ()))
    if trees:
        value = json.dumps(sorted(trees))
        proposals.append(
            Proposal("rules.RN202", "extend-allow", value, "RN202", sum(trees.values()))
        )
    patterns = _ignore_names(names)
    if patterns:
        answered = sum(1 for _, _, name in names if _matches(patterns, name))
        value = json.dumps(sorted(patterns))
        proposals.append(Proposal("rules.RN203", "ignore-names", value, "RN203", answered))
    return proposals


def _ignore_names(names: Sequence[tuple[str | None, Kind | None, str]]) -> set[str]:
    """The patterns stating each package's conventions: the names of every kind that a
    package has at least ``MIN_NAMES`` of, ``*Word`` for a last word ``MIN_SHARED`` of
    them share."""
    by_group: dict[tuple[str | None, Kind | None], set[str]] = defaultdict(set)
    for package, kind, name in names:
        by_group[package, kind].add(name)
    # A convention is its project's: the packages beside one that states it (the same
    # directory, as a repository holds them) follow it too. image_pipeline's
    # image_publisher names its one component node ``ImagePublisher``, as depth_image_proc
    # and image_proc name theirs.
    stating = {
        (_parent(package), kind)
        for (package, kind), group in by_group.items()
        if len(group) >= MIN_NAMES
    }
    conventional = {
        name
        for (package, kind), group in by_group.items()
        if (_parent(package), kind) in stating
        for name in group
    }
    last_words = {name: _last_word(name) for name in conventional}
    shared = Counter(word for word in last_words.values() if word is not None)
    return {
        f"*{word}" if word is not None and shared[word] >= MIN_SHARED else name
        for name, word in last_words.items()
    }


def _parent(package: str | None) -> str | None:
    """The directory holding a package's directory (display form), None outside any."""
    return None if package is None else posixpath.dirname(package)


def _last_word(name: str) -> str | None:
    """The last CamelCase word of a name ("Node" of "DebayerNode", "Score" of
    "minimumScore"), None where it does not end in one ("cmd__vel")."""
    words = _WORD.findall(name)
    return words[-1] if words and words[-1][0].isupper() else None


def _matches(patterns: Collection[str], name: str) -> bool:
    """Whether a proposed pattern covers the name, as ``ignore-names`` would."""
    return name in patterns or any(
        pattern.startswith("*") and name.endswith(pattern[1:]) for pattern in patterns
    )


def _trees(names: Sequence[str]) -> dict[str, int]:
    """``/first/shared/**`` for each first level at least ``MIN_TREE`` names share, with
    how many names it covers."""
    by_first: dict[str, list[list[str]]] = defaultdict(list)
    for name in names:
        levels = name.removesuffix("/**").strip("/").split("/")
        if len(levels) > 1 or name.endswith("/**"):
            by_first[levels[0]].append(levels)
    trees: dict[str, int] = {}
    for first, members in by_first.items():
        if len(members) < MIN_TREE:
            continue
        shared = [first]
        # The levels every name has in common, short of each name's own last level.
        for depth in range(1, min(len(levels) for levels in members)):
            candidates = {levels[depth] for levels in members}
            if len(candidates) != 1 or any(len(levels) <= depth + 1 for levels in members):
                break
            shared.append(candidates.pop())
        trees["/" + "/".join(shared) + "/**"] = len(members)
    return trees


def render(proposals: Sequence[Proposal]) -> str:
    """The proposals as the lines of a configuration file to paste, each commented with
    the findings it answers; "" when there are none."""
    if not proposals:
        return ""
    total = sum(proposal.findings for proposal in proposals)
    decisions = "one decision" if len(proposals) == 1 else f"{len(proposals)} decisions"
    lines = [
        f"{total} findings are {decisions}: if the names are this project's convention, "
        "state it in roslint-names.toml ([tool.roslint-names] in pyproject.toml), "
        "else fix them:",
    ]
    table = ""
    for proposal in sorted(proposals, key=lambda p: (p.table, p.key)):  # top-level keys first
        if proposal.table != table:
            table = proposal.table
            lines.append(f"  [{table}]")
        setting = f"{proposal.key} = {proposal.value}"
        lines.append(f"  {setting:<44}  # {proposal.code}: {proposal.findings} findings")
    return "\n".join(lines) + "\n"
