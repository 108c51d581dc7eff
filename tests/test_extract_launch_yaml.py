"""ROS 2 launch YAML extraction: the same model as launch XML, spans from YAML marks."""

from __future__ import annotations

import time
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from roslint_names.extract.launch import yaml_launch as launch_yaml
from roslint_names.model import FileFacts, Generation, Kind, Role, Span

FIXTURES = Path(__file__).parent / "fixtures" / "launch"


def extract(
    source: str | bytes, path: str = "x.launch.yaml", package: Generation | None = None
) -> FileFacts:
    data = source.encode() if isinstance(source, str) else source
    return launch_yaml.extract(path, data, package, Generation.ROS1)


def values(facts: FileFacts) -> list[tuple[Kind, str]]:
    return [(use.kind, use.value) for use in facts.names]


def spans(facts: FileFacts) -> list[tuple[str, Span]]:
    return [(use.value, use.span) for use in facts.names]


def test_node() -> None:
    facts = extract("launch:\n- node: {pkg: p, exec: e, name: n, namespace: ns}\n")
    assert values(facts) == [(Kind.NODE, "n"), (Kind.NAMESPACE, "ns")]
    [launched] = facts.launch_nodes
    assert (launched.package, launched.executable, launched.namespace) == ("p", "e", "/ns")


def test_generation_is_ros2_unless_the_package_says_otherwise() -> None:
    assert extract("launch: []\n").generation is Generation.ROS2
    assert extract("launch: []\n", package=Generation.ROS1).generation is Generation.ROS1


def test_group_as_list_and_as_mapping_with_children() -> None:
    facts = extract(
        "launch:\n"
        "- group:\n"
        "  - push-ros-namespace: {namespace: a}\n"
        "  - node: {pkg: p, exec: e, name: n1}\n"
        "- group:\n"
        "    scoped: 'false'\n"
        "    children:\n"
        "    - push_ros_namespace: {namespace: b}\n"
        "- node: {pkg: p, exec: e, name: n2}\n"
    )
    assert [(use.value, use.namespace) for use in facts.names] == [
        ("a", "/"),
        ("n1", "/a"),
        ("b", "/"),
        ("n2", "/b"),
    ]


def test_remaps_params_and_frames() -> None:
    facts = extract(
        "launch:\n"
        "- node:\n"
        "    pkg: p\n"
        "    exec: e\n"
        "    remap:\n"
        "    - {from: cmd_vel, to: /cmd_vel}\n"
        "    param:\n"
        "    - {name: rate, value: 10}\n"
        "    - {name: base_frame_id, value: /base_link}\n"
        "    - name: pid\n"
        "      param:\n"
        "      - {name: p, value: 1.0}\n"
        "    - from: params.yaml\n"
    )
    assert [(use.role, use.value) for use in facts.names] == [
        (Role.REMAP_FROM, "cmd_vel"),
        (Role.REMAP_TO, "/cmd_vel"),
        (Role.PARAMETER, "rate"),
        (Role.PARAMETER, "base_frame_id"),
        (Role.FRAME, "/base_link"),
        (Role.PARAMETER, "pid.p"),
    ]
    [launched] = facts.launch_nodes
    assert launched.parameters == ("rate", "base_frame_id", "pid.p")
    assert [(remap.source, remap.target) for remap in launched.remaps] == [("cmd_vel", "/cmd_vel")]


def test_let_arg_and_conditions() -> None:
    facts = extract(
        "launch:\n"
        "- arg: {name: robot, default: r1}\n"
        "- let: {name: sim, value: 'true'}\n"
        "- node: {pkg: p, exec: e, name: '$(var robot)_driver'}\n"
        "- node: {pkg: p, exec: e, name: skipped, unless: $(var sim)}\n"
        "- node: {pkg: p, exec: e, name: '$(var unknown)'}\n"
    )
    assert [(use.value, use.dynamic) for use in facts.names] == [
        ("r1_driver", False),
        ("skipped", False),  # an off branch starts nothing, but its names are read
        ("$(var unknown)", True),
    ]
    assert [node.name for node in facts.launch_nodes] == ["r1_driver", None]


def test_composable_nodes() -> None:
    facts = extract(
        "launch:\n"
        "- node_container:\n"
        "    pkg: rclcpp_components\n"
        "    exec: component_container\n"
        "    name: c\n"
        "    composable_node:\n"
        "    - {pkg: p, plugin: p::A, name: a, namespace: cam}\n"
    )
    assert [(node.name, node.executable, node.namespace) for node in facts.launch_nodes] == [
        ("c", "component_container", "/"),
        ("a", "p::A", "/cam"),
    ]


# -- spans ----------------------------------------------------------------------------------


def test_span_of_plain_and_quoted_scalars() -> None:
    facts = extract('launch:\n- node:\n    name: talker\n    namespace: "ns"\n    pkg: p\n')
    assert spans(facts) == [
        ("talker", Span(3, 11, 3, 17)),
        ("ns", Span(4, 16, 4, 20)),  # the quotes are part of the span
    ]


def test_span_inside_ros_args() -> None:
    facts = extract("launch:\n- node: {pkg: p, exec: e, ros_args: '-r a:=b -r __node:=drv'}\n")
    assert spans(facts) == [
        ("a", Span(2, 41, 2, 42)),
        ("b", Span(2, 44, 2, 45)),
        ("drv", Span(2, 57, 2, 60)),
    ]


