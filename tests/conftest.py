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
