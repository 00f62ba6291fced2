"""Independent dense assembly of a geared rotor train (validation case geared-lateral-torsional).

Written from the closed forms in the literature, not from the package's assembly:

* Timoshenko shaft element, uniform, one bending plane (displacement, slope) at its two nodes:
  Friswell, Penny, Garvey & Lees, *Dynamics of Rotating Machines* (CUP 2010), §5.4.3 (after Nelson
  1980), with Phi = 12 E I / (kappa G A L^2):

      K  = E I / ((1 + Phi) L^3) [[12, 6L, -12, 6L], [6L, (4+Phi)L^2, -6L, (2-Phi)L^2], ...]
      M_T = rho A L / (840 (1 + Phi)^2) [[m1, m2 L, m3, -m4 L], ...]   (m1 .. m6 below)
      M_R = rho I / (30 (1 + Phi)^2 L) [[36, m7 L, -36, m7 L], ...]   (m7 .. m9 below)

  the gyroscopic matrix from M_R with rho I_p = 2 rho I coupling the two planes (skew);
  Cowper's shear coefficient of the hollow circle (Cowper, J. Appl. Mech. 33 (1966) 335).
* Linear rod elements for torsion (G J, rho I_p) and axial motion (E A, rho A).
* Rigid discs (m on u, v, w; I_d on the tilts; I_p on the torsion; gyroscopic I_p), bearings
  (k_yy, k_zz, c_yy, c_zz on v, w).
* The gear mesh as a spring k along the line of action, its direction written out in components
  for a line of centres at the angle phi from +y (towards +z): with the transverse pressure angle
  alpha_t and the base helix angle beta_b,

      n = (h sin b_b,  cos b_b sin(alpha_t - phi),  cos b_b cos(alpha_t - phi)),

  and the coefficients of the mesh deflection on gear a's (u, v, w, theta_x, theta_y, theta_z):
  (n_x, n_y, n_z, r_b,a cos b_b, h r_p,a sin b_b sin phi, -h r_p,a sin b_b cos phi); on gear b
  (external pair) the negated translations and tilts with r_p,b -> -r_p,b and the torsion
  + r_b,b cos b_b (the rigid-body rotation theta_b = -(r_b,a / r_b,b) theta_a leaves it free).

DOFs: node-major (u, v, w, theta_x, theta_y, theta_z) per node, shaft a then shaft b -- the order of
the package's rotor (so the two assemblies can be compared entry by entry).  Eigenvalues from the
dense first-order form by scipy.linalg.eig (a second, independent solver).
"""
from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla

FIELDS = ("u", "v", "w", "theta_x", "theta_y", "theta_z")


def cowper(nu: float, ratio: float = 0.0) -> float:
    """Cowper's shear coefficient of a hollow circle (ratio = di / d)."""
    m2 = ratio ** 2
    return 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)


def timoshenko_plane(E, G, rho, d, di, L):
    """(K, M_T + M_R, R = M_R / (rho I)) of one uniform element in one plane (closed form, Friswell 2010)."""
    A = math.pi * (d ** 2 - di ** 2) / 4
    I = math.pi * (d ** 4 - di ** 4) / 64
    nu = E / (2 * G) - 1
    kappa = cowper(nu, di / d)
    P = 12 * E * I / (kappa * G * A * L ** 2)
    K = E * I / ((1 + P) * L ** 3) * np.array([
        [12, 6 * L, -12, 6 * L],
        [6 * L, (4 + P) * L ** 2, -6 * L, (2 - P) * L ** 2],
        [-12, -6 * L, 12, -6 * L],
        [6 * L, (2 - P) * L ** 2, -6 * L, (4 + P) * L ** 2]])
    m1 = 312 + 588 * P + 280 * P ** 2
    m2 = 44 + 77 * P + 35 * P ** 2
    m3 = 108 + 252 * P + 140 * P ** 2
    m4 = 26 + 63 * P + 35 * P ** 2
    m5 = 8 + 14 * P + 7 * P ** 2
    m6 = 6 + 14 * P + 7 * P ** 2
    MT = rho * A * L / (840 * (1 + P) ** 2) * np.array([
        [m1, m2 * L, m3, -m4 * L],
        [m2 * L, m5 * L ** 2, m4 * L, -m6 * L ** 2],
        [m3, m4 * L, m1, -m2 * L],
        [-m4 * L, -m6 * L ** 2, -m2 * L, m5 * L ** 2]])
    m7 = 3 - 15 * P
    m8 = 4 + 5 * P + 10 * P ** 2
    m9 = 1 + 5 * P - 5 * P ** 2
    R = 1.0 / (30 * (1 + P) ** 2 * L) * np.array([
        [36, m7 * L, -36, m7 * L],
        [m7 * L, m8 * L ** 2, -m7 * L, -m9 * L ** 2],
        [-36, -m7 * L, 36, -m7 * L],
        [m7 * L, -m9 * L ** 2, -m7 * L, m8 * L ** 2]])
    return K, MT + rho * I * R, rho * 2 * I * R


