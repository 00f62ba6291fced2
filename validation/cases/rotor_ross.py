"""Rotors imported from ROSS (``drivefem convert``) against ROSS's own results, and layered sections
against their hand-computed equivalent single section.

ROSS's numbers are stored in validation/data/ross/ with their provenance (ROSS 2.3.0; made by
benchmarks/ross_reference.py in ROSS's environment, which CI does not have): the ROSS rotor files
that are converted here, and ROSS's modes, Campbell diagrams, critical speeds and unbalance
responses on them.  Eigenvalues are matched to ROSS's by nearest damped frequency (ROSS keeps its
modes by Im lam, drivefem by |lam|).
"""
from __future__ import annotations

import json
import math
import tempfile
import warnings
from pathlib import Path

import numpy as np

from validation.registry import case, check, claim

DATA = Path(__file__).resolve().parent.parent / "data" / "ross"
EXAMPLES = Path(__file__).resolve().parent.parent.parent / "examples"
SRC = "ROSS 2.3.0 (stored, validation/data/ross)"
SPEED = 4000 * math.pi / 30
VARIANTS = ("isotropic", "anisotropic", "damped", "cross-coupled")


def _reference(name: str) -> dict:
    return json.loads((DATA / name).read_text())


def imported_rotor(ross_file: str, **options):
    """The drivefem rotor of a stored ROSS file, through the converter and the model-file loader
    (what ``drivefem convert`` writes and ``drivefem modal`` reads)."""
    from fem.modelfile.ross import convert_ross, read_ross

    doc, _ = convert_ross(read_ross(DATA / ross_file), source=ross_file, **options)
    return rotor_from_doc(doc), doc


def rotor_from_doc(doc: dict):
    from fem.modelfile.build.rotor import rotor_model
    from fem.modelfile.ross import rotor_file_text
    from fem.study import Study

    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "rotor.toml"
        p.write_text(rotor_file_text(doc, []))
        return rotor_model(Study.load(p).doc)


def _matched(ours: np.ndarray, wd: list, logdec: list | None = None):
    """(max relative difference of the damped frequencies, max |difference of the log decrements|)
    of ROSS's modes (wd > 1 rad/s) against the nearest of ``ours`` (complex eigenvalues)."""
    osc = ours[ours.imag > 1e-9]
    e_w, e_l = 0.0, 0.0
    for j, w in enumerate(wd):
        if w <= 1.0:
            continue
        k = int(np.argmin(np.abs(osc.imag - w)))
        e_w = max(e_w, abs(osc[k].imag - w) / w)
        if logdec is not None:
            e_l = max(e_l, abs(-2 * math.pi * osc[k].real / osc[k].imag - logdec[j]))
    return e_w, e_l


