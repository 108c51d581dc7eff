"""Static values of Python expressions: folded when known, dynamic otherwise."""

from __future__ import annotations

import ast
import warnings
from collections.abc import Iterable, Sequence
from typing import cast

import libcst as cst

from roslint_names.extract.launch.substitution import Value, without_surrogates
from roslint_names.extract.python.attributes import InstanceAttributes, instance_class
from roslint_names.extract.python.scope import Binding, Context, Scope, ScopeKind
from roslint_names.extract.python.spans import Locator

_MAX_DEPTH = 16  # constants defined through constants; deeper (or cyclic) is dynamic


class Folder:
    """The static string value of an expression, or its code marked dynamic.

    Folded: string literals, names bound only to one foldable value (module- or
    function-level constants, or every branch agreeing), ``self.x`` attributes every
    write agrees on (``attributes.py``), f-strings, implicit concatenation, ``+`` and
    ``%`` whose parts all fold. Everything else (a parameter, another object's
    attribute, a call) is dynamic; ``absolute_prefix`` says what absolute start such a
    name certainly has.
    """

    def __init__(self, locator: Locator, attributes: InstanceAttributes | None = None) -> None:
        self._locator = locator
        self._attributes = attributes

    def value(self, expr: cst.BaseExpression, scope: Scope, at: Context | None = None) -> Value:
        """``at``: where the expression is read, to take a local assigned several times
        in straight-line code at its last assignment before that place."""
        text = self.static(expr, scope, at=at)
        if text is None:
            return Value(self._locator.code(expr), dynamic=True)
        return Value(text)

    def static(
        self,
        expr: cst.BaseExpression,
        scope: Scope,
        depth: int = 0,
        at: Context | None = None,
    ) -> str | None:
        if depth > _MAX_DEPTH:
            return None
        kind = type(expr)  # not isinstance: libcst's node classes are ABCs, slow to ask
        if kind is cst.SimpleString:
            return string_literal(cast(cst.SimpleString, expr))
        if kind is cst.ConcatenatedString:
            concatenated = cast(cst.ConcatenatedString, expr)
            return _join(
                self.static(concatenated.left, scope, depth, at),
                self.static(concatenated.right, scope, depth, at),
            )
        if kind is cst.FormattedString:
            return self._formatted(cast(cst.FormattedString, expr), scope, depth, at)
        if kind is cst.BinaryOperation:
            return self._operation(cast(cst.BinaryOperation, expr), scope, depth, at)
        if kind is cst.Name:
            # Bound once, or several times to one value (``topic = "scan"`` on each branch)
            bindings = scope.lookup(cast(cst.Name, expr).value)
            agreed = self._agreed(bindings, depth)
            if agreed is None and at is not None:
                last = _last_in_straight_line(bindings, scope, at)
                if last is not None and last.value is not None:
                    return self.static(last.value, last.scope, depth + 1, last.context)
            return agreed
        if isinstance(expr, cst.Attribute) and self._attributes is not None:
            owner = instance_class(expr.value, scope)  # ``self.topic``
            if owner is not None:
                return self._agreed(self._attributes.of_instance(owner, expr.attr.value), depth)
        return None

    def absolute_prefix(self, expr: cst.BaseExpression, scope: Scope) -> str | None:
        """The absolute start a dynamic name certainly has: ``"/planning/" + name``,
        ``f"/planning/{name}"``, ``"/planning/%s" % name``, ``"/planning/{}".format(name)``,
        or a name bound once to one of these."""
        prefix = self._prefix(expr, scope, 0)
        return prefix if prefix is not None and prefix.startswith("/") else None

    def _prefix(self, expr: cst.BaseExpression, scope: Scope, depth: int) -> str | None:
        """The text ``expr`` certainly starts with (all of it when static)."""
        if depth > _MAX_DEPTH:
            return None
        static = self.static(expr, scope, depth)
        if static is not None:
            return static
        if isinstance(expr, cst.BinaryOperation):
            if isinstance(expr.operator, cst.Add):
                return self._prefix(expr.left, scope, depth + 1)
            left = self.static(expr.left, scope, depth + 1)
            if isinstance(expr.operator, cst.Modulo) and left is not None:
                return left.partition("%")[0]
            return None
        if isinstance(expr, cst.FormattedString):
            return self._formatted_prefix(expr, scope, depth)
        if isinstance(expr, cst.Call) and isinstance(expr.func, cst.Attribute):
            owner = self.static(expr.func.value, scope, depth + 1)  # "/a/{}".format(x)
            if expr.func.attr.value == "format" and owner is not None:
                return owner.partition("{")[0]
            return None
        if isinstance(expr, cst.Name):
            bindings = scope.lookup(expr.value)
            if len(bindings) == 1 and bindings[0].value is not None:
                return self._prefix(bindings[0].value, bindings[0].scope, depth + 1)
        return None

    def suffix(self, expr: cst.BaseExpression, scope: Scope, depth: int = 0) -> str | None:
        """The text a dynamic name certainly ends with: ``name + ".max_vel_x"``,
        ``f"{name}.max_vel_x"``, or a name bound once to one of these; None when nothing
        is certain."""
        if depth > _MAX_DEPTH:
            return None
        if isinstance(expr, cst.BinaryOperation) and isinstance(expr.operator, cst.Add):
            end = self.static(expr.right, scope, depth + 1)
            return end or self.suffix(expr.right, scope, depth + 1)
        if isinstance(expr, cst.FormattedString):
            parts = self._known_parts(expr, reversed(expr.parts), scope, depth)
            return "".join(reversed(parts)) or None
        if isinstance(expr, cst.Name):
            bindings = scope.lookup(expr.value)
            if len(bindings) == 1 and bindings[0].value is not None:
                value = bindings[0].value
                if self.static(value, bindings[0].scope, depth + 1) is None:
                    return self.suffix(value, bindings[0].scope, depth + 1)
        return None

    def _formatted_prefix(self, expr: cst.FormattedString, scope: Scope, depth: int) -> str:
        return "".join(self._known_parts(expr, expr.parts, scope, depth))

    def _known_parts(
        self,
        expr: cst.FormattedString,
        parts: Iterable[cst.BaseFormattedStringContent],
        scope: Scope,
        depth: int,
    ) -> list[str]:
        """The texts of an f-string's ``parts``, in their order, up to the first the
        folder cannot know (a format spec, a conversion, a dynamic value)."""
        known: list[str] = []
        for part in parts:
            text = None
            if isinstance(part, cst.FormattedStringText):
                text = _fstring_text(expr, part.value)
            elif isinstance(part, cst.FormattedStringExpression) and not (
                part.format_spec or part.equal or part.conversion not in (None, "s")
            ):
                text = self.static(part.expression, scope, depth + 1)
            if text is None:
                break
            known.append(text)
        return known

    def _agreed(self, bindings: Sequence[Binding], depth: int) -> str | None:
        """The value every binding gives, when they all give the same static one."""
        values = {
            None if binding.value is None else self.static(binding.value, binding.scope, depth + 1)
            for binding in bindings
        }
        return values.pop() if len(values) == 1 else None

    def _formatted(
        self, expr: cst.FormattedString, scope: Scope, depth: int, at: Context | None
    ) -> str | None:
        parts: list[str] = []
        for part in expr.parts:
            if isinstance(part, cst.FormattedStringText):
                text = _fstring_text(expr, part.value)
            elif not isinstance(part, cst.FormattedStringExpression) or (
                part.format_spec or part.equal or part.conversion not in (None, "s")
            ):
                return None  # formatting we do not reproduce
            else:
                text = self.static(part.expression, scope, depth, at)
            if text is None:
                return None
            parts.append(text)
        return "".join(parts)

    def _operation(
        self, expr: cst.BinaryOperation, scope: Scope, depth: int, at: Context | None
    ) -> str | None:
        left = self.static(expr.left, scope, depth, at)
        if left is None:
            return None
        if isinstance(expr.operator, cst.Add):
            return _join(left, self.static(expr.right, scope, depth, at))
        if not isinstance(expr.operator, cst.Modulo):
            return None
        right = expr.right
        items = (
            [element.value for element in right.elements]
            if isinstance(right, cst.Tuple)
            else [right]
        )
        values = [self.static(item, scope, depth, at) for item in items]
        if any(value is None for value in values):
            return None
        try:
            return left % tuple(values)
        except (TypeError, ValueError, KeyError):
            return None  # a %d or a mismatch: Python would raise, we do not guess


