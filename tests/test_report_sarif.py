"""The SARIF 2.1.0 report: schema-valid, GitHub-ready, byte-for-byte deterministic."""

from __future__ import annotations

import json
import os
import re
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest
import report_sample as sample
from jsonschema import Draft7Validator

from roslint_names import PROJECT_URL
from roslint_names.model import Diagnostic, Edit, RelatedLocation, Severity, Span
from roslint_names.report import render
from roslint_names.report.sarif import artifact_location, root_uri, semantic_version

FIXTURES = Path(__file__).parent / "fixtures" / "report"
# The official schema, kept with the tests (fixtures/schemas/README.md says whence and
# under which terms); ROSLINT_SARIF_SCHEMA points at another copy.
SCHEMA = Path(
    os.environ.get("ROSLINT_SARIF_SCHEMA")
    or Path(__file__).parent / "fixtures" / "schemas" / "sarif-schema-2.1.0.json"
)
FINGERPRINT = re.compile(r"^[0-9a-f]{16}:[1-9][0-9]*$")
LINK = re.compile(r"(?<!\\)\[(?:[^\\\[\]]|\\.)*\]\((\d+)\)")


def sarif(diagnostics: tuple[Diagnostic, ...] = sample.DIAGNOSTICS, **changes: object) -> str:
    return render("sarif", diagnostics, sample.RULES, sample.context(**changes))


def log(diagnostics: tuple[Diagnostic, ...] = sample.DIAGNOSTICS, **changes: object) -> Any:
    return json.loads(sarif(diagnostics, **changes))


def results(diagnostics: tuple[Diagnostic, ...] = sample.DIAGNOSTICS, **changes: object) -> Any:
    return log(diagnostics, **changes)["runs"][0]["results"]


def keys(value: Any) -> set[str]:
    """Every key at any depth of a JSON value."""
    if isinstance(value, dict):
        return set(value).union(*(keys(item) for item in value.values()))
    if isinstance(value, list):
        return set().union(*(keys(item) for item in value))
    return set()


@pytest.fixture(scope="module")
def validator() -> Draft7Validator:
    schema = json.loads(SCHEMA.read_text(encoding="utf-8"))
    return Draft7Validator(schema, format_checker=Draft7Validator.FORMAT_CHECKER)


OUTSIDE = (
    replace(sample.RN101, path="../other_ws/src/x.launch"),
    replace(sample.RN101, path="/opt/ros/noetic/share/x/launch/x.launch"),
    replace(sample.RN101, path="src/odd:name,with%signs#and?query.launch"),
    replace(sample.RN101, span=Span(3, 9, 5, 2), message="multi-line span"),
    replace(sample.RN101, code="RN999", rule_name="from-a-plugin", message="no metadata given"),
)


# A rename: its own edit, one more in its file and one in a launch file of another package.
RENAME = replace(
    sample.RN101,
    edit=Edit(Span(12, 22, 12, 33), "base_driver", False),
    also=(
        Edit(Span(20, 22, 20, 33), "base_driver", False, sample.RN101.path),
        Edit(Span(3, 15, 3, 26), "base_driver", False, "src/robot/launch/robot.launch"),
    ),
)


@pytest.mark.parametrize(
    ("diagnostics", "changes"),
    [
        (sample.DIAGNOSTICS, {}),
        (sample.DIAGNOSTICS, {"include_suppressed": True}),
        ((), {}),
        (OUTSIDE, {"root": Path("/home/dev/my ws")}),
        (sample.DIAGNOSTICS, {"tool_version": "1.2.0rc1.dev4+g0a1b2c3"}),
        (
            (replace(sample.RN101, baselined=True), *sample.DIAGNOSTICS[1:]),
            {"baseline": True},
        ),
        (
            (replace(sample.RN101, edit=Edit(Span(12, 22, 12, 33), "base_driver", False)),),
            {},
        ),
        ((RENAME,), {}),
    ],
    ids=[
        "default",
        "with-suppressed",
        "empty",
        "odd-paths",
        "dev-version",
        "baseline",
        "fix",
        "rename",
    ],
)
def test_valid_against_the_official_schema(
    validator: Draft7Validator, diagnostics: tuple[Diagnostic, ...], changes: dict[str, object]
) -> None:
    errors = sorted(validator.iter_errors(log(diagnostics, **changes)), key=str)
    assert not errors, "\n".join(f"{list(e.absolute_path)}: {e.message}" for e in errors)


