"""The CLI contract (design.md §5) and every example model (examples double as tests)."""
import json
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

from fem.app.cli import main
from fem.app.demo import _command

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))


def _kind(path):
    return _command(path)[0]


@pytest.mark.parametrize("path", [p for p in EXAMPLES if _kind(p) in ("modal", "forced")], ids=lambda p: p.name)
def test_linear_examples_run(path, tmp_path):
    out = tmp_path / "out.json"
    assert main([_kind(path), str(path), "--json", str(out)]) == 0
    data = json.loads(out.read_text())
    assert data["omega_rad_s"] and all(np.isfinite(v) for v in data["omega_rad_s"] if v is not None)


def test_modal_json_contract(tmp_path):
    out = tmp_path / "cantilever.json"
    r = subprocess.run([sys.executable, "-m", "fem.app.cli", "modal", str(ROOT / "examples" / "cantilever.toml"),
                        "--json", str(out)], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    data = json.loads(out.read_text())
    for key in ("omega_rad_s", "frequencies_hz", "n_dofs", "residuals"):
        assert key in data
    assert data["n_dofs"] == 80 and len(data["omega_rad_s"]) == 6
    # first cantilever frequency (4.72): 1.875104^2 / L^2 sqrt(EI / (rho A))
    EI, rhoA = 211e9 * np.pi * 0.05**4 / 64, 7810 * np.pi * 0.05**2 / 4
    assert data["omega_rad_s"][0] == pytest.approx(1.8751040687**2 / 1.5**2 * np.sqrt(EI / rhoA), rel=1e-7)
    assert max(data["residuals"]) < 1e-10
    assert "mode 1" not in r.stdout or "NOT RELIABLE" not in r.stdout


def test_unreliable_modes_are_not_printed_as_results(tmp_path):
    model = tmp_path / "fine.toml"
    text = (ROOT / "examples" / "cantilever.toml").read_text().replace("elements = 40", "elements = 5000")
    model.write_text(text)
    out = tmp_path / "fine.json"
    rc = main(["modal", str(model), "--modes", "2", "--json", str(out)])
    data = json.loads(out.read_text())
    assert rc == 3
    assert data["omega_rad_s"][0] is None and data["reliable"][0] is False
    assert any("too fine" in w for w in data["warnings"])


def test_forced_outputs(tmp_path):
    csv_path, js = tmp_path / "frf.csv", tmp_path / "frf.json"
    png = tmp_path / "frf.png"
    assert main(["forced", str(ROOT / "examples" / "sdof_base_motion.toml"), "--csv", str(csv_path),
                 "--json", str(js), "--plot", str(png)]) == 0
    data = json.loads(js.read_text())
    assert data["outputs"] == ["mass.x"] and len(data["amplitude"][0]) == 200
    # relative amplitude at 1.59 Hz (z = 1): x0 / (2 delta) = 1e-3 / 0.1
    f = np.array(data["frequencies_hz"])
    rel = np.array(data["relative_amplitude"][0])
    assert rel.max() == pytest.approx(1e-3 * 1.0 / (2 * 0.05 * np.sqrt(1 - 0.05**2)), rel=1e-3)
    assert len(csv_path.read_text().splitlines()) == 201
    assert png.stat().st_size > 10_000


def test_validate_json_and_exit_code(tmp_path):
    out = tmp_path / "v.json"
    rc = main(["validate", "--case", "torsion-end-disc", "--quiet", "--json", str(out), "--report", str(tmp_path / "rep")])
    data = json.loads(out.read_text())
    assert rc == 0 and data["passed"]
    keys = {"name", "source", "quantity", "expected", "computed", "rel_error", "tolerance", "passed"}
    assert keys <= set(data["cases"][0])
    assert (tmp_path / "rep" / "report.md").exists()


def test_validate_unknown_case_is_an_error(capsys):
    assert main(["validate", "--case", "no-such-case", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "--case = 'no-such-case'" in err and "torsion-end-disc" in err


def test_lumped_modal_reports_dunkerley_bound(tmp_path):
    """Digest V4.7b: trace(e m) = 4m/(3c) -> bound 27.386 rad/s, 13.4 % below k_1 = 31.623."""
    out = tmp_path / "chain.json"
    assert main(["modal", str(ROOT / "examples" / "two_mass_chain.toml"), "--json", str(out)]) == 0
    data = json.loads(out.read_text())
    assert data["dunkerley_lower_bound_rad_s"] == pytest.approx(1 / np.sqrt(4 / 3000), rel=1e-12)
    assert data["omega_rad_s"] == pytest.approx([np.sqrt(1000), np.sqrt(3000)], rel=1e-12)
