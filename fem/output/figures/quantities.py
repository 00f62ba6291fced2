"""Quantity names and units of the values a figure draws (axis labels ``quantity [unit]``): the FE
fields, the outputs of a harmonic response (``theta@x=1.2``, a lumped body's name), a drive's
stations and mechanism outputs, and the response measure of a nonlinear amplitude-frequency curve."""
from __future__ import annotations

import re

#: FE fields (fem.model.FIELDS): (quantity, unit)
FIELD = {"w": ("deflection w", "m"), "u": ("axial displacement u", "m"), "theta": ("twist angle theta", "rad"),
         "w_x": ("slope w'", "rad"), "phi": ("section rotation phi", "rad")}
#: a lumped coordinate is a displacement or an angle: the file does not say which
LUMPED = ("displacement or angle", "m | rad")
_AT = re.compile(r"^(?P<field>[A-Za-z_]+)@x=(?P<x>[-+0-9.eE]+)$")
_DRIVE = re.compile(r"^(?P<kind>theta|y)(?P<j>\d+)$")


def output_quantity(name: str, kind: str | None = None) -> tuple[str, str, str]:
    """(legend name, quantity, unit) of one output of a harmonic response: an FE DOF ``field@x=..``,
    a drive's ``theta<j>`` (shaft station) or ``y<j>`` (mechanism output), else a lumped body."""
    m = _AT.match(name)
    if m and m["field"] in FIELD:
        q, u = FIELD[m["field"]]
        return f"{q.split()[-1]} at x = {float(m['x']):g} m", q, u
    m = _DRIVE.match(name)
    if kind == "drive" and m:
        if m["kind"] == "theta":
            return f"shaft station {m['j']}", "station angle theta", "rad"
        return f"mechanism output {m['j']}", "output displacement y", "m"
    return name, *LUMPED


def common_label(quantities: list[tuple[str, str]], prefix: str = "") -> str:
    """'quantity [unit]' of the curves on one axis: their quantity if they share it, else their units."""
    qs = sorted({q for q, _ in quantities})
    us = sorted({u for _, u in quantities})
    q = qs[0] if len(qs) == 1 else "response"
    return f"{prefix}{q} [{', '.join(us)}]"


def measure_label(label: str) -> tuple[str, str]:
    """(quantity, unit) of a nonlinear curve's response measure (``discrete.steady`` labels such as
    'h1 mass', 'amplitude |F| spring', 'max rotor (x 0.001)')."""
    words = label.split()
    measure = words[0] if words else "response"
    nice = {"h1": "first-harmonic amplitude", "amplitude": "amplitude (half peak-to-peak)", "max": "maximum",
            "min": "minimum", "peak": "peak |value|"}.get(measure, measure)
    rest = " ".join(words[1:])
    scale = ""
    m = re.search(r"\s/\s*(\S+)$", rest)
    if m:                       # divided by a scale of the measure's own unit: dimensionless
        scale, rest = m.group(1), rest[:m.start()].strip()
    if rest.startswith("|F|"):
        q, u = f"{nice} of the force in {rest[3:].strip()}", "N | N m"
    else:
        q, u = f"{nice} of {rest}", LUMPED[1]
    return (f"{q} / scale {scale}" if scale else q), ("-" if scale else u)


def method_text(method: str) -> str:
    """A continuation method in words: 'hb (H = 15, N = 256, AFT)' -> 'harmonic balance, 15 harmonics'."""
    m = re.match(r"^hb \(H = (\d+)", method or "")
    if m:
        return f"harmonic balance, {m.group(1)} harmonic{'s' if m.group(1) != '1' else ''}"
    m = re.match(r"^EPMC by HB \(H = (\d+)", method or "")
    if m:
        return f"nonlinear mode (extended periodic motion concept), {m.group(1)} harmonics"
    if (method or "").startswith("shooting"):
        return "shooting on the event-driven time integration"
    return method or ""
