"""The converged buckling loads of the clamped Keplinger plate, as measured.

Two data files (in the wheel) hold the first physical buckling load ``D0_b`` of the whole
plate:

* ``validation/data/clamp_units.csv``: the clamp-zone study on meshes graded towards the
  clamp (:mod:`validation.clamp_zone`, one weight on one mesh per row, with the
  mode's half-wave count, ``J`` at the clamp and the command of each row).  A weight's
  load is the finest mesh's where the two finest hold the mode (at least
  :data:`~validation.data.registry.MIN_ELEMENTS_PER_HALF_WAVE` elements per half-wave across the width), count the
  same half-waves and agree (:func:`clamp_unit_load`);
* ``validation/data/buckling_loads.csv``: three uniform meshes per weight
  (:mod:`validation.studies.buckling`), their Richardson extrapolation with an error
  estimate and order, and where the plain form's Newton ramp stops on the finest mesh;
  its ``#`` header says how they were measured (command, meshes, solver, date, error
  estimate).  Its meshes hold two elements per half-wave of the heavier weights'
  clamp-zone wrinkle, so a weight with a converged graded load takes that one.

:func:`buckling_loads` gives, per weight, the entry the project stands behind; the figures
(paper Fig. 5 and the breakdown map, docs/breakdown.md) and ``skfem-dielectric check``
read it from here.  Reading the files loads no finite elements.

Only converged entries are answers: :func:`converged_buckling_load` refuses a weight
without one (the uniform meshes' ``alpha = 1.5``: its three meshes disagree) or absent
from the file rather than extrapolate or interpolate between weights.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from importlib import resources

from ..specs import LOCATION_TOL
from .clamp_zone import clamp_unit_load, clamp_voltage_limit, plain_p33_row
from .registry import load

__all__ = ["BUCKLING_LOADS_FILE", "CLAMP_UNITS_FILE", "BucklingEntry", "buckling_loads",
           "uniform_buckling_loads", "buckling_provenance", "converged_buckling_load",
           "newton_limits", "newton_limit_bands", "p33_onsets", "voltage_limits"]

#: the data file of the uniform meshes, relative to the ``validation`` package
BUCKLING_LOADS_FILE = "data/buckling_loads.csv"
#: the ``units`` table of the clamp-zone study on graded meshes (one unit per row,
#: :mod:`validation.clamp_zone`), relative to the ``validation`` package
CLAMP_UNITS_FILE = "data/clamp_units.csv"


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
        Where the plain form (``grad_div = 0``) stops on the finest mesh (for a ``"graded"``
        entry, the weight's finest graded ``P33`` mesh); ``nan`` if it reached every target
        (or, for a ``"graded"`` entry, was not run on a graded mesh).
    source
        ``"uniform"``: the three uniform meshes of :data:`BUCKLING_LOADS_FILE`, ``D0_b``
        their Richardson extrapolation; ``"graded"``: the two finest graded meshes of the
        clamp-zone study (:data:`CLAMP_UNITS_FILE`, ``meshes`` named ``"40x1x36 g0.1"``:
        mesh and grading), ``D0_b`` the finest mesh's where the two hold the mode and agree
        (:func:`clamp_unit_load`), ``error`` their difference, ``order`` ``nan`` (nothing
        is extrapolated).
    """

    alpha: float
    meshes: tuple[str, ...]
    D0_b_mesh: tuple[float, ...]
    D0_b: float
    error: float
    order: float
    newton_limit: float
    source: str = "uniform"

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


