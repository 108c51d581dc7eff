"""The facts cache: what an extractor returned for one file, kept between runs; and the
result of a whole run, for the next run over the same inputs.

Facts are cached per file, never with diagnostics: rules, configuration and suppressions
may change between runs, and applying them to cached facts is cheap next to parsing. An
entry is found by a key over
everything an extractor's result depends on: the file's bytes, the path it is reported
under (it is part of the facts, and the Python extractor reads the file name), the
language, the package's generation and the fallback generation, and whether a Python file
may be Python 2 (``generation.reads_python2``). Everything that is the
same for a whole run (this module's format, the tool version, the source of the
extractors and of the modules they import, the parser libraries, the Python version) is
hashed once into the name of the directory holding the entries, so a development checkout
whose extractor changed, or a parser upgrade, never serves stale facts.

Location: ``--cache-dir``, else ``$XDG_CACHE_HOME/roslint-names``, else
``~/.cache/roslint-names``; never the linted tree. A cache that cannot be created or
written makes the run slower, never wrong: problems are collected in ``problems``
(``--verbose`` prints them).

Entries are not files of their own: creating thousands of small files is what a cold run
would spend most of its cache time on (0.7 ms each on an ext4 disk, 3 s for realws's
4,500 entries), and opening them what a warm run would. Most files of a workspace hold
nothing (C++ and Python without ROS code, launch files without names), and their facts
are only a language and a generation: each is one line of a log, ``KEY LANGUAGE
GENERATION CHECKSUM``. The others are records of a pack: a marker, the key, the
payload's length, a checksum over all three and the pickled facts. A key's first hex
digit names its log and its pack (``empty-0.log``, ``facts-0.pack`` ... ``-f``): a run
after an edit looks up a few keys, and indexes only their sixteenths (a whole pack of
66 MB at 8 copies of the benchmark's workspace took 0.08 s to index, the log 0.03 s to
read, for three lookups). Logs and packs are only ever appended to, a batch at a time,
by a single ``write`` on an ``O_APPEND`` descriptor, which concurrent runs cannot
interleave on a local file system. Each is read at most once per run, when a key of it
is first looked up (a pack mapped, its pages handed back as it is indexed, and a
record's checksum verified when it is loaded). A line or record that is torn, truncated
or fails its checksum is skipped (the pack is searched for the next marker), its file is
extracted again and appended again; the last whole record of a key wins. Once a pack or
a log outgrows its share of ``PACK_LIMIT``, the next run that reads it rewrites it
(atomically, by a rename) with the records or lines that run used (every checked file's
facts, loaded or not: ``stand_on``) and whatever was appended after it read it.

Why pickle is safe enough here: entries are read with an unpickler that resolves no global
but the fact classes and enums of ``roslint_names.model``. Unpickling can then only build
those values; it cannot import a module or call anything else, so a tampered entry can at
worst yield wrong findings. The directory is created private to the user (0700), like the
rest of ``~/.cache``.

Deleting: the cache deletes only what it can tell is its own. Every entry directory it
creates holds a ``CACHEDIR.TAG`` of its own wording (``_CACHEDIR_TAG``), and the pruning
of stale directories passes over any ``facts-v*`` directory without one, whoever made
it: ``--cache-dir`` may name a folder the user keeps other things in. The folder itself
is tagged only when the cache created it (a tag tells backup tools to skip everything
under it).

A run over inputs a recent run had (every file's bytes, the package manifests read, the
settings, all of the tool's code: the engine makes the key, ``load_run``/``store_run`` keep
the value) is served whole from ``runs/``: applying the rules again is cheap next to
parsing, but not next to the 0.05x-the-parse-floor budget of a re-run (the README's
Performance table). Only the ``RUNS_KEPT`` most recently used results are kept.
``replays/`` holds what a run whose files' facts are those of a recent run takes instead
of building the workspace graph again (``same_facts``), keyed alike but for the facts;
``graphs/`` the graph the last runs over a whole workspace built, with the facts keys it
was built from, for a run whose edits change only what a node's code names
(``workspace.patch``).
``digests/`` holds, per workspace, each file's content digest with its status, so that
keying a re-run does not mean reading every file (``digests.ContentDigests``).
"""

from __future__ import annotations

import contextlib
import dataclasses
import enum
import hashlib
import io
import mmap
import os
import pickle
import re
import struct
import sys
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any, NamedTuple

from . import __version__, model
from .model import LANGUAGE_OF_VALUE, FileFacts, Generation, Language
from .reading import content_digest, open_regular

FORMAT_VERSION = 2  # 2: facts in one pack; whole-run results; digests
_MAGIC = b"RNFACTS\x01"
_CHECKSUM_BYTES = 16
_PREFIX = "facts-v"
# A key's first hex digit: the sixteenth of the log and of the pack its facts are in.
SHARDS = "0123456789abcdef"
_RECORD = b"RNREC\x02"  # starts every record of the pack
_KEY_BYTES = 40  # hex digits of a key
_LENGTH_BYTES = 4
_RECORD_HEADER = len(_RECORD) + _KEY_BYTES + _LENGTH_BYTES + _CHECKSUM_BYTES
# Bytes of the packs, or of the logs, together: beyond its share of it, a pack or a log is
# rewritten with what a run used.
PACK_LIMIT = 64 * 1024 * 1024
_PACK_BATCH = 1024 * 1024  # bytes of records buffered before an append
_RUNS = "runs"
DIGESTS = "digests"  # the directory of ``digests.ContentDigests``, one file per workspace
RUNS_KEPT = 64  # whole-run results: one per recent (file set, settings) of each checkout
_CHECKS = "checks"  # the sets of files the per-file rules found clean (``clean_files``)
CHECKS_KEPT = 8  # one per recent (settings, rules, packages) of each checkout
_REPLAYS = "replays"  # what a run whose facts are the last run's takes (``same_facts``)
REPLAYS_KEPT = 8  # one per recent (file set, settings) of each checkout
_GRAPHS = "graphs"  # a built graph, kept by its replay's key, to patch (``workspace.patch``)
# The same build's whole graph and its launch trees' parts (``workspace.launch_patch``)
_LAUNCH_PARTS = "launch-parts"
# What a built graph's nodes' parameters were gathered from, to patch what code declares
# (``workspace.parameter_patch``)
_CODE_PARAMETERS = "code-parameters"
GRAPHS_KEPT = 2  # tens of MB each in a large workspace: the last file sets only
# The last run of each shape that kept a replay, and where a renumbered run's graph is
# (``shifts``): one per recent (file set, settings) of each checkout, as replays.
_BASES = "bases"
_FILE_LISTS = "file-lists"
_GRAPH_MOVES = "graph-moves"
_LOG_BATCH = 512  # lines buffered before an append; and every batch of extraction ends one
_TAG_NAME = "CACHEDIR.TAG"
_CACHEDIR_TAG = (
    "Signature: 8a477f597d28d172789f06886806bc55\n"
    "# This file is a cache directory tag created by roslint-names.\n"
    "# For information about cache directory tags see https://bford.info/cachedir/\n"
)
# Another version's (or another checkout's) entries are deleted once no run has used them
# for this long: a development checkout gets a new directory with every extractor edit.
STALE_AFTER_SECONDS = 24 * 3600

