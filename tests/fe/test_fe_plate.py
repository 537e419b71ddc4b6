"""3D u-p-phi plate against the homogeneous closed forms of the paper.

References are the paper's formulas solved here with brentq (Eq. (loading_gent)),
independent of the FE code.
"""

import math

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.optimize import brentq
from skfem import MeshHex

from skfem_dielectric.fem.mesh import plate_mesh
from skfem_dielectric.gallery.drivers import equibiaxial_plate
from skfem_dielectric.gallery.plates import PlateOptions
from skfem_dielectric.materials import NeoHookeanDielectric
from skfem_dielectric.models.plate.problem import PlateProblem

JM = 97.2


def D0_nh(lam, s):
    return math.sqrt(max(lam**6 - 1 - lam**5 * s, 0.0))


def D0_gent(lam, s):
    return math.sqrt(max((lam**6 - 1) / (1 - (2 * lam**2 + lam**-4 - 3) / JM) - lam**5 * s, 0))


def lam_closed_form(D0, s, model):
    # the stretch on the loading curve: D0^2(lam) - D0^2 = 0, monotonic for these s
    f = (lambda L: (L**6 - 1 - L**5 * s) - D0**2) if model == "neo-Hookean" else \
        (lambda L: (L**6 - 1) / (1 - (2 * L**2 + L**-4 - 3) / JM) - L**5 * s - D0**2)
    hi = 10.0 if model == "neo-Hookean" else 0.999 * math.sqrt((JM + 3) / 2)  # Gent lock
    lo = brentq(lambda L: f(L) + D0**2, 1.0, hi, xtol=1e-15, rtol=1e-15)  # pre-stretch
    if D0 == 0:
        return lo
    return brentq(f, lo, hi, xtol=1e-15, rtol=1e-15)


@pytest.mark.parametrize("model", ["neo-Hookean", "Gent"])
@pytest.mark.parametrize("s", [0.8, 1.5, 2.5])
def test_equibiaxial_mixed_matches_closed_form(model, s):
    D0 = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    res = equibiaxial_plate(s, D0, model=model, preload_steps=8, linear_solver="superlu")
    assert res.converged, res.reason
    charge = [st for st in res.steps if st["phase"] == "charge"]
    assert [st.load[1] for st in charge] == D0
    for st in res.steps:
        lam_ref = lam_closed_form(st.load[1], st.load[0], model)
        # mixed formulation, homogeneous state: exact up to the Newton tolerance
        # (rtol 1e-11 on the residual), far below the required 1e-8
        assert abs(st["lam1"] / lam_ref - 1) < 1e-8
        assert abs(st["lam3"] / lam_ref - 1) < 1e-8
        assert abs(st["lam2"] * lam_ref**2 - 1) < 1e-8      # incompressibility
        # the D_L of the FE state is the prescribed charge
        assert abs(st["D0_centre"] - st.load[1]) < 1e-8 * max(1.0, st.load[1])
        # Newton: quadratic convergence, <= 5 iterations per target
        assert st.iterations <= 5 and st.substeps == 1


def test_equibiaxial_voltage_control_obeys_D0_equals_lam4_E0():
    s = 1.5
    E0 = [0.05, 0.1, 0.15]
    res = equibiaxial_plate(s, E0, options=PlateOptions(control="voltage"), linear_solver="superlu")
    assert res.converged
    for st in res.steps[-3:]:
        lam = st["lam1"]
        # Eq. (loading_gent) with D0 = lam^4 E0 (paper Sec. 2)
        assert abs(lam**4 * st.load[1] - D0_nh(lam, s)) < 1e-8 * D0_nh(lam, s)


def test_penalty_error_scales_like_mu_over_kappa():
    s, D0 = 1.5, 3.0
    lam_ref = lam_closed_form(D0, s, "neo-Hookean")
    kappas = np.array([1e2, 1e3, 1e4])
    errs = []
    for kappa in kappas:
        res = equibiaxial_plate(s, [D0], options=PlateOptions(formulation="penalty", kappa=kappa),
                                linear_solver="superlu")
        assert res.converged
        errs.append(abs(res.steps[-1]["lam1"] / lam_ref - 1))
    rate = np.polyfit(np.log(kappas), np.log(errs), 1)[0]
    # compressibility error is first order in mu/kappa: slope -1 (+-0.05 for the
    # O((mu/kappa)^2) remainder at kappa = 100)
    assert abs(rate + 1.0) < 0.05
    assert errs[-1] < 1e-3


