"""Refuse a configured regular expression that could backtrack without bound.

Python's engine backtracks: ``(a+)+$`` tries every way of sharing a run of ``a`` among
the repetitions of the group before it gives up, 2**n ways for n characters (minutes for
a 35-character node name). That happens where a repeated part can itself match in more
than one way (a quantifier or an alternation inside it) and nothing tells where one
repetition ends and the next begins. A repeated part that starts or ends with a
character none of its varying parts can match has one way only: the ``_`` of
``(_[a-z0-9]+)*``, the shape every ``[naming]`` template takes, and the ``/`` of
``(/[a-z_]+)+``. So does an alternation whose branches start with different characters
(``(foo|bar)+``). Everything else that repeats a varying part is refused
(``check_backtracking``), with ``(a+)+``, ``(a*)*``, ``(a|aa)+`` and ``(\\w+_?)+``.

The pattern is judged on the parser's tree (``re._parser``, ``sre_parse`` before Python
3.11), not its text. Character sets are compared on a probe alphabet (Latin, the
pattern's own characters and range ends) and case-folded when the pattern ignores case:
an overlap the probe finds is a real one, so a refusal is never for a wrong reason of
that kind. Possessive repetitions and atomic groups (``a++``, ``(?>...)``) never give
back what they matched: they repeat, and are repeated, one way.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Callable, Sequence
from typing import Any

if sys.version_info >= (3, 11):
    from re import _constants as constants
    from re import _parser as parser
else:  # pragma: no cover - exercised on Python 3.10 only
    import sre_constants as constants
    import sre_parse as parser

_Item = tuple[Any, Any]  # (opcode, argument) as the parser gives them
_SINGLE = frozenset({constants.LITERAL, constants.NOT_LITERAL, constants.ANY, constants.IN})
_BACKTRACKING_REPEATS = frozenset({constants.MAX_REPEAT, constants.MIN_REPEAT})
# Possessive repetitions and atomic groups (Python 3.11) never give back what they took.
_ONE_WAY = frozenset(
    op
    for name in ("POSSESSIVE_REPEAT", "ATOMIC_GROUP")
    if (op := getattr(constants, name, None)) is not None
)
_ZERO_WIDTH = frozenset({constants.AT, constants.ASSERT, constants.ASSERT_NOT})
# Every character of the Latin blocks; the pattern's own characters are added to these.
_PROBE = frozenset(chr(code) for code in range(0x250))
_CATEGORIES: dict[Any, Callable[[str], bool]] = {
    constants.CATEGORY_DIGIT: str.isdecimal,
    constants.CATEGORY_SPACE: str.isspace,
    constants.CATEGORY_WORD: lambda character: character.isalnum() or character == "_",
    constants.CATEGORY_LINEBREAK: lambda character: character == "\n",
}
_NOT_CATEGORIES: dict[Any, Any] = {
    constants.CATEGORY_NOT_DIGIT: constants.CATEGORY_DIGIT,
    constants.CATEGORY_NOT_SPACE: constants.CATEGORY_SPACE,
    constants.CATEGORY_NOT_WORD: constants.CATEGORY_WORD,
    constants.CATEGORY_NOT_LINEBREAK: constants.CATEGORY_LINEBREAK,
}


class UnboundedBacktrackingError(ValueError):
    """A pattern that could take exponential time on a text it does not match."""


def check_backtracking(pattern: str) -> None:
    """Raise ``UnboundedBacktrackingError`` if a repetition in ``pattern`` (a valid regular
    expression) repeats a part that can match the same text in more than one way."""
    tree = parser.parse(pattern)
    items: list[_Item] = list(tree.data)
    ignore_case = bool(tree.state.flags & re.IGNORECASE) or _sets_ignore_case(items)
    judge = _Judge(ignore_case, _PROBE | frozenset(_characters(items)))
    if not judge.bounded(items):
        raise UnboundedBacktrackingError(
            f"{pattern!r} repeats a part that can match the same text in more than one "
            "way (a quantifier or alternation inside a repeated group, as in '(a+)+'): "
            "a name it does not match could take minutes to reject. Start or end the "
            "repeated part with a character its inner quantifiers cannot match, as the "
            "'_' of '(_[a-z0-9]+)*' does"
        )


class _Judge:
    def __init__(self, ignore_case: bool, probe: frozenset[str]) -> None:
        self._ignore_case = ignore_case
        self._probe = probe

    def bounded(self, items: Sequence[_Item]) -> bool:
        """Whether every backtracking repetition in ``items``, at any depth, repeats a
        part that matches one way only."""
        for op, argument in items:
            if op in _BACKTRACKING_REPEATS:
                _, high, body = argument
                if high > 1 and not self._one_way(list(body)):
                    return False
            if not all(self.bounded(list(part)) for part in _parts(op, argument)):
                return False
        return True

    def _one_way(self, body: list[_Item]) -> bool:
        """Whether repetitions of ``body`` can share a text in one way only."""
        while len(body) == 1 and body[0][0] is constants.SUBPATTERN:
            body = list(body[0][1][3])
        if len(body) == 1 and body[0][0] is constants.BRANCH:
            return self._branches_one_way([list(branch) for branch in body[0][1][1]])
        varying: list[_Item] = []
        if not _collect_varying(body, False, varying):
            return True  # a fixed length: (ab)+, [a-z]+
        if not all(self._choice_one_way(branches) for branches in _alternations(body)):
            return False
        for boundary in (_edge(body), _edge(body, from_end=True)):
            if boundary is not None and self._disjoint([boundary], varying):
                return True
        return False

    def _branches_one_way(self, branches: list[list[_Item]]) -> bool:
        """An alternation repeated: one way when no two branches can start the same
        text and no branch's varying part can match a character a branch starts with."""
        if not self._apart([_prefix(branch) for branch in branches]):
            return False
        firsts = [_prefix(branch)[0] for branch in branches]
        varying: list[_Item] = []
        for branch in branches:
            _collect_varying(branch, False, varying)
            if not all(self._choice_one_way(inner) for inner in _alternations(branch)):
                return False
        return self._disjoint(firsts, varying)

    def _choice_one_way(self, branches: list[list[_Item]]) -> bool:
        """An alternation inside a repeated part: one way when at most one branch is
        empty and no two of the others can start the same text. Two branches that can
        match the same text (``a|a``, ``|``) double the ways with every repetition."""
        empty = [branch for branch in branches if all(op in _ZERO_WIDTH for op, _ in branch)]
        others = [branch for branch in branches if branch not in empty]
        return len(empty) <= 1 and self._apart([_prefix(branch) for branch in others])

    def _apart(self, prefixes: list[list[_Item]]) -> bool:
        """Whether no text can start with two of ``prefixes``: each pair differs in a
        character of their common length (``bar``, ``baz``)."""
        return all(
            any(
                self._disjoint([mine], [theirs])
                for mine, theirs in zip(prefix, other, strict=False)
            )
            for index, prefix in enumerate(prefixes)
            for other in prefixes[index + 1 :]
        ) and all(prefixes)

    def _disjoint(self, these: Sequence[_Item], those: Sequence[_Item]) -> bool:
        """No character of the probe is matched by one of ``these`` and one of ``those``."""
        if not these or not those:
            return True
        return not any(
            self._matches(these, character) and self._matches(those, character)
            for character in self._probe
        )

    def _matches(self, items: Sequence[_Item], character: str) -> bool:
        variants = {character, *_cases(character)} if self._ignore_case else {character}
        return any(_single_matches(item, variant) for item in items for variant in variants)


