"""RN405 unmatched-node-key: a ROS 2 parameter file's node key that no node it is
handed to has.

rcl reads every key of the file; the client library keeps the entries whose key matches
the node's fully qualified name and drops the rest without a word
(``workspace.parameters``). A key one letter or one underscore away from the name of a
node the file is handed to (``fusioncore`` for ``fusion_core``), or that node's name in a
namespace the node never runs in (``fusion_core`` for ``/robot1/fusion_core``), means every
parameter under it falls back to its default.

Reported only where it is certain, and only near a node the file is handed to:

- every node the file is handed to has a known fully qualified name (launch or code);
- no ROS 2 node of the workspace has the key's name at all (a file shared by nodes that
  get it from different launch files is no mistake);
- the key's base name is near one of those nodes' names, or is the same name in a
  namespace the node cannot be in. A namespace that an including file could still push
  (a key ``/robot1/fusion_core`` for a node ``/fusion_core`` of a launch file a robot's
  bringup includes under ``robot1``) is left alone; so is a key like no node's name: a
  program may create further nodes whose names the linter does not see
  (navigation2's controller_server creates ``local_costmap/local_costmap``).

ROS 1 has no such failure: ``rosparam load`` sets every key under its namespace.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from ..model import Generation, ParameterBlock, Severity
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import Graph, Location, NodeInstance, ParameterFileUse
from ..workspace.parameter_files import is_wildcard, key_matches
from .graph_common import finding, launch_site, where


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    handed: dict[str, list[tuple[NodeInstance, ParameterFileUse]]] = defaultdict(list)
    for node in graph.nodes:
        if node.generation is Generation.ROS2:
            for use in node.parameter_files:
                handed[use.path].append((node, use))
    ros2_names = [node.name for node in graph.nodes if node.generation is Generation.ROS2]
    for path, uses in sorted(handed.items()):
        if path in graph.unnamed_parameter_files:
            continue  # one node it is handed to has a name we do not know
        for block in graph.parameter_files.get(path, ()):
            if block.key is None or _matched(block.key, uses, ros2_names):
                continue
            meant = [(node, use) for node, use in uses if _meant(block.key, node)]
            if meant:
                yield _finding(path, block, meant)


def _matched(key: str, uses: list[tuple[NodeInstance, ParameterFileUse]], names: list[str]) -> bool:
    """The key applies to a node it is handed to, or names a node of the workspace."""
    if any(key_matches(key, _matched_name(node), composable=node.composable) for node, _ in uses):
        return True
    return any(key_matches(key, name) for name in names)


def _matched_name(node: NodeInstance) -> str:
    """The name launch_ros matches a composable node by: none when the launch file does
    not name it (``workspace.parameters``)."""
    return node.name if node.named_at_launch or not node.composable else ""


def _meant(key: str, node: NodeInstance) -> bool:
    """Whether ``key`` looks written for ``node``: its base name one small slip away from
    the node's, or the node's in a namespace no includer can give the node."""
    key_namespace, _, key_base = f"/{key.lstrip('/')}".rpartition("/")
    namespace, _, base = node.name.rpartition("/")
    if is_wildcard(key_base) or not key_base:
        return False
    if key_base != base:
        return near(key_base, base)
    if is_wildcard(key_namespace):
        return False
    # An includer may push a namespace in front of the node's: the key's namespace may
    # still become the node's when it ends with it.
    return not f"{key_namespace}/".endswith(f"{namespace}/")


def near(written: str, name: str) -> bool:
    """One slip apart: the same but for case, '_' and '-', or one edit (two in a name of
    ten letters or more)."""
    if _folded(written) == _folded(name):
        return True
    shortest = min(len(written), len(name))
    allowed = 2 if shortest >= 10 else 1 if shortest >= 4 else 0
    return allowed > 0 and _distance(written, name, allowed) <= allowed


def _folded(text: str) -> str:
    return text.lower().replace("_", "").replace("-", "")


def _distance(one: str, other: str, limit: int) -> int:
    """Levenshtein distance, or ``limit + 1`` once it is sure to exceed ``limit``."""
    if abs(len(one) - len(other)) > limit:
        return limit + 1
    previous = list(range(len(other) + 1))
    for i, char in enumerate(one, start=1):
        current = [i]
        for j, other_char in enumerate(other, start=1):
            cost = 0 if char == other_char else 1
            current.append(min(previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost))
        if min(current) > limit:
            return limit + 1
        previous = current
    return previous[-1]


def _spelled(key: str, node: NodeInstance) -> str:
    """The key that would match the node: the key with its base name mended where that
    is enough (``/**/colision_monitor``), else the node's name, with or without the
    leading '/' as the key has it."""
    head, slash, _ = key.rpartition("/")
    base = node.name.rpartition("/")[2]
    mended = f"{head}{slash}{base}"
    if key_matches(mended, _matched_name(node), composable=node.composable):
        return mended
    namespace = node.name.rpartition("/")[0]
    if not namespace:
        return base
    return node.name if key.startswith("/") else node.name.lstrip("/")


def _finding(
    path: str, block: ParameterBlock, meant: list[tuple[NodeInstance, ParameterFileUse]]
) -> WorkspaceFinding:
    key = block.key or ""
    suggestions = sorted({_spelled(key, node) for node, _ in meant})
    meant_nodes = sorted({node.name for node, _ in meant})
    count = len(block.parameters)
    parameters = f"{count} parameter{'s' if count != 1 else ''}"
    first = meant[0][1]
    spellings = " or ".join(f"'{suggestion}'" for suggestion in suggestions)
    nodes = ", ".join(f"'{name}'" for name in meant_nodes)
    message = (
        f"node key '{key}' matches no node this file is handed to, so ROS 2 ignores the "
        f"{parameters} under it; did you mean {spellings}? The file is handed to {nodes} "
        f"at {where(first.site)}"
    )
    related: list[tuple[Location, str]] = []
    for node, use in meant:
        related.append((use.site, f"the file is handed to node '{node.name}' here"))
        site = launch_site(node)
        if site is not None and site != use.site:
            related.append((site, f"node '{node.name}' is started here"))
    return finding(Location(path, block.span), message, related)


RULE = Rule(
    code="RN405",
    name="unmatched-node-key",
    summary="A ROS 2 parameter file's node key that no node it is handed to has",
    severity=Severity.WARNING,
    check=None,
    check_workspace=check_workspace,
    reads_code_names=False,
)
