"""Helpers shared by the test files (private to the test suite)."""

from __future__ import annotations

import numpy as np
import pytest


def _central_difference_columns(residual, x, load, cols, h=1e-6):
    """Columns ``j in cols`` of ``d residual(x, load)/d x`` by central differences of step ``h``.

    Returns an array with one column per entry of ``cols`` (in that order).
    """
    out = []
    for j in cols:
        e = np.zeros(x.size)
        e[j] = h
        out.append((residual(x + e, load) - residual(x - e, load)) / (2 * h))
    return np.stack(out, axis=1)


@pytest.fixture
def fd_columns():
    """The central-difference tangent columns of a problem's reduced residual."""
    return _central_difference_columns


def _assert_tangent_columns(residual, K, x, load, cols, h=1e-6, floor=0.0):
    """Assert that columns ``cols`` of the dense tangent ``K`` match central differences of
    ``residual`` with step ``h``: ``|fd - K[:, j]| <= 1e-6 max(|K[:, j]|, floor)``.

    The reason for 1e-6: central differences have an error O(h^2) + round-off/h ~ 1e-9
    relative at h = 1e-6, so 1e-6 leaves a wide margin yet catches any missing term.
    ``floor`` (e.g. 1.0) guards columns whose entries are all tiny.
    """
    for j, fd in zip(cols, _central_difference_columns(residual, x, load, cols, h).T):
        assert np.abs(fd - K[:, j]).max() <= 1e-6 * max(np.abs(K[:, j]).max(), floor)


@pytest.fixture
def assert_tangent_columns():
    """Checker of assembled tangent columns against central differences."""
    return _assert_tangent_columns


def _fake_wrinkling(monkeypatch, calls=None):
    """Stand-ins of the wrinkling-fe rows: the Stroh value times ``1 + 1e-5`` where the
    dispersion relation has a root, its "no root" row elsewhere (the real rows' shape).
    Returns the list of the calls made (appended to ``calls`` when given)."""
    import math

    import analytic as an
    import validation.studies.wrinkling as wr

    calls = [] if calls is None else calls

    def row(control, mode, lam, kh, n1):
        calls.append((control, mode, lam, kh))
        ref = float(an.critical_D0(lam, kh, mode=mode, control=control))
        if not math.isfinite(ref):
            return [control, mode, lam, kh, None, None, None, "", None, None,
                    "no root of the dispersion relation"]
        return [control, mode, lam, kh, ref * (1 + 1e-5), ref, 1e-5, f"{n1}x2", 0, 0, ""]

    def elastic(mode, kh, n1):
        calls.append((mode, kh))
        ref = wr.stroh_critical_stretch(kh, mode)
        return [mode, kh, ref * (1 + 1e-5), ref, 1e-5, f"{n1}x2", ""]

    monkeypatch.setattr(wr, "_row", row)
    monkeypatch.setattr(wr, "_elastic_row", elastic)
    return calls


@pytest.fixture
def fake_wrinkling():
    """``fake_wrinkling(monkeypatch, calls=None)``: cheap stand-ins of the wrinkling-fe FE
    rows (:func:`_fake_wrinkling`)."""
    return _fake_wrinkling


def _buckling_figure_rows() -> tuple[dict, list, list]:
    """``(row, scan, plain)`` of buckling.png for alpha = 1 on 10 x 1 x 5: D0_b = 2.9147, the
    lowest physical eigenvalue scanned at D0 = 2, 2.5 and 3 (through zero between the last
    two), the grad-div form's interior P33 onset 0.645 and the plain form's 2.52."""
    import validation.studies.buckling as bk

    nan = float("nan")
    row = {c: nan for c in bk.COLUMNS} | {"alpha": 1.0, "mesh": "10x1x5", "D0_b": 2.9147,
                                          "class": "x1 S", "P33_onset_interior": 0.645}
    scan = [{c: nan for c in bk.SCAN_COLUMNS} | {"alpha": 1.0, "mesh": "10x1x5", "D0": d,
                                                 "physical": v, **{f"P33_{k}": -0.02 * d
                                                                   for k in bk.P33_SETS}}
            for d, v in ((2.0, nan), (2.5, 0.05), (3.0, -0.02))]
    plain = [{c: nan for c in bk.PLAIN_COLUMNS} | {"alpha": 1.0, "mesh": "10x1x5",
                                                   "P33_onset_interior": 2.52}]
    return row, scan, plain


@pytest.fixture
def buckling_figure_rows():
    """The rows buckling.png is drawn from in the tests (:func:`_buckling_figure_rows`)."""
    return _buckling_figure_rows()
