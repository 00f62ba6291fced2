"""Hybrid problem building: full and reduced systems, element vectors, drivers, tributary weights,
floating-structure restitution, result contract and outputs."""
import json
import math

import numpy as np
import pytest

from fem.hybrid import compile_hybrid, tributary_weights
from fem.modelfile.schema.document import detect_kind
from fem.output import columns
from fem.output.figures import plot_hybrid
from fem.study import Study, simulate


def is_hybrid(doc):
    return detect_kind(doc) == "hybrid"


def parse_hybrid(doc):
    study = Study.parse(doc)
    return study.hybrid, study.simulation_settings()
from discrete.linear.reduction import elastic_flexibility


def bar_doc(n=10, modes=6, **extra):
    d = {"title": "bar", "material": {"E": 2e11, "G": 8e10, "rho": 8000.0},
         "model": {"physics": "axial", "order": 1, "mass": "lumped"},
         "segment": [{"length": 1.0, "elements": n, "section": {"A": 1e-4, "I": 1e-9, "J": 2e-9}}],
         "impact": [{"name": "wall", "x": 1.0, "side": "upper", "stop": 1e-5, "restitution": 0.0}],
         "initial": {"velocity": 1.0}, "reduction": {"modes": modes}, "simulation": {"t_end": 6e-4}}
    d.update(extra)
    return d


def test_is_hybrid():
    assert is_hybrid(bar_doc())
    plain = {k: v for k, v in bar_doc().items() if k in ("material", "model", "segment")}
    assert not is_hybrid(plain)
    assert not is_hybrid({"body": [{"name": "a", "inertia": 1.0}], "simulation": {"t_end": 1.0}})
    import glob, tomllib
    for p in glob.glob(str(__import__("pathlib").Path(__file__).parents[1] / "examples" / "*.toml")):
        with open(p, "rb") as fh:
            assert is_hybrid(tomllib.load(fh)) == ("hybrid_" in p), p


def test_reduced_element_vector_is_a_unit_vector_on_the_kept_coupling_dof():
    model, _ = parse_hybrid(bar_doc())
    comp = compile_hybrid(model)
    g = comp.elements[0].g
    assert np.count_nonzero(g) == 1 and abs(abs(g).max() - 1.0) < 1e-15
    k = int(np.flatnonzero(g)[0])
    j = model.fe.system.dof_index(field="u", x=1.0)
    # the kept DOF expands to the FE DOF at the wall
    e = np.zeros(comp.system.n_dofs)
    e[k] = 1.0
    assert comp.field(e[:, None])[0, j] == pytest.approx(1.0)
    # floating bar: Ritz approximation of the elastic (inertia-relief) flexibility, exact as modes grow
    assert comp.restitution_report["restitution"][0] == pytest.approx(1.0, abs=1e-3)


def test_full_and_reduced_give_the_same_element_coordinate():
    """s = g . q must be the same physical quantity: g_red = T^T g_full."""
    m_full, _ = parse_hybrid({k: v for k, v in bar_doc().items() if k != "reduction"})
    m_red, _ = parse_hybrid(bar_doc(modes=4))
    cf, cr = compile_hybrid(m_full), compile_hybrid(m_red)
    z = np.random.default_rng(1).normal(size=cr.system.n_dofs)
    q = cr.field(z[:, None])[0]
    assert cr.elements[0].g @ z == pytest.approx(cf.elements[0].g @ q, rel=1e-12)


def test_floating_bar_elastic_flexibility_is_L_over_3EA():
    """Free-free bar, unit end force balanced by inertia relief: sum over elastic modes of
    phi(L)^2/lambda = 2L/(EA pi^2) sum 1/n^2 = L/(3EA)."""
    model, _ = parse_hybrid(bar_doc(n=200))
    s = model.fe.system
    R = np.ones((s.n_dofs, 1))
    j = s.dof_index(field="u", x=1.0)
    flex = elastic_flexibility(s.K, s.M, R, np.array([j]))[0]
    assert flex == pytest.approx(1.0 / (3 * 2e11 * 1e-4), rel=1e-4)


def test_free_interface_basis_warns_on_low_restitution():
    d = bar_doc(n=20)
    d["reduction"] = {"modes": 1, "static_correction": False}
    comp = compile_hybrid(parse_hybrid(d)[0])
    r = comp.restitution_report["restitution"][0]
    # one elastic mode carries 6/pi^2 of the elastic flexibility L/(3EA) (first term of sum 1/n^2)
    assert r == pytest.approx(6 / math.pi ** 2, rel=5e-3)   # FE (20 lumped P1) error O((pi h/L)^2)
    assert any("restores only" in w for w in comp.warnings)


