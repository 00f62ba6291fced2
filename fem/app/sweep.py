"""``drivefem sweep``: parameter sweeps of a model file on Dask (see docs/steady.md, "Sweeps").

The ``[sweep]`` table is declared in the model-file schema (:mod:`fem.modelfile.schema.steady`);
every point is a model file of its own, validated up front before anything runs.

The sweep is defined in the model file::

    [sweep]
    analysis = "steady"      # per point: "steady" (periodic steady state at the point's forcing
                             # frequency: time integration + shooting, response of [steady] and
                             # Floquet stability; "response_observed": the response over the last
                             # 4 integrated periods, which differs where period 1 is unstable),
                             # "forced" (the whole AFC of [steady]: peak, folds),
                             # or "simulate" (the nonsmooth time simulation: extremes, period, events)
    # a grid (Cartesian product, first key slowest) ...
    grid = { "driver.cam.amplitude" = [1e-4, 4.7e-4], "driver.cam.omega" = { start = 20.0, stop = 80.0, points = 50 } }
    # ... or an explicit list of points
    # points = [ { "driver.cam.amplitude" = 1e-4, "driver.cam.omega" = 54.15 }, ... ]
    periods = 300            # "steady": at most this many forcing periods of time integration before shooting

A key is a dotted path into the model file: ``table.key`` (``steady.harmonics``), or for arrays of
tables ``array.NAME.key`` (the entry with ``name = NAME``) or ``array.INDEX.key`` (0-based).  A path
that names no existing table/entry, or a key the model does not accept, is rejected before anything
runs.

Execution: each point is an independent pure function of (model, values) -- results do not depend on
the number of workers or the order of completion.  Every finished point is written at once to
``OUT/points/NNNNNN.json`` (atomic rename); ``--resume OUT`` skips the points already written with
status "ok" (failed points are retried).  The store (:mod:`fem.app.sweep_store`) trusts a point file only
if it is complete and was written for this model and this point's values (a fingerprint), claims each
point atomically so that concurrent runs on one directory split the work, and checks the output
locations before any point runs.  A failing point is recorded with its error and the sweep goes
on; the exit code is 1 if any point failed, 2 for bad input or an unreachable scheduler, 0 otherwise.
"""
from __future__ import annotations

import copy
import itertools
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

from discrete.errors import ModelError

from .sweep_store import REASONS, SweepStore

MAX_POINTS = 100_000
"""Largest number of sweep points (each an independent analysis)."""


# ------------------------------------------------------------------ definition
def _axis(spec) -> list:
    """The values of one grid axis: a list as given, or { start, stop, points, spacing }."""
    from ..modelfile.budget import check_count

    if isinstance(spec, list):
        return list(spec)
    check_count("[sweep]", "points", spec.points, MAX_POINTS, "points", spec.points)
    f = np.geomspace if spec.spacing == "log" else np.linspace
    return [float(x) for x in f(spec.start, spec.stop, spec.points)]


def _locate(doc: dict, path: str):
    """(container, key) for a dotted path; raises ModelError naming the path if it does not exist."""
    parts = path.split(".")
    where = "[sweep]"
    if len(parts) < 2:
        raise ModelError(where, path, None, "a dotted model key such as 'driver.cam.omega' or 'steady.harmonics'")
    head = parts[0]
    if head not in doc:
        raise ModelError(where, path, None, f"a key of an existing table; the model has {sorted(doc)}")
    obj = doc[head]
    rest = parts[1:]
    if isinstance(obj, list):
        if len(rest) < 2:
            raise ModelError(where, path, None, f"'{head}.NAME.key' or '{head}.INDEX.key' for the array [[{head}]]")
        sel = rest[0]
        match = [t for t in obj if isinstance(t, dict) and str(t.get("name")) == sel]
        if not match and sel.isdigit() and int(sel) < len(obj):
            match = [obj[int(sel)]]
        if not match:
            names = [t.get("name", i) for i, t in enumerate(obj)]
            raise ModelError(where, path, None, f"an entry of [[{head}]] by name or index: {names}")
        obj, rest = match[0], rest[1:]
    for p in rest[:-1]:
        if not isinstance(obj, dict) or p not in obj or not isinstance(obj[p], dict):
            raise ModelError(where, path, None, "an existing (sub)table")
        obj = obj[p]
    if not isinstance(obj, dict):
        raise ModelError(where, path, None, "a key inside a table")
    return obj, rest[-1]


def apply(doc: dict, values: dict) -> dict:
    d = copy.deepcopy(doc)
    d.pop("sweep", None)
    for path, v in values.items():
        obj, key = _locate(d, path)
        obj[key] = v
    return d


