"""The model-file fuzzer (issue 11, item 6): mutated example files through the ``drivefem`` commands.

Every run must (1) exit with a documented code {0, 1, 2, 3, 4, 5} (exit 70, drivefem's "internal error",
is a failure like a traceback), (2) print no "Traceback",
(3) write no JSON with a NaN/Infinity/overflowing number, and (4) finish within its wall-clock limit.
The default tier runs a deterministic sample over every example (each example's main command, two
subprocesses at a time); the slow tier runs >= 3000 mutated files through every applicable command.
The harness itself is checked first, against a stand-in CLI that fails in each of the four ways.
Set DRIVEFEM_FUZZ_OUT=DIR to keep the results (summary.md, failures.json with reproducers).
"""
from __future__ import annotations

import os
import textwrap
from pathlib import Path

import pytest

from tests.fuzzing.classify import PROPERTY_CLASSES, check_json
from tests.fuzzing.examples import load_examples
from tests.fuzzing.execute import Job
from tests.fuzzing.mutate import Mutation, all_mutations
from tests.fuzzing.run import (FAST_LIMIT_S, ROOT, SLOW_LIMIT_S, controls, execute, fast_sample, plan,
                               slow_sample)

PROPERTIES = {
    "BADEXIT": "exit code outside the documented set {0, 1, 2, 3, 4, 5}",
    "TRACEBACK": "a Python traceback in the output",
    "NONFINITE": "a non-finite number in a JSON file",
    "HANG": "the run did not finish within its limit",
}


def _out_dir(tmp_path: Path, name: str) -> Path:
    base = os.environ.get("DRIVEFEM_FUZZ_OUT")
    return Path(base) / name if base else tmp_path / name


def _assert_properties(run) -> None:
    broken = {cls: [o for o in run.outcomes if o.cls == cls] for cls in PROPERTY_CLASSES}
    lines = []
    for cls, items in broken.items():
        if items:
            lines.append(f"{len(items)} runs: {PROPERTIES[cls]}")
            for o in items[:8]:
                lines.append(f"  {o.command} {o.id} ({o.description}): {o.root_cause}\n    {o.repro}")
    assert not any(broken.values()), (
        "the fuzzer found runs that break issue 11's properties\n" + "\n".join(lines)
        + f"\n\n{run.summary()}\n(all failures with reproducers: {run.out_dir}/failures.json)")


# ------------------------------------------------------------------ the harness itself (fast, no package)
FAKE_CLI = '''
import json, math, sys, time
def main():
    text = open(sys.argv[2]).read()
    out = sys.argv[sys.argv.index("--json") + 1]
    if "traceback" in text:
        raise RuntimeError("boom")
    if "hang" in text:
        time.sleep(600)
    if "spin" in text:
        while True:
            pass
    if "badexit" in text:
        return 7
    if "internal" in text:
        print("drivefem: internal error: ValueError: boom (at x.py:1; please report it)", file=sys.stderr)
        return 70
    if "nan" in text:
        json.dump({"amplitude": [1.0, math.nan], "x": {"y": math.inf}}, open(out, "w"))
        return 0
    if "overflow" in text:
        open(out, "w").write('{"a": 1e400}')
        return 0
    if "truncated" in text:
        open(out, "w").write('{"a": [1, 2')
        return 0
    if "unnamed" in text:
        print("drivefem: error: something is wrong", file=sys.stderr)
        return 2
    if "named" in text:
        print("drivefem: error: [material]: E = nan is not valid; allowed: a finite number", file=sys.stderr)
        return 2
    json.dump({"ok": 1.5}, open(out, "w"))
    return 0
'''


@pytest.mark.parametrize("fork", [True, False], ids=["forked", "fresh-interpreter"])
def test_harness_detects_each_failure_class(tmp_path, fork):
    """A stand-in CLI that fails in every way the fuzzer must catch: each run gets the right class
    (runs forked from the fork server, and runs in a fresh interpreter each); a run that waits is stopped at
    the wall-clock ceiling, one that computes at its CPU-time limit."""
    root = tmp_path / "src"
    root.mkdir()
    (root / "pyproject.toml").write_text('[project]\nname = "x"\n[project.scripts]\ndrivefem = "fakecli:main"\n')
    (root / "fakecli.py").write_text(textwrap.dedent(FAKE_CLI))
    expected = {"ok": "OK", "traceback": "TRACEBACK", "hang": "HANG", "spin": "HANG", "badexit": "BADEXIT",
                "internal": "BADEXIT",
                "nan": "NONFINITE",
                "overflow": "NONFINITE", "truncated": "BADJSON", "unnamed": "BADMESSAGE", "named": "OK"}
    jobs = [Job(Mutation(f"fake/test/-/{word}", "fake", "test", word, data=f"x = '{word}'\n".encode(),
                         names=("E", "material")), "modal") for word in expected]
    run = execute(jobs, root=root, limit_s=3.0, out_dir=tmp_path / "out", progress=False, fork=fork, wall_factor=1.0)
    got = {o.id.split("/")[-1]: o.cls for o in run.outcomes}
    assert got == expected
    nan = next(o for o in run.outcomes if o.id.endswith("/nan"))
    assert any("amplitude[1]" in p for p in nan.nonfinite_paths) and any("x.y" in p for p in nan.nonfinite_paths)
    tb = next(o for o in run.outcomes if o.id.endswith("/traceback"))
    assert tb.root_cause.startswith("RuntimeError in fakecli.py") or "fakecli.py:main" in tb.root_cause
    hang = next(o for o in run.outcomes if o.id.endswith("/hang"))
    assert "fakecli.py:main" in hang.root_cause and hang.repro
    spin = next(o for o in run.outcomes if o.id.endswith("/spin"))     # out of CPU time (RLIMIT_CPU)
    assert "fakecli.py:main" in spin.root_cause and spin.duration_s < 30
    assert (tmp_path / "out" / "failures.json").is_file() and (tmp_path / "out" / "summary.md").is_file()