# What the extractors' results depend on besides their arguments: their own code, the
# package modules they import (found by following their imports, see
# ``_extractor_sources``; these are always in), and the parser libraries.
_EXTRACTOR_SOURCES = ("extract", "model.py", "names.py", "types.py")
_PARSER_PACKAGES = ("tree_sitter", "tree_sitter_cpp", "libcst", "lxml", "yaml")
# `from roslint_names.X`, `import roslint_names.X`, `from roslint_names import X`, and the
# relative `from ..X` (in extract/) or `from .X` (in a top-level module), at any indent.
_PACKAGE_IMPORT = re.compile(
    rb"^[ \t]*(?:from|import)[ \t]+"
    rb"(?:roslint_names\.(\w+)|roslint_names[ \t]+import[ \t]+(\w+)|\.{1,3}(\w+))",
    re.MULTILINE,
)


def default_directory(environ: Mapping[str, str] | None = None) -> Path | None:
    """``$XDG_CACHE_HOME/roslint-names`` or ``~/.cache/roslint-names``; None without a home."""
    environ = os.environ if environ is None else environ
    xdg = environ.get("XDG_CACHE_HOME", "")
    if xdg and os.path.isabs(xdg):  # the XDG spec says to ignore a relative value
        return Path(xdg) / "roslint-names"
    try:
        return Path.home() / ".cache" / "roslint-names"
    except RuntimeError:  # no HOME and no passwd entry: run without a cache
        return None


@dataclass
class CacheStats:
    hits: int = 0
    misses: int = 0
    corrupt: int = 0
    written: int = 0


# Writes an entry's bytes into the open file (``FactsCache.write_atomically``).
Writer = Callable[[IO[bytes]], object]


