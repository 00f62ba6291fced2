"""The two-field pseudo-medium (fem.drives.continuum), the closed forms of §10.5 and the
spectrum-vs-n sweep with its plot."""
import numpy as np
import pytest

from discrete.transfer import RegularDrive
from discrete.transfer.continuum import pseudo_medium_forced, pseudo_medium_frequencies
from fem.drives import DistributedShaft, DriveModel, LumpedShaft, Mechanism, forced, modal
from fem.drives.analysis import spectrum_sweep
from fem.drives.continuum import build_continuum


def set_c(n=12, **kw):
    m = 10.0 / n
    return DriveModel(n=n, shaft=DistributedShaft(length=2.0, GI=2e4, rho=0.01),
                      mechanism=Mechanism(m=m, c=m * 9e4, ratio=0.05), **kw)


def test_closed_form_roots_satisfy_the_frequency_equation():
    lo, hi = pseudo_medium_frequencies(2e4, 0.01, 5.0, 300.0, 0.05, 2.0, "clamped-free", 4)
    for p in np.r_[lo, hi]:
        rho_p = 0.01 + 5.0 * 0.05**2 / (1 - p**2 / 300.0**2)
        assert np.cos(p * np.sqrt(rho_p / 2e4) * 2.0) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("boundary", ["clamped-free", "clamped-clamped", "free-clamped"])
def test_continuum_fe_matches_closed_form(boundary):
    m = set_c(boundary=boundary, continuum_elements=32)
    res = modal(m, 3, "continuum")
    assert np.allclose(res.omega_rad_s, res.reference_omega, rtol=1e-7)      # P2 x 32: O(h^4) ~ 1e-8


def test_continuum_forced_both_zones_and_clamp():
    m = set_c(representation="continuum", force=10.0 / 12, continuum_elements=72)   # stations on nodes
    ws = np.array([150.0, 380.0, 900.0])          # trig, hyperbolic (rho < 0), trig
    r = forced(m, ws)
    assert np.max(np.abs(r.theta.real - r.reference_theta) / np.abs(r.reference_theta).max(axis=1, keepdims=True)) < 1e-8
    cd = build_continuum(m)
    assert pseudo_medium_forced(np.array([0.0]), 380.0, 2e4, 0.01, 5.0, 300.0, 0.05, 2.0, 5.0)[0] == 0.0
    assert cd.system.constrained.size == 1       # theta(0) only; y free


def test_grounded_outputs_three_ways():
    m = DriveModel(n=6, shaft=LumpedShaft(c0=6e4, J0=0.02 / 6), mechanism=Mechanism(m=10 / 6, c=1.5e5, ratio=0.05,
                                                                                      output="grounded"))
    ref = RegularDrive(n=6, c0=6e4, J0=0.02 / 6, m=10 / 6, c=1.5e5, ratio=0.05, output="grounded").natural_frequencies()
    for rep in ("discrete", "transfer-matrix"):
        assert np.allclose(modal(m, 6, rep).omega_rad_s, ref, rtol=1e-11)
    # continuum: elastic foundation c_bar Pi'^2 -> p^2 = (GI s^2 + c_bar Pi'^2)/rho
    w = modal(m, 1, "continuum").omega_rad_s[0]
    s = m.smeared()
    exact = np.sqrt((s["GI"] * (np.pi / 2 / s["L"]) ** 2 + s["c_bar"] * 0.05**2) / s["rho"])
    assert w == pytest.approx(exact, rel=1e-7)


def test_spectrum_sweep_roots_in_pass_bands_and_plot(tmp_path):
    base = DriveModel(n=6, shaft=LumpedShaft(c0=6.0e4, J0=0.02 / 6), mechanism=Mechanism(m=10 / 6, c=1.5e5, ratio=0.05),
                      continuum_length=2.0 / 6)
    sw = spectrum_sweep(base, [1, 2, 5, 10, 20])
    for w, lo, hi in zip(sw.roots, sw.lower_band, sw.upper_band):
        inside = ((w >= lo[0]) & (w <= lo[1] * (1 + 1e-12))) | ((w >= hi[0] * (1 - 1e-12)) & (w <= hi[1] * (1 + 1e-12)))
        assert inside.all()
    assert np.all(np.diff(sw.upper_band[:, 1]) > 0)       # the band top grows with n (p0 ~ n at fixed totals)
    from fem.output.figures import plot_spectrum_vs_n

    out = plot_spectrum_vs_n(sw, tmp_path / "s.png")
    assert out.exists() and out.stat().st_size > 10_000
    with pytest.raises(Exception, match="lumped"):
        spectrum_sweep(set_c(), [2, 4])
