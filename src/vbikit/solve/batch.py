"""Many crossings that differ only in the road: prepare once, run many roads.

Crossings with the same bridge, vehicle, tire, speed profile, approach and integrator share
the time grid, the contact points, the tabulated mode shapes, the kernel argument bundles,
the RK4 stability limit and the static reference.  :class:`BatchSolver` computes those once
from a template crossing and then integrates each road with the same compiled kernels as
:func:`vbikit.solve.simulate`, so every result is identical (bit for bit, same operations in
the same order) to ``simulate(dataclasses.replace(template, road=road))``;
``tests/study/test_batch.py`` checks that.

Roads with a different sample spacing get the time step ``simulate`` would choose for them
(it depends on the road's spacing); that step is cached per spacing.

``run_many(roads, threads=k)`` runs k roads at a time on threads: then the kernels are called
through the ``nogil`` wrappers of :mod:`vbikit.solve.batch_kernels` (compiled on first use);
with one thread they are called directly, exactly as ``simulate`` does.
"""
from __future__ import annotations

import dataclasses
import logging
import math
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, Iterable, Optional, TypeVar

import numpy as np
from numpy.typing import NDArray

from vbikit.road.profile import RoadProfile
from vbikit.solve import batch_kernels, kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.system import kernel_data, static_modal_history, static_state
from vbikit.solve.timestep import accuracy_time_step, rk4_stability_limit

log = logging.getLogger(__name__)
T = TypeVar("T")


