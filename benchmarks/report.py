"""Run every benchmark script, collect their ``BENCH-RESULT`` lines, write docs/benchmarks.md and
regenerate the benchmark summary table of docs/performance.md (what ``make bench`` runs).

Each script runs in its own process (``sys.executable``, working directory the repository root);
its output is shown as it comes and saved to ``--save DIR/<script>.log``.  ``--from DIR`` skips
the runs and reads saved logs instead.  The table in docs/performance.md (``--summary FILE``; the
README held it before the README became a landing page) is replaced between the lines
``<!-- bench-table:begin -->`` and ``<!-- bench-table:end -->`` only; the script stops with an
error, changing nothing, when the markers are missing, repeated or out of order.  A script that
printed no BENCH-RESULT line, or failed, gets a visible row saying so (never a stale number).

`make bench` runs the scripts marked for it in :data:`SCRIPTS` (under 10 minutes); the others keep
their last results in docs/benchmarks.json (written here, with each script's full output), so the
table lists every script and says of each row not re-run when it was measured.  ``--all`` runs all.
Scripts that print no BENCH-RESULT records (afc.py, afc_hybrid.py, solid.py, owned elsewhere) have
their printed figures read by the parsers below (rows marked "parsed").

    python benchmarks/report.py [--all] [--only event_solver stick_slip ...] [--skip rotor] [--full]
                                [--save DIR] [--from DIR] [--store FILE] [--summary FILE] [--no-summary] [--no-write]
"""
from __future__ import annotations

import argparse
import datetime as dt
import json
import os
import platform
import re
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import common

ROOT = common.ROOT
HERE = Path(__file__).resolve().parent
BEGIN, END = "<!-- bench-table:begin -->", "<!-- bench-table:end -->"
BUDGET_S = 600.0

# (script, arguments under `make bench`, arguments with --full, in `make bench`): the table's order.
# `make bench` runs the scripts marked True, sized so that together they take under 10 minutes on the
# quiet 2-core machine (about 6.5 min of CPU); the others (each several minutes, or needing an extra
# environment) run with --all or --only, and their last results are kept in docs/benchmarks.json, so
# the summary table always lists every script, each row saying when it was measured.
SCRIPTS: list[tuple[str, list[str], list[str], bool]] = [
    ("event_solver.py", [], [], True),
    ("stick_slip.py", [], [], True),
    ("cli_simulate.py", [], [], True),
    ("hybrid.py", [], [], True),
    ("drives.py", [], [], True),
    ("modal_scaling.py", ["--quick"], [], True),
    ("render.py", [], [], True),
    ("sweep.py", ["--frequencies", "10", "--warm-cluster"], [], True),
    ("afc.py", [], [], True),
    ("loads.py", [], [], True),
    ("geared.py", [], [], True),           # the dense baseline is one eig of 2786 x 2786 (~1.5 min quiet)
    ("afc_hybrid.py", [], [], False),
    ("solid.py", ["--paths", "release", "auto"], [], False),
    ("rotor.py", ["--quick"], [], False),
    ("pyharm.py", [], [], False),          # needs benchmarks/pyharm_env.sh (pyHarm in its own env)
]


class MarkerError(RuntimeError):
    pass


@dataclass
class ScriptRun:
    script: str
    args: list[str]
    returncode: int | None
    wall: float | None
    cpu: float | None
    output: str
    records: list[dict] = field(default_factory=list)
    parse_error: str | None = None
    stored: str | None = None            # date of a run read back from docs/benchmarks.json (not re-run)
    date: str | None = None


# ------------------------------------------------------------------------------ stored results
def load_store(path: Path) -> dict:
    """docs/benchmarks.json: {script: {date, args, returncode, wall, cpu, records}} of the last run of
    each script; {} when absent or unreadable (then the rows of scripts not run say so)."""
    try:
        data = json.loads(path.read_text())
        return data.get("scripts", {}) if isinstance(data, dict) else {}
    except (OSError, ValueError):
        return {}


