"""The ``graph`` command's renderers: DOT (checked by Graphviz itself), Mermaid, JSON."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from dataclasses import replace
from pathlib import Path
from typing import Any
from xml.etree import ElementTree

import pytest
from conftest import write, write_package

from roslint_names.model import Generation, Kind, Remap, Span
from roslint_names.render import FORMATS, RENDERERS, render
from roslint_names.render import dot as dot_render
from roslint_names.render import json as json_render
from roslint_names.render import mermaid as mermaid_render
from roslint_names.render.view import MISMATCH_NOTE, layout
from roslint_names.workspace.graph import (
    EdgeKind,
    Endpoint,
    Graph,
    Location,
    NodeInstance,
    ParameterSetting,
    SettingSource,
)

FIXTURES = Path(__file__).parent / "fixtures" / "graph"
BRINGUP = "src/bringup/launch/robots.launch.py"
DEMO = "src/demo/launch/demo.launch"
DRIVER_CPP = "src/robot_driver/src/driver.cpp"
TELEOP_PY = "src/ünïcode pkg/scripts/joy teleop.py"  # non-ASCII and a space, as in the wild
ODD_PACKAGE = 'odd"pkg\\v2'  # a quote and a backslash: both need escaping in DOT
ODD_TOPIC = "/diag/{node}/status[0](x)|<y>#z;&`"  # every character Mermaid reads as syntax


T, S, A = Kind.TOPIC, Kind.SERVICE, Kind.ACTION
KINDS = {
    EdgeKind.PUBLISH: T,
    EdgeKind.SUBSCRIBE: T,
    EdgeKind.SERVE: S,
    EdgeKind.CALL: S,
    EdgeKind.ACTION_SERVE: A,
    EdgeKind.ACTION_CALL: A,
}


def at(path: str, line: int, column: int, length: int = 8) -> Location:
    return Location(path, Span(line, column, line, column + length))


def instance(
    name: str,
    package: str | None,
    executable: str | None,
    *,
    root: str = BRINGUP,
    launched_at: tuple[Location, ...] = (),
    sources: tuple[str, ...] = (),
    remaps: tuple[Remap, ...] = (),
) -> NodeInstance:
    return NodeInstance(
        name, Generation.ROS2, package, executable, root, launched_at, sources, remaps
    )


def endpoint(
    node: str,
    edge: EdgeKind,
    resource: str,
    type_name: str | None,
    location: Location,
    *,
    written: str | None = None,
    root: str = BRINGUP,
) -> Endpoint:
    kind = KINDS[edge]
    written = resource.rsplit("/", 1)[-1] if written is None else written
    return Endpoint(resource, kind, edge, node, root, type_name, location, written)


PUB, SUB, SERVE, CALL = EdgeKind.PUBLISH, EdgeKind.SUBSCRIBE, EdgeKind.SERVE, EdgeKind.CALL
ODOM, TWIST, EMPTY = "nav_msgs/Odometry", "geometry_msgs/Twist", "std_srvs/Empty"
NAV = "nav2_msgs/NavigateToPose"


def two_robots() -> Graph:
    """Two drivers in their own namespaces, a teleop, a monitor that got a type wrong, a
    navigator, an idle node, and names that stress every format's escaping."""
    nodes = (
        instance(
            "/robot1/driver",
            "robot_driver",
            "driver_node",
            launched_at=(at(BRINGUP, 14, 9), at("src/bringup/launch/robot.launch.py", 6, 5)),
            sources=(DRIVER_CPP,),
            remaps=(Remap("/robot1/odom_raw", "/robot1/odom", Span(7, 20, 7, 30)),),
        ),
        instance(
            "/robot2/driver",
            "robot_driver",
            "driver_node",
            launched_at=(at(BRINGUP, 18, 9), at("src/bringup/launch/robot.launch.py", 6, 5)),
            sources=(DRIVER_CPP,),
        ),
        instance("/teleop", "joy_teleop", "joy teleop.py", root="", sources=(TELEOP_PY,)),
        instance("/monitor", ODD_PACKAGE, "monitor", launched_at=(at(BRINGUP, 30, 9),)),
        instance("/navigator", "nav", "navigator", launched_at=(at(BRINGUP, 34, 9),)),
        instance("/robot1/planner", "nav", "planner", launched_at=(at(BRINGUP, 38, 9),)),
        instance("/idle", None, None, root=""),
        instance("/café", "crème", "brûlée", launched_at=(at(BRINGUP, 42, 9),)),
    )
    endpoints = (
        endpoint("/robot1/driver", PUB, "/robot1/odom", ODOM, at(DRIVER_CPP, 12, 5)),
        # A second publisher call of the same topic: collapses into the arrow above.
        endpoint("/robot1/driver", PUB, "/robot1/odom", ODOM, at(DRIVER_CPP, 40, 7)),
        endpoint("/robot2/driver", PUB, "/robot2/odom", ODOM, at(DRIVER_CPP, 12, 5)),
        endpoint("/robot1/driver", SUB, "/robot1/cmd_vel", TWIST, at(DRIVER_CPP, 20, 5)),
        endpoint("/teleop", PUB, "/robot1/cmd_vel", TWIST, at(TELEOP_PY, 9, 23), root=""),
        # The monitor believes odom is a pose: the type mismatch.
        endpoint("/monitor", SUB, "/robot1/odom", "geometry_msgs/PoseStamped", at("m.py", 3, 1)),
        endpoint("/robot1/driver", SERVE, "/robot1/reset", EMPTY, at(DRIVER_CPP, 25, 5)),
        endpoint("/teleop", CALL, "/robot1/reset", EMPTY, at(TELEOP_PY, 11, 9), root=""),
        endpoint("/navigator", EdgeKind.ACTION_CALL, "/robot1/navigate", NAV, at("n.py", 5, 9)),
        endpoint(
            "/robot1/planner", EdgeKind.ACTION_SERVE, "/robot1/navigate", NAV, at("p.py", 8, 3)
        ),
        endpoint("/monitor", SUB, ODD_TOPIC, None, at("m.py", 4, 1), written="{node}/x"),
        endpoint("/café", PUB, "/café/état", "std_msgs/String", at("c.py", 2, 1)),
    )
    return Graph(nodes, endpoints)


