"""Benchmark: what holds the memory of the full Keplinger plate ramp.

The reference ramp of ``bench_fe_ramp.py`` (the full plate, 40 x 1 x 20 Q2/Q1/Q2 elements,
40 836 unknowns, pre-load in 6 steps, ``D0 = 0.25 ... 5``, PARDISO if installed) run with
a thread that samples the resident memory (``VmRSS`` of ``/proc/self/status``) every
2 ms and notes in which phase it was highest: set-up, tangent assembly, PARDISO's
analysis (phase 11), factorisation (22) or solve (33).  It prints the unknowns, Newton
iterations and factorisations, the assembly and solve seconds, the peak (sampled, and
the kernel's ``VmHWM``), PARDISO's own report of its memory (``iparm(15)`` peak of the
analysis, ``iparm(16)`` its permanent memory, ``iparm(17)`` the factorisation's, and
the entries of the factors ``iparm(18)``) and the sizes of the arrays the model keeps
between iterations (scatter positions, block buffers, sparsity patterns, the upper
triangle handed to PARDISO, the shape-function gradients).

Each run is its own subprocess, so that its peak resident memory is its own.

Usage::

    python benchmarks/bench_fe_memory.py                      # the reference ramp
    python benchmarks/bench_fe_memory.py --D0-max 0.5         # pre-load + two charge steps
    python benchmarks/bench_fe_memory.py --elements 80 1 40   # the 160k-unknown plate
    python benchmarks/bench_fe_memory.py --solver superlu     # the default install
    python benchmarks/bench_fe_memory.py --smoke              # 2 x 1 x 1, 2 load steps
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import json
import os
import subprocess
import sys
import threading
import time
import warnings


def _status() -> tuple[float, float]:
    """``(VmRSS, VmHWM)`` of this process in MB."""
    out = {}
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(("VmRSS", "VmHWM")):
                key, value = line.split(":")
                out[key] = int(value.split()[0]) / 1024
    return out["VmRSS"], out["VmHWM"]


class Sampler:
    """Highest sampled ``VmRSS`` and the phase (``label``) in which it occurred."""

    def __init__(self, period: float = 0.002):
        self.label = "other (Newton, step limits, post-processing)"
        self.peak, self.where = 0.0, ""
        self.by_phase: dict[str, float] = {}
        self._stop = threading.Event()
        self._period = period
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        while not self._stop.is_set():
            rss = _status()[0]
            lab = self.label
            self.by_phase[lab] = max(self.by_phase.get(lab, 0.0), rss)
            if rss > self.peak:
                self.peak, self.where = rss, lab
            time.sleep(self._period)

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()


def _labelled(cls, name: str, sampler: Sampler, label):
    """Wrap method ``name`` of ``cls`` so that the sampler knows the phase it runs in."""
    f = getattr(cls, name)

    def wrapper(self, *args, **kw):
        old = sampler.label
        sampler.label = label(*args) if callable(label) else label
        try:
            return f(self, *args, **kw)
        finally:
            sampler.label = old

    setattr(cls, name, wrapper)


def _mb(*arrays) -> float:
    return sum(a.nbytes for a in arrays if a is not None) / 2**20


def run(a) -> dict:
    import numpy as np

    from skfem_dielectric import get_linear_solver, keplinger_plate
    from skfem_dielectric.gallery import KEPLINGER_SETTINGS
    from skfem_dielectric.forms.mixed_upphi import MixedUPPhiForm
    from skfem_dielectric.linalg.linear import PardisoSolver

    with Sampler() as smp:
        imports = _status()[0]
        _labelled(MixedUPPhiForm, "structure", smp, "set-up: pattern and scatter positions")
        _labelled(MixedUPPhiForm, "assemble", smp, "tangent assembly")
        _labelled(MixedUPPhiForm, "residual", smp, "residual")
        _labelled(PardisoSolver, "_upper", smp, "upper triangle for PARDISO")
        _labelled(PardisoSolver, "_call", smp, lambda phase, *r: f"PARDISO phase {phase}")
        solver = get_linear_solver(a.solver)
        pardiso = {}
        if isinstance(solver, PardisoSolver):
            solver._ps.set_iparm(18, -1)            # report the entries of the factors
            call = solver._call

            def noted(phase, A, b):
                x = call(phase, A, b)
                ip = solver._ps.iparm
                if phase == 22:
                    pardiso.update(iparm15_MB=ip[14] / 1024, iparm16_MB=ip[15] / 1024,
                                   iparm17_MB=ip[16] / 1024, factor_entries=int(ip[17]))
                return x

            solver._call = noted
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = keplinger_plate(1.0, D0=np.arange(a.D0_step, a.D0_max + 1e-9, a.D0_step),
                                  elements=tuple(a.elements), symmetry="full",
                                  preload_steps=a.preload_steps, linear_solver=solver,
                                  settings=replace(KEPLINGER_SETTINGS, chord=a.chord,
                                                             predictor=a.predictor))
        wall = time.perf_counter() - t0
    f = res.problem.form
    held = {}
    for upper, (sc, cache) in sorted(f._structures.items()):   # the patterns made
        what = "upper triangle" if upper else "whole tangent"
        held[f"{what}: scatter positions (per chunk)"] = _mb(*cache.values())  # BlockScatter
        held[f"{what}: sparsity pattern (indices, indptr)"] = _mb(sc.indices, sc.indptr)
        held[f"{what}: CSR data"] = (sc.nnz + 1) * 8 / 2**20
    held.update({
        "element block buffers (per thread)": _mb(*f._work.values()),
        "shape-function gradients": _mb(f.dNt, None if f.dNphit is f.dNt else f.dNphit),
        "scikit-fem bases (values, gradients)": _mb(*[c.value for fs in f.b2.basis
                                                      for c in fs[:1]],
                                                    *[c.grad for fs in f.b2.basis
                                                      for c in fs[:1]],
                                                    *[c.value for fs in f.b1.basis
                                                      for c in fs[:1]],
                                                    *[c.grad for fs in f.b1.basis
                                                      for c in fs[:1]]),
    })
    cache = getattr(solver, "_ucache", None)
    if cache is not None:
        U = cache[2]
        held["PARDISO's selected upper triangle: data"] = _mb(U.data)
        held["PARDISO's selected upper triangle: indices, indptr"] = _mb(U.indices, U.indptr)
        held["PARDISO's selected upper triangle: selection mask"] = _mb(cache[3])
    return {
        "dofs": int(res.problem.red.n), "elements": list(a.elements), "solver": solver.name,
        "steps": len(res.steps), "converged": bool(res.converged),
        "iterations": int(res.iterations_total), "factorisations": int(res.factorisations),
        "assembly_s": res.assembly_seconds, "solve_s": res.solve_seconds, "wall_s": wall,
        "nnz": {("upper triangle" if up else "whole tangent"): int(sc.nnz)
                for up, (sc, _) in f._structures.items()},
        "imports_MB": imports, "peak_sampled_MB": smp.peak,
        "peak_phase": smp.where, "VmHWM_MB": _status()[1], "by_phase": smp.by_phase,
        "pardiso": pardiso, "held_MB": held,
        "lam1_last": float(res.steps[-1]["lam1"]) if res.steps else float("nan"),
        "load_average": os.getloadavg()[0],
    }


def report(r: dict) -> None:
    nnz = ", ".join(f"{v} nonzeros in the {k}" for k, v in r["nnz"].items())
    print(f"[{r['solver']}] elements {r['elements']}, {r['dofs']} unknowns, {nnz}, "
          f"{r['steps']} load steps, converged {r['converged']}")
    print(f"  iterations {r['iterations']}, factorisations {r['factorisations']}, assembly "
          f"{r['assembly_s']:.1f} s, factorisation + solve {r['solve_s']:.1f} s, wall "
          f"{r['wall_s']:.1f} s (load average {r['load_average']:.2f}), lam1 at the last "
          f"step {r['lam1_last']:.10f}")
    print(f"  peak RSS {r['VmHWM_MB']:.0f} MB (sampled {r['peak_sampled_MB']:.0f} MB in "
          f"'{r['peak_phase']}'); after the imports {r['imports_MB']:.0f} MB")
    print("  highest sampled RSS per phase:")
    for k, v in sorted(r["by_phase"].items(), key=lambda kv: -kv[1]):
        print(f"    {v:8.0f} MB  {k}")
    if r["pardiso"]:
        p = r["pardiso"]
        print(f"  PARDISO: analysis peak {p['iparm15_MB']:.0f} MB, permanent {p['iparm16_MB']:.0f}"
              f" MB, factorisation {p['iparm17_MB']:.0f} MB (permanent + factorisation "
              f"{p['iparm16_MB'] + p['iparm17_MB']:.0f} MB), {p['factor_entries']} entries "
              f"in the factors")
    print("  arrays the model keeps between iterations:")
    for k, v in r["held_MB"].items():
        print(f"    {v:8.1f} MB  {k}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solver", choices=["auto", "pardiso", "superlu"], default="auto")
    ap.add_argument("--elements", type=int, nargs=3, default=[40, 1, 20],
                    metavar=("N1", "N2", "N3"))
    ap.add_argument("--preload-steps", type=int, default=6)
    ap.add_argument("--D0-step", type=float, default=0.25)
    ap.add_argument("--D0-max", type=float, default=5.0)
    ap.add_argument("--chord", type=float, default=0.1)
    ap.add_argument("--predictor", choices=["none", "secant"], default="secant")
    ap.add_argument("--json", action="store_true", help="run here, print JSON (internal)")
    ap.add_argument("--smoke", action="store_true",
                    help="2 x 1 x 1 elements, the pre-load in one step and D0 = 0.25, default "
                         "solver (a check that the script runs, not a measurement)")
    a = ap.parse_args(argv)
    if a.smoke:
        a.elements, a.preload_steps, a.D0_step, a.D0_max = [2, 1, 1], 1, 0.25, 0.25
    if a.json:
        print(json.dumps(run(a)))
        return 0
    cmd = [sys.executable, __file__, "--json", "--solver", a.solver, "--elements",
           *map(str, a.elements), "--preload-steps", str(a.preload_steps), "--D0-step",
           str(a.D0_step), "--D0-max", str(a.D0_max), "--chord", str(a.chord),
           "--predictor", a.predictor]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stderr[-3000:], file=sys.stderr)
        return 1
    report(json.loads(p.stdout.strip().splitlines()[-1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