def stored_run(script: str, store: dict) -> ScriptRun:
    e = store.get(script)
    if not e:
        return ScriptRun(script, [], None, None, None, "", parse_error="not run by this report and no stored result "
                         f"(python benchmarks/report.py --only {Path(script).stem})")
    return ScriptRun(script, e.get("args", []), e.get("returncode"), e.get("wall"), e.get("cpu"), e.get("output", ""),
                     records=e.get("records", []), stored=e.get("date", "?"), date=e.get("date"))


def save_store(path: Path, store: dict, runs: list[ScriptRun]) -> None:
    for r in runs:
        if r.stored is None and r.date is not None:
            store[r.script] = {"date": r.date, "args": r.args, "returncode": r.returncode, "wall": r.wall,
                               "cpu": r.cpu, "records": r.records, "output": r.output}
    path.write_text(json.dumps({"generated_by": "benchmarks/report.py", "scripts": store}, indent=1,
                               allow_nan=False) + "\n")


# ------------------------------------------------------------------------- scripts of other owners
# afc.py, afc_hybrid.py and solid.py print their own lines, not BENCH-RESULT records; their results
# are read from those lines (the figures they print, nothing recomputed) and marked "parsed" in the
# table.  When a script's wording changes and a line is not found, the row says so.
_NUM = r"([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"
_TIMES = re.compile(r"cpu\s+" + _NUM + r" s \(" + _NUM + r" \.\. " + _NUM + r", (\d+) runs?\)\s+wall\s+" + _NUM
                    + r" s \(" + _NUM + r" \.\. " + _NUM + r", (\d+) runs?\)")
_RATIO = re.compile(r"ratio \(brute force / continuation\): " + _NUM + r"x cpu, " + _NUM + r"x wall")
_PEAK = re.compile(r"peak error " + _NUM)


def _blas_line(text: str) -> str | None:
    for line in text.splitlines():
        if line.startswith("BLAS: "):
            return line[6:].strip()
        if line.startswith("BLAS/LAPACK in use"):
            return line.split(":", 1)[1].strip()
    return None


def _afc_records(script: str, text: str, sections: list[tuple[str, str]], target=(">=", 100)) -> list[dict]:
    """Brute force vs continuation records from afc.py-style blocks (``sections``: (label, text))."""
    recs = []
    for label, block in sections:
        lines = block.splitlines()
        bf = next((i for i, l in enumerate(lines) if l.startswith("brute force")), None)
        co = next((i for i, l in enumerate(lines) if l.startswith("continuation")), None)
        rm = _RATIO.search(block)
        if bf is None or co is None or rm is None:
            continue
        tb = _TIMES.search(lines[bf + 1]) if bf + 1 < len(lines) else None
        tc = _TIMES.search(lines[co + 1]) if co + 1 < len(lines) else None
        pb, pc = _PEAK.search(lines[bf]), _PEAK.search(lines[co])
        spread, runs = {}, {}
        for side, m in (("package", tc), ("baseline", tb)):
            if m:
                g = [float(x) for x in m.groups()]
                spread[side] = {"cpu": g[0:3], "wall": g[4:7], "runs": int(g[7])}
                runs[side] = int(g[7])
        rec = common.record(script, f"{label} (parsed from the script's output)", "continuation + shooting",
                            "brute-force time sweeps", float(rm.group(2)), target, ratio_cpu=float(rm.group(1)),
                            accuracy="peak error", accuracy_package=float(pc.group(1)) if pc else None,
                            accuracy_baseline=float(pb.group(1)) if pb else None, runs=runs or None,
                            spread=spread or None, blas=_blas_line(text) or "not reported")
        rec["load"] = None
        recs.append(rec)
    return recs


def parse_afc(text: str) -> list[dict]:
    head = next((l for l in text.splitlines() if l.startswith("seed 002 AFC")), "seed 002 AFC")
    n = re.search(r"brute force\s*: (\d+) frequencies", text)
    label = f"{head.split(',')[0]}, {n.group(1) if n else '?'} frequencies"
    return _afc_records("afc.py", text, [(label, text)])


