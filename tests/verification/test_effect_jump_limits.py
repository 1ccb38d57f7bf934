"""Load-effect peaks at the jumps of the influence line (``vbikit.analysis.effects.jump_limits``).

A shear or reaction peaks at the instant τ an axle stands on a jump of its influence line (a
shear at its section, a reaction at the deck end): a one-sided limit R(τ∓).  Read at the steps
only, the peak was R(τ ∓ θ dt), θ ∈ [0, 1): the static part off by the line's slope times v θ dt,
the dynamic part by the wheel force's change ḟ_w θ dt — on a rough road it varies at the tire-hop
frequency f ≈ 10–15 Hz with amplitude A, so by up to 2π f A dt (a traffic event on paper Bridge 2,
class B road: the shear impact factor scattered by 1.3e-2 over step changes of 1 %).  With both
limits at every jump instant (positions exact, f_w linear and ξ cubic between the steps), what is
left is the interpolation's (π f dt)²/2 · A — and the integrator's own change over the step change.

* Closed forms on a simple span (one moving force, smooth road): the shear at s = 0.3 L peaks at
  +0.7 P (the force just right of s) and −0.3 P (on s, counted left) at the same instant, whichever
  way it drives; the reaction of the support it enters over is P at that instant (bridge at rest,
  mode shapes zero at the pinned support; the lifetime's 1 mm run gives P within 6e-5,
  tests/lifetime/test_knot_total.py).
* The traffic case: the impact factors' spread over the step × (1, 0.999, 0.997, 0.995, 0.99) and
  their distance from a run at 1/32 of the step read at its steps only (its sampling miss is 1/32
  of the coarse one).
"""
from __future__ import annotations

import dataclasses
import logging

import numpy as np
import pytest

from vbikit.analysis.effect_step import STEP_TOLERANCE
from vbikit.analysis.effects import jump_limits, load_effect_responses
from vbikit.analysis.impact import impact_factor
from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.lifetime.jobs import moving_forces
from vbikit.solve import Crossing, VehicleMotion, simulate
from vbikit.solve.plan import plan_run

L = 16.76
BEAM = EulerBernoulliBeam(L, 4.2e9, 9000.0, 0.02, n_modes=4)
P = 1e5
SPEED = 25.0


@pytest.fixture(autouse=True)
def _quiet():
    logging.disable(logging.WARNING)  # the coarse steps' load-effect step notes
    yield
    logging.disable(logging.NOTSET)


def _beam_run(direction: str, dt: float):
    motion = VehicleMotion(moving_forces((P,), ()), speed=SPEED, direction=direction)
    return simulate(Crossing(BEAM, vehicles=(motion,), dt=dt))


@pytest.mark.parametrize("direction", ["+x", "-x"])
@pytest.mark.parametrize("dt", [0.0031, 0.0037])
def test_shear_off_midspan_both_limits_at_its_section(direction, dt):
    """Shear just right of s = 0.3 L under one moving force: static +P (1 − s/L) with the force
    just right of s, −P s/L with it on s (closed form of a simple span), both at the instant it
    passes s — from the left driving +x (−0.3 P, then +0.7 P), from the right driving −x."""
    s = 0.3 * L
    shear = BEAM.load_effect("shear", s)
    result = _beam_run(direction, dt)
    (r,) = load_effect_responses(result, [shear])
    assert np.max(np.abs(r.static)) < 0.7 * P * (1 - 1e-4)  # the steps miss the one-sided limit
    assert r.impact.static_peak == pytest.approx(P * (1 - s / L), rel=1e-6)
    assert r.two_signed and r.opposite_static_peak == pytest.approx(-P * s / L, rel=1e-6)
    # the instant of both: the force on s
    tau = (s if direction == "+x" else L - s) / SPEED + result.crossing.vehicles[0].entry_time
    assert r.impact.time_static_peak == pytest.approx(tau, abs=2e-6 * dt)  # (read at τ ∓ 1e-6 dt)
    assert r.opposite.time_static_peak == pytest.approx(tau, abs=2e-6 * dt)
    order = np.sign(r.opposite.time_static_peak - r.impact.time_static_peak)
    assert order == (1.0 if direction == "-x" else -1.0)  # +x: −0.3 P first; −x: +0.7 P first