PARAMS = "src/demo/config/listener.yaml"


def setting(
    name: str, location: Location, *, key: str | None = None, site: Location | None = None
) -> ParameterSetting:
    source = SettingSource.LAUNCH if key is None and site is None else SettingSource.FILE
    return ParameterSetting(name, location, source, key=key, site=site)


def small() -> Graph:
    """The golden graph: a talker, a listener, a service and an action, one mismatch; the
    talker's parameter set in the launch file, the listener's seven in a file."""
    talker, listener, launch = "src/demo/src/talker.cpp", "src/demo/scripts/listener.py", DEMO
    handed = at(launch, 5, 5)
    listener_parameters = tuple(
        setting(name, at(PARAMS, line, 5, len(name)), key="listener", site=handed)
        for line, name in enumerate(
            ["buffer_size", "qos.depth", "qos.reliability", "rate", "timeout", "topic", "verbose"],
            start=3,
        )
    )
    nodes = (
        replace(
            instance("/talker", "demo", "talker", root=launch, launched_at=(at(launch, 3, 3),)),
            parameter_settings=(setting("rate", at(launch, 3, 40, 4)),),
        ),
        replace(
            instance(
                "/listener", "demo", "listener.py", root=launch, launched_at=(at(launch, 4, 3),)
            ),
            parameter_settings=listener_parameters,
        ),
    )
    endpoints = (
        endpoint("/talker", PUB, "/chatter", "std_msgs/String", at(talker, 12, 5)),
        endpoint("/listener", SUB, "/chatter", "std_msgs/Int32", at(listener, 8, 9)),
        endpoint("/talker", SERVE, "/talker/reset", EMPTY, at(talker, 14, 5)),
        endpoint("/listener", CALL, "/talker/reset", EMPTY, at(listener, 10, 9)),
        endpoint("/listener", EdgeKind.ACTION_CALL, "/fibonacci", None, at(listener, 12, 9)),
        endpoint("/talker", EdgeKind.ACTION_SERVE, "/fibonacci", None, at(talker, 16, 5)),
    )
    return Graph(nodes, tuple(replace(e, root=launch) for e in endpoints))