def parse_afc_hybrid(text: str) -> list[dict]:
    """One record per example: a block starts at a line ``<example>: <title> (n = ...``."""
    starts = [m for m in re.finditer(r"^(\w+): (.*?) \(n = (\d+) DOFs.*$", text, flags=re.M)]
    sections = []
    for k, m in enumerate(starts):
        end = starts[k + 1].start() if k + 1 < len(starts) else len(text)
        sections.append((f"hybrid AFC, {m.group(1)} ({m.group(3)} DOFs)", text[m.start():end]))
    return _afc_records("afc_hybrid.py", text, sections, target=None)   # issue 13: "report their ratio too"


_SOLID_ROW = re.compile(r"^(release|today|superlu|auto): .*?\s" + _NUM + r"s\s+" + _NUM + r"-\s*" + _NUM + r"s\s+.*GB\s+"
                        + _NUM + r"\s+" + _NUM + r"\s*$", flags=re.M)


_SOLID_BASELINES = {"release": "release 890424e (SuperLU)",
                    "today": "today's code, SuperLU forced (checks included)"}


def parse_solid(text: str) -> list[dict]:
    rows = {m.group(1): [float(x) for x in m.groups()[1:]] for m in _SOLID_ROW.finditer(text)}
    head = re.search(r"(\d+) free DOFs.*lowest (\d+) modes", text)
    runs = re.search(r"median and spread of (\d+) runs", text)
    what = (f"3D shaft, {int(head.group(1)):,} DOFs, lowest {head.group(2)} modes" if head else "3D shaft")
    recs = []
    for m in re.finditer(r"^speed-up (\w+) vs (\w+): " + _NUM + r"x", text, flags=re.M):
        p, b = m.group(1), m.group(2)
        rp, rb = rows.get(p), rows.get(b)
        spread = {k: {"wall": v[:3], "runs": int(runs.group(1)) if runs else None}
                  for k, v in (("package", rp), ("baseline", rb)) if v}
        rec = common.record("solid.py", f"{what}, shift-invert Lanczos (parsed from the script's output)",
                            f"{p} factorisation", _SOLID_BASELINES.get(b, b),
                            float(m.group(3)), (">=", 3) if p == "auto" and b == "release" else None,
                            metric="speed-up (median of per-run ratios, fresh processes)",
                            accuracy="max residual / max rel. frequency change vs the baseline's first run",
                            accuracy_package=f"{rp[3]:.1e} / {rp[4]:.1e}" if rp else None,
                            accuracy_baseline=f"{rb[3]:.1e} / {rb[4]:.1e}" if rb else None,
                            runs=int(runs.group(1)) if runs else None, spread=spread or None,
                            blas=_blas_line(text) or "not reported")
        rec["load"] = None
        recs.append(rec)
    return recs


PARSERS = {"afc.py": parse_afc, "afc_hybrid.py": parse_afc_hybrid, "solid.py": parse_solid}


# ------------------------------------------------------------------------------------ collection
def collect(run: ScriptRun) -> ScriptRun:
    try:
        run.records = common.parse_results(run.output)
    except ValueError as e:
        run.parse_error = str(e)
    if not run.records and not run.parse_error and run.script in PARSERS:
        run.records = PARSERS[run.script](run.output)
    return run


