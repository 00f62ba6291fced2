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
Complex numbers are ``{"re": .., "im": ..}``; no number is NaN or infinite.
"""
from __future__ import annotations

import numpy as np

SCHEMA_VERSION = 1


def payload(command: str, study, data: dict) -> dict:
    """The JSON document of ``command`` for ``study`` with the command's ``data``."""
    return {"schema": f"drivefem.{command}", "version": SCHEMA_VERSION,
            "title": study.title if study is not None else "", "kind": study.kind if study is not None else None,
            **data}


# ------------------------------------------------------------------ modal
def modal_data(study, res) -> dict:
    """Modal keys for FE, lumped, hybrid (ModalResult) and drive (DriveModalResult) results."""
    if study.kind == "drive":
        return _drive_modal(res)
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

    if isinstance(res, AFCResult):
        d = res.to_dict()
        om = res.omega
        d.update({"omega_rad_s": om, "frequencies_hz": om / (2 * np.pi), "outputs": [res.response_label],
                  "amplitude": [res.response], "phase_lag_deg": None, "response": None,
                  "damping": None, "warnings": d.get("warnings", [])})
        d["steady"] = True
        d["psi_time_domain"] = study.damping_report.to_dict() if study.damping_report is not None else None
        return d
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
def simulate_data(study, res) -> dict:
    d = res.to_dict()
    d["psi_time_domain"] = study.damping_report.to_dict() if study.damping_report is not None else None
    return d
