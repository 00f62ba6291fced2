"""The sweep store's integrity (issue 16): fingerprints, incomplete or foreign point files, unusable output
locations, kills at random moments with resume, and two runs on one directory -- through the real CLI."""
import json
import os
import random
import select
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("distributed")

from fem.app.sweep import run_sweep  # noqa: E402
from tests.test_sweep_dask import MODEL as STEADY_MODEL  # noqa: E402

MODEL = STEADY_MODEL.replace('[sweep]\nanalysis = "steady"\nperiods = 200\n',
                             '[simulation]\nt_end = 20.0\n[sweep]\nanalysis = "simulate"\n')
"""The friction oscillator of tests/test_sweep_dask.py, swept by time simulation (cheap points)."""
CLI = [sys.executable, "-m", "fem.app.cli"]
ROOT = Path(__file__).resolve().parents[1]


def model(tmp_path, grid: str, name="m.toml") -> Path:
    p = tmp_path / name
    p.write_text(MODEL + grid + "\n")
    return p


def points(path) -> dict:
    return {r["index"]: r for r in json.loads(Path(path).read_text())["points"]}


def results(path) -> dict:
    return {i: (r["status"], r.get("values"), r.get("result")) for i, r in points(path).items()}


def test_grid_change_without_manifest_recomputes_stale_points(tmp_path, capsys):
    p = model(tmp_path, 'grid = { "force.0.omega" = [0.8, 1.0, 1.2] }')
    assert run_sweep(p, out=tmp_path / "o", workers=0, progress=False) == 0
    (tmp_path / "o" / "sweep.json").unlink()
    p = model(tmp_path, 'grid = { "force.0.omega" = [0.9, 1.0, 1.3] }')
    capsys.readouterr()
    assert run_sweep(p, resume=tmp_path / "o", workers=0, json_path=tmp_path / "r.json", progress=False) == 0
    err = capsys.readouterr().err
    assert "1 already done" in err and "2 stale" in err           # 1.0 is the same point at the same index
    got = points(tmp_path / "r.json")
    assert [got[i]["values"]["force.0.omega"] for i in range(3)] == [0.9, 1.0, 1.3]
    fresh = run_sweep(p, out=tmp_path / "f", workers=0, json_path=tmp_path / "f.json", progress=False)
    assert fresh == 0 and results(tmp_path / "f.json") == results(tmp_path / "r.json")
    assert json.loads((tmp_path / "r.json").read_text())["recomputed"] == {"stale": [0, 2]}


def test_changed_model_with_manifest_is_refused(tmp_path):
    from discrete.errors import ModelError

    p = model(tmp_path, 'grid = { "force.0.omega" = [0.8, 1.2] }')
    assert run_sweep(p, out=tmp_path / "o", workers=0, progress=False) == 0
    p.write_text(p.read_text().replace("c = 0.2", "c = 0.3"))        # not a swept key
    with pytest.raises(ModelError, match="another model, analysis or grid"):
        run_sweep(p, resume=tmp_path / "o", workers=0, progress=False)


@pytest.mark.parametrize("content, reason", [('{"index": 1, "status": "ok"}', "incomplete"),
                                             ('[1, 2, 3]', "incomplete"), ('{"index": 1, "sta', "unreadable")])
def test_untrusted_point_files_are_recomputed(tmp_path, capsys, content, reason):
    p = model(tmp_path, 'grid = { "force.0.omega" = [0.8, 1.2] }')
    assert run_sweep(p, out=tmp_path / "o", workers=0, json_path=tmp_path / "a.json", progress=False) == 0
    (tmp_path / "o" / "points" / "000001.json").write_text(content)
    (tmp_path / "o" / "sweep.json").write_text('{"model": "m.toml", "poi')            # truncated manifest
    capsys.readouterr()
    assert run_sweep(p, resume=tmp_path / "o", workers=0, json_path=tmp_path / "b.json", progress=False) == 0
    err = capsys.readouterr().err
    assert f"1 {reason}" in err and "sweep.json" in err and "rewritten" in err
    assert results(tmp_path / "b.json") == results(tmp_path / "a.json")


def test_unusable_output_locations_fail_before_any_point(tmp_path):
    p = model(tmp_path, 'grid = { "force.0.omega" = [0.8, 1.2] }')
    blocker = tmp_path / "file"
    blocker.write_text("")
    for argv in (["--out", str(blocker / "sub")], ["--out", "/proc/drivefem-sweep"],
                 ["--out", str(tmp_path / "ok"), "--json", str(blocker / "x.json")],
                 ["--out", str(tmp_path / "ok2"), "--json", "/proc/drivefem-sweep.json"]):
        r = subprocess.run(CLI + ["sweep", str(p), "--workers", "0"] + argv, capture_output=True, text=True,
                           cwd=ROOT, timeout=120)
        assert r.returncode == 2, (argv, r.stderr)
        assert "Traceback" not in r.stderr and "not valid" in r.stderr
        assert not list((tmp_path / "ok" / "points").glob("*.json")) if (tmp_path / "ok").exists() else True


