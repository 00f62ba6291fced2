"""Bad arguments to the public Python API: a clear ModelError/SolverError naming the key and what is
allowed (the model file's wording), never a raw exception or a silently wrong result; and valid edge
cases giving the closed-form result (issue 16, item 1).

Each probe is (id, callable, expected): ``expected`` is the key the error must name, or ``OK`` with
the callable itself asserting its result against a closed form.  Every error probe goes on to use
what it built (assemble + modal analysis, linear system, simulation), so that before the checks a
bad value showed as a raw exception or a wrong number, not as nothing.

Run as a script (``python tests/test_api_probes.py``) it prints how many probes give a clear error,
an unclear error (the key not named), a raw exception, a silent acceptance or a correct result.
"""
from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from discrete.errors import ModelError, SolverError
from discrete.linear import modal_analysis
from discrete.linear_system import LinearSystem
from discrete.lumped import Body, Driver, Gear, Link, LumpedModel
from discrete.nonsmooth import ExternalForce, Friction, Gap, Impact, MotionLaw, OneSided, Options, Problem, simulate
from discrete.nonsmooth.elements import Contact, Cubic, ModulatedSpring, Motor
from discrete.timestepping import StepOptions, simulate_timestepping
from fem import assemble
from fem.rotor.model import Disc, Rotor, ShaftSegment
from fem.model import PointAttachment, Segment, ShaftModel, Support
from fem.sections import Material, Section

OK = object()
nan, inf = math.nan, math.inf

STEEL = dict(E=2.1e11, G=8.1e10, rho=7850.0)
MAT = Material(**STEEL)
SEC = Section.circle(0.05)


# ----------------------------------------------------------------------------- FE helpers
def _modes(model: ShaftModel, n=2):
    return modal_analysis(assemble(model).system, n)


def _seg(section=SEC, material=MAT, **kw):
    kw.setdefault("length", 1.0)
    kw.setdefault("elements", 4)
    return Segment(section=section, material=material, **kw)


def _shaft(physics="torsion", segments=None, supports=None, points=(), **kw):
    return ShaftModel(physics=physics, segments=segments or [_seg()],
                      supports=[Support(0.0)] if supports is None else supports, points=list(points), **kw)


def fe_mat(**over):
    return lambda: _modes(_shaft(segments=[_seg(material=Material(**{**STEEL, **over}))]))


def fe_bend_mat(**over):
    return lambda: _modes(_shaft("bending", segments=[_seg(material=Material(**{**STEEL, **over}))]))


def fe_section(make, physics="bending", **kw):
    return lambda: _modes(_shaft(physics, segments=[_seg(section=make())], **kw))


def fe_seg(physics="torsion", **kw):
    return lambda: _modes(_shaft(physics, segments=[_seg(**kw)]))


def fe_support(physics="torsion", **kw):
    return lambda: _modes(_shaft(physics, supports=[Support(**kw)]))


def fe_point(physics="axial", **kw):
    return lambda: _modes(_shaft(physics, points=[PointAttachment(**kw)]))


def fe_model(physics="bending", **kw):
    return lambda: _modes(_shaft(physics, **kw))


def timo(kappa):
    return lambda: _modes(_shaft("bending", theory="timoshenko", shear_coefficient=kappa), 3)


# ----------------------------------------------------------------------------- discrete helpers
def _ls(n=2, **kw):
    M = np.eye(n)
    K = 2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    args = dict(M=M, K=K, dof_field=["x"] * n)
    args.update(kw)
    return LinearSystem(**args)


def ls_probe(**kw):
    return lambda: modal_analysis(_ls(**kw), 1)


def _chain(bodies=None, springs=None, **kw):
    bodies = bodies or [Body("a", 1.0), Body("b", 2.0)]
    springs = springs if springs is not None else [Link(("a", "b"), 3.0)]
    return LumpedModel(bodies=bodies, springs=springs, **kw)


def lumped(**kw):
    return modal_analysis(_chain(**kw).linear_system(), 1)


def problem(**kw):
    args = dict(x0=np.array([1.0, 0.0]))
    args.update(kw)
    return simulate(Problem(_ls(), **args), 1.0)


def element(el):
    return simulate(Problem(_ls(), [el], x0=np.array([0.5, 0.0])), 1.0)


def options(**kw):
    return lambda: simulate(Problem(_ls(), x0=np.array([1.0, 0.0])), 1.0, Options(**kw))


