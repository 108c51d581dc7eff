"""Configuration files: discovery, every key, and errors that name the key and the file."""

from __future__ import annotations

import random
import re
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from conftest import write

from roslint_names.config import (
    ConfigError,
    Settings,
    enabled_codes,
    find_config,
    load_settings,
    template_to_regex,
)
from roslint_names.model import Generation, Kind, Severity
from roslint_names.registry import load_registry

REGISTRY = load_registry()
LAUNCH = """<launch>
  <node name="baseDriver" pkg="robot_base" type="driver_node">
    <remap from="cmd_vel" to="base/Cmd_Vel/"/>
  </node>
</launch>
"""


def settings_from(tmp_path: Path, text: str, filename: str = "roslint-names.toml") -> Settings:
    write(tmp_path, filename, text)
    return load_settings(None, tmp_path, REGISTRY)


def test_every_key_is_read(tmp_path: Path) -> None:
    settings = settings_from(
        tmp_path,
        """
ros = 1
select = ["RN1", "RN2"]
extend-select = ["RN002"]
ignore = ["not-snake-case"]
exclude = ["third_party/"]
max-depth = 6
max-file-size = 1048576
per-file-ignores = { "test/**" = ["RN101"] }
[severity]
RN203 = "error"
[rules.RN201]
[naming]
topic = { template = "/{robot}/{function}" }
node = '[a-z_]+'
""",
    )
    assert settings.ros is Generation.ROS1
    assert settings.select == ("RN1", "RN2")
    assert settings.extend_select == ("RN002",)
    assert settings.ignore == ("not-snake-case",)
    assert settings.exclude == ("third_party/",)
    assert settings.max_depth == 6
    assert settings.max_file_size == 1024 * 1024
    assert settings.per_file_ignores == (("test/**", ("RN101",)),)
    assert settings.severity == {"RN203": Severity.ERROR}
    assert [(policy.kind, policy.description) for policy in settings.policies] == [
        (Kind.TOPIC, "/{robot}/{function}"),
        (Kind.NODE, "[a-z_]+"),
    ]
    assert settings.root == tmp_path.resolve()


def test_rn203_ignore_names_are_read(tmp_path: Path) -> None:
    settings = settings_from(
        tmp_path, '[rules.not-snake-case]\nignore-names = ["*Node", "minimumScore", "~/Base.*"]\n'
    )
    assert settings.rule_options == {
        "RN203": {"ignore-names": ("*Node", "minimumScore", "~/Base.*")}
    }


def test_pyproject_without_our_table_is_passed_over(tmp_path: Path) -> None:
    write(tmp_path, "roslint-names.toml", "max-depth = 7\n")
    write(tmp_path, "pkg/pyproject.toml", "[tool.black]\nline-length = 100\n")
    assert find_config(tmp_path / "pkg") == tmp_path / "roslint-names.toml"
    write(tmp_path, "pkg/pyproject.toml", "[tool.roslint-names]\nmax-depth = 3\n")
    assert load_settings(None, tmp_path / "pkg", REGISTRY).max_depth == 3


def test_most_specific_selector_wins(tmp_path: Path) -> None:
    settings = settings_from(
        tmp_path, 'select = ["RN"]\nignore = ["RN2"]\nextend-select = ["RN203"]\n'
    )
    enabled = enabled_codes(settings, REGISTRY)
    assert "RN203" in enabled
    assert "RN201" not in enabled
    assert "RN101" in enabled


def test_default_selection_leaves_off_by_default_rules_out(tmp_path: Path) -> None:
    enabled = enabled_codes(Settings(root=tmp_path), REGISTRY)
    assert "RN002" not in enabled
    assert {"RN001", "RN101", "RN102", "RN203"} <= enabled


