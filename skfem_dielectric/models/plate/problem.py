"""3D plate of an incompressible ideal dielectric: fully coupled or Maxwell-traction coupling.

One model, two couplings of the electric field (the paper's Sec. 6):

``coupling="full"`` (default)
    the mixed u-p-phi weak form of :mod:`skfem_dielectric.forms.mixed_upphi`: the electric
    energy is part of the total energy, charge control is the Neumann term
    ``int sigma_F phi dA`` on the charged faces.
``coupling="maxwell"``
    the elastic problem loaded on its deformed boundary by the Maxwell traction
    (:mod:`skfem_dielectric.forms.maxwell_traction`), with the field of the potential
    solved on the deformed body (``field="electrostatic"``) or the local field of the
    charge (``field="local"``, no potential unknowns; charge control only).  Voltage control
    of the electrostatic field prescribes the potential on the faces as in the full
    coupling; the traction follows from the solved field.  The tangent is not symmetric.

Energy of the full coupling::

    Pi(u, p, phi) = int_V psi(F, p, Grad phi) dV - int_{dV_t} t_A . u dA + int_{dV_q} sigma_F phi dA

a min over ``u``, max over ``phi``, saddle in ``p``; its stationarity gives equilibrium,
``J = 1`` and ``Div D_L = 0`` with ``N . D_L = -sigma_F`` on the charged faces (Eq. (BCS)).
``sigma_F`` is a charge per *reference* area: ``+sigma`` on ``top``, ``-sigma`` on
``bottom``, ``sigma = D0 sqrt(mu eps)``, so that ``D_L2 = -sigma`` and
``|D_L| / sqrt(mu eps) = D0``.  With the ``x2`` symmetry plane ``phi = 0`` there
(antisymmetric potential, no charge added); without it ``phi`` is pinned at the plate centre
(the total charge is zero, so the pin carries no reaction).  Voltage control prescribes
``phi`` on ``top``/``bottom`` so that ``E_L2 = -E0 sqrt(mu/eps)``.

Loads (``load = (s, D0)`` or ``(s, E0)`` under voltage control, ``s`` = nominal traction/mu):

``"equibiaxial"``
    dead nominal traction ``mu s N`` on all lateral faces (``x1_*``, ``x3_*``).
``"uniaxial-free"``
    dead nominal traction on the ``x1`` faces only, ``x3`` faces free (the homogeneous
    uni-axial state of Eq. (DEuniax)).
``"uniaxial"``
    the Keplinger experiment: the clamp faces ``x1_plus`` (and ``x1_minus``) have
    ``u2 = u3 = 0``; the moving clamp ``x1_plus`` is a rigid body in ``x1`` -- all its nodes
    share *one* ``u1`` unknown (dof reduction, no penalty) -- carrying the resultant force
    ``mu s A_face`` (``A_face`` = reference area of the modelled clamp face, which accounts
    for the symmetry fraction); without the ``x1`` symmetry plane ``x1_minus`` is the fixed
    clamp (``u = 0``).  ``x3_*`` are free edges.
``"none"``
    no mechanical load.
"""

from __future__ import annotations

import hashlib
import math
from typing import Any

import numpy as np
from skfem import ElementHex1, ElementHex2, FacetBasis, LinearForm, asm

from ...checks import (check_choice, check_count, check_instance, check_material,
                       check_nonnegative, check_positive)
from ...fem.assembly import DofReduction
from ...fem.runtime import SetupCache
from ...fem.mesh import PlateMesh
from ...forms.maxwell_traction import MaxwellBoundary
from ...forms.mixed_upphi import PRESSURE_ELEMENTS, MixedUPPhiForm
from ...kinematics import det3, segment_det_limit
from ...linalg.symmetric import SymmetricUpper
from ...materials import FORMULATIONS, MIXED_FORMULATIONS
from ...problem import Layout, Problem
from .post import plate_quantities, plate_step_mesh, plate_stresses, evaluate_fields

