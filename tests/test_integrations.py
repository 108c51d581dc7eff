"""The ament and catkin integrations under integrations/, run with real CMake.

No ROS installation here: ament_cmake_test's ament_add_test() and catkin's
catkin_run_tests_target() are stood in for by functions that record their arguments and
register the command with CTest, as the real ones do. What is tested is ours: the
modules' invocation, the entry point's arguments, and the JUnit file the test writes.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from conftest import write, write_package
from lxml import etree

INTEGRATIONS = Path(__file__).resolve().parents[1] / "integrations"
SCHEMA = etree.XMLSchema(etree.parse(str(Path(__file__).parent / "fixtures/schemas/junit-10.xsd")))
CMAKE = shutil.which("cmake", path=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}")
pytestmark = pytest.mark.skipif(
    CMAKE is None, reason="cmake is a test extra: pip install '.[test]'"
)

sys.path.insert(0, str(INTEGRATIONS / "ament_roslint_names"))
from ament_roslint_names.main import main as ament_roslint_names  # noqa: E402

BRINGUP_LAUNCH = """<launch>
  <node pkg="teleop_twist_joy" exec="teleop_node" name="teleop-twist">
    <remap from="cmd_vel" to="/cmd_vel"/>
  </node>
</launch>
"""
FIXTURE_LAUNCH = """<launch>
  <node pkg="demo" exec="demo_node" name="bad name on purpose"/>
</launch>
"""


def _package(root: Path) -> Path:
    package = root / "robot_bringup"
    write_package(package, 2)
    write(package, "launch/robot.launch.xml", BRINGUP_LAUNCH)
    write(package, "test/fixtures/broken.launch.xml", FIXTURE_LAUNCH)
    return package


def _environment(bin_directory: Path) -> dict[str, str]:
    """PATH with the entry points first: ``ament_roslint_names`` from integrations/ (not
    installed here) and this interpreter's ``roslint-names``."""
    bin_directory.mkdir(exist_ok=True)
    launcher = bin_directory / "ament_roslint_names"
    launcher.write_text(
        f"#!{sys.executable}\n"
        "import sys\n"
        f"sys.path.insert(0, {str(INTEGRATIONS / 'ament_roslint_names')!r})\n"
        "from ament_roslint_names.main import main\n"
        "sys.exit(main())\n",
        encoding="utf-8",
    )
    launcher.chmod(0o755)
    path = os.pathsep.join(
        (str(bin_directory), str(Path(sys.executable).parent), os.environ["PATH"])
    )
    return {**os.environ, "PATH": path, "XDG_CACHE_HOME": str(bin_directory.parent / "cache")}


def _cmake(*arguments: str, env: dict[str, str], cwd: Path) -> subprocess.CompletedProcess[str]:
    assert CMAKE is not None
    return _run([CMAKE, *arguments], env=env, cwd=cwd)


