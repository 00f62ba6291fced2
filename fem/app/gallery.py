"""The gallery page of ``drivefem demo``: one picture of every figure type the demo drew, with a
caption and the command that drew it (docs/gallery.md, images in docs/img/gallery/).

A figure's *type* comes from how the demo named it (:func:`figure_type`): the command, the kind of
model file and the figure's file name with model-specific parts (body names, probe numbers)
removed.  Every type has a caption in :data:`CAPTIONS`; a figure type without one is listed at the
end with its file name, and the tests fail on it, so that a new kind of figure gets a caption."""
from __future__ import annotations

import re
import shutil
from dataclasses import dataclass
from pathlib import Path

IMAGE_SUFFIXES = (".png", ".gif")


@dataclass
class Drawn:
    """One figure the demo wrote: its file, the command line that wrote it (as shown), and its type."""

    path: Path
    command: str
    kind: str


def figure_type(path: Path, out: Path, command: str, kind: str) -> str:
    """``command kind: name`` of a figure written under the demo directory ``out``."""
    rel = path.relative_to(out)
    name = re.sub(r"\.(png|gif)$", "", rel.name)
    if rel.parts[0] == "python":
        example = rel.parts[1] if len(rel.parts) > 2 else rel.stem
        return f"python {re.sub(r'[.]py$', '', example)}: {name if len(rel.parts) > 2 else 'figure'}"
    if rel.parts[0] == "validation":
        return f"validate: {name}"
    if rel.parts[0] == "render":
        return f"render {kind}: {'animation' if rel.suffix == '.gif' else 'picture'}"
    name = re.sub(r"^phase_.*$", "phase", name)
    name = re.sub(r"^polar_\d+_.*$", "polar", name)
    if len(rel.parts) == 1:                            # <stem>_<what>.png next to the JSON
        name = name.rsplit("_", 1)[-1] if "_" in name else name
    return f"{command} {kind}: {name}"


