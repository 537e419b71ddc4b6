"""The clamp-edge section model: its operator against finite differences of the energy, its
homogeneous strip against the exact (Stroh) dispersion of the analytic package, and its
input checks."""

import math

import numpy as np
import pytest

from analytic import critical_D0
from skfem_dielectric.linalg.linear import pardiso_available
from skfem_dielectric.materials import ideal_dielectric_response, make_material
from skfem_dielectric.models.edge_section import (EdgeSection, edge_section_grids,
                                                  graded_spacing, homogeneous_base)

MAT = make_material("neo-Hookean")


def _first_negative(g1, g2, lam, k, lo, hi, steps=22, grad_div=0.0, pressure="Q1"):
    """The smallest ``D0`` in ``[lo, hi]`` with a negative eigenvalue at ``k`` (bisection)."""
    def count(D0):
        return EdgeSection(g1, g2, MAT, homogeneous_base(MAT, lam, lam, D0),
                           fixed="normal", grad_div=grad_div, pressure=pressure).count(k)
    assert count(lo) == 0 and count(hi) > 0
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if count(mid) > 0 else (mid, hi)
    return hi


@pytest.mark.parametrize("k", [0.5, 2.0, 6.0])
def test_a_strip_wrinkles_at_the_stroh_charge(k):
    """A homogeneous equibiaxial strip (mirror planes at both ends, one element along X1,
    16 Q2 elements through the thickness) first loses stability at the charge where the
    exact finite-thickness dispersion relation of the antisymmetric mode has its root;
    ``kh`` is the deformed wavenumber ``k / lam`` times the deformed thickness
    ``H / lam^2``.  Measured: relative error 3e-8 (k = 0.5, 2) and 7e-6 (k = 6)."""
    lam, H = 1.5, 1.0
    ref = float(critical_D0(lam, (k / lam) * (H / lam**2)))
    got = _first_negative(np.array([0.0, 0.25]), np.linspace(-H / 2, H / 2, 17), lam, k,
                          0.8 * ref, 1.2 * ref)
    assert abs(got / ref - 1) < 5e-5, (got, ref)


@pytest.mark.parametrize("k", [0.5, 2.0])
def test_the_p0_strip_converges_to_the_stroh_charge_at_rate_two(k):
    """The second pressure space, one constant per element (Q2-P0), with the plate's
    grad-div weight 10: the strip's first negative charge approaches the exact dispersion
    relation's from below at rate 2 as the elements through the thickness are doubled
    (8, 16, 32; measured rates 1.95-2.00, error 2.3e-7 and 3.5e-6 on 32)."""
    lam, H = 1.5, 1.0
    ref = float(critical_D0(lam, (k / lam) * (H / lam**2)))
    err = [_first_negative(np.array([0.0, 0.25]), np.linspace(-H / 2, H / 2, n + 1), lam, k,
                           0.8 * ref, 1.2 * ref, steps=34, grad_div=10.0,
                           pressure="P0") / ref - 1 for n in (8, 16, 32)]
    assert all(e < 0 for e in err) and abs(err[-1]) < 1e-5, err
    for a, b in zip(err[:-1], err[1:]):
        assert 1.9 < math.log2(a / b) < 2.1, err


def test_without_grad_div_the_p0_strip_has_an_onset_the_mesh_does_not_move():
    """Q2-P0 without grad-div at k = 6: a first negative charge 19 % below the exact one
    on 16 and on 32 elements through the thickness (equal to 1e-3): an artefact of the
    discretisation of ``J = 1`` that refinement does not remove, as for Taylor-Hood on
    square elements (next test); with grad-div it is gone (the test above)."""
    lam, H, k = 1.5, 1.0, 6.0
    ref = float(critical_D0(lam, (k / lam) * (H / lam**2)))
    err = [_first_negative(np.array([0.0, 0.25]), np.linspace(-H / 2, H / 2, n + 1), lam, k,
                           0.5 * ref, 1.2 * ref, steps=30, pressure="P0") / ref - 1
           for n in (16, 32)]
    assert -0.20 < err[0] < -0.15 and abs(err[0] - err[1]) < 1e-3, err


