"""Sample mutations, plan the runs, execute them two at a time and write the results.

Command line (from the repository root)::

    python -m tests.fuzzing.run --n 3000 --out DIR [--jobs 2] [--limit 60] [--root SRC] [--seed 0]
    python -m tests.fuzzing.run --budget-only --out DIR     # only the 1e+-300 / 1e9 mutations
    python -m tests.fuzzing.run --fast --out DIR            # the default-tier sample
    python -m tests.fuzzing.run --only ID [--only ID ...]   # re-run given mutations
    python -m tests.fuzzing.run --list [--n N]              # print the sample without running it

``DIR`` receives ``results.jsonl`` (every run, written as it finishes), ``failures.json`` (every
failing run with the command line that reproduces it), ``summary.md`` and ``reproducers/`` (the
mutated files of failing runs).  ``SRC`` is the source tree under test (default: this checkout).
"""
from __future__ import annotations

import argparse
import hashlib
import json
import re
import signal
import sys
import tempfile
import threading
import time
from collections import defaultdict
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

from .classify import PROPERTY_CLASSES, Outcome, classify
from .examples import Example, load_examples
from .execute import WALL_FACTOR, Job, Runner
from .mutate import Mutation, all_mutations, mutations_of
from .summary import figures, markdown_report, text_summary

ROOT = Path(__file__).resolve().parents[2]

#: Variants that a correct package rejects before any work (the fast tier draws from these).
FAST_VARIANTS = re.compile(r"/(nan|inf|-inf|count_1e9|count_1e9_float|string|bool|list|table|number|unknown_word|"
                           r"made_up|typo_.*|extra_.*|to_array_of_tables|to_table|truncate_\d+|unclosed_header|"
                           r"extra_bracket|stray_close|unterminated_string|bad_escape|missing_value|missing_equals|"
                           r"unclosed_array|key_twice|table_twice_.*|lone_cr|binary_.*|latin1_title|"
                           r"invalid_utf8_comment|utf16|utf8_bom|nul_byte|empty|whitespace|comment_only|directory|"
                           r"missing|fifo|dangling_symlink|array_depth_5000|inline_table_depth_2000|"
                           r"header_depth_1000|dotted_key_depth_1000|value_depth_3000|.*--json_.*|"
                           r".*--(modes|mode|workers)_.*)$")
FAST_N = 56          # mutated files in the default tier (at least one per example; no controls: see test_fuzz_fast_sample)
FAST_LIMIT_S = 20.0  # CPU-time limit of one run in the default tier (wall clock: WALL_FACTOR times it)
SLOW_LIMIT_S = 60.0


def _h(s: str) -> int:
    return int(hashlib.sha256(s.encode()).hexdigest()[:12], 16)


def _round_robin(lists: list[list]) -> list:
    out, depth = [], 0
    while any(len(x) > depth for x in lists):
        out += [x[depth] for x in lists if len(x) > depth]
        depth += 1
    return out


def stratified_sample(mutations: list[Mutation], n: int, seed: int = 0) -> list[Mutation]:
    """``n`` mutations spread evenly: round-robin over the examples, each example's own sequence
    round-robin over its categories (in a seeded order), each category in a seeded order.

    Deterministic: the same mutations, seed and ``n`` give the same sample; a larger ``n`` extends it."""
    per_example: dict[str, dict[str, list[Mutation]]] = defaultdict(lambda: defaultdict(list))
    for m in mutations:
        per_example[m.example][m.category].append(m)
    sequences = []
    for ex in sorted(per_example):
        cats = sorted(per_example[ex], key=lambda c: _h(f"{seed}/{ex}/{c}"))
        sequences.append(_round_robin([sorted(per_example[ex][c], key=lambda m: _h(f"{seed}/{m.id}"))
                                       for c in cats]))
    return _round_robin(sequences)[:n]


def controls(examples: list[Example], cheap_only: bool = False) -> list[Mutation]:
    """The unmutated examples (as shipped and their cheap bases)."""
    out = []
    for ex in examples:
        cs = [m for m in mutations_of(ex) if m.category == "control"]
        if cheap_only:
            cs = [m for m in cs if m.id.endswith("/cheap_base")] or [m for m in cs if m.id.endswith("/original")]
        out += cs
    return out


