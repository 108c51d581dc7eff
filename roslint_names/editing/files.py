"""The one path by which the tool writes into the user's tree or beside it.

Fixes, renames, suppression comments, baselines and ``--output`` reports are all written
here, so that what is promised holds for every one of them:

- **Atomic**: the new bytes go to a temporary file in the same directory, flushed and
  fsynced, with the original's mode (and owner, where that may be set), which then
  replaces the file with ``os.replace``. A kill at any moment leaves each file whole,
  old or new, never short.
- **Only onto the bytes an edit was computed from**: ``Snapshot`` remembers each file's
  content as the run first read it; a change carries the bytes it was computed from, and
  the file must still hold exactly them when it is replaced (checked under a lock that
  other runs of this tool take too), else nothing is written: ``changed since it was
  read; run again``. Nothing is ever spliced into bytes it was not computed from.
- **All or nothing across files**: ``replace_all`` checks every file first (writable,
  unchanged, not a link leading outside the linted paths), writes every temporary file,
  and only then replaces them; a replace that fails puts back the files already replaced.
- **Errors name the file and the reason**, and say what was changed (nothing, as a rule).
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import time
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

from ..errors import UserError
from ..reading import content_digest, open_regular

LOCK_WAIT_SECONDS = 10.0  # another run of this tool writing the same files
TEMPORARY_SUFFIX = ".roslint-names.tmp"


class WriteError(UserError):
    """A write refused or failed; the message names the file, the reason and what changed."""


@dataclass(frozen=True)
class Change:
    """One file's new bytes, and the bytes they were computed from."""

    display: str  # the path as reports show it, relative to the working directory
    before: bytes
    after: bytes


class Snapshot:
    """The bytes of files as the run first read them.

    ``remember`` reads files before the run extracts them; ``read`` gives the bytes to
    compute an edit from, or None with the reason when the file cannot be read or is no
    longer what the run first saw (edited while the run went on)."""

    def __init__(self, cwd: Path, roots: Sequence[Path]) -> None:
        self.cwd = cwd
        self.roots = tuple(roots)
        self._digests: dict[str, str | None] = {}

    def remember(self, displays: Iterable[str]) -> None:
        for display in displays:
            if display not in self._digests:
                data, _ = read_regular(self.cwd / display)
                self._digests[display] = None if data is None else content_digest(data)

    def read(self, display: str) -> tuple[bytes | None, str]:
        """The file's bytes and "", or None and why they may not be edited."""
        data, why = read_regular(self.cwd / display)
        if data is None:
            return None, f"cannot read it: {why}"
        now = content_digest(data)
        if self._digests.setdefault(display, now) != now:
            return None, "changed since it was read; run again"
        return data, ""

    def for_edit(self, display: str) -> tuple[bytes | None, str]:
        """As ``read``, for a file to be written: None and why when it may not be."""
        target, why = writable_target(display, self.cwd, self.roots)
        return (None, why) if target is None else self.read(display)

    def replace_all(self, changes: Sequence[Change]) -> None:
        replace_all(changes, cwd=self.cwd, roots=self.roots)


def read_regular(path: Path) -> tuple[bytes | None, str]:
    """A regular file's bytes, or None and why not; never blocks on a FIFO or a device."""
    try:
        with open_regular(path) as stream:
            return stream.read(), ""
    except OSError as error:
        return None, _reason(error)


