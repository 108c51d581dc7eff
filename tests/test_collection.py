"""The cycle collector runs rarely during a run, and as before after it."""

from __future__ import annotations

import gc
import shutil
from pathlib import Path
from typing import Any

import pytest

from roslint_names import engine, gather
from roslint_names.collection import THRESHOLDS, kept_for_the_run, no_collections
from roslint_names.workers import Dispatcher
from roslint_names.workspace import build

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


def _collector_on(items: list[int]) -> list[bool]:
    return [gc.isenabled() for _ in items]


def test_the_graph_is_built_without_collections_and_what_the_run_made_is_old_after(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """No collection while the run gathers facts and builds the graph; after it, what
    the run made is in the oldest generation (a young collection would walk it all),
    the collector is on again, and nothing stays frozen."""
    shutil.copytree(EXAMPLES / "src" / "turtle_bringup", tmp_path / "ws")
    during: list[bool] = []
    real = build.build_parts  # engine imports it when a run builds the graph

    def observing(*arguments: Any, **keywords: Any) -> Any:
        during.append(gc.isenabled())
        return real(*arguments, **keywords)

    monkeypatch.setattr(build, "build_parts", observing)
    gc.unfreeze()  # what an earlier test's language server session froze
    gc.collect()
    run_cli(["check", "--no-cache", "--jobs", "1", "."], tmp_path / "ws")
    assert during == [False]
    assert gc.isenabled()
    assert gc.get_freeze_count() == 0
    # The young generations hold what the output made, not what the run did (about
    # 26,000 objects were left there for the next collection to walk).
    young = len(gc.get_objects(generation=0)) + len(gc.get_objects(generation=1))
    assert young < 5_000


def test_the_walk_and_the_keying_run_without_collections(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """What the walk finds and the statuses the run is keyed by live as long as the run:
    at 8 copies of the benchmark's workspace the collector's passes over them were 0.09 s
    of a 1.1 s re-run with nothing changed."""
    from roslint_names import discover, run_inputs

    shutil.copytree(EXAMPLES / "src" / "turtle_bringup", tmp_path / "ws")
    during: list[tuple[str, bool]] = []

    def observed(owner: Any, name: str) -> None:
        real = getattr(owner, name)

        def observing(*arguments: Any, **keywords: Any) -> Any:
            during.append((name, gc.isenabled()))
            return real(*arguments, **keywords)

        monkeypatch.setattr(owner, name, observing)

    observed(discover, "_walk_named")
    observed(run_inputs.RunInputs, "unchanged_key")
    run_cli(["check", "--jobs", "1", "."], tmp_path / "ws")
    assert during == [("_walk_named", False), ("unchanged_key", False)]
    assert gc.isenabled()


def test_a_callers_frozen_objects_stay_frozen() -> None:
    kept = [object() for _ in range(10)]
    gc.freeze()
    try:
        frozen = gc.get_freeze_count()
        with kept_for_the_run():
            made = [[item] for item in kept]
        assert gc.get_freeze_count() == frozen
        assert made
    finally:
        gc.unfreeze()


def test_workers_forked_while_the_collector_is_off_turn_it_on() -> None:
    with no_collections(), Dispatcher(_collector_on, jobs=2, min_items=1) as dispatcher:
        results = [result for item in range(4) for result in dispatcher.put(item, 1)]
        results += dispatcher.finish()
    assert results == [True] * 4
