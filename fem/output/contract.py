"""The output contract: what every command's JSON holds (docs/cli.md).

Every file has ``schema`` ("drivefem.<command>"), ``version`` (:data:`SCHEMA_VERSION`), ``title``
and ``kind`` (fe | lumped | hybrid | drive), then the command's keys:

* modal: ``omega_rad_s``, ``frequencies_hz`` (null for a mode that is not reliable; its raw value in
  ``omega_rad_s_unverified``), ``n_dofs``, ``n_modes``, ``residuals``, ``rayleigh_rel_diff`` and
  ``precision_bound`` (null where a representation has none), ``reliable``, ``rigid_body_modes``,
  ``mode_shapes``, ``method``, ``warnings``; drive files add their representation, reference and
  stop band.
* forced: ``frequencies_hz``, ``omega_rad_s`` (n_freq), ``outputs`` (n_out names), ``amplitude`` and
  ``phase_lag_deg`` (n_out x n_freq), ``response`` (complex, n_out x n_freq; null for the nonlinear
  curve, whose amplitude is its response measure), ``method``, ``damping``, ``warnings``; linear FE and
  lumped results add ``reliable`` and ``error_estimate`` per frequency (false / of order 1 where the dynamic
  stiffness is singular to working precision: an undamped resonance, omega = 0 of a free motion); the
  nonlinear curve (``steady``) adds ``stable``, ``max_multiplier``, ``folds``, ``reason``, ...
* simulate: ``t_end``, ``events``, ``period``, ``energy_error``, ``stopped_early``, ``reason``, ...;
  lumped and hybrid files add ``element_summary`` (impacts, impulse_sum, friction work per element) and
  ``history`` (the --h5 file, record_every); modal and forced of lumped, hybrid and rotor files add
  ``linearisation`` (what each nonsmooth element became).
* parametric: the stability chart -- ``depth`` (n_depth), ``omega_rad_s`` and ``omega_ratio`` (Omega /
  omega_1, n_omega), ``rho_max``, ``stable``, ``growth_rate_1_s``, ``error_estimate``,
  ``liouville_residual`` (n_depth x n_omega), ``natural_omega_rad_s``, ``centres``, ``thresholds``,
  ``boundaries``, ``modulations`` with ``parts``, ``damping``, ``inertia_form``, ``warnings``.
* train files (kind ``train``): modal as rotor files plus ``energy_share``, ``whirl_by_shaft``,
  ``speed_ratios``, ``mode_shapes`` (complex, every DOF with its label); campbell as rotor files plus
  ``speed_ratios``; forced (``[forced]``) the response over speed: mesh forces, dynamic load factors,
  bearing reactions (see docs/geared.md).
* rotor files (kind ``rotor``): modal adds ``speed_rad_s``, ``eigenvalues``, ``damping_ratio``,
  ``log_decrement``, ``whirl``, ``kind_of_mode``, orbits, and ``mode_shapes`` as complex v, w at the
  shaft nodes; forced is the unbalance response with the speeds as ``omega_rad_s``, one output per probe
  (named after the disc/bearing there), ``peaks`` (AF, separation margins, ``resolved``: false for an
  undamped peak whose amplitude only the search resolution bounds), ``orbit_major`` (n_speeds x
  n_nodes); simulate is the run-up; campbell: ``speeds_rad_s``, ``speeds_rpm``, ``omega_rad_s``,
  ``natural_frequency_rad_s``, ``log_decrement``, ``damping_ratio``, ``whirl`` (n_modes x n_speeds),
  ``kind_of_mode``, ``mac_min``, ``residual_max``, ``orders``, ``critical_speeds``, ``warnings``.
* ``named_outputs`` (every command of lumped, hybrid, FE and rotor files that has them, and train simulations; version 2,
  docs/outputs.md): {name: ``quantity``, ``unit``, ``source``, ``where`` (and ``x``, ``side``,
  ``section_quantity``, ``dof``, ... where they apply) + the analysis' values -- time histories: ``peak``,
  ``max``, ``min``, ``mean``, ``rms``, ``peak_to_peak``, ``dynamic_load_factor``; modes: ``modes``;
  frequencies: complex ``response``, ``amplitude``, ``phase_lag_deg``, ``peak``, ``peak_omega_rad_s``;
  Campbell speeds: ``shape``, ``amplitude`` (the reactions of each tracked mode); a [steady] curve: ``amplitude``, ``peak``, ``mean``, ``dynamic_load_factor`` per point}: element forces,
  reactions of drivers, supports and bearings, section loads of FE shafts and rotors; and
  ``named_outputs_notes``.  Version 1's ``section_loads`` key is gone (its loads are named outputs).
Complex numbers are ``{"re": .., "im": ..}``; no number is NaN or infinite.
"""
from __future__ import annotations

