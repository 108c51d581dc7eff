"""The Python extractor on rospy, actionlib, tf and rclpy code: names, spans, events.

Fixtures in ``fixtures/python/`` follow ros_tutorials (rospy_tutorials), actionlib
tutorials, the turtle tf tutorials and ros2/demos; the short sources below pin one
behaviour each, pyflakes style.
"""

from __future__ import annotations

import gc
import subprocess
import sys
import warnings
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from roslint_names.extract.python.extract import extract, may_hold_names
from roslint_names.model import EventKind, FileFacts, Generation, Language, NameUse

FIXTURES = Path(__file__).parent / "fixtures" / "python"
ROS1, ROS2 = Generation.ROS1, Generation.ROS2

Use = tuple[str, str, str, "str | None", int, int]


def facts_of(
    source: str | bytes, path: str = "node.py", ros: Generation | None = None
) -> FileFacts:
    data = source.encode() if isinstance(source, str) else source
    return extract(path, data, ros, ROS2)


def fixture(name: str, ros: Generation | None = None) -> FileFacts:
    return extract(f"fixtures/python/{name}", (FIXTURES / name).read_bytes(), ros, ROS2)


def brief(use: NameUse) -> Use:
    """(kind, role, value, type, line, column): what most assertions look at."""
    return (
        use.kind.value,
        use.role.value,
        use.value,
        use.type_name,
        use.span.line,
        use.span.column,
    )


def uses(facts: FileFacts) -> list[Use]:
    return [brief(use) for use in facts.names if not use.dynamic]


def values(source: str, ros: Generation | None = None) -> list[str]:
    return [use.value for use in facts_of(source, ros=ros).names if not use.dynamic]


def dynamic(facts: FileFacts) -> list[str]:
    return [use.value for use in facts.names if use.dynamic]


def events(facts: FileFacts) -> list[tuple[str, str, str, int, int]]:
    return [
        (event.kind.value, event.api, event.scope, event.span.line, event.span.column)
        for event in facts.events
    ]


# ---------------------------------------------------------------------------------------
# rospy, actionlib, tf (ros_tutorials style fixtures)


def test_talker_publisher_node_and_private_parameter() -> None:
    facts = fixture("talker.py")
    assert facts.language is Language.PYTHON
    assert facts.generation is ROS1  # rospy, no package.xml
    assert uses(facts) == [
        ("topic", "publish", "chatter", "std_msgs.msg.String", 10, 27),
        ("node", "node-name", "talker", None, 11, 21),
        ("parameter", "parameter", "~rate", None, 12, 39),
    ]
    assert facts.names[0].api == "rospy.Publisher"


def test_listener_through_import_aliases() -> None:
    """``import rospy as rp`` and ``String as StringMsg`` resolve to rospy and std_msgs."""
    assert uses(fixture("listener.py")) == [
        ("node", "node-name", "listener", None, 11, 18),
        ("topic", "subscribe", "chatter", "std_msgs.msg.String", 12, 19),
    ]


def test_add_two_ints_server_star_import_and_constant_node_name() -> None:
    """The type comes through ``from rospy_tutorials.srv import *``; a constant node
    name is folded and points at the identifier at the call site."""
    assert uses(fixture("add_two_ints_server.py")) == [
        ("node", "node-name", "add_two_ints_server", None, 14, 21),
        ("service", "serve", "add_two_ints", "rospy_tutorials.srv.AddTwoInts", 15, 23),
    ]


def test_add_two_ints_client_waits_and_calls() -> None:
    assert uses(fixture("add_two_ints_client.py")) == [
        ("service", "call", "add_two_ints", None, 12, 28),
        ("service", "call", "add_two_ints", "rospy_tutorials.srv.AddTwoInts", 14, 43),
    ]


def test_actionlib_client() -> None:
    assert uses(fixture("fibonacci_client.py")) == [
        ("action", "action-call", "fibonacci", "actionlib_tutorials.msg.FibonacciAction", 8, 43),
        ("node", "node-name", "fibonacci_client_py", None, 18, 25),
    ]


def test_tf_frames_from_send_transform_header_and_lookups() -> None:
    facts = fixture("turtle_tf_broadcaster.py")
    frames = [
        (use.value, use.api, use.span.line) for use in facts.names if use.kind.value == "frame"
    ]
    assert frames == [
        ("world", "tf sendTransform", 17),
        ("/world", ".frame_id =", 24),
        ("carrot1", ".child_frame_id =", 25),
        ("turtle2", "tf lookup_transform", 30),
        ("turtle1", "tf lookup_transform", 30),
    ]
    assert dynamic(facts) == ['"/%s/pose" % turtlename']  # a parameter's value: dynamic


