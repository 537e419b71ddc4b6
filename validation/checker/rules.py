"""The scoring rules of the loading cases: the homogeneous loading curves with their
``stable`` verdicts, the clamped Keplinger plate's centre stretch and its buckling load.
"""

from __future__ import annotations

import math

import numpy as np

import analytic as an
from analytic.units import keplinger_s

from ..data.loads import BUCKLING_LOADS_FILE, buckling_loads, uniform_buckling_loads
from ..cases import analytic_model
from ..specs import KEPLINGER
from .contract import CHECK_CASES, CheckInputError
from .diagnosis import Loading, closed_form, diagnose_loading, lam1_errors, lam3_state
from .reading import header_column, row_flag, row_model, row_number
from .scores import CaseCheck, Measure, file_names, make_measure, rows_text

__all__ = ["check_loading", "check_clamped", "loading_measure", "stable_measure"]

def loading_measure(case, p: Loading, name: str, tol: float, eq: str) -> Measure:
    """The :class:`Measure` of the stretch ``name`` of the rows ``p`` against the closed form
    named by ``eq`` with tolerance ``tol``; a failing measure carries the diagnosis of
    :func:`diagnose_loading`."""
    ref, err = lam1_errors(p)

    def details(i):
        load = f"s = {p.s[i]:.6g}" + (f" (alpha = {p.alpha[i]:g})"
                                      if np.isfinite(p.alpha[i]) else "")
        src = f"E0 = {p.E0[i]:.6g}, " if np.isfinite(p.E0[i]) else ""
        return (f"{p.model[i]}, {load}, {src}D0 = {p.D0[i]:.6g}: lam1 = {p.lam1[i]:.10g}, "
                f"closed form {ref[i]:.10g}")

    return make_measure(case, name, f"relative error of lam1 against {eq}", p.rows, err, tol,
                    details, lambda: diagnose_loading(p, tol))


def _loading_rows(case, tables, kind) -> tuple[Loading | None, list]:
    """The rows of a loading case (homogeneous or clamped) as :class:`Loading`, and the
    notes."""
    rows, vals, notes = [], [], []
    skipped_conv, skipped_empty = 0, 0
    for header, rs in tables:
        c_lam1, c_lam3 = header_column(header, "lam1"), header_column(header, "lam3")
        if kind != "clamped" and "s" not in header:
            raise CheckInputError(f"{rs[0].file}: column s missing (case {case} needs case, "
                                  f"s, D0 or E0, lam1; docs/check.md)")
        if kind == "clamped" and "s" not in header and "alpha" not in header:
            raise CheckInputError(f"{rs[0].file}: columns s and alpha missing (case {case} "
                                  f"needs s or alpha; docs/check.md)")
        if c_lam1 is None and not (kind == "clamped" and "D0_b" in header):
            raise CheckInputError(f"{rs[0].file}: column lam1 missing (case {case} needs "
                                  f"lam1_fe or lam1, the stretch at the plate centre)")
        if c_lam1 is not None and "D0" not in header and "E0" not in header:
            raise CheckInputError(f"{rs[0].file}: columns D0 and E0 missing (case {case} "
                                  f"needs the charge D0 or the field E0)")
        for r in rs:
            if row_flag(r, "converged" if "converged" in header else None) is False:
                skipped_conv += 1
                continue
            lam1 = row_number(r, c_lam1, required=False)
            if lam1 is None:
                skipped_empty += 1
                continue
            if lam1 <= 0:
                raise CheckInputError(f"{r.where}, column {c_lam1}: {lam1:g} is not a stretch "
                                      f"(> 0)")
            lam3 = row_number(r, c_lam3, required=False)
            if lam3 is not None and lam3 <= 0:
                raise CheckInputError(f"{r.where}, column {c_lam3}: {lam3:g} is not a stretch "
                                      f"(> 0)")
            model = row_model(r, header, case)
            alpha = row_number(r, "alpha" if "alpha" in header else None, required=False)
            s = row_number(r, "s" if "s" in header else None, required=alpha is None)
            from_alpha = s is None
            if from_alpha:
                if alpha < 0:
                    raise CheckInputError(f"{r.where}, column alpha: {alpha:g} < 0")
                s = float(keplinger_s(alpha, g=KEPLINGER["g"]))
            if "D0" in header and r.cells["D0"] != "":
                D0, E0 = row_number(r, "D0"), np.nan
            else:                  # D0 = lam1^2 lam3^2 E0 below, once lam3 is known
                D0, E0 = np.nan, row_number(r, "E0" if "E0" in header else "D0")
            rows.append(r)
            vals.append((s, D0, lam1, np.nan if lam3 is None else lam3, model, E0,
                         np.nan if alpha is None else alpha, from_alpha))
    if skipped_conv:
        notes.append(f"{rows_text(skipped_conv)} with converged = False not scored")
    if skipped_empty:
        notes.append(f"{rows_text(skipped_empty)} without lam1 not scored")
    if not rows:
        return None, notes
    s, D0, lam1, lam3, model, E0, alpha, from_alpha = (np.array(v) for v in zip(*vals))
    s, D0, lam1, lam3, E0, alpha = (np.asarray(a, dtype=float)
                                    for a in (s, D0, lam1, lam3, E0, alpha))
    loading = np.full(len(rows), "equibiaxial" if kind == "equibiaxial" else "uniaxial")
    p = Loading(rows, s, D0, lam1, lam3, model.astype(str), loading, E0, alpha,
                 from_alpha.astype(bool))
    if np.any(np.isfinite(E0)):                       # D0 = lam1^2 lam3^2 E0 (Eq. DLEL)
        l3 = lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
        with np.errstate(all="ignore"):
            p = p.replace(D0=np.where(np.isfinite(E0), E0 * (p.lam1 * l3) ** 2, p.D0))
    return p, notes


