"""Shared helpers of the benchmark scripts: the BLAS in use, interleaved timing (wall and CPU time,
median and spread of >= 5 runs), the one-line result record ``BENCH-RESULT {json}`` that
benchmarks/report.py collects, and an earlier release of the package run as a baseline.

Timing protocol (why each piece is there):

* The machine is shared: wall times of one run vary by factors of 3-10 with the load of other
  processes.  The candidates of a comparison are therefore run *interleaved* (package, baseline,
  baseline, package, ... -- the order alternates round by round so that neither side always runs
  first after the other's memory traffic), so both see the same load; the ratio is the ratio of
  the medians of the wall times, and also printed from the medians of the process CPU times
  (``time.process_time``: CPU of all threads of the process, insensitive to time slicing; it misses
  time spent waiting and the work of other processes, e.g. Dask workers).
* Medians, not means: a run that was descheduled is an outlier upwards, the median ignores it;
  the spread (min-max) is printed so a reader sees how noisy the run was.
* A warm-up call before timing (imports, caches, numba compilation) is reported separately by the
  scripts that have one-off costs.

Record: :func:`emit` prints ``BENCH-RESULT {json}`` with the keys of :data:`RECORD_KEYS`;
:func:`parse_results` reads them back from any text (the output of a script or of ``make bench``).

Baselines from an earlier commit: :func:`old_release` exports the tree of a pinned commit
(``git archive COMMIT | tar -x``: read-only use of the repository, the checkout is not touched) and
:func:`release_worker` runs a snippet there in a subprocess with ``PYTHONPATH`` set to that tree,
timing it on request so that its runs interleave with the package's runs in this process.
"""
from __future__ import annotations

import json
import math
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

ROOT = Path(__file__).resolve().parents[1]
PREFIX = "BENCH-RESULT "
RECORD_KEYS = ("script", "what", "package", "baseline", "metric", "ratio", "ratio_cpu", "unit", "target", "met",
               "met_cpu", "accuracy", "accuracy_package", "accuracy_baseline", "runs", "spread", "blas", "load")
MIN_RUNS = 5


def limit_blas_threads(n: int = 1) -> None:
    """Set the BLAS/OpenMP thread counts for libraries not loaded yet (call before importing numpy).
    Small dense matrices: BLAS threads only add contention on a shared 2-core machine."""
    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, str(n))


# ------------------------------------------------------------------------------------------ BLAS
def blas_info() -> list[dict]:
    """The BLAS libraries loaded in this process (threadpoolctl): library, version, threads,
    internal_api, architecture, file.  numpy and scipy.linalg are imported first so that both of
    their BLAS builds are listed (threadpoolctl sees only loaded libraries)."""
    import numpy  # noqa: F401
    import scipy.linalg  # noqa: F401
    from threadpoolctl import threadpool_info

    out = []
    for i in threadpool_info():
        if i.get("user_api") != "blas":
            continue
        out.append({"library": i.get("prefix"), "internal_api": i.get("internal_api"), "version": i.get("version"),
                    "threads": i.get("num_threads"), "architecture": i.get("architecture"),
                    "file": Path(i.get("filepath", "")).name})
    return out


def blas_summary(info: list[dict] | None = None) -> str:
    """One line: ``openblas 0.3.27 SkylakeX, 1 thread (libscipy_openblas...)``; identical builds listed once."""
    seen = []
    for b in blas_info() if info is None else info:
        arch = f" {b['architecture']}" if b.get("architecture") else ""
        s = (f"{b['internal_api']} {b.get('version') or '?'}{arch}, {b['threads']} thread"
             f"{'s' if b['threads'] != 1 else ''} ({b['file']})")
        if s not in seen:
            seen.append(s)
    return "; ".join(sorted(seen)) or "no BLAS loaded"


def load_average() -> list[float] | None:
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except OSError:
        return None


def machine_line() -> str:
    la = load_average()
    return (f"{platform.node()} {platform.machine()}, {os.cpu_count()} CPUs, Python {platform.python_version()}, "
            f"load average {' '.join(f'{x:.2f}' for x in la) if la else 'n/a'}")