# ---------------------------------------------------------------------------------------
# rclpy (ros2/demos style fixture)


def test_rclpy_node_subclass_every_site() -> None:
    facts = fixture("dock_controller.py")
    assert facts.generation is ROS2
    assert uses(facts) == [
        ("node", "node-name", "dock_controller", None, 19, 26),
        ("namespace", "namespace", "docking", None, 19, 55),
        ("topic", "publish", "/cmd_vel", "geometry_msgs.msg.Twist", 21, 53),
        ("topic", "publish", "status/twist", "geometry_msgs.msg.Twist", 24, 13),
        ("service", "serve", "robot1/dock", "std_srvs.srv.Trigger", 28, 54),
        ("service", "call", "motor/enable", "std_srvs.srv.SetBool", 29, 67),
        ("parameter", "parameter", "base_frame", None, 30, 32),
        ("frame", "frame", "base_link", None, 30, 46),  # a frame parameter's default
        ("parameter", "parameter", "gains.kp", None, 33, 26),
        ("parameter", "parameter", "gains.ki", None, 33, 39),
        ("action", "action-serve", "fibonacci", "example_interfaces.action.Fibonacci", 35, 60),
    ]
    assert dynamic(facts) == ['topic_prefix + "/odom"']  # a constructor argument


def test_rclpy_events_init_then_subclass_instance() -> None:
    assert events(fixture("dock_controller.py")) == [
        ("init", "rclpy.init", "main", 50, 5),
        ("handle", "DockController (an rclpy Node)", "main", 51, 12),
        # main() initialises where it is called: module-level code above it runs first
        ("init", "rclpy.init (in main())", "", 58, 5),
    ]


def test_rclpy_sites_keyword_forms() -> None:
    source = """
import rclpy
from rclpy.action import ActionClient
from std_msgs.msg import String
from example_interfaces.action import Fibonacci

rclpy.init()
node = rclpy.create_node(node_name="kw_node", namespace="/fleet")
node.create_publisher(msg_type=String, topic="chatter", qos_profile=10)
node.create_subscription(String, topic="heard", callback=print, qos_profile=10)
client = ActionClient(node, action_type=Fibonacci, action_name="fib")
node.get_parameter("rate")
node.get_parameters(["a", "b"])
"""
    assert values(source) == ["kw_node", "/fleet", "chatter", "heard", "fib", "rate", "a", "b"]


def test_rclpy_lifecycle_and_old_style_init() -> None:
    source = """
from rclpy.lifecycle import LifecycleNode
from rclpy.node import Node

class Managed(LifecycleNode):
    def __init__(self):
        super().__init__("managed")

class OldStyle(Node):
    def __init__(self):
        Node.__init__(self, "old_style")
"""
    assert values(source) == ["managed", "old_style"]


def test_super_init_of_a_base_with_its_own_signature_is_not_a_node_name() -> None:
    source = """
from rclpy.node import Node

class Base(Node):
    def __init__(self, topic):
        super().__init__("base")
        self.create_publisher(String, topic, 10)

class Derived(Base):
    def __init__(self):
        super().__init__("cmd_vel")  # Base's topic, not a node name

class Plain(Base):
    pass

class Leaf(Plain):
    def __init__(self):
        super().__init__("still_topic")
"""
    facts = facts_of(source)
    assert [(use.kind.value, use.value) for use in facts.names if not use.dynamic] == [
        ("node", "base")
    ]


def test_create_publisher_on_unknown_receivers_needs_rclpy_shapes() -> None:
    """``self.node.create_publisher`` counts in rclpy code; an argument shape that is not
    rclpy's (a string where the type goes) does not."""
    source = """
import rclpy
from std_msgs.msg import String

class Helper:
    def __init__(self, node):
        self.pub = node.create_publisher(String, "helper_out", 10)
        self.other = node.create_publisher("not_a_type", "x", 10)
"""
    assert values(source) == ["helper_out"]
    ros1 = "import rospy\nfrom std_msgs.msg import String\nthing.create_publisher(String, 'x', 1)\n"
    assert values(ros1, ros=ROS1) == []  # ROS 1 code without rclpy: not a node method


