"""Text labels that do not collide, and the check that none do.

:func:`place_labels` puts each label at the first of a list of candidate offsets (points from its
anchor) whose rendered text box overlaps no box already placed, none of the boxes to avoid (the
axes' other texts, the legend) and stays inside the axes; when every candidate collides it takes
the one with the least overlap.  Offsets farther than a few points get a thin leader line.  The
figure's layout must be final before the labels are placed (``tight_layout`` first, no re-layout
when saving): the boxes are measured with the figure's own renderer.

:func:`overlapping_texts` lists the pairs of visible texts of a drawn figure whose boxes
intersect (the tests' check on every figure); :func:`axis_labels_without_unit` the axes whose
visible tick labels have no label of the form ``quantity [unit]``.
"""
from __future__ import annotations

import itertools
import re

import numpy as np
from matplotlib.text import Text
from matplotlib.transforms import Bbox

#: candidate offsets (dx, dy in points, horizontal and vertical alignment), nearest first
AROUND = [(5, 4, "left", "bottom"), (5, -4, "left", "top"), (-5, 4, "right", "bottom"), (-5, -4, "right", "top"),
          (0, 9, "center", "bottom"), (0, -9, "center", "top")] + \
    [(dx, dy, "left" if dx > 0 else "right", "bottom" if dy > 0 else "top")
     for r in (16, 28, 42) for dx, dy in ((r, r), (r, -r), (-r, r), (-r, -r), (0.4 * r, 1.6 * r), (0.4 * r, -1.6 * r))]
#: to the right of a line's end, shifted up or down
RIGHT_OF = [(4, dy, "left", "center") for dy in (0, 7, -7, 14, -14, 21, -21, 28, -28, 36, -36, 44, -44, 54, -54)]
LEADER_FROM = 12.0          # points: offsets at least this far get a leader line


def _renderer(fig):
    if not hasattr(fig.canvas, "get_renderer"):        # a Figure made without pyplot: give it an Agg canvas
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    return fig.canvas.get_renderer()


def _text_box(t: Text, renderer) -> Bbox:
    """The rendered box of the text only (an Annotation's leader line excluded)."""
    if hasattr(t, "update_positions"):
        t.update_positions(renderer)                    # an Annotation places its text at draw time
    return Text.get_window_extent(t, renderer)


def _overlap(a: Bbox, b: Bbox) -> float:
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w * h if w > 0 and h > 0 else 0.0


def _outside(box: Bbox, frame: Bbox) -> float:
    """Area of ``box`` outside ``frame``."""
    inside = _overlap(box, frame)
    return box.width * box.height - inside


def _undrawn_ticks(fig) -> set:
    """Tick labels matplotlib keeps but does not draw (their ticks lie outside the view limits)."""
    out = set()
    for ax in fig.axes:
        for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            lo, hi = min(lo, hi), max(lo, hi)
            log = axis.get_scale() == "log"        # a log axis: the tolerance is relative to each limit
            tol = 1e-9 * max(abs(lo), abs(hi), 1e-300)
            inside = (lambda x: lo * (1 - 1e-9) <= x <= hi * (1 + 1e-9)) if log else \
                (lambda x: lo - tol <= x <= hi + tol)
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                loc = tick.get_loc()
                if loc is None or not inside(loc) or not tick.get_visible():
                    out.update({id(tick.label1), id(tick.label2)})
    return out


def visible_texts(fig) -> list[Text]:
    """Every visible, non-empty text of a drawn figure (titles, labels, tick labels, legends, annotations)."""
    hidden = _undrawn_ticks(fig)
    out = []
    for t in fig.findobj(Text):
        if id(t) in hidden or not t.get_visible() or not t.get_text().strip():
            continue
        ax = getattr(t, "axes", None)
        if ax is not None and not ax.get_visible():
            continue
        out.append(t)
    return out


def existing_boxes(ax, renderer) -> list[Bbox]:
    """Boxes of the texts already in ``ax`` and of its legend."""
    boxes = [_text_box(t, renderer) for t in ax.texts if t.get_visible() and t.get_text().strip()]
    leg = ax.get_legend()
    if leg is not None and leg.get_visible():
        boxes.append(leg.get_window_extent(renderer))
    return boxes