def test_strict_json_check():
    assert check_json(b'{"a": [1, 2.5e300, null, "nan"]}')[0] == "ok"
    assert check_json(b'{"a": NaN}')[0] == "nonfinite"
    assert check_json(b'{"a": [-Infinity]}')[0] == "nonfinite"
    assert check_json(b'{"a": 1e999}')[0] == "nonfinite"
    assert check_json(b'{"a": ')[0] == "invalid"
    assert check_json(b'\xff{}')[0] == "invalid"


def test_mutations_are_deterministic_and_cover_every_example():
    """Same examples, same mutations (ids and bytes); unique ids; every category; every example sampled."""
    examples = load_examples(ROOT)
    first, second = all_mutations(examples), all_mutations(load_examples(ROOT))
    assert [m.id for m in first] == [m.id for m in second]
    # bytes of the first mutation of every (example, category) -- every generator on every example -- and of
    # every 97th (materialising the contents of a seventh of the ~65000 took 12 s of CPU)
    leads = {}
    for k, m in enumerate(first):
        leads.setdefault((m.example, m.category), k)
    picked = sorted(set(leads.values()) | set(range(0, len(first), 97)))
    assert all(first[k].content == second[k].content for k in picked)
    assert len({m.id for m in first}) == len(first)
    assert all(m.description and "\n" not in m.description for m in first)
    cats = {m.category for m in first}
    assert {"number", "count", "type", "enum", "structure", "duplicate", "unknown_key", "delete", "semantic",
            "broken_toml", "encoding", "filesystem", "nesting", "output", "control", "extreme", "cli"} <= cats
    assert {m.example for m in fast_sample(examples)} == {ex.name for ex in examples}
    stratified = slow_sample(examples, 3000, budget=False)
    full = slow_sample(examples, 3000)
    assert len({m.id for m in stratified}) == 3000 and full[:3000] == stratified
    assert len({m.id for m in full}) == len(full) > 3000


# ------------------------------------------------------------------------------- the package
def test_fuzz_fast_sample(tmp_path):
    """Default tier: a sample of mutations a correct package rejects up front, at least one per example, each
    through the example's main command.  The unmutated examples are not re-run here: every example runs as
    shipped in tests/test_cli_examples.py or in its validation case (tests/test_examples_pinned.py checks
    that), and their cheap bases took four fifths of this test's time (87 of 112 s of runs, loaded machine);
    the slow tier runs every control."""
    examples = load_examples(ROOT)
    muts = fast_sample(examples)
    jobs = plan(muts, examples, all_commands=False, wrong_kind_every=0)
    run = execute(jobs, limit_s=FAST_LIMIT_S, out_dir=_out_dir(tmp_path, "fuzz-fast"), progress=False)
    print(run.summary())
    _assert_properties(run)


@pytest.mark.slow
def test_fuzz_slow_3000(tmp_path):
    """Slow tier: 3000 stratified mutated files plus the budget slice (1e+-300 and 1e9 in the keys that set
    the work: ~415 more) through every applicable command (render on a quarter of the FE files, a
    wrong-kind command on a tenth, CSV/plot outputs on a tenth of the runs), plus the examples as shipped:
    about 8000 runs, among them the extreme values, option and output-path attacks of issue 24."""
    examples = load_examples(ROOT)
    muts = slow_sample(examples, 3000)
    jobs = plan(controls(examples) + muts, examples, extras_every=10)
    run = execute(jobs, limit_s=SLOW_LIMIT_S, out_dir=_out_dir(tmp_path, "fuzz-slow"), progress=True)
    print(run.summary())
    assert len({o.id for o in run.outcomes if o.category != "control"}) >= 3000
    assert len(run.outcomes) >= 5000          # issue 24: >= 5000 runs (every command each kind accepts)
    _assert_properties(run)
