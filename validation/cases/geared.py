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


# ----------------------------------------------------------------------------- (d) backlash oscillator
SRC_KS = ("Kahraman & Singh, J. Sound Vib. 142 (1990) 49: the piecewise-linear gear-pair oscillator; exact "
          "periodic solutions by closed forms matched at the backlash boundaries (validation/analytic/backlash.py)")


def _ks(study):
    """The dimensionless oscillator of a two-body train with one mesh (examples/geared_rattle.toml):
    (oscillator, omega_n, b, m_e, mesh element name)."""
    from validation.analytic.backlash import Oscillator

    ts = study.train
    mesh = ts.train.connections[0]
    (ra, rb), _ = mesh.radii()
    Ia, Ib = (bd.inertia for bd in ts.train.bodies)
    me = 1.0 / (ra * ra / Ia + rb * rb / Ib)
    k, c, b = mesh.stiffness, mesh.damping, 0.5 * mesh.backlash
    f = study.doc.force[0]
    Fm, Fa = me * ra * f.value / Ia, me * ra * f.amplitude / Ia
    wn = math.sqrt(k / me)
    return Oscillator(zeta=c / (2 * math.sqrt(k * me)), b=1.0, Fm=Fm / (k * b), Fa=Fa / (k * b)), wn, b, mesh.name


def ks_reference(osc):
    """The exact jump frequencies and orbits: (fold_down, fold_up, grazing, {Omega: (branch, pattern, u)})."""
    pat, u9 = osc.orbit_from_integration(0.9)
    u8 = osc.continue_to(0.9, u9, pat, 0.8, step=0.001)
    f_down, _ = osc.fold(0.8, u8, pat, "min")
    # the middle branch: from the upper branch at 0.8 along the first segment's duration (in small steps,
    # through the fold), then its maximum near grazing
    d8, guess = u8[1] - u8[0], (u8, 0.8)
    for fct in np.linspace(1.02, 1.5, 25):
        Om, uu = osc.at_duration(d8 * fct, guess, pat)
        guess = (uu, Om)
    f_up, _ = osc.fold(guess[1], guess[0], pat, "max")
    orbits = {0.85: ("upper", pat, osc.continue_to(0.9, u9, pat, 0.85, step=0.001))}
    u, w = u9, 0.9
    for Om in (0.95, 1.0, 1.05):
        u = osc.continue_to(w, u, pat, Om, step=0.001)
        w = Om
        orbits[Om] = ("upper", pat, u)
    return f_down, f_up, osc.grazing_frequencies(0.5, 1.5), orbits


