"""The code blocks of README.md and docs/**/*.md, and how the tests run them (docs/writing_docs.md).

Every fenced block names its language.  ``sh``/``bash`` and ``python`` blocks are executed
(tests/test_doc_blocks.py); ``toml`` blocks are parsed; ``text``, ``json`` and the rest are shown
only.  An HTML comment on the line just before the fence (invisible on GitHub and on the site)
changes how a block is run::

    <!-- doctest: skip: REASON -->       not run; the reason is required and reported
    <!-- doctest: slow -->               run in the slow tier (make test-slow)
    <!-- doctest: timeout=SECONDS -->    the block's time limit (default 120 s, slow blocks 900 s)
    <!-- doctest: exit=N -->             the block must end with exit status N (an error example)
    <!-- doctest: render -->             needs off-screen rendering (skipped without it, unless
                                         DRIVEFEM_REQUIRE_RENDER=1)
    <!-- doctest: continue -->           a block run after the page's previous runnable block, in
                                         the same sandbox: a python block after a python block in
                                         the same process (a walk-through split by prose); after a
                                         shell block, once that block has run (it reads its files)
    <!-- doctest: synopsis -->           a text block with the usage of every drivefem command, one
                                         line each, with all of its options (checked against the parser)
    <!-- doctest: file=PATH -->          the block is an excerpt of PATH: its lines are lines of the
                                         file, in order ('...' lines aside)
    <!-- doctest: output rtol=R atol=A --> a text block that shows what the previous runnable block
                                         prints: its lines must appear, in order, in that output;
                                         numbers compared with numpy.isclose(rtol=R, atol=A), the
                                         rest word for word; lines '...' are not compared

Words combine: ``<!-- doctest: slow timeout=300 render -->``.

Blocks run in a sandbox: a temporary directory that mirrors the repository root (``examples/`` is
copied, the other top-level entries are linked), so ``examples/x.toml`` resolves and outputs land
in the temporary directory.  ``drivefem``, ``.venv/bin/drivefem``, ``python`` and
``.venv/bin/python`` there are this interpreter with this checkout on PYTHONPATH.
"""
from __future__ import annotations