@dataclass
class FactsCache:
    """Entries under ``root``; picklable, so worker processes write their own entries."""

    root: Path
    stats: CacheStats = field(default_factory=CacheStats)
    problems: list[str] = field(default_factory=list)
    _directory: Path | None = field(default=None, init=False)
    _writable: bool | None = field(default=None, init=False)
    _subdirectories: set[str] = field(default_factory=set, init=False)
    # Each log read, by shard (``SHARDS``): the keys of its lines.
    _empty: dict[str, dict[str, tuple[Language, Generation]]] = field(
        default_factory=dict, init=False
    )
    _pending: dict[str, list[str]] = field(default_factory=dict, init=False)  # lines, by shard
    _pending_lines: int = field(default=0, init=False)
    # Each pack as this process mapped it, and where each key's payload is in it, by shard.
    _packs: dict[str, bytes | mmap.mmap] = field(default_factory=dict, init=False)
    # The pack files as opened, read record by record (``_read_record``)
    _pack_files: dict[str, IO[bytes] | None] = field(default_factory=dict, init=False)
    _records: dict[str, dict[str, tuple[int, int]]] = field(default_factory=dict, init=False)
    _pending_records: dict[str, list[bytes]] = field(default_factory=dict, init=False)
    _pending_bytes: int = field(default=0, init=False)
    # Each pack and log read, by name: which file, and how much of it, this run read.
    _read_as: dict[str, _Read | None] = field(default_factory=dict, init=False)
    _stored: dict[str, FileFacts] = field(default_factory=dict, init=False)  # not yet written
    _used: set[str] = field(default_factory=set, init=False)  # keys looked up or stored

    def __getstate__(self) -> dict[str, object]:
        """What a spawned worker needs: where the cache is, not what this process read
        (the pack alone is megabytes) or has yet to write."""
        return {"root": self.root}

    def __setstate__(self, state: dict[str, object]) -> None:
        root = state["root"]
        assert isinstance(root, Path)
        self.__init__(root)  # type: ignore[misc]

    @property
    def directory(self) -> Path:
        """This run's entries: the root plus the fingerprint of everything run-constant."""
        if self._directory is None:
            self._directory = self.root / f"{_PREFIX}{FORMAT_VERSION}-{run_fingerprint()}"
        return self._directory

    def key(
        self,
        data: bytes,
        path: str,
        language: Language,
        package_generation: Generation | None,
        fallback_generation: Generation,
        *,
        python2: bool = False,
    ) -> str:
        return self.key_of_digest(
            content_digest(data),
            path,
            language,
            package_generation,
            fallback_generation,
            python2=python2,
        )

    def key_of_digest(
        self,
        content: str,
        path: str,
        language: Language,
        package_generation: Generation | None,
        fallback_generation: Generation,
        *,
        python2: bool = False,
    ) -> str:
        """``key`` of a file whose bytes have ``content_digest`` ``content``."""
        digest = hashlib.blake2b(digest_size=20)
        package = "-" if package_generation is None else str(package_generation.value)
        header = f"{path}\0{language.value}\0{package}\0{fallback_generation.value}\0{content}"
        if python2:  # only then: the other files' keys do not depend on it
            header += "\0python2"
        digest.update(header.encode("utf-8", errors="surrogatepass"))
        return digest.hexdigest()

    def load(self, key: str, path: str) -> FileFacts | None:
        """The facts stored under ``key`` (for the file reported as ``path``), or None."""
        self._used.add(key)
        shard = _shard_of(key)
        if shard is None:  # not a key this cache makes
            self.stats.misses += 1
            return None
        empty = self._empty_facts(shard).get(key)
        if empty is not None:
            self.stats.hits += 1
            return FileFacts(path, *empty)
        if key in self._stored:
            self.stats.hits += 1
            return self._stored[key]
        where = self._pack_records(shard).get(key)
        if where is None:  # the usual miss: extract
            self.stats.misses += 1
            return None
        facts = _read_record(self._pack_files.get(shard), self._packs[shard], *where)
        if facts is None:
            self.stats.corrupt += 1
            self.stats.misses += 1
        else:
            self.stats.hits += 1
        return facts

    def holds_facts(self) -> bool:
        """Whether any file's facts are stored: none in a first run of this version of the
        tool, where looking a file up by its content would find nothing."""
        if self._stored:
            return True
        names = [name for shard in SHARDS for name in (_log_name(shard), _pack_name(shard))]
        return any(_size(self.directory / name) for name in names)

    def _empty_facts(self, shard: str) -> dict[str, tuple[Language, Generation]]:
        """The keys of the facts that hold nothing whose first digit is ``shard``, and
        what they hold: its log, read once."""
        if shard not in self._empty:
            name = _log_name(shard)
            self._empty[shard], self._read_as[name] = _read_log_as(
                os.path.join(self.directory, name)
            )
        return self._empty[shard]

    def _pack_records(self, shard: str) -> dict[str, tuple[int, int]]:
        """Where each key of ``shard`` has its facts in its pack, the pack mapped once."""
        if shard not in self._records:
            name = _pack_name(shard)
            self._packs[shard], self._read_as[name], self._pack_files[shard] = _map_as(
                os.path.join(self.directory, name)
            )
            self._records[shard] = _index(self._packs[shard])
        return self._records[shard]

    def stand_on(self, keys: Iterable[str]) -> None:
        """Facts this run's result stands on without loading them (``same_facts``): used,
        as those loaded are, so that ``finish`` keeps them when it rewrites the pack."""
        self._used.update(keys)

    def store(self, key: str, facts: FileFacts) -> None:
        """Keep ``facts``; call ``flush`` before the process ends."""
        if not self.writable():
            return
        # Facts with nothing but a language and a generation (most files) are one log line.
        self._used.add(key)
        shard = _shard_of(key)
        if shard is None:
            return  # not a key this cache makes: nothing could find it again
        if facts == FileFacts(facts.path, facts.language, facts.generation):
            self._pending.setdefault(shard, []).append(
                _log_line(key, facts.language, facts.generation)
            )
            self._pending_lines += 1
            if self._pending_lines >= _LOG_BATCH:
                self.flush()
            return
        record = _record(key, model.dumps(facts))
        if record is None:
            return  # not a key this cache makes: nothing could find it again
        self._stored[key] = facts
        self._pending_records.setdefault(shard, []).append(record)
        self._pending_bytes += len(record)
        if self._pending_bytes >= _PACK_BATCH:
            self.flush()

    def load_run(self, key: str) -> object | None:
        """The value ``store_run`` kept under ``key``, or None (absent or corrupt)."""
        return self._load_entry(_RUNS, key)

    def load_checks(self, key: str) -> object | None:
        """The value ``store_checks`` kept under ``key``, or None (absent or corrupt)."""
        return self._load_entry(_CHECKS, key)

    def store_checks(self, key: str, value: object) -> None:
        """Keep a set of clean files (``clean_files``); forget the least recently used
        beyond ``CHECKS_KEPT``."""
        entry = self.directory / _CHECKS / key
        self.write_newest(entry, _encoded(value), CHECKS_KEPT)

    def load_replay(self, key: str) -> object | None:
        """The value ``store_replay`` kept under ``key``, or None (absent or corrupt)."""
        return self._load_entry(_REPLAYS, key)

    def store_replay(self, key: str, value: object) -> None:
        """Keep a run's replay (``same_facts``); forget the least recently used beyond
        ``REPLAYS_KEPT``."""
        self.write_newest(self.directory / _REPLAYS / key, _encoded(value), REPLAYS_KEPT)

    def load_graph(self, key: str) -> object | None:
        """The value ``store_graph`` kept under ``key``, or None (absent or corrupt)."""
        return self._load_entry(_GRAPHS, key, _GraphUnpickler)

    def holds_graph(self, key: str) -> bool:
        """Whether a graph is kept under ``key`` (whether it reads back is ``load_graph``'s)."""
        return os.path.isfile(os.path.join(self.directory, _GRAPHS, key))

    def store_graph(self, key: str, value: object) -> None:
        """Keep a built graph (``same_facts.KeptGraph``); forget all but the
        ``GRAPHS_KEPT`` most recently used."""
        self.write_newest(self.directory / _GRAPHS / key, _encoded(value), GRAPHS_KEPT)

    def load_base(self, key: str) -> object | None:
        """The value ``store_base`` kept under ``key``, or None."""
        return self._load_entry(_BASES, key)

    def store_base(self, key: str, value: object) -> None:
        """Keep the last run of a shape (``shifts.Base``); forget the least recently used
        beyond ``REPLAYS_KEPT``."""
        self.write_newest(self.directory / _BASES / key, _encoded(value), REPLAYS_KEPT)

    def load_file_list(self, key: str) -> object | None:
        """The value ``store_file_list`` kept under ``key``, or None."""
        return self._load_entry(_FILE_LISTS, key)

    def holds_file_list(self, key: str) -> bool:
        return os.path.isfile(os.path.join(self.directory, _FILE_LISTS, key))

    def store_file_list(self, key: str, value: object) -> None:
        """Keep the files of a run that kept a replay (``shifts.Base``), by its replay's
        key; forget the least recently used beyond ``REPLAYS_KEPT``."""
        self.write_newest(self.directory / _FILE_LISTS / key, _encoded(value), REPLAYS_KEPT)

    def load_graph_move(self, key: str) -> object | None:
        """The value ``store_graph_move`` kept under ``key``, or None."""
        return self._load_entry(_GRAPH_MOVES, key)

    def store_graph_move(self, key: str, value: object) -> None:
        """Keep where a renumbered run's graph is (``shifts.GraphMove``); forget the
        least recently used beyond ``REPLAYS_KEPT``."""
        self.write_newest(self.directory / _GRAPH_MOVES / key, _encoded(value), REPLAYS_KEPT)

    def load_launch_parts(self, key: str) -> object | None:
        """The value ``store_launch_parts`` kept under ``key``, or None."""
        return self._load_entry(_LAUNCH_PARTS, key, _GraphUnpickler)

    def store_launch_parts(self, key: str, value: object) -> None:
        """Keep a build's whole graph and its launch trees' parts
        (``same_facts.KeptLaunch``), loaded only by a run that walks some trees again:
        apart from the graph a code edit patches, which loads a third of the bytes."""
        self.write_newest(self.directory / _LAUNCH_PARTS / key, _encoded(value), GRAPHS_KEPT)

    def load_code_parameters(self, key: str) -> object | None:
        """The value ``store_code_parameters`` kept under ``key``, or None."""
        return self._load_entry(_CODE_PARAMETERS, key, _GraphUnpickler)

    def store_code_parameters(self, key: str, value: object) -> None:
        """Keep what a build's nodes' parameters were gathered from
        (``same_facts.KeptCode``), loaded only by a run that patches what code declares."""
        self.write_newest(self.directory / _CODE_PARAMETERS / key, _encoded(value), GRAPHS_KEPT)

    def _load_entry(
        self, kind: str, key: str, unpickler: type[pickle.Unpickler] | None = None
    ) -> object | None:
        entry = os.path.join(self.directory, kind, key)
        try:
            with open_regular(entry) as stream:
                blob = stream.read()
        except OSError:
            return None
        value = _decode(blob, unpickler or _FactsUnpickler)
        if value is not None:
            with contextlib.suppress(OSError):  # "recently used": kept by the pruning
                os.utime(entry)
        return value

    def store_run(self, key: str, value: object) -> None:
        """Keep a run's result (fact classes, enums and builtins only); forget the least
        recently used beyond ``RUNS_KEPT``."""
        self.write_newest(self.directory / _RUNS / key, _encoded(value), RUNS_KEPT)

    def write_newest(self, entry: Path, blob: bytes | Writer, kept: int) -> None:
        """Write ``blob`` (or what a ``Writer`` writes) as ``entry`` atomically, then forget
        all but the ``kept`` most recently written or used entries of its directory."""
        if self.writable() and self.write_atomically(entry, blob):
            keep_newest(entry.parent, kept)

    def write_atomically(self, entry: Path, blob: bytes | Writer) -> bool:
        """Write ``blob`` as ``entry`` atomically; False (and a problem noted) on failure.
        A ``Writer`` writes into the file itself: a large pickle is not held whole first."""
        # A unique temporary name in the entry's own directory: the rename stays on one
        # file system (so it is atomic) and two writers never share a temporary file.
        temporary = entry.with_name(f".{entry.name}.{os.getpid()}.{os.urandom(4).hex()}.tmp")
        try:
            self._make_subdirectory(entry.parent)
            descriptor = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
            try:
                with os.fdopen(descriptor, "wb") as stream:
                    if isinstance(blob, bytes):
                        stream.write(blob)
                    else:
                        blob(stream)
                os.replace(temporary, entry)
            except BaseException:
                _remove(temporary)
                raise
        except OSError as error:
            self._cannot_write(error)
            return False
        return True

    def flush(self) -> None:
        """Append the buffered lines of empty facts to their logs and the buffered records
        to their packs, each in one write."""
        pending, self._pending, self._pending_lines = self._pending, {}, 0
        for shard, shard_lines in sorted(pending.items()):
            lines = "".join(shard_lines).encode("ascii")
            written = self._append(_log_name(shard), lines)
            # A short write (a full disk) leaves a torn last line, which readers skip.
            self.stats.written += lines[:written].count(b"\n")
        pending_records, self._pending_records, self._pending_bytes = self._pending_records, {}, 0
        self._stored.clear()  # a worker process would otherwise hold all it extracted
        for shard, records in sorted(pending_records.items()):
            written = self._append(_pack_name(shard), b"".join(records))
            if written:
                self.stats.written += len(records)

    def _append(self, name: str, data: bytes) -> int:
        """Append ``data`` to ``name`` in one write; how many bytes were written."""
        try:
            # Non-blocking: a FIFO in its place fails the open rather than waits on it.
            flags = os.O_WRONLY | os.O_APPEND | os.O_CREAT | getattr(os, "O_NONBLOCK", 0)
            descriptor = os.open(os.path.join(self.directory, name), flags, 0o600)
            try:
                return os.write(descriptor, data)
            finally:
                os.close(descriptor)
        except OSError as error:
            self._cannot_write(error)
            return 0

    def finish(self) -> None:
        """End of the run: write what is buffered; and where a pack or a log this run
        read has outgrown its share of ``PACK_LIMIT`` and more than half that share of
        what the run read of it is what it did not look up, store or stand on (older
        versions of files, or other checkouts'), rewrite it with what it used and what
        was appended since the run read it (another run's, or its workers' before the
        run stood on them: new, not stale). A pack or log no run reads is not checked: a
        run after an edit reads the few it looks up in, and a workspace whose facts alone
        outgrow the limit would otherwise have its packs rewritten by every run."""
        self.flush()
        share = PACK_LIMIT // len(SHARDS)
        for shard, records in sorted(self._records.items()):
            if not self._may_have_outgrown(_pack_name(shard), share):
                continue
            used = {key: where for key, where in records.items() if key in self._used}
            used_bytes = sum(end - start + _RECORD_HEADER for start, end in used.values())
            tail = self._outgrown(_pack_name(shard), used_bytes, share)
            if tail is not None:
                pack = self._packs[shard]
                kept = [
                    pack[start - _RECORD_HEADER : end] for _, (start, end) in sorted(used.items())
                ]
                self.write_atomically(self.directory / _pack_name(shard), b"".join(kept) + tail)
        for shard, lines in sorted(self._empty.items()):
            if not self._may_have_outgrown(_log_name(shard), share):
                continue
            kept_lines = "".join(
                _log_line(key, language, generation)
                for key, (language, generation) in sorted(lines.items())
                if key in self._used
            ).encode("ascii")
            tail = self._outgrown(_log_name(shard), len(kept_lines), share)
            if tail is not None:
                self.write_atomically(self.directory / _log_name(shard), kept_lines + tail)
        self._let_go()

    def _let_go(self) -> None:
        """Forget what the run read of the packs and logs (their indexes, the keys it
        used: 27 MB at 81,000 files), and close them. The run's stores after ``finish``
        (a rebased graph's, whose pickling is that run's peak) look no facts up; a later
        run of the same process (the language server's) reads again what it looks up."""
        for stream in self._pack_files.values():
            if stream is not None:
                stream.close()
        for pack in self._packs.values():
            if isinstance(pack, mmap.mmap):
                pack.close()
        for read in (self._packs, self._pack_files, self._records, self._empty, self._read_as):
            read.clear()
        self._used.clear()

    def _may_have_outgrown(self, name: str, share: int) -> bool:
        """Whether this run read more than half ``share`` of the pack or log ``name``:
        else nothing it did not use can pass half the share, and what it used is not
        worked out (every log line of a first run formatted again)."""
        read = self._read_as.get(name)
        return read is not None and read.size > share // 2

    def _outgrown(self, name: str, used: int, share: int) -> bytes | None:
        """What was appended to the pack or log ``name`` since this run read it, where it
        is to be rewritten: past ``share`` and more than half of it what the run read of
        it and did not use (``used`` bytes of it used). None where it is not, or where
        another run rewrote it since (its inode)."""
        read = self._read_as.get(name)
        if read is None or read.size - used <= share // 2:
            return None
        tail = _appended_since(self.directory / name, read)
        return None if tail is None or read.size + len(tail) <= share else tail

    def writable(self) -> bool:
        """Create this run's directory once; False (and a problem noted) when impossible."""
        if self._writable is None:
            self._writable = self._open()
        return self._writable

    def _open(self) -> bool:
        directory = self.directory
        try:
            # exist_ok everywhere: another run may be creating the same directories.
            if _created(self.root, parents=True):  # not a folder the user had already
                _tag(self.root)
            _created(directory)
            # Also in a directory of this name made before tags were: the fingerprint in
            # its name says it is this version's.
            _tag(directory)
        except OSError as error:
            reason = error.strerror or str(error)
            self._problem(f"cache disabled: cannot create {directory}: {reason}")
            return False
        with contextlib.suppress(OSError):  # best effort: a read-only cache is still read
            os.utime(directory)  # "in use": keeps it from being pruned as stale
        _prune(self.root, keep=directory.name)
        return True

    def _make_subdirectory(self, subdirectory: Path) -> None:
        if subdirectory.name not in self._subdirectories:
            subdirectory.mkdir(mode=0o700, exist_ok=True)
            self._subdirectories.add(subdirectory.name)

    def _cannot_write(self, error: OSError) -> None:
        reason = error.strerror or str(error)
        self._problem(f"cannot write cache entries in {self.directory}: {reason}")

    def _problem(self, message: str) -> None:
        if message not in self.problems:  # said once, however many entries fail
            self.problems.append(message)