#: caption per figure type: (section, caption)
CAPTIONS = {
    "modal fe: modes": ("Modes", "Mode shapes of an FE shaft, one panel per mode, above a side view of the shaft "
                                  "with its segments, supports and discs"),
    "modal rotor: orbits": ("Rotordynamics", "Orbits of the first lateral mode of a rotor along the shaft, "
                                             "coloured by the node's position (colour bar)"),
    "render fe: picture": ("Modes", "Off-screen 3D picture of a mode (pyvista)"),
    "render fe: animation": ("Modes", "Animated mode, one period (GIF)"),
    "render rotor: picture": ("Rotordynamics", "Whirl of a rotor mode in 3D: orbits, discs, bearings, whirl direction"),
    "render rotor: animation": ("Rotordynamics", "Whirl animation of a rotor mode (GIF)"),
    "forced fe: frf": ("Forced response", "Harmonic response of an FE model: amplitude with quantity and unit, phase "
                                          "lag unwrapped along the sweep"),
    "forced lumped: frf": ("Forced response", "Harmonic response of a lumped model"),
    "forced drive: frf": ("Forced response", "Harmonic response of a drive of regular structure: shaft stations and "
                                             "mechanism outputs in their own panels, markers at the computed "
                                             "frequencies"),
    "forced lumped: afc": ("Forced response", "Nonlinear amplitude-frequency curve ([steady]): stable branch solid, "
                                              "unstable dashed, folds, backbone"),
    "forced fe: loads": ("Forced response", "Amplitudes of the named outputs (section loads, reactions) against "
                                            "frequency"),
    "forced lumped: loads": ("Forced response", "Amplitudes of the named outputs (element loads, reactions) against "
                                                "frequency"),
    "forced rotor: bode": ("Rotordynamics", "Bode plot of the unbalance response: peaks with half-power band and "
                                            "amplification factor, phase unwrapped, operating range"),
    "forced rotor: polar": ("Rotordynamics", "Polar (Nyquist) plot of the unbalance response, labelled in rev/min"),
    "forced rotor: loads": ("Rotordynamics", "Bearing reactions and section loads of the unbalance response"),
    "simulate lumped: time": ("Time simulation", "Time histories of the named outputs (relative twist and deflection "
                                                 "of the elements, slip speeds, element loads), events marked"),
    "simulate lumped: phase": ("Time simulation", "Phase portrait of a body"),
    "simulate lumped: energy": ("Time simulation", "Energy balance: E(t) - E(0) against the work of the "
                                                   "non-conservative forces"),
    "simulate hybrid: field": ("Time simulation", "Space-time map of the FE field of a hybrid model (colour bar)"),
    "simulate hybrid: coupling": ("Time simulation", "Hybrid model: history of the DOFs where the nonsmooth elements "
                                                     "act, events marked"),
    "simulate hybrid: loads": ("Time simulation", "Hybrid model: named outputs (element loads, reactions)"),
    "simulate hybrid: energy": ("Time simulation", "Hybrid model: energy balance"),
    "simulate rotor: run_up": ("Rotordynamics", "Run-up through a rub: orbit radius per probe (the clearance on "
                                                "the probe it applies to), rub forces"),
    "simulate rotor: run_up_orbits": ("Rotordynamics", "Orbits at the rub during the run-up with the clearance circle"),
    "simulate rotor: run_up_bode": ("Rotordynamics", "Run-up Bode plot: 1x tracking filter against the steady "
                                                     "unbalance response"),
    "simulate rotor: cascade": ("Rotordynamics", "Cascade (waterfall) of the run-up's whirl spectrum with the 1x "
                                                 "and 0.5x lines"),
    "simulate rotor: whirl_onset": ("Rotordynamics", "Subsynchronous whirl amplitude against speed, onset marked"),
    "simulate rotor: loads": ("Rotordynamics", "Bearing reactions and rub forces of the run-up"),
    "campbell rotor: campbell": ("Rotordynamics", "Campbell diagram: critical speeds (forward) and backward "
                                                  "crossings apart, operating range, log decrements"),
    "parametric lumped: parametric": ("Parametric vibrations", "Parametric stability chart (Floquet): tongues "
                                                               "shaded by growth rate, edges, damping threshold"),
    "static rotor: static": ("Rotordynamics", "Static sag under gravity with the load each bearing carries"),
    "critical-map rotor: map": ("Rotordynamics", "Undamped critical speed map with the model's bearings overlaid"),
    "stability rotor: stability": ("Rotordynamics", "Log decrement against speed (stability threshold) and the API "
                                                    "Level I screening"),
    "campbell train: campbell": ("Geared trains", "Campbell diagram of a geared train, each shaft at its own "
                                                  "speed, with the 1x lines of every shaft and the tooth-pass line"),
    "parametric train: parametric": ("Geared trains", "Floquet chart of the mesh-stiffness variation: max "
                                                      "|multiplier| over speed and depth, edges by root finding"),
    "simulate train: mesh_forces": ("Geared trains", "Force of every connection (gear mesh) against time, contact "
                                                     "events marked"),
    "simulate train: bearings": ("Geared trains", "Radial force of every bearing of a geared train against time"),
    "simulate train: phase": ("Geared trains", "Each mesh's deflection against its rate (phase portrait)"),
    "python absorber_design: absorber_afc": ("Python examples", "Tuned vibration absorber: amplitude-frequency "
                                                                "curves"),
    "python cam_report: cam_laws": ("Python examples", "Cam laws and their transfer functions"),
    "python cam_report: cam_follower": ("Python examples", "Elastic cam follower over a cycle"),
    "python cam_report: cam_accumulation": ("Python examples", "Accumulation factor of cam cycles"),
    "python cam_report: cam_residual": ("Python examples", "Residual vibration factor of an acceleration ramp"),
    "python drive_spectrum: figure": ("Python examples", "Spectrum of a regular drive against the number of "
                                                         "mechanisms, pass and stop bands"),
    "python hybrid_afc_figure: figure": ("Python examples", "Amplitude-frequency curves of hybrid FE models"),
    "python parametric_chart: parametric_book": ("Python examples", "The textbook's Fig. 7.4 recomputed"),
    "python parametric_chart: parametric_drive": ("Python examples", "Stability chart of a two-mass drive"),
    "python geared_trains: geared_two_stage_loads": ("Python examples", "Dynamic load factor of both meshes and "
                                                                        "peak bearing forces over the motor speed"),
    "python geared_trains: geared_two_stage_rattle": ("Python examples", "Two-stage gearbox in time with its "
                                                                         "backlash: mesh forces and contact events"),
    "python geared_trains: geared_compressor_campbell": ("Python examples", "Campbell diagram of a geared "
                                                                            "compressor train"),
    "python geared_trains: geared_rattle_afc": ("Python examples", "Gear-rattle curve by harmonic balance, "
                                                                   "shooting and the exact orbits"),
    "python geared_trains: geared_mesh_parametric": ("Python examples", "Floquet chart of a mesh-stiffness "
                                                                        "variation"),
    "python rotor_friswell: rotor_static": ("Python examples", "Static deflection of Friswell's rotor"),
    "python rotor_friswell: rotor_whirl_forward": ("Python examples", "3D whirl of a forward mode of Friswell's "
                                                                      "rotor (pyvista)"),
    "python rotor_friswell: rotor_whirl_backward": ("Python examples", "3D whirl of a backward mode of Friswell's "
                                                                       "rotor (pyvista)"),
    "python rotor_friswell: rotor_whirl": ("Python examples", "Whirl animation of a mode of Friswell's rotor (GIF)"),
    "python rotor_friswell: rotor_campbell": ("Python examples", "Campbell diagram of Friswell's damped rotor"),
    "python rotor_friswell: rotor_bode": ("Python examples", "Bode plot of Friswell's rotor"),
    "python rotor_friswell: rotor_polar": ("Python examples", "Polar plot of Friswell's rotor"),
    "python rotor_friswell: rotor_orbits": ("Python examples", "Orbits of Friswell's rotor"),
    "python rotor_friswell: rotor_journal_campbell": ("Python examples", "Campbell diagram on journal bearings"),
    "python rotor_friswell: rotor_critical_map": ("Python examples", "Critical speed map of Friswell's rotor"),
    "python rotor_friswell: rotor_stability": ("Python examples", "Stability of Friswell's rotor with a seal"),
    "python ross_compressor: rotor_ross_compressor_campbell": ("Python examples", "Campbell diagram of a compressor "
                                                                                  "imported from ROSS"),
    "python seed002_phase_portraits: figure": ("Python examples", "Phase portraits of seed 002 (zero tension red)"),
    "python subharmonic_third: figure": ("Python examples", "The 1/3 subharmonic of a cubic spring: time run "
                                                            "against harmonic balance"),
}
SECTIONS = ("Modes", "Forced response", "Time simulation", "Rotordynamics", "Geared trains", "Parametric vibrations",
            "Python examples", "Validation report")


