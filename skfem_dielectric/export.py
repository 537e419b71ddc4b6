"""Export of ramp results for ParaView (meshio VTU series with a PVD index, or XDMF).

Point data (at the mesh vertices, reference coordinates): ``displacement`` (vector),
``potential``, ``pressure`` (the mixed multiplier ``p``; zero for the penalty form).
Cell data (averages over each element's quadrature points): ``P33`` (second Piola
``S33/mu``), ``P11``, ``lam1``, ``lam2``, ``lam3`` (``|F e_i|``), ``J``.  In ParaView apply
"Warp By Vector" with ``displacement`` to see the deformed plate.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["step_mesh", "write_vtu_series", "write_xdmf"]


def step_mesh(problem, x: np.ndarray, load: Any):
    """meshio ``Mesh`` of one state of a :class:`~skfem_dielectric.plate.PlateProblem`.

    Parameters
    ----------
    problem
        The plate problem (``RampResult.problem``).
    x, load
        Reduced state and its load (``StepResult.x``, ``StepResult.load``).

    Returns
    -------
    meshio.Mesh
    """
    from skfem.io.meshio import to_meshio

    if hasattr(problem, "step_mesh"):  # 2D variants (membrane, cross-section) export themselves
        return problem.step_mesh(x, load)
    xf = problem.full(x, load)
    m = problem.plate.mesh
    nv = m.p.shape[1]
    # Q2 and Q1 scalar dofs are numbered vertices first (scikit-fem convention)
    u = xf[: problem.n_u].reshape(-1, 3)[:nv]
    phi = xf[problem.off_phi:][:nv]
    p = xf[problem.off_p:problem.off_phi][:nv] if problem.n_p else np.zeros(nv)
    mu = problem.material.mu
    cell = {k: [] for k in ("P33", "P11", "lam1", "lam2", "lam3", "J")}
    for sl in problem._chunks():
        F, G, pq = problem._fields(xf, sl)
        st = problem.stresses(F, G, pq)
        lam = np.linalg.norm(F, axis=0)
        cell["P33"].append((st["S"][2, 2] / mu).mean(axis=-1))
        cell["P11"].append((st["S"][0, 0] / mu).mean(axis=-1))
        for i in range(3):
            cell[f"lam{i + 1}"].append(lam[i].mean(axis=-1))
        cell["J"].append(st["J"].mean(axis=-1))
    cell_data = {k: [np.concatenate(v)] for k, v in cell.items()}
    return to_meshio(m, point_data={"displacement": u, "potential": phi, "pressure": p},
                     cell_data=cell_data, encode_cell_data=False)


def write_vtu_series(result, directory: str | Path, prefix: str = "step",
                     problem=None) -> list[Path]:
    """Write one VTU file per converged step and a ``<prefix>.pvd`` time-series index.

    Parameters
    ----------
    result
        :class:`~skfem_dielectric.newton.RampResult` (its ``problem`` is used unless
        ``problem`` is given).
    directory
        Output directory (created if missing).
    prefix
        File name prefix.
    problem
        Problem override.

    Returns
    -------
    list of Path
        The written VTU files followed by the PVD file.  The PVD "timestep" is the step
        index; each step's load is in the VTU field data ``load``.
    """
    import meshio

    problem = problem if problem is not None else result.problem
    if problem is None:
        raise ValueError("problem is None: pass the PlateProblem that produced the result")
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    files = []
    for i, st in enumerate(result.steps):
        mesh = step_mesh(problem, st.x, st.load)
        mesh.field_data = {"load": np.atleast_1d(np.asarray(st.load, dtype=float))}
        f = d / f"{prefix}_{i:04d}.vtu"
        meshio.write(f, mesh)
        files.append(f)
    pvd = d / f"{prefix}.pvd"
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    lines += [f'    <DataSet timestep="{i}" group="" part="0" file="{f.name}"/>'
              for i, f in enumerate(files)]
    lines += ["  </Collection>", "</VTKFile>"]
    pvd.write_text("\n".join(lines) + "\n")
    return files + [pvd]


def write_xdmf(result, path: str | Path, problem=None) -> Path:
    """Write the ramp as an XDMF time series (``path``, data inline as XML).

    The XDMF "time" is the step index; the load pairs are not stored in XDMF.  The data
    are written inline (``data_format="XML"``): meshio's HDF5 variant needs ``h5py`` and
    writes the ``.h5`` file into the working directory.
    """
    import meshio

    problem = problem if problem is not None else result.problem
    if problem is None:
        raise ValueError("problem is None: pass the PlateProblem that produced the result")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    meshes = [step_mesh(problem, st.x, st.load) for st in result.steps]
    if not meshes:
        raise ValueError("result has no converged steps to export")
    with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as w:
        w.write_points_cells(meshes[0].points, meshes[0].cells)
        for i, mm in enumerate(meshes):
            w.write_data(float(i), point_data=mm.point_data, cell_data=mm.cell_data)
    return path
