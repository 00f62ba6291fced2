"""The validation report as a self-contained HTML page plus its Markdown twin.

``write_html(outcomes, directory, figures)`` writes ``validation.html`` and
``validation.md`` into ``directory``: a summary, the table of every check (case, source,
quantity, expected, computed, relative error, tolerance, pass), errors of crashed cases,
each case's docstring (where its tolerances are justified) and the figures.  Figures
outside ``directory`` are copied into ``directory/figures/`` so the folder can be moved or
published as it is.  Nothing is fetched from the network (no scripts, no fonts).
"""
from __future__ import annotations

import html
import shutil
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from .registry import CaseOutcome

COLUMNS = ["case", "source", "quantity", "expected", "computed", "rel. error", "tolerance", "result"]

CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:2em auto;max-width:1200px;color:#222;padding:0 1em}
h1{font-size:1.6em} h2{font-size:1.25em;margin-top:2em;border-bottom:1px solid #ccc}
table{border-collapse:collapse;width:100%;font-size:.85em}
th,td{border:1px solid #ddd;padding:.25em .5em;text-align:left;vertical-align:top}
th{background:#f3f3f3;position:sticky;top:0} td.num{text-align:right;font-family:ui-monospace,monospace}
tr.fail td{background:#fde8e8} td.ok{color:#176317;font-weight:600} td.bad{color:#b00020;font-weight:700}
.summary span{display:inline-block;margin-right:1.5em} .pass{color:#176317} .failtxt{color:#b00020}
details{margin:.4em 0} summary{cursor:pointer} pre{white-space:pre-wrap;background:#fafafa;padding:.6em;border:1px solid #eee}
figure{display:inline-block;margin:.5em;max-width:48%} figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:.8em;color:#555}
"""


def _fmt(v) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    return f"{v:.6g}"


def table_rows(outcomes: list[CaseOutcome]) -> list[dict]:
    """One dict per check (and one per crashed case) with the report's columns."""
    out = []
    for o in outcomes:
        if o.error:
            out.append({"case": o.case.name, "source": "-", "quantity": "ERROR: " + o.error, "expected": "-",
                        "computed": "-", "rel. error": "-", "tolerance": "-", "result": "FAIL", "passed": False})
        for c in o.checks:
            out.append({"case": o.case.name, "source": c.source, "quantity": c.quantity, "expected": _fmt(c.expected),
                        "computed": _fmt(c.computed), "rel. error": f"{c.rel_error:.2e}",
                        "tolerance": f"{c.tolerance:.1e}" if c.tolerance else "claim",
                        "result": "pass" if c.passed else "FAIL", "passed": bool(c.passed), "note": c.note})
    return out


def _collect_figures(figures, directory: Path) -> list[Path]:
    """Figures as paths relative to ``directory`` (copied into figures/ when outside)."""
    out = []
    for f in figures or []:
        f = Path(f)
        if not f.is_file():
            continue
        try:
            out.append(f.resolve().relative_to(directory.resolve()))
        except ValueError:
            dest = directory / "figures" / (f"{f.parent.name}_{f.name}" if f.parent.name else f.name)
            dest.parent.mkdir(parents=True, exist_ok=True)
            if dest.resolve() != f.resolve():
                shutil.copyfile(f, dest)
            out.append(dest.relative_to(directory))
    return out


def _summary(outcomes) -> dict:
    n_checks = sum(len(o.checks) for o in outcomes)
    n_failed = sum(not c.passed for o in outcomes for c in o.checks) + sum(bool(o.error) for o in outcomes)
    return {"cases": len(outcomes), "checks": n_checks, "failed": n_failed,
            "cases_failed": sum(not o.passed for o in outcomes), "seconds": sum(o.seconds for o in outcomes)}


def write_html(outcomes: list[CaseOutcome], directory, figures: list[Path] | None = None) -> Path:
    """Write ``validation.html`` and ``validation.md`` into ``directory``; returns the HTML path."""
    from fem.output.mesh import ensure_directory

    directory = ensure_directory(directory, "validation report directory")
    figs = _collect_figures(figures, directory)
    rows = table_rows(outcomes)
    s = _summary(outcomes)
    stamp = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    esc = html.escape
    verdict = ('<span class="pass">all passed</span>' if s["failed"] == 0
               else f'<span class="failtxt">{s["cases_failed"]} case(s) failed</span>')
    h = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
         "<title>drivefem validation report</title>", f"<style>{CSS}</style></head><body>",
         "<h1>drivefem validation report</h1>",
         f'<p class="summary"><span>{s["cases"]} cases</span><span>{s["checks"]} checks</span>'
         f'<span>{verdict}</span><span>{s["seconds"]:.1f} s</span><span>{stamp}</span></p>',
         "<p>Every case compares the package with an independent reference (closed form, root of a "
         "frequency equation, a printed table, or a second independent method) under a tolerance "
         "justified in the case's description below. <code>claim</code> rows are yes/no statements.</p>",
         "<h2>Checks</h2>", "<table><thead><tr>" + "".join(f"<th>{c}</th>" for c in COLUMNS) + "</tr></thead><tbody>"]
    for r in rows:
        cls = "" if r["passed"] else ' class="fail"'
        cells = []
        for c in COLUMNS:
            v = esc(str(r[c]))
            if c == "quantity" and r.get("note"):
                v += f'<br><small>{esc(r["note"])}</small>'
            kind = "num" if c in ("expected", "computed", "rel. error", "tolerance") else ""
            if c == "result":
                kind = "ok" if r["passed"] else "bad"
            cells.append(f'<td class="{kind}">{v}</td>' if kind else f"<td>{v}</td>")
        h.append(f"<tr{cls}>" + "".join(cells) + "</tr>")
    h.append("</tbody></table>")
    if figs:
        h.append("<h2>Figures</h2>")
        for f in figs:
            h.append(f'<figure><img src="{esc(f.as_posix())}" alt="{esc(f.stem)}">'
                     f"<figcaption>{esc(f.stem)}</figcaption></figure>")
    h.append("<h2>Cases</h2>")
    for o in outcomes:
        status = "passed" if o.passed else "FAILED"
        h.append(f"<details{' open' if not o.passed else ''}><summary><b>{esc(o.case.name)}</b> "
                 f"({esc(o.case.group)}{', slow' if o.case.slow else ''}, {o.seconds:.2f} s): {status}</summary>")
        if o.case.doc:
            h.append(f"<pre>{esc(o.case.doc)}</pre>")
        if o.error:
            h.append(f'<p class="failtxt">error: {esc(o.error)}</p>')
        h.append("</details>")
    h.append("</body></html>")
    path = directory / "validation.html"
    path.write_text("\n".join(h), encoding="utf-8")
    (directory / "validation.md").write_text(_markdown(outcomes, rows, figs, s, stamp), encoding="utf-8")
    return path


def _markdown(outcomes, rows, figs, s, stamp) -> str:
    def cell(v):
        return str(v).replace("|", "\\|").replace("\n", " ")

    md = ["# drivefem validation report", "",
          f"{s['cases']} cases, {s['checks']} checks, "
          + ("all passed" if s["failed"] == 0 else f"**{s['cases_failed']} case(s) failed**")
          + f", {s['seconds']:.1f} s ({stamp})", "",
          "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for r in rows:
        q = r["quantity"] + (f" ({r['note']})" if r.get("note") else "")
        md.append("| " + " | ".join(cell(r[c] if c != "quantity" else q) if c != "result"
                                     else ("pass" if r["passed"] else "**FAIL**") for c in COLUMNS) + " |")
    if figs:
        md += ["", "## Figures", ""] + [f"![{f.stem}]({f.as_posix()})" for f in figs]
    md += ["", "## Cases", ""]
    for o in outcomes:
        md += [f"### {o.case.name} ({o.case.group}{', slow' if o.case.slow else ''}, {o.seconds:.2f} s)", "",
               o.case.doc or "", ""]
        if o.error:
            md += [f"**error:** {o.error}", ""]
    return "\n".join(md)


def make_figures(directory) -> list[Path]:
    """Figures for the report (about 5 s): a mesh-convergence plot (P2 torsion and Hermite
    bending against their frequency equations), the 3D stubby shaft against the 1D models,
    and rendered mode shapes of a cantilever (skipped, with a note, when VTK cannot render).
    Written into ``directory/figures``; pass the list to :func:`write_html`."""
    from fem import assemble, modal_analysis
    from fem.output.mesh import ensure_directory
    from fem.output.figures import plot_convergence, plot_solid_vs_beam
    from fem.solid import ShaftMeshSpec, build_solid, solid_modal
    from validation.analytic.bending import euler_bernoulli_omegas, euler_bernoulli_roots
    from validation.builders import uniform

    out = ensure_directory(Path(directory) / "figures", "validation report directory")
    figs = []
    L, d = 1.5, 0.05
    ns = np.array([4, 8, 16, 32])
    errs = {}
    for r in (0, 1):
        e_t, e_b = [], []
        for n in ns:
            m = uniform("torsion", L, int(n), d=d, supports=[(0.0, "clamped")])
            s = m.segments[0]
            exact_t = (2 * r + 1) * np.pi / (2 * L) * np.sqrt(s.material.G / s.material.rho)
            e_t.append(modal_analysis(assemble(m).system, 2).omega_rad_s[r] / exact_t - 1)
            mb = uniform("bending", L, int(n), d=d, supports=[(0.0, "clamped")])
            sb = mb.segments[0]
            exact_b = euler_bernoulli_omegas(sb.material.E * sb.section.I, sb.material.rho * sb.section.A, L,
                                             euler_bernoulli_roots("clamped-free", 2))[r]
            e_b.append(modal_analysis(assemble(mb).system, 2).omega_rad_s[r] / exact_b - 1)
        errs[f"torsion P2, mode {r + 1}"] = e_t
        errs[f"bending Hermite, mode {r + 1}"] = e_b
    figs.append(plot_convergence(ns, errs, out / "convergence.png", orders=(4,),
                                 title="cantilever frequencies vs frequency equations"))
    Ls, ds = 0.3, 0.1
    res = solid_modal(build_solid(uniform("bending", Ls, 8, d=ds, supports=[(0.0, "clamped")]),
                                  ShaftMeshSpec(n_quarter=2)), 10)
    beam = {}
    for label, phys, th in (("Euler-Bernoulli", "bending", "euler-bernoulli"), ("Timoshenko", "bending", "timoshenko"),
                            ("torsion 1D", "torsion", "euler-bernoulli"), ("axial rod", "axial", "euler-bernoulli")):
        fe = assemble(uniform(phys, Ls, 40, d=ds, theory=th, supports=[(0.0, "clamped")]))
        beam[label] = (phys if phys != "axial" else "axial", modal_analysis(fe.system, 3).frequencies_hz)
    figs.append(plot_solid_vs_beam(res, beam, out / "solid_vs_beam.png",
                                   title="stubby cantilever L/d = 3: 3D solid vs 1D models"))
    try:
        from fem.render import available, render_modes

        if available()[0]:
            fe = assemble(uniform("bending", L, 40, d=d, supports=[(0.0, "clamped")]))
            figs += render_modes(fe, modal_analysis(fe.system, 2), out, prefix="cantilever_mode")
    except ImportError:
        pass
    return figs
