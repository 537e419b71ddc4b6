"""Property-based tests of the two row stores: random sequences of writes, kills
(a temporary file left behind, a write cut short), damaged lines and reruns never lose a
finished row (it is in the table or, named, in ``<table>.damaged``) and never keep a
stale one (a row in the table is the last one written for its key)."""

from __future__ import annotations

import csv
import io
import random
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")

from hypothesis import HealthCheck, settings, strategies as st  # noqa: E402
from hypothesis.stateful import (RuleBasedStateMachine, initialize, invariant,  # noqa: E402
                                 rule)

from validation.data.spec import TableSpec, read_table  # noqa: E402
from validation.store import TableWriter  # noqa: E402
from validation.store import StudyStore, read_rows  # noqa: E402

SPEC = TableSpec("demo", "demo.csv", ("alpha", "mesh", "D0_b", "note"), ("alpha", "mesh"),
                 "# a table of the property tests\n", text=frozenset({"mesh", "note"}))
ALPHAS = (0.05, 0.3, 0.7, 1.0, 1.5)
MESHES = ("4x1x2", "8x1x4")
RUNS = settings(max_examples=40, stateful_step_count=25, deadline=None,
                suppress_health_check=[HealthCheck.too_slow])


def _damage(path: Path, rnd: random.Random, kind: str) -> None:
    """Damage one data line of ``path`` (text in a number column, a cell too many, the
    last line end cut), or leave a killed writer's temporary file."""
    if kind == "tmp":
        (path.parent / f".{path.name}.4242.tmp").write_text("half a file")
        return
    if not path.exists():
        return
    lines = path.read_text().splitlines(keepends=True)
    data = [i for i, ln in enumerate(lines) if ln[:1].isdigit()]
    if not data:
        return
    if kind == "cut":                       # the last line end lost (no character more)
        if lines[-1].endswith("\n"):
            path.write_text("".join(lines)[:-1])
        return
    i = rnd.choice(data)
    cells = next(csv.reader([lines[i]]))
    if kind == "text":
        cells[0] = "one"
    else:
        cells.append("extra")
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow(cells)
    lines[i] = buf.getvalue()
    path.write_text("".join(lines))


def _aside_rows(path: Path) -> list[list[str]]:
    aside = path.with_name(path.name + ".damaged")
    if not aside.exists():
        return []
    return [next(csv.reader([ln]), []) for ln in aside.read_text().splitlines()
            if ln and not ln.startswith("#")]


class ClampTable(RuleBasedStateMachine):
    """The clamp-zone writer (:class:`TableWriter`)."""

    @initialize(seed=st.integers(0, 2**16))
    def start(self, seed):
        import tempfile

        self.dir = Path(tempfile.mkdtemp())
        self.path = self.dir / SPEC.file
        self.rnd = random.Random(seed)
        self.written: dict[tuple, list[str]] = {}      # key -> cells of its last row
        self.counter = 0

    def _cells(self, row):
        return [row[c] for c in SPEC.columns]

    @rule(alpha=st.sampled_from(ALPHAS), mesh=st.sampled_from(MESHES),
          recompute=st.booleans())
    def run_unit(self, alpha, mesh, recompute):
        self.counter += 1
        new = {"alpha": alpha, "mesh": mesh, "D0_b": round(1 + self.counter / 8, 4),
               "note": f"run {self.counter}"}
        with TableWriter(self.path, SPEC, note=lambda m: None) as t:
            have = t.find(new)
            if have and not recompute:
                return
            t.add([new], replace=have)
        k = SPEC.key_of(new)
        self.written[k] = [f"{alpha:g}", mesh, f"{new['D0_b']:g}", new["note"]]

    @rule(kind=st.sampled_from(["text", "cells", "cut", "tmp"]))
    def damage(self, kind):
        _damage(self.path, self.rnd, kind)

    @rule()
    def rerun_reads(self):
        with TableWriter(self.path, SPEC, note=lambda m: None):
            pass

    @invariant()
    def nothing_lost_nothing_stale(self):
        if not hasattr(self, "path"):
            return
        rows = read_table(self.path, SPEC)
        table = {SPEC.key_of(r): self._cells(r) for r in rows}
        assert len(table) == len(rows)                   # one row per key
        aside = _aside_rows(self.path)
        text = self.path.read_text() if self.path.exists() else ""
        for k, cells in self.written.items():
            # the last row of a key (its note is unique) is in the table, or kept aside,
            # or still in the file as a damaged line the next write moves aside
            if table.get(k) == cells:
                continue
            assert any(cells[-1] in a for a in aside) or cells[-1] in text, (k, cells)
        for k, cells in table.items():                   # never a stale row
            assert self.written.get(k) == cells, (k, cells)


