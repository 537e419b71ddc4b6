"""Generic Newton / ramp machinery on small problems with closed-form solutions."""

import sys
import warnings

import numpy as np
import pytest
import scipy.sparse as sp

from skfem_dielectric import (Layout, NewtonSettings, Problem, RampResult, RampSettings,
                              StepResult, newton, ramp)
from skfem_dielectric.linalg.linear import get_linear_solver, pardiso_available


class Cubic(Problem):
    """r_i(x) = x_i^3 + x_i - t c_i  (decoupled cubics, root by Cardano)."""

    c = np.array([1.0, 2.0, 5.0])
    layout = Layout.single(3)

    def initial_state(self):
        return np.zeros(3)

    def assemble(self, x, load):
        return sp.diags(3 * x**2 + 1).tocsr(), x**3 + x - load * self.c

    def residual_scale(self, load):
        return 1.0

    def postprocess(self, x, load):
        return {"x2": x[2]}


def cardano(q):
    # real root of x^3 + x - q = 0
    d = np.sqrt(q**2 / 4 + 1 / 27)
    return np.cbrt(q / 2 + d) + np.cbrt(q / 2 - d)


def test_newton_quadratic_convergence_to_cardano_root():
    prob = Cubic()
    res = newton(lambda x: prob.assemble(x, 2.0), np.full(3, 0.5),
                 settings=NewtonSettings(atol=1e-14, rtol=0))
    assert res.converged
    # Root to round-off: Newton stops at ||r|| <= 1e-14, |dx| ~ |r| / (3x^2+1).
    np.testing.assert_allclose(res.x, cardano(2.0 * prob.c), rtol=1e-13)
    r = np.array(res.residual_norms)
    # quadratic convergence: r_{k+1} <= C r_k^2 once r_k < 1 (C ~ 3x/(3x^2+1)^2 < 1 here)
    late = r[:-1] < 0.1
    assert np.all(r[1:][late] <= 2.0 * r[:-1][late] ** 2)


@pytest.mark.parametrize("solver", ["superlu"] + (["pardiso"] if pardiso_available() else []))
def test_ramp_resume_is_bitwise_identical(solver):
    prob = Cubic()
    loads = [1.0, 4.0, 9.0, 20.0]
    full = ramp(prob, loads, linear_solver=solver, settings=RampSettings(atol=1e-12, rtol=0))
    assert full.converged
    np.testing.assert_allclose(full.column("x2"), cardano(5.0 * np.array(loads)), rtol=1e-11)
    part = ramp(prob, loads[2:], x0=full.steps[1].x, start=full.steps[1].load,
                back=full.steps[1].back, linear_solver=solver,
                settings=RampSettings(atol=1e-12, rtol=0))
    if solver == "superlu":  # deterministic; PARDISO (threads) may differ in the last bit
        assert np.array_equal(part.steps[-1].x, full.steps[-1].x)
    np.testing.assert_allclose(part.steps[-1].x, full.steps[-1].x, rtol=1e-14)


class NoRootBeyondOne(Problem):
    """r(x) = x^2 + (t - 1): real roots only while t <= 1; ramp must stop at t = 1."""

    layout = Layout.single(1)

    def initial_state(self):
        return np.array([2.0])

    def assemble(self, x, load):
        return sp.csr_matrix([[2 * x[0]]]), np.array([x[0] ** 2 + load - 1.0])

    def residual_scale(self, load):
        return 1.0


def test_ramp_failure_keeps_converged_steps_and_warns():
    seen = []
    with pytest.warns(RuntimeWarning, match="not reached"):
        out = ramp(NoRootBeyondOne(), [0.5, 0.9, 1.5, 2.0], on_step=seen.append,
                   settings=RampSettings(max_cutbacks=4, atol=1e-12, rtol=0))
    assert not out.converged
    reached = [st for st in out.steps if st.target_reached]
    assert [st.load for st in reached] == [0.5, 0.9] and len(seen) == len(out.steps)
    # root sqrt(1 - t) of every converged step, including the furthest sub-step on the
    # way to the unreachable target 1.5 (kept with target_reached=False)
    np.testing.assert_allclose([st.x[0] for st in out.steps],
                               np.sqrt([1 - st.load for st in out.steps]), rtol=1e-8)
    partial = out.steps[2:]
    assert len(partial) == 1 and 0.9 < partial[0].load <= 1.0
    # the failed sub-step lies beyond the last root (t = 1), within 4 halvings of 0.9
    assert 1.0 < out.failed_at <= 1.5 and out.reason


