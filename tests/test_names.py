"""Tests for roslint_names.names: the ROS name grammar, resolution and helpers.

Table tests pin every reason and every row of ROS_NAMES.md's "Differences that bite".
Property tests compare the checker with reference oracles ported line by line from the ROS
sources (rosgraph names.py, roscpp names.cpp, rcl validate_topic_name.c and
expand_topic_name.c, rmw validate_node_name.c / validate_namespace.c /
validate_full_topic_name.c), so a divergence from the runtime makes them fail.
"""

from __future__ import annotations

import re
import string
from dataclasses import dataclass, replace

import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from roslint_names.model import Generation, Kind
from roslint_names.names import (
    NameResolutionError,
    Problem,
    check_name,
    depth,
    is_snake_case,
    is_valid,
    join_namespace,
    resolve,
    snake_case,
    tokens,
)

R1 = Generation.ROS1
R2 = Generation.ROS2
GRAPH_KINDS = (Kind.TOPIC, Kind.SERVICE, Kind.ACTION)
WITH_NS = (*GRAPH_KINDS, Kind.NAMESPACE)
WITH_PARAM = (*GRAPH_KINDS, Kind.PARAMETER)
WITH_NS_PARAM = (*GRAPH_KINDS, Kind.NAMESPACE, Kind.PARAMETER)
LIMITS = {Kind.TOPIC: 247, Kind.SERVICE: 246, Kind.ACTION: 226}
ANY = object()  # "some suggestion, not checked here"

# --------------------------------------------------------------------------- oracles
# Ported from the ROS sources as literally as Python allows. C sees bytes, so the C ports
# work on the UTF-8 encoding and on ASCII-only ctype classes (C locale / rcutils).


def _c_isdigit(byte: int) -> bool:
    return ord("0") <= byte <= ord("9")


def _c_isalpha(byte: int) -> bool:
    return ord("a") <= byte <= ord("z") or ord("A") <= byte <= ord("Z")


def _c_isalnum(byte: int) -> bool:
    return _c_isalpha(byte) or _c_isdigit(byte)


ROSGRAPH_NAME = re.compile(r"^[\~\/A-Za-z][\w\/]*$")  # rosgraph.names.NAME_LEGAL_CHARS_P
ROSGRAPH_BASE_NAME = re.compile(r"^[A-Za-z][\w]*$")  # BASE_NAME_LEGAL_CHARS_P


def rosgraph_is_legal_name(name: str) -> bool:
    if name == "":
        return True
    m = ROSGRAPH_NAME.match(name)
    return m is not None and m.group(0) == name and "//" not in name


def rosgraph_is_legal_base_name(name: str) -> bool:
    m = ROSGRAPH_BASE_NAME.match(name)
    return m is not None and m.group(0) == name


def roscpp_validate(name: str) -> bool:
    raw = name.encode()
    if not raw:
        return True
    if not _c_isalpha(raw[0]) and raw[0] not in b"/~":
        return False
    return all(_c_isalnum(c) or c in b"/_" for c in raw[1:])


def rcl_validate_topic_name(name: str) -> str | None:
    """rcl_validate_topic_name: None when valid, else the result name."""
    raw = name.encode()
    n = len(raw)
    if n == 0:
        return "IS_EMPTY_STRING"
    if _c_isdigit(raw[0]):
        return "NAME_TOKEN_STARTS_WITH_NUMBER"
    if raw[n - 1] == ord("/"):
        return "ENDS_WITH_FORWARD_SLASH"
    in_open_curly_brace = False
    opening_curly_brace_index = 0
    for i in range(n):
        c = raw[i]
        if _c_isalnum(c):
            if _c_isdigit(c) and in_open_curly_brace and i - 1 == opening_curly_brace_index:
                return "SUBSTITUTION_STARTS_WITH_NUMBER"
            continue
        if c == ord("_"):
            continue
        if c == ord("/"):
            if in_open_curly_brace:
                return "SUBSTITUTION_CONTAINS_UNALLOWED_CHARACTERS"
            continue
        if c == ord("~"):
            if i != 0:
                return "MISPLACED_TILDE"
            continue
        if c == ord("{"):
            opening_curly_brace_index = i
            if in_open_curly_brace:
                return "SUBSTITUTION_CONTAINS_UNALLOWED_CHARACTERS"
            in_open_curly_brace = True
            continue
        if c == ord("}"):
            if not in_open_curly_brace:
                return "UNMATCHED_CURLY_BRACE"
            in_open_curly_brace = False
            continue
        if in_open_curly_brace:
            return "SUBSTITUTION_CONTAINS_UNALLOWED_CHARACTERS"
        return "CONTAINS_UNALLOWED_CHARACTERS"
    if in_open_curly_brace:
        return "UNMATCHED_CURLY_BRACE"
    for i in range(n):
        if i == n - 1:
            continue
        if raw[i] == ord("/"):
            if _c_isdigit(raw[i + 1]):
                return "NAME_TOKEN_STARTS_WITH_NUMBER"
        elif i == 1 and raw[0] == ord("~"):
            return "TILDE_NOT_FOLLOWED_BY_FORWARD_SLASH"
    return None


