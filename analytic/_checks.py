"""Input validation shared by the analytic functions (private)."""

from __future__ import annotations

import numpy as np

__all__ = ["as_array", "check_finite", "check_positive", "check_nonnegative", "check_choice",
           "check_count", "broadcast"]


def as_array(name: str, value) -> np.ndarray:
    """``value`` as a float array; ``ValueError`` naming ``name`` if it is not numeric (strings
    and booleans are not numbers here) or is NaN."""
    try:
        if isinstance(value, (str, bytes)) or np.asarray(value).dtype.kind in "bOUSV":
            raise TypeError
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number or array, got {value!r}") from None
    if np.any(np.isnan(arr)):
        raise ValueError(f"{name} must not be NaN, got {value!r}")
    return arr


def check_finite(name: str, value) -> np.ndarray:
    """``value`` as a float array, all entries finite (``ValueError`` naming ``name``)."""
    arr = as_array(name, value)
    if np.any(~np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return arr


def check_positive(name: str, value) -> np.ndarray:
    """``value`` as a float array, all entries finite and ``> 0``."""
    arr = as_array(name, value)
    if np.any(~np.isfinite(arr)) or np.any(arr <= 0):
        raise ValueError(f"{name} must be > 0 and finite, got {value!r}")
    return arr


def check_nonnegative(name: str, value) -> np.ndarray:
    """``value`` as a float array, all entries finite and ``>= 0``."""
    arr = as_array(name, value)
    if np.any(~np.isfinite(arr)) or np.any(arr < 0):
        raise ValueError(f"{name} must be >= 0 and finite, got {value!r}")
    return arr


def check_choice(name: str, value, choices) -> str:
    """``value`` if it is one of ``choices``, else ``ValueError`` listing them."""
    if value not in choices:
        raise ValueError(f"{name} must be one of {sorted(choices)}, got {value!r}")
    return value


def check_count(name: str, value) -> int:
    """``int(value)`` of an integer ``>= 1`` (``bool`` is not a count), else ``ValueError``
    naming ``name`` and the value."""
    if (isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer))
            or value < 1):
        raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
    return int(value)


def broadcast(**arrays) -> tuple[np.ndarray, ...]:
    """Broadcast named arrays together; ``ValueError`` naming them if shapes clash."""
    try:
        return tuple(np.broadcast_arrays(*arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k}{np.shape(v)}" for k, v in arrays.items())
        raise ValueError(f"incompatible shapes: {shapes}") from None
