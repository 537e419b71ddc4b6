"""The root finders of analytic._roots on problems with known roots."""

import numpy as np
import pytest
from scipy.optimize import brentq

from analytic._roots import (
    brent,
    expand_bracket,
    first_root_on_scan,
    golden_section_max,
    illinois,
    rtsafe,
    scan_first_up,
)

C = np.array([0.5, 2.0, 3.0, 10.0, 1e3])
ROOTS = np.cbrt(C)  # roots of x^3 - c


def test_rtsafe_cube_roots():
    def f(x, i):
        return x**3 - C[i], 3 * x**2

    for kw in ({}, {"start_on_bracket": True, "width_every": 1}):
        x = rtsafe(f, np.zeros(C.size), C + 1.0, C + 1.0, **kw)
        np.testing.assert_allclose(x, ROOTS, rtol=4e-16)


def test_illinois_cube_roots():
    x = illinois(lambda x, i: C[i] - x**3, np.zeros(C.size), C + 1.0)
    np.testing.assert_allclose(x, ROOTS, rtol=1e-15)


def test_expand_bracket_finds_the_sign():
    x = expand_bracket(lambda x, i: x**3 - C[i], np.ones(C.size), np.inf, +1)
    assert np.all(x**3 - C > 0) and np.all((x[1:] / 2) ** 3 - C[1:] <= 0)  # x = 2^k
    x = expand_bracket(lambda x, i: x - 5.0, np.ones(2), np.array([2.0, 9.0]), +1)
    assert np.isnan(x[0]) and x[1] > 5.0


def test_scan_first_up_takes_the_first_crossing():
    # sin(x) - 0.5 on [0, 10]: first upward crossing at pi/6
    x = scan_first_up(lambda x, r: np.sin(x) - 0.5, np.zeros(2), np.array([10.0, 0.4]))
    np.testing.assert_allclose(x[0], np.pi / 6, rtol=1e-14)
    assert np.isnan(x[1])


def test_first_root_on_scan_takes_the_smallest_root():
    hi = np.array([10.0, 1.0])

    def scan(t):
        return np.cos(hi[:, None] * t[None, :])

    def gfun(idx, D0):
        return np.cos(D0)

    x = first_root_on_scan(scan, gfun, hi)
    np.testing.assert_allclose(x[0], np.pi / 2, rtol=1e-13)
    assert np.isnan(x[1])


@pytest.mark.parametrize("f", [lambda x: x**3 - 2, lambda x: np.cos(x) - x, lambda x: (x - 0.7) ** 3,
                               lambda x: np.tanh(5 * (x - 0.3)), lambda x: x**5 - x - 1])
def test_brent_is_scipy_brentq_step_for_step(f):
    rng = np.random.default_rng(1)
    n = 0
    for a, b in zip(rng.uniform(-3, 0.2, 200), rng.uniform(0.9, 4, 200)):
        if np.sign(f(a)) == np.sign(f(b)):
            continue
        n += 1
        ref = brentq(f, a, b, xtol=1e-15, rtol=1e-15, maxiter=200)
        assert brent(lambda x: float(f(x)), a, b, 1e-15, 1e-15, 200) == ref
    assert n > 50


def test_brent_errors():
    with pytest.raises(ValueError, match="different signs"):
        brent(lambda x: x * x + 1.0, 0.0, 1.0, 1e-15, 1e-15, 100)
    with pytest.raises(RuntimeError, match="no convergence"):
        brent(lambda x: x**3 - 2.0, 0.0, 2.0, 1e-15, 1e-15, 2)


def test_golden_section_max():
    fc, fd = golden_section_max(lambda x: -(x - 0.3) ** 2, 0.0, 1.0)
    assert max(fc, fd) > -1e-15
