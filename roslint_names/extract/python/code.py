"""rospy, actionlib, rclpy and tf code: the names a node uses, and RN301's events.

Calls are recognised by what their callee resolves to through the file's imports
(``import rospy as rp`` makes ``rp.Publisher`` rospy's), never by spelling alone. Two
exceptions, because the receiver's type is not in the file: rclpy's node methods
(``self.create_publisher``, ``node.create_publisher``, ``self.node.declare_parameter``...)
count on any receiver in rclpy code (a ROS 2 file, or one importing rclpy) when the
arguments have the method's shape; and tf's lookup methods (``buffer.lookup_transform``,
``listener.lookupTransform``) count on any receiver, since their names are tf's own.

Names inside ``with pytest.raises(...)`` / ``self.assertRaises(...)`` are skipped: they
are meant to be wrong (rclpy's own tests feed ``create_publisher`` illegal names there).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import libcst as cst

from roslint_names.extract.launch.common import is_frame_parameter
from roslint_names.extract.launch.substitution import Value
from roslint_names.extract.python.apis import (
    ACTIONLIB,
    DECLARE_PARAMETERS,
    GET_PARAMETERS,
    MESSAGE_FILTERS,
    NODE_CLASSES,
    NODE_FACTORIES,
    PARAMETER_ACCESS,
    RCLPY,
    RCLPY_ALIASES,
    RCLPY_METHODS,
    ROSPY,
    SEND_TRANSFORM,
    TF_METHODS,
    Api,
    Arg,
    Use,
    arg,
    argument,
    is_frame_field,
    positional_count,
)
from roslint_names.extract.python.attributes import InstanceAttributes
from roslint_names.extract.python.fold import Folder
from roslint_names.extract.python.scope import AssignSite, CallSite, ClassSite, Scope
from roslint_names.extract.python.spans import Locator, Where
from roslint_names.extract.python.walk import Walk
from roslint_names.model import (
    EventKind,
    Generation,
    Kind,
    NameUse,
    ParameterAccess,
    Role,
    RuntimeEvent,
)


@dataclass(frozen=True)
class Resolved:
    """A call recognised as an API; ``shift`` skips ``self`` in ``Node.__init__(self, ...)``."""

    api: Api
    shift: int = 0

    def argument(self, call: cst.Call, where: Arg | None) -> cst.BaseExpression | None:
        if where is None:
            return None
        if self.shift and where.position is not None:
            where = Arg(where.position + self.shift, where.keywords)
        return argument(call, where)


class CodeExtractor:
    """Names and events of rospy/rclpy code, from one ``Walk``."""

    def __init__(self, walk: Walk, locator: Locator, generation: Generation) -> None:
        self.walk = walk
        self.locator = locator
        attributes = InstanceAttributes.of(
            walk.classes, walk.assignments, walk.other_attribute_writes
        )
        self.folder = Folder(locator, attributes)
        self.rclpy_code = generation is Generation.ROS2 or _imports(walk.root, "rclpy")
        self.node_classes = _node_classes(walk.classes)
        self.names: list[NameUse] = []
        self.events: list[RuntimeEvent] = []
        self._emitted: set[tuple[int, Kind, Role]] = set()

    def run(self) -> None:
        for site in self.walk.calls:
            if not site.context.expected_failure:
                self.call(site)
        for assignment in self.walk.assignments:
            if not assignment.context.expected_failure:
                self.frame_assignment(assignment)
        self.propagate_inits()

    def propagate_inits(self) -> None:
        """A call of a function that initialises the runtime initialises it at the call:
        ``if __name__ == "__main__": main()`` runs ``rospy.init_node`` on that line, after
        the module-level code above it (and the code that imports the module)."""
        initialising: dict[str, str] = {}  # scope key -> the init it runs
        for event in self.events:
            if event.kind is EventKind.INIT:
                initialising.setdefault(event.scope, event.api)
        calls = [(site, callee) for site in self.walk.calls if (callee := self.callee(site))]
        reached: set[int] = set()
        while True:
            found = [
                (site, callee)
                for site, callee in calls
                if callee.key in initialising and id(site.call) not in reached
            ]
            if not found:
                return
            for site, callee in found:
                reached.add(id(site.call))
                init = initialising[callee.key]
                api = f"{init} (in {callee.name.rpartition('.')[2]}())"
                span = self.locator.head_span(_in_call(site), site.call.func)
                key = site.context.scope.key
                self.events.append(RuntimeEvent(EventKind.INIT, api, span, key, site.order))
                initialising.setdefault(key, init)

    def callee(self, site: CallSite) -> Scope | None:
        """The scope of the file's function a call calls by name, if it is one."""
        func = site.call.func  # by type, not isinstance (an ABC's, slow): asked per call
        if type(func) is not cst.Name or site.context.expected_failure:
            return None
        bindings = site.context.scope.lookup(func.value)
        defined = bindings[0].defined if len(bindings) == 1 else None
        if type(defined) is cst.FunctionDef:
            return self.walk.function_scopes.get(defined)
        return None

    # -- calls --------------------------------------------------------------------------

    def call(self, site: CallSite) -> None:
        resolved = self.resolve(site)
        if resolved is not None:
            self.api_call(site, resolved)
        self.frame_arguments(site)
        func = site.call.func
        if isinstance(func, cst.Attribute):
            self.method_call(site, func.attr.value)

    def resolve(self, site: CallSite) -> Resolved | None:
        call, scope = site.call, site.context.scope
        super_init = self.super_init(site)
        if super_init is not None:
            return super_init
        for name in scope.qualified(call.func):
            found = _known_api(name, self.rclpy_code)
            if found is not None:
                return Resolved(found)
        node_class = self.instantiated_node_class(call.func, scope)
        if node_class is not None:
            api = f"{node_class.name.value} (an rclpy Node)"
            return Resolved(Api(api, None, event=EventKind.HANDLE))
        return None

    def super_init(self, site: CallSite) -> Resolved | None:
        """``super().__init__("talker")`` in a Node subclass names the node, as does
        ``Node.__init__(self, "talker")``; neither creates a node RN301 should order."""
        func = site.call.func
        if not isinstance(func, cst.Attribute) or func.attr.value != "__init__":
            return None
        naming = replace(RCLPY["rclpy.node.Node"], event=None)
        owner = site.context.scope.owner
        if _is_super(func.value) and owner is not None and self.inherits_node_init(owner):
            return Resolved(naming)
        if any(name in NODE_CLASSES for name in site.context.scope.qualified(func.value)):
            return Resolved(naming, shift=1)
        return None

    def inherits_node_init(self, node: cst.ClassDef) -> bool:
        """Whether ``super().__init__`` in ``node`` reaches rclpy's ``Node.__init__``: its
        first node base is rclpy's, or one of the file's that keeps that ``__init__``."""
        site = self.node_classes.get(node)
        base = None if site is None else _node_base(site, self.node_classes)
        if base is None or isinstance(base, str):
            return base is not None
        return not _defines(base.node, "__init__") and self.inherits_node_init(base.node)

    def instantiated_node_class(
        self, func: cst.BaseExpression, scope: Scope
    ) -> cst.ClassDef | None:
        if not isinstance(func, cst.Name):
            return None
        for binding in scope.lookup(func.value):
            if isinstance(binding.defined, cst.ClassDef) and binding.defined in self.node_classes:
                return binding.defined
        return None

    def api_call(self, site: CallSite, resolved: Resolved) -> None:
        api = resolved.api
        value = self.api_name(site, resolved)
        if api.event is not None and (not api.private_only or (value or "").startswith("~")):
            span = self.locator.head_span(_in_call(site), site.call.func)
            key = site.context.scope.key
            self.events.append(RuntimeEvent(api.event, api.api, span, key, site.order))
        if api.api in NODE_FACTORIES:
            namespace = argument(site.call, arg(":namespace"))
            if namespace is not None:
                self.emit(site, namespace, Use(Kind.NAMESPACE, Role.NAMESPACE, api.api))
        if value is not None:
            self.parameter_default(site, value, resolved.argument(site.call, api.default))

    def api_name(self, site: CallSite, resolved: Resolved) -> str | None:
        """Emit the name a recognised call takes, with its type; its static value."""
        api, call = resolved.api, site.call
        name = resolved.argument(call, api.name)
        if api.use is None or name is None or not _may_hold_name(name):
            return None
        type_expr = resolved.argument(call, api.type)
        scope = site.context.scope
        type_name = None if type_expr is None else self.type_name(type_expr, scope, api.use.kind)
        return self.emit(site, name, api.use, type_name)

    def method_call(self, site: CallSite, method: str) -> None:
        call, scope = site.call, site.context.scope
        if method in TF_METHODS:
            for where in TF_METHODS[method]:
                self.frame(site, argument(call, where), f"tf {method}", allow_empty=False)
        elif method == "sendTransform" and positional_count(call) >= 5:
            for where in SEND_TRANSFORM:
                self.frame(site, argument(call, where), "tf sendTransform", allow_empty=False)
        if not self.rclpy_code or scope.qualified(call.func):
            return  # a resolved callee (rospy.get_param...) is no node method
        if method in RCLPY_METHODS:
            self.rclpy_method(site, RCLPY_METHODS[method])
        elif method == "get_parameters":
            self.parameter_list(site)
        elif method == "declare_parameters":
            self.declare_parameters(site)

    def rclpy_method(self, site: CallSite, api: Api) -> None:
        """A node method, when its arguments have rclpy's shape: a type first, then a name
        (never a literal number, list or lambda)."""
        call = site.call
        name = argument(call, api.name) if api.name else None
        use = api.use
        if use is None or name is None or not _may_hold_name(name):
            return
        if use.kind is Kind.PARAMETER and _through_client(call):
            use = replace(use, access=ParameterAccess.REMOTE)
        type_name = None
        if api.type is not None:
            type_expr = argument(call, api.type)
            if type_expr is None or not _may_be_type(type_expr):
                return
            type_name = self.type_name(type_expr, site.context.scope, use.kind)
        value = self.emit(site, name, use, type_name)
        if value is not None and api.default is not None:
            self.parameter_default(site, value, argument(call, api.default))

    def parameter_list(self, site: CallSite) -> None:
        """``get_parameters(["a", "b"])``."""
        names = argument(site.call, arg("0:names"))
        if isinstance(names, cst.List | cst.Tuple):
            use = Use(Kind.PARAMETER, Role.PARAMETER, GET_PARAMETERS)
            if _through_client(site.call):
                use = replace(use, access=ParameterAccess.REMOTE)
            for element in names.elements:
                if _may_hold_name(element.value):
                    self.emit(site, element.value, use)

    def declare_parameters(self, site: CallSite) -> None:
        """``declare_parameters(namespace, [(name, value), ...])`` declares ``namespace.name``."""
        call, scope = site.call, site.context.scope
        namespace = argument(call, arg("0:namespace"))
        parameters = argument(call, arg("1:parameters"))
        if namespace is None or not isinstance(parameters, cst.List | cst.Tuple):
            return
        prefix = self.folder.static(namespace, scope)
        use = Use(Kind.PARAMETER, Role.PARAMETER, DECLARE_PARAMETERS)
        for element in parameters.elements:
            entry = element.value
            if not isinstance(entry, cst.Tuple) or not entry.elements:
                continue
            name = entry.elements[0].value
            value = self.folder.value(name, scope)
            if prefix is None:
                value = Value(self.locator.code(name), dynamic=True)
            elif prefix and not value.dynamic:
                value = Value(f"{prefix}.{value.text}")
            self.add(site.where(name), use, value)
            if len(entry.elements) > 1 and not value.dynamic:
                self.parameter_default(site, value.text, entry.elements[1].value)

    # -- frames -------------------------------------------------------------------------

    def frame_arguments(self, site: CallSite) -> None:
        """``Header(frame_id="map")``, ``TransformStamped(child_frame_id=...)``."""
        for item in site.call.args:
            if item.keyword is not None and is_frame_field(item.keyword.value):
                self.frame(site, item.value, f"{item.keyword.value}=", allow_empty=True)

    def frame_assignment(self, site: AssignSite) -> None:
        """``msg.header.frame_id = "map"``, ``t.child_frame_id = "base_link"``."""
        attribute = site.target.attr.value
        if not is_frame_field(attribute):
            return
        value = self.folder.value(site.value, site.context.scope)
        if value.dynamic or not value.text:
            return  # an empty frame id in a message means "no frame": legal
        use = Use(Kind.FRAME, Role.FRAME, f".{attribute} =")
        self.add(site.context.where(site.value), use, value)

    def frame(
        self, site: CallSite, expr: cst.BaseExpression | None, api: str, *, allow_empty: bool
    ) -> None:
        """A frame id argument; ``allow_empty`` where "" legally means "no frame"."""
        if expr is None:
            return
        value = self.folder.value(expr, site.context.scope)
        if value.dynamic or (allow_empty and not value.text):
            return
        self.add(site.where(expr), Use(Kind.FRAME, Role.FRAME, api), value)

    def parameter_default(
        self, site: CallSite, parameter: str, default: cst.BaseExpression | None
    ) -> None:
        """A frame-like parameter's default (``get_param("~frame_id", "map")``) is a frame."""
        if default is not None and is_frame_parameter(parameter):
            self.frame(site, default, "parameter default", allow_empty=True)

    # -- facts --------------------------------------------------------------------------

    def emit(
        self, site: CallSite, expr: cst.BaseExpression, use: Use, type_name: str | None = None
    ) -> str | None:
        """Emit the name an argument holds; its static value, or None when dynamic."""
        scope = site.context.scope
        value = self.folder.value(expr, scope, at=site.context)
        prefix = self.folder.absolute_prefix(expr, scope) if value.dynamic else None
        suffix = None
        if value.dynamic and use.kind is Kind.PARAMETER:
            suffix = self.folder.suffix(expr, scope)
        self.add(site.where(expr), use, value, type_name, prefix, suffix=suffix)
        return None if value.dynamic else value.text

    def add(
        self,
        where: Where,
        use: Use,
        value: Value,
        type_name: str | None = None,
        absolute_prefix: str | None = None,
        *,
        suffix: str | None = None,
    ) -> None:
        """One fact per node and kind: ``lookup_transform(target_frame="map")`` is both a
        tf lookup and a frame keyword."""
        if _access(use) is ParameterAccess.READ_PREFIX and not value.dynamic and not value.text:
            return  # ``get_parameters_by_prefix("")`` reads them all: it names none
        key = (id(where.node), use.kind, use.role)
        if key in self._emitted:
            return
        self._emitted.add(key)
        span = self.locator.span(where)
        self.names.append(
            NameUse(
                use.kind,
                value.text,
                span,
                use.role,
                use.api,
                value.dynamic,
                type_name,
                absolute_prefix=absolute_prefix,
                access=_access(use),
                suffix=suffix,
            )
        )

    def type_name(self, expr: cst.BaseExpression, scope: Scope, kind: Kind) -> str | None:
        """The type as the imports resolve it (``std_srvs.srv.SetBool``), else as spelled
        when nothing in the file binds it; None for a variable holding a type."""
        candidates = scope.qualified(expr)
        if len(candidates) == 1:
            return candidates[0]
        folder = _INTERFACE_FOLDERS.get(kind, "")
        matching = [name for name in candidates if f".{folder}." in name]
        if len(matching) == 1:
            return matching[0]
        if isinstance(expr, cst.Name) and (candidates or not scope.lookup(expr.value)):
            return expr.value
        return None


