"""Run the validation catalogue and present it: a table on stdout, a report directory
(markdown table, JSON, a plot of relative errors against tolerances, and the HTML page with
its figures from :mod:`validation.html_report`)."""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from .registry import CaseOutcome, run_case, select


def run_validation(names: list[str] | None = None, include_slow: bool = True, progress=None) -> list[CaseOutcome]:
    """Run the selected cases; ``progress``: called as ``progress(done, total)`` after each case (the
    command's bar: :func:`fem.app.progress.count_bar`, whose ``note`` shows the running case)."""
    cases = select(names, include_slow=include_slow)
    out = []
    for k, c in enumerate(cases):
        if progress is not None:
            getattr(progress, "note", lambda _: None)(c.name)
            progress(k, len(cases))
        out.append(run_case(c))
    if progress is not None:
        progress(len(cases), len(cases))
    return out


def _fmt(v) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    return f"{v:.6g}"


def rows(outcomes: list[CaseOutcome]) -> list[list[str]]:
    table = []
    for o in outcomes:
        if o.error:
            table.append([o.case.name, "-", "ERROR: " + o.error, "-", "-", "-", "-", "FAIL"])
        for c in o.checks:
            table.append([o.case.name, c.source, c.quantity, _fmt(c.expected), _fmt(c.computed),
                          f"{c.rel_error:.1e}", f"{c.tolerance:.0e}" if c.tolerance else "claim",
                          "ok" if c.passed else "FAIL"])
    return table


HEAD = ["case", "source", "quantity", "expected", "computed", "rel.err", "tol", ""]


def print_table(outcomes: list[CaseOutcome], out=None) -> None:
    out = sys.stdout if out is None else out      # bound at call time (a captured stream may close)
    table = rows(outcomes)
    widths = [min(max(len(r[i]) for r in table + [HEAD]), 46) for i in range(len(HEAD))]
    line = "  ".join(h.ljust(w) for h, w in zip(HEAD, widths))
    print(line, file=out)
    print("-" * len(line), file=out)
    for r in table:
        print("  ".join(c[:w].ljust(w) for c, w in zip(r, widths)), file=out)
    n_checks = sum(len(o.checks) for o in outcomes)
    n_fail = sum(not c.passed for o in outcomes for c in o.checks) + sum(bool(o.error) for o in outcomes)
    secs = sum(o.seconds for o in outcomes)
    print(f"\n{len(outcomes)} cases, {n_checks} checks: {n_checks - n_fail + sum(bool(o.error) for o in outcomes)} "
          f"passed, {n_fail} failed ({secs:.1f} s)", file=out)


def write_report(outcomes: list[CaseOutcome], directory: str | Path) -> Path:
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    md = ["# drivefem validation report", "",
          "| " + " | ".join(HEAD[:-1]) + " | result |", "|" + "---|" * len(HEAD)]
    md += ["| " + " | ".join(r) + " |" for r in rows(outcomes)]
    md += ["", "## Cases", ""]
    for o in outcomes:
        md += [f"### {o.case.name} ({o.case.group}{', slow' if o.case.slow else ''}, {o.seconds:.2f} s)", "",
               o.case.doc or "", ""]
        notes = [c for c in o.checks if c.note]
        md += [f"- {c.quantity}: {c.note}" for c in notes]
        md.append("")
    (directory / "report.md").write_text("\n".join(md))
    (directory / "report.json").write_text(json.dumps(
        {"cases": [c.to_dict() | {"case": o.case.name} for o in outcomes for c in o.checks],
         "errors": {o.case.name: o.error for o in outcomes if o.error}}, indent=2))
    _plot_errors(outcomes, directory / "errors.png")
    from .html_report import make_figures, write_html

    figures = [directory / "errors.png"] if (directory / "errors.png").exists() else []
    return write_html(outcomes, directory, figures + make_figures(directory))


def _plot_errors(outcomes, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    checks = [(o.case.name, c) for o in outcomes for c in o.checks if c.tolerance > 0]
    if not checks:
        return
    fig, ax = plt.subplots(figsize=(8, max(3, 0.12 * len(checks))))
    y = np.arange(len(checks))
    err = np.array([max(c.rel_error, 1e-17) for _, c in checks])
    tol = np.array([c.tolerance for _, c in checks])
    ax.scatter(err, y, s=8, c=["tab:green" if c.passed else "tab:red" for _, c in checks], label="rel. error")
    ax.scatter(tol, y, s=8, marker="|", c="k", label="tolerance")
    ax.set_xscale("log")
    ax.set_yticks([])
    ax.set_xlabel("relative error [-]")
    ax.set_title("validation checks: error (dot) vs tolerance (bar)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
