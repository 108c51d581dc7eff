"""The cycle collector runs rarely during a run, and as before after it."""

from __future__ import annotations

import gc
import shutil
from pathlib import Path
from typing import Any

import pytest

from roslint_names import engine, gather
from roslint_names.collection import THRESHOLDS, no_collections
from roslint_names.workers import Dispatcher

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_a_check_runs_with_rare_collections_and_restores_the_thresholds(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    shutil.copytree(EXAMPLES / "src" / "turtle_bringup", tmp_path / "ws")
    seen: list[tuple[int, ...]] = []
    real = engine.lint

    def observing(*arguments: Any, **keywords: Any) -> Any:
        seen.append(gc.get_threshold())
        return real(*arguments, **keywords)

    monkeypatch.setattr("roslint_names.cli.lint", observing)
    before = gc.get_threshold()
    run_cli(["check", "--no-cache", "."], tmp_path / "ws")
    assert seen == [THRESHOLDS]
    assert gc.get_threshold() == before


def _thresholds(items: list[int]) -> list[tuple[int, ...]]:
    return [gc.get_threshold() for _ in items]


def test_worker_processes_collect_rarely() -> None:
    assert gc.get_threshold() != THRESHOLDS  # so that a fork alone would not pass on them
    with Dispatcher(_thresholds, jobs=2, min_items=1) as dispatcher:
        results = [result for item in range(4) for result in dispatcher.put(item, 1)]
        results += dispatcher.finish()
        assert dispatcher.workers == 2
    assert results == [THRESHOLDS] * 4


def test_files_are_extracted_without_collections_and_the_collector_comes_back(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """No collection while a file is extracted (its tree goes by reference counting);
    the collector is on again after each file, and left off when it was off."""
    shutil.copytree(EXAMPLES / "src" / "turtle_bringup", tmp_path / "ws")
    during: list[bool] = []
    real = gather.extractor_for

    def observing(language: Any) -> Any:
        extract = real(language)

        def extracting(*arguments: Any) -> Any:
            during.append(gc.isenabled())
            return extract(*arguments)

        return extracting

    monkeypatch.setattr(gather, "extractor_for", observing)
    run_cli(["check", "--no-cache", "--jobs", "1", "."], tmp_path / "ws")
    assert during and not any(during)
    assert gc.isenabled()
    gc.disable()
    try:
        with no_collections():
            pass
        assert not gc.isenabled()
    finally:
        gc.enable()
