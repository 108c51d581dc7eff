"""RN301's facts: ``ros::init``/``rclcpp::init`` calls and the constructions that need them.

A construction needs the runtime when it builds a ``ros::NodeHandle``, an ``rclcpp::Node``
or ``LifecycleNode``, a node class of the file, a class of the file holding a
``ros::NodeHandle`` member, or an actionlib client or server (each holds a NodeHandle).
Members are built with their object, so they are not events of their own; their class is.
Pointer and reference declarations build nothing.
"""

from __future__ import annotations

from tree_sitter import Node

from roslint_names.model import EventKind, RuntimeEvent

from .apis import ACTIONLIB
from .objects import NODE_BASES, Classes, Construction, Form
from .source import Source, call_named_by, enclosing_functions

INIT_FUNCTIONS = {
    ("ros", "init"): "ros::init",
    ("rclcpp", "init"): "rclcpp::init",
    ("rclcpp", "init_and_remove_ros_arguments"): "rclcpp::init_and_remove_ros_arguments",
}
INIT_WORDS = frozenset(name for _, name in INIT_FUNCTIONS)


def scope_key(source: Source, node: Node) -> str:
    """``"main@12"``: the function (or lambda) ``node`` runs in; ``""`` at namespace scope."""
    functions = enclosing_functions(node)
    if not functions:
        return ""
    function = functions[0]
    line = source.line(function)
    if function.type == "lambda_expression":
        return f"lambda@{line}:{source.span(function).column}"
    if function.type != "function_definition":
        return f"block@{line}"  # the body of a macro-defined function (TEST_F)
    declarator = function.child_by_field_name("declarator")
    while declarator is not None and declarator.type != "function_declarator":
        declarator = declarator.child_by_field_name("declarator")
    inner = None if declarator is None else declarator.child_by_field_name("declarator")
    name = "function" if inner is None else source.text(inner)
    return f"{name}@{line}"


def init_event(source: Source, word: Node) -> RuntimeEvent | None:
    call = call_named_by(source, word)
    if call is None:
        return None
    api = INIT_FUNCTIONS.get((call.qualifier, call.name))
    if api is None:
        return None
    return RuntimeEvent(
        kind=EventKind.INIT,
        api=api,
        span=source.span(call.node),
        scope=scope_key(source, call.node),
        order=call.node.start_byte,
    )


def handle_event(
    source: Source, classes: Classes, construction: Construction
) -> RuntimeEvent | None:
    if construction.form in (Form.MEMBER, Form.ARGUMENT):
        return None
    api = _handle_api(classes, construction)
    if api is None:
        return None
    site = construction.site
    return RuntimeEvent(
        kind=EventKind.HANDLE,
        api=api,
        span=source.span(site),
        scope="" if construction.static_storage else scope_key(source, site),
        order=site.start_byte,
        static_storage=construction.static_storage,
    )


def _handle_api(classes: Classes, construction: Construction) -> str | None:
    """How a message names what was built, or None when it needs no runtime."""
    name, qualifier = construction.type_name, construction.qualifier
    if name == "NodeHandle":
        return "ros::NodeHandle"
    if name in NODE_BASES and classes.accepts_node_base(name, qualifier):
        return f"{qualifier}::{name}" if qualifier else NODE_BASES[name]
    if qualifier == "" and name in classes.nodes:
        return f"{name} (an {classes.nodes[name]})"
    if qualifier == "" and name in classes.holders:
        return f"{name} (holds a ros::NodeHandle)"
    if name in ACTIONLIB and qualifier == "actionlib":
        return f"actionlib::{name} (holds a ros::NodeHandle)"
    return None