def sim(*args, **kw):
    return lambda: simulate(Problem(_ls(), x0=np.array([1.0, 0.0])), *args, **kw)


def stepping(opt=None, **kw):
    args = dict(x0=np.array([1.0, 0.0]), t_end=1.0, options=StepOptions(**(opt or {"dt": 0.01})))
    args.update(kw)
    return simulate_timestepping(_ls(), [], **args)


# ----------------------------------------------------------------------------- valid edge cases
def valid_torsion_rod():
    """Clamped-free rod in torsion: f1 = sqrt(G/rho) / (4 L); quadratic elements, 8 of them: the
    first frequency converges as h^4, ~1e-6 relative here."""
    r = _modes(_shaft(segments=[_seg(elements=8)]), 1)
    f1 = math.sqrt(STEEL["G"] / STEEL["rho"]) / 4.0
    assert r.frequencies_hz[0] == pytest.approx(f1, rel=1e-5)


def valid_massless_shaft():
    """rho = 0 is a massless shaft (the [drive] models and the rotor closed forms use it): with a disc J0
    at the free end of a clamped shaft (one P1 element: the only free DOF carries J0), omega = sqrt(G J / (L J0))
    exactly."""
    J0 = 2.0
    r = _modes(_shaft(segments=[_seg(material=Material(E=2.1e11, G=8.1e10, rho=0.0), elements=1)], order=1,
                      points=[PointAttachment(1.0, inertia=J0)]), 1)
    assert r.omega_rad_s[0] == pytest.approx(math.sqrt(8.1e10 * SEC.J / J0), rel=1e-10)


def valid_auxetic_nu():
    """nu = -0.5 lies in the model file's (-1, 0.5): G = E / (2 (1 + nu)) = E."""
    m = Material.with_nu(2.0e11, -0.5, 7850.0)
    assert m.G == pytest.approx(2.0e11) and m.nu == pytest.approx(-0.5)


def valid_tube_area():
    s = Section.tube(0.05, 0.04)
    assert s.A == pytest.approx(math.pi * (0.05**2 - 0.04**2) / 4, rel=1e-14)


def valid_kappa_upper_bound():
    """kappa = 1.5 is the model file's upper bound (allowed); a larger kappa makes the beam stiffer in
    shear, so f1 stays below the Euler-Bernoulli value (shear flexibility only lowers it)."""
    t = _modes(_shaft("bending", theory="timoshenko", shear_coefficient=1.5), 1).frequencies_hz[0]
    e = _modes(_shaft("bending"), 1).frequencies_hz[0]
    assert t < e * (1 + 1e-6)


def valid_support_at_end():
    """A support at x = L (1 + 1e-13) is on the shaft (round-off of a sum of lengths)."""
    _modes(_shaft(supports=[Support(1.0 * (1 + 1e-13))]), 1)


def valid_two_body_chain():
    """Free-free two-body chain: omega^2 = k (1/m1 + 1/m2) = 3 (1 + 1/2) = 4.5."""
    r = modal_analysis(_chain().linear_system(), 2)
    assert np.max(r.omega_rad_s) == pytest.approx(math.sqrt(4.5), rel=1e-10) and r.rigid.sum() == 1


def valid_sdof_event():
    """M = 1, K = 1, x0 = 1: x(t) = cos t (exact pieces: round-off)."""
    ls = LinearSystem(M=np.eye(1), K=np.eye(1), dof_field=["x"])
    r = simulate(Problem(ls, x0=np.ones(1)), 1.0, Options(max_step=0.1))
    assert r.x[0, -1] == pytest.approx(math.cos(1.0), abs=1e-10) and r.t[-1] == 1.0 and not r.stopped_early


def valid_sdof_moreau():
    """Midpoint Moreau-Jean on x'' + x = 0, x0 = 1, dt = 1e-3: second order, error ~ t h^2 / 24 ~ 1e-7."""
    ls = LinearSystem(M=np.eye(1), K=np.eye(1), dof_field=["x"])
    r = simulate_timestepping(ls, [], x0=np.ones(1), t_end=1.0, options=StepOptions(dt=1e-3))
    assert r.x[0, -1] == pytest.approx(math.cos(1.0), abs=1e-6)


def valid_integer_numbers():
    """Integers are numbers (E = 200 GPa given as an int; numpy floats too)."""
    m = Material(E=200_000_000_000, G=np.float64(8e10), rho=7850)
    assert m.E == 2e11 and isinstance(m.E, float)


