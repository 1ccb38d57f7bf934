"""Exact extremes of moving point loads on a piecewise-linear influence line: the breakpoint
sweep shared by the lifetime's exact static peaks (``vbikit.lifetime.peaks``, on tabulated lines)
and the railway's static moment envelope (``vbikit.rail.envelope``, on a simply supported span's
straight-sided lines).

The extreme of a sum of moving point loads over a piecewise-linear line is reached at an instant
when some load stands on a node of the line.  Let g be given on nodes x_k: linear between
consecutive nodes from its one-sided limits g(x_k⁺) to g(x_(k+1)⁻), so a jump (a shear line at
its section) or a kink (a support, a moment line at its section) at a node is kept.  A load P_p
moving at constant speed, x_p(t) = −d_p + v_p (t − t_p) (driving +x) or L + d_p − v_p (t − t_p)
(driving −x), contributes P_p g(x_p(t)), piecewise linear in t with knots at the instants
τ_(p,k) when it stands on a node (zero off the nodes' range).  The history

    R(t) = Σ_p P_p g(x_p(t))

is then piecewise linear in t between the union of all knots, so its supremum and infimum are
among the one-sided limits R(τ⁻), R(τ⁺) at the knots (both kept: at a jump the extreme is a
one-sided limit, which is what a sampled history approaches).  Nothing is sampled: the peak is
the exact extreme of the line's response, whatever the speeds, directions and spacings of the
loads.

For a table on a uniform grid (``vbikit.lifetime.influence.Tabulated``) only *active* nodes are
knots (``active_nodes``): a node where the table stays on the straight line of the segment it is
on (within ``tol``) is skipped, so a piecewise-linear line (a simply supported beam's moment,
shear and reaction) has a handful of knots and a curved one (a deflection, a continuous beam) one
per node.  ``event_extremes`` sweeps every event's knots in time order (a merge of the loads'
sorted knot lists), carrying R and its slope dR/dt from knot to knot: cost O(K·n_p) an event for
K knots of n_p loads, no sort and no sampling.  ``chain_extremes`` is the one-event case of a
chain of loads (a train's axles) over a line given by its breakpoints.
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
            # the first node after k off the line: a jump or kink there (searched in growing windows)
            width, hit = 8, None
            while hit is None:
                end = min(k + 1 + width, m)
                line_a = A[k] + rise * (u_a[k + 1:end] - u_a[k])
                line_b = A[k] + rise * (u_b[k:end] - u_a[k])
                off = (np.abs(A[k + 1:end] - line_a) > tol) | (np.abs(B[k:end - 1] - line_b[:-1]) > tol) | \
                    (np.abs(B[k + 1:end] - line_b[1:]) > tol)
                found = np.flatnonzero(off)
                if found.size:
                    hit = k + 1 + int(found[0])
                elif end == m:
                    hit = m
                width *= 4
            if hit >= m:
                break
            k = hit
            idx.append(k)
        idx.append(m)
        ptr.append(len(idx))
    return np.asarray(ptr, np.int64), np.asarray(idx, np.int64)


def knot_tables(a: NDArray[np.float64], b: NDArray[np.float64], n_nodes: int, x0: float, h: float,
                ptr: NDArray[np.int64], idx: NDArray[np.int64]):
    """Per active node (``active_nodes``' flat order): its x [m], g(x⁻), g(x⁺) (zero off the grid)
    and the slope dg/dx of the segment to the row's next active node (0 after the last)."""
    m = n_nodes - 1
    row = np.repeat(np.arange(ptr.size - 1), np.diff(ptr))
    k = idx
    base = row * n_nodes
    left = np.where(k > 0, b[base + np.maximum(k - 1, 0)], 0.0)
    right = np.where(k < m, a[base + np.minimum(k, m - 1)], 0.0)
    x = x0 + h * k
    slope = np.zeros(k.size)
    nxt = np.arange(k.size) + 1
    inner = np.ones(k.size, bool)
    inner[ptr[1:] - 1] = False  # the last node of each row
    j = np.flatnonzero(inner)
    slope[j] = (left[nxt[j]] - right[j]) / (x[nxt[j]] - x[j])
    return x, left, right, slope


#: turning points of a history are kept when they reverse by more than this fraction of
#: max|g| · Σ P of the event (the tabulation's ε offsets make reversals of ≈ 1e-9 of it)
GATE = 1e-7


@njit(cache=True)
def _push(buf, n, first, x, gate):
    """Add x to the turning points buf[first:n] (hysteresis filter): a value that goes on in the
    direction of the last step replaces the last point; one that reverses by more than ``gate``
    is appended; anything else is dropped.  Returns the new n (``buf`` has room)."""
    if n == first:
        buf[n] = x
        return n + 1
    last = buf[n - 1]
    if n - first >= 2 and (x - last) * (last - buf[n - 2]) >= 0:
        buf[n - 1] = x
        return n
    if abs(x - last) > gate:
        buf[n] = x
        return n + 1
    return n


@njit(cache=True)
def _sweep(ev_ptr, t_entry, speed, direction, setback, load, row, span, act_ptr, kx, gl, gr, sx, hi, lo, tp, tp_ptr,
           e_start, g_max):
    """``event_extremes`` from event ``e_start`` on, writing turning points into ``tp`` (none if
    it is empty) until the next event might not fit; returns the next event to do."""
    n_ev = ev_ptr.size - 1
    keep = tp.size > 0
    max_p = 1
    for e in range(n_ev):
        max_p = max(max_p, ev_ptr[e + 1] - ev_ptr[e])
    nxt = np.empty(max_p, np.int64)  # next knot of each load (flat index of its active node)
    t_next = np.empty(max_p)
    slope = np.empty(max_p)
    t_a = np.empty(max_p)  # a load stands on x at t_a + t_b·x
    t_b = np.empty(max_p)
    n_tp = tp_ptr[e_start]
    for e in range(e_start, n_ev):
        p0 = ev_ptr[e]
        n_p = ev_ptr[e + 1] - p0
        if keep:
            knots = 0
            for p in range(p0, p0 + n_p):
                knots += act_ptr[row[p] + 1] - act_ptr[row[p]]
            if n_tp + 2 * knots + 2 > tp.size:  # at most two values a knot, and the zeros
                return e
        for q in range(n_p):
            p = p0 + q
            r = row[p]
            if direction[p] > 0:
                t_a[q] = t_entry[p] + setback[p] / speed[p]
                t_b[q] = 1.0 / speed[p]
                nxt[q] = act_ptr[r]
            else:
                t_a[q] = t_entry[p] + (span + setback[p]) / speed[p]
                t_b[q] = -1.0 / speed[p]
                nxt[q] = act_ptr[r + 1] - 1
            t_next[q] = t_a[q] + t_b[q] * kx[nxt[q]]
            slope[q] = 0.0
        R = 0.0
        S = 0.0
        t_cur = -np.inf
        best_hi = 0.0
        best_lo = 0.0
        first = n_tp
        gate = 0.0
        for p in range(p0, p0 + n_p):
            gate += abs(load[p])
        gate *= GATE * g_max
        if keep:
            n_tp = _push(tp, n_tp, first, 0.0, gate)
        while True:
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
                if t_cur > -np.inf:
                    if keep:
                        n_tp = _push(tp, n_tp, first, R, gate)
                    best_hi = max(best_hi, R)
                    best_lo = min(best_lo, R)
                    R += S * (t_min - t_cur)
                    best_hi = max(best_hi, R)
                    best_lo = min(best_lo, R)
                    if keep:
                        n_tp = _push(tp, n_tp, first, R, gate)
                t_cur = t_min
            # load q_min stands on its knot: its jump and its new slope
            q = q_min
            p = p0 + q
            r = row[p]
            j = nxt[q]
            S -= slope[q]
            if direction[p] > 0:
                R += load[p] * (gr[j] - gl[j])
                if j + 1 < act_ptr[r + 1]:
                    slope[q] = load[p] * speed[p] * sx[j]
                    nxt[q] = j + 1
                    t_next[q] = t_a[q] + t_b[q] * kx[j + 1]
                else:
                    slope[q] = 0.0
                    t_next[q] = np.inf
            else:
                R += load[p] * (gl[j] - gr[j])
                if j - 1 >= act_ptr[r]:
                    slope[q] = -load[p] * speed[p] * sx[j - 1]
                    nxt[q] = j - 1
                    t_next[q] = t_a[q] + t_b[q] * kx[j - 1]
                else:
                    slope[q] = 0.0
                    t_next[q] = np.inf
            S += slope[q]
        # after the last knot every load is off the grid: R = 0 (0 is among the extremes already)
        hi[e] = best_hi
        lo[e] = best_lo
        if keep:
            n_tp = _push(tp, n_tp, first, 0.0, gate)
            tp[n_tp - 1] = 0.0  # the bridge is empty again
        tp_ptr[e + 1] = n_tp
    return n_ev


def event_extremes(ev_ptr, t_entry, speed, direction, setback, load, row, span, act_ptr, kx, gl, gr, sx,
                   keep=False):
    """(max R, min R) of every event and, with ``keep``, the turning points of each event's R(t)
    (module docstring).

    ``ev_ptr`` (n_events + 1,): the loads of event e are ``ev_ptr[e]:ev_ptr[e+1]`` of the flat
    per-load arrays ``t_entry`` [s] (entry time of the load's vehicle, relative to a time origin
    of the event), ``speed`` [m/s], ``direction`` (±1), ``setback`` [m], ``load`` [N], ``row``
    (table row); ``act_ptr``: the rows' active nodes (``active_nodes``), ``kx``, ``gl``, ``gr``,
    ``sx``: their x, one-sided values and the slopes after them (``knot_tables``).

    Returns hi, lo (n_events,), the turning points ``tp`` of every event's history (0 before the
    first load arrives, every local extreme — both one-sided limits at a jump — and 0 when the
    last has left; reversals smaller than ``GATE`` · max|g| · Σ P dropped; empty without
    ``keep``) and their offsets ``tp_ptr`` (n_events + 1,)."""
    n_ev = ev_ptr.size - 1
    g_max = float(max(np.max(np.abs(gl), initial=0.0), np.max(np.abs(gr), initial=0.0)))
    hi, lo = np.empty(n_ev), np.empty(n_ev)
    tp_ptr = np.zeros(n_ev + 1, np.int64)
    tp = np.empty(max(4096, 8 * n_ev) if keep else 0)
    e = 0
    while True:
        e = _sweep(ev_ptr, t_entry, speed, direction, setback, load, row, span, act_ptr, kx, gl, gr, sx, hi, lo, tp,
                   tp_ptr, e, g_max)
        if e >= n_ev:
            return hi, lo, tp[:tp_ptr[-1]].copy(), tp_ptr
        # the next event might not fit: room for it and as much again
        knots = int(np.sum(np.diff(act_ptr)[row[ev_ptr[e]:ev_ptr[e + 1]]]))
        grown = np.empty(2 * tp.size + 2 * knots + 2)
        grown[:tp_ptr[e]] = tp[:tp_ptr[e]]
        tp = grown


def chain_extremes(x: NDArray[np.float64], left: NDArray[np.float64], right: NDArray[np.float64],
                   setbacks: NDArray[np.float64], loads: NDArray[np.float64]) -> tuple[float, float]:
    """(max R, min R) of a chain of point loads ``loads`` [N] at ``setbacks`` [m] behind its first
    (a train's axle positions) moving over a piecewise-linear line given by its breakpoints ``x``
    [m] (increasing) and its one-sided values there, ``left`` = g(x⁻) and ``right`` = g(x⁺),
    straight in between and 0 outside (``left[0]`` and ``right[-1]`` are taken as 0): the exact
    extremes over every position of the chain (module docstring; 0 among them: the line empty)."""
    x = np.asarray(x, float)
    left, right = np.array(left, float), np.array(right, float)
    left[0], right[-1] = 0.0, 0.0
    slope = np.zeros(x.size)
    slope[:-1] = (left[1:] - right[:-1]) / np.diff(x)
    n_p = int(np.size(loads))
    hi, lo, _, _ = event_extremes(np.array([0, n_p], np.int64), np.zeros(n_p), np.ones(n_p), np.ones(n_p),
                                  np.asarray(setbacks, float), np.asarray(loads, float), np.zeros(n_p, np.int64), 0.0,
                                  np.array([0, x.size], np.int64), x, left, right, slope)
    return float(hi[0]), float(lo[0])
