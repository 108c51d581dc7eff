"""`roslint-names server` against what real editors and broken clients send.

A minimal LSP client over a real server subprocess speaks JSON-RPC by hand, so that a
test can send what no well-behaved client sends (a malformed body, a request with invalid
parameters, a 50 MB edit) and read every message the server writes. Every wait has a
deadline: a server that goes deaf fails the test, it never hangs the suite.
"""

from __future__ import annotations

import contextlib
import json
import os
import queue
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

import pytest
from conftest import code_units, write, write_package

WORKTREE = Path(__file__).resolve().parents[1]

Message = dict[str, Any]


class WireServer:
    """The server process, the messages it sent, and helpers to talk to it."""

    def __init__(self, root: Path, cache: Path) -> None:
        environment = dict(os.environ)
        environment["PYTHONPATH"] = str(WORKTREE)  # this checkout, not an installed copy
        environment["XDG_CACHE_HOME"] = str(cache)
        self.log = (root.parent / "server.stderr").open("wb")
        self.process = subprocess.Popen(
            [sys.executable, "-m", "roslint_names.cli", "server"],
            cwd=root,
            env=environment,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self.log,
        )
        self.root = root
        self.received: list[Message] = []  # every message, in order
        self._arrived: queue.Queue[Message] = queue.Queue()
        self._next_id = 0
        assert self.process.stdout is not None
        self._reader = threading.Thread(target=self._read, args=(self.process.stdout,))
        self._reader.daemon = True
        self._reader.start()

    def _read(self, stream: IO[bytes]) -> None:
        while True:
            length = 0
            while (header := stream.readline()) not in (b"\r\n", b""):
                if header.lower().startswith(b"content-length:"):
                    length = int(header.split(b":")[1])
            if not header:
                return
            self._arrived.put(json.loads(stream.read(length)))

    def send_body(self, body: bytes) -> None:
        stdin = self.process.stdin
        assert stdin is not None
        stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        stdin.flush()

    def send(self, message: Message) -> None:
        self.send_body(json.dumps({"jsonrpc": "2.0", **message}).encode("utf-8"))

    def notify(self, method: str, params: Any) -> None:
        self.send({"method": method, "params": params})

    def request(self, method: str, params: Any) -> int:
        self._next_id += 1
        self.send({"id": self._next_id, "method": method, "params": params})
        return self._next_id

    def wait_for(self, wanted: Callable[[Message], bool], timeout: float) -> Message:
        """The first message (already received or to come) ``wanted`` accepts."""
        deadline = time.monotonic() + timeout
        seen = 0
        while True:
            self._drain()
            for message in self.received[seen:]:
                if wanted(message):
                    return message
            seen = len(self.received)
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"no such message within {timeout} s")
            with contextlib.suppress(queue.Empty):
                self.received.append(self._arrived.get(timeout=left))

    def response(self, request_id: int, timeout: float = 10) -> Message:
        return self.wait_for(lambda m: m.get("id") == request_id and "method" not in m, timeout)

    def call(self, method: str, params: Any, timeout: float = 10) -> Any:
        answer = self.response(self.request(method, params), timeout)
        assert "error" not in answer, answer
        return answer.get("result")

    def diagnostics(
        self, uri: str, wanted: Callable[[list[Message]], bool], timeout: float = 30
    ) -> list[Message]:
        """The diagnostics of the first publication for ``uri`` that ``wanted`` accepts."""

        def published(message: Message) -> bool:
            if message.get("method") != "textDocument/publishDiagnostics":
                return False
            params = message["params"]
            return bool(params["uri"] == uri and wanted(params["diagnostics"]))

        found: list[Message] = self.wait_for(published, timeout)["params"]["diagnostics"]
        return found

    def notifications(self, method: str) -> list[Message]:
        self._drain()
        return [m for m in self.received if m.get("method") == method]

    def _drain(self) -> None:
        while True:
            try:
                self.received.append(self._arrived.get_nowait())
            except queue.Empty:
                return

    def initialize(self, encodings: list[str] | None = None) -> Message:
        general = {} if encodings is None else {"positionEncodings": encodings}
        result: Message = self.call(
            "initialize",
            {
                "processId": None,
                "rootUri": self.root.as_uri(),
                "capabilities": {"general": general},
                "workspaceFolders": [{"uri": self.root.as_uri(), "name": "ws"}],
            },
            timeout=60,
        )
        self.notify("initialized", {})
        return result

    def open(self, uri: str, text: str, language: str) -> None:
        self.notify(
            "textDocument/didOpen",
            {"textDocument": {"uri": uri, "languageId": language, "version": 1, "text": text}},
        )

    def peak_memory_bytes(self) -> int | None:
        """The server's peak resident set (VmHWM), where /proc tells it."""
        try:
            status = Path(f"/proc/{self.process.pid}/status").read_text(encoding="ascii")
        except OSError:
            return None
        for line in status.splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
        return None

    def close(self) -> None:
        """Kill what is left of the server; every test ends with this."""
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait(timeout=10)
        for stream in (self.process.stdin, self.process.stdout):
            if stream is not None:
                stream.close()
        self.log.close()

    def stderr(self) -> str:
        self.log.flush()
        return Path(self.log.name).read_text(encoding="utf-8", errors="replace")


