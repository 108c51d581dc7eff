"""Language-neutral facts that extractors produce and rules consume.

Everything here is a frozen dataclass or an enum: facts are values, computed once per file,
cacheable and comparable. Nothing in this module parses, reads files or prints.
"""

from __future__ import annotations

import copyreg
import io
import pickle
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields
from enum import Enum
from operator import attrgetter
from types import MemberDescriptorType
from typing import Any, Protocol, TypeVar, cast


class Kind(str, Enum):
    """The kind of graph resource a name denotes; the grammar differs per kind."""

    NODE = "node"
    NAMESPACE = "namespace"
    TOPIC = "topic"
    SERVICE = "service"
    ACTION = "action"
    PARAMETER = "parameter"
    FRAME = "frame"


class Generation(int, Enum):
    """The ROS generation whose grammar and runtime judge a name."""

    ROS1 = 1
    ROS2 = 2


class Language(str, Enum):
    CPP = "cpp"
    PYTHON = "python"
    LAUNCH_PYTHON = "launch-python"  # a .py file defining generate_launch_description
    LAUNCH_XML = "launch-xml"  # ROS 1 .launch/.test and ROS 2 .launch.xml
    LAUNCH_YAML = "launch-yaml"
    URDF = "urdf"  # URDF and XACRO
    PACKAGE_XML = "package-xml"
    SERVICE_DEFINITION = "srv"  # a .srv file: not linted, but its type is known (RN204)
    CMAKE = "cmake"  # CMakeLists.txt, *.cmake: the executables and sources a package builds
    SETUP_PY = "setup-py"  # setup.py: a Python package's console_scripts
    SETUP_CFG = "setup-cfg"  # setup.cfg: console_scripts declared in [options.entry_points]
    # A YAML file that is not a launch file: a parameter file (ROS 2 ``ros__parameters``,
    # ROS 1 ``rosparam``) or other configuration, as its content and package tell.
    PARAMETERS = "parameters"
    # A dynamic_reconfigure ``.cfg``: a Python script catkin runs at build time to generate
    # a node's reconfigurable parameters (``ReconfigureConfig``).
    RECONFIGURE = "reconfigure"


# Each language by its value, as files kept by a run name it (an enum's call is slower)
LANGUAGE_OF_VALUE: Mapping[str, Language] = {language.value: language for language in Language}


class Role(str, Enum):
    """What the code or launch file does with a name.

    Endpoint roles are the ones RN202 cares about; the workspace model (graph rules) uses
    all of them to wire publishers to subscribers and remaps to the names they rename.
    """

    NODE_NAME = "node-name"
    NAMESPACE = "namespace"
    PUBLISH = "publish"
    SUBSCRIBE = "subscribe"
    SERVE = "serve"
    CALL = "call"
    ACTION_SERVE = "action-serve"
    ACTION_CALL = "action-call"
    PARAMETER = "parameter"
    PARAMETER_DEFAULT = "parameter-default"
    REMAP_FROM = "remap-from"
    REMAP_TO = "remap-to"
    FRAME = "frame"
    OTHER = "other"


ENDPOINT_ROLES = frozenset(
    {Role.PUBLISH, Role.SUBSCRIBE, Role.SERVE, Role.CALL, Role.ACTION_SERVE, Role.ACTION_CALL}
)


class TfRole(str, Enum):
    """What a file of code does with tf, by the classes and calls it names."""

    BROADCAST = "broadcast"  # a TransformBroadcaster or StaticTransformBroadcaster
    LISTEN = "listen"  # a tf buffer or listener, a message filter, a lookup or transform