@pytest.mark.parametrize(
    ("text", "key"),
    [
        ("colour = true\n", "colour"),
        ("max-depth = 0\n", "max-depth"),
        ('max-depth = "4"\n', "max-depth"),
        ('max-file-size = "5MB"\n', "max-file-size"),
        ("max-file-size = -1\n", "max-file-size"),
        ("ros = 3\n", "ros"),
        ('select = ["RN999"]\n', "select"),
        ('select = "RN1"\n', "select"),
        ('[severity]\nRN101 = "fatal"\n', "severity.RN101"),
        ('[severity]\nRN777 = "error"\n', "severity.RN777"),
        ("[rules.RN101]\nstrict = true\n", "rules.RN101.strict"),
        ('[naming]\ntopic = "([a-z"\n', "naming.topic.regex"),
        ('[naming]\nrobot = "[a-z]+"\n', "naming.robot"),
        ('[naming]\ntopic = { glob = "*" }\n', "naming.topic"),
        ('per-file-ignores = { "test/**" = ["RN1000"] }\n', "per-file-ignores"),
        # Patterns git would not accept: they stopped the run with an "internal error".
        ('exclude = ["!"]\n', "exclude: invalid pattern '!'"),
        ('exclude = ["vendor/[z-a]*"]\n', "exclude: invalid pattern 'vendor/[z-a]*'"),
        ('per-file-ignores = { "test/\\\\" = ["RN2"] }\n', "per-file-ignores: invalid pattern"),
        ('[test-code]\npaths = ["!"]\n', "test-code.paths: invalid pattern '!'"),
        # Nested quantifiers: a name they do not match takes minutes to reject.
        ('[naming]\nnode = "(a+)+$"\n', "naming.node.regex: '(a+)+$' repeats a part"),
        ("[naming]\ntopic = { regex = '^/([a-z][a-z0-9_]*)+$' }\n", "naming.topic.regex"),
        # ignore-names: '*' is its only wildcard; a pattern for every name is RN203 off.
        ('[rules.RN203]\nignore-names = ["Node?"]\n', "rules.RN203.ignore-names: invalid"),
        ('[rules.RN203]\nignore-names = ["[A-Z]*Node"]\n', "rules.RN203.ignore-names"),
        ('[rules.RN203]\nignore-names = [""]\n', "rules.RN203.ignore-names: invalid"),
        ('[rules.not-snake-case]\nignore-names = ["**"]\n', "not-snake-case.ignore-names"),
        ('[rules.RN203]\nignore-names = "*Node"\n', "rules.RN203.ignore-names: must be a list"),
        ('[rules.RN203]\nextend-ignore-names = ["*Node"]\n', "known: ignore-names"),
    ],
)
def test_bad_values_name_the_key_and_the_file(tmp_path: Path, text: str, key: str) -> None:
    with pytest.raises(ConfigError) as raised:
        settings_from(tmp_path, text)
    message = str(raised.value)
    assert str(tmp_path / "roslint-names.toml") in message
    assert key in message


def test_invalid_toml_is_a_config_error(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="invalid TOML"):
        settings_from(tmp_path, "select = [\n")


def test_cli_exits_2_on_a_bad_key(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, ".roslint-names.toml", "max_depth = 3\n")
    write(tmp_path, "robot.launch", LAUNCH)
    result = run_cli(["check", "robot.launch"], tmp_path)
    assert result.exit_code == 2
    assert "max_depth: unknown key" in result.stderr
    assert ".roslint-names.toml" in result.stderr
    assert "Traceback" not in result.stderr


def test_config_changes_what_is_reported(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "robot.launch", LAUNCH)
    default = run_cli(["check", "--format", "json", "robot.launch"], tmp_path)
    # ROS 1 (type= says so) strips the trailing slash: a warning, and 'Cmd_Vel' is still bad style.
    assert default.codes() == ["RN203", "RN102", "RN203"]
    write(
        tmp_path,
        "roslint-names.toml",
        'ignore = ["RN102"]\n[severity]\nnot-snake-case = "error"\n',
    )
    configured = run_cli(["check", "--format", "json", "robot.launch"], tmp_path)
    assert configured.codes() == ["RN203", "RN203"]
    assert {finding["severity"] for finding in configured.findings()} == {"error"}


def test_per_file_ignores(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "test/robot.launch", LAUNCH)
    write(tmp_path, "launch/robot.launch", LAUNCH)
    write(tmp_path, "roslint-names.toml", 'per-file-ignores = { "test/**" = ["RN2"] }\n')
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    by_path = sorted((finding["path"], finding["code"]) for finding in result.findings())
    assert by_path == [
        ("launch/robot.launch", "RN102"),
        ("launch/robot.launch", "RN203"),
        ("launch/robot.launch", "RN203"),
        ("test/robot.launch", "RN102"),
    ]


