"""Time integrators as registered objects: one [`Integrator`][vbikit.solve.Integrator] per name.

Everything that depends on the integrator — the scenario schema's allowed names, the automatic
time step and the stability check, the kernel a batch of lanes runs with, the preflight's
explicit/implicit distinction and the references a report cites — reads [`INTEGRATORS`][vbikit.solve.integrators.INTEGRATORS]
(through [`get_integrator`][vbikit.solve.get_integrator]), never a chain of name comparisons.

Built in (registered by ``vbikit.solve.builtin_integrators``):

* ``"exact"`` — every bridge mode by its exact transition with the modal load quadratic over the
  step through the loads at its ends and the end of the step before (Nigam & Jennings 1969 with a
  three-point hold, ``vbikit.solve.modal_step.quadratic_hold``), the vehicles by the exponential of
  their augmented system with their wheel loads linear over the step;
* ``"rk4"`` — the paper's classical Runge–Kutta (explicit: its step is capped by the stability
  limit of the coupled system);
* ``"newmark"`` — Newmark average acceleration for bridge and vehicles alike.

A new integrator is one module that builds an [`Integrator`][vbikit.solve.Integrator] and calls
[`register_integrator`][vbikit.solve.register_integrator], plus one import of that module (docs/extending.md).  An implicit
variant only supplies its step maps to ``run_implicit``.

Nothing here imports the compiled kernels until an integrator runs.
"""
from __future__ import annotations

import logging
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Iterator

import numpy as np

from vbikit.solve.integrator_registry import (  # noqa: F401  (the registry's names, importable from here as before)
    DEFAULT_INTEGRATOR,
    INTEGRATORS,
    Integrator,
    get_integrator,
    implicit_names,
    integrator_names,
    register_integrator,
)

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.crossing import Crossing
    from vbikit.solve.kernels import ModalStep, Motion, Road, VehicleStep
    from vbikit.solve.system import KernelData

log = logging.getLogger(__name__)


#: the implicit integrators' end-of-step contact forces hold the contact law to this fraction of the
#: largest static wheel load on every point: the step stops iterating once |law(F) − F| is below it
#: (tol = IMPLICIT_TOLERANCE × max static wheel load, ``run_implicit``).  The common step reaches it
#: with one contact-law evaluation and exact quasi-Newton increments (``vbikit.solve.kernels.lean``,
#: ``vbikit.solve.kernels.implicit``).  1e-10 lets each point force be off its law by 6.8e-6 N on
#: the ``vbikit demo`` crossing (largest wheel load 68 kN), against the 1e-12 used before it:
#: the histories differ from those at 1e-12 by 3e-11 of the peak in the modal displacements, 5e-11
#: in the vehicle's, 3e-10 in the wheel forces and 2e-9 in the accelerations — far below the
#: step's own error (≈ 5e-6 of the peak, benchmarks/README.md) — while the updates fall from 2.24
#: to 1.66 a step and the lean kernel from 7.3 to 6.5 ms (benchmarks/bench_floor.py).  Looser buys
#: little (1e-9: 1.65 updates a step, the same time; 1e-8: 1.57).  At 1e-10 lanes still equal single
#: crossings (1.4e-13 of the peak) and the lean kernel the full one (3e-14); a crossing the full
#: kernel takes over from the lean one differs from a full run by 1.3e-10 (tests/unit/test_lean_kernel.py).
IMPLICIT_TOLERANCE = 1e-10
IMPLICIT_MAX_ITERATIONS = 50


