"""Every hybrid example runs (shortened) and follows the simulate JSON contract."""
import json
import pathlib
import tomllib

import pytest

from fem.modelfile.schema.document import detect_kind
from fem.study import simulate

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("hybrid_*.toml"))


def test_one_example_per_validation_case():
    names = {p.stem for p in EXAMPLES}
    assert {"hybrid_bar_wall", "hybrid_drill_string", "hybrid_seed003_rod", "hybrid_vibro_impact_beam"} <= names


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_runs_and_json_contract(path):
    doc = tomllib.loads(path.read_text())
    assert detect_kind(doc) == "hybrid"
    for se in doc.get("superelement", []):          # a dict has no file of its own: matrix files by full path
        se["file"] = str(path.parent / se["file"])
    doc["simulation"]["t_end"] = doc["simulation"]["t_end"] / 8
    r = simulate(doc)
    d = json.loads(json.dumps(r.to_dict()))
    assert d["t_end"] == pytest.approx(doc["simulation"]["t_end"])
    assert "period" in d and d["energy_error"] < 1e-5
    for e in d["events"]:
        assert set(e) == {"t", "kind", "element", "state"}
    if "reduction" in doc:
        rep = d["reduction"]
        assert rep["restitution"] and rep["highest_frequency_hz"] > 0 and rep["suggested_time_step_s"] > 0
    assert r.field_history.shape[1] == r.fe.system.n_dofs
