"""The figure of docs/hybrid.md "Amplitude-frequency curves of hybrid models": the [steady] curves of
examples/hybrid_afc_vibro_impact.toml and examples/hybrid_afc_friction_rod.toml (harmonic balance,
continued in the forcing frequency, Floquet stability), long time simulations of the same models at a
few frequencies (markers), and the 1-DOF estimates of mode 1 (dotted).

    python examples/hybrid_afc_figure.py [docs/img/hybrid_afc_curves.png]

About 20 s.  The numbers are those of the validation cases hybrid_afc_vibro_impact and
hybrid_afc_friction_rod (drivefem validate --case hybrid).
"""
from __future__ import annotations

import copy
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from discrete.linalg import single_threaded_blas  # noqa: E402
from discrete.linear import modal_analysis  # noqa: E402
from fem.modelfile.source import read_toml  # noqa: E402
from fem.output.figures.steady import plot_afc  # noqa: E402
from fem.study import Study  # noqa: E402
from validation.analytic.hybrid_afc_refs import den_hartog_damped, first_mode_sdof  # noqa: E402

EXAMPLES = ROOT / "examples"


def simulated(doc: dict, omega: float, periods: int, measure) -> float:
    """``measure(result, T)`` of a simulation of ``doc`` at forcing frequency ``omega`` (from its [initial])."""
    d = copy.deepcopy(doc)
    d.pop("steady", None)
    for f in d["force"]:
        f["omega"] = omega
    T = 2 * math.pi / omega
    d["simulation"] = {"t_end": periods * T, "output_step": T / 500}
    return measure(Study.parse(d).simulate(), T)


def stop_force(res, T):
    t, F = res.element_force("stop")
    last = t >= t[-1] - 3 * T
    return float(np.max(np.abs(F[last])))


def tip_amplitude(res, T):
    s = res.solver
    x = s.x[s.names.index("u@x=1")]
    last = s.t >= s.t[-1] - 5 * T
    return 0.5 * float(np.ptp(x[last]))


def main(out: str | Path = "docs/img/hybrid_afc_curves.png") -> Path:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.6))
    with single_threaded_blas():
        # cantilever with a stop: curve, simulations below the hysteresis, 1-DOF of mode 1 at the stop
        doc = read_toml(EXAMPLES / "hybrid_afc_vibro_impact.toml")
        st = Study.parse(copy.deepcopy(doc))
        r = st.forced()
        plot_afc(r, None, ax=a1, label="FE model, HB 25 harmonics")
        ws = (300.0, 330.0, 350.0, 370.0, 380.0)
        a1.plot(ws, [simulated(doc, w, 90, stop_force) for w in ws], "ks", ms=5, mfc="none",
                label="time simulation (exact, event-driven)")
        S = st.compiled.system
        ja, jt = S.dof_index(field="w", x=0.45), S.dof_index(field="w", x=0.5)
        m = first_mode_sdof(S, ja, modal_analysis(S, 2))
        sdof = {"title": "mode 1 referred to the stop", "body": [{"name": "s", "inertia": m.m1}],
                "spring": [{"between": ["ground", "s"], "k": m.k1}], "damper": [{"between": ["ground", "s"], "c": m.c1}],
                "gap": [{"name": "stop", "body": "s", "upper": doc["gap"][0]["upper"], "k": doc["gap"][0]["k"]}],
                "force": [{"body": "s", "amplitude": doc["force"][0]["amplitude"] * m.ratio(jt), "omega": 300.0}],
                "steady": {**doc["steady"], "omega": [250.0, 450.0], "stability": False, "ds_max": 0.05}}
        r1 = Study.parse(sdof).forced()
        a1.plot(r1.omega, r1.response, ":", color="0.3", lw=1.4, label="1-DOF (mode 1 at the stop)")
        a1.set_xlabel("forcing frequency omega [rad/s]")
        a1.set_ylabel("peak stop force [N]")
        a1.set_title("cantilever, elastic stop 1 mm above x = 0.45 m, tip force 10 N", fontsize=10)
        # friction rod: curve, simulations, Den Hartog's exact 1-DOF solution of mode 1 at the tip
        doc = read_toml(EXAMPLES / "hybrid_afc_friction_rod.toml")
        st = Study.parse(copy.deepcopy(doc))
        r = st.forced()
        plot_afc(r, None, ax=a2, label="FE model, HB 15 harmonics (tanh friction)")
        w1 = doc["steady"]["omega_ref"]
        zs = (0.87, 0.92, 0.96, 1.0, 1.04, 1.08, 1.13)
        a2.plot(zs, [simulated(doc, z * w1, 150, tip_amplitude) / 1e-6 for z in zs], "ks", ms=5, mfc="none",
                label="time simulation (exact stick-slip)")
        S = st.compiled.system
        m = first_mode_sdof(S, S.dof_index(field="u", x=1.0), modal_analysis(S, 2))
        zz = np.linspace(0.85, 1.15, 301)
        X = [den_hartog_damped(m.m1, m.k1, m.c1, doc["friction"][0]["kinetic"], doc["force"][0]["amplitude"], z * w1)
             for z in zz]
        a2.plot(zz, np.array(X) / 1e-6, ":", color="0.3", lw=1.4, label="1-DOF: Den Hartog (mode 1 at the tip)")
        a2.set_xlabel("z = omega / omega_1 [-]")
        a2.set_ylabel("tip amplitude [um]")
        a2.set_title("rod, dry-friction damper 40 N and force 100 N at the tip", fontsize=10)
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


if __name__ == "__main__":
    print("wrote", main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "img" / "hybrid_afc_curves.png"))
