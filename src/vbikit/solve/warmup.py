"""Compile every kernel in advance (``vbikit compile``): for a cluster image, a container or a
shared installation, so that no run, study batch or Dask worker compiles on first use.

numba compiles a kernel once per combination of argument types and keeps it in its on-disk
cache (``vbikit.solve.numba_cache``).  The variants vbikit uses are few: each registered
integrator with one lane and with many lanes (the batched studies and traffic streams; one lane of an
implicit integrator: the lean kernel; many lanes: the many-lane lean kernel; and the full implicit
kernel, whose only variant is the many-lane one, ``kernels.MANY_LANES``: rigid-disk crossings and
batches, and the lean kernels' hand-overs, with a rigid-disk crossing for the general static start),
the static start, the static reference and the moving-load sweep (``vbikit.solve.moving_loads``,
railway speed sweeps).  ``compile_kernels`` runs a tiny crossing through each
of them (a sprung mass on a 3-mode beam over a short rough road), which compiles — or loads from
the cache — exactly those variants; ``kernel_groups`` hands the same work out as groups, for several
processes compiling at once (the test suite's workers).
"""
from __future__ import annotations

import logging
import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np

log = logging.getLogger(__name__)


def _tiny_crossing(integrator: str):
    """A sprung mass on a 3-mode 5 m beam over a short rough road: the smallest crossing that
    runs every compiled path of ``integrator`` (also used by ``vbikit.random.warmup``)."""
    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.road import RoadProfile
    from vbikit.solve.crossing import Crossing
    from vbikit.vehicle import quarter_car

    x = np.linspace(-20.0, 30.0, 51)
    road = RoadProfile(x, 1e-3 * np.sin(x), "warm-up")
    beam = EulerBernoulliBeam(5.0, 1e9, 1e3, 0.02, n_modes=3)
    return Crossing(beam, quarter_car(), road=road, speed=20.0, approach=1.0, integrator=integrator)


def _variants(name: str) -> dict[str, Callable[[], None]]:
    """The crossings that compile (or load) every kernel variant of integrator ``name``, by kind:
    ``one-lane`` (an implicit integrator: the lean kernel), ``rigid-disk`` (an implicit integrator: the
    general static start and the full kernel, the one variant that rigid-disk crossings and batches and
    the lean kernels' hand-overs run) and ``lanes`` (a 2-road batch: an implicit integrator's many-lane
    lean kernel)."""
    from vbikit.contact import RigidDiskTire
    from vbikit.solve.batch import BatchSolver
    from vbikit.solve.integrators import get_integrator
    from vbikit.solve.simulate import simulate

    crossing = _tiny_crossing(name)
    roads = [replace(crossing.road, z=crossing.road.z * k) for k in (1.0, 0.5)]
    variants: dict[str, Callable[[], None]] = {"one-lane": lambda: simulate(crossing)}
    if not get_integrator(name).explicit:
        variants["rigid-disk"] = lambda: simulate(replace(crossing, tire=RigidDiskTire()))
    variants["lanes"] = lambda: BatchSolver(crossing).run_many(roads)
    return variants


def _moving_loads() -> None:
    """The moving-load sweep's compiled peak loop (``vbikit.solve.moving_loads``)."""
    from vbikit.solve.moving_loads import moving_load_sweep

    from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR

    moving_load_sweep(_tiny_crossing(DEFAULT_INTEGRATOR).bridge, [0.0, 2.0], [1e5, 1e5], [20.0, 30.0], [2.5], dx=0.05)


def _static_starts() -> None:
    """The static start's compiled helpers, which the integrators' kernels call too: a crossing's
    start (``simulate._start``) on the flat law (``kernels.lean_law``: the lean kernels' ``_law``) and,
    with rigid disks, on the general law (``kernels.road_at``, ``kernels.contact_forces`` with many
    lanes: RK4's many-lane kernel and the full implicit kernel call them)."""
    from vbikit.contact import RigidDiskTire
    from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR
    from vbikit.solve.integrators import get_integrator
    from vbikit.solve.kernels import Motion
    from vbikit.solve.plan import plan_run
    from vbikit.solve.simulate import _start

    crossing = _tiny_crossing(DEFAULT_INTEGRATOR)
    for c in (crossing, replace(crossing, tire=RigidDiskTire())):
        plan = plan_run(c)
        motion = Motion(plan.grid.travel, plan.grid.speed)
        _start([c], plan.kernel_data, motion, 1, -get_integrator(c.integrator).road_rate_span(plan.grid.dt))


