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


def test_coupled_cars_count_unconverged_steps_per_speed_and_the_sweep_flags_them(monkeypatch, tmp_path):
    """At one contact-law evaluation a step (``IMPLICIT_MAX_ITERATIONS`` = 1) the implicit integrator
    cannot settle the Hertz contact of the coupled cars, so every speed counts steps; a moving-force
    sweep has none to count (None); the counts survive the checkpoint and the report's flag names
    the worst train and speed."""
    from importlib import import_module

    import xarray as xr

    from vbikit.rail.checkpoint import load, save
    from vbikit.rail.report import unconverged_flags
    from vbikit.solve import integrators

    simulate_module = import_module("vbikit.solve.simulate")  # (the package exports the function of that name)

    train = dataclasses.replace(ice3(), cars=ice3().cars[:1])  # its first car alone
    m = 1e4
    beam = EulerBernoulliBeam(20.0, (2 * 400 * 5 / np.pi) ** 2 * m, m, 0.02, n_modes=3)
    setup = SweepSetup(beam, np.array([10.0]), (), 0.1, 0.05, 1e12)
    speeds = np.array([200 / 3.6, 280 / 3.6])
    sound = coupled_envelopes(setup, train, speeds[:1])
    assert sound.unconverged_steps.tolist() == [0.0]
    monkeypatch.setattr(integrators, "IMPLICIT_MAX_ITERATIONS", 1)
    monkeypatch.setattr(simulate_module, "UNCONVERGED_HALVINGS", 0)  # counted at the step given, not run again
    env = coupled_envelopes(setup, train, speeds)
    assert env.unconverged_steps.shape == (2,) and np.all(env.unconverged_steps > 0)
    assert moving_load_sweep(beam, train.axle_positions, train.axle_loads, speeds, setup.points, dx=0.05,
                             free_vibration=0.2).unconverged_steps is None
    save(tmp_path, "k", env, None)
    np.testing.assert_array_equal(load(tmp_path, "k")[0].unconverged_steps, env.unconverged_steps)
    counts = np.vstack([np.zeros(2), env.unconverged_steps])
    ds = xr.Dataset({"unconverged_steps": (("train", "speed"), counts)},
                    coords={"train": ["HSLM-A1", "ICE 3 (coupled)"], "speed": speeds})
    [flag] = unconverged_flags(ds)
    worst = int(np.argmax(env.unconverged_steps))
    assert flag.code == "contact_not_converged" and flag.value == env.unconverged_steps[worst]
    assert "2 of 4 runs" in flag.message and "ICE 3 (coupled) at" in flag.message
    assert unconverged_flags(ds.assign(unconverged_steps=0 * ds["unconverged_steps"])) == []
