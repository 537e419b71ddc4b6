"""The local homogeneous state of an FE plate and the paper's criteria evaluated on it.

On a homogeneous FE plate (dead-load equi-biaxial and free uni-axial, one element) the
local state *is* the homogeneous state of the closed forms: Q2 displacements represent it
exactly, so the stretches, the charge and the stresses read at any point agree with
Eqs. (loading_gent), (DEuniax) to the Newton tolerance, and so do the criteria evaluated
on them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import analytic as an
from skfem_dielectric import PlateProblem, RampSettings, ramp
from skfem_dielectric.fem.mesh import plate_mesh
from skfem_dielectric.gallery import keplinger_problem
from skfem_dielectric.materials import NeoHookeanDielectric
from validation.clamp_zone.local_theory import (energy_centroid, first_firing, half_waves,
                                             local_criteria, local_state)

#: the Newton tolerance of the ramps below (relative residual), and what it allows on the
#: state: the stretches and charge of an exact homogeneous state are met to ~1e-10
NEWTON_RTOL = 1e-11
STATE_TOL = 1e-8
#: a criterion is a smooth function of (lam1, lam3) with derivatives of order 10 here:
#: an error of STATE_TOL in the state is at most ~1e-7 in the criterion
CRITERION_TOL = 1e-7
POINT = [0.7, 0.2, 0.9]          # inside the eighth model, on no node


def _homogeneous(loading, s, D0):
    pb = PlateProblem(plate_mesh(4.0, 1.0, 4.0, 1, 1, 1), NeoHookeanDielectric(1.0, 1.0),
                      loading=loading)
    res = ramp(pb, [(s / 2, 0.0), (s, 0.0)] + [(s, d) for d in D0],
               settings=RampSettings(atol=0.0, rtol=NEWTON_RTOL))
    assert res.converged, res.reason
    return pb, res.steps[2:]


@pytest.mark.parametrize("loading, s", [("equibiaxial", 1.0), ("uniaxial-free", 2.0)])
def test_local_state_of_a_homogeneous_plate_is_the_closed_form(loading, s):
    pb, steps = _homogeneous(loading, s, [0.5, 1.5, 2.5])
    for st in steps:
        D0 = float(st.load[1])
        if loading == "equibiaxial":
            lam1 = lam3 = float(an.equibiaxial_lam(D0, s))
            sigma1, sigma3 = s * lam1, s * lam3       # Cauchy = nominal x stretch (J = 1)
        else:
            lam1 = float(an.uniaxial_lam1(D0, s))
            lam3 = float(an.uniaxial_lam3(lam1, s))
            sigma1, sigma3 = s * lam1, 0.0            # free x3 faces
        ls = local_state(pb, st.x, st.load, POINT)
        assert abs(ls.lam1 / lam1 - 1) < STATE_TOL
        assert abs(ls.lam3 / lam3 - 1) < STATE_TOL
        assert abs(ls.lam2 * lam1 * lam3 - 1) < STATE_TOL    # incompressible: J = 1
        assert abs(ls.D0 / D0 - 1) < STATE_TOL                # d lam1 lam3 = D0
        assert abs(ls.D_L / D0 - 1) < STATE_TOL
        assert abs(ls.sigma1 - sigma1) < STATE_TOL * max(1.0, sigma1)
        assert abs(ls.sigma3 - sigma3) < STATE_TOL * max(1.0, sigma1)
        c = local_criteria(ls, an.NeoHookean(), kh=np.array([0.5, 5.0]))
        # the homogeneous theory's in-plane stresses a - c are the same stresses
        assert abs(c.parallel.sigma - sigma1) < CRITERION_TOL * max(1.0, sigma1)
        assert abs(c.perpendicular.sigma - sigma3) < CRITERION_TOL * max(1.0, sigma1)
        for direction in ("parallel", "perpendicular"):
            dc = getattr(c, direction)
            thin = float(an.thin_limit_D0_uniaxial(lam1, lam3, direction=direction))
            thick = float(an.thick_limit_D0_uniaxial(lam1, lam3, direction=direction))
            anti = an.critical_D0_biaxial(lam1, lam3, np.array([0.5, 5.0]),
                                          direction=direction)
            assert abs(dc.thin / thin - 1) < CRITERION_TOL
            assert abs(dc.thick / thick - 1) < CRITERION_TOL
            np.testing.assert_allclose(dc.antisymmetric, anti, rtol=CRITERION_TOL)
            # thin < flexural D0_c(kh) < thick (the closed forms' ordering, docs/wrinkling.md)
            assert thin < dc.antisymmetric[0] < dc.antisymmetric[1] < thick
        if loading == "equibiaxial":   # Eqs. (antisym_thin), (ideal-shortwave)
            assert abs(c.parallel.thin / float(an.thin_limit_D0(lam1)) - 1) < CRITERION_TOL
            assert abs(c.parallel.thick / float(an.thick_limit_D0(lam1)) - 1) < CRITERION_TOL
        else:   # on the free uni-axial path the perpendicular thin limit is the path itself
            assert abs(c.perpendicular.thin / D0 - 1) < CRITERION_TOL


def test_energy_centroid_of_a_node_mode_is_the_node():
    """A mode moving one interior vertex of a uniform mesh in a homogeneous state: the
    elements around it are mirror images, so the centroid is the vertex (to roundoff)."""
    pb = PlateProblem(plate_mesh(4.0, 1.0, 4.0, 4, 1, 4), NeoHookeanDielectric(1.0, 1.0),
                      loading="equibiaxial")
    res = ramp(pb, [(0.5, 0.0), (1.0, 0.0), (1.0, 1.0)],
               settings=RampSettings(atol=0.0, rtol=NEWTON_RTOL))
    st = res.steps[-1]
    m = pb.plate.mesh
    v = int(np.argmin(np.linalg.norm(m.p - np.array([[1.0], [0.5], [1.0]]), axis=0)))
    w = np.zeros(pb.n_full)
    w[3 * v + 1] = 1.0
    c = energy_centroid(pb, st.x, st.load, w)
    np.testing.assert_allclose(c, [m.p[0, v], 0.0, m.p[2, v]], atol=1e-9)


@pytest.mark.parametrize("n", [3, 4, 7])
def test_half_waves_counts_a_sine_across_the_width(n):
    pb = keplinger_problem(elements=(2, 1, 10))
    L3 = pb.plate.L3
    m = pb.plate.mesh
    w = np.zeros(pb.n_full)
    nv = m.p.shape[1]
    w[3 * np.arange(nv) + 1] = np.sin(n * math.pi * (m.p[2] + L3 / 2) / L3)
    parity = "symmetric" if n % 2 else "antisymmetric"   # sin(n pi/2 + .) is even for odd n
    assert half_waves(pb, w, {1: "symmetric", 2: "antisymmetric", 3: parity}, 10.0) == n


def test_first_firing_interpolates_the_first_crossing():
    D0 = np.array([1.0, 2.0, 3.0, 4.0])
    assert first_firing(D0, [-1.0, -0.5, 0.5, 1.0]) == pytest.approx(2.5, abs=1e-15)
    assert first_firing(D0, [-1.0, np.nan, math.inf, 1.0]) == 3.0   # no value before it
    assert first_firing(D0, [0.2, 0.5, 0.5, 1.0]) == 1.0
    assert math.isnan(first_firing(D0, [-1.0, -1.0, np.nan, -0.1]))
    with pytest.raises(ValueError, match="margin"):
        first_firing(D0, [0.0, 1.0])


def test_local_state_rejects_a_bad_point():
    pb = keplinger_problem(elements=(2, 1, 1))
    with pytest.raises(ValueError, match="point"):
        local_state(pb, pb.initial_state(), (0.0, 0.0), [1.0, 0.0])
