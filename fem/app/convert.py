"""``drivefem convert ROSS_FILE [--out F] [--interpolation smoothing-spline|spline|linear|pchip] [--extrapolate continue|refuse|hold|linear]``:
a rotor saved by ROSS (``Rotor.save``, TOML) as a drivefem ``[rotor]`` model file (:mod:`fem.modelfile.ross`).
The written file is loaded back and checked (the rotor is built) before the command succeeds.
Exit codes as for every command (0 done, 2 bad or unsupported input: one line naming the element
and key)."""
from __future__ import annotations

import sys

from ..output import check_output_path


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("convert", help="import a rotor saved by ROSS (Rotor.save TOML) as a drivefem rotor file")
    p.add_argument("source", help="the ROSS rotor file (.toml)")
    p.add_argument("--out", help="the drivefem model file to write (default: print it)")
    p.add_argument("--interpolation", default="smoothing-spline", choices=["smoothing-spline", "spline", "linear", "pchip"],
                   help="bearing tables between their speeds (default: smoothing-spline, ROSS's convention: its "
                        "UnivariateSpline with s = number of points, which misses the table points; spline: the "
                        "cubic spline through them)")
    p.add_argument("--extrapolate", default=None, choices=["continue", "refuse", "hold", "linear"],
                   help="bearing tables outside their speeds (default: continue -- the smoothing spline's end "
                        "cubics, ROSS's extrapolation -- with smoothing-spline, else refuse; linear: the tangent "
                        "line at the table's end)")
    p.add_argument("--title", help="title of the model (default: from the file name)")
    p.set_defaults(func=convert)


def convert(args) -> int:
    from pathlib import Path

    from discrete.errors import ModelError

    from ..modelfile.ross import convert_ross, read_ross, rotor_file_text

    if args.out:
        check_output_path(args.out, "--out", kind="toml")
    data = read_ross(args.source)
    extrapolate = args.extrapolate or ("continue" if args.interpolation == "smoothing-spline" else "refuse")
    doc, notes = convert_ross(data, source=args.source, extrapolate=extrapolate,
                              interpolation=args.interpolation, title=args.title)
    header = [f"Imported from the ROSS rotor file {Path(args.source).name} (saved by ROSS "
              f"{data.get('ross_version', '?')}) by drivefem convert --interpolation {args.interpolation} "
              f"--extrapolate {extrapolate}.",
              "Axes: ROSS x, y, z (axial) -> drivefem y, z, x; kxx -> kyy, kyy -> kzz, kxy -> kyz, kyx -> kzy (c alike);",
              "SI units on both sides; ROSS's frequency (rad/s) -> speeds; shaft elements sharing a node -> layers."]
    header += notes
    text = rotor_file_text(doc, header)
    r = doc["rotor"]
    if args.out:
        out = Path(args.out)
        out.write_text(text, encoding="utf-8")
        try:
            _check(out)
        except ModelError:
            out.unlink()
            raise
        print(f"wrote {out}: {sum(s['elements'] for s in r['segment'])} elements in {len(r['segment'])} segments "
              f"({sum(len(s.get('layer', [])) for s in r['segment'])} with layers), {len(r.get('disc', []))} discs, "
              f"{len(r['bearing'])} bearings and seals, {len(r.get('pedestal', []))} pedestals")
    else:
        sys.stdout.write(text)
    for n in notes:
        print(f"drivefem: note: {n}", file=sys.stderr)
    return 0


def _check(path) -> None:
    """Load the written file as drivefem would and build the rotor (positions, signs, layers)."""
    from ..modelfile.build.rotor import rotor_model
    from ..study import Study

    rotor_model(Study.load(path).doc)