# ---------------------------------------------------------------------------------------
# The fixtures: a roscpp driver whose advertise call carries a comment in French and an
# emoji before the absolute topic RN202 reports (and offers to make relative).

DRIVER = """#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "base_driver");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<geometry_msgs::Twist>(/* vitesse 😀 café */"/cmd_vel", 10);
  ros::spin();
  return 0;
}
"""
ADVERTISE_LINE = 6  # 0-based, as LSP counts lines
ON_THE_LITERAL = {"line": ADVERTISE_LINE, "character": 80}  # in UTF-16 (the default)
FIXED_LINE = (
    '  ros::Publisher pub = nh.advertise<geometry_msgs::Twist>(/* vitesse 😀 café */"cmd_vel", 10);'
)
ENCODINGS = ["utf-8", "utf-16", "utf-32"]


def _offset(text: str, position: Message, encoding: str) -> int:
    """The code point offset in ``text`` of an LSP position counted in ``encoding``."""
    lines = text.splitlines(keepends=True)
    start = sum(len(line) for line in lines[: position["line"]])
    line = lines[position["line"]] if position["line"] < len(lines) else ""
    units = 0
    for index, character in enumerate(line):
        if units >= position["character"]:
            return start + index
        units += code_units(character, encoding)
    assert units == position["character"], "a position inside a character"
    return start + len(line)


def _apply(text: str, edits: list[Message], encoding: str) -> str:
    """The buffer after ``edits``, applied as a client of ``encoding`` applies them."""
    spans = [
        (_offset(text, e["range"]["start"], encoding), _offset(text, e["range"]["end"], encoding))
        for e in edits
    ]
    placed = sorted(zip(spans, edits, strict=True), key=lambda pair: pair[0], reverse=True)
    for (start, end), edit in placed:
        text = text[:start] + edit["newText"] + text[end:]
    return text


@pytest.fixture
def workspace(tmp_path: Path) -> tuple[Path, str]:
    """A catkin workspace with the driver; the driver's URI."""
    root = tmp_path / "ws"
    write_package(root / "src/robot_base", 1, "robot_base")
    driver = write(root, "src/robot_base/src/base_driver.cpp", DRIVER)
    return root, driver.as_uri()


@pytest.fixture
def server(workspace: tuple[Path, str], tmp_path: Path) -> Any:
    started: list[WireServer] = []

    def start() -> WireServer:
        started.append(WireServer(workspace[0], tmp_path / "cache"))
        return started[-1]

    yield start
    for one in started:
        one.close()


def _rn202(diagnostics: list[Message]) -> bool:
    return any(d["code"] == "RN202" for d in diagnostics)


