"""What a file's package says about it: its ROS generation and the package's name.

The nearest ``package.xml`` decides: a catkin build tool means ROS 1, an ament build type or
build tool means ROS 2. A package that declares both under ``$ROS_VERSION`` conditions
(packages built for both generations) decides nothing, and the file's own evidence does.

package.xml is read with a regular expression rather than lxml on purpose: a one-file
pre-commit run over a C++ or Python file must not pay for importing an XML parser.
"""

from __future__ import annotations

import os
import re
import stat
from collections.abc import Collection, Iterable, Iterator, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from .model import Generation, Language
from .plugins import exported_descriptions, plugin_names
from .reading import Status, content_digest, status_from, status_of

if TYPE_CHECKING:
    from .discover import SourceFile

# The generation a file is read as where nothing says which (no package, no setting)
DEFAULT_GENERATION = Generation.ROS2

_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)
_DEPEND = re.compile(
    r"<(buildtool_depend|build_type)(\s[^>]*)?>\s*([A-Za-z0-9_]+)\s*</\1>", re.DOTALL
)
_NAME = re.compile(r"<name>\s*([A-Za-z0-9_]+)\s*</name>")
# Every dependency that says "runs with" or "builds with": not buildtool or doc ones.
_REQUIRES = re.compile(
    r"<((?:build_|build_export_|exec_|run_|test_)?depend)(\s[^>]*)?>\s*([A-Za-z0-9_]+)\s*</\1>"
)
_CONDITION = re.compile(r"""condition\s*=\s*["']([^"']*)["']""")


def package_xml_generation(text: str) -> Generation | None:
    found: set[Generation] = set()
    for match in _DEPEND.finditer(_COMMENT.sub("", text)):
        attributes, tool = match.group(2) or "", match.group(3)
        condition = _CONDITION.search(attributes)
        if condition and "ROS_VERSION" in condition.group(1):
            continue  # built for both generations: the condition decides, not the package
        if tool == "catkin":
            found.add(Generation.ROS1)
        elif tool.startswith("ament"):
            found.add(Generation.ROS2)
    return found.pop() if len(found) == 1 else None


def reads_python2(
    language: Language,
    package_generation: Generation | None,
    fallback_generation: Generation,
    ros1_python2: bool,
) -> bool:
    """Whether a file is read as Python 2 where it is not Python 3: a Python file of a
    ROS 1 package (or of no package, where ``ros = 1``), when the ROS 1 packages may be
    Python 2 (``config.ros1_python2``). ROS 2 is Python 3 only."""
    generation = package_generation or fallback_generation
    return ros1_python2 and language is Language.PYTHON and generation is Generation.ROS1


def package_xml_depends(text: str) -> frozenset[str]:
    """The packages a package.xml depends on (any format, any condition)."""
    return frozenset(match.group(3) for match in _REQUIRES.finditer(_COMMENT.sub("", text)))


def package_xml_name(text: str) -> str | None:
    match = _NAME.search(_COMMENT.sub("", text))
    return match.group(1) if match else None


@dataclass(frozen=True)
class _Package:
    name: str | None
    generation: Generation | None
    depends: frozenset[str] = frozenset()
    # Where its package.xml is, as a string: asked for every file of a run, where making
    # a ``Path`` for each cost more than the lookup.
    root: str | None = None


_NO_PACKAGE = _Package(None, None)

# A package as ``PackageGenerations.lookups`` keeps it: its name, generation, dependencies
# and directory.
_KeptPackage = tuple[str | None, int | None, tuple[str, ...], str | None]
# Each package found once; each directory looked up, by its package's place among them;
# each manifest read, by the digest of its text; the plugin names they export.
KeptLookups = tuple[list[_KeptPackage], dict[str, int], dict[str, str], list[str]]


# A plugin description is a short XML file; a larger one is no such file.
_MAX_DESCRIPTION = 1 << 20