def rcl_expand_topic_name(name: str, node_name: str, node_namespace: str) -> str | None:
    """rcl_expand_topic_name on an rcl-valid name; None for an unknown substitution."""
    has_a_substitution = "{" in name
    has_a_namespace_tilde = name[0] == "~"
    is_absolute = name[0] == "/"
    if is_absolute and not has_a_substitution:
        return name
    local_output: str | None = None
    if has_a_namespace_tilde:
        sep = "" if len(node_namespace) == 1 else "/"
        local_output = node_namespace + sep + node_name + name[1:]
    if has_a_substitution:
        current = local_output if local_output is not None else name
        while "{" in current:
            opening, closing = current.index("{"), current.index("}")
            substitution = current[opening : closing + 1]
            if substitution == "{node}":
                replacement = node_name
            elif substitution in ("{ns}", "{namespace}"):
                replacement = node_namespace
            else:
                return None  # the default substitution map is empty
            local_output = current.replace(substitution, replacement)
            current = local_output
    output = local_output if local_output is not None else name
    if output[0] != "/":
        sep = "" if len(node_namespace) == 1 else "/"
        output = node_namespace + sep + output
    return output


def rmw_validate_full_topic_name(name: str, max_length: int = 247) -> str | None:
    raw = name.encode()
    n = len(raw)
    if n == 0:
        return "IS_EMPTY_STRING"
    if raw[0] != ord("/"):
        return "NOT_ABSOLUTE"
    if raw[n - 1] == ord("/"):
        return "ENDS_WITH_FORWARD_SLASH"
    for c in raw:
        if not (_c_isalnum(c) or c in b"_/"):
            return "CONTAINS_UNALLOWED_CHARACTERS"
    for i in range(n - 1):
        if raw[i] == ord("/"):
            if raw[i + 1] == ord("/"):
                return "CONTAINS_REPEATED_FORWARD_SLASH"
            if _c_isdigit(raw[i + 1]):
                return "NAME_TOKEN_STARTS_WITH_NUMBER"
    if n > max_length:
        return "TOO_LONG"
    return None


def rmw_validate_namespace(namespace: str) -> str | None:
    if namespace == "/":
        return None
    result = rmw_validate_full_topic_name(namespace)
    if result is not None and result != "TOO_LONG":
        return result
    if len(namespace.encode()) > 245:
        return "TOO_LONG"
    return None


def rmw_validate_node_name(name: str) -> str | None:
    raw = name.encode()
    if not raw:
        return "IS_EMPTY_STRING"
    if not all(_c_isalnum(c) or c == ord("_") for c in raw):
        return "CONTAINS_UNALLOWED_CHARACTERS"
    if _c_isdigit(raw[0]):
        return "STARTS_WITH_NUMBER"
    if len(raw) > 255:
        return "TOO_LONG"
    return None


def ros1_oracle(name: str) -> bool:
    return rosgraph_is_legal_name(name) and roscpp_validate(name)


def ros2_topic_oracle(name: str, kind: Kind) -> bool:
    """Runtime acceptance in the root namespace with node 'n', minus rcl's '~X' quirk."""
    if rcl_validate_topic_name(name) is not None:
        return False
    if len(name) == 2 and name[0] == "~":
        return False  # rcl accepts '~a' and makes '<ns>/<node>a' of it; we refuse it
    expanded = rcl_expand_topic_name(name, "n", "/")
    return expanded is not None and rmw_validate_full_topic_name(expanded, LIMITS[kind]) is None


def ros2_namespace_oracle(namespace: str) -> bool:
    if namespace in ("", "/"):
        return True
    absolute = namespace if namespace.startswith("/") else "/" + namespace  # rcl_node_init
    return rmw_validate_namespace(absolute) is None


# ------------------------------------------------------------------------ strategies

PIECES = [
    "a", "b", "Z", "z9", "1", "_", "/", "//", "~", "{", "}", "{node}", "{ns}",
    "{namespace}", "{foo}", "{1x}", "-", ".", " ", "é", "\n", "ab_cd", "x/",
]  # fmt: skip
# Names built from the pieces that make the grammar interesting, and plain random text.
tricky_names = st.lists(st.sampled_from(PIECES), max_size=8).map("".join)
# Mostly-legal ROS 2 names, so that properties about valid names see enough of them.
ROS2_PIECES = ["a", "bc", "x_1", "_h", "/", "~/", "{node}", "{ns}", "{namespace}", "1", "~"]
ros2ish_names = st.lists(st.sampled_from(ROS2_PIECES), min_size=1, max_size=6).map("".join)
any_names = st.one_of(tricky_names, st.text(max_size=20), st.text("a/~{}_1.-", max_size=12))
snake_tokens = st.from_regex(r"[a-z][a-z0-9]{0,5}(_[a-z0-9]{1,4}){0,2}", fullmatch=True)
kinds = st.sampled_from(list(Kind))
generations = st.sampled_from(list(Generation))


# ----------------------------------------------------------------------- table tests


@dataclass(frozen=True)
class C:
    """One table row: the name, where it is judged, and the expected problem (None: fine)."""

    name: str
    kind: Kind
    generation: Generation
    code: str | None = None
    fatal: bool = True
    index: int | None = None
    words: tuple[str, ...] = ()
    suggestion: object = None

    def __str__(self) -> str:
        return f"{self.kind.value}-ros{self.generation.value}-{self.name[:24]!r}"


def _for_kinds(kinds_: tuple[Kind, ...], case: C) -> list[C]:
    return [replace(case, kind=kind) for kind in kinds_]


