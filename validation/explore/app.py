"""The ``explore`` page: four Bokeh panels of the paper's theory that follow the widgets.

:func:`build_page` draws the panels for one set of parameters and wires the widgets to
Python callbacks (server mode); :func:`export_html` writes the same panels, without the
widgets, as one HTML file with BokehJS inline.  Bokeh is the ``explore`` extra: it is
imported inside the functions, so that importing this module (the CLI does) costs nothing.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from ..figures.common import MODEL_NAME, VARIANT_MARKER
from ..markers import (ANTISYMMETRIC_MODE, CONVERGED_BUCKLING, NEWTON_LIMIT, P33_BREAKDOWN,
                       P33_ONSET_LOCATED, RUN_BUCKLING, SYMMETRIC_MODE,
                       THICK_PLATE_LIMIT, THIN_PLATE_LIMIT, VOLTAGE_LIMIT_LOCUS)
from .curves import (D0_MAX, E0_MAX, KH, LAM1_MAX, LAM_MAX, PAPER, ExploreParameters,
                     dispersion_panel, equibiaxial_panel, uniaxial_panel)
from .fe_layer import FEResults

__all__ = ["INSTALL_HINT", "PAPER_RANGES", "require_bokeh", "build_page", "export_html"]

#: What to do when Bokeh is missing (one line; the CLI exits with code 2).
INSTALL_HINT = ("the explore page needs Bokeh, the 'explore' extra: "
                "pip install -e '.[explore]' (or pip install bokeh)")
#: The axes of each panel as the paper's figure draws them: ``(x range, y range)``.
PAPER_RANGES = {"D0": ((1.0, LAM_MAX), (0.0, D0_MAX)), "E0": ((1.0, LAM_MAX), (0.0, E0_MAX)),
                "uniaxial": ((0.4, LAM1_MAX), (0.0, 7.0)),
                "dispersion": ((float(KH[0]), float(KH[-1])), (0.0, 40.0))}
_GREY = "#b0b0b0"
_BOKEH_MARKER = {"o": "circle", "s": "square", "^": "triangle", "D": "diamond"}


def require_bokeh():
    """``bokeh`` if it is installed, else ``ValueError`` with :data:`INSTALL_HINT`."""
    try:
        import bokeh
    except ImportError:
        raise ValueError(INSTALL_HINT) from None
    return bokeh


def _nan_to_none(a):
    """A float array (NaN breaks a line; Bokeh sends NaN as such in a typed array)."""
    return np.asarray(a, dtype=float)


class _Page:
    """The figures, their data sources and the widgets of one page."""

    def __init__(self, results: FEResults, p: ExploreParameters, widgets: bool):
        from bokeh.models import (Button, ColumnDataSource, CrosshairTool, Div, HoverTool,
                                  NumericInput, RadioButtonGroup, Slider)
        from bokeh.plotting import figure

        self.results, self.p = results, p
        self.src = {}

        def source(name, **cols):
            self.src[name] = ColumnDataSource(data=cols, name=name)
            return self.src[name]

        def fig(key, title, x_label, y_label, x_axis_type="linear"):
            (x0, x1), (y0, y1) = PAPER_RANGES[key]
            f = figure(title=title, x_axis_label=x_label, y_axis_label=y_label, width=560,
                       height=400, x_range=(x0, x1), y_range=(y0, y1), name=f"fig_{key}",
                       x_axis_type=x_axis_type, tools="pan,wheel_zoom,box_zoom,save")
            f.add_tools(CrosshairTool())
            return f

        def finish(f, location):
            f.legend.location = location
            f.legend.label_text_font_size = "8pt"
            f.legend.background_fill_alpha = 0.6
            f.legend.click_policy = "hide"      # a click on an entry hides its curve

        def hover(f, renderers, x, y):
            f.add_tools(HoverTool(renderers=renderers, line_policy="interp",
                                  tooltips=[("curve", "$name"), (x, "$x{0.0000}"),
                                            (y, "$y{0.0000}")]))

        def fe_glyphs(f, prefix, y="y"):
            for v, style in VARIANT_MARKER.items():
                if results.folder is None:      # no FE layer: no empty legend entries
                    source(f"{prefix}_{v}", x=[], y=[], E0=[])
                    continue
                f.scatter("x", y, source=source(f"{prefix}_{v}", x=[], y=[], E0=[]),
                          marker=_BOKEH_MARKER[style["marker"]], size=style["ms"] * 1.2,
                          fill_alpha=0.0 if style.get("mfc") == "none" else 1.0,
                          line_color="black", fill_color="black",
                          legend_label=MODEL_NAME[v])

        # --- (a), (b): equi-biaxial D0-lam and E0-lam (paper Figs. nh-d-e, gent-d-e)
        self.figs = {}
        for q, label in (("D0", "D0"), ("E0", "E0")):
            f = fig(q, f"(a) equi-biaxial: {label} vs lam" if q == "D0"
                    else "(b) equi-biaxial: E0 vs lam", "lam", label)
            f.multi_line("xs", "ys", source=source(f"eq_paper_{q}", xs=[], ys=[]),
                         color=_GREY, legend_label="the paper's s values")
            f.line("lam", "y", source=source(f"eq_locus_{q}", lam=[], y=[]), color="black",
                   line_dash=VOLTAGE_LIMIT_LOCUS.dash,
                   legend_label="det H* = 0 (voltage control limit)", name="det H* = 0")
            r1 = f.line("lam", "stable", source=source(f"eq_{q}", lam=[], stable=[],
                                                       unstable=[]),
                        color="#1f77b4", line_width=3, legend_label="stable", name="s curve")
            r2 = f.line("lam", "unstable", source=self.src[f"eq_{q}"], color="#d62728",
                        line_width=3, line_dash="dotted", legend_label="unstable",
                        name="s curve")
            f.scatter("x", "y", source=source(f"eq_max_{q}", x=[], y=[]), marker="triangle",
                      size=12, color="black", legend_label="max of E0 at fixed s")
            fe_glyphs(f, f"eq_fe_{q}")
            hover(f, [r1, r2], "lam", label)
            finish(f, "bottom_right" if q == "D0" else "top_right")
            self.figs[q] = f
        # --- (c): the Keplinger plate, uni-axial (paper Fig. uni-axial-ideal)
        f = fig("uniaxial", "(c) Keplinger plate, uni-axial: D0 vs lam1", "lam1", "D0")
        f.patch("x", "y", source=source("uni_zone", x=[], y=[]), color="#d9d9d9",
                legend_label="wrinkling zone")
        f.multi_line("xs", "ys", source=source("uni_paper", xs=[], ys=[]), color=_GREY,
                     legend_label="the paper's alpha values")
        f.line("x", "y", source=source("uni_thin", x=[], y=[]), color="black",
               line_dash=THIN_PLATE_LIMIT.dash, legend_label="thin-plate limit (s = 0)",
               name=THIN_PLATE_LIMIT.gid)
        f.line("x", "y", source=source("uni_thick", x=[], y=[]), color="#1f77b4",
               line_dash=THICK_PLATE_LIMIT.dash, legend_label="thick-plate limit",
               name=THICK_PLATE_LIMIT.gid)
        r = f.line("x", "y", source=source("uni", x=[], y=[]), color="#2ca02c", line_width=3,
                   legend_label="alpha curve", name="alpha curve")
        fe_glyphs(f, "uni_fe")
        for key, marker, size, color, name in (
                ("p33_onset", "dash", 22, "red", P33_ONSET_LOCATED.name),
                ("D0_b", "diamond", 12, "black", CONVERGED_BUCKLING.name),
                ("newton_limit", "inverted_triangle", 12, "black", NEWTON_LIMIT.name)):
            f.scatter("x", "y", source=source(f"uni_ref_{key}", x=[], y=[]), marker=marker,
                      size=size, color=color, line_width=3 if marker == "dash" else 1,
                      legend_label=name, name=f"reference-{key}")
        marks = {} if results.folder is None else {"legend_label": P33_BREAKDOWN.name}
        f.scatter("x", "y", source=source("uni_breakdown", x=[], y=[]), marker="circle",
                  size=22, fill_alpha=0.0, line_color="red", line_width=2, **marks)
        marks = {} if results.folder is None else {"legend_label": RUN_BUCKLING.name}
        f.scatter("x", "y", source=source("uni_buckling", x=[], y=[]), marker="x", size=16,
                  line_color="red", line_width=3, **marks)
        hover(f, [r], "lam1", "D0")
        finish(f, "bottom_right")
        self.figs["uniaxial"] = f
        # --- (d): the dispersion D0_c(kh) at lam (docs/wrinkling.md)
        f = fig("dispersion", "(d) wrinkling of a plate of finite thickness: D0_c vs kh",
                "kh", "D0_c", x_axis_type="log")
        ra = f.line("kh", "anti", source=source("disp", kh=[], anti=[], sym=[]),
                    color="#1f77b4", line_width=3, line_dash=ANTISYMMETRIC_MODE.dash,
                    legend_label="antisymmetric (flexural)", name="antisymmetric")
        rs = f.line("kh", "sym", source=self.src["disp"], color="#ff7f0e", line_width=3,
                    line_dash=SYMMETRIC_MODE.dash, legend_label="symmetric (extensional)",
                    name="symmetric")
        f.line("kh", "thin", source=source("disp_limits", kh=[], thin=[], thick=[]),
               color="black", line_dash=THIN_PLATE_LIMIT.dash,
               legend_label="thin-plate limit (kh -> 0)", name=THIN_PLATE_LIMIT.gid)
        f.line("kh", "thick", source=self.src["disp_limits"], color="#1f77b4",
               line_dash=THICK_PLATE_LIMIT.dash, legend_label="thick-plate limit (kh -> inf)",
               name=THICK_PLATE_LIMIT.gid)
        for mode, marker in (("antisymmetric", "circle"), ("symmetric", "square")):
            if results.folder is None:
                source(f"disp_fe_{mode}", x=[], y=[])
                continue
            f.scatter("x", "y", source=source(f"disp_fe_{mode}", x=[], y=[]), marker=marker,
                      size=12, fill_alpha=0.0, line_color="black",
                      legend_label=f"{MODEL_NAME['section']}, {mode}")
        hover(f, [ra, rs], "kh", "D0_c")
        finish(f, "top_right")
        self.figs["dispersion"] = f

        self.messages = {k: Div(text="", name=f"message_{k}", styles={"color": "#b00020"})
                         for k in ("model", "equibiaxial", "uniaxial", "dispersion")}
        self.readout = {k: Div(text="", name=f"readout_{k}")
                        for k in ("equibiaxial", "uniaxial", "dispersion")}
        self.widgets = None
        if widgets:
            w = dict(
                model=RadioButtonGroup(labels=["neo-Hookean", "Gent"], name="model",
                                       active=["neo-Hookean", "Gent"].index(p.model)),
                Jm=NumericInput(value=float(p.Jm), mode="float", title="Gent Jm", name="Jm",
                                width=120),
                control=RadioButtonGroup(labels=["charge", "voltage"], name="control",
                                         active=["charge", "voltage"].index(p.control)),
                s=Slider(start=-1.0, end=6.0, step=0.05, value=float(p.s),
                         title="equi-biaxial dead load s", name="s_slider", width=520),
                alpha=Slider(start=0.05, end=2.0, step=0.05, value=float(p.alpha),
                             title="Keplinger weight fraction alpha", name="alpha_slider",
                             width=520),
                lam=Slider(start=0.5, end=4.0, step=0.05, value=float(p.lam),
                           title="equi-biaxial stretch lam (dispersion)", name="lam_slider",
                           width=520))
            w["reset"] = {k: Button(label="reset to the paper's figure", name=f"reset_{k}",
                                    width=200) for k in PAPER_RANGES}
            self.widgets = w
            self._wire()
        self.redraw_all()

    # ------------------------------------------------------------------ widgets
    def _wire(self):
        w = self.widgets

        def setter(name, convert, panels):
            def cb(attr, old, new):
                self.p = replace(self.p, **{name: convert(new)})
                self.redraw(panels)
            return cb

        every = ("equibiaxial", "uniaxial", "dispersion")
        w["model"].on_change("active", setter("model", lambda i: ["neo-Hookean", "Gent"][i],
                                              every))
        w["Jm"].on_change("value", setter("Jm", lambda v: np.nan if v is None else float(v),
                                          every))
        w["control"].on_change("active", setter("control", lambda i: ["charge", "voltage"][i],
                                                ("equibiaxial", "dispersion")))
        w["s"].on_change("value_throttled", setter("s", float, ("equibiaxial",)))
        w["alpha"].on_change("value_throttled", setter("alpha", float, ("uniaxial",)))
        w["lam"].on_change("value_throttled", setter("lam", float, ("dispersion",)))
        slider = {"D0": "s", "E0": "s", "uniaxial": "alpha", "dispersion": "lam"}
        for key, button in w["reset"].items():
            def reset(key=key):
                (x0, x1), (y0, y1) = PAPER_RANGES[key]
                f = self.figs[key]
                f.x_range.start, f.x_range.end = x0, x1
                f.y_range.start, f.y_range.end = y0, y1
                name = slider[key]
                value = float(getattr(PAPER, name))
                w[name].value = value
                w[name].value_throttled = value  # a programmatic move fires no throttled event
            button.on_click(reset)

    def layout(self):
        """The page: widgets, panels and messages (server) or the panels alone (export)."""
        from bokeh.layouts import column, row
        from bokeh.models import Div
        head = Div(text="<b>Charge-controlled soft dielectric plates</b> (Conroy Broderick, "
                        "Righi, Destrade, Ogden, Int. J. Eng. Sci. 2020): the homogeneous "
                        "theory of the package <code>analytic</code>" +
                   (f"; FE results of <code>{self.results.folder}</code>"
                    if self.results.folder else ""), width=1140)
        f = self.figs
        if self.widgets is None:
            return column(head, row(f["D0"], f["E0"]), self.readout["equibiaxial"],
                          row(f["uniaxial"], f["dispersion"]),
                          row(self.readout["uniaxial"], self.readout["dispersion"]))
        w = self.widgets
        return column(
            head, row(w["model"], w["Jm"], w["control"]), self.messages["model"],
            w["s"], row(f["D0"], f["E0"]),
            row(w["reset"]["D0"], w["reset"]["E0"]),
            self.readout["equibiaxial"], self.messages["equibiaxial"],
            row(column(w["alpha"], f["uniaxial"], w["reset"]["uniaxial"],
                       self.readout["uniaxial"], self.messages["uniaxial"]),
                column(w["lam"], f["dispersion"], w["reset"]["dispersion"],
                       self.readout["dispersion"], self.messages["dispersion"])))

    # ------------------------------------------------------------------ drawing
    def redraw_all(self):
        self.redraw(("equibiaxial", "uniaxial", "dispersion"))

    def redraw(self, panels):
        """Recompute and redraw ``panels``; a bad parameter empties the panel and says why
        in its message line instead of raising."""
        try:
            self.p.analytic_model()
            self.messages["model"].text = ""
        except ValueError as exc:
            self.messages["model"].text = f"{exc}"
            for panel in panels:
                self._clear(panel)
            return
        for panel in panels:
            draw = {"equibiaxial": self._equibiaxial, "uniaxial": self._uniaxial,
                    "dispersion": self._dispersion}[panel]
            try:
                notes = draw()
                self.messages[panel].text = "<br>".join(notes)
            except ValueError as exc:
                self._clear(panel)
                self.messages[panel].text = " ".join(str(exc).split())[:300]

    def _clear(self, panel):
        prefix = {"equibiaxial": "eq", "uniaxial": "uni", "dispersion": "disp"}[panel]
        for name, src in self.src.items():
            if name.split("_")[0] == prefix:
                src.data = {k: [] for k in src.data}
        self.readout[panel].text = ""

    def _equibiaxial(self):
        d = equibiaxial_panel(self.p)
        fe = self.results.equibiaxial_dots(self.p)
        for q in ("D0", "E0"):
            self.src[f"eq_{q}"].data = dict(lam=d["lam"], stable=_nan_to_none(d[f"{q}_stable"]),
                                            unstable=_nan_to_none(d[f"{q}_unstable"]))
            self.src[f"eq_locus_{q}"].data = dict(lam=d["locus_lam"],
                                                  y=_nan_to_none(d[f"locus_{q}"]))
            self.src[f"eq_paper_{q}"].data = dict(
                xs=[c[1] for c in d["paper"]],
                ys=[c[2] if q == "D0" else c[3] for c in d["paper"]])
            ok = np.isfinite(d["max_lam"])
            self.src[f"eq_max_{q}"].data = dict(x=[d["max_lam"]] if ok else [],
                                                y=[d[f"max_{q}"]] if ok else [])
            for v in VARIANT_MARKER:
                x, D0, E0 = fe.get(v, (np.empty(0),) * 3)
                self.src[f"eq_fe_{q}_{v}"].data = dict(x=x, y=D0 if q == "D0" else E0, E0=E0)
        s = float(self.p.s)
        text = (f"s = {s:g}: max of E0 = <span id='E0max'>{d['max_E0']:.6f}</span> at "
                f"lam = {d['max_lam']:.6f} (D0 = {d['max_D0']:.6f})"
                if np.isfinite(d["max_lam"]) else f"s = {s:g}: no maximum of E0")
        if self.results.folder is not None:
            avail = self.results.available()["s"]
            text += (f"; FE dots: {', '.join(MODEL_NAME[v] for v in fe)}" if fe else
                     "; FE runs at s = " + ", ".join(f"{x:g}" for x in avail))
        self.readout["equibiaxial"].text = text
        return d["notes"]

    def _uniaxial(self):
        d = uniaxial_panel(self.p)
        self.src["uni"].data = dict(x=d["lam1"], y=d["D0"])
        self.src["uni_thin"].data = dict(x=d["thin_lam1"], y=_nan_to_none(d["thin_D0"]))
        self.src["uni_thick"].data = dict(x=d["thick_lam1"], y=_nan_to_none(d["thick_D0"]))
        zx, zy = d["zone"] if d["zone"] is not None else ([], [])
        self.src["uni_zone"].data = dict(x=zx, y=zy)
        self.src["uni_paper"].data = dict(xs=[c[2] for c in d["paper"]],
                                          ys=[c[3] for c in d["paper"]])
        marks = self.results.keplinger_marks(self.p)
        for v in VARIANT_MARKER:
            x, y = marks[v].dots if v in marks else ([], [])
            self.src[f"uni_fe_{v}"].data = dict(x=x, y=y, E0=[np.nan] * len(x))
        brk = [m.breakdown for m in marks.values() if m.breakdown is not None]
        bk = [m.buckling for m in marks.values() if m.buckling is not None]
        self.src["uni_breakdown"].data = dict(x=[b[0] for b in brk], y=[b[1] for b in brk])
        self.src["uni_buckling"].data = dict(x=[b[0] for b in bk], y=[b[1] for b in bk])
        for key in ("p33_onset", "D0_b", "newton_limit"):
            pt = d["reference"].get(key)
            self.src[f"uni_ref_{key}"].data = dict(x=[pt[0]] if pt else [],
                                                   y=[pt[1]] if pt else [])
        text = f"alpha = {float(self.p.alpha):g}: s = {d['s']:.6f}"
        if d["reference"]:
            text += "; the converged study: " + ", ".join(
                f"{n} {d['reference'][k][1]:.4g}" for k, n in (
                    ("p33_onset", "P33 onset"), ("D0_b", "D0_b"),
                    ("newton_limit", "Newton limit")) if k in d["reference"])
        if bk:
            text += f"; {RUN_BUCKLING.name} D0_b = {bk[0][1]:.4f}"
        if brk:
            text += f"; {P33_BREAKDOWN.name} at D0 = " + ", ".join(f"{b[1]:g}" for b in brk)
        if self.results.folder is not None and not marks:
            text += "; FE runs at alpha = " + ", ".join(
                f"{x:g}" for x in self.results.available()["alpha"])
        self.readout["uniaxial"].text = text
        return d["notes"]

    def _dispersion(self):
        d = dispersion_panel(self.p)
        self.src["disp"].data = dict(kh=d["kh"], anti=_nan_to_none(d["antisymmetric"]),
                                     sym=_nan_to_none(d["symmetric"]))
        ends = [float(KH[0]), float(KH[-1])]
        self.src["disp_limits"].data = dict(kh=ends, thin=_nan_to_none([d["thin"]] * 2),
                                            thick=_nan_to_none([d["thick"]] * 2))
        fe = self.results.dispersion_dots(self.p)
        for mode in ("antisymmetric", "symmetric"):
            x, y = fe.get(mode, ([], []))
            self.src[f"disp_fe_{mode}"].data = dict(x=x, y=y)
        self.readout["dispersion"].text = (
            f"lam = {float(self.p.lam):g}, {self.p.control} control: thin-plate limit "
            f"D0 = {d['thin']:.6f}, thick-plate limit D0 = {d['thick']:.6f}")
        return d["notes"]


def build_page(doc, results: FEResults | None = None, p: ExploreParameters = PAPER):
    """Fill the Bokeh document ``doc`` with the page (the server's session handler).

    Parameters
    ----------
    doc : bokeh.document.Document
    results : FEResults, optional
        The FE layer (:func:`~validation.explore.fe_layer.load_results`).
    p : ExploreParameters
        The parameters the page opens with (the paper's figures).

    Returns
    -------
    _Page
        The page's figures, data sources and widgets.
    """
    page = _Page(results or FEResults(), p, widgets=True)
    doc.add_root(page.layout())
    doc.title = "skfem-dielectric explore"
    return page


def export_html(path, results: FEResults | None = None, p: ExploreParameters = PAPER) -> Path:
    """Write the four panels at the parameters ``p`` as one HTML file with BokehJS inline
    (no network needed to view it; hover and zoom work, the widgets need the server).

    Returns
    -------
    Path
    """
    require_bokeh()
    from bokeh.embed import file_html
    from bokeh.resources import INLINE
    page = _Page(results or FEResults(), p, widgets=False)
    path = Path(path)
    path.write_text(file_html(page.layout(), INLINE, title="skfem-dielectric explore"))
    return path
