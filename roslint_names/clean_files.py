"""Which files the per-file rules found nothing in last time, so that a run after an edit
checks again only what can have changed (issue 30).

A file's per-file verdict is a function of its facts (its bytes, path, language and
generations: its facts key), its display path (test and example code, per-file ignores),
the settings, the rules' code, the pluginlib names of the workspace (RN203) and the
package layout (a file is example code up to its package's folder; which manifests there
are, not what they say: ``memo_key``): nothing else, for the
files checked as their facts arrive; and for those that wait for the names the launch
files wire (RN202), those names too (their ``digest`` is in the file's entry, ``under``).
The files whose verdict waits for other files' facts (a typed service, a constant of
another file) are always checked. So a run keys a set of files found clean by all of
those (``memo_key``), stores the entries (``entry``) of the files it found with no finding
and no suppression, and the next run under the same key skips them: their verdict is
"nothing", whatever the order of the files or their number. An entry that no longer
matches is simply never looked up: a stale set can only cost time, never change a result.

The files that had findings or suppressions are kept the same way, with their verdict
(the findings and suppressions the per-file rules made, before the run adds anything
about the workspace): the same inputs make the same verdict, so a file with findings is
no longer checked (and read) again on every run after an edit; at 8 copies of the
benchmark's workspace that was 1,576 files and 0.4 s of each such run.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable, Mapping

from .config import Settings, settings_fingerprint
from .model import Diagnostic, Span
from .registry import Registry
from .suppress import Suppression

# A file's verdict as kept: its findings and suppressions, as the per-file rules made them.
Verdict = tuple[tuple[Diagnostic, ...], tuple[Suppression, ...]]

_ENTRY_BYTES = 16


def memo_key(
    settings: Settings,
    registry: Registry,
    enabled: Iterable[str],
    plugin_names: Iterable[str],
    manifests: Iterable[str],
) -> str:
    """The name the set of clean files is stored under (``FactsCache.store_checks``).
    ``manifests``: the paths of every package.xml and plugin description the run read,
    the package layout. Not what they say: a verdict reads a manifest only through the
    generation it gives its files (in their facts keys) and the plugin names (here); the
    packages a manifest depends on decide which service types a file is compared with,
    and such a file's entry holds those types (``run_checks.RunChecks._typed``: ``under``).
    A dependency added checked every file of the workspace again: 2.8 s at 8 copies."""
    from .cache import code_fingerprint

    modules = {rule.check.__module__ for rule in registry.rules if rule.check is not None}
    digest = hashlib.blake2b(digest_size=20)
    for part in (
        code_fingerprint(modules),
        settings_fingerprint(settings),
        " ".join(sorted(enabled)),
        " ".join(sorted(plugin_names)),
    ):
        digest.update(part.encode("utf-8", "surrogateescape") + b"\0")
    for manifest in sorted(manifests):
        digest.update(f"{manifest}\n".encode("utf-8", "surrogateescape"))
    return digest.hexdigest()


def entry(display: str, facts_key: str) -> bytes:
    """One file as the set holds it: its display path and its facts key."""
    text = f"{display}\0{facts_key}".encode("utf-8", "surrogateescape")
    return hashlib.blake2b(text, digest_size=_ENTRY_BYTES).digest()


def digest(names: Iterable[str]) -> bytes:
    """The digest of a run-wide set of names a file's verdict may depend on (the absolute
    names the launch files wire: ``wiring``)."""
    text = "\n".join(sorted(names)).encode("utf-8", "surrogateescape")
    return hashlib.blake2b(text, digest_size=_ENTRY_BYTES).digest()


def under(entry: bytes, context: bytes) -> bytes:
    """A file's entry for a verdict that also depends on ``context`` (a ``digest``)."""
    return hashlib.blake2b(entry + context, digest_size=_ENTRY_BYTES).digest()


def stored(clean: Iterable[bytes], verdicts: Mapping[bytes, Verdict]) -> object:
    """What ``FactsCache.store_checks`` keeps: the clean files' entries, and the other
    files' verdicts by entry (a suppression as plain values: the cache builds model
    values only)."""
    return (
        frozenset(clean),
        {
            entry: (
                diagnostics,
                tuple((s.keys, tuple(sorted(s.lines)), s.span) for s in suppressions),
            )
            for entry, (diagnostics, suppressions) in verdicts.items()
        },
    )


def loaded(value: object) -> tuple[frozenset[bytes], dict[bytes, Verdict]]:
    """What ``stored`` made, as ``FactsCache.load_checks`` gave it back; nothing for
    anything else (an older cache's set alone, a damaged entry)."""
    nothing: tuple[frozenset[bytes], dict[bytes, Verdict]] = (frozenset(), {})
    if not (isinstance(value, tuple) and len(value) == 2):
        return nothing
    clean, kept = value
    if not (isinstance(clean, frozenset) and all(isinstance(item, bytes) for item in clean)):
        return nothing
    if not isinstance(kept, dict):
        return nothing
    verdicts: dict[bytes, Verdict] = {}
    for entry, verdict in kept.items():
        found = _verdict(verdict)
        if not isinstance(entry, bytes) or found is None:
            return nothing
        verdicts[entry] = found
    return clean, verdicts


def _verdict(value: object) -> Verdict | None:
    if not (isinstance(value, tuple) and len(value) == 2):
        return None
    diagnostics, suppressions = value
    if not (isinstance(diagnostics, tuple) and isinstance(suppressions, tuple)):
        return None
    if not all(isinstance(diagnostic, Diagnostic) for diagnostic in diagnostics):
        return None
    made: list[Suppression] = []
    for suppression in suppressions:
        if not (isinstance(suppression, tuple) and len(suppression) == 3):
            return None
        keys, lines, span = suppression
        if not (
            isinstance(keys, tuple)
            and all(isinstance(key, str) for key in keys)
            and isinstance(lines, tuple)
            and all(isinstance(line, int) for line in lines)
            and isinstance(span, Span)
        ):
            return None
        made.append(Suppression(keys, frozenset(lines), span))
    return diagnostics, tuple(made)
