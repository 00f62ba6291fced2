"""The fast paths of the steady-state solvers compute what the direct definitions compute.

* HB: the Galerkin matrices from one FFT (product-to-sum) equal the sampled sums ``Pm^T diag(c) G^T``;
  the assembled Jacobian and the analytic frequency derivative equal central differences of the residual;
* Floquet: the closed-form 2x2 exponential equals the [6/6] Pade one; the batched multipliers (2x2 and
  the general deduplicated path) equal the plain exponential-midpoint product built from
  ``PeriodicSystem.rhs_terms``, scipy's expm per interval, multiplied in sequence;
* shooting: period maps with the solver (and its exact pieces) kept between runs equal maps with a
  fresh solver each time;
* continuation: the warm-started branch points are the solutions a cold start finds at their frequencies.
"""
import numpy as np
import pytest
from scipy.linalg import expm
from threadpoolctl import threadpool_limits

from discrete.linalg import expm_batch
from discrete.steady import HBModel, ShootingModel, floquet_hb
from discrete.steady.hb import _expm2, _expm2_parts, _expm2_runs, floquet_hb_batch
from fem.study import forced, steady_model
from validation.analytic.steady_seed002 import K_NAT, seed002_doc


def chain(H=5, **steady):
    """Three masses with a cubic spring between 1 and 3, a backlash on 2, a force on 1."""
    return {"body": [{"name": "m1", "inertia": 1.0}, {"name": "m2", "inertia": 0.5}, {"name": "m3", "inertia": 0.7}],
            "spring": [{"between": ["ground", "m1"], "k": 1.0}, {"between": ["m1", "m2"], "k": 2.0},
                       {"between": ["m2", "m3"], "k": 1.5}],
            "damper": [{"between": ["ground", "m1"], "c": 0.05}, {"between": ["m2", "m3"], "c": 0.05}],
            "cubic_spring": [{"between": ["m1", "m3"], "k3": 0.5}],
            "gap": [{"name": "bl", "body": "m2", "k": 1.0, "delta": 0.1}],
            "force": [{"body": "m1", "amplitude": 0.25, "omega": 1.0}],
            "steady": {"omega": [0.5, 2.2], "harmonics": H, "response": {"body": "m1", "measure": "h1"}, **steady}}


@pytest.mark.parametrize("H, N", [(7, 64), (7, 17)])      # rfft path, and N < 4H + 1 (full FFT, aliased sums)
def test_galerkin_from_fft_equals_sampled_sums(H, N):
    hb = HBModel(steady_model(chain()).system, harmonics=H, samples=N)
    rng = np.random.default_rng(3)
    c = rng.normal(size=(2, N))
    direct = np.array([(hb.Pm.T * ck) @ hb.G.T for ck in c])
    assert np.max(np.abs(hb.galerkin(c) - direct)) < 1e-13 * np.max(np.abs(direct))
    B = hb.element_blocks(c[:1], c[1:], 1.7)
    assert np.max(np.abs(B[0] - (direct[0] + 1.7 * direct[1] @ hb.D.T))) < 1e-13 * np.max(np.abs(direct))


@pytest.mark.parametrize("nu", [1, 2])
def test_hb_jacobians_equal_central_differences(nu):
    hb = HBModel(steady_model(chain()).system, harmonics=5, nu=nu)
    w = 1.1
    X = hb.linear_guess(w) + 0.1 * np.random.default_rng(1).normal(size=hb.nq)
    R, J, Rw = hb.evaluate_residual(X, w, jac=True, dw=True)
    assert np.array_equal(R, hb.residual(X, w, jac=False))
    h = 1e-6
    Jfd = np.array([(hb.residual(X + h * e, w, jac=False) - hb.residual(X - h * e, w, jac=False)) / (2 * h)
                    for e in np.eye(hb.nq)]).T
    # the backlash samples do not cross its kink within +-h here: the difference is exact to ~1e-9
    assert np.max(np.abs(J - Jfd)) < 1e-7 * np.max(np.abs(J))
    hw = 1e-6 * w
    Rwfd = (hb.residual(X, w + hw, jac=False) - hb.residual(X, w - hw, jac=False)) / (2 * hw)
    assert np.max(np.abs(Rw - Rwfd)) < 1e-7 * np.max(np.abs(Rw))