@pytest.mark.parametrize("direction, support", [("+x", 0), ("-x", 1)])
@pytest.mark.parametrize("dt", [0.0031, 0.0037])
def test_reaction_of_the_entry_support_is_the_force_as_it_enters(direction, support, dt):
    """The reaction of the support the force enters over (support 0 driving +x, 1 driving −x):
    static and total P at that instant (closed form); the steps read both up to a step later, the
    total 3–4 % low."""
    reaction = BEAM.load_effect("reaction", support=support)
    (r,) = load_effect_responses(_beam_run(direction, dt), [reaction])
    assert float(np.max(r.dynamic)) < P * (1 - 1e-2)  # sampled
    assert r.impact.static_peak == pytest.approx(P, rel=1e-6)
    assert r.impact.dynamic_peak == pytest.approx(P, rel=1e-3)  # the interpolation's error (module docstring)
    (other,) = load_effect_responses(_beam_run(direction, dt), [BEAM.load_effect("reaction", support=1 - support)])
    assert other.impact.static_peak == pytest.approx(P, rel=1e-6)  # leaving over the other: P at 0⁺ too


@pytest.mark.parametrize("dt", [0.0031, 0.0037])
def test_shear_at_the_entry_support_as_the_force_starts_on_it(dt):
    """A force that starts on the entry support (approach 0: the run's first instant is the jump's): the shear
    just right of x = 0 is P (1 − ξ/L) → P as the force moves on (closed form), the reaction of that support P
    (a new user's trial found the shear 1 % low, +99.00 against the reaction's +100.00 kN on
    examples/verification/fryba_moving_force.toml: the jump at the first instant was left out, and the steps
    read it a step later, at ξ = v dt)."""
    motion = VehicleMotion(moving_forces((P,), ()), speed=SPEED, direction="+x")
    result = simulate(Crossing(BEAM, vehicles=(motion,), dt=dt, approach=0.0))
    assert result.time[0] == pytest.approx(result.crossing.vehicles[0].entry_time, abs=1e-12)  # on the support at t0
    shear, reaction = BEAM.load_effect("shear", 0.0), BEAM.load_effect("reaction", support=0)
    r_shear, r_reaction = load_effect_responses(result, [shear, reaction])
    assert np.max(np.abs(r_shear.static)) < P * (1 - SPEED * dt / L / 2)  # the steps: a step in, at most
    assert r_shear.impact.static_peak == pytest.approx(P, rel=1e-6)
    assert r_shear.impact.dynamic_peak == pytest.approx(P, rel=1e-6)  # (the bridge at rest at that instant)
    assert r_reaction.impact.static_peak == pytest.approx(P, rel=1e-6)


# ---------------------------------------------------------------- a traffic event on paper Bridge 2
#: the spread bound: 2π f A dt · n I / R_st ≈ 1e-2 sampled (f = 15 Hz, A = 3 kN per wheel, dt = 1.4 ms,
#: n = 2 wheels of influence I ≈ 0.6 on a 45 kN static shear) against (π f dt)²/2 · A n I / R_st ≈ 2e-4
#: interpolated; the bound allows ten times that, a fifth of the sampled spread
SPREAD = 2e-3
SCALES = (1.0, 0.999, 0.997, 0.995, 0.99)


