"""Generated bad inputs through the public API of ``analytic`` and ``skfem_dielectric``.

Every case must end in a ``ValueError`` whose message names the parameter, or (the last
group) in the documented result ``nan`` where a loading branch has no state.  The cases
are the product of call sites and bad values of the kind the site takes (wrong types,
nan, +-inf, negative, zero, huge, strings, wrong shapes, bad callables), plus seeded
random ones (huge magnitudes, random strings, random lengths).
"""

import math
from dataclasses import replace
import warnings

import numpy as np
import pytest

import analytic as an
import skfem_dielectric as sd

RNG = np.random.default_rng(20261201)
NAN, INF = math.nan, math.inf

NOT_A_NUMBER = ["x", None, "1.5", [1.0, "a"], {"a": 1}, 1j]
POSITIVE = [NAN, INF, -INF, -1.0, 0.0] + NOT_A_NUMBER
FINITE = [NAN, INF, -INF] + NOT_A_NUMBER
COUNT = [0, -4, 2.5, NAN, INF, "3", None, True]
NONNEG_INT = [-1, 1.5, NAN, INF, "2", None]
TOL = [-1e-3, NAN, INF, "1e-9", None]
CALLABLE = [42, "f", 1.5, [print]]
CHOICE = ["x", "", 3, None, "Gent!"]
HUGE = [float(10.0 ** RNG.uniform(155, 307)) for _ in range(3)]   # squares overflow
TINY = [float(10.0 ** -RNG.uniform(62, 307)) for _ in range(2)]
WORDS = ["".join(RNG.choice(list("abcxyz_-/."), size=int(RNG.integers(1, 8)))) for _ in range(3)]

GENT = an.Gent(97.2)
PB = sd.gallery.equibiaxial_problem()
LOAD = (0.5, 1.0)
NX = len(PB.initial_state())


def _ok_W(I):
    return 0.5 * (I - 3.0)


def _ok_dW(I):
    return 0.5 + 0.0 * I


def _ok_d2W(I):
    return 0.0 * I


def _assemble(x):
    return PB.assemble(x, LOAD)


