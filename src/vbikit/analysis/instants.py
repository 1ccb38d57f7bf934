"""A coupled run's state between its time steps, at the instants a contact point crosses a jump or
kink of an influence line: the one mechanism behind the one-sided limits of the load effects
(``vbikit.analysis.effects``, every path: ``load_effect_response(s)``, ``vbikit run``, studies,
traffic) and of the lifetime's lines (``vbikit.lifetime.peaks.knot_limits``).

A load effect read in mode acceleration (``vbikit.analysis.effects``, module docstring), with the
modal equations as the solver integrates them, ξ̈_i + 2 ζ_i ω_i ξ̇_i + ω_i² ξ_i = −Q_i (Q_i the modal
force of the contact points' forces; Σ_p φ_i(x_p, y_p) β_p f_w when each point carries its static
share β_p of its wheel's force f_w, compression positive), is

    R(t) = −Σ_p I(x_p, y_p) β_p f_w − Σ_i r_i (ξ̈_i + 2 ζ_i ω_i ξ̇_i) / ω_i²
         = −Σ_p I(x_p, y_p) β_p f_w + Σ_i r_i Q_i / ω_i² + Σ_i r_i ξ_i,
    R_st(t) = −Σ_p I(x_p, y_p) β_p P_w.

Every jump and kink of R is in a function of the positions x_p(t) — I, and the mode shapes φ_i in
Q_i — known exactly at any t (the vehicles' motion is prescribed), while the wheel forces f_w and
the modal displacements ξ_i are states of the dynamics, continuous in t (ξ_i even smooth: its
kinks are in ξ̈_i).  So at an instant u between the steps t_k−1 ≤ u ≤ t_k (``run_state``):

* the positions are exact, f_w is interpolated linearly, ξ_i by cubic Hermite interpolation of
  (ξ_i, ξ̇_i);
* Q_i is read off the modal equation at the two steps, Q_i = −(ξ̈_i + 2 ζ_i ω_i ξ̇_i + ω_i² ξ_i)
  (the stored ξ̈_i is the solver's, so these are its Q_i, also with multi-point tires, whose
  points carry their own forces rather than static shares of their wheel's: there the sum
  Σ_p φ_i β_p f_w is 1e-3 … 1e-2 of a load effect off the sampled history, ``vbikit demo``'s
  crossing), and taken linear in time between them, except for the points that pass a support
  line of the deck within that step — where their share φ_i β_p f_w jumps (a deck end on elastic
  bearings, a joint) or kinks (a pinned end): for those the linear share is replaced by the exact
  one from the run's mode tables.

R(u) and R_st(u) then follow at any u, in particular both one-sided limits R(τ∓) at an instant τ
when a point stands on a jump (read at τ ∓ δ, δ = ``KNOT_OFFSET`` · step, ``one_sided``); at the
steps themselves they are the sampled histories (tests/verification/test_effect_jump_limits.py).
The error left is the interpolation's: at most (1 − cos(π f dt)) ≈ (π f dt)²/2 of the amplitude of a
wheel-force component of frequency f (dt the stored step: 4e-3 at 15 Hz and 1.4 ms), the same order
for the smooth part of Q_i plus its mode shapes' change over v·dt ((π i v dt / L)²/8 of mode i's
share), and far less for ξ_i — against a sampled history's |ḟ_w| · dt, up to 2 π f dt ≈ 0.13 of that
amplitude, at a jump.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import kept_for
from vbikit._vertex import KNOT_OFFSET  # (the one-sided limits' offset, shared with the railway sweep)



def one_sided(tau: NDArray[np.float64], dt: float) -> NDArray[np.float64]:
    """τ_k − δ, τ_k + δ of every instant τ_k (interleaved, in the order of ``tau``), δ = ``KNOT_OFFSET`` · ``dt``."""
    delta = KNOT_OFFSET * float(dt)
    u = np.empty(2 * tau.size)
    u[0::2] = tau - delta
    u[1::2] = tau + delta
    return u


def crossing_instants(crossing, travels: Sequence[NDArray[np.float64]], t0: float,
                      t1: float) -> list[NDArray[np.float64]]:
    """Per block of ``travels``, the instants in (t0, t1) [s] at which contact point p's vehicle has
    the travel ``block[p, j]`` [m] (each block of shape (n_cp, n_j), NaN: none), sorted, unique (NaN:
    never there, dropped): every block timed in one ``Crossing.times_at`` pass (all vehicles at once).
    The load effects' jump and kink instants and the lifetime's knot instants all come from here."""
    s = travels[0] if len(travels) == 1 else np.concatenate(travels, axis=1)
    tau = crossing.times_at(s, crossing.point_vehicle[:, None])
    ok = (tau > t0) & (tau < t1)  # (NaN: never there, or padding)
    out, a = [], 0
    for block in travels:
        b = a + block.shape[1]
        mine = tau[ok] if len(travels) == 1 else tau[:, a:b][ok[:, a:b]]
        mine.sort()
        out.append(mine[np.concatenate(([True], mine[1:] != mine[:-1]))] if mine.size else mine)  # np.unique's pass
        a = b
    return out


@dataclass(frozen=True)
class RunState:
    """A run's state at the instants ``u`` (module docstring): contact points at ``x`` (n_u, n_cp) on
    the lines ``y`` (n_cp,), their forces β_p f_w ``f`` (n_u, n_cp, linear in time), the modal forces
    Q_i ``q`` (n_u, n_modes, from the steps) and displacements ξ_i ``xi`` (n_u, n_modes,
    cubic Hermite); the vehicles' travel ``travel`` (n_u, n_vehicles) and the wheel forces f_w
    ``wheel_forces`` (n_u, n_wheels, linear in time) the points' come from."""

    u: NDArray[np.float64]
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    f: NDArray[np.float64]
    q: NDArray[np.float64]
    xi: NDArray[np.float64]
    travel: NDArray[np.float64]
    wheel_forces: NDArray[np.float64]

    def total(self, g: NDArray[np.float64], modal: NDArray[np.float64], omega: NDArray[np.float64],
              rows: NDArray[np.int64] | None = None) -> NDArray[np.float64]:
        """A line's value R = Σ_p g_p β_p f_w + Σ_i r_i Q_i / ω_i² + Σ_i r_i ξ_i (module docstring; g = −I
        for a load effect's influence I, r_i ``modal``, ω_i ``omega``) at the instants' rows ``rows``
        (None: all), ``g`` (n_rows, n_cp) given at those rows."""
        f, q, xi = (self.f, self.q, self.xi) if rows is None else (self.f[rows], self.q[rows], self.xi[rows])
        r = np.asarray(modal, float)
        return np.sum(g * f, axis=1) + q @ (r / np.asarray(omega, float)**2) + xi @ r