def test_without_grad_div_the_discrete_strip_fails_early_on_every_mesh():
    """The Q2/Q1/Q2 strip with square elements and no grad-div term has element-scale
    modes at the charged faces: at k = 6 it first loses stability 15 % below the exact
    charge (4.1109), at a charge that does not move when the elements are halved
    (measured 3.4854 for h = H/8, 3.4879 for H/16), so refinement alone would not expose
    it.  The plate's grad-div weight (10 mu) removes it: the exact charge within 5e-5
    (measured 2.6e-5 on H/16)."""
    lam, k = 1.5, 6.0
    ref = float(critical_D0(lam, (k / lam) / lam**2))
    onset = {}
    for n in (8, 16):
        g1, g2 = np.linspace(0.0, 4.0 / n, 5), np.linspace(-0.5, 0.5, n + 1)
        onset[n] = _first_negative(g1, g2, lam, k, 2.0, 1.2 * ref)
        assert onset[n] < 0.86 * ref, (n, onset[n], ref)
    assert abs(onset[16] - onset[8]) < 1e-2, onset
    got = _first_negative(g1, g2, lam, k, 2.0, 1.2 * ref, grad_div=10.0)
    assert abs(got / ref - 1) < 5e-5, (got, ref)


def _base(X1, X2):
    """A smooth base state, even in X3 (no F_13, F_31, F_23, F_32, G_3), far from
    homogeneous."""
    n = X1.size
    F = np.zeros((3, 3, n))
    F[0, 0] = 1.3 + 0.05 * np.sin(X1)
    F[0, 1] = 0.04 * X2
    F[1, 0] = 0.03 * X1 * X2
    F[1, 1] = 1 / (1.3 * 1.1) + 0.02 * np.cos(X2)
    F[2, 2] = 1.1 + 0.01 * X1
    G = np.vstack([0.1 * X2, -0.4 + 0.05 * X1, np.zeros(n)])
    return F, G, 0.3 + 0.1 * X1 * X2


def test_the_operator_is_the_second_variation_of_the_energy():
    """``v^T K v`` equals twice the period average in X3 of the second difference of the
    energy ``int psi(F + t dF, G + t dG, p + t dp)`` for a perturbation assembled from the
    3D fields ``u = (a1 cos kX3, a2 cos kX3, a3 sin kX3)``, ``p = b cos kX3``,
    ``phi = c cos kX3`` (derivatives along X3 taken here, not by the model), on a base
    state that varies in X1 and X2.  Central differences, ``t = 1e-4``: agreement to
    1e-6 relative."""
    k, gd = 1.7, 10.0
    g1, g2 = np.linspace(0.0, 1.0, 4), np.linspace(-0.5, 0.5, 4)
    sec = EdgeSection(g1, g2, MAT, _base, grad_div=gd, fixed="none")
    rng = np.random.default_rng(1)
    v = rng.standard_normal(sec.ndofs)
    Kv = float(v @ (sec.matrix(k) @ v))

    b2, b1, n2 = sec.b2, sec.b1, sec.n2
    fields = [b2.interpolate(v[f * n2:(f + 1) * n2]) for f in range(4)]
    b = np.asarray(b1.interpolate(v[4 * n2:]))
    val = [np.asarray(f) for f in fields]
    grad = [np.asarray(f.grad) for f in fields]                  # (2, e, q)
    X = b2.mapping.F(b2.X)
    F0, G0, p0 = _base(X[0].ravel(), X[1].ravel())
    shape = X.shape[1:]
    F0 = F0.reshape(3, 3, *shape)
    G0 = G0.reshape(3, *shape)
    p0 = p0.reshape(shape)
    dx = np.asarray(b2.dx)

    def energy(t, theta):
        c, s = math.cos(theta), math.sin(theta)
        dF = np.zeros_like(F0)
        for a in range(2):                    # u_a = a_a cos kX3
            dF[a, 0], dF[a, 1] = grad[a][0] * c, grad[a][1] * c
            dF[a, 2] = -k * val[a] * s
        dF[2, 0], dF[2, 1] = grad[2][0] * s, grad[2][1] * s      # u_3 = a3 sin kX3
        dF[2, 2] = k * val[2] * c
        dG = np.stack([grad[3][0] * c, grad[3][1] * c, -k * val[3] * s])
        r = ideal_dielectric_response(MAT, F0 + t * dF, G0 + t * dG, p0 + t * b * c,
                                      need_tangent=False, grad_div=gd * MAT.mu)
        return float(np.sum(r.psi * dx))

    t, thetas = 1e-4, 2 * np.pi * np.arange(8) / 8
    second = np.mean([(energy(t, th) - 2 * energy(0.0, th) + energy(-t, th)) / t**2
                      for th in thetas])
    assert abs(Kv - 2 * second) < 1e-6 * abs(Kv), (Kv, 2 * second)


