"""Redraw cost of the ``explore`` page per slider move: CPU seconds of the analytic panels.

Each move recomputes the panel its slider drives (``s``: the two equi-biaxial panels,
``alpha``: the uni-axial panel, ``lam``: the dispersion panel) and, with Bokeh installed,
fills the page's data sources as the server does.  Target: at most 0.1 s per move.

Usage::

    python benchmarks/explore_redraw.py
    python benchmarks/explore_redraw.py --smoke    # one timed move per slider
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from validation.explore import ExploreParameters, FEResults, equibiaxial_panel, \
    dispersion_panel, uniaxial_panel

TARGET = 0.1


def _cpu(fn, values):
    fn(values[0])                                   # the model's curves are cached once
    t0 = time.process_time()
    for v in values[1:]:
        fn(v)
    return (time.process_time() - t0) / (len(values) - 1)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--smoke", action="store_true",
                    help="one timed move per slider (a check that the script runs, not a "
                         "measurement)")
    a = ap.parse_args(argv)
    moves = {
        "s (equi-biaxial panels)": (lambda v: equibiaxial_panel(ExploreParameters(s=v)),
                                    np.linspace(0.0, 3.0, 31)),
        "s, Gent": (lambda v: equibiaxial_panel(ExploreParameters(model="Gent", s=v)),
                    np.linspace(0.0, 3.0, 31)),
        "alpha (uni-axial panel)": (lambda v: uniaxial_panel(ExploreParameters(alpha=v)),
                                    np.linspace(0.05, 1.5, 30)),
        "lam (dispersion panel)": (lambda v: dispersion_panel(ExploreParameters(lam=v)),
                                   np.linspace(1.0, 3.0, 11)),
    }
    try:
        from bokeh.document import Document

        from validation.explore.app import build_page
        page = build_page(Document(), FEResults())
        moves["s, page update (Bokeh sources)"] = (
            lambda v: (setattr(page, "p", ExploreParameters(s=v)),
                       page.redraw(("equibiaxial",))), np.linspace(0.0, 3.0, 31))
        moves["lam, page update (Bokeh sources)"] = (
            lambda v: (setattr(page, "p", ExploreParameters(lam=v)),
                       page.redraw(("dispersion",))), np.linspace(1.0, 3.0, 11))
    except ImportError:
        print("bokeh not installed: the page updates are not timed")
    for name, (fn, values) in moves.items():
        cpu = _cpu(fn, values[:2] if a.smoke else values)
        print(f"{name:36s} {cpu:.4f} CPU s per move "
              f"({'within' if cpu <= TARGET else 'above'} the {TARGET:g} s target)")


if __name__ == "__main__":
    main()
