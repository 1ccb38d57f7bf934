"""The static start (``system.static_state``: Eq. 9 assembled in numpy by ``system.coupled_system``,
the contact law by the lean kernel's ``kernels.lean_law``) against a reference written out here:
Eq. 9 linearised about contact assembled point by point (the test's own loop over the points, from
the law in ``vbikit.solve.kernels``' docstring: K += k b bᵀ + c b gᵀ, C += c b bᵀ, F −= b (k (r − g)
+ c ṙ + f0), b = [φ_p; −h_w], g = v [φ'_p; 0]) and the general contact law kernel
(``kernels.contact_forces``), in the active-set iteration of ``static_state``'s docstring: solve
K u = F for the active points, drop those that do not press, repeat.  Same equations, sums in
another order: the states agree to round-off (asserted ≤ 1e-12 of each state's peak).  A
rigid-disk crossing keeps the general law (its envelopes), so its start is compared too.  The
assembled matrices themselves, damping and the convective term included, are compared as well.
"""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.scenario import demo_scenario_text, parse_scenario, scenario_from_toml
from vbikit.scenario.preflight import preflight
from vbikit.solve import Crossing, kernels
from vbikit.solve.crossing import VehicleMotion
from vbikit.solve.kernels import Road
from vbikit.solve.system import flat_road, kernel_data, point_positions, road_data, static_state
from vbikit.vehicle import hs20_44, semitrailer_3s2


def _assembled(data, x, vx, road, rate, active):
    """M, C, K, F of Eq. 9 at one instant, point by point (module docstring): the test's own assembly."""
    modes, veh, pts = data.modes, data.vehicles, data.points
    n_m, n_d, n_p = modes.omega.size, veh.gravity.size, x.size
    n = n_m + n_d
    mass, damp, stiff, load = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n)), np.zeros(n)
    mass[:n_m, :n_m], mass[n_m:, n_m:] = np.eye(n_m), veh.mass
    damp[:n_m, :n_m], damp[n_m:, n_m:] = np.diag(2.0 * modes.zeta * modes.omega), veh.damping
    stiff[:n_m, :n_m], stiff[n_m:, n_m:] = np.diag(modes.omega ** 2), veh.stiffness
    load[n_m:] = veh.gravity
    phi, dphi, on = np.zeros((n_p, n_m)), np.zeros((n_p, n_m)), np.zeros(n_p, bool)
    kernels.shapes_at(np.ascontiguousarray(x), pts.track, modes, phi, dphi, on)
    for p in range(n_p):
        if not active[p]:
            continue
        b, g = np.zeros(n), np.zeros(n)
        if on[p]:
            b[:n_m], g[:n_m] = phi[p], vx[p] * dphi[p]
        b[n_m:] = -veh.wheel_rows[pts.wheel[p]]
        k, c = pts.stiffness[p], pts.damping[p]
        stiff += k * np.outer(b, b) + c * np.outer(b, g)
        damp += c * np.outer(b, b)
        load -= b * (k * (road[p] - pts.gap[p]) + c * rate[p] + pts.fixed_load[p])
    return mass, damp, stiff, load


