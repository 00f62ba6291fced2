"""``drivefem demo``: representative examples end to end into one output directory."""
from __future__ import annotations

import json
import time
from pathlib import Path

from ..modelfile import load

EXAMPLES = Path(__file__).resolve().parent.parent.parent / "examples"


def _command(path: Path) -> tuple[str, object]:
    """The command that shows an example model (and its typed document)."""
    doc = load(path)
    if getattr(doc, "sweep", None) is not None:
        return "sweep", doc
    if getattr(doc, "simulation", None) is not None:
        return "simulate", doc
    an = doc.analysis
    return (an.type if an is not None else "modal"), doc


def _python_examples(out: Path, paths=None):
    """Run every examples/*.py (or the given ``paths``) through its ``main(out)`` (a directory for
    ``out_dir``, else a file named after the example, with the suffix of the default output):
    (name, exit code, seconds)."""
    import importlib.util
    import inspect
    import sys
    import traceback

    out.mkdir(parents=True, exist_ok=True)
    for path in (sorted(EXAMPLES.glob("*.py")) if paths is None else paths):
        spec = importlib.util.spec_from_file_location(f"drivefem_example_{path.stem}", path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module          # dataclasses look their module up while it loads
        t0 = time.perf_counter()
        try:
            spec.loader.exec_module(module)
            first = next(iter(inspect.signature(module.main).parameters.values()))
            if first.name == "out_dir":
                target = out / path.stem
            else:
                default = first.default if isinstance(first.default, (str, Path)) else ""
                target = out / (path.stem + (Path(str(default)).suffix or ".json"))
            print(f"$ python {path.relative_to(EXAMPLES.parent)}  (main({target}))")
            module.main(target)
            rc = 0
        except Exception:            # an example that fails is reported, the demo goes on
            traceback.print_exc()
            rc = 1
        finally:
            sys.modules.pop(spec.name, None)
        yield path.name, rc, time.perf_counter() - t0
        print()


def _run_list(out: Path) -> list[tuple[list[str], str]]:
    """Every command of the demo: (argv, kind of model file), each example through the command that
    shows it, then the pictures and rotor analyses beyond each file's default command."""
    from ..modelfile.load import kind_of

    runs = []
    for path in sorted(EXAMPLES.glob("*.toml")):
        command, doc = _command(path)
        kind = kind_of(doc)
        stem = out / path.stem
        if command == "sweep":
            runs.append((["sweep", str(path), "--json", f"{stem}.json"], kind))
            continue
        argv = [command, str(path), "--json", f"{stem}.json"]
        if command == "modal" and kind == "rotor":
            argv += ["--plot", f"{stem}_orbits.png"]
        elif command == "modal":
            argv += ["--plot", f"{stem}_modes.png", "--vtu", f"{stem}_modes.vtu"] if kind == "fe" \
                and not hasattr(doc, "reduction") else []
        elif command == "forced":
            argv += ["--csv", f"{stem}.csv", "--plot", f"{stem}_forced"]
        elif command in ("parametric", "campbell"):
            argv += ["--csv", f"{stem}.csv", "--plot", f"{stem}_{command}.png"]
        else:
            argv += ["--csv", f"{stem}.csv", "--plot", f"{stem}_plots"]
        runs.append((argv, kind))
    for name, extra in (("cantilever.toml", ["--gif"]), ("torsion_shaft_disc.toml", []),
                        ("stepped_rotor_timoshenko.toml", [])):
        runs.append((["render", str(EXAMPLES / name), "--modes", "4", "--render",
                      str(out / "render" / Path(name).stem)] + extra, "fe"))
    fan, compressor, seal = (str(EXAMPLES / f"rotor_{n}.toml") for n in ("overhung_fan", "compressor", "jeffcott_seal"))
    runs += [(["render", fan, "--mode", "1", "--mode", "2", "--gif", "--render", str(out / "render" / "rotor_overhung_fan")],
              "rotor"),
             (["campbell", fan, "--plot", str(out / "rotor_overhung_fan_campbell.png")], "rotor"),
             (["static", fan, "--plot", str(out / "rotor_overhung_fan_static.png")], "rotor"),
             (["critical-map", compressor, "--plot", str(out / "rotor_compressor_critical_map.png")], "rotor"),
             (["stability", seal, "--plot", str(out / "rotor_jeffcott_seal_stability.png")], "rotor")]
    return runs


def _images(root: Path) -> dict:
    return {p: p.stat().st_mtime_ns for p in root.rglob("*") if p.suffix in (".png", ".gif")}


def _shown(argv: list[str], out: Path) -> str:
    """The command line as the gallery shows it: example and output paths relative."""
    words = []
    for a in argv:
        p = Path(a)
        if p.is_absolute() and EXAMPLES in p.parents:
            a = str(p.relative_to(EXAMPLES.parent))
        elif p.is_absolute() and (p == out or out in p.parents):
            a = str(p.relative_to(out)) or "."
        words.append(a)
    return "drivefem " + " ".join(words)


def run_demo(out: Path, run_command, gallery: Path | None = None, quiet: bool = False) -> int:
    """Every example through ``run_command(argv) -> exit code`` (the command line's ``main``, passed in
    by the demo command so that this module does not import the command line back), then the gallery
    of the figures drawn (``out/gallery.md``; with ``gallery``, also ``gallery/gallery.md`` and
    ``gallery/img/gallery/``: :mod:`fem.app.gallery`)."""
    from .gallery import Drawn, figure_type, write_gallery

    out.mkdir(parents=True, exist_ok=True)
    summary, failures, drawn = [], 0, []
    runs = _run_list(out)
    print(f"drivefem demo: {len(list(EXAMPLES.glob('*.toml')))} example models from {EXAMPLES} -> {out.resolve()}\n")

    def record(before, command, kind, shown):
        for p, stamp in sorted(_images(out).items()):
            if before.get(p) != stamp and "gallery" not in p.relative_to(out).parts:
                drawn.append(Drawn(p, shown, figure_type(p, out, command, kind)))

    for argv, kind in runs:
        if argv[0] == "sweep":  # minutes of work: shown, not run (see docs/steady.md)
            print(f"(skipped: drivefem {' '.join(argv)}  -- a {Path(argv[1]).name} parameter map takes minutes)\n")
            continue
        argv = argv + (["--quiet"] if quiet else [])
        print(f"$ drivefem {' '.join(argv)}")
        before = _images(out)
        t0 = time.perf_counter()
        rc = run_command(argv)
        dt = time.perf_counter() - t0
        record(before, argv[0], kind, _shown(argv, out))
        failures += rc != 0
        summary.append((Path(argv[1]).name, argv[0], rc, dt))
        print()
    before = _images(out)
    for name, rc, dt in _python_examples(out / "python"):
        failures += rc != 0
        summary.append((name, "python", rc, dt))
    record(before, "python", "", "python examples/<name>.py")
    for d in drawn:
        if d.command == "python examples/<name>.py":
            rel = d.path.relative_to(out / "python")
            d.command = f"python examples/{rel.parts[0].split('.')[0]}.py"
    write_gallery(drawn, out, gallery)          # again after the validation report (its plots)
    print("$ drivefem validate --fast --report", out / "validation")
    before = _images(out)
    rc = run_command(["validate", "--fast", "--quiet", "--report", str(out / "validation"),
                      "--json", str(out / "validation" / "validation.json")])
    record(before, "validate", "", "drivefem validate --fast --report validation")
    failures += rc != 0
    summary.append(("validation catalogue (fast tier)", "validate", rc, 0.0))
    page = write_gallery(drawn, out, gallery)
    print(f"\nwrote {out / 'gallery.md'}" + (f" and {page}" if gallery is not None else ""))
    print("\nsummary")
    for name, kind, rc, dt in summary:
        print(f"  {'ok  ' if rc == 0 else 'FAIL'} {kind:9s} {name}" + (f"  ({dt:.2f} s)" if dt else ""))
    (out / "summary.json").write_text(json.dumps([{"example": n, "command": k, "exit_code": r} for n, k, r, _ in summary],
                                                 indent=2))
    print(f"\noutputs in {out.resolve()}")
    return 0 if failures == 0 else 1
