"""What a C++ file builds: node handles, nodes, action servers... where, and into what.

A construction is found from the word that names its type, in any of the forms C++ has:
a declared object (``ros::NodeHandle nh("~");``), a class member with a default or a
constructor initializer (``private_nh_("~")``), a temporary (``ros::NodeHandle("~")``),
``new``, ``std::make_shared<T>(...)`` and ``T::make_shared(...)``. Pointers, references and
smart-pointer declarations build nothing and are not constructions.

``Classes`` knows which classes of the file are nodes (they derive from ``rclcpp::Node``
or a ``LifecycleNode``) and which hold a ``ros::NodeHandle``: building one needs the ROS
runtime as much as building a handle does.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, replace
from enum import Enum

from tree_sitter import Node

from .source import (
    Source,
    arguments,
    call_named_by,
    compact,
    enclosing,
    enclosing_functions,
    is_field,
)

_OBJECT_DECLARATORS = frozenset({"identifier", "field_identifier", "qualified_identifier"})
_MAKERS = frozenset({"make_shared", "make_unique", "allocate_shared"})
_CLASSES = frozenset({"class_specifier", "struct_specifier"})
_FIELDS = frozenset({"field_declaration"})
_FUNCTIONS = frozenset({"function_definition"})
_DEFAULT_ARGUMENTS = frozenset({"optional_parameter_declaration"})
_USING_RCLCPP = re.compile(rb"using\s+(?:namespace\s+rclcpp\s*;|rclcpp::Node\s*;)")
NODE_BASES = {"Node": "rclcpp::Node", "LifecycleNode": "rclcpp_lifecycle::LifecycleNode"}
PRIVATE_HANDLE_GETTERS = ("getPrivateNodeHandle", "getMTPrivateNodeHandle")


class Form(str, Enum):
    OBJECT = "object"  # a declared object: `ros::NodeHandle nh;`
    MEMBER = "member"  # a class member: built with its object, not where it is written
    TEMPORARY = "temporary"  # a call, new or make_shared expression
    ARGUMENT = "argument"  # a default argument: built by each caller, wherever that is


@dataclass(frozen=True)
class Construction:
    type_name: str  # the type's own name: "NodeHandle", "SimpleActionServer", "Talker"
    qualifier: str  # what precedes it: "ros", "actionlib", "" when unqualified
    template: Node | None  # the constructed type's template arguments
    arguments: tuple[Node, ...]
    site: Node  # what a finding about the construction points at
    binding: str | None  # the variable or member that receives the object
    form: Form
    static_storage: bool  # built before main(): namespace scope or a static member
    initializer: Node | None = None  # `T x = expression;`: what the object is copied from


# ---------------------------------------------------------------------------------------
# Finding constructions


@dataclass(frozen=True)
class _TypeUse:
    """A type named in the code, before we know whether something is built with it."""

    name: str
    qualifier: str
    template: Node | None
    node: Node  # the whole spelling: `actionlib::SimpleActionServer<T>`

    def build(
        self,
        values: Iterable[Node],
        site: Node,
        binding: str | None,
        form: Form,
        initializer: Node | None = None,
    ) -> Construction:
        form, static = _storage(site, form)
        return Construction(
            self.name,
            self.qualifier,
            self.template,
            tuple(values),
            site,
            binding,
            form,
            static,
            initializer,
        )


def constructions_named_by(source: Source, word: Node) -> list[Construction]:
    """The constructions whose type ``word`` names (none when it names something else)."""
    parent = word.parent
    if (
        parent is not None
        and parent.type == "qualified_identifier"
        and is_field(parent, "scope", word)
    ):
        return _static_maker(source, word, parent)
    spelled = _type_spelling(word)
    if spelled is None or spelled[0].parent is None:
        return []
    node, template = spelled
    use = _TypeUse(source.text(word), _qualifier(source, node, word), template, node)
    context = spelled[0].parent
    if context.type in ("declaration", "field_declaration"):
        return _declared(source, context, use) if is_field(context, "type", node) else []
    if context.type == "type_descriptor":
        call = _maker_call(source, context)
        if call is None:
            return []
        return [use.build(call[1], call[0], binding_of(source, call[0]), Form.TEMPORARY)]
    field_name = _EXPRESSIONS.get(context.type)
    if field_name is None or not is_field(context, field_name[0], node):
        return []
    values = arguments(context.child_by_field_name(field_name[1]))
    return [use.build(values, context, binding_of(source, context), Form.TEMPORARY)]


# Expressions that build a temporary: (the field holding the type, the one holding arguments)
_EXPRESSIONS = {
    "call_expression": ("function", "arguments"),  # ros::NodeHandle("~")
    "compound_literal_expression": ("type", "value"),  # ros::NodeHandle{"~"}
    "new_expression": ("type", "arguments"),  # new ros::NodeHandle("~")
}


def _storage(site: Node, form: Form) -> tuple[Form, bool]:
    """What kind of object the site builds, and whether it is built before main().

    A temporary in a member's default initializer is built with its object, like the
    member itself; a default argument is built by each caller; a static member and
    anything else outside functions is built before main().
    """
    if enclosing(site, _DEFAULT_ARGUMENTS) is not None:
        return Form.ARGUMENT, False
    if enclosing_functions(site):
        return form, False
    field = site if site.type == "field_declaration" else enclosing(site, _FIELDS)
    if field is not None and not _is_static(field):
        return Form.MEMBER, False
    return form, form is not Form.MEMBER


def _is_static(declaration: Node) -> bool:
    return any(
        child.type == "storage_class_specifier" and child.text == b"static"
        for child in declaration.children
    )


def _type_spelling(word: Node) -> tuple[Node, Node | None] | None:
    """The whole type ``word`` is the name of (``a::B<T>``), with its template arguments."""
    node, template = word, None
    parent = node.parent
    if parent is not None and parent.type == "template_type" and is_field(parent, "name", node):
        template, node, parent = parent.child_by_field_name("arguments"), parent, parent.parent
    while parent is not None and parent.type == "qualified_identifier":
        if not is_field(parent, "name", node):
            return None
        node, parent = parent, parent.parent
    return node, template


def _qualifier(source: Source, type_node: Node, word: Node) -> str:
    if type_node == word or type_node.type == "template_type":
        return ""
    text = compact(source.text(type_node))
    text = text.split("<", 1)[0] if "<" in text else text
    return text.rpartition("::")[0]


def _declared(source: Source, declaration: Node, use: _TypeUse) -> list[Construction]:
    """Objects declared with the type: one per plain declarator, none for pointers."""
    storage = {
        source.text(child)
        for child in declaration.children
        if child.type == "storage_class_specifier"
    }
    if "extern" in storage or any(child.type == "typedef" for child in declaration.children):
        return []
    member = declaration.type == "field_declaration"
    default = declaration.child_by_field_name("default_value") if member else None
    if member and "static" in storage and "inline" not in storage and default is None:
        return []  # declares a static member; its definition outside the class builds it
    found = []
    for declarator in declaration.children_by_field_name("declarator"):
        target: Node | None = declarator
        value = default
        if declarator.type == "init_declarator":
            target = declarator.child_by_field_name("declarator")
            value = declarator.child_by_field_name("value")
        if target is None or target.type not in _OBJECT_DECLARATORS:
            continue  # a pointer, reference, array or function: nothing is built
        copied = None
        if value is not None and value.type not in ("argument_list", "initializer_list"):
            if _builds_same_type(source, value, use.node):
                continue  # `T x = T(...)`: the temporary on the right is the construction
            copied, value = value, None
        form = Form.MEMBER if member else Form.OBJECT
        name = _declared_name(source, target)
        found.append(use.build(arguments(value), use.node, name, form, copied))
    return found


def _builds_same_type(source: Source, value: Node, type_node: Node) -> bool:
    """`T x = T(...)` / `T x = T{...}`: the temporary on the right is the construction."""
    if value.type not in ("call_expression", "compound_literal_expression"):
        return False
    callee = value.child_by_field_name("function") or value.child_by_field_name("type")
    return callee is not None and compact(source.text(callee)) == compact(source.text(type_node))


def _maker_call(source: Source, descriptor: Node) -> tuple[Node, list[Node]] | None:
    """``std::make_shared<T>(args)``: the call and the arguments given to T's constructor."""
    argument_list = descriptor.parent
    template_function = None if argument_list is None else argument_list.parent
    if (
        argument_list is None
        or argument_list.type != "template_argument_list"
        or argument_list.named_children[:1] != [descriptor]
        or template_function is None
        or template_function.type != "template_function"
    ):
        return None
    name = template_function.child_by_field_name("name")
    if name is None or source.text(name) not in _MAKERS:
        return None
    call = call_named_by(source, name)
    if call is None:
        return None
    values = list(call.arguments)
    return call.node, values[1:] if call.name == "allocate_shared" else values


