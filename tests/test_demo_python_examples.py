"""The demo runs every examples/*.py through its main(): a module with a dataclass loads (it must be
in sys.modules while it executes), and the output target follows main()'s first parameter."""
from pathlib import Path

from fem.app import demo

EXAMPLE = '''
from dataclasses import dataclass
from pathlib import Path


@dataclass
class Result:
    value: float


def main(out: str | Path = "figure.png") -> Result:
    Path(out).write_text("ok")
    return Result(1.0)
'''


def test_python_examples_with_dataclasses_and_targets(tmp_path, monkeypatch):
    ex = tmp_path / "examples"
    ex.mkdir()
    (ex / "with_dataclass.py").write_text(EXAMPLE)
    (ex / "to_dir.py").write_text("from pathlib import Path\n\ndef main(out_dir='x'):\n"
                                  "    Path(out_dir).mkdir(parents=True, exist_ok=True)\n")
    (ex / "broken.py").write_text("def main(out=None):\n    raise RuntimeError('reported, not fatal')\n")
    monkeypatch.setattr(demo, "EXAMPLES", ex)
    out = tmp_path / "out"
    got = {name: rc for name, rc, _ in demo._python_examples(out)}
    assert got == {"broken.py": 1, "to_dir.py": 0, "with_dataclass.py": 0}
    assert (out / "with_dataclass.png").read_text() == "ok" and (out / "to_dir").is_dir()


def test_every_shipped_python_example_has_the_demo_entry():
    """``make demo`` runs each examples/*.py through ``main(out)``: an example without it failed only in the
    demo (examples/ross_compressor.py had ``run`` alone)."""
    import ast

    root = Path(__file__).resolve().parents[1] / "examples"
    missing = [p.name for p in sorted(root.glob("*.py"))
               if not any(isinstance(n, ast.FunctionDef) and n.name == "main" and n.args.args
                          for n in ast.parse(p.read_text()).body)]
    assert not missing, f"examples without main(out): {missing}"
