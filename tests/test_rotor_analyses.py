"""Rotor analyses against second methods: the quadratic eigensolver vs dense QZ, Campbell tracking
through a crossing, critical speeds by two methods, the unbalance response vs a sparse solve,
statics vs beam formulas, JSON and figures."""
import json
import math

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from discrete.linalg.banded import BandedLU
from discrete.linear.complex_modal import complex_modal_analysis
from discrete.linear_system import LinearSystem
from fem.rotor import (Bearing, Disc, Probe, Rotor, ShaftSegment, Support, Unbalance, assemble_rotor, campbell,
                       critical_speed_map, rotor_modes, rpm, stability_threshold, static_deflection,
                       unbalance_response, undamped_critical_speeds)
from fem.rotor.response import unbalance_load
from fem.sections import Material

STEEL = Material(E=211e9, G=81.2e9, rho=7810.0)


def friswell(elements=6, dofs="lateral", **kw):
    b = {"kyy": 1e6, "kzz": 1e6, **kw}
    return Rotor([ShaftSegment(1.5, elements, 0.05, STEEL)],
                 discs=[Disc.from_geometry(0.5, 0.07, 0.28, 0.05, 7810.0), Disc.from_geometry(1.0, 0.07, 0.35, 0.05, 7810.0)],
                 bearings=[Bearing(0.0, **b), Bearing(1.5, **b)], dofs=dofs)


def _dense_eigs(sys_, speed):
    f = sys_.free
    M, K = sys_.M[f][:, f].toarray(), sys_.K[f][:, f].toarray()
    D = (sys_.C + speed * sys_.G)[f][:, f].toarray()
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -D]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    lam = sla.eig(A, B, right=False)
    lam = lam[np.isfinite(lam) & (lam.imag > 1e-9)]
    return lam[np.argsort(np.abs(lam))]


def test_arnoldi_matches_dense_qz_with_damping_and_cross_coupling():
    rs = assemble_rotor(friswell(18, kzz=0.8e6, cyy=400.0, czz=300.0, kyz=2e5, cyz=50.0))
    speed = 350.0
    sys_ = rs.system_at(speed)
    res = complex_modal_analysis(sys_, 8, speed=speed)
    assert "Arnoldi" in res.method
    ref = _dense_eigs(sys_, speed)[:8]
    # the dense QZ of the unscaled linearisation is itself accurate only to ~1e-8 here (backward
    # error eps ||A|| with ||A|| ~ the largest K_ii / M_ii); the Arnoldi residuals are ~1e-13
    np.testing.assert_allclose(res.eigenvalues, ref, rtol=2e-8)
    assert np.all(res.residuals < 1e-11) and res.reliable.all()
    assert json.dumps(res.to_dict())


def test_generic_linear_system_two_dof():
    """A 2-DOF lumped system with damping and a gyroscopic coupling: eigenvalues from the characteristic polynomial."""
    m, k, c, g, W = 2.0, 800.0, 3.0, 1.5, 40.0
    sys_ = LinearSystem(M=sp.eye(2) * m, K=sp.eye(2) * k, C=sp.eye(2) * c,
                        G=sp.csr_matrix(np.array([[0.0, g], [-g, 0.0]])), dof_field=["x", "y"])
    res = complex_modal_analysis(sys_, 2, speed=W)
    # (m s^2 + c s + k)^2 + (g W s)^2 = 0  ->  m s^2 + c s + k = +- i g W s
    roots = np.concatenate([np.roots([m, c - 1j * g * W, k]), np.roots([m, c + 1j * g * W, k])])
    roots = np.sort_complex(roots[roots.imag > 0])
    np.testing.assert_allclose(np.sort_complex(res.eigenvalues), roots, rtol=1e-12)


def test_banded_lu_stacked_solves():
    rs = assemble_rotor(friswell(30))
    P = rs.pattern
    lay = BandedLU(P)
    rng = np.random.default_rng(0)
    data = rng.standard_normal((3, P.nnz)) + 1j * rng.standard_normal((3, P.nnz))
    data[:, np.flatnonzero(np.repeat(np.arange(P.shape[0]), np.diff(P.indptr)) == P.indices)] += 50.0
    b = rng.standard_normal((3, P.shape[0])) + 0j
    x = lay.factor_many(data).solve(b)
    for r in range(3):
        A = sp.csr_matrix((data[r], P.indices, P.indptr), shape=P.shape)
        np.testing.assert_allclose(A @ x[r], b[r], atol=1e-10 * np.abs(b[r]).max())


def test_campbell_tracks_through_a_crossing():
    """The backward 3rd lateral mode falls through the speed-independent torsional mode (650.4 rad/s):
    tracking by MAC keeps the torsion column constant, sorting would swap columns."""
    camp = campbell(friswell(6, "full"), np.linspace(0.0, rpm(6000), 25), 9, critical=False)
    col = camp.kind.index("torsion")
    w = camp.omega_damped_rad_s[:, col]
    assert np.ptp(w) < 1e-8 * w.mean()
    lateral = [j for j, k in enumerate(camp.kind) if k == "lateral"]
    crossing = [j for j in lateral if np.any(camp.omega_damped_rad_s[:, j] > w[0]) and
                np.any(camp.omega_damped_rad_s[:, j] < w[0])]
    assert crossing, "no lateral mode crosses the torsional one in this range"
    assert camp.mac_min.min() > 0.9 and not camp.warnings
    assert json.dumps(camp.to_dict())


