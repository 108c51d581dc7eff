"""THE ROS graph-resource name grammar, for ROS 1 and ROS 2, and the helpers built on it.

Everything the project knows about which names the ROS runtime accepts lives here (see
``ROS_NAMES.md``, which was read from the ROS sources). The checks mirror, in this order of
authority:

- ROS 1: rosgraph ``names.py`` (``is_legal_name``, ``resolve_name``) and roscpp
  ``names.cpp`` (``validate``, ``resolve``). A name must satisfy both, because names travel
  between C++ and Python tools.
- ROS 2: rmw ``validate_node_name.c``, ``validate_namespace.c``,
  ``validate_full_topic_name.c`` and rcl ``validate_topic_name.c``, ``expand_topic_name.c``.

Every function is pure: no I/O, no global state.
"""

from __future__ import annotations

import re
import string
import unicodedata
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from functools import lru_cache

from .model import Generation, Kind

__all__ = [
    "ROS2_NAMESPACE_MAX_LENGTH",
    "ROS2_NAME_MAX_LENGTH",
    "ROS2_NODE_NAME_MAX_LENGTH",
    "ROS2_SUBSTITUTIONS",
    "NameResolutionError",
    "Problem",
    "check_name",
    "depth",
    "is_snake_case",
    "is_valid",
    "join_namespace",
    "resolve",
    "snake_case",
    "tokens",
]

ILLEGAL = "RN101"
TRAILING_SLASH = "RN102"
FRAME_LEADING_SLASH = "RN205"

# rmw: RMW_NODE_NAME_MAX_NAME_LENGTH and RMW_NAMESPACE_MAX_LENGTH.
ROS2_NODE_NAME_MAX_LENGTH = 255
ROS2_NAMESPACE_MAX_LENGTH = 245
# Limits on a fully expanded name. DDS names hold at most 255 characters and the middleware
# decorates ROS names: rmw's RMW_TOPIC_MAX_NAME_LENGTH is 255 - 8 ("reserved for
# prefixes"); a service becomes 'rq' + name + 'Request' (the longer of its request/reply
# pair), and an action's longest derived service 'rq' + name + '/_action/cancel_goal' +
# 'Request'.
ROS2_NAME_MAX_LENGTH: dict[Kind, int] = {
    Kind.TOPIC: 247,
    Kind.SERVICE: 255 - len("rq") - len("Request"),
    Kind.ACTION: 255 - len("rq") - len("/_action/cancel_goal") - len("Request"),
}
# rcl_expand_topic_name knows these; its default substitution map is empty, so any other
# '{name}' fails at run time.
ROS2_SUBSTITUTIONS = frozenset({"node", "ns", "namespace"})

_LETTERS = frozenset(string.ascii_letters)
_DIGITS = frozenset(string.digits)
_LOWER_OR_DIGIT = frozenset(string.ascii_lowercase + string.digits)
_WORD = _LETTERS | _DIGITS | {"_"}  # ASCII only: both rcutils and roscpp (C locale) say so
_GRAPH = _WORD | {"/"}
_EMPTY = "must not be empty"
_DOUBLE = "contains '//'"
# Node name used to judge ROS 2 names that expand '~' or '{node}' when no node is known. A
# one-character name is the shortest any node can have, so a length finding made with it
# holds for every node the name could belong to.
_PLACEHOLDER_NODE = "n"
# A '{substitution}' as rcl allows it; bounded character class, no nesting: linear matching.
_SUBSTITUTION = re.compile(r"\{[A-Za-z0-9_]+\}")
_SLASH_RUN = re.compile(r"/{2,}")
# Characters people type where '_' was meant; repairs map them to '_'.
_SEPARATOR_TYPOS = str.maketrans({"-": "_", ".": "_", " ": "_"})


@dataclass(frozen=True)
class Problem:
    """The first thing wrong with a name, as a rule reports it.

    ``reason`` is a sentence fragment that does not repeat the name or kind, so rules can
    write ``f"{kind} name '{name}' {reason}"``. ``index`` is the 0-based index of the
    offending character in the name as written, or None when no single character is at
    fault. ``fatal`` is True when the runtime of that generation rejects the name.
    ``suggestion``, when set, is itself a name without any problem.
    """

    code: str
    reason: str
    index: int | None
    fatal: bool
    suggestion: str | None = None


