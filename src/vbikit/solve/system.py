"""The coupled system's data for the kernels, and the system at one instant (static start,
stability limit).

``kernel_data`` turns a [`Crossing`][vbikit.solve.Crossing] into the kernels' argument bundles
(``vbikit.solve.kernels``: ``Modes``, ``Vehicles``, ``Points``); ``motion`` gives the
vehicles' travel on a time grid and ``road_data`` the road lines of a set of lanes.  A
several-vehicle system is the same bundles with block-diagonal vehicle matrices, stacked
wheels and points that carry their own vehicle index, origin and direction (see the kernels'
module docstring); the functions below that take a ``KernelData`` work on such a system too.
"""
from __future__ import annotations

import logging

from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import Kept
from vbikit.road.profile import RoadProfile
from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.kernels import Modes, Motion, Points, Road, Vehicles
from vbikit.solve.tabulate import TrackTable, hermite_rows, tabulate_tracks


log = logging.getLogger(__name__)
#: the start warnings (``static_state``) this process has logged
_START_LOGGED: set[str] = set()

@dataclass(frozen=True)
class KernelData:
    """Argument bundles for ``vbikit.solve.kernels`` (see its docstring) and their sizes."""

    modes: Modes
    vehicles: Vehicles
    points: Points
    unilateral: bool

    @property
    def n_modes(self) -> int:
        return int(self.modes.omega.size)

    @property
    def n_dof(self) -> int:
        return int(self.vehicles.gravity.size)

    @property
    def n_points(self) -> int:
        return int(self.points.origin.size)

    @property
    def n_wheels(self) -> int:
        return int(self.vehicles.wheel_rows.shape[0])


def modes_data(bridge, table: TrackTable) -> Modes:
    """The ``Modes`` bundle of ``bridge`` with its mode-shape ``table`` (kept with the table: the
    tables of a bridge's tracks are kept, ``vbikit.solve.tabulate``)."""
    known = table.__dict__.get("_modes")
    if (known is not None and known.omega.tobytes() == np.asarray(bridge.omega, float).tobytes()
            and known.zeta.tobytes() == np.asarray(bridge.damping_ratios, float).tobytes()):
        return known
    modes = _modes_data(bridge, table)
    object.__setattr__(table, "_modes", modes)
    return modes


def _modes_data(bridge, table: TrackTable) -> Modes:
    amp = 1.01 * np.abs(table.values).max(axis=(0, 1))  # bound on |φ_m| incl. Hermite overshoot
    return Modes(np.ascontiguousarray(bridge.omega, float), np.ascontiguousarray(bridge.damping_ratios, float),
                 np.ascontiguousarray(table.start, float), np.ascontiguousarray(table.end, float),
                 float(table.spacing), table.values, table.slopes, amp)


def vehicles_data(vehicle, contact) -> Vehicles:
    """The ``Vehicles`` bundle of one vehicle and its contact points."""
    n_d = vehicle.n_dof
    n_w = len(vehicle.wheels)
    rows = np.array([w.row for w in vehicle.wheels], float).reshape(n_w, n_d)
    m_inv = np.linalg.inv(vehicle.mass) if n_d else np.zeros((0, 0))
    k_w = np.array([w.stiffness for w in vehicle.wheels], float)
    c_w = np.array([w.damping for w in vehicle.wheels], float)
    return Vehicles(np.ascontiguousarray(vehicle.mass, float).reshape(n_d, n_d), m_inv.reshape(n_d, n_d),
                    np.ascontiguousarray(vehicle.damping, float).reshape(n_d, n_d),
                    np.ascontiguousarray(vehicle.stiffness, float).reshape(n_d, n_d),
                    np.ascontiguousarray(vehicle.gravity, float).reshape(n_d), rows, contact.wheel_first,
                    contact.wheel_count, contact.wheel_envelope, k_w, c_w)


def points_data(contact, track: NDArray[np.int64], origin: NDArray[np.float64] | None = None, direction: float = 1.0,
                vehicle: int = 0) -> Points:
    """The ``Points`` bundle of one vehicle's ``contact`` points on mode-shape tables ``track``:
    x_p = ``origin`` + ``direction``·s (default origin −setback: s is the front-axle x), road
    line 1 for points right of the centreline (lateral < 0), else 0."""
    n = contact.n
    origin = -contact.setback if origin is None else np.asarray(origin, float)
    return Points(np.ascontiguousarray(origin, float), np.full(n, float(direction)), np.full(n, vehicle, np.int64),
                  np.asarray(track, np.int64), (contact.lateral < 0.0).astype(np.int64), contact.stiffness,
                  contact.damping, contact.fixed_load, contact.gap, contact.gated, contact.wheel, contact.width,
                  np.ascontiguousarray(contact.slope_range))