_INTERFACE_FOLDERS = {Kind.TOPIC: "msg", Kind.SERVICE: "srv", Kind.ACTION: "action"}


def _known_api(name: str, rclpy_code: bool) -> Api | None:
    head, _, rest = name.partition(".")
    last = name.rpartition(".")[2]
    if head == "message_filters" and rest:
        return MESSAGE_FILTERS["ros2" if rclpy_code else "ros1"].get(f"message_filters.{last}")
    if head == "rospy" and rest:
        return ROSPY.get(last)
    if head == "actionlib" and rest:
        return ACTIONLIB.get(last)
    if head == "rclpy":
        return RCLPY.get(RCLPY_ALIASES.get(name, name))
    return None


def _in_call(site: CallSite) -> Where:
    return Where(site.call, site.context.anchors, site.context.indents)


def _is_super(expr: cst.BaseExpression) -> bool:
    return (
        isinstance(expr, cst.Call)
        and isinstance(expr.func, cst.Name)
        and expr.func.value == "super"
    )


_NOT_A_NAME = (cst.Integer, cst.Float, cst.Imaginary, cst.Lambda, cst.List, cst.Dict, cst.Tuple)


def _may_hold_name(expr: cst.BaseExpression) -> bool:
    """Whether an argument may hold a name: not a number, list, lambda or ``None``."""
    if isinstance(expr, cst.Name):
        return expr.value not in ("None", "True", "False")
    return not isinstance(expr, _NOT_A_NAME)


