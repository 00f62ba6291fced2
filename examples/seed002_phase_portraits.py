"""Seed 002 Figs. 2b and 3b (phase portraits with zero tension, a = 4.7e-4 m) under the two readings of the
paper's (1)-(2): literally (the strand force switched off while the spool angle phi < 0, phi from the
untensioned position) and as the package reads it (the strand slack while its tension would be negative).

    python examples/seed002_phase_portraits.py [OUT.png]      (default docs/img/seed002_phase_portraits.png)

Both are plotted with phi from the static equilibrium; the zero-tension parts are red.  The literal
reading reproduces the figures; the package's reading, from rest, stays taut at both points (see
validation/cases/steady_seed002_portraits.py).  Returns the minimum tension of each panel (N).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from fem.output.figures.steady import plot_phase_portraits
from validation.analytic.seed002_literal import literal_orbit
from validation.cases.steady_seed002_portraits import package_orbit

POINTS = (("simple", 0.755, "Fig. 2b"), ("combined", 0.66, "Fig. 3b"))
A = 4.7e-4


def main(out: str | Path = "docs/img/seed002_phase_portraits.png") -> dict:
    panels, tmin = [], {}
    for friction, z, fig in POINTS:
        lit = literal_orbit(friction, A, z)
        panels.append({"title": f"{fig}: {friction} friction, z = {z} -- literal reading (switch on phi < 0)",
                       "phi": lit["phi"] - lit["phi_s"], "phidot": lit["phidot"], "slack": lit["phi"] < 0,
                       "xlabel": "phi - phi_static [rad]"})
        tmin[f"{fig} literal"] = float(lit["force"].min())
        pk = package_orbit(friction, A, z)
        panels.append({"title": f"{fig}: {friction} friction, z = {z} -- package reading (from rest)",
                       "phi": pk["phi"], "phidot": pk["phidot"], "slack": pk["tension"] <= 0,
                       "xlabel": "phi - phi_static [rad]"})
        tmin[f"{fig} package"] = float(pk["tension"].min())
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    plot_phase_portraits(panels, out)
    for k, v in tmin.items():
        print(f"{k:22s} min tension {v:9.3f} N")
    return tmin


if __name__ == "__main__":
    main(*sys.argv[1:])
