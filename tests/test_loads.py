"""fem.loads: element decomposition, recovery inside elements, the public API and its errors, hybrid time
histories, and the JSON key ``section_loads`` of the study's analyses (docs/loads.md)."""
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from discrete.errors import ModelError
from discrete.linear import harmonic_response
from fem import Material, PointAttachment, Section, Segment, ShaftModel, Support, assemble
from fem.loads import SectionLoads, elements_of, rotor_section_loads, section_loads, support_reactions
from fem.loads.elements import gauss
from fem.loads.motion import ElementDamping, motion
from fem.loads.recovery import _inside, end_forces, station_values
from fem.study import Study

EX = Path(__file__).resolve().parent.parent / "examples"
STEEL = Material(2.1e11, 8.1e10, 7850.0)
KINDS = [("torsion", "euler-bernoulli", 1, "consistent"), ("torsion", "euler-bernoulli", 2, "consistent"),
         ("axial", "euler-bernoulli", 2, "lumped"), ("bending", "euler-bernoulli", 2, "consistent"),
         ("bending", "euler-bernoulli", 2, "lumped"), ("bending", "timoshenko", 1, "consistent"),
         ("bending", "timoshenko", 2, "consistent")]


def _shaft(physics, theory, order, mass, n=5):
    segs = [Segment(0.6, n, Section.circle(0.05), STEEL, psi=0.1), Segment(0.8, n + 2, Section.circle(0.03), STEEL)]
    pts = [PointAttachment(0.6, mass=0.0 if physics == "torsion" else 2.0, inertia=0.0 if physics == "axial" else 0.01)]
    sup = [Support(0.0, "clamped"), Support(1.4, "spring", k=1e5, kr=10.0 if physics == "bending" else 0.0)]
    return assemble(ShaftModel(physics, segs, sup, pts, theory=theory, order=order, mass=mass))


def _harmonic(fe, omega=700.0):
    s = fe.system
    F = np.zeros(s.n_dofs, complex)
    F[s.dof_index(field=fe.model.fields[0], x=1.4)] = 30.0
    return harmonic_response(s, [omega], force=F).full[0], F, omega


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: "-".join(map(str, k)))
def test_elements_sum_to_the_assembled_matrices_and_their_densities_to_the_mass(kind):
    fe = _shaft(*kind)
    es = elements_of(fe)
    s = fe.system
    nodal_K = (s.K - es.assembled(es.K)).toarray()
    assert np.abs(nodal_K - np.diag(np.diag(nodal_K))).max() <= 1e-12 * abs(s.K).max()   # springs only
    assert np.abs(s.H - es.assembled(es.H)).max() <= 1e-12 * abs(s.H).max()
    if es.M is None:                     # lumped: the inertia belongs to the nodes
        assert not es.terms
        return
    nodal_M = (s.M - es.assembled(es.M)).toarray()
    assert np.count_nonzero(np.abs(nodal_M) > 1e-12 * abs(s.M).max()) <= 2     # the point mass and inertia
    g, w = gauss(8)
    el = np.arange(es.n_elements)
    t = np.repeat(g[None], el.size, 0)
    Mt = sum(np.einsum("sn,sni,snj->sij", term.weight(el, t) * w[None] * es.length[:, None], term.row_shape(el, t),
                       term.shape(el, t)) for term in es.terms)
    assert np.abs(Mt - es.M).max() <= 1e-11 * np.abs(es.M).max()


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: "-".join(map(str, k)))
def test_equilibrium_inside_an_element_reaches_its_right_end_force(kind):
    fe = _shaft(*kind)
    es = elements_of(fe)
    Q, _, omega = _harmonic(fe)
    mo = motion(es.n_dofs, Q, omega=omega)
    dmp = ElementDamping(alpha=3.0, beta=1e-5)
    f = end_forces(es, mo, dmp)
    el = np.arange(es.n_elements)
    side = np.array(["left"] * el.size, dtype=object)
    inside = _inside(es, f, mo, dmp, el, np.ones(el.size), side, 0.0, None)
    ends = station_values(es, f, mo, dmp, el, np.ones(el.size), side)
    for name in es.quantities:
        assert np.abs(inside[name] - ends[name]).max() <= 1e-11 * np.abs(ends[name]).max()


