"""fem and discrete export their public names on first use (discrete.lazy): the names and the
submodules a plain ``import fem`` / ``import discrete`` used to provide are there, other names
are an AttributeError, and dunder names import nothing."""
import subprocess
import sys

import pytest

import discrete
import fem


def test_public_names_and_submodules_resolve():
    from discrete.linear_system import LinearSystem
    from fem.assembly import assemble
    from fem.model import ShaftModel

    assert discrete.LinearSystem is LinearSystem and fem.assemble is assemble and fem.model.ShaftModel is ShaftModel
    assert set(fem.__all__) <= set(dir(fem)) and "LinearSystem" in dir(discrete)
    assert discrete.linear_system.LinearSystem is LinearSystem


@pytest.mark.parametrize("package", [fem, discrete])
def test_unknown_and_dunder_names_are_attribute_errors(package):
    with pytest.raises(AttributeError, match="has no attribute 'no_such_name'"):
        package.no_such_name
    assert not hasattr(package, "__wrapped__")


def test_a_submodule_that_fails_to_import_says_why():
    """A submodule's own ImportError is not hidden behind an AttributeError."""
    code = ("import sys, fem; sys.modules['skfem'] = None\n"
            "try:\n    fem.assembly\nexcept ImportError as e:\n    print('ImportError', e.name)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip() == "ImportError skfem", out.stderr
