"""Find the files to lint and tell which language each one is.

Directories are walked without following symbolic links (no loops), honouring
``.gitignore`` files, the configured ``exclude`` patterns, and ROS's own markers: a
directory holding ``COLCON_IGNORE``, ``CATKIN_IGNORE`` or ``AMENT_IGNORE`` is skipped, which
also keeps colcon's ``build/``, ``install/`` and ``log/`` copies of launch files out.
Files named on the command line are linted even when ``.gitignore`` matches them, but not
when ``exclude`` does (pre-commit passes every staged file; ``exclude`` must still hold).

No input stops the walk or passes in silence. Only regular files are opened (the
``.gitignore`` files and the heads sniffed too, through ``reading.open_regular``): a FIFO
never blocks the run. What the walk passes over for a reason the user should hear of (a
directory it cannot read, a FIFO or device named like a source, a ``.gitignore`` it
cannot read or a pattern of it that is invalid, a named path that yields no file) is one
line of the ``warnings`` the caller prints. A named path that cannot be linted at all (a
missing one, a FIFO, a directory that cannot be read) is a ``DiscoveryError``.
"""

from __future__ import annotations

import os
import re
import stat
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from enum import Enum
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Generic, TypeVar, cast

from . import walks
from .cache import FactsCache
from .collection import kept_for_the_run
from .errors import UserError
from .listings import DirectoryStatus, FileStatus, Listed, Listings
from .model import LANGUAGE_OF_VALUE, Language
from .reading import NotRegularFileError, open_regular

if TYPE_CHECKING:
    import pathspec

IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")
MANIFEST = "package.xml"
SKIPPED_DIRECTORIES = frozenset({".git", ".hg", ".svn", "__pycache__", ".mypy_cache", ".tox"})
SNIFF_BYTES = 64 * 1024
_T = TypeVar("_T")

# Files no extractor reads that hold ROS names all the same: `rosparam` and ROS 2
# parameter files, rviz displays, dynamic_reconfigure `.cfg`, Gazebo worlds, scripts.
_CONFIGURATION_SUFFIXES = frozenset(
    {".yaml", ".yml", ".xml", ".cfg", ".rviz", ".json", ".ini", ".toml", ".sdf", ".world"}
    | {".sh", ".bash", ".cmake", ".perspective"}
)
_CPP_SUFFIXES = frozenset({".cpp", ".cc", ".cxx", ".c++", ".hpp", ".hh", ".hxx", ".h", ".ipp"})
_YAML_LAUNCH_KEY = re.compile(rb"^launch\s*:", re.MULTILINE)
# Every dynamic_reconfigure .cfg makes a ``ParameterGenerator()`` (parameter_generator_catkin).
_RECONFIGURE_MARKER = b"ParameterGenerator"
# `#!/usr/bin/env python3`, `#!/usr/bin/python`, `#!/usr/bin/env -S python3 -u`: the line
# catkin_install_python rewrites and every ROS script without a `.py` suffix starts with.
_PYTHON_SHEBANG = re.compile(rb"#![ \t]*\S*?(?:/env(?:[ \t]+-\S+)*[ \t]+|/)python[0-9.]*(?:\s|$)")
_SHEBANG_BYTES = 128


class DiscoveryError(UserError):
    """A path named by the user that cannot be linted."""


@dataclass(frozen=True)
class _Notes:
    """Where the walk writes what it passed over, each line naming its path as reports
    show it (relative to ``prefix``, the current directory ending in a separator)."""

    prefix: str
    lines: list[str]

    def shown(self, path: str) -> str:
        return _displayed(path, self.prefix)

    def add(self, line: str) -> None:
        self.lines.append(line)


@dataclass(frozen=True)
class SourceFile:
    location: str  # the absolute path
    display: str  # what reports show: relative to the current directory when below it
    language: Language

    @cached_property
    def path(self) -> Path:
        """``location`` as a ``Path``, made when asked: a re-run with nothing changed asks
        for none of the workspace's, and making 80,000 of them costs 0.4 s."""
        return Path(self.location)


# Build files: not linted, but they map launch files' executables to their sources.
_BUILD_FILES = {
    "cmakelists.txt": Language.CMAKE,
    "setup.py": Language.SETUP_PY,
    "setup.cfg": Language.SETUP_CFG,
}


