"""The code a launch ``<node>`` runs where no build file names its executable
(``WorkspaceIndex.sources_of``: rosrun's rule), and a package file found by its name
(``find_in_package``): answered from the package's files by name, the facts of no other
file looked at. A launch patch's index loads a file's facts when asked for them
(``workspace.launch_patch``), and a package of a few hundred files was read whole for
each node started of it."""

from __future__ import annotations

from collections.abc import Iterator, Mapping

from roslint_names.model import FileFacts, Generation, Language
from roslint_names.workspace.index import Executables, Package, WorkspaceIndex

# A ROS 1 package whose CMakeLists.txt installs its scripts without naming them as
# targets (catkin_install_python), and a C++ node built by a macro the workspace does not
# hold: roslaunch finds both by name.
CHATTER = {
    "src/chatter/package.xml": Language.PACKAGE_XML,
    "src/chatter/CMakeLists.txt": Language.CMAKE,
    "src/chatter/scripts/talker": Language.PYTHON,
    "src/chatter/scripts/relay.py": Language.PYTHON,
    "src/chatter/src/listener.cpp": Language.CPP,
    "src/chatter/include/chatter/listener_core.hpp": Language.CPP,
    "src/chatter/launch/chatter.launch": Language.LAUNCH_XML,
    "src/chatter/launch/robot/chatter.launch": Language.LAUNCH_XML,
    "src/chatter/config/talker.yaml": Language.PARAMETERS,
    "src/chatter/config/relay.yaml": Language.PARAMETERS,
}
PACKAGES = [Package("chatter", "src/chatter", generation=Generation.ROS1)]


class _Asked(Mapping[str, FileFacts]):
    """Every file's facts, and which files were asked for theirs."""

    def __init__(self, files: Mapping[str, Language]) -> None:
        self.facts = {
            path: FileFacts(path, language, Generation.ROS1) for path, language in files.items()
        }
        self.asked: set[str] = set()

    def __getitem__(self, path: str) -> FileFacts:
        self.asked.add(path)
        return self.facts[path]

    def __contains__(self, path: object) -> bool:
        return path in self.facts  # whether it is a file of the run: no facts read

    def __iter__(self) -> Iterator[str]:
        return iter(self.facts)

    def __len__(self) -> int:
        return len(self.facts)


def _index(files: Mapping[str, Language] = CHATTER) -> tuple[WorkspaceIndex, _Asked]:
    facts = _Asked(files)
    return WorkspaceIndex.restored(facts, PACKAGES, Executables((), ())), facts


def test_a_script_of_the_executable_s_name_reads_only_the_files_of_that_name() -> None:
    index, facts = _index()
    assert index.sources_of("chatter", "talker") == ("src/chatter/scripts/talker",)
    assert index.sources_of("chatter", "relay") == ("src/chatter/scripts/relay.py",)
    assert facts.asked == {"src/chatter/scripts/talker", "src/chatter/scripts/relay.py"}


def test_the_package_s_one_code_file_of_the_executable_s_stem() -> None:
    index, facts = _index()
    assert index.sources_of("chatter", "listener") == ("src/chatter/src/listener.cpp",)
    assert facts.asked == {"src/chatter/src/listener.cpp"}
    # Two code files of that stem: neither is known to be the one.
    index, _ = _index({**CHATTER, "src/chatter/test/listener.cpp": Language.CPP})
    assert index.sources_of("chatter", "listener") == ()
    assert index.sources_of("chatter", "absent") == ()
    assert index.sources_of("other", "talker") == ()


def test_a_package_file_by_its_path_else_by_its_one_name() -> None:
    index, facts = _index()
    assert (
        index.find_in_package("chatter", "config/talker.yaml") == "src/chatter/config/talker.yaml"
    )
    # Installed flat (``install(DIRECTORY launch ...)``): the package's only file of that
    # name, and none where two share it.
    assert index.find_in_package("chatter", "relay.yaml") == "src/chatter/config/relay.yaml"
    assert index.find_in_package("chatter", "launch/chatter.launch") == (
        "src/chatter/launch/chatter.launch"
    )
    assert index.find_in_package("chatter", "chatter.launch") is None
    assert facts.asked == set()
