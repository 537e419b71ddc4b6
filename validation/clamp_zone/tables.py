"""The clamp-zone study as Markdown tables, from its tables alone
(``skfem-dielectric clamp-zone tables``; docs/clamp-zone.md shows the shipped ones)."""

from __future__ import annotations

import math

from ..data.clamp_zone import clamp_unit_load, clamp_voltage_limit, plain_p33_row
from ..data.registry import table_file
from ..specs import LOCATION_TOL
from ..data.registry import load as load_table

__all__ = ["clamp_study_tables", "breakdown_numbers", "breakdown_table", "voltage_table"]


def _file(where, name: str):
    return None if where is None else table_file(name, where)


def clamp_study_tables(where=None) -> str:
    """The clamp-zone study as four Markdown tables, from the data files alone
    (``skfem-dielectric clamp-zone tables``).

    The first has a row per unit (``formulation``, weight, mesh, grading; by weight and
    unknowns); the second a row per weight: the load of :func:`clamp_unit_load` (or why
    there is none), and the plain form's located ``P33`` onsets and Newton limit on the
    finest graded mesh of the ``p33`` table for the weight; the third a row per located
    class of the ``onsets`` table; the fourth a row per unit of the ``layer`` table.

    Parameters
    ----------
    where : path-like, optional
        A folder of the study's tables (a run's ``--out``); default: the shipped tables.

    Returns
    -------
    str
    """
    rows = [r for r in load_table("units", where) if r["D0_b"]]
    rows.sort(key=lambda r: (float(r["alpha"]), r["formulation"] != "mixed", r["formulation"],
                             int(r["dofs"])))
    out = ["| alpha | mesh (grading) | formulation | unknowns | half-waves | elements per "
           "half-wave | `D0_b` | `J` at the clamp | flagged at `D0_b` | CPU s (solver) |",
           "| --- " * 10 + "|"]
    for r in rows:
        out.append(f"| {float(r['alpha']):g} | {r['mesh']} ({r['grading']}) | "
                   f"{r['formulation']} | {int(r['dofs'])} | {r['half_waves']} | "
                   f"{float(r['elements_per_half_wave']):.1f} | {float(r['D0_b']):.4f} | "
                   f"{float(r['J_min_clamp']):.2f}-{float(r['J_max_clamp']):.2f} | "
                   f"{r['n_flagged_b']} | {r['cpu_s']} ({r['solver']}) |")
    out += ["", "| alpha | `D0_b` (two finest meshes, spread) | `P33` onset: centre line / "
            "clamp line / interior (mesh) | Newton limit, plain form |", "| --- " * 4 + "|"]
    for a in sorted({float(r["alpha"]) for r in rows}):
        try:
            g = clamp_unit_load(a, path=_file(where, "units"),
                                classes_path=_file(where, "onsets"))
            load = (f"**{g['D0_b']:.4f}** ({g['meshes'][0]}, {g['meshes'][1]}; "
                    f"{g['spread']:.4f})")
            if g["tied"]:
                load += (f"; `{g['class']}`, {g['half_waves']} half-waves on both, tied "
                         f"with " + ", ".join(f"`{c}` ({n})" for c, n in g["tied"].items()
                                              if c != g["class"]))
        except ValueError as exc:
            load = "none: " + str(exc).split(";")[0]
        r = plain_p33_row(a, _file(where, "p33"))
        if r is not None:
            def cell(k):
                name = k.removeprefix("P33_onset_")
                if not r[k]:
                    return "none"
                if f"{name}: below at the first target" in r["note"]:
                    return f"<= {float(r[k]):g} (below from the first step)"
                return f"{float(r[k]):.4f}"

            on = " / ".join(cell(k) for k in ("P33_onset_centre_line", "P33_onset_clamp",
                                               "P33_onset_interior"))
            onset, newton = (f"{on} ({r['mesh']} ({r['grading']}))",
                             r["newton_limit"] or f"none up to {float(r['D0_max']):g}")
        else:
            onset, newton = "not run", "not run"
        out.append(f"| {a:g} | {load} | {onset} | {newton} |")
    classes = [r for r in load_table("onsets", where) if r["D0_c"]]
    classes.sort(key=lambda r: (float(r["alpha"]), int(r["dofs"]), r["class"]))
    out += ["", "| alpha | mesh (grading) | class | half-waves | elements per half-wave | "
            "`D0_c` | bracket |", "| --- " * 7 + "|"]
    for r in classes:
        out.append(f"| {float(r['alpha']):g} | {r['mesh']} ({r['grading']}) | "
                   f"`{r['class']}` | {r['half_waves']} | "
                   f"{float(r['elements_per_half_wave']):.1f} | {float(r['D0_c']):.5f} | "
                   f"{r['lo']}-{r['hi']} |")
    layer = load_table("layer", where)
    layer.sort(key=lambda r: (float(r["alpha"]), int(r["dofs"])))
    out += ["", "| alpha | mesh (grading) | `D0` | mean `J`, first / second element layer | "
            "`J` at the first layer's centres | volume ratio, layer 0.5 / 1 / 2 mm | "
            "whole model |", "| --- " * 7 + "|"]
    for r in layer:
        f = {k: float(v) for k, v in r.items() if k.startswith(("J_", "V_"))}
        out.append(f"| {float(r['alpha']):g} | {r['mesh']} ({r['grading']}) | "
                   f"{float(r['D0']):.4f} | {f['J_first_min']:.3f}-{f['J_first_max']:.3f} / "
                   f"{f['J_second_min']:.3f}-{f['J_second_max']:.3f} | "
                   f"{f['J_centre_min']:.3f}-{f['J_centre_max']:.3f} | "
                   f"{f['V_0.5mm']:.4f} / {f['V_1mm']:.4f} / {f['V_2mm']:.4f} | "
                   f"{f['V_plate']:.6f} |")
    return "\n".join(out) + "\n"


