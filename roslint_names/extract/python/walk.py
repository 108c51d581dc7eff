"""One pass over a Python module: its scopes, calls and attribute stores.

Expressions are walked by their fields, which is far cheaper than libcst's visitor (that
would cost as much as the parse); statements and the constructs that open a scope or bind
a name are handled one by one.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Sequence
from typing import cast

import libcst as cst

from roslint_names.extract.python.scope import (
    AssignSite,
    Binding,
    CallSite,
    ClassSite,
    Context,
    Scope,
    ScopeKind,
)

_RAISES = frozenset({"raises", "assertRaises", "assertRaisesRegex", "assertRaisesRegexp"})
_PROBES = frozenset({"assertFalse", "failIf"})  # unittest's, on self
# Fields that hold only whitespace, punctuation and comments: never a name or a call.
_SKIPPED_FIELDS = frozenset(
    {
        "lpar",
        "rpar",
        "comma",
        "equal",
        "colon",
        "semicolon",
        "dot",
        "star",
        "lbracket",
        "rbracket",
        "lbrace",
        "rbrace",
        "operator",
        "header",
        "footer",
        "leading_lines",
        "lines_after_decorators",
        "trailing_whitespace",
        "newline",
        "first_line",
        "empty_lines",
        "last_line",
        "asynchronous",
    }
)
_FIELDS: dict[type, tuple[str, ...]] = {}
# Parts of a compound statement that hold a body of their own.
_CLAUSES = (
    cst.BaseCompoundStatement,
    cst.ExceptHandler,
    cst.ExceptStarHandler,
    cst.Else,
    cst.Finally,
    cst.MatchCase,
)


_LEAVES = frozenset(
    {
        cst.Name,
        cst.SimpleString,
        cst.Integer,
        cst.Float,
        cst.Imaginary,
        cst.Ellipsis,
        cst.FormattedStringText,
    }
)


_COMPREHENSIONS = frozenset({cst.ListComp, cst.SetComp, cst.GeneratorExp, cst.DictComp})


def _fields(node: cst.CSTNode) -> tuple[str, ...]:
    kind = type(node)
    names = _FIELDS.get(kind)
    if names is None:
        names = tuple(
            item.name
            for item in dataclasses.fields(node)
            if not item.name.startswith("whitespace") and item.name not in _SKIPPED_FIELDS
        )
        _FIELDS[kind] = names
    return names


# Whether a type is a node type, by type: CSTNode is an ABC, and ``isinstance`` against
# an ABC costs several times a dict lookup (the walk asks for every field of every node).
_IS_NODE: dict[type, bool] = {}


def _is_node(value: object) -> bool:
    kind = type(value)
    known = _IS_NODE.get(kind)
    if known is None:
        known = _IS_NODE[kind] = issubclass(kind, cst.CSTNode)
    return known


def _children(node: cst.CSTNode) -> list[cst.CSTNode]:
    found: list[cst.CSTNode] = []
    for name in _fields(node):
        value = getattr(node, name)
        if type(value) is tuple or type(value) is list:
            found.extend(item for item in value if _is_node(item))
        elif _is_node(value):
            found.append(value)
    return found


def dotted(expr: cst.BaseExpression) -> str | None:
    """``a.b.c`` as written, or None for anything but names and attributes."""
    if isinstance(expr, cst.Name):
        return expr.value
    if isinstance(expr, cst.Attribute):
        base = dotted(expr.value)
        return None if base is None else f"{base}.{expr.attr.value}"
    return None


def _import_name(node: cst.Attribute | cst.Name) -> str:
    return dotted(node) or ""


class Walk:
    """One pass over a module: scopes with their bindings, calls and attribute stores.

    Expressions are walked by their fields (far cheaper than libcst's visitor, which
    would cost as much as the parse); statements and the constructs that open a scope or
    bind a name are handled one by one.
    """

    def __init__(self, module: cst.Module) -> None:
        self.module = module
        self.root = Scope(ScopeKind.MODULE, "", None, "")
        self.scopes: list[Scope] = [self.root]  # every scope of the module (``release``)
        self.calls: list[CallSite] = []
        self.assignments: list[AssignSite] = []
        # Attributes written other than by ``x.attr = value`` (``+=``, tuple targets, del)
        self.other_attribute_writes: set[str] = set()
        self.classes: list[ClassSite] = []
        self.functions: list[cst.FunctionDef] = []  # module-level defs
        self.function_scopes: dict[cst.FunctionDef, Scope] = {}
        self.returns: dict[cst.FunctionDef, list[tuple[cst.BaseExpression, Context]]] = {}
        self.packages: set[str] = set()  # top-level packages imported anywhere
        self._order = 0
        self._top: tuple[cst.CSTNode, ...] = ()  # the module-level statement being walked
        # The compound statements around the statement being walked, innermost first
        # (below the top statement), and the indentation each is written at: anchors for
        # spans between its line and the whole top-level statement, so that a line whose
        # code repeats is placed by regenerating its ``if`` or ``for``, not its class.
        self._compounds: tuple[cst.BaseCompoundStatement, ...] = ()
        self.anchor_indents: dict[int, tuple[str, ...]] = {}
        self._keys: dict[str, int] = {}
        self.statements(module.body, Context(self.root))
        self.root.complete = True

    def release(self) -> None:
        """Break the cycles of the walk (a scope holds its bindings, each binding its
        scope) once nothing asks it any more. Reference counting then frees the file's
        tree as soon as its extraction is done; left to the cycle collector, the whole
        tree would be walked first (a seventh of a cold run's time on realws)."""
        for scope in self.scopes:
            scope.bindings.clear()

    # -- statements ---------------------------------------------------------------------

    def statements(self, body: Sequence[cst.CSTNode], context: Context) -> None:
        module_level = context.scope is self.root and not context.indents
        for statement in body:
            self._order += 1
            if module_level:
                # Spans are found inside the top-level statement when nothing nearer helps.
                self._top = (statement,)
            if type(statement) is cst.SimpleStatementLine:
                inner = context.anchored((statement, *self._compounds, *self._top))
                for small in statement.body:
                    self.small(small, inner)
            elif module_level:
                self.compound_statement(statement, context.anchored(self._top))
            else:
                self.nested(statement, context)

    def nested(self, statement: cst.CSTNode, context: Context) -> None:
        """A compound statement below the top one: the innermost anchor of what it holds,
        its header included, written at the indentation of the block it is in."""
        self.anchor_indents[id(statement)] = context.indents
        compound = cast(cst.BaseCompoundStatement, statement)  # what is not a line
        outer, self._compounds = self._compounds, (compound, *self._compounds)
        try:
            self.compound_statement(statement, context.anchored((*self._compounds, *self._top)))
        finally:
            self._compounds = outer

    def compound_statement(self, statement: cst.CSTNode, context: Context) -> None:
        if type(statement) is cst.FunctionDef:
            self.function(statement, context)
        elif type(statement) is cst.ClassDef:
            self.klass(statement, context)
        else:
            self.compound(statement, context)

    def block(self, suite: cst.BaseSuite, context: Context) -> None:
        if isinstance(suite, cst.IndentedBlock):
            indent = suite.indent if suite.indent is not None else self.module.default_indent
            self.statements(
                suite.body, dataclasses.replace(context, indents=(*context.indents, indent))
            )
        elif isinstance(suite, cst.SimpleStatementSuite):
            for small in suite.body:
                self.small(small, context)

    def compound(self, statement: cst.CSTNode, context: Context) -> None:
        """if/for/while/try/with/match: bind their targets, walk headers and bodies."""
        if isinstance(statement, cst.For):
            self.bind_target(statement.target, None, context.scope)
        elif isinstance(statement, cst.ExceptHandler | cst.ExceptStarHandler):
            if statement.name is not None:
                self.bind_target(statement.name.name, None, context.scope)
        elif isinstance(statement, cst.With):
            for item in statement.items:
                if item.asname is not None:
                    self.bind_target(item.asname.name, None, context.scope)
            if any(_expects_failure(item.item) for item in statement.items):
                context = dataclasses.replace(context, expected_failure=True)
        failing = None  # a try body that must raise before it fails the test
        if isinstance(statement, cst.Try) and (
            _try_expects_failure(statement) or _test_catches(statement, context.scope)
        ):
            failing = statement.body
        for child in _children(statement):
            if isinstance(child, cst.BaseSuite):
                # A new context only for the failing body: this walk is the extractor's
                # hot path, and a dataclass copy per suite is not free.
                if child is failing and not context.expected_failure:
                    self.block(child, dataclasses.replace(context, expected_failure=True))
                else:
                    self.block(child, context)
            elif isinstance(child, _CLAUSES):
                self.compound(child, context)
            else:
                self.expression(child, context)

    def function(self, node: cst.FunctionDef, context: Context) -> None:
        scope = context.scope
        scope.bind(node.name.value, Binding(scope, defined=node))
        if scope is self.root:
            self.functions.append(node)
        for decorator in node.decorators:
            self.expression(decorator.decorator, context)
        self.expression(node.params, context)  # defaults and annotations run here
        owner = _owner(scope)
        name = f"{scope.name}.{node.name.value}" if scope.name else node.name.value
        inner = Scope(ScopeKind.FUNCTION, name, scope, self._key(name), owner, node)
        self.scopes.append(inner)
        self.function_scopes[node] = inner
        _bind_parameters(node.params, inner)
        self.block(node.body, dataclasses.replace(context, scope=inner, expected_failure=False))

    def klass(self, node: cst.ClassDef, context: Context) -> None:
        scope = context.scope
        scope.bind(node.name.value, Binding(scope, defined=node))
        for decorator in node.decorators:
            self.expression(decorator.decorator, context)
        for argument in (*node.bases, *node.keywords):
            self.expression(argument.value, context)
        name = f"{scope.name}.{node.name.value}" if scope.name else node.name.value
        # A class body runs where the class statement runs: same RN301 key.
        body = Scope(ScopeKind.CLASS, name, scope, scope.key, node)
        self.scopes.append(body)
        self.classes.append(ClassSite(node, scope, body))
        self.block(node.body, dataclasses.replace(context, scope=body))

    def _key(self, name: str) -> str:
        count = self._keys.get(name, 0) + 1
        self._keys[name] = count
        return name if count == 1 else f"{name}#{count}"

    # -- small statements ---------------------------------------------------------------

    def small(self, node: cst.BaseSmallStatement, context: Context) -> None:
        # By type, not isinstance (an ABC's, slow): the walk asks for every statement.
        if type(node) is cst.Expr:  # most lines: a call; skip the checks below
            self.expression(node, context)
            return
        scope = context.scope
        if type(node) is cst.Assign:
            self.expression(node.value, context)
            for target in node.targets:
                self.store(target.target, node.value, context)
        elif type(node) is cst.AnnAssign:
            if node.value is not None:
                self.expression(node.value, context)
                self.store(node.target, node.value, context)
        elif type(node) is cst.AugAssign:
            self.expression(node.value, context)
            self.bind_target(node.target, None, scope)
        elif type(node) is cst.Import:
            for alias in node.names:
                self.bind_import(alias, None, scope)
        elif type(node) is cst.ImportFrom:
            self.import_from(node, scope)
        elif type(node) is cst.Global:
            scope.globals.update(item.name.value for item in node.names)
        elif type(node) is cst.Nonlocal:
            outer = scope.parent or scope
            for item in node.names:
                outer.bind(item.name.value, Binding(outer))  # rebound from inside: not constant
        elif type(node) is cst.Del:
            self.bind_target(node.target, None, scope)
        elif type(node) is cst.Return and node.value is not None:
            self.expression(node.value, context)
            if scope.function is not None and scope.kind is ScopeKind.FUNCTION:
                self.returns.setdefault(scope.function, []).append((node.value, context))
        else:
            self.expression(node, context)

    def store(
        self, target: cst.BaseExpression, value: cst.BaseExpression, context: Context
    ) -> None:
        if isinstance(target, cst.Attribute):
            self.assignments.append(AssignSite(target, value, context, self._order))
            self.expression(target.value, context)
        elif isinstance(target, cst.Subscript):
            self.expression(target, context)
        else:
            self.bind_target(target, value, context.scope, context)

    def bind_target(
        self,
        target: cst.BaseExpression,
        value: cst.BaseExpression | None,
        scope: Scope,
        context: Context | None = None,
    ) -> None:
        """Bind the names a target assigns; only a plain name keeps the value."""
        if isinstance(target, cst.Name):
            scope.bind(target.value, Binding(scope, value=value, context=context))
        elif isinstance(target, cst.Tuple | cst.List):
            for element in target.elements:
                self.bind_target(element.value, None, scope)
        elif isinstance(target, cst.StarredElement):
            self.bind_target(target.value, None, scope)
        elif isinstance(target, cst.Attribute):
            self.other_attribute_writes.add(target.attr.value)

    def bind_import(self, alias: cst.ImportAlias, module: str | None, scope: Scope) -> None:
        name = _import_name(alias.name)
        self.packages.add((module or name).split(".", 1)[0])
        if module is None:  # import a.b.c [as d]
            local = alias.asname.name if alias.asname else None
            if isinstance(local, cst.Name):
                scope.bind(local.value, Binding(scope, imported=name))
            else:
                head = name.split(".", 1)[0]
                scope.bind(head, Binding(scope, imported=head))
            return
        local_name = alias.asname.name if alias.asname else alias.name
        if isinstance(local_name, cst.Name):
            scope.bind(local_name.value, Binding(scope, imported=f"{module}.{name}"))

    def import_from(self, node: cst.ImportFrom, scope: Scope) -> None:
        # A relative import names a module of this package: never a ROS API.
        module = "." * len(node.relative) + (_import_name(node.module) if node.module else "")
        if isinstance(node.names, cst.ImportStar):
            self.packages.add(module.split(".", 1)[0])
            scope.module.star_imports.append(module)
            return
        for alias in node.names:
            self.bind_import(alias, module, scope)

    # -- expressions --------------------------------------------------------------------

    def expression(self, node: cst.CSTNode, context: Context) -> None:
        # By type and ``cast``, not isinstance: libcst's node classes are ABCs, slow to ask,
        # and this is the walk's hot spot (leaves are skipped before the call).
        kind = type(node)
        if kind is cst.Arg or kind is cst.Element:  # their keyword or comma holds nothing
            value = cast(cst.Arg | cst.Element, node).value
            if type(value) not in _LEAVES:
                self.expression(value, context)
        elif kind in _LEAVES:
            return
        elif kind is cst.Attribute:
            self.expression(cast(cst.Attribute, node).value, context)
        elif kind is cst.Call:
            self.call(cast(cst.Call, node), context)
        elif kind is cst.Lambda:
            self.lambda_(cast(cst.Lambda, node), context)
        elif kind in _COMPREHENSIONS:
            comprehension = cast(cst.ListComp | cst.SetComp | cst.GeneratorExp | cst.DictComp, node)
            self.comprehension(comprehension, context)
        elif kind is cst.NamedExpr:
            named = cast(cst.NamedExpr, node)
            self.expression(named.value, context)
            self.bind_target(named.target, named.value, _function_scope(context.scope), context)
        else:
            for child in _children(node):
                if type(child) not in _LEAVES:
                    self.expression(child, context)

    def call(self, node: cst.Call, context: Context) -> None:
        self.calls.append(CallSite(node, context, self._order))
        within = context.inside(node)
        if not context.expected_failure and _probes_failure(node):
            within = dataclasses.replace(within, expected_failure=True)
        self.expression(node.func, within)
        for argument in node.args:  # an argument's keyword is a name: nothing below it
            if type(argument.value) not in _LEAVES:
                self.expression(argument.value, within)

    def lambda_(self, node: cst.Lambda, context: Context) -> None:
        self.expression(node.params, context)
        outer = context.scope
        key = self._key(f"{outer.name}.<lambda>")
        scope = Scope(ScopeKind.FUNCTION, "<lambda>", outer, key)
        self.scopes.append(scope)
        _bind_parameters(node.params, scope)
        self.expression(node.body, dataclasses.replace(context, scope=scope))

    def comprehension(
        self, node: cst.ListComp | cst.SetComp | cst.GeneratorExp | cst.DictComp, context: Context
    ) -> None:
        """Loop targets are local to the comprehension: they shadow constants outside."""
        outer = context.scope
        scope = Scope(
            ScopeKind.COMPREHENSION, outer.name, outer, outer.key, outer.owner, outer.function
        )
        self.scopes.append(scope)
        inner = dataclasses.replace(context, scope=scope)
        clause: cst.CompFor | None = node.for_in
        while clause is not None:
            self.bind_target(clause.target, None, scope)
            self.expression(clause.iter, inner)
            for condition in clause.ifs:
                self.expression(condition.test, inner)
            clause = clause.inner_for_in
        if isinstance(node, cst.DictComp):
            self.expression(node.key, inner)
            self.expression(node.value, inner)
        else:
            self.expression(node.elt, inner)


def _owner(scope: Scope) -> cst.ClassDef | None:
    return scope.owner if scope.kind is ScopeKind.CLASS else None


def _function_scope(scope: Scope) -> Scope:
    while scope.kind is ScopeKind.COMPREHENSION and scope.parent is not None:
        scope = scope.parent
    return scope


def _bind_parameters(params: cst.Parameters, scope: Scope) -> None:
    every = (*params.posonly_params, *params.params, *params.kwonly_params)
    for param in every:
        scope.bind(param.name.value, Binding(scope))
    for star in (params.star_arg, params.star_kwarg):
        if isinstance(star, cst.Param):
            scope.bind(star.name.value, Binding(scope))


def _try_expects_failure(statement: cst.Try) -> bool:
    """``try: X; self.fail(...)`` or ``try: X`` ... ``else: self.fail(...)``: X must raise.

    ros_comm's rospy tests write ``try: rospy.init_node('ns/node') ... else: self.fail()``.
    """
    suites = [statement.body] + ([statement.orelse.body] if statement.orelse else [])
    return any(_fails(small) for suite in suites for small in _small_statements(suite))


def _probes_failure(call: cst.Call) -> bool:
    """``self.assertFalse(rospy.has_param('non-existent'))``: the call must come out false,
    a probe of what is refused or absent, not a use of the name."""
    func = call.func
    return type(func) is cst.Attribute and func.attr.value in _PROBES


def _test_catches(statement: cst.Try, scope: Scope) -> bool:
    """In a test function, one statement tried for one named exception that is not raised
    again: ``try: rospy.init_node('ns/node') except ValueError: failed = False`` then
    ``self.failIf(failed)`` (ros_comm's test_rospy). Outside tests the idiom guards code
    meant to work, and its names are judged; so does a handler that fails the test
    (rostest's hztest: ``try: rospy.get_param('~rate') except KeyError: self.fail(...)``)."""
    function = scope.function
    if function is None or not function.name.value.startswith("test"):
        return False
    if len(_lines(statement.body)) != 1 or not statement.handlers:
        return False
    return all(
        handler.type is not None
        and dotted(handler.type) not in (None, "Exception", "BaseException")
        and not _raises(handler.body)
        and not any(_fails(small) for small in _small_statements(handler.body))
        for handler in statement.handlers
    )


def _raises(suite: cst.BaseSuite) -> bool:
    return any(isinstance(small, cst.Raise) for small in _small_statements(suite))


def _lines(suite: cst.BaseSuite) -> Sequence[cst.BaseStatement | cst.BaseSuite]:
    """The statements of an indented block; a one-line suite is its own one line."""
    return suite.body if isinstance(suite, cst.IndentedBlock) else (suite,)


def _small_statements(suite: cst.BaseSuite) -> Iterator[cst.BaseSmallStatement]:
    """The simple statements of a suite's own lines (not of nested blocks)."""
    for line in _lines(suite):
        if isinstance(line, cst.SimpleStatementLine | cst.SimpleStatementSuite):
            yield from line.body


def _fails(small: cst.BaseSmallStatement) -> bool:
    """``self.fail(...)``, ``pytest.fail(...)``, ``fail(...)`` or ``assert False``."""
    if isinstance(small, cst.Assert):
        return isinstance(small.test, cst.Name) and small.test.value == "False"
    if not isinstance(small, cst.Expr) or not isinstance(small.value, cst.Call):
        return False
    func = small.value.func
    name = func.attr.value if isinstance(func, cst.Attribute) else dotted(func)
    return name == "fail"


def _expects_failure(item: cst.BaseExpression) -> bool:
    """``pytest.raises(...)``, ``self.assertRaises(...)``: the body is meant to fail."""
    if not isinstance(item, cst.Call):
        return False
    func = item.func
    name = func.attr.value if isinstance(func, cst.Attribute) else dotted(func)
    return name in _RAISES
