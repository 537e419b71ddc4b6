"""Every script of ``benchmarks/`` runs with ``--smoke``, and its output holds a right number.

``--smoke`` is each benchmark's smallest setting on the code path of the real benchmark
(tiniest mesh, one or two load steps, one repetition, the default solver), so that a
benchmark cannot rot unnoticed; its numbers are not measurements and no time is checked
here (speed is measured by the benchmarks themselves, never in the suite).

The scripts are those of ``benchmarks/*.py`` at collection time: a benchmark added later
runs here too, and needs its check in :data:`CHECKS` (a smoke run whose output is not
compared with anything fails with a message saying so).  Each check compares at least one
printed number with an independent value: a count of unknowns computed from the mesh by
formula, a closed form of the theory, the paper's load ``s = alpha m g / (mu A)``, or the
number of rows that the smoke setting asks for.
"""

from __future__ import annotations

import importlib.util
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = sorted((ROOT / "benchmarks").glob("*.py"))
#: a hang guard, not a speed check (a smoke run costs a few CPU seconds)
HANG_TIMEOUT = 600.0
#: optional extras a smoke run needs: the test skips where they are missing
NEEDS = {"explore_redraw.py": "bokeh", "bench_factor_fill.py": "pypardiso"}

#: the Keplinger plate's load per weight fraction, ``s / alpha = m g / (mu A)`` with
#: ``m = 150 g``, ``g = 9.81 m/s^2``, ``mu = 9833.07 Pa``, ``A = 50 mm^2`` (the paper's data)
S_PER_ALPHA = 0.150 * 9.81 / (9833.07 * 50e-6)
_NUMBER = r"[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|nan|inf)"


def _one(pattern: str, out: str) -> tuple[str, ...]:
    """The groups of the single match of ``pattern`` (multiline) in ``out``."""
    found = re.findall(pattern, out, re.M)
    assert len(found) == 1, f"{pattern!r}: {len(found)} matches in\n{out}"
    return found[0] if isinstance(found[0], tuple) else (found[0],)


def plate_unknowns(elements: tuple[int, int, int], symmetry: str) -> int:
    """Unknowns of the clamped Keplinger plate, counted from its mesh and constraints.

    Q2 displacement (3 per node) and potential, Q1 pressure on ``n1 x n2 x n3`` hexahedra:
    ``a b c`` Q2 nodes with ``a = 2 n1 + 1`` (along x1), ``b = 2 n2 + 1`` (x2),
    ``c = 2 n3 + 1`` (x3); a clamp face has ``b c`` of them.  Removed: ``u2 = u3 = 0`` on
    every clamp, the moving clamp's ``u1`` shared (``b c - 1``), and per symmetry

    * ``full``: the other clamp's ``u1 = 0`` and the potential's constant (one value);
    * ``quarter`` (planes x1 = 0, x3 = 0): ``u1 = 0`` and ``u3 = 0`` on them, the potential's
      constant; the clamp's ``u3`` on the line shared with x3 = 0 counted once;
    * ``eighth`` (also x2 = 0): ``u2 = 0`` and ``phi = 0`` (antisymmetric) on x2 = 0, the
      clamp's lines shared with x2 = 0 and x3 = 0 counted once.
    """
    n1, n2, n3 = elements
    a, b, c = 2 * n1 + 1, 2 * n2 + 1, 2 * n3 + 1
    total = 4 * a * b * c + (n1 + 1) * (n2 + 1) * (n3 + 1)
    clamp = b * c
    if symmetry == "full":
        removed = 2 * (2 * clamp) + clamp + (clamp - 1) + 1
    elif symmetry == "quarter":
        removed = clamp + a * b + clamp + (clamp - b) + (clamp - 1) + 1
    elif symmetry == "eighth":
        removed = clamp + a * b + 2 * a * c + (clamp - c) + (clamp - b) + (clamp - 1)
    else:
        raise ValueError(symmetry)
    return total - removed


def membrane_unknowns(n1: int, n3: int) -> int:
    """Unknowns of the quarter membrane: ``u1, u3`` at ``a c`` Q2 nodes less ``u1 = 0`` on
    x1 = 0 (``c``), ``u3 = 0`` on x3 = 0 (``a``) and on the clamp (``c - 1`` more), and the
    clamp's shared ``u1`` (``c - 1``)."""
    a, c = 2 * n1 + 1, 2 * n3 + 1
    return 2 * a * c - c - a - 2 * (c - 1)


