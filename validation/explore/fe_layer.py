"""The FE results of a ``validate`` folder on the ``explore`` page: the dots of the runs at
the page's parameters, the ``P33`` breakdown and the buckling load of the Keplinger runs.

The folder is read through its CSV contract (:func:`validation.table.read_table`, the columns
of :func:`validation.table.csv_columns`; ``wrinkling-fe.csv`` of
:mod:`validation.studies.wrinkling`), and the marks are those of the figures
(:func:`validation.figures.keplinger_run_marks`).  No Bokeh here.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..figures.common import VARIANT_MARKER, fe_E0, fe_rows
from ..figures.uniaxial_wrinkling import keplinger_run_marks
from ..specs import GENT_JM
from ..table import read_table
from .curves import ExploreParameters

__all__ = ["FEResults", "EQUIBIAXIAL_CASES", "load_results"]

#: The cases whose homogeneous equi-biaxial plates give dots on the equi-biaxial panels.
EQUIBIAXIAL_CASES = ("nh-d-e", "gent-d-e", "gent-equi-biaxial")
_MATCH = 1e-9                    # a parameter of the page matches a run's to this


@dataclass
class FEResults:
    """The tables of a ``validate`` folder that the page draws (empty: no folder).

    Attributes
    ----------
    folder : Path or None
    equibiaxial : list of dict
        The tables of :data:`EQUIBIAXIAL_CASES` present in the folder.
    keplinger : dict or None
        ``uni-axial-ideal.csv``.
    wrinkling : dict or None
        ``wrinkling-fe.csv`` (FE cross-section against Stroh).
    """

    folder: Path | None = None
    equibiaxial: list = field(default_factory=list)
    keplinger: dict | None = None
    wrinkling: dict | None = None

    def equibiaxial_dots(self, p: ExploreParameters) -> dict:
        """``{variant: (lam1_fe, D0, E0_fe)}`` of the converged rows at ``p.s`` and
        ``p.model`` (Gent only at the FE's ``Jm = 97.2``)."""
        out: dict = {}
        if p.model == "Gent" and not np.isclose(float(p.Jm), GENT_JM):
            return out
        for fe in self.equibiaxial:
            mask = fe_rows(fe, model=p.model)
            if mask is None:
                continue
            mask &= np.abs(fe["s"] - float(p.s)) < _MATCH
            for v in VARIANT_MARKER:
                sel = mask & (fe["variant"] == v)
                if sel.any():
                    x, d, e = out.get(v, (np.empty(0),) * 3)
                    out[v] = (np.r_[x, fe["lam1_fe"][sel]], np.r_[d, fe["D0"][sel]],
                              np.r_[e, fe_E0(fe)[sel]])
        return out

    def keplinger_marks(self, p: ExploreParameters) -> dict:
        """``{variant: RunMarks}`` of the Keplinger runs at ``p.alpha`` (neo-Hookean only,
        the model of those runs)."""
        if self.keplinger is None or p.model != "neo-Hookean":
            return {}
        marks = {v: keplinger_run_marks(self.keplinger, float(p.alpha), v)
                 for v in VARIANT_MARKER}
        return {v: m for v, m in marks.items() if m is not None}

    def dispersion_dots(self, p: ExploreParameters) -> dict:
        """``{mode: (kh, D0_fe)}`` of the FE cross-section at ``p.lam`` and ``p.control``
        (neo-Hookean, the model of ``wrinkling-fe``)."""
        t = self.wrinkling
        if t is None or p.model != "neo-Hookean" or "D0_fe" not in t:
            return {}
        sel = ((t["control"] == p.control) & (np.abs(t["lam"] - float(p.lam)) < _MATCH)
               & np.isfinite(t["D0_fe"]))
        return {mode: (t["kh"][sel & (t["mode"] == mode)], t["D0_fe"][sel & (t["mode"] == mode)])
                for mode in ("antisymmetric", "symmetric") if (sel & (t["mode"] == mode)).any()}

    def available(self) -> dict:
        """The parameters at which the folder has FE results: ``{"s": [...], "alpha": [...],
        "lam": [...]}`` (sorted, each once)."""
        s = sorted({float(x) for fe in self.equibiaxial for x in fe.get("s", [])})
        alpha = sorted({float(x) for x in (self.keplinger or {}).get("alpha", [])
                        if np.isfinite(x)})
        lam = sorted({float(x) for x in (self.wrinkling or {}).get("lam", []) if np.isfinite(x)})
        return {"s": s, "alpha": alpha, "lam": lam}


#: the columns the page reads of each kind of table (the contract of ``validate``)
_NEEDED = {
    "equibiaxial": ("run", "converged", "model", "s", "variant", "lam1_fe", "lam3_fe", "D0"),
    "keplinger": ("run", "converged", "alpha", "variant", "breakdown", "lam1_fe",
                  "lam1_analytic", "D0"),
    "wrinkling": ("control", "lam", "mode", "kh"),
}


def _table(path: Path, kind: str):
    """The table of ``path`` (``None`` without a row); a ``ValueError`` naming the file
    when it cannot be read or lacks a column of :data:`_NEEDED` ``[kind]``."""
    try:
        t = read_table(path)
    except (OSError, ValueError, csv.Error, UnicodeDecodeError) as exc:
        raise ValueError(f"--results: cannot read {path}: {' '.join(str(exc).split())}") \
            from None
    if not t or not len(next(iter(t.values()))):
        return None
    missing = [c for c in _NEEDED[kind] if c not in t]
    if missing:
        raise ValueError(f"--results: {path} lacks the column{'s' * (len(missing) > 1)} "
                         f"{', '.join(missing)} of the results contract (docs/theory.md); "
                         f"is it a table written by `skfem-dielectric validate`?")
    return t


def load_results(folder) -> FEResults:
    """The FE tables of the ``validate`` folder ``folder`` (``None``: no FE layer).

    Parameters
    ----------
    folder : path-like or None
        An output folder of ``skfem-dielectric validate``; the cases it lacks are left out.

    Returns
    -------
    FEResults

    Raises
    ------
    ValueError
        ``folder`` is not a folder, holds none of the tables, or a table cannot be read.
    """
    if folder is None:
        return FEResults()
    folder = Path(folder)
    if not folder.is_dir():
        raise ValueError(f"--results must be a folder written by `skfem-dielectric validate`, "
                         f"got {str(folder)!r}")
    res = FEResults(folder=folder)
    for name in EQUIBIAXIAL_CASES:
        if (folder / f"{name}.csv").is_file():
            t = _table(folder / f"{name}.csv", "equibiaxial")
            if t is not None:
                res.equibiaxial.append(t)
    if (folder / "uni-axial-ideal.csv").is_file():
        res.keplinger = _table(folder / "uni-axial-ideal.csv", "keplinger")
    if (folder / "wrinkling-fe.csv").is_file():
        res.wrinkling = _table(folder / "wrinkling-fe.csv", "wrinkling")
    if not (res.equibiaxial or res.keplinger or res.wrinkling):
        raise ValueError(f"--results {str(folder)!r} holds none of "
                         f"{', '.join(EQUIBIAXIAL_CASES)}, uni-axial-ideal, wrinkling-fe (.csv)")
    return res
