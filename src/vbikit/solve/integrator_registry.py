"""The registry of time integrators: [`Integrator`][vbikit.solve.Integrator] and the names they are
registered under ([`INTEGRATORS`][vbikit.solve.integrators.INTEGRATORS]).

Kept apart from ``vbikit.solve.integrators`` (kernel calls) so that the crossing, which checks
its integrator's name here, and the kernel calls, which take a crossing, import no circle.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Optional

# The annotations name ``Crossing`` (vbikit.solve.crossing) and ``KernelCall``
# (vbikit.solve.integrators) without importing them: both modules import this one.

#: the integrator a crossing (and a scenario) uses unless told otherwise: exact modal stepping
#: (registered with the other built-in ones in :mod:`vbikit.solve.builtin_integrators`)
DEFAULT_INTEGRATOR = "exact"


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
        start, filling ``call.outputs`` (a run that leaves the vehicles' accelerations q̈ out says so
        in ``call.deferred``; ``run_implicit`` does).
    stability_limit : callable, optional
        ``stability_limit(crossing) -> float``: the largest stable step [s]; the automatic step
        is capped at 0.9 times it and a larger user step is refused.  Required for an explicit
        integrator; a conditionally stable implicit one may give it too.
    kernel : callable, optional
        ``kernel() -> dispatcher``: the compiled kernel ``run`` calls (to announce its first
        compilation); None if there is none to announce.
    lanes_kernel : callable, optional
        ``lanes_kernel() -> dispatcher``: the compiled kernel ``run`` calls with many lanes (a study's
        batches; announced by ``vbikit.study.run``); None: ``kernel``'s.
    secant_road_rate : bool
        True if it evaluates the contact law at step ends and integrates the tire dashpots' load as
        linear over the step (the implicit ones): the road rate under a point is then the secant over
        the half steps around the step end (``road_rate_span`` = dt/2; ``vbikit.solve.kernels``, "the
        road rate").  False: the slope of the point's road cell (an integrator that evaluates the
        law at its stages, as RK4).
    """

    name: str
    description: str
    explicit: bool
    references: tuple[str, ...]
    time_step: Callable[["Crossing"], float]
    run: Callable[["KernelCall"], None]
    stability_limit: Optional[Callable[["Crossing"], float]] = None
    kernel: Optional[Callable[[], Any]] = None
    lanes_kernel: Optional[Callable[[], Any]] = None
    secant_road_rate: bool = False

    def road_rate_span(self, dt: float) -> float:
        """The kernels' road-rate ``span`` [s] at step ``dt`` [s] (``vbikit.solve.kernels.road_point``): dt/2
        with the secant road rate, 0 (the road cell's slope) without."""
        return 0.5 * float(dt) if self.secant_road_rate else 0.0

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
