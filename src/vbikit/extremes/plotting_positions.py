"""Plotting positions for probability paper (Gumbel plot) of block maxima."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from vbikit.extremes._checks import positive, sample
from vbikit.extremes.errors import ExtremesError

#: plotting-position formulas p_i of the i-th smallest of n values (i = 1 … n)
POSITIONS: dict[str, Callable[[np.ndarray, int], np.ndarray]] = {
    # Gringorten (1963), J. Geophys. Res. 68(3), 813–814: unbiased for the Gumbel distribution
    "gringorten": lambda i, n: (i - 0.44) / (n + 0.12),
    # Weibull (1939): the mean of the i-th order statistic's non-exceedance probability
    "weibull": lambda i, n: i / (n + 1.0),
    # Hazen (1914)
    "hazen": lambda i, n: (i - 0.5) / n,
}


@dataclass(frozen=True)
class PlottingPositions:
    """Sorted maxima with their empirical non-exceedance probabilities.

    Attributes
    ----------
    values : numpy.ndarray
        The maxima sorted ascending.
    probability : numpy.ndarray
        Non-exceedance probability p_i of each (formula ``method``).
    reduced_variate : numpy.ndarray
        Gumbel reduced variate y_i = −ln(−ln p_i) (a Gumbel sample lies on a straight line
        against it: x = μ + σ y).
    return_period : numpy.ndarray
        Return period in years, 1 / (n_b (1 − p_i)), with n_b blocks a year.
    method : str
        The plotting-position formula.
    """

    values: np.ndarray
    probability: np.ndarray
    reduced_variate: np.ndarray
    return_period: np.ndarray
    method: str


def plotting_positions(maxima: Any, method: str = "gringorten", blocks_per_year: float = 1.0) -> PlottingPositions:
    """Empirical probabilities and Gumbel reduced variates of block maxima.

    Parameters
    ----------
    maxima : array_like
        Block maxima (at least 2, finite).
    method : {"gringorten", "weibull", "hazen"}
        p_i = (i − 0.44)/(n + 0.12) (Gringorten 1963), i/(n + 1) (Weibull) or (i − 0.5)/n (Hazen).
    blocks_per_year : float
        Blocks per year, for the return periods.
    """
    if method not in POSITIONS:
        raise ExtremesError(f"method: unknown plotting position {method!r}; allowed: {', '.join(POSITIONS)}")
    n_b = positive(blocks_per_year, "blocks_per_year")
    x = np.sort(sample(maxima, "maxima", 2, distinct=False))  # tied maxima have positions too
    i = np.arange(1, x.size + 1, dtype=float)
    p = POSITIONS[method](i, x.size)
    return PlottingPositions(x, p, -np.log(-np.log(p)), 1.0 / (n_b * (1.0 - p)), method)


__all__ = ["POSITIONS", "PlottingPositions", "plotting_positions"]
