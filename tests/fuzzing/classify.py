"""Classify a run's outcome and name its root cause.

Classes, in order of precedence (a run gets the first that applies; every finding is also a flag):

``HANG``        the run was still going at its limit: its CPU time, or the wall-clock ceiling for a run that
                waits without computing (killed; its stack is in the dump)
``TRACEBACK``   "Traceback" in stdout or stderr
``BADEXIT``     an exit code outside the documented set {0, 1, 2, 3, 4, 5} -- among them 70, drivefem's own
                "internal error" (a bug, as a traceback is) -- or death by a signal
``NONFINITE``   a JSON file written holds NaN, Infinity or a number that overflows to inf
``BADJSON``     a JSON file written does not parse (truncated, not UTF-8, ...)
``BADMESSAGE``  exit 2 without a ``drivefem: error:`` line, or one that names no key (neither a word
                the mutation is about nor the ``key = value is not valid`` form of ``ModelError``)
``OK``          none of the above

The four properties of issue 11 item 6 are: no HANG, no TRACEBACK, no BADEXIT, no NONFINITE
(:data:`PROPERTY_CLASSES`); BADJSON and BADMESSAGE are reported beside them.
"""
from __future__ import annotations

import json
import math
import re
from dataclasses import asdict, dataclass, field
from pathlib import Path

from .execute import RunResult

DOCUMENTED_EXITS = frozenset({0, 1, 2, 3, 4, 5})
CLASSES = ("OK", "HANG", "TRACEBACK", "BADEXIT", "NONFINITE", "BADJSON", "BADMESSAGE")
PROPERTY_CLASSES = ("HANG", "TRACEBACK", "BADEXIT", "NONFINITE")
ERROR_PREFIX = "drivefem: error:"

_FRAME = re.compile(r'^\s*File "([^"]+)", line (\d+),? in (\S+)', re.M)
_MODEL_ERROR_SHAPE = re.compile(r"\S = .*(?:is not valid|allowed)")
_NONFINITE_TEXT = re.compile(r"(?<![\w.])[-+]?(?:nan|inf|infinity)(?![\w])", re.I)


@dataclass
class Outcome:
    """The classified result of one run (compact: what a report and a reproducer need)."""

    id: str
    example: str
    category: str
    target: str
    description: str
    command: str
    wrong_kind: bool
    argv: list[str]
    cls: str
    flags: list[str]
    returncode: int | None
    duration_s: float
    root_cause: str
    detail: str
    error_message: str = ""
    nonfinite_paths: list[str] = field(default_factory=list)
    stdout_tail: str = ""
    stderr_tail: str = ""
    repro: str = ""
    saved_model: str = ""

    @property
    def failed(self) -> bool:
        return self.cls != "OK"

    def to_dict(self) -> dict:
        return asdict(self)


# ------------------------------------------------------------------------------------ JSON
class _NonFinite(ValueError):
    pass


def _reject_constant(name):
    raise _NonFinite(name)


def _finite_float(s: str) -> float:
    v = float(s)
    if not math.isfinite(v):
        raise _NonFinite(s)
    return v


def nonfinite_paths(obj, path: str = "", out: list | None = None, limit: int = 20) -> list[str]:
    """JSON paths (``residuals[3]``, ``a.b``) of the non-finite floats in ``obj``."""
    out = [] if out is None else out
    if len(out) >= limit:
        return out
    if isinstance(obj, float) and not math.isfinite(obj):
        out.append(f"{path or '<root>'} = {obj}")
    elif isinstance(obj, dict):
        for k, v in obj.items():
            nonfinite_paths(v, f"{path}.{k}" if path else str(k), out, limit)
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            nonfinite_paths(v, f"{path}[{i}]", out, limit)
    return out


def check_json(data: bytes | None) -> tuple[str, list[str]]:
    """``("ok" | "nonfinite" | "invalid" | "too_large", details)`` of a JSON file's bytes.

    Python's ``json`` writes ``NaN``/``Infinity`` and reads ``1e400`` as inf, so the strict parse
    rejects both through its constant and float hooks."""
    if data is None:
        return "too_large", ["larger than the read-back cap"]
    try:
        text = data.decode("utf-8")
        json.loads(text, parse_constant=_reject_constant, parse_float=_finite_float)
        return "ok", []
    except _NonFinite as exc:
        try:
            return "nonfinite", nonfinite_paths(json.loads(text)) or [str(exc)]
        except ValueError:
            return "nonfinite", [str(exc)]
    except (UnicodeDecodeError, ValueError) as exc:
        return "invalid", [f"{type(exc).__name__}: {str(exc)[:200]}"]


