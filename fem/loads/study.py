"""What each analysis of a model file reports as named outputs (docs/outputs.md): :func:`outputs`, the one
entry behind :meth:`fem.study.Study.outputs`, the JSON key ``named_outputs``, the CSV columns, the --h5
container and the plots.

| file | modal | forced | simulate |
| --- | --- | --- | --- |
| lumped | load shapes of the drive's outputs | complex amplitudes (linear); amplitude, peak, mean per point of a [steady] curve | time histories |
| hybrid | drive outputs + section loads of the FE shaft | [steady] curve | drive outputs + section loads |
| fe | section loads + support reactions (+ [[output]] node motions) | the same, complex per frequency | -- |
| rotor | section loads + bearing/pedestal/support reactions (complex modes at the analysis speed) | the same per speed (unbalance response) | run-up: speed, probe orbits, rub forces, bearing reactions ([[output]]: section loads) |
| train | -- (own keys) | -- (own keys: mesh forces, load factors, bearing forces) | connection forces, bearing reactions (fem.train.outputs) |

Campbell diagrams: the reactions of every tracked mode over the speeds.  Drive files and periodic forced
responses have none (None).
"""
from __future__ import annotations

import numpy as np

from discrete.loads import Channel

from .analyses import NamedOutputs
from .shaft import (Columns, check_tables, fe_jumps, fe_marks, fe_reaction_columns, hybrid_damping,
                    hybrid_marks, is_section_output, node_columns, rotor_jumps, rotor_marks, rotor_reaction_columns,
                    section_columns)
from .section import elements_of


def outputs(study, result):
    """The named outputs of ``result`` (an analysis of ``study``): a :class:`NamedOutputs` -- over modes,
    frequencies (speeds) or time --, a dict along a [steady] curve (:func:`fem.loads.steady.curve_outputs`),
    or None where the analysis has none (module table)."""
    kind = study.kind
    if kind == "rotor":
        return _rotor(study, result)
    if kind == "train":                 # a time simulation's connection forces and bearing reactions
        from ..train.outputs import outputs as train_outputs

        return train_outputs(study, result)
    if kind == "fe":
        return _fe(study, result)
    if kind in ("lumped", "hybrid"):
        return _drive(study, result)
    return None


def _tables(study) -> list:
    return list(enumerate(getattr(study.doc, "output", None) or (), 1))


def _finish(out: NamedOutputs, cols: Columns, order: dict | None = None, tables=()) -> NamedOutputs:
    """``out`` with the columns of ``cols``, in the [[output]] tables' order when there are tables."""
    out.extend(cols.channels, cols.array(out.axis_values.size), cols.notes)
    if tables:
        rank = {**(order or {}), **cols.order}
        out.ordered(sorted(out.names, key=lambda n: rank.get(n, 0)))
    return out


def _empty(axis: str, values) -> NamedOutputs:
    v = np.asarray(values)
    return NamedOutputs(axis, v, [], np.zeros((0, v.size)))


# ------------------------------------------------------------------ lumped and hybrid files
def _drive(study, result):
    from discrete.linear.harmonic import HarmonicResult
    from discrete.linear.modal import ModalResult
    from discrete.steady import AFCResult

    from discrete.errors import ModelError

    from . import drive

    tables = _tables(study)
    if study.kind == "lumped":
        for i, t in tables:
            if is_section_output(t):
                raise ModelError(f"[[output]] #{i}", "x", t.x, "a station on an FE shaft: section loads (torque, "
                                 "moment, force, shear at x) are outputs of FE, hybrid and rotor files")
    if isinstance(result, AFCResult):
        from .steady import curve_outputs

        return curve_outputs(study, study.steady_model_of(result), result) if result.states else {}
    if isinstance(result, ModalResult):
        order: dict = {}
        out = drive.modal_outputs_of(study, study.linear_model, result, order)
        if study.kind == "hybrid":
            comp = study.compiled
            shapes = np.asarray(comp.T @ result.shapes[:comp.n_fe])
            fe = study.fe_model
            cols = section_columns(elements_of(fe), shapes, jumps=fe_jumps(fe, hybrid_marks(study)[1]), marks=hybrid_marks(
                study)[0], tables=[t for t in tables if is_section_output(t[1])],
                eigenvalue=1j * np.asarray(result.omega_rad_s, dtype=float))
            return _finish(out, cols, order, tables)
        return out
    if isinstance(result, HarmonicResult):
        return drive.forced_outputs_of_study(study, result)
    if hasattr(result, "solver") or hasattr(result, "events"):          # a simulation
        order = {}
        out, signals = drive.simulation_outputs(study, result, order)
        if study.kind == "hybrid":
            return _finish(out, _hybrid_section(study, result, signals, tables), order, tables)
        return out
    return None


