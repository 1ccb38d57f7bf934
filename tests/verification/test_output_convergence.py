# Every output converges at least at the exact integrator's order as the step halves (2: the
# vehicles' wheel loads are held linear over each step, the deck's modal loads quadratic, which lifts
# the accelerations and some load effects above 2 over these steps), on an unequal two-span continuous beam (20 + 25 m, 10 modes, 2 % damping;
# quarter car, point tire, smooth road, 70 km/h) with rigid and with elastic supports (vertical
# springs 5e8, 2e8, 5e8 N/m, rotational end springs 2e9 N m/rad).  Error: the largest difference
# from a run at 1/16 of the coarsest step, relative to the largest value, up to just before the
# wheel leaves the beam.  The wheel starts on the deck (approach 0): on elastic supports the
# deck end moves, so a wheel stepping onto it or off it is a jump in the load inside a step, which
# is first order (docs/theory.md); the step check of load-effect runs covers it (second test).
from __future__ import annotations

import numpy as np
import pytest

from vbikit.scenario.pipeline import run

SPEED = 70 / 3.6
STEPS = (2e-3, 1e-3, 5e-4)
REFERENCE = 1.25e-4
OUTPUTS = ("displacement", "acceleration", "moment_x10", "moment_x20", "shear_x5", "reaction_s1", "contact_force_w1")


def _scenario(dt: float, elastic: bool) -> dict:
    bridge = {"model": "continuous-beam", "spans": [20.0, 25.0], "EI": 4.865e10, "mass_per_length": 18358.0,
              "damping_ratio": 0.02, "n_modes": 10}
    if elastic:
        bridge |= {"support_stiffness": [5e8, 2e8, 5e8], "rotational_stiffness": [2e9, 2e9]}
    return {"bridge": bridge, "vehicle": {"model": "quarter-car"}, "tire": {"model": "point"}, "road": {"class": "none"},
            "crossing": {"speed_kmh": 70, "dt": dt, "approach": 0.0},
            "response": {"x": 10.0, "moment": [10.0, 20.0], "shear": [5.0], "reaction": [1]}}


@pytest.mark.parametrize("elastic", [False, True], ids=["rigid", "elastic"])
def test_every_output_second_order(elastic):
    runs = {dt: run(_scenario(dt, elastic)).histories() for dt in (*STEPS, REFERENCE)}
    fine = runs[REFERENCE]
    on_deck = 44.0 / SPEED
    for name in OUTPUTS:
        errors = []
        for dt in STEPS:
            k = int(round(dt / REFERENCE))
            coarse, ref = runs[dt][name][0], fine[name][0][::k]
            n = min(coarse.size, ref.size)
            keep = runs[dt]["time"][0][:n] < on_deck
            errors.append(np.abs(coarse[:n][keep] - ref[:n][keep]).max() / np.abs(ref[:n][keep]).max())
        order = np.polyfit(np.log(STEPS), np.log(errors), 1)[0]
        assert order > 1.9, (name, errors, order)  # measured 2.04–2.83 (2.04–2.07 with the deck's loads linear)
        assert errors[-1] < 1e-4, (name, errors)


def test_elastic_pier_moment_step_check():
    """The case of elastic bearings where the automatic step alone under-resolves the pier moment by
    12 % (IM 0.617 against 0.700 at dt = 5e-5 s; two 20 m spans, 40 modes, no damping): the run's
    step check halves the step until the impact factors settle, and either lands within 1 % of the
    fine run or says it did not converge."""
    bridge = {"model": "continuous-beam", "spans": [20.0, 20.0], "EI": 4.865e10, "mass_per_length": 18358.0,
              "support_stiffness": [5e8, 2e8, 5e8], "rotational_stiffness": [2e9, 2e9], "damping_ratio": 0.0,
              "n_modes": 40}
    scenario = {"bridge": bridge, "vehicle": {"model": "quarter-car"}, "tire": {"model": "point"},
                "road": {"class": "none"}, "crossing": {"speed_kmh": 70}, "response": {"moment": [20.0]}}
    auto = run(scenario).summary
    fine = run(scenario | {"crossing": {"speed_kmh": 70, "dt": 5e-5}}).summary
    close = abs(auto["moment_impact_factor"] / fine["moment_impact_factor"] - 1) <= 0.01
    warned = any("moment" in w and "not converged" in w for w in auto["warnings"])
    assert close or warned
    assert close  # measured: 0.7008 against 0.7003
