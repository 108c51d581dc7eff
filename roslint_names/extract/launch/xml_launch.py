"""Launch XML: ROS 1 roslaunch files (``.launch``, ``.test``) and ROS 2 launch XML.

Both generations share one shape, an action tree of entities with attributes, so the
walkers below work on a small ``Entity`` protocol; ``launch_yaml`` feeds the ROS 2 walker
the same entities read from YAML, exactly as launch's own frontends do.

Which syntax a file uses (``<group ns>`` and ``$(arg)`` vs ``<push-ros-namespace>`` and
``$(var)``) comes from its own markers first: a ROS 1 launch file inside an ament package
is still read as ROS 1, while the generation its names are judged by comes from the
package first (see ``evidence``).

Namespaces on the facts: a node's ``ns``/``namespace`` attribute, a group's and a pushed
namespace carry the namespace enclosing them; a node's name, remaps and command-line names
carry the node's namespace; its parameters carry the node's full name (that is where
they live). ``None`` when the namespace depends on something dynamic.

Includes become ``LaunchInclude`` facts (where the file is: ``launch_include``); the
workspace model then extracts the included file again with ``extract(arguments=...)``,
the values the include hands over, to get its nodes as this includer starts them.
"""

from __future__ import annotations

import functools
from abc import ABC, abstractmethod
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Protocol

from lxml import etree

from roslint_names.extract import evidence
from roslint_names.extract.launch import static_transform, xmlsafe
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
from roslint_names.extract.launch.include import (
    UNKNOWN,
    handed_over,
    in_package,
    locate,
    package_text,
    passed_values,
)
from roslint_names.extract.launch.substitution import (
    ARG,
    Assignment,
    Bindings,
    Condition,
    Declaration,
    Dialect,
    Located,
    Lookup,
    Meaning,
    Value,
    mapping_lookup,
    meaning,
    ros1_assignments,
    ros2_assignments,
    skipped,
    split_words,
    strip_node_prefix,
    substitute,
    truth,
)
from roslint_names.model import (
    FileFacts,
    Generation,
    InPackage,
    Language,
    LaunchArguments,
    LaunchInclude,
    LaunchNode,
    NameUse,
    ParameterLoad,
    ParseError,
    Remap,
    Span,
)

# ---------------------------------------------------------------------------------------
# Entities: what the walkers see of XML elements and YAML mappings


class Entity(Protocol):
    """One launch action or description, as launch's frontends model it."""

    @property
    def kind(self) -> str:
        """The tag (XML) or key (YAML): "node", "group", "remap"..."""
        ...

    def get(self, name: str) -> Located | None:
        """A scalar attribute, or None when absent."""
        ...

    def children(self) -> list[Entity]:
        """Child actions of a container (``<group>``, ``<launch>``)."""
        ...

    def nested(self, name: str) -> list[Entity]:
        """Sub-entities of one kind: a node's ``remap``s, ``param``s, ``composable_node``s."""
        ...

    def span(self) -> Span:
        """Where the entity starts, for facts that have no attribute to point at."""
        ...

    def api(self, attribute: str) -> str:
        """How messages name the attribute: ``<node name>`` or ``node: name``."""
        ...

    def content(self) -> Located | None:
        """The text inside the element, as written (XML; None in YAML and when blank)."""
        ...


class XmlEntity:
    """An lxml element seen as an ``Entity``.

    Its attributes and children are read once and kept: a walk asks for the same ones
    many times (``if``, ``unless``, ``name``...), and the entities of a file extracted
    under several includers' arguments are shared by those extractions (``_parsed``).
    """

    def __init__(self, document: xmlsafe.XmlDocument, element: etree._Element) -> None:
        self._document = document
        self._element = element
        self._kind = etree.QName(element).localname
        self._attributes: dict[str, Located | None] = {}
        self._children: list[Entity] | None = None

    @property
    def kind(self) -> str:
        return self._kind

    def get(self, name: str) -> Located | None:
        try:
            return self._attributes[name]
        except KeyError:
            found = self._attributes[name] = self._document.attribute(self._element, name)
            return found

    def children(self) -> list[Entity]:
        if self._children is None:
            self._children = [
                XmlEntity(self._document, child)
                for child in self._element
                if isinstance(child.tag, str)
            ]
        return self._children

    def nested(self, name: str) -> list[Entity]:
        return [child for child in self.children() if child.kind == name]

    def span(self) -> Span:
        return self._document.tag_span(self._element)

    def api(self, attribute: str) -> str:
        return f"<{self.kind} {attribute}>"

    def content(self) -> Located | None:
        return self._document.text(self._element, strip=False)


# ---------------------------------------------------------------------------------------
# Helpers shared by both generations (the parser-free ones live in launch_common)


def absolute_namespace(value: Value) -> str | None:
    """``__ns:=x`` replaces the namespace outright; roscpp and rcl make it absolute."""
    return join_namespace("/", value)


def is_absolute(value: Value) -> bool:
    """A namespace written absolute; a dynamic one only if its raw text starts with '/'."""
    return value.text.startswith("/")