@case("geared-backlash-kahraman-singh", group="geared", slow=True)
def backlash_kahraman_singh():
    """(d) Kahraman & Singh's piecewise-linear gear-pair oscillator (J. Sound Vib. 142 (1990) 49) as a train:
    examples/geared_rattle.toml (two gears on bodies, one mesh with backlash 2b, damping always acting,
    mean torque and a torque ripple on the pinion), in K&S's dimensionless form x'' + 2 zeta x' + f(x) =
    F_m + F_a cos(Omega t) with zeta = 0.05, F_m = 0.1, F_a = 0.02 (x: mesh deflection / b, Omega in
    omega_n = sqrt(k / m_e), m_e = 1/(r_a^2/I_a + r_b^2/I_b)).  The free rotation of the pair is eliminated
    exactly (zero total momentum), the mesh deflection is the coordinate of the mesh element.

    Reference (validation/analytic/backlash.py): the exact periodic orbits (closed forms per linear
    segment, matched at x = b), their exact Floquet multipliers (products of the segments' transition
    matrices: the force is continuous, no saltation), and the jump frequencies: the fold of the upper,
    single-sided-impact branch (jump down on a down-sweep, a multiplier through +1) and the fold of the
    middle branch just above the grazing frequency of the contact orbit (jump up on an up-sweep).
    Package: the [steady] curve by HB (25 harmonics, the exact piecewise law sampled by AFT) and by
    shooting (exact event-driven period maps), and fixed-frequency shooting and HB on the upper branch at
    Omega = 0.85, 0.95, 1.0, 1.05.  Tolerances: shooting is exact up to the event location and Newton
    (1e-8 on the flight duration from the located events, 1e-6 on the multipliers; the extremes 1e-7: the
    output is sampled 2000 times per period; folds 1e-6: continuation refinement); HB-25 truncates the kinked force
    (its error falls like H^-2 .. H^-3 for a kink: measured 2e-5 on the folds, 1e-4 on the orbit extremes)
    -- tolerances 1e-4 (folds) and 5e-4 (extremes)."""
    from discrete.steady import HBModel, PeriodicSystem, ShootingModel
    from fem.modelfile.source import read_toml
    from fem.study import Study

    doc = read_toml(EXAMPLES / "geared_rattle.toml")
    study = Study.parse(doc)
    osc, wn, b, el_name = _ks(study)
    f_down, f_up, grazing, orbits = ks_reference(osc)
    out = [check("K&S oscillator: the model's dimensionless parameters", SRC_KS, "zeta, F_m, F_a (sum)",
                 0.05 + 0.1 + 0.02, osc.zeta + osc.Fm + osc.Fa, 1e-6)]
    # curves: HB (the example) and shooting (the same model, the range around the jumps)
    afc_hb = study.forced()
    doc_s = read_toml(EXAMPLES / "geared_rattle.toml")
    doc_s["steady"].update(method="shooting", omega=[0.78 * wn, 0.93 * wn])
    doc_s["steady"].pop("harmonics", None)
    afc_sh = Study.parse(doc_s).forced()
    for tag, curve, tol in (("HB-25", afc_hb, 1e-4), ("shooting", afc_sh, 1e-6)):
        folds = sorted(f["omega"] / wn for f in curve.folds)
        lo = min(folds, key=lambda w: abs(w - f_down)) if folds else float("nan")
        hi = min(folds, key=lambda w: abs(w - f_up)) if folds else float("nan")
        out.append(check(f"jump-down frequency ({tag})", SRC_KS, "Omega / omega_n (fold of the upper branch)",
                         f_down, lo, tol))
        out.append(check(f"jump-up frequency ({tag})", SRC_KS, "Omega / omega_n (fold near grazing)", f_up, hi, tol))
    out.append(claim("the jump-up fold lies above the contact orbit's grazing frequency", SRC_KS,
                     "grazing < jump-up < the upper branch's end", grazing[0] < f_up < grazing[1],
                     note=f"grazing {grazing[0]:.6f}, jump up {f_up:.6f}, grazing {grazing[1]:.6f}"))
    # fixed-frequency orbits on the upper branch
    spec = study.problem_spec()
    sh = ShootingModel(spec.problem, steps_per_period=48)
    p0 = spec.problem(1.0)
    hb = HBModel(PeriodicSystem(p0), harmonics=25)
    g = p0.gf[[el.name for el in p0.elements].index(el_name)]
    for Om, (_, pat, u) in orbits.items():
        w = Om * wn
        t, x, v = osc.samples(Om, u, pat)
        xmax, xmin = float(x.max()), float(x.min())
        mu_ref = np.sort(np.abs(osc.multipliers(Om, u, pat)))
        # shooting from the exact orbit's state at the forcing phase 0 (the package's own Newton and period map)
        xs, vs = _exact_at_zero(osc, Om, u, pat)
        q0 = np.array([xs * b / g[0]])
        qd0 = np.array([vs * b * wn / g[0]])
        y, _ = sh.solve(np.concatenate([q0, qd0]), w, scale=np.abs(np.concatenate([q0, qd0])) + 1e-300)
        _, res = sh.run(y, w, dense=True)
        s_sh = (g @ res.x[p0.f]) / b
        mu_sh = np.sort(np.abs(sh.floquet(y, w, np.abs(y) + 1e-300)))
        out.append(check(f"Omega = {Om}: max x (shooting)", SRC_KS, "x_max (2000 samples per period)", xmax,
                         float(s_sh.max()), 1e-7))
        out.append(check(f"Omega = {Om}: min x (shooting)", SRC_KS, "x_min (2000 samples per period)", xmin,
                         float(s_sh.min()), 1e-7))
        opens = [e.t for e in res.events if e.kind == "contact_open"]
        closes = [e.t for e in res.events if e.kind == "contact_close"]
        if opens and closes:
            flight = (min(c for c in closes + [c + 2 * math.pi / w for c in closes] if c > opens[0]) - opens[0]) * wn
            T = 2 * math.pi / Om
            exact = (u[0] + T - u[1]) if pat[0][1] == 1 else (u[1] - u[0])
            out.append(check(f"Omega = {Om}: time out of contact per period (shooting)", SRC_KS,
                             "flight duration (omega_n t)", exact, flight, 1e-8))
        out.append(check(f"Omega = {Om}: Floquet multiplier (shooting)", SRC_KS, "max |mu|", mu_ref[-1], mu_sh[-1],
                         1e-6))
        X0 = _nearest_state(afc_hb, w)
        X, _ = hb.solve(X0, w)
        _, qh, _ = hb.evaluate(X, w, points=4096)
        s_hb = (g @ qh) / b
        out.append(check(f"Omega = {Om}: max x (HB-25)", SRC_KS, "x_max", xmax, float(s_hb.max()), 5e-4))
        out.append(check(f"Omega = {Om}: min x (HB-25)", SRC_KS, "x_min", xmin, float(s_hb.min()), 5e-4))
    return out