def _static_maker(source: Source, word: Node, qualified: Node) -> list[Construction]:
    """``rclcpp::Node::make_shared(args)`` and ``Talker::make_shared()``."""
    name = qualified.child_by_field_name("name")
    if name is None or name.type != "identifier" or source.text(name) not in _MAKERS:
        return []
    call = call_named_by(source, name)
    if call is None:
        return []
    outer = qualified
    while outer.parent is not None and outer.parent.type == "qualified_identifier":
        outer = outer.parent  # `rclcpp::` before `Node::make_shared`
    parts = compact(source.text(outer)).rsplit("::", 2)
    use = _TypeUse(source.text(word), parts[0] if len(parts) == 3 else "", None, word)
    site = call.node
    return [use.build(call.arguments, site, binding_of(source, site), Form.TEMPORARY)]


def member_constructions(source: Source, members: list[Construction]) -> list[Construction]:
    """Members built in constructor initializer lists: ``as_(nh_, "fibonacci", ...)``."""
    found = []
    for member in members:
        if member.form is not Form.MEMBER or member.binding is None:
            continue
        for initializer, values in _member_initializers(source, member.binding):
            found.append(replace(member, arguments=tuple(values), site=initializer))
    return found


def is_member_declaration(construction: Construction) -> bool:
    """The class's own declaration of a member, which constructors may initialise."""
    parent = construction.site.parent
    return (
        construction.form is Form.MEMBER
        and parent is not None
        and parent.type == ("field_declaration")
    )