def _record(key: str, payload: bytes) -> bytes | None:
    """One record of the pack; None for a key that is not ``_KEY_BYTES`` ASCII digits."""
    if len(key) != _KEY_BYTES or not key.isascii():
        return None
    head = key.encode("ascii") + len(payload).to_bytes(_LENGTH_BYTES, "little")
    checksum = hashlib.blake2b(head + payload, digest_size=_CHECKSUM_BYTES).digest()
    return _RECORD + head + checksum + payload


class _Read(NamedTuple):
    """A pack or log as a run read it: which file (its inode), and its first ``size``
    bytes (a pack's, a log's whole lines)."""

    inode: int
    size: int


def _map_as(path: str) -> tuple[bytes | mmap.mmap, _Read | None, IO[bytes] | None]:
    """The pack, mapped, what was mapped (None: nothing), and the file as opened, where
    the platform reads a file at an offset (``_read_record``): a run reads the records it
    loads, not all of it (a run after an edit loads one file's facts or none from a 100
    MB pack at 8 copies of the benchmark's workspace). The mapping is of the file as
    opened: a pack another run rewrites (a rename over it) or appends to meanwhile leaves
    it as it was."""
    try:
        stream = open_regular(path)
    except OSError:
        return b"", None, None
    try:
        mapped = mmap.mmap(stream.fileno(), 0, access=mmap.ACCESS_READ)
        read = _Read(os.fstat(stream.fileno()).st_ino, len(mapped))
    except (OSError, ValueError):  # unreadable or empty: everything misses
        stream.close()
        return b"", None, None
    if not hasattr(os, "pread"):
        stream.close()
        return mapped, read, None
    return mapped, read, stream