def replace_all(changes: Sequence[Change], *, cwd: Path, roots: Sequence[Path]) -> None:
    """Write every change or none. ``roots``: the linted paths; a file whose real path
    lies outside them (reached through a link) is read but never written."""
    if not changes:
        return
    targets = [_target(change, cwd, roots) for change in changes]
    if len(set(targets)) < len(targets):
        same = sorted(
            c.display for t, c in zip(targets, changes, strict=True) if targets.count(t) > 1
        )
        raise WriteError(
            f"not writing {', '.join(same)}: one file under two names; nothing was changed"
        )
    with _locked(sorted(zip(targets, changes, strict=True), key=lambda pair: pair[0])):
        for target, change in zip(targets, changes, strict=True):
            _check_unchanged(target, change)
        temporaries: list[str] = []
        try:
            for target, change in zip(targets, changes, strict=True):
                temporaries.append(_temporary(target, change))
        except BaseException as error:  # Ctrl-C too: no temporary is left beside a source
            _remove(temporaries)
            if not isinstance(error, OSError):
                raise
            failed = changes[len(temporaries)].display
            raise WriteError(f"{_failure(failed, error)}: nothing was changed") from error
        _replace_in_turn(targets, temporaries, changes)
    for directory in sorted({os.path.dirname(target) for target in targets}):
        _sync_directory(directory)


def write_new(path: Path, data: bytes, what: str) -> None:
    """A report or a baseline at ``path``, atomically; ``what`` names it in errors. A
    path that is a stream (``/dev/stdout``, a FIFO) is written as one; a link is
    followed, so that the link stays."""
    try:
        target = os.path.realpath(path)
        try:
            mode: int | None = os.stat(target).st_mode
        except FileNotFoundError:
            mode = None
        if mode is not None and not stat.S_ISREG(mode):
            if stat.S_ISDIR(mode):
                raise WriteError(f"cannot write {what} {path}: it is a directory")
            with open(target, "wb") as stream:
                stream.write(data)
            return
        os.makedirs(os.path.dirname(target) or ".", exist_ok=True)
        temporary = _temporary_file(target, data, mode if mode is not None else _default_mode())
        try:
            os.replace(temporary, target)
        except OSError:
            _remove([temporary])
            raise
    except OSError as error:
        raise WriteError(f"cannot write {what} {path}: {_reason(error)}") from error


def _target(change: Change, cwd: Path, roots: Sequence[Path]) -> str:
    """The real path a change is written to, after the checks that need no lock."""
    target, why = writable_target(change.display, cwd, roots)
    if target is None:
        raise WriteError(f"not writing {change.display}: {why}; nothing was changed")
    return target


def writable_target(display: str, cwd: Path, roots: Sequence[Path]) -> tuple[str | None, str]:
    """The real path the file ``display`` would be written at, or None and why it may
    not be: a link leading outside ``roots`` (the linted paths), not a regular file,
    read-only (its mode says so, even to root), or in a directory that is not writable
    (the new file is written beside the old one)."""
    target = os.path.realpath(os.path.join(cwd, display))
    if not any(_within(target, root) for root in roots):
        return None, f"it is a link to {target}, outside the linted paths"
    try:
        status = os.stat(target)
    except OSError as error:
        return None, _reason(error)
    if not stat.S_ISREG(status.st_mode):
        return None, "not a regular file"
    if status.st_mode & 0o222 == 0 or not os.access(target, os.W_OK):
        return None, "permission denied (the file is read-only)"
    if not os.access(os.path.dirname(target), os.W_OK | os.X_OK):
        return None, (
            "permission denied on its directory (the new file is written beside the old "
            "one, then put in its place)"
        )
    return target, ""


def _within(target: str, root: Path) -> bool:
    real_root = os.path.realpath(root)
    if target == real_root:
        return True
    return target.startswith(real_root.rstrip(os.sep) + os.sep)


@contextlib.contextmanager
def _locked(ordered: Sequence[tuple[str, Change]]) -> Iterator[None]:
    """Every target locked, in path order (two runs never wait on each other in a
    circle). The lock is on the file as it is now: a run that replaced it meanwhile
    leaves a new file, which ``_check_unchanged`` then sees."""
    try:
        import fcntl
    except ImportError:  # no advisory locks (Windows): the digest check still stands
        yield
        return
    held: list[int] = []
    try:
        for target, change in ordered:
            try:
                descriptor = os.open(target, os.O_RDONLY | os.O_NONBLOCK)
            except OSError as error:
                raise WriteError(
                    f"{_failure(change.display, error)}: nothing was changed"
                ) from error
            held.append(descriptor)
            deadline = time.monotonic() + LOCK_WAIT_SECONDS
            while True:
                try:
                    fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except OSError as error:
                    if error.errno not in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK):
                        break  # a file system without locks: the digest check still stands
                    if time.monotonic() > deadline:
                        raise WriteError(
                            f"not writing {change.display}: another run is writing it; "
                            "nothing was changed"
                        ) from error
                    time.sleep(0.05)
        yield
    finally:
        for descriptor in held:
            os.close(descriptor)  # closing releases the lock


