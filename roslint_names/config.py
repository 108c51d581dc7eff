"""Configuration: find it, read it, validate every key, and merge command-line overrides.

Sources, the first found walking up from the start directory (a directory's own files win
over its parents'; within one directory in this order):

- ``roslint-names.toml`` and ``.roslint-names.toml``: settings at the top level;
- ``pyproject.toml``: settings under ``[tool.roslint-names]`` (a pyproject without that
  table is passed over, so a Python package inside a ROS workspace does not hide the
  workspace's own file).

Every problem names the file and the key and ends the run with exit 2: a pattern
(``exclude``, ``per-file-ignores``, ``[test-code] paths``) git would not accept, and a
``[naming]`` regular expression that could backtrack without bound
(``regex_safety``), are refused here, before any file is read.
"""

from __future__ import annotations

import functools
import os
import re
import stat
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .discover import pattern_error
from .errors import UserError
from .model import Generation, Kind, Severity
from .reading import NotRegularFileError, open_regular
from .regex_safety import UnboundedBacktrackingError, check_backtracking
from .registry import Registry
from .rule import NamingPolicy, OptionValue, Rule

if TYPE_CHECKING:
    import pathspec

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

CONFIG_FILENAMES = ("roslint-names.toml", ".roslint-names.toml", "pyproject.toml")
DEFAULT_MAX_DEPTH = 4
# Larger files are generated or vendored, not written by hand: skipped (said with --verbose).
DEFAULT_MAX_FILE_SIZE = 5 * 1024 * 1024
_TEMPLATE_FIELD = re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)\}")


class ConfigError(UserError):
    """A configuration problem; the message names the file and the key."""


@dataclass(frozen=True)
class TestCodeSettings:
    """``[test-code]``: which rules judge test code, and what is test code besides the
    ecosystem's conventions (``test_code``). ``select`` None: the rules whose
    ``judges_test_code`` is true."""

    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    paths: tuple[str, ...] = ()  # gitignore-style patterns, relative to the settings' root


@dataclass(frozen=True)
class Settings:
    root: Path  # paths in exclude and per-file-ignores are relative to it
    source: Path | None = None  # the file the settings came from
    ros: Generation | None = None  # None: auto (package.xml, then file evidence, then ROS 2)
    python: int | None = None  # of ROS 1 packages, 2 or 3; None: auto (``ros1_python2``)
    select: tuple[str, ...] | None = None  # None: the rules enabled by default
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    per_file_ignores: tuple[tuple[str, tuple[str, ...]], ...] = ()
    exclude: tuple[str, ...] = ()
    max_depth: int = DEFAULT_MAX_DEPTH
    max_file_size: int = DEFAULT_MAX_FILE_SIZE  # bytes
    severity: Mapping[str, Severity] = field(default_factory=dict)  # code -> severity
    rule_options: Mapping[str, Mapping[str, OptionValue]] = field(default_factory=dict)
    policies: tuple[NamingPolicy, ...] = ()
    test_code: TestCodeSettings = TestCodeSettings()


def ros1_python2(settings: Settings, environ: Mapping[str, str] | None = None) -> bool:
    """Whether the workspace's ROS 1 packages may hold Python 2, which is then read.

    The ``python`` key says; on "auto", ``ROS_PYTHON_VERSION`` as a sourced ROS 1
    environment sets it (catkin's ros_environment: 2 up to Melodic, 3 from Noetic), and
    without one, yes: a ROS 1 package may be of any distribution. A sourced ROS 2
    environment (``ROS_VERSION=2``) sets ``ROS_PYTHON_VERSION=3`` for its own packages,
    which says nothing of ROS 1 ones. Read here only, once per run; the cache keys of
    the files it applies to hold the answer (``generation.reads_python2``).
    """
    if settings.python is not None:
        return settings.python == 2
    environ = os.environ if environ is None else environ
    if environ.get("ROS_VERSION", "1").strip() != "1":
        return True
    return environ.get("ROS_PYTHON_VERSION", "").strip() != "3"


