"""Launch files extracted under their includers' arguments while the rest of the
workspace is (issue 30).

A build walks the launch trees depth by depth, extracting again each launch file an
includer hands arguments to (``LaunchTrees``, ``gather.Specialiser``). Done once every
file's facts were in, that was seven rounds through the workers with nothing else to do
(realws: 761 files, 0.58 s of a first run's 4.9 s on 16 cores, 0.9 s with 2 jobs). The
trees need only the launch files' facts and where the packages are: the launch files are
handed out first (``gather.Gatherer``), and once their facts are in, the build's own
walk over an index of them alone sends each depth to the workers between the other
files. What comes back is kept by the specialiser, which the build then walks with: it
takes each up when its walk asks for it, so the build reads what it would have read
without; where the index of the launch files alone finds another file than the whole
workspace's, that file is extracted when asked, as before. Nothing is sent once every
file is handed out: the depths left are the build's.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence

from .gather import Extracted, Specialiser
from .model import FileFacts, Language, LaunchArguments
from .workspace.index import Package, WorkspaceIndex
from .workspace.launch_tree import LAUNCH_LANGUAGES, LaunchTrees


class Speculation:
    """``gather.Ahead`` for a build: ``specialiser`` is the one the build walks with."""

    # The files whose facts the trees read: launch files, and Python files, which are
    # launch files where their facts say so (``extract.python``; an include names one
    # by path, whatever its name).
    languages = LAUNCH_LANGUAGES | {Language.PYTHON}

    def __init__(
        self,
        specialiser: Specialiser,
        packages: Callable[[], Sequence[Package]],
        *,
        launch_files: int,
        first: int,
    ) -> None:
        """``packages``: the workspace's (made when first asked: while the workers
        extract, rather than before they start); ``launch_files``: how many files of
        ``languages`` the run has (by their ``SourceFile.language``); ``first``: the first
        number past its files (``Specialiser.ahead``)."""
        self.specialiser = specialiser
        self._make_packages = packages
        self._packages: Sequence[Package] | None = None
        self._expected = launch_files
        self._first = first
        self._launch: list[FileFacts] = []
        self._depths: Iterator[list[tuple[str, LaunchArguments]]] | None = None
        self._stopped = False

    def saw(self, facts: FileFacts) -> list[Extracted]:
        if self._stopped or self._depths is not None:
            return []  # walking, or done: the facts are the gatherer's to keep
        self._launch.append(facts)
        if len(self._launch) < self._expected:
            return []
        index = WorkspaceIndex(self._launch, self.packages())
        self._depths = LaunchTrees(index, self.specialiser.known_ahead).depths()
        return self._next()

    def packages(self) -> Sequence[Package]:
        """The workspace's packages, which the build takes too."""
        if self._packages is None:
            self._packages = self._make_packages()
        return self._packages

    def sent(self, number: int) -> bool:
        return self.specialiser.sent(number)

    def back(self, result: Extracted) -> list[Extracted]:
        self.specialiser.back(result)
        return [] if self.specialiser.flying else self._next()

    def stop(self) -> None:
        self._stopped = True

    def _next(self) -> list[Extracted]:
        """Each next depth's items sent, until some are in flight (their results come
        back through the gatherer, ``back``) or the trees end."""
        results: list[Extracted] = []
        while self._depths is not None and not self._stopped and not self.specialiser.flying:
            wanted = next(self._depths, None)
            if wanted is None:
                self._stopped = True
                break
            results += self.specialiser.ahead(wanted, self._first)
        return results
