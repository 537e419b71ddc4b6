"""What names a unit of the clamp-zone study: :class:`UnitKey`, parsed once and used for
the rows of every table, the mode files and the figures."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

__all__ = ["UnitKey", "mesh_text", "parse_mesh", "FORMULATIONS"]

#: how ``J = 1`` may be imposed in a unit (:class:`skfem_dielectric.PlateOptions`)
FORMULATIONS = ("mixed", "mixed-isochoric", "mixed-plain")

_STEM = re.compile(r"(?P<alpha>[0-9.e+-]+)_(?P<mesh>\d+x\d+x\d+)_g(?P<grading>[0-9.e+-]+)_"
                   r"(?P<formulation>[a-z-]+)$")


def _g(value) -> float:
    """A number as the tables write it in a key (``%g``), read back."""
    return float(f"{float(value):g}")


def mesh_text(elements) -> str:
    """``(n1, n2, n3)`` as the study writes it, ``"n1xn2xn3"``.

    Examples
    --------
    >>> mesh_text((40, 1, 36))
    '40x1x36'
    """
    return "x".join(str(int(n)) for n in elements)


def parse_mesh(text: str) -> tuple[int, int, int]:
    """``"n1xn2xn3"`` as ``(n1, n2, n3)``.

    Raises
    ------
    ValueError
        Not three positive counts; the message names the text.

    Examples
    --------
    >>> parse_mesh("12x1x6")
    (12, 1, 6)
    """
    try:
        n = tuple(int(v) for v in str(text).split("x"))
    except ValueError:
        n = ()
    if len(n) != 3 or min(n) < 1:
        raise ValueError(f"a mesh is n1xn2xn3 with positive counts, got {text!r}")
    return n


@dataclass(frozen=True)
class UnitKey:
    """One unit: the weight fraction ``alpha`` on the eighth-model mesh ``mesh`` graded by
    ``grading`` (last / first element length along ``x1``) with ``J = 1`` imposed as
    ``formulation``.  Numbers are held as the tables write them (``%g``), so a key read
    from a row equals the key of the run that wrote it.

    Examples
    --------
    >>> k = UnitKey.from_row({"alpha": "1", "mesh": "12x1x6", "grading": "0.25",
    ...                       "formulation": "mixed"})
    >>> k.stem, k.cells
    ('1_12x1x6_g0.25_mixed', ('1', '12x1x6', '0.25', 'mixed'))
    >>> UnitKey.parse(k.stem) == k == UnitKey(1.0, (12, 1, 6), 0.25)
    True
    """

    alpha: float
    mesh: tuple
    grading: float = 1.0
    formulation: str = "mixed"

    def __post_init__(self):
        object.__setattr__(self, "alpha", _g(self.alpha))
        object.__setattr__(self, "grading", _g(self.grading))
        object.__setattr__(self, "mesh", tuple(int(n) for n in self.mesh))

    @classmethod
    def from_row(cls, row: dict) -> "UnitKey":
        """The key of a row of any of the study's tables (text or numbers)."""
        return cls(float(row["alpha"]), parse_mesh(row["mesh"]), float(row["grading"]),
                   str(row.get("formulation") or "mixed"))

    @classmethod
    def parse(cls, stem: str) -> "UnitKey":
        """The key of a mode file's stem (:attr:`stem`).

        Raises
        ------
        ValueError
            ``stem`` is not ``<alpha>_<mesh>_g<grading>_<formulation>``.
        """
        m = _STEM.match(stem)
        if m is None:
            raise ValueError(f"a unit's file stem is <alpha>_<n1xn2xn3>_g<grading>_"
                             f"<formulation>, got {stem!r}")
        return cls(float(m["alpha"]), parse_mesh(m["mesh"]), float(m["grading"]),
                   m["formulation"])

    @property
    def mesh_text(self) -> str:
        """The mesh as ``"n1xn2xn3"``."""
        return mesh_text(self.mesh)

    @property
    def cells(self) -> tuple[str, str, str, str]:
        """The key's cells in a table: ``alpha``, ``mesh``, ``grading``, ``formulation``."""
        return (f"{self.alpha:g}", self.mesh_text, f"{self.grading:g}", self.formulation)

    @property
    def stem(self) -> str:
        """The stem of the unit's files (the mode at ``D0_b``)."""
        return f"{self.alpha:g}_{self.mesh_text}_g{self.grading:g}_{self.formulation}"

    @property
    def elements(self) -> int:
        """The eighth model's element count ``n1 n2 n3``."""
        return math.prod(self.mesh)

    def __str__(self) -> str:
        return (f"alpha = {self.alpha:g} {self.mesh_text} grading {self.grading:g}"
                + ("" if self.formulation == "mixed" else f" ({self.formulation})"))
