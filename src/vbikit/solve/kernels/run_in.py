"""The run-in's loops (``vbikit.solve.run_in``): the wheels' road loads step by step, read as the step
loops read the road, and a linear system's recursion step by step (the run-in's vehicles; the drive-by's
first-order-hold responses)."""
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
def linear_recursion(a_cols, b0_cols, b1_cols, c, u, x, work, history):
    """x ← A x + B0 u_k + B1 u_k+1 + c for k = 0 … rows(u) − 2, the matrices given by columns (``a_cols`` = Aᵀ
    (n, n), ``b0_cols`` = B0ᵀ, ``b1_cols`` = B1ᵀ (m, n), C-contiguous: every inner loop a contiguous
    x ← x + a·column the compiler vectorises), ``c`` (n,), ``u`` (rows, m), in ``x`` (n,) in place (``work``
    (n,) scratch): a linear time-invariant system with its inputs held linear over each step, step by step
    (the run-in of ``vbikit.solve.run_in``; the drive-by's first-order-hold responses,
    ``vbikit.driveby.decoupled``).  With ``history`` (rows(u), n), not empty, its row k the state after k
    steps (row 0: x as given)."""
    n = x.size
    keep = history.shape[0] > 0
    if keep:
        for i in range(n):
            history[0, i] = x[i]
    for k in range(u.shape[0] - 1):
        for i in range(n):
            work[i] = c[i]
        for j in range(n):
            xj = x[j]
            for i in range(n):
                work[i] += a_cols[j, i] * xj
        for j in range(u.shape[1]):
            u0 = u[k, j]
            u1 = u[k + 1, j]
            for i in range(n):
                work[i] += b0_cols[j, i] * u0 + b1_cols[j, i] * u1
        for i in range(n):
            x[i] = work[i]
        if keep:
            for i in range(n):
                history[k + 1, i] = x[i]
