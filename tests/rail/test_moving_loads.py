"""The fast moving-force solver against (1) the closed-form single-mode response of a simply
supported beam to a moving force (Frýba, *Vibration of Solids and Structures under Moving Loads*,
1972/1999, §1.2; written out below and superposed over the axles), (2) the resonance speed
v = n0 D of equally spaced axles, the growth of the resonant peak with their number and the
cancellation at L/d = (2i − 1)/2 (Yang, Yau & Hsu 1997, Eng. Struct. 19(11); derived below from the
same closed form), and (3) vbikit.solve.simulate with a moving-force vehicle."""
import math

import numpy as np
import pytest

from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.solve.moving_loads import moving_load_history, moving_load_sweep

SPAN, EI, MASS, ZETA = 15.0, 8.0e9, 12000.0, 0.01


def closed_form(t, speed, load, beam):
    """Midspan ξ₁(t) of one force ``load`` [N, downward] entering at t = 0 (first mode only).

    ξ̈ + 2ζωξ̇ + ω²ξ = F sin Ωt (0 ≤ t ≤ L/v), F = −P √(2/(mL)), Ω = πv/L, zero initial state:
    ξ = ξ_p + e^{−ζωt}(C cos ω_d t + D sin ω_d t), ξ_p = F[(ω² − Ω²) sin Ωt − 2ζωΩ cos Ωt]/Δ,
    Δ = (ω² − Ω²)² + (2ζωΩ)², C = 2ζωΩF/Δ, D = (ζωC − (ω² − Ω²)ΩF/Δ)/ω_d; after t_L = L/v free
    vibration from (ξ(t_L), ξ̇(t_L))."""
    L, m = beam.span, beam.mass_per_length
    w = float(beam.omega[0]); z = beam.damping_ratio
    wd = w * math.sqrt(1 - z * z)
    W = math.pi * speed / L
    F = -load * math.sqrt(2 / (m * L))
    dlt = (w * w - W * W) ** 2 + (2 * z * w * W) ** 2
    C = 2 * z * w * W * F / dlt
    D = (z * w * C - (w * w - W * W) * W * F / dlt) / wd

    def forced(t):
        e = np.exp(-z * w * t)
        xp = F * ((w * w - W * W) * np.sin(W * t) - 2 * z * w * W * np.cos(W * t)) / dlt
        vp = F * ((w * w - W * W) * W * np.cos(W * t) + 2 * z * w * W * W * np.sin(W * t)) / dlt
        xh = e * (C * np.cos(wd * t) + D * np.sin(wd * t))
        vh = -z * w * xh + e * wd * (-C * np.sin(wd * t) + D * np.cos(wd * t))
        return xp + xh, vp + vh

    t = np.asarray(t, float)
    tl = L / speed
    x_l, v_l = forced(np.array(tl))
    tau = t - tl
    free = np.exp(-z * w * tau) * (x_l * np.cos(wd * tau) + (v_l + z * w * x_l) / wd * np.sin(wd * tau))
    out = np.where(t <= tl, forced(np.clip(t, 0, tl))[0], free)
    return np.where(t < 0, 0.0, out)


def train_closed_form(t, speed, axles, loads, beam):
    return sum(closed_form(t - a / speed, speed, p, beam) for a, p in zip(axles, loads))


def one_mode(span=SPAN):
    return EulerBernoulliBeam(span, EI, MASS, ZETA, n_modes=1)


def test_history_matches_the_closed_form_with_unequal_axles():
    beam = one_mode()
    axles, loads = np.array([0.0, 2.5, 16.0, 19.0]), np.array([170e3, 150e3, 200e3, 120e3])
    v = 60.0
    h = moving_load_history(beam, axles, loads, v, dx=0.005, free_vibration=0.5)
    ref = train_closed_form(h.time, v, axles, loads, beam)
    err = np.max(np.abs(h.xi[:, 0] - ref)) / np.max(np.abs(ref))
    assert err < 2e-7  # first-order hold over 5 mm of travel (achieved 9e-8)


def _peak_acc(beam, axles, loads, speeds):
    env = moving_load_sweep(beam, axles, loads, speeds, [0.5 * beam.span], dx=0.01, free_vibration=1.0)
    return env.max_acceleration[:, 0], env.max_displacement[:, 0]