@dataclass(frozen=True)
class KernelCall:
    """One kernel call: lanes of crossings that share everything but the road.

    Attributes
    ----------
    crossing : Crossing
        The first lane's crossing (integrator, vehicles, static wheel loads).
    dt : float
        Integration step [s].
    n_steps : int
        Steps of the run.
    motion : vbikit.solve.kernels.Motion
        The vehicles' travel [m] and speed [m/s] on the half-step grid.
    data : vbikit.solve.system.KernelData
        Modes, vehicles and contact points of the system.
    road : vbikit.solve.kernels.Road
        Road lines of every lane.
    outputs : tuple of ndarray
        ``(xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len)``, each (n_lanes, n_stored, ·),
        row 0 holding the static start (zero but ξ and q); the kernel fills the other rows, which
        come as NaN (a row left unwritten fails ``check_finite``; q̈ may be left to the results,
        ``deferred``).
    lanes : tuple
        ``kernels.ONE_LANE`` for one lane (its own compiled variant of the lean and RK4 kernels),
        ``kernels.MANY_LANES`` for several (``implicit`` always runs its many-lane variant).
    stride : int
        Every ``stride``-th step is stored.
    deferred : set of str
        Filled by the run: ``"q_ddot"`` when it left the vehicles' accelerations (``outputs[5]``)
        unfilled; the results then compute them when read (``vbikit.solve.result.DeferredAccelerations``).
    unconverged : dict of int to int
        Filled by the run: per lane, the steps whose contact forces did not settle within
        ``IMPLICIT_MAX_ITERATIONS`` (lanes without any are left out; a call of the full kernel over
        several lanes counts a step for every lane when any of them did not settle).
    """

    crossing: "Crossing"
    dt: float
    n_steps: int
    motion: "Motion"
    data: "KernelData"
    road: "Road"
    outputs: tuple
    lanes: tuple
    stride: int
    deferred: set = field(default_factory=set, compare=False, repr=False)
    unconverged: dict = field(default_factory=dict, compare=False, repr=False)


#: run implicit calls through the lean kernels first (``vbikit.solve.kernels.lean`` for one lane,
#: ``vbikit.solve.kernels.lean_lanes`` for many), the full ``implicit`` kernel only for what they do
#: not take; False: always ``implicit`` (tests compare the two)
USE_LEAN = True

#: implicit runs so far.  One lane: ``"lean"`` completed by the lean kernel, ``"fallback"`` finished
#: with ``implicit`` after the lean kernel stopped at a step it does not take (a contact opening or
#: closing, corrections not settling).  Many lanes, counted per lane: ``"lanes"`` completed by
#: ``lean_lanes``, ``"lanes_fallback"`` frozen by it at such a step and finished with ``implicit``.
#: ``"implicit"``: calls sent to ``implicit`` directly (rigid disks, ``USE_LEAN`` off)
LEAN_COUNTS: dict[str, int] = {"lean": 0, "fallback": 0, "implicit": 0, "lanes": 0, "lanes_fallback": 0}


@contextmanager
def without_lean() -> Iterator[None]:
    """Run every implicit crossing with the full ``implicit`` kernel inside the block (``USE_LEAN``
    off): to compile its variants in advance, or to compare the kernels."""
    global USE_LEAN
    before, USE_LEAN = USE_LEAN, False
    try:
        yield
    finally:
        USE_LEAN = before