class NameResolutionError(ValueError):
    """A name (or the namespace or node it is resolved in) that cannot be resolved."""


class _UnknownSubstitutionError(Exception):
    """Raised while expanding a ROS 2 name that uses a substitution rcl does not know."""

    def __init__(self, text: str, index: int) -> None:
        super().__init__(text)
        self.text = text
        self.index = index


# --------------------------------------------------------------------------- public API


@lru_cache(maxsize=1 << 16)  # five rules ask about each name of a file; answers are frozen
def check_name(name: str, kind: Kind, generation: Generation) -> Problem | None:
    """Return None when ``name`` is fine for ``kind`` in ``generation``, else its first problem.

    "First" means: the character problem at the lowest index as written, then (ROS 2) what
    goes wrong once the name is expanded, then length. A trailing '/' is reported as RN102
    only when nothing else is wrong, and a frame id starting with '/' as RN205.
    """
    problem = _find_problem(name, kind, generation)
    if problem is None:
        return None
    return replace(problem, suggestion=_valid_suggestion(problem, name, kind, generation))


def is_valid(name: str, kind: Kind, generation: Generation) -> bool:
    """True when the runtime of ``generation`` accepts ``name`` (warnings allowed)."""
    problem = check_name(name, kind, generation)
    return problem is None or not problem.fatal


def tokens(name: str, kind: Kind) -> list[str]:
    """Split a name into its tokens (what style rules and depth limits look at).

    Graph names split on '/', ignoring a leading '/', '~' or '~/'; a '{substitution}' never
    splits. Parameters split on '.' as well (ROS 2) since ROS 1 parameters cannot contain
    one. A frame id is one token, after tf2's stripping of one leading '/'.
    """
    return list(_tokens(name, kind))


@lru_cache(maxsize=4096)
def _tokens(name: str, kind: Kind) -> tuple[str, ...]:
    """``tokens``, kept: the same names come back in every file of a package."""
    if kind is Kind.FRAME:
        frame = name[1:] if name.startswith("/") else name
        return (frame,) if frame else ()
    body = name[1:] if name.startswith("~") else name
    separators = "/." if kind is Kind.PARAMETER else "/"
    return tuple(token for token in _split_outside_braces(body, separators) if token)


def depth(name: str, kind: Kind) -> int:
    """Number of tokens of ``name``."""
    return len(_tokens(name, kind))


def is_snake_case(token: str) -> bool:
    """True for lower snake_case: ``_?[a-z0-9]+(_[a-z0-9]+)*``, '{substitution}' allowed.

    One leading '_' is fine (ROS 2 hidden names); '__', a trailing '_' and capitals are not.
    A substitution stands for a snake_case word, whatever it will expand to.
    """
    body = _SUBSTITUTION.sub("x", token)
    if body.startswith("_"):
        body = body[1:]
    return all(part and set(part) <= _LOWER_OR_DIGIT for part in body.split("_"))


def snake_case(text: str) -> str:
    """Best lower snake_case spelling of ``text``: 'HTTPServer' -> 'http_server'.

    Words are split at non-alphanumerics and at camel-case humps; accents are dropped
    ('é' -> 'e'). One leading '_' is kept. Returns '' when ``text`` has no word at all.
    """
    words = [word.lower() for run in _alnum_runs(_fold_accents(text)) for word in _humps(run)]
    if not words:
        return ""
    return ("_" if text.startswith("_") else "") + "_".join(words)


def token_pattern(words: Iterable[str]) -> re.Pattern[str]:
    """Each of ``words`` where it is a whole token: not inside a longer identifier
    (``TestNode`` in ``/TestNode/x`` and ``TestNode.rate``, not in ``MyTestNode``)."""
    alternatives = "|".join(re.escape(word) for word in sorted(words, key=len, reverse=True))
    return re.compile(rf"(?<![A-Za-z0-9_])(?:{alternatives})(?![A-Za-z0-9_])")


def rename_tokens(name: str, renamed: Mapping[str, str]) -> str:
    """``name`` with each whole token that ``renamed`` names replaced."""
    if not renamed:
        return name
    return token_pattern(renamed).sub(lambda found: renamed[found.group()], name)


