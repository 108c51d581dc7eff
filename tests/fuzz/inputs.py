"""What the fuzzers feed: the extractors, the real files they start from, and how inputs are made.

Shared by the hypothesis harness (``test_fuzz_*.py``) and the optional atheris script
(``atheris_fuzz.py``), so both speak of the same targets and seeds. Every input starts as
either random bytes (sometimes after a prefix that gets it past an extractor's cheap
prefilter) or a real file of the project (``tests/fixtures``, ``examples``), which may be
re-encoded (Latin-1, UTF-16 LE/BE with or without BOM, UTF-8 with BOM, UTF-32), given CRLF or
CR line ends, peppered with NUL bytes, and then mutated: bytes flipped, inserted, deleted,
duplicated, spliced from another real file, or the whole cut short.
"""

from __future__ import annotations

import codecs
import re
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path

from roslint_names.discover import classify
from roslint_names.extract.build import cmake, reconfigure, setup_py
from roslint_names.extract.cpp import extract as cpp
from roslint_names.extract.launch import urdf
from roslint_names.extract.launch import xml_launch as launch_xml
from roslint_names.extract.launch import yaml_launch as launch_yaml
from roslint_names.extract.python import extract as python
from roslint_names.model import FileFacts, Generation, Language, LaunchArguments

ROOT = Path(__file__).resolve().parents[2]
SEED_DIRECTORIES = (ROOT / "tests" / "fixtures", ROOT / "examples")

Extract = Callable[..., FileFacts]


@dataclass(frozen=True)
class Target:
    """One extractor, the file names an input is presented under, and its real files."""

    name: str
    extract: Extract
    languages: tuple[Language, ...]  # which real files are its seeds
    paths: tuple[str, ...]
    prefixes: tuple[bytes, ...]  # put before random bytes to pass the prefilter
    takes_arguments: bool = False  # launch extractors also take an includer's arguments


TARGETS: tuple[Target, ...] = (
    Target(
        "cpp.extract",
        cpp.extract,
        (Language.CPP,),
        ("src/node.cpp", "include/pkg/node.hpp"),
        (b"#include <ros/ros.h>\nros::NodeHandle nh;\n", b'#include "rclcpp/rclcpp.hpp"\n'),
    ),
    Target(
        "python.extract",
        python.extract,
        (Language.PYTHON,),
        ("scripts/node.py", "launch/robot.launch.py"),
        (b"import rospy\n", b"import rclpy\n", b"def generate_launch_description():\n"),
        takes_arguments=True,
    ),
    # A ROS 1 package's Python, which may be Python 2: rewritten when it is not Python 3.
    Target(
        "python.extract[python2]",
        partial(python.extract, python2=True),
        (Language.PYTHON,),
        ("scripts/node.py",),
        (b"import rospy\nprint ", b"import rospy\n\tprint `x`, 0777\nexcept E, e:\n"),
        takes_arguments=True,
    ),
    Target(
        "launch_xml.extract",
        launch_xml.extract,
        (Language.LAUNCH_XML,),
        ("launch/robot.launch", "launch/robot.launch.xml"),
        (b"<launch>", b'<?xml version="1.0"?>\n<launch>\n  <node '),
        takes_arguments=True,
    ),
    Target(
        "launch_yaml.extract",
        launch_yaml.extract,
        (Language.LAUNCH_YAML,),
        ("launch/robot.launch.yaml",),
        (b"launch:\n", b"launch:\n- node:\n    "),
        takes_arguments=True,
    ),
    Target(
        "urdf.extract",
        urdf.extract,
        (Language.URDF,),
        ("urdf/robot.urdf", "urdf/robot.urdf.xacro"),
        (b"<robot>", b'<robot name="r"><gazebo><plugin>'),
    ),
    Target(
        "cmake.extract",
        cmake.extract,
        (Language.CMAKE,),
        ("CMakeLists.txt",),
        (b"add_executable(", b"rclcpp_components_register_node("),
    ),
    Target(
        "setup_py.extract",
        setup_py.extract,
        (Language.SETUP_PY,),
        ("setup.py",),
        (b"from setuptools import setup\nsetup(",),
    ),
    # setup.cfg has no extractor module of its own: setup_py.extract reads it by its name.
    Target(
        "setup_py.extract[setup.cfg]",
        setup_py.extract,
        (Language.SETUP_CFG,),
        ("setup.cfg",),
        (b"[options.entry_points]\nconsole_scripts =\n    ",),
    ),
    # A dynamic_reconfigure .cfg: read with ``ast``, as Python 3 or the Python 2 it may be.
    Target(
        "reconfigure.extract",
        reconfigure.extract,
        (Language.RECONFIGURE,),
        ("cfg/Planner.cfg",),
        (b"gen = ParameterGenerator()\ngen.add(", b"ParameterGenerator\nprint `x`, 0777\n"),
    ),
)


