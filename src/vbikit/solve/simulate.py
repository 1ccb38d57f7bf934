"""Run crossings: set up the arrays, find the static start, call the compiled integrator.

``integrate`` runs several crossings that share everything but the road as *lanes* of
one kernel call (see ``vbikit.solve.kernels``); [`simulate`][vbikit.solve.simulate.simulate] is the one-lane case.
"""
from __future__ import annotations

import logging
import math
from dataclasses import replace
from typing import TYPE_CHECKING, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit.solve.budget import BudgetError, Limits
from vbikit.solve.compile_notice import announce_compile
from vbikit.solve.crossing import Crossing
from vbikit.solve.integrators import KernelCall, get_integrator
from vbikit.solve.plan import RunPlan, TimeGrid, plan_run
from vbikit.solve.result import CrossingResult, DeferredAccelerations, check_finite

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.system import KernelData

log = logging.getLogger(__name__)
#: memory [bytes] the stored histories of one ``simulate`` may take before they are thinned
HISTORY_BUDGET = 1 << 30
#: a run with steps whose contact forces did not converge (``unconverged_steps``) is run again at
#: half its step, at most this many times (an implicit integrator's contact iteration settles a
#: landing within a shorter step; what is still unconverged after that is counted and flagged)
UNCONVERGED_HALVINGS = 2


def simulate(crossing: Crossing, limits: Limits | None = None, output_every: int | None = None,
             history_budget: float = HISTORY_BUDGET, plan: RunPlan | None = None) -> CrossingResult:
    """Integrate the coupled equations (paper Eq. 9) over the whole crossing.

    Parameters
    ----------
    crossing : Crossing
        The crossing to integrate.
    limits : Limits, optional
        Memory and step budgets (default ``Limits``: 4 GiB, 5 × 10⁶ steps; raise them for bigger
        runs); the run's memory and steps are estimated first and refused (``BudgetError``)
        above them.
    output_every : int, optional
        Store every k-th step only (default 1, or the smallest k that keeps the histories within
        ``history_budget``, logged); the integration step is unchanged, ``result.dt`` is then the
        spacing of the stored samples and ``result.integration_dt`` the step.
    history_budget : float
        Memory [bytes] the stored histories may take when ``output_every`` is not given.
    plan : RunPlan, optional
        The crossing's [`RunPlan`][vbikit.solve.RunPlan] from [`plan_run`][vbikit.solve.plan_run]
        if it was planned already (its step, grid and kernel data are reused and ``limits`` is
        not consulted again).

    Returns
    -------
    CrossingResult
        The histories of the bridge modes, the vehicle DOFs and the wheel forces.

    A run with time steps whose contact forces did not converge (``unconverged_steps`` > 0: a light
    wheel landing on a stiff, heavily damped tire can leave one) is run again at half the step, up to
    ``UNCONVERGED_HALVINGS`` times within ``limits`` (logged, with the step used; ``result.crossing``
    then carries that step); the result is the last run's, its remaining count flagged as before.
    """
    result = _simulate_once(crossing, limits, output_every, history_budget, plan)
    for _ in range(UNCONVERGED_HALVINGS):
        if not result.unconverged_steps:
            break
        finer = _halved(result, limits, output_every, history_budget)
        if finer is None:  # refused by the budget
            break
        result = finer
    return result


def _halved(result: CrossingResult, limits: Limits | None, output_every: int | None,
            history_budget: float) -> CrossingResult | None:
    """``result``'s crossing run again at half its integration step (the histories thinned by twice
    ``output_every`` when that was given: the same stored samples), or None when the budget refuses it."""
    step = float(result.integration_dt or result.dt)
    finer = replace(result.crossing, dt=0.5 * step)
    try:
        plan = plan_run(finer, limits)
    except BudgetError as err:
        log.warning("%d time steps' contact forces did not converge at dt = %.4g s; the run at dt/2 is above the "
                    "budget (%s), so the result stands, flagged", result.unconverged_steps, step, err)
        return None
    again = _simulate_once(finer, limits, None if output_every is None else 2 * int(output_every), history_budget, plan)
    log.warning("%d time steps' contact forces did not converge at dt = %.4g s: run again at dt = %.4g s (%s)",
                result.unconverged_steps, step, 0.5 * step,
                f"{again.unconverged_steps} unconverged there" if again.unconverged_steps else "every step converged")
    return again