def test_span_inside_escaped_scalar_falls_back_to_the_whole_scalar() -> None:
    facts = extract('launch:\n- node: {pkg: p, exec: e, ros_args: "-r\\ta:=b"}\n')
    assert [span for _, span in spans(facts)] == [Span(2, 37, 2, 47)] * 2


def test_span_with_crlf_and_utf16_and_non_ascii() -> None:
    text = "launch:\r\n# größe 🤖\r\n- node: {pkg: 'größe🤖', name: naïve}\r\n"
    facts = extract(text.encode("utf-16"))
    assert facts.parse_errors == ()
    assert spans(facts) == [("naïve", Span(3, 31, 3, 36))]


# -- errors ---------------------------------------------------------------------------------


def test_malformed_yaml_is_one_parse_error_with_its_position() -> None:
    [error] = extract("launch:\n- node: {pkg: p\n").parse_errors
    assert (error.span.line, error.span.column) == (3, 1)
    assert error.message.startswith("cannot parse YAML: ")


def test_undecodable_bytes_are_one_parse_error() -> None:
    [error] = extract(b"launch:\n- node: {name: \xc3\x28}\n").parse_errors
    assert (error.span.line, error.span.column) == (2, 16)


def test_control_character_is_one_parse_error() -> None:
    facts = extract("launch:\n- node: {name: a\x07}\n")
    assert len(facts.parse_errors) == 1
    assert facts.names == ()


def test_empty_or_foreign_yaml_is_no_launch_file_and_no_error() -> None:
    for source in ("", "# only a comment\n", "foo: bar\n", "- a\n", "launch: 3\n"):
        facts = extract(source)
        assert facts.parse_errors == () and facts.names == ()


def test_multiple_documents_are_a_parse_error() -> None:
    assert len(extract("launch: []\n---\nlaunch: []\n").parse_errors) == 1


def test_alias_bomb_finishes_quickly() -> None:
    lines = ["a0: &a0 [{node: {pkg: p, exec: e, name: n}}]"]
    lines += [f"a{i}: &a{i} [{{group: *a{i - 1}}}, {{group: *a{i - 1}}}]" for i in range(1, 40)]
    lines.append("launch: [{group: *a39}, {group: *a39}]")
    start = time.monotonic()
    facts = extract("\n".join(lines) + "\n")
    assert time.monotonic() - start < 2
    assert len(facts.launch_nodes) == 1


def test_deep_nesting_does_not_raise() -> None:
    facts = extract("launch: " + "[" * 5000 + "]" * 5000 + "\n")
    assert len(facts.parse_errors) <= 1


@settings(max_examples=300)
@given(st.binary(max_size=256))
def test_random_bytes_never_raise(data: bytes) -> None:
    assert len(extract(data).parse_errors) <= 1


@settings(max_examples=200)
@given(st.text(alphabet="launch:-node{}[]&*!|>'\" \n\t#$()", max_size=200))
def test_yaml_shaped_text_never_raises(source: str) -> None:
    assert len(extract(source).parse_errors) <= 1


# -- fixture --------------------------------------------------------------------------------


def test_talker_listener_fixture() -> None:
    facts = extract((FIXTURES / "talker_listener.launch.yaml").read_bytes())
    assert facts.parse_errors == ()
    assert [(node.name, node.namespace) for node in facts.launch_nodes] == [
        ("talker", "/my/chatter/ns"),
        ("listener", "/my/chatter/ns"),
        ("sim", "/turtlesim1"),
        ("container", "/"),
        ("composed_talker", "/composed"),
    ]
    assert values(facts) == [
        (Kind.NAMESPACE, "my/chatter/ns"),
        (Kind.NODE, "talker"),
        (Kind.TOPIC, "chatter"),
        (Kind.TOPIC, "/chatter"),
        (Kind.NODE, "listener"),
        (Kind.NODE, "listener2"),
        (Kind.NODE, "sim"),
        (Kind.NAMESPACE, "turtlesim1"),
        (Kind.PARAMETER, "background_r"),
        (Kind.PARAMETER, "odom_frame"),
        (Kind.FRAME, "odom"),
        (Kind.PARAMETER, "limits.max_speed"),
        (Kind.NODE, "container"),
        (Kind.NODE, "composed_talker"),
        (Kind.NAMESPACE, "composed"),
    ]
    [frame] = [use for use in facts.names if use.kind is Kind.FRAME]
    assert frame.span == Span(33, 14, 33, 28)  # with its quotes


def test_surrogate_escape_stands_for_a_replacement_character() -> None:
    """PyYAML turns ``"\\ud800"`` into a lone surrogate, which no report (all UTF-8) can
    print: the CLI exited 2 with a UnicodeEncodeError. It stands for U+FFFD instead."""
    facts = extract('launch:\n- node: {pkg: p, exec: e, name: "a\\ud800b\\udc80"}\n')
    assert values(facts) == [(Kind.NODE, "a\ufffdb\ufffd")]
    assert spans(facts) == [("a\ufffdb\ufffd", Span(2, 33, 2, 49))]