def _may_be_type(expr: cst.BaseExpression) -> bool:
    """A message or service type is a class: a name, an attribute or a call returning one
    (``get_message(...)``), never a string."""
    return isinstance(expr, cst.Name | cst.Attribute | cst.Call | cst.Subscript)


def _defines(node: cst.ClassDef, method: str) -> bool:
    body = node.body.body if isinstance(node.body, cst.IndentedBlock) else ()
    return any(
        isinstance(statement, cst.FunctionDef) and statement.name.value == method
        for statement in body
    )


def _imports(scope: Scope, package: str) -> bool:
    """Whether the module imports ``package`` (or one of its modules) anywhere at its top."""
    imported = (
        binding.imported
        for bindings in scope.bindings.values()
        for binding in bindings
        if binding.imported
    )
    modules = (*imported, *scope.star_imports)
    return any(module.split(".", 1)[0] == package for module in modules)


def _node_classes(classes: Sequence[ClassSite]) -> dict[cst.ClassDef, ClassSite]:
    """The file's classes deriving from an rclpy Node, directly or through each other."""
    found: dict[cst.ClassDef, ClassSite] = {}
    changed = True
    while changed:
        changed = False
        for site in classes:
            if site.node not in found and _node_base(site, found) is not None:
                found[site.node] = site
                changed = True
    return found