@pytest.fixture(scope="module")
def traffic_runs():
    """Five-axle truck (the stream's class 9, event 299 of benchmarks/bench_traffic.py) driving −x in
    lane 2 of paper Bridge 2 (10 modes, point tires, class B road), response girder 4: shear at 0 and
    at 5 m (off midspan), reaction at support 0 (its exit), moment at midspan; runs at the automatic
    step times SCALES and at 1/32 of it."""
    from vbikit.traffic import VehicleRecord
    from vbikit.traffic.study import traffic_study

    record = VehicleRecord(time=0.0, direction="-x", speed=19.972222222222225,
                           axle_loads=(46620.0, 29820.0, 36330.0, 35920.0, 35290.0),
                           axle_spacings=(5.396, 1.34, 9.584, 1.269), lane=2, id="v0", line=0)
    base = {"bridge": {"model": "paper-bridge-2", "n_modes": 10}, "tire": {"model": "point"},
            "road": {"class": "B", "spacing": 0.01},
            "response": {"girder": 4, "moment": [8.38], "shear": [0.0, 5.0], "reaction": [0]}}
    job = traffic_study([record], base, seed=11)  # a road on which the shear at 0 and the reaction peak at the exit jump
    crossing = job.crossing(0)
    effects = job.context().plan.load_effects
    dt0 = plan_run(crossing).grid.dt
    runs = {f: simulate(dataclasses.replace(crossing, dt=dt0 * f)) for f in SCALES + (1 / 32,)}
    return effects, runs


def test_traffic_event_impact_factors_do_not_depend_on_where_the_steps_fall(traffic_runs):
    effects, runs = traffic_runs
    fine = runs[1 / 32]
    reference = [impact_factor(r.time, r.dynamic, r.static).impact_factor
                 for r in load_effect_responses(fine, effects, check_step=False)]  # sampled: independent of the fix
    ims = np.array([[r.impact.impact_factor for r in load_effect_responses(runs[f], effects, check_step=False)]
                    for f in SCALES])
    sampled = np.array([[impact_factor(r.time, r.dynamic, r.static).impact_factor
                         for r in load_effect_responses(runs[f], effects, check_step=False)] for f in SCALES])
    kinds = [(e.kind, e.x) for e in effects]
    jumps = [k for k, (kind, _) in enumerate(kinds) if kind != "moment"]
    assert np.ptp(sampled[:, jumps], axis=0).max() > 2 * SPREAD  # the sampled peaks scatter (the case is one that does)
    for k, kind in enumerate(kinds):
        assert np.ptp(ims[:, k]) <= SPREAD, (kind, ims[:, k])
        assert np.abs(ims[:, k] - reference[k]).max() <= STEP_TOLERANCE, (kind, ims[:, k], reference[k])


def test_an_effects_limits_do_not_depend_on_its_companions(traffic_runs):
    effects, runs = traffic_runs
    result = runs[1.0]
    together = jump_limits(result, effects)
    for k, e in enumerate(effects):
        (alone,) = jump_limits(result, [e])
        assert alone[0].size >= 2  # a wheel crosses a jump of every line
        for a, b in zip(alone, together[k]):
            np.testing.assert_array_equal(a, b)


def test_limits_at_the_steps_are_the_sampled_histories(traffic_runs):
    """The limits' formula (positions, f_w linear, ξ Hermite, Q from the steps) at the steps
    themselves reproduces the sampled mode-acceleration histories (point tires; the influence values
    evaluated afresh, not the histories' tables): the limits carry no offset against the samples."""
    from vbikit.analysis.effects import influence_values
    from vbikit.analysis.instants import run_state

    effects, runs = traffic_runs
    result = runs[1.0]
    state = run_state(result, result.time[1:-1])
    bridge = result.crossing.bridge
    y = np.broadcast_to(state.y[None, :], state.x.shape)
    xi = bridge.span_coordinate(state.x, y)
    on = (xi >= 0) & (xi <= bridge.span)
    cp = result.crossing.contact
    static_loads = cp.weight * result.crossing.vehicle.static_wheel_loads()[cp.wheel]
    for e, r in zip(effects, load_effect_responses(result, effects, check_step=False)):
        g = np.zeros(state.x.shape)
        g[on] = influence_values([e], state.x[on], y[on])[:, 0]
        dynamic = -np.sum(g * state.f, axis=1) + state.q @ (e.modal / bridge.omega**2) + state.xi @ e.modal
        scale = np.abs(r.dynamic).max()
        assert np.abs(dynamic - r.dynamic[1:-1]).max() <= 1e-8 * scale
        assert np.abs(-(g @ static_loads) - r.static[1:-1]).max() <= 1e-10 * scale


