"""Python scopes: what each name is bound to, by Python's own rules.

One ``Scope`` per module, function, lambda, class body and comprehension, holding every
binding of every name in source order: imports (so ``rp.Publisher`` resolves to
``rospy.Publisher``), single assignments (constants the folder may use), ``def`` and
``class`` statements. ``Context`` is where the walk is when it meets a call.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from enum import Enum
from typing import cast

import libcst as cst

from roslint_names.extract.python.spans import Where

# ---------------------------------------------------------------------------------------
# Scopes


class ScopeKind(Enum):
    MODULE = "module"
    FUNCTION = "function"  # def and lambda
    CLASS = "class"
    COMPREHENSION = "comprehension"


@dataclass(frozen=True)
class Binding:
    """One way a name gets bound in a scope.

    ``value`` is the expression of a plain ``name = value``; ``imported`` the qualified
    name an import binds; ``defined`` the ``def`` or ``class`` statement. A binding with
    none of them (a loop target, a parameter, ``+=``...) has no static value.
    """

    scope: Scope
    value: cst.BaseExpression | None = None
    imported: str | None = None
    defined: cst.ClassDef | cst.FunctionDef | None = None
    context: Context | None = None  # where ``value`` is written


@dataclass(eq=False)
class Scope:
    """A Python scope with every binding of every name in it, in source order.

    ``key`` is what RN301 groups events by: "" for code that runs when the module loads
    (module level, and class bodies there), else one key per function. ``owner`` is the
    class a method belongs to, so ``self.create_publisher`` can be judged.
    """

    kind: ScopeKind
    name: str
    parent: Scope | None
    key: str
    owner: cst.ClassDef | None = None
    function: cst.FunctionDef | None = None
    bindings: dict[str, list[Binding]] = field(default_factory=dict)
    star_imports: list[str] = field(default_factory=list)
    globals: set[str] = field(default_factory=set)
    # Set on the module scope once the walk has bound every name: from then on no
    # binding changes, and ``qualified`` (asked for most calls, several times) keeps its
    # answers, by the expression's id (with the expression, so that an id is never
    # mistaken for another's).
    complete: bool = field(default=False, init=False, repr=False)
    _qualified: dict[int, tuple[cst.BaseExpression, tuple[str, ...]]] = field(
        default_factory=dict, init=False, repr=False
    )

    @property
    def module(self) -> Scope:
        scope = self
        while scope.parent is not None:
            scope = scope.parent
        return scope

    def bind(self, name: str, binding: Binding) -> None:
        target = self.module if name in self.globals else self
        if binding.scope is not target:
            binding = dataclasses.replace(binding, scope=target)
        target.bindings.setdefault(name, []).append(binding)

    def lookup(self, name: str) -> list[Binding]:
        """The bindings ``name`` refers to here, by Python's rules (LEGB, classes skipped)."""
        scope: Scope | None = self
        first = True
        while scope is not None:
            if name in scope.globals:
                return scope.module.bindings.get(name, [])
            if (first or scope.kind is not ScopeKind.CLASS) and name in scope.bindings:
                return scope.bindings[name]
            first = False
            scope = scope.parent
        return []

    def qualified(self, expr: cst.BaseExpression) -> tuple[str, ...]:
        """What a dotted expression names through the imports: ``rp.Publisher`` ->
        ``rospy.Publisher``. Several candidates only through ``from x import *``."""
        kept = self._qualified.get(id(expr))
        if kept is not None and kept[0] is expr:
            return kept[1]
        found = self._qualify(expr)
        if self.module.complete:
            self._qualified[id(expr)] = (expr, found)
        return found

    def _qualify(self, expr: cst.BaseExpression) -> tuple[str, ...]:
        # By type, not isinstance: libcst's node classes are ABCs, slow to isinstance.
        kind = type(expr)
        if kind is cst.Attribute:
            attribute = cast(cst.Attribute, expr)
            return tuple(
                f"{base}.{attribute.attr.value}" for base in self.qualified(attribute.value)
            )
        if kind is not cst.Name:
            return ()
        name = cast(cst.Name, expr).value
        bindings = self.lookup(name)
        imported = {binding.imported for binding in bindings if binding.imported}
        if len(imported) == 1:
            return tuple(imported)  # try/except fallbacks rebinding it do not count
        if bindings:
            return ()
        return tuple(f"{module}.{name}" for module in self.module.star_imports)

    def constant(self, name: str) -> Binding | None:
        """The single plain assignment of ``name``, when it has exactly one binding."""
        bindings = self.lookup(name)
        if len(bindings) == 1 and bindings[0].value is not None:
            return bindings[0]
        return None


# ---------------------------------------------------------------------------------------
# Where the walk is


@dataclass(frozen=True)
class Context:
    """Where the walk is: scope, statement order, enclosing nodes, expected failure."""

    scope: Scope
    anchors: tuple[cst.CSTNode, ...] = ()
    indents: tuple[str, ...] = ()
    expected_failure: bool = False  # inside `with pytest.raises(...)` / `assertRaises`

    def where(self, node: cst.CSTNode) -> Where:
        return Where(node, self.anchors, self.indents)

    def inside(self, node: cst.CSTNode) -> Context:
        """The context of what ``node`` contains: ``node`` is the innermost anchor."""
        return self.anchored((node, *self.anchors))

    def anchored(self, anchors: tuple[cst.CSTNode, ...]) -> Context:
        # Not dataclasses.replace: the walk makes one per statement, and replace is slow.
        return Context(self.scope, anchors, self.indents, self.expected_failure)


@dataclass(frozen=True)
class CallSite:
    call: cst.Call
    context: Context
    order: int

    def where(self, node: cst.CSTNode) -> Where:
        """Where an argument (or the callee) sits: inside its ``keyword=value`` (which is
        unique in a call even when the value is not: ``Node(package="x", name="x")``)."""
        return argument_context(self.call, self.context, node).where(node)


def argument_context(call: cst.Call, context: Context, node: cst.CSTNode) -> Context:
    """The context of ``node`` written in ``call``, in its argument when it is one."""
    inner = context.inside(call)
    for item in call.args:
        if item.value is node:
            return inner.inside(item)
    return inner


@dataclass(frozen=True)
class AssignSite:
    """``target.attr = value``: how code fills ``msg.header.frame_id``."""

    target: cst.Attribute
    value: cst.BaseExpression
    context: Context
    order: int


@dataclass(frozen=True)
class ClassSite:
    node: cst.ClassDef
    scope: Scope  # where the class statement is
    body: Scope
