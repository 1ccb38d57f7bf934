"""Run one crossing: set up the arrays, find the static start, call the compiled integrator."""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import NDArray

from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.system import KernelData, kernel_data, static_state
from vbikit.solve.timestep import choose_time_step

log = logging.getLogger(__name__)


def simulate(crossing: Crossing) -> CrossingResult:
    """Integrate the coupled equations (paper Eq. 9) over the whole crossing."""
    dt = choose_time_step(crossing)
    grid = time_grid(crossing, dt)
    road, road_rate = road_along_paths(crossing, grid)
    return integrate(crossing, kernel_data(crossing), grid, road, road_rate)


@dataclass(frozen=True)
class TimeGrid:
    """Half-step time grid of a crossing: ``t_half`` [s] (index 2n = t_n), front-axle positions
    ``xf`` [m], speeds ``vel`` [m/s] and every contact point's position ``x_cp`` (n_half, n_cp) [m]."""

    dt: float
    n_steps: int
    t_half: NDArray[np.float64]
    xf: NDArray[np.float64]
    vel: NDArray[np.float64]
    x_cp: NDArray[np.float64]


def time_grid(crossing: Crossing, dt: float) -> TimeGrid:
    """The half-step grid of ``crossing`` for step ``dt`` [s] (it ends at or after ``crossing.duration``)."""
    n_steps = max(1, math.ceil(crossing.duration / dt - 1e-9))
    t_half = 0.5 * dt * np.arange(2 * n_steps + 1)
    xf = crossing.front_position(t_half)
    vel = crossing.velocity(t_half)
    return TimeGrid(dt, n_steps, t_half, xf, vel, xf[:, None] - crossing.contact.setback[None, :])


def road_along_paths(crossing: Crossing, grid: TimeGrid) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Road elevation [m] and rate [m/s] under every contact point at every half step; the right
    wheel line (y < 0) follows ``crossing.road_right`` when given."""
    x_cp, vel = grid.x_cp, grid.vel
    if crossing.road is None:
        return np.zeros_like(x_cp), np.zeros_like(x_cp)
    crossing.road.evaluate(np.array([x_cp.min(), x_cp.max()]))  # range check with a clear message
    road = np.empty_like(x_cp)
    road_rate = np.empty_like(x_cp)
    kernels.sample_paths(crossing.road.x, crossing.road.z, x_cp, vel, road, road_rate)
    right = crossing.contact.lateral < 0.0
    if crossing.road_right is not None and right.any():  # the right wheel line on its own profile
        r, rr = np.empty((x_cp.shape[0], int(right.sum()))), np.empty((x_cp.shape[0], int(right.sum())))
        kernels.sample_paths(crossing.road_right.x, crossing.road_right.z, np.ascontiguousarray(x_cp[:, right]), vel,
                             r, rr)
        road[:, right], road_rate[:, right] = r, rr
    return road, road_rate


def integrate(crossing: Crossing, data: KernelData, grid: TimeGrid, road: NDArray[np.float64],
              road_rate: NDArray[np.float64], rk4: Callable = kernels.rk4,
              newmark: Callable = kernels.newmark) -> CrossingResult:
    """Static start and time integration with the crossing's integrator (``rk4``/``newmark``: the
    compiled kernels, or their GIL-free wrappers for threads)."""
    dt, n_steps, xf, vel = grid.dt, grid.n_steps, grid.xf, grid.vel
    n_m, n_d, n_w = data.n_modes, data.n_dof, data.n_wheels
    n_t = n_steps + 1
    xi, dxi, ddxi = (np.zeros((n_t, n_m)) for _ in range(3))
    q, dq, ddq = (np.zeros((n_t, n_d)) for _ in range(3))
    wheel_force = np.zeros((n_t, n_w))
    wheel_len = np.zeros((n_t, n_w))
    xi[0], q[0], active0 = static_state(crossing, data, road[0])

    log.info("crossing: %d steps of %.3g s (%s), %d modes, %d vehicle DOFs, %d contact points",
             n_steps, dt, crossing.integrator, n_m, n_d, data.n_points)
    outputs = (xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len)
    if crossing.integrator == "rk4":
        rk4(dt, xf, vel, road, road_rate, data.bridge, data.vehicle, data.points, data.unilateral, *outputs)
    else:
        unsettled = newmark(dt, xf, vel, road, road_rate, data.bridge, data.vehicle_mass, data.points,
                            data.unilateral, *outputs, active0, 50)
        if unsettled:
            log.warning("Newmark: the contact set did not settle within 50 iterations in %d of %d steps",
                        unsettled, n_steps)
    return CrossingResult(crossing, grid.t_half[::2].copy(), dt, xf[::2].copy(), vel[::2].copy(), xi, dxi, ddxi, q,
                          dq, ddq, wheel_force, wheel_len)
