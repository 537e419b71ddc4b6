"""One FE ramp outside a validation case: ``skfem-dielectric simulate`` (export of every
step for ParaView) and ``skfem-dielectric bench`` (timing of a Keplinger ramp)."""

from __future__ import annotations

import csv
import time
from pathlib import Path

import meshio
import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.gallery.loads import keplinger_s

from ..specs import KEPLINGER, RunSpec
from .columns import membrane_stretch_maps
from .model import build_problem, is_membrane
from .runner import run_fe

__all__ = ["export_mesh", "simulate", "bench"]

def export_mesh(spec: RunSpec, problem, x, load):
    """meshio ``Mesh`` of a state: :func:`skfem_dielectric.export.step_mesh` in 3D (u, phi, p,
    P33, stretches); for the membrane the displacement ``(u1, 0, u3)``, ``lam1``, ``lam3``."""
    if not is_membrane(spec):
        return fe.export.step_mesh(problem, x, load)
    u = problem.T @ x
    ud = u[problem.basis.nodal_dofs]                   # (2, nverts): u1, u3
    p = problem.mesh.p
    pts = np.c_[p[0], np.zeros(p.shape[1]), p[1]]     # (x1, x2 = 0, x3)
    disp = np.c_[ud[0], np.zeros(p.shape[1]), ud[1]]
    maps = membrane_stretch_maps(problem, x)
    return meshio.Mesh(pts, [("quad", problem.mesh.t[:4].T.copy())],
                       point_data={"displacement": disp, "lam1": maps["lam1"],
                                   "lam3": maps["lam3"]})


def _ramp_spec(geometry, model, variant, s, alpha, D0, mesh) -> RunSpec:
    """A :class:`RunSpec` that runs to its last target (no breakdown stop)."""
    return RunSpec(geometry, model, variant, float(s), tuple(D0), alpha=alpha,
                   mesh=(("n1", mesh[0]), ("n2", mesh[1]), ("n3", mesh[2])),
                   stop_at_breakdown=False)


def simulate(*, geometry="uniaxial", model="neo-Hookean", variant="coupled", s=None,
             alpha=None, D0_max=4.0, steps=8, mesh=None, fmt="vtu", out="."):
    """Run one FE ramp and export every converged step (``skfem-dielectric simulate``).

    Parameters
    ----------
    geometry : {"equibiaxial", "uniaxial", "uniaxial-free"}
    model : {"neo-Hookean", "Gent"}
    variant : {"coupled", "maxwell", "membrane"}
    s : float, optional
        Dead load; for ``"uniaxial"`` it is set from ``alpha`` (default 1).
    alpha : float, optional
        Weight fraction of the Keplinger plate.
    D0_max : float
        Last charge target.
    steps : int
        Number of charge steps after the pre-load.
    mesh : (n1, n2, n3), optional
        Element counts (default coarse).
    fmt : {"vtu", "xdmf"}
        One ``.vtu`` per step, or one XDMF time series.
    out : path-like
        Output folder (created).

    Returns
    -------
    list of Path
        The written files: the fields and ``steps.csv``.
    """
    if steps < 1:
        raise ValueError(f"steps must be >= 1, got {steps}")
    if not np.isfinite(D0_max) or D0_max <= 0:
        raise ValueError(f"D0_max must be > 0, got {D0_max}")
    if fmt not in ("vtu", "xdmf"):
        raise ValueError(f"fmt must be 'vtu' or 'xdmf', got {fmt!r}")
    if geometry == "uniaxial":
        alpha = 1.0 if alpha is None else alpha
        s = keplinger_s(alpha, g=KEPLINGER["g"])
    else:
        s = 1.0 if s is None else s
    spec = _ramp_spec(geometry, model, variant, s, alpha, np.linspace(0, D0_max, steps + 1),
                      (20, 1, 10) if mesh is None else tuple(mesh))
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    problem = build_problem(spec)
    frames, rows = [], []

    def on_step(i, rec, st):
        frames.append(export_mesh(spec, problem, st["x"], st["load"]))
        rows.append([i, spec.D0[i], rec.lam1, rec.lam3, rec.min_P33, rec.min_P33_clamp,
                     rec.iterations])
        return False

    outcome = run_fe(spec, 0, None, on_step)
    written = []
    stem = f"{spec.key}"
    if fmt == "vtu":
        for i, frame in enumerate(frames):
            path = out / f"{stem}_{i:03d}.vtu"
            meshio.write(path, frame)
            written.append(path)
    elif frames:
        path = out / f"{stem}.xdmf"
        with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as w:   # no h5py needed
            w.write_points_cells(frames[0].points, frames[0].cells)
            for i, frame in enumerate(frames):
                w.write_data(spec.D0[i], point_data=frame.point_data,
                             cell_data=frame.cell_data or None)
        written.append(path)
    table = out / f"{stem}_steps.csv"
    with open(table, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["step", "D0", "lam1", "lam3", "min_P33", "min_P33_clamp", "iterations"])
        w.writerows(rows)
        if not outcome.converged:
            w.writerow([len(rows), "", "", "", "", "", f"stopped: {outcome.reason}"])
    return written + [table]


def bench(*, mesh=(20, 1, 10), alpha=1.0, D0_max=6.0, steps=6, variant="coupled",
          solver="auto"):
    """Time one Keplinger ramp; returns the lines of a small table (``skfem-dielectric bench``).

    Parameters
    ----------
    mesh : (n1, n2, n3)
    alpha : float
    D0_max : float
    steps : int
    variant : {"coupled", "maxwell", "membrane"}
    solver : str
        Linear solver name passed to the ramp.

    Returns
    -------
    list of str
    """
    if steps < 1:
        raise ValueError(f"steps must be >= 1, got {steps}")
    spec = _ramp_spec("uniaxial", "neo-Hookean", variant, keplinger_s(alpha, g=KEPLINGER["g"]),
                      alpha,
                      np.linspace(0, D0_max, steps + 1), mesh)
    t_build = time.perf_counter()
    problem = build_problem(spec)
    t_build = time.perf_counter() - t_build
    lines = [f"Keplinger plate, alpha = {alpha:g} (s = {spec.s:.4g}), variant {variant}, "
             f"mesh {tuple(mesh)}, {problem.initial_state().size} unknowns, set-up {t_build:.2f} s",
             f"{'step':>4} {'D0':>6} {'lam1':>9} {'min_P33':>9} {'iters':>5} {'seconds':>8}"]
    t = [time.perf_counter()]

    def on_step(i, rec, st):
        now = time.perf_counter()
        lines.append(f"{i:4d} {rec.D0:6.2f} {rec.lam1:9.5f} {rec.min_P33:9.4f} "
                     f"{rec.iterations:5d} {now - t[-1]:8.2f}")
        t.append(now)
        return False

    outcome = run_fe(spec, 0, None, on_step, linear_solver=solver)
    lines.append(f"total {t[-1] - t[0]:.2f} s" + ("" if outcome.converged
                                                 else f"; stopped: {outcome.reason}"))
    return lines
