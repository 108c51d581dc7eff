"""Strings a Python build script spells with the stdlib ``ast``: literals, names bound to
them, and ``+`` of those (``PACKAGE + "_node"``), as setup.py and dynamic_reconfigure's
``.cfg`` scripts write them."""

from __future__ import annotations

import ast
from collections.abc import Callable, Mapping


def folded_string(
    node: ast.expr,
    strings: Mapping[str, str],
    other: Callable[[ast.expr], str | None] | None = None,
) -> str | None:
    """The string ``node`` evaluates to, when it is built from known strings; ``other``
    folds what this does not know (setup.py's f-strings), else None."""
    if isinstance(node, ast.Constant):
        return node.value if isinstance(node.value, str) else None
    if isinstance(node, ast.Name):
        return strings.get(node.id)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left = folded_string(node.left, strings, other)
        right = folded_string(node.right, strings, other)
        return left + right if left is not None and right is not None else None
    return other(node) if other is not None else None