def _real_files() -> dict[Language, tuple[tuple[str, bytes], ...]]:
    found: dict[Language, list[tuple[str, bytes]]] = {}
    for directory in SEED_DIRECTORIES:
        for path in sorted(directory.rglob("*")):
            language = classify(path) if path.is_file() else None
            if language is not None:
                relative = path.relative_to(ROOT).as_posix()
                found.setdefault(language, []).append((relative, path.read_bytes()))
    return {language: tuple(files) for language, files in found.items()}


REAL_FILES = _real_files()
ALL_SEEDS: tuple[bytes, ...] = tuple(data for files in REAL_FILES.values() for _, data in files)


def seeds(target: Target) -> tuple[bytes, ...]:
    return tuple(data for language in target.languages for _, data in REAL_FILES[language])


# ---------------------------------------------------------------------------------------
# Re-encodings and line ends

ENCODINGS: dict[str, Callable[[str], bytes]] = {
    "utf-8": lambda text: text.encode("utf-8", "surrogateescape"),
    "utf-8-bom": lambda text: codecs.BOM_UTF8 + text.encode("utf-8", "replace"),
    "latin-1": lambda text: text.encode("latin-1", "replace"),
    "utf-16-le": lambda text: text.encode("utf-16-le", "replace"),
    "utf-16-be": lambda text: text.encode("utf-16-be", "replace"),
    "utf-16-le-bom": lambda text: codecs.BOM_UTF16_LE + text.encode("utf-16-le", "replace"),
    "utf-16-be-bom": lambda text: codecs.BOM_UTF16_BE + text.encode("utf-16-be", "replace"),
    "utf-32-bom": lambda text: text.encode("utf-32", "replace"),
}
LINE_ENDS = {"lf": "\n", "crlf": "\r\n", "cr": "\r"}
_XML_ENCODING = re.compile(r"""(<\?xml[^>]*?encoding\s*=\s*)(["'])[^"']*\2""")
_DECLARED = {
    "utf-8": "UTF-8",
    "utf-8-bom": "UTF-8",
    "latin-1": "ISO-8859-1",
    "utf-16-le": "UTF-16",
    "utf-16-be": "UTF-16",
    "utf-16-le-bom": "UTF-16",
    "utf-16-be-bom": "UTF-16",
    "utf-32-bom": "UTF-32",
}


def reencode(data: bytes, encoding: str, line_end: str, declare: bool) -> bytes:
    """``data`` (read as UTF-8) in another encoding and with other line ends.

    ``declare`` rewrites an XML declaration's ``encoding`` to match; without it the file
    says one encoding and is written in another, as hand-converted files sometimes do.
    """
    text = data.decode("utf-8", "surrogateescape").replace("\r\n", "\n")
    text = text.replace("\n", LINE_ENDS[line_end])
    if declare:
        text = _XML_ENCODING.sub(lambda m: f"{m[1]}{m[2]}{_DECLARED[encoding]}{m[2]}", text)
    return ENCODINGS[encoding](text)


# ---------------------------------------------------------------------------------------
# Byte mutations