class PackageGenerations:
    """Nearest-package.xml lookup with one read per directory for the whole run."""

    def __init__(self, without_manifest: Collection[str] = frozenset()) -> None:
        # The directories a walk of this run listed with no entry named package.xml
        # (``discover``): looking for one there takes no status, none can be there.
        self._without_manifest = without_manifest
        # By directory, as a string: every file of every run is looked up here, and
        # building ``Path.parent`` for each costs more than the lookup.
        self._by_directory: dict[str, _Package] = {}
        # And by file: a run asks about each file several times (keying it, extracting
        # it, its package for the graph), and even ``os.path.dirname`` costs more than this.
        # By the path's string too: hashing a ``Path`` builds a tuple of its parts each time.
        self._by_file: dict[str, _Package] = {}
        # Every package.xml read, and every plugin description one exports, with the
        # digest of its text: what a cached run's result depends on.
        self.manifests: dict[str, str] = {}
        # The names pluginlib gives the plugins those descriptions declare (``plugins``).
        self.plugin_names: set[str] = set()
        # The status of every package.xml looked for (None where there is none), and of
        # every plugin description, taken before reading it: what says that a re-run
        # would find the same packages (``unchanged``).
        self.statuses: dict[str, Status | None] = {}
        # What ``restore`` took up, and how many directories it knew.
        self._restored: tuple[KeptLookups, int] | None = None

    def lookups(self) -> KeptLookups:
        """What the lookups so far found, as builtins (``unchanged`` keeps them)."""
        if self._restored is not None and len(self._by_directory) == self._restored[1]:
            return self._restored[0]  # no directory looked up since: what was restored
        places: dict[int, int] = {}  # by the package object: one entry per package
        packages: list[_KeptPackage] = []
        directories: dict[str, int] = {}
        for directory, package in self._by_directory.items():
            place = places.get(id(package))
            if place is None:
                place = places[id(package)] = len(packages)
                generation = None if package.generation is None else package.generation.value
                depends = tuple(sorted(package.depends))
                packages.append((package.name, generation, depends, package.root))
            directories[directory] = place
        return packages, directories, dict(self.manifests), sorted(self.plugin_names)

    def layout(self) -> bytes:
        """What the manifests read so far say but for the dependencies: where each package
        is, its name and generation; each plugin description's digest. A run's shape
        holds it (``RunInputs.shape_key``): an earlier run of that shape whose packages
        depended on others is one whose graph a patch takes up (``depends_digest``)."""
        lines = sorted(
            f"{package.root}\0{package.name or ''}\0{_generation_text(package)}\n"
            for package in self._found()
        )
        lines.extend(
            f"{path}\0{digest}\n"
            for path, digest in sorted(self.manifests.items())
            if not is_package_manifest(path)
        )
        return "".join(lines).encode("utf-8", "surrogateescape")

    def depends_digest(self) -> str:
        """The digest of what each package looked up so far depends on (``layout``)."""
        lines = sorted(
            f"{package.root}\0{' '.join(sorted(package.depends))}\n" for package in self._found()
        )
        return content_digest("".join(lines).encode("utf-8", "surrogateescape"))

    def _found(self) -> Iterator[_Package]:
        """Each package looked up so far, once."""
        seen: set[int] = set()
        for package in self._by_directory.values():
            if package.root is not None and id(package) not in seen:
                seen.add(id(package))
                yield package

    def restore(
        self,
        lookups: KeptLookups,
        statuses: Mapping[str, Status | None],
        reread: Collection[str] = (),
    ) -> bool:
        """Take up what an earlier run's lookups found (``lookups``), each package.xml and
        plugin description they read having the status it had then (``statuses``, as
        ``unchanged`` takes them again): the same files, so the same answers; but the
        package.xml files of ``reread``, read again, which may depend on other packages
        now and say nothing else new (a dependency added looked every package up again:
        0.3 s at 8 copies). Only before any lookup; False (nothing taken) for one that is
        not of that shape, or a manifest read again that says more."""
        if self._by_directory:
            return False
        try:
            packages, directories, kept_manifests, kept_names = lookups
            made = [
                _NO_PACKAGE
                if kept == (None, None, (), None)
                else _Package(
                    kept[0],
                    None if kept[1] is None else Generation(kept[1]),
                    frozenset(kept[2]),
                    kept[3],
                )
                for kept in packages
            ]
            manifests, names = dict(kept_manifests), set(kept_names)
            if reread and not self._read_again(made, manifests, reread):
                return False
            by_directory = {directory: made[place] for directory, place in directories.items()}
        except (TypeError, ValueError, IndexError, KeyError):
            return False  # damaged: looked up again
        self._by_directory, self.manifests, self.plugin_names = by_directory, manifests, names
        self.statuses = dict(statuses)
        # What ``lookups`` gives: the kept lookups, unless a manifest was read again.
        self._restored = (lookups, -1 if reread else len(by_directory))
        return True

    @staticmethod
    def _read_again(
        made: list[_Package], manifests: dict[str, str], reread: Collection[str]
    ) -> bool:
        """``made`` (the kept packages) and ``manifests`` (their digests) with each
        package.xml of ``reread`` as it is now, where it says what it said but for its
        dependencies; False where one does not."""
        at = {package.root: place for place, package in enumerate(made) if package.root}
        for path in reread:
            directory = os.path.dirname(path)
            text = _manifest_text(path)
            place = at.get(directory)
            if text is None or place is None:
                return False
            package, exported = _package_said(text, directory)
            then = replace(package, depends=made[place].depends)
            if _package_digest(then, exported) != manifests.get(path):
                return False
            made[place] = package
            manifests[path] = _package_digest(package, exported)
        return True

    @property
    def restored(self) -> bool:
        """Whether the lookups are an earlier run's (``restore``)."""
        return self._restored is not None

    def for_file(self, path: str | Path) -> Generation | None:
        return self._for_file(path).generation

    def package_name(self, path: str | Path) -> str | None:
        return self._for_file(path).name

    def package_root(self, path: str | Path) -> str | None:
        """The directory of the package.xml nearest above ``path``."""
        return self._for_file(path).root

    def package_depends(self, path: str | Path) -> frozenset[str]:
        return self._for_file(path).depends

    def visible_packages(self, path: Path) -> frozenset[str] | None:
        """The packages whose interfaces code at ``path`` can use: its own package and
        every package its package.xml depends on. None outside a named package, where no
        manifest says what the file can see."""
        package = self._for_file(path)
        if package.name is None:
            return None
        return package.depends | {package.name}

    def _read_plugin_descriptions(self, directory: str, exported: Iterable[str]) -> None:
        for relative in exported:
            description = os.path.normpath(os.path.join(directory, relative))
            self.statuses[description] = status_of(description)
            text = _manifest_text(description, _MAX_DESCRIPTION)
            if text is None:
                continue  # a missing description declares nothing
            names = plugin_names(text)
            self.manifests[description] = _description_digest(names)
            self.plugin_names |= names

    def _for_file(self, path: str | Path) -> _Package:
        text = os.fspath(path)
        found = self._by_file.get(text)
        if found is None:
            found = self._by_file[text] = self._for_directory(_parent(text))
        return found

    def status(self, path: str) -> Status | None:
        """The status of a package.xml or plugin description as the lookups take it
        (``statuses``): none for a package.xml where the walk found no such entry."""
        if path.endswith(_IN_DIRECTORY) and path[: -len(_IN_DIRECTORY)] in self._without_manifest:
            return None
        return status_of(path)

    def _is_manifest(self, directory: str, manifest: str) -> bool:
        """Whether ``manifest`` is a file to read (``os.path.isfile``), its status kept
        (None where there is none to take): what says that the lookup would find the same
        next time. Not the directory's: a home directory or ``/tmp`` changes all the
        time, a ``package.xml`` appearing there does not; and a link to nothing, or into
        a directory that cannot be searched, may become a manifest with its directory
        unchanged. Where the walk listed the directory with no entry of that name, none
        is there: the walk's listings are trusted as they are for finding every file."""
        if directory in self._without_manifest:
            self.statuses[manifest] = None
            return False
        try:
            found = os.stat(manifest)
        except OSError:
            self.statuses[manifest] = None
            return False
        self.statuses[manifest] = status_from(found)
        return stat.S_ISREG(found.st_mode)

    def _for_directory(self, directory: str) -> _Package:
        found = self._by_directory.get(directory)
        if found is not None:
            return found
        manifest = os.path.join(directory, "package.xml")
        package: _Package
        if self._is_manifest(directory, manifest):
            text = _manifest_text(manifest) or ""
            package, exported = _package_said(text, directory)
            self.manifests[manifest] = _package_digest(package, exported)
            self._read_plugin_descriptions(directory, exported)
        elif (up := _parent(directory)) == directory:
            package = _NO_PACKAGE
        else:
            package = self._for_directory(up)
        self._by_directory[directory] = package
        return package