import numpy as np

SCHEMA_VERSION = 2


def payload(command: str, study, data: dict) -> dict:
    """The JSON document of ``command`` for ``study`` with the command's ``data``; the model file's
    plausibility warnings (values likely not in SI, a model outside its theory) come first in
    ``warnings`` (the key is added for them where a command has none)."""
    model_warnings = getattr(study, "model_warnings", None)
    if model_warnings:
        data = {**data, "warnings": model_warnings + list(data.get("warnings") or [])}
    return {"schema": f"drivefem.{command}", "version": SCHEMA_VERSION,
            "title": study.title if study is not None else "", "kind": study.kind if study is not None else None,
            **data}


def with_outputs(d: dict, outputs) -> dict:
    """``d`` with the named outputs of its analysis (:meth:`fem.study.Study.outputs`): ``named_outputs``
    {name: description and values} and ``named_outputs_notes``; nothing where the analysis has none."""
    if outputs is None:
        return d
    if isinstance(outputs, dict):                  # a [steady] curve: amplitude, peak, mean per point
        d["named_outputs"], d["named_outputs_notes"] = outputs, []
        return d
    if not np.all(np.isfinite(np.asarray(outputs.values))):
        d["named_outputs"], d["named_outputs_notes"] = None, list(outputs.notes)
        d.setdefault("warnings", []).append("named outputs not written: they overflow double precision (scale the "
                                            "model's units; the analysis' own results above are unaffected)")
        return d
    d["named_outputs"] = named_outputs_data(outputs)
    d["named_outputs_notes"] = list(outputs.notes)
    return d


def named_outputs_data(outputs) -> dict:
    """{name: quantity, unit, source, where (and what locates it: x, side, section_quantity, dof, between,
    ratios, ...) + the analysis' values}: time histories -- the derived quantities (peak, max, min, mean,
    rms, peak_to_peak, dynamic_load_factor); modes -- ``modes`` (one value per mode, complex for complex
    modes); frequencies -- ``response`` (complex), ``amplitude``, ``phase_lag_deg``, ``peak``,
    ``peak_omega_rad_s``; Campbell speeds -- ``shape`` (complex, per speed), ``amplitude``, ``peak``,
    ``peak_speed_rad_s``."""
    out = {}
    for k, c in enumerate(outputs.channels):
        d = {**c.describe(), **outputs.summaries.get(c.name, {})}
        v = outputs.values[k]
        if outputs.axis == "mode":
            d["modes"] = np.real_if_close(v) if np.iscomplexobj(v) and not np.any(np.imag(v)) else v
        elif outputs.axis == "omega":
            z = np.asarray(v, dtype=complex)
            d.update({"response": z, "amplitude": np.abs(z), "phase_lag_deg": np.mod(-np.degrees(np.angle(z)), 360.0)})
        elif outputs.axis == "speed":          # Campbell: one tracked mode shape per speed
            z = np.asarray(v, dtype=complex)
            d.update({"shape": z, "amplitude": np.abs(z)})
        out[c.name] = d
    return out