def _last_in_straight_line(
    bindings: Sequence[Binding], scope: Scope, at: Context
) -> Binding | None:
    """The assignment a function's local has where ``at`` reads it, when that is certain:
    the last one before it among the statements of the function's own body (not inside an
    ``if``, a loop or a ``try``), with no other binding after it and up to the statement
    that holds ``at`` (where a branch or a loop could bind it again)."""
    function = scope.function
    if scope.kind is not ScopeKind.FUNCTION or function is None:
        return None
    body = function.body.body
    positions = {id(statement): index for index, statement in enumerate(body)}
    use = _position(at, positions)
    if use is None or any(binding.scope is not scope for binding in bindings):
        return None  # a closure's read sees the value at call time
    last: tuple[int, Binding] | None = None
    for binding in bindings:  # in source order
        if binding.context is None:
            return None  # a parameter, loop target, `+=`: bound where we cannot place it
        index = _position(binding.context, positions)
        if index is None or index == use:
            return None
        if index < use and (last is None or index >= last[0]):
            last = (index, binding)
    if last is None or last[1].context is None or last[1].context.anchors[0] is not body[last[0]]:
        return None  # bound last inside a branch or loop before the use
    return last[1]


def _position(context: Context, positions: dict[int, int]) -> int | None:
    """Which statement of the function's body holds what ``context`` is at."""
    for anchor in context.anchors:
        index = positions.get(id(anchor))
        if index is not None:
            return index
    return None


