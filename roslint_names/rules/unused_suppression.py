"""RN002 unused-suppression: a suppression comment that silenced nothing.

The engine reports it after suppressions are matched (``check`` is None): only it knows
which findings each comment silenced.
"""

from __future__ import annotations

from ..model import Severity
from ..rule import Rule

RULE = Rule(
    code="RN002",
    name="unused-suppression",
    summary="A suppression comment that suppresses nothing",
    severity=Severity.WARNING,
    check=None,
    enabled_by_default=False,
)
