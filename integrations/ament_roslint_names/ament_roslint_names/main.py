"""``ament_roslint_names``: roslint-names as ament_lint runs its linters.

``ament_cmake_roslint_names`` registers a test that runs this in the package's source
directory with ``--xunit-file``: the findings go to the console in gcc's format, for the
test's log, and to the xunit file, for ``colcon test-result``. The exit code is the
linter's: 0 clean, 1 findings, 2 a usage or internal error.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import sys
from collections.abc import Sequence

from roslint_names.cli import main as roslint_names_main


def roslint_names(arguments: Sequence[str]) -> int:
    """The linter's exit code for ``arguments``; a usage error exits, here it returns."""
    try:
        return roslint_names_main(arguments)
    except SystemExit as stop:
        return stop.code if isinstance(stop.code, int) else 2


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="ament_roslint_names",
        description="Check the ROS names of a package with roslint-names.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    parser.add_argument(
        "paths",
        nargs="*",
        default=[os.curdir],
        metavar="path",
        help="files or directories to check",
    )
    parser.add_argument("--config", metavar="path", help="the roslint-names.toml to use")
    parser.add_argument("--ros", choices=("1", "2"), help="ROS generation when undecided")
    parser.add_argument(
        "--exclude",
        nargs="*",
        default=[],
        metavar="pattern",
        help="files or directories to skip (gitignore patterns)",
    )
    parser.add_argument("--xunit-file", help="write the findings as a JUnit XML file")
    args = parser.parse_args(argv)

    common = ["check"]
    if args.config:
        common += ["--config", args.config]
    if args.ros:
        common += ["--ros", args.ros]
    for pattern in args.exclude:
        common += ["--extend-exclude", pattern]
    code = roslint_names([*common, *args.paths])
    if args.xunit_file and code != 2:
        directory = os.path.dirname(args.xunit_file)
        if directory:
            os.makedirs(directory, exist_ok=True)
        # The same run again, answered from the cache of the first: the findings as
        # JUnit. Its summary line would repeat the first's; it is shown only on failure.
        junit = ["--format", "junit", "--output", args.xunit_file, "--exit-zero"]
        summary = io.StringIO()
        with contextlib.redirect_stderr(summary):
            written = roslint_names([*common, *junit, *args.paths])
        if written != 0:
            sys.stderr.write(summary.getvalue())
            return 2
    return code


if __name__ == "__main__":
    sys.exit(main())
