"""A one-file run imports only the parser its file needs (the pre-commit case)."""

from __future__ import annotations

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