@case("rotor-ross-friswell-roundtrip", group="rotor")
def friswell_roundtrip():
    """Friswell et al. (2010) Example 5.9.1 built in ROSS (6 elements; isotropic, anisotropic,
    damped and cross-coupled bearings), saved by ROSS's Rotor.save and converted: ROSS's damped
    frequencies and log decrements at 4000 rev/min, its Campbell diagram (10 speeds to 4500
    rev/min), its critical speeds (ROSS's Newton iteration to rtol 1e-13 against drivefem's roots of
    omega(Omega) = Omega by Brent's method) and its unbalance response at both discs (complex, per
    axis, relative to the peak), all within 1e-9 (measured 1e-13 ... 2e-11: same element, same
    matrices).  Exception: the undamped cross-coupled rotor at rest has nearly defective pairs
    -s + i w, s + i w, whose eigenvalues are conditioned like sqrt(eps) (measured 8e-7 against
    ROSS's dense solver): at zero speed its tolerance is 1e-6."""
    from fem.rotor import Unbalance, assemble_rotor, campbell, rotor_modes, unbalance_response

    name = "rotor-ross-friswell-roundtrip"
    ref = _reference("friswell.json")
    out = []
    for var in VARIANTS:
        r = ref[var]
        rotor, doc = imported_rotor(r["file"])
        m = rotor_modes(rotor, SPEED, 16)
        e_w, e_l = _matched(m.eigenvalues, r["modal_4000rpm"]["wd"], r["modal_4000rpm"]["log_dec"])
        out.append(check(name, SRC, f"{var}: damped frequencies at 4000 rev/min, max rel. difference", 0.0, e_w, 1e-9,
                         scale=1.0))
        out.append(check(name, SRC, f"{var}: log decrements at 4000 rev/min, max abs. difference", 0.0, e_l, 1e-9,
                         scale=1.0))
        sp = np.asarray(r["campbell"]["speeds"])
        camp = campbell(rotor, sp, 16, critical=False)
        for i, s in enumerate(sp):
            e, _ = _matched(1j * camp.omega_damped_rad_s[i], r["campbell"]["wd"][i])     # frequencies only
            tol = 1e-6 if (var == "cross-coupled" and s == 0.0) else 1e-9
            out.append(check(name, SRC, f"{var}: Campbell, {s * 30 / math.pi:.0f} rev/min, max rel. difference", 0.0, e,
                             tol, scale=1.0))
        crit = np.asarray(r["critical"]["wd"])
        cc = campbell(rotor, np.linspace(0.0, 1.2 * crit.max(), 41), 16, orders=(1.0,))
        roots = np.array([c.speed_rad_s for c in cc.crossings])
        for w in crit:
            k = int(np.argmin(np.abs(roots - w)))
            out.append(check(name, SRC + ", run_critical_speed", f"{var}: critical speed near {w:.3f} rad/s", w,
                             roots[k], 1e-9))
        u = r["unbalance"]
        rs = assemble_rotor(rotor)
        res = unbalance_response(rs, [Unbalance(doc["rotor"]["disc"][1]["x"], u["magnitude"], u["phase"])],
                                 np.asarray(u["speeds"]), find_peaks=False)
        err = 0.0
        for node, p in u["probes"].items():
            x = doc["rotor"]["disc"][0 if node == "2" else 1]["x"]
            rx = np.asarray(p["x_re"]) + 1j * np.asarray(p["x_im"])
            ry = np.asarray(p["y_re"]) + 1j * np.asarray(p["y_im"])
            peak = max(np.abs(rx).max(), np.abs(ry).max())
            err = max(err, np.abs(res.response[:, rs.dof(x, "v")] - rx).max() / peak,
                      np.abs(res.response[:, rs.dof(x, "w")] - ry).max() / peak)
        out.append(check(name, SRC + ", run_unbalance_response", f"{var}: unbalance response at both discs, "
                         "max |difference| / peak (ROSS x, y -> drivefem v, w)", 0.0, err, 1e-9, scale=1.0))
    return out


def _campbell_errors(camp, modes_ref: list, first: int = 6) -> tuple[np.ndarray, np.ndarray]:
    """Per speed: max rel. difference of ROSS's lowest ``first`` damped frequencies and max |d log dec|."""
    ew, el = [], []
    for i, r in enumerate(modes_ref):
        lam = camp.omega_damped_rad_s[i] * (1j - camp.damping_ratio[i] / np.sqrt(np.maximum(
            1 - camp.damping_ratio[i] ** 2, 1e-300)))
        e_w, e_l = _matched(lam, r["wd"][:first], r["log_dec"][:first])
        ew.append(e_w)
        el.append(e_l)
    return np.asarray(ew), np.asarray(el)


def _compressor_with_ross_coefficients(ref: dict):
    """The converted compressor whose bearings and seals carry, at each Campbell speed, the
    coefficients ROSS used there (its smoothing spline, extrapolated below its tables): linear
    tables on those speeds, evaluated at their points only."""
    from fem.modelfile.ross import LATERAL_MAP

    _, doc = imported_rotor(ref["file"])
    speeds = ref["campbell"]["speeds"]
    for b in doc["rotor"]["bearing"]:
        c = ref["coefficients"][b["name"]]
        for rk, dk in LATERAL_MAP.items():
            b[dk] = c[rk]
        b.update(speeds=speeds, interpolation="linear", extrapolate="refuse")
    return rotor_from_doc(doc)


