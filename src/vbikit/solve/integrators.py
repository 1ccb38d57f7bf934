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
from typing import TYPE_CHECKING, Any, Callable, Optional

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.crossing import Crossing
    from vbikit.solve.kernels import ModalStep, Motion, Road, VehicleStep
    from vbikit.solve.system import KernelData

log = logging.getLogger(__name__)

#: the integrator a crossing (and a scenario) uses unless told otherwise: exact modal stepping
#: (registered with the other built-in ones in :mod:`vbikit.solve.builtin_integrators`)
DEFAULT_INTEGRATOR = "exact"

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


@dataclass(frozen=True)
class Integrator:
    """A time integrator of the coupled equations.

    Parameters
    ----------
    name : str
        Its name in ``Crossing(integrator=…)`` and scenario files (``crossing.integrator``).
    description : str
        One line for the schema and the docs.
    explicit : bool
        True if its step is limited by stability (then ``stability_limit`` is required).
    references : tuple of str
        Keys of ``vbikit.references.REFERENCES`` that a report using it cites.
    time_step : callable
        ``time_step(crossing) -> float``: the automatic (accuracy) step [s].
    run : callable
        ``run(call: KernelCall) -> None``: integrates the lanes of ``call`` from their static
        start, filling ``call.outputs``.
    stability_limit : callable, optional
        ``stability_limit(crossing) -> float``: the largest stable step [s]; the automatic step
        is capped at 0.9 times it and a larger user step is refused.  Required for an explicit
        integrator; a conditionally stable implicit one may give it too.
    kernel : callable, optional
        ``kernel() -> dispatcher``: the compiled kernel ``run`` calls (to announce its first
        compilation); None if there is none to announce.
    """

    name: str
    description: str
    explicit: bool
    references: tuple[str, ...]
    time_step: Callable[["Crossing"], float]
    run: Callable[[KernelCall], None]
    stability_limit: Optional[Callable[["Crossing"], float]] = None
    kernel: Optional[Callable[[], Any]] = None

    def __post_init__(self) -> None:
        if not self.name or not isinstance(self.name, str):
            raise ValueError(f"an integrator needs a name, got {self.name!r}")
        if self.explicit and self.stability_limit is None:
            raise ValueError(f"integrator {self.name!r}: an explicit integrator needs a stability_limit")


#: every registered integrator by name (registration order)
INTEGRATORS: dict[str, Integrator] = {}


def register_integrator(integrator: Integrator, replace: bool = False) -> Integrator:
    """Add ``integrator`` to [`INTEGRATORS`][vbikit.solve.integrators.INTEGRATORS] under its name and return it.

    Parameters
    ----------
    integrator : Integrator
        The integrator, registered under ``integrator.name``.
    replace : bool
        Allow replacing an integrator of that name with another ``run`` function (refused
        otherwise; the same module executed again re-registers its integrator either way).

    Raises
    ------
    ValueError
        The name is taken by an integrator with another ``run`` function and not ``replace``.
    """
    if not isinstance(integrator, Integrator):
        raise TypeError(f"register_integrator: expected an Integrator, got {type(integrator).__name__}")
    old = INTEGRATORS.get(integrator.name)
    if old is not None and _origin(old.run) != _origin(integrator.run) and not replace:
        raise ValueError(f"an integrator named {integrator.name!r} is registered already")
    INTEGRATORS[integrator.name] = integrator
    return integrator


def _origin(function: Callable) -> tuple[str, str]:
    return getattr(function, "__module__", ""), getattr(function, "__qualname__", repr(function))


def integrator_names() -> tuple[str, ...]:
    """The registered integrator names, in registration order."""
    return tuple(INTEGRATORS)


def get_integrator(name: str) -> Integrator:
    """The integrator registered as ``name`` (ValueError listing the allowed names if none is)."""
    try:
        return INTEGRATORS[name]
    except (KeyError, TypeError):
        raise ValueError(f"crossing.integrator must be one of {integrator_names()}, got {name!r}") from None


def implicit_names() -> tuple[str, ...]:
    """The registered integrators that are not step-limited by stability."""
    return tuple(name for name, integ in INTEGRATORS.items() if not integ.explicit)


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
