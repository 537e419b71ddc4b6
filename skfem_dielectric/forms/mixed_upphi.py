"""Mixed u-p-phi weak form of the incompressible ideal dielectric on hexahedra.

Energy (per reference volume; :mod:`skfem_dielectric.materials`)::

    psi(F, p, G) = W(I1) + p (J - 1) - p^2/(2 kappa) - eps/2 J G.C^-1 G - mu0 ln J,
    G = Grad phi = -E_L,   F = I + Grad u,

the paper's Eq. (modelE) (times ``J``, which is 1 in the continuum).  The weak form is the
stationarity of ``Pi = int_V psi dV - (external work)``::

    int_V P : Grad v dV                 = f_u(v)     for all v   (equilibrium)
    int_V (J - 1 - p/kappa) q dV        = 0          for all q   (incompressibility)
    int_V D_L . Grad w dV               = f_phi(w)   for all w   (Gauss: Div D_L = 0),

``P = dpsi/dF``, ``D_L = dpsi/dG``; the right-hand sides (dead tractions, the charges
``-int sigma_F w dA``) belong to the model.  Its linearisation is the symmetric
saddle-point tangent ``[[K_uu, K_up, K_uf], [K_pu, K_pp, 0], [K_fu, 0, K_ff]]`` with
``K_ff`` negative definite.  Under the Maxwell-traction coupling with the electrostatic
field (``elastic_volume=True``) the equilibrium rows carry only the elastic stress
(``G = 0`` in ``P``), the Gauss rows keep ``D_L(F, G)``: the ``u``-``phi`` block vanishes and
the field acts through the boundary (:mod:`skfem_dielectric.forms.maxwell_traction`).

Discretisation (inf-sup stable, locking-free): ``u`` continuous Q2 (``ElementHex2`` per
component), ``p`` continuous Q1 (Taylor-Hood, default) or constant per element (``"P0"``,
the Q2-P0 pair, whose pressure is discontinuous), ``phi`` Q2 (default) or Q1; 27 Gauss points per element
(``intorder=4``).  Everything is computed with batched numpy over (element, quadrature
point) arrays and scattered through precomputed positions
(:class:`~skfem_dielectric.fem.assembly.ScatterMap`), in element chunks assembled by worker
threads.  :class:`~skfem_dielectric.forms.reference.ReferenceForm` states the same form as
plain scikit-fem integrands (the maths, readably); the two are tested equal.
"""

from __future__ import annotations

import math
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from skfem import Basis, ElementHex0, ElementHex1, ElementHex2

from ..fem.assembly import BlockScatter, DofReduction, OrderedSum, ScatterMap, drop_spare_slots
from ..fem.runtime import assembly_threads, single_threaded_blas, trim_heap
from ..materials import MIXED_FORMULATIONS, dielectric_response

__all__ = ["MixedUPPhiForm", "PRESSURE_ELEMENTS", "RESIDUAL_BATCH"]

#: Batches of the residual-only evaluation, in assembly chunks (docs/performance.md).
RESIDUAL_BATCH = 4

#: the pressure spaces: continuous Q1 (Taylor-Hood) or one constant per element (Q2-P0)
PRESSURE_ELEMENTS = ("Q1", "P0")


def _gradient_layouts(basis) -> np.ndarray:
    """Shape-function gradients of ``basis`` as ``(e, q, K, i)`` (``i`` the local
    function, ``K`` the reference direction)."""
    g = np.array([f[0].grad for f in basis.basis])                            # (i,K,e,q)
    return np.ascontiguousarray(g.transpose(2, 3, 1, 0))


def _functions_first(dNt: np.ndarray) -> np.ndarray:
    """The gradients ``(e, q, K, i)`` of a chunk as ``(e, i, q * K)``, the left factor of
    the element products (made per chunk: a second layout of the whole mesh's gradients
    would be kept for the whole assembly; docs/performance.md)."""
    ne, nq, _, nf = dNt.shape
    return np.ascontiguousarray(dNt.transpose(0, 3, 1, 2)).reshape(ne, nf, nq * 3)


def _left_factors(form, sl: slice) -> tuple[np.ndarray, np.ndarray]:
    """``(e, i, q * K)`` gradients of the displacement and of the potential of a chunk."""
    dNi = _functions_first(form.dNt[sl])
    return dNi, (dNi if form.dNphit is form.dNt else _functions_first(form.dNphit[sl]))


