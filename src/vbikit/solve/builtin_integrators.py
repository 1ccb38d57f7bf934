"""The integrators vbikit ships: ``"exact"`` (the default), ``"rk4"`` and ``"newmark"``
(``vbikit.solve.integrators``).  An integrator module added to the package is imported at the
end of this file."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from vbikit.solve.integrators import (
    DEFAULT_INTEGRATOR,
    INTEGRATORS,
    Integrator,
    KernelCall,
    implicit_kernel,
    implicit_lanes_kernel,
    register_integrator,
    run_implicit,
)
from vbikit.solve.timestep import accuracy_time_step, implicit_time_step, rk4_stability_limit

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.crossing import Crossing


#: True (the default): the exact integrator holds the wheel loads quadratic over the lean kernels' steps
#: (``modal_step.QUADRATIC``, third order, as the deck's modal loads), a step in which a wheel lands or lifts
#: off solved a second time with the linear hold's loads (``kernels.lean``), and linear over the full kernel's
#: (``modal_step.LINEAR``: the contact events the lean kernels hand over, the rest of a run after
#: ``integrators.LEAN_RESUMES`` of them, rigid-disk runs).  False: linear on every step (second order).
#: Where wheels keep the road it halves the step's error (tests/unit/test_wheel_load_hold.py); it keeps class D
#: within the automatic step's 5e-4 at the coarser first-period rule of deflection runs
#: (``timestep.EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD``; the lean kernels' variants ``lean_quadratic``,
#: ``lean_lanes_quadratic``; benchmarks/README.md, ``bench_period_rule.py``)
QUADRATIC_WHEEL_LOADS = True


def _run_exact(call: KernelCall) -> None:
    from vbikit.solve.modal_step import LINEAR, QUADRATIC, exact_step, vehicle_step

    data = call.data
    lean = vehicle_step(data.vehicles, call.dt, QUADRATIC if QUADRATIC_WHEEL_LOADS else LINEAR)
    run_implicit(call, exact_step(data.modes.omega, data.modes.zeta, call.dt, QUADRATIC), lean,
                 vehicle_step(data.vehicles, call.dt, LINEAR))


def _exact_time_step(crossing: Crossing) -> float:
    """``implicit_time_step`` with the hold this integrator runs ``crossing`` with: the wheel loads quadratic on the
    lean kernels' steps (``QUADRATIC_WHEEL_LOADS``), linear for rigid disks (the full kernel, ``run_implicit``)."""
    rigid = bool(np.any(crossing.contact.wheel_envelope))
    return implicit_time_step(crossing, quadratic_wheel_loads=QUADRATIC_WHEEL_LOADS and not rigid)


def _exact_kernel() -> Any:
    return implicit_kernel(QUADRATIC_WHEEL_LOADS)


def _exact_lanes_kernel() -> Any:
    return implicit_lanes_kernel(QUADRATIC_WHEEL_LOADS)


def _run_newmark(call: KernelCall) -> None:
    from vbikit.solve.modal_step import newmark_step, newmark_vehicle_step

    data = call.data
    run_implicit(call, newmark_step(data.modes.omega, data.modes.zeta, call.dt),
                 newmark_vehicle_step(data.vehicles, call.dt))


def _run_rk4(call: KernelCall) -> None:
    from vbikit.solve import kernels

    data = call.data
    kernels.rk4(call.dt, call.motion, data.modes, data.vehicles, data.points, call.road, data.unilateral, *call.outputs,
                call.lanes, call.stride)


def _rk4_kernel() -> Any:
    from vbikit.solve import kernels

    return kernels.rk4


EXACT = register_integrator(Integrator(
    name="exact",
    description="exact modal stepping (default; the step is not limited by the highest mode)",
    explicit=False,
    references=("NigamJennings1969", "Chopra2017"),
    time_step=_exact_time_step,
    run=_run_exact,
    kernel=_exact_kernel,
    lanes_kernel=_exact_lanes_kernel,
    secant_road_rate=True,
))
RK4 = register_integrator(Integrator(
    name="rk4",
    description="the paper's classical Runge–Kutta (explicit: the step is capped by its stability limit)",
    explicit=True,
    references=("MultiPointTire",),
    time_step=accuracy_time_step,
    run=_run_rk4,
    stability_limit=rk4_stability_limit,
    kernel=_rk4_kernel,
    lanes_kernel=_rk4_kernel,
))
NEWMARK = register_integrator(Integrator(
    name="newmark",
    description="Newmark average acceleration for bridge and vehicles alike",
    explicit=False,
    references=("Newmark1959",),
    time_step=accuracy_time_step,
    run=_run_newmark,
    kernel=implicit_kernel,
    lanes_kernel=implicit_lanes_kernel,
    secant_road_rate=True,
))

if DEFAULT_INTEGRATOR not in INTEGRATORS:  # pragma: no cover - a programming error
    raise RuntimeError(f"the default integrator {DEFAULT_INTEGRATOR!r} is not one of the built-in ones")
