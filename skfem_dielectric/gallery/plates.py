"""The model options of the paper's 3D plates, one object for what the builders and drivers
forward to :class:`~skfem_dielectric.models.plate.problem.PlateProblem`.

:class:`PlateOptions` lists them once: the control (charge ``D0`` or voltage ``E0``), the
coupling (the fully coupled energy of Eq. (OmegaOmegastar), or the Maxwell traction of the
solved field), the incompressibility formulation, the potential's element, the grad-div
stabilisation and the assembly threads.  A builder
(:func:`~skfem_dielectric.gallery.drivers.keplinger_problem`) and a driver
(:func:`~skfem_dielectric.gallery.drivers.keplinger_plate`) take it as ``options=``, so that
they forward one checked object instead of eight keyword arguments.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ..checks import check_choice, check_count, check_nonnegative, check_positive
from ..materials import FORMULATIONS
from ..forms.mixed_upphi import PRESSURE_ELEMENTS
from ..models.plate.problem import CONTROLS, COUPLINGS, FIELDS, PHI_ELEMENTS

__all__ = ["PlateOptions"]


@dataclass(frozen=True)
class PlateOptions:
    """The options of a :class:`~skfem_dielectric.models.plate.problem.PlateProblem` that
    the gallery's builders and drivers pass on, checked once where the object is made.

    Change one field with :func:`dataclasses.replace` or make a new object, e.g.
    ``PlateOptions(control="voltage")`` or ``PlateOptions(grad_div=10.0)``; the defaults
    are those of ``PlateProblem``.

    Attributes
    ----------
    control
        ``"charge"`` (the load is ``(s, D0)``, ``D0 = sigma_F / sqrt(mu eps)``, the
        paper's charge control, Eq. (BCS)) or ``"voltage"`` (``(s, E0)``).
    coupling
        ``"full"`` (the fully coupled energy, Eq. (OmegaOmegastar)) or ``"maxwell"`` (mechanics
        loaded by the Maxwell traction of the solved field).
    field
        With ``coupling="maxwell"``: ``"electrostatic"`` (the field of the solved potential)
        or ``"local"`` (the field of the charge, charge control only).
    formulation, kappa
        How ``J = 1`` is imposed: ``"mixed"`` (pressure multiplier), ``"penalty"``,
        ``"isochoric"``, ``"mixed-isochoric"`` or ``"mixed-plain"``; ``kappa`` the bulk modulus (units of
        ``mu``, ``> 0``, ``inf`` for the exactly incompressible mixed forms, finite for the
        penalty and isochoric ones).
    phi_element
        Element of the potential, ``"Q1"`` or ``"Q2"``.
    pressure
        Pressure space of the mixed forms, ``"Q1"`` (Taylor-Hood) or ``"P0"`` (Q2-P0).
    threads
        Assembly threads (``None``: the package default, ``>= 1`` otherwise).
    grad_div
        Grad-div stabilisation of the mixed form (units of ``mu``, ``>= 0``; ``10`` lets
        Newton pass the clamp/free-edge corner of the Keplinger plate, docs/validation.md).

    Raises
    ------
    ValueError
        A field out of its range, naming the field and the value.  Combinations of fields
        (the local Maxwell field under voltage control, ``grad_div`` with the penalty form)
        are checked by ``PlateProblem``.

    Examples
    --------
    >>> PlateOptions(control="voltage").as_kwargs()["control"]
    'voltage'
    >>> PlateOptions(phi_element="Q3")
    Traceback (most recent call last):
    ...
    ValueError: phi_element must be one of ('Q1', 'Q2'), got 'Q3'
    """

    control: str = "charge"
    coupling: str = "full"
    field: str = "electrostatic"
    formulation: str = "mixed"
    kappa: float = math.inf
    phi_element: str = "Q2"
    threads: int | None = None
    grad_div: float = 0.0
    pressure: str = "Q1"

    def __post_init__(self) -> None:
        for name, choices in (("control", CONTROLS), ("coupling", COUPLINGS),
                              ("field", FIELDS), ("formulation", FORMULATIONS),
                              ("phi_element", PHI_ELEMENTS), ("pressure", PRESSURE_ELEMENTS)):
            check_choice(name, getattr(self, name), choices)
        if self.kappa != math.inf:
            check_positive("kappa", self.kappa)
        if self.threads is not None:
            check_count("threads", self.threads)
        check_nonnegative("grad_div", self.grad_div)

    def as_kwargs(self) -> dict:
        """The fields as keyword arguments of
        :class:`~skfem_dielectric.models.plate.problem.PlateProblem`."""
        return asdict(self)