def _ctest(build: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    ctest = str(Path(CMAKE or "cmake").with_name("ctest"))
    return _run([ctest, "--output-on-failure"], env=env, cwd=build)


def _run(command: list[str], env: dict[str, str], cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        command, check=False, env=env, cwd=cwd, capture_output=True, text=True, timeout=300
    )


def _suite(path: Path) -> Any:
    suite = etree.parse(str(path)).getroot()
    SCHEMA.assertValid(suite)
    return suite


# ---------------------------------------------------------------------------------------
# ament: ament_cmake_roslint_names and the ament_roslint_names entry point

AMENT_CMAKE_TEST_STAND_IN = """
# ament_cmake_test and ament_cmake_core as far as ament_cmake_roslint_names uses them.
function(ament_register_extension extension_point package_name cmake_filename)
  file(APPEND "${CMAKE_BINARY_DIR}/calls.txt"
    "ament_register_extension|${extension_point}|${package_name}|${cmake_filename}\\n")
endfunction()
function(ament_add_test testname)
  cmake_parse_arguments(ARG "" "OUTPUT_FILE;RESULT_FILE;WORKING_DIRECTORY" "COMMAND" ${ARGN})
  file(APPEND "${CMAKE_BINARY_DIR}/calls.txt"
    "ament_add_test|${testname}|${ARG_COMMAND}|${ARG_RESULT_FILE}|${ARG_WORKING_DIRECTORY}\\n")
  add_test(NAME "${testname}" COMMAND ${ARG_COMMAND} WORKING_DIRECTORY "${ARG_WORKING_DIRECTORY}")
endfunction()
"""
AMENT_PACKAGE_CMAKE = """cmake_minimum_required(VERSION 3.5)
project(robot_bringup NONE)
enable_testing()
set(AMENT_TEST_RESULTS_DIR "${{CMAKE_BINARY_DIR}}/test_results")
find_package(ament_cmake_roslint_names REQUIRED)
# What ament_lint_auto_find_test_dependencies() does with the hook registered above.
set(AMENT_LINT_AUTO_FILE_EXCLUDE test/fixtures)
include("${{ament_cmake_roslint_names_DIR}}/ament_cmake_roslint_names_lint_hook.cmake")
"""


def _ament_prefix(root: Path) -> Path:
    """An install prefix as colcon leaves it: our package's share/ and the stand-in."""
    share = root / "prefix/share"
    ours = share / "ament_cmake_roslint_names/cmake"
    shutil.copytree(INTEGRATIONS / "ament_cmake_roslint_names/cmake", ours)
    extras = (
        INTEGRATIONS / "ament_cmake_roslint_names/ament_cmake_roslint_names-extras.cmake"
    ).read_text()
    (ours / "ament_cmake_roslint_names-extras.cmake").write_text(extras)
    (ours / "ament_cmake_roslint_namesConfig.cmake").write_text(
        'set(ament_cmake_roslint_names_DIR "${CMAKE_CURRENT_LIST_DIR}")\n'
        'include("${CMAKE_CURRENT_LIST_DIR}/ament_cmake_roslint_names-extras.cmake")\n'
    )
    stand_in = share / "ament_cmake_test/cmake"
    stand_in.mkdir(parents=True)
    (stand_in / "ament_cmake_testConfig.cmake").write_text(AMENT_CMAKE_TEST_STAND_IN)
    return root / "prefix"


def test_colcon_test_runs_the_linter_through_ament_lint_auto(tmp_path: Path) -> None:
    package = _package(tmp_path)
    (package / "CMakeLists.txt").write_text(AMENT_PACKAGE_CMAKE.format())
    env = _environment(tmp_path / "bin")
    build = tmp_path / "build"
    configured = _cmake(
        "-S",
        str(package),
        "-B",
        str(build),
        f"-DCMAKE_PREFIX_PATH={_ament_prefix(tmp_path)}",
        env=env,
        cwd=tmp_path,
    )
    assert configured.returncode == 0, configured.stderr
    assert "Added test 'roslint_names'" in configured.stdout
    calls = (build / "calls.txt").read_text().splitlines()
    result_file = build / "test_results/robot_bringup/roslint_names.xunit.xml"
    hook = "ament_cmake_roslint_names_lint_hook.cmake"
    command = f"{tmp_path / 'bin/ament_roslint_names'};--xunit-file;{result_file}"
    assert calls == [
        f"ament_register_extension|ament_lint_auto|ament_cmake_roslint_names|{hook}",
        f"ament_add_test|roslint_names|{command};--exclude;test/fixtures|{result_file}|{package}",
    ]

    tested = _ctest(build, env)
    assert tested.returncode != 0  # the package has findings: the test fails
    assert "launch/robot.launch.xml:2:" in tested.stdout and "[RN101 illegal-name]" in tested.stdout
    suite = _suite(result_file)
    cases = {case.get("name"): [f.get("type") for f in case] for case in suite.iter("testcase")}
    # The fixture is excluded; the build file is read (it names the executables), and clean.
    assert cases == {"CMakeLists.txt": [], "launch/robot.launch.xml": ["RN101"]}

    (package / "launch/robot.launch.xml").write_text(
        BRINGUP_LAUNCH.replace("teleop-twist", "teleop_twist")
    )
    assert _ctest(build, env).returncode == 0
    assert _suite(result_file).get("failures") == "0"


def test_the_entry_point_takes_ament_s_arguments(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    package = _package(tmp_path)
    monkeypatch.chdir(package)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    xunit = tmp_path / "results/robot_bringup/roslint_names.xunit.xml"
    assert ament_roslint_names(["--xunit-file", str(xunit)]) == 1
    out, err = capsys.readouterr()
    assert out.count("[RN101 illegal-name]") == 2  # the package and its test fixture
    assert err.count("Found 2 problems") == 1  # the JUnit pass says nothing more
    assert _suite(xunit).get("failures") == "2"

    assert ament_roslint_names(["launch", "--xunit-file", str(xunit), "--ros", "2"]) == 1
    assert _suite(xunit).get("tests") == "1"
    assert ament_roslint_names(["--xunit-file", str(xunit), "--exclude", "launch", "test"]) == 0
    assert _suite(xunit).get("tests") == "0"

    capsys.readouterr()
    assert ament_roslint_names(["--config", "missing.toml", "--xunit-file", str(xunit)]) == 2
    assert "missing.toml" in capsys.readouterr().err


# ---------------------------------------------------------------------------------------
# catkin: roslint_names_add_test()

CATKIN_PACKAGE_CMAKE = """cmake_minimum_required(VERSION 3.10)
project(robot_bringup NONE)
enable_testing()
set(CATKIN_TEST_RESULTS_DIR "${{CMAKE_BINARY_DIR}}/test_results")
# catkin's catkin_run_tests_target() as far as roslint_names_add_test() uses it: the
# command line is one string, run in the working directory.
function(catkin_run_tests_target type name xunit_filename)
  cmake_parse_arguments(_testing "" "WORKING_DIRECTORY" "COMMAND;DEPENDENCIES" ${{ARGN}})
  file(APPEND "${{CMAKE_BINARY_DIR}}/calls.txt"
    "catkin_run_tests_target|${{type}}|${{name}}|${{xunit_filename}}|${{_testing_COMMAND}}|${{_testing_WORKING_DIRECTORY}}\\n")
  add_test(NAME "${{type}}_${{name}}" COMMAND sh -c "${{_testing_COMMAND}}"
    WORKING_DIRECTORY "${{_testing_WORKING_DIRECTORY}}")
endfunction()
include("{extras}")
roslint_names_add_test(launch)
"""


def test_catkin_run_tests_runs_the_linter(tmp_path: Path) -> None:
    package = _package(tmp_path)
    extras = INTEGRATIONS / "catkin_roslint_names/cmake/roslint_names-extras.cmake"
    (package / "CMakeLists.txt").write_text(CATKIN_PACKAGE_CMAKE.format(extras=extras))
    env = _environment(tmp_path / "bin")
    build = tmp_path / "build"
    configured = _cmake("-S", str(package), "-B", str(build), env=env, cwd=tmp_path)
    assert configured.returncode == 0, configured.stderr
    (call,) = (build / "calls.txt").read_text().splitlines()
    kind, test_type, name, xunit_name, command, directory = call.split("|")
    result_file = build / "test_results/robot_bringup/roslint_names-robot_bringup.xml"
    assert (kind, test_type, name, xunit_name, directory) == (
        "catkin_run_tests_target",
        "roslint_names",
        "package",
        "roslint_names-robot_bringup.xml",
        str(package),
    )
    assert command.endswith(f"check --ros 1 --format junit --output {result_file} launch")

    tested = _ctest(build, env)
    assert tested.returncode != 0
    cases = {
        case.get("name"): [f.get("type") for f in case]
        for case in _suite(result_file).iter("testcase")
    }
    assert cases == {"launch/robot.launch.xml": ["RN101"]}

    # The console target: the same check, the report on the console.
    built = _cmake(
        "--build", str(build), "--target", "roslint_names_robot_bringup", env=env, cwd=tmp_path
    )
    assert built.returncode != 0
    assert "launch/robot.launch.xml:2:" in built.stdout + built.stderr
