"""A fast moving-force solver: a chain of constant axle loads crossing a modal bridge at constant
speed, for many speeds at once.

Each retained mode obeys ξ̈ᵢ + 2ζᵢωᵢξ̇ᵢ + ωᵢ²ξᵢ = pᵢ(t), pᵢ(t) = −Σ_k φᵢ(v t − a_k) P_k (z up, axle k
a_k behind the first axle, its load P_k downward; the first axle on the entry support at t = 0).
Time is sampled at a fixed *distance* Δx travelled per step, h = Δx / v: the modal loads at the
sample points s_j = j Δx do not depend on the speed and are tabulated once per train.  Between
samples the load is taken linear in time (first-order hold) and each mode is advanced by the exact
discrete-time solution of the damped oscillator, the recurrence of Nigam & Jennings (1969)
(Chopra, *Dynamics of Structures*, §5.2) whose coefficients a11 … c2 are those of the default
"exact" integrator (``vbikit.solve.modal_step.exact_step``), so a crossing here and one through
``vbikit.solve.simulate`` with a moving-force vehicle and the same step agree to round-off.

With constant coefficients the recurrence z_{n+1} = A z_n + B0 p_n + B1 p_{n+1} (z = (ξ, ξ̇)) is a
linear time-invariant filter; its z-transform gives, for ξ and ξ̇,

    den = [1, −(a11 + a22), a11 a22 − a12 a21]
    num_ξ = [c1, b1 − a22 c1 + a12 c2, a12 b2 − a22 b1]
    num_ξ̇ = [c2, b2 − a11 c2 + a21 c1, a21 b1 − a11 b2]

(zero initial state, the load zero at the first sample): ``moving_load_history`` applies it with
``scipy.signal.lfilter`` for every mode.  A sweep (``moving_load_sweep``) runs the recurrence itself
in one compiled loop per speed (numba) and keeps only the peaks, so no history is stored.
ξ̈ = p − 2ζωξ̇ − ω²ξ at the samples.  The train is followed until its last
axle leaves the deck plus ``free_vibration`` seconds.

Outputs: deck displacement and acceleration at points (plain modal sums Σ φᵢ ξᵢ, Σ φᵢ ξ̈ᵢ), the
static displacement within the same modes (Σ φᵢ pᵢ/ωᵢ²), and load effects (moment, shear,
reaction) by the mode-acceleration method as ``vbikit.analysis`` uses it:
R(t) = R_st(t) + Σᵢ rᵢ (ξᵢ − pᵢ/ωᵢ²) with R_st = −Σ_k I(x_k) P_k from the bridge's static
influence line (full stiffness) and rᵢ the effect per unit modal coordinate.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from numba import njit

from vbikit.bridge.base import ModalBridge
from vbikit.bridge.effects import LoadEffect
from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the @njit(cache=True) below

#: samples per period of the highest retained mode at the lowest speed (sets Δx when not given)
STEPS_PER_PERIOD = 20
#: default: the most (speed × mode × sample) filter steps one call may take
MAX_FILTER_STEPS = 4e9


class MovingLoadBudgetError(ValueError):
    """The sweep would take more filter steps than allowed (raise ``max_steps``)."""


@njit(cache=True, fastmath=False, error_model="numpy")
def _peaks(p, static, n_total, a11, a12, a21, a22, b1, b2, c1, c2, phi, r, omega2, damp):  # pragma: no cover (compiled)
    """The recurrence ξ_{n+1} = a11 ξ_n + a12 ξ̇_n + b1 p_n + c1 p_{n+1} (ξ̇ likewise) over ``n_total``
    samples (p zero beyond its rows), tracking max |Σ φ ξ̈|, max |Σ φ ξ| at each point and
    max |R_st + Σ r (ξ − p/ω²)| of each effect; ξ̈ = p − damp ξ̇ − ω² ξ (damp = 2ζω)."""
    n_m = a11.size
    n_p, n_e = phi.shape[0], r.shape[0]
    n_rows = p.shape[0]
    acc = np.zeros(n_p)
    disp = np.zeros(n_p)
    eff = np.zeros(n_e)
    x = np.zeros(n_m)
    v = np.zeros(n_m)
    xa = np.zeros(n_m)
    for n in range(n_total):
        for i in range(n_m):
            p1 = p[n, i] if n < n_rows else 0.0
            if n > 0:
                p0 = p[n - 1, i] if n - 1 < n_rows else 0.0
                x0, v0 = x[i], v[i]
                x[i] = a11[i] * x0 + a12[i] * v0 + b1[i] * p0 + c1[i] * p1
                v[i] = a21[i] * x0 + a22[i] * v0 + b2[i] * p0 + c2[i] * p1
            xa[i] = p1 - damp[i] * v[i] - omega2[i] * x[i]
        for k in range(n_p):
            sa = 0.0
            sd = 0.0
            for i in range(n_m):
                sa += phi[k, i] * xa[i]
                sd += phi[k, i] * x[i]
            if abs(sa) > acc[k]:
                acc[k] = abs(sa)
            if abs(sd) > disp[k]:
                disp[k] = abs(sd)
        for e in range(n_e):
            s = static[n, e] if n < n_rows else 0.0
            for i in range(n_m):
                pi = p[n, i] if n < n_rows else 0.0
                s += r[e, i] * (x[i] - pi / omega2[i])
            if abs(s) > eff[e]:
                eff[e] = abs(s)
    return acc, disp, eff


def _filter_coefficients(omega: NDArray[np.float64], zeta: NDArray[np.float64], h: float):
    """(num_ξ, num_ξ̇, den) of every mode for the step h [s] (module docstring), each (n_m, 3)."""
    from vbikit.solve.modal_step import exact_step

    s = exact_step(omega, zeta, h)
    den = np.stack([np.ones_like(omega), -(s.a11 + s.a22), s.a11 * s.a22 - s.a12 * s.a21], axis=1)
    num_x = np.stack([s.c1, s.b1 - s.a22 * s.c1 + s.a12 * s.c2, s.a12 * s.b2 - s.a22 * s.b1], axis=1)
    num_v = np.stack([s.c2, s.b2 - s.a11 * s.c2 + s.a21 * s.c1, s.a21 * s.b1 - s.a11 * s.b2], axis=1)
    return num_x, num_v, den


def default_dx(bridge: ModalBridge, min_speed: float, steps_per_period: int = STEPS_PER_PERIOD) -> float:
    """Δx [m]: ``steps_per_period`` samples per period of the highest retained mode at the lowest
    speed, and at least 100 samples along the span; rounded down so that the span is an even number
    of steps (the first axle is then sampled on both supports and at midspan)."""
    f_top = float(np.max(bridge.omega)) / (2 * np.pi)
    raw = min(min_speed / (f_top * steps_per_period), bridge.span / 100.0)
    return float(bridge.span / (2 * math.ceil(bridge.span / (2 * raw))))


@dataclass(frozen=True)
class LoadTable:
    """A train's modal loads and static quantities at the sample points s_j = (j − 1) Δx of its
    first axle (j = 0 is one step before it reaches the deck), shared by every speed."""

    dx: float
    travel: NDArray[np.float64]            # (n_s,) s_j [m]
    modal_load: NDArray[np.float64]        # (n_s, n_m) p_i(s_j) [N kg^-1/2]
    static_effects: NDArray[np.float64]    # (n_s, n_e) R_st(s_j) with the full stiffness
    n_forced: int                          # samples until the last axle has left the deck


def load_table(bridge: ModalBridge, axle_positions: ArrayLike, axle_loads: ArrayLike, dx: float,
               effects: Sequence[LoadEffect] = (), y: float = 0.0) -> LoadTable:
    """Modal loads p_i(s_j) = −Σ_k φ_i(s_j − a_k) P_k and static effects −Σ_k I(s_j − a_k) P_k at the
    travel samples of the first axle, from one step before entry until the last axle is off the deck."""
    a = np.asarray(axle_positions, float)
    p = np.asarray(axle_loads, float)
    n_forced = int(math.ceil((bridge.span + a[-1]) / dx)) + 2
    s = (np.arange(n_forced) - 1) * dx
    x = s[:, None] - a[None, :]
    on = (x >= 0.0) & (x <= bridge.span)
    n_m = bridge.omega.size
    load = np.zeros((s.size, n_m))
    rows, cols = np.nonzero(on)
    if rows.size:
        phi = bridge.mode_shapes(x[rows, cols], np.full(rows.size, y))
        np.add.at(load, rows, -phi * p[cols, None])
    static = np.zeros((s.size, len(effects)))
    for e, effect in enumerate(effects):
        infl = np.zeros(x.shape)
        if rows.size:
            infl[rows, cols] = effect.influence(x[rows, cols], np.full(rows.size, y))
        static[:, e] = -(infl @ p)
    return LoadTable(dx, s, load, static, n_forced)


@dataclass(frozen=True)
class MovingLoadHistory:
    """One crossing's histories: time [s] (t = 0: first axle on the entry support), modal
    coordinates ξ, ξ̇, ξ̈ (n_t, n_m), modal loads p (n_t, n_m) and static effects (n_t, n_e)."""

    time: NDArray[np.float64]
    xi: NDArray[np.float64]
    xi_dot: NDArray[np.float64]
    xi_ddot: NDArray[np.float64]
    modal_load: NDArray[np.float64]
    static_effects: NDArray[np.float64]


def _history(bridge: ModalBridge, table: LoadTable, speed: float, free_vibration: float) -> MovingLoadHistory:
    from scipy.signal import lfilter

    h = table.dx / speed
    n = table.n_forced + int(math.ceil(free_vibration / h))
    p = np.zeros((n, table.modal_load.shape[1]))
    p[:table.n_forced] = table.modal_load
    omega, zeta = bridge.omega, bridge.damping_ratios
    num_x, num_v, den = _filter_coefficients(omega, zeta, h)
    xi = np.empty_like(p)
    xv = np.empty_like(p)
    for i in range(omega.size):
        xi[:, i] = lfilter(num_x[i], den[i], p[:, i])
        xv[:, i] = lfilter(num_v[i], den[i], p[:, i])
    xa = p - 2.0 * zeta * omega * xv - omega**2 * xi
    static = np.zeros((n, table.static_effects.shape[1]))
    static[:table.n_forced] = table.static_effects
    time = (np.arange(n) - 1) * h
    return MovingLoadHistory(time, xi, xv, xa, p, static)


def moving_load_history(bridge: ModalBridge, axle_positions: ArrayLike, axle_loads: ArrayLike, speed: float,
                        dx: float | None = None, free_vibration: float | None = None,
                        effects: Sequence[LoadEffect] = (), y: float = 0.0) -> MovingLoadHistory:
    """Histories of one crossing at ``speed`` [m/s] (module docstring); ``dx`` default
    ``default_dx``, ``free_vibration`` [s] default one period of the first mode."""
    dx = default_dx(bridge, speed) if dx is None else float(dx)
    fv = 2 * np.pi / float(bridge.omega[0]) if free_vibration is None else float(free_vibration)
    return _history(bridge, load_table(bridge, axle_positions, axle_loads, dx, effects, y), float(speed), fv)


@dataclass(frozen=True)
class MovingLoadEnvelopes:
    """Peaks of one train over every speed.

    ``max_acceleration`` (n_v, n_p) [m/s²]: max |ẅ| at each point; ``max_displacement`` (n_v, n_p)
    [m]: max |w|; ``static_displacement`` (n_p,) [m]: max |w_st| (retained modes);
    ``max_effect`` (n_v, n_e) and ``static_effect`` (n_e,): max |R| dynamic (mode acceleration) and
    static (full stiffness) [N m or N]; ``dx`` [m] the travel per step; ``unconverged_steps`` (n_v,)
    the steps whose contact forces did not converge at each speed (coupled car models,
    ``CrossingResult.unconverged_steps``; None: moving forces, nothing iterated).
    """

    speeds: NDArray[np.float64]
    points: NDArray[np.float64]
    max_acceleration: NDArray[np.float64]
    max_displacement: NDArray[np.float64]
    static_displacement: NDArray[np.float64]
    max_effect: NDArray[np.float64]
    static_effect: NDArray[np.float64]
    dx: float
    unconverged_steps: Optional[NDArray[np.float64]] = None


def filter_steps(bridge: ModalBridge, train_lengths: Sequence[float], speeds: ArrayLike, dx: float,
                 free_vibration: float) -> float:
    """The number of (speed × mode × sample) filter steps of a sweep: its work estimate."""
    v = np.asarray(speeds, float)
    per_train = sum(((bridge.span + length) / dx + 3) * v.size + float(np.sum(free_vibration * v / dx))
                    for length in train_lengths)
    return 2.0 * per_train * bridge.omega.size


def moving_load_sweep(bridge: ModalBridge, axle_positions: ArrayLike, axle_loads: ArrayLike, speeds: ArrayLike,
                      points: ArrayLike, effects: Sequence[LoadEffect] = (), dx: float | None = None,
                      free_vibration: float | None = None, y: float = 0.0,
                      max_steps: float = MAX_FILTER_STEPS) -> MovingLoadEnvelopes:
    """Envelopes of one train (axles a_k [m], loads P_k [N]) at every speed [m/s] (module docstring):
    peak deck acceleration and displacement at ``points`` (x [m] on the line y), peak load effects."""
    v = np.atleast_1d(np.asarray(speeds, float))
    if v.size == 0 or not np.all(np.isfinite(v) & (v > 0)):
        raise ValueError("speeds must be finite and > 0 m/s")
    dx = default_dx(bridge, float(v.min())) if dx is None else float(dx)
    fv = 2 * np.pi / float(bridge.omega[0]) if free_vibration is None else float(free_vibration)
    a = np.asarray(axle_positions, float)
    steps = filter_steps(bridge, [float(a[-1])], v, dx, fv)
    if steps > max_steps:
        raise MovingLoadBudgetError(f"the sweep needs {steps:.3g} filter steps, above the budget of {max_steps:.3g}; "
                                    "use fewer speeds or modes, or raise the budget")
    xs = np.atleast_1d(np.asarray(points, float))
    phi = bridge.mode_shapes(xs, np.full(xs.size, y))          # (n_p, n_m)
    table = load_table(bridge, a, axle_loads, dx, effects, y)
    omega = bridge.omega
    static_xi = table.modal_load / omega**2
    static_disp = np.max(np.abs(static_xi @ phi.T), axis=0)
    r = np.array([e.modal for e in effects]).reshape(len(effects), omega.size)  # (n_e, n_m)
    static_eff = np.max(np.abs(table.static_effects), axis=0) if effects else np.zeros(0)
    acc = np.empty((v.size, xs.size))
    disp = np.empty((v.size, xs.size))
    eff = np.empty((v.size, len(effects)))
    from vbikit.solve.modal_step import exact_step

    zeta = bridge.damping_ratios
    omega2, damp = np.ascontiguousarray(omega**2), np.ascontiguousarray(2.0 * zeta * omega)
    p_tab = np.ascontiguousarray(table.modal_load)
    st_tab = np.ascontiguousarray(table.static_effects)
    phi_c, r_c = np.ascontiguousarray(phi), np.ascontiguousarray(r)
    for k, speed in enumerate(v):
        h = dx / float(speed)
        c = exact_step(omega, zeta, h)
        n_total = table.n_forced + int(math.ceil(fv / h))
        acc[k], disp[k], eff[k] = _peaks(p_tab, st_tab, n_total, c.a11, c.a12, c.a21, c.a22, c.b1, c.b2, c.c1, c.c2,
                                         phi_c, r_c, omega2, damp)
    return MovingLoadEnvelopes(v, xs, acc, disp, static_disp, eff, static_eff, dx)