def _hybrid_section(study, res, signals, tables) -> Columns:
    """Section-load columns of a hybrid run over every recorded instant (the drive's accelerations, FE
    part expanded chunk by chunk)."""
    comp = res.compiled
    T, n_fe = comp.T, comp.n_fe
    x, v, a = signals["x"], signals["v"], signals["a"]
    n_t = x.shape[1]

    def field(arr):
        return lambda sl: np.asarray(T @ arr[:n_fe, sl])

    fe = study.fe_model
    es = elements_of(fe)
    dmp, notes = hybrid_damping(study, res)
    marks, dofs = hybrid_marks(study)
    sec = [t for t in tables if is_section_output(t[1])]
    if tables and not sec:
        return Columns(notes=[])
    cols = section_columns(es, field(x), n_t=n_t, qd=field(v), qdd=field(a), damping=dmp,
                           jumps=fe_jumps(fe, dofs), marks=marks, tables=sec)
    cols.notes = notes + list(signals.get("notes", []))
    return cols


# ------------------------------------------------------------------ FE files
def _fe(study, result):
    from discrete.linear.harmonic import HarmonicResult
    from discrete.linear.modal import ModalResult
    from discrete.linear.periodic_forced import PeriodicForcedResult

    from .motion import motion
    from .reactions import support_reactions

    fe = study.fe_model
    es = elements_of(fe)
    tables = _tables(study)
    check_tables(tables, "fe")
    sec = [t for t in tables if is_section_output(t[1])]
    if isinstance(result, ModalResult):
        lam = 1j * np.asarray(result.omega_rad_s, dtype=float)
        out = _empty("mode", np.arange(1, lam.size + 1))
        state = {"eigenvalue": lam}
        q, force = result.shapes, None
        notes = ["load shapes of the mass-normalised mode shapes in mode_shapes (phi^T M phi = 1): loads per unit "
                 "modal coordinate eta (q = phi eta, eta in kg^0.5 m)"]
        extra = ()
    elif isinstance(result, HarmonicResult) and result.full is not None and not isinstance(result, PeriodicForcedResult):
        from ..modelfile.build import linear as build_linear

        spec = build_linear.forced_spec(study.doc, fe.system)
        om = result.omega_rad_s
        force = spec.force[:, None] + (om**2)[None, :] * (spec.force_w2[:, None] if spec.force_w2 is not None else 0.0)
        out = _empty("omega", om)
        q = result.full.T
        state = {"omega": om, "damping": build_linear.damping(study.doc.damping)}
        notes = ["complex amplitudes, y(t) = Re(Y e^{i omega t}), one per frequency"]
        extra = np.flatnonzero(np.any(force != 0, axis=1))
    else:
        return None
    cols = Columns(notes=notes)
    reactions = support_reactions(fe, q, force=force, **state)
    cols += fe_reaction_columns(fe, study.doc, reactions, tables)
    if not tables or sec:
        cols += section_columns(es, q, jumps=fe_jumps(fe, extra), marks=fe_marks(fe, fe.system.dof_x[list(extra)]),
                                tables=sec, **state)
    if tables:
        mo = motion(fe.system.n_dofs, q, None, None, state.get("omega"), state.get("eigenvalue"))
        cols += node_columns(fe.system, tables, mo)
    return _finish(out, cols, None, tables)