def _read_record(
    file: IO[bytes] | None, pack: bytes | mmap.mmap, start: int, end: int
) -> FileFacts | None:
    """The facts of the record whose payload is ``pack[start:end]``, read from the pack's
    ``file`` where there is one: a page of a mapping that a load touches stays in the
    process's memory, with the pages the kernel maps around it (2 of each pack's 4 MB
    after a patch's 2,000 loads at 8 copies, 31 MB in all). None where the record is
    torn or fails its checksum."""
    first = start - _CHECKSUM_BYTES - _KEY_BYTES - _LENGTH_BYTES
    if file is None:
        record = pack[first:end]
    else:
        try:
            record = os.pread(file.fileno(), end - first, first)
        except OSError:
            return None
    if len(record) != end - first:
        return None
    at = start - first
    return _unpickle_facts(record, at) if _intact(record, at, len(record)) else None


def _appended_since(path: Path, read: _Read) -> bytes | None:
    """The bytes of the file at ``path`` past those a run ``read`` of it; None where it
    is another file now (rewritten since) or cannot be read."""
    try:
        with open_regular(path) as stream:
            if os.fstat(stream.fileno()).st_ino != read.inode:
                return None
            stream.seek(read.size)
            return stream.read()
    except OSError:
        return None


def _index(pack: bytes | mmap.mmap) -> dict[str, tuple[int, int]]:
    """Where each key's payload is in ``pack``: the last whole record of a key wins.

    A record whose end is the pack's or the next record's marker is whole: its checksum
    is verified when it is loaded (``_intact``), not here, where a run that loads one
    record of a 100 MB pack would hash all of it (0.19 s). Any other record is torn, or
    its length is damaged: it is indexed only if its checksum holds, and the next marker
    is searched for (a marker inside a payload fails its checksum in turn). A damaged
    record that looks whole is then a miss where it is loaded: extracted again, and
    appended, so the next run finds the new record.
    """
    found: dict[str, tuple[int, int]] = {}
    size = len(pack)
    # One header read per record, the marker with the key and the length: a re-run
    # indexes 60,000 records at 8 copies of the benchmark's workspace (0.11 s by slices).
    header = _HEADER.unpack_from
    marker = len(_RECORD)
    position = pack.find(_RECORD)
    released = 0
    while position >= 0:
        if position + _HEADER.size <= size:
            _, key, length = header(pack, position)
            start = position + _HEADER.size + _CHECKSUM_BYTES
            end = start + length
        else:  # a header torn at the end of the pack
            key, start = b"", size + 1
            end = start
        whole = end == size or pack[end : end + marker] == _RECORD
        if start <= end <= size and (whole or _intact(pack, start, end)):
            found[key.decode("ascii", errors="replace")] = (start, end)
            position = end if whole and end < size else pack.find(_RECORD, end)
        else:
            position = pack.find(_RECORD, position + 1)
        if position - released >= _RELEASED_EVERY:
            released = _released(pack, released, position)
    _released(pack, released, size, at_least=0)  # the rest: a pack is 4 MB at 8 copies
    return found


