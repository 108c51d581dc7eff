"""Spans of the few nodes of a Python file that become facts.

libcst's ``PositionProvider`` regenerates the whole module to place every node, which
costs more than the parse itself. The code of a node is an exact slice of the source, so
a node whose code occurs once in the file is placed by a string search, and one that does
not is placed inside its nearest enclosing anchor (argument, call, statement) that can be;
``PositionProvider`` runs only for what is left.
"""

from __future__ import annotations

from collections.abc import Sequence
from contextlib import AbstractContextManager, nullcontext
from dataclasses import dataclass
from itertools import accumulate

import libcst as cst

from roslint_names.extract.launch.substitution import Source
from roslint_names.extract.python.python2 import Rewritten
from roslint_names.model import Span

try:
    from libcst._nodes.internal import CodegenState as _CodegenState
except ImportError:  # pragma: no cover - a libcst that moved its internals
    _CodegenState = None  # type: ignore[assignment,misc]

# ---------------------------------------------------------------------------------------
# Spans


def _unique(text: str, needle: str) -> int | None:
    """Index of the only occurrence of ``needle`` in ``text`` (overlaps count)."""
    first = text.find(needle)
    if first < 0 or not needle or text.find(needle, first + 1) >= 0:
        return None
    return first


@dataclass(frozen=True)
class Where:
    """A node to place, and what encloses it: anchors innermost first, block indents."""

    node: cst.CSTNode
    anchors: tuple[cst.CSTNode, ...] = ()
    indents: tuple[str, ...] = ()