def _simulate_once(crossing: Crossing, limits: Limits | None, output_every: int | None, history_budget: float,
                   plan: RunPlan | None) -> CrossingResult:
    """``simulate`` at the crossing's own step (no rerun)."""
    if plan is None:
        plan = plan_run(crossing, limits)
    elif plan.crossing is not crossing:
        raise ValueError("simulate(crossing, plan=...): the plan was made for another crossing")
    grid, data = plan.grid, plan.kernel_data
    if output_every is None:
        output_every = history_stride(grid.n_steps, data, history_budget)
        if output_every > 1:
            log.warning("the histories of %d steps would take more than %.3g GB: every %d-th step is stored "
                        "(simulate(..., output_every=k) or history_budget= to choose)", grid.n_steps,
                        history_budget / 1e9, output_every)
    elif int(output_every) != output_every or output_every < 1:
        raise ValueError(f"output_every must be an integer >= 1, got {output_every!r}")
    return check_finite(integrate([crossing], data, grid, int(output_every))[0], fresh=True)


def history_stride(n_steps: int, data: "KernelData", budget: float = HISTORY_BUDGET) -> int:
    """The smallest k such that every k-th of ``n_steps`` + 1 states fits in ``budget`` [bytes]
    (ξ, ξ̇, ξ̈, q, q̇, q̈ and two per wheel, 8 bytes each)."""
    per_row = 8.0 * (3 * data.n_modes + 3 * data.n_dof + 2 * data.n_wheels)
    return max(1, math.ceil((n_steps + 1) * per_row / max(budget, per_row)))


#: lanes per RK4 kernel call: a batch runs in calls of up to MAX_LANES lanes, each padded to a
#: multiple of LANE_PAD (padding lanes repeat the last road and are dropped): the compiler's
#: vector loops over the lanes take 32 doubles at a time, so 32 lanes cost little more than
#: 20 (benchmarks/bench_studies.py).  One crossing is one lane (its own compiled variant).
MAX_LANES = 32
LANE_PAD = 8