def test_names_are_resolved_not_spelled() -> None:
    """A local ``Publisher`` class, an unimported ``rospy``, a rebinding: no rospy site."""
    source = """
import std_msgs.msg

class Publisher:
    def __init__(self, name, kind):
        pass

Publisher("not_ros", std_msgs.msg.String)
rospy.Publisher("unimported", std_msgs.msg.String)
"""
    assert values(source) == []


def test_from_rospy_imports_and_submodules() -> None:
    source = """
from rospy import Publisher, init_node
import rospy.client
from std_msgs.msg import Empty

init_node("direct")
Publisher("out", Empty, queue_size=1)
rospy.client.get_param("deep")
"""
    assert values(source) == ["direct", "out", "deep"]


# ---------------------------------------------------------------------------------------
# Constants: folded when static, dynamic otherwise


@pytest.mark.parametrize(
    ("snippet", "expected"),
    [
        ('TOPIC = "/cmd_vel"\nrospy.Publisher(TOPIC, Twist)', "/cmd_vel"),
        ('NS = "robot"\nTOPIC = NS + "/cmd_vel"\nrospy.Publisher(TOPIC, Twist)', "robot/cmd_vel"),
        ('NS = "robot"\nrospy.Publisher(f"{NS}/cmd_vel", Twist)', "robot/cmd_vel"),
        ('NS = "robot"\nrospy.Publisher(f"{NS!s}/odom", Twist)', "robot/odom"),
        ('rospy.Publisher("%s/%s" % ("a", "b"), Twist)', "a/b"),
        ('rospy.Publisher("cmd" "_vel", Twist)', "cmd_vel"),
        ('rospy.Publisher(r"raw", Twist)', "raw"),
        ('rospy.Publisher(f"{{braces}}", Twist)', "{braces}"),
        ('rospy.Publisher(("paren"), Twist)', "paren"),
    ],
)
def test_folded(snippet: str, expected: str) -> None:
    source = f"import rospy\nfrom geometry_msgs.msg import Twist\n{snippet}\n"
    facts = facts_of(source)
    assert [(use.value, use.dynamic) for use in facts.names] == [(expected, False)]


@pytest.mark.parametrize(
    "snippet",
    [
        'rospy.Publisher("cmd\\ud800vel", Twist)',
        'rospy.Publisher(f"cmd\\udc80vel", Twist)',
        'NS = "cmd"\nrospy.Publisher(f"{NS}\\U0000dfffvel", Twist)',
    ],
)
def test_surrogate_escape_stands_for_a_replacement_character(snippet: str) -> None:
    """A lone surrogate is no character, and no report (all UTF-8) can print it: the CLI
    exited 2 with a UnicodeEncodeError. It stands for U+FFFD; the name stays illegal."""
    source = f"import rospy\nfrom geometry_msgs.msg import Twist\n{snippet}\n"
    facts = facts_of(source)
    assert [(use.value, use.dynamic) for use in facts.names] == [("cmd\ufffdvel", False)]


@pytest.mark.parametrize(
    "snippet",
    [
        'TOPIC = "a"\nTOPIC = "b"\nrospy.Publisher(TOPIC, Twist)',  # assigned twice
        'TOPIC = "a"\nTOPIC += "b"\nrospy.Publisher(TOPIC, Twist)',
        "def f(topic='cmd'):\n    rospy.Publisher(topic, Twist)",  # a parameter
        "rospy.Publisher(get_topic(), Twist)",
        "rospy.Publisher(self.topic, Twist)",
        'X = 3\nrospy.Publisher(f"{X:02d}", Twist)',  # formatted: not reproduced
        'rospy.Publisher("%d" % 3, Twist)',
        'rospy.Publisher(b"bytes", Twist)',
        'topic = "outer"\n[rospy.Publisher(topic, Twist) for topic in ["a", "b"]]',
        'def f():\n    global TOPIC\n    TOPIC = "b"\nTOPIC = "a"\nrospy.Publisher(TOPIC, Twist)',
        "for TOPIC in ('a', 'b'):\n    rospy.Publisher(TOPIC, Twist)",
    ],
)
def test_dynamic(snippet: str) -> None:
    source = f"import rospy\nfrom geometry_msgs.msg import Twist\n{snippet}\n"
    assert [use.dynamic for use in facts_of(source).names] == [True]


