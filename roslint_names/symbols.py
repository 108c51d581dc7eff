"""C++ names held in a constant of another file of the package.

``advertiseService(move_group::FK_SERVICE_NAME, ...)`` names the service as surely as a
literal when a header the file includes, in the same package, defines
``static const std::string FK_SERVICE_NAME = "compute_fk";``. The extractor marks such an
argument (an identifier the file does not declare) as a ``symbol`` and records every
header's constants and includes; once a run has every file's facts, a use whose symbol
the headers it reaches (through includes, within its package) define with one value gets
that value. A constant of another package stays unknown: that package chose the name,
and its own uses report it.
"""

from __future__ import annotations

from dataclasses import replace

from roslint_names.model import FileFacts, NameUse


def uses_constants(facts: FileFacts) -> bool:
    """Whether a name of ``facts`` waits for another file's constant."""
    return any(use.symbol for use in facts.names)


class PackageConstants:
    """The constants and includes of every C++ file of a run that has either."""

    def __init__(self) -> None:
        self._by_basename: dict[str, list[FileFacts]] = {}

    def add(self, facts: FileFacts) -> None:
        if facts.constants or facts.cpp_includes:
            basename = facts.path.rpartition("/")[2]
            self._by_basename.setdefault(basename, []).append(facts)

    def resolve(self, facts: FileFacts, package: str | None) -> FileFacts:
        """``facts`` with the symbols its package's included headers define made static.

        ``package`` is the display directory of the file's package; without one nothing
        is resolved.
        """
        if package is None or not uses_constants(facts):
            return facts
        constants = self._reachable_constants(facts, f"{package}/" if package else "")
        names = tuple(_resolved(use, constants) for use in facts.names)
        return replace(facts, names=names) if names != facts.names else facts

    def _reachable_constants(self, facts: FileFacts, prefix: str) -> dict[str, set[str]]:
        """name -> the values the package's headers ``facts`` includes (transitively) give."""
        found: dict[str, set[str]] = {}
        seen = {facts.path}
        pending = [facts]
        while pending:
            current = pending.pop()
            for include in current.cpp_includes:
                for header in self._headers(include, current.path, prefix):
                    if header.path in seen:
                        continue
                    seen.add(header.path)
                    pending.append(header)
                    for name, value in header.constants:
                        found.setdefault(name, set()).add(value)
        return found

    def _headers(self, include: str, includer: str, prefix: str) -> list[FileFacts]:
        """The package's files an ``#include`` line may mean: ``include`` relative to the
        includer's directory, or to any include directory of the package."""
        beside = f"{includer.rpartition('/')[0]}/{include}" if "/" in includer else include
        suffix = f"/{include}"
        candidates = self._by_basename.get(include.rpartition("/")[2], [])
        return sorted(
            (
                facts
                for facts in candidates
                if facts.path.startswith(prefix)
                and (facts.path == beside or facts.path.endswith(suffix))
            ),
            key=lambda facts: facts.path,
        )


def _resolved(use: NameUse, constants: dict[str, set[str]]) -> NameUse:
    if use.symbol is None:
        return use
    values = constants.get(use.symbol.rpartition("::")[2], set())
    if len(values) != 1:
        return use  # not defined there, or defined twice with different values
    return replace(use, value=next(iter(values)), dynamic=False, symbol=None)