@dataclass
class Scope:
    """What a launch action sees: its namespace, the remaps in force and the variables.

    ROS 1 arguments are file-global (``lookup`` reads one ``Bindings``); ROS 2 ``<let>``
    and ``<arg>`` are visible after their declaration and ``<group>`` scopes them, so each
    ROS 2 scope has its own ``variables``. ``anchored``: this file made ``namespace``
    absolute, so the namespace an includer pushes does not prefix it.
    """

    namespace: str | None
    remaps: list[Remap] = field(default_factory=list)
    variables: dict[str, Value] = field(default_factory=dict)
    global_lookup: Lookup | None = None
    anchored: bool = False
    conditional: bool = False  # inside a group whose condition is not statically known
    # Inside what a condition statically drops (``if="false"`` under the arguments in
    # force): its names are still checked, but it starts and includes nothing.
    inactive: bool = False

    @property
    def lookup(self) -> Lookup:
        return self.global_lookup or mapping_lookup(self.variables)

    def copy(self) -> Scope:
        return Scope(
            self.namespace,
            list(self.remaps),
            dict(self.variables),
            self.global_lookup,
            self.anchored,
            self.conditional,
            self.inactive,
        )

    def enter(self, value: Value) -> None:
        """Push a namespace (ROS 1 group ns, ROS 2 push-ros-namespace) onto this scope."""
        self.namespace = join_namespace(self.namespace, value)
        self.anchored = self.anchored or is_absolute(value)


@dataclass(frozen=True)
class NodeSpec:
    """The attributes one kind of node entity uses."""

    namespace_attribute: str  # "ns" in ROS 1, "namespace" in ROS 2
    executable_attribute: str  # "type", "exec" or "plugin"


@dataclass(frozen=True)
class CommandLineName:
    """An assignment from a node's command line, substituted."""

    meaning: Meaning
    api: str
    key_at: Located  # where the key is written
    key: Value
    value_at: Located
    value: Value


