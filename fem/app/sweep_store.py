"""The on-disk store of ``drivefem sweep``: what a directory of sweep points may be trusted for.

Layout of OUT: ``sweep.json`` (the manifest: model file, analysis, the points, and the sweep's fingerprint)
and ``points/NNNNNN.json`` (one finished point each), ``points/NNNNNN.claim`` while a run computes it.

* **Fingerprints.**  The sweep's fingerprint is the sha256 of the canonical JSON of the model (without its
  ``[sweep]`` table), the analysis, the periods and every point's values; a point's key is the sha256 of
  the model, analysis, periods and *its own* values.  A point file is trusted only if it parses, is a
  complete record (index, status, values, key; for "ok" a result) and its key is the one this sweep
  expects at its index -- so a point left by another grid or another model is never returned for this
  one, whether or not the manifest is still there.  Every point that is not trusted is recomputed, and
  why is reported (stale: another model/grid; incomplete: fields missing; unreadable: not JSON).
* **The manifest** of an existing directory must have this sweep's fingerprint: another sweep's directory is
  refused (exit 2, the directory named) -- reusing it would silently mix two studies' files; a manifest
  that does not parse is rewritten (its points are still checked one by one).
* **Claims.**  A point is computed only by the run that created its claim file (``os.open(O_CREAT |
  O_EXCL)``: atomic on local and NFSv3+ file systems); the claim records the host, pid and time.  A claim
  whose process is gone (same host, pid not alive) is stale and taken over; a run that finds points
  claimed by a live run waits for their files, so two concurrent resumes split the work and both end with
  the full set.  Temporary files carry the pid (``NNNNNN.PID.tmp``) and are renamed atomically.
"""
from __future__ import annotations

import hashlib
import json
import os
import socket
import time
from pathlib import Path

from discrete.errors import ModelError

from ..output.paths import try_writing

HOST = socket.gethostname()
REASONS = {"stale": "written for another model or grid", "incomplete": "fields missing", "unreadable": "not JSON"}
"""Why a point file present in the store is not trusted (:meth:`SweepStore.read`)."""


def _canonical(obj) -> str:
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), default=str)


def _sha(obj) -> str:
    return hashlib.sha256(_canonical(obj).encode()).hexdigest()


