"""Stored ROSS reference numbers for the validation cases of the ROSS import (validation/cases/rotor_ross.py).

Runs in ROSS's own environment (it imports ROSS, never drivefem):

    ROSS_ENV=/work/ross-env bash benchmarks/ross_env.sh         # ROSS 2.3.0 (pinned)
    /work/ross-env/bin/python benchmarks/ross_reference.py      # -> validation/data/ross/

and writes, with their provenance (ROSS, numpy, scipy versions, date, this script):

* ``friswell_<variant>.toml``: Friswell et al. (2010) Example 5.9.1's rotor built in ROSS (6 equal
  Timoshenko elements, discs of 280 and 350 mm at 0.5 and 1.0 m, bearings at the ends) in the four
  variants of benchmarks/rotor.py, saved by ROSS's ``Rotor.save`` -- the files drivefem converts;
* ``friswell.json``: ROSS's results on them: complex modes at 4000 rev/min, a Campbell diagram,
  critical speeds (``run_critical_speed`` with rtol 1e-13) and the unbalance response at disc 2;
* ``compressor_example.toml``: the compressor example shipped in ROSS's wheel (a copy);
* ``compressor.json``: ROSS's modes at 4000 rev/min of that rotor as it is (ROSS's smoothing-spline
  tables) and with every bearing and seal held at its table values at 4000 rev/min ("the same table
  values": a table point of every table); its Campbell diagram from 0 to 11000 rev/min (21 speeds)
  and the coefficients ROSS used at each of those speeds (its spline, extrapolated below 4000 rev/min).
"""
from __future__ import annotations

import datetime
import json
import shutil
import sys
import warnings
from pathlib import Path

warnings.filterwarnings("ignore")
import numpy as np  # noqa: E402
import scipy  # noqa: E402
import ross as rs  # noqa: E402

OUT = Path(__file__).resolve().parent.parent / "validation" / "data" / "ross"
SPEED = 4000 * np.pi / 30
VARIANTS = {
    "isotropic": {"kxx": 1e6, "kyy": 1e6},
    "anisotropic": {"kxx": 1e6, "kyy": 0.8e6},
    "damped": {"kxx": 1e6, "kyy": 1e6, "cxx": 3e3, "cyy": 3e3},
    "cross-coupled": {"kxx": 1e6, "kyy": 1e6, "kxy": 0.5e6},
}
COEFFS = ("kxx", "kyy", "kxy", "kyx", "cxx", "cyy", "cxy", "cyx")


def modes(rotor, speed, n):
    m = rotor.run_modal(speed, num_modes=2 * n)
    return {"evalues_re": np.real(m.evalues).tolist(), "evalues_im": np.imag(m.evalues).tolist(),
            "wd": np.asarray(m.wd).tolist(), "wn": np.asarray(m.wn).tolist(), "log_dec": np.asarray(m.log_dec).tolist()}


