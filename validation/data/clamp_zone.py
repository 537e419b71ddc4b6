"""What is read from the clamp-zone tables: a unit's row and scanned states, the plain
form's ``P33`` row of a weight, the convergence rule of a weight's load
(:func:`clamp_unit_load`) and the classes that cross together.  No finite elements.
"""

from __future__ import annotations

import errno
import math

from .key import UnitKey
from .registry import (CLASS_TIE, MAX_D0, MIN_ELEMENTS_PER_HALF_WAVE, load, shipped_path,
                       table_file)

__all__ = ["unit_row", "scan_states", "plain_p33_row", "clamp_unit_load", "tied_classes",
           "clamp_voltage_limit"]


def scan_states(row: dict) -> list[tuple[float, int, int]]:
    """Every state a unit scanned, ``(D0, negative, physical)`` in scan order (refined
    steps last), from its row's ``scan_counts`` cell (``D0:negative/physical ...``).

    Raises
    ------
    ValueError
        The cell is not of that form; the message names the unit and the item.

    Examples
    --------
    >>> scan_states({"alpha": "1", "mesh": "4x1x2", "scan_counts": "0.5:4/0 1:6/1"})
    [(0.5, 4, 0), (1.0, 6, 1)]
    """
    out = []
    for item in str(row.get("scan_counts") or "").split():
        try:
            d, counts = item.split(":")
            neg, phys = counts.split("/")
            out.append((float(d), int(neg), int(phys)))
        except ValueError:
            raise ValueError(f"the unit alpha = {row.get('alpha')} {row.get('mesh')} has "
                             f"{item!r} in scan_counts, not D0:negative/physical") from None
    return out


def plain_p33_row(alpha: float, where=None) -> dict | None:
    """The ``p33`` row of weight ``alpha`` on its finest graded mesh (most unknowns): the
    plain form's located ``P33`` onsets and Newton limit that the docs and the figures
    quote for the weight; ``None`` if the weight has no row.

    Parameters
    ----------
    alpha : float
        Weight fraction (matched to ``1e-9``).
    where : path-like, optional
        The ``p33`` table (a file or folder; default: the shipped one).
    """
    mine = [r for r in load("p33", where)
            if math.isclose(float(r["alpha"]), float(alpha), rel_tol=0.0, abs_tol=1e-9)]
    return max(mine, key=lambda r: int(r["dofs"])) if mine else None


def unit_row(key: UnitKey, where=None) -> dict:
    """The ``units`` row of one unit: from the table ``where`` (a file or folder) where it
    has the unit, else from the shipped table.

    Raises
    ------
    ValueError
        No table has the unit: the message names it and the command that computes it.
    OSError
        The unit's ``D0_b`` is not empty and not a charge in ``(0, MAX_D0]``: the message
        names the table (exit code 3 of the CLI: a damaged row).
    """
    for source in ((where, None) if where is not None else (None,)):
        for r in load("units", source):
            if UnitKey.from_row(r) == key:
                d0b = float(r["D0_b"] or "nan")
                if r["D0_b"] and not (0 < d0b <= MAX_D0):
                    raise OSError(errno.EINVAL, f"the row of the clamp-zone unit {key} has "
                                  f"D0_b = {r['D0_b']}, not a charge in (0, {MAX_D0:g}]; "
                                  f"compute that unit again", str(table_file("units", source)))
                return r
    raise ValueError(f"no clamp-zone unit {key} in the units table: run skfem-dielectric "
                     f"clamp-zone units for it first")


def _rows_by_size(name: str, alpha: float, path, keep, what: str) -> list[dict]:
    """The rows of the table ``name`` of ``alpha`` (to ``1e-9``) that ``keep``, by
    unknowns; ``ValueError`` (naming ``what`` and the table) unless there are two."""
    rows = [r for r in load(name, path) if keep(r)
            and math.isclose(float(r["alpha"]), alpha, rel_tol=0.0, abs_tol=1e-9)]
    rows.sort(key=lambda r: int(r["dofs"]))
    if len(rows) < 2:
        raise ValueError(f"alpha = {alpha:g} has {len(rows)} {what} in "
                         f"{path or shipped_path(name).name}: two meshes are needed")
    return rows