def resolve(
    name: str, generation: Generation, namespace: str = "/", node_name: str | None = None
) -> str:
    """Return the fully qualified name the runtime of ``generation`` makes of ``name``.

    ROS 1 (rosgraph/roscpp): '~x' -> '<ns>/<node>/x', relative -> '<ns>/x', '//' collapsed,
    one trailing '/' dropped, '' -> the namespace. ROS 2 (rcl_expand_topic_name): '~' ->
    '<ns>/<node>', '{node}' -> node name, '{ns}'/'{namespace}' -> namespace, relative ->
    '<ns>/' + name; this follows rcl exactly, so the '~a' quirk gives '<ns>/<node>a'.

    ``node_name`` is a base name (no namespace). ``namespace`` may be relative; '' is the
    root. Raises NameResolutionError when the name, namespace or node name is illegal, when
    a '~' (or '{node}') name has no node, or when the result is not a legal full name.
    """
    return _resolve(name, generation, namespace, node_name)


# The workspace graph resolves the same names for every launch of the same code: memoised
# (an illegal name raises each time; exceptions are not cached).
@lru_cache(maxsize=1 << 16)
def _resolve(name: str, generation: Generation, namespace: str, node_name: str | None) -> str:
    if generation is Generation.ROS1:
        return _resolve_ros1(name, namespace, node_name)
    return _resolve_ros2(name, namespace, node_name)


def join_namespace(outer: str, inner: str, generation: Generation) -> str:
    """Nest namespace ``inner`` in ``outer``, as ``<group ns>`` / ``<push-ros-namespace>`` do.

    An absolute ``inner`` replaces ``outer``; a relative one is appended; '' leaves
    ``outer``. The result starts with '/', has no '//' and no trailing '/' (except the root
    '/'). roslaunch (``ns_join`` + ``make_global_ns``) and launch_ros (``prefix_namespace`` +
    ``make_namespace_absolute``) nest the same way, so ``generation`` changes nothing today;
    it is taken so callers need not branch. Nothing is validated: check each part with
    ``check_name(..., Kind.NAMESPACE, ...)``.
    """
    del generation  # same nesting in both generations, see above
    if not inner:
        combined = outer
    elif inner.startswith("/"):
        combined = inner
    else:
        combined = f"{outer}/{inner}"
    return _canonical(combined)


# ------------------------------------------------------------------------- dispatching


def _find_problem(name: str, kind: Kind, generation: Generation) -> Problem | None:
    """The first problem, before any suggestion is validated."""
    if kind is Kind.FRAME:
        return _frame_problem(name, generation)
    if kind is Kind.NODE:
        return _node_problem(name, generation)
    if generation is Generation.ROS1:
        # ROS 1 parameters are graph names: same grammar as topics, '~private' included.
        return _ros1_graph_problem(name, kind)
    if kind is Kind.PARAMETER:
        # ROS 2 parameters are not graph names; rclcpp/rclpy only refuse the empty name.
        return _illegal(_EMPTY, None) if not name else None
    if kind is Kind.NAMESPACE:
        return _ros2_namespace_problem(name)
    return _ros2_graph_problem(name, kind)


def _illegal(reason: str, index: int | None, suggestion: str | None = None) -> Problem:
    return Problem(ILLEGAL, reason, index, fatal=True, suggestion=suggestion)


def _char_reason(char: str, index: int, prefix: str = "contains") -> str:
    # repr() quotes the character and escapes the unprintable ones ('\n', '\u200b').
    if not char.isascii():
        return f"{prefix} non-ASCII character {char!r} at index {index}"
    return f"{prefix} {char!r} at index {index}"


def _digit_reason(char: str, index: int) -> str:
    if index == 0:
        return f"starts with a digit ({char!r}) at index 0"
    return f"has a token that starts with a digit ({char!r}) at index {index}"


def _misplaced_tilde(index: int) -> Problem:
    return _illegal(
        f"contains '~' at index {index}; '~' is only allowed as the first character", index
    )


def _length_reason(length: int, limit: int, what: str, how: str = "") -> str:
    return f"is {length} characters long{how}; the limit for a ROS 2 {what} is {limit}"


# ------------------------------------------------------------------------------ frames


def _frame_problem(name: str, generation: Generation) -> Problem | None:
    # tf2 checks almost nothing; only the empty id and a leading '/' matter.
    if not name:
        return _illegal(_EMPTY, None)
    if not name.startswith("/"):
        return None
    if generation is Generation.ROS2:
        reason, fatal = "starts with '/', which tf2 in ROS 2 rejects", True
    else:
        reason, fatal = "starts with '/', which tf2 in ROS 1 strips with a warning", False
    return Problem(FRAME_LEADING_SLASH, reason, 0, fatal, name.lstrip("/") or None)


