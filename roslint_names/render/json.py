"""The ``graph`` command's JSON output (``--format json``), version 1.

One UTF-8 JSON object, indented by two spaces, ending with a line break. Keys come in the
fixed order shown, ``version`` first as in ``check --format json``; every list is sorted,
so the same graph always gives the same bytes::

    {
      "version": 1,
      "nodes": [...],
      "edges": [
        {
          "node": "/talker",
          "root": "src/demo/launch/demo.launch",
          "resource": "/chatter",
          "kind": "topic",
          "edge": "publish",
          "type": "std_msgs/String",
          "written": "chatter",
          "path": "src/demo/src/talker.cpp",
          "line": 12,
          "column": 5,
          "end_line": 12,
          "end_column": 14
        }
      ],
      "topics": [...],
      "services": [],
      "actions": []
    }

Fields:

``version`` (integer)
    The version of this format. It changes only when a field is removed or changes meaning;
    new fields may be added within a version, so ignore the ones you do not know.
``nodes`` (array)
    One object per node instance, by ``name`` then ``root``:
    ``name`` (string) the fully qualified node name (``/robot1/driver``);
    ``package``, ``executable`` (string or null) what it runs, null when unknown;
    ``generation`` (integer) 1 for ROS 1, 2 for ROS 2;
    ``root`` (string) the launch file whose tree starts it, ``""`` when no launch file does;
    ``sources`` (array of strings) the files of the code it runs, empty when that code is
    not in the workspace;
    ``launched_at`` (array) the chain of launch sites that start it, outermost include first
    and the node's own element last, each a location (below); empty when not launched;
    ``remaps`` (array) its remaps in force, each ``{"from": ..., "to": ...}`` with both sides
    fully qualified;
    ``parameters`` (array) every parameter the launch sets on it, by ``name`` then place
    (``workspace/parameter_settings.py``): ``name`` (string) as the node reads it (ROS 2
    dotted; ROS 1 relative to the node's private namespace when below it, else fully
    qualified); ``source`` (string) ``"launch"`` (the node's ``<param>``, its
    ``parameters={...}``, ``-p`` or ``_name:=`` on its command line) or ``"file"`` (a
    parameter file); ``key`` (string or null) the file's node key it is under (ROS 2
    files); the location of the name as written (the ``<param name>``, the file's key);
    ``site`` (a location, or null) where the launch hands the file over; ``conditional``
    (boolean) whether a condition the linter cannot decide guards it;
    ``code_parameters`` (object, or null where the graph did not compute it) what the
    node's code does with parameters, looked for in its sources, what they include of
    their package, their base classes and (for declarations) the rest of their packages
    (``workspace/parameters.py``): ``declared`` and ``read`` (arrays of strings)
    the names declared and read (read: also checked with ``has_parameter``);
    ``declared_under_prefix`` and ``read_under_prefix`` (arrays of strings) the names
    declared or read under a prefix known only at run time, as ``*`` and the literal end
    (``*.max_vel_x``); ``read_below`` (array of strings) the prefixes every parameter below
    which is read (``get_parameters("filters", map)``); ``reconfigure`` (array of
    strings) the dynamic_reconfigure ``.cfg`` files whose parameters the code's servers
    read (ROS 1; their names are in ``read``); ``complete`` (boolean) whether
    those are all the names the code may declare or read; ``incomplete`` (array of
    strings) why not: ``no-code``, ``library`` (code no program or component is known to
    run), ``run-time-declaration``, ``run-time-read``, ``allow-undeclared``,
    ``from-overrides``, ``plugins``, ``generated``, ``dynamic-reconfigure``, ``base-class``,
    ``search`` (ROS 1 ``searchParam``).
``topics``, ``services``, ``actions`` (arrays)
    One object per resolved name, by ``name``:
    ``name`` (string) the fully qualified name;
    ``types`` (array of strings) the distinct types its endpoints declare, sorted; empty when
    none is known, and more than one when they disagree;
    ``publishers``, ``subscribers`` (topics), ``servers``, ``clients`` (services and actions)
    (arrays of strings) the names of the nodes at each end, sorted, each once.
``edges`` (array)
    One object per endpoint, uncollapsed, by ``kind``, ``resource``, ``edge``, ``node``, then
    location:
    ``node`` (string) the node's fully qualified name, and ``root`` (string) its launch tree,
    which together pick one entry of ``nodes``;
    ``resource`` (string) the fully qualified name it uses;
    ``kind`` (string) ``"topic"``, ``"service"`` or ``"action"``;
    ``edge`` (string) ``"publish"``, ``"subscribe"``, ``"serve"``, ``"call"``,
    ``"action-serve"`` or ``"action-call"``;
    ``type`` (string or null) the type the code declares there, null when unknown;
    ``written`` (string) the name as the code wrote it, before namespaces and remaps;
    and the location of that name (below).

A location is ``path`` (string, relative to the directory roslint-names ran in, with ``/``
separators), ``line`` and ``column`` (integers, 1-based, the column counted in Unicode code
points), ``end_line`` and ``end_column`` (integers; ``end_column`` is exclusive).
"""