class _Sniff(Enum):
    """A suffix the name alone does not decide: the content says (``classify``)."""

    XML = "xml"
    YAML = "yaml"
    SCRIPT = "script"  # no suffix at all: a ROS script is Python by its shebang
    CFG = "cfg"  # a dynamic_reconfigure config, or an INI file (CPPLINT.cfg, tox.cfg)


# What a kept listing says a name said (``listings``): the values of both enums, which differ.
_SAID: dict[str, Language | _Sniff] = {said.value: said for said in (*Language, *_Sniff)}


def classify(path: Path) -> Language | None:
    """The language of a file, sniffing the content only for ambiguous suffixes."""
    return _decide(path, _by_name(path.name))


def _decide(path: str | Path, by_name: Language | _Sniff | None) -> Language | None:
    if by_name is _Sniff.XML:
        return _sniff_xml(path)
    if by_name is _Sniff.YAML:
        # Any other YAML may be a parameter file: its content and its package decide
        # (``extract.parameter_file``), and the launch files that load it.
        return Language.LAUNCH_YAML if _YAML_LAUNCH_KEY.search(_head(path)) else Language.PARAMETERS
    if by_name is _Sniff.SCRIPT:
        return Language.PYTHON if _PYTHON_SHEBANG.match(_head(path, _SHEBANG_BYTES)) else None
    if by_name is _Sniff.CFG:
        return Language.RECONFIGURE if _RECONFIGURE_MARKER in _head(path) else None
    return by_name


def _by_name(file_name: str) -> Language | _Sniff | None:
    """What the name says: a language, that the content must say, or nothing to lint. The
    walk asks this of every file, before any ignore rule, so it reads no file and builds
    no ``Path``."""
    name = file_name.lower()
    suffix = os.path.splitext(name)[1]
    if suffix in (".launch", ".test") or name.endswith(("_launch.xml", ".launch.xml")):
        return Language.LAUNCH_XML
    if name.endswith((".launch.yaml", "_launch.yaml", ".launch.yml", "_launch.yml")):
        return Language.LAUNCH_YAML
    if suffix in (".urdf", ".xacro"):
        return Language.URDF
    if suffix in _CPP_SUFFIXES:
        return Language.CPP
    if name in _BUILD_FILES:
        return _BUILD_FILES[name]
    if suffix == ".cmake":
        return Language.CMAKE  # a module of the package's build: what it compiles counts
    if suffix == ".py":
        return Language.PYTHON
    if suffix == ".cfg":
        return _Sniff.CFG
    if suffix == ".srv":
        return Language.SERVICE_DEFINITION
    if name == MANIFEST:
        return Language.PACKAGE_XML
    if suffix == ".xml":
        return _Sniff.XML
    if suffix in (".yaml", ".yml"):
        return _Sniff.YAML
    if "." not in name:
        return _Sniff.SCRIPT  # catkin's scripts/talker, ament's installed tools
    return None


def _sniff_xml(path: str | Path) -> Language | None:
    from .extract.launch.xmlsafe import root_tag  # lxml is imported only when an .xml file is seen

    tag = root_tag(_head(path))
    if tag == "launch":
        return Language.LAUNCH_XML
    if tag == "robot":
        return Language.URDF
    return None


def _head(path: str | Path, size: int = SNIFF_BYTES) -> bytes:
    try:
        with open_regular(path) as stream:
            return stream.read(size)
    except OSError:
        return b""  # unreadable: classified by name only, and reported when read for real


def display_path(path: Path, cwd: Path) -> str:
    """The path reports show: relative to ``cwd`` when below it, always valid Unicode.

    A file name that is not UTF-8 (``caf\\xe9.launch`` from a Latin-1 system) shows its
    undecodable bytes as ``\\xe9`` escapes: every report format must stay valid UTF-8.
    """
    return _displayed(os.fspath(path), os.path.join(os.fspath(cwd), ""))


def display_path_text(path: str) -> str:
    """A relative path string as reports show it (``display_path``)."""
    return _displayed(path, "")


def _displayed(path: str, prefix: str) -> str:
    """``display_path`` of a path string, ``prefix`` the current directory ending in a
    separator. String operations, not ``relative_to``: this runs for every file of the
    workspace."""
    text = path[len(prefix) :] if path.startswith(prefix) else path
    if os.sep != "/":
        text = text.replace(os.sep, "/")
    if text.isascii():  # nothing to escape: most paths
        return text
    return os.fsencode(text).decode("utf-8", errors="backslashreplace")