@pytest.mark.parametrize("encoding", ENCODINGS)
def test_positions_are_counted_in_the_negotiated_encoding(
    server: Any, workspace: tuple[Path, str], encoding: str
) -> None:
    lsp: WireServer = server()
    uri = workspace[1]
    result = lsp.initialize([encoding])
    assert result["capabilities"]["positionEncoding"] == encoding
    lsp.open(uri, DRIVER, "cpp")
    (found,) = [d for d in lsp.diagnostics(uri, _rn202) if d["code"] == "RN202"]
    line = DRIVER.splitlines()[ADVERTISE_LINE]
    literal = line.index('"/cmd_vel"')
    assert found["range"] == {
        "start": {"line": ADVERTISE_LINE, "character": code_units(line[:literal], encoding)},
        "end": {"line": ADVERTISE_LINE, "character": code_units(line[: literal + 10], encoding)},
    }

    # The quick fix, applied by a client that counts in the same encoding: exactly the line
    # --fix writes.
    actions = lsp.call(
        "textDocument/codeAction",
        {
            "textDocument": {"uri": uri},
            "range": found["range"],
            "context": {"diagnostics": [found]},
        },
    )
    (fix,) = [a for a in actions if a["title"].startswith("RN202: write 'cmd_vel'")]
    fixed = _apply(DRIVER, fix["edit"]["changes"][uri], encoding)
    assert fixed.splitlines()[ADVERTISE_LINE] == FIXED_LINE
    assert fixed.replace(FIXED_LINE, line) == DRIVER

    # A code action asked for a range that starts past the emoji still finds the finding.
    after_emoji = code_units(line[: line.index("café")], encoding)
    actions = lsp.call(
        "textDocument/codeAction",
        {
            "textDocument": {"uri": uri},
            "range": {
                "start": {"line": ADVERTISE_LINE, "character": after_emoji},
                "end": found["range"]["start"],
            },
            "context": {"diagnostics": []},
        },
    )
    assert any(a["title"].startswith("RN202: write") for a in actions)
    # And a hover on the last character of the literal shows the rule, one past it nothing
    # (in UTF-8, a client column just past the literal is a UTF-16 column inside it).
    end = found["range"]["end"]["character"]
    at_end = {"line": ADVERTISE_LINE, "character": end}
    hover = lsp.call("textDocument/hover", {"textDocument": {"uri": uri}, "position": at_end})
    assert hover["contents"]["value"].startswith("# RN202 hard-coded-absolute-name")
    past = {"line": ADVERTISE_LINE, "character": end + 2}
    assert lsp.call("textDocument/hover", {"textDocument": {"uri": uri}, "position": past}) is None
    before = {"line": ADVERTISE_LINE, "character": found["range"]["start"]["character"] - 1}
    assert (
        lsp.call("textDocument/hover", {"textDocument": {"uri": uri}, "position": before}) is None
    )


def _driver_open(server: Any, workspace: tuple[Path, str]) -> tuple[WireServer, str]:
    """A started server with the driver open and its first diagnostics in."""
    lsp: WireServer = server()
    uri = workspace[1]
    lsp.initialize()
    lsp.open(uri, DRIVER, "cpp")
    lsp.diagnostics(uri, _rn202)
    return lsp, uri


def test_a_request_with_invalid_params_gets_an_error_response(
    server: Any, workspace: tuple[Path, str]
) -> None:
    lsp, uri = _driver_open(server, workspace)
    started = time.monotonic()
    broken = lsp.request("textDocument/hover", {"textDocument": {"uri": uri}})  # no position
    answer = lsp.response(broken, timeout=5)
    assert time.monotonic() - started < 5
    assert answer["error"]["code"] == -32602  # InvalidParams
    assert "position" in answer["error"]["message"]
    wrong_type = lsp.request(
        "textDocument/codeAction",
        {"textDocument": {"uri": uri}, "range": "line 7", "context": {"diagnostics": []}},
    )
    assert lsp.response(wrong_type, timeout=5)["error"]["code"] == -32602
    # The server goes on: the next request has its answer.
    place = {"textDocument": {"uri": uri}, "position": ON_THE_LITERAL}
    assert lsp.call("textDocument/hover", place) is not None
    assert not lsp.notifications("window/showMessage")


