"""Which package holds each file, and the files of each package name
(``workspace.index.PackageFiles``): ``files_of`` asks only about the paths below the
package's directories, and must give what asking about every path gives."""

from __future__ import annotations

import pytest

from roslint_names.workspace.index import Package, PackageFiles

PATHS = [
    "CMakeLists.txt",  # in the package at the root
    "src/robot/package.xml",
    "src/robot/src/driver.cpp",
    "src/robot/tools/calibrate.py",
    "src/robot/tools/inner/package.xml",  # a package inside another's directory
    "src/robot/tools/inner/src/inner.cpp",
    "src/robot_extras/src/extra.cpp",  # a directory whose name starts like robot's
    "copy/src/robot/package.xml",  # another package of the same name
    "copy/src/robot/src/driver.cpp",
    "/elsewhere/robot/src/main.cpp",  # absolute: outside the run's directory
    "/elsewhere/robot/package.xml",
]
PACKAGES = [
    Package("root_package", ""),
    Package("robot", "src/robot"),
    Package("inner", "src/robot/tools/inner"),
    Package("robot_extras", "src/robot_extras"),
    Package("robot", "copy/src/robot"),
    Package("outside", "/elsewhere/robot"),
]


@pytest.mark.parametrize("name", sorted({package.name for package in PACKAGES} | {"absent"}))
def test_the_files_of_a_package_are_those_it_holds(name: str) -> None:
    files = PackageFiles(PATHS, PACKAGES)
    every = sorted(
        path for path in PATHS if (owner := files.package_of(path)) and owner.name == name
    )
    assert PackageFiles(PATHS, PACKAGES).files_of(name) == every


def test_the_files_of_a_package_are_found_as_expected() -> None:
    files = PackageFiles(PATHS, PACKAGES)
    assert files.files_of("robot") == [
        "copy/src/robot/package.xml",
        "copy/src/robot/src/driver.cpp",
        "src/robot/package.xml",
        "src/robot/src/driver.cpp",
        "src/robot/tools/calibrate.py",
    ]
    assert files.files_of("inner") == [
        "src/robot/tools/inner/package.xml",
        "src/robot/tools/inner/src/inner.cpp",
    ]
    assert files.files_of("root_package") == ["CMakeLists.txt"]
    assert files.files_of("outside") == [
        "/elsewhere/robot/package.xml",
        "/elsewhere/robot/src/main.cpp",
    ]
