"""ROS 1 service definitions, compared as roscpp and rospy compare them: by md5sum.

A ROS 1 client and server connect when the md5sums of their service types agree,
whatever the types are called: the server refuses a client whose md5sum differs (roscpp:
``ServiceClientLink::handleHeader`` in ``clients/roscpp/src/libros/service_client_link.cpp``,
"client wants service ... to have md5sum ..., but it has ...";
rospy: ``service_connection_handler`` in ``clients/rospy/src/rospy/impl/tcpros_service.py``,
"md5sums do not match"). genmsg computes that md5sum (``compute_md5_text`` and
``_compute_hash`` in ``src/genmsg/gentools.py``) over the request's text then the
response's, each with comments and whitespace out, constants first, a nested type by the
md5sum of its own definition, and the type's name nowhere: ``roscpp_tutorials/TwoInts`` and
``rospy_tutorials/AddTwoInts`` are one service.

``ServiceDefinition`` keeps that text with each nested type by its full name, since the
``.msg`` it names is not read here: two definitions with equal texts have equal md5sums,
and two whose texts differ outside the nested types' names never do. Between the two
(``my_pkg/Pose`` where the other has ``geometry_msgs/Pose``) nothing is decided.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from roslint_names.model import Generation, Language
from roslint_names.reading import MAX_DEFINITION_BYTES, read_file

if TYPE_CHECKING:
    from roslint_names.discover import SourceFile
    from roslint_names.generation import PackageGenerations

# genmsg's ``msgs.PRIMITIVE_TYPES`` (``char`` and ``byte`` deprecated but accepted) and
# ``BUILTIN_TYPES``: the types written into the md5 text by name.
_PRIMITIVE_TYPES = frozenset(
    {
        "int8",
        "uint8",
        "int16",
        "uint16",
        "int32",
        "uint32",
        "int64",
        "uint64",
        "float32",
        "float64",
        "string",
        "bool",
        "char",
        "byte",
    }
)
_BUILTIN_TYPES = _PRIMITIVE_TYPES | {"time", "duration"}
_SEPARATOR = "---"  # genmsg's IODELIM, matched at the start of a line as it does
_NESTED = "*"  # a nested type in ``ServiceDefinition.shape``


@dataclass(frozen=True)
class ServiceDefinition:
    """genmsg's md5 text of a service: the request's then the response's.

    ``text`` names each nested type by its full name (``std_msgs/Header``); ``shape`` is
    the same text with every nested type as ``*``.
    """

    text: str
    shape: str

    def same_md5(self, other: ServiceDefinition) -> bool | None:
        """Whether the two md5sums are equal; None when only the nested types' own
        definitions, which are not read, could tell."""
        if self.text == other.text:
            return True
        if self.shape != other.shape:
            return False
        return None


def parse_service(text: str, package: str) -> ServiceDefinition | None:
    """A ``.srv`` file's definition; None for text genmsg would refuse (the package then
    does not build, and no node serves the type).

    Follows ``load_srv_from_string`` and ``load_msg_from_string`` in genmsg's
    ``src/genmsg/msg_loader.py``: the first line starting with ``---`` splits request
    from response, ``#`` starts a comment (but not in a string constant's value), and a
    type without a package is the package's own (``Header`` is ``std_msgs/Header``).
    """
    request: list[str] = []
    response: list[str] = []
    part = request
    for line in text.split("\n"):
        if line.startswith(_SEPARATOR):
            part = response
        else:
            part.append(line)
    parsed = [_md5_text(lines, package) for lines in (request, response)]
    if parsed[0] is None or parsed[1] is None:
        return None
    (request_text, request_shape), (response_text, response_shape) = parsed[0], parsed[1]
    # _compute_hash feeds the two texts one after the other into one md5.
    return ServiceDefinition(request_text + response_text, request_shape + response_shape)


def _md5_text(lines: Iterable[str], package: str) -> tuple[str, str] | None:
    """``compute_md5_text`` of one message: constants first, then the fields, in order."""
    constants: list[str] = []
    fields: list[tuple[str, str]] = []
    for line in lines:
        clean = line.split("#", 1)[0].strip()
        if not clean:
            continue
        if "=" in clean:
            constant = _constant(line, clean)
            if constant is None:
                return None
            constants.append(constant)
        else:
            field = _field(clean, package)
            if field is None:
                return None
            fields.append(field)
    text = "".join(f"{c}\n" for c in constants) + "".join(f"{f}\n" for f, _ in fields)
    shape = "".join(f"{c}\n" for c in constants) + "".join(f"{s}\n" for _, s in fields)
    return text.strip(), shape.strip()


def _tokens(clean: str) -> list[str]:
    # genmsg splits on single spaces and drops empty pieces: a tab is part of a token.
    return [piece.strip() for piece in clean.split(" ") if piece.strip()]


def _constant(line: str, clean: str) -> str | None:
    """``_load_constant_line``: a string constant's value is the rest of the raw line."""
    tokens = _tokens(clean)
    kind = tokens[0]
    if kind not in _PRIMITIVE_TYPES:
        return None
    if kind == "string":
        equals = line.find("=")
        name, value = line[line.find(" ") + 1 : equals], line[equals + 1 :]
    else:
        sides = [side.strip() for side in " ".join(tokens[1:]).split("=")]
        if len(sides) != 2:
            return None
        name, value = sides
    return f"{kind} {name}={value.strip()}"


