"""Where an ``IncludeLaunchDescription`` of a launch.py points, without running it.

The launch file's path is evaluated into a ``Piece``: a base directory (a package's share
directory, the including file's directory, or none: plain text) and the text after it,
following the forms real launch files use: ``PathJoinSubstitution([FindPackageShare('p'),
'launch', 'a.launch.py'])``, ``[FindPackageShare('p'), '/launch/a.launch.py']``,
``os.path.join(get_package_share_directory('p'), 'launch', 'a.py')`` through variables,
f-strings, ``+``, pathlib's ``/``, ``ThisLaunchFileDir()`` and
``os.path.dirname(__file__)``. Everything else (strings, constants, ``LaunchConfiguration``)
is ``LaunchValues.text``: the one evaluator of launch values, reused, not repeated.
"""

from __future__ import annotations

import dataclasses
import posixpath
from dataclasses import dataclass
from enum import Enum

import libcst as cst

from roslint_names.extract.launch.include import handed
from roslint_names.extract.launch.python_values import (
    LaunchScope,
    LaunchValues,
    Written,
    call_argument,
    class_key,
    string_parts,
)
from roslint_names.extract.launch.substitution import Value
from roslint_names.model import InPackage

_MAX_DEPTH = 16  # variables defined through variables; deeper (or cyclic) is unknown

# Sources that load a launch file from a path (their first argument).
_FILE_SOURCES = frozenset(
    {
        "PythonLaunchDescriptionSource",
        "XMLLaunchDescriptionSource",
        "YAMLLaunchDescriptionSource",
        "FrontendLaunchDescriptionSource",
        "AnyLaunchDescriptionSource",
    }
)
_INLINE_SOURCE = ("launch", "LaunchDescriptionSource")  # wraps a LaunchDescription object

# Calls, by their qualified name (or ``class_key`` for the launch packages).
_JOIN = frozenset({"os.path.join", "posixpath.join"})
_DIRNAME = frozenset({"os.path.dirname", "posixpath.dirname"})
_SAME_PATH = frozenset({"os.path.realpath", "os.path.abspath", "os.path.normpath", "os.fspath"})
_PATHLIB = frozenset({"pathlib.Path", "pathlib.PurePath", "pathlib.PosixPath"})
_SAME_METHODS = frozenset({"resolve", "absolute", "as_posix"})  # Path methods: same path
_SHARE = frozenset(
    {
        ("ament_index_python", "get_package_share_directory"),
        ("ament_index_python", "get_package_share_path"),
        ("launch_ros", "FindPackageShare"),
    }
)
_THIS_DIRECTORY = ("launch", "ThisLaunchFileDir")
_THIS_FILE = ("launch", "ThisLaunchFile")
_PATH_JOIN = ("launch", "PathJoinSubstitution")
_PATH_SUBSTITUTION = ("launch", "PathSubstitution")  # Jazzy: PathSubstitution(x) / 'y'
_CONFIGURATION = ("launch", "LaunchConfiguration")


class Base(Enum):
    TEXT = "text"  # a plain string: absolute, or relative to launch's working directory
    PACKAGE = "package"  # a package's share directory
    HERE = "here"  # the including file's directory


@dataclass(frozen=True)
class Piece:
    """A path, or part of one: its base directory and the text after it.

    ``rest`` follows the base directly: ``''`` for the directory itself, ``'/launch/a.py'``
    under it (text glued to a directory's name, ``'launch'``, locates nothing); None when
    not static. A TEXT piece always has its text: an unknown plain string is no piece.
    ``package`` names the PACKAGE base, None when dynamic.
    """

    base: Base
    rest: str | None
    package: str | None = None


@dataclass(frozen=True)
class Source:
    """What an include's ``launch_description_source`` is: a file's path, or an inline
    ``LaunchDescriptionSource(LaunchDescription([...]))`` of this file."""

    path: Written | None = None
    inline: Written | None = None