# ------------------------------------------------------------------------------------ statistics
@dataclass(frozen=True)
class Stats:
    """Median and spread of a sample."""
    median: float
    min: float
    max: float
    n: int

    @classmethod
    def of(cls, values) -> "Stats":
        v = [float(x) for x in values]
        if not v:
            raise ValueError("Stats of an empty sample")
        return cls(statistics.median(v), min(v), max(v), len(v))

    @property
    def spread(self) -> float:
        """(max - min) / median: the relative width of the sample."""
        return (self.max - self.min) / self.median if self.median else math.inf

    def fmt(self, scale: float = 1.0, unit: str = "s", digits: int = 3) -> str:
        f = lambda x: f"{x * scale:.{digits}g}"   # noqa: E731
        return f"{f(self.median)} {unit} [{f(self.min)}-{f(self.max)}]"

    def to_list(self) -> list[float]:
        return [self.median, self.min, self.max]


@dataclass
class Timing:
    """Wall and process-CPU times of the runs of one candidate (seconds) and its last result."""
    wall: list[float] = field(default_factory=list)
    cpu: list[float] = field(default_factory=list)
    result: Any = None

    @property
    def runs(self) -> int:
        return len(self.wall)

    @property
    def wall_stats(self) -> Stats:
        return Stats.of(self.wall)

    @property
    def cpu_stats(self) -> Stats:
        return Stats.of(self.cpu)

    def line(self, scale: float = 1.0, unit: str = "s") -> str:
        """``median 0.146 s [0.140-0.160] wall, cpu 0.040 s [0.039-0.044], 5 runs``."""
        return (f"median {self.wall_stats.fmt(scale, unit)} wall, cpu {self.cpu_stats.fmt(scale, unit)}, "
                f"{self.runs} run{'s' if self.runs != 1 else ''}")

    def spread_dict(self) -> dict:
        return {"wall": self.wall_stats.to_list(), "cpu": self.cpu_stats.to_list(), "runs": self.runs}


@dataclass(frozen=True)
class Measured:
    """A run timed elsewhere (e.g. inside a subprocess): :func:`interleaved` uses these times
    instead of its own, so interprocess overhead is not counted."""
    wall: float
    cpu: float
    value: Any = None


def timed(fn: Callable[[], Any]) -> tuple[float, float, Any]:
    """(wall, cpu, result) of one call.  A :class:`Measured` result supplies its own times."""
    w0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    if isinstance(out, Measured):
        return out.wall, out.cpu, out.value
    return wall, cpu, out


def interleaved(candidates: dict[str, Callable[[], Any]], runs: int = MIN_RUNS, warmup: int = 0,
                runs_of: dict[str, int] | None = None, verbose: bool = False) -> dict[str, Timing]:
    """Time the candidates round by round: every round calls each candidate once, the order
    alternating (forward, then backward) between rounds.  ``runs_of`` gives fewer runs to slow
    candidates (they are skipped in the later rounds).  ``warmup`` untimed calls of each first."""
    names = list(candidates)
    want = {n: (runs_of or {}).get(n, runs) for n in names}
    out = {n: Timing() for n in names}
    for _ in range(warmup):
        for n in names:
            out[n].result = candidates[n]()
            if isinstance(out[n].result, Measured):
                out[n].result = out[n].result.value
    for r in range(max(want.values())):
        order = names if r % 2 == 0 else names[::-1]
        for n in order:
            if out[n].runs >= want[n]:
                continue
            wall, cpu, res = timed(candidates[n])
            out[n].wall.append(wall)
            out[n].cpu.append(cpu)
            out[n].result = res
            if verbose:
                print(f"  run {r + 1}: {n:<24s} wall {wall:9.4f} s, cpu {cpu:9.4f} s", flush=True)
    return out


def steady(fn: Callable[[], Any], calls: int = 5, warm: int = 1) -> Callable[[], Measured]:
    """A block of ``warm`` untimed and ``calls`` timed consecutive calls of a millisecond-scale
    ``fn``, as one candidate of :func:`interleaved`: its time is the median of the block's calls
    (steady state, like timeit: the first call after other large work meets cold caches), while
    the blocks still interleave with the other candidates' runs."""
    def block() -> Measured:
        out = None
        for _ in range(warm):
            out = fn()
        walls, cpus = [], []
        for _ in range(calls):
            w, c, out = timed(fn)
            walls.append(w)
            cpus.append(c)
        return Measured(statistics.median(walls), statistics.median(cpus), out)
    return block


