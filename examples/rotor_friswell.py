"""Friswell et al. (2010), Example 5.9.1 and its variants, through the Python API of fem.rotor.

The rotor: a steel shaft 1.5 m long, 50 mm in diameter, two discs 70 mm thick (280 mm at 0.5 m,
350 mm at 1.0 m), short bearings at both ends.  Variants: isotropic bearings (5.9.1: 1 MN/m),
anisotropic (5.9.2: 1 and 0.8 MN/m), damped (5.9.5: 1 MN/m, 3 kN s/m), cross-coupled (5.9.4:
k_yz = 0.5 MN/m).  For each: the modes at 4000 rev/min; for the damped one a Campbell diagram
with its critical speeds, an unbalance response with API 684-style margins, the static sag; for a
seal whose cross-coupling grows with speed, the stability threshold.

    .venv/bin/python examples/rotor_friswell.py [OUTPUT_DIR]     # figures into OUTPUT_DIR if given

tests/test_rotor_example.py runs :func:`main` and asserts the numbers it returns.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from fem.rotor import (Bearing, Disc, Rotor, ShaftSegment, Unbalance, assemble_rotor, campbell, rotor_modes, rpm,
                       stability_threshold, static_deflection, to_rpm, unbalance_response)
from fem.sections import Material

STEEL = Material(E=211e9, G=81.2e9, rho=7810.0)
VARIANTS = {
    "isotropic (5.9.1)": {"kyy": 1e6, "kzz": 1e6},
    "anisotropic (5.9.2)": {"kyy": 1e6, "kzz": 0.8e6},
    "damped (5.9.5)": {"kyy": 1e6, "kzz": 1e6, "cyy": 3e3, "czz": 3e3},
    "cross-coupled (5.9.4)": {"kyy": 1e6, "kzz": 1e6, "kyz": 0.5e6},
}


def friswell(bearing: dict, elements: int = 6, dofs: str = "full", seal: Bearing | None = None) -> Rotor:
    discs = [Disc.from_geometry(0.5, 0.07, 0.28, 0.05, STEEL.rho, "disc 1"),
             Disc.from_geometry(1.0, 0.07, 0.35, 0.05, STEEL.rho, "disc 2")]
    bearings = [Bearing(0.0, **bearing), Bearing(1.5, **bearing)] + ([seal] if seal else [])
    return Rotor([ShaftSegment(1.5, elements, 0.05, STEEL)], discs=discs, bearings=bearings, dofs=dofs,
                 title="Friswell et al. Example 5.9.1")


def main(out_dir: str | None = None, verbose: bool = True) -> dict:
    say = print if verbose else (lambda *a, **k: None)
    out = {"modes_4000rpm": {}}
    for name, b in VARIANTS.items():
        m = rotor_modes(friswell(b), rpm(4000), 8)
        keep = ~m.rigid
        out["modes_4000rpm"][name] = {"omega_rad_s": m.omega_damped_rad_s[keep].tolist(),
                                      "log_decrement": m.log_decrement[keep].tolist(),
                                      "whirl": [w for w, k in zip(m.whirl, keep) if k],
                                      "kind": [c for c, k in zip(m.kind, keep) if k]}
        say(f"\n{name}: modes at 4000 rev/min")
        for w, ld, wh, kd in zip(m.omega_damped_rad_s[keep], m.log_decrement[keep], out["modes_4000rpm"][name]["whirl"],
                                 out["modes_4000rpm"][name]["kind"]):
            say(f"  {w:9.3f} rad/s  log dec {ld:+.4f}  {kd:8s} {wh}")

    # the damped rotor, refined: Campbell diagram, critical speeds, unbalance response, static sag
    damped = assemble_rotor(friswell(VARIANTS["damped (5.9.5)"], elements=24, dofs="lateral"))
    camp = campbell(damped, np.linspace(0.0, rpm(6000), 31), 6, orders=(1.0,))
    out["critical_speeds_rpm"] = [round(c.speed_rpm, 3) for c in camp.critical_speeds]
    out["critical_whirl"] = [c.whirl for c in camp.critical_speeds]
    out["backward_crossings_rpm"] = [round(c.speed_rpm, 3) for c in camp.backward_crossings]
    say("\ndamped rotor, 24 elements: synchronous critical speeds (forward whirl) "
        + ", ".join(f"{c.speed_rpm:.1f} rev/min" for c in camp.critical_speeds)
        + "; backward-whirl crossings (not excited by unbalance: isotropic bearings) "
        + ", ".join(f"{c.speed_rpm:.1f}" for c in camp.backward_crossings) + " rev/min")
    op = (rpm(3000), rpm(3600))
    resp = unbalance_response(damped, [Unbalance(1.0, 1e-4)], np.linspace(rpm(200), rpm(6000), 300),
                              operating_range=op)
    peaks = sorted((p for p in resp.peaks if p.probe == 1), key=lambda p: p.speed_rad_s)   # probe at disc 1 (0.5 m)
    out["peaks"] = [{"speed_rpm": to_rpm(p.speed_rad_s), "amplitude_um": p.amplitude * 1e6,
                     "AF": p.amplification_factor, "SM": p.separation_margin, "SM_required": p.required_margin,
                     "passes": p.passes} for p in peaks]
    for p in out["peaks"]:
        af = "n/a" if p["AF"] is None else f"{p['AF']:.2f}"
        req = "n/a" if p["SM_required"] is None else f"{p['SM_required']:.1f} %"
        say(f"  peak at {p['speed_rpm']:.1f} rev/min: {p['amplitude_um']:.2f} um, AF {af}, "
            f"separation margin {p['SM']:.1f} % (required {req}) -> "
            + {True: "ok", False: "FAILS", None: "no AF: not assessed"}[p["passes"]])
    st = static_deflection(damped)
    out["static_sag_um"] = float(-st.w.min() * 1e6)
    out["bearing_loads_n"] = np.hypot(*st.bearing_force.T).tolist()
    say(f"  static sag {out['static_sag_um']:.1f} um, bearing loads "
        + ", ".join(f"{f:.1f} N" for f in out["bearing_loads_n"]))

    # a seal at mid-span whose cross-coupling grows with speed (k_yz = -k_zy = 100 N s/m * Omega)
    top = rpm(12000)
    seal = Bearing(0.75, cyy=100.0, czz=100.0, kyz=[0.0, 100.0 * top], kzy=[0.0, -100.0 * top], speeds=[0.0, top],
                   name="seal")
    unstable = assemble_rotor(friswell(VARIANTS["damped (5.9.5)"], elements=24, dofs="lateral", seal=seal))
    stab = stability_threshold(unstable, top, 4, n_grid=25)
    out["threshold_rpm"] = None if stab.threshold_rad_s is None else to_rpm(stab.threshold_rad_s)
    out["threshold_whirl"] = stab.whirl
    if stab.threshold_rad_s is None:
        say("\nwith the seal: stable up to 12000 rev/min")
    else:
        say(f"\nwith the seal: stability threshold {out['threshold_rpm']:.1f} rev/min "
            f"({stab.whirl} whirl at {stab.frequency_rad_s:.2f} rad/s)")

    if out_dir:
        from fem.rotor import plots

        d = Path(out_dir)
        d.mkdir(parents=True, exist_ok=True)
        plots.plot_campbell(camp, d / "rotor_campbell.png", title="Friswell 5.9.5 (damped bearings), 24 elements",
                            operating_range=op)
        plots.plot_bode(resp, d / "rotor_bode.png", probes=[1, 2], title="unbalance 1e-4 kg m at disc 2")
        plots.plot_polar(resp, d / "rotor_polar.png", probe=1)
        i = int(np.argmin(np.abs(resp.speeds_rad_s - peaks[0].speed_rad_s))) if peaks else 0
        plots.plot_orbits(resp.response[i, resp.v_index], resp.response[i, resp.w_index], resp.node_x,
                          d / "rotor_orbits.png", nodes=range(0, resp.node_x.size, 4))
        plots.plot_static(st, d / "rotor_static.png")
        from fem.render import available
        from fem.rotor import render

        ok, why = available()
        if ok:      # 3D whirl pictures of the isotropic rotor at 4000 rev/min (modes 3 and 4: the second pair)
            iso = assemble_rotor(friswell(VARIANTS["isotropic (5.9.1)"], elements=24, dofs="lateral"))
            m = rotor_modes(iso, rpm(4000), 4)
            for r in range(4):
                if m.whirl[r] in ("backward", "forward") and r >= 2:
                    render.render_whirl(iso, m, r, d / f"rotor_whirl_{m.whirl[r]}.png")
            render.render_whirl_gif(iso, m, 3, d / "rotor_whirl.gif")
        else:
            say(f"no 3D pictures: {why}")
        say(f"figures written to {d}")
    return out


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
