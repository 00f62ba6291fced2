"""The shortcuts that make an HB curve and its named outputs cheap must give what the long ways give:
the problems of a curve's points retuned from the first (ProblemSpec.problems) equal the ones built from
scratch; the batched reductions of the named outputs equal the scalar ones bit for bit; the shared grid
tables are read-only; the fold refinement by the root of the slope dw/ds equals Newton on the extended
system where both apply, and finds the fold next to a grazing without scipy.optimize."""
import subprocess
import sys

import numpy as np
import pytest

from discrete.loads.channels import history_quantities, summaries, summary
from discrete.steady.continuation import refine_fold, refine_fold_bounded
from discrete.steady.harmonics import grid_tables
from discrete.steady.hb_curve import residual_function
from fem.study import Study
from validation.examples import example_doc

STEADY_EXAMPLES = ["steady_duffing.toml", "steady_gap.toml", "steady_seed002.toml", "steady_coulomb.toml",
                   "hybrid_afc_vibro_impact.toml", "hybrid_afc_friction_rod.toml", "geared_rattle.toml"]


def _same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(a, b)
    if isinstance(a, (list, tuple)) and a and isinstance(a[0], np.ndarray):
        return len(a) == len(b) and all(np.array_equal(x, y) for x, y in zip(a, b))
    if isinstance(a, list) and a and hasattr(a[0], "__dataclass_fields__"):
        return len(a) == len(b) and all(_same(getattr(x, k), getattr(y, k)) for x, y in zip(a, b)
                                        for k in x.__dataclass_fields__)
    if isinstance(a, dict) and a and hasattr(next(iter(a.values())), "__dataclass_fields__"):
        return a.keys() == b.keys() and all(_same([a[k]], [b[k]]) for k in a)
    return a == b


@pytest.mark.parametrize("name", STEADY_EXAMPLES)
def test_retuned_problems_equal_the_built_ones(name):
    spec = Study.parse(example_doc(name)).problem_spec()
    ws = [1.3, 2.7, 513.0]
    for a, b in zip(spec.problems(ws), [spec.problem(w) for w in ws]):
        keys = (set(a.__dict__) | set(b.__dict__)) - {"elements", "omega_max", "rate_max"}
        differ = [k for k in keys if not _same(a.__dict__.get(k), b.__dict__.get(k))]
        assert not differ, differ
        assert a.omega_max == b.omega_max and a.rate_max == b.rate_max
        assert [type(e) for e in a.elements] == [type(e) for e in b.elements]
        assert all(x is not y for x, y in zip(a.elements, b.elements))


def test_batched_history_reductions_equal_the_scalar_ones():
    rng = np.random.default_rng(3)
    for m in (1, 2, 5, 64, 1025):
        t = np.sort(rng.random(m)) * 2.0
        Y = rng.standard_normal((6, m)) + 3.0 * rng.random((6, 1))
        rows = summaries(t, Y, [True, False] * 3)
        for k in range(6):
            assert rows[k] == summary(t, Y[k], k % 2 == 0)
        T = np.sort(rng.random((4, m)), axis=1)          # one sampling per history
        Y3 = rng.standard_normal((3, 4, m))
        q = history_quantities(T, Y3)
        for c in range(3):
            for p in range(4):
                s = summary(T[p], Y3[c, p], False)
                assert (q["peak"][c, p], q["mean"][c, p], q["rms"][c, p]) == (s["peak"], s["mean"], s["rms"])
    # instants that cover no time: the plain mean
    assert summary(np.zeros(3), np.array([1.0, 2.0, 6.0]), False)["mean"] == 3.0


def test_grid_tables_are_shared_and_read_only():
    a, b = grid_tables(7, 64), grid_tables(7, 64)
    assert a is b
    for arr in (a.G, a.D, a.DG, a.DDG, a.Pm, a.W, a.theta, *a.galerkin_maps):
        assert not arr.flags.writeable
    with pytest.raises(ValueError):
        a.G[0, 0] = 2.0


def _stop_fold_points():
    """The one-sided penalty stop of the pyHarm comparison: its branch points around both folds."""
    d = {"title": "one-sided penalty stop", "body": [{"name": "mass", "inertia": 1.0}],
         "spring": [{"between": ["ground", "mass"], "k": 1.0}], "damper": [{"between": ["ground", "mass"], "c": 0.05}],
         "gap": [{"name": "stop", "body": "mass", "k": 10.0, "upper": 0.5}],
         "force": [{"body": "mass", "amplitude": 0.05, "omega": 1.0, "phase": np.pi / 2}],
         "steady": {"method": "hb", "omega": [0.5, 2.0], "harmonics": 15, "samples": 1024, "stability": False,
                    "ds_max": 0.6, "response": {"body": "mass", "measure": "h1"}}}
    return d