LONG = "/" + "a" * 299  # 300 characters

DIFFERENCES = [
    # | `_private` | illegal | legal (hidden) |
    *_for_kinds(
        WITH_NS_PARAM,
        C(
            "_private",
            Kind.TOPIC,
            R1,
            "RN101",
            index=0,
            words=("starts with '_'", "ROS 1 rejects", "'/_private'", "'private'"),
            suggestion="private",
        ),
    ),
    *_for_kinds(WITH_NS_PARAM, C("_private", Kind.TOPIC, R2, None)),
    # | `/1robot` | legal | illegal (token starts with a digit) |
    *_for_kinds(WITH_NS_PARAM, C("/1robot", Kind.TOPIC, R1, None)),
    *_for_kinds(
        WITH_NS,
        C(
            "/1robot",
            Kind.TOPIC,
            R2,
            "RN101",
            index=1,
            words=("starts with a digit ('1')", "index 1"),
        ),
    ),
    C("/1robot", Kind.PARAMETER, R2, None),
    # | `a/` | legal, stripped | illegal |
    *_for_kinds(
        WITH_PARAM,
        C(
            "a/",
            Kind.TOPIC,
            R1,
            "RN102",
            fatal=False,
            index=1,
            words=("ends with '/'", "ROS 1 strips it"),
            suggestion="a",
        ),
    ),
    C("a/", Kind.NAMESPACE, R1, None),  # roslaunch writes 'ns/' itself
    *_for_kinds(
        WITH_NS,
        C(
            "a/",
            Kind.TOPIC,
            R2,
            "RN102",
            index=1,
            words=("ends with '/'", "ROS 2 rejects it"),
            suggestion="a",
        ),
    ),
    C("a/", Kind.PARAMETER, R2, None),
    # | `~ab` | `<node>/ab` | illegal, write `~/ab` |
    *_for_kinds(WITH_PARAM, C("~ab", Kind.TOPIC, R1, None)),
    *_for_kinds(
        GRAPH_KINDS,
        C(
            "~ab",
            Kind.TOPIC,
            R2,
            "RN101",
            index=1,
            words=("'~' not followed by '/'", "'~/name'"),
            suggestion="~/ab",
        ),
    ),
    C("~ab", Kind.NAMESPACE, R2, "RN101", index=0, words=("contains '~' at index 0",)),
    C("~ab", Kind.PARAMETER, R2, None),
    # | `{ns}/foo` | illegal | legal inside a namespace, `//foo` (illegal) at the root |
    *_for_kinds(
        WITH_NS_PARAM,
        C("{ns}/foo", Kind.TOPIC, R1, "RN101", index=0, words=("contains '{' at index 0",)),
    ),
    *_for_kinds(
        GRAPH_KINDS,
        C(
            "{ns}/foo",
            Kind.TOPIC,
            R2,
            "RN101",
            index=0,
            words=("'//foo'", "root namespace", "'//'"),
            suggestion="foo",
        ),
    ),
    C("{namespace}/foo", Kind.TOPIC, R2, "RN101", index=0, words=("'//foo'",), suggestion="foo"),
    C("{ns}/foo", Kind.NAMESPACE, R2, "RN101", index=0, words=("contains '{' at index 0",)),
    # | empty | legal (the namespace) | illegal |
    *_for_kinds(WITH_NS_PARAM, C("", Kind.TOPIC, R1, None)),
    *_for_kinds(
        WITH_PARAM, C("", Kind.TOPIC, R2, "RN101", index=None, words=("must not be empty",))
    ),
    C("", Kind.NAMESPACE, R2, None),  # the root namespace
    C("", Kind.NODE, R1, "RN101", words=("must not be empty",)),
    C("", Kind.NODE, R2, "RN101", words=("must not be empty",)),
    C("", Kind.FRAME, R1, "RN101", words=("must not be empty",)),
    C("", Kind.FRAME, R2, "RN101", words=("must not be empty",)),
    # | 300 characters | legal | illegal |
    *_for_kinds(WITH_NS_PARAM, C(LONG, Kind.TOPIC, R1, None)),
    C(LONG, Kind.TOPIC, R2, "RN101", words=("is 300 characters long", "ROS 2 topic is 247")),
    C(LONG, Kind.SERVICE, R2, "RN101", words=("300", "ROS 2 service is 246")),
    C(LONG, Kind.ACTION, R2, "RN101", words=("300", "ROS 2 action is 226")),
    C(LONG, Kind.NAMESPACE, R2, "RN101", words=("300", "ROS 2 namespace is 245")),
    C(LONG, Kind.PARAMETER, R2, None),
    C("a" * 300, Kind.NODE, R1, None),
    C("a" * 300, Kind.NODE, R2, "RN101", words=("300", "ROS 2 node name is 255")),
]