def lam1_uniaxial(s: float, D0: float) -> float:
    """Largest real root of Eq. (DEuniax), ``lam1^2 (lam1 - s) = sqrt(1 + D0^2)``, by
    bisection (``lam1 > max(s, 0)`` on the branch; the cubic grows on it)."""
    rhs = math.sqrt(1.0 + D0 * D0)
    lo, hi = max(s, 0.0), max(s, 0.0) + rhs + 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mid * mid * (mid - s) < rhs else (lo, mid)
    return 0.5 * (lo + hi)


# ---------------------------------------------------------------------------------------
# the checks, one per script: each asserts numbers of the smoke output


def check_analytic(out: str) -> None:
    # rows = the curves asked for: 8 loading curves x 2 models at 1000 points, and the
    # det H* = 0 locus x 2 models at 1000 // 10 points (exact counts)
    rows = re.findall(r"^(.+?)\s+(\d+)\s+\S+\s+\S+ s\s+(?:ok|SLOW)", out, re.M)
    assert [int(n) for _, n in rows] == [1000] * 16 + [100] * 2


def check_buckling_scan(out: str) -> None:
    # the unknowns of the 4 x 1 x 2 eighth model against the count by formula; one row per
    # charge target asked for (0, 1, 2); after the first state one factorisation per class
    # and state (the inertia count), back-substitutions only where a class's count changed;
    # the event scan of buckling_load gives the counts of the full-spectrum scan
    assert int(_one(r"mesh 4x1x2  (\d+) DOFs", out)[0]) == plate_unknowns((4, 1, 2), "eighth")
    rows = re.findall(r"^\s+(\d\.\d{3})\s+(\d+)\s+(\d+)\s+(\S+)\s+(\d+)\s", out, re.M)
    assert [float(r[0]) for r in rows] == [0.0, 1.0, 2.0]
    for _, _, changed, per_class, back in rows[1:]:
        assert float(per_class) == 1.0
        assert (int(back) == 0) == (int(changed) == 0)
    counts = dict(re.findall(r"scan=(\w+): D0_b \S+  counts (\[.*?\])", out))
    assert counts["events"] == counts["full"] == "[" + ", ".join(r[1] for r in rows) + "]"


def check_clamp_wrinkle(out: str) -> None:
    # two rows (centroid, compressive point) for the one alpha x mesh asked for; in each the
    # local J equals lam1 lam2 lam3 (det F of the principal stretches) within the rounding
    # of the printed three decimals
    rows = [ln.split() for ln in out.splitlines() if ln.split()[:2] == ["1.00", "4x1x2"]]
    assert [r[4] for r in rows] == ["centroid", "compressive"]
    for r in rows:
        lam1, lam2, lam3, J = map(float, r[7:11])
        bound = 5e-4 * (lam2 * lam3 + lam1 * lam3 + lam1 * lam2 + 1) + 1e-12
        assert abs(lam1 * lam2 * lam3 - J) <= bound, r


def check_fe_alpha_scan(out: str) -> None:
    # the header's s against the paper's data (4 printed decimals); every row's lam1_hom
    # against Eq. (DEuniax) at the printed (s_step, D0), tolerance 1e-3 (s_step is printed
    # with 3 decimals, d lam1/d s < 1); the last row is the charge target asked for, D0 = 1
    s = float(_one(r"^alpha = 1\.0  s = (\S+)", out)[0])
    assert s == pytest.approx(S_PER_ALPHA, abs=5e-5)
    rows = re.findall(rf"^\s+({_NUMBER})\s+({_NUMBER})\s+({_NUMBER})\s+({_NUMBER})\s", out, re.M)
    assert rows and float(rows[-1][1]) == 1.0
    for s_step, D0, _, hom in rows:
        assert float(hom) == pytest.approx(lam1_uniaxial(float(s_step), float(D0)), abs=1e-3)


def check_fe_corner_failure(out: str) -> None:
    # s of alpha = 0.05 against the paper's data; one converged charge step reported, at the
    # D0 = 1 asked for, and the replay of the failed jump at the D0 = 8 asked for
    s = float(_one(r"^alpha = 0\.05 \(s = (\S+)\)", out)[0])
    assert s == pytest.approx(0.05 * S_PER_ALPHA, abs=5e-5)
    assert [float(v) for v in re.findall(r"^D0 = (\S+)  it", out, re.M)] == [1.0]
    assert float(_one(r"^replay at D0 = (\S+):", out)[0]) == 8.0


