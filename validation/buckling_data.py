"""The converged buckling loads of the clamped Keplinger plate, as measured.

``validation/data/buckling_loads.csv`` (in the wheel) holds, per weight fraction
``alpha``, the first physical buckling load ``D0_b`` of the whole plate on three meshes,
its Richardson extrapolation with an error estimate and order, and where the plain form's
Newton ramp stops on the finest mesh; its ``#`` header says how they were measured
(command, meshes, solver, date, error estimate).  The study that produces them is
:mod:`validation.studies.buckling` (docs/validation.md, "The study"); the figures
(paper Fig. 5 and the breakdown map, docs/breakdown.md) read them from here.  Reading the
file loads no finite elements.

Only converged entries are answers: :func:`converged_buckling_load` refuses a weight
without one (``alpha = 1.5``: the three meshes disagree) or absent from the file rather
than extrapolate or interpolate between weights.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from importlib import resources

__all__ = ["BUCKLING_LOADS_FILE", "BucklingEntry", "buckling_loads", "buckling_provenance",
           "converged_buckling_load"]

#: the data file, relative to the ``validation`` package
BUCKLING_LOADS_FILE = "data/buckling_loads.csv"


@dataclass(frozen=True)
class BucklingEntry:
    """The buckling load of one weight fraction.

    Attributes
    ----------
    alpha
        Weight fraction of the dead load (paper Sec. 6, ``s = alpha m g/(mu A)``).
    meshes
        The eighth-model meshes, coarse to fine (``"10x1x5"``, ...).
    D0_b_mesh
        The located ``D0_b`` on each mesh.
    D0_b, error, order
        Richardson extrapolation of ``D0_b_mesh``, its error estimate (distance from the
        finest mesh's value) and the observed order; ``nan`` where not converged.
    newton_limit
        Where the plain form (``grad_div = 0``) stops on the finest mesh; ``nan`` if it
        reached every target.
    """

    alpha: float
    meshes: tuple[str, ...]
    D0_b_mesh: tuple[float, ...]
    D0_b: float
    error: float
    order: float
    newton_limit: float

    @property
    def converged(self) -> bool:
        """The three meshes give a converged (extrapolated) buckling load."""
        return math.isfinite(self.D0_b)


def _lines() -> list[str]:
    return (resources.files("validation") / BUCKLING_LOADS_FILE).read_text().splitlines()


def _float(cell: str) -> float:
    return float(cell) if cell.strip() else float("nan")


def buckling_provenance() -> str:
    """The ``#`` header of the data file: command, meshes, solver, date, error estimate."""
    return "\n".join(ln[1:].strip() for ln in _lines() if ln.startswith("#"))


def buckling_loads() -> tuple[BucklingEntry, ...]:
    """Every entry of the data file, converged or not, in increasing ``alpha``.

    Returns
    -------
    tuple of BucklingEntry
    """
    rows = list(csv.DictReader(ln for ln in _lines() if not ln.startswith("#")))
    meshes = tuple(k.removeprefix("D0_b_") for k in rows[0]
                   if k.startswith("D0_b_") and k != "D0_b_error")
    out = [BucklingEntry(alpha=float(r["alpha"]), meshes=meshes,
                         D0_b_mesh=tuple(_float(r[f"D0_b_{m}"]) for m in meshes),
                         D0_b=_float(r["D0_b"]), error=_float(r["D0_b_error"]),
                         order=_float(r["order"]),
                         newton_limit=_float(r[f"newton_limit_{meshes[-1]}"]))
           for r in rows]
    return tuple(sorted(out, key=lambda e: e.alpha))


def converged_buckling_load(alpha: float) -> BucklingEntry:
    """The converged buckling load of weight fraction ``alpha``.

    Parameters
    ----------
    alpha : float
        A weight fraction of the data file (matched to ``1e-9``).

    Returns
    -------
    BucklingEntry
        With a finite ``D0_b`` (the extrapolated load) and its ``error``.

    Raises
    ------
    ValueError
        ``alpha`` is not in the file, or its meshes do not converge; the message names the
        weights with a converged load.  No value is extrapolated or interpolated.

    Examples
    --------
    >>> e = converged_buckling_load(1.0)
    >>> round(e.D0_b, 3), e.meshes[-1]
    (2.84, '20x1x10')
    """
    alpha = float(alpha)
    entries = buckling_loads()
    ok = ", ".join(f"{e.alpha:g}" for e in entries if e.converged)
    bad = ", ".join(f"{e.alpha:g}" for e in entries if not e.converged)
    where = f"converged: alpha = {ok}" + (f"; not converged: alpha = {bad}" if bad else "")
    for e in entries:
        if math.isclose(e.alpha, alpha, rel_tol=0.0, abs_tol=1e-9):
            if e.converged:
                return e
            raise ValueError(f"alpha = {alpha:g} has no converged buckling load (meshes "
                             f"{', '.join(e.meshes)}: "
                             f"{', '.join(f'{v:g}' for v in e.D0_b_mesh)}); {where}")
    raise ValueError(f"alpha = {alpha:g} has no entry in {BUCKLING_LOADS_FILE}; {where}")