@case("geared-backlash-period-doubling", group="geared", slow=True)
def backlash_period_doubling():
    """(d') The period doubling of Kahraman & Singh's gear-pair oscillator (J. Sound Vib. 142 (1990) 49; the
    subharmonic regime of their light-damping, low-mean-load cases) on the same train as (d),
    examples/geared_rattle.toml with the torque ripple raised to 105 N m: zeta = 0.05, F_m = 0.1, F_a = 0.15.
    Below the grazing frequency of the contact orbit (Omega = 1.5785) the period-1 orbit has single-sided
    impacts (drive flank -> backlash -> drive flank); its complex multiplier pair meets on the negative real
    axis near 1.29 and one real multiplier passes through -1 at Omega = 1.2213045 (found here numerically
    with the exact map; the exact orbit leaves no other multiplier outside the unit circle on 1.15 .. 1.5785).

    Reference (validation/analytic/backlash.py, independent of the package): the exact single-impact orbit
    continued from grazing, its exact multipliers, Brent's method on mu_min + 1 along the branch (xtol 1e-14):
    the flip frequency; the exact orbit there has mu = -1 to round-off (checked to 1e-12); an event-located
    solve_ivp run (rtol 1e-9, 150 periods) settles on period 1 at +0.03 above it and on period 2 at -0.03
    below it (Poincare distances over one period measured 8e-7 above and 0.12 below, over two periods 1e-8
    below: the doubling is supercritical).  Package: the HB
    continuation of the train (41 harmonics, the mesh law sampled by AFT, bifurcations by test functions, the
    period doubling re-located by the package with 54 harmonics) over 1.15 .. 1.7 omega_n must report exactly
    one bifurcation, a period doubling, at the exact frequency; the package's shooting (exact event-driven
    period map, finite-difference monodromy) at the exact flip frequency from the exact orbit's state must
    give the exact multipliers.  Tolerances: HB truncates the kinked mesh force, and the flip frequency
    converges non-monotonically with the harmonics: measured relative errors 4.1e-3 (H = 25), 1.7e-3 (33),
    3.5e-4 (41), 5.0e-4 (54), 3.6e-6 (57), 1.7e-4 (76) -- tolerance 1e-3 at H = 41 (twice the largest
    error measured at H >= 41).  The mesh law is sampled by AFT (MeshContact has no exactly integrated
    piecewise law), so HB's multipliers come from the midpoint rule on max(512, 2 N_fine) uniform intervals:
    measured against 4096 intervals they are off by up to 1.6e-2 near the flip and jump between neighbouring
    points (psi_PD is not smooth), which is why the location converges non-monotonically and why its
    critical multiplier (|mu + 1| = 6.3e-3, 4.5e-3, 2.3e-3 at H = 25, 41, 57) gets 1e-2; with 4096
    intervals the HB-41 points put the crossing at 1.2211 (1.6e-4).  Shooting's multipliers 1e-6 (its
    finite-difference monodromy, as in (d))."""
    from discrete.steady import ShootingModel
    from fem.modelfile.source import read_toml
    from fem.study import Study

    doc = read_toml(EXAMPLES / "geared_rattle.toml")
    doc["force"][0]["amplitude"] = 105.0                          # N m: F_a = 0.15 k b
    study = Study.parse(doc)
    osc, wn, b, el_name = _ks(study)
    src = SRC_KS + "; period doubling: Brent on the exact multiplier mu_min + 1 along the exact branch"
    out = [check("K&S oscillator: the model's dimensionless parameters", src, "zeta, F_m, F_a (sum)",
                 0.05 + 0.1 + 0.15, osc.zeta + osc.Fm + osc.Fa, 1e-6)]
    # exact: the single-impact branch from grazing down to 1.15, the flip bracketed on it
    graze = max(osc.grazing_frequencies(0.5, 2.5))
    grid = np.linspace(graze - 1e-3, 1.15, 44)
    pat, u = osc.impact_orbit_near_grazing(grid[0])
    us, mins, ok = [u], [], True
    for a, c in zip(grid[:-1], grid[1:]):
        us.append(osc.continue_to(a, us[-1], pat, c, step=2e-3))
    for Om, uu in zip(grid, us):
        mu = osc.multipliers(Om, uu, pat)
        mins.append(float(np.min(mu.real)) + 1.0 if np.all(mu.imag == 0) else 1.0)
        ok = ok and osc.consistent(Om, uu, pat) and np.all(np.abs(mu) < 1 + 1e-12) == (mins[-1] > 0)
    flips = [i for i in range(len(grid) - 1) if mins[i] * mins[i + 1] < 0]
    out.append(claim("exact branch: one flip on 1.15 .. grazing, nothing else leaves the unit circle", src,
                     "one sign change of mu_min + 1; unstable only by it; pattern kept",
                     len(flips) == 1 and ok, note=f"grazing {graze:.7f}, flips between {[grid[i] for i in flips]}"))
    if not flips:
        return out
    i = flips[0]
    Om_pd, u_pd, mu_pd = osc.flip(grid[i], us[i], pat, grid[i + 1])
    out.append(check("exact orbit at the flip: multiplier -1", src, "min mu (exact)", -1.0, float(np.min(mu_pd.real)),
                     1e-12, scale=1.0, note=f"Omega = {Om_pd:.10f}, multipliers {np.sort(mu_pd.real)}"))
    # independent of the multipliers: the settled response (solve_ivp, 150 periods from x = b + F_m at rest)
    # repeats every period just above the flip and only every second period just below it
    def settled(Om):
        sol, _ = osc.integrate(Om, osc.b + osc.Fm, 0.0, 150, rtol=1e-9, steps=20)
        T = 2 * math.pi / Om
        P = [sol.sol(sol.t[-1] - k * T) for k in range(3)]
        return float(np.linalg.norm(P[0] - P[1])), float(np.linalg.norm(P[0] - P[2]))
    above, below = settled(Om_pd + 0.03), settled(Om_pd - 0.03)
    out.append(claim("time integration: period 1 above the flip, period 2 below", src + "; scipy solve_ivp",
                     "|P - P(T)| < 1e-3 at +0.03; |P - P(T)| > 1e-2 and |P - P(2T)| < 1e-4 at -0.03",
                     above[0] < 1e-3 and below[0] > 1e-2 and below[1] < 1e-4,
                     note=f"Poincare distances over T, 2T: above {above[0]:.2g}, {above[1]:.2g}; "
                          f"below {below[0]:.2g}, {below[1]:.2g}"))
    # package: HB continuation with bifurcations
    doc["steady"].update(omega=[1.7 * wn, 1.15 * wn], harmonics=41, bifurcations=True)
    r = Study.parse(doc).forced()
    pds = [bf for bf in r.bifurcations if bf.kind == "period_doubling"]
    out.append(claim("HB-41: one bifurcation on 1.15 .. 1.7 omega_n, a period doubling", src,
                     "period doublings == 1, others == 0", len(pds) == 1 and len(r.bifurcations) == 1,
                     note=f"{[bf.line() for bf in r.bifurcations]}"))
    bf = min(pds, key=lambda x: abs(x.omega / wn - Om_pd)) if pds else None
    out.append(check("period-doubling frequency (HB-41)", src, "Omega / omega_n", Om_pd,
                     bf.omega / wn if bf else float("nan"), 1e-3, note=bf.note if bf else "missing"))
    if bf is not None and bf.check[0] is not None:
        out.append(check(f"period-doubling frequency (HB re-located with {bf.check[1]} harmonics)", src,
                         "Omega / omega_n", Om_pd, bf.check[0] / wn, 1e-3))
    mu_hb = bf.multiplier if bf is not None and bf.multiplier is not None else complex("nan")
    out.append(check("critical multiplier (HB-41: monodromy of the HB orbit)", src, "mu", -1.0, float(np.real(mu_hb)), 1e-2, scale=1.0,
                     note=f"mu = {mu_hb}"))
    # package: shooting at the exact flip frequency from the exact orbit's state
    spec = study.problem_spec()
    p0 = spec.problem(1.0)
    g = p0.gf[[el.name for el in p0.elements].index(el_name)]
    sh = ShootingModel(spec.problem, steps_per_period=48)
    w = Om_pd * wn
    xs, vs = _exact_at_zero(osc, Om_pd, u_pd, pat)
    y0 = np.array([xs * b / g[0], vs * b * wn / g[0]])
    y, _ = sh.solve(y0, w, scale=np.abs(y0) + 1e-300)
    mu_sh = np.sort(np.real(sh.floquet(y, w, np.abs(y) + 1e-300)))
    mu_ex = np.sort(np.real(mu_pd))
    out.append(check("critical multiplier (shooting at the exact flip)", src, "min mu", mu_ex[0], mu_sh[0], 1e-6,
                     scale=1.0, note=f"shooting multipliers {mu_sh}"))
    out.append(check("other multiplier (shooting at the exact flip)", src, "max mu", mu_ex[1], mu_sh[1], 1e-6,
                     scale=1.0))
    return out


