"""SARIF 2.1.0, for GitHub code scanning and other SARIF consumers.

One run. ``tool.driver`` carries the metadata of every rule given (sorted by code): id, name,
short and full description, help as text and Markdown (the catalog page, with its link),
``helpUri``, default level and tags. No ``security-severity``: naming is not a security
alert. Results point at their files with URIs relative to ``%SRCROOT%`` (the directory the
paths are relative to, given in ``originalUriBaseIds``); regions carry start and end
columns counted in Unicode code points (``columnKind``). Related locations (the other half
of a collision, the other places of a name) go in ``relatedLocations`` and the message
links to them. Every result has a ``partialFingerprints.primaryLocationLineHash``.
Nothing depends on the clock or the order of a dictionary: two runs on the same tree give
identical bytes.

Suppressed results are left out (GitHub ignores ``suppressions`` and would show them as
open alerts) unless the context includes them; then each carries
``"suppressions": [{"kind": "inSource"}]``.
"""

from __future__ import annotations

import json
import os
import posixpath
import re
from collections import Counter
from collections.abc import Sequence
from pathlib import Path, PurePosixPath
from typing import Any
from urllib.parse import quote

from .. import PROJECT_URL
from ..catalog import RuleMeta
from ..fingerprint import line_fingerprint
from ..model import Diagnostic, Edit, Severity, Span
from .base import ReportContext, rules_by_code

SCHEMA_URI = "https://json.schemastore.org/sarif-2.1.0.json"
SARIF_VERSION = "2.1.0"
TOOL_NAME = "roslint-names"
SRCROOT = "%SRCROOT%"
RULE_TAGS = ("ros", "naming")

_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning"}
_SEMVER = re.compile(
    r"^(0|[1-9]\d*)\.(0|[1-9]\d*)\.(0|[1-9]\d*)"
    r"(?:-((?:0|[1-9]\d*|\d*[a-zA-Z-][0-9a-zA-Z-]*)(?:\.(?:0|[1-9]\d*|\d*[a-zA-Z-][0-9a-zA-Z-]*))*))?"
    r"(?:\+([0-9a-zA-Z-]+(?:\.[0-9a-zA-Z-]+)*))?$"
)
_PEP440 = re.compile(
    r"^v?(\d+)(?:\.(\d+))?(?:\.(\d+))?"
    r"(?:[.-]?(a|b|rc|alpha|beta|c)[.-]?(\d*))?"
    r"(?:[.-]?(post|dev)[.-]?(\d*))?"
    r"(?:\+([0-9a-zA-Z.]+))?$"
)
_WINDOWS_DRIVE = re.compile(r"^[A-Za-z]:[/\\]")


def render_sarif(
    diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta], context: ReportContext
) -> str:
    return json.dumps(sarif_log(diagnostics, rules, context), indent=2, ensure_ascii=False) + "\n"


def sarif_log(
    diagnostics: Sequence[Diagnostic], rules: Sequence[RuleMeta], context: ReportContext
) -> dict[str, Any]:
    """The SARIF log as JSON-ready values (``render_sarif`` serialises it)."""
    ordered_rules = _unique_sorted(rules)
    rule_index = {rule.code: index for index, rule in enumerate(ordered_rules)}
    fingerprints = _fingerprints(diagnostics)
    results = [
        _result(diagnostic, rule_index, fingerprint, context)
        for diagnostic, fingerprint in zip(diagnostics, fingerprints, strict=True)
        if (context.include_suppressed or not diagnostic.suppressed)
        and (context.baseline or not diagnostic.baselined)
    ]
    driver: dict[str, Any] = {
        "name": TOOL_NAME,
        "version": context.tool_version,
    }
    semantic = semantic_version(context.tool_version)
    if semantic is not None:
        driver["semanticVersion"] = semantic
    driver["informationUri"] = PROJECT_URL
    driver["rules"] = [_rule(rule) for rule in ordered_rules]
    return {
        "$schema": SCHEMA_URI,
        "version": SARIF_VERSION,
        "runs": [
            {
                "tool": {"driver": driver},
                "invocations": [{"executionSuccessful": True}],
                "originalUriBaseIds": {SRCROOT: {"uri": root_uri(context.root)}},
                "columnKind": "unicodeCodePoints",
                "results": results,
            }
        ],
    }


