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
    assert one.units == {"bending_moment": "N m", "shear_force": "N"}
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
    """Without reduction the drive's accelerations (the event solver's records) make M q'' + C q' + K q
    vanish at every free node that carries no element, so the section loads of the two elements there
    agree; the driver's reaction is minus the section torque at the root (docs/outputs.md)."""
    from fem.loads.drive import time_signals

    doc = tomllib.loads((EX / "hybrid_drill_string.toml").read_text())
    doc.pop("reduction")
    doc["simulation"]["t_end"] = 2.0
    study = Study.parse(doc)
    res = study.simulate()
    sig = time_signals(study, res)
    comp = res.compiled
    T, n = comp.T, comp.n_fe
    q, qd, qdd = T @ sig["x"][:n], T @ sig["v"][:n], T @ sig["a"][:n]
    s = study.fe_model.system
    r = s.K @ q + s.C @ qd + s.M @ qdd
    held = {0, s.dof_index(field="theta", x=1.0)}
    free = [i for i in range(s.n_dofs) if i not in held]
    assert np.abs(r[free]).max() <= 1e-12 * np.abs(s.K @ q).max()
    out = study.outputs(res)
    assert out.axis == "t" and out.axis_values.shape == res.solver.t.shape
    c = out.channels[out.names.index("driver[1] x=0 theta.reaction")]
    assert c.unit == "N m" and c.source == "driver"
    T_root = out.column("shaft.torque@x=0")
    R = out.column("driver[1] x=0 theta.reaction")
    assert np.allclose(R, -T_root, rtol=1e-9, atol=1e-9 * np.abs(T_root).max())
    # at the free inner nodes the two sides agree (no jump is reported there)
    assert not any(nm.endswith(("-", "+")) for nm in out.names if nm.startswith("shaft.torque@x=0.") and "@x=0.5" in nm)


def _run(tmp_path, command, name, *extra):
    from fem.app.cli import main

    out = tmp_path / "o.json"
    assert main([command, str(EX / name), "--json", str(out), *extra]) == 0
    return json.loads(out.read_text())


def _complex(v):
    return complex(v["re"], v["im"]) if isinstance(v, dict) else complex(v)


def test_modal_json_has_load_shapes_per_mode(tmp_path):
    d = _run(tmp_path, "modal", "cantilever_tip_mass.toml")
    s = d["named_outputs"]
    assert "section_loads" not in d and d["version"] == 2
    root = s["shaft.bending_moment@x=0"]
    assert root["quantity"] == "moment" and root["unit"] == "N m" and root["section_quantity"] == "bending_moment"
    assert len(root["modes"]) == d["n_modes"]
    assert any("mass-normalised" in n for n in d["named_outputs_notes"])
    # at the free end only the tip mass (11.56 kg) acts on the last element: V(L-) = m omega^2 w_tip per mode
    xs = d["mode_shapes"]["w"]["x"]
    tip = s["shaft.shear_force@x=1.5"]
    assert tip["side"] == "left"
    for r in range(d["n_modes"]):
        w_tip = d["mode_shapes"]["w"]["modes"][r][xs.index(max(xs))]
        V = tip["modes"][r]
        om = d["omega_rad_s_unverified"][r]
        assert abs(V - 11.56 * om ** 2 * w_tip) <= 1e-8 * abs(V)
    # the clamp's reactions balance the root section loads: R_w = -V(0), R_theta = -M(0)
    for r in range(d["n_modes"]):
        assert abs(s["support[1] x=0 w.reaction"]["modes"][r] + s["shaft.shear_force@x=0"]["modes"][r]) <= \
            1e-9 * abs(s["shaft.shear_force@x=0"]["modes"][r])


def test_forced_json_has_complex_loads_and_reactions_per_frequency(tmp_path):
    d = _run(tmp_path, "forced", "forced_torsion.toml")
    s = d["named_outputs"]
    nf = len(d["omega_rad_s"])
    root = s["shaft.torque@x=0"]
    assert root["x"] == 0.0 and len(root["response"]) == nf and set(root["response"][0]) == {"re", "im"}
    R = _complex(s["support[1] x=0.reaction"]["response"][0])
    assert abs(_complex(root["response"][0]) + R) <= 1e-9 * abs(R)        # the clamp carries the root torque
    assert abs(_complex(s["shaft.torque@x=1.2"]["response"][0]) - 100.0) < 1e-9   # the end torque


