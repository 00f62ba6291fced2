"""Geared multi-shaft trains (issue 26, docs/geared.md): validation group ``geared``."""
from __future__ import annotations

import json
import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from validation.analytic import geared as ref
from validation.examples import EXAMPLES
from validation.registry import case, check, claim

SRC_RED = "textbook §3.2 and §2.2 (digest textbook_ch2-5.md V2.2a, V3.2a): J u^2, c u^2"
ROSS_DATA = EXAMPLES.parent / "validation" / "data" / "ross" / "geared.json"


def _equivalent_shaft(u2: float, k_torsion: float):
    """The single shaft of examples/geared_two_shaft_torsion.toml reduced to the input by the ratio^2:
    input shaft as it is, a massless segment of torsional stiffness k_mesh r_b,a^2 (the mesh), the output
    shaft with G J u^2 and rho I_p u^2 (section constants scaled), its inertias times u^2."""
    from fem.assembly import assemble
    from fem.model import PointAttachment, Segment, ShaftModel, Support
    from fem.sections import Material, Section

    steel = Material(E=210e9, G=80e9, rho=7850.0)
    sec2 = Section.circle(0.08)
    ell = 0.1
    spring = Segment(ell, 1, Section.explicit(J=k_torsion * ell / steel.G), Material(E=210e9, G=80e9, rho=0.0))
    model = ShaftModel("torsion", [Segment(0.8, 8, Section.circle(0.05), steel), spring,
                                   Segment(1.2, 12, Section.explicit(J=sec2.J * u2, Ip=sec2.Ip * u2), steel)],
                       supports=[Support(0.0)],
                       points=[PointAttachment(0.8, inertia=0.02), PointAttachment(0.9, inertia=0.3 * u2),
                               PointAttachment(2.1, inertia=5.0 * u2)], order=1)
    return assemble(model), ell


@case("geared-two-shaft-equivalent", group="geared")
def two_shaft_equivalent():
    """(a) Two torsional shafts joined by a spur mesh (examples/geared_two_shaft_torsion.toml: clamped input
    shaft with a pinion, r_b = 0.05 / 0.15 m, mesh stiffness 2e8 N/m, output shaft with wheel and load)
    against the single shaft reduced to the input (textbook §3.2, §2.2: the output's inertias and
    stiffnesses times u^2, u = r_b,a / r_b,b; the mesh a torsional spring k r_b,a^2 between the pinion
    and the reduced wheel, here a massless segment of an FE model built independently of fem.train).

    Frequencies: the two are the same matrices up to the congruence theta_b = -u theta~, so the six lowest
    agree to the eigensolvers' round-off: tolerance 1e-10.  Loads: the train's static state and harmonic
    responses (fem.train.forced, the mesh force by the mesh's own law, the clamp's reaction) under a load
    torque T = -300 N m with a 50 N m ripple at the output's end, against the reduced shaft under -u T:
    mesh force x r_b,a = the spring segment's torque, clamp torques equal, load angle theta_b = -u theta~;
    at 60, 700 and 3000 rad/s (below, between and above modes): 1e-10."""
    from fem.study import Study
    from fem.train.forced import TrainLoad, train_forced

    study = Study.load(EXAMPLES / "geared_two_shaft_torsion.toml")
    ts = study.train
    mesh = ts.train.connections[0]
    (rba, rbb), _ = mesh.radii()
    u = rba / rbb
    fe, ell = _equivalent_shaft(u * u, mesh.stiffness * rba ** 2)
    from discrete.linear import modal_analysis

    out = []
    m_train = study.modal(6)
    m_ref = modal_analysis(fe.system, 6, tolerance=1e-12)
    for r in range(6):
        out.append(check(f"two-shaft train = reduced shaft: mode {r + 1}", SRC_RED, "omega (rad/s)",
                         m_ref.omega_rad_s[r], m_train.omega_damped_rad_s[r], 1e-10))
    T, ripple = -300.0, 50.0
    j_out = ts.dof("output", "theta", 1.2)
    sys_r = fe.system
    jr_load = sys_r.dof_index(field="theta", x=2.1)
    jr_a, jr_b = sys_r.dof_index(field="theta", x=0.8), sys_r.dof_index(field="theta", x=0.9)
    k_seg = mesh.stiffness * rba ** 2
    free = sys_r.free
    for w in (60.0, 700.0, 3000.0):
        res = train_forced(ts, [0.0], [TrainLoad(j_out, value=T, amplitude=ripple, omega=w, label="load")])
        c = res.mesh(mesh.name)
        # reduced shaft: static and harmonic solves under -u T, -u ripple
        rhs = np.zeros(sys_r.n_dofs)
        rhs[jr_load] = -u * T
        Kf = sp.csc_matrix(sys_r.free_block(sys_r.K))
        qs = sys_r.expand(spla.spsolve(Kf, rhs[free]))
        Z = sp.csc_matrix(sys_r.free_block(sys_r.K) - w * w * sys_r.free_block(sys_r.M))
        rhs_h = np.zeros(sys_r.n_dofs)
        rhs_h[jr_load] = -u * ripple
        qh = sys_r.expand(spla.spsolve(Z, rhs_h[free]))
        spring_s = k_seg * (qs[jr_a] - qs[jr_b])           # torque the spring carries (compression of the mesh)
        spring_h = k_seg * abs(qh[jr_a] - qh[jr_b])
        clamp = sys_r.constrained[0]
        R_s = float((sys_r.K @ qs)[clamp])
        R_h = abs(((sys_r.K - w * w * sys_r.M) @ qh)[clamp])
        tag = f"T = {T:g} N m + {ripple:g} sin({w:g} t)"
        out.append(check(f"static mesh force x r_b,a = spring torque ({tag})", SRC_RED, "N m", spring_s,
                         c.static * rba, 1e-10))
        out.append(check(f"mesh force amplitude x r_b,a ({tag})", SRC_RED, "N m", spring_h,
                         c.amplitude[0, 0] * rba, 1e-10))
        sup = next(iter(res.supports.values()))
        out.append(check(f"clamp torque, static ({tag})", SRC_RED, "N m", R_s, sup["static"], 1e-10))
        Qt = _harmonic_dof(ts, res, j_out, w, T, ripple)
        out.append(check(f"load angle amplitude theta_b = -u theta~ ({tag})", SRC_RED, "rad", u * abs(qh[jr_load]),
                         abs(Qt), 1e-10))
        out.append(check(f"clamp torque amplitude ({tag})", SRC_RED, "N m", R_h,
                         _harmonic_reaction(ts, w, j_out, ripple), 1e-10))
        out.append(check(f"force balance of every shaft ({tag})", "equilibrium of each shaft (fem.train.loads)",
                         "max relative residual", 0.0, res.balance_max, 1e-12, scale=1.0))
    return out


