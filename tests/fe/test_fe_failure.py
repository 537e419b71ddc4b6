"""The cause a plate ramp reports when Newton fails: quadrature-point extremes of a state
against the homogeneous closed form, and the step-limit count against the ramp's own
iteration count."""

import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

from skfem_dielectric import RampSettings
from skfem_dielectric.gallery.drivers import equibiaxial_problem, keplinger_problem, run_ramp
from skfem_dielectric.models.plate.failure import StepLimitCounter


def test_step_limit_counter_counts_the_shortened_steps():
    fractions = iter([1.0, 0.3, 1.0, 0.05, 0.7])
    counter = StepLimitCounter(lambda x, dx, load: next(fractions))
    got = [counter(None, None, None) for _ in range(5)]
    assert got == [1.0, 0.3, 1.0, 0.05, 0.7]
    # three of the five fractions are below one, the smallest is 0.05
    assert (counter.calls, counter.limited, counter.smallest) == (5, 3, 0.05)
    counter.reset()
    assert (counter.calls, counter.limited, counter.smallest) == (0, 0, 1.0)
    with pytest.raises(ValueError, match="step_limit"):
        StepLimitCounter(1.0)


def test_failed_plate_ramp_reports_the_state_it_stopped_at():
    s = 0.5
    pb = equibiaxial_problem()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        # a charge jump to D0 = 50 in one step with no cut-back cannot converge in 4
        # iterations: the ramp stops with the pre-loaded state as its last step
        res = run_ramp(pb, [np.array([s, 0.0]), np.array([s, 50.0])], linear_solver="superlu",
                       settings=RampSettings(max_cutbacks=0, max_iter=4, atol=0.0, rtol=1e-11))
    assert not res.converged and len(res.steps) == 1
    f = res.failure
    # the pre-loaded state is homogeneous: equi-biaxial lam - lam^-5 = s (Eq. (loading_gent)
    # at D0 = 0), J = 1, and the lateral second Piola stress S33 = s / lam
    lam = brentq(lambda L: L - L**-5 - s, 1.0, 3.0, xtol=1e-15)
    # mixed form, homogeneous state: exact up to the Newton tolerance (rtol 1e-11)
    assert abs(f["min_J"] - 1.0) < 1e-9
    assert abs(f["S33"] - s / lam) < 1e-9
    # the equi-biaxial plate has dead tractions on all lateral faces, no clamp: no corner
    # distance, and the reason gives the positions of the extremes
    assert f["min_J_corner_distance"] is None and f["S33_corner_distance"] is None
    where = "(" + ", ".join(f"{v:.3g}" for v in f["S33_at"]) + ")"
    assert f"S33/mu = {f['S33']:.3g} at {where}" in res.reason
    assert "corner" not in res.reason
    # every Newton step of the failed attempt asked the step limit once: the failed
    # attempt's iterations are the ramp's total less those of the converged step
    assert f["newton_steps"] == res.iterations_total - res.steps[0].iterations
    assert 0 <= f["step_limited"] <= f["newton_steps"]
    assert res.reason.startswith("target load") and "min det F = 1" in res.reason


def _forced_failure(pb, first, max_iter):
    """Ramp ``pb`` to ``first``, then jump to ``D0 = 50`` with no cut-back: the jump fails."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return run_ramp(pb, [np.array(first), np.array([first[0], 50.0])],
                        linear_solver="superlu",
                        settings=RampSettings(max_cutbacks=0, max_iter=max_iter, atol=0.0,
                                              rtol=1e-11))


def test_failed_clamped_plate_ramp_reports_the_corner_distances():
    # 8 x 1 x 4 Keplinger plate, eighth model of 2 x 1 x 2 elements: the pre-load s = 0.5
    # converges in 4 iterations, the jump to D0 = 50 does not
    pb = keplinger_problem(size=(8.0, 1.0, 4.0), elements=(2, 1, 2))
    res = _forced_failure(pb, [0.5, 0.0], 4)
    assert not res.converged and len(res.steps) == 1
    f = res.failure
    for key in ("min_J", "S33"):
        X = np.array(f[f"{key}_at"])
        # the clamp x1 = 4 meets the free edge x3 = 2; distance in thicknesses (H = 1) of
        # the reported point, round-off only
        d = np.hypot(abs(X[0]) - 4.0, abs(X[2]) - 2.0)
        assert abs(f[f"{key}_corner_distance"] - d) < 1e-12
    assert (f"min det F = {f['min_J']:.3g} ({f['min_J_corner_distance']:.2g} thicknesses "
            f"from a clamp/free-edge corner)") in res.reason


@pytest.mark.parametrize("clamped", [False, True])
def test_failure_at_the_unloaded_state_reports_its_stress_free_point(clamped):
    # the ramp stops with the unloaded state (0 iterations) as its last converged step: it is
    # stress free, S33 = 0 and det F = 1 at every quadrature point, exactly
    pb = (keplinger_problem(size=(8.0, 1.0, 4.0), elements=(2, 1, 2)) if clamped
          else equibiaxial_problem())
    res = _forced_failure(pb, [0.0, 0.0], 1)
    assert not res.converged and len(res.steps) == 1 and res.steps[0].iterations == 0
    f = res.failure
    assert f["S33"] == 0.0 and abs(f["min_J"] - 1.0) < 1e-14   # det of the identity
    assert len(f["S33_at"]) == 3
    assert ("clamp/free-edge corner" in res.reason) == clamped
    assert (f["S33_corner_distance"] is None) == (not clamped)