class ParameterAccess(str, Enum):
    """What code does with a parameter's name (``NameUse.access``), as the client library
    defines the call: what a node's parameter set (``workspace.parameters``) is made of.

    In ROS 2 the difference between a read that throws and one that does not is rclcpp's
    ``NodeParameters::get_parameter(name)`` (throws ``ParameterNotDeclaredException`` for
    an undeclared name unless undeclared parameters are allowed) against its
    ``get_parameter(name, parameter)`` (returns false); rclpy's ``Node.get_parameter``
    raises, ``Node.get_parameter_or`` returns the alternative.
    """

    DECLARE = "declare"  # declares it (ROS 2); a ROS 1 node has no declarations
    READ = "read"  # reads it; ROS 2: throws when it is not declared
    READ_QUIETLY = "read-quietly"  # reads it; ROS 2: false or a default when not declared
    READ_PREFIX = "read-prefix"  # reads every parameter below the name (``get_parameters``)
    CHECK = "check"  # asks whether it exists (``has_parameter``, ``hasParam``, ``searchParam``)
    WRITE = "write"  # sets, deletes or undeclares it
    REMOTE = "remote"  # another node's, through a parameter client: not this node's


class ParameterTrait(str, Enum):
    """What a file of code does that leaves a node's parameters open to names its code
    does not spell (``FileFacts.parameter_traits``)."""

    ALLOW_UNDECLARED = "allow-undeclared"  # NodeOptions().allow_undeclared_parameters(true)
    FROM_OVERRIDES = "from-overrides"  # automatically_declare_parameters_from_overrides
    PLUGINS = "plugins"  # loads pluginlib plugins, which declare on the node they are given
    GENERATED = "generated"  # generate_parameter_library: declared by generated code
    DYNAMIC_RECONFIGURE = "dynamic-reconfigure"  # serves a .cfg's parameters (ROS 1)
    # holds a filters::FilterChain, which declares ``filterN.name``/``.type`` and whose
    # filters declare ``filterN.params.*`` on the node
    FILTER_CHAIN = "filter-chain"


class Severity(str, Enum):
    ERROR = "error"
    WARNING = "warning"


REBUILT = "_rebuilt"  # the class attribute a Compact class's rebuilder is pickled by


class _CompactClass(type):
    """Gives each Compact class its ``_rebuilt`` on first asking, in any process: the
    one that pickles a value, and a worker or the main process that unpickles it."""

    def __getattr__(cls, name: str) -> Any:
        if name == REBUILT:
            return rebuilder(cls)
        raise AttributeError(f"type object {cls.__name__!r} has no attribute {name!r}")


class Compact(metaclass=_CompactClass):
    """A base of frozen dataclasses with slots that a run holds by the hundred thousand
    (the graph's nodes, endpoints and places): no ``__dict__`` per object, and pickled as
    its fields' values and what builds the object again from them (``rebuilder``, named
    as the class's ``_rebuilt``: a worker's facts are unpickled by the main process's
    plain unpickler). Pickled as a state dict, each object's dict stays in the
    unpickler's memo to the end of a load: 50 MB of the kept graph's 14 MB at 77,000
    files, the peak of a run that patches it."""

    __slots__ = ()

    def __reduce__(self) -> tuple[Callable[..., Any], tuple[object, ...]]:
        return (rebuilder(type(self)), _values(self))


_GETTERS: dict[type, Callable[[Any], tuple[object, ...]]] = {}
_REBUILDERS: dict[type, Callable[..., Any]] = {}


def rebuilder(cls: type[Any]) -> Callable[..., Any]:
    """What makes an instance of ``cls`` from its fields' values, in order, as
    ``cls(*values)`` does, but setting each slot directly: a frozen dataclass's
    ``__init__`` sets each field through ``object.__setattr__``, two thirds of the time
    unpickling a build's facts spends making them. ``cls`` itself where it has a
    ``__post_init__`` or a field that is no slot."""
    known = _REBUILDERS.get(cls)
    if known is not None:
        return known
    slots = [getattr(cls, item.name, None) for item in fields(cls)]
    setters = [slot.__set__ for slot in slots if isinstance(slot, MemberDescriptorType)]
    if hasattr(cls, "__post_init__") or len(setters) != len(slots):
        _REBUILDERS[cls] = cls
        return cls
    # Made from the count of fields alone: no name or value of the class is in the code.
    values = ", ".join(f"v{at}" for at in range(len(setters)))
    sets = "".join(f"    s{at}(made, v{at})\n" for at in range(len(setters)))
    scope: dict[str, Any] = {"new": object.__new__, "cls": cls}
    scope.update((f"s{at}", setter) for at, setter in enumerate(setters))
    exec(f"def rebuilt({values}):\n    made = new(cls)\n{sets}    return made\n", scope)
    rebuilt: Callable[..., Any] = scope["rebuilt"]
    # Where pickle finds it again: the class's attribute, of its module.
    rebuilt.__module__, rebuilt.__qualname__ = cls.__module__, f"{cls.__qualname__}.{REBUILT}"
    setattr(cls, REBUILT, rebuilt)
    _REBUILDERS[cls] = rebuilt
    return rebuilt