# ------------------------------------------------------------------ modal
def modal_data(study, res) -> dict:
    """Modal keys for FE, lumped, hybrid (ModalResult) and drive (DriveModalResult) results."""
    if study.kind == "drive":
        return _drive_modal(res)
    if study.kind == "rotor":
        return _rotor_modal(study, res)
    if study.kind == "train":
        return _train_modal(study, res)
    d = res.to_dict()
    ok = res.reliable | res.rigid
    d["omega_rad_s"] = [v if r else None for v, r in zip(res.omega_rad_s.tolist(), ok)]
    d["frequencies_hz"] = [v if r else None for v, r in zip(res.frequencies_hz.tolist(), ok)]
    d["omega_rad_s_unverified"] = res.omega_rad_s.tolist()
    if study.kind == "fe":
        fe = study.fe_model
        d["physics"] = fe.system.physics
        d["element"] = fe.model.element_name
        d["n_elements"] = fe.mesh.n_elements
        shapes = {}
        for fld in fe.model.fields:
            vals, xs = [], None
            for r in range(res.omega_rad_s.size):
                xs, v = fe.nodal_values(res.shapes[:, r], fld)
                vals.append(v)
            shapes[fld] = {"x": xs, "modes": vals}
        d["mode_shapes"] = shapes
    else:
        d["mode_shapes"] = {"dofs": study.linear_system().labels(), "modes": res.shapes.T}
    return d


def _drive_modal(res) -> dict:
    d = res.to_dict()
    m = res.modal
    ok = res.reliable
    n = res.omega_rad_s.size
    d.update({"omega_rad_s": [v if r else None for v, r in zip(res.omega_rad_s.tolist(), ok)],
              "frequencies_hz": [v if r else None for v, r in zip(res.frequencies_hz.tolist(), ok)],
              "omega_rad_s_unverified": res.omega_rad_s.tolist(), "reliable": ok.tolist(),
              "rayleigh_rel_diff": m.rayleigh_rel_diff.tolist() if m is not None else [None] * n,
              "precision_bound": m.precision_bound.tolist() if m is not None else [None] * n,
              "rigid_body_modes": m.rigid_body_modes if m is not None else int(np.sum(res.omega_rad_s == 0)),
              "mode_shapes": res.shapes})
    return d


# ------------------------------------------------------------------ forced
def forced_data(study, res) -> dict:
    """One shape for linear FE/lumped, drive and nonlinear (steady) results: outputs x frequencies."""
    from discrete.steady import AFCResult

    if study is not None and study.kind == "train" and not isinstance(res, AFCResult):
        d = _train_forced(res)
        loads = res.static_section_loads(study.train)
        if all(np.all(np.isfinite(np.asarray(q))) for v in loads.values() for q in v.quantities.values()):
            d["section_loads_static"] = {k: v.to_dict() for k, v in loads.items()}
        else:
            d.setdefault("warnings", []).append("section loads not written: they overflow double precision")
        return d
    if isinstance(res, AFCResult):
        d = res.to_dict()
        om = res.omega
        d.update({"omega_rad_s": om, "frequencies_hz": om / (2 * np.pi), "outputs": [res.response_label],
                  "amplitude": [res.response], "phase_lag_deg": None, "response": None,
                  "damping": None, "warnings": d.get("warnings", [])})
        d["steady"] = True
        d["psi_time_domain"] = study.damping_report.to_dict() if study.damping_report is not None else None
        return d
    if study.kind == "rotor":
        return _rotor_forced(res)
    if study.kind == "drive":
        d = res.to_dict()
        Z = np.concatenate([res.theta, res.y], axis=1).T            # (2n, n_freq)
        n = res.theta.shape[1]
        outputs = [f"theta{j + 1}" for j in range(n)] + [f"y{j + 1}" for j in range(n)]
        for key in ("theta_real", "theta_imag", "theta_amplitude", "y_amplitude", "y_real", "y_imag"):
            d.pop(key, None)
        if res.reference_theta is not None:
            d["reference_theta"] = np.asarray(res.reference_theta).T
        d.update({"outputs": outputs, "response": Z, "amplitude": np.abs(Z),
                  "phase_lag_deg": np.mod(-np.degrees(np.angle(Z)), 360.0), "steady": False})
        return d
    d = res.to_dict()
    d.pop("real", None)
    d.pop("imag", None)
    d["response"] = res.response.T
    if res.relative is not None:
        d["relative_amplitude"] = np.abs(res.relative).T
    d["steady"] = False
    return d