def shuffled(graph: Graph) -> Graph:
    """The same graph listed in another order."""
    return Graph(tuple(reversed(graph.nodes)), tuple(reversed(graph.endpoints)))


def check_snapshot(name: str, actual: str) -> None:
    path = FIXTURES / name
    if os.environ.get("ROSLINT_UPDATE_SNAPSHOTS"):
        path.write_text(actual, encoding="utf-8", newline="\n")
    assert actual == path.read_text(encoding="utf-8"), f"{name} changed; review the diff"


# --- every format ------------------------------------------------------------------------


def test_renderers_are_the_three_agreed() -> None:
    assert set(RENDERERS) == {"dot", "mermaid", "json"}
    assert tuple(RENDERERS) == FORMATS
    assert render("json", small()) == json_render.render(small())


def test_unknown_format_is_a_value_error() -> None:
    with pytest.raises(ValueError, match="'svg'"):
        render("svg", small())


@pytest.mark.parametrize("fmt", ["dot", "mermaid", "json"])
def test_same_graph_same_bytes_in_any_order(fmt: str) -> None:
    graph = two_robots()
    first = render(fmt, graph)
    assert first == render(fmt, graph)
    assert first == render(fmt, shuffled(graph))
    assert first.endswith("\n") and not first.endswith("\n\n")


@pytest.mark.parametrize(("fmt", "golden"), [("dot", "small.dot"), ("mermaid", "small.mmd")])
def test_snapshot_drawings(fmt: str, golden: str) -> None:
    check_snapshot(golden, render(fmt, small()))


def test_snapshot_json() -> None:
    check_snapshot("small.json", render("json", small()))


# --- the shared layout -------------------------------------------------------------------


def test_ids_are_sorted_and_safe() -> None:
    drawing = layout(two_robots())
    names = [node.name for node in drawing.nodes]
    assert names == sorted(names)
    assert [node.ident for node in drawing.nodes] == [f"n{i}" for i in range(len(names))]
    topics = [r for r in drawing.resources if r.kind is T]
    assert [t.ident for t in topics] == [f"t{i}" for i in range(len(topics))]
    assert [t.name for t in topics] == sorted(t.name for t in topics)
    assert {r.ident for r in drawing.resources if r.kind is S} == {"s0"}
    assert {r.ident for r in drawing.resources if r.kind is A} == {"a0"}


def test_idle_node_and_unlisted_node_get_shapes() -> None:
    graph = two_robots()
    ghost = endpoint("/ghost", PUB, "/robot1/odom", ODOM, at("g.py", 1, 1))
    drawing = layout(Graph(graph.nodes, (*graph.endpoints, ghost)))
    by_name = {node.name: node for node in drawing.nodes}
    assert by_name["/idle"].lines == ("/idle",)  # no package/executable known
    assert by_name["/ghost"].instance is None
    assert by_name["/robot1/driver"].lines == ("/robot1/driver", "robot_driver/driver_node")


def test_same_name_in_two_launch_trees_is_two_nodes() -> None:
    graph = small()
    other = instance("/talker", "demo", "talker", root="other.launch")
    drawing = layout(Graph((*graph.nodes, other), graph.endpoints))
    assert [node.name for node in drawing.nodes].count("/talker") == 2


def test_mismatched_types_are_all_listed() -> None:
    drawing = layout(two_robots())
    (odom,) = [r for r in drawing.resources if r.name == "/robot1/odom"]
    assert odom.mismatch
    assert odom.lines == ("/robot1/odom", "geometry_msgs/PoseStamped", ODOM, MISMATCH_NOTE)
    (cmd_vel,) = [r for r in drawing.resources if r.name == "/robot1/cmd_vel"]
    assert not cmd_vel.mismatch and cmd_vel.lines == ("/robot1/cmd_vel", TWIST)
    (odd,) = [r for r in drawing.resources if r.name == ODD_TOPIC]
    assert odd.lines == (ODD_TOPIC,)  # the type is unknown: no type line, no mismatch


