"""Several vehicles on one bridge: linearity, mirror symmetry, far-apart vehicles, VBI-2D.

Each test compares the coupled several-vehicle solution with an independent number: the sum
or the mirror image of single-vehicle runs (the bridge is linear; a symmetric bridge is
symmetric), a single crossing (vehicles far apart on a bridge that has come to rest), and
VBI-2D (DanielCanteroNTNU/VBI-2D in GNU Octave, tests/verification/vbi2d/).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vbikit.analysis import point_response
from vbikit.bridge import BRIDGE_PRESETS, EulerBernoulliBeam
from vbikit.road.profile import RoadProfile
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.solve import Crossing, simulate
from vbikit.solve.crossing import VehicleMotion
from vbikit.vehicle import VehicleBuilder, hs20_44, moving_force, semitrailer_3s2


def _beam(damping: float = 0.02, n_modes: int = 10) -> EulerBernoulliBeam:
    return BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=n_modes, damping_ratio=damping)


@pytest.fixture(scope="module")
def deck():
    return BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=8)


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


@pytest.mark.parametrize("lanes", ["same lane", "two lanes"])
def test_two_moving_forces_are_the_sum_of_the_single_runs(lanes, deck):
    """Linearity: two moving forces (one driving −x) give the sum of the two single runs.
    Entry times are chosen so that every run starts at t = 0 (same grid); measured ≤ 4.7e-15
    (ξ), 4.4e-14 (ξ̈), 4.6e-16 (static)."""
    bridge = _beam() if lanes == "same lane" else deck
    y = (0.0, 0.0) if lanes == "same lane" else (2.4, -2.4)
    approach = 10.0
    a = VehicleMotion(moving_force(120e3), speed=20.0, entry_time=approach / 20.0, lateral_offset=y[0])
    b = VehicleMotion(moving_force(80e3), speed=25.0, direction="-x", entry_time=approach / 25.0, lateral_offset=y[1])
    kw = dict(approach=approach, free_vibration=0.3, dt=2e-4)
    both = simulate(Crossing(bridge, vehicles=(a, b), **kw))
    one = simulate(Crossing(bridge, vehicles=(a,), **kw))
    two = simulate(Crossing(bridge, vehicles=(b,), **kw))
    n = min(one.time.size, two.time.size)
    np.testing.assert_array_equal(both.time[:n], one.time[:n])
    total = one.xi[:n] + two.xi[:n]
    assert _relative(both.xi[:n], total) < 1e-12
    assert _relative(both.xi_ddot[:n], one.xi_ddot[:n] + two.xi_ddot[:n]) < 1e-12
    # the static reference superposes too
    s_both = point_response(both, y=y[0]).static_displacement[:n]
    s_sum = point_response(one, y=y[0]).static_displacement[:n] + point_response(two, y=y[0]).static_displacement[:n]
    assert _relative(s_both, s_sum) < 1e-12


@pytest.mark.parametrize("bridge_kind", ["beam", "deck"])
def test_minus_x_is_the_mirror_of_plus_x(bridge_kind, deck):
    """A truck driving −x over a symmetric bridge on the mirrored road responds at x as the same
    truck driving +x responds at span − x (measured: 2.0e-15 beam, 1.8e-12 deck)."""
    bridge = _beam() if bridge_kind == "beam" else deck
    span = bridge.span
    # stations off the points' positions (−10 + 0.002 k m): at a station the slope of a
    # piecewise-linear road is that of the cell in +x, whichever way the point drives, which
    # would break the mirror symmetry of the road rate there
    road = random_profile(RoadPSD.iso("C"), seed=4, length=400.0, x_start=-200.0037)
    mirrored = RoadProfile(span - road.x[::-1], road.z[::-1], "mirrored")
    y0 = 0.0 if bridge_kind == "beam" else 1.4
    kw = dict(approach=10.0, free_vibration=0.2, dt=2e-4)
    plus = simulate(Crossing(bridge, road=road, vehicles=(VehicleMotion(hs20_44(), 20.0, lateral_offset=y0),), **kw))
    minus = simulate(Crossing(bridge, road=mirrored, vehicles=(VehicleMotion(hs20_44(), 20.0, direction="-x",
                                                                            lateral_offset=y0),), **kw))
    assert minus.wheel_forces.min() > 0  # stays in contact: the comparison is of the coupled solution
    # mirrored in x, the −x truck's left wheels (y = y0 − b) are the +x truck's right ones
    swap = [i + 1 if i % 2 == 0 else i - 1 for i in range(plus.wheel_forces.shape[1])]
    np.testing.assert_allclose(minus.wheel_forces, plus.wheel_forces[:, swap], rtol=0, atol=1e-9 * plus.wheel_forces.max())
    for x in (0.25 * span, 0.5 * span, 0.6 * span):
        for y in ((0.0,) if bridge_kind == "beam" else (-2.13, 2.13)):
            d_minus = point_response(minus, x, y).displacement
            d_plus = point_response(plus, span - x, y).displacement
            assert _relative(d_minus, d_plus) < 1e-11


def test_two_vehicles_far_apart_each_peak_as_a_single_crossing():
    """Two identical trucks 30 s apart on a damped bridge: the bridge is at rest before the second
    (e^(−ζωt) ≈ 1e-12), so each peak is that of a single crossing (history measured 7.6e-14)."""
    bridge = _beam(damping=0.02)
    gap = 30.0
    kw = dict(approach=10.0, free_vibration=0.5, dt=4e-4)
    single = point_response(simulate(Crossing(bridge, vehicles=(VehicleMotion(hs20_44(), 22.0, entry_time=0.0),), **kw)))
    pair = simulate(Crossing(bridge, vehicles=(VehicleMotion(hs20_44(), 22.0, entry_time=0.0),
                                               VehicleMotion(hs20_44(), 22.0, entry_time=gap)), **kw))
    resp = point_response(pair)
    first = resp.time < gap / 2
    second = resp.time >= gap - 1.0
    peak = single.displacement.min()
    assert resp.displacement[first].min() == pytest.approx(peak, rel=1e-11)
    assert resp.displacement[second].min() == pytest.approx(peak, rel=1e-11)
    assert resp.static_displacement.min() == pytest.approx(single.static_displacement.min(), rel=1e-12)
    # the second truck's history is the first one's, shifted by the gap (same grid: gap / dt steps)
    k = int(round(gap / kw["dt"]))
    n = single.displacement.size
    assert _relative(resp.displacement[k:k + n], single.displacement) < 1e-12


# -------------------------------------------------------------------- VBI-2D
VBI2D = Path(__file__).parent / "vbi2d" / "vbi2d_two_vehicles.csv"


def vbi2d_vehicle_2():
    """VBI-2D's two-axle ``Vehicle_2`` with the numbers of its ``E01_Example.m`` (planar: body heave
    and pitch, two axles; dj = ∓2.5 m from the body CG)."""
    vb = VehicleBuilder("vbi2d-vehicle-2")
    body = vb.body("body", 10500.0, 2.5, pitch_inertia=50000.0, pitch=True)
    for i, s in enumerate((0.0, 5.0)):
        axle = vb.body(f"axle{i + 1}", 900.0, s)
        vb.spring(body.point(s), axle.point(s), 6e6, 1e4)
        vb.wheel(f"axle{i + 1}", axle.point(s), s, 0.0, 1.75e6, 0.0)
    return vb.build()


def vbi2d_vehicle_2a3():
    """VBI-2D's five-axle ``Vehicle_2A3`` with the numbers of its ``E01_Example.m``: tractor
    (3100 kg, 5000 kg·m²) and semitrailer (20000 kg, 120000 kg·m²) pinned b1 = 3 m behind the
    tractor CG and a2 = 5 m ahead of the trailer CG; axles at dj = −1, 3.5 (tractor) and 2, 3.2,
    4.4 m (trailer) from their body's CG."""
    vb = VehicleBuilder("vbi2d-vehicle-2a3")
    tractor = vb.body("tractor", 3100.0, 1.0, pitch_inertia=5000.0, pitch=True)
    trailer = vb.hinged_body("trailer", 20000.0, 9.0, tractor, 4.0, pitch_inertia=120000.0)
    for i, (s, m, k_s, c_s, k_t, carrier) in enumerate((
            (0.0, 750.0, 6e6, 1e4, 1.75e6, tractor), (4.5, 750.0, 6e6, 1e4, 1.75e6, tractor),
            (11.0, 1100.0, 1e7, 2e4, 3.5e6, trailer), (12.2, 1100.0, 1e7, 2e4, 3.5e6, trailer),
            (13.4, 1100.0, 1e7, 2e4, 3.5e6, trailer))):
        axle = vb.body(f"axle{i + 1}", m, s)
        vb.spring(carrier.point(s), axle.point(s), k_s, c_s)
        vb.wheel(f"axle{i + 1}", axle.point(s), s, 0.0, k_t, 0.0)
    return vb.build()


