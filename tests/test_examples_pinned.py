"""Which example model files the validation catalogue pins, and that no example goes untested.

A case pins an example when it loads the file and runs the same model (overriding only what the case
sweeps or how long it runs), so a change of the example's numbers moves the catalogue's numbers
(``drivefem validate`` + validate-diff).  Every other example must at least run in
tests/test_cli_examples.py (the linear and steady-state examples there)."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
CASES = ROOT / "validation" / "cases"

PINNED = {
    "geared_mesh.toml": ["loads-lumped-geared-mesh"],
    "ross_compressor.toml": ["rotor-ross-compressor"],
    "rotor_friswell_damped.toml": ["loads-fe-rotor-equilibrium"],
    "rotor_compressor.toml": ["loads-fe-rotor-equilibrium"],
    "hybrid_afc_friction_rod.toml": ["hybrid_afc_friction_rod", "hybrid_afc_breakdown", "steady_condensed_hb",
                                     "hybrid_superelement_round_trip"],
    "hybrid_afc_vibro_impact.toml": ["hybrid_afc_vibro_impact", "hybrid_afc_breakdown", "steady_condensed_hb",
                                     "hybrid_superelement_round_trip"],
    "hybrid_afc_superelement.toml": ["hybrid_superelement_round_trip"],
    "superelement_tail_shaft.toml": ["hybrid_superelement_round_trip"],
    "hybrid_sweep_vibro_impact.toml": ["hybrid_afc_vibro_impact"],
    "beam_base_excitation.toml": ["base-motion-modal-vs-direct"],
    "parametric_drive.toml": ["parametric_model_file"],
    "cam_clearance.toml": ["timedomain_cam_follower", "timedomain_cam_clearance"],
    "motor_runup.toml": ["timedomain_motor_runup"],
    "motor_drive_forced.toml": ["motor-drive-forced-file"],
    "forced_periodic_load.toml": ["forced-periodic-rectangular"],
    "discrete_bouncing_ball.toml": ["discrete_impact_ball"],
    "discrete_ch8_quasi_harmonic.toml": ["discrete_ch8_quasi_harmonic"],
    "discrete_ch8_relaxation.toml": ["discrete_ch8_relaxation", "discrete_ch8_critical_speed"],
    "discrete_coulomb_decay.toml": ["discrete_coulomb_decay"],
    "discrete_gap_backlash.toml": ["discrete_gap_exact", "discrete_gap_arctan"],
    "discrete_seed000_stick_slip.toml": ["discrete_seed000_stick_slip", "loads-lumped-multipliers-and-reactions"],
    "discrete_seed004_variable_mass.toml": ["discrete_seed004_tables", "discrete_seed004_claims"],
    "discrete_seed004_weight_friction.toml": ["discrete_seed004_tables"],
    "discrete_strand_spool.toml": ["discrete_one_sided_strand", "loads-lumped-gap-drive-modal"],
    "drive_continuum.toml": ["drives-forced"],
    "drive_forced.toml": ["drives-forced"],
    "drive_large_n.toml": ["drives-seeded-large-n"],
    "free_free_beam.toml": ["beam-free-free"],
    "geared_drive.toml": ["lumped-geared-drive"],
    "hybrid_bar_wall.toml": ["hybrid_bar_wall"],
    "hybrid_drill_string.toml": ["hybrid_drill_string"],
    "hybrid_seed003_rod.toml": ["hybrid_seed003", "hybrid_seed003_breakdown"],
    "hybrid_vibro_impact_beam.toml": ["hybrid_vibro_impact"],
    "sdof_base_motion.toml": ["sdof-kinematic"],
    "steady_coulomb.toml": ["steady_coulomb_den_hartog", "steady_backbones"],
    "steady_duffing.toml": ["steady_cubic_forced_jumps", "steady_cubic_backbone", "steady_subharmonic_third",
                            "steady_backbones"],
    "steady_subharmonic.toml": ["steady_subharmonic_third", "steady_subharmonic_existence", "steady_measures_exact"],
    "steady_gap.toml": ["steady_gap_hb_vs_shooting", "steady_backbones", "steady_measures_exact"],
    "steady_seed002.toml": ["steady_seed002_afc", "steady_seed002_time_sweeps"],
    "sweep_seed002.toml": ["steady_seed002_afc", "steady_seed002_time_sweeps"],
    "torsion_shaft_disc.toml": ["torsion-end-disc"],
    "two_mass_chain.toml": ["lumped-two-mass-chain"],
    "rotor_rub_runup.toml": ["rotor-rub-runup-example"],
    "geared_two_shaft_torsion.toml": ["geared-two-shaft-equivalent"],
    "geared_ross_two_shaft.toml": ["geared-lateral-torsional-dense", "geared-lateral-torsional-ross"],
    "geared_rattle.toml": ["geared-backlash-kahraman-singh", "geared-backlash-period-doubling"],
    "geared_mesh_parametric.toml": ["geared-mesh-parametric-hill"],
    "geared_two_stage.toml": ["geared-two-stage-loads"],
    "geared_compressor_train.toml": ["geared-compressor-campbell"],
    "rotor_jeffcott_seal.toml": ["rotor-jeffcott-seal-cli"],
}
"""Example file -> the validation cases that load it as their model."""

NAMED = re.compile(r"[\"']([A-Za-z0-9_.-]+\.toml)[\"']")


def _registry():
    import inspect

    from validation.registry import load_all

    return {name: Path(inspect.getsourcefile(c.func)) for name, c in load_all().items()}


def _run_by_cli_tests() -> set[str]:
    """The examples tests/test_cli_examples.py runs: the parametrisation of its example test."""
    from tests import test_cli_examples as cli

    marks = [m for m in cli.test_linear_examples_run.pytestmark if m.name == "parametrize"]
    return {Path(p).name for m in marks for p in m.args[1]}


def test_pinned_examples_exist_and_their_cases_load_them():
    cases = _registry()
    for example, names in PINNED.items():
        assert (EXAMPLES / example).is_file(), example
        for name in names:
            assert name in cases, f"{example}: no validation case {name!r}"
            assert example in NAMED.findall(cases[name].read_text()), \
                f"{name} ({cases[name].name}) does not load {example}"


def test_every_example_a_case_loads_is_listed():
    """An example named in a case module is listed with every case of that module that uses it (the
    list above is the catalogue's record of what it pins)."""
    listed = {(e, n) for e, ns in PINNED.items() for n in ns}
    cases = _registry()
    by_module: dict[Path, list[str]] = {}
    for name, path in cases.items():
        by_module.setdefault(path, []).append(name)
    for path, names in by_module.items():
        for example in set(NAMED.findall(path.read_text())):
            if (EXAMPLES / example).is_file():
                assert any((example, n) in listed for n in names), \
                    f"{path.name} loads {example}: list it in PINNED with the case(s) that use it"


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.name)
def test_every_example_is_pinned_or_run_by_the_cli_tests(path):
    assert path.name in PINNED or path.name in _run_by_cli_tests(), \
        f"{path.name} is neither the model of a validation case nor run by tests/test_cli_examples.py"


def test_the_listing():
    """The listing itself (printed with -s): pinned examples, and the examples only the CLI tests run."""
    cli = _run_by_cli_tests()
    lines = [f"{e:40s} pinned by {', '.join(ns)}" for e, ns in sorted(PINNED.items())]
    lines += [f"{p.name:40s} run by tests/test_cli_examples.py" for p in sorted(EXAMPLES.glob("*.toml"))
              if p.name not in PINNED and p.name in cli]
    print("\n".join(lines))
    assert len(lines) == len(list(EXAMPLES.glob("*.toml")))