def run_script(script: str, args: list[str], save: Path | None, timeout: float) -> ScriptRun:
    """Run one benchmark script, echoing its output; wall and CPU time (children's rusage) measured."""
    env = dict(os.environ)
    env.setdefault("MPLBACKEND", "Agg")
    env.setdefault("PYVISTA_OFF_SCREEN", "true")
    cmd = [sys.executable, str(HERE / script), *args]
    print(f"\n### {' '.join([Path(sys.executable).name, 'benchmarks/' + script, *args])}", flush=True)
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    lines = []
    proc = subprocess.Popen(cmd, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            bufsize=1)
    try:
        for line in proc.stdout:
            sys.stdout.write(line)
            sys.stdout.flush()
            lines.append(line)
            if time.perf_counter() - t0 > timeout:
                raise subprocess.TimeoutExpired(cmd, timeout)
        rc = proc.wait()
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        lines.append(f"\n[report.py: killed after {timeout:g} s]\n")
        rc = None
    except KeyboardInterrupt:
        proc.kill()
        proc.wait()
        raise
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    out = "".join(lines)
    if save is not None:
        save.mkdir(parents=True, exist_ok=True)
        (save / (Path(script).stem + ".log")).write_text(
            f"# {' '.join(cmd[1:])}\n# exit code {rc}, wall {wall:.1f} s, cpu {cpu:.1f} s\n" + out)
    return collect(ScriptRun(script, args, rc, wall, cpu, out, date=_now()))


def _now() -> str:
    return dt.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")


def read_saved(script: str, directory: Path) -> ScriptRun:
    """A script's run from a saved log (the header lines written by :func:`run_script`, if present)."""
    path = directory / (Path(script).stem + ".log")
    if not path.exists():
        return ScriptRun(script, [], None, None, None, "", parse_error=f"no saved output {path}")
    text = path.read_text()
    rc = wall = cpu = None
    lines = text.splitlines()
    args = lines[0][2:].split()[1:] if lines and lines[0].startswith("# ") else []
    if len(lines) > 1 and lines[1].startswith("# exit code"):
        parts = lines[1][2:].replace(",", "").split()
        rc = None if parts[2] == "None" else int(parts[2])
        wall, cpu = float(parts[4]), float(parts[7])
    date = dt.datetime.fromtimestamp(path.stat().st_mtime).astimezone().strftime("%Y-%m-%d %H:%M %Z")
    return collect(ScriptRun(script, args, rc, wall, cpu, text, date=date))


# ------------------------------------------------------------------------------------ formatting
def _cell(x) -> str:
    if x is None:
        return "—"
    if isinstance(x, float):
        return f"{x:.1e}"
    return str(x).replace("|", "\\|")


def _target(rec: dict) -> str:
    t = rec.get("target")
    if not t:
        return ""
    op, val = t.split()
    op = {">=": "≥", "<=": "≤"}.get(op, op)
    unit = "x" if rec.get("unit") is None else rec["unit"]
    return f"{op} {val}{'×' if unit == 'x' else ' ' + unit}".strip()


def _figure(x, unit: str) -> str:
    return common.fmt_ratio(x, unit).replace("x", "×") if unit == "x" else common.fmt_ratio(x, unit)


def result_cell(rec: dict) -> str:
    unit = "x" if rec.get("unit") is None else rec["unit"]
    s = _figure(rec.get("ratio"), unit)
    metric = rec.get("metric") or ""
    if unit != "x" and metric and metric != unit:      # a bare number needs its name (period error, exponent)
        s = f"{_cell(metric)}: {s}"
    if rec.get("ratio_cpu") is not None:
        s += f" (CPU time {_figure(rec['ratio_cpu'], unit)})"
    tgt = _target(rec)
    if tgt:
        s += f"; target {tgt}: **{common.verdict(rec)}**"
    return s


def accuracy_cell(rec: dict) -> str:
    if not rec.get("accuracy"):
        return "—"
    s = f"{_cell(rec['accuracy'])}: {_cell(rec.get('accuracy_package'))}"
    if rec.get("baseline"):
        s += f" vs {_cell(rec.get('accuracy_baseline'))}"
    return s


def runs_cell(rec: dict) -> str:
    sp = rec.get("spread") or {}
    parts = []
    for side in ("package", "baseline"):
        w = (sp.get(side) or {}).get("wall")
        if w:
            parts.append(f"{side} {w[0]:.3g} s [{w[1]:.3g}–{w[2]:.3g}]")
    n = rec.get("runs")
    if isinstance(n, dict):
        label = "runs: " + ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in n.items())
    else:
        label = "—" if n is None else f"{n} run{'' if n == 1 else 's'}"
    return label + (": " + ", ".join(parts) if parts else "")


