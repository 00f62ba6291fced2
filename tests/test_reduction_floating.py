"""Reduction of floating structures (rigid-body modes, K_ff singular): inertia relief in
:func:`discrete.linear.reduction.reduce`.

References (unit stiffness and inertia per length, L = 1):

* elastic flexibility with inertia relief at the end of a free-free bar, L/(3 EA); of a free-free
  Euler-Bernoulli beam, L^3/(105 EI): the static response to a unit end force balanced by the
  rigid-body inertia forces (bar: uniform load -1/L; beam: linear load (2 - 6x/L)/L), measured from
  the mean axes (int w = int x w = 0);
* the share of one elastic mode is its term phi_r(L)^2 / lambda_r of the modal expansion of that
  flexibility: bar 6/(pi r)^2 (phi_r(L)^2 = 2/m, lambda_r = (r pi)^2 EA/(m L^2)); beam 420/(beta_r L)^4
  (end value of a free-free mode normalised to int phi^2 = L is 2);
* Craig-Bampton with the coupling DOF at the bar's end: the rigid translation is the constraint mode,
  and the inertia-relief load is a uniform load on the interior held at the coupling end, carried by the
  fixed-interface modes cos((2k-1) pi x/(2L)) with shares 96/(pi^4 (2k-1)^4).
"""
import numpy as np
import pytest

from discrete.errors import ModelError, SolverError
from discrete.linear_system import LinearSystem
from fem import assemble, modal_analysis
from discrete.linear.reduction import elastic_flexibility, reduce
from validation.analytic.bending import euler_bernoulli_roots
from validation.builders import uniform, unit_section

N_BAR, N_BEAM = 400, 40


def bar():
    """Free-free rod, lumped P1: nodal mode shapes exact, eigenvalue error (k h)^2/12."""
    mat, sec = unit_section()
    return assemble(uniform("axial", 1.0, N_BAR, order=1, mass="lumped", material=mat, section=sec)).system


def beam(supports=()):
    mat, sec = unit_section()
    return assemble(uniform("bending", 1.0, N_BEAM, material=mat, section=sec, supports=supports)).system


def end(s):
    """The end DOF u(L) of the bar, w(L) of the beam."""
    return s.dof_index(field="u" if "u" in s.fields() else "w", x=1.0)


def bar_tol(n):
    """Twice the lumped-P1 eigenvalue error (k_n h)^2/12 of the highest retained mode (the elastic
    flexibility's own O(h^2) error is smaller)."""
    return 2 * (np.pi * n / N_BAR) ** 2 / 12


def beam_tol(n):
    """An order above the Hermite element's leading eigenvalue error (beta_n h)^4/720."""
    return (euler_bernoulli_roots("free-free", n)[-1] / N_BEAM) ** 4 / 100


def test_elastic_flexibility_closed_forms():
    """Tolerances: the O(h^2) (lumped P1) and O(h^4) (Hermite) errors of the inertia-relief load and the
    mean-axis integrals; nodal static values are otherwise exact for both elements."""
    s = bar()
    assert elastic_flexibility(s.K, s.M, s.rigid_modes, np.array([end(s)]))[0] == pytest.approx(1 / 3, rel=1 / N_BAR**2)
    b = beam()
    assert elastic_flexibility(b.K, b.M, b.rigid_modes, np.array([end(b)]))[0] == pytest.approx(1 / 105, rel=2 / N_BEAM**4)


@pytest.mark.parametrize("static_correction", [True, False])
@pytest.mark.parametrize("make, coupling", [
    (bar, lambda s: [end(s)]),
    (beam, lambda s: [end(s)]),                                  # Craig-Bampton: the interior floats (rotation)
    (beam, lambda s: [s.dof_index(field="w", x=0.0), end(s)]),   # the boundary holds both rigid modes
    (lambda: beam([(0.0, "pinned")]), lambda s: [end(s)])])      # a support, one rigid rotation left
def test_rigid_modes_are_in_the_basis(make, coupling, static_correction):
    """The rigid-body modes R lie in the basis: T R_r = R with the reduced system's rigid_modes R_r,
    which the reduced stiffness does not strain; modal analysis finds them at omega = 0."""
    s = make()
    red = reduce(s, coupling(s), 2, static_correction=static_correction)
    R, Rr = s.rigid_modes, red.system.rigid_modes
    assert Rr.shape == (red.system.n_dofs, R.shape[1]) and R.shape[1] >= 1
    assert np.linalg.norm(red.T @ Rr - R) <= 1e-9 * np.linalg.norm(R)
    Kr = red.system.K.toarray()
    assert np.linalg.norm(Kr @ Rr) <= 1e-9 * np.abs(Kr).max() * np.linalg.norm(Rr)
    assert modal_analysis(red.system, R.shape[1] + 1).rigid_body_modes == R.shape[1]
    assert red.retained_modes == red.system.n_dofs - red.system.constrained.size - red.coupling_reduced.size
    assert not red.warnings or all("restores only" in w for w in red.warnings)
    if s.constrained.size:   # the quasi-static shape of a held DOF of a floating structure is strain-free
        assert np.linalg.norm(s.K @ red.T[:, 0]) <= 1e-9 * abs(s.K).max() * np.linalg.norm(red.T[:, 0])


