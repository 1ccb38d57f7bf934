"""What a crossing keeps of its own (``Crossing.kept``): its plan (step, budget estimate), time grid,
kernel data and static start, so that a run of the same crossing again sets up nothing.

Every kept path is compared bit for bit with the same run of a crossing built afresh from the same
inputs (nothing kept), and every kind of kept value is tested with a crossing that differs in one
input the value depends on (the road: another static start and another step; the speed; the budget),
where a value kept too widely would return the other crossing's stale one."""
from __future__ import annotations

import copy
import dataclasses
import pickle

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.road import RoadProfile
from vbikit.solve import Crossing, plan_run, simulate
from vbikit.solve.budget import BudgetError, Limits
from vbikit.solve.crossing import ROAD_FREE_KINDS
from vbikit.vehicle import sprung_mass

FIELDS = ("time", "front_position", "speed", "xi", "xi_dot", "xi_ddot", "q", "q_dot", "q_ddot", "wheel_forces",
          "contact_lengths")


def _beam():
    return EulerBernoulliBeam(25.0, 2.87e9 * 2.9, 2303.0, 0.02, n_modes=6)


def _road(amplitude: float, spacing: float = 0.05) -> RoadProfile:
    x = np.arange(-30.0, 80.0, spacing)
    return RoadProfile(x, amplitude * np.sin(2 * np.pi * x / 7.3), label=f"sine {amplitude:g} m")


def _crossing(**kw) -> Crossing:
    args = dict(vehicle=sprung_mass(5750.0, 1595e3, 2e3), speed=25.0, approach=5.0, free_vibration=0.2) | kw
    return Crossing(_beam(), **args)


def _same(a, b) -> bool:
    return all(np.array_equal(getattr(a, f), getattr(b, f)) for f in FIELDS) and a.dt == b.dt


def _kinds(crossing: Crossing) -> set:
    store = crossing.__dict__.get("_kept")
    return set() if store is None else {key[0] for key, _ in store.items()}


def test_a_run_again_sets_up_nothing_and_equals_a_fresh_crossing():
    c = _crossing(road=_road(2e-3))
    first = simulate(c)
    assert {"plan", "grid", "kernel_data", "start"} <= _kinds(c)
    kept = {key: value for key, value in c._kept.items()}
    again = simulate(c)
    assert {key: value for key, value in c._kept.items()}.keys() == kept.keys()
    assert all(c._kept.peek(key) is value for key, value in kept.items())  # reused, not made again
    fresh = simulate(_crossing(road=_road(2e-3)))  # the same inputs, nothing kept
    assert _same(first, again) and _same(first, fresh)
    assert again.xi is not first.xi and again.time is not first.time  # every result owns its histories


def test_another_road_gets_its_own_static_start_and_step():
    rough, smooth = _road(2e-3), _road(0.0, spacing=0.5)
    c = _crossing(road=rough)
    on_rough = simulate(c)
    other = c.with_road(smooth)
    assert _kinds(other) <= ROAD_FREE_KINDS  # the copy keeps only what does not depend on the road
    on_smooth = simulate(other)
    fresh = simulate(_crossing(road=smooth))
    assert _same(on_smooth, fresh)
    # a static start or step kept across roads would give these the rough road's
    assert not np.array_equal(on_smooth.q[0], on_rough.q[0])  # the wheel starts on another elevation
    assert plan_run(other).dt == plan_run(_crossing(road=smooth)).dt != plan_run(c).dt  # the road's spacing sets dt
    # and back: the first crossing still has its own
    assert _same(simulate(c), on_rough)


def test_another_speed_or_vehicle_keeps_nothing_of_the_first():
    c = _crossing()
    simulate(c)
    for changed in (dataclasses.replace(c, speed=30.0), dataclasses.replace(c, vehicle=sprung_mass(7000.0, 1595e3, 2e3))):
        assert _kinds(changed) == set()
        result = simulate(changed)
        rebuilt = Crossing(changed.bridge, changed.vehicle, speed=changed.speed, approach=5.0, free_vibration=0.2)
        assert _same(result, simulate(rebuilt))
    assert simulate(dataclasses.replace(c, speed=30.0)).n_steps != simulate(c).n_steps


def test_the_plan_is_kept_per_budget():
    c = _crossing()
    assert plan_run(c).n_steps > 10
    with pytest.raises(BudgetError):  # a plan kept without its limits would pass
        plan_run(c, Limits(max_steps=10))
    assert plan_run(c, Limits()).dt == plan_run(c).dt


def test_copies_and_pickles_carry_nothing_kept():
    c = _crossing(road=_road(1e-3))
    result = simulate(c)
    assert _kinds(pickle.loads(pickle.dumps(c))) == set()
    assert _kinds(copy.copy(c)) == set()
    assert _same(simulate(pickle.loads(pickle.dumps(c))), result)


def test_read_out_shapes_are_those_of_their_point():
    result = simulate(_crossing())
    bridge = result.crossing.bridge
    for x in (12.5, 6.0, 12.5):  # a shape kept under another point would give another history
        assert np.array_equal(result.displacement(x), result.xi @ bridge.mode_shapes([x], [0.0])[0])
    assert not np.array_equal(result.displacement(6.0), result.displacement(12.5))


def test_contact_points_are_those_of_their_own_vehicle_and_tire():
    from vbikit.contact import MultiPointTire
    from vbikit.contact.points import contact_points

    light, heavy = sprung_mass(5750.0, 1595e3, 2e3), sprung_mass(9000.0, 2500e3, 2e3)
    tire = MultiPointTire()
    cases = [(light, None), (heavy, None), (light, tire), (heavy, tire), (light, None)]
    for vehicle, t in cases:  # a contact kept under another vehicle or tire would carry its loads or layout
        c = _crossing(vehicle=vehicle) if t is None else _crossing(vehicle=vehicle, tire=t)
        fresh = contact_points(vehicle, c.tire)
        for name in ("setback", "weight", "stiffness", "damping", "gap", "width"):
            assert np.array_equal(getattr(c.contact, name), getattr(fresh, name))
    assert _crossing(vehicle=light).contact is _crossing(vehicle=light).contact  # one vehicle and tire: shared
    assert not np.array_equal(_crossing(vehicle=light).contact.stiffness, _crossing(vehicle=heavy).contact.stiffness)
    assert _crossing(vehicle=light, tire=tire).contact.n > _crossing(vehicle=light).contact.n


def test_many_read_out_points_do_not_push_the_run_set_up_out():
    c = _crossing()
    result = simulate(c)
    kept = {key: value for key, value in c._kept.items()}
    for x in np.linspace(1.0, 24.0, 40):
        result.displacement(float(x))
    assert all(c._kept.peek(key) is value for key, value in kept.items())


def test_result_travel_is_kept_and_each_access_a_fresh_copy():
    """``CrossingResult.travel`` is the crossing's travel at the stored times, s = −approach + v t for
    one vehicle at constant speed (closed form), computed once; writing to one access leaves the next."""
    result = simulate(_crossing())
    crossing = result.crossing
    first = result.travel
    np.testing.assert_allclose(first[:, 0], -crossing.approach + crossing.speed * result.time, rtol=0, atol=1e-12)
    first[:] = 0.0
    np.testing.assert_array_equal(result.travel, crossing.travel(result.time))
    assert result.travel is not result.travel
