"""The example model files the fuzzer starts from: their kind, the commands that apply, cheap bases.

The kind is decided here from the tables a file has (independently of the package, whose own
detection is under test).  A *cheap base* is the example with its run-time knobs turned down
(shorter ``t_end``, fewer sweep points, fewer harmonics, ...) so that a mutation that the package
accepts still finishes in seconds; a mutation of one of those keys overrides the cheap value, so
every key is still fuzzed.  The original examples are run too, as controls.
"""
from __future__ import annotations

import copy
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

COMMANDS = ("modal", "forced", "simulate", "compare", "sweep", "render", "parametric", "campbell")

#: Commands that apply to each kind of model file (the first one is the file's main command); every command
#: that accepts the kind (measured: each example's cheap base exits 0 through these), plus the commands its
#: optional tables open (:data:`BY_TABLE`).
APPLICABLE = {
    "fe_modal": ("modal", "render"),
    "fe_forced": ("forced", "modal", "render"),
    "lumped_modal": ("modal",),
    "lumped_forced": ("forced", "modal"),
    "nonsmooth": ("simulate", "modal"),
    "hybrid": ("simulate", "modal"),
    "steady": ("forced", "modal"),
    "sweep": ("sweep", "forced", "modal"),
    "drive_modal": ("modal", "compare"),
    "drive_forced": ("forced", "modal", "compare"),
    "parametric": ("parametric", "modal"),
    "rotor": ("modal", "campbell"),
    "rotor_campbell": ("campbell", "modal"),
    "rotor_forced": ("forced", "modal", "campbell"),
    "rotor_simulate": ("simulate", "modal", "campbell"),
    "train": ("modal", "campbell"),
    "train_campbell": ("campbell", "modal"),
    "train_forced": ("forced", "modal"),
    "train_simulate": ("simulate", "modal"),
    "train_parametric": ("parametric", "modal"),
    "other": ("modal", "forced", "simulate"),
}
#: A table that makes one more command apply: a [simulation] table (a steady or sweep file also simulates),
#: a rotor's [unbalance_response] (forced) and [run_up] (simulate).
BY_TABLE = {"simulation": "simulate", "unbalance_response": "forced", "run_up": "simulate"}

_NONSMOOTH_TABLES = {"impact", "friction", "gap", "one_sided", "distributed_friction", "initial",
                     "reduction", "simulation", "driver", "force"}


def kind_of(doc: dict) -> str:
    """The kind of a parsed model file, from the tables it has."""
    atype = doc.get("analysis", {}).get("type") if isinstance(doc.get("analysis"), dict) else None
    forced = atype == "forced"
    if any(k in doc for k in ("train", "shaft", "mesh", "coupling")):
        if "simulation" in doc and atype in (None, "simulate"):
            return "train_simulate"
        return {"campbell": "train_campbell", "forced": "train_forced", "simulate": "train_simulate",
                "parametric": "train_parametric"}.get(atype, "train_forced" if "steady" in doc else "train")
    if "rotor" in doc:
        return {"campbell": "rotor_campbell", "forced": "rotor_forced", "simulate": "rotor_simulate"}.get(atype, "rotor")
    if atype == "parametric":
        return "parametric"
    if "drive" in doc:
        return "drive_forced" if forced else "drive_modal"
    if "sweep" in doc:
        return "sweep"
    if "steady" in doc:
        return "steady"
    if "segment" in doc:
        if _NONSMOOTH_TABLES & set(doc):
            return "hybrid"
        return "fe_forced" if forced else "fe_modal"
    if "body" in doc:
        if "simulation" in doc:
            return "nonsmooth"
        return "lumped_forced" if forced else "lumped_modal"
    return "other"


@dataclass
class Example:
    """One example model file: its name, text, parsed document, kind and cheap base."""

    name: str
    path: Path
    text: str
    doc: dict
    kind: str
    cheap: dict = field(repr=False)
    cheap_notes: list[str] = field(default_factory=list)

    @property
    def commands(self) -> tuple[str, ...]:
        base = APPLICABLE[self.kind]
        return base + tuple(dict.fromkeys(c for t, c in BY_TABLE.items() if t in self.doc and c not in base))

    @property
    def wrong_commands(self) -> tuple[str, ...]:
        return tuple(c for c in COMMANDS if c not in self.commands)


def load_examples(root: Path) -> list[Example]:
    """Every ``examples/*.toml`` of the source tree ``root``, sorted by name."""
    out = []
    for p in sorted((Path(root) / "examples").glob("*.toml")):
        text = p.read_text(encoding="utf-8")
        doc = tomllib.loads(text)
        cheap, notes = cheapen(doc)
        out.append(Example(p.stem, p, text, doc, kind_of(doc), cheap, notes))
    return out


def _num(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def cheapen(doc: dict) -> tuple[dict, list[str]]:
    """A copy of ``doc`` with its run-time knobs turned down, and a note per change.

    Only keys that exist are touched, so the rules survive changes of the examples."""
    d = copy.deepcopy(doc)
    notes: list[str] = []

    def cap(table: dict, key: str, limit, where: str, scale: float | None = None):
        v = table.get(key)
        if not _num(v):
            return
        new = v * scale if scale is not None else min(v, limit)
        if scale is None and isinstance(v, int):
            new = int(new)
        if new != v:
            table[key] = new
            notes.append(f"{where}{key}: {v!r} -> {new!r}")

    sim = d.get("simulation")
    if isinstance(sim, dict):
        cap(sim, "t_end", None, "[simulation] ", scale=0.25)
        cap(sim, "samples", 500, "[simulation] ")
    an = d.get("analysis")
    if isinstance(an, dict) and isinstance(an.get("sweep_hz"), dict):
        cap(an["sweep_hz"], "points", 25, "[analysis] sweep_hz.")
    st = d.get("steady")
    if isinstance(st, dict):
        cap(st, "harmonics", 5, "[steady] ")
        for key in ("omega", "z"):
            rng = st.get(key)
            if isinstance(rng, list) and len(rng) == 2 and all(_num(x) for x in rng):
                new = [rng[0], rng[0] + 0.25 * (rng[1] - rng[0])]
                st[key] = new
                notes.append(f"[steady] {key}: {rng!r} -> {new!r}")
    sw = d.get("sweep")
    if isinstance(sw, dict):
        cap(sw, "periods", 20, "[sweep] ")
        grid = sw.get("grid")
        if isinstance(grid, dict):
            for axis, spec in grid.items():
                if isinstance(spec, list) and len(spec) > 2:
                    grid[axis] = spec[:2]
                    notes.append(f"[sweep] grid.{axis}: {len(spec)} values -> 2")
                elif isinstance(spec, dict):
                    cap(spec, "points", 2, f"[sweep] grid.{axis}.")
    for table in ("campbell", "forced", "parametric"):       # train files: fewer speeds
        t = d.get(table)
        if isinstance(t, dict):
            for key in ("speeds", "speeds_rpm"):
                if isinstance(t.get(key), dict):
                    cap(t[key], "points", 5, f"[{table}] {key}.")
            if isinstance(t.get("depth"), dict):
                cap(t["depth"], "points", 2, f"[{table}] depth.")
    dr = d.get("drive")
    if isinstance(dr, dict):
        cap(dr, "n", 60, "[drive] ")
    ru = d.get("run_up")
    if isinstance(ru, dict):
        cap(ru, "duration", None, "[run_up] ", scale=0.25)
        cap(ru, "modes", 8, "[run_up] ")
    return d, notes