def vbi2d_case(n_modes: int = 40) -> Crossing:
    """The VBI-2D run of tests/verification/vbi2d/two_vehicles.m: 25 m beam (ρA = 18358 kg/m,
    EI = 3.5e10 · 1.3901 N·m², undamped), Vehicle_2 driving −x at 70 km/h from x0 = 31 m,
    Vehicle_2A3 driving +x at 90 km/h from x0 = −2 m, smooth road, bilateral tires, 0.5 s of
    free vibration; Newmark average acceleration with VBI-2D's step."""
    beam = EulerBernoulliBeam(span=25.0, EI=3.5e10 * 1.3901, mass_per_length=18358.0, damping_ratio=0.0, n_modes=n_modes)
    v1, v2 = 70 / 3.6, 90 / 3.6
    return Crossing(beam, vehicles=(VehicleMotion(vbi2d_vehicle_2(), v1, direction="-x", entry_time=6.0 / v1),
                                    VehicleMotion(vbi2d_vehicle_2a3(), v2, direction="+x", entry_time=2.0 / v2)),
                    approach=2.0, free_vibration=0.5, loss_of_contact=False, dt=4.9998481213e-04, integrator="newmark")


def test_two_vehicles_in_opposite_directions_against_vbi2d():
    """VBI-2D (FE beam of 100 elements, coupled Newmark) vs vbikit (40 modes, Newmark, same step):
    midspan deflection 6.6e-7, static deflection 7.0e-7, contact forces 8.7e-8 of their peaks
    (measured; docs/verification.md)."""
    ref = np.loadtxt(VBI2D, delimiter=",", comments="#", skiprows=2)
    t_ref, u_ref, us_ref, f_ref = ref[:, 0], ref[:, 1], ref[:, 2], -ref[:, 3:]  # VBI-2D: forces down < 0
    crossing = vbi2d_case()
    # static axle loads: VBI-2D's at its first step (statically indeterminate five-axle truck)
    np.testing.assert_allclose(crossing.vehicle.static_wheel_loads(), f_ref[0], rtol=1e-9)
    result = simulate(crossing)
    resp = point_response(result)
    u = np.interp(t_ref, result.time, resp.displacement)
    us = np.interp(t_ref, result.time, resp.static_displacement)
    forces = np.stack([np.interp(t_ref, result.time, f) for f in result.wheel_forces.T], axis=1)
    assert _relative(u, u_ref) < 2e-6
    assert _relative(us, us_ref) < 2e-6
    assert _relative(forces, f_ref) < 3e-7
    assert resp.displacement.min() == pytest.approx(u_ref.min(), rel=1e-6)


def test_3s2_and_a_two_axle_truck_in_two_lanes_run(deck):
    """A smoke check of the 3D case in the docs: both trucks stay on the deck's wheel tracks and
    every wheel carries its static load before the run (equilibrium start)."""
    c = Crossing(deck, vehicles=(VehicleMotion(semitrailer_3s2(), 22.0, lateral_offset=2.4),
                                 VehicleMotion(vbi2d_vehicle_2(), 20.0, direction="-x", entry_time=0.3,
                                               lateral_offset=-2.4)), free_vibration=0.2)
    r = simulate(c)
    np.testing.assert_allclose(r.wheel_forces[0], c.vehicle.static_wheel_loads(), rtol=1e-9)
