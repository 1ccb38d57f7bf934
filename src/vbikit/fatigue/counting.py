"""Rainflow counting of a whole stress history (ASTM E1049-85, 5.4.4) with the ``rainflow`` package.

``rainflow(series)`` gives the (range, count) pairs of the standard: full cycles count 1, half
cycles 0.5, ranges exactly as they occur in the history (differences of two of its values, no
binning), sorted by range.  The counting itself is the ``rainflow`` package (Piotr Janiszewski,
PyPI ``rainflow`` 3.2.0), which implements the three-point algorithm of ASTM E1049-85 §5.4.4.
"""
from __future__ import annotations

from typing import Any

import numpy as np
import rainflow as _rainflow

from vbikit.fatigue._checks import series_1d


def rainflow(series: Any) -> list[tuple[float, float]]:
    """Rainflow cycles of a stress (or any load-effect) history, ASTM E1049-85 §5.4.4.

    Parameters
    ----------
    series : array_like
        The history, 1-D, finite values (any unit; ranges come out in the same unit).

    Returns
    -------
    list of (float, float)
        (range, count) pairs sorted by range; full cycles count 1.0, half cycles 0.5, equal
        ranges summed.  A history with fewer than two distinct values has no cycles (``[]``); a
        two-point history is one half cycle.

    Raises
    ------
    FatigueError
        The series is not 1-D or holds a non-finite value.

    Notes
    -----
    The worked example of ASTM E1049-85 §5.4.4 (rainflow counting), the reversals
    −2, 1, −3, 5, −1, 3, −4, 4, −2, gives (3, 0.5), (4, 1.5), (6, 0.5), (8, 1.0), (9, 0.5).
    First and last points of the history are treated as reversals.
    """
    arr = series_1d(series, "series")
    if arr.size < 2 or arr.min() == arr.max():
        return []
    if arr.size == 2:  # the package finds no reversal pair in a two-point history; it is one half cycle
        return [(float(abs(arr[1] - arr[0])), 0.5)]
    return [(float(r), float(n)) for r, n in _rainflow.count_cycles(arr.tolist())]


def reversals(series: Any) -> np.ndarray:
    """The reversal points (peaks and valleys) of a history, first and last point included.

    Repeated equal values count once; a point is a reversal where the slope changes sign
    (ASTM E1049-85, 3.2 / the peak-valley reduction before counting).

    Parameters
    ----------
    series : array_like
        The history, 1-D, finite.

    Returns
    -------
    numpy.ndarray
        The reversal values in order (empty for an empty series).
    """
    arr = series_1d(series, "series")
    return _reversals(arr)


def _reversals(arr: np.ndarray) -> np.ndarray:
    """Peaks and valleys of a checked 1-D array (first and last kept, plateaus once)."""
    if arr.size == 0:
        return arr.copy()
    keep = np.empty(arr.size, dtype=bool)
    keep[0] = True
    keep[1:] = arr[1:] != arr[:-1]
    x = arr[keep]
    if x.size <= 2:
        return x
    d = np.diff(x)
    turn = d[1:] * d[:-1] < 0
    mask = np.concatenate(([True], turn, [True]))
    return x[mask]


__all__ = ["rainflow", "reversals"]
