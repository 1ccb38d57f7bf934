"""Run one crossing: set up the arrays, find the static start, call the compiled integrator."""
from __future__ import annotations

import logging
import math

import numpy as np

from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.system import kernel_data, static_state
from vbikit.solve.timestep import choose_time_step

log = logging.getLogger(__name__)


def simulate(crossing: Crossing) -> CrossingResult:
    """Integrate the coupled equations (paper Eq. 9) over the whole crossing."""
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
    data = kernel_data(crossing)
    n_m, n_d, n_w = data.n_modes, data.n_dof, data.n_wheels
    n_t = n_steps + 1
    xi, dxi, ddxi = (np.zeros((n_t, n_m)) for _ in range(3))
    q, dq, ddq = (np.zeros((n_t, n_d)) for _ in range(3))
    wheel_force = np.zeros((n_t, n_w))
    wheel_len = np.zeros((n_t, n_w))
    xi[0], q[0], active0 = static_state(crossing, data, road[0])

    log.info("crossing: %d steps of %.3g s (%s), %d modes, %d vehicle DOFs, %d contact points",
             n_steps, dt, crossing.integrator, n_m, n_d, cp.n)
    outputs = (xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len)
    if crossing.integrator == "rk4":
        kernels.rk4(dt, xf, vel, road, road_rate, data.bridge, data.vehicle, data.points, data.unilateral, *outputs)
    else:
        unsettled = kernels.newmark(dt, xf, vel, road, road_rate, data.bridge, data.vehicle_mass, data.points,
                                    data.unilateral, *outputs, active0, 50)
        if unsettled:
            log.warning("Newmark: the contact set did not settle within 50 iterations in %d of %d steps",
                        unsettled, n_steps)
    return CrossingResult(crossing, t_half[::2].copy(), dt, xf[::2].copy(), vel[::2].copy(), xi, dxi, ddxi, q, dq,
                          ddq, wheel_force, wheel_len)