_IN_DIRECTORY = os.sep + "package.xml"


def is_package_manifest(path: str) -> bool:
    """Whether a manifest the lookups read (``PackageGenerations.manifests``) is a
    package.xml, not a plugin description."""
    return path.endswith(_IN_DIRECTORY) or path == "package.xml"


def manifest_digest(path: str) -> str | None:
    """The digest ``PackageGenerations.manifests`` keeps of a package.xml or plugin
    description read now; None where it cannot be read."""
    if is_package_manifest(path):
        text = _manifest_text(path)
        return None if text is None else _package_digest(*_package_said(text))
    text = _manifest_text(path, _MAX_DESCRIPTION)
    return None if text is None else _description_digest(plugin_names(text))


def _manifest_text(path: str, limit: int = -1) -> str | None:
    """A package.xml's or plugin description's text (its first ``limit`` characters), as
    the lookups read it; None where it cannot be read."""
    try:
        with open(path, encoding="utf-8", errors="replace") as stream:
            return stream.read(limit)
    except OSError:
        return None


def _package_said(text: str, directory: str | None = None) -> tuple[_Package, list[str]]:
    """The package a package.xml's text says (at ``directory``), and the plugin
    descriptions it exports."""
    package = _Package(
        package_xml_name(text), package_xml_generation(text), package_xml_depends(text), directory
    )
    return package, exported_descriptions(text)