REASONS = [
    # character classes, both generations
    *[
        C(
            "base-driver",
            Kind.TOPIC,
            g,
            "RN101",
            index=4,
            words=("contains '-' at index 4",),
            suggestion="base_driver",
        )
        for g in Generation
    ],
    *[
        C(
            "caméra",
            Kind.TOPIC,
            g,
            "RN101",
            index=3,
            words=("non-ASCII character 'é' at index 3",),
            suggestion="camera",
        )
        for g in Generation
    ],
    *[
        C(
            "my topic",
            Kind.SERVICE,
            g,
            "RN101",
            index=2,
            words=("contains ' ' at index 2",),
            suggestion="my_topic",
        )
        for g in Generation
    ],
    *[C("a\nb", Kind.TOPIC, g, "RN101", index=1, words=(r"'\n'",)) for g in Generation],
    *[
        C("1abc", Kind.TOPIC, g, "RN101", index=0, words=("starts with a digit ('1') at index 0",))
        for g in Generation
    ],
    *[
        C(
            "a//b",
            Kind.TOPIC,
            g,
            "RN101",
            index=1,
            words=("contains '//' at index 1",),
            suggestion="a/b",
        )
        for g in Generation
    ],
    *[
        C(
            "a/b~",
            Kind.TOPIC,
            g,
            "RN101",
            index=3,
            words=("contains '~' at index 3", "only allowed as the first character"),
        )
        for g in Generation
    ],
    # the first problem wins, and RN102 only when the trailing '/' is the only problem
    *[
        C("foo-bar/", Kind.TOPIC, g, "RN101", index=3, words=("'-'",), suggestion="foo_bar")
        for g in Generation
    ],
    *[
        C("a//", Kind.TOPIC, g, "RN101", index=1, words=("'//'",), suggestion="a")
        for g in Generation
    ],
    C("/a/b/", Kind.TOPIC, R1, "RN102", fatal=False, index=4, suggestion="/a/b"),
    C("~/", Kind.TOPIC, R1, "RN102", fatal=False, index=1, suggestion="~"),
    C("~/", Kind.TOPIC, R2, "RN102", index=1, suggestion="~"),
    C("/", Kind.TOPIC, R2, "RN102", index=0, words=("root namespace", "topic name")),
    C("/", Kind.TOPIC, R1, None),
    C("~", Kind.TOPIC, R1, None),
    C("~", Kind.TOPIC, R2, None),  # the node's own name
    # ROS 1 specifics
    C("-a", Kind.TOPIC, R1, "RN101", index=0, words=("contains '-' at index 0",), suggestion="a"),
    C("/_private", Kind.TOPIC, R1, None),
    C("~_private", Kind.PARAMETER, R1, None),
    C("_x-y", Kind.TOPIC, R1, "RN101", index=0, words=("starts with '_'",), suggestion="x_y"),
    C(
        "gains.p",
        Kind.PARAMETER,
        R1,
        "RN101",
        index=5,
        words=("contains '.' at index 5",),
        suggestion="gains/p",
    ),
    C("/ns/", Kind.NAMESPACE, R1, None),
    # ROS 2 '~' rules and rcl's two-character quirk
    C(
        "~a",
        Kind.TOPIC,
        R2,
        "RN101",
        index=1,
        words=("accepted by rcl", "'<ns>/<node>a'", "not a private name", "write '~/a'"),
        suggestion="~/a",
    ),
    C("~1", Kind.TOPIC, R2, "RN101", index=1, words=("accepted by rcl",)),  # '~/1' is bad
    C("~a", Kind.TOPIC, R1, None),
    C(
        "~foo/bar",
        Kind.SERVICE,
        R2,
        "RN101",
        index=1,
        words=("not followed by '/'",),
        suggestion="~/foo/bar",
    ),
    C(
        "~{node}",
        Kind.TOPIC,
        R2,
        "RN101",
        index=1,
        words=("not followed by '/'",),
        suggestion="~/{node}",
    ),
    C("~/foo", Kind.TOPIC, R2, None),
    # ROS 2 substitutions
    C("{node}/cmd", Kind.TOPIC, R2, None),
    C("robot_{node}/cmd", Kind.TOPIC, R2, None),
    C(
        "{foo}/bar",
        Kind.TOPIC,
        R2,
        "RN101",
        index=0,
        words=("unknown substitution '{foo}'", "{node}, {ns} and {namespace}"),
    ),
    C("a/{}", Kind.TOPIC, R2, "RN101", index=2, words=("unknown substitution '{}'",)),
    C("a/{1x}", Kind.TOPIC, R2, "RN101", index=3, words=("substitution", "digit ('1')")),
    C("a/{b-c}", Kind.TOPIC, R2, "RN101", index=4, words=("substitution", "'-' at index 4")),
    C("a/{b/c}", Kind.TOPIC, R2, "RN101", index=4, words=("substitution", "'/' at index 4")),
    C("a/{b~}", Kind.TOPIC, R2, "RN101", index=4, words=("substitution", "'~'")),
    C("a/{b{c}}", Kind.TOPIC, R2, "RN101", index=4, words=("inside another",)),
    C("a}", Kind.TOPIC, R2, "RN101", index=1, words=("unmatched '}'",)),
    C("a/{b", Kind.TOPIC, R2, "RN101", index=2, words=("unclosed '{'",)),
    C("a{ns}", Kind.TOPIC, R2, "RN101", index=1, words=("'/a/'", "ends with '/'")),
    C("{ns}1", Kind.TOPIC, R2, "RN101", index=4, words=("'/1'", "starts with a digit")),
    C("/{ns}", Kind.TOPIC, R2, "RN101", index=1, words=("root namespace",)),
    # a defect made by an expansion points at the substitution, not at a neighbouring '/'
    C("a/{ns}/b", Kind.TOPIC, R2, "RN101", index=2, words=("'/a///b'", "contains '//'")),
    C("~/{ns}/x", Kind.TOPIC, R2, "RN101", index=2, words=("'/<node>///x'",)),
    C("~{", Kind.TOPIC, R2, "RN101", index=1, words=("not followed by '/'",)),
    C("a/1b", Kind.TOPIC, R2, "RN101", index=2, words=("starts with a digit ('1') at index 2",)),
    C("a/1b", Kind.TOPIC, R1, None),
    # ROS 2 length limits: at the limit, one over; relative names are made absolute
    C("/" + "a" * 246, Kind.TOPIC, R2, None),
    C("/" + "a" * 247, Kind.TOPIC, R2, "RN101", words=("248 characters", "247")),
    C("a" * 246, Kind.TOPIC, R2, None),
    C("a" * 247, Kind.TOPIC, R2, "RN101", words=("248", "once made absolute")),
    C("~/" + "a" * 244, Kind.TOPIC, R2, None),  # '/n/' + 244 with the 1-character node
    C("~/" + "a" * 245, Kind.TOPIC, R2, "RN101", words=("248", "root namespace")),
    C("/" + "a" * 245, Kind.SERVICE, R2, None),
    C("/" + "a" * 246, Kind.SERVICE, R2, "RN101", words=("247", "service is 246")),
    C("/" + "a" * 225, Kind.ACTION, R2, None),
    C("/" + "a" * 226, Kind.ACTION, R2, "RN101", words=("227", "action is 226")),
    C("/" + "a" * 244, Kind.NAMESPACE, R2, None),
    C("/" + "a" * 245, Kind.NAMESPACE, R2, "RN101", words=("246", "245")),
    C("a" * 245, Kind.NAMESPACE, R2, "RN101", words=("246", "once made absolute")),
    C("a" * 255, Kind.NODE, R2, None),
    C("a" * 256, Kind.NODE, R2, "RN101", words=("256", "255")),
    # ROS 2 namespaces (relative ones get '/' prepended; indices stay as written)
    C("1robot", Kind.NAMESPACE, R2, "RN101", index=0, words=("starts with a digit",)),
    C("robot/", Kind.NAMESPACE, R2, "RN102", index=5, suggestion="robot"),
    C("/a//b", Kind.NAMESPACE, R2, "RN101", index=2, words=("'//' at index 2",), suggestion="/a/b"),
    C("a//b", Kind.NAMESPACE, R2, "RN101", index=1, words=("'//' at index 1",), suggestion="a/b"),
    C("/a b", Kind.NAMESPACE, R2, "RN101", index=2, words=("' ' at index 2",), suggestion="/a_b"),
    C("/", Kind.NAMESPACE, R2, None),
    C("robot1/arm", Kind.NAMESPACE, R2, None),
    # nodes
    *[
        C(
            "ns/talker",
            Kind.NODE,
            g,
            "RN101",
            index=2,
            words=(
                "'/' at index 2",
                "node names cannot contain '/'",
                "put the prefix in the namespace",
            ),
            suggestion="talker",
        )
        for g in Generation
    ],
    *[C("/talker", Kind.NODE, g, "RN101", index=0, suggestion="talker") for g in Generation],
    *[
        C(
            "~talker",
            Kind.NODE,
            g,
            "RN101",
            index=0,
            words=("cannot contain '~'",),
            suggestion="talker",
        )
        for g in Generation
    ],
    *[
        C("1node", Kind.NODE, g, "RN101", index=0, words=("starts with a digit ('1')",))
        for g in Generation
    ],
    *[
        C("my-node", Kind.NODE, g, "RN101", index=2, words=("'-'",), suggestion="my_node")
        for g in Generation
    ],
    C(
        "_hidden",
        Kind.NODE,
        R1,
        "RN101",
        index=0,
        words=("'_'", "ROS 1 rejects"),
        suggestion="hidden",
    ),
    C("_hidden", Kind.NODE, R2, None),
    C("Talker2", Kind.NODE, R1, None),
    # parameters in ROS 2 are not graph names
    C("controller.gains.p", Kind.PARAMETER, R2, None),
    C("weird name!", Kind.PARAMETER, R2, None),
    # frames
    C(
        "/map",
        Kind.FRAME,
        R1,
        "RN205",
        fatal=False,
        index=0,
        words=("starts with '/'",),
        suggestion="map",
    ),
    C(
        "/map",
        Kind.FRAME,
        R2,
        "RN205",
        index=0,
        words=("starts with '/'", "ROS 2"),
        suggestion="map",
    ),
    C("/", Kind.FRAME, R2, "RN205", index=0),
    *[C("base_link", Kind.FRAME, g, None) for g in Generation],
    *[C("Weird Frame!", Kind.FRAME, g, None) for g in Generation],  # tf2 checks nothing
]