class Locator:
    """Spans of nodes, without regenerating the whole module when it can be helped.

    ``code`` regenerates a node exactly as written, given the indentation of the blocks
    around it (a call continued over several lines repeats them), so when that code occurs
    once in the file, the occurrence is the node. Otherwise the node is placed inside the
    nearest enclosing anchor (its argument, call or statement) that can be placed, by
    regenerating only that anchor and noting where the node starts; the module itself is
    the last anchor. ``PositionProvider`` (slower still) only serves a libcst whose
    codegen state moved.

    A module parsed from Python 2 rewritten (``python2``) is placed in the rewritten
    text, and its spans are those of the original: the user's bytes.
    """

    def __init__(
        self,
        module: cst.Module,
        text: str,
        anchor_indents: dict[int, tuple[str, ...]] | None = None,
        rewritten: Rewritten | None = None,
    ) -> None:
        """``anchor_indents``: by id, the indentation of each anchor written at another
        than the nodes inside it (a function); every other anchor shares its nodes'.
        ``rewritten``: what ``text`` was rewritten from, when it was."""
        self._module = module
        self._anchor_indents = anchor_indents or {}
        self._source = Source(text)
        self._rewritten = rewritten
        self._original = None if rewritten is None else Source(rewritten.source)
        self._offsets: dict[int, int | None] = {}
        self._codes: dict[tuple[int, tuple[str, ...]], str] = {}
        self._starts: dict[int, _Starts] = {}
        self._positions: dict[cst.CSTNode, Span] | None = None
        self._offsets[id(module)] = 0
        # The module and its statements are written at no indentation: whatever the
        # indentation of a node placed inside them, they are regenerated without it.
        self._unindented = {id(module), *(id(statement) for statement in module.body)}

    def code(self, node: cst.CSTNode, indents: tuple[str, ...] = ()) -> str:
        key = (id(node), indents)
        if key not in self._codes:
            self._codes[key] = _code(self._module, _bare(node), indents)
        return self._codes[key]

    def span(self, where: Where) -> Span:
        # The module is the last anchor: always placed (at 0), regenerated only when no
        # nearer anchor could place the node (code repeated verbatim in the file).
        start = self._offset(where.node, (*where.anchors, self._module), where.indents)
        if start is None:
            return self._provided(where.node)
        return self._span(start, start + len(self.code(where.node, where.indents)))

    def head_span(self, where: Where, head: cst.CSTNode) -> Span:
        """The span of ``head`` (a callee), found inside ``where.node`` (its call)."""
        return self.span(Where(head, (where.node, *where.anchors), where.indents))

    def _offset(
        self, node: cst.CSTNode, anchors: Sequence[cst.CSTNode], indents: tuple[str, ...]
    ) -> int | None:
        if id(node) in self._offsets:
            return self._offsets[id(node)]
        found = _unique(self._source.text, self.code(node, self._indents(node, indents)))
        for index, anchor in enumerate(anchors):
            if found is not None:
                break
            if id(anchor) not in self._offsets:
                self._starts_in(anchor, indents)  # its code comes with them: one codegen
            base = self._offset(anchor, anchors[index + 1 :], indents)
            inner = None if base is None else self._start_in(anchor, node, indents)
            found = None if base is None or inner is None else base + inner
        self._offsets[id(node)] = found
        return found

    def _starts_in(self, anchor: cst.CSTNode, indents: tuple[str, ...]) -> _Starts:
        """Where each node inside ``anchor`` starts in its code, and that code (an anchor
        is placed by its code, then the node inside it by these), from one codegen."""
        starts = self._starts.get(id(anchor))
        if starts is None:
            own = self._indents(anchor, indents)
            recorded = _recorded(self._module, _bare(anchor), own)
            starts = _Starts([], {})
            if recorded is not None:
                self._codes[(id(anchor), own)], starts = recorded
            self._starts[id(anchor)] = starts
        return starts

    def _start_in(
        self, anchor: cst.CSTNode, node: cst.CSTNode, indents: tuple[str, ...]
    ) -> int | None:
        """Where ``node``'s code starts in ``anchor``'s."""
        starts = self._starts_in(anchor, indents)
        if isinstance(node, cst.SimpleStatementLine) and node.leading_lines:
            # Placed without the lines above it (``_bare``): it starts at its indentation,
            # which its first statement follows.
            first = starts.get(id(node.body[0]))
            indentation = len("".join(self._indents(node, indents)))
            return None if first is None else first - indentation
        parens = _parens(node)
        # A parenthesised node starts at its '('; its span starts after the last one.
        return starts.get(id(parens[-1]) if parens else id(node))

    def _span(self, start: int, end: int) -> Span:
        """The span of offsets ``start`` to ``end`` of the parsed text, in the file."""
        if self._rewritten is None or self._original is None:
            return self._source.span(start, end)
        original = self._rewritten.original
        return self._original.span(original(start), original(end))

    def _moved(self, span: Span) -> Span:
        """A span of the parsed text, in the file."""
        if self._rewritten is None:
            return span
        offset = self._source.offset
        return self._span(offset(span.line, span.column), offset(span.end_line, span.end_column))

    def _indents(self, node: cst.CSTNode, indents: tuple[str, ...]) -> tuple[str, ...]:
        if id(node) in self._unindented:
            return ()
        return self._anchor_indents.get(id(node), indents)

    def _provided(self, node: cst.CSTNode) -> Span:
        """libcst's own positions, when its codegen state is not at hand."""
        from libcst.metadata import MetadataWrapper, PositionProvider

        if self._positions is None:
            wrapper = MetadataWrapper(self._module, unsafe_skip_copy=True)
            ranges = wrapper.resolve(PositionProvider)
            self._positions = {
                key: self._moved(
                    Span(r.start.line, r.start.column + 1, r.end.line, r.end.column + 1)
                )
                for key, r in ranges.items()
            }
        return self._positions.get(node, Span(1, 1, 1, 1))


def _parens(node: cst.CSTNode) -> Sequence[cst.LeftParen]:
    """An expression's own parentheses (``with (...)`` and ``from x import (...)`` hold a
    single optional one, which is part of the statement, not around it)."""
    lpar = getattr(node, "lpar", ())
    return lpar if isinstance(lpar, list | tuple) else ()


