"""What ``check`` scores: the cases, their tolerances and where each comes from.

:data:`CHECK_CASES` names the closed forms each case is scored with, :data:`TOLERANCES` the
default tolerance of each measure (:data:`TOLERANCE_SOURCES` says why, docs/check.md in
full), :func:`parse_tolerances` reads ``--tol NAME=VALUE``; :class:`CheckInputError` is the
one error a file that cannot be scored raises, and :data:`MAX_FILE_BYTES` and
:data:`MAX_TOTAL_BYTES` bound what is read.
"""

from __future__ import annotations

import math

__all__ = ["CHECK_CASES", "TOLERANCES", "TOLERANCE_SOURCES", "VERDICT_MEASURES",
           "MAX_FILE_BYTES", "MAX_TOTAL_BYTES", "CheckInputError", "parse_tolerances"]

CHECK_CASES = {
    "nh-d-e": ("equibiaxial", "neo-Hookean"),
    "gent-d-e": ("equibiaxial", "Gent"),
    "gent-equi-biaxial": ("equibiaxial", None),
    "figde": ("uniaxial-free", "neo-Hookean"),
    "uni-axial-ideal": ("clamped", "neo-Hookean"),
    "lambda1-3": ("clamped", "neo-Hookean"),
    "zs22": ("clamped", "neo-Hookean"),
    "voltage-control": ("voltage", None),
    "wrinkling-fe": ("wrinkling", "neo-Hookean"),
}

#: Default tolerances of the measures (``--tol NAME=VALUE`` replaces one; docs/check.md
#: says where each comes from, :data:`TOLERANCE_SOURCES` in one line each).
TOLERANCES = {
    "lam1": 1e-6,
    "lam1_clamped": 1e-2,
    "lam1_limit": 1e-4,
    "E0_limit": 1e-6,
    "stable": 0.0,
    "D0_crit": 1e-3,
    "D0_b": 0.0,
}

TOLERANCE_SOURCES = {
    "lam1": "a homogeneous state is exact in any conforming discretisation: what remains is "
            "the solver tolerance and the digits of the file (validate itself holds 1e-8)",
    "lam1_clamped": "the centre of the clamped plate follows the homogeneous curve within "
                    "1 % (paper Sec. 6; validate's tolerance)",
    "lam1_limit": "the limit point located on a path of E0 flat to second order: 1e-4 in "
                  "lam1 (validate's voltage-control target)",
    "E0_limit": "the maximum of E0 itself, 1e-6 (validate's voltage-control target)",
    "stable": "the Hessian verdict is exact away from the det H* = 0 locus: no row may "
              "disagree (rows within the lam1_limit tolerance of the limit point excluded)",
    "D0_crit": "validate's FE cross-section with 8 elements per half-wave reaches 1e-3",
    "D0_b": "the converged buckling load's error bar (the graded meshes of "
            "validation/data/clamp_units.csv) plus the file's D0_b_error, or this absolute "
            "value",
}

#: The measures that are verdicts (a row agrees with the closed form or not): no tolerance
#: applies to them, and ``--tol`` refuses them.
VERDICT_MEASURES = ("stable",)

#: The largest results file ``check`` reads, in bytes (larger: one line, exit 2; split the
#: file by case).
MAX_FILE_BYTES = 12 * 1024**2
#: The most ``check`` reads from one folder, in bytes, all scored files together (the
#: files it names and skips, field samples and study tables, do not count).
MAX_TOTAL_BYTES = 12 * 1024**2


class CheckInputError(ValueError):
    """A results file that cannot be scored; the message is one line naming the file (and
    the line and column where there is one)."""


def parse_tolerances(items) -> dict:
    """Tolerances from ``NAME=VALUE`` texts (``--tol``).

    Parameters
    ----------
    items : iterable of str or dict
        ``["lam1=1e-4", ...]``, or a ``dict`` ``{name: value}``.

    Returns
    -------
    dict
        :data:`TOLERANCES` with the given ones replaced.

    Raises
    ------
    ValueError
        An unknown name, a verdict (:data:`VERDICT_MEASURES`), a text without ``=``, a
        value that is no number ``>= 0``.
    """
    tol = dict(TOLERANCES)
    pairs = items.items() if isinstance(items, dict) else []
    if not isinstance(items, dict):
        pairs = []
        for text in items or ():
            name, sep, value = str(text).partition("=")
            if not sep:
                raise ValueError(f"--tol must be NAME=VALUE (names: {', '.join(TOLERANCES)}), "
                                 f"got {text!r}")
            pairs.append((name.strip(), value.strip()))
    for name, value in pairs:
        if name not in TOLERANCES:
            raise ValueError(f"--tol: unknown measure {name!r} (measures: "
                             f"{', '.join(TOLERANCES)})")
        if name in VERDICT_MEASURES:
            raise ValueError(f"--tol {name}: a verdict, with no tolerance to set (a row agrees "
                             f"with the Hessian or not; rows near a limit point are left out "
                             f"by lam1_limit); tolerances: "
                             f"{', '.join(n for n in TOLERANCES if n not in VERDICT_MEASURES)}")
        try:
            v = float(value)
        except (TypeError, ValueError):
            v = math.nan
        if not (math.isfinite(v) and v >= 0):
            raise ValueError(f"--tol {name} must be a number >= 0, got {value!r}")
        tol[name] = v
    return tol