def test_bad_inputs():
    with pytest.raises(ValueError, match="linear solver"):
        get_linear_solver("mumps")
    with pytest.raises(ValueError, match="finite"):
        ramp(Cubic(), [1.0, np.nan])


def test_ramp_column_unknown_name_is_a_clear_error():
    # A quantity name that the problem does not post-process must name itself and the
    # available names (a KeyError deep in a list comprehension helps nobody).

    st = StepResult(load=np.array([1.0]), converged=True, iterations=2, substeps=1, cutbacks=0,
                    residual_norms=[[1.0, 1e-12]], x=np.zeros(1), quantities={"lam1": 1.5})
    res = RampResult(steps=[st], converged=True)
    assert res.column("lam1") == pytest.approx([1.5], rel=0, abs=0)
    with pytest.raises(ValueError, match="'lam'"):
        res.column("lam")


class DenseInertiaSolver:
    """Dense solve that reports the inertia from the eigenvalues (an independent check of
    the ramp's stop rule; PARDISO reports it from its LDL^T pivots)."""

    name = "dense"

    def solve(self, K, b):
        A = K.toarray()
        ev = np.linalg.eigvalsh(A)
        self.inertia = (int(np.sum(ev > 0)), int(np.sum(ev < 0)), int(np.sum(ev == 0)))
        self._A = A
        return np.linalg.solve(A, b)

    def resolve(self, b):
        return np.linalg.solve(self._A, b)


class SoftensAt(Problem):
    """x1^3 + x1 = t (always stiff) and (1 - t/t_c) x2 = 0: the trivial branch x2 = 0 of
    the second dof loses stability (negative stiffness) beyond t_c, Newton still converges."""

    t_c = 2.5
    layout = Layout.single(2)

    def initial_state(self):
        return np.zeros(2)

    def assemble(self, x, load):
        k2 = 1.0 - load / self.t_c
        return (sp.diags([3 * x[0] ** 2 + 1, k2]).tocsr(),
                np.array([x[0] ** 3 + x[0] - load, k2 * x[1]]))

    def residual_scale(self, load):
        return 1.0

    def postprocess(self, x, load):
        return {"x1": x[0]}

    def stability(self, inertia):
        return None if inertia is None else inertia[1] == 0


def test_ramp_stops_at_the_first_unstable_step():
    loads = [1.0, 2.0, 3.0, 4.0]
    with pytest.warns(RuntimeWarning, match="stability lost"):
        res = ramp(SoftensAt(), loads, linear_solver=DenseInertiaSolver(),
                   settings=RampSettings(atol=1e-13, rtol=0, stop_on_instability=True))
    assert not res.converged and res.unstable_at == 3.0 and res.failed_at is None
    assert [st.load for st in res.steps] == [1.0, 2.0, 3.0]
    assert [st["stable"] for st in res.steps] == [True, True, False]
    assert res.steps[-1].target_reached
    np.testing.assert_allclose(res.column("x1"), cardano(np.array(loads[:3])), rtol=1e-12)
    # per-call timings add up to the totals
    assert len(res.assembly_times) == res.assembly_calls
    assert np.isclose(sum(res.solve_times), res.solve_seconds)
    # without the option the ramp goes on through the unstable states
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = ramp(SoftensAt(), loads, linear_solver=DenseInertiaSolver(),
                   settings=RampSettings(atol=1e-13, rtol=0))
    assert res.converged and [st["stable"] for st in res.steps] == [True, True, False, False]