@case("rotor-ross-compressor", group="rotor")
def compressor():
    """ROSS 2.3.0's compressor example (91 shaft elements on 55 stations, 36 of them layered: a
    steel shaft and a sleeve of E = G = 6894.75 Pa, ROSS's way of a mass-only impeller hub; 7 discs,
    2 tilting-pad bearings and 12 seals with speed tables), converted by ``drivefem convert``.

    With the converter's default, ROSS's own table convention (interpolation = "smoothing-spline",
    extrapolate = "continue": scipy's UnivariateSpline with s = number of points, extrapolated along
    its end cubics -- the same FITPACK fit ROSS makes):

    * the bearing and seal coefficients at the 21 Campbell speeds equal the ones ROSS used (stored)
      to 1e-12 of each row's largest value (measured: identical);
    * the modes at 4000 rev/min against ROSS as it is (its tables not held): damped frequencies and
      log decrements of ROSS's 12 modes within 1e-6 (measured 9e-9 / 4e-9);
    * the Campbell diagram, 21 speeds from 0 to 11000 rev/min, against ROSS's modes at each speed
      (all 8 that ROSS reports), inside the tables (4400-11000 rev/min) and below them (0-3850
      rev/min, where both extrapolate): damped frequencies and log decrements within 1e-6 at every
      speed (measured 2e-9 / 1e-8: the same coefficients, the same layered elements; the rest is
      the two eigen-solvers' round-off on heavily damped modes).  The shipped
      examples/ross_compressor.toml (that conversion) is checked at 4000 rev/min the same way.

    With drivefem's other choices (``--interpolation spline --extrapolate linear``, the checks
    kept from the first import):

    * 4000 rev/min, where every table has a point: ROSS with each bearing and seal held at its table
      values there (the same table values as drivefem's, which evaluates its tables at their
      points exactly) against the converted rotor: damped frequencies and log decrements of ROSS's
      12 modes within 1e-6 (measured 5e-10 / 1e-9: the layered sections are ROSS's to round-off).
      ROSS as it is evaluates its tables through a smoothing spline (UnivariateSpline, s = number of
      points) that misses its own points by up to 4.5e-4 (seal damping): those results differ by
      2e-5 (reported, bound 1e-4).
    * Campbell diagram, 21 speeds from 0 to 11000 rev/min: with ROSS's own coefficients at every
      speed (stored) the converted rotor reproduces ROSS's lowest six modes within 1e-6 (frequency)
      and 1e-6 (log decrement) at every speed, including the speeds below the tables (0 to 3850
      rev/min), where ROSS extrapolates its cubic splines (a seal's kxx = -22034 N/m at rest:
      negative direct stiffness accepted).
    * With drivefem's own interpolation (spline) inside the tables (4400-11000 rev/min), the
      difference to ROSS stays within the interpolation's own accuracy, measured as the largest
      difference between drivefem's spline and pchip diagrams (two interpolants of the same tables).
    * Below the tables drivefem extrapolates linearly (the spline's end tangent), ROSS its end
      cubic: two different functions of speed (ROSS's bearing kxx at rest 1.7e7 N/m, the tangent
      line's 3.3e7 N/m). The frequencies then differ by up to 2 % (reported; bound 5 %); the log
      decrements of the heavily damped bearing modes by up to ~1: extrapolated tables are a
      modelling choice, not data."""
    from fem.rotor import assemble_rotor, campbell, rotor_modes

    name = "rotor-ross-compressor"
    ref = _reference("compressor.json")
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")                  # the extrapolation warnings are the point
        out += _compressor_ross_convention(name, ref)
        rotor, _ = imported_rotor(ref["file"], extrapolate="linear", interpolation="spline")
        rs = assemble_rotor(rotor)
        m = rotor_modes(rs, SPEED, 24)
        r = ref["modal_4000rpm_table_values"]
        e_w, e_l = _matched(m.eigenvalues, r["wd"], r["log_dec"])
        out.append(check(name, SRC, "4000 rev/min, same table values: damped frequencies, max rel. difference", 0.0,
                         e_w, 1e-6, scale=1.0))
        out.append(check(name, SRC, "4000 rev/min, same table values: log decrements, max abs. difference", 0.0,
                         e_l, 1e-6, scale=1.0))
        r = ref["modal_4000rpm_as_is"]
        e_w, _ = _matched(m.eigenvalues, r["wd"], r["log_dec"])
        out.append(check(name, SRC, "4000 rev/min, ROSS's smoothing spline as is: damped frequencies, max rel. "
                         "difference", 0.0, e_w, 1e-4, scale=1.0))
        speeds = np.asarray(ref["campbell"]["speeds"])
        modes_ref = ref["campbell_modes"]
        same = campbell(_compressor_with_ross_coefficients(ref), speeds, 20, critical=False)
        ew, el = _campbell_errors(same, modes_ref)
        out.append(check(name, SRC, "Campbell 0-11000 rev/min with ROSS's coefficients: frequencies, max rel. "
                         "difference", 0.0, ew.max(), 1e-6, scale=1.0))
        out.append(check(name, SRC, "Campbell 0-11000 rev/min with ROSS's coefficients: log decrements, max abs. "
                         "difference", 0.0, el.max(), 1e-6, scale=1.0))
        ours = campbell(rs, speeds, 20, critical=False)
        rotor_p, _ = imported_rotor(ref["file"], extrapolate="linear", interpolation="pchip")
        other = campbell(rotor_p, speeds, 20, critical=False)
        inside = speeds >= SPEED * (1 - 1e-12)
        ew, el = _campbell_errors(ours, modes_ref)
        spread = np.max(np.abs(other.omega_damped_rad_s[:, :8] - ours.omega_damped_rad_s[:, :8])
                        / ours.omega_damped_rad_s[:, :8].clip(1.0), axis=1)
        out.append(check(name, "drivefem spline vs pchip (the interpolation's own accuracy)",
                         "Campbell inside the tables (4400-11000 rev/min): frequencies vs ROSS, max rel. difference",
                         0.0, ew[inside].max(), spread[inside].max(), scale=1.0,
                         note=f"spline vs pchip differ by {spread[inside].max():.1e}"))
        out.append(check(name, SRC + "; extrapolations differ (tangent line vs ROSS's end cubic)",
                         "Campbell below the tables (0-3850 rev/min), extrapolate = 'linear': frequencies vs ROSS, "
                         "max rel. difference", 0.0, ew[~inside].max(), 0.05, scale=1.0,
                         note=f"log decrements differ by up to {el[~inside].max():.2f}"))
        out.append(claim(name, "model", "a seal's extrapolated negative direct stiffness (ROSS: kyy = -22034 N/m at "
                         "rest) is accepted and the rotor is stable at rest with it",
                         bool(np.all(same.log_decrement[0][:6] > -1e-9)), note=f"min log dec at rest "
                         f"{same.log_decrement[0][:6].min():.3f}"))
    return out


