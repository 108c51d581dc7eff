"""RN407 undeclared-parameter: ROS 2 code reading a parameter its node never declares.

A ROS 2 node holds only the parameters it declares (unless it allows undeclared ones).
Reading another one fails at run time:

- rclcpp's ``Node::get_parameter(name)`` (and ``get_parameters(names)``,
  ``describe_parameter``) throws ``ParameterNotDeclaredException``:
  ``NodeParameters::get_parameter(name)`` and ``NodeParameters::describe_parameters`` in
  ``rclcpp/src/rclcpp/node_interfaces/node_parameters.cpp``;
- rclpy's ``Node.get_parameter`` (and ``get_parameters``, ``describe_parameter``) raises
  it (``rclpy/node.py``);
- rclcpp's ``get_parameter(name, value)`` and ``get_parameter_or``, rclpy's
  ``get_parameter_or``, throw nothing: they return false or the alternative, every time,
  and no parameter file or launch argument can ever set the value (an undeclared
  override is dropped).

The read is reported where it is, when the node's declarations are all known
(``workspace.parameters``: no name declared at run time, no undeclared parameters
allowed, no declarations from overrides, no plugins, no generated parameters, no base
class outside the workspace, code that is a program or component) and the name is
declared nowhere in the node's code, by its client library, nor anywhere else in the
workspace (a helper the linter does not follow may declare it). Code run by several nodes
is reported only when every one of them is judged so.

Its related locations are where each node is started and, where the launch sets the same
name on the node (a ``<param>``, an inline dictionary, a parameter file's key), that
place and where the file is handed over: a value given there is never read either.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from ..model import ParameterAccess, Severity
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import Graph, Location, NodeInstance, SettingSource
from ..workspace.parameters import ParameterUse
from .graph_common import finding, launch_site
from .spelling import folded, one_edit

_JUDGED = frozenset({ParameterAccess.READ, ParameterAccess.READ_QUIETLY})
_MAX_NODES = 3


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    declarations = graph.parameter_declarations
    # Every node running the file of a read, and whether it proves the read undeclared.
    verdicts: dict[Location, list[tuple[bool, ParameterUse, NodeInstance]]] = defaultdict(list)
    for node in graph.nodes:
        parameters = node.code_parameters
        if node.generation.value != 2 or parameters is None:
            continue
        judged = parameters.declarations_complete
        for use in parameters.uses:
            if use.access not in _JUDGED:
                continue
            undeclared = (
                judged
                and not parameters.declares(use.name)
                and not parameters.may_declare(use.name)
                and not (declarations is not None and declarations.declares(use.name))
            )
            verdicts[use.location].append((undeclared, use, node))
    for location, seen in sorted(verdicts.items()):
        if not all(undeclared for undeclared, _, _ in seen):
            continue
        _, use, _ = seen[0]
        # Named only where a launch file starts the node: code no launch file starts is
        # put in a node by its program's sources, and a library linked into several
        # programs (ament_auto links each program with the package's libraries) would
        # name a program that never builds the class that reads.
        nodes = sorted({node.name for _, _, node in seen if node.launched_at})
        related = [
            (site, f"node '{node.name}' is started here")
            for _, _, node in seen
            if (site := launch_site(node)) is not None
        ]
        for _, _, node in seen:
            related += _set_at(use.name, node)
        yield finding(location, _message(use, nodes, seen[0][2]), related)


def _set_at(name: str, node: NodeInstance) -> list[tuple[Location, str]]:
    """Where the launch sets ``name`` on the node: a value that is never read."""
    found: list[tuple[Location, str]] = []
    for setting in node.parameter_settings:
        if setting.name != name:
            continue
        what = "the launch file" if setting.source is SettingSource.LAUNCH else "this file"
        found.append(
            (
                setting.location,
                f"{what} sets '{name}' on node '{node.name}' here; undeclared, it is never read",
            )
        )
        if setting.site is not None:
            found.append((setting.site, f"the file is handed to node '{node.name}' here"))
    return found


def _message(use: ParameterUse, nodes: list[str], node: NodeInstance) -> str:
    named = ", ".join(f"'{name}'" for name in nodes[:_MAX_NODES])
    more = f" and {len(nodes) - _MAX_NODES} more" if len(nodes) > _MAX_NODES else ""
    which = "the node that runs this code" if len(nodes) == 1 else "the nodes that run this code"
    if not nodes:
        which, named = "any code of its node", ""
    near = _near(use.name, node)
    fix = (
        f"read '{near}', which it declares, or declare this one"
        if near
        else "declare it (declare_parameter) before reading it"
    )
    return (
        f"parameter '{use.name}' is read here but never declared by {which}"
        f"{f' ({named}{more})' if named else ''}:"
        f" {_consequence(use)}; {fix}"
    )


def _consequence(use: ParameterUse) -> str:
    python = use.api.startswith("rclpy")
    call = use.api.rpartition("." if python else "::")[2]
    if use.access is ParameterAccess.READ:
        raised = "raises" if python else "throws"
        return f"{call} {raised} ParameterNotDeclaredException"
    if call == "get_parameter_or":
        return "get_parameter_or returns the alternative every time, and nothing can set it"
    return "get_parameter(name, value) returns false every time, and nothing can set it"


def _near(name: str, node: NodeInstance) -> str | None:
    """A declared name one edit, a case or an underscore away from ``name``."""
    parameters = node.code_parameters
    if parameters is None:
        return None
    written = folded(name)
    for declared in parameters.declared:
        if folded(declared) == written or one_edit(declared, name):
            return declared
    return None


RULE = Rule(
    code="RN407",
    name="undeclared-parameter",
    summary="ROS 2 code reading a parameter its node never declares",
    severity=Severity.ERROR,
    check=None,
    check_workspace=check_workspace,
    reads_code_names=False,
)
