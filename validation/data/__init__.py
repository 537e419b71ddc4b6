"""The ground floor of validation: the measured tables the project ships and their readers.

No finite elements are loaded here.

* :mod:`validation.data.registry` -- every table by name (:data:`~validation.data.registry.TABLES`)
  and one :func:`~validation.data.registry.load` for shipped and run-written tables;
* :mod:`validation.data.spec` -- a table's schema (:class:`~validation.data.spec.TableSpec`)
  and the one :func:`~validation.data.spec.read_table`;
* :mod:`validation.data.key` -- :class:`~validation.data.key.UnitKey`, what names a unit;
* :mod:`validation.data.clamp_zone` -- a unit's row, the convergence rule of a load;
* :mod:`validation.data.loads` -- the buckling loads the project stands behind, the Newton
  limits and the located ``P33`` onsets.
"""

from .key import UnitKey
from .loads import buckling_loads, converged_buckling_load, newton_limits, p33_onsets
from .registry import TABLES, load
from .spec import TableSpec, read_table

__all__ = ["UnitKey", "TableSpec", "read_table", "TABLES", "load", "buckling_loads",
           "converged_buckling_load", "newton_limits", "p33_onsets"]
