"""Static values of C++ expressions: literals, adjacent literals and same-file constants.

A name is folded when the whole argument is a string literal, adjacent literals
(``"a" "b"``), ``std::string("a")``, or an identifier bound to a constant of the same file:
a ``const``/``constexpr`` ``std::string``, ``std::string_view``, ``char*``, ``char[]`` or
``auto`` (namespace scope, class member or local), or a ``#define`` of literals; or to a
mutable variable whose value there is certain (``variables.py``); a constant member read
through an instance (``this->kTopic``, ``mux.kTopic``); a ``+`` of two of these
(``kNs + "/cmd"``). Anything else is dynamic: ``prefix + "/cmd"`` of a parameter, a
function result, a ternary, a string the code may change.
A constant that is assigned anywhere in the file, or set in a constructor's initializer
list, is not a constant. A dynamic ``std::string`` sum that starts with an absolute literal
(``"/planning/" + name``, or a string initialised once with one) keeps that literal as its
``prefix``: the name is still unknown, but certain to be absolute. One that ends with a
literal (``plugin_name_ + ".max_vel_x"``) keeps it as its ``suffix``: a parameter under a
run-time prefix.
"""

from __future__ import annotations

from dataclasses import dataclass

from tree_sitter import Node

from .source import (
    STRING_LITERALS,
    Source,
    arguments,
    compact,
    contains,
    enclosing_functions,
    is_field,
    literal_value,
    macro_literal,
    unparenthesized,
)
from .variables import Write, is_assigned, known_writes, reaching

_DECLARATIONS = frozenset(
    {"declaration", "field_declaration", "parameter_declaration", "optional_parameter_declaration"}
)
_POINTER_LIKE = frozenset({"pointer_declarator", "array_declarator"})
_STRING_TYPES = frozenset(
    {"std::string", "string", "std::string_view", "string_view", "auto", "std::basic_string<char>"}
)
_CHARACTER_TYPES = frozenset({"char", "auto"})
# Functions that return their single string argument unchanged, as far as names go.
STRING_WRAPPERS = frozenset(
    {
        "std::string",
        "string",
        "std::string_view",
        "string_view",
        "rclcpp::ParameterValue",
        "ParameterValue",
    }
)
# Operands that make ``"literal" + x`` pointer arithmetic, not a string
_NOT_STRINGS = frozenset({"number_literal", "char_literal", "true", "false"})
_MAX_DEPTH = 8  # constants defined through constants; also stops cycles in broken code


@dataclass(frozen=True)
class Value:
    """What an argument evaluates to; ``node`` is where a finding should point."""

    text: str  # the value, or the argument's spelling when dynamic
    dynamic: bool
    node: Node
    symbol: str | None = None  # a dynamic identifier no declaration of the file binds
    # a dynamic value's certain absolute start: the literal of ``"/planning/" + name``
    prefix: str | None = None
    # a dynamic value's certain end: the literal of ``name + ".max_vel_x"``
    suffix: str | None = None


@dataclass(frozen=True)
class Declaration:
    """One declaration of a name: a variable, member, parameter or macro."""

    name: str
    node: Node  # the declaration (or preproc_def) node
    value: Node | None  # its initializer expression, when it has one
    function: Node | None  # innermost enclosing function or lambda; None at file level
    constant: bool  # const (or a macro) and of a string type
    macro: bool
    string: bool = True  # a variable or member of a string type, const or not (or a macro)