def _exact_at_zero(osc, Om, u, pat):
    """(x, x') of the exact orbit at t = 0 (mod the period): the shooting section of the package."""
    T = 2 * math.pi / Om
    m = len(pat)
    ts = list(u[:m]) + [u[0] + T]
    t0 = math.ceil(ts[0] / T) * T if ts[0] > 0 else 0.0
    t0 = t0 if ts[0] <= t0 < ts[0] + T else t0 + T
    v = u[m]
    for i in range(m):
        if ts[i] <= t0 < ts[i + 1]:
            x, xd = osc.propagate(pat[i][1], Om, ts[i], pat[i][0], v, t0)
            return float(x), float(xd)
        v = float(osc.propagate(pat[i][1], Om, ts[i], pat[i][0], v, ts[i + 1])[1])
    raise RuntimeError("t = 0 not inside the period")


def _nearest_state(curve, w):
    """The HB coefficients of the stable curve point nearest to omega = w on the upper branch (the largest
    response among the stable points within 2 % of w)."""
    idx = [i for i in range(curve.omega.size) if abs(curve.omega[i] / w - 1) < 0.02 and curve.stable[i]]
    i = max(idx, key=lambda j: curve.response[j])
    return np.asarray(curve.states[i], float)


# ----------------------------------------------------------------------------- (e) textbook §11 gaps
SRC_11 = "textbook §11.1-11.2 (digest textbook_ch10-11.md (11.1), (11.4))"


