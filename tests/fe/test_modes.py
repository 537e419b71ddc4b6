"""Mode classification of a plate: element energies, corner share, mesh-scale indicator,
VTU export and the unfolded top-face deflection."""

from __future__ import annotations

import meshio
import numpy as np
import pytest

import skfem_dielectric as fe
from skfem_dielectric.gallery.drivers import keplinger_problem
from skfem_dielectric.models.plate.modes import (classify_mode, corner_elements, element_energies,
                                                energy_share, lowest_physical, mesh_scale,
                                                top_deflection, write_mode_vtu)
from skfem_dielectric.models.plate.symmetry_classes import class_mode_full, class_stability


@pytest.fixture(scope="module")
def buckled():
    """The slender clamped plate past its Euler load (s = -0.4, D0 = 1), eighth model."""
    pb = keplinger_problem(size=(8.0, 1.0, 4.0), elements=(4, 1, 2), symmetry="eighth")
    tg = [np.array([-0.4, 1.0]) * t for t in np.linspace(0.25, 1.0, 4)]
    res = fe.ramp(pb, tg, x0=pb.initial_state(), start=np.zeros(2))
    assert res.converged
    cs = class_stability(pb, res.x, tg[-1], k=1)
    return pb, res.x, tg[-1], cs


def test_element_energies_add_up_to_the_eigenvalue(buckled):
    pb, x, load, cs = buckled
    xf = pb.full(x, load)
    for c, r in zip(cs.classes, cs.results):
        w = class_mode_full(c, r.modes[:, 0])
        e = element_energies(pb, xf, w)
        # sum_K e_K = w.K w = lambda (unit metric norm); central differences O(h^2) with
        # h = 1e-6 relative, against the eigensolver's value
        assert e.sum() == pytest.approx(r.eigenvalues[0], rel=1e-6, abs=1e-9), c.name
        assert energy_share(e, np.ones(e.size, bool)) == pytest.approx(1.0, rel=1e-14)


def test_mesh_scale_of_known_waves():
    pb = keplinger_problem(size=(8.0, 1.0, 4.0), elements=(8, 1, 2), symmetry="eighth")
    X = pb.b2.doflocs
    h1 = 4.0 / 8
    # one half-wave per element: the Q2 interpolant of cos(pi x/h) through its nodes
    # (1, 0, -1) is the linear 1 - 2x/h per element, whose indicator is sqrt(12)/pi
    # exactly; four elements per half-wave: h/l = 0.25 for the continuous wave, and the
    # interpolant is within 1 % of it
    for ell, expected, rel in ((h1, np.sqrt(12) / np.pi, 1e-10), (4 * h1, 0.25, 1e-2)):
        w = np.zeros(pb.n_full)
        w[1:pb.n_u:3] = np.cos(np.pi * X[0] / ell)
        assert mesh_scale(pb, w) == pytest.approx(expected, rel=rel)


def test_corner_share_and_classification(buckled):
    pb, x, load, cs = buckled
    mask = corner_elements(pb)
    c = pb.plate.mesh.p[:, pb.plate.mesh.t].mean(axis=1)
    d = np.hypot(4.0 - c[0], 2.0 - c[2])
    assert np.array_equal(mask, d <= 2.0)
    xf = pb.full(x, load)
    v, name, j = cs.lowest(1)[0]
    ci = [k.name for k in cs.classes].index(name)
    w = class_mode_full(cs.classes[ci], cs.results[ci].modes[:, j])
    lab = classify_mode(pb, xf, w, symmetry=name)
    # the lowest mode is the plate's bending (Euler) mode, resolved and spread over its
    # length: not a corner or mesh-scale mode
    assert lab["kind"] == "physical" and lab["symmetry"] == name
    assert lab["corner_share"] == pytest.approx(
        energy_share(element_energies(pb, xf, w), mask), rel=1e-12)


def test_mode_vtu_and_unfolded_deflection(buckled, tmp_path):
    pb, x, load, cs = buckled
    v, name, j = cs.lowest(1)[0]
    ci = [k.name for k in cs.classes].index(name)
    c = cs.classes[ci]
    w = class_mode_full(c, cs.results[ci].modes[:, j])
    path = write_mode_vtu(tmp_path / "mode.vtu", pb, x, load, w)
    m = meshio.read(path)
    nv = pb.plate.mesh.p.shape[1]
    np.testing.assert_array_equal(m.point_data["mode_displacement"],
                                  w[: pb.n_u].reshape(-1, 3)[:nv])
    X1, X3, u2 = top_deflection(pb, w, c.increments)
    # unfolded by the class's parities: u2(-x1, x3) = +-u2(x1, x3), exactly
    s1 = 1.0 if c.increments[1] == "symmetric" else -1.0
    for i in np.flatnonzero(X1 > 0)[:5]:
        k = np.flatnonzero((np.abs(X1 + X1[i]) < 1e-12) & (np.abs(X3 - X3[i]) < 1e-12))
        assert u2[k[0]] == s1 * u2[i]
    with pytest.raises(ValueError, match="path must end in .vtu"):
        write_mode_vtu(tmp_path / "mode.txt", pb, x, load, w)
    with pytest.raises(ValueError, match="w_full must be a full dof vector"):
        mesh_scale(pb, w[:10])


def test_critical_end_load_of_the_clamped_plate(buckled):
    """The lowest physical eigenvalue along the end compression s (D0 = 1) crosses zero at
    the plate's first buckling load; critical_load finds it to 1e-4 in s, and it is the
    load where the classes' count first turns positive."""
    pb = buckled[0]
    res = fe.ramp(pb, [np.array([-0.02, 1.0])], x0=pb.initial_state(), start=np.zeros(2))

    def eig(x, load):
        return lowest_physical(pb, x, load).eigenvalue

    out = fe.critical_load(pb, res.x, np.array([-0.02, 1.0]), np.array([-0.4, 1.0]), eig,
                           tol=1e-4)
    s_c = out.load[0]
    lo, hi = [np.array([s, 1.0]) for s in (s_c + 2e-4, s_c - 2e-4)]
    counts = []
    for ld in (lo, hi):
        r = fe.ramp(pb, [ld], x0=res.x, start=np.array([-0.02, 1.0]))
        counts.append(class_stability(pb, r.x, ld, k=0).n_negative)
    # stable 2e-4 before the located load (twice the tolerance), one negative eigenvalue
    # 2e-4 after it
    assert counts == [0, 1]
