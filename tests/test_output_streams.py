"""Text output goes to the sys.stdout of the moment of the call: a default bound at import time kept the
stream a test harness had installed then, and printed into it after it was closed ("I/O operation on
closed file", depending on the order in which tests imported the module)."""
from __future__ import annotations

import importlib
import io
import sys


def _reimported_under_a_closed_stream(monkeypatch, name):
    """The module imported while sys.stdout is a stream that is then closed and replaced."""
    module = importlib.import_module(name)
    tmp = io.StringIO()
    monkeypatch.setattr(sys, "stdout", tmp)
    module = importlib.reload(module)
    tmp.close()
    monkeypatch.undo()
    return module


def test_tables_print_to_the_current_stdout(monkeypatch, capsys):
    tables = _reimported_under_a_closed_stream(monkeypatch, "fem.output.tables")
    tables.simulation_summary("a title", {"t_end": 1.5, "warnings": ["w1"]})
    out = capsys.readouterr().out
    assert "a title\nsimulated to t = 1.5" in out and "warning: w1" in out
    buf = io.StringIO()
    tables.simulation_summary("to a stream", {"t_end": 2.0}, out=buf)
    assert "to a stream" in buf.getvalue() and "to a stream" not in capsys.readouterr().out


def test_validation_table_prints_to_the_current_stdout(monkeypatch, capsys):
    report = _reimported_under_a_closed_stream(monkeypatch, "validation.report")
    report.print_table([])
    assert "case" in capsys.readouterr().out
