"""Amplitude-frequency curve of a dry-friction oscillator from a model written as a Python dict.

Den Hartog's problem: a unit mass on a unit spring with Coulomb friction P = 0.3 under the force
sin(omega t), continued in omega from 1.2 to 2.0 (above resonance; without viscous damping the
amplitude grows without bound at omega = 1 while P < pi/4, and below about omega = 0.5 the mass
sticks at its turning points, where Den Hartog's closed form no longer holds).  Each point is a
periodic orbit found by shooting with the exact event-driven integrator (true stick-slip law, no
smoothing) and its Floquet multipliers; the curve is continued by pseudo-arc-length.  The dict is what a model file would hold; ``fem.study.forced`` runs
its ``steady`` table.

    python examples/api_afc_coulomb.py [OUT.json]

Prints the curve; with OUT.json writes it (``AFCResult.to_dict()``) there.  tests/test_python_examples.py
checks every point against Den Hartog's exact closed form (validation/analytic/steady_refs.py).
"""
from __future__ import annotations

import sys
from pathlib import Path

from discrete.steady import AFCResult
from fem.output.jsonio import write_json
from fem.study import forced

MASS, STIFFNESS, FRICTION, FORCE = 1.0, 1.0, 0.3, 1.0
OMEGA_RANGE = (1.2, 2.0)


def model(omega_range=OMEGA_RANGE) -> dict:
    """The oscillator and its [steady] table (shooting over ``omega_range``, response: half the
    peak-to-peak displacement of the mass)."""
    return {
        "title": "Coulomb oscillator under harmonic force (Den Hartog)",
        "body": [{"name": "mass", "inertia": MASS}],
        "spring": [{"between": ["ground", "mass"], "k": STIFFNESS}],
        "friction": [{"name": "dry", "body": "mass", "kinetic": FRICTION}],
        "force": [{"body": "mass", "amplitude": FORCE, "omega": omega_range[0]}],
        "steady": {"method": "shooting", "omega": list(omega_range),
                   "response": {"body": "mass", "measure": "amplitude"}},
    }


def main(out: str | Path | None = None) -> AFCResult:
    """The amplitude-frequency curve; written to ``out`` (JSON) if given."""
    curve = forced(model())
    if out is not None:
        write_json(out, curve.to_dict())
    return curve


if __name__ == "__main__":
    print(main(*sys.argv[1:2]).table())