@pytest.mark.parametrize("case", DIFFERENCES + REASONS, ids=str)
def test_check_name_table(case: C) -> None:
    problem = check_name(case.name, case.kind, case.generation)
    if case.code is None:
        assert problem is None
        assert is_valid(case.name, case.kind, case.generation)
        return
    assert problem is not None
    assert (problem.code, problem.fatal, problem.index) == (case.code, case.fatal, case.index)
    for word in case.words:
        assert word in problem.reason
    if case.suggestion is not ANY:
        assert problem.suggestion == case.suggestion
    assert is_valid(case.name, case.kind, case.generation) is not case.fatal


def test_reason_does_not_start_with_name_or_kind() -> None:
    # Rules write f"{kind} name '{name}' {reason}".
    for name in ("_private", "~a", "a/b~", "ns/node", "a-b", "{ns}/foo"):
        for kind in Kind:
            for generation in Generation:
                problem = check_name(name, kind, generation)
                if problem is not None:
                    assert not problem.reason.startswith((f"'{name}'", kind.value))


def test_problem_is_frozen() -> None:
    problem = Problem("RN101", "must not be empty", None, True)
    with pytest.raises(AttributeError):
        problem.code = "RN102"  # type: ignore[misc]


# ------------------------------------------------------------------ tokens and depth


