"""What ``drivefem render MODEL.toml --modes N --out DIR [--gif]`` does, as a function the
command calls: modal analysis, data files (VTU of the mode shapes, CSV/JSON frequency table)
and then the images.  Rendering problems never cost the data files."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from discrete.errors import ModelError


@dataclass
class RenderReport:
    data_files: list[Path] = field(default_factory=list)
    images: list[Path] = field(default_factory=list)
    rendered: bool = False
    message: str = ""

    def to_dict(self) -> dict:
        return {"data_files": [str(p) for p in self.data_files], "images": [str(p) for p in self.images],
                "rendered": self.rendered, "message": self.message}


def render_study(study, out_dir, n_modes: int | None = None, gif: bool = False,
                 modes: list[int] | None = None) -> RenderReport:
    """Run the modal analysis of an FE model file (a :class:`fem.study.Study`) and write
    ``modes.vtu``, ``modes.csv``, ``modes.json`` and the PNG/GIF files into ``out_dir``.
    ``report.rendered`` is False (with ``report.message`` naming the missing library) if VTK
    cannot render here."""
    from ..output.mesh import ensure_directory, write_modes
    from ..output.tablefile import write_modal_table
    from .backend import RenderUnavailable
    from .images import mode_indices, render_modes

    if study.kind != "fe":
        raise ModelError("drivefem render", "model", str(study.path), "an FE model file (with [[segment]] tables; "
                         f"this is a {study.kind} model)")
    out = ensure_directory(out_dir, "render output directory")
    res = study.modal(n_modes)
    fe = study.fe_model
    mode_indices(res, modes)            # a bad mode number is an error before anything is written
    rep = RenderReport()
    rep.data_files.append(write_modes(fe, res, out / "modes.vtu"))
    rep.data_files.append(write_modal_table(res, out / "modes.csv"))
    rep.data_files.append(write_modal_table(res, out / "modes.json"))
    try:
        rep.images = render_modes(fe, res, out, modes=modes, gif=gif)
        rep.rendered = True
        rep.message = f"{len(rep.images)} image(s) written"
    except RenderUnavailable as exc:
        rep.message = str(exc)
    return rep
