"""Adapters from :mod:`skfem_dielectric` problems to the harness's runner protocol.

:func:`run_fe` is the default runner of :func:`validation.sweep.run_case`: it
builds the FE problem of a :class:`~validation.cases.RunSpec`, ramps the load
``(s, D0)`` with :func:`skfem_dielectric.newton.ramp` (pre-load first, then the
charge targets) and reports each converged target as a
:class:`~validation.records.StepRecord`. The saved state is the ramp's reduced
solution vector and its load, so a resumed ramp continues bit for bit.

Geometry in SI-like units of millimetres (the Keplinger plate 100 x 50 x 1 mm)
with ``mu = eps = 1``: every reported quantity is dimensionless.
"""

from __future__ import annotations

import numpy as np

from .records import RunOutcome, StepRecord

__all__ = ["build_problem", "run_fe", "simulate", "bench"]

L1, L3, H = 100.0, 50.0, 1.0     # mm
_PARDISO = None                  # cached PARDISO solver for the stability verdicts


class _Stop(Exception):
    """Raised inside ``on_step`` to end a ramp at the breakdown."""


def _material(model: str):
    from skfem_dielectric.materials import GentDielectric, NeoHookeanDielectric

    if model == "neo-Hookean":
        return NeoHookeanDielectric(1.0, 1.0)
    if model == "Gent":
        return GentDielectric(1.0, 1.0, 97.2)
    raise ValueError(f"model must be 'neo-Hookean' or 'Gent', got {model!r}")


def _interior_min(x1_mm, P33) -> float:
    """Minimum of ``P33`` on the centre line at least ``2 H`` away from the clamps.

    The 3D clamp (``u2 = u3 = 0``) is a stress singularity whose boundary layer
    decays over about one thickness ``H``; at the clamp itself ``P33/mu`` reaches
    about 5 and dips next to it on fine meshes. The breakdown is judged outside
    this layer (``|x1| <= L1/2 - 2H``), where the paper's "P33 near the clamps"
    is resolved on every mesh.
    """
    x1 = np.abs(np.asarray(x1_mm, dtype=float))
    keep = x1 <= L1 / 2 - 2 * H + 1e-9
    return float(np.min(np.asarray(P33)[keep])) if keep.any() else float("nan")


class _Membrane:
    """The 2D membrane model (skfem_dielectric.membrane) behind the runner protocol."""

    def __init__(self, spec):
        from skfem_dielectric.membrane import MembranePlate

        m = spec.mesh_dict
        loading = {"equibiaxial": "equibiaxial", "uniaxial": "clamped",
                   "uniaxial-free": "uniaxial"}[spec.geometry]
        coupling = "maxwell" if spec.variant == "membrane-maxwell" else "full"
        self.problem = MembranePlate(_material(spec.model), L1=L1, L3=L3, H=H,
                                     n1=m.get("n1", 1), n3=m.get("n3", 1), loading=loading,
                                     coupling=coupling)

    tolerances: dict = {}

    def targets(self, spec) -> list:
        """Ramp loads ``(s, D0)``: straight to the pre-load, then the charge targets."""
        return [np.array([spec.s, d]) for d in spec.D0]

    def record(self, step, fields: bool):
        q = step.quantities
        rec = StepRecord(D0=float(np.asarray(step.load)[1]), lam1=q["lam1"], lam3=q["lam3"],
                         min_P33=q["min_P33"], min_P33_clamp=q.get("min_P33_clamp", np.nan),
                         stable=None, iterations=step.iterations)
        prof = self.fields(step.x, step.load)
        rec.min_P33_interior = _interior_min(prof["x1"] * 1e3, prof["P33"])
        if fields:
            rec.fields = prof
        return rec

    def fields(self, x, load) -> dict:
        """Centre-line profile (quarter plate, metres): ``P33/mu``, ``lam1``, ``lam3``."""
        c = self.problem.centre_line(x, load)
        return {"kind": np.zeros(len(c["x1"])), "x1": np.asarray(c["x1"]) * 1e-3,
                "x3": np.zeros(len(c["x1"])), "P33": c["P33"], "lam1": c["lam1"],
                "lam3": c["lam3"]}

    def maps(self, x, load) -> dict:
        from skfem_dielectric.mesh2d import point_gradients

        pb = self.problem
        pts = pb.mesh.p
        # nudge boundary points inside so that the element finder locates them
        c = pts.mean(axis=1, keepdims=True)
        inner = pts + 1e-9 * (c - pts)
        G, dofs = point_gradients(pb.basis, inner)
        u = pb.T @ x
        F = np.einsum("pn,pijn->ijn", u[dofs], G) + np.eye(2)[:, :, None]
        return {"kind": np.ones(pts.shape[1]), "x1": pts[0] * 1e-3, "x3": pts[1] * 1e-3,
                "lam1": F[0, 0], "lam3": F[1, 1], "P33": np.full(pts.shape[1], np.nan)}


    def export(self, x, load):
        """meshio ``Mesh`` of the membrane: displacement ``(u1, 0, u3)``, ``lam1``, ``lam3``."""
        import meshio

        pb = self.problem
        u = pb.T @ x
        ud = u[pb.basis.nodal_dofs]                       # (2, nverts): u1, u3
        p = pb.mesh.p
        pts = np.c_[p[0], np.zeros(p.shape[1]), p[1]]     # (x1, x2 = 0, x3)
        disp = np.c_[ud[0], np.zeros(p.shape[1]), ud[1]]
        maps = self.maps(x, load)
        return meshio.Mesh(pts, [("quad", pb.mesh.t[:4].T.copy())],
                           point_data={"displacement": disp, "lam1": maps["lam1"],
                                       "lam3": maps["lam3"]})