def test_function_constant_shadows_module_constant() -> None:
    source = """
import rospy
from std_msgs.msg import String
TOPIC = "module"

def node():
    TOPIC = "local"
    rospy.Publisher(TOPIC, String)

rospy.Subscriber(TOPIC, String)
"""
    assert values(source) == ["local", "module"]


# ---------------------------------------------------------------------------------------
# RN301 events


def test_early_module_level_endpoints_only_when_rospy_needs_init() -> None:
    """rospy accepts topics before init_node unless ~private; services and get_param
    resolve without the node's remappings there, so they always need it first."""
    assert events(fixture("early_endpoints.py")) == [
        ("handle", "rospy.Publisher", "", 8, 13),  # '~debug'
        ("handle", "rospy.Service", "", 9, 13),
        ("handle", "rospy.get_param", "", 10, 8),
        ("init", "rospy.init_node", "", 18, 5),  # __main__ block: module level
    ]


def test_tutorial_talker_publisher_before_init_node_is_no_event() -> None:
    """Regression: rospy_tutorials' talker creates its publisher before init_node, which
    rospy supports (topics.py); it was reported as RN301."""
    assert [event[1] for event in events(fixture("talker.py"))] == [
        "rospy.init_node",
        "rospy.get_param",
        "rospy.init_node (in talker())",
    ]


def test_event_scopes_and_order() -> None:
    source = """
import rclpy
from rclpy.node import Node

def main():
    node = Node("early")
    rclpy.init()

class Holder:
    def method(self):
        self.node = rclpy.create_node("in_method")

def main():
    rclpy.init()
    helper = lambda: Node("later")
"""
    found = [(kind, api, scope) for kind, api, scope, _, _ in events(facts_of(source))]
    assert found == [
        ("handle", "rclpy.node.Node", "main"),
        ("init", "rclpy.init", "main"),
        ("handle", "rclpy.create_node", "Holder.method"),
        ("init", "rclpy.init", "main#2"),
        ("handle", "rclpy.node.Node", "main.<lambda>"),
    ]
    orders = [event.order for event in facts_of(source).events]
    assert orders[0] < orders[1]


def test_names_in_expected_failures_are_skipped() -> None:
    """rclpy's tests feed illegal names inside ``assertRaises``: they are meant wrong."""
    source = """
import pytest
import rclpy
from std_msgs.msg import String

def test(node, self):
    with pytest.raises(ValueError):
        node.create_publisher(String, "chatter?", 1)
    with self.assertRaises(ValueError):
        rclpy.create_node("bad name")
    node.create_publisher(String, "good", 1)
"""
    assert values(source) == ["good"]


def test_a_keyword_frame_of_a_lookup_is_one_fact() -> None:
    source = "import tf2_ros\nbuffer.lookup_transform(target_frame='map', source_frame='odom')\n"
    assert values(source) == ["map", "odom"]


def test_frames_empty_header_is_no_frame_but_empty_lookup_is() -> None:
    """Regression: ``header.frame_id = ''`` (moveit servo) means "no frame" and was
    reported as an empty, illegal frame id; an empty lookup target is still checked."""
    source = """
import rclpy
from std_msgs.msg import Header
msg.header.frame_id = ''
buffer.lookup_transform('', 'base_link', now)
Header(frame_id='odom')
self.base_frame = 'base_link'
self.frame = 'not_a_tf_frame'
"""
    assert values(source) == ["", "base_link", "odom", "base_link"]


# ---------------------------------------------------------------------------------------
# Spans


def test_span_of_a_literal_in_a_multi_line_call() -> None:
    source = "import rospy\nfrom std_msgs.msg import String\n"
    source += 'pub = rospy.Publisher(\n    "a/b",\n    String,\n)\n'
    (use,) = facts_of(source).names
    assert (use.span.line, use.span.column, use.span.end_line, use.span.end_column) == (4, 5, 4, 10)


def test_span_after_non_ascii_text_counts_code_points() -> None:
    source = 'import rospy\nx = "é€😀"; rospy.init_node("nœud")\n'
    (use,) = facts_of(source).names
    assert use.value == "nœud"
    assert (use.span.line, use.span.column, use.span.end_column) == (2, 28, 34)


def test_span_with_crlf_line_endings() -> None:
    source = "import rospy\r\n\r\nrospy.init_node(\r\n  'crlf')\r\n"
    (use,) = facts_of(source).names
    assert (use.span.line, use.span.column, use.span.end_column) == (4, 3, 9)