def string_literal(node: cst.SimpleString) -> str | None:
    """The literal's value; None for bytes, or escapes Python rejects (libcst does not)."""
    plain = _plain_literal(node.value)
    if plain is not None:
        return without_surrogates(plain)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "invalid escape sequence '\\d'": not ours to say
            value = node.evaluated_value
    except (SyntaxError, ValueError, MemoryError, RecursionError):
        return None
    return without_surrogates(value) if isinstance(value, str) else None


def _plain_literal(literal: str) -> str | None:
    """The value of a literal without prefix, escape or carriage return (most of them):
    what is between its quotes, as Python reads it, without asking Python's compiler.
    None for any other literal."""
    if literal[0] not in "'\"" or "\\" in literal or "\r" in literal:
        return None  # a prefix (bytes, raw...), an escape, or a newline Python translates
    quote = 3 if literal.startswith(literal[0] * 3) else 1
    return literal[quote:-quote]


def _join(left: str | None, right: str | None) -> str | None:
    return None if left is None or right is None else left + right


def _fstring_text(expr: cst.FormattedString, raw: str) -> str | None:
    """The value of an f-string's literal part: its escapes, and ``{{`` for ``{``."""
    prefix = expr.prefix.lower().replace("f", "")
    quote = expr.start[len(expr.prefix) :]
    if "\\" not in raw and "{" not in raw and "}" not in raw:
        return raw
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # as in string_literal
            value = ast.literal_eval(
                f"{prefix}{quote}{raw.replace('{{', '{').replace('}}', '}')}{quote}"
            )
    except (SyntaxError, ValueError, MemoryError, RecursionError):
        return None
    return without_surrogates(value) if isinstance(value, str) else None
