"""The name sites of roscpp and rclcpp: which call or construction takes which name.

Each site reads the argument that holds the name (folded to its static text, or marked
dynamic), the kind and role of the name, the interface type when the code says it, and
the namespace of the handle the call goes through. Only whole arguments are names: in
``nh.advertise<T>(prefix + "cmd", 1)`` neither ``prefix`` nor ``"cmd"`` is one.
"""

from __future__ import annotations

import re

from tree_sitter import Node

from roslint_names.model import Kind, NameUse, ParameterAccess, Role

from .apis import (
    ACTION_FUNCTIONS,
    ACTIONLIB,
    ACTIONLIB_QUALIFIERS,
    CAMERA_ENDPOINTS,
    DECLARE_OR_GET,
    DECLARE_OR_GET_API,
    DECLARE_PARAMETERS,
    DECLARE_PARAMETERS_API,
    ENDPOINTS,
    FRAME_CONSTRUCTIONS,
    FRAME_FUNCTIONS,
    GET_PARAMETERS,
    GET_PARAMETERS_API,
    MAX_FRAME_ARGUMENTS,
    OPTIONS,
    OPTIONS_USERS,
    PLUGIN_TYPE,
    PLUGIN_TYPE_API,
    PLUGIN_TYPE_SUFFIX,
    ROS1_PARAMETER_FUNCTIONS,
    ROS1_PARAMETERS,
    ROS2_PARAMETERS,
    SENT_FRAME_FIELD,
    SERVICE_FUNCTIONS,
    SERVICE_WRAPPERS,
    WAIT_FOR_MESSAGE,
    Endpoint,
    ParameterSite,
    value_fact,
)
from .handles import CHILD_HANDLE_API, Handles
from .objects import NODE_BASES, Classes, Construction, variable_name
from .source import (
    Call,
    Source,
    arguments,
    call_named_by,
    compact,
    contains,
    enclosing_functions,
    field_root,
    is_field,
    template_types,
    unparenthesized,
)
from .types import Types
from .values import Folder, Value
from .variables import statement_holding