class _IgnoreRules:
    """``.gitignore`` files and ``exclude`` patterns, each relative to its own directory.

    Paths are plain strings here: the walk meets every file of the tree, and building a
    ``Path`` for each costs more than the matching.
    """

    def __init__(self, exclude: Sequence[str], exclude_root: Path, notes: _Notes) -> None:
        self._notes = notes
        # Each spec with the directory its patterns are relative to, ending in a separator.
        self._specs: list[tuple[str, _Spec]] = []
        if exclude:
            self._specs.append((_directory_prefix(os.fspath(exclude_root)), _Spec(exclude)))
        self._exclude_count = len(self._specs)

    def excluded_by_config(self, path: Path, is_dir: bool) -> bool:
        return any(
            _matches(spec, prefix, os.fspath(path), is_dir)
            for prefix, spec in self._specs[: self._exclude_count]
        )

    def ignored(self, path: str, is_dir: bool) -> bool:
        return any(_matches(spec, prefix, path, is_dir) for prefix, spec in self._specs)

    def enter(self, directory: str | Path, *, known_valid: bool = False) -> tuple[int, bool]:
        """Read ``directory/.gitignore``: how many rules to pop on leaving it, and whether
        it was read and every pattern of it is valid (nothing said). ``known_valid``: it
        is as it was when it was found so (``listings``): its patterns are compiled only
        if a path is matched against them, which a replayed walk never does."""
        path = os.path.join(directory, ".gitignore")
        try:
            with open_regular(path) as stream:
                lines = stream.read().decode("utf-8", errors="replace").splitlines()
        except (FileNotFoundError, NotADirectoryError):
            return 0, True  # the usual case above a named directory: none there
        except OSError as error:
            reason = error.strerror or str(error)
            shown = self._notes.shown(path)
            self._notes.add(f"cannot read {shown}: {reason}; its patterns are not applied")
            return 0, False
        if known_valid:
            spec, valid = _Spec(lines, compiled=False), True
        else:
            spec, valid = self._spec(path, lines)
        self._specs.append((_directory_prefix(os.fspath(directory)), spec))
        return 1, valid

    def _spec(self, path: str, lines: list[str]) -> tuple[_Spec, bool]:
        """The patterns of ``lines``; an invalid one is left out, as git leaves it, and
        said. Whether all were valid."""
        try:
            return _Spec(lines), True
        except _INVALID_PATTERN:
            pass
        valid = []
        for number, line in enumerate(lines, start=1):
            reason = pattern_error(line)
            if reason is None:
                valid.append(line)
            else:
                shown = self._notes.shown(path)
                self._notes.add(f"{shown}:{number}: invalid pattern {line!r} not applied: {reason}")
        return _Spec(valid), False

    def leave(self, count: int) -> None:
        del self._specs[len(self._specs) - count :]


class _Spec:
    """A ``.gitignore``'s patterns, with one regular expression that matches where any of
    them does: most paths match none, and one search then answers instead of one search
    per pattern (pathspec's way, which keeps the last match: a ``!`` may undo an earlier
    one). A path it matches is handed to pathspec for the exact answer.

    Compiled at once (raising for an invalid pattern), or with ``compiled=False`` when
    first matched: 300 ``.gitignore`` files cost 0.1 s to compile, for a walk that may
    match nothing against them. Lines that then turn out invalid (the file was edited
    between its status and its read) are left out as git leaves them; the next walk,
    which sees the new status, says so."""

    def __init__(self, lines: Sequence[str], *, compiled: bool = True) -> None:
        self._lines = lines
        self._checked = compiled
        if compiled:
            self._patterns  # noqa: B018 - compiled now: an invalid pattern raises here

    @cached_property
    def _patterns(self) -> tuple[pathspec.GitIgnoreSpec, re.Pattern[str] | None]:
        import pathspec

        try:
            spec = pathspec.GitIgnoreSpec.from_lines(self._lines)
        except _INVALID_PATTERN:
            if self._checked:
                raise
            valid = [line for line in self._lines if pattern_error(line) is None]
            spec = pathspec.GitIgnoreSpec.from_lines(valid)
        expressions = [
            _NAMED_GROUP.sub("(?:", regex.pattern)
            for pattern in spec.patterns
            if pattern.include is not None and (regex := getattr(pattern, "regex", None))
        ]
        try:
            any_pattern: re.Pattern[str] | None = re.compile(
                "|".join(f"(?:{expression})" for expression in expressions) or "(?!)"
            )
        except re.error:  # a pattern form we did not foresee: pathspec alone decides
            any_pattern = None
        return spec, any_pattern

    def match_file(self, relative: str) -> bool:
        spec, any_pattern = self._patterns
        # pathspec searches each pattern: "*/" is a "/" anywhere in the path
        if any_pattern is not None and any_pattern.search(relative) is None:
            return False
        return bool(spec.match_file(relative))


