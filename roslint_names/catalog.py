"""The rule catalog: one Markdown page per rule, the single source of its documentation.

The pages live in the repository's ``rules/`` folder and are shipped inside the wheel as
``roslint_names/catalog/``. ``roslint-names rule RN101`` prints a page, SARIF reuses its
text, and the test suite runs every fenced Bad/Good example it holds.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from functools import cache
from pathlib import Path

from . import PROJECT_URL
from .errors import UserError
from .model import Generation, Severity
from .rule import Rule

_FENCE = re.compile(r"^```([^\n`]*)\n(.*?)^```\s*$", re.MULTILINE | re.DOTALL)
_SECTION = re.compile(r"^## (.+?)\s*$", re.MULTILINE)


@dataclass(frozen=True)
class Example:
    verdict: str  # "bad" or "good"
    filename: str  # where the test writes it, relative to a throwaway workspace
    ros: Generation | None  # forced generation; None lets detection decide
    code: str
    line: int  # line of the page where the example's code starts
    # More files of the same example (graph rules need several): fences marked `also`
    # right after it, as (filename, code).
    also: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class RuleDoc:
    code: str
    name: str
    markdown: str
    what_it_does: str  # the first paragraph under "## What it does"
    examples: tuple[Example, ...]
    config: str | None  # a ```toml config``` block applied to every example of the page


@dataclass(frozen=True)
class RuleMeta:
    """What reporters know of a rule: metadata, never the rule's code."""

    code: str
    name: str
    summary: str
    severity: Severity
    full_description: str
    help_markdown: str
    help_uri: str


class CatalogError(UserError):
    pass


def catalog_dir() -> Path:
    package_dir = Path(__file__).resolve().parent
    for candidate in (package_dir / "catalog", package_dir.parent / "rules"):
        if candidate.is_dir():
            return candidate
    raise CatalogError(f"the rule catalog is missing (looked in {package_dir / 'catalog'})")


def page_filename(code: str, name: str) -> str:
    return f"{code}-{name}.md"


def page_url(code: str, name: str) -> str:
    return f"{PROJECT_URL}/blob/main/rules/{page_filename(code, name)}"


@cache
def load_doc(code: str, name: str) -> RuleDoc:
    path = catalog_dir() / page_filename(code, name)
    try:
        markdown = path.read_text(encoding="utf-8")
    except OSError as error:
        raise CatalogError(f"cannot read the catalog page of {code}: {error}") from error
    return parse_page(code, name, markdown)


def parse_page(code: str, name: str, markdown: str) -> RuleDoc:
    examples: list[Example] = []
    config: str | None = None
    for match in _FENCE.finditer(markdown):
        words = match.group(1).split()
        body = match.group(2)
        start_line = markdown.count("\n", 0, match.start(2)) + 1
        if len(words) >= 2 and words[1] == "config":
            config = body
            continue
        if len(words) < 2 or words[1] not in ("bad", "good"):
            continue
        attributes = dict(word.split("=", 1) for word in words[2:] if "=" in word)
        if "file" not in attributes:
            raise CatalogError(f"{code}: example at line {start_line} has no file=NAME")
        if "also" in words[2:]:
            if not examples or examples[-1].verdict != words[1]:
                raise CatalogError(f"{code}: `also` at line {start_line} follows no example")
            previous = examples[-1]
            extra = (*previous.also, (attributes["file"], body))
            examples[-1] = replace(previous, also=extra)
            continue
        ros = attributes.get("ros")
        examples.append(
            Example(
                verdict=words[1],
                filename=attributes["file"],
                ros=Generation(int(ros)) if ros else None,
                code=body,
                line=start_line,
            )
        )
    return RuleDoc(
        code=code,
        name=name,
        markdown=markdown,
        what_it_does=_first_paragraph(_section(markdown, "What it does")),
        examples=tuple(examples),
        config=config,
    )


def rule_meta(rule: Rule) -> RuleMeta:
    doc = load_doc(rule.code, rule.name)
    url = page_url(rule.code, rule.name)
    return RuleMeta(
        code=rule.code,
        name=rule.name,
        summary=rule.summary,
        severity=rule.severity,
        full_description=doc.what_it_does or rule.summary,
        help_markdown=f"{doc.markdown.rstrip()}\n\n[Rule page]({url})\n",
        help_uri=url,
    )


def _section(markdown: str, title: str) -> str:
    sections = list(_SECTION.finditer(markdown))
    for index, match in enumerate(sections):
        if match.group(1).strip().lower() == title.lower():
            end = sections[index + 1].start() if index + 1 < len(sections) else len(markdown)
            return markdown[match.end() : end]
    return ""


def _first_paragraph(text: str) -> str:
    paragraph: list[str] = []
    for line in text.strip().splitlines():
        if not line.strip():
            if paragraph:
                break
            continue
        paragraph.append(line.strip())
    return " ".join(paragraph)