def breakdown_numbers(where=None) -> list[dict]:
    """The three meanings of "breakdown" per weight, each located and with its mesh: the
    plain form's ``P33`` onsets on the finest graded mesh of the ``p33`` table, the
    converged buckling load of :func:`~validation.data.clamp_zone.clamp_unit_load` and the
    plain form's Newton limit on that ``P33`` mesh.

    Parameters
    ----------
    where : path-like, optional
        A folder of the study's tables; default: the shipped tables.

    Returns
    -------
    list of dict
        One per weight with a converged load and a graded ``P33`` row, in increasing
        ``alpha``: ``alpha``, ``centre``, ``interior`` (the onsets), ``p33_mesh``,
        ``D0_b``, ``error`` (the two meshes' spread, at least the location tolerance),
        ``meshes``, ``newton_limit`` (``nan``: none up to ``D0_max``), ``D0_max``, and
        ``voltage``: the converged voltage-controlled limit of the weight
        (:func:`~validation.data.clamp_zone.clamp_voltage_limit`), ``None`` where the
        ``voltage`` table has no two agreeing meshes.
    """
    out = []
    for a in sorted({float(r["alpha"]) for r in load_table("p33", where)}):
        r = plain_p33_row(a, _file(where, "p33"))
        try:
            g = clamp_unit_load(a, path=_file(where, "units"),
                                classes_path=_file(where, "onsets"))
        except ValueError:
            continue
        if not r["P33_onset_interior"]:
            continue
        out.append({"alpha": a, "centre": float(r["P33_onset_centre_line"]),
                    "interior": float(r["P33_onset_interior"]),
                    "p33_mesh": f"{r['mesh']} g{r['grading']}", "D0_b": g["D0_b"],
                    "error": max(g["spread"], LOCATION_TOL),
                    "meshes": tuple(f"{m} g{g['rows'][-2 + i]['grading']}"
                                    for i, m in enumerate(g["meshes"])),
                    "newton_limit": float(r["newton_limit"] or "nan"),
                    "D0_max": float(r["D0_max"]), "voltage": _voltage(a, where)})
    return out


def _voltage(alpha: float, where) -> dict | None:
    try:
        return clamp_voltage_limit(alpha, path=_file(where, "voltage"))
    except ValueError:
        return None


