"""Odd files through the real CLI: each gives one clear outcome, never a traceback.

A finding, or one line on stderr that says what happened; exit code 2 only for a usage
error. Symbolic link loops, unreadable files, directories named like sources, names that
are not UTF-8, huge one-line files, NUL bytes, other encodings and line ends (which must
not move a finding), network entities, deep nesting.
"""

from __future__ import annotations

import codecs
import errno
import http.server
import os
import shutil
import subprocess
import sys
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from conftest import Run, write, write_package

BAD_LAUNCH = """\
<launch>
  <node pkg="turtlebot3_bringup" type="turtlebot3_core" name="base-driver"/>
</launch>
"""
BASE_DRIVER = "node name 'base-driver' contains '-' at index 4 (ROS 1); use 'base_driver'"


def check(run_cli: Any, root: Path, *arguments: str) -> Run:
    """``roslint-names check --format json ARGUMENTS`` in ``root``; never a traceback."""
    result: Run = run_cli(["check", "--format", "json", "--no-cache", *arguments], root)
    assert "Traceback" not in result.stderr
    assert "internal error" not in result.stderr
    return result


def found(result: Run) -> list[tuple[str, int, int, str]]:
    """(path, line, column, code) of every finding."""
    return [(f["path"], f["line"], f["column"], f["code"]) for f in result.findings()]


def places(result: Run) -> list[tuple[str, int, int, str]]:
    """(path, line, column, code) of every finding and of the other places it stands for:
    copies of one file write the same names, one decision (``decisions``)."""
    return sorted(
        (place["path"], place["line"], place["column"], f["code"])
        for f in result.findings()
        for place in (f, *f["related"])
    )


def messages(result: Run) -> list[tuple[str, str, str]]:
    return [(f["path"], f["code"], f["message"]) for f in result.findings()]


# ---------------------------------------------------------------------------------------
# Symbolic links, unreadable files, directories named like files, file names


def test_directory_symlinked_into_itself_is_not_followed(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "launch/robot.launch", BAD_LAUNCH)
    (tmp_path / "launch" / "again").symlink_to("..", target_is_directory=True)
    (tmp_path / "self").symlink_to(".", target_is_directory=True)
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    assert found(result) == [("launch/robot.launch", 2, 63, "RN101")]
    named = check(run_cli, tmp_path, "self")  # named, it is followed, once
    assert found(named) == [("self/launch/robot.launch", 2, 63, "RN101")]


def test_file_symlinked_to_itself_named_on_the_command_line_is_one_parse_error(
    run_cli: Any, tmp_path: Path
) -> None:
    (tmp_path / "loop.launch").symlink_to("loop.launch")
    result = check(run_cli, tmp_path, "loop.launch")
    assert result.exit_code == 1
    [(path, code, message)] = messages(result)
    assert (path, code) == ("loop.launch", "RN001")
    assert message == f"cannot read file: {os.strerror(errno.ELOOP)}"


def test_file_symlinked_to_itself_inside_the_tree_does_not_stop_the_run(
    run_cli: Any, tmp_path: Path
) -> None:
    """DirEntry.is_file() raised OSError(ELOOP) for the link and stopped the walk (exit 2);
    now the link is one 'cannot read' finding, as when it is named on the command line."""
    write(tmp_path, "launch/robot.launch", BAD_LAUNCH)
    (tmp_path / "launch" / "loop.launch").symlink_to("loop.launch")
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    assert ("launch/robot.launch", 2, 63, "RN101") in found(result)
    assert [f["code"] for f in result.findings() if f["path"] == "launch/loop.launch"] == ["RN001"]


def _readable_despite_mode_000(path: Path) -> bool:
    try:
        with path.open("rb"):
            return True
    except OSError:
        return False


