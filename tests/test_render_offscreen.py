"""Off-screen rendering: pixels of the pictures (not just files), GIFs, 3D models, and
what happens when rendering is impossible.  (The pixel check of issue 6 case 3 runs as the
validation case ``render-pixels`` in tests/test_validation_catalogue.py.)

Without a working VTK the image tests skip, unless DRIVEFEM_REQUIRE_RENDER=1 (CI sets
it) turns the skip into a failure, so a broken recipe cannot hide behind a skip."""
import os

import numpy as np
import pytest

from discrete.errors import ModelError
from fem import assemble, modal_analysis
from validation.builders import uniform

render = pytest.importorskip("fem.render")


@pytest.fixture(scope="module")
def can_render():
    ok, msg = render.available()
    if not ok:
        if os.environ.get("DRIVEFEM_REQUIRE_RENDER") == "1":
            pytest.fail(f"rendering required but unavailable: {msg}")
        pytest.skip(msg)
    return True


@pytest.fixture(scope="module")
def cantilever():
    fe = assemble(uniform("bending", 1.5, 40, d=0.05, supports=[(0.0, "clamped")]))
    return fe, modal_analysis(fe.system, 3)


def test_picture_not_blank_and_modes_differ(can_render, cantilever):
    from fem.render.pixels import body_mask, difference_fraction

    fe, res = cantilever
    imgs = [render.render_image(fe, res, r) for r in range(3)]
    for img in imgs:
        assert img.shape == (600, 1200, 3)
        assert 0.01 < body_mask(img).mean() < 0.5          # a shaft, not an empty or flooded frame
    assert difference_fraction(imgs[1], imgs[2]) > 0.02
    # mode 3 has two zero crossings: the centre line crosses the root row twice
    from fem.render.pixels import centreline

    cols, rows = centreline(imgs[2])
    rel = rows - rows[:5].mean()
    big = rel[np.abs(rel) > 10]
    assert np.count_nonzero(np.diff(np.sign(big))) == 2


def test_render_modes_files_and_gif(can_render, cantilever, tmp_path):
    import imageio.v2 as imageio

    fe, res = cantilever
    paths = render.render_modes(fe, res, tmp_path, modes=[2], gif=True)
    assert [p.name for p in paths] == ["mode02.png", "mode02.gif"]
    frames = imageio.mimread(paths[1])
    assert len(frames) == 24
    from fem.render.pixels import difference_fraction

    assert difference_fraction(frames[0], frames[12]) > 0.02          # opposite phases differ
    assert difference_fraction(frames[0], frames[23]) < difference_fraction(frames[0], frames[12])


def test_torsion_and_axial_pictures(can_render, tmp_path):
    from fem.render.pixels import body_mask, difference_fraction

    out = {}
    for physics in ("torsion", "axial"):
        fe = assemble(uniform(physics, 1.0, 12, d=0.05, supports=[(0.0, "clamped")]))
        res = modal_analysis(fe.system, 2)
        out[physics] = [render.render_image(fe, res, r) for r in range(2)]
        assert body_mask(out[physics][0]).mean() > 0.01
        assert difference_fraction(*out[physics]) > 0.01


def test_solid_pictures(can_render, tmp_path):
    from fem.render.pixels import body_mask, difference_fraction
    from fem.solid import ShaftMeshSpec, build_solid, solid_modal

    solid = build_solid(uniform("bending", 0.3, 4, d=0.1, supports=[(0.0, "clamped")]), ShaftMeshSpec(n_quarter=2))
    res = solid_modal(solid, 3)
    paths = render.render_modes(solid, res, tmp_path)
    assert len(paths) == 3
    import imageio.v2 as imageio

    imgs = [imageio.imread(p)[..., :3] for p in paths]
    assert all(body_mask(i).mean() > 0.05 for i in imgs)
    assert difference_fraction(imgs[0], imgs[2]) > 0.02      # bending vs torsion


def test_bad_mode_index_and_directory(cantilever, tmp_path):
    fe, res = cantilever
    with pytest.raises(ModelError, match="mode number from 1 to 3"):
        render.render_modes(fe, res, tmp_path, modes=[4])
    with pytest.raises(ModelError, match="mode number"):
        render.render_modes(fe, res, tmp_path, modes=[0])
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ModelError, match="render output directory"):
        render.render_modes(fe, res, blocker / "pics")


def test_unavailable_still_writes_data(tmp_path, monkeypatch):
    """With rendering impossible the command still writes its data files and reports why."""
    from pathlib import Path

    monkeypatch.setenv("DRIVEFEM_RENDER", "off")
    try:
        render.available(refresh=True)
        model = Path(__file__).resolve().parent.parent / "examples" / "cantilever.toml"
        from fem.study import Study

        rep = render.render_study(Study.load(model), tmp_path / "out", n_modes=2)
        assert not rep.rendered and "DRIVEFEM_RENDER" in rep.message
        assert sorted(p.name for p in rep.data_files) == ["modes.csv", "modes.json", "modes.vtu"]
        assert all(p.is_file() for p in rep.data_files) and rep.images == []
        with pytest.raises(render.RenderUnavailable):
            fe = assemble(uniform("torsion", 1.0, 4, d=0.05, supports=[(0.0, "clamped")]))
            render.render_modes(fe, modal_analysis(fe.system, 1), tmp_path / "x")
    finally:
        monkeypatch.delenv("DRIVEFEM_RENDER")
        render.available(refresh=True)


def test_missing_library_message_names_package(monkeypatch):
    from fem.render import backend

    for window in (backend.OSMESA, backend.EGL):
        monkeypatch.setitem(backend.WINDOW_LIBRARIES, window, (("libdoesnotexist-gl.so.9", "libgl-fake1"),))
        monkeypatch.setenv("VTK_DEFAULT_OPENGL_WINDOW", window)
        ok, msg = backend._diagnose()
        assert not ok
        assert "libdoesnotexist-gl.so.9" in msg and "libgl-fake1" in msg and "apt-get install" in msg


def test_headless_window_choice(monkeypatch):
    """OSMesa (one package) is preferred; EGL when only EGL is installed."""
    from fem.render import backend

    monkeypatch.setattr(backend, "_loads", lambda lib: lib != "libOSMesa.so.8")
    assert backend.headless_window() == backend.EGL
    monkeypatch.setattr(backend, "_loads", lambda lib: False)
    assert backend.headless_window() == backend.OSMESA
    monkeypatch.setattr(backend, "_loads", lambda lib: True)
    assert backend.headless_window() == backend.OSMESA