class Declarations:
    """Where each identifier of the file is declared, found on demand and cached."""

    def __init__(self, source: Source) -> None:
        self._source = source
        self._found: dict[str, list[Declaration]] = {}
        self._mutated: dict[str, bool] = {}

    def of(self, name: str) -> list[Declaration]:
        found = self._found.get(name)
        if found is None:
            found = [
                declaration
                for node in self._source.occurrences(name)
                if (declaration := self._declaration_at(node)) is not None
            ]
            self._found[name] = found
        return found

    def mutated(self, name: str) -> bool:
        """Assigned somewhere, or set in a constructor's initializer list."""
        known = self._mutated.get(name)
        if known is None:
            known = any(_is_mutation(node) for node in self._source.occurrences(name))
            self._mutated[name] = known
        return known

    def visible(self, name: str, use: Node) -> list[Declaration]:
        """The declarations ``use`` can mean: the innermost scope that declares ``name``.

        A local declared before the use (in this function or one enclosing it) shadows the
        file; several file-level declarations are all returned, so that a caller can see
        they disagree. A macro defined before the use replaces everything.
        """
        chain = enclosing_functions(use)
        before = [d for d in self.of(name) if d.node.start_byte < use.start_byte]
        macros = [d for d in before if d.macro]
        if macros:
            return macros[-1:]
        for function in chain:
            local = [d for d in before if d.function == function]
            if local:
                return local[-1:]
        found = [d for d in self.of(name) if d.function is None and not d.macro]
        if any(d.value is not None for d in found):
            # `static const std::string kName;` in the class, defined with its value later
            found = [d for d in found if d.value is not None or not d.constant]
        return found

    def _declaration_at(self, node: Node) -> Declaration | None:
        child, parent = node, node.parent
        if parent is not None and parent.type == "preproc_def":
            if not is_field(parent, "name", child):
                return None
            body = parent.child_by_field_name("value")
            return Declaration(self._source.text(node), parent, body, None, True, macro=True)
        while parent is not None and parent.type == "qualified_identifier":
            if not is_field(parent, "name", child):
                return None
            child, parent = parent, parent.parent  # `const std::string ns::Foo::kName = ...`
        value: Node | None = None
        indirect = False
        while parent is not None and _wraps_declarator(parent, child):
            if parent.type == "init_declarator":
                value = parent.child_by_field_name("value")
            indirect = indirect or parent.type in _POINTER_LIKE
            child, parent = parent, parent.parent
        if parent is None or parent.type not in _DECLARATIONS:
            return None
        if child not in parent.children_by_field_name("declarator"):
            return None
        if parent.type == "field_declaration":
            value = parent.child_by_field_name("default_value")
        functions = enclosing_functions(parent)
        string = parent.type in ("declaration", "field_declaration") and _string_typed(
            self._source, parent, indirect
        )
        constant = string and _const_qualified(self._source, parent)
        name = self._source.text(node)
        function = functions[0] if functions else None
        return Declaration(name, parent, value, function, constant, False, string)


def _declares(identifier: Node) -> bool:
    """Whether an identifier is the name a declaration declares."""
    parent = identifier.parent
    while parent is not None and parent.type in ("init_declarator", *_POINTER_LIKE):
        if not is_field(parent, "declarator", identifier):
            return False
        identifier, parent = parent, parent.parent
    return parent is not None and parent.type in _DECLARATIONS


def _wraps_declarator(parent: Node, child: Node) -> bool:
    if parent.type == "reference_declarator":
        return True  # its declarator is not a named field
    if parent.type in ("init_declarator", "pointer_declarator", "array_declarator"):
        return is_field(parent, "declarator", child)
    return False


def _const_qualified(source: Source, declaration: Node) -> bool:
    qualifiers = {
        source.text(child) for child in declaration.children if child.type == "type_qualifier"
    }
    return bool(qualifiers & {"const", "constexpr"})


def _string_typed(source: Source, declaration: Node, indirect: bool) -> bool:
    kind = declaration.child_by_field_name("type")
    spelling = "" if kind is None else compact(source.text(kind))
    return spelling in _STRING_TYPES or (indirect and spelling in _CHARACTER_TYPES)


def _named_identifier(node: Node) -> Node | None:
    """The identifier a name ends in: ``kTopic``, ``ns::Class::kTopic`` -> ``kTopic``."""
    while node.type == "qualified_identifier":
        inner = node.child_by_field_name("name")
        if inner is None:
            return None
        node = inner
    return node if node.type == "identifier" else None


def _is_mutation(node: Node) -> bool:
    target, parent = node, node.parent
    if parent is not None and parent.type == "field_expression" and is_field(parent, "field", node):
        target, parent = parent, parent.parent
    if parent is None:
        return False
    if parent.type == "assignment_expression":
        return is_field(parent, "left", target)
    return parent.type == "field_initializer" and parent.named_children[0] == node