def valid_constrained_driver():
    """A prescribed DOF (driver) moving at constant speed drags a spring-coupled free mass: with
    x_c = t, the free DOF of M = 1, K = [[1, -1], [-1, 1]] follows x = t - sin t from rest."""
    ls = LinearSystem(M=np.eye(2), K=np.array([[1.0, -1.0], [-1.0, 1.0]]), dof_field=["x", "x"], constrained=[0])
    r = simulate(Problem(ls, drivers={0: MotionLaw(velocity=1.0)}), 1.0)
    assert r.x[1, -1] == pytest.approx(1.0 - math.sin(1.0), abs=1e-10)


def rotor(seg=None, **kw):
    return Rotor(segments=[seg or ShaftSegment(1.0, 4, 0.05, MAT)], **kw)


# ----------------------------------------------------------------------------- the probes
PROBES = [
    # fem.Material
    ("Material E=nan", fe_mat(E=nan), "E"),
    ("Material E=-211e9", fe_bend_mat(E=-211e9), "E"),
    ("Material E=inf", fe_mat(E=inf), "E"),
    ("Material E=0", fe_bend_mat(E=0.0), "E"),
    ("Material E='2e11'", fe_mat(E="2e11"), "E"),
    ("Material E=complex", fe_mat(E=2e11 + 1j), "E"),
    ("Material E=True", fe_mat(E=True), "E"),
    ("Material G=0 (torsion)", fe_mat(G=0.0), "G"),
    ("Material G=nan", fe_mat(G=nan), "G"),
    ("Material G=-8e10", fe_mat(G=-8e10), "G"),
    ("Material G=inf", fe_mat(G=inf), "G"),
    ("Material rho=nan", fe_mat(rho=nan), "rho"),
    ("Material rho=-7850", fe_mat(rho=-7850.0), "rho"),
    ("Material rho=None", fe_mat(rho=None), "rho"),
    ("Material.with_nu nu=0.5", lambda: Material.with_nu(2e11, 0.5, 7850.0), "nu"),
    ("Material.with_nu nu=-1", lambda: Material.with_nu(2e11, -1.0, 7850.0), "nu"),
    ("Material.with_nu nu=nan", lambda: Material.with_nu(2e11, nan, 7850.0), "nu"),
    # fem.Section
    ("Section.circle d=0", fe_section(lambda: Section.circle(0.0)), "d"),
    ("Section.circle d=-0.05", fe_section(lambda: Section.circle(-0.05)), "d"),
    ("Section.circle d=nan", fe_section(lambda: Section.circle(nan)), "d"),
    ("Section.circle d=inf", fe_section(lambda: Section.circle(inf)), "d"),
    ("Section.circle d='5cm'", fe_section(lambda: Section.circle("5cm")), "d"),
    ("Section.tube di>d", fe_section(lambda: Section.tube(0.05, 0.06)), "di"),
    ("Section.tube d=nan", fe_section(lambda: Section.tube(nan, 0.01)), "d"),
    ("Section.tube di=nan", fe_section(lambda: Section.tube(0.05, nan)), "di"),
    ("Section.circle kappa=0", fe_section(lambda: Section.circle(0.05, kappa=0.0), theory="timoshenko"), "kappa"),
    ("Section.circle kappa=-1", fe_section(lambda: Section.circle(0.05, kappa=-1.0), theory="timoshenko"), "kappa"),
    ("Section.circle kappa=nan", fe_section(lambda: Section.circle(0.05, kappa=nan), theory="timoshenko"), "kappa"),
    ("Section.circle kappa=2", fe_section(lambda: Section.circle(0.05, kappa=2.0), theory="timoshenko"), "kappa"),
    ("Section.explicit A=-1", fe_section(lambda: Section.explicit(A=-1.0, I=1e-8, J=2e-8)), "A"),
    ("Section.explicit I=0", fe_section(lambda: Section.explicit(A=1e-3, I=0.0, J=2e-8)), "I"),
    ("Section.explicit J=inf", fe_section(lambda: Section.explicit(A=1e-3, I=1e-8, J=inf), "torsion"), "J"),
    ("Section.explicit Ip=-1", fe_section(lambda: Section.explicit(A=1e-3, I=1e-8, J=2e-8, Ip=-1.0), "torsion"),
     "Ip"),
    ("Section.explicit nothing", fe_section(lambda: Section.explicit()), "section"),
    ("Section.explicit A missing (axial)", fe_section(lambda: Section.explicit(I=1e-8, J=2e-8), "axial"), "A"),
    ("Section(...) I=-1e-8", fe_section(lambda: Section(A=1e-3, I=-1e-8, J=2e-8, Ip=2e-8)), "I"),
    ("Section shape='square'", fe_section(lambda: Section(A=1e-3, I=1e-8, J=2e-8, Ip=2e-8, shape="square")), "shape"),
    # fem.ShaftModel
    ("shear_coefficient=-1", timo(-1.0), "shear_coefficient"),
    ("shear_coefficient=nan", timo(nan), "shear_coefficient"),
    ("shear_coefficient=0", timo(0.0), "shear_coefficient"),
    ("shear_coefficient=2", timo(2.0), "shear_coefficient"),
    ("shear_coefficient for torsion", fe_model("torsion", shear_coefficient=0.9), "shear_coefficient"),
    ("ShaftModel physics='shear'", fe_model("shear"), "physics"),
    ("ShaftModel order=3", fe_model("torsion", order=3), "order"),
    ("ShaftModel order=2.0", fe_model("torsion", order=2.0), "order"),
    ("ShaftModel theory='rayleigh'", fe_model(theory="rayleigh"), "theory"),
    ("ShaftModel mass='diagonal'", fe_model(mass="diagonal"), "mass"),
    ("ShaftModel segments=[]", lambda: _modes(ShaftModel("torsion", [])), "segment"),
    ("ShaftModel segments=[1.0]", lambda: _modes(ShaftModel("torsion", [1.0], [Support(0.0)])), "segment"),
    ("ShaftModel supports=[0.0]", lambda: _modes(ShaftModel("torsion", [_seg()], [0.0])), "support"),
    ("ShaftModel points=['m']", lambda: _modes(ShaftModel("torsion", [_seg()], [Support(0.0)], ["m"])), "point"),
    # fem.Segment
    ("Segment length=nan", fe_seg(length=nan), "length"),
    ("Segment length=inf", fe_seg(length=inf), "length"),
    ("Segment length=-1", fe_seg(length=-1.0), "length"),
    ("Segment elements=2.0", fe_seg(elements=2.0), "elements"),
    ("Segment elements=True", fe_seg(elements=True), "elements"),
    ("Segment elements=0", fe_seg(elements=0), "elements"),
    ("Segment rho_extra=nan", fe_seg(rho_extra=nan), "rho_extra"),
    ("Segment rho_extra=-1", fe_seg(rho_extra=-1.0), "rho_extra"),
    ("Segment psi=nan", fe_seg(psi=nan), "psi"),
    ("Segment psi=inf", fe_seg(psi=inf), "psi"),
    ("Segment section=0.05", fe_seg(section=0.05), "section"),
    ("Segment material=None", fe_seg(material=None), "material"),
    # fem.Support
    ("Support x=nan", fe_support(x=nan), "x"),
    ("Support x=2 (L=1)", fe_support(x=2.0), "x"),
    ("Support k=nan", fe_support(type="spring", x=0.0, k=nan), "k"),
    ("Support k=inf", fe_support(type="spring", x=0.0, k=inf), "k"),
    ("Support k=-1", fe_support(type="spring", x=0.0, k=-1.0), "k"),
    ("Support kr=nan (bending)", fe_support("bending", type="spring", x=0.0, k=1e6, kr=nan), "kr"),
    ("Support type='pinned' (torsion)", fe_support(type="pinned", x=0.0), "type"),
    ("Support spring k=0", fe_support(type="spring", x=0.0), "k"),
    # fem.PointAttachment
    ("Point x=nan", fe_point(x=nan, mass=1.0), "x"),
    ("Point mass=nan", fe_point(x=1.0, mass=nan), "mass"),
    ("Point mass=inf", fe_point(x=1.0, mass=inf), "mass"),
    ("Point mass=-1", fe_point(x=1.0, mass=-1.0), "mass"),
    ("Point inertia=inf (torsion)", fe_point("torsion", x=1.0, inertia=inf), "inertia"),
    ("Point k=nan", fe_point(x=1.0, k=nan), "k"),
    ("Point kr=nan (bending)", fe_point("bending", x=1.0, kr=nan), "kr"),
    # discrete.LinearSystem
    ("LinearSystem complex K", ls_probe(K=np.array([[2, -1], [-1, 2]]) * (1 + 0.1j)), "K"),
    ("LinearSystem complex M", ls_probe(M=np.eye(2) * (1 + 0.1j)), "M"),
    ("LinearSystem complex C", ls_probe(C=np.eye(2) * 1j), "C"),
    ("LinearSystem complex H", ls_probe(H=np.eye(2) * 1j), "H"),
    ("LinearSystem K 3x3 for 2 DOFs", ls_probe(K=np.eye(3)), "K"),
    ("LinearSystem M 2x3", ls_probe(M=np.ones((2, 3))), "M"),
    ("LinearSystem G 3x3", ls_probe(G=np.eye(3)), "G"),
    ("LinearSystem 3 labels for 2 DOFs", ls_probe(dof_field=["x"] * 3), "dof_field"),
    ("LinearSystem dof_x length 3", ls_probe(dof_x=np.zeros(3)), "dof_x"),
    ("LinearSystem dof_name length 1", ls_probe(dof_name=["a"]), "dof_name"),
    ("LinearSystem constrained=[5]", ls_probe(constrained=[5]), "constrained"),
    ("LinearSystem constrained=[-1]", ls_probe(constrained=[-1]), "constrained"),
    ("LinearSystem constrained=[0.5]", ls_probe(constrained=[0.5]), "constrained"),
    ("LinearSystem M with NaN", ls_probe(M=np.array([[nan, 0], [0, 1.0]])), "M"),
    ("LinearSystem rigid_modes 3 rows", ls_probe(rigid_modes=np.ones((3, 1))), "rigid_modes"),
    ("LinearSystem M='abc'", ls_probe(M="abc"), "M"),
    # discrete.lumped
    ("Body inertia=nan", lambda: lumped(bodies=[Body("a", nan), Body("b", 2.0)]), "inertia"),
    ("Body inertia=inf", lambda: lumped(bodies=[Body("a", inf), Body("b", 2.0)]), "inertia"),
    ("Body inertia=-1", lambda: lumped(bodies=[Body("a", -1.0), Body("b", 2.0)]), "inertia"),
    ("Body inertia='1'", lambda: lumped(bodies=[Body("a", "1"), Body("b", 2.0)]), "inertia"),
    ("Body x0=nan", lambda: lumped(bodies=[Body("a", 1.0, x0=nan), Body("b", 2.0)]), "x0"),
    ("Body v0=inf", lambda: lumped(bodies=[Body("a", 1.0, v0=inf), Body("b", 2.0)]), "v0"),
    ("Body inertia_rate=nan", lambda: lumped(bodies=[Body("a", 1.0, inertia_rate=nan), Body("b", 2.0)]), "inertia_rate"),
    ("Body name=''", lambda: lumped(bodies=[Body("", 1.0), Body("b", 2.0)]), "name"),
    ("spring k=nan", lambda: lumped(springs=[Link(("a", "b"), nan)]), "value"),
    ("spring k=inf", lambda: lumped(springs=[Link(("a", "b"), inf)]), "value"),
    ("spring k=-3", lambda: lumped(springs=[Link(("a", "b"), -3.0)]), "value"),
    ("damper c=nan", lambda: lumped(dampers=[Link(("a", "b"), nan)]), "value"),
    ("spring psi=-1", lambda: lumped(springs=[Link(("a", "b"), 3.0, psi=-1.0)]), "psi"),
    ("spring psi=nan", lambda: lumped(springs=[Link(("a", "b"), 3.0, psi=nan)]), "psi"),
    ("spring ratios=(1, nan)", lambda: lumped(springs=[Link(("a", "b"), 3.0, ratios=(1.0, nan))]), "ratios"),
    ("spring ratios of 3", lambda: lumped(springs=[Link(("a", "b"), 3.0, ratios=(1.0, 1.0, 1.0))]), "ratios"),
    ("spring between unknown", lambda: lumped(springs=[Link(("a", "z"), 3.0)]), "between"),
    ("spring between='ab'", lambda: lumped(springs=[Link("ab", 3.0)]), "between"),
    ("gear ratio=nan", lambda: lumped(gears=[Gear(("a", "b"), nan)]), "ratio"),
    ("Driver omega=-1", lambda: lumped(drivers=[Driver("d", amplitude=1.0, omega=-1.0)]), "omega"),
    ("Driver amplitude=nan", lambda: lumped(drivers=[Driver("d", amplitude=nan, omega=1.0)]), "amplitude"),
    ("Driver amplitude without omega", lambda: lumped(drivers=[Driver("d", amplitude=1.0)]), "omega"),
    ("Driver inertia=-1", lambda: lumped(drivers=[Driver("d", velocity=1.0, inertia=-1.0)]), "inertia"),
    ("Driver velocity=inf", lambda: lumped(drivers=[Driver("d", velocity=inf)]), "velocity"),
    # discrete.nonsmooth.Problem / MotionLaw / ExternalForce
    ("Problem x0 of 3 for 2 DOFs", lambda: problem(x0=np.array([1.0, 0.0, 5.0])), "x0"),
    ("Problem v0 of 1 for 2 DOFs", lambda: problem(v0=np.array([1.0])), "v0"),
    ("Problem x0 with NaN", lambda: problem(x0=np.array([nan, 0.0])), "x0"),
    ("Problem v0 complex", lambda: problem(v0=np.array([1j, 0.0])), "v0"),
    ("Problem drivers={5: ..}", lambda: problem(drivers={5: MotionLaw()}), "drivers"),
    ("Problem driver on a free DOF", lambda: problem(drivers={0: MotionLaw(velocity=1.0)}), "drivers"),
    ("Problem system=None", lambda: Problem(None), "system"),
    ("MotionLaw omega=nan", lambda: MotionLaw(amplitude=1.0, omega=nan), "omega"),
    ("MotionLaw amplitude=inf", lambda: MotionLaw(amplitude=inf, omega=1.0), "amplitude"),
    ("MotionLaw velocity='fast'", lambda: MotionLaw(velocity="fast"), "velocity"),
    ("MotionLaw omega=-1", lambda: MotionLaw(amplitude=1.0, omega=-1.0), "omega"),
    ("ExternalForce g of 3", lambda: problem(forces=[ExternalForce(np.ones(3), value=1.0)]), "g"),
    ("ExternalForce value=nan", lambda: problem(forces=[ExternalForce(np.ones(2), value=nan)]), "value"),
    ("ExternalForce omega=-1", lambda: problem(forces=[ExternalForce(np.ones(2), amplitude=1.0, omega=-1.0)]), "omega"),
    ("ExternalForce g with inf", lambda: problem(forces=[ExternalForce(np.array([inf, 0.0]), value=1.0)]), "g"),
    ("element g of 3", lambda: element(OneSided("s", np.ones(3), k=1.0)), "g"),
    ("element g with NaN", lambda: element(OneSided("s", np.array([nan, 1.0]), k=1.0)), "g"),
    # discrete.nonsmooth elements
    ("Friction kinetic=nan", lambda: element(Friction("f", np.array([1.0, 0.0]), kinetic=nan)), "kinetic"),
    ("Friction kinetic=inf", lambda: element(Friction("f", np.array([1.0, 0.0]), kinetic=inf)), "kinetic"),
    ("Friction viscous=nan", lambda: element(Friction("f", np.array([1.0, 0.0]), kinetic=0.1, viscous=nan)), "viscous"),
    ("Friction surface_velocity=inf",
     lambda: element(Friction("f", np.array([1.0, 0.0]), kinetic=0.1, surface_velocity=inf)), "surface_velocity"),
    ("Friction restick='x'", lambda: element(Friction("f", np.array([1.0, 0.0]), kinetic=0.1, restick="x")), "restick"),
    ("OneSided k=inf", lambda: element(OneSided("s", np.array([1.0, 0.0]), k=inf)), "k"),
    ("OneSided k=nan", lambda: element(OneSided("s", np.array([1.0, 0.0]), k=nan)), "k"),
    ("OneSided side=0", lambda: element(OneSided("s", np.array([1.0, 0.0]), k=1.0, side=0)), "side"),
    ("OneSided s_open=nan", lambda: element(OneSided("s", np.array([1.0, 0.0]), k=1.0, s_open=nan)), "s_open"),
    ("Gap k=inf", lambda: element(Gap("g", np.array([1.0, 0.0]), k=inf, lower=-0.1, upper=0.1)), "k"),
    ("Gap lower=nan", lambda: element(Gap("g", np.array([1.0, 0.0]), k=1.0, lower=nan, upper=0.1)), "lower"),
    ("Gap L=inf (arctan)", lambda: element(Gap("g", np.array([1.0, 0.0]), k=1.0, lower=-0.1, upper=0.1, law="arctan",
                                       L=inf)), "L"),
    ("Impact restitution=nan", lambda: element(Impact("i", np.array([1.0, 0.0]), s_min=-1.0, restitution=nan)), "restitution"),
    ("Impact s_min=nan", lambda: element(Impact("i", np.array([1.0, 0.0]), s_min=nan)), "s_min"),
    ("Impact v_rest=-1", lambda: element(Impact("i", np.array([1.0, 0.0]), s_min=-1.0, v_rest=-1.0)), "v_rest"),
    ("Contact k=inf", lambda: element(Contact("c", np.array([1.0, 0.0]), k=inf, upper=1.0)), "k"),
    ("Contact c=nan", lambda: element(Contact("c", np.array([1.0, 0.0]), k=1.0, c=nan, upper=1.0)), "c"),
    ("Cubic k3=nan", lambda: element(Cubic("c", np.array([1.0, 0.0]), k3=nan)), "k3"),
    ("Cubic k3=inf", lambda: element(Cubic("c", np.array([1.0, 0.0]), k3=inf)), "k3"),
    ("ModulatedSpring depth=1", lambda: element(ModulatedSpring("m", np.array([1.0, 0.0]), k=1.0, depth=1.0, omega=1.0)),
     "depth"),
    ("Motor omega0=nan", lambda: element(Motor("m", np.array([1.0, 0.0]), omega0=nan, nu=1.0)), "omega0"),
    # discrete.nonsmooth.solver Options / simulate
    ("Options max_step=-1", options(max_step=-1.0), "max_step"),
    ("Options max_step=nan", options(max_step=nan), "max_step"),
    ("Options max_step=0", options(max_step=0.0), "max_step"),
    ("Options max_events=0", options(max_events=0), "max_events"),
    ("Options max_events=1.5", options(max_events=1.5), "max_events"),
    ("Options steps_per_period=0", options(steps_per_period=0), "steps_per_period"),
    ("Options rtol=0", options(rtol=0.0), "rtol"),
    ("Options rest_tol=-1", options(rest_tol=-1.0), "rest_tol"),
    ("Options output_step=0", options(output_step=0.0), "output_step"),
    ("Options max_zero_length=0", options(max_zero_length=0), "max_zero_length"),
    ("Options contact_tol=-1", options(contact_tol=-1.0), "contact_tol"),
    ("Options progress=5", options(progress=5), "progress"),
    ("simulate t_end=nan", sim(nan), "t_end"),
    ("simulate t_end=-1", sim(-1.0), "t_end"),
    ("simulate t_end=inf", sim(inf), "t_end"),
    ("simulate t0=nan", sim(1.0, t0=nan), "t0"),
    ("simulate options='fast'", sim(1.0, "fast"), "options"),
    ("simulate a LinearSystem", lambda: simulate(_ls(), 1.0), "problem"),
    # discrete.timestepping
    ("StepOptions dt=-1", lambda: stepping({"dt": -1.0}), "dt"),
    ("StepOptions dt=nan", lambda: stepping({"dt": nan}), "dt"),
    ("StepOptions theta=nan", lambda: stepping({"dt": 0.01, "theta": nan}), "theta"),
    ("StepOptions max_iter=0", lambda: stepping({"dt": 0.01, "max_iter": 0}), "max_iter"),
    ("StepOptions tol=-1", lambda: stepping({"dt": 0.01, "tol": -1.0}), "tol"),
    ("StepOptions sample_every=0", lambda: stepping({"dt": 0.01, "sample_every": 0}), "sample_every"),
    ("StepOptions max_events=0", lambda: stepping({"dt": 0.01, "max_events": 0}), "max_events"),
    ("timestepping t_end=inf", lambda: stepping(t_end=inf), "t_end"),
    ("timestepping t0=nan", lambda: stepping(t0=nan), "t0"),
    ("timestepping x0 of 3", lambda: stepping(x0=np.ones(3)), "x0"),
    ("timestepping v0 NaN", lambda: stepping(v0=np.array([nan, 0.0])), "v0"),
    ("timestepping drivers={7: ..}", lambda: stepping(drivers={7: MotionLaw()}), "drivers"),
    ("timestepping force g of 1", lambda: stepping(forces=[ExternalForce(np.ones(1), value=1.0)]), "g"),
    # fem.rotor.model (constructor checks)
    ("Rotor segment d=nan", lambda: rotor(ShaftSegment(1.0, 4, nan, MAT)), "d"),
    ("Rotor segment length='1'", lambda: rotor(ShaftSegment("1", 4, 0.05, MAT)), "length"),
    ("Rotor segment d=True", lambda: rotor(ShaftSegment(1.0, 4, True, MAT)), "d"),
    ("Rotor segment kappa=2", lambda: rotor(ShaftSegment(1.0, 4, 0.05, MAT, shear_coefficient=2.0)),
     "shear_coefficient"),
    ("Rotor segments=[1.0]", lambda: Rotor(segments=[1.0]), "segment"),
    ("Rotor disc mass=inf", lambda: rotor(discs=[Disc(0.5, inf)]), "mass"),
    ("Rotor disc x=nan", lambda: rotor(discs=[Disc(nan, 1.0)]), "x"),
    ("Rotor discs=['d']", lambda: rotor(discs=["d"]), "disc"),
    # valid edge cases: closed forms
    ("valid torsion rod f1", valid_torsion_rod, OK),
    ("valid nu=-0.5", valid_auxetic_nu, OK),
    ("valid massless shaft rho=0", valid_massless_shaft, OK),
    ("valid tube area", valid_tube_area, OK),
    ("valid kappa=1.5", valid_kappa_upper_bound, OK),
    ("valid support at L(1+1e-13)", valid_support_at_end, OK),
    ("valid two-body chain", valid_two_body_chain, OK),
    ("valid SDOF event solver", valid_sdof_event, OK),
    ("valid SDOF Moreau-Jean", valid_sdof_moreau, OK),
    ("valid integer numbers", valid_integer_numbers, OK),
    ("valid driver drags a mass", valid_constrained_driver, OK),
]