def test_stop_on_instability_without_inertia_warns_and_goes_on():
    # SuperLU reports no inertia: no verdict, the option cannot act and says so
    with pytest.warns(RuntimeWarning, match="no effect"):
        res = ramp(SoftensAt(), [1.0, 2.0, 3.0], linear_solver="superlu",
                   settings=RampSettings(atol=1e-13, rtol=0, stop_on_instability=True))
    assert res.converged and res.unstable_at is None
    np.testing.assert_allclose(res.column("x1"), cardano(np.array([1.0, 2.0, 3.0])),
                               rtol=1e-12)


def test_newton_step_limit_and_admissible_state():
    """A step limit caps the first trial at alpha_max / 2; a converged state that the
    admissibility check rejects is not reported as converged."""
    prob = Cubic()
    free = newton(lambda x: prob.assemble(x, 2.0), np.zeros(3),
                  settings=NewtonSettings(atol=1e-12, rtol=0))
    seen = []

    def limit(x, dx):
        seen.append(float(np.max(np.abs(dx))))
        return 0.5 if len(seen) == 1 else 1.0

    capped = newton(lambda x: prob.assemble(x, 2.0), np.zeros(3),
                    settings=NewtonSettings(atol=1e-12, rtol=0),
                    step_limit=limit)
    assert capped.converged and np.allclose(capped.x, free.x, atol=1e-11)
    assert capped.step_norms[0] == pytest.approx(0.25 * np.linalg.norm(2.0 * prob.c))
    stuck = newton(lambda x: prob.assemble(x, 2.0), np.zeros(3),
                   settings=NewtonSettings(atol=1e-12, rtol=0),
                   step_limit=lambda x, dx: 0.0)
    assert not stuck.converged and "inadmissible Newton step" in stuck.reason
    rejected = newton(lambda x: prob.assemble(x, 2.0), np.zeros(3),
                      settings=NewtonSettings(atol=1e-12, rtol=0),
                      admissible=lambda x: "x2 too large" if x[2] > 1 else "")
    assert not rejected.converged and rejected.reason.endswith("x2 too large")
    with pytest.raises(ValueError, match="atol and rtol must not both be 0"):
        newton(lambda x: prob.assemble(x, 2.0), np.zeros(3),
               settings=NewtonSettings(atol=0.0, rtol=0.0))


@pytest.mark.parametrize("solver", ["superlu"] + (["pardiso"] if pardiso_available() else []))
def test_chord_steps_reach_the_same_root_with_fewer_factorisations(solver):
    prob = Cubic()
    x0 = np.full(3, 0.5)
    plain = newton(lambda x: prob.assemble(x, 2.0), x0,
                   settings=NewtonSettings(atol=1e-13, rtol=0),
                   linear_solver=solver)
    chord = newton(lambda x: prob.assemble(x, 2.0), x0,
                   settings=NewtonSettings(atol=1e-13, rtol=0, chord=0.3),
                   residual=lambda x: prob.assemble(x, 2.0)[1], linear_solver=solver)
    ref = cardano(2.0 * prob.c)
    for res in (plain, chord):
        assert res.converged
        # |r| <= 1e-13 and r' = 3x^2 + 1 >= 1: the root to 1e-13
        np.testing.assert_allclose(res.x, ref, rtol=0, atol=1e-13)
    # plain Newton factorises in every iteration; the chord run reuses factors
    assert plain.factorisations == plain.iterations and plain.chord_steps == 0
    assert chord.chord_steps >= 1
    assert chord.factorisations + chord.chord_steps == chord.iterations
    assert chord.factorisations < plain.factorisations
    # a chord step contracts the residual by at least the chord factor, or it is the
    # last one before a new factorisation
    r = np.array(chord.residual_norms)
    assert np.all(r[1:] < r[:-1])


def test_secant_predictor_ramp_matches_cardano_with_fewer_iterations():
    prob = Cubic()
    loads = np.linspace(1.0, 8.0, 8)
    plain = ramp(prob, loads, settings=RampSettings(atol=1e-12, rtol=0, predictor="none"))
    pred = ramp(prob, loads,
                settings=RampSettings(atol=1e-12, rtol=0, predictor="secant", chord=0.1))
    ref = cardano(5.0 * loads)
    for res in (plain, pred):
        assert res.converged
        np.testing.assert_allclose(res.column("x2"), ref, rtol=0, atol=1e-12)
    assert pred.factorisations < plain.factorisations
    assert pred.column("factorisations").sum() == pred.factorisations
    assert plain.factorisations == plain.iterations_total