def clamp_unit_load(alpha: float, *, tol: float | None = None, path=None,
                    formulation: str = "mixed", classes_path=None) -> dict:
    """The clamp-zone buckling load of ``alpha`` where the study's two finest meshes agree.

    The rows of ``alpha`` (``formulation``, a located ``D0_b``) ordered by unknowns; the
    two finest must hold the mode (at least :data:`MIN_ELEMENTS_PER_HALF_WAVE` elements
    across the width per half-wave), count the same half-waves and give ``D0_b`` within
    ``tol`` (default 0.02; 0.05 for ``alpha >= 1.5``).  No value is extrapolated.

    Where the two finest meshes' first crossings differ in half-waves, the modes that
    cross together on each mesh (:func:`tied_classes`: the classes of the ``onsets`` table
    within :data:`CLASS_TIE` of the mesh's first) decide: a class tied for first on both
    meshes with the same half-waves on both is the converged mode (its count is reported);
    without class onsets, or without such a class, the count is not converged.

    Parameters
    ----------
    alpha : float
        Weight fraction (matched to ``1e-9``).
    tol : float, optional
        Largest difference of the two finest meshes' ``D0_b``.
    path : path-like, optional
        The ``units`` table (a file or folder; default: the shipped one).
    formulation : str
        How ``J = 1`` is imposed in the rows used.
    classes_path : path-like, optional
        The ``onsets`` table (default: the shipped one).

    Returns
    -------
    dict
        ``D0_b`` (the finest mesh's), ``spread`` (the two finest meshes' difference),
        ``half_waves``, ``class`` (the mode's symmetry class), ``tied`` (the classes tied
        for first on the finest mesh, ``{class: half-waves}``, empty where the two finest
        rows agreed by themselves), ``meshes`` (the two finest, coarser first), ``rows``
        (every located row of ``alpha`` and ``formulation``, by unknowns).

    Raises
    ------
    ValueError
        ``alpha`` has fewer than two located rows, or the two finest do not hold the mode,
        count different half-waves or differ by more than ``tol``; the message says which
        and gives their numbers.
    """
    alpha = float(alpha)
    if tol is None:
        tol = 0.05 if alpha >= 1.5 else 0.02
    rows = _rows_by_size("units", alpha, path,
                         lambda r: r["D0_b"] and r["formulation"] == formulation,
                         f"located clamp-zone unit(s) with formulation {formulation!r}")
    a, b = rows[-2], rows[-1]
    what = (f"alpha = {alpha:g}: {a['mesh']} graded {a['grading']} D0_b {a['D0_b']} "
            f"({a['half_waves']} half-waves, {float(a['elements_per_half_wave']):.1f} "
            f"elements each), {b['mesh']} graded {b['grading']} D0_b {b['D0_b']} "
            f"({b['half_waves']} half-waves, {float(b['elements_per_half_wave']):.1f} "
            f"elements each)")
    coarse = [r["mesh"] for r in (a, b)
              if float(r["elements_per_half_wave"]) < MIN_ELEMENTS_PER_HALF_WAVE]
    if coarse:
        raise ValueError(f"mesh too coarse for the mode ({', '.join(coarse)}: fewer than "
                         f"{MIN_ELEMENTS_PER_HALF_WAVE:g} elements per half-wave); {what}")
    name, n_half, tied = b["class"], int(b["half_waves"]), {}
    if a["half_waves"] != b["half_waves"]:
        ta, tb = tied_classes(a, classes_path), tied_classes(b, classes_path)
        shared = [c for c in tb if ta.get(c) == tb[c]]
        if not shared:
            ties = "; ".join(f"{r['mesh']}: " + (", ".join(
                f"{c} {n}" for c, n in sorted(t.items())) or "no class onsets")
                for r, t in ((a, ta), (b, tb)))
            raise ValueError(f"half-wave count not converged (tied classes: {ties}); {what}")
        name, tied = shared[0], tb
        n_half = tb[name]
    spread = abs(float(b["D0_b"]) - float(a["D0_b"]))
    if spread > tol:
        raise ValueError(f"D0_b not converged (spread {spread:.4f} > tol {tol:g}); {what}")
    return {"D0_b": float(b["D0_b"]), "spread": spread, "half_waves": n_half,
            "class": name, "tied": tied, "meshes": (a["mesh"], b["mesh"]), "rows": rows}


