"""Coupled time integration of vehicle and bridge (paper Eq. 9): RK4 and Newmark."""
from typing import TYPE_CHECKING

from vbikit._lazy import lazy_exports

if TYPE_CHECKING:  # imported on first use (vbikit._lazy); listed here for type checkers and the API reference
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

__getattr__, __dir__ = lazy_exports(globals(), {
    "vbikit.solve.crossing": ["INTEGRATORS", "Crossing", "VehicleMotion"],
    "vbikit.solve.result": ["CrossingResult"],
    "vbikit.solve.simulate": ["simulate"],
    "vbikit.solve.timestep": ["UnstableTimeStepError", "accuracy_time_step", "choose_time_step", "rk4_stability_limit"],
})