class _Plate:
    """The 3D fully coupled u-p-phi plate (skfem_dielectric.plate) behind the runner protocol.

    Mirrors :func:`skfem_dielectric.drivers.equibiaxial_plate` (1 element, eighth
    model of a 4 x 1 x 4 plate: the state is homogeneous) and
    :func:`skfem_dielectric.drivers.keplinger_plate` (eighth model of the
    100 x 1 x 50 mm plate), including their pre-load steps and tolerances; the
    problem object is kept so that fields and stability can be evaluated.
    """

    def __init__(self, spec):
        from skfem_dielectric.drivers import make_material
        from skfem_dielectric.mesh import plate_mesh
        from skfem_dielectric.plate import PlateProblem

        m = spec.mesh_dict
        el = (m.get("n1", 1), m.get("n2", 1), m.get("n3", 1))
        if spec.geometry == "equibiaxial":
            pm = plate_mesh(4.0, 1.0, 4.0, *el, symmetry="eighth")
            self.preload, self.tolerances = 4, {"atol": 0.0, "rtol": 1e-11}
        elif spec.geometry == "uniaxial":
            pm = plate_mesh(L1, H, L3, *el, symmetry="eighth")
            self.preload, self.tolerances = 3, {"atol": 0.0, "rtol": 1e-9}
        else:
            raise ValueError(f"the 3D plate has no geometry {spec.geometry!r}")
        if spec.variant == "maxwell":
            from skfem_dielectric.maxwell import MaxwellPlate

            # Maxwell traction with the field of the potential solved on the deformed body
            # (the variant that discretises the fully coupled equations; docs/fe_variants.md)
            self.problem = MaxwellPlate(pm, make_material(spec.model), loading=spec.geometry,
                                        field="electrostatic")
        else:
            self.problem = PlateProblem(pm, make_material(spec.model), loading=spec.geometry)
        self.maxwell = spec.variant == "maxwell"

    def targets(self, spec) -> list:
        """Pre-load in equal steps ``(s k/n, 0)``, then ``(s, D0)`` for the charge targets."""
        n = self.preload if spec.s > 0 else 1          # s = 0: a single (0, 0) target
        return ([np.array([spec.s * k / n, 0.0]) for k in range(1, n + 1)]
                + [np.array([spec.s, d]) for d in spec.D0 if d > 0])

    def stability(self, x, load):
        """Inertia verdict of the coupled tangent at a converged state (PARDISO), else None.

        Computed apart from the ramp, whose deterministic SuperLU path is kept so
        that a resumed ramp repeats the uninterrupted one bit for bit.
        """
        from skfem_dielectric.linear import get_linear_solver, pardiso_available

        global _PARDISO
        if self.maxwell or not pardiso_available():
            # the Maxwell tangent is non-symmetric: its inertia is no stability verdict
            return None
        if _PARDISO is None:             # one instance per process: its set-up is slow
            _PARDISO = get_linear_solver("pardiso")
        K, r = self.problem.assemble(x, load)
        _PARDISO.solve(K, r)
        return self.problem.stability(_PARDISO.inertia)

    def record(self, step, fields: bool):
        q = step.quantities
        rec = StepRecord(D0=float(np.asarray(step.load)[1]), lam1=q["lam1"], lam3=q["lam3"],
                         min_P33=q["min_P33"], min_P33_clamp=q.get("min_P33_clamp", np.nan),
                         stable=self.stability(step.x, step.load), iterations=step.iterations)
        c = q["centre_line"]
        rec.min_P33_interior = _interior_min(c["x1"], c["P33"])
        if fields:
            rec.fields = {"kind": np.zeros(len(c["x1"])), "x1": np.asarray(c["x1"]) * 1e-3,
                          "x3": np.zeros(len(c["x1"])), "P33": c["P33"], "lam1": c["lam1"],
                          "lam3": c["lam3"]}
        return rec

    def maps(self, x, load) -> dict:
        """``lam1 = |F e1|``, ``lam3 = |F e3|`` on a grid of the mid-thickness plane."""
        g1, _, g3 = self.problem.plate.grids
        x1 = np.linspace(g1[0], g1[-1], 4 * (len(g1) - 1) + 1)
        x3 = np.linspace(g3[0], g3[-1], 4 * (len(g3) - 1) + 1)
        X1, X3 = (a.ravel() for a in np.meshgrid(x1, x3, indexing="ij"))
        tiny = 1e-9 * (g1[-1] - g1[0])
        pts = np.vstack([np.clip(X1, g1[0] + tiny, g1[-1] - tiny), np.full(X1.size, tiny),
                         np.clip(X3, g3[0] + tiny, g3[-1] - tiny)])
        F = self.problem.evaluate(x, load, pts)["F"]
        lam = np.linalg.norm(F, axis=0)
        return {"kind": np.ones(X1.size), "x1": X1 * 1e-3, "x3": X3 * 1e-3, "lam1": lam[0],
                "lam3": lam[2], "P33": np.full(X1.size, np.nan)}

    def export(self, x, load):
        """meshio ``Mesh`` (:func:`skfem_dielectric.export.step_mesh`): u, phi, p, P33, stretches."""
        from skfem_dielectric.export import step_mesh

        return step_mesh(self.problem, x, load)


