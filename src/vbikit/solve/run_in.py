"""The vehicles' settled state at the start of a run: a run-in on the road behind them.

A run starts its vehicles at rest in static equilibrium ``crossing.approach`` before the bridge
(docs/theory.md, "Start and end of a crossing").  A truck that has driven on a rough road for long
carries a vibration that a short approach does not build up (docs/traffic.md, "Start from rest and
the approach").  With ``crossing.run_in`` = R > 0 [m] the vehicles are first driven alone over the
R metres of road behind their start positions, from rest in static equilibrium where that road begins,
and the run starts from the state they reach — as if the approach were R longer, without the coupled
steps over it (the run's own step: tests/verification/test_run_in.py).

Off the deck each contact point's force is the tire law on the road alone, F_p = k_p (r_p − g_p − z_w)
+ c_p (ṙ_p − ż_w) + f0_p (every point in contact: the run-in is linear), so the vehicles' wheel loads
of the exact step map (``modal_step.vehicle_step``: z_{n+1} = T z_n + L0 G_n + L1 G_{n+1} + b, the loads
held linear over a step) are G_n = a_n + D z_n with a_w = Σ_p (k_p (r_p − g_p) + c_p ṙ_p + f0_p) over the
wheel's points, known from the road, and D z = (k_w − Σ_p k_p) z_w + (c_w − Σ_p c_p) ż_w (zero where the
nominal tire is the sum of its points').  Then z_{n+1} = A z_n + u_n, A = S (T + L0 D), S = (I − L1 D)⁻¹,
u_n = S (L0 a_n + L1 a_{n+1} + b): a linear time-invariant recursion over the K run-in steps, stepped
vehicle by vehicle in a compiled loop (``kernels.linear_recursion``; the vehicles of an event do not
interact off the deck, ``independent_blocks``) — the numbers of the recursion in numpy
(``settled_state_by_steps``, the tests' reference) to round-off.  The road under each point is read as
the kernels read it (linear between stations; the rate the secant over ±|v| dt/2,
``kernels.run_in_loads``), each vehicle at its speed at the start, held over the run-in.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from vbikit._limits import MAX_RUN_IN

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.crossing import Crossing

#: [substitute] the shortest approach [m] from which a population's events start their vehicles settled: one-truck
#: traffic events on Bridge 2 (class B) give a mean IM 0.0147 ± 0.0024 higher at 100 m than at 10 m, and
#: within 1e-4 of 200 m's, each event's within 0.002 root mean square; beams of 15, 30, 40 and 60 m (first frequency
#: above, on and below the trucks' slowest modes the road excites) within 0.004 of 400 m's per event (docs/traffic.md,
#: "Start from rest and the approach"; docs/scripts/approach_numbers.py)
SETTLED_APPROACH = 100.0
#: [substitute] the largest share of its start transient, exp(−σ_min t), that a sprung vehicle may keep when it
#: reaches the bridge for its event to count as started settled (``start_transient_left``; σ_min the slowest decay
#: rate of the modes the road excites): the trucks ``SETTLED_APPROACH`` was checked with (1,000 one-truck events on
#: Bridge 2 and four beams, σ_min 0.69–0.81 s⁻¹ at 15–28 m/s, D = 100 m) kept 0.029 on average and 0.0657 at most
#: (rounded up here); an event's IM error against a 200 m start grows with the share kept, about 0.06–0.07 times it
#: root mean square (docs/traffic.md, "Start from rest and the approach"; docs/scripts/approach_numbers.py,
#: ``checked_transients`` and ``transient_effect``)
SETTLED_TRANSIENT_LEFT = 0.07
#: the start check's two numbers (``start_settling``), each (unit, meaning), as a single run's summary, a traffic
#: stream's events and a lifetime's dynamic events store them
START_OUTPUTS: dict[str, tuple[str, str]] = {
    "start_transient_left": ("1", "the largest share of its start transient (its slowest mode the road excites) a "
                                  "sprung vehicle kept when it reached the bridge, exp(−σ_min t) "
                                  "(vbikit.solve.run_in.start_transient_left; above SETTLED_TRANSIENT_LEFT = 0.07 the "
                                  "start is not settled: flagged start_unsettled in a population); 0 on a smooth road; "
                                  "NaN for moving forces (a single run's summary leaves it out)"),
    "start_settling_run_in": ("m", "the crossing.run_in with which every sprung vehicle would keep at most "
                                   "SETTLED_TRANSIENT_LEFT of its start transient, the approach as it is "
                                   "(vbikit.solve.run_in.start_settling; inf, null in JSON: an undamped mode the road "
                                   "excites); NaN for moving forces (left out, as above)"),
}
#: the least road [m] between the vehicles' front axle at the start and the deck's near end for which a
#: population adds its run-in (``population_run_in``): a contact patch reaches ahead of its axle, and a run-in
#: needs every contact point off the deck at the start
RUN_IN_CLEARANCE = 1.0

#: run-in steps whose road loads are read at a time (``settled_state``): its memory stays that of this many
#: steps, however long the run-in or fine the step
CHUNK_STEPS = 4096


def population_run_in(approach: float, overhang: float) -> float:
    """The run-in [m] a population (a traffic stream, a lifetime's dynamic events) gives its vehicles when its
    base scenario sets no ``crossing.run_in``: the rest of ``SETTLED_APPROACH`` after ``approach`` [m], so that
    every event starts its trucks as if they had driven 100 m of the road (docs/traffic.md, "Start from rest
    and the approach"); 0 when the approach leaves less than ``RUN_IN_CLEARANCE`` before a deck whose ends
    reach ``overhang`` [m] beyond their supports (a skew deck's oblique ends; a run-in needs the vehicles off the
    deck at the start: the events then start at rest, and are flagged ``start_from_rest``)."""
    if approach < least_run_in_approach(overhang):
        return 0.0
    return max(SETTLED_APPROACH - approach, 0.0)


def start_transient_left(crossing: "Crossing") -> float:
    """The largest share of its start transient that a sprung vehicle of ``crossing`` keeps when its front axle
    reaches its entry support: exp(−σ_min t), σ_min the slowest decay rate of the modes its road excites
    (``Vehicle.slowest_decay_rate``, its wheels grouped by axle and road line, ``road_groups``: with no
    ``road_right`` both wheel lines read one profile, and a roll mode has nothing to settle) and t the time it has
    driven since it was at rest — the run-in's, ``crossing.run_in`` at the slowest vehicle's speed at the start
    (``run_in_steps``: every vehicle drives for that long), and its own from the run's start to its entry
    (``crossing.approach`` at its speed for the leading vehicle, longer for one behind it): a free vibration decays
    as exp(−σ t); at a constant speed v over D metres in all, exp(−σ_min D / v).  1 for a vehicle with an undamped
    mode the road excites (it never settles); 0 on a smooth road (nothing to settle: rest is the settled state); NaN
    when no vehicle has DOFs (moving forces).  (``start_settling``'s first value.)"""
    return start_settling(crossing)[0]


def start_settling(crossing: "Crossing", limit: float | None = None) -> tuple[float, float]:
    """(``start_transient_left``, the run-in [m] with which every sprung vehicle of ``crossing`` would keep at most
    ``limit`` of its start transient (default ``SETTLED_TRANSIENT_LEFT``), the approach as it is): a vehicle needs
    t* = ln(1 / limit) / σ_min since rest, of which its own time from the run's start to its entry, τ, is given,
    and the run-in drives for run-in / v_slowest, so run-in = v_slowest (t* − τ), the largest over the vehicles, 0
    at least.  Infinite for a vehicle with an undamped mode the road excites, or when any vehicle is at rest at the
    start (no run-in then, ``run_in_steps``); 0 on a smooth road; NaN (both) when no vehicle has DOFs.  A vehicle
    that never reaches the bridge, or whose modes the road does not reach, is not judged."""
    if crossing.road is None and any(m.vehicle.n_dof for m in crossing.vehicles):
        return 0.0, 0.0
    return settling(crossing, crossing.road_right is not None, limit)


def settling(crossing: "Crossing", two_lines: bool, limit: float | None = None,
             settleable: bool = False) -> tuple[float, float]:
    """``start_settling`` of ``crossing``'s vehicles on a rough road, whether or not the crossing holds it yet
    (``two_lines``: the wheel lines read their own profiles, ``road_groups``): what a population decides its
    run-in with before it makes an event's road (``vbikit.traffic.study.EventContext.settled_run_in``; there with
    ``settleable``: the run-in is that of the vehicles that can settle, a vehicle with an undamped mode left out of
    it, not infinite)."""
    limit = SETTLED_TRANSIENT_LEFT if limit is None else float(limit)
    t0 = crossing.start_time
    sprung = [m for m in crossing.vehicles if m.vehicle.n_dof]
    if not sprung:
        return math.nan, math.nan
    slowest = min(abs(m._speed_at(t0)) for m in crossing.vehicles)
    run_in = max(float(crossing.run_in), 0.0)
    before = run_in / slowest if run_in > 0.0 and slowest > 0.0 else 0.0  # (run_in_steps: none at rest)
    worst, needed = 0.0, 0.0
    for motion in sprung:
        sigma = motion.vehicle.slowest_decay_rate(road_groups(motion.vehicle, two_lines))
        entry = motion.time_at(0.0)
        if not math.isfinite(entry) or sigma == math.inf:
            continue  # (a vehicle that never enters, or whose modes the road does not reach: nothing to judge)
        own = entry - t0
        worst = max(worst, math.exp(-sigma * (before + own)) if sigma > 0.0 else 1.0)
        if sigma > 0.0 and slowest > 0.0:
            needed = max(needed, slowest * (math.log(1.0 / limit) / sigma - own))
        elif not settleable:
            needed = math.inf
    return worst, needed


def lengthened_run_in(run_in: float, needed: float) -> float:
    """The run-in [m] a population gives an event whose vehicles need ``needed`` [m] to settle (``settling``) when its
    own is ``run_in`` [m]: the longer of the two, ``needed`` rounded up to the metre and at most ``MAX_RUN_IN``
    (``vbikit.traffic.study.EventContext.settled_run_in``; what ``vbikit.analysis.population_start.start_attrs``
    counts an event's run-in against)."""
    if not (math.isfinite(needed) and needed > run_in):
        return float(run_in)
    return max(float(run_in), min(float(math.ceil(needed)), MAX_RUN_IN))


#: run-ins [m] that differ by at most this are the same (``run_in_problem``): a lengthened run-in is rounded up to the
#: metre from an eigenvalue, which another machine's linear algebra may put a rounding error to the other side of
RUN_IN_SAME = 1.0 + 1e-6


def run_in_problem(stored: Any, given: Any) -> str | None:
    """Why a stored part of a population's runs cannot be used (None if it can): an event of it ran with another
    run-in [m] than this version gives it (``stored`` against ``given``, per event; NaN for moving forces), e.g. one
    written before the population lengthened a run-in for vehicles that need more."""
    stored, given = np.asarray(stored, float), np.asarray(given, float)
    sprung = np.isfinite(stored)
    if np.any(np.abs(stored[sprung] - given[sprung]) > RUN_IN_SAME):
        return "its events ran with another run-in than this version gives them (written by an earlier version)"
    return None


def road_groups(vehicle: Any, two_lines: bool = False) -> NDArray[np.int64]:
    """The wheels of ``vehicle`` that the road moves together (``Vehicle.slowest_decay_rate``'s groups): one group
    per axle (the wheels at one offset see the road at the same time), split into its left and right wheels when
    the two wheel lines read their own profiles (``two_lines``: a crossing's ``road_right``; the right line the
    wheels at lateral < 0, as the contact points read it)."""
    axles = np.unique(np.round([w.offset for w in vehicle.wheels], 9), return_inverse=True)[1]
    lines = np.array([two_lines and w.lateral < 0.0 for w in vehicle.wheels], np.int64)
    return np.asarray(axles, np.int64) * 2 + lines


def least_run_in_approach(overhang: float) -> float:
    """The shortest approach [m] from which a run-in can start before a deck whose ends reach ``overhang`` [m]
    beyond their supports: every contact point off the deck, ``RUN_IN_CLEARANCE`` beyond its ends."""
    return max(overhang, 0.0) + RUN_IN_CLEARANCE


def check_off_deck(data: Any, x0: NDArray[np.float64], run_in: float) -> None:
    """Refuse a run-in (``run_in`` [m] > 0) when a contact point is on the deck at the start (the points at
    ``x0`` [m]): the run-in drives the vehicles on the road alone."""
    if np.any((x0 >= data.modes.start[data.points.track]) & (x0 <= data.modes.end[data.points.track])):
        raise ValueError(f"crossing.run_in = {run_in:g} m: a contact point is on the deck when the run starts; the "
                         "run-in drives the vehicles on the road alone (give a crossing.approach that starts every "
                         f"contact point before the deck, at least {RUN_IN_CLEARANCE:g} m beyond its ends)")


def run_in_inputs(data: Any, step: Any, dt: float, travel0: NDArray[np.float64], speed0: NDArray[np.float64],
                  road: Any, n: int) -> tuple[NDArray[np.float64], ...]:
    """The recursion z_{k+1} = A z_k + M0 a_k + M1 a_{k+1} + c over the ``n`` run-in steps of ``dt`` ending
    at the start (module docstring): (A, M0, M1, c, a), a (n + 1, n_w) the wheels' road loads at the step
    ends (``road_loads``), for the vehicles at travel ``travel0`` [m] and speed ``speed0`` [m/s] (per
    vehicle) at the start on the road bundle ``road`` (lane 0); ``step`` the vehicles' exact step map over ``dt``."""
    return (*recursion(data, step), road_loads(data, dt, travel0, speed0, road, n, 0, n))


def recursion(data: Any, step: Any) -> tuple[NDArray[np.float64], ...]:
    """(A, M0, M1, c) of the run-in's recursion (module docstring) for the vehicles' step map ``step``.  Where
    every wheel's nominal tire is the sum of its points' (D = 0: point tires, the usual case) S = I, and A, M0,
    M1, c are the step map's own T, L0, L1, b — the numbers the products with S = (I − 0)⁻¹ = I give, exactly
    (shared with the step map: not to be written to)."""
    d = load_feedback(data)
    if d is None:
        return step.transition, step.load0, step.load1, step.constant
    settle = np.linalg.inv(np.eye(d.shape[1]) - step.load1 @ d)
    return settle @ (step.transition + step.load0 @ d), settle @ step.load0, settle @ step.load1, settle @ step.constant


def load_feedback(data: Any) -> NDArray[np.float64] | None:
    """D (n_w, 2 n_d) of the run-in's wheel loads G_n = a_n + D z_n (module docstring): each wheel's nominal tire
    less the sum of its points' tires, on the wheel's rows; None where that is zero for every wheel."""
    pts, veh = data.points, data.vehicles
    n_d, n_w = veh.gravity.size, veh.wheel_rows.shape[0]
    stiffness = veh.wheel_stiffness - np.bincount(pts.wheel, weights=pts.stiffness, minlength=n_w)
    damping = veh.wheel_damping - np.bincount(pts.wheel, weights=pts.damping, minlength=n_w)
    if not (stiffness.any() or damping.any()):
        return None
    d = np.zeros((n_w, 2 * n_d))
    d[:, :n_d] = stiffness[:, None] * veh.wheel_rows
    d[:, n_d:] = damping[:, None] * veh.wheel_rows
    return d


def road_loads(data: Any, dt: float, travel0: NDArray[np.float64], speed0: NDArray[np.float64], road: Any, n: int,
               first: int, last: int) -> NDArray[np.float64]:
    """The wheels' road loads a_k (module docstring) at the run-in's step ends k = ``first`` … ``last`` of ``n``
    (t = (k − n) dt, t = 0 the start), (last − first + 1, n_w) (``kernels.run_in_loads``)."""
    from vbikit.solve import kernels

    pts = data.points
    vx = np.ascontiguousarray(pts.direction * speed0[pts.vehicle], float)
    x0 = np.ascontiguousarray(pts.origin + pts.direction * travel0[pts.vehicle], float)
    out = np.zeros((last - first + 1, data.vehicles.wheel_rows.shape[0]))
    kernels.run_in_loads(x0, vx, float(dt), np.int64(first), np.int64(n),
                         np.ascontiguousarray(np.minimum(pts.line, road.elevations.shape[0] - 1), np.int64),
                         pts.stiffness, pts.damping, pts.fixed_load, pts.gap, np.ascontiguousarray(pts.wheel, np.int64),
                         road.stations, np.ascontiguousarray(road.elevations[:, :, 0]),
                         np.full(x0.size, -1, np.int64), out)
    return out


def settled_state(crossing: "Crossing", data: Any, step: Any, dt: float, travel0: NDArray[np.float64],
                  speed0: NDArray[np.float64], road: Any) -> NDArray[np.float64]:
    """The vehicles' state z = (q, q̇) at the start after ``crossing.run_in`` metres of road, from rest in
    static equilibrium where the run-in begins (module docstring: z0 = (I − A)⁻¹ ((M0 + M1) a_0 + c), the
    recursion's fixed point under that place's road loads); ``step`` the vehicles' exact step map over
    ``dt`` (linear hold).  The recursion z_{k+1} = A z_k + M0 a_k + M1 a_{k+1} + c stepped by each group of
    states that nothing couples to another (``independent_blocks``: a vehicle) on its own
    (``kernels.linear_recursion``), the road loads read ``CHUNK_STEPS`` steps at a time for every group."""
    from vbikit.solve import kernels

    n = run_in_steps(crossing, dt, speed0)
    a_mat, m0, m1, c = recursion(data, step)
    loads = road_loads(data, dt, travel0, speed0, road, n, 0, min(CHUNK_STEPS, n))  # (the first chunk's: a_0 first)
    z = _rest(a_mat, m0, m1, c, loads)
    if n == 0 or z.size == 0:
        return z
    groups = [(states, wheels, *_by_columns(a_mat, m0, m1, c, z, states, wheels))
              for states, wheels in independent_blocks(a_mat, m0, m1)]
    work, none = np.empty(z.size), np.empty((0, z.size))
    for k0 in range(0, n, CHUNK_STEPS):  # steps k0 … k1 − 1, their loads read once for every group
        if k0:
            loads = road_loads(data, dt, travel0, speed0, road, n, k0, min(k0 + CHUNK_STEPS, n))
        for _, wheels, a_g, m0_g, m1_g, c_g, z_g in groups:
            every = wheels.size == loads.shape[1]  # (a group's wheels ascend: all of them are the loads as they are)
            kernels.linear_recursion(a_g, m0_g, m1_g, c_g, loads if every else np.ascontiguousarray(loads[:, wheels]),
                                     z_g, work, none)
    for states, *_, z_g in groups:
        z[states] = z_g
    return z


def _by_columns(a_mat: NDArray[np.float64], m0: NDArray[np.float64], m1: NDArray[np.float64], c: NDArray[np.float64],
                z: NDArray[np.float64], states: NDArray[np.int64], wheels: NDArray[np.int64]) -> tuple:
    """A group's recursion (``states``, ``wheels``: ``independent_blocks``) as ``kernels.linear_recursion`` takes it:
    its Aᵀ, M0ᵀ, M1ᵀ (the matrices by columns), c and state z, fresh C-contiguous arrays (the whole recursion's
    own, transposed, when the group is all of it)."""
    c_ = np.ascontiguousarray
    if states.size == z.size and wheels.size == m0.shape[1]:  # (indices ascending: the whole recursion)
        return c_(a_mat.T), c_(m0.T), c_(m1.T), c.copy(), z.copy()
    return (c_(a_mat[np.ix_(states, states)].T), c_(m0[np.ix_(states, wheels)].T), c_(m1[np.ix_(states, wheels)].T),
            c_(c[states]), c_(z[states]))


def independent_blocks(a_mat: NDArray[np.float64], m0: NDArray[np.float64],
                       m1: NDArray[np.float64]) -> list[tuple[NDArray[np.int64], NDArray[np.int64]]]:
    """The groups (states, wheels) of the recursion over z = (q, q̇) that no entry of A, M0 or M1 couples to
    another group — each vehicle of an event, whose run-ins are independent — so that a group's recursion
    costs its own size, not the event's: the contiguous ranges of DOFs (a vehicle's are contiguous, stacked
    block-diagonal) that no DOF couples across (through its q or q̇, or a wheel whose load reaches both),
    each with its q and q̇ states and the wheels whose loads reach them (a wheel without DOFs in none).  A
    coupling anywhere else merges ranges: fewer, larger groups, the same recursion."""
    n_d = a_mat.shape[0] // 2
    reach = ((m0 != 0.0) | (m1 != 0.0)).reshape(2, n_d, m0.shape[1]).any(axis=0)  # (DOFs, wheels): reaching q or q̇
    shared = reach.astype(float)
    dofs = (a_mat != 0.0).reshape(2, n_d, 2, n_d).any(axis=(0, 2)) | ((shared @ shared.T) != 0.0)  # (q, q̇ blocks of A)
    dofs |= dofs.T
    index = np.arange(n_d)
    last = n_d - 1 - np.argmax(dofs[:, ::-1], axis=1)  # each DOF's last coupled DOF (its own at least)
    ends = (np.flatnonzero(np.maximum.accumulate(np.maximum(last, index)) == index) + 1).tolist()
    wheel_dof = np.where(reach.any(axis=0), np.argmax(reach, axis=0), -1)
    groups = []
    for lo, hi in zip([0, *ends[:-1]], ends):
        states = np.concatenate((index[lo:hi], index[lo:hi] + n_d))
        groups.append((states, np.flatnonzero((wheel_dof >= lo) & (wheel_dof < hi))))
    return groups


def settled_state_by_steps(crossing: "Crossing", data: Any, step: Any, dt: float, travel0: NDArray[np.float64],
                           speed0: NDArray[np.float64], road: Any) -> NDArray[np.float64]:
    """``settled_state`` by the recursion step by step (the reference of the tests)."""
    n = run_in_steps(crossing, dt, speed0)
    inputs = run_in_inputs(data, step, dt, travel0, speed0, road, n)
    return _by_steps(*inputs, _rest(*inputs))


def _rest(a_mat, m0, m1, c, a) -> NDArray[np.float64]:
    """The recursion's fixed point under the road loads where the run-in begins, a_0 held: the vehicles at
    rest in static equilibrium there, z = (I − A)⁻¹ ((M0 + M1) a_0 + c)."""
    return np.linalg.solve(np.eye(a_mat.shape[0]) - a_mat, (m0 + m1) @ a[0] + c)


def _by_steps(a_mat, m0, m1, c, a, z0: NDArray[np.float64]) -> NDArray[np.float64]:
    z = z0.copy()
    for k in range(a.shape[0] - 1):
        z = a_mat @ z + m0 @ a[k] + m1 @ a[k + 1] + c
    return z


def run_in_steps(crossing: "Crossing", dt: float, speed0: NDArray[np.float64]) -> int:
    """Steps of ``dt`` the slowest vehicle needs to drive ``crossing.run_in`` metres (0: no run-in)."""
    if not crossing.run_in > 0:
        return 0
    v = float(np.min(np.abs(speed0))) if speed0.size else 0.0
    return int(math.ceil(crossing.run_in / (v * dt) - 1e-9)) if v > 0 else 0
