"""Rotor description, assembly and bad input (fem.rotor.model / assembly)."""
import math

import numpy as np
import pytest
import scipy.sparse as sp

from discrete.errors import ModelError
from fem.rotor import (Bearing, Coupling, Disc, Pedestal, Probe, Rotor, ShaftSegment, Unbalance,
                       assemble_rotor, campbell, rotor_modes, stability_threshold, static_deflection,
                       unbalance_response)
from fem.rotor import elements as el
from fem.sections import Material

STEEL = Material(E=211e9, G=81.2e9, rho=7810.0)


def _rotor(**kw):
    base = dict(segments=[ShaftSegment(1.2, 6, 0.05, STEEL)], discs=[Disc.from_geometry(0.6, 0.05, 0.3, 0.05, 7810.0)],
                bearings=[Bearing(0.0, kyy=1e6, kzz=1e6), Bearing(1.2, kyy=1e6, kzz=1e6)])
    base.update(kw)
    return Rotor(**base)


# ---------------------------------------------------------------- element matrices
def test_element_reduces_to_hermite_for_zero_shear_parameter():
    """Phi -> 0: Nelson's matrices are the Euler-Bernoulli Hermite stiffness, consistent mass and rotary inertia."""
    L, E, rho, d = np.array([0.3]), np.array([2.0e11]), np.array([7800.0]), np.array([0.05])
    z = np.zeros(1)
    K, MT, MR, P, phi = el.plane_matrices(L, E, np.array([1e20]), rho, np.array([1.0]), d, d, z, z, z)
    A, I, l = math.pi * d[0] ** 2 / 4, math.pi * d[0] ** 4 / 64, L[0]
    Kref = E[0] * I / l**3 * np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l],
                                       [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l * l, -6 * l, 4 * l * l]])
    Mref = rho[0] * A * l / 420 * np.array([[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
                                            [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    MRref = rho[0] * I / (30 * l) * np.array([[36, 3 * l, -36, 3 * l], [3 * l, 4 * l * l, -3 * l, -l * l],
                                               [-36, -3 * l, 36, -3 * l], [3 * l, -l * l, -3 * l, 4 * l * l]])
    assert phi[0] < 1e-8
    np.testing.assert_allclose(K[0], Kref, rtol=1e-7, atol=1e-7 * abs(Kref).max())
    np.testing.assert_allclose(MT[0], Mref, rtol=1e-9, atol=1e-9 * abs(Mref).max())
    np.testing.assert_allclose(MR[0], MRref, rtol=1e-7, atol=1e-7 * abs(MRref).max())
    np.testing.assert_allclose(P[0], 2 * MRref, rtol=1e-7, atol=1e-7 * abs(MRref).max())
    # and scikit-fem's assembly of the Hermite element with the package's Euler-Bernoulli forms
    from skfem import Basis, ElementLineHermite, MeshLine, asm

    from fem import forms

    basis = Basis(MeshLine(np.array([0.0, l])), ElementLineHermite(), intorder=6)
    Ks = asm(forms.euler_bernoulli_stiffness, basis, EI=E[0] * I).toarray()
    Ms = asm(forms.euler_bernoulli_mass, basis, rhoA=rho[0] * A).toarray()
    np.testing.assert_allclose(K[0], Ks, rtol=1e-7, atol=1e-7 * abs(Ks).max())
    np.testing.assert_allclose(MT[0], Ms, rtol=1e-9, atol=1e-9 * abs(Ms).max())


def test_assembled_matrices_symmetric_gyroscopic_skew():
    rs = assemble_rotor(_rotor(dofs="full"))
    for A in (rs.M, rs.K0):
        assert abs(A - A.T).max() <= 1e-12 * abs(A).max()
    assert abs(rs.G + rs.G.T).max() <= 1e-14 * abs(rs.G).max() and rs.G.nnz > 0
    assert rs.n_dofs == 7 * 6
    # rigid translation along y carries no strain
    q = np.zeros(rs.n_dofs)
    q[rs.node_dofs["v"]] = 1.0
    shaft_only = assemble_rotor(_rotor(bearings=[], dofs="full"))
    assert np.abs(shaft_only.K0 @ q).max() <= 1e-6 * abs(shaft_only.K0).max()


def test_gravity_load_equals_weight():
    rs = assemble_rotor(_rotor())
    f = rs.gravity_load((0.0, 0.0, -9.81))
    assert np.isclose(f[rs.node_dofs["w"]].sum(), -9.81 * rs.total_mass(), rtol=1e-12)
    assert np.all(f[rs.node_dofs["v"]] == 0)


def test_dof_lookup_and_system_at():
    rs = assemble_rotor(_rotor())
    i = rs.dof(0.6, "w")
    assert rs.dof_field[i] == "w" and rs.dof_x[i] == pytest.approx(0.6)
    sys_ = rs.system_at(100.0)
    assert sys_.G.nnz and sys_.n_dofs == rs.n_dofs
    with pytest.raises(ModelError, match="node position"):
        rs.dof(0.61, "v")
    with pytest.raises(ModelError, match="dof"):
        rs.dof(0.6, "u")                       # lateral model: no axial DOF


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize("kw, key", [
    ({"kyy": 1e6, "kzz": 1e6, "cyy": -5.0}, "cyy"),
    ({"kyy": 1e6, "kzz": 1e6, "czz": -5.0}, "czz"),
    ({"kyy": 1e6, "kzz": 1e6, "cyy": 1.0, "czz": 1.0, "cyz": 3.0, "czy": 3.0}, "cyz"),   # indefinite sym. part
    ({"kyy": 0.0, "kzz": 0.0}, "kyy"),
    ({"cyy": [1e3, -1.0], "czz": 1e3, "speeds": [0.0, 100.0]}, "cyy"),
    ({"kyy": [1e6, 2e6, 3e6], "kzz": 1e6, "speeds": [0.0, 100.0]}, "kyy"),
    ({"kyy": [1e6, 2e6], "kzz": 1e6}, "kyy"),
    ({"kyy": [1e6, 2e6], "kzz": 1e6, "speeds": [100.0, 0.0]}, "speeds"),
    ({"kyy": float("nan"), "kzz": 1e6}, "kyy"),
])
def test_bad_bearing_coefficients(kw, key):
    with pytest.raises(ModelError) as err:
        _rotor(bearings=[Bearing(0.0, **kw), Bearing(1.2, kyy=1e6, kzz=1e6)])
    assert err.value.key == key


def test_cross_coupled_coefficients_may_be_negative():
    _rotor(bearings=[Bearing(0.0, kyy=1e6, kzz=1e6, kyz=-3e5, kzy=3e5, cyz=-10.0, czy=10.0),
                     Bearing(1.2, kyy=1e6, kzz=1e6)])
    with pytest.raises(ModelError, match="positive semidefinite") as err:      # cyz alone: d'^T C d' < 0 possible
        _rotor(bearings=[Bearing(0.0, kyy=1e6, kzz=1e6, cyz=-10.0), Bearing(1.2, kyy=1e6, kzz=1e6)])
    assert err.value.key == "cyz"


def test_stiffness_of_any_sign_and_skew_damping():
    """Seals: negative direct stiffness (also in a table); a skew cross-coupled damping does no work."""
    _rotor(bearings=[Bearing(0.0, kyy=1e6, kzz=1e6), Bearing(1.2, kyy=1e6, kzz=1e6),
                     Bearing(0.6, kyy=[-2e4, 3e4], kzz=-2e4, cyy=1.0, czz=1.0, cyz=50.0, czy=-50.0,
                             speeds=[0.0, 100.0])])


def test_speed_table_outside_its_grid_is_an_error():
    b = Bearing(0.0, kyy=[1e6, 2e6], kzz=1e6, czy=[0.0, 50.0], cyz=[0.0, -50.0], speeds=[100.0, 400.0])
    rs = assemble_rotor(_rotor(bearings=[b, Bearing(1.2, kyy=1e6, kzz=1e6)]))
    rs.system_at(250.0)
    for speed in (50.0, 500.0):
        with pytest.raises(ModelError, match="inside the bearing table") as err:
            rs.system_at(speed)
        assert err.value.key == "speed"
    with pytest.raises(ModelError, match="inside the bearing table"):
        campbell(rs, np.linspace(0.0, 300.0, 5), 2)
    with pytest.raises(ModelError, match="inside the bearing table"):
        unbalance_response(rs, [Unbalance(0.6, 1e-4)], np.linspace(150.0, 600.0, 5))


def test_table_interpolation_linear_and_pchip():
    grid = [0.0, 100.0, 200.0, 400.0]
    vals = [1e6, 1.5e6, 1.7e6, 2.5e6]
    for interp in ("linear", "pchip"):
        b = Bearing(0.0, kyy=vals, kzz=1e6, speeds=grid, interpolation=interp)
        rs = assemble_rotor(_rotor(bearings=[b, Bearing(1.2, kyy=1e6, kzz=1e6)]))
        K = rs.stiffness(150.0)
        i = rs.dof(0.0, "v")
        k_shaft = assemble_rotor(_rotor(bearings=[Bearing(0.0, kzz=1e6, cyy=1.0), Bearing(1.2, kyy=1e6, kzz=1e6)])).K0[i, i]
        got = K[i, i] - k_shaft
        if interp == "linear":
            assert got == pytest.approx(1.6e6, rel=1e-12)
        else:
            assert 1.5e6 < got < 1.7e6
        assert rs.stiffness(200.0)[i, i] - k_shaft == pytest.approx(1.7e6, rel=1e-12)   # table values exact


def test_disc_outside_shaft_and_off_node():
    with pytest.raises(ModelError, match="position on the shaft"):
        _rotor(discs=[Disc(1.5, 10.0)])
    with pytest.raises(ModelError, match="node position"):
        _rotor(discs=[Disc(0.55, 10.0)])
    with pytest.raises(ModelError, match="some inertia"):
        _rotor(discs=[Disc(0.6, 0.0)])
    with pytest.raises(ModelError, match="position on the shaft"):
        _rotor(bearings=[Bearing(-0.1, kyy=1e6, kzz=1e6)])


@pytest.mark.parametrize("seg, key", [
    (dict(length=0.0), "length"), (dict(elements=0), "elements"), (dict(d=-0.05), "d"),
    (dict(di=0.06), "di"), (dict(shear_coefficient=3.0), "shear_coefficient"),
])
def test_bad_segments(seg, key):
    base = dict(length=1.2, elements=6, d=0.05, material=STEEL)
    base.update(seg)
    with pytest.raises(ModelError) as err:
        _rotor(segments=[ShaftSegment(**base)])
    assert err.value.key == key


def test_pedestal_and_coupling_checks():
    with pytest.raises(ModelError, match="pedestal"):
        _rotor(bearings=[Bearing(0.0, kyy=1e6, kzz=1e6, pedestal="nope"), Bearing(1.2, kyy=1e6, kzz=1e6)])
    with pytest.raises(ModelError, match="some bearing uses"):
        _rotor(pedestals=[Pedestal("p", 10.0, 1e7, 1e7)])
    with pytest.raises(ModelError, match="junction"):
        _rotor(couplings=[Coupling(0.6, 1e6, 1e3)])
    with pytest.raises(ModelError, match="dofs"):
        _rotor(dofs="3d")


def test_speeds_must_be_positive_where_required():
    r = _rotor()
    with pytest.raises(ModelError, match="speed > 0"):
        stability_threshold(r, 0.0)
    with pytest.raises(ModelError, match="speeds > 0"):
        unbalance_response(r, [Unbalance(0.6, 1e-4)], [0.0, 10.0, 20.0])
    with pytest.raises(ModelError, match="speed >= 0"):
        rotor_modes(r, -5.0)
    with pytest.raises(ModelError, match="increasing"):
        campbell(r, [10.0, 5.0], 2)
    with pytest.raises(ModelError, match="magnitude"):
        unbalance_response(r, [Unbalance(0.6, -1e-4)], [10.0, 20.0])
    with pytest.raises(ModelError, match="direction"):
        unbalance_response(r, [Unbalance(0.6, 1e-4)], [10.0, 20.0], probes=[Probe(0.6, "x")])


def test_free_free_rotor_reports_rigid_modes():
    """No support at all: rigid-body modes with omega = 0 and the elastic ones, no crash; statics refuses."""
    r = _rotor(bearings=[])
    for speed in (0.0, 300.0):
        m = rotor_modes(r, speed, 8)
        assert m.rigid.sum() >= 3 and np.all(m.omega_damped_rad_s[m.rigid] == 0)
        assert np.all(m.residuals < 1e-6)
        assert any("rigid-body" in w for w in m.warnings)
    flexible = rotor_modes(r, 0.0, 8).omega_damped_rad_s[4:]
    assert flexible[0] > 100 and flexible[0] == pytest.approx(flexible[1], rel=1e-9)
    with pytest.raises(ModelError, match="hold the rotor"):
        static_deflection(r)


def test_couplings_and_pedestals_assemble():
    segs = [ShaftSegment(0.6, 3, 0.05, STEEL), ShaftSegment(0.6, 3, 0.04, STEEL, d_end=0.03, di=0.01)]
    r = Rotor(segs, discs=[Disc(0.4, 5.0, 0.02, 0.04)],
              bearings=[Bearing(0.0, kyy=1e6, kzz=1e6, pedestal="p"), Bearing(1.2, kyy=1e6, kzz=1e6)],
              pedestals=[Pedestal("p", 20.0, 5e6, 5e6, 100.0, 100.0)], couplings=[Coupling(0.6, 2e6, 5e3, mass=1.0)])
    rs = assemble_rotor(r)
    assert rs.node_x.size == 8 and np.count_nonzero(rs.node_x == 0.6) == 2
    assert sp.csr_matrix(rs.K0).nnz and "pedestal_v" in set(rs.dof_field)
    m = rotor_modes(rs, 200.0, 6)
    assert np.all(m.residuals < 1e-8) and np.all(m.omega_damped_rad_s > 0)