def check_fe_isochoric(out: str) -> None:
    # s against the paper's data; one ramp per form asked for (the reference and the four
    # finite-kappa forms), each converged; one table row per D0 asked for (0, 1)
    s = float(_one(r"^alpha = 1\.0 \(s = (\S+)\)", out)[0])
    assert s == pytest.approx(S_PER_ALPHA, abs=5e-5)
    forms = re.findall(r"^# (\S+) kappa=\S+: converged=(\w+)", out, re.M)
    assert forms == [("mixed", "True"), ("mixed-isochoric", "True"), ("isochoric", "True"),
                     ("mixed", "True"), ("penalty", "True")]
    assert [float(v) for v in re.findall(r"^(\d\S*)\s+\d\.\d{6}\s", out, re.M)] == [0.0, 1.0]


def check_fe_keplinger(out: str) -> None:
    # the unknowns and elements of the 2 x 1 x 1 eighth model against the count by formula;
    # the charge target asked for (D0 = 1) reached
    dofs, elements, reached = _one(
        r"^\[superlu\] DOFs (\d+)  elements (\d+)  converged True  last D0 target reached (\S+)",
        out)
    assert int(dofs) == plate_unknowns((2, 1, 1), "eighth")
    assert int(elements) == 2 * 1 * 1
    assert float(reached) == 1.0


def check_fe_membrane(out: str) -> None:
    # s against the paper's data; the reduced unknowns of the 4 x 2 quarter membrane against
    # the count by formula; one row per charge target asked for (0, 1)
    s = float(_one(r"s=(\S+), 4 x 2 Q2 quarter", out)[0])
    assert s == pytest.approx(S_PER_ALPHA, abs=5e-5)
    assert int(_one(r"^DOFs \(reduced\): (\d+)", out)[0]) == membrane_unknowns(4, 2)
    assert [float(v) for v in re.findall(r"^\s*(\d\.\d\d) ", out, re.M)] == [0.0, 1.0]


def check_fe_memory(out: str) -> None:
    # the unknowns of the 2 x 1 x 1 full plate against the count by formula; the load steps
    # asked for: the pre-load in one step and D0 = 0.25
    dofs, steps = _one(r"elements \[2, 1, 1\], (\d+) unknowns, .*?, (\d+) load steps", out)
    assert int(dofs) == plate_unknowns((2, 1, 1), "full")
    assert int(steps) == 2


def check_factor_fill(out: str) -> None:
    # the 4 x 1 x 2 eighth plate, both orderings: its unknowns by formula, the factors at
    # least as many entries as the upper triangle has (the fill only adds), the kept memory
    # at least the factors' doubles
    rows = re.findall(r"^4x1x2,(minimum-degree|metis),(\d+),(\d+),[^,]+,([^,]+),", out, re.M)
    assert [r[0] for r in rows] == ["minimum-degree", "metis"]
    for _, dofs, entries, kept in rows:
        assert int(dofs) == plate_unknowns((4, 1, 2), "eighth")
        assert int(entries) >= int(dofs) and float(kept) >= 8 * int(entries) / 1024**3


def check_fe_ramp(out: str) -> None:
    # as bench_fe_memory.py, and one entry per load step in the per-step iterations
    dofs, steps = _one(r"elements \[2, 1, 1\], (\d+) unknowns, (\d+) load steps", out)
    assert int(dofs) == plate_unknowns((2, 1, 1), "full")
    assert int(steps) == 2
    assert len(_one(r"per step: iterations \[(.*)\]", out)[0].split(",")) == 2


def check_stability_cost(out: str) -> None:
    # the unknowns of the 2 x 1 x 1 quarter model against the count by formula; one row per
    # load step (3 pre-load steps, D0 = 0.5); the monitor's counts equal those of
    # tangent_stability on a fresh assembly, and its eigenvalues within the monitor's
    # eigensolver tolerance (1e-6 relative)
    assert int(_one(r"quarter model 2 x 1 x 1, (\d+) DOFs", out)[0]) == \
        plate_unknowns((2, 1, 1), "quarter")
    assert len(re.findall(r"^  \(\S+, \S+\)\s+\d+ ", out, re.M)) == 4
    dn, de = _one(r"largest count difference (\S+), largest relative eigenvalue difference "
                  r"(\S+)", out)
    assert float(dn) == 0.0
    assert float(de) <= 1e-6


