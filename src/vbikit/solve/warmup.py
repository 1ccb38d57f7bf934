"""Compile every kernel in advance (``vbikit compile``): for a cluster image, a container or a
shared installation, so that no run, study batch or Dask worker compiles on first use.

numba compiles a kernel once per combination of argument types and keeps it in its on-disk
cache (``vbikit.solve.numba_cache``).  The variants vbikit uses are few: each registered
integrator with one lane and with many lanes (the batched studies and traffic streams; one lane of an
implicit integrator: the lean kernel and the full one it hands a crossing over to; many lanes of an
implicit integrator: the many-lane lean kernel, and the many-lane full one of rigid-disk batches; a
rigid-disk crossing for the general static start), the static start, the static reference and the moving-load sweep (``vbikit.solve.moving_loads``,
railway speed sweeps).  ``compile_kernels`` runs a tiny crossing through each
of them (a sprung mass on a 3-mode beam over a short rough road), which compiles — or loads from
the cache — exactly those variants.
"""
from __future__ import annotations

import logging
import time
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


def compile_kernels() -> dict[str, float]:
    """Compile (or load from numba's cache) every kernel variant vbikit runs; returns the seconds
    each integrator took (one lane, then many lanes)."""
    from vbikit.contact import RigidDiskTire
    from vbikit.solve.batch import BatchSolver
    from vbikit.solve.integrators import get_integrator, integrator_names, without_lean
    from vbikit.solve.moving_loads import moving_load_sweep
    from vbikit.solve.simulate import simulate

    took: dict[str, float] = {}
    for name in integrator_names():
        crossing = _tiny_crossing(name)
        t0 = time.perf_counter()
        simulate(crossing)
        if not get_integrator(name).explicit:
            with without_lean():  # the full implicit kernel's one-lane variant, which the lean one hands over to
                simulate(crossing)
        if not get_integrator(name).explicit:  # rigid disks: the general static start and the full kernel
            simulate(replace(crossing, tire=RigidDiskTire()))
        roads = [replace(crossing.road, z=crossing.road.z * k) for k in (1.0, 0.5)]
        BatchSolver(crossing).run_many(roads)  # an implicit integrator: the many-lane lean kernel
        if not get_integrator(name).explicit:
            with without_lean():  # the many-lane full kernel (rigid-disk batches, ``without_lean``)
                BatchSolver(crossing).run_many(roads)
        took[name] = time.perf_counter() - t0
        log.info("kernels of %s ready (%.1f s)", name, took[name])
    t0 = time.perf_counter()
    moving_load_sweep(crossing.bridge, [0.0, 2.0], [1e5, 1e5], [20.0, 30.0], [2.5], dx=0.05)
    took["moving-loads"] = time.perf_counter() - t0
    log.info("moving-load sweep ready (%.1f s)", took["moving-loads"])
    return took
