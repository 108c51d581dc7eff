"""CMakeLists.txt and .cmake files: the programs and component plugins a package builds,
and their sources; and every source any of its targets compiles (``cmake_compiled``).

Build files are context for the workspace model, not linted: a file that stops lexing
yields what was found before the error, and no parse error.

Programs come from ``add_executable`` (and ``cuda_add_executable``,
``ament_auto_add_executable``, ``rosbuild_add_executable``, and the test executables a
rostest file starts by name), with the sources ``target_sources`` adds and those of the
library targets of this file they link (``cmake_targets``). An ``ament_auto`` target
links every ``ament_auto`` library added before it, as ament_cmake_auto does.
``rclcpp_components_register_node`` makes a program named by ``EXECUTABLE`` and a plugin
named by ``PLUGIN``, ``rclcpp_components_register_nodes`` plugins only. Scripts installed
with ``catkin_install_python(PROGRAMS)``/``install(PROGRAMS)`` are programs named by
their file name (or ``RENAME``). ``set_target_properties(... OUTPUT_NAME x)`` renames a
program: launch files name the file, not the target.

Functions and macros defined in the file run at each call with the arguments bound
(``rostutorial(talker)``, demos' ``custom_executable(topics talker)``), and a ``foreach``
over known items once per item: targets made by such helpers get their names. A target
whose name this file does not determine is skipped, and unknown sources are dropped;
``cmake_eval`` says how far variables are followed.
"""

from __future__ import annotations

import codecs
import itertools
import posixpath
from collections.abc import Sequence
from dataclasses import dataclass, field

from roslint_names.extract.build.cmake_compiled import (
    RUNS_BUILD_FILES,
    Compiled,
    compiles_nothing,
)
from roslint_names.extract.build.cmake_eval import (
    DYNAMIC,
    FOLLOWED,
    SOURCE_DIR,
    Value,
    Variables,
    clean,
    split_list,
)
from roslint_names.extract.build.cmake_sources import code_paths, normalise
from roslint_names.extract.build.cmake_syntax import Command, lex
from roslint_names.extract.build.cmake_targets import Named, Registration, Targets
from roslint_names.extract.launch.substitution import Source
from roslint_names.model import FileFacts, Generation, Language

_PROGRAM_COMMANDS = frozenset(
    {
        "add_executable",
        "cuda_add_executable",
        "ament_auto_add_executable",
        "rosbuild_add_executable",
        "add_rostest_gtest",  # (name test_file sources...): the .test file starts it by name
        "catkin_add_executable_with_gtest",  # built for a rostest file to start
    }
)
_LIBRARY_COMMANDS = frozenset(
    {"add_library", "cuda_add_library", "ament_auto_add_library", "rosbuild_add_library"}
)
_INSTALLERS = frozenset({"catkin_install_python", "install"})
_INSTALL_KEYWORDS = frozenset(
    {
        "DESTINATION",
        "TYPE",
        "PERMISSIONS",
        "CONFIGURATIONS",
        "COMPONENT",
        "RENAME",
        "OPTIONAL",
        "EXCLUDE_FROM_ALL",
    }
)
_REGISTER_KEYWORDS = frozenset({"PLUGIN", "EXECUTABLE", "EXECUTOR", "RESOURCE_INDEX"})
_OUTPUT_NAMES = frozenset({"OUTPUT_NAME", "RUNTIME_OUTPUT_NAME"})


# Commands that open a body, and the command that closes each.
_BODY_ENDS = {"function": "endfunction", "macro": "endmacro", "foreach": "endforeach"}
_MAX_CALL_DEPTH = 8  # helpers calling helpers; deeper (or recursive) calls are not followed
_MAX_ITEMS = 256  # a longer foreach list is read once, its variable unknown
# Commands run again from bodies, per file: nested loops and calls stop there, not hang.
_MAX_REPLAYED = 50_000


@dataclass
class _Body:
    """The commands between an opening command and its end, nested ones included."""

    opening: Command
    commands: list[Command] = field(default_factory=list)
    depth: int = 0  # openings of the same command inside


@dataclass(frozen=True)
class _Definition:
    parameters: tuple[str, ...]
    commands: tuple[Command, ...]
    macro: bool  # a macro's variables are its caller's


def _known(text: str) -> bool:
    """The file determines this name: no unknown part, no directory, no generator."""
    return DYNAMIC not in text and SOURCE_DIR not in text and "$<" not in text