_C = TypeVar("_C", bound=Compact)
_POSITIONS: dict[type, dict[str, int]] = {}


def replaced(value: _C, /, **changes: object) -> _C:
    """``dataclasses.replace`` for a Compact value: its fields' values, ``changes`` in
    place of some, rebuilt (``rebuilder``), in less than half the time: a patch of the
    graph replaces every node's parameters (17,000 at 8 copies: 0.11 s by ``replace``)."""
    cls = type(value)
    positions = _POSITIONS.get(cls)
    if positions is None:
        names = [item.name for item in fields(cast(Any, value))]  # a Compact is a dataclass
        positions = _POSITIONS[cls] = {name: at for at, name in enumerate(names)}
    values = list(_values(value))
    for name, changed in changes.items():
        if name not in positions:
            raise TypeError(f"{cls.__name__} has no field {name!r}")
        values[positions[name]] = changed
    made: _C = rebuilder(cls)(*values)
    return made


def _values(instance: Any) -> tuple[object, ...]:
    """The values of a dataclass's fields, in ``__init__``'s order."""
    return _getter(type(instance))(instance)


def _getter(cls: type[Any]) -> Callable[[Any], tuple[object, ...]]:
    getter = _GETTERS.get(cls)
    if getter is None:
        names = [item.name for item in fields(cls)]
        several = attrgetter(*names)
        getter = several if len(names) > 1 else lambda value: (several(value),)
        _GETTERS[cls] = getter
    return getter


class _Reducers(dict[type, Callable[[Any], tuple[Any, ...]]]):
    """A pickler's dispatch table: a Compact value reduced in one call to what its
    ``__reduce__`` gives (the same bytes), without the three lookups a ``__reduce__``
    makes (a quarter to a third of the time pickling the kept graph); any other class
    as the default table (``copyreg``) says. Pickle asks it for each value of a class
    it does not pickle itself; a class's reduction is made the first time."""

    def __missing__(self, cls: type) -> Callable[[Any], tuple[Any, ...]]:
        if isinstance(cls, type) and issubclass(cls, Compact):
            rebuilt, getter = rebuilder(cls), _getter(cls)

            def reduce(value: Any) -> tuple[Any, ...]:
                return (rebuilt, getter(value))

            self[cls] = reduce
            return reduce
        found = copyreg.dispatch_table.get(cls)
        if found is None:
            raise KeyError(cls)
        return cast(Callable[[Any], tuple[Any, ...]], found)


_REDUCERS = _Reducers()


class Writable(Protocol):
    """Where ``dump`` writes: a file, or what writes through to one (``cache._Hashing``)."""

    def write(self, data: bytes, /) -> object: ...


def dump(value: object, stream: Writable) -> None:
    """``pickle.dump`` at the highest protocol, Compact values reduced fast (``_Reducers``)."""
    pickler = pickle.Pickler(stream, protocol=pickle.HIGHEST_PROTOCOL)
    pickler.dispatch_table = _REDUCERS
    pickler.dump(value)


def dumps(value: object) -> bytes:
    """``dump`` into bytes."""
    stream = io.BytesIO()
    dump(value, stream)
    return stream.getvalue()