def _start(p, out, extra=()):
    return subprocess.Popen(CLI + ["sweep", str(p), "--workers", "0", "--resume" if out.exists() else "--out",
                                   str(out), *extra], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)


def _computed(stderr: str) -> int:
    line = [ln for ln in stderr.splitlines() if "computed by this run" in ln][-1]
    return int(line.split(";")[-1].split()[0])


def _wait_for_start(proc, timeout=120.0):
    """Block until the sweep has opened its store (its "sweep: N points" line), so that a kill lands while
    points are being computed, whatever the start-up time on a loaded machine."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        ready, _, _ = select.select([proc.stderr], [], [], 0.5)
        if ready:
            line = proc.stderr.readline()
            if " points, " in line or not line:
                return
        elif proc.poll() is not None:
            return
    raise AssertionError("the sweep did not start within the timeout")


def test_kills_at_random_moments_lose_and_duplicate_nothing(tmp_path):
    """Three SIGKILLs at random moments, then a resume: every point present and trusted, no finished point
    file ever rewritten (same inode and mtime), results bit-identical to an uninterrupted run."""
    grid = 'grid = { "force.0.omega" = { start = 0.6, stop = 1.6, points = 24 } }'
    p = model(tmp_path, grid)
    p.write_text(p.read_text().replace("t_end = 20.0", "t_end = 15000.0"))     # ~0.25 s a point
    assert run_sweep(p, out=tmp_path / "ref", workers=0, json_path=tmp_path / "ref.json", progress=False) == 0
    out = tmp_path / "k"
    rng = random.Random(20261124)
    seen: dict[str, tuple] = {}
    kills = 0
    for _ in range(3):
        proc = _start(p, out)
        _wait_for_start(proc)                       # start-up takes 1.5 s to several s under a loaded machine
        time.sleep(rng.uniform(0.0, 1.2))           # then a point every ~0.25 s
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            kills += 1
        proc.wait(timeout=60)
        for f in (out / "points").glob("*.json"):
            st = f.stat()
            if f.name in seen:
                assert seen[f.name] == (st.st_ino, st.st_mtime_ns), f"{f.name} was rewritten"
            seen[f.name] = (st.st_ino, st.st_mtime_ns)
    assert kills >= 1
    fin = subprocess.run(CLI + ["sweep", str(p), "--workers", "0", "--resume", str(out), "--json",
                                str(tmp_path / "k.json")], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert fin.returncode == 0, fin.stderr
    for f in (out / "points").glob("*.json"):
        if f.name in seen:
            assert seen[f.name] == (f.stat().st_ino, f.stat().st_mtime_ns), f"{f.name} was rewritten by the resume"
    assert len(points(tmp_path / "k.json")) == 24
    assert results(tmp_path / "k.json") == results(tmp_path / "ref.json")
    assert not list((out / "points").glob("*.claim")) and not list((out / "points").glob("*.tmp"))


def test_two_concurrent_resumes_split_the_work(tmp_path):
    grid = 'grid = { "force.0.omega" = { start = 0.6, stop = 1.6, points = 16 } }'
    p = model(tmp_path, grid)
    p.write_text(p.read_text().replace("t_end = 20.0", "t_end = 15000.0"))
    out = tmp_path / "c"
    assert run_sweep(p, out=out, workers=0, progress=False, json_path=tmp_path / "first.json") == 0
    first = results(tmp_path / "first.json")
    for f in (out / "points").glob("*.json"):
        f.unlink()                                           # a resume with everything still to do
    a, b = _start(p, out, ["--json", str(tmp_path / "a.json")]), _start(p, out, ["--json", str(tmp_path / "b.json")])
    ea, eb = a.communicate(timeout=300)[1], b.communicate(timeout=300)[1]
    assert a.returncode == 0 and b.returncode == 0, (ea, eb)
    ka, kb = _computed(ea), _computed(eb)
    assert ka + kb == 16 and ka > 0 and kb > 0, (ka, kb)      # split, nothing computed twice
    pids = {r["run"]["pid"] for r in points(tmp_path / "a.json").values()}
    assert pids == {a.pid, b.pid}
    assert results(tmp_path / "a.json") == results(tmp_path / "b.json") == first


def test_a_claim_removes_the_temporary_file_a_killed_run_left(tmp_path):
    """A run killed between writing a point's temporary file and renaming it leaves NNNNNN.PID.tmp; the run
    that claims the point next (its only writer from then on) removes it, and keeps its own."""
    from fem.app.sweep_store import SweepStore

    store = SweepStore(tmp_path / "s", {"m": 1}, "simulate", 1, [{"a": 1.0}, {"a": 2.0}])
    store.open("--out")
    dead = store.dir / "000001.4194304.tmp"
    other = store.dir / "000000.4194304.tmp"
    dead.write_text("{")
    other.write_text("{")
    assert store.claim(1)
    assert not dead.exists() and other.exists()             # only the claimed point's leftovers
    store.release_all()