def test_span_of_prefixed_and_folded_strings() -> None:
    source = """import rospy
NAME = "n"
rospy.init_node(f"{NAME}_one")
rospy.init_node(rb"x" if False else NAME)
rospy.init_node(NAME)
rospy.init_node( ( "paren" ) )
"""
    found = [
        (use.value, use.dynamic, use.span.column, use.span.end_column)
        for use in facts_of(source).names
    ]
    assert found == [
        ("n_one", False, 17, 30),  # from the f, after the closing quote
        ('rb"x" if False else NAME', True, 17, 41),
        ("n", False, 17, 21),  # the identifier at the call site
        ("paren", False, 20, 27),  # the literal inside its parentheses
    ]


def test_span_of_repeated_identical_lines_comes_from_libcst() -> None:
    """Two byte-identical statements cannot be told apart by their text: each still gets
    its own line (``PositionProvider`` places them)."""
    source = (
        "import rospy\ndef a():\n    rospy.init_node('x')\ndef b():\n    rospy.init_node('x')\n"
    )
    assert [use.span.line for use in facts_of(source).names] == [3, 5]


def test_spans_of_identical_lines_in_methods_under_comments() -> None:
    """The same line in two methods and a nested function, each under a comment: placed
    inside its own method (written one indentation out), not the whole class."""
    source = """\
import rospy
from std_msgs.msg import String


class Relay(object):
    def start(self):
        # advertise once the node is up
        self.pub = rospy.Publisher("chatter", String, queue_size=10)

    def restart(self):

    # a comment left of the block
        self.pub = rospy.Publisher("chatter", String, queue_size=10)

        def again():
            # and once more, a level deeper
            self.pub = rospy.Publisher("chatter", String, queue_size=10)

        again()
"""
    facts = facts_of(source, ros=ROS1)
    assert [(use.value, use.span.line, use.span.column) for use in facts.names] == [
        ("chatter", 8, 36),
        ("chatter", 13, 36),
        ("chatter", 17, 40),
    ]


def test_span_inside_a_parenthesised_with_statement() -> None:
    """Regression: a top-level ``with (...)`` holds one ``LeftParen``, not a list of them,
    and placing a repeated literal inside it raised TypeError."""
    source = (
        "import rospy\n"
        "with (open('a') as a, open('b') as b):\n"
        "    msg.header.frame_id = 'map'\n"
        "    msg.header.frame_id = 'map'\n"
    )
    assert [use.span.line for use in facts_of(source).names] == [3, 4]


def test_spans_inside_indented_multi_line_calls_with_comments() -> None:
    source = """from launch import LaunchDescription
from launch_ros.actions import Node

def generate_launch_description():
    return LaunchDescription([
        Node(
            package='rviz2',  # the same text three times
            executable='rviz2',
            name='rviz2'),
    ])
"""
    (use,) = facts_of(source, "view.launch.py").names
    assert (use.value, use.span.line, use.span.column) == ("rviz2", 9, 18)


# ---------------------------------------------------------------------------------------
# Decoding, parse errors, prefilter, language and generation


def test_python2_file_is_one_parse_error_with_cpython_position() -> None:
    facts = facts_of("import rospy\nprint 'hello'\n")
    (error,) = facts.parse_errors
    assert error.message.startswith("not valid Python 3: Missing parentheses in call to 'print'")
    assert (error.span.line, error.span.column) == (2, 1)
    assert facts.names == ()


def test_undecodable_and_declared_encodings() -> None:
    latin1 = "# -*- coding: latin-1 -*-\nimport rospy\nrospy.init_node('n') # café\n"
    assert values(latin1.encode("latin-1").decode("latin-1")) == ["n"]
    assert [use.value for use in facts_of(latin1.encode("latin-1")).names] == ["n"]
    (error,) = facts_of(b"import rospy\nx = '\xff'\n").parse_errors
    assert "cannot decode" in error.message and error.span.line == 2
    (error,) = facts_of(b"# coding: klingon\nimport rospy\n").parse_errors
    assert "unknown source encoding" in error.message
    bom = b"\xef\xbb\xbfimport rospy\nrospy.init_node('bom')\n"
    (use,) = facts_of(bom).names
    assert (use.value, use.span.column) == ("bom", 17)
    # CPython refuses a UTF-8 BOM before a declaration of another encoding; so do we.
    contradiction = b"\xef\xbb\xbf# -*- coding: latin-1 -*-\nimport rospy\n"
    (error,) = facts_of(contradiction).parse_errors
    assert "UTF-8 BOM contradicts the coding declaration 'latin-1'" in error.message