@dataclass(frozen=True, order=True, slots=True)
class Span(Compact):
    """Where a name literal sits: 1-based lines, 1-based columns in Unicode code points.

    The span starts at the literal's first character (the opening quote in code, the first
    character of an attribute value or element text in XML) and ends just after it
    (``end_column`` is exclusive).
    """

    line: int
    column: int
    end_line: int
    end_column: int


@dataclass(frozen=True, slots=True)
class NameUse(Compact):
    """One occurrence of a ROS name in a file.

    ``value`` is the name exactly as the runtime will see it after static folding (constant
    propagation in code, ``$(arg x)`` defaults in launch files). When the value cannot be
    known statically, ``dynamic`` is true, ``value`` holds the raw text for display only,
    and rules skip the use: a dynamic name is never guessed.
    """

    kind: Kind
    value: str
    span: Span
    role: Role
    api: str  # where it came from, for messages: "<node name>", "ros::NodeHandle::advertise"
    dynamic: bool = False
    type_name: str | None = None  # message, service or action type when known
    namespace: str | None = None  # enclosing namespace known in the file (launch group ns)
    # A dynamic C++ name that is an identifier the file does not declare: a constant an
    # included header may define (``symbols`` gives it its value there).
    symbol: str | None = None
    # A dynamic name whose start is certain: the absolute literal it is joined from at run
    # time (``"/planning/" + name``, ``f"/planning/{name}"``). It stays dynamic, so that no
    # grammar rule judges the unknown rest; RN202 may judge the anchor the prefix fixes.
    absolute_prefix: str | None = None
    # A parameter: what the code does with it (declare, read...); None elsewhere.
    access: ParameterAccess | None = None
    # A dynamic name whose end is certain: the literal it ends with (``plugin_name_ +
    # ".max_vel_x"``, ``f"{name}.max_vel_x"``): a parameter under a run-time prefix.
    suffix: str | None = None


@dataclass(frozen=True, slots=True)
class Remap(Compact):
    source: str
    target: str
    span: Span  # the source (``from``): what RN404 says is unused
    target_span: Span | None = None  # the target (``to``): what RN201 says is too deep


@dataclass(frozen=True, slots=True)
class ParameterLoad(Compact):
    """A parameter file a launch file hands a node, or (ROS 1) loads into a namespace.

    ``package`` and ``path`` locate the file as ``LaunchInclude``'s do; ``span`` is the
    reference (``<rosparam file>``, ``<param from>``, the ``parameters=`` item).
    ``namespace``: ROS 1 only, where the file's names are loaded. On a node it is the
    ``ns`` relative to the node's private namespace ("" for that namespace itself); on a
    group-level ``<rosparam>`` (``FileFacts.parameter_loads``) the fully pushed namespace,
    as ``LaunchNode.namespace`` ("" when dynamic), with ``anchored`` likewise.
    """

    package: str | None
    path: str | None
    span: Span
    namespace: str = ""
    anchored: bool = False
    conditional: bool = False


@dataclass(frozen=True, slots=True)
class ParameterBlock(Compact):
    """The parameters one part of a parameter file sets, each name with its key's span.

    ROS 2: one node key (``controller_server``, ``/ns/node``, ``/**``) and the parameters
    under its ``ros__parameters``, nested keys joined with '.' (``FollowPath.max_vel_x``);
    ``key`` is the node key as rcl reads it (nested node keys joined with '/') and
    ``span`` covers the key written last before ``ros__parameters``. ROS 1: the whole
    file, ``key`` None and ``span`` its first key, names the nested keys joined with '/'.
    """

    key: str | None
    span: Span
    parameters: tuple[tuple[str, Span], ...] = ()