def test_closed_form_2x2_exponential_equals_pade():
    rng = np.random.default_rng(7)
    Y = rng.normal(size=(400, 2, 2)) * rng.choice([1e-4, 0.3, 2.0], size=(400, 1, 1))
    Y[0] = [[0.0, 1.0], [-1.0, 0.0]]               # rotation
    Y[1] = [[0.5, 1.0], [0.0, 0.5]]                # defective (x = 0)
    Y[2] = 0.0
    Y[3] = [[0.0, 0.3], [-0.3 * 3.0, -2 * np.sqrt(3.0) * 0.3]]   # critically damped oscillator step
    E = _expm2(Y)
    ref = expm_batch(Y)
    assert np.max(np.abs(E - ref) / np.maximum(np.abs(ref).max(axis=(1, 2), keepdims=True), 1e-300)) < 2e-14


def test_exponentials_by_runs_equal_one_per_interval():
    """Runs of equal intervals (a saturated friction law, a contact on or off) are exponentiated once:
    bit for bit what one exponential per interval gives, a run broken by a sign of zero included."""
    rng = np.random.default_rng(11)
    h = np.array([0.01, 0.02, 0.5])
    c = np.repeat(rng.normal(size=(3, 8)), rng.integers(1, 40, size=8), axis=1)[:, :64]
    d = np.repeat(rng.normal(size=(3, 8)), rng.integers(1, 40, size=8), axis=1)[:, :64]
    c, d = c[:, :min(c.shape[1], d.shape[1])], d[:, :min(c.shape[1], d.shape[1])]
    d[1, 5:9] = 0.0
    d[1, 7] = -0.0
    hh = np.broadcast_to(h[:, None], c.shape)
    runs = _expm2_runs(h, c, d)
    direct = _expm2_parts(np.zeros_like(hh), hh, c, d)
    assert all(np.array_equal(a.view(np.uint64), b.view(np.uint64)) for a, b in zip(runs, direct))


def test_floquet_of_a_linear_oscillator_is_its_exact_exponential():
    """One DOF and no nonlinear element (k, c scalars in the batch): every interval has the same
    matrix, the exponential midpoint rule is exact, and the multipliers are exp(lambda T) of the
    roots of m s^2 + c s + k, at every orbit of a batch."""
    doc = {"body": [{"name": "m", "inertia": 2.0}], "spring": [{"between": ["ground", "m"], "k": 3.0}],
           "damper": [{"between": ["ground", "m"], "c": 0.2}], "force": [{"body": "m", "amplitude": 0.1, "omega": 1.3}],
           "steady": {"omega": [1.0, 1.5], "harmonics": 3, "response": {"body": "m", "measure": "h1"}}}
    hb = HBModel(steady_model(doc).system, harmonics=3)
    ws = np.array([1.1, 1.3])
    Xs = [hb.solve(hb.linear_guess(w), w)[0] for w in ws]
    mu = floquet_hb_batch(hb, Xs, ws)
    lam = np.roots([2.0, 0.2, 3.0])
    for m, w in zip(mu, ws):
        exact = np.sort_complex(np.exp(lam * 2 * np.pi / w))
        assert np.max(np.abs(np.sort_complex(m) - exact)) < 1e-12


