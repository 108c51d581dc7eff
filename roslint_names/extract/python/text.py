"""Python source bytes to text as CPython reads them: BOM, PEP 263 declaration, UTF-8.

Parser-free, so that both the Python extractor (libcst) and the setup.py reader (``ast``)
decode alike, and failures come back as the same ``ParseError`` messages (RN001).
"""

from __future__ import annotations

import codecs
import re

from roslint_names.extract.launch.substitution import Source
from roslint_names.model import ParseError, Span

# PEP 263: a coding declaration in a comment on line 1, or on line 2 after a comment or a
# blank line 1 (the pattern CPython's tokenizer uses).
_CODING = re.compile(rb"^[ \t\f]*#.*?coding[:=][ \t]*([-\w.]+)")
_BLANK_OR_COMMENT = re.compile(rb"^[ \t\f]*(?:[#\r\n]|$)")
_SURROGATE = re.compile("[\ud800-\udfff]")


def _declared_encoding(data: bytes) -> str | None:
    for index, line in enumerate(data.split(b"\n", 2)[:2]):
        match = _CODING.match(line)
        if match:
            return match.group(1).decode("ascii", errors="replace")
        if index == 0 and not _BLANK_OR_COMMENT.match(line):
            return None
    return None


def decode(data: bytes) -> str | ParseError:
    """The text Python would read: BOM, else the PEP 263 declaration, else UTF-8 (with
    the Python extractor's messages when that fails)."""
    bom = data.startswith(codecs.BOM_UTF8)
    declared = _declared_encoding(data[len(codecs.BOM_UTF8) :] if bom else data)
    if bom:
        if declared is not None and _codec(declared) != "utf-8":
            return source_error(f"UTF-8 BOM contradicts the coding declaration '{declared}'", 1, 1)
        encoding, data = "utf-8", data[len(codecs.BOM_UTF8) :]
    else:
        encoding = declared or "utf-8"
    if _codec(encoding) is None:
        return source_error(f"unknown source encoding '{encoding}'", 1, 1)
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError as error:
        before = Source(data[: error.start].decode(encoding, errors="replace"))
        line, column = before.position(len(before.text))
        return source_error(
            f"cannot decode Python source as {encoding}: {error.reason}", line, column
        )
    except Exception as error:  # a codec's own failure (e.g. an incomplete utf-7 shift)
        return source_error(f"cannot decode Python source as {encoding}: {error}", 1, 1)
    # unicode_escape turns "\\ud800" into a lone surrogate, which CPython refuses and
    # libcst cannot even encode.
    surrogate = None if text.isascii() else _SURROGATE.search(text)
    if surrogate is not None:
        line, column = Source(text).position(surrogate.start())
        return source_error(
            f"cannot decode Python source as {encoding}: it gives a lone surrogate "
            f"(U+{ord(surrogate.group()):04X}), which is no character",
            line,
            column,
        )
    return text


def _codec(encoding: str) -> str | None:
    try:
        return codecs.lookup(encoding).name
    except LookupError:
        return None


def source_error(message: str, line: int, column: int) -> ParseError:
    return ParseError(message, Span(line, column, line, column + 1))
