"""One command-line convention (issue 28, docs/cli.md): every command's output options come from
:mod:`fem.app.options` (--json FILE.json, --csv FILE.csv, --plot FILE|DIR, --render DIR,
--html FILE.html, --quiet); a path that does not fit its option is exit 2 before any work and
creates nothing; old spellings warn once and mean the new option; two outputs on one path are
refused; long commands show a progress bar on a terminal and none with --quiet."""
import argparse
import io
import sys
from pathlib import Path

import pytest

from fem.app.cli import build_parser, main
from fem.app.options import DIRECTORY, EITHER, FIGURES, FILE

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"
FE = str(EX / "cantilever.toml")
LUMPED = str(EX / "discrete_seed000_stick_slip.toml")
FAN = str(EX / "rotor_overhung_fan.toml")
JEFFCOTT = str(EX / "rotor_jeffcott_seal.toml")
PARAMETRIC = str(EX / "parametric_drive.toml")

#: the options a command may use to write something (everything else is an input or a setting)
SHARED = {"--json": "FILE.json", "--csv": "FILE.csv", "--render": "DIR", "--html": "FILE.html"}
OWN = {"--vtu", "--h5", "--out", "--report", "--resume", "--gallery", "--scheduler"}   # one command's own outputs


def _commands():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices


def test_every_command_walks_the_one_convention():
    commands = _commands()
    assert {"modal", "forced", "simulate", "campbell", "parametric", "static", "critical-map", "stability",
            "render", "validate", "sweep", "demo", "compare", "schema", "convert"} <= set(commands)
    for name, p in commands.items():
        options = {s: a for a in p._actions for s in a.option_strings if s.startswith("--")}
        shown = {s for s, a in options.items() if a.help != argparse.SUPPRESS}
        for s, metavar in SHARED.items():
            if s in options:
                assert options[s].metavar == metavar, (name, s, options[s].metavar)
        if "--plot" in options:
            form = FIGURES[name][0]
            assert options["--plot"].metavar == {FILE: "FILE.png", DIRECTORY: "DIR", EITHER: "FILE.png|DIR"}[form]
            assert FIGURES[name][1].split(" (")[0] in options["--plot"].help
        assert "--png" not in shown, f"{name}: --png is an old spelling, hidden"
        assert not {s for s in shown if s in ("--plot-dir", "--figures", "--pictures")}, name
        takes_path = {s for s in shown if options[s].metavar and ("FILE" in options[s].metavar or
                                                                  "DIR" in options[s].metavar)}
        assert takes_path <= set(SHARED) | {"--plot"} | OWN, (name, takes_path)
        if name not in ("compare", "schema", "convert"):
            assert "--quiet" in options, f"{name} has no --quiet"
    assert set(FIGURES) <= {n for n, p in commands.items()
                            if any("--plot" in a.option_strings for a in p._actions)}


# a path that does not fit: (argv, fragment of the message, the path that must not appear)
NOT_FITTING = [
    (["modal", FE, "--plot", "{d}/figs"], "figure file name ending in .png", "figs"),
    (["modal", FE, "--render", "{d}/modes.png"], "a directory for", "modes.png"),
    (["render", FE, "--render", "{d}/modes.png"], "a directory for", "modes.png"),
    (["forced", FE, "--plot", "{d}/frf.txt"], "a figure file (.png, .svg, .pdf: the main figure) or a directory",
     "frf.txt"),
    (["simulate", LUMPED, "--plot", "{d}/run.png"], "a directory (drivefem simulate draws several", "run.png"),
    (["campbell", FAN, "--plot", "{d}/c.txt"], "drivefem campbell draws one figure", "c.txt"),
    (["parametric", PARAMETRIC, "--plot", "{d}/chart"], "drivefem parametric draws one figure", "chart"),
    (["static", JEFFCOTT, "--plot", "{d}/sag.csv"], "drivefem static draws one figure", "sag.csv"),
    (["critical-map", JEFFCOTT, "--plot", "{d}/map"], "drivefem critical-map draws one figure", "map"),
    (["stability", JEFFCOTT, "--plot", "{d}/s.json"], "drivefem stability draws one figure", "s.json"),
    (["sweep", LUMPED, "--out", "{d}/points.json"], "a directory for the outputs", "points.json"),
    (["validate", "--report", "{d}/report.md"], "a directory for the validation report", "report.md"),
    (["demo", "--out", "{d}/demo.png"], "a directory for the outputs", "demo.png"),
    (["demo", "--gallery", "{d}/gallery.md"], "a directory for the gallery", "gallery.md"),
    (["simulate", LUMPED, "--json", "{d}/x.h5", "--h5", "{d}/x.h5"], "two outputs would overwrite each other",
     "x.h5"),
]


@pytest.mark.parametrize("argv, message, path", NOT_FITTING, ids=[" ".join(a[:1] + a[2:3]) + f" {p}"
                                                                   for a, _, p in NOT_FITTING])
def test_a_path_that_does_not_fit_is_bad_input_and_creates_nothing(tmp_path, capsys, argv, message, path):
    assert main([a.format(d=tmp_path) for a in argv]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / path).exists() and list(tmp_path.iterdir()) == []


def test_existing_directory_where_a_figure_file_is_needed(tmp_path, capsys):
    assert main(["campbell", FAN, "--plot", str(tmp_path)]) == 2
    assert "this is a directory" in capsys.readouterr().err


