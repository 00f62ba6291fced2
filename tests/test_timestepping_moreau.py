"""Moreau-Jean time stepping: closed-form checks on lumped systems and bad input."""
import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.linear_system import LinearSystem
from discrete.nonsmooth import ExternalForce, Friction, Gap, Impact, MotionLaw
from discrete.timestepping import StepOptions, simulate_timestepping


def _sdof(k=1.0, m=1.0):
    return LinearSystem(M=np.array([[m]]), K=np.array([[k]]), dof_field=["x"])


def test_coulomb_decay_is_4F_over_k_per_period():
    """Free oscillator with Coulomb friction F: the amplitude falls by 4F/k per period (textbook 4.3);
    the midpoint Moreau-Jean scheme reproduces it to O(h^2)."""
    r = simulate_timestepping(_sdof(), [Friction("f", np.ones(1), kinetic=0.1)], x0=np.ones(1),
                              t_end=4 * np.pi, options=StepOptions(dt=1e-3))
    i = np.argmin(np.abs(r.t - 2 * np.pi))
    assert r.x[0, i] == pytest.approx(0.6, abs=1e-5)
    assert r.x[0, -1] == pytest.approx(0.2, abs=1e-5)
    assert r.energy_error < 1e-10


def test_stick_below_static_limit_and_breakaway_above():
    ls = LinearSystem(M=np.eye(1), K=np.zeros((1, 1)), dof_field=["x"])
    held = simulate_timestepping(ls, [Friction("f", np.ones(1), kinetic=1.0, static=2.0)],
                                 forces=[ExternalForce(np.ones(1), value=1.5)], t_end=1.0, options=StepOptions(dt=1e-2))
    assert np.max(np.abs(held.x)) < 1e-14
    moving = simulate_timestepping(ls, [Friction("f", np.ones(1), kinetic=1.0, static=2.0)],
                                   forces=[ExternalForce(np.ones(1), value=2.5)], t_end=1.0, options=StepOptions(dt=1e-2))
    # slides at once with a = 2.5 - 1 (kinetic): x = 0.75 t^2
    assert moving.x[0, -1] == pytest.approx(0.75, rel=1e-3)


def test_bouncing_ball_impact_time_and_restitution():
    ls = LinearSystem(M=np.eye(1), K=np.zeros((1, 1)), dof_field=["x"])
    dt = 1e-4
    r = simulate_timestepping(ls, [Impact("floor", np.ones(1), s_min=0.0, restitution=0.5)],
                              forces=[ExternalForce(np.ones(1), value=-9.81)], x0=np.ones(1), t_end=0.7,
                              options=StepOptions(dt=dt))
    t1 = np.sqrt(2 / 9.81)
    hits = [e.t for e in r.events if e.kind == "impact"]
    assert hits[0] == pytest.approx(t1, abs=2 * dt)
    # rebound velocity e * v_impact
    k = np.searchsorted(r.t, hits[0]) + 2
    assert r.v[0, k] == pytest.approx(0.5 * 9.81 * t1, rel=5e-3)
    assert r.energy_error < 1e-9      # the impact loss is counted as contact work


def test_theta_above_half_dissipates_linear_energy():
    r = simulate_timestepping(_sdof(), [], x0=np.ones(1), t_end=20.0, options=StepOptions(dt=0.05, theta=0.6))
    E = 0.5 * r.v[0] ** 2 + 0.5 * r.x[0] ** 2
    assert E[-1] < 0.9 * E[0]
    r2 = simulate_timestepping(_sdof(), [], x0=np.ones(1), t_end=20.0, options=StepOptions(dt=0.05, theta=0.5))
    E2 = 0.5 * r2.v[0] ** 2 + 0.5 * r2.x[0] ** 2
    assert abs(E2[-1] - E2[0]) < 1e-12


