"""Checks of the command-line options shared by the commands of ``skfem-dielectric``
(:mod:`validation.cli` and the studies' commands, :mod:`validation.studies.commands`):
each bad value is a ``ValueError`` (or an argparse type error) naming the option."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from .fe import pardiso_installed

__all__ = ["out_dir", "mesh_triple", "positive", "check_mesh", "solver_name", "MAX_TARGETS",
           "load_targets"]

#: the most load targets one option may ask for (a ramp or a grid of user input)
MAX_TARGETS = 10**5


def out_dir(text: str) -> Path:
    """The ``--out`` folder (argparse type): any non-blank path."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"must be a folder path, got {text!r}")
    return Path(text)



def mesh_triple(text: str) -> tuple[int, int, int]:
    """``"20x1x10"`` -> ``(20, 1, 10)`` (argparse type of ``--meshes``)."""
    try:
        el = tuple(int(v) for v in text.lower().split("x"))
    except ValueError:
        el = ()
    if len(el) != 3 or min(el) < 1:
        raise argparse.ArgumentTypeError(f"a mesh is N1xN2xN3 with counts >= 1, got {text!r}")
    return el


def positive(name: str, value, *, integer: bool = False, zero: bool = False) -> None:
    """``ValueError`` naming the option unless ``value`` is finite and > 0 (``zero``: >= 0)."""
    if math.isfinite(value) and (value >= 0 if zero else value > 0):
        return
    bound = ">= 0" if zero else (">= 1" if integer else "> 0")
    raise ValueError(f"{name} must be {bound}{'' if integer else ' and finite'}, got {value}")


def check_mesh(name: str, mesh) -> None:
    """``ValueError`` naming option ``name`` unless ``mesh`` (if given) has element
    counts >= 1."""
    if mesh is not None and any(n < 1 for n in mesh):
        raise ValueError(f"{name} must be three element counts >= 1, got "
                         f"{' '.join(map(str, mesh))}")


def solver_name(name: str) -> str:
    """The linear solver a command uses: ``auto`` is PARDISO when pypardiso (the ``fast``
    extra) is installed, else SuperLU; ``pardiso`` without it is a ``ValueError``."""
    if name == "pardiso" and not pardiso_installed():
        raise ValueError("--solver pardiso needs pypardiso (pip install -e '.[fast]'); "
                         "use --solver auto or superlu")
    if name == "auto":
        return "pardiso" if pardiso_installed() else "superlu"
    return name


def load_targets(name: str, start: float, stop: float, step: float | None = None, *,
                 num: int | None = None) -> np.ndarray:
    """The load targets of user input, bounded before anything is computed.

    With ``step``: ``start, start + step, ... <= stop`` (``np.arange``, the end included
    within 1e-9, rounded to 10 decimals); with ``num``: ``num`` points from ``start`` to
    ``stop`` (``np.linspace``).

    Parameters
    ----------
    name : str
        The option that sets the count (``"--D0-step"``, ``"--steps"``), for the message.
    start, stop : float
        The first target and the last one allowed.
    step : float, optional
        The spacing (> 0).
    num : int, optional
        The number of points (>= 1), instead of ``step``.

    Returns
    -------
    numpy.ndarray
        At most :data:`MAX_TARGETS` targets.

    Raises
    ------
    ValueError
        More than :data:`MAX_TARGETS` targets, or a spacing that is not finite and > 0;
        the message names ``name`` and its value.

    Examples
    --------
    >>> load_targets("--D0-step", 0.5, 2.0, 0.5)
    array([0.5, 1. , 1.5, 2. ])
    >>> load_targets("--D0-step", 1e-9, 6.0, 1e-9)
    Traceback (most recent call last):
    ...
    ValueError: --D0-step 1e-09 gives 6000000001 targets up to 6, more than 100000
    """
    if (step is None) == (num is None):
        raise ValueError("load_targets takes step or num, not both or neither")
    if num is None:
        positive(name, step)
        n = math.floor((stop + 1e-9 - start) / step) + 1 if stop >= start else 0
        given = f"{name} {step:g}"
    else:
        n = int(num)
        given = name
    if n > MAX_TARGETS:
        raise ValueError(f"{given} gives {n} targets up to {stop:g}, more than "
                         f"{MAX_TARGETS}")
    if num is not None:
        return np.linspace(start, stop, n)
    return np.round(np.arange(start, stop + 1e-9, step), 10)