def test_arrows_follow_the_data_and_collapse() -> None:
    drawing = layout(two_robots())
    ident = {n.name: n.ident for n in drawing.nodes} | {r.name: r.ident for r in drawing.resources}
    arrows = {(a.tail, a.head): a for a in drawing.arrows}
    expected = [
        ("/robot1/driver", "/robot1/odom", PUB),  # publisher -> topic
        ("/robot1/odom", "/monitor", SUB),  # topic -> subscriber
        ("/teleop", "/robot1/cmd_vel", PUB),
        ("/robot1/cmd_vel", "/robot1/driver", SUB),
        ("/teleop", "/robot1/reset", CALL),  # client -> service
        ("/robot1/reset", "/robot1/driver", SERVE),  # service -> server
        ("/navigator", "/robot1/navigate", EdgeKind.ACTION_CALL),
        ("/robot1/navigate", "/robot1/planner", EdgeKind.ACTION_SERVE),
    ]
    for tail, head, edge in expected:
        assert arrows[(ident[tail], ident[head])].edge is edge, (tail, head)
    collapsed = arrows[(ident["/robot1/driver"], ident["/robot1/odom"])]
    assert [e.location.span.line for e in collapsed.endpoints] == [12, 40]
    assert len(drawing.arrows) == len(two_robots().endpoints) - 1


# --- DOT ---------------------------------------------------------------------------------

DOT_QUOTED = r'"((?:[^"\\]|\\.)*)"'
DOT_NODE = re.compile(rf"^  (\w+) \[shape=(\w+), label={DOT_QUOTED}, tooltip={DOT_QUOTED}(.*)\];$")
DOT_EDGE = re.compile(
    rf"^  (\w+) -> (\w+) \[label={DOT_QUOTED}, style=(\w+), tooltip={DOT_QUOTED}\];$"
)


def dot_unquote(text: str) -> str:
    """What Graphviz reads from the inside of a quoted label: ``\\n`` a line break."""
    return re.sub(r"\\(.)", lambda m: "\n" if m.group(1) == "n" else m.group(1), text)


def dot_statements(text: str) -> tuple[dict[str, tuple[str, str, str]], list[tuple[str, ...]]]:
    """Node statements by id (shape, label, extra attributes) and edge statements."""
    nodes: dict[str, tuple[str, str, str]] = {}
    edges: list[tuple[str, ...]] = []
    for line in text.splitlines():
        if match := DOT_NODE.match(line):
            ident, shape, label, _tooltip, extra = match.groups()
            nodes[ident] = (shape, dot_unquote(label), extra)
        elif match := DOT_EDGE.match(line):
            edges.append(match.groups())
    return nodes, edges


def svg_texts_and_titles(svg: str) -> tuple[list[str], list[str]]:
    root = ElementTree.fromstring(svg)
    texts = [element.text or "" for element in root.iter("{http://www.w3.org/2000/svg}text")]
    titles = [
        value
        for element in root.iter()
        for key, value in element.attrib.items()
        if key == "{http://www.w3.org/1999/xlink}title"
    ]
    return texts, titles


def run_dot(text: str) -> str:
    executable = shutil.which("dot")
    if executable is None:
        pytest.skip("Graphviz's `dot` is not on PATH; .ci/run installs the graphviz package")
    result = subprocess.run(
        [executable, "-Tsvg"], input=text.encode(), capture_output=True, timeout=60, check=False
    )
    errors = result.stderr.decode(errors="replace")
    assert result.returncode == 0, errors
    # No warnings either (a badly delimited string or attribute warns and carries on); only
    # font ones are the machine's business, not the DOT's.
    warnings = [line for line in errors.splitlines() if "font" not in line.lower()]
    assert not warnings, errors
    return result.stdout.decode()


def test_dot_renders_with_graphviz_and_every_label_survives() -> None:
    graph = two_robots()
    texts, titles = svg_texts_and_titles(run_dot(dot_render.render(graph)))
    drawing = layout(graph)
    for shape in (*drawing.nodes, *drawing.resources):
        for line in shape.lines:
            assert line in texts, line
    assert ODD_PACKAGE + "/monitor" in texts  # quote and backslash back as written
    assert "/café/état" in texts and "crème/brûlée" in texts
    assert f"{DRIVER_CPP}:12:5\n{DRIVER_CPP}:40:7" in titles  # the collapsed arrow's tooltip
    assert f"{TELEOP_PY}:9:23" in titles


