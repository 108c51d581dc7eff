"""``roslint-names server``: the Language Server Protocol over stdio, with pygls.

The workspace the client opens is read once into a ``session.Session`` (through the facts
cache, so a second start is quick). Then, for each open document:

- on open and save at once, on change once typing has paused for ``TYPING_PAUSE_S``, the
  document's text (saved or not) is checked and its diagnostics published;
- once changes have paused for ``GRAPH_PAUSE_S`` (counted from the last change, open or
  save, not from the check that followed it: a change made meanwhile puts it off), and
  the checks of those changes are done, the workspace graph is built again in a worker
  thread and the graph rules' findings published for every open document.

Code actions offer each finding's fix (the same edit ``--fix`` makes, marked unsafe where
it is) and a suppression of the finding on its line in the file's own comment form;
hovering a finding shows its rule's catalog page.

What the server guarantees, whatever the client sends:

- every position it sends or reads is counted in the encoding negotiated at ``initialize``
  (UTF-8, UTF-16 or UTF-32 code units; the linter's columns are code points);
- every request is answered: one whose parameters cannot be read gets an InvalidParams
  error, one after ``shutdown`` an InvalidRequest error;
- a malformed message, or an edit of a document never opened, is a log line
  (``window/logMessage``), never a pop-up;
- the session's work (loading, checks, graph builds) runs in one worker thread, so the
  event loop always reads the next message: ``shutdown`` and ``exit`` are honoured at
  once, whatever check is running (the worker is a daemon thread: exit does not wait);
- an incremental edit costs the distance from the previous one and one copy of the text,
  lines counted as LSP counts them (CR, LF, CRLF);
- a document above ``max-file-size`` is not checked: its diagnostics are cleared and one
  log line says why, and the server's own code neither encodes nor splits its text.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import logging
import os
import queue
import threading
import time
from collections.abc import Callable, Generator
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, TypeVar
from urllib.parse import unquote

import cattrs
from lsprotocol import types
from pygls.exceptions import JsonRpcException, JsonRpcInvalidParams, JsonRpcInvalidRequest
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol, lsp_method
from pygls.uris import from_fs_path, to_fs_path

from . import __version__
from .cache import FactsCache
from .cache import default_directory as default_cache_directory
from .catalog import CatalogError, load_doc
from .config import ConfigError, Settings, load_settings
from .discover import classify, editor_workspace
from .editing.noqa import with_suppressions
from .lines import split_lines
from .model import Diagnostic, Edit, Severity, Span
from .registry import Registry, load_registry
from .session import Session

TYPING_PAUSE_S = 0.1  # a change is checked once the user has paused this long
GRAPH_PAUSE_S = 0.4  # and the workspace graph rebuilt once changes pause this long
SOURCE = "roslint-names"
SUPPRESS = "suppress"

log = logging.getLogger(__name__)
T = TypeVar("T")


@dataclass
class _Published:
    """What was last published for a document: to answer code actions and hovers."""

    text: str
    diagnostics: list[Diagnostic]
    positions: _Positions


@dataclass(frozen=True)
class _Unreadable:
    """A request whose parameters could not be read: answered with an error."""

    id: int | str
    method: str
    error: JsonRpcException


class _Protocol(LanguageServerProtocol):
    """pygls's protocol, answering every request and ignoring edits of unknown documents.

    pygls reads a request's parameters while it parses the JSON; when they do not fit the
    method's type it raises out of the parser, and the request, its id lost, is never
    answered. Here the failure becomes an ``_Unreadable`` that ``handle_message`` answers.
    """

    _server: RoslintServer
    _hints: dict[str, _LineHint]

    def __init__(self, server: RoslintServer, converter: cattrs.Converter) -> None:
        super().__init__(server, converter)
        self._hints = {}

    def structure_message(self, data: dict[str, Any]) -> Any:
        try:
            return super().structure_message(data)
        except JsonRpcException as error:
            if "id" in data and isinstance(data.get("method"), str):
                return _Unreadable(data["id"], data["method"], error)
            raise

    def handle_message(self, message: Any) -> None:
        if isinstance(message, _Unreadable):
            reason = f"invalid params for {message.method}: {_why(message.error)}"
            self._server.log_line(f"request {message.id!r}: {reason}", types.MessageType.Warning)
            self._send_response(message.id, None, JsonRpcInvalidParams(reason).to_response_error())
            return
        method = getattr(message, "method", types.EXIT)
        if self._shutdown and method != types.EXIT and hasattr(message, "id"):
            # pygls would drop a request after shutdown: the client waits for its answer.
            refused = JsonRpcInvalidRequest("the server is shutting down")
            self._send_response(message.id, None, refused.to_response_error())
            return
        super().handle_message(message)

    @lsp_method(types.TEXT_DOCUMENT_DID_CHANGE)
    def lsp_text_document__did_change(
        self, params: types.DidChangeTextDocumentParams
    ) -> Generator[Any, Any, None]:
        """pygls's, but with the edits applied by ``_apply``: pygls splits the whole text
        into lines for every keystroke (half a second in a 50 MB document), and at more
        characters than LSP's CR, LF and CRLF (a form feed moved every later edit)."""
        uri = params.text_document.uri
        if not self._is_open(uri, "an edit"):
            return
        document = self.workspace.text_documents[unquote(uri)]
        hint = self._hints.setdefault(uri, _LineHint())
        encoding = self._server.encoding
        for change in params.content_changes:
            document.apply_change(
                types.TextDocumentContentChangeWholeDocument(
                    _apply(document.source, change, encoding, hint)
                )
            )
        document.version = params.text_document.version
        if (handler := self.fm.features.get(types.TEXT_DOCUMENT_DID_CHANGE)) is not None:
            yield handler, (params,), None

    @lsp_method(types.TEXT_DOCUMENT_DID_OPEN)
    def lsp_text_document__did_open(
        self, params: types.DidOpenTextDocumentParams
    ) -> Generator[Any, Any, None]:
        self._hints.pop(params.text_document.uri, None)  # a new text: no place known in it
        yield from super().lsp_text_document__did_open(params)

    @lsp_method(types.TEXT_DOCUMENT_DID_CLOSE)
    def lsp_text_document__did_close(
        self, params: types.DidCloseTextDocumentParams
    ) -> Generator[Any, Any, None]:
        self._hints.pop(params.text_document.uri, None)
        if self._is_open(params.text_document.uri, "a close"):
            yield from super().lsp_text_document__did_close(params)

    def _is_open(self, uri: str, what: str) -> bool:
        if unquote(uri) in self.workspace.text_documents:
            return True
        self._server.log_line(f"ignored {what} of {uri}: the document is not open")
        return False