@pytest.mark.parametrize(
    ("name", "kind", "expected"),
    [
        ("/a/b/c", Kind.TOPIC, ["a", "b", "c"]),
        ("a/b", Kind.TOPIC, ["a", "b"]),
        ("~/a/b", Kind.TOPIC, ["a", "b"]),
        ("~a", Kind.TOPIC, ["a"]),
        ("~", Kind.TOPIC, []),
        ("", Kind.TOPIC, []),
        ("/", Kind.NAMESPACE, []),
        ("a//b/", Kind.SERVICE, ["a", "b"]),
        ("{node}/cmd", Kind.TOPIC, ["{node}", "cmd"]),
        ("{ns}/robot_{node}/cmd", Kind.ACTION, ["{ns}", "robot_{node}", "cmd"]),
        ("controller.gains.p", Kind.PARAMETER, ["controller", "gains", "p"]),
        ("~gains/p", Kind.PARAMETER, ["gains", "p"]),
        ("/base_link", Kind.FRAME, ["base_link"]),
        ("odom/base", Kind.FRAME, ["odom/base"]),
        ("", Kind.FRAME, []),
        ("talker", Kind.NODE, ["talker"]),
    ],
)
def test_tokens(name: str, kind: Kind, expected: list[str]) -> None:
    assert tokens(name, kind) == expected
    assert depth(name, kind) == len(expected)


# ------------------------------------------------------------------------ snake_case


@pytest.mark.parametrize(
    ("token", "expected"),
    [
        ("cmd_vel", True),
        ("_hidden", True),
        ("a1", True),
        ("1a", True),
        ("x", True),
        ("{node}", True),
        ("robot_{node}", True),
        ("Cmd_Vel", False),
        ("cmdVel", False),
        ("a__b", False),
        ("a_", False),
        ("_", False),
        ("", False),
        ("__a", False),
        ("a-b", False),
        ("é", False),
        ("{node", False),
        ("a b", False),
    ],
)
def test_is_snake_case(token: str, expected: bool) -> None:
    assert is_snake_case(token) is expected


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("AddTwoInts", "add_two_ints"),
        ("cmdVel", "cmd_vel"),
        ("Cmd_Vel", "cmd_vel"),
        ("HTTPServer", "http_server"),
        ("a__b", "a_b"),
        ("base-driver", "base_driver"),
        ("SetBool", "set_bool"),
        ("_Foo", "_foo"),
        ("__foo", "_foo"),
        ("getHTTPResponseCode", "get_http_response_code"),
        ("Vector3Stamped", "vector3_stamped"),
        ("Point3D", "point3d"),
        ("IMU", "imu"),
        ("cmd vel", "cmd_vel"),
        ("caméra", "camera"),
        ("already_snake", "already_snake"),
        ("_", ""),
        ("", ""),
    ],
)
def test_snake_case(text: str, expected: str) -> None:
    assert snake_case(text) == expected


# ---------------------------------------------------------------------------- resolve


@pytest.mark.parametrize(
    ("name", "generation", "namespace", "node", "expected"),
    [
        ("~x", R1, "/ns", "node", "/ns/node/x"),
        ("~", R1, "/ns", "node", "/ns/node"),
        ("~/x", R1, "/", "talker", "/talker/x"),
        ("x", R1, "ns", None, "/ns/x"),
        ("x", R1, "ns/", None, "/ns/x"),
        ("x/", R1, "/", None, "/x"),
        ("", R1, "/a/b", None, "/a/b"),
        ("", R1, "", None, "/"),
        ("/abs", R1, "/ns", None, "/abs"),
        ("/a//b", R1, "/", None, "/a/b"),  # roscpp collapses it
        ("/", R1, "/ns", None, "/"),
        ("/1robot/x", R1, "/", None, "/1robot/x"),
        ("~", R2, "/ns", "node", "/ns/node"),
        ("~/x", R2, "/", "talker", "/talker/x"),
        ("~/x", R2, "/ns", "talker", "/ns/talker/x"),
        ("x", R2, "", None, "/x"),
        ("x", R2, "robot", None, "/robot/x"),
        ("{node}/x", R2, "/ns", "talker", "/ns/talker/x"),
        ("{ns}/x", R2, "/robot", None, "/robot/x"),  # legal inside a namespace
        ("{namespace}/x", R2, "/robot", None, "/robot/x"),
        ("/abs", R2, "/ns", None, "/abs"),
        ("~a", R2, "/r", "n", "/r/na"),  # what rcl really does with the quirk
        ("_hidden", R2, "/", None, "/_hidden"),
    ],
)
def test_resolve(
    name: str, generation: Generation, namespace: str, node: str | None, expected: str
) -> None:
    assert resolve(name, generation, namespace, node) == expected


