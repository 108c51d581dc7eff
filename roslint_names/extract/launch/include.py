"""Where an included launch file lives, and what its includer hands over to it.

``$(find pkg)/launch/a.launch`` (ROS 1), ``$(find-pkg-share pkg)/launch/a.launch.py`` and
``$(find-pkg-prefix pkg)/share/pkg/launch/a.launch.py`` (ROS 2) name a file in a package;
``$(dirname)/a.launch`` one next to the including file. ``locate`` turns an include's
``file`` value into ``package`` and ``path`` as ``LaunchInclude`` wants them, or says the
location is not statically known.

Parser-free (no lxml), like ``launch_common``, so that the Python launch walker can share
``normalise`` and ``handed_over``.
"""

from __future__ import annotations

import posixpath
from collections.abc import Mapping
from dataclasses import dataclass

from roslint_names.extract.launch.substitution import (
    ARG,
    WHITESPACE,
    Dialect,
    Lookup,
    Value,
    closing_bracket,
)
from roslint_names.model import InPackage, LaunchArguments


@dataclass(frozen=True)
class Target:
    """The included file: in ``package`` (None: the includer's directory, or absolute)."""

    package: str | None
    path: str | None


UNKNOWN = Target(None, None)

_LOOKUP_COMMAND = {Dialect.ROS1: "arg", Dialect.ROS2: "var"}
_SHARE_COMMAND = {Dialect.ROS1: "find", Dialect.ROS2: "find-pkg-share"}
_PREFIX_COMMAND = "find-pkg-prefix"  # ROS 2 only: the install prefix, share/<pkg> below it
_DIRNAME_COMMAND = "dirname"  # both: the directory of the file being read
# An argument whose value is itself an argument reference is followed this deep; deeper
# chains (or a cycle) count as unknown.
_MAX_DEPTH = 8
_BUDGET = 256  # argument lookups per include path


def locate(raw: str, dialect: Dialect, lookup: Lookup) -> Target:
    """The include target ``raw`` names, its other parts substituted with ``lookup``.

    A relative path without ``$(dirname)`` is resolved by the launch system against its
    working directory, which no file tells: it is unknown, as is anything dynamic.
    """
    text = unfold(raw.strip(), dialect, lookup)
    if text is None:
        return UNKNOWN
    if not text.startswith("$("):
        absolute = "$(" not in text and text.startswith("/")
        return Target(None, normalise(text) if absolute else None)
    end = closing_bracket(text, 2)
    if end is None:
        return UNKNOWN
    command, _, argument = text[2:end].strip().partition(" ")
    return _from_head(command, _unquote(argument.strip()), text[end + 1 :], dialect)


def _from_head(command: str, argument: str, rest: str, dialect: Dialect) -> Target:
    """The target once the leading ``$(command argument)`` is split off ``rest``."""
    if command == _DIRNAME_COMMAND and not argument:
        return Target(None, _below(rest))
    in_prefix = dialect is Dialect.ROS2 and command == _PREFIX_COMMAND
    if command != _SHARE_COMMAND[dialect] and not in_prefix:
        return UNKNOWN  # $(env X), $(eval ...), $(optenv ...): no package to name
    if not argument or "$(" in argument or _spaced(argument):
        return UNKNOWN  # a package known only at run time
    return Target(argument, _in_share(argument, rest) if in_prefix else _below(rest))


def _below(rest: str) -> str | None:
    """``/launch/a.launch`` after a directory substitution, as a relative path."""
    if "$(" in rest or not rest.startswith("/"):
        return None  # "$(find pkg)x" names a sibling of the package; anything dynamic
    return normalise(rest.lstrip("/"))


def _in_share(package: str, rest: str) -> str | None:
    """``/share/pkg/launch/a.launch.py`` below an install prefix, relative to share/pkg."""
    relative = _below(rest)
    share = f"share/{package}/"
    if relative is None or not relative.startswith(share):
        return None  # lib/..., or another package's share directory
    return relative[len(share) :] or None


def normalise(path: str) -> str | None:
    """``a/./b//c``, ``a/../b``: '/'-separated, normalised; a relative path keeps its
    leading ``..`` (the includer's parent directory is a real place). None for "." or ""."""
    if not path:
        return None
    if path.startswith("/"):
        return "/" + posixpath.normpath(path).lstrip("/")  # POSIX keeps a leading "//"
    normal = posixpath.normpath(path)
    return None if normal == "." else normal


def in_package(raw: str, dialect: Dialect, lookup: Lookup) -> InPackage | None:
    """A value that is not static but names a file of a package (``$(find-pkg-share
    pkg)/config/a.yaml``, through arguments of this file), as the package and the path in
    it: what an include can hand over of it. None for anything else, a path next to this
    file (``$(dirname)``) among them: the included file lives elsewhere."""
    if "$(" not in raw:
        return None
    target = locate(raw, dialect, lookup)
    if target.package is None or target.path is None:
        return None
    return InPackage(target.package, target.path)


