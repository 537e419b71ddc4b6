"""Symmetry classes of a plate's increments: the full plate's spectrum from a reduced model."""

from __future__ import annotations

import numpy as np
import pytest

import analytic as an
import skfem_dielectric as fe
from skfem_dielectric.gallery.drivers import equibiaxial_problem, keplinger_problem
from skfem_dielectric.models.plate.problem import plate_reduction
from skfem_dielectric.models.plate.symmetry_classes import class_stability

SIZE = (8.0, 1.0, 4.0)
# the same plate on mirror-image meshes: eighth (x1, x2, x3 planes), half (x2) and full
MODELS = {"eighth": (2, 1, 2), "half": (4, 1, 4), "full": (4, 2, 4)}


def _state(pb, load):
    tg = [np.asarray(load) * t for t in np.linspace(0.25, 1.0, 4)]
    res = fe.ramp(pb, tg, x0=pb.initial_state(), start=np.zeros(2))
    assert res.converged
    return res.x, tg[-1]


@pytest.fixture(scope="module")
def clamped_spectra():
    """A slender clamped plate under end compression s = -0.4 and charge D0 = 1 (past its
    Euler load: four unstable modes, all bending), on the three meshes."""
    out = {}
    for sym, el in MODELS.items():
        pb = keplinger_problem(size=SIZE, elements=el, symmetry=sym)
        x, load = _state(pb, (-0.4, 1.0))
        out[sym] = (pb, x, load, class_stability(pb, x, load, k=4, method="dense"))
    return out


def test_class_counts_add_up_to_the_full_plate(clamped_spectra):
    full = clamped_spectra["full"][3]
    assert [r.n_negative for r in full.results] == [4]
    for sym in ("eighth", "half"):
        cs = clamped_spectra[sym][3]
        assert cs.n_negative == full.n_negative, sym
        # the reduced model's own (mirror-symmetric) class cannot bend: stable
        assert cs.results[0].n_negative == 0
    # every unstable mode bends: antisymmetric in x2
    for c, r in zip(clamped_spectra["eighth"][3].classes, clamped_spectra["eighth"][3].results):
        if r.n_negative:
            assert c.increments[2] == "antisymmetric", c.name


def test_class_spectra_are_the_full_plates(clamped_spectra):
    ref = np.array([v for v, _, _ in clamped_spectra["full"][3].lowest(4)])
    for sym in ("eighth", "half"):
        got = np.array([v for v, _, _ in clamped_spectra[sym][3].lowest(4)])
        # the same discrete operator split into blocks, in a metric that restricts the
        # full plate's: equal to the eigensolver's accuracy (dense, 1e-12 relative) times
        # the conditioning of the saddle-point solves
        np.testing.assert_allclose(got, ref, rtol=1e-8)


def test_voltage_control_counts_add_up():
    """Voltage control (phi prescribed on the faces): the classes of the eighth model
    against the full plate's own count (dense eigenvalues)."""
    counts = {}
    for sym in ("eighth", "full"):
        pb = keplinger_problem(size=SIZE, elements=MODELS[sym], symmetry=sym,
                               options=fe.PlateOptions(control="voltage"))
        x, load = _state(pb, (-0.4, 0.2))
        counts[sym] = class_stability(pb, x, load, k=0, method="dense").n_negative
    assert counts["eighth"] == counts["full"] > 0


def test_free_plate_pins_the_class_translations():
    """An equi-biaxially compressed free plate (s = -0.3, D0 = 0.5): the antisymmetric
    classes admit rigid translations, which are pinned (no zero pivot), and the eighth
    model's classes give the quarter model's (planes x1, x3) spectrum."""
    spectra = {}
    for sym, el in (("eighth", (2, 1, 2)), ("quarter", (2, 2, 2))):
        pb = equibiaxial_problem(size=SIZE, elements=el, symmetry=sym)
        x, load = _state(pb, (-0.3, 0.5))
        cs = class_stability(pb, x, load, k=3, method="dense")
        assert cs.n_zero == 0, sym
        spectra[sym] = cs
    assert spectra["eighth"].n_negative == spectra["quarter"].n_negative > 0
    np.testing.assert_allclose([v for v, _, _ in spectra["eighth"].lowest(3)],
                               [v for v, _, _ in spectra["quarter"].lowest(3)], rtol=1e-8)


def test_bad_classes_and_couplings():
    pb = keplinger_problem(size=SIZE, elements=MODELS["eighth"], symmetry="eighth")
    with pytest.raises(ValueError, match="increments must map every symmetry axis"):
        plate_reduction(pb, {1: "antisymmetric"})
    with pytest.raises(ValueError, match="increments must map"):
        plate_reduction(pb, {1: "anti", 2: "symmetric", 3: "symmetric"})
    mx = keplinger_problem(size=SIZE, elements=MODELS["eighth"], symmetry="eighth",
                           options=fe.PlateOptions(coupling="maxwell"))
    with pytest.raises(ValueError, match="Maxwell coupling"):
        class_stability(mx, mx.initial_state(), (0.0, 0.0))
    with pytest.raises(ValueError, match="x must have shape"):
        class_stability(pb, np.zeros(3), (0.0, 0.0))


