"""Pseudo-arclength continuation: limit points of problems with closed forms."""

import math
import re
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse as sp

from skfem_dielectric.problem import Layout, Problem
from skfem_dielectric.solvers.continuation import ContinuationSettings, continuation
from skfem_dielectric.solvers.newton import NewtonSettings


class Truss(Problem):
    """Two-bar (von Mises) truss of half-span ``a``, apex height ``h``, axial stiffness
    ``EA``, linear in the bar strain; unknown: the apex deflection ``v`` under the downward
    load ``P``.  Internal force ``f(y) = 2 EA/L (L/l - 1) y`` with ``y = h - v``,
    ``l = sqrt(a^2 + y^2)``, ``L = l(h)``."""

    def __init__(self, a=1.0, h=0.5, EA=1.0):
        self.a, self.h, self.EA, self.L = a, h, EA, math.hypot(a, h)

    @property
    def layout(self):
        return Layout.single(1)

    def initial_state(self):
        return np.zeros(1)

    def assemble(self, x, load):
        y = self.h - x[0]
        l, L = math.hypot(self.a, y), self.L
        f = 2 * self.EA / L * (L / l - 1) * y
        df_dy = 2 * self.EA / L * (L * self.a ** 2 / l ** 3 - 1)
        return sp.csr_matrix(np.array([[-df_dy]])), np.array([f - float(load)])

    def closed_form_limit(self):
        """``dP/dy = 0``: ``(a^2 + y^2)^(3/2) = L a^2``."""
        a, L = self.a, self.L
        y = math.sqrt((L * a * a) ** (2 / 3) - a * a)
        return 2 * self.EA / L * (L / (L * a * a) ** (1 / 3) - 1) * y, self.h - y


class Pitchfork(Problem):
    """``r = (u1 - t, (1 - t) u2 + u2^3)``: the trivial branch ``u2 = 0`` loses stability
    at ``t = 1`` with the load still increasing (a branch point, no limit point)."""

    @property
    def layout(self):
        return Layout.single(2)

    def initial_state(self):
        return np.zeros(2)

    def assemble(self, x, load):
        t = float(load)
        K = np.array([[1.0, 0.0], [0.0, 1.0 - t + 3 * x[1] ** 2]])
        return sp.csr_matrix(K), np.array([x[0] - t, (1.0 - t) * x[1] + x[1] ** 3])


class WrongLoadVector(Pitchfork):
    def load_vector(self, x, load, h=1e-6):
        return np.zeros((3, 1))


def test_truss_passes_both_limit_points_and_returns_to_stable_branch():
    pb = Truss()
    P_max, v_max = pb.closed_form_limit()
    res = continuation(pb, 0.0, 1.0, stop=lambda p: p.x[0] > 1.3,
                       settings=ContinuationSettings(ds=0.05))
    assert res.converged, res.reason
    limits = [e for e in res.events if e.kind == "limit"]
    assert len(limits) == 2 and all(e.located for e in limits)
    up, down = res.limit_points
    # the corrector converges to atol 1e-10 and the limit to |dt/ds| <= 1e-9: the load
    # is at a maximum, so its error is second order in the location error
    assert up.t == pytest.approx(P_max, rel=1e-8)
    assert up.x[0] == pytest.approx(v_max, rel=1e-6)      # first order in the location
    # the path is point symmetric about v = h: the second limit load is -P_max at 2h - v*
    assert down.t == pytest.approx(-P_max, rel=1e-8)
    assert down.x[0] == pytest.approx(2 * pb.h - v_max, rel=1e-6)
    # stable (count 0) before the first and after the second limit point, unstable between
    assert limits[0].n_negative_before == 0 and limits[0].n_negative_after == 1
    assert limits[1].n_negative_before == 1 and limits[1].n_negative_after == 0
    last = res.points[-1]
    assert last.stable and last.tangent_t > 0 and last.x[0] > 2 * pb.h
    # every point is an equilibrium of the closed form: P = f(h - v)
    y = pb.h - np.array([p.x[0] for p in res.points])
    l = np.hypot(pb.a, y)
    np.testing.assert_allclose(res.column("t"), 2 / pb.L * (pb.L / l - 1) * y, atol=1e-10)


