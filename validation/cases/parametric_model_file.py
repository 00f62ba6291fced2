"""The parametric chart from a model file (``[analysis] type = "parametric"``, ``drivefem parametric``):
examples/parametric_drive.toml -- a rotor on a shaft whose stiffness pulsates, c(t) = c0 (1 - eps sin
Omega t), psi = 0.2, k0 = 100 rad/s -- against the book's numbers (textbook §7.3, Fig. 7.4, (7.28))
and two independent references: Hill's infinite determinant and scipy's Mathieu characteristic values
(validation/analytic/parametric.py).  The model file goes through the whole chain: schema, the
``[[analysis.modulation]]`` part (``spring = 1``), the spring's psi converted to zeta = psi/(4 pi)
(7.31), the grid, the damping threshold and the edges by root finding.
"""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np

from fem.modelfile.build.parametric import run
from fem.modelfile.source import read_toml
from fem.study import Study
from validation.analytic import parametric as ref
from validation.registry import case, check, claim, printed

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "parametric_drive.toml"
SRC = "textbook §7.3 (7.25)-(7.28), Fig. 7.4 (digest textbook_ch6-9.md V7.3-a/b)"
MODEL = "examples/parametric_drive.toml"


@case("parametric_model_file", group="parametric")
def parametric_model_file():
    """``drivefem parametric`` on "parametric_drive.toml" (psi = 0.2) and on the same file with
    ``[damping] type = "none"``.

    * eps* at Omega = 2 k0 vs Hill's determinant (20 harmonic pairs, converged to round-off):
      1e-8 (100 x the effect of the 1e-10 monodromy tolerance); vs the digest's Floquet value
      0.063666 at half a unit of its last printed digit; vs the book's (7.28) psi/pi within twice
      its second-order correction (estimated independently by the two-pair Hill truncation).
    * The tongue tip (min over Omega) vs Hill's tip: depth 1e-8, Omega 1e-5 (a flat minimum: its
      location is fixed only to ~sqrt of the depth accuracy).
    * The damped edges at eps = 0.1 vs Hill's damped edges (1e-8: monodromy error over the slope of
      det(Phi + I)) and the digest's 1.96088, 2.03799 (half a digit).
    * Undamped (the same file, [damping] type = "none"): the first tongue at eps = 0.1 vs scipy's
      Mathieu a_1, b_1 (1e-8) and the book/digest's (1.94970, 2.04968) (half a digit).
    * The grid agrees with the root-found edges (every grid point at eps = 0.1 more than 1e-6 inside
      an edge is unstable, outside stable) and has no unstable point below eps*.
    """
    out = []
    study = Study.load(EXAMPLE)
    spec, chart = run(study)
    k0 = float(chart.natural_omega_rad_s[0])
    psi = 0.2
    zeta = ref.zeta_from_psi(psi)
    out.append(check("k0 of the mean system", MODEL + ": sqrt(c0 / J) = sqrt(500 / 0.05)", "rad/s", 100.0, k0, 1e-12))
    th = chart.thresholds[0]
    hill = ref.hill_damped_threshold(2.0, zeta=zeta)
    out.append(check("threshold vs Hill (model file)", SRC + "; Hill's determinant", "eps* at Omega = 2 k0", hill,
                     th.depth_at_centre, 1e-8))
    v, tol = printed("0.063666")
    out.append(check("threshold 0.063666 (digest Floquet)", "digest textbook_ch6-9.md §7.3 Floquet table",
                     "eps* at Omega = 2 k0", v, th.depth_at_centre, tol))
    book = ref.energy_threshold(psi)
    second = abs(ref.hill_damped_threshold(2.0, zeta=zeta, n_terms=2) - book) / book
    out.append(check("threshold vs (7.28) psi/pi", "textbook (7.28) eps* = psi/pi (first-order energy balance)",
                     "eps* at Omega = 2 k0", book, th.depth_at_centre, 2 * second + 1e-9,
                     note=f"second-order correction {second:.2e}"))
    w_tip, e_tip = ref.hill_damped_tip(zeta=zeta)
    out.append(check("tongue tip depth vs Hill", "Hill's determinant", "min over Omega of eps*", e_tip,
                     th.depth_minimum, 1e-8))
    out.append(check("tongue tip Omega vs Hill", "Hill's determinant", "Omega of the tip / k0", w_tip,
                     th.omega_at_minimum_rad_s / k0, 1e-5))
    b = next(x for x in chart.boundaries if abs(x.depth - 0.1) < 1e-15)
    out.append(check("damped tongue count at eps = 0.1", SRC, "instability intervals in [0.5, 2.5] k0", 1,
                     len(b.omega_low_rad_s), 0.0, scale=1.0, note="s = 2, 3 need eps > 0.3 at psi = 0.2"))
    if len(b.omega_low_rad_s) == 1:
        h_lo, h_hi = ref.hill_damped_edges(0.1, zeta=zeta)
        for name, mine, hl, txt in (("lower", b.omega_low_rad_s[0] / k0, h_lo, "1.96088"),
                                    ("upper", b.omega_high_rad_s[0] / k0, h_hi, "2.03799")):
            out.append(check(f"damped {name} edge vs Hill (model file)", "Hill's determinant with damping",
                             "Omega / k0", hl, mine, 1e-8))
            v, tol = printed(txt)
            out.append(check(f"damped {name} edge {txt} (digest)", "digest §7.3 (eps = 0.1, psi = 0.2)", "Omega / k0",
                             v, mine, tol))
        # the grid row at eps = 0.1 against the edges
        i = int(np.argmin(np.abs(chart.depth - 0.1)))
        lo, hi = b.omega_low_rad_s[0], b.omega_high_rad_s[0]
        om = chart.omega_rad_s
        clear = (np.abs(om - lo) > 1e-6 * k0) & (np.abs(om - hi) > 1e-6 * k0)
        inside = (om > lo) & (om < hi)
        agree = bool(np.all((~chart.stable[i]) [clear] == inside[clear]))
        out.append(claim("grid agrees with the root-found edges (eps = 0.1)", "Floquet grid vs Brent edges",
                         "unstable exactly between the edges", agree and abs(chart.depth[i] - 0.1) < 1e-12,
                         note=f"{int(inside.sum())} grid points inside"))
    below = chart.depth < th.depth_minimum * (1 - 1e-9)
    out.append(claim("no instability below eps*", "(7.28): the damping threshold", "stable grid rows eps < eps*",
                     bool(np.all(chart.stable[below])), note=f"{int(below.sum())} rows below eps*"))
    out.append(check("monodromy error estimate of the grid", "step doubling of the sixth-order Magnus integrator",
                     "max error_estimate", 0.0, float(chart.error_estimate.max()), 2e-10, scale=1.0,
                     note="the file's tolerance 1e-10 (a doubling that stops at the round-off floor may end above)"))

    # the same model file without damping: the Mathieu tongue
    doc = copy.deepcopy(read_toml(EXAMPLE))
    doc["damping"] = {"type": "none"}
    doc["analysis"].update(depth={"max": 0.1, "min": 0.05, "points": 2}, boundaries_at=[0.1], thresholds=False)
    _, undamped = run(Study.parse(doc))
    bu = undamped.boundaries[0]
    principal = [j for j, c in enumerate(bu.centre) if c == "2 w1/1"]
    out.append(claim("undamped: the principal tongue is found (eps = 0.1)", "(7.26) Omega* = 2 k0",
                     "an interval around 2 k0", len(principal) == 1, note=f"intervals: {bu.centre}"))
    if len(principal) == 1:
        j = principal[0]
        m_lo, m_hi = ref.mathieu_edges(0.1, 1)
        for name, mine, mat, txt in (("lower", bu.omega_low_rad_s[j] / k0, m_lo, "1.94970"),
                                     ("upper", bu.omega_high_rad_s[j] / k0, m_hi, "2.04968")):
            out.append(check(f"undamped {name} edge vs Mathieu (model file)", "scipy.special.mathieu_a/b",
                             "Omega / k0", mat, mine, 1e-8))
            v, tol = printed(txt)
            out.append(check(f"undamped {name} edge {txt} (book/digest)", "digest §7.3 tongue edges, eps = 0.1",
                             "Omega / k0", v, mine, tol))
    return out
