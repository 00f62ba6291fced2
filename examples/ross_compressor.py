"""ROSS's compressor example imported (examples/ross_compressor.toml): modes at 4000 rev/min and the
Campbell diagram from rest to 11000 rev/min with the log decrements.

    python examples/ross_compressor.py [OUT_DIR]      # writes OUT_DIR/rotor_ross_compressor_campbell.png

The bearing and seal tables are ROSS's convention (``interpolation = "smoothing-spline"``,
``extrapolate = "continue"``: ROSS's smoothing spline, extrapolated below 4000 rev/min along its end
cubics as ROSS does; the warnings name each bearing and the speeds), so the diagram is ROSS's to
1e-8 (validation ``rotor-ross-compressor``).  The figure shows the lateral modes (the axial and
torsional lines are left out; ``drivefem campbell`` lists them all).  Four bearing modes are
overdamped (real eigenvalues) at low speed: drawn from where they oscillate; they have no critical
speed at rest, and their 1x crossings near 5000 rev/min carry log decrements of about 20.
"""
from __future__ import annotations

import sys
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def run(out_dir: Path | None = None):
    from fem.modelfile.build.rotor import rotor_model, speed_grid
    from fem.rotor import assemble_rotor, campbell, rotor_modes, rpm
    from fem.rotor.plots import plot_campbell
    from fem.study import Study

    study = Study.load(HERE / "ross_compressor.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")              # the extrapolation below the tables is declared
        rs = assemble_rotor(rotor_model(study.doc))
        modes = rotor_modes(rs, rpm(4000), 12)
        camp = campbell(rs, speed_grid(study.doc.campbell, "[campbell]"), 16, orders=(1.0,))
    keep = [j for j in range(camp.n_modes) if camp.kind[j] == "lateral"]
    shown = replace(camp, omega_damped_rad_s=camp.omega_damped_rad_s[:, keep],
                    natural_frequency_rad_s=camp.natural_frequency_rad_s[:, keep],
                    log_decrement=camp.log_decrement[:, keep], damping_ratio=camp.damping_ratio[:, keep],
                    whirl=[[row[j] for j in keep] for row in camp.whirl], kind=[camp.kind[j] for j in keep],
                    crossings=[replace(c, mode=keep.index(c.mode)) for c in camp.crossings
                                     if c.mode in keep])
    path = None
    if out_dir is not None:
        path = plot_campbell(shown, Path(out_dir) / "rotor_ross_compressor_campbell.png",
                             title=f"{study.title}; ROSS's tables, extrapolated below 4000 rev/min")
    return modes, camp, shown, path


def main(out_dir=None):
    """The demo's entry (``drivefem demo`` calls ``main(OUT_DIR)``): run, print the table, write the figure."""
    if out_dir is not None:
        Path(out_dir).mkdir(parents=True, exist_ok=True)
    m, c, shown, p = run(Path(out_dir) if out_dir is not None else None)
    lat = ~m.rigid & (m.omega_damped_rad_s > 0)
    print("4000 rev/min: damped frequencies [rad/s]", np.round(m.omega_damped_rad_s[lat], 4))
    print("              log decrements          ", np.round(m.log_decrement[lat], 4))
    for cs in shown.critical_speeds:
        print(f"critical speed {cs.speed_rpm:9.1f} rev/min, {cs.whirl} whirl, log dec {cs.log_decrement:.3f}")
    if p:
        print(f"wrote {p}")
    return m, c, shown, p


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
