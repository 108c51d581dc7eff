"""console_scripts entries, and setup.cfg's ``[options.entry_points]``.

An entry ``talker = a.b.c:main [extra]`` is a program ``talker`` whose source is module
``a.b.c``, given as ``a/b/c.py`` relative to the build file. setup.cfg is read with
configparser; a file it rejects gives nothing (build files are context, not linted).
Since configparser keeps no positions, each entry's span is found by searching the text
for it, in order, from the ``console_scripts`` line down: the span covers the entry.
"""

from __future__ import annotations

import codecs
import configparser
import re

from roslint_names.model import Executable, ExecutableKind, Span

# name = package.module[:function] [extras]
_ENTRY = re.compile(r"\s*([^=\s][^=]*?)\s*=\s*(\w+(?:\.\w+)*)\s*(?::\s*[\w.]+\s*)?(?:\[.*\])?\s*")
_LINE_BREAK = re.compile(r"\r\n|\r|\n")
_ENTRY_SECTIONS = ("options.entry_points", "entry_points")  # setuptools, then pbr
_HEADER = re.compile(r"\[(.+)\]")  # configparser's: at the start of a line
_CONSOLE_SCRIPTS = re.compile(r"console_scripts\s*[=:]", re.IGNORECASE)


def program(entry: str, span: Span) -> Executable | None:
    """The program a console_scripts entry installs, or None if it is no entry."""
    match = _ENTRY.fullmatch(entry)
    if not match:
        return None
    source = match.group(2).replace(".", "/") + ".py"
    return Executable(match.group(1), ExecutableKind.PROGRAM, (source,), span)


def ini_console_scripts(text: str) -> list[str]:
    """The entries under ``[console_scripts]`` of an entry_points.txt-style string."""
    entries: list[str] = []
    section = None
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("[") and stripped.endswith("]"):
            section = stripped[1:-1].strip()
        elif section == "console_scripts" and stripped and not stripped.startswith(("#", ";")):
            entries.append(stripped)
    return entries


def console_scripts(data: bytes) -> tuple[Executable, ...]:
    """The programs a setup.cfg's console_scripts install."""
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8) :]
    text = data.decode("utf-8", errors="replace")
    parser = configparser.ConfigParser(interpolation=None)
    try:
        parser.read_string(text)
    except configparser.Error:
        return ()
    for section in _ENTRY_SECTIONS:
        if parser.has_option(section, "console_scripts"):
            entries = [line.strip() for line in parser.get(section, "console_scripts").splitlines()]
            spans = _cfg_spans(text, section, [entry for entry in entries if entry])
            found = (program(entry, span) for entry, span in spans)
            return tuple(installed for installed in found if installed is not None)
    return ()


def _cfg_spans(text: str, section: str, entries: list[str]) -> list[tuple[str, Span]]:
    """Where each entry is written: searched for in order from the option's line down
    (configparser keeps no positions)."""
    lines = _LINE_BREAK.split(text)
    current, index = None, len(lines)
    for number, line in enumerate(lines):
        header = _HEADER.match(line)
        if header:
            current = header.group(1).strip()
        elif current == section and _CONSOLE_SCRIPTS.match(line):
            index = number
            break
    located = []
    for entry in entries:
        while index < len(lines) and entry not in lines[index]:
            index += 1
        if index >= len(lines):
            break
        first = lines[index].find(entry) + 1
        located.append((entry, Span(index + 1, first, index + 1, first + len(entry))))
        index += 1
    return located
