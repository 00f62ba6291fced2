"""Steady case 3: cubic stiffness -- free backbone and the book's forced cubic oscillator with jumps."""
from __future__ import annotations


import numpy as np

from discrete.steady import HBModel, backbone, estimates
from fem.modelfile.source import read_toml
from fem.study import forced, steady_model
from validation.analytic.steady_refs import duffing_backbone_exact, duffing_rk4_sweep
from validation.registry import case, check, claim, printed
from validation.examples import EXAMPLES

SRC = "textbook §8.3-8.4 (8.20)-(8.23); digest textbook_ch6-9.md [C] checks for 8.4"
BACKBONE_TABLE = [(0.1, 1.0, "1.036717"), (0.5, 1.0, "1.170781"), (1.0, 1.0, "1.317776"), (0.5, 2.0, "1.569106"),
                  (1.0, 2.0, "1.976016")]


EXAMPLE = EXAMPLES / "steady_duffing.toml"


def forced_doc(harmonics=None):
    """examples/steady_duffing.toml: q'' + 0.1 q' + q + 0.5 q^3 = 0.25 sin(w t), HB with 7 harmonics over
    w = 0.5 .. 2.2, fundamental amplitude; ``harmonics`` replaces the file's 7."""
    doc = read_toml(EXAMPLE)
    if harmonics is not None:
        doc["steady"]["harmonics"] = harmonics
    return doc


@case("steady_cubic_backbone", group="steady")
def cubic_backbone():
    """Free q'' + q (1 + xi q^2) = 0, peak amplitude A: HB (9 harmonics, phase b1 = 0, amplitude condition)
    against the exact elliptic-integral frequency (independent closed form, itself checked against the
    digest's table to its printed digits).  Tolerance 1e-7: the neglected harmonics decay like q^k with
    q = e^{-pi} per odd harmonic (A11/A1 < 1e-8).  HB with one harmonic reproduces the book's (8.22)
    estimate w = k0 sqrt(1 + 0.75 xi A^2) to 1e-10 (it is the same approximation); its error against the exact
    value is reported (+0.010 % .. +1.21 % in the digest) and checked to the digest's printed digits."""
    out = []
    for xi, A, txt in BACKBONE_TABLE:
        ref_tab, tol_tab = printed(txt)
        ex = float(duffing_backbone_exact(1.0, xi, A))
        out.append(check(f"elliptic backbone xi = {xi}, A = {A}", SRC + " table 'Backbone vs exact'", "omega exact",
                         ref_tab, ex, tol_tab))
        d = forced_doc()
        d["spring"][0]["k"] = 1.0
        d["cubic_spring"][0]["k3"] = xi
        d["force"][0]["amplitude"] = 0.0
        d["force"][0]["omega"] = 1.0
        d["force"].append({"body": "mass", "amplitude": 1e-300, "omega": 1.0})
        sm = steady_model(d)
        w9, _ = backbone(HBModel(sm.system, harmonics=9), A, ex)
        out.append(check(f"HB backbone xi = {xi}, A = {A}", SRC, "omega (9 harmonics)", ex, w9, 1e-7))
        w1, _ = backbone(HBModel(sm.system, harmonics=1), A, ex)
        book = float(estimates.backbone_book(1.0, xi, A))
        out.append(check(f"one-harmonic HB = book (8.22) xi = {xi}, A = {A}", SRC + " (8.22)", "omega", book, w1, 1e-10))
        out.append(check(f"book estimate error xi = {xi}, A = {A}", SRC + " (8.22)", "omega (error reported)", ex, book,
                         0.013, note=f"(8.22) error {book / ex - 1:+.3%}"))
    return out