import os
import re
import resource
import shutil
import subprocess
import sys
import textwrap
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SHELL = {"sh", "bash", "shell"}
PYTHON = {"python", "py"}
RUNNABLE = SHELL | PYTHON
DEFAULT_TIMEOUT, SLOW_TIMEOUT = 120.0, 900.0
FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})[ \t]*(?P<info>[^`]*)$")
DIRECTIVE = re.compile(r"^\s*<!--\s*doctest:\s*(?P<body>.*?)\s*-->\s*$")
FLAGS = {"slow", "render", "continue", "output", "synopsis"}
KEYS = {"timeout": float, "exit": int, "rtol": float, "atol": float, "file": str}
NUMBER = re.compile(r"([-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?)")


class DocBlockError(ValueError):
    """A directive that breaks the convention (the message names file and line)."""


@dataclass
class Block:
    path: Path
    line: int                       # 1-based line of the opening fence
    language: str
    code: str
    directive: str = ""
    skip: str | None = None         # the reason, when not run
    flags: set[str] = field(default_factory=set)
    options: dict = field(default_factory=dict)
    expected: "Block | None" = None  # the output block shown after it
    previous: "Block | None" = None  # the runnable block a 'continue' block follows

    @property
    def where(self) -> str:
        return f"{self.path.relative_to(ROOT)}:{self.line}"

    @property
    def runnable(self) -> bool:
        return self.language in RUNNABLE

    @property
    def slow(self) -> bool:
        return "slow" in self.flags

    @property
    def timeout(self) -> float:
        return self.options.get("timeout", SLOW_TIMEOUT if self.slow else DEFAULT_TIMEOUT)

    def _joined(self) -> bool:
        """Whether this block runs in the same process as the one before it (python after python)."""
        return ("continue" in self.flags and self.language in PYTHON and self.previous is not None
                and self.previous.language in PYTHON)

    def script(self) -> str:
        """The python source to run: the chain of python 'continue' blocks up to this one."""
        parts, block = [self.code], self
        while block._joined():
            block = block.previous
            parts.append(block.code)
        return "\n".join(reversed(parts))

    def setup(self) -> "list[Block]":
        """The blocks to run before this one in its sandbox, first to last: a 'continue' block after
        a shell block needs that block (and what that one needs) run first."""
        first = self
        while first._joined():
            first = first.previous
        if "continue" not in first.flags or first.previous is None:
            return []
        return first.previous.setup() + [first.previous]


def doc_files() -> list[Path]:
    """README.md and every Markdown page under docs/ (new pages are covered without a list)."""
    return [ROOT / "README.md"] + sorted((ROOT / "docs").rglob("*.md"))


def parse_directive(body: str, where: str) -> tuple[str | None, set[str], dict]:
    if body.startswith("skip"):
        reason = body[4:].lstrip(" :").strip()
        if not body[4:].lstrip().startswith(":") or not reason:
            raise DocBlockError(f"{where}: write '<!-- doctest: skip: REASON -->' with the reason")
        return reason, set(), {}
    flags, options = set(), {}
    for word in body.split():
        key, eq, value = word.partition("=")
        if eq:
            if key not in KEYS:
                raise DocBlockError(f"{where}: unknown doctest option {key!r}; allowed: {sorted(KEYS)}")
            try:
                options[key] = KEYS[key](value)
            except ValueError:
                raise DocBlockError(f"{where}: doctest option {key}={value!r} is not a {KEYS[key].__name__}") from None
        elif word in FLAGS:
            flags.add(word)
        else:
            raise DocBlockError(f"{where}: unknown doctest word {word!r}; allowed: skip: REASON, "
                                f"{', '.join(sorted(FLAGS))}, {', '.join(k + '=' for k in KEYS)}")
    return None, flags, options


def parse(path: Path) -> tuple[list[Block], list[str]]:
    """The fenced blocks of one Markdown file, with their directives, outputs and chains linked,
    and the problems found (each names file and line; a block with a problem is not run)."""
    problems: list[str] = []
    lines = path.read_text(encoding="utf-8").split("\n")
    rel = path.relative_to(ROOT)
    blocks: list[Block] = []
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, fence, info = m["indent"], m["fence"], m["info"].strip()
        close = re.compile(rf"^[ \t]*{re.escape(fence[0])}{{{len(fence)},}}[ \t]*$")
        j = i + 1
        while j < len(lines) and not close.match(lines[j]):
            j += 1
        if j == len(lines):
            problems.append(f"{rel}:{i + 1}: the code block is never closed")
            break
        body = [ln[len(indent):] if ln.startswith(indent) else ln.lstrip() for ln in lines[i + 1:j]]
        where = f"{rel}:{i + 1}"
        k = i - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        d = DIRECTIVE.match(lines[k]) if k >= 0 else None
        directive = d["body"] if d else ""
        try:
            skip, flags, options = parse_directive(directive, where) if d else (None, set(), {})
        except DocBlockError as exc:
            problems.append(str(exc))
            skip, flags, options = "the doctest directive above it is not valid", set(), {}
        language = info.split()[0].lower() if info else ""
        blocks.append(Block(path, i + 1, language, textwrap.dedent("\n".join(body)) + "\n", directive,
                            skip, flags, options))
        i = j + 1
    last_runnable = None
    for b in blocks:
        where = f"{rel}:{b.line}"
        if not b.language:
            problems.append(f"{where}: the code block has no language; give it one (sh or python: run "
                            "by the tests; toml: parsed; text: shown only)")
        if "output" in b.flags:
            if b.runnable:
                problems.append(f"{where}: 'output' marks the text block that shows a command's output, "
                                "not a runnable block")
            elif last_runnable is None or last_runnable.expected is not None or last_runnable.skip:
                problems.append(f"{where}: an 'output' block must follow the runnable block (not skipped) "
                                "whose output it shows")
            else:
                last_runnable.expected = b
        if "continue" in b.flags:
            if not b.runnable or last_runnable is None or last_runnable.skip:
                problems.append(f"{where}: 'continue' runs a block after the page's previous runnable "
                                "block (not skipped)")
            else:
                b.previous = last_runnable
        if b.runnable:
            last_runnable = b
    return blocks, problems


def all_blocks() -> tuple[list[Block], list[str]]:
    """Every block of every page, and every problem found."""
    blocks, problems = [], []
    for path in doc_files():
        b, p = parse(path)
        blocks += b
        problems += p
    return blocks, problems


# -- running -------------------------------------------------------------------------------------

def make_sandbox(tmp: Path) -> Path:
    """A directory that looks like the repository root: examples/ and the top-level files copied
    (a block may write next to a model file, or over README.md: never into the checkout), the other
    directories linked; .venv/bin holds the shims.  (A linked file would let a block's output of the
    same name write through into the repository, as chart.png once did.)"""
    for entry in ROOT.iterdir():
        if entry.name in {".git", ".venv", "site", "examples"} or entry.name.startswith(".pytest"):
            continue
        if entry.is_dir():
            (tmp / entry.name).symlink_to(entry, target_is_directory=True)
        else:
            shutil.copy2(entry, tmp / entry.name)
    shutil.copytree(ROOT / "examples", tmp / "examples", ignore=shutil.ignore_patterns("__pycache__"))
    bin_dir = tmp / ".venv" / "bin"
    bin_dir.mkdir(parents=True)
    shims = {"drivefem": f'exec "{sys.executable}" -c "import sys; from fem.app.cli import main; '
                         f'sys.argv[0] = \'drivefem\'; sys.exit(main())" "$@"',
             "python": f'exec "{sys.executable}" "$@"'}
    shims["python3"] = shims["python"]
    for name, line in shims.items():
        shim = bin_dir / name
        shim.write_text(f"#!/bin/sh\n{line}\n")
        shim.chmod(0o755)
    return tmp


def repository_changes() -> set[str]:
    """``git status`` of the checkout, one entry per changed or new file (ignored files aside): a
    block that writes through a linked directory into the repository shows up here."""
    try:
        out = subprocess.run(["git", "status", "--porcelain", "--untracked-files=all"], cwd=ROOT,
                             capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return set()
    return set(out.stdout.splitlines()) if out.returncode == 0 else set()


def environment(sandbox: Path) -> dict:
    env = dict(os.environ)
    env["PATH"] = f"{sandbox / '.venv' / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT)] + [p for p in [env.get("PYTHONPATH")] if p])
    env.update(MPLBACKEND="Agg", PYVISTA_OFF_SCREEN="true", PYTHONDONTWRITEBYTECODE="1")
    env.pop("DISPLAY", None)
    return env


def run(block: Block, sandbox: Path) -> subprocess.CompletedProcess:
    """Run the block; with DOCBLOCKS_TIMES=FILE set, append its CPU and wall seconds to FILE (to
    keep the default tier within its budget on a loaded machine, where wall time says little)."""
    before, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    result = _run(block, sandbox)
    log = os.environ.get("DOCBLOCKS_TIMES")
    if log:
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
        with open(log, "a", encoding="utf-8") as fh:
            fh.write(f"{block.where}\t{block.language}\t{'slow' if block.slow else 'default'}\t"
                     f"{cpu:.2f}\t{time.perf_counter() - t0:.2f}\n")
    return result


def _run(block: Block, sandbox: Path) -> subprocess.CompletedProcess:
    if block.language in SHELL:
        argv = ["bash", "-e", "-o", "pipefail", "-c", block.code]
    else:
        script = sandbox / f"doc_block_{block.line}.py"
        script.write_text(block.script(), encoding="utf-8")
        argv = [sys.executable, str(script)]
    return subprocess.run(argv, cwd=sandbox, env=environment(sandbox), stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=block.timeout)


# -- expected output -----------------------------------------------------------------------------

NUM = r"(?<![\w.])([-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?)(?![\w.])"


def _pattern(expected: str) -> re.Pattern:
    """A regex for the shown line: its words literally (a run of spaces matches any), its numbers
    captured."""
    parts = NUMBER.split(expected.strip())
    rx = []
    for k, part in enumerate(parts):
        if k % 2:
            rx.append(NUM)
        else:
            rx.append(r"\s+".join(re.escape(w) for w in part.split(" ") if w) if part.strip() else r"\s*")
            if part[:1].isspace() and k:
                rx.insert(-1, r"\s+")
            if part[-1:].isspace() and k < len(parts) - 1:
                rx.append(r"\s+")
    return re.compile("".join(rx))


def line_matches(expected: str, actual: str, rtol: float, atol: float) -> bool:
    """Whether the shown line (or a piece of a long line wrapped for the page) is in ``actual``, its
    numbers within ``atol + rtol |expected|``."""
    want = [float(x) for x in NUMBER.findall(expected)]
    for m in _pattern(expected).finditer(actual):
        got = [float(x) for x in m.groups()]
        if all(abs(a - e) <= atol + rtol * abs(e) for e, a in zip(want, got)):
            return True
    return False


def check_output(expected: Block, output: str) -> None:
    """Every shown line, in order, in the output (numbers within the block's tolerances); a line of
    the page may be a piece of a longer printed line (wrapped for the page)."""
    rtol, atol = expected.options.get("rtol", 0.0), expected.options.get("atol", 0.0)
    actual = [ln for ln in output.splitlines() if ln.strip()]
    pos = 0
    for want in expected.code.splitlines():
        if not want.strip() or want.strip() in {"...", "…"}:
            continue
        for k in range(pos, len(actual)):
            if line_matches(want, actual[k], rtol, atol):
                pos = k
                break
        else:
            words = NUMBER.sub(" ", want).split()[:3]
            near = [a for a in actual[pos:] if words and all(w in a for w in words)][:1]
            hint = f"; the nearest line printed: {near[0]!r}" if near else ""
            raise AssertionError(f"{expected.where}: the shown line {want!r} is not in the output of "
                                 f"the block above (rtol={rtol}, atol={atol}){hint}\n--- output ---\n{output}")


def check_excerpt(block: Block) -> None:
    """A block marked ``file=PATH`` shows an excerpt of that file: each of its non-blank lines is a
    line of the file (surrounding spaces aside), in the file's order."""
    path = ROOT / block.options["file"]
    if not path.is_file():
        raise AssertionError(f"{block.where}: file={block.options['file']} does not exist")
    lines = [ln.strip() for ln in path.read_text(encoding="utf-8").splitlines()]
    pos = 0
    for want in (ln.strip() for ln in block.code.splitlines()):
        if not want or want in {"...", "…"}:
            continue
        try:
            pos = lines.index(want, pos) + 1
        except ValueError:
            raise AssertionError(f"{block.where}: the line {want!r} is not in {block.options['file']} "
                                 "(after the lines shown before it)") from None


def check_toml(block: Block) -> None:
    try:
        tomllib.loads(block.code)
    except tomllib.TOMLDecodeError as exc:
        raise AssertionError(f"{block.where}: the toml block does not parse: {exc}") from None
