"""Seed 002 (Khromov, Khromov, Kovryzhenko 2012): the spool with a tension-only strand and a friction
clutch under the kinematic excitation a sin(w1 t) -- data, derived parameters and the chosen reading.

Printed data: J = 0.03 kg m^2, r = 0.045 m, k = 54.15 1/s (T = 0.116 s), F0 = 30 N; friction
coefficients of the strand B_n1 = 0.0034, B_n2 = 7, B_n3 = 172 (the label "B_3n" is printed among the
support's coefficients: garbled), of the support C1 = 5.697e-3, C2 = 0.152, C3 = 0.087; the simplified,
energy-equivalent model B_n2 = 7.7 kg/s, C2 = 0.22 kg/s, all others zero.

Derived / chosen (documented in docs/steady.md):
* strand stiffness c = k^2 J / r^2 = 43 440 N/m (the spool's natural frequency k with the taut strand);
* clutch torque M0 = F0 r = 1.35 N m (it holds the static tension F0); the clutch disc runs at
  omega0 = 100 rad/s, far above the spool's speed (|phi'| < 5 rad/s), so sign(omega0 - phi') = 1 always;
* tension T = F0 + c (r phi - x_cam) while positive, zero while slack (the printed condition "phi < 0"
  is read as a condition on the strand elongation: the printed (1)-(2) with phi measured from the
  equilibrium would put the equilibrium at the slack point with zero tension, contradicting F0 = 30 N);
* losses acting on the spool velocity phi' (as printed): torque
  -(r B_n1 + C1) sign phi' - (r^2 B_n2 + C2) phi' - (r^3 B_n3 + C3) sign(phi') phi'^2,
  i.e. kinetic 5.850e-3 N m, viscous 0.16618 N m s, quadratic 0.10267 N m s^2 (combined model);
  viscous 0.235593 N m s only (simplified model);
* mu = T_max / F0 with T_max the largest tension over the steady cycle; z = w1 / k.
"""
from __future__ import annotations


J, R, K_NAT, F0 = 0.03, 0.045, 54.15, 30.0
C_STRAND = K_NAT ** 2 * J / R ** 2
M0 = F0 * R
OMEGA0 = 100.0
B1, B2, B3 = 0.0034, 7.0, 172.0
C1, C2, C3 = 5.697e-3, 0.152, 0.087
SIMPLE = {"viscous": 0.22 + 7.7 * R ** 2}
COMBINED = {"kinetic": R * B1 + C1, "viscous": R * R * B2 + C2, "quadratic": R ** 3 * B3 + C3}
AMPLITUDES = (1e-4, 4.7e-4, 7e-4, 8.6e-4)


def seed002_doc(a: float, friction: str = "simple", z=(0.3, 2.0), method: str = "hb", harmonics: int = 15,
                **steady) -> dict:
    """Model file (dict) of the spool for cam amplitude a and friction model 'simple' | 'combined'."""
    d = {"title": f"seed 002 spool, a = {a:g} m, {friction} friction",
         "body": [{"name": "spool", "inertia": J}],
         "driver": [{"name": "cam", "amplitude": a, "omega": K_NAT}],
         "one_sided": [{"name": "strand", "between": ["cam", "spool"], "ratios": [1.0, R], "k": C_STRAND,
                        "preload": F0, "side": "tension"}],
         "friction": [{"name": "clutch", "body": "spool", "kinetic": M0, "surface_velocity": OMEGA0}],
         "steady": {"method": method, "z": list(z), "omega_ref": K_NAT, "harmonics": harmonics,
                    "response": {"element": "strand", "measure": "max", "scale": F0}, **steady}}
    if friction == "simple":
        d["damper"] = [{"between": ["ground", "spool"], "c": SIMPLE["viscous"]}]
    elif friction == "combined":
        d["friction"].append({"name": "losses", "body": "spool", **COMBINED})
    else:
        raise ValueError(friction)
    return d


def linear_mu(a: float, z: float, b: float = SIMPLE["viscous"]) -> float:
    """mu of the always-taut (linear) model with viscous losses b: 1 + c |r phi - x_cam| / F0."""
    w = z * K_NAT
    H = C_STRAND * R * a / complex(C_STRAND * R * R - J * w * w, b * w)   # phi amplitude (complex)
    return 1 + C_STRAND * abs(R * H - a) / F0