def test_unreadable_file_is_one_parse_error(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "launch/robot.launch", BAD_LAUNCH)
    secret = write(tmp_path, "launch/secret.launch", BAD_LAUNCH)
    secret.chmod(0)
    try:
        if os.geteuid() == 0 and _readable_despite_mode_000(secret):
            pytest.skip("running as root: a file of mode 000 is still readable")
        result = check(run_cli, tmp_path, ".")
    finally:
        secret.chmod(0o644)
    assert result.exit_code == 1
    assert messages(result) == [
        ("launch/robot.launch", "RN101", BASE_DRIVER),
        ("launch/secret.launch", "RN001", f"cannot read file: {os.strerror(errno.EACCES)}"),
    ]


@pytest.mark.skipif(not Path("/proc/self/mem").exists(), reason="needs Linux /proc")
def test_file_whose_read_fails_is_one_parse_error(run_cli: Any, tmp_path: Path) -> None:
    """Reading /proc/self/mem from offset 0 fails with EIO, even for root: a file that
    exists, is a regular file, and cannot be read."""
    write(tmp_path, "launch/robot.launch", BAD_LAUNCH)
    (tmp_path / "launch" / "broken.launch").symlink_to("/proc/self/mem")
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    assert messages(result) == [
        ("launch/broken.launch", "RN001", f"cannot read file: {os.strerror(errno.EIO)}"),
        ("launch/robot.launch", "RN101", BASE_DRIVER),
    ]


def refuse_to_list(monkeypatch: pytest.MonkeyPatch, refused: Path) -> None:
    """``os.scandir`` of ``refused`` fails with EACCES: what a directory of mode 000 does
    to a user who is not root (root lists it all the same)."""
    listing = os.scandir

    def scandir(path: Any) -> Any:
        if os.fspath(path) == os.fspath(refused):
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), os.fspath(path))
        return listing(path)

    monkeypatch.setattr(os, "scandir", scandir)


