"""The explicit integrator: classical 4th-order Runge–Kutta on the coupled equations.
(``vbikit.solve.kernels``: the equations and conventions.)"""
from __future__ import annotations

import numpy as np
from numba import njit

from vbikit.solve.kernels.bundles import _slot, _work
from vbikit.solve.kernels.lanes import _fetch, _keep, _width
from vbikit.solve.kernels.contact import _refresh, accelerations


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _stage(stage, h, tau, x0, v0, a_prev2, a_prev, sx, sv, lanes):
    """RK4 stage state: sx = x0 + τ(v0 + h·a_{stage−2}) (x0 + h·v0 at stage 1), sv = v0 + τ·a_{stage−1}."""
    n_l = _width(lanes, x0)
    for i in range(x0.shape[0]):
        if stage == 1:
            for lane in range(n_l):
                sx[i, lane] = x0[i, lane] + h * v0[i, lane]
        else:
            for lane in range(n_l):
                sx[i, lane] = x0[i, lane] + tau * (v0[i, lane] + h * a_prev2[i, lane])
        for lane in range(n_l):
            sv[i, lane] = v0[i, lane] + tau * a_prev[i, lane]


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _update(dt, x0, v0, a, x1, v1, lanes):
    """RK4 step for ẍ = a: x1 = x0 + dt(v0 + dt/6 (a1 + a2 + a3)), v1 = v0 + dt/6 (a1 + 2a2 + 2a3 + a4)."""
    n_l = _width(lanes, x0)
    for i in range(x0.shape[0]):
        for lane in range(n_l):
            x1[i, lane] = x0[i, lane] + dt * (v0[i, lane] + dt / 6.0 * (a[0, i, lane] + a[1, i, lane] + a[2, i, lane]))
        for lane in range(n_l):
            v1[i, lane] = v0[i, lane] + dt / 6.0 * (a[0, i, lane] + 2 * a[1, i, lane] + 2 * a[2, i, lane]
                                                    + a[3, i, lane])


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def rk4(dt, motion, modes, vehicles, points, road, unilateral, xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len,
        lanes, stride=1):
    """Classical 4th-order Runge–Kutta (the paper's integrator) on the first-order form of Eq. 9.

    ``motion`` is given at half steps (row 2n = t_n).  The output arrays (L, n_steps + 1, ·)
    are lane-major (each lane's history is contiguous) and hold the initial state at [:, 0] on
    entry; the state itself is kept lane-minor, (·, L), so that the lane loops vectorise.
    ``lanes``: (0,) for one lane, (0, 0) for many (module docstring).  ``stride``: keep every
    stride-th step in the outputs (their second axis has n_steps / stride + 1 rows;
    ``motion`` covers all n_steps).
    """
    n_l = 1 if len(lanes) == 1 else xi.shape[0]
    n_steps = (motion.travel.shape[0] - 1) // 2
    n_m = xi.shape[2]
    n_d = q.shape[2]
    n_cp = points.origin.size
    n_w = wheel_force.shape[2]
    ax = np.zeros((4, n_m, n_l))
    aq = np.zeros((4, n_d, n_l))
    x0 = np.empty((n_m, n_l)); v0 = np.empty((n_m, n_l)); y0 = np.empty((n_d, n_l)); w0 = np.empty((n_d, n_l))
    x1 = np.empty((n_m, n_l)); v1 = np.empty((n_m, n_l)); y1 = np.empty((n_d, n_l)); w1 = np.empty((n_d, n_l))
    row0 = np.int64(0)  # the start row, not a bare 0 (``vbikit.solve.kernels``: literal arguments)
    _fetch(xi, row0, x0, lanes); _fetch(dxi, row0, v0, lanes); _fetch(q, row0, y0, lanes); _fetch(dq, row0, w0, lanes)
    sx = np.zeros((n_m, n_l)); sv = np.zeros((n_m, n_l)); sq = np.zeros((n_d, n_l)); sw = np.zeros((n_d, n_l))
    work = _work(n_cp, n_d, n_l)
    wf = np.zeros((n_w, n_l))
    wl = np.zeros((n_w, n_l))
    # the three position slots (start, middle, end of a step), built once
    caches = (_slot(n_cp, n_m, n_l), _slot(n_cp, n_m, n_l), _slot(n_cp, n_m, n_l))
    stage_x = (ax[0], ax[1], ax[2], ax[3])
    stage_q = (aq[0], aq[1], aq[2], aq[3])
    cur = 0
    _refresh(caches[0], motion, row0, points)
    h = 0.5 * dt
    for n in range(n_steps + 1):
        accelerations(x0, v0, y0, w0, modes, vehicles, points, road, unilateral, caches[cur], work, stage_x[0],
                      stage_q[0], wf, wl, lanes)
        _keep(ddxi, n, stride, stage_x[0], lanes); _keep(ddq, n, stride, stage_q[0], lanes)
        _keep(wheel_force, n, stride, wf, lanes); _keep(wheel_len, n, stride, wl, lanes)
        if n == n_steps:
            break
        mid = (cur + 1) % 3
        end = (cur + 2) % 3
        _refresh(caches[mid], motion, 2 * n + 1, points)
        _refresh(caches[end], motion, 2 * n + 2, points)
        # stages 2-4: state = start + tau * (velocity + h * previous-but-one stage acceleration)
        for stage in range(1, 4):
            tau = h if stage < 3 else dt
            slot = mid if stage < 3 else end
            prev = stage - 1
            _stage(stage, h, tau, x0, v0, stage_x[max(prev - 1, 0)], stage_x[prev], sx, sv, lanes)
            _stage(stage, h, tau, y0, w0, stage_q[max(prev - 1, 0)], stage_q[prev], sq, sw, lanes)
            accelerations(sx, sv, sq, sw, modes, vehicles, points, road, unilateral, caches[slot], work,
                          stage_x[stage], stage_q[stage], wf, wl, lanes)
        _update(dt, x0, v0, ax, x1, v1, lanes)
        _update(dt, y0, w0, aq, y1, w1, lanes)
        x0, x1 = x1, x0
        v0, v1 = v1, v0
        y0, y1 = y1, y0
        w0, w1 = w1, w0
        _keep(xi, n + 1, stride, x0, lanes); _keep(dxi, n + 1, stride, v0, lanes)
        _keep(q, n + 1, stride, y0, lanes); _keep(dq, n + 1, stride, w0, lanes)
        cur = end
