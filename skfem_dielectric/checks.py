"""Input checks of the FE API: each names the parameter and the value it rejects."""

from __future__ import annotations

import math
from typing import Any, Sequence

__all__ = ["check_positive", "check_count", "check_finite", "check_choice"]


def check_positive(name: str, value: Any) -> float:
    """``float(value)`` if it is a finite number > 0, else ``ValueError`` naming ``name``."""
    v = float(value)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return v


def check_count(name: str, value: Any) -> int:
    """``int(value)`` if it is an integer >= 1, else ``ValueError`` naming ``name``."""
    if int(value) != value or int(value) < 1:
        raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
    return int(value)


def check_finite(name: str, value: Any) -> float:
    """``float(value)`` if it is finite, else ``ValueError`` naming ``name``."""
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def check_choice(name: str, value: Any, choices: Sequence[str]) -> str:
    """``value`` if it is one of ``choices``, else ``ValueError`` naming ``name``."""
    if value not in choices:
        raise ValueError(f"{name} must be one of {tuple(choices)}, got {value!r}")
    return value
