"""The cache's large bookkeeping dicts kept as a base and a journal (``journal``)."""

from __future__ import annotations

import pickle
from pathlib import Path

from roslint_names.cache import BuiltinsUnpickler, FactsCache
from roslint_names.journal import _HEAD, Journaled

# Shaped as the digests are: path -> (status, digest, binary).
ENTRIES = {
    f"/ws/src/pkg/src/file{i}.cpp": ((100 + i, 1, 2, i), f"{i:040x}", False) for i in range(40)
}


def kept(cache: FactsCache) -> Journaled:
    return Journaled(cache, cache.directory / "digests" / "workspace", 8, BuiltinsUnpickler, 1)


def journal_of(cache: FactsCache) -> Path:
    return cache.directory / "digests" / "workspace-journal"


def base_of(cache: FactsCache) -> Path:
    return cache.directory / "digests" / "workspace"


def journaled_entries(cache: FactsCache) -> tuple[dict[str, object], ...]:
    """The sections the journal holds, past its head."""
    sections: tuple[dict[str, object], ...] = pickle.loads(
        journal_of(cache).read_bytes()[_HEAD.size :]
    )
    return sections


def test_a_few_changes_are_journaled_and_read_back_over_the_base(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    kept(cache).save((dict(ENTRIES),))
    base = (cache.directory / "digests" / "workspace").read_bytes()
    changed = dict(ENTRIES)
    changed["/ws/src/pkg/src/file3.cpp"] = ((7, 7, 7, 3), "f" * 40, False)
    del changed["/ws/src/pkg/src/file5.cpp"]
    changed["/ws/src/pkg/src/new.cpp"] = ((1, 1, 1, 99), "e" * 40, False)
    journaled = kept(cache)
    assert journaled.load(1) == (ENTRIES,)
    journaled.save((changed,))
    assert (cache.directory / "digests" / "workspace").read_bytes() == base  # not rewritten
    assert journaled_entries(cache) == (
        {
            "/ws/src/pkg/src/file3.cpp": ((7, 7, 7, 3), "f" * 40, False),
            "/ws/src/pkg/src/new.cpp": ((1, 1, 1, 99), "e" * 40, False),
            "/ws/src/pkg/src/file5.cpp": None,
        },
    )
    again = kept(cache)
    assert again.load(1) == (changed,)
    # A later change adds to the journal, which still holds the earlier ones.
    later = dict(changed)
    later["/ws/src/pkg/src/file9.cpp"] = ((9, 9, 9, 9), "d" * 40, True)
    again.save((later,))
    assert kept(cache).load(1) == (later,)
    assert len(journaled_entries(cache)[0]) == 4


def test_nothing_changed_writes_nothing(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    kept(cache).save((dict(ENTRIES),))
    journaled = kept(cache)
    journaled.load(1)
    journaled.save((dict(ENTRIES),))
    assert not journal_of(cache).exists()


def test_a_long_journal_is_folded_into_a_new_base(tmp_path: Path) -> None:
    """Past a quarter of the entries: the whole is written again, the journal removed."""
    cache = FactsCache(tmp_path)
    kept(cache).save((dict(ENTRIES),))
    journaled = kept(cache)
    journaled.load(1)
    few = dict(ENTRIES)
    for i in range(5):
        few[f"/ws/src/pkg/src/file{i}.cpp"] = ((0, 0, 0, i), "0" * 40, False)
    journaled.save((few,))
    assert journal_of(cache).exists()
    journaled = kept(cache)
    journaled.load(1)
    many = dict(few)
    for i in range(5, 11):
        many[f"/ws/src/pkg/src/file{i}.cpp"] = ((0, 0, 0, i), "0" * 40, False)
    journaled.save((many,))  # 11 of 40 journaled: more than a quarter
    assert not journal_of(cache).exists()
    assert kept(cache).load(1) == (many,)


def test_a_journal_of_another_base_is_not_read(tmp_path: Path) -> None:
    """A journal left by a crash between a new base and its removal, or one whose base was
    evicted and written again: its entries are not this base's changes."""
    cache = FactsCache(tmp_path)
    kept(cache).save((dict(ENTRIES),))
    journaled = kept(cache)
    journaled.load(1)
    changed = {**ENTRIES, "/ws/src/pkg/src/file1.cpp": ((5, 5, 5, 1), "a" * 40, False)}
    journaled.save((changed,))
    stale = journal_of(cache).read_bytes()
    kept(cache).save((dict(ENTRIES),))  # a new base, nothing loaded first
    journal_of(cache).write_bytes(stale)
    assert kept(cache).load(1) == (ENTRIES,)


def test_a_damaged_base_or_journal_is_none(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    kept(cache).save((dict(ENTRIES),))
    journaled = kept(cache)
    journaled.load(1)
    journaled.save(({**ENTRIES, "/ws/x.cpp": ((1, 1, 1, 1), "b" * 40, False)},))
    journal_of(cache).write_bytes(b"\x80\x05damaged")
    assert kept(cache).load(1) == (ENTRIES,)  # the base alone: an entry missed, none wrong
    assert kept(cache).load(2) is None  # another shape
    (cache.directory / "digests" / "workspace").write_bytes(pickle.dumps(("1", "t", ({},))))
    assert kept(cache).load(1) is None
    assert not kept(cache).extend(({"/ws/x.cpp": ((1, 1, 1, 1), "b" * 40, False)},))
    head = base_of(cache).read_bytes()
    base_of(cache).write_bytes(head[: _HEAD.size - 1])  # a head torn short
    assert kept(cache).load(1) is None


def test_additions_are_journaled_over_a_base_never_loaded(tmp_path: Path) -> None:
    """What a run that carried every other entry saves (``digests``): the base is read
    no further than its head, and left as it was."""
    cache = FactsCache(tmp_path)
    kept(cache).save((dict(ENTRIES),))
    base = base_of(cache).read_bytes()
    first = {"/ws/src/pkg/src/file3.cpp": ((7, 7, 7, 3), "f" * 40, False)}
    assert kept(cache).extend((first,))
    second = {"/ws/src/pkg/src/file4.cpp": ((8, 8, 8, 4), "e" * 40, False)}
    assert kept(cache).extend((second,))  # onto the journal the first left
    assert base_of(cache).read_bytes() == base
    assert journaled_entries(cache) == ({**first, **second},)
    assert kept(cache).load(1) == ({**ENTRIES, **first, **second},)
    assert kept(cache).extend(({},))  # nothing learned: nothing written
    assert journaled_entries(cache) == ({**first, **second},)


def test_additions_past_the_journal_s_share_or_without_a_base_are_left_to_the_caller(
    tmp_path: Path,
) -> None:
    cache = FactsCache(tmp_path)
    first = {"/ws/src/pkg/src/file3.cpp": ((7, 7, 7, 3), "f" * 40, False)}
    assert not kept(cache).extend((first,))  # no base
    assert not journal_of(cache).exists()
    kept(cache).save((dict(ENTRIES),))
    many = {f"/ws/new{i}.cpp": ((i, i, i, i), "c" * 40, False) for i in range(11)}
    assert not kept(cache).extend((many,))  # 11 of 40: past a quarter
    assert not journal_of(cache).exists()


def test_additions_over_a_journal_of_another_base_drop_that_journal(tmp_path: Path) -> None:
    cache = FactsCache(tmp_path)
    kept(cache).save((dict(ENTRIES),))
    stale = {"/ws/src/pkg/src/file1.cpp": ((5, 5, 5, 1), "a" * 40, False)}
    assert kept(cache).extend((stale,))
    left = journal_of(cache).read_bytes()
    kept(cache).save((dict(ENTRIES),))  # a new base, nothing loaded first
    journal_of(cache).write_bytes(left)
    fresh = {"/ws/src/pkg/src/file2.cpp": ((6, 6, 6, 2), "b" * 40, False)}
    assert kept(cache).extend((fresh,))
    assert kept(cache).load(1) == ({**ENTRIES, **fresh},)
