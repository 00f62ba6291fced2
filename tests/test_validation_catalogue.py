"""Every fast validation case passes (the same catalogue `drivefem validate` runs)."""
import pytest

from validation.registry import load_all, run_case

CASES = load_all()


@pytest.mark.parametrize("name", [n for n, c in CASES.items() if not c.slow])
def test_fast_case(name):
    outcome = run_case(CASES[name])
    assert outcome.error is None, outcome.error
    failed = [f"{c.quantity}: expected {c.expected}, computed {c.computed}, rel.err {c.rel_error:.2e} > tol {c.tolerance:.1e}"
              for c in outcome.checks if not c.passed]
    assert outcome.checks, "a case must compare something"
    assert not failed, "\n".join(failed)


@pytest.mark.slow
@pytest.mark.parametrize("name", [n for n, c in CASES.items() if c.slow])
def test_slow_case(name):
    outcome = run_case(CASES[name])
    assert outcome.passed, outcome.error or [c for c in outcome.checks if not c.passed]


def test_check_can_fail():
    from validation.registry import check, printed

    assert not check("x", "s", "q", 1.0, 1.1, 1e-3).passed
    assert check("x", "s", "q", 1.0, 1.0005, 1e-3).passed
    assert printed("1.56434") == (1.56434, pytest.approx(0.5e-5 / 1.56434))
