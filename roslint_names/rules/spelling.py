"""Whether one parameter name looks like a slip of another: the 'did you mean' of the
parameter rules (RN406, RN407)."""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable

_SHORTEST = 4  # one edit turns any short name into another: 'x' is no slip of 'y'


def folded(name: str) -> str:
    """The name with case and underscores ignored: ``maxVelX``, ``max_vel_x`` and
    ``max_vel_x_`` (a trailing underscore copied from a member) fold alike."""
    return name.lower().replace("_", "")


def one_edit(one: str, other: str) -> bool:
    """One character inserted, removed or replaced."""
    if abs(len(one) - len(other)) > 1 or one == other:
        return False
    if len(one) > len(other):
        one, other = other, one
    start = 0
    while start < len(one) and one[start] == other[start]:
        start += 1
    if len(one) == len(other):
        return one[start + 1 :] == other[start + 1 :]
    return one[start:] == other[start + 1 :]


def one_word_apart(one: str, other: str) -> bool:
    """The same words but one (``max_speed_x`` and ``max_vel_x``), in names of three
    words or more: fewer leave too little in common to call it a slip."""
    words, others = _words(one), _words(other)
    if len(words) != len(others) or len(words) < 3:
        return False
    return sum(a != b for a, b in zip(words, others, strict=True)) == 1


def one_word_more(one: str, other: str) -> bool:
    """The same words with one more in either (``simulation_step`` and
    ``simulation_time_step``), the shorter of two words or more."""
    words, others = _words(one), _words(other)
    if len(words) > len(others):
        words, others = others, words
    if len(others) != len(words) + 1 or len(words) < 2:
        return False
    return any(others[:index] + others[index + 1 :] == words for index in range(len(others)))


def nearest(name: str, candidates: Iterable[str]) -> str | None:
    """The candidate ``name`` is a slip of: equal but for case and underscores, else one
    edit or one swap of neighbours away (names of four characters or more), else the same
    under another prefix (``resample.delta_yaw_threshold``), else one word away, else one
    word more or less (``simulation_time_step``); None when
    there is none, or more than one of the closest kind (a guess between two helps no
    one)."""
    pool = sorted({candidate for candidate in candidates if candidate and candidate != name})
    tests: tuple[Callable[[str, str], bool], ...] = (
        lambda one, other: folded(one) == folded(other),
        lambda one, other: (
            min(len(one), len(other)) >= _SHORTEST
            and (one_edit(one, other) or _swapped(one, other))
        ),
        lambda one, other: _leaf(one) == _leaf(other),
        one_word_apart,
        one_word_more,
    )
    for test in tests:
        found = [candidate for candidate in pool if test(candidate, name)]
        if found:
            return found[0] if len(found) == 1 else None
    return None


def _swapped(one: str, other: str) -> bool:
    """Two neighbouring characters swapped (``jerk_wieght``)."""
    if len(one) != len(other) or one == other:
        return False
    differ = [index for index, (a, b) in enumerate(zip(one, other, strict=True)) if a != b]
    first = differ[0]
    if differ != [first, first + 1]:
        return False
    return one[first] == other[first + 1] and one[first + 1] == other[first]


def _leaf(name: str) -> str:
    """The last part of a nested name: ``FollowPath.max_vel_x`` -> ``max_vel_x``."""
    return re.split(r"[./]", name)[-1]


def _words(name: str) -> list[str]:
    return [word for word in re.split(r"[_./]+", name) if word]
