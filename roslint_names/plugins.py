"""pluginlib's plugin names: the names a plugin's class gives the parameters it reads.

A node that loads a plugin hands it a name that pluginlib makes from the plugin's lookup
name (``ClassLoader::getName``, pluginlib ``class_loader_imp.hpp``: the lookup name split
at ``/`` and ``:``, the last part), and the plugin reads its parameters under it: move_base
gives ``base_local_planner/TrajectoryPlannerROS`` the namespace ``~/TrajectoryPlannerROS``,
and ROS 1 navigation's ``rotate_recovery`` reads the planner's parameters there. Such a
namespace is the plugin's class name, chosen by whoever wrote the class: RN203 leaves it
alone. The lookup names are those of the plugin description files a ``package.xml``
exports (``<export><nav_core plugin="${prefix}/blp_plugin.xml"/></export>``): each
``<class name="pkg/Name">``, else its ``type="ns::Name"``.
"""

from __future__ import annotations

import re

_EXPORT = re.compile(r"<export\b[^>]*>(.*?)</export\s*>", re.DOTALL)
_DESCRIPTION = re.compile(r"""\bplugin\s*=\s*["']\$\{prefix\}/([^"']+)["']""")
_CLASS = re.compile(r"<class\b([^>]*)>")
_ATTRIBUTE = re.compile(r"""\b(name|type)\s*=\s*["']([^"']*)["']""")
_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)


def exported_descriptions(manifest: str) -> list[str]:
    """The plugin description files a package.xml exports, relative to its package."""
    exports = _EXPORT.findall(_COMMENT.sub("", manifest))
    return [path for block in exports for path in _DESCRIPTION.findall(block)]


def plugin_names(description: str) -> set[str]:
    """The names pluginlib gives the plugins of a description file."""
    names: set[str] = set()
    for attributes in _CLASS.findall(_COMMENT.sub("", description)):
        found = dict(_ATTRIBUTE.findall(attributes))
        lookup = found.get("name") or found.get("type")
        if lookup:
            names.add(re.split(r"[/:]", lookup)[-1])
    return names - {""}
