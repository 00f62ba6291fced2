"""Every shell and Python block of README.md and docs/**/*.md runs, so a page that drifts from the
code fails here (convention: docs/writing_docs.md, tests/docblocks.py).

The blocks are found anew at every collection: a new page or a new block is covered without any
list to update.  Unmarked blocks run in the default tier (each within 120 s); blocks marked
``<!-- doctest: slow -->`` in the slow tier; ``<!-- doctest: skip: REASON -->`` blocks are reported
as skipped with their reason.
"""
import os

import pytest

from tests import docblocks as db

BLOCKS, PROBLEMS = db.all_blocks()


def _param(block: db.Block):
    marks = []
    if block.skip:
        marks.append(pytest.mark.skip(reason=f"{block.where}: {block.skip}"))
    elif block.slow:
        marks.append(pytest.mark.slow)
    return pytest.param(block, marks=marks, id=f"{block.where}:{block.language}")


@pytest.mark.parametrize("block", [_param(b) for b in BLOCKS if b.runnable])
def test_doc_block_runs(block, tmp_path):
    if "render" in block.flags and os.environ.get("DRIVEFEM_REQUIRE_RENDER") != "1":
        from fem.render import available
        ok, why = available()
        if not ok:
            pytest.skip(f"off-screen rendering unavailable: {why}")
    sandbox = db.make_sandbox(tmp_path)
    repository_before = db.repository_changes()
    for before in block.setup():             # 'continue' after a shell block: that block first
        done = db.run(before, sandbox)
        assert done.returncode == before.options.get("exit", 0), (
            f"{block.where}: the block it continues, {before.where}, ended with exit status "
            f"{done.returncode}\n--- output ---\n{done.stdout}")
    result = db.run(block, sandbox)
    want = block.options.get("exit", 0)
    assert result.returncode == want, (
        f"{block.where}: the {block.language} block ended with exit status {result.returncode} "
        f"(expected {want})\n--- block ---\n{block.script()}--- output ---\n{result.stdout}")
    assert "Traceback (most recent call last)" not in result.stdout or block.language == "python", (
        f"{block.where}: a traceback in the output\n{result.stdout}")
    if block.expected is not None:
        db.check_output(block.expected, result.stdout)
    written = sorted(db.repository_changes() - repository_before)
    assert not written, (f"{block.where}: the block wrote into the repository, not into its sandbox "
                         f"(write outputs to the working directory): {written}")


@pytest.mark.parametrize("block", [_param(b) for b in BLOCKS if b.language == "toml"])
def test_doc_toml_block_parses(block):
    db.check_toml(block)


@pytest.mark.parametrize("block", [_param(b) for b in BLOCKS if "file" in b.options])
def test_doc_excerpt_matches_its_file(block):
    db.check_excerpt(block)


def test_every_block_follows_the_convention():
    """No block without a language, no unknown or malformed directive, no 'output' block without
    its command before it, no 'skip' without its reason, no unclosed block."""
    assert not PROBLEMS, "docs code blocks that break the convention (docs/writing_docs.md):\n" + "\n".join(PROBLEMS)
    assert sum(b.runnable for b in BLOCKS) > 20


def test_the_checker_catches_drift(tmp_path):
    """The output check fails on a changed number, passes within tolerance, and the parser refuses
    what the convention forbids (a self-test: the doc tests cannot pass vacuously)."""
    page = tmp_path / "page.md"
    page.write_text("```sh\necho 'mode 1  16.158985 Hz'\n```\n\n<!-- doctest: output rtol=1e-6 -->\n"
                    "```text\nmode 1  16.15899 Hz\n...\n```\n")
    root = db.ROOT
    try:
        db.ROOT = tmp_path
        blocks, problems = db.parse(page)
        assert not problems and blocks[0].expected is blocks[1]
        db.check_output(blocks[1], "mode 1  16.158985 Hz\n")
        with pytest.raises(AssertionError, match="16.15899"):
            db.check_output(blocks[1], "mode 1  16.2 Hz\n")
        for text, msg in (("```\nx\n```\n", "no language"),
                          ("<!-- doctest: skip -->\n```sh\nx\n```\n", "reason"),
                          ("<!-- doctest: fast -->\n```sh\nx\n```\n", "unknown doctest word"),
                          ("<!-- doctest: output -->\n```text\nx\n```\n", "must follow"),
                          ("```sh\nx\n", "never closed")):
            page.write_text(text)
            assert msg in " ".join(db.parse(page)[1])
    finally:
        db.ROOT = root