def test_secant_is_the_default_and_resume_needs_its_second_point():
    # the secant start of the step after a resume depends on the state before x0: with
    # back (StepResult.back) the resumed ramp repeats the uninterrupted one bit for bit,
    # without it only within the Newton tolerance; each step's back is the previous step
    prob = Cubic()
    loads = [1.0, 2.0, 3.0, 4.0, 5.0]
    assert RampSettings().predictor == "secant"
    settings = RampSettings(atol=1e-10, rtol=0)
    full = ramp(prob, loads, settings=settings)
    assert full.steps[0].back is None
    for before, st in zip(full.steps, full.steps[1:]):
        assert st.substeps == 1 and st.back[0] is not None
        assert np.array_equal(st.back[0], before.x) and st.back[1] == before.load
    part = ramp(prob, loads[2:], x0=full.steps[1].x, start=full.steps[1].load,
                back=full.steps[1].back, settings=settings)
    assert all(np.array_equal(a.x, b.x) for a, b in zip(part.steps, full.steps[2:]))
    cold = ramp(prob, loads[2:], x0=full.steps[1].x, start=full.steps[1].load,
                settings=settings)
    np.testing.assert_allclose(cold.steps[-1].x, full.steps[-1].x, rtol=0, atol=1e-9)
    np.testing.assert_allclose(full.column("x2"), cardano(5.0 * np.array(loads)), atol=1e-10)
    with pytest.raises(ValueError, match="back given without x0"):
        ramp(prob, loads, back=full.steps[1].back)
    with pytest.raises(ValueError, match="back must be a pair"):
        ramp(prob, loads[2:], x0=full.steps[1].x, start=2.0, back=full.steps[1].x)
    with pytest.raises(ValueError, match="back must be a finite vector of length 3"):
        ramp(prob, loads[2:], x0=full.steps[1].x, start=2.0, back=(np.zeros(2), 1.0))


class Parabola(Problem):
    """r_i(x) = x_i + x_i^3 - (t^2 c_i + (t^2 c_i)^3): the root x_i = t^2 c_i, a parabola
    in the load (nonlinear in x, so that Newton needs iterations from any other start)."""

    c = np.array([0.1, 0.2, 0.3])
    layout = Layout.single(3)

    def initial_state(self):
        return np.zeros(3)

    def assemble(self, x, load):
        q = load**2 * self.c
        return sp.diags(1 + 3 * x**2).tocsr(), x + x**3 - (q + q**3)

    def residual_scale(self, load):
        return 1.0

    def postprocess(self, x, load):
        return {"x2": x[2]}


def test_quadratic_predictor_is_exact_on_a_parabola_and_resumes_bit_for_bit():
    # three converged states on a path x(t) = t^2 c: the parabola through them is the path
    # itself, so from the fourth step on each solve starts at the root (within the
    # tolerance of the three states, amplified by the weights 1, -3, 3), where the secant
    # start misses it by h^2 c = 0.3 (x2) and needs iterations
    prob = Parabola()
    loads = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    quad = ramp(prob, loads, settings=RampSettings(atol=1e-12, rtol=0, predictor="quadratic"))
    sec = ramp(prob, loads, settings=RampSettings(atol=1e-12, rtol=0, predictor="secant"))
    for res in (quad, sec):
        assert res.converged
        np.testing.assert_allclose(res.column("x2"), 0.3 * np.array(loads) ** 2, atol=1e-12)
    first = [st.residual_norms[0][0] for st in quad.steps[3:]]
    assert max(first) < 1e-10 and all(st.iterations <= 1 for st in quad.steps[3:])
    assert min(st.residual_norms[0][0] for st in sec.steps[3:]) > 0.1
    assert all(st.iterations >= 3 for st in sec.steps[3:])
    # each step's back2 is the step before its back
    assert quad.steps[1].back2 is None
    for older, st in zip(quad.steps[1:], quad.steps[3:]):
        assert np.array_equal(st.back2[0], older.x) and st.back2[1] == older.load
    # resumed with back and back2: bit for bit; without back2 the first step is the secant's
    kw = dict(x0=quad.steps[2].x, start=quad.steps[2].load, back=quad.steps[2].back,
              settings=RampSettings(atol=1e-12, rtol=0, predictor="quadratic"))
    part = ramp(prob, loads[3:], back2=quad.steps[2].back2, **kw)
    assert all(np.array_equal(a.x, b.x) for a, b in zip(part.steps, quad.steps[3:]))
    cold = ramp(prob, loads[3:], **kw)
    assert cold.steps[0].residual_norms[0][0] > 0.1 and cold.steps[1].residual_norms[0][0] < 1e-10
    with pytest.raises(ValueError, match="back2 must be a pair"):
        ramp(prob, loads[3:], back2=quad.steps[2].x, **kw)


