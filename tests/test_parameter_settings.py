"""The parameters a launch sets on each node, in the graph (issue 28, part 4): the
node's own ``<param>``s, inline dictionaries and command-line keys, and every parameter
file's keys that reach it, each with its file, key and launch site; JSON lists them all,
DOT and Mermaid a few per node."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from conftest import write
from test_parameter_files import nav_workspace
from test_reconfigure import planner_package

from roslint_names.model import Generation, Span
from roslint_names.render.view import MAX_PARAMETERS, parameter_lines
from roslint_names.workspace.graph import (
    Location,
    NodeInstance,
    ParameterSetting,
    SettingSource,
)


def graph(run_cli: Any, root: Path, fmt: str = "json") -> str:
    result = run_cli(["graph", "--format", fmt, "--no-cache", "."], root)
    assert result.exit_code == 0, result.stderr
    output: str = result.stdout
    return output


def nodes(run_cli: Any, root: Path) -> dict[str, dict[str, Any]]:
    return {node["name"]: node for node in json.loads(graph(run_cli, root))["nodes"]}


def where(entry: dict[str, Any] | None) -> tuple[str, int] | None:
    return None if entry is None else (entry["path"], entry["line"])


def settings(node: dict[str, Any]) -> list[tuple[str, str, str | None, Any, Any]]:
    return [
        (entry["name"], entry["source"], entry["key"], where(entry), where(entry["site"]))
        for entry in node["parameters"]
    ]


NAV_LAUNCH = "src/nav_bringup/launch/bringup.launch.py"
NAV_PARAMS = "src/nav_bringup/config/nav2_params.yaml"
EKF = "src/nav_bringup/config/ekf.yaml"


def test_ros2_files_and_inline_dictionaries(run_cli: Any, tmp_path: Path) -> None:
    """navigation2's bringup: a FindPackageShare path and an inline dict on the
    controller server; a ParameterFile with a ``/**`` key and the node's own on the EKF;
    a file keyed to a name the node does not have (RN405's case) sets nothing."""
    nav_workspace(tmp_path)
    found = nodes(run_cli, tmp_path)
    server = "controller_server"
    assert settings(found["/controller_server"]) == [
        ("FollowPath.max_vel_x", "file", server, (NAV_PARAMS, 7), (NAV_LAUNCH, 28)),
        ("FollowPath.plugin", "file", server, (NAV_PARAMS, 6), (NAV_LAUNCH, 28)),
        ("controller_frequency", "file", server, (NAV_PARAMS, 3), (NAV_LAUNCH, 28)),
        ("controller_plugins", "file", server, (NAV_PARAMS, 4), (NAV_LAUNCH, 28)),
        ("use_sim_time", "launch", None, (NAV_LAUNCH, 28), None),
    ]
    ekf = "ekf_filter_node"
    assert settings(found["/ekf_filter_node"]) == [
        ("frequency", "file", ekf, (EKF, 6), (NAV_LAUNCH, 34)),
        ("two_d_mode", "file", ekf, (EKF, 7), (NAV_LAUNCH, 34)),
        ("use_sim_time", "file", "/**", (EKF, 3), (NAV_LAUNCH, 34)),
    ]
    assert settings(found["/fusion_core"]) == []


def test_ros1_params_rosparam_loads_and_group_loads(run_cli: Any, tmp_path: Path) -> None:
    """A move_base-style launch: a ``<param>`` and a ``<rosparam load>`` in the node, a
    group-level load into the node's namespace, and one into another namespace."""
    directory = planner_package(tmp_path)
    write(
        directory,
        "launch/planner.launch",
        "<launch>\n"
        '  <node pkg="slow_planner" type="slow_planner_node" name="slow_planner" args="_rate:=5">\n'
        '    <param name="max_vel_x" value="0.4"/>\n'
        '    <rosparam file="$(find slow_planner)/config/planner.yaml" command="load"/>\n'
        "  </node>\n"
        '  <rosparam file="$(find slow_planner)/config/costmap.yaml" command="load"\n'
        '            ns="slow_planner/local_costmap"/>\n'
        '  <rosparam file="$(find slow_planner)/config/costmap.yaml" command="load"\n'
        '            ns="global_costmap"/>\n'
        "</launch>\n",
    )
    write(directory, "config/costmap.yaml", "width: 6\nplugins:\n  inflation: true\n")
    launch, planner = "src/slow_planner/launch/planner.launch", "src/slow_planner/config/"
    assert settings(nodes(run_cli, tmp_path)["/slow_planner"]) == [
        (
            "local_costmap/plugins/inflation",
            "file",
            None,
            (planner + "costmap.yaml", 3),
            (launch, 6),
        ),
        ("local_costmap/width", "file", None, (planner + "costmap.yaml", 1), (launch, 6)),
        ("max_vel_x", "launch", None, (launch, 3), None),
        ("rate", "launch", None, (launch, 2), None),
        ("sim_time", "file", None, (planner + "planner.yaml", 1), (launch, 4)),
        ("vx_samples", "file", None, (planner + "planner.yaml", 2), (launch, 4)),
    ]


def test_drawings_list_a_node_parameters(run_cli: Any, tmp_path: Path) -> None:
    nav_workspace(tmp_path)
    dot = graph(run_cli, tmp_path, "dot")
    (server,) = [line for line in dot.splitlines() if 'label="/controller_server' in line]
    assert "\\nparam FollowPath.max_vel_x\\n" in server
    assert "\\nparam use_sim_time" in server
    assert f"parameters from {NAV_PARAMS}, {NAV_LAUNCH}" in dot
    mermaid = graph(run_cli, tmp_path, "mermaid")
    assert "<br>param FollowPath.max_vel_x<br>" in mermaid


def test_a_long_list_is_cut_short() -> None:
    def node(count: int) -> NodeInstance:
        place = Location("params.yaml", Span(1, 1, 1, 4))
        found = tuple(
            ParameterSetting(f"p{index:03}", place, SettingSource.FILE) for index in range(count)
        )
        return NodeInstance("/n", Generation.ROS2, None, None, "", (), (), parameter_settings=found)

    assert parameter_lines(node(0)) == ()
    assert parameter_lines(node(MAX_PARAMETERS))[-1] == f"param p{MAX_PARAMETERS - 1:03}"
    assert parameter_lines(node(MAX_PARAMETERS + 1))[-1] == "and 1 more parameter"
    assert parameter_lines(node(120))[-1] == f"and {120 - MAX_PARAMETERS} more parameters"
    assert len(parameter_lines(node(120))) == MAX_PARAMETERS + 1