class Folder:
    """Evaluates name arguments to their static text, or says they are dynamic."""

    def __init__(self, source: Source, declarations: Declarations) -> None:
        self._source = source
        self.declarations = declarations

    def fold(self, node: Node) -> Value:
        return self._fold(node, 0)

    def static(self, node: Node) -> str | None:
        value = self.fold(node)
        return None if value.dynamic else value.text

    def local_field(self, node: Node) -> Value | None:
        """A field of a local object the function sets once, plainly, before ``node``
        reads it: ``descriptor.name = "colormap"; declare_parameter(descriptor.name, ...)``
        (how image_pipeline names its parameters). None when anything else may write it:
        another assignment, a setter (``set__name``), the object handed to a call first."""
        access = unparenthesized(node)
        if access.type != "field_expression":
            return None
        holder = access.child_by_field_name("argument")
        field = access.child_by_field_name("field")
        operator = access.child_by_field_name("operator")
        functions = enclosing_functions(access)
        if holder is None or field is None or holder.type != "identifier" or not functions:
            return None
        if operator is not None and self._source.text(operator) != ".":
            return None
        function, name, wanted = functions[0], self._source.text(holder), self._source.text(field)
        writes: list[Node] = []
        for occurrence in self._source.occurrences(name):
            if not contains(function, occurrence) or occurrence == holder:
                continue
            parent = occurrence.parent
            if parent is not None and parent.type == "field_expression":
                member = parent.child_by_field_name("field")
                spelled = "" if member is None else self._source.text(member)
                outer = parent.parent
                if spelled == f"set__{wanted}":
                    return None
                if (
                    spelled == wanted
                    and outer is not None
                    and outer.type == "assignment_expression"
                    and is_field(outer, "left", parent)
                ):
                    writes.append(outer)
                continue
            if occurrence.start_byte < access.start_byte and not _declares(occurrence):
                return None  # handed to something before the use: it may set the field
        if len(writes) != 1 or writes[0].end_byte > access.start_byte:
            return None
        statement = writes[0].parent
        block = None if statement is None else statement.parent
        if block is None or block.type != "compound_statement" or not contains(block, access):
            return None  # set on one branch only
        right = writes[0].child_by_field_name("right")
        value = None if right is None else self.fold(right)
        return None if value is None or value.dynamic else Value(value.text, False, node)

    def _fold(self, node: Node, depth: int) -> Value:
        expression = unparenthesized(node)
        kind = expression.type
        text: str | None = None
        if kind in STRING_LITERALS:
            text = literal_value(self._source, expression)
        elif kind == "concatenated_string":
            text = self._concatenation(expression, depth)
        elif kind in ("identifier", "qualified_identifier"):
            text = self._constant(expression, depth)
            if text is None and depth == 0 and self._undeclared(expression):
                spelling = compact(self._source.text(node))
                return Value(spelling, True, node, symbol=compact(self._source.text(expression)))
            if text is None:
                written = self._written_once(expression, depth)
                prefix = None if written is None else written.prefix
                suffix = None if written is None else written.suffix
                return Value(
                    compact(self._source.text(node)), True, node, prefix=prefix, suffix=suffix
                )
        elif kind in ("call_expression", "compound_literal_expression"):
            wrapped = self._wrapped(expression)
            if wrapped is not None:
                return self._fold(wrapped, depth)
        elif kind == "binary_expression":
            return self._sum(node, expression, depth)
        elif kind == "field_expression":
            text = self._member_constant(expression, depth)
        if text is None:
            return Value(compact(self._source.text(node)), True, node)
        return Value(text, False, expression)

    def _sum(self, node: Node, expression: Node, depth: int) -> Value:
        """``"/planning/" + name``: dynamic, but certain to start with its absolute literal
        (a ``std::string`` sum; a number added to a literal is pointer arithmetic);
        ``name + ".max_vel_x"``: certain to end with its literal."""
        spelling = Value(compact(self._source.text(node)), True, node)
        operator = expression.child_by_field_name("operator")
        left = expression.child_by_field_name("left")
        right = expression.child_by_field_name("right")
        if operator is None or left is None or right is None or self._source.text(operator) != "+":
            return spelling
        if unparenthesized(right).type in _NOT_STRINGS or depth >= _MAX_DEPTH:
            return spelling
        start = self._fold(left, depth + 1)
        suffix = None
        if not start.dynamic:
            end = self._fold(right, depth + 1)
            if not end.dynamic:  # kNs + "/cmd" of two constants
                return Value(start.text + end.text, False, expression)
            suffix = end.suffix
        elif unparenthesized(right).type in STRING_LITERALS:  # plugin_name_ + ".max_vel_x"
            suffix = literal_value(self._source, unparenthesized(right))
        prefix = start.prefix if start.dynamic else start.text
        if prefix is not None and not prefix.startswith("/"):
            prefix = None
        return Value(spelling.text, True, node, prefix=prefix, suffix=suffix or None)

    def _member_constant(self, access: Node, depth: int) -> str | None:
        """``this->kTopic``, ``driver.kTopic``: a constant member of the file's classes, the
        same in every class that declares one of that name."""
        field = access.child_by_field_name("field")
        if field is None or field.type != "field_identifier" or depth >= _MAX_DEPTH:
            return None
        name = self._source.text(field)
        members = [d for d in self.declarations.of(name) if d.function is None and not d.macro]
        if any(d.value is not None for d in members):
            members = [d for d in members if d.value is not None]  # `static const` defined later
        if not members or not all(d.constant for d in members) or self.declarations.mutated(name):
            return None
        values = {self._declaration_value(member, depth + 1) for member in members}
        return values.pop() if len(values) == 1 else None

    def _written_once(self, expression: Node, depth: int) -> Value | None:
        """The dynamic value of a string written once, where it is declared, for the
        absolute start and the end it certainly has: ``const std::string topic =
        "/planning/" + name;``."""
        name_node = _named_identifier(expression)
        if name_node is None or depth >= _MAX_DEPTH:
            return None
        name = self._source.text(name_node)
        candidates = self.declarations.visible(name, expression)
        if len(candidates) != 1 or candidates[0].macro or not candidates[0].string:
            return None
        writes = known_writes(self._source, self._source.occurrences(name))
        if writes is None or len(writes) != 1 or writes[0].value is None:
            return None
        value = self._fold(writes[0].value, depth + 1)
        return value if value.dynamic else None

    def _concatenation(self, node: Node, depth: int) -> str | None:
        parts: list[str] = []
        for child in node.named_children:
            if child.type == "comment":
                continue  # "a/"  // NOLINT(RN202)  "b": the comment is not part of it
            if child.type in STRING_LITERALS:
                part = literal_value(self._source, child)
            elif child.type == "identifier":
                part = self._constant(child, depth)  # "prefix" MACRO "suffix"
            else:
                part = None
            if part is None:
                return None
            parts.append(part)
        return "".join(parts)

    def _wrapped(self, node: Node) -> Node | None:
        """The argument of ``std::string("a")`` or ``std::string{"a"}``."""
        callee = node.child_by_field_name("function") or node.child_by_field_name("type")
        if callee is None or compact(self._source.text(callee)) not in STRING_WRAPPERS:
            return None
        values = arguments(
            node.child_by_field_name("arguments") or node.child_by_field_name("value")
        )
        return values[0] if len(values) == 1 else None

    def _constant(self, node: Node, depth: int) -> str | None:
        name_node = _named_identifier(node)
        if depth >= _MAX_DEPTH or name_node is None:
            return None
        name = self._source.text(name_node)
        candidates = self.declarations.visible(name, node)
        if not candidates or any(not candidate.constant for candidate in candidates):
            return self._variable(name, node, candidates, depth)
        if not candidates[0].macro and self.declarations.mutated(name):
            return None
        values = {self._declaration_value(candidate, depth + 1) for candidate in candidates}
        if len(values) != 1:
            return None
        return values.pop()

    def _undeclared(self, expression: Node) -> bool:
        """An identifier the file neither declares nor assigns: maybe another file's
        constant (a constant cannot be written through the calls it is passed to)."""
        name_node = _named_identifier(expression)
        if name_node is None:
            return False
        name = self._source.text(name_node)
        return not self.declarations.of(name) and not is_assigned(
            self._source, self._source.occurrences(name)
        )

    def _variable(
        self, name: str, use: Node, candidates: list[Declaration], depth: int
    ) -> str | None:
        """A mutable local, member or global whose value at ``use`` is certain: the one
        every write agrees on, or a local's last write before the use on every path to it.
        A member the file only assigns (declared in its header) counts too."""
        if len(candidates) > 1 or any(candidate.macro for candidate in candidates):
            return None
        declared = candidates[0] if candidates else None
        if declared is not None and not declared.string:
            return None  # a parameter, or not a string
        function = declared.function if declared is not None else None
        if declared is None and not enclosing_functions(use):
            return None
        occurrences = self._source.occurrences(name)
        if declared is not None and function is not None:  # a local
            start = declared.node.start_byte
            occurrences = [
                o for o in occurrences if contains(function, o) and o.start_byte >= start
            ]
        else:  # a member or a global, where no function declares its own
            shadowing = [d.function for d in self.declarations.of(name) if d.function is not None]
            occurrences = [o for o in occurrences if not any(contains(f, o) for f in shadowing)]
        writes = known_writes(self._source, occurrences)
        if writes is not None and function is None:
            writes = [w for w in writes if w.value is not None]  # `std::string topic_;`
        if not writes:
            return None
        values = {self._written_value(write, depth) for write in writes}
        if len(values) == 1:
            return values.pop()
        last = reaching(writes, use, function) if function is not None else None
        return None if last is None else self._written_value(last, depth)

    def _written_value(self, write: Write, depth: int) -> str | None:
        if write.value is None or depth >= _MAX_DEPTH:
            return None
        value = self._fold(write.value, depth + 1)
        return None if value.dynamic else value.text

    def _declaration_value(self, declaration: Declaration, depth: int) -> str | None:
        initializer = declaration.value
        if initializer is None:
            return None
        if declaration.macro:
            return macro_literal(self._source.text(initializer))
        if initializer.type in ("argument_list", "initializer_list"):
            values = arguments(initializer)  # `const std::string k("a")` or `k{"a"}`
            if len(values) != 1:
                return None
            initializer = values[0]
        value = self._fold(initializer, depth)
        return None if value.dynamic else value.text
