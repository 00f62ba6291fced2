"""Progress bars of long runs: one policy for every command (tqdm on stderr).

A bar is drawn only when stderr is a terminal, the command was not given ``--quiet`` and the work
has run for :data:`DELAY` seconds (quick runs print nothing, piped or redirected output never gets
bar debris).  Two environment variables adjust the policy: ``DRIVEFEM_PROGRESS_DELAY`` (seconds
before a bar appears; the tests use 0) and ``DRIVEFEM_PROGRESS=never`` (no bars at all, e.g. in CI
logs captured through a pseudo-terminal)."""
from __future__ import annotations

import os
import sys
from contextlib import contextmanager

#: seconds of work before a bar appears
DELAY = 2.0
_QUIET = [False]


def set_quiet(quiet: bool) -> None:
    """``--quiet`` for the whole command (every bar the command or its callees open)."""
    _QUIET[0] = bool(quiet)


def _disable(quiet: bool):
    """tqdm's ``disable``: True (no bar) when quiet, else None (drawn only on a terminal)."""
    if quiet or _QUIET[0] or os.environ.get("DRIVEFEM_PROGRESS", "").lower() == "never":
        return True
    return None


def _delay(default: float) -> float:
    try:
        return max(0.0, float(os.environ["DRIVEFEM_PROGRESS_DELAY"]))
    except (KeyError, ValueError):
        return default


def _shape() -> dict:
    """tqdm's ``ncols`` and ``nrows`` of the terminal: one that reports a size of 0 (a new
    pseudo-terminal, some CI runners) gets 80 x 24, where tqdm would draw nothing."""
    try:
        size = os.get_terminal_size(sys.stderr.fileno())
    except (AttributeError, OSError, ValueError):
        return {}
    return {"ncols": size.columns or 80, "nrows": size.lines or 24}


@contextmanager
def progress_bar(start: float, end: float, desc: str, unit: str, *, quiet: bool = False, delay: float = DELAY):
    """A function ``update(value)`` that moves a bar from ``start`` to ``end`` (time or frequency)."""
    from tqdm import tqdm

    span = abs(end - start) or 1.0
    bar = tqdm(total=round(span, 12), desc=desc, unit=unit, file=sys.stderr, disable=_disable(quiet), leave=False,
               delay=_delay(delay), **_shape(),
               bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.4g}/{total:.4g} {unit} [{elapsed}<{remaining}]")
    done = [0.0]

    def update(value: float) -> None:
        pos = min(max(abs(value - start), 0.0), span)
        if pos - done[0] >= 1e-3 * span or pos >= span:
            bar.update(pos - done[0])
            done[0] = pos
    try:
        yield update
    finally:
        bar.close()


@contextmanager
def count_bar(desc: str, unit: str, *, quiet: bool = False, delay: float = DELAY, total: int = 1):
    """A function ``update(done, total)`` moving a counting bar (the total may grow as the work
    reveals it, e.g. the crossings a Campbell diagram refines); ``update.note(text)`` shows what is
    being done (a validation case's name)."""
    from tqdm import tqdm

    bar = tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, disable=_disable(quiet), leave=False,
               delay=_delay(delay), **_shape())

    def update(done: int, total: int) -> None:
        if total != bar.total:
            bar.total = total
        bar.update(max(0, done - bar.n))

    def note(text: str) -> None:
        bar.set_postfix_str(text, refresh=False)

    update.note = note
    try:
        yield update
    finally:
        bar.close()
