"""Bad input of [steady] and [[cubic_spring]]: clear ModelErrors naming key and value."""
import copy

import pytest

from discrete.errors import ModelError
from fem.study import Study
from fem.study import forced

BASE = {"body": [{"name": "m", "inertia": 1.0}], "spring": [{"between": ["ground", "m"], "k": 1.0}],
        "damper": [{"between": ["ground", "m"], "c": 0.1}],
        "force": [{"body": "m", "amplitude": 0.25, "omega": 1.0}],
        "steady": {"omega": [0.5, 1.5], "harmonics": 1}}


def with_steady(**kw):
    d = copy.deepcopy(BASE)
    d["steady"].update(kw)
    return d


@pytest.mark.parametrize("kw,key", [
    ({"omega": [1.0, 1.0]}, "omega"), ({"omega": [-1.0, 2.0]}, "omega"), ({"omega": [1.0]}, "omega"),
    ({"omega": "fast"}, "omega"), ({"z": [0.5, 1.5]}, "omega"), ({"harmonics": 0}, "harmonics"),
    ({"method": "magic"}, "method"), ({"response": {"element": "nope"}}, "element"),
    ({"response": {"body": "nope"}}, "body"), ({"unknown": 1}, "unknown"), ({"stability": "yes"}, "stability"),
    ({"samples": 3, "harmonics": 2}, "samples"), ({"response": {"body": "m", "measure": "rms"}}, "measure"),
])
def test_bad_steady(kw, key):
    with pytest.raises(ModelError) as exc:
        forced(with_steady(**kw))
    assert key in str(exc.value)


def test_z_without_ref():
    d = copy.deepcopy(BASE)
    d["steady"] = {"z": [0.5, 1.5]}
    with pytest.raises(ModelError, match="omega_ref"):
        forced(d)


def test_no_harmonic_excitation():
    d = copy.deepcopy(BASE)
    d["force"][0]["amplitude"] = 0.0
    with pytest.raises(ModelError, match="harmonic"):
        forced(d)


def test_cubic_bad():
    d = copy.deepcopy(BASE)
    d["cubic_spring"] = [{"between": ["ground", "m"]}]
    with pytest.raises(ModelError, match="k3"):
        forced(d)
    d["cubic_spring"] = [{"between": ["ground", "m"], "k3": 1.0, "foo": 2}]
    with pytest.raises(ModelError, match="foo"):
        forced(d)


def test_hb_refuses_impact():
    d = copy.deepcopy(BASE)
    d["impact"] = [{"name": "stop", "body": "m", "stop": -1.0, "restitution": 0.8}]
    with pytest.raises(ModelError, match="shooting"):
        forced(d)


def test_steady_table_makes_forced_nonlinear():
    assert Study.parse(BASE).is_steady()
    assert not Study.parse({"body": [{"name": "m", "inertia": 1.0}]}).is_steady()