def _package_digest(package: _Package, exported: Iterable[str]) -> str:
    """What ``PackageGenerations.manifests`` keeps of a package.xml: the digest of all a
    run reads in it (its name, generation, dependencies and the plugin descriptions it
    exports), not of its text. A version released, a maintainer or a description
    changed is then no other run: it changed no finding, yet built the whole graph again
    (8 s at 8 copies of the benchmark's workspace)."""
    said = [
        package.name or "",
        _generation_text(package),
        *sorted(package.depends),
        "",
        *exported,
    ]
    return content_digest("\n".join(said).encode("utf-8", "surrogateescape"))


def _description_digest(names: Iterable[str]) -> str:
    """What ``PackageGenerations.manifests`` keeps of a plugin description: the digest of
    the plugin names it gives (``plugins.plugin_names``), all a run reads in it."""
    return content_digest("\n".join(sorted(names)).encode("utf-8", "surrogateescape"))


def _generation_text(package: _Package) -> str:
    return "" if package.generation is None else str(package.generation.value)


def _parent(path: str) -> str:
    """``os.path.dirname(path)``, by one ``rpartition`` where the path has no repeated
    separator (every path a run asks about, 81,000 at 8 copies of the benchmark's
    workspace: ``dirname`` was a quarter of the lookup)."""
    head, separator, _ = path.rpartition(os.sep)
    if not separator:
        return ""
    if not head:
        return os.sep
    if head.endswith(os.sep):
        return os.path.dirname(path)  # "a//b", "//a": dirname's own answer
    return head


def workspace_plugin_names(
    sources: Iterable[SourceFile], packages: PackageGenerations
) -> frozenset[str]:
    """The names pluginlib gives the plugins the packages of ``sources`` export."""
    for source in sources:
        packages.for_file(source.location)
    return frozenset(packages.plugin_names)


def visible_service_types(types: frozenset[str], visible: frozenset[str] | None) -> frozenset[str]:
    """The ``package/Name`` service types of ``types`` whose package is in ``visible``
    (``PackageGenerations.visible_packages``); all of them when ``visible`` is None.

    A file can only serve or call a type of a package its package.xml depends on (or of
    its own package): a sibling package's ``.srv`` it does not depend on is no name its
    service could be after, whatever the two names share (issue 27: autoware's
    ``~/service/load_plugin`` held against a sibling planner's ``LoadPlugin``).
    """
    if visible is None:
        return types
    return frozenset(spelling for spelling in types if spelling.split("/", 1)[0] in visible)


def service_types(
    sources: Iterable[SourceFile], packages: PackageGenerations
) -> frozenset[tuple[Generation | None, str]]:
    """The generation and ``package/Name`` of every ``.srv`` file among ``sources``.

    The generation is the package's (None when it builds for both): a ROS 1 package's
    service type is no name for a ROS 2 service to be measured against.
    """
    return frozenset(
        (packages.for_file(source.path), f"{package}/{source.path.stem}")
        for source in sources
        if source.language is Language.SERVICE_DEFINITION
        and (package := packages.package_name(source.path))
    )
