"""Reporters: diagnostics and rule metadata in, one string out.

Each output format lives in its own module (``text``, ``json``, ``sarif``, ``github``,
``junit``, ``gitlab``).
Reporters never see rules, extractors or the engine: only
:class:`~roslint_names.model.Diagnostic` values, already sorted, and the
:class:`~roslint_names.catalog.RuleMeta` of the rules that ran.

Every function returns text and writes nothing. ``render`` returns the whole report, each
line ending in ``\\n`` (an empty string for a text or GitHub report with no findings), to be
written as is; ``statistics`` likewise; ``summary`` returns a single line without its line
break, for ``print(..., file=sys.stderr)``.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence

from ..catalog import RuleMeta
from ..model import Diagnostic, Severity
from .base import ReportContext, plural, rules_by_code, visible
from .github import render_github
from .gitlab import render_gitlab
from .json import render_json
from .junit import render_junit
from .sarif import render_sarif
from .text import render_text

__all__ = ["FORMATS", "ReportContext", "render", "statistics", "summary"]

Renderer = Callable[[Sequence[Diagnostic], Sequence[RuleMeta], ReportContext], str]

FORMATS = ("text", "json", "sarif", "github", "junit", "gitlab")
_RENDERERS: dict[str, Renderer] = {
    "text": render_text,
    "json": render_json,
    "sarif": render_sarif,
    "github": render_github,
    "junit": render_junit,
    "gitlab": render_gitlab,
}


def render(
    fmt: str,
    diagnostics: Sequence[Diagnostic],
    rules: Sequence[RuleMeta],
    context: ReportContext,
) -> str:
    """The report of ``diagnostics`` in format ``fmt`` (one of :data:`FORMATS`).

    ``diagnostics`` are rendered in the order given (the engine sorts them). Suppressed ones
    are left out, except by SARIF when ``context.include_suppressed`` is set.
    """
    renderer = _RENDERERS.get(fmt)
    if renderer is None:
        raise ValueError(f"unknown output format {fmt!r}; choose one of {', '.join(FORMATS)}")
    return renderer(diagnostics, rules, context)


def summary(diagnostics: Sequence[Diagnostic], files_checked: int) -> str:
    """One line for stderr; suppressed diagnostics do not count.

    ``Found 3 problems (2 errors, 1 warning) in 2 files (12 files checked).`` or
    ``All checks passed: 12 files checked, no problems.``: the files with problems apart
    from the files checked, which "in 12 files" left one to confuse.
    """
    shown = visible(diagnostics)
    checked = f"{plural(files_checked, 'file')} checked"
    baselined = sum(1 for d in diagnostics if d.baselined)
    known = f"{baselined} more in the baseline" if baselined else ""
    if not shown:
        new = "new " if baselined else ""
        return f"All checks passed: {checked}, no {new}problems{f' ({known})' if known else ''}."
    errors = sum(1 for diagnostic in shown if diagnostic.severity is Severity.ERROR)
    warnings = len(shown) - errors
    counts = ((errors, "error"), (warnings, "warning"))
    detail = ", ".join(plural(count, noun) for count, noun in counts if count)
    where = plural(len({diagnostic.path for diagnostic in shown}), "file")
    checked += f"; {known}" if known else ""
    return f"Found {plural(len(shown), 'problem')} ({detail}) in {where} ({checked})."


def statistics(diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta]) -> str:
    """Counts per code, like ``ruff --statistics``: most frequent first, then by code.

    One line per code, ``count<TAB>code<TAB>slug``, the counts right-aligned and the codes
    padded to a common width; suppressed diagnostics do not count. Empty when there is
    nothing to count.
    """
    shown = visible(diagnostics)
    if not shown:
        return ""
    counts = Counter(diagnostic.code for diagnostic in shown)
    names: dict[str, str] = {}
    for diagnostic in shown:
        names.setdefault(diagnostic.code, diagnostic.rule_name)
    for code, meta in rules_by_code(rules).items():
        if code in names:
            names[code] = meta.name
    ordered = sorted(counts.items(), key=lambda item: (-item[1], item[0]))
    count_width = max(len(str(count)) for _, count in ordered)
    code_width = max(len(code) for code, _ in ordered)
    return "".join(
        f"{count:>{count_width}}\t{code:<{code_width}}\t{names[code]}\n" for code, count in ordered
    )
