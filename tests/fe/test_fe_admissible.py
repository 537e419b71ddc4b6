"""Admissible states of the 3D plate: Newton steps keep ``det F > 0`` and an inverted
equilibrium is never reported as converged."""

import warnings

import numpy as np
import pytest

import analytic
import skfem_dielectric as sd
from skfem_dielectric import NewtonSettings, RampSettings, newton, ramp
from skfem_dielectric.gallery import plate_admissible, preload_then_charge
from skfem_dielectric.kinematics import segment_det_limit

GENT = analytic.Gent(97.2)

# Gent plate, s = 1: large jumps of the charge target that a plain Newton solve answered
# with the inverted state F11 = F33 = -lam, F22 = lam^-2 (det F = 1, |F e1| = lam)
JUMPS = [(1.0, [2, 4, 500]), (1.0, [2, 4, 100]), (1.0, [2, 4, 200]), (1.0, [2, 4, 1000]),
         (1.0, [1, 1e4])]


@pytest.mark.parametrize("s, D0", JUMPS)
def test_large_charge_jumps_reach_the_closed_form_or_fail(s, D0):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = sd.equibiaxial_plate(s, D0, model="Gent")
    for st in res.steps:
        assert plate_admissible(res.problem, st.x, st.load) == ""
        if st.target_reached:
            lam = analytic.equibiaxial_lam(st.load[1], s=st.load[0], model=GENT)
            assert abs(st["lam1"] - lam) <= 1e-8 * lam
    if res.converged:
        assert res.steps[-1].load[1] == D0[-1]
    else:
        assert res.reason


def test_an_unguarded_ramp_finds_the_inverted_state_and_plate_admissible_names_it(
        monkeypatch):
    """The same plate with its guards taken away (a model without ``newton_guards``)
    reaches the inverted state F11 = F33 = -lam; the guarded Newton refuses it."""
    prob = sd.gallery.equibiaxial_problem(model="Gent")
    monkeypatch.setattr(prob, "newton_guards", lambda: {})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = ramp(prob, preload_then_charge(1.0, [2, 4, 500], 4),
                   settings=RampSettings(atol=0.0, rtol=1e-11))
    st = res.steps[-1]
    F = prob.evaluate(st.x, st.load, np.zeros((3, 1)))["F"][:, :, 0]
    assert F[0, 0] < 0 and F[2, 2] < 0 and abs(np.linalg.det(F) - 1) < 1e-9
    why = plate_admissible(prob, st.x, st.load)
    assert "inverted" in why and "F11" in why
    # the guarded ramp from the same state rejects it: a solve started on it is no success
    nr = newton(lambda xx: prob.assemble(xx, st.load), st.x,
                settings=NewtonSettings(atol=0.0, rtol=1e-11),
                scale=prob.residual_scale(st.load),
                admissible=lambda xx: plate_admissible(prob, xx, st.load))
    assert not nr.converged and "inverted" in nr.reason


def test_ramp_asks_the_problem_for_its_guards_and_cuts_a_step_into_inversion():
    """``ramp`` called with no guards uses the plate's own: on the jump that inverts the
    unguarded plate, the step limit cuts Newton steps that would turn an element inside
    out (``max_step < 1``), every kept state is admissible, and a reached target is the
    closed form's stretch (1e-8)."""
    prob = sd.gallery.equibiaxial_problem(model="Gent")
    limited = []
    own = prob.max_step

    def counted(x, dx, load):
        a = own(x, dx, load)
        limited.append(a < 1.0)
        return a

    prob.max_step = counted                      # the guard the problem hands to ramp
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = ramp(prob, preload_then_charge(1.0, [2, 4, 500], 4),
                   settings=RampSettings(atol=0.0, rtol=1e-11))
    assert any(limited) and len(limited) > 10
    for st in res.steps:
        assert plate_admissible(prob, st.x, st.load) == ""
        if st.target_reached:
            lam = analytic.equibiaxial_lam(st.load[1], s=st.load[0], model=GENT)
            assert abs(st["lam1"] - lam) <= 1e-8 * lam


def test_max_step_stops_before_det_F_reaches_zero():
    prob = sd.gallery.equibiaxial_problem()
    x = prob.initial_state()
    # a pure displacement increment that maps the plate to u = -2 X (F = -I at a = 1)
    full = np.zeros(prob.n_full)
    X = prob.b2.doflocs
    full[: prob.n_u] = (-2.0 * X).T.ravel()
    dx = prob.red.reduce(full)
    a = prob.max_step(x, dx, (0.0, 0.0))
    assert 0.0 < a <= 0.5 and a > 0.49     # det F = (1 - 2a)^3 > 0 for a < 1/2
    assert prob.max_step(x, 0.1 * dx, (0.0, 0.0)) == 1.0


def test_segment_det_limit_simple_double_and_touching_roots():
    I = np.eye(3)[None]
    assert segment_det_limit(I, 0.5 * I) == 1.0
    # F11 = 1 - 2a crosses zero alone at a = 1/2
    d = np.diag([-2.0, 0.0, 0.0])[None]
    assert abs(segment_det_limit(I, d) - 0.5) < 1e-8
    # F11 = F33 = 1 - a/0.4 touch zero together at a = 0.4: det F >= 0 on the segment,
    # but the body turns inside out there
    d = np.diag([-2.5, 0.0, -2.5])[None]
    assert abs(segment_det_limit(I, d) - 0.4) < 1e-4
    assert segment_det_limit(-I, d) == 0.0


def test_the_newton_guards_are_part_of_the_problem_contract():
    """A Problem has no guards by default; the plate's are its own methods, and the
    gallery's plate_admissible answers what the problem answers."""
    pb = sd.gallery.equibiaxial_problem(model="Gent")
    guards = pb.newton_guards()
    assert guards["step_limit"] == pb.max_step and guards["admissible"] == pb.admissible
    x = pb.initial_state()
    load = np.array([1.0, 0.0])
    assert pb.admissible(x, load) == "" == plate_admissible(pb, x, load)
    cs = sd.CrossSection(sd.section_mesh(4.0, 1.0, 2, 1), sd.NeoHookeanDielectric())
    assert cs.newton_guards() == {}
    assert not hasattr(sd.gallery, "newton_guards")