@dataclass(frozen=True)
class _Prepared:
    """The workspace the editor's root lies in, and its settings."""

    opened: Path  # the editor's root
    in_workspace: bool  # False: a directory no workspace holds, never read whole
    root: Path
    settings: Settings
    registry: Registry


def _first_look(prepared: _Prepared, path: Path, text: str) -> list[Diagnostic] | None:
    """A document's findings from its own text alone, on a session of its own that has read
    nothing: the rules that take something from other files (the names launch files wire,
    the plugins packages export, the service types of the workspace) wait for the real one,
    so that nothing published now is taken back."""
    waiting = tuple(
        rule.code
        for rule in prepared.registry.rules
        if rule.reads_wiring or rule.reads_plugins or rule.code in _READS_SERVICE_TYPES
    )
    settings = replace(prepared.settings, ignore=(*prepared.settings.ignore, *waiting))
    session = Session(prepared.root, settings, prepared.registry, None)
    if session.skip_reason(text) is not None:
        return None  # too large to check: the real session says so, once
    return session.check(path, text)


# RN204 compares a service's name with the service types the workspace defines.
_READS_SERVICE_TYPES = frozenset({"RN204"})


class _Worker:
    """One daemon thread that runs the session's work, one job at a time, in order.

    A session is not thread-safe, and a check of a large document takes seconds: it must
    not run on the event loop. A daemon thread, unlike an executor's, does not hold the
    process once the client says exit. A job cancelled before it starts is not run.
    """

    def __init__(self) -> None:
        self._jobs: queue.SimpleQueue[tuple[Callable[[], Any], concurrent.futures.Future[Any]]]
        self._jobs = queue.SimpleQueue()
        self._thread: threading.Thread | None = None

    def run(self, job: Callable[[], T]) -> asyncio.Future[T]:
        if self._thread is None:
            self._thread = threading.Thread(target=self._serve, name="session", daemon=True)
            self._thread.start()
        done: concurrent.futures.Future[T] = concurrent.futures.Future()
        self._jobs.put((job, done))
        return asyncio.wrap_future(done)

    def _serve(self) -> None:
        while True:
            job, done = self._jobs.get()
            if not done.set_running_or_notify_cancel():
                continue
            try:
                done.set_result(job())
            except BaseException as error:  # handed to whoever awaits the job
                done.set_exception(error)


class RoslintServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("roslint-names", __version__, protocol_cls=_Protocol)
        self.session: Session | None = None
        self.published: dict[str, _Published] = {}
        self._pending: dict[str, asyncio.Task[None]] = {}
        self._graph: asyncio.Task[None] | None = None
        self._loading: asyncio.Task[Session | None] | None = None
        self._prepared: _Prepared | None = None
        self._worker = _Worker()
        self._skipped: set[str] = set()  # documents above max-file-size, logged once
        self._last_change = 0.0  # ``time.monotonic()`` of the last change, open or save

    def log_line(self, message: str, kind: types.MessageType = types.MessageType.Info) -> None:
        """A line in the client's log (and the server's): never a pop-up."""
        log.info("%s", message)
        self.window_log_message(types.LogMessageParams(kind, f"roslint-names: {message}"))

    def report_server_error(self, error: Exception, source: type[Exception]) -> None:
        """A message pygls could not read is logged; other errors are pygls's to report."""
        if source is JsonRpcException:
            self.log_line(f"ignored a message: {_why(error)}", types.MessageType.Warning)
            return
        super().report_server_error(error, source)  # type: ignore[arg-type]

    @property
    def encoding(self) -> str:
        """The position encoding negotiated at ``initialize``: LSP's UTF-16 until then."""
        try:
            negotiated = self.workspace.position_encoding
        except RuntimeError:  # not initialized
            return types.PositionEncodingKind.Utf16.value
        return str(getattr(negotiated, "value", negotiated or "utf-16"))

    def workspace_root(self) -> Path | None:
        """The root of the workspace the server reads, once it has found it."""
        return None if self._prepared is None else self._prepared.root

    async def ready_session(self) -> Session | None:
        # Shielded: a waiter cancelled (a handler, a check put off by a newer change) must
        # not cancel the reading of the workspace, which every later check waits for.
        return await asyncio.shield(self._start_loading())

    def _start_loading(self) -> asyncio.Task[Session | None]:
        if self._loading is None:
            self._prepared = self._prepare()
            self._loading = asyncio.ensure_future(self._read(self._prepared))
        return self._loading

    def _prepare(self) -> _Prepared | None:
        """Where the workspace is and its settings; None (said in a message) when its
        configuration is broken."""
        opened = Path(self.workspace.root_path or os.getcwd()).absolute()
        # The editor's root may be a package (the graph rules then miss the packages beside
        # it) or any directory at all (reading a home directory takes minutes): the
        # workspace is found from it, and none is read where there is none.
        workspace = editor_workspace(opened)
        root = opened if workspace is None else workspace
        try:
            registry = load_registry()
            settings = load_settings(None, root, registry)
        except ConfigError as error:
            self.window_show_message(
                types.ShowMessageParams(types.MessageType.Error, f"roslint-names: {error}")
            )
            return None
        os.chdir(root)  # the engine shows and matches paths relative to the workspace
        return _Prepared(opened, workspace is not None, root, settings, registry)

    async def _read(self, prepared: _Prepared | None) -> Session | None:
        if prepared is None:
            return None
        directory = default_cache_directory()
        cache = None if directory is None else FactsCache(directory.absolute())
        session = Session(prepared.root, prepared.settings, prepared.registry, cache)
        if not prepared.in_workspace:
            self.log_line(
                f"{prepared.opened} is in no ROS workspace (no src/ with packages, no git "
                "root, no package): only the open documents are checked"
            )
        else:
            started = time.monotonic()
            await self._worker.run(session.load)
            self.log_line(
                f"read the workspace {prepared.root} in {time.monotonic() - started:.1f} s"
            )
        self.session = session
        return session

    def schedule(self, uri: str, delay: float) -> None:
        """Check ``uri`` after ``delay``, unless it changes again before."""
        self._last_change = time.monotonic()
        pending = self._pending.pop(uri, None)
        if pending is not None:
            pending.cancel()
        self._pending[uri] = asyncio.ensure_future(self._check(uri, delay))

    async def _check(self, uri: str, delay: float) -> None:
        await asyncio.sleep(delay)
        loading = self._start_loading()
        path = to_fs_path(uri)
        document = self.workspace.text_documents.get(unquote(uri))
        if not loading.done() and self._prepared is not None and path and document:
            # While the workspace is read (seconds, on a large one), the document's own
            # findings: those that need no other file; the rest follow once it is read.
            text = document.source
            early = await asyncio.to_thread(_first_look, self._prepared, Path(path), text)
            if early is not None and not loading.done():
                self.publish(uri, text, early)
        session = await asyncio.shield(loading)  # put off, never the reading (``ready_session``)
        if session is None or path is None or document is None:
            return
        text = document.source
        too_large = session.skip_reason(text)
        if too_large is not None:
            await self._worker.run(lambda: session.skip(Path(path)))
            if uri not in self._skipped:
                self._skipped.add(uri)
                self.log_line(f"not checked: {session.display(Path(path))}: {too_large}")
            self.publish(uri, text, [])
            return
        self._skipped.discard(uri)
        try:
            found = await self._worker.run(lambda: session.check(Path(path), text))
        except Exception as error:  # a bug of the linter: said in the log, the editor goes on
            log.exception("checking %s", uri)
            failed = f"checking {session.display(Path(path))} failed: {error!r}"
            self.log_line(failed, types.MessageType.Error)
            return
        if found is None:
            return
        self.publish(uri, text, found)
        self._schedule_graph()

    def _schedule_graph(self) -> None:
        if self._graph is not None:
            self._graph.cancel()
        self._graph = asyncio.ensure_future(self._check_graph())

    async def _check_graph(self) -> None:
        # Scheduled once a check is published, which comes ``TYPING_PAUSE_S`` and the
        # check's own time after the change: only the rest of the pause is left to wait.
        while (left := self._last_change + GRAPH_PAUSE_S - time.monotonic()) > 0:
            await asyncio.sleep(left)
        session = self.session
        if session is None:
            return
        for display, found in (await self._worker.run(session.check_graph)).items():
            uri = from_fs_path(str(session.root / display))
            if uri is not None and uri in self.published:
                self.publish(uri, self.published[uri].text, found)

    def publish(self, uri: str, text: str, found: list[Diagnostic]) -> None:
        shown = [d for d in found if not d.suppressed]
        # The lines only where there is something to place on them: a document too large to
        # check is not split.
        positions = _Positions(split_lines(text) if shown else [], self.encoding)
        self.published[uri] = _Published(text, shown, positions)
        self.text_document_publish_diagnostics(
            types.PublishDiagnosticsParams(uri, [_diagnostic(d, positions) for d in shown])
        )

    def forget(self, uri: str) -> None:
        self.published.pop(uri, None)
        self._skipped.discard(uri)
        pending = self._pending.pop(uri, None)
        if pending is not None:
            pending.cancel()
        path = to_fs_path(uri)
        session = self.session
        if session is not None and path is not None:
            self._worker.run(lambda: session.close(Path(path)))
        self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(uri, []))