def test_rotor_forced_json_reports_bending_moments_and_bearing_forces(tmp_path):
    d = _run(tmp_path, "forced", "rotor_friswell_damped.toml")
    s = d["named_outputs"]
    qs = {o["section_quantity"] for o in s.values() if o["source"] == "section"}
    assert qs == {"bending_moment_y", "bending_moment_z", "shear_force_y", "shear_force_z"}
    assert s["bearing[1] x=0.force_y"]["unit"] == "N" and s["bearing[1] x=0.force_y"]["source"] == "bearing"


def test_fe_output_tables_pick_stations_sides_and_supports(tmp_path):
    """[[output]] in an FE file: a section load at x on one side of a jump, a support's reaction by name."""
    doc = tomllib.loads((EX / "cantilever_tip_mass.toml").read_text())
    doc["support"][0]["name"] = "clamp"
    doc["output"] = [{"name": "root moment", "x": 0.0, "quantity": "moment"},
                     {"x": 0.75, "quantity": "shear", "side": "left"},
                     {"support": "clamp", "quantity": "reaction"}]
    study = Study.parse(doc)
    res = study.modal(3)
    out = study.outputs(res)
    assert out.names == ["root moment", "shaft.shear_force@x=0.75-", "clamp w.reaction", "clamp w_x.reaction"]
    full = section_loads(study.fe_model, res.shapes, eigenvalue=1j * res.omega_rad_s, x=[0.0, 0.75], side="left")
    assert np.allclose(out.column("root moment"), full["bending_moment"][0], rtol=1e-12, atol=0)
    assert np.allclose(out.column("shaft.shear_force@x=0.75-"), full["shear_force"][1], rtol=1e-12, atol=0)
    doc["output"] = [{"support": "nowhere", "quantity": "reaction"}]
    with pytest.raises(ModelError, match="clamp"):
        Study.parse(doc).outputs(res)


def test_lumped_files_have_no_section_loads(tmp_path):
    d = _run(tmp_path, "modal", "two_mass_chain.toml")
    assert all(o["source"] != "section" for o in d["named_outputs"].values())


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
    assert d["quantities"] == ["torque"] and d["units"] == {"torque": "N m"}


# ------------------------------------------------------------------ balance over every FE and rotor example
def _examples_of(kind):
    out = []
    for p in sorted(EX.glob("*.toml")):
        d = tomllib.loads(p.read_text())
        k = "rotor" if "rotor" in d else ("fe" if "segment" in d else None)
        if k == "fe":
            k = Study.load(p).kind
        if k == kind:
            out.append(p.name)
    return out


def _rigid_fe(s, bending: bool):
    """Rigid motions of a shaft model's DOFs: translation (torsion, axial: the rotation/extension) and,
    bending, the rotation about x = 0 (w = x, slope 1)."""
    prim = s.dof_field == s.fields()[0] if not bending else np.isin(s.dof_field, ("w",))
    t = np.where(prim, 1.0, 0.0) if bending else np.ones(s.n_dofs)
    if not bending:
        return [("translation", t)]
    rot = np.where(prim, s.dof_x, 0.0) + np.where(~prim, 1.0, 0.0)
    return [("force", t), ("moment about x = 0", rot)]


def _fe_reaction_vector(s, out):
    """The reactions of the named outputs (channels of source "support") as a DOF vector per column."""
    R = np.zeros((s.n_dofs, out.axis_values.size), dtype=complex)
    for k, c in enumerate(out.channels):
        if c.source == "support":
            R[s.dof_index(field=c.info["dof"], x=c.info["x"])] += out.values[k]
    return R


