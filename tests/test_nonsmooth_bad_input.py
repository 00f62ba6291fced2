"""Bad input to the nonsmooth model files: a clear ModelError naming the key, its value and what is allowed."""
import copy

import pytest

from discrete.errors import ModelError
from fem.study import simulate

BASE = {"body": [{"name": "disk", "inertia": 1.0}],
        "driver": [{"name": "top", "velocity": 1.0}],
        "spring": [{"between": ["top", "disk"], "k": 1.0}],
        "friction": [{"name": "f", "body": "disk", "kinetic": 1.0, "static": 2.0}],
        "simulation": {"t_end": 1.0}}


def doc_with(path, value, base=BASE):
    d = copy.deepcopy(base)
    node = d
    for p in path[:-1]:
        node = node[p]
    if value is KeyError:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return d


CASES = [
    # (path, value, words that must appear in the message)
    (("body", 0, "inertia"), -1.0, ["inertia", "-1.0", "> 0"]),
    (("spring", 0, "k"), -5.0, ["k", "-5.0", ">= 0"]),
    (("friction", 0, "static"), 0.5, ["static", "0.5", "kinetic level"]),
    (("friction", 0, "kinetic"), -1.0, ["kinetic", "-1.0", ">= 0"]),
    (("friction", 0, "restick"), "sometimes", ["restick", "sometimes", "'static' | 'kinetic'"]),
    (("friction", 0, "body"), "disc", ["body", "disc", "'disk'"]),
    (("friction", 0, "colour"), "red", ["colour", "red", "unknown keys are an error"]),
    (("simulation", "t_end"), 0.0, ["t_end", "0.0", "> 0"]),
    (("simulation", "t_end"), -3.0, ["t_end", "-3.0", "> 0"]),
    (("simulation", "t_end"), KeyError, ["t_end", "required"]),
    (("simulation", "method"), "magic", ["method", "magic", "'event' | 'moreau' | 'regularised'"]),
    (("simulation",), KeyError, ["simulation", "t_end"]),
    (("driver", 0, "name"), KeyError, ["name", "required"]),
    (("impact",), [{"body": "disk", "restitution": 1.5}], ["restitution", "1.5", "[0, 1]"]),
    (("impact",), [{"body": "disk", "restitution": -0.1}], ["restitution", "-0.1", "[0, 1]"]),
    (("impact",), [{"body": "nobody", "restitution": 0.5}], ["body", "nobody", "'disk'"]),
    (("one_sided",), [{"between": ["top", "disk"], "k": -1.0}], ["k", "-1.0", "> 0"]),
    (("one_sided",), [{"between": ["top", "wheel"], "k": 1.0}], ["between", "wheel", "'ground'"]),
    (("one_sided",), [{"between": ["top", "disk"], "k": 1.0, "side": "both"}], ["side", "both", "'tension'"]),
    (("gap",), [{"body": "disk", "k": 0.0, "delta": 0.1}], ["k", "0.0", "> 0"]),
    (("gap",), [{"body": "disk", "k": 1.0, "lower": 0.2, "upper": 0.1}], ["lower", "0.2", "upper"]),
    (("gap",), [{"body": "disk", "k": 1.0, "lower": -0.1, "upper": 0.3, "law": "arctan"}],
     ["clearance", "symmetric"]),
    (("force",), [{"body": "disk", "amplitude": 1.0}], ["omega", "with amplitude"]),
    (("friction", 0, "normal"), "weight", ["kinetic", "mu"]),
    (("wheel",), [{"name": "w"}], ["wheel", "unknown keys are an error"]),
    (("constants", ), {"g": -9.81}, ["g", "-9.81", "> 0"]),
]


@pytest.mark.parametrize("path,value,words", CASES, ids=[".".join(map(str, c[0])) + "=" + repr(c[1])[:20] for c in CASES])
def test_bad_input_message(path, value, words):
    with pytest.raises(ModelError) as exc:
        simulate(doc_with(path, value))
    msg = str(exc.value)
    for w in words:
        assert w in msg, f"{w!r} not in message {msg!r}"


def test_variable_mass_vanishing():
    d = {"body": [{"name": "m", "inertia": 1.0, "inertia_rate": -1.0}],
         "spring": [{"between": ["ground", "m"], "k": 1.0}], "simulation": {"t_end": 2.0}}
    with pytest.raises(ModelError) as exc:
        simulate(d)
    assert "inertia_rate" in str(exc.value) and "-1.0" in str(exc.value) and "t = 1" in str(exc.value)


def test_weight_friction_mu_static_below_mu():
    d = copy.deepcopy(BASE)
    d["friction"] = [{"body": "disk", "mu": 0.3, "mu_static": 0.2, "normal": "weight"}]
    with pytest.raises(ModelError) as exc:
        simulate(d)
    assert "mu_static" in str(exc.value) and "0.2" in str(exc.value) and ">= mu" in str(exc.value)


def test_duplicate_element_name():
    d = copy.deepcopy(BASE)
    d["friction"].append({"name": "f", "body": "disk", "kinetic": 1.0})
    with pytest.raises(ModelError) as exc:
        simulate(d)
    assert "name" in str(exc.value) and "'f'" in str(exc.value)


def test_event_limit_keeps_results_and_says_where():
    d = copy.deepcopy(BASE)
    d["simulation"] = {"t_end": 100.0, "max_events": 3}
    res = simulate(d)
    assert res.stopped_early and "max_events = 3" in res.reason and "t = " in res.reason
    assert res.t[-1] > 0 and len(res.events) == 3


def test_initial_state_on_gear_driven_body():
    d = {"body": [{"name": "a", "inertia": 1.0}, {"name": "b", "inertia": 1.0, "x0": 0.1}],
         "gear": [{"between": ["a", "b"], "ratio": 2.0}],
         "spring": [{"between": ["ground", "a"], "k": 1.0}], "simulation": {"t_end": 1.0}}
    with pytest.raises(ModelError) as exc:
        simulate(d)
    assert "x0" in str(exc.value) and "0.1" in str(exc.value) and "gear" in str(exc.value)


def test_tables_of_other_analyses_are_not_silently_ignored():
    d = copy.deepcopy(BASE)
    d["damping"] = {"zeta": 0.02}
    with pytest.raises(ModelError) as exc:
        simulate(d)
    assert "[damping]" in str(exc.value) and "'modal'" in str(exc.value) and "time simulation" in str(exc.value)
