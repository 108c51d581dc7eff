"""Read a file to lint, or say why not: too large, binary, or unreadable."""

from __future__ import annotations

import codecs
import hashlib
import os
from pathlib import Path

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


def read_file(path: Path, max_size: int) -> Read:
    """The file's bytes, else why it cannot be read; and why it is skipped, if it is.

    Files above ``max_size`` bytes are generated or vendored: skipped before they are read.
    So are binary files, by git's test (a NUL in the first 8,000 bytes) unless a UTF-16
    or UTF-32 byte order mark says the NULs are text; the engine reports a source that is
    not text (RN001) rather than passing over it.
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
