"""String literals of code that are shaped like ROS names.

Not facts about what the code does with them: they are evidence that a name may be used
through an API the linter does not know (``InterProcessPollingSubscriber{this,
"~/input/accel"}``, ``rospy.wait_for_message("input", ...)`` through a helper), which keeps
RN404 from calling a remap of such a name unused. Found by a regular expression over the
text, so they cost no parse; a name-shaped string in a comment is harmless evidence too.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable, Iterator

from roslint_names.model import NameUse

# A quoted relative, private (``~``, ``~/``) or absolute name of at most nine tokens, its
# quotes either `"` or `'`: searched for with every `'` made a `"` first (no quote can be
# part of a name, so the matches are the same), as re finds a literal first character many
# times faster than one of a set.
_NAME = r'"((?:~/?|/)?[A-Za-z_][A-Za-z0-9_]{0,63}(?:/[A-Za-z0-9_]{1,64}){0,8}/?)"'
_QUOTED = re.compile(_NAME)
_QUOTED_BYTES = re.compile(_NAME.encode("ascii"))


def name_literals(text: str | bytes) -> tuple[str, ...]:
    """Every distinct name-shaped string literal of ``text`` (UTF-8 if bytes), sorted."""
    if isinstance(text, bytes):
        found = _QUOTED_BYTES.findall(text.replace(b"'", b'"'))
        return tuple(sorted({name.decode("ascii") for name in found}))
    return tuple(sorted(set(_QUOTED.findall(text.replace("'", '"')))))


def name_literal_spans(text: str) -> Iterator[tuple[int, int]]:
    """Where each name-shaped string literal's name is in ``text``: (start, end) offsets,
    quotes excluded; every occurrence, in order."""
    for found in _QUOTED.finditer(text.replace("'", '"')):
        yield found.span(1)


# A parameter-shaped word: tokens joined by '.' or '/' (``FollowPath.max_vel_x``), in
# ROS 1 perhaps private or absolute (``~hzerror``, ``/use_sim_time``).
_WORD = re.compile(rb"(?:~/?|/)?[A-Za-z_][A-Za-z0-9_]{0,63}(?:[./][A-Za-z0-9_]{1,64}){0,8}")
_LONGEST = 200  # longer strings are messages, not names: not even matched
# String literals and comments, in order, so that a quote in a comment (``// "rate" is
# ...``) is no string: the group holds a string's text, and is empty for the rest. C++ (a
# char literal is no string either) and Python.
_CPP_TOKENS = re.compile(
    rb'"((?:[^"\\\n]|\\.)*)"|\'(?:[^\'\\\n]|\\.)*\'|//[^\n]*|/\*.*?\*/', re.DOTALL
)
_PYTHON_TOKENS = re.compile(rb'"((?:[^"\\\n]|\\.)*)"|\'((?:[^\'\\\n]|\\.)*)\'|#[^\n]*')


def unexplained_literals(
    data: bytes, names: Iterable[NameUse], *, python: bool = False
) -> tuple[str, ...]:
    """The parameter-shaped string literals of ``data`` (UTF-8 code) that occur more often
    than the static names the extractor read: strings the code hands to something the
    linter does not know (a project's ``declare(node, "rate")``, a list of names a loop
    declares), sorted. RN407 doubts a parameter such a string may declare."""
    if python:
        strings = [double or single for double, single in _PYTHON_TOKENS.findall(data)]
    else:
        strings = _CPP_TOKENS.findall(data)
    counts = Counter(text for text in strings if 0 < len(text) < _LONGEST and _WORD.fullmatch(text))
    for use in names:
        if not use.dynamic:
            word = use.value.encode("utf-8", "surrogatepass")
            if word in counts:
                counts[word] -= 1
    return tuple(sorted(word.decode("ascii") for word, count in counts.items() if count > 0))