def _cases():
    """``(label, thunk, name)``: the call with one bad argument and the parameter name."""
    out = []

    def add(label, name, values, call):
        for v in values:
            out.append((f"{label}:{name}={v!r}", (lambda v=v: call(v)), name))

    # ---- analytic: stretches, loads, models, choices, shapes, overflow
    add("equibiaxial_D0", "lam", POSITIVE + HUGE, lambda v: an.equibiaxial_D0(v, 0.5))
    add("equibiaxial_D0", "s", FINITE, lambda v: an.equibiaxial_D0(2.0, v))
    add("equibiaxial_D0", "model", ["x", "Gent", 3, 1.0, GENT.dW],
        lambda v: an.equibiaxial_D0(2.0, 0.5, v))
    add("equibiaxial_lam", "D0", FINITE + HUGE, lambda v: an.equibiaxial_lam(v, 0.5))
    add("equibiaxial_lam", "s", FINITE + [-1e300], lambda v: an.equibiaxial_lam(2.0, v))
    add("equibiaxial_lam(Gent)", "D0", FINITE, lambda v: an.equibiaxial_lam(v, 1.0, GENT))
    add("equibiaxial_E0", "lam", POSITIVE, lambda v: an.equibiaxial_E0(v))
    add("equibiaxial_s", "D0", FINITE, lambda v: an.equibiaxial_s(1.5, v))
    add("uniaxial_lam1", "D0", FINITE + HUGE, lambda v: an.uniaxial_lam1(v, 1.0))
    add("uniaxial_lam1", "s", FINITE, lambda v: an.uniaxial_lam1(1.0, v))
    add("uniaxial_lam3", "lam1", POSITIVE, lambda v: an.uniaxial_lam3(v, 1.0))
    add("uniaxial_D0", "lam1", POSITIVE + HUGE, lambda v: an.uniaxial_D0(v, 1.0))
    add("biaxial_stress", "lam3", POSITIVE, lambda v: an.biaxial_stress(1.2, v, 0.5))
    add("biaxial_stress", "D0", FINITE, lambda v: an.biaxial_stress(1.2, 1.1, v))
    add("biaxial_stretches", "s1", FINITE, lambda v: an.biaxial_stretches(v, 0.0, 1.0))
    add("voltage_limit_D0", "lam", POSITIVE + HUGE + TINY, lambda v: an.voltage_limit_D0(v))
    add("stability_verdict", "control", CHOICE,
        lambda v: an.stability_verdict(1.2, 1.2, 0.5, control=v))
    add("hessian_omega_star", "lam1", POSITIVE, lambda v: an.hessian_omega_star(v, 1.2, 0.5))
    add("omega", "E0", FINITE, lambda v: an.omega(1.2, 1.2, v))
    add("stroh_matrix", "direction", CHOICE,
        lambda v: an.stroh_matrix(1.2, 1.2, 0.5, direction=v))
    add("stroh_exponents", "D0", FINITE, lambda v: an.stroh_exponents(1.2, 1.2, v))
    add("critical_D0", "lam", POSITIVE + [1e6], lambda v: an.critical_D0(v, 2.0))
    add("critical_D0", "mode", CHOICE, lambda v: an.critical_D0(1.5, 2.0, mode=v))
    add("thin_limit_D0", "lam", POSITIVE, lambda v: an.thin_limit_D0(v))
    add("Gent", "Jm", POSITIVE, lambda v: an.Gent(v))
    add("max_E0", "loading", CHOICE, lambda v: an.max_E0(0.5, loading=v))
    for n in (int(RNG.integers(4, 6)), int(RNG.integers(6, 9))):   # incompatible shapes
        out.append((f"shapes lam(3,) s({n},)",
                    lambda n=n: an.equibiaxial_D0([1.1, 1.2, 1.3], np.zeros(n)), "lam"))
        out.append((f"shapes lam1(2,) lam3({n},)",
                    lambda n=n: an.biaxial_stress([1.1, 1.2], np.ones(n), 0.0), "lam3"))
    for which in ("W", "dW", "d2W"):   # user models
        kw = {"W": _ok_W, "dW": _ok_dW, "d2W": _ok_d2W}
        for bad in CALLABLE + [lambda I: np.nan * I, lambda I: None,
                               lambda I: np.full(2, 0.5), lambda I: np.inf + 0 * I]:
            out.append((f"UserModel:{which}={bad!r}",
                        lambda kw=kw, which=which, bad=bad: an.UserModel(**{**kw, which: bad}),
                        which))
            out.append((f"IdealDielectric:{which}={bad!r}",
                        lambda kw=kw, which=which, bad=bad:
                        sd.IdealDielectric(**{**kw, which: bad}), which))
    add("UserModel", "dW", [lambda I: 1.0 + 0 * I],
        lambda v: an.UserModel(_ok_W, v, _ok_d2W))

    # ---- skfem_dielectric: meshes, models, builders
    for i, name in enumerate(("L1", "H", "L3")):
        add("plate_mesh", name, POSITIVE,
            lambda v, i=i: sd.plate_mesh(*[v if j == i else 1.0 for j in range(3)], 1, 1, 1))
    for i, name in enumerate(("n1", "n2", "n3")):
        add("plate_mesh", name, COUNT,
            lambda v, i=i: sd.plate_mesh(1.0, 1.0, 1.0, *[v if j == i else 1 for j in range(3)]))
    add("plate_mesh", "symmetry", CHOICE + [(4,), (True,)],
        lambda v: sd.plate_mesh(1.0, 1.0, 1.0, 1, 1, 1, symmetry=v))
    add("plate_mesh", "grading", POSITIVE, lambda v: sd.plate_mesh(1.0, 1.0, 1.0, 1, 1, 1, grading=v))
    pm = PB.plate
    for name, values in (("intorder", COUNT), ("chunk", COUNT), ("threads", [0, -4, 1.5, "2"]),
                         ("loading", CHOICE), ("control", CHOICE), ("coupling", CHOICE),
                         ("field", CHOICE), ("formulation", CHOICE), ("phi_element", CHOICE),
                         ("kappa", [-1.0, 0.0, NAN, "x", None])):
        add("PlateProblem", name, values,
            lambda v, name=name: sd.PlateProblem(pm, PB.material, **{name: v}))
    add("PlateProblem", "material", ["rubber", 3, None], lambda v: sd.PlateProblem(pm, v))
    mm, sm = sd.membrane_mesh(100.0, 1.0, 50.0, 1, 1), sd.section_mesh(20.0, 1.0, 1, 1)
    add("MembranePlate", "material", ["rubber", 1.0] + WORDS[:1],
        lambda v: sd.MembranePlate(mm, v))
    add("CrossSection", "material", ["x", None], lambda v: sd.CrossSection(sm, v))
    mat = sd.NeoHookeanDielectric(1.0, 1.0)
    for label, mesh, model in (("PlateProblem", pm, sd.PlateProblem),
                               ("MembranePlate", mm, sd.MembranePlate),
                               ("CrossSection", sm, sd.CrossSection)):
        add(label, "mesh", [mesh.mesh, None, "x"] + [m for m in (pm, mm, sm) if m is not mesh],
            lambda v, model=model: model(v, mat))
    add("membrane_mesh", "n1", COUNT, lambda v: sd.membrane_mesh(100.0, 1.0, 50.0, v, 1))
    add("section_mesh", "L1", POSITIVE, lambda v: sd.section_mesh(v, 1.0, 1, 1))
    add("section_mesh", "thickness", CHOICE, lambda v: sd.section_mesh(20.0, 1.0, 1, 1, v))
    add("NeoHookeanDielectric", "mu", POSITIVE, lambda v: sd.NeoHookeanDielectric(v, 1.0))
    add("GentDielectric", "Jm", POSITIVE, lambda v: sd.GentDielectric(1.0, 1.0, v))
    add("make_material", "model", CHOICE + WORDS, lambda v: sd.make_material(v))
    add("equibiaxial_problem", "size", [(1.0, 2.0), "abc", 3.0, (1.0, -1.0, 1.0)],
        lambda v: sd.gallery.equibiaxial_problem(size=v))
    add("equibiaxial_problem", "elements", [(1, 1), (1, 0, 1), (1, INF, 1)],
        lambda v: sd.gallery.equibiaxial_problem(elements=v))
    add("keplinger_s", "alpha", [NAN, INF, -0.5, "x", None], lambda v: sd.keplinger_s(v, g=9.81))
    add("keplinger_s", "g", POSITIVE, lambda v: sd.keplinger_s(1.0, g=v))
    add("preload_then_charge", "preload_steps", COUNT,
        lambda v: sd.gallery.preload_then_charge(1.0, [1.0], v))
    add("charge_targets", "D0", [[NAN], [INF], [], "x", [[1.0, 2.0]]],
        lambda v: sd.gallery.charge_targets(v))
    add("equibiaxial_plate", "s", FINITE, lambda v: sd.equibiaxial_plate(v, [1.0]))
    add("equibiaxial_plate", "settings", CHOICE + [sd.NewtonSettings()],
        lambda v: sd.equibiaxial_plate(1.0, [1.0], settings=v))
    add("EQUIBIAXIAL_SETTINGS", "rtol", TOL,
        lambda v: replace(sd.gallery.EQUIBIAXIAL_SETTINGS, rtol=v))

    # ---- skfem_dielectric: Newton, ramp, solvers, export
    targets = [np.array([0.5, 0.0])]
    for name, values in (("max_cutbacks", NONNEG_INT), ("atol", TOL), ("rtol", TOL),
                         ("xtol", TOL), ("max_iter", COUNT), ("max_backtracks", NONNEG_INT),
                         ("chord", [-0.1, 1.0, NAN, INF, "0.1", None]),
                         ("line_search", [None, "yes", 1]), ("predictor", CHOICE),
                         ("stop_on_instability", [None, "no", 0])):
        add("RampSettings", name, values, lambda v, name=name: sd.RampSettings(**{name: v}))
    for name, values in (("settings", CHOICE + [sd.NewtonSettings()]), ("on_step", CALLABLE),
                         ("step_limit", CALLABLE), ("admissible", CALLABLE),
                         ("linear_solver", CHOICE + [1.5]),
                         ("x0", [np.zeros(3), np.zeros(NX + int(RNG.integers(1, 9))), "abc",
                                 np.full(NX, NAN), np.zeros((NX, 2))])):
        add("ramp", name, values, lambda v, name=name: sd.ramp(PB, targets, **{name: v}))
    add("ramp", "loads", [[NAN], [[INF, 0.0]], ["x"], 5.0, [np.zeros((2, 2))]],
        lambda v: sd.ramp(PB, v))
    out.append(("RampSettings atol=rtol=0", lambda: sd.RampSettings(atol=0.0, rtol=0.0),
                "rtol"))
    for name, values in (("atol", TOL), ("rtol", TOL), ("xtol", TOL), ("max_iter", COUNT),
                         ("max_backtracks", NONNEG_INT)):
        add("NewtonSettings", name, values,
            lambda v, name=name: sd.NewtonSettings(**{name: v}))
    for name, values in (("settings", CHOICE + [sd.RampResult(steps=[], converged=True)]),
                         ("scale", TOL[:3]), ("residual", CALLABLE), ("step_limit", CALLABLE),
                         ("admissible", CALLABLE)):
        add("newton", name, values,
            lambda v, name=name: sd.newton(_assemble, PB.initial_state(), **{name: v}))
    add("newton", "x0", ["abc", np.zeros((2, 2)), np.full(3, INF)],
        lambda v: sd.newton(_assemble, v))
    add("newton", "assemble", CALLABLE, lambda v: sd.newton(v, PB.initial_state()))
    add("get_linear_solver", "linear_solver", CHOICE + [2.0],
        lambda v: sd.get_linear_solver(v))
    res = sd.RampResult(steps=[], converged=True, problem=PB)
    add("write_vtu_series", "prefix", ["../../..", "a/b", "..", "", "a\\b", 3, None] +
        [w + "/" + w for w in WORDS[:2]],
        lambda v: sd.write_vtu_series(res, "/nonexistent-dir-not-created", prefix=v))
    return out