# ------------------------------------------------------------------------------ tracebacks
def _frames(text: str) -> list[tuple[str, int, str]]:
    return [(f, int(n), fn) for f, n, fn in _FRAME.findall(text)]


def _is_project(path: str, root: Path) -> bool:
    return path.startswith(str(root) + "/") and "/site-packages/" not in path and "/.venv/" not in path


def _rel(path: str, root: Path) -> str:
    return path[len(str(root)) + 1:] if path.startswith(str(root) + "/") else path.rsplit("/site-packages/", 1)[-1]


def last_traceback(text: str) -> tuple[list[tuple[str, int, str]], str]:
    """Frames (outermost first) and the exception line of the last traceback printed in ``text``."""
    i = text.rfind("Traceback (most recent call last):")
    if i < 0:
        return [], ""
    block = text[i:]
    frames = _frames(block)
    exc = ""
    for line in block.splitlines()[1:]:
        if line and not line.startswith((" ", "\t")) and not line.startswith("Traceback"):
            exc = line.strip()
            break
    return frames, exc


def stack_dump(text: str) -> list[tuple[str, int, str]]:
    """Frames (innermost first) of the main thread in a faulthandler dump."""
    for marker in ("Current thread", "Stack (most recent call first)", "Thread "):
        i = text.rfind(marker)
        if i >= 0:
            block = text[i:].split("\n\n")[0]
            return [(f, int(n), fn) for f, n, fn in
                    re.findall(r'^\s*File "([^"]+)", line (\d+) in (\S+)', block, re.M)]
    return []


def _where(frames: list, root: Path, innermost_first: bool) -> tuple[str, str]:
    """(innermost project frame ``path:function``, innermost frame overall if it is elsewhere, else '')."""
    seq = frames if innermost_first else list(reversed(frames))
    proj = next((f for f in seq if _is_project(f[0], root)), None)
    inner = seq[0] if seq else None
    if proj is None:
        return (f"{_rel(inner[0], root)}:{inner[2]}" if inner else "unknown place"), ""
    lib = f"{_rel(inner[0], root)}:{inner[2]}" if inner and inner is not proj else ""
    return f"{_rel(proj[0], root)}:{proj[2]}", lib


# ------------------------------------------------------------------------------- messages
def error_message(stderr: str) -> str:
    """The ``drivefem: error:`` message (from its line to the end, at most 600 characters), or ''."""
    lines = stderr.splitlines()
    for i, ln in enumerate(lines):
        if ln.startswith(ERROR_PREFIX):
            return "\n".join(lines[i:])[:600]
    return ""


def names_one_of(message: str, names: tuple[str, ...]) -> bool:
    """Whether ``message`` contains one of ``names`` as a word (case-insensitive beyond two letters)."""
    if not names:
        return True
    for tok in names:
        flags = re.I if len(tok) > 2 else 0
        if re.search(rf"(?<![A-Za-z0-9_]){re.escape(tok)}(?![A-Za-z0-9_])", message, flags):
            return True
    return False


def _normalise(line: str) -> str:
    line = re.sub(r"'[^']*'|\"[^\"]*\"", "'…'", line)
    line = re.sub(r"[-+]?\d[\d.e+-]*", "N", line)
    return line[:110]


def badmessage_cause(command: str, msg: str, stderr: str) -> tuple[str, str]:
    """(root cause, first message line) of an exit-2 run whose message is not a clear error."""
    if msg:
        first = msg.splitlines()[0]
        return f"{command}: the error names no key: {_normalise(first)[:70]}", first
    first = next((ln for ln in stderr.splitlines() if ln.strip()), "(nothing on stderr)")
    prefix = re.match(r"\s*([A-Za-z ]{0,30}:)", first)
    shown = prefix.group(1) if prefix else _normalise(first)[:30]
    return f"{command}: exit 2 without the '{ERROR_PREFIX}' prefix (prints '{shown}')", first


