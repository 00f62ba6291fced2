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
                 modes: list[int] | None = None, progress=None) -> RenderReport:
    """Run the modal analysis of an FE or rotor model file (a :class:`fem.study.Study`) and write
    the data files and the PNG/GIF pictures into ``out_dir`` (FE: ``modes.vtu``, ``modes.csv``,
    ``modes.json``; rotor: :func:`render_rotor_study`).  ``report.rendered`` is False (with
    ``report.message`` naming the missing library) if VTK cannot render here."""
    from ..output.mesh import ensure_directory, write_modes
    from ..output.tablefile import write_modal_table
    from .backend import RenderUnavailable
    from .images import mode_indices, render_modes

    if study.kind == "rotor":
        return render_rotor_study(study, out_dir, n_modes, gif, modes, progress)
    if study.kind != "fe":
        raise ModelError("drivefem render", "model", str(study.path), "an FE or rotor model file (with [[segment]] "
                         f"tables or a [rotor] table; this is a {study.kind} model)")
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


def render_rotor_study(study, out_dir, n_modes: int | None = None, gif: bool = False, modes: list[int] | None = None,
                       progress=None) -> RenderReport:
    """The complex modes of a rotor file at its ``[analysis]`` speed: ``modes.json`` (schema
    drivefem.modal), ``modes.csv`` (frequency, damping, whirl per mode) and, for every lateral mode
    (or the 1-based ``modes``), ``modeNN_<whirl>.png`` (and ``.gif`` with ``gif``): the whirling
    shaft in 3D with its orbits, the whirl direction marked (:mod:`fem.rotor.render`)."""
    import numpy as np

    from ..output import contract, write_csv, write_json
    from ..output.mesh import ensure_directory
    from ..rotor.render import render_whirl, render_whirl_gif
    from .backend import RenderUnavailable

    out = ensure_directory(out_dir, "render output directory")
    res = study.modal(n_modes)
    if modes is not None:
        for m in modes:
            if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or not 1 <= m <= res.n_modes:
                raise ModelError("render", "mode", m, f"a mode number from 1 to {res.n_modes} (the modes computed)")
        picks = [int(m) - 1 for m in modes]
        bad = [r + 1 for r in picks if res.rigid[r] or res.kind[r] != "lateral"]
        if bad:
            raise ModelError("render", "mode", bad[0], "a lateral flexible mode (axial, torsional and rigid-body modes "
                             "have no whirl to draw): " + ", ".join(str(r + 1) for r in range(res.n_modes)
                                                                    if not res.rigid[r] and res.kind[r] == "lateral"))
    else:
        picks = [r for r in range(res.n_modes) if not res.rigid[r] and res.kind[r] == "lateral"]
    rep = RenderReport()
    rep.data_files.append(write_json(out / "modes.json", contract.payload("modal", study, contract.modal_data(study, res))))
    head = ["mode", "omega_d_rad_s", "f_d_hz", "damping_ratio", "log_decrement", "whirl", "kind"]
    rows = [[r + 1, res.omega_damped_rad_s[r], res.frequencies_hz[r], res.damping_ratio[r],
             res.log_decrement[r] if np.isfinite(res.log_decrement[r]) else "", res.whirl[r], res.kind[r]]
            for r in range(res.n_modes)]
    write_csv(out / "modes.csv", head, rows)
    rep.data_files.append(out / "modes.csv")
    total = len(picks) * (2 if gif else 1)
    try:
        for k, r in enumerate(picks):
            stem = f"mode{r + 1:02d}_{res.whirl[r]}"
            rep.images.append(render_whirl(study.rotor, res, r, out / f"{stem}.png", title=study.title))
            if progress is not None:
                progress(len(rep.images), total)
            if gif:
                rep.images.append(render_whirl_gif(study.rotor, res, r, out / f"{stem}.gif", title=study.title))
                if progress is not None:
                    progress(len(rep.images), total)
        rep.rendered = True
        rep.message = (f"{len(rep.images)} image(s) written: whirl of the lateral modes at "
                       f"{res.speed_rad_s * 30 / np.pi:.6g} rev/min" if picks else
                       "no lateral flexible mode among the modes computed: no picture (ask for more with --modes)")
    except RenderUnavailable as exc:
        rep.message = str(exc)
    return rep
