"""Export of ramp results for ParaView (meshio VTU series with a PVD index, or XDMF).

Each model writes its own fields (:meth:`~skfem_dielectric.problem.Problem.step_mesh`);
the 3D plate: point data (at the mesh vertices, reference coordinates) ``displacement``
(vector), ``potential``, ``pressure`` (the mixed multiplier ``p``; zero for the penalty
form), cell data (averages over each element's quadrature points) ``P33`` (second Piola
``S33/mu``), ``P11``, ``lam1``, ``lam2``, ``lam3`` (``|F e_i|``), ``J``.  In ParaView apply
"Warp By Vector" with ``displacement`` to see the deformed plate.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import meshio
import numpy as np

from .checks import check_file_path, check_file_prefix, check_folder
from .problem import Problem

__all__ = ["step_mesh", "write_vtu_series", "write_xdmf"]


def step_mesh(problem: Problem, x: np.ndarray, load: Any):
    """meshio ``Mesh`` of one state of a problem (its :meth:`~Problem.step_mesh`).

    Parameters
    ----------
    problem
        The problem (``RampResult.problem``).
    x, load
        Reduced state and its load (``StepResult.x``, ``StepResult.load``).

    Returns
    -------
    meshio.Mesh
    """
    return problem.step_mesh(x, load)


def write_vtu_series(result, directory: str | Path, prefix: str = "step",
                     problem=None) -> list[Path]:
    """Write one VTU file per converged step and a ``<prefix>.pvd`` time-series index.

    Parameters
    ----------
    result
        :class:`~skfem_dielectric.solvers.ramp.RampResult` (its ``problem`` is used unless
        ``problem`` is given).
    directory
        Output directory (created if missing; ``ValueError`` naming ``directory`` if it,
        or a folder on its path, is an existing file).
    prefix
        File name prefix (no path separators: the files stay in ``directory``).
    problem
        Problem override.

    Returns
    -------
    list of Path
        The written VTU files followed by the PVD file.  The PVD "timestep" is the step
        index; each step's load is in the VTU field data ``load``.
    """
    check_file_prefix("prefix", prefix)
    d = check_folder("directory", directory)
    problem = problem if problem is not None else result.problem
    if problem is None:
        raise ValueError("problem is None: pass the PlateProblem that produced the result")
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

    Parameters
    ----------
    result
        :class:`~skfem_dielectric.solvers.ramp.RampResult` (its ``problem`` is used unless
        ``problem`` is given).
    path
        The ``.xdmf`` file (overwritten if it exists; its folder is created if missing).
        ``ValueError`` naming ``path`` if it is an existing folder or a folder on its path
        is an existing file.
    problem
        Problem override.

    Returns
    -------
    Path
        ``path``.
    """
    path = check_file_path("path", path)
    problem = problem if problem is not None else result.problem
    if problem is None:
        raise ValueError("problem is None: pass the PlateProblem that produced the result")
    path.parent.mkdir(parents=True, exist_ok=True)
    meshes = [step_mesh(problem, st.x, st.load) for st in result.steps]
    if not meshes:
        raise ValueError("result has no converged steps to export")
    with meshio.xdmf.TimeSeriesWriter(path, data_format="XML") as w:
        w.write_points_cells(meshes[0].points, meshes[0].cells)
        for i, mm in enumerate(meshes):
            w.write_data(float(i), point_data=mm.point_data, cell_data=mm.cell_data)
    return path
