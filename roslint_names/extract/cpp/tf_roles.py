"""What a C++ file does with tf: broadcast transforms, look them up, or both.

Told by the identifiers the code writes (not in comments or strings): a
``TransformBroadcaster`` or ``StaticTransformBroadcaster`` (tf, tf2_ros) broadcasts; a
buffer or listener (``Buffer``, ``BufferCore``, ``BufferClient``, ``BufferInterface``,
``TransformListener``, ``Transformer``), a ``MessageFilter``, a lookup
(``lookupTransform``, ``canTransform``, ``waitForTransform``, ``transformPose``...) or a
called ``transform`` method (``tf2_ros::Buffer::transform``) listens. A name counts wherever
it is written: a file that holds a buffer it never uses still listens, which only keeps
RN205 judging its frames.
"""

from __future__ import annotations

from roslint_names.model import TfRole

from .apis import FRAME_FUNCTIONS
from .source import Source, field

_BROADCASTERS = ("TransformBroadcaster", "StaticTransformBroadcaster")
_LISTENERS = (
    "Buffer",
    "BufferCore",
    "BufferClient",
    "BufferInterface",
    "TransformListener",
    "Transformer",
    "MessageFilter",
    *sorted(FRAME_FUNCTIONS),
)
_TRANSFORM = "transform"  # a field of every TransformStamped too: only a call counts


def tf_roles(source: Source) -> tuple[TfRole, ...]:
    """The roles the file's code names, in ``TfRole`` order."""
    found: list[TfRole] = []
    if any(source.occurrences(word) for word in _BROADCASTERS):
        found.append(TfRole.BROADCAST)
    if any(source.occurrences(word) for word in _LISTENERS) or _calls_transform(source):
        found.append(TfRole.LISTEN)
    return tuple(found)


def _calls_transform(source: Source) -> bool:
    """``buffer_->transform(msg, "map")``, ``buffer.transform(...)``."""
    for word in source.occurrences(_TRANSFORM):
        access = word.parent
        call = None if access is None else access.parent
        if (
            access is not None
            and access.type == "field_expression"
            and call is not None
            and call.type == "call_expression"
            and field(call, "function") == access
        ):
            return True
    return False
