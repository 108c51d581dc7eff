"""Mutable C++ string variables whose value at a use is certain.

``std::string topic = "scan"; ... nh.subscribe(topic, ...)`` and a member set in the
constructor (``topic_ = "scan";`` or ``topic_("scan")``) and used in another method hold
names as surely as constants do. A variable is followed when every place the file writes
it is known (a declaration's initializer, a plain ``=``, a constructor's initializer) and
every other occurrence only reads it; then its value at a use is the one all writes agree
on, or, for a local, the last write before the use when that write runs on every path to
it. An occurrence that may write through a reference makes the value unknown: an argument
of a call not known to only read it (``nh.param("topic", topic, topic)`` stores the
parameter in ``topic``), ``&topic``, ``stream >> topic``, ``topic.append(...)``, a
lambda's ``[&topic]``; a lambda's ``[topic]`` or ``[=]`` copies it.
"""

from __future__ import annotations

from dataclasses import dataclass

from tree_sitter import Node

from .apis import ACTION_FUNCTIONS, ENDPOINTS, WAIT_FOR_MESSAGE
from .source import Source, compact, contains, is_field

# Calls that take a name by value or const reference: the APIs the extractor reads, and
# the string wrappers.
_READING_CALLS = frozenset(
    {
        *ENDPOINTS,
        *ACTION_FUNCTIONS,
        *WAIT_FOR_MESSAGE,
        "subscribe",
        "advertiseService",
        "create_sub_node",
        "declare_parameter",
        "setParam",
        "init",
        "NodeHandle",
        "string",
        "string_view",
        # A container's insertions copy their argument (``topics.push_back(front)``); one
        # moved from is the argument of ``std::move``, which is not read.
        "push_back",
        "emplace_back",
        "push_front",
        "emplace_front",
        "insert",
        "emplace",
        "push",
    }
)
_LOGGING_PREFIXES = ("ROS_", "RCLCPP_", "RCUTILS_LOG_")
# std::string members that leave the string as it is.
_READING_METHODS = frozenset(
    {
        "c_str",
        "data",
        "size",
        "length",
        "empty",
        "substr",
        "find",
        "rfind",
        "find_first_of",
        "find_last_of",
        "compare",
        "starts_with",
        "ends_with",
        "front",
        "back",
    }
)
_LOOPS = frozenset({"for_statement", "for_range_loop", "while_statement", "do_statement"})
_STATEMENT_PARENTS = frozenset({"compound_statement", "translation_unit"})


@dataclass(frozen=True)
class Write:
    """A place the variable gets a value: ``value`` is None for a declaration without an
    initializer (an empty string)."""

    occurrence: Node
    value: Node | None


def known_writes(source: Source, occurrences: list[Node]) -> list[Write] | None:
    """The writes among ``occurrences`` of one variable, or None when one of them may
    write it in a way the file does not show."""
    found: list[Write] = []
    for occurrence in occurrences:
        kind, value = _classify(source, occurrence)
        if kind == "unknown":
            return None
        if kind == "write":
            found.append(Write(occurrence, value))
    return found


def is_assigned(source: Source, occurrences: list[Node]) -> bool:
    """Whether the file gives the variable a value anywhere (a declaration, ``=``, a
    constructor initializer)."""
    return any(_classify(source, occurrence)[0] == "write" for occurrence in occurrences)


def reaching(writes: list[Write], use: Node, function: Node) -> Write | None:
    """The write a local's use sees: the last one before it, when that one runs on every
    path to the use, and no later write can come round a loop to it."""
    before = [write for write in writes if write.occurrence.start_byte < use.start_byte]
    if not before:
        return None
    last = before[-1]
    statement = statement_holding(last.occurrence, function)
    if statement is None or statement.parent is None or not contains(statement.parent, use):
        return None  # inside an `if` or a loop the use may not go through
    for write in writes:
        if write.occurrence.start_byte > use.start_byte and _shares_loop(write, use, function):
            return None
    return last