__all__ = ["PlateProblem", "plate_reduction", "increment_classes"]

LOADINGS = ("equibiaxial", "uniaxial", "uniaxial-free", "none")
CONTROLS = ("charge", "voltage")
COUPLINGS = ("full", "maxwell")
FIELDS = ("electrostatic", "local")
PHI_ELEMENTS = ("Q1", "Q2")
CLASSES = ("symmetric", "antisymmetric")


def _nearest(basis, point) -> int:
    d = np.linalg.norm(basis.doflocs - np.asarray(point)[:, None], axis=0)
    return int(np.argmin(d))


def _class_dofs(problem, name: str, comps) -> list[np.ndarray]:
    return [3 * problem.b2.get_dofs(problem.plate.facets(name)).all() + c for c in comps]


def plate_reduction(problem, increments=None) -> DofReduction:
    """The dof reduction of a plate: symmetry planes, potential datum or electrodes, clamps
    and rigid-motion pins -- of the model, or of one symmetry class of its increments.

    On a plate cut by the symmetry planes ``x_i = 0`` the increments of a symmetric state
    split into classes, one choice per plane (``increments = {i: "symmetric" |
    "antisymmetric"}``).  Mirror-symmetric increments have ``u_i`` odd and the other
    components even in ``x_i`` (so ``u_i = 0`` on the plane), ``p`` even, and ``phi`` even
    for ``i = 1, 3`` but odd for ``i = 2`` (the charges change sign under that mirror):
    these are the model's own conditions.  Antisymmetric ones have the opposite parities:
    ``u_j = 0`` (``j != i``), ``p = 0`` and, for ``i = 1, 3``, ``phi = 0`` on the plane.
    The full plate's increments are the direct sum of the classes and its tangent is
    block diagonal in them, so its spectrum is the union of the classes' spectra.  An
    antisymmetric class also fixes the rigid clamp's ``u1`` (the clamp then moves as a
    rigid translation, which the fixed clamp of the full plate excludes), pins the
    translation along ``x_i`` that it admits (free plates) and, for ``i = 2`` under charge
    control, the potential datum.  ``increments = "union"``: every dof free in some class
    (no clamp tie), the space on which the classes' tangents are assembled.

    Parameters
    ----------
    problem
        The :class:`PlateProblem` (its bases, mesh and loading).
    increments
        ``None``, ``"union"`` or a mapping of every symmetry axis to a class.

    Returns
    -------
    DofReduction
    """
    sym = problem.plate.symmetry
    if increments is None:
        increments = {ax: "symmetric" for ax in sym}
    if increments == "union":
        reds = [plate_reduction(problem, c) for c in increment_classes(sym)]
        fixed = reds[0].fixed
        for r in reds[1:]:
            fixed = np.intersect1d(fixed, r.fixed)
        return DofReduction(problem.n_full, fixed)
    if (not hasattr(increments, "keys") or sorted(increments) != sorted(sym)
            or any(v not in CLASSES for v in increments.values())):
        raise ValueError(f"increments must map every symmetry axis {sym} to one of "
                         f"{CLASSES}, or be 'union', got {increments!r}")
    names = set(problem.plate.mesh.boundaries)
    fixed, tied = [], []
    anti = [ax for ax in sym if increments[ax] == "antisymmetric"]
    for ax in sym:
        plane = f"sym_x{ax}"
        if ax in anti:
            fixed += _class_dofs(problem, plane, [c for c in range(3) if c != ax - 1])
            if problem.n_p:
                fixed.append(problem.boundary_dofs(plane, "p"))
            if ax != 2:
                fixed.append(problem.boundary_dofs(plane, "phi"))
        else:
            fixed += _class_dofs(problem, plane, [ax - 1])
            if ax == 2:
                fixed.append(problem.boundary_dofs(plane, "phi"))
    if problem.control == "charge" and (2 not in sym or 2 in anti):
        fixed.append(np.atleast_1d(problem.off_phi + _nearest(problem.bphi, np.zeros(3))))
    if problem.control == "voltage":
        fixed += [problem._phi_top, problem._phi_bottom]
    if problem.loading == "uniaxial":
        fixed += _class_dofs(problem, "x1_plus", (1, 2))
        clamp = _class_dofs(problem, "x1_plus", (0,))[0]
        (fixed if anti else tied).append(clamp)
        if "x1_minus" in names:
            fixed += _class_dofs(problem, "x1_minus", (0, 1, 2))
    else:
        # pin the rigid translations the symmetry planes (and classes) leave free
        k = _nearest(problem.b2, np.zeros(3))
        for ax in (1, 2, 3):
            if ax not in sym or ax in anti:
                fixed.append(np.array([3 * k + ax - 1]))
    if problem.local_field:   # purely elastic: every potential dof fixed at 0
        fixed.append(np.arange(problem.off_phi, problem.n_full))
    return DofReduction(problem.n_full, np.concatenate(fixed) if fixed else None, tied)