def test_malformed_messages_and_unknown_documents_are_logged_not_shown(
    server: Any, workspace: tuple[Path, str]
) -> None:
    lsp, uri = _driver_open(server, workspace)
    never_opened = (workspace[0] / "src/robot_base/src/teleop.cpp").as_uri()
    lsp.notify(
        "textDocument/didChange",
        {
            "textDocument": {"uri": never_opened, "version": 2},
            "contentChanges": [{"text": DRIVER}],
        },
    )
    lsp.notify("textDocument/didClose", {"textDocument": {"uri": never_opened}})
    lsp.send_body(b'{"jsonrpc": "2.0", "method": "textDocument/didChange", "par')
    lsp.notify("textDocument/didSave", {"document": uri})  # invalid params, no answer due
    place = {"textDocument": {"uri": uri}, "position": ON_THE_LITERAL}
    assert lsp.call("textDocument/hover", place) is not None
    # Edits of the open document are still followed.
    lsp.notify(
        "textDocument/didChange",
        {
            "textDocument": {"uri": uri, "version": 2},
            "contentChanges": [{"text": DRIVER.replace('"/cmd_vel"', '"cmd_vel"')}],
        },
    )
    lsp.diagnostics(uri, lambda found: not found, timeout=10)
    # A lone surrogate (JSON can carry one) is one character, not a failed check.
    lone = DRIVER.replace("café", "caf\ud800")
    lsp.notify(
        "textDocument/didChange",
        {"textDocument": {"uri": uri, "version": 3}, "contentChanges": [{"text": lone}]},
    )
    (found,) = lsp.diagnostics(uri, _rn202, timeout=10)
    assert found["range"]["start"] == {"line": ADVERTISE_LINE, "character": 79}
    assert not lsp.notifications("window/showMessage")
    logged = " ".join(m["params"]["message"] for m in lsp.notifications("window/logMessage"))
    assert never_opened in logged
    assert "KeyError" not in logged


def _big_driver(size: int, head: str = DRIVER) -> str:
    """A generated C++ file of about ``size`` bytes, every line of it a finding."""
    line = '  ros::Publisher pub{0} = nh.advertise<std_msgs::String>("/Generated_{0}", 1);\n'
    lines = [head.split("  ros::spin", maxsplit=1)[0]]
    total = len(lines[0])
    index = 0
    while total < size:
        lines.append(line.format(index))
        total += len(lines[-1])
        index += 1
    return "".join(lines) + "}\n"


def test_a_50_mb_edit_is_not_checked_and_the_server_stays_responsive(
    server: Any, workspace: tuple[Path, str]
) -> None:
    lsp, uri = _driver_open(server, workspace)
    huge = _big_driver(50 * 1024 * 1024)
    lsp.notify(
        "textDocument/didChange",
        {"textDocument": {"uri": uri, "version": 2}, "contentChanges": [{"text": huge}]},
    )
    del huge
    started = time.monotonic()
    place = {"textDocument": {"uri": uri}, "position": ON_THE_LITERAL}
    lsp.call("textDocument/hover", place, timeout=10)
    assert time.monotonic() - started < 10
    # Above max-file-size: not checked, its diagnostics cleared, and the log says why.
    # (Publications are waited for after the log line: the first, while the workspace was
    # read, held the document's own findings only, none here.)
    said = lsp.wait_for(
        lambda m: m.get("method") == "window/logMessage" and "max-file-size" in str(m), 10
    )
    after = next(index for index, m in enumerate(lsp.received) if m is said)

    def cleared(message: Message) -> bool:
        return (
            message.get("method") == "textDocument/publishDiagnostics"
            and message["params"]["uri"] == uri
            and not message["params"]["diagnostics"]
            and any(m is message for m in lsp.received[after:])
        )

    lsp.wait_for(cleared, 10)
    (why,) = [
        m["params"]["message"]
        for m in lsp.notifications("window/logMessage")
        if "max-file-size" in m["params"]["message"]
    ]
    assert "base_driver.cpp" in why and "50.0 MiB" in why
    peak = lsp.peak_memory_bytes()
    if peak is not None:
        assert peak < 600 * 1024 * 1024, f"peak RSS {peak / 2**20:.0f} MiB"
    # Back under the limit, the document is checked again.
    lsp.notify(
        "textDocument/didChange",
        {"textDocument": {"uri": uri, "version": 3}, "contentChanges": [{"text": DRIVER}]},
    )
    lsp.diagnostics(uri, _rn202, timeout=10)
    assert lsp.call("shutdown", None, timeout=5) is None
    # A request after shutdown is refused, not left unanswered.
    late = lsp.response(lsp.request("textDocument/hover", place), timeout=5)
    assert late["error"]["code"] == -32600  # InvalidRequest
    lsp.notify("exit", None)
    assert lsp.process.wait(timeout=5) == 0