def _unique_sorted(rules: Sequence[RuleMeta]) -> list[RuleMeta]:
    table = rules_by_code(rules)
    return [table[code] for code in sorted(table)]


def _rule(rule: RuleMeta) -> dict[str, Any]:
    full = rule.full_description or rule.summary
    help_markdown = rule.help_markdown
    if not help_markdown.strip():  # a plugin without a catalog page
        help_markdown = f"{full}\n\n[Rule page]({rule.help_uri})\n" if rule.help_uri else full
    descriptor: dict[str, Any] = {
        "id": rule.code,
        "name": rule.name,
        "shortDescription": {"text": rule.summary or full},
        "fullDescription": {"text": full},
        # the catalog page: Markdown reads well as plain text, and it is the whole story
        "help": {"text": help_markdown, "markdown": help_markdown},
    }
    if rule.help_uri:
        descriptor["helpUri"] = rule.help_uri
    descriptor["defaultConfiguration"] = {"level": _LEVEL[rule.severity]}
    descriptor["properties"] = {"tags": list(RULE_TAGS)}
    return descriptor


def _result(
    diagnostic: Diagnostic,
    rule_index: dict[str, int],
    fingerprint: str,
    context: ReportContext,
) -> dict[str, Any]:
    result: dict[str, Any] = {"ruleId": diagnostic.code}
    if diagnostic.code in rule_index:
        result["ruleIndex"] = rule_index[diagnostic.code]
    result["level"] = _LEVEL[diagnostic.severity]
    result["message"] = {"text": _message_text(diagnostic, context.root)}
    result["locations"] = [
        {"physicalLocation": _physical_location(diagnostic.path, diagnostic.span, context.root)}
    ]
    if diagnostic.related:
        related_locations = []
        for number, related in enumerate(diagnostic.related, start=1):
            location: dict[str, Any] = {
                "id": number,
                "physicalLocation": _physical_location(related.path, related.span, context.root),
            }
            if related.message:
                location["message"] = {"text": escape_braces(related.message)}
            related_locations.append(location)
        result["relatedLocations"] = related_locations
    result["partialFingerprints"] = {"primaryLocationLineHash": fingerprint}
    if diagnostic.suppressed:
        result["suppressions"] = [{"kind": "inSource"}]
    if context.baseline:
        result["baselineState"] = "unchanged" if diagnostic.baselined else "new"
    if diagnostic.edit is not None:
        result["fixes"] = [_fix(diagnostic, diagnostic.edit, context)]
    return result


def _fix(diagnostic: Diagnostic, edit: Edit, context: ReportContext) -> dict[str, Any]:
    """The fix as one change per file: a rename's other uses are in the same fix."""
    safety = "safe" if edit.safe else "unsafe (--unsafe-fixes)"
    by_file: dict[str, list[Edit]] = {diagnostic.path: [edit]}
    for other in diagnostic.also:
        by_file.setdefault(other.path or diagnostic.path, []).append(other)
    uses = f", and {len(diagnostic.also)} other uses" if diagnostic.also else ""
    return {
        "description": {"text": f"write '{edit.text}'{uses} ({safety} fix)"},
        "artifactChanges": [
            {
                "artifactLocation": artifact_location(path, context.root),
                "replacements": [
                    {
                        "deletedRegion": _region(change.span),
                        "insertedContent": {"text": change.text},
                    }
                    for change in edits
                ],
            }
            for path, edits in by_file.items()
        ],
    }


def _message_text(diagnostic: Diagnostic, root: Path) -> str:
    """The result message; with related locations, a sentence linking to each of them."""
    text = escape_braces(diagnostic.message)
    if not diagnostic.related:
        return text
    links = ", ".join(
        f"[{escape_link_text(f'{related.path}:{related.span.line}')}]({number})"
        for number, related in enumerate(diagnostic.related, start=1)
    )
    separator = " " if text.endswith((".", "!", "?")) else ". "
    noun = "Related location" if len(diagnostic.related) == 1 else "Related locations"
    return f"{text}{separator}{noun}: {links}."


