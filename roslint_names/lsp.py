"""``roslint-names server``: the Language Server Protocol over stdio, with pygls.

The workspace the client opens is read once into a ``session.Session`` (through the facts
cache, so a second start is quick). Then, for each open document:

- on open and save at once, on change once typing has paused for ``TYPING_PAUSE_S``, the
  document's text (saved or not) is checked and its diagnostics published;
- once changes have paused for ``GRAPH_PAUSE_S``, the workspace graph is built again in
  a worker thread and the graph rules' findings published for every open document.

Code actions offer each finding's fix (the same edit ``--fix`` makes, marked unsafe where
it is) and a suppression of the finding on its line in the file's own comment form;
hovering a finding shows its rule's catalog page. Positions are converted between the
linter's code points and the UTF-16 units LSP counts by default.
"""

from __future__ import annotations

import asyncio
import logging
import os
from dataclasses import dataclass
from pathlib import Path

from lsprotocol import types
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from . import __version__
from .cache import FactsCache
from .cache import default_directory as default_cache_directory
from .catalog import CatalogError, load_doc
from .config import ConfigError, load_settings
from .discover import classify
from .editing.noqa import with_suppressions
from .lines import split_lines
from .model import Diagnostic, Edit, Severity, Span
from .registry import load_registry
from .session import Session

TYPING_PAUSE_S = 0.1  # a change is checked once the user has paused this long
GRAPH_PAUSE_S = 0.4  # and the workspace graph rebuilt once changes pause this long
SOURCE = "roslint-names"
SUPPRESS = "suppress"

log = logging.getLogger(__name__)


@dataclass
class _Published:
    """What was last published for a document: to answer code actions and hovers."""

    text: str
    diagnostics: list[Diagnostic]


class RoslintServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("roslint-names", __version__)
        self.session: Session | None = None
        self.published: dict[str, _Published] = {}
        self._pending: dict[str, asyncio.Task[None]] = {}
        self._graph: asyncio.Task[None] | None = None
        self._loading: asyncio.Task[Session | None] | None = None

    async def ready_session(self) -> Session | None:
        if self._loading is None:
            self._loading = asyncio.ensure_future(self._load())
        return await self._loading

    async def _load(self) -> Session | None:
        root = Path(self.workspace.root_path or os.getcwd())
        try:
            registry = load_registry()
            settings = load_settings(None, root, registry)
        except ConfigError as error:
            self.window_show_message(
                types.ShowMessageParams(types.MessageType.Error, f"roslint-names: {error}")
            )
            return None
        directory = default_cache_directory()
        cache = None if directory is None else FactsCache(directory.absolute())
        os.chdir(root)  # the engine shows and matches paths relative to the workspace
        session = Session(root, settings, registry, cache)
        await asyncio.get_running_loop().run_in_executor(None, session.load)
        self.session = session
        return session

    def schedule(self, uri: str, delay: float) -> None:
        """Check ``uri`` after ``delay``, unless it changes again before."""
        pending = self._pending.pop(uri, None)
        if pending is not None:
            pending.cancel()
        self._pending[uri] = asyncio.ensure_future(self._check(uri, delay))

    async def _check(self, uri: str, delay: float) -> None:
        await asyncio.sleep(delay)
        session = await self.ready_session()
        path = to_fs_path(uri)
        if session is None or path is None:
            return
        text = self.workspace.get_text_document(uri).source
        found = session.check(Path(path), text)
        if found is None:
            return
        self.publish(uri, text, found)
        self._schedule_graph()

    def _schedule_graph(self) -> None:
        if self._graph is not None:
            self._graph.cancel()
        self._graph = asyncio.ensure_future(self._check_graph())

    async def _check_graph(self) -> None:
        await asyncio.sleep(GRAPH_PAUSE_S)
        session = self.session
        if session is None:
            return
        job = session.graph_job()
        graph = await asyncio.get_running_loop().run_in_executor(None, job.build)
        for display, found in session.apply_graph(job, graph).items():
            uri = from_fs_path(str(session.root / display))
            if uri is not None and uri in self.published:
                self.publish(uri, self.published[uri].text, found)

    def publish(self, uri: str, text: str, found: list[Diagnostic]) -> None:
        shown = [d for d in found if not d.suppressed]
        self.published[uri] = _Published(text, shown)
        lines = split_lines(text)
        self.text_document_publish_diagnostics(
            types.PublishDiagnosticsParams(uri, [_diagnostic(d, lines) for d in shown])
        )

    def forget(self, uri: str) -> None:
        self.published.pop(uri, None)
        pending = self._pending.pop(uri, None)
        if pending is not None:
            pending.cancel()
        path = to_fs_path(uri)
        if self.session is not None and path is not None:
            self.session.close(Path(path))
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
    if published is None or path is None or ls.session is None:
        return []
    lines = split_lines(published.text)
    wanted = params.range
    actions: list[types.CodeAction] = []
    for diagnostic in published.diagnostics:
        shown = _range(diagnostic.span, lines)
        if not _overlaps(shown, wanted):
            continue
        lsp_diagnostic = _diagnostic(diagnostic, lines)
        if diagnostic.edit is not None:
            actions.append(_fix_action(ls.session, uri, diagnostic, lines, lsp_diagnostic))
        suppress = _suppress_action(Path(path), uri, published.text, diagnostic, lsp_diagnostic)
        if suppress is not None:
            actions.append(suppress)
    return actions