def parse_sweep(doc: dict) -> dict:
    """The points of the ``[sweep]`` table of a parsed model file, every point checked: its key paths
    exist and the model it gives is valid (a bad value fails here, before any point runs)."""
    from ..modelfile import parse
    from ..modelfile.budget import check_count

    typed = parse(doc)
    sw = getattr(typed, "sweep", None)
    if sw is None:
        raise ModelError("model file", "sweep", None, "a table [sweep] (grid = {..} or points = [..])")
    if sw.grid is not None:
        keys = list(sw.grid)
        axes = [_axis(sw.grid[k]) for k in keys]
        check_count("[sweep]", "grid", int(np.prod([len(a) for a in axes], dtype=float)), MAX_POINTS, "points")
        pts = [dict(zip(keys, combo)) for combo in itertools.product(*axes)]
    else:
        check_count("[sweep]", "points", len(sw.points), MAX_POINTS, "points")
        pts = [dict(x) for x in sw.points]
    base = {k: v for k, v in doc.items() if k != "sweep"}
    for path in dict.fromkeys(k for pt in pts for k in pt):
        _locate(copy.deepcopy(base), path)
    first = None
    for pt in pts:                          # every point checked; only the first one's study is kept
        study = _point_study(base, pt, sw.analysis)
        first = first or study
    return {"analysis": sw.analysis, "points": pts, "periods": sw.periods,
            "title": first.title if first else "", "kind": first.kind if first else None}


def _point_study(base: dict, values: dict, analysis: str):
    """The validated model of one point (ModelError naming the point on a bad value)."""
    from ..study import Study

    try:
        study = Study.parse(apply(base, values))
    except ModelError as exc:
        raise ModelError(f"[sweep] point {values}", exc.key, exc.value, f"{exc.allowed} (in {exc.where})") from None
    if analysis in ("steady", "forced") and not study.is_steady():
        raise ModelError("[sweep]", "analysis", analysis, "a model with a [steady] table for this analysis")
    if analysis == "simulate" and getattr(study.doc, "simulation", None) is None:
        raise ModelError("[sweep]", "analysis", analysis, "a model with a [simulation] table for this analysis")
    return study