_NAMED_GROUP = re.compile(r"\(\?P<\w+>")
# What pathspec raises for a pattern it cannot compile: its own ValueError ('!' alone, a
# trailing backslash) or the regular expression's (a range such as '[z-a]').
_INVALID_PATTERN = (ValueError, re.error)


def pattern_error(pattern: str) -> str | None:
    """Why ``pattern`` is not a valid gitignore pattern, or None when it is."""
    import pathspec

    try:
        pathspec.GitIgnoreSpec.from_lines([pattern])
    except re.error as error:
        return error.msg  # without the position, which is in pathspec's translation
    except ValueError:
        return "git does not accept it"
    return None


def _directory_prefix(directory: str) -> str:
    return directory.rstrip(os.sep) + os.sep


def _matches(spec: _Spec, prefix: str, path: str, is_dir: bool) -> bool:
    if not path.startswith(prefix):
        return False
    relative = path[len(prefix) :].replace(os.sep, "/")
    return spec.match_file(relative + "/" if is_dir else relative)


def discover(
    paths: Sequence[Path],
    exclude: Sequence[str],
    exclude_root: Path,
    cwd: Path,
    warnings: list[str] | None = None,
    *,
    cache: FactsCache | None = None,
    without_manifest: set[str] | None = None,
) -> list[SourceFile]:
    """Every lintable file under ``paths``, sorted by display path, each once.

    What was passed over and why, one line each, is appended to ``warnings``; the
    paths named that cannot be linted at all raise ``DiscoveryError``. With a ``cache``,
    each named directory's walk keeps its listings there (``listings``) and lists again
    only what changed since the last one. The directories walked that hold no entry
    named ``package.xml`` join ``without_manifest`` (``generation.PackageGenerations``).
    """
    # What the walk finds lives as long as the run, and holds no cycle: the collector
    # does not walk it again and again (``collection``).
    with kept_for_the_run():
        return _discover(
            paths,
            exclude,
            exclude_root,
            cwd,
            warnings,
            cache=cache,
            without_manifest=without_manifest,
        )


def _discover(
    paths: Sequence[Path],
    exclude: Sequence[str],
    exclude_root: Path,
    cwd: Path,
    warnings: list[str] | None,
    *,
    cache: FactsCache | None,
    without_manifest: set[str] | None,
) -> list[SourceFile]:
    prefix = os.path.join(os.fspath(cwd), "")
    notes = _Notes(prefix, [] if warnings is None else warnings)
    rules = _IgnoreRules(exclude, exclude_root, notes)
    found: dict[str, SourceFile] = {}
    for given in paths:
        absolute = (cwd / given).absolute()
        mode, unfollowable = _named_status(given, absolute)
        if mode is not None and stat.S_ISDIR(mode):
            walked: list[tuple[str, Language | _Sniff]]
            listings = None
            if cache is not None:
                kept_at = Listings.path_of(cache, os.fspath(absolute), exclude, exclude_root)
                above = [join_gitignore(ancestor) for ancestor in _repository_ancestors(absolute)]
                kept = walks.taken(kept_at, prefix, above, _WALK)
                if kept is not None and kept.again:
                    kept = _walked_again(kept, absolute, exclude, exclude_root, prefix)
                if kept is not None and _take_walked(found, kept, without_manifest):
                    if not kept.found:
                        notes.add(f"{given}: no file to lint in this directory")
                    if kept.amended is not None:
                        walks.refresh(cache, kept_at, kept.amended)
                    continue
                listings = Listings(kept_at, cache)
            noted = len(notes.lines)
            try:
                walked = _walk_named(
                    absolute, rules, _by_name, notes, listings, without_manifest=without_manifest
                )
            except OSError as error:
                reason = error.strerror or str(error)
                raise DiscoveryError(f"{given}: cannot read directory: {reason}") from None
            lintable = [_add(found, path, by_name, prefix, listings) for path, by_name in walked]
            if cache is not None and listings is not None:
                listings.save()  # what the files' content said too
                if len(notes.lines) == noted:  # a walk that warned warns again
                    files = [
                        found[path]
                        for (path, _), added in zip(walked, lintable, strict=True)
                        if added
                    ]
                    kept_files = [
                        (file.location, file.display, file.language.value) for file in files
                    ]
                    walks.keep(cache, listings, prefix, kept_files)
            if not any(lintable):
                notes.add(f"{given}: no file to lint in this directory")
        elif not rules.excluded_by_config(absolute, is_dir=False):
            added_file = _add(found, os.fspath(absolute), _by_name(absolute.name), prefix)
            if unfollowable is not None and not added_file:
                notes.add(f"{given}: not linted: {unfollowable}")
    # By display, then by path: two files may show alike (a name of Latin-1 bytes, shown
    # escaped, beside one spelling that escape), and the walk's order must not decide.
    return sorted(found.values(), key=lambda source: (source.display, source.location))


