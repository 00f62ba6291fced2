"""The rotor analyses of ``drivefem stability`` and ``drivefem static`` against closed forms: the
stability threshold and the API Level I screening of a Jeffcott rotor with a damper and a
cross-coupled seal (examples/rotor_jeffcott_seal.toml, read through the model-file path the
commands use), Wachel's anticipated cross-coupling by hand, and the static sag of a shaft under its
own weight on two bearings (Timoshenko beam)."""
from __future__ import annotations

import math

import numpy as np

from fem.rotor import Bearing, Rotor, ShaftSegment, static_deflection
from fem.sections import Material
from validation.analytic import rotor as ref
from validation.registry import case, check, claim

from validation.examples import EXAMPLES

STEEL = Material(E=211e9, G=81.2e9, rho=7850.0)


def _jeffcott_forward_root(m: float, c: float, k: float, q: float) -> complex:
    """The forward root of m s^2 + c s + (k - i q) = 0 (r = y + i z; module notes of fem.rotor.api_level1):
    the one with Im s > 0."""
    disc = np.sqrt(complex(c * c - 4 * m * (k - 1j * q)))
    roots = [(-c + disc) / (2 * m), (-c - disc) / (2 * m)]
    return max(roots, key=lambda s: s.imag)


@case("rotor-jeffcott-seal-cli", group="rotor")
def jeffcott_seal():
    """examples/rotor_jeffcott_seal.toml: massless shaft on rigid supports, m = 10 kg at mid-span, a
    damper c = 200 N s/m and a seal k_yz = -k_zy = beta Omega (beta = 30 N s/m) there.  With
    r = y + i z the disc obeys m r'' + c r' + (k - i q) r = 0 (q the cross-coupled stiffness): for
    s = i w, w^2 = k/m and q = c w, so (i) the threshold of q = beta Omega is Omega_th = c w_n / beta
    and (ii) the Level I zero crossing is Q0 = c w_n; (iii) the log decrement at Q_A is
    -2 pi Re s / Im s of the forward root; (iv) Wachel's Q_A = 3 (P / Omega) / (D H) (rho_d/rho_s) by
    hand from the file's stage.  k = the Timoshenko mid-span stiffness 1/(L^3/(48 EI) + L/(4 kappa G A)).
    The thresholds are roots converged by Brent's method (xtol 1e-10 relative for the speed, 1e-12 of
    Q_A for Q0): tolerance 1e-8; the log decrement and Q_A are direct evaluations: 1e-9 and 1e-14."""
    from fem.modelfile.build.rotor import level1_spec, modes_count, operating_range, stability_speeds
    from fem.rotor import stability_threshold
    from fem.rotor.api_level1 import api_level1
    from fem.study import Study

    name = "rotor-jeffcott-seal-cli"
    study = Study.load(EXAMPLES / "rotor_jeffcott_seal.toml")
    doc = study.doc
    seg = doc.rotor.segment[0]
    mat = doc.rotor.material
    m, L, d = doc.rotor.disc[0].mass, seg.length, seg.d
    damper = next(b for b in doc.rotor.bearing if b.name == "damper")
    seal = next(b for b in doc.rotor.bearing if b.name == "seal")
    c = damper.cyy
    beta = seal.kyz[1] / seal.speeds[1]
    A, I, _ = ref.circle(d)
    kappa = ref.cowper_solid(mat.E / (2 * mat.G) - 1)
    k = ref.simply_supported_midspan_stiffness(mat.E, mat.G, kappa, A, I, L)
    wn = math.sqrt(k / m)
    src = "closed form (Jeffcott rotor: m r'' + c r' + (k - i q) r = 0)"
    s = stability_speeds(doc)
    n = modes_count(doc, doc.stability, None)
    thr = stability_threshold(study.rotor, float(s[-1]), n, speed_min=float(s[0]), n_grid=int(s.size))
    out = [check(name, src, "stability threshold c w_n / beta [rad/s]", ref.jeffcott_threshold(m, k, c, beta),
                 thr.threshold_rad_s if thr.threshold_rad_s else np.nan, 1e-8),
           claim(name, src, "the destabilised mode whirls forward at w_n", thr.whirl == "forward"
                 and abs(thr.frequency_rad_s - wn) < 1e-8 * wn, note=f"{thr.whirl}, {thr.frequency_rad_s}")]
    spec = level1_spec(doc, operating_range(doc))
    st = doc.stability.api_level1.stage[0]
    omega = spec["speed"]
    qa_hand = 3.0 * (st.power / omega) / (st.diameter * st.width) * st.density_ratio
    lv = api_level1(study.rotor.rotor, n_modes=n, **spec)
    wachel = "API 617 7th ed. 2.6.5 / API RP 684 SP6.8.5.6 (Wachel), by hand"
    out.append(check(name, wachel, "QA = B_c (P/Omega)/(D_c H_c) (rho_d/rho_s) [N/m]", qa_hand, lv.q_a, 1e-14))
    out.append(check(name, src, "Level I zero crossing Q0 = c w_n [N/m]", c * wn, lv.q0 if lv.q0 else np.nan, 1e-8))
    sa = _jeffcott_forward_root(m, c, k, qa_hand)
    out.append(check(name, src, "log decrement of the forward mode at QA", -2 * math.pi * sa.real / sa.imag,
                     lv.log_decrement_a, 1e-9))
    s0 = _jeffcott_forward_root(m, c, k, 0.0)
    out.append(check(name, src, "log decrement at Q = 0", -2 * math.pi * s0.real / s0.imag, lv.log_decrement[0], 1e-9))
    ratio_ok = (c * wn / qa_hand >= 2.0) == (lv.criteria[0]["passed"])
    out.append(claim(name, "API RP 684 SP6.8.5.10 criteria", "verdict: Q0/QA >= 2 and log dec at QA >= 0.1 "
                     "evaluated on the closed-form values", ratio_ok and lv.passed == (
                         c * wn / qa_hand >= 2.0 and -2 * math.pi * sa.real / sa.imag >= 0.1)))
    return out


