"""Closed-form theory of charge-controlled soft dielectric plates.

Implements the homogeneous theory of Conroy Broderick, Righi, Destrade, Ogden,
"Stability analysis of charge-controlled soft dielectric plates", Int. J. Eng. Sci.,
2020 ("the paper" throughout): loading curves,
Hessian criteria and Stroh-formalism wrinkling. Everything is dimensionless
(``mu = eps = 1``); see :mod:`analytic.units` for SI conversions.

Return convention: the functions broadcast their number arguments. When all of
them are scalars, each result is a Python ``float`` (``bool`` for the stability
verdicts, ``complex`` for the Stroh exponents) and several results are a tuple of
such numbers; otherwise each result is an ``ndarray`` of the broadcast shape.
Matrix results (Hessians, moduli, Stroh matrix, surface impedance) are always
arrays, of the broadcast shape followed by the matrix axes. The methods ``W``,
``dW`` and ``d2W`` of the models are array kernels and return arrays.
"""

from .models import Gent, Model, NeoHookean, UserModel, as_model
from .stroh import electroelastic_moduli, stroh_coefficients, stroh_exponents, stroh_matrix
from .wrinkling import (
    WrinklingMap,
    critical_D0,
    critical_D0_biaxial,
    critical_point_on_path,
    dispersion_function,
    surface_impedance,
    surface_instability_stretch,
    thick_limit_D0,
    thick_limit_D0_numeric,
    thick_limit_D0_uniaxial,
    thin_limit_D0,
    thin_limit_D0_uniaxial,
    thin_plate_factors,
    wrinkling_map,
)
from .hessian import (
    equibiaxial_hessian_omega,
    equibiaxial_hessian_omega_star,
    equibiaxial_omega,
    equibiaxial_omega_star,
    equibiaxial_stability_verdict,
    hessian_omega,
    hessian_omega_star,
    invariant_I1,
    leading_minors,
    max_E0,
    no_maximum_threshold,
    omega,
    omega_star,
    stability_verdict,
    uniaxial_voltage_limit_D0,
    uniaxial_voltage_limit_E0,
    uniaxial_voltage_limit_lam3,
    voltage_limit_D0,
    voltage_limit_E0,
)
from .homogeneous import (
    biaxial_E0,
    biaxial_stress,
    biaxial_stretches,
    equibiaxial_D0,
    equibiaxial_E0,
    equibiaxial_lam,
    equibiaxial_s,
    equibiaxial_s_E0,
    uniaxial_D0,
    uniaxial_E0,
    uniaxial_lam1,
    uniaxial_lam3,
)

__all__ = ["Model", "NeoHookean", "Gent", "UserModel", "as_model"]
__all__ += [  # homogeneous loading
    "biaxial_E0", "biaxial_stress", "biaxial_stretches",
    "equibiaxial_D0", "equibiaxial_E0", "equibiaxial_lam", "equibiaxial_s", "equibiaxial_s_E0",
    "uniaxial_D0", "uniaxial_E0", "uniaxial_lam1", "uniaxial_lam3",
    # energies, Hessians, verdicts, voltage limits
    "invariant_I1", "omega", "omega_star", "equibiaxial_omega", "equibiaxial_omega_star",
    "hessian_omega", "hessian_omega_star", "equibiaxial_hessian_omega",
    "equibiaxial_hessian_omega_star", "leading_minors", "stability_verdict",
    "equibiaxial_stability_verdict", "voltage_limit_D0", "voltage_limit_E0",
    "uniaxial_voltage_limit_lam3", "uniaxial_voltage_limit_D0", "uniaxial_voltage_limit_E0",
    "max_E0", "no_maximum_threshold",
]
__all__ += [  # Stroh formalism and wrinkling
    "electroelastic_moduli", "stroh_coefficients", "stroh_exponents", "stroh_matrix",
    "WrinklingMap", "critical_D0", "critical_D0_biaxial", "critical_point_on_path",
    "dispersion_function", "surface_impedance", "surface_instability_stretch",
    "thick_limit_D0", "thick_limit_D0_numeric", "thick_limit_D0_uniaxial",
    "thin_limit_D0", "thin_limit_D0_uniaxial", "thin_plate_factors", "wrinkling_map",
]
