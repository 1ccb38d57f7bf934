"""One vehicle is a VehicleMotion like any other: travel has one meaning, results one shape."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.solve import Crossing, VehicleMotion, simulate
from vbikit.vehicle import hs20_44, sprung_mass


@pytest.fixture(scope="module")
def beam():
    return EulerBernoulliBeam(20.0, 1e10, 6000.0, n_modes=4)


def test_one_vehicle_normalises_to_one_motion(beam):
    truck = hs20_44()
    c = Crossing(beam, truck, speed=20.0, approach=12.0, lateral_offset=0.5)
    assert c.single and c.n_vehicles == 1
    (m,) = c.vehicles
    assert isinstance(m, VehicleMotion)
    assert m.vehicle is truck and c.vehicle is truck  # its own wheel and DOF names
    assert (m.direction, m.acceleration, m.lateral_offset, m.tire) == ("+x", 0.0, 0.5, None)
    assert m.speed == 20.0 and m.entry_time == pytest.approx(12.0 / 20.0, rel=1e-15)
    several = Crossing(beam, vehicles=(VehicleMotion(truck, 20.0),))
    assert not several.single and several.n_vehicles == 1


@pytest.mark.parametrize("acceleration", [0.0, 1.5, -2.0])
def test_travel_is_the_distance_past_the_entry_support(beam, acceleration):
    speed, approach = 20.0, 10.0
    c = Crossing(beam, sprung_mass(), speed=speed, approach=approach, acceleration=acceleration)
    assert c.start_time == 0.0 and math.copysign(1.0, c.start_time) == 1.0
    t = np.linspace(0.0, c.duration, 37)
    tau = np.minimum(t, -speed / acceleration if acceleration < 0 else math.inf)
    expected = -approach + speed * tau + 0.5 * acceleration * tau**2  # the one-vehicle formula, bit for bit
    travel = c.travel(t)
    assert travel.shape == (t.size, 1)
    np.testing.assert_array_equal(travel[:, 0], expected)
    np.testing.assert_array_equal(c.front_positions(t), travel)
    np.testing.assert_array_equal(c.travel_speed(t)[:, 0], speed + acceleration * tau)
    assert float(c.travel(c.vehicles[0].entry_time)[0, 0]) == pytest.approx(0.0, abs=1e-12)


def test_braking_stop_stays_put(beam):
    m = VehicleMotion(sprung_mass(), 10.0, -2.0, reference=(0.0, -10.0, 10.0))
    assert float(m.travel(100.0)) == -10.0 + 10.0 * 5.0 + 0.5 * -2.0 * 25.0
    assert float(m.velocity(100.0)) == 0.0


def test_results_have_one_column_per_vehicle(beam):
    one = simulate(Crossing(beam, hs20_44(), speed=20.0))
    n_t = one.time.size
    assert one.time[0] == 0.0
    assert one.front_position.shape == one.speed.shape == one.travel.shape == (n_t, 1)
    np.testing.assert_array_equal(one.travel, one.front_position)  # +x: travel = front-axle x
    ds = one.to_xarray()
    assert ds["front_axle_x"].dims == ("time",) and "vehicle" not in ds.dims
    two = simulate(Crossing(beam, vehicles=(VehicleMotion(hs20_44(), 20.0), VehicleMotion(hs20_44(), 15.0, direction="-x"))))
    assert two.front_position.shape == two.travel.shape == (two.time.size, 2)
    np.testing.assert_allclose(two.front_position[:, 1], beam.span - two.travel[:, 1])
    assert two.to_xarray()["front_axle_x"].dims == ("time", "vehicle")


def test_one_vehicle_equals_the_same_motion_given_as_vehicles(beam):
    speed, approach = 18.0, 8.0
    one = simulate(Crossing(beam, hs20_44(), speed=speed, approach=approach, free_vibration=0.2))
    motion = VehicleMotion(hs20_44(), speed, entry_time=approach / speed)
    many = simulate(Crossing(beam, vehicles=(motion,), approach=approach, free_vibration=0.2))
    assert many.time.size == one.time.size
    np.testing.assert_allclose(many.time, one.time, rtol=0, atol=1e-12)
    np.testing.assert_allclose(many.travel, one.travel, rtol=0, atol=1e-10)
    scale = np.abs(one.xi).max()
    np.testing.assert_allclose(many.xi, one.xi, rtol=0, atol=1e-8 * scale)


def test_copies_rebuild_the_motion(beam):
    c = Crossing(beam, sprung_mass(), speed=20.0)
    faster = dataclasses.replace(c, speed=25.0, approach=5.0)
    assert faster.single and faster.vehicles[0].speed == 25.0
    assert float(faster.travel(0.0)[0, 0]) == -5.0
    with pytest.raises(ValueError, match="not both"):
        Crossing(beam, sprung_mass(), vehicles=(VehicleMotion(sprung_mass(), 20.0),))