def test_log_header_and_run() -> None:
    loaded = log()
    assert loaded["$schema"] == "https://json.schemastore.org/sarif-2.1.0.json"
    assert loaded["version"] == "2.1.0"
    (run,) = loaded["runs"]
    assert run["columnKind"] == "unicodeCodePoints"
    assert run["invocations"] == [{"executionSuccessful": True}]
    assert run["originalUriBaseIds"] == {"%SRCROOT%": {"uri": "file:///home/dev/catkin_ws/"}}


def test_driver() -> None:
    driver = log()["runs"][0]["tool"]["driver"]
    assert driver["name"] == "roslint-names"
    assert driver["version"] == "0.1.0"
    assert driver["semanticVersion"] == "0.1.0"
    assert driver["informationUri"] == PROJECT_URL


def test_every_rule_given_is_described_sorted_by_code() -> None:
    rules = log(())["runs"][0]["tool"]["driver"]["rules"]
    assert [rule["id"] for rule in rules] == ["RN101", "RN202", "RN203", "RN401"]
    by_code = {meta.code: meta for meta in sample.RULES}
    for rule in rules:
        meta = by_code[rule["id"]]
        assert rule["name"] == meta.name
        assert rule["shortDescription"] == {"text": meta.summary}
        assert rule["fullDescription"] == {"text": meta.full_description}
        assert rule["help"]["markdown"] == meta.help_markdown
        assert rule["help"]["text"]
        assert meta.help_uri in rule["help"]["markdown"]  # GitHub ignores helpUri
        assert rule["helpUri"] == meta.help_uri
        assert rule["defaultConfiguration"] == {"level": meta.severity.value}
        assert rule["properties"]["tags"] == ["ros", "naming"]


def test_naming_is_not_a_security_alert() -> None:
    assert "security-severity" not in keys(log(include_suppressed=True))


def test_result_fields() -> None:
    loaded = log((sample.RN101,))
    rules = loaded["runs"][0]["tool"]["driver"]["rules"]
    (result,) = loaded["runs"][0]["results"]
    assert result["ruleId"] == "RN101"
    assert rules[result["ruleIndex"]]["id"] == "RN101"
    assert result["level"] == "error"
    assert result["message"] == {"text": sample.RN101.message}
    (location,) = result["locations"]
    assert location["physicalLocation"] == {
        "artifactLocation": {
            "uri": "src/robot_bringup/launch/robot.launch",
            "uriBaseId": "%SRCROOT%",
        },
        "region": {"startLine": 12, "startColumn": 15, "endLine": 12, "endColumn": 26},
    }
    assert "suppressions" not in result


def test_rule_index_points_at_the_rule_of_every_result() -> None:
    loaded = log()
    rules = loaded["runs"][0]["tool"]["driver"]["rules"]
    for result in loaded["runs"][0]["results"]:
        assert rules[result["ruleIndex"]]["id"] == result["ruleId"]
        assert result["level"] in ("error", "warning")


def test_a_result_without_rule_metadata_has_no_rule_index() -> None:
    (result,) = results((OUTSIDE[-1],))
    assert result["ruleId"] == "RN999"
    assert "ruleIndex" not in result


def test_uris_are_relative_and_percent_encoded() -> None:
    uris = [r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in results()]
    assert uris == [
        "src/robot_bringup/launch/robot.launch",
        "src/robot_bringup/launch/robot.launch",
        "src/teleop/src/teleop_node.cpp",
        "src/%C3%BCn%C3%AFcode%20pkg/src/bras_robot.py",
    ]


def test_artifact_locations_outside_the_root_are_absolute_file_uris() -> None:
    root = Path("/home/dev/my ws")
    assert root_uri(root) == "file:///home/dev/my%20ws/"
    assert root_uri(Path("/")) == "file:///"
    assert artifact_location("../other_ws/src/x.launch", root) == {
        "uri": "file:///home/dev/other_ws/src/x.launch"
    }
    assert artifact_location("/opt/ros/x.launch", root) == {"uri": "file:///opt/ros/x.launch"}
    assert artifact_location("./src/a#b?.launch", root) == {
        "uri": "src/a%23b%3F.launch",
        "uriBaseId": "%SRCROOT%",
    }
    assert artifact_location("a:b/c.launch", root)["uri"] == "a%3Ab/c.launch"  # not a scheme