@case("steady_cubic_forced_jumps", group="steady")
def cubic_forced():
    """q'' + 0.1 q' + q + 0.5 q^3 = 0.25 sin(w t) (the digest's forced hardening example).
    (a) One-harmonic HB continuation: folds at w_L = 1.23243, w_R = 1.45384 and the (8.17) amplitudes
    A(0.8) = 0.5296, A(1.0) = 0.8556, A(2.0) = 0.0832 (digest, printed digits: tolerance half a unit of
    the last digit, plus 1e-6 for the fold location by bounded minimisation).
    (b) 7-harmonic HB continuation (fundamental amplitude): the middle branch between the folds is unstable
    (Floquet multiplier > 1) and the rest stable; brute-force RK4 time integration (64 steps/period,
    independent code) swept up and down in steps of 0.01 jumps down between the two sweep frequencies that
    bracket w_R and up between those that bracket w_L; its amplitudes on both branches agree with HB to 2e-3
    (RK4 at 64 steps/period: ~1e-5; settling to 1e-9 over a period; the digest quotes <= 0.9 %).
    The model and the 7-harmonic continuation are examples/steady_duffing.toml.
    """
    out = []
    r1 = forced(forced_doc(harmonics=1))
    fw = sorted(f["omega"] for f in r1.folds)
    out.append(claim("two folds (one-harmonic HB)", SRC, "number of folds", len(fw) == 2, note=str(fw)))
    if len(fw) == 2:
        for name, val, txt in (("w_L", fw[0], "1.23243"), ("w_R", fw[1], "1.45384")):
            ref, tol = printed(txt)
            out.append(check(f"fold {name} (H = 1)", SRC, "omega", ref, val, tol + 1e-6))
    sm = steady_model(forced_doc(harmonics=1))
    hb = HBModel(sm.system, harmonics=1)
    for w, txt in ((0.8, "0.5296"), (1.0, "0.8556"), (2.0, "0.0832")):
        X, _ = hb.solve(hb.linear_guess(w), w)
        ref, tol = printed(txt)
        out.append(check(f"(8.17) amplitude w = {w}", SRC, "A", ref, float(np.hypot(X[1], X[2])), tol))
    r7 = forced(forced_doc())
    f7 = sorted(f["omega"] for f in r7.folds)
    # stability pattern: along the branch, points between the two folds are unstable
    i_r = int(np.argmax(r7.omega * (r7.response > 1.0)))  # right fold index (top of the upper branch)
    lo_fold_idx = i_r + int(np.argmin(r7.omega[i_r:]))
    unstable_ok = bool(np.all(~r7.stable[i_r + 2:lo_fold_idx - 1]) and np.all(r7.stable[:i_r - 1])
                       and np.all(r7.stable[lo_fold_idx + 2:]))
    out.append(claim("middle branch unstable, others stable (H = 7, Floquet)", SRC + " (8.25)", "stability pattern",
                     unstable_ok and len(f7) == 2,
                     note=f"folds {f7}; {int(np.sum(~r7.stable))} unstable of {r7.omega.size} points"))
    up = np.round(np.arange(1.20, 1.5001, 0.01), 10)
    dn = up[::-1]
    a_up, _ = duffing_rk4_sweep(up)
    a_dn, _ = duffing_rk4_sweep(dn)
    ju = int(np.argmax(np.diff(a_up) < -0.5))        # last index before the down-jump
    jd = int(np.argmax(np.diff(a_dn) > 0.3))
    out.append(claim("up-sweep jumps down across the right fold", SRC, "w_j < w_R(H=7) <= w_j + 0.01",
                     bool(up[ju] < f7[1] <= up[ju + 1]), note=f"jump between {up[ju]} and {up[ju + 1]}, fold {f7[1]:.5f}"))
    out.append(claim("down-sweep jumps up across the left fold", SRC, "w_j - 0.01 <= w_L(H=7) < w_j",
                     bool(dn[jd + 1] <= f7[0] < dn[jd]), note=f"jump between {dn[jd]} and {dn[jd + 1]}, fold {f7[0]:.5f}"))
    # amplitudes: compare with the HB branch point nearest in (omega, amplitude)
    hb7 = HBModel(steady_model(forced_doc()).system, harmonics=7)
    errs = []
    for ws, amps in ((up, a_up), (dn, a_dn)):
        for w, a in zip(ws[::5], amps[::5]):
            j = np.argmin(np.abs(r7.omega - w) / 0.05 + np.abs(r7.response - a))
            X, _ = hb7.solve(r7.states[j], w)      # re-solved at w from the nearest branch point
            t, q, v = hb7.evaluate(X, w, points=512)
            h1 = 2 / 512 * abs(np.sum(q[0] * np.exp(-1j * w * t)))
            errs.append(abs(h1 - a) / a)
    out.append(check("RK4 sweeps vs HB (stable branches)", SRC, "max rel. difference of fundamental amplitude",
                     0.0, max(errs), 2e-3, scale=1.0))
    for w, txt, arr, ws in ((1.3, "1.4479", a_up, up), (1.3, "0.3861", a_dn, dn)):
        ref, _ = printed(txt)
        k = int(np.argmin(np.abs(ws - w)))
        out.append(check(f"time sweep amplitude w = {w} ({'up' if arr is a_up else 'down'})", SRC + " sweep table",
                         "fundamental amplitude", ref, arr[k], 2e-3))
    return out
