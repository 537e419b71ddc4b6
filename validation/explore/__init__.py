"""``skfem-dielectric explore``: the paper's theory live in a browser.

Four panels follow the widgets (model, Gent ``Jm``, control, ``s``, ``alpha``, ``lam``):
the equi-biaxial loading curves ``D0(lam)`` and ``E0(lam)`` with the ``det H* = 0`` locus
and the maximum of ``E0`` (paper Figs. nh-d-e, gent-d-e), the Keplinger plate's uni-axial
curve with the thin- and thick-plate wrinkling limits (Fig. uni-axial-ideal), and the
critical charge ``D0_c(kh)`` of both mode families at a chosen stretch (docs/wrinkling.md);
with a ``validate`` folder, the FE dots and the ``P33``/buckling markers on top.  The curves
come from :mod:`analytic` alone (:mod:`.curves`), the FE layer from the folder's CSVs
(:mod:`.fe_layer`); the page (:mod:`.app`) and its server (:mod:`.server`) need Bokeh, the
``explore`` extra, imported only when a page is built.
"""

from .app import INSTALL_HINT, PAPER_RANGES, build_page, export_html, require_bokeh
from .curves import (PAPER, ExploreParameters, dispersion_panel, equibiaxial_panel,
                     uniaxial_panel)
from .fe_layer import FEResults, load_results
from .server import free_port, local_hosts, make_server

__all__ = ["ExploreParameters", "PAPER", "equibiaxial_panel", "uniaxial_panel",
           "dispersion_panel", "FEResults", "load_results", "INSTALL_HINT", "PAPER_RANGES",
           "require_bokeh", "build_page", "export_html", "free_port", "local_hosts",
           "make_server"]
