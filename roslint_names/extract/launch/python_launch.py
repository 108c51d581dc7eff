"""ROS 2 Python launch files: the same facts the launch XML and YAML extractors produce.

A launch.py builds a tree of launch actions as Python values; ``python_launch_values``
evaluates the part of it that is static. The tree is walked from what
``generate_launch_description`` (or launch_testing's ``generate_test_description``)
returns, as ``launch_xml.Ros2Launch`` walks an XML file: ``GroupAction`` scopes pushed
namespaces, remaps and launch configurations; ``PushRosNamespace`` pushes; a node's
relative namespace is prefixed with the pushed one; composable nodes get the pushed
namespace, not their container's; a statically false ``IfCondition`` skips its action.
Namespaces on the facts follow ``launch_xml``: a node's ``namespace=`` carries the
enclosing namespace, its name and remaps the node's, its parameters the node's full name.
``IncludeLaunchDescription`` gives a ``LaunchInclude``: the file (``python_launch_paths``),
the namespace, remaps and launch configurations in force, so that the workspace model can
extract the included file again with those arguments (``arguments=``).

Actions no walk reaches (built in a loop, a comprehension, or a helper this file does not
call) still get their names checked, in an unknown namespace.
"""

from __future__ import annotations

import weakref
from collections.abc import Iterator, Sequence

import libcst as cst

from roslint_names.extract.launch import static_transform
from roslint_names.extract.launch.common import (
    FRAME,
    NAMESPACE,
    NODE,
    PARAMETER,
    REMAP_FROM,
    REMAP_TO,
    Fact,
    is_frame_parameter,
    join_namespace,
    node_path,
)
from roslint_names.extract.launch.include import handed, package_text, passed_values
from roslint_names.extract.launch.python_paths import IncludePaths
from roslint_names.extract.launch.python_values import (
    Action,
    ActionCall,
    LaunchCalls,
    LaunchScope,
    LaunchValues,
    Written,
    call_argument,
    class_key,
    defined_function,
    frames_key,
)
from roslint_names.extract.launch.substitution import Dialect, Value, skipped, truth
from roslint_names.extract.python.scope import Scope, argument_context
from roslint_names.extract.python.spans import Locator, Where
from roslint_names.extract.python.walk import Walk
from roslint_names.model import (
    InPackage,
    LaunchArguments,
    LaunchInclude,
    LaunchNode,
    NameUse,
    ParameterLoad,
    Remap,
    Span,
)

_IF = ("launch", "IfCondition")
_PARAMETER_FILE = ("launch_ros", "ParameterFile")
# nav2_common's substitution that rewrites a parameter file's values (and, with
# ``key_rewrites``, its keys) into a temporary copy: nav2_bringup hands every server one.
_REWRITTEN_YAML = ("nav2_common", "RewrittenYaml")
_UNLESS = ("launch", "UnlessCondition")
_ROOTS = ("generate_launch_description", "generate_test_description")
# Keywords, current then pre-Foxy spelling (node_name, node_namespace...).
_NAME = ":name|node_name"
_NAMESPACE = ":namespace|node_namespace"