def test_dot_golden_renders_with_graphviz() -> None:
    texts, _ = svg_texts_and_titles(run_dot((FIXTURES / "small.dot").read_text("utf-8")))
    assert "/chatter" in texts and MISMATCH_NOTE in texts


def test_dot_shapes_labels_and_mismatch_colour() -> None:
    text = dot_render.render(two_robots())
    nodes, _ = dot_statements(text)
    drawing = layout(two_robots())
    shapes = {"topic": "box", "service": "hexagon", "action": "parallelogram"}
    for node in drawing.nodes:
        assert nodes[node.ident][:2] == ("ellipse", "\n".join(node.lines))
    for resource in drawing.resources:
        shape, label, extra = nodes[resource.ident]
        assert (shape, label) == (shapes[resource.kind.value], "\n".join(resource.lines))
        assert ("color=red" in extra) is resource.mismatch, resource.name
    assert len(nodes) == len(drawing.nodes) + len(drawing.resources)


def test_dot_edges_carry_kind_style_and_locations() -> None:
    text = dot_render.render(two_robots())
    _, edges = dot_statements(text)
    drawing = layout(two_robots())
    assert len(edges) == len(drawing.arrows)
    styles = {"publish": "solid", "subscribe": "solid", "call": "dashed", "serve": "dashed"}
    styles |= {"action call": "bold", "action serve": "bold"}
    for (tail, head, label, style, tooltip), arrow in zip(edges, drawing.arrows, strict=True):
        assert (tail, head, label) == (arrow.tail, arrow.head, arrow.label)
        assert style == styles[label]
        assert dot_unquote(tooltip).split("\n") == [
            f"{e.location.path}:{e.location.span.line}:{e.location.span.column}"
            for e in arrow.endpoints
        ]
    # Each endpoint is also a comment, with the name as written.
    assert f"  // publish: {DRIVER_CPP}:40:7 written 'odom'" in text.splitlines()


def test_dot_quote_escapes_what_graphviz_reads() -> None:
    assert dot_render.quote('a"b') == r'"a\"b"'
    assert dot_render.quote("a\\nb") == r'"a\\nb"'  # a backslash-n in a name, not a break
    assert dot_render.quote("a\nb") == r'"a\nb"'
    assert dot_render.quote("tab\there\r") == '"tab here "'
    assert dot_render.quote("ünï") == '"ünï"'


def test_dot_comments_stay_on_one_line() -> None:
    graph = small()
    odd = endpoint("/talker", PUB, "/x", None, at("dir\nnew.cpp", 1, 1), written="a\rb")
    text = dot_render.render(Graph(graph.nodes, (*graph.endpoints, odd)))
    assert "  // publish: dir new.cpp:1:1 written 'a\\rb'" in text.splitlines()
    for line in text.splitlines()[4:-1]:
        assert line.startswith("  "), line  # nothing spilled out of a comment


# --- Mermaid -----------------------------------------------------------------------------

MM_ID = r"[ntsa]\d+"
MM_LABEL = r'"(?:[^"\[\](){}|<>#;&`\x00-\x1f]|#\w+;|<br>)*"'
MM_SHAPES = [(r"\(\[", r"\]\)"), (r"\[", r"\]"), (r"\{\{", r"\}\}"), (r"\[/", r"/\]")]
MM_LINE = re.compile(
    "|".join(
        [
            r"    %% [^{}\n]*",
            *(rf"    {MM_ID}{opening}{MM_LABEL}{closing}" for opening, closing in MM_SHAPES),
            rf"    {MM_ID} (?:-->|-\.->|==>)\|[a-z ]+\| {MM_ID}",
            r"    classDef mismatch stroke:red,color:red",
            rf"    subgraph c\d+\[{MM_LABEL}\]",
            r"    end",
            r"        %% [^{}\n]*",
            *(rf"        {MM_ID}{opening}{MM_LABEL}{closing}" for opening, closing in MM_SHAPES),
            rf"    class {MM_ID}(?:,{MM_ID})* mismatch",
        ]
    )
)
MM_SHAPE = re.compile(rf'^    ({MM_ID})(?:\(\[|\[/|\[|\{{\{{)("[^"]*")')
MM_LINK = re.compile(rf"^    ({MM_ID}) (-->|-\.->|==>)\|([a-z ]+)\| ({MM_ID})$")