def test_driver_moves_constrained_dof():
    """Two DOFs, the first driven at constant speed through a spring: the second follows."""
    ls = LinearSystem(M=np.eye(2), K=np.array([[1.0, -1.0], [-1.0, 1.0]]), dof_field=["x", "x"], constrained=[0])
    r = simulate_timestepping(ls, [], drivers={0: MotionLaw(velocity=1.0)}, t_end=2 * np.pi,
                              options=StepOptions(dt=1e-3))
    # exact: x2 = t - sin t
    assert r.x[1, -1] == pytest.approx(2 * np.pi - np.sin(2 * np.pi), abs=1e-5)
    assert r.x[0, -1] == pytest.approx(2 * np.pi)


@pytest.mark.parametrize("kw, key", [(dict(dt=0.0), "dt"), (dict(dt=1e-3, theta=0.3), "theta")])
def test_bad_options(kw, key):
    with pytest.raises(ModelError) as exc:
        simulate_timestepping(_sdof(), [], t_end=1.0, options=StepOptions(**kw))
    assert key in str(exc.value)


def test_smooth_gap_law_is_rejected_with_a_pointer_to_the_event_solver():
    with pytest.raises(ModelError, match="event"):
        simulate_timestepping(_sdof(), [Gap("g", np.ones(1), k=1.0, lower=-1.0, upper=1.0, law="arctan")], t_end=1.0,
                              options=StepOptions(dt=1e-2))


def test_gap_oscillator_agrees_with_the_exact_event_driven_solution():
    """Oscillator k = 1 with a stiff two-sided gap (k = 50, clearance +-0.5) started at x = 1.2: the
    exact event-driven solution is the reference; the implicit midpoint treatment converges at second
    order between switches and first order at them, and conserves the energy (spring potentials)."""
    from discrete.nonsmooth import Options, Problem, simulate

    gap = Gap("g", np.ones(1), k=50.0, lower=-0.5, upper=0.5)
    exact = simulate(Problem(_sdof(), [Gap("g", np.ones(1), k=50.0, lower=-0.5, upper=0.5)], x0=np.array([1.2])),
                     5.0, Options())
    errs = []
    for dt in (1e-3, 5e-4):
        r = simulate_timestepping(_sdof(), [gap], x0=np.array([1.2]), t_end=5.0, options=StepOptions(dt=dt))
        errs.append(abs(r.x[0, -1] - exact.x[0, -1]))
        assert r.energy_error < 5e-3
        assert any(e.kind == "contact_close" for e in r.events)
    assert errs[1] < 1e-3 and errs[1] < 0.7 * errs[0]


def test_many_frictions_agree_with_the_exact_event_driven_solver():
    """Three masses in a chain, the first pulled at constant speed through a spring, Coulomb friction
    (static > kinetic) on every mass: Moreau-Jean converges to the exact event-driven solution at
    first order in the step (events are located only to the step)."""
    from discrete.nonsmooth import Options, Problem, simulate

    K = np.array([[1.0, -1.0, 0, 0], [-1.0, 2.0, -1.0, 0], [0, -1.0, 2.0, -1.0], [0, 0, -1.0, 1.0]]) * 10.0
    ls = LinearSystem(M=np.diag([1.0, 1.0, 1.5, 2.0]), K=K, dof_field=["x"] * 4, constrained=[0])
    els = [Friction(f"f{i}", np.eye(4)[i], kinetic=0.5 * i, static=0.8 * i) for i in (1, 2, 3)]
    drv = {0: MotionLaw(velocity=0.3)}
    exact = simulate(Problem(ls, [Friction(e.name, e.g, e.kinetic, e.static) for e in els], drivers=drv), 6.0,
                     Options())
    errs = []
    for dt in (2e-3, 1e-3):
        r = simulate_timestepping(ls, els, drivers=drv, t_end=6.0, options=StepOptions(dt=dt))
        errs.append(np.max(np.abs(r.x[1:, -1] - exact.x[1:, -1])))
        assert r.energy_error < 1e-9
    assert errs[1] < 2e-3 * np.max(np.abs(exact.x[1:, -1]))
    assert errs[1] < 0.7 * errs[0]          # converges (first order at the stick/slip switches)
