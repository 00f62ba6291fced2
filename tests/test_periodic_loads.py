"""Periodic non-harmonic loads ([[load]] waveform, [analysis] period): exact series, the model-file rules,
and the JSON of drivefem forced."""
import json
import math

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.motion.waveforms import unit_waveform
from fem.app.cli import main
from fem.modelfile.source import read_toml
from fem.study import Study
from validation.examples import EXAMPLES

EXAMPLE = EXAMPLES / "forced_periodic_load.toml"


@pytest.mark.parametrize("kind, kw", [("triangle", {}), ("sawtooth", {}), ("square", {"duty": 0.25}),
                                      ("table", {"s_points": [0, 0.125, 0.5, 1], "values": [0, 2, -1, 0]})])
def test_exact_coefficients_equal_a_dense_fft(kind, kw):
    """Knots on the FFT grid (and the midpoint at jumps): the sampled coefficients converge to the exact ones
    like 1/N^2 (piecewise linear) -- agreement to 1e-6 at N = 2^14."""
    w = unit_waveform(kind, **kw)
    mean, c = w.coefficients(8)
    N = 1 << 14
    f = np.fft.rfft(w(np.arange(N) / N)) / N
    assert abs(mean - f[0].real) < 1e-12
    assert np.max(np.abs(c - 2 * f[1:9])) < 1e-6


def _doc(**analysis):
    d = read_toml(EXAMPLE)
    d["analysis"].update(analysis)
    return d


@pytest.mark.parametrize("change, key", [
    (lambda d: d["analysis"].pop("period"), "[load.1]: waveform"),
    (lambda d: d["analysis"].update(omega_rad_s=[1.0]), "[analysis]: omega_rad_s"),
    (lambda d: d["load"][0].update(waveform={"kind": "triangle", "duty": 0.3}), "duty"),
    (lambda d: d["load"][0].update(waveform={"kind": "table", "t": [0, 0.5, 0.9], "value": [0, 1, 0]}), "t"),
    (lambda d: d["load"][0].update(waveform={"kind": "table", "t": [0, 0.5, 1], "value": [0, 1, 2]}), "value"),
    (lambda d: (d["analysis"].pop("period"), d["load"][0].pop("waveform"), d["analysis"].update(omega_rad_s=[1.0])),
     "[analysis]: harmonics"),
])
def test_model_file_rules(change, key):
    d = read_toml(EXAMPLE)
    change(d)
    with pytest.raises(ModelError) as e:
        Study.parse(d).forced()
    assert key in str(e.value)


def test_drive_file_refuses_period():
    d = read_toml(EXAMPLES / "drive_forced.toml")
    d["analysis"]["period"] = 0.1
    for k in ("frequencies_hz", "omega_rad_s", "sweep_hz"):
        d["analysis"].pop(k, None)
    with pytest.raises(ModelError, match="period"):
        Study.parse(d)


def test_cli_json_has_the_period_and_the_peak(tmp_path, capsys):
    out = tmp_path / "p.json"
    assert main(["forced", str(EXAMPLE), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["periodic"]["period"] == 0.1 and d["periodic"]["harmonics"] == 200
    assert len(d["omega_rad_s"]) == 201 and math.isclose(d["omega_rad_s"][1], 2 * math.pi / 0.1)
    assert d["periodic"]["peak"][0] == pytest.approx(0.0165634, rel=1e-5)     # exact periodic state: 0.0165634
    assert "peak |q| over a period" in capsys.readouterr().out


def test_omega2_loads_rules_and_superposition():
    """scaling = "omega2" is refused with a waveform or a period; mixed with a constant load the response is
    the sum (linear superposition), each part checked against its own run."""
    d = read_toml(EXAMPLE)
    d["load"][0]["scaling"] = "omega2"
    with pytest.raises(ModelError, match="scaling"):
        Study.parse(d)
    d = read_toml(EXAMPLE)
    d["load"][0].pop("waveform")
    d["load"][0]["scaling"] = "omega2"
    with pytest.raises(ModelError, match="scaling"):
        Study.parse(d).forced()
    base = {"title": "t", "body": [{"name": "a", "inertia": 1.0}], "spring": [{"between": ["ground", "a"], "k": 100.0}],
            "damper": [{"between": ["ground", "a"], "c": 0.5}],
            "analysis": {"type": "forced", "omega_rad_s": [3.0, 9.0, 20.0]}}
    const = dict(base, load=[{"body": "a", "amplitude": 2.0}])
    unb = dict(base, load=[{"body": "a", "amplitude": 0.01, "scaling": "omega2", "phase_deg": 30.0}])
    both = dict(base, load=const["load"] + unb["load"])
    rc, ru, rb = (Study.parse(x).forced().response[:, 0] for x in (const, unb, both))
    w = np.array([3.0, 9.0, 20.0])
    H = 1 / (100.0 - w ** 2 + 0.5j * w)
    assert np.allclose(ru, 0.01 * np.exp(1j * math.radians(30)) * w ** 2 * H, rtol=1e-12)
    assert np.allclose(rb, rc + ru, rtol=1e-12)