@pytest.mark.parametrize("n", [1, 2, 4])
def test_bar_restitution_closed_forms(n):
    """Free-interface: sum_{r<=n} 6/(pi r)^2; Craig-Bampton: 96/pi^4 sum_{k<=n} (2k-1)^-4 (module docstring);
    both in (0, 1], Craig-Bampton above free-interface."""
    s = bar()
    fi = reduce(s, [end(s)], n, static_correction=False)
    cb = reduce(s, [end(s)], n)
    r = np.arange(1, n + 1)
    assert fi.restitution[0] == pytest.approx(6 / np.pi**2 * np.sum(1.0 / r**2), rel=bar_tol(n))
    assert cb.restitution[0] == pytest.approx(96 / np.pi**4 * np.sum(1.0 / (2 * r - 1.0) ** 4), rel=bar_tol(n))
    assert 0 < fi.restitution[0] < cb.restitution[0] <= 1
    assert fi.retained_modes == n + 1 and cb.retained_modes == n     # the rigid translation: on top / constraint mode
    assert any("(elastic, inertia-relief) static flexibility" in w for w in fi.warnings)


@pytest.mark.parametrize("n", [1, 2, 4, 6])
def test_beam_free_interface_restitution(n):
    s = beam()
    red = reduce(s, [end(s)], n, static_correction=False)
    exact = 420 * np.sum(euler_bernoulli_roots("free-free", n) ** -4.0)
    assert red.restitution[0] == pytest.approx(exact, rel=beam_tol(n))
    assert (len(red.warnings) > 0) == (exact < red.threshold)


def test_craig_bampton_restitution_rises_to_one():
    """Ritz: the reduced flexibility is that of a Galerkin projection, so the share is in (0, 1] and
    grows with the basis (nested fixed-interface modes); the beam's interior floats (rotation about the
    coupling DOF), the bar's does not."""
    for s in (bar(), beam()):
        shares = [reduce(s, [end(s)], n).restitution[0] for n in (1, 2, 4, 8)]
        assert 0 < shares[0] and np.all(np.diff(shares) > 0) and shares[-1] <= 1 + 1e-12
        assert shares[-1] > 0.9999


@pytest.mark.parametrize("make", [bar, beam])
def test_lowest_elastic_frequencies_converge(make):
    """Craig-Bampton: Rayleigh-Ritz upper bounds of the full model's elastic frequencies, errors
    decreasing as modes are added (measured with 8 modes: omega_1 to 1.3e-4 for the bar, whose single
    end coupling DOF leaves slowly converging fixed-free interior modes); free-interface: the retained
    modes themselves (equal to rounding)."""
    s = make()
    nr = s.rigid_modes.shape[1]
    full = modal_analysis(s, nr + 3).omega_rad_s[nr:]
    errs = []
    for n in (3, 5, 8):
        red = reduce(s, [end(s)], n)
        w = modal_analysis(red.system, nr + 3).omega_rad_s[nr:]
        assert np.all(w >= full * (1 - 1e-10))
        errs.append(w / full - 1)
        fi = reduce(s, [end(s)], n, static_correction=False)
        assert modal_analysis(fi.system, nr + 3).omega_rad_s[nr:] == pytest.approx(full, rel=1e-9)
    assert np.all(np.diff(errs, axis=0) <= 0) and errs[-1][0] < 2e-4


def test_bad_input():
    s = beam()
    j = end(s)
    for modes in (0, True, 2.5):
        with pytest.raises(ModelError, match=r"modes = .* an integer >= 1"):
            reduce(s, [j], modes)
    with pytest.raises(ModelError, match=r"modes = 200 .*at most 79 .*minus the 2 rigid-body mode\(s\)"):
        reduce(s, [j], 200, static_correction=False)          # 82 free DOFs, minus one, minus 2 rigid modes
    with pytest.raises(ModelError, match=r"modes = 200 .*at most 79 .*1 coupling DOFs.*minus the 1 rigid-body"):
        reduce(s, [j], 200)                # 81 interior DOFs, minus one, minus the rotation about the coupling DOF
    with pytest.raises(ModelError, match=r"coupling DOF = 82 .*from 0 to 81"):
        reduce(s, [82], 2)
    held = beam([(0.0, "clamped")])
    with pytest.raises(ModelError, match=r"coupling DOF = 'w@x=0' .*held by a support"):
        reduce(held, [held.dof_index(field="w", x=0.0)], 2)
    for thr in (0.0, 1.5):
        with pytest.raises(ModelError, match=r"threshold = .*\(0, 1\]"):
            reduce(s, [j], 2, threshold=thr)
    unknown = LinearSystem(M=s.M, K=s.K, dof_field=s.dof_field, dof_x=s.dof_x)    # rigid_modes = None
    with pytest.raises(SolverError, match=r"K_ff is singular.*rigid_modes = None"):
        reduce(unknown, [j], 2)