class _Build:
    """Follows one file's commands in order, into a ``Targets`` table."""

    def __init__(self, source: Source) -> None:
        self.source = source
        self.variables = Variables()
        self.targets = Targets()
        self.auto_libraries: list[str] = []  # what ament_auto links its next targets to
        self._body: _Body | None = None  # the body being collected, if any
        self._definitions: dict[str, _Definition] = {}
        self._calls = 0  # how deep in function and macro calls
        self._replayed = 0
        self.compiled = Compiled()  # every source any target may compile
        self._defining = 0  # inside a body read where it is defined: it compiles nothing yet
        self._handlers = {
            "target_sources": self._target_sources,
            "target_link_libraries": self._link,
            "set_target_properties": self._properties,
            "rclcpp_components_register_node": self._register_node,
            "rclcpp_components_register_nodes": self._register_nodes,
        }

    def named(self, value: Value) -> Named:
        span = self.source.span(value.start, value.end)
        return Named(value.text, span, _known(value.text))

    def run(self, command: Command) -> None:
        if self._body is not None:
            self._collect(self._body, command)
            return
        name = command.name
        if name in _BODY_ENDS:
            self._body = _Body(command)
            return
        definition = self._definitions.get(name)
        if definition is not None:
            self._call(definition, command)
            return
        handler = self._handlers.get(name)
        targets = name in _PROGRAM_COMMANDS or name in _LIBRARY_COMMANDS
        compiling = not compiles_nothing(name)
        if (
            name not in FOLLOWED
            and handler is None
            and not targets
            and name not in _INSTALLERS
            and not compiling
        ):
            return  # its arguments need no evaluation
        values = self.variables.values(command.arguments)
        self.variables.apply(name, values)
        if compiling and (not self._defining or name in RUNS_BUILD_FILES):
            self.compiled.command(name, values)
        if handler is not None:
            handler(values)
        elif targets and values:
            self._add_target(name, values[0], values[1:])
        elif name in _INSTALLERS and values[:1] and values[0].text == "PROGRAMS":
            self._install_programs(values[1:])

    def open_body(self) -> bool:
        """Whether the file ended inside a body it never closed (a broken file)."""
        return self._body is not None

    # -----------------------------------------------------------------------------------
    # Bodies: functions, macros, loops

    def _collect(self, body: _Body, command: Command) -> None:
        if command.name == body.opening.name:
            body.depth += 1
        elif command.name == _BODY_ENDS[body.opening.name]:
            if body.depth == 0:
                self._body = None
                self._finish(body, command)
                return
            body.depth -= 1
        body.commands.append(command)

    def _finish(self, body: _Body, end: Command) -> None:
        opening = body.opening
        values = self.variables.values(opening.arguments)
        if opening.name == "foreach":
            items = _loop_items(values, self.variables)
            if items is not None:
                for item in items:
                    self.variables.enter("foreach", {values[0].text: item})
                    self._run_all(body.commands)
                    self.variables.leave()
                return
        elif values and not values[0].dynamic:
            self._definitions[values[0].text.lower()] = _Definition(
                tuple(value.text for value in values[1:]),
                tuple(body.commands),
                macro=opening.name == "macro",
            )
        # Read once where it stands, what is not known unknown: a definition's parameters
        # (it may be called from another directory), a loop's variable.
        defining = int(opening.name != "foreach")
        self.variables.apply(opening.name, values)
        self._defining += defining
        self._run_all(body.commands)
        self._defining -= defining
        self.variables.apply(end.name, [])

    def _call(self, definition: _Definition, command: Command) -> None:
        if self._calls >= _MAX_CALL_DEPTH:
            if not self._defining:
                self.compiled.anything()  # a body not followed may compile anything
            return
        texts = [value.text for value in self.variables.values(command.arguments)]
        count = len(definition.parameters)
        bindings = {
            parameter: texts[index] if index < len(texts) else ""
            for index, parameter in enumerate(definition.parameters)
        }
        bindings |= {f"ARGV{index}": text for index, text in enumerate(texts)}
        bindings |= {"ARGN": ";".join(texts[count:]), "ARGV": ";".join(texts)}
        bindings["ARGC"] = str(len(texts))
        self.variables.enter("macro" if definition.macro else "function", bindings)
        self._calls += 1
        self._run_all(definition.commands)
        self._calls -= 1
        self.variables.leave()

    def _run_all(self, commands: Sequence[Command]) -> None:
        """Run a body's commands; a body left open inside (a broken file) ends with it."""
        outer, self._body = self._body, None
        for command in commands:
            self._replayed += 1
            if self._replayed > _MAX_REPLAYED:
                self.compiled.anything()
                break
            self.run(command)
        self._body = outer

    # -----------------------------------------------------------------------------------
    # Targets

    def _add_target(self, command: str, name: Value, rest: list[Value]) -> None:
        kinds = [value.text for value in rest[:2]]  # add_library(name SHARED IMPORTED)
        if "ALIAS" in kinds:
            aliased = rest[kinds.index("ALIAS") + 1 : kinds.index("ALIAS") + 2]
            for aliased_target in aliased:
                self.targets.alias(name.text, aliased_target.text)
            return
        named = self.named(name)
        if "IMPORTED" in kinds or not named.known:
            return  # an imported target is built elsewhere
        target = self.targets.add(named, library=command in _LIBRARY_COMMANDS)
        target.sources.extend(code_paths(value.text for value in rest))
        if command.startswith("ament_auto_"):
            if all(value.text != "NO_TARGET_LINK_LIBRARIES" for value in rest):
                target.links.extend(self.auto_libraries)
            if target.library:
                self.auto_libraries.append(name.text)

    def _target_sources(self, values: list[Value]) -> None:
        target = self.targets.find(values[0].text) if values else None
        if target is not None:
            target.sources.extend(code_paths(value.text for value in values[1:]))

    def _link(self, values: list[Value]) -> None:
        target = self.targets.find(values[0].text) if values else None
        if target is not None:
            target.links.extend(value.text for value in values[1:] if not value.dynamic)

    def _properties(self, values: list[Value]) -> None:
        texts = [value.text for value in values]
        if "PROPERTIES" not in texts:
            return
        split = texts.index("PROPERTIES")
        pairs = values[split + 1 :]
        for key, value in zip(pairs[::2], pairs[1::2], strict=False):
            if key.text in _OUTPUT_NAMES:
                for named in values[:split]:
                    target = self.targets.find(named.text)
                    if target is not None and not target.library:
                        target.output = self.named(value)

    # -----------------------------------------------------------------------------------
    # Components and installed scripts

    def _register_node(self, values: list[Value]) -> None:
        if not values:
            return
        options: dict[str, Named] = {}
        for keyword, value in itertools.pairwise(values[1:]):
            if keyword.text in _REGISTER_KEYWORDS and keyword.text not in options:
                options[keyword.text] = self.named(value)
        plugin, program = options.get("PLUGIN"), options.get("EXECUTABLE")
        self.targets.register(
            Registration(
                values[0].text if _known(values[0].text) else None,
                plugin if plugin is not None and plugin.known else None,
                program if program is not None and program.known else None,
            )
        )

    def _register_nodes(self, values: list[Value]) -> None:
        library = values[0].text if values and _known(values[0].text) else None
        skip = False
        for value in values[1:]:
            if skip or value.text == "RESOURCE_INDEX":
                skip = not skip  # the keyword, then its value
                continue
            named = self.named(value)
            if named.known:
                self.targets.register(Registration(library, named, None))

    def _install_programs(self, values: list[Value]) -> None:
        texts = [value.text for value in values]
        end = next((i for i, text in enumerate(texts) if text in _INSTALL_KEYWORDS), len(texts))
        rename = None
        if "RENAME" in texts[end:] and texts.index("RENAME", end) + 1 < len(values):
            rename = self.named(values[texts.index("RENAME", end) + 1])
        for file in values[:end]:
            self._script(file, rename if end == 1 else None)  # RENAME takes one file only

    def _script(self, file: Value, rename: Named | None) -> None:
        if "$<" in file.text:
            return
        if rename is None:
            # The installed name is the file's: known even when its directory is not.
            named = self.named(file)
            basename = posixpath.basename(file.text.rstrip("/"))
            rename = Named(basename, named.span, bool(basename) and _known(basename))
        if rename.known:
            self.targets.script(rename, normalise(file.text))


