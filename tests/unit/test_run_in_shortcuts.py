"""The run-in's and the static start's shortcuts (``vbikit.solve.run_in``, ``vbikit.solve.simulate._start``) and the
vehicles' step-map terms shared by both holds (``vbikit.solve.modal_step._vehicle_terms``): each gives the numbers
of the longer path it skips, bit for bit."""
from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def _event(trucks: int):
    """A ``trucks``-truck traffic event on Bridge 2 (point tires, class B, 10 m approach, 60 m run-in): its crossing
    and run plan."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_traffic import _stream

    from vbikit.scenario.build import with_scenario_road
    from vbikit.solve.plan import plan_run
    from vbikit.traffic.study import traffic_study

    base = {"bridge": {"model": "paper-bridge-2", "n_modes": 10}, "tire": {"model": "point"},
            "road": {"class": "B", "spacing": 0.01}, "crossing": {"approach": 10.0}}
    job = traffic_study(_stream(400, 600.0), base, batch_size=16)
    ctx = job.context()
    e = next(e for e in range(job.size) if len(job.events[e]) == trucks)
    crossing = dataclasses.replace(job.crossing(e), run_in=60.0, road=None, road_right=None)
    crossing = with_scenario_road(crossing, ctx.scenario.road, ctx.scenario, job.road_seed(e))
    return crossing, plan_run(crossing)


def _reference_recursion(data, step):
    """(A, M0, M1, c) by the inverse S = (I − L1 D)⁻¹ whatever D (the general path)."""
    pts, veh = data.points, data.vehicles
    n_d, n_w = veh.gravity.size, veh.wheel_rows.shape[0]
    k_sum = np.bincount(pts.wheel, weights=pts.stiffness, minlength=n_w)
    c_sum = np.bincount(pts.wheel, weights=pts.damping, minlength=n_w)
    d = np.zeros((n_w, 2 * n_d))
    d[:, :n_d] = (veh.wheel_stiffness - k_sum)[:, None] * veh.wheel_rows
    d[:, n_d:] = (veh.wheel_damping - c_sum)[:, None] * veh.wheel_rows
    settle = np.linalg.inv(np.eye(2 * n_d) - step.load1 @ d)
    return settle @ (step.transition + step.load0 @ d), settle @ step.load0, settle @ step.load1, settle @ step.constant


def _reference_blocks(a_mat, m0, m1):
    """``independent_blocks`` as first written (the sums of magnitudes of A's four blocks)."""
    n_d = a_mat.shape[0] // 2
    mag = np.abs(a_mat)
    reach = (np.abs(m0) + np.abs(m1)) != 0.0
    reach = (reach[:n_d] | reach[n_d:]).astype(float)
    dofs = (mag[:n_d, :n_d] + mag[:n_d, n_d:] + mag[n_d:, :n_d] + mag[n_d:, n_d:] + reach @ reach.T) != 0.0
    dofs |= dofs.T
    last = n_d - 1 - np.argmax(dofs[:, ::-1], axis=1)
    ends = np.flatnonzero(np.maximum.accumulate(np.maximum(last, np.arange(n_d))) == np.arange(n_d)) + 1
    reach = reach != 0.0
    wheel_dof = np.where(reach.any(axis=0), np.argmax(reach, axis=0), -1)
    return [(np.r_[lo:hi, n_d + lo:n_d + hi], np.flatnonzero((wheel_dof >= lo) & (wheel_dof < hi)))
            for lo, hi in zip([0, *ends[:-1].tolist()], ends.tolist())]


def _same_groups(got, want) -> bool:
    return len(got) == len(want) and all(np.array_equal(a, c) and np.array_equal(b, d) and a.dtype == c.dtype
                                         for (a, b), (c, d) in zip(got, want))


@pytest.mark.parametrize("trucks", [1, 3])
def test_the_recursion_without_feedback_is_the_step_maps_own(trucks):
    """Point tires (each wheel's nominal tire its point's: D = 0): the recursion's matrices are the step map's own T,
    L0, L1, b, the numbers the inverse S = (I − 0)⁻¹ and its products give, bit for bit; with points whose tires are
    not the nominal one (D ≠ 0) the inverse path, as before."""
    from vbikit.solve.modal_step import vehicle_step
    from vbikit.solve.run_in import load_feedback, recursion

    _, plan = _event(trucks)
    data = plan.kernel_data
    step = vehicle_step(data.vehicles, plan.dt)
    assert load_feedback(data) is None
    for got, want in zip(recursion(data, step), _reference_recursion(data, step)):
        assert np.array_equal(got, want)
    softer = dataclasses.replace(data, points=data.points._replace(stiffness=0.5 * data.points.stiffness))
    assert load_feedback(softer) is not None
    for got, want in zip(recursion(softer, step), _reference_recursion(softer, step)):
        assert np.array_equal(got, want)
    assert not np.array_equal(recursion(softer, step)[0], step.transition)


def test_independent_blocks_are_the_first_writings():
    """``independent_blocks`` gives the groups of its first writing on a three-truck event's recursion and on random
    patterns: vehicles of random sizes, couplings within and (sometimes) across them through A, M0 or M1 at random,
    wheels without DOFs, DOFs without any entry."""
    from vbikit.solve.modal_step import vehicle_step
    from vbikit.solve.run_in import independent_blocks, recursion

    _, plan = _event(3)
    a_mat, m0, m1, _ = recursion(plan.kernel_data, vehicle_step(plan.kernel_data.vehicles, plan.dt))
    assert len(independent_blocks(a_mat, m0, m1)) == 3
    assert _same_groups(independent_blocks(a_mat, m0, m1), _reference_blocks(a_mat, m0, m1))
    rng = np.random.default_rng(7)
    for _ in range(300):
        sizes = rng.integers(1, 5, rng.integers(1, 5))
        n_d, n_w = int(sizes.sum()), int(rng.integers(1, 8))
        a_mat, m0, m1 = np.zeros((2 * n_d, 2 * n_d)), np.zeros((2 * n_d, n_w)), np.zeros((2 * n_d, n_w))
        lo = 0
        for size in sizes:  # each vehicle's states coupled among themselves (some entries left out)
            idx = np.r_[lo:lo + size, n_d + lo:n_d + lo + size]
            a_mat[np.ix_(idx, idx)] = rng.normal(size=(idx.size, idx.size)) * (rng.random((idx.size, idx.size)) < 0.7)
            lo += size
        for w in range(n_w):  # a wheel on one DOF's q̇ (or none), sometimes on another's too
            if rng.random() < 0.85:
                (m0 if rng.random() < 0.5 else m1)[n_d + int(rng.integers(n_d)), w] = rng.normal()
            if rng.random() < 0.1:
                m1[int(rng.integers(2 * n_d)), w] = rng.normal()
        if rng.random() < 0.2:
            a_mat[rng.integers(2 * n_d), rng.integers(2 * n_d)] = rng.normal()
        assert _same_groups(independent_blocks(a_mat, m0, m1), _reference_blocks(a_mat, m0, m1))


def test_a_group_of_the_whole_recursion_is_its_arrays_by_columns():
    """``_by_columns`` of a group that is the whole recursion: the gathered arrays' numbers, in fresh arrays (the
    compiled recursion writes its state; the recursion's matrices may be a step map's own)."""
    from vbikit.solve.run_in import _by_columns

    rng = np.random.default_rng(3)
    n, m = 8, 3
    a_mat, m0, m1 = rng.normal(size=(n, n)), rng.normal(size=(n, m)), rng.normal(size=(n, m))
    c, z = rng.normal(size=n), rng.normal(size=n)
    states, wheels = np.arange(n), np.arange(m)
    got = _by_columns(a_mat, m0, m1, c, z, states, wheels)
    want = (a_mat[np.ix_(states, states)].T, m0[np.ix_(states, wheels)].T, m1[np.ix_(states, wheels)].T, c[states],
            z[states])
    for g, w, source in zip(got, want, (a_mat, m0, m1, c, z)):
        assert np.array_equal(g, w) and g.flags.c_contiguous and not np.shares_memory(g, source)
    part = _by_columns(a_mat, m0, m1, c, z, np.array([1, 2, 5, 6]), np.array([0, 2]))
    assert np.array_equal(part[0], a_mat[np.ix_([1, 2, 5, 6], [1, 2, 5, 6])].T)


@pytest.mark.parametrize("trucks", [1, 3])
def test_a_run_ins_start_is_the_static_start_on_the_bridge(trucks):
    """A run that begins with a run-in, every contact point off the deck: its start (``_start``) is the bridge at rest
    — the static equilibrium's ξ, which is exactly zero there — and zero vehicle states, which the run-in then
    replaces with its own (the run's first row is the run-in's state); the road bundle and reach are those of the
    full path."""
    from vbikit.solve import simulate
    from vbikit.solve.integrator_registry import get_integrator
    from vbikit.solve.kernels import Motion
    from vbikit.solve.simulate import _run_in_start, _start
    from vbikit.solve.system import flat_road, point_positions, static_state

    crossing, plan = _event(trucks)
    data, grid = plan.kernel_data, plan.grid
    mot = Motion(grid.travel, grid.speed)
    span = -get_integrator(crossing.integrator).road_rate_span(plan.dt)
    x0, vx0 = point_positions(data, mot.travel[0], mot.speed[0])
    assert _run_in_start(data, x0)
    road, xi0, q0, reach = _start([crossing], data, mot, 1, span)
    road0, rate0 = flat_road(data, road, x0, vx0, span)
    xi_static, _, _ = static_state(crossing, data, road0, mot.travel[0], road_rate=rate0, speed=mot.speed[0],
                                   replaced=True)
    assert np.array_equal(xi0, xi_static) and not np.any(xi0) and not np.any(q0)
    full = _start([dataclasses.replace(crossing, run_in=0.0)], data, mot, 1, span)
    assert full[3] == reach and np.array_equal(full[0].elevations, road.elevations)
    result = simulate(crossing, plan=plan)
    assert np.any(result.q[0]) and not np.any(result.xi[0])


def _combined(pair: bool):
    from vbikit.contact.points import contact_points, stack_contact_points
    from vbikit.contact.tires import PointTire
    from vbikit.solve.system import vehicles_data
    from vbikit.vehicle.axles import axle_truck
    from vbikit.vehicle.model import combine_vehicles

    trucks = [axle_truck([55e3, 95e3, 95e3, 80e3, 80e3], [3.6, 1.3, 6.0, 1.3])] + ([axle_truck([60e3, 110e3], [4.2])] if pair else [])
    combined = combine_vehicles(trucks)
    contact = stack_contact_points([contact_points(t, PointTire()) for t in trucks], combined.dof_offsets)
    return vehicles_data(combined, contact)


@pytest.mark.parametrize("pair", [False, True])
def test_the_holds_share_the_vehicles_terms(pair):
    """The step maps of both holds made with the vehicles' terms kept from the other (``_vehicle_terms``,
    ``vehicle_step``'s store) are those made afresh, every array bit for bit; the augmented matrix from the
    terms is the one written out (h I, the chain's I); two vehicles asked for in turn each get their own."""
    from vbikit.solve import modal_step

    veh, h = _combined(pair), 0.0013
    terms = modal_step._vehicle_terms(veh)
    assert len(terms.blocks) == (2 if pair else 1)
    for hold in (modal_step.QUADRATIC, modal_step.LINEAR):
        shared, fresh = modal_step._vehicle_step(veh, h, hold, terms), modal_step._vehicle_step(veh, h, hold)
        for name, a, b in zip(shared._fields, shared, fresh):
            assert np.array_equal(a, b), name
        c_hat, k_hat = modal_step._nominal(veh)
        m_inv, rows, gravity = veh.mass_inv, veh.wheel_rows, veh.gravity
        n_d, n_w = gravity.size, rows.shape[0]
        n = 2 * n_d + (hold + 1) * n_w + 1
        a = np.zeros((n, n))
        a[:n_d, n_d:2 * n_d] = h * np.eye(n_d)
        a[n_d:2 * n_d, :n_d] = -h * (m_inv @ k_hat)
        a[n_d:2 * n_d, n_d:2 * n_d] = -h * (m_inv @ c_hat)
        a[n_d:2 * n_d, 2 * n_d:2 * n_d + n_w] = h * (m_inv @ rows.T)
        a[n_d:2 * n_d, -1] = h * (m_inv @ gravity)
        for k in range(hold):
            lo = 2 * n_d + k * n_w
            a[lo:lo + n_w, lo + n_w:lo + 2 * n_w] = np.eye(n_w)
        assert np.array_equal(modal_step._augmented(m_inv, c_hat, k_hat, rows, gravity, h, hold), a)
    other = _combined(not pair)
    for veh_i in (veh, other, veh):
        kept = modal_step.vehicle_step(veh_i, h, modal_step.QUADRATIC)
        for name, a, b in zip(kept._fields, kept, modal_step._vehicle_step(veh_i, h, modal_step.QUADRATIC)):
            assert np.array_equal(a, b), name
