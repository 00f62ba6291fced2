"""drivefem against pyHarm (Safran's open-source harmonic balance code, PyPI ``pyharm-os`` 1.2.2) on the
problems of ../shared/reference/pyharm_comparison.md: one DOF, m x'' + c x' + k x + f_nl = F cos(w t),
m = k = 1.

| problem    | f_nl              | c, F        | w range    | H, N     | pyHarm element         | drivefem table       |
|------------|-------------------|-------------|------------|----------|------------------------|----------------------|
| duffing    | 0.1 x^3           | 0.02, 0.05  | 0.5 .. 2   | 7, 64    | CubicSpring            | [[cubic_spring]]     |
| duffing_k3 | 1.0 x^3           | 0.02, 0.05  | 0.5 .. 2.5 | 9, 64    | CubicSpring            | [[cubic_spring]]     |
| stop       | 10 (x - 0.5)+     | 0.05, 0.05  | 0.5 .. 2   | 15, 1024 | PenaltyUnilateralGap   | [[gap]] upper = 0.5  |
| friction   | 0.05 sign(x')     | 0.02, 0.1   | 0.5 .. 2   | 15, 1024 | DLFTFriction, eps = 10 | [[friction]] (tanh)  |

Continuation as in the comparison: pyHarm ds0 = 0.01, ds_max = 0.05 (its defaults jump over the
peaks), drivefem ds_max = 0.6 (comparable point counts); Floquet stability off in drivefem (pyHarm has
none).  BLAS, OpenMP, MKL and numba limited to one thread on both sides.

Timings (medians and ranges of ``--repeat`` rounds, the two tools alternating, the order swapped every
round):

* in-process: one whole curve, model building included, imports and compilation excluded (pyHarm in a
  worker process of its own environment, warmed up once per problem; drivefem ``Study.parse(doc).forced()``
  here) -- target >= 10x;
* fresh process: a new interpreter per curve, everything included (pyHarm: ``Maestro(...).operate()`` in a
  runner script; drivefem: ``drivefem forced FILE.toml --json``) -- target >= 3x.  Both sides run as installed
  software does: one untimed fresh run first (files in the OS cache), Python's bytecode cache written
  (PYTHONDONTWRITEBYTECODE dropped from both environments: set, it recompiled every edited drivefem module
  in every run, ~25 ms).

Curves, compared in the same run: each timed curve against exact shooting (drivefem's event-driven period
map, Newton from that tool's own harmonic orbit) at 9 points spread along it, |h1 - exact| / peak; and
the two curves' shapes on denser untimed runs (pyHarm ds_max 0.01, friction 0.05; drivefem ds_max 0.1,
as in the comparison doc): the largest distance from a point of one curve to the other (both ways) in
(omega / range, h1 / peak) units.

pyHarm lives in its own virtualenv (not a drivefem dependency): ``bash benchmarks/pyharm_env.sh`` builds
it at ``$PYHARM_ENV`` (default /work/pyharm-env); ``--pyharm PYTHON`` points elsewhere.  Its first run
compiles its numba kernels (about 25 s for the cubic problem, 2 min for the DLFT friction; cached after).

    python benchmarks/pyharm.py [--repeat 7] [--fresh 5] [--only duffing stop ...]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import common  # noqa: E402

common.limit_blas_threads(1)

import numpy as np  # noqa: E402

ONE_THREAD = {k: "1" for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS")}
PROBLEMS = {
    "duffing": dict(c=0.02, F=0.05, w=(0.5, 2.0), H=7, N=64, law="cubic", k3=0.1),
    "duffing_k3": dict(c=0.02, F=0.05, w=(0.5, 2.5), H=9, N=64, law="cubic", k3=1.0),
    "stop": dict(c=0.05, F=0.05, w=(0.5, 2.0), H=15, N=1024, law="stop", kc=10.0, gap=0.5),
    "friction": dict(c=0.02, F=0.1, w=(0.5, 2.0), H=15, N=1024, law="friction", mu_n=0.05, eps=10.0),
}
DS_MAX = 0.6

PYHARM_SIDE = textwrap.dedent('''
    """pyHarm side of benchmarks/pyharm.py: "once PROBLEM_JSON" (a fresh process: one curve, printed) or
    "worker" (reads "RUN <json>" lines, answers "REPLY <json>" with the timed run and its curve)."""
    import json, logging, sys, time, warnings
    warnings.simplefilter("ignore")
    t0 = time.perf_counter()
    import numpy as np
    from pyHarm.Maestro import Maestro
    T_IMPORT = time.perf_counter() - t0
    logging.disable(logging.CRITICAL)

    def connectors(p):
        one = {"connect": {"sub": [0]}, "dirs": [0]}
        con = {"mass": dict(one, type="GOElement", dto=2, xo=1, k=1.0),
               "spring": dict(one, type="LinearSpring", k=1.0),
               "damper": dict(one, type="LinearDamper", k=p["c"]),
               "force": dict(one, type="CosinusForcing", amp=p["F"])}
        if p["law"] == "cubic":
            con["nl"] = dict(one, type="CubicSpring", k=p["k3"])
        elif p["law"] == "stop":
            con["nl"] = dict(one, type="PenaltyUnilateralGap", g=p["gap"], k=p["kc"])
        else:
            con["nl"] = dict(one, type="DLFTFriction", mu=p["mu_n"], N0=1.0, eps=p["eps"])
        return con

    def run(p):
        idata = {"system": {"type": "Base", "nh": p["H"], "nti": p["N"]},
                 "substructures": {"sub": {"type": "onlydofs", "nnodes": 1, "ndofs": 1}},
                 "connectors": connectors(p),
                 "analysis": {"frf": {"study": "frf", "puls_inf": p["w"][0], "puls_sup": p["w"][1], "ds0": 0.01,
                                      "ds_max": p.get("ds_max", 0.05), "verbose": False}}}
        m = Maestro(idata)
        m.operate()
        sols = [s for s in m.nls["frf"].SolList if s.flag_accepted]
        X = np.array([s.x for s in sols])
        return {"omega": X[:, -1].tolist(), "h1": np.hypot(X[:, 1], X[:, 2]).tolist(), "x": X[:, :-1].tolist()}

    if sys.argv[1] == "once":
        out = run(json.loads(sys.argv[2]))
        print("REPLY " + json.dumps({"n": len(out["omega"])}), flush=True)
    else:
        print("READY " + json.dumps({"import_s": T_IMPORT}), flush=True)
        for line in sys.stdin:
            p = json.loads(line[4:])
            t = time.perf_counter()
            c = time.process_time()
            out = run(p)
            out.update(wall=time.perf_counter() - t, cpu=time.process_time() - c)
            print("REPLY " + json.dumps(out), flush=True)
''')


# ------------------------------------------------------------------ drivefem side
def drivefem_doc(p: dict) -> dict:
    doc = {"title": "pyHarm comparison", "body": [{"name": "m", "inertia": 1.0}],
           "spring": [{"between": ["ground", "m"], "k": 1.0}],
           "damper": [{"between": ["ground", "m"], "c": p["c"]}],
           "force": [{"body": "m", "amplitude": p["F"], "omega": p["w"][0], "phase": math.pi / 2}],
           "steady": {"method": "hb", "omega": list(p["w"]), "harmonics": p["H"], "samples": p["N"],
                      "stability": False, "ds_max": DS_MAX, "response": {"body": "m", "measure": "h1"}}}
    if p["law"] == "cubic":
        doc["cubic_spring"] = [{"between": ["ground", "m"], "k3": p["k3"]}]
    elif p["law"] == "stop":
        doc["gap"] = [{"name": "stop", "body": "m", "upper": p["gap"], "k": p["kc"]}]
    else:
        doc["friction"] = [{"name": "dry", "body": "m", "kinetic": p["mu_n"]}]
    return doc


def toml_text(doc: dict) -> str:
    """The model dict as TOML (the few value types used here)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(val(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{k} = {val(x)}" for k, x in v.items()) + " }"
        return repr(float(v)) if isinstance(v, float) else str(v)

    out = [f"title = {val(doc['title'])}"]
    for key, v in doc.items():
        if isinstance(v, list):
            for item in v:
                out.append(f"\n[[{key}]]")
                out += [f"{k} = {val(x)}" for k, x in item.items()]
        elif isinstance(v, dict):
            out.append(f"\n[{key}]")
            out += [f"{k} = {val(x)}" for k, x in v.items()]
    return "\n".join(out) + "\n"


def drivefem_curve(doc: dict):
    from fem.study import Study

    return Study.parse(doc).forced()


def h1_of(r) -> np.ndarray:
    """First-harmonic amplitude straight from the HB coefficients (independent of the response measure)."""
    Q = np.array(r.states)
    return np.hypot(Q[:, 1], Q[:, 2])


def picks_along(w, a, count: int = 9) -> list[int]:
    """Indices of ``count`` points spread along a curve by arc length in (omega, h1 / peak), peak included."""
    u = np.column_stack([np.asarray(w) / np.ptp(w), np.asarray(a) / np.max(a)])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(u, axis=0), axis=1))])
    return sorted(set(np.searchsorted(s, np.linspace(0, s[-1], count)).clip(0, len(w) - 1).tolist())
                  | {int(np.argmax(a))})


