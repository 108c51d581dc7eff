"""Every extractor over random bytes and damaged, re-encoded real files: never raises.

The invariants are in ``checks``; how long this runs is up to ``runner`` (see README.md).
"""

from __future__ import annotations

import pytest

from fuzz.checks import check_extraction
from fuzz.inputs import TARGETS, Sample, Target
from fuzz.runner import fuzz, report_failures
from fuzz.strategies import samples


def _describe(sample: Sample) -> str:
    return (
        f"{sample.origin}; path {sample.path!r}, package {sample.package_generation}, "
        f"fallback {sample.fallback_generation}, arguments {sample.arguments!r}; "
        f"{len(sample.data)} bytes: {sample.data[:400]!r}"
    )


def _check(target: Target, sample: Sample) -> None:
    check_extraction(target, sample)


@pytest.mark.parametrize("target", TARGETS, ids=[target.name for target in TARGETS])
def test_fuzz_extractor(target: Target) -> None:
    stats = fuzz(
        target.name,
        samples(target),
        lambda sample: _check(target, sample),
        data_of=lambda sample: sample.data,
        kind_of=lambda sample: sample.kind,
        describe=_describe,
    )
    assert stats.inputs > 0
    failures = report_failures(stats)
    if failures:
        pytest.fail(failures, pytrace=False)
