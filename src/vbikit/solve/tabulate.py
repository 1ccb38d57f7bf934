"""Mode shapes tabulated along wheel tracks for the compiled kernels.

For each distinct track y, φ(x, y) and ∂φ/∂x(x, y) are evaluated exactly by the bridge at
``grid_points`` equally spaced stations over the track's own span — from x = y tan θ where the
entry support line crosses it to span + y tan θ (0 … span unless the deck is skew), so that a
skew deck's oblique supports lie on grid points (no kink of φ inside a cell); the kernel interpolates them with
cubic Hermite polynomials, whose error is ≤ (k h)⁴/384 relative for a mode of wavenumber k
and grid spacing h.  The default grid (100 points per retained mode) keeps this below 1e-8
for beam modes; ``tests/unit/test_tabulate.py`` checks it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import Kept, kept_for
from vbikit.bridge.base import ModalBridge


@dataclass(frozen=True)
class TrackTable:
    tracks: NDArray[np.float64]  # y of each track [m]
    start: NDArray[np.float64]  # x of each track's first grid point (its entry support) [m]
    end: NDArray[np.float64]  # x of each track's last grid point (its exit support) [m]
    spacing: float  # grid spacing h [m]
    values: NDArray[np.float64]  # (n_tracks, n_grid, n_modes)
    slopes: NDArray[np.float64]  # (n_tracks, n_grid, n_modes)


#: tracks already tabulated, per bridge (by identity, dropped when the bridge is collected): the
#: events of a traffic stream run on the same few wheel tracks of one bridge (entries (y, points per
#: mode): one track's φ, ∂φ/∂x; ("table", tracks, points per mode): a TrackTable, whose arrays are
#: those of its track when it has one: read only, as every table)
_TRACKS_PER_BRIDGE = 64


def _cache(bridge: ModalBridge) -> Kept:
    """The tables kept for ``bridge``'s mode shapes, by the bridge they come from
    (``ModalBridge.shape_source``: a field calibration's rescaled bridges share their base's; dropped
    when it is collected)."""
    return kept_for(bridge.shape_source, "track tables", _TRACKS_PER_BRIDGE)


def _track(bridge: ModalBridge, y: float, x: NDArray[np.float64], points_per_mode: int):
    """φ and ∂φ/∂x on track y at the stations x (kept per bridge and track)."""
    return _cache(bridge).get((float(y), points_per_mode), lambda: (
        bridge.mode_shapes(x, np.full_like(x, y)), bridge.mode_slopes(x, np.full_like(x, y))))


def tabulate_tracks(bridge: ModalBridge, tracks: NDArray[np.float64], points_per_mode: int = 100) -> TrackTable:
    """Tabulate φ and ∂φ/∂x along each track y in ``tracks`` (each track of a bridge once: the
    tables are kept while the bridge lives; bridges are immutable; so is the table of each set
    of tracks, which the runs of one vehicle class on one bridge share)."""
    tracks = np.asarray(tracks, float)
    return _cache(bridge).get(("table", tracks.tobytes(), points_per_mode),
                              lambda: _tabulate(bridge, tracks, points_per_mode))


def _tabulate(bridge: ModalBridge, tracks: NDArray[np.float64], points_per_mode: int) -> TrackTable:
    n_modes = bridge.omega.size
    n_grid = max(points_per_mode * n_modes, 200) + 1
    grid = np.linspace(0.0, float(bridge.span), n_grid)  # ξ along every track
    start = -bridge.span_coordinate(np.zeros(tracks.size), tracks)  # x of ξ = 0 on each track (0 if square)
    if tracks.size == 1:  # one track (a beam, one lane): its kept φ, ∂φ/∂x as the table, no copy
        x = grid + start[0] if start[0] else grid
        values, slopes = (np.ascontiguousarray(a)[None] for a in _track(bridge, float(tracks[0]), x, points_per_mode))
    else:
        values = np.empty((tracks.size, n_grid, n_modes))
        slopes = np.empty_like(values)
        for k, y in enumerate(tracks):
            x = grid + start[k] if start[k] else grid
            values[k], slopes[k] = _track(bridge, float(y), x, points_per_mode)
    return TrackTable(tracks, np.ascontiguousarray(start + 0.0), start + float(bridge.span),
                      float(bridge.span) / (n_grid - 1), values, slopes)


def hermite_rows(start: NDArray[np.float64], spacing: float, values: NDArray[np.float64], slopes: NDArray[np.float64],
                 track: NDArray[np.int64], x: NDArray[np.float64], with_slopes: bool = True
                 ) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """φ(x) and ∂φ/∂x(x) (None unless ``with_slopes``), each (n, n_modes), of n points at ``x`` [m] on
    the tabulated tracks ``track`` (a table's ``start``, ``spacing``, ``values`` and ``slopes``, as
    ``TrackTable`` and the kernels' ``Modes`` hold them): the cubic Hermite interpolant of the
    tabulated shapes and slopes on the cell of x, clamped to the last cell — the formulas of the
    compiled kernels (``kernels.hermite_shape``), for Python callers, vectorised over the points.  Every point given is evaluated: a caller keeps
    those on the deck (start ≤ x ≤ end of their track)."""
    x = np.asarray(x, float)
    track = np.asarray(track, np.int64)
    n_grid = values.shape[1]
    u = (x - start[track]) / spacing
    i = np.minimum(u.astype(np.int64), n_grid - 2)
    t = u - i
    t2 = t * t
    t3 = t2 * t
    v0, v1, s0, s1 = values[track, i], values[track, i + 1], slopes[track, i], slopes[track, i + 1]
    phi = ((2 * t3 - 3 * t2 + 1)[:, None] * v0 + ((t3 - 2 * t2 + t) * spacing)[:, None] * s0
           + (-2 * t3 + 3 * t2)[:, None] * v1 + ((t3 - t2) * spacing)[:, None] * s1)
    if not with_slopes:
        return phi, None
    dphi = (((6 * t2 - 6 * t) / spacing)[:, None] * v0 + (3 * t2 - 4 * t + 1)[:, None] * s0
            + ((-6 * t2 + 6 * t) / spacing)[:, None] * v1 + (3 * t2 - 2 * t)[:, None] * s1)
    return phi, dphi
