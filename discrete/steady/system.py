"""A periodic forced system extracted from a nonsmooth :class:`~discrete.nonsmooth.Problem`, with the
forcing frequency as a free parameter, for the steady-state solvers (harmonic balance, shooting).

Equations on the free DOFs q (drivers x_c(t) = P_c e(t) prescribed, e = [1, t, sin w t, cos w t]):

    M q'' + C q' + K q = -(K_fc x_c + C_fc x_c' + M_fc x_c'') + F_x e(t) + sum_i g_i F_i(s_i, s_i')

with s_i = g_i . q + ge_i . e(t) the coordinate of element i.  ``P``, ``F_x`` and ``ge`` do not depend
on w (they hold amplitudes and phases), only ``e(t)`` and its derivatives do, so one compiled Problem
serves every frequency.  Element force laws for the smooth solvers (HB):

* one-sided spring, gap (exact law): piecewise linear, continuous -- used as they are (AFT handles the
  kink; the Newton Jacobian is the piecewise derivative);
* gap (arctan law (11.2)): as defined;
* Coulomb friction: regularised ``-a0 tanh(w / eps) - a1 w - a2 w|w| - a3 w^2|w|`` (w the slip
  velocity), eps = ``regularisation`` (a stated approximation: the HB branch is compared with exact
  shooting in the validation cases);
* impacts: not supported by HB (use shooting);
* the cubic spring ``F = -k3 s^3`` of the textbook's (8.20) (a smooth element: HB as it is, shooting
  with numerically integrated pieces).

Each element supplies its law (``Element.smooth_force``); this module does not look at their types.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError


@dataclass(frozen=True)
class GridParts:
    """Exogenous terms on a phase grid by powers of omega (:meth:`PeriodicSystem.grid_parts`)."""

    fa: np.ndarray
    fb: np.ndarray
    fc: np.ndarray
    fd: np.ndarray
    sa: np.ndarray
    sb: np.ndarray
    sda: np.ndarray
    sdb: np.ndarray

    def forcing(self, omega):
        return self.fa + self.fb / omega + omega * self.fc + omega * omega * self.fd

    def coords(self, omega):
        """(s_e, s_e') exogenous parts of the element coordinates."""
        return self.sa + self.sb / omega, self.sda + omega * self.sdb


class PeriodicSystem:
    """Free-DOF matrices, driver/force data and elements of a Problem, evaluable at any forcing omega."""

    def __init__(self, problem, regularisation: float = 1e-3):
        p = problem
        if not p.time_invariant:
            raise ModelError("steady", "inertia_rate", "nonzero", "constant inertias for a periodic steady state")
        if len(p.omegas) > 1:
            raise ModelError("steady", "omega", p.omegas, "one common excitation frequency of all drivers and forces")
        if p.ne > 2 and np.any(np.abs(p.P[:, 1]) > 0):
            raise ModelError("steady", "driver.velocity", "nonzero", "drivers without drift (x = V t is not periodic)")
        self.problem = p
        self.n = p.nf
        f, c = p.f, p.c
        self.M, self.C, self.K = p.M0, p.C + p.Cr, p.K
        self.Kfc = p.Kfull[np.ix_(f, c)]
        self.Cfc = p.Cfull[np.ix_(f, c)]
        self.Mfc = p.Mfull[np.ix_(f, c)]
        self.Pc = p.P[c]
        self.Fx = p.Fx
        self.harmonic = p.ne > 2
        self.elements = list(p.elements)
        self.gf = [np.asarray(x, float) for x in p.gf]
        self.ge = [np.asarray(x, float) for x in p.ge]
        self.Pfull = p.P
        self.eps = float(regularisation)
        ne, nel = p.ne, len(self.elements)
        self.Gf = np.array(self.gf, float).reshape(nel, self.n)     # element directions, stacked
        self.Ge = np.array(self.ge, float).reshape(nel, ne)

    @property
    def smooth_ok(self) -> bool:
        """Every element has a smooth (or piecewise-linear continuous) law for harmonic balance."""
        return all(el.smooth_law for el in self.elements)

    # ------------------------------------------------------------ exogenous
    def exo(self, t, omega):
        """e, e', e'' at times t (arrays (ne, m)) for forcing frequency omega."""
        t = np.atleast_1d(np.asarray(t, float))
        ne = self.problem.ne
        e = np.zeros((ne, t.size))
        ed = np.zeros_like(e)
        edd = np.zeros_like(e)
        e[0] = 1.0
        e[1] = t
        ed[1] = 1.0
        if ne > 2:
            s, co = np.sin(omega * t), np.cos(omega * t)
            e[2], e[3] = s, co
            ed[2], ed[3] = omega * co, -omega * s
            edd[2], edd[3] = -omega ** 2 * s, -omega ** 2 * co
        return e, ed, edd

    def forcing(self, t, omega):
        """Linear right-hand side f(t) (n, m) and the element coordinates' exogenous parts."""
        e, ed, edd = self.exo(t, omega)
        xc, xcd, xcdd = self.Pc @ e, self.Pc @ ed, self.Pc @ edd
        f = -(self.Kfc @ xc + self.Cfc @ xcd + self.Mfc @ xcdd) + self.Fx @ e
        if not self.ge:                   # a linear model: no element coordinates
            m = e.shape[1] if e.ndim > 1 else 1
            return f, np.zeros((0, m)), np.zeros((0, m))
        se = np.array([ge @ e for ge in self.ge]).reshape(len(self.ge), -1)
        sde = np.array([ge @ ed for ge in self.ge]).reshape(len(self.ge), -1)
        return f, se, sde

    # ------------------------------------------------------------ elements
    def element_force(self, i, s, sd):
        """Force along s of element i, and its derivatives dF/ds, dF/ds' (smooth/penalty laws)."""
        return self.elements[i].smooth_force(s, sd, self.eps)

    def rhs_terms(self, t, q, v, omega):
        """Sum of element forces on the DOFs (n, m) and Jacobians dFq, dFv (n, n, m)."""
        f, se, sde = self.forcing(t, omega)
        n, m = q.shape
        Fq = np.zeros((n, n, m))
        Fv = np.zeros((n, n, m))
        Fsum = f.copy()
        for i in range(len(self.elements)):
            g = self.gf[i]
            s = g @ q + se[i]
            sd = g @ v + sde[i]
            F, dFs, dFv = self.element_force(i, s, sd)
            Fsum += np.outer(g, F)
            gg = np.outer(g, g)[:, :, None]
            Fq += gg * dFs[None, None, :]
            Fv += gg * dFv[None, None, :]
        return Fsum, Fq, Fv

    def element_series(self, t, q, v, omega):
        """Element forces along s (n_el, m) and coordinates s (n_el, m) at given states."""
        e, ed, _ = self.exo(t, omega)
        se = np.array([ge @ e for ge in self.ge]).reshape(len(self.ge), -1)
        sde = np.array([ge @ ed for ge in self.ge]).reshape(len(self.ge), -1)
        out, ss = [], []
        for i in range(len(self.elements)):
            s = self.gf[i] @ q + se[i]
            sd = self.gf[i] @ v + sde[i]
            out.append(self.element_force(i, s, sd)[0])
            ss.append(s)
        return np.array(out).reshape(len(self.elements), -1), np.array(ss).reshape(len(self.elements), -1)

    def element_laws(self, S, Sd):
        """(F, dF/ds, dF/ds') of every element at coordinates ``S``, ``Sd`` (n_el, ...) at once."""
        F, dFs, dFv = np.empty_like(S), np.empty_like(S), np.empty_like(S)
        for i, el in enumerate(self.elements):
            F[i], dFs[i], dFv[i] = el.smooth_force(S[i], Sd[i], self.eps)
        return F, dFs, dFv

    def grid_parts(self, theta, nu: int = 1) -> "GridParts":
        """The exogenous terms on a grid of phases ``theta`` of the period ``nu 2 pi / omega``
        (t = nu theta / omega), split by their power of omega so one grid serves every frequency:
        ``f = fa + fb / w + w fc + w^2 fd`` (the linear right-hand side of the module docstring),
        ``s_e = sa + sb / w`` and ``s_e' = sda + w sdb`` (the elements' exogenous coordinates).
        Exact: e = [1, t, sin w t, cos w t] with w t = nu theta."""
        th = np.asarray(theta, float)
        ne = self.problem.ne
        E0, Et, Ed0, Ed1, Edd2 = (np.zeros((ne, th.size)) for _ in range(5))
        E0[0] = 1.0
        Et[1] = nu * th
        Ed0[1] = 1.0
        if ne > 2:
            sn, cs = np.sin(nu * th), np.cos(nu * th)
            E0[2], E0[3] = sn, cs
            Ed1[2], Ed1[3] = cs, -sn
            Edd2[2], Edd2[3] = -sn, -cs
        KP, CP, MP = self.Kfc @ self.Pc, self.Cfc @ self.Pc, self.Mfc @ self.Pc
        lin0 = self.Fx - KP
        return GridParts(fa=lin0 @ E0 - CP @ Ed0, fb=lin0 @ Et, fc=-CP @ Ed1, fd=-MP @ Edd2,
                         sa=self.Ge @ E0, sb=self.Ge @ Et, sda=self.Ge @ Ed0, sdb=self.Ge @ Ed1)

    def ode(self, omega):
        """First-order right-hand side y' = fun(t, y) (y = [q, v]) of the smooth/penalty model."""
        Minv = np.linalg.inv(self.M)
        n = self.n

        def fun(t, y):
            y2 = y.reshape(2 * n, -1)
            q, v = y2[:n], y2[n:]
            Fs, _, _ = self.rhs_terms(np.atleast_1d(t), q, v, omega)
            a = Minv @ (Fs - self.K @ q - self.C @ v)
            return np.concatenate([v, a]).reshape(y.shape)

        return fun