@pytest.mark.parametrize("name", _examples_of("fe"))
def test_fe_examples_named_reactions_balance_inertia_and_loads(name):
    """Every FE example: its modes (and its forced response when the file asks for one) -- the support
    reactions of the named outputs plus the applied loads balance the inertia (and mass-proportional
    damping) forces of the whole shaft for every rigid motion, to round-off; the section loads of the named
    outputs are those of fem.loads.section_loads at their stations."""
    from fem.modelfile.build import linear as build_linear

    study = Study.load(EX / name)
    fe = study.fe_model
    s = fe.system
    bending = fe.model.physics == "bending"
    res = study.modal(4)
    out = study.outputs(res)
    R = _fe_reaction_vector(s, out)
    acc = -(res.omega_rad_s ** 2)[None, :] * res.shapes
    for label, r in _rigid_fe(s, bending):
        inert, ext = r @ (s.M @ acc), r @ R
        scale = max(np.abs(inert).max(), np.abs(ext).max(), 1e-300)
        if res.rigid.any():
            continue                    # free-free: no reactions, rigid modes have zero inertia force too
        assert np.abs(ext - inert).max() <= 1e-9 * scale, (name, label)
    lam = 1j * res.omega_rad_s
    for k, c in enumerate(out.channels):
        if c.source == "section":
            ref = section_loads(fe, res.shapes, eigenvalue=lam, x=[c.info["x"]], side=c.info["side"])
            v = ref[c.info["section_quantity"]][0]
            assert np.allclose(out.values[k], v, rtol=1e-12, atol=1e-12 * np.abs(v).max()), c.name
    an = study.analysis
    if getattr(an, "type", None) == "forced" and getattr(an, "period", None) is None:
        res = study.forced()
        out = study.outputs(res)
        spec = build_linear.forced_spec(study.doc, s)
        damping = build_linear.damping(study.doc.damping)
        if damping.type == "modal":         # no element form: the outputs say so, and balance up to it
            assert any("modal damping" in n for n in out.notes)
            return
        w = res.omega_rad_s
        F = spec.force[:, None] + (w ** 2)[None, :] * (spec.force_w2[:, None] if spec.force_w2 is not None else 0.0)
        Q = res.full.T
        alpha = damping.alpha if damping.type == "rayleigh" else 0.0
        acc = (-(w ** 2) + 1j * w * alpha)[None, :] * Q
        R = _fe_reaction_vector(s, out)
        for label, r in _rigid_fe(s, bending):
            inert, ext = r @ (s.M @ acc), r @ (F + R)
            scale = max(np.abs(inert).max(), np.abs(ext).max(), np.abs(r @ F).max())
            assert np.abs(ext - inert).max() <= 1e-9 * scale, (name, label)


@pytest.mark.parametrize("name", _examples_of("rotor"))
def test_rotor_examples_named_reactions_balance_inertia(name):
    """Every rotor example's complex modes at its analysis speed (and its unbalance response when it has
    one): the bearing, pedestal and support reactions of the named outputs (plus the unbalance forces)
    balance the inertia and gyroscopic forces of the whole rotor, forces along y and z and moments at
    x = 0, to round-off."""
    from fem.rotor.response import unbalance_load

    study = Study.load(EX / name)
    rs = study.rotor
    names = fem_bearing_names(rs)
    res = study.modal(4)
    speed = float(res.speed_rad_s)
    lam = np.asarray(res.eigenvalues)
    out = study.outputs(res)
    q = res.shapes
    inertia = rs.M @ (lam ** 2 * q) + speed * (rs.G @ (lam * q))
    _check_rotor_balance(rs, out, names, np.zeros_like(q), inertia, name + " modes")
    if getattr(study.doc, "unbalance_response", None) is not None and study.doc.unbalance:
        from fem.modelfile.build import rotor as build_rotor

        spec = build_rotor.response_spec(study.doc)
        res = study.forced()
        out = study.outputs(res)
        w = res.speeds_rad_s
        Q = res.response.T
        F = unbalance_load(rs, spec.unbalances)[:, None] * (w ** 2)[None, :]
        inertia = rs.M @ (-(w ** 2) * Q) + (rs.G @ (1j * w * Q)) * w
        _check_rotor_balance(rs, out, names, F, inertia, name + " unbalance response")


