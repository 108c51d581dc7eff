"""Python 2 in ROS 1 packages: read for names, not an RN001 (issue 29).

ROS 1 ran Python 2 up to Melodic, and its packages keep Python 2 scripts (ros-perception
slam_gmapping's ``gmapping/test/test_map.py`` has ``print '...'``). Such a file in a
catkin package is rewritten into Python 3 (``extract.python.python2``), its names are
checked where the file spells them, and only its findings set the exit code. ROS 2 is
Python 3 only: the same file in an ament package is RN001.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

import pytest
from conftest import write
from hypothesis import example, given, settings
from hypothesis import strategies as st

from roslint_names.config import Settings, load_settings, ros1_python2
from roslint_names.extract.python.extract import extract
from roslint_names.extract.python.python2 import rewrite
from roslint_names.model import Generation
from roslint_names.registry import load_registry

ROS1, ROS2 = Generation.ROS1, Generation.ROS2

# A melodic-era node as its authors wrote them: tab-indented, print statements, the
# Python 2 ``except``, a backtick repr and an octal mode. Its topic 'cmdVel' is camelCase
# (RN203) on a tab-indented line, and its 'scan/' has a trailing slash (RN102, a safe fix).
MELODIC_NODE = """\
#!/usr/bin/env python
import os
import sys

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan


class SafetyStop(object):
\tdef __init__(self):
\t\tself.pub = rospy.Publisher('cmdVel', Twist, queue_size=1)
\t\trospy.Subscriber('scan/', LaserScan, self.on_scan)
\t\tprint "safety_stop: publishing on", self.pub.resolved_name

\tdef on_scan(self, scan):
\t\tif min(scan.ranges) < 0.3:
\t\t\tprint >>sys.stderr, "obstacle at", `min(scan.ranges)`
\t\t\tself.pub.publish(Twist())


if __name__ == '__main__':
\trospy.init_node('safety_stop')
\tos.umask(0022)
\ttry:
\t\tSafetyStop()
\t\trospy.spin()
\texcept rospy.ROSInterruptException, e:
\t\tprint "shutting down:", e
"""

CATKIN = """<?xml version="1.0"?>
<package format="2">
  <name>safety_stop</name>
  <version>0.3.1</version>
  <description>Stops the base near obstacles</description>
  <maintainer email="ops@example.com">Ops</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>rospy</exec_depend>
  <exec_depend>geometry_msgs</exec_depend>
  <exec_depend>sensor_msgs</exec_depend>
</package>
"""

AMENT_PYTHON = """<?xml version="1.0"?>
<package format="3">
  <name>safety_stop</name>
  <version>0.3.1</version>
  <description>Stops the base near obstacles</description>
  <maintainer email="ops@example.com">Ops</maintainer>
  <license>Apache-2.0</license>
  <exec_depend>rclpy</exec_depend>
  <export><build_type>ament_python</build_type></export>