class BatchSolver:
    """Shared set-up of crossings that differ only in ``road``.

    Parameters
    ----------
    template : Crossing
        Bridge, vehicle, tire, speed [m/s], acceleration [m/s²], approach [m], free vibration
        [s], lateral offset [m], dt [s] (optional), integrator and contact law of every crossing
        of the batch; its road only serves as the default.
    """

    def __init__(self, template: Crossing) -> None:
        self.template = template
        self.contact = template.contact
        self.data = kernel_data(template)
        self._limit: Optional[float] = None
        self._grids: dict[float, tuple] = {}
        self._static: dict[float, NDArray[np.float64]] = {}

    # ------------------------------------------------------------------ shared data
    def crossing(self, road: RoadProfile | None, road_right: RoadProfile | None = None) -> Crossing:
        """The template with ``road`` (and the right wheel line's ``road_right``; checks coverage)."""
        return dataclasses.replace(self.template, road=road, road_right=road_right)

    def time_step(self, crossing: Crossing) -> float:
        """The step [s] ``simulate`` would choose for ``crossing`` (same rule, cached limit)."""
        if crossing.integrator == "rk4":
            if self._limit is None:
                self._limit = rk4_stability_limit(self.template)
            if crossing.dt is not None:
                if crossing.dt > self._limit:
                    from vbikit.solve.timestep import choose_time_step

                    return choose_time_step(crossing)  # raises the standard UnstableTimeStepError
                return float(crossing.dt)
            return min(accuracy_time_step(crossing), 0.9 * self._limit)
        return float(crossing.dt) if crossing.dt is not None else accuracy_time_step(crossing)

    def _grid(self, dt: float) -> tuple:
        if dt not in self._grids:
            c = self.template
            n_steps = max(1, math.ceil(c.duration / dt - 1e-9))
            t_half = 0.5 * dt * np.arange(2 * n_steps + 1)
            xf = c.front_position(t_half)
            vel = c.velocity(t_half)
            x_cp = xf[:, None] - self.contact.setback[None, :]
            self._grids[dt] = (n_steps, t_half, xf, vel, x_cp)
        return self._grids[dt]

    def static_modal(self, dt: float) -> NDArray[np.float64]:
        """ξ_st(t) (n_t, n_modes) under the moving static wheel loads on the time grid of step
        ``dt`` [s] — the same for every road of the batch (computed once per step)."""
        if dt not in self._static:
            n_steps, t_half, xf, vel, x_cp = self._grid(dt)
            self._static[dt] = static_modal_history(self.template, xf[::2].copy())
        return self._static[dt]

    # ------------------------------------------------------------------ running
    def run(self, road: RoadProfile | None, road_right: RoadProfile | None = None, nogil: bool = False) -> CrossingResult:
        """One crossing on ``road`` (right wheel line on ``road_right`` if given); equal to
        ``simulate(replace(template, road=road, road_right=road_right))``.
        ``nogil``: integrate through the GIL-free wrappers (for threads; compiled on first use)."""
        crossing = self.crossing(road, road_right)
        dt = self.time_step(crossing)
        n_steps, t_half, xf, vel, x_cp = self._grid(dt)
        if road is None:
            r = np.zeros_like(x_cp)
            r_rate = np.zeros_like(x_cp)
        else:
            road.evaluate(np.array([x_cp.min(), x_cp.max()]))
            r = np.empty_like(x_cp)
            r_rate = np.empty_like(x_cp)
            kernels.sample_paths(road.x, road.z, x_cp, vel, r, r_rate)
            right = self.contact.lateral < 0.0
            if road_right is not None and right.any():  # the right wheel line on its own profile (as simulate)
                rl, rlr = np.empty((x_cp.shape[0], int(right.sum()))), np.empty((x_cp.shape[0], int(right.sum())))
                kernels.sample_paths(road_right.x, road_right.z, np.ascontiguousarray(x_cp[:, right]), vel, rl, rlr)
                r[:, right], r_rate[:, right] = rl, rlr
        data = self.data
        n_m, n_d, n_w = data.n_modes, data.n_dof, data.n_wheels
        n_t = n_steps + 1
        xi, dxi, ddxi = (np.zeros((n_t, n_m)) for _ in range(3))
        q, dq, ddq = (np.zeros((n_t, n_d)) for _ in range(3))
        wheel_force = np.zeros((n_t, n_w))
        wheel_len = np.zeros((n_t, n_w))
        xi[0], q[0], active0 = static_state(crossing, data, r[0])
        outputs = (xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len)
        if crossing.integrator == "rk4":
            rk4 = batch_kernels.rk4_nogil if nogil else kernels.rk4
            rk4(dt, xf, vel, r, r_rate, data.bridge, data.vehicle, data.points, data.unilateral, *outputs)
        else:
            newmark = batch_kernels.newmark_nogil if nogil else kernels.newmark
            unsettled = newmark(dt, xf, vel, r, r_rate, data.bridge, data.vehicle_mass, data.points, data.unilateral,
                                *outputs, active0, 50)
            if unsettled:
                log.warning("Newmark: the contact set did not settle within 50 iterations in %d of %d steps",
                            unsettled, n_steps)
        return CrossingResult(crossing, t_half[::2].copy(), dt, xf[::2].copy(), vel[::2].copy(), xi, dxi, ddxi, q,
                              dq, ddq, wheel_force, wheel_len)

    def run_many(self, roads: Iterable, reduce: Callable[[CrossingResult], T] | None = None,
                 threads: int = 1) -> list:
        """Run every road (a RoadProfile, None, or a pair (road, road_right)); ``reduce(result)`` (default: keep the result) is applied as each
        finishes so that only the reduced values are held.  ``threads`` > 1 runs that many
        roads at once (the compiled kernels release the GIL)."""
        roads = list(roads)
        nogil = threads > 1 and len(roads) > 1
        keep = reduce if reduce is not None else (lambda result: result)

        def fn(road):
            left, right = road if isinstance(road, tuple) else (road, None)
            return keep(self.run(left, right, nogil))

        if not nogil:
            return [fn(road) for road in roads]
        if self._limit is None and self.template.integrator == "rk4":
            self._limit = rk4_stability_limit(self.template)
        with ThreadPoolExecutor(max_workers=threads) as pool:
            return list(pool.map(fn, roads))
