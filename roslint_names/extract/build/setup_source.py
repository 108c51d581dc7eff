"""setup.py trees with the standard library's ``ast``.

Failures come back as ``ParseError`` with the Python extractor's messages; that extractor
parses with libcst, which a build file must not pay for.
"""

from __future__ import annotations

import ast
import warnings

from roslint_names.extract.python.text import decode, source_error
from roslint_names.model import ParseError

__all__ = ["decode", "parse"]


def parse(text: str) -> ast.Module | ParseError:
    try:
        # The compiler warns about things like "\\d" in a string; that is no finding
        # of ours, and a linter must not print it.
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return ast.parse(text)
    except SyntaxError as error:
        return source_error(
            f"not valid Python 3: {error.msg}", error.lineno or 1, error.offset or 1
        )
    except ValueError as error:  # null bytes, before Python 3.12
        return source_error(f"not valid Python 3: {error}", 1, 1)
    except (RecursionError, MemoryError):
        return source_error("not valid Python 3: nested too deeply", 1, 1)