def _intact(pack: bytes | mmap.mmap, start: int, end: int) -> bool:
    """Whether the record whose payload is ``pack[start:end]`` holds its checksum."""
    checksum_start = start - _CHECKSUM_BYTES
    head = pack[checksum_start - _KEY_BYTES - _LENGTH_BYTES : checksum_start]
    checksum = pack[checksum_start:start]
    digest = hashlib.blake2b(head + pack[start:end], digest_size=_CHECKSUM_BYTES).digest()
    return digest == checksum


_RELEASED_EVERY = 8 * 1024 * 1024  # bytes of a mapped pack indexed between releases
# A record's head: the marker, the key, the payload's length in ``_LENGTH_BYTES`` (4,
# little-endian: "<I"); the checksum follows.
_HEADER = struct.Struct(f"<{len(_RECORD)}s{_KEY_BYTES}sI")


def _released(
    pack: bytes | mmap.mmap, released: int, position: int, *, at_least: int = _RELEASED_EVERY
) -> int:
    """Hand the pages of a mapped pack indexed since ``released`` back (they stay in the
    kernel's page cache, a later load faults them in again): indexing a 100 MB pack
    would otherwise hold all of it in the process's memory. Where the pack is bytes, or
    the platform has no ``madvise``, nothing; nor where less than ``at_least`` bytes
    were indexed since. How far is handed back now."""
    if position < 0:
        position = len(pack)
    if not isinstance(pack, mmap.mmap) or position - released < at_least:
        return released
    # To a page's start, but at the pack's end: its last page, partly the pack's, too.
    end = position if position == len(pack) else position - position % mmap.PAGESIZE
    if hasattr(pack, "madvise") and end > released:
        pack.madvise(mmap.MADV_DONTNEED, released, end - released)
    return end


def _unpickle_facts(payload: bytes, start: int = 0) -> FileFacts | None:
    facts = _unpickle(payload, start=start)
    return facts if isinstance(facts, FileFacts) else None


def _unpickle(
    payload: bytes, unpickler: type[pickle.Unpickler] | None = None, start: int = 0
) -> object | None:
    """The value of a payload (from ``start`` on), through the unpickler that builds only
    model values (or ``unpickler``)."""
    stream = io.BytesIO(payload)  # shares the bytes, where a slice or a view copies them
    stream.seek(start)
    try:
        value: object = (unpickler or _FactsUnpickler)(stream).load()
    except Exception:  # any malformed pickle: a miss, never a crash
        return None
    return value


def _size(path: Path) -> int:
    try:
        return path.stat().st_size
    except OSError:
        return 0


def _shard_of(key: str) -> str | None:
    """The shard a key's facts are kept in: its first hex digit (None: not a key)."""
    shard = key[:1]
    return shard if shard and shard in SHARDS else None


def _pack_name(shard: str) -> str:
    return f"facts-{shard}.pack"


def _log_name(shard: str) -> str:
    return f"empty-{shard}.log"


def _log_line(key: str, language: Language, generation: Generation) -> str:
    record = f"{key} {language.value} {generation.value}"
    return f"{record} {_line_checksum(record)}\n"


def _line_checksum(record: str) -> str:
    return hashlib.blake2b(record.encode("ascii"), digest_size=4).hexdigest()


_GENERATIONS = {str(generation.value): generation for generation in Generation}


