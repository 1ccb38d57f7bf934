"""Rainflow counting of a history that arrives in chunks, possibly on different workers.

The counter keeps the closed cycles (exact ranges, or a histogram of fixed bin width) and the
*residual*: the reversals not yet closed into a full cycle.  Its memory is bounded by the
residual, not by the history.  Counting is the four-point form of ASTM E1049-85 §5.4.4: with
the four most recent reversals A, B, C, D, the range |B − C| is a full cycle when
|A − B| ≥ |B − C| ≤ |C − D|; B and C are then removed.  ``finish`` counts the residual's
consecutive ranges as half cycles; this equals the standard's three-point count of the whole
history (the standard counts a range that contains the first point as a half cycle as soon as
it is found; the four-point form keeps it in the residual and counts it at the end — the same
ranges, the same counts).

Chunks counted separately join exactly: the cycles of chunk a and chunk b, plus the cycles
closed when b's residual is pushed onto a's residual (``join``), equal the cycles of the
history a + b (Amzallag et al. 1994, Standardization of the rainflow counting method for
fatigue analysis, Int. J. Fatigue 16(4), residue handling; checked in tests/fatigue against the
``rainflow`` package on the whole history).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from vbikit.fatigue._checks import positive, series_1d, spectrum
from vbikit.fatigue.counting import _reversals
from vbikit.fatigue.errors import FatigueError


@dataclass(frozen=True)
class RainflowState:
    """What a counter has seen, small and serialisable: closed cycles and the residual.

    Attributes
    ----------
    ranges : numpy.ndarray
        Closed-cycle ranges (same unit as the history), sorted, unique; with ``bin_width`` the
        lower edge of each bin (``index · bin_width``).
    counts : numpy.ndarray
        Full cycles closed at each range (whole numbers; half cycles only come from ``finish``).
    residual : numpy.ndarray
        The unclosed reversals in order; the last one may still move (the history's latest point).
    bin_width : float or None
        None: ranges exact; otherwise closed ranges are accumulated in bins
        ``[k·w, (k+1)·w)``.
    """

    ranges: np.ndarray
    counts: np.ndarray
    residual: np.ndarray
    bin_width: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """The state as plain lists and numbers (JSON-ready; floats round-trip exactly)."""
        return {"ranges": self.ranges.tolist(), "counts": self.counts.tolist(),
                "residual": self.residual.tolist(), "bin_width": self.bin_width}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> RainflowState:
        """The state written by ``to_dict``."""
        try:
            ranges = np.asarray(data["ranges"], dtype=float)
            counts = np.asarray(data["counts"], dtype=float)
            residual = np.asarray(data["residual"], dtype=float)
            width = data.get("bin_width")
        except (KeyError, TypeError, ValueError) as exc:
            raise FatigueError(f"state: not a rainflow state ({exc})") from None
        if ranges.shape != counts.shape or ranges.ndim != 1 or residual.ndim != 1:
            raise FatigueError("state: ranges and counts need equal 1-D lengths and the residual a 1-D list")
        return cls(ranges, counts, residual, None if width is None else float(width))


def _key(rng: float, width: float | None) -> float:
    return rng if width is None else math.floor(rng / width)


class RainflowCounter:
    """Streaming rainflow counter (ASTM E1049-85 §5.4.4, four-point form with residual).

    Parameters
    ----------
    bin_width : float, optional
        Accumulate closed cycles in bins of this width (same unit as the history) instead of
        exact ranges — bounded memory for very long histories.  Default: exact ranges.

    Examples
    --------
    >>> c = RainflowCounter()
    >>> c.feed([-2, 1, -3, 5, -1]); c.feed([3, -4, 4, -2])
    >>> c.finish()
    [(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]
    """

    def __init__(self, bin_width: float | None = None) -> None:
        self.bin_width = None if bin_width is None else positive(bin_width, "bin_width")
        self._cycles: dict[float, float] = {}
        self._res: list[float] = []

    # -- counting ---------------------------------------------------------------------------
    def feed(self, chunk: Any) -> None:
        """Add the next piece of the history (1-D, finite); full cycles are closed as they occur."""
        arr = series_1d(chunk, "chunk")
        for x in _reversals(arr).tolist():
            self._push(x)

    def _push(self, x: float) -> None:
        res = self._res
        if res:
            last = res[-1]
            if x == last:
                return
            if len(res) >= 2 and (x - last) * (last - res[-2]) > 0:
                res[-1] = x  # the previous last point was inside a monotone run
            else:
                res.append(x)
        else:
            res.append(x)
        cycles, width = self._cycles, self.bin_width
        while len(res) >= 4:
            a, b, c, d = res[-4], res[-3], res[-2], res[-1]
            y = abs(b - c)
            if abs(a - b) >= y and abs(c - d) >= y:
                k = _key(y, width)
                cycles[k] = cycles.get(k, 0.0) + 1.0
                del res[-3:-1]
            else:
                break

    # -- state ------------------------------------------------------------------------------
    @property
    def state(self) -> RainflowState:
        """The closed cycles and residual so far (a copy)."""
        keys = sorted(self._cycles)
        ranges = np.array(keys, dtype=float)
        if self.bin_width is not None:
            ranges = ranges * self.bin_width
        return RainflowState(ranges, np.array([self._cycles[k] for k in keys], dtype=float),
                             np.array(self._res, dtype=float), self.bin_width)

    @classmethod
    def from_state(cls, state: RainflowState) -> RainflowCounter:
        """A counter that continues from ``state``."""
        counter = cls(state.bin_width)
        for r, n in zip(state.ranges.tolist(), state.counts.tolist()):
            k = _key(r, None) if state.bin_width is None else round(r / state.bin_width)
            counter._cycles[k] = counter._cycles.get(k, 0.0) + n
        counter._res = state.residual.tolist()
        return counter

    def cycles(self) -> list[tuple[float, float]]:
        """The closed full cycles so far as (range, count) pairs, sorted (residual not counted)."""
        s = self.state
        return list(zip(s.ranges.tolist(), s.counts.tolist()))

    def finish(self) -> list[tuple[float, float]]:
        """All cycles: the closed ones plus the residual's ranges as half cycles, sorted by range.

        The counter is not changed (more chunks may still be fed)."""
        return finish(self.state)


def join(state_a: RainflowState, state_b: RainflowState) -> RainflowState:
    """The state of history a followed by history b, from the states of a and b counted apart.

    Closed cycles add; b's residual is pushed onto a's residual and the cycles that closes are
    counted.  Exact: ``join(count(a), count(b)) == count(a + b)``.

    Raises
    ------
    FatigueError
        The two states use different bin widths.
    """
    if state_a.bin_width != state_b.bin_width:
        raise FatigueError(f"state_b: bin_width {state_b.bin_width} differs from state_a's {state_a.bin_width}")
    counter = RainflowCounter.from_state(state_a)
    other = RainflowCounter.from_state(state_b)
    for k, n in other._cycles.items():
        counter._cycles[k] = counter._cycles.get(k, 0.0) + n
    for x in other._res:
        counter._push(x)
    return counter.state


def finish(state: RainflowState) -> list[tuple[float, float]]:
    """All cycles of a state: closed cycles plus the residual's consecutive ranges as half cycles.

    Returns (range, count) pairs sorted by range (bin lower edges when the state is binned)."""
    width = state.bin_width
    totals: dict[float, float] = {}
    for r, n in zip(state.ranges.tolist(), state.counts.tolist()):
        k = r if width is None else round(r / width)
        totals[k] = totals.get(k, 0.0) + n
    res = state.residual.tolist()
    for x0, x1 in zip(res[:-1], res[1:]):
        k = _key(abs(x1 - x0), width)
        totals[k] = totals.get(k, 0.0) + 0.5
    keys = sorted(totals)
    scale = 1.0 if width is None else width
    return [(k * scale if width is not None else k, totals[k]) for k in keys]


def histogram(ranges: Any, counts: Any, bin_width: float) -> tuple[np.ndarray, np.ndarray]:
    """Cycle counts in bins of equal width, for storage and plots.

    Parameters
    ----------
    ranges, counts : array_like
        (range, count) pairs, e.g. from ``rainflow``; ranges ≥ 0.
    bin_width : float
        Bin width (unit of the ranges); bin k is ``[k·w, (k+1)·w)``.

    Returns
    -------
    edges : numpy.ndarray
        Bin edges, ``0, w, 2w, …`` up to the bin holding the largest range (n + 1 values).
    totals : numpy.ndarray
        Cycles in each bin (n values); their sum equals ``sum(counts)``.
    """
    r, n = spectrum(ranges, counts)
    w = positive(bin_width, "bin_width")
    if r.size == 0:
        return np.zeros(1), np.zeros(0)
    idx = np.floor(r / w).astype(np.int64)
    nbins = int(idx.max()) + 1
    totals = np.bincount(idx, weights=n, minlength=nbins).astype(float)
    return np.arange(nbins + 1) * w, totals


__all__ = ["RainflowCounter", "RainflowState", "finish", "histogram", "join"]