@dataclass(frozen=True, slots=True)
class ReconfigureConfig(Compact):
    """What a dynamic_reconfigure ``.cfg`` file generates: the parameters of one config.

    ``gen.generate(package, node, name)`` generates the C++ class ``package::nameConfig``
    and the Python class ``package.cfg.nameConfig``; ``package`` and ``name`` are None
    where the file does not spell them statically. ``parameters`` are the names of every
    ``add`` (groups add to the same namespace), each with its literal's span;
    ``complete`` is false where the file may add others the linter does not see (a name
    built at run time, the generator handed to a helper).
    """

    package: str | None
    name: str | None
    parameters: tuple[tuple[str, Span], ...] = ()
    complete: bool = True


@dataclass(frozen=True, slots=True)
class LaunchNode(Compact):
    """A node started by a launch file, with the scope the file gives it.

    The workspace model (resolution across files) is built from these; file rules look at
    the ``NameUse`` facts the extractor emits for the same attributes.

    ``remaps`` lists the group-level remaps in force first, then the node's own (its
    ``<remap>`` children, ``remappings=``, ``-r``/``from:=to`` on its command line);
    ``own_remaps`` says how many of the last ones are the node's own. ``anchored`` is true
    when this file made the namespace absolute (an absolute ``ns``/``namespace`` on the
    node or an enclosing group or push, ``__ns:=``): an including file's namespace then
    does not prefix it.
    """

    package: str | None
    executable: str | None
    name: str | None
    namespace: str  # the fully pushed namespace, "/" for the root; "" when dynamic
    span: Span
    remaps: tuple[Remap, ...] = ()
    parameters: tuple[str, ...] = ()
    own_remaps: int = 0
    anchored: bool = False
    # Under an if/unless (or IfCondition) the linter cannot decide: it may not run, and
    # two such nodes of one name are usually alternatives (composed or not), not twins.
    conditional: bool = False
    # The file names the node, but not statically (``$(anon x)``, an argument the linter
    # cannot know): its name is unknown, not the one its code gives itself.
    dynamic_name: bool = False
    # A rostest ``<test>``: rostest runs its tests one at a time once the nodes are up, so
    # two tests of one name never run together.
    test: bool = False
    # The parameter files handed to the node, in order (``parameters=[path]``, ``<param
    # from>``, ``<rosparam command="load" file>`` inside the node).
    parameter_files: tuple[ParameterLoad, ...] = ()
    # Where each of ``parameters`` is written (its ``<param name>``, dictionary key or
    # command-line key), in the same order.
    parameter_spans: tuple[Span, ...] = ()


@dataclass(frozen=True, order=True, slots=True)
class InPackage(Compact):
    """A value known only as a file of a package: ``$(find-pkg-share pkg)/config/a.yaml``,
    ``$(find pkg)/config/a.yaml``, ``PathJoinSubstitution([FindPackageShare('pkg'),
    'config', 'a.yaml'])``. Where the package is installed is the machine's; which file of
    which package it is, the launch file says. ``path`` is relative to the package."""

    package: str
    path: str


# What an include hands the included file, sorted by name: each argument's value, an
# ``InPackage`` where it names a package's file, None when the includer sets it to
# something the linter cannot know (the included file must then not fall back to its
# default).
LaunchArguments = tuple[tuple[str, "str | InPackage | None"], ...]


@dataclass(frozen=True, slots=True)
class LaunchInclude(Compact):
    """A launch file including another: where the included file is and the scope it gets.

    ``package`` and ``path`` locate the included file: ``$(find pkg)/launch/a.launch``,
    ``$(find-pkg-share pkg)/launch/a.launch.py``, ``FindPackageShare('pkg')`` joined with
    ``'launch'``, ``'a.launch.py'`` and ``get_package_share_directory('pkg')`` all give
    ``package="pkg"`` and ``path="launch/a.launch[.py]"`` (relative to the package's
    directory, '/'-separated). With ``package`` None, ``path`` is relative to the including
    file's directory (``$(dirname)``, ``ThisLaunchFileDir()``) or absolute. ``path`` is None
    when not statically known. ``namespace`` follows ``LaunchNode.namespace``; ``anchored``
    likewise. ``arguments`` are the statically known values handed to the included file
    (``<arg name value>`` children, ``launch_arguments``), sorted by name; ``remaps`` are
    the group-level remaps in force at the include, which apply to the included nodes.
    """

    package: str | None
    path: str | None
    namespace: str
    span: Span
    arguments: LaunchArguments = ()
    remaps: tuple[Remap, ...] = ()
    anchored: bool = False
    conditional: bool = False  # as LaunchNode.conditional: everything it starts is too