def _bare(node: cst.CSTNode) -> cst.CSTNode:
    """The node without its own parentheses: a span starts at the literal's quote; a
    statement line without the comment and blank lines above it, whose indentation is
    the block's and not always the line's.

    An empty tuple keeps them: they are all there is of it (libcst refuses ``()`` without).
    """
    if isinstance(node, cst.SimpleStatementLine):
        return node.with_changes(leading_lines=()) if node.leading_lines else node
    if _parens(node) and not (isinstance(node, cst.Tuple) and not node.elements):
        return node.with_changes(lpar=[], rpar=[])
    return node


def _code(module: cst.Module, node: cst.CSTNode, indents: tuple[str, ...]) -> str:
    """The node's code as it sits in the file.

    ``Module.code_for_node`` knows nothing of enclosing blocks, so a call continued over
    indented lines would come out without their indentation; libcst's own codegen state
    (internal, stable since libcst 0.3) takes it. Without it, such nodes are only placed
    by ``PositionProvider``: slower, never wrong.
    """
    if isinstance(node, cst.SimpleString):
        return node.value
    if _QuickState is None:
        return module.code_for_node(node)  # no indentation: then only by PositionProvider
    state = _QuickState(module.default_indent, module.default_newline, None, list(indents))
    node._codegen(state)
    return "".join(state.tokens)


class _Starts:
    """Where each node inside an anchor starts in its code (for a '(', where it ends: see
    ``Locator._start_in``). Noted by token while the code is written, and turned into a
    character offset only when asked: most of them never are."""

    def __init__(self, tokens: Sequence[str], by_token: dict[int, int]) -> None:
        self._by_token = by_token
        self._offsets = list(accumulate(map(len, tokens), initial=0))

    def get(self, node_id: int) -> int | None:
        index = self._by_token.get(node_id)
        return None if index is None else self._offsets[index]


def _recorded(
    module: cst.Module, node: cst.CSTNode, indents: tuple[str, ...]
) -> tuple[str, _Starts] | None:
    """``node``'s code, and where each node inside it starts; None without libcst's
    codegen state."""
    if _RecordingState is None:
        return None
    state = _RecordingState(module.default_indent, module.default_newline, None, list(indents))
    node._codegen(state)
    return "".join(state.tokens), _Starts(state.tokens, state.starts)


if _CodegenState is not None:
    _NO_POSITION = nullcontext()

    class _QuickState(_CodegenState):
        """libcst's codegen state, without its generator-based context manager for
        syntactic positions, which only yields when no position provider is set (as
        here): a quarter of the codegen's time, for nothing."""

        def record_syntactic_position(  # type: ignore[override]  # any context manager
            self,
            node: cst.CSTNode,
            *,
            start_node: cst.CSTNode | None = None,
            end_node: cst.CSTNode | None = None,
        ) -> AbstractContextManager[None]:
            return _NO_POSITION

    class _RecordingState(_QuickState):
        """libcst's codegen state, noting where each node's code starts.

        ``starts`` maps a node's id to the index of its first token; a '(' to the index
        after its last, which is where the span of the node it parenthesises starts.
        """

        def __init__(
            self,
            default_indent: str,
            default_newline: str,
            provider: object,
            indent_tokens: list[str],
        ) -> None:
            super().__init__(default_indent, default_newline, provider, indent_tokens, [])
            self.starts: dict[int, int] = {}

        def before_codegen(self, node: cst.CSTNode) -> None:
            self.starts[id(node)] = len(self.tokens)

        def after_codegen(self, node: cst.CSTNode) -> None:
            if type(node) is cst.LeftParen:  # not isinstance: an ABC, slow to ask
                self.starts[id(node)] = len(self.tokens)
else:  # pragma: no cover - a libcst that moved its internals
    _QuickState = None  # type: ignore[assignment,misc]
    _RecordingState = None  # type: ignore[assignment,misc]