def run_implicit(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep",
                 event_step: "VehicleStep | None" = None) -> None:
    """Run ``call`` through the partitioned implicit kernel (``vbikit.solve.kernels.implicit``)
    with the step maps ``modal_step`` (every bridge mode over ``call.dt``) and ``vehicle_step``
    (the vehicles over ``call.dt``), iterating the end-of-step contact forces to
    ``IMPLICIT_TOLERANCE`` of the largest static wheel load.

    Without rigid disks the lean kernels run first, with the same arithmetic on the steps that take
    one contact-law evaluation: ``vbikit.solve.kernels.lean`` for one lane, ``lean_lanes`` for
    many.  Should one lane need more at a step (a contact opening or closing within the step's
    updates), ``implicit`` goes on with that lane alone from the last state stored (``LEAN_COUNTS``).
    Its start there evaluates the law at that state and extrapolates from it alone, so the rest of
    the run differs from an ``implicit`` run from t = 0 by the order of the tolerance
    (``IMPLICIT_TOLERANCE`` of the largest wheel load).  ``event_step`` (None: ``vehicle_step``) is the
    vehicles' map of the full kernel's steps, those handed over and rigid-disk runs (the exact integrator's
    linear hold where its lean kernels hold the loads quadratic, ``builtin_integrators.QUADRATIC_WHEEL_LOADS``);
    the lean kernels take the variant for ``vehicle_step`` (``_lean``).

    The lean kernels leave the vehicles' accelerations q̈ out of the step loop: when they ran,
    ``"q_ddot"`` is added to ``call.deferred`` (the results compute q̈ when read,
    ``vbikit.solve.result.DeferredAccelerations``); ``implicit`` alone fills every output."""
    data, name = call.data, call.crossing.integrator
    event_step = vehicle_step if event_step is None else event_step
    loads = np.abs(call.crossing.vehicle.static_wheel_loads())
    tol = IMPLICIT_TOLERANCE * max(float(loads.max(initial=0.0)), 1.0)
    envelopes = bool(np.any(data.vehicles.wheel_envelope))  # (rigid disks: the full kernel, linear hold)
    if not USE_LEAN or envelopes:
        LEAN_COUNTS["implicit"] += 1
        _full(call, modal_step, event_step if envelopes else vehicle_step, tol, call.motion, call.road, call.outputs, 0,
              _no_past(call, call.outputs[0].shape[0]))
        return
    if len(call.lanes) == 1:
        past_p, past_g, _ = _no_past(call)
        stop, evaluations, landings = _lean(vehicle_step, event_step)(*_lean_arguments(call, modal_step, vehicle_step, start=True), past_p[:, 0],
                                         past_g[:, 0], False, _positions_before(call, 0), tol, call.stride,
                                         *_lean_work(call))
        if stop < 0:
            LEAN_COUNTS["lean"] += 1
            log.debug("%s (lean kernel): %.2f contact-law evaluations per step; %d step(s) in which a wheel landed or "
                      "lifted off solved a second time", name, evaluations / max(call.n_steps, 1), landings)
        else:
            LEAN_COUNTS["fallback"] += 1
            _finish_lane(call, modal_step, vehicle_step, event_step, tol, 0, int(stop),
                         (past_p, past_g, int(stop) >= call.stride))
    else:
        _run_lanes(call, modal_step, vehicle_step, event_step, tol)
    call.deferred.add("q_ddot")