class ExecutableKind(str, Enum):
    PROGRAM = "program"  # what <node type|exec> and Node(executable=) name
    PLUGIN = "plugin"  # a component class, what <composable_node plugin> names


@dataclass(frozen=True, slots=True)
class Executable(Compact):
    """A program or component plugin a package builds or installs, and its source files.

    ``name`` is what launch files use: the CMake target or ``EXECUTABLE`` name, the
    console_scripts entry, the script's file name (``talker.py``), or the plugin's C++
    class (``demo_nodes_cpp::Talker``). ``sources`` are paths relative to the build file's
    directory, '/'-separated, normalised; a console_scripts module ``a.b`` is given as
    ``a/b.py``.
    """

    name: str
    kind: ExecutableKind
    sources: tuple[str, ...]
    span: Span


@dataclass(frozen=True, slots=True)
class CompiledSources(Compact):
    """Which source files one build file compiles, as far as its text tells.

    Paths are relative to the build file's directory, '/'-separated, normalised (as
    ``Executable.sources``). ``paths`` are the sources its targets name (programs,
    libraries, tests). What the file leaves open keeps its sources possibly compiled:
    ``patterns`` are sources named with a part the file does not determine, that part a
    ``*`` (``"*"`` alone: any file of the package, as a glob's variable or a file that
    stops lexing leaves it); ``words`` are what commands the linter does not know pass
    (a macro of another package's ``.cmake``), which may name a file by its path, its
    directory, its name or its stem; ``subdirectories`` (``add_subdirectory``) and
    ``includes`` (``include`` of a file of the package) are build files this one runs,
    which must be in the run for the rest to be the whole story, and the only
    ``CMakeLists.txt`` files of its package besides its root that CMake reads.
    ``rostest`` are the sources of the test executables that only rostest starts
    (``add_rostest_gtest``); such a source is in ``paths`` only where another target
    names it too.
    """

    paths: tuple[str, ...] = ()
    patterns: tuple[str, ...] = ()
    words: tuple[str, ...] = ()
    subdirectories: tuple[str, ...] = ()
    includes: tuple[str, ...] = ()
    rostest: tuple[str, ...] = ()


class EventKind(str, Enum):
    """What RN301 orders: the runtime's initialisation and the objects that need it."""

    INIT = "init"  # ros::init, rclcpp::init, rclpy.init, rospy.init_node
    HANDLE = "handle"  # ros::NodeHandle, rclcpp::Node, an rclpy Node, a rospy endpoint...


@dataclass(frozen=True, slots=True)
class RuntimeEvent(Compact):
    """An init call or a construction that needs one, in the order the code runs them.

    ``scope`` names the code the event runs in: a function (unique within the file, e.g.
    ``"main@12"``), or ``""`` for what runs when the program or module loads (C++
    namespace scope and static data members, Python module level). ``order`` is the
    statement position within that scope. ``static_storage`` marks C++ objects built before
    ``main()`` starts (globals, static data members), which no init can precede.
    """

    kind: EventKind
    api: str  # "ros::init", "ros::NodeHandle", "rclpy.create_node", "rospy.Publisher"
    span: Span
    scope: str
    order: int
    static_storage: bool = False


@dataclass(frozen=True, slots=True)
class ParseError(Compact):
    """A file, or part of one, that could not be decoded or parsed (becomes RN001)."""

    message: str
    span: Span