def test_critical_speeds_roots_equal_linear_eigenproblem():
    rs = assemble_rotor(friswell(6, kzz=0.7e6))
    camp = campbell(rs, np.linspace(0.0, 400.0, 11), 6, orders=(1.0, 0.5))
    for k in (1.0, 0.5):
        roots = np.sort([c.speed_rad_s for c in camp.crossings if c.order == k])
        lin = undamped_critical_speeds(rs, 8, order=k).speeds_rad_s
        lin = lin[lin <= 400.0]
        assert roots.size == lin.size > 0
        np.testing.assert_allclose(roots, lin, rtol=1e-8)


def test_overdamped_modes_have_no_critical_speed_at_rest():
    """Heavily damped bearings: four bearing modes are real (overdamped) at rest; their omega_d = 0
    meets omega = Omega at the origin, which is no critical speed.  The crossings of the modes that
    oscillate are unchanged (roots of omega_d(Omega) = Omega, checked against the diagram)."""
    camp = campbell(friswell(6, cyy=2e5, czz=2e5), np.linspace(0.0, 600.0, 13), 8)
    assert np.sum(camp.omega_damped_rad_s[0] == 0.0) == 4            # non-oscillating at rest
    assert all(c.speed_rad_s > 0 and np.isfinite(c.log_decrement) for c in camp.crossings)
    assert len(camp.crossings) == 4                                   # forward and backward crossings
    assert len(camp.critical_speeds) == 2 and {c.whirl for c in camp.critical_speeds} == {"forward"}
    for c in camp.crossings:
        assert c.frequency_rad_s == pytest.approx(c.speed_rad_s, rel=1e-9)
        w = np.interp(c.speed_rad_s, camp.speeds_rad_s, camp.omega_damped_rad_s[:, c.mode])
        assert w == pytest.approx(c.speed_rad_s, rel=0.02)                # the grid's linear interpolation


def test_critical_speed_map_limits():
    """Soft bearings: the rotor moves rigidly, the first critical near sqrt(2 k / m_total) (the
    discs are not symmetric, so translation and tilt couple slightly: measured 0.3 % lower);
    stiff bearings: the pinned-pinned shaft's first critical; the map rises with stiffness."""
    r = friswell(12)
    rs = assemble_rotor(r)
    cmap = critical_speed_map(r, [1e3, 1e6, 1e10], n=2)
    assert cmap.speeds_rad_s[0, 0] == pytest.approx(math.sqrt(2e3 / rs.total_mass()), rel=1e-2)
    assert np.all(np.diff(cmap.speeds_rad_s[:, 0]) > 0)
    pinned = Rotor(r.segments, discs=r.discs, supports=[Support(0.0), Support(1.5)])
    assert cmap.speeds_rad_s[2, 0] == pytest.approx(undamped_critical_speeds(pinned, 1).speeds_rad_s[0], rel=1e-3)
    assert json.dumps(cmap.to_dict())


def test_unbalance_response_matches_sparse_solve_and_whirls_forward():
    rs = assemble_rotor(friswell(12, cyy=200.0, czz=200.0))
    U = [Unbalance(1.0, 1e-4, 0.4)]
    speeds = np.array([60.0, 90.0, 300.0])
    res = unbalance_response(rs, U, speeds, probes=[Probe(0.5, "major"), Probe(0.5, "v")], find_peaks=False)
    F = unbalance_load(rs, U)
    for j, W in enumerate(speeds):
        Z = sp.csc_matrix(rs.K0 - W**2 * rs.M + 1j * W * (rs.C0 + W * rs.G))
        q = spla.spsolve(Z, W**2 * F)
        np.testing.assert_allclose(res.response[j], q, atol=1e-9 * np.abs(q).max())
    o = res.orbits()
    assert np.all(o.forward >= o.backward)              # isotropic rotor: synchronous forward circles
    np.testing.assert_allclose(o.minor, o.major, rtol=1e-9)
    assert json.dumps(res.to_dict())


def test_static_deflection_simply_supported_shaft():
    """Uniform shaft on rigid short supports under its weight: mid-span sag 5 w L^4/(384 EI) + w L^2/(8 kGA)."""
    L, d = 1.5, 0.05
    r = Rotor([ShaftSegment(L, 10, d, STEEL)], supports=[Support(0.0), Support(L)])
    st = static_deflection(r, gravity=(0.0, 0.0, -9.81))
    A, I = math.pi * d * d / 4, math.pi * d**4 / 64
    nu = STEEL.E / (2 * STEEL.G) - 1
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    w = STEEL.rho * A * 9.81
    sag = 5 * w * L**4 / (384 * STEEL.E * I) + w * L**2 / (8 * kappa * STEEL.G * A)
    assert -st.w[np.argmin(np.abs(st.node_x - L / 2))] == pytest.approx(sag, rel=1e-10)
    assert st.equilibrium_error < 1e-10 and np.allclose(st.v, 0.0)