def _cli_parsers() -> dict:
    """{command: its parser}, from the command line's own parser."""
    import argparse

    from fem.app.cli import build_parser
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def _cli_options() -> dict[str, set[str]]:
    """{command: its option strings}, old spellings included."""
    return {name: {s for a in p._actions for s in a.option_strings} for name, p in _cli_parsers().items()}


def _old_spellings() -> dict[str, dict[str, str]]:
    """{command: {old spelling: what to write instead}}: the options hidden from ``--help``
    (``help=argparse.SUPPRESS``), which the command line keeps for old scripts with a deprecation
    message (fem/app/options.py); the docs show the current spelling only."""
    import argparse
    return {name: {s: str(getattr(a, "new", "the current option of --help")) for a in p._actions
                   if a.help == argparse.SUPPRESS for s in a.option_strings}
            for name, p in _cli_parsers().items()}


def test_command_lines_shown_in_the_docs_exist():
    """Every line of a shell block or of a usage synopsis (a text block of ``drivefem ...`` lines,
    which is not run) that starts with ``drivefem COMMAND`` names a real command and only options
    it accepts (the command line's own parser)."""
    import re
    options, old = _cli_options(), _old_spellings()
    wrong = []
    for b in BLOCKS:
        lines = [ln for ln in b.code.splitlines() if ln.strip()]
        synopsis = lines and all(re.match(r"\s*(drivefem |#)", ln) for ln in lines)
        if not (b.runnable or synopsis):        # printed output may start with the word drivefem
            continue
        for line in lines:
            m = re.match(r"\s*(?:\.venv/bin/)?drivefem\s+([a-z][a-z-]*)(.*)", line)
            if not m or line.lstrip().startswith("drivefem:"):
                continue
            command, rest = m[1], m[2].split("#")[0]
            if command not in options:
                wrong.append(f"{b.where}: no command 'drivefem {command}': {line.strip()}")
                continue
            for flag in re.findall(r"(?<![\w-])--[a-z][\w-]*", rest):
                if flag not in options[command]:
                    wrong.append(f"{b.where}: 'drivefem {command}' has no option {flag}: {line.strip()}")
                elif flag in old[command]:
                    wrong.append(f"{b.where}: 'drivefem {command} {flag}' is an old spelling; write "
                                 f"{old[command][flag]}: {line.strip()}")
    assert not wrong, "\n".join(wrong)


@pytest.mark.parametrize("block", [_param(b) for b in BLOCKS if "synopsis" in b.flags])
def test_synopsis_lists_every_command_and_option(block):
    """A block marked ``synopsis`` lists every command of the command line, each with all of its
    options (old spellings, hidden from ``--help``, left out): a new command or option that the page
    does not show fails here."""
    import re
    options, old = _cli_options(), _old_spellings()
    options = {c: o - set(old[c]) for c, o in options.items()}
    shown = {}
    for line in block.code.splitlines():
        m = re.match(r"\s*drivefem\s+([a-z][a-z-]*)(.*)", line)
        if m:
            shown[m[1]] = set(re.findall(r"(?<![\w-])--[a-z][\w-]*", m[2]))
    assert sorted(shown) == sorted(options), f"{block.where}: commands shown {sorted(shown)}, the parser's {sorted(options)}"
    missing = {c: sorted(options[c] - {"-h", "--help"} - {o for o in options[c] if not o.startswith("--")} - f)
               for c, f in shown.items()}
    missing = {c: m for c, m in missing.items() if m}
    assert not missing, f"{block.where}: options not shown: {missing}"
