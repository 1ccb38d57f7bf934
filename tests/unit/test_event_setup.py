"""The set-up of a traffic event's crossing, made cheaper without changing a number: the windowed
random road (the band's coefficients and chirp-z sums in place in one buffer, 2π n_k x0 kept
per grid and start), contact points of tires with one layout under every wheel, a one-vehicle
crossing's own contact points, the road extent's travel as floats, the event's road seed kept per
event.  Each is checked bit for bit against the separate-array form it replaced (written out here)
or against the general path that still serves every other case."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import scipy.fft as sp_fft

from vbikit.contact import MultiPointTire, PointTire, contact_points
from vbikit.contact.base import TireModel
from vbikit.contact.points import stack_contact_points
from vbikit.road import RoadPSD, random_profile
from vbikit.road.psd import WINDOW_QUANTUM, _amplitudes, _band_sum_factors, _phase_origin, _wavenumber_grid, _window_samples
from vbikit.solve import Crossing, VehicleMotion
from vbikit.vehicle import hs20_44
from vbikit.vehicle.axles import axle_truck


def _separate_arrays(psd: RoadPSD, seed: int, spacing: float, length: float, x_start, window):
    """The windowed road as summed before (every step on its own array): coefficients
    amp·exp(1j·(θ + 2π n_k x0 + shift)), then Re(post · ifft(fft(c·pre, size) · kernel)[:m])."""
    n_samples, period, k, n_k = _wavenumber_grid(psd, spacing, length)
    x0 = -period / 2 if x_start is None else float(x_start)
    theta = np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi, n_k.size)
    amp = np.sqrt(2.0 * psd(n_k) / period)
    first, last = _window_samples(window, x0, spacing, n_samples)
    m = last - first + 1
    shift = (2.0 * np.pi / n_samples) * ((k * first) % n_samples)
    band = amp * np.exp(1j * (theta + 2.0 * np.pi * n_k * x0 + shift))
    m_kept = -(-m // WINDOW_QUANTUM) * WINDOW_QUANTUM
    pre, kernel, post, size = _band_sum_factors(int(k[0]), int(band.size), int(n_samples), int(m_kept))
    conv = sp_fft.ifft(sp_fft.fft(band * pre, size) * kernel)[:m]
    return x0 + spacing * np.arange(first, last + 1), np.real(post[:m] * conv)


@pytest.mark.parametrize("road_class, spacing, length, x_start, window", [
    ("B", 0.01, 1000.0, None, (-15.056, 24.578)),
    ("C", 0.01, 1000.0, None, (-600.0, -540.3)),
    ("A", 0.02, 300.0, -40.0, (3.0, 3.0)),
    ("D", 0.05, 1000.0, 17.5, (100.0, 180.0)),
])
def test_windowed_road_is_bitwise_the_separate_array_sum(road_class, spacing, length, x_start, window):
    psd = RoadPSD.iso(road_class)
    for seed in (0, 7, 2**40 + 3):
        road = random_profile(psd, seed, spacing=spacing, length=length, x_start=x_start, window=window)
        x, z = _separate_arrays(psd, seed, spacing, length, x_start, window)
        assert np.array_equal(road.x, x) and np.array_equal(road.z, z)


def test_kept_phase_origins_serve_only_their_grid_and_start():
    """2π n_k x0 kept per (spectrum, spacing, length, x0) (``_phase_origin``): windows with two starts
    and two band limits asked for in turn, each again, are each the separate-array sum (a key without
    the start or the band would hand one the other's phases)."""
    _phase_origin.cache_clear()
    cases = [(RoadPSD.iso("B"), -30.0), (RoadPSD.iso("B"), 12.25), (RoadPSD.iso("B", n_max=2.0), -30.0)]
    for psd, x_start in cases + cases:
        road = random_profile(psd, 4, spacing=0.02, length=200.0, x_start=x_start, window=(0.0, 25.0))
        x, z = _separate_arrays(psd, 4, 0.02, 200.0, x_start, (0.0, 25.0))
        assert np.array_equal(road.x, x) and np.array_equal(road.z, z)
    info = _phase_origin.cache_info()
    assert (info.misses, info.hits) == (3, 3)
    n_k = _wavenumber_grid(cases[0][0], 0.02, 200.0)[3]
    assert not _phase_origin(cases[0][0], 0.02, 200.0, 1.0).flags.writeable
    assert np.array_equal(_phase_origin(cases[0][0], 0.02, 200.0, 1.0), 2.0 * np.pi * n_k * 1.0)
    assert _amplitudes(cases[0][0], 0.02, 200.0).shape == n_k.shape


class _PerWheel(PointTire):
    """A point tire through the per-wheel path (``contact_layout`` overridden, the same numbers)."""

    def contact_layout(self, stiffness, damping, static_load):
        return TireModel.contact_layout(self, stiffness, damping, static_load)


class _PerWheelMulti(MultiPointTire):
    def contact_layout(self, stiffness, damping, static_load):
        return TireModel.contact_layout(self, stiffness, damping, static_load)


@pytest.mark.parametrize("vehicle", [
    axle_truck([47800.0, 36780.0, 40910.0, 40670.0, 39630.0], [5.784, 1.367, 9.928, 1.384]),
    axle_truck([47530.0, 76600.0], [4.389]),
    hs20_44(),
], ids=["3s2", "2-axle", "hs20"])
@pytest.mark.parametrize("tire, per_wheel", [
    (PointTire(), _PerWheel()),
    (MultiPointTire(6), _PerWheelMulti(6)),
    (MultiPointTire(4, 0.3, "cells"), _PerWheelMulti(4, 0.3, "cells")),
    (MultiPointTire(1), _PerWheelMulti(1)),
])
def test_one_layout_contact_points_are_the_per_wheel_ones(vehicle, tire, per_wheel):
    fast, general = contact_points(vehicle, tire), contact_points(vehicle, per_wheel)
    for f in dataclasses.fields(fast):
        a, b = getattr(fast, f.name), getattr(general, f.name)
        assert a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b), f.name