</package>
"""

SCRIPT = "src/safety_stop/scripts/safety_stop.py"


def workspace(tmp_path: Path, manifest: str = CATKIN, source: str = MELODIC_NODE) -> Path:
    write(tmp_path, "src/safety_stop/package.xml", manifest)
    return write(tmp_path, SCRIPT, source)


def findings(run_cli: Any, tmp_path: Path, *options: str) -> tuple[int, list[tuple[Any, ...]]]:
    result = run_cli(["check", "--format", "json", *options, "src"], tmp_path)
    assert result.exit_code in (0, 1), result.stderr
    return result.exit_code, [
        (f["code"], f["line"], f["column"], f["message"]) for f in result.findings()
    ]


def column_of(text: str, line: int, needle: str) -> int:
    return text.splitlines()[line - 1].index(needle) + 1


# ---------------------------------------------------------------------------------------
# A catkin package: read, its findings where the file spells the names


def test_melodic_node_in_a_catkin_package_is_read(run_cli: Any, tmp_path: Path) -> None:
    workspace(tmp_path)
    exit_code, found = findings(run_cli, tmp_path)
    assert [(code, line, column) for code, line, column, _ in found] == [
        ("RN203", 12, column_of(MELODIC_NODE, 12, "'cmdVel'")),
        ("RN102", 13, column_of(MELODIC_NODE, 13, "'scan/'")),
    ]
    assert exit_code == 1  # from the findings: no RN001


def test_only_findings_set_the_exit_code(run_cli: Any, tmp_path: Path) -> None:
    clean = MELODIC_NODE.replace("'cmdVel'", "'cmd_vel'").replace("'scan/'", "'scan'")
    workspace(tmp_path, source=clean)
    assert findings(run_cli, tmp_path) == (0, [])


def test_the_same_file_in_an_ament_python_package_is_rn001(run_cli: Any, tmp_path: Path) -> None:
    workspace(tmp_path, AMENT_PYTHON)
    exit_code, found = findings(run_cli, tmp_path)
    # CPython's tokenizer stops first, at the octal ``0022``.
    assert [(code, line) for code, line, _, _ in found] == [("RN001", 24)]
    assert found[0][3].startswith("not valid Python 3: leading zeros")
    assert exit_code == 1


def test_what_the_rewrite_cannot_read_stays_rn001(run_cli: Any, tmp_path: Path) -> None:
    # Tuple parameters are Python 2 that is not rewritten: the file stops there, not at
    # its first print statement, which is fine Python 2.
    source = MELODIC_NODE.replace(
        "\tdef on_scan(self, scan):",
        "\tdef on_pose(self, (x, y)):\n\t\tpass\n\n\tdef on_scan(self, scan):",
    )
    workspace(tmp_path, source=source)
    exit_code, found = findings(run_cli, tmp_path)
    assert [(code, line) for code, line, _, _ in found] == [("RN001", 16)]
    assert found[0][3].startswith("cannot read as Python 2 or 3: ")
    assert found[0][2] > 1  # on the parameters, in the file's own columns
    assert exit_code == 1


def test_a_syntax_error_after_print_statements_is_reported_where_it_is(
    run_cli: Any, tmp_path: Path
) -> None:
    source = MELODIC_NODE.replace("\tdef on_scan(self, scan):", "\tdef on_scan(self, scan)")
    workspace(tmp_path, source=source)
    _, found = findings(run_cli, tmp_path)
    assert [(code, line) for code, line, _, _ in found] == [("RN001", 16)]


# ---------------------------------------------------------------------------------------
# Which Python: the ``python`` key, then ROS_PYTHON_VERSION


@pytest.mark.parametrize(
    ("config", "environment", "read"),
    [
        ("", {}, True),
        ("python = 2\n", {"ROS_PYTHON_VERSION": "3"}, True),
        ('python = "3"\n', {}, False),
        ("", {"ROS_PYTHON_VERSION": "2", "ROS_VERSION": "1"}, True),
        ("", {"ROS_PYTHON_VERSION": "3", "ROS_VERSION": "1"}, False),  # a sourced Noetic
        ("", {"ROS_PYTHON_VERSION": "3"}, False),
        # A sourced ROS 2 says 3 of its own packages, nothing of ROS 1 ones.
        ("", {"ROS_PYTHON_VERSION": "3", "ROS_VERSION": "2"}, True),
    ],
)
def test_which_python_the_ros1_packages_use(  # noqa: PLR0917 - fixtures and parameters
    run_cli: Any,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    config: str,
    environment: dict[str, str],
    read: bool,
) -> None:
    workspace(tmp_path)
    write(tmp_path, "roslint-names.toml", config)
    for variable, value in environment.items():
        monkeypatch.setenv(variable, value)
    _, found = findings(run_cli, tmp_path)
    codes = [code for code, *_ in found]
    assert codes == (["RN203", "RN102"] if read else ["RN001"])


def test_the_python_key_is_checked(tmp_path: Path) -> None:
    registry = load_registry()
    write(tmp_path, "roslint-names.toml", 'python = "2.7"\n')
    with pytest.raises(Exception, match=r'python: must be 2, 3 or "auto"'):
        load_settings(None, tmp_path, registry)


def test_ros1_python2_reads_the_environment_only_on_auto() -> None:
    auto, three = Settings(root=Path()), Settings(root=Path(), python=3)
    assert ros1_python2(auto, {})
    assert not ros1_python2(auto, {"ROS_PYTHON_VERSION": "3"})
    assert ros1_python2(auto, {"ROS_PYTHON_VERSION": "3", "ROS_VERSION": "2"})
    assert not ros1_python2(three, {"ROS_PYTHON_VERSION": "2"})


def test_a_cached_run_follows_ros_python_version(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The environment variable is an input of every ROS 1 Python file's facts key: a
    run after it changed is not an earlier run's stored result."""
    workspace(tmp_path)
    run = ["check", "--format", "json", "src"]
    assert run_cli(run, tmp_path).codes() == ["RN203", "RN102"]
    monkeypatch.setenv("ROS_PYTHON_VERSION", "3")
    assert run_cli(run, tmp_path).codes() == ["RN001"]
    monkeypatch.setenv("ROS_PYTHON_VERSION", "2")
    assert run_cli(run, tmp_path).codes() == ["RN203", "RN102"]