def stable_measure(case, rows, lam1, lam3, D0, model, control, theirs, exclude=None,
                    name="stable"):
    """Rows whose ``stable`` disagrees with the Hessian verdict, Eq. (equiv)
    (:func:`analytic.stability_verdict`)."""
    ours = np.zeros(len(rows), dtype=bool)
    for m in set(model):
        sel = model == m
        am = analytic_model(m)
        ours[sel] = closed_form([r for r, k in zip(rows, sel) if k],
                            lambda a, b, c: an.stability_verdict(a, b, c, am, control=control),
                            lam1[sel], lam3[sel], D0[sel]) > 0.5
    keep = np.ones(len(rows), dtype=bool) if exclude is None else ~exclude
    idx = np.flatnonzero(keep)
    if not idx.size:
        return None
    err = (ours[idx] != theirs[idx]).astype(float)

    def details(i):
        j = idx[i]
        return (f"lam1 = {lam1[j]:.6g}, D0 = {D0[j]:.6g}: {name} = {bool(theirs[j])}, the "
                f"Hessian ({control} control) says {bool(ours[j])}")

    return make_measure(case, name, f"rows whose {name} disagrees with the Hessian verdict "
                    f"under {control} control, Eq. (equiv)", [rows[j] for j in idx], err,
                    0.0, details, lambda: "the verdict differs from the sign of the Hessian's "
                    "leading 2x2 minor (docs/theory.md, Stability)")


def _stability_rows(case, tables, p: Loading):
    """``stable`` of the rows of ``p`` (``None`` where the file says nothing)."""
    by_row = {}
    for header, rs in tables:
        if "stable" in header:
            for r in rs:
                by_row[(r.file, r.line)] = row_flag(r, "stable")
    return np.array([by_row.get((r.file, r.line)) for r in p.rows], dtype=object)


def check_loading(case, tables, tol) -> CaseCheck:
    """The equibiaxial and uni-axial free cases: ``lam1`` against Eq. (loading_gent) or
    Eq. (DEuniax), ``stable`` against the Hessian criterion at each row."""
    kind = CHECK_CASES[case][0]
    p, notes = _loading_rows(case, tables, kind)
    if p is None:
        raise CheckInputError(f"case {case}: no row to score in "
                              f"{', '.join(sorted({h[1][0].file for h in tables}))}")
    eq = "Eq. (loading_gent)" if kind == "equibiaxial" else "Eq. (DEuniax)"
    measures = [loading_measure(case, p, "lam1", tol["lam1"], eq)]
    stable = _stability_rows(case, tables, p)
    given = np.array([v is not None for v in stable])
    if given.any():
        lam3 = lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows)
        sel = np.flatnonzero(given)
        m = stable_measure(case, [p.rows[i] for i in sel], p.lam1[sel], lam3[sel],
                            p.D0[sel], p.model[sel], "charge",
                            np.array([bool(v) for v in stable[sel]]))
        measures.append(m)
    _, err = lam1_errors(p)
    points = dict(kind=kind, s=p.s, D0=p.D0, lam1=p.lam1, model=p.model,
                  lam3=lam3_state(p.lam1, p.lam3, p.s, p.model, p.loading, p.rows),
                  ok=err <= tol["lam1"])
    return CaseCheck(case, file_names(tables), tuple(measures), tuple(notes), points)


def check_clamped(case, tables, tol) -> CaseCheck:
    """The clamped case: ``lam1`` of the clamped plate against the homogeneous curve,
    Eq. (DEuniax), and the buckling charges ``D0_b`` (every row, the worst counts) against
    the clamped-plate onsets."""
    p, notes = _loading_rows(case, tables, "clamped")
    measures, points = [], {"kind": "clamped"}
    if p is not None:
        measures.append(loading_measure(case, p, "lam1_clamped", tol["lam1_clamped"],
                                         "the homogeneous curve, Eq. (DEuniax)"))
        _, err = lam1_errors(p)
        alpha = np.where(np.isfinite(p.alpha), p.alpha,
                         p.s / float(keplinger_s(1.0, g=KEPLINGER["g"])))
        points.update(s=p.s, D0=p.D0, lam1=p.lam1, alpha=alpha, ok=err <= tol["lam1_clamped"])
    m, bpoints, bnotes = _buckling_measure(case, tables, tol)
    notes += bnotes
    if m is not None:
        measures.append(m)
        points["buckling"] = bpoints
    if not measures:
        raise CheckInputError(f"case {case}: no row to score (lam1 with D0, or D0_b) in "
                              f"{', '.join(file_names(tables))}")
    return CaseCheck(case, file_names(tables), tuple(measures), tuple(notes), points)