def fast_sample(examples: list[Example], n: int | None = None, seed: int = 0) -> list[Mutation]:
    """The default-tier sample: ``n`` files whose mutations a correct package rejects up front
    (default: ``FAST_N``, and at least one per example, so every shipped example is attacked)."""
    n = max(FAST_N, len(examples)) if n is None else n
    pool = [m for m in all_mutations(examples) if m.category != "control" and FAST_VARIANTS.search(m.id)]
    return stratified_sample(pool, n, seed)


def slow_sample(examples: list[Example], n: int = 3000, seed: int = 0, budget: bool = True) -> list[Mutation]:
    """The slow-tier sample: ``n`` files drawn by :func:`stratified_sample`, plus (``budget``) the whole
    :func:`budget_slice` (the mutations behind the hangs and memory errors of issue 11)."""
    pool = [m for m in all_mutations(examples) if m.category != "control"]
    sample = stratified_sample(pool, n, seed)
    return sample + (budget_slice(examples, exclude={m.id for m in sample}, pool=pool) if budget else [])


BUDGET_TABLES = {"simulation", "steady", "sweep", "analysis", "reduction", "drive", "initial"}
BUDGET_KEYS = {"inertia", "mass", "E", "k"}
BUDGET_VARIANTS = re.compile(r"/(1e300|1e-300|int_1e9|int_1e20|count_1e9|count_1e9_float)$")


def budget_slice(examples: list[Example], exclude: set[str] = frozenset(),
                 pool: list[Mutation] | None = None) -> list[Mutation]:
    """Every mutation that makes a run huge or endless: 1e+-300 and 1e9/1e20 integers in the tables that set
    the work (``[simulation]``, ``[steady]``, ``[sweep]``, ``[analysis]``, ``[reduction]``, ``[drive]``,
    ``[initial]``) and in inertias, masses, E and stiffnesses; the slow tier adds them to its sample."""
    out = []
    for m in pool if pool is not None else all_mutations(examples):
        if m.id in exclude or m.category not in ("number", "count") or not BUDGET_VARIANTS.search(m.id):
            continue
        head = re.split(r"[.\[]", m.target)[0]
        leaf = re.split(r"[.\]]", m.target)[-1]
        if head in BUDGET_TABLES or leaf in BUDGET_KEYS:
            out.append(m)
    return out


