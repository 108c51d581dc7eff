"""ROS 2 launch YAML (``.launch.yaml``, ``*_launch.yaml``).

The YAML frontend is the XML one spelled differently (``launch:`` is a list of one-key
mappings, ``{node: {pkg, exec, name, namespace, remap: [...], param: [...]}}``), so the
file is read into the same ``Entity`` shape and walked by the ROS 2 launch walker.

The file is composed, never constructed: ``yaml.compose`` with ``SafeLoader`` builds
nodes that keep their start and end marks and runs no constructor at all.

Spans of YAML values cover the scalar as written, from its first character to just after
its last, *including the quotes* of a quoted scalar (``"talker"`` spans all eight
characters), which matches the rule for code literals ("the opening quote"). A part of a
value (``__node:=x`` inside ``args``) gets its own exact span when the scalar is plain or
quoted without escapes on one line; otherwise it falls back to the whole scalar.

An anchor reused through aliases is walked once: an alias bomb stays linear, and a
repeated node would only repeat the same facts at the same span.
"""

from __future__ import annotations

import yaml

from roslint_names.extract import evidence, yaml_text
from roslint_names.extract.launch.substitution import Located, Source, without_surrogates
from roslint_names.extract.launch.xml_launch import Entity, Ros2Launch, facts_from, too_deep
from roslint_names.model import (
    FileFacts,
    Generation,
    Language,
    LaunchArguments,
    ParseError,
    Span,
)


class _Document:
    """The composed file and its text; remembers which mappings became entities."""

    def __init__(self, source: Source) -> None:
        self.source = source
        self._walked: set[int] = set()
        self._listed: dict[tuple[int, str], list[Entity]] = {}

    def located(self, node: yaml.ScalarNode) -> Located:
        start, end = node.start_mark.index, node.end_mark.index
        span = self.source.span(start, end)
        raw = self.source.text[start:end]
        if node.style is None and raw == node.value:
            first = start  # plain scalar: raw text is the value
        elif node.style in ("'", '"') and raw[1:-1] == node.value and len(raw) >= 2:
            first = start + 1  # quoted without escapes: the value sits inside the quotes
        else:
            return Located(without_surrogates(node.value), span)  # "\ud800" is an escape
        return Located(node.value, span, self.source, first)

    def entities(
        self, owner: yaml.Node, label: str, items: list[tuple[str, yaml.Node, Span]]
    ) -> list[Entity]:
        """Entities for ``items`` listed under ``owner``; a node met twice is dropped."""
        key = (id(owner), label)
        if key not in self._listed:
            listed: list[Entity] = []
            for kind, node, span in items:
                if id(node) not in self._walked:
                    self._walked.add(id(node))
                    listed.append(YamlEntity(self, kind, node, span))
            self._listed[key] = listed
        return self._listed[key]

    def span(self, node: yaml.Node) -> Span:
        return self.source.span(node.start_mark.index, node.end_mark.index)


class YamlEntity:
    """A YAML mapping (or a group's list of children) seen as an ``Entity``."""

    def __init__(self, document: _Document, kind: str, node: yaml.Node, span: Span) -> None:
        self._document = document
        self._kind = kind
        self._node = node
        self._span = span

    @property
    def kind(self) -> str:
        return self._kind

    def _value(self, name: str) -> yaml.Node | None:
        if not isinstance(self._node, yaml.MappingNode):
            return None
        for key, value in self._node.value:
            if isinstance(key, yaml.ScalarNode) and key.value == name:
                return value if isinstance(value, yaml.Node) else None
        return None

    def get(self, name: str) -> Located | None:
        value = self._value(name)
        return self._document.located(value) if isinstance(value, yaml.ScalarNode) else None

    def children(self) -> list[Entity]:
        """A group is either a list of actions or a mapping with a ``children`` list."""
        listing: yaml.Node | None = self._node
        if not isinstance(listing, yaml.SequenceNode):
            listing = self._value("children")
        if not isinstance(listing, yaml.SequenceNode):
            return []
        items: list[tuple[str, yaml.Node, Span]] = []
        for item in listing.value:
            if isinstance(item, yaml.MappingNode) and len(item.value) == 1:
                key, value = item.value[0]
                if isinstance(key, yaml.ScalarNode):
                    items.append((str(key.value), value, self._document.span(key)))
        return self._document.entities(listing, "children", items)

    def nested(self, name: str) -> list[Entity]:
        """``remap:``, ``param:``, ``composable_node:``... a list of attribute mappings."""
        value = self._value(name)
        listed = value.value if isinstance(value, yaml.SequenceNode) else [value]
        items: list[tuple[str, yaml.Node, Span]] = [
            (name, item, self._document.span(item))
            for item in listed
            if isinstance(item, yaml.MappingNode)
        ]
        return self._document.entities(self._node, name, items) if items else []

    def span(self) -> Span:
        return self._span

    def api(self, attribute: str) -> str:
        return f"{self._kind}: {attribute}"

    def content(self) -> Located | None:
        return None  # launch YAML has no free text


def _launch_root(document: _Document, root: yaml.Node | None) -> Entity | None:
    """The ``launch:`` list as an entity whose children are the file's actions."""
    if not isinstance(root, yaml.MappingNode):
        return None
    for key, value in root.value:
        if isinstance(key, yaml.ScalarNode) and key.value == "launch":
            return YamlEntity(document, "launch", value, document.span(key))
    return None


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
    *,
    arguments: LaunchArguments = (),
) -> FileFacts:
    """Names, namespaces, launch nodes and includes of a ROS 2 launch YAML file.

    A file that is valid YAML but no launch file (empty, or without ``launch:``) yields
    nothing: it is not a parse error, and rules have nothing to check in it.
    ``arguments`` are launch configurations set by an including file, as for launch XML.
    """
    default = evidence.extension_generation(path) or Generation.ROS2
    generation = evidence.decide(package_generation, None, default, fallback_generation)
    text = yaml_text.decode(data)
    if isinstance(text, ParseError):
        return FileFacts(path, Language.LAUNCH_YAML, generation, parse_errors=(text,))
    composed = yaml_text.compose(text)
    if isinstance(composed, ParseError):
        return FileFacts(path, Language.LAUNCH_YAML, generation, parse_errors=(composed,))
    root = _launch_root(_Document(Source(text)), composed)
    walker = Ros2Launch(arguments)
    if root is not None:
        try:
            walker.run(root)
        except RecursionError:
            return too_deep(path, Language.LAUNCH_YAML, generation)
    return facts_from(path, Language.LAUNCH_YAML, generation, walker)