def test_bifurcation_is_reported_with_the_load_increasing():
    res = continuation(Pitchfork(), 0.0, 1.0, t_max=1.5, settings=ContinuationSettings(ds=0.1))
    assert [e.kind for e in res.events] == ["bifurcation"]
    ev = res.events[0]
    before = res.points[ev.index - 1]
    # the closed-form branch point t = 1 lies between the bracketing points
    assert before.t < 1.0 < ev.t
    assert (ev.n_negative_before, ev.n_negative_after) == (0, 1)
    assert np.all(res.column("tangent_t") > 0)


def test_bad_arguments():
    with pytest.raises(ValueError, match="direction"):
        continuation(Pitchfork(), 0.0, np.array([1.0, 0.0]))
    with pytest.raises(ValueError, match=r"^settings must be a ContinuationSettings, got "):
        continuation(Pitchfork(), 0.0, 1.0, settings=NewtonSettings())


@pytest.mark.parametrize("field, value", [
    ("ds", 0.0), ("ds", -0.1), ("ds", math.nan), ("ds_min", 0.0), ("ds_max", -1.0),
    ("max_steps", 0), ("max_steps", 2.5), ("predictor", "cubic"), ("increase", "yes"),
    ("target_iterations", 0), ("max_cutbacks", -1), ("max_angle", 0.0), ("locate", 1),
    ("locate_tol", -1e-9), ("corrector", {"max_iter": 15}),
])
def test_continuation_settings_name_the_bad_field(field, value):
    with pytest.raises(ValueError, match=rf"^{field} must .*got {re.escape(repr(value))}$"):
        ContinuationSettings(**{field: value})


def test_step_bounds_follow_ds_unless_given():
    # ds_min = ds 1e-4 and ds_max = 8 ds by default: scaled with ds by a replace
    coarse = replace(ContinuationSettings(), ds=0.5)
    assert coarse.step_bounds == (0.5e-4, 4.0)
    assert ContinuationSettings(ds=0.5, ds_min=0.01, ds_max=1.0).step_bounds == (0.01, 1.0)


def test_max_steps_of_the_settings_ends_the_path():
    # the pitchfork's trivial branch (u1 = t, u2 = 0) has no stop before t_max: max_steps = 3
    # ends it after the start and three steps of arclength ds = ds_max = 0.1.  In the metric
    # W = 1/2 on both unknowns a step dt has arclength sqrt(1/2 + 1) dt, so t = 3 ds / sqrt(1.5)
    res = continuation(Pitchfork(), 0.0, 1.0, t_max=1.5,
                       settings=ContinuationSettings(ds=0.1, ds_max=0.1, max_steps=3))
    assert res.converged and res.reason == "max_steps = 3 reached"
    assert len(res.points) == 4
    # the branch is linear: each corrector lands on it to round-off
    assert res.points[-1].t == pytest.approx(0.3 / math.sqrt(1.5), rel=1e-12)


def test_load_vector_of_wrong_size():
    with pytest.raises(ValueError, match=r"load_vector of WrongLoadVector must have shape"):
        continuation(WrongLoadVector(), 0.0, 1.0)


def test_problem_without_the_contract():
    class NotAProblem:
        def assemble(self, x, load):
            return sp.eye(1), x

    with pytest.raises(ValueError, match="problem must be a skfem_dielectric.Problem"):
        continuation(NotAProblem(), 0.0, 1.0)


@pytest.mark.parametrize("count", [42, "yes", None])
def test_continuation_names_a_count_that_is_neither_a_bool_nor_callable(count):
    calls = []

    class Watched(Truss):
        def assemble(self, x, load):
            calls.append(load)
            return super().assemble(x, load)

    with pytest.raises(ValueError, match=r"^count must be True, False or a callable "
                       r"count\(x, load\), got " + repr(count).replace("(", r"\(") + "$"):
        continuation(Watched(), 0.0, 1.0, count=count)
    assert calls == []    # rejected before the first assembly
