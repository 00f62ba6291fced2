"""Import a rotor saved by ROSS (``Rotor.save``, TOML) as a drivefem rotor model file.

ROSS (ross-rotordynamics, MIT licence) saves a rotor as one TOML table per element, named
``<Class>_<tag>``: ``ShaftElement`` (L, idl, odl, idr, odr, n, material {rho, E, G_s}, flags),
``DiskElement`` (n, m, Id, Ip), ``BearingElement`` / ``SealElement`` and other linear bearing
classes (kxx ... cyx, kzz, czz, m.. over ``frequency``), ``PointMass`` (n, mx, my, mz); and
``parameters`` (min_w, max_w, rated_w).  This module reads that file (no ROSS needed) and writes
the equivalent ``[rotor]`` file.

Conventions mapped (docs/rotor.md, "Importing a ROSS rotor"):

* axes: ROSS's x, y (lateral) and z (axial, the spin axis) become drivefem's y, z and x (a cyclic
  permutation: both right-handed, both spin about +axial): kxx -> kyy, kyy -> kzz, kxy -> kyz,
  kyx -> kzy (likewise c), kzz/czz -> k_axial/c_axial; ROSS's node n becomes the node at x = the
  sum of the lengths of the stations before it;
* units: SI on both sides (m, kg, N, s; ROSS's ``frequency`` is rad/s as drivefem's ``speeds``);
* 6 DOFs per node in ROSS: ``dofs = "full"``;
* shaft elements sharing a node number are ROSS's layered sections: the innermost becomes the
  segment's own section, the others ``[[rotor.segment.layer]]`` (each its own Timoshenko element,
  as in ROSS); consecutive identical stations are merged into one segment of several elements;
* Cowper's shear coefficient (ROSS's default) is drivefem's default; Hutchinson's is written as
  an explicit ``shear_coefficient`` (ROSS's formula for the element's mean diameter ratio);
* bearing tables keep their values; ``interpolation`` defaults to "smoothing-spline" with
  ``extrapolate = "continue"``: ROSS's own convention (scipy's ``UnivariateSpline`` with s = number
  of points, not an interpolant, extrapolated along its end cubics; :mod:`fem.rotor.tables`), so the
  converted rotor computes with ROSS's coefficients at every speed; the caller may choose
  "spline" / "linear" / "pchip" and "refuse" / "hold" / "linear" instead (the written file says
  which, and by how much ROSS's spline misses the table points);
* a ``PointMass`` linked to the shaft by bearings with ``n_link`` and held by a grounded bearing
  with constant, uncoupled coefficients becomes a ``[[rotor.pedestal]]``; a point mass on a shaft
  node (mx = my) a disc without inertia.

What drivefem cannot express is refused with a :class:`~discrete.errors.ModelError` naming the
element and the key (exit 2): axial force or torque preload, shear, rotary inertia or
gyroscopic effects switched off, Rayleigh damping (alpha, beta), bearing mass coefficients,
speed-dependent axial coefficients, anisotropic point masses, unknown element classes or keys.
"""
from __future__ import annotations

import math
import tomllib
from collections import Counter, defaultdict
from pathlib import Path

from discrete.errors import ModelError

LATERAL_MAP = {"kxx": "kyy", "kyy": "kzz", "kxy": "kyz", "kyx": "kzy",
               "cxx": "cyy", "cyy": "czz", "cxy": "cyz", "cyx": "czy"}
MASS_KEYS = ("mxx", "myy", "mxy", "myx", "mzz")
SHAFT_KEYS = {"L", "idl", "odl", "idr", "odr", "n", "material", "axial_force", "torque", "shear_effects",
              "rotary_inertia", "gyroscopic", "shear_method_calc", "tag", "alpha", "beta"}
DISK_KEYS = {"n", "m", "Id", "Ip", "tag", "scale_factor", "color"}
POINT_MASS_KEYS = {"n", "m", "mx", "my", "mz", "tag", "scale_factor", "color"}
#: keys of a linear bearing table that carry no mechanics (labels, plotting, a seal's leakage)
BEARING_INERT = {"n", "n_link", "tag", "color", "scale_factor", "frequency", "seal_leakage", "kwargs"}
EXTRAPOLATIONS = ("continue", "refuse", "hold", "linear")
INTERPOLATIONS = ("smoothing-spline", "spline", "linear", "pchip")
#: ROSS's own convention for its speed tables (UnivariateSpline, extrapolated)
ROSS_TABLES = ("smoothing-spline", "continue")


def _bad(where: str, key: str, value, allowed: str):
    raise ModelError(where, key, value, allowed)