def _classify(source: Source, occurrence: Node) -> tuple[str, Node | None]:
    """("write", value), ("read", None) or ("unknown", None) for one occurrence."""
    target, parent = occurrence, occurrence.parent
    if parent is not None and parent.type == "field_expression":
        if is_field(parent, "argument", occurrence):
            return _method_use(source, parent)  # topic.c_str()
        owner = parent.child_by_field_name("argument")
        if owner is None or owner.type != "this":
            return "read", None  # other.topic_: another object's member
        target, parent = parent, parent.parent  # this->topic_
    if parent is None:
        return "read", None
    kind = parent.type
    if kind == "assignment_expression" and is_field(parent, "left", target):
        operator = parent.child_by_field_name("operator")
        if operator is None or source.text(operator) != "=":
            return "unknown", None  # +=
        return "write", parent.child_by_field_name("right")
    if kind == "init_declarator" and is_field(parent, "declarator", target):
        value = parent.child_by_field_name("value")
        if value is not None and value.type in ("argument_list", "initializer_list"):
            values = value.named_children
            value = values[0] if len(values) == 1 else None
            if value is None:
                return "unknown", None
        return "write", value
    if kind in ("declaration", "field_declaration") and is_field(parent, "declarator", target):
        return "write", parent.child_by_field_name("default_value")
    if kind == "field_initializer" and parent.named_children[0] == occurrence:
        values = [child for child in parent.named_children[1:] if child.type != "comment"]
        arguments = values[0].named_children if values else []
        return ("write", arguments[0]) if len(arguments) == 1 else ("unknown", None)
    if kind == "init_declarator" and is_field(parent, "value", target):
        declarator = parent.child_by_field_name("declarator")
        if declarator is not None and declarator.type == "reference_declarator":
            return "unknown", None  # std::string& alias = topic;
        return "read", None
    if kind == "argument_list":
        return _argument_use(source, parent)
    if kind in ("pointer_expression", "update_expression"):
        return "unknown", None  # &topic
    if kind == "binary_expression":
        operator = parent.child_by_field_name("operator")
        if operator is not None and source.text(operator) == ">>":
            return "unknown", None  # stream >> topic
        return "read", None
    if kind == "lambda_capture_specifier":
        return _capture(occurrence)
    if kind == "lambda_capture_initializer":
        if is_field(parent, "right", target) and parent.children[0].type != "&":
            return "read", None  # [name = topic]: a copy
        return "unknown", None
    if kind in ("for_range_loop", "structured_binding_declarator"):
        return "unknown", None  # bound by reference here
    if kind in ("reference_declarator", "pointer_declarator", "array_declarator"):
        return "unknown", None  # a declaration we do not follow (std::string& topic = ...)
    if kind in ("parameter_declaration", "optional_parameter_declaration"):
        return "unknown", None  # a parameter: its value comes from the caller
    return "read", None


def _capture(occurrence: Node) -> tuple[str, Node | None]:
    """``[topic]`` copies the string into the lambda; ``[&topic]`` lets it write."""
    previous = occurrence.prev_sibling
    return ("unknown", None) if previous is not None and previous.type == "&" else ("read", None)


def _method_use(source: Source, field_expression: Node) -> tuple[str, Node | None]:
    method = field_expression.child_by_field_name("field")
    call = field_expression.parent
    if call is None or call.type != "call_expression":
        return "read", None
    if method is not None and source.text(method) in _READING_METHODS:
        return "read", None
    return "unknown", None  # topic.append("/raw"), topic.swap(other)


def _argument_use(source: Source, arguments: Node) -> tuple[str, Node | None]:
    holder = arguments.parent
    if holder is None:
        return "unknown", None
    if holder.type == "init_declarator":
        declarator = holder.child_by_field_name("declarator")
        if declarator is not None and declarator.type == "identifier":
            return "read", None  # copied into a new object: ros::NodeHandle nh(ns)
        return "unknown", None
    if holder.type != "call_expression":
        return "unknown", None
    callee = holder.child_by_field_name("function")
    if callee is None:
        return "unknown", None
    name = compact(source.text(callee)).partition("<")[0]  # nh.advertise<std_msgs::String>
    last = name.rpartition("::")[2].rpartition(".")[2].rpartition("->")[2]
    if last in _READING_CALLS or name.startswith(_LOGGING_PREFIXES):
        return "read", None
    return "unknown", None


def statement_holding(
    node: Node, function: Node, holders: frozenset[str] = _STATEMENT_PARENTS
) -> Node | None:
    """The statement of ``function``'s blocks (``holders``: the node types whose children
    are statements) that holds ``node``; None for anything outside them."""
    child, parent = node, node.parent
    while parent is not None and parent != function:
        if parent.type in holders:
            return child
        child, parent = parent, parent.parent
    return None


def _shares_loop(write: Write, use: Node, function: Node) -> bool:
    node = use.parent
    while node is not None and node != function:
        if node.type in _LOOPS and contains(node, write.occurrence):
            return True
        node = node.parent
    return False
