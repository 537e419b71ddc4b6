"""J and volume ratios at the clamp (validation.studies.clamp_layer)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from validation.data.key import UnitKey

import skfem_dielectric as fe
from validation.fe.model import BUCKLING_GRAD_DIV
from validation.cli import main
from validation.data.registry import TABLES, load
from validation.clamp_zone.layer import COLUMNS, LAYER_WIDTHS, run_layer, volume_ratios


def test_an_affine_displacement_has_every_ratio_det_F0():
    """u = (F0 - I) X on the graded 6 x 1 x 4 eighth model: J = det F0 at every quadrature
    point, so every element mean, layer and the whole model give det F0 (to 1e-12)."""
    pb = fe.gallery.keplinger_problem(elements=(6, 1, 4), symmetry="eighth", grading=0.25,
                                      options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV))
    F0 = np.array([[1.3, 0.1, 0.0], [0.0, 0.8, 0.05], [0.02, 0.0, 0.9]])
    b2 = pb.form.b2
    X = b2.doflocs                                   # (3, N2) the Q2 nodes
    xf = np.zeros(pb.form.n_full)
    xf[:pb.form.n_u] = ((F0 - np.eye(3)) @ X).T.ravel()
    stub = SimpleNamespace(full=lambda x, load: xf, form=pb.form, plate=pb.plate)
    got = volume_ratios(stub, None, None)
    det = np.linalg.det(F0)
    assert set(got) == {"J_first_min", "J_first_max", "J_second_min", "J_second_max",
                        *(f"V_{d:g}mm" for d in LAYER_WIDTHS), "V_plate"}
    for k, v in got.items():
        assert v == pytest.approx(det, abs=1e-12), k


def test_the_smallest_committed_unit_is_reproduced_and_the_volume_is_kept(tmp_path):
    """alpha = 1, 10 x 1 x 24 graded 0.1 at its D0_b again (default solver): every column
    within 1e-4 of the committed row; the whole model's volume ratio is 1 to 1e-6 (the
    constant is a pressure test function of the mixed form); a rerun keeps the row."""
    ref = next(r for r in load("layer") if r["alpha"] == "1" and r["mesh"] == "10x1x24")
    row = run_layer(UnitKey(1.0, (10, 1, 24), 0.1))
    assert row["D0"] == float(ref["D0"])
    for k in COLUMNS:
        if k.startswith(("J_", "V_")):
            assert abs(row[k] - float(ref[k])) <= 1e-4, k
    assert abs(row["V_plate"] - 1.0) <= 1e-6
    out = tmp_path / "clamp_layer.csv"
    args = ["clamp-zone", "layer", "--alpha", "1", "--mesh", "10x1x24", "--grading", "0.1",
            "--out", str(tmp_path)]
    out.write_text("".join(f"{line}\n" for line in (
        TABLES["layer"].declaration, ",".join(COLUMNS),
        ",".join(str(ref[k]) for k in COLUMNS))))
    before = out.read_bytes()
    assert main(args) == 0 and out.read_bytes() == before


def test_a_unit_without_D0_b_is_one_line(tmp_path, capsys):
    assert main(["clamp-zone", "layer", "--alpha", "0.9", "--mesh", "4x1x2",
                 "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "alpha = 0.9 4x1x2" in err[0] and "clamp-zone units" in err[0]
    assert not (tmp_path / "clamp_layer.csv").exists()
