"""Post-processing of 3D plate states: fields at points, stresses, line profiles, export.

Every function takes a :class:`~skfem_dielectric.models.plate.problem.PlateProblem` and a state;
stresses are the *total* physical stresses (elastic, pressure and electric parts; for the local
Maxwell field the Maxwell stress of ``D = F D_L / J`` is added), dimensionless quantities are
divided by ``mu``.  A numerical device of the model never enters them: the grad-div term
``gamma (J - 1)^2 / 2`` of a stabilised model stiffens its weak form but is not part of the
material, so its stress ``gamma (J - 1) J F^-T`` is left out.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import scipy.sparse as sp
from skfem.io.meshio import to_meshio

from ...fem.runtime import SetupCache
from ...forms.maxwell_traction import maxwell_nominal_stress
from ...kinematics import inv3
from ...materials import ideal_dielectric_response

__all__ = ["evaluate_fields", "plate_stresses", "centre_line_points", "clamp_line_points",
           "plate_quantities", "plate_step_mesh"]


#: Point operators built so far in this process, by the plate's layout and the points
#: (at most 256, the oldest dropped first).
_POINT_OPS = SetupCache(256)


def _point_operator(problem, points: np.ndarray) -> sp.csr_matrix:
    """The sparse operator from the full dof vector to the fields at reference ``points``.

    Rows, in blocks of ``n = points.shape[1]``: ``u_a`` (3), ``F_aK - delta_aK`` (9),
    ``phi`` (1), ``Grad phi`` (3), ``p`` (1).  The mesh is the reference configuration, so
    the elements holding the points, their reference coordinates and the basis values and
    gradients there depend on the mesh, the elements and the points only: they are found
    once per point set and plate layout (``problem.layout_key``; plates of one mesh share
    them) and an evaluation is one sparse product.
    """
    layout = getattr(problem, "layout_key", None)
    key = (layout, points.shape, points.tobytes())
    op = _POINT_OPS.get(key) if layout is not None else None
    if op is not None:
        return op
    b2, bphi, bp = problem.b2, problem.bphi, problem.bp
    mp = b2.mapping
    cells = problem.plate.mesh.element_finder(mapping=mp)(*points)
    X = mp.invF(points[:, :, None], tind=cells)
    n = points.shape[1]
    j = np.arange(n)
    rows, cols, vals = [], [], []

    def add(row0, col, v):
        rows.append(row0 * n + j)
        cols.append(col)
        vals.append(np.asarray(v, dtype=float))

    ed2 = b2.element_dofs[:, cells]
    for i in range(ed2.shape[0]):
        df = b2.elem.gbasis(mp, X, i, tind=cells)[0]
        v, g = np.asarray(df)[:, 0], df.grad[:, :, 0]
        for a in range(3):
            col = 3 * ed2[i] + a
            add(a, col, v)
            for K in range(3):
                add(3 + 3 * a + K, col, g[K])
    edf = bphi.element_dofs[:, cells]
    for i in range(edf.shape[0]):
        df = bphi.elem.gbasis(mp, X, i, tind=cells)[0]
        col = problem.off_phi + edf[i]
        add(12, col, np.asarray(df)[:, 0])
        for K in range(3):
            add(13 + K, col, df.grad[K, :, 0])
    if problem.n_p:
        ed1 = bp.element_dofs[:, cells]
        for i in range(ed1.shape[0]):
            df = bp.elem.gbasis(mp, X, i, tind=cells)[0]
            add(16, problem.off_p + ed1[i], np.asarray(df)[:, 0])
    op = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                       shape=(17 * n, problem.n_full))
    if layout is not None:
        _POINT_OPS.put(key, op)
    return op


def evaluate_fields(problem, xf: np.ndarray, points: np.ndarray) -> dict[str, np.ndarray]:
    """Fields of the full dof vector ``xf`` at reference points ``points`` ``(3, n)``.

    The finite-element interpolation ``u = sum_i u_i N_i(X)``, ``F = I + Grad u``,
    ``phi``, ``Grad phi`` and ``p`` at the points, as one sparse product with an operator
    built once per point set (the reference mesh does not move).

    Returns
    -------
    dict
        ``u (3, n)``, ``phi (n)``, ``p (n)`` (zeros for the penalty), ``F (3, 3, n)``,
        ``G = Grad phi (3, n)`` at the points.
    """
    points = np.ascontiguousarray(points, dtype=float)
    n = points.shape[1]
    v = (_point_operator(problem, points) @ np.asarray(xf, dtype=float)).reshape(17, n)
    F = v[3:12].reshape(3, 3, n) + np.eye(3)[:, :, None]
    return {"u": v[0:3].copy(), "phi": v[12].copy(), "p": v[16].copy(), "F": F,
            "G": v[13:16].copy()}


def plate_stresses(problem, F: np.ndarray, G: np.ndarray, p: np.ndarray | None,
                   sigma: float = 0.0) -> dict[str, np.ndarray]:
    """Physical stresses and fields from ``F``, ``G = Grad phi`` and ``p`` (any trailing
    shape).

    ``sigma`` is the charge per reference area, used only by the local Maxwell field.  The
    stress is the material's, Eq. (const-rels1) with Eq. (modelD) (``dOmega*/dF - p
    F^-T``), with the model's multiplier ``p``.  The grad-div stabilisation of the model
    (``problem.grad_div``), a device of the discretisation, is not part of it: a stabilised
    and a plain model give the same stress at the same ``F``, ``p``, ``G``, and the paper's
    ``P33`` criterion reads the material's stress on either.

    Returns
    -------
    dict
        ``P1`` first Piola, ``S`` second Piola-Kirchhoff (total: elastic, pressure and
        electric parts; the paper's ``P``), ``sigma`` Cauchy, ``E``, ``D`` (spatial),
        ``E_L``, ``D_L``, ``J``.
    """
    local = problem.local_field
    r = ideal_dielectric_response(problem.material, F, np.zeros_like(G) if local else G, p,
                                  kappa=problem.kappa, formulation=problem.formulation,
                                  need_tangent=False)
    Finv = inv3(F)
    S = np.einsum("Ka...,aL...->KL...", Finv, r.P)
    cauchy = np.einsum("aK...,bK...->ab...", r.P, F) / r.J
    E_L = -G
    E = np.einsum("Ka...,K...->a...", Finv, E_L)
    D = np.einsum("aK...,K...->a...", F, r.D_L) / r.J
    out = {"P1": r.P, "S": S, "sigma": cauchy, "E": E, "D": D, "E_L": E_L, "D_L": r.D_L,
           "J": r.J}
    if local:   # the total stress adds the Maxwell stress of the assumed field
        eps = problem.material.eps
        tau, P_m = maxwell_nominal_stress(F, -sigma, eps)
        DL = np.zeros_like(G)
        DL[1] = -sigma
        D = np.einsum("aK...,K...->a...", F, DL) / r.J
        out.update(P1=r.P + P_m, S=S + np.einsum("Ka...,aL...->KL...", Finv, P_m),
                   sigma=cauchy + tau, D=D, E=D / eps, D_L=DL,
                   E_L=np.einsum("aK...,a...->K...", F, D / eps))
    return out


def _line(start, end, n):
    t = np.linspace(0.0, 1.0, n)
    return np.asarray(start, float)[:, None] + t * (np.asarray(end, float)
                                                    - np.asarray(start, float))[:, None]


def centre_line_points(plate, n: int | None = None) -> np.ndarray:
    """Points on the x1 centre line (mid-thickness, mid-width) from the model's ``x1``
    start to ``x1 = L1/2`` (``n`` default: two per element)."""
    g1 = plate.grids[0]
    if n is None:
        n = 2 * (len(g1) - 1) + 1
    return _line([g1[0], 0.0, 0.0], [g1[-1], 0.0, 0.0], n)


def clamp_line_points(plate, offset: float | None = None, n: int | None = None) -> np.ndarray:
    """Points on a line along x3 at mid-thickness, a distance ``offset`` (default: one
    element length) inside the clamp ``x1 = L1/2``."""
    g1, g3 = plate.grids[0], plate.grids[2]
    if offset is None:
        offset = g1[-1] - g1[-2]
    if n is None:
        n = 2 * (len(g3) - 1) + 1
    x1 = g1[-1] - offset
    return _line([x1, 0.0, g3[0]], [x1, 0.0, g3[-1]], n)


def _S33(problem, fld, load) -> np.ndarray:
    st = problem.stresses(fld["F"], fld["G"], fld["p"], load)
    return st, st["S"][2, 2] / problem.material.mu


def plate_quantities(problem, x: np.ndarray, load) -> dict[str, Any]:
    """Quantities of a converged state (dimensionless stresses: divided by ``mu``).

    Returns
    -------
    dict
        ``s``, ``D0`` (or ``E0``); ``lam1``, ``lam2``, ``lam3`` (principal-axis
        stretches ``|F e_i|`` at the plate centre); ``lam1_mean``, ``lam2_mean``,
        ``lam3_mean`` (mean face displacements over the model's extent);
        ``P33_centre``; ``min_P33``, ``x1_min_P33`` (minimum of ``S33/mu`` along the
        x1 centre line at mid-thickness and mid-width, and where); for uni-axial
        loading ``min_P33_clamp``, ``x3_min_P33_clamp`` (line along x3 one element
        inside the clamp); ``min_P33_all`` and ``where_min_P33_all`` (over all
        quadrature points); ``D0_centre`` (``|D_L|/sqrt(mu eps)`` at the centre);
        ``centre_line``: dict of arrays along the centre line (``x1``, ``lam1``,
        ``lam3``, ``P33``, ``P11``, ``sigma33``, ``E2``, ``D2``).
    """
    s, e = problem.check_load(load)
    mu, eps = problem.material.mu, problem.material.eps
    plate = problem.plate
    xf = problem.full(x, load)
    q: dict[str, Any] = {"s": s, problem.load_names[1]: e}
    pts = centre_line_points(plate)
    fld = evaluate_fields(problem, xf, pts)
    st, P33 = _S33(problem, fld, load)
    lam = np.linalg.norm(fld["F"], axis=0)          # |F e_K| for K = 1, 2, 3
    i0 = int(np.argmin(np.abs(pts[0])))
    q.update(lam1=float(lam[0, i0]), lam2=float(lam[1, i0]), lam3=float(lam[2, i0]),
             P33_centre=float(P33[i0]),
             D0_centre=float(np.linalg.norm(st["D_L"][:, i0]) / math.sqrt(mu * eps)))
    k = int(np.argmin(P33))
    q.update(min_P33=float(P33[k]), x1_min_P33=float(pts[0, k]))
    q["centre_line"] = {"x1": pts[0], "lam1": lam[0], "lam3": lam[2], "P33": P33,
                        "P11": st["S"][0, 0] / mu, "sigma33": st["sigma"][2, 2] / mu,
                        "E2": st["E"][1], "D2": st["D"][1]}
    if problem.loading == "uniaxial":
        cp = clamp_line_points(plate)
        _, Pc = _S33(problem, evaluate_fields(problem, xf, cp), load)
        kc = int(np.argmin(Pc))
        q.update(min_P33_clamp=float(Pc[kc]), x3_min_P33_clamp=float(cp[2, kc]))
    # over all quadrature points
    best, where = np.inf, None
    for sl, F, G, p in problem.quadrature_fields(x, load):
        S33 = problem.stresses(F, G, p, load)["S"][2, 2] / mu
        j = np.unravel_index(int(np.argmin(S33)), S33.shape)
        if S33[j] < best:
            best = float(S33[j])
            where = problem.b2.mapping.F(problem.b2.X)[:, sl][:, j[0], j[1]]
    q.update(min_P33_all=best, where_min_P33_all=tuple(float(c) for c in where))
    # mean stretches from face displacements
    g, b2 = plate.grids, problem.b2
    for ax, face in ((1, "x1_plus"), (2, "top"), (3, "x3_plus")):
        d = b2.get_dofs(face).all()
        ext = g[ax - 1][-1] - g[ax - 1][0]
        if ax == 1 and 1 not in plate.symmetry and "x1_minus" in plate.mesh.boundaries:
            dm = b2.get_dofs("x1_minus").all()
            q["lam1_mean"] = float(1 + (xf[3 * d].mean() - xf[3 * dm].mean()) / ext)
            continue
        low = 0.0
        if ax not in plate.symmetry:
            other = {2: "bottom", 3: "x3_minus"}.get(ax)
            dm = b2.get_dofs(other).all() if other else None
            low = xf[3 * dm + ax - 1].mean() if dm is not None else 0.0
        q[f"lam{ax}_mean"] = float(1 + (xf[3 * d + ax - 1].mean() - low) / ext)
    return q


def plate_step_mesh(problem, x: np.ndarray, load):
    """meshio ``Mesh`` of one state of a plate (reference coordinates).

    Point data (at the mesh vertices): ``displacement`` (vector), ``potential``,
    ``pressure`` (the mixed multiplier ``p``; zero for the penalty form).  Cell data
    (averages over each element's quadrature points): ``P33`` (second Piola ``S33/mu``),
    ``P11``, ``lam1``, ``lam2``, ``lam3`` (``|F e_i|``), ``J``.
    """
    xf = problem.full(x, load)
    m = problem.plate.mesh
    nv = m.p.shape[1]
    # Q2 and Q1 scalar dofs are numbered vertices first (scikit-fem convention)
    u = xf[: problem.n_u].reshape(-1, 3)[:nv]
    phi = xf[problem.off_phi:][:nv]
    p = (xf[problem.off_p:problem.off_phi][:nv]
         if problem.n_p and problem.pressure == "Q1" else np.zeros(nv))
    mu = problem.material.mu
    cell = {k: [] for k in ("P33", "P11", "lam1", "lam2", "lam3", "J")}
    for _, F, G, pq in problem.quadrature_fields(x, load):
        st = problem.stresses(F, G, pq, load)
        lam = np.linalg.norm(F, axis=0)
        cell["P33"].append((st["S"][2, 2] / mu).mean(axis=-1))
        cell["P11"].append((st["S"][0, 0] / mu).mean(axis=-1))
        for i in range(3):
            cell[f"lam{i + 1}"].append(lam[i].mean(axis=-1))
        cell["J"].append(st["J"].mean(axis=-1))
    cell_data = {k: [np.concatenate(v)] for k, v in cell.items()}
    if problem.n_p and problem.pressure == "P0":       # the element constants
        cell_data["pressure"] = [xf[problem.off_p:problem.off_phi].copy()]
        return to_meshio(m, point_data={"displacement": u, "potential": phi},
                         cell_data=cell_data, encode_cell_data=False)
    return to_meshio(m, point_data={"displacement": u, "potential": phi, "pressure": p},
                     cell_data=cell_data, encode_cell_data=False)