class IncludePaths:
    """Evaluates include paths with ``values`` for everything that is not a path call."""

    def __init__(self, values: LaunchValues, file_name: str) -> None:
        self.values = values
        self.file_name = file_name  # what ``__file__`` ends with

    # -- the source ---------------------------------------------------------------------

    def source(self, located: Written, depth: int = 0) -> Source:
        """``PythonLaunchDescriptionSource(path)`` and its siblings; since Humble a bare
        path (or substitution list) is accepted too."""
        expr = located.expr
        if depth > _MAX_DEPTH:
            return Source()
        if isinstance(expr, cst.Name):
            bound = self.values.bound(located)
            return Source(path=located) if bound is None else self.source(bound, depth + 1)
        if not isinstance(expr, cst.Call):
            return Source(path=located)
        names = located.scope.qualified(expr.func)
        if any(name.rpartition(".")[2] in _FILE_SOURCES for name in names):
            return Source(path=call_argument(expr, located.context, "0:launch_file_path"))
        if any(class_key(name) == _INLINE_SOURCE for name in names):
            return Source(inline=call_argument(expr, located.context, "0:launch_description"))
        return Source(path=located)

    def locate(self, located: Written, scope: LaunchScope) -> tuple[str | None, str | None]:
        """(package, path) as ``LaunchInclude`` gives them."""
        return _located(self.piece(located, scope, 0))

    # -- pieces -------------------------------------------------------------------------

    def piece(self, located: Written, scope: LaunchScope, depth: int) -> Piece | None:
        expr = located.expr
        if depth > _MAX_DEPTH:
            return None
        if isinstance(expr, cst.Call):
            return self.call(located, scope, depth)
        if isinstance(expr, cst.List | cst.Tuple):  # a substitution list: concatenated
            return self.concatenation(self.elements(located), scope, depth)
        if isinstance(expr, cst.FormattedString) or (
            isinstance(expr, cst.BinaryOperation) and isinstance(expr.operator, cst.Add)
        ):
            return self.strings(located, scope, depth)
        if isinstance(expr, cst.BinaryOperation) and isinstance(expr.operator, cst.Divide):
            parts = [Written(expr.left, located.context), Written(expr.right, located.context)]
            return self.joined(parts, scope, depth)  # pathlib's and PathSubstitution's /
        if isinstance(expr, cst.Attribute) and expr.attr.value == "parent":
            inner = self.piece(Written(expr.value, located.context), scope, depth + 1)
            return _parent(inner)
        if isinstance(expr, cst.Name):
            if expr.value == "__file__" and not located.scope.lookup("__file__"):
                return Piece(Base.HERE, f"/{self.file_name}")
            bound = self.values.bound(located)
            if bound is not None:
                return self.piece(bound, scope, depth + 1)
        return self.text(located, scope, depth)

    def text(self, located: Written, scope: LaunchScope, depth: int) -> Piece | None:
        text = self.values.text(located, scope, depth + 1)
        return None if text is None else Piece(Base.TEXT, text)

    def elements(self, located: Written) -> list[Written]:
        expr = located.expr
        assert isinstance(expr, cst.List | cst.Tuple)
        return [
            Written(element.value, located.context.inside(element)) for element in expr.elements
        ]

    def concatenation(self, parts: list[Written], scope: LaunchScope, depth: int) -> Piece | None:
        found: Piece | None = Piece(Base.TEXT, "")
        for part in parts:
            found = _concatenate(found, self.piece(part, scope, depth + 1))
        return found

    def joined(self, parts: list[Written], scope: LaunchScope, depth: int) -> Piece | None:
        if not parts:
            return None
        found = self.piece(parts[0], scope, depth + 1)
        for part in parts[1:]:
            found = _join(found, self.piece(part, scope, depth + 1))
        return found

    def strings(self, located: Written, scope: LaunchScope, depth: int) -> Piece | None:
        """``a + b`` and f-strings: their parts concatenated."""
        parts = string_parts(located)
        if parts is None:
            return None
        found: Piece | None = Piece(Base.TEXT, "")
        for part in parts:
            piece = (
                Piece(Base.TEXT, part)
                if isinstance(part, str)
                else self.piece(part, scope, depth + 1)
            )
            found = _concatenate(found, piece)
        return found

    # -- calls --------------------------------------------------------------------------

    def call(self, located: Written, scope: LaunchScope, depth: int) -> Piece | None:
        call = located.expr
        assert isinstance(call, cst.Call)
        qualified = set(located.scope.qualified(call.func))
        keys = {class_key(name) for name in qualified}
        arguments = [
            Written(item.value, located.context.inside(call).inside(item))
            for item in call.args
            if item.keyword is None and not item.star
        ]
        if qualified & _JOIN or qualified & _PATHLIB:
            return self.joined(arguments, scope, depth)
        if qualified & _DIRNAME and len(arguments) == 1:
            return _parent(self.piece(arguments[0], scope, depth + 1))
        same = qualified & _SAME_PATH or _PATH_SUBSTITUTION in keys or _is_str(call, located)
        if same and len(arguments) == 1:
            return self.piece(arguments[0], scope, depth + 1)
        if keys & _SHARE:
            return self.share(located, scope, depth)
        if _THIS_DIRECTORY in keys:
            return Piece(Base.HERE, "")
        if _THIS_FILE in keys:
            return Piece(Base.HERE, f"/{self.file_name}")
        if _PATH_JOIN in keys:
            return self.path_join(located, scope, depth)
        if _CONFIGURATION in keys:
            return self.configuration(located, scope, depth)
        return self.method(located, scope, depth)

    def method(self, located: Written, scope: LaunchScope, depth: int) -> Piece | None:
        """``path.resolve()``, ``path.joinpath('a', 'b')``; anything else by its text."""
        call = located.expr
        assert isinstance(call, cst.Call)
        func = call.func
        if not isinstance(func, cst.Attribute) or any(item.star for item in call.args):
            return self.text(located, scope, depth)
        owner = Written(func.value, located.context)
        if func.attr.value in _SAME_METHODS and not call.args:
            return self.piece(owner, scope, depth + 1)
        if func.attr.value == "joinpath":
            inner = located.context.inside(call)
            parts = [Written(item.value, inner.inside(item)) for item in call.args]
            return self.joined([owner, *parts], scope, depth)
        return self.text(located, scope, depth)

    def share(self, located: Written, scope: LaunchScope, depth: int) -> Piece:
        """``FindPackageShare('p')``, ``get_package_share_directory('p')``: the package is
        known when its name is, even if the rest of the path is not."""
        assert isinstance(located.expr, cst.Call)
        name = call_argument(located.expr, located.context, "0:package|package_name")
        package = None if name is None else self.values.text(name, scope, depth + 1)
        return Piece(Base.PACKAGE, "", package or None)

    def path_join(self, located: Written, scope: LaunchScope, depth: int) -> Piece | None:
        """``PathJoinSubstitution([a, b, c])``: each element a substitution list, joined."""
        assert isinstance(located.expr, cst.Call)
        parts = call_argument(located.expr, located.context, "0:substitutions")
        if parts is None:
            return None
        return self.joined(self.values.items(parts), scope, depth)

    def configuration(self, located: Written, scope: LaunchScope, depth: int) -> Piece | None:
        """A ``LaunchConfiguration`` whose value is a path: what it is set to as text, else
        the declared default or its own ``default=``, evaluated as paths."""
        found = self.text(located, scope, depth)
        if found is not None:
            return found
        assert isinstance(located.expr, cst.Call)
        name_at = call_argument(located.expr, located.context, "0:variable_name")
        name = None if name_at is None else self.values.text(name_at, scope, depth + 1)
        if name is None:
            return None  # a name we cannot know
        if name in scope.variables:
            return _package_file(scope.variables[name])  # set to something dynamic
        declared = self.values.declarations(name)
        if declared:
            pieces = {
                None if default is None else self.piece(default, scope, depth + 1)
                for default in declared
            }
            return pieces.pop() if len(pieces) == 1 else None
        default = call_argument(located.expr, located.context, "1:default")
        return None if default is None else self.piece(default, scope, depth + 1)


