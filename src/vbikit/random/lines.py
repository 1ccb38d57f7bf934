"""Spatial-frequency lines of the pseudo-excitation method: where to put them and their weights.

The road's variance is the integral of its one-sided displacement PSD G_d(n) [m³/cycle] over
the band n_min … n_max [cycle/m].  Every response variance of the linear system is the same
integral weighted by the response's squared transfer function, σ²(t) = ∫ |H(n, t)|² G_d(n) dn,
evaluated by the midpoint rule on cells [a_k, b_k] that tile the band:

    σ²(t) ≈ Σ_k |H(n_k, t)|² G_d(n_k) Δn_k,   n_k = (a_k + b_k)/2,  Δn_k = b_k − a_k.

The cells grow geometrically (width ρ·n, resolving the steep low-wavenumber end of a power-law
PSD) up to a largest width Δn_max, then stay uniform (resolving the oscillation of |H|² with n
caused by axle spacing and by a finite crossing: period 1/(v T) for a memory T), and above
n = Δn_max/τ grow again as τ·n: there the response is the higher modes', whose memory is short
(T ∝ 1/(ζω)), and the power-law PSD, the tire's wavelength filter and the modes' damping make
the integrand small and smooth (on the demo crossing the lines above 1.5 cycle/m carry < 0.2 % of
every variance's grid change).  The method's own check compares the rule on every line with the
rule on every second line (twice the width, ``coarse_weights``): an estimate of the coarser
grid's error, so an upper bound for the grid's.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class Lines:
    """Midpoint-rule lines: wavenumbers ``n`` [cycle/m] and cell widths ``width`` Δn [cycle/m]."""

    n: NDArray[np.float64]
    width: NDArray[np.float64]

    @property
    def size(self) -> int:
        return int(self.n.size)

    def coarse_weights(self) -> NDArray[np.float64]:
        """Per line, the factor that turns the fine rule into the rule on every second line with
        merged cells: (Δn_k + Δn_{k+1})/Δn_k on even k, 0 on odd k (a last unpaired line keeps 1)."""
        w = np.zeros(self.size)
        k = np.arange(0, self.size - 1, 2)
        w[k] = (self.width[k] + self.width[k + 1]) / self.width[k]
        if self.size % 2:
            w[-1] = 1.0
        return w


#: the default grid's cell rule (``band_lines``' ratio, max_width [cycle/m] and tail)
DEFAULT_GRID = (0.1, 0.01, 0.01)


def default_lines(n_min: float, n_max: float, refinement: int = 0) -> Lines:
    """The default grid (``DEFAULT_GRID``) over the band ``n_min`` … ``n_max`` [cycle/m], each cell's
    width halved ``refinement`` times (about 2^refinement times the lines: 254, 506, 1,009 over ISO 8608's
    band), as a random run refines it while its own grid check is above the limit
    (``vbikit.random.response.GRID_REFINEMENTS``)."""
    if int(refinement) != refinement or refinement < 0:
        raise ValueError(f"refinement must be an integer >= 0, got {refinement!r}")
    ratio, max_width, tail = (v / 2 ** int(refinement) for v in DEFAULT_GRID)
    return band_lines(n_min, n_max, ratio, max_width, tail)


def band_lines(n_min: float, n_max: float, ratio: float = DEFAULT_GRID[0], max_width: float = DEFAULT_GRID[1],
               tail: float = DEFAULT_GRID[2]) -> Lines:
    """Cells tiling the band ``n_min`` … ``n_max`` [cycle/m]: widths min(``ratio``·a, max(``max_width``,
    ``tail``·a)) [cycle/m], a the cell's lower edge (geometric, capped, geometric again above
    max_width/tail; ``tail`` = 0: uniform up to n_max), the last cell cut at n_max.

    The defaults (0.1, 0.01 cycle/m, 0.01: 254 lines over ISO 8608's 0.01 … 4 cycle/m) give the demo
    crossing's σ histories within 0.01 % of the peak of a grid 7 × finer (1,762 lines: ratio 0.0125,
    max_width 0.0025, tail 0) on the deck outputs and wheel forces, 0.09 % on the vehicle
    displacements (``benchmarks/bench_random.py``; tests/random_vibration/test_pem_paths.py)."""
    if not 0 < n_min < n_max:
        raise ValueError(f"need 0 < n_min < n_max (cycle/m), got {n_min!r}, {n_max!r}")
    if not 0 < ratio <= 1 or not max_width > 0 or not 0 <= tail <= ratio:
        raise ValueError(f"lines: ratio must be in (0, 1], max_width > 0 and tail in [0, ratio], got {ratio!r}, "
                         f"{max_width!r}, {tail!r}")
    edges = [float(n_min)]
    while edges[-1] < n_max * (1 - 1e-12):
        a = edges[-1]
        edges.append(min(a + min(ratio * a, max(max_width, tail * a)), float(n_max)))
    e = np.asarray(edges)
    return Lines(0.5 * (e[1:] + e[:-1]), np.diff(e))
