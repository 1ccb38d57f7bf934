"""Input checks shared by the extremes modules (raise before any computation)."""
from __future__ import annotations

from typing import Any

import numpy as np

from vbikit._checks import finite_1d, positive_number
from vbikit.extremes.errors import ExtremesError


def sample(values: Any, name: str, minimum: int, distinct: bool = True) -> np.ndarray:
    """``values`` as a 1-D float64 array of at least ``minimum`` finite numbers, not all equal
    (``distinct``: a fit needs scatter; plotting positions do not)."""
    arr = finite_1d(values, name, ExtremesError)
    if arr.size < minimum:
        raise ExtremesError(f"{name}: needs at least {minimum} values for this fit, got {arr.size}")
    if distinct and arr.size and arr.min() == arr.max():
        raise ExtremesError(f"{name}: all {arr.size} values are equal ({float(arr[0]):.6g}); nothing to fit")
    return arr


def positive(value: Any, name: str) -> float:
    """``value`` as a finite float > 0, or an ExtremesError naming ``name``."""
    return positive_number(value, name, ExtremesError)


def open_unit(value: Any, name: str, what: str) -> float:
    """``value`` as a float in the open interval (0, 1) (``what`` it is, for the message)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ExtremesError(f"{name}: needs {what} in (0, 1), got {value!r}") from None
    if not 0.0 < v < 1.0:
        raise ExtremesError(f"{name}: needs {what} in (0, 1), got {value!r}")
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