# ---------------------------------------------------------------------------------------
# Edits land on the user's bytes


def test_fix_edits_the_python2_file_where_it_spells_the_name(run_cli: Any, tmp_path: Path) -> None:
    script = workspace(tmp_path)
    result = run_cli(["check", "--fix", "src"], tmp_path)
    assert "RN001" not in result.stdout
    fixed = script.read_text(encoding="utf-8")
    assert fixed == MELODIC_NODE.replace("'scan/'", "'scan'")  # RN102's safe fix, only it
    assert findings(run_cli, tmp_path)[1][0][0] == "RN203"


def test_add_noqa_onto_a_python2_file(run_cli: Any, tmp_path: Path) -> None:
    script = workspace(tmp_path)
    run_cli(["check", "--add-noqa", "src"], tmp_path)
    lines = script.read_text(encoding="utf-8").splitlines()
    assert lines[11].endswith("queue_size=1)  # noqa: RN203")
    assert lines[12].endswith("self.on_scan)  # noqa: RN102")
    assert findings(run_cli, tmp_path) == (0, [])


# ---------------------------------------------------------------------------------------
# The rewrite itself


def facts_of(source: str, package: Generation | None = ROS1, python2: bool = True) -> Any:
    return extract("scripts/node.py", source.encode(), package, ROS2, python2=python2)


def test_not_python2_unless_told() -> None:
    assert facts_of(MELODIC_NODE, python2=False).parse_errors
    facts = facts_of(MELODIC_NODE)
    assert not facts.parse_errors
    spans = {use.value: (use.span.line, use.span.column) for use in facts.names}
    assert spans["cmdVel"] == (12, column_of(MELODIC_NODE, 12, "'cmdVel'"))
    assert spans["safety_stop"] == (23, column_of(MELODIC_NODE, 23, "'safety_stop'"))


