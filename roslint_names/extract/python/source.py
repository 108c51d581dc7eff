"""Python source text and tree: PEP 263 / BOM decoding and libcst parsing.

Failures come back as ``ParseError`` (RN001), never as exceptions. This module (like every
``python_*`` module but ``python.py``) imports libcst, so only ``python.py`` imports it,
after its prefilter decided the file is worth parsing.
"""

from __future__ import annotations

import ast
import re
import warnings

import libcst as cst

from roslint_names.extract.launch.substitution import Source
from roslint_names.extract.python.shape import CHAIN_LIMIT, longest_chain
from roslint_names.extract.python.text import decode, source_error
from roslint_names.model import ParseError

__all__ = ["decode", "parse"]

# ---------------------------------------------------------------------------------------
# Text and tree


def parse(text: str) -> cst.Module | ParseError:
    """The libcst tree, or where the file stops being Python 3.

    libcst's native parser reports unreliable positions, so a failure asks CPython's own
    parser (cheap, and only on this path) where and why; Python 2 files get its
    "Missing parentheses in call to 'print'".
    """
    null = text.find("\0")
    if null >= 0:  # libcst parses it (a string holding it is then "dynamic"); CPython refuses
        line, column = Source(text).position(null)
        return source_error(
            "not valid Python 3: source code cannot contain null bytes", line, column
        )
    chain = longest_chain(text)
    if chain is not None:  # minutes in libcst's parser, or a crash, for nothing (``shape``)
        line, column = Source(text).position(chain.offset)
        return source_error(
            f"gave up before parsing: {chain.describe()}; from {CHAIN_LIMIT:,} on, "
            "libcst takes minutes or crashes, and the tree is too deep to analyse",
            line,
            column,
        )
    if _may_be_too_deep(text):
        # libcst's parser overflows its stack (a segfault, not an exception) on nesting
        # far past what CPython accepts; CPython's parser refuses such files cleanly.
        try:
            _cpython_parse(text)
        except SyntaxError as error:
            return source_error(
                f"not valid Python 3: {error.msg}", error.lineno or 1, error.offset or 1
            )
        except (RecursionError, MemoryError, ValueError):
            return source_error("not valid Python 3: nested too deeply", 1, 1)
    try:
        return cst.parse_module(text)
    except cst.ParserSyntaxError as error:
        return _syntax_error(text, error.raw_line, str(error.message))
    except cst.CSTLogicError as error:  # a node libcst builds, then rejects: '"a" t"b"'
        return _syntax_error(text, 1, f"libcst cannot read it ({error})")
    except RecursionError:
        return source_error("cannot parse Python: nested too deeply", 1, 1)


_BRACKETS = re.compile(r"[^()\[\]{}]+")
_OPENING = frozenset("([{")
# CPython refuses more than 200 nested brackets, and about 3000 nested unary operators or
# lambdas; libcst crashes some way past both. Runs far below those limits are common.
_MAX_BRACKETS = 200
_PREFIX_RUN_LENGTH = 1000
_LONG_PREFIX_RUN = re.compile(
    rf"(?:(?:[-+~]|\bnot\b|\blambda\b[^:\n]*:)\s*){{{_PREFIX_RUN_LENGTH}}}"
)


def _may_be_too_deep(text: str) -> bool:
    """Cheap over-approximation (brackets in strings count too) of "too deep to parse"."""
    depth = 0
    for char in _BRACKETS.sub("", text):
        depth = depth + 1 if char in _OPENING else max(depth - 1, 0)
        if depth > _MAX_BRACKETS:
            return True
    # The run's regex tries every position (0.24 s over a large workspace); it needs a
    # thousand prefix operators, which counting the characters rules out in microseconds.
    operators = sum(text.count(char) for char in "-+~") + text.count("not") + text.count("lambda")
    return operators >= _PREFIX_RUN_LENGTH and _LONG_PREFIX_RUN.search(text) is not None


def _cpython_parse(text: str) -> None:
    """``ast.parse``, without the warnings CPython's tokenizer prints on its way ("invalid
    decimal literal"): they are no finding of ours, and a linter must not print them."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ast.parse(text)


def _syntax_error(text: str, line: int, message: str) -> ParseError:
    try:
        _cpython_parse(text)
    except SyntaxError as error:
        reason = error.msg or message
        return source_error(
            f"not valid Python 3: {reason}", error.lineno or line, error.offset or 1
        )
    except (ValueError, RecursionError, MemoryError):
        pass
    reason = message.split(": ", 1)[-1] if ": " in message else message
    return source_error(f"not valid Python 3: {reason}", max(line, 1), 1)