class Sites:
    """Collects the ``NameUse`` facts of one file."""

    def __init__(
        self,
        source: Source,
        folder: Folder,
        classes: Classes,
        handles: Handles,
        types: Types,
    ) -> None:
        self.source = source
        self.folder = folder
        self.classes = classes
        self.handles = handles
        self.types = types
        self.names: list[NameUse] = []
        self._clients: frozenset[str] | None = None  # ``_parameter_clients``, once asked

    # -- emitting -----------------------------------------------------------------------

    def emit(
        self,
        kind: Kind,
        role: Role,
        api: str,
        value: Value | None,
        type_name: str | None = None,
        *,
        namespace: str | None = None,
        access: ParameterAccess | None = None,
    ) -> None:
        if value is None:
            return
        parameter = kind is Kind.PARAMETER and role is Role.PARAMETER
        if parameter and value.dynamic and _implements_declaring_api(self.source, value.node):
            access = None  # the API's own body: its callers' names are what it declares
        self.names.append(
            NameUse(
                kind=kind,
                value=value.text,
                span=self.source.span(value.node),
                role=role,
                api=api,
                dynamic=value.dynamic,
                type_name=type_name,
                namespace=namespace,
                symbol=value.symbol,
                absolute_prefix=value.prefix if value.dynamic else None,
                access=access if parameter else None,
                suffix=value.suffix if parameter and value.dynamic else None,
            )
        )

    def argument(self, values: tuple[Node, ...], index: int) -> Value | None:
        return self.folder.fold(values[index]) if 0 <= index < len(values) else None

    def static_argument(self, values: tuple[Node, ...], index: int) -> Value | None:
        value = self.argument(values, index)
        return None if value is None or value.dynamic else value

    # -- calls --------------------------------------------------------------------------

    def call(self, word: str, node: Node) -> None:
        if word in OPTIONS:
            self.options_create(word, node)
            return
        if word in ("param", "service") and node.type == "namespace_identifier":
            node = _qualified_member(node) or node  # ros::param::get, ros::service::call
        call = call_named_by(self.source, node)
        if call is None:
            return
        if call.name == "init" and call.qualifier == "ros":
            self.ros_init(call)
        elif call.name == "init" and call.receiver is not None:
            self.options_init(call)
        elif _takes_options(self.folder, call):
            return  # nh.subscribe(ops): the name was read where ops got it
        elif call.qualifier.endswith("rclcpp_action") and call.name in ACTION_FUNCTIONS:
            self.action_function(call)
        elif call.name in ENDPOINTS:
            self.endpoint(call, ENDPOINTS[call.name])
        elif call.name == "subscribe":
            self.subscribe(call)
        elif call.name == "create_sub_node":
            self.sub_node(call)
        elif (
            call.name in WAIT_FOR_MESSAGE
            and call.receiver is None
            and call.qualifier.endswith(WAIT_FOR_MESSAGE[call.name][0])
        ):
            _, index, api = WAIT_FOR_MESSAGE[call.name]
            value = self.argument(call.arguments, index)
            self.emit(Kind.TOPIC, Role.SUBSCRIBE, api, value, self._template_type(call))
        elif call.name == "advertiseService":
            self.advertise_service(call)
        elif call.qualifier.endswith("service") and call.name in SERVICE_FUNCTIONS:
            self.service_function(call)
        elif call.qualifier.endswith("param") and call.name in ROS1_PARAMETER_FUNCTIONS:
            self.parameter(call, ROS1_PARAMETER_FUNCTIONS[call.name])
        elif call.name in ROS1_PARAMETERS and call.receiver is not None:
            self.parameter(call, ROS1_PARAMETERS[call.name])
        elif call.name in ROS2_PARAMETERS:
            self.parameter(call, ROS2_PARAMETERS[call.name])
        elif call.name == DECLARE_OR_GET:
            self.declare_or_get(call)
        elif call.name == PLUGIN_TYPE and len(call.arguments) >= 2:
            self.plugin_type(call)
        elif call.name == DECLARE_PARAMETERS and call.qualifier == "":
            self.declare_parameters(call)
        elif call.name == GET_PARAMETERS and call.qualifier == "":
            self.get_parameters(call)
        elif call.name in FRAME_FUNCTIONS:
            self.frames(call)

    def ros_init(self, call: Call) -> None:
        """``ros::init(argc, argv, name[, options])`` or ``ros::init(remappings, name)``."""
        values = call.arguments
        index = 1 if self.static_argument(values, 1) is not None or len(values) == 2 else 2
        self.emit(Kind.NODE, Role.NODE_NAME, "ros::init", self.argument(values, index))

    def options_create(self, word: str, node: Node) -> None:
        """``ros::SubscribeOptions::create<M>("scan", 1, cb, tracked, &queue)``."""
        member = _qualified_member(node)
        call = None if member is None else call_named_by(self.source, member)
        if call is not None and call.name == "create":
            self.options(OPTIONS[word], call, _options_variable(call.node))

    def options_init(self, call: Call) -> None:
        """``ops.init<M>("scan", 1, cb)`` on a variable declared as an options object."""
        receiver = unparenthesized(call.receiver) if call.receiver is not None else None
        name = None if receiver is None else variable_name(self.source, receiver)
        if receiver is None or name is None:
            return
        declarations = self.folder.declarations.visible(name, receiver)
        declared = self.types.declared_type([declaration.node for declaration in declarations])
        site = OPTIONS.get((declared or "").rpartition("::")[2].partition("<")[0])
        if site is not None:
            self.options(site, call, receiver)

    def options(self, site: Endpoint, call: Call, variable: Node | None) -> None:
        """The name an options object carries, under the namespace of the handle that
        ``subscribe(ops)`` (or ``advertise``, ``advertiseService``) is called on."""
        types = template_types(self.source, call.template)
        # init<MReq, MRes> names a service's request and response, not the service
        type_name = self.types.resolve(types[0]) if len(types) == 1 else None
        namespace = None
        if variable is not None:
            namespaces = {self.handles.namespace_of(user) for user in self._options_users(variable)}
            namespace = namespaces.pop() if len(namespaces) == 1 else None
        api = f"{site.api}::{call.name}"
        value = self.argument(call.arguments, 0)
        self.emit(site.kind, site.role, api, value, type_name, namespace=namespace)

    def _options_users(self, variable: Node) -> list[Node]:
        """The handles ``variable`` (an options object, or the call making one) is handed to."""
        if variable.type == "call_expression":
            holders = [variable]
        else:
            name = variable_name(self.source, variable)
            functions = enclosing_functions(variable)
            holders = [
                occurrence
                for occurrence in self.source.occurrences(name or "")
                if not functions or contains(functions[-1], occurrence)
            ]
        users = []
        for holder in holders:
            call = _called_with(holder)
            if call is not None and call[0] in OPTIONS_USERS:
                users.append(call[1])
        return users

    def endpoint(self, call: Call, site: Endpoint) -> None:
        """A member call (``nh.advertise``, ``create_publisher``) or its free form
        (``rclcpp::create_publisher<T>(node, name, qos)``)."""
        free = call.receiver is None and _is_namespace(call.qualifier)
        index = self._name_after_node(call.arguments) if free else 0
        api = f"{call.qualifier}::{call.name}" if free else site.api
        type_name = self._template_type(call)
        if call.name.startswith("create_generic_"):
            generic = self.static_argument(call.arguments, index + 1)
            type_name = None if generic is None else generic.text
        namespace = self.handles.namespace_of(call.receiver)
        value = self.argument(call.arguments, index)
        if value is not None and value.dynamic and call.name in CAMERA_ENDPOINTS:
            # image_publisher resolves "image_raw" into a variable first: the literal is
            # the evidence RN404 reads, and an unknown use would silence it for the node.
            return
        self.emit(site.kind, site.role, api, value, type_name, namespace=namespace)

    def _name_after_node(self, values: tuple[Node, ...]) -> int:
        """Where a free function's name is: after the node, or after the node interfaces
        its other overloads take (``rclcpp::create_client<T>(node_base, node_graph,
        node_services, "name", ...)``): the first string among the next arguments."""
        for index in range(1, min(len(values), 5)):
            value = values[index]
            if self.folder.static(value) is not None or '"' in self.source.text(value):
                return index
        return 1

    def sub_node(self, call: Call) -> None:
        """``node->create_sub_node("sensors")``: a namespace below the node's."""
        value = self.argument(call.arguments, 0)
        self.emit(Kind.NAMESPACE, Role.NAMESPACE, "rclcpp::Node::create_sub_node", value)

    def action_function(self, call: Call) -> None:
        """``rclcpp_action::create_server<T>(node, name, ...)``; with node interfaces
        instead of a node, the name comes after four of them."""
        site = ACTION_FUNCTIONS[call.name]
        first = self.source.text(call.arguments[0]) if call.arguments else ""
        index = 4 if "interface" in first else 1
        value = self.argument(call.arguments, index)
        self.emit(site.kind, site.role, site.api, value, self._template_type(call))

    def subscribe(self, call: Call) -> None:
        """``nh.subscribe(name, queue, callback)``; message_filters' ``sub.subscribe(nh,
        name, queue)`` takes the handle first. A call of fewer arguments names no topic:
        roscpp's ``NodeHandle::subscribe`` takes a queue size and a callback after the
        name, or one ``SubscribeOptions`` (``options``); message_filters'
        ``Subscriber::subscribe()`` subscribes again to the topic it was given (ros/ros_comm
        ``node_handle.h``, ros2/message_filters ``subscriber.h``). Autoware's
        ``pointcloud_preprocessor::Filter::subscribe(filter_name)`` is its own."""
        values = call.arguments
        if len(values) < 2:
            return
        index = 0
        if self.folder.fold(values[0]).dynamic and (
            self.handles.is_handle_expression(values[0]) or not self.folder.fold(values[1]).dynamic
        ):
            index = 1
        api = "message_filters::Subscriber::subscribe" if index else "ros::NodeHandle::subscribe"
        type_name = self._template_type(call)
        if type_name is None and index == 0 and len(values) > 2:
            type_name = self.types.message_type(values[2])
        namespace = self.handles.namespace_of(call.receiver)
        value = self.argument(values, index)
        self.emit(Kind.TOPIC, Role.SUBSCRIBE, api, value, type_name, namespace=namespace)

    def advertise_service(self, call: Call) -> None:
        values = call.arguments
        type_name = self.types.service_type(values[1]) if len(values) > 1 else None
        namespace = self.handles.namespace_of(call.receiver)
        api = "ros::NodeHandle::advertiseService"
        value = self.argument(values, 0)
        self.emit(Kind.SERVICE, Role.SERVE, api, value, type_name, namespace=namespace)

    def service_function(self, call: Call) -> None:
        """``ros::service::call(name, srv)``: the type is the one ``srv`` is declared with."""
        api = f"ros::service::{call.name}"
        type_name = None
        if call.name == "call" and len(call.arguments) == 2:
            type_name = self._variable_type(call.arguments[1])
        self.emit(Kind.SERVICE, Role.CALL, api, self.argument(call.arguments, 0), type_name)

    def parameter(self, call: Call, site: ParameterSite) -> None:
        values = call.arguments
        if len(values) < site.minimum:
            return
        namespace = self.handles.namespace_of(call.receiver)
        name = self.argument(values, site.name)
        if name is not None and name.dynamic:
            name = self.folder.local_field(values[site.name]) or name
        access = site.access
        if site.quiet_from is not None and len(values) >= site.quiet_from:
            access = ParameterAccess.READ_QUIETLY
        access = self._parameter_access(call, access)
        self.emit(
            Kind.PARAMETER, Role.PARAMETER, site.api, name, namespace=namespace, access=access
        )
        if site.value is not None and name is not None and not name.dynamic:
            index = len(values) - 1 if site.value < 0 else site.value
            if index > site.name:
                self.parameter_value(name.text, values, index, site.api, namespace)

    def _parameter_access(
        self, call: Call, access: ParameterAccess | None
    ) -> ParameterAccess | None:
        """A ROS 2 read through a parameter client (``rclcpp::SyncParametersClient``,
        ``AsyncParametersClient``: ``client->get_parameters({"a"})``,
        ``client->get_parameter<T>("a", default)``) asks a node by service, whatever node
        it names: it reads no parameter of the calling node, and throws nothing."""
        receiver = call.receiver
        if receiver is None or access not in _READS_AND_CHECKS:
            return access
        spelled = self.source.text(receiver).lower()
        if "client" in spelled:
            return ParameterAccess.REMOTE
        if self._clients is None:
            self._clients = _parameter_clients(self.source)
        if not self._clients:
            return access
        name = variable_name(self.source, unparenthesized(receiver))
        return ParameterAccess.REMOTE if name in self._clients else access

    def declare_or_get(self, call: Call) -> None:
        """nav2's ``declare_or_get_parameter``: ``node->declare_or_get_parameter(name,
        default)``, ``nav2::declare_or_get_parameter(node, name, default)`` or
        ``(logger, interface, name, default)``: the name is the first string argument,
        else where its form puts it."""
        values = call.arguments
        if not values:
            return
        index = 0 if call.receiver is not None else None
        for candidate in range(min(len(values), 3)) if index is None else ():
            if self.folder.static(values[candidate]) is not None or '"' in self.source.text(
                values[candidate]
            ):
                index = candidate
                break
        if index is None:
            first = self.source.text(values[0]).lower()
            index = 2 if "logger" in first else 1 if call.qualifier or len(values) >= 3 else 0
        name = self.argument(values, index)
        access = ParameterAccess.DECLARE
        self.emit(Kind.PARAMETER, Role.PARAMETER, DECLARE_OR_GET_API, name, access=access)
        if name is not None and not name.dynamic and index + 1 < len(values):
            self.parameter_value(name.text, values, index + 1, DECLARE_OR_GET_API, None)

    def plugin_type(self, call: Call) -> None:
        """nav2's ``get_plugin_type_param(node, plugin)`` declares ``plugin.plugin``."""
        name = self.argument(call.arguments, 1)
        if name is None:
            return
        if name.dynamic:
            name = Value(name.text, True, name.node, suffix=PLUGIN_TYPE_SUFFIX)
        else:
            name = Value(name.text + PLUGIN_TYPE_SUFFIX, False, name.node)
        access = ParameterAccess.DECLARE
        self.emit(Kind.PARAMETER, Role.PARAMETER, PLUGIN_TYPE_API, name, access=access)

    def declare_parameters(self, call: Call) -> None:
        """``declare_parameters("ns", {{"a", 1}, {"b", 2}})`` declares ``ns.a`` and
        ``ns.b``; a map the call does not spell declares names the linter cannot know."""
        values = call.arguments
        if len(values) < 2:
            return
        namespace = self.folder.fold(values[0])
        entries = _initializer_entries(values[1])
        access = ParameterAccess.DECLARE
        if namespace.dynamic or entries is None:
            unknown = Value(compact(self.source.text(values[1])), True, values[1])
            api = DECLARE_PARAMETERS_API
            self.emit(Kind.PARAMETER, Role.PARAMETER, api, unknown, access=access)
            return
        for entry in entries:
            key = self.folder.fold(entry)
            if not key.dynamic and namespace.text:
                key = Value(f"{namespace.text}.{key.text}", False, key.node)
            self.emit(Kind.PARAMETER, Role.PARAMETER, DECLARE_PARAMETERS_API, key, access=access)

    def get_parameters(self, call: Call) -> None:
        """``get_parameters({"a", "b"})`` reads each name, throwing for an undeclared one;
        ``get_parameters("prefix", map)`` reads every parameter below ``prefix.``."""
        values = call.arguments
        if len(values) == 2:
            prefix = self.argument(values, 0)
            if prefix is not None and not prefix.dynamic and not prefix.text:
                return  # ``get_parameters("", map)`` reads them all: it names none
            access = self._parameter_access(call, ParameterAccess.READ_PREFIX)
            self.emit(Kind.PARAMETER, Role.PARAMETER, GET_PARAMETERS_API, prefix, access=access)
            return
        names = _initializer_items(values[0]) if len(values) == 1 else None
        if names is None:
            return  # a vector the call does not spell: what it reads is unknown, and dynamic
        access = self._parameter_access(call, ParameterAccess.READ)
        for item in names:
            value = self.folder.fold(item)
            self.emit(Kind.PARAMETER, Role.PARAMETER, GET_PARAMETERS_API, value, access=access)

    def parameter_value(
        self, name: str, values: tuple[Node, ...], index: int, api: str, namespace: str | None
    ) -> None:
        """A string default or value that names something, judged by the parameter name;
        not a placeholder meaning "unset" (moveit's ``"<undefined>"``)."""
        fact = value_fact(name)
        value = self.static_argument(values, index)
        if fact is None or value is None or not value.text or re.search(r"\s", value.text):
            return
        if value.text.startswith("<") and value.text.endswith(">"):
            return
        self.emit(fact[0], fact[1], api, value, namespace=namespace)

    def frames(self, call: Call) -> None:
        for node in call.arguments[:MAX_FRAME_ARGUMENTS]:
            value = self.folder.fold(node)
            if not value.dynamic:
                self.emit(Kind.FRAME, Role.FRAME, call.name, value)

    def frame_field(self, word: str, node: Node) -> None:
        """``msg.header.frame_id = "map"``, ``t.child_frame_id = "base_link"``."""
        access = node.parent
        if (
            access is None
            or access.type != "field_expression"
            or not is_field(access, "field", node)
        ):
            return
        assignment = access.parent
        if assignment is None or assignment.type != "assignment_expression":
            return
        right = assignment.child_by_field_name("right")
        if not is_field(assignment, "left", access) or right is None:
            return
        value = self.folder.fold(right)
        if not value.dynamic and value.text:  # "" clears the field, it names no frame
            api = SENT_FRAME_FIELD[word] if self._sent_as_transform(access) else word
            self.emit(Kind.FRAME, Role.FRAME, api, value)

    def _sent_as_transform(self, access: Node) -> bool:
        """Whether the message variable whose field ``access`` is (``t.header.frame_id``,
        ``t.child_frame_id``) is handed to a ``sendTransform`` call in the same function:
        a tf broadcaster's (slam_toolbox's ``merge_maps_kinematic.cpp`` fills a
        ``TransformStamped`` so, in a node that also publishes maps)."""
        root = field_root(access)
        functions = enclosing_functions(access)
        if root is None or root.type != "identifier" or not functions:
            return False
        body, variable = functions[0], self.source.text(root)
        for word in self.source.occurrences("sendTransform"):
            if not body.start_byte <= word.start_byte < body.end_byte:
                continue
            call = call_named_by(self.source, word)
            if call is not None and any(
                argument.type == "identifier" and self.source.text(argument) == variable
                for argument in call.arguments
            ):
                return True
        return False

    def _template_type(self, call: Call) -> str | None:
        return self._first_type(call.template)

    def _first_type(self, template: Node | None) -> str | None:
        """The first template argument, through the file's type aliases."""
        types = template_types(self.source, template)
        return self.types.resolve(types[0]) if types else None

    def _variable_type(self, node: Node) -> str | None:
        if node.type != "identifier":
            return None
        declarations = self.folder.declarations.visible(self.source.text(node), node)
        return self.types.declared_type([declaration.node for declaration in declarations])

    # -- constructions ------------------------------------------------------------------

    def construction(self, construction: Construction) -> None:
        name, qualifier = construction.type_name, construction.qualifier
        if name == "NodeHandle":
            self.node_handle(construction)
        elif name in ("Node", "LifecycleNode"):
            if self.classes.accepts_node_base(name, qualifier):
                api = f"{qualifier or 'rclcpp'}::{name}"
                self.node(construction.arguments, api, construction.site)
        elif name in ACTIONLIB and qualifier in ACTIONLIB_QUALIFIERS and construction.template:
            self.action(construction, ACTIONLIB[name])
        elif name == "Subscriber" and construction.template is not None:
            if qualifier in ("message_filters", ""):
                self.filter_subscriber(construction)
        elif name in SERVICE_WRAPPERS and construction.template is not None:
            if qualifier.startswith("nav2"):
                self.service_wrapper(construction, SERVICE_WRAPPERS[name])
        elif name in FRAME_CONSTRUCTIONS and qualifier in ("tf", "tf2", ""):
            for index in FRAME_CONSTRUCTIONS[name]:
                value = self.static_argument(construction.arguments, index)
                self.emit(Kind.FRAME, Role.FRAME, f"{qualifier or 'tf'}::{name}", value)
        elif name == "Parameter" and qualifier == "rclcpp":
            self.parameter(_as_call(construction), ParameterSite(0, 1, "rclcpp::Parameter", None))

    def node_handle(self, construction: Construction) -> None:
        """``NodeHandle(ns)``, ``NodeHandle(ns, remappings)``, ``NodeHandle(parent, ns)``."""
        values = construction.arguments
        if not values:
            return
        first = self.folder.fold(values[0])
        if not first.dynamic:
            if first.text != "~":  # the private namespace, legal wherever NodeHandle exists
                self.emit(Kind.NAMESPACE, Role.NAMESPACE, "ros::NodeHandle", first)
        elif len(values) >= 2:
            parent = self.handles.parent_namespace(construction)
            value = self.argument(values, 1)
            self.emit(Kind.NAMESPACE, Role.NAMESPACE, CHILD_HANDLE_API, value, namespace=parent)

    def node(self, values: tuple[Node, ...], api: str, site: Node) -> None:
        """``rclcpp::Node(name[, namespace][, options])`` and its subclasses' base call.

        Code that builds ``--ros-args -r __node:=...`` into the options the node is given
        renames it at run time (moveit and nav2 name such helper nodes "_"): the name
        written is not the one the node gets, so it is dynamic; ``__ns:=`` likewise for
        the namespace. Another node of the same function keeps its names.
        """
        remapped = _remapped(self.source, site, values)
        name = self.argument(values, 0)
        self.emit(Kind.NODE, Role.NODE_NAME, api, _dynamic_if(name, "node" in remapped))
        namespace = self.static_argument(values, 1)
        namespace = _dynamic_if(namespace, "namespace" in remapped)
        self.emit(Kind.NAMESPACE, Role.NAMESPACE, api, namespace)

    def base_initializer(self, word: str, node: Node) -> None:
        """``: Node("talker")`` / ``: rclcpp_lifecycle::LifecycleNode("lc", options)``."""
        head = node.parent if node.parent and node.parent.type == "qualified_identifier" else node
        initializer = head.parent
        if initializer is None or initializer.type != "field_initializer":
            return
        if initializer.named_children[0] != head or initializer.named_child_count < 2:
            return
        qualifier = self.source.text(head).rpartition("::")[0] if head != node else ""
        if not self.classes.initializes_node_base(initializer, word, qualifier):
            return
        values = tuple(arguments(initializer.named_children[1]))
        self.node(values, f"{qualifier}::{word}" if qualifier else NODE_BASES[word], initializer)

    def action(self, construction: Construction, role: Role) -> None:
        """actionlib's ``(name, ...)`` or ``(nh, name, ...)``; nav2's ``(node, name, ...)``."""
        values = construction.arguments
        if not values:
            return
        index = 0
        if self.folder.fold(values[0]).dynamic and len(values) >= 2:
            second = self.folder.fold(values[1])
            if not second.dynamic or self.handles.is_handle_expression(values[0]):
                index = 1
        api = f"{construction.qualifier or 'actionlib'}::{construction.type_name}"
        value = self.argument(values, index)
        self.emit(Kind.ACTION, role, api, value, self._first_type(construction.template))

    def filter_subscriber(self, construction: Construction) -> None:
        """``message_filters::Subscriber<T> sub(nh, "scan", 10)``."""
        value = self.argument(construction.arguments, 1)
        api = "message_filters::Subscriber"
        self.emit(Kind.TOPIC, Role.SUBSCRIBE, api, value, self._first_type(construction.template))

    def service_wrapper(self, construction: Construction, role: Role) -> None:
        """nav2's ``ServiceClient<T>(name, node)`` and ``ServiceServer<T>(name, node, cb)``."""
        value = self.argument(construction.arguments, 0)
        api = f"{construction.qualifier}::{construction.type_name}"
        self.emit(Kind.SERVICE, role, api, value, self._first_type(construction.template))


