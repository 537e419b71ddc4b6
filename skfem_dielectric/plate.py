"""Fully coupled 3D u-p-phi model of an incompressible ideal-dielectric plate.

Discretisation (Taylor-Hood, locking-free): displacement ``u`` continuous Q2
(``ElementHex2`` per component), pressure ``p`` continuous Q1, potential ``phi`` continuous
Q2 (default; its gradient -- the electric field -- is then approximated in the same space as
the deformation gradient, so the Maxwell stress and the elastic stress converge at the same
rate; ``phi_element="Q1"`` is available and cheaper).  Quadrature: 27 Gauss points per
hexahedron (``intorder=4``; scikit-fem's default for Q2 would be 343).

Energy (see :mod:`skfem_dielectric.materials`)::

    Pi(u, p, phi) = int_V psi(F, p, Grad phi) dV - int_{dV_t} t_A . u dA + int_{dV_q} sigma_F phi dA

a min over ``u``, max over ``phi``, saddle in ``p``; its stationarity gives equilibrium,
``J = 1`` (mixed, ``kappa = inf``) and ``Div D_L = 0`` with ``N . D_L = -sigma_F`` on the
charged faces (Eq. (BCS)).  ``sigma_F`` is a charge per *reference* area: ``+sigma`` on
``top``, ``-sigma`` on ``bottom``, ``sigma = D0 sqrt(mu eps)``, so that ``D_L2 = -sigma``
and ``|D_L| / sqrt(mu eps) = D0``.  With the ``x2`` symmetry plane ``phi = 0`` there
(antisymmetric potential, no charge added); without it ``phi`` is pinned at the plate
centre (the total charge is zero, so the pin carries no reaction).  Voltage control
prescribes ``phi`` on ``top``/``bottom`` so that ``E_L2 = -E0 sqrt(mu/eps)``.

Loads (``load = (s, D0)`` or ``(s, E0)`` under voltage control, ``s`` = nominal traction/mu):

``"equibiaxial"``
    dead nominal traction ``mu s N`` on all lateral faces (``x1_*``, ``x3_*``).
``"uniaxial"``
    the Keplinger experiment: the clamp faces ``x1_plus`` (and ``x1_minus``) have
    ``u2 = u3 = 0``; the moving clamp ``x1_plus`` is a rigid body in ``x1`` -- all its nodes
    share *one* ``u1`` unknown (dof reduction, no penalty) -- carrying the resultant force
    ``mu s A_face`` (``A_face`` = reference area of the modelled clamp face, which accounts
    for the symmetry fraction); without the ``x1`` symmetry plane ``x1_minus`` is the fixed
    clamp (``u = 0``).  ``x3_*`` are free edges.

Everything is assembled with batched numpy over (element, quadrature point) arrays and
scattered through a precomputed :class:`~skfem_dielectric.assembly.ScatterMap`.
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np
from skfem import Basis, ElementHex1, ElementHex2, FacetBasis, LinearForm, asm

from .assembly import DofReduction, ScatterMap
from .materials import _response as _material_response
from .materials import ideal_dielectric_response
from .mesh import PlateMesh

__all__ = ["PlateProblem"]

_LOADINGS = ("equibiaxial", "uniaxial", "none")
_CONTROLS = ("charge", "voltage")


class PlateProblem:
    """Discretised 3D plate; a :class:`~skfem_dielectric.newton.RampProblem`.

    Parameters
    ----------
    plate
        :class:`~skfem_dielectric.mesh.PlateMesh`.
    material
        Ideal dielectric (``NeoHookeanDielectric``, ``GentDielectric``, ``IdealDielectric``).
    loading
        ``"equibiaxial"``, ``"uniaxial"`` (clamped Keplinger plate) or ``"none"``.
    control
        ``"charge"`` (load ``(s, D0)``) or ``"voltage"`` (load ``(s, E0)``).
    formulation
        ``"mixed"`` (u-p-phi, default) or ``"penalty"`` (u-phi with ``kappa (J-1)^2/2``).
    kappa
        Bulk modulus; ``inf`` (mixed only) = exactly incompressible.
    phi_element
        ``"Q2"`` (default) or ``"Q1"``.
    intorder
        Quadrature order (4 -> 27 Gauss points per hexahedron).
    chunk
        Maximum number of elements assembled per batch (bounds the memory of element
        matrices).
    threads
        Worker threads for the batched assembly (default ``min(2, cpu_count)``).

    Raises
    ------
    ValueError
        Unknown options, non-positive ``kappa``, or a mesh lacking the boundaries the loading
        needs (e.g. ``x1_plus`` for the clamp, enough symmetry planes for equi-biaxial).
    """

    def __init__(self, plate: PlateMesh, material, *, loading: str = "equibiaxial",
                 control: str = "charge", formulation: str = "mixed",
                 kappa: float = math.inf, phi_element: str = "Q2", intorder: int = 4,
                 chunk: int = 1500, threads: int | None = None):
        if not isinstance(plate, PlateMesh):
            raise ValueError(f"plate must be a PlateMesh, got {type(plate).__name__}")
        if loading not in _LOADINGS:
            raise ValueError(f"loading must be one of {_LOADINGS}, got {loading!r}")
        if control not in _CONTROLS:
            raise ValueError(f"control must be one of {_CONTROLS}, got {control!r}")
        if formulation not in ("mixed", "penalty"):
            raise ValueError(f"formulation must be 'mixed' or 'penalty', got {formulation!r}")
        kappa = float(kappa)
        if not kappa > 0 or math.isnan(kappa):
            raise ValueError(f"kappa must be > 0, got {kappa}")
        if formulation == "penalty" and not math.isfinite(kappa):
            raise ValueError("kappa must be finite for the penalty formulation, got inf")
        if phi_element not in ("Q1", "Q2"):
            raise ValueError(f"phi_element must be 'Q1' or 'Q2', got {phi_element!r}")
        for attr in ("mu", "eps", "energy_derivatives"):
            if not hasattr(material, attr):
                raise ValueError(f"material must define {attr!r}, got {type(material).__name__}")
        self.plate, self.material = plate, material
        self.loading, self.control = loading, control
        self.formulation, self.kappa = formulation, kappa
        self.phi_element = phi_element
        self.load_names = ("s", "D0") if control == "charge" else ("s", "E0")
        self.chunk = int(chunk)
        if threads is None:
            threads = min(2, os.cpu_count() or 1)
        self.threads = max(1, int(threads))
        self._pool = None
        m = plate.mesh
        names = set(m.boundaries)
        sym = plate.symmetry
        if loading == "uniaxial" and "x1_plus" not in names:
            raise ValueError("loading 'uniaxial' needs the clamp boundary 'x1_plus'")
        if loading == "equibiaxial" and len(sym) < 2:
            raise ValueError("loading 'equibiaxial' needs at least two symmetry planes "
                             f"(symmetry 'quarter' or 'eighth') to remove rigid motions, "
                             f"got symmetry {sym}")
        if "top" not in names:
            raise ValueError("the mesh needs the charged boundary 'top'")

        # ---- bases (shared quadrature) ----
        self.b2 = Basis(m, ElementHex2(), intorder=intorder)
        self.b1 = Basis(m, ElementHex1(), intorder=intorder)
        self.bphi = self.b2 if phi_element == "Q2" else self.b1
        nel, nq = self.b2.nelems, self.b2.X.shape[1]
        self.nel, self.nq = nel, nq
        self.dN = np.ascontiguousarray(np.moveaxis(
            np.array([f[0].grad for f in self.b2.basis]), (0, 1), (2, 3)))   # (e,q,i,K)
        self.N1 = np.ascontiguousarray(np.moveaxis(
            np.array([np.array(f[0]) for f in self.b1.basis]), 0, 2))           # (e,q,k)
        if phi_element == "Q2":
            self.dNphi = self.dN
        else:
            self.dNphi = np.ascontiguousarray(np.moveaxis(
                np.array([f[0].grad for f in self.b1.basis]), (0, 1), (2, 3)))
        self.w = np.asarray(self.b2.dx)                                       # (e,q)
        # matmul-friendly layouts of the shape-function gradients (computed once)
        self.dNt = np.ascontiguousarray(self.dN.transpose(0, 1, 3, 2))       # (e,q,K,i)
        self.dNi = np.ascontiguousarray(self.dN.transpose(0, 2, 1, 3)).reshape(nel, 27, nq * 3)
        self.dNphit = np.ascontiguousarray(self.dNphi.transpose(0, 1, 3, 2))
        self.dNphii = np.ascontiguousarray(self.dNphi.transpose(0, 2, 1, 3)).reshape(
            nel, self.dNphi.shape[2], nq * 3)

        # ---- full dof layout: [u (3 N2, node-major), p (N1, mixed only), phi] ----
        N2, N1, Nphi = self.b2.N, self.b1.N, self.bphi.N
        self.n_u = 3 * N2
        self.n_p = N1 if formulation == "mixed" else 0
        self.off_p = self.n_u
        self.off_phi = self.n_u + self.n_p
        self.n_phi = Nphi
        self.n_full = self.off_phi + Nphi
        e2 = self.b2.element_dofs.T                                            # (e, 27)
        eu = (3 * e2[:, :, None] + np.arange(3)).reshape(nel, -1)
        parts = [eu]
        if self.n_p:
            parts.append(self.off_p + self.b1.element_dofs.T)
        parts.append(self.off_phi + self.bphi.element_dofs.T)
        self.edofs = np.concatenate(parts, axis=1)
        self.m_u, self.m_p = eu.shape[1], (8 if self.n_p else 0)
        self.m_phi = self.bphi.element_dofs.shape[0]

        # ---- constraints ----
        def udofs(name, comp):
            return 3 * self.b2.get_dofs(plate.facets(name)).all() + comp

        def phidofs(name):
            return self.off_phi + self.bphi.get_dofs(plate.facets(name)).all()

        fixed, tied = [], []
        self._phi_top = phidofs("top")
        self._phi_bottom = phidofs("bottom") if "bottom" in names else np.zeros(0, int)
        for ax in sym:
            fixed.append(udofs(f"sym_x{ax}", ax - 1))
        if 2 in sym:
            fixed.append(phidofs("sym_x2"))
        elif control == "charge":
            fixed.append(np.atleast_1d(self.off_phi + self._nearest(self.bphi, self._centre())))
        if control == "voltage":
            fixed += [self._phi_top, self._phi_bottom]
        centre = self._centre()
        if loading == "uniaxial":
            fixed += [udofs("x1_plus", 1), udofs("x1_plus", 2)]
            tied.append(udofs("x1_plus", 0))
            if "x1_minus" in names:
                fixed += [udofs("x1_minus", c) for c in range(3)]
        else:
            # pin the rigid translations the symmetry planes leave free
            k = self._nearest(self.b2, centre)
            for ax in (1, 2, 3):
                if ax not in sym:
                    fixed.append(np.array([3 * k + ax - 1]))
        self.red = DofReduction(self.n_full, np.concatenate(fixed) if fixed else None, tied)
        self.scatter = ScatterMap(self.red.index[self.edofs], self.red.n)
        self._block_pos = self._block_positions()
        self._pos_cache: dict[tuple[int, int], np.ndarray] = {}
        self._work: dict[tuple[int, int, int], np.ndarray] = {}

        # ---- external loads per unit load value ----
        mu, eps = material.mu, material.eps
        self.f_s = np.zeros(self.n_full)     # nominal traction mu * N per unit s
        if loading == "equibiaxial":
            faces = [n for n in ("x1_plus", "x1_minus", "x3_plus", "x3_minus") if n in names]
        elif loading == "uniaxial":
            faces = ["x1_plus"]
        else:
            faces = []
        for name in faces:
            fb = FacetBasis(m, ElementHex2(), facets=m.boundaries[name], intorder=intorder)
            for c in range(3):
                v = asm(LinearForm(lambda v, w, c=c: v * w.n[c]), fb)
                self.f_s[c::3][: N2] += mu * v[:N2]
        self.f_s[self.n_u:] = 0.0
        self.q_D0 = np.zeros(self.n_full)    # charge sigma_F per unit D0 (phi rows)
        for name, sign in (("top", 1.0), ("bottom", -1.0)):
            if name in names:
                fb = FacetBasis(m, self.bphi.elem, facets=m.boundaries[name], intorder=intorder)
                v = asm(LinearForm(lambda v, w: v), fb)
                self.q_D0[self.off_phi:] += sign * math.sqrt(mu * eps) * v
        self.clamp_area = (float(asm(LinearForm(lambda v, w: v), FacetBasis(
            m, ElementHex1(), facets=m.boundaries["x1_plus"])).sum())
            if "x1_plus" in names else 0.0)
        self.stats = {"assembly_calls": 0}

    # ------------------------------------------------------------------ helpers
    def _block_positions(self) -> dict[str, np.ndarray]:
        """Scatter positions of the tangent blocks in the layouts `_element_blocks` uses."""
        red = self.red.index[self.edofs]
        mu_, mp = self.m_u, self.m_p
        U = red[:, :mu_].reshape(self.nel, 27, 3)                 # (e, i, a)
        Ph = red[:, mu_ + mp:]                                    # (e, j)
        sc = self.scatter
        pos = {
            "uu": sc.positions(U[:, :, :, None, None], U.transpose(0, 2, 1)[:, None, None]),
            "uf": sc.positions(U[:, :, :, None], Ph[:, None, None, :]),
            "fu": sc.positions(Ph[:, None, None, :], U[:, :, :, None]),
            "ff": sc.positions(Ph[:, :, None], Ph[:, None, :]),
        }
        if mp:
            Pd = red[:, mu_:mu_ + mp]
            pos["up"] = sc.positions(U[:, :, :, None], Pd[:, None, None, :])
            pos["pu"] = sc.positions(Pd[:, None, None, :], U[:, :, :, None])
            pos["pp"] = sc.positions(Pd[:, :, None], Pd[:, None, :])
        return pos

    def _centre(self) -> np.ndarray:
        """Plate centre (the origin), which lies in every model."""
        return np.zeros(3)

    @staticmethod
    def _nearest(basis, point) -> int:
        d = np.linalg.norm(basis.doflocs - np.asarray(point)[:, None], axis=0)
        return int(np.argmin(d))

    def boundary_dofs(self, name: str, field: str = "u") -> np.ndarray:
        """Full dof indices of boundary ``name`` for ``field`` ``"u"`` (all three components,
        node-major), ``"p"`` or ``"phi"``; ``ValueError`` for unknown names or fields."""
        facets = self.plate.facets(name)
        if field == "u":
            return (3 * self.b2.get_dofs(facets).all()[:, None] + np.arange(3)).ravel()
        if field == "p" and self.n_p:
            return self.off_p + self.b1.get_dofs(facets).all()
        if field == "phi":
            return self.off_phi + self.bphi.get_dofs(facets).all()
        raise ValueError(f"field must be 'u', 'p' (mixed only) or 'phi', got {field!r}")

    def _check_load(self, load) -> tuple[float, float]:
        ld = np.atleast_1d(np.asarray(load, dtype=float))
        if ld.shape != (2,) or not np.all(np.isfinite(ld)):
            raise ValueError(f"load must be a finite pair {self.load_names}, got {load!r}")
        return float(ld[0]), float(ld[1])

    def prescribed(self, load) -> np.ndarray:
        """Full vector of prescribed values (non-zero only for voltage control)."""
        xD = np.zeros(self.n_full)
        if self.control == "voltage":
            _, E0 = self._check_load(load)
            m = self.material
            grad = E0 * math.sqrt(m.mu / m.eps)       # Grad phi_2 = -E_L2 = E0 sqrt(mu/eps)
            xD[self._phi_top] = grad * self.plate.H / 2
            xD[self._phi_bottom] = -grad * self.plate.H / 2
        return xD

    def external(self, load) -> np.ndarray:
        """Full external 'force' vector: tractions (u rows) minus charges (phi rows)."""
        s, e = self._check_load(load)
        f = s * self.f_s
        if self.control == "charge":
            f = f - e * self.q_D0
        return f

    def full(self, x: np.ndarray, load) -> np.ndarray:
        """Full dof vector from the reduced one."""
        return self.red.expand(x, self.prescribed(load))

    def initial_state(self) -> np.ndarray:
        """Reduced zero vector (undeformed, uncharged)."""
        return np.zeros(self.red.n)

    def residual_scale(self, load) -> float:
        """Norm of the reduced external load vector plus ``mu * area`` of a face (so that
        the relative tolerance is meaningful at zero load)."""
        f = self.red.reduce(self.external(load))
        H, L1 = self.plate.H, self.plate.L1
        return float(np.linalg.norm(f)) + self.material.mu * H * L1 * 1e-3

    # --------------------------------------------------------------- kinematics
    def _fields(self, xf: np.ndarray, sl: slice):
        """``F[a, K, e, q]``, ``Grad phi[K, e, q]`` and ``p[e, q]`` of the elements ``sl``."""
        ed = self.edofs[sl]
        ne = ed.shape[0]
        nq = self.nq
        # one (nq*3 x 27) @ (27 x 3) product per element, not one tiny one per point
        ue = xf[ed[:, : self.m_u]].reshape(ne, 27, 3)
        FT = (self.dNt[sl].reshape(ne, nq * 3, 27) @ ue).reshape(ne, nq, 3, 3)  # (e, q, K, a)
        F = np.ascontiguousarray(FT.transpose(3, 2, 0, 1))                    # (a, K, e, q)
        F[0, 0] += 1.0
        F[1, 1] += 1.0
        F[2, 2] += 1.0
        phie = xf[ed[:, self.m_u + self.m_p:]]
        mf = phie.shape[1]
        G = np.ascontiguousarray((self.dNphit[sl].reshape(ne, nq * 3, mf) @ phie[:, :, None])
                                 .reshape(ne, nq, 3).transpose(2, 0, 1))
        if self.m_p:
            pe = xf[ed[:, self.m_u: self.m_u + self.m_p]]
            p = np.einsum("ek,eqk->eq", pe, self.N1[sl])
        else:
            p = None
        return F, G, p

    def _point_response(self, F, G, p, sl, need_tangent=True):
        """Material response of the elements ``sl``: tensor-first stresses, the tangent
        times the quadrature weights in the points-first layout `_element_blocks` uses."""
        return _material_response(self.material, F, G, p, self.kappa, self.formulation,
                                  need_tangent, True, self.w[sl] if need_tangent else None)

    def _response(self, xf, sl, need_tangent=True):
        F, G, p = self._fields(xf, sl)
        return self._point_response(F, G, p, sl, need_tangent), F, G, p

    def _element_residual(self, r, sl):
        w = self.w[sl]
        ne, nq = w.shape
        P = np.moveaxis(r.P * w, (2, 3), (0, 1)).transpose(0, 1, 3, 2)        # e q K a
        ru = (self.dNi[sl] @ np.ascontiguousarray(P).reshape(ne, nq * 3, 3)).reshape(ne, -1)
        parts = [ru]
        if self.m_p:
            parts.append(np.einsum("eqk,eq->ek", self.N1[sl], r.dpsi_dp * w))
        D = np.ascontiguousarray(np.moveaxis(r.D_L * w, 0, 2)).reshape(ne, nq * 3, 1)
        parts.append((self.dNphii[sl] @ D)[:, :, 0])
        return np.concatenate(parts, axis=1)

    def _block_sizes(self) -> list[tuple[str, int]]:
        mp, mf = self.m_p, self.m_phi
        sizes = [("uu", 81 * 81), ("uf", 81 * mf), ("fu", 81 * mf), ("ff", mf * mf)]
        if mp:
            sizes += [("up", 81 * mp), ("pu", 81 * mp)]
            if math.isfinite(self.kappa) and self.formulation == "mixed":
                sizes.append(("pp", mp * mp))
        return sizes

    def _chunk_positions(self, sl) -> np.ndarray:
        """Flat scatter positions of a chunk's block buffer (cached per chunk)."""
        key = (sl.start, sl.stop)
        pos = self._pos_cache.get(key)
        if pos is None:
            P = self._block_pos
            # intp: np.bincount would otherwise convert the int32 positions on every call
            pos = np.concatenate([P[name][sl].ravel() for name, _ in self._block_sizes()]
                                 ).astype(np.intp)
            self._pos_cache[key] = pos
        return pos

    def _element_blocks(self, r, sl) -> np.ndarray:
        """Tangent blocks of a chunk written into one flat buffer (layouts need no
        transposes; the matmuls write in place), ordered as `_chunk_positions`."""
        w = self.w[sl]
        ne, nq = w.shape
        mp, mf = self.m_p, self.m_phi
        dNi, dNt = self.dNi[sl], self.dNt[sl]
        dNphii, dNphit = self.dNphii[sl], self.dNphit[sl]
        sizes = self._block_sizes()
        # the buffer is reused across calls (one per chunk: no page faults of a fresh large
        # array on every call); it is consumed by the scatter before the next call
        size = ne * sum(n for _, n in sizes)
        key = (sl.start, sl.stop, size)
        buf = self._work.get(key)
        if buf is None:
            buf = self._work[key] = np.empty(size)
        views, o = {}, 0
        for name, n in sizes:
            views[name] = buf[o: o + ne * n]
            o += ne * n
        uu = views["uu"].reshape(ne, 27, 243)
        uf = views["uf"].reshape(ne, 27, 3 * mf)
        # u-u, layout (e, i, a, b, j), and u-phi, layout (e, i, a, j), in sub-batches of
        # elements so that the large temporaries stay small (cache, no page faults)
        for a in range(0, ne, 32):
            b = min(a + 32, ne)
            nb = b - a
            A = r.A_FF[a:b].reshape(nb, nq, 27, 3)                        # e q (K a b) L
            V = (A @ dNt[a:b]).reshape(nb, nq * 3, 9 * 27)
            np.matmul(dNi[a:b], V, out=uu[a:b])
            A = r.A_FG[a:b].reshape(nb, nq, 9, 3)                          # e q (K a) L
            np.matmul(dNi[a:b], (A @ dNphit[a:b]).reshape(nb, nq * 3, 3 * mf), out=uf[a:b])
        views["fu"][:] = views["uf"]
        # phi-phi
        np.matmul(dNphii, (r.A_GG @ dNphit).reshape(ne, nq * 3, mf),
                  out=views["ff"].reshape(ne, mf, mf))
        if mp:
            A = r.A_Fp                                                     # e q K a
            V = (A[..., None] * self.N1[sl][:, :, None, None, :]).reshape(ne, nq * 3, 3 * mp)
            np.matmul(dNi, V, out=views["up"].reshape(ne, 27, 3 * mp))
            views["pu"][:] = views["up"]
            if "pp" in views:
                views["pp"][:] = (r.A_pp * np.einsum("eqk,eql,eq->ekl", self.N1[sl],
                                                     self.N1[sl], w)).ravel()
        return buf

    def _chunks(self):
        n = max(1, -(-self.nel // self.chunk))
        if self.threads > 1:
            n = max(n, self.threads)
        bounds = np.linspace(0, self.nel, n + 1).round().astype(int)
        for a, b in zip(bounds[:-1], bounds[1:]):
            if b > a:
                yield slice(int(a), int(b))

    def _assemble_chunk(self, xf, sl):
        r, *_ = self._response(xf, sl)
        data = np.bincount(self._chunk_positions(sl), weights=self._element_blocks(r, sl),
                           minlength=self.scatter.nnz + 1)[: self.scatter.nnz]
        re = self._element_residual(r, sl)
        return data, np.bincount(self.edofs[sl].ravel(), weights=re.ravel(),
                                 minlength=self.n_full)

    def assemble(self, x: np.ndarray, load) -> tuple[Any, np.ndarray]:
        """Reduced tangent (CSR, symmetric) and residual at reduced state ``x``.

        The CSR matrices of one problem share a read-only sparsity pattern
        (:meth:`~skfem_dielectric.assembly.ScatterMap.csr`): copy before in-place
        structural changes such as ``eliminate_zeros``.

        Element batches are assembled by ``threads`` worker threads (numpy releases the GIL
        in the batched matmuls)."""
        xf = self.full(x, load)
        chunks = list(self._chunks())
        if self.threads > 1 and len(chunks) > 1:
            if self._pool is None:
                from concurrent.futures import ThreadPoolExecutor
                self._pool = ThreadPoolExecutor(self.threads)
            parts = list(self._pool.map(lambda sl: self._assemble_chunk(xf, sl), chunks))
        else:
            parts = [self._assemble_chunk(xf, sl) for sl in chunks]
        data = parts[0][0]
        rf = parts[0][1]
        for d, r in parts[1:]:
            if self._pool is not None:     # the sum of the 47 MB data arrays, in threads
                cuts = np.linspace(0, data.size, self.threads + 1).astype(int)
                list(self._pool.map(lambda ab: np.add(data[ab[0]:ab[1]], d[ab[0]:ab[1]],
                                                      out=data[ab[0]:ab[1]]),
                                    zip(cuts[:-1], cuts[1:])))
            else:
                data += d
            rf += r
        rf -= self.external(load)
        self.stats["assembly_calls"] += 1
        return self.scatter.csr(data), self.red.reduce(rf)

    def residual(self, x: np.ndarray, load) -> np.ndarray:
        """Reduced residual only (cheaper; used by the line search)."""
        xf = self.full(x, load)
        rf = np.zeros(self.n_full)
        for sl in self._chunks():
            r, *_ = self._response(xf, sl, need_tangent=False)
            re = self._element_residual(r, sl)
            rf += np.bincount(self.edofs[sl].ravel(), weights=re.ravel(),
                              minlength=self.n_full)
        rf -= self.external(load)
        return self.red.reduce(rf)

    def stability(self, inertia) -> bool | None:
        """Stability verdict from the inertia of the reduced tangent (``None`` if unknown).

        Notes
        -----
        The tangent is ``[[K_uu, K_up, K_uf], [K_pu, K_pp, 0], [K_fu, 0, K_ff]]`` with
        ``K_ff`` negative definite (max over ``phi``) and, for ``kappa = inf``,
        ``K_pp = 0`` with ``K_up`` of full rank.  By Haynsworth's inertia additivity the
        equilibrium is stable -- the charge-controlled mechanical stiffness on the
        incompressible subspace (Schur complement over ``phi`` and ``p``) is positive
        definite -- iff the tangent has exactly ``n_p + n_phi`` negative and no zero
        eigenvalues (``n_p``, ``n_phi`` = free pressure and potential unknowns).
        """
        if inertia is None:
            return None
        idx = self.red.index
        n_p = int(np.count_nonzero(idx[self.off_p:self.off_phi] >= 0))
        n_f = int(np.count_nonzero(idx[self.off_phi:] >= 0))
        npos, nneg, nzero = inertia
        return bool(nneg == n_p + n_f and nzero == 0)

    # ------------------------------------------------------------ post-processing
    def evaluate(self, x: np.ndarray, load, points: np.ndarray) -> dict[str, np.ndarray]:
        """Fields at reference points ``points`` of shape ``(3, n)``.

        Returns
        -------
        dict
            ``u (3, n)``, ``phi (n)``, ``p (n)`` (zeros for the penalty), ``F (3, 3, n)``,
            ``G = Grad phi (3, n)`` at the points.
        """
        xf = self.full(x, load)
        points = np.asarray(points, dtype=float)
        mp = self.b2.mapping
        cells = self.plate.mesh.element_finder(mapping=mp)(*points)
        X = mp.invF(points[:, :, None], tind=cells)
        n = points.shape[1]
        u = np.zeros((3, n))
        F = np.zeros((3, 3, n))
        ed2 = self.b2.element_dofs[:, cells]
        for i in range(ed2.shape[0]):
            df = self.b2.elem.gbasis(mp, X, i, tind=cells)[0]
            for a in range(3):
                ca = xf[3 * ed2[i] + a]
                u[a] += ca * np.array(df)[:, 0]
                F[a] += ca * df.grad[:, :, 0]
        F += np.eye(3)[:, :, None]
        phi, G = np.zeros(n), np.zeros((3, n))
        edf = self.bphi.element_dofs[:, cells]
        for i in range(edf.shape[0]):
            df = self.bphi.elem.gbasis(mp, X, i, tind=cells)[0]
            c = xf[self.off_phi + edf[i]]
            phi += c * np.array(df)[:, 0]
            G += c * df.grad[:, :, 0]
        p = np.zeros(n)
        if self.n_p:
            ed1 = self.b1.element_dofs[:, cells]
            for i in range(ed1.shape[0]):
                df = self.b1.elem.gbasis(mp, X, i, tind=cells)[0]
                p += xf[self.off_p + ed1[i]] * np.array(df)[:, 0]
        return {"u": u, "phi": phi, "p": p, "F": F, "G": G}

    def stresses(self, F: np.ndarray, G: np.ndarray, p: np.ndarray | None) -> dict[str, np.ndarray]:
        """Stresses and fields from ``F``, ``G = Grad phi`` and ``p`` (any trailing shape).

        Returns
        -------
        dict
            ``P1`` first Piola, ``S`` second Piola-Kirchhoff (total: elastic, pressure and
            electric parts; the paper's ``P``), ``sigma`` Cauchy, ``E``, ``D`` (spatial),
            ``E_L``, ``D_L``, ``J``.
        """
        r = ideal_dielectric_response(self.material, F, G, p, kappa=self.kappa,
                                      formulation=self.formulation, need_tangent=False)
        Finv = np.linalg.inv(np.moveaxis(F, (0, 1), (-2, -1)))
        Finv = np.moveaxis(Finv, (-2, -1), (0, 1))
        S = np.einsum("Ka...,aL...->KL...", Finv, r.P)
        sigma = np.einsum("aK...,bK...->ab...", r.P, F) / r.J
        E_L = -G
        E = np.einsum("Ka...,K...->a...", Finv, E_L)
        D = np.einsum("aK...,K...->a...", F, r.D_L) / r.J
        return {"P1": r.P, "S": S, "sigma": sigma, "E": E, "D": D, "E_L": E_L,
                "D_L": r.D_L, "J": r.J}

    def _line(self, start, end, n):
        t = np.linspace(0.0, 1.0, n)
        return np.asarray(start, float)[:, None] + t * (np.asarray(end, float)
                                                        - np.asarray(start, float))[:, None]

    def centre_line_points(self, n: int | None = None) -> np.ndarray:
        """Points on the x1 centre line (mid-thickness, mid-width) from the model's
        ``x1`` start to ``x1 = L1/2``."""
        g1 = self.plate.grids[0]
        if n is None:
            n = 2 * (len(g1) - 1) + 1
        return self._line([g1[0], 0.0, 0.0], [g1[-1], 0.0, 0.0], n)

    def clamp_line_points(self, offset: float | None = None, n: int | None = None) -> np.ndarray:
        """Points on a line along x3 at mid-thickness, a distance ``offset`` (default: one
        element length) inside the clamp ``x1 = L1/2``."""
        g1, g3 = self.plate.grids[0], self.plate.grids[2]
        if offset is None:
            offset = g1[-1] - g1[-2]
        if n is None:
            n = 2 * (len(g3) - 1) + 1
        x1 = g1[-1] - offset
        return self._line([x1, 0.0, g3[0]], [x1, 0.0, g3[-1]], n)

    def postprocess(self, x: np.ndarray, load) -> dict[str, Any]:
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
        s, e = self._check_load(load)
        mu, eps = self.material.mu, self.material.eps
        q: dict[str, Any] = {"s": s, self.load_names[1]: e}
        pts = self.centre_line_points()
        fld = self.evaluate(x, load, pts)
        st = self.stresses(fld["F"], fld["G"], fld["p"])
        lam = np.linalg.norm(fld["F"], axis=0)          # |F e_K| for K = 1, 2, 3
        P33 = st["S"][2, 2] / mu
        i0 = int(np.argmin(np.abs(pts[0])))
        q.update(lam1=float(lam[0, i0]), lam2=float(lam[1, i0]), lam3=float(lam[2, i0]),
                 P33_centre=float(P33[i0]),
                 D0_centre=float(np.linalg.norm(st["D_L"][:, i0]) / math.sqrt(mu * eps)))
        k = int(np.argmin(P33))
        q.update(min_P33=float(P33[k]), x1_min_P33=float(pts[0, k]))
        q["centre_line"] = {"x1": pts[0], "lam1": lam[0], "lam3": lam[2], "P33": P33,
                            "P11": st["S"][0, 0] / mu, "sigma33": st["sigma"][2, 2] / mu,
                            "E2": st["E"][1], "D2": st["D"][1]}
        if self.loading == "uniaxial":
            cp = self.clamp_line_points()
            fc = self.evaluate(x, load, cp)
            Pc = self.stresses(fc["F"], fc["G"], fc["p"])["S"][2, 2] / mu
            kc = int(np.argmin(Pc))
            q.update(min_P33_clamp=float(Pc[kc]), x3_min_P33_clamp=float(cp[2, kc]))
        # over all quadrature points
        xf = self.full(x, load)
        best, where = np.inf, None
        for sl in self._chunks():
            F, G, p = self._fields(xf, sl)
            S33 = self.stresses(F, G, p)["S"][2, 2] / mu
            j = np.unravel_index(int(np.argmin(S33)), S33.shape)
            if S33[j] < best:
                best = float(S33[j])
                where = self.b2.mapping.F(self.b2.X)[:, sl][:, j[0], j[1]]
        q.update(min_P33_all=best, where_min_P33_all=tuple(float(c) for c in where))
        # mean stretches from face displacements
        xr = self.full(x, load)
        g = self.plate.grids
        for ax, face in ((1, "x1_plus"), (2, "top"), (3, "x3_plus")):
            d = self.b2.get_dofs(face).all()
            ext = g[ax - 1][-1] - g[ax - 1][0]
            if ax - 1 == 0 and 1 not in self.plate.symmetry and "x1_minus" in self.plate.mesh.boundaries:
                dm = self.b2.get_dofs("x1_minus").all()
                q["lam1_mean"] = float(1 + (xr[3 * d].mean() - xr[3 * dm].mean()) / ext)
                continue
            lower = f"sym_x{ax}" if ax in self.plate.symmetry else None
            if lower is None:
                other = {2: "bottom", 3: "x3_minus"}.get(ax)
                dm = self.b2.get_dofs(other).all() if other else None
                low = xr[3 * dm + ax - 1].mean() if dm is not None else 0.0
            else:
                low = 0.0
            q[f"lam{ax}_mean"] = float(1 + (xr[3 * d + ax - 1].mean() - low) / ext)
        return q