def test_mode_superposition_has_no_limits(traffic_runs):
    """R = Σ r_i ξ_i does not jump: no limits, only the samples and (ξ smooth: no kinks) the extremes
    between them (``impact.smooth_vertices``: at most four, inside the run)."""
    effects, runs = traffic_runs
    for r in load_effect_responses(runs[1.0], effects, method="mode-superposition", check_step=False):
        assert r.limits is None
        t = r.peak_series[0]
        n = r.time.size
        np.testing.assert_array_equal(t[:n], r.time)
        assert 1 <= t.size - n <= 4 and np.all((t[n:] > r.time[0]) & (t[n:] < r.time[-1]))


def test_the_limits_formula_reproduces_multipoint_histories_at_the_steps():
    """With multi-point tires each point carries its own force, not its static share β_p f_w of the
    wheel's: the solver's modal forces Q_i are not Σ_p φ_i β_p f_w.  The run state the limits use
    (Q_i from the modal equation at the steps, ``vbikit.analysis.instants``) reproduces the sampled
    histories (``vbikit demo``'s crossing, 6 points a tire) at the steps to round-off; with Q_i summed
    from the static shares (the bridge's mode shapes) the same formula is off by more than 1e-3 of
    the largest value there (measured 1.2e-3 … 9.0e-3), an offset one-sided limits would carry."""
    from pathlib import Path

    from vbikit.analysis.effects import influence_values
    from vbikit.analysis.instants import run_state
    from vbikit.scenario import build, load_scenario

    built = build(load_scenario(Path(__file__).resolve().parents[2] / "src" / "vbikit" / "scenario" / "demo.toml"))
    result = simulate(built.crossing)
    effects = list(built.plan.load_effects)
    assert {e.kind for e in effects} == {"moment", "shear", "reaction"}
    bridge = result.crossing.bridge
    u = result.time[1:-1]
    state = run_state(result, u)
    y = np.broadcast_to(state.y[None, :], state.x.shape)
    on = (state.x >= 0) & (state.x <= bridge.span)
    phi = np.zeros(state.x.shape + (bridge.omega.size,))
    phi[on] = bridge.mode_shapes(state.x[on], y[on])
    static_shares = np.einsum("upi,up->ui", phi, state.f)
    offsets = {"steps": [], "static shares": []}
    for e, r in zip(effects, load_effect_responses(result, effects, check_step=False)):
        g = np.zeros(state.x.shape)
        g[on] = influence_values([e], state.x[on], y[on])[:, 0]
        for name, q in (("steps", state.q), ("static shares", static_shares)):
            dynamic = -np.sum(g * state.f, axis=1) + q @ (e.modal / bridge.omega**2) + state.xi @ e.modal
            offsets[name].append(np.abs(dynamic - r.dynamic[1:-1]).max() / np.abs(r.dynamic).max())
    assert max(offsets["steps"]) <= 1e-12
    assert min(offsets["static shares"]) > 1e-3


def test_no_vertex_across_the_station_kinks_of_a_line_between_girders():
    """A review's finding (2026-12-06): on a grillage a wheel line between two girders kinks at every
    element station (paper Bridge 2, 14 elements, skew 20°: its shear line at x = 3.1 m of girder 2
    on y = −2.8 m breaks by up to its largest slope), and the extremes between the samples
    (``impact.smooth_vertices``) were taken across them: the static peak came out 8.2e-4 *above* the
    exact static maximum, which no static peak can be (the dynamic one 1.0e-3 off).  With the
    stations in the kinks of such lines (``effects.station_kinks``) the static peak stays at or below
    the exact one (the maximum over the samples and limits of a run at 1/32 of the step: measured
    −7.1e-5) and the dynamic one within 5e-4 of that run's (measured −4.5e-5)."""
    from vbikit.analysis.effects import station_kinks
    from vbikit.bridge import paper_deck
    from vbikit.vehicle import hs20_44, semitrailer_3s2

    deck = paper_deck(2, n_modes=4, use_cache=False, n_elements=14, skew=20.0)
    shear = deck.load_effect("shear", x=3.1, girder=2)
    assert station_kinks(shear.influence, -2.8).size == 13 and station_kinks(shear.influence, 0.0).size == 0

    def run(dt):
        return simulate(Crossing(deck, vehicles=(VehicleMotion(semitrailer_3s2(), 22.0, lateral_offset=2.1),
                                                 VehicleMotion(hs20_44(), 19.0, direction="-x", entry_time=0.25,
                                                               lateral_offset=-1.7)), free_vibration=0.05, dt=dt))

    coarse = run(None)
    fine = run(float(coarse.time[1] - coarse.time[0]) / 32)
    (r,), (f,) = (load_effect_responses(x, [shear], check_step=False) for x in (coarse, fine))
    exact_static = np.abs(np.r_[f.static, f.limits()[2]]).max()
    fine_dynamic = np.abs(np.r_[f.dynamic, f.limits()[1]]).max()
    assert abs(r.impact.static_peak) <= exact_static * (1 + 1e-6)
    assert abs(abs(r.impact.dynamic_peak) - fine_dynamic) <= 5e-4 * fine_dynamic