# ------------------------------------------------------------------ rotor files
def _rotor(study, result):
    from ..rotor.modal import RotorModes
    from ..rotor.response import UnbalanceResponse
    from ..rotor.runup import RunUpResult
    from .reactions import rotor_reactions

    rs = study.rotor
    es = elements_of(rs)
    tables = _tables(study)
    check_tables(tables, "rotor")
    sec = [t for t in tables if is_section_output(t[1])]
    if isinstance(result, RunUpResult):
        return run_up_outputs(study, result, tables)
    from ..rotor.campbell import CampbellResult

    if isinstance(result, CampbellResult):
        return campbell_outputs(study, result, tables)
    if isinstance(result, RotorModes):
        lam = np.asarray(result.eigenvalues)
        out = _empty("mode", np.arange(1, lam.size + 1))
        speed = float(result.speed_rad_s)
        q, force, jumps = result.shapes, None, rotor_jumps(rs)
        state = {"eigenvalue": lam, "speed": speed}
        notes = [f"load shapes of the complex mode shapes in mode_shapes (largest DOF amplitude 1, m or rad) at the "
                 f"speed {speed:g} rad/s, gyroscopic moments included: y(t) = Re(Y e^(lambda t))"]
    elif isinstance(result, UnbalanceResponse):
        from ..modelfile.build import rotor as build_rotor
        from ..rotor.response import unbalance_load

        w = result.speeds_rad_s
        Fu = unbalance_load(rs, build_rotor.response_spec(study.doc).unbalances)
        out = _empty("omega", w)
        q, force, jumps = result.response.T, Fu[:, None] * (w**2)[None, :], rotor_jumps(rs, np.flatnonzero(Fu))
        state = {"omega": w, "speed": w}
        notes = ["synchronous complex amplitudes at each speed (omega = spin speed), y(t) = Re(Y e^{i Omega t})"]
    else:
        return None
    cols = Columns(notes=notes)
    reactions = rotor_reactions(rs, q, force=force, **state)
    cols += rotor_reaction_columns(rs, reactions, tables)
    if not tables or sec:
        cols += section_columns(es, q, jumps=jumps, marks=rotor_marks(rs), tables=sec, **state)
    return _finish(out, cols, None, tables)


