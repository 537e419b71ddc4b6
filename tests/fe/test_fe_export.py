"""VTU/PVD and XDMF export of a homogeneous ramp, checked against the closed form."""

import meshio
import numpy as np
import pytest

from skfem_dielectric.export import write_vtu_series, write_xdmf
from skfem_dielectric.gallery.drivers import equibiaxial_plate


def test_vtu_series_and_xdmf_hold_the_homogeneous_state(tmp_path):
    s = 1.5
    res = equibiaxial_plate(s, [2.0], elements=(2, 1, 2), preload_steps=2,
                            linear_solver="superlu")
    files = write_vtu_series(res, tmp_path / "vtu")
    assert files[-1].suffix == ".pvd" and len(files) == len(res.steps) + 1
    assert all(f"step_{i:04d}.vtu" in files[-1].read_text() for i in range(len(res.steps)))
    last = meshio.read(files[-2])
    lam = res.steps[-1]["lam1"]
    # homogeneous: u = (lam - 1) X1 e1 + (lam^-2 - 1) X2 e2 + (lam - 1) X3 e3 (round-off)
    X = last.points
    expected = X * np.array([lam - 1, lam**-2 - 1, lam - 1])
    np.testing.assert_allclose(last.point_data["displacement"], expected, atol=1e-10)
    np.testing.assert_allclose(last.cell_data["lam1"][0], lam, rtol=1e-10)
    # lateral second Piola stress S33 = t / lam (nominal t = s mu on x3 faces)
    np.testing.assert_allclose(last.cell_data["P33"][0], s / lam, rtol=1e-9)
    np.testing.assert_allclose(last.cell_data["J"][0], 1.0, atol=1e-10)
    path = write_xdmf(res, tmp_path / "ramp.xdmf")
    with meshio.xdmf.TimeSeriesReader(path) as r:
        r.read_points_cells()
        assert r.num_steps == len(res.steps)
        _, pd, cd = r.read_data(r.num_steps - 1)
    np.testing.assert_allclose(pd["displacement"], last.point_data["displacement"], atol=1e-12)
    np.testing.assert_allclose(cd["P33"][0], s / lam, rtol=1e-9)


def test_export_to_a_path_that_is_a_file_is_a_value_error_naming_it(tmp_path):
    """docs/fe.md: export raises a ``ValueError`` naming the parameter and its value."""
    res = equibiaxial_plate(1.5, [2.0], elements=(2, 1, 2), preload_steps=2,
                            linear_solver="superlu")
    a_file = tmp_path / "a_file"
    a_file.write_text("not a folder\n")
    for call, name, value in [
            (lambda: write_vtu_series(res, a_file), "directory", a_file),
            (lambda: write_vtu_series(res, a_file / "sub"), "directory", a_file / "sub"),
            (lambda: write_xdmf(res, a_file / "ramp.xdmf"), "path", a_file / "ramp.xdmf"),
            (lambda: write_xdmf(res, tmp_path), "path", tmp_path)]:
        with pytest.raises(ValueError) as err:
            call()
        assert str(err.value).startswith(f"{name} must be")
        assert str(value) in str(err.value)
    assert a_file.read_text() == "not a folder\n"
    # an existing XDMF file is overwritten
    assert write_xdmf(res, a_file) == a_file
    with meshio.xdmf.TimeSeriesReader(a_file) as r:
        r.read_points_cells()
        assert r.num_steps == len(res.steps)