@pytest.mark.parametrize("formulation,kappa,phi_element,pressure",
                         [("mixed", math.inf, "Q2", "Q1"), ("mixed", 30.0, "Q1", "Q1"),
                          ("penalty", 30.0, "Q2", "Q1"), ("isochoric", 30.0, "Q2", "Q1"),
                          ("mixed-isochoric", 30.0, "Q2", "Q1"),
                          ("mixed-plain", math.inf, "Q2", "Q1"),
                          ("mixed", math.inf, "Q2", "P0"), ("mixed", 30.0, "Q1", "P0")])
@pytest.mark.parametrize("loading,symmetry", [("uniaxial", "eighth"),
                                              ("equibiaxial", "quarter"),
                                              ("uniaxial", "half")])
def test_tangent_matches_finite_differences(formulation, kappa, phi_element, loading,
                                            symmetry, pressure, fd_columns):
    pm = plate_mesh(4.0, 1.0, 2.0, 2, 1, 2, symmetry=symmetry)
    pr = PlateProblem(pm, NeoHookeanDielectric(1.0, 1.0), loading=loading,
                      formulation=formulation, kappa=kappa, phi_element=phi_element,
                      threads=1, pressure=pressure)
    rng = np.random.default_rng(3)
    x = 0.05 * rng.standard_normal(pr.red.n)
    load = (0.7, 1.3)
    K, _ = pr.assemble(x, load)
    K = K.toarray()
    h = 1e-6
    Kfd = fd_columns(pr.residual, x, load, range(pr.red.n), h)
    # central differences: truncation O(h^2) ~ 1e-12, round-off ~1e-16/h ~ 1e-10
    assert np.abs(K - Kfd).max() / np.abs(K).max() < 1e-6
    assert np.abs(K - K.T).max() < 1e-12 * np.abs(K).max()


def test_bad_inputs():
    pm = plate_mesh(4.0, 1.0, 2.0, 1, 1, 1)
    mat = NeoHookeanDielectric()
    with pytest.raises(ValueError, match="L1"):
        plate_mesh(0.0, 1.0, 1.0, 1, 1, 1)
    with pytest.raises(ValueError, match="n2"):
        plate_mesh(1.0, 1.0, 1.0, 1, 0, 1)
    with pytest.raises(ValueError, match="symmetry"):
        plate_mesh(1.0, 1.0, 1.0, 1, 1, 1, symmetry="sixteenth")
    with pytest.raises(ValueError, match="loading"):
        PlateProblem(pm, mat, loading="shear")
    with pytest.raises(ValueError, match="kappa"):
        PlateProblem(pm, mat, kappa=-1.0)
    with pytest.raises(ValueError, match="kappa"):
        PlateProblem(pm, mat, formulation="penalty")
    # equi-biaxial needs two symmetry planes to remove rigid motions
    with pytest.raises(ValueError, match="symmetry"):
        PlateProblem(plate_mesh(1, 1, 1, 1, 1, 1, symmetry="half"), mat)
    with pytest.raises(ValueError, match="load"):
        PlateProblem(pm, mat).assemble(np.zeros(PlateProblem(pm, mat).red.n),
                                       (float("nan"), 0.0))
    with pytest.raises(ValueError, match="unknown boundary 'bottom'"):
        PlateProblem(pm, mat).boundary_dofs("bottom")      # cut by the x2 symmetry plane
    with pytest.raises(ValueError, match="field"):
        PlateProblem(pm, mat).boundary_dofs("top", "T")
    # a mesh without the clamp face cannot carry the uni-axial load
    g = pm.grids
    bare = type(pm)(mesh=MeshHex.init_tensor(*g).with_boundaries(
        {"top": lambda x: x[1] > 0.49}), L1=4.0, H=1.0, L3=2.0, symmetry=(), grids=g)
    with pytest.raises(ValueError, match="x1_plus"):
        PlateProblem(bare, mat, loading="uniaxial")
    with pytest.raises(ValueError, match="D0"):
        equibiaxial_plate(1.0, [1.0, float("nan")])
    with pytest.raises(ValueError, match="s must be finite"):
        equibiaxial_plate(float("nan"), [1.0])


