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

Peaks between the time samples (``moving_load_sweep``): a sampled extreme of a smooth history misses
up to 1 − cos(π f h) ≈ (π f h)²/2 of the amplitude of its component of frequency f (1.2 % at 20 samples
a period), and h = Δx/v grows with the speed.  The compiled loop keeps the last five samples of every
output; each local maximum of |y| is taken at the vertex of the parabola through it and its two
neighbours (the arithmetic of ``vbikit.analysis.impact.smooth_vertices``, ``vbikit._vertex.parabola``
compiled), unless an axle stands on a support line (entering or leaving: the modal loads kink, or
jump on a support that moves) or, for a load effect, on its section or another of its kinks
(``vbikit.bridge.effects.kink_positions``) within the two steps — then the sample stands, and the
history's one-sided limits y(τ−), y(τ+) at each such instant τ are candidates too, as
``vbikit.analysis.instants`` takes them for the coupled runs: everything but the modal state is known
exactly at τ (the axles' positions), so the modal loads pᵢ(τ±) and each effect's static value R_st(τ±)
at τ ∓ δ (δ = ``KNOT_OFFSET`` of a step) are tabulated once per train (``instant_table``), and inside
the loop ξᵢ(τ), ξ̇ᵢ(τ) follow by cubic Hermite interpolation of (ξᵢ, ξ̇ᵢ) at the step's two samples (ξ
is smooth, ξ̇ continuous): Σ φ ξ(τ), Σ φ ξ̈(τ±) with ξ̈ = p(τ±) − 2ζωξ̇ − ω²ξ, R_st(τ±) + Σ rᵢ (ξᵢ −
pᵢ(τ±)/ωᵢ²).  (A jump's sample, a fraction of a step after it, missed up to a step's change: 0.5 … 0.6 %
for the shear at an entry support on a 20 m span.)  The axles' positions do not depend on the speed
(sample j has the first axle at (j − 1) Δx), so the instants and their steps are found once per train
(``kink_instants``, ``kink_steps``).  The peak is the largest candidate; with it the sweep states
``*_sampling_change`` = (peak − largest value read, at a sample or as a limit)/peak, what a vertex
added, and ``*_sampling_bound``, the estimated bound of its remaining error (``sampling_error``): for
a vertex the three-point Lagrange remainder h³ max|y‴|/(9√3) with h³ y‴ read off the third
differences beside it (it covered a pure cosine's vertex error by a factor of at least 1.5 up to 4
samples a period), for a limit the Hermite interpolation's remainder (``_peaks``), for a sample kept at
a kink how far the one-sided limits there, extrapolated from either side, lie above it.  The
first-order hold's own error (above) is not part of it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from numba import njit

from vbikit._vertex import KNOT_OFFSET
from vbikit._vertex import parabola as _three_point_parabola
from vbikit.bridge.base import ModalBridge
from vbikit.bridge.effects import LoadEffect, kink_positions
from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the @njit(cache=True) below

#: samples per period of the highest retained mode at the lowest speed (sets Δx when not given)
STEPS_PER_PERIOD = 20
#: default: the most (speed × mode × sample) filter steps one call may take
MAX_FILTER_STEPS = 4e9


class MovingLoadBudgetError(ValueError):
    """The sweep would take more filter steps than allowed (raise ``max_steps``)."""


#: the parabola through three samples, as ``vbikit.analysis.impact.smooth_vertices`` takes it, compiled
#: for the sweep's loop (one arithmetic: ``vbikit._vertex.parabola`` itself)
_parabola = njit(cache=True)(_three_point_parabola)