def check_costs(out: str) -> None:
    # the table printed by the smoke run has one row per command the README shows (parsed
    # from README.md by tests/docs/test_readme.py); the two commands --smoke measures have
    # numbers, exit code 0 and this machine's core count, and only they were run
    from test_readme import readme_commands

    rows, demos = {}, []
    for ln in out.splitlines():
        if ln.startswith("| `"):
            cells = [c.strip() for c in ln.strip().strip("|").split("|")]
            rows[cells[0].split("`")[1]] = cells[1:]
            if "(lecture demo " in cells[0]:    # the demos of docs/lecture.md, beside them
                demos.append(cells[0].split("`")[1])
    assert sorted(set(rows) - set(demos)) == sorted(readme_commands())
    assert len(demos) == 7
    ran = re.findall(r"^(\S+)\s+CPU\s+" + _NUMBER + r" s .* exit (\d+)$", out, re.M)
    assert ran == [("list", "0"), ("simulate-help", "0")]
    for cmd in ("skfem-dielectric list", "skfem-dielectric simulate --help"):
        cpu, wall, load, peak, measured = rows[cmd]
        assert float(cpu) > 0 and float(wall) > 0 and float(peak.split()[0]) > 0, rows[cmd]
        assert f", {os.cpu_count()} CPUs, " in measured, measured


def check_validate(out: str) -> None:
    # one row, the one case asked for, and its verdict
    rows = re.findall(rf"^(\S+)\s+{_NUMBER}\s+\d+\s+\d+\s+\d*\s+(\S+)$", out, re.M)
    assert rows == [("figde", "pass")]


def check_wrinkling(out: str) -> None:
    # 2 models x 2 modes x 2 controls rows; neo-Hookean at lam = 1.5: the thin limit
    # sqrt(lam^6 - 1) (Eq. antisym_thin) and, under charge control, the thick limit, the
    # positive root of D0^4 - (lam^6 + 3 lam^3 - 2) D0^2 - (lam^9 + lam^6 + 3 lam^3 - 1) = 0
    # (Eq. ideal-shortwave), both to the printed 5 decimals; the antisymmetric charge curve
    # tends to them at kh = 0.01 and kh = 100 (relative 1e-3 and 1e-5)
    rows = [ln.split() for ln in out.splitlines()
            if ln.split()[:1] in (["neo-Hookean"], ["Gent"])]
    assert len(rows) == 8
    lam = 1.5
    thin = math.sqrt(lam**6 - 1)
    b, c = lam**6 + 3 * lam**3 - 2, lam**9 + lam**6 + 3 * lam**3 - 1
    thick = math.sqrt((b + math.sqrt(b * b + 4 * c)) / 2)
    for model, mode, control, _, _, D_thin, th, D_thick, tk in rows:
        if model != "neo-Hookean":
            continue
        assert float(th) == pytest.approx(thin, abs=1e-5)
        if control == "charge":
            assert float(tk) == pytest.approx(thick, abs=1e-5)
            if mode == "antisymmetric":
                assert float(D_thin) == pytest.approx(thin, rel=1e-3)
                assert float(D_thick) == pytest.approx(thick, rel=1e-5)


def check_check_input(out: str) -> None:
    # the smoke size is read and passes (exact rows: 2001 charges a block), and the 50 MB
    # file is refused with check's one line and exit code 2
    rows = re.findall(r"^\s*([\d.]+)\s+(\d+)\s+(\d+)\s+\S+\s+\S+\s+\S+\s.*check: 1 of 1 "
                      r"cases pass", out, re.M)
    assert len(rows) == 1 and int(rows[0][1]) % 2001 == 0 and rows[0][2] == "0"
    assert re.search(r"^\s*50\.00\s+-\s+2\s.*refused: skfem-dielectric check: error: big.csv: "
                     r"50\.0 MB, above the 12 MB", out, re.M)