def increment_classes(sym) -> list[dict[int, str]]:
    """Every symmetry class ``{axis: "symmetric" | "antisymmetric"}`` of the planes
    ``x_i = 0``, ``i`` in ``sym``; the all-symmetric one (the model's own) first."""
    return [{ax: CLASSES[(i >> j) & 1] for j, ax in enumerate(sym)}
            for i in range(2 ** len(sym))]


#: Unit loads of the plates built so far in this process, by :func:`layout_key` and
#: loading (a sweep builds many plates of one mesh).
_UNIT_LOADS = SetupCache(64)


def layout_key(problem, intorder: int) -> str:
    """A digest of what a plate's discrete operators depend on besides its material: the
    mesh (nodes, elements, named boundaries), the elements and quadrature and the dof
    layout.  Plates with the same key share their unit loads and point operators
    (:func:`~skfem_dielectric.models.plate.post.evaluate_fields`)."""
    m = problem.plate.mesh
    h = hashlib.sha1()
    for a in (m.p, m.t):
        h.update(np.ascontiguousarray(a).tobytes())
    for name in sorted(m.boundaries):
        h.update(name.encode())
        h.update(np.ascontiguousarray(m.boundaries[name]).tobytes())
    h.update(repr((type(problem.bphi.elem).__name__, problem.pressure, int(intorder),
                   problem.n_u, problem.n_p, problem.off_p, problem.off_phi,
                   problem.n_full)).encode())
    return h.hexdigest()


def _unit_loads(problem, intorder: int):
    """Unit external vectors of a plate: traction ``mu N`` per unit ``s``, charge per unit
    ``D0``, and the reference area of the clamp face.  Assembled once per layout and
    loading (:func:`layout_key`) and scaled by the material's ``mu`` and ``eps``."""
    mu, eps = problem.material.mu, problem.material.eps
    key = (problem.layout_key, problem.loading)
    got = _UNIT_LOADS.get(key)
    if got is None:
        got = _UNIT_LOADS.put(key, _assembled_unit_loads(problem, intorder))
    f_s, q_D0, clamp_area = got
    return mu * f_s, math.sqrt(mu * eps) * q_D0, clamp_area


