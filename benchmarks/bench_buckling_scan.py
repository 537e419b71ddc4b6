"""Benchmark: the whole-plate scan of a buckling run, event by event against the full spectrum.

The α = 1 run of the main job analysed for buckling (the case ``uni-axial-ideal``): the
grad-div form of the clamped Keplinger plate (eighth model, every symmetry class of the
whole plate) is ramped to the run's charge targets, then its converged states are scanned

* by events (:class:`~skfem_dielectric.models.plate.scan.PlateScan`, the default of the
  harness and of ``buckling_load``): one factorisation per symmetry class and state for
  its inertia count, eigenpairs only where a class's count changes;
* with ``--full`` also by the full spectrum (the lowest physical mode of every class at
  every state, :func:`~skfem_dielectric.models.plate.modes.lowest_physical`).

Per state it prints the negative count of the whole plate, the classes whose count
changed, factorisations per class, back-substitutions and CPU seconds of the scan; per
mesh the averages over the states after the first (the first classifies every negative
mode it finds, a one-off), the ramp's DOFs, CPU seconds, factorisations and the located
``D0_b`` (``buckling_load`` with ``scan="events"``, and ``"full"`` with ``--full``), then
the peak resident memory and the load average.

Usage::

    python benchmarks/bench_buckling_scan.py [--meshes 10x1x5 20x1x10] [--alpha 1]
                                             [--D0-step 0.5] [--D0-max 4] [--full]
    python benchmarks/bench_buckling_scan.py --meshes 20x1x24 --grading 0.1 --D0-max 3 \
        --solver pardiso                                # a graded mesh, the scan only
    python benchmarks/bench_buckling_scan.py --smoke    # 4 x 1 x 2, D0 = 0, 1, 2, --full

``--smoke`` runs the same code path on the smallest mesh: a check that the script runs,
its numbers are not measurements.
"""

from __future__ import annotations

import argparse
import os
import resource
import time
import warnings
from dataclasses import replace

import numpy as np

from skfem_dielectric.linalg.solver_base import back_substitution_count, factorisation_count
from skfem_dielectric.models.plate.scan import PlateScan
from skfem_dielectric.models.plate.symmetry_classes import symmetry_classes
from skfem_dielectric.studies.buckling import buckling_load
from validation.cases import CASES
from validation.fe.model import BUCKLING_NEWTON
from validation.specs import LOCATION_TOL
from validation.fe.runner import grad_div_states
from validation.clamp_zone.units import UNIT_SETTINGS


def _mesh(text: str) -> tuple[int, int, int]:
    try:
        n1, n2, n3 = (int(v) for v in text.split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"a mesh is n1xn2xn3, got {text!r}") from None
    return n1, n2, n3


def states_of(alpha: float, mesh, D0) -> tuple:
    """The grad-div form of the α run of ``uni-axial-ideal`` on ``mesh`` ramped to ``D0``:
    ``(problem, [(x, load), ...], ramp CPU s, factorisations)``."""
    base = next(r for r in CASES["uni-axial-ideal"].runs(True) if r.buckling)
    spec = replace(base, alpha=alpha, s=None, D0=tuple(D0),
                   mesh=(("n1", mesh[0]), ("n2", mesh[1]), ("n3", mesh[2])))
    t, f0 = time.process_time(), factorisation_count()
    problem, states = grad_div_states(spec)
    return problem, states, time.process_time() - t, factorisation_count() - f0