@pytest.mark.skipif(not __import__("skfem_dielectric.linalg.linear",
                                    fromlist=["x"]).pardiso_available(),
                    reason="inertia needs PARDISO")
def test_charge_control_is_stable_by_inertia():
    # Paper Sec. 4: charge-controlled activation of the neo-Hookean plate is always
    # Hessian-stable; the inertia verdict (exactly n_p + n_phi negative eigenvalues) must
    # agree on the homogeneous plate at every step (pre-load and charge ramp).
    res = equibiaxial_plate(1.5, [2.0, 4.0, 6.0], elements=(2, 1, 2), linear_solver="pardiso")
    assert res.converged
    assert [st["stable"] for st in res.steps] == [True] * len(res.steps)
    with_superlu = equibiaxial_plate(1.5, [2.0], linear_solver="superlu")
    assert with_superlu.steps[-1]["stable"] is None       # SuperLU reports no inertia


@pytest.mark.parametrize("threads, chunk", [(1, 1), (2, 3), (2, 100)])
def test_tangent_equals_one_scatter_of_all_element_blocks(threads, chunk):
    # the chunks' ordered np.add.at into one array against the plain assembly: every
    # element block of the whole mesh through one np.bincount of 64-bit positions
    pm = plate_mesh(4.0, 1.0, 2.0, 3, 1, 2, symmetry="full")
    mat = NeoHookeanDielectric(1.0, 1.0)
    kw = dict(loading="uniaxial", threads=threads, chunk=chunk)
    pr = PlateProblem(pm, mat, **kw)
    rng = np.random.default_rng(7)
    x = 0.05 * rng.standard_normal(pr.red.n)
    load = (0.7, 1.3)
    K, r = pr.assemble(x, load)
    f = pr.form
    xf = pr.full(x, load)
    sl = slice(0, f.nel)
    resp = f._response(xf, sl)
    pos = np.concatenate([f._chunk_positions(s).positions() for s in f.chunks()])
    blocks = np.concatenate([f._element_blocks(f._response(xf, s), s).copy()
                             for s in f.chunks()])
    data = np.bincount(pos, weights=blocks, minlength=f.scatter.nnz + 1)[:f.scatter.nnz]
    rf = np.bincount(f.edofs.ravel(), weights=f._element_residual(resp, sl).ravel(),
                     minlength=f.n_full) - pr.external(load)
    scale = np.abs(data).max()
    assert np.abs(K.data - data).max() <= 1e-12 * scale
    np.testing.assert_allclose(r, pr.red.reduce(rf), rtol=1e-12,
                               atol=1e-12 * np.abs(r).max())
    # the same tangent and residual whatever the chunks and threads (chunk order: bit for bit)
    K1, r1 = PlateProblem(pm, mat, loading="uniaxial", threads=1, chunk=1000).assemble(x, load)
    assert np.array_equal(K.data, K1.data) and np.array_equal(r, r1)


@pytest.mark.parametrize("options", [dict(), dict(phi_element="Q1", chunk=2),
                                     dict(formulation="penalty", kappa=50.0),
                                     dict(kappa=80.0, threads=1)])