# A remapping argument as rclcpp's NodeOptions().arguments() takes it: a string of its own
# (``"__node:=planner"``, ``"__ns:=" + ns``), not inside a command line a test hands a
# shell (``"ros2 run demo talker --ros-args -r __node:=x"``), which renames that process.
_REMAPS = re.compile(rb'"(?:-r )?__(node|name|ns):=')


def _remapped(source: Source, site: Node, values: tuple[Node, ...]) -> set[str]:
    """What ``__node:=``/``__ns:=`` arguments rename this node: in its own arguments, or in
    a statement of its function, before it, that writes or reads a variable its arguments
    use (``options``, then the ``args`` vector ``options.arguments(args)`` takes): another
    node's options in the same function rename that node only."""
    functions = enclosing_functions(site)
    scope = functions[-1] if functions else source.root
    texts = [source.data[value.start_byte : value.end_byte] for value in values]
    wanted, seen = _variables(source, values), set[str]()
    for _ in range(_FOLLOWED_VARIABLES):
        new = wanted - seen
        seen |= new
        for name in sorted(new):
            for occurrence in source.occurrences(name):
                if occurrence.start_byte >= site.start_byte or not contains(scope, occurrence):
                    continue
                # The statement or member initializer: None for a parameter
                statement = statement_holding(occurrence, scope, _STATEMENT_HOLDERS)
                if statement is not None:
                    texts.append(source.data[statement.start_byte : statement.end_byte])
                    wanted |= _variables(source, (statement,))
    found = {match.group(1) for text in texts for match in _REMAPS.finditer(text)}
    return {"namespace" if key == b"ns" else "node" for key in found}