def _gap_problem(el, A, forces=()):
    """One unit mass on the element's coordinate s = x, started at x = A at rest."""
    import scipy.sparse as sp_

    from discrete.linear_system import LinearSystem
    from discrete.nonsmooth import Problem

    ls = LinearSystem(M=sp_.eye(1), K=sp_.csr_matrix((1, 1)), dof_field=["x"], dof_name=["q"])
    return Problem(ls, [el], forces=list(forces), x0=np.array([A]))


@case("geared-textbook-gap-cases", group="geared")
def textbook_gap_cases():
    """(e) The textbook's §11 gap cases through the mesh's element (discrete MeshContact, the law of
    [[mesh]] backlash and of [[coupling]] backlash):

    * free vibration with clearance (11.1), m = k0 = 1, started at q = A = 1 at rest, clearances [-0.1, 0.1],
      [-0.3, 0.3], [-0.05, 0.15] (the cases of discrete_gap_exact): period 2 pi/k0 + 2 (upper - lower)/(k0 (A -
      upper)) to 1e-10, energy conserved to 1e-10 -- by the element directly, and by a train file (a body
      joined to the ground by a [[coupling]] with k_torsion = 1 and backlash 2 Delta, symmetric clearances);
    * the impact excitation (11.4) of §11.2 with N = 30, delta = 0.03, s = 1e-3 (contact_11_2_impact_excitation):
      the element with its in-contact dashpot c = 2 delta N gives the digest's contact angles (half a unit of
      their 4th decimal), max |q| and max |q''| (half a printed digit), as the Kelvin-Voigt contact does."""
    from discrete.nonsmooth import ExternalForce, simulate as run
    from discrete.nonsmooth.elements import MeshContact
    from fem.study import Study
    from validation.analytic import gap as ref
    from validation.analytic.contact_refs import SEC_11_2
    from validation.registry import printed

    out = []
    for lower, upper, A in ((-0.1, 0.1, 1.0), (-0.3, 0.3, 1.0), (-0.05, 0.15, 1.0)):
        T = ref.period(1.0, A, lower, upper)
        tag = f"[{lower}, {upper}], A={A}"
        r = run(_gap_problem(MeshContact("mesh", np.ones(1), k=1.0, lower=lower, upper=upper), A), 4.2 * T)
        closes = r.event_times("contact_close")
        out.append(check(f"mesh element: gap period ({tag})", SRC_11 + " (11.1)", "period (s)", T,
                         closes[-1] - closes[-3], 1e-10))
        out.append(claim(f"mesh element: energy conserved ({tag})", SRC_11, "energy_error <= 1e-10",
                         r.energy_error <= 1e-10, note=f"{r.energy_error:.2e}"))
        if lower == -upper:
            doc = {"title": "gap through a coupling", "body": [{"name": "q", "inertia": 1.0, "x0": A}],
                   "coupling": [{"name": "backlash", "between": ["q", "ground"], "k_torsion": 1.0,
                                 "backlash": 2 * upper}],
                   "simulation": {"t_end": 4.2 * T}}
            res = Study.parse(doc).simulate().result
            closes = res.event_times("contact_close")
            out.append(check(f"train coupling backlash: gap period ({tag})", SRC_11 + " (11.1)", "period (s)", T,
                             closes[-1] - closes[-3], 1e-10))
    d = SEC_11_2
    N, delta, D = d["N"], d["delta"], d["gap"] / 2
    T = 2 * math.pi
    el = MeshContact("mesh", np.ones(1), k=N * N, c=2 * delta * N, lower=-D, upper=D)
    force = ExternalForce(g=np.ones(1), amplitude=1.0, omega=1.0, phase=math.pi / 2)
    r = run(_gap_problem(el, 0.0, [force]), 39 * T)
    p = _gap_problem(el, float(r.x[0, -1]), [force])
    p.v0 = np.array([float(r.v[0, -1])])
    from discrete.nonsmooth.solver import Options

    r = run(p, T, Options(output_step=T / 4000))
    for kind, angles in (("contact_open", d["opens"]), ("contact_close", d["closes"])):
        got = r.event_times(kind)
        for text, phi in zip(angles, got):
            out.append(check(f"mesh element (11.4): {kind} angle {text}", SRC_11 + ": digest simulation",
                             f"{kind} phi mod 2 pi", float(text), phi, 0.5e-4 / T, scale=T))
        out.append(check(f"mesh element (11.4): {kind} events per period", SRC_11, "count", len(angles), got.size,
                         0.0, scale=1.0))
    q, v, t = r.x[0], r.v[0], r.t
    a = np.cos(t) - (2 * delta * N * v + N * N * (q - D * np.sign(q))) * (np.abs(q) > D)
    for key, value in (("max_displacement", np.max(np.abs(q))), ("max_acceleration", np.max(np.abs(a)))):
        refv, tol = printed(d[key])
        out.append(check(f"mesh element (11.4): {key.replace('_', ' ')}", SRC_11 + ": digest simulation", key,
                         refv, value, tol))
    return out


