"""Exact static peaks of events on a tabulated influence line, and the coupled runs' total at the
same instants.

The static peaks: every event's loads swept over the active nodes of the tabulated lines
(``vbikit.lifetime.influence.Tabulated``) by the breakpoint sweep of
``vbikit.analysis.breakpoints`` (exact on the tabulated line: module docstring there; points of
one vehicle at the same setback on the same table row, the two wheels of an axle on a beam, are
merged into one load beforehand).  The coupled runs: ``with_knot_limits`` evaluates a run's total
at the instants a wheel stands on one of those knots.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from vbikit.analysis.breakpoints import GATE, active_nodes, event_extremes, knot_tables
from vbikit.analysis.effects import kink_instants
from vbikit.analysis.impact import smooth_vertices
from vbikit.analysis.instants import KNOT_OFFSET, crossing_instants, instant_rows, one_sided, run_state

__all__ = ["GATE", "KNOT_OFFSET", "active_nodes", "event_extremes", "knot_instants", "knot_limits", "knot_tables",
           "with_knot_limits"]


# ---------------------------------------------------------------- the coupled run's total at the knots
# (KNOT_OFFSET, the one-sided limits' offset: ``vbikit.analysis.instants``, re-exported)


def knot_instants(crossing, table, t0: float, t1: float) -> NDArray[np.float64]:
    """The instants τ in (t0, t1) [s] at which a contact point of ``crossing`` stands on an active
    node of ``table`` (a ``vbikit.lifetime.influence.Tabulated`` line: the knots of the module
    docstring, the jump of a reaction or shear line, the kink of a moment line), sorted, unique."""
    return crossing_instants(crossing, [_point_geometry(table, *crossing.point_kinematics())[1]], t0, t1)[0]


def _row_knots(table) -> NDArray[np.float64]:
    """x [m] of the active nodes of every row of ``table``, shape (n_rows, most active nodes in a row),
    padded with NaN (made once per table and kept on it)."""
    known = table.__dict__.get("_row_knots")
    if known is None:
        ptr = np.asarray(table.active_ptr, np.int64)
        count = np.diff(ptr)
        known = np.full((count.size, int(count.max()) if count.size else 0), np.nan)
        col = np.arange(ptr[-1]) - np.repeat(ptr[:-1], count)
        known[np.repeat(np.arange(count.size), count), col] = np.asarray(table.knots[0], float)[:col.size]
        table.__dict__["_row_knots"] = known
    return known


def _tracks(table, y: NDArray[np.float64]) -> NDArray[np.int64]:
    """The table's track of every contact point at deck y (ValueError if one is not tabulated)."""
    y = np.asarray(y, float)
    ids = np.argmin(np.abs(table.tracks[None, :] - y[:, None]), axis=1)
    if not np.all(np.abs(table.tracks[ids] - y) <= 1e-9):  # within 1e-9 m (NaN: not tabulated)
        raise ValueError("a contact point's wheel track is not among the tabulated tracks")
    return ids


#: point geometries a table keeps (``_point_geometry``); beyond, it forgets them all
KEPT_TRACKS = 256