def blas_threads(n: int | None):
    """Context manager: BLAS calls of this process use ``n`` threads (threadpoolctl; None: as loaded)."""
    from contextlib import nullcontext

    from threadpoolctl import threadpool_limits

    return nullcontext() if n is None else threadpool_limits(limits=n, user_api="blas")


def speedup(baseline: Timing, package: Timing) -> tuple[float, float]:
    """(wall, cpu) ratios baseline / package from the medians."""
    return (baseline.wall_stats.median / package.wall_stats.median,
            baseline.cpu_stats.median / package.cpu_stats.median)


# ----------------------------------------------------------------------------------------- record
def _target_met(value: float | None, target: tuple[str, float] | None) -> bool | None:
    if value is None or target is None or not math.isfinite(value):
        return None if value is None or target is None else False
    op, bound = target
    return {">=": value >= bound, ">": value > bound, "<=": value <= bound, "<": value < bound}[op]


def _clean(x):
    """JSON-safe copy: non-finite floats become None, numpy scalars plain numbers."""
    if isinstance(x, dict):
        return {str(k): _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    if hasattr(x, "item") and not isinstance(x, (str, bytes)):
        try:
            x = x.item()
        except (TypeError, ValueError):
            pass
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def record(script: str, what: str, package: str, baseline: str | None, ratio: float | None,
           target: tuple[str, float] | None, *, metric: str = "speed-up", unit: str = "x",
           ratio_cpu: float | None = None, accuracy: str = "", accuracy_package=None, accuracy_baseline=None,
           runs: int | dict | None = None, spread: dict | None = None, blas: str | None = None) -> dict:
    """The standard result record.  ``ratio`` is the headline figure (baseline/package from the
    medians of the interleaved wall times for a speed-up; or a rate, or a time, as ``metric`` and
    ``unit`` say); ``target`` is ``(op, bound)`` with op one of >=, >, <=, <; ``met`` is judged on
    the wall-time figure, ``met_cpu`` on the CPU-time one."""
    return _clean({
        "script": Path(script).name, "what": what, "package": package, "baseline": baseline, "metric": metric,
        "ratio": ratio, "ratio_cpu": ratio_cpu, "unit": unit,
        "target": None if target is None else f"{target[0]} {target[1]:g}",
        "met": _target_met(ratio, target), "met_cpu": _target_met(ratio_cpu, target),
        "accuracy": accuracy, "accuracy_package": accuracy_package, "accuracy_baseline": accuracy_baseline,
        "runs": runs, "spread": spread, "blas": blas if blas is not None else blas_summary(),
        "load": load_average()})


def emit(rec: dict) -> dict:
    """Print the record as one line ``BENCH-RESULT {json}`` (flushed) and return it."""
    print(PREFIX + json.dumps(rec, sort_keys=False, allow_nan=False), flush=True)
    return rec


def parse_results(text: str) -> list[dict]:
    """All records in ``text`` (lines starting with ``BENCH-RESULT ``, other lines ignored); a line
    with the prefix but broken JSON raises ValueError naming it (a silent drop would hide a row)."""
    out = []
    for k, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s.startswith(PREFIX):
            continue
        try:
            rec = json.loads(s[len(PREFIX):])
        except json.JSONDecodeError as e:
            raise ValueError(f"line {k}: broken BENCH-RESULT record ({e}): {s[:120]}") from None
        if not isinstance(rec, dict) or "script" not in rec:
            raise ValueError(f"line {k}: BENCH-RESULT record without a 'script' key: {s[:120]}")
        out.append(rec)
    return out


def fmt_ratio(x: float | None, unit: str = "x") -> str:
    if x is None or not math.isfinite(x):
        return "n/a"
    if unit == "x":
        return f"{x:.4g}x" if x < 1e4 else f"{x:.0f}x" if x < 1e5 else f"{x:.1e}x"
    return (f"{x:.3g} {unit}" if abs(x) < 1000 else f"{x:,.0f} {unit}").strip()


def verdict(rec: dict) -> str:
    m, mc = rec.get("met"), rec.get("met_cpu")
    if m is None:
        return "no target" if rec.get("target") is None else "NOT MEASURED"
    s = "MET" if m else "NOT MET"
    if mc is not None and mc != m:
        s += f" (CPU time: {'met' if mc else 'not met'})"
    return s


def print_summary(rec: dict) -> None:
    """The human-readable line of a record: ratio (wall, CPU), target, accuracy side by side."""
    acc = ""
    if rec.get("accuracy"):
        acc = (f"; {rec['accuracy']}: package {_num(rec.get('accuracy_package'))}"
               + (f", baseline {_num(rec.get('accuracy_baseline'))}" if rec.get("baseline") else ""))
    cpu = f" (CPU time {fmt_ratio(rec['ratio_cpu'], rec['unit'])})" if rec.get("ratio_cpu") is not None else ""
    vs = f" vs {rec['baseline']}" if rec.get("baseline") else ""
    print(f"RESULT {rec['what']}: {rec['package']}{vs}: {rec['metric']} {fmt_ratio(rec['ratio'], rec['unit'])}{cpu}, "
          f"target {rec['target'] or '-'}: {verdict(rec)}{acc}", flush=True)


def finish(recs: list[dict]) -> int:
    """Print the summary of every record, then their ``BENCH-RESULT`` lines; the exit code: 1 when a
    target is not met, else 0 (records without a target never fail)."""
    for rec in recs:
        print_summary(rec)
    for rec in recs:
        emit(rec)
    return 0 if all(rec["met"] is not False for rec in recs) else 1


def _num(x) -> str:
    if isinstance(x, float):
        return f"{x:.2e}"
    return "n/a" if x is None else str(x)


def header(script: str, description: str) -> None:
    """First lines of every benchmark: what, machine, BLAS."""
    print(f"== {Path(script).name}: {description}")
    print(f"machine: {machine_line()}")
    print(f"BLAS: {blas_summary()}", flush=True)


# ------------------------------------------------------------------------------ earlier releases
def old_release(commit: str, root: Path = ROOT) -> Path:
    """The source tree of ``commit`` exported once to a cached temporary directory
    (``git archive COMMIT | tar -x``; read-only use of the repository).  Raises RuntimeError
    with the reason when git or the commit is not available (e.g. a shallow clone)."""
    if shutil.which("git") is None:
        raise RuntimeError("git is not installed: the pinned earlier release cannot be exported")
    try:
        full = subprocess.run(["git", "-C", str(root), "rev-parse", "--verify", f"{commit}^{{commit}}"],
                              capture_output=True, text=True, check=True).stdout.strip()
    except subprocess.CalledProcessError as e:
        raise RuntimeError(f"commit {commit} not found in {root} ({e.stderr.strip()}); a shallow clone lacks it: "
                           f"git fetch --unshallow") from None
    dest = Path(tempfile.gettempdir()) / f"drivefem-release-{full[:12]}"
    if (dest / ".complete").exists():
        return dest
    tmp = Path(tempfile.mkdtemp(prefix=f"drivefem-release-{full[:12]}-"))
    archive = subprocess.Popen(["git", "-C", str(root), "archive", full], stdout=subprocess.PIPE)
    tar = subprocess.run(["tar", "-x", "-C", str(tmp)], stdin=archive.stdout, capture_output=True)
    archive.stdout.close()
    if archive.wait() != 0 or tar.returncode != 0:
        shutil.rmtree(tmp, ignore_errors=True)
        raise RuntimeError(f"git archive {commit} | tar -x failed: {tar.stderr.decode(errors='replace').strip()}")
    (tmp / ".complete").write_text(full + "\n")
    try:
        tmp.rename(dest)
    except OSError:                       # another process exported it meanwhile
        shutil.rmtree(tmp, ignore_errors=True)
    return dest


def _release_env(tree: Path, env: dict | None) -> dict:
    e = dict(os.environ)
    e["PYTHONPATH"] = str(tree)
    e.update(env or {})
    return e


_WORKER = r"""
import json, os, sys, time, traceback
tree = sys.argv[1]
proto = os.fdopen(os.dup(1), "w")      # the protocol channel; anything the snippet prints goes to stderr
os.dup2(2, 1)
sys.stdout = sys.stderr
ns = {"__name__": "release_snippet"}
try:
    exec(compile(json.loads(sys.stdin.readline()), "<snippet>", "exec"), ns)
    import discrete
    if not os.path.realpath(discrete.__file__).startswith(os.path.realpath(tree)):
        raise RuntimeError(f"discrete imported from {discrete.__file__}, not from {tree}")
    print(json.dumps({"ready": True}), file=proto, flush=True)
except Exception:
    print(json.dumps({"error": traceback.format_exc()}), file=proto, flush=True)
    sys.exit(1)
for line in sys.stdin:
    cmd = line.strip()
    if cmd == "quit":
        break
    if cmd.startswith("call "):
        try:
            print(json.dumps({"value": ns[cmd[5:]]()}), file=proto, flush=True)
        except Exception:
            print(json.dumps({"error": traceback.format_exc()}), file=proto, flush=True)
        continue
    try:
        w0, c0 = time.perf_counter(), time.process_time()
        value = ns["run"]()
        wall, cpu = time.perf_counter() - w0, time.process_time() - c0
        print(json.dumps({"wall": wall, "cpu": cpu, "value": value}), file=proto, flush=True)
    except Exception:
        print(json.dumps({"error": traceback.format_exc()}), file=proto, flush=True)
"""


class Worker:
    """A subprocess running the package from the source tree ``tree`` (an earlier release from
    :func:`old_release`, or this checkout with other environment variables, e.g. ``DRIVEFEM_JIT=0``).
    ``setup`` (Python source executed once, with ``PYTHONPATH`` = the tree and the tree as working
    directory) must define ``run()`` returning a JSON-serialisable value; each call of the worker
    runs ``run()`` once and returns :class:`Measured` with the wall and CPU time taken inside the
    subprocess (import and setup excluded); :meth:`call` calls another function of the snippet
    untimed (e.g. the accuracy of the last run).  Use as a context manager (the subprocess ends on exit)."""

    def __init__(self, tree: Path, setup: str, env: dict | None = None, timeout: float = 900.0, label: str = ""):
        self.tree, self.timeout = Path(tree), timeout
        self.label = label or str(tree)
        self.proc = subprocess.Popen([sys.executable, "-c", _WORKER, str(self.tree)], cwd=self.tree,
                                     env=_release_env(self.tree, env), stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, text=True)
        self.proc.stdin.write(json.dumps(setup) + "\n")
        self.proc.stdin.flush()
        msg = self._reply()
        if not msg.get("ready"):
            self.close()
            raise RuntimeError(f"{self.label}: setup failed:\n{msg.get('error')}")

    def _reply(self) -> dict:
        import select

        ready, _, _ = select.select([self.proc.stdout], [], [], self.timeout)
        if not ready:
            self.proc.kill()
            raise RuntimeError(f"{self.label}: no answer within {self.timeout:g} s (worker killed)")
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f"{self.label}: worker ended (exit code {self.proc.poll()})")
        return json.loads(line)

    def __call__(self) -> Measured:
        self.proc.stdin.write("run\n")
        self.proc.stdin.flush()
        msg = self._reply()
        if "error" in msg:
            raise RuntimeError(f"{self.label}: run() failed:\n{msg['error']}")
        return Measured(msg["wall"], msg["cpu"], msg["value"])

    def call(self, name: str) -> Any:
        """Call the snippet's function ``name`` (untimed), e.g. to evaluate the accuracy of the last run."""
        self.proc.stdin.write(f"call {name}\n")
        self.proc.stdin.flush()
        msg = self._reply()
        if "error" in msg:
            raise RuntimeError(f"{self.label}: {name}() failed:\n{msg['error']}")
        return msg["value"]

    def close(self) -> None:
        if self.proc.poll() is None:
            try:
                self.proc.stdin.write("quit\n")
                self.proc.stdin.close()
                self.proc.wait(timeout=30)
            except (OSError, subprocess.TimeoutExpired):
                self.proc.kill()
                self.proc.wait()

    def __enter__(self) -> "Worker":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def release_worker(commit: str, setup: str, env: dict | None = None, timeout: float = 900.0) -> Worker:
    """A :class:`Worker` on the exported tree of ``commit`` (see :func:`old_release`)."""
    return Worker(old_release(commit), setup, env, timeout, label=f"release {commit}")


def run_in_release(commit: str, code: str, env: dict | None = None, timeout: float = 900.0) -> Any:
    """Run ``code`` once in a subprocess on the tree of ``commit``; the code prints one JSON value
    on its last line of output, which is returned."""
    tree = old_release(commit)
    p = subprocess.run([sys.executable, "-c", code], cwd=tree, env=_release_env(tree, env), capture_output=True,
                       text=True, timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError(f"release {commit}: exit code {p.returncode}:\n{p.stderr[-3000:]}")
    return json.loads(p.stdout.strip().splitlines()[-1])
