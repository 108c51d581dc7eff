"""One decision, one finding: a name written at many places is reported once.

The rules that judge a name (RN101 illegal-name, RN202 hard-coded-absolute-name, RN203
not-snake-case, RN201 name-too-deep for names in code) find it wherever it is written:
ros2/examples publishes ``topicA`` from two programs, MoveIt builds its
``/recognize_objects`` action client in two files of one plugin, amcl reads
``beam_skip_error_threshold_`` twice. Its maintainer changes the name once, so the run
reports it once. Each such finding carries its ``Decision``; once every reported file's
per-file findings are in (``one_per_decision``):

- the findings of one rule on one decision (the kind, the name or the absolute prefix it
  is built from, the generation; for a parameter or a private ``~`` name, its file) are
  one finding;
- it is kept where the name starts, at a producer (a publisher, a service or action
  server), else at the first place in path and line order; every other place becomes a
  related location, and the message says how many there are;
- its fix is the whole decision: the other places' edits go with its own (``Diagnostic.
  also``), all or none, so a place the linter cannot edit leaves the decision without a
  fix; a rename (RN203) renames every use of the name anyway (``editing.renames``);
- suppressions were applied file by file before, so a comment at any place is used (no
  RN002 says it silences nothing). A kept finding that is suppressed silences the whole
  decision: it does not come back at another place. A place suppressed while the kept one
  is not stays a suppressed finding of its own, not merged: someone chose to keep the
  spelling there, and that holds a rename of it back.

Then a file whose code writes every endpoint name absolute (``Decision.bound``, RN202)
binds its node to the root namespace by one choice: what is left of its findings of the
rule is joined the same way, kept at its first place.

Only the reported files are grouped. In a run over some files (pre-commit passes the
changed ones; the rest of the workspace is context), a place whose producer is in a
context file is reported where it is: the files not linted have no findings to join.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Sequence
from dataclasses import replace

from .model import Decision, Diagnostic, Edit, Generation, Kind, RelatedLocation, Span

_Key = tuple[str, Kind, str, Generation, bool, str]
_Place = tuple[int, int]  # (file slot, position in it)


def one_per_decision(per_file: Sequence[Sequence[Diagnostic]]) -> list[list[Diagnostic]]:
    """Each file's diagnostics with every decision reported once (module docstring).

    ``per_file``: the reported files' diagnostics, one slot per file in discovery order;
    the result does not depend on the order within or across slots beyond that."""
    # The slots holding any, of one per file of the workspace (77,000 at 8 copies of the
    # benchmark's): the rest are walked by none of the loops below.
    occupied = [slot for slot, found in enumerate(per_file) if found]
    groups: dict[_Key, list[_Place]] = defaultdict(list)
    for slot in occupied:
        for position, diagnostic in enumerate(per_file[slot]):
            if diagnostic.decision is not None:
                groups[_key(diagnostic.code, diagnostic.decision)].append((slot, position))
    joined = _join(per_file, occupied, groups.values(), design=False)
    # Then a file bound to the root by design (``Decision.bound``): what is left of its
    # names' findings is one.
    designs: dict[tuple[int, str], list[_Place]] = defaultdict(list)
    for slot in occupied:
        for position, diagnostic in enumerate(joined[slot]):
            if diagnostic.decision is not None and diagnostic.decision.bound:
                designs[(slot, diagnostic.code)].append((slot, position))
    return _join(joined, occupied, designs.values(), design=True)


def _join(
    per_file: Sequence[Sequence[Diagnostic]],
    occupied: Sequence[int],
    groups: Iterable[list[_Place]],
    *,
    design: bool,
) -> list[list[Diagnostic]]:
    """``per_file`` with each group of places reported once; ``design``: the groups are
    files' designs, kept at their first place. ``occupied``: the slots holding any."""
    replaced: dict[_Place, Diagnostic | None] = {}
    for places in groups:
        if len(places) < 2:
            continue
        kept_at, *others = sorted(
            places, key=lambda place: _preference(_at(per_file, place), design=design)
        )
        kept = _at(per_file, kept_at)
        joined = [
            place for place in others if kept.suppressed or not _at(per_file, place).suppressed
        ]
        if not joined:
            continue
        replaced[kept_at] = _joined(kept, [_at(per_file, place) for place in joined], design)
        replaced.update((place, None) for place in joined)
    result = list(map(list, per_file))
    for slot in {slot for slot, _ in replaced}:
        result[slot] = [
            shown
            for position, diagnostic in enumerate(per_file[slot])
            if (shown := replaced.get((slot, position), diagnostic)) is not None
        ]
    return result