def test_no_charge_no_negative_mode():
    """Without charge the stretched strip (and the section with its ends fixed) is stable
    at every wavenumber: the count is the law of inertia less the multipliers, so a
    wrong multiplier count would show here."""
    g1, g2 = edge_section_grids(h0=0.05)
    sec = EdgeSection(g1, g2, MAT, homogeneous_base(MAT, 1.3, 1.2, 0.0), fixed="ends")
    assert [sec.count(k) for k in (0.1, 3.0, 50.0)] == [0, 0, 0]


def test_graded_spacing():
    """First interval ``h0``, growth at most ``growth``, last node at ``length``."""
    t = graded_spacing(5.0, 0.02, 1.3, 0.5)
    d = np.diff(t)
    assert t[0] == 0 and t[-1] == pytest.approx(5.0, abs=1e-14)
    assert d[0] == pytest.approx(0.02, rel=1e-12)
    assert np.all(d[1:-2] / d[:-3] <= 1.3 + 1e-12) and d.max() <= 0.5 * 1.5 + 1e-12
    g1, g2 = edge_section_grids(h0=0.01)
    assert g1[-1] - g1[-2] == pytest.approx(0.01, rel=1e-9)
    assert g2[1] - g2[0] == pytest.approx(0.01, rel=1e-9)
    assert g2[-1] - g2[-2] == pytest.approx(0.01, rel=1e-9)


@pytest.mark.parametrize("call, name", [
    (lambda: graded_spacing(5.0, -1.0, 1.3, 0.5), "h0"),
    (lambda: graded_spacing(5.0, 0.1, 0.9, 0.5), "growth"),
    (lambda: EdgeSection([0.0, 1.0], [0.0, 1.0], MAT, _base, fixed="both"), "fixed"),
    (lambda: EdgeSection([1.0, 0.0], [0.0, 1.0], MAT, _base), "g1"),
    (lambda: EdgeSection([0.0, 1.0], [0.0, 1.0], MAT, _base, grad_div=-1.0), "grad_div"),
    (lambda: EdgeSection([0.0, 1.0], [0.0, 1.0], MAT, _base).matrix(0.0), "k"),
])
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def _homogeneous_fields(lam1, lam3, D0):
    """The homogeneous state as the 3D plate's fields would give it (``u`` about the
    clamp face ``X1 = 50``, ``phi`` odd in ``X2``)."""
    hb = homogeneous_base(MAT, lam1, lam3, D0)

    def fields(X1, X2):
        X1, X2 = np.asarray(X1, float).ravel(), np.asarray(X2, float).ravel()
        F, G, p = hb(X1, X2)
        u = np.vstack([(lam1 - 1) * (X1 - 50.0), (1 / (lam1 * lam3) - 1) * X2,
                       np.zeros(X1.size)])
        return {"u": u, "phi": G[1] * X2, "p": p, "F": F, "G": G}
    return fields


