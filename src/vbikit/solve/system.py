"""The coupled system's data for the kernels, and the system at one instant (static start,
stability limit)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit.road.profile import RoadProfile
from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.tabulate import TrackTable, tabulate_tracks


@dataclass(frozen=True)
class KernelData:
    """Argument bundles for ``vbikit.solve.kernels`` (see its docstring)."""

    bridge: tuple
    vehicle: tuple  # with M⁻¹ (RK4) in slot 0
    vehicle_mass: tuple  # with M (Newmark, assembly) in slot 0
    points: tuple
    unilateral: bool
    n_modes: int
    n_dof: int
    n_points: int
    n_wheels: int


def kernel_data(crossing: Crossing, points_per_mode: int = 100) -> KernelData:
    """Tabulate mode shapes along every wheel track and bundle all arrays for the kernels."""
    bridge, vehicle, cp = crossing.bridge, crossing.vehicle, crossing.contact
    tracks, track_idx = np.unique(cp.lateral + crossing.lateral_offset, return_inverse=True)
    table: TrackTable = tabulate_tracks(bridge, tracks, points_per_mode)
    amp = 1.01 * np.abs(table.values).max(axis=(0, 1))  # bound on |φ_m| incl. Hermite overshoot
    b = (bridge.omega, bridge.damping_ratios, float(bridge.span), float(table.spacing), table.values, table.slopes, amp)
    n_d = vehicle.n_dof
    rows = np.array([w.row for w in vehicle.wheels], float).reshape(len(vehicle.wheels), n_d)
    m_inv = np.linalg.inv(vehicle.mass) if n_d else np.zeros((0, 0))
    tail = (vehicle.damping, vehicle.stiffness, vehicle.gravity, rows, cp.wheel_first, cp.wheel_count, cp.wheel_envelope)
    pts = (cp.setback, track_idx.astype(np.int64), cp.stiffness, cp.damping, cp.fixed_load, cp.gap, cp.gated, cp.wheel,
           cp.width, np.ascontiguousarray(cp.slope_range))
    return KernelData(b, (m_inv, *tail), (vehicle.mass, *tail), pts, bool(crossing.loss_of_contact),
                      bridge.omega.size, n_d, cp.n, len(vehicle.wheels))


def coupled_matrices(
    crossing: Crossing,
    data: KernelData,
    front_position: float,
    speed: float,
    road: NDArray[np.float64] | None = None,
    road_rate: NDArray[np.float64] | None = None,
    active: NDArray[np.bool_] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """M, C, K, F of Eq. 9 (u = [ξ; q]) with the front axle at ``front_position`` [m] moving at
    ``speed`` [m/s], the given contact points ``active`` (default: every point in linear contact)."""
    n = data.n_modes + data.n_dof
    zero = np.zeros(data.n_points)
    act = np.ones(data.n_points, bool) if active is None else np.asarray(active, bool)
    mass, damp, stiff = (np.zeros((n, n)) for _ in range(3))
    load = np.zeros(n)
    phi = np.zeros((data.n_points, data.n_modes))
    kernels.assemble(float(speed), float(front_position), zero if road is None else np.asarray(road, float),
                     zero if road_rate is None else np.asarray(road_rate, float), data.bridge, data.vehicle_mass,
                     data.points, phi, np.zeros_like(phi), np.zeros(data.n_points, bool), act, mass, damp, stiff, load)
    return mass, damp, stiff, load


def static_state(crossing: Crossing, data: KernelData, road: NDArray[np.float64],
                 max_iterations: int = 100) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """Static equilibrium (ξ, q) at t = 0 on the road elevations ``road`` under the points, and the
    active contact points.  Contact is piecewise linear, so the active set is iterated: start
    with every point in contact (for a rigid disk, each wheel's highest point), solve, drop
    points that do not press, repeat until the set is unchanged."""
    xf = float(crossing.front_position(0.0))
    n_m, n_p = data.n_modes, data.n_points
    active = np.ones(n_p, bool)
    gap = data.points[5]
    for first, count, env in zip(*data.vehicle[5:8]):
        if env:
            sl = slice(first, first + count)
            active[sl] = False
            active[first + int(np.argmax(road[sl] - gap[sl]))] = True
    cache = (np.zeros((n_p, n_m)), np.zeros((n_p, n_m)), np.zeros(n_p, bool),
             np.ascontiguousarray(road, float).reshape(n_p, 1), np.zeros((n_p, 1)), np.ones(n_p, bool))
    work = (np.zeros(n_p, np.int64), np.zeros((n_p, 1)), np.zeros((n_p, 1), bool), np.zeros(n_p, bool),
            np.zeros((5, 1)), np.zeros((data.n_dof, 1)))
    wf, wl = np.zeros((data.n_wheels, 1)), np.zeros((data.n_wheels, 1))
    # the road values are given (have_r all True): the bundle only carries r_max
    bundle = (np.array([0.0, 1.0]), np.zeros((1, 2, 1)), np.zeros(n_p, np.int64), float(np.max(road, initial=0.0)))
    for _ in range(max_iterations):
        _, _, stiff, load = coupled_matrices(crossing, data, xf, 0.0, road, None, active)
        u = np.linalg.solve(stiff, load)
        kernels.contact_forces(u[:n_m].reshape(n_m, 1).copy(), np.zeros((n_m, 1)), u[n_m:].reshape(-1, 1).copy(),
                               np.zeros((data.n_dof, 1)), 0.0, xf, data.bridge, data.vehicle, data.points, bundle,
                               data.unilateral, cache, work, wf, wl, (0,))
        new_active = work[2][:, 0]
        if np.array_equal(new_active, active):
            return u[:n_m], u[n_m:], active
        active = new_active.copy()
    raise RuntimeError("the static start did not settle on a set of contact points; check the road under the vehicle")


def road_data(roads: Sequence[tuple[RoadProfile | None, RoadProfile | None]], lateral: NDArray[np.float64],
              x_min: float, x_max: float) -> tuple:
    """The kernels' road bundle (stations, elevations (n_lines, n_s, L), line per point, r_max) of
    L lanes with (left, right) wheel-line profiles each (None: smooth; right None: as the left).

    Lanes share one station array: the union of all profiles' stations, on which every profile
    is exactly the same piecewise-linear function (random profiles of one study share their
    stations, so the union is just those).  Points with ``lateral`` < 0 [m] follow the right
    line when any lane has one.  Checks that every profile covers ``x_min`` … ``x_max`` [m].
    """
    profiles = [p for pair in roads for p in pair if p is not None]
    for p in profiles:
        p.evaluate(np.array([x_min, x_max]))  # range check with a clear message

    def window(p: RoadProfile) -> slice:  # the stations that matter for x_min … x_max
        lo, hi = np.searchsorted(p.x, [x_min, x_max], side="right")
        return slice(max(0, lo - 2), min(p.x.size, hi + 2))

    cut = [(p.x[window(p)], p.z[window(p)]) for p in profiles]
    if not profiles:
        stations = np.array([x_min - 1.0, x_max + 1.0])
    elif all(np.array_equal(x, cut[0][0]) for x, _ in cut):
        stations = np.ascontiguousarray(cut[0][0], float)
    else:
        stations = np.unique(np.concatenate([x for x, _ in cut]))
    two = any(right is not None for _, right in roads)
    elev = np.zeros((2 if two else 1, stations.size, len(roads)))

    def on_stations(p: RoadProfile) -> NDArray[np.float64]:
        x, z = p.x[window(p)], p.z[window(p)]
        return z if np.array_equal(x, stations) else np.interp(stations, x, z)

    for lane, (left, right) in enumerate(roads):
        if left is not None:
            elev[0, :, lane] = on_stations(left)
        if two:
            elev[1, :, lane] = on_stations(right) if right is not None else elev[0, :, lane]
    line = ((np.asarray(lateral) < 0.0) & two).astype(np.int64)
    return stations, elev, line, float(elev.max())


def static_modal_history(crossing: Crossing, front_positions: NDArray[np.float64],
                         data: KernelData | None = None) -> NDArray[np.float64]:
    """Static modal coordinates ξ_st(t) (n_t, n_modes) under the vehicle's static wheel loads,
    each spread over its contact points by their static shares, at the given front-axle
    positions [m] (same tabulated mode shapes as the dynamic solution; ``data``: the crossing's
    kernel data if already computed)."""
    cp = crossing.contact
    loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    data = kernel_data(crossing) if data is None else data
    setback, track = data.points[0], data.points[1]
    span, grid_h, values, slopes = data.bridge[2:6]
    force = kernels.static_modal_history(np.ascontiguousarray(front_positions, float), setback, track, loads, span,
                                         grid_h, values, slopes)
    return -force / crossing.bridge.omega**2