server = RoslintServer()


@server.feature(types.INITIALIZED)
async def initialized(ls: RoslintServer, params: types.InitializedParams) -> None:
    await ls.ready_session()


@server.feature(types.TEXT_DOCUMENT_DID_OPEN)
def did_open(ls: RoslintServer, params: types.DidOpenTextDocumentParams) -> None:
    ls.schedule(params.text_document.uri, 0)


@server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
def did_change(ls: RoslintServer, params: types.DidChangeTextDocumentParams) -> None:
    ls.schedule(params.text_document.uri, TYPING_PAUSE_S)


@server.feature(types.TEXT_DOCUMENT_DID_SAVE)
def did_save(ls: RoslintServer, params: types.DidSaveTextDocumentParams) -> None:
    ls.schedule(params.text_document.uri, 0)


@server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
def did_close(ls: RoslintServer, params: types.DidCloseTextDocumentParams) -> None:
    ls.forget(params.text_document.uri)


@server.feature(
    types.TEXT_DOCUMENT_CODE_ACTION,
    types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix]),
)
def code_action(ls: RoslintServer, params: types.CodeActionParams) -> list[types.CodeAction]:
    uri = params.text_document.uri
    published = ls.published.get(uri)
    path = to_fs_path(uri)
    # Known before the workspace is read: the findings published meanwhile have actions too.
    root = ls.workspace_root()
    if published is None or path is None or root is None:
        return []
    positions = published.positions
    wanted = params.range  # in the client's units, as the ranges it is compared with
    actions: list[types.CodeAction] = []
    for diagnostic in published.diagnostics:
        shown = positions.range(diagnostic.span)
        if not _overlaps(shown, wanted):
            continue
        lsp_diagnostic = _diagnostic(diagnostic, positions)
        if diagnostic.edit is not None:
            actions.append(_fix_action(root, uri, diagnostic, positions, lsp_diagnostic))
        suppress = _suppress_action(Path(path), uri, published.text, diagnostic, lsp_diagnostic)
        if suppress is not None:
            actions.append(suppress)
    return actions