def kernel_data(crossing: Crossing, points_per_mode: int = 100) -> KernelData:
    """Tabulate mode shapes along every wheel track and bundle all arrays for the kernels (several
    vehicles: their stacked DOFs and wheels, each point with its vehicle, origin and direction;
    kept with the crossing, ``Crossing.kept``: shared, not to be written)."""
    return crossing.kept("kernel_data", int(points_per_mode), lambda: _kernel_data(crossing, int(points_per_mode)))


def _kernel_data(crossing: Crossing, points_per_mode: int) -> KernelData:
    """``kernel_data`` made afresh."""
    cp = crossing.contact
    origin, direction, y = crossing.point_kinematics()  # copies: the bundle owns its arrays
    tracks, track_idx = wheel_tracks(y)
    table: TrackTable = tabulate_tracks(crossing.bridge, tracks, points_per_mode)
    points = points_data(cp, track_idx.ravel())._replace(
        origin=np.ascontiguousarray(origin, float), direction=np.ascontiguousarray(direction, float),
        vehicle=np.ascontiguousarray(crossing.point_vehicle, np.int64))
    return KernelData(modes_data(crossing.bridge, table), vehicles_data(crossing.vehicle, cp), points,
                      bool(crossing.loss_of_contact))


#: ``wheel_tracks`` already found, by the points' exact y (a stream's events put their points on a few lines)
_TRACKS: "Kept[tuple, tuple[NDArray[np.float64], NDArray[np.int64]]]" = Kept(64)