def fem_bearing_names(rs):
    from fem.loads.names import bearing_names

    return bearing_names(rs.rotor)


def _check_rotor_balance(rs, out, names, F, inertia, what):
    ext = np.asarray(F, dtype=complex).copy()
    nd = rs.node_dofs
    ped = {p.name: rs.node_x.size * len(rs.fields) + 2 * i for i, p in enumerate(rs.rotor.pedestals)}
    col = dict(zip(out.names, out.values))
    for b, n in zip(rs.rotor.bearings, names):
        if b.pedestal is None:                  # to ground: an external force on the shaft
            node = rs.node(b.x)
            ext[nd["v"][node]] += col[f"{n}.force_y"]
            ext[nd["w"][node]] += col[f"{n}.force_z"]
    for p in rs.rotor.pedestals:
        ext[ped[p.name]] += col[f"{p.name}.force_y"]
        ext[ped[p.name] + 1] += col[f"{p.name}.force_z"]
    for c in out.channels:
        if c.source == "support":
            ext[rs.dof(c.info["x"], c.info["dof"])] += col[c.name]
    for label, direction, rotation in (("force along y", "v", None), ("force along z", "w", None),
                                       ("moment about z", "v", "theta_z"), ("moment about y", "w", "theta_y")):
        r = np.zeros(rs.n_dofs)
        mask = np.isin(rs.dof_field, (direction, "pedestal_" + direction))
        r[mask] = rs.dof_x[mask] if rotation else 1.0
        if rotation:
            r[rs.dof_field == rotation] = 1.0 if rotation == "theta_z" else -1.0
        scale = max(np.abs(r @ inertia).max(), np.abs(r @ ext).max(), 1e-300)
        assert np.abs(r @ ext - r @ inertia).max() <= 1e-9 * scale, (what, label)


def test_rotor_output_tables_name_sections_and_bearings(tmp_path):
    """[[output]] in a rotor file: a bending moment just left of a disc (both planes, <name>.y/.z) and a
    bearing's reaction by its name, in the tables' order; the values are rotor_section_loads and
    rotor_reactions of the unbalance response; the CSV has their columns."""
    from fem.loads import rotor_reactions

    doc = tomllib.loads((EX / "rotor_friswell_damped.toml").read_text())
    doc["output"] = [{"name": "disc moment", "x": 0.5, "quantity": "moment", "side": "left"},
                     {"support": "bearing[2] x=1.5", "quantity": "reaction"}]
    study = Study.parse(doc)
    res = study.forced()
    out = study.outputs(res)
    assert out.names == ["disc moment.y", "disc moment.z", "bearing[2] x=1.5.force_y", "bearing[2] x=1.5.force_z"]
    w = res.speeds_rad_s
    ref = rotor_section_loads(study.rotor, res.response.T, omega=w, x=[0.5], side="left")
    assert np.allclose(out.column("disc moment.y"), ref["bending_moment_y"][0], rtol=1e-12, atol=0)
    R = rotor_reactions(study.rotor, res.response.T, omega=w)
    assert np.array_equal(out.column("bearing[2] x=1.5.force_z"), R["bearing 2@x=1.5:F_z"])
    doc["output"] = [{"x": 0.5, "quantity": "displacement"}]
    with pytest.raises(ModelError, match="probe"):
        Study.parse(doc).outputs(res)