def uniform_buckling_loads() -> tuple[BucklingEntry, ...]:
    """Every entry of :data:`BUCKLING_LOADS_FILE` (three uniform meshes), converged or not,
    in increasing ``alpha``.

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


def _plain_newton_limit(alpha: float) -> tuple[float, str]:
    """The plain form's Newton limit of ``alpha`` on its finest graded mesh and that mesh
    (:func:`~validation.data.clamp_zone.plain_p33_row`); ``nan`` where the ramp reached
    every target or was not run."""
    r = plain_p33_row(alpha)
    if r is None:
        return math.nan, ""
    return _float(r["newton_limit"]), f"{r['mesh']} g{r['grading']}"


def buckling_loads() -> tuple[BucklingEntry, ...]:
    """The buckling load the project stands behind, per weight fraction, in increasing
    ``alpha``: the clamp-zone study's graded meshes where the two finest hold the mode and
    agree (:func:`clamp_unit_load`; ``source="graded"``), else the entry of the three
    uniform meshes (:func:`uniform_buckling_loads`, converged or not).  A graded entry's
    ``error`` is the two finest meshes' difference, at least :data:`LOCATION_TOL` (each is
    located to it: two meshes that agree to the last digit do not make the load exact).

    The uniform meshes of :data:`BUCKLING_LOADS_FILE` have two elements per half-wave of
    the heavier weights' clamp-zone wrinkle: where the graded meshes resolve it, their load
    replaces the uniform extrapolation (docs/validation.md, "The clamp-zone wrinkle on
    graded meshes").

    Returns
    -------
    tuple of BucklingEntry
    """
    out = {round(e.alpha, 9): e for e in uniform_buckling_loads()}
    alphas = {round(float(r["alpha"]), 9) for r in load("units") if r["D0_b"]}
    for a in alphas:
        try:
            g = clamp_unit_load(a)
        except ValueError:
            continue
        rows = g["rows"][-2:]                  # the two finest, that agree
        out[a] = BucklingEntry(
            alpha=a, meshes=tuple(f"{r['mesh']} g{r['grading']}" for r in rows),
            D0_b_mesh=tuple(float(r["D0_b"]) for r in rows), D0_b=g["D0_b"],
            error=max(g["spread"], LOCATION_TOL), order=math.nan,
            newton_limit=_plain_newton_limit(a)[0],
            source="graded")
    return tuple(sorted(out.values(), key=lambda e: e.alpha))


def newton_limits() -> list[tuple[float, float, str]]:
    """Where the plain form's Newton ramp stops, one per weight: ``(alpha, D0, mesh)``, in
    increasing ``alpha``.  A weight with a graded ``P33`` row takes its finest graded mesh's
    (the clamp-zone ``p33`` table, the mesh the docs' breakdown table quotes), else the
    finest uniform mesh's; a weight whose ramp reached every target has none.

    Returns
    -------
    list of tuple
    """
    uniform = {round(e.alpha, 9): e for e in uniform_buckling_loads()}
    out = []
    for a in sorted(set(uniform) | {round(e.alpha, 9) for e in buckling_loads()}):
        d, mesh = _plain_newton_limit(a)
        if not mesh and a in uniform:
            d, mesh = uniform[a].newton_limit, uniform[a].meshes[-1]
        if math.isfinite(d):
            out.append((a, d, mesh))
    return out


def newton_limit_bands() -> list[tuple[float, float, float, tuple[str, ...]]]:
    """The plain form's Newton limit of each weight over every mesh that has one: the graded
    ``P33`` rows of the clamp-zone ``p33`` table and the finest uniform mesh of
    :data:`BUCKLING_LOADS_FILE`.  A solver limit moves with the mesh; the band is how far.

    Returns
    -------
    list of tuple
        ``(alpha, lowest, highest, meshes)`` in increasing ``alpha``, one per weight with a
        limit on at least one mesh (``lowest == highest`` where only one mesh has one).

    Examples
    --------
    >>> [(a, lo, hi) for a, lo, hi, _ in newton_limit_bands()][:2]
    [(0.05, 3.91, 3.91), (0.3, 2.5, 5.125)]
    """
    per: dict[float, list[tuple[float, str]]] = {}
    for r in load("p33"):
        d = _float(r["newton_limit"])
        if math.isfinite(d):
            per.setdefault(round(float(r["alpha"]), 9), []).append(
                (d, f"{r['mesh']} g{r['grading']}"))
    for e in uniform_buckling_loads():
        if math.isfinite(e.newton_limit):
            per.setdefault(round(e.alpha, 9), []).append((e.newton_limit, e.meshes[-1]))
    return [(a, min(d for d, _ in v), max(d for d, _ in v), tuple(m for _, m in sorted(v)))
            for a, v in sorted(per.items())]


def p33_onsets() -> list[tuple[float, float, str]]:
    """The located ``P33`` onset of the plain form in the interior, one per weight with a
    graded ``P33`` row: ``(alpha, D0, mesh)`` of its finest graded mesh
    (:func:`~validation.data.clamp_zone.plain_p33_row`, the clamp-zone ``p33`` table), in
    increasing ``alpha``; the reference layer the figures draw beside a run's own ``P33``
    step (docs/breakdown.md).

    Returns
    -------
    list of tuple
    """
    out = []
    for a in sorted({round(float(r["alpha"]), 9) for r in load("p33")}):
        r = plain_p33_row(a)
        if r is not None and r["P33_onset_interior"]:
            out.append((a, float(r["P33_onset_interior"]), f"{r['mesh']} g{r['grading']}"))
    return out


def voltage_limits() -> list[tuple[float, float, tuple[str, ...]]]:
    """The snap-through of the clamped plate under voltage control, one per weight whose two
    finest meshes of the ``voltage`` table agree
    (:func:`~validation.data.clamp_zone.clamp_voltage_limit`): ``(alpha, D0, meshes)``, the
    charge at the plate's centre at the limit point of the finest mesh, in increasing
    ``alpha``; the map draws it beside ``D0_b`` (docs/breakdown.md).

    Returns
    -------
    list of tuple
    """
    out = []
    for a in sorted({round(float(r["alpha"]), 9) for r in load("voltage") if r["E0_limit"]}):
        try:
            v = clamp_voltage_limit(a)
        except ValueError:
            continue
        out.append((a, v["D0_limit"], v["meshes"]))
    return out


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
    >>> round(e.D0_b, 3), e.source, len(e.meshes)
    (3.37, 'graded', 2)
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
    raise ValueError(f"alpha = {alpha:g} has no entry in {BUCKLING_LOADS_FILE} or "
                     f"{CLAMP_UNITS_FILE}; {where}")
