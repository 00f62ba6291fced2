"""Run one mutated model file through one ``drivefem`` command in a subprocess with a wall-clock limit.

Each run gets a fresh directory as its working directory (the model file is ``model.toml`` there,
outputs go to ``out/``), so nothing leaks into the checkout.  The child is the package's own
console-script entry point (read from ``pyproject.toml``) started by a small bootstrap that

* puts the source tree under test first on ``sys.path`` (so a snapshot can be fuzzed),
* limits address space, file size (a 1e9-element model must fail, not swap the machine) and CPU time
  (the run's limit: a loaded machine slows a run down, it does not make it a "hang"; a wall-clock
  ceiling of ``wall_factor`` x the limit catches a run that waits without computing), and
* registers ``faulthandler`` on SIGUSR1 and SIGXCPU, so a run over its limit dumps its stack before it
  is killed.

BLAS/OpenMP run single-threaded; the child is its own process group, killed whole at the end.
"""
from __future__ import annotations

import json
import math
import os
import shlex
import shutil
import signal
import subprocess
import sys
import threading
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .mutate import FILE_SUFFIX, Mutation, SECONDARY_OUTPUTS

MEMORY_LIMIT = 4 << 30      # bytes of address space per run
WALL_FACTOR = 5.0           # wall-clock ceiling of a run, in units of its CPU-time limit
FILE_SIZE_LIMIT = 1 << 30   # bytes per file written
TEXT_CAP = 1 << 20          # characters of stdout / stderr kept per run (head and tail beyond that)
JSON_CAP = 200 << 20        # bytes of a JSON file read back (larger ones are reported, not parsed)

_BOOT = """\
import faulthandler, os, resource, signal, sys
faulthandler.register(signal.SIGUSR1, all_threads=True)
faulthandler.register(signal.SIGXCPU, all_threads=True)
for lim, env in ((resource.RLIMIT_AS, "DRIVEFEM_FUZZ_MEMORY"), (resource.RLIMIT_FSIZE, "DRIVEFEM_FUZZ_FSIZE")):
    v = int(os.environ.get(env, "0"))
    if v:
        resource.setrlimit(lim, (v, v))
cpu = int(os.environ.get("DRIVEFEM_FUZZ_CPU", "0"))
if cpu:
    resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 1))
resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
sys.path.insert(0, os.environ["DRIVEFEM_FUZZ_ROOT"])
sys.argv[0] = "drivefem"
from {module} import {func} as _main
sys.exit(_main())
"""


def entry_point(root: Path) -> tuple[str, str]:
    """(module, function) of the ``drivefem`` console script declared in ``root/pyproject.toml``."""
    with open(Path(root) / "pyproject.toml", "rb") as fh:
        spec = tomllib.load(fh)["project"]["scripts"]["drivefem"]
    module, func = spec.split(":")
    return module.strip(), func.strip()


@dataclass(frozen=True)
class Job:
    """One run: a mutation through one command; ``extra_outputs`` adds the command's CSV/plot options."""

    mutation: Mutation
    command: str
    wrong_kind: bool = False
    extra_outputs: bool = False


@dataclass
class RunResult:
    """What a run did: exit code (None if it was killed at its limit), output tails, JSON files written."""

    job: Job
    argv: list[str]
    setup: list[str]
    returncode: int | None
    timed_out: bool
    duration_s: float
    stdout: str
    stderr: str
    traceback_seen: bool
    json_files: dict[str, bytes | None] = field(default_factory=dict)  # run-dir path -> bytes (None: too large)


