"""Load paths of the drivers: the Keplinger weight, pre-load then charge, resume.

Every driver ramps the load ``(s, D0)`` (``(s, E0)`` under voltage control): first the
mechanical pre-load ``s`` in equal steps at zero charge, then the charge targets at fixed
``s``.  A ramp resumed from a saved step continues with the targets after that step's load.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from ..checks import check_count, check_finite, check_positive

__all__ = ["keplinger_s", "charge_targets", "preload_then_charge", "remaining_targets"]


def keplinger_s(alpha: float, *, g: float, m: float = 0.150, mu: float = 9833.07,
                A: float = 50e-6) -> float:
    """Dimensionless dead load ``s = alpha m g / (mu A)`` of the Keplinger plate.

    The plate of the paper's Sec. 6 (after Keplinger et al.): ``mu = 9833.07 Pa``, the
    weight ``m = 150 g`` hanging on the reference cross-section ``A = 50 mm x 1 mm``.

    Parameters
    ----------
    alpha
        Weight fraction (the paper uses 0.05, 0.3, 0.7, 1.0, 1.5), ``>= 0``.
    g
        Gravitational acceleration in m/s^2, keyword and required (9.81 in the paper's
        figures, 9.80665 standard).
    m, mu, A
        Mass [kg], shear modulus [Pa] and reference cross-section [m^2].

    Returns
    -------
    float
        ``s``; e.g. ``keplinger_s(1.0, g=9.81) = 2.993``.
    """
    for name, v in (("m", m), ("g", g), ("mu", mu), ("A", A)):
        check_positive(name, v)
    alpha = check_finite("alpha", alpha)
    if alpha < 0:
        raise ValueError(f"alpha must be >= 0, got {alpha}")
    return alpha * m * g / (mu * A)


def charge_targets(D0: Any, name: str = "D0") -> np.ndarray:
    """Charge (or ``E0``) targets as a non-empty 1-D array of finite floats.

    Raises
    ------
    ValueError
        Naming ``name`` if ``D0`` is empty, not 1-D or not finite.
    """
    vals = _floats(name, D0)
    if vals.ndim != 1 or vals.size == 0 or not np.all(np.isfinite(vals)):
        raise ValueError(f"{name} must be a non-empty 1-D array of finite values, got {D0!r}")
    return vals


def _floats(name: str, values: Any) -> np.ndarray:
    """``values`` as an at least 1-D float array (strings, booleans, None rejected)."""
    try:
        if isinstance(values, (str, bytes)) or np.asarray(values).dtype.kind in "bOUSV":
            raise TypeError
        return np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a sequence of finite numbers, got {values!r}") from None


def preload_then_charge(s: float, D0: Sequence[float], preload_steps: int) -> list[np.ndarray]:
    """Targets ``(s k/n, 0)`` for ``k = 1 .. n`` (the pre-load), then ``(s, D0_i)`` for
    every non-zero ``D0_i`` (the zero charge is the pre-loaded state itself).

    Parameters
    ----------
    s
        Dead load (finite).
    D0
        Charge targets (finite).
    preload_steps
        ``n``, an integer >= 1.

    Returns
    -------
    list of ndarray
        The loads ``(s, D0)`` in ramp order.
    """
    n = check_count("preload_steps", preload_steps)
    s = check_finite("s", s)
    vals = _floats("D0", D0)
    if vals.ndim != 1 or not np.all(np.isfinite(vals)):
        raise ValueError(f"D0 must be a finite sequence, got {D0!r}")
    out = [np.array([s * k / n, 0.0]) for k in range(1, n + 1)]
    out += [np.array([s, v]) for v in vals if v != 0.0]
    return out


def remaining_targets(targets: Sequence[np.ndarray], start: Any) -> list[np.ndarray]:
    """The targets after ``start`` (the load of a saved step), to resume a ramp.

    Raises
    ------
    ValueError
        If ``start`` is not one of ``targets`` (to 1e-14).
    """
    st = np.asarray(start, dtype=float)
    idx = [i for i, t in enumerate(targets) if np.allclose(t, st, rtol=0, atol=1e-14)]
    if not idx:
        raise ValueError(f"start {start!r} is not one of the ramp's loads")
    return list(targets[idx[0] + 1:])