def test_encoding_that_decodes_to_a_lone_surrogate_is_one_parse_error() -> None:
    """``unicode_escape`` turns ``\\ud800`` in the code into a lone surrogate, which libcst's
    parser cannot encode (a UnicodeEncodeError escaped the extractor); CPython refuses such
    a file too."""
    source = b"# coding: unicode_escape\nimport rospy\nx = 1\nnode\\ud800 = rospy.init_node('n')\n"
    facts = facts_of(source)
    (error,) = facts.parse_errors
    assert error.message == (
        "cannot decode Python source as unicode_escape: "
        "it gives a lone surrogate (U+D800), which is no character"
    )
    assert (error.span.line, error.span.column) == (4, 5)
    assert facts.names == ()


def test_null_byte_is_one_parse_error_where_it_is() -> None:
    """libcst parses a NUL in a string (the name was then silently dynamic); CPython
    refuses the whole file."""
    facts = facts_of("import rospy\nrospy.init_node('talker')\nrospy.Publisher('a\0b', X)\n")
    (error,) = facts.parse_errors
    assert error.message == "not valid Python 3: source code cannot contain null bytes"
    assert (error.span.line, error.span.column) == (3, 19)
    assert facts.names == ()


@pytest.mark.parametrize(
    "source",
    [
        "import rospy\nok = 1 if 1else 2\ny = )\n",  # broken: CPython is asked where
        'import rospy\nBANNER = "' + "(" * 201 + '"\nok = 1 if 1else 2\n',  # deep-looking
    ],
)
def test_cpython_syntax_warnings_are_not_printed(source: str) -> None:
    """CPython's tokenizer warns ("invalid decimal literal") on its way; asked by the
    extractor (where a file breaks, or first when it looks too deep for libcst), it printed
    the warning on the user's terminal."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        facts_of(source)
    assert [str(warning.message) for warning in caught] == []


def test_invalid_escape_warnings_are_not_printed() -> None:
    """Folding ``"a\\d"`` evaluates it: Python 3.12 printed "SyntaxWarning: invalid escape
    sequence '\\d'" on the user's terminal (3.11 warns too, hidden by default)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        found = values('import rospy\nrospy.Publisher("a\\d", X)\nrospy.Publisher(f"b\\d", X)\n')
    assert found == ["a\\d", "b\\d"]
    assert [str(warning.message) for warning in caught] == []


def test_string_joined_to_a_template_string_is_one_parse_error() -> None:
    """libcst reads t-strings (PEP 750) but raises CSTLogicError on ``"a" t"b"``, which
    escaped the extractor (found by atheris); CPython refuses it too."""
    facts = facts_of('import rospy\nrospy.init_node("a" t"b")\n')
    (error,) = facts.parse_errors
    assert error.message.startswith("not valid Python 3: ")
    assert error.span.line == 2


def test_prefilter_skips_files_without_ros() -> None:
    assert not may_hold_names(b"import os\nprint('/cmd_vel')\n")
    assert may_hold_names(b"import os, rospy\n")
    assert may_hold_names(b"    from geometry_msgs.msg import Twist\n")
    assert may_hold_names(b"def generate_launch_description():\n")
    facts = facts_of(b"import os\nprint 'not even python 3'\n")
    assert facts.parse_errors == () and facts.names == ()


def test_prefiltered_run_does_not_import_libcst(tmp_path: Path) -> None:
    script = (
        "import sys\n"
        "from roslint_names.extract.python.extract import extract\n"
        "from roslint_names.model import Generation\n"
        "extract('a.py', b'import numpy\\n', None, Generation.ROS2)\n"
        "assert 'libcst' not in sys.modules\n"
        "extract('b.py', b'import rospy\\n', None, Generation.ROS2)\n"
        "assert 'libcst' in sys.modules\n"
    )
    subprocess.run([sys.executable, "-c", script], check=True, cwd=tmp_path)


def test_language_and_generation() -> None:
    assert facts_of("import rclpy\n", "bringup.launch.py").language is Language.LAUNCH_PYTHON
    assert facts_of("import rclpy\n", "nav_launch.py").language is Language.LAUNCH_PYTHON
    launch = "from launch import LaunchDescription\ndef generate_launch_description():\n    pass\n"
    assert facts_of(launch, "anything.py").language is Language.LAUNCH_PYTHON
    assert facts_of("import rospy\n").generation is ROS1
    assert facts_of("import rospy\n", ros=ROS2).generation is ROS2  # the package wins
    assert facts_of("import std_msgs.msg\n").generation is ROS2  # the fallback