# ------------------------------------------------------------------------------- nodes


def _node_problem(name: str, generation: Generation) -> Problem | None:
    """rosgraph ``is_legal_base_name`` / roscpp ``init`` (ROS 1), rmw (ROS 2).

    Reported in index order (rmw looks at characters before the leading digit; both are
    fatal, so only the position reported differs).
    """
    if not name:
        return _illegal(_EMPTY, None)
    for index, char in enumerate(name):
        problem = _node_char_problem(char, index, generation)
        if problem is not None:
            return problem
    if generation is Generation.ROS2 and len(name) > ROS2_NODE_NAME_MAX_LENGTH:
        return _illegal(_length_reason(len(name), ROS2_NODE_NAME_MAX_LENGTH, "node name"), None)
    return None


def _node_char_problem(char: str, index: int, generation: Generation) -> Problem | None:
    if char == "/":
        reason = "node names cannot contain '/', put the prefix in the namespace"
        return _illegal(f"contains '/' at index {index}; {reason}", index)
    if char == "~":
        reason = "node names cannot contain '~', it marks private names"
        return _illegal(f"contains '~' at index {index}; {reason}", index)
    if char not in _WORD:
        return _illegal(_char_reason(char, index), index)
    if index == 0 and char in _DIGITS:
        return _illegal(_digit_reason(char, 0), 0)
    if index == 0 and char == "_" and generation is Generation.ROS1:
        # ROS 2 allows it (hidden nodes); rosgraph and roscpp want a letter first.
        return _illegal("starts with '_' (index 0), which ROS 1 rejects in node names", 0)
    return None


# ------------------------------------------------------------------------ ROS 1 names


def _ros1_graph_problem(name: str, kind: Kind) -> Problem | None:
    """What both rosgraph ``is_legal_name`` and roscpp ``validate`` accept.

    Together: ASCII only; first character a letter, '/' or '~'; then [A-Za-z0-9_/]; no '//'
    (rosgraph); '' is the namespace itself and legal. A trailing '/' is legal but stripped,
    except for a namespace, where roslaunch itself writes 'ns/'.
    """
    if not name:
        return None
    problem = _ros1_first_char_problem(name, kind)
    if problem is not None:
        return problem
    for index in range(1, len(name)):
        char = name[index]
        if char == "~":
            return _misplaced_tilde(index)
        if char not in _GRAPH:
            return _illegal(_char_reason(char, index), index)
        if char == "/" and name[index - 1] == "/":
            # The index is the first '/' of the pair: that is where '//' starts.
            return _illegal(f"contains '//' at index {index - 1}", index - 1)
    if len(name) > 1 and name.endswith("/") and kind is not Kind.NAMESPACE:
        reason = "ends with '/' (ROS 1 strips it)"
        return Problem(TRAILING_SLASH, reason, len(name) - 1, fatal=False, suggestion=name[:-1])
    return None


def _ros1_first_char_problem(name: str, kind: Kind) -> Problem | None:
    char = name[0]
    if char in _LETTERS or char in "/~":
        return None
    if char in _DIGITS:
        return _illegal(_digit_reason(char, 0), 0)
    if char == "_":
        return _illegal(_ros1_underscore_reason(name, kind), 0)
    return _illegal(_char_reason(char, 0), 0)


def _ros1_underscore_reason(name: str, kind: Kind) -> str:
    # ROS 2 hidden names ('_private') are a classic porting trap; name the legal spellings,
    # but only those that really are legal for this name.
    legal = [
        alternative
        for alternative in ("/" + name, name.lstrip("_"))
        if alternative and _is_ros1_legal(alternative, kind)
    ]
    reason = "starts with '_', which ROS 1 rejects"
    if not legal:
        return reason
    verb = "are" if len(legal) > 1 else "is"
    return f"{reason}; {' or '.join(repr(alternative) for alternative in legal)} {verb} legal"


def _is_ros1_legal(name: str, kind: Kind) -> bool:
    problem = _ros1_graph_problem(name, kind)
    return problem is None or not problem.fatal


# ------------------------------------------------------------------------ ROS 2 names