def _member_initializers(source: Source, member: str) -> list[tuple[Node, list[Node]]]:
    """``member_(args)`` in constructor initializer lists: the initializer and its arguments."""
    found = []
    for node in source.occurrences(member):
        parent = node.parent
        if (
            parent is not None
            and parent.type == "field_initializer"
            and parent.named_children[0] == node
            and parent.named_child_count > 1
        ):
            found.append((parent, arguments(parent.named_children[1])))
    return found


# ---------------------------------------------------------------------------------------
# Bindings: which variable receives an object


def binding_of(source: Source, expression: Node) -> str | None:
    """The variable or member an expression's value is stored in, when that is plain."""
    parent = expression.parent
    if parent is None:
        return None
    if parent.type == "init_declarator" and is_field(parent, "value", expression):
        target = parent.child_by_field_name("declarator")
        return None if target is None else _declared_name(source, target)
    if parent.type == "field_declaration" and is_field(parent, "default_value", expression):
        target = parent.child_by_field_name("declarator")
        return None if target is None else _declared_name(source, target)
    if parent.type == "assignment_expression" and is_field(parent, "right", expression):
        left = parent.child_by_field_name("left")
        return None if left is None else variable_name(source, left)
    if parent.type == "argument_list" and parent.parent is not None:
        owner = parent.parent
        if owner.type == "field_initializer":
            return source.text(owner.named_children[0])
        call = owner.child_by_field_name("function") if owner.type == "call_expression" else None
        if call is not None and call.type == "field_expression":
            method = call.child_by_field_name("field")
            receiver = call.child_by_field_name("argument")
            if method is not None and source.text(method) == "reset" and receiver is not None:
                return variable_name(source, receiver)
    return None


def variable_name(source: Source, node: Node) -> str | None:
    """``nh``, ``this->nh_``, ``*nh_`` -> the variable or member name."""
    if node.type in ("identifier", "field_identifier"):
        return source.text(node)
    if node.type == "pointer_expression":
        inner = node.child_by_field_name("argument")
        return None if inner is None else variable_name(source, inner)
    if node.type == "field_expression":
        owner = node.child_by_field_name("argument")
        member = node.child_by_field_name("field")
        if owner is not None and owner.type == "this" and member is not None:
            return source.text(member)
    return None


def _declared_name(source: Source, declarator: Node) -> str | None:
    node: Node | None = declarator
    while node is not None:
        if node.type in ("identifier", "field_identifier"):
            return source.text(node)
        if node.type == "qualified_identifier":
            node = node.child_by_field_name("name")
        elif node.type == "reference_declarator":
            node = node.named_children[-1] if node.named_child_count else None
        else:
            node = node.child_by_field_name("declarator")
    return None


