"""Interactive figures as self-contained HTML files (plotly, an optional extra: ``pip install
'drivefem[html]'``): zoom, pan and hover on the Campbell diagram and the Bode plot.

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
