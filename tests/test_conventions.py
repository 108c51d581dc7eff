"""Conventions proposed: many findings one line of configuration answers."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import write, write_package

from roslint_names.conventions import Proposal, propose, render
from roslint_names.model import Answer, Diagnostic, Kind, Severity, Span


def _diagnostic(code: str, answer: tuple[str, str], **fields: Any) -> Diagnostic:
    return Diagnostic(
        "src/x.cpp",
        Span(1, 1, 1, 2),
        code,
        "r",
        Severity.WARNING,
        "m",
        answer=Answer(*answer),
        **fields,
    )


def test_a_global_tree_is_the_levels_its_names_share() -> None:
    """MoveIt's rviz plugin topics, autoware's /api services, and two names alone."""
    allow = "rules.RN202.extend-allow"
    names = [
        "/rviz/moveit/update_goal_state",
        "/rviz/moveit/update_start_state",
        "/rviz/moveit/move_marker/goal",
        "/api/autoware/get/engage",
        "/api/operation_mode/state",
        "/api/localization/initialize",
        "/joy",
        "/cmd_vel",
    ]
    diagnostics = [_diagnostic("RN202", (allow, name)) for name in names]
    diagnostics.append(_diagnostic("RN202", (allow, "/api/x/y"), suppressed=True))
    assert propose(diagnostics) == [
        Proposal("rules.RN202", "extend-allow", '["/api/**", "/rviz/moveit/**"]', "RN202", 6)
    ]


def test_a_deep_tree_needs_enough_findings_and_its_deepest_level() -> None:
    deep = [_diagnostic("RN201", ("max-depth", str(levels))) for levels in (5, 7, 6, 5)]
    assert propose(deep) == []  # four: not yet a convention
    deep.append(_diagnostic("RN201", ("max-depth", "6")))
    [proposal] = propose(deep)
    assert render([proposal]) == (
        "5 findings are one decision: if the names are this project's convention, state it "
        "in roslint-names.toml ([tool.roslint-names] in pyproject.toml), else fix them:\n"
        "  max-depth = 7                                 # RN201: 5 findings\n"
    )


# An Autoware-shaped planning launch file: every module's debug output is deep by design.
PLANNING_LAUNCH = """<launch>
  <node pkg="autoware_path_planner" exec="path_planner_node" name="path_planner">
    <remap from="~/output/path" to="/planning/scenario_planning/lane_driving/path_planner/path"/>
    <remap from="~/debug/a" to="/planning/scenario_planning/lane_driving/debug/a/markers"/>
    <remap from="~/debug/b" to="/planning/scenario_planning/lane_driving/debug/b/markers"/>
    <remap from="~/debug/c" to="/planning/scenario_planning/lane_driving/debug/c/markers"/>
    <remap from="~/debug/d" to="/planning/scenario_planning/lane_driving/debug/d/markers"/>
  </node>
</launch>
"""


def test_a_project_without_configuration_is_told_its_convention(
    run_cli: Any, tmp_path: Path
) -> None:
    write_package(tmp_path / "src/planning_launch", 2, "planning_launch")
    write(tmp_path, "src/planning_launch/launch/planning.launch.xml", PLANNING_LAUNCH)
    first = run_cli(["check", "--no-cache", "."], tmp_path)
    assert "5 findings are one decision" in first.stderr
    assert "  max-depth = 6" in first.stderr
    # Stated, the findings are gone; a project with a configuration is not told again.
    write(tmp_path, "roslint-names.toml", "max-depth = 6\n")
    assert run_cli(["check", "--no-cache", "."], tmp_path).exit_code == 0
    write(tmp_path, "roslint-names.toml", "max-depth = 4\n")
    configured = run_cli(["check", "--no-cache", "."], tmp_path)
    assert configured.exit_code == 1 and "one decision" not in configured.stderr
    # --statistics always proposes it, with the counts.
    statistics = run_cli(["check", "--no-cache", "--statistics", "."], tmp_path)
    assert "  max-depth = 6" in statistics.stdout


def _named(value: str, package: str | None, kind: Kind = Kind.NODE, **fields: Any) -> Diagnostic:
    answer = Answer("rules.RN203.ignore-names", value, kind)
    return Diagnostic(
        f"{package}/src/x.cpp",
        Span(1, 1, 1, 2),
        "RN203",
        "not-snake-case",
        Severity.WARNING,
        "m",
        answer=answer,
        package=package,
        **fields,
    )


def test_camel_case_names_are_a_convention_of_one_package_and_one_kind() -> None:
    image_proc = ["DebayerNode", "RectifyNode", "ResizeNode", "ImagePublisher", "cropFilter"]
    diagnostics = [_named(name, "image_proc") for name in image_proc]
    diagnostics.append(_named("DebayerNode", "image_proc"))  # another use: one name
    diagnostics.append(_named("TrackMarkerNode", "image_view"))  # alone, but covered
    diagnostics.append(_named("StereoNode", "image_view", suppressed=True))
    # Four node names and four parameters of a package of another repository: neither is
    # a convention yet.
    diagnostics += [_named(f"Stage{index}Filter", "vision/stereo_image_proc") for index in range(4)]
    diagnostics += [
        _named(name, "vision/stereo_image_proc", Kind.PARAMETER)
        for name in ("minDisparity", "maxDisparity", "uniquenessRatio", "speckleSize")
    ]
    assert propose(diagnostics) == [
        Proposal(
            "rules.RN203",
            "ignore-names",
            '["*Node", "ImagePublisher", "cropFilter"]',
            "RN203",
            7,  # both DebayerNode findings, and image_view's TrackMarkerNode
        )
    ]


def test_a_convention_holds_in_the_packages_beside_the_one_stating_it() -> None:
    """image_pipeline: depth_image_proc names its component nodes ``XxxNode``;
    image_publisher, beside it in the repository, names its one ``ImagePublisher``. A
    package in another directory, or names of another kind, do not follow."""
    stating = ["ConvertMetricNode", "CropForemostNode", "DisparityNode", "RegisterNode"]
    stating.append("PointCloudXyzNode")
    diagnostics = [_named(name, "src/image_pipeline/depth_image_proc") for name in stating]
    diagnostics.append(_named("ImagePublisher", "src/image_pipeline/image_publisher"))
    diagnostics.append(_named("kernelSize", "src/image_pipeline/image_publisher", Kind.PARAMETER))
    diagnostics.append(_named("TeleopTwist", "src/teleop/teleop_twist"))
    [proposal] = propose(diagnostics)
    assert proposal.value == '["*Node", "ImagePublisher"]'
    assert proposal.findings == 6


def test_a_package_of_camel_case_parameters_lists_them_by_their_last_word() -> None:
    names = ["maxUrange", "maxRange", "linearUpdate", "angularUpdate", "temporalUpdate"]
    names += ["TrajectoryPlannerROS", "cmd__vel"]
    diagnostics = [_named(name, "", Kind.PARAMETER) for name in names]  # the run's root
    [proposal] = propose(diagnostics)
    # Two names ending in "Range" are not enough for "*Range"; "cmd__vel" ends in no word.
    assert proposal.value == (
        '["*Update", "TrajectoryPlannerROS", "cmd__vel", "maxRange", "maxUrange"]'
    )
    assert proposal.findings == 7