@pytest.mark.parametrize("pressure", ["Q1", "P0"])
def test_the_section_base_keeps_a_homogeneous_state_and_newton_returns_to_it(pressure):
    """The homogeneous state (charge on both faces, its own boundary data) is an
    equilibrium of the section's equations, with either pressure space: no Newton step is
    taken; from a guess 1e-2 away Newton returns to it within 1e-8 in at most 6 steps (a
    wrong tangent would not)."""
    from skfem_dielectric.studies.section_base import solve_section_base
    lam1, lam3, D0 = 1.4, 1.2, 1.0
    fields = _homogeneous_fields(lam1, lam3, D0)
    g1, g2 = edge_section_grids(h0=0.05)
    sb = solve_section_base(g1, g2, MAT, fields, D0, grad_div=10.0, pressure=pressure)
    assert sb.iterations == 0
    X1, X2 = np.array([46.0, 49.9]), np.array([0.0, 0.45])

    def guess(a, b):
        f = fields(a, b)
        f["u"] = f["u"] + 1e-2 * np.vstack([np.sin(a) * b, np.cos(b) * (a - 50) / 5, 0 * a])
        f["p"] = f["p"] + 1e-2 * b
        return f

    sb = solve_section_base(g1, g2, MAT, fields, D0, guess=guess, grad_div=10.0,
                            pressure=pressure)
    assert 1 <= sb.iterations <= 6
    got = sb.fields(X1, X2)
    assert np.allclose(got["F"][0, 0], lam1, atol=1e-8)
    assert np.allclose(got["F"][1, 1], 1 / (lam1 * lam3), atol=1e-8)
    assert np.allclose(got["G"][1], fields(X1, X2)["G"][1], atol=1e-8)


def test_continuation_reaches_the_homogeneous_end_state():
    """Along a path of homogeneous states (lam1 1.1 -> 1.5, D0 0 -> 2; the first one's
    fields carry the charge 0.5, not its D0 = 0, so its section state is not homogeneous
    and no guess on the way is exact) the continued base state ends on the last one:
    F11, F22 and Grad phi within 1e-8; a path of one state is the direct solve."""
    from skfem_dielectric.studies.section_base import continue_section_base
    lam3 = 1.2
    path = [(D0, _homogeneous_fields(lam1, lam3, Df))
            for lam1, D0, Df in ((1.1, 0.0, 0.5), (1.3, 1.0, 1.0), (1.5, 2.0, 2.0))]
    g1, g2 = edge_section_grids(h0=0.1)
    seen = []
    sb = continue_section_base(g1, g2, MAT, path, grad_div=10.0, progress=seen.append)
    assert len(seen) == 2 and sb.iterations >= 2
    X1, X2 = np.array([45.5, 47.0, 49.95]), np.array([0.1, -0.3, 0.45])
    got = sb.fields(X1, X2)
    assert np.allclose(got["F"][0, 0], 1.5, atol=1e-8)
    assert np.allclose(got["F"][1, 1], 1 / (1.5 * lam3), atol=1e-8)
    assert np.allclose(got["G"][1], path[-1][1](X1, X2)["G"][1], atol=1e-8)
    assert continue_section_base(g1, g2, MAT, path[-1:], grad_div=10.0).iterations == 0
    with pytest.raises(ValueError, match="path"):
        continue_section_base(g1, g2, MAT, [], grad_div=10.0)


def test_band_onsets_and_the_figure(tmp_path):
    """``band_onsets`` gives, per state and section mesh, the smallest k with a negative
    mode and whether the base inverted elements (hand-made rows); the figure has a panel per state and a line per h0; the CLI
    refuses a folder that is not one with code 2."""
    from validation.cli import main
    from validation.clamp_zone.band import band_onsets, edge_band_figure, mesh_reach

    # 36 elements over the half-width 25 mm, 4 per half-wave: k = pi / (4 * 25 / 36)
    assert math.isclose(mesh_reach("40x1x36"), math.pi * 36 / 100, rel_tol=1e-12)
    def row(alpha, D0, h0, k, n):
        return {"alpha": alpha, "D0": D0, "mesh": "40x1x36", "grading": "0.1",
                "grad_div": "10", "h0": h0, "k": k, "n_negative": n,
                "J_min": "-0.1" if alpha == "1.5" else "0.6"}
    rows = [row("1", "3.25", h0, k, n) for h0, kn in
            (("0.04", ((1, 0), (10, 2), (100, 4))), ("0.02", ((1, 0), (10, 0), (100, 2))))
            for k, n in kn] + [row("1.5", "4.5", "0.04", k, 0) for k in (1, 10)]
    got = band_onsets(rows)
    assert got[(1.0, 3.25, "40x1x36", 0.1, 10.0, "Q1")] == {
        0.04: (10.0, 2, 100.0, False), 0.02: (100.0, 2, 100.0, False)}
    assert got[(1.5, 4.5, "40x1x36", 0.1, 10.0, "Q1")] == {0.04: (None, 0, 10.0, True)}
    fig = edge_band_figure(rows)
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert len(visible) == 2 and [len(ax.lines) for ax in visible] == [2, 1]
    assert main(["clamp-zone", "band", "--from", str(tmp_path / "missing"),
                 "--out", str(tmp_path)]) == 2


