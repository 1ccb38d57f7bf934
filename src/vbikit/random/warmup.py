"""Compile the pseudo-excitation kernel in advance (``vbikit compile``), as
``vbikit.solve.warmup`` does for the integrators: one tiny random crossing (the warm-up's sprung
mass on a 3-mode beam, ISO 8608 class A, a handful of lines) compiles — or loads from numba's
cache — ``vbikit.random.kernel``."""
from __future__ import annotations

import logging
import time
from dataclasses import replace

import numpy as np

log = logging.getLogger(__name__)


def compile_random_kernels() -> float:
    """Run one tiny pseudo-excitation analysis; returns the seconds it took."""
    from vbikit.random.lines import band_lines
    from vbikit.random.pem import Probes, PseudoRoad, pseudo_excitation
    from vbikit.road import RoadPSD
    from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR
    from vbikit.solve.warmup import _tiny_crossing

    crossing = replace(_tiny_crossing(DEFAULT_INTEGRATOR), road=None)
    psd = RoadPSD.iso("A")
    t0 = time.perf_counter()
    shapes = np.atleast_2d(crossing.bridge.mode_shapes([2.5], [0.0]))
    pseudo_excitation(crossing, PseudoRoad(psd), Probes(shapes), 2e-3, lines=band_lines(psd.n_min, psd.n_max, ratio=0.5))
    took = time.perf_counter() - t0
    log.info("pseudo-excitation kernel ready (%.1f s)", took)
    return took
