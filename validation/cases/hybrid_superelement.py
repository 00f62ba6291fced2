"""Linear super-elements from matrix files (fem/superelement.py, ``[[superelement]]``): the package's own
shaft matrices exported (Matrix Market and Harwell-Boeing), imported and joined to a shaft, against the
all-shaft models (issue 27, item 3)."""
from __future__ import annotations

import copy
import tempfile
from pathlib import Path

import numpy as np

from discrete.linalg import single_threaded_blas
from fem.assembly import assemble
from fem.modelfile.build.fe import shaft_model
from fem.study import Study
from fem.superelement import read_superelement, write_superelement
from validation.examples import EXAMPLES, example_doc
from validation.registry import case, check, claim

SRC = "the same model with the part as shaft segments"


def _rod_docs(tmp: Path, fmt: str):
    """(all-shaft rod, rod with its last element from matrix files) of hybrid_afc_friction_rod.toml."""
    rod = example_doc("hybrid_afc_friction_rod.toml")
    rod.pop("simulation", None)
    tip = {"title": "rod tip", "material": rod["material"], "model": rod["model"],
           "segment": [{"length": 0.1, "elements": 1, "section": rod["segment"][0]["section"]}]}
    fe = assemble(shaft_model(Study.parse(tip).doc))
    side = write_superelement(tmp / f"tip_{fmt}.json", fe.system, title="rod tip", fmt=fmt)
    split = copy.deepcopy(rod)
    split["segment"] = [dict(rod["segment"][0], length=0.9, elements=9)]
    split["superelement"] = [{"name": "tip", "file": str(side), "join": [{"dof": "u@x=0", "x": 0.9}]}]
    for table in ("friction", "force"):
        for t in split[table]:
            t.pop("x")
            t["body"] = "tip:u@x=0.1"
    split["steady"]["response"] = dict(rod["steady"]["response"], body="tip:u@x=0.1")
    return rod, split, fe.system, side


def _same_curve(label: str, a, b, tol: float, note: str = "") -> list:
    out = [claim(label, SRC, "same number of points, both complete", a.omega.size == b.omega.size and
                 bool(a.completed and b.completed), note=f"{a.omega.size} / {b.omega.size} points")]
    if a.omega.size != b.omega.size:
        return out
    out.append(check(label, SRC, "largest relative difference of the frequencies", 0.0,
                     float(np.max(np.abs(b.omega / a.omega - 1))), tol, scale=1.0))
    out.append(check(label, SRC, "largest difference of the response (relative to the peak)", 0.0,
                     float(np.max(np.abs(b.response - a.response)) / np.max(np.abs(a.response))), tol, scale=1.0,
                     note=note))
    for fa, fb in zip(sorted(f["omega"] for f in a.folds), sorted(f["omega"] for f in b.folds)):
        out.append(check(label, SRC, "fold frequency", fa, fb, tol))
    return out


@case("hybrid_superelement_round_trip", group="hybrid")
def hybrid_superelement_round_trip():
    """Round trip of the package's own FE matrices through matrix files, and the joined models' curves.

    (1) The free DOFs' M and K of an assembled shaft written by ``fem.superelement.write_superelement``
    (Matrix Market .mtx and Harwell-Boeing .rua) and read back: bitwise equal (both formats carry 17
    significant digits).

    (2) examples/hybrid_afc_friction_rod.toml (10 quadratic axial elements, Craig-Bampton 2 modes, HB 15,
    friction damper and force at the tip) with its last element replaced by a super-element: the element
    assembled alone (x = 0 .. 0.1), exported, imported, joined at x = 0.9; damper and force act on the
    super-element's DOF ``tip:u@x=0.1``.  The AFC equals the all-shaft one to 1e-12 (frequencies, response
    relative to the peak), in both formats.  The two systems differ only by the element's position in
    the assembly (its length 0.1 vs 1.0 - 0.9, one rounding of the Jacobian).

    (3) examples/hybrid_afc_superelement.toml: the cantilever of hybrid_afc_vibro_impact.toml with its tail
    (x = 0.3375 .. 0.5, exported from examples/superelement_tail_shaft.toml) from the shipped Matrix Market
    files, stop and force on the super-element's DOFs: the same curve to 1e-10.  Here the Hermite element
    matrices themselves depend on the absolute coordinates (scikit-fem inverts a Vandermonde matrix of the
    node positions): the tail's K assembled at x = 0 and at x = 0.3375 differ by 6e-13 relative, the
    curves by ~4e-12 (the peak amplifies it by the resonance's ~1/(2 zeta) = 10); tolerance 1e-10.  The
    shipped files are checked to be what the export writes today (bitwise)."""
    out = []
    with single_threaded_blas(), tempfile.TemporaryDirectory() as td:
        tmp = Path(td)
        for fmt in ("mtx", "hb"):
            rod, split, system, side = _rod_docs(tmp, fmt)
            se = read_superelement(side, name="tip")
            f = system.free
            worst = max(float(np.max(np.abs((getattr(se, k) - getattr(system, k)[f][:, f]).toarray())))
                        for k in ("M", "K"))
            out.append(check(f"superelement file round trip ({fmt})", "the assembled shaft's matrices",
                             "largest |difference| of M, K after write and read", 0.0, worst, 0.0, scale=1.0))
            a, b = Study.parse(rod).forced(), Study.parse(split).forced()
            out += _same_curve(f"hybrid_afc_friction_rod, tip element from {fmt} files", a, b, 1e-12)
        # the shipped cantilever tail: what the export writes today, and the curve
        tail = Study.load(EXAMPLES / "superelement_tail_shaft.toml")
        fresh = write_superelement(tmp / "tail.json", assemble(shaft_model(tail.doc)).system, title=tail.doc.title)
        shipped = EXAMPLES / "superelement_tail"
        same = all((shipped / p.name).read_bytes() == p.read_bytes() for p in tmp.glob("tail*"))
        out.append(claim("superelement_tail", "python -m fem.superelement examples/superelement_tail_shaft.toml ...",
                         "the shipped files are the export of today's assembly", same, note=str(fresh.name)))
        a = Study.load(EXAMPLES / "hybrid_afc_vibro_impact.toml").forced()
        b = Study.load(EXAMPLES / "hybrid_afc_superelement.toml").forced()
        out += _same_curve("hybrid_afc_superelement (tail from matrix files)", a, b, 1e-10,
                           note="Hermite element matrices differ by 6e-13 with the position (docstring)")
    return out
