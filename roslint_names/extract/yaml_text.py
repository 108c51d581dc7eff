"""YAML text as every YAML extractor reads it: decoded as the YAML spec says, composed
into PyYAML's node graph (with marks for spans), or the error the user sees as RN001.

PyYAML is imported where a YAML file is read, never at import time: a one-file run on a
C++ or launch XML file does not pay for it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from roslint_names.extract.launch.substitution import Source
from roslint_names.model import ParseError, Span
from roslint_names.reading import bom_encoding

if TYPE_CHECKING:
    import yaml


def decode(data: bytes) -> str | ParseError:
    """Text as the YAML spec reads it: UTF-8, or UTF-16/32 announced by a BOM."""
    encoding = bom_encoding(data) or "utf-8"
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError as error:
        before = Source(data[: error.start].decode(encoding, errors="replace"))
        line, column = before.position(len(before.text))
        message = f"cannot decode YAML as {encoding}: {error.reason}"
        return ParseError(message, Span(line, column, line, column + 1))
    return text[1:] if text.startswith("\ufeff") else text


def compose(text: str, *, libyaml: bool = False) -> yaml.Node | ParseError | None:
    """The node graph, or the error PyYAML reports (its marks are 0-based). With
    ``libyaml``, the C loader where PyYAML was built with it (rcl's own parser): the same
    nodes and marks, faster."""
    import yaml

    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader) if libyaml else yaml.SafeLoader
    try:
        return yaml.compose(text, Loader=loader)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        line, column = (mark.line + 1, mark.column + 1) if mark else (1, 1)
        problem = error.problem or error.context or "malformed YAML"
        return ParseError(f"cannot parse YAML: {problem}", Span(line, column, line, column + 1))
    except yaml.reader.ReaderError as error:
        line, column = Source(text).position(error.position)
        character = error.character
        shown = f"#x{character:04x}" if isinstance(character, int) else repr(character)
        message = f"cannot parse YAML: unacceptable character {shown}"
        return ParseError(message, Span(line, column, line, column + 1))
    except yaml.YAMLError as error:
        return ParseError(f"cannot parse YAML: {error}", Span(1, 1, 1, 2))
    except RecursionError:
        return ParseError("cannot parse YAML: nested too deeply", Span(1, 1, 1, 2))