@dataclass(frozen=True, slots=True)
class FileFacts(Compact):
    """Everything one extraction learned about one file."""

    path: str  # as given on the command line or found by discovery
    language: Language
    generation: Generation
    names: tuple[NameUse, ...] = ()
    launch_nodes: tuple[LaunchNode, ...] = ()
    events: tuple[RuntimeEvent, ...] = ()
    parse_errors: tuple[ParseError, ...] = ()
    includes: tuple[LaunchInclude, ...] = ()
    executables: tuple[Executable, ...] = ()
    # Name-shaped string literals of code (``extract.literals``): evidence of names used
    # through APIs the linter does not know.
    literals: tuple[str, ...] = ()
    # Code: what it does that leaves its node's parameter names open (``ParameterTrait``,
    # in that order), and each class it defines with the bases it names, as written
    # (``("ControllerServer", ("nav2::LifecycleNode",))``): where else declarations hide.
    parameter_traits: tuple[ParameterTrait, ...] = ()
    class_bases: tuple[tuple[str, tuple[str, ...]], ...] = ()
    # Code: the base classes of the plugins it loads (``pluginlib::ClassLoader<
    # nav2_amcl::MotionModel>`` gives ``nav2_amcl::MotionModel``), sorted; "" for a loader
    # whose base the text does not show (BehaviorTree.CPP's ``registerFromPlugin``).
    plugin_loaders: tuple[str, ...] = ()
    # Code: parameter-shaped string literals it holds more often than the names it was
    # read for (``extract.literals.unexplained_literals``): names it may declare through
    # something the linter does not know.
    unexplained_literals: tuple[str, ...] = ()
    # C++: the string constants a header defines, (name, value), and the paths the file
    # includes (both only where ``symbols`` may need them).
    constants: tuple[tuple[str, str], ...] = ()
    cpp_includes: tuple[str, ...] = ()
    # The file's bytes may hold a suppression comment (``suppress``), as extraction found
    # them: a re-run from cached facts does not read a file that holds none and has no
    # finding. False by default, so that the facts of most files stay the empty ones.
    suppression_marker: bool = False
    # Python test code: the base names of launch, URDF and YAML files it loads expecting
    # them to be refused (``extract.python.fixtures``); their findings are the test's point.
    rejected_fixtures: tuple[str, ...] = ()
    # C++ with ROS code: what the file does with tf (``extract.cpp.tf_roles``), in
    # ``TfRole`` order; RN205 leaves the frames of a file that only broadcasts alone.
    tf_roles: tuple[TfRole, ...] = ()
    # A build file: the sources it compiles (``CompiledSources``); None for other files.
    compiled: CompiledSources | None = None
    # C++: the source files (not headers) it includes, ``#include "impl.cpp"``, by name:
    # such a file is compiled though no build file names it.
    included_sources: tuple[str, ...] = ()
    # A parameter file: what each of its parts sets (``ParameterBlock``).
    parameter_blocks: tuple[ParameterBlock, ...] = ()
    # A ROS 1 launch file: the ``<rosparam command="load" file>`` outside any node.
    parameter_loads: tuple[ParameterLoad, ...] = ()
    # A dynamic_reconfigure ``.cfg``: the config it generates.
    reconfigure: ReconfigureConfig | None = None
    # Code: the dynamic_reconfigure configs it serves (``Server<pkg::NameConfig>``,
    # rospy's ``Server(NameConfig, cb)``), as ``pkg::NameConfig`` or, where the file
    # does not qualify it, ``NameConfig``.
    reconfigure_servers: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class Fix(Compact):
    """A rule's certain fix: write ``replacement`` where the finding's name ``value`` is.

    ``safe``: the fix cannot change what the running system does (``--fix`` applies it;
    an unsafe one needs ``--unsafe-fixes`` too).
    """

    value: str
    replacement: str
    safe: bool
    # A rename (RN203): the tokens it renames, (old, new). Not a fix of one place: it is
    # offered only once every other use of those tokens in the workspace is found and
    # renamed with it (``renames``), else not at all.
    tokens: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True, slots=True)
class Edit(Compact):
    """A fix located in a file: ``span`` (one line) becomes ``text``.

    ``path`` is None for the finding's own file; a rename's edits of the name's other
    uses name theirs.
    """

    span: Span
    text: str
    safe: bool
    path: str | None = None


