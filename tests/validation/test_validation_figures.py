"""Figure helpers: the curves they draw satisfy the paper's closed forms; plots return axes."""

from __future__ import annotations

import numpy as np
import pytest

from validation.figures import (case_figure, plot_equibiaxial_loading, uniaxial_thick_limit_curve,
                                uniaxial_voltage_locus)


def test_uniaxial_thick_limit_curve_solves_the_paper_polynomial():
    lam1 = np.linspace(0.5, 3.0, 26)
    D0 = uniaxial_thick_limit_curve(lam1)
    ok = np.isfinite(D0)
    assert ok.sum() >= 24
    lam3 = ((1 + D0[ok] ** 2) / lam1[ok] ** 2) ** 0.25            # Eq. (uni-axial-loading)_2
    l1 = lam1[ok]
    # Eq. (thick-uni-axial), printed in the paper; scaled by D0^4 + const it is O(1):
    # the bisection runs to machine precision in lam3, so 1e-9 relative
    poly = (D0[ok] ** 4 - (l1**4 * lam3**2 + 3 * l1**2 * lam3 - 2) * D0[ok] ** 2
            - (l1**6 * lam3**3 + l1**4 * lam3**2 + 3 * l1**2 * lam3 - 1))
    scale = D0[ok] ** 4 + l1**6 * lam3**3 + 1
    assert np.max(np.abs(poly) / scale) < 1e-9
    # D0 -> 0 at Biot's uni-axial surface instability lam1 = 0.444 (paper Sec. 5)
    assert np.isnan(uniaxial_thick_limit_curve(np.array([0.44]))[0])
    assert uniaxial_thick_limit_curve(np.array([0.4440]))[0] < 0.05



def test_gent_uniaxial_thick_limit_curve_lies_on_the_gent_path_and_the_limit():
    """For Gent the point solves both the uni-axial path D0^2 = 2W'(I1)(lam1^2 lam3^4 - 1)
    and the thick-plate limit; lam3 is found here independently by brentq on the path."""
    from scipy.optimize import brentq

    import analytic as an
    gent = an.Gent(Jm=97.2)
    lam1 = np.array([0.8, 1.5, 2.5, 4.0])
    D0 = uniaxial_thick_limit_curve(lam1, gent)
    assert np.isfinite(D0).all()
    for l1, d in zip(lam1, D0):
        def path(l3):
            I1 = l1**2 + l3**2 + 1 / (l1 * l3) ** 2
            return 2 * float(gent.dW(I1)) * (l1**2 * l3**4 - 1) - d**2
        b = 100.2 - l1**2                   # lam3^2 where I1 = 3 + Jm (locking)
        top = np.sqrt(0.5 * (b + np.sqrt(b**2 - 4 / l1**2))) * (1 - 1e-12)
        l3 = brentq(path, l1**-0.5, top, xtol=1e-15)
        # both sides are smooth in lam3 and the bisection runs to machine precision in lam3:
        # 1e-8 relative leaves room for the conditioning of the path near the locking
        assert abs(float(an.thick_limit_D0_uniaxial(l1, l3, gent)) - d) < 1e-8 * d
    # the Gent plate stiffens: its limit lies above the neo-Hookean one at every lam1
    assert (D0 > uniaxial_thick_limit_curve(lam1)).all()

def test_uniaxial_voltage_locus_is_det_H_star_zero():
    lam1, D0, E0 = uniaxial_voltage_locus("neo-Hookean", s=np.linspace(0.0, 4.0, 9))
    lam3 = ((1 + D0**2) / lam1**2) ** 0.25
    # paper Sec. 5: det H* = 4 lam1^-6 lam3^-6 (3 lam3^2 + lam1^2 - lam1^2 lam3^6) = 0
    detH = 3 * lam3**2 + lam1**2 - lam1**2 * lam3**6
    np.testing.assert_allclose(detH / (lam1**2 * lam3**6), 0.0, atol=1e-7)  # max_E0 is an
    # optimiser: E0 is flat at its maximum, lam1 is known to ~1e-8 relative
    # and E0 = sqrt(lam1^-2 - lam1^-4 lam3^-4) on the path (Eq. uni-axial-loading_3)
    np.testing.assert_allclose(E0, np.sqrt(lam1**-2 - lam1**-4 * lam3**-4), rtol=1e-8)


def test_plots_return_axes_and_validate_args():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    assert plot_equibiaxial_loading("Gent", (0, 1), "E0", ax=ax) is ax
    # the s = 0 neo-Hookean maximum of E0 is drawn at (2^(1/3), sqrt(3)/2^(4/3))
    fig2, ax2 = plt.subplots()
    plot_equibiaxial_loading("neo-Hookean", (0,), "E0", ax=ax2)
    tri = [ln for ln in ax2.lines if ln.get_marker() == "^"][0]
    np.testing.assert_allclose(tri.get_xydata()[0], [2 ** (1 / 3), np.sqrt(3) / 2 ** (4 / 3)],
                               rtol=1e-7)
    with pytest.raises(ValueError, match="quantity"):
        plot_equibiaxial_loading(quantity="P33", ax=ax)
    with pytest.raises(ValueError, match="needs FE fields"):
        case_figure("zs22")
    plt.close("all")


def test_figde_legend_says_which_panel_has_s_4():
    """Paper Fig. figde: (a) has s = 0 ... 4, (b) s = 0 ... 3 (the paper's caption); the
    shared legend's s = 4 entry says so, and (b) draws no fifth curve."""
    import matplotlib.pyplot as plt

    fig = case_figure("figde")
    texts = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    assert "$s = 4$ ((a) only, as in the paper)" in texts and "$s = 4$" not in texts
    b = fig.axes[1]
    assert sum(ln.get_label().startswith("$s = ") for ln in b.lines) == 4
    plt.close(fig)
