"""Exact integration of piecewise-affine laws in HB, truncation estimates, measures, bifurcation tools
(issue 27)."""
import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.nonsmooth.elements.base import PiecewiseAffineLaw
from discrete.steady import HBModel, bifurcation as bif, measures
from discrete.steady.hb import floquet_hb_batch
from discrete.steady.piecewise import ExactProjection, crossings, trig_eval
from fem.study import forced, steady_model
from validation.cases.steady_bifurcations import stop_doc  # the issue-27 two-sided stop, as validated


def _series(rng, H, scale):
    C = rng.standard_normal(2 * H + 1) * scale / np.arange(1, 2 * H + 2) ** 2
    C[0], C[1] = 0.0, scale
    return C


@pytest.mark.parametrize("law", [
    PiecewiseAffineLaw((-0.3, 0.4), (-6.0, 0.0, 8.0), (-20.0, 0.0, -20.0), (0.0, 0.0, 0.0)),     # gap
    PiecewiseAffineLaw((0.2,), (0.0, 3.0), (0.0, -15.0), (0.0, 0.0)),                              # one-sided
    PiecewiseAffineLaw((0.1,), (0.0, 2.0), (0.0, -20.0), (0.0, -0.7)),                             # stop + dashpot
])
def test_exact_projection_equals_dense_sampling(law):
    rng = np.random.default_rng(3)
    H, N = 9, 64
    proj = ExactProjection(law, H)
    Cs = _series(rng, H, 1.0)
    D = np.zeros((2 * H + 1, 2 * H + 1))
    for k in range(1, H + 1):
        D[2 * k, 2 * k - 1], D[2 * k - 1, 2 * k] = k, -k
    Om = 1.3
    out = proj.evaluate(Cs, Om * (Cs @ D), trig_eval(Cs, 2 * np.pi * np.arange(N) / N), jac=True)
    Nd = 1 << 18                       # dense rectangle rule: error ~ 1/Nd^2 at a kink, ~ 1/Nd at a jump
    td = 2 * np.pi * np.arange(Nd) / Nd
    F = np.fft.rfft(law.force(trig_eval(Cs, td), Om * trig_eval(Cs @ D, td)))[:H + 1] / Nd
    ref = np.concatenate([[F[0].real], np.ravel(np.column_stack([2 * F[1:].real, -2 * F[1:].imag]))])
    tol = 1e-4 if np.any(law.c) else 1e-9
    assert np.max(np.abs(out["F"] - ref)) < tol * np.max(np.abs(ref))
    assert (out["jump"] is not None) == bool(np.any(law.c))


@pytest.mark.parametrize("element", [
    {"gap": [{"name": "stop", "body": "mass", "k": 8e5, "delta": 1e-3}]},
    {"contact": [{"name": "stop", "body": "mass", "k": 8e5, "c": 300.0, "upper": 1e-3}]},    # jumps at contact
])
def test_hb_jacobian_of_exact_kinks_equals_finite_differences(element):
    d = stop_doc()
    d.pop("gap")
    d.update(element)
    hb = HBModel(steady_model(d).system, harmonics=12)
    assert hb.exact_elements == [0]
    rng = np.random.default_rng(0)
    X = np.zeros(25)
    X[1], X[2] = 2e-3, 1e-3
    X[3:] = 1e-5 * rng.standard_normal(22)
    w = 400.0
    R, J, Rw = hb.evaluate_residual(X, w, jac=True, dw=True)
    h = 1e-10
    Jfd = np.column_stack([(hb.residual(X + h * e, w, jac=False) - hb.residual(X - h * e, w, jac=False)) / (2 * h)
                           for e in np.eye(25)])
    assert np.max(np.abs(J - Jfd)) < 1e-6 * np.max(np.abs(J))
    Rwfd = (hb.residual(X, w + 1e-4, jac=False) - hb.residual(X, w - 1e-4, jac=False)) / 2e-4
    assert np.max(np.abs(Rw - Rwfd)) < 1e-6 * np.max(np.abs(Rw))


def test_crossings_find_a_contact_shorter_than_a_sample_interval():
    H, N = 5, 32
    C = np.zeros(2 * H + 1)
    C[1] = 1.0                                        # cos(theta): maximum 1 at theta = 0 (a sample)
    C[2] = 0.1                                        # shifted: the maximum falls between samples
    peak = np.hypot(1.0, 0.1)
    b = peak - 1e-6                                   # a break just below the true maximum
    S = trig_eval(C, 2 * np.pi * np.arange(N) / N)
    assert np.all(S < b)                              # no sample sees the contact
    th, bi, d1 = crossings(C, S, (b,))
    assert th.size == 2
    assert np.allclose(trig_eval(C, th), b, atol=1e-14)


def test_stop_repro_two_folds_exact_kinks_and_json_keys(tmp_path):
    r = forced(stop_doc(stability=False, bifurcations=False))
    w = sorted(f["omega"] for f in r.folds)
    assert len(w) == 2
    assert abs(w[0] - 264.326786256) < 1e-3 * 264.33 and abs(w[1] - 584.404326840) < 1e-3 * 584.4   # exact shooting
    d = r.to_dict()
    assert len(d["truncation_estimate"]) == r.omega.size and d["truncation_ok"] is True
    assert [b["type"] for b in d["bifurcations"]] == ["fold", "fold"]
    assert all(b["check_harmonics"] == 20 and b["estimate"] < 1e-5 for b in d["bifurcations"])
    from fem.output.figures import plot_afc
    plot_afc(r, tmp_path / "stop.png", title="two-sided stop")
    assert (tmp_path / "stop.png").stat().st_size > 10_000


