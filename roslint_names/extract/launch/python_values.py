"""Static evaluation of a launch.py: which actions a list holds, what a value is.

Action constructors are recognised through the imports (``launch_ros.actions.Node``,
``launch.actions.GroupAction``...). Lists of actions are followed through literals, ``+``,
``*starred`` elements, variables assigned once, ``ld.add_action(x)`` /
``actions.append(x)`` in statement order, and calls of the file's own functions (whose
parameters are bound to each call's arguments, see ``CallFrame``). Values
are what launch's ``perform_substitutions`` would give without running anything: a
string, a constant, a list of parts (concatenated), a ``TextSubstitution``, or a
``LaunchConfiguration`` known from a ``DeclareLaunchArgument`` default of the file (all
declarations of a name must agree), a group's ``launch_configurations`` or a
``SetLaunchConfiguration``; anything else is dynamic.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

import libcst as cst

from roslint_names.extract.launch.substitution import Value
from roslint_names.extract.python.apis import arg, argument
from roslint_names.extract.python.fold import Folder, string_literal
from roslint_names.extract.python.scope import CallSite, Context, Scope, argument_context
from roslint_names.extract.python.spans import Locator, Where
from roslint_names.extract.python.walk import Walk
from roslint_names.model import Remap


class Action(Enum):
    NODE = "Node"
    COMPOSABLE = "ComposableNode"
    CONTAINER = "ComposableNodeContainer"
    LOAD = "LoadComposableNodes"
    PUSH = "PushRosNamespace"
    SET_REMAP = "SetRemap"
    SET_PARAMETER = "SetParameter"
    GROUP = "GroupAction"
    TIMER = "TimerAction"
    DESCRIPTION = "LaunchDescription"
    INCLUDE = "IncludeLaunchDescription"
    OPAQUE = "OpaqueFunction"
    HANDLER = "RegisterEventHandler"
    DECLARE = "DeclareLaunchArgument"
    LET = "SetLaunchConfiguration"


# By the last component of the qualified name, for the package that defines it.
_ACTIONS: dict[tuple[str, str], Action] = {
    ("launch_ros", "Node"): Action.NODE,
    ("launch_ros", "LifecycleNode"): Action.NODE,
    ("launch_ros", "ComposableNode"): Action.COMPOSABLE,
    ("launch_ros", "ComposableNodeContainer"): Action.CONTAINER,
    ("launch_ros", "LoadComposableNodes"): Action.LOAD,
    ("launch_ros", "PushRosNamespace"): Action.PUSH,
    ("launch_ros", "PushROSNamespace"): Action.PUSH,
    ("launch_ros", "SetRemap"): Action.SET_REMAP,
    ("launch_ros", "SetParameter"): Action.SET_PARAMETER,
    ("launch", "GroupAction"): Action.GROUP,
    ("launch", "TimerAction"): Action.TIMER,
    ("launch", "LaunchDescription"): Action.DESCRIPTION,
    ("launch", "IncludeLaunchDescription"): Action.INCLUDE,
    ("launch", "OpaqueFunction"): Action.OPAQUE,
    ("launch", "RegisterEventHandler"): Action.HANDLER,
    ("launch", "DeclareLaunchArgument"): Action.DECLARE,
    ("launch", "SetLaunchConfiguration"): Action.LET,
}
_LAUNCH_PACKAGES = frozenset(package for package, _ in _ACTIONS)
_CONFIGURATION = ("launch", "LaunchConfiguration")
_TEXT = ("launch", "TextSubstitution")
# Methods that add actions to a list or a description, in statement order.
_ADDERS = frozenset({"append", "add_action", "add_entity", "extend"})
_MAX_DEPTH = 12  # helper functions calling helpers; deeper is left unreached


@dataclass(frozen=True)
class Written:
    """An expression and the context it is written in (for its span and its scope)."""

    expr: cst.BaseExpression
    context: Context

    @property
    def scope(self) -> Scope:
        return self.context.scope

    def where(self) -> Where:
        return self.context.where(self.expr)


@dataclass(frozen=True)
class CallFrame:
    """A call of one of the file's own functions: what its parameters are bound to.

    ``robot('robot1')`` and ``robot('robot2')`` build the same ``GroupAction`` call twice,
    once per frame: an action carries the frames it was built in.
    """

    scope: Scope  # the called function's scope
    call: cst.Call
    parameters: dict[str, Written]


Frames = tuple[CallFrame, ...]


def frames_key(frames: Frames) -> tuple[int, ...]:
    return tuple(id(frame.call) for frame in frames)


@dataclass(frozen=True)
class ActionCall:
    kind: Action
    call: cst.Call
    context: Context  # where the call is written
    frames: Frames = ()  # the helper calls it was built in, outermost first

    def get(self, spec: str) -> Written | None:
        return call_argument(self.call, self.context, spec)


def call_argument(call: cst.Call, context: Context, spec: str) -> Written | None:
    """An argument by spec (see ``python_code.arg``), written inside the call."""
    found = argument(call, arg(spec))
    if found is None:
        return None
    return Written(found, argument_context(call, context, found))


@dataclass
class LaunchScope:
    """What an action sees: pushed namespace, remaps, launch configurations set so far.

    ``anchored``: an absolute namespace was pushed in this file, so the namespace of a
    file including this one does not prefix ``namespace`` (see ``LaunchNode.anchored``).
    """

    namespace: str | None
    remaps: list[Remap] = field(default_factory=list)
    variables: dict[str, Value] = field(default_factory=dict)
    anchored: bool = False

    def copy(self) -> LaunchScope:
        return LaunchScope(self.namespace, list(self.remaps), dict(self.variables), self.anchored)


@dataclass(frozen=True)
class LaunchCalls:
    """What of a module's calls no launch argument changes, found once per module and
    shared by its extractions under each includer's arguments: the calls that build an
    action, ``add_action``-like calls per variable, ``DeclareLaunchArgument`` defaults.

    An action or a declaration is a class of the launch packages, named through the
    file's imports: a module importing neither has none, and its calls are not asked.
    """

    actions: list[tuple[CallSite, Action]]
    adders: dict[tuple[int, str], list[Written]]
    declarations: dict[str, list[Written | None]]

    @classmethod
    def of(cls, walk: Walk) -> LaunchCalls:
        if not walk.packages & _LAUNCH_PACKAGES:
            return cls([], _adder_calls(walk), {})
        actions = [
            (site, kind)
            for site in walk.calls
            if (kind := action_kind(site.call, site.context.scope)) is not None
        ]
        return cls(actions, _adder_calls(walk), _declarations(walk))


class LaunchValues:
    """Evaluates the static part of a module's launch actions and values."""

    def __init__(self, walk: Walk, locator: Locator, calls: LaunchCalls | None = None) -> None:
        """``calls``: ``LaunchCalls.of(walk)``, when already at hand."""
        self.walk = walk
        self.locator = locator
        self.folder = Folder(locator)
        self.calls = LaunchCalls.of(walk) if calls is None else calls
        self.adders = self.calls.adders
        self._declarations = self.calls.declarations
        self._resolving: set[str] = set()
        self.frames: Frames = ()  # of the action being evaluated

    # -- evaluating lists of actions ----------------------------------------------------

    def action_kind(self, call: cst.Call, scope: Scope) -> Action | None:
        return action_kind(call, scope)

    def actions(self, located: Written, depth: int = 0) -> list[ActionCall]:
        """The actions an expression evaluates to, in order; [] when unknown."""
        expr, context = located.expr, located.context
        if depth > _MAX_DEPTH:
            return []
        if isinstance(expr, cst.List | cst.Tuple):
            found: list[ActionCall] = []
            for element in expr.elements:
                found += self.actions(Written(element.value, context.inside(element)), depth + 1)
            return found
        if isinstance(expr, cst.BinaryOperation) and isinstance(expr.operator, cst.Add):
            left = self.actions(Written(expr.left, context), depth + 1)
            return left + self.actions(Written(expr.right, context), depth + 1)
        if isinstance(expr, cst.Name):
            return self.named_actions(expr, context, depth)
        if isinstance(expr, cst.Call):
            return self.call_actions(expr, context, depth)
        return []

    def named_actions(self, expr: cst.Name, context: Context, depth: int) -> list[ActionCall]:
        """A variable assigned once, then whatever ``.append``/``.add_action`` adds to it."""
        binding = context.scope.constant(expr.value)
        if binding is None or binding.value is None or binding.context is None:
            argument = self.parameter(Written(expr, context))  # def group(actions): ...
            return [] if argument is None else self.actions(argument, depth + 1)
        found = self.actions(Written(binding.value, binding.context), depth + 1)
        only = found[0] if len(found) == 1 else None
        if only is not None and only.call is binding.value and only.kind is Action.DESCRIPTION:
            return found  # what ld.add_action adds are its children: see visit_added
        for added in self.adders.get((id(binding.scope), expr.value), []):
            found += self.actions(added, depth + 1)
        return found

    def call_actions(self, call: cst.Call, context: Context, depth: int) -> list[ActionCall]:
        kind = self.action_kind(call, context.scope)
        if kind is not None:
            return [ActionCall(kind, call, context, self.frames)]
        function = defined_function(call.func, context.scope)
        if function is None:
            return []  # another module's helper: what it builds is walked as unreached
        frame = self.call_frame(function, call, context)
        saved = self.frames
        self.frames = saved if frame is None else (*saved, frame)
        try:
            found: list[ActionCall] = []
            for value, returned in self.walk.returns.get(function, []):
                found += self.actions(Written(value, returned), depth + 1)
        finally:
            self.frames = saved
        return found

    def call_frame(
        self, function: cst.FunctionDef, call: cst.Call, context: Context
    ) -> CallFrame | None:
        """The arguments of a call of the file's function, by parameter; defaults for the
        rest. None for a function without parameters: nothing differs between calls."""
        scope = self.walk.function_scopes.get(function)
        params = function.params
        positional = [*params.posonly_params, *params.params]
        if scope is None or not (positional or params.kwonly_params):
            return None
        found: dict[str, Written] = {}
        index = 0
        for item in call.args:
            if item.star:
                break  # positions after *args (and what **kwargs holds) are unknown
            written = Written(item.value, argument_context(call, context, item.value))
            if item.keyword is not None:
                found[item.keyword.value] = written
            elif index < len(positional):
                found[positional[index].name.value] = written
                index += 1
        outside = Context(scope.parent or scope)  # defaults run where the def is
        for param in (*positional, *params.kwonly_params):
            if param.name.value not in found and param.default is not None:
                found[param.name.value] = Written(param.default, outside)
        return CallFrame(scope, call, found)

    def parameter(self, located: Written) -> Written | None:
        """What a parameter of a function being called is bound to, when it is one."""
        if not isinstance(located.expr, cst.Name):
            return None
        bindings = located.scope.lookup(located.expr.value)
        if len(bindings) != 1 or bindings[0].value is not None:
            return None
        for frame in reversed(self.frames):
            if frame.scope is bindings[0].scope:
                return frame.parameters.get(located.expr.value)
        return None

    def children(self, action: ActionCall, where: str) -> list[ActionCall]:
        located = action.get(where)
        return [] if located is None else self.actions(located)

    # -- values -------------------------------------------------------------------------

    def items(self, located: Written, depth: int = 0) -> list[Written]:
        """The elements of a list or tuple, through variables, ``+`` and ``*starred``."""
        expr = located.expr
        if depth > _MAX_DEPTH:
            return []
        if isinstance(expr, cst.List | cst.Tuple):
            found: list[Written] = []
            for element in expr.elements:
                inner = Written(element.value, located.context.inside(element))
                found += (
                    self.items(inner, depth + 1)
                    if isinstance(element, cst.StarredElement)
                    else [inner]
                )
            return found
        if isinstance(expr, cst.BinaryOperation) and isinstance(expr.operator, cst.Add):
            left = self.items(Written(expr.left, located.context), depth + 1)
            return left + self.items(Written(expr.right, located.context), depth + 1)
        bound = self.bound(located)
        return [] if bound is None else self.items(bound, depth + 1)

    def dictionary(self, located: Written) -> Written | None:
        if isinstance(located.expr, cst.Dict):
            return located
        bound = self.bound(located)
        return None if bound is None else self.dictionary(bound)

    def pairs(self, located: Written) -> list[tuple[Written, Written]]:
        """Key and value of a dict literal, ``{...}.items()`` or a list of 2-tuples."""
        expr = located.expr
        if (
            isinstance(expr, cst.Call)
            and isinstance(expr.func, cst.Attribute)
            and expr.func.attr.value == "items"
        ):
            return self.pairs(Written(expr.func.value, located.context))
        dictionary = self.dictionary(located)
        if dictionary is not None:
            assert isinstance(dictionary.expr, cst.Dict)
            return [
                (
                    Written(element.key, dictionary.context.inside(element)),
                    Written(element.value, dictionary.context.inside(element)),
                )
                for element in dictionary.expr.elements
                if isinstance(element, cst.DictElement)
            ]
        found = []
        for item in self.items(located):
            if isinstance(item.expr, cst.Tuple) and len(item.expr.elements) == 2:
                key, value = item.expr.elements
                inside = item.context.inside(item.expr)
                found.append(
                    (
                        Written(key.value, inside.inside(key)),
                        Written(value.value, inside.inside(value)),
                    )
                )
        return found

    def bound(self, located: Written) -> Written | None:
        """What a variable assigned once holds, where it is written; what a parameter of
        a function being called is given."""
        if not isinstance(located.expr, cst.Name):
            return None
        binding = located.scope.constant(located.expr.value)
        if binding is None or binding.value is None or binding.context is None:
            return self.parameter(located)
        return Written(binding.value, binding.context)

    def is_text(self, located: Written) -> bool:
        """A string (or parts of one): not ``True``, a number, or a list of frames."""
        return not isinstance(located.expr, cst.Integer | cst.Float | cst.Dict)

    def value(self, located: Written, scope: LaunchScope, depth: int = 0) -> Value:
        text = self.text(located, scope, depth)
        return Value(self.locator.code(located.expr), dynamic=True) if text is None else Value(text)

    def static(self, located: Written | None, scope: LaunchScope) -> str | None:
        if located is None:
            return None
        value = self.value(located, scope)
        return None if value.dynamic else value.text

    def text(self, located: Written, scope: LaunchScope, depth: int) -> str | None:
        """launch's ``perform_substitutions`` when it needs nothing from the run."""
        expr = located.expr
        if depth > _MAX_DEPTH:
            return None
        folded = self.folder.static(expr, located.scope)
        if folded is not None:
            return folded
        if isinstance(expr, cst.List | cst.Tuple):
            parts = [
                self.text(Written(e.value, located.context), scope, depth + 1)
                for e in expr.elements
            ]
            return None if any(part is None for part in parts) else "".join(p for p in parts if p)
        if isinstance(expr, cst.Call):
            return self.substitution(Written(expr, located.context), scope, depth)
        pieces = string_parts(located)  # what the folder could not: a parameter inside
        if pieces is not None:
            texts = [p if isinstance(p, str) else self.text(p, scope, depth + 1) for p in pieces]
            return None if any(text is None for text in texts) else "".join(map(str, texts))
        bound = self.bound(located)
        return None if bound is None else self.text(bound, scope, depth + 1)

    def substitution(self, located: Written, scope: LaunchScope, depth: int) -> str | None:
        """``TextSubstitution(text=...)`` and ``LaunchConfiguration(name, default=...)``."""
        call = located.expr
        assert isinstance(call, cst.Call)
        names = {class_key(name) for name in located.scope.qualified(call.func)}
        if _TEXT in names:
            text = call_argument(call, located.context, "0:text")
            return None if text is None else self.text(text, scope, depth + 1)
        if _CONFIGURATION not in names:
            return None
        name_at = call_argument(call, located.context, "0:variable_name")
        name = None if name_at is None else self.text(name_at, scope, depth + 1)
        if name is None:
            return None
        if name in scope.variables:
            value = scope.variables[name]
            return None if value.dynamic else value.text
        declared = self.declared(name, scope, depth)
        if declared is not None:
            return declared
        default = call_argument(call, located.context, "1:default")
        return None if default is None else self.text(default, scope, depth + 1)

    def declarations(self, name: str) -> list[Written | None]:
        """The default of every ``DeclareLaunchArgument`` of ``name`` (None: no default)."""
        return self._declarations.get(name, [])

    def configurations(self, scope: LaunchScope) -> dict[str, Value]:
        """Every launch configuration ``scope`` sees: declared defaults, then what the
        scope set (a group's ``launch_configurations``, ``SetLaunchConfiguration``, an
        include's arguments), which wins; dynamic values included, as they hide defaults."""
        found: dict[str, Value] = {}
        for name in self._declarations:
            declared = self.declared(name, scope, 0)
            if declared is not None:
                found[name] = Value(declared)
        found.update(scope.variables)
        return found

    def declared(self, name: str, scope: LaunchScope, depth: int) -> str | None:
        """The default every ``DeclareLaunchArgument(name, default_value=...)`` agrees on."""
        declarations = self._declarations.get(name, [])
        if not declarations or name in self._resolving:
            return None
        self._resolving.add(name)
        try:
            values = {None if d is None else self.text(d, scope, depth + 1) for d in declarations}
        finally:
            self._resolving.discard(name)
        return values.pop() if len(values) == 1 else None