def _reference(data, road, travel, rate, speed):
    """The static start by the point-by-point assembly and ``kernels.contact_forces``."""
    n_m, n_p = data.n_modes, data.n_points
    x, vx = point_positions(data, travel, speed)
    rate = rate.copy()
    active = np.ones(n_p, bool)
    pts, veh = data.points, data.vehicles
    for first, count, env in zip(veh.wheel_first, veh.wheel_count, veh.wheel_envelope):
        if env:
            sl = slice(first, first + count)
            active[sl] = False
            active[first + int(np.argmax(road[sl] - pts.gap[sl]))] = True
            v = pts.direction[sl] * vx[sl]
            rate[sl] = np.clip(rate[sl], v * pts.slope_range[sl, 0], v * pts.slope_range[sl, 1])
    cache = kernels.new_cache(n_p, n_m, 1)._replace(x=x, vx=vx, rv=road.reshape(n_p, 1).copy(),
                                                    rr=rate.reshape(n_p, 1).copy(), have_r=np.ones(n_p, bool))
    work = kernels.new_work(n_p, data.n_dof, 1)
    wf, wl = np.zeros((data.n_wheels, 1)), np.zeros((data.n_wheels, 1))
    bundle = Road(np.array([0.0, 1.0]), np.zeros((1, 2, 1)), float(np.max(road, initial=0.0)))
    for _ in range(100):
        _, _, stiff, load = _assembled(data, x, vx, road, rate, active)
        u = np.linalg.solve(stiff, load)
        kernels.contact_forces(u[:n_m].reshape(n_m, 1).copy(), np.zeros((n_m, 1)), u[n_m:].reshape(-1, 1).copy(),
                               np.zeros((data.n_dof, 1)), data.modes, veh, pts, bundle, data.unilateral, cache, work,
                               wf, wl, kernels.MANY_LANES, 0.0)
        if np.array_equal(work.active[:, 0], active):
            return u[:n_m], u[n_m:], active
        active = work.active[:, 0].copy()
    raise AssertionError("reference start did not settle")


def _scenario(spec):
    return preflight(spec if not isinstance(spec, dict) else parse_scenario(spec)).built.crossing


def _two_vehicles():
    beam = EulerBernoulliBeam(span=30.0, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=12)
    road = random_profile(RoadPSD.iso("B"), length=120.0, seed=4, x_start=-50.0)
    return Crossing(beam, road=road, approach=3.0, free_vibration=0.1,
                    vehicles=(VehicleMotion(semitrailer_3s2(), 22.0, lateral_offset=1.2),
                              VehicleMotion(hs20_44(), 17.0, direction="-x", entry_time=0.4)))


CASES = {
    "demo": lambda: _scenario(scenario_from_toml(demo_scenario_text(), source="demo.toml")),
    "point": lambda: _scenario({"bridge": {"model": "paper-bridge-1-beam"}, "vehicle": {"model": "hs20-44"},
                                "tire": {"model": "point"}, "road": {"class": "B", "seed": 3},
                                "crossing": {"speed_kmh": 60.0}}),
    "two-vehicles": _two_vehicles,
    "rigid-disk": lambda: _scenario({"bridge": {"model": "paper-bridge-1-beam"}, "vehicle": {"model": "hs20-44"},
                                     "tire": {"model": "rigid-disk"}, "road": {"class": "D", "seed": 1},
                                     "crossing": {"speed_kmh": 100.0}}),
}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("where", [0.0, 0.5])
def test_flat_static_start_equals_the_general_kernels(case, where):
    """At the crossing's start (vehicles on the approach, deck at rest) and half-way (on the deck)."""
    crossing = CASES[case]()
    data = kernel_data(crossing)
    assert bool(np.any(data.vehicles.wheel_envelope)) == (case == "rigid-disk")
    t0 = crossing.start_time + where * crossing.duration
    travel, speed = crossing.travel(np.array([t0]))[0], crossing.travel_speed(np.array([t0]))[0]
    x, vx = point_positions(data, travel, speed)
    road = road_data([(crossing.road, crossing.road_right)], float(x.min()) - 1.0, float(x.max()) + 1.0)
    rv, rr = np.zeros((data.n_points, 1)), np.zeros((data.n_points, 1))
    kernels.road_at(x, vx, data.points, road, np.full(data.n_points, -1, np.int64), rv, rr, kernels.MANY_LANES, 0.0)
    assert np.any(rv != 0.0) and np.any(rr != 0.0)  # a rough road under a moving vehicle
    xi, q, active = static_state(crossing, data, rv[:, 0], travel, road_rate=rr[:, 0], speed=speed)
    xi_ref, q_ref, active_ref = _reference(data, rv[:, 0].copy(), travel, rr[:, 0].copy(), speed)
    np.testing.assert_array_equal(active, active_ref)
    assert np.max(np.abs(xi - xi_ref)) <= 1e-12 * np.max(np.abs(xi_ref))
    assert np.max(np.abs(q - q_ref)) <= 1e-12 * np.max(np.abs(q_ref))
    assert np.max(np.abs(q_ref)) > 0.0 and (where == 0.0 or np.max(np.abs(xi_ref)) > 0.0)