@dataclass(frozen=True, slots=True)
class Answer(Compact):
    """The setting that would state a finding's name as the project's convention, and its
    value: ``max-depth`` 7, ``rules.RN202.extend-allow`` "/api/state". Many findings
    sharing one answer are one decision (``conventions`` proposes it)."""

    setting: str
    value: str
    # The kind of the name, where answers count as one convention only within a kind and
    # a package (RN203: a package's CamelCase node names are its convention, and its
    # parameters another); None where they count across the run.
    kind: Kind | None = None


@dataclass(frozen=True, slots=True)
class Decision(Compact):
    """The name a finding judges, as one choice however many places write it.

    Findings of one rule on equal decisions are reported once (``decisions``): the place
    that writes the name is an occurrence of the choice, not a choice of its own.
    """

    kind: Kind
    name: str  # the name's value; with ``prefix``, the absolute start it is built from
    generation: Generation
    prefix: bool = False
    # "" where the name is the workspace's (a topic, a node name); the file's path where it
    # is one node's own (a parameter, a private ``~`` name): another node's is another name.
    scope: str = ""
    producer: bool = False  # the place publishes, serves or serves the action: the source
    api: str = ""  # what the place hands the name to, for the note at it
    # The file writes every endpoint name absolute: its node is bound to the root namespace
    # by design, and what is left of the file's findings of the rule once each name is
    # reported once is that one decision, whatever their names.
    bound: bool = False


@dataclass(frozen=True, slots=True)
class Finding(Compact):
    """What a rule reports: no code or severity, the engine attaches those from the rule."""

    span: Span
    message: str
    related: tuple[RelatedLocation, ...] = ()
    fix: Fix | None = None
    answer: Answer | None = None
    # The name the finding judges, where other places may write the same (``decisions``).
    decision: Decision | None = None
    # What it says goes wrong only where the code is deployed: under a launch file's
    # namespaces and remaps, which a test or an example is never given (RN301), or on a
    # node that is a test's stand-in (RN406). Left out in test and example code even by a
    # rule that judges test code.
    deployment_only: bool = False


@dataclass(frozen=True, slots=True)
class RelatedLocation(Compact):
    path: str
    span: Span
    message: str


@dataclass(frozen=True, slots=True)
class Diagnostic(Compact):
    """A finding bound to its rule, file and effective severity; what reporters format."""

    path: str
    span: Span
    code: str
    rule_name: str
    severity: Severity
    message: str
    related: tuple[RelatedLocation, ...] = ()
    suppressed: bool = False
    source_line: str | None = field(default=None, compare=False)
    # Matched by the baseline given to the run (``baseline``): known before, not reported.
    baselined: bool = False
    edit: Edit | None = None  # the fix, where the file spells the name exactly
    # A rename's edits of the other uses of the name, in this file or others: applied
    # with ``edit`` or not at all.
    also: tuple[Edit, ...] = ()
    # A rename not yet offered: ``renames.resolve`` turns it into ``edit`` and ``also``
    # once it has seen every use of the name, or drops it.
    renaming: Fix | None = None
    # Why a rename was not offered (``renames.resolve``): what --fix and --diff say of it.
    held_back: str = field(default="", compare=False)
    answer: Answer | None = field(default=None, compare=False)  # Finding.answer
    # The display directory of the file's package ("" for the run's root; None outside
    # any package, and for graph rules' findings, whose answers count across the run):
    # RN203's answers group by it.
    package: str | None = field(default=None, compare=False)
    decision: Decision | None = field(default=None, compare=False)  # Finding.decision
    # The other places of its decision, as the findings they were (``decisions``): a
    # baseline knows the decision by every one of them.
    joined: tuple[Diagnostic, ...] = field(default=(), compare=False)

    def sort_key(self) -> tuple[str, int, int, str, str]:
        return (self.path, self.span.line, self.span.column, self.code, self.message)