def _run_in() -> None:
    """The run-in's loops (``vbikit.solve.run_in``: traffic streams' and lifetimes' settled start)."""
    from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR
    from vbikit.solve.simulate import simulate

    simulate(replace(_tiny_crossing(DEFAULT_INTEGRATOR), run_in=5.0))


def compile_kernels() -> dict[str, float]:
    """Compile (or load from numba's cache) every kernel variant vbikit runs; returns the seconds
    each integrator took (one lane, then many lanes)."""
    from vbikit.solve.integrators import integrator_names

    took: dict[str, float] = {}
    for name in integrator_names():
        t0 = time.perf_counter()
        for run in _variants(name).values():
            run()
        took[name] = time.perf_counter() - t0
        log.info("kernels of %s ready (%.1f s)", name, took[name])
    t0 = time.perf_counter()
    _run_in()
    took["run-in"] = time.perf_counter() - t0
    log.info("run-in loops ready (%.1f s)", took["run-in"])
    t0 = time.perf_counter()
    _moving_loads()
    took["moving-loads"] = time.perf_counter() - t0
    log.info("moving-load sweep ready (%.1f s)", took["moving-loads"])
    return took


#: the variants of ``_variants`` that compile the same kernels for every implicit integrator (the
#: implicit integrators differ in their step maps, which are arguments, not compiled code, and in the lean
#: kernels' variant the maps choose: "exact" holds the wheel loads quadratic, ``lean_quadratic``), one group
#: each: ``one-lane`` the lean kernel; ``rigid-disk`` the full kernel; ``lanes`` the many-lane lean kernel
IMPLICIT_GROUPS = {"implicit-lean": ("one-lane",), "implicit-full": ("rigid-disk",), "implicit-lanes": ("lanes",)}

#: the group of ``kernel_groups`` whose kernels the integrators' kernels call (``_static_starts``: the
#: contact law with many lanes, the road reading, the lean law): a group compiled after it loads them from
#: numba's cache instead of compiling them again (the test suite's workers run it first)
SHARED_GROUP = "static-starts"


def kernel_groups() -> dict[str, Callable[[], None]]:
    """``compile_kernels``' work as named groups, for compiling them in several processes at once (the
    test suite's workers share them out).  Each explicit integrator is one group (its own kernel, one lane
    and many lanes: apart, its two variants cost as much as together), the implicit ones share
    ``IMPLICIT_GROUPS`` (the run-in's loops go with the default integrator's one-lane variant: the run-in's
    crossing runs it), the moving-load sweep is one more, and ``SHARED_GROUP`` (first) compiles the static
    start's kernels, which the integrators' kernels call too.  numba writes one cache index per kernel,
    and two processes adding different variants of one kernel at the same time could each write that
    index without the other's variant: groups that compile one kernel (a helper two groups call) need
    their index writes locked against each other (the test suite's workers lock them), or to run one
    after the other (``SHARED_GROUP`` before the groups that call its kernels: they then load them from
    the cache)."""
    from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR
    from vbikit.solve.integrators import get_integrator, integrator_names

    groups: dict[str, list[Callable[[], None]]] = {SHARED_GROUP: [_static_starts]}
    for name in integrator_names():
        variants = _variants(name)
        if get_integrator(name).explicit:
            groups[name] = list(variants.values())
            continue
        for group, kinds in IMPLICIT_GROUPS.items():
            groups.setdefault(group, []).extend(variants[k] for k in kinds)
    # the run-in's crossing (``_run_in``) runs the default integrator's one-lane kernel: compiled by that group
    groups[DEFAULT_INTEGRATOR if get_integrator(DEFAULT_INTEGRATOR).explicit else "implicit-lean"].append(_run_in)
    groups["moving-loads"] = [_moving_loads]
    return {group: _run_all(runs) for group, runs in groups.items()}


def _run_all(runs: list[Callable[[], None]]) -> Callable[[], None]:
    """One call running ``runs`` in order."""
    def run() -> None:
        for r in runs:
            r()
    return run
