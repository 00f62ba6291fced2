"""Progress bars of long runs (tqdm on stderr, shown only on a terminal)."""
from __future__ import annotations

import sys
from contextlib import contextmanager


@contextmanager
def progress_bar(start: float, end: float, desc: str, unit: str):
    """A function ``update(value)`` that moves a bar from ``start`` to ``end`` (time or frequency)."""
    from tqdm import tqdm

    span = abs(end - start) or 1.0
    bar = tqdm(total=round(span, 12), desc=desc, unit=unit, file=sys.stderr, disable=None, leave=False,
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
def count_bar(desc: str, unit: str, *, quiet: bool = False, delay: float = 2.0):
    """A function ``update(done, total)`` moving a counting bar (the total may grow as the work
    reveals it, e.g. the crossings a Campbell diagram refines).  Shown on stderr only when it is a
    terminal, not ``quiet``, and only once the work has taken ``delay`` seconds."""
    from tqdm import tqdm

    bar = tqdm(total=1, desc=desc, unit=unit, file=sys.stderr, disable=True if quiet else None, leave=False,
               delay=delay)

    def update(done: int, total: int) -> None:
        if total != bar.total:
            bar.total = total
        bar.update(max(0, done - bar.n))
    try:
        yield update
    finally:
        bar.close()