CASES = _cases()


def test_enough_cases():
    assert len(CASES) >= 200


def test_every_bad_input_is_a_value_error_naming_the_parameter():
    bad = []
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)   # no silent overflow either
        for label, thunk, name in CASES:
            try:
                result = thunk()
            except ValueError as exc:
                if name not in str(exc):
                    bad.append(f"{label}: message does not name {name!r}: {exc}")
            except Exception as exc:  # noqa: BLE001 - the point of the test
                bad.append(f"{label}: {type(exc).__name__}: {exc}")
            else:
                bad.append(f"{label}: no error, returned {result!r}")
    assert not bad, f"{len(bad)} of {len(CASES)} cases:\n" + "\n".join(bad[:40])


@pytest.mark.parametrize("call", [
    lambda: an.equibiaxial_D0(0.9),               # below the unloaded stretch: D0^2 < 0
    lambda: an.equibiaxial_D0(1.2, 5.0),          # below the mechanical stretch of s
    lambda: an.uniaxial_lam3(0.5, 1.0),           # lam1 below the dead-load stretch
    lambda: an.uniaxial_D0(1.2, 3.0),
    lambda: an.equibiaxial_E0(0.95, 0.0, GENT),
])
def test_no_state_is_nan(call):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        assert math.isnan(call())