def test_the_docs_show_the_committed_band_table():
    """docs/clamp-zone.md shows ``band_table`` of the committed rows verbatim, and every
    charged Taylor-Hood state of the committed rows has three section meshes (the P0 and
    the dead-load states two)."""
    from pathlib import Path

    from validation.clamp_zone.band import band_onsets, band_table
    from validation.data.registry import load

    rows = load("section")
    assert all(len(by_h) == (3 if state[-1] == "Q1" and state[1] > 0 else 2)
               for state, by_h in band_onsets(rows).items())
    docs = (Path(__file__).resolve().parents[2] / "docs" / "clamp-zone.md").read_text()
    assert band_table(rows) in docs


def test_the_section_base_guards_every_step_against_inversion():
    """The section's Newton guard is the plate's: the largest step fraction that keeps
    ``J = det F > 0`` at every quadrature point (``max_step``) is where a brute-force scan
    of ``min J`` along the step (1e-4 apart) first reaches zero, within the scan's step;
    a state past it is named inadmissible, and a first guess that is inverted is refused
    with one line before any Newton step."""
    from skfem_dielectric.models.edge_base import SectionBaseProblem
    from skfem_dielectric.studies.section_base import solve_section_base

    lam1, lam3, D0 = 1.4, 1.2, 1.0
    fields = _homogeneous_fields(lam1, lam3, D0)
    g1, g2 = edge_section_grids(h0=0.1)
    pb = SectionBaseProblem(g1, g2, MAT, fields, D0, grad_div=10.0)
    y = pb.initial_state()
    X = pb.b2.doflocs
    d = np.zeros(pb.ndofs_full)
    d[: pb.n2] = -3.0 * lam1 * (X[0] - 50.0)          # u1: F11 -> lam1 (1 - 3 a) inside
    dy = d[pb.free]
    a = pb.max_step(y, dy)
    assert 0.0 < a < 1.0 / 3.0 + 1e-9
    grid = np.arange(0.0, 0.5, 1e-4)
    first = grid[np.argmax([pb.jacobian(y + g * dy).min() <= 0 for g in grid])]
    assert first - 1e-4 <= a <= first
    assert pb.admissible(y + 0.999 * a * dy) == ""
    assert "inverted section state" in pb.admissible(y + 1.01 * first * dy)
    assert pb.newton_guards() == {"step_limit": pb.max_step, "admissible": pb.admissible}

    def inverted(a_, b_):
        f = fields(a_, b_)
        f["u"] = f["u"] * np.array([[-2.0], [1.0], [0.0]])   # F11 < 0 inside
        return f

    with pytest.raises(ValueError, match="first guess is not admissible: inverted"):
        solve_section_base(g1, g2, MAT, fields, D0, guess=inverted, grad_div=10.0)