# How many times variables are followed from the node's arguments: options, the argument
# vector the options take, the strings that vector is built from.
_FOLLOWED_VARIABLES = 3
_STATEMENT_HOLDERS = frozenset({"compound_statement", "translation_unit", "field_initializer_list"})
# Where an identifier names a function or a qualified name's part, not a variable
_NOT_VARIABLES = frozenset({"qualified_identifier", "template_function", "call_expression"})
_MAX_WALKED = 2000  # nodes of one statement looked at for variables


def _variables(source: Source, nodes: tuple[Node, ...]) -> set[str]:
    """The variables ``nodes`` mention: plain identifiers, not the function a call names
    nor a qualified name's parts (``rclcpp::NodeOptions``, ``std::make_shared``)."""
    found: set[str] = set()
    pending, walked = list(nodes), 0
    while pending and walked < _MAX_WALKED:
        node = pending.pop()
        walked += 1
        if node.type == "identifier":
            parent = node.parent
            if parent is None or parent.type not in _NOT_VARIABLES:
                found.add(source.text(node))
            continue
        pending.extend(node.named_children)
    return found


def _takes_options(folder: Folder, call: Call) -> bool:
    """``nh.subscribe(ops)``: roscpp's one-argument form takes an options object."""
    values = call.arguments
    return (
        call.name in OPTIONS_USERS
        and call.receiver is not None
        and len(values) == 1
        and folder.fold(values[0]).dynamic
    )


