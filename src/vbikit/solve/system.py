"""The coupled system's data for the kernels, and the system at one instant (static start,
stability limit)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

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
    phi = np.zeros((n_p, n_m)); dphi = np.zeros_like(phi); have = np.zeros(n_p, bool)
    force = np.zeros(n_p); new_active = np.zeros(n_p, bool)
    wf = np.zeros(data.n_wheels); wl = np.zeros(data.n_wheels)
    for _ in range(max_iterations):
        _, _, stiff, load = coupled_matrices(crossing, data, xf, 0.0, road, None, active)
        u = np.linalg.solve(stiff, load)
        kernels.contact_forces(u[:n_m], np.zeros(n_m), u[n_m:], np.zeros(data.n_dof), 0.0, xf, road, np.zeros(n_p),
                               data.bridge, data.vehicle, data.points, data.unilateral, phi, dphi, have, force, wf, wl,
                               new_active)
        if np.array_equal(new_active, active):
            return u[:n_m], u[n_m:], active
        active = new_active.copy()
    raise RuntimeError("the static start did not settle on a set of contact points; check the road under the vehicle")


def static_modal_history(crossing: Crossing, front_positions: NDArray[np.float64]) -> NDArray[np.float64]:
    """Static modal coordinates ξ_st(t) (n_t, n_modes) under the vehicle's static wheel loads,
    each spread over its contact points by their static shares, at the given front-axle
    positions [m] (same tabulated mode shapes as the dynamic solution)."""
    cp = crossing.contact
    loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    data = kernel_data(crossing)
    setback, track = data.points[0], data.points[1]
    span, grid_h, values, slopes = data.bridge[2:6]
    force = kernels.static_modal_history(np.ascontiguousarray(front_positions, float), setback, track, loads, span,
                                         grid_h, values, slopes)
    return -force / crossing.bridge.omega**2