def test_compiled_limit_sums_equal_those_of_the_influence_values(traffic_runs, monkeypatch):
    """The influence sums at the one-sided instants of tabulated lines are compiled (``line_sums``,
    the sampled histories' pass); the same limits from ``influence_values`` at the on-deck points
    (the path of untabulated lines) agree to round-off, on every effect (shears, reaction, moment)."""
    import vbikit.analysis.effects as effects_module

    effects, runs = traffic_runs
    result = runs[1.0]
    compiled = jump_limits(result, effects)
    monkeypatch.setattr(effects_module, "tabulated_together", lambda effects: False)
    plain = jump_limits(result, effects)
    for k, (a, b) in enumerate(zip(compiled, plain)):
        assert a[0].size >= 2
        np.testing.assert_array_equal(a[0], b[0])
        scale = np.abs(b[1]).max()
        assert np.abs(a[1] - b[1]).max() <= 1e-12 * scale, k
        assert np.abs(a[2] - b[2]).max() <= 1e-12 * scale, k


def _state_by_arrays(result, u):
    """``run_state``'s formulas (``vbikit.analysis.instants``, module docstring) restated with whole arrays
    (the implementation before the compiled pass, kept here as the reference): travel, positions, wheel
    forces linear, ξ cubic Hermite, Q from the modal equation at the two steps, linear, with the exact
    shares of the points passing a support line within the step (φ from ``hermite_rows`` of the run's
    tables, 0 off them)."""
    from vbikit.solve import system
    from vbikit.solve.tabulate import hermite_rows

    t = np.asarray(result.time, float)
    crossing = result.crossing
    bridge, cp = crossing.bridge, crossing.contact
    origin, sign, y = crossing.point_kinematics()
    travel = crossing.travel(u)
    x = origin[None, :] + sign[None, :] * travel[:, crossing.point_vehicle]
    k = np.searchsorted(t[1:-1], u) + 1
    km = k - 1
    h = t[k] - t[km]
    w = (u - t[km]) / h
    forces = result.wheel_forces
    wheel_forces = forces[km] * (1.0 - w)[:, None] + forces[k] * w[:, None]
    f = wheel_forces[:, cp.wheel] * cp.weight[None, :]
    h00, h10, h01, h11 = 2 * w**3 - 3 * w**2 + 1, w**3 - 2 * w**2 + w, -2 * w**3 + 3 * w**2, w**3 - w**2
    xi = (h00[:, None] * result.xi[km] + (h10 * h)[:, None] * result.xi_dot[km]
          + h01[:, None] * result.xi[k] + (h11 * h)[:, None] * result.xi_dot[k])
    omega, zeta = np.asarray(bridge.omega, float), np.asarray(bridge.damping_ratios, float)

    def at_steps(rows):
        return -(result.xi_ddot[rows] + result.xi_dot[rows] * (2.0 * zeta * omega) + result.xi[rows] * omega**2)

    q = (1.0 - w)[:, None] * at_steps(km) + w[:, None] * at_steps(k)
    x_ends = np.stack([origin + sign * crossing.travel(t[r])[:, crossing.point_vehicle] for r in (km, k)])
    xi_ends = bridge.span_coordinate(x_ends, np.broadcast_to(y, x_ends.shape))
    passing = np.zeros(f.shape, bool)
    for s in np.asarray(bridge.support_x, float):
        passing |= (xi_ends[0] - s) * (xi_ends[1] - s) <= 0.0
    data = result.kernel_data if result.kernel_data is not None else system.kernel_data(crossing)
    modes = data.modes
    for j, p in zip(*np.nonzero(passing)):
        wheel, weight, track = cp.wheel[p], cp.weight[p], data.points.track[p]
        for coef, xe, load in ((1.0, x[j, p], f[j, p]), (-(1.0 - w[j]), x_ends[0][j, p], forces[km[j], wheel] * weight),
                               (-w[j], x_ends[1][j, p], forces[k[j], wheel] * weight)):
            if modes.start[track] <= xe <= modes.end[track]:
                phi = hermite_rows(modes.start, modes.grid_h, modes.values, modes.slopes, np.array([track]),
                                   np.array([xe]), with_slopes=False)[0][0]
                q[j] += coef * phi * load
    return x, f, q, xi, travel, wheel_forces, passing.any(axis=1)


