"""Static reference and impact factor.

The static reference is the same bridge model (same modes) under the vehicle's static wheel
loads moved along the same path: at each time t the contact points carry their static
share β_p·P_w of the wheel load P_w (from the vehicle's equilibrium on flat rigid ground)
and ξ_st(t) = −Σ_p φ(x_p(t)) β_p P_w / ω² (downward loads, z up).

Impact factor (paper, §3):  IM = (R_dyn,max − R_st,max) / R_st,max, where R is the response
measured in the direction of the static peak (downward for deflection, tension for
bottom-fibre strain), so R_max = max_t(s·R(t)) with s the sign of the static peak.

Peaks between time samples: when the response's rate is given (the dynamic displacement and
strain, from ξ̇), the dynamic peak is the maximum of the cubic Hermite interpolant of (R, Ṙ)
on the two steps around the largest sample — fourth-order accurate, so the peak does not
depend on the output step (a sampled peak misses up to 1 − cos(ω₁Δt/2) of a mode-1 peak:
1e-3 at Δt = 2 ms on a 7 Hz bridge).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import kept_for
from vbikit._vertex import parabola
from vbikit.solve import system
from vbikit.solve.result import CrossingResult


#: static modal histories one bridge keeps (``static_modal_history``; least recently used dropped first)
STATIC_HISTORIES_KEPT = 8


def static_modal_history(result: CrossingResult) -> NDArray[np.float64]:
    """ξ_st(t) (n_t, n_modes): static modal coordinates under the moving static wheel loads
    (``vbikit.solve.system.static_modal_history``).  It depends on the bridge, the contact points'
    static loads, origins, directions and lines and the vehicles' travel only, not on the road or
    the dynamic solution: kept for the bridge (``vbikit._kept.kept_for``) under those inputs (exact bytes), so that a
    kept bridge's runs with the same vehicles, speeds and time grid (repeated runs, the roads of
    one study point) compute it once.  Read-only: shared by those runs."""
    crossing = result.crossing
    travel = np.asarray(result.travel, float)
    data = result.kernel_data if result.kernel_data is not None else system.kernel_data(crossing)
    cp = crossing.contact
    loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    pts, modes = data.points, data.modes  # the key from the very arrays the history is computed from
    grid = (modes.grid_h, modes.values.shape, modes.start.tobytes())
    _, _, y = crossing.point_kinematics()  # the wheel lines, which ``pts.track`` indexes
    key = (travel.shape, grid, b"".join(np.ascontiguousarray(a, float).tobytes() for a in (
        travel, loads, pts.origin, pts.direction, pts.track, pts.vehicle, y)))

    def make() -> NDArray[np.float64]:
        xi_st = system.static_modal_history(crossing, travel, data)
        xi_st.flags.writeable = False
        return xi_st

    return kept_for(crossing.bridge, "static histories", STATIC_HISTORIES_KEPT).get(key, make)


@dataclass(frozen=True)
class ImpactFactor:
    """Peak dynamic and static responses (signed, largest magnitude in the load direction) and IM.

    Parameters
    ----------
    dynamic_peak, static_peak : float
        The peaks of the dynamic and static responses.
    impact_factor : float
        IM = (R_dyn,max − R_st,max)/R_st,max [-].
    time_dynamic_peak, time_static_peak : float
        When the peaks occur [s].
    """

    dynamic_peak: float
    static_peak: float
    impact_factor: float
    time_dynamic_peak: float
    time_static_peak: float


def hermite_peak(time: NDArray[np.float64], values: NDArray[np.float64], rates: NDArray[np.float64],
                 i: int) -> tuple[float, float]:
    """Largest value (and its time) of the cubic Hermite interpolant of ``values`` with
    derivatives ``rates`` on the steps either side of sample ``i`` (which must be the largest
    sample)."""
    lo = max(i - 1, 0)  # (the samples it reads, as Python floats: the same values, the same arithmetic)
    tl, vl, rl = (np.asarray(a)[lo:i + 2].tolist() for a in (time, values, rates))
    best, t_best = vl[i - lo], tl[i - lo]
    for j in (i - 1 - lo, i - lo):
        if j < 0 or j + 1 >= len(vl):
            continue
        h = tl[j + 1] - tl[j]
        y0, y1, d0, d1 = vl[j], vl[j + 1], h * rl[j], h * rl[j + 1]
        # y(s) = y0 h00 + d0 h10 + y1 h01 + d1 h11; y'(s) = A s² + B s + C
        a = 6 * y0 + 3 * d0 - 6 * y1 + 3 * d1
        b = -6 * y0 - 4 * d0 + 6 * y1 - 2 * d1
        c = d0
        for s in _real_roots(a, b, c):
            if not 0.0 < s < 1.0:
                continue
            y = (y0 * (2 * s**3 - 3 * s**2 + 1) + d0 * (s**3 - 2 * s**2 + s) + y1 * (-2 * s**3 + 3 * s**2)
                 + d1 * (s**3 - s**2))
            if y > best:
                best, t_best = float(y), float(tl[j] + s * h)
    return best, t_best


def smooth_vertices(time: NDArray[np.float64], dynamic: NDArray[np.float64], static: NDArray[np.float64],
                    kinks: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The extremes of two sampled histories between their samples, where no rate is known (the load
    effects): for each history (``dynamic``, ``static``) and each sense (largest, smallest) the vertex
    of the parabola through its extreme sample and the two either side, when that sample is interior,
    the parabola turns that way and no instant of ``kinks`` [s] (where the histories may jump or kink:
    an axle on a jump of the influence line or on a support line) lies on the two steps — then
    (t*, dynamic(t*), static(t*)), both histories read off their parabolas through the same three
    samples.  Up to four entries (time, dynamic, static), to be taken with the samples.

    A sampled extreme of a smooth history misses up to 1 − cos(π f dt) ≈ (π f dt)²/2 of the amplitude
    of its component of frequency f; the parabola's vertex misses O((f dt)³) of it (Lagrange
    interpolation's remainder, at most h³ max|y‴|/(9√3) on three samples h apart: A (2π f h)³/(9√3)).
    Where a kink lies on the two steps the sample stands (and misses up to a step's change)."""
    t = np.asarray(time, float)
    histories = (np.asarray(dynamic, float), np.asarray(static, float))
    if t.size < 3:
        return np.zeros(0), np.zeros(0), np.zeros(0)
    # per history and sense its extreme sample (argmin: the first largest of −h, as argmax(−h))
    extremes = [int(i) for h in histories for i in (h.argmax(), h.argmin())]
    return _vertices(t, histories, extremes, _clear_of(t, np.sort(np.asarray(kinks, float)), np.array(extremes)))


