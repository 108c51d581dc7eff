"""The targets one CMake file defines, and the executables they come to.

A program's sources are its own, then those of every library target of the same file it
links, transitively (nodes often keep their ROS code in the package's library, and a
``main.cpp`` that only spins it). Links are resolved at the end of the file, because CMake
allows linking a library that is defined further down.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from roslint_names.extract.build.cmake_sources import plugin_sources
from roslint_names.model import Executable, ExecutableKind, Span


@dataclass(frozen=True)
class Named:
    """A name as written: its text, where, and whether the file determines it."""

    text: str
    span: Span
    known: bool = True


@dataclass
class Target:
    name: str
    span: Span
    library: bool
    sources: list[str] = field(default_factory=list)
    links: list[str] = field(default_factory=list)
    output: Named | None = None  # OUTPUT_NAME: what the program's file is called


@dataclass(frozen=True)
class Registration:
    """A component registration: the library it names, the plugin and program it makes."""

    library: str | None
    plugin: Named | None
    program: Named | None


class Targets:
    def __init__(self) -> None:
        self._targets: dict[str, Target] = {}
        self._aliases: dict[str, str] = {}
        self._registrations: list[Registration] = []
        self._scripts: list[Executable] = []

    def add(self, name: Named, library: bool) -> Target:
        """The target named ``name``; defined again (in another ``if`` branch), the same."""
        return self._targets.setdefault(name.text, Target(name.text, name.span, library))

    def alias(self, name: str, target: str) -> None:
        self._aliases[name] = target

    def find(self, name: str) -> Target | None:
        return self._targets.get(self._aliases.get(name, name))

    def register(self, registration: Registration) -> None:
        self._registrations.append(registration)

    def script(self, name: Named, path: str | None) -> None:
        sources = (path,) if path else ()
        self._scripts.append(Executable(name.text, ExecutableKind.PROGRAM, sources, name.span))

    def _resolved(self, target: Target) -> tuple[str, ...]:
        sources = dict.fromkeys(target.sources)
        seen = {target.name}
        queue = list(target.links)
        for link in queue:  # the queue grows while it is walked
            linked = self.find(link)
            if linked is None or not linked.library or linked.name in seen:
                continue
            seen.add(linked.name)
            sources.update(dict.fromkeys(linked.sources))
            queue.extend(linked.links)
        return tuple(sources)

    def executables(self) -> tuple[Executable, ...]:
        found = list(self._scripts)
        for target in self._targets.values():
            if target.library:
                continue
            named = target.output or Named(target.name, target.span)
            if named.known:  # else renamed to a name this file does not determine
                sources = self._resolved(target)
                found.append(Executable(named.text, ExecutableKind.PROGRAM, sources, named.span))
        for registration in self._registrations:
            found.extend(self._registered(registration))
        return _merged(found)

    def _registered(self, registration: Registration) -> list[Executable]:
        library = self.find(registration.library) if registration.library else None
        sources = self._resolved(library) if library is not None else ()
        found = []
        if registration.program is not None:
            program = registration.program
            found.append(Executable(program.text, ExecutableKind.PROGRAM, sources, program.span))
        if registration.plugin is not None:
            plugin = registration.plugin
            registered = [item.plugin.text for item in self._registrations if item.plugin]
            matching = plugin_sources(plugin.text, sources, registered)
            found.append(Executable(plugin.text, ExecutableKind.PLUGIN, matching, plugin.span))
        return found


def _merged(found: list[Executable]) -> tuple[Executable, ...]:
    """One executable per name and kind (both branches of an ``if`` may build it): the
    first place it is named, and every source any of them has."""
    merged: dict[tuple[str, ExecutableKind], Executable] = {}
    for executable in sorted(found, key=lambda item: (item.span, item.kind.value, item.name)):
        key = (executable.name, executable.kind)
        earlier = merged.get(key)
        if earlier is None:
            merged[key] = executable
        else:
            sources = tuple(dict.fromkeys(earlier.sources + executable.sources))
            merged[key] = Executable(earlier.name, earlier.kind, sources, earlier.span)
    return tuple(merged.values())