def _options_variable(create: Node) -> Node | None:
    """What a ``create<M>(...)`` call's result goes into: the variable it initialises or is
    assigned to, or the call itself when it is handed on directly."""
    parent = create.parent
    if parent is not None and parent.type == "init_declarator":
        return parent.child_by_field_name("declarator")
    if parent is not None and parent.type == "assignment_expression":
        return parent.child_by_field_name("left")
    return create


def _called_with(argument: Node) -> tuple[str, Node] | None:
    """(method, receiver) of a call ``receiver.method(argument)`` taking only ``argument``."""
    arguments_node = argument.parent
    if arguments_node is None or arguments_node.type != "argument_list":
        return None
    if len([c for c in arguments_node.named_children if c.type != "comment"]) != 1:
        return None
    call = arguments_node.parent
    callee = None if call is None else call.child_by_field_name("function")
    if callee is None or callee.type != "field_expression":
        return None
    method = callee.child_by_field_name("field")
    receiver = callee.child_by_field_name("argument")
    if method is None or receiver is None:
        return None
    return method.text.decode("utf-8", "replace") if method.text else "", receiver


def _dynamic_if(value: Value | None, condition: bool) -> Value | None:
    if value is None or not condition:
        return value
    return Value(value.text, True, value.node)


def _qualified_member(scope: Node) -> Node | None:
    """``get`` of ``ros::param::get`` given the ``param`` node."""
    parent = scope.parent
    if (
        parent is None
        or parent.type != "qualified_identifier"
        or not is_field(parent, "scope", scope)
    ):
        return None
    name = parent.child_by_field_name("name")
    if name is not None and name.type == "template_function":  # SubscribeOptions::create<M>
        name = name.child_by_field_name("name")
    return name if name is not None and name.type == "identifier" else None


