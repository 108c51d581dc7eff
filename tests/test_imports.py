"""A one-file run imports only the parser its file needs (the pre-commit case)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import write

PARSERS = ("lxml", "libcst", "tree_sitter", "yaml")
FILES = {
    "talker.py": (
        "import rclpy\nfrom rclpy.node import Node\n\n\ndef main():\n"
        '    rclpy.init()\n    node = Node("talker")\n    rclpy.spin(node)\n',
        {"libcst"},
    ),
    "bringup.launch.py": (
        "from launch import LaunchDescription\nfrom launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n"
        '    return LaunchDescription([Node(package="demo_nodes_cpp", executable="talker")])\n',
        {"libcst"},
    ),
    "talker.cpp": (
        "#include <ros/ros.h>\nint main(int argc, char** argv)\n"
        '{\n  ros::init(argc, argv, "talker");\n}\n',
        {"tree_sitter"},
    ),
    "robot.launch": ('<launch>\n  <node name="talker" pkg="p" type="t"/>\n</launch>\n', {"lxml"}),
    # A parameter file by its content is parsed; other YAML of a ROS 2 workspace is not.
    "params.yaml": ("amcl:\n  ros__parameters:\n    use_sim_time: true\n", {"yaml"}),
    "costmap.yaml": ("robot_radius: 0.2\nplugins: [obstacle_layer]\n", set()),
}


@pytest.mark.parametrize("name", sorted(FILES))
def test_one_file_run_imports_only_its_parser(tmp_path: Path, name: str) -> None:
    source, expected = FILES[name]
    write(tmp_path, name, source)
    probe = (
        "import sys\nfrom roslint_names.cli import main\n"
        f"code = main(['check', '--no-cache', {name!r}])\n"
        f"print(sorted(p for p in {PARSERS!r} if p in sys.modules))\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", probe], cwd=tmp_path, capture_output=True, text=True, check=False
    )
    assert set(eval(run.stdout.strip().splitlines()[-1])) == expected, run.stderr


# What a run extracts, checks, builds or patches the graph, or edits files with: none of it
# is needed to take the stored result of a run over the same unchanged files.
RUN_MODULES = (
    "roslint_names.checks",
    "roslint_names.editing.baseline",
    "roslint_names.editing.changes",
    "roslint_names.editing.files",
    "roslint_names.editing.fixing",
    "roslint_names.editing.noqa",
    "roslint_names.editing.renames",
    "roslint_names.gather",
    "roslint_names.graph_patch",
    "roslint_names.run_checks",
    "roslint_names.same_facts",
    "roslint_names.shifts",
    "roslint_names.speculation",
    "roslint_names.workers",
    "roslint_names.workspace.build",
    "roslint_names.workspace.launch_tree",
)


def test_a_rerun_of_unchanged_files_imports_nothing_that_runs_them(tmp_path: Path) -> None:
    """The stored result of an unchanged workspace is the pre-commit hook's most frequent
    run: imports were a fifth of it (0.05 s of the CLI's 0.24 s to import and load its
    rules, alternated with the code before), for modules it never calls."""
    workspace = tmp_path / "ws"
    shutil.copytree(Path(__file__).resolve().parent.parent / "examples", workspace)
    probe = (
        "import sys\nfrom roslint_names import engine, reading\n"
        "reading.RACY_NANOSECONDS = 0  # the copy's statuses vouch for it at once\n"
        "stored_result = engine._stored_result\n"
        "def told(*given):\n"
        "    found = stored_result(*given)\n"
        "    print('reused' if found else 'not reused')\n"
        "    return found\n"
        "engine._stored_result = told\n"
        "from roslint_names.cli import main\n"
        "main(['check', '.'])\n"
        f"print(sorted(m for m in {RUN_MODULES!r} if m in sys.modules))\n"
    )

    def run() -> subprocess.CompletedProcess[str]:
        command = [sys.executable, "-c", probe]
        return subprocess.run(command, cwd=workspace, capture_output=True, text=True, check=False)

    first = run()
    assert "reused" not in first.stdout.splitlines()
    assert eval(first.stdout.strip().splitlines()[-1]), first.stderr  # the run needs them
    again = run()
    assert "reused" in again.stdout.splitlines(), again.stderr
    assert eval(again.stdout.strip().splitlines()[-1]) == [], again.stderr
