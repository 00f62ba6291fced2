"""The demo's gallery (issue 28): the demo runs every example on the new option spellings, each
figure it draws gets a type and a caption, and the page shows one picture per type with the
command that drew it.  The demo itself is minutes of work (``make demo``); these tests check its
run list and the page writer on figures drawn for the test."""
import struct
import zlib
from pathlib import Path

import pytest

from fem.app.cli import build_parser
from fem.app.demo import _run_list, _shown
from fem.app.gallery import CAPTIONS, Drawn, caption, figure_type, write_gallery
from fem.app.options import FIGURES, plot_target


def _png(path: Path) -> Path:
    """A 1 x 1 PNG (the page writer copies files; it does not read them)."""
    raw = b"\x00\xff\xff\xff"
    chunk = lambda kind, data: (struct.pack(">I", len(data)) + kind + data          # noqa: E731
                                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    return path


def test_demo_runs_on_the_new_spellings_only(tmp_path, capsys):
    """Every command of the demo parses without a deprecation message and its --plot and --render
    paths fit their commands (a file where one figure is drawn, a directory where several)."""
    parser = build_parser()
    runs = _run_list(tmp_path)
    commands = {argv[0] for argv, _ in runs}
    assert {"modal", "forced", "simulate", "render", "campbell", "parametric", "static", "critical-map",
            "stability"} <= commands
    for argv, _ in runs:
        args = parser.parse_args(argv)
        assert not getattr(args, "_old_given", None), argv
        if getattr(args, "plot", None):
            file, folder = plot_target(args.plot, argv[0])           # ModelError when the path does not fit
            form = FIGURES[argv[0]][0]
            assert (file is not None, folder is not None) in {"file": [(True, False)], "directory": [(False, True)]}.get(
                form, [(True, False), (False, True)]), (argv, form)
        if getattr(args, "render", None):
            assert Path(args.render).suffix == "", argv
    assert "deprecated" not in capsys.readouterr().err


@pytest.mark.parametrize("rel, command, kind, expected", [
    ("discrete_seed000_stick_slip_plots/time.png", "simulate", "lumped", "simulate lumped: time"),
    ("discrete_seed000_stick_slip_plots/phase_disk.png", "simulate", "lumped", "simulate lumped: phase"),
    ("rotor_overhung_fan_forced/polar_2_disc_x.png", "forced", "rotor", "forced rotor: polar"),
    ("rotor_overhung_fan_campbell.png", "campbell", "rotor", "campbell rotor: campbell"),
    ("cantilever_modes.png", "modal", "fe", "modal fe: modes"),
    ("render/cantilever/mode_1.gif", "render", "fe", "render fe: animation"),
    ("python/rotor_friswell/rotor_bode.png", "python", "", "python rotor_friswell: rotor_bode"),
    ("validation/plots/rotor_campbell.png", "validate", "", "validate: rotor_campbell"),
])
def test_figure_types_have_captions(tmp_path, rel, command, kind, expected):
    assert figure_type(tmp_path / rel, tmp_path, command, kind) == expected
    assert caption(expected) is not None


def test_gallery_page_one_picture_per_type_with_its_command(tmp_path):
    out, docs = tmp_path / "demo", tmp_path / "docs"
    drawn = [Drawn(_png(out / "a_plots" / "time.png"), "drivefem simulate a.toml --plot a_plots", "simulate lumped: time"),
             Drawn(_png(out / "b_plots" / "time.png"), "drivefem simulate b.toml --plot b_plots", "simulate lumped: time"),
             Drawn(_png(out / "c.png"), "drivefem campbell c.toml --plot c.png", "campbell rotor: campbell"),
             Drawn(_png(out / "d.png"), "drivefem new d.toml --plot d.png", "new lumped: d")]
    page = write_gallery(drawn, out, docs)
    assert page == docs / "gallery.md"
    for root, link in ((out, "gallery"), (docs, "img/gallery")):
        text = (root / "gallery.md").read_text()
        assert text.count("simulate lumped") == 0 and text.count(CAPTIONS["simulate lumped: time"][1]) == 2   # alt + caption
        assert "`drivefem simulate a.toml --plot a_plots`" in text and "b.toml" not in text      # first drawn shown
        assert f"]({link}/simulate_lumped_time.png)" in text and "## Time simulation" in text
        assert "## Without a caption" in text and "new lumped: d" in text            # a new type is visible
        images = sorted(p.name for p in (root / link).iterdir())
        assert images == ["campbell_rotor_campbell.png", "new_lumped_d.png", "simulate_lumped_time.png"]


def test_commands_shown_relative(tmp_path):
    from fem.app.demo import EXAMPLES

    argv = ["forced", str(EXAMPLES / "cantilever.toml"), "--plot", str(tmp_path / "cantilever_forced")]
    assert _shown(argv, tmp_path) == "drivefem forced examples/cantilever.toml --plot cantilever_forced"