def _is_namespace(qualifier: str) -> bool:
    """``rclcpp`` or ``image_transport`` (a free function), not ``rclcpp::Node`` (a class)."""
    last = qualifier.rpartition("::")[2]
    return bool(last) and not last[0].isupper()


def _as_call(construction: Construction) -> Call:
    return Call(
        node=construction.site,
        word=construction.site,
        name=construction.type_name,
        qualifier=construction.qualifier,
        receiver=None,
        template=construction.template,
        arguments=construction.arguments,
    )


_READS_AND_CHECKS = frozenset(
    {
        ParameterAccess.READ,
        ParameterAccess.READ_QUIETLY,
        ParameterAccess.READ_PREFIX,
        ParameterAccess.CHECK,
    }
)
# ``auto client = std::make_shared<rclcpp::SyncParametersClient>(...)``,
# ``rclcpp::AsyncParametersClient::SharedPtr client_;``, ``client_ = ...ParametersClient...``
_PARAMETER_CLIENT = re.compile(
    rb"ParametersClient\b[^;(){}\n]{0,80}?\b([A-Za-z_]\w*)\s*[;=({]"
    rb"|\b([A-Za-z_]\w*)\s*=[^;=]{0,80}?ParametersClient\b"
)


def _parameter_clients(source: Source) -> frozenset[str]:
    """The variables and members the file declares as, or assigns, parameter clients."""
    data = source.data
    if b"ParametersClient" not in data:
        return frozenset()
    found = set()
    for match in _PARAMETER_CLIENT.finditer(data):
        name = match.group(1) or match.group(2)
        if name:
            found.add(name.decode("utf-8", "replace"))
    return frozenset(found)