def test_template_fields_are_snake_case_tokens() -> None:
    pattern = re.compile(template_to_regex("/{site}/{robot}/cmd_vel"))
    assert pattern.fullmatch("/warehouse_a/amr_07/cmd_vel")
    assert not pattern.fullmatch("/warehouse_a/AMR/cmd_vel")
    assert not pattern.fullmatch("/warehouse_a/amr_07/extra/cmd_vel")


def test_invalid_exclude_pattern_exits_2_naming_the_key(run_cli: Any, tmp_path: Path) -> None:
    configured = tmp_path / "configured"
    write(configured, "roslint-names.toml", 'exclude = ["third_party/", "[z-a]"]\n')
    write(configured, "launch/robot.launch", LAUNCH)
    result = run_cli(["check", "."], configured)
    assert result.exit_code == 2
    assert result.stderr == (
        f"roslint-names: error: {configured / 'roslint-names.toml'}: exclude: "
        "invalid pattern '[z-a]': bad character range z-a\n"
    )
    write(tmp_path, "plain/launch/robot.launch", LAUNCH)
    option = run_cli(["check", "--extend-exclude", "!", "."], tmp_path / "plain")
    assert option.exit_code == 2
    assert option.stderr == (
        "roslint-names: error: --extend-exclude: invalid pattern '!': git does not accept it\n"
    )


# Repetitions of a part that matches one way: each repetition starts or ends with a
# character the varying part inside cannot match, or its branches start apart.
LINEAR_POLICIES = [
    template_to_regex("/{site}/{robot}/{function}"),
    "[a-z][a-z0-9_]*",
    "^[a-z][a-z0-9]*(_[a-z0-9]+)*$",
    "(/[a-z_]+)+",
    "([a-z]+_)*[a-z]+",
    "^(/[a-z]+(_[a-z]+)*)+$",
    "(?:/(?:left|right)_arm_[0-9]+)+",
    "(foo|bar|baz)+",
    "(a|ab)+",
    # A possessive repetition: Python's re has them from 3.11 on (3.10 refuses the
    # pattern, as a configuration error that names it).
    pytest.param(
        "(a++)+",
        marks=pytest.mark.skipif(sys.version_info < (3, 11), reason="re has no a++ before 3.11"),
    ),
]
# Each can share one text among its repetitions in many ways: exponential on a miss.
BACKTRACKING_POLICIES = [
    "(a+)+$",
    "(a*)*",
    "(a|aa)+",
    "(?:a|a)*x",
    "(a|b|ab)+",
    "(a?)+",
    "(.*)+",
    r"(\w+_?)+",
    r"(_\w+)*",
    r"(\d+\s?)+",
    "^/([a-z][a-z0-9_]*)+$",
    "(?:[a-z]+/?)+",
    "(?i)(A[a-z]+)+",
    "((ab)*)+",
    "(|foo)+",
]


@pytest.mark.parametrize("pattern", BACKTRACKING_POLICIES)
def test_policies_that_backtrack_without_bound_are_refused(tmp_path: Path, pattern: str) -> None:
    write(tmp_path, "roslint-names.toml", f"[naming]\nnode = '{pattern}'\n")
    with pytest.raises(ConfigError, match=re.escape(f"naming.node.regex: {pattern!r} repeats")):
        load_settings(None, tmp_path, REGISTRY)


@pytest.mark.parametrize("pattern", LINEAR_POLICIES)
def test_policies_that_match_one_way_are_kept_and_fail_fast(tmp_path: Path, pattern: str) -> None:
    """Accepted, and quick to reject the names most likely to make them backtrack: a
    run of each of their characters, and random mixes of them, ending in a misfit."""
    write(tmp_path, "roslint-names.toml", f"[naming]\nnode = '{pattern}'\n")
    [policy] = load_settings(None, tmp_path, REGISTRY).policies
    compiled = re.compile(policy.pattern)
    alphabet = sorted({c for c in pattern if c.isalnum() or c in "_/"})
    chooser = random.Random(206)
    names = [c * 34 + "!" for c in alphabet]
    names += ["".join(chooser.choices(alphabet, k=34)) + "!" for _ in range(300)]
    started = time.perf_counter()
    for name in names:
        compiled.fullmatch(name)
    assert time.perf_counter() - started < 1.0
