"""Identification from a passing vehicle, against independent numbers: the bridge's own modal
frequencies (closed form of a simply supported beam, and vbikit's damage model for a damaged
span, itself checked against Rayleigh's quotient below), the sampling theorem's resolution 1/T,
and the road profile the simulation used (roughness cancellation)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.bridge.damage import Damage
from vbikit.driveby import (Sampling, Sensor, SingleAxle, contact_acceleration_from_measured, frequency_labels,
                            identify_frequency, measure, mode_shape_squares, on_bridge, residual_response,
                            sensor_cart, shape_change, true_contact_response)
from vbikit.solve import Crossing, simulate

SPAN, EI, MASS = 25.0, 2.4e10, 4800.0
F1 = (math.pi / SPAN) ** 2 * math.sqrt(EI / MASS) / (2 * math.pi)  # 5.6199 Hz, Frýba 1972 ch. 1
RATE = 200.0


def pass_identify(bridge, speed, noise=0.0, seed=0):
    cart = sensor_cart()  # 120 kg: mass ratio 1e-3
    result = simulate(Crossing(bridge, cart, speed=speed, approach=5.0, dt=1.0 / (5 * RATE)))
    m = measure(result, [Sensor("acc", body="body", noise_rms=noise)], Sampling(RATE), seed=seed)
    t_on = result.time[on_bridge(result)]
    window = (m.time >= t_on[0]) & (m.time <= t_on[-1])
    a_c = contact_acceleration_from_measured(m.values[0], SingleAxle.of(cart), m.dt)
    return identify_frequency(a_c[window], RATE, speed, SPAN, band=(1.0, 20.0), bridge_hz=[F1])


@pytest.mark.parametrize("speed", [5.0, 7.5, 10.0])
def test_identified_first_frequency_within_one_percent_on_a_smooth_road(speed):
    bridge = EulerBernoulliBeam(span=SPAN, EI=EI, mass_per_length=MASS, n_modes=6)
    assert bridge.frequencies_hz[0] == pytest.approx(F1, rel=1e-12)
    ident = pass_identify(bridge, speed)
    assert abs(ident.frequency_hz / F1 - 1) < 0.01, ident.frequency_hz  # achieved 0.2–0.4 %
    assert ident.resolution_hz == pytest.approx(speed / SPAN, rel=0.01)  # 1 / T, T = L / v (to one sample)
    labels = ident.labels
    assert labels["driving_1"] == pytest.approx(speed / SPAN)
    assert labels["bridge_1_plus"] - labels["bridge_1_minus"] == pytest.approx(speed / SPAN)  # ω_b ± πv/L, 1/T apart


def test_damage_shift_identified_within_the_spectral_resolution():
    """A 30 % EI loss over 2.5 m at midspan: identified shift vs the damaged bridge's own shift."""
    healthy = ContinuousBeam(spans=(SPAN,), EI=EI, mass_per_length=MASS, n_modes=6)
    damaged = ContinuousBeam(spans=(SPAN,), EI=EI, mass_per_length=MASS, n_modes=6,
                             damage=(Damage(11.25, 2.5, 0.3),))
    # the damage model against Rayleigh's quotient with the intact shape φ ∝ sin(πx/L) as the
    # trial function (vbikit.bridge.damage): Δ(ω²)/ω² ≈ −s · share, share = ∫_region (φ'')² / ∫_0^L (φ'')²
    # = (b − a) − (sin 2πb − sin 2πa) / 2π with a, b the region's ends / L (by hand, 0.198 here).
    # Rayleigh's quotient bounds ω² from above, so the model's shift must be larger, and agree
    # to first order at a small severity.
    a, b = 11.25 / SPAN, 13.75 / SPAN
    share = (b - a) - (math.sin(2 * math.pi * b) - math.sin(2 * math.pi * a)) / (2 * math.pi)
    true_shift = damaged.frequencies_hz[0] / healthy.frequencies_hz[0] - 1
    assert true_shift < math.sqrt(1 - 0.3 * share) - 1 < 0  # −4.0 % below the bound −3.0 %
    slight = ContinuousBeam(spans=(SPAN,), EI=EI, mass_per_length=MASS, n_modes=1, damage=(Damage(11.25, 2.5, 0.01),))
    assert slight.frequencies_hz[0] / healthy.frequencies_hz[0] - 1 == pytest.approx(math.sqrt(1 - 0.01 * share) - 1, rel=0.05)
    for speed in (5.0, 10.0):
        f_h = pass_identify(healthy, speed).frequency_hz
        ident = pass_identify(damaged, speed)
        shift_hz = ident.frequency_hz - f_h
        true_hz = damaged.frequencies_hz[0] - healthy.frequencies_hz[0]
        assert shift_hz < 0
        assert abs(shift_hz - true_hz) < ident.resolution_hz  # achieved 0.003 / 0.016 Hz vs 1/T = 0.2 / 0.4 Hz


