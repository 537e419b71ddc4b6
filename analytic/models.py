"""Strain-energy models ``W(I1)`` of ideal dielectrics, in dimensionless form.

All energies are divided by the shear modulus ``mu`` (the paper's ``W-bar``), so
that a model is fully described by ``W(I1)``, ``W'(I1)`` and ``W''(I1)``. The
electric part of the energy, ``+ I5*/(2 eps)`` (Eq. modelD) or ``- eps I5/2``
(Eq. modelE), is the same for every model and lives in :mod:`analytic.homogeneous`.

The models here are the paper's Eq. (gent): neo-Hookean ``W = (I1 - 3)/2`` and
Gent ``W = -(Jm/2) ln(1 - (I1 - 3)/Jm)``; :class:`UserModel` accepts any
``W(I1)`` with its first two derivatives.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

__all__ = ["Model", "NeoHookean", "Gent", "UserModel", "as_model"]


def _as_I1(I1) -> np.ndarray:
    I1 = np.asarray(I1, dtype=float)
    if np.any(np.isnan(I1)):
        raise ValueError(f"I1 must not be NaN, got {I1}")
    return I1


class Model:
    """Base class of dimensionless strain-energy models ``W(I1)`` (``mu = 1``).

    Subclasses implement :meth:`W`, :meth:`dW` and :meth:`d2W`; all three are
    vectorised over array ``I1`` and raise ``ValueError`` where ``I1`` is outside
    the model's domain (e.g. beyond the Gent locking limit).
    """

    name: str = "model"

    def W(self, I1):
        """Strain energy ``W(I1)/mu``."""
        raise NotImplementedError

    def dW(self, I1):
        """First derivative ``W'(I1)/mu`` (the paper's ``W-bar'``, Eq. W)."""
        raise NotImplementedError

    def d2W(self, I1):
        """Second derivative ``W''(I1)/mu`` (the paper's ``W-bar''``, Eq. W)."""
        raise NotImplementedError

    def I1_max(self) -> float:
        """Supremum of admissible ``I1`` (``inf`` when the model does not lock)."""
        return np.inf


@dataclass(frozen=True)
class NeoHookean(Model):
    """Neo-Hookean dielectric, ``W = (I1 - 3)/2`` (Eq. gent, left).

    Examples
    --------
    >>> from analytic import NeoHookean
    >>> m = NeoHookean()
    >>> float(m.W(5.0)), float(m.dW(5.0)), float(m.d2W(5.0))
    (1.0, 0.5, 0.0)
    """

    name: str = field(default="neo-Hookean", init=False)

    def W(self, I1):
        return 0.5 * (_as_I1(I1) - 3.0)

    def dW(self, I1):
        return np.full_like(_as_I1(I1), 0.5)

    def d2W(self, I1):
        return np.zeros_like(_as_I1(I1))


@dataclass(frozen=True)
class Gent(Model):
    """Gent dielectric, ``W = -(Jm/2) ln(1 - (I1 - 3)/Jm)`` (Eq. gent, right).

    Parameters
    ----------
    Jm : float
        Stiffening (locking) parameter, ``Jm > 0``. The paper uses ``Jm = 97.2``
        (Gent 1996). ``I1`` must stay below ``3 + Jm``.

    Notes
    -----
    ``W' = 1/(2 (1 - (I1-3)/Jm))`` and ``W'' = 1/(2 Jm (1 - (I1-3)/Jm)^2)``,
    the paper's Eq. (W). ``Gent(Jm)`` tends to :class:`NeoHookean` as
    ``Jm -> inf``.

    Examples
    --------
    >>> from analytic import Gent
    >>> g = Gent(Jm=97.2)
    >>> round(float(g.dW(3.0)), 12)
    0.5
    """

    Jm: float = 97.2
    name: str = field(default="Gent", init=False)

    def __post_init__(self):
        Jm = self.Jm.item() if isinstance(self.Jm, np.ndarray) and self.Jm.ndim == 0 else self.Jm
        if isinstance(Jm, (bool, np.bool_, str, bytes)) or not isinstance(
                Jm, (int, float, np.integer, np.floating)) or not np.isfinite(Jm) or Jm <= 0:
            raise ValueError(f"Jm must be a finite number > 0, got {self.Jm!r}")
        Jm = float(Jm)
        object.__setattr__(self, "Jm", Jm)

    def I1_max(self) -> float:
        return 3.0 + self.Jm

    def _x(self, I1):
        I1 = _as_I1(I1)
        x = 1.0 - (I1 - 3.0) / self.Jm
        if np.any(x <= 0):
            bad = I1[x <= 0] if I1.ndim else I1
            raise ValueError(
                f"I1 beyond the Gent limit 3 + Jm = {3.0 + self.Jm}: got I1 = {bad}"
            )
        return x

    def W(self, I1):
        return -0.5 * self.Jm * np.log(self._x(I1))

    def dW(self, I1):
        return 0.5 / self._x(I1)

    def d2W(self, I1):
        return 0.5 / (self.Jm * self._x(I1) ** 2)


