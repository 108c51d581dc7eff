"""The frames a launch file gives a static transform publisher on its command line.

``static_transform_publisher`` takes its two frames as arguments, not parameters, and each
program reads them its own way:

- ROS 1 tf (ros/geometry ``tf/src/static_transform_publisher.cpp``, ``main``): after
  ``ros::init`` has removed the ``a:=b`` words, ``x y z yaw pitch roll frame_id
  child_frame_id period_ms`` (9 arguments) or ``x y z qx qy qz qw frame_id child_frame_id
  period_ms`` (10); any other count prints the usage and exits.
- ROS 1 tf2_ros (ros/geometry2 ``tf2_ros/src/static_transform_broadcaster_program.cpp``,
  ``main``): the same without the period, 8 or 9 arguments.
- ROS 2 tf2_ros (ros2/geometry2 ``tf2_ros/src/static_transform_broadcaster_program.cpp``,
  ``parse_args``), after ``rclcpp::init_and_remove_ros_arguments`` has removed every
  ``--ros-args ... --`` block: ``--frame-id X`` and ``--child-frame-id Y`` (the option
  name is a word of its own, looked up whole in a map: there is no ``--frame-id=X``), or
  the deprecated positional forms of 8 or 9 words that take no flag, which tf2_ros refuses
  next to a frame, translation or rotation flag; ``--help``/``-h`` only prints the usage.

A substitution the linter cannot know counts as one word (``$(arg parent)``): what it
expands to stays unknown, and so does the frame there.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum

# How the frames are told apart from the other facts of the launch file, and what
# RN205 knows them by (rules/frame_id_leading_slash.py names the same two strings).
FRAME_API = "static_transform_publisher frame_id"
CHILD_FRAME_API = "static_transform_publisher child_frame_id"

_EXECUTABLE = "static_transform_publisher"


class Program(Enum):
    TF = "tf"  # ROS 1 tf: positional, with a period
    TF2_ROS1 = "tf2_ros ROS 1"  # positional
    TF2_ROS2 = "tf2_ros ROS 2"  # flags, or positional (deprecated)


def program(package: str | None, executable: str | None, ros1: bool) -> Program | None:
    """The static transform publisher a launch node runs, by its generation's launch."""
    if executable != _EXECUTABLE:
        return None
    if package == "tf2_ros":
        return Program.TF2_ROS1 if ros1 else Program.TF2_ROS2
    if package == "tf" and ros1:
        return Program.TF
    return None


@dataclass(frozen=True)
class Frame:
    """The word (an index into the words given) that the program broadcasts as a frame."""

    index: int
    api: str  # FRAME_API or CHILD_FRAME_API


# Positional frames per argument count (the program's argument vector less its name).
_POSITIONAL = {
    Program.TF: {9: (6, 7), 10: (7, 8)},
    Program.TF2_ROS1: {8: (6, 7), 9: (7, 8)},
    Program.TF2_ROS2: {8: (6, 7), 9: (7, 8)},
}
# ROS 2 tf2_ros's options (parse_args): each takes the next word, but for the help ones.
# Translation and quaternion flags cannot go with the positional form; Euler angles can.
_POSE_FLAGS = frozenset({"--qx", "--qy", "--qz", "--qw", "--x", "--y", "--z"})
_EULER_FLAGS = frozenset({"--roll", "--pitch", "--yaw"})
_FRAME_FLAGS = {"--frame-id": FRAME_API, "--child-frame-id": CHILD_FRAME_API}
_HELP = frozenset({"--help", "-h"})


def frames(which: Program, words: Sequence[str]) -> list[Frame]:
    """The frames among the command line's ``words``; none when the program would refuse
    the command line (it then prints its usage and broadcasts nothing)."""
    if which is Program.TF2_ROS2:
        return _ros2_frames(words)
    # ros::init takes every word holding ':=' out of argv before main looks at argc.
    kept = [index for index, word in enumerate(words) if ":=" not in word]
    return _positional(which, kept)


def _positional(which: Program, indices: Sequence[int]) -> list[Frame]:
    positions = _POSITIONAL[which].get(len(indices))
    if positions is None:
        return []
    frame, child = positions
    return [Frame(indices[frame], FRAME_API), Frame(indices[child], CHILD_FRAME_API)]


def _ros2_frames(words: Sequence[str]) -> list[Frame]:
    """``parse_args`` of ros2/geometry2's static_transform_broadcaster_program.cpp."""
    kept = _without_ros_arguments(words)
    flagged: dict[str, int] = {}  # api -> index of the last value given
    positional: list[int] = []
    pose_flags = False
    i = 0
    while i < len(kept):
        word = words[kept[i]]
        if word in _HELP:
            return []  # prints the usage and exits
        if word in _FRAME_FLAGS or word in _POSE_FLAGS or word in _EULER_FLAGS:
            if i + 1 == len(kept):
                return []  # "Not enough arguments for <flag>"
            if word in _FRAME_FLAGS:
                flagged[_FRAME_FLAGS[word]] = kept[i + 1]
            pose_flags = pose_flags or word in _POSE_FLAGS
            i += 2
            continue
        positional.append(kept[i])
        i += 1
    if positional:
        if flagged or pose_flags:
            return []  # "Cannot specify both new-style (flags) and old-style (arguments)"
        return _positional(Program.TF2_ROS2, positional)  # other counts: "Extra unparsed"
    if len(flagged) < len(_FRAME_FLAGS):
        return []  # "Frame id must not be empty", "Child frame id must not be empty"
    return [Frame(flagged[api], api) for api in (FRAME_API, CHILD_FRAME_API)]


def _without_ros_arguments(words: Sequence[str]) -> list[int]:
    """The indices of the words rcl leaves to the program: not ``--ros-args`` up to the
    next ``--`` (or the end), markers included."""
    kept: list[int] = []
    inside = False
    for index, word in enumerate(words):
        if word == "--ros-args":
            inside = True
        elif inside and word == "--":
            inside = False
        elif not inside:
            kept.append(index)
    return kept