def readme_table(runs: list[ScriptRun], meta: dict) -> str:
    rows = ["| script | package vs baseline | result, wall time (CPU time); target | accuracy: package vs baseline |",
            "| --- | --- | --- | --- |"]
    stored = False
    for run in runs:
        name = f"`{run.script}`" + (f" (stored run of {run.stored})" if run.stored else "")
        stored |= bool(run.stored)
        if not run.records:
            rows.append(f"| {name} | — | {_missing(run)} | — |")
            continue
        for rec in run.records:
            vs = f"{rec['package']} vs {rec['baseline']}" if rec.get("baseline") else rec["package"]
            rows.append(f"| {name} | {_cell(rec['what'])}: {_cell(vs)} | {result_cell(rec)} | {accuracy_cell(rec)} |")
    rows.append("")
    rows.append(f"Generated by `benchmarks/report.py` on {meta['date']} ({meta['machine']}; load average "
                f"{meta['load_start']} at the start, {meta['load_end']} at the end; BLAS: {meta['blas']}). "
                f"Ratios of the medians of runs timed in the same process run (interleaved); wall-time figures judge "
                f"the targets, CPU-time figures in brackets; the number of runs, their spread and each script's full "
                f"output in [{meta.get('doc_link', 'benchmarks.md')}]({meta.get('doc_link', 'benchmarks.md')})."
                + (" Rows marked *stored run* were not re-run by this report (`make bench` skips the scripts that "
                   "take several minutes each; `python benchmarks/report.py --all` runs every one): their figures "
                   "are from docs/benchmarks.json, of the date shown." if stored else ""))
    return "\n".join(rows)


def _missing(run: ScriptRun) -> str:
    if run.parse_error:
        return f"**no result**: {run.parse_error}"
    if run.returncode is None and run.wall is not None:
        return "**no result**: killed at the time limit"
    if run.returncode not in (0, None):
        return f"**no BENCH-RESULT line** (exit code {run.returncode})"
    return "**no BENCH-RESULT line** (the script does not print one)"


def replace_table(text: str, table: str) -> str:
    """``text`` with everything between the begin and end markers replaced by ``table`` (the marker
    lines themselves kept).  MarkerError when a marker is missing, repeated or out of order."""
    nb, ne = text.count(BEGIN), text.count(END)
    if nb != 1 or ne != 1:
        raise MarkerError(f"expected exactly one '{BEGIN}' and one '{END}' line, found {nb} and {ne}")
    i, j = text.index(BEGIN), text.index(END)
    if j < i:
        raise MarkerError(f"'{END}' comes before '{BEGIN}'")
    return text[:i + len(BEGIN)] + "\n" + table.strip("\n") + "\n" + text[j:]


def machine_info() -> dict:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = ""
    try:
        kb = int(next(l for l in Path("/proc/meminfo").read_text().splitlines() if l.startswith("MemTotal")).split()[1])
        mem = f", {kb / 2**20:.1f} GiB RAM"
    except (OSError, StopIteration, ValueError):
        pass
    versions = []
    from importlib.metadata import PackageNotFoundError, version

    for mod in ("numpy", "scipy", "numba", "threadpoolctl", "pypardiso"):
        try:
            versions.append(f"{mod} {version(mod)}")
        except PackageNotFoundError:
            versions.append(f"{mod} not installed")
    try:
        commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    return {"cpu": cpu, "cores": os.cpu_count(), "mem": mem, "python": platform.python_version(),
            "versions": ", ".join(versions), "commit": commit, "platform": platform.platform(),
            "machine": f"{cpu}, {os.cpu_count()} CPUs{mem}"}


def _blas_of(runs: list[ScriptRun]) -> str:
    """The BLAS configurations the scripts reported (each record carries its process's)."""
    seen = []
    for r in runs:
        for rec in r.records:
            if rec.get("blas") and rec["blas"] not in seen:
                seen.append(rec["blas"])
    return " | ".join(seen) or "not reported"


