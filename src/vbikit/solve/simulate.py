"""Run one crossing: set up the arrays, find the static start, call the compiled integrator."""
from __future__ import annotations

import logging
import math

import numpy as np

from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.system import static_state, track_table
from vbikit.solve.timestep import choose_time_step

log = logging.getLogger(__name__)


def simulate(crossing: Crossing) -> CrossingResult:
    """Integrate the coupled equations (paper Eq. 9) over the whole crossing."""
    bridge, vehicle = crossing.bridge, crossing.vehicle
    cp = crossing.contact
    dt = choose_time_step(crossing)
    n_steps = max(1, math.ceil(crossing.duration / dt - 1e-9))
    t_half = 0.5 * dt * np.arange(2 * n_steps + 1)
    xf = crossing.front_position(t_half)
    vel = crossing.velocity(t_half)
    x_cp = xf[:, None] - cp.setback[None, :]
    if crossing.road is None:
        road = np.zeros_like(x_cp)
        road_rate = np.zeros_like(x_cp)
    else:
        crossing.road.evaluate(np.array([x_cp.min(), x_cp.max()]))  # range check with a clear message
        road = np.empty_like(x_cp)
        road_rate = np.empty_like(x_cp)
        kernels.sample_paths(crossing.road.x, crossing.road.z, x_cp, vel, road, road_rate)
        right = cp.lateral < 0.0
        if crossing.road_right is not None and right.any():  # the right wheel line on its own profile
            r, rr = np.empty((x_cp.shape[0], int(right.sum()))), np.empty((x_cp.shape[0], int(right.sum())))
            kernels.sample_paths(crossing.road_right.x, crossing.road_right.z, np.ascontiguousarray(x_cp[:, right]), vel, r, rr)
            road[:, right], road_rate[:, right] = r, rr
    table, track_idx = track_table(crossing)

    n_m, n_d = bridge.omega.size, vehicle.n_dof
    n_t = n_steps + 1
    xi, dxi, ddxi = (np.zeros((n_t, n_m)) for _ in range(3))
    q, dq, ddq = (np.zeros((n_t, n_d)) for _ in range(3))
    force = np.zeros((n_t, cp.n))
    xi[0], q[0] = static_state(crossing, table, track_idx, road[0])

    log.info("crossing: %d steps of %.3g s (%s), %d modes, %d vehicle DOFs, %d contact points",
             n_steps, dt, crossing.integrator, n_m, n_d, cp.n)
    common = (bridge.omega, bridge.damping_ratios)
    veh = (vehicle.damping, vehicle.stiffness, vehicle.gravity)
    wheel_rows = np.array([w.row for w in vehicle.wheels], float).reshape(len(vehicle.wheels), n_d)
    tail = (cp.setback, track_idx, cp.stiffness, cp.damping, cp.fixed_load, cp.wheel, wheel_rows, bridge.span, table.spacing,
            table.values, table.slopes, xi, dxi, q, dq, ddxi, ddq, force)
    if crossing.integrator == "rk4":
        m_inv = np.linalg.inv(vehicle.mass) if n_d else np.zeros((0, 0))
        kernels.rk4(dt, xf, vel, road, road_rate, *common, m_inv, *veh, *tail)
    else:
        kernels.newmark(dt, xf, vel, road, road_rate, *common, vehicle.mass, *veh, *tail)
    return CrossingResult(crossing, t_half[::2].copy(), dt, xf[::2].copy(), vel[::2].copy(), xi, dxi, ddxi, q, dq,
                          ddq, force)