def test_unreadable_directory_is_one_warning_line(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Its files were left out without a word."""
    write(tmp_path, "src/bringup/launch/robot.launch", BAD_LAUNCH)
    write(tmp_path, "src/secret/launch/robot.launch", BAD_LAUNCH)
    refuse_to_list(monkeypatch, tmp_path / "src" / "secret")
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    assert found(result) == [("src/bringup/launch/robot.launch", 2, 63, "RN101")]
    assert result.stderr.splitlines()[0] == (
        f"roslint-names: warning: cannot read directory src/secret: {os.strerror(errno.EACCES)}"
    )
    named = check(run_cli, tmp_path, "src/secret")  # named, it cannot be linted at all
    assert named.exit_code == 2
    assert named.stderr == (
        f"roslint-names: error: src/secret: cannot read directory: {os.strerror(errno.EACCES)}\n"
    )


def test_named_link_loop_and_empty_directory_are_said(run_cli: Any, tmp_path: Path) -> None:
    """Both said 'All checks passed: 0 files, no problems.' and nothing else."""
    (tmp_path / "launch").mkdir()
    (tmp_path / "scripts").symlink_to("scripts")
    result: Run = run_cli(["check", "--no-cache", "launch", "scripts"], tmp_path)
    assert result.exit_code == 0
    assert result.stderr.splitlines() == [
        "roslint-names: warning: launch: no file to lint in this directory",
        f"roslint-names: warning: scripts: not linted: {os.strerror(errno.ELOOP)}",
        "All checks passed: 0 files checked, no problems.",
    ]


def test_directories_named_like_source_files_are_walked_not_read(
    run_cli: Any, tmp_path: Path
) -> None:
    write(tmp_path, "src/node.cpp/README", "not C++\n")
    write(tmp_path, "launch/x.launch/robot.launch", BAD_LAUNCH)
    (tmp_path / "empty.launch.xml").mkdir()
    for named in (".", "launch/x.launch"):
        result = check(run_cli, tmp_path, named)
        assert result.exit_code == 1
        assert found(result) == [("launch/x.launch/robot.launch", 2, 63, "RN101")]


def test_file_name_that_is_not_utf8_is_reported_with_escapes(run_cli: Any, tmp_path: Path) -> None:
    name = os.path.join(os.fsencode(tmp_path), b"caf\xe9.launch")
    try:
        with open(name, "wb") as stream:
            stream.write(BAD_LAUNCH.encode())
    except (OSError, UnicodeError):
        pytest.skip("this file system refuses names that are not UTF-8")
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    assert found(result) == [("caf\\xe9.launch", 2, 63, "RN101")]
    text: Run = run_cli(["check", "--no-cache", "."], tmp_path)  # gcc style, UTF-8 too
    assert text.stdout.startswith("caf\\xe9.launch:2:63: error: node name 'base-driver'")


# ---------------------------------------------------------------------------------------
# Size and content

TEN_MIB = 10 * 1024 * 1024


def test_ten_megabyte_one_line_cpp_file(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "roslint-names.toml", f"max-file-size = {2 * TEN_MIB}\n")  # default: 5 MiB
    head = 'int main(int argc, char** argv) { ros::init(argc, argv, "base-driver"); '
    blob = 'const char* blob = "' + "x" * TEN_MIB + '"; '
    tail = 'ros::NodeHandle nh; nh.advertise<std_msgs::String>("cmd-vel", 1); }'
    write(tmp_path, "src/generated.cpp", head + blob + tail)
    result = check(run_cli, tmp_path, "src/generated.cpp")
    assert result.exit_code == 1
    column = len(head + blob + tail) - len('"cmd-vel", 1); }') + 1
    assert found(result) == [
        ("src/generated.cpp", 1, 57, "RN101"),
        ("src/generated.cpp", 1, column, "RN101"),
    ]


def test_ten_megabyte_one_line_launch_file(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "roslint-names.toml", f"max-file-size = {2 * TEN_MIB}\n")
    # Ten values of 1 MiB: libxml2 refuses a single text or attribute above 10,000,000.
    blobs = f'<param name="blob" value="{"x" * (TEN_MIB // 10)}"/>' * 10
    node = '<node pkg="p" type="t" name="base-driver"/>'
    write(tmp_path, "launch/generated.launch", f"<launch>{blobs}{node}</launch>")
    result = check(run_cli, tmp_path, "launch/generated.launch")
    assert result.exit_code == 1
    column = len(f"<launch>{blobs}") + len('<node pkg="p" type="t" name="') + 1
    assert found(result) == [("launch/generated.launch", 1, column, "RN101")]


def test_ten_megabyte_attribute_is_one_parse_error(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "roslint-names.toml", f"max-file-size = {2 * TEN_MIB}\n")
    value = "x" * TEN_MIB
    write(tmp_path, "robot.launch", f'<launch><param name="blob" value="{value}"/></launch>')
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    [(path, code, message)] = messages(result)
    assert (path, code) == ("robot.launch", "RN001")
    assert message.startswith("cannot parse XML: ")


PYTHON_NODE = (
    'import rospy\n\nrospy.init_node("talker")\npub = rospy.Publisher("chatter", String)\n'
)
PADDING_LINES = 1000  # "# padding\n" 1,000 times: the NUL comes after the first 8,000 bytes


@pytest.mark.parametrize(
    ("name", "content"),
    [
        ("talker.py", PYTHON_NODE.replace('"chatter"', '"chat\0ter"')),
        ("robot.launch", BAD_LAUNCH.replace('name="base-driver"', 'name="base\0driver"')),
    ],
    ids=["python", "launch"],
)
def test_nul_byte_near_the_start_is_not_text_and_says_so(
    run_cli: Any, tmp_path: Path, name: str, content: str
) -> None:
    """git's test, as the engine applies it: a NUL in the first 8,000 bytes is binary;
    a source that is not text is one RN001, never "All checks passed"."""
    write(tmp_path, name, content)
    result = check(run_cli, tmp_path, ".", "--verbose")
    assert result.exit_code == 1
    assert [(f["path"], f["code"]) for f in result.findings()] == [(name, "RN001")]
    assert "skipped" not in result.stderr


@pytest.mark.parametrize(
    ("name", "content", "expected"),
    [
        (
            "talker.py",
            "# padding\n" * PADDING_LINES + PYTHON_NODE.replace('"chatter"', '"chat\0ter"'),
            (PADDING_LINES + 4, 28, "not valid Python 3: source code cannot contain null bytes"),
        ),
        (
            "robot.launch",
            "<!-- padding -->\n" * PADDING_LINES + BAD_LAUNCH.replace("-driver", "\0driver"),
            (PADDING_LINES + 2, 67, "cannot parse XML: invalid character in attribute value"),
        ),
    ],
    ids=["python", "launch"],
)
def test_nul_byte_further_in_is_one_parse_error_where_it_is(
    run_cli: Any, tmp_path: Path, name: str, content: str, expected: tuple[int, int, str]
) -> None:
    write(tmp_path, name, content)
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    assert [(f["line"], f["column"], f["code"], f["message"]) for f in result.findings()] == [
        (expected[0], expected[1], "RN001", expected[2])
    ]


@pytest.mark.parametrize(
    ("name", "content"),
    [
        (
            "src/talker.cpp",
            '#include <ros/ros.h>\nint main(int c, char** v) { ros::init(c, v, "talker");\n'
            '  ros::NodeHandle nh; nh.advertise<std_msgs::String>("chat\\ud800ter", 1); }\n',
        ),
        (
            "scripts/talker.py",
            'import rospy\nrospy.init_node("talker")\n'
            'pub = rospy.Publisher("chat\\ud800ter", String)\n',
        ),
        (
            "launch/talker.launch.yaml",
            "launch:\n- node: {pkg: p, exec: e, name: talker}\n"
            '- node: {pkg: p, exec: e, name: "chat\\ud800ter"}\n',
        ),
    ],
)
def test_surrogate_escape_in_a_name_is_an_illegal_name_not_a_crash(
    run_cli: Any, tmp_path: Path, name: str, content: str
) -> None:
    """An escape for a lone surrogate made the report unprintable: exit code 2."""
    write(tmp_path, name, content)
    for report in ("json", "text", "sarif", "github"):
        result: Run = run_cli(["check", "--no-cache", "--format", report, "."], tmp_path)
        assert (result.exit_code, "internal error" in result.stderr) == (1, False), report
    result = check(run_cli, tmp_path, ".")
    [(path, line, _column, code)] = found(result)
    assert (path, line, code) == (name, 3, "RN101")
    assert "'chat\ufffdter'" in result.findings()[0]["message"]


# ---------------------------------------------------------------------------------------
# Encodings and line ends: a finding stays where it is

# Non-ASCII before the name on its line, one of them outside the BMP (two UTF-16 units):
# columns count code points whatever the encoding.
ENCODED_LAUNCH = """\
<?xml version="1.0" encoding="UTF-8"?>
<launch>
  <!-- Base of the delivery robot, size M -->
  <arg name="robot" default="robot1"/>
  <group ns="$(arg robot)">
    <!-- Größe 🤖 --> <node pkg="turtlebot3_bringup" type="turtlebot3_core" name="base-driver"/>
    <node pkg="hls_lfcd_lds_driver" type="hlds_laser_publisher" name="lidar">
      <remap from="scan" to="scan/"/>
    </node>
  </group>
</launch>
"""
ENCODED_CPP = """\
// Publishes the smoothed velocity — «vitesse» 🤖
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "velocity_publisher");
  ros::NodeHandle nh;
  /* 🤖 größe */ ros::Publisher pub = nh.advertise<geometry_msgs::Twist>("cmd-vel", 10);
  ros::spin();
  return 0;
}
"""
ENCODINGS = {
    "utf-8 crlf": ("utf-8", b"", "\r\n"),
    "utf-8 bom": ("utf-8", codecs.BOM_UTF8, "\n"),
    "utf-8 bom crlf": ("utf-8", codecs.BOM_UTF8, "\r\n"),
    "utf-16-le bom": ("utf-16-le", codecs.BOM_UTF16_LE, "\n"),
    "utf-16-be bom": ("utf-16-be", codecs.BOM_UTF16_BE, "\n"),
    "utf-16-le bom crlf": ("utf-16-le", codecs.BOM_UTF16_LE, "\r\n"),
}


def _position(text: str, needle: str) -> tuple[int, int]:
    """1-based line and code-point column of ``needle`` in ``text``."""
    before = text[: text.index(needle)]
    return before.count("\n") + 1, len(before) - (before.rfind("\n") + 1) + 1


def _encode(text: str, encoding: str, bom: bytes, line_end: str) -> bytes:
    declared = "UTF-16" if encoding.startswith("utf-16") else "UTF-8"
    text = text.replace('encoding="UTF-8"', f'encoding="{declared}"')
    return bom + text.replace("\n", line_end).encode(encoding)


# (file, its text, where its findings are): a launch file's span starts at the value, a
# code literal's at its opening quote.
ENCODED_FILES = {
    "launch": (
        "launch/robot.launch",
        ENCODED_LAUNCH,
        [
            (*_position(ENCODED_LAUNCH, "base-driver"), "RN101"),
            (*_position(ENCODED_LAUNCH, "scan/"), "RN102"),
        ],
    ),
    "cpp": ("src/velocity.cpp", ENCODED_CPP, [(*_position(ENCODED_CPP, '"cmd-vel"'), "RN101")]),
}


@pytest.mark.parametrize("variant", list(ENCODINGS))
@pytest.mark.parametrize("language", list(ENCODED_FILES))
def test_encoding_and_line_ends_do_not_move_a_finding(
    run_cli: Any, tmp_path: Path, language: str, variant: str
) -> None:
    name, text, expected = ENCODED_FILES[language]
    write_package(tmp_path, 1)
    plain = tmp_path / "plain" / name
    plain.parent.mkdir(parents=True)
    plain.write_bytes(text.encode("utf-8"))
    other = tmp_path / "other" / name
    other.parent.mkdir(parents=True)
    other.write_bytes(_encode(text, *ENCODINGS[variant]))
    result = check(run_cli, tmp_path, "plain", "other", "--verbose")
    assert "skipped" not in result.stderr
    positions: dict[str, list[tuple[int, int, str]]] = {}
    for path, line, column, code in places(result):
        positions.setdefault(path.split("/")[0], []).append((line, column, code))
    assert positions == {"plain": expected, "other": expected}


# ---------------------------------------------------------------------------------------
# Hostile XML: the network, and nesting


class _CountingHandler(http.server.BaseHTTPRequestHandler):
    requests: list[str]

    def do_GET(self) -> None:
        self.requests.append(self.path)
        body = b'<!ENTITY leak "LEAKED">' if self.path.endswith((".dtd", ".ent")) else b"LEAKED"
        self.send_response(200)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def log_message(self, format: str, *args: Any) -> None:
        pass


@pytest.fixture
def counting_server() -> Iterator[tuple[str, list[str]]]:
    """An HTTP server on 127.0.0.1 that counts the requests it gets."""
    requests: list[str] = []
    handler = type("Handler", (_CountingHandler,), {"requests": requests})
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, args=(0.05,), daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}", requests
    finally:
        server.shutdown()
        server.server_close()
        thread.join()


def test_network_entities_are_never_fetched(
    run_cli: Any, tmp_path: Path, counting_server: tuple[str, list[str]]
) -> None:
    url, requests = counting_server
    node = '<node pkg="p" type="t" name="&leak;"/>'
    files = {
        "attribute.launch": f'<!DOCTYPE launch [<!ENTITY x SYSTEM "{url}/a">]>\n'
        '<launch><node pkg="p" type="t" name="&x;"/></launch>\n',
        "text.urdf": f'<!DOCTYPE robot [<!ENTITY x SYSTEM "{url}/t">]>\n<robot name="r">'
        "<gazebo><plugin><frameName>&x;</frameName></plugin></gazebo></robot>\n",
        "dtd.launch": f'<!DOCTYPE launch SYSTEM "{url}/d.dtd">\n<launch>{node}</launch>\n',
        "parameter.launch": f'<!DOCTYPE launch [<!ENTITY % p SYSTEM "{url}/p.ent"> %p;]>\n'
        f"<launch>{node}</launch>\n",
        "xinclude.launch": '<launch xmlns:xi="http://www.w3.org/2001/XInclude">'
        f'<xi:include href="{url}/i" parse="text"/></launch>\n',
    }
    for name, content in files.items():
        write(tmp_path, name, content)
    result = check(run_cli, tmp_path, ".")
    assert requests == []
    assert "LEAKED" not in result.stdout
    assert result.exit_code == 1
    assert messages(result) == [
        ("attribute.launch", "RN001", "cannot parse XML: Attribute references external entity 'x'")
    ]


def test_five_thousand_nested_groups_are_at_most_one_parse_error(
    run_cli: Any, tmp_path: Path
) -> None:
    depth = 5000
    node = '<node pkg="p" type="t" name="base-driver"/>'
    write(
        tmp_path,
        "deep.launch",
        "<launch>" + '<group ns="a">' * depth + node + "</group>" * depth + "</launch>\n",
    )
    nested = "[{group: " * depth + "[{node: {pkg: p, exec: e, name: base-driver}}]" + "}]" * depth
    write(tmp_path, "deep.launch.yaml", f"launch: {nested}\n")
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code in (0, 1)
    by_file = {path: code for path, _, _, code in found(result)}
    assert len(found(result)) == len(by_file)  # at most one finding per file
    assert set(by_file.values()) <= {"RN001"}
    assert "deep.launch" in by_file  # libxml2 refuses more than 256 levels without XML_PARSE_HUGE


# Windows editors save UTF-16 (and some tools UTF-32) with a byte order mark.
ROSCPP_DRIVER = """#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "base-driver");
  ros::NodeHandle nh;
  ros::Publisher odom = nh.advertise<geometry_msgs::Twist>("odom raw", 10);  // NOLINT(RN101)
  ros::spin();
}
"""
DIFF_DRIVE_URDF = """<?xml version="1.0" encoding="UTF-32"?>
<robot name="rover">
  <gazebo>
    <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
      <ros><namespace>rover 1</namespace></ros>
      <odometry_frame>/odom</odometry_frame>
    </plugin>
  </gazebo>