def _harmonic_dof(ts, res, j_out, w, T, ripple):
    """The train's complex amplitude at the load DOF (one harmonic solve, as fem.train.forced does)."""
    K, M = ts.stiffness(0.0), ts.M
    free = np.setdiff1d(np.arange(ts.n_dofs), ts.constrained)
    F = np.zeros(ts.n_dofs)
    F[j_out] = ripple
    Q = np.zeros(ts.n_dofs, complex)
    Q[free] = spla.spsolve(sp.csc_matrix((K - w * w * M)[free][:, free]), F[free])
    return Q[j_out]


def _harmonic_reaction(ts, w, j_out, ripple):
    from fem.train.forced import TrainLoad, train_forced

    res = train_forced(ts, [0.0], [TrainLoad(j_out, amplitude=ripple, omega=w)])
    # peak of a pure harmonic over its period = its amplitude
    return next(iter(res.supports.values()))["peak"][0]


# ----------------------------------------------------------------------------- (b) lateral-torsional
def _ross_spec():
    """The ROSS example's data as dicts for validation/analytic/geared.py (SI; drivefem axes)."""
    d = json.loads(ROSS_DATA.read_text())["model"]

    def shaft(R):
        sh = R["shaft"]
        xs = np.concatenate([[0.0], np.cumsum([e["L"] for e in sh])])
        n0 = min(e["n"] for e in sh)
        return dict(E=sh[0]["E"], G=sh[0]["G_s"], rho=sh[0]["rho"],
                    segments=[(e["L"], 1, e["odl"], e["idl"]) for e in sh],
                    discs=[(xs[c["n"] - n0], c["m"], c["Id"], c["Ip"]) for c in R["discs"]],
                    bearings=[(xs[b["n"] - n0], b["kxx"], b["kyy"], b["cxx"], b["cyy"]) for b in R["bearings"]])
    m = d["mesh"]
    mesh = dict(base_radius=(m["driving"]["base_radius"], m["driven"]["base_radius"]),
                pressure_angle=m["pressure_angle"], stiffness=m["stiffness"], x=(5.8, 0.0),
                ratio=-m["gear_ratio"], line_of_centres=0.0)
    return shaft(d["driving"]), shaft(d["driven"]), mesh


