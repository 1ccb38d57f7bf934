"""Coupled time integration of vehicle and bridge (paper Eq. 9): RK4 and Newmark."""
from vbikit.solve.crossing import INTEGRATORS, Crossing, VehicleMotion
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
    "UnstableTimeStepError",
    "VehicleMotion",
    "accuracy_time_step",
    "choose_time_step",
    "rk4_stability_limit",
    "simulate",
]