def string_parts(located: Written) -> list[Written | str] | None:
    """The parts of ``a + b`` or of an f-string, in order; None for anything else, or for
    f-string formatting (a format spec, a conversion, escapes, braces) not reproduced."""
    expr = located.expr
    if isinstance(expr, cst.BinaryOperation) and isinstance(expr.operator, cst.Add):
        return [Written(expr.left, located.context), Written(expr.right, located.context)]
    if not isinstance(expr, cst.FormattedString):
        return None
    parts: list[Written | str] = []
    for part in expr.parts:
        if isinstance(part, cst.FormattedStringText):
            if any(mark in part.value for mark in "\\{}"):
                return None
            parts.append(part.value)
        elif not isinstance(part, cst.FormattedStringExpression) or (
            part.format_spec or part.equal or part.conversion not in (None, "s")
        ):
            return None
        else:
            parts.append(Written(part.expression, located.context))
    return parts


def action_kind(call: cst.Call, scope: Scope) -> Action | None:
    for name in scope.qualified(call.func):
        if class_key(name) in _ACTIONS:
            return _ACTIONS[class_key(name)]
    return None


def class_key(name: str) -> tuple[str, str]:
    """(package, last component) of a qualified name: how launch classes are matched."""
    return name.split(".", 1)[0], name.rpartition(".")[2]


