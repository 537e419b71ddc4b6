"""Benchmark: the full Keplinger plate ramp (alpha = 1), its counts, times and memory.

The reference ramp: the full plate (``symmetry="full"``), 40 x 1 x 20 Q2/Q1/Q2 elements
(40 836 unknowns), pre-load in 6 steps of ``s``, then ``D0 = 0.25, 0.5, ..., 5`` (26 load
steps), ``keplinger_plate``'s Newton settings.  It prints the unknowns, Newton iterations,
factorisations and chord steps (per load step and in total), the medians of one assembly,
one factorisation + solve, one residual-only evaluation and one chord back-substitution,
the wall time, the peak resident memory and the load average of the machine.  Counts and
memory are deterministic; wall times depend on what else runs on the machine (compare
runs in alternating pairs under the same load).

Each run is its own subprocess, so that its peak resident memory is its own.

Usage::

    python benchmarks/bench_fe_ramp.py                       # the reference ramp, PARDISO
    python benchmarks/bench_fe_ramp.py --solver superlu      # the default install
    python benchmarks/bench_fe_ramp.py --elements 80 1 40    # the 160k-unknown plate
    python benchmarks/bench_fe_ramp.py --plain               # every iteration factorises
    python benchmarks/bench_fe_ramp.py --scaling             # s/iteration vs unknowns
    python benchmarks/bench_fe_ramp.py --save ramp.npz       # lam1, fields per step
    python benchmarks/bench_fe_ramp.py --smoke               # 2 x 1 x 1, 2 load steps
    python benchmarks/bench_fe_ramp.py --against OLD --one-core   # beside another tree

``--against OLD`` runs the same ramp with the packages of the source tree ``OLD`` (e.g.
``git archive 13becd9 | tar -x -C OLD``) and of this tree in alternation (``--repeat``
times each, default 3), each in its own subprocess, and prints the counts, the medians of
wall and CPU time (of the ramp, and of the whole process with the interpreter's start and
the imports), the peak memory, the factors' entries and memory (PARDISO's
``iparm(18)``, ``iparm(16) + iparm(17)``) and ordering, the ratio of the medians and the
largest difference of every per-step column (``lam1``, ``lam3``, ``min_P33``, ...).  ``--one-core`` runs every ramp on one core
(``taskset -c 0``); set ``OMP_NUM_THREADS=MKL_NUM_THREADS=OPENBLAS_NUM_THREADS=1`` for one
thread of the linear solver as well.

``--smoke`` runs the same code path on the full plate of 2 x 1 x 1 elements, the pre-load
in one step and ``D0 = 0.25`` with the default solver: a check that the script runs, its
numbers are not measurements.

``--scaling`` runs the pre-load and the first charge steps (``--D0-max 0.5``) on four
meshes (20 x 10, 40 x 20, 56 x 28, 80 x 40) and fits ``t = c n^k`` to the time per
iteration (assembly + factorisation + solve medians) against the unknowns ``n``.
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import json
import os
import resource
import subprocess
import sys
import time
import warnings


def run(a) -> dict:
    import numpy as np

    from skfem_dielectric import get_linear_solver, keplinger_plate
    from skfem_dielectric.gallery import KEPLINGER_SETTINGS

    load0 = os.getloadavg()
    # the precision of the factors keplinger_plate's settings choose (a tree from before
    # the option has none: its solver as it was)
    precision = a.precision or getattr(KEPLINGER_SETTINGS, "factor_precision", None)
    solver = get_linear_solver(a.solver, **({"precision": precision} if precision else {}))
    ps = getattr(solver, "_ps", None)             # PARDISO: report the factors' entries
    if ps is not None:
        ps.set_iparm(18, -1)
    t0, c0 = time.perf_counter(), time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = keplinger_plate(1.0, D0=np.arange(a.D0_step, a.D0_max + 1e-9, a.D0_step),
                              elements=tuple(a.elements), symmetry=a.symmetry,
                              preload_steps=a.preload_steps, linear_solver=solver,
                              settings=replace(
                                  KEPLINGER_SETTINGS,
                                  chord=0.0 if a.plain else (KEPLINGER_SETTINGS.chord
                                                             if a.chord is None else a.chord),
                                  predictor="none" if a.plain else (
                                      KEPLINGER_SETTINGS.predictor if a.predictor is None
                                      else a.predictor),
                                  **({"acceleration": 0, "keep_factors": False}
                                     if a.plain and hasattr(KEPLINGER_SETTINGS,
                                                            "keep_factors") else {})))
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0

    def med(v):
        return float(np.median(v)) if len(v) else float("nan")

    if a.save:
        np.savez(a.save, x=np.array([st.x for st in res.steps]), load=res.column("load"),
                 lam1=res.column("lam1"), lam3=res.column("lam3"),
                 min_P33=res.column("min_P33"))
    steps = len(res.steps)
    return {
        "dofs": int(res.problem.red.n), "elements": list(a.elements), "solver": solver.name,
        "steps": steps, "converged": bool(res.converged), "reason": res.reason,
        "iterations": int(res.iterations_total), "factorisations": int(res.factorisations),
        "chord_steps": int(res.chord_steps),
        "iterations_per_step": res.column("iterations").tolist(),
        "factorisations_per_step": res.column("factorisations").tolist(),
        "assembly_calls": int(res.assembly_calls),
        "assembly_median_s": med(res.assembly_times), "solve_median_s": med(res.solve_times),
        "residual_median_s": med(res.residual_times), "chord_median_s": med(res.chord_times),
        "assembly_s": res.assembly_seconds, "solve_s": res.solve_seconds,
        "residual_s": float(sum(res.residual_times)), "chord_s": float(sum(res.chord_times)),
        "wall_s": wall, "cpu_s": cpu,
        "peak_rss_MB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        "load_average": [load0, os.getloadavg()],
        "lam1_last": float(res.steps[-1]["lam1"]) if steps else float("nan"),
        "columns": {name: [float(st.quantities[name]) for st in res.steps]
                    for name in COLUMNS if steps and name in res.steps[0].quantities},
        "threads": len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else None,
        # PARDISO's own report of its last factorisation: entries of the factors
        # (iparm(18)) and its permanent + factorisation memory (iparm(16) + iparm(17))
        "factor_entries": int(ps.iparm[17]) if ps is not None else None,
        "precision": getattr(solver, "precision", "double" if ps is not None else None),
        "factor_MB": (int(ps.iparm[15]) + int(ps.iparm[16])) / 1024 if ps is not None else None,
        "ordering": getattr(solver, "chosen_ordering", None) or getattr(solver, "ordering", None),
    }


#: The per-step columns compared between two trees (``--against``): those of the
#: validation CSVs of the Keplinger plate.
COLUMNS = ("lam1", "lam3", "min_P33", "x1_min_P33", "min_P33_clamp", "x3_min_P33_clamp")


def report(r: dict) -> None:
    n = max(1, r["steps"])
    print(f"[{r['solver']}] elements {r['elements']}, {r['dofs']} unknowns, {r['steps']} load "
          f"steps, converged {r['converged']} {r['reason'][:120]}")
    print(f"  iterations {r['iterations']} ({r['iterations'] / n:.2f}/step), factorisations "
          f"{r['factorisations']} ({r['factorisations'] / n:.2f}/step), chord steps "
          f"{r['chord_steps']}, assembly calls {r['assembly_calls']}")
    print(f"  per step: iterations {r['iterations_per_step']}")
    print(f"            factorisations {r['factorisations_per_step']}")
    print(f"  medians: assembly {r['assembly_median_s']:.3f} s, factorisation + solve "
          f"{r['solve_median_s']:.3f} s, residual {r['residual_median_s']:.4f} s, chord "
          f"back-substitution {r['chord_median_s']:.4f} s")
    print(f"  totals: assembly {r['assembly_s']:.1f} s, factorisation + solve "
          f"{r['solve_s']:.1f} s, residuals {r['residual_s']:.1f} s, chord {r['chord_s']:.1f} s")
    la = r["load_average"]
    print(f"  wall {r['wall_s']:.1f} s, CPU {r.get('cpu_s', float('nan')):.1f} s, peak RSS "
          f"{r['peak_rss_MB']:.0f} MB, load average "
          f"{la[0][0]:.2f} -> {la[1][0]:.2f} (1 min), lam1 at the last step "
          f"{r['lam1_last']:.8f}")


def child(a, tree: str | None = None, **over) -> dict:
    """Run one benchmark in a subprocess (its own peak memory); returns its JSON.

    ``tree``: a source tree whose packages the subprocess imports (``PYTHONPATH``) instead
    of the installed ones; ``a.one_core``: the subprocess runs on one core."""
    d = dict(vars(a), **over)
    env = dict(os.environ)
    if tree is not None:
        env["PYTHONPATH"] = os.path.abspath(tree)
    prefix = ["taskset", "-c", "0"] if d.get("one_core") else []
    cmd = prefix + [sys.executable, __file__, "--json", "--solver", d["solver"], "--symmetry",
           d["symmetry"], "--elements", *map(str, d["elements"]), "--preload-steps",
           str(d["preload_steps"]), "--D0-step", str(d["D0_step"]), "--D0-max",
           str(d["D0_max"])]
    if d["predictor"] is not None:
        cmd += ["--predictor", d["predictor"]]
    if d["chord"] is not None:
        cmd += ["--chord", str(d["chord"])]
    if d["plain"]:
        cmd.append("--plain")
    if d["save"]:
        cmd += ["--save", d["save"]]
    t0, r0 = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, capture_output=True, text=True, env=env,
                       cwd=tree if tree is not None else None)
    wall, r1 = time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        raise RuntimeError(p.stderr[-2000:])
    out = json.loads(p.stdout.strip().splitlines()[-1])
    # the whole process, the interpreter's start and the imports included
    out["process_wall_s"] = wall
    out["process_cpu_s"] = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return out


def against(a) -> None:
    """The reference ramp of this tree and of the tree ``a.against`` in alternation,
    ``a.repeat`` times each: counts, medians of wall and CPU time, peak memory, the time
    ratio and the largest difference of every per-step column."""
    import numpy as np

    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    trees = {"this tree": here, "reference": a.against}
    runs = {k: [] for k in trees}
    for _ in range(a.repeat):
        for name, tree in trees.items():
            r = child(a, tree=tree)
            runs[name].append(r)
            print(f"  {name:>9}: wall {r['wall_s']:6.1f} s, CPU {r['cpu_s']:6.1f} s, "
                  f"whole process wall {r['process_wall_s']:6.1f} s, CPU "
                  f"{r['process_cpu_s']:6.1f} s, load {r['load_average'][0][0]:.2f} -> "
                  f"{r['load_average'][1][0]:.2f}", flush=True)
    print(f"{'':>10} {'unknowns':>9} {'steps':>5} {'iter.':>5} {'fact.':>5} "
          f"{'wall s':>7} {'CPU s':>7} {'peak MB':>7} {'factor entries':>14} "
          f"{'factors MB':>10} ordering, precision")
    med = {}
    for name, rs in runs.items():
        r = rs[0]
        med[name] = tuple(float(np.median([x[k] for x in rs]))
                          for k in ("wall_s", "cpu_s", "process_wall_s", "process_cpu_s"))
        fill = r.get("factor_entries")
        fmb = r.get("factor_MB")
        print(f"{name:>10} {r['dofs']:>9} {r['steps']:>5} {r['iterations']:>5} "
              f"{r['factorisations']:>5} {med[name][0]:>7.1f} {med[name][1]:>7.1f} "
              f"{max(x['peak_rss_MB'] for x in rs):>7.0f} "
              f"{'-' if fill is None else fill:>14} "
              f"{'-' if fmb is None else format(fmb, '.0f'):>10} {r.get('ordering') or '-'}, "
              f"{r.get('precision') or '-'}")
    print(f"time ratio (this tree / reference, medians): wall "
          f"{med['this tree'][0] / med['reference'][0]:.3f}, CPU "
          f"{med['this tree'][1] / med['reference'][1]:.3f}; the whole process: wall "
          f"{med['this tree'][2] / med['reference'][2]:.3f}, CPU "
          f"{med['this tree'][3] / med['reference'][3]:.3f} (medians "
          f"{med['this tree'][2]:.1f} and {med['reference'][2]:.1f} s wall)")
    new, ref = runs["this tree"][0]["columns"], runs["reference"][0]["columns"]
    for col in COLUMNS:
        if col in new and col in ref and len(new[col]) == len(ref[col]):
            x, y = np.array(new[col]), np.array(ref[col])
            scale = max(float(np.max(np.abs(y))), 1e-300)
            d = np.abs(x - y)
            k = int(np.argmax(d))
            print(f"  {col:>17}: max |difference| {d[k]:.2e} (relative to its largest value "
                  f"{d[k] / scale:.2e}) at step {k}: {x[k]:.10g} against {y[k]:.10g}"
                  + (f"; steps that differ: {np.flatnonzero(d > 0).tolist()}"
                     if col.startswith("x") else ""))


def scaling(a) -> None:
    import numpy as np

    meshes = [(20, 1, 10), (40, 1, 20), (56, 1, 28), (80, 1, 40)]
    rows = []
    print("time per iteration against unknowns (pre-load + charge to D0 = "
          f"{min(a.D0_max, 0.5)}), solver {a.solver}")
    print(f"{'elements':>12} {'unknowns':>9} {'assembly s':>10} {'fact+solve s':>12} "
          f"{'s/iteration':>11} {'peak MB':>8} {'load':>5}")
    for el in meshes:
        r = child(a, elements=list(el), D0_max=min(a.D0_max, 0.5), save=None)
        t = r["assembly_median_s"] + r["solve_median_s"]
        rows.append((r["dofs"], t, r["assembly_median_s"], r["solve_median_s"]))
        print(f"{'x'.join(map(str, el)):>12} {r['dofs']:>9} {r['assembly_median_s']:>10.3f} "
              f"{r['solve_median_s']:>12.3f} {t:>11.3f} {r['peak_rss_MB']:>8.0f} "
              f"{r['load_average'][1][0]:>5.2f}")
    n, t, ta, ts = (np.array(v) for v in zip(*rows))
    for name, y in (("s/iteration", t), ("assembly", ta), ("factorisation + solve", ts)):
        k = np.polyfit(np.log(n), np.log(y), 1)[0]
        print(f"fitted exponent of {name}: {k:.2f}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solver", choices=["auto", "pardiso", "superlu"], default="auto")
    ap.add_argument("--elements", type=int, nargs=3, default=[40, 1, 20],
                    metavar=("N1", "N2", "N3"))
    ap.add_argument("--symmetry", default="full")
    ap.add_argument("--preload-steps", type=int, default=6)
    ap.add_argument("--D0-step", type=float, default=0.25)
    ap.add_argument("--D0-max", type=float, default=5.0)
    ap.add_argument("--chord", type=float, default=None,
                    help="chord contraction of the Newton solves (default: keplinger_plate's)")
    ap.add_argument("--predictor", choices=["none", "secant", "quadratic"], default=None,
                    help="start of each Newton solve (default: keplinger_plate's)")
    ap.add_argument("--precision", choices=["double", "single"], default=None,
                    help="precision of PARDISO's factors (default: keplinger_plate's)")
    ap.add_argument("--plain", action="store_true",
                    help="plain Newton: factorise in every iteration, no predictor")
    ap.add_argument("--save", default=None, help="write lam1, lam3, min P33 and x to NPZ")
    ap.add_argument("--scaling", action="store_true",
                    help="time per iteration on four meshes and the fitted exponent")
    ap.add_argument("--against", default=None, metavar="TREE",
                    help="also run the ramp with the packages of the source tree TREE (e.g. "
                         "a 'git archive' of an earlier commit), in alternation, and compare")
    ap.add_argument("--repeat", type=int, default=3,
                    help="runs of each tree with --against (default: 3)")
    ap.add_argument("--one-core", action="store_true",
                    help="run each ramp on one core (taskset -c 0)")
    ap.add_argument("--json", action="store_true", help="run here, print JSON (internal)")
    ap.add_argument("--smoke", action="store_true",
                    help="2 x 1 x 1 elements, the pre-load in one step and D0 = 0.25, default "
                         "solver (a check that the script runs, not a measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.elements, a.preload_steps, a.D0_step, a.D0_max = [2, 1, 1], 1, 0.25, 0.25
        a.scaling = False
    if a.json:
        print(json.dumps(run(a)))
        return 0
    print("NOTE: counts and memory are deterministic; wall times depend on the machine's load.")
    if a.scaling:
        scaling(a)
        return 0
    if a.against:
        against(a)
        return 0
    report(child(a))
    return 0


if __name__ == "__main__":
    sys.exit(main())