def run_up_outputs(study, res, tables=()) -> NamedOutputs:
    """A run-up's outputs over time: the speed, the orbit (y, z) at every probe, the normal force of every
    rub, the reaction of every bearing (linear ones: -K d - C d' at the speed; those computed from their
    geometry: their own law, as the run used it); section loads only where [[output]] tables ask for them
    (q = basis eta, the accelerations the recorded rates differentiated): recovered from the truncated
    basis (mode displacement), they converge slowly at bearings and contacts (a bearing's shear was off
    by 23, 17, 8 % of its reaction with 8, 16, 32 modes on rotor_rub_runup.toml, the mid-span moments
    steady to 0.3 %), so they are no default outputs."""
    from .names import bearing_names
    from .reactions import bearing_forces

    rs = study.rotor
    t = res.t
    cols = Columns()
    cols.add(Channel("speed", "velocity", "rad/s", "run_up", "rotor"), res.speed)
    for k in range(res.probe_x.size):
        x = float(res.probe_x[k])
        name = res.probe_names[k] if k < len(res.probe_names) else ""
        for c, arr in (("y", res.orbit_y), ("z", res.orbit_z)):
            cols.add(Channel(f"{name}.{c}" if name else f"{c}@x={x:g}", "displacement", "m", "probe",
                             name or f"x={x:g}", info={"x": x}), arr[:, k])
    for r in res.rubs:
        cols.add(Channel(f"{r.name}.normal_force", "force", "N", "rub", r.name, info={"x": float(r.x)}),
                 r.normal_force)
    names = bearing_names(rs.rotor)
    reactions = Columns()
    if res.eta is not None:
        B, eta, eta_dot = res.basis, res.eta, res.eta_dot
        lin = bearing_forces(rs, res.speed, lambda idx: eta @ B[idx].T, lambda idx: eta_dot @ B[idx].T,
                             linear_only=True)
        for k, (fy, fz) in lin.items():
            for c, f in (("y", fy), ("z", fz)):
                reactions.add(Channel(f"{names[k]}.force_{c}", "reaction", "N", "bearing", names[k],
                                      info={"x": float(rs.rotor.bearings[k].x)}), f)
    nonlinear = [k for k, b in enumerate(rs.rotor.bearings) if getattr(b, "nonlinear", False)]
    for k, h in zip(nonlinear, res.bearings):
        for c, f in (("y", h.force_y), ("z", h.force_z)):
            reactions.add(Channel(f"{names[k]}.force_{c}", "reaction", "N", "bearing", names[k],
                                  info={"x": float(h.x), "law": h.kind}), f)
    reactions = _select_bearing_tables(reactions, tables)
    sec = [tb for tb in tables if is_section_output(tb[1])]
    if res.eta is not None and t.size > 2 and sec:
        es = elements_of(rs)
        acc = np.gradient(res.eta_dot, t, axis=0, edge_order=2)
        B = res.basis

        def field(arr):
            return lambda sl: np.asarray(B @ arr[sl].T)

        sc = section_columns(es, field(res.eta), n_t=t.size, qd=field(res.eta_dot), qdd=field(acc), speed=res.speed,
                             jumps=rotor_jumps(rs), marks=rotor_marks(rs) + [r.x for r in res.rubs], tables=sec)
        sc.notes = ["section loads of the reduced run-up (q = basis eta, mode displacement; the accelerations are the "
                    "recorded rates differentiated): accurate away from bearings and contacts, slow to converge at "
                    "them with the number of retained modes ([run_up] modes)"]
    else:
        sc = Columns()
    if tables:                      # exactly the outputs asked for: bearing reactions and section loads
        cols = Columns()
    cols += reactions
    cols += sc
    out = _empty("t", t)
    return _finish(out, cols, None, tables)


def campbell_outputs(study, camp, tables=()) -> NamedOutputs | None:
    """The reactions of the bearings, pedestals and rigid supports for every tracked mode of a Campbell
    diagram, over its speeds: ``mode<j> <reaction name>``, the reaction for the mode shape as tracked
    (largest DOF amplitude 1, m or rad; d' = lambda d, the bearings at each speed).  Section loads of
    every mode at every speed are not written (``[[output]]`` tables of section loads are for modal and
    forced)."""
    from .reactions import rotor_reactions

    if not camp.shapes or camp.eigenvalues is None:
        return None
    rs = study.rotor
    s = camp.speeds_rad_s
    per_speed = []
    for i, speed in enumerate(s):
        R = rotor_reactions(rs, camp.shapes[i], eigenvalue=camp.eigenvalues[i], speed=float(speed))
        per_speed.append(rotor_reaction_columns(rs, R, [t for t in tables if not is_section_output(t[1])]))
    base = per_speed[0]
    cols = Columns(notes=["reactions of the bearings, pedestals and supports per tracked mode, for the mode shape "
                          "as tracked (largest DOF amplitude 1, m or rad) at each speed"])
    for j in range(camp.n_modes):
        for k, c in enumerate(base.channels):
            vals = np.array([np.asarray(p.values[k])[j] for p in per_speed])
            cols.add(Channel(f"mode{j + 1} {c.name}", c.quantity, c.unit, c.source, c.where,
                             info={**c.info, "mode": j + 1}), vals)
    return _finish(_empty("speed", s), cols)


def _select_bearing_tables(cols: Columns, tables) -> Columns:
    from .shaft import _select_reactions

    return _select_reactions(cols, tables)


__all__ = ["outputs", "run_up_outputs"]