def _read_log_as(path: str) -> tuple[dict[str, tuple[Language, Generation]], _Read | None]:
    """The keys of a log's lines and what each says, and what of it was read (None:
    nothing)."""
    try:
        with open_regular(path) as stream:
            data = stream.read()
            inode = os.fstat(stream.fileno()).st_ino
    except OSError:
        return {}, None
    found: dict[str, tuple[Language, Generation]] = {}
    # The part after the last line break is a line still being written, or a torn one.
    for raw in data.split(b"\n")[:-1]:
        try:
            key, language, generation, checksum = raw.decode("ascii").split(" ")
        except (UnicodeDecodeError, ValueError):
            continue
        record = f"{key} {language} {generation}"
        if (
            checksum == _line_checksum(record)
            and language in LANGUAGE_OF_VALUE
            and generation in _GENERATIONS
        ):
            found[key] = (LANGUAGE_OF_VALUE[language], _GENERATIONS[generation])
    return found, _Read(inode, data.rfind(b"\n") + 1)


def _encoded(value: object) -> Writer:
    """``value`` pickled behind the magic bytes and its checksum, into the file as it is
    pickled: neither the payload (7 MB for a replay at 77,000 files, 14 MB for a kept
    graph) nor a copy of it behind its header is held whole."""

    def write(stream: IO[bytes]) -> None:
        stream.write(_MAGIC + bytes(_CHECKSUM_BYTES))  # the checksum's place: written last
        digest = hashlib.blake2b(digest_size=_CHECKSUM_BYTES)
        model.dump(value, _Hashing(stream, digest))
        stream.seek(len(_MAGIC))
        stream.write(digest.digest())

    return write


class _Hashing:
    """Writes to ``stream``, hashing what it writes."""

    def __init__(self, stream: IO[bytes], digest: Any) -> None:
        self._stream = stream
        self._digest = digest

    def write(self, data: bytes) -> int:
        self._digest.update(data)
        return self._stream.write(data)


def _decode(blob: bytes, unpickler: type[pickle.Unpickler] | None = None) -> object | None:
    """What ``_encoded`` wrote; None for a blob that is truncated, corrupt or foreign."""
    header = len(_MAGIC) + _CHECKSUM_BYTES
    if len(blob) < header or not blob.startswith(_MAGIC):
        return None
    # Not sliced: the kept graph is 14 MB, and the copy was the peak of a run patching it.
    payload = memoryview(blob)[header:]
    if hashlib.blake2b(payload, digest_size=_CHECKSUM_BYTES).digest() != blob[len(_MAGIC) : header]:
        return None
    return _unpickle(blob, unpickler or _FactsUnpickler, start=header)


_MODEL_CLASSES = frozenset(
    name
    for name, value in vars(model).items()
    if isinstance(value, type) and value.__module__ == model.__name__
)


def _built_by(value: type, attribute: str) -> Any:
    """What the unpicklers build a class's instances with, by the name the pickle gives
    (``attribute`` of the class, else the class): a ``model.Compact`` is pickled as its
    fields' values and its rebuilder (``model.rebuilder``; as its class before); None
    for any other attribute."""
    compact = issubclass(value, model.Compact)
    if attribute and not (compact and attribute == model.REBUILT):
        return None
    return model.rebuilder(value) if compact else value


class BuiltinsUnpickler(pickle.Unpickler):
    """Builtins only (dicts, lists, tuples, strings, numbers): what the cache's own
    bookkeeping files hold (digests, kept keys, listings); any global is refused, so
    loading one builds nothing else."""

    def find_class(self, module: str, name: str) -> Any:
        raise pickle.UnpicklingError(f"{module}.{name} is not a builtin value")


class _FactsUnpickler(pickle.Unpickler):
    """Builds fact values and nothing else (see the module docstring)."""

    def find_class(self, module: str, name: str) -> Any:
        owner, _, attribute = name.partition(".")
        if module == model.__name__ and owner in _MODEL_CLASSES:
            found = _built_by(getattr(model, owner), attribute)
            if found is not None:
                return found
        if (module, name) == ("builtins", "getattr"):
            # How Python 3.11.0 to 3.11.4 (Debian 12's 3.11.2) pickle an enum member:
            # ``getattr(Language, "CPP")``. Only that: a member of a model enum.
            return _model_enum_member
        raise pickle.UnpicklingError(f"{module}.{name} is not a fact class")


class _GraphUnpickler(pickle.Unpickler):
    """Builds fact values and the graph's (``workspace.graph``, its parameters and
    service definitions): the data classes and enums those modules define, nothing else."""

    def find_class(self, module: str, name: str) -> Any:
        owner, _, attribute = name.partition(".")
        if module in _GRAPH_MODULES:
            value = getattr(sys.modules.get(module), owner, None)
            if (
                isinstance(value, type)
                and value.__module__ == module
                and (dataclasses.is_dataclass(value) or issubclass(value, enum.Enum))
                and (found := _built_by(value, attribute)) is not None
            ):
                return found
        if (module, name) == ("builtins", "getattr"):
            return _graph_enum_member
        raise pickle.UnpicklingError(f"{module}.{name} is not a graph class")


# Imported by the time a graph is loaded: the engine builds graphs from them.
_GRAPH_MODULES = frozenset(
    {
        model.__name__,
        "roslint_names.workspace.graph",
        "roslint_names.workspace.parameters",
        "roslint_names.workspace.interfaces",
        "roslint_names.workspace.index",  # the packages a kept graph was built with
        "roslint_names.workspace.launch_parts",
    }
)


def _graph_enum_member(owner: object, name: str) -> enum.Enum:
    """``getattr(owner, name)`` for a member of an enum of the graph's modules."""
    if isinstance(owner, type) and owner.__module__ in _GRAPH_MODULES:
        return _model_enum_member(owner, name, owner.__module__)
    raise pickle.UnpicklingError(f"getattr({owner!r}, {name!r}) is no member of a graph enum")


def _model_enum_member(owner: object, name: str, module: str = model.__name__) -> enum.Enum:
    """``getattr(owner, name)`` where ``owner`` is an enum of the model and ``name`` one of
    its members; an unpickling error for anything else."""
    if (
        isinstance(owner, type)
        and issubclass(owner, enum.Enum)
        and owner.__module__ == module
        and isinstance(name, str)
        and name in owner.__members__
    ):
        return owner.__members__[name]
    raise pickle.UnpicklingError(f"getattr({owner!r}, {name!r}) is no member of a fact enum")


_FINGERPRINT: str | None = None