# A massless shaft (rho = 0) whose inertia is one disc, meshed with P2 elements: M is singular (8 of 9 free
# DOFs carry no inertia) and the one finite mode exists (omega^2 = G J / (L J0)); modal_analysis condenses the
# massless DOFs out exactly (it used to end in a raw ArpackError -9999).
def singular_mass_one_mode():
    J0 = 2.0
    r = _modes(_shaft(segments=[_seg(material=Material(E=2.1e11, G=8.1e10, rho=0.0))],
                      points=[PointAttachment(1.0, inertia=J0)]), 1)
    assert r.omega_rad_s[0] == pytest.approx(math.sqrt(8.1e10 * SEC.J / J0), rel=1e-8)


PROBES.append(("modal: massless P2 shaft + disc, 1 mode", singular_mass_one_mode, OK))


def _names_key(message: str, key: str) -> bool:
    return f"{key} = " in message or f"{key} =" in message


def _param(p):
    if not hasattr(p, "marks"):
        return pytest.param(p[1], p[2], id=p[0])
    return pytest.param(*p.values[1:], id=p.values[0], marks=p.marks)


@pytest.mark.parametrize("call,expected", [_param(p) for p in PROBES])
def test_probe(call, expected):
    if expected is OK:
        call()
        return
    with pytest.raises((ModelError, SolverError)) as info:
        call()
    msg = str(info.value)
    assert _names_key(msg, expected), msg
    if isinstance(info.value, ModelError):
        assert info.value.key == expected and info.value.allowed, msg


def classify(call, expected) -> str:
    """'clear' | 'unclear' (own error, key not named) | 'raw' | 'silent' | 'correct' | 'wrong'."""
    import signal
    import warnings

    def alarm(*_):
        raise TimeoutError

    signal.signal(signal.SIGALRM, alarm)
    signal.alarm(20)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            call()
        except TimeoutError:
            return "hang"
        except (ModelError, SolverError) as exc:
            if expected is OK:
                return "wrong"
            return "clear" if _names_key(str(exc), expected) else "unclear"
        except AssertionError:
            return "wrong"
        except Exception:
            return "wrong" if expected is OK else "raw"
        finally:
            signal.alarm(0)
    return "correct" if expected is OK else "silent"


if __name__ == "__main__":
    from collections import Counter

    counts = Counter()
    for p in PROBES:
        name, call, expected = p.values if hasattr(p, "marks") else p
        c = classify(call, expected)
        counts[c] += 1
        if c not in ("clear", "correct") or "-v" in sys.argv:
            print(f"{c:8s} {name}")
    print(f"{len(PROBES)} probes:", dict(counts))