# -- operations on pieces ----------------------------------------------------------------


def _package_file(value: Value) -> Piece | None:
    """A dynamic configuration that an includer set to a package's file
    (``include.handed``), as the piece that file's path is."""
    found = handed(value)
    if not isinstance(found, InPackage):
        return None
    return Piece(Base.PACKAGE, f"/{found.path}", found.package)


def _concatenate(left: Piece | None, right: Piece | None) -> Piece | None:
    """``left + right`` as strings (substitution lists, ``+``, f-strings)."""
    if left is None:
        return None
    if left.base is Base.TEXT and not left.rest:
        return right
    if right is None:
        return None if left.base is Base.TEXT else dataclasses.replace(left, rest=None)
    if right.base is not Base.TEXT:
        return None  # a directory glued after text: nothing launch could open
    if left.rest is None:
        return left
    return dataclasses.replace(left, rest=left.rest + (right.rest or ""))


def _join(left: Piece | None, right: Piece | None) -> Piece | None:
    """``os.path.join(left, right)``: an absolute right side replaces the left one."""
    if right is not None and (right.base is not Base.TEXT or (right.rest or "").startswith("/")):
        return right
    if left is None:
        return None
    if right is None:
        return None if left.base is Base.TEXT else dataclasses.replace(left, rest=None)
    if left.rest is None:
        return left
    if left.base is Base.TEXT and not left.rest:
        return right
    separator = "" if left.rest.endswith("/") else "/"
    return dataclasses.replace(left, rest=f"{left.rest}{separator}{right.rest}")