def exact_errors(doc: dict, omegas, coeffs, h1s, peak: float, count: int = 9) -> tuple[float, int]:
    """Largest |h1 - exact h1| / peak at ``count`` points of a curve, the exact value from shooting (the
    event-driven period map, Newton) started from that point's harmonic orbit (coefficients [a0, a1, b1,
    ...] of q = a0 + sum a_k cos k w t + b_k sin k w t); returns (error, points that converged)."""
    from discrete.steady import ShootingModel
    from fem.study import Study

    sm = Study.parse(doc).steady_model()
    sh = ShootingModel(sm.factory)
    worst, done = 0.0, 0
    for i in picks_along(omegas, h1s, count):
        w, X = float(omegas[i]), np.asarray(coeffs[i], float)
        k = np.arange(1, (X.size - 1) // 2 + 1)
        q0 = X[0] + np.sum(X[1::2])
        v0 = float(np.sum(k * w * X[2::2]))
        try:
            y, _ = sh.solve(np.array([q0, v0]), w, np.array([peak, peak * w]))
        except Exception as exc:            # a point where shooting does not converge is reported, not hidden
            print(f"  exact shooting failed at omega = {w:.6g}: {exc}")
            continue
        _, res = sh.run(y, w, dense=True)
        p = sh.problem(w)
        t, x = res.t - res.t[0], res.x[p.f][0]
        z = np.trapezoid(x * np.exp(-1j * w * t), t) * w / np.pi
        worst = max(worst, abs(abs(z) - float(h1s[i])) / peak)
        done += 1
    return worst, done


# ------------------------------------------------------------------ curve distances
def _dist_to_polyline(P: np.ndarray, L: np.ndarray) -> np.ndarray:
    """Distance of each point of P (k, 2) to the polyline L (m, 2)."""
    A, B = L[:-1], L[1:]
    d = B - A
    n2 = np.maximum(np.sum(d * d, axis=1), 1e-300)
    t = np.clip(np.einsum("kmj,mj->km", P[:, None, :] - A[None], d) / n2, 0.0, 1.0)
    C = A[None] + t[..., None] * d[None]
    return np.min(np.linalg.norm(P[:, None, :] - C, axis=2), axis=1)


def scaled(w, a, wr, peak):
    return np.column_stack([np.asarray(w) / (wr[1] - wr[0]), np.asarray(a) / peak])


def curve_distance(c1, c2, wr, peak) -> float:
    A, B = scaled(*c1, wr, peak), scaled(*c2, wr, peak)
    return float(max(_dist_to_polyline(A, B).max(), _dist_to_polyline(B, A).max()))


# ------------------------------------------------------------------ the pyHarm worker
class PyHarm:
    def __init__(self, python: str, workdir: Path):
        self.script = workdir / "pyharm_side.py"
        self.script.write_text(PYHARM_SIDE)
        self.python, self.workdir = python, workdir
        env = dict(os.environ, **ONE_THREAD)
        env.pop("PYTHONPATH", None)
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        self.env = env
        self.proc = subprocess.Popen([python, str(self.script), "worker"], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=env,
                                     cwd=workdir)
        self.import_s = self._reply("READY")["import_s"]

    def _reply(self, tag="REPLY"):
        while True:
            line = self.proc.stdout.readline()
            if not line:
                raise SystemExit(f"the pyHarm worker ended ({self.python}); run bash benchmarks/pyharm_env.sh")
            if line.startswith(tag + " "):
                return json.loads(line[len(tag) + 1:])

    def run(self, p: dict) -> dict:
        self.proc.stdin.write("RUN " + json.dumps(p) + "\n")
        self.proc.stdin.flush()
        return self._reply()

    def fresh(self, p: dict) -> float:
        t = time.perf_counter()
        out = subprocess.run([self.python, str(self.script), "once", json.dumps(p)], capture_output=True, text=True,
                             env=self.env, cwd=self.workdir, timeout=900)
        wall = time.perf_counter() - t
        if out.returncode != 0 or "REPLY" not in out.stdout:
            raise SystemExit(f"pyHarm fresh run failed: {out.stderr[-2000:]}")
        return wall

    def close(self):
        self.proc.stdin.close()
        self.proc.wait(timeout=60)


def drivefem_fresh(model: Path, workdir: Path) -> float:
    env = dict(os.environ, **ONE_THREAD, PYTHONPATH=str(ROOT))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    t = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "fem.app.cli", "forced", str(model), "--json",
                          str(workdir / "afc.json")], capture_output=True, text=True, env=env, cwd=ROOT, timeout=900)
    wall = time.perf_counter() - t
    if out.returncode != 0:
        raise SystemExit(f"drivefem fresh run failed: {out.stderr[-2000:]}")
    return wall