def mermaid_unescape(label: str) -> str:
    """The text Mermaid shows for a quoted label: entity codes decoded, ``<br>`` a break."""
    named = {"quot": '"', "lt": "<", "gt": ">", "amp": "&"}
    inner = label[1:-1].replace("<br>", "\n")
    return re.sub(r"#(\w+);", lambda m: named.get(m.group(1)) or chr(int(m.group(1))), inner)


def test_mermaid_header_and_grammar() -> None:
    lines = mermaid_render.render(two_robots()).splitlines()
    assert lines[0] == "flowchart LR"
    declared = set()
    for line in lines[1:]:
        assert MM_LINE.fullmatch(line), line
        if match := MM_SHAPE.match(line):
            declared.add(match.group(1))
        elif match := MM_LINK.match(line):
            assert {match.group(1), match.group(4)} <= declared, line  # declared before use


def test_mermaid_labels_are_escaped_and_survive() -> None:
    graph = two_robots()
    text = mermaid_render.render(graph)
    labels = {
        m.group(1): mermaid_unescape(m.group(2))
        for m in map(MM_SHAPE.match, text.splitlines())
        if m
    }
    drawing = layout(graph)
    for shape in (*drawing.nodes, *drawing.resources):
        assert labels[shape.ident] == "\n".join(shape.lines), shape.name
    assert ODD_TOPIC in labels.values() and "/café/état\nstd_msgs/String" in labels.values()
    assert "/diag/#123;node#125;/status#91;0#93;#40;x#41;#124;#lt;y#gt;#35;z#59;#amp;#96;" in text


def test_mermaid_links_shapes_and_mismatch_class() -> None:
    text = mermaid_render.render(two_robots())
    drawing = layout(two_robots())
    links = [m.groups() for m in map(MM_LINK.match, text.splitlines()) if m]
    arrows = {"publish": "-->", "subscribe": "-->", "call": "-.->", "serve": "-.->"}
    arrows |= {"action call": "==>", "action serve": "==>"}
    assert len(links) == len(drawing.arrows)
    for (tail, link, label, head), arrow in zip(links, drawing.arrows, strict=True):
        assert (tail, label, head) == (arrow.tail, arrow.label, arrow.head)
        assert link == arrows[label]
    mismatched = ",".join(r.ident for r in drawing.resources if r.mismatch)
    assert f"    class {mismatched} mismatch" in text.splitlines()
    assert '    s0{{"/robot1/reset<br>std_srvs/Empty"}}' in text.splitlines()
    assert '    a0[/"/robot1/navigate<br>nav2_msgs/NavigateToPose"/]' in text.splitlines()


def test_mermaid_locations_are_comments() -> None:
    lines = mermaid_render.render(two_robots()).splitlines()
    assert f"    %% publish: {TELEOP_PY}:9:23 written 'cmd_vel'" in lines
    # Braces in a comment would read as a directive: coded, like in labels.
    assert "    %% subscribe: m.py:4:1 written '#123;node#125;/x'" in lines


def test_mermaid_escape_codes_control_characters() -> None:
    assert mermaid_render.escape("a\nb\tc") == "a#10;b#9;c"
    assert mermaid_render.escape("ünï/~x") == "ünï/~x"


# --- JSON --------------------------------------------------------------------------------


def document(graph: Graph | None = None) -> dict[str, Any]:
    loaded: dict[str, Any] = json.loads(json_render.render(graph or two_robots()))
    return loaded


def by_name(entries: list[dict[str, Any]], name: str) -> dict[str, Any]:
    (entry,) = [entry for entry in entries if entry["name"] == name]
    return entry


def test_json_layout_version_first_two_space_indent_utf8() -> None:
    text = json_render.render(two_robots())
    loaded = json.loads(text)
    assert text == json.dumps(loaded, indent=2, ensure_ascii=False) + "\n"
    assert "crème" in text and "\\u" not in text  # readable, not \u-escaped
    # The order the module documents, version first as in `check --format json`.
    assert list(loaded) == ["version", "nodes", "edges", "topics", "services", "actions"]
    assert list(loaded["edges"][0])[:3] == ["node", "root", "resource"]
    assert loaded["version"] == 1


