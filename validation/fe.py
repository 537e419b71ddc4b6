"""Adapters from :mod:`skfem_dielectric` drivers to the harness's runner protocol.

:func:`run_fe` is the default runner of :func:`validation.sweep.run_case`: it
builds the FE problem of a :class:`~validation.cases.RunSpec`, ramps ``D0``
with :func:`skfem_dielectric.newton.ramp` and reports each converged target
as a :class:`~validation.sweep.StepRecord`.
"""

from __future__ import annotations

__all__ = ["run_fe", "simulate", "bench"]


def _drivers():
    try:
        import skfem_dielectric as fe
    except ImportError as exc:  # pragma: no cover
        raise RuntimeError(f"the FE package is not importable: {exc}") from exc
    return fe


def run_fe(spec, start, state, on_step):
    """Run one FE ramp of ``spec`` from target ``start`` (runner protocol of :mod:`.sweep`)."""
    raise RuntimeError("the FE drivers of skfem_dielectric are not available yet")


def simulate(**kwargs):
    """Run one FE ramp and export it (``skfem-dielectric simulate``)."""
    raise RuntimeError("the FE drivers of skfem_dielectric are not available yet")


def bench(**kwargs):
    """Time one Keplinger ramp (``skfem-dielectric bench``)."""
    raise RuntimeError("the FE drivers of skfem_dielectric are not available yet")