def test_one_vehicle_crossing_has_its_vehicles_own_contact_points():
    from vbikit.bridge.presets import BRIDGE_PRESETS

    v = axle_truck([50000.0, 60000.0, 60000.0], [4.0, 1.3])
    c = Crossing(BRIDGE_PRESETS["paper-bridge-2-beam"].build(n_modes=2), vehicles=(VehicleMotion(v, 20.0),), tire=MultiPointTire(3))
    stacked = stack_contact_points([contact_points(v, MultiPointTire(3))], c.vehicle.dof_offsets)
    for f in dataclasses.fields(stacked):
        a, b = getattr(c.contact, f.name), getattr(stacked, f.name)
        assert a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b), f.name


def test_travel_at_one_time_is_the_arrays_travel():
    v = hs20_44()
    rng = np.random.default_rng(1)
    for i in range(400):
        a = [0.0, -2.5, 1.3, -1e-13][i % 4]
        ref = None if i % 3 else (float(rng.uniform(-2, 2)), float(rng.uniform(-30, 0)), float(rng.uniform(1, 30)))
        m = VehicleMotion(v, speed=float(rng.uniform(1, 40)), acceleration=a, entry_time=float(rng.uniform(-5, 5)),
                          reference=ref)
        t = rng.uniform(-20, 20, 3)
        assert np.array_equal([m._travel_at(float(x)) for x in t], m.travel(t))


def test_event_road_seed_is_the_derived_seed_of_each_event():
    """``TrafficStudy.road_seed`` keeps the last event's seed: asked for events in any order, each
    is still derive_seed(seed, event)."""
    from vbikit.study.spec import derive_seed
    from vbikit.traffic import LaneTraffic, synthetic_stream
    from vbikit.traffic.study import traffic_study

    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 2}, "road": {"class": "B", "length": 200.0}}
    job = traffic_study(synthetic_stream([LaneTraffic(1, "+x", 900, 80, 5)], 6, seed=2), base, lanes=[0.0], seed=11)
    for e in (0, 0, 3, 1, 1, 3, 0):
        assert job.road_seed(e) == derive_seed(11, e)


def _three_trucks_on_a_skew_deck():
    from vbikit.bridge import SlabOnGirderBridge

    deck = SlabOnGirderBridge(span=9.0, n_girders=3, n_modes=4, n_elements=6, skew=15.0, use_cache=False)
    trucks = [axle_truck([50e3, 70e3, 70e3], [4.2, 1.3]), axle_truck([45e3, 90e3], [5.0]),
              axle_truck([53e3, 75e3, 74e3, 76e3, 73e3], [5.5, 1.3, 9.5, 1.3])]
    motions = (VehicleMotion(trucks[0], 22.0, direction="+x", lateral_offset=-0.9),
               VehicleMotion(trucks[1], 19.0, acceleration=-1.5, direction="-x", entry_time=0.4, lateral_offset=0.8),
               VehicleMotion(trucks[2], 24.0, acceleration=0.7, direction="+x", entry_time=-0.3, lateral_offset=-0.2))
    return Crossing(deck, vehicles=motions, tire=MultiPointTire(3))


def test_leaving_distances_in_one_pass_are_each_vehicles_own():
    """``Crossing._leaving_distances`` (every vehicle's points at once) is ``leaving_distance`` of each
    vehicle's own points and direction, bit for bit, on a skew deck with traffic both ways (each wheel
    track's own far end); the exit time is the latest vehicle's time there."""
    c = _three_trucks_on_a_skew_deck()
    own = [c.leaving_distance(np.flatnonzero(c.point_vehicle == i), m.sign) for i, m in enumerate(c.vehicles)]
    assert c._leaving_distances() == own
    assert len(set(own)) == 3 and all(d > c.bridge.span for d in own)
    assert c.exit_time() == max(m.time_at(d) for m, d in zip(c.vehicles, own))


def test_travel_speed_of_every_vehicle_at_once_is_each_velocity():
    """``Crossing.travel_speed`` (every vehicle in one pass) is each motion's ``velocity`` bit for bit,
    braking (to rest after its stop time), accelerating and steady vehicles alike."""
    c = _three_trucks_on_a_skew_deck()
    t = np.linspace(c.start_time - 2.0, c.start_time + c.duration + 20.0, 997)
    want = np.stack([m.velocity(t) for m in c.vehicles], axis=1)
    got = c.travel_speed(t)
    assert got.shape == want.shape and np.array_equal(got, want)
    assert got[-1, 1] == 0.0 and got[-1, 2] > 24.0  # (the braking one has stopped by then)


def test_combined_stiffness_bound_is_the_whole_systems():
    """A combined vehicle's ‖M⁻¹K̂‖∞ (the step rule's bound on ω_max²) is its vehicles' largest, kept
    with each: the whole block-diagonal system's to round-off, and above its largest eigenvalue."""
    from scipy.linalg import eigh

    v = _three_trucks_on_a_skew_deck().vehicle
    whole = float(np.abs(np.linalg.solve(v.mass, v.stiffness + v.tire_stiffness_matrix())).sum(axis=1).max())
    assert v.stiffness_bound() == pytest.approx(whole, rel=1e-12)
    assert v.stiffness_bound() == max(p.stiffness_bound() for p in v.parts)
    assert eigh(v.stiffness + v.tire_stiffness_matrix(), v.mass, eigvals_only=True).max() <= v.stiffness_bound()
