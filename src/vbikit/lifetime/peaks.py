"""Exact static peaks of events on a tabulated influence line: the extreme of a sum of moving
point loads over a piecewise-linear line is reached at an instant when some load stands on a
node of the line.

Let g be tabulated on nodes x_k = x_0 + k h (``vbikit.lifetime.influence.Tabulated``): linear
within each cell between its one-sided limits g(x_k⁺) = a_k and g(x_(k+1)⁻) = b_k, so a jump (a
shear line at its section) or a kink (a support, a moment line at its section) at a node is
kept.  A load P_p moving at constant speed, x_p(t) = −d_p + v_p (t − t_p) (driving +x) or
L + d_p − v_p (t − t_p) (driving −x), contributes P_p g(x_p(t)), piecewise linear in t with
knots at the instants τ_(p,k) when it stands on a node (zero off the grid).  The event's static
history

    R(t) = Σ_p P_p g(x_p(t))

is then piecewise linear in t between the union of all knots, so its supremum and infimum are
among the one-sided limits R(τ⁻), R(τ⁺) at the knots (both kept: at a jump the extreme is a
one-sided limit, which is what a sampled history approaches).  Nothing is sampled: the peak is
the exact extreme of the tabulated line's response, whatever the speeds, directions and
spacings of the event's vehicles.

Only *active* nodes are knots: a node where the tabulated line stays on the straight line of the
segment it is on (within ``tol``, the tabulation's own ε-offset error) is skipped, so a
piecewise-linear line (a simply supported beam's moment, shear and reaction) has a handful of
knots and a curved one (a deflection, a continuous beam) one per node.  ``event_extremes``
sweeps every event's knots in time order (a merge of the loads' sorted knot lists), carrying
R and its slope dR/dt from knot to knot: cost O(K·n_p) a event for K knots of n_p loads, no
sort and no sampling.  Points of one vehicle at the same setback on the same table row (the
two wheels of an axle on a beam) are merged into one load beforehand.
"""
from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the @njit(cache=True) below


