"""Closed-form theory of charge-controlled soft dielectric plates.

Implements the homogeneous theory of Conroy Broderick, Righi, Destrade & Ogden,
"Stability analysis of charge-controlled soft dielectric plates": loading curves,
Hessian criteria and Stroh-formalism wrinkling. Everything is dimensionless
(``mu = eps = 1``); see :mod:`analytic.units` for SI conversions.
"""

from .models import Gent, Model, NeoHookean, UserModel, as_model

__all__ = ["Model", "NeoHookean", "Gent", "UserModel", "as_model"]