def escape_braces(text: str) -> str:
    """SARIF §3.11.5: literal ``{`` and ``}`` in a message are written ``{{`` and ``}}``."""
    return text.replace("{", "{{").replace("}", "}}")


def escape_link_text(text: str) -> str:
    """SARIF §3.11.6: ``\\``, ``[`` and ``]`` in an embedded link's text take a backslash."""
    return re.sub(r"([\\\[\]])", r"\\\1", escape_braces(text))


def _physical_location(path: str, span: Span, root: Path) -> dict[str, Any]:
    return {"artifactLocation": artifact_location(path, root), "region": _region(span)}


def _region(span: Span) -> dict[str, int]:
    start_line = max(span.line, 1)
    start_column = max(span.column, 1)
    end_line = max(span.end_line, start_line)
    end_column = max(span.end_column, 1)
    if end_line == start_line:
        end_column = max(end_column, start_column)
    return {
        "startLine": start_line,
        "startColumn": start_column,
        "endLine": end_line,
        "endColumn": end_column,
    }


def artifact_location(path: str, root: Path) -> dict[str, str]:
    """A relative, percent-encoded URI against ``%SRCROOT%``; an absolute ``file`` URI for
    a path that is absolute or climbs out of the root.

    ``path`` is already '/'-separated (the Diagnostic contract); a backslash in it is part
    of a POSIX file name, not a separator, and is percent-encoded like any other byte.
    """
    if _WINDOWS_DRIVE.match(path):
        return {"uri": "file:///" + quote(path, safe="/:")}
    if PurePosixPath(path).is_absolute():
        return {"uri": "file://" + quote(posixpath.normpath(path), safe="/")}
    normal = posixpath.normpath(path)
    if normal == ".." or normal.startswith("../"):
        absolute = os.path.normpath(os.path.join(os.path.abspath(root), path))
        return {"uri": Path(absolute).as_uri()}
    return {"uri": quote(normal, safe="/"), "uriBaseId": SRCROOT}


def root_uri(root: Path) -> str:
    """The absolute ``file`` URI of ``root``, ending in ``/`` as SARIF wants."""
    uri = Path(os.path.abspath(root)).as_uri()
    return uri if uri.endswith("/") else uri + "/"


def _fingerprints(diagnostics: Sequence[Diagnostic]) -> list[str]:
    """``primaryLocationLineHash`` of each diagnostic: a hash and an occurrence counter.

    The hash covers the code, the path and the source line with all whitespace removed, so
    it survives moving the line and re-indenting it; ``:N`` numbers the diagnostics sharing
    a hash, in order, as GitHub's own fingerprints do. The counter runs over suppressed
    diagnostics too, so including them does not renumber the others. Without a source line
    the message stands in for it.
    """
    seen: Counter[str] = Counter()
    fingerprints: list[str] = []
    for diagnostic in diagnostics:
        digest = line_fingerprint(diagnostic)
        seen[digest] += 1
        fingerprints.append(f"{digest}:{seen[digest]}")
    return fingerprints


def semantic_version(version: str) -> str | None:
    """``version`` as a SemVer 2.0 string: kept when it already is one, converted from a
    PEP 440 version (``1.2.0rc1`` -> ``1.2.0-rc.1``, ``1.2.0.dev3`` -> ``1.2.0-dev.3``,
    ``1.2.0.post1`` -> ``1.2.0+post.1``), None when it is neither."""
    if _SEMVER.match(version):
        return version
    match = _PEP440.match(version.strip().lower())
    if match is None:
        return None
    major, minor, patch, pre, pre_number, extra, extra_number, local = match.groups()
    core = f"{int(major)}.{int(minor or 0)}.{int(patch or 0)}"
    prerelease: list[str] = []
    build: list[str] = []
    if pre:
        label = {"a": "alpha", "b": "beta", "c": "rc"}.get(pre, pre)
        prerelease += [label, str(int(pre_number or 0))]
    if extra == "dev":
        prerelease += ["dev", str(int(extra_number or 0))]
    elif extra == "post":
        build += ["post", str(int(extra_number or 0))]
    if local:
        build += [part for part in local.split(".") if part]
    result = core
    if prerelease:
        result += "-" + ".".join(prerelease)
    if build:
        result += "+" + ".".join(build)
    return result if _SEMVER.match(result) else None