def build_problem(spec):
    """The FE problem wrapper of ``spec`` (``.problem`` is a ``RampProblem``)."""
    if spec.variant in ("membrane", "membrane-maxwell"):
        return _Membrane(spec)
    if spec.variant in ("coupled", "maxwell"):
        return _Plate(spec)
    raise ValueError(f"variant {spec.variant!r} has no FE driver yet")


def run_fe(spec, start, state, on_step, linear_solver="superlu"):
    """Run the FE ramp of ``spec`` from target ``start`` (runner protocol of :mod:`.sweep`).

    Parameters
    ----------
    spec : RunSpec
    start : int
        First target to compute; ``state`` holds ``x`` and ``load`` of target
        ``start - 1`` (``None`` when ``start == 0``).
    state : dict or None
    on_step : callable
        ``on_step(index, record, state) -> stop``.
    linear_solver : str
        Passed to the ramp; SuperLU (deterministic) by default, so that a
        resumed ramp repeats the uninterrupted one bit for bit.

    Returns
    -------
    RunOutcome
    """
    from skfem_dielectric.newton import ramp

    if "maxwell" in spec.variant:
        # the Maxwell follower load has a non-symmetric tangent, which the symmetric-
        # indefinite PARDISO set-up (upper triangle only) cannot factorise: SuperLU, or
        # PARDISO as a general LU (mtype 11) when PARDISO is asked for
        from skfem_dielectric.maxwell import nonsymmetric_solver

        linear_solver = nonsymmetric_solver(linear_solver)
    wrap = build_problem(spec)
    targets = wrap.targets(spec)
    x0 = None if state is None else np.asarray(state["x"], dtype=float)
    start_load = None if state is None else np.asarray(state["load"], dtype=float)
    if start_load is not None:
        pos = [k for k, t in enumerate(targets) if np.allclose(t, start_load, rtol=0, atol=1e-14)]
        if not pos:
            raise ValueError(f"saved load {start_load} is not a target of run {spec.key}")
        targets = targets[pos[0] + 1:]

    def cb(step):
        load = np.asarray(step.load, dtype=float)
        if load[0] != spec.s:
            return                                   # an intermediate pre-load step
        i = spec.D0.index(float(load[1]))
        rec = wrap.record(step, spec.record_fields)
        if spec.record_fields and spec.record_maps and spec.D0[i] == 0.0:
            # stretch maps of the pre-loaded plate (kind 1) after the centre line (kind 0)
            maps = wrap.maps(step.x, step.load)
            rec.fields = {k: np.r_[rec.fields[k], maps[k]] for k in rec.fields}
        if on_step(i, rec, {"x": step.x, "load": load}):
            raise _Stop

    try:
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)   # the failure is recorded
            res = ramp(wrap.problem, targets, x0=x0, start=start_load, on_step=cb,
                       linear_solver=linear_solver, **wrap.tolerances)
    except _Stop:
        return RunOutcome(True)
    failed = None if res.failed_at is None else float(np.asarray(res.failed_at).ravel()[-1])
    return RunOutcome(bool(res.converged), res.reason, failed)


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
    import csv
    from pathlib import Path

    import meshio

    from .cases import RunSpec, keplinger_s

    if steps < 1:
        raise ValueError(f"steps must be >= 1, got {steps}")
    if not np.isfinite(D0_max) or D0_max <= 0:
        raise ValueError(f"D0_max must be > 0, got {D0_max}")
    if fmt not in ("vtu", "xdmf"):
        raise ValueError(f"fmt must be 'vtu' or 'xdmf', got {fmt!r}")
    if geometry == "uniaxial":
        alpha = 1.0 if alpha is None else alpha
        s = keplinger_s(alpha)
    else:
        s = 1.0 if s is None else s
    n = (20, 1, 10) if mesh is None else tuple(mesh)
    spec = RunSpec(geometry, model, variant, float(s), tuple(np.linspace(0, D0_max, steps + 1)),
                   alpha=alpha, mesh=(("n1", n[0]), ("n2", n[1]), ("n3", n[2])),
                   stop_at_breakdown=False)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    wrap = build_problem(spec)
    frames, rows = [], []

    def on_step(i, rec, st):
        frames.append(wrap.export(st["x"], st["load"]))
        rows.append([i, spec.D0[i], rec.lam1, rec.lam3, rec.min_P33, rec.min_P33_clamp,
                     rec.iterations])
        return False

    outcome = run_fe(spec, 0, None, on_step)
    written = []
    stem = f"{spec.key}"
    if fmt == "vtu":
        for i, mesh in enumerate(frames):
            path = out / f"{stem}_{i:03d}.vtu"
            meshio.write(path, mesh)
            written.append(path)
    elif frames:
        path = out / f"{stem}.xdmf"
        with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as w:   # no h5py needed
            w.write_points_cells(frames[0].points, frames[0].cells)
            for i, mesh in enumerate(frames):
                w.write_data(spec.D0[i], point_data=mesh.point_data,
                             cell_data=mesh.cell_data or None)
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
    import time

    from .cases import RunSpec, keplinger_s

    if steps < 1:
        raise ValueError(f"steps must be >= 1, got {steps}")
    spec = RunSpec("uniaxial", "neo-Hookean", variant, keplinger_s(alpha),
                   tuple(np.linspace(0, D0_max, steps + 1)), alpha=alpha,
                   mesh=(("n1", mesh[0]), ("n2", mesh[1]), ("n3", mesh[2])),
                   stop_at_breakdown=False)
    t_build = time.perf_counter()
    wrap = build_problem(spec)
    t_build = time.perf_counter() - t_build
    lines = [f"Keplinger plate, alpha = {alpha:g} (s = {spec.s:.4g}), variant {variant}, "
             f"mesh {tuple(mesh)}, {wrap.problem.initial_state().size} unknowns, set-up {t_build:.2f} s",
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
