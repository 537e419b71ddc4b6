"""The FE problem of a :class:`~validation.specs.RunSpec` and the settings of its ramp.

* :func:`build_problem` -- the FE problem of a spec (3D plate, 3D Maxwell-traction
  plate or 2D membrane);
* :func:`buckling_problem` -- the grad-div form of the plate of a run analysed for
  buckling, whose states give its whole-plate spectrum and ``D0_b``;
* :func:`ramp_targets` and :func:`ramp_settings` -- the ramp's loads ``(s, D0)`` and
  its Newton tolerances, cut-back limit and linear solver;
* :func:`with_dead_load` -- the dead load of a Keplinger run given by its weight fraction.

Geometry in SI-like units of millimetres (the Keplinger plate 100 x 50 x 1 mm)
with ``mu = eps = 1``: every reported quantity is dimensionless.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

import skfem_dielectric as fe
from skfem_dielectric.gallery.defaults import (EQUIBIAXIAL_PRELOAD_STEPS, EQUIBIAXIAL_RTOL,
                                               KEPLINGER_ACCELERATION, KEPLINGER_CHORD,
                                               KEPLINGER_PRELOAD_STEPS,
                                               KEPLINGER_RTOL, KEPLINGER_SIZE)
from skfem_dielectric.gallery.loads import keplinger_s

from ..specs import GENT_JM, KEPLINGER, RunSpec

__all__ = ["BUCKLING_GRAD_DIV", "BUCKLING_NEWTON", "with_dead_load",
           "is_membrane", "build_problem", "buckling_problem", "ramp_targets", "ramp_settings",
           "pardiso_installed"]

#: the Keplinger plate, mm: the gallery's plate
L1, H, L3 = KEPLINGER_SIZE
MEMBRANE_VARIANTS = ("membrane", "membrane-maxwell")
#: 3D pre-load sub-steps: those of the drivers equibiaxial_plate and keplinger_plate.
PRELOAD_STEPS = {"equibiaxial": EQUIBIAXIAL_PRELOAD_STEPS, "uniaxial": KEPLINGER_PRELOAD_STEPS}
#: 3D Newton tolerance relative to the external load (``atol = 0``): that of
#: equibiaxial_plate and of keplinger_plate; the membrane keeps the plain ramp's tolerances.
RTOL = {"equibiaxial": EQUIBIAXIAL_RTOL, "uniaxial": KEPLINGER_RTOL}
#: chord factor of the ramps' Newton solves (:func:`skfem_dielectric.solvers.newton.newton`),
#: that of keplinger_plate: a factorisation is reused, within a load step and across load
#: steps, while the residual contracts by at least this factor per (Anderson-accelerated,
#: :data:`ACCELERATION`) chord step.  Every Newton solve starts from the secant through the
#: last two converged states (the ramp's default predictor); the state before the last one
#: and the origin of the factors the next step starts on are saved with each row's state,
#: so that a resumed ramp repeats the uninterrupted one bit for bit (timings:
#: docs/performance.md).
CHORD = KEPLINGER_CHORD
#: depth of the Anderson acceleration of the ramps' chord steps, that of keplinger_plate
ACCELERATION = KEPLINGER_ACCELERATION
#: grad-div stabilisation (units of mu) of the form ramped for the whole plate's spectrum
#: and ``D0_b``: the second ramp of the uni-axial runs analysed for buckling
#: (``RunSpec.buckling``, :func:`buckling_problem`), and the ramps of the studies
#: ``buckling`` and ``post-buckling``; each state is analysed with its own tangent, the
#: Hessian of the energy whose equilibrium it is (docs/stability.md, "Which state each
#: column is of")
BUCKLING_GRAD_DIV = 10.0
#: Newton settings of the trial states of the location of ``D0_b`` (to
#: :data:`validation.specs.LOCATION_TOL`)
BUCKLING_NEWTON = fe.RampSettings(rtol=1e-9, max_cutbacks=6, max_iter=25)


def with_dead_load(spec: RunSpec) -> RunSpec:
    """``spec`` with its dead load ``s`` set: a Keplinger run given by its weight fraction
    (``s=None``, ``alpha`` given) gets the FE package's ``s = alpha m g/(mu A)``,
    :func:`skfem_dielectric.gallery.loads.keplinger_s` with ``g = KEPLINGER["g"] = 9.81
    m/s^2`` (paper caption of Fig. uni-axial-ideal); any other spec is returned as it is.

    Parameters
    ----------
    spec : RunSpec

    Returns
    -------
    RunSpec

    Examples
    --------
    >>> spec = RunSpec("uniaxial", "neo-Hookean", "coupled", None, (0.0,), alpha=1.0)
    >>> round(with_dead_load(spec).s, 5)
    2.99296
    """
    if spec.s is not None:
        return spec
    return replace(spec, s=keplinger_s(spec.alpha, g=KEPLINGER["g"]))


def is_membrane(spec: RunSpec) -> bool:
    """Whether ``spec`` is a 2D membrane run (``membrane`` or ``membrane-maxwell``)."""
    return spec.variant in MEMBRANE_VARIANTS


# --------------------------------------------------------------------------- the FE model
def build_problem(spec: RunSpec):
    """The FE problem of ``spec``, a ramp problem of :mod:`skfem_dielectric`.

    The 3D plates are eighth models: of a 4 x 1 x 4 plate with one element per
    direction by default for the homogeneous equi-biaxial state (as
    :func:`skfem_dielectric.equibiaxial_plate`), of the 100 x 1 x 50 mm Keplinger plate
    (as :func:`skfem_dielectric.keplinger_plate`). The membrane is the quarter of the
    100 x 50 mm plate of thickness 1 mm.

    Parameters
    ----------
    spec : RunSpec

    Returns
    -------
    PlateProblem or MembranePlate
        For ``variant="maxwell"`` the plate with ``coupling="maxwell"`` and the field of
        the potential solved on the deformed body.
    """
    m = spec.mesh_dict
    if is_membrane(spec):
        coupling = "maxwell" if spec.variant == "membrane-maxwell" else "full"
        # the geometry names are the models' loadings (the Keplinger plate is "uniaxial")
        return fe.MembranePlate(fe.membrane_mesh(L1, H, L3, m.get("n1", 1), m.get("n3", 1)),
                                fe.make_material(spec.model, Jm=GENT_JM),
                                loading=spec.geometry, coupling=coupling)
    el = (m.get("n1", 1), m.get("n2", 1), m.get("n3", 1))
    # the variant that discretises the fully coupled equations (docs/fe_variants.md)
    options = fe.PlateOptions(coupling="maxwell", field="electrostatic") \
        if spec.variant == "maxwell" else fe.PlateOptions()
    if spec.geometry == "equibiaxial":
        return fe.gallery.equibiaxial_problem(model=spec.model, Jm=GENT_JM, elements=el,
                                              options=options)
    if spec.geometry == "uniaxial":
        # the plain form for every run, also the one analysed for buckling: its state is
        # the one the paper's P33 criterion reads (the whole plate's spectrum of such a run
        # is of the grad-div form's own state, buckling_problem)
        return fe.gallery.keplinger_problem(model=spec.model, Jm=GENT_JM, size=(L1, H, L3),
                                            elements=el, options=options)
    raise ValueError(f"the 3D plate has no geometry {spec.geometry!r}")


def buckling_problem(spec: RunSpec):
    """The grad-div form of the plate of a run analysed for buckling (``spec.buckling``).

    The plain form (:func:`build_problem`) gives the run's ``P33`` columns; this form
    (:data:`BUCKLING_GRAD_DIV`, which lets Newton pass the clamp/free-edge corner) is
    ramped to the same loads for the whole plate's spectrum and the located ``D0_b``.
    Each of its states is an equilibrium of the stabilised energy, so that its own tangent
    is the Hessian whose spectrum is read; the stabilised tangent at a plain state is not
    (the stabilised energy's gradient there is ``gamma (J - 1)``, not zero, where the
    discrete ``J`` departs from 1).  The same form as the studies ``buckling`` and
    ``post-buckling`` (Conroy Broderick et al. 2020, Sec. 6, the clamped plate).

    Parameters
    ----------
    spec : RunSpec
        A 3D fully coupled uni-axial run (``variant="coupled"``).

    Returns
    -------
    PlateProblem

    Raises
    ------
    ValueError
        ``spec`` is not such a run.
    """
    if spec.geometry != "uniaxial" or spec.variant != "coupled":
        raise ValueError(f"spec must be a 3D fully coupled uni-axial run, got geometry "
                         f"{spec.geometry!r}, variant {spec.variant!r}")
    m = spec.mesh_dict
    el = (m.get("n1", 1), m.get("n2", 1), m.get("n3", 1))
    return fe.gallery.keplinger_problem(model=spec.model, Jm=GENT_JM, size=(L1, H, L3),
                                        elements=el,
                                        options=fe.PlateOptions(grad_div=BUCKLING_GRAD_DIV))


def ramp_targets(spec: RunSpec) -> list:
    """The ramp's loads ``(s, D0)`` for ``spec``, the pre-load first.

    3D: the pre-load in equal steps ``(s k/n, 0)``, ``n`` from :data:`PRELOAD_STEPS`
    (a single ``(0, 0)`` target when ``s = 0``), then ``(s, D0)`` for the charge
    targets. Membrane: straight to ``(s, D0)`` for every target, as
    :func:`skfem_dielectric.gallery.membrane_ramp`.

    Parameters
    ----------
    spec : RunSpec

    Returns
    -------
    list of ndarray
    """
    if is_membrane(spec):
        return [np.array([spec.s, d]) for d in spec.D0]
    n = PRELOAD_STEPS[spec.geometry] if spec.s > 0 else 1
    return fe.gallery.preload_then_charge(spec.s, spec.D0, n)


def ramp_settings(spec: RunSpec, linear_solver="superlu") -> dict:
    """Keyword arguments of :func:`skfem_dielectric.solvers.ramp.ramp` for ``spec``.

    Parameters
    ----------
    spec : RunSpec
    linear_solver : str
        Requested solver. The Maxwell-traction variants have a non-symmetric tangent
        (follower load), which the symmetric-indefinite PARDISO set-up (upper triangle
        only) cannot factorise: they get :func:`skfem_dielectric.linalg.nonsymmetric_solver`
        of it (SuperLU, or PARDISO as a general LU when PARDISO is asked for).

    Returns
    -------
    dict
        ``settings``: the ramp's :class:`skfem_dielectric.RampSettings` (its tolerances,
        cut-backs and Newton budget) with ``chord`` :data:`CHORD`, ``acceleration``
        :data:`ACCELERATION` and ``keep_factors``, and in 3D ``atol = 0``
        and ``rtol`` :data:`RTOL`; and ``linear_solver``.
    """
    if "maxwell" in spec.variant:
        linear_solver = fe.linalg.nonsymmetric_solver(linear_solver)
    settings = fe.RampSettings(chord=CHORD, acceleration=ACCELERATION, keep_factors=True)
    if not is_membrane(spec):
        settings = replace(settings, atol=0.0, rtol=RTOL[spec.geometry])
    return {"settings": settings, "linear_solver": linear_solver}


def pardiso_installed() -> bool:
    """Whether PARDISO (pypardiso, the ``fast`` extra) can be used."""
    return fe.linalg.pardiso_available()
