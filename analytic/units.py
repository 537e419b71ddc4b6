"""SI <-> dimensionless conversions and the Keplinger et al. plate (paper Secs. 2 and 6).

The analytic package works with ``mu = eps = 1``. The scalings are those of
Sec. 2.1 (after Eq. gent):

``D0 = D_L/sqrt(mu eps)``,  ``E0 = E_L sqrt(eps/mu)``,  ``s = t/mu``,

with ``D_L`` the Lagrangian electric displacement (charge per *reference* face
area, ``|D_L| = sigma_F = Q/(L1 L3)``), ``E_L = V/H`` the Lagrangian field
(voltage over *reference* thickness) and ``t`` a nominal traction (force per
*reference* area). Signs are kept as given: the loading curves depend on
``D0^2`` only.

The Keplinger et al. (2010) plate of Sec. 6: 100 mm x 50 mm x 1 mm, neo-Hookean
``mu = 9833.07 Pa``, a weight of ``m = 150 g`` hanging on the ``A = 50 mm^2``
reference cross-section (width x thickness), ``s = alpha m g/(mu A)`` with
``alpha in (0.05, 0.3, 0.7, 1.0, 1.5)``. The gravitational acceleration ``g``
is always an explicit argument (9.81 or 9.80665 m/s^2 are both in use).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._checks import as_array, check_positive
from ._output import representable, scalar_or_array

__all__ = [
    "EPS0",
    "Plate",
    "KEPLINGER_PLATE",
    "KEPLINGER_MASS",
    "KEPLINGER_ALPHAS",
    "D0_from_SI",
    "D0_to_SI",
    "E0_from_SI",
    "E0_to_SI",
    "s_from_SI",
    "s_to_SI",
    "charge_to_D0",
    "D0_to_charge",
    "voltage_to_E0",
    "E0_to_voltage",
    "dead_load_s",
    "keplinger_s",
]

#: Vacuum permittivity in F/m (CODATA 2018).
EPS0 = 8.8541878128e-12


def _pos(name, value) -> float:
    v = float(check_positive(name, value))
    return v


@dataclass(frozen=True)
class Plate:
    """Reference geometry and shear modulus of a rectangular plate (SI units).

    Parameters
    ----------
    length : float
        ``L1`` in m (x1, the load direction).
    width : float
        ``L3`` in m (x3).
    thickness : float
        ``H = L2`` in m (x2, the field direction).
    mu : float
        Shear modulus in Pa.

    Examples
    --------
    >>> from analytic.units import KEPLINGER_PLATE
    >>> round(KEPLINGER_PLATE.cross_section * 1e6, 9)  # mm^2
    50.0
    """

    length: float
    width: float
    thickness: float
    mu: float

    def __post_init__(self):
        for name in ("length", "width", "thickness", "mu"):
            object.__setattr__(self, name, _pos(name, getattr(self, name)))

    @property
    def cross_section(self) -> float:
        """Reference cross-section ``A = width x thickness`` (m^2) carrying the x1 load."""
        return self.width * self.thickness

    @property
    def face_area(self) -> float:
        """Reference area ``L1 L3`` (m^2) of one charged face."""
        return self.length * self.width


#: The plate of Keplinger et al. (2010) as modelled in Sec. 6 (Fig. lambda1-3).
KEPLINGER_PLATE = Plate(length=0.100, width=0.050, thickness=0.001, mu=9833.07)
#: Attached mass in kg (Sec. 6).
KEPLINGER_MASS = 0.150
#: Load fractions ``alpha`` of the weight used for the uni-axial cases (Sec. 6).
KEPLINGER_ALPHAS = (0.05, 0.3, 0.7, 1.0, 1.5)


@representable
def D0_from_SI(D_L, mu: float, eps: float):
    """``D0 = D_L/sqrt(mu eps)`` from ``D_L`` in C/m^2 (Sec. 2.1).

    Examples
    --------
    >>> from analytic.units import D0_from_SI, D0_to_SI
    >>> float(D0_from_SI(3.0, mu=4.0, eps=9.0))
    0.5
    """
    return scalar_or_array(as_array("D_L", D_L) / np.sqrt(_pos("mu", mu) * _pos("eps", eps)))


@representable
def D0_to_SI(D0, mu: float, eps: float):
    """``D_L = D0 sqrt(mu eps)`` in C/m^2 (inverse of :func:`D0_from_SI`).

    Examples
    --------
    >>> from analytic.units import D0_to_SI
    >>> float(D0_to_SI(0.5, mu=4.0, eps=9.0))
    3.0
    """
    return scalar_or_array(as_array("D0", D0) * np.sqrt(_pos("mu", mu) * _pos("eps", eps)))


@representable
def E0_from_SI(E_L, mu: float, eps: float):
    """``E0 = E_L sqrt(eps/mu)`` from ``E_L`` in V/m (Sec. 2.1).

    Examples
    --------
    >>> from analytic.units import E0_from_SI
    >>> float(E0_from_SI(2.0, mu=4.0, eps=9.0))
    3.0
    """
    return scalar_or_array(as_array("E_L", E_L) * np.sqrt(_pos("eps", eps) / _pos("mu", mu)))


@representable
def E0_to_SI(E0, mu: float, eps: float):
    """``E_L = E0 sqrt(mu/eps)`` in V/m (inverse of :func:`E0_from_SI`).

    Examples
    --------
    >>> from analytic.units import E0_to_SI
    >>> float(E0_to_SI(3.0, mu=4.0, eps=9.0))
    2.0
    """
    return scalar_or_array(as_array("E0", E0) * np.sqrt(_pos("mu", mu) / _pos("eps", eps)))


@representable
def s_from_SI(t, mu: float):
    """``s = t/mu`` from a nominal traction ``t`` in Pa (Sec. 2.1).

    Examples
    --------
    >>> from analytic.units import s_from_SI
    >>> float(s_from_SI(19666.14, mu=9833.07))
    2.0
    """
    return scalar_or_array(as_array("t", t) / _pos("mu", mu))


@representable
def s_to_SI(s, mu: float):
    """Nominal traction ``t = s mu`` in Pa (inverse of :func:`s_from_SI`).

    Examples
    --------
    >>> from analytic.units import s_to_SI
    >>> float(s_to_SI(2.0, mu=9833.07))
    19666.14
    """
    return scalar_or_array(as_array("s", s) * _pos("mu", mu))


@representable
def charge_to_D0(Q, face_area: float, mu: float, eps: float):
    """``D0`` of a total charge ``Q`` (C) spread over a face of reference area ``face_area`` (m^2).

    ``|D_L| = sigma_F = Q/(L1 L3)`` (Sec. 2.1; charges per reference area, Eq. BCS).

    Examples
    --------
    >>> from analytic.units import charge_to_D0, D0_to_charge
    >>> float(charge_to_D0(6.0, face_area=2.0, mu=1.0, eps=9.0))
    1.0
    """
    return scalar_or_array(D0_from_SI(as_array("Q", Q) / _pos("face_area", face_area), mu, eps))


@representable
def D0_to_charge(D0, face_area: float, mu: float, eps: float):
    """Total charge ``Q = D0 sqrt(mu eps) L1 L3`` in C (inverse of :func:`charge_to_D0`).

    Examples
    --------
    >>> from analytic.units import D0_to_charge
    >>> float(D0_to_charge(1.0, face_area=2.0, mu=1.0, eps=9.0))
    6.0
    """
    return scalar_or_array(D0_to_SI(D0, mu, eps) * _pos("face_area", face_area))


@representable
def voltage_to_E0(V, thickness: float, mu: float, eps: float):
    """``E0`` of a voltage ``V`` (V) across a plate of reference thickness ``H`` (m): ``|E_L| = V/H``.

    Examples
    --------
    >>> from analytic.units import voltage_to_E0
    >>> float(voltage_to_E0(4.0, thickness=2.0, mu=4.0, eps=9.0))
    3.0
    """
    return scalar_or_array(E0_from_SI(as_array("V", V) / _pos("thickness", thickness), mu, eps))


@representable
def E0_to_voltage(E0, thickness: float, mu: float, eps: float):
    """Voltage ``V = E0 sqrt(mu/eps) H`` in V (inverse of :func:`voltage_to_E0`).

    Examples
    --------
    >>> from analytic.units import E0_to_voltage
    >>> float(E0_to_voltage(3.0, thickness=2.0, mu=4.0, eps=9.0))
    4.0
    """
    return scalar_or_array(E0_to_SI(E0, mu, eps) * _pos("thickness", thickness))


@representable
def dead_load_s(mass, g: float, area: float, mu: float):
    """Dimensionless dead load ``s = m g/(mu A)`` of a hanging mass (nominal stress over ``mu``).

    Parameters
    ----------
    mass : array_like
        Mass in kg (>= 0).
    g : float
        Gravitational acceleration in m/s^2 (explicit: 9.81 or 9.80665).
    area : float
        Reference cross-section ``A`` in m^2 carrying the load.
    mu : float
        Shear modulus in Pa.

    Examples
    --------
    >>> from analytic.units import dead_load_s
    >>> float(dead_load_s(1.0, g=10.0, area=2.0, mu=5.0))
    1.0
    """
    mass = as_array("mass", mass)
    if np.any(mass < 0) or np.any(~np.isfinite(mass)):
        raise ValueError(f"mass must be finite and >= 0, got {mass!r}")
    return scalar_or_array(mass * _pos("g", g) / (_pos("area", area) * _pos("mu", mu)))


@representable
def keplinger_s(alpha, *, g: float, plate: Plate = KEPLINGER_PLATE, mass: float = KEPLINGER_MASS):
    """Dead load ``s = alpha m g/(mu A)`` of the Keplinger et al. plate (Sec. 6).

    Parameters
    ----------
    alpha : array_like
        Fraction(s) of the 150 g weight (>= 0); the uni-axial cases use
        :data:`KEPLINGER_ALPHAS` ``= (0.05, 0.3, 0.7, 1.0, 1.5)``.
    g : float
        Gravitational acceleration in m/s^2, keyword only and required.
    plate : Plate
        Geometry and ``mu`` (default :data:`KEPLINGER_PLATE`, ``A = 50 mm^2``).
    mass : float
        Mass in kg (default 0.150).

    Returns
    -------
    s : ndarray
        ``alpha * 0.150 * g / (9833.07 * 50e-6)``; ``s = 2.99296`` for
        ``alpha = 1``, ``g = 9.81``.

    Examples
    --------
    >>> from analytic.units import keplinger_s
    >>> round(float(keplinger_s(1.0, g=9.81)), 5)
    2.99296
    """
    alpha = as_array("alpha", alpha)
    if np.any(alpha < 0) or np.any(~np.isfinite(alpha)):
        raise ValueError(f"alpha must be finite and >= 0, got {alpha!r}")
    return scalar_or_array(alpha * dead_load_s(mass, g, plate.cross_section, plate.mu))