def check_explore_redraw(out: str) -> None:
    # one line per slider move asked for: 4 analytic panels, 2 page updates (Bokeh)
    assert len(re.findall(r"CPU s per move", out)) == 6


CHECKS = {
    "bench_analytic.py": check_analytic,
    "bench_buckling_scan.py": check_buckling_scan,
    "bench_check_input.py": check_check_input,
    "bench_clamp_wrinkle.py": check_clamp_wrinkle,
    "bench_costs.py": check_costs,
    "bench_factor_fill.py": check_factor_fill,
    "bench_fe_alpha_scan.py": check_fe_alpha_scan,
    "bench_fe_corner_failure.py": check_fe_corner_failure,
    "bench_fe_isochoric.py": check_fe_isochoric,
    "bench_fe_keplinger.py": check_fe_keplinger,
    "bench_fe_membrane.py": check_fe_membrane,
    "bench_fe_memory.py": check_fe_memory,
    "bench_fe_ramp.py": check_fe_ramp,
    "bench_stability_cost.py": check_stability_cost,
    "bench_validate.py": check_validate,
    "bench_wrinkling.py": check_wrinkling,
    "explore_redraw.py": check_explore_redraw,
}


def test_unknown_counts_by_formula():
    """The counting formulas against the plate the paper's tables name: the full
    40 x 1 x 20 plate has 40 836 unknowns (docs/performance.md)."""
    assert plate_unknowns((40, 1, 20), "full") == 40836


@pytest.mark.parametrize("script", SCRIPTS, ids=[p.name for p in SCRIPTS])
def test_smoke(script: Path):
    if script.name in NEEDS:
        pytest.importorskip(NEEDS[script.name])
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, str(script), "--smoke"], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=HANG_TIMEOUT)
    assert proc.returncode == 0, f"exit code {proc.returncode}\n{proc.stderr[-3000:]}"
    check = CHECKS.get(script.name)
    if check is None:
        pytest.fail(f"benchmarks/{script.name} ran with --smoke but its output is compared "
                    f"with nothing: add its check to CHECKS in tests/docs/test_benchmarks.py\n"
                    f"{proc.stdout[-2000:]}")
    check(proc.stdout)


def test_buckling_scan_on_a_graded_mesh():
    """bench_buckling_scan --grading (the clamp-zone study's meshes): the same checks on
    its rows as the smoke run's (a grading moves nodes, not unknowns)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_buckling_scan.py"),
                           "--meshes", "4x1x2", "--grading", "0.5", "--D0-step", "1",
                           "--D0-max", "2"], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=HANG_TIMEOUT)
    assert proc.returncode == 0, proc.stderr[-2000:]
    out = proc.stdout
    assert int(_one(r"mesh 4x1x2  (\d+) DOFs", out)[0]) == plate_unknowns((4, 1, 2), "eighth")
    rows = re.findall(r"^\s+(\d\.\d{3})\s+(\d+)\s+(\d+)\s+(\S+)\s+(\d+)\s", out, re.M)
    assert [float(r[0]) for r in rows] == [0.0, 1.0, 2.0]
    for _, _, changed, per_class, back in rows[1:]:
        assert float(per_class) == 1.0 and (int(back) == 0) == (int(changed) == 0)


def test_costs_keeps_each_row_as_it_is_measured(tmp_path, monkeypatch):
    """bench_costs writes the table after each command: stopped during the second command
    (an interrupt), the first command's row is in the table with its numbers and the
    second keeps its old row."""
    spec = importlib.util.spec_from_file_location("bench_costs_mod",
                                                  ROOT / "benchmarks" / "bench_costs.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    calls = []

    def fake(command, cwd):
        calls.append(command)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return {"cpu": 12.5, "wall": 13.0, "load": (0.5, 0.75), "peak_mb": 321.0, "exit": 0}

    monkeypatch.setattr(mod, "measure", fake)
    table = tmp_path / "costs.md"
    with pytest.raises(KeyboardInterrupt):
        mod.main(["--only", "list", "curves", "--table", str(table)])
    rows = {ln.split("|")[1].strip(): ln for ln in table.read_text().splitlines()
            if ln.startswith("| `")}
    assert "| 12.5 | 13.0 | 0.50 -> 0.75 | 321 MB |" in rows["`skfem-dielectric list`"]
    assert "not measured" in rows["`skfem-dielectric curves --out results/curves`"]