def _alpha_of(r, header) -> float:
    alpha = row_number(r, "alpha" if "alpha" in header else None, required=False)
    if alpha is not None:
        return alpha
    s = row_number(r, "s" if "s" in header else None)
    return s / float(keplinger_s(1.0, g=KEPLINGER["g"]))


def _buckling_measure(case, tables, tol):
    """``D0_b`` per weight against the converged load of
    :func:`validation.data.loads.buckling_loads` (Sec. 6; docs/validation.md: the graded
    meshes' load where they agree, else the uniform meshes' extrapolation)."""
    entries, uniform = buckling_loads(), uniform_buckling_loads()
    found = {}      # (alpha, run, variant, D0_b, own error) -> (row, D0_b, own error, alpha)
    for header, rs in tables:
        if "D0_b" not in header:
            continue
        if "s" not in header and "alpha" not in header:
            raise CheckInputError(f"{rs[0].file}: column alpha (or s) missing: D0_b is "
                                  f"checked per weight fraction alpha")
        for r in rs:
            D0b = row_number(r, "D0_b", required=False)
            if D0b is None:
                continue
            alpha = _alpha_of(r, header)
            u = row_number(r, "D0_b_error" if "D0_b_error" in header else None,
                           required=False)
            # a run repeats its D0_b on every row: one score per run and value; two
            # values for one weight are both scored (the worst counts), never dropped
            key = (round(alpha, 9), r.cells.get("run", ""), r.cells.get("variant", ""), D0b, u)
            found.setdefault(key, (r, D0b, u, alpha))
    notes, rows, err, tols, info = [], [], [], [], []
    per_weight: dict = {}
    for (r, D0b, _, alpha) in found.values():
        per_weight.setdefault(round(alpha, 9), []).append((r, D0b, alpha))
    for same in per_weight.values():
        if len({d for _, d, _ in same}) > 1:
            notes.append(f"alpha = {same[0][2]:g}: {len(same)} different D0_b ("
                         + ", ".join(f"{d:.6g} at {r.where}" for r, d, _ in same)
                         + "): each is scored, the worst counts")
    for (r, D0b, u, alpha) in found.values():
        e = next((e for e in entries if math.isclose(e.alpha, alpha, rel_tol=1e-6,
                                                     abs_tol=1e-9)), None)
        if e is None or not e.converged:
            why = "no entry" if e is None else "no converged load (its meshes disagree)"
            notes.append(f"{r.where}: D0_b of alpha = {alpha:g} not scored: {why} in "
                         f"validation/{BUCKLING_LOADS_FILE}")
            continue
        extra = u if u is not None else tol["D0_b"]
        rows.append(r)
        err.append(abs(D0b - e.D0_b))
        tols.append(e.error + extra)
        info.append((alpha, D0b, e, u))
    if not rows:
        return None, [], notes

    def details(i):
        alpha, D0b, e, u = info[i]
        mine = f" ± {u:g}" if u is not None else ""
        return (f"alpha = {alpha:g}: D0_b = {D0b:.6g}{mine}, converged {e.D0_b:.4f} ± "
                f"{e.error:.4f}")

    def diagnose():
        out = []
        for (alpha, D0b, e, u), er, t in zip(info, err, tols):
            if er <= t:
                continue
            meshes = ", ".join(f"{m}: {v:.4f}" for m, v in zip(e.meshes, e.D0_b_mesh))
            # our meshes that are not converged: the entry's own, and the uniform ones
            # where the graded meshes replaced them
            cands = list(zip(e.meshes, e.D0_b_mesh)) + [
                (f"uniform {m}", v) for u in uniform if u.source != e.source
                and math.isclose(u.alpha, alpha, rel_tol=1e-6, abs_tol=1e-9)
                for m, v in zip(u.meshes, u.D0_b_mesh) if math.isfinite(v)]
            near = min(cands, key=lambda mv: abs(mv[1] - D0b))
            side = "above" if D0b > e.D0_b else "below"
            text = (f"alpha = {alpha:g}: {D0b:.4f} is {side} the converged load (our eighth "
                    f"models: {meshes})")
            if abs(near[1] - D0b) <= 0.1 * abs(D0b - e.D0_b):
                text += (f"; it is the load of our {near[0]} mesh: a mesh that is not "
                         f"converged (refine, or state its error in a D0_b_error column)")
            out.append(text)
        return "; ".join(out)

    m = make_measure(case, "D0_b", "|D0_b - D0_b converged| (buckling load, Sec. 6)", rows,
                 np.array(err), np.array(tols), details, diagnose)
    points = [(alpha, D0b, ok) for (alpha, D0b, _, _), ok in
              zip(info, np.array(err) <= np.array(tols))]
    return m, points, notes