def test_floquet_split_at_crossings_is_exact_for_piecewise_linear_laws():
    """Between crossings the coefficients of a piecewise-linear law are constant: the crossing-cut
    intervals give the exact transition matrices -- 8 intervals equal 4096 uniform ones cut likewise, and
    the uncut uniform midpoint rule is off by O(1/M)."""
    r = forced(stop_doc(stability=False, bifurcations=False))
    hb = HBModel(steady_model(stop_doc()).system, harmonics=15)
    i = int(np.argmax(r.response))                    # the resonance peak: in contact
    X, w = r.states[i], r.omega[i]
    mu8 = floquet_hb_batch(hb, [X], [w])[0]
    mu_fine = floquet_hb_batch(hb, [X], [w], steps=4096)[0]
    assert np.max(np.abs(np.sort_complex(mu8) - np.sort_complex(mu_fine))) < 1e-10
    hs = HBModel(hb.s, harmonics=15, kinks="sampled")
    mu_plain = floquet_hb_batch(hs, [X], [w], steps=512)[0]
    assert np.max(np.abs(np.sort_complex(mu_plain) - np.sort_complex(mu_fine))) > 1e-6


def test_measures_extremes_and_h1():
    rng = np.random.default_rng(5)
    C = rng.standard_normal((3, 2 * 8 + 1)) / np.arange(1, 18)
    mx, mn = measures.series_extremes(C)
    gx, gn = measures.golden_extremes(lambda t: measures.series_values(C, t), 3, 64)
    assert np.allclose(mx, gx, atol=1e-12) and np.allclose(mn, gn, atol=1e-12)
    P = 1 << 16
    y = measures.series_values(C, np.broadcast_to(2 * np.pi * np.arange(P) / P, (3, P)))
    assert np.all(mx >= y.max(axis=1) - 1e-15) and np.all(mx - y.max(axis=1) < 1e-8)
    # h1 of harmonic nu of the series: a 1/3 subharmonic's forcing component, no leakage of omega / 3
    C2 = np.zeros(2 * 6 + 1)
    C2[1], C2[5], C2[6] = 1.0, 0.3, 0.4
    assert measures.series_h1(C2, 3)[0] == pytest.approx(0.5, abs=1e-15)
    # time series: dense output repeats instants where pieces join; no parabola across an event
    t = np.linspace(0.0, 1.0, 101)
    t = np.sort(np.concatenate([t, t[40:60]]))
    yy = np.sin(2 * np.pi * t + 0.05)
    assert measures.refined_sample_extremes(t, yy)[0] == pytest.approx(1.0, abs=1e-6)
    yk = 1 - np.abs(t - 0.2503)                        # a kink between samples: the event keeps the sample
    assert measures.refined_sample_extremes(t, yk, events=[0.2503])[0] == yk.max()


def test_bifurcation_test_functions_classify():
    fold_pair = ([0.9, 0.5], [1.1, 0.5])
    assert bif.detect([np.array(a, complex) for a in fold_pair], None, [0])[0:0] == []
    kinds = [k for _, k, _ in bif.detect([np.array([0.9, 0.5], complex), np.array([1.1, 0.5], complex)], None, [])]
    assert kinds == ["branch_point"]               # +1 crossing without a fold
    kinds = [k for _, k, _ in bif.detect([np.array([-0.9, 0.5], complex), np.array([-1.1, 0.5], complex)], None, [])]
    assert kinds == ["period_doubling"]
    ns = [np.array([0.9 * np.exp(1j), 0.9 * np.exp(-1j)]), np.array([1.1 * np.exp(1j), 1.1 * np.exp(-1j)])]
    assert [k for _, k, _ in bif.detect(ns, None, [])] == ["neimark_sacker"]
    saddle = [np.array([2.0, 0.45], complex), np.array([2.0, 0.55], complex)]   # mu1 mu2 through 1: not NS
    assert bif.detect(saddle, None, []) == []
    assert [k for _, k, _ in bif.detect([np.array([0.5, 0.4]), np.array([0.5, 0.4])], [1.0, -1.0], [])] == \
        ["branch_point"]


def test_embedding_doubles_the_period():
    n, H = 2, 4
    X = np.arange(n * (2 * H + 1), dtype=float)
    Y = bif.embed_doubled(X, n, H).reshape(n, 4 * H + 1)
    th = np.linspace(0, 2 * np.pi, 7)
    for j in range(n):
        assert np.allclose(trig_eval(X.reshape(n, -1)[j], th), trig_eval(Y[j], th / 2))
    assert np.all(Y[:, 1::4] == 0) and np.all(Y[:, 2::4] == 0)      # odd harmonics of omega / 2


@pytest.mark.parametrize("key,value,words", [
    ("max_harmonics", 5, "at least harmonics"),
    ("kinks", "linear", "exact"),
    ("truncation_tol", 0.0, "> 0"),
])
def test_new_steady_keys_are_checked(key, value, words):
    with pytest.raises(ModelError) as e:
        forced(stop_doc(**{key: value}))
    assert key in str(e.value) and words in str(e.value)


def test_switching_needs_stability_and_adaptive_is_hb_only():
    with pytest.raises(ModelError, match="switch_branches"):
        forced(stop_doc(switch_branches=True, stability=False))
    with pytest.raises(ModelError, match="adaptive"):
        forced(stop_doc(adaptive=True, method="shooting"))