def tied_classes(row: dict, path=None) -> dict:
    """The symmetry classes that cross together first on a clamp-zone unit's mesh.

    Parameters
    ----------
    row : dict
        A row of the ``units`` table (``alpha``, ``mesh``, ``grading``, ``formulation``,
        ``D0_b``).
    path : path-like, optional
        The ``onsets`` table (default: the shipped one).

    Returns
    -------
    dict
        ``{class: half-waves}`` of the located classes of that unit whose ``D0_c`` lies
        within :data:`CLASS_TIE` of the lowest, in increasing ``D0_c``; empty where the unit
        has no located class or its lowest ``D0_c`` is not within :data:`CLASS_TIE` of the
        unit's ``D0_b`` (the two locations disagree).
    """
    key = UnitKey.from_row(row)
    mine = sorted((r for r in load("onsets", path)
                   if r["D0_c"] and UnitKey.from_row(r) == key),
                  key=lambda r: float(r["D0_c"]))
    if not mine or abs(float(mine[0]["D0_c"]) - float(row["D0_b"])) > CLASS_TIE:
        return {}
    first = float(mine[0]["D0_c"])
    return {r["class"]: int(r["half_waves"]) for r in mine
            if float(r["D0_c"]) - first <= CLASS_TIE}


def clamp_voltage_limit(alpha: float, *, tol: float = 1e-3, grad_div: float = 10.0,
                        path=None) -> dict:
    """The voltage-controlled limit of the clamped plate of ``alpha`` where the two finest
    meshes of the ``voltage`` table agree.

    The rows of ``alpha`` with ``grad_div`` and a located limit, ordered by unknowns; the two
    finest must give ``E0_limit`` within ``tol`` (relative).  No value is extrapolated.

    Parameters
    ----------
    alpha : float
        Weight fraction (matched to ``1e-9``).
    tol : float
        Largest relative difference of the two finest meshes' ``E0_limit``.
    grad_div : float
        The grad-div weight of the rows used (the units': 10).
    path : path-like, optional
        The ``voltage`` table (a file or folder; default: the shipped one).

    Returns
    -------
    dict
        The finest mesh's ``E0_limit``, ``D0_limit``, ``lam1_limit``, ``ratio``,
        ``E0_membrane``, ``D0_stable`` and ``D0_physical`` (the bracket of the first
        physical mode; ``nan``: none before the limit); ``spread`` (the two finest meshes'
        relative difference in ``E0_limit``), ``D0_spread`` (their difference in
        ``D0_limit``),
        ``meshes`` (the two finest, coarser first, with their grading) and ``rows``.

    Raises
    ------
    ValueError
        Fewer than two located rows, or the two finest differ by more than ``tol``; the
        message gives their numbers.
    """
    alpha = float(alpha)
    rows = _rows_by_size("voltage", alpha, path,
                         lambda r: r["E0_limit"] and float(r["grad_div"]) == float(grad_div),
                         f"voltage-controlled limit(s) with grad-div {grad_div:g}")
    a, b = rows[-2], rows[-1]
    spread = abs(float(b["E0_limit"]) / float(a["E0_limit"]) - 1.0)
    if spread > tol:
        raise ValueError(f"E0_limit not converged (relative spread {spread:.2g} > tol "
                         f"{tol:g}); alpha = {alpha:g}: {a['mesh']} {a['E0_limit']}, "
                         f"{b['mesh']} {b['E0_limit']}")
    num = {c: float(b[c] or "nan") for c in ("E0_limit", "D0_limit", "lam1_limit", "ratio",
                                              "E0_membrane", "D0_stable", "D0_physical")}
    return {**num, "spread": spread, "rows": rows,
            "D0_spread": abs(float(b["D0_limit"]) - float(a["D0_limit"])),
            "meshes": tuple(f"{r['mesh']} g{r['grading']}" for r in (a, b))}