# ---------------------------------------------------------------------------------------
# Through the CLI: rules on Python facts


def test_rules_on_python_through_the_cli(lint_text: Any) -> None:
    source = """import rospy
from std_srvs.srv import SetBool

if __name__ == '__main__':
    rospy.init_node('motorDriver')
    rospy.Service('SetBool', SetBool, lambda request: None)
    rospy.Publisher('/cmd_vel', Twist, queue_size=1)  # noqa: RN202
    rospy.Subscriber('scan/', LaserScan)
"""
    codes = lint_text(source, "src/driver/scripts/driver.py", 1, "--select", "ALL")
    assert sorted(codes) == ["RN102", "RN203", "RN204"]


def test_rn301_from_python_through_the_cli(lint_text: Any) -> None:
    source = "import rclpy\nfrom rclpy.node import Node\nnode = Node('early')\nrclpy.init()\n"
    assert lint_text(source, "src/pkg/pkg/early.py", 2) == ["RN301"]


# ---------------------------------------------------------------------------------------
# Never raises


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.binary(max_size=400))
def test_random_bytes_never_raise(data: bytes) -> None:
    for prefix in (b"", b"import rospy\n", b"import rclpy\nfrom launch import LaunchDescription\n"):
        facts = extract("fuzz.py", prefix + data, None, ROS2)
        assert isinstance(facts, FileFacts)


ALL_FIXTURES = sorted(FIXTURES.glob("*.py"))


@settings(max_examples=200, deadline=None)
@given(st.sampled_from(ALL_FIXTURES), st.integers(min_value=0, max_value=4000), st.data())
def test_truncated_and_spliced_fixtures_never_raise(path: Path, cut: int, data: Any) -> None:
    text = path.read_bytes()
    noise = data.draw(st.binary(max_size=20))
    for mangled in (text[:cut], text[:cut] + noise + text[cut:]):
        facts = extract(path.name, mangled, None, ROS2)
        assert isinstance(facts, FileFacts)
        for use in facts.names:
            assert 1 <= use.span.line <= use.span.end_line
        for event in facts.events:
            assert event.kind in (EventKind.INIT, EventKind.HANDLE)


@pytest.mark.parametrize(
    "expression",
    ["[" * 3000 + "]" * 3000, "-" * 30000 + "1", "not " * 30000 + "a", "lambda: " * 30000 + "1"],
)
def test_nesting_that_crashes_libcst_is_a_parse_error(expression: str) -> None:
    """libcst's native parser dies (SIGSEGV) on these; CPython refuses them cleanly."""
    (error,) = facts_of(f"import rospy\nx = {expression}\n").parse_errors
    assert error.message.startswith("not valid Python 3")


def test_brackets_in_strings_do_not_make_a_file_too_deep() -> None:
    source = "import rospy\nART = '" + "(" * 300 + "'\nrospy.init_node('n')\n"
    assert values(source) == ["n"]


# message_filters.Subscriber takes rospy's arguments in ROS 1 and (node, type, topic) in
# ROS 2 (recall issue, cause 4): a stereo pair synchronised by time, in both generations.
STEREO_SYNC_ROS1 = """#!/usr/bin/env python
import message_filters
import rospy
from sensor_msgs.msg import CameraInfo, Image

rospy.init_node("stereo_sync")
left = message_filters.Subscriber("/stereo/left/image_raw", Image)
info = message_filters.Subscriber("left/camera_info", CameraInfo)
sync = message_filters.ApproximateTimeSynchronizer([left, info], 10, 0.1)
"""
STEREO_SYNC_ROS2 = """import message_filters
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import CameraInfo, Image


class StereoSync(Node):
    def __init__(self):
        super().__init__("stereo_sync")
        left = message_filters.Subscriber(self, Image, "/stereo/left/image_raw")
        info = message_filters.Subscriber(self, CameraInfo, topic="left/camera_info")
        self.sync = message_filters.ApproximateTimeSynchronizer([left, info], 10, 0.1)
"""


