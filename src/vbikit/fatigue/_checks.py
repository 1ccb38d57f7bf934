"""Input checks shared by the fatigue modules (raise before any computation)."""
from __future__ import annotations

from typing import Any

import numpy as np

from vbikit.fatigue.errors import FatigueError


def series_1d(values: Any, name: str) -> np.ndarray:
    """``values`` as a 1-D float64 array of finite numbers, or a FatigueError naming ``name``."""
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise FatigueError(f"{name}: needs a 1-D sequence of numbers ({exc})") from None
    if arr.ndim != 1:
        raise FatigueError(f"{name}: needs a 1-D sequence of numbers, got an array of shape {arr.shape}")
    bad = ~np.isfinite(arr)
    if bad.any():
        raise FatigueError(f"{name}: values must be finite; entry {int(np.argmax(bad))} is {arr[bad][0]!r}")
    return arr


def spectrum(ranges: Any, counts: Any) -> tuple[np.ndarray, np.ndarray]:
    """Checked (ranges, counts) arrays of a stress-range spectrum: same length, both ≥ 0."""
    r = series_1d(ranges, "ranges")
    n = series_1d(counts, "counts")
    if r.shape != n.shape:
        raise FatigueError(f"counts: needs one count per range, got {n.size} counts for {r.size} ranges")
    if (r < 0).any():
        raise FatigueError(f"ranges: stress ranges are ≥ 0 (Pa); entry {int(np.argmax(r < 0))} is {r[r < 0][0]!r}")
    if (n < 0).any():
        raise FatigueError(f"counts: cycle counts are ≥ 0; entry {int(np.argmax(n < 0))} is {n[n < 0][0]!r}")
    return r, n


def positive(value: float, name: str) -> float:
    """``value`` as a finite float > 0, or a FatigueError naming ``name``."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise FatigueError(f"{name}: needs a number > 0, got {value!r}") from None
    if not np.isfinite(v) or v <= 0:
        raise FatigueError(f"{name}: needs a finite number > 0, got {value!r}")
    return v
