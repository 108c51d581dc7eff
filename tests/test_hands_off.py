"""A run never writes into the tree it lints: every command, cold and warm, in parallel.

The bundled example workspace (every language, launch trees, build files) is copied, its
bytes, names and modes hashed, and every way of running the tool is tried on it; the
default cache directory (XDG) is pointed outside the tree, as on a developer machine.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import stat
from pathlib import Path
from typing import Any

import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def tree_state(root: Path) -> dict[str, tuple[str, int, int]]:
    """Every entry below ``root``: its content hash (or "dir"), mode and modification time."""
    state: dict[str, tuple[str, int, int]] = {}
    for path in sorted(root.rglob("*")):
        info = path.lstat()
        digest = "dir" if path.is_dir() else hashlib.sha256(path.read_bytes()).hexdigest()
        state[path.relative_to(root).as_posix()] = (
            digest,
            stat.S_IMODE(info.st_mode),
            info.st_mtime_ns,
        )
    return state


def test_no_command_writes_into_the_linted_tree(
    run_cli: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    workspace = tmp_path / "ws"
    shutil.copytree(EXAMPLES, workspace)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    one_launch_file = next(p for p in sorted(workspace.rglob("*.launch")))
    one_file = os.fspath(one_launch_file.relative_to(workspace))
    before = tree_state(workspace)
    runs = [
        ["check", "."],  # cold, default cache
        ["check", "."],  # warm
        ["check", "--jobs", "2", "--format", "sarif", "."],
        ["check", "--no-cache", "--format", "json", "--show-source", "."],
        ["check", one_file],  # the pre-commit case: the rest of the workspace as context
        ["graph", "--format", "dot", "."],
        ["graph", "--format", "mermaid", "."],
        ["graph", "--format", "json", "."],
    ]
    for arguments in runs:
        result = run_cli(arguments, workspace)
        assert result.exit_code in (0, 1), (arguments, result.stderr)
    assert tree_state(workspace) == before
    assert any((tmp_path / "xdg").rglob("*")), "the cache went somewhere else"
