"""Read a file to lint, or say why not: too large, binary, unreadable, or not a file.

Every file the tool reads is opened through ``open_regular``: a FIFO, socket or device
met in a tree or named by the user is refused with a reason, never opened for a read
that would block the run forever (a FIFO without a writer) or act on a device.
"""

from __future__ import annotations

import codecs
import errno
import hashlib
import os
import stat
import time
from array import array
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import BinaryIO, NamedTuple, overload

Read = tuple["bytes | None", str, "str | None"]  # the bytes, why unreadable, why skipped

_BINARY_SNIFF = 8000
BINARY = "binary (NUL bytes)"
# Byte order marks and the codecs that read them (dropping the mark), UTF-32 LE before
# UTF-16 LE, whose mark is its prefix. Editors on Windows write UTF-16 with a mark.
BOMS = (
    (codecs.BOM_UTF32_LE, "utf-32"),
    (codecs.BOM_UTF32_BE, "utf-32"),
    (codecs.BOM_UTF8, "utf-8-sig"),
    (codecs.BOM_UTF16_LE, "utf-16"),
    (codecs.BOM_UTF16_BE, "utf-16"),
)
WIDE_ENCODINGS = frozenset({"utf-16", "utf-32"})


class NotRegularFileError(OSError):
    """A path that is a FIFO, socket, device or directory where a file was expected;
    ``strerror`` says which (``not a regular file (a FIFO)``)."""

    def __init__(self, path: str | os.PathLike[str], mode: int) -> None:
        super().__init__(errno.EINVAL, f"not a regular file ({file_kind(mode)})", os.fspath(path))


_KINDS = (
    (stat.S_ISFIFO, "a FIFO"),
    (stat.S_ISSOCK, "a socket"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISDIR, "a directory"),
)


# Non-blocking only matters for the open: reads of a regular file never wait on it.
_READ_FLAGS = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)


def file_kind(mode: int) -> str:
    """What a status's mode says the path is, for messages: ``a FIFO``, ``a socket``..."""
    return next((kind for test, kind in _KINDS if test(mode)), "an unknown kind of file")


def open_regular(path: str | os.PathLike[str]) -> BinaryIO:
    """``path`` opened for reading in binary, if it is a regular file (links followed);
    anything else raises ``NotRegularFileError``.

    The open does not block (a FIFO would wait for a writer that may never come), and the
    status is taken on the open descriptor, so no file swapped in between gets through.
    No status is taken before: this runs for every file of every run, and the walk and
    the paths named (``discover``) only hand over regular files, so that a device is
    never opened.
    """
    descriptor = os.open(path, _READ_FLAGS)
    try:
        mode = os.fstat(descriptor).st_mode
        if not stat.S_ISREG(mode):
            raise NotRegularFileError(path, mode)
        return os.fdopen(descriptor, "rb")
    except BaseException:
        os.close(descriptor)
        raise


def read_regular(path: str | os.PathLike[str], max_size: int) -> tuple[bytes | None, int]:
    """The bytes of the regular file at ``path`` (as ``open_regular`` opens it), and its
    size; None for the bytes of a file larger than ``max_size``, which is not read.

    On the descriptor, without a file object: a cold run reads every file of the
    workspace twice (to key it, in the main process; to extract it, in a worker), and
    the buffered reader and its second status cost a third of each read (0.04 s of
    realws's 9,663 files)."""
    descriptor = os.open(path, _READ_FLAGS)
    try:
        found = os.fstat(descriptor)
        if not stat.S_ISREG(found.st_mode):
            raise NotRegularFileError(path, found.st_mode)
        if found.st_size > max_size:
            return None, found.st_size
        # Until the end: a file grown since its status was taken is read whole, as it is.
        chunks = []
        wanted = found.st_size + 1
        while chunk := os.read(descriptor, wanted):
            chunks.append(chunk)
            wanted = _READ_CHUNK
        return (chunks[0] if len(chunks) == 1 else b"".join(chunks)), found.st_size
    finally:
        os.close(descriptor)


_READ_CHUNK = 1 << 16


def read_file(path: str | Path, max_size: int) -> Read:
    """The file's bytes, else why it cannot be read; and why it is skipped, if it is.

    Files above ``max_size`` bytes are generated or vendored: skipped before they are read.
    So are binary files, by git's test (a NUL in the first 8,000 bytes) unless a UTF-16
    or UTF-32 byte order mark says the NULs are text; the engine reports a source that is
    not text (RN001) rather than passing over it.
    """
    # One open, then the size of what was opened: this runs for every file of every run.
    try:
        data, size = read_regular(path, max_size)
    except OSError as error:
        return None, error.strerror or str(error), None
    if data is None:
        return None, "", too_large(size, max_size)
    if is_binary(data):
        return None, "", BINARY
    return data, "", None