def read_ross(path) -> dict:
    """The tables of a ROSS rotor TOML file (a clear error for a file that is not one)."""
    p = Path(path)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        _bad(str(p), "file", str(p), "an existing ROSS rotor file (Rotor.save, .toml)")
    except (IsADirectoryError, PermissionError, UnicodeDecodeError) as exc:
        _bad(str(p), "file", str(p), f"a readable UTF-8 TOML file ({type(exc).__name__})")
    except tomllib.TOMLDecodeError as exc:
        _bad(str(p), "TOML", str(exc), "a valid TOML file saved by ROSS's Rotor.save")
    if not any(isinstance(v, dict) and k.startswith("ShaftElement") for k, v in data.items()):
        _bad(str(p), "ShaftElement", None, "a ROSS rotor file with ShaftElement_<tag> tables (Rotor.save)")
    return data


def _number(where, key, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        _bad(where, key, value, "a finite number")
    return float(value)


def _int(where, key, value) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        _bad(where, key, value, "a node number (an integer >= 0)")
    return value


def _unknown(where: str, table: dict, known: set) -> None:
    extra = sorted(set(table) - known)
    if extra:
        _bad(where, extra[0], table[extra[0]], "a key drivefem's import knows: " + ", ".join(sorted(known))
             + " (not supported: the element would not be converted faithfully)")


def _material(where: str, m) -> dict:
    if not isinstance(m, dict):
        _bad(where, "material", m, "a material table {rho, E, G_s} (ROSS >= 1.0 saves it with the element)")
    for k in ("rho", "E", "G_s"):
        if k not in m:
            _bad(where + ".material", k, None, "rho, E and G_s of the material")
    return {"E": _number(where, "E", m["E"]), "G": _number(where, "G_s", m["G_s"]), "rho": _number(where, "rho", m["rho"])}


def _hutchinson(where: str, el: dict, mat: dict) -> float:
    """ROSS's Hutchinson (2001) shear coefficient for the element's mean diameter ratio."""
    r = ((el["idl"] + el["idr"]) / 2) / ((el["odl"] + el["odr"]) / 2)
    r2 = r * r
    r12 = (1 + r2) ** 2
    nu = mat["E"] / (2 * mat["G"]) - 1
    return 6 * r12 * (1 + nu) / (r12 * (7 + 12 * nu + 4 * nu ** 2) + 4 * r2 * (5 + 6 * nu + 2 * nu ** 2))


def _shaft_element(name: str, t: dict) -> dict:
    where = f"[{name!r}]"
    _unknown(where, t, SHAFT_KEYS)
    el = {"n": _int(where, "n", t.get("n")), "L": _number(where, "L", t.get("L")), "tag": str(t.get("tag", name))}
    for k in ("idl", "odl"):
        el[k] = _number(where, k, t.get(k))
    el["idr"] = _number(where, "idr", t.get("idr", el["idl"]))
    el["odr"] = _number(where, "odr", t.get("odr", el["odl"]))
    for k in ("shear_effects", "rotary_inertia", "gyroscopic"):
        if t.get(k, True) is not True:
            _bad(where, k, t.get(k), "true (drivefem's element always has shear, rotary inertia and gyroscopic "
                 "terms; not supported: switching them off)")
    for k in ("axial_force", "torque", "alpha", "beta"):
        if _number(where, k, t.get(k, 0)) != 0:
            _bad(where, k, t[k], "0 (not supported: axial-force or torque preload, Rayleigh damping of the shaft)")
    method = t.get("shear_method_calc", "cowper")
    if method not in ("cowper", "hutchinson"):
        _bad(where, "shear_method_calc", method, "'cowper' or 'hutchinson'")
    el["material"] = _material(where, t.get("material"))
    el["kappa"] = None if method == "cowper" else _hutchinson(where, el, el["material"])
    return el


def _section(el: dict, mat_default: dict | None) -> dict:
    """A drivefem section table (segment's own or a layer) of one ROSS element."""
    out = {"d": el["odl"]}
    if el["odr"] != el["odl"]:
        out["d_end"] = el["odr"]
    out["di"] = el["idl"]
    if el["idr"] != el["idl"]:
        out["di_end"] = el["idr"]
    if el["material"] != mat_default:
        out["material"] = dict(el["material"])
    if el["kappa"] is not None:
        out["shear_coefficient"] = el["kappa"]
    return out


def _coefficients(where: str, t: dict) -> tuple[list | None, dict]:
    """(speeds or None, {ROSS key: value or list}) of a linear bearing table."""
    freq = t.get("frequency")
    if freq is not None and not (isinstance(freq, list) and all(isinstance(v, (int, float)) for v in freq)):
        _bad(where, "frequency", freq, "a list of speeds, rad/s")
    n = len(freq) if freq is not None else 1
    vals = {}
    for key in list(LATERAL_MAP) + ["kzz", "czz"] + list(MASS_KEYS):
        v = t.get(key, 0.0)
        v = v if isinstance(v, list) else [v]
        v = [_number(where, key, x) for x in v]
        if len(v) == 1 and n > 1:
            v = v * n
        if len(v) != n:
            _bad(where, key, v, f"one value per speed of `frequency` ({n} values)")
        vals[key] = v
    for key in MASS_KEYS:
        if any(vals[key]):
            _bad(where, key, vals[key][0], "0 (not supported: bearing mass coefficients)")
    speeds = [float(f) for f in freq] if freq is not None and n > 1 else None
    return speeds, vals


def convert_ross(data: dict, *, source: str = "ROSS file", extrapolate: str | None = None,
                 interpolation: str = "smoothing-spline", title: str | None = None) -> tuple[dict, list[str]]:
    """A drivefem rotor document (dict, ready for TOML) from a ROSS file's tables, and notes on
    what was mapped or left out (ROSS's plotting attributes, speed ranges of its parameters) and on
    the bearing tables' interpolation.  ``extrapolate`` None: "continue" for "smoothing-spline"
    (ROSS's extrapolation), else "refuse"."""
    if extrapolate is None:
        extrapolate = "continue" if interpolation == "smoothing-spline" else "refuse"
    if extrapolate not in EXTRAPOLATIONS:
        _bad("convert", "--extrapolate", extrapolate, " | ".join(EXTRAPOLATIONS))
    if interpolation not in INTERPOLATIONS:
        _bad("convert", "--interpolation", interpolation, " | ".join(INTERPOLATIONS))
    notes = []
    shafts, disks, bearings, masses = [], [], [], []
    for name, t in data.items():
        if name in ("ross_version", "_note"):
            continue
        if name == "parameters":
            if isinstance(t, dict) and any(v is not None for v in t.values()):
                notes.append("ROSS parameters not converted (operating speeds): "
                             + ", ".join(f"{k} = {v}" for k, v in t.items() if v is not None))
            continue
        if not isinstance(t, dict):
            _bad(source, name, t, "a table <Class>_<tag> of a ROSS element")
        cls = name.split("_", 1)[0]
        if cls == "ShaftElement":
            shafts.append(_shaft_element(name, t))
        elif cls == "DiskElement":
            _unknown(f"[{name!r}]", t, DISK_KEYS)
            disks.append((name, t))
        elif cls == "PointMass":
            _unknown(f"[{name!r}]", t, POINT_MASS_KEYS)
            masses.append((name, t))
        elif "kxx" in t and "cxx" in t and cls != "MagneticBearingElement":
            extra = sorted(k for k in t if k not in BEARING_INERT and k not in LATERAL_MAP and k not in
                           ("kzz", "czz") + MASS_KEYS)
            if extra and cls in ("BearingElement", "SealElement"):
                _bad(f"[{name!r}]", extra[0], t[extra[0]], "a key of a linear bearing table (not supported)")
            if cls not in ("BearingElement", "SealElement"):
                notes.append(f"{name}: a ROSS {cls}, imported by its saved linear coefficients")
            bearings.append((name, cls, t))
        else:
            _bad(source, name, cls, "a ShaftElement, DiskElement, BearingElement, SealElement (or another linear "
                 "bearing saved with its coefficients) or PointMass (not supported: " + cls + ")")
    if not shafts:
        _bad(source, "ShaftElement", None, "at least one shaft element")

    # ------------------------------------------------------------ stations (layers share n)
    stations = defaultdict(list)
    for el in shafts:
        stations[el["n"]].append(el)
    ns = sorted(stations)
    if ns != list(range(len(ns))):
        _bad(source, "n", ns, "shaft element numbers 0, 1, 2, ... without gaps")
    mat_default = Counter(tuple(sorted(el["material"].items())) for el in shafts).most_common(1)[0][0]
    mat_default = dict(mat_default)
    segs = []
    for n in ns:
        els = sorted(stations[n], key=lambda e: (e["idl"], e["odl"]))
        L = els[0]["L"]
        for e in els[1:]:
            if abs(e["L"] - L) > 1e-12 * L:
                _bad(f"[ShaftElement {e['tag']!r}]", "L", e["L"], f"the length of the other layers at n = {n} ({L})")
        seg = {"length": L, "elements": 1, **_section(els[0], mat_default)}
        if len(els) > 1:
            seg["layer"] = [_section(e, mat_default) for e in els[1:]]
        if segs and _same_station(segs[-1], seg):
            segs[-1]["elements"] += 1
            segs[-1]["length"] = segs[-1]["_L"] * segs[-1]["elements"]
        else:
            seg["_L"] = L
            segs.append(seg)
    node_x, x0 = [0.0], 0.0                   # as fem.rotor.Rotor.node_positions computes them
    for s in segs:
        node_x += [x0 + s["length"] * k / s["elements"] for k in range(1, s["elements"] + 1)]
        x0 += s["length"]
    for s in segs:
        s.pop("_L")
    n_nodes = len(node_x)

    rotor = {"dofs": "full", "material": mat_default, "segment": segs}
    # ------------------------------------------------------------ discs and point masses
    discs = []
    for name, t in disks:
        where = f"[{name!r}]"
        n = _int(where, "n", t.get("n"))
        if n >= n_nodes:
            _bad(where, "n", n, f"a shaft node (0 ... {n_nodes - 1})")
        discs.append({"x": node_x[n], "mass": _number(where, "m", t.get("m", 0.0)),
                      "Id": _number(where, "Id", t.get("Id", 0.0)), "Ip": _number(where, "Ip", t.get("Ip", 0.0)),
                      "name": str(t.get("tag", name))})
    point = {}
    for name, t in masses:
        where = f"[{name!r}]"
        n = _int(where, "n", t.get("n"))
        m = _number(where, "m", t.get("m", t.get("mx", 0.0))) if "mx" not in t else _number(where, "mx", t["mx"])
        my = _number(where, "my", t.get("my", m))
        if my != m:
            _bad(where, "my", my, f"mx = my (= {m}: drivefem's pedestals and discs have one lateral mass; not "
                 "supported: anisotropic point masses)")
        if n < n_nodes:
            if _number(where, "mz", t.get("mz", m)) != m:
                _bad(where, "mz", t.get("mz"), f"mz = mx (= {m}) for a point mass on the shaft")
            discs.append({"x": node_x[n], "mass": m, "Id": 0.0, "Ip": 0.0, "name": str(t.get("tag", name))})
        else:
            point[n] = (name, m)
    # ------------------------------------------------------------ bearings, seals, pedestals
    grounded_at = defaultdict(list)
    for name, cls, t in bearings:
        n = _int(f"[{name!r}]", "n", t.get("n"))
        if n >= n_nodes and t.get("n_link") is None:
            grounded_at[n].append((name, t))
    pedestals, out_bearings = {}, []
    for name, cls, t in bearings:
        where = f"[{name!r}]"
        n = _int(where, "n", t.get("n"))
        if n >= n_nodes:
            if t.get("n_link") is not None:
                _bad(where, "n_link", t["n_link"], "a link from a shaft node only (not supported: chains of supports)")
            if n not in point:
                _bad(where, "n", n, f"a shaft node (0 ... {n_nodes - 1}) or the node of a PointMass")
            continue
        speeds, vals = _coefficients(where, t)
        b = {"x": node_x[n], "name": str(t.get("tag", name))}
        for rk, dk in LATERAL_MAP.items():
            v = vals[rk]
            b[dk] = v if speeds is not None and any(x != v[0] for x in v) else v[0]
        for rk, dk in (("kzz", "k_axial"), ("czz", "c_axial")):
            v = vals[rk]
            if any(x != v[0] for x in v):
                _bad(where, rk, v, "a constant (not supported: speed-dependent axial coefficients)")
            if v[0]:
                b[dk] = v[0]
        if speeds is not None and any(isinstance(b[k], list) for k in LATERAL_MAP.values()):
            b["speeds"] = speeds
            b["interpolation"] = interpolation
            b["extrapolate"] = extrapolate
        link = t.get("n_link")
        if link is not None:
            b["pedestal"] = _pedestal(where, _int(where, "n_link", link), point, grounded_at, pedestals)
        out_bearings.append(b)
    for n, (name, _) in point.items():
        if f"support {n}" not in pedestals:
            _bad(f"[{name!r}]", "n", n, "a point mass on a shaft node, or one that some bearing links to (n_link)")
    if not out_bearings:
        notes.append("no bearings: a free-free rotor")
    tabled = [b for b in out_bearings if "speeds" in b]
    if tabled:
        notes += _table_notes(tabled, interpolation, extrapolate)
    rotor["disc"] = discs
    rotor["bearing"] = out_bearings
    if pedestals:
        rotor["pedestal"] = list(pedestals.values())
    doc = {"title": title or f"{Path(source).stem} (imported from ROSS {data.get('ross_version', '?')})",
           "rotor": rotor}
    if not discs:
        del rotor["disc"]
    return doc, notes


def _table_notes(tabled: list, interpolation: str, extrapolate: str) -> list[str]:
    """What the written file says about its bearing tables: the interpolation and extrapolation and
    how far ROSS's smoothing spline lies from the table points (largest over the tables' rows,
    relative to the row's largest value)."""
    import numpy as np

    from ..rotor.tables import SmoothingSplines

    miss, where = 0.0, ""
    for b in tabled:
        grid = np.asarray(b["speeds"], dtype=float)
        rows = np.array([np.broadcast_to(np.asarray(b.get(k, 0.0), dtype=float), grid.shape)
                         for k in LATERAL_MAP.values()])
        fit = SmoothingSplines(grid, rows)(grid)
        scale = np.maximum(np.abs(rows).max(axis=1, keepdims=True), 1e-300)
        err = np.abs(fit - rows) / scale
        if err.max() > miss:
            r = int(np.unravel_index(np.argmax(err), err.shape)[0])
            miss, where = float(err.max()), f"{b['name']!r} {list(LATERAL_MAP.values())[r]}"
    ross = (f"ROSS's smoothing spline misses the table points by up to {miss:.1e} of a row's largest value "
            f"({where})")
    if (interpolation, extrapolate) == ROSS_TABLES:
        return [f"Bearing tables: interpolation = 'smoothing-spline', extrapolate = 'continue': ROSS's convention "
                "(scipy's UnivariateSpline, a cubic smoothing spline with s = number of points, extrapolated along "
                f"its end cubics), the coefficients ROSS computes with at every speed. It is not an interpolant: {ross}. "
                "drivefem convert --interpolation spline|linear|pchip and --extrapolate refuse|hold|linear choose "
                "otherwise."]
    return [f"Bearing tables: interpolation = {interpolation!r}, extrapolate = {extrapolate!r} (chosen); ROSS "
            f"computes with its smoothing spline, extrapolated (drivefem convert's default, 'smoothing-spline' with "
            f"'continue'): {ross}."]


def _same_station(prev: dict, seg: dict) -> bool:
    keys = set(prev) | set(seg)
    return all(prev.get(k) == seg.get(k) for k in keys - {"length", "elements", "_L"}) and \
        prev["_L"] == seg["length"]


def _pedestal(where: str, node: int, point: dict, grounded_at: dict, pedestals: dict) -> str:
    """The [[rotor.pedestal]] name of ROSS's support node ``node`` (point mass + grounded bearing)."""
    name = f"support {node}"
    if name in pedestals:
        return name
    if node not in point:
        _bad(where, "n_link", node, "the node of a PointMass (the pedestal's mass)")
    ground = grounded_at.get(node, [])
    if len(ground) != 1:
        _bad(where, "n_link", node, "a support node held by exactly one grounded bearing (found "
             f"{len(ground)}; not supported otherwise)")
    gname, t = ground[0]
    gw = f"[{gname!r}]"
    speeds, vals = _coefficients(gw, t)
    for key in LATERAL_MAP:
        if any(x != vals[key][0] for x in vals[key]):
            _bad(gw, key, vals[key], "a constant (not supported: speed-dependent pedestal supports)")
    for key in ("kxy", "kyx", "cxy", "cyx"):
        if vals[key][0]:
            _bad(gw, key, vals[key][0], "0 (not supported: cross-coupled pedestal supports)")
    for key in ("kzz", "czz"):
        if vals[key][0]:
            _bad(gw, key, vals[key][0], "0 (drivefem's pedestals move laterally only)")
    pedestals[name] = {"name": name, "mass": point[node][1], "kyy": vals["kxx"][0], "kzz": vals["kyy"][0],
                       "cyy": vals["cxx"][0], "czz": vals["cyy"][0]}
    return name


def rotor_file_text(doc: dict, header: list[str]) -> str:
    """The model file: the schema line (editors), ``header`` as comments, the document."""
    import tomli_w

    import textwrap

    lines = ["#:schema ../fem/modelfile/drivefem.schema.json"] + [
        f"# {line}".rstrip() for h in header for line in (textwrap.wrap(h, 110, subsequent_indent="  ") or [""])]
    return "\n".join(lines) + "\n\n" + tomli_w.dumps(doc)