def test_roughness_cancels_in_the_residual_of_two_contact_points():
    """Two carts 4 m apart on one wheel line (class A road): the residual of their back-calculated
    contact responses holds no road — it equals the residual of the deck displacements alone."""
    from vbikit.road.psd import random_profile  # noqa: F401
    from vbikit.scenario import build, parse_scenario
    from vbikit.solve import VehicleMotion

    built = build(parse_scenario({"bridge": {"model": "beam", "span": SPAN, "EI": EI, "mass_per_length": MASS, "n_modes": 3},
                                  "vehicle": {"model": "sprung-mass"}, "road": {"class": "A", "seed": 2},
                                  "crossing": {"speed": 6.0, "approach": 8.0}}))
    c = built.crossing
    speed, gap = 6.0, 4.0
    cart = sensor_cart()
    crossing = Crossing(c.bridge, vehicles=(VehicleMotion(cart, speed), VehicleMotion(cart, speed, entry_time=gap / speed)),
                        road=c.road, approach=8.0, dt=1e-3)
    result = simulate(crossing)
    single = SingleAxle.of(cart)
    back = []
    for j in range(2):
        u = result.q[:, j] - result.q[0, j]
        u0 = float(true_contact_response(result, j)[0])
        from vbikit.driveby import contact_point_response

        back.append(contact_point_response(u, result.q_dot[:, j], result.q_ddot[:, j], single, result.dt) + u0)
    fs = 1.0 / result.dt
    residual = residual_response(back[0], back[1], fs, gap, speed)
    deck = residual_response(true_contact_response(result, 0, road=False), true_contact_response(result, 1, road=False),
                             fs, gap, speed)
    road_only = true_contact_response(result, 0) - true_contact_response(result, 0, road=False)
    ok = np.isfinite(residual)
    assert np.max(np.abs(residual[ok] - deck[ok])) < 1e-3 * np.max(np.abs(road_only))
    assert np.max(np.abs(back[0] - true_contact_response(result, 0, road=False))) > 0.5 * np.max(np.abs(road_only))


def test_mode_shape_squares_follow_sin_squared_and_shape_indicators():
    """The band-passed contact response's Hilbert envelope² along x = vt against sin²(πx/L) of the
    first mode (Frýba 1972), within the band-pass's edge effects."""
    bridge = EulerBernoulliBeam(span=SPAN, EI=EI, mass_per_length=MASS, n_modes=1, damping_ratio=0.0)
    cart = sensor_cart(mass=12.0)
    speed = 2.0
    result = simulate(Crossing(bridge, cart, speed=speed, approach=0.0, dt=2e-3, free_vibration=0.0))
    u_c = true_contact_response(result, road=False)
    acc = np.gradient(np.gradient(u_c, result.dt), result.dt)
    on = on_bridge(result)
    env = mode_shape_squares(acc[on], 1 / result.dt, F1, 1.0)
    x = result.time[on] * speed
    inner = (x > 0.15 * SPAN) & (x < 0.85 * SPAN)
    expected = np.sin(np.pi * x / SPAN) ** 2
    ind = shape_change(expected[inner], env[inner])
    assert ind["mac"] > 0.99, ind
    flat = shape_change(expected[inner], np.ones(inner.sum()))
    assert flat["mac"] < ind["mac"] and flat["shape_change"] > ind["shape_change"]


def test_frequency_labels_by_hand():
    labels = frequency_labels(10.0, 25.0, [4.0], [3.0], n_driving=2)
    assert labels == {"driving_1": 0.4, "driving_2": 0.8, "bridge_1": 4.0, "bridge_1_minus": 3.8,
                      "bridge_1_plus": 4.2, "vehicle_1": 3.0}


def test_spectra_of_a_known_tone_and_their_resolution():
    """A 7.3 Hz tone, 4 s at 100 Hz: the periodogram's peak at the tone, resolution 1/T = 0.25 Hz;
    Welch with 128-sample segments: resolution 100/128 Hz (sampling theorem, by hand)."""
    from vbikit.driveby import spectrum
    from vbikit.driveby.identify import peak

    fs, f0 = 100.0, 7.3
    t = np.arange(400) / fs
    x = np.sin(2 * np.pi * f0 * t) + 0.3 * np.sin(2 * np.pi * 21.0 * t)
    p = spectrum(x, fs)
    assert p.resolution_hz == pytest.approx(0.25)
    assert abs(peak(p, (1.0, 15.0)) - f0) <= p.resolution_hz / 32  # half the 16-fold zero-padded grid spacing
    assert peak(p, (15.0, 40.0)) == pytest.approx(21.0, abs=0.01)
    w = spectrum(x, fs, method="welch", nperseg=128)
    assert w.resolution_hz == pytest.approx(100.0 / 128.0)
    assert abs(peak(w, (1.0, 15.0)) - f0) <= w.resolution_hz / 32
    # excluding a known frequency ± 2/T leaves the next peak
    assert peak(p, (1.0, 40.0), exclude_hz=[f0]) == pytest.approx(21.0, abs=0.01)