def _take_walked(
    found: dict[str, SourceFile], kept: walks.Taken, without_manifest: set[str] | None
) -> bool:
    """Add the files a kept walk found (``walks``); False, adding nothing, where what was
    kept is not what a walk keeps."""
    try:
        taken = [
            SourceFile(path, shown, LANGUAGE_OF_VALUE[said]) for path, shown, said in kept.found
        ]
    except (KeyError, TypeError, ValueError):
        return False
    for source in taken:
        found[source.location] = source
    if without_manifest is not None:
        without_manifest.update(kept.without_manifest)
    return True


def _walked_again(
    kept: walks.Taken, top: Path, exclude: Sequence[str], exclude_root: Path, prefix: str
) -> walks.Taken | None:
    """``kept`` with the directories it names to walk again walked, under the ignore
    rules above each as the kept walk read them (those of the repository above ``top``,
    the kept ``.gitignore`` files from ``top`` down) and its own; None where that walk
    warned or chose a link (the whole is walked then, and says so)."""
    notes = _Notes(prefix, [])
    chosen: list[tuple[str, Language | _Sniff]] = []
    without: set[str] = set()
    gitignores = set(kept.gitignores)
    ancestors = _repository_ancestors(top)
    for directory in kept.again:
        rules = _IgnoreRules(exclude, exclude_root, notes)
        for ancestor in ancestors:
            rules.enter(ancestor)
        for above in _directories_down_to(os.fspath(top), directory):
            if join_gitignore(above) in gitignores:
                rules.enter(above)
        walker = _Walker(rules, _by_name, chosen, notes, None, without)
        walker.walk(directory, trusted=False)
    if notes.lines or any(os.path.islink(path) for path, _ in chosen):
        return None
    files: list[walks.Found] = []
    for path, by_name in chosen:
        language = by_name if isinstance(by_name, Language) else _decide(path, by_name)
        if language is not None:
            files.append((path, _displayed(path, prefix), language.value))
    bases = tuple(directory.rstrip(os.sep) + os.sep for directory in kept.again)

    def outside(path: str) -> bool:
        return path not in kept.again and not path.startswith(bases)

    return walks.Taken(
        [found for found in kept.found if outside(found[0])] + files,
        [directory for directory in kept.without_manifest if outside(directory)] + sorted(without),
        [],
        kept.gitignores,
        kept.amended,
    )


def _directories_down_to(top: str, directory: str) -> list[str]:
    """The directories from ``top`` down to the one holding ``directory``, outermost
    first (none where ``directory`` is ``top``)."""
    relative = os.path.relpath(directory, top)
    if relative == os.curdir:
        return []
    parts = relative.split(os.sep)[:-1]
    return [os.path.join(top, *parts[:count]) for count in range(len(parts) + 1)]


def _may_choose(file_name: str) -> bool:
    """Whether a walk may choose a file of this name, or choose otherwise for it (a
    ``.gitignore``, an ignore marker)."""
    return (
        _by_name(file_name) is not None or file_name == ".gitignore" or file_name in IGNORE_MARKERS
    )


def _said(path: str) -> str:
    """The value of the language a file's name and content say, "" for none."""
    language = _decide(path, _by_name(os.path.basename(path)))
    return "" if language is None else language.value