def breakdown_table(where=None) -> str:
    """:func:`breakdown_numbers` as a Markdown table (docs/breakdown.md shows it, generated
    by ``skfem-dielectric clamp-zone tables --breakdown``): the three meanings of breakdown
    under charge control, and the same plate under voltage control where the ``voltage``
    table has two agreeing meshes (its snap-through charge at the centre with the two
    meshes' difference, the bracket of its first physical mode, and ``D0_b`` over the
    snap-through charge).

    Returns
    -------
    str
    """
    lines = ["| alpha | `P33` onset, centre line / interior (plain form) | `D0_b` (grad-div "
             "form) | `D0_b` minus the interior onset | Newton limit, plain form | meshes "
             "(graded): `P33` and Newton limit / `D0_b` | voltage control: snap-through "
             "`D0` (`E0` / `max_E0`); first physical mode between | `D0_b` / snap-through "
             "`D0` |", "| --- " * 8 + "|"]
    for n in breakdown_numbers(where):
        newton = (f"{n['newton_limit']:g}" if math.isfinite(n["newton_limit"])
                  else f"none up to {n['D0_max']:g}")
        v = n["voltage"]
        if v is None:
            volt, ratio = "not computed on two agreeing meshes", ""
        else:
            first = (f"{v['D0_stable']:.2f}-{v['D0_physical']:.2f}"
                     if math.isfinite(v["D0_physical"]) else "none before it")
            volt = (f"{v['D0_limit']:.4f} +- {max(v['D0_spread'], 1e-4):.4f} "
                    f"({v['ratio']:.4f}); "
                    f"{first} ({', '.join(v['meshes'])})")
            r = n["D0_b"] / v["D0_limit"]
            err = r * (n["error"] / n["D0_b"] + v["D0_spread"] / v["D0_limit"])
            ratio = f"{r:.4f} +- {max(err, 1e-4):.4f}"
        lines.append(f"| {n['alpha']:g} | {n['centre']:.4f} / {n['interior']:.4f} | "
                     f"{n['D0_b']:.4f} +- {n['error']:.4f} | "
                     f"{n['D0_b'] - n['interior']:.3f} | {newton} | {n['p33_mesh']} / "
                     f"{', '.join(n['meshes'])} | {volt} | {ratio} |")
    return "\n".join(lines) + "\n"


def voltage_table(where=None) -> str:
    """The ``voltage`` table as Markdown, a row per unit (by weight, grad-div and unknowns):
    the limit field against the homogeneous ``max_E0`` and the clamped membrane's, the
    charge at the centre at the limit, the bracket of the first physical mode, the first
    new negative mode with where its energy sits, ``J`` at the limit and the costs
    (``skfem-dielectric clamp-zone tables --voltage``; docs/clamp-zone.md shows it).

    Parameters
    ----------
    where : path-like, optional
        A folder of the study's tables; default: the shipped tables.

    Returns
    -------
    str
    """
    rows = [r for r in load_table("voltage", where) if r["E0_limit"]]
    rows.sort(key=lambda r: (float(r["alpha"]), -float(r["grad_div"]), int(r["dofs"])))
    out = ["| alpha | mesh (grading) | grad-div | unknowns | `E0` limit | / `max_E0` | "
           "membrane's limit | `D0` at the limit | first physical mode between `D0` | "
           "first new negative mode: `E0`, kind, class, centroid `X1` (layer) | `J` at the "
           "limit | CPU s, GB |", "| --- " * 12 + "|"]
    for r in rows:
        phys = (f"{float(r['D0_stable']):.3f}-{float(r['D0_physical']):.3f}"
                if r["D0_physical"] and r["D0_stable"] else "none before the limit")
        first = (f"{float(r['E0_first']):.5f}, {r['first_kind']}, `{r['first_class']}`, "
                 f"{float(r['first_X1']):.1f} mm ({r['first_layer']})" if r["E0_first"]
                 else "none before the limit")
        out.append(f"| {float(r['alpha']):g} | {r['mesh']} ({r['grading']}) | "
                   f"{float(r['grad_div']):g} | {int(r['dofs'])} | "
                   f"{float(r['E0_limit']):.6f} | {float(r['ratio']):.4f} | "
                   f"{float(r['E0_membrane']):.6f} | {float(r['D0_limit']):.4f} | {phys} | "
                   f"{first} | {float(r['J_min_limit']):.2f}-{float(r['J_max_limit']):.2f} | "
                   f"{r['cpu_s']}, {r['peak_GB']} |")
    return "\n".join(out) + "\n"
