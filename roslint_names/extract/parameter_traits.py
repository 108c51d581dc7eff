"""What code does that leaves its node's parameter names open, and the classes it defines.

Read from the bytes without parsing, for C++ and Python alike: the switches and libraries
that make a node accept, or declare, parameters its code never spells
(``ParameterTrait``), and each class with the bases it names (a node's declarations may be
in a base class: ``workspace.parameters`` follows the bases the workspace defines and
distrusts the others). Facts only: what they mean for a node is decided over the whole
workspace.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from roslint_names.model import ParameterTrait

# rclcpp's NodeOptions::allow_undeclared_parameters(bool) and
# automatically_declare_parameters_from_overrides(bool), rclpy's Node keyword arguments of
# the same names: on unless given a literal false (a variable may hold true). A getter
# (``options.allow_undeclared_parameters()``) switches nothing.
_SWITCH = rb"\s*(?:\(\s*(?!false\b|\))|=\s*(?!False\b))"
_ALLOW_UNDECLARED = re.compile(rb"\ballow_undeclared_parameters" + _SWITCH)
_FROM_OVERRIDES = re.compile(rb"\bautomatically_declare_parameters_from_overrides" + _SWITCH)
# pluginlib's ClassLoader and its instance makers: a plugin is handed the node and
# declares its own parameters on it (nav2's controllers, costmap layers, behaviours).
_PLUGINS = re.compile(
    rb"\bClassLoader\s*<|\bcreate(?:Shared|Unique|Unmanaged)Instance\b"
    rb"|\bregisterFromPlugin\b"  # BehaviorTree.CPP's: nav2's tree nodes read the ROS node's
)
# The filters library's chains: ros/filters (ros2) include/filters/filter_chain.hpp,
# ``impl::load_chain_config``, declares each ``filterN.name`` and ``filterN.type`` under
# the prefix ``configure`` is given, and loads the filters through a pluginlib
# ``ClassLoader``; each declares its ``filterN.params.*`` (``FilterBase::getParamImpl``,
# filter_base.hpp). laser_filters' scan_to_scan_filter_chain holds one.
_FILTER_CHAIN = re.compile(rb"\b(?:MultiChannel)?FilterChain\s*<")
# generate_parameter_library's generated ParamListener declares a YAML file's parameters.
_GENERATED = re.compile(rb"\bParamListener\b|\bgenerate_parameter_library\b")
# A ROS 1 dynamic_reconfigure server: the parameters its .cfg file generates.
_DYNAMIC_RECONFIGURE = re.compile(
    rb"\bdynamic_reconfigure::Server\s*<|\bdynamic_reconfigure\.server\b"
    rb"|\bfrom\s+dynamic_reconfigure\.server\s+import\b"
)
# The config a server serves: ``dynamic_reconfigure::Server<amcl::AMCLConfig>`` (a
# declaration, a ``new``, a ``make_shared``'s argument, a typedef), and rospy's
# ``from amcl.cfg import AMCLConfig`` in a file that imports the server.
# A template's one argument, a (qualified) class name: ``< ::amcl::AMCLConfig >``.
_CLASS_ARGUMENT = rb"<\s*((?:::\s*)?[A-Za-z_][\w\s:]{0,200}?)\s*>"
_CPP_SERVER = re.compile(rb"\bdynamic_reconfigure\s*::\s*Server\s*" + _CLASS_ARGUMENT)
_PYTHON_CONFIG_IMPORT = re.compile(
    rb"(?m)^[ \t]*from[ \t]+([A-Za-z_]\w*)\.cfg[ \t]+import[ \t]*(?:\(([^()]*)\)|([\w \t,]+))"
)
_PYTHON_CONFIG_ALIAS = re.compile(r"(\w+)(?:\s+as\s+(\w+))?")
_SPACE = re.compile(r"\s+")
_TRAITS = (
    (b"allow_undeclared_parameters", _ALLOW_UNDECLARED, ParameterTrait.ALLOW_UNDECLARED),
    (
        b"automatically_declare_parameters_from_overrides",
        _FROM_OVERRIDES,
        ParameterTrait.FROM_OVERRIDES,
    ),
    (b"Instance", _PLUGINS, ParameterTrait.PLUGINS),
    (b"ClassLoader", _PLUGINS, ParameterTrait.PLUGINS),
    (b"registerFromPlugin", _PLUGINS, ParameterTrait.PLUGINS),
    (b"FilterChain", _FILTER_CHAIN, ParameterTrait.FILTER_CHAIN),
    (b"ParamListener", _GENERATED, ParameterTrait.GENERATED),
    (b"generate_parameter_library", _GENERATED, ParameterTrait.GENERATED),
    (b"dynamic_reconfigure", _DYNAMIC_RECONFIGURE, ParameterTrait.DYNAMIC_RECONFIGURE),
)

# ``class NAV2_EXPORT ControllerServer : public nav2::LifecycleNode, private Base<T> {``:
# the last word before the colon is the class; the base clause runs to the brace.
_CPP_CLASS = re.compile(
    rb"(class|struct)[ \t\n]+(?:[A-Za-z_]\w*[ \t\n]+){0,3}?([A-Za-z_]\w*)\s*(?:final\s*)?"
    rb"(?::(?!:)([^{};()]{1,600}))?\{"
)
_ENUM = re.compile(rb"\benum\s*$")
_CPP_COMMENT = re.compile(rb"//[^\n]*|/\*.*?\*/", re.DOTALL)
_CPP_ACCESS = re.compile(r"^(?:(?:public|protected|private|virtual)\s+)+")
# ``class Talker(Node):``, ``class Talker(rclpy.node.Node, metaclass=Meta):``
_PYTHON_CLASS = re.compile(
    rb"(?m)^[ \t]*class[ \t]+([A-Za-z_]\w*)[ \t]*(?:\(([^()]{0,600})\))?[ \t]*:"
)


def parameter_traits(data: bytes) -> tuple[ParameterTrait, ...]:
    """The traits the file's text shows, in ``ParameterTrait`` order."""
    found = {trait for word, pattern, trait in _TRAITS if word in data and pattern.search(data)}
    return tuple(trait for trait in ParameterTrait if trait in found)