def test_upper_triangle_assembled_directly(options):
    # assemble_upper scatters only the upper triangle (the entries below the diagonal into
    # the rows' spare slots, the p-u and phi-u blocks not at all): the upper triangle of
    # the whole tangent bit for bit, and the same residual; the whole pattern is not made
    from skfem_dielectric.linalg.symmetric import SymmetricUpper

    pm = plate_mesh(4.0, 1.0, 2.0, 3, 1, 2, symmetry="full")
    pr = PlateProblem(pm, NeoHookeanDielectric(1.0, 1.0), loading="uniaxial", **options)
    rng = np.random.default_rng(8)
    x = 0.05 * rng.standard_normal(pr.red.n)
    S, r1 = pr.assemble_upper(x, (0.7, 1.3))
    assert isinstance(S, SymmetricUpper) and list(pr.form._structures) == [True]
    K, r = pr.assemble(x, (0.7, 1.3))
    T = sp.triu(K, format="csr")
    assert np.array_equal(S.upper.indptr, T.indptr) and np.array_equal(S.upper.indices,
                                                                      T.indices)
    assert np.array_equal(S.upper.data, T.data) and np.array_equal(r, r1)
    assert abs(S.tocsr() - K).max() <= 1e-12 * abs(K).max()     # K symmetric to round-off


def test_ramp_hands_the_upper_triangle_to_a_solver_that_reads_it(monkeypatch):
    from skfem_dielectric import ramp
    from skfem_dielectric.linalg.solver_base import SuperLUSolver

    pm = plate_mesh(4.0, 1.0, 2.0, 3, 1, 2, symmetry="full")
    pr = PlateProblem(pm, NeoHookeanDielectric(1.0, 1.0), loading="uniaxial")
    seen = []

    class UpperReader(SuperLUSolver):
        reads_upper = True

        def solve(self, K, b):
            seen.append(type(K).__name__)
            return super().solve(K, b)

    a = ramp(pr, [(0.2, 0.0), (0.2, 0.3)], linear_solver=UpperReader())
    b = ramp(pr, [(0.2, 0.0), (0.2, 0.3)], linear_solver=SuperLUSolver())
    assert seen and set(seen) == {"SymmetricUpper"} and a.converged and b.converged
    np.testing.assert_allclose(a.steps[-1].x, b.steps[-1].x, rtol=0,
                               atol=1e-9 * np.abs(b.steps[-1].x).max())


def _no_build(monkeypatch):
    """Make building a mesh or a membrane fail loudly: a driver that checks its callbacks
    first never gets there."""
    from skfem_dielectric.gallery import drivers

    def forbidden(*args, **kwargs):
        raise AssertionError("the driver built its model before checking its callbacks")

    for name in ("plate_mesh", "membrane_mesh", "MembranePlate"):
        monkeypatch.setattr(drivers, name, forbidden)
    return drivers


@pytest.mark.parametrize("call, name", [
    (lambda d: d.equibiaxial_plate(0.5, [1.0], on_step=42), "on_step"),
    (lambda d: d.maxwell_equibiaxial(0.5, [1.0], on_step="x"), "on_step"),
    (lambda d: d.keplinger_plate(1.0, [1.0], on_step=42), "on_step"),
    (lambda d: d.keplinger_plate(1.0, [1.0], state_analysis=3.0), "state_analysis"),
    (lambda d: d.maxwell_keplinger(1.0, [1.0], on_step=[1]), "on_step"),
    (lambda d: d.membrane_keplinger(1.0, [1.0], on_step=42), "on_step"),
    (lambda d: d.membrane_keplinger(1.0, [1.0], admissible=0), "admissible"),
])
def test_drivers_name_a_callback_that_is_not_callable_before_building(monkeypatch, call, name):
    drivers = _no_build(monkeypatch)
    with pytest.raises(ValueError, match=rf"^{name} must be callable or None, got "):
        call(drivers)


def test_run_ramp_names_a_callback_that_is_not_callable():
    from skfem_dielectric.gallery.drivers import equibiaxial_problem, run_ramp
    pb = equibiaxial_problem()
    with pytest.raises(ValueError, match=r"^on_step must be callable or None, got 42$"):
        run_ramp(pb, [np.array([0.5, 0.0])], on_step=42)


