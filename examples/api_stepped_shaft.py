"""Natural frequencies of a stepped shaft built in Python (no model file): the FE model API.

A cantilever in bending with two steps -- steel d = 60 mm over 0.4 m, a steel tube 80/50 mm over
0.6 m, an aluminium journal d = 40 mm over 0.3 m -- on an elastic bearing k = 2e6 N/m at the last
step (x = 1.0 m), with a disc (5 kg, diametral inertia 0.01 kg m^2) at the free end x = 1.3 m.
Euler-Bernoulli Hermite elements (h = 5 cm), consistent mass; the lowest four bending modes by the
sparse shift-invert eigen-solver.

    python examples/api_stepped_shaft.py [OUT.json]

Prints the frequencies; with OUT.json writes the modal result (``ModalResult.to_dict()``) there.
tests/test_python_examples.py checks them against the roots of the exact transfer-matrix
frequency equation of the same stepped beam.
"""
from __future__ import annotations

import sys
from pathlib import Path

from fem import Material, PointAttachment, Section, Segment, ShaftModel, Support, assemble, modal_analysis
from fem.output.jsonio import write_json

STEEL = Material(E=2.1e11, G=8.1e10, rho=7850.0)
ALUMINIUM = Material(E=7.0e10, G=2.6e10, rho=2700.0)
BEARING_K = 2.0e6      # N/m, translational stiffness of the bearing at x = 1.0 m
DISC_MASS, DISC_INERTIA = 5.0, 0.01      # kg, kg m^2 (diametral) at the free end
N_MODES = 4


def stepped_shaft(elements_per_metre: int = 20) -> ShaftModel:
    """The shaft: segments (length, elements, section, material), supports and the end disc."""
    def n(length: float) -> int:
        return max(1, round(length * elements_per_metre))

    segments = [Segment(0.4, n(0.4), Section.circle(0.06), STEEL),
                Segment(0.6, n(0.6), Section.tube(0.08, 0.05), STEEL),
                Segment(0.3, n(0.3), Section.circle(0.04), ALUMINIUM)]
    return ShaftModel("bending", segments,
                      supports=[Support(0.0, "clamped"), Support(1.0, "spring", k=BEARING_K)],
                      points=[PointAttachment(x=1.3, mass=DISC_MASS, inertia=DISC_INERTIA)],
                      theory="euler-bernoulli", mass="consistent",
                      title="stepped cantilever on a bearing with an end disc")


def main(out: str | Path | None = None, n_modes: int = N_MODES):
    """Assemble the stepped shaft, solve its lowest ``n_modes`` modes; write them to ``out`` (JSON) if given."""
    fe = assemble(stepped_shaft())
    result = modal_analysis(fe.system, n_modes)
    if out is not None:
        write_json(out, result.to_dict())
    return result


if __name__ == "__main__":
    res = main(*sys.argv[1:2])
    for r, (w, f, ok) in enumerate(zip(res.omega_rad_s, res.frequencies_hz, res.reliable), 1):
        print(f"mode {r}: {w:12.4f} rad/s  {f:10.4f} Hz{'' if ok else '  (NOT RELIABLE)'}")
