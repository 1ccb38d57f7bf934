# References: (1) statics of the paper's HS20-44 (Table 1 of "A Multi-Point Tire Model for
# Studying Bridge–Vehicle Coupled Vibration": masses 2612 + 26113 + 490 + 808 + 653 kg) with the
# geometry of docs/model-data.md §2 (axle 1 at 0, tractor CG 1.698, fifth wheel
# 3.913, axle 2 4.267, trailer CG 6.251, axle 3 8.534 m) — solved by hand below (both bodies are
# statically determinate); model data §2 quotes ≈ 30.7 / 134.2 / 136.0 kN.  (2) The exact
# Euler–Bernoulli influence line of midspan deflection, w = P a (3L² − 4a²) / (48 EI) for a load
# at a ≤ L/2 (any strength-of-materials text, e.g. Roark's Formulas, simply supported beam).
# (3) Trivial identities: a zero road is no road; a vehicle at rest on flat ground stays at rest.
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis import point_response
from vbikit.bridge import paper_beam
from vbikit.road import RoadProfile
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import GRAVITY, hs20_44
from vbikit.contact import MultiPointTire, PointTire

G = GRAVITY
M_TRACTOR, M_TRAILER, M_AXLES = 2612.0, 26113.0, (490.0, 808.0, 653.0)
S_TRACTOR, S_FIFTH, S_AXLE2, S_TRAILER, S_AXLE3 = 1.698, 3.913, 4.267, 6.251, 8.534


def hand_axle_loads() -> np.ndarray:
    """Static axle loads [N] by statics: trailer on fifth wheel + axle 3, tractor on axles 1, 2."""
    w_trailer = M_TRAILER * G
    r3 = w_trailer * (S_TRAILER - S_FIFTH) / (S_AXLE3 - S_FIFTH)
    r_fifth = w_trailer - r3
    w_tractor = M_TRACTOR * G
    r2 = (w_tractor * S_TRACTOR + r_fifth * S_FIFTH) / S_AXLE2
    r1 = w_tractor + r_fifth - r2
    return np.array([r1, r2, r3]) + np.array(M_AXLES) * G


def test_hs20_static_wheel_loads():
    veh = hs20_44()
    loads = veh.static_wheel_loads()
    total = (M_TRACTOR + M_TRAILER + sum(M_AXLES)) * G  # 30 676 kg · g
    assert loads.sum() == pytest.approx(total, rel=1e-12)
    axle = loads.reshape(3, 2).sum(axis=1)  # wheels are (left, right) per axle
    assert np.allclose(loads[0::2], loads[1::2], rtol=1e-12)  # symmetric: no roll load
    assert np.allclose(axle, hand_axle_loads(), rtol=1e-10)  # statically determinate: exact
    assert np.allclose(axle / 1e3, [30.7, 134.2, 136.0], atol=0.05)  # model data §2, rounded to 0.1 kN
    assert [w.offset for w in veh.wheels[::2]] == pytest.approx([0.0, S_AXLE2, S_AXLE3], abs=1e-12)


def _influence(a: np.ndarray, span: float, EI: float) -> np.ndarray:
    """Midspan deflection [m, positive down] per newton at x = a (zero off the span)."""
    b = np.where(a <= span / 2, a, span - a)
    return np.where((a >= 0) & (a <= span), b * (3 * span**2 - 4 * b**2) / (48 * EI), 0.0)


def test_very_slow_crossing_is_quasi_static():
    n_modes = 5
    beam = paper_beam(16.76, "II", n_modes=n_modes, damping_ratio=0.05)
    veh = hs20_44()
    r = simulate(Crossing(beam, veh, speed=0.5, approach=1.0))
    x = r.front_position[:, :1] - np.array([w.offset for w in veh.wheels])[None, :]
    exact_static = -(_influence(x, beam.span, beam.EI) * veh.static_wheel_loads()).sum(axis=1)
    peak = np.abs(exact_static).max()
    # modal truncation of the static deflection at midspan: |Σ_{j>5} …| ≤ (2/π⁴)(PL³/EI) Σ_{j≥6} 1/j⁴
    # per newton of load; relative to the peak (≥ the central-load value for the heaviest axle)
    trunc = sum(2 / np.pi**4 * beam.span**3 / beam.EI / j**4 for j in range(n_modes + 1, 2000))
    trunc_rel = trunc * veh.static_wheel_loads().sum() / peak
    pr = point_response(r)
    # vbikit's static reference (same modes, same path) vs the exact influence line
    assert np.abs(pr.static_displacement - exact_static).max() <= trunc_rel * peak + 1e-12
    # dynamic at 0.5 m/s: α = v/(2 f1 L) ≈ 2e-3 → DAF − 1 ≈ α; 5 % damping kills the entry
    # transient.  Brief: within 1 % (plus the truncation bound, because exact_static has all modes)
    assert np.abs(r.displacement() - exact_static).max() <= (0.01 + trunc_rel) * peak
    assert abs(pr.displacement_impact.impact_factor) < 2e-3  # ≤ α (a priori); measured 3.7e-6


@pytest.mark.parametrize("tire", [PointTire(), MultiPointTire(n_points=6)])
def test_zero_roughness_road_equals_smooth(tire):
    beam = paper_beam(16.76, "II", n_modes=10)
    x = np.arange(-60.0, 60.0, 0.01)
    smooth = simulate(Crossing(beam, hs20_44(), tire=tire, road=None, speed=20.0, approach=10.0))
    zero = simulate(Crossing(beam, hs20_44(), tire=tire, road=RoadProfile(x, np.zeros_like(x)), speed=20.0,
                             approach=10.0))
    for field in ("time", "xi", "xi_dot", "xi_ddot", "q", "q_dot", "q_ddot", "wheel_forces", "contact_lengths"):
        assert np.array_equal(getattr(smooth, field), getattr(zero, field)), field


@pytest.mark.parametrize("integrator", ["rk4", "newmark"])
def test_vehicle_at_rest_on_flat_approach(integrator):
    beam = paper_beam(16.76, "II", n_modes=10)
    veh = hs20_44()
    r = simulate(Crossing(beam, veh, speed=20.0, approach=30.0, free_vibration=0.0, integrator=integrator))
    before = r.front_position[:, 0] < 0.0  # no contact point on the deck yet
    assert before.sum() > 1000
    assert np.abs(r.q[before] - r.q[0]).max() <= 1e-12  # [m, rad]; |q| ~ 0.06
    # the step's contact iteration stops at a wheel-force residual of 1e-10 of the largest wheel
    # load (one evaluation and exact updates, vbikit.solve.kernels.newton): the resting vehicle's
    # velocities stay at that round-off level (measured 1.3e-13 m/s with Newmark), not exactly 0
    assert np.abs(r.q_dot[before]).max() <= 1e-11
    assert np.abs(r.xi[before]).max() == 0.0  # nothing loads the bridge
    assert np.allclose(r.q[0], veh.static_state(), rtol=1e-12, atol=1e-15)
    assert np.allclose(r.wheel_forces[before], veh.static_wheel_loads()[None, :], rtol=1e-10)
