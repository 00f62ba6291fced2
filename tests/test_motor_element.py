"""The motor as a model element (discrete.motion.motor) and the transfer-matrix wrapper built on it."""
import math

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.linear.harmonic import harmonic_response
from discrete.lumped import Body, Driver, Link, LumpedModel
from discrete.motion.motor import DynamicMotor, motor_modes, with_motor
from discrete.transfer import damper_matrix, spring_matrix
from discrete.transfer.motor import MotorCharacteristic

CAT = dict(f_mains=50.0, pole_pairs=2, speed_nominal=0.96 * 50 * math.pi, torque_nominal=100.0, torque_ratio=2.2)


def test_catalogue_conversion():
    m = DynamicMotor.from_catalogue(**CAT)
    assert m.omega0 == pytest.approx(157.0796327, rel=1e-9)
    assert m.T == pytest.approx(0.0172372, abs=5e-8)
    assert m.nu == pytest.approx(4.19692e-4, abs=5e-10)
    assert m.c == pytest.approx(880.0, rel=1e-9)          # c_d = 4 pi f M_n xi/omega0 = 2 p xi M_n: slip-free
    rc = m.rotor_constants(0.05)
    assert rc["k"] == pytest.approx(132.665, abs=5e-4) and rc["k1"] == pytest.approx(129.455, abs=5e-4)
    assert m.rotor_constants(2.0)["aperiodic"]


def test_law_and_linearisation_agree():
    m = DynamicMotor(157.0, 3e-3, 0.043)
    # static characteristic and steady speed (5.57) are inverse to each other
    assert m.steady_speed(float(m.static_torque(150.0))) == pytest.approx(150.0)
    # state row reproduces torque_rate
    row = m.state_row()
    M, w = 12.0, 151.0
    assert row["M"] * M + row["omega"] * w + row["const"] == pytest.approx(float(m.torque_rate(M, w)))
    # complex stiffness = damper b in series with spring c (Maxwell element of (10.65)-(10.66))
    om = np.array([0.5, 9.0, 80.0])
    series = 1 / (1 / m.c + 1 / (1j * om * m.b))
    assert np.allclose(m.complex_stiffness(om), series, rtol=1e-14)
    # and equals the clamp-side transfer matrix: torque per rotor angle = 1/B of Gamma_c Gamma_b
    for w_ in om:
        B = (spring_matrix(m.c) @ damper_matrix(m.b, w_))[0, 1]
        assert m.complex_stiffness(w_) == pytest.approx(1 / B, rel=1e-13)


def test_with_motor_equals_frequency_dependent_stiffness():
    m = DynamicMotor(157.0, 3e-3, 0.043)
    mdl = LumpedModel(bodies=[Body("rotor", 0.224), Body("load", 0.1)], springs=[Link(("rotor", "load"), 2000.0)])
    ls = mdl.linear_system()
    aug = with_motor(ls, 0, m)
    assert aug.n_dofs == 3 and aug.label(2) == "motor_maxwell.motor"
    ws = np.array([2.0, 30.0, 140.0])
    F = np.array([0.0, 1.0, 0.0])
    q = harmonic_response(aug, ws, force=F).response
    for j, w in enumerate(ws):
        K = (ls.K.toarray() - w**2 * ls.M.toarray()).astype(complex)
        K[0, 0] += m.complex_stiffness(w)
        assert np.allclose(q[j, :2], np.linalg.solve(K, F[:2]), rtol=1e-12)


def test_rotor_modes_and_transfer_wrapper():
    m = DynamicMotor(157.0, 3e-3, 0.043)
    ls = LumpedModel(bodies=[Body("rotor", 0.224)]).linear_system()
    modes = motor_modes(ls, 0, m)
    assert modes.oscillatory()[0].imag == pytest.approx(9.2313, abs=5e-5)
    assert modes.oscillatory()[0].real == pytest.approx(-0.5 / 0.043, rel=1e-12)
    assert modes.residuals.max() < 1e-12
    mc = MotorCharacteristic(157.0, 3e-3, 0.043)
    assert mc.partial_frequency(0.224) == pytest.approx(m.partial_frequency(0.224))
    damper, spring = mc.elements()
    assert damper.b == pytest.approx(m.b) and spring.c == pytest.approx(m.c)
    assert math.isnan(mc.partial_frequency(100.0))
    assert "omega0" in m.to_dict()


def test_bad_input_names_the_key():
    with pytest.raises(ModelError, match="T = 0"):
        DynamicMotor(157.0, 3e-3, 0.0)
    with pytest.raises(ModelError, match="omega0"):
        MotorCharacteristic(-1.0, 3e-3, 0.04)
    with pytest.raises(ModelError, match="pole_pairs"):
        DynamicMotor.from_catalogue(**{**CAT, "pole_pairs": 0})
    with pytest.raises(ModelError, match="speed_nominal"):
        DynamicMotor.from_catalogue(**{**CAT, "speed_nominal": 200.0})
    with pytest.raises(ModelError, match="torque_ratio"):
        DynamicMotor.from_catalogue(**{**CAT, "torque_ratio": -2.0})
    m = DynamicMotor(157.0, 3e-3, 0.043)
    with pytest.raises(ModelError, match="J"):
        m.rotor_constants(0.0)
    driven = LumpedModel(bodies=[Body("load", 1.0)], drivers=[Driver("d", velocity=1.0)],
                         springs=[Link(("d", "load"), 10.0)]).linear_system()
    with pytest.raises(ModelError, match="dof"):
        with_motor(driven, driven.dof_index(name="d"), m)
    with pytest.raises(ModelError, match="dof"):
        motor_modes(driven, 7, m)


def test_model_file_motor_in_forced_and_modal_warning():
    """drivefem forced on a lumped file with a [[motor]] includes its complex stiffness (the rotor is held by the
    speed characteristic: the low-frequency response stays finite); modal says the motor is not in its modes."""
    from fem.modelfile.source import read_toml
    from fem.study import Study
    from validation.examples import EXAMPLES

    doc = read_toml(EXAMPLES / "motor_drive_forced.toml")
    with_motor_r = Study.parse(doc).forced().response[:, 0]
    bare = dict(doc)
    bare.pop("motor")
    without = Study.parse(bare).forced().response[:, 0]
    assert abs(with_motor_r[0]) == pytest.approx(0.465335, rel=2e-6)      # digest §10.6 at omega = 1
    assert abs(without[0]) > 2 * abs(with_motor_r[0])                    # free drive: ~1/(2 J omega^2)
    modes = Study.parse(doc).modal(2)
    assert any("motor" in w and "motor_modes" in w for w in modes.warnings)