def dense_rotor(shaft: dict):
    """M, K, C, G (dense, full DOFs) of one rotor described by ``shaft``: ``segments`` [(L, n_el, d, di)],
    ``E``, ``G``, ``rho``, ``discs`` [(x, m, Id, Ip)], ``bearings`` [(x, kyy, kzz, cyy, czz)]."""
    E, Gm, rho = shaft["E"], shaft["G"], shaft["rho"]
    xs = [0.0]
    elems = []
    for L, n_el, d, di in shaft["segments"]:
        for _ in range(n_el):
            elems.append((L / n_el, d, di))
            xs.append(xs[-1] + L / n_el)
    nn = len(xs)
    n = 6 * nn
    M, K, C, G = (np.zeros((n, n)) for _ in range(4))

    def idx(node, f):
        return 6 * node + FIELDS.index(f)

    S = np.diag([1.0, -1.0, 1.0, -1.0])
    for e, (L, d, di) in enumerate(elems):
        Kp, Mp, Pp = timoshenko_plane(E, Gm, rho, d, di, L)
        y = [idx(e, "v"), idx(e, "theta_z"), idx(e + 1, "v"), idx(e + 1, "theta_z")]
        z = [idx(e, "w"), idx(e, "theta_y"), idx(e + 1, "w"), idx(e + 1, "theta_y")]
        K[np.ix_(y, y)] += Kp
        M[np.ix_(y, y)] += Mp
        K[np.ix_(z, z)] += S @ Kp @ S
        M[np.ix_(z, z)] += S @ Mp @ S
        # theta_z = slope of v, theta_y = -slope of w: G[theta_y rows, theta_z cols] = +rho Ip int N_ty^T N_tz
        G[np.ix_(y, z)] += Pp @ S
        G[np.ix_(z, y)] += -S @ Pp
        A = math.pi * (d ** 2 - di ** 2) / 4
        J = math.pi * (d ** 4 - di ** 4) / 32
        for f, stiff, inert in (("u", E * A, rho * A), ("theta_x", Gm * J, rho * J)):
            ii = [idx(e, f), idx(e + 1, f)]
            K[np.ix_(ii, ii)] += stiff / L * np.array([[1, -1], [-1, 1]])
            M[np.ix_(ii, ii)] += inert * L / 6 * np.array([[2, 1], [1, 2]])

    def node(x):
        k = int(np.argmin(np.abs(np.asarray(xs) - x)))
        assert abs(xs[k] - x) < 1e-9
        return k

    for x, m, Id, Ip in shaft.get("discs", ()):
        k = node(x)
        for f in ("u", "v", "w"):
            M[idx(k, f), idx(k, f)] += m
        for f in ("theta_y", "theta_z"):
            M[idx(k, f), idx(k, f)] += Id
        M[idx(k, "theta_x"), idx(k, "theta_x")] += Ip
        G[idx(k, "theta_y"), idx(k, "theta_z")] += Ip
        G[idx(k, "theta_z"), idx(k, "theta_y")] -= Ip
    for x, kyy, kzz, cyy, czz in shaft.get("bearings", ()):
        k = node(x)
        K[idx(k, "v"), idx(k, "v")] += kyy
        K[idx(k, "w"), idx(k, "w")] += kzz
        C[idx(k, "v"), idx(k, "v")] += cyy
        C[idx(k, "w"), idx(k, "w")] += czz
    return M, K, C, G, np.asarray(xs)