class Runner:
    """Runs jobs for one source tree ``root`` with ``python`` and a per-run ``limit_s``."""

    def __init__(self, root: Path, work: Path, limit_s: float = 60.0, python: str = sys.executable,
                 memory_limit: int = MEMORY_LIMIT, fork: bool = True, wall_factor: float = WALL_FACTOR):
        self.root = Path(root).resolve()
        self.work = Path(work)
        self.work.mkdir(parents=True, exist_ok=True)
        self.limit_s = limit_s                     # CPU seconds of one run
        self.wall_s = limit_s * wall_factor        # wall-clock ceiling of one run
        self.python = python
        self.module, self.func = entry_point(self.root)
        self.boot = _BOOT.format(module=self.module, func=self.func)
        self.env = dict(os.environ, DRIVEFEM_FUZZ_ROOT=str(self.root), DRIVEFEM_FUZZ_MEMORY=str(memory_limit),
                        DRIVEFEM_FUZZ_FSIZE=str(FILE_SIZE_LIMIT), OPENBLAS_NUM_THREADS="1",
                        OMP_NUM_THREADS="1", MKL_NUM_THREADS="1", MPLBACKEND="Agg",
                        PYVISTA_OFF_SCREEN="true", VTK_DEFAULT_OPENGL_WINDOW="vtkOSOpenGLRenderWindow",
                        PYTHONFAULTHANDLER="1", PYTHONDONTWRITEBYTECODE="1", PYTHONIOENCODING="utf-8",
                        DRIVEFEM_FUZZ_CPU=str(int(math.ceil(limit_s))))
        self.env.pop("PYTHONPATH", None)
        self._chattr = shutil.which("chattr") if os.geteuid() == 0 else None
        self._active: set[subprocess.Popen] = set()
        self._lock = threading.Lock()
        self.stopped = False
        self.fork = fork
        self._local = threading.local()           # one fork server per worker thread
        self._servers: list[subprocess.Popen] = []

    def kill_all(self) -> None:
        """Stop: kill the process group of every run in progress; no new run starts."""
        with self._lock:
            self.stopped = True
            for proc in list(self._active):
                _kill_group(proc, reap=False)
            for srv in self._servers:
                _signal(srv.pid, signal.SIGTERM)      # it kills its current child's session

    def close(self) -> None:
        """Stop the fork servers."""
        for srv in self._servers:
            try:
                srv.stdin.close()
                srv.wait(timeout=5)
            except Exception:
                _kill_group(srv)
        self._servers = []

    def _server(self) -> subprocess.Popen:
        """This thread's fork server (started on first use, restarted if it died)."""
        srv = getattr(self._local, "server", None)
        if srv is None or srv.poll() is not None:
            srv = subprocess.Popen([self.python, "-P", str(Path(__file__).with_name("zygote.py")), self.module,
                                    self.func], env=self.env, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                   stderr=subprocess.DEVNULL, text=True, bufsize=1, start_new_session=True)
            if json.loads(srv.stdout.readline() or "{}").get("ready") is not True:
                raise RuntimeError("the fuzzer's fork server did not start")
            self._local.server = srv
            with self._lock:
                self._servers.append(srv)
        return srv

    def _run_forked(self, run_dir: Path, argv: list[str]) -> tuple[int | None, bool]:
        """(exit code, timed out) of one run forked from this thread's fork server."""
        srv = self._server()
        srv.stdin.write(json.dumps({"dir": str(run_dir), "argv": argv, "limit": self.limit_s,
                                    "wall": self.wall_s}) + "\n")
        line = srv.stdout.readline()
        if not line:                       # the server died (killed by a Ctrl-C of the fuzzer)
            if self.stopped:
                raise KeyboardInterrupt
            raise RuntimeError("the fuzzer's fork server died")
        out = json.loads(line)
        return out["rc"], out["timed_out"]

    # ------------------------------------------------------------------ building a run
    def command_line(self, job: Job) -> tuple[list[str], list[str], list[tuple]]:
        """(argv after ``drivefem``, shell setup lines, file-system actions) of a job, relative to its run dir."""
        m, cmd = job.mutation, job.command
        setup: list[str] = ["mkdir -p out"]
        actions: list[tuple] = [("mkdir", "out")]
        art = {"directory": ("mkdir", "mkdir model.toml"), "fifo": ("mkfifo", "mkfifo model.toml"),
               "dangling_symlink": ("symlink", "ln -s nowhere/model.toml model.toml")}
        if m.artifact in art:
            actions.append((art[m.artifact][0], "model.toml"))
            setup.append(art[m.artifact][1])
        outputs = {"--json": "out/result.json"}
        if cmd == "render":       # no --json: its JSON (modes.json) goes into --render
            outputs = {"--render": "out/render"}
        if cmd == "sweep":
            outputs["--out"] = "out/sweep"
        secondary = dict(SECONDARY_OUTPUTS.get(cmd, ()))

        def extra_path(option):
            return f"out/extra{option.replace('-', '_')}" + ("" if secondary.get(option) == "dir"
                                                                 else FILE_SUFFIX.get(option, ""))

        if job.extra_outputs:
            for option in secondary:
                outputs.setdefault(option, extra_path(option))
        if m.output:
            option, kind = m.output
            is_dir = secondary.get(option) == "dir"
            ext = "" if is_dir else FILE_SUFFIX.get(option, "")
            if kind == "under_file":
                actions.append(("file", "out/blocker"))
                setup.append("touch out/blocker")
                outputs[option] = "out/blocker/target" + ext
            elif kind == "occupied":
                if is_dir:
                    actions.append(("file", "out/occupied"))
                    setup.append("touch out/occupied")
                else:
                    actions.append(("mkdir", "out/occupied"))
                    setup.append("mkdir out/occupied")
                outputs[option] = "out/occupied"
            elif kind == "readonly_dir":
                actions.append(("readonly", "out/readonly"))
                setup.append("mkdir out/readonly && chmod 555 out/readonly"
                             + (" && chattr +i out/readonly" if self._chattr else ""))
                outputs[option] = "out/readonly/target" + ext
            elif kind == "dev_full":
                outputs[option] = "/dev/full"
            elif kind == "empty":
                outputs[option] = ""
            elif kind == "long_name":
                outputs[option] = "out/" + "n" * 300 + ext
            elif kind == "bad_suffix":
                outputs[option] = "out/result.xyz"
            elif kind == "same_path":
                partner = next((o for o in outputs if o != option), None)
                if partner is None:          # a second output is added to share the path with
                    partner = next((o for o in (["--json"] if cmd != "render" else []) + list(secondary)
                                    if o != option), None)
                    if partner is not None:
                        outputs[partner] = extra_path(partner)
                outputs[option] = outputs[partner] if partner is not None else outputs.get(option, "out/x")
        argv = [cmd, "model.toml"]
        for option, path in outputs.items():
            argv += [option, path]
        if cmd == "sweep":
            argv += ["--workers", "0"]
        if cmd == "render":
            argv += ["--mode", "1"]
        argv += list(m.options)          # after the run's own options: an attacked option wins
        return argv, setup, actions

    def _prepare(self, run_dir: Path, job: Job, actions: list[tuple]) -> None:
        m = job.mutation
        if m.artifact == "file":
            (run_dir / "model.toml").write_bytes(m.content)
        for what, rel in actions:
            p = run_dir / rel
            if what == "mkdir":
                p.mkdir(parents=True, exist_ok=True)
            elif what == "file":
                p.write_bytes(b"")
            elif what == "mkfifo":
                os.mkfifo(p)
            elif what == "symlink":
                os.symlink("nowhere/model.toml", p)
            elif what == "readonly":
                p.mkdir()
                p.chmod(0o555)
                if self._chattr:
                    subprocess.run([self._chattr, "+i", str(p)], check=False, capture_output=True)

    def _cleanup(self, run_dir: Path) -> None:
        ro = run_dir / "out" / "readonly"
        if ro.exists() and self._chattr:
            subprocess.run([self._chattr, "-i", str(ro)], check=False, capture_output=True)
        if ro.exists():
            ro.chmod(0o755)
        shutil.rmtree(run_dir, ignore_errors=True)

    # ------------------------------------------------------------------ running
    def run(self, job: Job, index: int) -> RunResult:
        run_dir = self.work / f"run{index:06d}"
        shutil.rmtree(run_dir, ignore_errors=True)
        run_dir.mkdir(parents=True)
        argv, setup, actions = self.command_line(job)
        try:
            self._prepare(run_dir, job, actions)
            out_f, err_f = run_dir / ".stdout", run_dir / ".stderr"
            t0 = time.monotonic()
            if self.fork:
                if self.stopped:
                    raise KeyboardInterrupt
                rc, timed_out = self._run_forked(run_dir, argv)
                if rc in (-signal.SIGKILL, -signal.SIGXCPU) and _dumped(err_f):
                    rc, timed_out = None, True      # killed at its CPU-time limit after the SIGXCPU stack dump
                return self._collect(job, argv, setup, run_dir, rc, timed_out, time.monotonic() - t0)
            with open(out_f, "wb") as fo, open(err_f, "wb") as fe:
                with self._lock:
                    if self.stopped:
                        raise KeyboardInterrupt
                    proc = subprocess.Popen([self.python, "-P", "-c", self.boot, *argv], cwd=run_dir, env=self.env,
                                            stdin=subprocess.DEVNULL, stdout=fo, stderr=fe, start_new_session=True)
                    self._active.add(proc)
                timed_out = False
                try:
                    rc = proc.wait(timeout=self.wall_s)
                    if rc in (-signal.SIGKILL, -signal.SIGXCPU) and _dumped(err_f):
                        timed_out, rc = True, None       # out of CPU time (RLIMIT_CPU; SIGXCPU dumped the stack)
                except subprocess.TimeoutExpired:
                    timed_out = True
                    _signal(proc.pid, signal.SIGUSR1)      # faulthandler: where is it stuck?
                    try:
                        proc.wait(timeout=1.0)                # time to write the dump
                    except subprocess.TimeoutExpired:
                        pass
                    rc = None
                finally:
                    _kill_group(proc)
                    with self._lock:
                        self._active.discard(proc)
            return self._collect(job, argv, setup, run_dir, rc, timed_out, time.monotonic() - t0)
        finally:
            self._cleanup(run_dir)

    def _collect(self, job, argv, setup, run_dir: Path, rc, timed_out: bool, duration: float) -> RunResult:
        out_f, err_f = run_dir / ".stdout", run_dir / ".stderr"
        raw_out = out_f.read_bytes() if out_f.is_file() else b""
        raw_err = err_f.read_bytes() if err_f.is_file() else b""
        traceback_seen = b"Traceback" in raw_out or b"Traceback" in raw_err
        stdout, stderr = _tail(raw_out), _tail(raw_err)
        jsons = {}
        for p in sorted(run_dir.rglob("*.json")):
            if p.is_file() and not p.is_symlink():
                jsons[str(p.relative_to(run_dir))] = p.read_bytes() if p.stat().st_size <= JSON_CAP else None
        return RunResult(job, argv, setup, None if timed_out else rc, timed_out, duration, stdout, stderr,
                         traceback_seen, jsons)

    def repro(self, job: Job, saved_model: Path | None) -> str:
        """A shell line that reproduces a run (the model file saved at ``saved_model``)."""
        argv, setup, _ = self.command_line(job)
        model = shlex.quote(str(saved_model)) if saved_model else "model.toml"
        setup = [s for s in setup if "model.toml" not in s] if saved_model else setup
        argv = [model if a == "model.toml" else shlex.quote(a) for a in argv]
        line = (f"cd \"$(mktemp -d)\" && {' && '.join(setup)} && "
                f"PYTHONPATH={shlex.quote(str(self.root))} {shlex.quote(self.python)} -c "
                f"'import sys; from {self.module} import {self.func}; sys.argv[0] = \"drivefem\"; "
                f"sys.exit({self.func}())' {' '.join(argv)}")
        if "chattr +i" in line:
            line += "; chattr -i out/readonly"
        return line


def _dumped(err_f: Path) -> bool:
    """Whether the run's stderr holds a faulthandler stack dump (written at SIGXCPU or SIGUSR1)."""
    try:
        return b"(most recent call first)" in err_f.read_bytes()
    except OSError:
        return False


def _tail(data: bytes) -> str:
    text = data.decode("utf-8", errors="replace")
    return text if len(text) <= TEXT_CAP else text[:TEXT_CAP // 4] + "\n[...]\n" + text[-3 * TEXT_CAP // 4:]


def _signal(pid: int, sig) -> None:
    try:
        os.kill(pid, sig)
    except ProcessLookupError:
        pass


def _kill_group(proc: subprocess.Popen, reap: bool = True) -> None:
    """Kill the run's process group (the child and anything it started), then reap the child."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    if not reap:
        return
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        pass