def _fmt_load(la) -> str:
    return " / ".join(f"{x:.2f}" for x in la) if la else "n/a"


def benchmarks_md(runs: list[ScriptRun], meta: dict) -> str:
    out = ["# Benchmarks", "",
           "Generated by `benchmarks/report.py` (`make bench`); do not edit by hand. Every script times the "
           "package against its baseline in the same run, interleaved, and prints the median and spread of "
           "the runs, wall time and process CPU time (the CPU-time figure is insensitive to other processes "
           "on a shared machine; wall time is what the targets are stated in).", "",
           f"- date: {meta['date']}",
           f"- machine: {meta['machine']}; {meta['platform']}",
           f"- Python {meta['python']}; {meta['info']['versions']}",
           f"- BLAS (threadpoolctl, as the scripts reported it): {meta['blas']}",
           f"- commit: {meta['info']['commit']} (plus any uncommitted changes of the working tree)",
           f"- load average (1 / 5 / 15 min): {meta['load_start']} at the start, {meta['load_end']} at the end",
           f"- total: {meta['total']}", "",
           "## Scripts", "",
           "| script | arguments | exit code | wall [s] | CPU [s] | results | BLAS (threadpoolctl) |",
           "| --- | --- | --- | --- | --- | --- | --- |"]
    for run in runs:
        out.append(f"| `{run.script}`{' (stored run of ' + run.stored + ')' if run.stored else ''} | "
                   f"`{' '.join(run.args) or '-'}` | {_cell(run.returncode)} | "
                   f"{'—' if run.wall is None else f'{run.wall:.1f}'} | {'—' if run.cpu is None else f'{run.cpu:.1f}'} | "
                   f"{len(run.records) if run.records else _missing(run)} | "
                   f"{_cell(run.records[0].get('blas')) if run.records else '—'} |")
    out += ["", "## Results", "",
            "| script | what | package vs baseline | result, wall (CPU); target | accuracy: package vs baseline "
            "| runs: median wall [min–max] | load at the end |",
            "| --- | --- | --- | --- | --- | --- | --- |"]
    for run in runs:
        for rec in run.records:
            vs = f"{rec['package']} vs {rec['baseline']}" if rec.get("baseline") else rec["package"]
            out.append(f"| `{run.script}` | {_cell(rec['what'])} | {_cell(vs)} | {result_cell(rec)} | "
                       f"{accuracy_cell(rec)} | {runs_cell(rec)} | {_fmt_load(rec.get('load'))} |")
    out += ["", "## Output of each script", ""]
    for run in runs:
        text = "\n".join(l for l in run.output.splitlines() if not l.startswith(common.PREFIX)
                         and not l.startswith("# "))
        title = f"### {run.script}" + (f" (stored run of {run.stored})" if run.stored else "")
        out += [title, "", "```text", text.strip() or "(no output)", "```", ""]
    return "\n".join(out)


