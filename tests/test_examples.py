"""Run every gallery script ``docs/examples/ex*.py`` top to bottom and pin one number.

Like scikit-fem's tests/test_examples.py: the examples are documentation, so they must
run; plotting sits under ``if __name__ == "__main__":`` and is executed too (Agg
backend, in a temporary working directory so that nothing lands in the repository).
"""

from __future__ import annotations

import runpy
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "docs" / "examples").glob("ex*.py"))

# name of the script -> (global variable, reference value, rtol, why this reference)
PINNED: dict[str, tuple[str, float, float, str]] = {}


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(path, tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    ns = runpy.run_path(str(path), run_name="__main__")
    plt.close("all")
    if path.stem in PINNED:
        name, ref, rtol, _why = PINNED[path.stem]
        assert np.asarray(ns[name], dtype=float) == pytest.approx(ref, rel=rtol)
