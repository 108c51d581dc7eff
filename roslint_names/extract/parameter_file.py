"""Parameter files: ROS 2 ``ros__parameters`` YAML and ROS 1 ``rosparam`` YAML.

Which YAML file is a parameter file is decided from evidence. A file holding
``ros__parameters`` is a ROS 2 one by its content, whatever loads it: rcl reads nothing
else (rcl_yaml_param_parser ``parse.c``, ``parse_key``: "There are no node names before
ros__parameters", ``parse_file_events``: "Cannot have a value before ros__parameters").
Any other YAML file of a ROS 1 package may be a ``rosparam`` file, which is any mapping;
whether it is one is a question about the launch files that load it, answered by the
workspace graph: so its names are kept as ``ParameterBlock`` facts only, never as
``NameUse``s that the per-file rules would judge. A YAML file of a ROS 2 package without
``ros__parameters`` is no parameter file and is not even parsed.

ROS 2 keys, as rcl reads them (``parse_key``, ``parse_file_events``): the keys down to
``ros__parameters`` name the node, joined with '/' (``add_name_to_ns`` with
``NODE_NS_SEPERATOR``): ``controller_server``, ``/robot1/amcl``, ``robot1: {amcl: ...}``,
wildcards ``/**``, ``/**/node``, ``*``. rcl compares the key with ``strncmp(PARAMS_KEY,
value, strlen(PARAMS_KEY))``: any key that starts with ``ros__parameters`` counts. Below
it, nested mappings are joined with '.' (``PARAMETER_NS_SEPERATOR``): ``FollowPath:
{max_vel_x: 0.5}`` is ``FollowPath.max_vel_x``.

ROS 1 (roslaunch ``loader.py``, ``Loader.add_param``): a mapping is unrolled into one
parameter per leaf, its keys joined with ``ns_join`` ('/'); the namespace it is loaded
under is the launch file's to say (``<rosparam command="load" file ns>``).

Spans are those of the keys as written (quotes included), from the composer's node marks
(``yaml.compose`` builds nodes and runs no constructor). PyYAML is imported on first use,
its C loader when built: a run over a launch file alone never loads it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from roslint_names.extract import yaml_text
from roslint_names.extract.launch.substitution import Located, Source
from roslint_names.model import (
    FileFacts,
    Generation,
    Kind,
    Language,
    NameUse,
    ParameterBlock,
    ParseError,
    Role,
    Span,
)
from roslint_names.reading import bom_encoding

if TYPE_CHECKING:
    import yaml

PARAMS_KEY = "ros__parameters"  # rcl_yaml_param_parser src/impl/types.h
API = "parameter file"
_PARAMS_BYTES = PARAMS_KEY.encode("ascii")
_MERGE_KEY = "<<"  # a YAML merge key: PyYAML's constructor merges it, rcl refuses aliases
_MAX_DEPTH = 64  # nesting deeper than any parameter file; stops a malicious one


def extract(
    path: str,
    data: bytes,
    package_generation: Generation | None,
    fallback_generation: Generation,
) -> FileFacts:
    """The parameter blocks of a parameter file (and, ROS 2, its parameter names)."""
    ros2 = _PARAMS_BYTES in data or _wide(data)
    generation = Generation.ROS2 if ros2 else package_generation or fallback_generation
    empty = FileFacts(path, Language.PARAMETERS, generation)
    if not ros2 and generation is not Generation.ROS1:
        return empty  # a ROS 2 package's YAML without ros__parameters: no parameter file
    text = yaml_text.decode(data)
    if isinstance(text, ParseError):
        return (
            FileFacts(path, Language.PARAMETERS, generation, parse_errors=(text,))
            if ros2
            else empty
        )
    composed = yaml_text.compose(text, libyaml=True)
    if isinstance(composed, ParseError):
        # Only a file that is a parameter file by its content is one whose YAML must parse.
        if not ros2:
            return empty
        return FileFacts(path, Language.PARAMETERS, generation, parse_errors=(composed,))
    if ros2 and PARAMS_KEY not in text:
        return empty  # a UTF-16 file without the key after all
    reader = _Reader(Source(text))
    try:
        blocks = reader.ros2(composed) if ros2 else reader.ros1(composed)
    except RecursionError:
        blocks = []
    names = tuple(
        NameUse(Kind.PARAMETER, name, span, Role.PARAMETER, API)
        for block in blocks
        for name, span in block.parameters
        if ros2
    )
    return FileFacts(
        path, Language.PARAMETERS, generation, names=names, parameter_blocks=tuple(blocks)
    )


def inline_names(content: Located) -> list[tuple[str, Span]]:
    """The leaves of the YAML mapping a ROS 1 ``<rosparam>`` holds, keys joined with '/',
    each with the span of its key in the launch file; none for anything else."""
    import yaml

    composed = yaml_text.compose(content.text, libyaml=True)
    if not isinstance(composed, yaml.MappingNode):
        return []
    reader = _Reader(Source(content.text), locate=lambda start, end: content.slice(start, end).span)
    try:
        return list(reader._parameters(composed, "", "/", 0))
    except RecursionError:
        return []


def _wide(data: bytes) -> bool:
    """UTF-16 or UTF-32: the key's bytes are not ASCII there; decide after decoding."""
    return bom_encoding(data) not in (None, "utf-8", "utf-8-sig")