def _compressor_ross_convention(name: str, ref: dict) -> list:
    """The checks of the compressor converted with ROSS's table convention (see :func:`compressor`)."""
    from fem.modelfile.build.rotor import rotor_model
    from fem.modelfile.ross import LATERAL_MAP
    from fem.rotor import assemble_rotor, campbell, rotor_modes
    from fem.rotor.model import BEARING_COEFFICIENTS
    from fem.study import Study

    out = []
    rotor, doc = imported_rotor(ref["file"])                     # the converter's default
    tables = {b["name"]: (b["interpolation"], b["extrapolate"]) for b in doc["rotor"]["bearing"] if "speeds" in b}
    out.append(claim(name, "drivefem convert's default", "every bearing and seal table is written with "
                     "interpolation = 'smoothing-spline', extrapolate = 'continue' (ROSS's convention)",
                     len(tables) == 14 and set(tables.values()) == {("smoothing-spline", "continue")},
                     note=f"{len(tables)} tables"))
    rs = assemble_rotor(rotor)
    speeds = np.asarray(ref["campbell"]["speeds"])
    ours = rs.coefficients(speeds)
    err = 0.0
    for t_no, t in enumerate(rs.tables):
        for rk, dk in LATERAL_MAP.items():
            theirs = np.asarray(ref["coefficients"][t.name][rk])
            mine = ours[:, 8 * t_no + BEARING_COEFFICIENTS.index(dk)]
            err = max(err, float(np.max(np.abs(mine - theirs)) / max(np.abs(theirs).max(), 1e-300)))
    out.append(check(name, SRC + ", BearingElement.<coefficient>_interpolated", "ROSS's convention: the 14 tables' "
                     "coefficients at the 21 Campbell speeds (0-11000 rev/min) vs ROSS's, max difference / row's "
                     "largest", 0.0, err, 1e-12, scale=1.0))
    r = ref["modal_4000rpm_as_is"]
    e_w, e_l = _matched(rotor_modes(rs, SPEED, 24).eigenvalues, r["wd"], r["log_dec"])
    out.append(check(name, SRC, "ROSS's convention, 4000 rev/min, ROSS as it is (tables not held): damped "
                     "frequencies, max rel. difference", 0.0, e_w, 1e-6, scale=1.0))
    out.append(check(name, SRC, "ROSS's convention, 4000 rev/min, ROSS as it is (tables not held): log "
                     "decrements, max abs. difference", 0.0, e_l, 1e-6, scale=1.0))
    camp = campbell(rs, speeds, 20, critical=False)
    ew, el = _campbell_errors(camp, ref["campbell_modes"], first=8)
    inside = speeds >= SPEED * (1 - 1e-12)
    for part, sel in (("inside the tables (4400-11000 rev/min)", inside),
                      ("below the tables (0-3850 rev/min, both extrapolate)", ~inside)):
        out.append(check(name, SRC, f"ROSS's convention, Campbell {part}: damped frequencies of ROSS's 8 modes, "
                         "max rel. difference over the speeds", 0.0, float(ew[sel].max()), 1e-6, scale=1.0))
        out.append(check(name, SRC, f"ROSS's convention, Campbell {part}: log decrements of ROSS's 8 modes, "
                         "max abs. difference over the speeds", 0.0, float(el[sel].max()), 1e-6, scale=1.0))
    shipped = rotor_modes(rotor_model(Study.load(EXAMPLES / "ross_compressor.toml").doc), SPEED, 24)
    e_w, e_l = _matched(shipped.eigenvalues, r["wd"], r["log_dec"])
    out.append(check(name, SRC, "examples/ross_compressor.toml (the shipped conversion, ROSS's convention), 4000 "
                     "rev/min vs ROSS as it is: damped frequencies and log decrements, max difference", 0.0,
                     max(e_w, e_l), 1e-6, scale=1.0))
    return out