def caption(kind: str) -> tuple[str, str] | None:
    if kind.startswith("validate: "):
        return "Validation report", f"Validation report: {kind.split(': ', 1)[1].replace('_', ' ')}"
    return CAPTIONS.get(kind)


def write_gallery(drawn: list[Drawn], out: Path, docs: Path | None = None) -> Path:
    """Write ``gallery.md`` (one picture per figure type, first drawn first) into ``out`` with the
    images beside it in ``gallery/``; with ``docs`` also ``docs/gallery.md`` and ``docs/img/gallery/``."""
    first: dict[str, Drawn] = {}
    for d in drawn:
        first.setdefault(d.kind, d)
    targets = [(out, out / "gallery", "gallery")]
    if docs is not None:
        targets.append((docs, docs / "img" / "gallery", "img/gallery"))
    page = None
    for root, images, link in targets:
        images.mkdir(parents=True, exist_ok=True)
        for old in images.glob("*"):
            if old.suffix in IMAGE_SUFFIXES:
                old.unlink()
        by_section: dict[str, list[str]] = {s: [] for s in SECTIONS}
        missing = []
        for kind, d in first.items():
            name = re.sub(r"[^A-Za-z0-9]+", "_", kind).strip("_") + d.path.suffix
            shutil.copyfile(d.path, images / name)
            cap = caption(kind)
            if cap is None:
                missing.append(kind)
                cap = ("Validation report", kind)
            section, text = cap
            by_section.setdefault(section, []).append(f"![{text}]({link}/{name})\n\n{text}.  \n`{d.command}`\n")
        lines = ["# Gallery", "", "Every kind of figure `drivefem demo` draws, one example each, generated by the demo "
                 "itself (`drivefem demo --gallery docs`, the figures copied to `docs/img/gallery/`).  Each caption "
                 "gives the command that drew the figure; [Command line](cli.md) describes the options.", ""]
        for section, items in by_section.items():
            if items:
                lines += [f"## {section}", ""] + items
        if missing:
            lines += ["## Without a caption", "", "Figure types the gallery has no caption for: "
                      + ", ".join(missing), ""]
        page = root / "gallery.md"
        page.write_text("\n".join(lines))
    return page