class LaunchWalker(ABC):
    """State and helpers common to the ROS 1 and ROS 2 walkers; facts accumulate here."""

    dialect: Dialect

    def __init__(self) -> None:
        self.names: list[NameUse] = []
        self.nodes: list[LaunchNode] = []
        self.includes: list[LaunchInclude] = []
        self.loads: list[ParameterLoad] = []  # ROS 1 ``<rosparam load>`` outside nodes
        self.node_files: list[ParameterLoad] = []  # of the node being read

    def parameter_file(
        self, entity: Entity, attribute: str, scope: Scope, namespace: str = ""
    ) -> ParameterLoad | None:
        """The parameter file ``attribute`` names, located as an include's file is
        (``include.locate``); None where the entity names none or is inactive."""
        located = entity.get(attribute)
        if located is None or located.opaque or scope.inactive:
            return None
        target = locate(located.text, self.dialect, scope.lookup)
        conditional = scope.conditional or self.undecided(entity, scope)
        return ParameterLoad(
            target.package, target.path, located.span, namespace, conditional=conditional
        )

    # -- values and facts ---------------------------------------------------------------

    def value(self, located: Located, scope: Scope) -> Value:
        if located.opaque:
            return Value(located.text, dynamic=True)
        return substitute(located.text, self.dialect, scope.lookup)

    def emit(
        self,
        fact: Fact,
        api: str,
        located: Located,
        value: Value,
        namespace: str | None,
    ) -> None:
        self.names.append(
            NameUse(
                kind=fact.kind,
                value=value.text,
                span=located.span,
                role=fact.role,
                api=api,
                dynamic=value.dynamic,
                namespace=namespace,
            )
        )

    def attribute(
        self,
        entity: Entity,
        name: str,
        scope: Scope,
        fact: Fact,
        namespace: str | None,
    ) -> Value | None:
        """Emit the attribute as a name; its value, or None when absent."""
        located = entity.get(name)
        if located is None:
            return None
        value = self.value(located, scope)
        self.emit(fact, entity.api(name), located, value, namespace)
        return value

    def static(self, entity: Entity, name: str, scope: Scope) -> str | None:
        """A non-name attribute (pkg, exec) when statically known."""
        located = entity.get(name)
        value = None if located is None else self.value(located, scope)
        return None if value is None or value.dynamic else value.text

    def undecided(self, entity: Entity, scope: Scope) -> bool:
        """An ``if``/``unless`` whose outcome is not statically known."""
        if_attr, unless_attr = entity.get("if"), entity.get("unless")
        return (if_attr is not None and truth(self.value(if_attr, scope)) is not True) or (
            unless_attr is not None and truth(self.value(unless_attr, scope)) is not False
        )

    def branch(self, entity: Entity, scope: Scope) -> Scope:
        """The scope to read ``entity`` in: ``scope``, or an inactive copy of it when a
        condition statically drops the entity. Per-file rules see every name of every
        branch; the graph sees only what the arguments in force start."""
        if scope.inactive or not self.skipped(entity, scope):
            return scope
        inactive = scope.copy()
        inactive.inactive = True
        return inactive

    def skipped(self, entity: Entity, scope: Scope) -> bool:
        if_attr, unless_attr = entity.get("if"), entity.get("unless")
        return skipped(
            None if if_attr is None else self.value(if_attr, scope),
            None if unless_attr is None else self.value(unless_attr, scope),
        )

    # -- remaps and parameters ----------------------------------------------------------

    def remap(self, entity: Entity, scope: Scope, namespace: str | None) -> Remap | None:
        """``<remap from to>``: both names, and the remap when both are static."""
        source, target = entity.get("from"), entity.get("to")
        source_value = self.attribute(entity, "from", scope, REMAP_FROM, namespace)
        target_value = self.attribute(entity, "to", scope, REMAP_TO, namespace)
        return _static_remap(source, source_value, target_value, target)

    def frame_value(
        self,
        entity: Entity,
        scope: Scope,
        parameter: Value,
        namespace: str | None,
    ) -> None:
        """A frame-like parameter's value is a tf2 frame id."""
        if parameter.dynamic or not is_frame_parameter(parameter.text):
            return
        self.attribute(entity, "value", scope, FRAME, namespace)

    # -- nodes --------------------------------------------------------------------------

    @abstractmethod
    def command_line(self, entity: Entity, scope: Scope) -> list[CommandLineName]:
        """The node's ``a:=b`` arguments (per generation)."""

    @abstractmethod
    def node_contents(
        self, entity: Entity, scope: Scope, namespace: str | None, path: str | None
    ) -> tuple[list[Remap], list[tuple[str, Span]]]:
        """Emit the node's own remaps and parameters; return the static ones (each
        parameter with where its name is written)."""

    def node(self, entity: Entity, scope: Scope, spec: NodeSpec) -> None:
        """A node: its names, then one ``LaunchNode`` with its scope."""
        inner = Scope(scope.namespace, anchored=scope.anchored)  # the node's own namespace
        namespace_value = self.attribute(
            entity, spec.namespace_attribute, scope, NAMESPACE, inner.namespace
        )
        if namespace_value is not None:
            inner.enter(namespace_value)
        arguments = self.command_line(entity, scope)
        for argument in arguments:
            if argument.meaning is Meaning.NAMESPACE:
                inner.namespace, inner.anchored = absolute_namespace(argument.value), True
        namespace = inner.namespace
        name_attribute = entity.get("name")
        name_value = self.attribute(entity, "name", scope, NODE, namespace)
        name = _node_name(name_value, arguments)
        test_name = self.test_node_name(entity, scope) if name_attribute is None else None
        if test_name is not None:
            name = None if test_name.dynamic else test_name.text
        path = node_path(namespace, name)
        line_remaps, line_parameters = self.command_line_names(arguments, namespace, path)
        self.node_files = []
        child_remaps, child_parameters = self.node_contents(entity, scope, namespace, path)
        files = tuple(self.node_files)
        self.broadcast_frames(entity, scope, spec, path)
        own_remaps = child_remaps + line_remaps
        if scope.inactive:
            return
        self.nodes.append(
            LaunchNode(
                package=self.static(entity, "pkg", scope),
                executable=self.static(entity, spec.executable_attribute, scope),
                name=name,
                namespace="" if namespace is None else namespace,
                span=entity.span() if name_attribute is None else name_attribute.span,
                remaps=tuple(scope.remaps + own_remaps),
                parameters=tuple(name for name, _ in child_parameters + line_parameters),
                parameter_spans=tuple(span for _, span in child_parameters + line_parameters),
                own_remaps=len(own_remaps),
                anchored=inner.anchored,
                conditional=scope.conditional or self.undecided(entity, scope),
                dynamic_name=name is None
                and (test_name is not None or _names_node(name_value, arguments)),
                test=entity.kind == "test",
                parameter_files=files,
            )
        )

    def test_node_name(self, entity: Entity, scope: Scope) -> Value | None:
        """A ROS 1 ``<test>`` without a name runs as its ``test-name``: roslaunch's
        ``XmlLoader._node_tag`` takes ``name = test_name`` and passes ``__name:=`` with it."""
        if entity.kind != "test" or self.dialect is not Dialect.ROS1:
            return None
        located = entity.get("test-name")
        return None if located is None else self.value(located, scope)

    def broadcast_frames(
        self, entity: Entity, scope: Scope, spec: NodeSpec, path: str | None
    ) -> None:
        """The two frames a static transform publisher is given in ``args``."""
        which = static_transform.program(
            self.static(entity, "pkg", scope),
            self.static(entity, spec.executable_attribute, scope),
            ros1=self.dialect is Dialect.ROS1,
        )
        located = entity.get("args")
        if which is None or located is None or located.opaque:
            return
        words = self.program_words(located, scope)
        for frame in static_transform.frames(which, [value.text for _, value in words]):
            at, value = words[frame.index]
            self.emit(FRAME, frame.api, at, value, path)

    def program_words(self, located: Located, scope: Scope) -> list[tuple[Located, Value]]:
        """The words of ``args`` as the program gets them, each with where it is written.

        launch's frontends split the attribute into words first and substitute each word
        alone (a substitution stays within its word); the ROS 1 walker substitutes, then
        splits (see ``Ros1Launch.program_words``)."""
        return [(word, self.value(word, scope)) for word in split_words(located)]

    # -- includes -----------------------------------------------------------------------

    @abstractmethod
    def include_arguments(self, entity: Entity, scope: Scope) -> LaunchArguments:
        """The statically known values the include hands over (per generation)."""

    def include(self, entity: Entity, scope: Scope, namespace_attribute: str | None) -> None:
        """An include: where the file is, the namespace and remaps it gets, its arguments.

        Emitted even when the file is not statically known: its namespace and arguments
        still tell the workspace model something, and a later resolver may know more.
        """
        inner = Scope(scope.namespace, anchored=scope.anchored)
        if namespace_attribute is not None:
            value = self.attribute(entity, namespace_attribute, scope, NAMESPACE, inner.namespace)
            if value is not None:
                inner.enter(value)
        located = entity.get("file")
        if scope.inactive:
            return
        target = UNKNOWN
        if located is not None and not located.opaque:  # opaque: unexpanded entities
            target = locate(located.text, self.dialect, scope.lookup)
        self.includes.append(
            LaunchInclude(
                package=target.package,
                path=target.path,
                namespace="" if inner.namespace is None else inner.namespace,
                span=entity.span() if located is None else located.span,
                arguments=self.include_arguments(entity, scope),
                remaps=tuple(scope.remaps),
                anchored=inner.anchored,
                conditional=scope.conditional or self.undecided(entity, scope),
            )
        )

    def explicit_arguments(
        self, entity: Entity, scope: Scope, attributes: Sequence[str]
    ) -> dict[str, str | InPackage | None]:
        """An include's ``<arg name value>`` children: name to static value, or the
        package's file it names, else None (unknown).

        ``attributes`` are where the value may be, first found wins.
        """
        found: dict[str, str | InPackage | None] = {}
        for child in entity.nested("arg"):
            name = child.get("name")
            given = next((v for v in map(child.get, attributes) if v is not None), None)
            if name is None or given is None or self.skipped(child, scope):
                continue
            found[name.text] = self.handed(self.value(given, scope), scope.lookup)
        return found

    def handed(self, value: Value, lookup: Lookup) -> str | InPackage | None:
        """What an include hands over of a value of this file."""
        if not value.dynamic:
            return value.text
        return in_package(value.text, self.dialect, lookup)

    def command_line_names(
        self, arguments: Sequence[CommandLineName], namespace: str | None, path: str | None
    ) -> tuple[list[Remap], list[tuple[str, Span]]]:
        """Emit the names a node's command line sets; the static remaps and parameters."""
        remaps: list[Remap] = []
        parameters: list[tuple[str, Span]] = []
        for argument in arguments:
            api, key, value = argument.api, argument.key, argument.value
            if argument.meaning is Meaning.NODE:
                self.emit(NODE, api, argument.value_at, value, namespace)
            elif argument.meaning is Meaning.NAMESPACE:
                self.emit(NAMESPACE, api, argument.value_at, value, "/")  # made absolute
            elif argument.meaning is Meaning.REMAP:
                self.emit(REMAP_FROM, api, argument.key_at, key, namespace)
                self.emit(REMAP_TO, api, argument.value_at, value, namespace)
                remap = _static_remap(argument.key_at, key, value, argument.value_at)
                remaps.extend([remap] if remap else [])
            elif argument.meaning is Meaning.PARAMETER:
                self.emit(PARAMETER, api, argument.key_at, key, path)
                parameters.extend([] if key.dynamic else [(key.text, argument.key_at.span)])
                if not key.dynamic and is_frame_parameter(key.text):
                    self.emit(FRAME, api, argument.value_at, value, path)
            elif argument.meaning is Meaning.PRIVATE_PARAMETER and not key.dynamic:
                # ROS 1 _rate:=10 sets ~rate
                parameters.append((key.text[1:], argument.key_at.span))
        return remaps, parameters

    def substitute_assignments(
        self, assignments: Sequence[Assignment], api: str, scope: Scope
    ) -> list[CommandLineName]:
        """Substitute both sides of each ``key:=value`` and tell what it sets."""
        found = []
        for assignment in assignments:
            key = assignment.key
            if assignment.flag == "-r":
                key = strip_node_prefix(key)
            key_value = self.value(key, scope)
            what = meaning(assignment.flag, key_value.text, self.dialect)
            if what is not None:
                value = self.value(assignment.value, scope)
                found.append(CommandLineName(what, api, key, key_value, assignment.value, value))
        return found


