"""The return convention of analytic: scalar numbers in -> Python scalars out, arrays in
-> ndarrays of the broadcast shape (followed by the matrix axes of matrix results)."""

import numpy as np
import pytest

import analytic as an
from analytic import units

A = np.array([[1.2], [1.5], [2.0]])  # shape (3, 1)
B = np.array([[1.0, 1.1]])  # shape (1, 2)
AB = (3, 2)

F, C, BOOL = float, complex, bool
# name: (scalar arguments, array arguments, broadcast shape, kind of each result,
#        trailing (matrix) axes of each result)
POINTWISE = {
    "biaxial_E0": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F,), ((),)),
    "biaxial_stress": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F, F), ((), ())),
    "biaxial_stretches": ((1.0, 0.3, 2.0), (A, B, 2.0), AB, (F, F), ((), ())),
    "equibiaxial_D0": ((1.5, 0.5), (A, B), AB, (F,), ((),)),
    "equibiaxial_E0": ((1.5, 0.5), (A, B), AB, (F,), ((),)),
    "equibiaxial_lam": ((2.0, 0.5), (A, B), AB, (F,), ((),)),
    "equibiaxial_s": ((1.5, 0.5), (A, B), AB, (F,), ((),)),
    "equibiaxial_s_E0": ((1.5, 0.5), (A, B), AB, (F,), ((),)),
    "uniaxial_D0": ((2.0, 1.0), (A + 1.0, B), AB, (F,), ((),)),
    "uniaxial_E0": ((2.0, 1.0), (A + 1.0, B), AB, (F,), ((),)),
    "uniaxial_lam1": ((2.0, 1.0), (A, B), AB, (F,), ((),)),
    "uniaxial_lam3": ((2.0, 1.0), (A + 1.0, B), AB, (F,), ((),)),
    "invariant_I1": ((1.2, 1.1), (A, B), AB, (F,), ((),)),
    "omega": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F,), ((),)),
    "omega_star": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F,), ((),)),
    "equibiaxial_omega": ((1.2, 0.5), (A, B), AB, (F,), ((),)),
    "equibiaxial_omega_star": ((1.2, 0.5), (A, B), AB, (F,), ((),)),
    "hessian_omega": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F,), ((3, 3),)),
    "hessian_omega_star": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F,), ((3, 3),)),
    "equibiaxial_hessian_omega": ((1.2, 0.5), (A, B), AB, (F,), ((2, 2),)),
    "equibiaxial_hessian_omega_star": ((1.2, 0.5), (A, B), AB, (F,), ((2, 2),)),
    "stability_verdict": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (BOOL,), ((),)),
    "equibiaxial_stability_verdict": ((1.5, 3.0), (A, B), AB, (BOOL,), ((),)),
    "voltage_limit_D0": ((1.2,), (A,), (3, 1), (F,), ((),)),
    "voltage_limit_E0": ((1.2,), (A,), (3, 1), (F,), ((),)),
    "uniaxial_voltage_limit_D0": ((1.2,), (A,), (3, 1), (F,), ((),)),
    "uniaxial_voltage_limit_E0": ((1.2,), (A,), (3, 1), (F,), ((),)),
    "uniaxial_voltage_limit_lam3": ((1.2,), (A,), (3, 1), (F,), ((),)),
    "max_E0": ((1.0,), (A,), (3, 1), (F, F), ((), ())),
    "electroelastic_moduli": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F, F, F, F),
                              ((3, 3, 3, 3), (3, 3, 3), (3, 3), ())),
    "stroh_coefficients": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F, F, F, F), ((),) * 4),
    "stroh_exponents": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (C, C, C), ((),) * 3),
    "stroh_matrix": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (C,), ((6, 6),)),
    "surface_impedance": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (C,), ((3, 3),)),
    "thin_plate_factors": ((1.2, 1.1, 0.5), (A, B, 0.5), AB, (F, F, F), ((),) * 3),
    "thin_limit_D0": ((1.2,), (A,), (3, 1), (F,), ((),)),
    "thin_limit_D0_uniaxial": ((1.5, 0.9), (A, B), AB, (F,), ((),)),
    "thick_limit_D0": ((1.2,), (A,), (3, 1), (F,), ((),)),
    "thick_limit_D0_uniaxial": ((1.5, 0.9), (A, B), AB, (F,), ((),)),
    "thick_limit_D0_numeric": ((1.5, 0.9), (A, B), AB, (F,), ((),)),
    "critical_D0": ((1.5, 1.0), (A, B), AB, (F,), ((),)),
    "critical_D0_biaxial": ((1.5, 1.1, 1.0), (A, 1.1, B), AB, (F,), ((),)),
    "dispersion_function": ((1.3, 1.3, 2.5, 2.0), (A, 1.1, 2.0, B), AB, (F,), ((),)),
}
# public names that are not functions of numbers broadcast point by point
CLASSES = {"Model", "NeoHookean", "Gent", "UserModel", "as_model", "WrinklingMap"}
OTHER = {"leading_minors", "critical_point_on_path", "wrinkling_map", "no_maximum_threshold",
         "surface_instability_stretch"}
