"""The pull-request gate: which lines a change added or modified since a git revision.

``check --changed-since REV`` reports only findings on those lines, and graph findings
whose location or related location is on one: what the change under review brought in.
The lines come from ``git diff --unified=0 REV`` against the working tree (committed,
staged and unstaged changes alike); a file git does not track yet is new in every line.
"""

from __future__ import annotations

import os
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from ..errors import UserError
from ..model import Diagnostic, Span

_HUNK = re.compile(r"^@@ -\d+(?:,\d+)? \+(\d+)(?:,(\d+))? @@")
# "+++ b/x", or '+++ "b/caf\\351.launch"' when git quotes an unusual name whole
_NEW_FILE = re.compile(r'^\+\+\+ (?:b/(.*)|("b/.*"))$')


class ChangesError(UserError):
    """git could not say what changed; the message says why."""


@dataclass(frozen=True)
class ChangedLines:
    """Lines added or modified, per absolute path; ``None`` for a file new as a whole."""

    lines: dict[str, frozenset[int] | None]

    def touches(self, path: str, span: Span, cwd: Path) -> bool:
        absolute = _displayed(os.path.normpath(os.path.join(_displayed(os.fspath(cwd)), path)))
        if absolute not in self.lines:
            return False
        changed = self.lines[absolute]
        return changed is None or any(
            line in changed for line in range(span.line, span.end_line + 1)
        )


def changed_lines(revision: str, cwd: Path) -> ChangedLines:
    root = Path(_git(["rev-parse", "--show-toplevel"], cwd).strip())
    _git(["rev-parse", "--verify", "--quiet", f"{revision}^{{commit}}"], cwd, revision)
    diff = _git(
        ["diff", "--no-color", "--no-ext-diff", "--unified=0", "--no-renames", revision, "--"],
        root,
    )
    lines: dict[str, frozenset[int] | None] = {}
    found: dict[str, set[int]] = {}
    current: set[int] | None = None
    in_header = False  # "+++ b/x" names the file only between "diff --git" and its hunks
    for text in diff.splitlines():
        if text.startswith("diff --git "):
            in_header, current = True, None
        elif in_header and text.startswith("+++ "):
            match = _NEW_FILE.match(text)  # "+++ /dev/null": deleted, nothing to report
            if match is not None:
                name = match.group(1) or _unquote('"' + match.group(2)[3:])
                current = found.setdefault(_displayed(os.path.normpath(root / name)), set())
        elif (hunk := _HUNK.match(text)) is not None:
            in_header = False
            if current is not None:
                start, count = int(hunk.group(1)), int(hunk.group(2) or "1")
                current.update(range(start, start + count))
    lines.update((path, frozenset(numbers)) for path, numbers in found.items())
    untracked = _git(["ls-files", "--others", "--exclude-standard", "-z"], root)
    for name in untracked.split("\0"):
        if name:
            lines[_displayed(os.path.normpath(root / name))] = None
    return ChangedLines(lines)


def gate(diagnostics: Sequence[Diagnostic], changes: ChangedLines, cwd: Path) -> list[Diagnostic]:
    """The diagnostics the change brought in: on a changed line, or (graph findings)
    related to one."""
    return [
        diagnostic
        for diagnostic in diagnostics
        if changes.touches(diagnostic.path, diagnostic.span, cwd)
        or any(changes.touches(r.path, r.span, cwd) for r in diagnostic.related)
    ]


def _displayed(path: str) -> str:
    """A path as findings name it (``discover.display_path``): the bytes of a name that is
    not UTF-8 as ``\\xe9`` escapes. Both sides are compared in that form."""
    return path if path.isascii() else os.fsencode(path).decode("utf-8", "backslashreplace")


def _unquote(name: str) -> str:
    """git quotes paths with unusual characters in C style (``"caf\\351.launch"``): the
    bytes it stands for, named as Python names that file (``os.fsdecode``), so that a name
    that is not UTF-8 matches the path the run reports."""
    if not (name.startswith('"') and name.endswith('"')):
        return name
    raw = os.fsencode(name[1:-1]).decode("latin-1").encode("latin-1", "backslashreplace")
    return os.fsdecode(raw.decode("unicode_escape").encode("latin-1"))


def _git(arguments: list[str], cwd: Path, revision: str | None = None) -> str:
    import subprocess  # only --changed-since runs git: other runs do not pay for the import

    try:
        done = subprocess.run(["git", *arguments], cwd=cwd, capture_output=True, check=False)
    except OSError as error:
        raise ChangesError(f"--changed-since needs git: {error.strerror}") from error
    if done.returncode != 0:
        if revision is not None:
            raise ChangesError(f"--changed-since: {revision!r} is not a commit git knows here")
        errors = done.stderr.decode("utf-8", "replace").strip()
        reason = errors.splitlines()[-1] if errors else "git failed"
        raise ChangesError(f"--changed-since: {reason}")
    # As Python names files: a name that is not UTF-8 (``ls-files -z`` prints it raw)
    # keeps its bytes, and so the same str as the run's own paths.
    return os.fsdecode(done.stdout)
