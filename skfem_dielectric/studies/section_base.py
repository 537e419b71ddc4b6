"""The base state of a clamp-edge section solved by the package's Newton: one 3D state
(:func:`solve_section_base`) or a path of them (:func:`continue_section_base`).

The equations are those of :class:`~skfem_dielectric.models.edge_base.SectionBaseProblem`
(the plate's ``u``-``p``-``phi`` energy on the section, ``F_33`` and the boundary data
from the 3D state); each state is solved by :func:`~skfem_dielectric.solvers.newton.newton`
with the model's own guards, so that no state with ``J = det F <= 0`` at a quadrature
point is ever accepted, as on the plate.
"""

from __future__ import annotations

from typing import Callable

from ..models.edge_base import SectionBase, SectionBaseProblem
from ..solvers.newton import NewtonSettings, newton

__all__ = ["solve_section_base", "continue_section_base"]


def solve_section_base(g1, g2, material, fields: Callable, D0: float, *,
                       guess: Callable | None = None, grad_div: float = 0.0,
                       tol: float = 1e-10, max_iter: int = 40,
                       pressure: str = "Q1") -> SectionBase:
    """Solve the section's base state from the 3D state ``fields``.

    Parameters
    ----------
    g1, g2, material, fields, D0, guess, grad_div, pressure
        The section, its 3D state and its pressure space
        (:class:`~skfem_dielectric.models.edge_base.SectionBaseProblem`); ``guess`` is the
        first guess inside the section (default ``fields``): the solution on a coarser
        section (:meth:`~skfem_dielectric.models.edge_base.SectionBase.fields`) is a better
        one where the edge is fine, since the 3D state is far from the section's
        equilibrium at the edge, where the 3D mesh cannot follow the singular field.
    tol, max_iter
        Newton stops when the residual norm is below ``tol`` times its scale (the largest
        of the first residual, the charge's load vector and ``mu`` times the section's
        area), or at round-off (:class:`~skfem_dielectric.solvers.newton.NewtonSettings`
        ``xtol``); at most ``max_iter`` steps.

    Returns
    -------
    SectionBase

    Raises
    ------
    ValueError
        A first guess with ``J <= 0`` somewhere, or Newton not converging within
        ``max_iter`` steps (the message gives Newton's reason: an inverted state is one).
    """
    pb = SectionBaseProblem(g1, g2, material, fields, D0, guess=guess, grad_div=grad_div,
                            pressure=pressure)
    y = pb.initial_state()
    why = pb.admissible(y)
    if why:
        raise ValueError(f"the section's first guess is not admissible: {why}")
    r0 = pb.residual0 / pb.scale
    if r0 < tol:
        return pb.base(y, 0, r0)
    guards = pb.newton_guards()
    res = newton(pb.assemble, y, residual=pb.residual, linear_solver="superlu",
                 scale=pb.scale,
                 step_limit=lambda x, dx: guards["step_limit"](x, dx, None),
                 admissible=lambda x: guards["admissible"](x, None),
                 settings=NewtonSettings(atol=0.0, rtol=tol, max_iter=max_iter,
                                         max_backtracks=12))
    if not res.converged:
        raise ValueError(f"the section's base state did not converge in max_iter = {max_iter} "
                         f"Newton steps ({res.reason or 'no reason given'}; relative "
                         f"residual {res.residual_norms[-1] / pb.scale:.2e})")
    return pb.base(res.x, res.iterations, res.residual_norms[-1] / pb.scale)


def _blend(fa: Callable, fb: Callable, t: float) -> Callable:
    """The fields ``(1 - t) fa + t fb`` (``u``, ``phi``, ``p``, ``F``)."""
    def fields(X1, X2):
        a, b = fa(X1, X2), fb(X1, X2)
        return {name: (1.0 - t) * a[name] + t * b[name] for name in ("u", "phi", "p", "F")}
    if hasattr(fa, "grad_div"):
        fields.grad_div = fa.grad_div
    return fields


def _shifted(sb: SectionBase, old: Callable, new: Callable) -> Callable:
    """The guess ``sb + (new - old)``: the section's solution moved by the change of the
    3D state, so that the boundary data move with it."""
    def guess(X1, X2):
        f, a, b = sb.fields(X1, X2), old(X1, X2), new(X1, X2)
        return {"u": f["u"] + (b["u"][:2] - a["u"][:2]),
                "phi": f["phi"] + (b["phi"] - a["phi"]),
                "p": f["p"] + (b["p"] - a["p"])}
    return guess


def continue_section_base(g1, g2, material, path, *, grad_div: float = 0.0,
                          tol: float = 1e-10, max_iter: int = 40, max_halvings: int = 6,
                          progress: Callable | None = None,
                          pressure: str = "Q1") -> SectionBase:
    """Solve the section's base state along a path of 3D states, by continuation in the
    charge.

    The first state is solved from its own 3D fields (:func:`solve_section_base`); each
    next one from the last solution moved by the change of the 3D state, ``guess = x + (f_new
    - f_old)`` (so the clamp's and the cut's data move with it).  Between two states of the
    path the 3D fields and ``D0`` are interpolated linearly, and a step that does not
    converge is halved, at most ``max_halvings`` times.

    Parameters
    ----------
    g1, g2, material, grad_div, tol, max_iter, pressure
        As for :func:`solve_section_base`.
    path
        ``[(D0, fields), ...]`` in the order to follow (e.g. the 3D ramp's converged
        states, :func:`~skfem_dielectric.models.edge_section.plate_fields` of each); the
        result is the last one's base state.
    max_halvings
        The smallest step is ``2 ** -max_halvings`` of an interval of the path.
    progress
        Optional ``progress(text)`` after each state of the path.

    Returns
    -------
    SectionBase
        The base state at the path's last state; its ``iterations`` are the Newton steps
        of the whole path.

    Raises
    ------
    ValueError
        An empty path, or a step of the smallest size that does not converge (the message
        names the charge).
    """
    path = list(path)
    if not path:
        raise ValueError("path must hold at least one (D0, fields) state, got none")
    D0, f0 = path[0]
    sb = solve_section_base(g1, g2, material, f0, D0, grad_div=grad_div, tol=tol,
                            max_iter=max_iter, pressure=pressure)
    total = sb.iterations
    for (Da, fa), (Db, fb) in zip(path[:-1], path[1:]):
        t, dt = 0.0, 1.0
        while t < 1.0:
            t1 = min(1.0, t + dt)
            old, new = _blend(fa, fb, t), _blend(fa, fb, t1)
            try:
                sb = solve_section_base(g1, g2, material, new, (1 - t1) * Da + t1 * Db,
                                        guess=_shifted(sb, old, new), grad_div=grad_div,
                                        tol=tol, max_iter=max_iter, pressure=pressure)
            except ValueError:
                if dt <= 2.0 ** -max_halvings:
                    raise ValueError(f"the section's base state did not converge at D0 = "
                                     f"{(1 - t1) * Da + t1 * Db:.6g} with the smallest step "
                                     f"(max_halvings = {max_halvings})") from None
                dt /= 2
                continue
            total += sb.iterations
            t = t1
        if progress is not None:
            progress(f"D0 = {Db:g}: {total} Newton steps so far")
    sb.iterations = total
    return sb
