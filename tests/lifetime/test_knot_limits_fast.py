"""The vectorised knot limits (``vbikit.lifetime.peaks.knot_limits``, ``with_knot_limits``,
``knot_instants``) against the code they replace: the per-vehicle loop of instants, the histories
concatenated and put in order by a stable ``argsort``, the totals one instant and one point at a
time and the extremes between the samples (written out here as the reference: times and static
values bit-identical but the vertices', those and the totals to round-off), and the several lines of one run at once against each line alone (bit-identical).  Also the motions of
all vehicles at once (``Crossing.travel``, ``Crossing.times_at``) against each ``VehicleMotion``'s own."""
from __future__ import annotations

import logging

import numpy as np
import pytest

from vbikit.analysis.effects import load_effect_responses
from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.lifetime.influence import Tabulated, effect_line
from vbikit.lifetime.jobs import moving_forces
from vbikit.lifetime.peaks import KNOT_OFFSET, _merged, _tracks, knot_instants, knot_limits, with_knot_limits
from vbikit.solve import Crossing, VehicleMotion, simulate

from tests.vertices_reference import written_out_vertices

L = 16.76
BRIDGE = EulerBernoulliBeam(L, 4.2e9, 9000.0, 0.02, n_modes=4)
MOTIONS = (VehicleMotion(moving_forces((1e5, 2e5), (4.0,)), speed=25.0),
           VehicleMotion(moving_forces((1e5, 1e5, 1e5), (3.0, 1.2)), speed=22.0, acceleration=-2.0, direction="-x",
                         entry_time=0.4))


@pytest.fixture(scope="module")
def run():
    """Two vehicles (one +x at constant speed, one −x braking) at a 3 ms step, and three lines on one
    grid (entry reaction, midspan moment, shear at L/3: knots partly shared)."""
    logging.disable(logging.WARNING)
    try:
        effects = [BRIDGE.load_effect("reaction", support=0), BRIDGE.load_effect("moment", x=L / 2),
                   BRIDGE.load_effect("shear", x=L / 3)]
        tables = [Tabulated(effect_line(BRIDGE, e, f"line{j}"), BRIDGE, [-0.9, 0.9], 0.1) for j, e in enumerate(effects)]
        result = simulate(Crossing(BRIDGE, vehicles=MOTIONS, dt=0.003))
        responses = load_effect_responses(result, effects, check_step=False)
    finally:
        logging.disable(logging.NOTSET)
    return result, effects, tables, responses


def _reference_instants(crossing, table, t0, t1):
    """The instants as the code before computed them: the (point, node) pairs, one vehicle at a time
    through ``VehicleMotion.times_at``, ``np.unique``."""
    origin, sign, y = crossing.point_kinematics()
    rows = np.asarray(table.row, np.int64)[_tracks(table, y)]
    point, knot = [], []
    for p, r in enumerate(rows):
        for n in range(table.active_ptr[r], table.active_ptr[r + 1]):
            point.append(p)
            knot.append(n)
    point, knot = np.array(point), np.array(knot)
    s = (table.knots[0][knot] - origin[point]) * sign[point]
    tau = np.empty(point.size)
    for i, motion in enumerate(crossing.vehicles):
        mine = crossing.point_vehicle[point] == i
        tau[mine] = motion.times_at(s[mine])
    return np.unique(tau[np.isfinite(tau) & (tau > t0) & (tau < t1)])