def _check_unchanged(target: str, change: Change) -> None:
    data, why = read_regular(Path(target))
    if data is None:
        raise WriteError(
            f"not writing {change.display}: cannot read it: {why}; nothing was changed"
        )
    if data != change.before:
        raise WriteError(
            f"not writing {change.display}: changed since it was read; run again "
            "(nothing was changed)"
        )


def _temporary(target: str, change: Change) -> str:
    status = os.stat(target)
    return _temporary_file(target, change.after, status.st_mode, status)


def _temporary_file(
    target: str, data: bytes, mode: int, owner: os.stat_result | None = None
) -> str:
    """A new file beside ``target`` holding ``data``, on disk (fsynced), with ``mode``."""
    import tempfile

    directory, name = os.path.split(target)
    descriptor, temporary = tempfile.mkstemp(
        prefix=f".{name}.", suffix=TEMPORARY_SUFFIX, dir=directory or "."
    )
    try:
        with os.fdopen(descriptor, "wb") as stream:
            stream.write(data)
            stream.flush()
            os.fchmod(stream.fileno(), stat.S_IMODE(mode))
            if owner is not None and hasattr(os, "fchown"):
                with contextlib.suppress(OSError):  # only root may give a file away
                    os.fchown(stream.fileno(), owner.st_uid, owner.st_gid)
            os.fsync(stream.fileno())
    except BaseException:
        _remove([temporary])
        raise
    return temporary


def _replace_in_turn(
    targets: Sequence[str], temporaries: Sequence[str], changes: Sequence[Change]
) -> None:
    """Each temporary file into its target's place; on a failure, the targets already
    replaced are put back as they were, and the error says what is left."""
    for index, (target, temporary) in enumerate(zip(targets, temporaries, strict=True)):
        try:
            os.replace(temporary, target)
        except BaseException as error:  # Ctrl-C too: no run ends with half a fix written
            _remove(temporaries[index:])
            lost = _put_back(targets[:index], changes[:index])
            if not isinstance(error, OSError):
                raise
            message = _failure(changes[index].display, error)
            if lost:
                raise WriteError(
                    f"{message}; could not put back {', '.join(lost)}, which hold the fix"
                ) from error
            raise WriteError(f"{message}: nothing was changed") from error


def _put_back(targets: Sequence[str], changes: Sequence[Change]) -> list[str]:
    """The files replaced before a failure, as they were; those that could not be."""
    lost: list[str] = []
    for target, change in zip(targets, changes, strict=True):
        undo = Change(change.display, change.after, change.before)
        try:
            os.replace(_temporary(target, undo), target)
        except OSError:
            lost.append(change.display)
    return lost


def _remove(paths: Iterable[str]) -> None:
    for path in paths:
        with contextlib.suppress(OSError):
            os.unlink(path)


def _sync_directory(directory: str) -> None:
    """The renames themselves on disk (POSIX: a directory's entries are its data)."""
    try:
        descriptor = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(descriptor)
    except OSError:
        pass  # not every file system syncs directories; the replaces are done
    finally:
        os.close(descriptor)


def _default_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def _failure(display: str, error: OSError) -> str:
    if error.errno == errno.ENOSPC:
        return f"no space left on device writing {display}"
    return f"cannot write {display}: {_reason(error)}"


def _reason(error: OSError) -> str:
    """``Permission denied`` as ``permission denied``: the middle of a sentence."""
    text = error.strerror or str(error)
    return text[:1].lower() + text[1:]