def test_related_locations_are_linked_from_the_message() -> None:
    (result,) = results((sample.RN401,))
    (related,) = result["relatedLocations"]
    assert related == {
        "id": 1,
        "physicalLocation": {
            "artifactLocation": {
                "uri": "src/teleop/scripts/joy%20teleop.py",
                "uriBaseId": "%SRCROOT%",
            },
            "region": {"startLine": 9, "startColumn": 23, "endLine": 9, "endColumn": 33},
        },
        "message": {"text": "'/Cmd_Vel' is used here"},
    }
    assert result["message"]["text"] == (
        "topic '/cmd_vel' differs only in case from '/Cmd_Vel'. "
        "Related location: [src/teleop/scripts/joy teleop.py:9](1)."
    )


def test_every_embedded_link_resolves_to_exactly_one_related_location() -> None:
    second = RelatedLocation("launch/[x]/b.launch", Span(2, 3, 2, 9), "and here")
    diagnostic = replace(sample.RN401, related=(*sample.RN401.related, second))
    (result,) = results((diagnostic,))
    text = result["message"]["text"]
    ids = [location["id"] for location in result["relatedLocations"]]
    assert [int(target) for target in LINK.findall(text)] == ids == [1, 2]
    assert "[launch/\\[x\\]/b.launch:2](2)" in text  # brackets in link text are escaped


def test_braces_in_messages_are_doubled() -> None:
    (result,) = results((sample.RN203_BRACES,))
    assert result["message"]["text"] == (
        "topic token '{{robot}}Odom' of '{{robot}}Odom/raw' is not snake_case; use 'odom'"
    )


def test_fingerprints_are_set_and_stable() -> None:
    first = [r["partialFingerprints"]["primaryLocationLineHash"] for r in results()]
    assert all(FINGERPRINT.match(fingerprint) for fingerprint in first)
    assert len(set(first)) == len(first)
    # moving the finding (lines added above, re-indented) keeps its fingerprint
    moved = replace(
        sample.RN101,
        span=Span(40, 9, 40, 20),
        source_line='<node  name="base-driver"  pkg="base_driver" type="driver_node"/>',
    )
    again = results((moved, *sample.DIAGNOSTICS[1:]))
    assert again[0]["partialFingerprints"]["primaryLocationLineHash"] == first[0]


def test_identical_lines_are_counted() -> None:
    twin = replace(sample.RN101, span=Span(30, 15, 30, 26))
    fingerprints = [
        r["partialFingerprints"]["primaryLocationLineHash"] for r in results((sample.RN101, twin))
    ]
    digest = fingerprints[0].split(":")[0]
    assert fingerprints == [f"{digest}:1", f"{digest}:2"]


def test_fingerprints_do_not_depend_on_showing_suppressed_results() -> None:
    def by_line(include_suppressed: bool) -> dict[int, str]:
        found = results(sample.DIAGNOSTICS, include_suppressed=include_suppressed)
        return {
            r["locations"][0]["physicalLocation"]["region"]["startLine"]: r["partialFingerprints"][
                "primaryLocationLineHash"
            ]
            for r in found
        }

    hidden, shown = by_line(False), by_line(True)
    assert set(shown) - set(hidden) == {15}
    assert all(shown[line] == fingerprint for line, fingerprint in hidden.items())


def test_suppressed_results_are_left_out_by_default() -> None:
    assert results((sample.RN101_SUPPRESSED,)) == []
    assert "lidar.front" not in sarif()


def test_suppressed_results_can_be_included() -> None:
    marked = [r for r in results(include_suppressed=True) if "suppressions" in r]
    assert len(marked) == 1
    assert marked[0]["suppressions"] == [{"kind": "inSource"}]
    assert "lidar.front" in marked[0]["message"]["text"]


def test_no_timestamps_and_identical_bytes() -> None:
    assert sarif() == sarif()
    assert sarif(include_suppressed=True) == sarif(include_suppressed=True)
    assert not {key for key in keys(log()) if "time" in key.lower()}