</robot>
"""
TELEOP_YAML = """launch:
- node: {pkg: teleop_twist_joy, exec: teleop_node, name: teleop-joy}
"""
RCLPY_NODE = """import rclpy
from rclpy.node import Node

rclpy.init()
node = Node("base-driver")
"""


def _with_bom(text: str, codec: str) -> bytes:
    boms = {
        "utf-16-le": codecs.BOM_UTF16_LE,
        "utf-16-be": codecs.BOM_UTF16_BE,
        "utf-32-le": codecs.BOM_UTF32_LE,
        "utf-32-be": codecs.BOM_UTF32_BE,
    }
    return boms[codec] + text.encode(codec)


@pytest.mark.parametrize("codec", ["utf-16-le", "utf-16-be", "utf-32-le", "utf-32-be"])
def test_wide_sources_are_decoded_where_the_language_allows(
    run_cli: Any, tmp_path: Path, codec: str
) -> None:
    """C++ compilers, XML and YAML accept a byte order mark; spans and suppressions hold."""
    write(
        tmp_path,
        "base/package.xml",
        "<package><buildtool_depend>catkin</buildtool_depend></package>",
    )
    (tmp_path / "base/src").mkdir()
    (tmp_path / "base/src/driver.cpp").write_bytes(_with_bom(ROSCPP_DRIVER, codec))
    (tmp_path / "base/urdf").mkdir()
    (tmp_path / "base/urdf/rover.urdf").write_bytes(
        _with_bom(DIFF_DRIVE_URDF.replace("UTF-32", codec[:6].upper()), codec)
    )
    (tmp_path / "teleop/launch").mkdir(parents=True)
    (tmp_path / "teleop/launch/teleop.launch.yaml").write_bytes(_with_bom(TELEOP_YAML, codec))
    result = check(run_cli, tmp_path, ".", "--ros", "2")
    assert [(f["path"], f["line"], f["column"], f["code"]) for f in result.findings()] == [
        ("base/src/driver.cpp", 6, 25, "RN101"),  # the suppressed 'odom raw' stays silent
        ("base/urdf/rover.urdf", 5, 23, "RN101"),
        ("base/urdf/rover.urdf", 6, 23, "RN205"),
        ("teleop/launch/teleop.launch.yaml", 2, 58, "RN101"),
    ]


@pytest.mark.parametrize("codec", ["utf-16-le", "utf-32-be"])
def test_a_wide_python_source_is_one_parse_error(run_cli: Any, tmp_path: Path, codec: str) -> None:
    """CPython refuses UTF-16 and UTF-32 source: so does the linter, out loud."""
    (tmp_path / "scripts").mkdir()
    (tmp_path / "scripts/driver.py").write_bytes(_with_bom(RCLPY_NODE, codec))
    result = check(run_cli, tmp_path, ".")
    assert result.exit_code == 1
    [finding] = result.findings()
    assert (finding["code"], finding["line"]) == ("RN001", 1)
    assert finding["message"].startswith(f"Python source is {codec[:6].upper()} (byte order mark)")


def _without_file_permission_override() -> list[str] | None:
    """A command prefix that runs as a user whom file modes bind: none needed when not
    root; ``setpriv`` dropping root's override capabilities; None where neither can."""
    if os.geteuid() != 0:
        return []
    setpriv = shutil.which("setpriv")
    if setpriv is None:
        return None
    capabilities = "-dac_override,-dac_read_search"
    return [setpriv, f"--bounding-set={capabilities}", f"--inh-caps={capabilities}"]


