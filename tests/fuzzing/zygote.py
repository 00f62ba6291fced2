"""A fork server for the fuzzer: imports the package once, then forks one child per run.

Started by :class:`tests.fuzzing.execute.Runner` as ``python -P zygote.py MODULE FUNC`` with the
source tree under test in ``DRIVEFEM_FUZZ_ROOT``.  It reads one JSON request per line on stdin,
``{"dir": run directory, "argv": [...], "limit": seconds, "wall": seconds}``, forks, and answers one JSON
line ``{"rc": exit code or None, "timed_out": bool}``.  ``limit`` is CPU time (``RLIMIT_CPU``: at the limit
SIGXCPU dumps the stack, two seconds later the kernel kills the run), so that a loaded machine does not turn
slow runs into "hangs"; ``wall`` (default 5 x limit) catches a run that waits without computing.  The child is what a fresh ``drivefem`` process
would be after its imports: its own session (killed whole at the end), cwd = the run directory,
stdout/stderr into ``.stdout``/``.stderr`` there, the address-space and file-size limits, a
faulthandler dump on SIGUSR1, and an uncaught exception printed as a traceback with exit code 1
(as the interpreter does).  The imports themselves are the only thing the runs share: a fresh
interpreter per run cost ~1-3 s of imports, ~90 % of a typical run that rejects a bad file.
"""
from __future__ import annotations

import faulthandler
import importlib
import json
import math
import os
import resource
import signal
import sys
import time
import traceback

#: Imported before forking when importable (the package imports the rest lazily, per command).
PRELOAD = ("numpy", "scipy.sparse", "scipy.sparse.linalg", "scipy.linalg", "scipy.integrate", "scipy.optimize",
           "pydantic", "tomllib", "skfem", "meshio", "matplotlib", "matplotlib.pyplot",
           "fem.study", "fem.modelfile", "fem.app.commands", "discrete.nonsmooth.solver",
           "discrete.nonsmooth.kernel", "discrete.steady.afc", "discrete.timestepping")


def _limits(cpu: float | None = None) -> None:
    for lim, env in ((resource.RLIMIT_AS, "DRIVEFEM_FUZZ_MEMORY"), (resource.RLIMIT_FSIZE, "DRIVEFEM_FUZZ_FSIZE")):
        v = int(os.environ.get(env, "0"))
        if v:
            resource.setrlimit(lim, (v, v))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    if cpu:
        soft = max(1, int(math.ceil(cpu)))
        resource.setrlimit(resource.RLIMIT_CPU, (soft, soft + CPU_GRACE))


CPU_GRACE = 1          # seconds of CPU between the stack dump (SIGXCPU) and the kernel's kill


def _child(run_dir: str, argv: list, module: str, func: str, cpu: float | None = None) -> None:
    """In the forked child: become a fresh ``drivefem`` run; never returns."""
    code = 1
    try:
        os.setsid()
        os.chdir(run_dir)
        fin = os.open(os.devnull, os.O_RDONLY)
        fout = os.open(".stdout", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        ferr = os.open(".stderr", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(fin, 0)
        os.dup2(fout, 1)
        os.dup2(ferr, 2)
        for fd in (fin, fout, ferr):
            os.close(fd)
        signal.signal(signal.SIGINT, signal.default_int_handler)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        faulthandler.register(signal.SIGUSR1, all_threads=True)
        faulthandler.register(signal.SIGXCPU, all_threads=True)        # out of CPU time: where was it?
        _limits(cpu)
        sys.argv = ["drivefem", *argv]
        try:
            rc = getattr(importlib.import_module(module), func)()
            code = rc if isinstance(rc, int) else (0 if rc is None else 1)
        except SystemExit as exc:
            c = exc.code
            code = c if isinstance(c, int) else (0 if c is None else 1)
            if not isinstance(c, int) and c is not None:
                print(c, file=sys.stderr)
        except BaseException:
            traceback.print_exc()
            code = 1
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        except BaseException:
            pass
        os._exit(code & 0xFF)


def _wait(pid: int, limit: float, cpu: float | None = None) -> tuple[int | None, bool]:
    """Wait for the child up to ``limit`` s of wall time; on time-out dump its stack (SIGUSR1) and kill its
    session.  With ``cpu``: a child killed after using that much CPU time (RLIMIT_CPU) timed out too."""
    t_end = time.monotonic() + limit
    delay = 0.001
    while True:
        done, status, usage = os.wait4(pid, os.WNOHANG)
        if done:
            _killpg(pid)
            rc = os.waitstatus_to_exitcode(status)
            used = usage.ru_utime + usage.ru_stime
            if cpu and rc in (-signal.SIGKILL, -signal.SIGXCPU) and used >= math.ceil(cpu) - 0.05:
                return None, True
            return rc, False
        if time.monotonic() > t_end:
            break
        time.sleep(delay)
        delay = min(2 * delay, 0.02)
    _kill(pid, signal.SIGUSR1)
    t_dump = time.monotonic() + 1.0
    while time.monotonic() < t_dump and not os.waitpid(pid, os.WNOHANG)[0]:
        time.sleep(0.02)
    _killpg(pid)
    try:
        os.waitpid(pid, 0)
    except ChildProcessError:
        pass
    return None, True


def _kill(pid: int, sig) -> None:
    try:
        os.kill(pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def _killpg(pid: int) -> None:
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def main() -> None:
    module, func = sys.argv[1], sys.argv[2]
    sys.path.insert(0, os.environ["DRIVEFEM_FUZZ_ROOT"])
    reply = os.fdopen(os.dup(1), "w", buffering=1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)                     # nothing the preloads print reaches the reply channel
    for name in PRELOAD:
        try:
            importlib.import_module(name)
        except BaseException:               # the child imports it again and reports what goes wrong
            pass
    try:
        importlib.import_module(module)
    except BaseException:                   # the child's import prints the traceback
        pass
    current = {"pid": None}

    def stop(signum, frame):
        if current["pid"]:
            _killpg(current["pid"])
        os._exit(0)

    signal.signal(signal.SIGTERM, stop)
    reply.write(json.dumps({"ready": True}) + "\n")
    for line in sys.stdin:
        req = json.loads(line)
        sys.stderr.flush()
        cpu = float(req["limit"])
        wall = float(req.get("wall") or 5 * cpu)
        pid = os.fork()
        if pid == 0:
            _child(req["dir"], req["argv"], module, func, cpu)
        current["pid"] = pid
        rc, timed_out = _wait(pid, wall, cpu)
        current["pid"] = None
        reply.write(json.dumps({"rc": rc, "timed_out": timed_out}) + "\n")


if __name__ == "__main__":
    main()