@server.feature(types.TEXT_DOCUMENT_HOVER)
def hover(ls: RoslintServer, params: types.HoverParams) -> types.Hover | None:
    published = ls.published.get(params.text_document.uri)
    if published is None:
        return None
    pages: list[str] = []
    for diagnostic in published.diagnostics:
        shown = published.positions.range(diagnostic.span)
        if _contains(shown, params.position):
            try:
                pages.append(load_doc(diagnostic.code, diagnostic.rule_name).markdown)
            except CatalogError:
                continue
    if not pages:
        return None
    markdown = "\n\n---\n\n".join(dict.fromkeys(pages))
    return types.Hover(types.MarkupContent(types.MarkupKind.Markdown, markdown))


def serve() -> None:
    """Speak LSP on stdin and stdout until the client says exit."""
    logging.basicConfig(level=logging.WARNING)
    server.start_io()


# ---------------------------------------------------------------------------------------
# From the linter's spans (1-based lines, code point columns) to LSP's (0-based lines,
# columns in code units of the negotiated encoding)


@dataclass
class _Positions:
    """A document's lines, and how its client counts columns."""

    lines: list[str]
    encoding: str
    _others: dict[str, _Positions] = field(default_factory=dict)

    def position(self, line: int, column: int) -> types.Position:
        text = self.lines[line - 1] if 0 < line <= len(self.lines) else ""
        return types.Position(max(line - 1, 0), _units(text[: max(column - 1, 0)], self.encoding))

    def range(self, span: Span) -> types.Range:
        return types.Range(
            self.position(span.line, span.column), self.position(span.end_line, span.end_column)
        )

    def of(self, path: Path) -> _Positions:
        """Another file's positions, as it is on disk (read once)."""
        key = str(path)
        if key not in self._others:
            self._others[key] = _Positions(_disk_lines(path), self.encoding)
        return self._others[key]


