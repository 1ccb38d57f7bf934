"""Compile the load-effect kernel in advance (``vbikit compile``), as ``vbikit.solve.warmup`` does
for the integrators: one call of ``vbikit.analysis.line_sums.line_sums`` on a tiny table with the
argument types every run passes (contiguous float64 and int64 arrays, two floats) compiles — or
loads from numba's cache — the one variant the load effects of grillage decks and beams use."""
from __future__ import annotations

import logging
import time

import numpy as np

log = logging.getLogger(__name__)


def compile_effect_kernels() -> float:
    """Run ``line_sums`` once on two points, two times and one effect; returns the seconds it took."""
    from vbikit.analysis.line_sums import line_sums

    f8, i8 = np.float64, np.int64
    two = np.zeros(2, f8)
    t0 = time.perf_counter()
    line_sums(np.zeros((2, 1)), two, np.ones(2), two, np.zeros(2, i8), np.zeros(2, i8), np.zeros(2, i8), np.ones(2),
              np.ones(2), np.ones((2, 1)), np.array([0.0, 1.0]), 0.0, 1.0, np.zeros((1, 1, 4)), np.zeros(1, i8),
              np.zeros(1, i8), np.zeros(1, f8), np.ones((1, 1)), np.zeros((1, 2)), np.zeros((1, 2)))
    took = time.perf_counter() - t0
    log.info("load-effect kernel ready (%.1f s)", took)
    return took