def _key(code: str, decision: Decision) -> _Key:
    return (
        code,
        decision.kind,
        decision.name,
        decision.generation,
        decision.prefix,
        decision.scope,
    )


def _at(per_file: Sequence[Sequence[Diagnostic]], place: _Place) -> Diagnostic:
    return per_file[place[0]][place[1]]


def _preference(
    diagnostic: Diagnostic, *, design: bool
) -> tuple[bool, tuple[str, int, int, str, str]]:
    """A producer first, then path and line order; a file's design at its first name."""
    decision = diagnostic.decision
    producer = decision is not None and decision.producer and not design
    return (not producer, diagnostic.sort_key())


def _joined(kept: Diagnostic, others: list[Diagnostic], design: bool) -> Diagnostic:
    """``kept`` standing for ``others`` too: theirs as related locations, and one fix."""
    others = sorted(others, key=Diagnostic.sort_key)
    related = [*kept.related]
    for other in others:
        related.append(RelatedLocation(other.path, other.span, _note(other, design)))
        related.extend(other.related)
    count = len(others)
    places = f"{count} other place{'s' if count > 1 else ''}"
    if design:
        message = (
            f"{kept.message} (every endpoint name of this file is absolute, {count} more: "
            "one decision, its node is bound to the root namespace)"
        )
    else:
        message = f"{kept.message} (also written at {places})"
    edit, also = _whole_fix(kept, others)
    joined = (
        *kept.joined,
        *(place for other in others for place in (replace(other, joined=()), *other.joined)),
    )
    return replace(
        kept, message=message, related=tuple(related), edit=edit, also=also, joined=joined
    )


def _note(diagnostic: Diagnostic, design: bool) -> str:
    decision = diagnostic.decision
    assert decision is not None
    kind = decision.kind.value
    what = (
        f"a {kind} built from '{decision.name}'" if decision.prefix else f"{kind} '{decision.name}'"
    )
    if design:
        absolute = f"a {kind} built from the absolute" if decision.prefix else f"absolute {kind}"
        return f"{absolute} '{decision.name}' here too"
    return f"{what} also written here" + (f" ({decision.api})" if decision.api else "")


def _whole_fix(kept: Diagnostic, others: list[Diagnostic]) -> tuple[Edit | None, tuple[Edit, ...]]:
    """The kept finding's fix extended to every place, or none where a place has none: a
    decision fixed at some places only is not fixed (a publisher made relative, its
    subscriber left absolute, meet only in the root namespace). A pending rename is left
    as it is: ``renames`` offers it with every use of the name, these places among them."""
    if kept.renaming is not None or kept.edit is None:
        return kept.edit, kept.also
    if any(other.edit is None or other.renaming is not None for other in others):
        return None, ()
    own = (kept.path, kept.edit.span)
    edits: dict[tuple[str, Span], Edit] = {}  # by file and span: each place's edit once
    for diagnostic in (kept, *others):
        assert diagnostic.edit is not None
        for edit in (diagnostic.edit, *diagnostic.also):
            path = edit.path or diagnostic.path
            if (path, edit.span) != own:
                located = replace(edit, path=None if path == kept.path else path)
                edits.setdefault((path, edit.span), located)
    safe = kept.edit.safe and all(edit.safe for edit in edits.values())
    also = tuple(replace(edits[key], safe=safe) for key in sorted(edits))
    return replace(kept.edit, safe=safe), also
