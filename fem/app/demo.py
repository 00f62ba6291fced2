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


def _python_examples(out: Path):
    """Run every examples/*.py through its ``main(out)`` (a directory for ``out_dir``, else a file
    named after the example, with the suffix of the default output): (name, exit code, seconds)."""
    import importlib.util
    import inspect
    import sys
    import traceback

    out.mkdir(parents=True, exist_ok=True)
    for path in sorted(EXAMPLES.glob("*.py")):
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


def run_demo(out: Path, run_command) -> int:
    """Every example through ``run_command(argv) -> exit code`` (the command line's ``main``, passed in
    by the demo command so that this module does not import the command line back)."""
    out.mkdir(parents=True, exist_ok=True)
    summary, failures = [], 0
    examples = sorted(EXAMPLES.glob("*.toml"))
    print(f"drivefem demo: {len(examples)} example models from {EXAMPLES} -> {out.resolve()}\n")
    for path in examples:
        kind, doc = _command(path)
        stem = out / path.stem
        if kind == "sweep":  # minutes of work: shown, not run (see docs/steady.md)
            print(f"(skipped: drivefem sweep {path} --json {stem}.json  -- a {path.name} parameter map takes minutes)\n")
            continue
        t0 = time.perf_counter()
        argv = [kind, str(path), "--json", f"{stem}.json"]
        if kind == "modal" and hasattr(doc, "rotor"):
            argv += ["--plot", f"{stem}_orbits.png"]
        elif kind == "modal":
            argv += ["--plot", f"{stem}_modes.png", "--vtu", f"{stem}_modes.vtu"] if hasattr(doc, "segment") \
                and not hasattr(doc, "reduction") else []
        elif kind == "forced":
            argv += ["--csv", f"{stem}.csv", "--plot", f"{stem}_frf.png"]
        elif kind in ("parametric", "campbell"):
            argv += ["--csv", f"{stem}.csv", "--png", f"{stem}_{kind}.png"]
        else:
            argv += ["--csv", f"{stem}.csv", "--png", str(out / f"{path.stem}_plots")]
        print(f"$ drivefem {' '.join(argv)}")
        rc = run_command(argv)
        dt = time.perf_counter() - t0
        failures += rc != 0
        summary.append((path.name, kind, rc, dt))
        print()
    for name, extra in (("cantilever.toml", ["--gif"]), ("torsion_shaft_disc.toml", []),
                        ("stepped_rotor_timoshenko.toml", [])):
        argv = ["render", str(EXAMPLES / name), "--modes", "4", "--out", str(out / "render" / Path(name).stem)] + extra
        print(f"$ drivefem {' '.join(argv)}")
        rc = run_command(argv)
        failures += rc != 0
        summary.append((name, "render", rc, 0.0))
        print()
    rotor_runs = (["render", str(EXAMPLES / "rotor_overhung_fan.toml"), "--mode", "1", "--mode", "2", "--gif", "--quiet",
                   "--out", str(out / "render" / "rotor_overhung_fan")],
                  ["static", str(EXAMPLES / "rotor_overhung_fan.toml"), "--plot", str(out / "rotor_overhung_fan_static.png")],
                  ["critical-map", str(EXAMPLES / "rotor_compressor.toml"),
                   "--plot", str(out / "rotor_compressor_critical_map.png")],
                  ["stability", str(EXAMPLES / "rotor_jeffcott_seal.toml"), "--quiet",
                   "--plot", str(out / "rotor_jeffcott_seal_stability.png")],
                  ["forced", str(EXAMPLES / "rotor_overhung_fan.toml"), "--plot", str(out / "rotor_overhung_fan_plots")])
    for argv in rotor_runs:                 # the rotor analyses and figures beyond each file's default command
        print(f"$ drivefem {' '.join(argv)}")
        rc = run_command(argv)
        failures += rc != 0
        summary.append((Path(argv[1]).name, argv[0], rc, 0.0))
        print()
    for name, rc, dt in _python_examples(out / "python"):
        failures += rc != 0
        summary.append((name, "python", rc, dt))
    print("$ drivefem validate --fast --report", out / "validation")
    rc = run_command(["validate", "--fast", "--quiet", "--report", str(out / "validation"),
                   "--json", str(out / "validation" / "validation.json")])
    failures += rc != 0
    summary.append(("validation catalogue (fast tier)", "validate", rc, 0.0))
    print("\nsummary")
    for name, kind, rc, dt in summary:
        print(f"  {'ok  ' if rc == 0 else 'FAIL'} {kind:9s} {name}" + (f"  ({dt:.2f} s)" if dt else ""))
    (out / "summary.json").write_text(json.dumps([{"example": n, "command": k, "exit_code": r} for n, k, r, _ in summary],
                                                 indent=2))
    print(f"\noutputs in {out.resolve()}")
    return 0 if failures == 0 else 1