def _ros2_graph_problem(name: str, kind: Kind) -> Problem | None:
    """Topic, service and action names: rcl_validate_topic_name, then the expansion.

    The expansion (rcl_expand_topic_name + rmw_validate_full_topic_name) is judged in the
    root namespace with a one-character node name: the root is where '{ns}' misuse shows
    ('{ns}/foo' -> '//foo') and the shortest possible expansion, so a length finding holds
    in every namespace. A trailing '/' is judged last, on the name without it, so that it is
    RN102 only when it is the only problem.
    """
    if not name:
        return _illegal(_EMPTY, None)
    if name == "/":
        reason = f"is only '/', the root namespace, which ROS 2 rejects as a {kind.value} name"
        return Problem(TRAILING_SLASH, reason, 0, fatal=True)
    problem = _ros2_written_problem(name, strict_tilde=True)
    if problem is not None:
        return problem
    # No '//' got through, so the name without its trailing '/' does not end with one.
    body = name[:-1] if name.endswith("/") else name
    problem = _ros2_expansion_problem(body, kind)
    if problem is not None:
        return problem
    if body != name:
        reason = "ends with '/' (ROS 2 rejects it)"
        return Problem(TRAILING_SLASH, reason, len(name) - 1, fatal=True, suggestion=body)
    return None


def _ros2_written_problem(name: str, *, strict_tilde: bool) -> Problem | None:
    """rcl_validate_topic_name's checks on a non-empty name, reported in index order.

    Also reports a literal '//': rcl lets it through but no expansion can remove it, so the
    full-name check always fails on it. With ``strict_tilde`` false this accepts exactly
    what rcl accepts (apart from '//' and the trailing '/', which callers handle).
    """
    open_at: int | None = None
    for index, char in enumerate(name):
        if open_at is not None:
            problem = _substitution_char_problem(char, index, open_at)
            if char == "}":
                open_at = None
        else:
            problem = _ros2_char_problem(name, index, strict_tilde=strict_tilde)
            if char == "{":
                open_at = index
        if problem is not None:
            return problem
    if open_at is not None:
        return _illegal(f"has an unclosed '{{' at index {open_at}", open_at)
    return None


def _ros2_char_problem(name: str, index: int, *, strict_tilde: bool) -> Problem | None:
    """One character of a ROS 2 topic name outside any '{substitution}'."""
    char = name[index]
    if char == "}":
        return _illegal(f"has an unmatched '}}' at index {index}", index)
    if char == "~" and index > 0:
        return _misplaced_tilde(index)
    if char not in _GRAPH and char not in "{~":
        return _illegal(_char_reason(char, index), index)
    if char in _DIGITS and (index == 0 or name[index - 1] == "/"):
        return _illegal(_digit_reason(char, index), index)
    if index == 1 and name[0] == "~" and char != "/":
        return _tilde_problem(name, strict=strict_tilde)
    if char == "/" and index > 0 and name[index - 1] == "/":
        return _illegal(f"contains '//' at index {index - 1}", index - 1)
    return None


def _tilde_problem(name: str, *, strict: bool) -> Problem | None:
    """A leading '~' not followed by '/'.

    rcl skips the last character when it looks for this, so a two-character '~a' passes
    and expands to '<ns>/<node>a', a name nobody meant; we reject it when ``strict``.
    """
    if len(name) == 2 and name[1] in _WORD:
        if not strict:
            return None
        reason = (
            f"is accepted by rcl but expands to '<ns>/<node>{name[1]}', "
            f"not a private name; write '~/{name[1]}'"
        )
        return _illegal(reason, 1, suggestion="~/" + name[1])
    reason = (
        f"has '~' not followed by '/' ({name[1:2]!r} at index 1); "
        "private names are written '~/name'"
    )
    return _illegal(reason, 1, suggestion="~/" + name[1:])


def _substitution_char_problem(char: str, index: int, open_at: int) -> Problem | None:
    """One character inside '{...}' (rcl: alphanumerics and '_', not starting with a digit)."""
    if char == "}":
        return None
    if char == "{":
        return _illegal(f"opens a substitution inside another at index {index}", index)
    if char in _DIGITS and index == open_at + 1:
        return _illegal(
            f"has a substitution that starts with a digit ({char!r}) at index {index}", index
        )
    if char not in _WORD:
        return _illegal(_char_reason(char, index, "has a substitution that contains"), index)
    return None


