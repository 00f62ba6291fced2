"""Internal loads of a stepped shaft from Python: torque along a torsional shaft under a harmonic end torque.

A shaft clamped at the motor (x = 0): steel d = 50 mm over 0.6 m, a disc (J = 0.01 kg m^2) at the step,
aluminium d = 30 mm over 0.9 m; a harmonic torque T = 10 N m at the free end (x = 1.5 m) at 4000 rad/s,
between the first two natural frequencies.  Quadratic Lagrange elements (h = 2.5 cm).  The harmonic
response gives the complex twist amplitudes of every DOF; :func:`fem.loads.section_loads` turns them
into the torque along the shaft (both sides of the disc, where it jumps by -omega^2 J theta), and
:func:`fem.loads.support_reactions` into the torque the clamp must take.

    python examples/api_section_loads.py [OUT.json]

Prints the torque amplitudes; with OUT.json writes the section loads (``SectionLoads.to_dict()``).
tests/test_loads.py checks them against the exact wave solution per segment.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from fem import Material, PointAttachment, Section, Segment, ShaftModel, Support, assemble, harmonic_response
from fem.loads import section_loads, support_reactions
from fem.output.jsonio import write_json

STEEL = Material(E=2.1e11, G=8.1e10, rho=7850.0)
ALUMINIUM = Material(E=7.0e10, G=2.6e10, rho=2700.0)
DISC_INERTIA, END_TORQUE, OMEGA = 0.01, 10.0, 4000.0      # kg m^2, N m, rad/s
STATIONS = [0.0, 0.3, 0.6, 0.6, 1.05, 1.5]
SIDES = ["right", "right", "left", "right", "right", "left"]


def shaft(elements_per_metre: int = 40) -> ShaftModel:
    """The stepped torsion shaft with its disc, clamped at x = 0."""
    return ShaftModel("torsion", [Segment(0.6, round(0.6 * elements_per_metre), Section.circle(0.05), STEEL),
                                  Segment(0.9, round(0.9 * elements_per_metre), Section.circle(0.03), ALUMINIUM)],
                      supports=[Support(0.0, "clamped")], points=[PointAttachment(0.6, inertia=DISC_INERTIA)],
                      order=2, title="stepped torsion shaft with a disc")


def main(out: str | Path | None = None):
    """Torque amplitudes at ``STATIONS`` (complex, N m) and the clamp's reaction; JSON to ``out`` if given."""
    fe = assemble(shaft())
    s = fe.system
    F = np.zeros(s.n_dofs, complex)
    F[s.dof_index(field="theta", x=1.5)] = END_TORQUE
    Q = harmonic_response(s, [OMEGA], force=F).full[0]        # every DOF, q(t) = Re(Q e^{i omega t})
    torque = np.array([section_loads(fe, Q, omega=OMEGA, x=x, side=side)["torque"][0]
                       for x, side in zip(STATIONS, SIDES)])
    reaction = support_reactions(fe, Q, omega=OMEGA, force=F)["theta@x=0"]
    if out is not None:
        write_json(out, section_loads(fe, Q, omega=OMEGA).to_dict())
    return torque, complex(reaction)


if __name__ == "__main__":
    torque, reaction = main(sys.argv[1] if len(sys.argv) > 1 else None)
    for x, side, t in zip(STATIONS, SIDES, torque):
        print(f"T(x = {x:4.2f} m, {side:5s}) = {abs(t):9.4f} N m")
    print(f"clamp reaction: {abs(reaction):.4f} N m")