def _field(clean: str, package: str) -> tuple[str, str] | None:
    """``_load_field_line``, then the field's line of the md5 text and of the shape."""
    tokens = _tokens(clean)
    if len(tokens) != 2:
        return None
    kind, name = tokens
    bare = kind.partition("[")[0]
    if bare in _BUILTIN_TYPES:
        return f"{kind} {name}", f"{kind} {name}"
    if bare == "Header":
        bare = "std_msgs/Header"
    elif "/" not in bare:
        bare = f"{package}/{bare}"
    # A nested field is written as its type's md5sum and its name: the array suffix is
    # not written (``compute_md5_text``), so ``Pose[] a`` and ``Pose a`` hash alike.
    return f"{bare} {name}", f"{_NESTED} {name}"


# std_srvs, which most ROS 1 workspaces use without holding: its three definitions have
# not changed since ROS Fuerte (ros/ros_comm_msgs, ``std_srvs/srv/*.srv``).
WELL_KNOWN: dict[str, ServiceDefinition] = {
    name: definition
    for name, text in (
        ("std_srvs/Empty", "---\n"),
        ("std_srvs/Trigger", "---\nbool success\nstring message\n"),
        ("std_srvs/SetBool", "bool data\n---\nbool success\nstring message\n"),
    )
    if (definition := parse_service(text, "std_srvs")) is not None
}


def service_definitions(
    sources: Iterable[SourceFile], packages: PackageGenerations
) -> dict[str, tuple[tuple[str, ServiceDefinition], ...]]:
    """package directory (``PackageGenerations.package_root``) -> (type name, definition)
    of each ``.srv`` of a package that is not ROS 2 only; files that cannot be read or
    parsed are left out (unknown types)."""
    found: dict[str, list[tuple[str, ServiceDefinition]]] = {}
    for source in sources:
        if source.language is not Language.SERVICE_DEFINITION:
            continue
        directory = packages.package_root(source.location)
        package = packages.package_name(source.path)
        if directory is None or package is None:
            continue
        if packages.for_file(source.path) is Generation.ROS2:
            continue
        definition = _read(source.path, package)
        if definition is not None:
            found.setdefault(directory, []).append((source.path.stem, definition))
    return {
        directory: tuple(sorted(pairs, key=lambda pair: pair[0]))
        for directory, pairs in found.items()
    }


def _read(path: Path, package: str) -> ServiceDefinition | None:
    data, _, skipped = read_file(path, MAX_DEFINITION_BYTES)
    if data is None or skipped is not None:
        return None
    return parse_service(data.decode("utf-8", errors="replace"), package)
