"""``[steady]`` -> :class:`discrete.steady.SteadySettings`."""
from __future__ import annotations

from discrete.steady import SteadySettings


def steady_settings(t) -> SteadySettings:
    r = t.response
    return SteadySettings(range=t.range, method=t.method, omega_ref=t.omega_ref, harmonics=t.harmonics,
                          subharmonic=t.subharmonic, samples=t.samples, regularisation=t.regularisation,
                          stability=t.stability, ds=t.ds, ds_max=t.ds_max, ds_min=t.ds_min, max_steps=t.max_steps,
                          steps_per_period=t.steps_per_period, response_body=r.body, response_element=r.element,
                          measure=r.measure, scale=r.scale, start=t.start,
                          start_periods=t.start_periods, kinks=t.kinks, truncation_tol=t.truncation_tol,
                          adaptive=t.adaptive, max_harmonics=t.max_harmonics, bifurcations=t.bifurcations,
                          switch_branches=t.switch_branches, condense=t.condense)
