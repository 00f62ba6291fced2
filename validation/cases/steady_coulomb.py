"""Steady case 2: single-DOF oscillator with Coulomb friction under a harmonic force (no stops)."""
from __future__ import annotations


import numpy as np

from discrete.steady import HBModel, ShootingModel, estimates
from fem.modelfile.source import read_toml
from fem.study import steady_model
from validation.analytic.steady_refs import den_hartog_amplitude
from validation.registry import case, check, claim
from validation.examples import EXAMPLES

SRC = "Den Hartog (1930) closed form; textbook §9.2 (harmonic linearisation), §5.13 (5.75)"
M, K, P, F0 = 1.0, 1.0, 0.3, 1.0
OMEGAS = (0.6, 0.8, 1.3, 1.6)
EXAMPLE = EXAMPLES / "steady_coulomb.toml"


def doc(method="shooting", c=0.0, **steady):
    """examples/steady_coulomb.toml (m = k = 1, P = 0.3, F0 = 1) with its [steady] table replaced by
    ``method`` over w = 0.5 .. 2 (and ``steady``), and a viscous damper c where given."""
    d = read_toml(EXAMPLE)
    d["steady"] = {"method": method, "omega": [0.5, 2.0], "response": {"body": "mass"}, **steady}
    if c:
        d["damper"] = [{"between": ["ground", "mass"], "c": c}]
    return d


@case("steady_coulomb_den_hartog", group="steady")
def coulomb():
    """x'' + x + 0.3 sign x' = sin(w t) at r = w/w0 = 0.6, 0.8, 1.3, 1.6 (two stops per period, no stick).
    (a) Shooting with the exact event-driven integrator against Den Hartog's closed form: both exact, so
    tolerance 1e-9 (Newton tolerance 1e-10 on the state, events to round-off).  The orbit has exactly two
    velocity reversals and no stick; Floquet multipliers (FD monodromy incl. saltation) all inside the unit
    circle, and time integration from rest reaches the same orbit (stable).
    (b) The quick estimates, errors reported: the harmonic-linearisation amplitude
    A = F0 sqrt(1 - (4P/(pi F0))^2)/|k - m w^2| and the one-harmonic HB (friction tanh(v/1e-4), N = 4096
    AFT samples) agree with each other to 3e-4 (regularisation + sampling error of a discontinuous force,
    ~0.2 * 2 pi/N); their error against the exact amplitude is the method's own error (a few %) and is
    checked only to be below 7 %.  HB with 15 harmonics is within 0.6 % of the exact amplitude.
    (c) Energy balance (5.75) with viscous damping c = 0.05 at resonance w = w0: A* = (pi F0 - 4P)/(pi c w)
    against shooting, tolerance 1e-3 (the estimate neglects the higher harmonics of the friction force).
    The oscillator is examples/steady_coulomb.toml.
    """
    out = []
    sm = steady_model(doc())
    sh = ShootingModel(sm.factory)
    hb1 = HBModel(steady_model(doc("hb", regularisation=1e-4)).system, harmonics=1, samples=4096)
    hb15 = HBModel(steady_model(doc("hb", regularisation=1e-4)).system, harmonics=15, samples=4096)
    for w in OMEGAS:
        ref = den_hartog_amplitude(M, K, P, F0, w)
        y, _, _ = sh.settle(np.zeros(2), w, periods=60, tol=1e-6, scale=np.ones(2))
        sc = np.array([ref, ref * w])
        y, _ = sh.solve(y, w, sc)
        _, res = sh.run(y, w, dense=True)
        x = res.x[0]
        A = 0.5 * (x.max() - x.min())
        out.append(check(f"Coulomb shooting r = {w}", SRC, "steady amplitude X", ref, A, 1e-9))
        kinds = [e.kind for e in res.events]
        out.append(claim(f"Coulomb orbit r = {w}: two reversals, no stick", SRC, "event kinds per period",
                         kinds.count("reversal") == 2 and "stick" not in kinds, note=str(kinds)))
        mu = np.abs(sh.floquet(y, w, sc))
        ys, n, ok = sh.settle(np.zeros(2), w, periods=400, tol=1e-10, scale=sc)
        out.append(claim(f"Coulomb orbit r = {w} stable", SRC, "max |Floquet multiplier| < 1 and reached from rest",
                         bool(mu.max() < 1 and ok and np.max(np.abs(ys - y) / sc) < 1e-7),
                         note=f"max|mu| = {mu.max():.4f}; settled in {n} periods"))
        hl = estimates.coulomb_hl_amplitude(M, K, P, F0, w)
        X1, _ = hb1.solve(hb1.linear_guess(w), w)
        a1 = float(np.hypot(X1[1], X1[2]))
        out.append(check(f"one-harmonic HB = harmonic linearisation r = {w}", SRC, "amplitude", hl, a1, 3e-4))
        out.append(check(f"harmonic linearisation error r = {w}", SRC, "amplitude (error reported)", ref, hl, 0.07,
                         note=f"HL error {hl / ref - 1:+.3%}, 1-harmonic HB error {a1 / ref - 1:+.3%}"))
        X15, _ = hb15.solve(hb15.linear_guess(w), w)
        _, q, _ = hb15.evaluate(X15, w, points=8192)
        out.append(check(f"HB 15 harmonics r = {w}", SRC, "amplitude", ref, 0.5 * (q.max() - q.min()), 0.006))
    # energy balance at resonance with viscous damping
    c = 0.05
    smc = steady_model(doc(c=c))
    shc = ShootingModel(smc.factory)
    y, _, _ = shc.settle(np.zeros(2), 1.0, periods=600, tol=1e-9, scale=np.ones(2))
    y, _ = shc.solve(y, 1.0, np.array([10.0, 10.0]))
    _, res = shc.run(y, 1.0, dense=True)
    A = 0.5 * (res.x[0].max() - res.x[0].min())
    eb = estimates.energy_balance_resonance(F0, c, 1.0, P)
    out.append(check("energy balance at resonance (5.75)", "textbook §5.13 (5.75)-(5.76)", "amplitude A*", A, eb, 1e-3,
                     note=f"error {eb / A - 1:+.2e}"))
    return out
