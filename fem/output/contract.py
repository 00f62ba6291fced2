"""The output contract: what every command's JSON holds (README "CLI and JSON").

Every file has ``schema`` ("drivefem.<command>"), ``version`` (:data:`SCHEMA_VERSION`), ``title``
and ``kind`` (fe | lumped | hybrid | drive), then the command's keys:

* modal: ``omega_rad_s``, ``frequencies_hz`` (null for a mode that is not reliable; its raw value in
  ``omega_rad_s_unverified``), ``n_dofs``, ``n_modes``, ``residuals``, ``rayleigh_rel_diff`` and
  ``precision_bound`` (null where a representation has none), ``reliable``, ``rigid_body_modes``,
  ``mode_shapes``, ``method``, ``warnings``; drive files add their representation, reference and
  stop band.
* forced: ``frequencies_hz``, ``omega_rad_s`` (n_freq), ``outputs`` (n_out names), ``amplitude`` and
  ``phase_lag_deg`` (n_out x n_freq), ``response`` (complex, n_out x n_freq; null for the nonlinear
  curve, whose amplitude is its response measure), ``method``, ``damping``, ``warnings``; the
  nonlinear curve (``steady``) adds ``stable``, ``max_multiplier``, ``folds``, ``reason``, ...
* simulate: ``t_end``, ``events``, ``period``, ``energy_error``, ``stopped_early``, ``reason``, ...
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
  shaft nodes; forced is the unbalance response with the speeds as ``omega_rad_s``, one output per
  probe, ``peaks`` (AF, separation margins) and ``orbit_major`` (n_speeds x n_nodes); campbell:
  ``speeds_rad_s``, ``speeds_rpm``, ``omega_rad_s``, ``natural_frequency_rad_s``, ``log_decrement``,
  ``damping_ratio``, ``whirl`` (n_modes x n_speeds), ``kind_of_mode``, ``mac_min``, ``residual_max``,
  ``orders``, ``critical_speeds``, ``warnings``.
* ``section_loads`` (FE, hybrid and rotor files; absent for lumped and drive files and nonlinear steady
  states): the internal loads of the result (docs/loads.md) -- ``quantities`` (names), ``units``,
  ``kind`` (modal | harmonic | time), ``stations`` (which), ``x`` and ``side`` (n_x; "left"/"right": the
  value just left/right of x), ``values`` {quantity: n_x x n_columns} with one column per mode,
  frequency or time sample (``omega_rad_s`` of frequencies and undamped modes, complex ``eigenvalues`` of
  rotor modes, or ``t``), ``normalisation`` (modes),
  ``reactions`` {``labels``, ``units``, ``values``: n_reactions x n_columns}, ``convention``, ``notes``.
Complex numbers are ``{"re": .., "im": ..}``; no number is NaN or infinite.
"""
from __future__ import annotations

import numpy as np

SCHEMA_VERSION = 1


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


def with_loads(study, res, d: dict) -> dict:
    """``d`` with the key ``section_loads`` where the study's kind has internal loads of ``res``."""
    loads = study.loads(res) if study is not None and study.kind in ("fe", "hybrid", "rotor") else None
    if loads is not None and loads.finite:
        d["section_loads"] = loads.to_dict()
    elif loads is not None:
        d["section_loads"] = None
        d.setdefault("warnings", []).append("section loads not written: they overflow double precision (scale the "
                                            "model's units; the analysis' own results above are unaffected)")
    return d


# ------------------------------------------------------------------ modal
def modal_data(study, res) -> dict:
    """Modal keys for FE, lumped, hybrid (ModalResult) and drive (DriveModalResult) results."""
    if study.kind == "drive":
        return _drive_modal(res)
    if study.kind == "rotor":
        return with_loads(study, res, _rotor_modal(study, res))
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
    return with_loads(study, res, d)


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
        return with_loads(study, res, _rotor_forced(res))
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
    return with_loads(study, res, d)


# ------------------------------------------------------------------ simulate
def simulate_data(study, res) -> dict:
    d = res.to_dict()
    d["psi_time_domain"] = study.damping_report.to_dict() if study.damping_report is not None else None
    return with_loads(study, res, d)


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
def _rotor_modal(study, res) -> dict:
    """Complex modes at a speed (:class:`fem.rotor.RotorModes`) in the modal contract's shape."""
    d = res.to_dict()
    ok = res.reliable | res.rigid
    n = res.n_modes
    d["omega_rad_s_unverified"] = d["omega_rad_s"]
    d["omega_rad_s"] = [v if r else None for v, r in zip(d["omega_rad_s"], ok)]
    d["frequencies_hz"] = [v if r else None for v, r in zip(d["frequencies_hz"], ok)]
    d["eigenvalues"] = res.eigenvalues
    d.pop("eigenvalues_real", None)
    d.pop("eigenvalues_imag", None)
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
              "outputs": [f"{p['direction']}@x={p['x']:g}" for p in probes],
              "amplitude": [p["amplitude"] for p in probes], "phase_lag_deg": [p["phase_lag_deg"] for p in probes],
              "response": [pr.value for pr in res.probes], "probes": [{"x": p["x"], "direction": p["direction"]}
                                                                     for p in probes],
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
    d = res.to_dict()
    ok = res.reliable | res.rigid
    n = res.n_modes
    d["omega_rad_s_unverified"] = d["omega_rad_s"]
    d["omega_rad_s"] = [v if r else None for v, r in zip(d["omega_rad_s"], ok)]
    d["frequencies_hz"] = [v if r else None for v, r in zip(d["frequencies_hz"], ok)]
    d["eigenvalues"] = res.eigenvalues
    d.pop("eigenvalues_real", None)
    d.pop("eigenvalues_imag", None)
    d["rayleigh_rel_diff"] = [None] * n
    d["precision_bound"] = [None] * n
    ts = study.train
    d["speed_ratios"] = dict(ts.ratios)
    d["mode_shapes"] = {"labels": res.labels, "shapes": res.shapes.T}
    return d