def _parts(op: Any, argument: Any) -> list[Any]:
    """The sub-patterns an item holds."""
    if op is constants.SUBPATTERN:
        return [argument[3]]
    if op in _BACKTRACKING_REPEATS or op is getattr(constants, "POSSESSIVE_REPEAT", None):
        return [argument[2]]
    if op is constants.BRANCH:
        return list(argument[1])
    if op in (constants.ASSERT, constants.ASSERT_NOT):
        return [argument[1]]
    if op is constants.GROUPREF_EXISTS:
        return [part for part in argument[1:] if part is not None]
    if op is getattr(constants, "ATOMIC_GROUP", None):
        return [argument]
    return []


def _alternations(items: Sequence[_Item]) -> list[list[list[_Item]]]:
    """The branches of every alternation in ``items``, at any depth (not inside the
    possessive or atomic parts, which match one way)."""
    found: list[list[list[_Item]]] = []
    for op, argument in items:
        if op in _ONE_WAY:
            continue
        if op is constants.BRANCH:
            found.append([list(branch) for branch in argument[1]])
        for part in _parts(op, argument):
            found.extend(_alternations(list(part)))
    return found


def _collect_varying(items: Sequence[_Item], inside: bool, found: list[_Item]) -> bool:
    """Append to ``found`` the single-character items of ``items`` that are inside a
    part matching a varying text (a quantifier with a range, an alternation); whether
    there is such a part."""
    varies = False
    for op, argument in items:
        if op in _SINGLE:
            if inside:
                found.append((op, argument))
        elif op is constants.GROUPREF:
            if inside:
                found.append((constants.ANY, None))  # the group's text: any character
        elif op in _ZERO_WIDTH:
            continue
        elif op is constants.BRANCH or op is constants.GROUPREF_EXISTS:
            varies = True
            for part in _parts(op, argument):
                _collect_varying(part, True, found)
        elif op in _ONE_WAY:
            continue  # possessive, atomic: what they match they keep, one way
        elif op in _BACKTRACKING_REPEATS:
            low, high, body = argument
            ranged = low != high
            varies = _collect_varying(body, inside or ranged, found) or ranged or varies
        else:
            for part in _parts(op, argument):
                varies = _collect_varying(part, inside, found) or varies
    return varies


