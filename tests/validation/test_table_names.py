"""One name per measured table: the table ``<name>`` of the clamp-zone study is the file
``clamp_<name>.csv``, written by ``clamp-zone <name>`` and tested in
``test_clamp_<name>.py``; a folder of an earlier release, with the tables under their
former file names, is read as it is and renamed by the table's next writer.  And one table
concept for every study: a plain study CSV and a declared clamp-zone table are both a
:class:`TableSpec`, differing only in how a cell is written."""

from __future__ import annotations

import argparse
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from validation.cli import build_parser
from validation.data.registry import TABLES, load, shipped_path, table_file
from validation.data.spec import ForeignTableError, TableSpec
from validation.store import TableWriter

HERE = Path(__file__).parent


def _clamp_zone_subcommands() -> set[str]:
    top = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    cz = top.choices["clamp-zone"]
    sub = next(a for a in cz._actions if isinstance(a, argparse._SubParsersAction))
    return set(sub.choices)


@pytest.mark.parametrize("name", list(TABLES))
def test_a_table_has_one_name_for_its_file_its_command_and_its_tests(name):
    assert TABLES[name].file == f"clamp_{name}.csv"
    assert shipped_path(name).is_file()
    assert (HERE / f"test_clamp_{name}.py").is_file()
    assert name in _clamp_zone_subcommands()


@pytest.mark.parametrize("name", [n for n in TABLES if TABLES[n].former])
def test_a_folder_of_the_former_names_is_read_then_renamed_by_the_writer(name, tmp_path):
    spec = TABLES[name]
    shutil.copy(shipped_path(name), tmp_path / spec.former)
    assert table_file(name, tmp_path) == tmp_path / spec.former
    shipped = load(name)
    assert load(name, tmp_path) == shipped and len(shipped) > 0
    notes = []
    with TableWriter(tmp_path / spec.file, spec, note=notes.append) as t:
        assert len(t.rows) == len(shipped)
    assert not (tmp_path / spec.former).exists()
    assert (tmp_path / spec.file).read_bytes() == shipped_path(name).read_bytes()
    assert len(notes) == 1 and f"renamed {spec.file}" in notes[0]
    assert load(name, tmp_path) == shipped


def test_a_former_name_holding_another_table_is_refused_and_left(tmp_path):
    spec = TABLES["counts"]
    other = tmp_path / spec.former
    shutil.copy(shipped_path("units"), other)
    before = other.read_bytes()
    with pytest.raises(ForeignTableError, match="not the clamp-zone counts table"):
        with TableWriter(tmp_path / spec.file, spec):
            pass
    assert other.read_bytes() == before and not (tmp_path / spec.file).exists()


def test_a_plain_and_a_declared_table_write_a_cell_by_their_digits():
    plain = TableSpec.plain("t.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"))
    declared = TableSpec("t", "t.csv", ("alpha", "mesh", "D0_b"), ("alpha", "mesh"), "")
    x = math.pi
    assert float(plain.cell(x)) == pytest.approx(x, rel=5e-10)
    assert float(declared.cell(x)) == pytest.approx(x, rel=5e-6)
    assert abs(float(declared.cell(x)) - x) > 1e-7          # 6 digits, not 10
    for spec in (plain, declared):
        assert spec.cell(float("nan")) == "" and spec.cell(None) == ""
        assert spec.cell(np.float32(0.5)) == "0.5" and spec.cell(3) == "3"
        assert float(spec.cell(math.inf)) == math.inf
    # a key from a row of values, from the row's cells and from its text agree
    row = {"alpha": 1.5, "mesh": "70x4x36", "D0_b": 4.8}
    cells = [plain.cell(row[c]) for c in plain.columns]
    assert plain.key_of(row) == plain.key_of(cells) == ("1.5", "70x4x36")
    assert plain.key_of({"alpha": "1.50", "mesh": "70x4x36"}) == ("1.5", "70x4x36")


def test_the_table_writer_refuses_a_plain_csv(tmp_path):
    plain = TableSpec.plain("t.csv", ("alpha",), ("alpha",))
    with pytest.raises(ValueError, match="spec must be a declared table"):
        TableWriter(tmp_path / "t.csv", plain)