@server.feature(types.TEXT_DOCUMENT_HOVER)
def hover(ls: RoslintServer, params: types.HoverParams) -> types.Hover | None:
    published = ls.published.get(params.text_document.uri)
    if published is None:
        return None
    lines = split_lines(published.text)
    pages: list[str] = []
    for diagnostic in published.diagnostics:
        shown = _range(diagnostic.span, lines)
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
# From the linter's spans (1-based lines, code point columns) to LSP's (0-based, UTF-16)


def _position(line: int, column: int, lines: list[str]) -> types.Position:
    text = lines[line - 1] if 0 < line <= len(lines) else ""
    prefix = text[: max(column - 1, 0)]
    return types.Position(max(line - 1, 0), len(prefix.encode("utf-16-le")) // 2)


def _range(span: Span, lines: list[str]) -> types.Range:
    return types.Range(
        _position(span.line, span.column, lines), _position(span.end_line, span.end_column, lines)
    )


def _diagnostic(diagnostic: Diagnostic, lines: list[str]) -> types.Diagnostic:
    severity = (
        types.DiagnosticSeverity.Error
        if diagnostic.severity is Severity.ERROR
        else types.DiagnosticSeverity.Warning
    )
    return types.Diagnostic(
        range=_range(diagnostic.span, lines),
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
                    types.Range(
                        types.Position(related.span.line - 1, related.span.column - 1),
                        types.Position(related.span.end_line - 1, related.span.end_column - 1),
                    ),
                ),
                related.message,
            )
            for related in diagnostic.related
        ]
        or None,
    )


def _overlaps(one: types.Range, other: types.Range) -> bool:
    return _before_or_at(one.start, other.end) and _before_or_at(other.start, one.end)


def _contains(shown: types.Range, position: types.Position) -> bool:
    return _before_or_at(shown.start, position) and _before_or_at(position, shown.end)


def _before_or_at(one: types.Position, other: types.Position) -> bool:
    return (one.line, one.character) <= (other.line, other.character)


def _fix_action(
    session: Session,
    uri: str,
    diagnostic: Diagnostic,
    lines: list[str],
    lsp_diagnostic: types.Diagnostic,
) -> types.CodeAction:
    edit = diagnostic.edit
    assert edit is not None
    changes: dict[str, list[types.TextEdit]] = {uri: [_text_edit(edit, lines)]}
    for other in diagnostic.also:
        other_uri = from_fs_path(str(session.root / (other.path or diagnostic.path))) or uri
        other_lines = lines if other_uri == uri else _disk_lines(session.root / (other.path or ""))
        changes.setdefault(other_uri, []).append(_text_edit(other, other_lines))
    safety = "" if edit.safe else " (unsafe: may change what the system does)"
    return types.CodeAction(
        title=f"{diagnostic.code}: write '{edit.text}'{safety}",
        kind=types.CodeActionKind.QuickFix,
        diagnostics=[lsp_diagnostic],
        edit=types.WorkspaceEdit(changes=changes),
        is_preferred=edit.safe,
    )


def _text_edit(edit: Edit, lines: list[str]) -> types.TextEdit:
    return types.TextEdit(_range(edit.span, lines), edit.text)


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
