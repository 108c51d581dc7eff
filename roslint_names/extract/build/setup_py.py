"""setup.py and setup.cfg: the ``console_scripts`` a Python package installs.

ament_python packages declare their nodes as console_scripts entry points, and launch
files name the entry (``Node(executable='talker')``); ``setup_cfg`` says what an entry
gives. This module reads setup.py, and hands setup.cfg to ``setup_cfg``.

setup.py is read with the standard library's ``ast``, never run and never given to
libcst: it is context, and must stay cheap. ``setup(entry_points=...)`` (also through
``**kwargs`` or a module-level variable) may be a dict literal or ``dict(...)``, or an
entry_points.txt-style string; entries are string literals, f-strings or ``+``
concatenations over module-level string variables (``package_name = 'demo_nodes_py'``),
which are taken as assigned, in order. An entry built any other way is skipped. The span
of an entry is the expression that writes it, quotes included. A setup.py that is not
Python is reported (RN001), since the user wrote it.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Iterator

from roslint_names.extract.build.ast_strings import folded_string
from roslint_names.extract.build.setup_cfg import console_scripts, ini_console_scripts, program
from roslint_names.extract.build.setup_source import decode, parse
from roslint_names.model import (
    CompiledSources,
    Executable,
    FileFacts,
    Generation,
    Language,
    ParseError,
    Span,
)

_EXTENSIONS = re.compile(rb"ext_modules|Extension\b")
_MAY_COMPILE = CompiledSources(patterns=("*",))
_LINE_BREAK = re.compile(r"\r\n|\r|\n")  # also CPython's, for ast's line numbers
_SETUP_FUNCTIONS = frozenset({"setup"})  # setup(), setuptools.setup(), distutils.core.setup()
# Module variables referring to one another are followed this many steps, no more.
_MAX_HOPS = 8


class _Module:
    """One setup.py: its module-level variables, and where its expressions are."""

    def __init__(self, text: str, tree: ast.Module) -> None:
        self._lines = _LINE_BREAK.split(text)
        self.strings: dict[str, str] = {}  # evaluated when assigned: a later change is later
        self.values: dict[str, ast.expr] = {}
        for statement in tree.body:
            self._assign(statement)

    def _assign(self, statement: ast.stmt) -> None:
        if isinstance(statement, ast.Assign | ast.AnnAssign) and statement.value is not None:
            targets = statement.targets if isinstance(statement, ast.Assign) else [statement.target]
            text = self.string(statement.value)
            for target in targets:
                if isinstance(target, ast.Name):
                    self._bind(target.id, statement.value, text)
        elif isinstance(statement, ast.AugAssign) and isinstance(statement.target, ast.Name):
            name = statement.target.id
            added = self.string(statement.value)
            before = self.strings.get(name)
            text = before + added if before is not None and added is not None else None
            self._bind(name, None, text if isinstance(statement.op, ast.Add) else None)

    def _bind(self, name: str, value: ast.expr | None, text: str | None) -> None:
        self.strings.pop(name, None)
        self.values.pop(name, None)
        if text is not None:
            self.strings[name] = text
        if value is not None:
            self.values[name] = value

    def resolve(self, node: ast.expr) -> ast.expr:
        """The expression a module variable was assigned, followed a few steps."""
        for _ in range(_MAX_HOPS):
            if not isinstance(node, ast.Name) or node.id not in self.values:
                break
            node = self.values[node.id]
        return node

    def string(self, node: ast.expr) -> str | None:
        """The string ``node`` evaluates to, when it is built from known strings."""
        return folded_string(node, self.strings, self._joined)

    def _joined(self, node: ast.expr) -> str | None:
        if isinstance(node, ast.JoinedStr):
            parts = [self._formatted(value) for value in node.values]
            return None if None in parts else "".join(part for part in parts if part)
        return None

    def _formatted(self, node: ast.expr) -> str | None:
        if isinstance(node, ast.FormattedValue):
            # {x!r} adds quotes and a format spec may pad: only the plain form is known.
            plain = node.conversion in (-1, ord("s")) and node.format_spec is None
            return self.string(node.value) if plain else None
        return self.string(node)

    def span(self, node: ast.expr) -> Span:
        """Columns in code points; ``ast`` counts UTF-8 bytes."""
        end_line = node.end_lineno or node.lineno
        end_column = node.end_col_offset if node.end_col_offset is not None else node.col_offset
        return Span(
            node.lineno,
            self._column(node.lineno, node.col_offset),
            end_line,
            self._column(end_line, end_column),
        )

    def _column(self, line: int, offset: int) -> int:
        if not 0 < line <= len(self._lines):
            return offset + 1
        encoded = self._lines[line - 1].encode("utf-8", errors="surrogatepass")
        return len(encoded[:offset].decode("utf-8", errors="replace")) + 1


def _setup_calls(tree: ast.Module) -> Iterator[ast.Call]:
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            function = node.func
            name = function.id if isinstance(function, ast.Name) else None
            if isinstance(function, ast.Attribute):
                name = function.attr
            if name in _SETUP_FUNCTIONS:
                yield node


def _keyword(module: _Module, call: ast.Call, name: str) -> Iterator[ast.expr]:
    """The values ``call`` passes for keyword ``name``, directly or in ``**mapping``."""
    for keyword in call.keywords:
        if keyword.arg == name:
            yield keyword.value
        elif keyword.arg is None:
            yield from _item(module, keyword.value, name)


def _item(module: _Module, node: ast.expr, key: str) -> Iterator[ast.expr]:
    """The values a dict literal or ``dict(...)`` call maps ``key`` to."""
    node = module.resolve(node)
    if isinstance(node, ast.Dict):
        for name, value in zip(node.keys, node.values, strict=True):
            if name is None:
                yield from _item(module, value, key)  # {**other}
            elif module.string(name) == key:
                yield value
    elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "dict":
        yield from _keyword(module, node, key)


def _entries(module: _Module, node: ast.expr) -> Iterator[tuple[str, ast.expr]]:
    """Each entry of a console_scripts value and the expression that writes it."""
    node = module.resolve(node)
    if isinstance(node, ast.List | ast.Tuple | ast.Set):
        for element in node.elts:
            inner = element.value if isinstance(element, ast.Starred) else element
            text = module.string(inner)
            if text is not None:
                yield from ((line, inner) for line in text.splitlines() if line.strip())
            else:
                yield from _entries(module, inner)
    elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        yield from _entries(module, node.left)
        yield from _entries(module, node.right)
    else:
        text = module.string(node)  # one string, an entry a line
        if text is not None:
            yield from ((line, node) for line in text.splitlines() if line.strip())


def _setup_py_programs(module: _Module, tree: ast.Module) -> list[Executable]:
    found: list[Executable] = []
    for call in _setup_calls(tree):
        for entry_points in _keyword(module, call, "entry_points"):
            ini = module.string(module.resolve(entry_points))
            if ini is not None:
                pairs = [(line, entry_points) for line in ini_console_scripts(ini)]
            else:
                pairs = [
                    pair
                    for value in _item(module, entry_points, "console_scripts")
                    for pair in _entries(module, value)
                ]
            for entry, node in pairs:
                installed = program(entry, module.span(node))
                if installed is not None:
                    found.append(installed)
    return found


def _setup_py(data: bytes) -> tuple[Executable, ...] | ParseError:
    text = decode(data)
    tree = text if isinstance(text, ParseError) else parse(text)
    if isinstance(tree, ParseError):
        return tree
    assert isinstance(text, str)
    try:
        module = _Module(text, tree)
        return tuple(_setup_py_programs(module, tree))
    except RecursionError:  # a pathologically long concatenation: no entries rather than a crash
        return ()


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
) -> FileFacts:
    """The console_scripts ``path`` (a setup.py or setup.cfg) installs."""
    generation = package_generation or fallback_generation
    if path.endswith(".cfg"):
        return FileFacts(path, Language.SETUP_CFG, generation, executables=console_scripts(data))
    # A setup.py that builds extension modules (``ext_modules``, ``Extension(...)``,
    # ``CppExtension``) may compile any C++ source of its package: no source of it is
    # taken for one nothing builds (``workspace.built``).
    compiled = _MAY_COMPILE if _EXTENSIONS.search(data) else None
    found = _setup_py(data)
    if isinstance(found, ParseError):
        return FileFacts(
            path, Language.SETUP_PY, generation, parse_errors=(found,), compiled=compiled
        )
    return FileFacts(path, Language.SETUP_PY, generation, executables=found, compiled=compiled)
