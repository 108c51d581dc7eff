"""What a launch sets on each node: every parameter, by name, with where it is written.

A launch sets a node's parameters three ways: on the node itself (``<param name>``,
``<rosparam param>``, a ``Node``'s ``parameters=[{...}]``, ``-p name:=value`` or ROS 1's
``_name:=value`` on its command line), through a parameter file it hands the node (ROS 2:
the entries of the node keys that match the node, ``parameter_files.key_matches``), and,
in ROS 1, through a ``<rosparam command="load" file>`` whose namespace is the node's
private one or below it (roslaunch sets every leaf under the namespace, ``loader.py``,
``Loader.load_rosparam``).

Names are as the node reads them: ROS 2's dotted names; ROS 1's relative to the node's
private namespace when they are below it (``max_vel_x``, ``global_costmap/width``), else
fully qualified.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from roslint_names.model import Generation, LaunchNode, ParameterBlock, Span
from roslint_names.workspace.graph import (
    Location,
    ParameterFileUse,
    ParameterSetting,
    SettingSource,
)
from roslint_names.workspace.parameter_files import key_matches


def launch_settings(
    node: LaunchNode, path: str, full_name: str, generation: Generation, conditional: bool
) -> Iterator[ParameterSetting]:
    """The parameters the launch file ``path`` sets on the node itself."""
    for name, span in zip(node.parameters, node.parameter_spans, strict=False):
        shown = _ros1_name(name, full_name) if generation is Generation.ROS1 else name
        yield ParameterSetting(
            shown, Location(path, span), SettingSource.LAUNCH, conditional=conditional
        )


def file_settings(
    blocks: Iterable[ParameterBlock],
    use: ParameterFileUse,
    full_name: str,
    *,
    generation: Generation,
    matched: str,
    composable: bool,
) -> Iterator[ParameterSetting]:
    """The parameters one file sets on the node ``full_name``; ROS 2 matches its node
    keys against ``matched`` (the name launch_ros or rclcpp matches the node by)."""
    for block in blocks:
        if generation is Generation.ROS1:
            if block.key is not None:
                continue
            base = use.namespace.rstrip("/")
            for name, span in block.parameters:
                full = f"{base}/{name.strip('/')}"
                yield _from_file(_ros1_name(full, full_name), use, span, None)
        elif block.key is not None and key_matches(block.key, matched, composable=composable):
            for name, span in block.parameters:
                yield _from_file(name, use, span, block.key)


def group_settings(
    full_name: str,
    root: str,
    loads: Iterable[tuple[str, ParameterFileUse]],
    blocks_of: dict[str, tuple[ParameterBlock, ...]],
) -> Iterator[ParameterSetting]:
    """ROS 1: the parameters that group-level ``<rosparam load>`` of the node's launch
    tree (``loads``: each with its tree's root) put in the node's private namespace."""
    for load_root, use in loads:
        if load_root != root:
            continue
        for setting in file_settings(
            blocks_of.get(use.path, ()),
            use,
            full_name,
            generation=Generation.ROS1,
            matched=full_name,
            composable=False,
        ):
            if not setting.name.startswith("/"):  # below the node's private namespace
                yield setting


def ordered(settings: Iterable[ParameterSetting]) -> tuple[ParameterSetting, ...]:
    return tuple(sorted(set(settings), key=ParameterSetting.sort_key))


def _from_file(name: str, use: ParameterFileUse, span: Span, key: str | None) -> ParameterSetting:
    return ParameterSetting(
        name,
        Location(use.path, span),
        SettingSource.FILE,
        key=key,
        site=use.site,
        conditional=use.conditional,
    )


def _ros1_name(name: str, full_name: str) -> str:
    """A ROS 1 name set on the node ``full_name``, relative to its private namespace
    when below it (``~x`` and a relative ``x`` are), else fully qualified."""
    if name.startswith("~"):
        return name[1:].lstrip("/")
    if not name.startswith("/"):
        return name
    private = f"{full_name.rstrip('/')}/"
    return name[len(private) :] if name.startswith(private) else name
