"""Input checks shared by the extremes modules (raise before any computation)."""
from __future__ import annotations

from typing import Any

import numpy as np

from vbikit.extremes.errors import ExtremesError


def sample(values: Any, name: str, minimum: int) -> np.ndarray:
    """``values`` as a 1-D float64 array of at least ``minimum`` finite numbers."""
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ExtremesError(f"{name}: needs a 1-D sequence of numbers ({exc})") from None
    if arr.ndim != 1:
        raise ExtremesError(f"{name}: needs a 1-D sequence of numbers, got an array of shape {arr.shape}")
    bad = ~np.isfinite(arr)
    if bad.any():
        raise ExtremesError(f"{name}: values must be finite; entry {int(np.argmax(bad))} is {arr[bad][0]!r}")
    if arr.size < minimum:
        raise ExtremesError(f"{name}: needs at least {minimum} values for this fit, got {arr.size}")
    if arr.size and arr.min() == arr.max():
        raise ExtremesError(f"{name}: all {arr.size} values are equal ({arr[0]!r}); nothing to fit")
    return arr


def positive(value: Any, name: str) -> float:
    """``value`` as a finite float > 0."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ExtremesError(f"{name}: needs a number > 0, got {value!r}") from None
    if not np.isfinite(v) or v <= 0:
        raise ExtremesError(f"{name}: needs a finite number > 0, got {value!r}")
    return v


def periods(values: Any, name: str = "periods") -> np.ndarray:
    """Return periods (years) as a 1-D array of finite numbers > 0."""
    try:
        arr = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise ExtremesError(f"{name}: needs return periods in years (numbers > 0), got {values!r}") from None
    if arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)) or (arr <= 0).any():
        raise ExtremesError(f"{name}: needs return periods in years, finite and > 0, got {values!r}")
    return arr
