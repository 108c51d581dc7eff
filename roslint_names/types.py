"""ROS interface type spellings: one canonical form for the many ways code writes a type.

``std_msgs::msg::String``, ``std_msgs::String``, ``std_msgs/msg/String``,
``std_msgs/String`` and ``std_msgs.msg.String`` all name one type. Extractors store what
the code wrote; rules compare canonical forms.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

_SEPARATORS = re.compile(r"::|/|\.")
_INTERFACE_FOLDERS = frozenset({"msg", "srv", "action"})
_WRAPPERS = ("Request", "Response", "Goal", "Result", "Feedback")


@dataclass(frozen=True, order=True)
class InterfaceType:
    package: str | None  # None when the code names the type without its package
    name: str  # "SetBool"

    def __str__(self) -> str:
        return f"{self.package}/{self.name}" if self.package else self.name


@lru_cache(maxsize=4096)  # a pure function of a string, asked again for every use of a type
def parse_type(spelling: str) -> InterfaceType | None:
    """The canonical type of a spelling, or None when it is not a type name.

    A service's ``Request``/``Response`` part (``std_srvs::SetBool::Request``,
    ``SetBool_Request``) names the service itself.
    """
    text = spelling.strip().lstrip(":")
    text = re.sub(r"\s+", "", text)
    text = re.sub(r"(ConstPtr|Ptr|::SharedPtr|::ConstSharedPtr|::UniquePtr)$", "", text)
    parts = [part for part in _SEPARATORS.split(text) if part]
    if parts and parts[-1] in _WRAPPERS and len(parts) >= 2:
        parts = parts[:-1]
    if parts:
        for wrapper in _WRAPPERS:
            suffix = "_" + wrapper
            if parts[-1].endswith(suffix) and len(parts[-1]) > len(suffix):
                parts[-1] = parts[-1][: -len(suffix)]
    parts = [part for part in parts if part not in _INTERFACE_FOLDERS]
    if not parts or not all(re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", part) for part in parts):
        return None
    if len(parts) == 1:
        return InterfaceType(None, parts[0])
    return InterfaceType(parts[-2], parts[-1])
