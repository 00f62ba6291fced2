"""Weak forms of the 1D drive models, as small scikit-fem forms.

Coefficients arrive as element-wise arrays (stepped shafts): ``w['stiffness']`` etc.
"""
from skfem import BilinearForm
from skfem.helpers import dd


@BilinearForm
def rod_stiffness(u, v, w):
    """Torsion (4.51): G J_t phi' psi';  axial rod: E A u' v'."""
    return w["stiffness"] * u.grad[0] * v.grad[0]


@BilinearForm
def rod_mass(u, v, w):
    """Torsion: (rho I_p + rho_extra) phi psi as in (4.56);  axial: (rho A + extra) u v."""
    return w["inertia"] * u * v


@BilinearForm
def euler_bernoulli_stiffness(u, v, w):
    """(4.58): E I w'' v''."""
    return w["EI"] * dd(u)[0, 0] * dd(v)[0, 0]


@BilinearForm
def euler_bernoulli_mass(u, v, w):
    """(4.58): m/L w v (translational inertia only, as in the textbook)."""
    return w["rhoA"] * u * v


@BilinearForm
def timoshenko_bending(w_, phi, v_, chi, w):
    """Bending part E I phi' chi' of the Timoshenko beam (fields w, phi)."""
    return w["EI"] * phi.grad[0] * chi.grad[0]


@BilinearForm
def timoshenko_shear(w_, phi, v_, chi, w):
    """Shear part kappa G A (w' - phi)(v' - chi); assembled with reduced quadrature
    (one order below exact), which removes shear locking in the slender limit."""
    return w["kGA"] * (w_.grad[0] - phi) * (v_.grad[0] - chi)


@BilinearForm
def timoshenko_mass(w_, phi, v_, chi, w):
    """rho A w v + rho I phi chi (translational and rotary inertia)."""
    return w["rhoA"] * w_ * v_ + w["rhoI"] * phi * chi
