"""Checks of numeric arguments shared by the pure-numerics packages (vbikit.fatigue,
vbikit.extremes): each raises the caller's error class, naming the argument, before any
computation."""
from __future__ import annotations

from typing import Any

import numpy as np

from vbikit.errors import VbikitError


def finite_1d(values: Any, name: str, error: type[VbikitError]) -> np.ndarray:
    """``values`` as a 1-D float64 array of finite numbers, or ``error`` naming ``name``."""
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise error(f"{name}: needs a 1-D sequence of numbers ({exc})") from None
    if arr.ndim != 1:
        raise error(f"{name}: needs a 1-D sequence of numbers, got an array of shape {arr.shape}")
    bad = ~np.isfinite(arr)
    if bad.any():
        raise error(f"{name}: values must be finite; entry {int(np.argmax(bad))} is {arr[bad][0]!r}")
    return arr


def positive_number(value: Any, name: str, error: type[VbikitError]) -> float:
    """``value`` as a finite float > 0, or ``error`` naming ``name``."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise error(f"{name}: needs a number > 0, got {value!r}") from None
    if not np.isfinite(v) or v <= 0:
        raise error(f"{name}: needs a finite number > 0, got {value!r}")
    return v
