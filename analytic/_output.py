"""The return convention of the public analytic functions (private).

Every public function hands its results to :func:`scalar_or_array`: a result of
shape ``()`` - all number arguments were scalars - becomes the Python number of its
kind (``float``; ``bool`` for the stability verdicts; ``complex`` for the Stroh
exponents); any other result is returned as an ``ndarray`` whose shape is the
broadcast shape of the arguments, followed by the matrix or tensor axes where a
function returns matrices (Hessians, moduli, Stroh matrix, impedance).

Every public function is also wrapped by :func:`representable`: an input so large or so
small that a step of the computation leaves double precision (an overflow) raises a
``ValueError`` naming the argument instead of returning ``inf``, ``nan`` or a wrong number
with a ``RuntimeWarning``.
"""

from __future__ import annotations

import functools
import inspect
import math

import numpy as np

__all__ = ["scalar_or_array", "representable"]


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


def _magnitude(value) -> float:
    """Largest ``|log10 |v||`` over the finite non-zero numbers in ``value`` (0 if none)."""
    try:
        arr = np.abs(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        return 0.0
    arr = arr[np.isfinite(arr) & (arr > 0)]
    return float(np.max(np.abs(np.log10(arr)))) if arr.size else 0.0


def _culprit(func, args, kwargs) -> tuple[str, object]:
    """The number argument of the most extreme magnitude (the likely cause of an overflow)."""
    try:
        bound = inspect.signature(func).bind(*args, **kwargs).arguments
    except TypeError:
        bound = {f"argument {i}": a for i, a in enumerate(args)} | dict(kwargs)
    numbers = {k: v for k, v in bound.items() if not isinstance(v, (str, bool))
               and not callable(v) and math.isfinite(_magnitude(v))}
    if not numbers:
        return "the arguments", bound
    name = max(numbers, key=lambda k: _magnitude(numbers[k]))
    return name, numbers[name]


class _Unrepresentable(ValueError):
    """The ``ValueError`` of :func:`representable`, so that an enclosing public function
    can name its own argument instead of the one of the function it calls."""


def representable(func):
    """Decorator: a computation that overflows double precision raises ``ValueError``.

    ``func`` runs under ``numpy.errstate(over="raise")`` (code that expects an overflow
    says so with a local ``errstate``); a ``FloatingPointError`` (or a singular matrix,
    ``numpy.linalg.LinAlgError``, of such inputs) becomes a ``ValueError`` that names the
    argument of the most extreme magnitude.  When a decorated function calls another
    one, the message names the argument of the outermost (the user's) call.  Results
    that do not overflow are unchanged.
    """

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            with np.errstate(over="raise"):
                return func(*args, **kwargs)
        except (FloatingPointError, np.linalg.LinAlgError, _Unrepresentable):
            pass
        name, value = _culprit(func, args, kwargs)
        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value.item()
        raise _Unrepresentable(f"{name} must be of a size for which {func.__name__} is "
                               f"representable in double precision (a step of the "
                               f"computation overflows), got {value!r}")

    return wrapper