def _reference_limits(result, effect, table, dynamic, static):
    """``with_knot_limits`` as written before: the same formulas at u = τ ∓ δ, the whole wheel-force
    history indexed, the histories concatenated and ordered by a stable ``argsort``."""
    t = result.time
    crossing = result.crossing
    origin, sign, y = crossing.point_kinematics()
    track = _tracks(table, y)
    tau = _reference_instants(crossing, table, t[0], t[-1])
    delta = KNOT_OFFSET * float(t[1] - t[0])
    u = np.column_stack([tau - delta, tau + delta]).ravel()
    x = origin[None, :] + sign[None, :] * np.stack([m.travel(u) for m in crossing.vehicles], axis=1)[:, crossing.point_vehicle]
    g = table(x.ravel(), np.broadcast_to(track, x.shape).ravel()).reshape(x.shape)
    k = np.clip(np.searchsorted(t, u), 1, t.size - 1)
    h = t[k] - t[k - 1]
    w = (u - t[k - 1]) / h
    cp = crossing.contact
    forces = result.wheel_forces[:, cp.wheel]
    f = (forces[k - 1] * (1.0 - w)[:, None] + forces[k] * w[:, None]) * cp.weight[None, :]
    h00, h10, h01, h11 = 2 * w**3 - 3 * w**2 + 1, w**3 - 2 * w**2 + w, -2 * w**3 + 3 * w**2, w**3 - w**2
    xi = (h00[:, None] * result.xi[k - 1] + (h10 * h)[:, None] * result.xi_dot[k - 1]
          + h01[:, None] * result.xi[k] + (h11 * h)[:, None] * result.xi_dot[k])
    # Q_i from the modal equation at the two steps, linear between them; a point passing a support
    # (ξ = 0 or L) within the step: its share φ_i β_p f_w exact (the bridge's mode shapes)
    omega, zeta = BRIDGE.omega, BRIDGE.damping_ratios
    q_at = lambda j: -(result.xi_ddot[j] + result.xi_dot[j] * (2 * zeta * omega) + result.xi[j] * omega**2)  # noqa: E731
    q = (1.0 - w)[:, None] * q_at(k - 1) + w[:, None] * q_at(k)

    def share(when, p, force):
        x_p = origin[p] + sign[p] * crossing.vehicles[crossing.point_vehicle[p]].travel(np.array([when]))[0]
        on = 0.0 <= x_p <= BRIDGE.span
        return BRIDGE.mode_shapes(np.array([x_p]), np.array([y[p]]))[0] * force if on else 0.0

    for n in range(u.size):
        for p in range(origin.size):
            ends = [origin[p] + sign[p] * crossing.vehicles[crossing.point_vehicle[p]].travel(np.array([t[j]]))[0]
                    for j in (k[n] - 1, k[n])]
            if any((ends[0] - s) * (ends[1] - s) <= 0.0 for s in (0.0, BRIDGE.span)):
                fa, fb = (result.wheel_forces[j, cp.wheel[p]] * cp.weight[p] for j in (k[n] - 1, k[n]))
                q[n] += share(u[n], p, f[n, p]) - ((1 - w[n]) * share(t[k[n] - 1], p, fa) + w[n] * share(t[k[n]], p, fb))
    r = np.asarray(effect.modal, float)
    total = np.sum(g * f, axis=1) + q @ (r / BRIDGE.omega**2) + xi @ r
    st = g @ (cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel])
    v, v_dyn, v_st = _reference_vertices(result, dynamic, static, tau)
    time = np.concatenate([t, u, v])
    order = np.argsort(time, kind="stable")
    return (time[order], np.concatenate([dynamic, total, v_dyn])[order],
            np.concatenate([static, st, v_st])[order])


def _reference_vertices(result, dynamic, static, tau):
    """The extremes between the samples (``impact.smooth_vertices``) written out: per history and sense
    its extreme sample, unless a knot instant ``tau`` or a point on a deck end (each vehicle's
    ``time_at``) lies within the two steps around it, the vertex of ``np.polyfit``'s parabola through
    the three samples, both histories' parabolas read there."""
    t = result.time
    crossing = result.crossing
    origin, sign, _ = crossing.point_kinematics()
    ends = [crossing.vehicles[crossing.point_vehicle[p]].time_at((x - origin[p]) * sign[p])
            for p in range(origin.size) for x in (0.0, BRIDGE.span)]
    kinks = np.concatenate([tau, np.array(ends, float)])
    return written_out_vertices(t, dynamic, static, kinks)


