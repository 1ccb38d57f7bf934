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
from contextlib import contextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Iterator

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
#: (tol = IMPLICIT_TOLERANCE × max static wheel load, ``run_implicit``).  The common step reaches it
#: with one contact-law evaluation and exact quasi-Newton increments (``vbikit.solve.kernels.lean``,
#: ``vbikit.solve.kernels.implicit``).  1e-10 lets each point force be off its law by 6.8e-6 N on
#: the ``vbikit demo`` crossing (largest wheel load 68 kN), against the 1e-12 used before it:
#: the histories differ from those at 1e-12 by 3e-11 of the peak in the modal displacements, 5e-11
#: in the vehicle's, 3e-10 in the wheel forces and 2e-9 in the accelerations — far below the
#: step's own error (≈ 5e-6 of the peak, benchmarks/README.md) — while the updates fall from 2.24
#: to 1.66 a step and the lean kernel from 7.3 to 6.5 ms (benchmarks/bench_floor.py).  Looser buys
#: little (1e-9: 1.65 updates a step, the same time; 1e-8: 1.57).  At 1e-10 lanes still equal single
#: crossings (1.4e-13 of the peak) and the lean kernel the full one (3e-14); a crossing the full
#: kernel takes over from the lean one differs from a full run by 1.3e-10 (tests/unit/test_lean_kernel.py).
IMPLICIT_TOLERANCE = 1e-10
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


#: run one-lane calls through the lean kernel first (``vbikit.solve.kernels.lean``), the full
#: ``implicit`` kernel only when a step needs it; False: always ``implicit`` (tests compare the two)
USE_LEAN = True

#: one-lane implicit runs so far: ``"lean"`` completed by the lean kernel, ``"fallback"`` rerun with
#: ``implicit`` after the lean kernel stopped at a step it does not take (a contact opening or
#: closing, corrections not settling), ``"implicit"`` sent to ``implicit`` directly (many lanes,
#: rigid disks, ``USE_LEAN`` off)
LEAN_COUNTS: dict[str, int] = {"lean": 0, "fallback": 0, "implicit": 0}


@contextmanager
def without_lean() -> Iterator[None]:
    """Run every implicit crossing with the full ``implicit`` kernel inside the block (``USE_LEAN``
    off): to compile its one-lane variant in advance, or to compare the two kernels."""
    global USE_LEAN
    before, USE_LEAN = USE_LEAN, False
    try:
        yield
    finally:
        USE_LEAN = before


def run_implicit(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep") -> None:
    """Run ``call`` through the partitioned implicit kernel (``vbikit.solve.kernels.implicit``)
    with the step maps ``modal_step`` (every bridge mode over ``call.dt``) and ``vehicle_step``
    (the vehicles over ``call.dt``), iterating the end-of-step contact forces to
    ``IMPLICIT_TOLERANCE`` of the largest static wheel load.

    One lane without rigid disks runs the lean kernel (``vbikit.solve.kernels.lean``: the steps
    that take one contact-law evaluation, the same arithmetic) first; should it stop at a step it
    does not take (a contact opening or closing within the step's updates), ``implicit`` goes on
    from the last state it stored (``LEAN_COUNTS``).  Its start there evaluates the law at that
    state and extrapolates from it alone, so the rest of the run differs from an ``implicit`` run
    from t = 0 by the order of the tolerance (``IMPLICIT_TOLERANCE`` of the largest wheel load)."""
    from vbikit.solve import kernels

    data, name = call.data, call.crossing.integrator
    loads = np.abs(call.crossing.vehicle.static_wheel_loads())
    tol = IMPLICIT_TOLERANCE * max(float(loads.max(initial=0.0)), 1.0)
    motion, outputs, first = call.motion, call.outputs, 0
    if USE_LEAN and len(call.lanes) == 1 and not np.any(data.vehicles.wheel_envelope):
        stop, evaluations = kernels.lean(*_lean_arguments(call, modal_step, vehicle_step), tol, call.stride,
                                         *kernels.lean_work(data.n_modes, data.n_dof, data.n_points, data.n_wheels))
        if stop < 0:
            LEAN_COUNTS["lean"] += 1
            log.debug("%s (lean kernel): %.2f contact-law evaluations per step", name,
                      evaluations / max(call.n_steps, 1))
            return
        LEAN_COUNTS["fallback"] += 1
        # the full kernel starts from the last stored state the lean one reached (row 0 of the views)
        row = stop // call.stride
        first = row * call.stride
        motion = motion._replace(travel=motion.travel[2 * first:], speed=motion.speed[2 * first:])
        outputs = tuple(a[:, row:] for a in outputs)
        log.debug("%s: the lean kernel stops at step %d of %d (a contact opens or closes within the step); the "
                  "full implicit kernel goes on from step %d", name, stop + 1, call.n_steps, first)
    else:
        LEAN_COUNTS["implicit"] += 1
    unsettled, evaluations = kernels.implicit(call.dt, motion, data.modes, data.vehicles, data.points, call.road,
                                              data.unilateral, modal_step, vehicle_step, *outputs, tol,
                                              IMPLICIT_MAX_ITERATIONS, call.lanes, call.stride)
    log.debug("%s: %.2f contact-law evaluations per step", name, evaluations / max(call.n_steps - first, 1))
    if unsettled:
        log.warning("%s: the contact forces did not converge within %d iterations in %d of %d steps",
                    name, IMPLICIT_MAX_ITERATIONS, unsettled, call.n_steps)


def _lean_arguments(call: KernelCall, modal_step: "ModalStep", vehicle_step: "VehicleStep") -> tuple:
    """The lean kernel's arguments (``kernels.lean``) of a one-lane ``call``, up to ``tol`` and
    ``stride`` (its work spaces follow those: ``kernels.lean_work``): the bundles' arrays one by one,
    contiguous, the road of the one lane."""
    from vbikit.solve.system import point_gates

    c = np.ascontiguousarray
    data, road = call.data, call.road
    modes, veh, pts = data.modes, data.vehicles, data.points
    gated = point_gates(data)
    line = np.minimum(pts.line, road.elevations.shape[0] - 1)
    outputs = tuple(a[0] for a in call.outputs)
    return tuple(c(a) if isinstance(a, np.ndarray) else a for a in (
        call.motion.travel, call.motion.speed, modes.start, modes.end, float(modes.grid_h), modes.values,
        modes.slopes, modes.amp, modes.omega, modes.zeta, *modal_step, vehicle_step.transition, vehicle_step.load0,
        vehicle_step.constant, vehicle_step.settle, vehicle_step.response, vehicle_step.wheel_q,
        vehicle_step.wheel_v, vehicle_step.c_hat, vehicle_step.k_hat, veh.mass_inv, veh.gravity, veh.wheel_rows,
        veh.wheel_stiffness, veh.wheel_damping, veh.wheel_first, veh.wheel_count, pts.origin, pts.direction,
        pts.vehicle, pts.track, line, pts.stiffness, pts.damping, pts.fixed_load, pts.gap, gated, pts.wheel,
        pts.width, road.stations, road.elevations[:, :, 0], float(road.r_max), *outputs))


def implicit_kernel() -> Any:
    """The compiled kernel a single implicit crossing runs first (for ``Integrator.kernel``, which
    announces the first compilation): the lean kernel (``run_implicit``)."""
    from vbikit.solve import kernels

    return kernels.lean
