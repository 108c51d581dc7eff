"""The one shape of Python source known to make libcst's parser slow: a long chain of
binary operators, found from the text without parsing.

libcst nests ``a + b + c`` as one ``BinaryOperation`` inside the next, and its native
parser takes time that grows faster than the square of the chain (libcst 1.9, on
``x = "a" + "a" + ...``: 1,000 terms 0.2 s, 2,000 0.5 s, 4,000 2.8 s; ``*`` 7.2 s at
4,000), and at 8,000 terms it overflows its stack: a segfault, not an exception. The
tree is of no use anyway: walking it needs a Python frame per level, so past about 990
levels the extraction stops with "nested too deeply". A chain of ``CHAIN_LIMIT``
operators is therefore refused before parsing (``parse``), at no loss.

Imports nothing heavy: the engine also asks it to explain a file that ran out of time.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

# Past Python's default recursion limit (1,000 frames), the walk cannot follow the tree.
CHAIN_LIMIT = 1000

# Tokens, roughly as CPython's tokenizer sees them; strings and comments first, so that
# operators inside them do not count. Strings are matched with unrolled loops (no
# backtracking), and an unterminated one falls through to ``other``.
_TOKEN = re.compile(
    r"""
    (?P<string>[rRbBuUfF]{0,2}(?:
        '''[^'\\]*(?:(?:\\.|'(?!''))[^'\\]*)*'''
      | \"\"\"[^"\\]*(?:(?:\\.|"(?!""))[^"\\]*)*\"\"\"
      | '[^'\\\n]*(?:\\.[^'\\\n]*)*'
      | "[^"\\\n]*(?:\\.[^"\\\n]*)*"
    ))
    | (?P<skip>[ \t\f\r]+|\\\r?\n|\#[^\n]*)
    | (?P<number>\.?\d(?:[eE][-+]|[\w.])*)
    | (?P<name>\w+)
    | (?P<operator>(?:\*\*|//|<<|>>|[-+*/%@&|^])(?!=))
    | (?P<open>[(\[{])
    | (?P<close>[)\]}])
    | (?P<newline>\n)
    | (?P<dot>\.)
    | (?P<other>.)
    """,
    re.VERBOSE | re.DOTALL,
)
_OPERANDS = frozenset({"True", "False", "None"})
_OPERATOR_CHARACTERS = "+-*/%@&|^"


@dataclass(frozen=True)
class Chain:
    """The longest run of binary operators in one expression at one bracket depth."""

    operators: int
    spelled: tuple[str, ...]  # the distinct operators, in order of first use
    offset: int  # where its first operand starts in the text

    def describe(self) -> str:
        spelled = ", ".join(f"'{operator}'" for operator in self.spelled)
        return f"one expression chains {self.operators} {spelled} operators"

    def line(self, text: str) -> int:
        return text.count("\n", 0, self.offset) + 1


def longest_chain(text: str, at_least: int = CHAIN_LIMIT) -> Chain | None:
    """The longest chain of binary operators if it has ``at_least`` of them, else None.

    Counting the operator characters rules out nearly every file in microseconds; only a
    file with that many is scanned token by token (20 to 40 ms per 100 KB)."""
    if sum(text.count(character) for character in _OPERATOR_CHARACTERS) < at_least:
        return None
    found = _scan(text)
    return found if found is not None and found.operators >= at_least else None


def _scan(text: str) -> Chain | None:
    # One open chain per bracket depth: (operators, their spellings, where it starts).
    levels: list[tuple[int, list[str], int]] = [(0, [], 0)]
    best: Chain | None = None
    operand_before = False  # a binary operator follows an operand; a unary one does not
    operand_start = 0
    for match in _TOKEN.finditer(text):
        kind = match.lastgroup
        if kind == "skip":
            continue
        if kind in ("string", "number") or (
            kind == "name" and (match.group() in _OPERANDS or not _is_keyword(match.group()))
        ):
            if not operand_before:
                operand_start = match.start()
            operand_before = True
            continue
        if kind == "operator" and operand_before:
            count, spelled, start = levels[-1]
            if count == 0:
                start = operand_start
            operator = match.group()
            if operator not in spelled:
                spelled = [*spelled, operator]
            levels[-1] = (count + 1, spelled, start)
            if best is None or count + 1 > best.operators:
                best = Chain(count + 1, tuple(spelled), start)
            operand_before = False
        elif kind == "open":
            if not operand_before:
                operand_start = match.start()
            levels.append((0, [], 0))
            operand_before = False
        elif kind == "close":
            if len(levels) > 1:
                levels.pop()
            operand_before = True  # ``(...)`` and ``f(...)`` are operands
        elif kind == "dot":
            operand_before = False  # ``a.b``: the name after it continues the operand
        elif kind != "operator" and (kind != "newline" or len(levels) == 1):
            # A separator (``,`` ``=`` ``:`` a keyword, the end of a statement) ends the
            # chain at this depth; a unary operator and a newline inside brackets do not.
            levels[-1] = (0, [], 0)
            operand_before = False
    return best


def _is_keyword(word: str) -> bool:
    return word in _KEYWORDS


_KEYWORDS = frozenset(
    {
        "and", "as", "assert", "async", "await", "break", "class", "continue", "def", "del",
        "elif", "else", "except", "finally", "for", "from", "global", "if", "import", "in",
        "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try", "while",
        "with", "yield",
    }
)  # fmt: skip