def test_rotor_elements_inertia_gyroscopic_and_gravity_are_consistent():
    rs = Study.load(EX / "rotor_friswell_damped.toml").rotor
    es = elements_of(rs)
    for A, B in ((es.K, rs.K0), (es.M, rs.M), (es.G, rs.G)):
        D = (B - es.assembled(A)).tocoo()
        big = np.abs(D.data) > 1e-12 * abs(B).max()
        node = np.searchsorted(np.arange(rs.node_x.size) * len(rs.fields), D.row[big], side="right")
        node_c = np.searchsorted(np.arange(rs.node_x.size) * len(rs.fields), D.col[big], side="right")
        assert np.all(node == node_c)          # discs and bearings act within a node
    g, w = gauss(8)
    el = np.arange(es.n_elements)
    t = np.repeat(g[None], el.size, 0)
    for source, ref in (("inertia", es.M), ("gyroscopic", es.G)):
        got = sum(np.einsum("sn,sni,snj->sij", term.weight(el, t) * w[None] * es.length[:, None], term.row_shape(el, t),
                            term.shape(el, t)) for term in es.terms if term.source == source)
        assert np.abs(got - ref).max() <= 1e-12 * np.abs(ref).max()
    # gravity: the element loads equal the integral of the load densities
    for term in es.load_terms:
        dens = np.einsum("sn,sn->s", term.weight(el, t), w[None] * es.length[:, None])
        total = es.applied[:, [k for k, r in enumerate(es.roles) if r == (term.kind, term.axis)], term.axis].sum(axis=1)
        assert np.allclose(dens, total, rtol=1e-12)


def test_rotor_interior_with_gyroscopic_moments_and_gravity_reaches_the_right_end():
    study = Study.load(EX / "rotor_friswell_damped.toml")
    rs = study.rotor
    modes = study.modal(4)
    es = elements_of(rs)
    lam = modes.eigenvalues
    mo = motion(es.n_dofs, modes.shapes, eigenvalue=lam)
    speed = 3000.0
    f = end_forces(es, mo, ElementDamping(), speed=speed, load=np.array([0.0, 1.0, -9.81]))
    el = np.arange(es.n_elements)
    side = np.array(["left"] * el.size, dtype=object)
    inside = _inside(es, f, mo, ElementDamping(), el, np.ones(el.size), side, speed, np.array([0.0, 1.0, -9.81]))
    ends = station_values(es, f, mo, ElementDamping(), el, np.ones(el.size), side)
    for name in es.quantities:
        assert np.abs(inside[name] - ends[name]).max() <= 1e-11 * np.abs(ends[name]).max(), name


def test_public_api_shapes_units_sides_and_dict():
    fe = _shaft("bending", "euler-bernoulli", 2, "consistent")
    Q, F, omega = _harmonic(fe)
    one = section_loads(fe, Q, omega=omega)
    assert isinstance(one, SectionLoads) and one.kind == "harmonic"
    n_el = fe.mesh.n_elements
    assert one.x.shape == (2 * n_el,) and one["bending_moment"].shape == (2 * n_el,)
    assert one.units == {"bending_moment": "N·m", "shear_force": "N"}
    assert list(one.side[:2]) == ["right", "left"]
    many = section_loads(fe, np.column_stack([Q, 2 * Q]), omega=[omega, omega], x=[0.3, 0.6, 0.6])
    assert many["shear_force"].shape == (3, 2)
    assert np.allclose(many["shear_force"][:, 1], 2 * many["shear_force"][:, 0])
    left = section_loads(fe, Q, omega=omega, x=0.6, side="left")
    assert left.side[0] == "left" and many.side[1] == "right"
    assert abs(left["shear_force"][0] - many["shear_force"][1, 0]) > 1e-3       # the point mass is at 0.6
    d = one.to_dict()
    assert set(d) >= {"x", "side", "kind", "quantities", "units", "values", "omega_rad_s", "notes"}
    static = section_loads(fe, Q.real)
    assert static.kind == "static" and static.parameter is None
    R = support_reactions(fe, Q, omega=omega, force=F)
    assert set(R) == {"w@x=0", "w_x@x=0", "spring:w@x=1.4", "spring:w_x@x=1.4"}