def _initializer_items(node: Node) -> list[Node] | None:
    """The elements of ``{"a", "b"}`` or ``std::vector<std::string>{"a", "b"}``."""
    node = unparenthesized(node)
    if node.type == "compound_literal_expression":
        node = node.child_by_field_name("value") or node
    if node.type != "initializer_list":
        return None
    return [child for child in node.named_children if child.type != "comment"]


def _initializer_entries(node: Node) -> list[Node] | None:
    """The keys of a map spelled in the call: ``{{"a", 1}, {"b", 2}}``; None when the
    call does not spell it, or an element is not a pair."""
    items = _initializer_items(node)
    if items is None:
        return None
    keys = []
    for item in items:
        pair = _initializer_items(item)
        if not pair:
            return None
        keys.append(pair[0])
    return keys


# The parameter APIs whose callers the linter reads (``apis``): their own bodies, when the
# workspace holds them (nav2_ros_common's node_utils.hpp, ros2_control's
# controller_interface_base.hpp), declare what each caller passes, not a name of their own.
_DECLARING_APIS = frozenset(
    {
        "declare_parameter",
        "declare_parameters",
        "declare_parameter_if_not_declared",
        DECLARE_OR_GET,
        PLUGIN_TYPE,
        "auto_declare",
        "get_or_declare_parameter",
        "getOrDeclareParameter",
    }
)


def _implements_declaring_api(source: Source, node: Node) -> bool:
    """Whether ``node`` is inside the definition of one of ``_DECLARING_APIS``."""
    for function in enclosing_functions(node):
        if function.type != "function_definition":
            continue
        declarator = function.child_by_field_name("declarator")
        while declarator is not None and declarator.type != "function_declarator":
            declarator = declarator.child_by_field_name("declarator")
        name = None if declarator is None else declarator.child_by_field_name("declarator")
        if name is not None:
            spelled = source.text(name).rpartition("::")[2]
            return spelled in _DECLARING_APIS
    return False
