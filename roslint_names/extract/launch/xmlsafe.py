"""Untrusted XML: a parser that never leaves the document, and exact source positions.

Launch files and URDFs come from anywhere (a cloned repository, a pull request), so the
parser resolves no entity, loads no DTD and opens no network or file: an external entity
in an attribute is a parse error, one in element text stays an unexpanded reference, and
libxml2's amplification limit turns a billion-laughs document into a quick parse error.
No value extracted from a document ever holds an entity's replacement text: a value that
references a DTD entity is reported raw and ``opaque`` (dynamic for the extractors).

lxml reports only a line per element, and for a multi-line start tag it is the line the
tag *ends* on. Rules need the column of the value itself, so the decoded text is scanned
once for start tags. Start tags appear in the text in the same order as the elements lxml
builds (no entity is expanded into elements), which pairs each element with the raw text
of its attributes.
"""

from __future__ import annotations

import codecs
import re
from dataclasses import dataclass

from lxml import etree

from roslint_names.extract.launch.substitution import Located, Source
from roslint_names.model import ParseError, Span
from roslint_names.reading import bom_encoding

SNIFF_LIMIT = 64 * 1024  # root_tag never looks further than this


def make_parser() -> etree.XMLParser:
    """A parser with every door to the outside closed (see the module docstring)."""
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=False,
        remove_comments=False,
    )


# ---------------------------------------------------------------------------------------
# Encoding: the same decision libxml2 makes (BOM, then the declaration, then UTF-8)

_DECLARED_ENCODING = re.compile(rb"""<\?xml[^>]*?\bencoding\s*=\s*["']([A-Za-z0-9._:-]+)["']""")


def detect_encoding(data: bytes) -> str:
    """The Python codec for ``data``: BOM, then XML declaration, then UTF-8."""
    marked = bom_encoding(data)
    if marked is not None:
        return marked
    if data.startswith(b"<\x00?\x00"):
        return "utf-16-le"
    if data.startswith(b"\x00<\x00?"):
        return "utf-16-be"
    declared = _DECLARED_ENCODING.match(data[:200])
    if declared:
        name = declared.group(1).decode("ascii")
        try:
            return codecs.lookup(name).name
        except LookupError:
            return "utf-8"
    return "utf-8"


def decode(data: bytes) -> str:
    """The document's text for locating values (never fails; the BOM is dropped)."""
    text = data.decode(detect_encoding(data), errors="replace")
    return text[1:] if text.startswith("\ufeff") else text


# ---------------------------------------------------------------------------------------
# Sniffing

_PROLOG_NAME = re.compile(r"<([^\s/>!?]+)")


def root_tag(data: bytes) -> str | None:
    """Local name of the first element, read from the first 64 KiB without parsing."""
    head = data[:SNIFF_LIMIT]
    text = decode(head)
    position = 0
    while position < len(text):
        position = _skip_space(text, position)
        if text.startswith("<?", position):
            position = _after(text, "?>", position + 2)
        elif text.startswith("<!--", position):
            position = _after(text, "-->", position + 4)
        elif text.startswith("<!", position):
            position = skip_doctype(text, position)
        else:
            match = _PROLOG_NAME.match(text, position)
            return match.group(1).rpartition(":")[2] if match else None
    return None


def _skip_space(text: str, position: int) -> int:
    while position < len(text) and text[position] in " \t\r\n":
        position += 1
    return position


def _after(text: str, terminator: str, position: int) -> int:
    """Offset just after the next ``terminator``, or the end of the text."""
    found = text.find(terminator, position)
    return len(text) if found < 0 else found + len(terminator)


def skip_doctype(text: str, position: int) -> int:
    """Offset after ``<!DOCTYPE ...>``; its internal subset may hold '>' in quotes."""
    depth, quote, i = 0, "", position + 2
    while i < len(text):
        char = text[i]
        if quote:
            quote = "" if char == quote else quote
        elif text.startswith("<!--", i):
            i = _after(text, "-->", i + 4)
            continue
        elif char in "'\"":
            quote = char
        elif char == "[":
            depth += 1
        elif char == "]":
            depth -= 1
        elif char == ">" and depth <= 0:
            return i + 1
        i += 1
    return len(text)


# ---------------------------------------------------------------------------------------
# Start tags in the raw text


@dataclass(frozen=True)
class StartTag:
    """A start tag as written: offsets into the decoded text."""

    name: str  # qualified name as written, e.g. "xacro:property"
    start: int  # the '<'
    end: int  # just after the '>'
    self_closing: bool
    attributes: tuple[tuple[str, int, int], ...]  # (name as written, value start, value end)