@case("rotor-layered-section-equivalent", group="rotor")
def layered_equivalent():
    """A layered section against the single section computed by hand (lateral model, Friswell's
    rotor geometry: 1.5 m, discs at 0.5 and 1.0 m, 1 MN/m bearings, 4000 rev/min, 6, 48 and 96
    elements).  Core: solid steel shaft d1 = 50 mm; layer: annulus 50-80 mm, same density.

    * Exact: when every layer has the same shear parameter Phi = 12 E I/(kappa G A L^2) (layer
      material with E2/G2 = (E1/G1) d1^2/(d2^2 + d1^2), same kappa), the layers share one
      interpolation, so the layered element equals the element of the solid 80 mm section with
      E I = E1 I1 + E2 I2, kappa G A = kappa (G1 A1 + G2 A2) (E_eq = sum E_i I_i / I, G_eq = sum G_i A_i / A):
      frequencies equal to 1e-12.  The same for a mass-only layer (E_eq = E1 I1 / I, G_eq = G1 A1 / A).
    * Converged: a steel layer (its own Phi, ROSS's convention: the layers are joined at the nodes
      only) and the solid 80 mm steel section with the same explicit kappa tend to the same
      continuum beam as the mesh is refined: measured differences 5.6e-4, 4.4e-4, 2.3e-4, 7.6e-5,
      2.1e-5, 5.3e-6 at 6, 12, 24, 48, 96, 192 elements, O(h^2) once the elements are shorter than
      about the diameter.  Checked: below 5e-5 at 96 elements, ratio 48 -> 96 above 3.
    * Total mass of core and layer (mass-only or not) and discs: rho (A1 + A2) L + discs to 1e-13."""
    from fem.rotor import Bearing, Disc, Layer, Rotor, ShaftSegment, assemble_rotor, rotor_modes
    from fem.sections import Material

    name = "rotor-layered-section-equivalent"
    out = []
    rho, kappa = 7810.0, 0.9
    d1, d2 = 0.05, 0.08
    steel = Material(E=211e9, G=81.2e9, rho=rho)
    I1, I2, I = (math.pi * d1 ** 4 / 64, math.pi * (d2 ** 4 - d1 ** 4) / 64, math.pi * d2 ** 4 / 64)
    A1, A2, A = (math.pi * d1 ** 2 / 4, math.pi * (d2 ** 2 - d1 ** 2) / 4, math.pi * d2 ** 2 / 4)
    ratio = (steel.E / steel.G) * d1 ** 2 / (d2 ** 2 + d1 ** 2)          # E2/G2 that gives the layer the core's Phi
    layer_mat = Material(E=100e9, G=100e9 / ratio, rho=rho)

    def rotor(n, segment):
        return Rotor([segment(n)], discs=[Disc.from_geometry(0.5, 0.07, 0.28, 0.08, rho),
                                          Disc.from_geometry(1.0, 0.07, 0.35, 0.08, rho)],
                     bearings=[Bearing(0.0, kyy=1e6, kzz=1e6), Bearing(1.5, kyy=1e6, kzz=1e6)])

    def freqs(r):
        return rotor_modes(r, SPEED, 6).omega_damped_rad_s

    for mass_only in (False, True):
        tag = "mass-only layer" if mass_only else "structural layer"
        layered = rotor(6, lambda n: ShaftSegment(1.5, n, d1, steel, shear_coefficient=kappa, layers=[
            Layer(d2, d1, layer_mat, shear_coefficient=kappa, mass_only=mass_only)]))
        EI = steel.E * I1 + (0.0 if mass_only else layer_mat.E * I2)
        GA = steel.G * A1 + (0.0 if mass_only else layer_mat.G * A2)
        single = rotor(6, lambda n: ShaftSegment(1.5, n, d2, Material(E=EI / I, G=GA / A, rho=rho),
                                                 shear_coefficient=kappa))
        a, b = freqs(layered), freqs(single)
        out.append(check(name, "hand-computed equivalent section (same Phi)", f"{tag}: 6 lowest damped frequencies, "
                         "max rel. difference", 0.0, float(np.max(np.abs(a - b) / b)), 1e-12, scale=1.0))
        m_l = assemble_rotor(layered).total_mass()
        out.append(check(name, "rho (A1 + A2) L + discs", f"{tag}: total mass [kg]",
                         rho * (A1 + A2) * 1.5 + sum(d.mass for d in layered.discs), m_l, 1e-13))
    diffs = []
    for n in (48, 96):
        layered = rotor(n, lambda n: ShaftSegment(1.5, n, d1, steel, shear_coefficient=kappa,
                                                  layers=[Layer(d2, d1, steel, shear_coefficient=kappa)]))
        single = rotor(n, lambda n: ShaftSegment(1.5, n, d2, steel, shear_coefficient=kappa))
        a, b = freqs(layered), freqs(single)
        diffs.append(float(np.max(np.abs(a - b) / b)))
    out.append(check(name, "continuum limit (one Timoshenko beam)", "steel layer vs solid section, 96 elements: max "
                     "rel. difference of 6 frequencies", 0.0, diffs[1], 5e-5, scale=1.0,
                     note=f"48 elements: {diffs[0]:.1e}, 96: {diffs[1]:.1e}"))
    out.append(claim(name, "mesh refinement", "the layered section converges to the single section at O(h^2) "
                     "(difference ratio 48 -> 96 elements > 3; 4 asymptotically)", diffs[0] / diffs[1] > 3.0,
                     note=f"ratio {diffs[0] / diffs[1]:.2f}"))
    return out