def test_run_up_outputs_in_json_csv_and_h5(tmp_path):
    """A short run-up of rotor_rub_runup.toml through the command line: speed, probe orbits, the rub's
    normal force and the bearings' reactions as named outputs in the JSON, the CSV and --h5; the reaction
    of a linear bearing is -K d - C d' of the recorded motion."""
    import h5py
    import tomli_w

    from fem.app.cli import main

    doc = tomllib.loads((EX / "rotor_rub_runup.toml").read_text())
    doc["run_up"]["duration"] = 0.3
    f = tmp_path / "r.toml"
    f.write_text(tomli_w.dumps(doc))
    j, c, h = tmp_path / "r.json", tmp_path / "r.csv", tmp_path / "r.h5"
    assert main(["simulate", str(f), "--json", str(j), "--csv", str(c), "--h5", str(h)]) == 0
    d = json.loads(j.read_text())
    no = d["named_outputs"]
    assert {"speed", "disc 1.y", "seal at disc 2.normal_force", "bearing[1] x=0.force_y"} <= set(no)
    assert no["bearing[1] x=0.force_y"]["unit"] == "N" and no["bearing[1] x=0.force_y"]["source"] == "bearing"
    head = c.read_text().splitlines()[0].split(",")
    assert "bearing[2] x=1.5.force_z" in head and head[:2] == ["t", "speed_rad_s"]
    with h5py.File(h, "r") as hf:
        names = [n.decode() for n in hf["outputs/names"][()]]
        assert names == list(no)
    study = Study.load(f)
    res = study.run_up()
    out = study.outputs(res)
    rs = study.rotor
    b = rs.rotor.bearings[0]
    q = res.eta @ res.basis.T
    qd = res.eta_dot @ res.basis.T
    iv, iw = rs.dof(b.x, "v"), rs.dof(b.x, "w")
    tab = b.table()
    want = -(tab["kyy"][0] * q[:, iv] + tab["kyz"][0] * q[:, iw] + tab["cyy"][0] * qd[:, iv] + tab["cyz"][0] * qd[:, iw])
    assert np.allclose(out.column("bearing[1] x=0.force_y"), want, rtol=1e-12, atol=1e-12 * np.abs(want).max())


def test_rotor_modal_csv_has_complex_load_shapes(tmp_path):
    from fem.app.cli import main

    c = tmp_path / "m.csv"
    assert main(["modal", str(EX / "rotor_friswell_damped.toml"), "--json", str(tmp_path / "m.json"),
                 "--csv", str(c)]) == 0
    head = c.read_text().splitlines()[0].split(",")
    d = json.loads((tmp_path / "m.json").read_text())
    assert head[:3] == ["mode", "f_hz", "omega_rad_s"] and "bearing[1] x=0.force_y re" in head
    assert len(head) == 3 + 2 * len(d["named_outputs"])


def test_campbell_writes_the_reactions_of_every_tracked_mode(tmp_path):
    """drivefem campbell: the bearing reactions of each tracked mode over the speeds; at every speed they
    balance the mode's inertia and gyroscopic forces (forces along y and z) of the whole rotor."""
    from fem.app.cli import main

    j, c = tmp_path / "c.json", tmp_path / "c.csv"
    assert main(["campbell", str(EX / "rotor_friswell_damped.toml"), "--json", str(j), "--csv", str(c)]) == 0
    d = json.loads(j.read_text())
    rec = d["named_outputs"]["mode1 bearing[1] x=0.force_y"]
    assert len(rec["shape"]) == len(d["speeds_rad_s"]) and rec["source"] == "bearing"
    assert "mode1 bearing[1] x=0.force_y amplitude" in c.read_text().splitlines()[0]
    study = Study.load(EX / "rotor_friswell_damped.toml")
    camp = study.campbell()
    out = study.outputs(camp)
    rs = study.rotor
    names = fem_bearing_names(rs)
    for i in (0, camp.speeds_rad_s.size - 1):
        s, lam, phi = camp.speeds_rad_s[i], camp.eigenvalues[i], camp.shapes[i]
        inertia = rs.M @ (lam ** 2 * phi) + s * (rs.G @ (lam * phi))
        for m in range(camp.n_modes):
            for field, comp in (("v", "y"), ("w", "z")):
                r = np.zeros(rs.n_dofs)
                r[rs.node_dofs[field]] = 1.0
                ext = sum(out.column(f"mode{m + 1} {n}.force_{comp}")[i] for n in names)
                assert abs(ext - r @ inertia[:, m]) <= 1e-9 * max(abs(r @ inertia[:, m]), abs(ext)) + 1e-12
