"""Read a file to lint, or say why not: too large, binary, or unreadable."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

Read = tuple["bytes | None", str, "str | None"]  # the bytes, why unreadable, why skipped

_BINARY_SNIFF = 8000
_WIDE_BOMS = (b"\xff\xfe", b"\xfe\xff")  # UTF-16 LE and BE (UTF-32 LE starts like LE)
BINARY = "binary (NUL bytes)"


def read_file(path: Path, max_size: int) -> Read:
    """The file's bytes, else why it cannot be read; and why it is skipped, if it is.

    Files above ``max_size`` bytes are generated or vendored: skipped before they are read.
    So are binary files, by git's test (a NUL in the first 8,000 bytes) unless a UTF-16
    or UTF-32 byte order mark says the NULs are text.
    """
    # One open, then the size of what was opened: this runs for every file of every run.
    try:
        with open(path, "rb") as stream:
            size = os.fstat(stream.fileno()).st_size
            if size > max_size:
                return None, "", too_large(size, max_size)
            data = stream.read()
    except OSError as error:
        return None, error.strerror or str(error), None
    if is_binary(data):
        return None, "", BINARY
    return data, "", None


def content_digest(data: bytes) -> str:
    """What a file's bytes are keyed by."""
    return hashlib.blake2b(data, digest_size=20).hexdigest()


def is_binary(data: bytes) -> bool:
    return b"\0" in data[:_BINARY_SNIFF] and not data.startswith(_WIDE_BOMS)


def too_large(size: int, max_size: int) -> str:
    """Why a file of ``size`` bytes is skipped."""
    return f"{_megabytes(size)}, above max-file-size ({_megabytes(max_size)})"


def _megabytes(size: int) -> str:
    return f"{size / (1024 * 1024):.1f} MiB"