def _assembled_unit_loads(problem, intorder: int):
    """:func:`_unit_loads` for ``mu = eps = 1``."""
    m, mu, eps = problem.plate.mesh, 1.0, 1.0
    names = set(m.boundaries)
    f_s = np.zeros(problem.n_full)
    faces = {"equibiaxial": ("x1_plus", "x1_minus", "x3_plus", "x3_minus"),
             "uniaxial-free": ("x1_plus", "x1_minus"),
             "uniaxial": ("x1_plus",), "none": ()}[problem.loading]
    comps = (0,) if problem.loading == "uniaxial-free" else (0, 1, 2)
    N2 = problem.b2.N
    for name in (n for n in faces if n in names):
        fb = FacetBasis(m, ElementHex2(), facets=m.boundaries[name], intorder=intorder)
        for c in comps:
            v = asm(LinearForm(lambda v, w, c=c: v * w.n[c]), fb)
            f_s[c::3][: N2] += mu * v[:N2]
    f_s[problem.n_u:] = 0.0
    q_D0 = np.zeros(problem.n_full)    # charge sigma_F per unit D0 (phi rows)
    for name, sign in (("top", 1.0), ("bottom", -1.0)):
        if name in names:
            fb = FacetBasis(m, problem.bphi.elem, facets=m.boundaries[name],
                            intorder=intorder)
            v = asm(LinearForm(lambda v, w: v), fb)
            q_D0[problem.off_phi:] += sign * math.sqrt(mu * eps) * v
    clamp_area = (float(asm(LinearForm(lambda v, w: v), FacetBasis(
        m, ElementHex1(), facets=m.boundaries["x1_plus"])).sum())
        if "x1_plus" in names else 0.0)
    return f_s, q_D0, clamp_area


