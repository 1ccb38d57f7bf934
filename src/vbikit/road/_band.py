"""Compiled loop of the windowed random road (``vbikit.road.psd._window_sum``): the band's
coefficients of Eq. 7 for one window, in one pass over the wavenumbers.

For every wavenumber k of the band, with θ_k the phase, 2π n_k x0 its phase at the period's first
station (``origin``) and first the window's first station,

    y_k = (θ_k + 2π n_k x0) + (2π/N)·(k·first mod N),   c_k = a_k cos y_k + i a_k sin y_k,

the same numbers as numpy's ``a_k · exp(1j · y_k)`` (exp(i y) = cos y + i sin y, both from the C
library's cos and sin; a real times a complex multiplies each part), without the period-long
temporaries.  N is a power of two, so k·first mod N is k·first & (N − 1).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray


def _band_phasors(theta: NDArray[np.float64], origin: NDArray[np.float64], amp: NDArray[np.float64],
                  k: NDArray[np.int64], first: int, mask: int, step: float, out: NDArray[np.complex128]) -> None:
    """Write c_k (module docstring) to ``out[:k.size]``; ``mask`` = N − 1, ``step`` = 2π/N."""
    for j in range(theta.size):
        y = (theta[j] + origin[j]) + step * ((k[j] * first) & mask)
        out[j] = complex(amp[j] * math.cos(y), amp[j] * math.sin(y))


try:
    band_phasors = njit(cache=True, nogil=True)(_band_phasors)
except RuntimeError:  # (numba finds no writable cache location: compiled in each process instead)
    band_phasors = njit(nogil=True)(_band_phasors)
