"""The language server's latency on a workspace, as an editor sees it.

    python bench/lsp.py WORKSPACE [--edits N] [--cache DIR]

Starts ``roslint-names server`` as an editor would (a pygls client on stdio) with the
workspace as its root, after a CLI run has filled the facts cache (``--cache``, else a
fresh temporary one filled here): the warm workspace of the target. Then, for one launch
file, one C++ file and one Python file of the workspace, and that C++ file again with a
topic it publishes renamed (``cpp-names``) and with a class deriving from
``rclcpp::Node`` appended (``cpp-class``: the classes the parameters of nodes' code are
gathered through change), opens the document and makes ``--edits``
changes, each a whole-document change as editors send them, waiting between
two for everything the change brings. Measured, from the moment the change is sent:

- ``file``: until the document's diagnostics are published (its own text checked by the
  per-file rules, the last graph findings kept): the target is 0.5 s, the server's
  typing pause (``TYPING_PAUSE_S``) included;
- ``graph``: until they are published again with the graph rules' findings made anew
  over the whole workspace, which the server does once changes pause (``GRAPH_PAUSE_S``).

Also the time from ``initialized`` to the server's word that it read the workspace
(``load_s``: the session loading it from the warm cache) and to the first document's
first graph findings (``first_graph_s``: the first graph is a whole build; the edits
start after it).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from lsprotocol import types
from pygls.lsp.client import LanguageClient
from pygls.uris import from_fs_path

# The package this interpreter has installed, never one the current directory holds
# (``-c`` would put it first: a comparison of two installs run from a checkout measured
# the checkout's code twice): ``-P`` leaves the directory out and keeps ``PYTHONPATH``
# (a machine whose packages are a folder on it: ``-I`` ignored it, and the server could
# not start there), ``-I`` before Python 3.11.
CLI = [
    sys.executable,
    "-P" if sys.version_info >= (3, 11) else "-I",
    "-c",
    "import sys; from roslint_names.cli import main; sys.exit(main())",
]
SERVER = [*CLI, "server"]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("workspace", type=Path)
    parser.add_argument("--edits", type=int, default=10)
    parser.add_argument("--cache", type=Path, help="a facts cache the CLI filled for WORKSPACE")
    parser.add_argument("--json", type=Path, metavar="OUT")
    options = parser.parse_args(argv)
    results = latency(options.workspace.resolve(), options.edits, options.cache)
    print(json.dumps(results, indent=2))
    if options.json:
        options.json.write_text(json.dumps(results, indent=2) + "\n", encoding="utf-8")
    return 0


def latency(
    workspace: Path, edits: int, cache: Path | None = None, python_path: str | None = None
) -> dict[str, Any]:
    """Open and edit one file per language; the latencies in seconds. ``python_path``:
    where the server and the CLI import the package from first (``PYTHONPATH``; this
    process's, where not given): the code measured, such as a growth run's snapshot."""
    with tempfile.TemporaryDirectory(prefix="roslint-names-lsp-") as scratch:
        home = cache.parent if cache is not None else Path(scratch)
        environment = _environment(home, python_path or os.environ.get("PYTHONPATH"))
        if cache is None:  # fill one: the warm workspace the target is about
            # From the workspace, as the server runs: the cache knows files by that path.
            subprocess.run(
                [*CLI, "check", "--exit-zero", "."],
                cwd=workspace,
                env=environment,
                capture_output=True,
                check=False,
            )
        return asyncio.run(_measure(workspace, environment, edits))


def _environment(home: Path, python_path: str | None) -> dict[str, str]:
    """The server's and the CLI's whole environment: the cache under ``home``, no tool
    on the path, and the package from ``python_path`` where given (an environment
    without it imports the installed package, whatever code is measured)."""
    environment = {"XDG_CACHE_HOME": str(home), "PATH": ""}
    if python_path:
        environment["PYTHONPATH"] = python_path
    return environment


def pick(
    workspace: Path, suffixes: tuple[str, ...], marker: str, without: tuple[str, ...] = ()
) -> Path:
    """A mid-sized file of the workspace with ``marker`` in it, and none of ``without``:
    what a developer edits."""
    found = sorted(
        path
        for suffix in suffixes
        for path in workspace.rglob(f"*{suffix}")
        if path.is_file()
        and 2_000 < path.stat().st_size < 20_000
        and marker in (text := _text(path))
        and not any(word in text for word in without)
    )
    if not found:
        raise SystemExit(f"no {suffixes} file with {marker!r} in {workspace}")
    return found[len(found) // 2]


def _text(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return ""


class _Client:
    def __init__(self) -> None:
        self.lsp = LanguageClient("roslint-names-bench", "1")
        self.arrivals: dict[str, list[float]] = {}
        self.event = asyncio.Event()
        self.workspace_read: float | None = None  # when the server said it read it

        @self.lsp.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def published(params: types.PublishDiagnosticsParams) -> None:
            self.arrivals.setdefault(params.uri, []).append(time.perf_counter())
            self.event.set()

        @self.lsp.feature(types.WINDOW_LOG_MESSAGE)
        def logged(params: types.LogMessageParams) -> None:
            if "read the workspace " in params.message and self.workspace_read is None:
                self.workspace_read = time.perf_counter()

    async def arrivals_after(self, uri: str, count: int, timeout: float = 120) -> list[float]:
        async def wait() -> list[float]:
            while len(self.arrivals.get(uri, [])) < count:
                self.event.clear()
                await self.event.wait()
            return self.arrivals[uri]

        return await asyncio.wait_for(wait(), timeout)


async def _measure(workspace: Path, environment: dict[str, str], edits: int) -> dict[str, Any]:
    files = {
        "launch": pick(workspace, (".launch", ".launch.xml"), "<node"),
        "cpp": pick(workspace, (".cpp",), "create_publisher"),
        "python": pick(workspace, (".py",), "create_subscription"),
        "cpp-names": pick(workspace, (".cpp",), "create_publisher"),
        "cpp-class": pick(workspace, (".cpp",), "create_publisher"),
        "cpp-endpoints": pick(workspace, (".cpp",), "rclcpp::Node", ENDPOINT_CALLS),
    }
    client = _Client()
    await client.lsp.start_io(*SERVER, env=environment)
    results: dict[str, Any] = {"workspace": str(workspace), "edits": edits}
    try:
        root = from_fs_path(str(workspace)) or ""
        await client.lsp.initialize_async(
            types.InitializeParams(
                capabilities=types.ClientCapabilities(),
                root_uri=root,
                workspace_folders=[types.WorkspaceFolder(root, workspace.name)],
            )
        )
        started = time.perf_counter()
        client.lsp.initialized(types.InitializedParams())
        for language, path in files.items():
            uri = from_fs_path(str(path)) or ""
            text = path.read_text(encoding="utf-8")
            opened = time.perf_counter()
            client.lsp.text_document_did_open(
                types.DidOpenTextDocumentParams(
                    types.TextDocumentItem(uri=uri, language_id=language, version=1, text=text)
                )
            )
            # Counted from the open: ``cpp-names`` opens the C++ file again.
            before = len(client.arrivals.get(uri, []))
            arrivals = (await client.arrivals_after(uri, before + 2))[before:]  # its, the graph's
            # The server says it read the workspace before it publishes the diagnostics
            # made with it; it says nothing where it reads none.
            read = client.workspace_read
            if read is not None and arrivals[0] < read:
                # The first came before the workspace was read (its own findings alone):
                # then its diagnostics with the workspace, then the graph's, the first
                # graph a whole build. Edits start after it, or they would wait for it.
                arrivals = (await client.arrivals_after(uri, before + 3))[before:]
            if "load_s" not in results:
                results["load_s"] = round((read or arrivals[0]) - started, 3)
                results["first_graph_s"] = round(arrivals[-1] - started, 3)
            results.setdefault("open_s", {})[language] = round(arrivals[0] - opened, 3)
            file_s: list[float] = []
            graph_s: list[float] = []
            for edit in range(edits):
                changed = EDITS[language](text) if edit % 2 == 0 else text
                count = len(client.arrivals[uri])
                sent = time.perf_counter()
                client.lsp.text_document_did_change(
                    types.DidChangeTextDocumentParams(
                        types.VersionedTextDocumentIdentifier(uri=uri, version=edit + 2),
                        [types.TextDocumentContentChangeWholeDocument(text=changed)],
                    )
                )
                arrivals = await client.arrivals_after(uri, count + 2)
                file_s.append(arrivals[count] - sent)
                graph_s.append(arrivals[count + 1] - sent)
            results.setdefault("file", {})[language] = _summary(file_s, path, workspace)
            results.setdefault("graph", {})[language] = _summary(graph_s, path, workspace)
            client.lsp.text_document_did_close(
                types.DidCloseTextDocumentParams(types.TextDocumentIdentifier(uri))
            )
        await client.lsp.shutdown_async(None)
    finally:
        client.lsp.exit(None)
        await client.lsp.stop()
    return results


def _edited(text: str, line: str) -> str:
    """``text`` with ``line`` inserted in the middle (inside the root element of XML)."""
    lines = text.splitlines(keepends=True)
    middle = len(lines) // 2
    return "".join([*lines[:middle], line, *lines[middle:]])


_PUBLISHED = re.compile(r'create_publisher\s*<[^;]*?>\s*\(\s*"([^"]+)"')


def _renamed(text: str) -> str:
    """``text`` with the first topic it publishes by a literal name renamed."""
    found = _PUBLISHED.search(text)
    if found is None:
        raise SystemExit("no create_publisher with a literal topic in the C++ file picked")
    return f"{text[: found.end(1)]}_bench{text[found.end(1) :]}"


# What declares an endpoint in C++: a file with none of these, given a publisher, starts
# declaring endpoints (``cpp-endpoints``).
ENDPOINT_CALLS = (
    "create_publisher",
    "create_subscription",
    "create_service",
    "create_client",
    "create_server",
    "advertise",
    "subscribe",
)

# One edit each way, then the text as it was: a line that gives the document a finding
# (in the middle: ``_edited``), a topic renamed (``_renamed``: the graph changes, and
# the server patches it, ``workspace.patch``), a class added (named as no class the
# growth benchmark adds before it: a file's classes are known by name, and a second
# class of one name changes nothing), or a publisher in code that declared no endpoint
# (code no launch file starts is a program of its own where it declares some).
EDITS: dict[str, Callable[[str], str]] = {
    "launch": lambda text: _edited(
        text, '  <node name="bench-node" pkg="bench" type="bench_node"/>\n'
    ),
    "cpp": lambda text: _edited(text, '// bench: "cmd vel"\n'),
    "python": lambda text: _edited(text, '# bench: "cmd vel"\n'),
    "cpp-names": _renamed,
    "cpp-class": lambda text: f"{text}\nclass LspProbe : public rclcpp::Node\n{{\n}};\n",
    "cpp-endpoints": lambda text: (
        f"{text}\nvoid lsp_probe(rclcpp::Node & node)\n{{\n"
        '  node.create_publisher<std_msgs::msg::String>("lsp_probe", 1);\n}\n'
    ),
}


def _summary(values: list[float], path: Path, workspace: Path) -> dict[str, Any]:
    return {
        "file": path.relative_to(workspace).as_posix(),
        "median_s": round(statistics.median(values), 3),
        "max_s": round(max(values), 3),
    }


if __name__ == "__main__":
    sys.exit(main())
