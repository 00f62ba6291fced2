"""The one JSON serialiser (fem.output.jsonio): numbers as they are, numeric arrays as lists without
visiting their elements one by one, the place of a non-finite number or an unknown object named
exactly, and an encoded document written without a second pass."""
import json
import re

import numpy as np
import pytest

from discrete.errors import SolverError
from fem.output.jsonio import encode, write_json


def test_arrays_and_scalars_encode_to_plain_json():
    doc = {"i": np.arange(3, dtype=np.int32), "u": np.array([7], dtype=np.uint64), "b": np.array([True, False]),
           "f": np.array([[0.1, -2.5e-300], [1e300, 3.0]]), "z": np.array([1 + 2j]), "o": np.array([1.5, "x"], dtype=object),
           "s": (np.float32(1.5), np.int8(-3), np.bool_(True), None, "text"), "c": 2 - 1j}
    out = encode(doc)
    assert out == {"i": [0, 1, 2], "u": [7], "b": [True, False], "f": [[0.1, -2.5e-300], [1e300, 3.0]],
                   "z": [{"re": 1.0, "im": 2.0}], "o": [1.5, "x"], "s": [1.5, -3, True, None, "text"],
                   "c": {"re": 2.0, "im": -1.0}}
    assert all(type(x) is int for x in out["i"]) and all(type(x) is float for row in out["f"] for x in row)
    assert json.loads(json.dumps(out)) == out


@pytest.mark.parametrize("doc, where", [
    ({"a": [1.0, {"b": float("nan")}]}, "$.a[1].b"),
    ({"x": np.array([[1.0, np.inf]])}, "$.x[0][1]"),
    ({"events": [{"t": 1.0}, {"t": np.float64("-inf")}]}, "$.events[1].t"),
    ({"c": [1 + 2j, complex(1, float("nan"))]}, "$.c[1].im"),
])
def test_a_non_finite_number_is_refused_with_its_place(doc, where):
    with pytest.raises(SolverError, match="not finite at " + re.escape(where) + "[ :]"):
        encode(doc)


def test_an_unknown_object_is_refused_with_its_place():
    with pytest.raises(TypeError, match=r"not JSON serialisable at \$\.k\[0\]: object"):
        encode({"k": [object()]})


def test_an_encoded_document_is_written_as_it_is(tmp_path, monkeypatch):
    import fem.output.jsonio as jsonio

    doc = encode({"t": np.linspace(0, 1, 5), "events": [{"kind": "stick", "t": 0.5}]})
    calls = []
    monkeypatch.setattr(jsonio, "encode", lambda d, path="$": (path == "$" and calls.append(1)) or encode(d, path))
    write_json(tmp_path / "a.json", doc, encoded=True)
    assert calls == []
    write_json(tmp_path / "b.json", doc)
    assert calls == [1]
    assert (tmp_path / "a.json").read_text() == (tmp_path / "b.json").read_text()
    assert json.loads((tmp_path / "a.json").read_text()) == doc


def test_extended_precision_arrays_become_python_floats():
    out = encode({"x": np.array([1.5, 2.25], dtype=np.longdouble), "h": np.array([0.5], dtype=np.float16)})
    assert out == {"x": [1.5, 2.25], "h": [0.5]} and all(type(v) is float for v in out["x"] + out["h"])
    assert json.loads(json.dumps(out)) == out