# ------------------------------------------------------------------------------------------ main
def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    names = [s for s, _, _, _ in SCRIPTS]
    ap.add_argument("--only", nargs="+", metavar="SCRIPT", help=f"run only these ({', '.join(names)})")
    ap.add_argument("--skip", nargs="+", metavar="SCRIPT", default=[])
    ap.add_argument("--all", action="store_true", help="run every script, also those `make bench` leaves out")
    ap.add_argument("--full", action="store_true", help="every script run at its own default sizes")
    ap.add_argument("--from", dest="from_dir", type=Path, help="read saved logs instead of running")
    ap.add_argument("--save", type=Path, default=Path(tempfile.gettempdir()) / "drivefem-bench",
                    help="where to save each script's output (DIR/<script>.log)")
    ap.add_argument("--timeout", type=float, default=1800.0, help="per script, seconds")
    ap.add_argument("--doc", type=Path, default=ROOT / "docs" / "benchmarks.md")
    ap.add_argument("--store", type=Path, default=ROOT / "docs" / "benchmarks.json",
                    help="the last results of every script (read for the scripts not run, updated with those run)")
    ap.add_argument("--summary", "--readme", dest="readme", type=Path, default=ROOT / "docs" / "performance.md",
                    help="the page whose table between the bench-table markers is replaced (default docs/performance.md)")
    ap.add_argument("--no-summary", "--no-readme", dest="no_readme", action="store_true",
                    help="write docs/benchmarks.md but leave the summary page alone")
    ap.add_argument("--no-write", action="store_true", help="print the table only; write no file")
    a = ap.parse_args(argv)
    norm = lambda s: s if s.endswith(".py") else s + ".py"  # noqa: E731
    only = {norm(s) for s in a.only} if a.only else None
    skip = {norm(s) for s in a.skip}
    unknown = ((only or set()) | skip) - set(names)
    if unknown:
        print(f"report.py: unknown script(s) {sorted(unknown)}; known: {', '.join(names)}", file=sys.stderr)
        return 2
    chosen = {s: full if a.full else args for s, args, full, bench in SCRIPTS
              if (s in only if only is not None else (bench or a.all)) and s not in skip}
    readme_text = None
    if not a.no_write and not a.no_readme:    # check the markers before spending ten minutes
        try:
            readme_text = a.readme.read_text()
            replace_table(readme_text, "")
        except (OSError, MarkerError) as e:
            print(f"report.py: cannot update {a.readme}: {e}", file=sys.stderr)
            return 2
    store = load_store(a.store)
    load_start = common.load_average()
    t0 = time.perf_counter()
    if a.from_dir:
        fresh = [read_saved(s, a.from_dir) for s in chosen]
    else:
        fresh = [run_script(s, args, a.save, a.timeout) for s, args in chosen.items()]
    total = time.perf_counter() - t0
    load_end = common.load_average()
    by_name = {r.script: r for r in fresh}
    runs = [by_name.get(s) or stored_run(s, store) for s in names]
    info = machine_info()
    scripts_wall = sum(r.wall or 0 for r in fresh)
    scripts_cpu = sum(r.cpu or 0 for r in fresh)
    meta = {"date": _now(), "machine": info["machine"],
            "platform": info["platform"], "python": info["python"], "info": info, "blas": _blas_of(fresh),
            "load_start": _fmt_load(load_start) if not a.from_dir else "n/a (read from saved logs)",
            "load_end": _fmt_load(load_end) if not a.from_dir else "n/a (read from saved logs)",
            "total": f"{scripts_wall:.0f} s wall, {scripts_cpu:.0f} s CPU for the {len(fresh)} scripts run "
                     f"(`make bench`: budget {BUDGET_S:.0f} s wall on a quiet 2-core machine)"}
    if a.from_dir:                         # the records carry the load at their end
        loads = [rec.get("load") for r in fresh for rec in r.records if rec.get("load")]
        if loads:
            meta["load_start"] = f"{_fmt_load(loads[0])} (first record)"
            meta["load_end"] = f"{_fmt_load(loads[-1])} (last record)"
    meta["doc_link"] = os.path.relpath(a.doc.resolve(), a.readme.resolve().parent)   # from the summary file
    table = readme_table(runs, meta)
    print("\n" + table)
    print(f"\n{meta['total']}; report took {total:.0f} s")
    if not a.no_write:
        a.doc.parent.mkdir(parents=True, exist_ok=True)
        a.doc.write_text(benchmarks_md(runs, meta) + "\n")
        print(f"written: {a.doc}")
        save_store(a.store, store, fresh)
        print(f"written: {a.store}")
        if not a.no_readme:
            a.readme.write_text(replace_table(a.readme.read_text(), table))
            print(f"written: the table in {a.readme}")
    bad = [r.script for r in fresh if not r.records or r.parse_error]
    failed = [f"{r.script}: {rec['what']}" for r in runs for rec in r.records if rec.get("met") is False]
    if bad:
        print(f"scripts run without results: {', '.join(bad)}")
    if failed:
        print("targets NOT met (wall time):\n  " + "\n  ".join(failed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
