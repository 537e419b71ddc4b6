"""Input checks of the FE API: each names the parameter and the value it rejects.

Numbers are real numbers (Python or numpy scalars; ``bool``, strings and ``None`` are
rejected rather than converted), counts are integral, callables are callable; every
rejection is a ``ValueError`` whose message starts with the parameter's name.
"""

from __future__ import annotations

import math
import numbers
import os
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np

__all__ = ["check_number", "check_positive", "check_nonnegative", "check_count",
           "check_nonnegative_int", "check_finite", "check_choice", "check_callable",
           "check_tolerances", "check_material", "check_vector", "check_file_prefix",
           "check_folder", "check_file_path", "check_energy", "check_instance"]


def check_number(name: str, value: Any) -> float:
    """``float(value)`` of a real number (may be ``inf``/``nan``), else ``ValueError``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        if not (isinstance(value, np.ndarray) and value.shape == ()
                and value.dtype.kind in "iuf"):
            raise ValueError(f"{name} must be a real number, got {value!r}")
    return float(value)


def check_positive(name: str, value: Any) -> float:
    """``float(value)`` if it is a finite number > 0, else ``ValueError`` naming ``name``."""
    v = check_number(name, value)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return v


def check_nonnegative(name: str, value: Any) -> float:
    """``float(value)`` if it is a finite number >= 0, else ``ValueError`` naming ``name``."""
    v = check_number(name, value)
    if not (math.isfinite(v) and v >= 0):
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return v


def _integer(name: str, value: Any, low: int) -> int:
    v = check_number(name, value) if not isinstance(value, numbers.Integral) else value
    if isinstance(value, (bool, np.bool_)) or not math.isfinite(v) or int(v) != v or v < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    return int(v)


def check_count(name: str, value: Any) -> int:
    """``int(value)`` if it is an integer >= 1, else ``ValueError`` naming ``name``."""
    return _integer(name, value, 1)


def check_nonnegative_int(name: str, value: Any) -> int:
    """``int(value)`` if it is an integer >= 0, else ``ValueError`` naming ``name``."""
    return _integer(name, value, 0)


def check_finite(name: str, value: Any) -> float:
    """``float(value)`` if it is finite, else ``ValueError`` naming ``name``."""
    v = check_number(name, value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def check_choice(name: str, value: Any, choices: Sequence[str]) -> str:
    """``value`` if it is one of ``choices``, else ``ValueError`` naming ``name``."""
    if not isinstance(value, str) or value not in choices:
        raise ValueError(f"{name} must be one of {tuple(choices)}, got {value!r}")
    return value


def check_callable(name: str, value: Any, optional: bool = True) -> Any:
    """``value`` if it is callable (or ``None`` when ``optional``), else ``ValueError``."""
    if not (callable(value) or (optional and value is None)):
        raise ValueError(f"{name} must be callable{' or None' if optional else ''}, "
                         f"got {value!r}")
    return value


def check_instance(name: str, value: Any, cls: type, made_by: str) -> Any:
    """``value`` if it is a ``cls`` (as ``made_by`` returns it), else ``ValueError`` naming
    ``name`` and the type it got; e.g. the mesh argument of a model."""
    if not isinstance(value, cls):
        raise ValueError(f"{name} must be a {cls.__name__} (from {made_by}), got "
                         f"{type(value).__name__} {value!r:.60}")
    return value


def check_tolerances(atol: Any, rtol: Any) -> tuple[float, float]:
    """``(atol, rtol)``: finite and >= 0, not both zero (a test that can never be met)."""
    a, r = check_nonnegative("atol", atol), check_nonnegative("rtol", rtol)
    if a == 0 and r == 0:
        raise ValueError(f"atol and rtol must not both be 0 (the convergence test "
                         f"||r|| <= 0 can never be met), got atol={atol!r}, rtol={rtol!r}")
    return a, r


def check_material(name: str, material: Any) -> Any:
    """``material`` if it has ``mu``, ``eps`` and ``energy_derivatives`` (a dielectric of
    :mod:`skfem_dielectric.materials`), else ``ValueError`` naming ``name``."""
    for attr in ("mu", "eps", "energy_derivatives"):
        if not hasattr(material, attr):
            raise ValueError(f"{name} must be a dielectric material (NeoHookeanDielectric, "
                             f"GentDielectric, IdealDielectric) defining {attr!r}, got "
                             f"{material!r}")
    return material


def check_vector(name: str, value: Any, n: int) -> np.ndarray:
    """``value`` as a float array of shape ``(n,)`` with finite entries, else ``ValueError``."""
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real vector of length {n}, got {value!r}") from None
    if arr.shape != (n,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be a finite vector of length {n}, got shape "
                         f"{arr.shape}" + ("" if arr.shape != (n,) else " with non-finite entries"))
    return arr


def check_file_prefix(name: str, value: Any) -> str:
    """``value`` if it is a non-empty file-name prefix without path separators, ``..``
    or NUL characters (files stay in their folder), else ``ValueError``."""
    if (not isinstance(value, str) or not value or "/" in value or "\\" in value
            or "\0" in value or value in (".", "..")):
        raise ValueError(f"{name} must be a file-name prefix without path separators, "
                         f"got {value!r}")
    return value


def _path(name: str, value: Any, what: str) -> Path:
    if not isinstance(value, (str, os.PathLike)) or not os.fspath(value):
        raise ValueError(f"{name} must be a {what} path, got {value!r}")
    return Path(value)


def _folders_on(name: str, value: Any, folders: Sequence[Path], what: str) -> None:
    for part in folders:
        if part.exists() and not part.is_dir():
            raise ValueError(f"{name} must be a {what}, got {value!r}: {str(part)!r} is "
                             f"a file")


def check_folder(name: str, value: Any) -> Path:
    """``Path(value)`` of a folder to write into: an existing folder or a path where one
    can be made, else ``ValueError`` (the path, or a folder on it, is an existing file;
    the value is not a path)."""
    path = _path(name, value, "folder")
    _folders_on(name, value, [path, *path.parents], "folder (existing or to be made)")
    return path


def check_file_path(name: str, value: Any) -> Path:
    """``Path(value)`` of a file to write (overwritten if it exists; missing folders are
    made), else ``ValueError`` (the path is an existing folder, a folder on it is an
    existing file, or the value is not a path)."""
    path = _path(name, value, "file")
    if path.is_dir():
        raise ValueError(f"{name} must be a file, got {value!r}: a folder")
    _folders_on(name, value, list(path.parents), "file in a folder (existing or to be "
                "made)")
    return path


#: ``I1`` values at which a user strain energy is probed on construction (from the
#: reference state to moderate stretches)
ENERGY_PROBE = np.array([3.0, 3.05, 3.2, 3.5, 4.0])


def check_energy(owner: str, funcs: dict[str, Callable], dW3: float,
                 probe: np.ndarray = ENERGY_PROBE) -> None:
    """``ValueError`` unless each of ``funcs`` (``{"W": W, "dW": dW, "d2W": d2W}``) returns
    finite numbers of the shape of ``I1`` (or a scalar) on ``probe``, and ``dW(3) = dW3``
    (the normalisation of the shear modulus, ``mu = 2 W'(3)``) to ``1e-9`` relative.

    ``owner`` names the model in the message (e.g. ``"IdealDielectric"``).
    """
    I1 = np.asarray(probe, dtype=float)
    for label, f in funcs.items():
        if not callable(f):
            raise ValueError(f"{owner}: {label} must be callable, got {f!r}")
        try:
            raw = f(I1.copy())
            if raw is None:
                raise TypeError("it returned None")
            v = np.asarray(raw, dtype=float)
        except Exception as exc:  # noqa: BLE001 - any failure of user code is reported
            raise ValueError(f"{owner}: {label}(I1) must return numbers for I1 = "
                             f"{I1.tolist()}, it raised {type(exc).__name__}: {exc}") from None
        if v.shape not in ((), I1.shape):
            raise ValueError(f"{owner}: {label}(I1) must return an array of the shape of I1 "
                             f"{I1.shape} (or a scalar), got shape {v.shape}")
        bad = ~np.isfinite(np.broadcast_to(v, I1.shape))
        if np.any(bad):
            k = int(np.argmax(bad))
            vk = float(np.broadcast_to(v, I1.shape)[k])
            raise ValueError(f"{owner}: {label}(I1) must be finite, got "
                             f"{label}({float(I1[k])!r}) = {vk!r}")
    d = float(np.broadcast_to(np.asarray(funcs["dW"](I1.copy()), dtype=float), I1.shape)[0])
    if not abs(d - dW3) <= 1e-9 * abs(dW3):
        raise ValueError(f"{owner}: dW(3) must equal {dW3!r} (normalised shear modulus, "
                         f"mu = 2 W'(3)), got {d!r}")