def test_driver_dof_stays_a_driver_in_the_reduced_system():
    d = {"material": {"E": 130.0, "G": 50.0, "rho": 0.02}, "model": {"physics": "torsion"},
         "segment": [{"length": 1.0, "elements": 6, "section": {"A": 1.0, "I": 0.5, "J": 1.0}}],
         "point": [{"x": 1.0, "inertia": 2.0}], "driver": [{"x": 0.0, "velocity": 0.45}],
         "friction": [{"x": 1.0, "kinetic": 3.0, "static": 18.0, "restick": "kinetic"}],
         "reduction": {"modes": 2}, "simulation": {"t_end": 1.0}}
    comp = compile_hybrid(parse_hybrid(d)[0])
    (k, law), = comp.drivers.items()
    assert k in comp.system.constrained and law.velocity == 0.45
    e = np.zeros(comp.system.n_dofs)
    e[k] = 1.0
    fld = comp.field(e[:, None])[0]
    # the constraint mode of the driven top with the bit DOF held: the static twist 1 - x/L
    assert np.allclose(fld, 1.0 - parse_hybrid(d)[0].fe.system.dof_x / 1.0)


@pytest.mark.parametrize("physics, order, expected", [
    ("axial", 1, lambda h: [h / 2] + [h] * 9 + [h / 2]),
    ("axial", 2, None), ("bending", None, None)])
def test_tributary_weights_sum_to_length(physics, order, expected):
    d = {"material": {"E": 2e11, "G": 8e10, "rho": 8000.0}, "model": {"physics": physics},
         "segment": [{"length": 2.0, "elements": 10, "section": {"shape": "circle", "d": 0.02}}]}
    if order:
        d["model"]["order"] = order
    from fem.assembly import assemble
    fe = assemble(Study.parse(d).shaft)
    fld = "u" if physics == "axial" else "w"
    idx, w = tributary_weights(fe, fld, 0.0, 2.0)
    assert w.sum() == pytest.approx(2.0, rel=1e-12)
    if expected:
        order_ = np.argsort(fe.system.dof_x[idx])
        assert np.allclose(w[order_], expected(0.2))
    if order == 2:   # Simpson: vertex h/3 (h/6 + h/6), mid-side 2h/3
        x = fe.system.dof_x[idx]
        mid = np.isclose((x / 0.2) % 1, 0.5)
        assert np.allclose(w[mid], 2 * 0.2 / 3)


def test_run_contract_csv_and_plots(tmp_path):
    r = simulate(bar_doc())
    d = r.to_dict()
    json.dumps(d)
    for key in ("t_end", "events", "period", "energy_error", "reduction", "warnings"):
        assert key in d
    ev = d["events"][0]
    assert set(ev) == {"t", "kind", "element", "state"} and ev["kind"] == "impact"
    assert ev["t"] == pytest.approx(1e-5, rel=1e-9)
    assert "restitution" in d["reduction"] and "suggested_time_step_s" in d["reduction"]
    assert r.field_history.shape == (r.t.size, r.fe.system.n_dofs)
    # the field history is a rigid translation before the impact
    k = np.searchsorted(r.t, 5e-6)
    assert np.allclose(r.field_history[k], r.t[k] * 1.0, rtol=1e-9)
    p = tmp_path / "bar.csv"
    columns.write(p, columns.hybrid(r))
    head = p.read_text().splitlines()[0].split(",")
    assert head[0] == "t" and len(head) == 1 + r.fe.system.n_dofs
    paths = plot_hybrid(r, tmp_path / "png")
    assert all(q.exists() and q.stat().st_size > 1000 for q in paths)


def test_python_api_with_bodies_and_springs():
    """A lumped body attached to the bar tip by a spring: the body's DOF follows the FE model."""
    d = bar_doc(n=6, reduction={"modes": 3})
    d.pop("impact")
    d.pop("initial")
    d["support"] = [{"x": 0.0, "type": "clamped"}]
    d["body"] = [{"name": "m", "inertia": 1.0, "v0": 1.0}]
    d["spring"] = [{"between": [{"x": 1.0}, "m"], "k": 1e4}]
    d["friction"] = [{"body": "m", "kinetic": 0.5}]
    d["simulation"] = {"t_end": 0.05}
    r = simulate(d)
    assert "m" in r.solver.names
    assert r.energy_error < 1e-7
    assert any(e.element == "friction1" for e in r.events)
