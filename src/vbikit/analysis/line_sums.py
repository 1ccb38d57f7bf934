"""The quasi-static sums of mode acceleration over moving contact points, compiled, for influence
functions tabulated along wheel lines ([`TabulatedInfluence`][vbikit.bridge.effects.TabulatedInfluence]).

For every effect k and time t_i (``vbikit.analysis.effects``, module docstring)

    S_k(t_i) = Σ_p I_k(x_p(t_i), y_p) · a_p(t_i),   x_p(t_i) = origin_p + direction_p · s_v(p)(t_i),

with two weights at once: the static a_p = β_p P_w and the dynamic a_p = β_p f_w(t_i).  A point
is on the deck while 0 ≤ ξ_p = x_p − y_p tan θ ≤ span; there I_k is the cubic of its element's row
of the wheel line's table at t = (ξ − ξ_e)/(ξ_(e+1) − ξ_e) (Horner), plus on the section's own
element the share c(y_p) times the moment's kink (s − ξ for ξ < s) or the shear's step (1 for
ξ ≤ s).  One pass over the (time, point) pairs, no (time, point) arrays: the same values as the
on-deck pair tables of ``contact_influence_table`` and ``ContactInfluences.sums``, summed per time
in the same point order (equal up to round-off, ``tests/unit/test_line_sums.py``).
"""
from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from vbikit._kept import Kept
from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the @njit(cache=True) below

#: the codes of ``TabulatedInfluence.kink`` in the kernel
KINK_CODES = {"none": 0, "moment": 1, "shear": 2}


@njit(cache=True)
def line_sums(travel, origin, direction, y, vehicle, line, wheel, share, static_load, wheel_forces, stations,
              skew_tan, span, table, kink, element, section, line_share, static, dynamic):  # pragma: no cover (compiled)
    """Add Σ_p I_k β_p P_w to ``static`` (n_effects, n_t) and Σ_p I_k β_p f_w(t) to ``dynamic``
    (module docstring); ``table`` (n_lines · n_elements, n_effects, 4): each row's monomial coefficients
    of every effect side by side, ``line_share`` (n_effects, n_lines)."""
    n_t = travel.shape[0]
    n_cp = origin.size
    n_el = stations.size - 1
    n_eff = table.shape[1]
    lo = max(0.0, stations[0])  # on the deck (0 ≤ ξ ≤ span) and on the stations
    hi = min(span, stations[n_el])
    # point by point (each time's points are still added in point order); a point's element walks
    # with its monotone travel: the largest e in 0 … n_el − 1 with ξ_e ≤ ξ (searchsorted, clipped)
    for p in range(n_cp):
        e = 0
        o, d, v_p, w_p, lp = origin[p], direction[p], vehicle[p], wheel[p], line[p]
        shift = y[p] * skew_tan
        f_static = static_load[p]
        beta = share[p]
        for i in range(n_t):
            x = o + d * travel[i, v_p]
            xi = x - shift if skew_tan != 0.0 else x
            if not (xi >= lo and xi <= hi):
                continue
            while e < n_el - 1 and stations[e + 1] <= xi:
                e += 1
            while e > 0 and stations[e] > xi:
                e -= 1
            t = (xi - stations[e]) / (stations[e + 1] - stations[e])
            r = lp * n_el + e
            f_dynamic = wheel_forces[i, w_p] * beta
            for k in range(n_eff):
                v = ((table[r, k, 3] * t + table[r, k, 2]) * t + table[r, k, 1]) * t + table[r, k, 0]
                if kink[k] != 0 and e == element[k]:
                    s = section[k]
                    if kink[k] == 1:
                        v += line_share[k, lp] * (s - xi if xi < s else 0.0)
                    else:
                        v += line_share[k, lp] * (1.0 if xi <= s else 0.0)
                static[k, i] += v * f_static
                dynamic[k, i] += v * f_dynamic


def tabulated_sums(origin: NDArray[np.float64], direction: NDArray[np.float64], y: NDArray[np.float64],
                   vehicle: NDArray[np.int64], travel: NDArray[np.float64], wheel: NDArray[np.int64],
                   share: NDArray[np.float64], static_load: NDArray[np.float64], wheel_forces: NDArray[np.float64],
                   influences, span: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(Σ_p I_k β_p P_w, Σ_p I_k β_p f_w(t)) of the ``TabulatedInfluence`` functions ``influences`` (all
    on the same stations and skew), each (n_effects, n_t), for contact points at ``origin`` +
    ``direction`` · ``travel``[:, ``vehicle``] on the lines ``y`` (module docstring)."""
    first = influences[0]
    y = np.ascontiguousarray(y, float)
    line, table, line_share, kink, element, section = line_tables(influences, y)
    travel = np.ascontiguousarray(np.asarray(travel, float).reshape(len(travel), -1))
    n_t = travel.shape[0]
    static = np.zeros((len(influences), n_t))
    dynamic = np.zeros((len(influences), n_t))
    from vbikit.solve.compile_notice import announce_compile  # (not a kernel's source: the shipped kernels' list)

    announce_compile(line_sums)
    line_sums(travel, np.ascontiguousarray(origin, float), np.ascontiguousarray(direction, float),
              y, np.ascontiguousarray(vehicle, np.int64), line, np.ascontiguousarray(wheel, np.int64),
              np.ascontiguousarray(share, float), np.ascontiguousarray(static_load, float),
              np.ascontiguousarray(wheel_forces, float), np.ascontiguousarray(first.stations, float),
              float(first.skew_tan), float(span), table, kink, element, section, line_share, static, dynamic)
    return static, dynamic


#: ``line_tables`` already made: by the influences' identities (each entry holds them, so no other
#: object can take an identity while its entry is kept) and the wheel lines' exact bytes
_TABLES: "Kept[tuple, tuple]" = Kept(64)


def line_tables(influences, y: NDArray[np.float64]) -> tuple[NDArray, ...]:
    """``line_sums``' arguments of the ``TabulatedInfluence`` functions ``influences`` for points on the
    wheel lines ``y`` [m]: each point's line index (into the distinct lines, ascending), the cubic rows
    ``table`` (n_lines · n_elements, n_effects, 4), ``line_share`` (n_effects, n_lines) and the kink
    codes, elements and sections, made once per influences and lines in a process (a stream's
    events put their points on the same few lines) and shared: not to be written to."""
    key = (tuple(id(f) for f in influences), y.shape, y.tobytes())
    return _TABLES.get(key, lambda: (tuple(influences),) + _line_tables(influences, y))[1:]


def _line_tables(influences, y: NDArray[np.float64]) -> tuple[NDArray, ...]:
    """``line_tables`` made afresh."""
    lines, line = np.unique(y, return_inverse=True)
    tables = [f.line_tables(lines) for f in influences]
    table = np.ascontiguousarray(np.stack([tb[0] for tb in tables]).transpose(2, 0, 1))  # (row, effect, power)
    line_share = np.ascontiguousarray(np.stack([tb[1] for tb in tables]))
    return (np.ascontiguousarray(line.ravel(), np.int64), table, line_share,
            np.array([KINK_CODES[f.kink] for f in influences], np.int64),
            np.array([f.element for f in influences], np.int64), np.array([f.section for f in influences], float))
