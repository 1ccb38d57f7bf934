"""The in-contact step of population events (``vbikit.solve.simulate.simulate_in_contact``): the
exact integrator's step 1.5 times as long, at whole road stations, where no contact opens or
closes, the automatic step where one does; the same run as ``simulate`` at the step it reports, and within the default's
accuracy of a converged RK4 run (the reference: RK4 at an eighth of the automatic step, another
integrator; docs/verification.md states 5e-4 in IM for the automatic step)."""
from __future__ import annotations

import dataclasses
import importlib

import numpy as np
import pytest

from vbikit.analysis import point_response
from vbikit.contact import DiskTire, RigidDiskTire
from vbikit.scenario.build import build
from vbikit.scenario.schema import parse_scenario
from vbikit.solve import simulate
from vbikit.solve.plan import plan_run
from vbikit.solve.simulate import simulate_in_contact
from vbikit.solve.timestep import IN_CONTACT_FACTOR, in_contact_time_step

#: the module (``vbikit.solve.simulate`` as an attribute is the function)
simulate_module = importlib.import_module("vbikit.solve.simulate")


def _crossing(road_class: str, speed_kmh: float, seed: int = 3, **crossing):
    data = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 6}, "vehicle": {"model": "hs20-44"},
            "tire": {"model": "point"}, "road": {"class": road_class, "seed": seed, "length": 200.0, "spacing": 0.01},
            "crossing": {"speed_kmh": speed_kmh, "approach": 5.0, **crossing}}
    return build(parse_scenario(data, ".")).crossing


def _same(a, b) -> None:
    for name in ("xi", "xi_dot", "q", "q_dot", "wheel_forces"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def test_a_run_that_keeps_contact_takes_the_longer_step_and_is_simulate_at_that_step():
    crossing = _crossing("A", 110.0)
    automatic = plan_run(crossing).dt
    result, held = simulate_in_contact(crossing)
    assert held
    assert result.integration_dt == pytest.approx(in_contact_time_step(crossing), rel=1e-15)
    # 110 km/h: 2 cm of road is 0.65 ms, below T1/100 (1.37 ms): the road term governs; 1.5 times it
    # is 3 cm of road, three whole stations
    assert result.integration_dt == pytest.approx(IN_CONTACT_FACTOR * automatic, rel=1e-12)
    assert result.integration_dt * crossing.max_speed == pytest.approx(0.03, rel=1e-12)
    assert np.all(result.wheel_forces[1:] > 0.0)
    _same(result, simulate(dataclasses.replace(crossing, dt=result.integration_dt)))


def test_the_in_contact_step_passes_whole_road_stations():
    """45 km/h on the 16.76 m beam: the automatic step is T1/100 = 1.369 ms (2 cm of road would be
    1.6 ms); 1.5 times it passes 2.57 stations of 1 cm, so the in-contact step is two whole stations,
    2 cm / 12.5 m/s = 1.6 ms — longer than the automatic step, shorter than 1.5 times it."""
    crossing = _crossing("B", 45.0)
    automatic = plan_run(crossing).dt
    omega1 = crossing.bridge.omega.min()
    assert automatic == pytest.approx(2 * np.pi / omega1 / 100, rel=1e-12) and automatic > 1.3e-3
    assert in_contact_time_step(crossing) == pytest.approx(0.02 / 12.5, rel=1e-12)


def test_a_run_where_a_wheel_loses_contact_runs_again_at_the_automatic_step():
    crossing = _crossing("E", 100.0)
    coarse = simulate(dataclasses.replace(crossing, dt=in_contact_time_step(crossing)))
    assert np.any(coarse.wheel_forces <= 0.0)  # the case: a wheel lifts off at the longer step
    result, held = simulate_in_contact(crossing)
    assert not held
    assert result.integration_dt == plan_run(crossing).dt
    _same(result, simulate(crossing))


@pytest.mark.parametrize("change", [{"integrator": "rk4"}, {"dt": 5e-4}, {"tire": DiskTire()}, {"tire": RigidDiskTire()}],
                         ids=["rk4", "user dt", "disk", "rigid disk"])
def test_without_an_in_contact_rule_a_user_step_or_with_changing_contacts_it_is_simulate(change, monkeypatch):
    """RK4 has no in-contact step, a user step is kept, and disk tires touch and leave by design:
    one run, that of ``simulate``, at the automatic (or the user's) step."""
    crossing = dataclasses.replace(_crossing("A", 100.0), **change)
    runs = []
    original = simulate_module.simulate
    monkeypatch.setattr(simulate_module, "simulate", lambda *a, **k: runs.append(1) or original(*a, **k))
    result, held = simulate_in_contact(crossing)
    assert not held and len(runs) == 1
    _same(result, original(crossing))


@pytest.mark.parametrize("road_class, speed_kmh, seed", [("A", 100.0, 3), ("B", 90.0, 4), ("C", 80.0, 5)])
def test_the_longer_step_keeps_the_impact_factor_of_converged_rk4(road_class, speed_kmh, seed):
    crossing = _crossing(road_class, speed_kmh, seed)
    result, held = simulate_in_contact(crossing)
    if not held:
        pytest.skip("a contact changed: the automatic step ran (covered by docs/verification.md)")
    reference = simulate(dataclasses.replace(crossing, integrator="rk4", dt=plan_run(crossing).dt / 8))
    im = point_response(result).displacement_impact.impact_factor
    im_ref = point_response(reference).displacement_impact.impact_factor
    assert abs(im - im_ref) <= 5e-4, (im, im_ref)


def test_a_point_of_a_multipoint_tire_leaving_counts_as_a_change():
    """The wheels keep load but a point of a multi-point tire leaves the road: the patch length
    changes (``contact_changed``), so the crossing runs again at the automatic step."""
    from vbikit.contact import MultiPointTire

    crossing = dataclasses.replace(_crossing("C", 110.0, seed=5), tire=MultiPointTire())
    coarse = simulate(dataclasses.replace(crossing, dt=in_contact_time_step(crossing)))
    assert np.all(coarse.wheel_forces[1:] > 0.0)  # no wheel left the road …
    assert np.unique(coarse.contact_lengths).size > 1  # … but a point did
    assert simulate_module.contact_changed(coarse)
    result, held = simulate_in_contact(crossing)
    assert not held
    _same(result, simulate(crossing))
