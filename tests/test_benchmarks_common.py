"""The benchmark helpers (benchmarks/common.py, benchmarks/report.py): statistics, interleaved
timing, the BENCH-RESULT record and its parser, and the README table replacement between markers."""
from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def _load(name):
    if str(BENCH) not in sys.path:
        sys.path.insert(0, str(BENCH))      # report.py imports common by name, as when run as a script
    spec = importlib.util.spec_from_file_location(name, BENCH / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


common = _load("common")
report = _load("report")


def test_stats_median_and_spread():
    s = common.Stats.of([3.0, 1.0, 2.0, 10.0, 2.5])
    assert (s.median, s.min, s.max, s.n) == (2.5, 1.0, 10.0, 5)
    assert s.spread == pytest.approx((10.0 - 1.0) / 2.5)
    assert common.Stats.of([4, 2]).median == 3.0           # even count: mean of the middle two
    with pytest.raises(ValueError):
        common.Stats.of([])


def test_interleaved_alternates_order_and_counts_runs():
    calls = []
    cands = {"a": lambda: calls.append("a") or 1, "b": lambda: calls.append("b") or 2,
             "slow": lambda: calls.append("slow") or common.Measured(0.5, 0.25, "inner")}
    t = common.interleaved(cands, runs=5, warmup=1, runs_of={"slow": 2})
    assert calls[:3] == ["a", "b", "slow"]                  # warm-up
    assert calls[3:6] == ["a", "b", "slow"]                 # round 1 forward
    assert calls[6:9] == ["slow", "b", "a"]                 # round 2 backward
    assert calls[9:] == ["a", "b", "b", "a", "a", "b"]      # slow done after 2 runs
    assert (t["a"].runs, t["b"].runs, t["slow"].runs) == (5, 5, 2)
    assert t["slow"].wall == [0.5, 0.5] and t["slow"].cpu == [0.25, 0.25]   # times measured elsewhere
    assert t["slow"].result == "inner" and t["b"].result == 2
    w, c = common.speedup(t["slow"], common.Timing(wall=[0.1, 0.1, 0.1], cpu=[0.05, 0.05, 0.05]))
    assert (w, c) == (pytest.approx(5.0), pytest.approx(5.0))


def test_record_target_and_json_round_trip(capsys):
    rec = common.record("benchmarks/x.py", "demo", "pkg", "base", 30.0, (">=", 25), ratio_cpu=20.0,
                        accuracy="period error", accuracy_package=1e-12, accuracy_baseline=float("nan"),
                        runs=5, blas="test BLAS")
    assert rec["script"] == "x.py" and rec["met"] is True and rec["met_cpu"] is False
    assert rec["target"] == ">= 25" and rec["accuracy_baseline"] is None     # NaN -> null (strict JSON)
    assert set(common.RECORD_KEYS) <= set(rec)
    common.emit(rec)
    common.print_summary(rec)
    out = capsys.readouterr().out
    parsed = common.parse_results("noise\n" + out + "more noise\n")
    assert parsed == [json.loads(json.dumps(rec))]
    assert "speed-up 30x (CPU time 20x), target >= 25: MET (CPU time: not met)" in out
    assert common.record("x.py", "t", "p", None, 0.5, ("<", 1), unit="s", metric="time")["met"] is True
    assert common.record("x.py", "t", "p", None, None, (">=", 1))["met"] is None      # not measured
    assert common.record("x.py", "t", "p", None, float("inf"), (">=", 1))["met"] is False


def test_parse_results_rejects_broken_records():
    with pytest.raises(ValueError, match="line 2"):
        common.parse_results("ok\nBENCH-RESULT {not json\n")
    with pytest.raises(ValueError, match="script"):
        common.parse_results('BENCH-RESULT {"what": "no script key"}')
    assert common.parse_results("nothing here\n  BENCH-RESULTS are elsewhere") == []


README = """# Title

text before
<!-- bench-table:begin -->
| old | table |
| --- | --- |
| 1 | 2 |
<!-- bench-table:end -->

text after
"""


def test_replace_table_only_between_markers(tmp_path):
    p = tmp_path / "README.md"
    p.write_text(README)
    new = report.replace_table(p.read_text(), "| new |\n| --- |\n")
    before, after = README.split("<!-- bench-table:begin -->")[0], README.split("<!-- bench-table:end -->")[1]
    assert new.startswith(before + "<!-- bench-table:begin -->\n| new |\n| --- |\n<!-- bench-table:end -->")
    assert new.endswith("<!-- bench-table:end -->" + after)
    assert report.replace_table(new, "| new |\n| --- |") == new          # idempotent
    for bad, msg in ((README.replace("<!-- bench-table:end -->", ""), "exactly one"),
                     (README + "<!-- bench-table:begin -->\n", "exactly one"),
                     (README.replace("<!-- bench-table:begin -->", "@").replace("<!-- bench-table:end -->",
                      "<!-- bench-table:begin -->").replace("@", "<!-- bench-table:end -->"), "before")):
        with pytest.raises(report.MarkerError, match=msg):
            report.replace_table(bad, "x")


def test_collect_from_saved_logs_and_table(tmp_path, capsys):
    rec = common.record("event_solver.py", "events/s", "event-driven", None, 12345.0, (">=", 10000),
                        metric="events/s", unit="events/s", ratio_cpu=20000.0, accuracy="period error",
                        accuracy_package=1e-13, runs=5, blas="b")
    (tmp_path / "event_solver.log").write_text(
        "# benchmarks/event_solver.py\n# exit code 0, wall 12.5 s, cpu 3.0 s\nhello\n"
        + common.PREFIX + json.dumps(rec) + "\n")
    (tmp_path / "solid.log").write_text("# benchmarks/solid.py\n# exit code 0, wall 1.0 s, cpu 1.0 s\nno records\n")
    runs = [report.read_saved("event_solver.py", tmp_path), report.read_saved("solid.py", tmp_path),
            report.read_saved("afc.py", tmp_path)]
    assert (runs[0].returncode, runs[0].wall, runs[0].cpu) == (0, 12.5, 3.0)
    assert runs[0].records[0]["ratio"] == 12345.0 and runs[1].records == []
    assert "no saved output" in runs[2].parse_error
    meta = {"date": "d", "machine": "m", "load_start": "1", "load_end": "2", "blas": "b"}
    table = report.readme_table(runs, meta)
    lines = table.splitlines()
    assert lines[0].startswith("| script |") and len([l for l in lines if l.startswith("| `")]) == 3
    assert "12,345 events/s (CPU time 20,000 events/s); target ≥ 10000 events/s: **MET**" in table
    assert "no BENCH-RESULT line" in table and "no saved output" in table
    readme = tmp_path / "README.md"
    readme.write_text(README)
    assert report.main(["--from", str(tmp_path), "--only", "event_solver", "solid", "--readme", str(readme),
                        "--store", str(tmp_path / "store.json"),
                        "--doc", str(tmp_path / "benchmarks.md")]) == 0
    text = readme.read_text()
    assert "| old | table |" not in text and "12,345 events/s" in text and text.endswith("text after\n")
    assert "hello" in (tmp_path / "benchmarks.md").read_text()
    assert "stick_slip.py" in text and "no stored result" in text             # every script has a row
    store = json.loads((tmp_path / "store.json").read_text())["scripts"]
    assert store["event_solver.py"]["records"][0]["ratio"] == 12345.0
    assert report.main(["--from", str(tmp_path), "--only", "solid", "--readme", str(readme), "--store",
                        str(tmp_path / "store.json"), "--doc", str(tmp_path / "benchmarks.md")]) == 0
    assert "`event_solver.py` (stored run of " in readme.read_text() and "12,345 events/s" in readme.read_text()
    readme.write_text("no markers here\n")
    assert report.main(["--from", str(tmp_path), "--readme", str(readme), "--doc", str(tmp_path / "b.md"),
                        "--store", str(tmp_path / "s2.json")]) == 2
    assert readme.read_text() == "no markers here\n" and not (tmp_path / "b.md").exists()
    capsys.readouterr()


def test_worker_runs_a_snippet_in_a_subprocess():
    setup = "import time\nprint('noise on stdout must not break the protocol')\nN = [0]\n" \
            "def run():\n    N[0] += 1\n    time.sleep(0.01)\n    return {'n': N[0]}\ndef total():\n    return N[0]\n"
    with common.Worker(common.ROOT, setup, label="test") as w:
        m1, m2 = w(), w()
        assert isinstance(m1, common.Measured) and (m1.value, m2.value) == ({"n": 1}, {"n": 2})
        assert m1.wall >= 0.01 and 0 <= m1.cpu < m1.wall
        assert w.call("total") == 2
        with pytest.raises(RuntimeError, match="nothing"):
            w.call("nothing")
    assert w.proc.poll() is not None                       # ended on exit
    with pytest.raises(RuntimeError, match="setup failed"):
        common.Worker(common.ROOT, "raise ValueError('bad snippet')", label="test")


def test_old_release_refuses_an_unknown_commit():
    with pytest.raises(RuntimeError, match="deadbeef|git"):
        common.old_release("deadbeef" * 5)


AFC_OUT = """BLAS: openblas 0.3.30 (libscipy_openblas.so, 1 threads, SkylakeX) -- timed single-threaded
seed 002 AFC, a = 0.00047 m, simplified friction, z = 0.3..2.0
brute force  : 200 frequencies, down-sweep, exact event-driven, peak mu 1.234000 at z = 0.9900, peak error 4.59e-04
               cpu   12.345 s (12.000 .. 13.000, 3 runs)   wall   20.000 s (19.000 .. 21.000, 3 runs)
continuation : 120 branch points (ds_max 0.1), 2 folds, Floquet stability of every point, peak mu 1.2345, peak error 5.00e-05
               cpu    0.100 s (0.090 .. 0.120, 5 runs)   wall    0.250 s (0.140 .. 0.260, 5 runs)
ratio (brute force / continuation): 123.4x cpu, 80.0x wall (target >= 100x)
"""

SOLID_OUT = """3D cantilever L = 1 m, d = 50 mm: 104907 free DOFs (27-node hexahedra, n_quarter = 3), lowest 10 modes; build 9 s
BLAS/LAPACK in use (auto process): openblas 0.3.30 SkylakeX (2 threads, libscipy_openblas.so)
release: release 890424e (SuperLU)   SuperLU LU (release)  18.00s  17.00-19.00s         -         -    2.10GB    1.0e-10    0.0e+00
auto: automatic choice               MKL PARDISO LL^T      5.00s   4.50- 5.50s     2.00s     3.00s    1.20GB    2.0e-10    3.0e-13
(median and spread of 5 runs; load average 1.0 at the start)
speed-up auto vs release: 3.60x (per-run ratios 3.10-3.90)
"""
# the old baseline (this checkout forced to SuperLU): reported, but the target is against the release
SOLID_OUT_TODAY = SOLID_OUT.replace("release: release 890424e (SuperLU)   SuperLU LU (release)  18.00s  17.00-19.00s         -         -",
                                    "today: SuperLU + eager ratio, today's checks superlu  18.00s  17.00-19.00s    12.00s     6.00s") \
    .replace("auto vs release", "auto vs today")


def test_parsers_of_scripts_without_records():
    (afc,) = report.parse_afc(AFC_OUT)
    assert (afc["ratio"], afc["ratio_cpu"], afc["met"], afc["met_cpu"]) == (80.0, 123.4, False, True)
    assert (afc["accuracy_package"], afc["accuracy_baseline"]) == (5e-05, 4.59e-04)
    assert afc["spread"]["baseline"]["wall"] == [20.0, 19.0, 21.0] and afc["runs"] == {"package": 5, "baseline": 3}
    assert "SkylakeX" in afc["blas"] and "parsed" in afc["what"]
    (solid,) = report.parse_solid(SOLID_OUT)
    assert (solid["ratio"], solid["met"], solid["target"]) == (3.6, True, ">= 3")
    assert solid["accuracy_package"] == "2.0e-10 / 3.0e-13" and solid["spread"]["package"]["wall"] == [5.0, 4.5, 5.5]
    assert solid["baseline"] == "release 890424e (SuperLU)" and solid["spread"]["baseline"]["wall"] == [18.0, 17.0, 19.0]
    (today,) = report.parse_solid(SOLID_OUT_TODAY)
    assert (today["ratio"], today["target"], today["met"]) == (3.6, None, None)
    assert today["spread"]["baseline"]["wall"] == [18.0, 17.0, 19.0]
    assert report.parse_afc("the wording changed\n") == [] and report.parse_solid("") == []
    hyb = "BLAS: b\n\nrod: Friction rod (n = 5 DOFs, 1 element(s)); response: x\n" + AFC_OUT.split("\n", 2)[2]
    (rod,) = report.parse_afc_hybrid(hyb)
    assert rod["what"].startswith("hybrid AFC, rod (5 DOFs)") and rod["ratio"] == 80.0 and rod["target"] is None
