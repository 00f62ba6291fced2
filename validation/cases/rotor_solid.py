"""The 1D rotor (Timoshenko beam elements) against the 3D solid shaft of :mod:`fem.solid` at zero speed."""
from __future__ import annotations

import math

import numpy as np

from fem.model import Segment, ShaftModel
from fem.model import Support as SolidSupport
from fem.rotor import Rotor, ShaftSegment, Support, rotor_modes
from fem.sections import Material, Section
from validation.registry import case, check, claim

SRC = "3D elasticity (fem.solid, 27-node hexahedra) vs the 1D rotor"


@case("rotor-vs-3d-solid", group="rotor", slow=True)
def rotor_vs_solid():
    """Friswell's shaft (steel, L = 1.5 m, d = 50 mm, L/d = 30), simply supported (3D: the end
    sections held transversely, free to rotate; rotor: v = w = 0 at the ends), not spinning:
    the three lowest bending frequencies of the 3D solid (48 quadratic hexahedra along x, 8 around,
    25 899 DOFs) against the rotor's 30 Timoshenko elements.  Beam theory itself differs from 3D
    elasticity by O((d/L)^4) here (< 1e-5), the rotor mesh by < 1e-5 (O(h^4), Phi << 1); what
    remains is the 3D mesh, measured by refinement at 2-3e-4 (24 -> 48 layers moves mode 1 by
    0.9e-4, 8 -> 12 points around by 1.9e-4).  Tolerance 5e-4 (measured -2.0e-4, -0.6e-4, +1.2e-4)."""
    from fem.solid import ShaftMeshSpec, build_solid, solid_modal

    name = "rotor-vs-3d-solid"
    steel = Material(E=211e9, G=81.2e9, rho=7810.0)
    L, d = 1.5, 0.05
    A, I = math.pi * d * d / 4, math.pi * d**4 / 64
    sec = Section(A=A, I=I, J=2 * I, Ip=2 * I, shape="circle", d=d)
    model = ShaftModel("bending", [Segment(L, 48, sec, steel)],
                       supports=[SolidSupport(0.0, "pinned"), SolidSupport(L, "pinned")])
    solid = build_solid(model, ShaftMeshSpec(n_quarter=2, radial=1))
    res = solid_modal(solid, 8)
    bend = res.frequencies_hz[np.array([k == "bending" for k in res.kinds])]
    pairs = bend.size // 2
    split = max(abs(bend[2 * i + 1] / bend[2 * i] - 1) for i in range(pairs)) if pairs else np.inf
    rotor = Rotor([ShaftSegment(L, 30, d, steel)], supports=[Support(0.0), Support(L)])
    m = rotor_modes(rotor, 0.0, 6)
    one_d = np.sort(m.frequencies_hz)[0::2]
    out = [claim(name, SRC, "3D bending modes come in equal pairs (circular section)", split < 1e-6,
                 note=f"largest split {split:.1e}")]
    for j in range(min(3, pairs)):
        out.append(check(name, SRC, f"bending f_{j + 1} [Hz] (1D rotor vs 3D solid)", bend[2 * j], one_d[j], 5e-4))
    return out