from __future__ import annotations

import json
from collections import defaultdict
from collections.abc import Iterable
from typing import Any

from ..model import Kind
from ..workspace.graph import EdgeKind, Endpoint, Graph, Location, NodeInstance, ParameterSetting
from ..workspace.parameters import NodeParameters

FORMAT_VERSION = 1
# Each resource list, the kind it holds, and the edge kinds behind each of its role lists.
_RESOURCE_LISTS: tuple[tuple[str, Kind, dict[str, EdgeKind]], ...] = (
    ("topics", Kind.TOPIC, {"publishers": EdgeKind.PUBLISH, "subscribers": EdgeKind.SUBSCRIBE}),
    ("services", Kind.SERVICE, {"servers": EdgeKind.SERVE, "clients": EdgeKind.CALL}),
    ("actions", Kind.ACTION, {"servers": EdgeKind.ACTION_SERVE, "clients": EdgeKind.ACTION_CALL}),
)


def render(graph: Graph) -> str:
    document: dict[str, Any] = {
        "version": FORMAT_VERSION,
        "nodes": [_node(node) for node in sorted(graph.nodes, key=_node_order)],
        "edges": [_edge(endpoint) for endpoint in sorted(graph.endpoints, key=_edge_order)],
    }
    for key, kind, roles in _RESOURCE_LISTS:
        document[key] = _resources([e for e in graph.endpoints if e.resource_kind is kind], roles)
    return json.dumps(document, indent=2, ensure_ascii=False) + "\n"


def _location(location: Location) -> dict[str, Any]:
    span = location.span
    return {
        "path": location.path,
        "line": span.line,
        "column": span.column,
        "end_line": span.end_line,
        "end_column": span.end_column,
    }


def _node_order(node: NodeInstance) -> tuple[str, str, int, str, str]:
    # Not the dataclass order: it would compare None with a string, and Remap, unordered.
    return (node.name, node.root, node.generation.value, node.package or "", node.executable or "")


def _node(node: NodeInstance) -> dict[str, Any]:
    return {
        "name": node.name,
        "package": node.package,
        "executable": node.executable,
        "generation": node.generation.value,
        "root": node.root,
        "sources": list(node.sources),
        "launched_at": [_location(location) for location in node.launched_at],
        "remaps": [{"from": remap.source, "to": remap.target} for remap in node.remaps],
        "parameters": [_setting(setting) for setting in node.parameter_settings],
        "code_parameters": _code_parameters(node.code_parameters),
    }


def _setting(setting: ParameterSetting) -> dict[str, Any]:
    return {
        "name": setting.name,
        "source": setting.source.value,
        "key": setting.key,
        **_location(setting.location),
        "site": None if setting.site is None else _location(setting.site),
        "conditional": setting.conditional,
    }


def _code_parameters(found: NodeParameters | None) -> dict[str, Any] | None:
    if found is None:
        return None
    return {
        "declared": list(found.declared),
        "read": list(found.read),
        "declared_under_prefix": [f"*{suffix}" for suffix in found.declared_suffixes],
        "read_under_prefix": [f"*{suffix}" for suffix in found.read_suffixes],
        "read_below": list(found.read_prefixes),
        "reconfigure": list(found.reconfigure),
        "complete": found.complete,
        "incomplete": [cause.value for cause in found.incomplete],
    }


def _resources(endpoints: Iterable[Endpoint], roles: dict[str, EdgeKind]) -> list[dict[str, Any]]:
    by_name: dict[str, list[Endpoint]] = defaultdict(list)
    for endpoint in endpoints:
        by_name[endpoint.resource].append(endpoint)
    return [_resource(name, by_name[name], roles) for name in sorted(by_name)]


def _resource(name: str, endpoints: list[Endpoint], roles: dict[str, EdgeKind]) -> dict[str, Any]:
    entry: dict[str, Any] = {
        "name": name,
        "types": sorted({e.type_name for e in endpoints if e.type_name is not None}),
    }
    for key, edge in roles.items():
        entry[key] = sorted({e.node for e in endpoints if e.edge is edge})
    return entry


def _edge_order(endpoint: Endpoint) -> tuple[str, str, str, str, str, Location, str, str]:
    return (
        endpoint.resource_kind.value,
        endpoint.resource,
        endpoint.edge.value,
        endpoint.node,
        endpoint.root,
        endpoint.location,
        endpoint.written,
        endpoint.type_name or "",
    )


def _edge(endpoint: Endpoint) -> dict[str, Any]:
    return {
        "node": endpoint.node,
        "root": endpoint.root,
        "resource": endpoint.resource,
        "kind": endpoint.resource_kind.value,
        "edge": endpoint.edge.value,
        "type": endpoint.type_name,
        "written": endpoint.written,
        **_location(endpoint.location),
    }