def _stats(xs):
    return {"median": statistics.median(xs), "min": min(xs), "max": max(xs), "runs": len(xs)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=7, help="in-process rounds (each tool once per round)")
    ap.add_argument("--fresh", type=int, default=5, help="fresh-process rounds")
    ap.add_argument("--only", nargs="*", choices=sorted(PROBLEMS), default=None)
    ap.add_argument("--pyharm", default=str(Path(os.environ.get("PYHARM_ENV", "/work/pyharm-env")) / "bin" / "python"))
    args = ap.parse_args(argv)
    common.header(__file__, "drivefem vs pyHarm 1.2.2 (HB + continuation, one DOF): in-process and fresh-process "
                            "ratios, curves compared in the same run")
    if not Path(args.pyharm).exists():
        print(f"pyHarm environment not found ({args.pyharm}): bash benchmarks/pyharm_env.sh (PYHARM_ENV=...)")
        return 2
    recs = []
    with tempfile.TemporaryDirectory(prefix="pyharm-bench-") as td:
        work = Path(td)
        ph = PyHarm(args.pyharm, work)
        print(f"pyHarm worker: import {ph.import_s:.2f} s ({args.pyharm})")
        try:
            for name in (args.only or list(PROBLEMS)):
                recs += _problem(name, PROBLEMS[name], ph, work, args)
        finally:
            ph.close()
    return common.finish(recs)


