"""Which variable or member holds which node handle, and the namespace it gives names.

``ros::NodeHandle pnh("~")`` makes ``pnh.param("rate", ...)`` the private ``~rate``;
``ros::NodeHandle arm(nh, "arm")`` puts ``arm.advertise("cmd", 1)`` in ``<nh's ns>/arm``;
``rclcpp::Node::make_shared("driver", "left")`` puts the node in ``left``. The namespace is
recorded on each name used through the handle (``NameUse.namespace``) as the code wrote
it: relative, private (``~``) or absolute; ``None`` when the handle is the default one or
cannot be known.
"""

from __future__ import annotations

from dataclasses import dataclass

from tree_sitter import Node

from .objects import (
    PRIVATE_HANDLE_GETTERS,
    Classes,
    Construction,
    Form,
    binding_of,
    is_member_declaration,
    variable_name,
)
from .source import Source, enclosing_functions, unparenthesized
from .values import Folder

_MAX_DEPTH = 8  # handles built from handles; also stops cycles in broken code
# The API named on the namespace of ``ros::NodeHandle(parent, ns)``: roscpp validates
# that namespace only joined to the parent's (absolute) one, so rules judge it apart from
# ``ros::NodeHandle(ns)``'s, which roscpp validates alone (RN101).
CHILD_HANDLE_API = "ros::NodeHandle(parent, ns)"


@dataclass(frozen=True)
class Binding:
    name: str
    function: Node | None  # the function a local lives in; None for members and globals
    start: int
    construction: Construction | None  # None for a fixed namespace (a private getter)
    fixed: str | None = None
    declaration: bool = False  # the class's own declaration of a member


def join_namespace(parent: str | None, child: str) -> str:
    """roscpp's ``names::append`` for a handle's namespace, kept symbolic (``~/arm``)."""
    if child.startswith("/") or not parent:
        return child
    if not child:
        return parent
    return f"{parent.rstrip('/')}/{child}"


class Handles:
    """The handles of one file and the namespaces they carry."""

    def __init__(
        self,
        source: Source,
        folder: Folder,
        classes: Classes,
        constructions: list[Construction],
    ) -> None:
        self._source = source
        self._folder = folder
        self._classes = classes
        self._bindings: dict[str, list[Binding]] = {}
        self._temporaries: dict[Node, Construction] = {}
        for construction in constructions:
            if self.is_handle(construction):
                self._add(construction)
        self._add_private_getters()
        self._add_private_initializers()

    def is_handle(self, construction: Construction) -> bool:
        if construction.type_name == "NodeHandle":
            return True
        name, qualifier = construction.type_name, construction.qualifier
        return name in ("Node", "LifecycleNode") and self._classes.accepts_node_base(
            name, qualifier
        )

    def namespace_of(self, receiver: Node | None, depth: int = 0) -> str | None:
        """The namespace of the handle an expression denotes, when the file says it."""
        if receiver is None or depth > _MAX_DEPTH:
            return None
        node = unparenthesized(receiver)
        if node.type == "call_expression":
            construction = self._temporaries.get(node)
            if construction is not None:
                return self.namespace(construction, depth + 1)
            callee = node.child_by_field_name("function")
            if callee is not None and self._source.text(callee) in PRIVATE_HANDLE_GETTERS:
                return "~"
            return None
        name = variable_name(self._source, node)
        if name is None:
            return None
        namespaces = {self._namespace(binding, depth + 1) for binding in self._visible(name, node)}
        return namespaces.pop() if len(namespaces) == 1 else None

    def is_handle_expression(self, node: Node) -> bool:
        """A handle or node passed as an argument: ``nh``, ``*this``, ``node_``..."""
        node = unparenthesized(node)
        if node.type == "this" or self._source.text(node) == "*this":
            return True
        name = variable_name(self._source, node)
        return name is not None and bool(self._bindings.get(name))

    def namespace(self, construction: Construction, depth: int = 0) -> str | None:
        """The namespace a handle construction gives: ``("ns")``, ``(parent, "ns")``."""
        values = construction.arguments
        if construction.type_name != "NodeHandle":
            second = self._folder.static(values[1]) if len(values) > 1 else None
            return second  # rclcpp::Node(name, namespace, options)
        if not values:
            initializer = construction.initializer  # `ros::NodeHandle nh = other;`
            if initializer is None:
                return ""  # a default handle is in the node's own namespace
            return self.namespace_of(initializer, depth + 1)
        first = self._folder.fold(values[0])
        if not first.dynamic:
            return first.text  # NodeHandle(ns) and NodeHandle(ns, remappings)
        parent = self.namespace_of(values[0], depth + 1)
        if len(values) == 1:
            return parent  # a copy of another handle
        child = self._folder.static(values[1])
        return None if child is None else join_namespace(parent, child)

    def parent_namespace(self, construction: Construction) -> str | None:
        """For ``NodeHandle(parent, "ns")``: the parent's namespace, that "ns" is inside."""
        values = construction.arguments
        if construction.type_name != "NodeHandle" or len(values) < 2:
            return None
        return self.namespace_of(values[0])

    def _namespace(self, binding: Binding, depth: int) -> str | None:
        if binding.construction is None:
            return binding.fixed
        return self.namespace(binding.construction, depth)

    def _visible(self, name: str, use: Node) -> list[Binding]:
        bindings = self._bindings.get(name, [])
        for function in enclosing_functions(use):
            local = [b for b in bindings if b.function == function and b.start < use.start_byte]
            if local:
                return local[-1:]
        shared = [binding for binding in bindings if binding.function is None]
        # A constructor's `pnh_("~")` or an assignment overrides the member's declaration.
        assigned = [b for b in shared if b.construction is None or not b.declaration]
        return assigned or shared

    def _add(self, construction: Construction) -> None:
        if construction.form is Form.TEMPORARY:
            self._temporaries[construction.site] = construction
        if construction.binding is None:
            return
        self._bind(construction.binding, construction.site, construction, None)

    def _bind(
        self, name: str, site: Node, construction: Construction | None, fixed: str | None
    ) -> None:
        functions = enclosing_functions(site)
        local = functions and _declares_local(site, construction)
        declaration = construction is not None and is_member_declaration(construction)
        function = functions[0] if local else None
        binding = Binding(name, function, site.start_byte, construction, fixed, declaration)
        self._bindings.setdefault(name, []).append(binding)

    def _add_private_getters(self) -> None:
        """nodelet's ``getPrivateNodeHandle()`` is the nodelet's private ``~`` handle."""
        for getter in PRIVATE_HANDLE_GETTERS:
            for word in self._source.occurrences(getter):
                call = word.parent
                if call is None or call.type != "call_expression":
                    continue
                name = binding_of(self._source, call)
                if name is not None:
                    self._bind(name, call, None, "~")

    def _add_private_initializers(self) -> None:
        """``private_nh_("~")`` in a constructor whose class is declared in a header."""
        for node in self._source.literals('"~"'):
            initializer = node.parent.parent if node.parent is not None else None
            if initializer is None or initializer.type != "field_initializer":
                continue
            member = self._source.text(initializer.named_children[0])
            if member not in self._bindings:
                self._bind(member, initializer, None, "~")


def _declares_local(site: Node, construction: Construction | None) -> bool:
    """A declaration in a function binds a local; assignments and initializers a member."""
    if construction is not None and construction.form is Form.OBJECT:
        return True
    parent = site.parent
    return parent is not None and parent.type == "init_declarator"