# ----------------------------------------------------------------------------- (c) parametric tongues
SRC_HILL = ("Hill's determinant (validation/analytic/parametric.py hill_edges: x'' + (a h(theta)) x = 0, "
            "multipliers +-1) with the mesh's Fourier coefficients")


@case("geared-mesh-parametric-hill", group="geared")
def mesh_parametric_hill():
    """(c) Mesh-stiffness variation: the parametric tongues of a one-mesh model (examples/geared_mesh_parametric.toml:
    two gears, m_e = 1 kg, k = 1e8 N/m, omega_n = 1e4 rad/s, 30 teeth, rectangular-wave variation of contact ratio
    1.6 and depth 0.3, 25 Fourier terms, undamped) against Hill's determinant of the same equation
    x'' + omega_n^2 (1 + eps w(theta)) x = 0, theta = w_m t (validation/analytic/parametric.py; the truncated
    Fourier series of w as the Toeplitz matrix, 121 terms): every tongue edge inside 150 .. 800 rad/s of the
    pinion (tooth-pass frequency 30 x) at depths 0.5 and 1 (1 = the declared variation).  The package locates
    the edges by root finding on det(Phi -+ I) of Magnus monodromy matrices (tolerance 1e-10): edges agree to
    1e-8 (measured ~1e-12; the Hill truncation's own error is below 1e-14 at 121 terms for these 25 harmonics)."""
    from fem.study import Study
    from validation.analytic.parametric import hill_edges

    study = Study.load(EXAMPLES / "geared_mesh_parametric.toml")
    from fem.modelfile.build.train import operating_speed
    from fem.train.parametric import train_parametric

    ts = study.train
    mesh = ts.train.connections[0]
    (ra, rb), _ = mesh.radii()
    Ia, Ib = (bd.inertia for bd in ts.train.bodies)
    wn = math.sqrt(mesh.stiffness * (ra * ra / Ia + rb * rb / Ib))
    res = train_parametric(ts, speed=operating_speed(study.doc), speed_min=150.0, speed_max=800.0, n_speed=66,
                           depth_min=0.0, depth_max=1.0, n_depth=3, boundaries_at=[0.5, 1.0])
    z = res.pass_per_speed
    L = len(mesh.variation)
    out = [check("tooth-pass frequency per speed", "z_a |ratio_a|", "w_m / Omega", 30.0, z, 1e-15)]
    for b in res.chart.boundaries:
        coef = np.zeros(2 * L + 1, complex)
        coef[L] = 1.0
        for h, a, bb in mesh.variation:
            coef[L + h] = b.depth * (a - 1j * bb) / 2
            coef[L - h] = b.depth * (a + 1j * bb) / 2
        ref_edges = np.sort(np.concatenate([hill_edges(coef, parity=p, n_terms=60, k0=wn) for p in (0, 1)]))
        lo_w, hi_w = 150.0 * z, 800.0 * z
        ref_edges = ref_edges[(ref_edges > lo_w) & (ref_edges < hi_w)]
        got = np.sort(np.concatenate([b.omega_low_rad_s, b.omega_high_rad_s]))
        got = got[(got > lo_w * (1 + 1e-12)) & (got < hi_w * (1 - 1e-12))]     # interval ends clipped at the range
        out.append(check(f"tongue edges in range at depth {b.depth:g}", SRC_HILL, "count", ref_edges.size, got.size,
                         0.0, scale=1.0))
        for e_ref, e in zip(ref_edges, got):
            out.append(check(f"tongue edge at depth {b.depth:g}, tooth-pass {e_ref:.6g} rad/s", SRC_HILL,
                             "speed (rad/s)", e_ref / z, e / z, 1e-8))
    return out


