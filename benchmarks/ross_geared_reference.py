"""Stored ROSS reference numbers for the geared-train validation (validation/cases/geared.py, case
geared-lateral-torsional-ross).

Runs in ROSS's own environment (it imports ROSS, never drivefem):

    ROSS_ENV=/work/ross-env bash benchmarks/ross_env.sh              # ROSS 2.3.0 (pinned)
    /work/ross-env/bin/python benchmarks/ross_geared_reference.py   # -> validation/data/ross/geared.json

ROSS's MultiRotor example ``ross.multi_rotor.two_shaft_rotor_example`` (Rao, Shiau & Chang, Mech. Mach.
Theory 33 (1998) 761: a turbo-alternator, generator rotor and turbine rotor joined by a spur gear pair,
mesh stiffness 1e8 N/m, pressure angle 22.5 deg, orientation angle 0) is built as ROSS ships it, and
its complex eigenvalues (``run_modal(speed, sparse=False)``: all of them) are stored at a few speeds of
the driving rotor, with the model's data (shafts, discs, gears, bearings, the mesh) so that the drivefem
side can build the same model without ROSS, and ROSS's gear coupling matrix (``coupling_matrix()``,
Stringer 2008) for the statement of conventions.
"""
from __future__ import annotations

import datetime
import json
import sys
import warnings
from pathlib import Path

warnings.filterwarnings("ignore")
import numpy as np  # noqa: E402
import scipy  # noqa: E402
import ross as rs  # noqa: E402
from ross.multi_rotor import two_shaft_rotor_example  # noqa: E402

OUT = Path(__file__).resolve().parent.parent / "validation" / "data" / "ross" / "geared.json"
SPEEDS = (0.0, 100.0, 250.0, 500.0)


def element_data(mr) -> dict:
    """The model as ROSS holds it (SI units, ROSS's axes: x, y lateral, z axial)."""
    R1, R2 = mr.rotors["driving"], mr.rotors["driven"]

    def rotor(R):
        return {"shaft": [{"L": float(e.L), "odl": float(e.odl), "idl": float(e.idl), "E": float(e.material.E),
                           "G_s": float(e.material.G_s), "rho": float(e.material.rho), "n": int(e.n)}
                          for e in R.shaft_elements],
                "discs": [{"n": int(d.n), "m": float(d.m), "Id": float(d.Id), "Ip": float(d.Ip),
                           "gear": "GearElement" in type(d).__name__} for d in R.disk_elements],
                "bearings": [{"n": int(b.n), "kxx": float(np.ravel(b.kxx)[0]), "kyy": float(np.ravel(b.kyy)[0]),
                              "cxx": float(np.ravel(b.cxx)[0]), "cyy": float(np.ravel(b.cyy)[0]),
                              "kxy": float(np.ravel(b.kxy)[0]), "kyx": float(np.ravel(b.kyx)[0])}
                             for b in R.bearing_elements]}
    g1, g2 = mr.mesh.driving_gear, mr.mesh.driven_gear
    return {"driving": rotor(R1), "driven": rotor(R2),
            "mesh": {"stiffness": float(mr.mesh.stiffness), "gear_ratio": float(mr.mesh.gear_ratio),
                     "pressure_angle": float(mr.mesh.pressure_angle), "helix_angle": float(mr.mesh.helix_angle),
                     "orientation_angle": float(mr.orientation_angle),
                     "driving": {"n": int(g1.n), "n_teeth": int(g1.n_teeth), "base_radius": float(g1.base_radius),
                                 "pitch_diameter": float(g1.pitch_diameter)},
                     "driven": {"n": int(g2.n), "n_teeth": int(g2.n_teeth), "base_radius": float(g2.base_radius),
                                "pitch_diameter": float(g2.pitch_diameter)}}}


def main() -> None:
    mr = two_shaft_rotor_example()
    out = {"provenance": {"ross": rs.__version__, "numpy": np.__version__, "scipy": scipy.__version__,
                          "python": sys.version.split()[0], "date": datetime.date.today().isoformat(),
                          "script": "benchmarks/ross_geared_reference.py",
                          "model": "ross.multi_rotor.two_shaft_rotor_example (Rao, Shiau & Chang 1998)"},
           "model": element_data(mr), "ndof": int(mr.ndof),
           "coupling_matrix": np.asarray(mr.coupling_matrix()).tolist(), "modal": []}
    for speed in SPEEDS:
        m = mr.run_modal(speed, sparse=False)
        lam = np.asarray(m.evalues)
        out["modal"].append({"speed": speed, "evalues_re": lam.real.tolist(), "evalues_im": lam.imag.tolist(),
                             "wd": np.asarray(m.wd).tolist(), "log_dec": np.asarray(m.log_dec).tolist()})
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
