"""The Python-API examples (examples/api_*.py) run and reproduce their numbers against independent
references: the stepped shaft against the exact transfer-matrix frequency equation, the drill string
built in Python against the model file's run and seed 000's period, the dry-friction AFC against Den
Hartog's closed form.  Each example runs once (module fixtures) in an empty directory, which must hold
only the JSON file asked for afterwards."""
import importlib.util
import json
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from fem.study import Study
from validation.analytic import seed000
from validation.analytic.steady_refs import den_hartog_amplitude

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


def load_example(name: str):
    """Import examples/<name>.py as a module (registered, so its dataclasses resolve)."""
    spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def run_in_empty_dir(tmp_path_factory, name: str):
    """(module, result of main(out), out, files in the working directory afterwards)."""
    mod = load_example(name)
    work = tmp_path_factory.mktemp(name)
    out = work / f"{name}.json"
    cwd = os.getcwd()
    os.chdir(work)
    try:
        result = mod.main(out)
    finally:
        os.chdir(cwd)
    return mod, result, out, sorted(p.name for p in work.iterdir())


# ------------------------------------------------------------------ (a) stepped shaft, transfer matrices
def euler_bernoulli_field(beta: float, length: float, EI: float) -> np.ndarray:
    """Exact transfer matrix of a uniform Euler-Bernoulli segment in free vibration (w'''' = beta^4 w)
    for the state (w, w', EI w'', EI w'''), from the Krylov functions S, T, U, V of beta x."""
    x = beta * length
    S, T = (math.cosh(x) + math.cos(x)) / 2, (math.sinh(x) + math.sin(x)) / 2
    U, V = (math.cosh(x) - math.cos(x)) / 2, (math.sinh(x) - math.sin(x)) / 2
    b = beta
    K = np.array([[S, T / b, U / b**2, V / b**3],
                  [b * V, S, T / b, U / b**2],
                  [b**2 * U, b * V, S, T / b],
                  [b**3 * T, b**2 * U, b * V, S]])
    D = np.diag([1.0, 1.0, EI, EI])
    return D @ K @ np.linalg.inv(D)


def point_matrix(omega: float, mass=0.0, inertia=0.0, k=0.0) -> np.ndarray:
    """Jumps at a point with mass, rotary inertia and a spring to ground:
    [EI w''']+- = (m omega^2 - k) w, [EI w'']+- = -J omega^2 w' (from the weak form)."""
    P = np.eye(4)
    P[3, 0] = mass * omega**2 - k
    P[2, 1] = -inertia * omega**2
    return P


def clamped_free_determinant(omega: float, shaft) -> float:
    """Frequency determinant of a shaft clamped at x = 0 and free at its end, with springs and point
    attachments at segment ends: (w, w') = 0 at the clamp leaves (EI w'', EI w''') unknown; the free end
    needs EI w'' = EI w''' = 0."""
    assert [s.type for s in shaft.supports if s.x == 0.0] == ["clamped"]
    points = {round(p.x, 12): p for p in shaft.points}
    springs = {round(s.x, 12): s for s in shaft.supports if s.type == "spring"}
    assert len(points) + len(springs) + 1 == len(shaft.supports) + len(shaft.points)
    G, x = np.eye(4), 0.0
    for seg in shaft.segments:
        EI, rho_A = seg.material.E * seg.section.I, seg.material.rho * seg.section.A
        G = euler_bernoulli_field((omega**2 * rho_A / EI) ** 0.25, seg.length, EI) @ G
        x = round(x + seg.length, 12)
        p, s = points.pop(x, None), springs.pop(x, None)
        G = point_matrix(omega, p.mass if p else 0.0, p.inertia if p else 0.0, s.k if s else 0.0) @ G
    assert not points and not springs, "attachments inside a segment: split the segment there"
    return float(np.linalg.det(G[2:, 2:]))


def transfer_matrix_roots(shaft, omega_max: float, points: int = 4000) -> np.ndarray:
    """All roots of the frequency determinant below omega_max (sign changes on a grid, then brentq)."""
    w = np.linspace(omega_max / points, omega_max, points)
    d = np.array([clamped_free_determinant(v, shaft) for v in w])
    idx = np.flatnonzero(np.sign(d[:-1]) != np.sign(d[1:]))
    return np.array([brentq(clamped_free_determinant, w[i], w[i + 1], args=(shaft,), xtol=1e-13, rtol=1e-15)
                     for i in idx])


def test_transfer_matrix_reference_reproduces_the_uniform_cantilever():
    """The reference itself: a uniform clamped-free beam gives sigma L = 1.875104, 4.694091 (4.72)."""
    from fem import Material, Section, Segment, ShaftModel, Support

    sec, mat = Section.circle(0.05), Material(E=2.1e11, G=8.1e10, rho=7850.0)
    beam = ShaftModel("bending", [Segment(1.5, 1, sec, mat)], supports=[Support(0.0, "clamped")])
    scale = math.sqrt(mat.E * sec.I / (mat.rho * sec.A)) / 1.5**2
    exact = np.array([1.8751040687119611, 4.6940911329741746]) ** 2 * scale
    np.testing.assert_allclose(transfer_matrix_roots(beam, 1.1 * exact[1]), exact, rtol=1e-11)


@pytest.fixture(scope="module")
def stepped(tmp_path_factory):
    return run_in_empty_dir(tmp_path_factory, "api_stepped_shaft")


