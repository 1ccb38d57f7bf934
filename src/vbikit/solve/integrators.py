"""Time integrators as registered objects: one [`Integrator`][vbikit.solve.Integrator] per name.

Everything that depends on the integrator — the scenario schema's allowed names, the automatic
time step and the stability check, the kernel a batch of lanes runs with, the preflight's
explicit/implicit distinction and the references a report cites — reads [`INTEGRATORS`][vbikit.solve.integrators.INTEGRATORS]
(through [`get_integrator`][vbikit.solve.get_integrator]), never a chain of name comparisons.

Built in (registered by ``vbikit.solve.builtin_integrators``):

* ``"exact"`` — every bridge mode by its exact transition with the modal load linear over the
  step (Nigam & Jennings 1969), the vehicles by the exponential of their augmented system;
* ``"rk4"`` — the paper's classical Runge–Kutta (explicit: its step is capped by the stability
  limit of the coupled system);
* ``"newmark"`` — Newmark average acceleration for bridge and vehicles alike.

A new integrator is one module that builds an [`Integrator`][vbikit.solve.Integrator] and calls
[`register_integrator`][vbikit.solve.register_integrator], plus one import of that module (docs/extending.md).  An implicit
variant only supplies its step maps to ``run_implicit``.

Nothing here imports the compiled kernels until an integrator runs.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from vbikit.solve.integrator_registry import (  # noqa: F401  (the registry's names, importable from here as before)
    DEFAULT_INTEGRATOR,
    INTEGRATORS,
    Integrator,
    get_integrator,
    implicit_names,
    integrator_names,
    register_integrator,
)

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.crossing import Crossing
    from vbikit.solve.kernels import ModalStep, Motion, Road, VehicleStep
    from vbikit.solve.system import KernelData

log = logging.getLogger(__name__)


#: the implicit integrators' end-of-step contact forces hold the contact law to this fraction of the
#: largest static wheel load on every point: the step stops iterating once |law(F) − F| is below it
#: (tight enough that lanes, which iterate until all have converged, equal single crossings to
#: round-off).  The common step reaches it with one contact-law evaluation and exact increments
#: (``vbikit.solve.kernels.implicit``).
IMPLICIT_TOLERANCE = 1e-12
IMPLICIT_MAX_ITERATIONS = 50


@dataclass(frozen=True)
class KernelCall:
    """One kernel call: lanes of crossings that share everything but the road.

    Attributes
    ----------
    crossing : Crossing
        The first lane's crossing (integrator, vehicles, static wheel loads).
    dt : float
        Integration step [s].
    n_steps : int
        Steps of the run.
    motion : vbikit.solve.kernels.Motion
        The vehicles' travel [m] and speed [m/s] on the half-step grid.
    data : vbikit.solve.system.KernelData
        Modes, vehicles and contact points of the system.
    road : vbikit.solve.kernels.Road
        Road lines of every lane.
    outputs : tuple of ndarray
        ``(xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len)``, each (n_lanes, n_stored, ·),
        row 0 holding the static start; the kernel fills the other rows.
    lanes : tuple
        ``(0,)`` for one lane (its own compiled variant), ``(0, 0)`` for several.
    stride : int
        Every ``stride``-th step is stored.
    """

    crossing: "Crossing"
    dt: float
    n_steps: int
    motion: "Motion"
    data: "KernelData"
    road: "Road"
    outputs: tuple
    lanes: tuple
    stride: int


def run_implicit(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep") -> None:
    """Run ``call`` through the partitioned implicit kernel (``vbikit.solve.kernels.implicit``)
    with the step maps ``modal_step`` (every bridge mode over ``call.dt``) and ``vehicle_step``
    (the vehicles over ``call.dt``), iterating the end-of-step contact forces to
    ``IMPLICIT_TOLERANCE`` of the largest static wheel load."""
    from vbikit.solve import kernels

    data, name = call.data, call.crossing.integrator
    loads = np.abs(call.crossing.vehicle.static_wheel_loads())
    tol = IMPLICIT_TOLERANCE * max(float(loads.max(initial=0.0)), 1.0)
    unsettled, evaluations = kernels.implicit(call.dt, call.motion, data.modes, data.vehicles, data.points, call.road,
                                              data.unilateral, modal_step, vehicle_step, *call.outputs, tol,
                                              IMPLICIT_MAX_ITERATIONS, call.lanes, call.stride)
    log.debug("%s: %.2f contact-law evaluations per step", name, evaluations / max(call.n_steps, 1))
    if unsettled:
        log.warning("%s: the contact forces did not converge within %d iterations in %d of %d steps",
                    name, IMPLICIT_MAX_ITERATIONS, unsettled, call.n_steps)


def implicit_kernel() -> Any:
    """The compiled partitioned implicit kernel (for ``Integrator.kernel``)."""
    from vbikit.solve import kernels

    return kernels.implicit