# Far above any real .srv: a larger file is no definition worth reading whole. Not the
# ``max-file-size`` of the files linted: the definitions are read, not linted.
MAX_DEFINITION_BYTES = 1 << 20

Status = tuple[int, int, int, int]  # size, mtime_ns, ctime_ns, inode

# A status taken within this of a change may hide another change made in the same clock
# tick (git's "racily clean" entries): such a status proves nothing yet. Measured on the
# change time as well as the modification time: tools set the latter back (``cp -p``,
# ``rsync -t``, ``tar``), never the former, and a file system that keeps whole seconds
# keeps them for both.
RACY_NANOSECONDS = 2_000_000_000  # coarser than any file system's time stamps


def is_racy(mtime_ns: int, ctime_ns: int, now_ns: int) -> bool:
    """Whether a status with these times, taken at ``now_ns`` or later, may hide a change."""
    return max(mtime_ns, ctime_ns) >= racy_from(now_ns)


def racy_from(now_ns: int) -> int:
    """The earliest time a status taken at ``now_ns`` or later may hide a change after:
    ``is_racy`` where either time is at or past it."""
    return now_ns - RACY_NANOSECONDS


def status_of(path: str | Path) -> Status | None:
    """What says a file or directory changed without reading it (git's index keeps the
    same): None when it cannot be taken."""
    try:
        found = os.stat(path)
    except OSError:
        return None
    return status_from(found)


def statuses_of(paths: Iterable[str]) -> Statuses:
    """``status_of`` each of ``paths``, in one loop: a re-run takes 80,000 at 8 copies
    of the benchmark's workspace, and two calls each cost 0.03 s of it."""
    values = array("q")
    add = values.extend
    take = os.stat
    for path in paths:
        try:
            found = take(path)
        except OSError:
            add(_NO_STATUS)
            continue
        add((found.st_size, found.st_mtime_ns, found.st_ctime_ns, found.st_ino))
    return Statuses(values)


# A file's place in ``Statuses`` where it has no status (a size no file has), or where
# one was kept as changed: too recent to vouch for the file (``unchanged``)
_NO_STATUS = (-1, 0, 0, 0)
_CHANGED = (-2, 0, 0, 0)
_FIELDS = len(_NO_STATUS)
_BLOCK = 256  # files compared at once where two runs' statuses differ somewhere


class Statuses(Sequence["Status | bool | None"]):
    """The statuses of many files, packed: four integers each in one array, where a
    tuple each held 17 MB for 89,000 files at 8 copies of the benchmark's workspace
    through a run, and pickling them cost 0.03 s and loading them 0.025 s. A file's is
    its ``Status``, None (it had none) or False (kept as changed: ``unchanged``)."""

    __slots__ = ("_values",)

    def __init__(self, values: array[int] | None = None) -> None:
        self._values = array("q") if values is None else values

    @classmethod
    def of(cls, statuses: Iterable[Status | bool | None]) -> Statuses:
        values = array("q")
        for status in statuses:
            if status is None or isinstance(status, bool):
                values.extend(_NO_STATUS if status is None else _CHANGED)
            else:
                values.extend(status)
        return cls(values)

    @classmethod
    def from_bytes(cls, data: bytes) -> Statuses | None:
        """What ``to_bytes`` wrote, on a machine of the same byte order; None for bytes
        it did not write."""
        values = array("q")
        if len(data) % (values.itemsize * _FIELDS):
            return None
        values.frombytes(data)
        return cls(values)

    def to_bytes(self) -> bytes:
        return self._values.tobytes()

    def __len__(self) -> int:
        return len(self._values) // _FIELDS

    @overload
    def __getitem__(self, index: int) -> Status | bool | None: ...

    @overload
    def __getitem__(self, index: slice) -> Statuses: ...

    def __getitem__(self, index: int | slice) -> Status | bool | Statuses | None:
        if isinstance(index, slice):
            start, stop, step = index.indices(len(self))
            if step != 1:
                raise ValueError("statuses are sliced in steps of one")
            return Statuses(self._values[start * _FIELDS : max(start, stop) * _FIELDS])
        if index < 0:
            index += len(self)
        if not 0 <= index < len(self):
            raise IndexError(index)
        at = index * _FIELDS
        found = self._values[at : at + _FIELDS]
        size = found[0]
        return None if size == -1 else False if size == -2 else (size, found[1], found[2], found[3])

    def __iter__(self) -> Iterator[Status | bool | None]:
        values = self._values
        for at in range(0, len(values), _FIELDS):
            size = values[at]
            if size >= 0:
                yield (size, values[at + 1], values[at + 2], values[at + 3])
            else:
                yield None if size == -1 else False

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Statuses):
            return self._values == other._values
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]

    def sizes(self) -> list[int]:
        """Each file's size, 0 where it has no status."""
        return [max(size, 0) for size in self._values[::_FIELDS]]

    def unvouched(self, kept: Statuses, count: int) -> Iterator[int]:
        """The indices, in order, of the first ``count`` files that have no status or
        another than ``kept`` holds: blocks of files compared at once, each file of a
        block that differs or holds a file without one."""
        mine, theirs = self._values, kept._values
        width, end = _BLOCK * _FIELDS, min(count, len(self)) * _FIELDS
        for start in range(0, end, width):
            stop = min(start + width, end)
            if mine[start:stop] == theirs[start:stop] and -1 not in mine[start:stop:_FIELDS]:
                continue
            for at in range(start, stop, _FIELDS):
                if mine[at] == -1 or mine[at : at + _FIELDS] != theirs[at : at + _FIELDS]:
                    yield at // _FIELDS

    def taking(self, indices: Iterable[int]) -> Statuses:
        """The statuses at ``indices``, in their order; None for -1."""
        values, mine = array("q"), self._values
        for index in indices:
            values.extend(
                _NO_STATUS if index < 0 else mine[index * _FIELDS : (index + 1) * _FIELDS]
            )
        return Statuses(values)

    def replaced(self, statuses: Mapping[int, Status | None]) -> Statuses:
        """These statuses, those at the indices of ``statuses`` replaced."""
        values = array("q", self._values)
        for index, status in statuses.items():
            at = index * _FIELDS
            values[at : at + _FIELDS] = array("q", _NO_STATUS if status is None else status)
        return Statuses(values)

    def changed_from(self, recent: int) -> Statuses:
        """These statuses, each whose modification or change time is ``recent`` or
        later kept as changed (False: ``unchanged``, git's racily clean entries)."""
        values = self._values
        latest = max(values[1::_FIELDS], default=0), max(values[2::_FIELDS], default=0)
        if max(latest) < recent:
            return Statuses(array("q", values))
        kept = array("q", values)
        for at in range(0, len(values), _FIELDS):
            if values[at] >= 0 and (values[at + 1] >= recent or values[at + 2] >= recent):
                kept[at : at + _FIELDS] = array("q", _CHANGED)
        return Statuses(kept)

    def __repr__(self) -> str:
        return f"Statuses({list(self)!r})"


