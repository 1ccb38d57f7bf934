"""A run planned once: its time step, budget estimate, time grid and kernel data.

[`plan_run`][vbikit.solve.plan_run] does every check a run makes before it integrates (the integrator's step rule
and stability limit, the memory and step budgets); [`vbikit.solve.simulate`][vbikit.solve.simulate.simulate] takes the plan
and reuses what it holds, so that a preflight followed by the run computes nothing twice.  The
time grid and the kernel data (mode shapes tabulated along the wheel tracks, the kernels'
argument bundles) are built on first use and kept: planning alone (``vbikit validate``) does
not load the compiled kernels unless an explicit integrator's stability limit needs the
coupled system's matrices.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from vbikit.solve.budget import Limits, RunEstimate, check_run
from vbikit.solve.crossing import Crossing
from vbikit.solve.integrators import Integrator, get_integrator
from vbikit.solve.timestep import choose_time_step

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.system import KernelData


@dataclass(frozen=True)
class TimeGrid:
    """Half-step time grid of a crossing: ``t_half`` [s] (index 2n = t_n, from the crossing's
    start time), the vehicles' ``travel`` [m] and ``speed`` [m/s] there (n_half, n_vehicles)."""

    dt: float
    n_steps: int
    t_half: NDArray[np.float64]
    travel: NDArray[np.float64]
    speed: NDArray[np.float64]

    @property
    def xf(self) -> NDArray[np.float64]:
        """The first vehicle's travel [m]."""
        return self.travel[:, 0]

    @property
    def vel(self) -> NDArray[np.float64]:
        """The first vehicle's speed [m/s]."""
        return self.speed[:, 0]


def time_grid(crossing: Crossing, dt: float) -> TimeGrid:
    """The half-step grid of ``crossing`` for step ``dt`` [s] (it ends at or after ``crossing.duration``;
    kept with the crossing, ``Crossing.kept``: shared, not to be written)."""
    return crossing.kept("grid", float(dt), lambda: _time_grid(crossing, float(dt)))


def _time_grid(crossing: Crossing, dt: float) -> TimeGrid:
    """``time_grid`` made afresh."""
    n_steps = max(1, math.ceil(crossing.duration / dt - 1e-9))
    t_half = crossing.start_time + 0.5 * dt * np.arange(2 * n_steps + 1)
    return TimeGrid(dt, n_steps, t_half, np.ascontiguousarray(crossing.travel(t_half)),
                    np.ascontiguousarray(crossing.travel_speed(t_half)))


@dataclass(frozen=True)
class RunPlan:
    """A checked run of ``crossing``; the time [`grid`][vbikit.solve.RunPlan.grid] and
    [`kernel_data`][vbikit.solve.RunPlan.kernel_data] are built on first use and kept.

    Parameters
    ----------
    crossing : Crossing
        The crossing to integrate.
    integrator : Integrator
        Its integrator.
    dt : float
        The integration step [s].
    estimate : RunEstimate
        The run's memory and step budget estimate.
    """

    crossing: Crossing
    integrator: Integrator
    dt: float
    estimate: RunEstimate

    @property
    def n_steps(self) -> int:
        return self.estimate.n_steps

    @property
    def grid(self) -> TimeGrid:
        """The half-step time grid of the run (kept with the crossing)."""
        return time_grid(self.crossing, self.dt)

    @property
    def kernel_data(self) -> "KernelData":
        """Mode-shape tables along the wheel tracks and the kernels' argument bundles (loads the
        kernels; kept with the crossing)."""
        from vbikit.solve.system import kernel_data

        return kernel_data(self.crossing)


def plan_run(crossing: Crossing, limits: Limits | None = None) -> RunPlan:
    """Choose the step of ``crossing`` and check the run against ``limits`` without integrating.

    An explicit integrator's run is checked at its accuracy step first, before its stability
    limit is computed.

    Parameters
    ----------
    crossing : Crossing
        The crossing to plan.
    limits : Limits, optional
        Memory and step budgets (default ``Limits()``).

    Returns
    -------
    RunPlan
        The checked run, to pass to [`simulate`][vbikit.solve.simulate.simulate] as ``plan``.

    Raises
    ------
    UnstableTimeStepError
        A user step above an explicit integrator's stability limit.
    BudgetError
        A run above the limits.

    The step and the estimate are kept with the crossing per ``limits`` (``Crossing.kept``): a run
    of the same crossing again plans nothing.
    """
    integrator = get_integrator(crossing.integrator)
    limits = Limits() if limits is None else limits
    dt, estimate = crossing.kept("plan", (integrator, limits), lambda: _plan(crossing, integrator, limits))
    return RunPlan(crossing, integrator, dt, estimate)


def _plan(crossing: Crossing, integrator: Integrator, limits: Limits) -> tuple[float, RunEstimate]:
    """The step and estimate of ``plan_run`` made afresh."""
    automatic = None
    if integrator.explicit:
        if crossing.dt is None:
            step = integrator.time_step(crossing)
            automatic = lambda _crossing: step  # noqa: E731 - computed once, reused below
            check_run(crossing, step, limits)
        else:
            check_run(crossing, crossing.dt, limits)
    dt = choose_time_step(crossing, automatic=automatic)
    return dt, check_run(crossing, dt, limits)