class LaunchExtractor(LaunchValues):
    """Walks a module's launch actions like ``launch_xml.Ros2Launch``, emitting facts."""

    def __init__(
        self,
        walk: Walk,
        locator: Locator,
        file_name: str = "",
        arguments: LaunchArguments = (),
        calls: LaunchCalls | None = None,
    ) -> None:
        """``arguments``: launch configurations set before the description runs (what an
        including file hands over); ``file_name`` is what ``__file__`` ends with;
        ``calls``: ``LaunchCalls.of(walk)``, when already at hand."""
        super().__init__(walk, locator, calls)
        # A proxy, not the extractor itself: the two would make a cycle, which keeps the
        # file's tree alive until the cycle collector walks it (see ``Walk.release``).
        self.paths = IncludePaths(weakref.proxy(self), file_name)
        self.arguments = passed_values(arguments)
        self.names: list[NameUse] = []
        self.nodes: list[LaunchNode] = []
        self.includes: list[LaunchInclude] = []
        self.found_actions = False
        self.undecided_depth = 0  # conditions of enclosing actions not statically known
        self.inactive_depth = 0  # enclosing actions a condition statically turns off
        self._visited: set[tuple[int, tuple[int, ...]]] = set()  # (call, frames)
        self._reached: set[int] = set()  # calls visited in any frames
        self._emitted: set[tuple[int, Fact]] = set()

    # -- entry --------------------------------------------------------------------------

    def run(self) -> None:
        for root in self.roots():
            self.visit_all(root, LaunchScope("/", variables=dict(self.arguments)))
        # What no description reaches: an unknown namespace, and no known launch either.
        # Actions built apart (each test function of a launch test module its own
        # description, a helper's alternatives) are not one launch that starts them all,
        # so their nodes are as undecided as a condition's (never RN402 twins).
        self.undecided_depth += 1
        for site, kind in self.calls.actions:
            if id(site.call) not in self._reached:
                self.found_actions = True
                unknown = LaunchScope(None, variables=dict(self.arguments))
                self.visit(ActionCall(kind, site.call, site.context), unknown)
        self.undecided_depth -= 1

    def roots(self) -> Iterator[list[ActionCall]]:
        for function in self.walk.functions:
            if function.name.value in _ROOTS:
                for value, context in self.walk.returns.get(function, []):
                    yield self.actions(Written(value, context))

    # -- walking ------------------------------------------------------------------------

    def visit_all(self, actions: Sequence[ActionCall], scope: LaunchScope) -> None:
        for action in actions:
            self.visit(action, scope)

    def visit(self, action: ActionCall, scope: LaunchScope) -> None:
        """Once per call and helper frames: ``robot('a'), robot('b')`` visit the helper's
        actions twice, with its parameters bound to each call's arguments."""
        key = (id(action.call), frames_key(action.frames))
        if key in self._visited or (not action.frames and id(action.call) in self._reached):
            return
        self._visited.add(key)
        self._reached.add(id(action.call))
        self.found_actions = True
        saved, self.frames = self.frames, action.frames
        try:
            if self.excluded(action, scope):
                # Statically off: its names are still checked, but it starts nothing,
                # and what it would push or set stays in a copy of the scope.
                self.inactive_depth += 1
                try:
                    self.visit_kind(action, scope.copy())
                finally:
                    self.inactive_depth -= 1
            else:
                undecided = self.undecided(action, scope)
                self.undecided_depth += undecided
                try:
                    self.visit_kind(action, scope)
                finally:
                    self.undecided_depth -= undecided
        finally:
            self.frames = saved

    def visit_kind(self, action: ActionCall, scope: LaunchScope) -> None:
        kind = action.kind
        if kind is Action.DESCRIPTION:
            self.visit_all(self.children(action, "0:initial_entities"), scope)
            self.visit_added(action, scope)
        elif kind is Action.GROUP:
            self.group(action, scope)
        elif kind is Action.TIMER:
            self.visit_all(self.children(action, "1:actions"), scope)
        elif kind is Action.OPAQUE:
            self.opaque(action, scope)
        elif kind is Action.HANDLER:
            self.handler(action, scope)
        elif kind is Action.PUSH:
            self.push(action, scope)
        elif kind is Action.SET_REMAP:
            apis = ("SetRemap(src=)", "SetRemap(dst=)")
            source, target = action.get("0:src"), action.get("1:dst")
            remap = self.remap(source, target, scope.namespace, scope, apis)
            scope.remaps.extend([remap] if remap else [])
        elif kind is Action.SET_PARAMETER:
            self.set_parameter(action, scope)
        elif kind is Action.LET:
            self.let(action, scope)
        elif kind in (Action.NODE, Action.CONTAINER):
            self.node(action, scope)
            self.composable_nodes(action, scope)
        elif kind is Action.LOAD:
            self.composable_nodes(action, scope)
        elif kind is Action.COMPOSABLE:
            self.node(action, scope)
        elif kind is Action.INCLUDE:
            self.include(action, scope)

    def visit_added(self, action: ActionCall, scope: LaunchScope) -> None:
        """``ld = LaunchDescription(); ld.add_action(x)``: what the variable gets later."""
        for binding_scope, name in _bound_to(action.call, action.context.scope):
            for added in self.adders.get((id(binding_scope), name), []):
                self.visit_all(self.actions(added), scope)

    def undecided(self, action: ActionCall, scope: LaunchScope) -> bool:
        """A ``condition=`` whose outcome is not statically known (not excluded either)."""
        condition = action.get(":condition")
        if condition is None:
            return False
        if not isinstance(condition.expr, cst.Call):
            return True
        inner = call_argument(condition.expr, condition.context, "0:predicate_expression")
        tests = {class_key(name) for name in condition.scope.qualified(condition.expr.func)}
        if inner is None or not tests & {_IF, _UNLESS}:
            return True
        return truth(self.value(inner, scope)) is None

    def excluded(self, action: ActionCall, scope: LaunchScope) -> bool:
        """A ``condition=IfCondition(x)`` that is statically false (as launch XML's if=)."""
        condition = action.get(":condition")
        if condition is None or not isinstance(condition.expr, cst.Call):
            return False
        names = condition.scope.qualified(condition.expr.func)
        tests = {class_key(name) for name in names}
        inner = call_argument(condition.expr, condition.context, "0:predicate_expression")
        if inner is None:
            return False
        value = self.value(inner, scope)
        if _IF in tests:
            return skipped(value, None)
        if _UNLESS in tests:
            return skipped(None, value)
        return False

    def group(self, action: ActionCall, scope: LaunchScope) -> None:
        """A group keeps pushes, remaps and configurations to itself unless scoped=False;
        its ``launch_configurations`` are set inside it."""
        scoped = action.get(":scoped")
        leaks = scoped is not None and _is_false(scoped.expr)
        inner = scope if leaks else scope.copy()
        configurations = action.get(":launch_configurations")
        if configurations is not None and isinstance(configurations.expr, cst.Dict):
            for key, value in self.pairs(configurations):
                name = self.value(key, inner)
                if not name.dynamic:
                    inner.variables[name.text] = self.value(value, inner)
        self.visit_all(self.children(action, "0:actions"), inner)

    def opaque(self, action: ActionCall, scope: LaunchScope) -> None:
        """``OpaqueFunction(function=launch_setup)``: what the file's function returns runs
        here, when it is a literal list of actions."""
        function = action.get("0:function")
        if function is None:
            return
        defined = defined_function(function.expr, function.scope)
        if defined is not None:
            for value, context in self.walk.returns.get(defined, []):
                self.visit_all(self.actions(Written(value, context)), scope)

    def handler(self, action: ActionCall, scope: LaunchScope) -> None:
        """``RegisterEventHandler(OnProcessExit(on_exit=[...]))``: the actions run later,
        in the scope the handler was registered in."""
        handler = action.get("0:event_handler")
        if handler is None or not isinstance(handler.expr, cst.Call):
            return
        for item in handler.expr.args:
            if item.keyword is not None and item.keyword.value.startswith("on_"):
                located = Written(
                    item.value, argument_context(handler.expr, handler.context, item.value)
                )
                self.visit_all(self.actions(located), scope)

    def push(self, action: ActionCall, scope: LaunchScope) -> None:
        """``PushRosNamespace``: the rest of the enclosing group (or file) is inside it."""
        located = action.get("0:namespace")
        if located is not None:
            value = self.emit(
                NAMESPACE, "PushRosNamespace(namespace=)", located, scope, scope.namespace
            )
            scope.namespace = join_namespace(scope.namespace, value)
            scope.anchored = scope.anchored or _is_absolute(value)

    def let(self, action: ActionCall, scope: LaunchScope) -> None:
        """``SetLaunchConfiguration``, launch XML's ``<let>``."""
        name, value = action.get("0:name"), action.get("1:value")
        if name is not None and value is not None:
            key = self.value(name, scope)
            if not key.dynamic:
                scope.variables[key.text] = self.value(value, scope)

    def set_parameter(self, action: ActionCall, scope: LaunchScope) -> None:
        """``SetParameter(name, value)``: for every node after it in its scope."""
        name = action.get("0:name")
        if name is None:
            return
        value = self.emit(PARAMETER, "SetParameter(name=)", name, scope, scope.namespace)
        frame = action.get("1:value")
        if frame is not None and not value.dynamic and is_frame_parameter(value.text):
            self.frame(frame, scope, scope.namespace, "SetParameter(value=)")

    # -- includes -----------------------------------------------------------------------

    def include(self, action: ActionCall, scope: LaunchScope) -> None:
        """One ``LaunchInclude``, or the actions of an inline description walked here.

        launch runs an include as ``SetLaunchConfiguration`` of each argument followed by
        the included description, unscoped: the arguments stay set in the including scope
        (a group around the include is what keeps them in).
        """
        explicit = self.launch_arguments(action, scope)
        located = action.get("0:launch_description_source")
        source = None if located is None else self.paths.source(located)
        if source is not None and source.inline is not None:
            scope.variables.update(explicit)
            self.visit_all(self.actions(source.inline), scope)
            return
        span = self.locator.span(located.where() if located else _callee(action))
        self.add_include(None if source is None else source.path, span, scope, explicit)
        scope.variables.update(explicit)

    def add_include(
        self, path: Written | None, span: Span, scope: LaunchScope, explicit: dict[str, Value]
    ) -> None:
        """The included file sees every configuration of the including scope (ROS 2
        configurations are not per file), then the explicit arguments over them."""
        package, where = (None, None) if path is None else self.paths.locate(path, scope)
        given = self.configurations(scope) | explicit
        if self.inactive_depth:
            return
        self.includes.append(
            LaunchInclude(
                package=package,
                path=where,
                namespace="" if scope.namespace is None else scope.namespace,
                span=span,
                arguments=tuple(sorted((k, handed(v)) for k, v in given.items())),
                remaps=tuple(scope.remaps),
                anchored=scope.anchored,
                conditional=self.undecided_depth > 0,
            )
        )

    def launch_arguments(self, action: ActionCall, scope: LaunchScope) -> dict[str, Value]:
        """``launch_arguments`` by name (dynamic values kept: they hide what the scope
        knows); a namespace or a frame handed over is a name of this file."""
        arguments = action.get("1:launch_arguments")
        found: dict[str, Value] = {}
        for key, value in [] if arguments is None else self.pairs(arguments):
            name = self.value(key, scope)
            if name.dynamic:
                continue
            api = f"IncludeLaunchDescription(launch_arguments={name.text!r})"
            if _is_namespace_argument(name.text):
                found[name.text] = self.emit(NAMESPACE, api, value, scope, scope.namespace)
                continue
            found[name.text] = self.argument_value(value, scope)
            if is_frame_parameter(name.text):
                self.frame(value, scope, scope.namespace, api)
        return found

    def argument_value(self, located: Written, scope: LaunchScope) -> Value:
        """A value handed to an included file: its text, or for a path in a package
        (``PathJoinSubstitution([FindPackageShare('pkg'), 'config', 'a.yaml'])``) a
        dynamic value whose text names the package's file as launch XML would."""
        value = self.value(located, scope)
        if not value.dynamic:
            return value
        package, where = self.paths.locate(located, scope)
        if package is None or where is None:
            return value
        return Value(package_text(InPackage(package, where), Dialect.ROS2), dynamic=True)

    # -- nodes --------------------------------------------------------------------------

    def node(self, action: ActionCall, scope: LaunchScope) -> None:
        """A node or composable node: its names, then one ``LaunchNode``."""
        label = action.kind.value
        namespace, anchored = scope.namespace, scope.anchored
        located = action.get(_NAMESPACE)
        if located is not None:
            value = self.emit(NAMESPACE, f"{label}(namespace=)", located, scope, namespace)
            namespace = join_namespace(namespace, value)
            anchored = anchored or _is_absolute(value)
        name_at = action.get(_NAME)
        name, dynamic_name = None, False
        if name_at is not None:
            name_value = self.emit(NODE, f"{label}(name=)", name_at, scope, namespace)
            name, dynamic_name = (None, True) if name_value.dynamic else (name_value.text, False)
        remaps = self.remappings(action, scope, namespace, label)
        parameters = self.parameters(action, scope, node_path(namespace, name), label)
        files = self.parameter_files(action, scope)
        composable = action.kind is Action.COMPOSABLE
        executable = ":plugin|node_plugin" if composable else ":executable|node_executable"
        if not composable:
            self.broadcast_frames(action, scope, node_path(namespace, name), executable)
        if self.inactive_depth:
            return
        self.nodes.append(
            LaunchNode(
                package=self.static(action.get(":package"), scope),
                executable=self.static(action.get(executable), scope),
                name=name,
                namespace="" if namespace is None else namespace,
                span=self.locator.span(name_at.where() if name_at else _callee(action)),
                remaps=tuple(scope.remaps + remaps),
                parameters=tuple(name for name, _ in parameters),
                parameter_spans=tuple(span for _, span in parameters),
                own_remaps=len(remaps),
                anchored=anchored,
                conditional=self.undecided_depth > 0,
                dynamic_name=dynamic_name,
                parameter_files=tuple(files),
            )
        )

    def broadcast_frames(
        self, action: ActionCall, scope: LaunchScope, path: str | None, executable: str
    ) -> None:
        """The two frames a static transform publisher is given in ``arguments=``: one
        word per element, as launch_ros's ``Node`` puts each on the command line (a
        string given whole is a sequence of characters there, and no command line of
        the program)."""
        which = static_transform.program(
            self.static(action.get(":package"), scope),
            self.static(action.get(executable), scope),
            ros1=False,
        )
        located = action.get(":arguments")
        if which is None or located is None:
            return
        words = [(item, self.value(item, scope)) for item in self.items(located)]
        for frame in static_transform.frames(which, [value.text for _, value in words]):
            item, value = words[frame.index]
            if self.is_text(item):
                self.add(FRAME, frame.api, item, value, path)

    def composable_nodes(self, action: ActionCall, scope: LaunchScope) -> None:
        """Composable nodes get the pushed namespace, not their container's."""
        for description in self.children(action, ":composable_node_descriptions"):
            self.visit(description, scope)

    def remappings(
        self, action: ActionCall, scope: LaunchScope, namespace: str | None, label: str
    ) -> list[Remap]:
        located = action.get(":remappings")
        found: list[Remap] = []
        for rule in [] if located is None else self.items(located):
            if isinstance(rule.expr, cst.Tuple) and len(rule.expr.elements) == 2:
                source, target = (
                    Written(e.value, rule.context.inside(e)) for e in rule.expr.elements
                )
                apis = (f"{label}(remappings=) from", f"{label}(remappings=) to")
                remap = self.remap(source, target, namespace, scope, apis)
                found.extend([remap] if remap else [])
        return found

    def remap(
        self,
        source: Written | None,
        target: Written | None,
        namespace: str | None,
        scope: LaunchScope,
        apis: tuple[str, str],
    ) -> Remap | None:
        """Emit a remap's two names; the remap when both are static."""
        if source is None or target is None:
            return None
        source_value = self.emit(REMAP_FROM, apis[0], source, scope, namespace)
        target_value = self.emit(REMAP_TO, apis[1], target, scope, namespace)
        if source_value.dynamic or target_value.dynamic:
            return None
        return Remap(
            source_value.text,
            target_value.text,
            self.locator.span(source.where()),
            self.locator.span(target.where()),
        )

    def parameters(
        self, action: ActionCall, scope: LaunchScope, path: str | None, label: str
    ) -> list[tuple[str, Span]]:
        """Names of ``parameters=[{...}]`` dictionaries (nested ones joined with '.'),
        each with its key's span; parameter files and other substitutions are not read."""
        located = action.get(":parameters")
        found: list[tuple[str, Span]] = []
        for item in [] if located is None else self.items(located):
            dictionary = self.dictionary(item)
            if dictionary is not None:
                found += self.parameter_dict(dictionary, scope, "", path, label)
        return found

    def parameter_files(self, action: ActionCall, scope: LaunchScope) -> list[ParameterLoad]:
        """The files of ``parameters=``: every item that is no dictionary, a path or a
        ``ParameterFile(path)``, located as an include's file is (``IncludePaths``)."""
        located = action.get(":parameters")
        found: list[ParameterLoad] = []
        for item in [] if located is None else self.items(located):
            if self.dictionary(item) is not None:
                continue
            path = self.parameter_file_path(item, 0)
            package, where = self.paths.locate(path, scope)
            span = self.locator.span(item.where())
            found.append(ParameterLoad(package, where, span, conditional=self.undecided_depth > 0))
        return found

    def parameter_file_path(self, item: Written, depth: int) -> Written:
        """The path of ``ParameterFile(path)`` (through a variable holding one); any
        other item is the path itself."""
        expr = item.expr
        if isinstance(expr, cst.Name) and depth < 8:
            bound = self.bound(item)
            if bound is not None and isinstance(bound.expr, cst.Call):
                return self.parameter_file_path(bound, depth + 1)
        if isinstance(expr, cst.Call) and any(
            class_key(name) == _PARAMETER_FILE for name in item.scope.qualified(expr.func)
        ):
            path = call_argument(expr, item.context, "0:param_file")
            return item if path is None else self.parameter_file_path(path, depth + 1)
        if isinstance(expr, cst.Call) and any(
            class_key(name) == _REWRITTEN_YAML for name in item.scope.qualified(expr.func)
        ):
            return self.rewritten_source(expr, item)
        return item

    def rewritten_source(self, call: cst.Call, item: Written) -> Written:
        """The file ``RewrittenYaml`` rewrites, where its keys stay the file's: new values
        (``param_rewrites``, ``value_rewrites``) change no name, and ``root_key`` nests the
        file under the namespace nav2_bringup pushes onto the same nodes (a launch
        argument), which moves the keys and the nodes alike. ``key_rewrites`` renames keys,
        and a literal ``root_key`` nests them under a namespace of its own: the call itself
        then, which names no file the linter can read."""
        source = call_argument(call, item.context, "0:source_file")
        root_key = call_argument(call, item.context, "2:root_key")
        renames_keys = call_argument(call, item.context, "3:key_rewrites") is not None
        nests = (
            root_key is not None
            and isinstance(root_key.expr, cst.SimpleString)
            and bool(root_key.expr.evaluated_value)
        )
        if source is None or renames_keys or nests:
            return item
        return source

    def parameter_dict(
        self,
        dictionary: Written,
        scope: LaunchScope,
        prefix: str | None,
        path: str | None,
        label: str,
    ) -> list[tuple[str, Span]]:
        found: list[tuple[str, Span]] = []
        for key, value in self.pairs(dictionary):
            full = self.parameter_name(key, scope, prefix)
            nested = self.dictionary(value)
            if nested is not None:
                found += self.parameter_dict(
                    nested, scope, None if full.dynamic else full.text, path, label
                )
                continue
            self.add(PARAMETER, f"{label}(parameters=)", key, full, path)
            if not full.dynamic:
                found.append((full.text, self.locator.span(key.where())))
                if is_frame_parameter(full.text):
                    self.frame(value, scope, path, f"{label}(parameters=)")
        return found

    def parameter_name(self, key: Written, scope: LaunchScope, prefix: str | None) -> Value:
        """``prefix.key``; dynamic when either is (``prefix`` None: a dynamic parent)."""
        name = self.value(key, scope)
        if prefix is None or name.dynamic:
            return Value(self.locator.code(key.expr), dynamic=True)
        return Value(f"{prefix}.{name.text}" if prefix else name.text)

    def frame(self, located: Written, scope: LaunchScope, namespace: str | None, api: str) -> None:
        """A frame-like parameter's value, when static and a string."""
        value = self.value(located, scope)
        if not value.dynamic and value.text and self.is_text(located):
            self.add(FRAME, api, located, value, namespace)

    # -- facts --------------------------------------------------------------------------

    def emit(
        self, fact: Fact, api: str, located: Written, scope: LaunchScope, namespace: str | None
    ) -> Value:
        value = self.value(located, scope)
        self.add(fact, api, located, value, namespace)
        return value

    def add(
        self, fact: Fact, api: str, located: Written, value: Value, namespace: str | None
    ) -> None:
        """One fact per place: remaps kept in one list and given to six nodes are one use
        each (the nodes' ``LaunchNode.remaps`` still list them all)."""
        key = (id(located.expr), fact)
        if key in self._emitted:
            return
        self._emitted.add(key)
        span = self.locator.span(located.where())
        self.names.append(
            NameUse(fact.kind, value.text, span, fact.role, api, value.dynamic, None, namespace)
        )


def _callee(action: ActionCall) -> Where:
    context = action.context
    return Where(action.call.func, (action.call, *context.anchors), context.indents)


def _is_false(expr: cst.BaseExpression) -> bool:
    return isinstance(expr, cst.Name) and expr.value == "False"


def _is_absolute(value: Value) -> bool:
    return not value.dynamic and value.text.startswith("/")


def _is_namespace_argument(name: str) -> bool:
    return name in ("namespace", "ns") or (
        name.endswith("_namespace") and not name.startswith("use_")
    )


def _bound_to(call: cst.Call, scope: Scope) -> Iterator[tuple[Scope, str]]:
    """The variables assigned exactly this call (``ld = LaunchDescription()``)."""
    current: Scope | None = scope
    while current is not None:
        for name, bindings in current.bindings.items():
            if len(bindings) == 1 and bindings[0].value is call:
                yield current, name
        current = current.parent