@pytest.mark.parametrize("model, s", [("neo-Hookean", 1.0), ("Gent", 2.3)])
def test_homogeneous_equibiaxial_plate_never_buckles_under_charge(model, s):
    """The paper's claim for charge control: a loading curve with a dead load s > 0 does
    not reach the wrinkling (Stroh) threshold -- so no symmetry class of a thin plate
    (20 x 1 x 20, bending and sway included) has a negative eigenvalue along it (the
    stabilised tangent of the homogeneous state, as in the harness)."""
    mdl = an.NeoHookean() if model == "neo-Hookean" else an.Gent(Jm=97.2)
    D0 = np.array([2.0, 4.0, 6.0])
    pb = equibiaxial_problem(model=model, size=(20.0, 1.0, 20.0), elements=(4, 1, 4))
    tg = [np.array([s, 0.0])] + [np.array([s, d]) for d in D0]
    res = fe.ramp(pb, tg, x0=pb.initial_state(), start=np.zeros(2))
    assert res.converged
    lam = []
    for step in res.steps[1:]:
        cs = class_stability(pb, step.x, step.load, k=0, grad_div=10.0)
        assert cs.n_negative == 0 and cs.n_zero == 0, (model, s, step.load)
        lam.append(step.quantities["lam1"])
    # the analytic side agrees: the path (lam, D0) stays below the critical D0 of every
    # wavenumber (thin- and thick-plate limits of the Stroh analysis)
    assert np.all(D0 < an.thin_limit_D0(np.array(lam), mdl))
    assert np.all(D0 < an.thick_limit_D0(np.array(lam), mdl))


def test_the_class_tangent_is_the_galerkin_product():
    """``class_tangent`` (a submatrix where the prolongation selects) equals the products
    ``P^T K P`` of the union tangent, entry by entry and with the same stored diagonal,
    for every class of a charged eighth plate."""
    import importlib

    import scipy.sparse as sp

    import skfem_dielectric as fe

    sc = importlib.import_module("skfem_dielectric.models.plate.symmetry_classes")
    pb = fe.gallery.keplinger_problem(elements=(3, 1, 2), symmetry="eighth", grading=0.5,
                                      options=fe.PlateOptions(grad_div=10.0))
    x = pb.initial_state()
    load = np.array([1.0, 0.5])
    classes, K = sc.union_tangent(pb, x, load, 10.0)
    selected = 0
    for c in classes:
        got = sc.class_tangent(c, K)
        want = sc._with_diagonal((c.P.T @ K @ c.P).tocoo())
        selected += sc._selection(c.P) is not None
        assert got.shape == want.shape
        assert abs(got - want).max() <= 1e-14 * abs(want).max()
        n = got.shape[0]
        rows = np.repeat(np.arange(n), np.diff(sp.csr_matrix(got).indptr))
        assert np.count_nonzero(got.indices == rows) == n       # every diagonal stored
    # seven classes select; the symmetric one ties unknowns (a column of P with 15 ones,
    # the electrode's potential), and takes the products
    assert selected == len(classes) - 1 == 7


def test_the_class_upper_triangle_is_that_of_the_class_tangent():
    """``class_upper`` of the union tangent's upper triangle (assembled directly) is the
    upper triangle of ``class_tangent`` of the whole union tangent, every diagonal entry
    stored, for every class of a charged eighth plate: the seven that select and the
    symmetric one, whose tied unknowns (the electrode) count a union entry between two of
    them twice on the diagonal."""
    import importlib

    import scipy.sparse as sp

    import skfem_dielectric as fe

    sc = importlib.import_module("skfem_dielectric.models.plate.symmetry_classes")
    pb = fe.gallery.keplinger_problem(elements=(3, 1, 2), symmetry="eighth", grading=0.5,
                                      options=fe.PlateOptions(grad_div=10.0))
    rng = np.random.default_rng(3)
    x = pb.initial_state() + 1e-3 * rng.standard_normal(pb.ndofs)   # a general state
    load = np.array([1.0, 0.5])
    classes, K = sc.union_tangent(pb, x, load, 10.0)
    same, U = sc.union_upper(pb, x, load, 10.0)
    assert [c.name for c in same] == [c.name for c in classes]
    assert abs(sp.triu(K) - U).max() <= 1e-14 * abs(K).max()
    tied = 0
    for c in classes:
        want = sp.triu(sc.class_tangent(c, K), format="csr")
        got = sc.class_upper(c, U)
        tied += sc._selection(c.P) is None
        assert got.shape == want.shape
        assert abs(got.upper - want).max() <= 1e-13 * abs(want).max()
        assert abs(got.tocsr() - sc.class_tangent(c, K)).max() <= 1e-13 * abs(want).max()
        n = got.shape[0]
        rows = np.repeat(np.arange(n), np.diff(got.upper.indptr))
        assert np.count_nonzero(got.upper.indices == rows) == n   # every diagonal stored
    assert tied == 1