def _node_name(attribute: Value | None, arguments: Sequence[CommandLineName]) -> str | None:
    """The name attribute; else ``__name:=``/``__node:=`` from the command line."""
    if attribute is not None:
        return None if attribute.dynamic else attribute.text
    for argument in arguments:
        if argument.meaning is Meaning.NODE and not argument.value.dynamic:
            return argument.value.text
    return None


def _names_node(attribute: Value | None, arguments: Sequence[CommandLineName]) -> bool:
    """Whether the file gives the node a name (static or not)."""
    return attribute is not None or any(a.meaning is Meaning.NODE for a in arguments)


def _static_remap(
    source: Located | None,
    source_value: Value | None,
    target_value: Value | None,
    target: Located | None,
) -> Remap | None:
    """A remap for ``LaunchNode``; dynamic ones are left out rather than guessed."""
    if source is None or source_value is None or target_value is None:
        return None
    if source_value.dynamic or target_value.dynamic:
        return None
    target_span = target.span if target is not None else None
    return Remap(source_value.text, target_value.text, source.span, target_span)


# ---------------------------------------------------------------------------------------
# ROS 1


_ROS1_NODE = NodeSpec(namespace_attribute="ns", executable_attribute="type")
_ROS1_IGNORED = frozenset({"arg", "machine", "env", "master"})


