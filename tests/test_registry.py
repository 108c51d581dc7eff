"""The rule registry: the built-in rules arrive through the plugin entry point."""

from __future__ import annotations

from importlib.metadata import entry_points

import pytest

from roslint_names.model import Severity
from roslint_names.registry import ENTRY_POINT_GROUP, RegistryError, build_registry, load_registry
from roslint_names.rule import Rule

RN101 = load_registry().by_code_or_name("RN101")


def test_built_in_rules_are_entry_points() -> None:
    declared = {entry.name for entry in entry_points(group=ENTRY_POINT_GROUP)}
    assert declared == {rule.code for rule in load_registry().rules}


def test_lookup_by_code_slug_and_prefix() -> None:
    registry = load_registry()
    assert registry.by_code_or_name("rn101") is RN101
    assert registry.by_code_or_name("illegal-name") is RN101
    assert [rule.code for rule in registry.matching("RN10")] == ["RN101", "RN102"]
    assert registry.matching("RN9") == []


def plugin(code: str, name: str) -> Rule:
    return Rule(code=code, name=name, summary="s", severity=Severity.WARNING, check=None)


@pytest.mark.parametrize(
    ("rules", "message"),
    [
        ([plugin("RN101", "other-name")], "registered twice"),
        ([plugin("RN9001", "x")], "not of the form"),
        ([plugin("XY123", "Bad_Name")], "not kebab-case"),
        (["not a rule"], "is not a roslint_names Rule"),
    ],
)
def test_plugins_that_break_the_contract_are_refused(rules: list[object], message: str) -> None:
    with pytest.raises(RegistryError, match=message):
        build_registry([RN101, *rules])  # type: ignore[list-item]


def test_a_plugin_with_its_own_prefix_joins_the_registry() -> None:
    registry = build_registry([*load_registry().rules, plugin("ACME101", "acme-robot-prefix")])
    assert registry.by_code_or_name("acme-robot-prefix") is not None
    assert [rule.code for rule in registry.matching("ACME")] == ["ACME101"]