def _passed_over(directory_name: str) -> bool:
    """Whether a walk never enters a directory of this name, whatever ignores it."""
    return directory_name in SKIPPED_DIRECTORIES


_WALK = walks.Walk(_may_choose, _passed_over, _said)


def join_gitignore(directory: str | Path) -> str:
    """The ``.gitignore`` of a directory above a named one (``_walk_named``)."""
    return os.path.join(directory, ".gitignore")


def _named_status(given: Path, absolute: Path) -> tuple[int | None, str | None]:
    """The mode of a path the user named (links followed), or why it cannot be followed
    (a link in a loop, or to nothing): such a link is linted as a file, where its name
    says it is one, and reading it then says why, as one finding. A missing path, and
    a FIFO, socket or device (never opened: a FIFO would block), raise
    ``DiscoveryError``."""
    try:
        mode = os.stat(absolute).st_mode
    except OSError as error:
        reason = error.strerror or str(error)
        if not os.path.lexists(absolute):
            # Missing, or behind a directory that cannot be searched (not even lstat).
            missing = isinstance(error, FileNotFoundError)
            raise DiscoveryError(
                f"{given}: {'no such file or directory' if missing else reason}"
            ) from None
        return None, reason
    if not (stat.S_ISDIR(mode) or stat.S_ISREG(mode)):
        raise DiscoveryError(f"{given}: {NotRegularFileError(absolute, mode).strerror}")
    return mode, None


def text_files(
    paths: Sequence[Path], exclude: Sequence[str], exclude_root: Path, cwd: Path
) -> list[Path]:
    """Every file under ``paths`` that can hold a ROS name, sorted: the lintable ones and
    the configuration no extractor reads (parameter files, rviz and dynamic_reconfigure
    configs, scripts). What a rename must search before it is offered (``renames``);
    documentation is left out, it does not break when a name changes."""
    # Quiet: what the walk passes over is the lint run's to say (``discover``), and a
    # rename's search comes after one over the same tree.
    notes = _Notes(os.path.join(os.fspath(cwd), ""), [])
    rules = _IgnoreRules(exclude, exclude_root, notes)
    found: set[Path] = set()
    for given in paths:
        absolute = (cwd / given).absolute()
        if absolute.is_dir():
            try:
                walked = _walk_named(absolute, rules, _holds_names, notes)
            except OSError:
                continue
            found.update(Path(path) for path, _ in walked)
        elif absolute.is_file() and not rules.excluded_by_config(absolute, is_dir=False):
            found.add(absolute)
    return sorted(found)


def _holds_names(file_name: str) -> bool | None:
    """True for a file a name may be in: lintable or configuration (``text_files``)."""
    if _by_name(file_name) is not None:
        return True
    return os.path.splitext(file_name.lower())[1] in _CONFIGURATION_SUFFIXES or None


def workspace_root(path: Path) -> Path | None:
    """The workspace a file belongs to, for the graph rules of a per-file run.

    The nearest directory above it whose ``src/`` holds packages (a catkin or colcon
    workspace), else the root of its git repository; None when it is in neither.
    """
    return _enclosing_workspace(path.parent)


def editor_workspace(directory: Path) -> Path | None:
    """The workspace an editor that opened ``directory`` works in: the workspace at or
    above it as ``workspace_root`` finds one (an editor rooted at a package still sees the
    packages beside it), else ``directory`` itself where it is a package or holds some;
    None for any other directory (a home directory, a download folder), which is never
    read whole."""
    found = _enclosing_workspace(directory)
    if found is None and ((directory / "package.xml").is_file() or _holds_packages(directory)):
        return directory
    return found


def _enclosing_workspace(directory: Path) -> Path | None:
    """The nearest of ``directory`` and the directories above it whose ``src/`` holds
    packages, or that is a git repository's root."""
    for candidate in (directory, *directory.parents):
        source = candidate / "src"
        if source.is_dir() and _holds_packages(source):
            return candidate
        if (candidate / ".git").exists():
            return candidate
    return None


def _holds_packages(directory: Path) -> bool:
    """A package.xml one or two levels down (``src/pkg``, ``src/repo/pkg``)."""
    return any(directory.glob("*/package.xml")) or any(directory.glob("*/*/package.xml"))