def friswell(out: dict) -> None:
    steel = rs.Material(name="steel_friswell", rho=7810.0, E=211e9, G_s=81.2e9)
    n = 6
    for var, bearing in VARIANTS.items():
        shaft = [rs.ShaftElement(L=1.5 / n, idl=0.0, odl=0.05, material=steel) for _ in range(n)]
        discs = [rs.DiskElement.from_geometry(n=2, material=steel, width=0.07, i_d=0.05, o_d=0.28),
                 rs.DiskElement.from_geometry(n=4, material=steel, width=0.07, i_d=0.05, o_d=0.35)]
        kw = dict(bearing)
        kw.setdefault("cxx", 0.0)
        rotor = rs.Rotor(shaft, discs, [rs.BearingElement(n=0, **kw), rs.BearingElement(n=n, **kw)])
        path = OUT / f"friswell_{var}.toml"
        path.unlink(missing_ok=True)
        rotor.save(path)
        rec = {"file": path.name, "modal_4000rpm": modes(rotor, SPEED, 12)}
        speeds = np.linspace(0.0, 4500 * np.pi / 30, 10)
        camp = rotor.run_campbell(speeds, frequencies=8)
        rec["campbell"] = {"speeds": speeds.tolist(), "wd": np.asarray(camp.wd).tolist(),
                           "log_dec": np.asarray(camp.log_dec).tolist()}
        crit = rotor.run_critical_speed(num_modes=12, rtol=1e-13)
        rec["critical"] = {"wn": np.asarray(crit.wn()).tolist(), "wd": np.asarray(crit.wd()).tolist()}
        freq = np.linspace(20.0, 4500 * np.pi / 30, 40)
        resp = rotor.run_unbalance_response(4, 1e-4, 0.0, freq)
        fr = np.asarray(resp.forced_resp)
        probes = {}
        for node in (2, 4):
            probes[str(node)] = {"x_re": fr[6 * node].real.tolist(), "x_im": fr[6 * node].imag.tolist(),
                                 "y_re": fr[6 * node + 1].real.tolist(), "y_im": fr[6 * node + 1].imag.tolist()}
        rec["unbalance"] = {"node": 4, "magnitude": 1e-4, "phase": 0.0, "speeds": freq.tolist(), "probes": probes}
        out[var] = rec


def compressor(out: dict) -> None:
    src = Path(rs.__file__).parent / "tests" / "data" / "compressor_example.toml"
    shutil.copyfile(src, OUT / "compressor_example.toml")
    rotor = rs.Rotor.load(src)
    out["file"] = "compressor_example.toml"
    out["modal_4000rpm_as_is"] = modes(rotor, SPEED, 12)
    # every table at its table values at 4000 rev/min (a point of every table), held constant
    held = []
    for b in rotor.bearing_elements:
        j = int(np.argmin(np.abs(np.asarray(b.frequency) - SPEED)))
        assert abs(b.frequency[j] - SPEED) < 1e-9 * SPEED, (b.tag, b.frequency)
        kw = {c: float(np.asarray(getattr(b, c))[j]) for c in COEFFS}
        held.append(rs.BearingElement(n=b.n, tag=b.tag, **kw))
    same = rs.Rotor(rotor.shaft_elements, rotor.disk_elements, held, rotor.point_mass_elements)
    out["modal_4000rpm_table_values"] = modes(same, SPEED, 12)
    speeds = np.linspace(0.0, 11000 * np.pi / 30, 21)
    camp = rotor.run_campbell(speeds, frequencies=8)
    out["campbell"] = {"speeds": speeds.tolist(), "wd": np.asarray(camp.wd).tolist(),
                       "log_dec": np.asarray(camp.log_dec).tolist()}
    out["campbell_modes"] = [modes(rotor, float(s), 8) for s in speeds]
    out["coefficients"] = {b.tag: {c: np.asarray(getattr(b, f"{c}_interpolated")(speeds), float).tolist() for c in COEFFS}
                           for b in rotor.bearing_elements}


def main() -> int:
    OUT.mkdir(parents=True, exist_ok=True)
    provenance = {"ross": rs.__version__, "numpy": np.__version__, "scipy": scipy.__version__,
                  "python": sys.version.split()[0], "date": datetime.datetime.now(datetime.timezone.utc).isoformat(
                      timespec="seconds"), "script": "benchmarks/ross_reference.py",
                  "licence": "ROSS is MIT licensed (ross-rotordynamics); its compressor example is copied unchanged"}
    if rs.__version__ != "2.3.0":
        print(f"warning: ROSS {rs.__version__}; the stored references were made with 2.3.0", file=sys.stderr)
    fr = {"provenance": provenance}
    friswell(fr)
    (OUT / "friswell.json").write_text(json.dumps(fr, indent=1))
    comp = {"provenance": provenance}
    compressor(comp)
    (OUT / "compressor.json").write_text(json.dumps(comp, indent=1))
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