def _helical_train():
    """A helical, multi-element variant built with the Python API: the ROSS rotors refined (2-4 elements
    per segment, a bore in the turbine shaft), helix 15 deg (left hand), line of centres at 30 deg."""
    from fem.rotor.model import Bearing, Disc, Rotor, ShaftSegment
    from fem.sections import Material
    from fem.train import GearMesh, Port, Train, TrainShaft

    sa, sb, _ = _ross_spec()
    sa = dict(sa, segments=[(0.1, 1, 0.3, 0.0), (4.24, 3, 0.3, 0.0), (1.16, 2, 0.22, 0.0), (0.3, 1, 0.22, 0.0)])
    sb = dict(sb, segments=[(0.3, 1, 0.15, 0.0), (5.0, 4, 0.15, 0.03), (0.1, 1, 0.15, 0.0)])
    mesh = dict(base_radius=(0.5086, 0.03567), pressure_angle=math.radians(22.5), stiffness=1e8, x=(5.8, 0.0),
                helix_angle=math.radians(15.0), hand=-1, line_of_centres=math.radians(30.0))

    def rotor(s, name):
        mat = Material(E=s["E"], G=s["G"], rho=s["rho"])
        return Rotor([ShaftSegment(L, n, d, mat, di=di) for L, n, d, di in s["segments"]],
                     discs=[Disc(x, m, Id, Ip) for x, m, Id, Ip in s["discs"]],
                     bearings=[Bearing(x, kyy=a, kzz=b, cyy=c, czz=e) for x, a, b, c, e in s["bearings"]],
                     dofs="full", title=name)
    at = math.atan(math.tan(mesh["pressure_angle"]) / math.cos(mesh["helix_angle"]))
    rpa, rpb = (r / math.cos(at) for r in mesh["base_radius"])
    phi = mesh["line_of_centres"]
    pos = ((rpa + rpb) * math.cos(phi), (rpa + rpb) * math.sin(phi))
    gm = GearMesh("helical", (Port("a", 5.8), Port("b", 0.0)), stiffness=1e8, base_radius=mesh["base_radius"],
                  pressure_angle=mesh["pressure_angle"], helix_angle=mesh["helix_angle"], hand=-1)
    train = Train([TrainShaft("a", rotor(sa, "a")), TrainShaft("b", rotor(sb, "b"), position=pos)], [], [gm])
    return train, sa, sb, mesh


SRC_DENSE = ("independent dense assembly (validation/analytic/geared.py: Friswell et al. 2010 §5.4.3 closed-form "
             "Timoshenko elements, line of action in components) and dense eigenvalues")


@case("geared-lateral-torsional-dense", group="geared")
def lateral_torsional_dense():
    """(b) Lateral-torsional geared rotor trains against an independent dense assembly of the same matrices
    (validation/analytic/geared.py, written from Friswell et al. (2010) §5.4.3's closed-form Timoshenko
    matrices and the line of action in components, not from fem.rotor or fem.train): M, K, C and
    G = sum ratio_i G_i entry by entry, and the complex eigenvalues (dense shift-invert eig of the
    first-order form, an independent solver) at 0 and 300 rad/s.

    Models: examples/geared_ross_two_shaft.toml (ROSS's spur two-shaft example, one element per segment)
    and a helical variant (helix 15 deg, left hand, line of centres at 30 deg, 2-4 elements per segment,
    bored turbine shaft), which exercises the axial and tilt terms of the line of action.
    Tolerances: matrices 1e-13 of their largest entry (the same numbers summed in another order: measured
    2e-16); eigenvalues 1e-8 relative (the package's Arnoldi tolerance 1e-10 and the dense reference's
    round-off: measured 1e-10 .. 2e-10)."""
    from fem.study import Study
    from fem.train import assemble_train, train_modes

    out = []
    study = Study.load(EXAMPLES / "geared_ross_two_shaft.toml")
    sa, sb, mesh = _ross_spec()
    helical, ha, hb, hmesh = _helical_train()
    for tag, ts, A, B, msh in (("ROSS spur example", study.train, sa, sb, mesh),
                               ("helical variant", assemble_train(helical), ha, hb, hmesh)):
        msh = dict(msh, ratio=ts.ratios[ts.blocks[1].name])
        M, K, C, G = ref.dense_train(A, B, msh)
        for name, R, P in (("M", M, ts.M), ("K", K, ts.K0), ("C", C, ts.C0), ("G", G, ts.G)):
            err = float(np.abs(P.toarray() - R).max() / np.abs(R).max())
            out.append(check(f"{tag}: {name} entry by entry", SRC_DENSE, f"max |{name} - {name}_ref| / max |{name}_ref|",
                             0.0, err, 1e-13, scale=1.0))
        for speed in (0.0, 300.0):
            lam_r = ref.eigenvalues(M, K, C, G, speed)
            lam_r = lam_r[np.abs(lam_r) > 1e-6 * np.abs(lam_r).max()]
            m = train_modes(ts, speed, 16, tolerance=1e-10)
            lam = m.eigenvalues[~m.rigid]
            err = np.abs(lam - lam_r[:lam.size]) / np.abs(lam_r[:lam.size])
            out.append(check(f"{tag}: {lam.size} lowest eigenvalues at {speed:g} rad/s", SRC_DENSE,
                             "max |lam - lam_ref| / |lam_ref|", 0.0, float(err.max()), 1e-8, scale=1.0))
            n_rigid = int(m.rigid.sum())
            n_rigid_ref = int(np.sum(np.abs(ref.eigenvalues(M, K, C, G, speed)) <= 1e-6 * np.abs(lam_r).max())) // 2
            out.append(check(f"{tag}: rigid-body motions at {speed:g} rad/s", SRC_DENSE, "count", n_rigid_ref,
                             n_rigid, 0.0, scale=1.0))
    return out


