"""Negative fixtures: launch, URDF and YAML files a Python test loads expecting a failure.

roslaunch's own tests hold ``test/xml/test-node-invalid-name-2.xml`` and loads it to see
``XmlLoader`` refuse it; that file's illegal node name is the point of the test, not a
mistake for its maintainer to fix. A file name is taken as such a fixture when a test
function names it where it expects the failure:

- inside the expected-failure construct: ``with self.assertRaises(...)``/``pytest.raises``
  bodies, the arguments of ``self.assertRaises(Error, load, "bad.launch")``, a ``try``
  whose body or ``else`` calls ``fail`` (``self.fail``, ``pytest.fail``);
- or in what a ``for`` loop around that construct iterates over: a list, tuple or set of
  names written in the loop or assigned to the loop's iterable name earlier in the
  function, as roslaunch's ``for filename in tests: try: loader.load(...)`` does.

Only the file's base name is kept (tests join it to a fixture directory); the engine
matches it against the files of the same package. ``ast`` of the standard library, not
libcst: most test files are not ROS code and never reach the ROS extractors.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Iterator

_FAILURE_MARKER = re.compile(rb"assertRaises|\braises\(|\bfail\(")
_FIXTURE = re.compile(r"[^/\\\s'\"]+\.(?:launch|test|xml|yaml|yml|urdf|xacro)\Z", re.IGNORECASE)
_FIXTURE_BYTES = re.compile(rb"\.(?:launch|test|xml|yaml|yml|urdf|xacro)['\"]", re.IGNORECASE)
_RAISES = frozenset({"raises", "assertRaises", "assertRaisesRegex", "assertRaisesRegexp"})


def rejected_fixtures(data: bytes) -> tuple[str, ...]:
    """The base names of the fixture files the test code in ``data`` expects to fail,
    sorted; () for a file that cannot hold any (most: two byte searches decide)."""
    if _FAILURE_MARKER.search(data) is None or _FIXTURE_BYTES.search(data) is None:
        return ()
    try:
        tree = ast.parse(data)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return ()  # the extractor reports what does not parse
    found: set[str] = set()
    for function in ast.walk(tree):
        if isinstance(function, ast.FunctionDef | ast.AsyncFunctionDef):
            found.update(_in_function(function))
    return tuple(sorted(found))


def _in_function(function: ast.FunctionDef | ast.AsyncFunctionDef) -> Iterator[str]:
    lists = _assigned_lists(function)
    for node, loops in _expecting_failure(function.body, ()):
        yield from _names(node)
        for loop in loops:
            iterated = loop.iter
            if isinstance(iterated, ast.Name):
                yield from (name for value in lists.get(iterated.id, ()) for name in _names(value))
            else:
                yield from _names(iterated)


def _expecting_failure(
    statements: list[ast.stmt], loops: tuple[ast.For | ast.AsyncFor, ...]
) -> Iterator[tuple[ast.AST, tuple[ast.For | ast.AsyncFor, ...]]]:
    """Each expected-failure construct among ``statements`` (nested blocks included),
    with the ``for`` loops around it."""
    for statement in statements:
        if isinstance(statement, ast.With | ast.AsyncWith) and any(
            _is_raises(item.context_expr) for item in statement.items
        ):
            yield statement, loops
            continue
        if isinstance(statement, ast.Try) and any(
            _calls_fail(part) for part in (*statement.body, *statement.orelse)
        ):
            yield ast.Module(body=statement.body, type_ignores=[]), loops
            continue
        for call in _calls(statement):
            if _is_raises(call) and call.args[1:]:
                yield ast.Tuple(elts=call.args[1:], ctx=ast.Load()), loops
        inner = (*loops, statement) if isinstance(statement, ast.For | ast.AsyncFor) else loops
        for block in ("body", "orelse", "finalbody", "handlers"):
            children = getattr(statement, block, None)
            if isinstance(children, list):
                nested = [
                    child
                    for item in children
                    for child in (item.body if isinstance(item, ast.ExceptHandler) else [item])
                ]
                yield from _expecting_failure(nested, inner)


def _calls(statement: ast.stmt) -> Iterator[ast.Call]:
    """The calls of a simple statement (an expression or an assignment), not of the
    blocks a compound statement holds."""
    if isinstance(statement, ast.Expr | ast.Assign | ast.AnnAssign | ast.Return):
        value = statement.value
        if isinstance(value, ast.Call):
            yield value


def _is_raises(expression: ast.expr) -> bool:
    """``pytest.raises(...)``, ``self.assertRaises(...)``."""
    if not isinstance(expression, ast.Call):
        return False
    function = expression.func
    name = function.attr if isinstance(function, ast.Attribute) else getattr(function, "id", "")
    return name in _RAISES


def _calls_fail(statement: ast.stmt) -> bool:
    for node in ast.walk(statement):
        if isinstance(node, ast.Call):
            function = node.func
            name = (
                function.attr
                if isinstance(function, ast.Attribute)
                else getattr(function, "id", "")
            )
            if name == "fail":
                return True
    return False


def _assigned_lists(function: ast.FunctionDef | ast.AsyncFunctionDef) -> dict[str, list[ast.expr]]:
    """Names assigned a list, tuple or set display in the function: what a loop may
    iterate over."""
    lists: dict[str, list[ast.expr]] = {}
    for node in ast.walk(function):
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.List | ast.Tuple | ast.Set):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    lists.setdefault(target.id, []).append(node.value)
    return lists


def _names(node: ast.AST) -> Iterator[str]:
    """The fixture file names among the string constants under ``node``, as base names."""
    for child in ast.walk(node):
        if isinstance(child, ast.Constant) and isinstance(child.value, str):
            base = child.value.replace("\\", "/").rpartition("/")[2]
            if _FIXTURE.match(base):
                yield base