# --------------------------------------------------------------------------------- classify
def classify(res: RunResult, root: Path) -> Outcome:
    """The :class:`Outcome` of a run of the source tree ``root``."""
    m, job = res.job.mutation, res.job
    flags: list[str] = []
    nonfinite, detail, cause = [], "", ""
    both = res.stdout + "\n" + res.stderr
    if res.timed_out:
        flags.append("HANG")
    if res.traceback_seen:
        flags.append("TRACEBACK")
    rc = res.returncode
    if rc is not None and rc not in DOCUMENTED_EXITS:
        flags.append("BADEXIT")
    json_problems = []
    for name, data in res.json_files.items():
        status, info = check_json(data)
        if status == "nonfinite":
            flags.append("NONFINITE")
            nonfinite += [f"{name}: {p}" for p in info]
        elif status != "ok":
            flags.append("BADJSON")
            json_problems.append(f"{name}: {status}: {'; '.join(info)}")
    msg = error_message(res.stderr) if rc == 2 else ""
    if rc == 2 and not res.timed_out:
        if not msg:
            flags.append("BADMESSAGE")
            detail = "exit 2 without a 'drivefem: error:' line"
        elif not (names_one_of(msg, m.names) or _MODEL_ERROR_SHAPE.search(msg)):
            flags.append("BADMESSAGE")
            detail = f"the message names no key (none of {list(m.names)}, no 'key = value is not valid')"
        elif not names_one_of(msg, m.names) and not job.wrong_kind and m.category != "control":
            flags.append("other_key_named")
    if "MemoryError" in res.stderr:
        flags.append("memory_error")
    if rc == 0 and _NONFINITE_TEXT.search(res.stdout):
        flags.append("nonfinite_printed")
    flags = list(dict.fromkeys(flags))
    cls = next((c for c in ("HANG", "TRACEBACK", "BADEXIT", "NONFINITE", "BADJSON", "BADMESSAGE") if c in flags), "OK")

    if cls == "HANG":
        where, lib = _where(stack_dump(res.stderr), root, innermost_first=True)
        cause = f"hang in {where}"
        detail = f"still running after {res.duration_s:.0f} s (wall clock)" + (f"; innermost frame {lib}" if lib else "")
    elif cls == "TRACEBACK":
        frames, exc = last_traceback(both)
        etype = exc.split(":")[0].rsplit(".", 1)[-1] if exc else "Traceback"
        where, lib = _where(frames, root, innermost_first=False)
        cause = f"{etype} in {where}"
        detail = exc[:300] + (f" (raised in {lib})" if lib else "")
    elif cls == "BADEXIT":
        if rc is not None and rc < 0:
            import signal as _s
            try:
                name = _s.Signals(-rc).name
            except ValueError:
                name = str(-rc)
            cause = f"killed by {name}"
        else:
            cause = f"exit code {rc}" + (" (internal error)" if rc == 70 else "")
        frames = stack_dump(res.stderr)
        if frames:
            cause += f" in {_where(frames, root, innermost_first=True)[0]}"
        detail = res.stderr.strip().splitlines()[-1][:300] if res.stderr.strip() else ""
    elif cls == "NONFINITE":
        first = nonfinite[0].split(" = ")[0]
        pattern = re.sub(r"\[\d+\]", "[]", first.split(": ", 1)[-1])
        cause = f"{job.command}: non-finite {pattern}"
        detail = "; ".join(nonfinite[:5])
    elif cls == "BADJSON":
        cause = f"{job.command}: JSON {json_problems[0].split(': ', 2)[1]}"
        detail = "; ".join(json_problems)[:300]
    elif cls == "BADMESSAGE":
        cause, first = badmessage_cause(job.command, msg, res.stderr)
        detail = f"{detail}: {first[:200]}"
    return Outcome(id=m.id, example=m.example, category=m.category, target=m.target, description=m.description,
                   command=job.command, wrong_kind=job.wrong_kind, argv=res.argv, cls=cls, flags=flags,
                   returncode=rc, duration_s=round(res.duration_s, 3), root_cause=cause, detail=detail,
                   error_message=msg[:300], nonfinite_paths=nonfinite[:10],
                   stdout_tail=res.stdout[-1500:] if cls != "OK" else "",
                   stderr_tail=res.stderr[-3000:] if cls != "OK" else "")