@pytest.mark.parametrize("field, value", [
    ("control", "current"), ("coupling", "weak"), ("field", "far"), ("formulation", "exact"),
    ("phi_element", "Q3"), ("pressure", "P1"), ("kappa", 0.0), ("kappa", -1.0), ("threads", 0), ("threads", 1.5),
    ("grad_div", -1.0), ("grad_div", math.nan),
])
def test_plate_options_name_the_bad_field_as_the_plate_does(field, value):
    # the reference is PlateProblem's own check of the same keyword: one message for one
    # bad value, whether it is given to the model or to the drivers' options
    pm = plate_mesh(4.0, 1.0, 4.0, 1, 1, 1, symmetry="eighth")
    with pytest.raises(ValueError) as model_error:
        PlateProblem(pm, NeoHookeanDielectric(1.0, 1.0), **{field: value})
    with pytest.raises(ValueError, match=rf"^{field} must ") as options_error:
        PlateOptions(**{field: value})
    assert str(options_error.value) == str(model_error.value)


@pytest.mark.parametrize("call", [
    lambda d: d.equibiaxial_plate(0.5, [1.0], options={"grad_div": 10.0}),
    lambda d: d.keplinger_plate(1.0, [1.0], options={"grad_div": 10.0}),
    lambda d: d.maxwell_keplinger(1.0, [1.0], options="maxwell"),
    lambda d: d.keplinger_problem(options=None),
])
def test_drivers_name_options_that_are_not_plate_options_before_building(monkeypatch, call):
    drivers = _no_build(monkeypatch)
    with pytest.raises(ValueError, match=r"^options must be a PlateOptions, got "):
        call(drivers)


def test_plate_options_reach_the_plate():
    from skfem_dielectric.gallery.drivers import keplinger_problem
    opts = PlateOptions(control="voltage", phi_element="Q1", grad_div=3.0, threads=1)
    pb = keplinger_problem(elements=(2, 1, 1), options=opts)
    # PlateProblem records the options it was built with: exactly the ones given
    assert {k: pb.options[k] for k in opts.as_kwargs()} == opts.as_kwargs()
    assert pb.load_names == ("s", "E0") and pb.grad_div == 3.0


def test_column_targets_only_is_one_entry_per_charge_target():
    """``column(..., targets_only=True)`` leaves the pre-load steps out: one stretch per
    ``D0`` (the zero charge is the pre-loaded state), equal to Eq. (loading_gent)."""
    s, D0 = 1.5, [0.0, 2.0, 4.0, 6.0]
    res = equibiaxial_plate(s, D0, preload_steps=4, linear_solver="superlu")
    assert res.converged, res.reason
    assert len(res.column("lam1")) == 4 + 3                 # 4 pre-load steps, 3 charges
    lam1 = res.column("lam1", targets_only=True)
    assert res.column("load", targets_only=True).tolist() == [[s, d] for d in D0]
    ref = np.array([lam_closed_form(d, s, "neo-Hookean") for d in D0])
    assert np.abs(lam1 - ref).max() < 1e-10
    assert res.column("iterations", targets_only=True).dtype.kind == "i"
    # resumed after D0 = 2: only the targets of this ramp
    at2 = res.target_steps()[1]
    rest = equibiaxial_plate(s, D0, preload_steps=4, linear_solver="superlu",
                             x0=at2.x, start=at2.load)
    assert rest.column("load", targets_only=True)[:, 1].tolist() == [4.0, 6.0]
    assert np.abs(rest.column("lam1", targets_only=True) - ref[2:]).max() < 1e-10
    with pytest.raises(ValueError, match="targets_only"):
        res.column("lam1", targets_only="yes")
    with pytest.raises(ValueError, match="name"):
        res.column("nope", targets_only=True)


def test_target_steps_match_loads_once_in_ramp_order():
    """The selection by hand-made steps: a stopped ramp (the intermediate last step is no
    target), a repeated load taken once per target, no targets: every reached one."""
    from skfem_dielectric.solvers.ramp import RampResult, StepResult

    def step(load, reached=True):
        return StepResult(load=np.array(load, float), converged=True, iterations=1,
                          substeps=1, cutbacks=0, residual_norms=[], x=np.zeros(1),
                          quantities={"q": load[1]}, target_reached=reached)

    steps = [step([0.5, 0]), step([1.0, 0]), step([1.0, 2]), step([1.0, 2]),
             step([1.0, 2.5], reached=False)]
    res = RampResult(steps=steps, converged=False,
                     targets=[np.array([1.0, 0.0]), np.array([1.0, 2.0]), np.array([1.0, 3.0])])
    assert res.column("q", targets_only=True).tolist() == [0.0, 2.0]
    assert [st.load[0] for st in res.target_steps()] == [1.0, 1.0]
    res.targets = None
    assert res.column("q", targets_only=True).tolist() == [0.0, 0.0, 2.0, 2.0]
    assert res.column("q").tolist() == [0.0, 0.0, 2.0, 2.0, 2.5]