def handed(value: Value) -> str | InPackage | None:
    """What an include hands over of a ROS 2 launch configuration's value: its text, the
    package's file a dynamic value names in ``package_text``'s form, else None."""
    if not value.dynamic:
        return value.text
    return in_package(value.text, Dialect.ROS2, _nothing)


def _nothing(kind: str, name: str) -> Value | None:
    """A lookup that knows no argument: the text is already unfolded."""
    del kind, name
    return None


def package_text(value: InPackage, dialect: Dialect) -> str:
    """The value as the included file's dialect writes it: ``$(find-pkg-share pkg)/path``
    (ROS 2), ``$(find pkg)/path`` (ROS 1)."""
    return f"$({_SHARE_COMMAND[dialect]} {value.package})/{value.path}"


def handed_over(
    inherited: Mapping[str, str | InPackage | None],
    explicit: Mapping[str, str | InPackage | None],
) -> LaunchArguments:
    """The arguments an include passes, sorted by name, None for an unknown value.

    ``inherited`` are the values passed wholesale (ROS 1 ``pass_all_args``, the ROS 2
    launch configurations in scope); ``explicit`` the include's own ``<arg>``s, which win
    even when their value is unknown. An unknown value is handed over as such: the
    included file must not take its default for it.
    """
    return tuple(sorted({**inherited, **explicit}.items()))


def passed_values(arguments: LaunchArguments) -> dict[str, Value]:
    """What an included ROS 2 file sees of the arguments handed to it: a launch
    configuration per argument, dynamic when its value is unknown or a package's file
    (then written as a substitution the file's paths unfold: ``unfold``)."""
    return {name: _passed_value(name, value) for name, value in arguments}


def _passed_value(name: str, value: str | InPackage | None) -> Value:
    if value is None:
        return Value(f"$(var {name})", dynamic=True)
    if isinstance(value, InPackage):
        return Value(package_text(value, Dialect.ROS2), dynamic=True)
    return Value(value)


# ---------------------------------------------------------------------------------------
# Unfolding argument references


def unfold(raw: str, dialect: Dialect, lookup: Lookup) -> str | None:
    """``raw`` with every known ``$(arg x)`` / ``$(var x)`` replaced; the rest as written.

    An argument whose value is not static but written with substitutions (an argument
    defaulting to ``$(find pkg)/launch``, a frequent way to name an include's directory)
    is replaced by that text, unfolded in turn, so that ``locate`` still finds the package.
    An argument with no usable value stays as written: the part of the path it is in is
    unknown, the package before it may still be known. None for unbalanced brackets, or
    when references to references multiply beyond ``_BUDGET`` lookups.
    """
    return _Unfolder(dialect, lookup).unfold(raw, 0)


class _Unfolder:
    def __init__(self, dialect: Dialect, lookup: Lookup) -> None:
        self.command = _LOOKUP_COMMAND[dialect]
        self.lookup = lookup
        self.budget = _BUDGET  # a file may nest references exponentially: bound the work

    def unfold(self, raw: str, depth: int) -> str | None:
        out: list[str] = []
        i = 0
        while (found := raw.find("$(", i)) >= 0:  # text up to the next "$(" stays as it is
            out.append(raw[i:found])
            end = closing_bracket(raw, found + 2)
            replaced = None if end is None else self.replace(raw[found + 2 : end], depth)
            if end is None or replaced is None:
                return None
            out.append(replaced)
            i = end + 1
        out.append(raw[i:])
        return "".join(out)

    def replace(self, body: str, depth: int) -> str | None:
        """One ``$(...)``'s replacement: an argument's value, else the text as written."""
        command, _, argument = body.strip().partition(" ")
        inner = self.unfold(argument.strip(), depth)
        if inner is None:
            return None
        kept = f"$({command} {inner})" if inner else f"$({command})"
        name = _unquote(inner.strip())
        if command != self.command or not name or "$(" in name or _spaced(name):
            return kept
        self.budget -= 1
        if self.budget < 0:
            return None
        value = self.lookup(ARG, name)
        if value is not None and not value.dynamic:
            return value.text
        # A dynamic value's text is its raw text, unless it has none to give (no default,
        # disagreeing declarations): only text with a substitution in it is worth unfolding.
        if value is None or "$(" not in value.text or depth >= _MAX_DEPTH:
            return kept
        return self.unfold(value.text, depth + 1)


def _unquote(text: str) -> str:
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        return text[1:-1]
    return text


def _spaced(text: str) -> bool:
    return WHITESPACE.search(text) is not None
