"""The absolute names a workspace's launch files wire nodes to (RN202's global interfaces).

A launch file that remaps a node's name onto an absolute one (``<remap
from="~/input/odometry" to="/localization/kinematic_state"/>``) states that the absolute
name is one of the system's interfaces, chosen where the system is assembled. Node code
that writes the same absolute name follows that decision rather than escaping it
(``RuleContext.wired_names``).

Where the launch files wire many names into one first level (Autoware's ``/planning/...``,
``/localization/...``, ``/map/...``), that level is a tree of interfaces the system lays out
(``wired_trees``): a name code writes under it (``/map/map_projector_info``,
``"/planning/planning_factors/" + module``) is a branch of that same layout, chosen with it.
One or two names under a level say nothing of the kind: ``/camera/image_raw`` wired once
is one connection.

Only a remap's target counts: it is where the launch author connects a node, the one
place a launch file chooses a name for the graph. A remap's source names what some node's
code already uses, often to move it away (``<remap from="/map" to="map"/>``), and a
parameter's value is a string the node may or may not use as a name.
"""

from __future__ import annotations

import functools

from .model import ENDPOINT_ROLES, FileFacts, Language, Role

# Distinct wired names of two or more levels that make their first level a tree.
TREE_BRANCHES = 3

_WIRING_LANGUAGES = frozenset(
    {Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.LAUNCH_PYTHON, Language.URDF}
)
# Where node code is: a Python launch file may hold a launch_testing test's own nodes.
_CODE_LANGUAGES = frozenset({Language.CPP, Language.PYTHON, Language.LAUNCH_PYTHON})
# What discovery calls the files that may wire names: a Python launch file is told from
# a script only by its content, once extracted.
WIRING_SOURCES = frozenset(
    {Language.LAUNCH_XML, Language.LAUNCH_YAML, Language.PYTHON, Language.URDF}
)


def wired_by(facts: FileFacts) -> frozenset[str]:
    """The absolute names the file's remaps connect nodes to, as it writes them."""
    if facts.language not in _WIRING_LANGUAGES:
        return frozenset()
    return frozenset(
        use.value
        for use in facts.names
        if use.role is Role.REMAP_TO and not use.dynamic and use.value.startswith("/")
    )


def awaits_wiring(facts: FileFacts) -> bool:
    """Whether the file's code hands an endpoint an absolute name, or one joined from an
    absolute start: its check needs the whole workspace's wiring, known only once every
    file is in."""
    return facts.language in _CODE_LANGUAGES and any(
        use.role in ENDPOINT_ROLES
        and (use.absolute_prefix is not None or use.value.startswith("/"))
        for use in facts.names
    )


@functools.lru_cache(maxsize=8)
def wired_trees(wired: frozenset[str]) -> frozenset[str]:
    """The first levels (``"/planning/"``) under which at least ``TREE_BRANCHES`` distinct
    wired names of two or more levels lie."""
    counts: dict[str, int] = {}
    for name in wired:
        first, separator, rest = name[1:].partition("/")
        if separator and rest:
            counts[f"/{first}/"] = counts.get(f"/{first}/", 0) + 1
    return frozenset(level for level, count in counts.items() if count >= TREE_BRANCHES)


def in_wired_tree(name: str, trees: frozenset[str]) -> bool:
    """Whether the absolute ``name`` (or an absolute start) lies under one of ``trees``
    below its first level."""
    first, separator, _ = name[1:].partition("/")
    return bool(separator) and f"/{first}/" in trees