@pytest.mark.parametrize("kwargs,key", [(dict(q=np.zeros(3)), "q"), (dict(q="x"), "q"),
                                        (dict(omega=1.0, eigenvalue=1j), "eigenvalue"),
                                        (dict(omega=1.0, qd=0), "qd"), (dict(omega=-1.0), "omega"),
                                        (dict(x=5.0), "x"), (dict(x=0.5, side="up"), "side"),
                                        (dict(speed=10.0), "speed"), (dict(omega=[1.0, 2.0, 3.0]), "omega"),
                                        (dict(x="middle"), "x")])
def test_bad_arguments_are_model_errors_naming_the_key(kwargs, key):
    fe = _shaft("torsion", "euler-bernoulli", 1, "consistent")
    q = kwargs.pop("q", np.zeros(fe.system.n_dofs))
    with pytest.raises(ModelError) as err:
        section_loads(fe, q, **kwargs)
    assert err.value.key == key


@pytest.mark.parametrize("kwargs,key", [(dict(speed="fast"), "speed"), (dict(speed=-1.0), "speed"),
                                        (dict(gravity=(0, "down")), "gravity"), (dict(gravity=(0, 0)), "gravity")])
def test_bad_rotor_arguments_are_model_errors(kwargs, key):
    rs = Study.load(EX / "rotor_friswell_damped.toml").rotor
    with pytest.raises(ModelError) as err:
        rotor_section_loads(rs, np.zeros(rs.n_dofs), **kwargs)
    assert err.value.key == key


def test_section_loads_of_a_non_model_is_refused():
    with pytest.raises(ModelError):
        section_loads("shaft", np.zeros(3))
    with pytest.raises(ModelError):
        rotor_section_loads(assemble(ShaftModel("torsion", [Segment(1, 2, Section.circle(0.1), STEEL)])), np.zeros(3))


def test_hybrid_time_history_accelerations_satisfy_the_full_equations():
    """Without reduction the recovered accelerations make M q'' + C q' + K q vanish at every free node
    that carries no element, so the section loads of the two elements there agree."""
    from fem.loads.study import hybrid_states

    doc = tomllib.loads((EX / "hybrid_drill_string.toml").read_text())
    doc.pop("reduction")
    doc["simulation"]["t_end"] = 2.0
    study = Study.parse(doc)
    res = study.simulate()
    q, qd, qdd = hybrid_states(study, res)
    s = study.fe_model.system
    r = s.K @ q + s.C @ qd + s.M @ qdd
    held = {0, s.dof_index(field="theta", x=1.0)}
    free = [i for i in range(s.n_dofs) if i not in held]
    assert np.abs(r[free]).max() <= 1e-12 * np.abs(s.K @ q).max()
    loads = study.loads(res)
    assert loads.section.kind == "time" and loads.t.shape == res.t.shape
    assert "driver theta@x=0" in loads.reactions
    d = loads.to_dict()
    assert d["reactions"]["units"][d["reactions"]["labels"].index("driver theta@x=0")] == "N·m"
    T_root = loads.section["torque"][0]
    assert np.allclose(loads.reactions["driver theta@x=0"], -T_root, rtol=1e-9, atol=1e-9 * np.abs(T_root).max())


def _run(tmp_path, command, name):
    from fem.app.cli import main

    out = tmp_path / "o.json"
    assert main([command, str(EX / name), "--json", str(out)]) == 0
    return json.loads(out.read_text())


