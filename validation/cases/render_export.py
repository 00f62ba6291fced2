"""Issue 6 cases 2 and 3: export round trip (VTU/XDMF) and the pixel check of rendered
mode shapes."""
from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from fem import assemble, modal_analysis
from validation.builders import uniform
from validation.registry import case, check, claim

L, D = 1.5, 0.05


def _models():
    return {"bending EB": uniform("bending", L, 20, d=D, supports=[(0.0, "clamped")]),
            "bending Timoshenko P2": uniform("bending", L, 8, d=D, theory="timoshenko", supports=[(0.0, "clamped")]),
            "torsion P2": uniform("torsion", L, 10, d=D, supports=[(0.0, "clamped")],
                                  points=[{"x": L, "inertia": 0.05}]),
            "axial P1 free-free": uniform("axial", L, 12, d=D, order=1)}


@case("export-roundtrip", group="render")
def export_roundtrip():
    """Mode shapes written to VTU (binary) and XDMF (XML, 17 digits) through meshio and read
    back equal the originals to 1e-12 (relative to the largest nodal value of each field);
    frequencies travel as VTU field data / XDMF information and must match to 1e-12 too.
    Both encodings are exact for doubles, so the tolerance only guards against a lossy
    format sneaking in (single precision would give ~1e-7)."""
    from fem.output.mesh import read_modes, write_modes

    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, model in _models().items():
            fe = assemble(model)
            res = modal_analysis(fe.system, 4)
            for suffix in (".vtu", ".xdmf"):
                back = read_modes(write_modes(fe, res, Path(tmp) / f"m{suffix}"))
                err = 0.0
                for field in model.fields:
                    for r in range(4):
                        x, v = fe.nodal_values(res.shapes[:, r], field)
                        err = max(err, np.max(np.abs(back["fields"][field][:, r] - v)) / np.max(np.abs(v)))
                        err = max(err, np.max(np.abs(back["points"][:, 0] - x)) / L)
                out.append(check("export-roundtrip", "issue 6 case 2", f"{label} {suffix}: max rel. error of mode shapes",
                                 0.0, err, 1e-12, scale=1.0))
                ferr = np.max(np.abs(back["frequencies_hz"] - res.frequencies_hz)) / np.max(res.frequencies_hz)
                out.append(check("export-roundtrip", "issue 6 case 2", f"{label} {suffix}: frequencies",
                                 0.0, ferr, 1e-12, scale=1.0))
    return out


def cantilever_pictures():
    """(fe, modal, [image mode 1, image mode 2]) of the reference cantilever (40 EB elements)."""
    from fem.render import render_image

    fe = assemble(uniform("bending", L, 40, d=D, supports=[(0.0, "clamped")]))
    res = modal_analysis(fe.system, 3)
    return fe, res, [render_image(fe, res, r) for r in (0, 1)]


def picture_vs_shape(fe, res, img, r: int) -> dict:
    """Compare the body centre line read from the image with mode ``r``'s shape.

    The picture is a parallel projection looking down z, so columns map linearly to x
    (calibrated by the body's root, x = 0, where the clamped slope is zero, and the end of the
    faint undeformed shaft, x = L) and rows to w
    (the row of the clamped root is w = 0); the displayed tip deflection is the renderer's
    documented display amplitude, 15 % of L for the largest |w|."""
    from fem.render.pixels import centreline, faint_extent
    from fem.render.scene import DISPLAY_AMPLITUDE, sample_field

    cols, rows = centreline(img)
    root_row = rows[:5].mean()
    c0, c1 = cols.min(), faint_extent(img, root_row)[1]
    px_per_m = (c1 - c0) / L
    x, w = sample_field(fe, res.shapes[:, r], "w")
    scale = DISPLAY_AMPLITUDE["bending"] * L / np.abs(w).max()
    inner = (cols > c0 + 10) & (cols < c1 - 20)
    xc = (cols[inner] - c0) / px_per_m
    expected = root_row - scale * np.interp(xc, x, w) * px_per_m
    full = DISPLAY_AMPLITUDE["bending"] * L * px_per_m
    x_tip = 0.97 * L
    col_tip = int(round(c0 + x_tip * px_per_m))
    tip_measured = rows[np.argmin(np.abs(cols - col_tip))] - root_row
    tip_expected = -scale * np.interp(x_tip, x, w) * px_per_m
    return {"rms": float(np.sqrt(np.mean((rows[inner] - expected) ** 2)) / full),
            "tip_measured": float(tip_measured), "tip_expected": float(tip_expected), "full": float(full)}


@case("render-pixels", group="render")
def render_pixels():
    """Off-screen PNGs of a cantilever's modes 1 and 2 (no display): the pictures differ
    (more than 2 % of the pixels change), and the body's centre line (midpoint of its upper
    and lower edge in each pixel column) read back from the pixels follows the computed
    shape.  Tolerances, relative to the displayed amplitude (0.15 L, about 160 px): the tip
    row of mode 2 (at x = 0.97 L) within 3 % (5 px: half a pixel per edge, antialiasing,
    and the x calibration from the tube's end, which a tilted end cap blurs by ~2 px; the
    slope there is ~0.6, so 2 px in x are ~1.2 px in the row; measured 1.1 %); the RMS
    deviation along the whole shaft within 4 % (the same, plus the steeper parts of the
    curve; measured 0.1-1 %).  As a control, mode 2's picture must NOT match mode 1's
    shape (RMS deviation > 30 %)."""
    from fem.render.pixels import difference_fraction

    fe, res, imgs = cantilever_pictures()
    frac = difference_fraction(*imgs)
    out = [claim("render-pixels", "issue 6 case 3", "PNG of mode 1 and mode 2 differ (> 2 % of pixels)",
                 frac > 0.02, note=f"{100 * frac:.1f} % of the pixels differ")]
    for r in (0, 1):
        cmp = picture_vs_shape(fe, res, imgs[r], r)
        out.append(check("render-pixels", "issue 6 case 3", f"mode {r + 1}: RMS of centre line vs shape / amplitude",
                         0.0, cmp["rms"], 0.04, scale=1.0))
    cmp = picture_vs_shape(fe, res, imgs[1], 1)
    out.append(check("render-pixels", "issue 6 case 3", "mode 2: tip row offset in the picture [px]",
                     cmp["tip_expected"], cmp["tip_measured"], 0.03, scale=cmp["full"]))
    wrong = picture_vs_shape(fe, res, imgs[1], 0)
    out.append(claim("render-pixels", "issue 6 case 3", "control: mode 2 picture does not match mode 1 shape",
                     wrong["rms"] > 0.3, note=f"RMS deviation {wrong['rms']:.2f} of the amplitude"))
    return out