def _repository_ancestors(directory: Path) -> list[Path]:
    """The directories above ``directory`` up to its git root, outermost first.

    Their ``.gitignore`` files apply to ``directory`` as they do for git. Outside a git
    repository no parent's ``.gitignore`` is read.
    """
    ancestors: list[Path] = []
    for parent in directory.parents:
        ancestors.append(parent)
        if (parent / ".git").exists():
            return ancestors[::-1]
    return []


def _add(
    found: dict[str, SourceFile],
    path: str,
    by_name: Language | _Sniff | None,
    prefix: str,
    listings: Listings | None = None,
) -> bool:
    """Add the file at ``path`` if it is lintable, shown relative to ``prefix``; whether
    it is. A file whose content decides is asked only when it changed since ``listings``
    kept what it said."""
    if isinstance(by_name, Language):
        language: Language | None = by_name
    elif isinstance(by_name, _Sniff) and listings is not None:
        status, said = listings.sniffed(path)
        if said is not None:
            language = Language(said) if said else None
        else:
            language = _decide(path, by_name)
            listings.keep_sniffed(path, status, "" if language is None else language.value)
    else:
        language = _decide(path, by_name)
    if language is None:
        return False
    # package.xml too: the workspace model needs every package
    found[path] = SourceFile(path, _displayed(path, prefix), language)
    return True


def _walk_named(
    directory: Path,
    rules: _IgnoreRules,
    select: Callable[[str], _T | None],
    notes: _Notes,
    listings: Listings | None = None,
    *,
    without_manifest: set[str] | None = None,
) -> list[tuple[str, _T]]:
    """The walk of a directory named by the user, under the ``.gitignore`` files of its
    repository above it, as git applies them. Raises ``OSError`` when ``directory``
    itself cannot be read. With ``listings`` (``select`` is then ``_by_name``), the
    directories whose status is what it was are not listed again. The directories
    walked that hold no ``package.xml`` join ``without_manifest``."""
    top = os.fspath(directory)
    ancestors = _repository_ancestors(directory)
    trusted = listings is not None and listings.trusts_ancestors(
        [join_gitignore(ancestor) for ancestor in ancestors]
    )
    pushed = sum(rules.enter(ancestor)[0] for ancestor in ancestors)
    found: list[tuple[str, _T]] = []
    walker = _Walker(rules, select, found, notes, listings)
    if without_manifest is not None:
        walker.without_manifest = without_manifest
    walker.walk(top, trusted=trusted, named=True)
    rules.leave(pushed)
    return found


def _listing(directory: str) -> list[os.DirEntry[str]]:
    return sorted(os.scandir(directory), key=lambda entry: entry.name)


