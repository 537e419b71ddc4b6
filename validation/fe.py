"""Adapters from :mod:`skfem_dielectric` problems to the harness's runner protocol.

:func:`run_fe` is the default runner of :func:`validation.sweep.run_case`: it
builds the FE problem of a :class:`~validation.cases.RunSpec`, ramps the load
``(s, D0)`` with :func:`skfem_dielectric.newton.ramp` (pre-load first, then the
charge targets) and reports each converged target as a
:class:`~validation.sweep.StepRecord`. The saved state is the ramp's reduced
solution vector and its load, so a resumed ramp continues bit for bit.

Geometry in SI-like units of millimetres (the Keplinger plate 100 x 50 x 1 mm)
with ``mu = eps = 1``: every reported quantity is dimensionless.
"""

from __future__ import annotations

import numpy as np

__all__ = ["build_problem", "run_fe", "simulate", "bench"]

L1, L3, H = 100.0, 50.0, 1.0     # mm


class _Stop(Exception):
    """Raised inside ``on_step`` to end a ramp at the breakdown."""


def _material(model: str):
    from skfem_dielectric.materials import GentDielectric, NeoHookeanDielectric

    if model == "neo-Hookean":
        return NeoHookeanDielectric(1.0, 1.0)
    if model == "Gent":
        return GentDielectric(1.0, 1.0, 97.2)
    raise ValueError(f"model must be 'neo-Hookean' or 'Gent', got {model!r}")


class _Membrane:
    """The 2D membrane model (skfem_dielectric.membrane) behind the runner protocol."""

    def __init__(self, spec):
        from skfem_dielectric.membrane import MembranePlate

        m = spec.mesh_dict
        loading = {"equibiaxial": "equibiaxial", "uniaxial": "clamped",
                   "uniaxial-free": "uniaxial"}[spec.geometry]
        self.problem = MembranePlate(_material(spec.model), L1=L1, L3=L3, H=H,
                                     n1=m.get("n1", 1), n3=m.get("n3", 1), loading=loading)

    def record(self, step, fields: bool):
        from .sweep import StepRecord

        q = step.quantities
        rec = StepRecord(D0=float(np.asarray(step.load)[1]), lam1=q["lam1"], lam3=q["lam3"],
                         min_P33=q["min_P33"], min_P33_clamp=q.get("min_P33_clamp", np.nan),
                         stable=None, iterations=step.iterations)
        if fields:
            rec.fields = self.fields(step.x, step.load)
        return rec

    def fields(self, x, load) -> dict:
        """Centre-line ``P33/mu`` profile and nodal stretch maps (quarter plate, metres)."""
        pb = self.problem
        _, el = pb._electric(load)
        u = pb.T @ x
        F, S = pb._probe(u, pb._probe_line, el)
        return {"kind": np.zeros(len(pb.x_line)), "x1": pb.x_line * 1e-3,
                "x3": np.zeros_like(pb.x_line), "P33": S[1, 1] / pb.material.mu,
                "lam1": F[0, 0], "lam3": F[1, 1]}

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


def build_problem(spec):
    """The FE problem wrapper of ``spec`` (``.problem`` is a ``RampProblem``)."""
    if spec.variant == "membrane":
        return _Membrane(spec)
    raise ValueError(f"variant {spec.variant!r} has no FE driver yet")


def run_fe(spec, start, state, on_step):
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

    Returns
    -------
    RunOutcome
    """
    from skfem_dielectric.newton import ramp

    from .sweep import RunOutcome

    wrap = build_problem(spec)
    targets = [np.array([spec.s, d]) for d in spec.D0]
    x0 = None if state is None else np.asarray(state["x"], dtype=float)
    start_load = None if state is None else np.asarray(state["load"], dtype=float)
    counter = {"i": start}

    def cb(step):
        i = counter["i"]
        rec = wrap.record(step, spec.record_fields)
        if spec.record_fields and spec.D0[i] == 0.0:
            # stretch maps of the pre-loaded plate (kind 1) after the centre line (kind 0)
            maps = wrap.maps(step.x, step.load)
            rec.fields = {k: np.r_[rec.fields[k], maps[k]] for k in rec.fields}
        counter["i"] += 1
        if on_step(i, rec, {"x": step.x, "load": np.asarray(step.load, dtype=float)}):
            raise _Stop

    try:
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)   # the failure is recorded
            res = ramp(wrap.problem, targets[start:], x0=x0, start=start_load, on_step=cb)
    except _Stop:
        return RunOutcome(True)
    failed = None if res.failed_at is None else float(np.asarray(res.failed_at).ravel()[-1])
    return RunOutcome(bool(res.converged), res.reason, failed)


def simulate(**kwargs):
    """Run one FE ramp and export it (``skfem-dielectric simulate``)."""
    raise RuntimeError("the 3D FE drivers of skfem_dielectric are not available yet")


def bench(**kwargs):
    """Time one Keplinger ramp (``skfem-dielectric bench``)."""
    raise RuntimeError("the 3D FE drivers of skfem_dielectric are not available yet")