def _ros2_expansion_problem(name: str, kind: Kind) -> Problem | None:
    """Expand ``name`` (valid as written, no trailing '/') at the root and check the result."""
    try:
        expansion, origins = _expand(name, "/", _PLACEHOLDER_NODE)
    except _UnknownSubstitutionError as error:
        reason = (
            f"uses unknown substitution '{error.text}' at index {error.index}; "
            "rcl only expands {node}, {ns} and {namespace}"
        )
        return _illegal(reason, error.index)
    defect = _full_name_defect(expansion)
    if defect is not None:
        what, at = defect
        shown = _expand(name, "/", "<node>")[0]  # readable form for the message only
        reason = f"expands to '{shown}' in the root namespace, which {what}"
        return _illegal(reason, _blame(name, origins[at : at + 2 if what == _DOUBLE else at + 1]))
    limit = ROS2_NAME_MAX_LENGTH[kind]
    if len(expansion) > limit:
        how = ""
        if expansion != name:
            relative = expansion == "/" + name
            how = " once made absolute" if relative else " once expanded in the root namespace"
        return _illegal(_length_reason(len(expansion), limit, kind.value, how), None)
    return None


def _ros2_namespace_problem(name: str) -> Problem | None:
    """rmw_validate_namespace after rcl_node_init's normalisation.

    '' and '/' are the root; a relative namespace gets '/' prepended first, so indices are
    shifted back to the name as written.
    """
    if name in ("", "/"):
        return None
    shift = 0 if name.startswith("/") else 1
    full = "/" * shift + name
    for at in range(1, len(full)):
        problem = _full_name_char_problem(full, at, shift)
        if problem is not None:
            return problem
    body = name[:-1] if name.endswith("/") else name
    if len(body) + shift > ROS2_NAMESPACE_MAX_LENGTH:
        how = " once made absolute" if shift else ""
        reason = _length_reason(len(body) + shift, ROS2_NAMESPACE_MAX_LENGTH, "namespace", how)
        return _illegal(reason, None)
    if body != name:
        reason = "ends with '/' (ROS 2 rejects it)"
        return Problem(TRAILING_SLASH, reason, len(name) - 1, fatal=True, suggestion=body)
    return None


def _full_name_char_problem(full: str, at: int, shift: int) -> Problem | None:
    """Character ``at`` (> 0) of an absolute name; reported at ``at - shift`` as written."""
    char, index = full[at], at - shift
    if char not in _GRAPH:
        return _illegal(_char_reason(char, index), index)
    if char in _DIGITS and full[at - 1] == "/":
        return _illegal(_digit_reason(char, index), index)
    if char == "/" and full[at - 1] == "/":
        return _illegal(f"contains '//' at index {index - 1}", index - 1)
    return None


def _full_name_defect(full: str) -> tuple[str, int] | None:
    """rmw_validate_full_topic_name, without the length check, on an expansion.

    An expansion of a name that passed ``_ros2_written_problem``, in a valid namespace with
    a valid node name, is non-empty, absolute and made of legal characters, so only the
    structural checks are left, in rmw's order. Returns what is wrong (a fragment that
    follows "which") and its index in ``full``.
    """
    if full.endswith("/"):
        return "ends with '/'", len(full) - 1
    for index in range(len(full) - 1):
        if full[index] != "/":
            continue
        follower = full[index + 1]
        if follower == "/":
            return _DOUBLE, index
        if follower in _DIGITS:
            return f"has a token that starts with a digit ({follower!r})", index + 1
    return None


def _expand(name: str, namespace: str, node: str) -> tuple[str, list[int]]:
    """rcl_expand_topic_name for a name that passed ``_ros2_written_problem``.

    ``namespace`` is absolute and canonical ('/' or '/a/b'). Also returns, for every
    character of the expansion, the index in ``name`` it came from (a substitution's
    characters map to its '{', the '~' and namespace prefixes to 0), so a defect found after
    expansion can be pointed at in the name as written. Raises _UnknownSubstitutionError.
    """
    parent = namespace.rstrip("/")  # rcl writes no separator after the root namespace
    chars: list[str] = []
    origins: list[int] = []
    index = 0
    if name.startswith("~"):
        prefix = f"{parent}/{node}"
        chars.extend(prefix)
        origins.extend([0] * len(prefix))
        index = 1
    while index < len(name):
        end = name.index("}", index) + 1 if name[index] == "{" else index + 1
        piece = (
            _substitute(name[index:end], index, namespace, node) if end > index + 1 else name[index]
        )
        chars.extend(piece)
        origins.extend([index] * len(piece))
        index = end
    if not chars or chars[0] != "/":
        chars[:0] = parent + "/"
        origins[:0] = [0] * (len(parent) + 1)
    return "".join(chars), origins


