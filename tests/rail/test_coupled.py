"""A whole train of coupled car models (vbikit.vehicle.rail_car, one VehicleMotion per car) against
the same train as moving forces: with stiff suspensions (×100) and a vehicle-to-bridge mass ratio
of 0.3 % the car bodies follow the deck and add no inertia worth counting, so the two agree within
1 % (the independent number is the moving-force solution, itself checked against Frýba's closed
form and vbikit.solve.simulate in test_moving_loads.py)."""
import dataclasses

import numpy as np
import pytest

from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.rail.sweep import SweepSetup, coupled_envelopes
from vbikit.vehicle.trains import ice3
from vbikit.solve.moving_loads import moving_load_sweep


@pytest.mark.parametrize("contact", ["hertz", "rigid"])  # rigid: the wheelset weight must still reach the deck
def test_train_of_stiff_cars_on_a_heavy_bridge_is_the_moving_force_train(contact):
    train = ice3()
    stiff = tuple(dataclasses.replace(c, primary_stiffness=100 * c.primary_stiffness,
                                      secondary_stiffness=100 * c.secondary_stiffness) for c in train.cars)
    stiff_train = dataclasses.replace(train, cars=stiff)
    m = 1e6  # kg/m: the 8 cars (≈ 490 t) against 20 000 t of span
    beam = EulerBernoulliBeam(20.0, (2 * 400 * 5 / np.pi) ** 2 * m, m, 0.02, n_modes=3)  # n0 = 5 Hz
    points = np.array([5.0, 10.0, 13.0])
    setup = SweepSetup(beam, points, (("moment", 10.0),), 0.05, 0.5, 1e12)
    speeds = np.array([280 / 3.6])
    coupled = coupled_envelopes(setup, stiff_train, speeds, contact=contact)
    forces = moving_load_sweep(beam, train.axle_positions, train.axle_loads, speeds, points, setup.effects,
                               dx=0.05, free_vibration=0.5)
    for a, b in ((coupled.max_displacement, forces.max_displacement), (coupled.max_acceleration, forces.max_acceleration),
                 (coupled.max_effect, forces.max_effect)):
        np.testing.assert_allclose(a, b, rtol=0.01)