def run_fingerprint() -> str:
    """A hash of everything that is the same for every file of a run; computed once."""
    global _FINGERPRINT  # noqa: PLW0603 - a per-process memo of a pure function
    if _FINGERPRINT is None:
        digest = hashlib.blake2b(digest_size=8)
        header = f"{FORMAT_VERSION}\0{__version__}\0{sys.version_info[:2]}\0"
        digest.update(header.encode())
        package = Path(__file__).parent
        for source, content in _extractor_sources(package).items():
            digest.update(source.relative_to(package).as_posix().encode() + b"\0" + content)
        digest.update(_parser_stamp())
        _FINGERPRINT = digest.hexdigest()
    return _FINGERPRINT


_CODE_FINGERPRINTS: dict[tuple[str, ...], str] = {}


def code_fingerprint(modules: Iterable[str] = ()) -> str:
    """A hash of all of the tool's code, of ``modules`` (plugin rules' modules, by name)
    and of the parsers: what a whole run's result depends on besides its inputs."""
    memo_key = tuple(sorted(modules))
    if memo_key not in _CODE_FINGERPRINTS:
        digest = hashlib.blake2b(digest_size=16)
        digest.update(run_fingerprint().encode())  # the format, the parsers, Python
        package = Path(__file__).parent
        sources = {*package.rglob("*.py")}
        for name in memo_key:
            origin = getattr(sys.modules.get(name), "__file__", None)
            if origin:
                sources.add(Path(origin))
        for source in sorted(sources):
            try:
                content = source.read_bytes()
            except OSError:
                content = b"\xff"
            digest.update(b"%s\0%d\0" % (os.fsencode(source), len(content)) + content)
        _CODE_FINGERPRINTS[memo_key] = digest.hexdigest()
    return _CODE_FINGERPRINTS[memo_key]


def _extractor_sources(package: Path) -> dict[Path, bytes]:
    """The extractors' code and every package module it imports, transitively, by path.

    Following the imports rather than listing modules means a helper module the extractors
    start to use (``lines.py``, say) is fingerprinted without anyone remembering to.
    """
    pending: list[Path] = []
    for name in _EXTRACTOR_SOURCES:
        path = package / name
        pending.extend(sorted(path.rglob("*.py")) if path.is_dir() else [path])
    found: dict[Path, bytes] = {}
    while pending:
        path = pending.pop(0)
        if path in found:
            continue
        try:
            found[path] = content = path.read_bytes()
        except OSError:
            found[path] = b"\xff"  # absent: still a state of the code worth telling apart
            continue
        for match in _PACKAGE_IMPORT.finditer(content):
            module = next(group for group in match.groups() if group).decode("ascii")
            if (package / f"{module}.py").is_file():
                pending.append(package / f"{module}.py")
    return dict(sorted(found.items()))


def _parser_stamp() -> bytes:
    """Names, sizes and times of the parser packages' files: changes when one is upgraded.

    Reading their versions through ``importlib.metadata`` costs more than a one-file run
    may spend, and importing them would defeat the lazy imports; ``find_spec`` does neither.
    """
    from importlib.util import find_spec

    stamp: list[str] = []
    for package in _PARSER_PACKAGES:
        try:
            spec = find_spec(package)
        except (ImportError, ValueError):
            spec = None
        locations = list(spec.submodule_search_locations or []) if spec else []
        stamp.append(f"{package}:{spec.origin if spec else None}")
        for location in locations:
            try:
                entries = sorted(os.scandir(location), key=lambda entry: entry.name)
                for entry in entries:
                    if entry.is_file():
                        status = entry.stat()
                        stamp.append(f"{entry.name}:{status.st_size}:{status.st_mtime_ns}")
            except OSError:
                stamp.append("?")
    return "\n".join(stamp).encode("utf-8", errors="surrogateescape")


def _created(directory: Path, parents: bool = False) -> bool:
    """Make ``directory`` (0700); whether this call made it rather than finding it."""
    try:
        directory.mkdir(parents=parents, mode=0o700)
    except FileExistsError:
        if not directory.is_dir():
            raise
        return False
    return True


def _tag(directory: Path) -> None:
    """Mark ``directory`` as this cache's: backup tools skip it, and pruning may delete
    it (``_is_own``)."""
    tag = directory / _TAG_NAME
    if not tag.exists():
        tag.write_text(_CACHEDIR_TAG, encoding="ascii")


def _is_own(directory: str) -> bool:
    """Whether ``directory`` holds the tag this cache writes into what it creates."""
    try:
        with open_regular(os.path.join(directory, _TAG_NAME)) as stream:
            return stream.read(len(_CACHEDIR_TAG) + 1) == _CACHEDIR_TAG.encode("ascii")
    except OSError:
        return False


def _prune(root: Path, keep: str) -> None:
    """Delete other versions' entry directories that no run has used for a day; only
    those that carry this cache's tag, never a folder it did not create."""
    now = time.time()
    try:
        candidates = [
            entry
            for entry in os.scandir(root)
            if entry.name.startswith(_PREFIX)
            and entry.name != keep
            and entry.is_dir(follow_symlinks=False)
        ]
        stale = [
            entry.path
            for entry in candidates
            if now - entry.stat(follow_symlinks=False).st_mtime > STALE_AFTER_SECONDS
            and _is_own(entry.path)
        ]
    except OSError:
        return
    if stale:
        import shutil

        for path in stale:
            shutil.rmtree(path, ignore_errors=True)


def keep_newest(directory: Path, count: int) -> None:
    """Delete all but the ``count`` most recently modified entries of ``directory``."""
    try:
        # Not the dot-named temporary files: a writer may be about to rename its own.
        entries = [
            entry
            for entry in os.scandir(directory)
            if not entry.name.startswith(".") and entry.is_file()
        ]
        if len(entries) <= count:
            return
        entries.sort(key=lambda entry: entry.stat().st_mtime_ns, reverse=True)
    except OSError:
        return
    for entry in entries[count:]:
        _remove(Path(entry.path))


def _remove(path: Path) -> None:
    with contextlib.suppress(OSError):
        path.unlink()