@pytest.mark.parametrize("case", ["traffic deck", "demo multipoint"])
def test_compiled_run_state_equals_the_array_formulas_between_the_steps(case, traffic_runs):
    """``run_state`` (compiled, one pass) against the same formulas with whole arrays, at instants
    spread between the steps (w ≠ 0, 1: the interpolations and the support-passing shares at work) and
    at every jump instant's one-sided limits: equal to round-off, on a deck event (two girder lines,
    point tires, 10 modes) and on the demo's beam (36 multi-point tire points, many passing the
    supports within a step)."""
    from pathlib import Path

    from vbikit.analysis.instants import run_state
    from vbikit.scenario import build, load_scenario

    if case == "traffic deck":
        result = traffic_runs[1][1.0]
    else:
        built = build(load_scenario(Path(__file__).resolve().parents[2] / "src" / "vbikit" / "scenario" / "demo.toml"))
        result = simulate(built.crossing)
    t = result.time
    rng = np.random.default_rng(7)
    between = t[:-1] + rng.uniform(0.05, 0.95, t.size - 1) * np.diff(t)
    crossing = result.crossing
    bridge = crossing.bridge
    entries = [crossing.times_at(np.full(1, s), np.array([v]))[0] for v in range(len(crossing.vehicles))
               for s in (0.0, bridge.span)]
    u = np.sort(np.concatenate([between, [e for e in entries if t[0] < e < t[-1]]]))
    state = run_state(result, u)
    x, f, q, xi, travel, wheel_forces, passing = _state_by_arrays(result, u)
    assert passing.sum() >= 3  # instants whose step has a point passing a support: the exact shares exercised
    for name, a, b in (("x", state.x, x), ("f", state.f, f), ("q", state.q, q), ("xi", state.xi, xi),
                       ("travel", state.travel, travel), ("wheel_forces", state.wheel_forces, wheel_forces)):
        assert a.shape == b.shape, name
        assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max(), name


@pytest.mark.parametrize("dt", [0.0031, 0.0037])
def test_shear_at_the_entry_end_when_the_run_starts_on_the_deck(dt):
    """A force that starts on the entry support (``approach = 0``, as the Frýba and Yang–Yau
    examples do): the shear just right of x = 0 jumps from 0 (the force on the support, counted
    left) to P (1 − v t/L) at the first instant, which the run's first step holds.  No parabola
    through a jump: the static peak is at most P (closed form of a simple span; the first step after
    the jump reads P (1 − v dt/L)), not the vertex of a parabola through the jump (≈ 1.11 P with
    the Frýba example's 50 modes, 1.12 P with Yang–Yau's)."""
    shear = BEAM.load_effect("shear", 0.0)
    motion = VehicleMotion(moving_forces((P,), ()), speed=SPEED)
    result = simulate(Crossing(BEAM, vehicles=(motion,), dt=dt, approach=0.0))
    (r,) = load_effect_responses(result, [shear])
    assert r.impact.static_peak <= P * (1 + 1e-9)
    assert r.impact.static_peak >= P * (1 - SPEED * dt / L) * (1 - 1e-9)