@pytest.mark.parametrize(
    ("python2", "python3"),
    [
        ('print "hello"\n', 'print( "hello")\n'),
        ("print\n", "print()\n"),
        ('print "a",\n', 'print( "a",)\n'),
        ('print >>sys.stderr, "x", y  # why\n', 'print( sys.stderr, "x", y)  # why\n'),
        ('if x: print "a"; print "b"\n', 'if x: print( "a"); print( "b")\n'),
        ('print "a %s" % (\n  x,\n  y)\n', 'print( "a %s" % (\n  x,\n  y))\n'),
        ('print "a" \\\n  "b"\n', 'print( "a" \\\n  "b")\n'),
        ("except rospy.ROSException, e:\n", "except rospy.ROSException as  e:\n"),
        ("except IOError,why:\n", "except IOError as why:\n"),
        ("except (IOError, OSError), e:\n", "except (IOError, OSError) as  e:\n"),
        ('raise ValueError, "bad"\n', 'raise ValueError( "bad")\n'),
        ('exec "x = 1"\n', 'exec( "x = 1")\n'),
        ("exec code in ns\n", "exec( code , ns)\n"),
        ("x = `a` + `b.c`\n", "x = repr(a) + repr(b.c)\n"),
        ("if a <> b:\n", "if a != b:\n"),
        ("os.chmod(p, 0755)\n", "os.chmod(p, 0o755)\n"),
        ("x = 10L + 0x1fL + 00 + 07.5\n", "x = 10 + 0x1f + 00 + 07.5\n"),
        ('y = ur"\\d+"\n', 'y = r"\\d+"\n'),
        ("if x:\n        a = 1\n\tb = 2\n", "if x:\n        a = 1\n        b = 2\n"),
    ],
)
def test_rewrite(python2: str, python3: str) -> None:
    rewritten = rewrite(python2)
    assert rewritten is not None
    assert rewritten.text == python3
    # Python 3, once a clause or a block header has the statement around it.
    if python3.startswith("except"):
        python3 = f"try:\n    pass\n{python3}"
    ast.parse(python3 + "    pass\n" if python3.rstrip().endswith(":") else python3)


@pytest.mark.parametrize(
    "python3",
    [
        'print("x")\n',
        "print = log\nprint.x\n",
        "from __future__ import print_function\nprint 'x'\n",
        'print ("a"), b\n',
    ],
)
def test_nothing_to_rewrite(python3: str) -> None:
    assert rewrite(python3) is None


def test_offsets_map_back_to_the_original() -> None:
    source = "\tprint `a`, 'cmdVel'\n"
    rewritten = rewrite(source)
    assert rewritten is not None
    assert rewritten.text == "        print( repr(a), 'cmdVel')\n"
    literal = rewritten.text.index("'cmdVel'")
    assert rewritten.original(literal) == source.index("'cmdVel'")
    assert rewritten.original(literal + len("'cmdVel'")) == source.index("'cmdVel'") + 8
    # Inserted text maps onto what it replaced: ``repr(`` onto the backtick.
    assert rewritten.original(rewritten.text.index("repr")) == source.index("`")


_PIECES = st.sampled_from(
    [
        "print", "exec", "except", "raise", "lambda", "in", "x", " ", "\t", "\n", "\r\n",
        ",", ":", ";", "(", ")", "[", "]", "`", ">>", "<>", "0777", "10L", "07.5", "ur'a'",
        '"s"', "'''t\n'''", "# c\n", "\\\n", "é", "=",
    ]
)  # fmt: skip


@example("print[\n")  # a file ending inside brackets: the ")" stays on the line
@given(st.lists(_PIECES, max_size=40).map("".join))
@settings(max_examples=300, deadline=None)
def test_the_rewrite_keeps_lines_and_maps_every_offset_back(source: str) -> None:
    rewritten = rewrite(source)
    if rewritten is None:
        return
    assert rewritten.source == source
    assert len(rewritten.text.splitlines()) == len(source.splitlines())  # never across lines
    mapped = [rewritten.original(offset) for offset in range(len(rewritten.text) + 1)]
    assert mapped == sorted(mapped)
    assert mapped[0] >= 0 and mapped[-1] == len(source)


def test_the_language_server_reads_python2_alike(tmp_path: Path) -> None:
    from roslint_names.session import Session

    script = workspace(tmp_path)
    registry = load_registry()
    session = Session(tmp_path, load_settings(None, tmp_path, registry), registry, None)
    session.load()
    found = session.check(script, MELODIC_NODE)
    assert found is not None
    assert [(d.code, d.span.line, d.span.column) for d in found] == [
        ("RN203", 12, column_of(MELODIC_NODE, 12, "'cmdVel'")),
        ("RN102", 13, column_of(MELODIC_NODE, 13, "'scan/'")),
    ]
