"""The load effects a traffic stream stores per event against a brute-force reduction of the plain
``simulate`` result of the same crossing: each effect's influence read by ``DeckInfluence.direct``
(the consistent load of every (time, contact point) pair, ``load_weights``: no wheel-line tables, no
compiled sums), summed pair by pair, and the mode-acceleration correction written out
(``vbikit.analysis.effects``, module docstring: R = −Σ_p I β_p f_w − Σ_i r_i (ξ̈_i + 2ζ_i ω_i ξ̇_i)/ω_i²),
with both one-sided limits at the instants a contact point crosses a jump or kink of the line written
out too (each vehicle's own ``time_at``, f_w by ``np.interp``, ξ by scipy's cubic Hermite spline, Q_i
from the bridge's mode shapes, the influence by ``direct``), and the extremes between the samples
away from those instants and the deck ends (``np.polyfit``'s parabola through three samples);
and the compiled sums (``vbikit.analysis.line_sums``) against the numpy pair tables on a skew deck
with multi-point tires, two vehicles driving in opposite directions."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis import impact_factor
from vbikit.analysis.effects import contact_influence_table, contact_positions, load_effect_responses
from vbikit.bridge import paper_deck
from vbikit.contact import MultiPointTire
from vbikit.solve import Crossing, simulate
from vbikit.solve.crossing import VehicleMotion
from vbikit.traffic import LaneTraffic, synthetic_stream
from vbikit.traffic.study import traffic_study
from vbikit.vehicle import hs20_44, semitrailer_3s2

from tests.vertices_reference import written_out_vertices

#: Bridge 2's grillage with 4 modes, a class B road sampled every 0.05 m, short approach and free vibration
BASE = {"bridge": {"model": "paper-bridge-2", "n_modes": 4}, "road": {"class": "B", "length": 200.0, "spacing": 0.05},
        "crossing": {"approach": 5.0, "free_vibration": 0.1}}


def brute_force(result, effect):
    """(dynamic, static) histories of ``effect`` summed pair by pair from ``influence.direct``."""
    crossing = result.crossing
    bridge, cp = crossing.bridge, crossing.contact
    x, y = contact_positions(result)
    xi = bridge.span_coordinate(x, y)
    static_loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    static = np.zeros(x.shape[0])
    quasi = np.zeros(x.shape[0])
    for p in range(x.shape[1]):
        on = (xi[:, p] >= 0.0) & (xi[:, p] <= bridge.span)
        if on.any():
            infl = effect.influence.direct(x[on, p], y[on, p])
            static[on] -= infl * static_loads[p]
            quasi[on] -= infl * result.wheel_forces[on, cp.wheel[p]] * cp.weight[p]
    omega, zeta = bridge.omega, bridge.damping_ratios
    modal = sum(effect.modal[i] * (result.xi_ddot[:, i] + 2.0 * zeta[i] * omega[i] * result.xi_dot[:, i]) / omega[i]**2
                for i in range(omega.size))
    return quasi - modal, static


def brute_force_limits(result, effect):
    """(times, dynamic, static) at both one-sided limits τ ∓ 1e-6 dt of every instant τ a contact point
    stands on the effect's section (moment, shear) or a deck end (shear, reaction), written out
    (module docstring) with R = −Σ_p I β_p f_w + Σ_i r_i Q_i/ω_i² + Σ_i r_i ξ_i: Q_i from the modal
    equation at the two steps around the instant, linear between them, except for the points that
    pass a deck end within that step, whose share φ_i β_p f_w is taken from the bridge's own mode
    shapes (``vbikit.analysis.instants``, "steps"), one instant and one point at a time."""
    from scipy.interpolate import CubicHermiteSpline

    crossing = result.crossing
    bridge, cp = crossing.bridge, crossing.contact
    origin, sign, y = crossing.point_kinematics()
    t = result.time
    dt = t[1] - t[0]
    where = {"moment": [effect.influence.section], "shear": [effect.influence.section, 0.0, bridge.span],
             "reaction": [0.0, bridge.span]}[effect.kind]
    tau = set()
    for p in range(origin.size):
        motion = crossing.vehicles[crossing.point_vehicle[p]]
        for xi_j in where:
            when = motion.time_at((xi_j + y[p] * bridge.skew_tan - origin[p]) * sign[p])
            if t[0] < when < t[-1]:
                tau.add(when)
    u = np.array([v + d for v in sorted(tau) for d in (-1e-6 * dt, 1e-6 * dt)])
    x = np.stack([origin[p] + sign[p] * crossing.vehicles[crossing.point_vehicle[p]].travel(u) for p in range(origin.size)],
                 axis=1)
    f = np.stack([np.interp(u, t, result.wheel_forces[:, cp.wheel[p]]) * cp.weight[p] for p in range(origin.size)], axis=1)
    xi = CubicHermiteSpline(t, result.xi, result.xi_dot)(u)
    static_loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    omega, zeta = bridge.omega, bridge.damping_ratios
    dynamic, static = xi @ effect.modal, np.zeros(u.size)

    def position(p, when):
        return origin[p] + sign[p] * crossing.vehicles[crossing.point_vehicle[p]].travel(np.array([when]))[0]

    def on_deck(p, x_p):
        return 0.0 <= x_p - y[p] * bridge.skew_tan <= bridge.span

    def share(p, when, force):  # φ_i(x_p) β_p f_w of point p at ``when`` (zero off the deck)
        x_p = position(p, when)
        if not on_deck(p, x_p):
            return np.zeros(omega.size)
        return bridge.mode_shapes(np.array([x_p]), np.array([y[p]]))[0] * force

    for n, when in enumerate(u):
        k = int(np.searchsorted(t, when))  # t[k - 1] < when <= t[k]
        w = (when - t[k - 1]) / (t[k] - t[k - 1])
        q_steps = [-(result.xi_ddot[j] + 2 * zeta * omega * result.xi_dot[j] + omega**2 * result.xi[j]) for j in (k - 1, k)]
        q = (1 - w) * q_steps[0] + w * q_steps[1]
        for p in range(origin.size):
            ends = [position(p, t[j]) - y[p] * bridge.skew_tan for j in (k - 1, k)]
            if any((ends[0] - s) * (ends[1] - s) <= 0.0 for s in (0.0, bridge.span)):  # passes a deck end in the step
                forces = [result.wheel_forces[j, cp.wheel[p]] * cp.weight[p] for j in (k - 1, k)]
                linear = (1 - w) * share(p, t[k - 1], forces[0]) + w * share(p, t[k], forces[1])
                q = q + share(p, when, f[n, p]) - linear
        dynamic[n] += q @ (effect.modal / omega**2)
    for p in range(origin.size):
        on = (x[:, p] - y[p] * bridge.skew_tan >= 0.0) & (x[:, p] - y[p] * bridge.skew_tan <= bridge.span)
        if on.any():
            infl = effect.influence.direct(x[on, p], np.full(on.sum(), y[p]))
            dynamic[on] -= infl * f[on, p]
            static[on] -= infl * static_loads[p]
    return u, dynamic, static


def _line_breaks(effect, bridge, y):
    """The interior stations ξ_s at which the influence along the wheel line y kinks: its one-sided
    slopes by ``direct`` at ξ_s ∓ ε (ε = 1e-4 m, central differences over ε/2) differ by more than 1e-4
    of the line's largest slope (a grillage's line between two girders breaks at every station)."""
    stations = np.asarray(effect.influence.stations, float)[1:-1]
    eps = 1e-4
    xi = np.concatenate([stations + d for d in (-1.25 * eps, -0.75 * eps, 0.75 * eps, 1.25 * eps)])
    values = effect.influence.direct(xi + y * bridge.skew_tan, np.full(xi.size, y)).reshape(4, -1)
    left, right = (values[1] - values[0]) / (0.5 * eps), (values[3] - values[2]) / (0.5 * eps)
    scale = max(float(np.abs(np.r_[left, right]).max(initial=0.0)), 1e-300)
    return list(stations[np.abs(right - left) > 1e-4 * scale])


def brute_force_vertices(result, effect, dynamic, static):
    """(times, dynamic, static) at the extremes between the samples (``impact.smooth_vertices``),
    written out: for each history and sense its extreme sample, unless a contact point stands on the
    effect's section, a deck end or a station where its line kinks (``_line_breaks``; each vehicle's
    ``time_at``) within the two steps around it, the
    vertex of ``np.polyfit``'s parabola through the three samples, both histories' parabolas read there."""
    crossing = result.crossing
    bridge = crossing.bridge
    origin, sign, y = crossing.point_kinematics()
    t = result.time
    where = ([] if effect.kind == "reaction" else [effect.influence.section]) + [0.0, bridge.span]
    kinks = np.array([crossing.vehicles[crossing.point_vehicle[p]].time_at((xi_j + y[p] * bridge.skew_tan - origin[p]) * sign[p])
                      for p in range(origin.size) for xi_j in where + _line_breaks(effect, bridge, float(y[p]))])
    return written_out_vertices(t, dynamic, static, kinks)


def test_stream_load_effects_equal_a_brute_force_reduction_of_each_event():
    records = synthetic_stream([LaneTraffic(1, "+x", 1500, 80, 5), LaneTraffic(2, "-x", 1500, 70, 5)], 8, seed=4)
    job = traffic_study(records, BASE, seed=3, batch_size=8)
    assert any(len(m) > 1 for m in job.events)  # a multiple-presence event among them
    out = job.run_batch(tuple(range(job.size)))
    effects = job.context().plan.first_effects
    assert set(effects) == {"moment", "shear", "reaction"}
    moved = 0
    for e in range(job.size):
        result = simulate(job.crossing(e))  # the same crossing (its own road seed) as the event's
        for kind, effect in effects.items():
            dynamic, static = brute_force(result, effect)
            u, at_u, static_at_u = brute_force_limits(result, effect)
            v, at_v, static_at_v = brute_force_vertices(result, effect, dynamic, static)
            im = impact_factor(np.r_[result.time, u, v], np.r_[dynamic, at_u, at_v], np.r_[static, static_at_u, static_at_v])
            scale = np.abs(static).max()
            assert scale > 0
            # (the static peaks: the same positions and influence values; the dynamic ones: Q_i from the
            # bridge's mode shapes here, from the solver's mode tables in the library, ~1e-9 apart)
            assert abs(out[f"{kind}_static_peak"][e] - im.static_peak) <= 1e-11 * scale, (e, kind)
            assert abs(out[f"{kind}_dynamic_peak"][e] - im.dynamic_peak) <= 1e-8 * scale, (e, kind)
            assert out[f"{kind}_impact_factor"][e] == pytest.approx(im.impact_factor, rel=1e-7, abs=1e-9)
            sampled = impact_factor(result.time, dynamic, static)
            moved += abs(sampled.static_peak - im.static_peak) > 1e-6 * scale
    assert moved >= job.size  # the limits set the static peaks of one effect per event at least


@pytest.mark.parametrize("skew", [0.0, 20.0], ids=["straight", "skew 20°"])
def test_compiled_sums_equal_the_pair_tables_and_the_direct_influence(skew):
    deck = paper_deck(2, n_modes=4, use_cache=False, n_elements=14, skew=skew)
    c = Crossing(deck, vehicles=(VehicleMotion(semitrailer_3s2(), 22.0, lateral_offset=2.1),
                                 VehicleMotion(hs20_44(), 19.0, direction="-x", entry_time=0.25, lateral_offset=-1.7)),
                 tire=MultiPointTire(), free_vibration=0.05, dt=2e-3)
    result = simulate(c)
    effects = [deck.load_effect("moment", x=7.3, girder=4), deck.load_effect("shear", x=3.1, girder=2),
               deck.load_effect("reaction", support=0, girder=3), deck.load_effect("moment", x=8.38, girder=4),
               deck.load_effect("shear", x=deck.dof_map.stations[5], girder=1)]  # a section on a station
    compiled = load_effect_responses(result, effects)  # tabulated influences: the compiled sums
    tables = load_effect_responses(result, effects, influence=contact_influence_table(result, effects))
    for k, effect in enumerate(effects):
        dynamic, static = brute_force(result, effect)
        scale = np.abs(static).max()
        assert scale > 0
        for name, got in (("compiled", compiled[k]), ("tables", tables[k])):
            # round-off of the tables' cubics (≤ 1e-13 of the largest influence value) and of the sums
            assert np.abs(got.static - static).max() <= 1e-11 * scale, (name, effect.label)
            assert np.abs(got.dynamic - dynamic).max() <= 1e-11 * scale, (name, effect.label)
        assert np.abs(compiled[k].dynamic - tables[k].dynamic).max() <= 1e-12 * scale
        # the peaks: over the samples and the one-sided limits at the jumps, written out (skew: the
        # instants on each wheel line at x = ξ_j + y tan θ; two vehicles driving opposite ways)
        u, at_u, static_at_u = brute_force_limits(result, effect)
        assert u.size > 0
        v, at_v, static_at_v = brute_force_vertices(result, effect, dynamic, static)
        im = impact_factor(np.r_[result.time, u, v], np.r_[dynamic, at_u, at_v], np.r_[static, static_at_u, static_at_v])
        for got in (compiled[k], tables[k]):
            assert abs(got.impact.static_peak - im.static_peak) <= 1e-11 * scale, effect.label
            assert abs(got.impact.dynamic_peak - im.dynamic_peak) <= 1e-8 * scale, effect.label