# ------------------------------------------------------------------ simulate
def simulate_data(study, res, outputs=None, history=None) -> dict:
    """The simulation's summary; ``outputs``: its named outputs (``named_outputs``: each one's description
    and derived quantities; ``element_summary``: impacts and friction work per element); ``history``: where
    the time history went (--h5) and how it was decimated."""
    solver = getattr(res, "solver", res)
    d = res.to_dict(events=False)
    d["events"] = events_json(solver.events)
    d["psi_time_domain"] = study.damping_report.to_dict() if study.damping_report is not None else None
    with_outputs(d, outputs)
    if outputs is not None:
        d["element_summary"] = outputs.elements
    d["history"] = history
    return d


def events_json(events):
    """The ``events`` list ({t, kind, element, state: {dof: {x, v}}} each, design.md §5) as JSON text
    built in one pass from the run's arrays of event states (:class:`discrete.nonsmooth.result.EventState`:
    a long run's thousands of events are written without building a dictionary per event); other events
    through the one encoder.  Numbers are written as Python's repr (the shortest round-trip form, as
    ``json`` writes them); a non-finite one is refused like everywhere else."""
    import json

    from discrete.errors import SolverError
    from discrete.nonsmooth.result import EventState

    from .jsonio import Raw

    if not events:
        return []
    first = events[0].state
    if not (type(first) is EventState and all(type(e.state) is EventState and e.state._x is first._x
                                               for e in events)):
        return [e.to_dict() for e in events]
    names = first._names
    cols = np.fromiter((e.state._k for e in events), dtype=np.intp, count=len(events))
    X, V = first._x[:, cols], first._v[:, cols]
    t = np.fromiter((e.t for e in events), dtype=float, count=len(events))
    for what, arr in (("t", t), ("x", X), ("v", V)):
        if not np.all(np.isfinite(arr)):
            k = int(np.argwhere(~np.isfinite(arr.reshape(-1, t.size)))[0][-1])
            raise SolverError(f"the result is not finite at $.events[{k}] ({what}): the computation lost its meaning "
                              "there (check the model's parameters, or the solver's warnings above)")
    # one %-template per line: t, kind, element, then x and v of every coordinate (repr: json's own form)
    template = '{"t": %r, "kind": %s, "element": %s, "state": {' + ", ".join(
        json.dumps(str(n)).replace("%", "%%") + ': {"x": %r, "v": %r}' for n in names) + "}}"
    kinds = {k: json.dumps(k) for k in {e.kind for e in events}}
    elems = {k: json.dumps(k) for k in {e.element for e in events}}
    XV = np.empty((t.size, 2 * len(names)))
    XV[:, 0::2], XV[:, 1::2] = X.T, V.T
    rows, tl = XV.tolist(), t.tolist()
    lines = [template % (tl[k], kinds[e.kind], elems[e.element], *rows[k]) for k, e in enumerate(events)]
    return Raw("[\n    " + ",\n    ".join(lines) + "\n  ]", len(lines))


def linearisation_data(study) -> list | None:
    """What the linear analysis did with each nonsmooth element (None: the file has none)."""
    return study.linearisation


def run_up_data(study, res) -> dict:
    """A rotor's run-up (:class:`fem.rotor.RunUpResult`): summary, events, energy balance, the samples."""
    return res.to_dict(samples=True)


# ------------------------------------------------------------------ parametric
def parametric_data(study, spec, chart) -> dict:
    """The stability chart of ``drivefem parametric`` (a :class:`StabilityChart` and its file spec)."""
    d = chart.to_dict()
    d["omega_ratio"] = (chart.omega_rad_s / chart.natural_omega_rad_s[0]).tolist()
    d["omega_grid_unit"] = spec.omega_unit
    d["parts"] = list(spec.parts)
    return d