def _node_base(site: ClassSite, known: dict[cst.ClassDef, ClassSite]) -> ClassSite | str | None:
    """The first base that is a node: rclpy's qualified name, one of the file's node
    classes, or None."""
    for base in site.node.bases:
        for name in site.scope.qualified(base.value):
            if name in NODE_CLASSES:
                return name
        if isinstance(base.value, cst.Name):
            for binding in site.scope.lookup(base.value.value):
                if isinstance(binding.defined, cst.ClassDef) and binding.defined in known:
                    return known[binding.defined]
    return None


def _access(use: Use) -> ParameterAccess | None:
    if use.kind is not Kind.PARAMETER or use.role is not Role.PARAMETER:
        return None
    return use.access or PARAMETER_ACCESS.get(use.api)


def _through_client(call: cst.Call) -> bool:
    """``client.get_parameters(["a"])`` on an rclpy ``AsyncParameterClient`` (or a
    hand-made parameter service client) asks another node: not this node's parameter."""
    func = call.func
    if not isinstance(func, cst.Attribute):
        return False
    receiver = func.value
    while isinstance(receiver, cst.Attribute):
        if "client" in receiver.attr.value.lower():
            return True
        receiver = receiver.value
    return isinstance(receiver, cst.Name) and "client" in receiver.value.lower()