@pytest.mark.parametrize("case", ["demo", "two-vehicles"])
def test_flat_road_at_the_start_equals_road_at(case):
    """The road under the points at t = 0 of a one-lane crossing (``simulate``: ``system.flat_road``) against ``kernels.road_at``: the same linear interpolation, written
    as (z1 − z0)/Δs instead of (z1 − z0)·(1/Δs), so equal to round-off (asserted ≤ 1e-12 of the
    peak; the two-vehicle case drives one vehicle −x, the station rule for vx < 0)."""
    crossing = CASES[case]()
    data = kernel_data(crossing)
    n_p = data.n_points
    t0 = crossing.start_time + 0.5 * crossing.duration
    travel, speed = crossing.travel(np.array([t0]))[0], crossing.travel_speed(np.array([t0]))[0]
    x, vx = point_positions(data, travel, speed)
    road = road_data([(crossing.road, crossing.road_right)], float(x.min()) - 1.0, float(x.max()) + 1.0)
    rv, rr = np.zeros((n_p, 1)), np.zeros((n_p, 1))
    kernels.road_at(x, vx, data.points, road, np.full(n_p, -1, np.int64), rv, rr, kernels.MANY_LANES, 0.0)
    r0, dr0 = flat_road(data, road, x, vx)
    assert np.max(np.abs(r0 - rv[:, 0])) <= 1e-12 * np.max(np.abs(rv))
    assert np.max(np.abs(dr0 - rr[:, 0])) <= 1e-12 * np.max(np.abs(rr))
    assert np.any(vx < 0.0) == (case == "two-vehicles")


@pytest.mark.parametrize("case", ["demo", "two-vehicles"])
def test_coupled_system_equals_the_point_by_point_assembly(case):
    """``system.coupled_system`` (numpy, vectorised over the points) against ``_assembled`` (a loop over
    the points): M, C, K (with the convective term c v b φ'ᵀ, which only a moving vehicle on the deck
    has) and F, half-way across a rough road with every third point inactive, to round-off (≤ 1e-12
    of each matrix's largest entry).  The two-vehicle case drives one vehicle −x (v < 0)."""
    from vbikit.solve.system import coupled_system

    crossing = CASES[case]()
    data = kernel_data(crossing)
    t0 = crossing.start_time + 0.5 * crossing.duration
    travel, speed = crossing.travel(np.array([t0]))[0], crossing.travel_speed(np.array([t0]))[0]
    x, vx = point_positions(data, travel, speed)
    road = road_data([(crossing.road, crossing.road_right)], float(x.min()) - 1.0, float(x.max()) + 1.0)
    rv, rr = np.zeros((data.n_points, 1)), np.zeros((data.n_points, 1))
    kernels.road_at(x, vx, data.points, road, np.full(data.n_points, -1, np.int64), rv, rr, kernels.MANY_LANES, 0.0)
    active = np.arange(data.n_points) % 3 != 0
    got = coupled_system(data.modes, data.vehicles, data.points, x, vx, rv[:, 0], rr[:, 0], active)
    want = _assembled(data, x, vx, rv[:, 0], rr[:, 0], active)
    for name, a, b in zip(("M", "C", "K", "F"), got[:4], want):
        assert np.max(np.abs(a - b)) <= 1e-12 * np.max(np.abs(b)), name
    n_m = data.n_modes
    deck = want[2][:n_m, :n_m]
    # the convective term: K's deck block not symmetric (round-off would be ≈ 1e-16 of it)
    assert np.max(np.abs(deck - deck.T)) > 1e-9 * np.max(np.abs(deck))
    on = active & (data.modes.start[data.points.track] <= x) & (x <= data.modes.end[data.points.track])
    assert np.all(got[4][~on] == 0.0) and np.all(np.any(got[4][on] != 0.0, axis=1))