def place_labels(ax, anchors, texts, *, offsets=None, avoid=None, inside: bool = True, colors=None, **text_kw) -> list:
    """Annotate ``ax`` with ``texts`` at the data points ``anchors`` [(x, y), ...] without overlaps
    (module notes); returns the annotation artists.  ``avoid``: further display boxes to keep
    clear (default: the axes' texts and legend); ``colors``: one colour per label."""
    fig = ax.figure
    renderer = _renderer(fig)
    placed = list(existing_boxes(ax, renderer) if avoid is None else avoid)
    frame = ax.get_window_extent(renderer)
    offsets = AROUND if offsets is None else offsets
    out = []
    for k, ((x, y), text) in enumerate(zip(anchors, texts)):
        best = None
        colour = None if colors is None else colors[k]
        for dx, dy, ha, va in offsets:
            far = np.hypot(dx, dy) >= LEADER_FROM
            kw = dict(text_kw)
            if colour is not None:
                kw.setdefault("color", colour)
            ann = ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points", ha=ha, va=va,
                              arrowprops=dict(arrowstyle="-", lw=0.5, color=colour or "0.35", shrinkA=0, shrinkB=2)
                              if far else None, annotation_clip=False, **kw)
            box = _text_box(ann, renderer)
            cost = sum(_overlap(box, b) for b in placed) + (_outside(box, frame) if inside else 0.0)
            if best is None or cost < best[0]:
                if best is not None:
                    best[1].remove()
                best = (cost, ann, box)
                if cost == 0.0:
                    break
            else:
                ann.remove()
        placed.append(best[2])
        out.append(best[1])
    return out


def overlapping_texts(fig, tolerance: float = 0.5) -> list[tuple[str, str]]:
    """Pairs of visible texts of ``fig`` whose rendered boxes overlap by more than ``tolerance``
    square pixels (draws the figure first)."""
    renderer = _renderer(fig)
    fig.canvas.draw()
    items = [(t.get_text(), _text_box(t, renderer)) for t in visible_texts(fig)]
    return [(a[0], b[0]) for a, b in itertools.combinations(items, 2) if _overlap(a[1], b[1]) > tolerance]


UNIT = re.compile(r"\[[^\]]+\]")
NUMBER = re.compile(r"^[$\s]*[-\u2212+]?(\d|\\mathdefault)")


def axis_labels_without_unit(fig) -> list[str]:
    """Axes (by title or index) with visible numeric tick labels on x or y but no axis label of the
    form ``quantity [unit]`` there (dimensionless quantities: ``[-]``; tick labels that name
    categories, e.g. mode families, need none)."""
    _renderer(fig)
    fig.canvas.draw()
    bad = []
    for i, ax in enumerate(fig.axes):
        if not ax.get_visible() or not ax.axison:
            continue
        for name, axis, label in (("x", ax.xaxis, ax.get_xlabel()), ("y", ax.yaxis, ax.get_ylabel())):
            ticks = [t for t in axis.get_ticklabels() if t.get_visible() and t.get_text().strip()]
            numeric = any(NUMBER.search(t.get_text()) for t in ticks)      # categories need no unit
            if numeric and not UNIT.search(label or ""):
                bad.append(f"axes {i} ({ax.get_title() or 'untitled'}): {name} label {label!r}")
    return bad


def colours_without_bar(fig) -> list[str]:
    """Axes (by title or index) where colour encodes a value (an image, a mesh, points or lines
    coloured by an array of numbers) in a figure without any colour bar."""
    if any(getattr(ax, "_colorbar", None) is not None for ax in fig.axes):
        return []
    bad = []
    for i, ax in enumerate(fig.axes):
        for art in list(ax.collections) + list(ax.images):
            values = art.get_array() if hasattr(art, "get_array") else None
            if values is not None and np.size(values) > 1:
                bad.append(f"axes {i} ({ax.get_title() or 'untitled'}): {type(art).__name__} coloured by value")
                break
    return bad


def figure_report(fig) -> dict:
    """What the figure standards check on a drawn figure: overlapping text pairs, axes without a
    unit label, colour that encodes a value without a colour bar, and the titles (axes titles and
    the figure's suptitle)."""
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    if getattr(fig, "_suptitle", None) is not None and fig._suptitle.get_text():
        titles.append(fig._suptitle.get_text())
    return {"overlaps": overlapping_texts(fig), "without_unit": axis_labels_without_unit(fig),
            "without_colour_bar": colours_without_bar(fig), "titles": titles}
