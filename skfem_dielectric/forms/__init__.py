"""Weak forms of the FE models, one module per form (equations in each docstring).

``mixed_upphi``
    3D mixed u-p-phi volume form of the incompressible ideal dielectric (hexahedra).
``reference``
    the same form as plain scikit-fem integrands (:class:`reference.ReferenceForm`):
    slow, readable, the statement the fast assembly is tested against.
``maxwell_traction``
    the Maxwell traction on the deformed boundary, its follower-load linearisation, and
    its boundary form on a 3D plate.
``membrane``
    the membrane energy of a thin plate and the Maxwell traction on its edges.
``plane_strain``
    the generalised-plane-strain cross-section (x1-x2) with a uniform ``lam3``.
"""
