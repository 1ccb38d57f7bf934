"""The coupled system at one instant, for the static start, the stability limit and checks."""
from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.tabulate import TrackTable, tabulate_tracks


def track_table(crossing: Crossing, points_per_mode: int = 100) -> tuple[TrackTable, NDArray[np.int64]]:
    """Mode shapes tabulated along every wheel track of the crossing, and each contact point's track."""
    cp = crossing.contact
    tracks, track_idx = np.unique(cp.lateral + crossing.lateral_offset, return_inverse=True)
    return tabulate_tracks(crossing.bridge, tracks, points_per_mode), track_idx.astype(np.int64)


def coupled_matrices(
    crossing: Crossing,
    table: TrackTable,
    track_idx: NDArray[np.int64],
    front_position: float,
    speed: float,
    road: NDArray[np.float64] | None = None,
    road_rate: NDArray[np.float64] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """M, C, K, F of Eq. 9 (u = [ξ; q]) with the front axle at ``front_position`` [m] moving at ``speed`` [m/s].

    ``road``/``road_rate``: elevation [m] and its rate [m/s] under each contact point (default 0).
    """
    bridge, vehicle, cp = crossing.bridge, crossing.vehicle, crossing.contact
    n_m = bridge.omega.size
    n = n_m + vehicle.n_dof
    phi = np.zeros((cp.n, n_m))
    dphi = np.zeros_like(phi)
    on = np.zeros(cp.n, bool)
    kernels.shapes_at(float(front_position), cp.setback, track_idx, bridge.span, table.spacing, table.values,
                      table.slopes, phi, dphi, on)
    mass, damp, stiff = (np.zeros((n, n)) for _ in range(3))
    load = np.zeros(n)
    zero = np.zeros(cp.n)
    kernels.assemble(float(speed), phi, dphi, on, zero if road is None else np.asarray(road, float),
                     zero if road_rate is None else np.asarray(road_rate, float), bridge.omega,
                     bridge.damping_ratios, vehicle.mass, vehicle.damping, vehicle.stiffness, vehicle.gravity,
                     cp.stiffness, cp.damping, cp.fixed_load, cp.rows, mass, damp, stiff, load)
    return mass, damp, stiff, load


def static_state(crossing: Crossing, table: TrackTable, track_idx: NDArray[np.int64],
                 road: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Static equilibrium (ξ, q) of the coupled system at t = 0 on the road elevations under the points."""
    _, _, stiff, load = coupled_matrices(crossing, table, track_idx, float(crossing.front_position(0.0)), 0.0, road)
    u = np.linalg.solve(stiff, load)
    n_m = crossing.bridge.omega.size
    return u[:n_m], u[n_m:]