@dataclass
class _Walker(Generic[_T]):
    """Appends the selected files under a directory to ``found``. A list, not a
    generator: every file found would pass up through one generator per level."""

    rules: _IgnoreRules
    select: Callable[[str], _T | None]
    found: list[tuple[str, _T]]
    notes: _Notes
    listings: Listings | None
    # The directories listed (or replayed: as they were listed) holding no entry named
    # ``package.xml``: no package lookup needs to look for one there.
    without_manifest: set[str] = field(default_factory=set)

    def walk(self, top: str, *, trusted: bool, named: bool = False) -> None:
        """Walk ``top``; ``trusted`` when the ignore rules above it are those its kept
        listing was made under. Only the named directory's listing raises ``OSError``."""
        status = None
        if self.listings is not None:
            self.listings.walked += 1
            status = self.listings.directory_status(top)  # before listing: a change shows
            kept = self.listings.unchanged(top, status) if trusted else None
            if kept is not None and self._replay(top, kept):
                return
        try:
            entries = _listing(top)
        except OSError as error:
            if named:
                raise
            # Said, not passed over: the files in it are not linted, and the user should know.
            reason = error.strerror or str(error)
            self.notes.add(f"cannot read directory {self.notes.shown(top)}: {reason}")
            return
        self._list(top, entries, status, trusted)

    def _replay(self, top: str, kept: Listed) -> bool:
        """Walk ``top`` as ``kept`` lists it; False when its ``.gitignore`` changed."""
        assert self.listings is not None
        pushed = 0
        if kept.gitignore is not None:
            if self.listings.file_status(os.path.join(top, ".gitignore")) != kept.gitignore:
                return False
            pushed, _ = self.rules.enter(top, known_valid=kept.gitignore_valid)
        self.listings.keep(top, kept)
        if not kept.manifest:
            self.without_manifest.add(top)
        if not kept.stop:
            # Joined by hand: ``os.path.join`` for every file of the workspace costs 0.1 s.
            base = top if top.endswith(os.sep) else top + os.sep
            # Kept only for ``_by_name``'s walk, whose selections ``_SAID`` reads back.
            self.found.extend((base + name, cast(_T, _SAID[said])) for name, said in kept.files)
            for name, said in kept.links:
                if _is_file(base + name, self.notes):
                    self.found.append((base + name, cast(_T, _SAID[said])))
            for name in kept.directories:
                self.walk(base + name, trusted=True)
        self.rules.leave(pushed)
        return True

    def _list(
        self,
        top: str,
        entries: list[os.DirEntry[str]],
        status: DirectoryStatus | None,
        trusted: bool,
    ) -> None:
        """Walk ``top`` from its ``entries``, and keep what it found."""
        names = {entry.name for entry in entries}
        manifest = _holds_manifest(names)
        if not manifest:
            self.without_manifest.add(top)
        listings = self.listings
        previous = None if listings is None else listings.previous(top)
        if not names.isdisjoint(IGNORE_MARKERS):
            if listings is not None:
                listings.keep(top, Listed(status, None, False, True, (), (), (), manifest))
            return
        gitignore: FileStatus | None = None
        pushed, valid = 0, False
        # Only where the listing shows one: trying to open a .gitignore in every directory
        # costs a failed system call each.
        if ".gitignore" in names:
            if listings is not None:
                gitignore = listings.file_status(os.path.join(top, ".gitignore"))
            pushed, valid = self.rules.enter(top)
        # The kept listings below were made under this directory's .gitignore as it was.
        keepable = ".gitignore" not in names or gitignore is not None
        trusted = trusted and keepable and previous is not None and previous.gitignore == gitignore
        directories: list[str] = []
        files: list[tuple[str, str]] = []
        links: list[tuple[str, str]] = []
        for entry in entries:
            if entry.is_dir(follow_symlinks=False):
                if entry.name in SKIPPED_DIRECTORIES or self.rules.ignored(entry.path, is_dir=True):
                    continue
                directories.append(entry.name)
                self.walk(entry.path, trusted=trusted)
            elif (by_name := self.select(entry.name)) is not None and not self.rules.ignored(
                entry.path, is_dir=False
            ):
                said = getattr(by_name, "value", "")
                if entry.is_symlink():
                    links.append((entry.name, said))
                elif not entry.is_file():
                    keepable = False  # a FIFO or device: said again each time
                if _is_file(entry, self.notes):
                    self.found.append((entry.path, by_name))
                    if not entry.is_symlink():
                        files.append((entry.name, said))
        self.rules.leave(pushed)
        if listings is not None and keepable:
            kept = Listed(
                status,
                gitignore,
                valid,
                False,
                tuple(directories),
                tuple(files),
                tuple(links),
                manifest,
            )
            listings.keep(top, kept)


def _holds_manifest(names: set[str]) -> bool:
    """Whether a directory of these entries may hold a package.xml: an entry of that name
    in any case, which a file system that ignores case (macOS's, Windows') opens as one."""
    return MANIFEST in names or any(
        name.lower() == MANIFEST for name in names if len(name) == len(MANIFEST)
    )


def _is_file(entry: os.DirEntry[str] | str, notes: _Notes) -> bool:
    """A file, or a link that cannot be followed (to itself, in a loop): reading it then
    says why, as one finding, rather than the walk stopping. A FIFO, socket or device
    named like a source is passed over, and said (a link to a directory, not followed,
    and a link to nothing are passed over as they always were). ``entry`` is a path
    for a link a kept listing names."""
    path = entry if isinstance(entry, str) else entry.path
    try:
        if isinstance(entry, str):
            mode = os.stat(entry).st_mode
            if stat.S_ISREG(mode):
                return True
        elif entry.is_file():
            return True
        else:
            mode = entry.stat().st_mode
    except FileNotFoundError:
        return False  # a link to nothing
    except OSError:
        return True
    if not stat.S_ISDIR(mode):
        reason = NotRegularFileError(path, mode).strerror
        notes.add(f"skipped {notes.shown(path)}: {reason}")
    return False
