"""The output contract (docs/cli.md, docs/outputs.md): every command's JSON says what it is, modal and
forced give one documented shape for every kind of model, complex numbers are {re, im}, and no
number is ever NaN or infinite (a result that became non-finite is exit 4, naming its place)."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from fem.app.cli import main

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"
MODAL_KEYS = {"schema", "version", "title", "kind", "omega_rad_s", "frequencies_hz", "omega_rad_s_unverified",
              "n_dofs", "n_modes", "residuals", "rayleigh_rel_diff", "precision_bound", "reliable",
              "rigid_body_modes", "mode_shapes", "method", "warnings"}
FORCED_KEYS = {"schema", "version", "title", "kind", "frequencies_hz", "omega_rad_s", "outputs", "amplitude",
               "phase_lag_deg", "response", "method", "damping", "warnings", "steady"}


def strict(path):
    """Parse JSON refusing NaN/Infinity tokens."""
    def bad(token):
        raise AssertionError(f"non-finite number {token} in {path}")
    return json.loads(Path(path).read_text(), parse_constant=bad)


def run(tmp_path, *argv):
    out = tmp_path / "out.json"
    rc = main([argv[0], str(EX / argv[1]), "--json", str(out), *argv[2:]])
    return rc, strict(out)


@pytest.mark.parametrize("name,kind", [("cantilever.toml", "fe"), ("two_mass_chain.toml", "lumped"),
                                       ("drive_regular.toml", "drive")])
def test_modal_contract_for_every_kind(tmp_path, name, kind):
    rc, d = run(tmp_path, "modal", name)
    assert rc == 0 and d["schema"] == "drivefem.modal" and d["version"] == 2 and d["kind"] == kind
    assert MODAL_KEYS <= set(d)
    n = d["n_modes"]
    for key in ("omega_rad_s", "frequencies_hz", "residuals", "rayleigh_rel_diff", "precision_bound", "reliable"):
        assert len(d[key]) == n, key
    assert d["mode_shapes"]
    if kind == "drive":
        assert "named_outputs" not in d
    else:                   # one layout of the named outputs: description + one value per mode
        assert d["named_outputs"] and isinstance(d["named_outputs_notes"], list)
        for name, o in d["named_outputs"].items():
            assert {"quantity", "unit", "source", "where"} <= set(o) and len(o["modes"]) == n, name


@pytest.mark.parametrize("name,kind,steady", [("forced_torsion.toml", "fe", False), ("sdof_base_motion.toml", "lumped", False),
                                              ("drive_forced.toml", "drive", False), ("steady_gap.toml", "lumped", True)])
def test_forced_contract_outputs_by_frequencies(tmp_path, name, kind, steady):
    rc, d = run(tmp_path, "forced", name)
    assert rc == 0 and d["schema"] == "drivefem.forced" and d["kind"] == kind and d["steady"] is steady
    assert FORCED_KEYS <= set(d)
    nf, no = len(d["omega_rad_s"]), len(d["outputs"])
    assert np.array(d["amplitude"]).shape == (no, nf)
    assert np.allclose(d["frequencies_hz"], np.array(d["omega_rad_s"]) / (2 * math.pi))
    if steady:
        assert d["response"] is None and {"stable", "max_multiplier", "folds", "reason"} <= set(d)
    else:
        z = d["response"]
        assert len(z) == no and len(z[0]) == nf and set(z[0][0]) == {"re", "im"}
        assert abs(complex(z[0][0]["re"], z[0][0]["im"])) == pytest.approx(d["amplitude"][0][0])
    if kind == "drive":
        assert "named_outputs" not in d
    else:                   # one layout: description + values over the frequencies (curve points)
        for name, o in d["named_outputs"].items():
            assert {"quantity", "unit", "source", "where"} <= set(o), name
            assert len(o["amplitude"]) == nf, name


@pytest.mark.parametrize("name", ["discrete_coulomb_decay.toml", "hybrid_bar_wall.toml"])
def test_simulate_contract(tmp_path, name):
    rc, d = run(tmp_path, "simulate", name)
    assert rc == 0 and d["schema"] == "drivefem.simulate"
    assert {"t_end", "events", "period", "energy_error", "stopped_early", "reason"} <= set(d)


def test_schema_command(tmp_path, capsys):
    assert main(["schema", "lumped"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["title"] == "drivefem lumped model file" and "body" in s["properties"]
    assert main(["schema", "--out", str(tmp_path / "s.json")]) == 0
    assert "anyOf" in strict(tmp_path / "s.json")


def test_non_finite_result_is_exit_4_naming_where(tmp_path, capsys, monkeypatch):
    """A result that became NaN is never written: exit 4 with the JSON place of the first one."""
    import fem.study

    real = fem.study.Study.modal

    def poisoned(self, *a, **kw):
        res = real(self, *a, **kw)
        res.residuals[1] = float("nan")
        return res

    monkeypatch.setattr(fem.study.Study, "modal", poisoned)
    rc = main(["modal", str(EX / "cantilever.toml"), "--json", str(tmp_path / "o.json")])
    assert rc == 4 and "not finite at $.residuals[1]" in capsys.readouterr().err
    assert not (tmp_path / "o.json").exists()


def test_extreme_scales_are_solved_or_refused_never_crash(tmp_path, capsys):
    """Masses 1e90 apart with stiffnesses 1e100 (within the schema's magnitudes): once refused, now solved by
    the dense fallback (issue 16) -- both frequencies equal the closed form of the 2x2 chain to 1e-12."""
    m = tmp_path / "m.toml"
    m.write_text('[[body]]\nname = "a"\ninertia = 1e-90\n[[body]]\nname = "b"\ninertia = 1.0\n'
                 '[[spring]]\nbetween = ["ground", "a"]\nk = 1e100\n[[spring]]\nbetween = ["a", "b"]\nk = 1e100\n'
                 '[[spring]]\nbetween = ["ground", "b"]\nk = 1e100\n[analysis]\ntype = "modal"\n')
    out = tmp_path / "o.json"
    rc = main(["modal", str(m), "--json", str(out)])
    err = capsys.readouterr().err
    assert "Traceback" not in err and "internal error" not in err
    assert rc == 0, err
    m1, m2, k = 1e-90, 1.0, 1e100
    b, c = 2 * k * (m1 + m2), 3 * k * k                   # m1 m2 lam^2 - b lam + c = 0, stable roots
    l1 = 2 * c / (b + math.sqrt(b * b - 4 * m1 * m2 * c))
    l2 = c / (m1 * m2 * l1)
    f = json.loads(out.read_text())["frequencies_hz"]
    assert f == pytest.approx([math.sqrt(l1) / (2 * math.pi), math.sqrt(l2) / (2 * math.pi)], rel=1e-12)


def test_numbers_beyond_any_physical_scale_are_bad_input(tmp_path, capsys):
    m = tmp_path / "m.toml"
    m.write_text('[[body]]\nname = "a"\ninertia = 1e-308\n[[spring]]\nbetween = ["ground", "a"]\nk = 1e308\n')
    assert main(["modal", str(m)]) == 2
    assert "[body #1]: inertia = 1e-308 is not valid; allowed: a number of magnitude between 1e-100 and 1e+100" \
        in capsys.readouterr().err


def test_free_chain_without_stiffness_has_exact_rigid_modes(tmp_path):
    m = tmp_path / "k0.toml"
    m.write_text('[[body]]\nname = "a"\ninertia = 1.0\n[[body]]\nname = "b"\ninertia = 1.0\n'
                 '[[spring]]\nbetween = ["ground", "a"]\nk = 0.0\n[[spring]]\nbetween = ["a", "b"]\nk = 0.0\n')
    assert main(["modal", str(m), "--json", str(tmp_path / "o.json")]) == 0
    d = strict(tmp_path / "o.json")
    assert d["rigid_body_modes"] == 2 and d["residuals"] == [0.0, 0.0] and d["omega_rad_s"] == [0.0, 0.0]


def test_output_paths_are_checked_before_any_work(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    rc = main(["modal", str(EX / "cantilever.toml"), "--json", str(blocker / "sub" / "o.json")])
    assert rc == 2 and "--json" in capsys.readouterr().err
    rc = main(["simulate", str(EX / "discrete_coulomb_decay.toml"), "--png", str(blocker)])
    assert rc == 2 and "a directory" in capsys.readouterr().err
