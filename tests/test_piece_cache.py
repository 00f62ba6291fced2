"""The content-keyed caches of the exact pieces (discrete.nonsmooth.piece): a repeated run of the
same model finds its step maps, work matrices and power forms, and gives the same bits as a run
with empty caches; a changed model finds nothing of the old one (its results are those of a
fresh process)."""
import numpy as np
import pytest

from discrete.nonsmooth import Options, piece, simulate
from fem.study import Study


def _problem(c=50.0):
    doc = {"body": [{"name": "disk", "inertia": 2.0}],
           "driver": [{"name": "top", "velocity": 1.0}],
           "spring": [{"between": ["top", "disk"], "k": c}],
           "friction": [{"name": "bit", "body": "disk", "kinetic": 3.0, "static": 18.0, "restick": "kinetic"}],
           "simulation": {"t_end": 8.0}}
    study = Study.parse(doc)
    return study.problem_spec().problem(), study.simulation_settings()["t_end"]


def _arrays(r):
    return [r.t, r.x, r.v, r.energy, r.work, r.element_forces, np.array([e.t for e in r.events])]


def _clear():
    for cache in (piece._RHO, piece._STEP_MAPS, piece._WORK, piece._POWER):
        cache.clear()


def test_repeated_run_uses_the_caches_and_keeps_the_bits(monkeypatch):
    problem, t_end = _problem()
    _clear()
    first = simulate(problem, t_end, Options())
    assert len(first.events) > 5 and piece._STEP_MAPS and piece._POWER
    calls = []
    inner = piece._taylor_terms
    monkeypatch.setattr(piece, "_taylor_terms", lambda A, h: calls.append(h) or inner(A, h))
    monkeypatch.setattr(piece, "power_form", lambda *a: pytest.fail("power form recomputed"))
    again = simulate(problem, t_end, Options())
    assert calls == []                                  # every mode found its expansion
    for a, b in zip(_arrays(first), _arrays(again)):
        assert np.array_equal(a, b)


def test_changed_model_finds_nothing_stale():
    """A stiffer spring: its results with the caches full of the first model's entries equal its
    results from empty caches (and differ from the first model's)."""
    problem, t_end = _problem()
    stiff, _ = _problem(c=80.0)
    _clear()
    first = simulate(problem, t_end, Options())
    warm = simulate(stiff, t_end, Options())
    _clear()
    cold = simulate(stiff, t_end, Options())
    for a, b in zip(_arrays(warm), _arrays(cold)):
        assert np.array_equal(a, b)
    assert first.t.size != warm.t.size or not np.array_equal(first.t, warm.t)


def test_cache_size_is_bounded(monkeypatch):
    monkeypatch.setattr(piece, "CACHE_SIZE", 3)
    _clear()
    for c in (40.0, 50.0, 60.0, 70.0):
        problem, t_end = _problem(c)
        simulate(problem, 1.0, Options())
    assert all(len(cache) <= 3 for cache in (piece._RHO, piece._STEP_MAPS, piece._WORK, piece._POWER))


def test_power_forms_are_kept_per_problem(monkeypatch):
    """Two problems built from the same file are separate entries of the power-form cache (its
    key holds the problem; matrices alone do not say everything a power form depends on), and the
    results agree to the bit."""
    first_problem, t_end = _problem()
    _clear()
    first = simulate(first_problem, t_end, Options())
    calls = []
    inner = piece.power_form
    monkeypatch.setattr(piece, "power_form", lambda *a: calls.append(a[1]) or inner(*a))
    second_problem, _ = _problem()
    second = simulate(second_problem, t_end, Options())
    assert calls                                        # computed again for the new problem
    for a, b in zip(_arrays(first), _arrays(second)):
        assert np.array_equal(a, b)
