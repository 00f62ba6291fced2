"""The shaft as a side view under a figure of results along it: the segments' outline (outer and
inner diameters to scale across the strip), the supports (clamped: a hatched wall; pinned: a
triangle; spring: a zig-zag) and the point attachments (discs: a block whose size follows the
mass).  Draws a :class:`fem.model.ShaftModel`; nothing is computed here."""
from __future__ import annotations

import math

import numpy as np


def _diameters(section) -> tuple[float, float]:
    """(outer, inner) diameter of a section; an explicit section: the solid circle of its area."""
    if section.d is not None:
        return float(section.d), float(section.d) * float(section.inner_to_outer)
    A = getattr(section, "A", None)
    return (2.0 * math.sqrt(A / math.pi) if A else 0.0), 0.0


def support_text(s) -> str:
    if s.type == "spring":
        parts = [f"k = {s.k:.3g}"] + ([f"kr = {s.kr:.3g}"] if s.kr else [])
        return "spring support (" + ", ".join(parts) + ")"
    return f"{s.type} support"


def point_text(p) -> str:
    parts = ([f"{p.mass:.4g} kg"] if p.mass else []) + ([f"{p.inertia:.3g} kg m^2"] if p.inertia else []) + \
        ([f"k = {p.k:.3g}"] if p.k else []) + ([f"kr = {p.kr:.3g}"] if p.kr else [])
    return "point: " + ", ".join(parts) if parts else "point"


def draw_shaft(ax, model) -> None:
    """The side view of ``model`` on ``ax`` (its own strip: y in units of the largest diameter,
    no y ticks), x in metres."""
    from matplotlib.patches import Polygon, Rectangle

    x0 = 0.0
    dmax = max((_diameters(s.section)[0] for s in model.segments), default=1.0) or 1.0
    for seg in model.segments:
        do, di = _diameters(seg.section)
        h, hi = 0.5 * do / dmax, 0.5 * di / dmax
        ax.add_patch(Rectangle((x0, -h), seg.length, 2 * h, facecolor="0.82", edgecolor="0.25", lw=0.8))
        if hi > 0:
            ax.add_patch(Rectangle((x0, -hi), seg.length, 2 * hi, facecolor="white", edgecolor="0.5", lw=0.5, ls=":"))
        x0 += seg.length
    L = x0 or 1.0
    mtop = max((p.mass for p in model.points), default=0.0)
    for p in model.points:
        if p.mass <= 0 and p.inertia <= 0:
            continue
        hh = 0.55 + 0.35 * (p.mass / mtop if mtop > 0 else 0.5)
        w = 0.012 * L
        ax.add_patch(Rectangle((p.x - w / 2, -hh), w, 2 * hh, facecolor="tab:brown", edgecolor="k", lw=0.6, zorder=4))
    for s in model.supports:
        y = -0.55
        if s.type == "clamped":
            ax.plot([s.x, s.x], [-1.0, 1.0], color="k", lw=1.6, zorder=5)
            side = -1.0 if s.x <= 0.5 * L else 1.0
            for yy in np.linspace(-0.95, 0.95, 7):
                ax.plot([s.x, s.x + side * 0.015 * L], [yy, yy - 0.15], color="k", lw=0.7, zorder=5)
        elif s.type == "pinned":
            ax.add_patch(Polygon([[s.x, y], [s.x - 0.012 * L, y - 0.4], [s.x + 0.012 * L, y - 0.4]], closed=True,
                                 facecolor="white", edgecolor="k", lw=0.9, zorder=5))
        else:
            zz = np.linspace(y, y - 0.45, 9)
            xs = s.x + 0.008 * L * np.array([0, 1, -1, 1, -1, 1, -1, 1, 0])
            ax.plot(xs, zz, color="k", lw=0.8, zorder=5)
            ax.plot([s.x - 0.01 * L, s.x + 0.01 * L], [y - 0.45, y - 0.45], color="k", lw=1.2, zorder=5)
    ax.set_xlim(-0.03 * L, 1.03 * L)
    ax.set_ylim(-1.15, 1.15)
    ax.set_yticks([])
    for side in ("left", "right", "top"):
        ax.spines[side].set_visible(False)


def legend_handles(model) -> list:
    """Legend entries naming what the strip shows (supports, point attachments) by their values."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    out = []
    kinds = {}
    for s in model.supports:
        kinds.setdefault(s.type, []).append(s)
    marker = {"clamped": dict(marker="|", ms=10, mew=1.6), "pinned": dict(marker="^", ms=7, mfc="white"),
              "spring": dict(marker="$\\wr$", ms=9)}
    for kind, group in kinds.items():
        xs = ", ".join(f"{s.x:g}" for s in group)
        text = support_text(group[0]) if len(group) == 1 else f"{kind} supports"
        out.append(Line2D([], [], ls="none", color="k", label=f"{text} at x = {xs} m", **marker[kind]))
    for p in model.points:
        if p.mass > 0 or p.inertia > 0:
            out.append(Patch(facecolor="tab:brown", edgecolor="k", label=f"{point_text(p)} at x = {p.x:g} m"))
    return out