def defined_function(func: cst.BaseExpression, scope: Scope) -> cst.FunctionDef | None:
    if not isinstance(func, cst.Name):
        return None
    bindings = scope.lookup(func.value)
    if len(bindings) == 1 and isinstance(bindings[0].defined, cst.FunctionDef):
        return bindings[0].defined
    return None


def _adder_calls(walk: Walk) -> dict[tuple[int, str], list[Written]]:
    """``x.append(a)``, ``x.extend(b)``, ``ld.add_action(c)`` per variable, in order."""
    found: dict[tuple[int, str], list[Written]] = {}
    for site in walk.calls:
        func = site.call.func
        if not (isinstance(func, cst.Attribute) and isinstance(func.value, cst.Name)):
            continue
        if func.attr.value not in _ADDERS or not site.call.args:
            continue
        bindings = site.context.scope.lookup(func.value.value)
        if len(bindings) != 1:
            continue
        inner = site.context.inside(site.call)
        added = Written(site.call.args[0].value, inner)
        found.setdefault((id(bindings[0].scope), func.value.value), []).append(added)
    return found


def _declarations(walk: Walk) -> dict[str, list[Written | None]]:
    """Every ``DeclareLaunchArgument`` default of the file, by argument name."""
    found: dict[str, list[Written | None]] = {}
    for site in walk.calls:
        names = site.context.scope.qualified(site.call.func)
        if not any(class_key(name) == ("launch", "DeclareLaunchArgument") for name in names):
            continue
        name = call_argument(site.call, site.context, "0:name")
        if name is None or not isinstance(name.expr, cst.SimpleString):
            continue
        literal = string_literal(name.expr)
        if literal is not None:
            default = call_argument(site.call, site.context, "1:default_value")
            found.setdefault(literal, []).append(default)
    return found