# Bytes that mean something to one of the parsers: worth inserting more than random ones.
TOKENS: tuple[bytes, ...] = (
    b"\x00",
    b"\r",
    b"\n",
    b"\r\n",
    b"\t",
    b"\xff",
    b"\xfe",
    b"\xc3",
    b"\xed\xa0\x80",  # an encoded surrogate
    b"\xef\xbb\xbf",
    b"\xe2\x80\xa8",  # U+2028
    b"\xf0\x9f\xa4\x96",  # an emoji, four UTF-8 bytes, two UTF-16 units
    b"<",
    b">",
    b"/>",
    b"</",
    b"<!--",
    b"-->",
    b"<![CDATA[",
    b"]]>",
    b"<!DOCTYPE x [",
    b'<!ENTITY e "v">',
    b"&",
    b"&amp;",
    b"&#0;",
    b"&#x110000;",
    b"&e;",
    b'"',
    b"'",
    b"=",
    b"$(",
    b"$(arg ",
    b"$(var ",
    b"$(find ",
    b"$(eval ",
    b"$(dirname)",
    b"${",
    b"{",
    b"}",
    b"(",
    b")",
    b"[",
    b"]",
    b"\\",
    b"~",
    b"/",
    b"//",
    b"/*",
    b"*/",
    b"#",
    b"#include",
    b'R"x(',
    b')x"',
    b'"""',
    b"'''",
    b' t"',  # string prefixes: a t-string joined to a string broke libcst
    b' f"',
    b' b"',
    b' rb"',
    b' u"',
    b":",
    b"::",
    b"- ",
    b"---",
    b"!!",
    b"&a ",
    b"*a",
    b"? ",
    b"|",
    b"%YAML 1.1\n",
    b";",
    b",",
    b".",
    b"@",
    b"0",
    b"-1",
    b"9" * 20,
    b" " * 64,
    b"(" * 64,
    b"[" * 64,
    b"<a>" * 64,
    b"\\\n",
    b"__name:=",
    b"__ns:=",
    b":=",
    b"\\ud800",
    b"\\udc80",
    b"\\U0000d800",
    b"\\xd800",
    b"\\x00",
    b"\\N{bogus}",
    b"\\N{",
    b"\\x",
    b"\\u12",
    b"\\777",
    b"{x}",
    b"{{",
    b"%s",
    b"%c",
    b"# -*- coding: latin-1 -*-\n",
    b"# coding: utf-16\n",
    b"# coding=unicode_escape\n",
    b"# coding: bogus\n",
    b'<?xml version="1.0" encoding="UTF-16"?>',
    b'<?xml version="1.0" encoding="bogus"?>',
)


_QUOTES = re.compile(rb"[\"'>]")  # where a string literal, or an attribute or element text, starts
_WORDS = re.compile(rb"[\w:]+")  # an identifier, qualified or not
_LINES = re.compile(rb"[^\n]*\n?")


@dataclass(frozen=True)
class Mutation:
    """One edit of a byte string; positions are taken modulo the current length.

    ``in_string`` inserts after the position-th quote or ``>`` (modulo their number): at
    the start of a string literal or an XML value, where names are, and where a random
    position seldom falls. ``delete_word`` and ``delete_line`` remove the position-th word
    (a type, a keyword, a name) or line: broken code as people write it.
    """

    kind: str  # flip, set, insert, in_string, delete, delete_word, delete_line, duplicate,
    # splice, truncate
    position: int
    value: int = 0  # the bit to flip, the byte to set, a length
    payload: bytes = b""

    def apply(self, data: bytes) -> bytes:
        size = len(data)
        at = self.position % (size + 1)
        if self.kind == "truncate":
            return data[:at]
        if self.kind == "in_string":
            quotes = [match.end() for match in _QUOTES.finditer(data)]
            at = quotes[self.position % len(quotes)] if quotes else at
            return data[:at] + self.payload + data[at:]
        if self.kind in {"insert", "splice"}:
            return data[:at] + self.payload + data[at:]
        if self.kind in {"delete_word", "delete_line"}:
            pattern = _WORDS if self.kind == "delete_word" else _LINES
            spans = [
                match.span() for match in pattern.finditer(data) if match.end() > match.start()
            ]
            if not spans:
                return data
            start, end = spans[self.position % len(spans)]
            return data[:start] + data[end:]
        if size == 0:
            return data
        at = self.position % size
        if self.kind == "flip":
            return data[:at] + bytes([data[at] ^ (1 << (self.value % 8))]) + data[at + 1 :]
        if self.kind == "set":
            return data[:at] + bytes([self.value % 256]) + data[at + 1 :]
        if self.kind == "delete":
            return data[:at] + data[at + 1 + self.value % 64 :]
        if self.kind == "duplicate":
            piece = data[at : at + 1 + self.value % 256]
            return data[:at] + piece + data[at:]
        raise ValueError(f"unknown mutation {self.kind!r}")


def mutate(data: bytes, mutations: list[Mutation]) -> bytes:
    for mutation in mutations:
        data = mutation.apply(data)
    return data


@dataclass(frozen=True)
class Sample:
    """One input: its bytes, where they came from, and the arguments of the call."""

    kind: str  # "random bytes", "real file" (as is), "mutated", "re-encoded"
    origin: str  # the kind, with the details
    data: bytes
    path: str
    package_generation: Generation | None
    fallback_generation: Generation
    arguments: LaunchArguments = ()

    def call(self, target: Target) -> FileFacts:
        if target.takes_arguments:
            return target.extract(
                self.path,
                self.data,
                self.package_generation,
                self.fallback_generation,
                arguments=self.arguments,
            )
        return target.extract(
            self.path, self.data, self.package_generation, self.fallback_generation
        )
