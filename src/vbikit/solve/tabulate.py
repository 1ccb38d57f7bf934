"""Mode shapes tabulated along wheel tracks for the compiled kernels.

For each distinct track y, φ(x, y) and ∂φ/∂x(x, y) are evaluated exactly by the bridge at
``grid_points`` equally spaced stations over the span; the kernel interpolates them with
cubic Hermite polynomials, whose error is ≤ (k h)⁴/384 relative for a mode of wavenumber k
and grid spacing h.  The default grid (100 points per retained mode) keeps this below 1e-8
for beam modes; ``tests/unit/test_tabulate.py`` checks it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vbikit.bridge.base import ModalBridge


@dataclass(frozen=True)
class TrackTable:
    tracks: NDArray[np.float64]  # y of each track [m]
    spacing: float  # grid spacing h [m]
    values: NDArray[np.float64]  # (n_tracks, n_grid, n_modes)
    slopes: NDArray[np.float64]  # (n_tracks, n_grid, n_modes)


def tabulate_tracks(bridge: ModalBridge, tracks: NDArray[np.float64], points_per_mode: int = 100) -> TrackTable:
    """Tabulate φ and ∂φ/∂x along each track y in ``tracks``."""
    n_modes = bridge.omega.size
    n_grid = max(points_per_mode * n_modes, 200) + 1
    x = np.linspace(0.0, bridge.span, n_grid)
    values = np.empty((tracks.size, n_grid, n_modes))
    slopes = np.empty_like(values)
    for k, y in enumerate(tracks):
        values[k] = bridge.mode_shapes(x, np.full_like(x, y))
        slopes[k] = bridge.mode_slopes(x, np.full_like(x, y))
    return TrackTable(np.asarray(tracks, float), bridge.span / (n_grid - 1), values, slopes)