@pytest.mark.parametrize(
    ("name", "generation", "namespace", "node", "words"),
    [
        ("_private", R1, "/", None, "starts with '_'"),
        ("a-b", R1, "/", None, "'-'"),
        ("~x", R1, "/", None, "without a node name"),
        ("~x", R1, "/", "my-node", "'-'"),
        ("x", R1, "~ns", None, "private"),
        ("{ns}/x", R1, "/", None, "'{'"),
        ("{ns}/x", R2, "/", None, "'//x'"),
        ("{x}", R2, "/", None, "unknown substitution"),
        ("", R2, "/", None, "empty"),
        ("a/", R2, "/", None, "ends with '/'"),
        ("~/x", R2, "/", None, "without a node name"),
        ("{node}", R2, "/", None, "without a node name"),
        ("1a", R2, "/", None, "digit"),
        ("a//b", R2, "/", None, "'//'"),
        ("x", R2, "a/", None, "ends with '/'"),
        ("x", R2, "/1a", None, "digit"),
        ("~/x", R2, "/", "1n", "digit"),
        ("x", R2, "/", "bad-node", "'-'"),
        ("/" + "a" * 247, R2, "/", None, "longer than 247"),
    ],
)
def test_resolve_errors(
    name: str, generation: Generation, namespace: str, node: str | None, words: str
) -> None:
    with pytest.raises(NameResolutionError, match=re.escape(words)):
        resolve(name, generation, namespace, node)
    assert issubclass(NameResolutionError, ValueError)


@pytest.mark.parametrize("generation", list(Generation))
@pytest.mark.parametrize(
    ("outer", "inner", "expected"),
    [
        ("/", "a", "/a"),
        ("/a", "b", "/a/b"),
        ("/a", "b/c", "/a/b/c"),
        ("/a", "/b", "/b"),
        ("/a", "", "/a"),
        ("", "", "/"),
        ("", "a", "/a"),
        ("a/", "b/", "/a/b"),
        ("/a/", "/", "/"),
        ("/", "/", "/"),
    ],
)
def test_join_namespace(outer: str, inner: str, expected: str, generation: Generation) -> None:
    assert join_namespace(outer, inner, generation) == expected


# --------------------------------------------------------------------------- properties


@given(
    st.lists(snake_tokens, min_size=1, max_size=6),
    st.sampled_from(["", "/", "~/"]),
    st.sampled_from(GRAPH_KINDS),
)
def test_snake_case_tokens_make_valid_names(parts: list[str], prefix: str, kind: Kind) -> None:
    name = prefix + "/".join(parts)
    for generation in Generation:
        assert check_name(name, kind, generation) is None
    assert tokens(name, kind) == parts
    assert all(is_snake_case(part) for part in parts)


ros1_names = st.from_regex(r"[~/A-Za-z]?([A-Za-z][A-Za-z0-9_]{0,4}/?){0,3}", fullmatch=True)
ros1_namespaces = st.from_regex(r"(/?[A-Za-z][A-Za-z0-9_]{0,4}){0,3}/?", fullmatch=True)


@given(ros1_names, ros1_namespaces)
@example("", "/")
@example("~", "ns/")
@example("/", "/")
def test_ros1_resolve_is_canonical_and_idempotent(name: str, namespace: str) -> None:
    assume(is_valid(name, Kind.TOPIC, R1))
    resolved = resolve(name, R1, namespace, "node")
    assert resolved.startswith("/")
    assert "//" not in resolved
    assert resolved == "/" or not resolved.endswith("/")
    assert resolve(resolved, R1, namespace, "node") == resolved
    assert rosgraph_is_legal_name(resolved)
    assert roscpp_validate(resolved)


@given(any_names, kinds, generations)
@settings(max_examples=500)
@example("a-b", Kind.TOPIC, R1)
@example("{ns}1", Kind.TOPIC, R2)
def test_check_name_never_raises_and_points_at_the_culprit(
    name: str, kind: Kind, generation: Generation
) -> None:
    problem = check_name(name, kind, generation)
    if problem is None:
        assert is_valid(name, kind, generation)
        return
    assert problem.code in {"RN101", "RN102", "RN205"}
    assert is_valid(name, kind, generation) is not problem.fatal
    if problem.index is not None:
        assert 0 <= problem.index < len(name)
    _assert_index_matches_reason(name, problem)
    if problem.suggestion is not None:
        assert problem.suggestion != name
        assert check_name(problem.suggestion, kind, generation) is None
    if problem.code == "RN102":
        assert problem.index == len(name) - 1
        assert name.endswith("/")


CONTAINS = re.compile(r"contains (?:non-ASCII character )?(.+?) at index (\d+)")
DIGIT = re.compile(r"starts with a digit \((.+?)\) at index (\d+)")