def graded_states_of(alpha: float, mesh, D0, grading: float, solver: str = "auto") -> tuple:
    """The grad-div form of the clamp-zone study's unit (eighth model graded ``grading``
    towards the clamp, :mod:`validation.clamp_zone.units`) ramped to ``D0``: as
    :func:`states_of`."""
    import skfem_dielectric as fe
    from validation.fe.model import BUCKLING_GRAD_DIV

    t, f0 = time.process_time(), factorisation_count()
    pb = fe.gallery.keplinger_problem(elements=tuple(mesh), symmetry="eighth", grading=grading,
                                      options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV))
    s = fe.gallery.keplinger_s(alpha, g=9.81)
    states = []

    def keep(step):
        load = np.asarray(step.load, dtype=float)
        if step.target_reached and load[0] == s:
            states.append((step.x.copy(), load))

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        fe.gallery.run_ramp(pb, fe.gallery.preload_then_charge(
            s, [d for d in D0 if d > 0], fe.gallery.KEPLINGER_PRELOAD_STEPS), on_step=keep,
            linear_solver=solver,
            settings=UNIT_SETTINGS)
    return pb, states, time.process_time() - t, factorisation_count() - f0


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshes", type=_mesh, nargs="+", default=[(10, 1, 5), (20, 1, 10)])
    ap.add_argument("--alpha", type=float, default=1.0)
    ap.add_argument("--D0-step", type=float, default=0.5)
    ap.add_argument("--D0-max", type=float, default=4.0)
    ap.add_argument("--full", action="store_true",
                    help="also scan by the full spectrum and locate D0_b with it")
    ap.add_argument("--grading", type=float, default=None,
                    help="the clamp-zone study's graded mesh (grading towards the clamp) "
                         "instead of the harness's uniform one; the scan only")
    ap.add_argument("--solver", default="auto", choices=["auto", "superlu", "pardiso"])
    ap.add_argument("--smoke", action="store_true",
                    help="4 x 1 x 2 elements, D0 = 0, 1, 2, with --full (a check that the "
                         "script runs, not a measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.meshes, a.D0_step, a.D0_max, a.full = [(4, 1, 2)], 1.0, 2.0, True
    D0 = np.round(np.arange(0.0, a.D0_max + 1e-9, a.D0_step), 10)
    print(f"load average before: {os.getloadavg()[0]:.2f}")
    for mesh in a.meshes:
        if a.grading is None:
            problem, states, ramp_cpu, ramp_fac = states_of(a.alpha, mesh, D0)
        else:
            problem, states, ramp_cpu, ramp_fac = graded_states_of(a.alpha, mesh, D0,
                                                                   a.grading, a.solver)
        n_classes = len(symmetry_classes(problem))
        print(f"alpha = {a.alpha:g}  mesh {mesh[0]}x{mesh[1]}x{mesh[2]}  {problem.ndofs} DOFs  "
              f"{n_classes} symmetry classes  ramp: {len(states)} states, "
              f"{ramp_cpu:.1f} CPU s, {ramp_fac} factorisations", flush=True)
        print("  D0      n_negative  changed  fact/class  back-subs  CPU s  physical")
        scan = PlateScan(problem, method="pardiso" if a.solver == "pardiso" else "auto")
        rows = []
        for x, load in states:
            r = scan.analyse(x, load)
            rows.append(r)
            phys = " ".join(f"{m.eigenvalue:.3e}" for m in r.labels if m.kind == "physical")
            print(f"  {load[1]:6.3f}  {r.n_negative:10d}  {len(r.changed):7d}  "
                  f"{r.factorisations / n_classes:10.2f}  {r.back_substitutions:9d}  "
                  f"{r.cpu:5.2f}  {phys}", flush=True)
        later = rows[1:] or rows
        per_class = np.mean([r.factorisations for r in later]) / n_classes
        print(f"  events, states after the first: {per_class:.2f} "
              f"factorisations per class per state, "
              f"{np.mean([r.back_substitutions for r in later]):.0f} back-substitutions per state, "
              f"{np.mean([r.cpu for r in later]):.2f} CPU s per state; first state "
              f"{rows[0].back_substitutions} back-substitutions")
        scans = ("events", "full") if a.full else ("events",)
        if a.grading is not None:
            scans = ()
        for how in scans:
            t, f0, b0 = time.process_time(), factorisation_count(), back_substitution_count()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                bl = buckling_load(problem, states, tol=LOCATION_TOL, scan=how,
                                   linear_solver="superlu", settings=BUCKLING_NEWTON)
            counts = [row["n_negative"] for row in bl.scan]
            print(f"  buckling_load scan={how}: D0_b {bl.D0_b:.6f}  counts {counts}  "
                  f"{factorisation_count() - f0} factorisations  "
                  f"{back_substitution_count() - b0} back-substitutions  "
                  f"{time.process_time() - t:.1f} CPU s", flush=True)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    print(f"peak resident memory {peak:.2f} GB  load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