def test_exit_is_honoured_while_a_check_runs(server: Any, workspace: tuple[Path, str]) -> None:
    lsp, uri = _driver_open(server, workspace)
    # Under the limit, but a check of it takes seconds.
    lsp.notify(
        "textDocument/didChange",
        {
            "textDocument": {"uri": uri, "version": 2},
            "contentChanges": [{"text": _big_driver(4 * 1024 * 1024)}],
        },
    )
    time.sleep(0.5)  # the typing pause is over: the check has started
    started = time.monotonic()
    assert lsp.call("shutdown", None, timeout=5) is None
    lsp.notify("exit", None)
    assert lsp.process.wait(timeout=5) == 0
    assert time.monotonic() - started < 5


def test_200_edits_in_a_row_make_one_check_of_the_last_text(
    server: Any, workspace: tuple[Path, str]
) -> None:
    lsp: WireServer = server()
    uri = workspace[1]
    lsp.initialize(["utf-8"])
    # A form feed is no line break to LSP (nor to the parsers): the lines below it keep
    # their numbers.
    text = DRIVER.replace(
        "#include <geometry_msgs/Twist.h>\n", "#include <geometry_msgs/Twist.h>\f\n"
    )
    lsp.open(uri, text, "cpp")
    lsp.diagnostics(uri, _rn202)
    before = len(lsp.notifications("textDocument/publishDiagnostics"))
    # The user types 200 letters into the topic, after the emoji: incremental edits whose
    # columns count UTF-8 bytes.
    line = text.split("\n")[ADVERTISE_LINE]
    column = code_units(line[: line.index('"/cmd_vel"') + len('"/cmd_vel')], "utf-8")
    typed = "".join("abcdefghijklmnopqrstuvwxyz"[i % 26] for i in range(200))
    for version, letter in enumerate(typed, start=2):
        lsp.notify("textDocument/didChange", _typed(uri, version, ADVERTISE_LINE, column, letter))
        column += 1
    started = time.monotonic()
    lsp.call("textDocument/hover", {"textDocument": {"uri": uri}, "position": ON_THE_LITERAL}, 5)
    assert time.monotonic() - started < 5
    name = f"/cmd_vel{typed}"
    found = lsp.diagnostics(uri, lambda d: any(name in x["message"] for x in d), timeout=30)
    assert [d["code"] for d in found] == ["RN202"]
    published = lsp.notifications("textDocument/publishDiagnostics")[before:]
    assert len(published) <= 3, f"{len(published)} publications for one burst of typing"


def _typed(uri: str, version: int, line: int, column: int, letter: str) -> Message:
    """A didChange that types ``letter`` at ``line``, ``column``."""
    at = {"line": line, "character": column}
    return {
        "textDocument": {"uri": uri, "version": version},
        "contentChanges": [{"range": {"start": at, "end": at}, "text": letter}],
    }


def test_typing_in_a_20_mb_document_costs_the_edit_not_the_document(
    server: Any, workspace: tuple[Path, str]
) -> None:
    lsp: WireServer = server()
    uri = workspace[1]
    lsp.initialize()
    # ASCII, as generated files are: a str of one byte a character (an emoji anywhere makes
    # it four, and every edit's copy of the text four times as long).
    huge = _big_driver(20 * 1024 * 1024, head=DRIVER.replace(" 😀 café", ""))
    last_line = huge.count("\n") - 2
    lsp.open(uri, huge, "cpp")
    lsp.diagnostics(uri, lambda found: not found, timeout=10)  # above max-file-size
    for version in range(2, 102):  # 100 keystrokes near the end of the file
        lsp.notify("textDocument/didChange", _typed(uri, version, last_line, version, "x"))
    started = time.monotonic()
    lsp.call("textDocument/hover", {"textDocument": {"uri": uri}, "position": ON_THE_LITERAL}, 10)
    assert time.monotonic() - started < 3
    # Cut back to the driver by a range edit: the text the server kept is the client's.
    end = {"line": last_line + 2, "character": 0}
    lsp.notify(
        "textDocument/didChange",
        {
            "textDocument": {"uri": uri, "version": 102},
            "contentChanges": [
                {"range": {"start": {"line": 0, "character": 0}, "end": end}, "text": DRIVER},
            ],
        },
    )
    (found,) = lsp.diagnostics(uri, _rn202, timeout=10)
    assert found["range"]["start"] == {"line": ADVERTISE_LINE, "character": 79}
