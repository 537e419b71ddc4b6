"""The harness with the real FE runner: interrupted sweeps resume to identical files."""

from __future__ import annotations

import filecmp

import numpy as np
import pytest

from validation import cases as vc
from validation.fe import run_fe
from validation.sweep import read_table, run_case


class Interrupted(Exception):
    """Stands for Ctrl-C in the middle of a ramp."""


class StopAfter:
    """The real FE runner, interrupted after ``k`` converged targets (picklable)."""

    def __init__(self, k: int):
        self.k, self.seen = k, 0

    def __call__(self, spec, start, state, on_step):
        def wrapped(i, rec, st):
            stop = on_step(i, rec, st)
            self.seen += 1
            if self.seen >= self.k:
                raise Interrupted
            return stop

        return run_fe(spec, start, state, wrapped)


def small_case():
    runs = (
        # 3D: pre-load in sub-steps, then charge; resumes from (x, load) of a target
        vc.RunSpec("equibiaxial", "Gent", "coupled", 1.5, (0.0, 1.0, 2.0, 3.0)),
        vc.RunSpec("uniaxial", "neo-Hookean", "coupled", vc.keplinger_s(1.0), (0.0, 1.5, 3.0),
                   alpha=1.0, mesh=(("n1", 4), ("n2", 1), ("n3", 2)), record_fields=True,
                   record_maps=True),
        vc.RunSpec("uniaxial", "neo-Hookean", "membrane", vc.keplinger_s(1.0),
                   (0.0, 1.0, 2.0, 3.0, 4.0), alpha=1.0, mesh=(("n1", 8), ("n2", 1), ("n3", 4)),
                   record_fields=True),
        # s = 0: the pre-load is the unloaded state itself (a single target)
        vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 0.0, (0.0, 1.0, 2.0)),
    )
    return vc.Case("zs22", "fig:zs22", "test", "uniaxial", quick=runs, full=runs)


@pytest.mark.parametrize("k", [2, 6, 9])   # inside: 3D homogeneous, 3D Keplinger, membrane
def test_real_fe_resume_is_bit_identical(tmp_path, k):
    case = small_case()
    run_case(case, tmp_path / "full", runner=run_fe, progress=False)
    with pytest.raises(Interrupted):
        run_case(case, tmp_path / "part", runner=StopAfter(k), progress=False)
    n_part = len((tmp_path / "part" / "zs22.csv").read_text().splitlines()) - 1
    assert n_part == k                                   # rows written step by step
    run_case(case, tmp_path / "part", runner=run_fe, progress=False)
    for name in ("zs22.csv", "zs22_fields.csv"):
        assert filecmp.cmp(tmp_path / "full" / name, tmp_path / "part" / name, shallow=False)
    t = read_table(tmp_path / "full" / "zs22.csv")
    # one row per FE target of every run, steps 0, 1, ... in order
    for spec in case.quick:
        assert list(t["step"][t["run"] == spec.key]) == list(range(len(spec.D0)))
    # the homogeneous 3D plates against Eq. (loading_gent) (mixed formulation, Newton
    # tolerance 1e-11 relative): 1e-8
    sel = t["variant"] == "coupled"
    eq = sel & np.isin(t["s"], (0.0, 1.5))
    np.testing.assert_allclose(t["lam1_fe"][eq], t["lam1_analytic"][eq], rtol=1e-8)


def test_process_pool_matches_serial(tmp_path, monkeypatch):
    # two worker processes (--jobs 2) write the same bytes as one serial process: the
    # CSV keeps 12 digits and at most 12 decimals, so threaded-BLAS round-off stays out
    from validation.sweep import run_cases

    eq = vc.Case("nh-d-e", "nh-d-e", "test", "equibiaxial",
                 quick=(vc.RunSpec("equibiaxial", "neo-Hookean", "coupled", 0.0, (0.0, 2.0, 4.0)),
                        vc.RunSpec("equibiaxial", "neo-Hookean", "membrane", 1.0, (0.0, 2.0))))
    monkeypatch.setitem(vc.CASES, "nh-d-e", eq)
    monkeypatch.setitem(vc.CASES, "zs22", small_case())
    names = ["nh-d-e", "zs22"]
    run_cases(names, tmp_path / "serial", quick=True, runner=run_fe, progress=False)
    res = run_cases(names, tmp_path / "pool", quick=True, jobs=2, runner=run_fe, progress=False)
    for n in names:
        assert filecmp.cmp(tmp_path / "serial" / f"{n}.csv", tmp_path / "pool" / f"{n}.csv",
                           shallow=False)
    # homogeneous 3D and membrane plates against Eq. (loading_gent): Newton tolerance
    assert res[0].max_rel_error < 1e-8
