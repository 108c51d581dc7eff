"""dynamic_reconfigure ``.cfg`` files: the parameters a config generates, and its name.

A ``.cfg`` is a Python script that catkin runs at build time
(``generate_dynamic_reconfigure_options``); dynamic_reconfigure's
``src/dynamic_reconfigure/parameter_generator_catkin.py`` defines what it calls:

- ``ParameterGenerator.add(name, paramtype, level, description, default, min, max,
  edit_method)`` adds a parameter to the default group, and ``add_group(name)`` returns a
  ``Group`` whose ``add`` adds to the same flat namespace (``Group.get_parameters``
  gathers every group's parameters into one config); ``check_name`` refuses any name but
  ``[a-zA-Z][a-zA-Z0-9_]*``. ``const`` and ``enum`` make the constants of an
  ``edit_method``, no parameters;
- ``generate(pkgname, nodename, name)`` writes the class ``nameConfig`` (``msgname``) in
  the C++ namespace ``pkgname`` and the Python module ``pkgname.cfg.nameConfig``.

The server reads each of those names from its node handle's namespace, private by default
(``include/dynamic_reconfigure/server.h``: ``Server(const ros::NodeHandle &nh =
ros::NodeHandle("~"))``, whose ``init`` calls the generated ``__fromServer__``;
``src/dynamic_reconfigure/server.py``: ``Server(type, callback, namespace="")`` reads
``rospy.get_param(self.ns + name)`` with ``self.ns`` ``"~"``).

Read with the standard library's ``ast``, never run. The file is the ROS 1 script it is:
a Python 2 one is rewritten first (``python.python2``). An ``add`` is one on a generator
(``ParameterGenerator()``) or a group (``add_group(...)``), or any ``add`` whose type is a
generator type (``double_t``, ``pgc.int_t``). Module-level strings are folded
(``PACKAGE = "amcl"``). The config is incomplete where an ``add``'s name is not a string
the file spells, or a generator is handed to a function (navigation's
``add_generic_localplanner_params(gen)`` adds a library's parameters).

dynamic_reconfigure is ROS 1 only: a ``.cfg`` left in a ROS 2 package generates nothing
and is not read.
"""

from __future__ import annotations

import ast
import os
import re
from collections.abc import Callable
from dataclasses import dataclass, field

from roslint_names.extract.build.ast_strings import folded_string
from roslint_names.extract.build.setup_source import decode, parse
from roslint_names.extract.launch.substitution import Source
from roslint_names.extract.python.python2 import rewrite
from roslint_names.model import (
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    ParseError,
    ReconfigureConfig,
    Role,
    Span,
)

API = "dynamic_reconfigure ParameterGenerator.add"
MARKER = b"ParameterGenerator"
# parameter_generator_catkin's type constants: str_t, bool_t, int_t, double_t.
_TYPES = frozenset({"str_t", "bool_t", "int_t", "double_t"})
_METHODS = frozenset({"add", "add_group", "generate", "const", "enum"})
_LINE_BREAK = re.compile(r"\r\n|\r|\n")


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
) -> FileFacts:
    """The config a ``.cfg`` generates, and its parameter names."""
    del fallback_generation  # a .cfg is dynamic_reconfigure's, which is ROS 1's
    if package_generation is Generation.ROS2 or MARKER not in data:
        return FileFacts(path, Language.RECONFIGURE, package_generation or Generation.ROS1)
    generation = Generation.ROS1
    text = decode(data)
    if isinstance(text, ParseError):
        return FileFacts(path, Language.RECONFIGURE, generation, parse_errors=(text,))
    read = _read(text)
    if isinstance(read, ParseError):
        return FileFacts(path, Language.RECONFIGURE, generation, parse_errors=(read,))
    tree, positions = read
    try:
        config = _Config(positions)
        config.visit(tree)
    except RecursionError:
        return FileFacts(path, Language.RECONFIGURE, generation)
    names = tuple(
        NameUse(Kind.PARAMETER, value, span, Role.PARAMETER, API)
        for value, span in config.parameters
    )
    # A script that generates nothing (a helper, a file commented out) is no config.
    found = (
        ReconfigureConfig(
            config.package, config.name or _stem(path), tuple(config.parameters), config.complete
        )
        if config.generated
        else None
    )
    return FileFacts(path, Language.RECONFIGURE, generation, names=names, reconfigure=found)


def _stem(path: str) -> str | None:
    """parameter_generator_catkin: "name must match the first part of the configuration
    file" (``generate``'s docstring)."""
    stem = os.path.splitext(os.path.basename(path))[0]
    return stem or None


def _read(text: str) -> tuple[ast.Module, _Positions] | ParseError:
    """The tree, parsed as Python 3, else as the Python 2 the script may be."""
    tree = parse(text)
    if not isinstance(tree, ParseError):
        return tree, _Positions(Source(text), text)
    rewritten = rewrite(text)
    second = None if rewritten is None else parse(rewritten.text)
    if rewritten is None or second is None or isinstance(second, ParseError):
        return tree
    return second, _Positions(Source(text), rewritten.text, rewritten.original)