def _run_lanes(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep", event_step: "VehicleStep",
               tol: float) -> None:
    """Many lanes through ``kernels.lean_lanes``, ``LANES_CHUNK`` steps a call: a lane it stops at a
    step goes on alone (its road) from its last stored row (``_finish_lane``: ``implicit`` for the contact
    event's ``LEAN_WINDOW`` steps, the one-lane lean kernel after it) to the end of the chunk, or of the
    first chunk after the event's window where that window crosses the chunk's end (the lane sits out
    the calls in between: ``SKIP_LANE``), so that its windows are those of the lane run alone.  It
    rejoins the lanes where the one-lane lean kernel left it (its forces at the last two steps, modal and
    wheel loads: exactly as a lane that did not stop), or afresh when a window ended there (the law at
    that state, the forces extrapolated from it alone: as the lane alone restarts after a window); the
    other lanes go on exactly (``lean_lanes``' carried state)."""

    lean_lanes = _lean(vehicle_step, event_step, lanes=True)  # (announces its first compilation: a batch's first run may compile it)
    args = _lean_arguments(call, modal_step, vehicle_step, lanes=True, start=True)
    n_l, n_cp = call.outputs[0].shape[0], call.data.n_points
    stride, n_steps = call.stride, call.n_steps
    chunk = max(LANES_CHUNK // stride, 1) * stride
    stops = np.full(n_l, -1, np.int64)
    fresh = np.ones(n_l, np.bool_)
    carry_f = np.zeros((2, n_cp, n_l))
    carry_p = np.zeros((call.data.n_modes, n_l))
    carry_g = np.zeros((call.data.n_wheels, n_l))
    carry_pm, carry_gm = np.zeros_like(carry_p), np.zeros_like(carry_g)
    evaluations = handed = 0
    ever = np.zeros(n_l, np.bool_)
    away: dict[int, tuple] = {}  # lanes run alone: (the step they rejoin at, their end state or None, hold loads)
    resumes = np.full(n_l, LEAN_RESUMES, np.int64)  # each lane's windows left before ``implicit`` takes the rest
    for first in range(0, n_steps, chunk):
        last = min(n_steps, first + chunk)
        for lane, (rejoin, end_state, pm, gm) in list(away.items()):
            if rejoin > first:
                stops[lane] = SKIP_LANE
                continue
            del away[lane]  # (the calls it sat out wrote their carried state over its own: put back here)
            stops[lane] = -1
            carry_pm[:, lane], carry_gm[:, lane] = pm, gm
            fresh[lane] = end_state is None
            if end_state is not None:
                carry_f[0, :, lane], carry_f[1, :, lane], carry_p[:, lane], carry_g[:, lane] = end_state
        if np.all(stops == SKIP_LANE):
            continue
        evaluations += lean_lanes(*args, tol, stride, stops, first, last, fresh, carry_f, carry_p, carry_g,
                                          carry_pm, carry_gm, _positions_before(call, first))
        frozen = np.flatnonzero(stops >= 0)
        fresh[:] = False
        for lane in frozen:  # (the hold's loads before its last stored row in, those before its rejoin out)
            past = (carry_pm[:, lane:lane + 1].copy(), carry_gm[:, lane:lane + 1].copy(), int(stops[lane]) >= stride)
            end_state, reached, resumes[lane] = _finish_lane(call, modal_step, vehicle_step, event_step, tol, int(lane),
                                                             int(stops[lane]), past, last, chunk, int(resumes[lane]))
            away[int(lane)] = (reached, end_state, past[0][:, 0].copy(), past[1][:, 0].copy())
        ever[frozen] = True
        handed += frozen.size
    LEAN_COUNTS["lanes"] += int(n_l - ever.sum())
    LEAN_COUNTS["lanes_fallback"] += int(ever.sum())
    log.debug("%s (lean kernel, %d lanes): %.2f contact-law evaluations per step; %d lane(s) handed to the full kernel "
              "%d time(s)", call.crossing.integrator, n_l, evaluations / max(n_steps, 1), int(ever.sum()), handed)


def _lean(vehicle_step: "VehicleStep", event_step: "VehicleStep", lanes: bool = False) -> Any:
    """The lean kernel for the vehicles' map ``vehicle_step``: its variant with the wheel loads held
    quadratic when the map has the past loads' term (Lp ≠ 0: the default, "exact"), else the linear one.
    Vehicles without wheels (moving forces, trains of axle loads) have no such term: they take the variant
    of the integrator's maps, the quadratic one when its contact events' map ``event_step`` is another
    (as "exact"'s, whose compile notice names it, ``Integrator.kernel``; both variants compute the same)."""
    from vbikit.solve.compile_notice import announce_compile

    past = vehicle_step.load_past
    quadratic = bool(np.any(past)) or (past.size == 0 and event_step is not vehicle_step)
    kernel = implicit_lanes_kernel(quadratic) if lanes else implicit_kernel(quadratic)
    announce_compile(kernel)  # (announced by the integrator's ``kernel`` already, unless a user's map chose the other)
    return kernel


def _lean_work(call: KernelCall) -> tuple:
    """Zeroed work spaces of the one-lane lean kernel for ``call`` (``kernels.lean_work``)."""
    from vbikit.solve import kernels

    data = call.data
    return kernels.lean_work(data.n_modes, data.n_dof, data.n_points, data.n_wheels)


def _lane_road(road: "Road", lane: int) -> "Road":
    """The road of lane ``lane`` alone (its own r_max, as ``road_data`` gives one lane)."""
    from vbikit.solve.kernels import Road

    if road.elevations.shape[2] == 1:
        return road
    elevations = np.ascontiguousarray(road.elevations[:, :, lane:lane + 1])
    return Road(road.stations, elevations, float(elevations.max()))


#: a crossing the one-lane lean kernel stops at a step goes on with ``implicit`` for this many steps
#: (the contact event), then with the lean kernel again from the last row stored, at most
#: ``LEAN_RESUMES`` times in a run (a batch lane's counted over the run too); after that ``implicit`` takes
#: the rest of the run
LEAN_WINDOW = 16
LEAN_RESUMES = 40

#: steps per ``kernels.lean_lanes`` call: a lane it stops at a step runs alone to the end of the chunk, or
#: of the chunk after its window (``_finish_lane``), and rejoins the lanes at the next call (``_run_lanes``)
LANES_CHUNK = 128
#: ``lean_lanes``' ``stop`` entry of a lane that sits a call out (run alone past the call's first step)
SKIP_LANE = -2


def _finish_lane(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep", event_step: "VehicleStep",
                 tol: float, lane: int, stop: int, past: tuple, last: int | None = None,
                 chunk: int | None = None, resumes: int = LEAN_RESUMES) -> tuple[tuple | None, int, int]:
    """Lane ``lane`` of ``call`` from the last row a lean kernel stored before step ``stop`` to step
    ``last`` (None: the run's end): on that lane's road, ``implicit`` (that lane alone, with the map
    ``event_step``) for ``LEAN_WINDOW`` steps, then the one-lane lean kernel, alternating while the lean
    kernel stops, at most ``resumes`` more times (after that ``implicit`` to the run's end); ``past`` (modal (n_m, 1), wheel
    (n_w, 1), resume) the hold's loads before the row it starts from, which each kernel call reads and
    leaves at those before its last stored row for the next.  Each hand-over restarts from a stored state
    (the law there, the forces extrapolated from it alone): the histories differ from an uninterrupted run
    by the order of the tolerance.  A lane of ``lean_lanes`` stopped within a chunk goes on so to the
    chunk's end ``last`` (``_run_lanes``), or with ``chunk`` given, where a window crosses ``last``, to
    the end of the first chunk after the window (the windows then fall where the lane alone has them):
    the full kernel only for the contact event's windows.

    Returns (the state the one-lane lean kernel ended with when it ran to the end, else None; the step
    reached; the resumes left): the state is its point forces at the last two steps, modal load and
    wheel loads (``lean_lanes``' carried state)."""
    from vbikit.solve import kernels

    road = _lane_road(call.road, lane)
    one = replace(call, road=road, outputs=tuple(a[lane:lane + 1] for a in call.outputs), lanes=kernels.ONE_LANE)
    stride = call.stride
    n_steps = call.n_steps if last is None else last
    row = stop // stride
    for resume in range(resumes + 1):
        first = row * stride
        window = max(LEAN_WINDOW // stride, 1) * stride
        if resume == resumes:  # (no resume left: ``implicit`` to the run's end)
            n_steps = call.n_steps
        elif chunk is not None and first + window > n_steps:  # (the chunk boundary after the window)
            n_steps = min(call.n_steps, -(-(first + window) // chunk) * chunk)
        end = n_steps if resume == resumes else min(n_steps, first + window)
        log.debug("%s: the lean kernel stops lane %d at step %d of %d (a contact opens or closes within the step); "
                  "the full implicit kernel goes on from step %d", call.crossing.integrator, lane, stop + 1, n_steps,
                  first)
        _full(call, modal_step, event_step, tol, _steps(call.motion, first, end), road,
              tuple(a[:, row:end // stride + 1] for a in one.outputs), first, past, lane)
        past = (past[0], past[1], True)
        if end >= n_steps or end % stride:
            return None, end, max(resumes - resume - 1, 0)  # (this window used one)
        row = end // stride
        part = replace(one, motion=_steps(call.motion, end, n_steps), n_steps=n_steps - end,
                       outputs=tuple(a[:, row:n_steps // stride + 1] for a in one.outputs))
        work = _lean_work(part)
        stop, _, _ = _lean(vehicle_step, event_step)(*_lean_arguments(part, modal_step, vehicle_step, start=False), past[0][:, 0],
                               past[1][:, 0], True, _positions_before(call, end), tol, stride, *work)
        if stop < 0:  # (``lean_work``'s rows: the forces F_{n+1}, F_n; the modal load; the wheel loads)
            modal, wheels, points = work[0], work[2], work[6]
            end_state = points[0].copy(), points[1].copy(), modal[4].copy(), wheels[0].copy()
            return end_state, n_steps, resumes - resume - 1
        stop += end
        row = stop // stride
    return None, n_steps, 0  # (not reached: the last pass runs to the end)


def _steps(motion: "Motion", first: int, end: int) -> "Motion":
    """The motion of steps ``first`` … ``end`` (half-step rows 2·first … 2·end)."""
    return motion._replace(travel=motion.travel[2 * first:2 * end + 1], speed=motion.speed[2 * first:2 * end + 1])


#: when the full kernel runs (``_full``): what its compile notice says
FULL_KERNEL_USE = "this process (the full contact kernel: a wheel leaves or lands on the road within a step, or rigid-disk tires)"


def _full(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep", tol: float, motion: "Motion",
          road: "Road", outputs: tuple, first: int, past: tuple, lane: int | None = None) -> None:
    """``kernels.implicit`` on ``outputs`` (row 0 the start state) from step ``first`` of ``call``, in its
    many-lane variant whatever the lane count (``kernels.MANY_LANES``: one compiled variant of the full
    kernel), with ``past`` the hold's loads before its start (modal, wheel, resume: ``_no_past`` at the run's
    start; the kernel leaves those before its last stored row in them); its unsettled steps are
    counted in ``call.unconverged`` for lane ``lane`` (None: every lane of ``outputs``)."""
    from vbikit.solve import kernels
    from vbikit.solve.compile_notice import announce_compile

    data, name = call.data, call.crossing.integrator
    announce_compile(kernels.implicit, FULL_KERNEL_USE)  # (rare: its first use on a machine compiles it)
    unsettled, evaluations = kernels.implicit(call.dt, motion, data.modes, data.vehicles, data.points, road,
                                              data.unilateral, modal_step, vehicle_step, *outputs, *past,
                                              _positions_before(call, first), tol,
                                              IMPLICIT_MAX_ITERATIONS, kernels.MANY_LANES, call.stride,
                                              _span(call, first == 0))
    log.debug("%s: %.2f contact-law evaluations per step", name, evaluations / max(call.n_steps - first, 1))
    if unsettled:
        for k in range(outputs[0].shape[0]) if lane is None else (lane,):
            call.unconverged[k] = call.unconverged.get(k, 0) + int(unsettled)
        log.warning("%s: the contact forces did not converge within %d iterations in %d of %d steps",
                    name, IMPLICIT_MAX_ITERATIONS, unsettled, call.n_steps)


def _lean_arguments(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep",
                    lanes: bool = False, *, start: bool) -> tuple:
    """The lean kernels' arguments (``kernels.lean``; ``kernels.lean_lanes`` with ``lanes``) of
    ``call`` (``start``: its motion begins at the run's start, ``_span``), up to ``tol`` and
    ``stride`` (the one-lane kernel's work spaces follow those:
    ``_lean_work``): the bundles' arrays one by one, contiguous (the vehicle step map's fused products and
    wheel entries, ``modal_step.fused_step``), the road and outputs of the one lane (of every lane)."""
    from vbikit.solve.modal_step import fused_step
    from vbikit.solve.system import point_gates

    c = np.ascontiguousarray
    data, road = call.data, call.road
    modes, veh, pts = data.modes, data.vehicles, data.points
    gated = point_gates(data)
    line = np.minimum(pts.line, road.elevations.shape[0] - 1)
    xi, dxi, q, dq, ddxi, _, wheel_force, wheel_len = call.outputs  # all but q̈ (computed when read)
    outputs = (xi, dxi, q, dq, ddxi, wheel_force, wheel_len)
    outputs = outputs if lanes else tuple(a[0] for a in outputs)
    elevations = road.elevations if lanes else road.elevations[:, :, 0]
    fused = fused_step(veh, vehicle_step)
    return tuple(c(a) if isinstance(a, np.ndarray) else a for a in (
        call.motion.travel, call.motion.speed, modes.start, modes.end, float(modes.grid_h), modes.values,
        modes.slopes, modes.amp, modes.omega, modes.zeta, *modal_step, fused.free, fused.free_load, fused.free_constant,
        fused.free_past, vehicle_step.response, vehicle_step.wheel_q, vehicle_step.wheel_v, fused.wheel_dof, fused.wheel_h,
        veh.wheel_stiffness, veh.wheel_damping, veh.wheel_first, veh.wheel_count, pts.origin, pts.direction,
        pts.vehicle, pts.track, line, pts.stiffness, pts.damping, pts.fixed_load, pts.gap, gated, pts.wheel,
        pts.width, road.stations, elevations, float(road.r_max), _span(call, start), *outputs))


def _positions_before(call: KernelCall, first: int) -> np.ndarray:
    """The contact points' positions x [m] (n_cp,) at t_{first−1}, a step before a kernel call that starts
    at step ``first`` of ``call`` (the hold at the deck's ends, ``vbikit.solve.kernels.hold``); before the
    run's start, where the motion has no row, each vehicle's travel less its speed times the step."""
    pts, motion = call.data.points, call.motion
    if first > 0:
        travel = motion.travel[2 * first - 2]
    else:
        travel = motion.travel[0] - motion.speed[0] * call.dt
    return np.ascontiguousarray(pts.origin + pts.direction * travel[pts.vehicle])


def _no_past(call: KernelCall, n_l: int = 1) -> tuple:
    """The hold's loads before a kernel call's start (modal (n_m, L), wheel (n_w, L), ``resume``) for a call
    at the run's start: none (the kernel holds the start's loads constant before t_0 and writes, at
    each row it stores, the loads of the step before it there: a call going on from that row reads
    them with ``resume`` True)."""
    return np.zeros((call.data.n_modes, n_l)), np.zeros((call.data.n_wheels, n_l)), False


def _span(call: KernelCall, start: bool) -> float:
    """The road-rate span [s] of ``call``'s integrator at its step (``Integrator.road_rate_span``),
    negative when the kernel call begins at the run's start (``start``): its first evaluation, the
    start state, then reads the road ahead of each point only (``kernels.road_point``), as the static
    start did (``vbikit.solve.simulate``); a call that goes on from a stored state reads the secant
    around it, as the steps before it did."""
    span = get_integrator(call.crossing.integrator).road_rate_span(call.dt)
    return -span if start else span


def implicit_kernel(quadratic: bool = False) -> Any:
    """The compiled kernel a single implicit crossing runs first (for ``Integrator.kernel``, which
    announces the first compilation): the lean kernel (``run_implicit``), its variant with the wheel
    loads held quadratic with ``quadratic`` (a map with Lp ≠ 0, ``_lean``)."""
    from vbikit.solve import kernels

    return kernels.lean_quadratic if quadratic else kernels.lean


def implicit_lanes_kernel(quadratic: bool = False) -> Any:
    """The compiled kernel a many-lane implicit call (a study's batch) runs first (for
    ``Integrator.lanes_kernel``): the many-lane lean kernel (``_run_lanes``), its variant with the
    wheel loads held quadratic with ``quadratic``."""
    from vbikit.solve import kernels

    return kernels.lean_lanes_quadratic if quadratic else kernels.lean_lanes
