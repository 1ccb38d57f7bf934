"""Compile the load-effect kernel in advance (``vbikit compile``), as ``vbikit.solve.warmup`` does
for the integrators: one call of ``vbikit.analysis.line_sums.line_sums`` on a tiny table with the
argument types every run passes (contiguous float64 and int64 arrays, two floats) compiles — or
loads from numba's cache — the one variant the load effects of grillage decks and beams use, and
one call of ``vbikit.analysis.state_kernel.run_state_pass`` (the run's state at the one-sided limits
of every load effect and lifetime line) on a one-point, two-step run.
``compile_history_kernels`` does the same for the static modal history of every run's impact factor
(``vbikit.solve.kernels.assembly.static_modal_history``) and the exact static peaks' sweep
(``vbikit.analysis.breakpoints``: lifetime events, railway envelopes), through the public calls
that run them."""
from __future__ import annotations

import logging
import time

import numpy as np

log = logging.getLogger(__name__)


def compile_effect_kernels() -> float:
    """Run ``line_sums`` once on two points, two times and one effect, and ``run_state_pass`` at one
    instant of a two-step, one-point, one-mode run; returns the seconds they took."""
    from vbikit.analysis.line_sums import line_sums
    from vbikit.analysis.state_kernel import run_state_pass

    f8, i8 = np.float64, np.int64
    two = np.zeros(2, f8)
    t0 = time.perf_counter()
    line_sums(np.zeros((2, 1)), two, np.ones(2), two, np.zeros(2, i8), np.zeros(2, i8), np.zeros(2, i8), np.ones(2),
              np.ones(2), np.ones((2, 1)), np.array([0.0, 1.0]), 0.0, 1.0, np.zeros((1, 1, 4)), np.zeros(1, i8),
              np.zeros(1, i8), np.zeros(1, f8), np.ones((1, 1)), np.zeros((1, 2)), np.zeros((1, 2)))
    one, row = np.zeros(1, f8), np.zeros((2, 1))
    run_state_pass(np.array([0.5]), np.array([0.0, 1.0]), one, one, np.ones(1), one, np.full(1, np.inf), one, np.ones(1),
                   one, np.zeros(1, i8), np.zeros(1, i8), np.ones(1), row, row, row.copy(), row.copy(), one, np.ones(1),
                   np.array([0.0, 1.0]), 0.0, one, np.ones(1), 0.5, np.zeros((1, 3, 1)), np.zeros((1, 3, 1)),
                   np.zeros(1, i8), *(np.zeros((1, 1)) for _ in range(6)))
    took = time.perf_counter() - t0
    log.info("load-effect kernel ready (%.1f s)", took)
    return took


def compile_history_kernels() -> float:
    """Run the static modal history of the warm-up's tiny crossing (``vbikit.solve.warmup``; no
    simulation: its integrator kernels are another group's) and the exact extremes of a two-load
    chain over a three-point line; returns the seconds they took."""
    from vbikit.analysis.breakpoints import chain_extremes
    from vbikit.solve.integrator_registry import DEFAULT_INTEGRATOR
    from vbikit.solve.system import static_modal_history
    from vbikit.solve.warmup import _tiny_crossing

    t0 = time.perf_counter()
    static_modal_history(_tiny_crossing(DEFAULT_INTEGRATOR), np.linspace(0.0, 8.0, 5))
    chain_extremes(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 0.5]), np.array([0.0, 1.0, 0.0]),
                   np.array([0.0, 0.5]), np.array([1.0, 1.0]))
    took = time.perf_counter() - t0
    log.info("static-history and exact-peak kernels ready (%.1f s)", took)
    return took