class SweepStore:
    """The point files of one sweep in ``out`` (see the module docstring)."""

    def __init__(self, out, model: dict, analysis: str, periods, points: list[dict], model_file: str = ""):
        self.out = Path(out)
        self.dir = self.out / "points"
        self.points = [json.loads(_canonical(p)) for p in points]
        base = {"model": model, "analysis": analysis, "periods": periods}
        self.keys = [_sha({**base, "values": p}) for p in self.points]
        self.fingerprint = _sha({**base, "points": self.points})
        self.meta = {"model": model_file, "analysis": analysis, "n_points": len(points), "points": self.points,
                     "fingerprint": self.fingerprint}
        self.pid = os.getpid()
        self.mine: set[int] = set()
        self.computed = 0                    # points this run computed and stored
        self.started = time.time()

    # ------------------------------------------------------------ set-up
    def open(self, option: str) -> str | None:
        """Create or check the directory and its manifest before any work; returns a note to print."""
        try_writing(self.dir, option, self.out, "a writable directory")
        mp = self.out / "sweep.json"
        note = None
        if mp.exists():
            try:
                old = json.loads(mp.read_text())
                if not isinstance(old, dict):
                    raise ValueError("not a JSON object")
            except (OSError, ValueError) as exc:
                note = f"sweep.json in {self.out} unreadable ({type(exc).__name__}): rewritten; points checked one by one"
                old = None
            if old is not None and old.get("fingerprint") != self.fingerprint:
                what = ("another model, analysis or grid" if old.get("fingerprint")
                        else "a sweep written without a fingerprint, or another one")
                raise ModelError("command line", option, str(self.out), f"a new directory or the directory of this "
                                 f"same sweep: this one holds {what} (its points would be mixed with this sweep's)")
            if old is not None:
                return None
        self._atomic(mp, self.meta)
        return note

    # ------------------------------------------------------------ points
    def path(self, i: int) -> Path:
        return self.dir / f"{i:06d}.json"

    def _atomic(self, path: Path, data) -> None:
        tmp = self._tmp_path(path)
        with open(tmp, "w") as fh:
            json.dump(data, fh, indent=1, sort_keys=True)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)

    def _tmp_path(self, path: Path) -> Path:
        return path.with_name(f"{path.stem}.{self.pid}.tmp")

    def read(self, i: int) -> tuple[dict | None, str | None]:
        """(record, None) for a trusted point file, else (None, reason): missing | unreadable | incomplete |
        stale."""
        p = self.path(i)
        if not p.exists():
            return None, "missing"
        try:
            rec = json.loads(p.read_text())
        except (OSError, ValueError):
            return None, "unreadable"
        if not isinstance(rec, dict) or rec.get("status") not in ("ok", "error") or rec.get("index") != i \
                or "values" not in rec or "key" not in rec or (rec["status"] == "ok" and not isinstance(rec.get("result"), dict)):
            return None, "incomplete"
        if rec["key"] != self.keys[i] or json.loads(_canonical(rec["values"])) != self.points[i]:
            return None, "stale"
        return rec, None

    def scan(self) -> tuple[set[int], dict[str, list[int]]]:
        """(indices of trusted "ok" points, {reason: indices} of files present but not trusted)."""
        done, rejected = set(), {}
        for i in range(len(self.points)):
            rec, why = self.read(i)
            if rec is not None and rec["status"] == "ok":
                done.add(i)
            elif why not in (None, "missing"):
                rejected.setdefault(why, []).append(i)
        return done, rejected

    def write(self, i: int, rec: dict) -> None:
        """Store point i (atomically), with the run that computed it, and release its claim."""
        self._atomic(self.path(i), {"index": i, "key": self.keys[i], "run": {"host": HOST, "pid": self.pid}, **rec})
        self.computed += 1
        self.release(i)

    # ------------------------------------------------------------ claims
    def _claim_path(self, i: int) -> Path:
        return self.dir / f"{i:06d}.claim"

    def _owner_alive(self, claim: Path) -> bool:
        try:
            info = json.loads(claim.read_text())
        except (OSError, ValueError):
            # being written right now, or left empty by a kill between create and write
            try:
                return time.time() - claim.stat().st_mtime < 30.0
            except OSError:
                return False
        if info.get("host") != HOST:
            return True                      # another machine: assume alive (cannot check its pid)
        try:
            os.kill(int(info.get("pid", -1)), 0)
        except ProcessLookupError:
            return False
        except (PermissionError, ValueError, TypeError, OverflowError):
            return True
        return True

    def claim(self, i: int) -> bool:
        """Take point i for this run; False if a live run holds it (a stale claim is taken over)."""
        c = self._claim_path(i)
        for _ in range(3):
            try:
                fd = os.open(c, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
            except FileExistsError:
                if self._owner_alive(c):
                    return False
                try:
                    c.unlink()               # stale: its owner died (killed mid-point)
                except FileNotFoundError:
                    pass
                continue
            with os.fdopen(fd, "w") as fh:
                json.dump({"host": HOST, "pid": self.pid, "time": time.time()}, fh)
            self.mine.add(i)
            # a temporary file of this point left by a run killed between writing and renaming it: the claim
            # makes this run the point's only writer, so any other run's temporary file of it is dead
            own = self._tmp_path(self.path(i))
            for old in own.parent.glob(f"{self.path(i).stem}.*.tmp"):
                if old != own:
                    old.unlink(missing_ok=True)
            if self.finished_elsewhere(i):   # another run stored it after this run's scan
                self.release(i)
                return False
            return True
        return False

    def finished_elsewhere(self, i: int) -> bool:
        """A trusted file for point i written after this run started: "ok", or an error another run got now."""
        rec, _ = self.read(i)
        if rec is None:
            return False
        if rec["status"] == "ok":
            return True
        try:
            return self.path(i).stat().st_mtime >= self.started
        except OSError:
            return False

    def claimed_by_others(self, i: int) -> bool:
        c = self._claim_path(i)
        return c.exists() and i not in self.mine and self._owner_alive(c)

    def release(self, i: int) -> None:
        if i in self.mine:
            self.mine.discard(i)
            try:
                self._claim_path(i).unlink()
            except FileNotFoundError:
                pass

    def release_all(self) -> None:
        for i in list(self.mine):
            self.release(i)
