"""Design of a dynamic vibration absorber (textbook §6.5) and its check with the package's solvers.

A machine of m1 = 100 kg on isolators c1 = 1e6 N/m (k = 100 rad/s) is driven at omega* = 95 rad/s by an
unbalance force of amplitude F1 = 500 N (close to resonance).  The absorber is tuned to omega* by (6.30)
with the lightest mass whose stroke F1/c2 stays within 5 mm.  The amplitude-frequency curves without
absorber, with it, and with a damper b between the masses (Fig. 6.10) are computed by harmonic_response
of the assembled LumpedModel; the force on the foundation by element_forces (discrete.linear.reactions).

    python examples/absorber_design.py [OUT_DIR]      (default drivefem-demo/absorber_design)

Writes absorber_design.json and absorber_afc.png.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from discrete.linear.harmonic import harmonic_response
from discrete.linear.modal import modal_analysis
from discrete.linear.reactions import element_forces, lumped_links
from discrete.lumped import Body, Link, LumpedModel
from discrete.protection import Absorber
from fem.output.figures.protection import plot_amplitude_curves

M1, C1, OMEGA_STAR, F1, STROKE, B = 100.0, 1.0e6, 95.0, 500.0, 0.005, 60.0
PSI1 = 0.2     # dissipation coefficient of the isolators (hysteretic, delta = psi/(4 pi) = 0.016)


def _with_isolator_damping(model: LumpedModel) -> LumpedModel:
    model.springs[0].psi = PSI1          # springs[0] is ground-main in every model below
    return model


def _afc(model: LumpedModel, omegas):
    ls = model.linear_system()
    F = np.zeros(ls.n_dofs)
    F[ls.dof_index(name="main")] = F1
    r = harmonic_response(ls, omegas, force=F)
    P = element_forces(lumped_links(model), omegas, r.response)
    return np.abs(r.response[:, ls.dof_index(name="main")]), np.abs(P.foundation), r, ls


def main(out_dir: str | Path = "drivefem-demo/absorber_design") -> dict:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    a = Absorber.design(M1, C1, OMEGA_STAR, F1, STROKE)
    damped = Absorber(a.m1, a.c1, a.m2, a.c2, b=B)
    bare = _with_isolator_damping(LumpedModel(bodies=[Body("main", M1)], springs=[Link(("ground", "main"), C1)]))
    w = np.linspace(60.0, 140.0, 401)
    A0, R0, _, _ = _afc(bare, w)
    A1, R1, _, ls = _afc(_with_isolator_damping(a.lumped_model()), w)
    A2, R2, _, _ = _afc(_with_isolator_damping(damped.lumped_model()), w)
    Astar, Rstar, rs, _ = _afc(_with_isolator_damping(a.lumped_model()), [OMEGA_STAR])
    A0star = _afc(bare, [OMEGA_STAR])[0]
    modal = modal_analysis(ls, 2)
    result = {
        "absorber": a.to_dict(), "damper_b": B,
        "modal_frequencies": modal.omega_rad_s.tolist(),
        "A1_at_omega_star": float(Astar[0]), "A2_at_omega_star": float(abs(rs.response[0, 1])),
        "foundation_force_at_omega_star": float(Rstar[0]),
        "A1_without_absorber_at_omega_star": float(A0star[0]),
        "peak_A1_without_absorber": float(A0.max()),
        "peak_A1_with_absorber": float(A1.max()), "peak_A1_with_damper": float(A2.max()),
        "A1_with_damper_at_omega_star": float(A2[np.argmin(np.abs(w - OMEGA_STAR))]),
    }
    fig = plot_amplitude_curves(w, {"no absorber (1)": A0, "tuned absorber (2)": A1, f"absorber + damper b = {B:g} (3)": A2},
                                out / "absorber_afc.png", ylabel="|A1| [m]",
                                marks={"omega*": OMEGA_STAR, "k1": a.natural_frequencies()[0], "k2": a.natural_frequencies()[1]},
                                title=f"m1 = {M1:g} kg, c1 = {C1:g} N/m, absorber m2 = {a.m2:.3g} kg, c2 = {a.c2:.3g} N/m")
    result["figures"] = [str(fig)]
    (out / "absorber_design.json").write_text(json.dumps(result, indent=1))
    return result


if __name__ == "__main__":
    r = main(*sys.argv[1:2])
    print(json.dumps({k: v for k, v in r.items() if k != "figures"}, indent=1))
