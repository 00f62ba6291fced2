"""examples/rotor_friswell.py runs and reproduces its numbers (Friswell et al. 2010, Example 5.9.1 and variants)."""
import importlib.util
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rotor_friswell.py"


@pytest.fixture(scope="module")
def numbers():
    spec = importlib.util.spec_from_file_location("rotor_friswell_example", EXAMPLE)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.main(verbose=False)


def test_friswell_591_printed_frequencies(numbers):
    """Friswell's printed values at 4000 rev/min, 6 elements (half a unit of the last digit)."""
    w = numbers["modes_4000rpm"]["isotropic (5.9.1)"]["omega_rad_s"]
    for got, printed in zip(w, (85.39, 87.80, 251.78, 294.71, 600.18, 650.41)):
        assert abs(got - printed) <= 0.005
    assert numbers["modes_4000rpm"]["isotropic (5.9.1)"]["kind"][-1] == "torsion"
    assert numbers["modes_4000rpm"]["isotropic (5.9.1)"]["whirl"][:2] == ["backward", "forward"]


def test_variants(numbers):
    m = numbers["modes_4000rpm"]
    assert m["anisotropic (5.9.2)"]["omega_rad_s"][:2] == pytest.approx([82.325, 86.864], abs=5e-3)
    damped = m["damped (5.9.5)"]
    assert damped["omega_rad_s"][:2] == pytest.approx([85.966, 88.415], abs=5e-3)
    assert damped["log_decrement"][:2] == pytest.approx([0.2984, 0.3370], abs=5e-4)
    cc = m["cross-coupled (5.9.4)"]
    assert cc["log_decrement"][1] < 0 < cc["log_decrement"][0]       # cross-coupling destabilises forward whirl


def test_damped_rotor_reports(numbers):
    assert numbers["critical_speeds_rpm"][:2] == pytest.approx([835.7, 2979.2], abs=0.05)
    assert set(numbers["critical_whirl"]) == {"forward"}
    assert numbers["backward_crossings_rpm"][:2] == pytest.approx([830.8, 2615.5], abs=0.05)
    first = numbers["peaks"][0]
    assert first["speed_rpm"] == pytest.approx(839.3, abs=0.05)
    assert first["AF"] == pytest.approx(9.58, abs=0.01) and first["passes"] is True
    assert first["SM_required"] == pytest.approx(14.9, abs=0.05)
    assert numbers["static_sag_um"] == pytest.approx(1443.9, abs=0.05)
    assert numbers["threshold_rpm"] == pytest.approx(8104.3, abs=0.05) and numbers["threshold_whirl"] == "forward"
