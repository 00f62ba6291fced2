"""drivefem sweep: Dask local cluster vs serial, resume, failed points, bad keys, scheduler errors."""
import json

import pytest

pytest.importorskip("distributed")

from fem.app.sweep import parse_sweep, run_sweep
from discrete.errors import ModelError

MODEL = """
title = "sweep test"
[[body]]
name = "m"
inertia = 1.0
[[spring]]
between = ["ground", "m"]
k = 1.0
[[damper]]
between = ["ground", "m"]
c = 0.2
[[friction]]
name = "dry"
body = "m"
kinetic = 0.1
[[force]]
body = "m"
amplitude = 1.0
omega = 1.0
[steady]
method = "shooting"
omega = [0.5, 2.0]
response = { body = "m" }
[sweep]
analysis = "steady"
periods = 200
"""


def write(tmp_path, sweep_line, name="m.toml"):
    p = tmp_path / name
    p.write_text(MODEL + sweep_line + "\n")
    return p


def load(path):
    return {r["index"]: r for r in json.load(open(path))["points"]}


def test_parallel_equals_serial_and_resume(tmp_path, capsys):
    p = write(tmp_path, 'grid = { "force.0.amplitude" = [0.5, 1.0], "force.0.omega" = [0.7, 1.3] }')
    assert run_sweep(p, out=tmp_path / "s", workers=0, json_path=tmp_path / "s.json", progress=False) == 0
    assert run_sweep(p, out=tmp_path / "d", workers=2, json_path=tmp_path / "d.json", progress=False) == 0
    s, d = load(tmp_path / "s.json"), load(tmp_path / "d.json")
    assert len(s) == 4 and all(r["status"] == "ok" for r in s.values())
    assert s == d                                        # identical whatever the number of workers
    # the linear part dominates: response close to the viscous FRF, not exactly (friction)
    r0 = s[0]["result"]
    assert r0["converged"] and r0["stable"] and r0["response"] > 0
    # resume: delete one finished point; exactly that one is recomputed, others untouched
    victim = tmp_path / "d" / "points" / "000002.json"
    victim.unlink()
    mtime = (tmp_path / "d" / "points" / "000001.json").stat().st_mtime_ns
    capsys.readouterr()
    assert run_sweep(p, resume=tmp_path / "d", workers=0, json_path=tmp_path / "r.json", progress=False) == 0
    err = capsys.readouterr().err
    assert "3 already done" in err and "1 to run" in err
    assert (tmp_path / "d" / "points" / "000001.json").stat().st_mtime_ns == mtime
    assert load(tmp_path / "r.json") == d


def test_bad_point_value_is_refused_before_anything_runs(tmp_path):
    p = write(tmp_path, 'points = [ { "spring.0.k" = 1.0 }, { "spring.0.k" = -5.0 }, { "spring.0.k" = 2.0 } ]')
    with pytest.raises(ModelError, match=r"point \{'spring.0.k': -5.0\}.*k = -5.0.*>= 0"):
        run_sweep(p, out=tmp_path / "f", workers=0, progress=False)
    assert not (tmp_path / "f").exists()


def test_failed_point_is_reported_and_sweep_goes_on(tmp_path, capsys, monkeypatch):
    import fem.app.sweep as sweep

    real = sweep._steady_point

    def fails_at_k2(study, periods):
        if study.doc.spring[0].k == 2.0:
            raise RuntimeError("solver diverged (injected)")
        return real(study, periods)

    monkeypatch.setattr(sweep, "_steady_point", fails_at_k2)
    p = write(tmp_path, 'points = [ { "spring.0.k" = 1.0 }, { "spring.0.k" = 2.0 }, { "spring.0.k" = 1.5 } ]')
    code = run_sweep(p, out=tmp_path / "f", workers=0, json_path=tmp_path / "f.json", progress=False)
    assert code == 1
    recs = load(tmp_path / "f.json")
    assert recs[0]["status"] == "ok" and recs[2]["status"] == "ok"
    assert recs[1]["status"] == "error" and "injected" in recs[1]["error"]
    assert "point 1" in capsys.readouterr().err