def test_json_nodes_carry_everything() -> None:
    nodes = document()["nodes"]
    assert [node["name"] for node in nodes] == sorted(node["name"] for node in nodes)
    assert by_name(nodes, "/robot1/driver") == {
        "name": "/robot1/driver",
        "package": "robot_driver",
        "executable": "driver_node",
        "generation": 2,
        "root": BRINGUP,
        "sources": [DRIVER_CPP],
        "launched_at": [
            {"path": BRINGUP, "line": 14, "column": 9, "end_line": 14, "end_column": 17},
            {
                "path": "src/bringup/launch/robot.launch.py",
                "line": 6,
                "column": 5,
                "end_line": 6,
                "end_column": 13,
            },
        ],
        "remaps": [{"from": "/robot1/odom_raw", "to": "/robot1/odom"}],
        "parameters": [],
        "code_parameters": None,  # a graph built by hand: not computed
    }
    idle = by_name(nodes, "/idle")
    assert (idle["package"], idle["executable"], idle["root"], idle["launched_at"]) == (
        None,
        None,
        "",
        [],
    )
    assert by_name(nodes, "/monitor")["package"] == ODD_PACKAGE


def test_json_resources_with_roles_and_types() -> None:
    loaded = document()
    topics = loaded["topics"]
    assert [t["name"] for t in topics] == sorted(t["name"] for t in topics)
    assert by_name(topics, "/robot1/odom") == {
        "name": "/robot1/odom",
        "types": ["geometry_msgs/PoseStamped", ODOM],  # they disagree: both listed
        "publishers": ["/robot1/driver"],  # two endpoints, listed once
        "subscribers": ["/monitor"],
    }
    assert by_name(topics, ODD_TOPIC)["types"] == []
    assert loaded["services"] == [
        {
            "name": "/robot1/reset",
            "types": [EMPTY],
            "servers": ["/robot1/driver"],
            "clients": ["/teleop"],
        }
    ]
    assert loaded["actions"] == [
        {
            "name": "/robot1/navigate",
            "types": [NAV],
            "servers": ["/robot1/planner"],
            "clients": ["/navigator"],
        }
    ]


def test_json_edges_are_every_endpoint_with_its_location() -> None:
    graph = two_robots()
    loaded = document(graph)
    edges = loaded["edges"]
    assert len(edges) == len(graph.endpoints)  # uncollapsed
    nodes = {(node["name"], node["root"]) for node in loaded["nodes"]}
    assert all((edge["node"], edge["root"]) in nodes for edge in edges)
    odd = [edge for edge in edges if edge["resource"] == ODD_TOPIC]
    assert odd == [
        {
            "node": "/monitor",
            "root": BRINGUP,
            "resource": ODD_TOPIC,
            "kind": "topic",
            "edge": "subscribe",
            "type": None,
            "written": "{node}/x",
            "path": "m.py",
            "line": 4,
            "column": 1,
            "end_line": 4,
            "end_column": 9,
        }
    ]
    keys = [(e["kind"], e["resource"], e["edge"], e["node"], e["line"]) for e in edges]
    assert keys == sorted(keys)


def test_json_empty_graph() -> None:
    assert document(Graph((), ())) == {
        "version": 1,
        "nodes": [],
        "topics": [],
        "services": [],
        "actions": [],
        "edges": [],
    }


def test_json_every_field_is_documented_in_the_module_docstring() -> None:
    doc = json_render.__doc__ or ""
    loaded = document()
    keys = set(loaded) | set(loaded["nodes"][0]) | set(loaded["edges"][0])
    for kind in ("topics", "services", "actions"):
        keys |= set(loaded[kind][0])
    keys |= set(loaded["nodes"][0]["launched_at"][0])
    for key in sorted(keys):
        assert f"``{key}``" in doc, key


# --- launch trees as boxes ----------------------------------------------------------------


