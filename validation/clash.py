"""Detect that another distribution's ``analytic`` or ``skfem_dielectric`` shadows ours.

The names of our import packages are generic: the PyPI distributions ``analytic``
and ``validation`` install top-level packages of the same names, and when one of them
is installed after skfem-dielectric it overwrites ours (a regular install) or comes first
on ``sys.path`` (an editable install). The symptoms would be puzzling attribute errors
deep inside a sweep; :func:`check_packages` instead stops at ``import validation`` with
a message naming the conflicting distribution and the fix.

The check is cheap (no import, one ``find_spec`` and, for a regular install, the hash of
one ``__init__.py`` per package); it runs once when :mod:`validation` is imported.
"""

from __future__ import annotations

import base64
import hashlib
import importlib.metadata as md
import importlib.util
from pathlib import Path

__all__ = ["PackageClash", "DISTRIBUTION", "PACKAGES", "find_clashes", "check_packages"]

#: Our distribution and its three import packages.
DISTRIBUTION = "skfem-dielectric"
PACKAGES = ("analytic", "skfem_dielectric", "validation")

_ROOT = Path(__file__).resolve().parent.parent    # the folder holding our three packages


class PackageClash(ImportError):
    """An import package of skfem-dielectric is provided by another distribution."""


def _record_hashes() -> dict[str, str]:
    """``{"analytic/__init__.py": "sha256=..."}`` from our RECORD (empty if not installed,
    or for an editable install, whose RECORD lists no package files)."""
    try:
        files = md.distribution(DISTRIBUTION).files or []
    except md.PackageNotFoundError:
        return {}
    return {str(f.as_posix()): f"{f.hash.mode}={f.hash.value}" for f in files
            if f.hash is not None and f.name == "__init__.py"}


def _file_hash(path: Path, mode: str) -> str:
    digest = hashlib.new(mode, path.read_bytes()).digest()
    return f"{mode}=" + base64.urlsafe_b64encode(digest).rstrip(b"=").decode()


def _owners(name: str, origin: Path | None) -> list[str]:
    """``"dist version"`` of the other distributions that install package ``name``."""
    owners = []
    for dist in md.distributions():
        dname = dist.metadata["Name"] or ""
        if dname.lower().replace("_", "-") == DISTRIBUTION:
            continue
        top = (dist.read_text("top_level.txt") or "").split()
        files = [str(f.as_posix()) for f in (dist.files or [])]
        located = origin is not None and any(
            f == f"{name}/__init__.py" and Path(dist.locate_file(f)).resolve() == origin
            for f in files)
        if located or name in top or f"{name}/__init__.py" in files:
            owners.append(f"{dname} {dist.version}")
    return sorted(set(owners))


def find_clashes() -> list[str]:
    """Messages for every package of :data:`PACKAGES` that is not ours (empty list: none).

    A package is ours when its ``__init__.py`` lies next to this module's package and,
    for a regular (non-editable) install, has the hash our installation recorded.
    """
    hashes = _record_hashes()
    problems = []
    for name in PACKAGES:
        spec = importlib.util.find_spec(name)
        origin = Path(spec.origin).resolve() if spec is not None and spec.origin else None
        if origin is not None and origin.parent.parent == _ROOT:
            recorded = hashes.get(f"{name}/__init__.py")
            mode = recorded.split("=", 1)[0] if recorded else ""
            if not recorded or _file_hash(origin, mode) == recorded:
                continue
        owners = _owners(name, origin)
        who = " or ".join(repr(o) for o in owners) if owners else "an unknown distribution"
        problems.append(f"the import package {name!r} at {origin or 'nowhere'} is not the "
                        f"one of {DISTRIBUTION} (expected under {_ROOT}); it comes from "
                        f"{who}")
    return problems


def check_packages() -> None:
    """Raise :class:`PackageClash` if another distribution shadows one of our packages.

    Raises
    ------
    PackageClash
        Naming the conflicting distribution(s) and the fix: install skfem-dielectric in
        its own virtual environment (or uninstall the other distribution and reinstall
        skfem-dielectric).
    """
    problems = find_clashes()
    if problems:
        raise PackageClash(
            f"{DISTRIBUTION} cannot run: " + "; ".join(problems) + ". Fix: install "
            f"{DISTRIBUTION} in its own virtual environment "
            "(python3 -m venv .venv && . .venv/bin/activate && pip install -e .), or "
            "uninstall the other distribution and reinstall skfem-dielectric.")
