"""3D Maxwell-traction plate and cross-checks between the FE variants.

The Keplinger comparisons (3D fully coupled vs 3D Maxwell traction vs 2D membrane)
take minutes and are marked ``slow``; the homogeneous checks and the tangent are fast.
"""

import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

from skfem_dielectric import (CrossSection, MembranePlate, PlateProblem, keplinger_plate,
                              membrane_mesh, section_mesh, write_vtu_series)
from skfem_dielectric.gallery import (cross_section_ramp, maxwell_equibiaxial, maxwell_keplinger,
                                      membrane_keplinger, membrane_ramp)
from skfem_dielectric.linalg import nonsymmetric_solver, pardiso_available
from skfem_dielectric import RampSettings, ramp
from skfem_dielectric.fem.mesh import plate_mesh
from skfem_dielectric.materials import GentDielectric, NeoHookeanDielectric


def maxwell_plate(plate, material, **options):
    """The 3D plate with the Maxwell-traction coupling."""
    return PlateProblem(plate, material, coupling="maxwell", **options)

MU, EPS = 1.3, 0.7


def _lam_equibiaxial(D0, s):
    """Invert Eq. (loading_gent)_1 (neo-Hookean), written here as the reference."""
    return brentq(lambda l: l**6 - 1 - l**5 * s - D0**2, 1.0, 8.0, xtol=1e-15, rtol=1e-14)


def _lam1_uniaxial(D0, s):
    """Invert Eq. (DEuniax)_1."""
    lo = brentq(lambda l: l - l**-2 - s, 0.5, 20.0)
    return brentq(lambda l: l**4 * (l - s) ** 2 - 1 - D0**2, lo - 1e-12, 20.0, xtol=1e-15,
                  rtol=1e-14)


@pytest.mark.parametrize("field", ["electrostatic", "local"])
@pytest.mark.parametrize("s", [0.8, 2.5])
def test_maxwell_3d_equibiaxial_matches_closed_form(field, s):
    res = maxwell_equibiaxial(s, [2.0, 4.0, 6.0], field=field,
                              model=NeoHookeanDielectric(MU, EPS), linear_solver="superlu")
    assert res.converged
    for st in res.steps:
        lam = _lam_equibiaxial(st.load[1], s) if st.load[1] > 0 else brentq(
            lambda l: l - l**-5 - st.load[0], 0.5, 8.0, xtol=1e-15, rtol=1e-14)
        # homogeneous state exact in Q2/Q1 and the field exact on it: Newton tolerance
        assert abs(st["lam1"] / lam - 1) < 1e-8
        assert abs(st["lam3"] / lam - 1) < 1e-8
        assert abs(st["min_P33"] - st.load[0] / lam) < 1e-8  # total P33 = s/lam


@pytest.mark.parametrize("field", ["electrostatic", "local"])
def test_maxwell_3d_uniaxial_matches_closed_form(field):
    s = 2.5
    pb = maxwell_plate(plate_mesh(4.0, 1.0, 4.0, 1, 1, 1), NeoHookeanDielectric(MU, EPS),
                      loading="uniaxial-free", field=field)
    res = ramp(pb, [(s / 2, 0.0), (s, 0.0), (s, 2.0), (s, 4.0), (s, 6.0)],
               settings=RampSettings(atol=0.0, rtol=1e-11))
    assert res.converged
    for st in res.steps[1:]:
        lam1 = _lam1_uniaxial(st.load[1], s)
        assert abs(st["lam1"] / lam1 - 1) < 1e-8  # exact homogeneous state
        assert abs(st["lam3"] / np.sqrt(lam1 * (lam1 - s)) - 1) < 1e-8
        assert abs(st["min_P33"]) < 1e-8  # free x3 faces: total P33 = 0


@pytest.mark.parametrize("field", ["electrostatic", "local"])
def test_maxwell_3d_tangent_matches_finite_differences(field, assert_tangent_columns):
    pb = maxwell_plate(plate_mesh(4.0, 1.0, 2.0, 2, 1, 1), GentDielectric(MU, EPS, 20.0),
                      loading="uniaxial", field=field)
    rng = np.random.default_rng(8)
    x = 0.01 * rng.standard_normal(pb.red.n)
    load = (1.0, 2.5)
    K, _ = pb.assemble(x, load)
    K = K.toarray()
    cols = rng.choice(pb.red.n, 12, replace=False)
    assert_tangent_columns(pb.residual, K, x, load, cols, floor=1.0)
    # the follower traction makes the tangent non-symmetric
    assert np.abs(K - K.T).max() > 1e-6 * np.abs(K).max()


def test_maxwell_bad_input():
    pm = plate_mesh(4.0, 1.0, 4.0, 1, 1, 1)
    mat = NeoHookeanDielectric(1.0, 1.0)
    with pytest.raises(ValueError, match="field"):
        maxwell_plate(pm, mat, field="nonlocal")
    with pytest.raises(ValueError, match="control"):
        maxwell_plate(pm, mat, control="voltage", field="local")
    with pytest.raises(ValueError, match="formulation"):
        maxwell_plate(pm, mat, formulation="penalty", kappa=1e3)
    with pytest.raises(ValueError, match="linear solver"):
        nonsymmetric_solver("umfpack")


