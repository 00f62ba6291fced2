"""Weak forms of the two-field pseudo-medium (§10.5): shaft twist theta(x) and smeared
mechanism output y(x), with the mechanisms' stiffness c_bar = n c/L, mass m_bar = n m/L and
ratio Pi' distributed along the shaft (the potential 1/2 c_bar (y - Pi' theta)^2 per length)."""
from skfem import BilinearForm, LinearForm


@BilinearForm
def pseudo_medium_stiffness(th, y, psi, z, w):
    """GI theta' psi' + c_bar (y - Pi' theta)(z - Pi' psi); (10.47)-(10.48) with the smeared mechanisms."""
    return w["GI"] * th.grad[0] * psi.grad[0] + w["c_bar"] * (y - w["ratio"] * th) * (z - w["ratio"] * psi)


@BilinearForm
def pseudo_medium_mass(th, y, psi, z, w):
    """rho theta psi + m_bar y z (rho: shaft plus smeared discs)."""
    return w["rho"] * th * psi + w["m_bar"] * y * z


@LinearForm
def smeared_output_force(psi, z, w):
    """Distributed force f_bar = n F / L on the mechanism outputs (the corrected load of (10.57))."""
    return w["f_bar"] * z