class Taken(NamedTuple):
    """What reading a file found, to key it by (``digests``, ``run_inputs``), where the
    process that read it is not the one that keys it (a worker's, for a first run)."""

    status: Status | None  # taken before the bytes were read
    content: str | None  # the bytes' digest; None where they were not read
    error: str  # why they could not be, else ""
    skip: str | None  # why they are skipped (too large, binary), as ``read_file`` says
    racy: bool  # the status was taken too soon after a change to vouch for the bytes


class Untaken:
    """A status not taken yet (None is one: the file's that cannot be looked at)."""


UNTAKEN = Untaken()


def taken(
    path: str | Path, max_size: int, status: Status | Untaken | None = UNTAKEN
) -> tuple[Taken, bytes | None]:
    """Read ``path`` as a run keys it: its status first (``status``, where the caller
    took it already), then its bytes (``read_file``), their digest, and whether the status
    can vouch for them (``is_racy``, as of the read: a change in between shows as a
    status the next run does not find)."""
    if isinstance(status, Untaken):
        status = status_of(path)
    data, error, skip = read_file(path, max_size)
    content = None if data is None else content_digest(data)
    racy = status is None or is_racy(status[1], status[2], time.time_ns())
    return Taken(status, content, error, skip, racy), data


def status_from(found: os.stat_result) -> Status:
    return found.st_size, found.st_mtime_ns, found.st_ctime_ns, found.st_ino


def content_digest(data: bytes) -> str:
    """What a file's bytes are keyed by."""
    return hashlib.blake2b(data, digest_size=20).hexdigest()


def is_binary(data: bytes) -> bool:
    return b"\0" in data[:_BINARY_SNIFF] and bom_encoding(data) not in WIDE_ENCODINGS


def decode_for_display(data: bytes) -> str:
    """Text for suppression scanning, source excerpts and searches; never fails."""
    return data.decode(bom_encoding(data) or "utf-8", errors="replace")


def bom_encoding(data: bytes) -> str | None:
    """The codec a byte order mark at the start of ``data`` announces, if any."""
    for bom, codec in BOMS:
        if data.startswith(bom):
            return codec
    return None


def too_large(size: int, max_size: int) -> str:
    """Why a file of ``size`` bytes is skipped."""
    return f"{_megabytes(size)}, above max-file-size ({_megabytes(max_size)})"


def _megabytes(size: int) -> str:
    return f"{size / (1024 * 1024):.1f} MiB"