# ---------------------------------------------------------------------------------------
# Classes of the file


class Classes:
    """The file's classes that are ROS nodes, or that hold a ``ros::NodeHandle``."""

    def __init__(self, source: Source) -> None:
        self._source = source
        self.using_rclcpp = bool(_USING_RCLCPP.search(source.data))
        self.mentions_rclcpp = b"rclcpp" in source.data
        self.nodes: dict[str, str] = {}  # class name -> the rclcpp base it derives from
        self.holders: set[str] = set()
        self._find_nodes()
        self._find_holders()

    def accepts_node_base(self, name: str, qualifier: str) -> bool:
        """``rclcpp::Node`` (or ``Node`` under a using), any ``LifecycleNode``, a node class."""
        if name == "Node":
            return qualifier == "rclcpp" or (qualifier == "" and self.using_rclcpp)
        return name == "LifecycleNode" or (qualifier == "" and name in self.nodes)

    def initializes_node_base(self, initializer: Node, name: str, qualifier: str) -> bool:
        """Whether ``: Node("talker")`` in a constructor builds an rclcpp base class.

        ``rclcpp::Node`` and any ``LifecycleNode`` always do; a bare ``Node`` does in a node
        class of the file, or in a constructor of a class the file does not define (its
        header does) when the file uses rclcpp.
        """
        if name == "LifecycleNode" or qualifier == "rclcpp":
            return True
        if name != "Node" or qualifier:
            return False
        owner = self._constructor_class(initializer)
        if owner is None:
            return False
        return owner in self.nodes or (self.mentions_rclcpp and not self._defines(owner))

    def _constructor_class(self, initializer: Node) -> str | None:
        function = enclosing(initializer, _FUNCTIONS)
        declarator = None if function is None else function.child_by_field_name("declarator")
        name = None if declarator is None else declarator.child_by_field_name("declarator")
        if name is not None and name.type == "qualified_identifier":
            scope = name.child_by_field_name("scope")  # Talker::Talker()
            return None if scope is None else self._source.text(scope)
        owner = enclosing(initializer, _CLASSES)  # a constructor defined in its class
        owner_name = None if owner is None else owner.child_by_field_name("name")
        return None if owner_name is None else self._source.text(owner_name)

    def _defines(self, name: str) -> bool:
        return any(
            word.parent is not None
            and word.parent.type in _CLASSES
            and word.parent.child_by_field_name("name") == word
            for word in self._source.occurrences(name)
        )

    def _find_nodes(self) -> None:
        pending = list(NODE_BASES)
        while pending:
            base = pending.pop()
            for word in self._source.occurrences(base):
                derived = self._derived_class(word)
                if derived is None or derived in self.nodes:
                    continue
                spelled = _type_spelling(word)
                qualifier = "" if spelled is None else _qualifier(self._source, spelled[0], word)
                if base in NODE_BASES and not self.accepts_node_base(base, qualifier):
                    continue
                self.nodes[derived] = NODE_BASES.get(base) or self.nodes.get(base, "rclcpp::Node")
                pending.append(derived)

    def _derived_class(self, word: Node) -> str | None:
        spelled = _type_spelling(word)
        if spelled is None:
            return None
        clause = spelled[0].parent
        if clause is None or clause.type != "base_class_clause" or clause.parent is None:
            return None
        name = clause.parent.child_by_field_name("name")
        return None if name is None else self._source.text(name)

    def _find_holders(self) -> None:
        """Classes with a ``ros::NodeHandle`` object member, or a member of such a class."""
        pending = ["NodeHandle"]
        while pending:
            held = pending.pop()
            for word in self._source.occurrences(held):
                holder = self._owner_of_member(word)
                if holder and holder not in self.holders and holder != held:
                    self.holders.add(holder)
                    pending.append(holder)

    def _owner_of_member(self, word: Node) -> str | None:
        """The class that declares a member of ``word``'s type (not a temporary in one)."""
        for construction in constructions_named_by(self._source, word):
            if construction.form is Form.MEMBER and construction.site.parent is not None:
                if construction.site.parent.type != "field_declaration":
                    continue
                owner = enclosing(construction.site, _CLASSES)
                name = None if owner is None else owner.child_by_field_name("name")
                return None if name is None else self._source.text(name)
        return None
