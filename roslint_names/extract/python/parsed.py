"""Python files past the prefilter: decode, parse once, walk once, extract, assemble.

Imported by ``python.py`` only after its prefilter passed, because it imports libcst.
"""

from __future__ import annotations

import threading
from collections import OrderedDict

import libcst as cst

from roslint_names.extract import evidence
from roslint_names.extract.launch.python_launch import LaunchExtractor
from roslint_names.extract.launch.python_values import LaunchCalls
from roslint_names.extract.launch.substitution import Source
from roslint_names.extract.literals import name_literals, unexplained_literals
from roslint_names.extract.parameter_traits import (
    parameter_traits,
    python_class_bases,
    reconfigure_servers,
)
from roslint_names.extract.python.code import CodeExtractor
from roslint_names.extract.python.python2 import Rewritten, rewrite
from roslint_names.extract.python.source import decode, parse
from roslint_names.extract.python.spans import Locator
from roslint_names.extract.python.walk import Walk
from roslint_names.model import (
    FileFacts,
    Generation,
    Language,
    LaunchArguments,
    ParameterTrait,
    ParseError,
    Span,
)

# Imports that only exist in one generation (tf2_ros, message_filters and the message
# packages exist in both).
_ROS1_PACKAGES = frozenset(
    {"rospy", "roslib", "actionlib", "tf", "rostest", "rosbag", "roslaunch", "rosgraph"}
)
_ROS2_PACKAGES = frozenset(
    {"rclpy", "launch", "launch_ros", "launch_testing", "launch_testing_ros", "ament_index_python"}
)
_LAUNCH_PACKAGES = frozenset({"launch", "launch_ros"})
_NODE_PACKAGES = frozenset({"rospy", "rclpy"})
_ROOTS = frozenset({"generate_launch_description", "generate_test_description"})


def import_generation(packages: set[str]) -> Generation | None:
    ros1 = len(packages & _ROS1_PACKAGES)
    ros2 = len(packages & _ROS2_PACKAGES)
    if ros1 == ros2:
        return None
    return Generation.ROS1 if ros1 > ros2 else Generation.ROS2


def extract_parsed(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
    launch_path: bool,
    *,
    arguments: LaunchArguments = (),
    python2: bool = False,
) -> FileFacts:
    """``python2``: the file may be Python 2 (a ROS 1 package's, see ``python2``)."""
    default_language = Language.LAUNCH_PYTHON if launch_path else Language.PYTHON
    key = (data, package_generation, fallback_generation, python2)
    prepared = _LAUNCH_FILES.begin(key)
    if isinstance(prepared, ParseError):
        generation = package_generation or fallback_generation
        return FileFacts(path, default_language, generation, parse_errors=(prepared,))
    language = default_language
    try:
        walk, locator, code, launch_calls, generation, text = prepared
        file_name = path.replace("\\", "/").rpartition("/")[2]
        launch = LaunchExtractor(walk, locator, file_name, arguments, launch_calls)
        launch.run()
        defines_root = any(function.name.value in _ROOTS for function in walk.functions)
        launch_module = launch.found_actions and not (walk.packages & _NODE_PACKAGES)
        if launch_path or defines_root or launch_module:
            language = Language.LAUNCH_PYTHON
        names = sorted(code.names + launch.names, key=lambda use: (use.span.line, use.span.column))
    except RecursionError:  # the launch part follows the tree recursively too
        generation = package_generation or fallback_generation
        return FileFacts(path, default_language, generation, parse_errors=(_TOO_DEEP,))
    finally:
        # Only a launch file is extracted again (under its includers' arguments).
        _LAUNCH_FILES.end(key, prepared, keep=language is Language.LAUNCH_PYTHON)
    return FileFacts(
        path=path,
        language=language,
        generation=generation,
        names=tuple(names),
        launch_nodes=tuple(launch.nodes),
        events=tuple(code.events),
        includes=tuple(launch.includes),
        literals=() if language is Language.LAUNCH_PYTHON else name_literals(text),
        parameter_traits=() if language is Language.LAUNCH_PYTHON else _traits(text),
        reconfigure_servers=()
        if language is Language.LAUNCH_PYTHON
        else reconfigure_servers(text.encode("utf-8", "surrogatepass"), python=True),
        class_bases=() if language is Language.LAUNCH_PYTHON else _bases(text),
        unexplained_literals=()
        if language is Language.LAUNCH_PYTHON
        else unexplained_literals(text.encode("utf-8", "surrogatepass"), names, python=True),
    )


def _traits(text: str) -> tuple[ParameterTrait, ...]:
    return parameter_traits(text.encode("utf-8", "surrogatepass"))


def _bases(text: str) -> tuple[tuple[str, tuple[str, ...]], ...]:
    return python_class_bases(text.encode("utf-8", "surrogatepass"))


_Prepared = tuple[Walk, Locator, CodeExtractor, LaunchCalls, Generation, str]
_Key = tuple[bytes, Generation | None, Generation, bool]