def _blame(name: str, origins: list[int]) -> int:
    """Of the written characters behind a defect, the substitution or '~' that caused it.

    A defect the written checks missed was made by an expansion ('{ns}/x' -> '//x'), so
    point there rather than at a neighbouring '/'.
    """
    return next((origin for origin in origins if name[origin] in "{~"), origins[0])


def _substitute(text: str, index: int, namespace: str, node: str) -> str:
    """The replacement for ``text`` ('{...}', at ``index`` in the name), as rcl makes it."""
    key = text[1:-1]
    if key not in ROS2_SUBSTITUTIONS:
        raise _UnknownSubstitutionError(text, index)
    return node if key == "node" else namespace


# -------------------------------------------------------------------------- suggestions


def _valid_suggestion(
    problem: Problem, name: str, kind: Kind, generation: Generation
) -> str | None:
    """The problem's own suggestion, else a general repair; only one with no problem left."""
    for candidate in (problem.suggestion, _repair(name, kind, generation)):
        if candidate and candidate != name and _find_problem(candidate, kind, generation) is None:
            return candidate
    return None


def _repair(name: str, kind: Kind, generation: Generation) -> str | None:
    """An obvious corrected spelling, or None; the caller checks that it is legal.

    Only unambiguous fixes: accents dropped, '-', '.' and ' ' turned into '_', '//' into
    '/', a trailing '/' dropped, ROS 2 '~x' -> '~/x', ROS 2 '{ns}/x' -> 'x' (the same name
    in every namespace but the root), a ROS 1 leading '_' dropped.
    """
    if kind is Kind.FRAME:
        return name.lstrip("/") or None
    if kind is Kind.PARAMETER and generation is Generation.ROS2:
        return None
    text = _fold_accents(name)
    if not text.isascii():
        return None
    if kind is Kind.PARAMETER:
        text = text.replace(".", "/")  # a ROS 1 user writing 'gains.p' means a namespace
    text = text.translate(_SEPARATOR_TYPOS)
    if kind is Kind.NODE:
        text = text.rsplit("/", 1)[-1].lstrip("~")
        return text.lstrip("_") if generation is Generation.ROS1 else text
    return _repair_graph_name(text, kind, generation)


def _repair_graph_name(text: str, kind: Kind, generation: Generation) -> str:
    if generation is Generation.ROS2:
        if len(text) > 1 and text[0] == "~" and text[1] != "/":
            text = "~/" + text[1:]
        for prefix in ("{ns}/", "{namespace}/"):
            if text.startswith(prefix) and kind is not Kind.NAMESPACE:
                text = text[len(prefix) :]
    else:
        text = text.lstrip("_")
    text = _SLASH_RUN.sub("/", text)
    keeps_slash = kind is Kind.NAMESPACE and generation is Generation.ROS1
    if len(text) > 1 and text.endswith("/") and not keeps_slash:
        text = text[:-1]
    return text


# ---------------------------------------------------------------------------- resolving


def _resolve_ros1(name: str, namespace: str, node_name: str | None) -> str:
    """roscpp ``names::resolve`` (which agrees with rosgraph ``resolve_name``)."""
    # roscpp validates and then collapses '//' (rosgraph would refuse it): check the name as
    # roscpp will use it.
    _require(_ros1_graph_problem(_SLASH_RUN.sub("/", name), Kind.TOPIC), "ROS 1 name", name)
    parent = _ros1_namespace(namespace)
    if name.startswith("~"):
        node = _require_node(name, node_name, Generation.ROS1)
        joined = f"{parent}/{node}/{name[1:]}"
    elif name.startswith("/"):
        joined = name
    else:
        joined = f"{parent}/{name}"  # '' -> the namespace itself
    return _canonical(joined)


def _ros1_namespace(namespace: str) -> str:
    if namespace.startswith("~"):
        raise NameResolutionError(f"cannot resolve in namespace {namespace!r}: it is private")
    collapsed = _SLASH_RUN.sub("/", namespace)
    _require(_ros1_graph_problem(collapsed, Kind.NAMESPACE), "ROS 1 namespace", namespace)
    return _canonical(namespace)