# ------------------------------------------------------------------ one point
def evaluate_point(doc: dict, values: dict, analysis: str, periods: int = 300) -> dict:
    """Evaluate one sweep point; never raises (errors are returned as a record).  BLAS is limited to
    one thread while the point runs (threadpoolctl, if installed), so serial and parallel runs take the
    same floating-point paths and give bit-identical results."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:  # pragma: no cover
        return _evaluate(doc, values, analysis, periods)
    with threadpool_limits(limits=1):
        return _evaluate(doc, values, analysis, periods)


def _evaluate(doc: dict, values: dict, analysis: str, periods: int) -> dict:
    try:
        study = _point_study(doc, values, analysis)
        if analysis == "steady":
            res = _steady_point(study, periods)
        elif analysis == "forced":
            r = study.forced()
            w, m = r.peak()
            res = {"peak_omega_rad_s": w, "peak_response": m, "folds_rad_s": [f["omega"] for f in r.folds],
                   "jump_intervals_rad_s": [list(j) for j in r.jump_intervals()],
                   "period_doubling_intervals_rad_s": [list(j) for j in r.unstable_intervals("flip")],
                   "n_points": int(r.omega.size), "reason": r.reason,
                   "outputs": {n: {"max_amplitude": o["max_amplitude"], "at_omega_rad_s": o["at_omega_rad_s"]}
                               for n, o in (study.outputs(r) or {}).items()}}
        else:
            r = study.simulate()
            res = {"period": r.period, "energy_error": r.energy_error, "n_events": len(r.events),
                   "stopped_early": bool(r.stopped_early),
                   "x_max": {n: float(np.max(r.x[i])) for i, n in enumerate(r.names)},
                   "x_min": {n: float(np.min(r.x[i])) for i, n in enumerate(r.names)},
                   "outputs": _summaries(study.outputs(r))}
        return {"values": values, "status": "ok", "result": _clean(res)}
    except Exception as exc:  # a failed point is a record, not a crash of the sweep
        return {"values": values, "status": "error", "error": f"{type(exc).__name__}: {exc}"}


def _steady_point(study, periods: int) -> dict:
    from discrete.steady import ShootingModel

    sm = study.steady_model()
    w = float(sm.problem0.omegas[0])
    sh = ShootingModel(sm.factory, nu=sm.cfg.subharmonic, steps_per_period=sm.cfg.steps_per_period)
    n = sh.n
    y, used, settled = sh.settle(np.zeros(n), w, periods=periods, tol=1e-9, scale=np.ones(n))
    _, res = sh.run(y, w, dense=True, periods=4)
    p = sh.problem(w)
    observed = sm.measure(res.t, res.x[p.f], res.v[p.f], w)     # what the time integration shows (4 periods)
    sc = np.concatenate([np.ptp(res.x[p.f], axis=1), np.ptp(res.v[p.f], axis=1)])
    sc = np.maximum(sc, 1e-9 * max(float(np.max(sc)), 1e-300))
    out = {"omega_rad_s": w, "periods_integrated": used, "settled": bool(settled), "response_observed": observed}
    try:
        y, _ = sh.solve(y, w, sc)
        mu = sh.floquet(y, w, sc)
        _, res = sh.run(y, w, dense=True)
        out.update(converged=True, max_multiplier=float(np.max(np.abs(mu))),
                   stable=bool(np.max(np.abs(mu)) < 1 + 1e-6))
    except Exception as exc:
        out.update(converged=False, shooting_error=f"{type(exc).__name__}: {exc}")
    out["response"] = sm.measure(res.t, res.x[p.f], res.v[p.f], w)
    # named outputs of the orbit: lumped and hybrid files (a train's steady point has its response only)
    out["outputs"] = _orbit_outputs(study, res) if study.kind in ("lumped", "hybrid") else None
    return out


_SUMMARY_KEYS = ("peak", "mean", "rms", "peak_to_peak", "dynamic_load_factor")


def _summaries(outputs) -> dict:
    """{output: its derived quantities} of a point (peak, mean, rms, peak-to-peak, dynamic load factor)."""
    return {n: {k: s.get(k) for k in _SUMMARY_KEYS if k in s} for n, s in outputs.summaries.items()}


def _orbit_outputs(study, res) -> dict:
    """The derived quantities of every named output over the orbit integrated at the point (``res``: the
    event solver's result over the last period(s))."""
    from ..loads.analyses import time_outputs
    from ..loads.drive import selected

    lm = selected(study, study.time_loads)
    out = time_outputs(lm, res.t, res.x, res.v, res.acceleration, res.element_forces, res.applied)
    d = _summaries(out)
    for k, c in enumerate(lm.channels):
        y = out.values[k]
        d[c.name]["amplitude"] = 0.5 * float(np.max(y) - np.min(y))
    return d


def _clean(o):
    if isinstance(o, dict):
        return {str(k): _clean(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_clean(v) for v in o]
    if isinstance(o, (np.floating, float)):
        return None if not math.isfinite(float(o)) else float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.bool_):
        return bool(o)
    return o


# ------------------------------------------------------------------ storage (fem/app/sweep_store.py)
def collect(store: SweepStore) -> list:
    """Every point's trusted record, or {index, status: missing} where none is."""
    recs = []
    for i in range(len(store.points)):
        rec, why = store.read(i)
        recs.append(rec if rec is not None else {"index": i, "status": "missing", "values": store.points[i],
                                                 "error": f"no trusted point file ({why})"})
    return recs


def _wait_for(store: SweepStore, deferred: list, base, pts, spec, bar, stream, poll: float = 0.5) -> None:
    """Wait for the points another live run has claimed (it writes them); a point whose claim is released
    without a file, or whose run died, is computed here."""
    if not deferred:
        return
    print(f"sweep: {len(deferred)} points are being computed by another run on {store.out}; waiting for them",
          file=stream)
    left = list(deferred)
    while left:
        still = []
        for i in left:
            rec, _ = store.read(i)
            if rec is not None:
                if bar:
                    bar.update(1)
                continue
            if store.claimed_by_others(i):
                still.append(i)
            elif store.claim(i):
                store.write(i, evaluate_point(base, pts[i], spec["analysis"], spec["periods"]))
                if bar:
                    bar.update(1)
            else:
                still.append(i)
        left = still
        if left:
            time.sleep(poll)


# ------------------------------------------------------------------ driver
def _dask():
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ModelError("drivefem sweep", "dask", None,
                         'the dask.distributed package: pip install "dask[distributed]"') from exc
    return Client, LocalCluster, as_completed


def run_sweep(model_path, *, scheduler=None, resume=None, out=None, json_path=None, workers=None,
              progress: bool = True, stream=None) -> int:
    """Run the sweep of ``model_path``.  ``workers``: size of the in-process local cluster (default: the
    CPU count); ``workers = 0`` runs serially without Dask.  Returns the exit code."""
    stream = stream or sys.stderr
    from ..modelfile.source import read_toml

    doc = read_toml(model_path)
    spec = parse_sweep(doc)
    base = {k: v for k, v in doc.items() if k != "sweep"}
    pts = spec["points"]
    n = len(pts)
    outdir = Path(resume or out or (Path(model_path).stem + "-sweep"))
    if resume and not Path(resume).is_dir():
        raise ModelError("command line", "--resume", str(resume), "the directory of an earlier sweep")
    if json_path:
        from ..output.paths import check_output_path, try_writing

        try_writing(check_output_path(json_path, "--json", kind="json").parent, "--json", json_path)
    store = SweepStore(outdir, base, spec["analysis"], spec["periods"], pts, str(model_path))
    note = store.open("--resume" if resume else "--out")
    if note:
        print(f"sweep: {note}", file=stream)
    done, rejected = store.scan()
    todo = [i for i in range(n) if i not in done]
    print(f"sweep: {n} points, {len(done)} already done in {outdir}, {len(todo)} to run", file=stream)
    if rejected:
        print("sweep: point files not trusted, recomputed: " + "; ".join(
            f"{len(v)} {why} ({REASONS[why]})" for why, v in rejected.items()), file=stream)
    bar = None
    if progress:
        try:
            from tqdm import tqdm

            bar = tqdm(total=n, initial=len(done), desc="sweep", unit="pt", file=stream)
        except ImportError:  # pragma: no cover
            bar = None
    try:
        deferred = []                              # points a live concurrent run has claimed

        def claimed(indices):
            for i in indices:
                if store.claim(i):
                    yield i
                elif not store.finished_elsewhere(i):
                    deferred.append(i)
                elif bar:
                    bar.update(1)

        if workers == 0 and scheduler is None:
            for i in claimed(todo):
                rec = evaluate_point(base, pts[i], spec["analysis"], spec["periods"])
                store.write(i, rec)
                if bar:
                    bar.update(1)
        elif todo:
            Client, LocalCluster, as_completed = _dask()
            cluster = None
            try:
                if scheduler:
                    try:
                        client = Client(scheduler, timeout="5s")
                    except Exception as exc:
                        raise ModelError("command line", "--scheduler", scheduler, "the address of a reachable Dask "
                                         f"scheduler ({type(exc).__name__}: {exc})") from None
                else:
                    nw = int(workers or os.cpu_count() or 1)
                    # one single-threaded process per core: the solvers are small-matrix numpy, and BLAS
                    # threads inside each worker would only compete for the same cores
                    one = {k: "1" for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
                    cluster = LocalCluster(n_workers=nw, threads_per_worker=1, processes=True, host="127.0.0.1",
                                           dashboard_address=None, silence_logs=40, env=one)
                    client = Client(cluster)
                try:
                    bdoc = client.scatter(base, broadcast=True)
                    # bounded queue: at most 2 tasks per worker in flight, the next point submitted as one
                    # finishes -- dynamic load balancing (point costs differ by 10x near resonances)
                    nwk = max(1, len(client.scheduler_info().get("workers", {})) or 1)
                    queue = claimed(todo)
                    futs = {}
                    ac = as_completed()

                    def submit_next():
                        i = next(queue, None)
                        if i is None:
                            return
                        f = client.submit(evaluate_point, bdoc, pts[i], spec["analysis"], spec["periods"],
                                          key=f"sweep-point-{i}-{os.getpid()}-{id(outdir)}", pure=False)
                        futs[f] = i
                        ac.add(f)

                    for _ in range(2 * nwk):
                        submit_next()
                    for fut in ac:
                        i = futs.pop(fut)
                        try:
                            rec = fut.result()
                        except Exception as exc:   # worker lost etc.
                            rec = {"values": pts[i], "status": "error", "error": f"{type(exc).__name__}: {exc}"}
                        store.write(i, rec)
                        if bar:
                            bar.update(1)
                        submit_next()
                finally:
                    client.close()
            finally:
                if cluster is not None:
                    cluster.close()
        _wait_for(store, deferred, base, pts, spec, bar, stream)
    finally:
        store.release_all()
        if bar:
            bar.close()
    recs = collect(store)
    bad = [r for r in recs if r.get("status") != "ok"]
    for r in bad:
        print(f"point {r['index']} {r.get('values')}: {r.get('status')}: {r.get('error', '')}", file=stream)
    summary = {"model": str(model_path), "analysis": spec["analysis"], "out": str(outdir), "n_points": n,
               "n_ok": n - len(bad), "n_failed": len(bad), "computed_here": store.computed,
               "fingerprint": store.fingerprint,
               "recomputed": rejected, "points": recs}
    if json_path:
        from types import SimpleNamespace

        from ..output import payload, write_json

        try:
            write_json(json_path, payload("sweep", SimpleNamespace(title=spec["title"], kind=spec["kind"]), summary))
        except OSError as exc:
            print(f"sweep: could not write --json {json_path} ({exc.strerror or exc}); the {n} points are kept in "
                  f"{outdir}: `drivefem sweep {model_path} --resume {outdir} --json PATH` writes the summary "
                  "without recomputing them", file=stream)
            return 1
    print(f"sweep: {n - len(bad)} of {n} points ok" + (f", {len(bad)} failed" if bad else "")
          + f"; {store.computed} computed by this run", file=stream)
    return 1 if bad else 0