def smooth_vertices_rows(time: NDArray[np.float64], dynamic: NDArray[np.float64], static: NDArray[np.float64],
                         kinks: Sequence[NDArray[np.float64]]) -> list[tuple[NDArray[np.float64], ...]]:
    """``smooth_vertices(time, dynamic[k], static[k], kinks[k])`` of every row k of the (n_rows, n_t)
    histories ``dynamic`` and ``static`` (several load effects of one run), the same values: the extreme
    samples found for all rows in one pass per history and sense, the kink test of the rows that share one
    array of kinks (the same object: a deck's effects kink at the same stations) in one pass."""
    t = np.asarray(time, float)
    dynamic, static = np.asarray(dynamic, float), np.asarray(static, float)
    if t.size < 3:
        return [(np.zeros(0), np.zeros(0), np.zeros(0)) for _ in range(dynamic.shape[0])]
    extremes = np.stack([dynamic.argmax(axis=1), dynamic.argmin(axis=1), static.argmax(axis=1),
                         static.argmin(axis=1)], axis=1)  # (n_rows, 4): the order of ``smooth_vertices``
    clear = np.empty(extremes.shape, bool)
    shared: dict[int, list[int]] = {}
    for k, mine in enumerate(kinks):
        shared.setdefault(id(mine), []).append(k)
    for rows in shared.values():
        clear[rows] = _clear_of(t, np.sort(np.asarray(kinks[rows[0]], float)), extremes[rows]).reshape(len(rows), 4)
    return [_vertices(t, (dynamic[k], static[k]), extremes[k].tolist(), clear[k]) for k in range(dynamic.shape[0])]


def _clear_of(t: NDArray[np.float64], kinks: NDArray[np.float64], extremes: NDArray[np.int64]) -> NDArray[np.bool_]:
    """Per extreme sample i (any shape) whether it is interior and no instant of the sorted ``kinks`` lies on the
    two steps t[i − 1] … t[i + 1], ends included (a kink there: the limits (``vbikit.analysis.effects``) hold the
    peak)."""
    inner = (extremes > 0) & (extremes < t.size - 1)
    if not kinks.size:
        return inner
    i = np.where(inner, extremes, 1)
    return inner & (kinks.searchsorted(t[i - 1], "left") >= kinks.searchsorted(t[i + 1], "right"))


def _vertices(t: NDArray[np.float64], histories: tuple[NDArray[np.float64], NDArray[np.float64]],
              extremes: Sequence[int], clear: Sequence[bool]) -> tuple[NDArray[np.float64], ...]:
    """``smooth_vertices``' entries of the extreme samples ``extremes`` (largest and smallest of the dynamic
    history, then of the static) that are ``clear`` (``_clear_of``)."""
    out: list[tuple[float, ...]] = []
    for (which, sign), i, ok in zip(((0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)), extremes, clear):
        if not ok:
            continue
        s0, s2 = float(t[i - 1] - t[i]), float(t[i + 1] - t[i])  # (times about the middle sample)
        coef = [parabola(s0, s2, float(h[i - 1]), float(h[i]), float(h[i + 1])) for h in histories]
        a, b, _ = coef[which]
        if not sign * a < 0.0:
            continue  # not turning that way (a flat or inflected top): the sample stands
        s = -b / (2.0 * a)
        out.append((float(t[i] + s),) + tuple(c2 * s * s + c1 * s + c0 for c2, c1, c0 in coef))
    if not out:
        return np.zeros(0), np.zeros(0), np.zeros(0)
    return tuple(np.array(col) for col in zip(*out))


