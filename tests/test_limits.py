"""Files too large or binary are skipped, and said so with --verbose; nothing else is.

A CI gate meets generated and vendored files (a 40 MB generated URDF, a launch file that
is really a zip): reading them costs time and says nothing about names written by hand.
"""

from __future__ import annotations

import codecs
from pathlib import Path
from typing import Any

from conftest import write

BAD_LAUNCH = """\
<launch>
  <!-- a hyphen: roslaunch refuses this name -->
  <node name="base-driver" pkg="base_driver" type="driver_node"/>
</launch>
"""


def check(run_cli: Any, root: Path, *options: str) -> Any:
    return run_cli(["check", "--format", "json", *options, "."], root)


def test_a_file_above_the_limit_is_skipped_and_said_so_with_verbose(
    run_cli: Any, tmp_path: Path
) -> None:
    padding = "  <!-- generated -->\n" * (6 * 1024 * 1024 // 21 + 1)
    write(
        tmp_path, "launch/generated.launch", BAD_LAUNCH.replace("</launch>", padding + "</launch>")
    )
    quiet = check(run_cli, tmp_path)
    assert (quiet.exit_code, quiet.findings()) == (0, [])
    assert "skipped" not in quiet.stderr
    verbose = check(run_cli, tmp_path, "--verbose")
    assert (
        "roslint-names: skipped launch/generated.launch: 6.0 MiB, above max-file-size (5.0 MiB)"
        in verbose.stderr.splitlines()
    )


def test_max_file_size_is_configurable(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "launch/robot.launch", BAD_LAUNCH)
    assert [f["code"] for f in check(run_cli, tmp_path).findings()] == ["RN101"]
    write(tmp_path, "roslint-names.toml", "max-file-size = 100\n")
    result = check(run_cli, tmp_path, "--verbose")
    assert (result.exit_code, result.findings()) == (0, [])
    assert "skipped launch/robot.launch: 0.0 MiB, above max-file-size (0.0 MiB)" in result.stderr
    assert result.stderr.splitlines()[-1] == "All checks passed: 0 files checked, no problems."


def test_a_bad_max_file_size_names_the_key_and_the_file(run_cli: Any, tmp_path: Path) -> None:
    write(tmp_path, "launch/robot.launch", BAD_LAUNCH)
    for value in ('"5MB"', "0", "true"):
        write(tmp_path, "roslint-names.toml", f"max-file-size = {value}\n")
        result = check(run_cli, tmp_path)
        assert result.exit_code == 2
        assert "roslint-names.toml" in result.stderr and "max-file-size" in result.stderr
        assert "Traceback" not in result.stderr


def test_a_binary_file_with_a_source_name_is_one_parse_error(run_cli: Any, tmp_path: Path) -> None:
    """A .launch that is not text is never passed over as clean: nothing is lost."""
    (tmp_path / "launch").mkdir()
    (tmp_path / "launch/firmware.launch").write_bytes(b"PK\x03\x04\x00\x00" + bytes(range(256)))
    (tmp_path / "launch/robot.launch").write_text(BAD_LAUNCH, encoding="utf-8")
    result = check(run_cli, tmp_path, "--verbose")
    assert [(f["path"], f["code"]) for f in result.findings()] == [
        ("launch/firmware.launch", "RN001"),
        ("launch/robot.launch", "RN101"),
    ]
    assert result.findings()[0]["message"].startswith("not a text file: a NUL byte")
    assert "skipped" not in result.stderr


def test_utf16_and_utf32_text_is_not_taken_for_binary(run_cli: Any, tmp_path: Path) -> None:
    """UTF-16 and UTF-32 are full of NUL bytes; the byte order mark says they are text."""
    for name, encoded in (
        ("little.launch", codecs.BOM_UTF16_LE + BAD_LAUNCH.encode("utf-16-le")),
        ("big.launch", codecs.BOM_UTF16_BE + BAD_LAUNCH.encode("utf-16-be")),
        ("little32.launch", codecs.BOM_UTF32_LE + BAD_LAUNCH.encode("utf-32-le")),
        ("big32.launch", codecs.BOM_UTF32_BE + BAD_LAUNCH.encode("utf-32-be")),
    ):
        path = tmp_path / "launch" / name
        path.parent.mkdir(exist_ok=True)
        path.write_bytes(encoded)
    result = check(run_cli, tmp_path, "--verbose")
    assert "skipped" not in result.stderr
    # One node name in four files is one decision: its finding names the other three.
    assert sorted(
        (place["path"], f["code"], place["line"])
        for f in result.findings()
        for place in (f, *f["related"])
    ) == [
        ("launch/big.launch", "RN101", 3),
        ("launch/big32.launch", "RN101", 3),
        ("launch/little.launch", "RN101", 3),
        ("launch/little32.launch", "RN101", 3),
    ]