def test_the_alpha_1_5_section_sentence_is_the_table_s():
    """docs/clamp-zone.md's alpha = 1.5 sentence from the shipped rows: no row with an
    inverted base state, ``J`` between the rows' least ``J_min`` and largest ``J_max`` (to
    the two printed digits), the range of the row sets' least ``J``, and the first
    ``k`` with a negative mode 9.267 on every mesh and state."""
    from pathlib import Path

    from validation.data.registry import load

    every = [r for r in load("section") if r["alpha"] == "1.5"]
    assert every and min(float(r["J_min"]) for r in every) > 0
    rows = [r for r in every if r["pressure"] == "Q1"           # the sentence's sections
            and float(r["D0"]) > 0]
    text = (Path(__file__).resolve().parents[2] / "docs" / "clamp-zone.md").read_text()
    lo, hi = min(float(r["J_min"]) for r in rows), max(float(r["J_max"]) for r in rows)
    assert f"`J` between {lo:.2f} and {hi:.2f}" in text
    top = max(float(r["J_min"]) for r in rows)      # the least J of the most regular set
    assert f"`J` ({lo:.2f}-{top:.2f} at the edge)" in " ".join(text.split())
    first = {}
    for r in every:                                     # both pressure spaces
        if int(r["n_negative"]) > 0:
            key = (r["D0"], r["h0"])
            first[key] = min(first.get(key, float("inf")), float(r["k"]))
    assert len(first) == 11 and set(first.values()) == {9.267}
    assert "the band starts at 9.267/mm on every mesh and\n  state" in text
    dead = [r for r in every if float(r["D0"]) == 0]        # the dead load alone
    assert {(r["pressure"], r["h0"]) for r in dead} == {(p, h) for p in ("Q1", "P0")
                                                       for h in ("0.04", "0.02")}
    neg = [float(r["k"]) for r in dead if int(r["n_negative"]) > 0]
    assert min(neg) == 9.267 and f"up to {max(neg):.3g}/mm" in " ".join(text.split())
    assert {int(r["n_negative"]) for r in dead if int(r["n_negative"]) > 0} == {2}
    lo, hi = min(float(r["J_min"]) for r in dead), max(float(r["J_max"]) for r in dead)
    assert f"`J` between {lo:.2f} and {hi:.2f} in the section" in " ".join(text.split())


def test_the_section_takes_the_grad_div_of_its_3d_state():
    """The section's boundary data and F33 come from the 3D state, whose discrete
    equilibrium holds its grad-div term: with the state's weight the section's base state
    converges under the dead load (a 4 x 1 x 2 plate of alpha = 1.5, the 10 of the
    units); another weight is refused before any Newton step, naming ``grad_div`` and the
    state's weight (it would not converge: measured, 40 steps at a relative residual of
    0.66 for weight 0)."""
    from skfem_dielectric.models.edge_section import plate_fields
    from skfem_dielectric.studies.section_base import continue_section_base
    from validation.clamp_zone.units import ramp_states, unit_problem

    pb, s = unit_problem(1.5, (4, 1, 2), grading=0.5)
    path = [(d, plate_fields(pb, pb.full(x, load))) for d, x, load in ramp_states(pb, s, 0.0)]
    assert path[0][1].grad_div == 10.0
    g1, g2 = edge_section_grids(50.0, 5.0, 1.0, 0.1)
    sb = continue_section_base(g1, g2, pb.material, path, grad_div=10.0)
    assert sb.iterations > 0 and sb.residual <= 1e-10
    for other in (0.0, 30.0):
        with pytest.raises(ValueError, match=r"grad_div must be the 3D state's grad-div "
                                             r"weight 10 .*got " + f"{other!r}"):
            continue_section_base(g1, g2, pb.material, path, grad_div=other)


@pytest.mark.skipif(not pardiso_available(), reason="needs pypardiso")
def test_pardiso_counts_the_strip_as_superlu_does_next_to_its_first_negative_charge():
    """Within 2.3e-7 above the Q2-P0 strip's first negative charge on 32 elements
    (k = 0.5) the smallest eigenvalue is tiny: the count of PARDISO with weighted matching
    (that of ``counted_inertia``) is SuperLU's at every charge (one negative mode), where
    without the matching it flipped to 0 and back within 4e-8 of the charge."""
    lam, H, k = 1.5, 1.0, 0.5
    ref = float(critical_D0(lam, (k / lam) * (H / lam**2)))
    for e in (-2.3e-7, -2.1e-7, -1.95e-7, -1.9e-7, -1.8e-7):
        sec = EdgeSection(np.array([0.0, 0.25]), np.linspace(-H / 2, H / 2, 33), MAT,
                          homogeneous_base(MAT, lam, lam, ref * (1 + e)), fixed="normal",
                          grad_div=10.0, pressure="P0")
        assert sec.count(k, method="pardiso") == sec.count(k, method="superlu") == 1, e