def test_static_bearing_loads_balance_weight():
    r = friswell(12)
    st = static_deflection(r)
    total = assemble_rotor(r).total_mass() * 9.81
    assert st.bearing_force[:, 1].sum() == pytest.approx(-total, rel=1e-10)
    assert st.equilibrium_error < 1e-10


def test_stability_threshold_and_whirl():
    """A seal with cross-coupling beta Omega destabilises the forward mode; without it the rotor stays stable."""
    top = 3000.0
    seal = Bearing(0.75, cyy=100.0, czz=100.0, kyz=[0.0, 30.0 * top], kzy=[0.0, -30.0 * top], speeds=[0.0, top])
    r = friswell(6, cyy=100.0, czz=100.0)
    unstable = Rotor(r.segments, discs=r.discs, bearings=r.bearings + [seal])
    s = stability_threshold(unstable, top, 2, n_grid=13)
    assert s.threshold_rad_s is not None and not s.unstable_from_start and s.whirl == "forward"
    m = rotor_modes(unstable, s.threshold_rad_s, 2)
    assert np.min(np.abs(m.damping_ratio)) < 1e-8
    assert stability_threshold(r, top, 2, n_grid=7).threshold_rad_s is None


def _figure_inputs():
    rs = assemble_rotor(friswell(6, cyy=300.0, czz=300.0))
    camp = campbell(rs, np.linspace(0.0, 400.0, 9), 4)
    resp = unbalance_response(rs, [Unbalance(1.0, 1e-4)], np.linspace(20.0, 400.0, 60), operating_range=(250.0, 300.0))
    return rs, camp, resp


def test_figures(tmp_path):
    from fem.rotor import plots

    rs, camp, resp = _figure_inputs()
    path = plots.plot_campbell(camp, tmp_path / "c.png")
    assert path.exists() and path.stat().st_size > 5000


@pytest.mark.slow
def test_more_figures(tmp_path):
    from fem.rotor import plots

    rs, camp, resp = _figure_inputs()
    m = rotor_modes(rs, 300.0, 4)
    paths = [plots.plot_bode(resp, tmp_path / "b.png"), plots.plot_polar(resp, tmp_path / "p.png"), plots.plot_mode_orbits(m, 1, tmp_path / "o.png"),
             plots.plot_orbits(resp.response[10, resp.v_index], resp.response[10, resp.w_index], resp.node_x,
                               tmp_path / "r.png"),
             plots.plot_critical_speed_map(critical_speed_map(rs.rotor, np.logspace(5, 8, 4), 2), tmp_path / "u.png"),
             plots.plot_static(static_deflection(rs), tmp_path / "s.png")]
    assert all(p.exists() and p.stat().st_size > 5000 for p in paths)


@pytest.mark.slow
def test_whirl_render(tmp_path):
    from fem.render import available
    from fem.rotor import render

    ok, why = available()
    if not ok:
        pytest.skip(why)
    rs = assemble_rotor(friswell(12))
    m = rotor_modes(rs, rpm(4000), 4)
    png = render.render_whirl(rs, m, 1, tmp_path / "w.png")
    gif = render.render_whirl_gif(rs, m, 1, tmp_path / "w.gif", frames=4)
    assert png.stat().st_size > 10000 and gif.stat().st_size > 10000


def test_solver_leaves_the_callers_matrices_alone():
    """An undamped rotor at rest stores positions that are zero in M, K, C and G alike; building the
    quadratic solver drops them from its own pattern without compacting the caller's M in place
    (it used to: M's structure was corrupted and the solve failed with a shape error at 198
    elements).  The eigenvalues at rest are +-i omega of (K, M): the reference is scipy's
    shift-invert Lanczos on that symmetric pencil."""
    rs = assemble_rotor(friswell(198, "full"))
    sys_ = rs.system_at(0.0)
    before = {n: getattr(sys_, n).copy() for n in "MKCG"}
    res = complex_modal_analysis(sys_, 6, speed=0.0)
    for n, A in before.items():
        B = getattr(sys_, n)
        assert np.array_equal(B.indptr, A.indptr) and np.array_equal(B.indices, A.indices)
        assert np.array_equal(B.data, A.data)
    f = sys_.free                   # axial and torsional motion are free: two rigid-body modes first
    lam = np.sort(spla.eigsh(sys_.K[f][:, f].tocsc(), k=6, M=sys_.M[f][:, f].tocsc(), sigma=-1.0,
                             return_eigenvectors=False))
    omega = np.sort(np.abs(res.eigenvalues.imag))
    assert np.all(omega[:2] == 0.0) and np.all(np.abs(lam[:2]) < 1e-3)
    assert np.allclose(omega[2:], np.sqrt(lam[2:]), rtol=1e-8)
