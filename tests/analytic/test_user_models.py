"""User strain energies are probed on construction: a callable returning nan, None, inf,
a wrong shape, or an energy with W'(3) != mu/2 is a ValueError naming the problem."""

import re

import numpy as np
import pytest

import analytic as an
import skfem_dielectric as sd


def ok_W(I):
    return 0.5 * (I - 3.0)


def ok_dW(I):
    return 0.5 + 0.0 * I


def ok_d2W(I):
    return 0.0 * I


def fail(I):
    raise ZeroDivisionError("boom")


BAD = [  # (which callable is replaced, replacement, message fragment)
    ("W", lambda I: np.nan * I, r"W\(I1\) must be finite, got W\(3.0\) = nan"),
    ("W", lambda I: None, r"W\(I1\) must return numbers.*None"),
    ("dW", lambda I: np.where(I > 3.4, np.inf, 0.5), r"dW\(I1\) must be finite, got dW\(3.5\) = inf"),
    ("d2W", lambda I: np.zeros(2), r"d2W\(I1\) must return an array of the shape of I1"),
    ("d2W", lambda I: np.zeros((5, 1)), r"d2W\(I1\) must return an array of the shape of I1 \(5,\)"),
    ("d2W", fail, r"d2W\(I1\) must return numbers.*ZeroDivisionError: boom"),
    ("W", lambda I: "x", r"W\(I1\) must return numbers"),
    ("dW", lambda I: 1.0 + 0.0 * I, r"dW\(3\) must"),
    ("dW", lambda I: 0.5 * I / 3.0 + 1e-6, r"dW\(3\) must"),
]


@pytest.mark.parametrize("which, f, match", BAD)
def test_analytic_user_model_rejects(which, f, match):
    kw = {"W": ok_W, "dW": ok_dW, "d2W": ok_d2W, which: f}
    with pytest.raises(ValueError, match="UserModel 'mine': " + match):
        an.UserModel(**kw, name="mine")


@pytest.mark.parametrize("which, f, match", BAD)
def test_fe_ideal_dielectric_rejects(which, f, match):
    kw = {"W": ok_W, "dW": ok_dW, "d2W": ok_d2W, which: f}
    with pytest.raises(ValueError, match="IdealDielectric: " + match):
        sd.IdealDielectric(**kw)


def test_valid_user_models_and_scaling():
    m = an.UserModel(W=ok_W, dW=ok_dW, d2W=lambda I: 0.0)   # scalar result broadcast
    assert float(m.dW(3.0)) == 0.5
    # a Gent copy with a limit below the probe grid is probed inside its range
    Jm = 0.5
    an.UserModel(W=lambda I: -0.5 * Jm * np.log(1 - (I - 3) / Jm),
                 dW=lambda I: 0.5 / (1 - (I - 3) / Jm),
                 d2W=lambda I: 0.5 / (Jm * (1 - (I - 3) / Jm) ** 2), I1_limit=3 + Jm)
    # FE: W in the units of mu, W'(3) = mu/2
    sd.IdealDielectric(W=lambda I: 2.0 * (I - 3), dW=lambda I: 2.0 + 0 * I,
                       d2W=lambda I: 0 * I, mu=4.0)
    with pytest.raises(ValueError, match=r"dW\(3\) must equal 2.0"):
        sd.IdealDielectric(W=ok_W, dW=ok_dW, d2W=ok_d2W, mu=4.0)


@pytest.mark.parametrize("limit", ["x", None, [5.0, 6.0], True, 1 + 2j, float("nan"), 3.0])
def test_user_model_rejects_an_I1_limit_that_is_not_a_real_number_above_3(limit):
    called = []

    def spy(I):
        called.append(I)
        return 0.5 + 0.0 * I

    with pytest.raises(ValueError, match=r"^I1_limit must be a real number > 3 \(or inf\), "
                       r"got " + re.escape(repr(limit)) + "$"):
        an.UserModel(W=spy, dW=spy, d2W=spy, I1_limit=limit)
    assert called == []    # rejected before any user callable is evaluated


@pytest.mark.parametrize("dW", [lambda I: 0.5 + 1e-3j + 0.0 * I, lambda I: 0.5 + 0j])
def test_user_model_rejects_a_complex_dW(dW):
    called = []

    def d2W(I):
        called.append(I)
        return 0.0 * I

    # the probe starts at I1 = 3, where the first complex value is reported
    value = np.ravel(dW(np.array([3.0])))[0]
    with pytest.raises(ValueError, match=r"^UserModel 'mine': dW\(I1\) must return real "
                       r"numbers, got dW\(3.0\) = " + re.escape(repr(complex(value))) + "$"):
        an.UserModel(W=ok_W, dW=dW, d2W=d2W, name="mine")
    assert called == []    # d2W is probed after dW: the complex dW stopped the probe


def test_user_model_accepts_an_integer_I1_limit():
    # an integer limit is a real number; it is stored as float and bounds the domain
    m = an.UserModel(W=ok_W, dW=ok_dW, d2W=ok_d2W, I1_limit=10)
    assert m.I1_max() == 10.0 and isinstance(m.I1_limit, float)
