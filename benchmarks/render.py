"""Off-screen rendering speed: 6 mode-shape PNGs of a 200-element shaft (issue 6 target:
under 1 s per image on 2 cores after start-up).

Start-up (importing pyvista/VTK and the first OpenGL context) is timed separately; then
each image is timed (median of ``--repeat`` runs of all 6).  Baseline in the same run: a
matplotlib line plot of the same 6 modes (fem.plots.plot_mode_shapes), so the printed
ratio is stable across machines.

    python benchmarks/render.py [--repeat 3] [--physics bending|torsion]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from fem import assemble, modal_analysis  # noqa: E402
from validation.builders import uniform  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--physics", default="bending", choices=("bending", "torsion", "axial"))
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    from fem.render import available, render_image, render_modes

    ok, msg = available()
    t_probe = time.perf_counter() - t0
    if not ok:
        print(f"rendering unavailable: {msg}")
        return 1
    fe = assemble(uniform(args.physics, 2.0, 200, d=0.05, supports=[(0.0, "clamped")]))
    res = modal_analysis(fe.system, 6)
    t0 = time.perf_counter()
    render_image(fe, res, 0)
    t_first = time.perf_counter() - t0
    per_image, per_plot = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            render_modes(fe, res, tmp)
            per_image.append((time.perf_counter() - t0) / 6)
            from fem.plots import plot_mode_shapes

            t0 = time.perf_counter()
            for r in range(6):
                plot_mode_shapes(fe, res, Path(tmp) / f"line{r}.png", n=1)
            per_plot.append((time.perf_counter() - t0) / 6)
    img, base = statistics.median(per_image), statistics.median(per_plot)
    print(f"{args.physics} shaft, 200 elements, {fe.system.n_dofs} DOFs, 6 modes; {msg}")
    print(f"start-up: backend probe {t_probe:.2f} s, first image {t_first:.2f} s")
    print(f"seconds per PNG (median of {args.repeat}): {img:.3f} s   target < 1 s: {'met' if img < 1 else 'NOT met'}")
    print(f"baseline matplotlib line plot per image:  {base:.3f} s   ratio render/plot = {img / base:.2f}")
    return 0 if img < 1 else 1


if __name__ == "__main__":
    sys.exit(main())
