"""The cause a plate ramp reports when Newton fails: quadrature-point extremes of a state
against the homogeneous closed form, and the step-limit count against the ramp's own
iteration count."""

import warnings

import numpy as np
import pytest
from scipy.optimize import brentq

from skfem_dielectric import RampSettings
from skfem_dielectric.gallery.drivers import equibiaxial_problem, run_ramp
from skfem_dielectric.models.plate.failure import StepLimitCounter, plate_failure_cause


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
    X = np.array(f["S33_at"])
    # the reported corner distance is that of the reported point (eighth model of the
    # 4 x 1 x 4 plate: corners at |x1| = |x3| = 2), in thicknesses (H = 1); round-off only
    assert abs(f["S33_corner_distance"] - np.hypot(abs(X[0]) - 2.0, abs(X[2]) - 2.0)) < 1e-12
    # every Newton step of the failed attempt asked the step limit once: the failed
    # attempt's iterations are the ramp's total less those of the converged step
    assert f["newton_steps"] == res.iterations_total - res.steps[0].iterations
    assert 0 <= f["step_limited"] <= f["newton_steps"]
    assert res.reason.startswith("target load") and "min det F = 1" in res.reason
