"""A hybrid (FE + nonsmooth) simulation built in Python: the drill string of seed 000.

The model of examples/hybrid_drill_string.toml written with the Python API instead of a model file:
an FE torsional string (P2 elements, GJ = 50 N m^2 over L = 1 m, its own polar inertia 0.02 kg m^2,
1 % of the bit's), turned at its top at omega = 0.45 rad/s; the bit (a disc I = 2 kg m^2 at x = L)
under Coulomb friction M0 = 3 N m with breakaway M1 = 18 N m and seed 000's restick rule; the string
reduced by Craig-Bampton to 4 fixed-interface modes; the exact event-driven solver over 40 s.

    python examples/api_hybrid_drill_string.py [OUT.json]

Prints the stick-slip period (the mean breakaway-to-breakaway time of the last cycles) and the
velocity reversals per cycle; with OUT.json writes the run (``HybridResult.to_dict()``) there.
tests/test_python_examples.py checks that this run is the model file's run, and its period against
seed 000's one-mass period (20) and its first-order correction for the string's inertia.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from discrete.nonsmooth import Friction, MotionLaw
from fem import Material, PointAttachment, Section, Segment, ShaftModel, assemble
from fem.hybrid import DriverSpec, ElementSpec, HybridModel, HybridResult, NodeRef, ReductionSpec, run
from fem.output.jsonio import write_json

GJ, L, RHO_IP = 50.0, 1.0, 0.02          # N m^2, m, kg m^2/m: c = GJ/L = 50 N m/rad
I_BIT, M0, M1, OMEGA = 2.0, 3.0, 18.0, 0.45
T_END = 40.0


def drill_string() -> HybridModel:
    """FE string (driven top, bit disc at the bottom) + the bit's friction + the reduction."""
    string = ShaftModel("torsion", [Segment(L, 8, Section.explicit(A=1.0, I=0.5, J=1.0, Ip=1.0),
                                            Material(E=130.0, G=GJ, rho=RHO_IP))],
                        points=[PointAttachment(x=L, inertia=I_BIT)], order=2, title="drill string")
    bit = NodeRef(x=L, dof="theta")
    return HybridModel(
        fe=assemble(string),
        drivers=[DriverSpec(NodeRef(x=0.0, dof="theta"), MotionLaw(velocity=OMEGA))],
        elements=[ElementSpec(Friction, dict(name="bit", kinetic=M0, static=M1, restick="kinetic"), [(bit, 1.0)])],
        reduction=ReductionSpec(modes=4, static_correction=True),
        title="drill string: FE torsional shaft + bit with stick-slip friction")


@dataclass
class DrillStringRun:
    """The run and its stick-slip cycle: ``period`` the mean of the last ``cycles`` breakaway-to-breakaway
    intervals (s), ``scatter`` their max - min, ``reversals_per_cycle`` over those cycles."""

    result: HybridResult
    period: float
    scatter: float
    reversals_per_cycle: float
    cycles: int

    def to_dict(self) -> dict:
        return {"period_s": self.period, "scatter_s": self.scatter, "reversals_per_cycle": self.reversals_per_cycle,
                "cycles": self.cycles, "run": self.result.to_dict()}


def stick_slip_cycle(result: HybridResult, cycles: int = 3) -> DrillStringRun:
    """Period, scatter and reversals per cycle from the slip (breakaway) events of the bit."""
    slips = np.array([e.t for e in result.events if e.kind == "slip"])
    if slips.size <= cycles:
        raise ValueError(f"only {slips.size} breakaways in {result.t_end:g} s: run longer for {cycles} cycles")
    intervals = np.diff(slips)[-cycles:]
    first, last = slips[-cycles - 1], slips[-1]
    reversals = sum(1 for e in result.events if e.kind == "reversal" and first < e.t < last)
    return DrillStringRun(result, float(intervals.mean()), float(intervals.max() - intervals.min()),
                          reversals / cycles, cycles)


def main(out: str | Path | None = None, t_end: float = T_END) -> DrillStringRun:
    """Build and run the drill string for ``t_end`` s; write the run to ``out`` (JSON) if given."""
    cycle = stick_slip_cycle(run(drill_string(), {"t_end": t_end, "method": "event"}))
    if out is not None:
        write_json(out, cycle.to_dict())
    return cycle


if __name__ == "__main__":
    c = main(*sys.argv[1:2])
    print(f"stick-slip period {c.period:.6f} s (scatter {c.scatter:.1e} s over {c.cycles} cycles), "
          f"{c.reversals_per_cycle:g} velocity reversals per cycle, energy error {c.result.energy_error:.1e}")
