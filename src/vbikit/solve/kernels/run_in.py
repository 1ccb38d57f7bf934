"""The run-in's loops (``vbikit.solve.run_in``): the wheels' road loads step by step, read as the step
loops read the road, and the recursion's sum in its eigenbasis by Horner's rule."""
from __future__ import annotations

from vbikit.solve.kernels.bundles import _flat
from vbikit.solve.kernels.contact import road_cell


@_flat
def run_in_loads(x0, vx, dt, first, n, line, stiffness, damping, fixed_load, gap, wheel, stations, elevations, idx,
                 out):
    """Add to ``out`` (rows, n_w) the wheels' road loads a_k = Σ_p (k_p (r_p − g_p) + c_p ṙ_p + f0_p) at the
    run-in's step ends k = ``first`` … ``first`` + rows − 1 of ``n`` (t = (k − n) ``dt``, t = 0 the start), each
    point at x_p = ``x0``_p + ``vx``_p t on road line ``line``_p of ``elevations`` (n_lines, n_s) at
    ``stations``: linear between stations, the rate the secant over the half steps around the step end,
    vx (r(x_k+½) − r(x_k−½)) / (vx dt) (``road_point`` with span dt/2, as ``lean`` reads it; at vx = 0 the
    cell's slope times vx, 0).  The reading at x_k+½ is the next step's at x_k−½: two readings a step.
    ``idx``: the points' station pointers (−1 before their first use)."""
    for p in range(x0.size):
        v = vx[p]
        ln = line[p]
        w = wheel[p]
        back = 0.0
        for k in range(-1, out.shape[0]):
            t = (first + k - n) * dt
            x = x0[p] + v * t
            xh = x + 0.5 * v * dt  # the half step after x_k: x_k+½
            ih = road_cell(stations, xh, v, idx, p)
            ahead = elevations[ln, ih] + (xh - stations[ih]) * (elevations[ln, ih + 1] - elevations[ln, ih]) / (
                stations[ih + 1] - stations[ih])
            if k >= 0:
                i = road_cell(stations, x, v, idx, p)
                slope = (elevations[ln, i + 1] - elevations[ln, i]) / (stations[i + 1] - stations[i])
                r = elevations[ln, i] + slope * (x - stations[i])
                rate = (ahead - back) / dt if v != 0.0 else 0.0
                out[k, w] += stiffness[p] * (r - gap[p]) + damping[p] * rate + fixed_load[p]
            back = ahead


@_flat
def run_in_horner(lam, w0, w1, wheels, loads, total):
    """total_j ← λ_j total_j + Σ_i (w0_ji a_k,i + w1_ji a_k+1,i) over the rows k of ``loads`` (rows, n_w) but the
    last, a_k,i = ``loads``[k, ``wheels``_i]: after the K steps of a run-in from total = 0,
    total_j = Σ_k λ_j^(K−1−k) (V⁻¹ (M0 a_k + M1 a_k+1))_j (``vbikit.solve.run_in.settled_state``)."""
    for k in range(loads.shape[0] - 1):
        for j in range(lam.size):
            u = 0.0j
            for i in range(wheels.size):
                u += w0[j, i] * loads[k, wheels[i]] + w1[j, i] * loads[k + 1, wheels[i]]
            total[j] = lam[j] * total[j] + u
