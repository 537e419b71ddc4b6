"""The Sphinx site builds with ``-W`` (warnings are errors).

The default test parses every page, docstring and gallery script without running the
examples (``SKFEM_DOCS_NO_GALLERY=1``; ``tests/docs/test_examples.py`` runs them); the slow
test is the documented command, examples included. Both build a copy of ``docs/`` in a
temporary folder, so nothing is generated inside the repository.
"""

from __future__ import annotations

import importlib
import inspect
import os
import pkgutil
import posixpath
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx")
pytest.importorskip("sphinx_gallery")

ROOT = Path(__file__).resolve().parents[2]
_GENERATED_PATTERNS = shutil.ignore_patterns("_build", "auto_examples", "generated", "*.png",
                                             "sg_execution_times.rst", "__pycache__")
#: images committed with the docs (the others are written by the examples)
_COMMITTED = {"explore.png"}


def _GENERATED(folder, names):
    return set(_GENERATED_PATTERNS(folder, names)) - _COMMITTED


def _build(tmp_path: Path, run_examples: bool) -> Path:
    src, out = tmp_path / "docs", tmp_path / "html"
    shutil.copytree(ROOT / "docs", src, ignore=_GENERATED)
    env = dict(os.environ, MPLBACKEND="Agg")
    env.pop("SKFEM_DOCS_NO_GALLERY", None)
    if not run_examples:
        env["SKFEM_DOCS_NO_GALLERY"] = "1"
    r = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                        "html", str(src), str(out)], capture_output=True, text=True, env=env,
                       cwd=tmp_path, timeout=900)
    assert r.returncode == 0, r.stderr[-3000:]
    return out


def _check_site(out: Path):
    for page in ("index.html", "theory.html", "api.html", "auto_examples/index.html",
                 "api/generated/analytic.html",
                 "api/generated/skfem_dielectric.models.plate.problem.html",
                 "api/generated/validation.clash.html"):
        assert (out / page).exists(), page
    index = " ".join((out / "index.html").read_text().split())
    assert "Stability analysis of charge-controlled soft dielectric" in index
    gallery = (out / "auto_examples" / "index.html").read_text()
    for p in sorted((ROOT / "docs" / "examples").glob("ex*.py")):
        assert f"{p.stem}.html" in gallery, p.stem


def _public_modules(package: str):
    """The package and every module of it whose dotted name has no ``_`` part."""
    pkg = importlib.import_module(package)
    yield pkg
    for info in pkgutil.walk_packages(pkg.__path__, package + "."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            yield importlib.import_module(info.name)


def _check_inventory(out: Path):
    """Every public module, and every class and function in the ``__all__`` of a package
    or public module, is an object of the site's inventory (``objects.inv``, what
    cross-references and intersphinx resolve), under the module that defines it."""
    from sphinx.util.inventory import InventoryFile

    with open(out / "objects.inv", "rb") as f:
        inventory = InventoryFile.load(f, "", posixpath.join)
    documented = {name for role, objs in inventory.items() if role.startswith("py:")
                  for name in objs}
    missing, checked = [], 0
    for package in ("analytic", "skfem_dielectric", "validation"):
        for module in _public_modules(package):
            if module.__name__ not in documented:
                missing.append(module.__name__)
            for name in getattr(module, "__all__", ()):
                obj = getattr(module, name)
                if inspect.isclass(obj) or inspect.isfunction(obj):
                    checked += 1
                    if f"{obj.__module__}.{obj.__qualname__}" not in documented:
                        missing.append(f"{module.__name__}.{name}")
    # a module that shares its name with a function of its package (skfem_dielectric.solvers.ramp)
    # was documented as that function, without its classes: the case this test guards
    assert "skfem_dielectric.solvers.ramp.RampResult" in documented
    assert checked > 300, checked          # the walk saw the packages, not an empty list
    assert not missing, missing


def test_sphinx_build_warnings_are_errors(tmp_path):
    out = _build(tmp_path, run_examples=False)
    _check_site(out)
    _check_inventory(out)


@pytest.mark.slow
def test_sphinx_build_with_gallery(tmp_path):
    out = _build(tmp_path, run_examples=True)
    _check_site(out)
    thumbs = list((out / "_images").glob("sphx_glr_ex*_thumb.png"))
    assert len(thumbs) == len(list((ROOT / "docs" / "examples").glob("ex*.py")))
    assert list((out / "_downloads").rglob("*.ipynb"))
