"""Compiled loops of the decoupled drive-by mode (``vbikit.driveby.decoupled``)."""
from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the @njit(cache=True) below


@njit(cache=True)
def diagonal_recursion(c: NDArray[np.float64], p: NDArray[np.float64], z: NDArray[np.float64]) -> None:
    """z_{k+1, i} = μ_i z_{k, i} + β₀_i p_{k, i} + β₁_i p_{k+1, i} from z_0, i < r: independent
    first-order recursions, the eigen-coordinates of a linear system under inputs linear between
    samples (``decoupled.hold_weights``).  Complex numbers as real and imaginary parts:
    c = (Re μ, Im μ, Re β₀, Im β₀, Re β₁, Im β₁, Re z_0, Im z_0), each r long; p (n_t, 2r) and the
    output columns of z (n_t, ≥ 2r) the real parts then the imaginary parts (so that the products
    before and after are contiguous real matrix products); other columns of z are left alone."""
    r = c.size // 8
    n_t = p.shape[0]
    for i in range(r):
        z[0, i] = c[6 * r + i]
        z[0, r + i] = c[7 * r + i]
    for k in range(n_t - 1):
        for i in range(r):
            mr, mi, ar, ai, br, bi = c[i], c[r + i], c[2 * r + i], c[3 * r + i], c[4 * r + i], c[5 * r + i]
            g_re = ar * p[k, i] - ai * p[k, r + i] + br * p[k + 1, i] - bi * p[k + 1, r + i]
            g_im = ar * p[k, r + i] + ai * p[k, i] + br * p[k + 1, r + i] + bi * p[k + 1, i]
            a, b = z[k, i], z[k, r + i]
            z[k + 1, i] = mr * a - mi * b + g_re
            z[k + 1, r + i] = mr * b + mi * a + g_im
