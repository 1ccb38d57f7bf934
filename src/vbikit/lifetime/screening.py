"""Which events to simulate dynamically: the screening rule.

Let R_st,e be event e's static peak of a load effect (largest s·R, s the effect's governing
sign; ``vbikit.lifetime.influence``) and A an upper bound of the dynamic increment (the IM, R_dyn/R_st − 1) of any
event, s·R_dyn,e ≤ (1 + A)·s·R_st,e.  In each block b (a day) the block maximum of the total
effect is M_b = max_e s·R_dyn,e.  Simulate first, in every block and for every effect, the
event with the largest static peak (round 1); its dynamic peak D_b ≤ M_b.  Every event with

    (1 + A)·s·R_st,e ≥ D_b                                   (screening rule)

is then simulated.  The events are taken in rounds, in every block the ``per_round`` largest
static peaks of each effect among those the rule keeps, and D_b is updated after every round
(it only grows, so the rule only gets stricter); the rounds end when the rule keeps no event
that has not been simulated.  An event left out has s·R_dyn,e ≤ (1 + A)·s·R_st,e < D_b ≤ M_b:
it cannot be the block's maximum, so the block maxima of the total effect are exact, whatever
the order the events come in.  After the run every simulated event's amplification
a_e = s·R_dyn,e / s·R_st,e − 1 is checked: if any exceeds A the bound was not an upper bound,
A is raised to 1.25 × the largest a_e seen and the blocks are screened again (``rescreen``).
"""
from __future__ import annotations

from typing import Iterable

import numpy as np
from numpy.typing import NDArray


#: the amplification check covers the simulated events whose static peak is at least this fraction
#: of their block's largest (light events, far below any block maximum, may amplify more)
CHECK_FRACTION = 0.5


def top_events(static: NDArray[np.float64], signs: NDArray[np.float64], block: NDArray[np.int64]) -> NDArray[np.int64]:
    """Index of the event with the largest s·R_st in every block and every effect (unique, sorted)."""
    s = np.asarray(static) * np.asarray(signs)[None, :]
    order = np.lexsort((np.arange(len(block)), block))
    b_sorted = np.asarray(block)[order]
    starts = np.flatnonzero(np.r_[True, b_sorted[1:] != b_sorted[:-1]])
    picks = set()
    for j in range(s.shape[1]):
        vals = s[order, j]
        for a, b in zip(starts, np.r_[starts[1:], len(order)]):
            picks.add(int(order[a + int(np.argmax(vals[a:b]))]))
    return np.array(sorted(picks), np.int64)


def block_dynamic_max(dyn: NDArray[np.float64], signs: NDArray[np.float64], block: NDArray[np.int64],
                      simulated: NDArray[np.bool_], n_blocks: int) -> NDArray[np.float64]:
    """D_b (n_blocks, n_effects): the largest s·R_dyn among the simulated events of each block (−inf if none)."""
    out = np.full((n_blocks, dyn.shape[1]), -np.inf)
    idx = np.flatnonzero(simulated)
    for j in range(dyn.shape[1]):
        np.maximum.at(out[:, j], block[idx], signs[j] * dyn[idx, j])
    return out


def candidates(static: NDArray[np.float64], signs: NDArray[np.float64], block: NDArray[np.int64],
               threshold: NDArray[np.float64], amplification: float, simulated: NDArray[np.bool_] | None = None,
               per_round: int | None = None) -> NDArray[np.int64]:
    """Events with (1 + A)·s·R_st ≥ D_b for any effect (the screening rule) not yet
    ``simulated``; with ``per_round``, in every block only the ``per_round`` largest s·R_st of
    each effect among them (sorted indices)."""
    s = np.asarray(static) * np.asarray(signs)[None, :]
    keep = (1.0 + amplification) * s >= threshold[block]
    if simulated is not None:
        keep &= ~np.asarray(simulated)[:, None]
    if per_round is None:
        return np.flatnonzero(np.any(keep, axis=1))
    picks: list[NDArray[np.int64]] = []
    for j in range(s.shape[1]):
        idx = np.flatnonzero(keep[:, j])
        if not idx.size:
            continue
        # order by block, then by decreasing static peak; the first per_round of each block
        order = idx[np.lexsort((-s[idx, j], block[idx]))]
        b = block[order]
        first = np.r_[0, np.flatnonzero(b[1:] != b[:-1]) + 1]
        rank = np.arange(order.size) - np.repeat(first, np.diff(np.r_[first, order.size]))
        picks.append(order[rank < per_round])
    return np.unique(np.concatenate(picks)) if picks else np.zeros(0, np.int64)