SCAN = "sensor_msgs/LaserScan"
NODE_CPP, CLIENT_CPP = "src/rplidar_ros/src/node.cpp", "src/rplidar_ros/src/client.cpp"


def alternatives() -> Graph:
    """rplidar_ros, reduced: two alternative launch files each start /rplidarNode, which
    publishes /scan; a node no launch file starts reads it."""
    nodes = (
        instance("/rplidarNode", "rplidar_ros", "rplidarNode", root="launch/rplidar_a1.launch"),
        instance("/rplidarNode", "rplidar_ros", "rplidarNode", root="launch/rplidar_s2.launch"),
        instance("/scan_client", "rplidar_ros", "rplidarNodeClient", root=""),
    )
    endpoints = (
        endpoint("/rplidarNode", PUB, "/scan", SCAN, at(NODE_CPP, 3, 5), root=nodes[0].root),
        endpoint("/rplidarNode", PUB, "/scan", SCAN, at(NODE_CPP, 3, 5), root=nodes[1].root),
        endpoint("/scan_client", SUB, "/scan", SCAN, at(CLIENT_CPP, 4, 5), root=""),
    )
    return Graph(nodes, endpoints)


def test_alternative_launch_trees_are_boxes_in_dot() -> None:
    """Before, both /rplidarNode were drawn among every other node, unlabelled."""
    source = dot_render.render(alternatives())
    assert source.count("subgraph cluster_") == 2
    assert 'label="launch/rplidar_a1.launch";' in source
    texts, _ = svg_texts_and_titles(run_dot(source))
    assert {"launch/rplidar_a1.launch", "launch/rplidar_s2.launch"} <= set(texts)
    assert dot_render.render(small()).count("subgraph") == 0  # one tree: no box


def test_alternative_launch_trees_are_subgraphs_in_mermaid() -> None:
    lines = mermaid_render.render(alternatives()).splitlines()
    for line in lines[1:]:
        assert MM_LINE.fullmatch(line), line
    assert lines.count("    end") == 2
    assert '    subgraph c0["launch/rplidar_a1.launch"]' in lines
    client = next(i for i, line in enumerate(lines) if "/scan_client" in line and "%%" not in line)
    assert not lines[client].startswith("        ")  # not launched: outside every box


RPLIDAR_LAUNCH = """<launch>
  <node name="rplidarNode" pkg="rplidar_ros" type="rplidarNode" output="screen">
    <param name="serial_port" value="/dev/ttyUSB0"/>
  </node>
</launch>
"""
VIEW_LAUNCH = """<launch>
  <include file="$(find rplidar_ros)/launch/rplidar_a1.launch"/>
  <node name="rviz" pkg="rviz" type="rviz"/>
</launch>
"""


def test_graph_of_a_launch_file_draws_what_it_starts(run_cli: Any, tmp_path: Path) -> None:
    """Before, `graph launch/view_rplidar.launch` drew the whole workspace: every
    alternative launch file's /rplidarNode, ungrouped."""
    write_package(tmp_path / "src/rplidar_ros", 1, "rplidar_ros")
    for name in ("rplidar_a1", "rplidar_s2", "rplidar_a3"):
        write(tmp_path, f"src/rplidar_ros/launch/{name}.launch", RPLIDAR_LAUNCH)
    write(tmp_path, "src/rplidar_ros/launch/view_rplidar.launch", VIEW_LAUNCH)

    def nodes(*paths: str) -> list[tuple[str, str]]:
        result = run_cli(["graph", "--format", "json", "--no-cache", *paths], tmp_path)
        return [(node["name"], node["root"]) for node in json.loads(result.stdout)["nodes"]]

    view = "src/rplidar_ros/launch/view_rplidar.launch"
    assert nodes(view) == [("/rplidarNode", view), ("/rviz", view)]
    # A file another includes is drawn as its includers launch it.
    assert nodes("src/rplidar_ros/launch/rplidar_a1.launch") == [("/rplidarNode", view)]
    # The whole package: every tree, each in its own box.
    assert len(nodes("src/rplidar_ros")) == 4
    dot = run_cli(["graph", "--format", "dot", "--no-cache", "src/rplidar_ros"], tmp_path).stdout
    assert dot.count("subgraph cluster_") == 3