def _loop_items(values: Sequence[Value], variables: Variables) -> list[str] | None:
    """The items ``foreach(var ...)`` runs over, None when the file does not tell them
    (``RANGE``, ``ZIP_LISTS``, a list too long or unknown as a whole)."""
    if not values or values[0].dynamic:
        return None
    rest = [value.text for value in values[1:]]
    items: list[str] = []
    if rest[:1] == ["IN"]:
        mode = None
        for word in rest[1:]:
            if word in ("LISTS", "ITEMS"):
                mode = word
            elif mode == "LISTS":
                items.extend(split_list(variables.get(word)) if variables.is_set(word) else [])
            elif mode == "ITEMS":
                items.append(word)
            else:
                return None  # ZIP_LISTS, or a form we do not know
    elif rest[:1] == ["RANGE"]:
        return None
    else:
        items = rest
    if len(items) > _MAX_ITEMS or any(item == DYNAMIC for item in items):
        return None
    return items


def _decode(data: bytes) -> str:
    """CMake reads its files as UTF-8; a BOM is not part of the first line."""
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8) :]
    return clean(data.decode("utf-8", errors="replace"))


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
) -> FileFacts:
    """The programs and component plugins ``path`` builds or installs."""
    text = _decode(data)
    build = _Build(Source(text))
    lexed = lex(text)
    for command in lexed.commands:  # a lexing error only ends the list
        build.run(command)
    if lexed.error is not None or build.open_body():
        build.compiled.anything()  # what follows the error (or a body left open) is unknown
    return FileFacts(
        path,
        Language.CMAKE,
        package_generation or fallback_generation,
        executables=build.targets.executables(),
        compiled=build.compiled.result(),
    )