def plan(mutations: list[Mutation], examples: list[Example], *, all_commands: bool = True,
         wrong_kind_every: int = 10, render_every: int = 4, extras_every: int = 0, seed: int = 0) -> list[Job]:
    """The runs of ``mutations``: every applicable command (or only the main one), render on one file in
    ``render_every``, a wrong-kind command on one file in ``wrong_kind_every``, the command's CSV/plot
    outputs on one run in ``extras_every`` (0: never)."""
    by_name = {ex.name: ex for ex in examples}
    jobs = []
    for m in mutations:
        ex = by_name[m.example]
        h = _h(f"{seed}/{m.id}")
        if m.commands:
            cmds = list(m.commands)
        elif all_commands:
            cmds = [c for c in ex.commands if c != "render" or (render_every and h % render_every == 0)]
            if m.id.endswith("/control/-/original") and ex.cheap_notes:
                cmds = [c for c in cmds if c != "sweep"] or cmds[:1]   # a full serial sweep takes minutes
        else:
            cmds = [ex.commands[0]]
        for c in cmds:
            extra = bool(extras_every) and _h(f"{seed}/{m.id}/{c}/extra") % extras_every == 0 and not m.output
            jobs.append(Job(m, c, extra_outputs=extra))
        if not m.commands and wrong_kind_every and h % wrong_kind_every == 1 and m.category != "control":
            wrong = ex.wrong_commands
            jobs.append(Job(m, wrong[(h // wrong_kind_every) % len(wrong)], wrong_kind=True))
    return jobs


def _safe(s: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "_", s)[:150]


@dataclass
class FuzzRun:
    """A finished fuzz run: its outcomes, wall time and the directory it wrote (if any)."""

    outcomes: list[Outcome]
    wall_s: float
    out_dir: Path | None

    @property
    def failures(self) -> list[Outcome]:
        return [o for o in self.outcomes if o.failed]

    def property_failures(self) -> list[Outcome]:
        return [o for o in self.outcomes if o.cls in PROPERTY_CLASSES]

    def summary(self) -> str:
        return text_summary(self.outcomes, self.wall_s)


def execute(jobs: list[Job], *, root: Path = ROOT, jobs_at_once: int = 2, limit_s: float = SLOW_LIMIT_S,
            out_dir: Path | None = None, progress: bool = True, meta: dict | None = None,
            fork: bool = True, wall_factor: float = WALL_FACTOR) -> FuzzRun:
    """Run ``jobs`` (``jobs_at_once`` at a time) and classify them; write results to ``out_dir``.
    ``limit_s``: CPU seconds of one run (wall clock at most ``wall_factor`` times that).
    ``fork``: fork each run from a server that has imported the package (tests/fuzzing/zygote.py);
    False: a fresh interpreter per run (slower by the import time, ~1-3 s a run)."""
    root = Path(root).resolve()
    t0 = time.monotonic()
    outcomes: list[Outcome] = []
    with tempfile.TemporaryDirectory(prefix="drivefem-fuzz-") as tmp:
        runner = Runner(root, Path(tmp), limit_s=limit_s, fork=fork, wall_factor=wall_factor)
        results_f = None
        if out_dir:
            out_dir = Path(out_dir)
            (out_dir / "reproducers").mkdir(parents=True, exist_ok=True)
            results_f = open(out_dir / "results.jsonl", "w")
        lock = threading.Lock()

        def one(i: int, job: Job) -> Outcome:
            o = classify(runner.run(job, i), root)
            saved = None
            if o.failed and out_dir and job.mutation.artifact == "file":
                saved = (out_dir / "reproducers" / (_safe(job.mutation.id) + ".toml")).resolve()
                saved.write_bytes(job.mutation.content)
                o.saved_model = str(saved)
            if o.failed:
                o.repro = runner.repro(job, saved)
            return o

        try:
            with ThreadPoolExecutor(max_workers=jobs_at_once) as pool:
                futures = [pool.submit(one, i, job) for i, job in enumerate(jobs)]
                try:
                    for k, fut in enumerate(as_completed(futures), 1):
                        o = fut.result()
                        with lock:
                            outcomes.append(o)
                            if results_f:
                                results_f.write(json.dumps(o.to_dict()) + "\n")
                                results_f.flush()
                        if progress and (k % 50 == 0 or k == len(jobs) or o.cls != "OK"):
                            bad = sum(x.failed for x in outcomes)
                            print(f"[{k}/{len(jobs)} {time.monotonic() - t0:6.0f} s, {bad} failing] "
                                  + (f"{o.cls} {o.command} {o.id}" if o.failed else ""), file=sys.stderr, flush=True)
                except KeyboardInterrupt:
                    for f in futures:
                        f.cancel()
                    runner.kill_all()
                    raise
        finally:
            runner.close()
            if results_f:
                results_f.close()
    wall = time.monotonic() - t0
    outcomes.sort(key=lambda o: (o.id, o.command))
    run = FuzzRun(outcomes, wall, out_dir)
    if out_dir:
        meta = dict(meta or {}, root=str(root), cpu_limit_s=limit_s, wall_limit_s=limit_s * wall_factor,
                    processes=jobs_at_once, wall_s=round(wall, 1))
        (out_dir / "failures.json").write_text(json.dumps(
            {"meta": meta, "figures": figures(outcomes), "failures": [o.to_dict() for o in run.failures]}, indent=1))
        (out_dir / "summary.md").write_text(markdown_report(outcomes, meta))
    return run


def _interrupt(signum, frame):
    raise KeyboardInterrupt


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m tests.fuzzing.run", description=__doc__.split("\n")[0])
    p.add_argument("--n", type=int, default=3000, help="mutated files to run (default 3000)")
    p.add_argument("--fast", action="store_true", help="the default-tier sample (main command only, short limit)")
    p.add_argument("--out", type=Path, help="directory for results.jsonl, failures.json, summary.md, reproducers/")
    p.add_argument("--jobs", type=int, default=2, help="subprocesses at a time (default 2)")
    p.add_argument("--limit", type=float, default=None, help="CPU-time limit of one run in seconds")
    p.add_argument("--wall-factor", type=float, default=WALL_FACTOR,
                   help=f"wall-clock ceiling of one run, in units of --limit (default {WALL_FACTOR:g})")
    p.add_argument("--root", type=Path, default=ROOT, help="source tree under test (default: this checkout)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--example", action="append", help="only mutations of this example (repeatable)")
    p.add_argument("--category", action="append", help="only this mutation category (repeatable)")
    p.add_argument("--only", action="append", help="only this mutation id (repeatable; all its commands)")
    p.add_argument("--no-controls", action="store_true", help="leave out the unmutated examples")
    p.add_argument("--extras-every", type=int, default=10, help="add CSV/plot outputs to one run in N (0: never)")
    p.add_argument("--no-budget", action="store_true", help="the stratified sample only, without the budget slice")
    p.add_argument("--budget-only", action="store_true", help="only the budget slice (1e+-300, 1e9 counts)")
    p.add_argument("--list", action="store_true", help="print the planned runs and stop")
    p.add_argument("--no-fork", action="store_true", help="a fresh interpreter per run instead of forking "
                   "from a server that imported the package once (slower; the import itself is exercised)")
    a = p.parse_args(argv)
    signal.signal(signal.SIGTERM, _interrupt)   # a kill stops the runs cleanly (background jobs ignore SIGINT)
    signal.signal(signal.SIGINT, _interrupt)
    examples = load_examples(a.root)
    if a.example:
        examples = [ex for ex in examples if ex.name in a.example]
    if a.only:
        wanted = set(a.only)
        muts = [m for m in all_mutations(examples) if m.id in wanted]
        missing = wanted - {m.id for m in muts}
        if missing:
            print(f"unknown mutation ids: {sorted(missing)}", file=sys.stderr)
            return 2
        ctrl = []
    elif a.budget_only:
        muts, ctrl = budget_slice(examples), []
    else:
        if a.category:
            allm = [m for m in all_mutations(examples) if m.category in a.category]
            muts = stratified_sample(allm, a.n, a.seed)
        elif a.fast:
            muts = fast_sample(examples, None if a.n == 3000 else a.n, a.seed)
        else:
            muts = slow_sample(examples, a.n, a.seed, budget=not a.no_budget)
        ctrl = [] if a.no_controls or a.fast else controls(examples)
    jobs = plan(ctrl + muts, examples, all_commands=not a.fast, wrong_kind_every=0 if a.fast else 10,
                extras_every=0 if a.fast else a.extras_every, seed=a.seed)
    if a.list:
        for j in jobs:
            print(f"{j.command:<9}{' (wrong kind)' if j.wrong_kind else '':<13} {j.mutation.id}  |  {j.mutation.description}")
        print(f"{len(jobs)} runs of {len({j.mutation.id for j in jobs})} files", file=sys.stderr)
        return 0
    limit = a.limit or (FAST_LIMIT_S if a.fast else SLOW_LIMIT_S)
    print(f"{len(jobs)} runs of {len({j.mutation.id for j in jobs})} files ({len(ctrl)} controls), "
          f"{a.jobs} at a time, limit {limit:.0f} s, source tree {a.root}", file=sys.stderr)
    try:
        run = execute(jobs, root=a.root, jobs_at_once=a.jobs, limit_s=limit, out_dir=a.out, fork=not a.no_fork,
                      meta={"seed": a.seed, "sample": "fast" if a.fast else f"n={a.n}"}, wall_factor=a.wall_factor)
    except KeyboardInterrupt:
        print("interrupted: runs in progress killed" + (f"; finished runs are in {a.out}/results.jsonl" if a.out else ""),
              file=sys.stderr)
        return 130
    print(run.summary())
    if a.out:
        print(f"\nwrote {a.out}/summary.md, failures.json, results.jsonl")
    return 1 if run.property_failures() else 0


if __name__ == "__main__":
    sys.exit(main())