#: [substitute] the dynamic amplification of a block's largest static event that ``expected_dynamic_events`` takes
#: for the block's D_b: with the blocks' top events and the random sample the estimate is then, on a week of 4,000
#: trucks a day over the 4-mode beam and the 10-mode deck of Bridge 2 (A = 0.6, class B), 418 and 3,304 events where
#: the runs simulated 396 and 1,552 (``benchmarks/bench_lifetime.py``, with ``--deck``; 2026-12-07)
EXPECTED_TOP_AMPLIFICATION = 0.1


def expected_dynamic_events(static: NDArray[np.float64], signs: NDArray[np.float64], block: NDArray[np.int64],
                            n_blocks: int, amplification: float,
                            extra: NDArray[np.int64] | None = None) -> NDArray[np.int64]:
    """The events (sorted indices) the screening (module docstring) is expected to simulate, from the static peaks
    alone: those the rule keeps with D_b = (1 + ``EXPECTED_TOP_AMPLIFICATION``) times the block's largest s·R_st of
    each effect (the dynamic peak of that event, which round 1 simulates, at a typical amplification), the blocks'
    largest events and ``extra`` (the random sample); where a block's largest s·R_st of an effect is not positive
    (an effect the block's traffic does not load its way), only that block's largest event of it.  A run-time
    estimate made once the static pass is done (``vbikit.lifetime.run.dynamics_estimate``); the re-screening after
    an amplification above A, and the governing events' half-step runs, add a few more."""
    s = np.asarray(static) * np.asarray(signs)[None, :]
    top = np.full((n_blocks, s.shape[1]), -np.inf)
    for j in range(s.shape[1]):
        np.maximum.at(top[:, j], block, s[:, j])
    threshold = np.where(top > 0, (1.0 + EXPECTED_TOP_AMPLIFICATION) * top, np.inf)
    kept = candidates(static, signs, block, threshold, amplification)
    extra = np.zeros(0, np.int64) if extra is None else np.asarray(extra, np.int64)
    return np.union1d(np.union1d(kept, top_events(static, signs, block)), extra).astype(np.int64)


def amplifications(dyn: NDArray[np.float64], static: NDArray[np.float64]) -> NDArray[np.float64]:
    """a = R_dyn / R_st − 1 (same sign convention; NaN where R_st = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(static != 0, dyn / static - 1.0, np.nan)


def rescreen_bound(observed: Iterable[float], amplification: float) -> float:
    """The new bound when an observed amplification exceeds A: 1.25 × the largest (else A)."""
    top = max((float(a) for a in observed if np.isfinite(a)), default=-np.inf)
    return float(1.25 * top) if top > amplification else float(amplification)


def heavy_events(static: NDArray[np.float64], signs: NDArray[np.float64], block: NDArray[np.int64], n_blocks: int,
                 fraction: float) -> NDArray[np.bool_]:
    """(event, effect) pairs whose s·R_st is at least ``fraction`` of the block's largest of that
    effect: the amplifications the run checks against A.  Per effect, since an event heavy for one
    effect can be light for another, whose amplification cannot make a maximum of it (the screening
    rule; a light event's amplification may exceed A)."""
    s = np.asarray(static) * np.asarray(signs)[None, :]
    top = np.full((n_blocks, s.shape[1]), -np.inf)
    for j in range(s.shape[1]):
        np.maximum.at(top[:, j], block, s[:, j])
    return s >= fraction * top[block]


def heavy_amplifications(dyn: NDArray[np.float64], static: NDArray[np.float64], signs: NDArray[np.float64],
                         block: NDArray[np.int64], n_blocks: int, simulated: NDArray[np.bool_],
                         fraction: float) -> NDArray[np.float64]:
    """The amplifications R_dyn/R_st − 1 of the simulated heavy (event, effect) pairs (``heavy_events``), flat."""
    heavy = np.asarray(simulated, bool)[:, None] & heavy_events(static, signs, block, n_blocks, fraction)
    return amplifications(np.asarray(dyn)[heavy], np.asarray(static)[heavy])