def _assert_index_matches_reason(name: str, problem: Problem) -> None:
    """For character-class reasons the quoted character is really at the reported index."""
    for pattern in (CONTAINS, DIGIT):
        match = pattern.search(problem.reason)
        if match is None:
            continue
        quoted, at = match.group(1), int(match.group(2))
        assert at == problem.index
        if quoted == "'//'":
            assert name[at : at + 2] == "//"
        else:
            assert repr(name[at]) == quoted
        if pattern is DIGIT:
            assert name[at] in string.digits
        return
    if "unclosed '{'" in problem.reason or "unknown substitution" in problem.reason:
        assert problem.index is not None
        assert name[problem.index] == "{"
    if problem.code in {"RN102", "RN205"}:
        assert problem.index is not None
        assert name[problem.index] == "/"


@given(st.text(string.ascii_letters + string.digits + "_-", max_size=24))
@example("_")
@example("__A__b__")
def test_snake_case_output_is_snake_case(text: str) -> None:
    result = snake_case(text)
    if result:
        assert is_snake_case(result)
        assert snake_case(result) == result
    else:
        assert not any(char.isalnum() for char in text)


@given(snake_tokens | st.from_regex(r"_[a-z0-9]{1,4}(_[a-z0-9]{1,3})?", fullmatch=True))
def test_snake_case_keeps_snake_case_tokens(token: str) -> None:
    assert is_snake_case(token)
    assert snake_case(token) == token


@given(ros2ish_names)
@settings(max_examples=500)
@example("{ns}/foo")
@example("~/x")
def test_ros2_valid_topic_resolves_in_a_namespace(name: str) -> None:
    assume(is_valid(name, Kind.TOPIC, R2))
    resolved = resolve(name, R2, "/robot1", "n")
    assert rmw_validate_full_topic_name(resolved) is None


@given(any_names)
@settings(max_examples=500)
@example("/a//b")
@example("a/")
@example("é")
def test_ros1_agrees_with_rosgraph_and_roscpp(name: str) -> None:
    for kind in WITH_PARAM:
        assert is_valid(name, kind, R1) is ros1_oracle(name)
    # namespaces: the same grammar; a trailing '/' is not even a warning
    assert is_valid(name, Kind.NAMESPACE, R1) is ros1_oracle(name)
    if name.endswith("/") and len(name) > 1 and ros1_oracle(name):
        problem = check_name(name, Kind.TOPIC, R1)
        assert problem is not None
        assert problem.code == "RN102"
        assert check_name(name, Kind.NAMESPACE, R1) is None
    expected_node = rosgraph_is_legal_base_name(name) and name.isascii()
    assert is_valid(name, Kind.NODE, R1) is expected_node


@given(st.one_of(any_names, st.builds("/{}".format, any_names)))
@settings(max_examples=800)
@example("~a")
@example("{ns}")
@example("~/{ns}")
@example("a/{b}c{node}")
def test_ros2_agrees_with_rcl_and_rmw(name: str) -> None:
    assume("\x00" not in name)  # C would stop reading there
    for kind in GRAPH_KINDS:
        assert is_valid(name, kind, R2) is ros2_topic_oracle(name, kind)
    assert is_valid(name, Kind.NAMESPACE, R2) is ros2_namespace_oracle(name)
    assert is_valid(name, Kind.NODE, R2) is (rmw_validate_node_name(name) is None)


@given(st.integers(min_value=1, max_value=270), st.sampled_from(["", "/", "~/"]))
def test_ros2_length_limits_agree_with_rmw(size: int, prefix: str) -> None:
    name = prefix + "a" * size
    for kind in GRAPH_KINDS:
        assert is_valid(name, kind, R2) is ros2_topic_oracle(name, kind)
    assert is_valid(name, Kind.NODE, R2) is (rmw_validate_node_name(name) is None)
    if prefix != "~/":
        assert is_valid(name, Kind.NAMESPACE, R2) is ros2_namespace_oracle(name)


@given(tricky_names | ros2ish_names, st.sampled_from(["/", "/robot1", "robot1/arm", ""]))
@settings(max_examples=500)
@example("~a", "/r")
@example("{ns}/x", "/")
def test_ros2_resolve_agrees_with_rcl_expand(name: str, namespace: str) -> None:
    absolute_ns = "/" + namespace.strip("/")
    expected: str | None = None
    if rcl_validate_topic_name(name) is None:
        expanded = rcl_expand_topic_name(name, "talker", absolute_ns)
        if expanded is not None and rmw_validate_full_topic_name(expanded) is None:
            expected = expanded
    if expected is None:
        with pytest.raises(NameResolutionError):
            resolve(name, R2, namespace, "talker")
    else:
        assert resolve(name, R2, namespace, "talker") == expected


@given(ros1_namespaces, ros1_namespaces, generations)
def test_join_namespace_properties(outer: str, inner: str, generation: Generation) -> None:
    joined = join_namespace(outer, inner, generation)
    assert joined.startswith("/")
    assert "//" not in joined
    assert joined == "/" or not joined.endswith("/")
    if inner.startswith("/"):
        assert joined == join_namespace("/", inner, generation)
    else:
        assert joined.startswith(join_namespace("/", outer, generation).rstrip("/"))
        assert tokens(joined, Kind.NAMESPACE) == tokens(outer, Kind.NAMESPACE) + tokens(
            inner, Kind.NAMESPACE
        )


@given(any_names, kinds)
def test_depth_is_token_count(name: str, kind: Kind) -> None:
    parts = tokens(name, kind)
    assert depth(name, kind) == len(parts)
    assert all(parts)
    if kind is not Kind.FRAME and "{" not in name:
        assert all("/" not in part for part in parts)
