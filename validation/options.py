"""Checks of the command-line options shared by the commands of ``skfem-dielectric``
(:mod:`validation.cli` and the studies' commands, :mod:`validation.studies.commands`):
each bad value is a ``ValueError`` (or an argparse type error) naming the option."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from .fe import pardiso_installed

__all__ = ["out_dir", "mesh_triple", "positive", "check_mesh", "solver_name"]


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
