"""Untrusted XML: sniffing, safe parsing, exact spans, and never raising."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from roslint_names.extract.launch import urdf, xmlsafe
from roslint_names.extract.launch import xml_launch as launch_xml
from roslint_names.extract.launch.xmlsafe import root_tag
from roslint_names.model import FileFacts, Generation, Kind, ParseError, Span

FIXTURES = Path(__file__).parent / "fixtures"


def ros1(data: bytes | str, path: str = "test.launch") -> FileFacts:
    raw = data.encode() if isinstance(data, str) else data
    return launch_xml.extract(path, raw, None, Generation.ROS1)


def node_name_span(facts: FileFacts) -> Span:
    [use] = [use for use in facts.names if use.kind is Kind.NODE]
    return use.span


# -- root_tag ---------------------------------------------------------------------------


def test_root_tag_of_plain_documents() -> None:
    assert root_tag(b"<launch><node/></launch>") == "launch"
    assert root_tag(b"<robot name='r'/>") == "robot"
    assert root_tag(b"<package format='3'>") == "package"  # no full parse: truncation is fine


def test_root_tag_skips_prolog() -> None:
    data = (
        b"\xef\xbb\xbf<?xml version='1.0'?>\n<!-- <robot> in a comment -->\n"
        b"<?xml-model href='x'?>\n<!DOCTYPE launch [<!ENTITY gt2 '>>'>]>\n  <launch/>"
    )
    assert root_tag(data) == "launch"


def test_root_tag_returns_local_name_of_prefixed_root() -> None:
    assert root_tag(b'<xacro:robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>') == "robot"


def test_root_tag_reads_utf16() -> None:
    assert root_tag('<?xml version="1.0" encoding="UTF-16"?><robot/>'.encode("utf-16")) == "robot"


def test_root_tag_of_non_xml() -> None:
    assert root_tag(b"") is None
    assert root_tag(b"just text") is None
    assert root_tag(b"\x00\xff\xfe garbage <") is None
    assert root_tag(b"<!-- never closed <launch>") is None


def test_root_tag_reads_at_most_64_kib() -> None:
    padding = b"<!--" + b"x" * (64 * 1024) + b"-->"
    assert root_tag(padding + b"<launch/>") is None
    assert root_tag(b"<!--" + b"x" * 1000 + b"-->" + b"<launch/>") == "launch"


# -- safety -----------------------------------------------------------------------------


@pytest.fixture
def secret_file(tmp_path: Path) -> Path:
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET-7d1e")
    return secret


def all_values(facts: FileFacts) -> str:
    return " ".join(use.value for use in facts.names)


def test_external_entity_in_attribute_is_never_read(secret_file: Path) -> None:
    data = (
        f'<!DOCTYPE launch [<!ENTITY x SYSTEM "{secret_file.as_uri()}">]>'
        '<launch><node pkg="p" type="t" name="&x;"/></launch>'
    )
    facts = ros1(data)
    assert "TOP-SECRET" not in all_values(facts)
    assert len(facts.parse_errors) == 1  # libxml2 refuses an external entity in attributes


def test_external_entity_in_text_is_never_read(secret_file: Path) -> None:
    data = (
        f'<!DOCTYPE robot [<!ENTITY x SYSTEM "{secret_file.as_uri()}">]>'
        "<robot><gazebo><plugin><frameName>&x;</frameName></plugin></gazebo></robot>"
    )
    facts = urdf.extract("r.urdf", data.encode(), None, Generation.ROS1)
    assert "TOP-SECRET" not in all_values(facts)
    assert [(use.value, use.dynamic) for use in facts.names] == [("&x;", True)]


def test_internal_entity_is_not_expanded_into_values() -> None:
    facts = ros1(
        '<!DOCTYPE launch [<!ENTITY robot "r2d2">]>'
        '<launch><group ns="&robot;"><node pkg="p" type="t" name="a&robot;"/></group></launch>'
    )
    assert [(use.value, use.dynamic) for use in facts.names] == [
        ("&robot;", True),
        ("a&robot;", True),
    ]


def test_external_dtd_is_not_loaded(secret_file: Path) -> None:
    data = f'<!DOCTYPE launch SYSTEM "{secret_file.as_uri()}"><launch/>'
    assert ros1(data).parse_errors == ()


def test_billion_laughs_finishes_quickly() -> None:
    entities = "".join(f'<!ENTITY lol{i} "{f"&lol{i - 1};" * 10}">' for i in range(1, 10))
    data = (
        f'<?xml version="1.0"?><!DOCTYPE launch [<!ENTITY lol0 "lol">{entities}]>'
        '<launch><node pkg="p" type="t" name="&lol9;"/><group ns="a">&lol9;</group></launch>'
    )
    start = time.monotonic()
    facts = ros1(data)
    assert time.monotonic() - start < 2
    assert len(facts.parse_errors) == 1 or len(all_values(facts)) < 10_000


# -- never raise ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "data",
    [
        b"",
        b"   \n",
        b"<launch><node name='a'></launch>",
        b"<launch>\xff\xfe</launch>",
        b'<?xml version="1.0" encoding="bogus"?><launch/>',
        b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR",
        b"<launch>" * 300 + b"</launch>" * 300,
    ],
)
def test_bad_input_gives_exactly_one_parse_error(data: bytes) -> None:
    for extract in (launch_xml.extract, urdf.extract):
        facts = extract("x.xml", data, None, Generation.ROS1)
        assert len(facts.parse_errors) == 1
        assert facts.names == () and facts.launch_nodes == ()


def test_parse_error_has_lxml_position() -> None:
    [error] = ros1("<launch>\n  <node name='a' pkg='p'\n</launch>").parse_errors
    assert (error.span.line, error.span.column) == (3, 1)
    assert error.message.startswith("cannot parse XML: ")


@settings(max_examples=300)
@given(st.binary(max_size=512))
def test_random_bytes_never_raise(data: bytes) -> None:
    for extract in (launch_xml.extract, urdf.extract):
        facts = extract("x.launch", data, None, Generation.ROS1)
        assert len(facts.parse_errors) <= 1


def _mutations() -> st.SearchStrategy[bytes]:
    seed = (FIXTURES / "launch" / "multi_robot.launch").read_bytes()
    return st.lists(st.tuples(st.integers(0, len(seed) - 1), st.integers(0, 255)), max_size=8).map(
        lambda edits: _apply(seed, edits)
    )


def _apply(seed: bytes, edits: list[tuple[int, int]]) -> bytes:
    data = bytearray(seed)
    for index, byte in edits:
        data[index] = byte
    return bytes(data)


@settings(max_examples=200)
@given(_mutations())
def test_mutated_launch_files_never_raise(data: bytes) -> None:
    facts = ros1(data)
    assert len(facts.parse_errors) <= 1


# -- spans ------------------------------------------------------------------------------


def test_span_covers_the_attribute_value() -> None:
    facts = ros1('<launch><node pkg="p" type="t" name="talker"/></launch>')
    assert node_name_span(facts) == Span(1, 38, 1, 44)


def test_span_on_a_later_line_of_a_multi_line_tag() -> None:
    facts = ros1(
        '<launch>\n  <node pkg="p"\n        type="t"\n        name = \'talker\'/>\n</launch>'
    )
    assert node_name_span(facts) == Span(4, 17, 4, 23)


def test_span_with_several_elements_on_one_line() -> None:
    facts = ros1('<launch><group ns="a"/><group ns="b"/></launch>')
    assert [(use.value, use.span.column) for use in facts.names] == [("a", 20), ("b", 35)]


def test_span_covers_raw_text_of_entity_escaped_value() -> None:
    facts = ros1('<launch><node pkg="p" type="t" name="a&amp;b&#x41;"/></launch>')
    [use] = facts.names
    assert use.value == "a&bA"
    assert use.span == Span(1, 38, 1, 51)


def test_span_inside_args_after_an_escaped_character() -> None:
    facts = ros1('<launch><node pkg="p" type="t" args="--x=&quot;y&quot; __name:=drv"/></launch>')
    assert node_name_span(facts) == Span(1, 64, 1, 67)


def test_span_inside_args_ending_in_an_escaped_character() -> None:
    facts = ros1('<launch><node name="n" pkg="p" type="t" args="in&amp;:=out"/></launch>')
    assert [(use.value, use.span) for use in facts.names[1:]] == [
        ("in&", Span(1, 47, 1, 54)),
        ("out", Span(1, 56, 1, 59)),
    ]


def test_span_with_crlf_line_ends() -> None:
    facts = ros1('<launch>\r\n\r\n  <node pkg="p" type="t"\r\n    name="talker"/>\r\n</launch>\r\n')
    assert node_name_span(facts) == Span(4, 11, 4, 17)


def test_span_ignores_utf8_bom() -> None:
    facts = ros1(b'\xef\xbb\xbf<launch><node name="a" pkg="p" type="t"/></launch>')
    assert node_name_span(facts) == Span(1, 21, 1, 22)


def test_span_counts_code_points_in_utf16_file() -> None:
    text = (
        '<?xml version="1.0" encoding="UTF-16"?>\n'
        "<launch>\n"
        '  <node pkg="größe🤖" type="t" name="naïve"/>\n'
        "</launch>\n"
    )
    facts = ros1(text.encode("utf-16"))  # with a BOM
    assert facts.parse_errors == ()
    [use] = facts.names
    assert use.value == "naïve"
    assert use.span == Span(3, 37, 3, 42)


def test_span_in_latin1_file() -> None:
    text = (
        '<?xml version="1.0" encoding="ISO-8859-1"?>\n<launch><node pkg="élan" name="ça"/></launch>'
    )
    facts = ros1(text.encode("latin-1"))
    [use] = facts.names
    assert (use.value, use.span) == ("ça", Span(2, 32, 2, 34))


def test_span_of_element_text_is_stripped() -> None:
    data = b"<robot><gazebo><plugin>\n<topicName>\n   imu\n</topicName></plugin></gazebo></robot>"
    [use] = urdf.extract("r.urdf", data, None, Generation.ROS1).names
    assert (use.value, use.span) == ("imu", Span(3, 4, 3, 7))


def test_span_of_cdata_text() -> None:
    data = (
        b"<robot><gazebo><plugin><topicName><![CDATA[ imu ]]></topicName></plugin></gazebo></robot>"
    )
    [use] = urdf.extract("r.urdf", data, None, Generation.ROS1).names
    assert (use.value, use.span) == ("imu", Span(1, 45, 1, 48))


def test_prefixed_attribute_is_not_confused_with_plain_one() -> None:
    data = (
        b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        b'<link xacro:name="decoy" name="base"/></robot>'
    )
    document = xmlsafe.parse(data)
    assert not isinstance(document, ParseError)
    link = document.root[0]
    plain = document.attribute(link, "name")
    prefixed = document.attribute(link, "{http://www.ros.org/wiki/xacro}name")
    assert plain is not None and prefixed is not None
    assert (plain.text, plain.span.column) == ("base", 83)
    assert (prefixed.text, prefixed.span.column) == ("decoy", 70)