_START_TAG = re.compile(r"""<([^\s/>!?]+)((?:\s+[^\s=/>]+\s*=\s*(?:"[^"]*"|'[^']*'))*)\s*(/?)>""")
_ATTRIBUTE = re.compile(r"""([^\s=/>]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")


def scan_start_tags(text: str) -> list[StartTag]:
    """Every start tag outside comments, CDATA, PIs and the DOCTYPE, in document order."""
    tags: list[StartTag] = []
    position = text.find("<")
    while 0 <= position < len(text):
        if text.startswith("<!--", position):
            position = _after(text, "-->", position + 4)
        elif text.startswith("<![CDATA[", position):
            position = _after(text, "]]>", position + 9)
        elif text.startswith("<?", position):
            position = _after(text, "?>", position + 2)
        elif text.startswith("<!", position):
            position = skip_doctype(text, position)
        elif text.startswith("</", position):
            position = _after(text, ">", position + 2)
        else:
            match = _START_TAG.match(text, position)
            if match:
                tags.append(_start_tag(match))
            position = match.end() if match else position + 1
        position = text.find("<", position)
    return tags


def _start_tag(match: re.Match[str]) -> StartTag:
    attributes = []
    for attribute in _ATTRIBUTE.finditer(match.string, match.start(2), match.end(2)):
        group = 2 if attribute.group(2) is not None else 3
        attributes.append((attribute.group(1), attribute.start(group), attribute.end(group)))
    return StartTag(
        name=match.group(1),
        start=match.start(),
        end=match.end(),
        self_closing=match.group(3) == "/",
        attributes=tuple(attributes),
    )


# ---------------------------------------------------------------------------------------
# Raw text -> parsed text, character by character

_REFERENCE = re.compile(r"&(#[0-9]+|#x[0-9A-Fa-f]+|[A-Za-z_:][\w.:-]*);")
_PREDEFINED = {"amp": "&", "lt": "<", "gt": ">", "quot": '"', "apos": "'"}


@dataclass
class _Decoded:
    """Parsed characters with, for each, the raw range it came from."""

    chars: list[str]
    starts: list[int]
    ends: list[int]

    def add(self, char: str, start: int, end: int) -> None:
        self.chars.append(char)
        self.starts.append(start)
        self.ends.append(end)


def _reference(name: str) -> str | None:
    if name.startswith("#"):
        try:
            return chr(int(name[2:], 16) if name.startswith("#x") else int(name[1:]))
        except (ValueError, OverflowError):
            return None
    return _PREDEFINED.get(name)  # a DTD-declared entity: its text is not ours to know


def _decode_markup(text: str, start: int, end: int, into: _Decoded, *, attribute: bool) -> bool:
    """Decode ``text[start:end]`` as XML does; False on a reference we cannot expand.

    Line ends become LF (CRLF counts once); in attribute values every tab and line end
    becomes a space (attribute-value normalisation; without a DTD every attribute is CDATA).
    """
    i = start
    while i < end:
        char = text[i]
        if char == "&":
            match = _REFERENCE.match(text, i, end)
            expanded = _reference(match.group(1)) if match else None
            if match is None or expanded is None:
                return False
            into.add(expanded, i, match.end())
            i = match.end()
            continue
        width = 2 if text.startswith("\r\n", i) else 1
        if char in "\r\n":
            char = " " if attribute else "\n"
        elif char == "\t" and attribute:
            char = " "
        into.add(char, i, i + width)
        i += width
    return True


# ---------------------------------------------------------------------------------------
# The parsed document


class XmlDocument:
    """An lxml tree plus the source positions of its attribute values and texts."""

    def __init__(self, root: etree._Element, source: Source) -> None:
        self.root = root
        self.source = source
        self._tags = _pair_tags(root, scan_start_tags(source.text))

    def attribute(self, element: etree._Element, name: str) -> Located | None:
        """An attribute value and the span of its raw text (inside the quotes).

        ``name`` is lxml's key: ``"name"`` or ``"{uri}local"`` for a prefixed attribute.
        """
        value = element.get(name)
        if value is None:
            return None
        tag = self._tags.get(element)
        raw = _find_attribute(tag, name, element) if tag else None
        if raw is None:
            return Located(value, self._line_span(element))
        start, end = raw
        span = self.source.span(start, end)
        if self.source.text[start:end] == value:  # nothing escaped or normalised
            return Located(value, span, self.source, start)
        decoded = _Decoded([], [], [])
        if not _decode_markup(self.source.text, start, end, decoded, attribute=True):
            # libxml2 expands internal entities in attribute values whatever the parser
            # options; a name must not come from a DTD, so keep the raw text, unknown.
            return Located(self.source.text[start:end], span, opaque=True)
        if "".join(decoded.chars) != value:
            return Located(value, span)
        return Located(value, span, self.source, None, tuple(decoded.starts), tuple(decoded.ends))

    def text(self, element: etree._Element, *, strip: bool = True) -> Located | None:
        """The element's own text without surrounding whitespace (``strip``, else as
        written: YAML's indentation is in it); None when blank.

        Text holding an entity reference (left unexpanded on purpose) comes back raw and
        ``opaque``: its real value is unknown.
        """
        tag = self._tags.get(element)
        if tag is None or tag.self_closing:
            value = (element.text or "").strip(" \t\r\n")
            return Located(value, self._line_span(element)) if value else None
        if any(child.tag is etree.Entity for child in element):
            return self._opaque_text(tag)
        located = self._plain_text(tag, element.text or "") or self._decoded_text(tag, element)
        stripped = located.strip()
        if not stripped.text:
            return None
        return stripped if strip else located

    def _plain_text(self, tag: StartTag, value: str) -> Located | None:
        """The text when its raw form is the value itself (no reference, CDATA or CR)."""
        end = tag.end + len(value)
        if self.source.text[tag.end : end] != value or self.source.text[end : end + 1] != "<":
            return None
        if self.source.text.startswith("<![CDATA[", end):
            return None
        return Located(value, self.source.span(tag.end, end), self.source, tag.end)

    def _decoded_text(self, tag: StartTag, element: etree._Element) -> Located:
        decoded = _Decoded([], [], [])
        exact = _decode_content(self.source.text, tag.end, decoded)
        parsed = "".join(decoded.chars)
        if not exact or parsed != (element.text or ""):
            return Located((element.text or "").strip(" \t\r\n"), self.tag_span(element))
        end = decoded.ends[-1] if decoded.ends else tag.end
        span = self.source.span(tag.end, end)
        return Located(parsed, span, self.source, None, tuple(decoded.starts), tuple(decoded.ends))

    def tag_span(self, element: etree._Element) -> Span:
        """The ``<name`` of the element's start tag."""
        tag = self._tags.get(element)
        if tag is None:
            return self._line_span(element)
        return self.source.span(tag.start, tag.start + 1 + len(tag.name))

    def _opaque_text(self, tag: StartTag) -> Located | None:
        end = self.source.text.find("<", tag.end)
        end = len(self.source.text) if end < 0 else end
        raw = self.source.text[tag.end : end]
        stripped = raw.strip(" \t\r\n")
        if not stripped:
            return None
        start = tag.end + len(raw) - len(raw.lstrip(" \t\r\n"))
        return Located(stripped, self.source.span(start, start + len(stripped)), opaque=True)

    @staticmethod
    def _line_span(element: etree._Element) -> Span:
        # lxml-stubs types sourceline as "...": read it as the Optional[int] it is.
        reported: object = element.sourceline
        line = reported if isinstance(reported, int) and reported > 0 else 1
        return Span(line, 1, line, 1)


def _decode_content(text: str, start: int, into: _Decoded) -> bool:
    """Decode element content from ``start`` up to the first child, comment or end tag."""
    position = start
    while True:
        markup = text.find("<", position)
        markup = len(text) if markup < 0 else markup
        if not _decode_markup(text, position, markup, into, attribute=False):
            return False
        if not text.startswith("<![CDATA[", markup):
            return True
        close = text.find("]]>", markup + 9)
        if close < 0:
            return False
        for i in range(markup + 9, close):  # CDATA is verbatim, line ends aside
            if text[i] == "\r":
                into.add("\n", i, i + (2 if text.startswith("\r\n", i) else 1))
            elif not (text[i] == "\n" and i > 0 and text[i - 1] == "\r"):
                into.add(text[i], i, i + 1)
        position = close + 3


def _pair_tags(root: etree._Element, tags: list[StartTag]) -> dict[etree._Element, StartTag]:
    """Pair elements with start tags in document order; nothing if they disagree.

    The list of elements must stay referenced while the mapping is used: lxml keys an
    element proxy by identity, and keeping the proxies alive keeps them the same objects.
    """
    elements = [element for element in root.iter() if isinstance(element.tag, str)]
    if len(elements) != len(tags):
        return {}
    for element, tag in zip(elements, tags, strict=True):
        if etree.QName(element).localname != tag.name.rpartition(":")[2]:
            return {}
    return dict(zip(elements, tags, strict=True))


def _find_attribute(tag: StartTag, key: str, element: etree._Element) -> tuple[int, int] | None:
    uri, _, local = key[1:].partition("}") if key.startswith("{") else ("", "", key)
    for written, start, end in tag.attributes:
        prefix, _, name = written.rpartition(":")
        if name != local:
            continue
        if (not uri and not prefix) or (uri and prefix and element.nsmap.get(prefix) == uri):
            return start, end
    return None


# ---------------------------------------------------------------------------------------
# Parsing

_POSITION_SUFFIX = re.compile(r",\s*line \d+, column \d+\s*$")


def parse(data: bytes) -> XmlDocument | ParseError:
    """Parse untrusted bytes; any failure becomes one ParseError, never an exception."""
    try:
        root = etree.fromstring(data, make_parser())
    except etree.XMLSyntaxError as error:
        return _syntax_error(error)
    except (etree.LxmlError, ValueError, LookupError, UnicodeError) as error:
        return ParseError(f"cannot parse XML: {error}", Span(1, 1, 1, 2))
    if root is None:
        return ParseError("cannot parse XML: no root element", Span(1, 1, 1, 2))
    return XmlDocument(root, Source(decode(data)))


def _syntax_error(error: etree.XMLSyntaxError) -> ParseError:
    line, column = error.position if error.position else (1, 1)
    line, column = max(line or 1, 1), max(column or 1, 1)
    lines = (error.msg or str(error)).strip().splitlines() or ["malformed document"]
    message = _POSITION_SUFFIX.sub("", lines[0])
    return ParseError(f"cannot parse XML: {message}", Span(line, column, line, column + 1))
