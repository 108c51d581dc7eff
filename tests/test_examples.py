"""The example workspace shows every rule, and the README shows what it really prints."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from roslint_names.registry import load_registry

ROOT = Path(__file__).resolve().parents[1]


def test_examples_show_every_rule(run_cli: Any) -> None:
    result = run_cli(["check", "--format", "json", "examples"], ROOT)
    assert result.exit_code == 1, result.stderr
    shown = set(result.codes())
    missing = {rule.code for rule in load_registry().rules} - shown
    assert not missing, f"examples/ shows no finding of {sorted(missing)}"


def test_readme_sample_output_is_real(run_cli: Any) -> None:
    output = run_cli(["check", "examples/"], ROOT)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    sample = readme.split("On the example workspace (`examples/`):", 1)[1]
    sample = sample.split("```text\n", 1)[1].split("```", 1)[0]
    lines = [line for line in sample.splitlines() if line != "..."]
    assert lines, "the README lost its sample output"
    for line in lines[:-1]:
        assert line in output.stdout.splitlines(), line
    assert lines[-1] == output.stderr.strip()


def test_readme_validate_sample_is_real(run_cli: Any) -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    block = readme.split("```console\n", 1)[1].split("```", 1)[0]
    command = re.search(r"^\$ roslint-names (validate .*'~scan' cmd_vel)$", block, re.MULTILINE)
    assert command is not None
    arguments = ["validate", "--ros", "2", "--kind", "topic", "~scan", "cmd_vel"]
    output = run_cli(arguments, ROOT).stdout.splitlines()
    for line in output:
        assert line in block.splitlines(), line
