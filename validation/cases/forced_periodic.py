"""Forced case: a periodic non-harmonic load by Fourier superposition (textbook §5.8, (5.41)-(5.45)),
examples/forced_periodic_load.toml, against the exact periodic steady state of the same oscillator under
the rectangular torque (validation.analytic.periodic_refs: matrix exponentials, no series)."""
from __future__ import annotations

import math

import numpy as np

from discrete.motion.waveforms import unit_waveform
from fem.modelfile.source import read_toml
from fem.study import Study
from validation.analytic.periodic_refs import sdof_rectangular
from validation.examples import EXAMPLES
from validation.registry import case, check, claim

SRC = "textbook §5.8 (5.41)-(5.45); exact piecewise solution"
EXAMPLE = EXAMPLES / "forced_periodic_load.toml"
J, K, C, A, DUTY, T = 0.5, 2.0e4, 4.0, 100.0, 0.3, 0.1


def _run(harmonics: int):
    d = read_toml(EXAMPLE)
    d["analysis"]["harmonics"] = harmonics
    r = Study.parse(d).forced()
    exact = sdof_rectangular(J, C, K, A, -A, DUTY, T, r.t)
    return r, exact


@case("forced-periodic-rectangular", group="forced")
def forced_periodic_rectangular():
    """The unit square wave's series is exact (closed-form integrals over its linear pieces): c_1 = 2 sin(2 pi
    d)/pi - 2i (1 - cos 2 pi d)/pi... checked for j = 1..5 against the textbook coefficients (1e-14).  The
    response's mean is -0.4 A/k exactly (1e-12).  Superposing H harmonics of a load with jumps leaves an error
    ~ 1/H^2 in q (§5.8: the discarded harmonics' responses fall like 1/j^3, their sum like 1/H^2): measured
    at H = 100, 200 against the exact periodic state -- 7.4e-5, 1.8e-5 of the peak -- the ratio is checked
    to be 4 +- 0.5 (second order), the error at H = 200 below 3e-5, and the peak of the example (200
    harmonics) equal to the exact peak to 1e-6."""
    out = []
    w = unit_waveform("square", duty=DUTY)
    _, c = w.coefficients(5)
    j = np.arange(1, 6)
    ref = (2 * np.sin(2 * math.pi * j * DUTY) - 2j * (1 - np.cos(2 * math.pi * j * DUTY))) / (math.pi * j)
    out.append(check("forced-periodic-rectangular", "Fourier coefficients of the square wave (5.42)",
                     "max |c_j - c_j,exact|, j = 1..5", 0.0, float(np.max(np.abs(c - ref))), 1e-14, scale=1.0))
    errs = {}
    for H in (100, 200):
        r, exact = _run(H)
        errs[H] = float(np.max(np.abs(r.q[:, 0] - exact)) / np.max(np.abs(exact)))
        if H == 200:
            out.append(check("forced-periodic-rectangular", SRC, "mean response (j = 0)", (2 * DUTY - 1) * A / K,
                             float(r.response[0, 0].real), 1e-12))
            out.append(check("forced-periodic-rectangular", SRC, "max |q - q_exact| / peak (H = 200)", 0.0, errs[H],
                             3e-5, scale=1.0))
            tt = np.linspace(0, T, 20001)
            peak = float(np.max(np.abs(sdof_rectangular(J, C, K, A, -A, DUTY, T, tt))))
            out.append(check("forced-periodic-rectangular", SRC, "peak |q| over a period (H = 200)", peak,
                             float(r.peak[0]), 1e-6))
    ratio = errs[100] / errs[200]
    out.append(claim("forced-periodic-rectangular", "§5.8 truncation of a load with jumps", "error ratio H = 100 / 200 "
                     "in [3.5, 4.5] (1/H^2)", 3.5 <= ratio <= 4.5, note=f"{errs[100]:.2e} / {errs[200]:.2e} = {ratio:.2f}"))
    return out
