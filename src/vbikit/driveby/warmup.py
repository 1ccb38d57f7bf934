"""Compile the decoupled drive-by solution's kernels in advance (``vbikit compile``), as
``vbikit.solve.warmup`` does for the integrators: the vehicle's exact discrete response
(``vbikit.driveby.decoupled.linear_response``) of a damped oscillator, once through its eigen-
coordinates and once stepped directly, compiles — or loads from numba's cache — both loops of
``vbikit.driveby._decoupled_kernels`` with the argument types a drive-by pass gives them."""
from __future__ import annotations

import logging
import time

import numpy as np

log = logging.getLogger(__name__)


def compile_driveby_kernels() -> float:
    """Run both recursions of ``linear_response`` on a 2-state oscillator over four samples; returns
    the seconds they took."""
    from vbikit.driveby.decoupled import _state_recursion, linear_response

    a = np.array([[0.0, 1.0], [-4.0, -0.4]])
    b = np.array([[0.0], [1.0]])
    u = np.ones((4, 1))
    t0 = time.perf_counter()
    linear_response(a, b, u, 0.01, np.zeros(2), n_rate=1)
    _state_recursion(a, b, u, 0.01, np.zeros(2), 0)
    took = time.perf_counter() - t0
    log.info("drive-by kernels ready (%.1f s)", took)
    return took