def settings_fingerprint(settings: Settings) -> str:
    """The settings as text, the same for equal settings whatever order the configuration
    listed its tables in: part of the key of a cached run."""
    return repr(
        tuple((item.name, _canonical(getattr(settings, item.name))) for item in fields(settings))
    )


def _canonical(value: object) -> object:
    if isinstance(value, Mapping):
        return tuple(sorted((repr(key), _canonical(item)) for key, item in value.items()))
    return value


def find_config(start: Path) -> Path | None:
    for directory in (start, *start.parents):
        for filename in CONFIG_FILENAMES:
            candidate = directory / filename
            if _is_config_file(candidate) and (
                filename != "pyproject.toml" or _has_tool_table(candidate)
            ):
                return candidate
    return None


def _is_config_file(candidate: Path) -> bool:
    """A regular file; False where there is none. A FIFO, socket or device of a config
    file's name is an error: passing over it would quietly use another configuration,
    and opening it could block."""
    try:
        mode = os.stat(candidate).st_mode
    except OSError:
        return False
    if stat.S_ISREG(mode):
        return True
    if stat.S_ISDIR(mode):
        return False
    reason = NotRegularFileError(candidate, mode).strerror
    raise ConfigError(f"{candidate}: cannot read config file: {reason}")


def _check_named_config(path: Path) -> None:
    """``--config``'s file exists and is a regular file: anything else is never opened
    (a FIFO would block the run, a device could act on the open)."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise ConfigError(f"{path}: config file not found") from None
    except OSError as error:
        raise ConfigError(f"{path}: cannot read config file: {error.strerror}") from None
    if not stat.S_ISREG(mode):
        reason = NotRegularFileError(path, mode).strerror
        raise ConfigError(f"{path}: cannot read config file: {reason}")


def load_settings(config_file: Path | None, start: Path, registry: Registry) -> Settings:
    """Settings from ``config_file``, or from the nearest config above ``start``."""
    if config_file is None:
        config_file = find_config(start.resolve())
        if config_file is None:
            return Settings(root=start.resolve())
    else:
        _check_named_config(config_file)
    table = _read_table(config_file)
    return parse_settings(table, config_file.resolve(), registry)


def parse_settings(table: Mapping[str, Any], source: Path, registry: Registry) -> Settings:
    reader = _Reader(source, registry)
    known = {
        "ros",
        "python",
        "select",
        "extend-select",
        "ignore",
        "per-file-ignores",
        "exclude",
        "max-depth",
        "max-file-size",
        "severity",
        "rules",
        "naming",
        "test-code",
    }
    for key in table:
        if key not in known:
            raise reader.error(key, f"unknown key; known keys: {', '.join(sorted(known))}")
    select = table.get("select")
    return Settings(
        root=source.parent,
        source=source,
        ros=reader.generation("ros", table.get("ros", "auto")),
        python=reader.python("python", table.get("python", "auto")),
        select=None if select is None else reader.selectors("select", select),
        extend_select=reader.selectors("extend-select", table.get("extend-select", [])),
        ignore=reader.selectors("ignore", table.get("ignore", [])),
        per_file_ignores=reader.per_file_ignores(table.get("per-file-ignores", {})),
        exclude=reader.patterns("exclude", table.get("exclude", [])),
        max_depth=reader.max_depth("max-depth", table.get("max-depth", DEFAULT_MAX_DEPTH)),
        max_file_size=reader.positive(
            "max-file-size", table.get("max-file-size", DEFAULT_MAX_FILE_SIZE), "bytes"
        ),
        severity=reader.severities(table.get("severity", {})),
        rule_options=reader.rule_options(table.get("rules", {})),
        policies=reader.policies(table.get("naming", {})),
        test_code=reader.test_code(table.get("test-code", {})),
    )


@dataclass(frozen=True)
class Overrides:
    """Command-line options that take precedence over the file."""

    ros: Generation | None = None
    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    max_depth: int | None = None
    extend_exclude: tuple[str, ...] = ()  # gitignore patterns, after the file's ``exclude``


def apply_overrides(settings: Settings, overrides: Overrides, registry: Registry) -> Settings:
    for option, selectors in (
        ("--select", overrides.select or ()),
        ("--extend-select", overrides.extend_select),
        ("--ignore", overrides.ignore),
    ):
        for selector in selectors:
            if not registry.matching(selector):
                raise ConfigError(f"{option}: {selector!r} matches no rule code, prefix or name")
    if overrides.max_depth is not None and overrides.max_depth < 1:
        raise ConfigError(f"--max-depth: must be at least 1, got {overrides.max_depth}")
    for pattern in overrides.extend_exclude:
        reason = pattern_error(pattern)
        if reason is not None:
            raise ConfigError(f"--extend-exclude: invalid pattern {pattern!r}: {reason}")
    return replace(
        settings,
        ros=overrides.ros if overrides.ros is not None else settings.ros,
        select=overrides.select if overrides.select is not None else settings.select,
        extend_select=settings.extend_select + overrides.extend_select,
        ignore=settings.ignore + overrides.ignore,
        max_depth=overrides.max_depth if overrides.max_depth is not None else settings.max_depth,
        exclude=settings.exclude + overrides.extend_exclude,
    )


def enabled_codes(settings: Settings, registry: Registry) -> frozenset[str]:
    """The rules the run checks.

    As in ruff, the most specific selector wins: ``select = ["RN"]`` with
    ``ignore = ["RN2"]`` and ``extend-select = ["RN203"]`` keeps RN203. A slug is as
    specific as a full code. On a tie, ignore wins.
    """
    return _selected(
        registry,
        settings.select,
        settings.extend_select,
        settings.ignore,
        by_default=lambda rule: rule.enabled_by_default,
    )


def test_code_codes(settings: Settings, registry: Registry) -> frozenset[str]:
    """The rules that judge test code: those of the run that ``[test-code]`` selects
    (by default the rules whose findings would break a test, see ``Rule``)."""
    test_code = settings.test_code
    selected = _selected(
        registry,
        test_code.select,
        test_code.extend_select,
        test_code.ignore,
        by_default=lambda rule: rule.judges_test_code,
    )
    return selected & enabled_codes(settings, registry)


def _selected(
    registry: Registry,
    select: tuple[str, ...] | None,
    extend_select: tuple[str, ...],
    ignore: tuple[str, ...],
    *,
    by_default: Callable[[Rule], bool],
) -> frozenset[str]:
    enabled: set[str] = set()
    for rule in registry.rules:
        if select is None:
            # The default selection is the least specific one: any ignore beats it.
            base = 1 if by_default(rule) else 0
        else:
            base = _specificity(rule.code, rule.name, select)
        on = max(base, _specificity(rule.code, rule.name, extend_select))
        off = _specificity(rule.code, rule.name, ignore)
        if on > off:
            enabled.add(rule.code)
    return frozenset(enabled)


def ignored_for_path(settings: Settings, relative_path: str, registry: Registry) -> frozenset[str]:
    """Codes that ``per-file-ignores`` turns off for one path (relative to ``settings.root``);
    the engine asks only when some are configured."""
    codes: set[str] = set()
    for pattern, selectors in settings.per_file_ignores:
        if _path_pattern(pattern).match_file(relative_path):
            for selector in selectors:
                codes.update(rule.code for rule in registry.matching(selector))
    return frozenset(codes)


@functools.lru_cache(maxsize=256)
def _path_pattern(pattern: str) -> pathspec.GitIgnoreSpec:
    """A ``per-file-ignores`` pattern compiled once per run, not once per file."""
    import pathspec  # only runs that configure per-file-ignores pay for it

    return pathspec.GitIgnoreSpec.from_lines([pattern])


def _specificity(code: str, name: str, selectors: Sequence[str]) -> int:
    best = 0
    for selector in selectors:
        upper = selector.upper()
        if upper == "ALL":
            best = max(best, 1)
        elif selector.lower() == name:
            best = max(best, len(code) + 1)
        elif code.startswith(upper):
            best = max(best, len(upper) + 1)
    return best


def _has_tool_table(pyproject: Path) -> bool:
    try:
        return "roslint-names" in _load_toml(pyproject).get("tool", {})
    except ConfigError:
        return True  # a broken pyproject is reported when it is read, not skipped silently


def _read_table(path: Path) -> Mapping[str, Any]:
    data = _load_toml(path)
    if path.name == "pyproject.toml":
        tool = data.get("tool", {})
        table = tool.get("roslint-names", {}) if isinstance(tool, dict) else {}
        if not isinstance(table, dict):
            raise ConfigError(f"{path}: [tool.roslint-names] must be a table")
        return table
    return data


def _load_toml(path: Path) -> dict[str, Any]:
    try:
        with open_regular(path) as stream:  # a FIFO is refused, never waited on
            data: dict[str, Any] = tomllib.load(stream)
            return data
    except OSError as error:
        raise ConfigError(f"{path}: cannot read config file: {error.strerror}") from error
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: invalid TOML: {error}") from error
    except UnicodeDecodeError as error:
        raise ConfigError(f"{path}: config file is not UTF-8: {error}") from error


@dataclass(frozen=True)
class _Reader:
    """Type-checks one config table, naming the file and key in every error."""

    source: Path
    registry: Registry

    def error(self, key: str, message: str) -> ConfigError:
        return ConfigError(f"{self.source}: {key}: {message}")

    def generation(self, key: str, value: object) -> Generation | None:
        if value in ("auto",):
            return None
        if value in (1, "1"):
            return Generation.ROS1
        if value in (2, "2"):
            return Generation.ROS2
        raise self.error(key, f'must be 1, 2 or "auto", got {value!r}')

    def python(self, key: str, value: object) -> int | None:
        if value == "auto":
            return None
        if value in (2, "2", 3, "3"):
            return int(value)
        raise self.error(key, f'must be 2, 3 or "auto", got {value!r}')

    def strings(self, key: str, value: object) -> tuple[str, ...]:
        if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
            raise self.error(key, f"must be a list of strings, got {value!r}")
        return tuple(value)

    def patterns(self, key: str, value: object) -> tuple[str, ...]:
        """Gitignore-style patterns, each one git accepts."""
        patterns = self.strings(key, value)
        for pattern in patterns:
            reason = pattern_error(pattern)
            if reason is not None:
                raise self.error(key, f"invalid pattern {pattern!r}: {reason}")
        return patterns

    def selectors(self, key: str, value: object) -> tuple[str, ...]:
        selectors = self.strings(key, value)
        for selector in selectors:
            if not self.registry.matching(selector):
                raise self.error(key, f"{selector!r} matches no rule code, prefix or name")
        return selectors

    def max_depth(self, key: str, value: object) -> int:
        return self.positive(key, value, "tokens")

    def positive(self, key: str, value: object, unit: str) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise self.error(key, f"must be a whole number of {unit}, at least 1, got {value!r}")
        return value

    def per_file_ignores(self, value: object) -> tuple[tuple[str, tuple[str, ...]], ...]:
        if not isinstance(value, dict):
            raise self.error("per-file-ignores", "must be a table of glob = [codes]")
        return tuple(
            (
                self.patterns("per-file-ignores", [pattern])[0],
                self.selectors(f"per-file-ignores.{pattern!r}", selectors),
            )
            for pattern, selectors in value.items()
        )

    def test_code(self, value: object) -> TestCodeSettings:
        if not isinstance(value, dict):
            raise self.error("test-code", "must be a table (select, extend-select, ignore, paths)")
        known = {"select", "extend-select", "ignore", "paths"}
        for key in value:
            if key not in known:
                raise self.error(
                    f"test-code.{key}", f"unknown key; known keys: {', '.join(sorted(known))}"
                )
        select = value.get("select")
        return TestCodeSettings(
            select=None if select is None else self.selectors("test-code.select", select),
            extend_select=self.selectors("test-code.extend-select", value.get("extend-select", [])),
            ignore=self.selectors("test-code.ignore", value.get("ignore", [])),
            paths=self.patterns("test-code.paths", value.get("paths", [])),
        )

    def _rule_key(self, key: str, table_key: str) -> str:
        rule = self.registry.by_code_or_name(key)
        if rule is None:
            raise self.error(f"{table_key}.{key}", "not a rule code or name")
        return rule.code

    def severities(self, value: object) -> dict[str, Severity]:
        if not isinstance(value, dict):
            raise self.error("severity", 'must be a table of code = "error" | "warning"')
        severities: dict[str, Severity] = {}
        for key, level in value.items():
            code = self._rule_key(key, "severity")
            if level not in ("error", "warning"):
                raise self.error(f"severity.{key}", f'must be "error" or "warning", got {level!r}')
            severities[code] = Severity(level)
        return severities

    def rule_options(self, value: object) -> dict[str, dict[str, OptionValue]]:
        if not isinstance(value, dict):
            raise self.error("rules", "must be a table of rule tables")
        options: dict[str, dict[str, OptionValue]] = {}
        for key, table in value.items():
            code = self._rule_key(key, "rules")
            rule = self.registry.by_code_or_name(code)
            assert rule is not None
            if not isinstance(table, dict):
                raise self.error(f"rules.{key}", "must be a table of options")
            checked: dict[str, OptionValue] = {}
            for option, setting in table.items():
                if option not in rule.options:
                    known = ", ".join(sorted(rule.options)) or "none"
                    raise self.error(
                        f"rules.{key}.{option}", f"unknown option of {code}; known: {known}"
                    )
                checked[option] = self._option(
                    f"rules.{key}.{option}", rule.options[option], setting
                )
                if rule.option_error is not None:
                    reason = rule.option_error(option, checked[option])
                    if reason is not None:
                        raise self.error(f"rules.{key}.{option}", reason)
            options[code] = checked
        return options

    def _option(self, key: str, default: OptionValue, value: object) -> OptionValue:
        if isinstance(default, bool):
            if not isinstance(value, bool):
                raise self.error(key, f"must be true or false, got {value!r}")
            return value
        if isinstance(default, int):
            if isinstance(value, bool) or not isinstance(value, int):
                raise self.error(key, f"must be a whole number, got {value!r}")
            return value
        if isinstance(default, str):
            if not isinstance(value, str):
                raise self.error(key, f"must be a string, got {value!r}")
            return value
        return self.strings(key, value)

    def policies(self, value: object) -> tuple[NamingPolicy, ...]:
        if not isinstance(value, dict):
            raise self.error("naming", "must be a table of kind = pattern")
        kinds = {kind.value: kind for kind in Kind}
        policies = []
        for kind_name, spec in value.items():
            key = f"naming.{kind_name}"
            if kind_name not in kinds:
                raise self.error(key, f"unknown kind; kinds: {', '.join(sorted(kinds))}")
            pattern, description = self._policy_pattern(key, spec)
            policies.append(NamingPolicy(kinds[kind_name], pattern, description))
        return tuple(policies)

    def _policy_pattern(self, key: str, spec: object) -> tuple[str, str]:
        if isinstance(spec, str):
            spec = {"regex": spec}
        if not isinstance(spec, dict) or len(spec) != 1 or not {"regex", "template"} >= set(spec):
            raise self.error(
                key, 'must be a regex string, { regex = "..." } or { template = "..." }'
            )
        ((form, text),) = spec.items()
        if not isinstance(text, str):
            raise self.error(f"{key}.{form}", f"must be a string, got {text!r}")
        pattern = template_to_regex(text) if form == "template" else text
        try:
            re.compile(pattern)
        except re.error as error:
            raise self.error(f"{key}.{form}", f"invalid regular expression: {error}") from error
        try:
            check_backtracking(pattern)
        except UnboundedBacktrackingError as error:
            raise self.error(f"{key}.{form}", str(error)) from None
        return pattern, text


def template_to_regex(template: str) -> str:
    """``/{zone}/{robot}/{function}``: each ``{field}`` is one snake_case name token."""
    parts: list[str] = []
    position = 0
    for match in _TEMPLATE_FIELD.finditer(template):
        parts.append(re.escape(template[position : match.start()]))
        parts.append(r"[a-z0-9]+(?:_[a-z0-9]+)*")
        position = match.end()
    parts.append(re.escape(template[position:]))
    return "".join(parts)