def integrate(crossings: Sequence[Crossing], data: "KernelData", grid: TimeGrid, stride: int = 1) -> list[CrossingResult]:
    """Static start and time integration of ``crossings`` (they differ only in their roads; ``data``
    and ``grid`` are those of the first) with their integrator (its registered ``run``,
    ``vbikit.solve.integrators``), as lanes of kernel calls (``MAX_LANES``)."""
    from vbikit.solve.kernels import MANY_LANES, ONE_LANE, Motion

    first, n_real = crossings[0], len(crossings)
    if n_real > MAX_LANES:
        return [res for k in range(0, n_real, MAX_LANES)
                for res in integrate(crossings[k:k + MAX_LANES], data, grid, stride)]
    n_l = 1 if n_real == 1 else -(-n_real // LANE_PAD) * LANE_PAD
    crossings = list(crossings) + [crossings[-1]] * (n_l - n_real)
    dt, n_steps = grid.dt, grid.n_steps
    n_m, n_d, n_w, n_p = data.n_modes, data.n_dof, data.n_wheels, data.n_points
    mot = Motion(grid.travel, grid.speed)
    n_t = n_steps // stride + 1  # stored rows (every stride-th step)
    # row 0 zero (the static start goes in), the other rows filled by the kernel (``KernelCall.outputs``)
    xi, dxi, ddxi = (_histories(n_l, n_t, n_m) for _ in range(3))
    q, dq, ddq = (_histories(n_l, n_t, n_d) for _ in range(3))
    wheel_force = _histories(n_l, n_t, n_w)
    wheel_len = _histories(n_l, n_t, n_w)
    integrator = get_integrator(first.integrator)
    # the road rate the static start loads the dashpots with: the road ahead of each point only (the
    # kernels' first evaluation of a run reads it so too, ``integrators._span``)
    span = -integrator.road_rate_span(dt)
    if n_l == 1:  # one crossing: its static start depends on it alone, kept with it
        key = (id(data), mot.travel[0].tobytes(), mot.speed[0].tobytes(), span)  # the entry holds data: its id stays its own
        made: list = []

        def start() -> tuple:
            road, xi0, q0, reach = _start(crossings, data, mot, 1, span)
            made.append(road)  # a road profile's bundle is not kept (its size is the profile's)
            return data, road if first.road is None and first.road_right is None else None, xi0, q0, reach

        _, road, xi[0, 0], q[0, 0], reach = first.kept("start", key, start)
        if road is None:
            road = made[0] if made else _road(crossings, *reach)
    else:
        road, xi0, q0, _ = _start(crossings, data, mot, n_real, span)
        xi[:n_real, 0], q[:n_real, 0] = xi0, q0
        xi[n_real:, 0], q[n_real:, 0] = xi0[-1], q0[-1]  # padding: copies of the last real lane
    if first.run_in > 0 and n_d:  # the vehicles' state after their run-in on the road behind them (vbikit.solve.run_in)
        from vbikit.solve import kernels as compiled

        announce_compile([compiled.run_in_loads, compiled.linear_recursion])
        _run_in(crossings[:n_real], data, mot, dt, q, dq)
    log.info("%d crossing(s) as %d lanes: %d steps of %.3g s (%s), %d modes, %d vehicle DOFs, %d contact points",
             n_real, n_l, n_steps, dt, first.integrator, n_m, n_d, n_p)
    outputs = (xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len)
    if integrator.kernel is not None:
        announce_compile(integrator.kernel())
    call = KernelCall(first, dt, n_steps, mot, data, road, outputs, ONE_LANE if n_l == 1 else MANY_LANES, stride)
    integrator.run(call)
    deferred = "q_ddot" in call.deferred
    time, front, speed, travel = _rows(first, grid, stride)
    results = []
    for lane, c in enumerate(crossings[:n_real]):
        # one view of each history, shared by the result and its deferred q̈ (a pickle then holds each once)
        q_l, dq_l, f_l = q[lane], dq[lane], wheel_force[lane]
        ddq_l = DeferredAccelerations(data.vehicles, q_l, dq_l, f_l, ddq[lane]) if deferred else ddq[lane]
        results.append(CrossingResult(c, time, dt * stride, front, speed, xi[lane], dxi[lane], ddxi[lane], q_l, dq_l,
                                      ddq_l, f_l, wheel_len[lane], integration_dt=dt, kernel_data=data,
                                      unconverged_steps=call.unconverged.get(lane, 0)))
        results[-1].keep_travel(travel)
    return results


def _run_in(crossings: Sequence[Crossing], data: "KernelData", mot, dt: float, q: NDArray[np.float64],
            dq: NDArray[np.float64]) -> None:
    """Row 0 of every lane's q, q̇: the vehicles' state after ``crossing.run_in`` metres of road from rest
    where it begins (``run_in.settled_state``; its road read as the lane's kernels read it).  Refused when a
    contact point is on the deck at the start (the run-in drives the vehicles on the road alone).  The run-in
    steps ``dt``, the run's own step: 2 or 4 of them a step moved an HS20-44's IM by 7e-4 and 2.5e-3."""
    from vbikit.solve.modal_step import vehicle_step
    from vbikit.solve.run_in import check_off_deck, run_in_steps, settled_state
    from vbikit.solve.system import point_positions

    travel0, speed0 = np.asarray(mot.travel[0], float), np.asarray(mot.speed[0], float)
    x0, _ = point_positions(data, travel0, speed0)
    check_off_deck(data, x0, crossings[0].run_in)
    step = vehicle_step(data.vehicles, dt)
    n_d = data.vehicles.gravity.size
    n = run_in_steps(crossings[0], dt, speed0)
    x_back, _ = point_positions(data, travel0 - speed0 * (n + 1) * dt, speed0)
    lo, hi = float(min(x_back.min(), x0.min())), float(max(x_back.max(), x0.max()))
    for lane, crossing in enumerate(crossings):
        road = _road([crossing], lo, hi)
        z = settled_state(crossing, data, step, dt, travel0, speed0, road)
        q[lane, 0], dq[lane, 0] = z[:n_d], z[n_d:]
    q[len(crossings):, 0], dq[len(crossings):, 0] = q[len(crossings) - 1, 0], dq[len(crossings) - 1, 0]  # padding lanes


def _histories(n_l: int, n_t: int, n: int) -> NDArray[np.float64]:
    """A history (n_l, n_t, n) of every lane with row 0 zero and the other rows NaN until the kernel writes
    them: a row an integrator failed to write is then caught by ``check_finite`` instead of being read
    as numbers (uninitialised memory would be; this costs ≈ 0.04 ms a traffic event over ``np.empty``)."""
    out = np.full((n_l, n_t, n), np.nan)
    out[:, 0] = 0.0
    return out


def _rows(crossing: Crossing, grid: TimeGrid, stride: int) -> tuple:
    """Time [s], front-axle positions [m], speeds [m/s] and travel [m] at the stored rows (every
    ``stride``-th step) of ``grid``: its own travel and speed there (``Crossing.front_positions`` of the
    grid's travel; the travel is the grid's, shared)."""
    rows = slice(0, None, 2 * stride)
    travel = grid.travel[rows]
    sign = np.array([m.sign for m in crossing.vehicles])
    return (grid.t_half[rows].copy(), np.where(sign > 0, travel, crossing.bridge.span - travel), grid.speed[rows].copy(),
            travel)


def _road(crossings: Sequence[Crossing], x_min: float, x_max: float):
    """The road bundle of the lanes ``crossings`` over ``x_min`` … ``x_max`` [m] (``road_data``)."""
    from vbikit.solve.system import road_data

    return road_data([(c.road, c.road_right) for c in crossings], x_min, x_max)


def _start(crossings: Sequence[Crossing], data: "KernelData", mot, n_real: int, span: float) -> tuple:
    """The road bundle of the lanes ``crossings`` (the first ``n_real`` real, the rest padding) over
    the range of x the points cover, the static start (ξ, q) of every real lane, (n_real, ·) (one
    lane: (n_modes,), (n_dof,)), and that range (x_min, x_max) [m].  The tire dashpots' road rate at
    the start as the kernels read it (``span`` [s]: minus ``Integrator.road_rate_span``: the road
    ahead of each point only, ``kernels.road_point``).  A run-in's start (``_run_in_start``) is the
    bridge at rest and the vehicles' state left for the run-in to set."""
    from vbikit.solve import kernels
    from vbikit.solve.system import flat_road, point_positions, static_state

    n_p, n_l = data.n_points, len(crossings)
    x0, vx0 = point_positions(data, mot.travel[0], mot.speed[0])
    x_last, _ = point_positions(data, mot.travel[-1])  # travel is monotone: extremes at the ends
    reach = float(min(x0.min(), x_last.min())), float(max(x0.max(), x_last.max()))
    road = _road(crossings, *reach)
    run_in = bool(data.vehicles.gravity.size) and crossings[0].run_in > 0  # (the run-in sets the vehicles' start state)
    if run_in and _run_in_start(data, x0):
        xi0, q0 = np.zeros(data.n_modes), np.zeros(data.n_dof)
        return (road, xi0, q0, reach) if n_l == 1 else (road, np.zeros((n_real, xi0.size)),
                                                        np.zeros((n_real, q0.size)), reach)
    road0, rate0 = np.zeros((n_p, n_l)), np.zeros((n_p, n_l))
    if n_l == 1 and not np.any(data.vehicles.wheel_envelope):  # the lean kernel's flat law reads the road
        road0[:, 0], rate0[:, 0] = flat_road(data, road, x0, vx0, span)
    else:
        kernels.road_at(x0, vx0, data.points, road, np.full(n_p, -1, np.int64), road0, rate0, kernels.MANY_LANES,
                        span)
    states = [static_state(crossing, data, road0[:, lane], mot.travel[0], road_rate=rate0[:, lane], speed=mot.speed[0],
                           replaced=run_in) for lane, crossing in enumerate(crossings[:n_real])]
    if n_l == 1:
        return road, states[0][0], states[0][1], reach
    return road, np.array([s[0] for s in states]), np.array([s[1] for s in states]), reach


def _run_in_start(data: "KernelData", x0: NDArray[np.float64]) -> bool:
    """Whether a run that begins with a run-in (``_run_in``, the vehicles' state its own) with the contact points at
    ``x0`` [m] starts with the bridge at rest: no point on the deck (a run-in refuses any other), so the static
    start's equilibrium (``system.static_state``) has no load on the bridge: ξ = 0, which it need not solve for
    (its vehicles' q, the rest of its solution, the run-in replaces)."""
    modes, track = data.modes, data.points.track
    return not np.any((x0 >= modes.start[track]) & (x0 <= modes.end[track]))