# --------------------------------------------------------------------------
# Keplinger plate (alpha = 1): membrane and Maxwell traction vs fully coupled 3D
# --------------------------------------------------------------------------
KEPLINGER_MESH = (20, 1, 10)  # eighth model: 20 x 10 in-plane Q2, one layer per half
KEPLINGER_D0 = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0]


@pytest.fixture(scope="module")
def coupled_keplinger():

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return keplinger_plate(1.0, KEPLINGER_D0, elements=KEPLINGER_MESH,
                               linear_solver="superlu")


def _charge_steps(res):
    return {round(float(np.asarray(st.load)[1]), 6): st for st in res.steps
            if np.asarray(st.load)[1] > 0}


def _breakdown_D0(steps):
    """First charge at which min P33 on the centre line turns compressive (paper Sec. 6)."""
    neg = [d for d, st in sorted(steps.items()) if st["min_P33"] < 0]
    return neg[0] if neg else np.inf


@pytest.mark.slow
def test_keplinger_membrane_matches_coupled_3d(coupled_keplinger):

    mem = _charge_steps(membrane_keplinger(1.0, KEPLINGER_D0, n1=KEPLINGER_MESH[0],
                                           n3=KEPLINGER_MESH[2]))
    cpl = _charge_steps(coupled_keplinger)
    assert set(cpl) == set(mem)
    for d, st in cpl.items():
        # the plane-stress membrane and the 3D plate agree on the centre
        # stretch within 0.1 % (thin plate H/L1 = 0.01; the 3D effects are local to the
        # clamps); measured ~5e-6 on this mesh
        assert abs(mem[d]["lam1"] / st["lam1"] - 1) < 1e-3, d


@pytest.mark.slow
def test_keplinger_maxwell_matches_coupled_3d_up_to_breakdown(coupled_keplinger):

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        mx = _charge_steps(maxwell_keplinger(1.0, KEPLINGER_D0, field="electrostatic",
                                             elements=KEPLINGER_MESH,
                                             linear_solver="superlu"))
    cpl = _charge_steps(coupled_keplinger)
    D0b = _breakdown_D0(cpl)
    assert np.isfinite(D0b)  # P33 does turn compressive on this path (paper Fig. zs22)
    compared = [d for d in cpl if d <= D0b]
    assert len(compared) >= 4
    for d in compared:
        # lam1 within 0.1 %, min P33 within 5 % of mu up to the breakdown; the
        # two discretise the same equations (Div tau_m = 0 for the solved field)
        assert abs(mx[d]["lam1"] / cpl[d]["lam1"] - 1) < 1e-3, d
        assert abs(mx[d]["min_P33"] - cpl[d]["min_P33"]) < 0.05, d


def test_export_of_the_2d_variants(tmp_path):
    """VTU series of the membrane and cross-section ramps: the exported fields are the
    post-processed ones (homogeneous equi-biaxial state: P33 = s/lam in every cell)."""
    import meshio


    s = 1.5
    for name, res in (
        ("membrane", membrane_ramp(MembranePlate(membrane_mesh(2.0, 0.1, 1.0, 2, 1),
                                                 NeoHookeanDielectric(MU, EPS),
                                                 loading="equibiaxial"), s, [0.0, 2.0])),
        ("section", cross_section_ramp(CrossSection(section_mesh(2.0, 1.0, 2, 1),
                                                    NeoHookeanDielectric(MU, EPS)),
                                       s, s, [0.0, 2.0])),
    ):
        files = write_vtu_series(res, tmp_path / name)
        assert len(files) == 3 and files[-1].suffix == ".pvd"
        m = meshio.read(files[1])
        lam = res.steps[1]["lam1"]
        # homogeneous state: every element carries the post-processed values (round-off)
        np.testing.assert_allclose(m.cell_data["P33"][0], s / lam, rtol=1e-8)
        np.testing.assert_allclose(m.cell_data["lam1"][0], lam, rtol=1e-10)
        # corner displacement (L1/2 from the centre line) = (lam - 1) L1/2
        assert abs(m.point_data["displacement"][:, 0].max() - (lam - 1) * 1.0) < 1e-9


def test_nonsymmetric_pardiso_solves_the_maxwell_tangent():
    """PARDISO LU (mtype 11) on the non-symmetric tangent equals SuperLU."""

    if not pardiso_available():
        pytest.skip("pypardiso not installed")
    pb = maxwell_plate(plate_mesh(4.0, 1.0, 2.0, 2, 1, 1), NeoHookeanDielectric(MU, EPS),
                      loading="uniaxial")
    x = 0.01 * np.random.default_rng(9).standard_normal(pb.red.n)
    K, r = pb.assemble(x, (1.0, 2.0))
    dx_lu = nonsymmetric_solver("pardiso").solve(K, r)
    dx_ref = nonsymmetric_solver("superlu").solve(K, r)
    # two direct solvers on a well-conditioned system agree to round-off x condition number
    np.testing.assert_allclose(dx_lu, dx_ref, rtol=1e-8, atol=1e-10 * np.abs(dx_ref).max())
    assert np.abs(K @ dx_lu - r).max() <= 1e-9 * np.abs(r).max()