def _point_geometry(table, origin: NDArray[np.float64], sign: NDArray[np.float64],
                    y: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """For contact points with ``point_kinematics`` (origin, sign, y): their tracks on ``table``
    (``_tracks``) and the travel s = (x_knot − origin)·sign [m] of a point's vehicle when the point
    stands on each active node of its row, shape (point, most active nodes in a row), NaN-padded
    (``_row_knots``).  Neither depends on the vehicles' timing: kept on the table per geometry (the
    events of a lifetime run repeat a few lanes and vehicle types; the arrays are shared: not to be
    written; ``KEPT_TRACKS`` geometries at most)."""
    kept = table.__dict__.setdefault("_point_geometry", {})
    key = origin.tobytes() + sign.tobytes() + y.tobytes()
    known = kept.get(key)
    if known is None:
        if len(kept) >= KEPT_TRACKS:
            kept.clear()
        track = _tracks(table, y)
        knot_x = _row_knots(table)[np.asarray(table.row, np.int64)[track]]
        known = kept[key] = track, (knot_x - origin[:, None]) * sign[:, None]
    return known


def with_knot_limits(result, effect, table, dynamic: NDArray[np.float64],
                     static: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The run's histories of a load effect with both one-sided limits at every knot instant, and the
    extremes between the samples away from the knots and support lines (``vbikit.analysis.impact.smooth_vertices``,
    as every load effect's peaks: ``vbikit.analysis.effects``), inserted in time order: (time, total, static).

    A coupled run reads R at its steps t_n; where a contact point crosses a jump or kink of the
    influence line (a reaction under an axle passing its support, a shear at its section) R peaks
    between two steps, and the exact static peak (``event_extremes``) is one of its one-sided
    limits there.  In mode acceleration (``vbikit.analysis.effects``), with the modal equations
    ξ̈_i + 2 ζ_i ω_i ξ̇_i + ω_i² ξ_i = −Q_i, Q_i = Σ_p φ_i(x_p) β_p f_w (as the solver integrates them),

        R(t) = Σ_p g(x_p) β_p f_w − Σ_i r_i (ξ̈_i + 2 ζ_i ω_i ξ̇_i) / ω_i²
             = Σ_p g(x_p) β_p f_w + Σ_i r_i Q_i / ω_i² + Σ_i r_i ξ_i,
        R_st(t) = Σ_p g(x_p) β_p P_w,

    every jump and kink is in a function of the positions x_p(t) — g, and the mode shapes φ_i in
    Q_i — known exactly at any t (the vehicles' motion is prescribed), while the wheel forces f_w
    and the modal displacements ξ_i are states of the dynamics, continuous in t (ξ_i even smooth:
    its kinks are in ξ̈_i).  So at each knot instant τ (``knot_instants``) both limits R(τ∓) are
    evaluated at x_p(τ ∓ δ), δ = ``KNOT_OFFSET`` · step, with g from ``table`` (the line the
    exact static peaks use), f_w interpolated linearly, ξ_i by cubic Hermite interpolation
    (ξ_i, ξ̇_i) and Q_i from the modal equation at the two steps around τ, linear between them
    except for the points that pass a support line in that step (their share from the run's mode
    tables: the solver's own Q_i, also with multi-point tires, whose points carry their
    own forces rather than static shares of their wheel's): the total at the
    instant of the exact static peak, no longer up to a step away from it (the run's state at the
    instants: ``vbikit.analysis.instants.run_state``, which the load effects' jump limits of
    ``vbikit.analysis.effects`` share).  Its remaining error
    is the interpolation: at most (1 − cos(π f dt)) ≈ (π f dt)²/2 of the amplitude of a wheel-force
    component at frequency f (dt the stored step), and far less for ξ_i.

    ``result``: the ``CrossingResult``; ``effect``: the ``LoadEffect`` (its modal values r_i);
    ``dynamic``, ``static``: its histories at ``result.time`` (``vbikit.analysis.effects``).  Several
    lines of one run at once: ``knot_limits``."""
    return knot_limits(result, (effect,), (table,), (dynamic,), (static,))[0]


def knot_limits(result, effects, tables, dynamics, statics) -> list[tuple[NDArray[np.float64], ...]]:
    """``with_knot_limits`` of several lines of one run (``effects[j]`` tabulated as ``tables[j]``,
    its histories ``dynamics[j]``, ``statics[j]``), a list of (time, total, static) per line.

    The lines share the run's state at their instants: the positions, mode shapes, wheel forces and
    modal displacements are evaluated once at the union of their instants (element by element, as for
    one line alone), each line's sums then over its own instants' rows (so that its numbers are
    those of ``with_knot_limits`` of it alone)."""
    t = np.asarray(result.time, float)
    n_lines = len(tables)
    keep = [(t, np.asarray(d, float), np.asarray(s, float)) for d, s in zip(dynamics, statics)]
    if t.size <= 1 or n_lines == 0:
        return keep
    crossing = result.crossing
    origin, sign, y = crossing.point_kinematics()
    tracks, travels = zip(*[_point_geometry(table, origin, sign, y) for table in tables])
    taus = crossing_instants(crossing, travels, float(t[0]), float(t[-1]))  # (all tables in one pass)
    # the extremes between the samples away from the knots and the support lines (``impact.smooth_vertices``)
    vertices = [smooth_vertices(t, dyn, sta, np.union1d(mine, kinks))
                for (_, dyn, sta), mine, kinks in zip(keep, taus, kink_instants(result, effects))]
    if n_lines == 1:
        tau = taus[0]
    else:
        tau = np.concatenate(taus)
        tau.sort()
        tau = tau[np.concatenate(([True], tau[1:] != tau[:-1]))] if tau.size else tau
    if tau.size == 0:
        return [_merged(t, v[0], dyn, v[1], sta, v[2]) for (_, dyn, sta), v in zip(keep, vertices)]
    u = one_sided(tau, float(t[1] - t[0]))  # R(τ⁻), R(τ⁺), in time order
    ordered = bool((u[1:] >= u[:-1]).all())  # so is every line's part of u (unless instants closer than 2δ)
    state = run_state(result, u)  # the run at every instant u (shared by the lines)
    x = state.x
    n_u = x.shape[0]
    xs = x.ravel()
    cp = crossing.contact
    p_static = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    out, located = [], {}
    for effect, table, track, mine, (_, dyn, sta), v in zip(effects, tables, tracks, taus, keep, vertices):
        if mine.size == 0:
            out.append(_merged(t, v[0], dyn, v[1], sta, v[2]))
            continue
        grid = (table.x0, table.h, table.n, table.row.tobytes(), track.tobytes())  # lines on one grid share cells
        if grid not in located:
            located[grid] = table.locate(xs, np.repeat(track[None, :], n_u, 0).ravel())
        g = table.at(*located[grid]).reshape(x.shape)  # table(x, track): g at every point and instant
        rows = None if mine.size == tau.size else instant_rows(tau, mine)  # None: every instant is this line's
        if rows is not None:
            g = g[rows]
        total = state.total(g, effect.modal, crossing.bridge.omega, rows)
        mine_u = u if rows is None else u[rows]
        out.append(_merged(t, np.concatenate((mine_u, v[0])), dyn, np.concatenate((total, v[1])), sta,
                           np.concatenate((g @ p_static, v[2])), ordered and v[0].size == 0))
    return out


def _merged(t: NDArray[np.float64], u: NDArray[np.float64], a1: NDArray[np.float64], b1: NDArray[np.float64],
            a2: NDArray[np.float64], b2: NDArray[np.float64], ordered: bool = False) -> tuple[NDArray[np.float64], ...]:
    """(time, a1 then b1, a2 then b2) in time order, a1 and a2 at the times ``t`` (nondecreasing), b1
    and b2 at the times ``u``: the order of a stable sort of (t, u) concatenated (a time of u after
    the equal ones of t, equal times of u in their own order), by inserting u into t (one
    ``searchsorted``) rather than sorting t again.  ``ordered``: u is known to be nondecreasing."""
    if not ordered and u.size > 1 and not (u[1:] >= u[:-1]).all():  # instants closer than 2δ: u out of order
        order = np.argsort(u, kind="stable")
        u, b1, b2 = u[order], b1[order], b2[order]
    pos = np.searchsorted(t, u, side="right") + np.arange(u.size)  # u's places in the merged series
    keep = np.ones(t.size + u.size, bool)
    keep[pos] = False
    out = []
    for a, b in ((t, u), (a1, b1), (a2, b2)):
        m = np.empty(keep.size)
        m[keep] = a
        m[pos] = b
        out.append(m)
    return tuple(out)