@dataclass
class _Positions:
    """Spans in the user's text of nodes of the parsed text (the same, or rewritten)."""

    source: Source
    parsed: str
    # ``Rewritten.original``, where the parsed text is the Python 2 script rewritten.
    original: Callable[[int], int] | None = None
    _starts: list[int] = field(default_factory=list)

    def __post_init__(self) -> None:
        # CPython's line ends, which ``ast``'s line numbers count.
        self._starts = [0, *(match.end() for match in _LINE_BREAK.finditer(self.parsed))]

    def span(self, node: ast.expr) -> Span:
        start = self._offset(node.lineno, node.col_offset)
        end_line = node.end_lineno or node.lineno
        end_offset = node.end_col_offset if node.end_col_offset is not None else node.col_offset
        end = self._offset(end_line, end_offset)
        if self.original is not None:
            start, end = self.original(start), self.original(end)
        return self.source.span(start, end)

    def _offset(self, line: int, byte_column: int) -> int:
        """``ast`` counts UTF-8 bytes within the line; spans count code points."""
        if not 0 < line <= len(self._starts):
            return len(self.parsed)
        start = self._starts[line - 1]
        stop = self._starts[line] if line < len(self._starts) else len(self.parsed)
        encoded = self.parsed[start:stop].encode("utf-8", errors="surrogatepass")
        return start + len(encoded[:byte_column].decode("utf-8", errors="replace"))


class _Config(ast.NodeVisitor):
    """Walks the script in order: its strings, generators, groups, adds and generate."""

    def __init__(self, positions: _Positions) -> None:
        self.positions = positions
        self.strings: dict[str, str] = {}
        self.generators: set[str] = set()  # names bound to a generator or a group
        self.parameters: list[tuple[str, Span]] = []
        self.package: str | None = None
        self.name: str | None = None
        self.complete = True
        self.generated = False  # a generate call seen: else the script may be a helper

    def visit_Assign(self, node: ast.Assign) -> None:
        self.generic_visit(node)
        value = self.string(node.value)
        made = self.makes_generator(node.value)
        for target in node.targets:
            if isinstance(target, ast.Name):
                self.strings.pop(target.id, None)
                self.generators.discard(target.id)
                if value is not None:
                    self.strings[target.id] = value
                if made:
                    self.generators.add(target.id)

    def visit_Call(self, node: ast.Call) -> None:
        self.generic_visit(node)
        function = node.func
        if isinstance(function, ast.Attribute) and function.attr in _METHODS:
            if function.attr == "add" and (self.is_generator(function.value) or _typed(node)):
                self.add(node)
            elif function.attr == "generate" and self.is_generator(function.value):
                self.generate(node)
            return
        # A generator handed to anything else may be given parameters there.
        arguments = [*node.args, *(keyword.value for keyword in node.keywords)]
        if any(self.is_generator(argument) for argument in arguments):
            self.complete = False

    def add(self, node: ast.Call) -> None:
        argument = _argument(node, 0, "name")
        value = None if argument is None else self.string(argument)
        if argument is None or value is None:
            self.complete = False
            return
        self.parameters.append((value, self.positions.span(argument)))

    def generate(self, node: ast.Call) -> None:
        self.generated = True
        package = _argument(node, 0, "pkgname")
        name = _argument(node, 2, "name")
        self.package = None if package is None else self.string(package)
        self.name = None if name is None else self.string(name)

    def makes_generator(self, node: ast.expr) -> bool:
        """``ParameterGenerator()`` (however imported), or a group: ``gen.add_group(...)``."""
        if not isinstance(node, ast.Call):
            return False
        function = node.func
        if isinstance(function, ast.Name):
            return function.id == "ParameterGenerator"
        if isinstance(function, ast.Attribute):
            return function.attr == "ParameterGenerator" or (
                function.attr == "add_group" and self.is_generator(function.value)
            )
        return False

    def is_generator(self, node: ast.expr) -> bool:
        if isinstance(node, ast.Name):
            return node.id in self.generators
        return self.makes_generator(node)

    def string(self, node: ast.expr) -> str | None:
        return folded_string(node, self.strings)


def _argument(call: ast.Call, position: int, keyword: str) -> ast.expr | None:
    if len(call.args) > position and not any(
        isinstance(argument, ast.Starred) for argument in call.args[: position + 1]
    ):
        return call.args[position]
    return next((k.value for k in call.keywords if k.arg == keyword), None)


def _typed(call: ast.Call) -> bool:
    """An ``add`` whose type is one of the generator's (``double_t``, ``pgc.int_t``): a
    parameter however the generator reached this call."""
    paramtype = _argument(call, 1, "paramtype")
    return _type_name(paramtype) in _TYPES


def _type_name(node: ast.expr | None) -> str | None:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return node.attr
    return None