class _RecentLaunchFiles:
    """The prepared trees of the last launch files extracted, for their extractions under
    includers' arguments. Only launch files: a library or test module is never extracted
    again, and keeping its tree (a large module's is tens of megabytes) only costs memory.

    A tree neither kept here nor being extracted is released (``Walk.release``) at once,
    so that reference counting frees it: left to the cycle collector, the trees of the
    launch files pushed out were a third of a cold run's collections' work. Locked and
    counting its users: the language server extracts in two threads, which may share a
    tree."""

    def __init__(self, kept: int) -> None:
        self._kept = kept
        self._found: OrderedDict[_Key, _Prepared] = OrderedDict()
        self._users: dict[int, int] = {}  # extractions under way, by ``id`` of their walk
        self._lock = threading.Lock()

    def begin(self, key: _Key) -> _Prepared | ParseError:
        """The file prepared (kept, else now), for one extraction that calls ``end``."""
        with self._lock:
            found = self._found.get(key)
            if found is not None:
                self._found.move_to_end(key)
                self._use(found, 1)
                return found
        prepared = _prepare(*key)  # outside the lock: the parse is the long part
        if not isinstance(prepared, ParseError):
            with self._lock:
                self._use(prepared, 1)
        return prepared

    def end(self, key: _Key, prepared: _Prepared, *, keep: bool) -> None:
        """One extraction of ``prepared`` is done; ``keep``: it is a launch file's."""
        with self._lock:
            if keep:
                replaced = self._found.get(key)
                self._found[key] = prepared
                self._found.move_to_end(key)
                if replaced is not None and replaced is not prepared:
                    self._release_unused(replaced)
                while len(self._found) > self._kept:
                    self._release_unused(self._found.popitem(last=False)[1])
            self._use(prepared, -1)
            if self._found.get(key) is not prepared:
                self._release_unused(prepared)

    def __contains__(self, key: _Key) -> bool:
        with self._lock:
            return key in self._found

    def clear(self) -> None:
        with self._lock:
            while self._found:
                self._release_unused(self._found.popitem()[1])

    def _use(self, prepared: _Prepared, change: int) -> None:
        walk = id(prepared[0])
        users = self._users.get(walk, 0) + change
        if users:
            self._users[walk] = users
        else:
            self._users.pop(walk, None)

    def _release_unused(self, prepared: _Prepared) -> None:
        if id(prepared[0]) not in self._users:
            prepared[0].release()


_LAUNCH_FILES = _RecentLaunchFiles(16)


def _prepare(
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
    python2: bool,
) -> _Prepared | ParseError:
    """Everything of a file that launch arguments do not change: parsed, walked, its
    code's names extracted and its launch calls found. A launch file that includers hand
    different arguments is extracted once per set (``extract(arguments=...)``); only its
    launch part runs again, from ``_LAUNCH_FILES``. Nothing here answers differently
    after it is built (the locator and the scopes only fill their own memos), so it is
    safe to share.

    A file that may be Python 2 and is not Python 3 is parsed again rewritten
    (``python2``), and placed in the original text through the rewrite.
    """
    text = decode(data)
    if isinstance(text, ParseError):
        return text
    module = parse(text)
    rewritten = None
    if isinstance(module, ParseError) and python2:
        rewritten = rewrite(text)
        if rewritten is not None:
            module = _parse_rewritten(rewritten)
    if isinstance(module, ParseError):
        return module
    # Every step follows the tree recursively: a long operator chain as a name's value
    # (500 '+' terms handed to ``create_publisher``) exhausted the stack in the folding.
    try:
        walk = Walk(module)
        generation = evidence.decide(
            package_generation, import_generation(walk.packages), None, fallback_generation
        )
        parsed = text if rewritten is None else rewritten.text
        locator = Locator(module, parsed, walk.anchor_indents, rewritten)
        code = CodeExtractor(walk, locator, generation)
        code.run()
        return walk, locator, code, LaunchCalls.of(walk), generation, text
    except RecursionError:
        return _TOO_DEEP


def _parse_rewritten(rewritten: Rewritten) -> cst.Module | ParseError:
    """The rewritten text's tree; else where and why it fails, in the original text.

    Its own failure, not the original's: that one is often a ``print`` statement, which
    is fine Python 2, while what stops the file is further on."""
    module = parse(rewritten.text)
    if not isinstance(module, ParseError):
        return module
    span = module.span
    start = rewritten.original(Source(rewritten.text).offset(span.line, span.column))
    line, column = Source(rewritten.source).position(start)
    reason = module.message.removeprefix("not valid Python 3: ")
    return ParseError(
        f"cannot read as Python 2 or 3: {reason}", Span(line, column, line, column + 1)
    )


_TOO_DEEP = ParseError("Python code nested too deeply to analyse", Span(1, 1, 1, 2))
