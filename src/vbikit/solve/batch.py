"""Many crossings that differ only in the road: prepare once, run many roads together.

Crossings with the same bridge, vehicle, tire, speed profile, approach and integrator share
the time grid, the contact points, the tabulated mode shapes, the kernel argument bundles,
the RK4 stability limit and the static reference.  ``BatchSolver`` computes those once
from a template crossing and integrates the roads as *lanes* of one call of the same compiled
kernel that [`vbikit.solve.simulate`][vbikit.solve.simulate.simulate] calls with one lane (any integrator): the mode shapes at the
contact points are evaluated once per step for all lanes and the per-lane arithmetic is
vectorised.  Each lane's arithmetic is that of its own crossing, so every result equals
``simulate(dataclasses.replace(template, road=road))`` to round-off (``tests/study/test_batch.py``).

Roads with a different sample spacing get the time step ``simulate`` would choose for them
(it depends on the road's spacing); such roads run in their own group of lanes.

``run_many(roads, threads=k)`` splits the lanes into k calls running at once on threads (the
kernels release the GIL).
"""
from __future__ import annotations

import logging
from concurrent.futures import ThreadPoolExecutor
from importlib import import_module
from typing import Callable, Iterable, Optional, Sequence, TypeVar

import numpy as np
from numpy.typing import NDArray

from vbikit.road.profile import RoadProfile
from vbikit.solve.crossing import Crossing
from vbikit.solve.integrators import get_integrator
from vbikit.solve.plan import TimeGrid, time_grid
from vbikit.solve.result import CrossingResult
from vbikit.solve.simulate import MAX_LANES, integrate
from vbikit.solve.system import kernel_data, static_modal_history
from vbikit.solve.timestep import choose_time_step, road_step_key

log = logging.getLogger(__name__)
T = TypeVar("T")


def lane_chunks(steps: Sequence[float], threads: int = 1, lanes: int = MAX_LANES) -> list[tuple[float, list[int]]]:
    """How ``BatchSolver.run_many`` splits crossings with time steps ``steps`` [s] into kernel calls: the
    crossings of one step together (in order), each group cut into ``threads`` calls of at most ``lanes``
    crossings — (step, indices of its crossings) per call.  A call of one crossing runs the integrator's
    one-lane kernel, a call of several its many-lane kernel (``vbikit.solve.simulate.integrate``): a
    batch no larger than ``threads``, or whose crossings all have different steps, never runs the
    many-lane kernel (``vbikit.study.run.batch_kernels`` names the kernels by this split)."""
    groups: dict[float, list[int]] = {}
    for k, dt in enumerate(steps):
        groups.setdefault(dt, []).append(k)
    chunks = []
    for dt, members in groups.items():
        size = max(1, min(lanes, -(-len(members) // max(1, threads))))
        chunks += [(dt, members[i:i + size]) for i in range(0, len(members), size)]
    return chunks


def _settled(result: CrossingResult) -> CrossingResult:
    """A lane whose contact forces did not converge in some steps (the lanes settle together: a step
    any lane needs more for counts for all) run again alone by ``simulate``, which runs it at half
    its step where its own steps do not settle (``simulate.UNCONVERGED_HALVINGS``); else ``result``."""
    if not result.unconverged_steps:
        return result
    run = import_module("vbikit.solve.simulate")  # (the module, whose name the package's function shadows)
    if run.UNCONVERGED_HALVINGS <= 0:
        return result
    log.info("a lane of a batch left %d steps unconverged: run again alone", result.unconverged_steps)
    return run.simulate(result.crossing)


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
        self._accuracy: dict[tuple, float] = {}

    # ------------------------------------------------------------------ shared data
    def crossing(self, road: RoadProfile | None, road_right: RoadProfile | None = None) -> Crossing:
        """The template with ``road`` (and the right wheel line's ``road_right``; checks coverage)."""
        return self.template.with_road(road, road_right)

    def time_step(self, crossing: Crossing) -> float:
        """The step [s] ``simulate`` would choose for ``crossing`` (same rule; the stability limit
        of an explicit integrator computed once for the template)."""
        integrator = get_integrator(crossing.integrator)
        if integrator.stability_limit is not None and self._limit is None:
            self._limit = integrator.stability_limit(self.template)
        return choose_time_step(crossing, stability_limit=self._limit, automatic=self._accuracy_step)

    def _accuracy_step(self, crossing: Crossing) -> float:
        # within a batch the automatic step depends only on what the rules read of the roads
        key = tuple(road_step_key(r) for r in (crossing.road, crossing.road_right))
        if key not in self._accuracy:
            self._accuracy[key] = get_integrator(crossing.integrator).time_step(crossing)
        return self._accuracy[key]

    def _grid(self, dt: float) -> TimeGrid:
        if dt not in self._grids:
            self._grids[dt] = time_grid(self.template, dt)
        return self._grids[dt]

    def static_modal(self, dt: float) -> NDArray[np.float64]:
        """ξ_st(t) (n_t, n_modes) under the moving static wheel loads on the time grid of step
        ``dt`` [s] — the same for every road of the batch (computed once per step)."""
        if dt not in self._static:
            self._static[dt] = static_modal_history(self.template, self._grid(dt).travel[::2].copy(), self.data)
        return self._static[dt]

    # ------------------------------------------------------------------ running
    def run(self, road: RoadProfile | None, road_right: RoadProfile | None = None) -> CrossingResult:
        """One crossing on ``road`` (right wheel line on ``road_right`` if given); equal to
        ``simulate(replace(template, road=road, road_right=road_right))``."""
        return self.run_many([(road, road_right)])[0]

    def run_many(self, roads: Iterable, reduce: Callable[[CrossingResult], T] | None = None,
                 threads: int = 1, lanes: int = MAX_LANES) -> list:
        """Run every road (a RoadProfile, None, or a pair (road, road_right)); ``reduce(result)``
        (default: keep the result) is applied as each group of lanes finishes so that only the
        reduced values are held.  At most ``lanes`` roads per kernel call; ``threads`` > 1 runs
        that many calls at once."""
        pairs = [road if isinstance(road, tuple) else (road, None) for road in roads]
        crossings = [self.crossing(left, right) for left, right in pairs]
        keep = reduce if reduce is not None else (lambda result: result)
        chunks = lane_chunks([self.time_step(crossing) for crossing in crossings], threads, lanes)

        def fn(chunk):
            dt, members = chunk
            results = integrate([crossings[k] for k in members], self.data, self._grid(dt))
            return [keep(_settled(result)) for result in results]

        out: list = [None] * len(crossings)
        if threads > 1 and len(chunks) > 1:
            with ThreadPoolExecutor(max_workers=threads) as pool:
                done = list(pool.map(fn, chunks))
        else:
            done = [fn(chunk) for chunk in chunks]
        for (_, members), values in zip(chunks, done):
            for k, value in zip(members, values):
                out[k] = value
        return out
