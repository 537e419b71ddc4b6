"""The paper's figures: analytic curves from :mod:`analytic` with the FE dots on top.

One module per paper figure (:mod:`.equibiaxial_loading`: Figs. 1 and 2,
:mod:`.equibiaxial_wrinkling`: Fig. 3, :mod:`.uniaxial_loading`: Fig. 4,
:mod:`.uniaxial_wrinkling`: Fig. 5 (and :mod:`.breakdown_map`: its breakdown loads per weight), :mod:`.stretch_maps`: Fig. 6, :mod:`.p33_profiles`:
Fig. 7), the drawing they share (:mod:`.common`: markers, model names, caption line,
:func:`save_figure`) and the figure of each case with its caption (:mod:`.case`).
"""

from .breakdown_map import breakdown_map_figure, homogeneous_wrinkling_D0, plot_breakdown_map
from .case import case_figure, figure_caption
from .common import (BREAKDOWN_NAME, BUCKLING_NAME, LIMIT_NAME, MODEL_NAME, NEWTON_NAME,
                     PAPER_FIGURE,
                     add_caption, mesh_caption, plate_mesh_text, run_caption, save_figure,
                     tag_panels)
from .equibiaxial_loading import plot_equibiaxial_loading
from .equibiaxial_wrinkling import plot_equibiaxial_wrinkling
from .p33_profiles import plot_p33_profiles
from .stretch_maps import plot_stretch_maps
from .uniaxial_loading import plot_uniaxial_loading, uniaxial_voltage_locus
from .uniaxial_wrinkling import (RunMarks, keplinger_run_marks, plot_uniaxial_wrinkling,
                                 uniaxial_thick_limit_curve)

__all__ = [
    "plot_equibiaxial_loading",
    "plot_equibiaxial_wrinkling",
    "plot_uniaxial_loading",
    "plot_uniaxial_wrinkling",
    "plot_stretch_maps",
    "plot_p33_profiles",
    "plot_breakdown_map",
    "breakdown_map_figure",
    "homogeneous_wrinkling_D0",
    "uniaxial_thick_limit_curve",
    "keplinger_run_marks",
    "RunMarks",
    "uniaxial_voltage_locus",
    "case_figure",
    "figure_caption",
    "run_caption",
    "mesh_caption",
    "plate_mesh_text",
    "add_caption",
    "tag_panels",
    "save_figure",
    "PAPER_FIGURE",
    "MODEL_NAME",
    "BREAKDOWN_NAME",
    "BUCKLING_NAME",
    "NEWTON_NAME",
    "LIMIT_NAME",
]