def _problem(name, p, ph: PyHarm, work: Path, args) -> list:
    doc = drivefem_doc(p)
    model = work / f"{name}.toml"
    model.write_text(toml_text(doc))
    print(f"\n{name}: H = {p['H']}, N = {p['N']}, omega {p['w'][0]} .. {p['w'][1]}")
    ph.run(p)                                   # warm-up (numba compilation / cache load)
    drivefem_curve(doc)
    times = {"pyharm": [], "drivefem": []}
    cpu = {"pyharm": [], "drivefem": []}
    r = out = None
    for k in range(args.repeat):
        for side in (("pyharm", "drivefem") if k % 2 == 0 else ("drivefem", "pyharm")):
            if side == "pyharm":
                out = ph.run(p)
                times["pyharm"].append(out["wall"])
                cpu["pyharm"].append(out["cpu"])
            else:
                wall, c, r = common.timed(lambda: drivefem_curve(doc))
                times["drivefem"].append(wall)
                cpu["drivefem"].append(c)
    fresh = {"pyharm": [], "drivefem": []}
    ph.fresh(p)                                 # untimed: both sides' files in the OS cache, bytecode written
    drivefem_fresh(model, work)
    for k in range(args.fresh):
        for side in (("pyharm", "drivefem") if k % 2 == 0 else ("drivefem", "pyharm")):
            fresh[side].append(ph.fresh(p) if side == "pyharm" else drivefem_fresh(model, work))
    # accuracy: the timed runs' points against exact shooting; the curves' shapes on denser untimed runs
    a_d, a_p = h1_of(r), np.array(out["h1"])
    peak = max(a_d.max(), a_p.max())
    e_d, n_d = exact_errors(doc, r.omega, [np.asarray(x).reshape(-1) for x in r.states], a_d, peak)
    e_p, n_p = exact_errors(doc, out["omega"], out["x"], a_p, peak)
    dense_doc = json.loads(json.dumps(doc))
    dense_doc["steady"]["ds_max"] = 0.1
    rd = drivefem_curve(dense_doc)
    od = ph.run(dict(p, ds_max=0.05 if p["law"] == "friction" else 0.01))
    dist = curve_distance((rd.omega, h1_of(rd)), (od["omega"], np.array(od["h1"])), p["w"], peak)
    s_in = {k: _stats(v) for k, v in times.items()}
    s_fr = {k: _stats(v) for k, v in fresh.items()}
    ratio_in = s_in["pyharm"]["median"] / s_in["drivefem"]["median"]
    ratio_cpu = statistics.median(cpu["pyharm"]) / statistics.median(cpu["drivefem"])
    ratio_fr = s_fr["pyharm"]["median"] / s_fr["drivefem"]["median"]
    for side in ("pyharm", "drivefem"):
        s, f = s_in[side], s_fr[side]
        print(f"  {side:9s} in-process {s['median']:.3f} s [{s['min']:.3f} .. {s['max']:.3f}], fresh process "
              f"{f['median']:.2f} s [{f['min']:.2f} .. {f['max']:.2f}]")
    print(f"  points: pyHarm {len(out['omega'])}, drivefem {r.omega.size}; peak h1 pyHarm {a_p.max():.6f}, drivefem "
          f"{a_d.max():.6f}")
    print(f"  h1 against exact shooting at the curves' own points (relative to the peak): drivefem {e_d:.2e} "
          f"({n_d} points), pyHarm {e_p:.2e} ({n_p} points)")
    print(f"  curve distance drivefem-pyHarm (dense untimed runs: {rd.omega.size} / {len(od['omega'])} points) {dist:.2e} "
          f"(units: omega / range, h1 / peak)")
    print(f"  ratio (pyHarm / drivefem): in-process {ratio_in:.1f}x wall ({ratio_cpu:.1f}x cpu), fresh {ratio_fr:.2f}x")
    acc = {"curve_distance": dist, "exact_error_drivefem": e_d, "exact_error_pyharm": e_p,
           "points": {"pyharm": len(out["omega"]), "drivefem": int(r.omega.size)}}
    rec_in = common.record(__file__, f"pyHarm {name}: in-process AFC", "drivefem HB + continuation",
                           "pyHarm 1.2.2 FRF_NonLinear", ratio_in, (">=", 10.0), ratio_cpu=ratio_cpu,
                           accuracy="largest |h1 - exact shooting h1| / peak at 9 points of each curve",
                           accuracy_package=e_d, accuracy_baseline=e_p,
                           runs={"package": args.repeat, "baseline": args.repeat},
                           spread={"package": s_in["drivefem"], "baseline": s_in["pyharm"], "curves": acc})
    rec_fr = common.record(__file__, f"pyHarm {name}: fresh process", "drivefem forced (CLI)",
                           "pyHarm 1.2.2 runner script", ratio_fr, (">=", 3.0),
                           runs={"package": args.fresh, "baseline": args.fresh},
                           spread={"package": s_fr["drivefem"], "baseline": s_fr["pyharm"]})
    return [rec_in, rec_fr]


if __name__ == "__main__":
    raise SystemExit(main())