def test_a_named_file_behind_a_directory_that_cannot_be_searched_is_a_usage_error(
    tmp_path: Path,
) -> None:
    """Not an internal error: the file's directory can be listed but not entered."""
    prefix = _without_file_permission_override()
    if prefix is None:
        pytest.skip("running as root without setpriv: file modes do not bind")
    write(tmp_path, "src/robot_base/package.xml", "<package><name>robot_base</name></package>")
    write(tmp_path, "src/robot_base/src/driver.cpp", "int main() {}\n")
    hidden = tmp_path / "src/robot_base/src"
    hidden.chmod(0o644)
    try:
        command = [*prefix, sys.executable, "-m", "roslint_names.cli", "check", "--no-cache"]
        result = subprocess.run(
            [*command, "src/robot_base/src/driver.cpp"],
            cwd=tmp_path,
            capture_output=True,
            text=True,
            check=False,
        )
    finally:
        hidden.chmod(0o755)
    assert result.returncode == 2
    assert result.stderr == (
        f"roslint-names: error: src/robot_base/src/driver.cpp: {os.strerror(errno.EACCES)}\n"
    )


def test_a_package_is_shown_by_its_directory_when_its_files_are_named_in_latin_1(
    tmp_path: Path,
) -> None:
    """A file name that is not UTF-8 is shown with its byte as four characters (``\\xe9``):
    the package's display directory is its file's display less the part below the
    package as shown, not as named (it was cut three characters short)."""
    from roslint_names.discover import discover
    from roslint_names.engine import workspace_packages
    from roslint_names.generation import PackageGenerations

    write_package(tmp_path / "src" / "robot", 1, "robot")
    launch = tmp_path / "src" / "robot" / "launch"
    launch.mkdir()
    (launch / os.fsdecode(b"caf\xe9.launch")).write_text("<launch/>\n", encoding="utf-8")
    sources = discover([Path("src")], (), tmp_path, tmp_path, [])
    assert sources[0].display == "src/robot/launch/caf\\xe9.launch"
    (package,) = workspace_packages(sources[:1], PackageGenerations())
    assert (package.name, package.directory) == ("robot", "src/robot")