def wheel_tracks(y: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The distinct wheel tracks y [m] of points at deck y ``y``, ascending, and each point's index
    into them (``np.unique(y, return_inverse=True)``; a fresh copy of both: the bundle owns its arrays)."""
    y = np.ascontiguousarray(y, float)
    tracks, index = _TRACKS.get((y.shape, y.tobytes()), lambda: np.unique(y, return_inverse=True))
    return tracks.copy(), index.copy()


def motion(crossing: Crossing, t: NDArray[np.float64]) -> Motion:
    """Travel s_v [m] and speed [m/s] of the crossing's vehicles at times ``t`` [s], (n_t, n_vehicles)."""
    return Motion(np.ascontiguousarray(crossing.travel(t), float), np.ascontiguousarray(crossing.travel_speed(t), float))


def point_positions(data: KernelData, travel: NDArray[np.float64] | float,
                    speed: NDArray[np.float64] | float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Positions x_p [m] and x-rates dir_p·v [m/s] of every point for the vehicles' ``travel``
    (n_vehicles,) [m] and ``speed`` [m/s] (scalars: every vehicle)."""
    pts = data.points
    s, v = np.asarray(travel, float), np.asarray(speed, float)
    # one value (every vehicle's) multiplies as a scalar: the same products as gathering copies of it
    return (pts.origin + pts.direction * (s.reshape(()) if s.size == 1 else s[pts.vehicle]),
            pts.direction * (v.reshape(()) if v.size == 1 else v[pts.vehicle]))


def coupled_matrices(
    crossing: Crossing | None,
    data: KernelData,
    front_position: float | NDArray[np.float64],
    speed: float | NDArray[np.float64],
    road: NDArray[np.float64] | None = None,
    road_rate: NDArray[np.float64] | None = None,
    active: NDArray[np.bool_] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """M, C, K, F of Eq. 9 (u = [ξ; q]) with the vehicles' travel ``front_position`` [m] (past
    their entry supports) moving at ``speed`` [m/s], the given contact points ``active``
    (default: every point in linear contact)."""
    x, vx = point_positions(data, front_position, speed)
    return coupled_system(data.modes, data.vehicles, data.points, x, vx, road, road_rate, active)[:4]


def coupled_system(modes: Modes, vehicles: Vehicles, points: Points, x: NDArray[np.float64], vx: NDArray[np.float64],
                   road: NDArray[np.float64] | None = None, road_rate: NDArray[np.float64] | None = None,
                   active: NDArray[np.bool_] | None = None) -> tuple[NDArray[np.float64], ...]:
    """The coupled system matrices of Eq. 9 at one instant, M ü + C u̇ + K u = F with u = [ξ; q], for
    contact points at positions ``x`` [m] with x-rates ``vx`` [m/s]: the linearisation of the contact
    law about contact (``vbikit.solve.kernels``: F_p = k_p δ_p + c_p δ̇_p + f0_p, δ_p = φ_p·ξ + r_p −
    g_p − h_w·q, δ̇_p = φ_p·ξ̇ + v_p φ'_p·ξ + ṙ_p − h_w·q̇) over the ``active`` points (default all),
    with the road elevation ``road`` [m] and rate ``road_rate`` [m/s] under each point (default 0).
    With b_p = [φ_p; −h_w] (φ_p = 0 off the deck) and g_p = v_p [φ'_p; 0]:

    M = diag(I, M_v),  C = diag(2ζω, C_v) + Σ c_p b_p b_pᵀ,
    K = diag(ω², K_v) + Σ (k_p b_p b_pᵀ + c_p b_p g_pᵀ),  F = [0; F_G] − Σ b_p (k_p (r_p − g_p) + c_p ṙ_p + f0_p).

    Returns M, C, K, F and the points' mode-shape rows φ, φ' (n_p, n_m), zero off the deck and for
    points not active (the static start, the explicit step's stability limit and the random-vibration
    solver assemble here)."""
    n_m, n_d = modes.omega.size, vehicles.gravity.size
    act, phi, dphi, k, c, b = _contact_rows(modes, vehicles, points, x, active)
    n = n_m + n_d
    mass, damp = np.zeros((n, n)), np.zeros((n, n))
    mass[:n_m, :n_m] = np.eye(n_m)
    mass[n_m:, n_m:] = vehicles.mass
    damp[:n_m, :n_m] = np.diag(2.0 * modes.zeta * modes.omega)
    damp[n_m:, n_m:] = vehicles.damping
    damp += b.T @ (c[:, None] * b)
    stiff, load = _stiffness_load(modes, vehicles, points, vx, road, road_rate, act, dphi, k, c, b)
    return mass, damp, stiff, load, phi, dphi


def _contact_rows(modes: Modes, vehicles: Vehicles, points: Points, x: NDArray[np.float64],
                  active: NDArray[np.bool_] | None) -> tuple[NDArray[np.float64], ...]:
    """``coupled_system``'s contact terms: the active mask, the rows φ_p, φ'_p (zero off the deck and
    for points not active), the active points' k_p, c_p and the rows b_p = [φ_p; −h_w] (n_p, n)."""
    n_m, n_p = modes.omega.size, x.size
    act = np.ones(n_p, bool) if active is None else np.asarray(active, bool)
    on = act & (modes.start[points.track] <= x) & (x <= modes.end[points.track])
    phi, dphi = np.zeros((n_p, n_m)), np.zeros((n_p, n_m))
    if on.any():
        phi[on], dphi[on] = hermite_rows(modes.start, modes.grid_h, modes.values, modes.slopes, points.track[on], x[on])
    k, c = np.where(act, points.stiffness, 0.0), np.where(act, points.damping, 0.0)
    b = np.concatenate([phi, -vehicles.wheel_rows[points.wheel]], axis=1)  # (n_p, n): the rows b_p
    return act, phi, dphi, k, c, b


def _stiffness_load(modes: Modes, vehicles: Vehicles, points: Points, vx: NDArray[np.float64],
                    road: NDArray[np.float64] | None, road_rate: NDArray[np.float64] | None, act: NDArray[np.bool_],
                    dphi: NDArray[np.float64], k: NDArray[np.float64], c: NDArray[np.float64],
                    b: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """K and F of ``coupled_system`` from its contact terms (``_contact_rows``): all the static start needs."""
    n_m, n_d, n_p = modes.omega.size, vehicles.gravity.size, vx.size
    r = np.zeros(n_p) if road is None else np.asarray(road, float)
    rdot = np.zeros(n_p) if road_rate is None else np.asarray(road_rate, float)
    n = n_m + n_d
    stiff = np.zeros((n, n))
    stiff[:n_m, :n_m] = np.diag(modes.omega * modes.omega)
    stiff[n_m:, n_m:] = vehicles.stiffness
    stiff += b.T @ (k[:, None] * b)
    stiff[:, :n_m] += b.T @ ((c * vx)[:, None] * dphi)
    load = np.concatenate([np.zeros(n_m), vehicles.gravity]) - b.T @ (k * (r - points.gap) + c * rdot
                                                                        + np.where(act, points.fixed_load, 0.0))
    return stiff, load


def static_state(crossing: Crossing | None, data: KernelData, road: NDArray[np.float64], travel=None,
                 road_rate: NDArray[np.float64] | None = None, speed: float | NDArray[np.float64] = 0.0,
                 max_iterations: int = 100, replaced: bool = False
                 ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """The state (ξ, q) at t = 0 with zero velocities and zero accelerations, and the active
    contact points: the equilibrium of Eq. 9 on the road elevations ``road`` [m] under the points,
    with the tire dashpots' forces c_p·ṙ_p from the road rates ``road_rate`` [m/s] = dir·v·r'(x_p)
    and the convective deck rate dir·v·φ'_p·ξ at the vehicles' ``speed`` v [m/s] (both 0 by
    default: rest).  ``travel``: the vehicles' travel at the start, default the crossing's.  Contact is piecewise linear, so the active set is iterated: start with every
    point in contact (for a rigid disk, each wheel's highest point), solve, drop points that do
    not press (by the kernels' contact law), repeat until the set is unchanged.

    When the dashpot forces are so large that no such state exists (a tire would have to pull:
    the vehicle is not supported, e.g. a profile in mm read as m), the start falls back to the
    equilibrium at rest (no rates), with a warning — none when the vehicles' start state is ``replaced``
    (a run-in follows, ``vbikit.solve.run_in``: it starts every contact point off the deck, so the bridge
    starts at rest either way, and it sets the vehicles' state itself; the fallback changes nothing)."""
    travel = crossing.travel(crossing.start_time)[0] if travel is None else travel
    try:
        return _equilibrium(crossing, data, road, travel, road_rate, speed, max_iterations)
    except (np.linalg.LinAlgError, RuntimeError):
        moving = road_rate is not None and bool(np.any(np.asarray(road_rate) != 0.0)) or \
            bool(np.any(np.asarray(speed) != 0.0))
        if not moving:
            raise
    kmh = 3.6 * float(np.max(np.abs(np.asarray(speed, float)), initial=0.0))
    text = (f"the vehicle cannot start at {kmh:.0f} km/h in equilibrium with its tire dampers' forces from the "
            "road's slope under the tires (a tire would have to pull at t = 0; a very rough road, or a profile "
            "in mm read as m): it starts from its equilibrium at rest instead")
    if not replaced and text not in _START_LOGGED:  # once a process and text: a study's worker runs many such crossings
        _START_LOGGED.add(text)
        log.warning(text)
    return _equilibrium(crossing, data, road, travel, None, 0.0, max_iterations)


def _equilibrium(crossing: Crossing | None, data: KernelData, road: NDArray[np.float64], travel,
                 road_rate: NDArray[np.float64] | None, speed: float | NDArray[np.float64],
                 max_iterations: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """``static_state`` for given rates (raises LinAlgError / RuntimeError if there is none)."""
    n_m, n_p = data.n_modes, data.n_points
    x, vx = point_positions(data, travel, speed)
    rate = np.zeros(n_p) if road_rate is None else np.array(road_rate, float)
    active = np.ones(n_p, bool)
    gap = data.points.gap
    veh = data.vehicles
    flat = not np.any(veh.wheel_envelope)  # no rigid disk: the flat law of the lean kernel
    for first, count, env in zip(veh.wheel_first, veh.wheel_count, veh.wheel_envelope) if not flat else ():
        if env:
            sl = slice(first, first + count)
            active[sl] = False
            active[first + int(np.argmax(road[sl] - gap[sl]))] = True
            # the rigid disk's contact rate: the surface rate clamped to the circle's slopes (as the kernels)
            v = data.points.direction[sl] * vx[sl]
            rate[sl] = np.clip(rate[sl], v * data.points.slope_range[sl, 0], v * data.points.slope_range[sl, 1])
    if flat:
        gated = point_gates(data)
        zeros = np.zeros(n_p, np.int64)
        road_c, rate_c = np.ascontiguousarray(road, float), np.ascontiguousarray(rate)
        r_max = float(np.max(road, initial=0.0))
    else:
        cache = kernels.new_cache(n_p, n_m, 1)._replace(x=x, vx=vx, rv=np.ascontiguousarray(road, float).reshape(n_p, 1),
                                                        rr=np.ascontiguousarray(rate).reshape(n_p, 1),
                                                        have_r=np.ones(n_p, bool))
        work = kernels.new_work(n_p, data.n_dof, 1)
        wf, wl = np.zeros((data.n_wheels, 1)), np.zeros((data.n_wheels, 1))
        # the road values are given (have_r all True): the bundle only carries r_max
        bundle = Road(np.array([0.0, 1.0]), np.zeros((1, 2, 1)), float(np.max(road, initial=0.0)))
    for _ in range(max_iterations):
        act, _, dphi, k, c, b = _contact_rows(data.modes, veh, data.points, x, active)  # (``coupled_matrices``' K, F)
        stiff, load = _stiffness_load(data.modes, veh, data.points, vx, road, rate, act, dphi, k, c, b)
        u = np.linalg.solve(stiff, load)
        if flat:
            new_active = np.zeros(n_p, bool)
            pts, modes = data.points, data.modes
            kernels.lean_law(u[:n_m].copy(), u[n_m:].copy(), x, vx, modes.start, modes.end, float(modes.grid_h),
                             modes.values, modes.slopes, modes.amp, veh.wheel_rows, veh.wheel_first, veh.wheel_count,
                             pts.track, zeros, pts.stiffness, pts.damping, pts.fixed_load, pts.gap, gated, pts.width,
                             np.array([0.0, 1.0]), np.zeros((1, 2)), r_max, road_c.copy(), rate_c.copy(), True,
                             new_active)
        else:
            kernels.contact_forces(u[:n_m].reshape(n_m, 1).copy(), np.zeros((n_m, 1)), u[n_m:].reshape(-1, 1).copy(),
                                   np.zeros((data.n_dof, 1)), data.modes, data.vehicles, data.points, bundle,
                                   data.unilateral, cache, work, wf, wl, kernels.MANY_LANES, 0.0)
            new_active = work.active[:, 0]
        if np.array_equal(new_active, active):
            return u[:n_m], u[n_m:], active
        active = new_active.copy()
    raise RuntimeError("the static start did not settle on a set of contact points; check the road under the vehicle")


def point_gates(data: KernelData) -> NDArray[np.bool_]:
    """Which points the flat kernels (``kernels.lean``, ``kernels.lean_law``) gate: those of rigid
    disks and wheels that may lift off (``Points.gated``), and every point with a tire when contact
    is unilateral."""
    pts = data.points
    return np.ascontiguousarray(pts.gated | (bool(data.unilateral) & (pts.stiffness > 0.0)))


def flat_road(data: KernelData, road: Road, x: NDArray[np.float64], vx: NDArray[np.float64],
              span: float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Road elevation [m] and rate [m/s] under every point at positions ``x`` [m] with x-rates
    ``vx`` [m/s] on the first lane of ``road``, by the lean kernel's flat law (``kernels.lean_law``,
    the same interpolation as ``kernels.road_at``; no rigid disks; ``span`` [s]: the rate's secant
    half-width in time, ``kernels.road_point``)."""
    pts, modes, veh, n_p = data.points, data.modes, data.vehicles, data.n_points
    r, dr = np.zeros(n_p), np.zeros(n_p)
    kernels.lean_law(np.zeros(data.n_modes), np.zeros(data.n_dof), np.ascontiguousarray(x, float),
                     np.ascontiguousarray(vx, float), modes.start, modes.end, float(modes.grid_h), modes.values,
                     modes.slopes, modes.amp, veh.wheel_rows, veh.wheel_first, veh.wheel_count, pts.track,
                     np.minimum(pts.line, road.elevations.shape[0] - 1), pts.stiffness, pts.damping, pts.fixed_load,
                     pts.gap, np.zeros(n_p, bool), pts.width, road.stations,
                     np.ascontiguousarray(road.elevations[:, :, 0]), float(road.r_max), r, dr, False,
                     np.zeros(n_p, bool), span)
    return r, dr


def road_data(roads: Sequence[tuple[RoadProfile | None, RoadProfile | None]], x_min: float, x_max: float) -> Road:
    """The kernels' road bundle (stations, elevations (n_lines, n_s, L), r_max) of L lanes with
    (left, right) wheel-line profiles each (None: smooth; right None: as the left).

    Lanes share one station array: the union of all profiles' stations, on which every profile
    is exactly the same piecewise-linear function (random profiles of one study share their
    stations, so the union is just those).  Line 1 (the points with ``Points.line`` = 1, right
    of the centreline) exists when any lane has a right profile; otherwise every point reads
    line 0.  Checks that every profile covers ``x_min`` … ``x_max`` [m].
    """
    profiles = [p for pair in roads for p in pair if p is not None]
    for p in profiles:
        if not (min(x_min, x_max) >= p.x[0] - 1e-9 and max(x_min, x_max) <= p.x[-1] + 1e-9):  # (its range check)
            p.evaluate(np.array([x_min, x_max]))  # its clear message

    def cut_of(p: RoadProfile, a: float, b: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        lo, hi = np.searchsorted(p.x, [a, b], side="right")
        window = slice(max(0, lo - 2), min(p.x.size, hi + 2))
        return p.x[window], p.z[window]

    cuts: dict[int, tuple[NDArray[np.float64], NDArray[np.float64]]] = {}  # per profile (by identity): its stations
    for p in profiles:  # the stations that matter for x_min … x_max (two beyond each end), and its elevations there
        if id(p) not in cuts:
            cuts[id(p)] = cut_of(p, x_min, x_max)
    if cuts:  # profiles of other spacings: each cut over the widest cut's range, so that every lane reads its own
        # profile (not another's stations, nor its own clamped) wherever any lane's stations reach
        a, b = min(x[0] for x, _ in cuts.values()), max(x[-1] for x, _ in cuts.values())
        cuts = {k: cut_of(p, a, b) for p in profiles if (k := id(p)) in cuts}
    cut = list(cuts.values())
    if not profiles:
        stations = np.array([x_min - 1.0, x_max + 1.0])
    elif all(x is cut[0][0] or np.array_equal(x, cut[0][0]) for x, _ in cut):
        stations = np.array(cut[0][0], float)  # own, writeable copy: numba compiles kernels again for read-only arrays
    else:
        stations = np.unique(np.concatenate([x for x, _ in cut]))
    two = any(right is not None for _, right in roads)
    elev = np.zeros((2 if two else 1, stations.size, len(roads)))

    def on_stations(p: RoadProfile) -> NDArray[np.float64]:
        x, z = cuts[id(p)]
        return z if np.array_equal(x, stations) else np.interp(stations, x, z)

    for lane, (left, right) in enumerate(roads):
        if left is not None:
            elev[0, :, lane] = on_stations(left)
        if two:
            elev[1, :, lane] = on_stations(right) if right is not None else elev[0, :, lane]
    return Road(stations, elev, float(elev.max()))


def static_modal_history(crossing: Crossing, travel: NDArray[np.float64],
                         data: KernelData | None = None) -> NDArray[np.float64]:
    """Static modal coordinates ξ_st(t) (n_t, n_modes) under the vehicles' static wheel loads,
    each spread over its contact points by their static shares, at the vehicles' ``travel``
    [m] past their entry supports, (n_t, n_vehicles) ((n_t,): one vehicle) (same tabulated mode
    shapes as the dynamic solution; ``data``: the crossing's kernel data if already computed).
    Several vehicles: every vehicle's static loads along its own path, superposed."""
    cp = crossing.contact
    loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    data = kernel_data(crossing) if data is None else data
    travel = np.asarray(travel, float)
    travel = np.ascontiguousarray(travel.reshape(-1, 1) if travel.ndim == 1 else travel)
    pts, modes = data.points, data.modes
    force = np.zeros((travel.shape[0], data.n_modes))
    kernels.static_modal_history(travel, pts.origin, pts.direction, pts.vehicle, pts.track,
                                 np.ascontiguousarray(loads, float), modes.start, modes.end, float(modes.grid_h),
                                 modes.values, modes.slopes, force, np.zeros(data.n_modes), np.zeros(data.n_modes))
    return -force / crossing.bridge.omega**2