KIND = {F: "f", C: "c", BOOL: "b"}


def _results(out, kinds):
    return out if len(kinds) > 1 else (out,)


def test_every_public_name_is_classified():
    assert set(an.__all__) == set(POINTWISE) | CLASSES | OTHER


@pytest.mark.parametrize("name", sorted(POINTWISE))
def test_scalar_numbers_give_python_scalars(name):
    args, _, _, kinds, trailing = POINTWISE[name]
    out = getattr(an, name)(*args)
    if len(kinds) > 1:
        assert type(out) is tuple and len(out) == len(kinds)
    for r, kind, tr in zip(_results(out, kinds), kinds, trailing):
        if tr:
            assert type(r) is np.ndarray and r.shape == tr and r.dtype.kind == KIND[kind]
        else:
            assert type(r) is kind, (name, type(r))


@pytest.mark.parametrize("name", sorted(POINTWISE))
def test_arrays_give_arrays_of_the_broadcast_shape(name):
    _, args, shape, kinds, trailing = POINTWISE[name]
    out = getattr(an, name)(*args)
    for r, kind, tr in zip(_results(out, kinds), kinds, trailing):
        assert type(r) is np.ndarray and r.shape == shape + tr and r.dtype.kind == KIND[kind], name


def test_other_public_functions():
    H = an.hessian_omega_star(A, B, 0.5)
    assert an.leading_minors(H).shape == AB + (3,)
    assert type(an.no_maximum_threshold(an.Gent(97.2))) is float
    assert type(an.surface_instability_stretch()) is float
    lam = np.linspace(1.0, 1.6, 31)
    lc, Dc = an.critical_point_on_path(lam, 1.02 * np.sqrt(lam**6 - 1), 0.05)
    assert type(lc) is float and type(Dc) is float
    m = an.wrinkling_map(lam)
    assert all(type(v) is np.ndarray and v.shape == lam.shape for v in (m.thin, m.thick, m.lower, m.upper))


@pytest.mark.parametrize("fun, args", [
    (units.D0_from_SI, (3.0, 4.0, 9.0)), (units.D0_to_SI, (0.5, 4.0, 9.0)),
    (units.E0_from_SI, (2.0, 4.0, 9.0)), (units.E0_to_SI, (3.0, 4.0, 9.0)),
    (units.s_from_SI, (2.0, 4.0)), (units.s_to_SI, (2.0, 4.0)),
    (units.charge_to_D0, (6.0, 2.0, 1.0, 9.0)), (units.D0_to_charge, (1.0, 2.0, 1.0, 9.0)),
    (units.voltage_to_E0, (4.0, 2.0, 4.0, 9.0)), (units.E0_to_voltage, (3.0, 2.0, 4.0, 9.0)),
    (units.dead_load_s, (1.0, 10.0, 2.0, 5.0)),
])
def test_units_follow_the_convention(fun, args):
    assert type(fun(*args)) is float
    out = fun(A, *args[1:])
    assert type(out) is np.ndarray and out.shape == A.shape
    assert type(units.keplinger_s(1.0, g=9.81)) is float
    assert units.keplinger_s(A, g=9.81).shape == A.shape
