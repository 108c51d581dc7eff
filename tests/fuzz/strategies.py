"""Hypothesis strategies for fuzz inputs (see ``inputs`` for what each step does)."""

from __future__ import annotations

from hypothesis import strategies as st

from fuzz.inputs import (
    ALL_SEEDS,
    ENCODINGS,
    LINE_ENDS,
    TOKENS,
    Mutation,
    Sample,
    Target,
    mutate,
    reencode,
    seeds,
)
from roslint_names.model import Generation, LaunchArguments

MAX_RANDOM_BYTES = 4096


@st.composite
def mutations(draw: st.DrawFn) -> Mutation:
    kind = draw(
        st.sampled_from(
            (
                "flip",
                "set",
                "insert",
                "in_string",
                "delete",
                "delete_word",
                "delete_line",
                "duplicate",
                "splice",
                "truncate",
            )
        )
    )
    position = draw(st.just(0) | st.integers(0, 1 << 20))  # the start matters most
    if kind in ("insert", "in_string"):
        payload = draw(st.sampled_from(TOKENS) | st.binary(min_size=1, max_size=16))
        return Mutation(kind, position, payload=payload)
    if kind == "splice":
        donor = draw(st.sampled_from(ALL_SEEDS))
        start = draw(st.integers(0, len(donor)))
        length = draw(st.integers(1, 512))
        return Mutation(kind, position, payload=donor[start : start + length])
    return Mutation(kind, position, draw(st.integers(0, 255)))


def random_bytes(target: Target) -> st.SearchStrategy[tuple[str, str, bytes]]:
    plain = st.binary(max_size=MAX_RANDOM_BYTES).map(lambda data: ("", data))
    prefixed = st.tuples(st.sampled_from(target.prefixes), st.binary(max_size=MAX_RANDOM_BYTES))
    return (plain | prefixed.map(lambda pair: (" after a prefix", pair[0] + pair[1]))).map(
        lambda found: ("random bytes", "random bytes" + found[0], found[1])
    )


def real_file(target: Target) -> st.SearchStrategy[tuple[str, str, bytes]]:
    # Mostly the target's own files; sometimes another language's, which is hostile too.
    return damaged(st.sampled_from(seeds(target)) | st.sampled_from(ALL_SEEDS))


@st.composite
def damaged(draw: st.DrawFn, originals: st.SearchStrategy[bytes]) -> tuple[str, str, bytes]:
    """(kind, origin, bytes): a real file mutated, or re-encoded and perhaps mutated too."""
    data = draw(originals)
    kind = "real file"
    details = []
    if draw(st.booleans()):
        encoding = draw(st.sampled_from(tuple(ENCODINGS)))
        line_end = draw(st.sampled_from(tuple(LINE_ENDS)))
        declare = draw(st.booleans())
        data = reencode(data, encoding, line_end, declare)
        kind = "re-encoded"
        details.append(f"{encoding}, {line_end}" + (", declared" if declare else ""))
    if draw(st.integers(0, 9)) == 0:  # NUL bytes everywhere, not just at one point
        data = data.replace(b" ", b"\x00")
        details.append("NUL for space")
    edits = draw(st.lists(mutations(), min_size=1 if kind == "real file" else 0, max_size=16))
    if edits:
        data = mutate(data, edits)
        kind = "mutated" if kind == "real file" else kind
        details.append(f"{len(edits)} mutations")
    return kind, ": ".join([kind, ", ".join(details)]), data


_NAMES = st.text(alphabet="abcxyz_/~$()", min_size=1, max_size=8)
ARGUMENTS: st.SearchStrategy[LaunchArguments] = st.lists(
    st.tuples(
        st.sampled_from(("robot", "ns", "model", "use_sim_time")) | _NAMES, st.none() | _NAMES
    ),
    max_size=3,
).map(tuple)


@st.composite
def samples(draw: st.DrawFn, target: Target) -> Sample:
    kind, origin, data = draw(random_bytes(target) | real_file(target) | real_file(target))
    arguments = draw(ARGUMENTS) if target.takes_arguments else ()
    return Sample(
        kind=kind,
        origin=origin,
        data=data,
        path=draw(st.sampled_from(target.paths)),
        package_generation=draw(st.sampled_from((None, Generation.ROS1, Generation.ROS2))),
        fallback_generation=draw(st.sampled_from((Generation.ROS1, Generation.ROS2))),
        arguments=arguments,
    )