def test_layout() -> None:
    text = sarif()
    assert text.startswith('{\n  "$schema": ')
    assert text.endswith("}\n") and not text.endswith("\n\n")
    assert "ünïcode" not in text  # the path is percent-encoded in the URI...
    assert "'/bras/état'" in text  # ...and the message is written as UTF-8, unescaped


def test_no_findings_still_describes_the_rules() -> None:
    run = log(())["runs"][0]
    assert run["results"] == []
    assert len(run["tool"]["driver"]["rules"]) == len(sample.RULES)


@pytest.mark.parametrize(
    ("version", "expected"),
    [
        ("0.1.0", "0.1.0"),
        ("1.2.3-rc.1+build.5", "1.2.3-rc.1+build.5"),
        ("0.0.0+source", "0.0.0+source"),
        ("1.2", "1.2.0"),
        ("1.2.0rc1", "1.2.0-rc.1"),
        ("1.2.0a2", "1.2.0-alpha.2"),
        ("1.2.0.dev3", "1.2.0-dev.3"),
        ("1.2.0rc1.dev4+g0a1b2c3", "1.2.0-rc.1.dev.4+g0a1b2c3"),
        ("1.2.0.post1", "1.2.0+post.1"),
        ("unknown", None),
    ],
)
def test_semantic_version(version: str, expected: str | None) -> None:
    assert semantic_version(version) == expected


def test_snapshot() -> None:
    path = FIXTURES / "expected.sarif"
    actual = sarif(include_suppressed=True)
    if os.environ.get("ROSLINT_UPDATE_SNAPSHOTS"):
        path.write_text(actual, encoding="utf-8", newline="\n")
    assert actual == path.read_text(encoding="utf-8"), "expected.sarif changed; review the diff"


def test_severity_maps_to_level() -> None:
    levels = {r["ruleId"]: r["level"] for r in results()}
    assert levels == {"RN101": "error", "RN203": "warning", "RN401": "warning", "RN202": "warning"}
    warning = replace(sample.RN101, severity=Severity.WARNING)  # configured down
    assert results((warning,))[0]["level"] == "warning"


URI_REFERENCE = re.compile(r"^(?:[A-Za-z0-9\-._~:/?#\[\]@!$&'()*+,;=]|%[0-9A-F]{2})+$")


def test_every_uri_is_a_well_formed_rfc3986_reference() -> None:
    def uris(value: Any) -> list[str]:
        if isinstance(value, dict):
            own = [value["uri"]] if isinstance(value.get("uri"), str) else []
            return own + [uri for item in value.values() for uri in uris(item)]
        if isinstance(value, list):
            return [uri for item in value for uri in uris(item)]
        return []

    found = uris(log(OUTSIDE + sample.DIAGNOSTICS, root=Path("/home/dev/my ws")))
    assert len(found) > len(OUTSIDE)
    for uri in found:
        assert URI_REFERENCE.match(uri), uri
        assert "/../" not in uri and not uri.startswith("../")


def test_a_rule_without_a_catalog_page_still_has_help(validator: Draft7Validator) -> None:
    bare = replace(sample.RULES[1], full_description="", help_markdown="", help_uri="")
    loaded = json.loads(render("sarif", (sample.RN101,), (bare,), sample.context()))
    (rule,) = loaded["runs"][0]["tool"]["driver"]["rules"]
    assert rule["fullDescription"] == {"text": bare.summary}
    assert rule["help"] == {"text": bare.summary, "markdown": bare.summary}
    assert "helpUri" not in rule
    assert not list(validator.iter_errors(loaded))


def test_a_rename_is_one_fix_with_a_change_per_file() -> None:
    (result,) = results((RENAME,))
    (fix,) = result["fixes"]
    assert fix["description"]["text"] == (
        "write 'base_driver', and 2 other uses (unsafe (--unsafe-fixes) fix)"
    )
    changes = [
        (
            change["artifactLocation"]["uri"],
            [r["deletedRegion"]["startLine"] for r in change["replacements"]],
        )
        for change in fix["artifactChanges"]
    ]
    assert changes == [(sample.RN101.path, [12, 20]), ("src/robot/launch/robot.launch", [3])]
