"""The decoupled drive-by mode's two one-way solutions, each against an independent number:

* the vehicle's exact discrete state space (``linear_response``: eigen-coordinates, first-order
  hold) against ``scipy.signal.lsim`` (matrix exponential of the augmented system, linear
  interpolation of the input) on a system with complex pairs and real eigenvalues, and its
  first-order-hold weights' series branch against the closed form (Chopra §5.2's ramp response);
* the bridge under the static axle loads against the library's moving-force solver
  (``vbikit.solve.moving_loads.moving_load_history``: the load table on the travel grid, one
  ``lfilter`` per mode) for a two-axle car of unequal axle loads on a two-span continuous beam of
  unequal spans (no symmetry that could hide a reversed axle order or span);
* the vehicle's response against the coupled run (``vbikit.solve.simulate``) for a light car on a
  rough road: the difference is the neglected interaction, first order in the mass ratio.

The light-vehicle limit against Yang & Lin's closed form is ``tests/driveby/test_dataset.py``.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vbikit.bridge.continuous import ContinuousBeam
from vbikit.driveby import sensor_cart, two_axle_car
from vbikit.driveby.decoupled import (WheelLines, _time_grid, bridge_under_forces, hold_weights, linear_response,
                                      relative_rms_error, simulate_decoupled)
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.solve.moving_loads import moving_load_history


def test_linear_response_equals_scipy_lsim():
    from scipy.signal import lsim

    rng = np.random.default_rng(5)
    n, m = 8, 3
    A = rng.standard_normal((n, n)) - 2.5 * np.eye(n)
    lam = np.linalg.eigvals(A)
    assert np.all(lam.real < 0), lam
    assert np.count_nonzero(lam.imag > 0) >= 1 and np.count_nonzero(lam.imag == 0) >= 1   # pairs and real ones
    B = rng.standard_normal((n, m))
    h = 0.01
    t = h * np.arange(600)
    u = np.column_stack([np.sin(3.0 * t), np.cos(7.0 * t) * t, rng.standard_normal(t.size)])
    x0 = rng.standard_normal(n)
    _, _, ref = lsim((A, B, np.eye(n), np.zeros((n, m))), u, t, X0=x0, interp=True)
    ours = linear_response(A, B, u, h, x0, n_rate=n)
    assert np.max(np.abs(ours[:, :n] - ref)) < 1e-10 * np.max(np.abs(ref))
    # the appended rates are ẋ = A x + B u at the samples
    assert np.max(np.abs(ours[:, n:] - (ref @ A.T + u @ B.T))) < 1e-9 * np.max(np.abs(ours[:, n:]))


def test_linear_response_of_a_defective_system_equals_scipy_lsim():
    # a critically damped oscillator has one double eigenvalue and one eigenvector (a Jordan block):
    # no eigenbasis, the direct state step is taken
    from scipy.signal import lsim

    w = 12.0
    A = np.array([[0.0, 1.0], [-w * w, -2.0 * w]])
    B = np.array([[0.0], [w * w]])
    h = 2e-3
    t = h * np.arange(800)
    u = np.sin(9.0 * t)[:, None]
    x0 = np.array([0.01, -0.2])
    _, _, ref = lsim((A, B, np.eye(2), np.zeros((2, 1))), u, t, X0=x0, interp=True)
    ours = linear_response(A, B, u, h, x0, n_rate=1)
    assert np.max(np.abs(ours[:, :2] - ref)) < 1e-10 * np.max(np.abs(ref))
    assert np.max(np.abs(ours[:, 2] - (ref @ A[1] + u[:, 0] * B[1, 0]))) < 1e-9 * np.max(np.abs(ours[:, 2]))


@pytest.mark.parametrize("lam", [-3.0 + 40.0j, -0.01 + 0.0j, 1e-3 + 1e-3j])
def test_hold_weights_both_branches_equal_the_block_exponential(lam):
    # ż = λz + u, u linear over the step: exp of [[λh, h, 0], [0, 0, 1], [0, 0, 0]] holds μ = e^{λh} and
    # β₀ + β₁, β₁ (the construction of scipy.signal.lsim); at |λh| = 1e-3 the closed form applies, at
    # 1e-5 the module's series
    from scipy.linalg import expm

    for h in (1e-3 / abs(lam), 1e-5 / abs(lam)):
        e = expm(np.array([[lam * h, h, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]], complex))
        mu, b0, b1 = hold_weights(np.array([lam]), h)
        assert abs(e[0, 0] - mu[0]) < 1e-15
        assert abs(e[0, 2] - b1[0]) < 1e-11 * h and abs(e[0, 1] - e[0, 2] - b0[0]) < 1e-11 * h


def _asymmetric_crossing(dt):
    bridge = ContinuousBeam(spans=(14.0, 20.0), EI=9e9, mass_per_length=6000.0, damping_ratio=0.03, n_modes=5)
    car = two_axle_car()
    return Crossing(bridge, car, speed=17.0, approach=0.0, dt=dt, free_vibration=0.3)


def test_bridge_under_two_axles_equals_the_moving_load_solver_on_unequal_spans():
    crossing = _asymmetric_crossing(1e-3)
    car, bridge = crossing.vehicles[0].vehicle, crossing.bridge
    loads = car.static_wheel_loads()
    assert abs(loads[0] - loads[1]) > 0.2 * loads.max()                     # unequal axle loads
    time = _time_grid(crossing)
    assert time[0] == 0.0 and crossing.front_positions(0.0)[0, 0] == 0.0   # front axle on the entry support at t = 0
    xi, xi_dot, xi_ddot = bridge_under_forces(crossing, time)
    lines = WheelLines.of(crossing)
    hist = moving_load_history(bridge, lines.offset, lines.load, 17.0, dx=17.0 * 1e-3, free_vibration=0.3)
    # its sample j is at t = (j − 1) h: ours k is its k + 1
    n = min(time.size, hist.time.size - 1)
    assert np.allclose(hist.time[1:n + 1], time[:n], atol=1e-12)
    for ours, ref in ((xi, hist.xi), (xi_dot, hist.xi_dot), (xi_ddot, hist.xi_ddot)):
        scale = np.max(np.abs(ref[1:n + 1]), axis=0)
        assert np.all(np.max(np.abs(ours[:n] - ref[1:n + 1]), axis=0) < 1e-9 * scale)


def test_light_vehicle_response_approaches_the_coupled_run_first_order_in_mass():
    from vbikit.bridge.beam import EulerBernoulliBeam

    bridge = EulerBernoulliBeam(span=25.0, EI=2.4e10, mass_per_length=4800.0, damping_ratio=0.02, n_modes=4)
    road = random_profile(RoadPSD.iso("A"), seed=4, length=45.0, x_start=-10.0)
    errors, forces = [], []
    for ratio in (1e-3, 4e-3):
        cart = sensor_cart(mass=ratio * 4800.0 * 25.0, frequency_hz=2.3, damping_ratio=0.1)
        crossing = Crossing(bridge, cart, speed=12.0, approach=2.0, road=road)
        coupled, decoupled = simulate(crossing), simulate_decoupled(crossing)
        assert np.array_equal(coupled.time, decoupled.time)
        assert coupled.wheel_forces.min() > 0.0                             # in contact throughout
        errors.append(relative_rms_error(decoupled.q_ddot[:, 0], coupled.q_ddot[:, 0]))
        # the displacement and the tire force (what the bridge feels) follow too (displacement achieved
        # 2.4e-5 and 9.5e-5; tire force 2.8e-5 and 1.1e-4)
        assert relative_rms_error(decoupled.q[:, 0], coupled.q[:, 0]) < 0.1 * ratio
        forces.append(relative_rms_error(decoupled.wheel_forces[:, 0], coupled.wheel_forces[:, 0]))
    # achieved 6.9e-4 and 2.75e-3: below the mass ratio, and growing in proportion to it (a damped cart:
    # the tire dashpot reads the road's rate as the engine does, v r'(x), and starts loaded by it)
    assert errors[0] < 1e-3, errors
    assert 3.6 < errors[1] / errors[0] < 4.4, errors
    assert forces[0] < 1e-4 and 3.6 < forces[1] / forces[0] < 4.4, forces


def test_scour_truck_pass_decoupled_close_to_coupled_at_its_light_limit():
    """The scour set's 5-axle truck over its continuous beam on support springs, a class A road, the
    truck's masses, stiffnesses and loads scaled to 1 % (same frequencies; mass ratio 7.6e-4): the
    decoupled record of the tractor body close to the coupled one (achieved 1.3e-3 relative RMS, about
    the mass ratio; at full mass the same pass differs by ≈ 0.1, docs/driveby.md)."""
    import dataclasses

    from vbikit.vehicle.axles import axle_truck

    truck = axle_truck(axle_loads=[58.86e3, 71.1225e3, 71.1225e3, 71.1225e3, 71.1225e3],
                       axle_spacings=[3.6, 1.3, 6.0, 1.3])
    light = dataclasses.replace(truck, mass=truck.mass * 0.01, stiffness=truck.stiffness * 0.01,
                                damping=truck.damping * 0.01, gravity=truck.gravity * 0.01,
                                wheels=tuple(dataclasses.replace(w, stiffness=w.stiffness * 0.01,
                                                                 damping=w.damping * 0.01, fixed_load=w.fixed_load * 0.01)
                                             for w in truck.wheels))
    bridge = ContinuousBeam(spans=(25.0,), EI=4.86535e10, mass_per_length=18358.0, damping_ratio=0.02, n_modes=4,
                            support_stiffness=2e8)
    road = random_profile(RoadPSD.iso("A"), seed=2, length=60.0, x_start=-20.0)
    crossing = Crossing(bridge, light, speed=20.0, approach=1.0, road=road)
    coupled, decoupled = simulate(crossing), simulate_decoupled(crossing)
    ratio = light.total_weight / 9.81 / (18358.0 * 25.0)
    assert math.isclose(ratio, 7.626e-4, rel_tol=1e-3), ratio
    err = relative_rms_error(decoupled.q_ddot[:, 0], coupled.q_ddot[:, 0])
    assert err < 2.5e-3, err


def test_passes_differing_only_in_their_road_share_the_bridge_solution(monkeypatch):
    from vbikit.bridge.beam import EulerBernoulliBeam
    from vbikit.driveby import decoupled

    bridge = EulerBernoulliBeam(span=20.0, EI=1.5e10, mass_per_length=5000.0, damping_ratio=0.02, n_modes=3)
    car = two_axle_car()
    roads = [random_profile(RoadPSD.iso("B"), seed=s, length=40.0, x_start=-10.0) for s in (1, 2)]
    crossings = [Crossing(bridge, car, speed=15.0, approach=2.0, road=r) for r in roads]
    decoupled._SHARED.clear()
    first = [simulate_decoupled(c) for c in crossings]             # the second reuses the first's bridge
    calls = []
    monkeypatch.setattr(decoupled, "line_shapes", lambda *a: calls.append(1) or pytest.fail("recomputed"))
    again = simulate_decoupled(crossings[1])
    assert not calls
    monkeypatch.undo()
    decoupled._SHARED.clear()
    fresh = simulate_decoupled(crossings[1])                         # computed anew
    for a, b in ((first[1], fresh), (again, fresh)):
        for name in ("xi", "xi_dot", "q", "q_ddot", "wheel_forces"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert not np.array_equal(first[0].q_ddot, first[1].q_ddot)     # the roads differ, the vehicles' records too
    first[1].xi[:] = 0.0                                             # a result's arrays are its own
    assert np.array_equal(simulate_decoupled(crossings[1]).xi, fresh.xi)
    n = len(decoupled._SHARED)
    simulate_decoupled(Crossing(bridge, car, speed=16.0, approach=2.0, road=roads[0]))   # another speed: its own
    assert len(decoupled._SHARED) == n + 1
