"""Python source text and tree: PEP 263 / BOM decoding and libcst parsing.

Failures come back as ``ParseError`` (RN001), never as exceptions. This module (like every
``python_*`` module but ``python.py``) imports libcst, so only ``python.py`` imports it,
after its prefilter decided the file is worth parsing.
"""

from __future__ import annotations

import ast
import codecs
import re

import libcst as cst

from roslint_names.extract.substitution import Source
from roslint_names.model import ParseError, Span

# ---------------------------------------------------------------------------------------
# Text and tree

# PEP 263: a coding declaration in a comment on line 1 or 2 (line 2 only after a comment
# or blank line 1), the same pattern CPython's tokenizer uses.
_CODING = re.compile(rb"^[ \t\f]*#.*?coding[:=][ \t]*([-\w.]+)")
_BLANK_OR_COMMENT = re.compile(rb"^[ \t\f]*(?:[#\r\n]|$)")


def _declared_encoding(data: bytes) -> str | None:
    lines = data.split(b"\n", 2)[:2]
    for index, line in enumerate(lines):
        match = _CODING.match(line)
        if match:
            return match.group(1).decode("ascii", errors="replace")
        if index == 0 and not _BLANK_OR_COMMENT.match(line):
            return None
    return None


def decode(data: bytes) -> str | ParseError:
    """The text Python would read: BOM, else the PEP 263 declaration, else UTF-8."""
    declared = _declared_encoding(data)
    if data.startswith(codecs.BOM_UTF8):
        if declared is not None and codecs.lookup(declared).name != "utf-8":
            return _error(f"UTF-8 BOM contradicts the coding declaration '{declared}'", 1, 1)
        encoding, data = "utf-8", data[len(codecs.BOM_UTF8) :]
    else:
        encoding = declared or "utf-8"
    try:
        codecs.lookup(encoding)
    except LookupError:
        return _error(f"unknown source encoding '{encoding}'", 1, 1)
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as error:
        before = Source(data[: error.start].decode(encoding, errors="replace"))
        line, column = before.position(len(before.text))
        return _error(f"cannot decode Python source as {encoding}: {error.reason}", line, column)
    except Exception as error:  # a codec's own failure (e.g. an incomplete utf-7 shift)
        return _error(f"cannot decode Python source as {encoding}: {error}", 1, 1)


def parse(text: str) -> cst.Module | ParseError:
    """The libcst tree, or where the file stops being Python 3.

    libcst's native parser reports unreliable positions, so a failure asks CPython's own
    parser (cheap, and only on this path) where and why; Python 2 files get its
    "Missing parentheses in call to 'print'".
    """
    if _may_be_too_deep(text):
        # libcst's parser overflows its stack (a segfault, not an exception) on nesting
        # far past what CPython accepts; CPython's parser refuses such files cleanly.
        try:
            ast.parse(text)
        except SyntaxError as error:
            return _error(f"not valid Python 3: {error.msg}", error.lineno or 1, error.offset or 1)
        except (RecursionError, MemoryError, ValueError):
            return _error("not valid Python 3: nested too deeply", 1, 1)
    try:
        return cst.parse_module(text)
    except cst.ParserSyntaxError as error:
        return _syntax_error(text, error.raw_line, str(error.message))
    except RecursionError:
        return _error("cannot parse Python: nested too deeply", 1, 1)


_BRACKETS = re.compile(r"[^()\[\]{}]+")
_OPENING = frozenset("([{")
# CPython refuses more than 200 nested brackets, and about 3000 nested unary operators or
# lambdas; libcst crashes some way past both. Runs far below those limits are common.
_MAX_BRACKETS = 200
_LONG_PREFIX_RUN = re.compile(r"(?:(?:[-+~]|\bnot\b|\blambda\b[^:\n]*:)\s*){1000}")


def _may_be_too_deep(text: str) -> bool:
    """Cheap over-approximation (brackets in strings count too) of "too deep to parse"."""
    depth = 0
    for char in _BRACKETS.sub("", text):
        depth = depth + 1 if char in _OPENING else max(depth - 1, 0)
        if depth > _MAX_BRACKETS:
            return True
    return _LONG_PREFIX_RUN.search(text) is not None


def _syntax_error(text: str, line: int, message: str) -> ParseError:
    try:
        ast.parse(text)
    except SyntaxError as error:
        reason = error.msg or message
        return _error(f"not valid Python 3: {reason}", error.lineno or line, error.offset or 1)
    except (ValueError, RecursionError, MemoryError):
        pass
    reason = message.split(": ", 1)[-1] if ": " in message else message
    return _error(f"not valid Python 3: {reason}", max(line, 1), 1)


def _error(message: str, line: int, column: int) -> ParseError:
    return ParseError(message, Span(line, column, line, column + 1))
