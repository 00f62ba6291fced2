"""What internal loads cost next to the analysis they come from (fem.loads, docs/loads.md).

Three analyses, each timed interleaved with the section-load recovery of its result (benchmarks/common.py:
medians of the rounds, spread, wall and process-CPU time).  The ratio is analysis time / recovery time
(how many recoveries fit in one analysis); target >= 2, i.e. the loads add at most half of the analysis:

* forced response of a stepped Euler-Bernoulli shaft (399 Hermite elements, 200 frequencies, direct
  sparse solves) against ``section_loads`` at both ends of every element for every frequency;
* unbalance response of the shipped compressor rotor (examples/rotor_compressor.toml, its speed grid)
  against ``rotor_section_loads`` at every element end for every speed;
* the Craig-Bampton hybrid drill string (examples/hybrid_drill_string.toml, 12 s of stick-slip) against
  ``Study.outputs`` (all its named outputs: the drive's element loads and reactions, and the section loads
  at the default stations over every recorded instant, the drive's accelerations).

The element matrices of a model are built once and cached with it (their first build is printed).

    python benchmarks/loads.py [--runs 5]
"""
from __future__ import annotations

import argparse
import sys
import time
import tomllib
from pathlib import Path

import common

common.limit_blas_threads(1)

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from discrete.linear import harmonic_response  # noqa: E402
from fem import Material, Section, Segment, ShaftModel, Support, assemble  # noqa: E402
from fem.loads import elements_of, rotor_section_loads, section_loads  # noqa: E402
from fem.study import Study  # noqa: E402

TARGET = 2.0
EXAMPLES = common.ROOT / "examples"


def stepped_beam(n: int) -> ShaftModel:
    steel = Material(2.1e11, 8.1e10, 7850.0)
    segs = [Segment(0.6, n // 3, Section.circle(0.06), steel, psi=0.1),    # n = 3 k: nodes every 1.8/n m
            Segment(1.2, n - n // 3, Section.circle(0.04), steel)]
    return ShaftModel("bending", segs, [Support(0.0, "clamped"), Support(1.8, "pinned")])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5)
    a = ap.parse_args(argv)
    common.header(__file__, "internal loads against the analyses they come from")
    recs = []

    # ------------------------------------------------------------ FE forced response
    fe = assemble(stepped_beam(399))
    s = fe.system
    F = np.zeros(s.n_dofs, complex)
    F[s.dof_index(field="w", x=0.6)] = 100.0
    omegas = np.linspace(10.0, 4000.0, 200)
    t0 = time.perf_counter()
    elements_of(fe)
    print(f"FE: element matrices of {fe.mesh.n_elements} Hermite elements built once in {time.perf_counter() - t0:.3f} s")
    Q = harmonic_response(s, omegas, force=F).full.T
    tm = common.interleaved({"harmonic response": lambda: harmonic_response(s, omegas, force=F),
                             "section loads": lambda: section_loads(fe, Q, omega=omegas)}, runs=a.runs, warmup=1)
    recs.append(_record(tm, "harmonic response", "FE forced: 399 Hermite elements, 200 frequencies", a.runs))

    # ------------------------------------------------------------ rotor unbalance response
    study = Study.load(EXAMPLES / "rotor_compressor.toml")
    rs = study.rotor
    res = study.forced()
    elements_of(rs)
    Qr, w = res.response.T, res.speeds_rad_s
    tm = common.interleaved({"unbalance response": study.forced,
                             "section loads": lambda: rotor_section_loads(rs, Qr, omega=w)}, runs=a.runs, warmup=1)
    recs.append(_record(tm, "unbalance response", f"rotor compressor: {rs.n_dofs} DOFs, {w.size} speeds", a.runs))

    # ------------------------------------------------------------ hybrid time history
    doc = tomllib.loads((EXAMPLES / "hybrid_drill_string.toml").read_text())
    doc["simulation"]["t_end"] = 12.0
    hybrid = Study.parse(doc)
    run = hybrid.simulate()
    hybrid.outputs(run)
    runs = max(3, a.runs // 2)
    tm = common.interleaved({"simulate": hybrid.simulate, "section loads": lambda: hybrid.outputs(run)},
                            runs=runs, warmup=0)
    recs.append(_record(tm, "simulate", f"hybrid drill string: 12 s, {run.solver.t.size} recorded instants", runs))
    return common.finish(recs)


def _record(tm, analysis: str, what: str, runs: int) -> dict:
    ratio, ratio_cpu = common.speedup(tm[analysis], tm["section loads"])
    for name, t in tm.items():
        print(f"  {what}: {name:<20} {t.line(1e3, 'ms')}")
    return common.record(__file__, f"internal loads, {what}", "section loads", analysis, ratio, (">=", TARGET),
                         metric="analysis time / loads time", ratio_cpu=ratio_cpu, runs=runs,
                         spread={n: t.spread_dict() for n, t in tm.items()})


if __name__ == "__main__":
    sys.exit(main())