# ------------------------------------------------------------------ rotor files
def _complex_modes(res) -> tuple[dict, int]:
    """The modal contract's frequencies of complex modes (rotor, train): those neither reliable nor rigid
    null (their values kept as ``omega_rad_s_unverified``), the eigenvalues complex; (dict, n_modes)."""
    d = res.to_dict()
    ok = res.reliable | res.rigid
    d["omega_rad_s_unverified"] = d["omega_rad_s"]
    d["omega_rad_s"] = [v if r else None for v, r in zip(d["omega_rad_s"], ok)]
    d["frequencies_hz"] = [v if r else None for v, r in zip(d["frequencies_hz"], ok)]
    d["eigenvalues"] = res.eigenvalues
    d.pop("eigenvalues_real", None)
    d.pop("eigenvalues_imag", None)
    return d, res.n_modes


def _rotor_modal(study, res) -> dict:
    """Complex modes at a speed (:class:`fem.rotor.RotorModes`) in the modal contract's shape."""
    d, n = _complex_modes(res)
    d["kind_of_mode"] = d.pop("kind")
    d["rayleigh_rel_diff"] = [None] * n
    d["precision_bound"] = [None] * n
    d["speed_rpm"] = res.speed_rad_s * 30.0 / np.pi
    rs = study.rotor
    d["mode_shapes"] = {"x": res.node_x, "v": res.shapes[rs.node_dofs["v"]].T, "w": res.shapes[rs.node_dofs["w"]].T}
    return d


def _rotor_forced(res) -> dict:
    """Unbalance response (:class:`fem.rotor.UnbalanceResponse`): the speeds are the forcing frequencies."""
    d = res.to_dict()
    probes = d.pop("probes")
    w = res.speeds_rad_s
    d.update({"omega_rad_s": w, "frequencies_hz": w / (2 * np.pi),
              "outputs": [p["label"] for p in probes],
              "amplitude": [p["amplitude"] for p in probes], "phase_lag_deg": [p["phase_lag_deg"] for p in probes],
              "response": [pr.value for pr in res.probes],
              "probes": [{"x": p["x"], "direction": p["direction"], "name": p["name"]} for p in probes],
              "damping": "bearing and seal coefficients (no global damping)", "steady": False})
    return d


def campbell_data(study, camp) -> dict:
    """The Campbell diagram of ``drivefem campbell`` (:class:`fem.rotor.CampbellResult`)."""
    d = camp.to_dict()
    d["kind_of_mode"] = d.pop("kind")          # "kind" is the file's kind in every document
    sys_ = study.train if study.kind == "train" else study.rotor
    d["n_dofs"] = sys_.n_dofs - int(sys_.constrained.size)
    if study.kind == "train":
        d["speed_ratios"] = dict(study.train.ratios)
    return d


def _train_forced(res) -> dict:
    """A train's linear response over speed (:class:`fem.train.forced.TrainForcedResult`): the speeds as
    ``omega_rad_s``; outputs: every connection coordinate's peak force and dynamic load factor, every
    bearing's peak radial force."""
    d = res.to_dict()
    outs, amp = [], []
    for c in res.connections:
        outs.append(f"{c.connection}:{c.coordinate} peak force")
        amp.append(c.peak)
        outs.append(f"{c.connection}:{c.coordinate} dynamic load factor")
        amp.append(np.where(np.isfinite(c.dynamic_factor), c.dynamic_factor, 0.0))
    for k, v in res.bearings.items():
        outs.append(f"{k} peak radial force")
        amp.append(v["peak_radial"])
    w = res.speeds_rad_s
    d.update({"omega_rad_s": w, "frequencies_hz": w / (2 * np.pi), "outputs": outs, "amplitude": amp,
              "phase_lag_deg": None, "response": None, "steady": False,
              "damping": "bearings, mesh and coupling dampers (no global damping)"})
    return d


def _train_modal(study, res) -> dict:
    """Complex modes of a train at a reference speed (:class:`fem.train.TrainModes`)."""
    d, n = _complex_modes(res)
    d["rayleigh_rel_diff"] = [None] * n
    d["precision_bound"] = [None] * n
    ts = study.train
    d["speed_ratios"] = dict(ts.ratios)
    d["mode_shapes"] = {"labels": res.labels, "shapes": res.shapes.T}
    return d
