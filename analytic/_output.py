"""The return convention of the public analytic functions (private).

Every public function hands its results to :func:`scalar_or_array`: a result of
shape ``()`` - all number arguments were scalars - becomes the Python number of its
kind (``float``; ``bool`` for the stability verdicts; ``complex`` for the Stroh
exponents); any other result is returned as an ``ndarray`` whose shape is the
broadcast shape of the arguments, followed by the matrix or tensor axes where a
function returns matrices (Hessians, moduli, Stroh matrix, impedance).
"""

from __future__ import annotations

import numpy as np

__all__ = ["scalar_or_array"]


def scalar_or_array(*values):
    """Results in the package's return convention.

    Parameters
    ----------
    *values : array_like
        One or more results of a public function.

    Returns
    -------
    float, bool, complex, ndarray or tuple of them
        Each value of shape ``()`` as the Python scalar of its dtype
        (``ndarray.item``), every other value as an ``ndarray`` (not copied); a
        tuple when several values are given.
    """
    out = tuple(_one(v) for v in values)
    return out[0] if len(out) == 1 else out


def _one(value):
    arr = np.asarray(value)
    return arr.item() if arr.ndim == 0 else arr
