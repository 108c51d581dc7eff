"""Runs over the files of an earlier run, some added or removed (``shifts``): how files
are renumbered, which files may come or go without a graph of their own, and what the
cache keeps for it reading back. ``test_same_facts`` runs them over the example
workspace against fresh runs."""

from __future__ import annotations

import pytest

from roslint_names.model import (
    Executable,
    ExecutableKind,
    FileFacts,
    Generation,
    InPackage,
    Language,
    LaunchInclude,
    LaunchNode,
    ParameterLoad,
    ParseError,
    Span,
)
from roslint_names.shifts import (
    MOST_CHANGED,
    SEVERAL,
    Base,
    GraphMove,
    Lookups,
    Renumbering,
    digest,
    loaded_base,
    loaded_move,
    loaded_renumbering,
    renumbering,
    says_nothing,
)

SPAN = Span(1, 1, 1, 2)


def test_files_are_renumbered_by_display_path() -> None:
    found = renumbering(["a.cpp", "b.py", "c.launch", "d.yaml"], 3, ["a.cpp", "c.launch", "e.hpp"])
    assert found == Renumbering((0, 2, -1), 4, 3, ((1, "b.py"), (3, "d.yaml")))
    assert found is not None and found.then_of(2) == {0: 0, 2: 1}


def test_a_path_twice_or_too_many_changes_is_no_renumbering() -> None:
    assert renumbering(["a.cpp", "a.cpp"], 2, ["a.cpp"]) is None
    assert renumbering(["a.cpp"], 1, ["a.cpp", "a.cpp"]) is None
    many = [f"new{index}.cpp" for index in range(MOST_CHANGED + 1)]
    assert renumbering(["a.cpp"], 1, ["a.cpp", *many]) is None
    assert renumbering(["a.cpp"], 1, ["a.cpp", *many[:-1]]) is not None


def test_renumberings_join_from_the_first_run_to_the_last() -> None:
    first = ["a.cpp", "b.py", "c.hpp"]
    second = ["a.cpp", "c.hpp", "d.py"]  # b.py removed, d.py added
    third = ["b.py", "c.hpp", "e.py"]  # b.py back, a.cpp and d.py removed, e.py added
    earlier = renumbering(first, 3, second)
    later = renumbering(second, 3, third)
    assert earlier is not None and later is not None
    joined = later.after(earlier, third)
    # b.py, removed by the second run, is the first run's again; d.py never was in it.
    assert joined == Renumbering((1, 2, -1), 3, 3, ((0, "a.cpp"),))


def test_a_renumbering_reads_back_and_a_damaged_one_is_none() -> None:
    found = Renumbering((0, -1, 1), 3, 2, ((2, "c.hpp"),))
    assert loaded_renumbering(found.stored()) == found
    previous, before, reported, removed = found.stored()
    assert isinstance(previous, bytes)
    assert loaded_renumbering((previous, 1, 1, removed)) is None  # an index past the run
    assert loaded_renumbering((previous[:-1], before, reported, removed)) is None
    assert loaded_renumbering((previous, before, 4, removed)) is None  # reports more
    assert loaded_renumbering((previous, before, reported, ((7, "x"),))) is None
    assert loaded_renumbering((previous, before, reported, (("x",),))) is None


def test_a_base_and_a_graph_move_read_back() -> None:
    base = Base("k" * 40, ("a.cpp", "b.py"), 2, "d" * 40)
    lists = {base.replay_at: base.listed()}
    assert loaded_base(base.pointer(), lists.get) == base
    assert loaded_base(("base 0", *base.pointer()[1:]), lists.get) is None
    assert loaded_base((*base.pointer()[:2], 3, 2, ""), lists.get) is None  # more reported
    assert loaded_base((*base.pointer()[:3], 3, ""), lists.get) is None  # another count
    assert loaded_base((*base.pointer()[:4], None), lists.get) is None  # no dependencies
    assert loaded_base(base.pointer(), lambda _: None) is None  # its files forgotten
    assert loaded_base(base.pointer(), {base.replay_at: ("file list 1", ("a", 1))}.get) is None
    move = GraphMove("g" * 40, Renumbering((1, 0), 2, 2, ()))
    assert loaded_move(move.stored()) == move
    assert loaded_move((*move.stored()[:2], None)) is None
    assert loaded_move(None) is None


def _facts(path: str, language: Language = Language.CPP, **fields: object) -> FileFacts:
    return FileFacts(path, language, Generation.ROS2, **fields)  # type: ignore[arg-type]


