"""RN406 unused-parameter: a parameter set on a node under a name its code never declares
(ROS 2) or reads (ROS 1).

What sets a parameter on a node is ``NodeInstance.parameter_settings``
(``workspace.parameter_settings``): an entry of a parameter file whose node key applies to
the node, a ROS 1 ``<rosparam command="load">`` into the node's private namespace, a
launch file's ``<param name>`` on the node, a ``parameters=[{...}]`` key, ``-p
name:=value`` (ROS 1 ``_name:=value``). A ROS 1 name outside the node's private
namespace is any node's to read, and is left alone.

What the runtimes do with a name no code asks for:

- ROS 2: rclcpp keeps the overrides it is started with in ``parameter_overrides_``
  (``NodeParameters::NodeParameters`` in
  ``rclcpp/src/rclcpp/node_interfaces/node_parameters.cpp``) and gives one to the node
  only when the node declares that name (``__declare_parameter_common``); only
  ``automatically_declare_parameters_from_overrides`` declares them all. rclpy does the
  same (``Node.__init__`` keeps ``_parameter_overrides``, ``Node.declare_parameters``
  reads them, in ``rclpy/node.py``). An override the node never declares is dropped
  without a word.
- ROS 1: roslaunch sets the name on the parameter server (``Loader.add_param``), where it
  stays, unread.

Reported only where the node's parameter set leaves no doubt (``workspace.parameters``):
ROS 2, every name the node may declare is known (no run-time declaration, no undeclared
parameters allowed, no declarations from overrides, no plugins but its package's own, no
generated parameters, no base class or code outside the workspace), or the name is in a
group the node's own code declares names in and only plugins are in doubt; ROS 1, every
name it may read is known (no run-time read, no search for a run-time name, no
dynamic_reconfigure server whose ``.cfg`` the workspace does not hold, no plugins). The
name is
known when the code declares or reads it (ROS 2: or its client library declares it:
``use_sim_time``, ``qos_overrides.``), when it sits under a prefix the code reads whole,
ends as a name declared under a run-time prefix does, or is a string the code holds that
no API the linter knows takes. ROS 1 names are compared without their namespaces: a read
through a handle of another namespace, or of a whole dictionary, counts.

An entry several nodes receive (a ``/**`` key, a launch file included twice) is reported
once, when every node it applies to is judged so. A parameter file handed also to a node
whose name the linter does not know may be that node's: an entry is left alone where
that node's code may take the name.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator
from dataclasses import replace

from ..model import Decision, Generation, Kind, Severity, Span
from ..rule import Rule, RuleContext, WorkspaceFinding
from ..workspace.graph import Graph, Location, NodeInstance, ParameterSetting, SettingSource
from ..workspace.parameters import Incomplete, NodeParameters, WorkspaceDeclarations
from .graph_common import finding, launch_site
from .spelling import nearest

_MAX_NODES = 3
_MAX_SOURCES = 3


def check_workspace(graph: Graph, context: RuleContext) -> Iterator[WorkspaceFinding]:
    del context
    # Every node a written name reaches, and whether that node's code misses it.
    judged: list[tuple[bool, ParameterSetting, NodeInstance]] = []
    elsewhere = graph.parameter_declarations or WorkspaceDeclarations()
    # Whether a name is unknown to a node's code, by that code's parameters and the name:
    # nodes of the same code share one ``NodeParameters`` (``ParameterSets.of``), and the
    # 27,100 settings realws's nodes receive are 2,600 such pairs.
    unknown_to: dict[tuple[int, Generation, str], bool] = {}
    for node in graph.nodes:
        parameters = node.code_parameters
        for setting in node.parameter_settings:
            if node.generation is Generation.ROS1 and setting.name.startswith("/"):
                continue  # outside the node's private namespace: any node's to read
            unknown = False
            if parameters is not None:
                pair = (id(parameters), node.generation, setting.name)
                unknown_then = unknown_to.get(pair)
                if unknown_then is None:
                    unknown_then = unknown_to[pair] = (
                        _judged(node.generation, parameters, setting.name)
                        and _unknown(node.generation, parameters, setting.name)
                        and not _mentioned(node, setting.name, elsewhere)
                    )
                unknown = unknown_then and not any(
                    _may_take(receiver.generation, receiver.parameters, setting.name)
                    for receiver in graph.unnamed_parameter_files.get(setting.location.path, ())
                )
            judged.append((unknown, setting, node))
    # By where each name is written, in the files where one is unknown to a node: a
    # place is hashed for those only (the workspace writes 13,000 at 8 copies of realws).
    suspects = {setting.location.path for unknown, setting, _ in judged if unknown}
    verdicts: dict[Location, list[tuple[bool, ParameterSetting, NodeInstance]]] = defaultdict(list)
    for verdict in judged:
        if verdict[1].location.path in suspects:
            verdicts[verdict[1].location].append(verdict)
    # Sorted once found: sorting every written name of the workspace cost more.
    found = [location for location, seen in verdicts.items() if all(u for u, _, _ in seen)]
    for location in sorted(found):
        yield _finding(location, verdicts[location])


def _judged(generation: Generation, parameters: NodeParameters, name: str) -> bool:
    """Whether the node's code shows every name it may take under which ``name`` could
    be: in ROS 2 every name it may declare (an override it does not declare is dropped,
    read or not), in ROS 1 every name it may read.

    A ROS 2 node that loads plugins of other packages may be given any name they declare
    under the names of their instances (nav2's ``FollowPath.``), but a group the node's
    own code declares names in is its own: opennav_docking's ``controller.`` parameters
    are its ``Controller`` class's, not a dock plugin's."""
    if generation is not Generation.ROS2:
        return parameters.complete
    if parameters.declarations_complete:
        return True
    left = set(parameters.incomplete) - {Incomplete.RUN_TIME_READ, Incomplete.PLUGINS}
    return not left and _in_own_group(name, parameters)


def _in_own_group(name: str, parameters: NodeParameters) -> bool:
    group, dot, _ = name.partition(".")
    return bool(dot) and any(declared.startswith(f"{group}.") for declared in parameters.declared)


def _may_take(generation: Generation, parameters: NodeParameters, name: str) -> bool:
    """Whether a node of unknown name that is handed the same file may take ``name``:
    any key may be its (map_saver_server, started without a name in nav2's
    slam_launch.py), so only its code can say it does not."""
    return not _judged(generation, parameters, name) or not _unknown(generation, parameters, name)


def _unknown(generation: Generation, parameters: NodeParameters, name: str) -> bool:
    if not name or parameters.may_declare(name):
        return False
    if generation is Generation.ROS1:
        return not _read_in_ros1(name, parameters)
    if parameters.declares(name) or name in parameters.read:
        return False
    if any(name.endswith(suffix) for suffix in parameters.read_suffixes):
        return False
    return not any(
        not prefix or name == prefix or name.startswith(f"{prefix}.")
        for prefix in parameters.read_prefixes
    )


def _mentioned(node: NodeInstance, name: str, elsewhere: WorkspaceDeclarations) -> bool:
    """Whether other code of the workspace declares, reads or holds the name: code the
    linter does not follow from the node's may take it on the node (opennav_following's
    server builds opennav_docking's ``Controller``, which declares ``controller.*`` on
    it), or the entry may be meant for another node (a file of common parameters)."""
    if node.generation is Generation.ROS1:
        return elsewhere.mentions(name) or elsewhere.mentions(name.rpartition("/")[2])
    return elsewhere.mentions(name)


def _read_in_ros1(name: str, parameters: NodeParameters) -> bool:
    """Whether ROS 1 code may read ``name`` (relative to the node's private namespace),
    namespaces aside: a read of the name through any handle, of a dictionary holding it,
    or of a key inside the dictionary it sets; a read of ``~`` reads everything. A string
    the code holds that no API the linter knows takes counts as a read: a helper of the
    package may read it (``get_param(prefix + key)`` over a table of keys)."""
    for read in (*parameters.read, *parameters.declared, *parameters.literals):
        written = read.lstrip("~").strip("/")
        if (
            not written
            or written == name
            or name.endswith(f"/{written}")
            or written.endswith(f"/{name}")
            or name.startswith(f"{written}/")
            or written.startswith(f"{name}/")
        ):
            return True
    ends = (suffix.strip("/") for suffix in parameters.read_suffixes)
    return any(end and (name == end or name.endswith(f"/{end}")) for end in ends)


def _finding(
    location: Location, seen: list[tuple[bool, ParameterSetting, NodeInstance]]
) -> WorkspaceFinding:
    _, setting, first = seen[0]
    nodes = sorted({node.name for _, _, node in seen})
    ros1 = first.generation is Generation.ROS1
    verb = "reads" if ros1 else "declares"
    if len(nodes) == 1:
        whom, lacks = f"node '{nodes[0]}'", f"its code never {verb} it"
    else:
        named = ", ".join(f"'{name}'" for name in nodes[:_MAX_NODES])
        more = f" and {len(nodes) - _MAX_NODES} more" if len(nodes) > _MAX_NODES else ""
        whom, lacks = f"every node it applies to ({named}{more})", f"none of their code {verb} it"
    effect = (
        "it stays on the parameter server, unread"
        if ros1
        else "a ROS 2 node keeps no parameter it does not declare, so the setting is dropped"
    )
    near = {nearest(setting.name, _candidates(node, setting.name)) for _, _, node in seen}
    suggestion = near.pop() if len(near) == 1 else None
    hint = f"; did you mean '{suggestion}'?" if suggestion else ""
    message = (
        f"parameter '{setting.name}' is {_how(setting)} for {whom}, but {lacks}: {effect}{hint}"
    )
    related: list[tuple[Location, str]] = []
    for _, each, node in seen:
        if each.site is not None:
            related.append((each.site, f"the file is handed to node '{node.name}' here"))
        site = launch_site(node)
        if site is not None:
            related.append((site, f"node '{node.name}' is started here"))
        related.extend(_code(node, suggestion))
    # One stale setting copied into several launch or parameter files is one decision
    # about one program's parameter: reported once, the copies related (``decisions``).
    # Autoware's four map_projection_loader tests all set ``use_local_projector``; two
    # copies of ``ekf_localizer.param.yaml`` (the package's and autoware_core_localization's)
    # set a name the ekf_localizer no longer declares, for differently named instances.
    decision = Decision(
        kind=Kind.PARAMETER,
        name=setting.name,
        generation=first.generation,
        scope=" ".join(sorted({source for _, _, node in seen for source in node.sources})),
    )
    found = finding(location, message, related)
    # A test's stand-in node started outside a test (roslaunch's ``example.launch`` gives
    # ``rospy/test_nodes/talker.py`` a ``talker_param``) shows launch syntax, not a
    # node's configuration: left out where the setting is in example or test code.
    stand_in = all(node.stand_in for _, _, node in seen)
    return replace(
        found,
        finding=replace(found.finding, decision=decision, deployment_only=stand_in),
    )


def _how(setting: ParameterSetting) -> str:
    if setting.source is SettingSource.LAUNCH:
        return "set by the launch file"
    if setting.key is None:
        return "loaded from this file"
    return f"set under node key '{setting.key}'"


def _code(node: NodeInstance, suggestion: str | None) -> list[tuple[Location, str]]:
    """Where the node's code names the suggested parameter; else its first parameter use
    in each of its sources; else its first source."""
    parameters = node.code_parameters
    uses = () if parameters is None else parameters.uses
    if suggestion is not None:
        named = [use for use in uses if _bare(use.name, node) == suggestion]
        if named:
            return [(named[0].location, f"'{suggestion}' is {_verb(node)} here")]
    firsts: dict[str, Location] = {}
    for use in uses:
        path = use.location.path
        firsts[path] = min(firsts.get(path, use.location), use.location)
    if firsts:
        does = "reads" if node.generation is Generation.ROS1 else "declares"
        note = f"the code of node '{node.name}' {does} parameters here"
        return [(where, note) for where in sorted(firsts.values())[:_MAX_SOURCES]]
    return [
        (Location(source, _FILE_START), f"the code of node '{node.name}'")
        for source in node.sources[:_MAX_SOURCES]
    ]


def _verb(node: NodeInstance) -> str:
    return "read" if node.generation is Generation.ROS1 else "declared"


def _bare(name: str, node: NodeInstance) -> str:
    return name.lstrip("~").strip("/") if node.generation is Generation.ROS1 else name


def _candidates(node: NodeInstance, name: str) -> list[str]:
    """The names the node's code declares or reads; a name declared under a run-time
    prefix (``.max_vel_x``) counts under the prefix ``name`` has (``FollowPath.``)."""
    parameters = node.code_parameters
    if parameters is None:
        return []
    found = [_bare(each, node) for each in (*parameters.declared, *parameters.read)]
    parts = name.split(".")
    for suffix in (*parameters.declared_suffixes, *parameters.read_suffixes):
        depth = suffix.count(".")
        if suffix.startswith(".") and 0 < depth < len(parts):
            found.append(".".join(parts[:-depth]) + suffix)
    return found


_FILE_START = Span(1, 1, 1, 1)


RULE = Rule(
    code="RN406",
    name="unused-parameter",
    summary="A parameter set on a node under a name its code never declares or reads",
    severity=Severity.WARNING,
    check=None,
    check_workspace=check_workspace,
    reads_code_names=False,
)