# ----------------------------------------------------------------------------- the examples' loads
@case("geared-two-stage-loads", group="geared")
def two_stage_loads():
    """The loads of examples/geared_two_stage.toml (two spur stages 20/60 and 18/54 on three rotor shafts, motor
    and machine bodies on flexible couplings, 10 N m against 90 N m):

    * static mesh forces = torque / base radius: stage 1 T_m / r_b1 with r_b1 = m z cos(alpha) / 2, stage 2
      3 T_m / r_b of its pinion (the intermediate shaft carries 3 T_m), to round-off (1e-10);
    * static bearing forces of each shaft balance its mesh forces' lateral components (sum over the shaft's
      bearings = -sum of n F over its gears), 1e-10 of the mesh force;
    * the force balance of every shaft and body in every direction, for the static state and every
      transmission-error harmonic at every speed of [forced] (1e-11) and at every sample of the time simulation
      with backlash and Craig-Bampton reduction (1e-11): every force by its own law (meshes, couplings, bearings,
      inertia from the equations of motion) accounted for;
    * the Craig-Bampton reduction of the simulation (8 fixed-interface modes per shaft, the connection, bearing
      and coupling DOFs kept) against the full train: the 8 lowest complex eigenvalues of the linear train
      (meshes closed) at the simulation's speed within 1e-3 (measured 7.5e-4).  (The package's restitution
      report is below 1 at the floating shafts' torsion DOFs: it measures inertia-relief flexibility, which a
      fixed-interface basis of a shaft free in torsion carries only through its few retained modes.)"""
    from fem.study import Study
    from fem.train.loads import bearing_terms

    study = Study.load(EXAMPLES / "geared_two_stage.toml")
    ts = study.train
    res = study.forced()
    Tm = study.doc.force[0].value
    s1, s2 = ts.train.connections[0], ts.train.connections[1]
    rb1 = s1.radii()[0][0]
    rb2_pinion = s2.radii()[0][1]           # stage 2's gear b is the intermediate pinion
    out = [check("stage 1 static mesh force = T_m / r_b", "statics of the input shaft", "N", Tm / rb1,
                 abs(res.mesh("stage 1").static), 1e-10),
           check("stage 2 static mesh force = 3 T_m / r_b (pinion 2)", "statics of the intermediate shaft", "N",
                 3 * Tm / rb2_pinion, abs(res.mesh("stage 2").static), 1e-10)]
    q = res.static_state
    F_mesh = {m.name: res.mesh(m.name).static for m in (s1, s2)}
    for b in ts.blocks:
        tot = np.zeros(2)
        for bt in bearing_terms(ts, 0.0):
            if bt.shaft == b.name:
                tot += bt.force(q, np.zeros_like(q))[:2, 0]
        lat = np.zeros(2)
        for m in (s1, s2):
            g = m.geometry(ts)
            for port, sgn in zip(m.ports, (1.0, -1.0)):
                if port.shaft == b.name:
                    # the mesh force on gear a is -F n (compression F along s = delta_a - delta_b), on gear b +F n
                    lat += -sgn * F_mesh[m.name] * g["n"][1:]
        out.append(check(f"{b.name}: static bearing forces balance the mesh forces", "statics of the shaft", "N",
                         0.0, float(np.max(np.abs(tot + lat))), 1e-10, scale=max(abs(F_mesh["stage 2"]), 1.0)))
    # fem.loads (section loads recovered from the element equations, and its bearing reactions) on the shafts
    from fem.loads import rotor_reactions

    sec = res.static_section_loads(ts)
    for shaft, x, factor in (("input", 0.2, 1.0), ("intermediate", 0.25, 3.0), ("output", 0.5, 9.0)):
        sl = sec[shaft]
        k = int(np.argmin(np.abs(sl.x - x)))
        out.append(check(f"{shaft}: static torque between its gear and its coupling/gear (fem.loads)",
                         "statics: T = ratio x T_m", "N m", factor * Tm, abs(float(sl.quantities["torque"][k])), 1e-10))
    for b in ts.blocks:
        rr = rotor_reactions(b.rs, q[b.offset:b.offset + b.n])
        mine = {bt.label.split(":", 1)[1]: bt.force(q, np.zeros_like(q))[:, 0] for bt in bearing_terms(ts, 0.0)
                if bt.shaft == b.name}
        diff = 0.0
        for key, val in rr.items():
            if key.endswith(":F_y") or key.endswith(":F_z"):
                name = key.rsplit(":", 1)[0].replace("bearing ", "bearing")
                comp = 0 if key.endswith("F_y") else 1
                diff = max(diff, abs(float(np.real(np.ravel(val)[0])) - mine[name][comp]))
        out.append(check(f"{b.name}: bearing forces = fem.loads.rotor_reactions", "fem.loads (issue 25)", "N", 0.0,
                         diff, 1e-10, scale=max(abs(F_mesh["stage 2"]), 1.0)))
    out.append(check("force balance, linear response over speed", "equilibrium of every shaft and body",
                     "max relative residual", 0.0, res.balance_max, 1e-11, scale=1.0))
    sim = study.simulate()
    out.append(check("force balance, time simulation with backlash (every sample)", "equilibrium of every shaft and body",
                     "max relative residual", 0.0, sim.force_balance.max_residual, 1e-11, scale=1.0))
    out.append(claim("contact lost and regained in the simulation (exact events)", "dynamic load factor > 2",
                     "contact_open and contact_close events", len(sim.result.events) > 0,
                     note=f"{len(sim.result.events)} events"))
    from fem.train import train_modes
    from fem.train.compile import compile_train

    speed = sim.compiled.speed
    m = train_modes(ts, speed, 12, tolerance=1e-10)
    lam_full = m.eigenvalues[~m.rigid][:8]
    red = compile_train(ts, speed, reduction=_reduction(study), linear=True).system
    f = red.free
    Mr, Kr, Cr = (A.toarray()[np.ix_(f, f)] for A in (red.M, red.K, red.C))
    lam = ref.eigenvalues(Mr, Kr, Cr, np.zeros_like(Cr), 0.0)
    lam = lam[np.abs(lam) > 1e-6 * np.abs(lam).max()][:8]
    out.append(check("Craig-Bampton per shaft (8 modes): the train's 8 lowest complex eigenvalues",
                     "full train (sparse modal) vs reduced train (dense eig)", "max |lam_red - lam| / |lam|", 0.0,
                     float(np.max(np.abs(lam - lam_full) / np.abs(lam_full))), 1e-3, scale=1.0))
    return out