@case("geared-lateral-torsional-ross", group="geared")
def lateral_torsional_ross():
    """(b) ROSS 2.3.0's MultiRotor/GearElement (ross.multi_rotor.two_shaft_rotor_example: Rao, Shiau & Chang,
    Mech. Mach. Theory 33 (1998) 761; stored by benchmarks/ross_geared_reference.py in ROSS's own
    environment, validation/data/ross/geared.json) against examples/geared_ross_two_shaft.toml: all
    complex eigenvalues (ROSS's dense run_modal, sparse = False; its six zero eigenvalues of the three
    rigid-body motions removed) at 0, 100, 250, 500 rad/s.

    The same model: Timoshenko shaft elements with Cowper's shear coefficient on both sides, discs and
    bearings as ROSS holds them, the mesh a spring k along the line of action (ROSS's coupling matrix
    after Stringer 2008 is k v v^T).  Conventions: ROSS's axes x, y, z are drivefem's y, z, x; ROSS writes
    the mesh deflection with -r_b,b theta_b where drivefem has + r_b,b theta_b (the same rigid rotation
    measured with the opposite sign on the driven shaft: a congruence with diag(+-1), the same
    eigenvalues); ROSS turns the driven rotor at its teeth ratio -328/23 while the base radii give
    -14.2585 (declared as speed_ratio in the example, which drivefem warns about).  For a helical mesh
    ROSS's direction vector (cos a cos b, sin a, sin a sin b) is not a unit vector, drivefem's line of
    action is; only the spur case is compared.  Tolerance 1e-8 (measured 1.6e-10 .. 8e-10: ROSS's dense
    eig limits it)."""
    from fem.study import Study
    from fem.train import train_modes

    data = json.loads(ROSS_DATA.read_text())
    ts = Study.load(EXAMPLES / "geared_ross_two_shaft.toml").train
    src = f"ROSS {data['provenance']['ross']} (stored, {data['provenance']['date']}): {data['provenance']['model']}"
    out = [claim("the speed ratio convention is stated", src, "warning names the declared teeth ratio",
                 any("declared speed_ratio" in w for w in ts.warnings))]
    for rec in data["modal"]:
        lam_r = np.asarray(rec["evalues_re"]) + 1j * np.asarray(rec["evalues_im"])
        lam_r = lam_r[lam_r.imag > 0]
        lam_r = lam_r[np.argsort(np.abs(lam_r))]
        m = train_modes(ts, rec["speed"], 24, tolerance=1e-10)
        lam = m.eigenvalues[~m.rigid]
        err = np.abs(lam - lam_r[:lam.size]) / np.abs(lam_r[:lam.size])
        out.append(check(f"ROSS two-shaft example: {lam.size} lowest eigenvalues at {rec['speed']:g} rad/s", src,
                         "max |lam - lam_ROSS| / |lam_ROSS|", 0.0, float(err.max()), 1e-8, scale=1.0))
    return out
