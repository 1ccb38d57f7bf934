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
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, Iterable, Optional, TypeVar

import numpy as np
from numpy.typing import NDArray

from vbikit.road.profile import RoadProfile
from vbikit.solve import batch_kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.result import CrossingResult
from vbikit.solve.simulate import TimeGrid, integrate, road_along_paths, time_grid
from vbikit.solve.system import kernel_data, static_modal_history
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
        self._grids: dict[float, TimeGrid] = {}
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

    def _grid(self, dt: float) -> TimeGrid:
        if dt not in self._grids:
            self._grids[dt] = time_grid(self.template, dt)
        return self._grids[dt]

    def static_modal(self, dt: float) -> NDArray[np.float64]:
        """ξ_st(t) (n_t, n_modes) under the moving static wheel loads on the time grid of step
        ``dt`` [s] — the same for every road of the batch (computed once per step)."""
        if dt not in self._static:
            self._static[dt] = static_modal_history(self.template, self._grid(dt).xf[::2].copy())
        return self._static[dt]

    # ------------------------------------------------------------------ running
    def run(self, road: RoadProfile | None, road_right: RoadProfile | None = None, nogil: bool = False) -> CrossingResult:
        """One crossing on ``road`` (right wheel line on ``road_right`` if given); equal to
        ``simulate(replace(template, road=road, road_right=road_right))``.
        ``nogil``: integrate through the GIL-free wrappers (for threads; compiled on first use)."""
        crossing = self.crossing(road, road_right)
        grid = self._grid(self.time_step(crossing))
        r, r_rate = road_along_paths(crossing, grid)
        if nogil:
            return integrate(crossing, self.data, grid, r, r_rate, batch_kernels.rk4_nogil, batch_kernels.newmark_nogil)
        return integrate(crossing, self.data, grid, r, r_rate)

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