class Ros1Launch(LaunchWalker):
    """roslaunch's tags: node, test, group ns, remap, param, rosparam, include, arg.

    ``arguments`` are the values an including file passes: they take the place of the
    defaults of the arguments this file declares (``_declare_arguments``).
    """

    dialect = Dialect.ROS1

    def __init__(self, root: Entity, arguments: LaunchArguments = ()) -> None:
        super().__init__()
        self.bindings = Bindings(Dialect.ROS1)
        self.declared: dict[str, None] = {}  # the file's argument names, in order
        _declare_arguments(
            root.children(), _Declaring(self.bindings, _ros1_passed(arguments), self.declared), ()
        )

    def run(self, root: Entity) -> None:
        self.walk(root.children(), Scope("/", global_lookup=self.bindings.lookup))

    def walk(self, entities: Sequence[Entity], parent: Scope) -> None:
        scope = parent.copy()  # remaps declared here stay in this group
        for entity in entities:
            here = self.branch(entity, scope)  # an inactive copy leaks nothing to scope
            kind = entity.kind
            if kind == "group":
                self.group(entity, here)
            elif kind in ("node", "test"):
                self.node(entity, here, _ROS1_NODE)
            elif kind == "remap":
                remap = self.remap(entity, here, here.namespace)
                here.remaps.extend([remap] if remap else [])
            elif kind == "param":
                self.param(entity, here, here.namespace)
            elif kind == "rosparam":
                self.rosparam(entity, here, here.namespace)
                self.group_load(entity, here)
            elif kind == "include":
                self.include(entity, here, "ns")
            elif kind not in _ROS1_IGNORED:
                self.walk(entity.children(), here)

    def group(self, entity: Entity, scope: Scope) -> None:
        inner = scope.copy()
        inner.conditional = scope.conditional or self.undecided(entity, scope)
        value = self.attribute(entity, "ns", scope, NAMESPACE, scope.namespace)
        if value is not None:
            inner.enter(value)
        self.walk(entity.children(), inner)

    def include_arguments(self, entity: Entity, scope: Scope) -> LaunchArguments:
        """``<arg>`` children (roslaunch passes a ``default`` there too) and, with
        ``pass_all_args``, every argument of this file; the children win."""
        explicit = self.explicit_arguments(entity, scope, ("value", "default"))
        pass_all = entity.get("pass_all_args")
        if pass_all is None or truth(self.value(pass_all, scope)) is not True:
            return handed_over({}, explicit)
        inherited = {name: self._handed_argument(name) for name in self.declared}
        return handed_over(inherited, explicit)

    def _handed_argument(self, name: str) -> str | InPackage | None:
        value = self.bindings.lookup(ARG, name)
        return None if value is None else self.handed(value, self.bindings.lookup)

    def param(self, entity: Entity, scope: Scope, namespace: str | None) -> tuple[str, Span] | None:
        """``<param name value>``: the name, and the value when the name is frame-like."""
        name = self.attribute(entity, "name", scope, PARAMETER, namespace)
        written = entity.get("name")
        if name is None or written is None:
            return None
        self.frame_value(entity, scope, name, namespace)
        return None if name.dynamic else (name.text, written.span)

    def rosparam(
        self, entity: Entity, scope: Scope, namespace: str | None
    ) -> tuple[str, Span] | None:
        """``<rosparam ns param>``: the parameter lives in ``ns`` below the enclosing one."""
        ns = self.attribute(entity, "ns", scope, NAMESPACE, namespace)
        inner = namespace if ns is None else join_namespace(namespace, ns)
        param = self.attribute(entity, "param", scope, PARAMETER, inner)
        written = entity.get("param")
        if param is None or written is None or param.dynamic or (ns is not None and ns.dynamic):
            return None
        name = param.text if ns is None or not ns.text else f"{ns.text.rstrip('/')}/{param.text}"
        return name, written.span

    def inline_parameters(self, entity: Entity, scope: Scope) -> list[tuple[str, Span]]:
        """``<rosparam>`` holding YAML inside a node and naming no ``param``: each leaf
        of its mapping is a parameter of the node (below ``ns``), its keys joined with
        '/' (roslaunch ``xmlloader.py``, ``_rosparam_tag``, then ``Loader.load_rosparam``
        with the text ``yaml.safe_load`` reads). Keys that ``subst_value`` would
        substitute are not known: such a tag gives nothing."""
        command = self.static(entity, "command", scope) if entity.get("command") else "load"
        if command != "load" or entity.get("file") is not None or entity.get("param"):
            return []
        content = entity.content()
        if content is None or content.opaque:
            return []
        substituted = entity.get("subst_value")
        if substituted is not None and "$(" in content.text:
            return []
        ns = entity.get("ns")
        prefix = ""
        if ns is not None:
            value = self.value(ns, scope)
            if value.dynamic:
                return []
            prefix = value.text.strip("/")
        from roslint_names.extract.parameter_file import inline_names  # PyYAML on first use

        return [
            (f"{prefix}/{name}" if prefix else name, span) for name, span in inline_names(content)
        ]

    def loaded_namespace(self, entity: Entity, scope: Scope) -> str | None:
        """Where ``<rosparam command="load" file>`` puts the file's names, relative to
        where the tag is: ``ns_join(ns, param)`` (roslaunch ``xmlloader.py``,
        ``_rosparam_tag``); None when the tag loads no file or the place is dynamic."""
        command = self.static(entity, "command", scope) if entity.get("command") else "load"
        if command != "load" or entity.get("file") is None:
            return None
        parts: list[str] = []
        for attribute in ("ns", "param"):
            written = entity.get(attribute)
            value = self.static(entity, attribute, scope)
            if written is not None and value is None:
                return None
            parts.append(value or "")
        joined = "/".join(part.strip("/") for part in parts if part.strip("/"))
        return f"/{joined}" if parts[0].startswith("/") else joined

    def node_load(self, entity: Entity, scope: Scope) -> None:
        """``<rosparam load>`` inside a node: below the node's private namespace."""
        namespace = self.loaded_namespace(entity, scope)
        found = None if namespace is None else self.parameter_file(entity, "file", scope, namespace)
        self.node_files.extend([found] if found else [])

    def group_load(self, entity: Entity, scope: Scope) -> None:
        """``<rosparam load>`` outside nodes: below the group's namespace."""
        relative = self.loaded_namespace(entity, scope)
        if relative is None or scope.namespace is None:
            return
        namespace = join_namespace(scope.namespace, Value(relative))
        found = self.parameter_file(entity, "file", scope)
        if found is not None and namespace is not None:
            anchored = scope.anchored or relative.startswith("/")
            self.loads.append(replace(found, namespace=namespace, anchored=anchored))

    def command_line(self, entity: Entity, scope: Scope) -> list[CommandLineName]:
        args = entity.get("args")
        if args is None or args.opaque:
            return []
        return self.substitute_assignments(ros1_assignments(args), entity.api("args"), scope)

    def program_words(self, located: Located, scope: Scope) -> list[tuple[Located, Value]]:
        """roslaunch substitutes ``args`` whole, then splits it with ``shlex.split``
        (``create_local_process_args`` in roslaunch's node_args.py): an argument holding
        several words gives several. Quotes, which shlex would pair up, are not
        reproduced: such a command line gives no words. A substitution the linter cannot
        know counts as one word."""
        if any(quote in located.text for quote in "'\""):
            return []
        found: list[tuple[Located, Value]] = []
        for word in split_words(located):
            value = self.value(word, scope)
            parts = [value.text] if value.dynamic else value.text.split()
            found.extend((word, Value(part, value.dynamic)) for part in parts)
        return found

    def node_contents(
        self, entity: Entity, scope: Scope, namespace: str | None, path: str | None
    ) -> tuple[list[Remap], list[tuple[str, Span]]]:
        remaps: list[Remap] = []
        parameters: list[tuple[str, Span]] = []
        for child in entity.children():
            here = self.branch(child, scope)
            found: Remap | tuple[str, Span] | None = None
            if child.kind == "remap":
                found = self.remap(child, here, namespace)
            elif child.kind == "param":
                found = self.param(child, here, path)
            elif child.kind == "rosparam":
                found = self.rosparam(child, here, path)
                self.node_load(child, here)
                if not here.inactive:
                    parameters.extend(self.inline_parameters(child, here))
            if found is None or here.inactive:
                continue
            if isinstance(found, Remap):
                remaps.append(found)
            else:
                parameters.append(found)
        return remaps, parameters


