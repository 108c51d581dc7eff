"""Load every rule, built-in or plugin, through the ``roslint_names.rules`` entry points.

The built-in rules are declared in ``pyproject.toml`` under the same group third parties
use, so the plugin path is exercised by every run.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cache
from importlib.metadata import entry_points

from .errors import UserError
from .rule import Rule

ENTRY_POINT_GROUP = "roslint_names.rules"
_CODE = re.compile(r"^[A-Z]{1,4}[0-9]{3}$")
_SLUG = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")


class RegistryError(UserError):
    """A plugin that does not honour the rule contract."""


@dataclass(frozen=True)
class Registry:
    rules: tuple[Rule, ...]  # sorted by code

    def by_code_or_name(self, key: str) -> Rule | None:
        for rule in self.rules:
            if key.upper() == rule.code or key.lower() == rule.name:
                return rule
        return None

    def matching(self, selector: str) -> list[Rule]:
        """Rules a selector names: a code ("RN101"), a code prefix ("RN1", "RN") or a slug."""
        selector = selector.strip()
        if selector.upper() == "ALL":
            return list(self.rules)
        by_name = [rule for rule in self.rules if rule.name == selector.lower()]
        if by_name:
            return by_name
        return [rule for rule in self.rules if rule.code.startswith(selector.upper())]

    @property
    def codes(self) -> frozenset[str]:
        return frozenset(rule.code for rule in self.rules)


def build_registry(rules: Iterable[Rule]) -> Registry:
    seen_codes: dict[str, Rule] = {}
    seen_names: dict[str, Rule] = {}
    for rule in rules:
        if not isinstance(rule, Rule):
            raise RegistryError(f"entry point object {rule!r} is not a roslint_names Rule")
        if not _CODE.match(rule.code):
            raise RegistryError(f"rule code {rule.code!r} is not of the form RN123")
        if not _SLUG.match(rule.name):
            raise RegistryError(f"rule name {rule.name!r} ({rule.code}) is not kebab-case")
        if rule.code in seen_codes or rule.name in seen_names:
            raise RegistryError(f"rule {rule.code} {rule.name} is registered twice")
        seen_codes[rule.code] = rule
        seen_names[rule.name] = rule
    return Registry(tuple(sorted(seen_codes.values(), key=lambda rule: rule.code)))


@cache
def load_registry() -> Registry:
    loaded: list[Rule] = []
    for entry_point in entry_points(group=ENTRY_POINT_GROUP):
        try:
            loaded.append(entry_point.load())
        except Exception as error:  # a broken plugin must say which one it is
            raise RegistryError(
                f"cannot load rule plugin {entry_point.value!r}: {error}"
            ) from error
    if not loaded:
        raise RegistryError(
            "no rules are registered: roslint-names is not installed (run `pip install .`)"
        )
    return build_registry(loaded)