@njit(cache=True, fastmath=False, error_model="numpy")
def _peaks(p, static, n_total, a11, a12, a21, a22, b1, b2, c1, c2, phi, r, omega2, damp, kink_step,
           group, h, e_step, e_w, e_group, e_load, e_static, g_ptr, g_q):  # pragma: no cover (compiled)
    """The recurrence ξ_{n+1} = a11 ξ_n + a12 ξ̇_n + b1 p_n + c1 p_{n+1} (ξ̇ likewise) over ``n_total``
    samples (p zero beyond its rows) and two more, tracking the peaks of the quantities q: |Σ φ ξ̈| at
    each point, then |Σ φ ξ| at each point, then |R_st + Σ r (ξ − p/ω²)| of each effect (ξ̈ = p − damp ξ̇
    − ω² ξ, damp = 2ζω).

    Each sample c < ``n_total`` that is a local maximum of |y_q| (and the last, still rising) is a
    candidate: the vertex of the parabola through it and its two neighbours when it turns that way and
    no kink of the history lies on the two steps (``kink_step[group[q], j]``: an instant where the
    history may jump or kink lies on the step from sample j to j + 1; steps beyond its columns:
    none), else the sample itself.
    The one-sided limits at the kink instants are candidates too (``InstantTable``, entries sorted by
    step): entry k lies on the step ``e_step[k]`` → + 1 at the fraction ``e_w[k]`` (h [s] the step);
    ξ, ξ̇ there by cubic Hermite interpolation of the two samples' (ξ, ξ̇), the modal loads
    ``e_load[k, s]`` and the static effect ``e_static[k, s]`` (of group ``e_group[k]``'s effect) exact
    on either side s (τ − δ, τ + δ), for the quantities ``g_q[g_ptr[g]:g_ptr[g + 1]]`` of that group:
    Σ φ ξ(τ), Σ φ ξ̈(τ±) with ξ̈ = p(τ±) − damp ξ̇ − ω² ξ, R_st(τ±) + Σ r (ξ − p(τ±)/ω²).  Each carries
    the bound of the interpolation's remainder (``hermite``, absolute): with e = ξ − H (H the Hermite
    cubic) e = ė = 0 at both samples, so |e(w)| ≤ M h² min(w, 1 − w)²/2 and |ė| ≤ M h min(w, 1 − w),
    M = max |ξ̈ − H''| read at the two samples and at τ± (ξ̈ is near linear on either side of τ).
    Returns per quantity the largest candidate (``peak``), the largest sample (``sampled``), the
    candidate's sample index, whether it is a vertex, the five samples c − 2 … c + 2 about it
    (the history is 0 before the first sample) and, where the candidate is a limit at an instant,
    its Hermite bound (else NaN; the centre is then the step's first sample and the window holds
    the samples c − 3 … c + 1)."""
    n_m = a11.size
    n_p, n_e = phi.shape[0], r.shape[0]
    n_q = 2 * n_p + n_e
    n_rows = p.shape[0]
    n_steps = kink_step.shape[1]
    x = np.zeros(n_m)
    v = np.zeros(n_m)
    xa = np.zeros(n_m)
    ring = np.zeros((5, n_q))  # the last five samples, sample n in row n % 5 (0 before the first)
    peak = np.zeros(n_q)
    cut = np.zeros(n_q)  # peak / 1.25
    sampled = np.zeros(n_q)
    centre = np.full(n_q, -1, np.int64)
    vertex = np.zeros(n_q, np.bool_)
    window = np.zeros((n_q, 5))
    hermite = np.full(n_q, np.nan)
    n_ent = e_step.size
    k_ent = 0
    xp = np.zeros(n_m)  # the previous sample's ξ, ξ̇, ξ̈
    vp = np.zeros(n_m)
    ap = np.zeros(n_m)
    xt = np.zeros(n_m)  # ξ, ξ̇ at an instant, the bounds of their interpolation
    vt = np.zeros(n_m)
    ex = np.zeros(n_m)
    ev = np.zeros(n_m)
    for n in range(n_total + 2):
        for i in range(n_m):
            p1 = p[n, i] if n < n_rows else 0.0
            xp[i], vp[i], ap[i] = x[i], v[i], xa[i]
            if n > 0:
                p0 = p[n - 1, i] if n - 1 < n_rows else 0.0
                x0, v0 = x[i], v[i]
                x[i] = a11[i] * x0 + a12[i] * v0 + b1[i] * p0 + c1[i] * p1
                v[i] = a21[i] * x0 + a22[i] * v0 + b2[i] * p0 + c2[i] * p1
            xa[i] = p1 - damp[i] * v[i] - omega2[i] * x[i]
        y = ring[n % 5]
        for k in range(n_p):
            sa = 0.0
            sd = 0.0
            for i in range(n_m):
                sa += phi[k, i] * xa[i]
                sd += phi[k, i] * x[i]
            y[k] = sa
            y[n_p + k] = sd
        for e in range(n_e):
            s = static[n, e] if n < n_rows else 0.0
            for i in range(n_m):
                pi = p[n, i] if n < n_rows else 0.0
                s += r[e, i] * (x[i] - pi / omega2[i])
            y[2 * n_p + e] = s
        while k_ent < n_ent and e_step[k_ent] < n:  # the instants on the step n − 1 → n
            if e_step[k_ent] == n - 1:
                w = e_w[k_ent]
                g = e_group[k_ent]
                w2, w3 = w * w, w * w * w
                h00, h10, h01, h11 = 2 * w3 - 3 * w2 + 1, w3 - 2 * w2 + w, 3 * w2 - 2 * w3, w3 - w2
                d00, d10, d11 = 6 * w2 - 6 * w, 3 * w2 - 4 * w + 1, 3 * w2 - 2 * w
                s00, s10, s11 = 12 * w - 6, 6 * w - 4, 6 * w - 2
                near = min(w, 1.0 - w)
                for i in range(n_m):
                    xt[i] = h00 * xp[i] + h01 * x[i] + h * (h10 * vp[i] + h11 * v[i])
                    vt[i] = d00 * (xp[i] - x[i]) / h + d10 * vp[i] + d11 * v[i]
                    # H'' at the two samples and at w; ξ̈ there (samples) and at τ ± (the exact loads)
                    hx = (xp[i] - x[i]) / (h * h)
                    m = max(abs(ap[i] - (-6 * hx + (-4 * vp[i] - 2 * v[i]) / h)),
                            abs(xa[i] - (6 * hx + (2 * vp[i] + 4 * v[i]) / h)))
                    hw = s00 * hx + (s10 * vp[i] + s11 * v[i]) / h
                    for side in range(2):
                        m = max(m, abs(e_load[k_ent, side, i] - damp[i] * vt[i] - omega2[i] * xt[i] - hw))
                    ex[i] = 0.5 * m * h * h * near * near
                    ev[i] = m * h * near
                for j in range(g_ptr[g], g_ptr[g + 1]):
                    q = g_q[j]
                    best = 0.0
                    err = 0.0
                    if q < n_p:  # acceleration at point q: both sides
                        for side in range(2):
                            sa = 0.0
                            for i in range(n_m):
                                sa += phi[q, i] * (e_load[k_ent, side, i] - damp[i] * vt[i] - omega2[i] * xt[i])
                            best = max(best, abs(sa))
                        for i in range(n_m):
                            err += abs(phi[q, i]) * (omega2[i] * ex[i] + damp[i] * ev[i])
                    elif q < 2 * n_p:  # deflection: continuous
                        sd = 0.0
                        for i in range(n_m):
                            sd += phi[q - n_p, i] * xt[i]
                            err += abs(phi[q - n_p, i]) * ex[i]
                        best = abs(sd)
                    else:
                        e = q - 2 * n_p
                        for side in range(2):
                            se = e_static[k_ent, side]
                            for i in range(n_m):
                                se += r[e, i] * (xt[i] - e_load[k_ent, side, i] / omega2[i])
                            best = max(best, abs(se))
                        for i in range(n_m):
                            err += abs(r[e, i]) * ex[i]
                    if best > sampled[q]:  # a value read at an instant, as a sample is
                        sampled[q] = best
                    if best > peak[q]:
                        peak[q] = best
                        cut[q] = best / 1.25
                        centre[q] = n - 1
                        vertex[q] = False
                        hermite[q] = err
                        for jj in range(5):
                            window[q, jj] = ring[(n + 1 + jj) % 5, q]  # samples n − 4 … n
            k_ent += 1
        c = n - 2  # the candidate: sample c, with c − 2 … c + 2 in the ring
        if c < 1:
            continue
        r0, rm, rp = c % 5, (c + 4) % 5, (c + 1) % 5
        last = c == n_total - 1
        hits = 0
        for q in range(n_q):  # (no branch: vectorised) a vertex exceeds its sample by at most a quarter of it
            hits += abs(ring[r0, q]) >= cut[q]
        if hits == 0:
            continue
        for q in range(n_q):
            y0 = ring[r0, q]
            m = abs(y0)
            if m < cut[q]:  # (cut = peak / 1.25)
                continue
            ym, yp = ring[rm, q], ring[rp, q]
            rising = m < abs(yp)
            # a local maximum of |y| (or the run's last sample, still rising); the largest sample is one
            # (``&``, not ``and``: one branch, rarely taken)
            if not ((m >= abs(ym)) & ((not rising) | last) & (m > 0.0)):
                continue
            if m > sampled[q]:
                sampled[q] = m
            best = m
            took = False
            g = group[q]
            kinked = (c - 1 < n_steps and kink_step[g, c - 1]) or (c < n_steps and kink_step[g, c])
            if not (kinked or rising):
                sg = 1.0 if y0 > 0.0 else -1.0
                a, b, c0 = _parabola(-1.0, 1.0, sg * ym, m, sg * yp)
                if a < 0.0:  # turning that way (not a flat top)
                    u = -b / (2.0 * a)
                    best = (a * u + b) * u + c0
                    took = True
            if best > peak[q]:
                peak[q] = best
                cut[q] = best / 1.25
                centre[q] = c
                vertex[q] = took
                hermite[q] = np.nan
                for j in range(5):
                    window[q, j] = ring[(c + 3 + j) % 5, q]
    return peak, sampled, centre, vertex, window, hermite


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
    n_forced = int(math.ceil((bridge.span + a[-1]) / dx)) + 2
    s = (np.arange(n_forced) - 1) * dx
    load, static = axle_loads_at(bridge, s, a, axle_loads, effects, y)
    return LoadTable(dx, s, load, static, n_forced)


