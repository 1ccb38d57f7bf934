"""Coupled time integration of vehicle and bridge (paper Eq. 9) with registered integrators.

Importing this package does not load the compiled kernels (numba): they load when a crossing
is first integrated (or an explicit integrator's stability limit is computed).
"""
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