def instant_rows(tau: NDArray[np.float64], mine: NDArray[np.float64]) -> NDArray[np.int64]:
    """The rows of ``one_sided(tau)`` holding τ⁻ and τ⁺ of each instant of ``mine`` (a sorted subset of
    the sorted ``tau``), in order."""
    rows = np.repeat(2 * np.searchsorted(tau, mine), 2)
    rows[1::2] += 1
    return rows


def modal_terms(bridge) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float]:
    """2 ζ_i ω_i and ω_i² of every mode, the support lines' ξ [m] (contiguous) and tan θ of the immutable
    ``bridge``: what ``run_state`` hands its compiled pass, kept by the bridge (``kept_for``; a traffic
    stream's events ask for them once each, a deck builds its damping ratios and supports anew on every
    read) — shared: not to be written."""
    def make() -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], float]:
        omega, zeta = np.asarray(bridge.omega, float), np.asarray(bridge.damping_ratios, float)
        return 2.0 * zeta * omega, omega**2, np.ascontiguousarray(bridge.support_x, float), float(bridge.skew_tan)

    return kept_for(bridge, "modal terms", 1).get(None, make)


def run_state(result, u: NDArray[np.float64]) -> RunState:
    """The ``RunState`` of ``result`` (a ``CrossingResult`` of at least two steps) at the instants
    ``u`` [s] within its time span (module docstring); each instant's values are computed element by
    element (the same whatever the other instants), in one compiled pass
    (``vbikit.analysis.state_kernel.run_state_pass``)."""
    from vbikit.analysis.state_kernel import run_state_pass
    from vbikit.solve.compile_notice import announce_compile

    t = np.ascontiguousarray(result.time, float)
    crossing = result.crossing
    bridge, cp = crossing.bridge, crossing.contact
    origin, sign, y = crossing._kinematics  # (read only: the state gets a copy of y)
    y = y.copy()
    t_ref, s_ref, v_ref, acc, stop = crossing._motion_refs
    data = result.kernel_data
    if data is None:
        from vbikit.solve import system

        data = system.kernel_data(crossing)
    modes = data.modes
    damping, stiffness, support_x, skew_tan = modal_terms(bridge)
    u = np.ascontiguousarray(u, float)
    n_u, n_cp, n_m = u.size, origin.size, stiffness.size
    forces = np.ascontiguousarray(result.wheel_forces, float)
    travel, x, f = np.empty((n_u, t_ref.size)), np.empty((n_u, n_cp)), np.empty((n_u, n_cp))
    wheel_forces, q, xi = np.empty((n_u, forces.shape[1])), np.empty((n_u, n_m)), np.empty((n_u, n_m))
    announce_compile(run_state_pass)
    run_state_pass(u, t, *(np.ascontiguousarray(a, float) for a in (t_ref, s_ref, v_ref, acc, stop, origin, sign, y)),
                   np.ascontiguousarray(crossing.point_vehicle, np.int64), np.ascontiguousarray(cp.wheel, np.int64),
                   np.ascontiguousarray(cp.weight, float), forces,
                   *(np.ascontiguousarray(a, float) for a in (result.xi, result.xi_dot, result.xi_ddot)),
                   damping, stiffness, support_x, skew_tan,
                   modes.start, modes.end, float(modes.grid_h), modes.values, modes.slopes,
                   np.ascontiguousarray(data.points.track, np.int64), travel, x, wheel_forces, f, q, xi)
    return RunState(u, x, y, f, q, xi, travel, wheel_forces)
