"""The invariants every fuzz input must keep.

An extractor returns ``FileFacts`` for any bytes: no exception, at most one parse error
(one RN001 per file), no warning a user would see printed, spans that are 1-based and do
not end before they start, and nothing but plain fact values inside: the facts cache
pickles them and unpickles only ``roslint_names.model`` classes, and every report is
UTF-8, so a string holding a lone surrogate could not be printed.
"""

from __future__ import annotations

import dataclasses
import enum
import warnings
from collections.abc import Iterator

from fuzz.inputs import Sample, Target
from roslint_names import model
from roslint_names.model import FileFacts, Span

# What Python's default warning filters hide from a user (outside __main__).
QUIET_WARNINGS = (DeprecationWarning, PendingDeprecationWarning, ImportWarning, ResourceWarning)
_PLAIN = (str, int, float, bool, type(None))


def check_extraction(target: Target, sample: Sample) -> FileFacts:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        facts = sample.call(target)
    shown = [str(w.message) for w in caught if not issubclass(w.category, QUIET_WARNINGS)]
    assert not shown, f"warnings a user would see: {shown}"
    assert isinstance(facts, FileFacts), type(facts)
    assert facts.path == sample.path
    assert len(facts.parse_errors) <= 1, facts.parse_errors
    for where, value in _values(facts, "facts"):
        if isinstance(value, Span):
            assert value.line >= 1 and value.column >= 1, f"{where}: {value}"
            assert (value.end_line, value.end_column) >= (value.line, value.column), (
                f"{where}: {value} ends before it starts"
            )
    return facts


def _values(value: object, where: str) -> Iterator[tuple[str, object]]:
    """Every value inside ``value``; fails on anything that is no plain fact value."""
    yield where, value
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        assert type(value).__module__ == model.__name__, f"{where}: {type(value)}"
        for field in dataclasses.fields(value):
            yield from _values(getattr(value, field.name), f"{where}.{field.name}")
    elif isinstance(value, tuple):
        assert type(value) is tuple, f"{where}: {type(value)}"
        for index, item in enumerate(value):
            yield from _values(item, f"{where}[{index}]")
    elif isinstance(value, enum.Enum):
        assert type(value).__module__ == model.__name__, f"{where}: {type(value)}"
    else:
        assert type(value) in _PLAIN, f"{where}: {type(value).__name__} {value!r:.80}"
        if isinstance(value, str):  # every report is UTF-8: a lone surrogate cannot be written
            assert _encodable(value), f"{where}: a lone surrogate in {value!r:.200}"


def _encodable(text: str) -> bool:
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return False
    return True
