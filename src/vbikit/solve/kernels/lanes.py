"""Lane-wise array helpers of the kernels: products, copies and stored outputs over the last (lane)
axis. (``vbikit.solve.kernels``: the equations and conventions.)"""
from __future__ import annotations

from numba import njit

from vbikit.solve.kernels.bundles import _internal

#: the ``lanes`` argument of a one-lane call (its own compiled variant: every lane loop disappears)
ONE_LANE = (0,)
#: the ``lanes`` argument of a many-lane call (L read from the arrays at run time, L = 1 too): the only
#: one ``implicit``, ``road_at`` and ``contact_forces`` are called with from Python (``vbikit.solve.kernels``)
MANY_LANES = (0, 0)


@njit(cache=True, inline="always")
def _width(lanes, a):
    """The lane count L: a compile-time 1 when ``lanes`` is a 1-tuple (one crossing: every lane
    loop disappears), else the last dimension of ``a`` (a runtime count, which the compiler's
    loop vectoriser handles best; widths that are multiples of 32 fill its vector loops)."""
    return 1 if len(lanes) == 1 else a.shape[-1]


@_internal
def _gemv(alpha, a, x, y, lanes, transpose):
    """y += α·A·x (or α·Aᵀ·x) for every lane (x, y: (·, L)); zero entries of A are skipped.  One
    lane accumulates in a register; many lanes run ``_gemv_lanes`` (the lanes innermost).  Compiled
    once and called (inlining it at each call site cost seconds of compile time, no run time)."""
    if len(lanes) == 1:  # one lane: accumulate in a register
        n_i = a.shape[1] if transpose else a.shape[0]
        n_j = a.shape[0] if transpose else a.shape[1]
        for i in range(n_i):
            acc = y[i, 0]
            for j in range(n_j):
                aij = a[j, i] if transpose else a[i, j]
                if aij != 0.0:
                    acc += alpha * aij * x[j, 0]
            y[i, 0] = acc
    else:
        _gemv_lanes(alpha, a, x, y, lanes, transpose)


@_internal
def _gemv_lanes(alpha, a, x, y, lanes, transpose):
    """``_gemv`` for many lanes: the lanes innermost, vectorised."""
    n_i = a.shape[1] if transpose else a.shape[0]
    n_j = a.shape[0] if transpose else a.shape[1]
    for i in range(n_i):
        for j in range(n_j):
            aij = a[j, i] if transpose else a[i, j]
            if aij != 0.0:
                _axpy(alpha * aij, x, j, y, i, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _axpy(a, x, i, y, k, lanes):
    """y[k, :] += a·x[i, :] over the lanes (2-D indexing rather than row views)."""
    for lane in range(_width(lanes, y)):
        y[k, lane] += a * x[i, lane]


@_internal
def _store(out, n, state, lanes):
    """out[lane, n, i] = state[i, lane]: a lane-major output row from the lane-minor state."""
    n_l = _width(lanes, state)
    for i in range(state.shape[0]):
        for lane in range(n_l):
            out[lane, n, i] = state[i, lane]


@_internal
def _fetch(src, n, state, lanes):
    """state[i, lane] = src[lane, n, i]: the inverse of ``_store`` (explicit loops: slice
    assignments would compile numba's shape-mismatch error path, seconds of compile time)."""
    n_l = _width(lanes, state)
    for i in range(state.shape[0]):
        for lane in range(n_l):
            state[i, lane] = src[lane, n, i]


@_internal
def _copy(src, dst, lanes):
    """dst[i, :] = src[i, :] (explicit loops, see ``_fetch``)."""
    n_l = _width(lanes, src)
    for i in range(src.shape[0]):
        for lane in range(n_l):
            dst[i, lane] = src[i, lane]


@_internal
def _keep(out, n, stride, state, lanes):
    """Store the state of step ``n`` in row n / stride when ``stride`` divides n (thinned histories)."""
    if n % stride == 0:
        _store(out, n // stride, state, lanes)


@_internal
def _keep_step(xi, dxi, ddxi, q, dq, ddq, wheel_force, wheel_len, n, stride, x, v, a, y, w, b, wf, wl, lanes):
    """``_keep`` of every output of step ``n`` (one call a step)."""
    _keep(xi, n, stride, x, lanes); _keep(dxi, n, stride, v, lanes); _keep(ddxi, n, stride, a, lanes)
    _keep(q, n, stride, y, lanes); _keep(dq, n, stride, w, lanes); _keep(ddq, n, stride, b, lanes)
    _keep(wheel_force, n, stride, wf, lanes); _keep(wheel_len, n, stride, wl, lanes)


@_internal
def _combine(a, x, b, y, c, z, d, u, out, lanes):
    """out[m, :] = a_m x[m, :] + b_m y[m, :] + c_m z[m, :] + d_m u[m, :] (per-row coefficients)."""
    n_l = _width(lanes, x)
    for m in range(x.shape[0]):
        am = a[m]
        bm = b[m]
        cm = c[m]
        dm = d[m]
        for lane in range(n_l):
            out[m, lane] = am * x[m, lane] + bm * y[m, lane] + cm * z[m, lane] + dm * u[m, lane]