def test_first_resonance_speed_is_n0_times_spacing():
    beam = one_mode()
    n0, d = float(beam.frequencies_hz[0]), 20.0
    axles = d * np.arange(12)
    speeds = n0 * d * np.linspace(0.85, 1.15, 61)
    acc, _ = _peak_acc(beam, axles, np.full(12, 170e3), speeds)
    v_star = speeds[np.argmax(acc)]
    assert abs(v_star / (n0 * d) - 1) <= 0.005 + 1e-12  # the grid step is 0.5 %


@pytest.mark.parametrize("n", [1, 2, 4, 8])
def test_resonant_peak_grows_with_axles_as_the_closed_form(n):
    beam = one_mode()
    n0, d = float(beam.frequencies_hz[0]), 20.0
    v = n0 * d
    axles, loads = d * np.arange(n), np.full(n, 170e3)
    _, disp = _peak_acc(beam, axles, loads, [v])
    t = np.linspace(0, (SPAN + axles[-1]) / v + 1.0, 200001)
    ref = np.max(np.abs(train_closed_form(t, v, axles, loads, beam))) * math.sqrt(2 / (MASS * SPAN))
    assert disp[0] == pytest.approx(ref, rel=3e-6)  # achieved 8e-7 (the reference sampled at 2e5 points)


def test_cancellation_at_span_over_spacing_three_halves():
    """Undamped single mode: the free vibration a force leaves behind has amplitude ∝ |cos(ωL/(2v))|
    (closed form above with ζ = 0); at the resonance v = n0 d it vanishes when ωL/(2v) = (2i − 1)π/2,
    i.e. L/d = (2i − 1)/2 — Yang, Yau & Hsu's cancellation; L/d = 1 is the worst case."""
    growth = {}
    for ratio in (1.5, 1.0):
        d = SPAN / ratio
        beam = one_mode()
        v = float(beam.frequencies_hz[0]) * d
        ten, _ = _peak_acc(beam, d * np.arange(10), np.full(10, 170e3), [v])
        twenty, _ = _peak_acc(beam, d * np.arange(20), np.full(20, 170e3), [v])
        growth[ratio] = twenty[0] / ten[0]
    assert growth[1.5] == pytest.approx(1.0, abs=1e-3)  # no build-up: ten more axles add nothing
    assert growth[1.0] > 1.5  # resonant build-up continues


def test_matches_simulate_with_a_moving_force_vehicle():
    """The moving-load solver holds each mode's load linear over a step, as the exact integrator does
    with ``exact_step``'s linear hold: a crossing through ``run_implicit`` with those maps (registered
    here) gives the same histories to round-off.  (The built-in "exact" integrator holds the deck's load
    quadratic: docs/railway.md quotes that difference, the linear hold's error at these steps.)"""
    import dataclasses

    from vbikit.solve import Crossing, simulate
    from vbikit.solve.integrators import INTEGRATORS, get_integrator, register_integrator, run_implicit
    from vbikit.solve.modal_step import exact_step, vehicle_step
    from vbikit.vehicle.builder import VehicleBuilder
    from vbikit.vehicle.trains import hslm_a

    def linear_hold(call):
        run_implicit(call, exact_step(call.data.modes.omega, call.data.modes.zeta, call.dt),
                     vehicle_step(call.data.vehicles, call.dt))

    beam = EulerBernoulliBeam(20.0, 1.2e10, 15000.0, 0.015, n_modes=4)
    train = hslm_a(4)
    vb = VehicleBuilder("train")
    for k, (a, p) in enumerate(zip(train.axle_positions, train.axle_loads)):
        vb.wheel(f"a{k}", {}, float(a), 0.0, 0.0, 0.0, fixed_load=float(p))
    v, dx = 280 / 3.6, 0.05
    h = moving_load_history(beam, train.axle_positions, train.axle_loads, v, dx=dx, free_vibration=0.4)
    register_integrator(dataclasses.replace(get_integrator("exact"), name="exact-linear-hold", run=linear_hold))
    try:
        r = simulate(Crossing(beam, vb.build("train"), speed=v, approach=0.0, dt=dx / v, free_vibration=0.4,
                              integrator="exact-linear-hold"))
    finally:
        INTEGRATORS.pop("exact-linear-hold", None)
    n = min(r.time.size, h.time.size - 1)
    np.testing.assert_allclose(h.time[1:n + 1], r.time[:n], atol=1e-12)
    for mine, theirs in ((h.xi, r.xi), (h.xi_ddot, r.xi_ddot)):
        assert np.max(np.abs(mine[1:n + 1] - theirs[:n])) <= 5e-10 * np.max(np.abs(theirs))  # achieved 8.5e-11