def mesh_vectors(mesh: dict):
    """Coefficients of the mesh deflection on gear a's and gear b's (u, v, w, theta_x, theta_y, theta_z)
    for an external pair (see the module docstring); ``mesh``: base_radius (r_a, r_b), pressure_angle
    (normal), helix_angle, hand (+-1), line_of_centres phi (rad)."""
    an, beta = mesh["pressure_angle"], mesh.get("helix_angle", 0.0)
    h = mesh.get("hand", 1)
    phi = mesh.get("line_of_centres", 0.0)
    at = math.atan(math.tan(an) / math.cos(beta))
    bb = math.atan(math.tan(beta) * math.cos(at))
    rba, rbb = mesh["base_radius"]
    rpa, rpb = rba / math.cos(at), rbb / math.cos(at)
    nx, ny, nz = h * math.sin(bb), math.cos(bb) * math.sin(at - phi), math.cos(bb) * math.cos(at - phi)
    va = np.array([nx, ny, nz, rba * math.cos(bb), h * rpa * math.sin(bb) * math.sin(phi),
                   -h * rpa * math.sin(bb) * math.cos(phi)])
    vb = np.array([-nx, -ny, -nz, rbb * math.cos(bb), h * rpb * math.sin(bb) * math.sin(phi),
                   -h * rpb * math.sin(bb) * math.cos(phi)])
    return va, vb


def dense_train(shaft_a: dict, shaft_b: dict, mesh: dict):
    """M, K, C, G(Omega = 1) of two rotors joined by a mesh at ``mesh['x']`` = (x_a, x_b): shaft b turns at
    ``mesh['ratio']`` times shaft a's speed (its gyroscopic matrix scaled by it)."""
    Ma, Ka, Ca, Ga, xa = dense_rotor(shaft_a)
    Mb, Kb, Cb, Gb, xb = dense_rotor(shaft_b)
    na, nb = Ma.shape[0], Mb.shape[0]
    M = sla.block_diag(Ma, Mb)
    K = sla.block_diag(Ka, Kb)
    C = sla.block_diag(Ca, Cb)
    G = sla.block_diag(Ga, mesh["ratio"] * Gb)
    ka = int(np.argmin(np.abs(xa - mesh["x"][0])))
    kb = int(np.argmin(np.abs(xb - mesh["x"][1])))
    g = np.zeros(na + nb)
    va, vb = mesh_vectors(mesh)
    g[6 * ka:6 * ka + 6] = va
    g[na + 6 * kb:na + 6 * kb + 6] = vb
    K = K + mesh["stiffness"] * np.outer(g, g)
    return M, K, C, G


def eigenvalues(M, K, C, G, speed: float, shift: float = -1.0) -> np.ndarray:
    """All eigenvalues with Im >= 0 of M q'' + (C + speed G) q' + K q = 0, dense: scipy.linalg.eig of
    (A - s B)^-1 B for the first-order form A z = lam B z, A = [[0, I], [-K, -D]], B = [[I, 0], [0, M]]
    (lam = s + 1/mu), so that the low eigenvalues are the large mu and are resolved to round-off of
    their own size (a plain eig of A, B loses ~ eps ||K|| / ||M|| in every eigenvalue).  Sorted by
    modulus; the rigid-body eigenvalues (mu = -1/s) come out as lam = 0 up to round-off."""
    n = M.shape[0]
    D = C + speed * G
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -D]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    mu = sla.eig(sla.solve(A - shift * B, B), right=False)
    mu = mu[np.abs(mu) > 0]
    lam = shift + 1.0 / mu
    lam = lam[lam.imag >= -1e-9 * np.abs(lam).max()]
    return lam[np.argsort(np.abs(lam))]
