"""Parametric stability charts (textbook ch. 7, Fig. 7.4) through the Python API.

1. ``book_chart``: the oscillator of (7.2), m y'' + b y' + c0 (1 - eps sin Omega t) y = 0, built
   as a lumped chain (motor held -- spring c0 with the book's dissipation coefficient
   psi = 0.2 -- body m).  The spring's psi becomes the equivalent viscous ratio
   zeta = psi/(4 pi) of (7.31).  The chart shows the tongues around Omega* = 2 k0/s (7.26), the
   damping threshold eps* = psi/pi (7.28) -- computed: 0.063666 at Omega = 2 k0, 0.063661 at the
   tongue tip -- and the edges of the principal tongue at eps = 0.1.
2. ``drive_chart``: a two-mass drive whose coupling spring pulsates (a mechanism with variable
   reduced stiffness): principal tongues of both modes and the combination tongue w1 + w2.

Run:  python examples/parametric_chart.py [OUT_DIR]   (default ./parametric_chart_out)
Writes <name>.json (StabilityChart.to_dict()) and <name>.png for each chart and returns the
headline numbers, which tests/test_parametric.py asserts.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from discrete.linear.harmonic import Damping
from discrete.linear.parametric import Modulation, stability_chart
from discrete.lumped import Body, Driver, Link, LumpedModel
from fem.output.figures.parametric import plot_stability_chart


def book_chart(out_dir: str | Path) -> dict:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    m, c0, psi = 1.0, 1.0, 0.2                      # k0 = 1 rad/s: Omega in units of k0
    model = LumpedModel(bodies=[Body("mass", m)], drivers=[Driver("motor", velocity=0.0)],
                        springs=[Link(("motor", "mass"), c0, psi=psi)], title="(7.2) with psi = 0.2")
    chart = stability_chart(model.linear_system(), [Modulation(target="stiffness", label="spring")],
                            omega_min=0.5, omega_max=2.5, n_omega=161, depth_max=0.3, n_depth=61,
                            damping=Damping("viscous"), boundaries_at=[0.1, 0.2])
    (out_dir / "parametric_book.json").write_text(json.dumps(chart.to_dict()))
    plot_stability_chart(chart, out_dir / "parametric_book.png",
                         title="Fig. 7.4: k^2(t) = k0^2 (1 - eps sin Omega t), psi = 0.2 (zeta = psi/4pi)")
    th = chart.thresholds[0]
    b = chart.boundaries[0]
    principal = int(np.argmin(np.abs(0.5 * (b.omega_low_rad_s + b.omega_high_rad_s) - 2.0)))
    return {"threshold_at_2k0": th.depth_at_centre, "threshold_tip": th.depth_minimum,
            "omega_tip": th.omega_at_minimum_rad_s, "energy_estimate": th.energy_estimate,
            "edges_eps_0.1": (float(b.omega_low_rad_s[principal]), float(b.omega_high_rad_s[principal])),
            "max_error_estimate": float(chart.error_estimate.max()),
            "max_liouville_residual": float(chart.liouville_residual.max()),
            "png": str(out_dir / "parametric_book.png"), "json": str(out_dir / "parametric_book.json")}


def drive_chart(out_dir: str | Path) -> dict:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    c_ab = 0.8
    model = LumpedModel(bodies=[Body("a", 1.0), Body("b", 0.5)], drivers=[Driver("motor", velocity=0.0)],
                        springs=[Link(("motor", "a"), 1.0, psi=0.1), Link(("a", "b"), c_ab, psi=0.1)],
                        title="two-mass drive, pulsating coupling spring")
    system = model.linear_system()
    names = model.transformation()[0]
    g = np.zeros(len(names))
    g[names.index("a")], g[names.index("b")] = -1.0, 1.0
    coupling = c_ab * np.outer(g, g)                # the part of K that pulsates (spring a-b)
    chart = stability_chart(system, [Modulation(part=coupling, label="spring a-b")],
                            omega_min=0.4, omega_max=3.6, n_omega=161, depth_max=0.6, n_depth=41,
                            damping=Damping("viscous"), boundaries_at=[0.4], boundary_samples=201)
    (out_dir / "parametric_drive.json").write_text(json.dumps(chart.to_dict()))
    plot_stability_chart(chart, out_dir / "parametric_drive.png",
                         title="Two-mass drive, coupling spring c(t) = c (1 - eps sin Omega t), psi = 0.1")
    b = chart.boundaries[0]
    return {"natural_omega_rad_s": chart.natural_omega_rad_s.tolist(),
            "thresholds_tip": [t.depth_minimum for t in chart.thresholds],
            "tongues_eps_0.4": list(zip(b.centre, b.crossing, b.omega_low_rad_s.tolist(), b.omega_high_rad_s.tolist())),
            "png": str(out_dir / "parametric_drive.png"), "json": str(out_dir / "parametric_drive.json")}


def main(out_dir: str | Path = "parametric_chart_out") -> dict:
    return {"book": book_chart(out_dir), "drive": drive_chart(out_dir)}


if __name__ == "__main__":
    result = main(sys.argv[1] if len(sys.argv) > 1 else "parametric_chart_out")
    print(json.dumps(result, indent=2))
