"""Coverage-guided fuzzing of one extractor with atheris (libFuzzer), when it is installed.

    python tests/fuzz/atheris_fuzz.py TARGET [libFuzzer options]
    python tests/fuzz/atheris_fuzz.py launch_xml.extract -max_total_time=300

TARGET is a name from ``inputs.TARGETS`` (``list`` prints them). libFuzzer starts from a
corpus of the real files of the project, as they are and re-encoded (UTF-16, Latin-1,
CRLF...), and mutates them guided by the coverage of ``roslint_names``; each input is
checked with the same invariants as the hypothesis harness (``checks``). A failure stops
the run and is written to ``$ROSLINT_FUZZ_CRASHES`` (default ``$TMPDIR/roslint-fuzz-crashes``)
as ``atheris-crash-*``; replay it with the same command and the file as the argument.
atheris is not a test dependency: ``pip install atheris``.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/: `fuzz` imports

import atheris

with atheris.instrument_imports(include=["roslint_names"]):
    import importlib
    import pkgutil

    import roslint_names.extract
    from fuzz.checks import check_extraction
    from fuzz.inputs import ENCODINGS, LINE_ENDS, TARGETS, Sample, Target, reencode, seeds
    from fuzz.runner import crash_directory
    from roslint_names.model import Generation

    # Extractors import their parsers' glue on first use: instrument all of it now.
    for module in pkgutil.walk_packages(roslint_names.extract.__path__, "roslint_names.extract."):
        importlib.import_module(module.name)

_GENERATIONS = (None, Generation.ROS1, Generation.ROS2)


def _sample(target: Target, data: bytes) -> Sample:
    """The call for ``data``: path and generations chosen by its length, so a replay of
    the same bytes makes the same call."""
    size = len(data)
    return Sample(
        kind="atheris",
        origin="atheris",
        data=data,
        path=target.paths[size % len(target.paths)],
        package_generation=_GENERATIONS[size % 3],
        fallback_generation=(Generation.ROS1, Generation.ROS2)[size // 3 % 2],
    )


def _corpus(target: Target, directory: Path) -> None:
    for index, data in enumerate(seeds(target)):
        (directory / f"seed-{index}").write_bytes(data)
        for encoding in ENCODINGS:
            for line_end in LINE_ENDS:
                variant = reencode(data, encoding, line_end, declare=True)
                (directory / f"seed-{index}-{encoding}-{line_end}").write_bytes(variant)


def main() -> None:
    names = {target.name: target for target in TARGETS}
    if len(sys.argv) < 2 or sys.argv[1] not in names:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        print("targets: " + ", ".join(names), file=sys.stderr)
        raise SystemExit(0 if sys.argv[1:2] == ["list"] else 2)
    target = names[sys.argv.pop(1)]
    options = sys.argv[1:]
    crashes = crash_directory()
    crashes.mkdir(parents=True, exist_ok=True)
    arguments = [sys.argv[0], f"-artifact_prefix={crashes}/atheris-", *options]
    if not any(not option.startswith("-") for option in options):  # no corpus or input given
        corpus = Path(tempfile.mkdtemp(prefix="roslint-fuzz-corpus-"))
        _corpus(target, corpus)
        arguments.append(str(corpus))

    def test_one_input(data: bytes) -> None:
        check_extraction(target, _sample(target, data))

    atheris.Setup(arguments, test_one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
