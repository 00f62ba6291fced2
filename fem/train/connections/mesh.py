"""Gear mesh: the line of action of two gears (lateral-torsional coupling), its stiffness (constant or
periodic at the tooth-pass frequency), damping, backlash on both flanks and static transmission error.

Geometry (docs/geared.md, "Conventions").  Gear a on port a, gear b on port b; transverse pressure
angle alpha_t = atan(tan alpha_n / cos beta), base helix angle beta_b = atan(tan beta cos alpha_t),
base radii r_b (given, or r_b = m_n z cos alpha_t / (2 cos beta) from teeth and normal module), pitch
radii r_p = r_b / cos alpha_t.  e_p is the unit vector from gear a's centre to the pitch point: towards
b's centre (external) or away from it (internal); t = x_hat x e_p.  The drive flank's line of action

    n = cos(beta_b) (cos(alpha_t) t + sin(alpha_t) e_p) + hand sin(beta_b) x_hat

(flank = -1 mirrors the transverse part about e_p), and the mesh compression is the relative
displacement of the two gears' material points at the contact point P along n (rigid gears):

    s = delta_a - delta_b,   delta_i = n . u_i + (r_i x n) . theta_i,   r_i = P - C_i

(r_i x n is the same for every point of the line).  So s = r_b,a cos(beta_b) theta_a +- r_b,b cos(beta_b)
theta_b + n . (u_a - u_b) + tilt terms (helical only), + for external, - for internal pairs.  The
coast flank's line n_c reverses the tangential and axial parts of n (same separating radial part).

Law along s: F = -k(t) h(s - e(t)) - c s' (Kahraman & Singh 1990, 1991): h the backlash function
(total backlash b along the line of action, half on each flank), k(t) = k (1 + sum_h a_h cos(h w_m t)
+ b_h sin(h w_m t)) at the tooth-pass frequency w_m = z_a |Omega_a|, e(t) = sum_h e_h sin(h w_m t + phi_h)
the static transmission error.  With lateral DOFs at either gear the two flanks act along their own
lines (two one-sided contacts); without them the coast line is the drive line reversed and the mesh is
one two-sided gap (textbook (11.1)).  The viscous damping acts always along the drive line (Kahraman &
Singh) or, with ``damping_in_contact``, in contact only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from discrete import checks
from discrete.errors import ModelError
from discrete.nonsmooth.elements import MeshContact

from .base import Connection, Coord, ElementPart, Excitation, coord

MOTIONS = ("ux", "uy", "uz", "rx", "ry", "rz")


def rectangular_variation(contact_ratio: float, depth: float, harmonics: int) -> tuple:
    """Fourier coefficients ((h, a_h, b_h), ...) of k(t)/k - 1 = depth r(t) with r the zero-mean
    rectangular wave of the contact ratio eps in (1, 2): double contact over the first eps - 1 of each
    mesh period (r = 2 - eps), single contact over the rest (r = 1 - eps); r's peak-to-peak is 1, so
    ``depth`` = (k_double - k_single) / k_mean.  a_h = depth sin(2 pi h d)/(pi h),
    b_h = depth (1 - cos(2 pi h d))/(pi h), d = eps - 1 (truncated after ``harmonics`` terms)."""
    d = contact_ratio - 1.0
    out = []
    for h in range(1, harmonics + 1):
        a = depth * math.sin(2 * math.pi * h * d) / (math.pi * h)
        b = depth * (1.0 - math.cos(2 * math.pi * h * d)) / (math.pi * h)
        out.append((h, a, b))
    return tuple(out)


@dataclass
class GearMesh(Connection):
    """A gear pair between ports a and b (see the module docstring).  Lengths in m, angles in rad,
    stiffness N/m and damping N s/m along the line of action."""

    stiffness: float = 0.0
    damping: float = 0.0
    base_radius: tuple | None = None
    teeth: tuple | None = None
    module: float | None = None
    pressure_angle: float = math.radians(20.0)
    helix_angle: float = 0.0
    hand: int = 1
    internal: bool = False
    flank: int = 1
    line_of_centres: float | None = None
    backlash: float = 0.0
    damping_in_contact: bool = False
    variation: tuple = ()
    transmission_error: tuple = ()

    table = "mesh"

    def check(self, train) -> None:
        super().check(train)
        w = self.where
        if any(p.is_ground for p in self.ports):
            raise ModelError(w, "between", [p.describe() for p in self.ports], "two gears (shaft nodes or bodies), "
                             "not the ground")
        self.stiffness = checks.positive(w, "stiffness", self.stiffness, "mean mesh stiffness along the line of "
                                         "action, N/m")
        self.damping = checks.non_negative(w, "damping", self.damping, "mesh damping, N s/m")
        self.pressure_angle = checks.bounded(w, "pressure_angle", self.pressure_angle, (">", 0.0),
                                             ("<", math.pi / 2), "normal pressure angle, rad")
        self.helix_angle = checks.bounded(w, "helix_angle", self.helix_angle, (">=", 0.0), ("<", math.pi / 2),
                                          "helix angle, rad")
        for key in ("hand", "flank"):
            v = getattr(self, key)
            if isinstance(v, bool) or v not in (1, -1):
                raise ModelError(w, key, v, "+1 or -1")
        self.backlash = checks.non_negative(w, "backlash", self.backlash, "total backlash along the line of "
                                            "action, m")
        if self.teeth is not None:
            z = np.asarray(self.teeth)
            if z.shape != (2,) or z.dtype.kind not in "iu" or np.any(z < 1):
                raise ModelError(w, "teeth", self.teeth, "[z_a, z_b]: two tooth counts >= 1 (integers)")
            self.teeth = (int(z[0]), int(z[1]))
        if self.base_radius is not None:
            r = checks.vector(w, "base_radius", self.base_radius, 2, "base radii [r_a, r_b], m")
            if np.any(r <= 0):
                raise ModelError(w, "base_radius", r.tolist(), "two base radii > 0 (m)")
            self.base_radius = (float(r[0]), float(r[1]))
            if self.module is not None:
                raise ModelError(w, "module", self.module, "either base_radius or teeth with module, not both")
        else:
            if self.teeth is None or self.module is None:
                raise ModelError(w, "base_radius", None, "base_radius = [r_a, r_b] (m) or teeth = [z_a, z_b] with "
                                 "module = .. (normal module, m)")
            self.module = checks.positive(w, "module", self.module, "normal module, m")
        if self.internal and self.radii()[0][1] <= self.radii()[0][0]:
            raise ModelError(w, "internal", True, "gear b (the ring) larger than gear a (the pinion)")
        if self.line_of_centres is not None:
            self.line_of_centres = checks.finite(w, "line_of_centres", self.line_of_centres, "angle of the line "
                                                 "of centres from +y towards +z, rad")
        var = []
        for row in self.variation:
            if len(row) != 3:
                raise ModelError(w, "variation", list(row), "rows [harmonic, a_h, b_h]")
            h, a, b = row
            if isinstance(h, bool) or int(h) != h or h < 1:
                raise ModelError(w, "variation", list(row), "harmonic numbers >= 1 of the tooth-pass frequency")
            var.append((int(h), checks.finite(w, "variation", a), checks.finite(w, "variation", b)))
        self.variation = tuple(var)
        if sum(math.hypot(a, b) for _, a, b in var) >= 1.0:
            raise ModelError(w, "variation", [list(r) for r in var], "Fourier coefficients with sum of "
                             "sqrt(a_h^2 + b_h^2) < 1 (the mesh stiffness stays positive)")
        ste = []
        for row in self.transmission_error:
            if len(row) != 3:
                raise ModelError(w, "transmission_error", list(row), "rows [harmonic, amplitude (m), phase (rad)]")
            h, e, ph = row
            if isinstance(h, bool) or int(h) != h or h < 1:
                raise ModelError(w, "transmission_error", list(row), "harmonic numbers >= 1 of the tooth-pass "
                                 "frequency")
            ste.append((int(h), checks.finite(w, "transmission_error", e), checks.finite(w, "transmission_error", ph)))
        self.transmission_error = tuple(ste)
        if (self.variation or self.transmission_error) and self.teeth is None:
            raise ModelError(w, "teeth", None, "teeth = [z_a, z_b] for a stiffness variation or transmission error "
                             "(the tooth-pass frequency is z_a times gear a's speed)")

    # ------------------------------------------------------------------ geometry
    def transverse_angles(self) -> tuple[float, float]:
        """(alpha_t, beta_b): transverse pressure angle and base helix angle, rad."""
        at = math.atan(math.tan(self.pressure_angle) / math.cos(self.helix_angle))
        bb = math.atan(math.tan(self.helix_angle) * math.cos(at))
        return at, bb

    def radii(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """((r_b,a, r_b,b), (r_p,a, r_p,b)): base and pitch radii, m."""
        at, _ = self.transverse_angles()
        if self.base_radius is not None:
            rb = self.base_radius
        else:
            rp = tuple(self.module * z / (2.0 * math.cos(self.helix_angle)) for z in self.teeth)
            rb = tuple(r * math.cos(at) for r in rp)
        return rb, tuple(r / math.cos(at) for r in rb)

    @property
    def ratio_of_radii(self) -> float:
        rb, _ = self.radii()
        return rb[0] / rb[1]

    def speed_ratio(self) -> float:
        """omega_b / omega_a: -r_b,a / r_b,b (external), +r_b,a / r_b,b (internal)."""
        return self.ratio_of_radii if self.internal else -self.ratio_of_radii

    def geometry(self, ts) -> dict:
        """Line of centres e_p, tangent t, lines of action n (drive) and n_c (coast), lever arms r_a, r_b
        (3-vectors in the train frame)."""
        ka, kb = ts.port(self.ports[0]), ts.port(self.ports[1])
        ca, cb = np.asarray(ka.centre_yz, float), np.asarray(kb.centre_yz, float)
        d = cb - ca
        dist = float(np.hypot(*d))
        if dist > 0 and ka.shaft is not None and kb.shaft is not None and self.line_of_centres is None:
            u = d / dist
        else:
            phi = self.line_of_centres or 0.0
            u = np.array([math.cos(phi), math.sin(phi)])
        ep = -u if self.internal else u
        e3 = np.array([0.0, ep[0], ep[1]])
        x = np.array([1.0, 0.0, 0.0])
        t = np.cross(x, e3)
        at, bb = self.transverse_angles()
        rb, rp = self.radii()
        n = math.cos(bb) * (math.cos(at) * t + self.flank * math.sin(at) * e3) + self.hand * math.sin(bb) * x
        nc = math.cos(bb) * (-math.cos(at) * t + self.flank * math.sin(at) * e3) - self.hand * math.sin(bb) * x
        P = rp[0] * e3                       # pitch point relative to gear a's centre (transverse plane)
        ra = P
        rbv = rp[1] * e3 if self.internal else -rp[1] * e3     # P - C_b (C_b = C_a + (r_pa + r_pb) e_p external,
        #                                                        C_a - (r_pb - r_pa) e_p internal)
        return {"e": e3, "t": t, "n": n, "n_coast": nc, "r_a": ra, "r_b": rbv, "centre_distance": dist,
                "pitch_radius": rp, "base_radius": rb}

    def _coordinate(self, ts, n, label, k, c) -> Coord:
        g = self.geometry(ts)
        parts = []
        for port, r, sign in ((self.ports[0], g["r_a"], 1.0), (self.ports[1], g["r_b"], -1.0)):
            kin = ts.port(port)
            rn = np.cross(r, n)
            comp = {"ux": n[0], "uy": n[1], "uz": n[2], "rx": rn[0], "ry": rn[1], "rz": rn[2]}
            for m in MOTIONS:
                for dof, factor in kin.motions.get(m, ()):
                    parts.append((dof, sign * factor * comp[m]))
        return coord(parts, label, k, c)

    def lateral(self, ts) -> bool:
        """Whether either gear has a DOF besides its rotation about x (then the flanks act on their own lines)."""
        return any(m != "rx" and ts.port(p).motions.get(m) for p in self.ports for m in MOTIONS)

    def isotropic(self, ts) -> bool:
        """A line of action is one direction: with lateral DOFs the mesh is anisotropic."""
        return not self.lateral(ts)

    def coordinates(self, ts) -> list[Coord]:
        g = self.geometry(ts)
        return [self._coordinate(ts, g["n"], "line of action", self.stiffness, self.damping)]

    def coast_coordinate(self, ts) -> Coord:
        g = self.geometry(ts)
        return self._coordinate(ts, g["n_coast"], "coast flank", self.stiffness, 0.0)

    def tooth_pass(self, ts, speed: float) -> float:
        """w_m = z_a |Omega_a| at the reference speed ``speed`` (rad/s)."""
        if self.teeth is None:
            return 0.0
        return self.teeth[0] * abs(ts.ratio_of(self.ports[0])) * abs(float(speed))

    # ------------------------------------------------------------------ excitations and modulations
    def excitations(self, ts, speed: float) -> list[Excitation]:
        w = self.tooth_pass(ts, speed)
        loa = self.coordinates(ts)[0]
        return [Excitation(key=f"{self.name}:te{h}", coord=loa, harmonic=h, amplitude=e, phase=ph, omega=h * w,
                           stiffness=self.stiffness, damping=self.damping)
                for h, e, ph in self.transmission_error if e != 0.0]

    def modulations(self, ts) -> list:
        """[(coordinate, k, ((h, a_h, b_h), ...))]: K(t) = K + k (sum a_h cos + b_h sin) g g^T in the closed state."""
        if not self.variation or self.linear_state == "open":
            return []
        return [(self.coordinates(ts)[0], self.stiffness, self.variation)]

    # ------------------------------------------------------------------ time simulation
    def nonsmooth(self, ts, speed: float = 0.0):
        loa = self.coordinates(ts)[0]
        exo = {f"{self.name}:te{h}": -1.0 for h, e, _ in self.transmission_error if e != 0.0}
        w = self.tooth_pass(ts, speed)
        if self.variation and not w > 0:
            raise ModelError(self.where, "variation", [list(r) for r in self.variation],
                             "a running train for a stiffness variation in time ([train] speed or speed_rpm > 0: the "
                             "tooth-pass frequency)")
        law = dict(k=self.stiffness, harmonics=self.variation, omega=w if self.variation else 0.0)
        if self.backlash == 0:
            if not self.variation:
                return [Coord(loa.idx, loa.val, loa.label, self.stiffness, self.damping)], [], exo
            lin = [Coord(loa.idx, loa.val, loa.label, 0.0, self.damping)]
            return lin, [ElementPart(MeshContact, self.name, dict(law, engaged=True), loa, exo)], exo
        half = 0.5 * self.backlash
        c_el = self.damping if self.damping_in_contact else 0.0
        lin = [] if self.damping_in_contact or self.damping == 0 else [Coord(loa.idx, loa.val, loa.label, 0.0,
                                                                             self.damping)]
        if not self.lateral(ts):
            return lin, [ElementPart(MeshContact, self.name, dict(law, c=c_el, lower=-half, upper=half), loa, exo)], exo
        coast = self.coast_coordinate(ts)
        exo_c = {k: -v for k, v in exo.items()}
        return lin, [ElementPart(MeshContact, f"{self.name}:drive", dict(law, c=c_el, lower=-math.inf, upper=half),
                                 loa, exo),
                     ElementPart(MeshContact, f"{self.name}:coast", dict(law, c=c_el, lower=-math.inf, upper=half),
                                 coast, exo_c)], exo

    # ------------------------------------------------------------------ loads
    def mesh_force(self, ts, q, v, t, exo_values: dict, speed: float = 0.0) -> np.ndarray:
        """The mesh force (N): compression of the drive flank positive, of the coast flank negative,
        by the mesh's own law at DOF histories q, v (n, m) and times t; ``exo_values``: {key: (e, e')}
        of the transmission error's prescribed coordinates."""
        t = np.atleast_1d(np.asarray(t, float))
        loa = self.coordinates(ts)[0]
        e = sum((exo_values[k][0] for k in exo_values if k.startswith(f"{self.name}:te")), np.zeros(t.size))
        ed = sum((exo_values[k][1] for k in exo_values if k.startswith(f"{self.name}:te")), np.zeros(t.size))
        s, sd = loa.of(q) - e, loa.of(v) - ed
        w = self.tooth_pass(ts, speed)
        k = MeshContact(self.name, np.zeros(1), k=self.stiffness, harmonics=self.variation,
                        omega=w if self.variation else 0.0, engaged=True).stiffness_at(t) \
            if self.variation and w > 0 else self.stiffness * np.ones(t.size)
        half = 0.5 * self.backlash
        if self.backlash == 0:
            return k * s + self.damping * sd
        c_el = self.damping if self.damping_in_contact else 0.0
        if not self.lateral(ts):
            d = np.where(s > half, s - half, 0.0) + np.where(s < -half, s + half, 0.0)
            on = d != 0
            return k * d + (c_el * sd * on if c_el else 0.0) + (0.0 if self.damping_in_contact else self.damping * sd)
        coast = self.coast_coordinate(ts)
        sc, scd = coast.of(q) + e, coast.of(v) + ed
        dd = np.maximum(s - half, 0.0)
        dc = np.maximum(sc - half, 0.0)
        fd = k * dd + (c_el * sd * (dd > 0) if c_el else 0.0)
        fc = k * dc + (c_el * scd * (dc > 0) if c_el else 0.0)
        return fd - fc + (0.0 if self.damping_in_contact else self.damping * sd)