def _reduction(study):
    from fem.modelfile.build.train import reduction

    return reduction(study.doc)


@case("geared-compressor-campbell", group="geared", slow=True)
def compressor_campbell():
    """The critical speeds of examples/geared_compressor_train.toml (motor, bull gear and the high-speed pinion
    rotor with three impellers; helical mesh 150/25, the pinion at -6 x the motor speed), found on the Campbell
    diagram by Brent's method on omega_j(Omega) = k Omega (orders 1 and 6 of the motor speed), checked by an
    independent dense solve (validation/analytic/geared.eigenvalues: dense shift-invert eig of the first-order
    form of the same matrices at each critical speed and each backward-whirl crossing): some eigenvalue has
    Im lam = k Omega_c, 1e-8.  And the
    pinion's speed in the model is -6 x the motor's (the kinematic ratio of the mesh), exactly."""
    from fem.study import Study

    study = Study.load(EXAMPLES / "geared_compressor_train.toml")
    ts = study.train
    camp = study.campbell()
    out = [check("pinion speed ratio = -150/25", "kinematics of the external mesh", "Omega_pinion / Omega_motor",
                 -6.0, ts.ratios["pinion"], 1e-14)]
    for c in camp.crossings:               # critical speeds (forward, mixed, torsion) and backward crossings
        sys_ = ts.system_at(c.speed_rad_s)
        M, K, C, G = (np.asarray(A.toarray()) for A in (sys_.M, sys_.K, sys_.C, sys_.G))
        f = sys_.free
        lam = ref.eigenvalues(M[np.ix_(f, f)], K[np.ix_(f, f)], C[np.ix_(f, f)], G[np.ix_(f, f)], c.speed_rad_s)
        target = c.order * c.speed_rad_s
        err = float(np.min(np.abs(lam.imag - target))) / target
        out.append(check(f"critical speed order {c.order:g} at {c.speed_rpm:.2f} rev/min ({c.kind})", SRC_DENSE,
                         "min |Im lam_dense - k Omega_c| / (k Omega_c)", 0.0, err, 1e-8, scale=1.0))
    return out
