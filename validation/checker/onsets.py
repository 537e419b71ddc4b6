"""The scoring rules of the paths under voltage control (loading curve, ``stable``
verdicts, the limit point ``det H* = 0``) and of the wrinkling onsets (the dispersion
relation of Sec. 4).
"""

from __future__ import annotations

import math

import numpy as np

import analytic as an

from ..cases import analytic_model
from .contract import CheckInputError
from .diagnosis import Loading, closed_form, lam1_errors, lam3_state
from .reading import LOADINGS, header_column, row_flag, row_model, row_number, row_text
from .rules import loading_measure, stable_measure
from .scores import CaseCheck, file_names, fmt_g, make_measure, rows_text

__all__ = ["check_voltage", "check_wrinkling"]

def check_voltage(case, tables, tol) -> CaseCheck:
    """Paths under voltage control: ``lam1`` at each point against the loading curve,
    ``stable`` and ``stable_charge`` against the Hessian, the limit points against
    :func:`analytic.max_E0`."""
    rows, vals, notes = [], [], []
    limits = {}
    clamped = 0
    skipped = 0
    for header, rs in tables:
        for col in ("loading", "s", "lam1"):
            if header_column(header, col) is None:
                raise CheckInputError(f"{rs[0].file}: column {col} missing (case {case} "
                                      f"needs case, loading, s, E0 or D0, lam1; "
                                      f"docs/check.md)")
        if "D0" not in header and "E0" not in header:
            raise CheckInputError(f"{rs[0].file}: columns D0 and E0 missing")
        c_lam1 = header_column(header, "lam1")
        for r in rs:
            loading = row_text(r, "loading", LOADINGS)
            if loading == "uniaxial":
                clamped += 1
                continue
            lam1 = row_number(r, c_lam1, required=False)
            if lam1 is None:
                skipped += 1
                continue
            model = row_model(r, header, case)
            s = row_number(r, "s")
            D0 = row_number(r, "D0", required=False) if "D0" in header else None
            E0 = row_number(r, "E0", required=D0 is None) if "E0" in header else None
            run = r.cells.get("run") or f"{loading} {model} s={s:g}"
            kind = r.cells.get("kind", "")
            rows.append(r)
            vals.append((s, np.nan if D0 is None else D0, lam1, model, loading,
                         np.nan if E0 is None else E0, row_flag(r, "stable" if "stable" in
                                                             header else None),
                         row_flag(r, "stable_charge" if "stable_charge" in header else None)))
            if kind == "limit":
                limits[run] = (r, lam1, E0 if E0 is not None else np.nan, s, model, loading)
            elif run not in limits and "lam1_max_fe" in header and \
                    r.cells.get("lam1_max_fe", "") != "":
                limits[run] = (r, row_number(r, "lam1_max_fe"),
                               row_number(r, "E0_max_fe" if "E0_max_fe" in header else None,
                                       required=False) or np.nan, s, model, loading)
    if clamped:
        notes.append(f"{rows_text(clamped)} of the clamped plate (loading uniaxial) not scored: "
                     f"the closed forms are of homogeneous plates")
    if skipped:
        notes.append(f"{rows_text(skipped)} without lam1 not scored")
    if not rows:
        raise CheckInputError(f"case {case}: no row of a homogeneous plate to score in "
                              f"{', '.join(file_names(tables))}")
    s, D0, lam1, model, loading, E0, stable, stable_charge = (list(v) for v in zip(*vals))
    s, D0, lam1, E0 = (np.asarray(a, dtype=float) for a in (s, D0, lam1, E0))
    model, loading = np.array(model, dtype=str), np.array(loading, dtype=str)
    ld = np.where(loading == "equibiaxial", "equibiaxial", "uniaxial")
    p = Loading(rows, s, D0, lam1, np.full(len(rows), np.nan), model, ld,
                 np.where(np.isfinite(D0), np.nan, E0), np.full(len(rows), np.nan),
                 np.zeros(len(rows), dtype=bool))
    lam3 = lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
    with np.errstate(all="ignore"):
        p = p.replace(D0=np.where(np.isfinite(D0), D0, E0 * (lam1 * lam3) ** 2))
    measures = [loading_measure(case, p, "lam1", tol["lam1"],
                                 "the loading curve, Eq. (loading_gent) or Eq. (DEuniax)")]
    # the limit point of each row's path, and the rows within tolerance of it
    lim_lam = np.full(len(rows), np.nan)
    for m_ in set(model):
        for l_ in set(ld):
            sel = (model == m_) & (ld == l_)
            if sel.any():
                am = analytic_model(m_)
                lim_lam[sel] = closed_form([r for r, k in zip(rows, sel) if k],
                                       lambda s_: an.max_E0(s_, am, loading=l_)[0], s[sel])
    with np.errstate(invalid="ignore"):
        marginal = np.abs(lam1 / lim_lam - 1) <= tol["lam1_limit"]
    marginal |= np.array([r.cells.get("kind", "") == "limit" for r in rows])
    for name, flags, control in (("stable", stable, "voltage"),
                                 ("stable_charge", stable_charge, "charge")):
        given = np.array([f is not None for f in flags])
        if not given.any():
            continue
        sel = np.flatnonzero(given)
        m = stable_measure(case, [rows[i] for i in sel], lam1[sel], lam3[sel],
                            p.D0[sel], model[sel], control,
                            np.array([bool(flags[i]) for i in sel]),
                            exclude=marginal[sel] if control == "voltage" else None, name=name)
        if m is not None:
            measures.append(m)
    lim_points = []
    if limits:
        lrows, lerr, Eerr, linfo = [], [], [], []
        for run, (r, l1, e0, s_, m_, l_) in limits.items():
            lam_ref, E0_ref = (float(v[0]) for v in closed_form(
                [r], lambda x: np.array(an.max_E0(x, analytic_model(m_), loading=(
                    "equibiaxial" if l_ == "equibiaxial" else "uniaxial"))), np.array([s_])))
            lrows.append(r)
            lerr.append(abs(l1 / lam_ref - 1) if math.isfinite(lam_ref) else math.inf)
            Eerr.append(abs(e0 / E0_ref - 1) if math.isfinite(E0_ref) and math.isfinite(e0)
                        else (math.inf if not math.isfinite(E0_ref) else math.nan))
            linfo.append((run, l1, e0, lam_ref, E0_ref, s_, m_, l_))

        def ldetail(key):
            def details(i):
                run, l1, e0, lam_ref, E0_ref, s_, m_, l_ = linfo[i]
                if not math.isfinite(lam_ref):
                    return (f"{run}: a limit point, but E0 has no maximum at s = {s_:g} "
                            f"({m_}, analytic.max_E0)")
                return (f"{run}: lam1 = {l1:.10g}, E0 = {e0:.10g}; max_E0: lam1 = "
                        f"{lam_ref:.10g}, E0 = {E0_ref:.10g}")
            return details

        lerr_a = np.array(lerr)
        measures.append(make_measure(case, "lam1_limit", "relative error of lam1 at the limit "
                                 "point against analytic.max_E0 (det H* = 0)", lrows, lerr_a,
                                 tol["lam1_limit"], ldetail("lam1")))
        E = np.array(Eerr)
        if np.any(np.isfinite(E) | np.isinf(E)):
            keep = ~np.isnan(E)
            measures.append(make_measure(case, "E0_limit", "relative error of the maximum of E0 "
                                     "against analytic.max_E0", [lrows[i] for i in
                                                                  np.flatnonzero(keep)],
                                     E[keep], tol["E0_limit"],
                                     lambda i: ldetail("E0")(int(np.flatnonzero(keep)[i]))))
        lim_points = [("equibiaxial" if l_ == "equibiaxial" else "uniaxial", m_, s_, l1, e0,
                       lerr_a[i] <= tol["lam1_limit"])
                      for i, (run, l1, e0, lam_ref, E0_ref, s_, m_, l_) in enumerate(linfo)]
    _, err = lam1_errors(p)
    points = dict(kind="voltage", s=s, D0=p.D0, lam1=lam1, lam3=lam3, model=model,
                  loading=ld, ok=err <= tol["lam1"], limits=lim_points)
    return CaseCheck(case, file_names(tables), tuple(measures), tuple(notes), points)


