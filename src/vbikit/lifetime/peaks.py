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

__all__ = ["GATE", "KNOT_OFFSET", "active_nodes", "event_extremes", "knot_instants", "knot_tables", "with_knot_limits"]


# ---------------------------------------------------------------- the coupled run's total at the knots
#: the one-sided limits at a knot instant τ are read at τ ∓ this fraction of the run's step
KNOT_OFFSET = 1e-6


def knot_instants(crossing, table, t0: float, t1: float) -> NDArray[np.float64]:
    """The instants τ in (t0, t1) [s] at which a contact point of ``crossing`` stands on an active
    node of ``table`` (a ``vbikit.lifetime.influence.Tabulated`` line: the knots of the module
    docstring, the jump of a reaction or shear line, the kink of a moment line), sorted, unique."""
    return _knot_instants(crossing, table, t0, t1, _tracks(table, crossing.point_kinematics()[2]))


def _knot_instants(crossing, table, t0: float, t1: float, track: NDArray[np.int64]) -> NDArray[np.float64]:
    """``knot_instants`` with the table's track of every contact point given (``_tracks``)."""
    origin, sign, _ = crossing.point_kinematics()
    veh = crossing.point_vehicle
    rows = np.asarray(table.row, np.int64)[track]
    first, count = table.active_ptr[rows], table.active_ptr[rows + 1] - table.active_ptr[rows]
    point = np.repeat(np.arange(origin.size), count)  # every (contact point, active node) pair
    knot = first[point] + np.arange(point.size) - np.repeat(np.cumsum(count) - count, count)
    s = (table.knots[0][knot] - origin[point]) * sign[point]  # travel of the point's vehicle there
    tau = np.empty(point.size)
    for i, motion in enumerate(crossing.vehicles):
        mine = veh[point] == i
        tau[mine] = motion.times_at(s[mine])
    tau = tau[np.isfinite(tau) & (tau > t0) & (tau < t1)]
    return np.unique(tau)


def _tracks(table, y: NDArray[np.float64]) -> NDArray[np.int64]:
    """The table's track of every contact point at deck y (ValueError if one is not tabulated)."""
    y = np.asarray(y, float)
    ids = np.argmin(np.abs(table.tracks[None, :] - y[:, None]), axis=1)
    if not np.all(np.abs(table.tracks[ids] - y) <= 1e-9):  # within 1e-9 m (NaN: not tabulated)
        raise ValueError("a contact point's wheel track is not among the tabulated tracks")
    return ids


def with_knot_limits(result, effect, table, dynamic: NDArray[np.float64],
                     static: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The run's histories of a load effect with both one-sided limits at every knot instant inserted
    in time order: (time, total, static).

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
    exact static peaks use) and the bridge's mode shapes, f_w interpolated linearly and ξ_i by
    cubic Hermite interpolation (ξ_i, ξ̇_i) between the two steps around τ: the total at the
    instant of the exact static peak, no longer up to a step away from it.  Its remaining error
    is the interpolation: at most (1 − cos(π f dt)) ≈ (π f dt)²/2 of the amplitude of a wheel-force
    component at frequency f (dt the stored step), and far less for ξ_i.

    ``result``: the ``CrossingResult``; ``effect``: the ``LoadEffect`` (its modal values r_i);
    ``dynamic``, ``static``: its histories at ``result.time`` (``vbikit.analysis.effects``)."""
    t = np.asarray(result.time, float)
    crossing = result.crossing
    origin, sign, y = crossing.point_kinematics()
    track = _tracks(table, y)
    tau = _knot_instants(crossing, table, float(t[0]), float(t[-1]), track) if t.size > 1 else np.zeros(0)
    if tau.size == 0:
        return t, np.asarray(dynamic, float), np.asarray(static, float)
    delta = KNOT_OFFSET * float(t[1] - t[0])
    u = np.column_stack([tau - delta, tau + delta]).ravel()  # R(τ⁻), R(τ⁺), in time order
    veh = crossing.point_vehicle
    x = origin[None, :] + sign[None, :] * crossing.travel(u)[:, veh]
    yy = np.broadcast_to(y, x.shape)
    g = table(x.ravel(), np.broadcast_to(track, x.shape).ravel()).reshape(x.shape)
    bridge = crossing.bridge
    phi = np.asarray(bridge.mode_shapes(x.ravel(), yy.ravel()), float).reshape(x.shape + (-1,))
    k = np.clip(np.searchsorted(t, u), 1, t.size - 1)
    h = t[k] - t[k - 1]
    w = (u - t[k - 1]) / h
    cp = crossing.contact
    share = cp.weight
    forces = result.wheel_forces[:, cp.wheel]
    f = (forces[k - 1] * (1.0 - w)[:, None] + forces[k] * w[:, None]) * share[None, :]
    h00, h10, h01, h11 = 2 * w**3 - 3 * w**2 + 1, w**3 - 2 * w**2 + w, -2 * w**3 + 3 * w**2, w**3 - w**2
    xi = (h00[:, None] * result.xi[k - 1] + (h10 * h)[:, None] * result.xi_dot[k - 1]
          + h01[:, None] * result.xi[k] + (h11 * h)[:, None] * result.xi_dot[k])
    r = np.asarray(effect.modal, float)
    q = np.einsum("upi,up->ui", phi, f)
    total = np.sum(g * f, axis=1) + q @ (r / bridge.omega**2) + xi @ r
    st = g @ (share * crossing.vehicle.static_wheel_loads()[cp.wheel])
    time = np.concatenate([t, u])
    order = np.argsort(time, kind="stable")
    return time[order], np.concatenate([dynamic, total])[order], np.concatenate([static, st])[order]