def _thread_buffer(work: dict[int, np.ndarray], size: int, most: int) -> np.ndarray:
    """``size`` entries of the calling thread's buffer in ``work`` (made with ``most``
    entries, the largest chunk's, on first use): one per worker thread, reused across
    chunks and calls (no page faults of a fresh large array each time); the scatter
    consumes it before the thread's next chunk."""
    key = threading.get_ident()
    buf = work.get(key)
    if buf is None or buf.size < size:
        buf = work[key] = np.empty(max(size, most))
    return buf[:size]


def _block_positions(form, sl: slice) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Rows and columns of the tangent blocks of ``form``'s elements ``sl`` in the layouts
    `MixedUPPhiForm._element_blocks` uses."""
    red = form.red.index[form.edofs[sl]]
    mu_, mp = form.m_u, form.m_p
    U = red[:, :mu_].reshape(red.shape[0], 27, 3)             # (e, i, a)
    Ph = red[:, mu_ + mp:]                                    # (e, j)
    pos = {
        "uu": (U[:, :, :, None, None], U.transpose(0, 2, 1)[:, None, None]),
        "uf": (U[:, :, :, None], Ph[:, None, None, :]),
        "fu": (Ph[:, None, None, :], U[:, :, :, None]),
        "ff": (Ph[:, :, None], Ph[:, None, :]),
    }
    if mp:
        Pd = red[:, mu_:mu_ + mp]
        pos["up"] = (U[:, :, :, None], Pd[:, None, None, :])
        pos["pu"] = (Pd[:, None, None, :], U[:, :, :, None])
        pos["pp"] = (Pd[:, :, None], Pd[:, None, :])
    return pos


def _lower_coupling(form) -> bool:
    """Whether the reduced unknowns of ``p`` and ``phi`` all follow those of ``u`` (the
    ``p``-``u`` and ``phi``-``u`` blocks then lie below the diagonal)."""
    idx = form.red.index
    u, rest = idx[: form.n_u], idx[form.n_u:]
    u, rest = u[u >= 0], rest[rest >= 0]
    return not (u.size and rest.size) or int(u.max()) < int(rest.min())


def _block_sizes(form, upper: bool = False) -> list[tuple[str, int]]:
    """Names and entries per element of the blocks of ``form``'s element buffer (for the
    upper triangle without the blocks that lie below the diagonal)."""
    mp, mf = form.m_p, form.m_phi
    below = upper and _lower_coupling(form)     # the blocks "fu", "pu" are not needed
    sizes = [("uu", 81 * 81), ("uf", 81 * mf)] + ([] if below else [("fu", 81 * mf)])
    sizes.append(("ff", mf * mf))
    if mp:
        sizes += [("up", 81 * mp)] + ([] if below else [("pu", 81 * mp)])
        if math.isfinite(form.kappa) and form.formulation in MIXED_FORMULATIONS:
            sizes.append(("pp", mp * mp))
    return sizes


class MixedUPPhiForm:
    """Volume terms of the mixed u-p-phi plate on a hexahedral mesh.

    Parameters
    ----------
    mesh
        scikit-fem ``MeshHex``.
    material
        Ideal dielectric (``mu``, ``eps``, ``energy_derivatives``).
    formulation, kappa
        ``"mixed"`` (u-p-phi), ``"penalty"`` (u-phi, ``W(I1) + kappa (J-1)^2/2``) or
        ``"isochoric"`` (u-phi, ``W(J^(-2/3) I1) + kappa (J-1)^2/2``) or
        ``"mixed-isochoric"`` (u-p-phi, ``W(J^(-2/3) I1) + p (J-1) - p^2/(2 kappa)``).
    phi_element
        ``"Q2"`` or ``"Q1"``.
    pressure
        The pressure space of the mixed forms, one of :data:`PRESSURE_ELEMENTS`.
    intorder, chunk, threads
        Quadrature order, elements per batch, worker threads.
    elastic_volume
        Equilibrium rows with the elastic stress only (Maxwell-traction coupling).
    grad_div
        Grad-div stabilisation ``gamma (J - 1)^2 / 2`` of the mixed form
        (:func:`~skfem_dielectric.materials.ideal_dielectric_response`).

    Notes
    -----
    Full dof layout: ``[u (3 N2, node-major), p (Np, mixed only), phi (Nphi)]`` with offsets
    ``off_p`` and ``off_phi``.  :meth:`bind` attaches the dof reduction of the model
    (constraints), after which :meth:`assemble` and :meth:`residual` work on reduced
    vectors.
    """

    def __init__(self, mesh, material, *, formulation: str = "mixed", kappa: float = math.inf,
                 phi_element: str = "Q2", intorder: int = 4, chunk: int = 50,
                 threads: int | None = None, elastic_volume: bool = False,
                 grad_div: float = 0.0, pressure: str = "Q1"):
        self.material, self.formulation, self.kappa = material, formulation, kappa
        self.grad_div = grad_div
        self.elastic_volume = elastic_volume
        self.chunk = int(chunk)
        self.threads = max(1, int(assembly_threads() if threads is None else threads))
        self._pool = None
        self.b2 = Basis(mesh, ElementHex2(), intorder=intorder)
        self.b1 = Basis(mesh, ElementHex1(), intorder=intorder)
        self.bphi = self.b2 if phi_element == "Q2" else self.b1
        self.pressure = pressure
        self.bp = self.b1 if pressure == "Q1" else Basis(mesh, ElementHex0(), intorder=intorder)
        nel, nq = self.b2.nelems, self.b2.X.shape[1]
        self.nel, self.nq = nel, nq
        self.N1 = np.ascontiguousarray(np.moveaxis(
            np.array([np.array(f[0]) for f in self.bp.basis]), 0, 2))           # (e,q,k)
        self.w = np.asarray(self.b2.dx)                                       # (e,q)
        # matmul-friendly layouts of the shape-function gradients (computed once; the
        # Q2 potential shares the displacement's arrays)
        self.dNt = _gradient_layouts(self.b2)                             # (e,q,K,i)
        self.dNphit = self.dNt if phi_element == "Q2" else _gradient_layouts(self.b1)
        N2 = self.b2.N
        self.n_u = 3 * N2
        self.n_p = self.bp.N if formulation in MIXED_FORMULATIONS else 0
        self.off_p = self.n_u
        self.off_phi = self.n_u + self.n_p
        self.n_phi = self.bphi.N
        self.n_full = self.off_phi + self.n_phi
        e2 = self.b2.element_dofs.T                                            # (e, 27)
        eu = (3 * e2[:, :, None] + np.arange(3)).reshape(nel, -1)
        parts = [eu] + ([self.off_p + self.bp.element_dofs.T] if self.n_p else [])
        parts.append(self.off_phi + self.bphi.element_dofs.T)
        self.edofs = np.concatenate(parts, axis=1)
        self.m_u, self.m_p = eu.shape[1], (self.bp.Nbfun if self.n_p else 0)
        self.m_phi = self.bphi.element_dofs.shape[0]
        self.red: DofReduction | None = None

    @property
    def fields(self) -> dict[str, slice]:
        """Full-dof ranges of the field blocks ``u``, ``p`` (mixed only), ``phi``."""
        out = {"u": slice(0, self.n_u)}
        if self.n_p:
            out["p"] = slice(self.off_p, self.off_phi)
        out["phi"] = slice(self.off_phi, self.n_full)
        return out

    def bind(self, red: DofReduction) -> None:
        """Attach the model's dof reduction; the sparsity pattern and the scatter positions
        of the whole tangent and of its upper triangle are made on first use."""
        self.red = red
        self._structures: dict[bool, tuple[ScatterMap, dict]] = {}
        self._work: dict[int, np.ndarray] = {}

    def structure(self, upper: bool = False) -> tuple[ScatterMap, dict]:
        """The :class:`~skfem_dielectric.fem.assembly.ScatterMap` of the tangent (``upper``:
        of its upper triangle) and the scatter positions of the chunks, made on first use
        (a model factorised by the symmetric PARDISO never needs the whole pattern)."""
        got = self._structures.get(bool(upper))
        if got is None:
            sc = ScatterMap(self.red.index[self.edofs], self.red.n, upper=bool(upper))
            got = self._structures[bool(upper)] = (sc, {})
            for sl in self.chunks():    # chunk by chunk: the searches' temporaries stay small
                self._chunk_positions(sl, upper)
            sc.compact()
        return got

    @property
    def scatter(self) -> ScatterMap:
        """The :class:`~skfem_dielectric.fem.assembly.ScatterMap` of the whole tangent."""
        return self.structure(False)[0]

    @property
    def upper_scatter(self) -> ScatterMap:
        """The :class:`~skfem_dielectric.fem.assembly.ScatterMap` of the upper triangle."""
        return self.structure(True)[0]

    # ------------------------------------------------------------------ layout
    def _chunk_positions(self, sl, upper: bool = False) -> BlockScatter:
        """Scatter positions of a chunk's block buffer (cached per chunk; 16-bit offsets
        in the rows, added by ``np.add.at``, which needs no 64-bit copy; for the upper
        triangle in the spare layout, whose spare slots take the entries below the
        diagonal)."""
        scatter, cache = self.structure(upper)
        key = (sl.start, sl.stop)
        pos = cache.get(key)
        if pos is None:
            P = _block_positions(self, sl)
            pos = BlockScatter(scatter, [P[name] for name, _ in _block_sizes(self, upper)],
                               spare=bool(upper))
            cache[key] = pos
        return pos

    def chunks(self, size: int | None = None):
        """Element slices of the batches of ``size`` elements (default ``chunk``; at least
        one per worker thread)."""
        n = max(1, -(-self.nel // (self.chunk if size is None else size)))
        if self.threads > 1:
            n = max(n, self.threads)
        bounds = np.linspace(0, self.nel, n + 1).round().astype(int)
        for a, b in zip(bounds[:-1], bounds[1:]):
            if b > a:
                yield slice(int(a), int(b))

    # ------------------------------------------------------------- kinematics
    def deformation_gradient(self, xf: np.ndarray, sl: slice) -> np.ndarray:
        """``F[a, K, e, q]`` of the elements ``sl`` from the full dof vector ``xf``."""
        ed = self.edofs[sl]
        ne = ed.shape[0]
        # one (nq*3 x 27) @ (27 x 3) product per element, not one tiny one per point
        ue = xf[ed[:, : self.m_u]].reshape(ne, 27, 3)
        FT = (self.dNt[sl].reshape(ne, self.nq * 3, 27) @ ue).reshape(ne, self.nq, 3, 3)
        F = np.ascontiguousarray(FT.transpose(3, 2, 0, 1))                    # (a, K, e, q)
        F[0, 0] += 1.0
        F[1, 1] += 1.0
        F[2, 2] += 1.0
        return F

    def quadrature_fields(self, xf: np.ndarray, sl: slice):
        """``F[a, K, e, q]``, ``Grad phi[K, e, q]`` and ``p[e, q]`` (``None`` for the
        penalty) of the elements ``sl`` from the full dof vector ``xf``."""
        ed = self.edofs[sl]
        ne = ed.shape[0]
        nq = self.nq
        F = self.deformation_gradient(xf, sl)
        phie = xf[ed[:, self.m_u + self.m_p:]]
        mf = phie.shape[1]
        G = np.ascontiguousarray((self.dNphit[sl].reshape(ne, nq * 3, mf) @ phie[:, :, None])
                                 .reshape(ne, nq, 3).transpose(2, 0, 1))
        p = None
        if self.m_p:
            pe = xf[ed[:, self.m_u: self.m_u + self.m_p]]
            p = np.einsum("ek,eqk->eq", pe, self.N1[sl])
        return F, G, p

    def _response(self, xf, sl, need_tangent=True, grad_div=None):
        """Material response of the elements ``sl``: tensor-first stresses, the tangent
        times the quadrature weights in the points-first layout `_element_blocks` uses."""
        F, G, p = self.quadrature_fields(xf, sl)
        w = self.w[sl] if need_tangent else None
        gd = self.grad_div if grad_div is None else grad_div
        r = dielectric_response(self.material, F, G, p, self.kappa, self.formulation,
                                need_tangent, True, w, gd)
        if self.elastic_volume:   # equilibrium rows: elastic stress, Gauss rows: D_L(F, G)
            r0 = dielectric_response(self.material, F, np.zeros_like(G), p, self.kappa,
                                     self.formulation, need_tangent, True, w, gd)
            r.P = r0.P
            if need_tangent:
                r.A_FF = r0.A_FF
        return r

    # --------------------------------------------------------------- element arrays
    def _element_residual(self, r, sl):
        w = self.w[sl]
        ne, nq = w.shape
        P = np.moveaxis(r.P * w, (2, 3), (0, 1)).transpose(0, 1, 3, 2)        # e q K a
        dNi, dNphii = _left_factors(self, sl)
        ru = (dNi @ np.ascontiguousarray(P).reshape(ne, nq * 3, 3)).reshape(ne, -1)
        parts = [ru]
        if self.m_p:
            parts.append(np.einsum("eqk,eq->ek", self.N1[sl], r.dpsi_dp * w))
        D = np.ascontiguousarray(np.moveaxis(r.D_L * w, 0, 2)).reshape(ne, nq * 3, 1)
        parts.append((dNphii @ D)[:, :, 0])
        return np.concatenate(parts, axis=1)

    def _element_blocks(self, r, sl, upper: bool = False) -> np.ndarray:
        """Tangent blocks of a chunk written into one flat buffer (layouts need no
        transposes; the matmuls write in place), ordered as `_chunk_positions`."""
        w = self.w[sl]
        ne, nq = w.shape
        mp, mf = self.m_p, self.m_phi
        dNt, dNphit = self.dNt[sl], self.dNphit[sl]
        dNi, dNphii = _left_factors(self, sl)
        sizes = _block_sizes(self, upper)
        per = sum(n for _, n in sizes)
        buf = _thread_buffer(self._work, ne * per,
                             max(b.stop - b.start for b in self.chunks()) * per)
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
        if "fu" in views:
            views["fu"][:] = views["uf"]
        if self.elastic_volume:    # the equilibrium rows do not depend on phi
            views["uf"][:] = 0.0
        # phi-phi
        np.matmul(dNphii, (r.A_GG @ dNphit).reshape(ne, nq * 3, mf),
                  out=views["ff"].reshape(ne, mf, mf))
        if mp:
            A = r.A_Fp                                                     # e q K a
            V = (A[..., None] * self.N1[sl][:, :, None, None, :]).reshape(ne, nq * 3, 3 * mp)
            np.matmul(dNi, V, out=views["up"].reshape(ne, 27, 3 * mp))
            if "pu" in views:
                views["pu"][:] = views["up"]
            if "pp" in views:
                views["pp"][:] = (r.A_pp * np.einsum("eqk,eql,eq->ekl", self.N1[sl],
                                                     self.N1[sl], w)).ravel()
        return buf

    def _assemble_chunk(self, xf, k, sl, grad_div, total, upper=False):
        """Chunk ``k``'s element blocks and internal forces added into ``total`` (an
        :class:`OrderedSum`)."""
        try:
            r = self._response(xf, sl, grad_div=grad_div)
            blocks = self._element_blocks(r, sl, upper)
            re = self._element_residual(r, sl)
        except Exception:
            total.add(k, None, None)     # the later chunks wait for this one's turn
            raise
        total.add(k, self._chunk_positions(sl, upper), blocks, self.edofs[sl].ravel(),
                  re.ravel())

    # ------------------------------------------------------------------ assembly
    def assemble(self, xf: np.ndarray, grad_div: float | None = None, upper: bool = False):
        """CSR data of the reduced tangent and the *full* internal force vector at the full
        dof vector ``xf`` (element chunks in ``threads`` worker threads; numpy releases the
        GIL in the batched matmuls); ``grad_div`` overrides the form's stabilisation;
        ``upper``: the data of the upper triangle (pattern :attr:`upper_scatter`).

        Every chunk adds its element blocks into one data array (``np.add.at`` through
        32-bit positions, in chunk order), not into a partial sum of its own."""
        chunks = list(self.chunks())
        scatter = self.structure(upper)[0]
        total = OrderedSum(scatter.nnz + (scatter.n + 1 if upper else 1), self.n_full)
        with single_threaded_blas():   # small products: BLAS threads cost more than they gain
            if self.threads > 1 and len(chunks) > 1:
                if self._pool is None:
                    self._pool = ThreadPoolExecutor(self.threads)
                list(self._pool.map(
                    lambda ks: self._assemble_chunk(xf, *ks, grad_div, total, upper),
                    enumerate(chunks)))
            else:
                for k, sl in enumerate(chunks):
                    self._assemble_chunk(xf, k, sl, grad_div, total, upper)
        trim_heap(self.n_full)     # the chunks' freed temporaries
        if upper:
            return drop_spare_slots(total.data, scatter.indptr), total.vector
        return total.data[: scatter.nnz], total.vector

    def element_residuals(self, xf: np.ndarray) -> np.ndarray:
        """Internal force vectors of every element, shape ``(nel, m)``, in the order of
        the element dofs ``edofs`` (``u`` node-major, ``p``, ``phi``)."""
        return np.concatenate([self._element_residual(
            self._response(xf, sl, need_tangent=False), sl) for sl in self.chunks()])

    def residual(self, xf: np.ndarray) -> np.ndarray:
        """Full internal force vector only (cheaper; the line search).  In batches of
        :data:`RESIDUAL_BATCH` times ``chunk`` elements: without the tangent a batch is
        small, and fewer batches cost less overhead."""
        rf = np.zeros(self.n_full)
        for sl in self.chunks(RESIDUAL_BATCH * self.chunk):
            re = self._element_residual(self._response(xf, sl, need_tangent=False), sl)
            rf += np.bincount(self.edofs[sl].ravel(), weights=re.ravel(),
                              minlength=self.n_full)
        return rf