@pytest.mark.parametrize("argv, old, new", [
    (["modal", FE, "--png", "{d}/a", "--render", "{d}/b"], "--png", "--render DIR"),
    (["render", FE, "--out", "{d}/modes.png"], "--out", "--render DIR"),
    (["campbell", FAN, "--png", "{d}/c.txt"], "--png", "--plot FILE"),
    (["parametric", PARAMETRIC, "--png", "{d}/chart"], "--png", "--plot FILE"),
])
def test_old_spellings_warn_and_are_checked_like_the_new(tmp_path, capsys, argv, old, new):
    """The old spelling says once which option replaces it and its path is checked by the new rules
    (and naming the old option); giving both spellings is bad input."""
    assert main([a.format(d=tmp_path) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count(f"{old} is deprecated; use {new}") == 1
    assert f"command line: {old} = " in err
    assert list(tmp_path.iterdir()) == []


def test_old_simulate_png_still_draws_the_figures(tmp_path, capsys):
    d = tmp_path / "figs"
    assert main(["simulate", LUMPED, "--png", str(d), "--quiet"]) == 0
    assert "--png is deprecated; use --plot DIR" in capsys.readouterr().err
    assert {"time.png", "energy.png", "phase_disk.png"} <= {p.name for p in d.iterdir()}


class _Tty(io.StringIO):
    def isatty(self):
        return True


@pytest.mark.parametrize("argv, bar", [
    (["simulate", LUMPED], "simulate"),
    (["validate", "--case", "cam-table-6-1"], "validation"),
])
def test_progress_on_a_terminal_and_quiet(monkeypatch, capsys, argv, bar):
    """With the bar's 2 s delay set to 0 (DRIVEFEM_PROGRESS_DELAY) the command draws its bar on a
    terminal's stderr; --quiet draws none, and neither does a stderr that is not a terminal."""
    monkeypatch.setenv("DRIVEFEM_PROGRESS_DELAY", "0")
    for extra, tty, shown in (([], True, True), (["--quiet"], True, False), ([], False, False)):
        err = _Tty() if tty else io.StringIO()
        monkeypatch.setattr(sys, "stderr", err)
        assert main(argv + extra) == 0
        assert (f"{bar}:" in err.getvalue() and "%|" in err.getvalue()) is shown, (extra, tty, err.getvalue()[-300:])
    capsys.readouterr()


@pytest.mark.slow
@pytest.mark.parametrize("argv, bar", [
    (["parametric", PARAMETRIC], "parametric"),
    (["campbell", FAN], "campbell"),
    (["stability", JEFFCOTT], "stability"),
    (["render", FE, "--render", "{d}/r", "--mode", "1"], "render"),
])
def test_progress_of_the_long_commands_in_a_pty(tmp_path, argv, bar):
    """The long commands in a real pseudo-terminal (a new process): a bar appears."""
    import os
    import pty
    import subprocess
    import threading

    main_fd, child_fd = pty.openpty()
    env = dict(os.environ, DRIVEFEM_PROGRESS_DELAY="0", PYTHONPATH=str(ROOT))
    chunks = []

    def read():                        # drained while the command runs: a full pty would block it
        while True:
            try:
                data = os.read(main_fd, 65536)
            except OSError:
                return
            if not data:
                return
            chunks.append(data)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    proc = subprocess.run([sys.executable, "-m", "fem.app.cli"] + [a.format(d=tmp_path) for a in argv],
                          stdin=child_fd, stdout=subprocess.DEVNULL, stderr=child_fd, env=env, timeout=600)
    os.close(child_fd)
    reader.join(timeout=10)
    os.close(main_fd)
    text = b"".join(chunks).decode(errors="replace")
    assert proc.returncode == 0, text[-2000:]
    assert f"{bar}:" in text and "%|" in text, text[-1000:]


def test_docs_cli_page_lists_every_plot_form_and_old_spelling():
    """docs/cli.md's tables follow fem.app.options: a command's --plot form and every old spelling."""
    text = (ROOT / "docs" / "cli.md").read_text()
    for name, (form, _) in FIGURES.items():
        assert f"| `{name}` | {form} |" in text, name
    for name, p in _commands().items():
        for a in p._actions:
            if a.help == argparse.SUPPRESS and a.option_strings and hasattr(a, "new"):
                assert f"| `{name} {a.option_strings[0]}" in text and a.new.split()[0] in text, (name, a.option_strings)


@pytest.mark.slow
@pytest.mark.parametrize("argv, title, axes", [
    (["simulate", LUMPED], "seed 000: stick-slip", {"time t [s]", "force [N | N m]"}),
    (["forced", str(EX / "forced_torsion.toml")], "Clamped shaft with a harmonic end moment",
     {"frequency f [Hz]", "amplitude [rad]", "phase lag [deg]"}),
])
def test_html_is_one_self_contained_file(tmp_path, capsys, argv, title, axes):
    """--html (time histories, FRF): one file with plotly inside (no script loaded from elsewhere), the
    model's title and the axes with units."""
    pytest.importorskip("plotly")
    import json
    import re

    page = tmp_path / "figure.html"
    assert main(argv + ["--html", str(page), "--quiet"]) == 0
    text = page.read_text()
    assert "<script src=" not in text and "Plotly.newPlot" in text
    titles = {json.loads(f'"{t}"') for t in re.findall(r'"title":\{"text":"((?:[^"\\]|\\.)*)"', text)}
    assert axes <= titles and any(title in t for t in titles), sorted(titles)
    capsys.readouterr()