# ``pluginlib::ClassLoader<karto::ScanSolver>``: the base class its plugins derive from.
_LOADED_BASE = re.compile(rb"\bClassLoader\s*" + _CLASS_ARGUMENT)


def plugin_loaders(data: bytes) -> tuple[str, ...]:
    """The base classes whose plugins the text loads (``FileFacts.plugin_loaders``); ""
    where it loads plugins without showing their base (BehaviorTree.CPP's
    ``registerFromPlugin``). An instance maker uses a loader declared elsewhere (its
    header), whose file says the base."""
    if b"ClassLoader" not in data and b"registerFromPlugin" not in data:
        return ()
    found = {_class_written(match) for match in _LOADED_BASE.finditer(data)}
    if b"registerFromPlugin" in data:
        found.add("")
    return tuple(sorted(found))


def _class_written(match: re.Match[bytes]) -> str:
    """The class name ``_CLASS_ARGUMENT`` matched, without spaces or a leading ``::``."""
    return _SPACE.sub("", match.group(1).decode("utf-8", "replace")).lstrip(":")


def reconfigure_servers(data: bytes, *, python: bool) -> tuple[str, ...]:
    """The dynamic_reconfigure configs the code serves, ``pkg::NameConfig`` or, where the
    text does not qualify it (``using namespace``, the package's own namespace),
    ``NameConfig``; sorted. Only where the text shows a server
    (``ParameterTrait.DYNAMIC_RECONFIGURE``)."""
    if b"dynamic_reconfigure" not in data or not _DYNAMIC_RECONFIGURE.search(data):
        return ()
    found: set[str] = set()
    if python:
        # ``from pkg.cfg import NameConfig`` is what rospy's Server is handed; a client
        # needs no config class.
        for match in _PYTHON_CONFIG_IMPORT.finditer(data):
            package = match.group(1).decode("utf-8", "replace")
            names = (match.group(2) or match.group(3)).decode("utf-8", "replace")
            for part in names.split(","):
                alias = _PYTHON_CONFIG_ALIAS.fullmatch(part.strip())
                if alias and alias.group(1).endswith("Config"):
                    found.add(f"{package}::{alias.group(1)}")
    else:
        found.update(_class_written(match) for match in _CPP_SERVER.finditer(data))
    return tuple(sorted(found))


def cpp_class_bases(data: bytes) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """Each class or struct the C++ text defines: (name, bases as written, template
    arguments dropped; none for a class without bases)."""
    if b"class" not in data and b"struct" not in data:
        return ()
    found: dict[str, tuple[str, ...]] = {}
    for match in _cpp_classes(data):
        if _ENUM.search(data, max(match.start() - 8, 0), match.start()):
            continue  # ``enum class Mode : uint8_t {``
        name = match.group(2).decode("utf-8", "replace")
        clause = _CPP_COMMENT.sub(b" ", match.group(3) or b"").decode("utf-8", "replace")
        bases = tuple(
            base
            for part in _without_templates(clause).split(",")
            if (base := _CPP_ACCESS.sub("", part.strip()).strip())
        )
        if bases or name not in found:
            found[name] = bases
    return tuple(sorted(found.items()))


def _cpp_classes(data: bytes) -> Iterator[re.Match[bytes]]:
    """``_CPP_CLASS`` matched where each ``class`` or ``struct`` keyword starts, in order:
    found with ``bytes.find``, which is many times faster than a search for either."""
    for keyword in (b"class", b"struct"):
        start = data.find(keyword)
        while start >= 0:
            if start == 0 or not (data[start - 1 : start].isalnum() or data[start - 1] == 95):
                match = _CPP_CLASS.match(data, start)
                if match is not None:
                    yield match
            start = data.find(keyword, start + len(keyword))


def python_class_bases(data: bytes) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """Each class the Python text defines, with its bases (keywords such as
    ``metaclass=`` dropped)."""
    if b"class" not in data:
        return ()
    found: dict[str, tuple[str, ...]] = {}
    for match in _PYTHON_CLASS.finditer(data):
        name = match.group(1).decode("utf-8", "replace")
        bases = tuple(
            base
            for part in (match.group(2) or b"").decode("utf-8", "replace").split(",")
            if (base := part.strip()) and "=" not in base
        )
        if bases or name not in found:
            found[name] = bases
    return tuple(sorted(found.items()))


def _without_templates(text: str) -> str:
    """``Base<T, U>`` as ``Base``: what is between angle brackets goes."""
    kept: list[str] = []
    depth = 0
    for character in text:
        if character == "<":
            depth += 1
        elif character == ">":
            depth = max(depth - 1, 0)
        elif depth == 0:
            kept.append(character)
    return "".join(kept)
