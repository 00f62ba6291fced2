"""The HTML validation report and its Markdown twin."""
import numpy as np

from validation.html_report import write_html
from validation.registry import Case, CaseOutcome, check, claim


def _outcomes():
    good = Case(name="good<case>", group="g", func=lambda: [], doc="Tolerance justified: 1e-3 because ...")
    bad = Case(name="bad", group="g", func=lambda: [])
    crash = Case(name="crash", group="g", func=lambda: [])
    return [CaseOutcome(case=good, checks=[check("good<case>", "seed 001 (4.1)", "omega_1 | rad/s", 2.0, 2.001, 1e-3),
                                            claim("good<case>", "src", "pairs", True, note="3 pairs")], seconds=0.5),
            CaseOutcome(case=bad, checks=[check("bad", "src", "f_2", 1.0, 1.5, 1e-2)], seconds=0.1),
            CaseOutcome(case=crash, error="ValueError: boom", seconds=0.0)]


def test_html_and_markdown(tmp_path):
    fig = tmp_path / "elsewhere" / "plot.png"
    fig.parent.mkdir()
    fig.write_bytes(b"\x89PNG\r\n\x1a\n")
    path = write_html(_outcomes(), tmp_path / "report", figures=[fig, tmp_path / "missing.png"])
    text = path.read_text()
    assert path.name == "validation.html" and text.startswith("<!DOCTYPE html>")
    assert "good&lt;case&gt;" in text and "<case>" not in text          # escaped
    assert text.count("<tr") == 1 + 4                                      # header + 3 checks + 1 error row
    assert 'class="fail"' in text and "ValueError: boom" in text and "2 case(s) failed" in text
    assert (tmp_path / "report" / "figures" / "elsewhere_plot.png").is_file()
    assert 'src="figures/elsewhere_plot.png"' in text
    md = (tmp_path / "report" / "validation.md").read_text()
    assert "omega_1 \\| rad/s" in md and "**FAIL**" in md and "![elsewhere_plot](figures/elsewhere_plot.png)" in md
    assert "Tolerance justified" in md and "Tolerance justified" in text
    assert md.count("\n| ") == 1 + 4


def test_all_passed_summary(tmp_path):
    ok = _outcomes()[:1]
    text = write_html(ok, tmp_path).read_text()
    assert "all passed" in text and np.isfinite(ok[0].seconds)
