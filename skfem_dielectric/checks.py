"""Input checks of the FE API: each names the parameter and the value it rejects."""

from __future__ import annotations

import math
from typing import Any, Callable, Sequence

import numpy as np

__all__ = ["check_positive", "check_count", "check_finite", "check_choice", "check_energy"]


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


#: ``I1`` values at which a user strain energy is probed on construction (from the
#: reference state to moderate stretches)
ENERGY_PROBE = np.array([3.0, 3.05, 3.2, 3.5, 4.0])


def check_energy(owner: str, funcs: dict[str, Callable], dW3: float,
                 probe: np.ndarray = ENERGY_PROBE) -> None:
    """``ValueError`` unless each of ``funcs`` (``{"W": W, "dW": dW, "d2W": d2W}``) returns
    finite numbers of the shape of ``I1`` (or a scalar) on ``probe``, and ``dW(3) = dW3``
    (the normalisation of the shear modulus, ``mu = 2 W'(3)``) to ``1e-9`` relative.

    ``owner`` names the model in the message (e.g. ``"IdealDielectric"``).
    """
    I1 = np.asarray(probe, dtype=float)
    for label, f in funcs.items():
        if not callable(f):
            raise ValueError(f"{owner}: {label} must be callable, got {f!r}")
        try:
            raw = f(I1.copy())
            if raw is None:
                raise TypeError("it returned None")
            v = np.asarray(raw, dtype=float)
        except Exception as exc:  # noqa: BLE001 - any failure of user code is reported
            raise ValueError(f"{owner}: {label}(I1) must return numbers for I1 = "
                             f"{I1.tolist()}, it raised {type(exc).__name__}: {exc}") from None
        if v.shape not in ((), I1.shape):
            raise ValueError(f"{owner}: {label}(I1) must return an array of the shape of I1 "
                             f"{I1.shape} (or a scalar), got shape {v.shape}")
        bad = ~np.isfinite(np.broadcast_to(v, I1.shape))
        if np.any(bad):
            k = int(np.argmax(bad))
            raise ValueError(f"{owner}: {label}(I1) must be finite, got {label}({float(I1[k])!r}) = "
                             f"{float(np.broadcast_to(v, I1.shape)[k])!r}")
    d = float(np.broadcast_to(np.asarray(funcs["dW"](I1.copy()), dtype=float), I1.shape)[0])
    if not abs(d - dW3) <= 1e-9 * abs(dW3):
        raise ValueError(f"{owner}: dW(3) must equal {dW3!r} (normalised shear modulus, "
                         f"mu = 2 W'(3)), got {d!r}")