def test_knot_instants_as_before(run):
    result, _, tables, _ = run
    t = result.time
    for table in tables:
        ref = _reference_instants(result.crossing, table, t[0], t[-1])
        assert ref.size >= 5  # both vehicles over the line's knots
        np.testing.assert_array_equal(knot_instants(result.crossing, table, t[0], t[-1]), ref)


def test_knot_limits_as_written_out_and_bit_identical_to_each_line_alone(run):
    result, effects, tables, responses = run
    alone = []
    vertices = 0
    for effect, table, resp in zip(effects, tables, responses):
        ref = _reference_limits(result, effect, table, resp.dynamic, resp.static)
        mine = with_knot_limits(result, effect, table, resp.dynamic, resp.static)
        assert ref[0].size > result.time.size
        # the samples' and limits' times and statics bit-identical; the (≤ 4) vertices' to round-off
        # (divided differences in the library, ``np.polyfit`` here)
        for got, want in ((mine[0], ref[0]), (mine[2], ref[2])):
            np.testing.assert_allclose(got, want, rtol=1e-14, atol=0.0)
            assert np.count_nonzero(got != want) <= 4
        vertices += ref[0].size - result.time.size - 2 * _reference_instants(result.crossing, table, result.time[0],
                                                                             result.time[-1]).size
        # the totals: the same formula written out one instant and point at a time (the points' shares
        # from the bridge's mode shapes, not the run's tables: ~1e-9 of a share), to round-off
        np.testing.assert_allclose(mine[1], ref[1], rtol=0.0, atol=1e-9 * np.abs(ref[1]).max())
        alone.append(mine)
    assert vertices >= 1  # an extreme between the samples on some line
    together = knot_limits(result, effects, tables, [r.dynamic for r in responses], [r.static for r in responses])
    assert len({tuple(knot_instants(result.crossing, tb, result.time[0], result.time[-1])) for tb in tables}) == 3
    for mine, ref in zip(together, alone):
        for a, b in zip(mine, ref):
            np.testing.assert_array_equal(a, b)


def test_merge_is_the_stable_argsort_order():
    """``_merged`` (insertion by ``searchsorted``) against the stable ``argsort`` of the concatenation,
    with times of u equal to times of t and u out of order (instants closer than 2δ)."""
    rng = np.random.default_rng(3)
    t = np.cumsum(rng.uniform(0.5, 1.5, 200))
    for ordered_u in (True, False):
        u = np.concatenate([t[[3, 3, 50, 199]], rng.uniform(t[0] - 1, t[-1] + 1, 30), [t[10] + 1e-9, t[10]]])
        if ordered_u:
            u.sort()
        a1, a2, b1, b2 = rng.normal(size=200), rng.normal(size=200), rng.normal(size=u.size), rng.normal(size=u.size)
        order = np.argsort(np.concatenate([t, u]), kind="stable")
        mine = _merged(t, u, a1, b1, a2, b2, ordered_u)
        for got, a, b in zip(mine, (t, a1, a2), (u, b1, b2)):
            np.testing.assert_array_equal(got, np.concatenate([a, b])[order])


def test_all_vehicles_motion_at_once_is_each_vehicles_own():
    """``Crossing.travel`` and ``Crossing.times_at`` against ``VehicleMotion.travel`` / ``times_at`` of
    each vehicle (the braking one past its stop: travel constant, times NaN), bit-identical."""
    crossing = Crossing(BRIDGE, vehicles=MOTIONS)
    t = np.linspace(-1.0, 20.0, 401)  # the braking one stops 11 s after its entry
    np.testing.assert_array_equal(crossing.travel(t), np.stack([m.travel(t) for m in MOTIONS], axis=1))
    s = np.linspace(-30.0, 200.0, 97)
    for i, m in enumerate(MOTIONS):
        np.testing.assert_array_equal(crossing.times_at(s, np.full(s.size, i)), m.times_at(s))
    both = crossing.times_at(np.stack([s, s]), np.array([[0], [1]]))  # vehicle broadcast against travel
    np.testing.assert_array_equal(both, np.stack([m.times_at(s) for m in MOTIONS]))
    assert np.isnan(both[1, -1]) and np.isfinite(both[0, -1])
