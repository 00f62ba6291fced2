"""Exact dynamic condensation of harmonic balance onto the nonlinear DOFs (discrete/steady/condense.py)
against the full HB equations, on the hybrid AFC examples (issue 27, item 3)."""
from __future__ import annotations

import numpy as np

from discrete.linalg import single_threaded_blas
from discrete.steady import HBModel, afc
from discrete.steady.condense import CondensedHB
from fem.study import Study
from validation.examples import example_doc
from validation.registry import case, check, claim

SRC = "full HB equations of the same model (all DOFs, dense Newton)"
EXAMPLES = ("hybrid_afc_vibro_impact.toml", "hybrid_afc_friction_rod.toml")


def _curves(name: str):
    """(steady model, condensed AFC, full AFC) of an example."""
    out = []
    for mode in ("yes", "no"):
        d = example_doc(name)
        d["steady"]["condense"] = mode
        sm = Study.parse(d).steady_model()
        out.append((sm, afc(sm)))
    (sm, rc), (_, rf) = out
    return sm, rc, rf


def _checks(name: str) -> list:
    label = name.removesuffix(".toml")
    sm, rc, rf = _curves(name)
    c = sm.cfg
    hb = HBModel(sm.system, harmonics=c.harmonics, nu=c.subharmonic, samples=c.samples)
    cond = CondensedHB(hb)
    out = [claim(f"{label} condensed", "[steady] condense = \"yes\"", "condensed curve completes",
                 bool(rc.completed), note=f"{rc.extra.get('condensation')}; {rc.omega.size} points "
                 f"(full: {rf.omega.size}); {rc.reason}")]
    # (1) every point of the condensed curve, polished by the condensed Newton at its frequency and expanded,
    # is a solution of the full equations: full Newton from it (the equations agree) ...
    worst_step, worst_resp, cont_step, cont_resp = 0.0, 0.0, 0.0, 0.0
    peak = np.max(np.abs(rc.response))
    for x, w, y in zip(rc.states, rc.omega, rc.response):
        Xc = cond.expand(cond.solve(cond.restrict(x), w, tol=1e-13)[0], w)
        X, _ = hb.solve(Xc, w, tol=1e-13)
        worst_step = max(worst_step, float(np.max(np.abs(X - Xc)) / np.max(np.abs(X))))
        yc = sm.measure_hb(hb, [Xc], [w])[0]
        worst_resp = max(worst_resp, abs(sm.measure_hb(hb, [X], [w])[0] - yc) / max(abs(yc), peak))
        # ... and the curve's points as reported are within the continuation corrector's tolerance of it
        cont_step = max(cont_step, float(np.max(np.abs(X - x)) / np.max(np.abs(X))))
        cont_resp = max(cont_resp, abs(sm.measure_hb(hb, [X], [w])[0] - y) / max(abs(y), peak))
    out.append(check(f"{label} condensed points", SRC, "largest full-Newton correction of an expanded condensed "
                     "solution (relative to the largest coefficient)", 0.0, worst_step, 1e-10, scale=1.0,
                     note=f"{rc.omega.size} points"))
    out.append(check(f"{label} condensed points", SRC, "largest change of the response measure", 0.0, worst_resp,
                     1e-10, scale=1.0))
    out.append(check(f"{label} curve points", SRC, "largest full-Newton correction of a continuation point "
                     "(corrector tolerance 1e-9)", 0.0, cont_step, 1e-9, scale=1.0))
    out.append(check(f"{label} curve points", SRC, "largest change of the response measure (corrector "
                     "tolerance 1e-9)", 0.0, cont_resp, 1e-9, scale=1.0))
    # (2) at fixed frequencies (the full curve's points) the two solutions agree
    worst = 0.0
    for k in np.linspace(0, rf.omega.size - 1, 12).astype(int):
        w, x = float(rf.omega[k]), rf.states[k]
        Xf, _ = hb.solve(x, w, tol=1e-13)
        Xc, _ = cond.solve(cond.restrict(x), w, tol=1e-13)
        worst = max(worst, float(np.max(np.abs(cond.expand(Xc, w) - Xf)) / np.max(np.abs(Xf))))
    out.append(check(f"{label} fixed frequencies", SRC, "condensed vs full solution, 12 frequencies (relative to "
                     "the largest coefficient)", 0.0, worst, 1e-10, scale=1.0))
    # (3) folds (both curves locate them from their own branch points): same frequency
    out.append(claim(f"{label} folds", SRC, "as many folds condensed as full", len(rc.folds) == len(rf.folds),
                     note=f"{len(rc.folds)} / {len(rf.folds)}"))
    for f in rf.folds:
        g = min(rc.folds, key=lambda h: abs(h["omega"] - f["omega"]))
        out.append(check(f"{label} fold", SRC, "fold frequency", f["omega"], g["omega"], 1e-10,
                         note=f"response {g['response']:.10g} vs {f['response']:.10g}"))
    return out


@case("steady_condensed_hb", group="hybrid")
def steady_condensed_hb():
    """Exact dynamic condensation of HB onto the nonlinear DOFs (the linear rest eliminated per harmonic by
    its dynamic stiffness, factorised once per frequency) on the two hybrid AFC examples (Craig-Bampton
    models: cantilever with a stop, 4 -> 1 DOFs, H = 25; rod with a friction damper, 3 -> 1 DOFs, H = 15).

    Reference: the full HB equations of the same model.  The elimination is exact algebra, so the two
    differ by round-off and solver tolerance only.  Checks: (1) every point of the condensed curve,
    expanded to all DOFs, solves the full equations: a full Newton (tolerance 1e-13) started from it moves
    it by < 1e-10 of the largest coefficient, and the response measure by < 1e-10 of the peak -- the
    condensed point polished first by the condensed Newton (tolerance 1e-13), so that this measures the
    equations and not the continuation: its corrector stops at a scaled step of 1e-9 (or when quadratic
    convergence predicts the next step far below it), so the curve's points themselves are checked to
    1e-9 (measured 4.8e-10 on the friction rod, whose regularised friction law slows Newton's quadratic
    phase; the full curve's points are at 4.2e-10 likewise); (2) at 12 frequencies the condensed and the
    full Newton solutions agree to 1e-10; (3) the same folds (the cantilever's jump-up 383.9 and
    jump-down 413.6 rad/s; the stop law integrated exactly between its crossings makes the branch smooth,
    so the jump-down fold is located alike -- with the kink sampled it lay where the branch zig-zags) at
    the same frequencies to 1e-10.  The two curves' points differ (the arc length is measured on other
    unknowns, scaled to the full one at the start, condense.arclength_scale), not the equations they
    solve."""
    out = []
    with single_threaded_blas():
        for name in EXAMPLES:
            out += _checks(name)
    return out