def test_code_says_nothing_where_only_its_own_checks_read_its_facts() -> None:
    error = (ParseError("unexpected token", SPAN),)
    assert says_nothing(_facts("src/a/util.hpp"))
    assert says_nothing(_facts("src/a/util.hpp", parse_errors=error, suppression_marker=True))
    assert says_nothing(_facts("src/a/a/util.py", Language.PYTHON))
    assert not says_nothing(_facts("src/a/util.hpp", class_bases=(("Util", ("Base",)),)))
    assert not says_nothing(_facts("src/a/util.hpp", constants=(("TOPIC", "scan"),)))
    assert not says_nothing(_facts("src/a/impl.cpp", included_sources=("solver.cpp",)))
    # A launch or parameter file is a tree or a file a tree may load, whatever it holds.
    assert not says_nothing(_facts("src/a/launch/a.launch.xml", Language.LAUNCH_XML))
    assert not says_nothing(_facts("src/a/config/a.yaml", Language.PARAMETERS))


def test_what_launch_and_build_files_find_by_name() -> None:
    load = ParameterLoad("a", "config/nav.yaml", SPAN)
    node = LaunchNode("a", "talker", None, "/", SPAN, parameter_files=(load,))
    include = LaunchInclude(
        "a",
        "launch/robot.launch.py",
        "/",
        SPAN,
        arguments=(("map", InPackage("maps", "warehouse.yaml")), ("world", "worlds/w.sdf")),
    )
    launch = _facts(
        "src/a/launch/all.launch.xml",
        Language.LAUNCH_XML,
        launch_nodes=(node,),
        includes=(include,),
        parameter_loads=(ParameterLoad(None, "../config/extra.yaml", SPAN),),
    )
    found_by = Lookups()
    found_by.add(launch)
    assert found_by.names == {
        "talker",
        "nav.yaml",
        "robot.launch.py",
        "warehouse.yaml",
        "w.sdf",
        "extra.yaml",
    }
    # who looks up a parameter file's name (a parameter file added: ``shifts``)
    assert found_by.naming_of("nav.yaml", [launch.path, "src/b/launch/b.launch"]) == {launch.path}
    assert found_by.naming_of("other.yaml", [launch.path]) == set()
    assert found_by.naming_of("robot.launch.py", [launch.path]) is None  # not kept
    executables = (
        Executable("talker", ExecutableKind.PROGRAM, ("src/talker.cpp", "../b/src/x.cpp"), SPAN),
        Executable("listener", ExecutableKind.PROGRAM, ("a/listener.py",), SPAN),
    )
    found_by.add(_facts("src/a/CMakeLists.txt", Language.CMAKE, executables=executables))
    assert found_by.named == {
        digest(path): digest("src/a/CMakeLists.txt")
        for path in ("src/a/src/talker.cpp", "src/b/src/x.cpp", "src/a/a/listener.py")
    }
    # which build files name a source (a file added to a package: ``program_patch``)
    assert found_by.builders("src/b/src/x.cpp") == {digest("src/a/CMakeLists.txt")}
    assert found_by.builders("src/a/a/listener/__init__.py") == {digest("src/a/CMakeLists.txt")}
    assert found_by.builders("src/b/src/y.cpp") == set()
    found_by.add(_facts("src/b/CMakeLists.txt", Language.CMAKE, executables=executables[:1]))
    assert found_by.builders("src/b/src/talker.cpp") == {digest("src/b/CMakeLists.txt")}
    assert found_by.builders("src/b/src/x.cpp") == {SEVERAL}  # src/a's and src/b's
    assert found_by.adds_nothing(_facts("src/a/src/util.cpp"))
    # rosrun's rule: a script of the executable's name, a code file of its stem
    assert not found_by.adds_nothing(_facts("src/c/scripts/talker", Language.PYTHON))
    assert not found_by.adds_nothing(_facts("src/c/src/talker.cpp"))
    # a file an include finds by its name (a Python file of a launch file's name)
    assert not found_by.adds_nothing(_facts("src/c/robot.launch.py", Language.PYTHON))
    assert not found_by.adds_nothing(_facts("src/b/src/x.cpp"))  # a target's source
    # a console_scripts module that is a package
    assert not found_by.adds_nothing(_facts("src/a/a/listener/__init__.py", Language.PYTHON))


@pytest.mark.parametrize("value", [None, (), ("base 3",), ("base 3", 7, 1, 1, "")])
def test_a_base_of_another_shape_is_none(value: object) -> None:
    lists: dict[object, object] = {7: ("file list 1", ("a",))}
    assert loaded_base(value, lists.get) is None
