"""Off-screen rendering speed: 6 mode-shape PNGs of a 200-element shaft (issue 6 target:
under 1 s per image on 2 cores after start-up).

Start-up (importing pyvista/VTK and the first OpenGL context) is timed separately; then the
6 PNGs (``fem.render.render_modes``) and, interleaved with them round by round, the baseline:
a matplotlib line plot of the same 6 modes (``fem.output.figures.plot_mode_shapes``, one PNG
each), so the printed ratio render/plot is stable across machines.  Median and spread of
``--runs`` runs, seconds per image, wall and process-CPU time (VTK's software rasteriser runs in
this process, so its CPU time is counted).  Both sides' PNG sizes are printed as the check that
real images were written.

    python benchmarks/render.py [--runs 5] [--physics bending|torsion|axial]
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import common

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from fem import assemble, modal_analysis  # noqa: E402
from validation.builders import uniform  # noqa: E402

TARGET = 1.0
IMAGES = 6


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--physics", default="bending", choices=("bending", "torsion", "axial"))
    args = ap.parse_args(argv)
    common.header(__file__, f"off-screen PNGs of {IMAGES} modes of a 200-element shaft vs matplotlib line plots")
    t0 = time.perf_counter()
    from fem.render import available, render_image, render_modes

    ok, msg = available()
    t_probe = time.perf_counter() - t0
    if not ok:
        print(f"rendering unavailable: {msg}")
        common.emit(common.record(__file__, f"seconds per PNG, {IMAGES} modes of a 200-element shaft",
                                  "pyvista off-screen", "matplotlib line plot", None, ("<", TARGET), metric="s per image",
                                  unit="s"))
        return 1
    from fem.output.figures import plot_mode_shapes

    fe = assemble(uniform(args.physics, 2.0, 200, d=0.05, supports=[(0.0, "clamped")]))
    res = modal_analysis(fe.system, IMAGES)
    t0 = time.perf_counter()
    render_image(fe, res, 0)
    t_first = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)

        def render():
            return render_modes(fe, res, out / "render")

        def plot():
            return [plot_mode_shapes(fe, res, out / f"line{r}.png", n=1) for r in range(IMAGES)]

        tm = common.interleaved({"render": render, "plot": plot}, runs=args.runs, warmup=1)
        size_r = [p.stat().st_size for p in tm["render"].result]
        size_p = [Path(p).stat().st_size for p in tm["plot"].result]
    per = {k: common.Timing(wall=[w / IMAGES for w in t.wall], cpu=[c / IMAGES for c in t.cpu]) for k, t in tm.items()}
    img, base = per["render"], per["plot"]
    ratio, ratio_cpu = common.speedup(img, base)     # render / plot: > 1 means rendering is the slower
    print(f"{args.physics} shaft, 200 elements, {fe.system.n_dofs} DOFs, {IMAGES} modes; {msg}")
    print(f"start-up: backend probe {t_probe:.2f} s, first image {t_first:.2f} s (not in the timed runs)")
    print(f"seconds per PNG, off-screen render : {img.line()}; PNG sizes {min(size_r)}-{max(size_r)} bytes")
    print(f"seconds per PNG, matplotlib plot   : {base.line()}; PNG sizes {min(size_p)}-{max(size_p)} bytes")
    print(f"ratio render / plot: {ratio:.2f} wall, {ratio_cpu:.2f} cpu (no target)")
    w = img.wall_stats.median
    rec = common.record(
        __file__, f"seconds per PNG, {IMAGES} modes of a 200-element shaft ({args.physics}); render/plot time "
        f"ratio {ratio:.2f}", "pyvista off-screen", None, w, ("<", TARGET), metric="s per image", unit="s",
        ratio_cpu=img.cpu_stats.median, runs=args.runs,
        spread={"package": img.spread_dict(), "baseline": base.spread_dict()})
    print()
    common.print_summary(rec)
    common.emit(rec)
    return 0 if rec["met"] else 1


if __name__ == "__main__":
    sys.exit(main())
