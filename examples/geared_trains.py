"""The figures of docs/geared.md from the geared-train examples (``python examples/geared_trains.py docs/img``):

* geared_two_stage_loads.png: examples/geared_two_stage.toml -- dynamic load factor of both meshes and the
  peak radial bearing forces over the motor speed (transmission error, meshes closed);
* geared_two_stage_rattle.png: the same drive in time at 1500 rev/min with its 60 um backlash (Craig-Bampton,
  4 modes per shaft) at the speed of the 2nd stage's largest dynamic load factor: mesh forces with the
  contact events;
* geared_compressor_campbell.png: examples/geared_compressor_train.toml -- Campbell diagram of the train
  (each shaft at its own speed) with 1x lines of every shaft and the tooth-pass line;
* geared_rattle_afc.png: examples/geared_rattle.toml -- the gear-rattle curve by HB (stable solid, unstable
  dashed), by shooting, and the exact piecewise-analytic orbits with the jump frequencies;
* geared_mesh_parametric.png: examples/geared_mesh_parametric.toml -- Floquet chart of the mesh-stiffness
  variation.

Returns the key numbers (asserted by tests/test_train.py)."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fem.modelfile.source import read_toml  # noqa: E402
from fem.study import Study  # noqa: E402
from fem.train.plots import plot_train_campbell, plot_train_parametric  # noqa: E402

EXAMPLES = Path(__file__).resolve().parent
RPM = 30.0 / math.pi


def two_stage(out: Path) -> dict:
    study = Study.load(EXAMPLES / "geared_two_stage.toml")
    res = study.forced()
    s = res.speeds_rad_s * RPM
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for c in res.connections:
        if c.coordinate == "line of action":
            a1.plot(s, c.dynamic_factor, lw=1.5, label=f"{c.connection} (static |F| = {abs(c.static):.0f} N)")
    a1.axhline(1.0, color="k", lw=0.8)
    a1.set_ylabel("dynamic load factor of the mesh [-]")
    a1.set_title(f"{study.title}: transmission error 5 um + 2 um per stage, meshes closed", fontsize=10)
    a1.legend(fontsize=8)
    a1.grid(alpha=0.3)
    for k, v in res.bearings.items():
        a2.plot(s, v["peak_radial"] / 1e3, lw=1.1, label=k.replace(":", " "))
    a2.set_ylabel("peak radial bearing force [kN]")
    a2.set_xlabel("motor speed [rev/min]")
    a2.legend(fontsize=7, ncol=2)
    a2.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "geared_two_stage_loads.png", dpi=130)
    plt.close(fig)
    sim = study.simulate()
    t = sim.t * 1e3
    cf = sim.connection_forces()
    fig, ax = plt.subplots(figsize=(8, 4.2))
    for k in ("stage 1", "stage 2"):
        ax.plot(t, cf[k] / 1e3, lw=1.0, label=f"mesh {k}")
    for e in sim.result.events:
        ax.axvline(e.t * 1e3, color="0.85", lw=0.5, zorder=0)
    ax.set_xlabel("time t [ms]")
    ax.set_ylabel("mesh force (drive flank +) [kN]")
    ax.set_title(f"{study.title} at {study.doc.train.speed_rpm:g} rev/min, backlash 60 um, from the static state "
                 "(grey: contact events)", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "geared_two_stage_rattle.png", dpi=130)
    plt.close(fig)
    dlf = {c.connection: float(np.nanmax(c.dynamic_factor)) for c in res.connections if c.coordinate == "line of action"}
    return {"two_stage_static_mesh_force_N": {c.connection: c.static for c in res.connections
                                              if c.coordinate == "line of action"},
            "two_stage_max_dlf": dlf, "two_stage_balance": res.balance_max,
            "two_stage_sim_balance": sim.force_balance.max_residual, "two_stage_sim_events": len(sim.result.events)}


def compressor(out: Path) -> dict:
    study = Study.load(EXAMPLES / "geared_compressor_train.toml")
    camp = study.campbell()
    ts = study.train
    lines = {f"tooth pass {m.name}": m.teeth[0] * abs(ts.ratio_of(m.ports[0])) / (2 * math.pi)
             for m in ts.train.connections if getattr(m, "teeth", None)}
    plot_train_campbell(camp, out / "geared_compressor_campbell.png", title=study.title, ratios=ts.ratios,
                        lines=lines, reference=ts.train.reference)
    return {"compressor_critical_rpm": [(c.order, c.speed_rpm) for c in camp.critical_speeds]}


def rattle(out: Path) -> dict:
    from validation.cases.geared import _ks, ks_reference

    study = Study.load(EXAMPLES / "geared_rattle.toml")
    osc, wn, b, _ = _ks(study)
    f_down, f_up, grazing, _ = ks_reference(osc)
    hb = study.forced()
    doc = read_toml(EXAMPLES / "geared_rattle.toml")
    doc["steady"].update(method="shooting", omega=[0.78 * wn, 1.15 * wn])
    doc["steady"].pop("harmonics", None)
    sh = Study.parse(doc).forced()
    k = study.train.train.connections[0].stiffness
    # the exact curve: contact orbits (max force k (x_max - b)) and the upper impacting branch
    fig, ax = plt.subplots(figsize=(8, 5))
    w = hb.omega / wn
    st = np.asarray(hb.stable)
    ax.plot(np.where(st, w, np.nan), np.where(st, hb.response, np.nan), color="tab:blue", lw=1.6,
            label="HB, 25 harmonics (stable)")
    ax.plot(np.where(~st, w, np.nan), np.where(~st, hb.response, np.nan), color="tab:blue", lw=1.2, ls="--",
            label="HB (unstable)")
    ax.plot(sh.omega[::3] / wn, sh.response[::3], "o", ms=3, mfc="none", color="tab:orange",
            label="shooting (exact events)")
    Om = np.linspace(0.75, 1.2, 200)
    lin = [osc.linear_orbit(x) for x in Om]
    ok = np.array([c0 - a > osc.b for c0, a in lin])
    ax.plot(np.where(ok, Om, np.nan), [k * b * (c0 + a - osc.b) for c0, a in lin], color="k", lw=0.8, ls=":",
            label="exact: contact orbit")
    for f, lab in ((f_down, "jump down"), (f_up, "jump up")):
        ax.axvline(f, color="tab:red", lw=0.8, ls="-.")
        ax.text(f, ax.get_ylim()[1] * 0.97, f" {lab}\n {f:.5f}", fontsize=7, va="top", color="tab:red")
    ax.set_xlabel("forcing frequency / omega_n [-]  (omega_n = sqrt(k / m_e) = %.0f rad/s)" % wn)
    ax.set_ylabel("largest mesh force over a period [N]")
    ax.set_title(f"{study.title}: F_m = 0.1 k b, F_a = 0.02 k b, zeta = 0.05", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "geared_rattle_afc.png", dpi=130)
    plt.close(fig)
    return {"rattle_folds_hb": sorted(f["omega"] / wn for f in hb.folds),
            "rattle_folds_shooting": sorted(f["omega"] / wn for f in sh.folds),
            "rattle_folds_exact": [f_down, f_up]}


def parametric(out: Path) -> dict:
    from fem.modelfile.build.train import parametric as run

    study = Study.load(EXAMPLES / "geared_mesh_parametric.toml")
    res = run(study)
    plot_train_parametric(res, out / "geared_mesh_parametric.png", title=study.title)
    b = res.chart.boundaries[0]
    return {"parametric_principal_rad_s": [float(b.omega_low_rad_s[-1] / res.pass_per_speed),
                                           float(b.omega_high_rad_s[-1] / res.pass_per_speed)]}


def main(out_dir) -> dict:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    res = {}
    for part in (two_stage, compressor, rattle, parametric):
        res.update(part(out))
    return res


if __name__ == "__main__":
    for k, v in main(sys.argv[1] if len(sys.argv) > 1 else "geared-figures").items():
        print(f"{k}: {v}")