def active_nodes(a: NDArray[np.float64], b: NDArray[np.float64], n_rows: int, n_nodes: int, delta: float,
                 tol: float) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Active nodes of every row of a tabulated line (module docstring), CSR: ``ptr`` (n_rows + 1,),
    ``idx`` node numbers in increasing order.

    ``a``, ``b``: the table's flat cell starts and ends (row r's cell i at r·n_nodes + i, as in
    ``Tabulated``), sampled at the fractions ``delta`` and 1 − ``delta`` of the cell (the
    one-sided limits' offset ε/h).  A segment starts at an active node k with the straight line
    through a_k and b_k; node k' > k is active when b_(k'−1), a_k' or b_k' (the cell after it)
    leaves that line by more than ``tol``: a jump, or a kink at k'.  Between active nodes the
    table is thus straight within ``tol``."""
    m = n_nodes - 1
    ptr = [0]
    idx: list[int] = []
    u_a = np.arange(m) + delta  # positions (in cells) of a_k and b_k
    u_b = np.arange(m) + 1.0 - delta
    for r in range(n_rows):
        A = a[r * n_nodes:r * n_nodes + m]
        B = b[r * n_nodes:r * n_nodes + m]
        idx.append(0)
        k = 0
        while k < m - 1:
            rise = (B[k] - A[k]) / (1.0 - 2.0 * delta)  # per cell
            # first node after k off the line: a jump or kink there (vectorised over the rest of the row)
            line_a = A[k] + rise * (u_a[k + 1:] - u_a[k])
            line_b = A[k] + rise * (u_b[k:] - u_a[k])
            off = (np.abs(A[k + 1:] - line_a) > tol) | (np.abs(B[k:-1] - line_b[:-1]) > tol) | \
                (np.abs(B[k + 1:] - line_b[1:]) > tol)
            hit = np.flatnonzero(off)
            if not hit.size:
                break
            k = k + 1 + int(hit[0])
            idx.append(k)
        idx.append(m)
        ptr.append(len(idx))
    return np.asarray(ptr, np.int64), np.asarray(idx, np.int64)


@njit(cache=True)
def _knot_values(a, b, base, m, k):
    """(g(x_k⁻), g(x_k⁺)) of a row whose cell 0 is at flat index ``base`` (zero off the grid)."""
    left = b[base + k - 1] if k > 0 else 0.0
    right = a[base + k] if k < m else 0.0
    return left, right


@njit(cache=True)
def event_extremes(ev_ptr, t_entry, speed, direction, setback, load, row, span, x0, h, n_nodes, a, b, act_ptr,
                   act_idx):
    """(max R, min R) of every event (module docstring).

    ``ev_ptr`` (n_events + 1,): the loads of event e are ``ev_ptr[e]:ev_ptr[e+1]`` of the flat
    per-load arrays ``t_entry`` [s] (entry time of the load's vehicle, relative to any time
    origin of the event), ``speed`` [m/s], ``direction`` (±1), ``setback`` [m], ``load`` [N],
    ``row`` (table row); ``a``, ``b``: the table's flat one-sided cell values, ``act_ptr``,
    ``act_idx``: its active nodes per row (``active_nodes``)."""
    n_ev = ev_ptr.size - 1
    m = n_nodes - 1
    hi = np.empty(n_ev)
    lo = np.empty(n_ev)
    max_p = 1
    for e in range(n_ev):
        max_p = max(max_p, ev_ptr[e + 1] - ev_ptr[e])
    nxt = np.empty(max_p, np.int64)  # next knot of each load (position in its row's active list)
    t_next = np.empty(max_p)
    slope = np.empty(max_p)
    for e in range(n_ev):
        p0 = ev_ptr[e]
        n_p = ev_ptr[e + 1] - p0
        for q in range(n_p):
            p = p0 + q
            r = row[p]
            nxt[q] = act_ptr[r + 1] - 1 if direction[p] < 0 else act_ptr[r]
            k = act_idx[nxt[q]]
            xk = x0 + k * h
            t_next[q] = t_entry[p] + ((xk + setback[p]) if direction[p] > 0 else (span + setback[p] - xk)) / speed[p]
            slope[q] = 0.0
        R = 0.0
        S = 0.0
        t_cur = -np.inf
        best_hi = 0.0
        best_lo = 0.0
        while True:
            # the earliest next knot
            q_min = -1
            t_min = np.inf
            for q in range(n_p):
                if t_next[q] < t_min:
                    t_min = t_next[q]
                    q_min = q
            if q_min < 0:
                break
            if t_min > t_cur:
                # every knot at t_cur is through: R is the right limit there; then the left limit at t_min
                best_hi = max(best_hi, R)
                best_lo = min(best_lo, R)
                if t_cur > -np.inf:
                    R += S * (t_min - t_cur)
                    best_hi = max(best_hi, R)
                    best_lo = min(best_lo, R)
                t_cur = t_min
            # load q_min stands on its knot: its jump and new slope
            q = q_min
            p = p0 + q
            r = row[p]
            base = r * (m + 1)
            j = nxt[q]
            k = act_idx[j]
            left, right = _knot_values(a, b, base, m, k)
            if direction[p] > 0:
                before, after = left, right
                j_next = j + 1 if j + 1 < act_ptr[r + 1] else -1
            else:
                before, after = right, left
                j_next = j - 1 if j - 1 >= act_ptr[r] else -1
            R += load[p] * (after - before)
            S -= slope[q]
            if j_next >= 0:
                k2 = act_idx[j_next]
                l2, r2 = _knot_values(a, b, base, m, k2)
                end = l2 if direction[p] > 0 else r2
                xk2 = x0 + k2 * h
                t2 = t_entry[p] + ((xk2 + setback[p]) if direction[p] > 0 else (span + setback[p] - xk2)) / speed[p]
                slope[q] = load[p] * (end - after) / (t2 - t_min) if t2 > t_min else 0.0
                S += slope[q]
                nxt[q] = j_next
                t_next[q] = t2
            else:
                slope[q] = 0.0
                t_next[q] = np.inf
        best_hi = max(best_hi, R)  # the right limit at the last knot
        best_lo = min(best_lo, R)
        hi[e] = best_hi
        lo[e] = best_lo
    return hi, lo