def _units(text: str, encoding: str) -> int:
    """How many code units of ``encoding`` ``text`` takes."""
    if encoding == types.PositionEncodingKind.Utf32.value:
        return len(text)
    if encoding == types.PositionEncodingKind.Utf8.value:
        return len(text.encode("utf-8", errors="surrogatepass"))
    return len(text.encode("utf-16-le", errors="surrogatepass")) // 2


def _why(error: Exception) -> str:
    """What was wrong with a message, in a line: cattrs's own words for bad parameters."""
    cause = error.__cause__
    if isinstance(cause, cattrs.ClassValidationError):
        return "; ".join(cattrs.transform_error(cause))
    return str(error) or type(error).__name__


def _diagnostic(diagnostic: Diagnostic, positions: _Positions) -> types.Diagnostic:
    severity = (
        types.DiagnosticSeverity.Error
        if diagnostic.severity is Severity.ERROR
        else types.DiagnosticSeverity.Warning
    )
    return types.Diagnostic(
        range=positions.range(diagnostic.span),
        message=diagnostic.message,
        severity=severity,
        code=diagnostic.code,
        source=SOURCE,
        code_description=types.CodeDescription(
            f"https://github.com/roslint-names/roslint-names/blob/main/rules/"
            f"{diagnostic.code}-{diagnostic.rule_name}.md"
        ),
        related_information=[
            types.DiagnosticRelatedInformation(
                types.Location(
                    from_fs_path(os.path.abspath(related.path)) or related.path,
                    (
                        positions
                        if related.path == diagnostic.path
                        else positions.of(Path(os.path.abspath(related.path)))
                    ).range(related.span),
                ),
                related.message,
            )
            for related in diagnostic.related
        ]
        or None,
    )


# ---------------------------------------------------------------------------------------
# A client's incremental edits, applied at the cost of the distance from the last one


@dataclass
class _LineHint:
    """Where one line of a document starts: the last place an edit was made. Typing edits
    near the previous edit, so finding the next one costs that distance, not the text."""

    line: int = 0
    start: int = 0


def _apply(
    text: str, change: types.TextDocumentContentChangeEvent, encoding: str, hint: _LineHint
) -> str:
    """``text`` after ``change``, its range counted in ``encoding``."""
    if not isinstance(change, types.TextDocumentContentChangePartial):
        hint.line, hint.start = 0, 0
        return change.text
    start = _offset(text, change.range.start, encoding, hint)
    kept = _LineHint(hint.line, hint.start)  # before the edit: still right after it,
    if kept.start > 0 and text[kept.start - 1] == "\r":  # unless a LF joins that CR
        kept = _LineHint(kept.line - 1, _previous_line_start(text, kept.start))
    end = _offset(text, change.range.end, encoding, hint)
    if end < start:  # a range given backwards
        start, end = end, start
        hint.line, hint.start = 0, 0
    else:
        hint.line, hint.start = kept.line, kept.start
    return "".join((text[:start], change.text, text[end:]))  # one copy of the text, not two


def _offset(text: str, position: types.Position, encoding: str, hint: _LineHint) -> int:
    """The index in ``text`` of a client's position; past a line's end is its end."""
    start = _line_start(text, position.line, hint)
    line = text[start : _line_end(text, start)]
    if encoding == types.PositionEncodingKind.Utf32.value or line.isascii():
        return start + min(position.character, len(line))
    units = 0
    for index, character in enumerate(line):
        if units >= position.character:
            return start + index
        units += _units(character, encoding)
    return start + len(line)


def _line_start(text: str, line: int, hint: _LineHint) -> int:
    if line < hint.line - line:  # nearer the top than the hint: from the top
        hint.line, hint.start = 0, 0
    while hint.line > line:
        hint.start = _previous_line_start(text, hint.start)
        hint.line -= 1
    while hint.line < line:
        following = _next_line_start(text, hint.start)
        if following < 0:  # past the last line: its end
            return len(text)
        hint.line, hint.start = hint.line + 1, following
    return hint.start