def _floquet_reference(hb, X, w, M):
    """The exponential-midpoint monodromy the plain way: rhs_terms at the midpoints, one exponential
    per interval (scipy), sequential product."""
    s, n = hb.s, hb.s.n
    th = (2 * np.pi * np.arange(2 * M) / (2 * M))[1::2]
    t, q, v = hb.evaluate(X, w, points=2 * M)
    t, q, v = t[1::2], q[:, 1::2], v[:, 1::2]
    _, Fq, Fv = s.rhs_terms(t, q, v, w)
    Minv = np.linalg.inv(s.M)
    Phi = np.eye(2 * n)
    h = 2 * np.pi * hb.nu / w / M
    with threadpool_limits(1):          # scipy's expm kernel slows down badly under BLAS thread contention
        for j in range(th.size):
            A = np.zeros((2 * n, 2 * n))
            A[:n, n:] = np.eye(n)
            A[n:, :n] = -Minv @ (s.K - Fq[:, :, j])
            A[n:, n:] = -Minv @ (s.C - Fv[:, :, j])
            Phi = expm(A * h) @ Phi
    return np.sort_complex(np.linalg.eigvals(Phi))


def test_batched_floquet_equals_plain_product():
    sm = steady_model(seed002_doc(4.7e-4, "simple"))          # one DOF: the 2x2 closed form
    hb = HBModel(sm.system, harmonics=15)
    ws = [0.6 * K_NAT, 0.72 * K_NAT]
    Xs = [hb.solve(hb.linear_guess(w), w)[0] for w in ws]
    mus = floquet_hb_batch(hb, Xs, ws, steps=256)
    for X, w, mu in zip(Xs, ws, mus):
        ref = _floquet_reference(hb, X, w, 256)
        assert np.max(np.abs(np.sort_complex(mu) - ref)) < 1e-12
        assert np.max(np.abs(np.sort_complex(floquet_hb(hb, X, w, steps=256)) - ref)) < 1e-12
    # three DOFs: deduplicated Pade path (sampled kinks: the plain uniform midpoint rule; with exactly
    # integrated kinks the intervals are cut at the crossings, tests/test_steady_piecewise.py)
    hb3 = HBModel(steady_model(chain()).system, harmonics=5, kinks="sampled")
    X = hb3.solve(hb3.linear_guess(1.1), 1.1)[0]
    mu = floquet_hb_batch(hb3, [X, X], [1.1, 1.1], steps=128)
    ref = _floquet_reference(hb3, X, 1.1, 128)
    assert np.max(np.abs(np.sort_complex(mu[0]) - ref)) < 1e-12 and np.array_equal(mu[0], mu[1])


def test_shooting_with_kept_solver_equals_fresh_solver():
    """Maps at 0.69, 0.8, then 0.69 again: the third reuses the solver kept from the first (its exact
    pieces and the per-run reset of what depends on the initial state)."""
    sm = steady_model(seed002_doc(8.6e-4, "combined"))        # exact and numerically integrated pieces
    kept = ShootingModel(sm.factory)
    fresh = ShootingModel(sm.factory, reuse=False)
    assert kept.reuse, "the solver-reuse path is not available (discrete.nonsmooth.solver changed?)"
    y = np.array([0.002, -0.05])
    for w in (0.69 * K_NAT, 0.8 * K_NAT, 0.69 * K_NAT):
        a, b = kept.map(y, w), fresh.map(y, w)
        assert np.max(np.abs(a - b)) <= 1e-13 * np.max(np.abs(b))
        y = a
    assert len(kept._solvers) == 2 and fresh.n_sims == kept.n_sims == 3


def test_warm_started_branch_points_equal_cold_solutions():
    r = forced(seed002_doc(1e-4, "simple", z=(0.3, 1.4)))
    sm = steady_model(seed002_doc(1e-4, "simple"))
    hb = HBModel(sm.system, harmonics=15)
    for i in range(0, r.omega.size, max(1, r.omega.size // 6)):
        X, _ = hb.solve(hb.linear_guess(r.omega[i]), r.omega[i])
        assert np.max(np.abs(X - r.states[i])) <= 1e-8 * np.max(np.abs(X))