def test_stepped_shaft_frequencies_match_the_transfer_matrix(stepped):
    """FE (Hermite, h = 5 cm) against the exact roots: tolerance twice the Hermite error constant
    (beta h)^4/1440 of the most demanding segment at each root, plus rounding; measured 1.3e-8 ..
    2.8e-6 (the leading term of the error, halving h divides it by 16)."""
    mod, res, out, files = stepped
    shaft = mod.stepped_shaft()
    assert res.omega_rad_s.size == mod.N_MODES and res.reliable.all()
    roots = transfer_matrix_roots(shaft, 1.05 * res.omega_rad_s[-1])
    assert roots.size == mod.N_MODES, f"transfer-matrix roots {roots} vs FE {res.omega_rad_s}"
    for w_ref, w_fe in zip(roots, res.omega_rad_s):
        beta_h = max((w_ref**2 * s.material.rho * s.section.A / (s.material.E * s.section.I)) ** 0.25
                     * s.length / s.elements for s in shaft.segments)
        assert abs(w_fe / w_ref - 1) <= 2 * beta_h**4 / 1440 + 1e-9


def test_stepped_shaft_writes_only_what_is_asked(stepped, tmp_path):
    mod, res, out, files = stepped
    assert files == [out.name]
    data = json.loads(out.read_text())
    assert data["omega_rad_s"] == pytest.approx(res.omega_rad_s.tolist(), rel=1e-15)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        again = mod.main()
    finally:
        os.chdir(cwd)
    assert list(tmp_path.iterdir()) == [] and np.array_equal(again.omega_rad_s, res.omega_rad_s)


# ------------------------------------------------------------------ (b) hybrid drill string
@pytest.fixture(scope="module")
def drill(tmp_path_factory):
    return run_in_empty_dir(tmp_path_factory, "api_hybrid_drill_string")


def test_drill_string_built_in_python_is_the_model_files_run(drill):
    """The same model through HybridModel + run and through examples/hybrid_drill_string.toml: the same
    events at the same times and the same field history (to round-off; observed identical)."""
    mod, cycle, out, files = drill
    ours = cycle.result
    theirs = Study.load(EXAMPLES / "hybrid_drill_string.toml").simulate()
    assert [(e.kind, e.element) for e in ours.events] == [(e.kind, e.element) for e in theirs.events]
    np.testing.assert_allclose([e.t for e in ours.events], [e.t for e in theirs.events], rtol=1e-12, atol=0)
    assert ours.field_history.shape == theirs.field_history.shape
    assert np.max(np.abs(ours.field_history - theirs.field_history)) <= 1e-12 * np.max(np.abs(theirs.field_history))
    assert ours.t_end == theirs.t_end == mod.T_END


def test_drill_string_period_against_seed000(drill):
    """Stick-slip period against seed 000's one-mass period (20) (eps = M1/M0 = 6, Omega =
    omega sqrt(c I)/M0 = 1.5: 3.0092 s, k* = 2 reversals per cycle) with the string's inertia share
    mu = rho Ip L / I = 0.01: within 0.3 mu of (20) and 0.15 mu of the one-mass model with the Rayleigh
    inertia I (1 + mu/3) -- the tolerances of validation case hybrid_drill_string, where the string's
    undamped modes make the cycle wander by 0.13..0.17 mu (measured here: 0.15 mu and 0.02 mu)."""
    mod, cycle, out, files = drill
    c = mod.GJ / mod.L
    mu = mod.RHO_IP * mod.L / mod.I_BIT

    def one_mass(I):
        return seed000.dimensional(mod.M1 / mod.M0, mod.OMEGA * math.sqrt(c * I) / mod.M0, I, c, mod.M0)["period"]

    assert cycle.period == pytest.approx(one_mass(mod.I_BIT), rel=0.3 * mu)
    assert cycle.period == pytest.approx(one_mass(mod.I_BIT * (1 + mu / 3)), rel=0.15 * mu)
    assert cycle.reversals_per_cycle == seed000.k_star(mod.M1 / mod.M0) == 2
    assert cycle.result.energy_error < 1e-6


def test_drill_string_writes_only_what_is_asked(drill):
    mod, cycle, out, files = drill
    assert files == [out.name]
    data = json.loads(out.read_text())
    assert data["period_s"] == cycle.period and data["run"]["t_end"] == mod.T_END
    assert len(data["run"]["events"]) == len(cycle.result.events)


# ------------------------------------------------------------------ (c) dry-friction AFC
@pytest.fixture(scope="module")
def coulomb(tmp_path_factory):
    return run_in_empty_dir(tmp_path_factory, "api_afc_coulomb")


def test_coulomb_afc_against_den_hartog(coulomb):
    """Shooting with the exact event-driven integrator against Den Hartog's exact closed form: both
    exact, so 1e-9 (continuation Newton tolerance 1e-8 on the scaled update, events to round-off;
    observed 3e-13), at every point from 1.2 to exactly 2.0; every orbit stable (Floquet), the
    amplitude falls with omega and stays below the frictionless F/|k - m omega^2|."""
    mod, curve, out, files = coulomb
    assert curve.completed and curve.omega[0] == mod.OMEGA_RANGE[0] and curve.omega[-1] == mod.OMEGA_RANGE[1]
    assert curve.omega.size >= 10
    ref = np.array([den_hartog_amplitude(mod.MASS, mod.STIFFNESS, mod.FRICTION, mod.FORCE, w) for w in curve.omega])
    np.testing.assert_allclose(curve.response, ref, rtol=1e-9)
    assert curve.stable.all() and np.all(np.diff(curve.response) < 0)
    assert np.all(curve.response < mod.FORCE / np.abs(mod.STIFFNESS - mod.MASS * curve.omega**2))


def test_coulomb_afc_writes_only_what_is_asked(coulomb):
    mod, curve, out, files = coulomb
    assert files == [out.name]
    data = json.loads(out.read_text())
    assert data["omega_rad_s"] == pytest.approx(curve.omega.tolist(), rel=1e-15) and data["completed"] is True