def check_wrinkling(case, tables, tol) -> CaseCheck:
    """The critical ``D0`` of each row against :func:`analytic.critical_D0` (the exact
    dispersion relation of the finite plate, Sec. 4; ``D0 = lam^4 E0`` under voltage
    control)."""
    rows, vals, notes, skipped = [], [], [], 0
    for header, rs in tables:
        col = header_column(header, "D0_crit")
        for need in ("mode", "lam", "kh"):
            if need not in header:
                raise CheckInputError(f"{rs[0].file}: column {need} missing (case {case} needs "
                                      f"mode, lam, kh, D0_fe; control optional)")
        if col is None:
            raise CheckInputError(f"{rs[0].file}: column D0_fe missing (the critical D0)")
        for r in rs:
            D0 = row_number(r, col, required=False)
            if D0 is None:
                skipped += 1
                continue
            control = row_text(r, "control", ("charge", "voltage"), default="charge")
            mode = row_text(r, "mode", ("antisymmetric", "symmetric"))
            lam, kh = row_number(r, "lam"), row_number(r, "kh")
            if lam <= 0 or kh <= 0:
                raise CheckInputError(f"{r.where}: lam and kh must be > 0, got lam = {lam:g}, "
                                      f"kh = {kh:g}")
            rows.append(r)
            vals.append((control, mode, lam, kh, D0, row_model(r, header, case)))
    if skipped:
        notes.append(f"{rows_text(skipped)} without a critical D0 not scored")
    if not rows:
        raise CheckInputError(f"case {case}: no row with a critical D0 in "
                              f"{', '.join(file_names(tables))}")
    control, mode, lam, kh, D0, model = (np.array(v) for v in zip(*vals))
    lam, kh, D0 = (np.asarray(a, dtype=float) for a in (lam, kh, D0))

    def reference(lam_, kh_, mode_):
        ref = np.full(lam_.shape, np.nan)
        for c in set(control):
            for md in set(mode_):
                for mo in set(model):
                    sel = (control == c) & (mode_ == md) & (model == mo)
                    if sel.any():
                        am = analytic_model(mo)
                        ref[sel] = closed_form(
                            [r for r, k in zip(rows, sel) if k],
                            lambda a, b: an.critical_D0(a, b, am, mode=md, control=c),
                            lam_[sel], kh_[sel])
        return ref

    ref = reference(lam, kh, mode)
    with np.errstate(all="ignore"):
        err = np.abs(D0 - ref) / ref

    def details(i):
        stroh = f"{ref[i]:.8g}" if np.isfinite(ref[i]) else "no root of the dispersion relation"
        return (f"{control[i]} control, {mode[i]}, lam = {lam[i]:g}, kh = {kh[i]:g}: critical "
                f"D0 = {D0[i]:.8g}, Stroh {stroh}")

    def diagnose():
        t = tol["D0_crit"]
        tries = [("kh is per reference thickness (the contract's kh is per deformed "
                  "thickness, h = lam^-2 H)", lambda: np.abs(D0 - reference(
                      lam, kh * lam**-2, mode)) / reference(lam, kh * lam**-2, mode))]
        if np.any(control == "voltage"):
            tries.append(("the voltage-control rows give E0 (the contract's critical D0 = "
                          "lam^4 E0)", lambda: np.abs(np.where(control == "voltage",
                                                               D0 * lam**4, D0) - ref) / ref))
        other = np.where(mode == "symmetric", "antisymmetric", "symmetric")
        tries.append(("the modes are swapped (antisymmetric: flexural, u2 even through the "
                      "thickness)", lambda: np.abs(D0 - reference(lam, kh, other))
                      / reference(lam, kh, other)))
        for what, e in tries:
            try:
                with np.errstate(all="ignore"):
                    ee = e()
            except ValueError:
                continue
            if np.all(np.isfinite(ee) & (ee <= t)):
                return f"looks like {what}: read that way the largest error would be " \
                       f"{fmt_g(float(ee.max()))}"
        return "no usual mix-up explains it (tried: kh per reference thickness, E0 for D0, " \
               "the modes swapped)"

    m = make_measure(case, "D0_crit", "relative error of the critical D0 against the dispersion "
                 "relation (analytic.critical_D0)", rows, err, tol["D0_crit"], details,
                 diagnose)
    points = dict(kind="wrinkling", control=control, mode=mode, lam=lam, kh=kh, D0=D0,
                  ok=np.nan_to_num(err, nan=np.inf) <= tol["D0_crit"])
    return CaseCheck(case, file_names(tables), (m,), tuple(notes), points)