@case("rotor-static-sag", group="rotor")
def static_sag():
    """A uniform steel shaft (L = 1.2 m, d = 60 mm) on two bearings of stiffness k_b at its ends,
    under its own weight w = rho A g: mid-span deflection of the Timoshenko beam plus the bearings'
    give, 5 w L^4 / (384 E I) + w L^2 / (8 kappa G A) + w L / (2 k_b), and each bearing carries
    w L / 2 (the shaft pushes it down: F_z = -w L / 2).  The rotor element interpolates the static Timoshenko beam exactly and the weight is its
    consistent load, so the nodal deflections are exact whatever the mesh: tolerance 1e-9 (round-off
    of the solve); the equilibrium of the ground reactions 1e-12."""
    name = "rotor-static-sag"
    L, d, kb, g = 1.2, 0.06, 5e7, 9.81
    A, I, _ = ref.circle(d)
    kappa = ref.cowper_solid(STEEL.E / (2 * STEEL.G) - 1)
    w = STEEL.rho * A * g
    src = "closed form (simply supported Timoshenko beam under uniform load, elastic supports)"
    out = []
    for n in (4, 9):
        rotor = Rotor([ShaftSegment(L, n if n % 2 == 0 else n + 1, d, STEEL)],
                      bearings=[Bearing(0.0, kyy=kb, kzz=kb, name="left"), Bearing(L, kyy=kb, kzz=kb, name="right")])
        res = static_deflection(rotor)
        mid = float(np.interp(L / 2, res.node_x, res.w))
        expected = -(5 * w * L**4 / (384 * STEEL.E * I) + w * L**2 / (8 * kappa * STEEL.G * A) + w * L / (2 * kb))
        ne = n if n % 2 == 0 else n + 1
        out.append(check(name, src, f"mid-span sag, {ne} elements [m]", expected, mid, 1e-9))
        out.append(check(name, src, f"load on each bearing -w L / 2 (along z, down), {ne} elements [N]", -w * L / 2,
                         float(res.bearing_force[0, 1]), 1e-9))
        out.append(check(name, "equilibrium", f"ground reactions balance the weight, {ne} elements", 0.0,
                         res.equilibrium_error, 1e-12, scale=1.0))
    return out