def _real_roots(a: float, b: float, c: float) -> tuple[float, ...]:
    """Real roots of a s² + b s + c (a root pair whose imaginary part is at most 1e-12 counts as
    real, at its real part; a, b = 0: none), by the cancellation-free quadratic formula
    q = −(b + sign(b)·√(b² − 4ac))/2, s = q/a, c/q (Numerical Recipes, 3rd ed., §5.6)."""
    if a == 0.0:
        return (-c / b,) if b != 0.0 else ()
    disc = b * b - 4.0 * a * c
    if disc < 0.0:  # a complex pair −b/2a ± i √(−disc)/2|a|
        return (-b / (2.0 * a),) if math.sqrt(-disc) / (2.0 * abs(a)) <= 1e-12 else ()
    q = -0.5 * (b + math.copysign(math.sqrt(disc), b))  # (math's: the same correctly rounded root, on floats)
    return (q / a, c / q) if q != 0.0 else (0.0,)


def static_direction(static: NDArray[np.float64]) -> float:
    """s = ±1, the sign of the static history's largest-magnitude value (+1 where it is 0): the
    direction in which the peaks of an impact factor are taken (module docstring)."""
    static = np.asarray(static)
    return _sign_at(static, largest_magnitude(static))


def _sign_at(static: NDArray[np.float64], i: int) -> float:
    """``static_direction`` given the index ``i`` of the largest magnitude."""
    return float(np.sign(static[i]) or 1.0)


def largest_magnitude(values: NDArray[np.float64]) -> int:
    """``argmax(abs(values))`` — the first index of the largest magnitude (the first NaN, if any) — from
    the largest and the smallest value, without the array of magnitudes: the first of the two when
    they are as large (an impact factor's peaks read several histories an event)."""
    hi, lo = int(values.argmax()), int(values.argmin())
    top, bottom = values[hi], -values[lo]
    return hi if top > bottom else lo if bottom > top else min(hi, lo)


def first_largest(values: NDArray[np.float64], sign: float) -> int:
    """``argmax(sign * values)`` (the first index) for ``sign`` ±1, without the product: the first
    largest value (+1) or the first smallest (−1: the first largest of −values)."""
    if sign > 0.0:
        return int(values.argmax())
    if sign < 0.0:
        return int(values.argmin())
    return int(np.argmax(sign * values))


def impact_factor(time: NDArray[np.float64], dynamic: NDArray[np.float64], static: NDArray[np.float64],
                  dynamic_rate: NDArray[np.float64] | None = None) -> ImpactFactor:
    """IM = (R_dyn,max − R_st,max)/R_st,max with peaks taken in the static peak's direction;
    with ``dynamic_rate`` (dR/dt) the dynamic peak is refined between samples (module docstring)."""
    static = np.asarray(static)
    i_st = largest_magnitude(static)
    if static[i_st] == 0.0:
        raise ValueError("the static response is zero everywhere: no impact factor at this response point")
    return _peaks(time, dynamic, static, _sign_at(static, i_st), i_st, dynamic_rate)


def impact_factor_toward(time: NDArray[np.float64], dynamic: NDArray[np.float64], static: NDArray[np.float64],
                         sign: float) -> ImpactFactor | None:
    """Peaks and IM of a response measured in the direction ``sign`` (±1), whatever the static
    peak's direction: R_max = max_t(sign·R(t)), IM = (R_dyn,max − R_st,max)/R_st,max as in
    ``impact_factor``; None when the static history never goes that way (max_t(sign·R_st) ≤ 0).
    With ``sign = −static_direction(static)`` it gives the opposite extreme of a load effect whose
    static history takes both signs (the hogging moment over a soft pier whose largest static
    moment is sagging: ``vbikit.analysis.effects``)."""
    signed_st = sign * np.asarray(static, float)
    i_st = int(np.argmax(signed_st))
    if not signed_st[i_st] > 0.0:
        return None
    return _peaks(time, np.asarray(dynamic, float), static, sign, i_st)


def _peaks(time: NDArray[np.float64], dynamic: NDArray[np.float64], static: NDArray[np.float64], sign: float,
           i_st: int, dynamic_rate: NDArray[np.float64] | None = None) -> ImpactFactor:
    """The ``ImpactFactor`` in the direction ``sign`` with the static peak at sample ``i_st``: the
    dynamic peak max_t(sign·R(t)), refined between samples with ``dynamic_rate`` (dR/dt)."""
    dynamic = np.asarray(dynamic)
    i_dyn = first_largest(dynamic, sign)
    r_dyn, t_dyn = float(dynamic[i_dyn]), float(time[i_dyn])
    if dynamic_rate is not None:  # (the Hermite steps either side of the peak read those three samples only)
        lo, hi = max(i_dyn - 1, 0), i_dyn + 2
        peak, t_dyn = hermite_peak(time[lo:hi], sign * dynamic[lo:hi], sign * dynamic_rate[lo:hi], i_dyn - lo)
        r_dyn = sign * peak
    r_st = float(static[i_st])
    return ImpactFactor(r_dyn, r_st, (sign * r_dyn - sign * r_st) / (sign * r_st), t_dyn, float(time[i_st]))