def _edge(items: Sequence[_Item], from_end: bool = False) -> _Item | None:
    """The single-character item every match of ``items`` starts with (ends with, with
    ``from_end``), or None when there is none."""
    for op, argument in reversed(items) if from_end else items:
        if op in _SINGLE:
            return (op, argument)
        if op in _ZERO_WIDTH:
            continue
        if op is constants.SUBPATTERN:
            return _edge(list(argument[3]), from_end)
        if op in _BACKTRACKING_REPEATS and argument[0] >= 1:
            return _edge(list(argument[2]), from_end)
        return None
    return None


def _prefix(items: Sequence[_Item]) -> list[_Item]:
    """The single-character items every match of ``items`` starts with, in order; at
    least the first (``_edge``), if there is one."""
    run: list[_Item] = []
    for op, argument in items:
        if op in _SINGLE:
            run.append((op, argument))
        elif op not in _ZERO_WIDTH:
            break
    if run:
        return run
    first = _edge(items)
    return [] if first is None else [first]


def _single_matches(item: _Item, character: str) -> bool:
    op, argument = item
    if op is constants.LITERAL or op is constants.NOT_LITERAL:
        return _member(item, character)  # the same test as inside a set
    if op is constants.IN:
        negated = bool(argument) and argument[0][0] is constants.NEGATE
        hit = any(_member(member, character) for member in argument[negated:])
        return hit != negated
    return True  # ANY, and anything not foreseen: as if it matched every character


def _member(member: _Item, character: str) -> bool:
    op, argument = member
    if op is constants.LITERAL:
        return chr(argument) == character
    if op is constants.NOT_LITERAL:
        return chr(argument) != character
    if op is constants.RANGE:
        return bool(argument[0] <= ord(character) <= argument[1])
    if op is constants.CATEGORY:
        if argument in _NOT_CATEGORIES:
            return not _CATEGORIES[_NOT_CATEGORIES[argument]](character)
        test = _CATEGORIES.get(argument)
        return True if test is None else bool(test(character))
    return True


def _characters(items: Sequence[_Item]) -> set[str]:
    """The characters ``items`` name (literals, range ends), with their case variants:
    the probe must hold every character two sets could share outside the Latin blocks."""
    found: set[str] = set()
    for op, argument in items:
        if op in (constants.LITERAL, constants.NOT_LITERAL):
            found.add(chr(argument))
        elif op is constants.IN:
            for member_op, member in argument:
                if member_op in (constants.LITERAL, constants.NOT_LITERAL):
                    found.add(chr(member))
                elif member_op is constants.RANGE:
                    found.update((chr(member[0]), chr(member[1])))
        for part in _parts(op, argument):
            found |= _characters(list(part))
    return found | {variant for character in found for variant in _cases(character)}


def _cases(character: str) -> set[str]:
    return {text for text in (character.lower(), character.upper()) if len(text) == 1}


def _sets_ignore_case(items: Sequence[_Item]) -> bool:
    """Whether a group of ``items`` turns case-insensitive matching on: ``(?i:...)``."""
    for op, argument in items:
        if op is constants.SUBPATTERN and argument[1] & re.IGNORECASE:
            return True
        if any(_sets_ignore_case(list(part)) for part in _parts(op, argument)):
            return True
    return False
