"""RN003 invalid-suppression: a suppression naming an RN code that does not exist.

Reported by the engine while it matches suppressions (``check`` is None).
"""

from __future__ import annotations

from ..model import Severity
from ..rule import Rule

RULE = Rule(
    code="RN003",
    name="invalid-suppression",
    summary="A suppression comment naming an unknown rule code",
    severity=Severity.WARNING,
    check=None,
)