def _ros1_passed(arguments: LaunchArguments) -> dict[str, str | None]:
    """The raw values of the arguments handed to a roslaunch file: a package's file as
    ``$(find pkg)/path``, which the file's paths unfold as their own defaults'."""
    return {
        name: package_text(value, Dialect.ROS1) if isinstance(value, InPackage) else value
        for name, value in arguments
    }


@dataclass(frozen=True)
class _Declaring:
    """Where ``_declare_arguments`` puts what it finds, and the values passed in."""

    bindings: Bindings
    passed: dict[str, str | None]  # from the including file, replacing defaults; None: unknown
    declared: dict[str, None]  # every declared name, in order (for pass_all_args)


def _declare_arguments(
    entities: Sequence[Entity], into: _Declaring, conditions: tuple[Condition, ...]
) -> None:
    """Collect every ``<arg>`` of the file with the conditions guarding it.

    roslaunch arguments are file-global; ``<arg>`` children of ``<include>`` are values
    handed to another file, not declarations here.
    """
    for entity in entities:
        if_attr, unless_attr = entity.get("if"), entity.get("unless")
        guarded = conditions
        if if_attr is not None or unless_attr is not None:
            condition = Condition(
                None if if_attr is None else if_attr.text,
                None if unless_attr is None else unless_attr.text,
            )
            guarded = (*conditions, condition)
        if entity.kind == "arg":
            _declare_argument(entity, into, guarded)
        elif entity.kind not in ("include", "node", "test"):
            _declare_arguments(entity.children(), into, guarded)