class PlateProblem(Problem):
    """Discretised 3D plate, a :class:`~skfem_dielectric.problem.Problem`.

    Constructed as every model of :mod:`skfem_dielectric.models` (docs/fe.md, "Constructing
    a model"): the mesh first, then the material, then keyword-only options, e.g.
    ``PlateProblem(plate_mesh(4, 1, 4, 1, 1, 1), NeoHookeanDielectric(), loading="uniaxial")``.

    Parameters
    ----------
    mesh
        The plate's geometry and mesh, a :class:`~skfem_dielectric.fem.mesh.PlateMesh` of
        :func:`~skfem_dielectric.fem.mesh.plate_mesh` (sizes ``L1, H, L3``, element counts
        ``n1, n2, n3``, symmetry planes); kept as :attr:`plate`.
    material
        Ideal dielectric (``NeoHookeanDielectric``, ``GentDielectric``, ``IdealDielectric``).
    loading
        ``"equibiaxial"`` (default: dead traction on the ``x1`` and ``x3`` faces),
        ``"uniaxial"`` (the clamped Keplinger plate), ``"uniaxial-free"`` (dead traction on
        the ``x1`` faces, ``x3`` faces free) or ``"none"``.
    control
        ``"charge"`` (load ``(s, D0)``) or ``"voltage"`` (load ``(s, E0)``).
    coupling
        ``"full"`` (default) or ``"maxwell"`` (mixed formulation; with ``field="local"``
        charge control only).
    field
        Field of the Maxwell traction: ``"electrostatic"`` (default) or ``"local"``.
    phi_element
        Interpolation of the potential: ``"Q2"`` (default) or ``"Q1"``.
    pressure
        The pressure space of the mixed forms: ``"Q1"`` (continuous, Taylor-Hood, default)
        or ``"P0"`` (a constant per element, the Q2-P0 pair); both are inf-sup stable.
    intorder
        Quadrature order (4 -> 27 Gauss points per hexahedron).
    grad_div
        Grad-div stabilisation ``gamma (J - 1)^2 / 2`` (in units of ``mu``; mixed
        formulation): removes spurious mesh-scale modes from the stability analysis,
        leaves every homogeneous state unchanged (docs/stability.md).  Default 0.
    formulation
        ``"mixed"`` (u-p-phi, default), ``"penalty"`` (u-phi, ``W(I1) + kappa (J-1)^2/2``),
        ``"isochoric"`` (u-phi, COMSOL's ``W(J^(-2/3) I1) + kappa (J-1)^2/2``) or
        ``"mixed-isochoric"`` (u-p-phi, the same energy without volumetric locking) or
        ``"mixed-plain"`` (u-p-phi, ``"mixed"`` without its ``-mu0 ln J``;
        :mod:`skfem_dielectric.materials`).
    kappa
        Bulk modulus; ``inf`` (the mixed forms only) = exactly incompressible.
    chunk
        Maximum number of elements assembled per batch (bounds the memory of element
        matrices).
    threads
        Worker threads for the batched assembly (default ``min(2, cpu_count)``).
    increments
        ``None`` (the model's own constraints) or the symmetry class of the increments
        (:func:`plate_reduction`): a model whose tangent is that class's stiffness.

    Raises
    ------
    ValueError
        Naming the parameter and the value: a ``mesh`` that is no ``PlateMesh``, a
        ``material`` that is no dielectric, unknown options, non-positive ``kappa``, or a mesh
        lacking the boundaries the loading needs (e.g. ``x1_plus`` for the clamp, enough
        symmetry planes for equi-biaxial).

    Notes
    -----
    The energy and boundary conditions are those of the module docstring (Eq. (BCS) of the
    paper); the loads of the uni-axial cases reproduce Eq. (DEuniax), the equi-biaxial one
    Eq. (loading_gent).
    """

    def __init__(self, mesh: PlateMesh, material, *, loading: str = "equibiaxial",
                 control: str = "charge", coupling: str = "full",
                 field: str = "electrostatic", phi_element: str = "Q2", intorder: int = 4,
                 grad_div: float = 0.0, formulation: str = "mixed",
                 kappa: float = math.inf, chunk: int = 50, threads: int | None = None,
                 increments=None, pressure: str = "Q1"):
        plate = check_instance("mesh", mesh, PlateMesh, "plate_mesh")
        check_material("material", material)
        check_choice("loading", loading, LOADINGS)
        check_choice("control", control, CONTROLS)
        check_choice("coupling", coupling, COUPLINGS)
        check_choice("field", field, FIELDS)
        check_choice("phi_element", phi_element, PHI_ELEMENTS)
        check_choice("pressure", pressure, PRESSURE_ELEMENTS)
        intorder = check_count("intorder", intorder)
        grad_div = check_nonnegative("grad_div", grad_div)
        check_choice("formulation", formulation, FORMULATIONS)
        if coupling == "maxwell" and field == "local" and control != "charge":
            raise ValueError("the local Maxwell field is the field of the charge: it needs "
                             f"control='charge', got {control!r}")
        if coupling == "maxwell" and formulation != "mixed":
            raise ValueError(f"coupling 'maxwell' needs formulation='mixed', got {formulation!r}")
        kappa = math.inf if kappa == math.inf else check_positive("kappa", kappa)
        if formulation not in MIXED_FORMULATIONS and not math.isfinite(kappa):
            raise ValueError(f"kappa must be finite for the {formulation} formulation, got inf")
        if grad_div and formulation not in MIXED_FORMULATIONS:
            raise ValueError("grad_div needs formulation='mixed' (the penalty form has its "
                             f"own kappa), got {formulation!r}")
        self.grad_div = grad_div
        self.options = dict(loading=loading, control=control, coupling=coupling, field=field,
                            formulation=formulation, kappa=kappa, phi_element=phi_element,
                            intorder=intorder, chunk=chunk, threads=threads, grad_div=grad_div,
                            pressure=pressure)
        chunk = check_count("chunk", chunk)
        threads = None if threads is None else check_count("threads", threads)
        self.plate, self.material = plate, material
        self.loading, self.control = loading, control
        self.coupling, self.field = coupling, field
        self.formulation, self.kappa = formulation, kappa
        self.load_names = ("s", "D0") if control == "charge" else ("s", "E0")
        self.symmetric = coupling == "full"
        self.local_field = coupling == "maxwell" and field == "local"
        m = plate.mesh
        names = set(m.boundaries)
        if loading == "uniaxial" and "x1_plus" not in names:
            raise ValueError("loading 'uniaxial' needs the clamp boundary 'x1_plus'")
        if loading in ("equibiaxial", "uniaxial-free") and len(plate.symmetry) < 2:
            raise ValueError(f"loading {loading!r} needs at least two symmetry planes "
                             f"(symmetry 'quarter' or 'eighth') to remove rigid motions, "
                             f"got symmetry {plate.symmetry}")
        if "top" not in names:
            raise ValueError("the mesh needs the charged boundary 'top'")
        self.form = MixedUPPhiForm(
            m, material, formulation=formulation, kappa=kappa, phi_element=phi_element,
            intorder=intorder, chunk=chunk, threads=threads,
            elastic_volume=coupling == "maxwell" and field == "electrostatic",
            grad_div=grad_div * material.mu, pressure=pressure)
        f = self.form
        self.threads, self.nel = f.threads, f.nel
        self.b2, self.b1, self.bphi, self.bp = f.b2, f.b1, f.bphi, f.bp
        self.pressure = pressure
        self.n_u, self.n_p, self.off_p, self.off_phi = f.n_u, f.n_p, f.off_p, f.off_phi
        self.n_full = f.n_full
        self._phi_top = self._phidofs("top")
        self._phi_bottom = self._phidofs("bottom") if "bottom" in names else np.zeros(0, int)
        self.red = plate_reduction(self, increments)
        f.bind(self.red)
        self._layout = Layout.from_reduction(self.red, f.fields, ("p", "phi"))
        self.layout_key = layout_key(self, intorder)
        self.f_s, self.q_D0, self.clamp_area = _unit_loads(self, intorder)
        self.boundary = (MaxwellBoundary(m, self.bphi.elem, self.off_phi, self.red,
                                         material.eps, field, intorder)
                         if coupling == "maxwell" else None)

    # ------------------------------------------------------------------ set-up
    def _udofs(self, name: str, comp: int) -> np.ndarray:
        return 3 * self.b2.get_dofs(self.plate.facets(name)).all() + comp

    def _phidofs(self, name: str) -> np.ndarray:
        return self.off_phi + self.bphi.get_dofs(self.plate.facets(name)).all()

    # ------------------------------------------------------------------ contract
    @property
    def layout(self) -> Layout:
        """Blocks ``u`` (with the clamp unknown), ``p`` (mixed), ``phi``; ``p`` and
        ``phi`` are the multiplier/potential blocks."""
        return self._layout

    def boundary_dofs(self, name: str, field: str = "u") -> np.ndarray:
        """Full dof indices of boundary ``name`` for ``field`` ``"u"`` (all three components,
        node-major), ``"p"`` or ``"phi"``; ``ValueError`` for unknown names or fields."""
        facets = self.plate.facets(name)
        if field == "u":
            return (3 * self.b2.get_dofs(facets).all()[:, None] + np.arange(3)).ravel()
        if field == "p" and self.n_p:
            return self.off_p + self.bp.get_dofs(facets).all()
        if field == "phi":
            return self.off_phi + self.bphi.get_dofs(facets).all()
        raise ValueError(f"field must be 'u', 'p' (mixed only) or 'phi', got {field!r}")

    def check_load(self, load) -> tuple[float, float]:
        """``(s, D0)`` (or ``(s, E0)``) as floats; ``ValueError`` unless a finite pair."""
        ld = np.atleast_1d(np.asarray(load, dtype=float))
        if ld.shape != (2,) or not np.all(np.isfinite(ld)):
            raise ValueError(f"load must be a finite pair {self.load_names}, got {load!r}")
        return float(ld[0]), float(ld[1])

    def sigma(self, load) -> float:
        """Charge per reference area ``sigma_F = D0 sqrt(mu eps)`` of a charge-control load."""
        return self.check_load(load)[1] * math.sqrt(self.material.mu * self.material.eps)

    def prescribed(self, load) -> np.ndarray:
        """Full vector of prescribed values (non-zero only for voltage control)."""
        xD = np.zeros(self.n_full)
        if self.control == "voltage":
            _, E0 = self.check_load(load)
            m = self.material
            grad = E0 * math.sqrt(m.mu / m.eps)       # Grad phi_2 = -E_L2 = E0 sqrt(mu/eps)
            xD[self._phi_top] = grad * self.plate.H / 2
            xD[self._phi_bottom] = -grad * self.plate.H / 2
        return xD

    def external(self, load) -> np.ndarray:
        """Full external 'force' vector: tractions (u rows) minus charges (phi rows; none
        for the local Maxwell field, whose charge acts through the traction)."""
        s, e = self.check_load(load)
        f = s * self.f_s
        if self.control == "charge" and not self.local_field:
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

    def assemble(self, x: np.ndarray, load) -> tuple[Any, np.ndarray]:
        """Reduced tangent (CSR; symmetric for the full coupling) and residual.

        The CSR matrices of one problem share a read-only sparsity pattern
        (:meth:`~skfem_dielectric.fem.assembly.ScatterMap.csr`): copy before in-place
        structural changes such as ``eliminate_zeros``."""
        xf = self.full(x, load)
        data, rf = self.form.assemble(xf)
        rf -= self.external(load)
        K, r = self.scatter.csr(data), self.red.reduce(rf)
        if self.boundary is not None:
            Kb, rb = self.boundary.assemble(xf, self.sigma(load))
            return (K + Kb).tocsr(), r + rb
        return K, r

    def assemble_upper(self, x: np.ndarray, load) -> tuple[Any, np.ndarray]:
        """The tangent as its upper triangle, assembled directly (no whole matrix; see
        :meth:`~skfem_dielectric.problem.Problem.assemble_upper`), and the residual; the
        Maxwell-traction coupling (not symmetric) from :meth:`assemble`."""
        if self.boundary is not None:
            return super().assemble_upper(x, load)
        xf = self.full(x, load)
        data, rf = self.form.assemble(xf, upper=True)
        rf -= self.external(load)
        return SymmetricUpper(self.form.upper_scatter.csr(data)), self.red.reduce(rf)

    @property
    def scatter(self):
        """The :class:`~skfem_dielectric.fem.assembly.ScatterMap` of the reduced tangent."""
        return self.form.scatter

    def stabilised_tangent(self, x: np.ndarray, load, grad_div: float):
        """Reduced tangent at ``(x, load)`` with the grad-div stabilisation ``grad_div``
        (units of ``mu``) in place of the model's: the stiffness a stability analysis of a
        state of the unstabilised model uses (:mod:`skfem_dielectric.stability.analysis`)."""
        xf = self.full(x, load)
        K = self.scatter.csr(self.form.assemble(xf, grad_div * self.material.mu)[0])
        if self.boundary is not None:
            K = (K + self.boundary.assemble(xf, self.sigma(load))[0]).tocsr()
        return K

    def residual(self, x: np.ndarray, load) -> np.ndarray:
        """Reduced residual only (cheaper; used by the line search)."""
        xf = self.full(x, load)
        r = self.red.reduce(self.form.residual(xf) - self.external(load))
        if self.boundary is not None:
            r = r + self.boundary.assemble(xf, self.sigma(load), need_tangent=False)[1]
        return r

    def load_vector(self, x: np.ndarray, load, h: float = 1e-6) -> np.ndarray:
        """``d residual / d (s, D0)``: the dead loads and charges enter linearly,
        ``-[f_s, -q_D0]`` reduced; the prescribed potential (voltage control) and the
        Maxwell traction by central differences (:meth:`Problem.load_vector`)."""
        if self.control == "voltage" or self.boundary is not None:
            return super().load_vector(x, load, h)
        return np.stack([-self.red.reduce(self.f_s), self.red.reduce(self.q_D0)], axis=1)

    def max_step(self, x: np.ndarray, dx: np.ndarray, load) -> float:
        """Largest ``alpha`` in ``(0, 1]`` with ``det F(x + a dx) > 0`` at every quadrature
        point for all ``a`` in ``[0, alpha]`` (a ``step_limit`` of
        :func:`~skfem_dielectric.solvers.newton.newton`, by
        :func:`~skfem_dielectric.kinematics.segment_det_limit`); 0.0 if ``det F(x) <= 0``."""
        every = slice(0, self.nel)              # F of every element at once: 9 values a point
        F0 = self.form.deformation_gradient(self.full(x, load), every).reshape(3, 3, -1)
        dF = self.form.deformation_gradient(self.red.expand(dx), every).reshape(3, 3, -1)
        dF[0, 0] -= 1.0                         # Grad dx (no prescribed part): I taken out
        dF[1, 1] -= 1.0
        dF[2, 2] -= 1.0
        return segment_det_limit(np.moveaxis(F0, 2, 0), np.moveaxis(dF, 2, 0))

    def admissible(self, x: np.ndarray, load) -> str:
        """Why the plate state ``x`` is inverted, or ``""`` if it is not.

        Inverted: ``det F <= 0`` at a quadrature point, or ``F11 <= 0`` or ``F33 <= 0`` at
        the plate centre (the plate turned inside out through a symmetry plane: ``F11 = F33
        = -lam``, ``F22 = lam^-2`` has ``det F = 1`` and ``|F e1| = lam``, an equilibrium of
        the discrete equations that no deformation of the plate reaches).
        """
        J = det3(self.form.deformation_gradient(self.full(x, load), slice(0, self.nel)))
        if not np.all(J > 0):
            return f"det F = {float(J.min()):.3g} <= 0 at a quadrature point"
        F = self.evaluate(x, load, np.zeros((3, 1)))["F"][:, :, 0]
        if not (F[0, 0] > 0 and F[2, 2] > 0):
            return (f"inverted deformation: F11 = {F[0, 0]:.6g}, F33 = {F[2, 2]:.6g} at the "
                    f"plate centre (must be > 0)")
        return ""

    def newton_guards(self) -> dict[str, Any]:
        """``step_limit``: :meth:`max_step` (``det F > 0`` along every Newton step) and
        ``admissible``: :meth:`admissible` (no converged inverted state)."""
        return {"step_limit": self.max_step, "admissible": self.admissible}

    # ------------------------------------------------------------ post-processing
    def evaluate(self, x: np.ndarray, load, points: np.ndarray) -> dict[str, np.ndarray]:
        """Fields ``u (3, n)``, ``phi (n)``, ``p (n)`` (zeros for the penalty),
        ``F (3, 3, n)`` and ``G = Grad phi (3, n)`` at reference points ``(3, n)``."""
        return evaluate_fields(self, self.full(x, load), points)

    def stresses(self, F: np.ndarray, G: np.ndarray, p: np.ndarray | None,
                 load=None) -> dict[str, np.ndarray]:
        """Total stresses and fields from ``F``, ``G = Grad phi`` and ``p`` (any trailing
        shape): ``P1``, ``S`` (second Piola, the paper's ``P``), ``sigma``, ``E``, ``D``,
        ``E_L``, ``D_L``, ``J``.  The local Maxwell field needs ``load`` (its charge)."""
        if self.local_field and load is None:
            raise ValueError("load is needed for the stresses of the local Maxwell field")
        return plate_stresses(self, F, G, p, self.sigma(load) if self.local_field else 0.0)

    def quadrature_fields(self, x: np.ndarray, load):
        """``(F, G, p)`` at the quadrature points, one triple per element chunk."""
        xf = self.full(x, load)
        for sl in self.form.chunks():
            yield (sl,) + self.form.quadrature_fields(xf, sl)

    def postprocess(self, x: np.ndarray, load) -> dict[str, Any]:
        """Quantities of a converged state
        (:func:`~skfem_dielectric.models.plate.post.plate_quantities`)."""
        return plate_quantities(self, x, load)

    def step_mesh(self, x: np.ndarray, load):
        """meshio ``Mesh`` of a state
        (:func:`~skfem_dielectric.models.plate.post.plate_step_mesh`)."""
        return plate_step_mesh(self, x, load)