@dataclass(frozen=True)
class UserModel(Model):
    """A user-supplied dimensionless ``W(I1)`` with its first two derivatives.

    Parameters
    ----------
    W, dW, d2W : callable
        Vectorised functions of ``I1`` returning ``W/mu``, ``W'/mu``, ``W''/mu``.
        For the reference state to be stress free with shear modulus ``mu``,
        ``dW(3) = 1/2``.
    name : str
        Label used in tables and figures.
    I1_limit : float, optional
        Supremum of admissible ``I1`` (default ``inf``); larger ``I1`` raises.

    Raises
    ------
    ValueError
        On construction, an ``I1_limit`` that is not a real number ``> 3``; a callable that
        fails, returns complex or non-finite values or an array of
        another shape than ``I1`` (a scalar is broadcast) on the probe ``I1`` = 3, 3.05,
        3.2, 3.5, 4 (those below ``I1_limit``; else points between 3 and the limit), or a
        model with ``W'(3) != 1/2`` (the energies are normalised by the shear modulus,
        ``mu = 2 W'(3) = 1``).

    Examples
    --------
    A Mooney-free "quadratic" model ``W = (I1-3)/2 + 0.01 (I1-3)^2``:

    >>> from analytic import UserModel
    >>> m = UserModel(W=lambda I: 0.5*(I-3) + 0.01*(I-3)**2,
    ...               dW=lambda I: 0.5 + 0.02*(I-3),
    ...               d2W=lambda I: 0.02 + 0*I, name="quadratic")
    >>> float(m.dW(3.0))
    0.5
    """

    W_fun: Callable = field(default=None, repr=False)
    dW_fun: Callable = field(default=None, repr=False)
    d2W_fun: Callable = field(default=None, repr=False)
    name: str = "user"
    I1_limit: float = np.inf

    def __init__(self, W, dW, d2W, name: str = "user", I1_limit: float = np.inf):
        for label, f in (("W", W), ("dW", dW), ("d2W", d2W)):
            if not callable(f):
                raise ValueError(f"{label} must be callable, got {f!r}")
        if (isinstance(I1_limit, (bool, np.bool_))
                or not isinstance(I1_limit, (int, float, np.integer, np.floating))
                or not I1_limit > 3.0):
            raise ValueError(f"I1_limit must be a real number > 3 (or inf), got {I1_limit!r}")
        object.__setattr__(self, "W_fun", W)
        object.__setattr__(self, "dW_fun", dW)
        object.__setattr__(self, "d2W_fun", d2W)
        object.__setattr__(self, "name", str(name))
        object.__setattr__(self, "I1_limit", float(I1_limit))
        _probe_energy(self)

    def I1_max(self) -> float:
        return self.I1_limit

    def _check(self, I1):
        I1 = _as_I1(I1)
        if np.any(I1 >= self.I1_limit):
            raise ValueError(f"I1 beyond the model limit {self.I1_limit}: got I1 = {I1}")
        return I1

    def W(self, I1):
        I1 = self._check(I1)
        return np.asarray(self.W_fun(I1), dtype=float) + 0.0 * I1

    def dW(self, I1):
        I1 = self._check(I1)
        return np.asarray(self.dW_fun(I1), dtype=float) + 0.0 * I1

    def d2W(self, I1):
        I1 = self._check(I1)
        return np.asarray(self.d2W_fun(I1), dtype=float) + 0.0 * I1


_PROBE = np.array([3.0, 3.05, 3.2, 3.5, 4.0])


def _probe_energy(model: "UserModel") -> None:
    """``ValueError`` naming the model and the callable unless ``W, W', W''`` give finite
    numbers of the shape of ``I1`` on a probe grid and ``W'(3) = 1/2``."""
    lim = model.I1_limit
    I1 = _PROBE[_PROBE < lim] if np.sum(_PROBE < lim) >= 3 else \
        3.0 + (lim - 3.0) * np.array([0.0, 0.1, 0.4, 0.7, 0.9])
    who = f"UserModel {model.name!r}"
    for label, f in (("W", model.W_fun), ("dW", model.dW_fun), ("d2W", model.d2W_fun)):
        try:
            raw = f(I1.copy())
            if raw is None:
                raise TypeError("it returned None")
            complex_out = np.iscomplexobj(raw)
            v = np.asarray(raw, dtype=float) if not complex_out else None
        except Exception as exc:  # noqa: BLE001 - any failure of user code is reported
            raise ValueError(f"{who}: {label}(I1) must return numbers for I1 = {I1.tolist()}, "
                             f"it raised {type(exc).__name__}: {exc}") from None
        if complex_out:
            raise ValueError(f"{who}: {label}(I1) must return real numbers, got "
                             f"{label}({float(I1[0])!r}) = {complex(np.ravel(raw)[0])!r}")
        if v.shape not in ((), I1.shape):
            raise ValueError(f"{who}: {label}(I1) must return an array of the shape of I1 "
                             f"{I1.shape} (or a scalar), got shape {v.shape}")
        v = np.broadcast_to(v, I1.shape)
        if not np.all(np.isfinite(v)):
            k = int(np.argmax(~np.isfinite(v)))
            raise ValueError(f"{who}: {label}(I1) must be finite, got {label}({float(I1[k])!r}) = "
                             f"{float(v[k])!r}")
        if label == "dW" and not abs(v[0] - 0.5) <= 1e-9:
            raise ValueError(f"{who}: dW(3) must be 0.5 (energies normalised by the shear "
                             f"modulus, mu = 2 W'(3) = 1), got {float(v[0])!r}")


def as_model(model) -> Model:
    """Return ``model`` as a :class:`Model`; ``None`` means :class:`NeoHookean`.

    Raises
    ------
    ValueError
        If ``model`` is not a :class:`Model` (or ``None``).
    """
    if model is None:
        return NeoHookean()
    if isinstance(model, Model):
        return model
    raise ValueError(
        f"model must be an analytic model (NeoHookean(), Gent(Jm), UserModel(...)), got {model!r}"
    )