@pytest.mark.parametrize("line,word", [
    ('grid = { "spring.0.nope.k" = [1.0] }', "spring.0.nope.k"),
    ('grid = { "driver.cam.omega" = [1.0] }', "driver.cam.omega"),
    ('grid = { "spring.7.k" = [1.0] }', "spring.7.k"),
    ('grid = { "steady.harmonics" = [] }', "non-empty"),
    ('grid = { "spring.0.kk" = [1.0] }', "kk"),
    ('analysis = "nope"\ngrid = { "spring.0.k" = [1.0] }', "analysis"),
])
def test_bad_sweep_keys(tmp_path, line, word):
    text = MODEL.replace('analysis = "steady"\n', "") if line.startswith("analysis") else MODEL
    p = tmp_path / "b.toml"
    p.write_text(text + line + "\n")
    with pytest.raises(ModelError) as exc:
        run_sweep(p, out=tmp_path / "b", workers=0, progress=False)
    assert word in str(exc.value)


def test_unreachable_scheduler(tmp_path):
    p = write(tmp_path, 'grid = { "spring.0.k" = [1.0] }')
    with pytest.raises(ModelError, match="--scheduler.*reachable Dask scheduler"):
        run_sweep(p, out=tmp_path / "u", scheduler="tcp://127.0.0.1:9", progress=False)


def test_existing_scheduler(tmp_path):
    from dask.distributed import LocalCluster

    p = write(tmp_path, 'grid = { "spring.0.k" = [1.0, 1.5] }')
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp", host="127.0.0.1",
                      dashboard_address=None) as cluster:
        code = run_sweep(p, out=tmp_path / "e", scheduler=cluster.scheduler_address,
                         json_path=tmp_path / "e.json", progress=False)
    assert code == 0
    assert all(r["status"] == "ok" for r in load(tmp_path / "e.json").values())


def test_parse_grid_product_order():
    import tomllib

    doc = tomllib.loads(MODEL + 'grid = { "force.0.amplitude" = [1, 2], "force.0.omega" = { start = 1, stop = 2, '
                        'points = 3 } }\n')
    sp = parse_sweep(doc)
    assert len(sp["points"]) == 6 and sp["points"][1] == {"force.0.amplitude": 1, "force.0.omega": 1.5}
    doc["sweep"]["points"] = [{"a": 1}]
    with pytest.raises(ModelError, match="exactly one of grid"):
        parse_sweep(doc)


def test_simulate_and_forced_analyses(tmp_path):
    text = MODEL.replace('[sweep]\nanalysis = "steady"\nperiods = 200\n', "")
    p = tmp_path / "s.toml"
    p.write_text(text + '[simulation]\nt_end = 5.0\n[sweep]\nanalysis = "simulate"\n'
                 'grid = { "friction.dry.kinetic" = [0.05, 0.1] }\n')
    assert run_sweep(p, out=tmp_path / "sim", workers=0, json_path=tmp_path / "sim.json", progress=False) == 0
    recs = load(tmp_path / "sim.json")
    assert all(r["status"] == "ok" and r["result"]["n_events"] > 0 for r in recs.values())
    p2 = tmp_path / "f.toml"
    p2.write_text(text.replace('method = "shooting"', 'method = "hb"\nharmonics = 3')
                  + '[sweep]\nanalysis = "forced"\npoints = [ { "steady.harmonics" = 3 } ]\n')
    assert run_sweep(p2, out=tmp_path / "fo", workers=0, json_path=tmp_path / "fo.json", progress=False) == 0
    r = load(tmp_path / "fo.json")[0]["result"]
    assert r["peak_response"] > 0 and 0.5 <= r["peak_omega_rad_s"] <= 2.0


def test_missing_dask_message(tmp_path, monkeypatch):
    import fem.app.sweep as sweep

    def no_dask():
        raise ModelError("drivefem sweep", "dask", None, 'the dask.distributed package: pip install "dask[distributed]"')

    monkeypatch.setattr(sweep, "_dask", no_dask)
    p = write(tmp_path, 'grid = { "spring.0.k" = [1.0] }')
    with pytest.raises(ModelError, match="pip install"):
        run_sweep(p, out=tmp_path / "n", workers=2, progress=False)
