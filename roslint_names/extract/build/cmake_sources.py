"""Source paths of CMake targets: normalisation, and which files hold a component class."""

from __future__ import annotations

import posixpath
import re
from collections.abc import Iterable, Sequence

from roslint_names.extract.build.cmake_eval import DYNAMIC, SOURCE_DIR

# C, C++, CUDA and Python sources and headers; the .C/.H spellings are C++ to CMake.
CODE_SUFFIXES = frozenset(
    {
        ".c",
        ".cc",
        ".cpp",
        ".cxx",
        ".c++",
        ".C",
        ".h",
        ".hh",
        ".hpp",
        ".hxx",
        ".h++",
        ".H",
        ".ipp",
        ".inl",
        ".tpp",
        ".txx",
        ".cu",
        ".cuh",
        ".py",
    }
)


def normalise(text: str) -> str | None:
    """``text`` as a '/'-separated path relative to the build file's directory, or None
    when the file does not determine it (unknown variables, generator expressions, an
    absolute path outside the package)."""
    if DYNAMIC in text or "$<" in text:
        return None
    if text.startswith(SOURCE_DIR):
        text = text[len(SOURCE_DIR) :].lstrip("/")
    if SOURCE_DIR in text or text.startswith("/") or not text:
        return None
    path = posixpath.normpath(text)
    return None if path == "." else path


def code_paths(texts: Iterable[str]) -> list[str]:
    """The normalised source and header paths among ``texts``; keywords, flags, data files
    and anything unknown drop out."""
    paths = (normalise(text) for text in texts)
    return [path for path in paths if path and posixpath.splitext(path)[1] in CODE_SUFFIXES]


_WORD_START = re.compile(r"(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])")
# Component sources are often named after the class plus one of these.
_SUFFIXES = ("_component", "_node")


def _snake(name: str) -> str:
    return _WORD_START.sub("_", name).lower()


def _forms(name: str) -> set[str]:
    """``name`` in snake_case, also without a ``_component``/``_node`` suffix, with the
    underscores dropped: ``PointCloudMapLoaderNode`` is ``pointcloud_map_loader_node.cpp``."""
    snake = _snake(name)
    forms = {snake}
    forms.update(snake.removesuffix(suffix) for suffix in _SUFFIXES if snake.endswith(suffix))
    forms.discard("")
    return {form.replace("_", "") for form in forms}


def plugin_sources(
    plugin: str, sources: Sequence[str], registered: Iterable[str] = ()
) -> tuple[str, ...]:
    """The library sources that hold component class ``plugin`` and the code it runs:
    the files named after the class (``pkg::Talker`` -> ``talker.cpp``,
    ``talker_component.hpp``), and the helpers beside them (``utils.cpp``, a
    ``parameter_handler.cpp`` given the node): files named neither after another class
    ``registered`` in the build file nor as another node's (``*_node.cpp``,
    ``*_component.cpp``). All of the library when no file is named after the class."""
    wanted = _forms(plugin.rsplit("::", 1)[-1])
    others: set[str] = set()
    for other in registered:
        others.update(_forms(other.rsplit("::", 1)[-1]))
    others -= wanted
    stems = {path: posixpath.splitext(posixpath.basename(path))[0] for path in sources}
    named = {path for path, stem in stems.items() if _forms(stem) & wanted}
    if not named:
        return tuple(sources)
    return tuple(
        path
        for path, stem in stems.items()
        if path in named or not (_forms(stem) & others or _snake(stem).endswith(_SUFFIXES))
    )
