"""Every rule has a catalog page, and every Bad/Good example on it runs through the engine."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from conftest import write, write_package

from roslint_names.catalog import Example, catalog_dir, load_doc, page_filename
from roslint_names.registry import load_registry

RULES = load_registry().rules
EXAMPLES = [
    pytest.param(rule.code, example, id=f"{rule.code}-{example.verdict}-line{example.line}")
    for rule in RULES
    for example in load_doc(rule.code, rule.name).examples
]


@pytest.mark.parametrize("rule", RULES, ids=lambda rule: rule.code)
def test_every_rule_has_a_page_with_bad_and_good_examples(rule: Any) -> None:
    doc = load_doc(rule.code, rule.name)
    assert doc.markdown.startswith(f"# {rule.code} {rule.name}\n")
    assert doc.what_it_does, f"{rule.code}: the page needs a '## What it does' section"
    verdicts = {example.verdict for example in doc.examples}
    assert verdicts == {"bad", "good"}, f"{rule.code}: needs Bad and Good examples"


@pytest.mark.parametrize("rule", RULES, ids=lambda rule: rule.code)
def test_every_page_says_whether_the_rule_judges_test_code(rule: Any) -> None:
    markdown = load_doc(rule.code, rule.name).markdown
    verdict = "judged" if rule.judges_test_code else "not judged"
    assert f"## Where it applies\n\n**Test code: {verdict}.**" in markdown


def test_no_page_without_a_rule() -> None:
    expected = {page_filename(rule.code, rule.name) for rule in RULES}
    assert {path.name for path in catalog_dir().glob("RN*.md")} == expected


@pytest.mark.parametrize(("code", "example"), EXAMPLES)
def test_example(code: str, example: Example, run_cli: Any, tmp_path: Path) -> None:
    rule = load_registry().by_code_or_name(code)
    assert rule is not None
    doc = load_doc(rule.code, rule.name)
    if example.ros is not None:
        write_package(tmp_path, example.ros.value)
    if doc.config is not None:
        write(tmp_path, "roslint-names.toml", doc.config)
    write(tmp_path, example.filename, example.code)
    for filename, code_text in example.also:
        write(tmp_path, filename, code_text)
    files = [example.filename, *(filename for filename, _ in example.also)]
    result = run_cli(["check", "--format", "json", "--select", "ALL", *files], tmp_path)
    assert result.exit_code in (0, 1), result.stderr
    found = result.codes()
    if example.verdict == "bad":
        assert found and set(found) == {code}, result.stdout
        assert result.exit_code == 1
    else:
        assert found == [], result.stdout
        assert result.exit_code == 0
