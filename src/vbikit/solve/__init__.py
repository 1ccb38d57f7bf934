"""Coupled time integration of vehicle and bridge (paper Eq. 9) with registered integrators.

Importing this package does not load the compiled kernels (numba): they load when a crossing
is first integrated (or an explicit integrator's stability limit is computed).
"""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports
from vbikit.solve import builtin_integrators as _builtin_integrators  # noqa: F401  (registers exact, rk4, newmark)

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
    from vbikit.solve.crossing import Crossing, VehicleMotion
    from vbikit.solve.integrators import INTEGRATORS, Integrator, get_integrator, integrator_names, register_integrator
    from vbikit.solve.plan import RunPlan, plan_run
    from vbikit.solve.result import CrossingResult
    from vbikit.solve.simulate import simulate
    from vbikit.solve.timestep import (
        UnstableTimeStepError,
        accuracy_time_step,
        choose_time_step,
        rk4_stability_limit,
    )

__all__ = [
    "INTEGRATORS",
    "Crossing",
    "CrossingResult",
    "Integrator",
    "RunPlan",
    "UnstableTimeStepError",
    "VehicleMotion",
    "accuracy_time_step",
    "choose_time_step",
    "get_integrator",
    "integrator_names",
    "plan_run",
    "register_integrator",
    "rk4_stability_limit",
    "simulate",
]

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.solve.crossing": ["Crossing", "VehicleMotion"],
    "vbikit.solve.integrators": ["INTEGRATORS", "Integrator", "get_integrator", "integrator_names", "register_integrator"],
    "vbikit.solve.plan": ["RunPlan", "plan_run"],
    "vbikit.solve.result": ["CrossingResult"],
    "vbikit.solve.simulate": ["simulate"],
    "vbikit.solve.timestep": ["UnstableTimeStepError", "accuracy_time_step", "choose_time_step", "rk4_stability_limit"],
})