STOP_TOML = """title = "one-sided penalty stop"
[[body]]
name = "mass"
inertia = 1.0
[[spring]]
between = ["ground", "mass"]
k = 1.0
[[damper]]
between = ["ground", "mass"]
c = 0.05
[[gap]]
name = "stop"
body = "mass"
k = 10.0
upper = 0.5
[[force]]
body = "mass"
amplitude = 0.05
omega = 1.0
phase = 1.5707963267948966
[steady]
method = "hb"
omega = [0.5, 2.0]
harmonics = 15
samples = 1024
stability = false
ds_max = 0.6
response = { body = "mass", measure = "h1" }
"""


def test_the_slope_root_refinement_equals_newton_and_the_bounded_search():
    """At the smooth fold near 1.2283 (contact all along) Newton on the extended system, the root of dw/ds
    and the bounded search of the values find the same fold (to the refinements' 1e-10 resolution in the
    parameter: w is stationary there, so to ~1e-13 in w)."""
    from discrete.steady.hb import HBModel

    d = _stop_fold_points()
    r = Study.parse(d).forced()
    hb = HBModel(Study.parse(d).steady_model().system, harmonics=15, samples=1024)
    fun = residual_function(hb)
    folds = sorted(f["omega"] for f in r.folds)
    assert len(folds) == 2
    w_hi = folds[1]
    # the two points that bracket it along the branch: where the tangent's omega component changes sign
    W = np.asarray(r.omega)
    j = next(k for k in range(len(W) - 2)
             if (W[k + 1] - W[k]) * (W[k + 2] - W[k + 1]) < 0 and abs(W[k + 1] - w_hi) < 0.05)
    xa, xb = np.asarray(r.states[j]).ravel(), np.asarray(r.states[j + 2]).ravel()
    xs = np.full(xa.size, max(np.abs(xa).max(), 1e-12))
    _, w_root = refine_fold(fun, xa, W[j], xb, W[j + 2], xs)
    _, w_box = refine_fold_bounded(fun, xa, W[j], xb, W[j + 2], xs, True)
    assert abs(w_root - w_hi) <= 1e-12 * w_hi and abs(w_box - w_hi) <= 1e-12 * w_hi, (w_root, w_box, w_hi)


def test_the_fold_next_to_a_grazing_needs_no_scipy_optimize(tmp_path):
    """drivefem forced of the one-sided stop: its lower fold (1.04180, the orbit grazing the stop) is
    refined by the slope root, and the command never imports scipy.optimize (~0.07 s of its start-up)."""
    import json

    model = tmp_path / "stop.toml"
    model.write_text(STOP_TOML)
    code = ("import atexit, sys; from fem.app import cli; sys.argv = ['drivefem', 'forced', sys.argv[1], '--json', "
            "sys.argv[2]]; atexit.register(lambda: print('OPT', 'scipy.optimize' in sys.modules)); cli.main()")
    out = subprocess.run([sys.executable, "-c", code, str(model), str(tmp_path / "o.json")], capture_output=True,
                         text=True)
    assert out.stdout.strip().splitlines()[-1] == "OPT False" and out.returncode == 0, (out.stdout[-2000:]
                                                                                        + out.stderr[-2000:])
    folds = sorted(f["omega"] for f in json.loads((tmp_path / "o.json").read_text())["folds"])
    assert abs(folds[0] - 1.0418038632940971) <= 1e-5 * 1.04 and abs(folds[1] - 1.2283215565531747) <= 1e-5 * 1.23


def test_a_one_shot_command_ends_its_process_with_its_code_and_its_output(tmp_path):
    """Run as the program, a one-shot command ends inside main() (cli._end_process): the exit code is the
    command's, everything printed reaches a pipe, the files it wrote are complete, the exit handlers run;
    a long-lived command (validate) and main(argv) return normally."""
    import json

    model = tmp_path / "stop.toml"
    model.write_text(STOP_TOML)
    code = ("import atexit, sys; from fem.app import cli; sys.argv = ['drivefem'] + sys.argv[1:]; "
            "atexit.register(lambda: print('HANDLER RAN')); cli.main(); print('NOT REACHED')")
    out = subprocess.run([sys.executable, "-c", code, "forced", str(model), "--json", str(tmp_path / "o.json"),
                          "--csv", str(tmp_path / "o.csv")], capture_output=True, text=True)
    assert out.returncode == 0 and "NOT REACHED" not in out.stdout, out.stderr[-2000:]
    lines = out.stdout.strip().splitlines()
    assert lines[-1] == "HANDLER RAN" and any("wrote" in line for line in lines), out.stdout[-2000:]
    assert json.loads((tmp_path / "o.json").read_text())["n_points"] > 10
    assert (tmp_path / "o.csv").read_text().count("\n") > 10
    bad = subprocess.run([sys.executable, "-c", code, "forced", str(tmp_path / "missing.toml")], capture_output=True,
                         text=True)
    assert bad.returncode == 2 and "drivefem: error" in bad.stderr and "NOT REACHED" not in bad.stdout
    from fem.app import cli

    assert cli.main(["schema"]) == 0
