"""A coupled run's state between its time steps, at the instants a contact point crosses a jump or
kink of an influence line: the one mechanism behind the one-sided limits of the load effects
(``vbikit.analysis.effects``, every path: ``load_effect_response(s)``, ``vbikit run``, studies,
traffic) and of the lifetime's lines (``vbikit.lifetime.peaks.knot_limits``).

A load effect read in mode acceleration (``vbikit.analysis.effects``, module docstring), with the
modal equations as the solver integrates them, ξ̈_i + 2 ζ_i ω_i ξ̇_i + ω_i² ξ_i = −Q_i,
Q_i = Σ_p φ_i(x_p, y_p) β_p f_w (compression positive), is

    R(t) = −Σ_p I(x_p, y_p) β_p f_w − Σ_i r_i (ξ̈_i + 2 ζ_i ω_i ξ̇_i) / ω_i²
         = −Σ_p I(x_p, y_p) β_p f_w + Σ_i r_i Q_i / ω_i² + Σ_i r_i ξ_i,
    R_st(t) = −Σ_p I(x_p, y_p) β_p P_w.

Every jump and kink of R is in a function of the positions x_p(t) — I, and the mode shapes φ_i in
Q_i — known exactly at any t (the vehicles' motion is prescribed), while the wheel forces f_w and
the modal displacements ξ_i are states of the dynamics, continuous in t (ξ_i even smooth: its
kinks are in ξ̈_i).  So at an instant u between the steps t_k−1 ≤ u ≤ t_k (``run_state``) the
positions are exact, f_w is interpolated linearly, ξ_i by cubic Hermite interpolation of (ξ_i, ξ̇_i),
and Q_i is summed from the exact mode shapes: R(u) and R_st(u) then follow at any u, in particular
both one-sided limits R(τ∓) at an instant τ when a point stands on a jump (read at τ ∓ δ,
δ = ``KNOT_OFFSET`` · step, ``one_sided``).  The error left is the interpolation's: at most
(1 − cos(π f dt)) ≈ (π f dt)²/2 of the amplitude of a wheel-force component of frequency f (dt the
stored step: 4e-3 at 15 Hz and 1.4 ms), and far less for ξ_i — against a sampled history's
|ḟ_w| · dt, up to 2 π f dt ≈ 0.13 of that amplitude, at a jump.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

#: the one-sided limits at an instant τ are read at τ ∓ this fraction of the run's step
KNOT_OFFSET = 1e-6


def one_sided(tau: NDArray[np.float64], dt: float) -> NDArray[np.float64]:
    """τ_k − δ, τ_k + δ of every instant τ_k (interleaved, in the order of ``tau``), δ = ``KNOT_OFFSET`` · ``dt``."""
    delta = KNOT_OFFSET * float(dt)
    u = np.empty(2 * tau.size)
    u[0::2] = tau - delta
    u[1::2] = tau + delta
    return u


def crossing_instants(crossing, travels: NDArray[np.float64], t0: float, t1: float) -> NDArray[np.float64]:
    """The instants in (t0, t1) [s] at which contact point p's vehicle has the travel ``travels[p, j]``
    [m] (shape (n_cp, n_j), NaN: none), by ``Crossing.times_at`` (all vehicles in one pass), sorted,
    unique (NaN: never there, dropped)."""
    tau = crossing.times_at(travels, crossing.point_vehicle[:, None])
    mine = tau[(tau > t0) & (tau < t1)]
    mine.sort()
    return mine[np.concatenate(([True], mine[1:] != mine[:-1]))] if mine.size else mine  # np.unique's pass


@dataclass(frozen=True)
class RunState:
    """A run's state at the instants ``u`` (module docstring): contact points at ``x`` (n_u, n_cp) on
    the lines ``y`` (n_cp,), their forces β_p f_w ``f`` (n_u, n_cp, linear in time), the modal forces
    Q_i ``q`` (n_u, n_modes, from the exact mode shapes) and displacements ξ_i ``xi`` (n_u, n_modes,
    cubic Hermite)."""

    u: NDArray[np.float64]
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    f: NDArray[np.float64]
    q: NDArray[np.float64]
    xi: NDArray[np.float64]


def run_state(result, u: NDArray[np.float64], tables: bool = False) -> RunState:
    """The ``RunState`` of ``result`` (a ``CrossingResult`` of at least two steps) at the instants
    ``u`` [s] within its time span; each instant's values are computed element by element (the same
    whatever the other instants).  The mode shapes in Q_i: the bridge's own (``mode_shapes``), or
    with ``tables`` the solver's (the run's mode tables along the wheel tracks, cubic Hermite,
    ``vbikit.solve.tabulate.hermite_rows``: the Q_i the solver integrated, at a fraction of the
    cost; the two agree to the tables' accuracy, ~1e-9 of a load effect on paper Bridge 2)."""
    t = np.asarray(result.time, float)
    crossing = result.crossing
    origin, sign, y = crossing.point_kinematics()
    x = origin[None, :] + sign[None, :] * crossing.travel(u)[:, crossing.point_vehicle]
    n_u = x.shape[0]
    if tables:
        phi = _table_shapes(result, x)
    else:
        phi = np.asarray(crossing.bridge.mode_shapes(x.ravel(), np.repeat(y[None, :], n_u, 0).ravel()),
                         float).reshape(x.shape + (-1,))
    k = np.searchsorted(t[1:-1], u) + 1  # the step ending at or after u, within 1 … n_t − 1
    km = k - 1
    h = t[k] - t[km]
    w = (u - t[km]) / h
    cp = crossing.contact
    forces = result.wheel_forces  # only the rows around the instants, not the whole history
    f = (forces[km][:, cp.wheel] * (1.0 - w)[:, None] + forces[k][:, cp.wheel] * w[:, None]) * cp.weight[None, :]
    # cubic Hermite basis (the same arithmetic as 2w³ − 3w² + 1, w³ − 2w² + w, −2w³ + 3w², w³ − w²)
    w2, w3 = w**2, w**3
    h00, h10, h01, h11 = 2 * w3 - 3 * w2 + 1, w3 - 2 * w2 + w, -2 * w3 + 3 * w2, w3 - w2
    xi = (h00[:, None] * result.xi[km] + (h10 * h)[:, None] * result.xi_dot[km]
          + h01[:, None] * result.xi[k] + (h11 * h)[:, None] * result.xi_dot[k])
    q = np.einsum("upi,up->ui", phi, f)
    return RunState(u, x, y, f, q, xi)


def _table_shapes(result, x: NDArray[np.float64]) -> NDArray[np.float64]:
    """φ_i of the contact points at ``x`` (n_u, n_cp) from the run's mode tables (``run_state``),
    (n_u, n_cp, n_modes), zero off the deck (as the solver's contact rows)."""
    from vbikit.solve import system
    from vbikit.solve.tabulate import hermite_rows

    data = result.kernel_data if result.kernel_data is not None else system.kernel_data(result.crossing)
    modes, track = data.modes, data.points.track
    on = (modes.start[track][None, :] <= x) & (x <= modes.end[track][None, :])
    phi = np.zeros(x.shape + (modes.omega.size,))
    if on.any():
        phi[on] = hermite_rows(modes.start, modes.grid_h, modes.values, modes.slopes, track[np.nonzero(on)[1]], x[on],
                               with_slopes=False)[0]
    return phi