def axle_loads_at(bridge: ModalBridge, travel: NDArray[np.float64], axle_positions: ArrayLike, axle_loads: ArrayLike,
                  effects: Sequence[LoadEffect] = (), y: float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The modal loads −Σ_k φ_i(s − a_k) P_k (n_s, n_m) and the static effects −Σ_k I(s − a_k) P_k
    (n_s, n_e) with the first axle at each travel s [m] (``travel``, (n_s,)), only the axles on the
    deck (0 ≤ s − a_k ≤ L) counted: the samples' (``load_table``) and the instants' (``instant_table``)."""
    a = np.asarray(axle_positions, float)
    p = np.asarray(axle_loads, float)
    x = np.asarray(travel, float)[:, None] - a[None, :]
    on = (x >= 0.0) & (x <= bridge.span)
    load = np.zeros((x.shape[0], bridge.omega.size))
    rows, cols = np.nonzero(on)
    if rows.size:
        phi = bridge.mode_shapes(x[rows, cols], np.full(rows.size, y))
        np.add.at(load, rows, -phi * p[cols, None])
    static = np.zeros((x.shape[0], len(effects)))
    for e, effect in enumerate(effects):
        infl = np.zeros(x.shape)
        if rows.size:
            infl[rows, cols] = effect.influence(x[rows, cols], np.full(rows.size, y))
        static[:, e] = -(infl @ p)
    return load, static


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

    The time sampling of each dynamic peak (``peak_between_samples``; moving forces): ``*_sampling_change``
    (relative) what the largest time sample, or one-sided limit at an axle's passage, fell short of the peak taken
    between the samples (what a vertex added), and
    ``*_sampling_bound`` (relative) the estimated bound of the peak's remaining time-sampling error,
    for the acceleration and displacement (n_v, n_p) and the effects (n_v, n_e); NaN: not estimated
    (coupled cars: sampled peaks).
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
    acceleration_sampling_change: Optional[NDArray[np.float64]] = None
    acceleration_sampling_bound: Optional[NDArray[np.float64]] = None
    displacement_sampling_change: Optional[NDArray[np.float64]] = None
    displacement_sampling_bound: Optional[NDArray[np.float64]] = None
    effect_sampling_change: Optional[NDArray[np.float64]] = None
    effect_sampling_bound: Optional[NDArray[np.float64]] = None


#: the envelopes' time-sampling fields (``MovingLoadEnvelopes``)
SAMPLING_FIELDS = ("acceleration_sampling_change", "acceleration_sampling_bound", "displacement_sampling_change",
                   "displacement_sampling_bound", "effect_sampling_change", "effect_sampling_bound")


def unsampled(n_v: int, n_p: int, n_e: int) -> dict[str, NDArray[np.float64]]:
    """The time-sampling fields of envelopes whose peaks are plain samples, not estimated (NaN)."""
    return {name: np.full((n_v, n_e if name.startswith("effect") else n_p), np.nan) for name in SAMPLING_FIELDS}


def kink_instants(positions: Sequence[NDArray[np.float64]], axle_positions: ArrayLike, dx: float
                  ) -> list[NDArray[np.float64]]:
    """Per group g, the instants, in samples, at which an axle stands on one of ``positions[g]`` (ξ [m]
    along the span), sorted: sample j is the first axle at travel (j − 1) Δx whatever the speed, so
    axle k (a_k behind the first) stands on ξ at u = (ξ + a_k)/Δx + 1."""
    a = np.asarray(axle_positions, float)
    return [np.sort((np.asarray(xs, float)[:, None] + a[None, :]).ravel() / dx + 1.0) for xs in positions]


#: an instant within this many samples (relative, round-off) of a sample counts as on it
INSTANT_TOLERANCE = 1e-9


def kink_steps(instants: Sequence[NDArray[np.float64]], n_steps: int) -> NDArray[np.bool_]:
    """(n_groups, n_steps): whether one of ``instants[g]`` (``kink_instants``) lies on the step from
    sample j to j + 1, its ends included."""
    out = np.zeros((len(instants), n_steps), bool)
    for g, u in enumerate(instants):
        tol = INSTANT_TOLERANCE * (1.0 + np.abs(u))
        lo = np.maximum(np.ceil(u - 1.0 - tol), 0).astype(np.int64)
        hi = np.minimum(np.floor(u + tol), n_steps - 1).astype(np.int64)
        keep = lo <= hi
        count = np.zeros(n_steps + 1, np.int64)  # +1 from each lo, −1 after each hi: the steps covered
        np.add.at(count, lo[keep], 1)
        np.add.at(count, hi[keep] + 1, -1)
        out[g] = np.cumsum(count[:-1]) > 0
    return out




@dataclass(frozen=True)
class InstantTable:
    """A train's kink instants (``kink_instants``) with everything but the modal state known there,
    shared by every speed: entry k (sorted by step) of group ``group[k]`` lies on the step from sample
    ``step[k]`` to + 1 at the fraction ``w[k]``; ``modal_load[k, s]`` (n_m) the modal loads and
    ``static[k, s]`` the static value of the group's effect (0 for the deck's group 0) at τ − δ (s = 0)
    and τ + δ (s = 1), δ = ``KNOT_OFFSET`` steps, with the axles on the deck there."""

    step: NDArray[np.int64]
    w: NDArray[np.float64]
    group: NDArray[np.int64]
    modal_load: NDArray[np.float64]   # (n_k, 2, n_m)
    static: NDArray[np.float64]       # (n_k, 2)


def instant_table(bridge: ModalBridge, instants: Sequence[NDArray[np.float64]], axle_positions: ArrayLike,
                  axle_loads: ArrayLike, dx: float, effects: Sequence[LoadEffect] = (), y: float = 0.0) -> InstantTable:
    """The ``InstantTable`` of ``instants`` (per group: the deck's, then one per effect), each side's
    modal loads −Σ_k φ_i(x_k) P_k and static effect −Σ_k I(x_k) P_k from the axles' exact positions
    x_k = (u ∓ δ − 1) Δx − a_k (only those on the deck, 0 ≤ x_k ≤ L): ``axle_loads_at``, as ``load_table`` at the samples."""
    u = np.concatenate([np.asarray(x, float) for x in instants]) if instants else np.zeros(0)
    g = np.concatenate([np.full(len(x), k, np.int64) for k, x in enumerate(instants)]) if instants else np.zeros(0, np.int64)
    tol = INSTANT_TOLERANCE * (1.0 + np.abs(u))
    step = np.floor(u + tol).astype(np.int64)
    w = np.clip(u - step, 0.0, 1.0)
    order = np.lexsort((g, step))
    u, g, step, w = u[order], g[order], step[order], w[order]
    load = np.zeros((u.size, 2, bridge.omega.size))
    static = np.zeros((u.size, 2))
    mine = g >= 1  # (an effect's instants: its own static value; the deck's group 0 has none)
    for side, sign in enumerate((-1.0, 1.0)):
        load[:, side], st = axle_loads_at(bridge, (u + sign * KNOT_OFFSET - 1.0) * dx, axle_positions, axle_loads,
                                          effects, y)
        static[mine, side] = st[np.flatnonzero(mine), g[mine] - 1]
    return InstantTable(step, w, g, load, static)


def static_effect_peaks(sampled: NDArray[np.float64], at: InstantTable, n_e: int) -> NDArray[np.float64]:
    """max |R_st| of each effect (n_e,): over the travel samples (``LoadTable.static_effects``, (n_s, n_e))
    and both one-sided limits at every instant an axle stands on one of its kinks (``instant_table``,
    group e + 1): the static influence line's jumps and kinks, where its peak stands when the line is
    straight between them (a simply supported span's moment, shear and reaction), exactly, whatever Δx."""
    out = np.max(np.abs(sampled), axis=0) if n_e and sampled.size else np.zeros(n_e)
    for e in range(n_e):
        mine = at.group == e + 1
        if mine.any():
            out[e] = max(float(out[e]), float(np.max(np.abs(at.static[mine]))))
    return out


def nearest_instant(instants: Sequence[NDArray[np.float64]], group: NDArray[np.int64],
                    centre: NDArray[np.int64]) -> NDArray[np.float64]:
    """u − c of the instant of ``instants[group]`` nearest to each sample ``centre`` c, when within one
    step of it (NaN: none); ``group`` broadcasts against ``centre``."""
    g = np.broadcast_to(group, centre.shape)
    out = np.full(centre.shape, np.nan)
    for k, u in enumerate(instants):
        mine = g == k
        if not u.size or not mine.any():
            continue
        c = centre[mine].astype(float)
        i = np.searchsorted(u, c)
        near = np.where(np.abs(u[np.clip(i - 1, 0, u.size - 1)] - c) <= np.abs(u[np.clip(i, 0, u.size - 1)] - c),
                        u[np.clip(i - 1, 0, u.size - 1)], u[np.clip(i, 0, u.size - 1)]) - c
        out[mine] = np.where(np.abs(near) <= 1.0 + INSTANT_TOLERANCE * (1.0 + np.abs(c)), near, np.nan)
    return out


#: a vertex's remaining error: the three-point Lagrange remainder max|y‴| h³ max|(s + 1) s (s − 1)| / 3!
#: = max|y‴| h³ / (9√3), with h³ y‴ read off the third difference beside the peak
LAGRANGE_FACTOR = 1.0 / (9.0 * math.sqrt(3.0))


def sampling_error(peak: NDArray[np.float64], sampled: NDArray[np.float64], vertex: NDArray[np.bool_],
                   window: NDArray[np.float64], kinked: NDArray[np.bool_], instant: NDArray[np.float64],
                   hermite: Optional[NDArray[np.float64]] = None) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(change, bound), relative to each peak: ``_peaks``' outputs (any leading shape), ``kinked``
    (..., 4) whether the steps c − 2 … c + 1 about the peak's sample c hold a kink and ``instant``
    the offset u − c of the kink nearest to c (``nearest_instant``; NaN: none within a step).

    change = (peak − largest sample) / peak: what the time sampling alone missed.  bound: for a
    vertex, ``LAGRANGE_FACTOR`` × the largest |third difference| of the five samples about it whose
    steps hold no kink (both when both do).  For a sample that stands next to a kink, what the
    history on either side of the kink, extrapolated linearly from its two samples nearest to the
    kink instant (a step clear of kinks between them), reaches at that instant above the sample —
    the one-sided limits of the jump or the corner, read to a step's second difference; where no side
    has two such samples, the largest change over a kink-free step of the four (all four when none
    is) — a history moves about that much over the part of a step between the sample and the kink.
    A flat top's sample: the same rule without a kink (0).  A one-sided limit at a kink instant
    (``hermite`` finite: ``_peaks``' absolute bound of its cubic Hermite interpolation): that bound."""
    w = window
    sg = np.where(w[..., 2] >= 0, 1.0, -1.0)
    d3 = np.abs(np.stack([w[..., 3] - 3 * w[..., 2] + 3 * w[..., 1] - w[..., 0],
                          w[..., 4] - 3 * w[..., 3] + 3 * w[..., 2] - w[..., 1]], axis=-1))
    clean3 = np.stack([~kinked[..., 0], ~kinked[..., 3]], axis=-1)  # (the middle steps are clean at a vertex)
    third = np.where(clean3.any(axis=-1), np.max(np.where(clean3, d3, 0.0), axis=-1), d3.max(axis=-1))
    steps = np.abs(np.diff(w, axis=-1))
    clean = ~kinked
    step = np.where(clean.any(axis=-1), np.max(np.where(clean, steps, 0.0), axis=-1), steps.max(axis=-1))
    # the one-sided limits at the nearest kink u = c + d: the left side from the samples i0 < i1 < u, the
    # right from u < i1 < i2 (window columns: sample c + m is column m + 2)
    d = np.nan_to_num(instant, nan=9.0)
    tol = INSTANT_TOLERANCE
    left1 = np.floor(d - tol).astype(np.int64) + 2  # column of the last sample before u
    right1 = np.ceil(d + tol).astype(np.int64) + 2  # first after
    limits = np.full(w.shape[:-1], -np.inf)
    for near, far, side, step_col in ((left1, left1 - 1, d - (left1 - 2), left1 - 1),
                                      (right1, right1 + 1, (right1 - 2) - d, right1)):
        ok = np.isfinite(instant) & (far >= 0) & (far <= 4) & (near >= 0) & (near <= 4)
        col = np.clip(step_col, 0, 3)
        ok &= ~np.take_along_axis(kinked, col[..., None], axis=-1)[..., 0]
        yn = np.take_along_axis(w, np.clip(near, 0, 4)[..., None], axis=-1)[..., 0]
        yf = np.take_along_axis(w, np.clip(far, 0, 4)[..., None], axis=-1)[..., 0]
        limits = np.where(ok, np.maximum(limits, sg * (yn + (yn - yf) * side)), limits)
    have = np.isfinite(limits)
    kept = np.where(have, np.maximum(limits - sg * w[..., 2], 0.0), step)
    absolute = np.where(vertex, LAGRANGE_FACTOR * third, kept)
    if hermite is not None:
        absolute = np.where(np.isfinite(hermite), hermite, absolute)
    safe = np.where(peak > 0, peak, 1.0)
    change = np.where(peak > 0, (peak - sampled) / safe, 0.0)
    bound = np.where(peak > 0, absolute / safe, 0.0)
    return change, bound


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
    peak deck acceleration and displacement at ``points`` (x [m] on the line y), peak load effects,
    each taken between the time samples with its sampling error (``peak_between_samples``)."""
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
    n_p, n_e = xs.size, len(effects)
    n_q = 2 * n_p + n_e
    out = {name: np.empty((v.size, n_q)) for name in ("peak", "sampled")}
    centre = np.empty((v.size, n_q), np.int64)
    vertex = np.empty((v.size, n_q), bool)
    window = np.empty((v.size, n_q, 5))
    from vbikit.solve.modal_step import exact_step

    zeta = bridge.damping_ratios
    omega2, damp = np.ascontiguousarray(omega**2), np.ascontiguousarray(2.0 * zeta * omega)
    p_tab = np.ascontiguousarray(table.modal_load)
    st_tab = np.ascontiguousarray(table.static_effects)
    phi_c, r_c = np.ascontiguousarray(phi), np.ascontiguousarray(r)
    instants = kink_instants(_kink_positions(bridge, effects, y), a, dx)
    kinks = kink_steps(instants, table.n_forced + 1)
    group = np.concatenate([np.zeros(2 * n_p, np.int64), 1 + np.arange(n_e, dtype=np.int64)])
    at = instant_table(bridge, instants, a, axle_loads, dx, effects, y)
    static_eff = static_effect_peaks(table.static_effects, at, n_e)
    g_q = np.argsort(group, kind="stable").astype(np.int64)  # the quantities of each group, in order
    g_ptr = np.searchsorted(group[g_q], np.arange(len(instants) + 1)).astype(np.int64)
    hermite = np.empty((v.size, n_q))
    for k, speed in enumerate(v):
        h = dx / float(speed)
        c = exact_step(omega, zeta, h)
        n_total = table.n_forced + int(math.ceil(fv / h))
        out["peak"][k], out["sampled"][k], centre[k], vertex[k], window[k], hermite[k] = _peaks(
            p_tab, st_tab, n_total, c.a11, c.a12, c.a21, c.a22, c.b1, c.b2, c.c1, c.c2, phi_c, r_c, omega2, damp, kinks,
            group, h, at.step, at.w, at.group, at.modal_load, at.static, g_ptr, g_q)
    j = centre[..., None] + np.arange(-2, 2)  # the steps c − 2 … c + 1 about each peak's sample
    inside = (j >= 0) & (j < kinks.shape[1])
    kinked = inside & kinks[group[None, :, None], np.clip(j, 0, kinks.shape[1] - 1)]
    change, bound = sampling_error(out["peak"], out["sampled"], vertex, window, kinked,
                                   nearest_instant(instants, group[None, :], centre), hermite)
    peak = out["peak"]
    acc, disp, eff = peak[:, :n_p], peak[:, n_p:2 * n_p], peak[:, 2 * n_p:]
    sampling = {"acceleration_sampling_change": change[:, :n_p], "acceleration_sampling_bound": bound[:, :n_p],
                "displacement_sampling_change": change[:, n_p:2 * n_p], "displacement_sampling_bound": bound[:, n_p:2 * n_p],
                "effect_sampling_change": change[:, 2 * n_p:], "effect_sampling_bound": bound[:, 2 * n_p:]}
    return MovingLoadEnvelopes(v, xs, acc, disp, static_disp, eff, static_eff, dx, **sampling)


def _kink_positions(bridge: ModalBridge, effects: Sequence[LoadEffect], y: float) -> list[NDArray[np.float64]]:
    """ξ [m] where an axle's passage may kink or jump the histories: the deck's (acceleration and
    displacement) at the support lines (an axle entering or leaving: the modal loads kink there, or
    jump on a support that moves), then each effect's (``vbikit.bridge.effects.kink_positions``:
    its section, the support lines, a tabulated line's breaks)."""
    return [np.asarray(bridge.support_x, float)] + [np.asarray(kink_positions(bridge, e, y), float) for e in effects]