def _parent(piece: Piece | None) -> Piece | None:
    """``os.path.dirname``, pathlib's ``.parent``."""
    if piece is None or piece.rest is None:
        return None if piece is None or piece.base is Base.TEXT else piece
    if piece.base is Base.TEXT:
        return Piece(Base.TEXT, posixpath.dirname(piece.rest))
    inner = posixpath.normpath(posixpath.join(piece.rest.lstrip("/") or ".", ".."))
    rest = "" if inner == "." else f"/{inner}"
    if piece.base is Base.PACKAGE and rest.startswith("/.."):
        return dataclasses.replace(piece, rest=None)  # above the share directory
    return dataclasses.replace(piece, rest=rest)


def _located(piece: Piece | None) -> tuple[str | None, str | None]:
    if piece is None:
        return None, None
    if piece.base is Base.PACKAGE:
        if piece.package is None:
            return None, None
        inside = _inside(piece.rest)
        # '..' leaves the share directory: another package's, or none, we do not guess.
        return piece.package, None if inside is None or inside.startswith("..") else inside
    if piece.base is Base.HERE:
        return None, _inside(piece.rest)
    rest = piece.rest or ""
    # A relative plain path is opened from launch's working directory: unknown here.
    return None, posixpath.normpath(rest) if rest.startswith("/") else None


def _inside(rest: str | None) -> str | None:
    """The path under a base directory, normalised; None for the directory itself or a
    name glued to the directory's own (``FindPackageShare('p') + 'launch'``)."""
    if rest is None or not rest.startswith("/"):
        return None
    normalised = posixpath.normpath(rest.lstrip("/") or ".")
    return None if normalised == "." else normalised


def _is_str(call: cst.Call, located: Written) -> bool:
    """The builtin ``str(...)`` (not a local name shadowing it)."""
    func = call.func
    return isinstance(func, cst.Name) and func.value == "str" and not located.scope.lookup("str")
