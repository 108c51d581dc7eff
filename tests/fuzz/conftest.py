"""Share the fuzzing budget among the selected fuzz tests, and say what they did."""

from __future__ import annotations

from pathlib import Path

import pytest

from fuzz import runner


@pytest.hookimpl(trylast=True)  # after -k and -m have deselected what they deselect
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    here = Path(__file__).parent
    runner.SELECTED[0] = sum(
        1 for item in items if item.path.parent == here and item.name.startswith("test_fuzz_")
    )
    try:
        runner.minutes()
    except runner.FuzzUsageError as error:
        raise pytest.UsageError(str(error)) from None


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if not runner.STATS:
        return
    total_inputs = sum(stats.inputs for stats in runner.STATS)
    total_seconds = sum(stats.seconds for stats in runner.STATS)
    budget = runner.minutes()
    if budget is None:
        terminalreporter.write_line(
            f"fuzz: {total_inputs} inputs in {total_seconds:.1f} s over "
            f"{len(runner.STATS)} targets (quick run; set {runner.MINUTES_VARIABLE} for more)"
        )
        return
    terminalreporter.section("fuzz summary")
    for stats in runner.STATS:
        rate = stats.inputs / stats.seconds if stats.seconds else 0.0
        kinds = ", ".join(f"{kind} {count}" for kind, count in sorted(stats.kinds.items()))
        failures = sum(failure.count for failure in stats.failures.values())
        terminalreporter.write_line(
            f"{stats.target:<34} {stats.inputs:>8} inputs {stats.seconds:>8.1f} s "
            f"{rate:>7.1f}/s  failures {failures:<4} ({kinds})"
        )
    terminalreporter.write_line(
        f"{'total':<34} {total_inputs:>8} inputs {total_seconds:>8.1f} s "
        f"(budget {budget:g} min; crashes kept in {runner.crash_directory()})"
    )