def _declare_argument(entity: Entity, into: _Declaring, guarded: tuple[Condition, ...]) -> None:
    """``<arg name value>`` is fixed; a passed value replaces ``default`` (or its absence).

    roslaunch refuses to override a ``value``; the linter keeps the file's own value.
    """
    name = entity.get("name")
    if name is None:
        return
    fixed, default = entity.get("value"), entity.get("default")
    if fixed is not None:
        raw: str | None = fixed.text
    elif name.text in into.passed:
        raw = into.passed[name.text]
    else:
        raw = None if default is None else default.text
    into.bindings.declare(ARG, name.text, Declaration(raw, guarded))
    into.declared[name.text] = None


# ---------------------------------------------------------------------------------------
# ROS 2


_ROS2_NODE = NodeSpec(namespace_attribute="namespace", executable_attribute="exec")
_ROS2_COMPOSABLE = NodeSpec(namespace_attribute="namespace", executable_attribute="plugin")
_ROS2_NODES = frozenset({"node", "node_container", "lifecycle_node"})
_ROS2_PUSH = frozenset({"push-ros-namespace", "push_ros_namespace"})
_ROS2_LEAVES = frozenset({"executable", "set_env", "unset_env", "append_env", "log", "shutdown"})


class Ros2Launch(LaunchWalker):
    """launch/launch_ros frontend actions, from XML or YAML entities.

    ``arguments`` are the launch configurations an including file set before this one
    runs: an ``<arg default>`` does not override them, a ``<let>`` does.
    """

    dialect = Dialect.ROS2

    def __init__(self, arguments: LaunchArguments = ()) -> None:
        super().__init__()
        self.arguments = passed_values(arguments)

    def run(self, root: Entity) -> None:
        self.walk(root.children(), Scope("/", variables=dict(self.arguments)))

    def walk(self, entities: Sequence[Entity], scope: Scope) -> None:
        for entity in entities:
            here = self.branch(entity, scope)  # an inactive copy leaks nothing to scope
            kind = entity.kind
            if kind in ("let", "arg"):
                self.variable(entity, here)
            elif kind == "group":
                self.group(entity, here)
            elif kind in _ROS2_PUSH:
                self.push_namespace(entity, here)
            elif kind in ("set_remap", "remap"):
                remap = self.remap(entity, here, here.namespace)
                here.remaps.extend([remap] if remap else [])
            elif kind == "set_parameter":
                self.parameters([entity], here, "", here.namespace)
            elif kind in _ROS2_NODES:
                self.node(entity, here, _ROS2_NODE)
                self.composable_nodes(entity, here)
            elif kind == "load_composable_node":
                self.composable_nodes(entity, here)
            elif kind == "include":
                self.include(entity, here, None)  # its <arg>s go to another file
            elif kind not in _ROS2_LEAVES:
                self.walk(entity.children(), here)

    def variable(self, entity: Entity, scope: Scope) -> None:
        """``<let name value>`` sets; ``<arg name default>`` sets unless already set."""
        name = entity.get("name")
        given = entity.get("value" if entity.kind == "let" else "default")
        if name is None or given is None:
            return
        value = self.value(given, scope)
        if entity.kind == "let":
            scope.variables[name.text] = value
        else:
            scope.variables.setdefault(name.text, value)

    def group(self, entity: Entity, scope: Scope) -> None:
        """A group scopes variables, pushed namespaces and remaps unless scoped="false"."""
        scoped = entity.get("scoped")
        leaks = scoped is not None and truth(self.value(scoped, scope)) is False
        inner = scope if leaks else scope.copy()
        if self.undecided(entity, scope):
            inner = scope.copy()  # a conditional group marks its own nodes only
            inner.conditional = True
        self.walk(entity.children(), inner)

    def push_namespace(self, entity: Entity, scope: Scope) -> None:
        value = self.attribute(entity, "namespace", scope, NAMESPACE, scope.namespace)
        if value is not None:
            scope.enter(value)

    def include_arguments(self, entity: Entity, scope: Scope) -> LaunchArguments:
        """``<arg name value>`` children over every configuration in scope: an included
        file sees the configurations of the context that includes it."""
        inherited = {
            name: self.handed(value, scope.lookup) for name, value in scope.variables.items()
        }
        return handed_over(inherited, self.explicit_arguments(entity, scope, ("value",)))

    def composable_nodes(self, entity: Entity, scope: Scope) -> None:
        """Composable nodes get the pushed namespace, not their container's."""
        for description in entity.nested("composable_node"):
            self.node(description, self.branch(description, scope), _ROS2_COMPOSABLE)

    def parameters(
        self,
        entities: Sequence[Entity],
        scope: Scope,
        prefix: str | None,
        owner: str | None,
    ) -> list[tuple[str, Span]]:
        """Emit ``<param>`` names, nested ones joined with '.'; ``from=`` files skipped.

        ``prefix`` is the enclosing parameter's name ("" at the top, None when dynamic).
        """
        found: list[tuple[str, Span]] = []
        for entity in entities:
            if entity.get("from") is not None:
                loaded = self.parameter_file(entity, "from", self.branch(entity, scope))
                self.node_files.extend([loaded] if loaded and prefix == "" else [])
                continue
            located = entity.get("name")
            if located is None:
                continue
            value = self.value(located, scope)
            if prefix is None or value.dynamic:
                full = Value(located.text, dynamic=True)
            else:
                full = Value(f"{prefix}.{value.text}" if prefix else value.text)
            nested = entity.nested("param")
            if nested:
                found += self.parameters(nested, scope, None if full.dynamic else full.text, owner)
                continue
            self.emit(PARAMETER, entity.api("name"), located, full, owner)
            self.frame_value(entity, scope, full, owner)
            found.extend([] if full.dynamic else [(full.text, located.span)])
        return found

    def command_line(self, entity: Entity, scope: Scope) -> list[CommandLineName]:
        found: list[CommandLineName] = []
        for attribute, all_ros_args in (("args", False), ("ros_args", True)):
            located = entity.get(attribute)
            if located is not None and not located.opaque:
                assignments = ros2_assignments(located, all_ros_args=all_ros_args, bare=False)
                found += self.substitute_assignments(assignments, entity.api(attribute), scope)
        return found

    def node_contents(
        self, entity: Entity, scope: Scope, namespace: str | None, path: str | None
    ) -> tuple[list[Remap], list[tuple[str, Span]]]:
        remaps: list[Remap] = []
        for child in entity.nested("remap"):
            here = self.branch(child, scope)
            remap = self.remap(child, here, namespace)
            remaps.extend([remap] if remap and not here.inactive else [])
        return remaps, self.parameters(entity.nested("param"), scope, "", path)