def _line_end(text: str, start: int) -> int:
    newline = text.find("\n", start)
    limit = len(text) if newline < 0 else newline
    carriage = text.find("\r", start, limit)
    return limit if carriage < 0 else carriage


def _next_line_start(text: str, start: int) -> int:
    """Where the line after the one at ``start`` starts; -1 if it is the last."""
    end = _line_end(text, start)
    if end == len(text):
        return -1
    return end + 2 if text.startswith("\r\n", end) else end + 1


def _previous_line_start(text: str, start: int) -> int:
    """Where the line before the one at ``start`` (not the first) starts."""
    end = start - 2 if start >= 2 and text.startswith("\r\n", start - 2) else start - 1
    newline = text.rfind("\n", 0, end)
    carriage = text.rfind("\r", newline + 1, end)
    return max(newline, carriage) + 1


def _overlaps(one: types.Range, other: types.Range) -> bool:
    return _before_or_at(one.start, other.end) and _before_or_at(other.start, one.end)


def _contains(shown: types.Range, position: types.Position) -> bool:
    return _before_or_at(shown.start, position) and _before_or_at(position, shown.end)


def _before_or_at(one: types.Position, other: types.Position) -> bool:
    return (one.line, one.character) <= (other.line, other.character)


def _fix_action(
    root: Path,
    uri: str,
    diagnostic: Diagnostic,
    positions: _Positions,
    lsp_diagnostic: types.Diagnostic,
) -> types.CodeAction:
    edit = diagnostic.edit
    assert edit is not None
    changes: dict[str, list[types.TextEdit]] = {uri: [_text_edit(edit, positions)]}
    for other in diagnostic.also:
        other_uri = from_fs_path(str(root / (other.path or diagnostic.path))) or uri
        other_positions = positions if other_uri == uri else positions.of(root / (other.path or ""))
        changes.setdefault(other_uri, []).append(_text_edit(other, other_positions))
    safety = "" if edit.safe else " (unsafe: may change what the system does)"
    return types.CodeAction(
        title=f"{diagnostic.code}: write '{edit.text}'{safety}",
        kind=types.CodeActionKind.QuickFix,
        diagnostics=[lsp_diagnostic],
        edit=types.WorkspaceEdit(changes=changes),
        is_preferred=edit.safe,
    )


def _text_edit(edit: Edit, positions: _Positions) -> types.TextEdit:
    return types.TextEdit(positions.range(edit.span), edit.text)


def _disk_lines(path: Path) -> list[str]:
    try:
        return split_lines(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError):
        return []


def _suppress_action(
    path: Path,
    uri: str,
    text: str,
    diagnostic: Diagnostic,
    lsp_diagnostic: types.Diagnostic,
) -> types.CodeAction | None:
    """The finding suppressed on its line, as ``--add-noqa`` writes it."""
    suppressed = with_suppressions(text, classify(path), {diagnostic.span.line: {diagnostic.code}})
    if suppressed is None or not suppressed[1]:
        return None
    before, after = split_lines(text), split_lines(suppressed[0])
    # The comment changes one line, or adds one before a tag: replace from the first line
    # that differs to the last, counted from the end.
    first = next(
        (i for i, (old, new) in enumerate(zip(before, after, strict=False)) if old != new),
        min(len(before), len(after)),
    )
    tail = 0
    while tail < min(len(before), len(after)) - first and before[-1 - tail] == after[-1 - tail]:
        tail += 1
    old_end = len(before) - tail
    ending = "\r\n" if "\r\n" in text else "\n"
    new_text = "".join(line + ending for line in after[first : len(after) - tail])
    edit = types.TextEdit(
        types.Range(types.Position(first, 0), types.Position(old_end, 0)), new_text
    )
    return types.CodeAction(
        title=f"{diagnostic.code}: suppress on this line",
        kind=types.CodeActionKind.QuickFix,
        diagnostics=[lsp_diagnostic],
        edit=types.WorkspaceEdit(changes={uri: [edit]}),
    )