@dataclass
class _Reader:
    source: Source
    # Where characters ``start:end`` of the text are written (a launch file's, for YAML
    # inside a ``<rosparam>``); by default the text's own.
    locate: Callable[[int, int], Span] | None = None
    _seen: set[int] = field(default_factory=set)  # an anchored node is read once

    def span(self, node: yaml.Node) -> Span:
        start, end = node.start_mark.index, node.end_mark.index
        return self.source.span(start, end) if self.locate is None else self.locate(start, end)

    def ros2(self, root: yaml.Node | None) -> list[ParameterBlock]:
        import yaml

        if not isinstance(root, yaml.MappingNode):
            return []
        return list(self._node_keys(root, [], None, 0))

    def _node_keys(
        self, mapping: yaml.MappingNode, keys: list[str], last: Span | None, depth: int
    ) -> Iterator[ParameterBlock]:
        """rcl's ``MAP_NODE_NAME_LVL``: keys name the node until ``ros__parameters``;
        ``last`` is the span of the key written last."""
        import yaml

        if depth > _MAX_DEPTH or id(mapping) in self._seen:
            return
        self._seen.add(id(mapping))
        for key, value in _pairs(mapping):
            if key.value.startswith(PARAMS_KEY):
                if last is not None and isinstance(value, yaml.MappingNode):
                    parameters = tuple(self._parameters(value, "", ".", depth + 1))
                    yield ParameterBlock("/".join(keys), last, parameters)
            elif isinstance(value, yaml.MappingNode):
                yield from self._node_keys(value, [*keys, key.value], self.span(key), depth + 1)

    def ros1(self, root: yaml.Node | None) -> list[ParameterBlock]:
        import yaml

        if not isinstance(root, yaml.MappingNode) or not root.value:
            return []
        first = root.value[0][0]
        parameters = tuple(self._parameters(root, "", "/", 0))
        return [ParameterBlock(None, self.span(first), parameters)]

    def _parameters(
        self, mapping: yaml.MappingNode, prefix: str, separator: str, depth: int
    ) -> Iterator[tuple[str, Span]]:
        """Every leaf below ``mapping``: its name (the keys joined with ``separator``)
        and its key's span."""
        import yaml

        if depth > _MAX_DEPTH or id(mapping) in self._seen:
            return
        self._seen.add(id(mapping))
        for key, value in _pairs(mapping):
            name = f"{prefix}{separator}{key.value}" if prefix else key.value
            if isinstance(value, yaml.MappingNode) and value.value:
                yield from self._parameters(value, name, separator, depth + 1)
            else:
                yield name, self.span(key)


def _pairs(mapping: yaml.MappingNode) -> Iterator[tuple[yaml.ScalarNode, yaml.Node]]:
    """The pairs with a scalar key other than a merge key."""
    import yaml

    for key, value in mapping.value:
        if isinstance(key, yaml.ScalarNode) and key.value != _MERGE_KEY:
            yield key, value