# ---------------------------------------------------------------------------------------
# Entry point


def facts_from(
    path: str,
    language: Language,
    generation: Generation,
    walker: LaunchWalker,
) -> FileFacts:
    return FileFacts(
        path=path,
        language=language,
        generation=generation,
        names=tuple(sorted(walker.names, key=lambda use: (use.span.line, use.span.column))),
        launch_nodes=tuple(walker.nodes),
        includes=tuple(walker.includes),
        parameter_loads=tuple(walker.loads),
    )


def too_deep(path: str, language: Language, generation: Generation) -> FileFacts:
    """Nesting deep enough to exhaust Python's stack is reported, not raised."""
    error = ParseError("launch file nested too deeply to analyse", Span(1, 1, 1, 2))
    return FileFacts(path, language, generation, parse_errors=(error,))


@dataclass(frozen=True)
class _Parsed:
    """What a launch XML file is whatever arguments it is handed: its entities (which
    keep the parsed document) and the generation its own markers point to."""

    root: XmlEntity
    evidence: Generation | None


def _parse(data: bytes) -> _Parsed | ParseError:
    document = xmlsafe.parse(data)
    if isinstance(document, ParseError):
        return document
    return _Parsed(XmlEntity(document, document.root), evidence.launch_xml_evidence(document.root))


# A file included with arguments is extracted once per argument set, its sets spread over
# the depths of the launch trees: parsed once and kept for the next set. Nothing in
# ``_Parsed`` changes after it is built but the entities' own memos of what they read
# (the same answers), so extractions (in the language server's threads too) share it.
# Bounded for the language server, which extracts for as long as it runs: 128 of the
# launch files of the 28-repository workspace hold about 10 MB.
_parsed_again = functools.lru_cache(maxsize=128)(_parse)


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
    *,
    arguments: LaunchArguments = (),
) -> FileFacts:
    """Names, namespaces, launch nodes and includes of a ROS 1 or ROS 2 launch XML file.

    ``arguments`` are the values an including file hands over (``LaunchInclude``): the
    workspace model extracts an included file once per distinct set to get its nodes as
    that includer starts them.
    """
    default = evidence.extension_generation(path)
    parsed = _parsed_again(data) if arguments else _parse(data)
    if isinstance(parsed, ParseError):
        generation = evidence.decide(package_generation, None, default, fallback_generation)
        return FileFacts(path, Language.LAUNCH_XML, generation, parse_errors=(parsed,))
    # The file's own markers, when they agree, decide both syntax and grammar: only
    # roslaunch runs a file with <node type=> or $(arg), even one left in a ROS 2 package
    # (moveit2's generate_state_database.launch), and only ros2 launch one with exec=.
    generation = evidence.decide(parsed.evidence, package_generation, default, fallback_generation)
    root = parsed.root
    if root.kind != "launch":
        return FileFacts(path, Language.LAUNCH_XML, generation)
    walker: Ros1Launch | Ros2Launch
    try:
        if generation is Generation.ROS1:
            walker = Ros1Launch(root, arguments)
        else:
            walker = Ros2Launch(arguments)
        walker.run(root)
    except RecursionError:
        return too_deep(path, Language.LAUNCH_XML, generation)
    return facts_from(path, Language.LAUNCH_XML, generation, walker)