def test_message_filters_subscribers_in_both_generations() -> None:
    ros1 = facts_of(STEREO_SYNC_ROS1, ros=ROS1)
    assert [u for u in uses(ros1) if u[0] == "topic"] == [
        ("topic", "subscribe", "/stereo/left/image_raw", "sensor_msgs.msg.Image", 7, 35),
        ("topic", "subscribe", "left/camera_info", "sensor_msgs.msg.CameraInfo", 8, 35),
    ]
    ros2 = facts_of(STEREO_SYNC_ROS2, ros=ROS2)
    assert [u[:4] for u in uses(ros2) if u[0] == "topic"] == [
        ("topic", "subscribe", "/stereo/left/image_raw", "sensor_msgs.msg.Image"),
        ("topic", "subscribe", "left/camera_info", "sensor_msgs.msg.CameraInfo"),
    ]


# Names held in instance attributes: followed where every write agrees.

SCAN_MONITOR_PY = """\
import unittest

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String

STATUS = "/monitor/status"


class ScanMonitor(Node):
    def __init__(self, args):
        super().__init__("scan_monitor")
        self.scan_topic = "/scan"
        self.status_topic = STATUS
        self.alert_topic = "alerts"
        self.input_topic = args.input
        self.create_timer(1.0, self.start)

    def start(self):
        self.create_subscription(LaserScan, self.scan_topic, self.on_scan, 10)
        self.status_pub = self.create_publisher(String, self.status_topic, 10)
        self.alert_pub = self.create_publisher(String, self.alert_topic, 10)
        self.input_sub = self.create_subscription(String, self.input_topic, self.on_scan, 10)

    def retarget(self):
        self.alert_topic = "alerts_" + str(self.get_clock().now().nanoseconds)

    def on_scan(self, msg):
        self.status_pub.publish(String(data="ok"))


class TestScanMonitor(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rclpy.init()
        cls.node = rclpy.create_node("scan_monitor_test")
        cls.topic = "/monitor/status"

    def test_status_is_published(self):
        received = []
        self.node.create_subscription(String, self.topic, received.append, 10)
"""


def test_instance_attributes_every_write_agrees_on_are_followed() -> None:
    facts = facts_of(SCAN_MONITOR_PY, "scan_monitor/scan_monitor.py", ros=ROS2)
    topics = [(u.role.value, u.value) for u in facts.names if u.kind.value == "topic"]
    assert [(role, value) for role, value in topics if "_topic" not in value] == [
        ("subscribe", "/scan"),
        ("publish", "/monitor/status"),
        ("subscribe", "/monitor/status"),  # cls.topic, set in setUpClass
    ]
    # set from an argument; rewritten with a time stamp in retarget()
    assert [value for role, value in topics if "_topic" in value] == [
        "self.alert_topic",
        "self.input_topic",
    ]


def test_a_name_bound_to_one_value_on_every_branch_is_followed() -> None:
    source = (
        "import rospy\n"
        "from std_msgs.msg import String\n"
        "\n"
        "def main(simulated):\n"
        "    rospy.init_node('odometry_bridge')\n"
        "    topic = '/odom'\n"
        "    if simulated:\n"
        "        topic = '/odom'  # the simulator publishes the same name\n"
        "    source = 'wheel_odom'\n"
        "    if simulated:\n"
        "        source = 'sim_odom'\n"
        "    rospy.Subscriber(topic, String, print)\n"
        "    rospy.Subscriber(source, String, print)\n"
    )
    facts = facts_of(source, "odometry_bridge/bridge.py", ros=ROS1)
    assert [u.value for u in facts.names if u.kind.value == "topic" and not u.dynamic] == ["/odom"]
    assert dynamic(facts) == ["source"]


@pytest.mark.parametrize("name", ["dock_controller.py", "fibonacci_client.py", "talker.py"])
def test_extracting_a_node_leaves_no_cycle_for_the_collector(name: str) -> None:
    """A node's tree is freed by reference counting once its facts are out: a cycle
    (a scope and its bindings, the launch extractor and its include paths) would keep
    the whole tree until the cycle collector walks it, a seventh of a cold run."""
    data = (FIXTURES / name).read_bytes()
    fixture(name)  # whatever the first extraction imports and caches stays out of the count
    gc.collect()
    gc.disable()
    try:
        facts = extract(f"fixtures/python/{name}", data, None, ROS2)
        assert facts.names  # a real node, not a file the prefilter skipped
        del facts
        assert gc.collect() == 0
    finally:
        gc.enable()