def test_chord_and_predictor_bad_input():
    prob = Cubic()
    with pytest.raises(ValueError, match="chord must be in"):
        NewtonSettings(chord=1.0)
    with pytest.raises(ValueError, match="chord"):
        RampSettings(chord=-0.1)
    with pytest.raises(ValueError, match="predictor"):
        RampSettings(predictor="cubic")
    with pytest.raises(ValueError, match="factor_precision"):
        RampSettings(factor_precision="half")
    # a ramp needs its cut-back and predictor rules: plain Newton settings are not enough
    with pytest.raises(ValueError, match="settings must be a RampSettings"):
        ramp(prob, [1.0], settings=NewtonSettings())
    with pytest.raises(ValueError, match="settings must be a NewtonSettings"):
        newton(lambda x: prob.assemble(x, 1.0), np.zeros(3), settings={"rtol": 1e-9})


def test_ramp_settings_reach_every_newton_solve():
    # From x = 0 the Cubic root at load 20 needs more than two Newton iterations, so with
    # max_iter = 2 and no cut-back the first target fails, with the Newton reason; with the
    # default budget the same ramp reaches Cardano's root to the absolute tolerance.
    prob, c = Cubic(), Cubic.c
    tight = RampSettings(atol=1e-12, rtol=0, max_iter=2, max_cutbacks=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        short = ramp(prob, [20.0], settings=tight)
    assert not short.converged and short.iterations_total == 2
    assert "no convergence in 2 iterations" in short.reason
    assert "after 0 cut-backs" in short.reason
    full = ramp(prob, [20.0], settings=RampSettings(atol=1e-12, rtol=0, max_cutbacks=0))
    assert full.converged and full.steps[0].substeps == 1
    # ||r|| <= 1e-12 and |dr/dx| = 3x^2 + 1 >= 1: the root to 1e-12
    np.testing.assert_allclose(full.steps[0].x, cardano(20.0 * c), rtol=0, atol=1e-12)


@pytest.mark.parametrize("solver", ["superlu"] + (["pardiso"] if pardiso_available() else []))
def test_old_factors_are_discarded_before_a_tangent_to_factorise(solver, monkeypatch):
    # with chord steps the tangent is assembled only to be factorised: the solver's old
    # factors of a large system are freed before each such assembly (never before a chord
    # step), and the iterations are those of a solver that keeps them; a small system's
    # are kept (the next factorisation reuses their memory)
    newton_module = sys.modules[newton.__module__]
    prob = Cubic()
    events = []

    class Watched(type(get_linear_solver(solver))):
        def discard(self):
            events.append("discard")
            super().discard()

        def solve(self, K, b):
            events.append("solve")
            return super().solve(K, b)

        def resolve(self, b):
            out = super().resolve(b)
            events.append("resolve" if out is not None else "none")
            return out

    def assemble(x):
        events.append("assemble")
        return prob.assemble(x, 2.0)

    kw = dict(settings=NewtonSettings(atol=1e-13, rtol=0, chord=0.3),
              residual=lambda x: prob.assemble(x, 2.0)[1])
    small = newton(assemble, np.full(3, 0.5), linear_solver=Watched(), **kw)
    assert small.converged and small.factorisations >= 2 and "discard" not in events
    events.clear()
    monkeypatch.setattr(newton_module, "TRIM_MIN_UNKNOWNS", 3)     # 3 unknowns: large
    res = newton(assemble, np.full(3, 0.5), linear_solver=Watched(), **kw)
    ref = newton(lambda x: prob.assemble(x, 2.0), np.full(3, 0.5),
                 linear_solver=get_linear_solver(solver), **kw)
    assert res.converged and np.array_equal(res.x, ref.x) and np.array_equal(small.x, ref.x)
    assert res.chord_steps == ref.chord_steps >= 1 and "none" not in events
    seq = " ".join(events)
    assert seq.count("discard assemble solve") == res.factorisations
    # a discarded solver has no factors to reuse until it factorises again
    s = Watched()
    s.solve(sp.identity(3, format="csr"), np.ones(3))
    s.discard()
    assert s.resolve(np.ones(3)) is None
    s.discard()                                            # nothing to free: no error
    np.testing.assert_allclose(s.solve(2 * sp.identity(3, format="csr"), np.ones(3)), 0.5)
    np.testing.assert_allclose(s.resolve(np.ones(3)), 0.5)


@pytest.mark.parametrize("returned, what", [
    (None, "None"),
    (np.zeros(3), "array"),
    ((sp.identity(3, format="csr"),), r"\(<"),
])
def test_newton_says_what_assemble_must_return(returned, what):
    calls = []

    def assemble(x):
        calls.append(x)
        return returned

    with pytest.raises(ValueError, match=r"^assemble\(x\) must return a \(K, r\) pair "
                       r"\(sparse tangent dr/dx of shape \(3, 3\) and residual of shape "
                       r"\(3,\)\), got " + what):
        newton(assemble, np.full(3, 0.5))
    assert len(calls) == 1    # reported at the first evaluation, no Newton step taken


def test_newton_names_a_residual_of_the_wrong_shape():
    prob = Cubic()
    with pytest.raises(ValueError, match=r"^assemble\(x\) must return the residual as a "
                       r"real array of shape \(3,\) \(one entry per unknown of x\), got "
                       r"ndarray of shape \(2,\)"):
        newton(lambda x: (prob.assemble(x, 2.0)[0], np.ones(2)), np.full(3, 0.5))
    with pytest.raises(ValueError, match=r"^assemble\(x\) must return a \(K, r\) pair whose "
                       r"tangent K has shape \(3, 3\), got K = None"):
        newton(lambda x: (None, prob.assemble(x, 2.0)[1]), np.full(3, 0.5))
    # a residual-only evaluation is checked the same way
    with pytest.raises(ValueError, match=r"^residual must return the residual as a real "
                       r"array of shape \(3,\)"):
        newton(lambda x: prob.assemble(x, 2.0), np.full(3, 0.5), residual=lambda x: None,
               settings=NewtonSettings(chord=0.3))


def test_newton_accepts_a_list_pair_from_assemble():
    # [K, r] is a pair too: the same iterates as the tuple, root to round-off as in
    # test_newton_quadratic_convergence_to_cardano_root
    prob = Cubic()
    res = newton(lambda x: list(prob.assemble(x, 2.0)), np.full(3, 0.5),
                 settings=NewtonSettings(atol=1e-14, rtol=0))
    np.testing.assert_allclose(res.x, cardano(2.0 * prob.c), rtol=1e-13)


def test_a_stop_predicate_ends_the_ramp_as_a_result():
    """``stop`` asked at every converged target: the ramp ends after the first target it
    accepts (``stopped_at``, ``converged``: every step it took converged), no later target
    is attempted, and the steps taken equal the unstopped ramp's bit for bit; a stop that
    is not callable is a ValueError naming it."""
    prob = Cubic()
    loads = [1.0, 4.0, 9.0, 20.0]
    settings = RampSettings(atol=1e-12, rtol=0)
    full = ramp(prob, loads, settings=settings)
    asked = []

    def past_two(step):
        asked.append(step.load)
        return step.quantities["x2"] > cardano(5.0 * 2.0)

    res = ramp(prob, loads, settings=settings, stop=past_two)
    assert res.converged and res.stopped_at == 4.0 and asked == [1.0, 4.0]
    assert [s.load for s in res.steps] == [1.0, 4.0]
    for a, b in zip(res.steps, full.steps):
        assert np.array_equal(a.x, b.x)
    assert full.stopped_at is None
    with pytest.raises(ValueError, match="stop"):
        ramp(prob, loads, stop=1.0)


@pytest.mark.parametrize("m, bound", [(0, None), (6, 7)])
def test_accelerated_chord_steps_are_gmres_on_a_linear_problem(m, bound):
    # A x = b on the factors of K0 = A - E: plain chord steps contract by the spectral
    # radius of K0^-1 E (0.37 here) per step; with Anderson depth m >= n they are
    # GMRES preconditioned by K0, exact after at most n + 1 steps (finite termination)
    rng = np.random.default_rng(3)
    n = 6
    A = np.diag(np.linspace(2.0, 4.0, n)) + 0.1 * rng.standard_normal((n, n))
    E = 0.2 * np.diag(rng.uniform(2.0, 3.0, n))
    K0 = A - E
    b = rng.standard_normal(n)
    rho = max(abs(np.linalg.eigvals(np.linalg.solve(K0, E))))
    assert 0.3 < rho < 0.5
    solver = get_linear_solver("superlu")
    solver.solve(sp.csr_matrix(K0), np.zeros(n))          # the old factors at hand
    res = newton(lambda x: (sp.csr_matrix(A), A @ x - b), np.zeros(n),
                 residual=lambda x: A @ x - b, linear_solver=solver, reuse_factors=True,
                 settings=NewtonSettings(atol=1e-11, rtol=0, chord=0.95, acceleration=m,
                                         max_iter=200))
    assert res.converged, res.reason
    np.testing.assert_allclose(res.x, np.linalg.solve(A, b), rtol=0, atol=1e-10)
    assert res.factorisations == 0 and res.chord_steps == res.iterations
    if bound is None:       # linear rate rho: log(1e-11 / ||b||) / log(rho) steps at least
        assert res.iterations >= np.log(1e-11 / np.linalg.norm(b)) / np.log(rho) - 1
    else:
        assert res.iterations <= bound


def test_kept_factors_cut_factorisations_and_resume_bit_for_bit():
    prob = Cubic()
    loads = list(np.linspace(1.0, 8.0, 8))
    base = RampSettings(atol=1e-12, rtol=0, chord=0.5)
    plain = ramp(prob, loads, settings=base)
    kept = ramp(prob, loads, settings=RampSettings(atol=1e-12, rtol=0, chord=0.5,
                                                   acceleration=3, keep_factors=True))
    for res in (plain, kept):
        assert res.converged
        np.testing.assert_allclose(res.column("x2"), cardano(5.0 * np.array(loads)),
                                   rtol=0, atol=1e-12)
    assert kept.factorisations < plain.factorisations
    # each step records the state whose tangent its factors are of (only when kept)
    assert all(st.factors is None for st in plain.steps)
    assert all(st.factors is not None and len(st.factors) == 2 for st in kept.steps)
    saved = kept.steps[3]
    part = ramp(prob, loads[4:], x0=saved.x, start=saved.load, back=saved.back,
                factors=saved.factors, settings=kept_settings(saved))
    assert all(np.array_equal(a.x, b.x) for a, b in zip(part.steps, kept.steps[4:]))
    assert part.factorisations == 1 + sum(st.factorisations for st in kept.steps[4:])
    with pytest.raises(ValueError, match="factors given without x0"):
        ramp(prob, loads, factors=saved.factors, settings=kept_settings(saved))
    with pytest.raises(ValueError, match="factors must be a pair"):
        ramp(prob, loads[4:], x0=saved.x, start=saved.load, factors=saved.x,
             settings=kept_settings(saved))
    with pytest.raises(ValueError, match="acceleration"):
        NewtonSettings(acceleration=-1)
    with pytest.raises(ValueError, match="keep_factors must be True or False"):
        RampSettings(keep_factors="yes")


def kept_settings(_step):
    """The settings of the kept-factors ramp above (a resume repeats them)."""
    return RampSettings(atol=1e-12, rtol=0, chord=0.5, acceleration=3, keep_factors=True)
