"""Bad hybrid input: clear errors naming the key, its value and what is allowed."""
import pytest

from discrete.errors import ModelError
from fem.study import Study, simulate


def shaft_doc():
    return {"material": {"E": 130.0, "G": 50.0, "rho": 0.02}, "model": {"physics": "torsion"},
            "segment": [{"length": 1.0, "elements": 4, "section": {"A": 1.0, "I": 0.5, "J": 1.0}}],
            "point": [{"x": 1.0, "inertia": 2.0}], "driver": [{"x": 0.0, "velocity": 0.45}],
            "friction": [{"name": "bit", "x": 1.0, "kinetic": 3.0, "static": 18.0}],
            "reduction": {"modes": 2}, "simulation": {"t_end": 1.0}}


def _err(doc):
    with pytest.raises(ModelError) as exc:
        Study.parse(doc).compiled
    return str(exc.value)


def test_element_outside_the_model():
    d = shaft_doc()
    d["friction"][0]["x"] = 1.5
    msg = _err(d)
    assert "x = 1.5" in msg and "0 <= x <= 1" in msg


def test_element_between_nodes():
    d = shaft_doc()
    d["friction"][0]["x"] = 0.3
    assert "nearest node" in _err(d)


def test_dof_the_physics_does_not_have():
    d = shaft_doc()
    d["friction"][0]["dof"] = "w"
    msg = _err(d)
    assert "dof = 'w'" in msg and "'theta'" in msg


def test_more_modes_than_dofs():
    d = shaft_doc()
    d["reduction"]["modes"] = 50
    msg = _err(d)
    assert "modes = 50" in msg and "at most" in msg


def test_element_on_a_held_dof_would_never_act():
    d = shaft_doc()
    d["friction"][0]["x"] = 0.0          # the driven top
    assert "never act" in _err(d)


def test_contradictory_supports():
    d = shaft_doc()
    d["support"] = [{"x": 1.0, "type": "clamped"}, {"x": 1.0, "type": "spring", "k": 10.0}]
    assert "contradictory" in _err(d)


def test_driver_on_a_supported_dof():
    d = shaft_doc()
    d["support"] = [{"x": 0.0, "type": "clamped"}]
    msg = _err(d)
    assert "[[driver]]" in msg and "support" in msg


def test_unknown_keys_are_errors():
    d = shaft_doc()
    d["friction"][0]["kinetik"] = 1.0
    assert "kinetik" in _err(d)
    d = shaft_doc()
    d["reduction"]["mode"] = 3
    assert "mode" in _err(d)


def test_bad_reduction_values():
    for key, val in (("modes", 0), ("static_correction", "yes"), ("threshold", 1.5)):
        d = shaft_doc()
        d["reduction"][key] = val
        assert key in _err(d)


def test_moreau_needs_dt_and_rejects_gaps():
    d = shaft_doc()
    d["simulation"]["method"] = "moreau"
    assert "dt" in _err(d)
    d["simulation"]["dt"] = 1e-3
    d["gap"] = [{"x": 1.0, "k": 10.0, "delta": 0.1, "law": "arctan"}]
    with pytest.raises(ModelError, match="event"):
        simulate(d)


def test_distributed_friction_range_and_keys():
    d = shaft_doc()
    d["distributed_friction"] = [{"intensity": 1.0, "mu": 0.3}]
    assert "either intensity" in _err(d)
    d = shaft_doc()
    d["distributed_friction"] = [{"mu": 0.3}]
    assert "radius" in _err(d)
    d = shaft_doc()
    d["distributed_friction"] = [{"intensity": 1.0, "from": 0.1}]
    assert "node" in _err(d)


def test_low_restitution_is_a_warning_in_the_result():
    d = shaft_doc()
    d.pop("driver")
    d["support"] = [{"x": 0.0, "type": "clamped"}]
    d["point"][0]["inertia"] = 0.01
    d["segment"][0]["elements"] = 20
    d["friction"][0]["static"] = 3.0
    d["force"] = [{"x": 1.0, "value": 1.0}]
    d["reduction"] = {"modes": 1, "static_correction": False, "threshold": 0.99}
    d["simulation"]["t_end"] = 0.05
    r = simulate(d)
    assert any("restores only" in w for w in r.warnings)
    assert any("restores only" in w for w in r.to_dict()["warnings"])
