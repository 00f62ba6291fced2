"""Start-up of the command line: ``drivefem forced`` of a one-DOF steady file imports only what it needs
(issue 27, item 5).  Heavy packages that such a run never uses must stay out of the process: their
import costs 0.1 .. 1 s of every run (measured with ``python -X importtime``, docs/steady.md)."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

#: not needed by an HB amplitude-frequency curve of a lumped model (time integration, plots, 3-D, sweeps, units)
# (steady_gap.toml does import scipy.integrate: its linear guess does not converge and the first point
#  comes from a time integration -- needed there)
HEAVY = ("scipy.integrate", "matplotlib", "pyvista", "dask", "pint", "skfem", "meshio", "fem.rotor", "fem.drives",
         "fem.hybrid", "discrete.linear.parametric")

RUN = """
import json, sys
from fem.app.cli import main
code = main(sys.argv[1:])
print(json.dumps({"code": code, "modules": sorted(sys.modules)}))
"""


def _modules(args, tmp_path):
    out = subprocess.run([sys.executable, "-c", RUN, *args], cwd=ROOT, capture_output=True, text=True,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "MPLBACKEND": "Agg"}, timeout=120)
    assert out.returncode == 0, out.stderr
    rec = json.loads(out.stdout.strip().splitlines()[-1])
    return rec["code"], set(rec["modules"])


@pytest.mark.parametrize("example", ["steady_duffing.toml", "steady_coulomb.toml"])
def test_forced_one_dof_imports_no_heavy_module(example, tmp_path):
    code, mods = _modules(["forced", f"examples/{example}", "--json", str(tmp_path / "afc.json")], tmp_path)
    assert code == 0
    loaded = sorted(m for m in HEAVY if m in mods)
    assert not loaded, f"drivefem forced {example} imported {loaded}"
    assert "discrete.steady.afc" in mods         # the run did compute the curve


def test_a_plot_still_imports_matplotlib(tmp_path):
    """The check above can fail: the same run asked for a figure loads matplotlib."""
    code, mods = _modules(["forced", "examples/steady_duffing.toml", "--plot", str(tmp_path / "afc.png")], tmp_path)
    assert code == 0 and "matplotlib" in mods