class StudyTable(RuleBasedStateMachine):
    """The studies' store (:class:`StudyStore`): a table and one detail file."""

    T = TableSpec.plain("t.csv", ("alpha", "mesh", "D0_b", "n"), ("alpha", "mesh"))
    D = TableSpec.plain("d.csv", ("alpha", "mesh", "D0"), ("alpha", "mesh"))

    @initialize(seed=st.integers(0, 2**16))
    def start(self, seed):
        import tempfile

        self.dir = Path(tempfile.mkdtemp())
        self.rnd = random.Random(seed)
        self.written: dict[tuple, tuple] = {}
        self.counter = 0

    def _store(self, plan=()):
        return StudyStore(self.dir, "demo", {"D0_step": 0.5}, self.T, (self.D,),
                          plan=plan, counts={"d.csv": "n"}, note=lambda m: None)

    @rule(alpha=st.sampled_from(ALPHAS), mesh=st.sampled_from(MESHES),
          n=st.integers(1, 3), killed=st.booleans())
    def run_unit(self, alpha, mesh, n, killed):
        self.counter += 1
        key = (alpha, mesh)
        with self._store(plan=[key]) as s:
            if s.done(key):
                return
            d0b = round(1 + self.counter / 8, 4)
            details = [{"alpha": alpha, "mesh": mesh, "D0": d0b + i} for i in range(n)]
            if killed:       # the detail file written, the table not: a kill between
                s.cells["d.csv"][s.table.key_of({"alpha": alpha, "mesh": mesh})] = [
                    [f"{alpha:g}", mesh, f"{r['D0']:g}"] for r in details]
                from validation.store import write_csv_atomic
                write_csv_atomic(self.dir / "d.csv", list(self.D.columns),
                                 [r for rows in s.cells["d.csv"].values() for r in rows])
                return
            s.commit({"alpha": alpha, "mesh": mesh, "D0_b": d0b, "n": n},
                     {"d.csv": details})
        self.written[(f"{alpha:g}", mesh)] = (f"{d0b:g}", n)

    @rule(kind=st.sampled_from(["cut", "tmp"]))
    def damage(self, kind):
        _damage(self.dir / "t.csv", self.rnd, kind)

    @rule()
    def rerun(self):
        with self._store():
            pass

    @invariant()
    def nothing_lost_nothing_stale(self):
        if not hasattr(self, "dir"):
            return
        path = self.dir / "t.csv"
        try:
            rows = read_rows(path)
        except OSError:
            rows = None                     # a cut row: the next open keeps it aside
        text = path.read_text() if path.exists() else ""
        aside = _aside_rows(path)
        table = {} if rows is None else {(f"{r['alpha']:g}", r["mesh"]): r for r in rows}
        for k, (d0b, n) in self.written.items():
            r = table.get(k)
            if r is not None and f"{r['D0_b']:g}" == d0b:
                assert len([x for x in read_rows(self.dir / "d.csv")
                            if (f"{x['alpha']:g}", x["mesh"]) == k]) in (0, n)
                continue
            assert any(a[:3] == [k[0], k[1], d0b] or a[:2] == [k[0], k[1]] for a in aside) \
                or f"{k[0]},{k[1]},{d0b}" in text, (k, d0b)
        for k, r in table.items():
            assert k in self.written and f"{r['D0_b']:g}" == self.written[k][0]


TestClampTable = ClampTable.TestCase
TestClampTable.settings = RUNS
TestStudyTable = StudyTable.TestCase
TestStudyTable.settings = RUNS