def test_modal_json_has_load_shapes_per_mode(tmp_path):
    d = _run(tmp_path, "modal", "cantilever_tip_mass.toml")
    s = d["section_loads"]
    assert s["kind"] == "modal" and s["quantities"] == ["bending_moment", "shear_force"]
    assert np.array(s["values"]["bending_moment"]).shape == (len(s["x"]), d["n_modes"])
    assert np.allclose(s["omega_rad_s"], d["omega_rad_s_unverified"]) and "eigenvalues" not in s
    assert "mass-normalised" in s["normalisation"]
    # at the free end only the tip mass (11.56 kg) acts on the last element: V(L-) = m omega^2 w_tip per mode
    xs = d["mode_shapes"]["w"]["x"]
    for r in range(d["n_modes"]):
        w_tip = d["mode_shapes"]["w"]["modes"][r][xs.index(max(xs))]
        V = s["values"]["shear_force"][-1][r]
        assert s["side"][-1] == "left" and abs(V - 11.56 * s["omega_rad_s"][r] ** 2 * w_tip) <= 1e-8 * abs(V)


def test_forced_json_has_complex_loads_and_reactions_per_frequency(tmp_path):
    d = _run(tmp_path, "forced", "forced_torsion.toml")
    s = d["section_loads"]
    assert s["kind"] == "harmonic" and s["quantities"] == ["torque"] and s["x"][0] == 0.0
    nf = len(d["omega_rad_s"])
    v = s["values"]["torque"]
    assert len(v[0]) == nf and set(v[0][0]) == {"re", "im"}
    root = complex(v[0][0]["re"], v[0][0]["im"])
    R = s["reactions"]["values"][s["reactions"]["labels"].index("theta@x=0")][0]
    assert abs(root + complex(R["re"], R["im"])) <= 1e-9 * abs(root)         # the clamp carries the root torque
    assert s["x"][-1] == 1.2 and abs(complex(v[-1][0]["re"], v[-1][0]["im"]) - 100.0) < 1e-9   # the end torque


def test_rotor_forced_json_reports_bending_moments_and_bearing_forces(tmp_path):
    d = _run(tmp_path, "forced", "rotor_friswell_damped.toml")
    s = d["section_loads"]
    assert s["quantities"] == ["bending_moment_y", "bending_moment_z", "shear_force_y", "shear_force_z"]
    assert "bearing 1@x=0:F_y" in s["reactions"]["labels"] and s["reactions"]["units"][0] == "N"


def test_lumped_files_have_no_section_loads(tmp_path):
    assert "section_loads" not in _run(tmp_path, "modal", "two_mass_chain.toml")


def test_api_example_matches_the_exact_wave_solution(tmp_path):
    """examples/api_section_loads.py: torque of the P2 model (h = 2.5 cm) against the exact wave solution per
    segment (validation/analytic/loads.py): P2 error ~ (k h)^4, measured 3e-9; the clamp takes -T(0)."""
    import importlib.util
    import sys

    from validation.analytic.loads import stepped_torsion_torque

    spec = importlib.util.spec_from_file_location("example_api_section_loads", EX / "api_section_loads.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    torque, reaction = mod.main(tmp_path / "loads.json")
    s1, s2 = Section.circle(0.05), Section.circle(0.03)
    segs = [(0.6, mod.STEEL.G * s1.J, mod.STEEL.rho * s1.Ip), (0.9, mod.ALUMINIUM.G * s2.J, mod.ALUMINIUM.rho * s2.Ip)]
    left, right = stepped_torsion_torque(segs, {0.6: mod.DISC_INERTIA}, mod.END_TORQUE, mod.OMEGA, mod.STATIONS)
    exact = np.where(np.array(mod.SIDES) == "left", left, right)
    assert np.abs(torque - exact).max() <= 2e-8 * np.abs(exact).max()
    assert abs(reaction + torque[0]) <= 1e-10 * abs(torque[0])
    d = json.loads((tmp_path / "loads.json").read_text())
    assert d["quantities"] == ["torque"] and d["units"] == {"torque": "N·m"}