@pytest.mark.parametrize("grad_div", [0.0, 10.0])
def test_equibiaxial_q2_p0_matches_closed_form(grad_div):
    """The second pressure space (one constant per element, the Q2-P0 pair) gives the
    homogeneous equi-biaxial state of Eq. (loading_gent) to 1e-8, as the Taylor-Hood one."""
    s, D0 = 1.5, [1.0, 3.0, 5.0]
    res = equibiaxial_plate(s, D0, options=PlateOptions(pressure="P0", grad_div=grad_div),
                            preload_steps=8, linear_solver="superlu")
    assert res.converged, res.reason
    for st in res.steps:
        lam_ref = lam_closed_form(st.load[1], st.load[0], "neo-Hookean")
        assert abs(st["lam1"] / lam_ref - 1) < 1e-8
        assert abs(st["lam2"] * lam_ref**2 - 1) < 1e-8
        assert abs(st["D0_centre"] - st.load[1]) < 1e-8 * max(1.0, st.load[1])


def test_plates_of_one_mesh_share_their_setup_and_fields_are_exact_for_affine_states():
    from skfem_dielectric.gallery.drivers import keplinger_problem
    from skfem_dielectric.models.plate.post import evaluate_fields

    p1 = keplinger_problem(elements=(3, 1, 2), symmetry="eighth")
    p2 = keplinger_problem(model=NeoHookeanDielectric(mu=2.5, eps=4.0), elements=(3, 1, 2),
                           symmetry="eighth")
    p3 = keplinger_problem(elements=(4, 1, 2), symmetry="eighth")
    assert p1.layout_key == p2.layout_key != p3.layout_key
    # the unit loads scale with the material: traction mu N, charge sqrt(mu eps)
    np.testing.assert_allclose(p2.f_s, 2.5 * p1.f_s, rtol=1e-15, atol=0)
    np.testing.assert_allclose(p2.q_D0, math.sqrt(2.5 * 4.0) * p1.q_D0, rtol=1e-15, atol=0)
    assert p2.clamp_area == p1.clamp_area == pytest.approx(0.5 * 1.0 * 0.5 * 50.0)
    # an affine state u = A X, phi = c . X, p = p0 is interpolated exactly by Q2/Q1/Q2:
    # F = I + A, Grad phi = c at any point, whichever plate of the mesh asks
    A = np.array([[0.1, -0.02, 0.03], [0.01, -0.05, 0.0], [0.02, 0.04, -0.03]])
    c = np.array([0.3, -1.2, 0.7])
    for prob in (p1, p2):
        xf = np.zeros(prob.n_full)
        X2 = prob.b2.doflocs
        for a in range(3):
            xf[a:prob.n_u:3] = A[a] @ X2
        xf[prob.off_phi:] = c @ prob.bphi.doflocs
        xf[prob.off_p:prob.off_phi] = 0.25
        pts = np.array([[1.0, 17.3, 49.9], [0.1, 0.2, 0.45], [0.5, 11.0, 24.0]])
        fld = evaluate_fields(prob, xf, pts)
        np.testing.assert_allclose(fld["F"], (np.eye(3) + A)[:, :, None] * np.ones(3),
                                   rtol=0, atol=1e-13)
        np.testing.assert_allclose(fld["G"], c[:, None] * np.ones(3), rtol=0, atol=1e-12)
        np.testing.assert_allclose(fld["u"], A @ pts, rtol=0, atol=1e-12)
        np.testing.assert_allclose(fld["p"], 0.25, rtol=0, atol=1e-14)
