"""Interactive figures as self-contained HTML files (plotly, an optional extra: ``pip install
'drivefem[html]'``): zoom, pan and hover on the Campbell diagram, the Bode plot, the harmonic
response and the nonlinear amplitude-frequency curve (``forced``) and the time histories
(``simulate``).

The file embeds plotly.js (``include_plotlyjs=True``, about 3.5 MB), so it opens offline in any
browser.  Nothing here computes: each function draws a result object like its matplotlib
counterpart in :mod:`fem.rotor.plots` (same quantities, units, names and markers)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from discrete.errors import ModelError

RPM = 30.0 / np.pi
EXTRA = "pip install 'drivefem[html]'  (plotly >= 5)"
DASH = {"forward": "solid", "backward": "dash", "mixed": "dashdot", "planar": "dot", "none": "solid"}


def require_plotly(option: str = "--html"):
    """The plotly module, or a :class:`ModelError` (exit 2) naming the optional extra to install."""
    try:
        import plotly.graph_objects as go  # noqa: F401
    except ImportError:
        raise ModelError("command line", option, None, f"the optional package plotly for interactive HTML figures: "
                         f"{EXTRA}") from None
    import plotly

    return plotly


def _write(fig, path) -> Path:
    path = Path(path)
    fig.write_html(str(path), include_plotlyjs=True, full_html=True)
    return path


def campbell_html(camp, path, *, title: str = "", operating_range=None) -> Path:
    """The Campbell diagram (damped frequencies [Hz] vs speed [rev/min], excitation lines, critical
    speeds and backward crossings apart, operating range) and the log decrements below."""
    require_plotly()
    from plotly.subplots import make_subplots
    import plotly.graph_objects as go

    from ..rotor.plots import _dominant, mode_tags

    s = camp.speeds_rad_s * RPM
    f = camp.omega_damped_rad_s / (2 * np.pi)
    tags = mode_tags(camp)
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, row_heights=[0.7, 0.3], vertical_spacing=0.06)
    for j in range(camp.n_modes):
        w = _dominant([row[j] for row in camp.whirl])
        ld = np.where(np.isfinite(camp.log_decrement[:, j]), camp.log_decrement[:, j], np.nan)
        name = f"mode {tags[j]} ({w})"
        fig.add_trace(go.Scatter(x=s, y=f[:, j], mode="lines", name=name, legendgroup=name, line=dict(dash=DASH.get(w)),
                                 hovertemplate="%{x:.0f} rev/min<br>%{y:.3f} Hz<extra>" + name + "</extra>"), 1, 1)
        fig.add_trace(go.Scatter(x=s, y=ld, mode="lines", name=name, legendgroup=name, showlegend=False,
                                 line=dict(dash=DASH.get(w)),
                                 hovertemplate="%{x:.0f} rev/min<br>log dec %{y:.4f}<extra>" + name + "</extra>"), 2, 1)
    top = float(np.nanmax(f)) * 1.08 if f.size else 1.0
    for k in camp.orders:
        fig.add_trace(go.Scatter(x=s, y=k * s / 60.0, mode="lines", name=f"{k:g}x", line=dict(color="gray", width=1),
                                 hoverinfo="skip"), 1, 1)
    for group, marker, label in ((camp.critical_speeds, dict(symbol="circle", color="black", size=9), "critical speed"),
                                 (camp.backward_crossings, dict(symbol="square-open", color="red", size=9),
                                  "backward crossing")):
        if group:
            fig.add_trace(go.Scatter(x=[c.speed_rpm for c in group], y=[c.frequency_rad_s / (2 * np.pi) for c in group],
                                     mode="markers", marker=marker, name=label,
                                     text=[f"{c.speed_rpm:.1f} rev/min, order {c.order:g}, mode {c.mode + 1} "
                                           f"({c.whirl}), log dec {c.log_decrement:.3f}" for c in group],
                                     hovertemplate="%{text}<extra>" + label + "</extra>"), 1, 1)
    if operating_range is not None:
        lo, hi = (v * RPM for v in operating_range)
        fig.add_vrect(x0=lo, x1=hi, fillcolor="green", opacity=0.13, line_width=0,
                      annotation_text=f"operating range {lo:.0f}-{hi:.0f} rev/min", annotation_position="top left")
    fig.update_yaxes(title_text="damped natural frequency [Hz]", range=[0, top], row=1, col=1)
    fig.update_yaxes(title_text="log decrement [-]", row=2, col=1)
    fig.update_xaxes(title_text="speed [rev/min]", row=2, col=1)
    fig.update_layout(title=f"Campbell diagram: {title}" if title else "Campbell diagram", hovermode="closest",
                      template="plotly_white")
    return _write(fig, path)


def bode_html(resp, path, *, title: str = "") -> Path:
    """The unbalance response: amplitude [um] (log) and phase lag [deg] of every probe against
    speed [rev/min], peaks with their amplification factor, the operating range shaded."""
    require_plotly()
    from plotly.subplots import make_subplots
    import plotly.graph_objects as go

    s = resp.speeds_rad_s * RPM
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, row_heights=[0.6, 0.4], vertical_spacing=0.06)
    for j, p in enumerate(resp.probes):
        name = getattr(p, "label", None) or f"x = {p.x:g} m ({p.direction})"
        fig.add_trace(go.Scatter(x=s, y=p.amplitude * 1e6, mode="lines", name=name, legendgroup=name,
                                 hovertemplate="%{x:.0f} rev/min<br>%{y:.4g} um<extra>" + name + "</extra>"), 1, 1)
        fig.add_trace(go.Scatter(x=s, y=p.phase_lag_deg, mode="lines", name=name, legendgroup=name, showlegend=False,
                                 hovertemplate="%{x:.0f} rev/min<br>%{y:.1f} deg<extra>" + name + "</extra>"), 2, 1)
    if resp.peaks:
        fig.add_trace(go.Scatter(x=[pk.speed_rad_s * RPM for pk in resp.peaks], y=[pk.amplitude * 1e6 for pk in resp.peaks],
                                 mode="markers", marker=dict(symbol="triangle-down", color="black", size=9), name="peaks",
                                 text=[f"{pk.speed_rad_s * RPM:.1f} rev/min, AF "
                                       + ("n/a" if pk.amplification_factor is None else f"{pk.amplification_factor:.2f}")
                                       for pk in resp.peaks], hovertemplate="%{text}<extra>peak</extra>"), 1, 1)
    if resp.operating_range is not None:
        lo, hi = (v * RPM for v in resp.operating_range)
        fig.add_vrect(x0=lo, x1=hi, fillcolor="green", opacity=0.13, line_width=0)
    fig.update_yaxes(title_text="amplitude [um]", type="log", row=1, col=1)
    fig.update_yaxes(title_text="phase lag [deg]", range=[0, 360], dtick=90, row=2, col=1)
    fig.update_xaxes(title_text="speed [rev/min]", row=2, col=1)
    fig.update_layout(title=f"Unbalance response: {title}" if title else "Unbalance response", template="plotly_white")
    return _write(fig, path)


def _two_panels(rows: int = 2, heights=(0.6, 0.4)):
    from plotly.subplots import make_subplots

    return make_subplots(rows=rows, cols=1, shared_xaxes=True, row_heights=list(heights), vertical_spacing=0.06)


def frf_html(result, path, *, title: str = "") -> Path:
    """A harmonic response (FE, lumped or drive): amplitude (log; quantity and unit per output) and
    phase lag [deg] against frequency [Hz], one trace per output named as in the model file."""
    require_plotly()
    import plotly.graph_objects as go

    from .figures.modes import _frf_arrays
    from .figures.quantities import output_quantity

    f, Z, names, kind = _frf_arrays(result)
    fig = _two_panels()
    units = set()
    for j, name in enumerate(names):
        legend, q, u = output_quantity(name, kind)
        units.add(u)
        lag = np.mod(-np.degrees(np.angle(Z[:, j])), 360.0)
        if f.size > 40:                                  # a sweep: unwrapped along it
            lag = np.rad2deg(np.unwrap(np.deg2rad(lag)))
        fig.add_trace(go.Scatter(x=f, y=np.abs(Z[:, j]), mode="lines" if f.size > 40 else "markers", name=legend,
                                 legendgroup=legend,
                                 hovertemplate="%{x:.5g} Hz<br>%{y:.4g} " + u + "<extra>" + legend + "</extra>"), 1, 1)
        fig.add_trace(go.Scatter(x=f, y=lag, mode="lines" if f.size > 40 else "markers", name=legend, legendgroup=legend,
                                 showlegend=False,
                                 hovertemplate="%{x:.5g} Hz<br>%{y:.1f} deg<extra>" + legend + "</extra>"), 2, 1)
    fig.update_yaxes(title_text=f"amplitude [{', '.join(sorted(units))}]", type="log", row=1, col=1)
    fig.update_yaxes(title_text="phase lag [deg]", row=2, col=1)
    fig.update_xaxes(title_text="frequency f [Hz]", row=2, col=1)
    damping = getattr(result, "damping", None)
    fig.update_layout(title=(f"{title}: " if title else "") + "harmonic response" + (f" ({damping})" if damping else ""),
                      template="plotly_white")
    return _write(fig, path)


def afc_html(result, path, *, title: str = "") -> Path:
    """A nonlinear amplitude-frequency curve of ``[steady]``: the stable branch solid, the unstable
    dashed, folds marked, the backbone dash-dotted; hover gives frequency, response and the largest
    Floquet multiplier."""
    require_plotly()
    import plotly.graph_objects as go

    from .figures.quantities import measure_label, method_text

    ref = result.omega_ref
    x = np.asarray(result.z if ref else result.omega, float)
    y = np.asarray(result.response, float)
    st = np.asarray(result.stable, bool)
    mu = np.asarray(getattr(result, "max_multiplier", np.full(y.size, np.nan)), float)
    q, u = measure_label(result.response_label)
    name = method_text(result.method)
    fig = go.Figure()
    for keep, branch, dash in ((st, "stable branch", "solid"), (~st, "unstable branch", "dash")):
        yy = np.where(keep, y, np.nan)
        for i in range(1, st.size):                  # join the branches where the stability changes
            if st[i] != st[i - 1] and not keep[i - 1] and keep[i]:
                yy[i - 1] = y[i - 1]
        if np.any(keep):
            fig.add_trace(go.Scatter(x=x, y=yy, mode="lines", name=f"{name}: {branch}", line=dict(dash=dash, color="#1f77b4"),
                                     customdata=mu, hovertemplate="%{x:.6g}<br>%{y:.5g} " + u
                                     + "<br>max |Floquet multiplier| %{customdata:.4f}<extra>" + branch + "</extra>"))
    if result.folds:
        fx = [fo["omega"] / ref if ref else fo["omega"] for fo in result.folds]
        fig.add_trace(go.Scatter(x=fx, y=[fo["response"] for fo in result.folds], mode="markers", name="folds",
                                 marker=dict(symbol="circle-open", size=9, color="#1f77b4")))
    bb = (result.extra or {}).get("backbone")
    if bb and bb.get("response"):
        fig.add_trace(go.Scatter(x=np.asarray(bb["omega_rad_s"]) / (ref or 1.0), y=bb["response"], mode="lines",
                                 name=f"backbone: {method_text(bb['method'])}", line=dict(dash="dashdot", color="gray")))
    fig.update_xaxes(title_text=f"excitation frequency omega / omega_ref [-] (omega_ref = {ref:.6g} rad/s)" if ref
                     else "excitation frequency omega [rad/s]")
    fig.update_yaxes(title_text=f"{q} [{u}]")
    fig.update_layout(title=(f"{title}: " if title else "") + "amplitude-frequency curve", template="plotly_white")
    return _write(fig, path)


def simulation_html(result, outputs, path, *, title: str = "") -> Path:
    """The time histories of a simulation: one panel per unit of the named outputs (twist, speeds,
    loads, ...; :mod:`fem.loads`) when the model has them, else the coordinates and their velocities;
    events as markers on the time axis."""
    require_plotly()
    import plotly.graph_objects as go
    from plotly.subplots import make_subplots

    solver = getattr(result, "solver", result)
    panels = []                             # (axis title, [(name, t, values)])
    if outputs is not None and getattr(outputs, "channels", None):
        groups: dict = {}
        for k, c in enumerate(outputs.channels):
            groups.setdefault((c.quantity if len({cc.unit for cc in outputs.channels if cc.quantity == c.quantity}) == 1
                               else c.unit, c.unit), []).append(k)
        t = np.asarray(outputs.axis_values, float)
        for (quantity, unit), ks in list(groups.items())[:8]:
            panels.append((f"{quantity} [{unit}]", [(outputs.channels[k].name, t, np.real(outputs.values[k])) for k in ks]))
    else:
        t = np.asarray(solver.t, float)
        names = list(solver.names)
        panels.append(("displacement or angle [m | rad]", [(n, t, solver.x[i]) for i, n in enumerate(names)]))
        panels.append(("velocity [m/s | rad/s]", [(n, t, solver.v[i]) for i, n in enumerate(names)]))
    fig = make_subplots(rows=len(panels), cols=1, shared_xaxes=True, vertical_spacing=0.04)
    for r, (label, series) in enumerate(panels, 1):
        for name, tt, y in series:
            fig.add_trace(go.Scattergl(x=tt, y=y, mode="lines", name=name,
                                       hovertemplate="t = %{x:.6g} s<br>%{y:.5g}<extra>" + name + "</extra>"), r, 1)
        fig.update_yaxes(title_text=label, row=r, col=1)
    events = getattr(solver, "events", None) or []
    if events and len(events) < 5000:
        kinds = sorted({e.kind for e in events})
        for kind in kinds:
            tt = [e.t for e in events if e.kind == kind]
            fig.add_trace(go.Scattergl(x=tt, y=[0.0] * len(tt), mode="markers", name=f"event: {kind}",
                                       marker=dict(size=6, symbol="x-thin-open"),
                                       hovertemplate="t = %{x:.6g} s<extra>" + kind + "</extra>"), len(panels), 1)
    fig.update_xaxes(title_text="time t [s]", row=len(panels), col=1)
    fig.update_layout(title=(f"{title}: " if title else "") + "time histories", template="plotly_white",
                      height=max(450, 260 * len(panels)))
    return _write(fig, path)