def _resolve_ros2(name: str, namespace: str, node_name: str | None) -> str:
    """rcl_expand_topic_name then rmw_validate_full_topic_name, as rcl_node_resolve_name."""
    if not name:
        raise NameResolutionError("cannot resolve ROS 2 name '': it must not be empty")
    if name.endswith("/"):
        raise NameResolutionError(f"cannot resolve ROS 2 name {name!r}: it ends with '/'")
    _require(_ros2_written_problem(name, strict_tilde=False), "ROS 2 name", name)
    parent = _ros2_namespace(namespace)
    needs_node = name.startswith("~") or "{node}" in name
    node = _require_node(name, node_name, Generation.ROS2) if needs_node else ""
    if node_name is not None and not needs_node:
        _require(_node_problem(node_name, Generation.ROS2), "ROS 2 node name", node_name)
    try:
        full, _ = _expand(name, parent, node)
    except _UnknownSubstitutionError as error:
        message = f"cannot resolve ROS 2 name {name!r}: unknown substitution '{error.text}'"
        raise NameResolutionError(message) from None
    defect = _full_name_defect(full)
    if defect is not None:
        message = f"cannot resolve ROS 2 name {name!r} in {parent!r}: {full!r} {defect[0]}"
        raise NameResolutionError(message)
    limit = ROS2_NAME_MAX_LENGTH[Kind.TOPIC]  # what rmw_validate_full_topic_name enforces
    if len(full) > limit:
        message = f"cannot resolve ROS 2 name {name!r}: {full!r} is longer than {limit}"
        raise NameResolutionError(message)
    return full


def _ros2_namespace(namespace: str) -> str:
    _require(_ros2_namespace_problem(namespace), "ROS 2 namespace", namespace)
    if namespace in ("", "/"):
        return "/"
    return namespace if namespace.startswith("/") else "/" + namespace


def _require_node(name: str, node_name: str | None, generation: Generation) -> str:
    if node_name is None:
        raise NameResolutionError(f"cannot resolve {name!r} without a node name")
    label = f"ROS {generation.value} node name"
    _require(_node_problem(node_name, generation), label, node_name)
    return node_name


def _require(problem: Problem | None, what: str, name: str) -> None:
    if problem is not None and problem.fatal:
        raise NameResolutionError(f"cannot resolve {what} {name!r}: it {problem.reason}")


def _canonical(name: str) -> str:
    """Absolute, '//' collapsed, no trailing '/' except for the root."""
    return "/" + "/".join(token for token in name.split("/") if token)


# ------------------------------------------------------------------------------ helpers


def _split_outside_braces(text: str, separators: str) -> list[str]:
    parts: list[str] = []
    current: list[str] = []
    braces = 0
    for char in text:
        if char in separators and braces == 0:
            parts.append("".join(current))
            current = []
            continue
        braces += (char == "{") - (char == "}")
        braces = max(braces, 0)  # a stray '}' must not hide later separators
        current.append(char)
    parts.append("".join(current))
    return parts


def _fold_accents(text: str) -> str:
    """'caméra' -> 'camera': NFKD, then drop the combining marks."""
    decomposed = unicodedata.normalize("NFKD", text)
    return "".join(char for char in decomposed if not unicodedata.combining(char))


def _alnum_runs(text: str) -> list[str]:
    """Maximal runs of ASCII letters and digits; everything else separates words."""
    runs: list[str] = []
    current: list[str] = []
    for char in text + " ":
        if char.isascii() and char.isalnum():
            current.append(char)
        elif current:
            runs.append("".join(current))
            current = []
    return runs


def _humps(run: str) -> list[str]:
    """Split a camel-case run: 'cmdVel' -> cmd|Vel, 'HTTPServer' -> HTTP|Server.

    A capital starts a word after a lowercase letter, or after a digit or capital when a
    lowercase letter follows it ('Vector3Stamped' -> Vector3|Stamped, 'Point3D' stays whole).
    """
    words: list[str] = []
    start = 0
    for index in range(1, len(run)):
        previous, char = run[index - 1], run[index]
        following = run[index + 1] if index + 1 < len(run) else ""
        if not char.isupper():
            continue
        if previous.islower() or (following.islower() and not previous.islower()):
            words.append(run[start:index])
            start = index
    words.append(run[start:])
    return words
