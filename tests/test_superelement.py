"""Linear super-elements from matrix files (fem/superelement.py, [[superelement]])."""
import json

import numpy as np
import pytest

from discrete.errors import ModelError
from fem.study import Study
from fem.superelement import read_superelement, write_superelement
from validation.examples import EXAMPLES, example_doc


def _tail_system():
    from fem.assembly import assemble
    from fem.modelfile.build.fe import shaft_model

    return assemble(shaft_model(Study.load(EXAMPLES / "superelement_tail_shaft.toml").doc)).system


@pytest.mark.parametrize("fmt", ["mtx", "hb"])
def test_write_read_is_exact(tmp_path, fmt):
    system = _tail_system()
    se = read_superelement(write_superelement(tmp_path / "t.json", system, fmt=fmt), name="t")
    assert se.dofs == system.labels() and se.C is None
    for k in ("M", "K"):
        assert np.array_equal(getattr(se, k).toarray(), getattr(system, k).toarray())


def test_bad_descriptions_are_refused_with_the_key(tmp_path):
    side = write_superelement(tmp_path / "t.json", _tail_system())
    doc = json.loads(side.read_text())
    for change, key in (({"format": "other"}, "format"), ({"dofs": doc["dofs"][:-1]}, "M"),
                        ({"dofs": ["a"] * 6}, "dofs"), ({"K": "missing.mtx"}, "K"), ({"M": None}, "M")):
        bad = tmp_path / "bad.json"
        bad.write_text(json.dumps({**doc, **change}))
        with pytest.raises(ModelError, match=key):
            read_superelement(bad)
    (tmp_path / "x.json").write_text("{")
    with pytest.raises(ModelError, match="JSON"):
        read_superelement(tmp_path / "x.json")


def test_joined_model_errors_name_the_table():
    d = example_doc("hybrid_afc_superelement.toml")
    d["superelement"][0]["file"] = str(EXAMPLES / d["superelement"][0]["file"])
    d["superelement"][0]["join"][0]["dof"] = "w@x=9"
    with pytest.raises(ModelError, match=r"\[\[superelement\]\] #1 join.*w@x=9"):
        Study.parse(d).compiled
    d = example_doc("hybrid_afc_superelement.toml")
    d["superelement"][0]["file"] = str(EXAMPLES / d["superelement"][0]["file"])
    d["gap"][0]["body"] = "tail:nowhere"
    with pytest.raises(ModelError, match="tail:nowhere"):
        Study.parse(d).compiled


def test_superelement_dofs_are_in_the_system():
    st = Study.load(EXAMPLES / "hybrid_afc_superelement.toml")
    sys_ = st.hybrid.fe.system
    assert sys_.n_dofs == 12 and "tail:w@x=0.1625" in list(sys_.dof_name)
    assert st.hybrid.superelement_dofs["tail:w@x=0"] == sys_.dof_index(field="w", x=0.3375)
