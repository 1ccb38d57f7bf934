"""Compiled (numba) kernels of the coupled vehicle–bridge equations (paper Eq. 9, modal form).

State: bridge modal coordinates ξ (n_m) and vehicle coordinates q (n_d).  Contact point p of
wheel w sits at x_p = x_front − setback_p with mode-shape row φ_p, slope row φ'_p, spring k_p,
dashpot c_p, gap g_p, fixed load f0_p, road elevation r_p and rate ṙ_p = v·r'(x_p); the wheel's
lowest point moves as z_w = h_w·q.  Surface s_p = φ_p·ξ + r_p, ṡ_p = φ_p·ξ̇ + v φ'_p·ξ + ṙ_p
(v φ'_p·ξ: the convective part of the deck velocity under a moving point), penetration
δ_p = s_p − g_p − z_w, and

    F_p = k_p δ_p + c_p (ṡ_p − ż_w) + f0_p                        (compression > 0)
    gated points (disk tires, or all points with loss of contact): F_p = max(0, F_p) if δ_p > 0 else 0
    envelope wheels (rigid disk): only the point of largest s_p − g_p acts
    ξ̈ + 2ζω ξ̇ + ω² ξ = −Σ_p φ_pᵀ F_p
    M_v q̈ + C_v q̇ + K_v q = F_G + Σ_w h_wᵀ Σ_{p∈w} F_p

Lanes.  The state carries a last axis of L *lanes*: L crossings that share everything but the
road (a batch of a study), integrated together.  Everything that does not depend on the road
(positions, mode shapes at the contact points, the step) is computed once for all lanes, and
the per-lane arithmetic runs in contiguous inner loops that the compiler vectorises.  Each
lane's arithmetic is that of a single crossing (L = 1 is ``simulate``).  The argument
``lanes`` selects one of two compiled variants: a 1-tuple = one lane, a compile-time constant,
so that every lane loop disappears (and sums stay in registers); a 2-tuple = many lanes, L
read from the arrays at run time (the form the loop vectoriser handles; its vector loops take
32 doubles at a time, hence the callers' 32-lane calls padded to multiples of 8).  Hot loops
index 2-D arrays directly rather than through row views (measured faster here, ≈ 15 %).

Mode shapes along each wheel track are tabulated on a uniform grid with values and slopes and
evaluated by cubic Hermite interpolation (``vbikit.solve.tabulate``).  Road elevations are
interpolated linearly in the road's stations inside the kernels.  Both lazily: a gated point
that no lane can bring into contact (r_max − g_p − min z_w + B ≤ 0, with r_max the highest
road elevation and B = max_lanes Σ_m max|φ_m|·|ξ_m| the largest possible deck displacement)
needs neither.

Argument bundles (tuples, to keep signatures short):
  bridge = (omega, zeta, span, grid_h, V, S, amp)
  vehicle = (m_inv or mass, c_v, k_v, f_g, wheel_rows, wheel_first, wheel_count, wheel_envelope)
  points = (setback, track, k, c, f0, gap, gated, wheel, width, slope_range)
  road = (stations (n_s,), elevations (n_lines, n_s, L), line (n_cp,) wheel line of each point, r_max)
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def shape_point(x, track, grid_h, V, S, phi_row, dphi_row):
    """φ(x) and ∂φ/∂x(x) of one point on tabulated track ``track`` (cubic Hermite)."""
    n_grid = V.shape[1]
    u = x / grid_h
    i = int(u)
    if i > n_grid - 2:
        i = n_grid - 2
    t = u - i
    t2 = t * t
    t3 = t2 * t
    h00 = 2 * t3 - 3 * t2 + 1
    h10 = (t3 - 2 * t2 + t) * grid_h
    h01 = -2 * t3 + 3 * t2
    h11 = (t3 - t2) * grid_h
    d00 = (6 * t2 - 6 * t) / grid_h
    d10 = 3 * t2 - 4 * t + 1
    d01 = (-6 * t2 + 6 * t) / grid_h
    d11 = 3 * t2 - 2 * t
    for m in range(V.shape[2]):
        a0 = V[track, i, m]
        a1 = V[track, i + 1, m]
        b0 = S[track, i, m]
        b1 = S[track, i + 1, m]
        phi_row[m] = h00 * a0 + h10 * b0 + h01 * a1 + h11 * b1
        dphi_row[m] = d00 * a0 + d10 * b0 + d01 * a1 + d11 * b1


@njit(cache=True, fastmath=True, error_model="numpy")
def shapes_at(xf, cp_setback, cp_track, span, grid_h, V, S, phi, dphi, on):
    """Mode-shape rows φ_p, φ'_p of every contact point for front-axle position ``xf`` (eager)."""
    for p in range(cp_setback.size):
        x = xf - cp_setback[p]
        on[p] = 0.0 <= x <= span
        if on[p]:
            shape_point(x, cp_track[p], grid_h, V, S, phi[p], dphi[p])


@njit(cache=True, inline="always")
def _width(lanes, a):
    """The lane count L: a compile-time 1 when ``lanes`` is a 1-tuple (one crossing: every lane
    loop disappears), else the last dimension of ``a`` (a runtime count, which the compiler's
    loop vectoriser handles best; widths that are multiples of 32 fill its vector loops)."""
    return 1 if len(lanes) == 1 else a.shape[-1]


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def road_point(x, vel, p, road, idx, rv, rr, lanes):
    """Road elevation ``rv[p, :]`` [m] and rate ``rr[p, :]`` = v·dr/dx [m/s] of every lane at
    position ``x`` [m] of point ``p`` (linear interpolation; ``idx[p]`` is the point's station
    pointer, −1 before its first use; positions of a point never decrease)."""
    n_l = _width(lanes, rv)
    stations, elev, line, r_max = road
    n_s = stations.size
    i = idx[p]
    if i < 0:
        i = max(0, min(n_s - 2, np.searchsorted(stations, x, side="right") - 1))
    while i < n_s - 2 and stations[i + 1] <= x:
        i += 1
    idx[p] = i
    z = elev[line[p]]
    dx = x - stations[i]
    inv = 1.0 / (stations[i + 1] - stations[i])
    for lane in range(n_l):
        slope = (z[i + 1, lane] - z[i, lane]) * inv
        rv[p, lane] = z[i, lane] + slope * dx
        rr[p, lane] = slope * vel


@njit(cache=True, fastmath=True, error_model="numpy")
def road_at(xf, vel, setback, road, idx, rv, rr, lanes):
    """Road elevation and rate (n_cp, L) under every contact point at front position ``xf``
    (``idx``: the points' station pointers, see :func:`road_point`)."""
    for p in range(setback.size):
        road_point(xf - setback[p], vel, p, road, idx, rv, rr, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _deck(phi, dphi, p, vel, xi, dxi, s, dr, sd, lanes):
    """Add the deck's displacement φ_p·ξ to ``s``, its velocity φ_p·ξ̇ to ``dr`` and the convective
    rate v φ'_p·ξ to ``sd`` (rows (1, L)) of point ``p``, per lane."""
    if len(lanes) == 1:  # one lane: the mode sums in registers
        a = s[0, 0]
        b = dr[0, 0]
        c = sd[0, 0]
        for m in range(xi.shape[0]):
            a += phi[p, m] * xi[m, 0]
            b += phi[p, m] * dxi[m, 0]
            c += vel * dphi[p, m] * xi[m, 0]
        s[0, 0] = a
        dr[0, 0] = b
        sd[0, 0] = c
        return
    for m in range(xi.shape[0]):  # many lanes: one array per loop, so that they vectorise
        _axpy(phi[p, m], xi, m, s, 0, lanes)
    for m in range(xi.shape[0]):
        _axpy(phi[p, m], dxi, m, dr, 0, lanes)
    for m in range(xi.shape[0]):
        _axpy(vel * dphi[p, m], xi, m, sd, 0, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def contact_forces(xi, dxi, q, dq, vel, xf, bridge, vehicle, points, road, unilateral, cache, work, wheel_force,
                   wheel_len, lanes):
    """Contact forces F_p [N] (``force`` (n_cp, L), compression > 0), per-wheel sums ``wheel_force``
    and patch lengths ``wheel_len`` [m] (n_w, L), ``active`` flags, and ``used[p]``: the point's
    force was evaluated (else it is 0 in every lane).

    ``cache`` = (phi, dphi, have, rv, rr, have_r): mode shapes and road (elevation, rate) of the
    points at front position ``xf``, filled on first use.  ``work`` = (idx, force, active, used,
    scratch (5, L), rhs (n_d, L)): station pointers, outputs and scratch space.  ``lanes``: (0,)
    for one lane, (0, 0) for many (see the module docstring).
    """
    phi, dphi, have, rv, rr, have_r = cache
    idx, force, active, used, scratch, rhs = work
    omega, zeta, span, grid_h, V, S, amp = bridge
    m_x, c_v, k_v, f_g, wheel_rows, wheel_first, wheel_count, wheel_envelope = vehicle
    setback, track, cp_k, cp_c, cp_f0, gap, gated, cp_wheel, width, slope_range = points
    r_max = road[3]
    n_m = xi.shape[0]
    n_d = q.shape[0]
    n_l = _width(lanes, xi)
    zw, dzw = scratch[0], scratch[1]
    s, sd, dr = scratch[2:3], scratch[3:4], scratch[4:5]  # (1, L) rows for 2-D indexing
    b_max = 0.0
    for lane in range(n_l):
        b = 0.0
        for m in range(n_m):
            b += amp[m] * abs(xi[m, lane])
        b_max = max(b_max, b)
    for w in range(wheel_rows.shape[0]):
        for lane in range(n_l):
            zw[lane] = 0.0
            dzw[lane] = 0.0
        for j in range(n_d):
            h = wheel_rows[w, j]
            if h != 0.0:
                for lane in range(n_l):
                    zw[lane] += h * q[j, lane]
                    dzw[lane] += h * dq[j, lane]
        zw_min = zw[0]
        for lane in range(n_l):
            zw_min = min(zw_min, zw[lane])
            wheel_force[w, lane] = 0.0
            wheel_len[w, lane] = 0.0
        first = wheel_first[w]
        last = first + wheel_count[w]
        for p in range(first, last):
            used[p] = False
            x = xf - setback[p]
            onb = 0.0 <= x <= span
            gate = gated[p] or (unilateral and cp_k[p] > 0.0)
            if gate and not wheel_envelope[w] and r_max - gap[p] - zw_min + (b_max if onb else 0.0) <= 0.0:
                for lane in range(n_l):
                    force[p, lane] = 0.0
                    active[p, lane] = False
                continue  # no lane can touch the surface here
            if not have_r[p]:
                road_point(x, vel, p, road, idx, rv, rr, lanes)
                have_r[p] = True
            if onb and not have[p]:
                shape_point(x, track[p], grid_h, V, S, phi[p], dphi[p])
                have[p] = True
            used[p] = True
            if wheel_envelope[w]:
                for lane in range(n_l):
                    force[p, lane] = 0.0
                    active[p, lane] = False
                continue  # the rigid disk's contact point is chosen below, per lane
            # one store per lane loop, so that the compiler vectorises them (aliasing checks)
            for lane in range(n_l):
                s[0, lane] = rv[p, lane]
                sd[0, lane] = rr[p, lane]  # v · r'(x_p)
                dr[0, lane] = 0.0  # ∂u_b/∂t at the fixed point x_p
            if onb:
                _deck(phi, dphi, p, vel, xi, dxi, s, dr, sd, lanes)
            k = cp_k[p]
            c = cp_c[p]
            f0 = cp_f0[p]
            g = gap[p]
            wd = width[p]
            for lane in range(n_l):
                pen = s[0, lane] - g - zw[lane]
                f = k * pen + c * (sd[0, lane] + dr[0, lane] - dzw[lane]) + f0
                force[p, lane] = f if not gate or (pen > 0.0 and f > 0.0) else 0.0
            for lane in range(n_l):
                active[p, lane] = not gate or force[p, lane] > 0.0  # a gated point acts iff it presses
            _axpy(1.0, force, p, wheel_force, w, lanes)
            for lane in range(n_l):
                wheel_len[w, lane] += wd if active[p, lane] else 0.0
        if wheel_envelope[w]:
            _envelope(w, first, last, xi, dxi, vel, xf, bridge, points, phi, dphi, rv, rr, zw, dzw, force,
                      wheel_force, active, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _envelope(w, first, last, xi, dxi, vel, xf, bridge, points, phi, dphi, rv, rr, zw, dzw, force, wheel_force,
              active, lanes):
    """Rigid-disk wheel ``w``: per lane, only the point of highest surface s_p − g_p acts; its rate
    is the deck velocity + v·e', e' the surface slope clamped to the circle's slopes."""
    n_l = _width(lanes, xi)
    span = bridge[2]
    setback, track, cp_k, cp_c, cp_f0, gap, gated, cp_wheel, width, slope_range = points
    n_m = xi.shape[0]
    for lane in range(n_l):
        p_env = -1
        s_env = -1e300
        sd_env = 0.0
        for p in range(first, last):
            s = rv[p, lane]
            sd = rr[p, lane]
            deck_rate = 0.0
            x = xf - setback[p]
            if 0.0 <= x <= span:
                for m in range(n_m):
                    s += phi[p, m] * xi[m, lane]
                    deck_rate += phi[p, m] * dxi[m, lane]
                    sd += vel * dphi[p, m] * xi[m, lane]
            if s - gap[p] > s_env:
                s_env = s - gap[p]
                sd_env = deck_rate + min(max(sd, vel * slope_range[p, 0]), vel * slope_range[p, 1])
                p_env = p
        if p_env >= 0:
            pen = s_env - zw[lane]
            f = cp_k[p_env] * pen + cp_c[p_env] * (sd_env - dzw[lane]) + cp_f0[p_env]
            if pen > 0.0 and f > 0.0:
                force[p_env, lane] = f
                active[p_env, lane] = True
                wheel_force[w, lane] = f


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def accelerations(xi, dxi, q, dq, vel, xf, bridge, vehicle, points, road, unilateral, cache, work, ddxi, ddq,
                  wheel_force, wheel_len, lanes):
    """ξ̈ (n_m, L), q̈ (n_d, L) and contact forces for a given state (the right-hand side of Eq. 9)."""
    contact_forces(xi, dxi, q, dq, vel, xf, bridge, vehicle, points, road, unilateral, cache, work, wheel_force,
                   wheel_len, lanes)
    phi = cache[0]
    force, used, rhs = work[1], work[3], work[5]
    omega, zeta, span, grid_h, V, S, amp = bridge
    m_inv, c_v, k_v, f_g, wheel_rows, wheel_first, wheel_count, wheel_envelope = vehicle
    setback = points[0]
    n_m = xi.shape[0]
    n_d = q.shape[0]
    n_l = _width(lanes, xi)
    for m in range(n_m):
        a = 2.0 * zeta[m] * omega[m]
        b = omega[m] * omega[m]
        for lane in range(n_l):
            ddxi[m, lane] = -a * dxi[m, lane] - b * xi[m, lane]
    for p in range(force.shape[0]):
        if used[p]:
            x = xf - setback[p]
            if 0.0 <= x <= span:
                for m in range(n_m):
                    _axpy(-phi[p, m], force, p, ddxi, m, lanes)
    if n_d == 0:
        return
    for i in range(n_d):
        for lane in range(n_l):
            rhs[i, lane] = f_g[i]
    _gemv(-1.0, c_v, dq, rhs, lanes, False)
    _gemv(-1.0, k_v, q, rhs, lanes, False)
    _gemv(1.0, wheel_rows, wheel_force, rhs, lanes, True)
    for i in range(n_d):
        for lane in range(n_l):
            ddq[i, lane] = 0.0
    _gemv(1.0, m_inv, rhs, ddq, lanes, False)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _gemv(alpha, a, x, y, lanes, transpose):
    """y += α·A·x (or α·Aᵀ·x) for every lane (x, y: (·, L)); zero entries of A are skipped."""
    n_i = a.shape[1] if transpose else a.shape[0]
    n_j = a.shape[0] if transpose else a.shape[1]
    if len(lanes) == 1:  # one lane: accumulate in a register
        for i in range(n_i):
            acc = y[i, 0]
            for j in range(n_j):
                aij = a[j, i] if transpose else a[i, j]
                if aij != 0.0:
                    acc += alpha * aij * x[j, 0]
            y[i, 0] = acc
        return
    for i in range(n_i):  # many lanes: the lanes innermost, vectorised
        for j in range(n_j):
            aij = a[j, i] if transpose else a[i, j]
            if aij != 0.0:
                _axpy(alpha * aij, x, j, y, i, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _axpy(a, x, i, y, k, lanes):
    """y[k, :] += a·x[i, :] over the lanes (2-D indexing rather than row views)."""
    for lane in range(_width(lanes, y)):
        y[k, lane] += a * x[i, lane]


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


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _store(out, n, state, lanes):
    """out[lane, n, i] = state[i, lane]: a lane-major output row from the lane-minor state."""
    n_l = _width(lanes, state)
    for i in range(state.shape[0]):
        for lane in range(n_l):
            out[lane, n, i] = state[i, lane]


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def rk4(dt, xf, vel, bridge, vehicle, points, road, unilateral, xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len,
        lanes):
    """Classical 4th-order Runge–Kutta (the paper's integrator) on the first-order form of Eq. 9.

    ``xf``, ``vel`` are given at half steps (index 2n = t_n).  The output arrays (L, n_steps + 1, ·)
    are lane-major (each lane's history is contiguous) and hold the initial state at [:, 0] on
    entry; the state itself is kept lane-minor, (·, L), so that the lane loops vectorise.
    ``lanes``: (0,) for one lane, (0, 0) for many (module docstring).
    """
    n_l = 1 if len(lanes) == 1 else xi.shape[0]
    n_steps = xi.shape[1] - 1
    n_m = xi.shape[2]
    n_d = q.shape[2]
    n_cp = points[0].size
    n_w = wheel_force.shape[2]
    phi = np.zeros((3, n_cp, n_m))
    dphi = np.zeros((3, n_cp, n_m))
    have = np.zeros((3, n_cp), dtype=np.bool_)
    rv = np.zeros((3, n_cp, n_l))
    rr = np.zeros((3, n_cp, n_l))
    have_r = np.zeros((3, n_cp), dtype=np.bool_)
    idx = np.full(n_cp, -1, dtype=np.int64)
    ax = np.zeros((4, n_m, n_l))
    aq = np.zeros((4, n_d, n_l))
    x0 = np.empty((n_m, n_l)); v0 = np.empty((n_m, n_l)); y0 = np.empty((n_d, n_l)); w0 = np.empty((n_d, n_l))
    x1 = np.empty((n_m, n_l)); v1 = np.empty((n_m, n_l)); y1 = np.empty((n_d, n_l)); w1 = np.empty((n_d, n_l))
    for lane in range(n_l):
        x0[:, lane] = xi[lane, 0]; v0[:, lane] = dxi[lane, 0]; y0[:, lane] = q[lane, 0]; w0[:, lane] = dq[lane, 0]
    sx = np.zeros((n_m, n_l)); sv = np.zeros((n_m, n_l)); sq = np.zeros((n_d, n_l)); sw = np.zeros((n_d, n_l))
    work = (idx, np.zeros((n_cp, n_l)), np.zeros((n_cp, n_l), dtype=np.bool_), np.zeros(n_cp, dtype=np.bool_),
            np.zeros((5, n_l)), np.zeros((n_d, n_l)))
    wf = np.zeros((n_w, n_l))
    wl = np.zeros((n_w, n_l))
    # the three position slots' caches, built once
    caches = ((phi[0], dphi[0], have[0], rv[0], rr[0], have_r[0]), (phi[1], dphi[1], have[1], rv[1], rr[1], have_r[1]),
              (phi[2], dphi[2], have[2], rv[2], rr[2], have_r[2]))
    stage_x = (ax[0], ax[1], ax[2], ax[3])
    stage_q = (aq[0], aq[1], aq[2], aq[3])
    cur = 0
    h = 0.5 * dt
    for n in range(n_steps + 1):
        accelerations(x0, v0, y0, w0, vel[2 * n], xf[2 * n], bridge, vehicle, points, road, unilateral,
                      caches[cur], work, stage_x[0], stage_q[0], wf, wl, lanes)
        _store(ddxi, n, stage_x[0], lanes); _store(ddq, n, stage_q[0], lanes)
        _store(wheel_force, n, wf, lanes); _store(wheel_len, n, wl, lanes)
        if n == n_steps:
            break
        mid = (cur + 1) % 3
        end = (cur + 2) % 3
        for p in range(n_cp):
            have[mid, p] = False
            have[end, p] = False
            have_r[mid, p] = False
            have_r[end, p] = False
        # stages 2-4: state = start + tau * (velocity + h * previous-but-one stage acceleration)
        for stage in range(1, 4):
            tau = h if stage < 3 else dt
            ih = 2 * n + (1 if stage < 3 else 2)
            slot = mid if stage < 3 else end
            prev = stage - 1
            _stage(stage, h, tau, x0, v0, stage_x[max(prev - 1, 0)], stage_x[prev], sx, sv, lanes)
            _stage(stage, h, tau, y0, w0, stage_q[max(prev - 1, 0)], stage_q[prev], sq, sw, lanes)
            accelerations(sx, sv, sq, sw, vel[ih], xf[ih], bridge, vehicle, points, road, unilateral,
                          caches[slot], work, stage_x[stage], stage_q[stage], wf, wl, lanes)
        _update(dt, x0, v0, ax, x1, v1, lanes)
        _update(dt, y0, w0, aq, y1, w1, lanes)
        x0, x1 = x1, x0
        v0, v1 = v1, v0
        y0, y1 = y1, y0
        w0, w1 = w1, w0
        _store(xi, n + 1, x0, lanes); _store(dxi, n + 1, v0, lanes)
        _store(q, n + 1, y0, lanes); _store(dq, n + 1, w0, lanes)
        cur = end


@njit(cache=True, fastmath=True, error_model="numpy")
def assemble(vel, xf, r, rdot, bridge, vehicle, points, phi, dphi, have, active, mass, damp, stiff, load):
    """Coupled system matrices of Eq. 9 at one instant, M ü + C u̇ + K u = F with u = [ξ; q],
    for the contact points flagged ``active`` (their linear law F_p = k δ + c δ̇ + f0 holds)."""
    omega, zeta, span, grid_h, V, S, amp = bridge
    m_v, c_v, k_v, f_g, wheel_rows, wheel_first, wheel_count, wheel_envelope = vehicle
    setback, track, cp_k, cp_c, cp_f0, gap, gated, cp_wheel, width, slope_range = points
    n_m = omega.size
    n_d = f_g.size
    mass[:, :] = 0.0
    damp[:, :] = 0.0
    stiff[:, :] = 0.0
    load[:] = 0.0
    for m in range(n_m):
        mass[m, m] = 1.0
        damp[m, m] = 2.0 * zeta[m] * omega[m]
        stiff[m, m] = omega[m] * omega[m]
    for i in range(n_d):
        load[n_m + i] = f_g[i]
        for j in range(n_d):
            mass[n_m + i, n_m + j] = m_v[i, j]
            damp[n_m + i, n_m + j] = c_v[i, j]
            stiff[n_m + i, n_m + j] = k_v[i, j]
    for p in range(cp_k.size):
        if not active[p]:
            continue
        k = cp_k[p]
        c = cp_c[p]
        ext = k * (r[p] - gap[p]) + c * rdot[p] + cp_f0[p]
        h = wheel_rows[cp_wheel[p]]
        for i in range(n_d):
            load[n_m + i] += h[i] * ext
            for j in range(n_d):
                stiff[n_m + i, n_m + j] += k * h[i] * h[j]
                damp[n_m + i, n_m + j] += c * h[i] * h[j]
        x = xf - setback[p]
        if not 0.0 <= x <= span:
            continue
        if not have[p]:
            shape_point(x, track[p], grid_h, V, S, phi[p], dphi[p])
            have[p] = True
        f = phi[p]
        g = dphi[p]
        for a in range(n_m):
            load[a] -= f[a] * ext
            for b in range(n_m):
                stiff[a, b] += k * f[a] * f[b] + c * vel * f[a] * g[b]
                damp[a, b] += c * f[a] * f[b]
            for j in range(n_d):
                stiff[a, n_m + j] -= k * f[a] * h[j]
                damp[a, n_m + j] -= c * f[a] * h[j]
                stiff[n_m + j, a] -= k * h[j] * f[a] + c * vel * h[j] * g[a]
                damp[n_m + j, a] -= c * h[j] * f[a]


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def newmark(dt, xf, vel, bridge, vehicle, points, road, unilateral, xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len,
            active0, max_iterations):
    """Newmark average acceleration (γ = 1/2, β = 1/4), unconditionally stable for the linear system.

    Contact is piecewise linear (points enter and leave contact), so each step iterates on the
    set of active points: assemble with the current set, solve, re-evaluate the contact forces,
    repeat until the set is unchanged.  Returns the number of steps whose active set did not
    settle within ``max_iterations``.  Same array conventions as :func:`rk4`, one lane (L = 1);
    ``vehicle`` carries the mass matrix M in slot 0.
    """
    n_steps = xi.shape[1] - 1
    n_m = xi.shape[2]
    n_d = q.shape[2]
    n_cp = points[0].size
    n_w = wheel_force.shape[2]
    setback = points[0]
    n = n_m + n_d
    phi = np.zeros((n_cp, n_m))
    dphi = np.zeros((n_cp, n_m))
    have = np.zeros(n_cp, dtype=np.bool_)
    rv = np.zeros((n_cp, 1)); rr = np.zeros((n_cp, 1))
    have_r = np.ones(n_cp, dtype=np.bool_)
    idx = np.full(n_cp, -1, dtype=np.int64)
    r1 = rv.reshape(n_cp); rr1 = rr.reshape(n_cp)
    mass = np.zeros((n, n)); damp = np.zeros((n, n)); stiff = np.zeros((n, n)); load = np.zeros(n)
    u = np.zeros(n); v = np.zeros(n); a = np.zeros(n)
    sx = np.zeros((n_m, 1)); sv = np.zeros((n_m, 1)); sq = np.zeros((n_d, 1)); sw = np.zeros((n_d, 1))
    wf = np.zeros((n_w, 1)); wl = np.zeros((n_w, 1))
    active = active0.copy()
    new_active = np.zeros((n_cp, 1), dtype=np.bool_)
    cache = (phi, dphi, have, rv, rr, have_r)
    work = (idx, np.zeros((n_cp, 1)), new_active, np.zeros(n_cp, dtype=np.bool_), np.zeros((5, 1)), np.zeros((n_d, 1)))
    u[:n_m] = xi[0, 0]; u[n_m:] = q[0, 0]; v[:n_m] = dxi[0, 0]; v[n_m:] = dq[0, 0]
    road_at(xf[0], vel[0], setback, road, idx, rv, rr, (0,))
    assemble(vel[0], xf[0], r1, rr1, bridge, vehicle, points, phi, dphi, have, active, mass, damp, stiff, load)
    a[:] = np.linalg.solve(mass, load - damp @ v - stiff @ u)
    sx[:, 0] = u[:n_m]; sv[:, 0] = v[:n_m]; sq[:, 0] = u[n_m:]; sw[:, 0] = v[n_m:]
    contact_forces(sx, sv, sq, sw, vel[0], xf[0], bridge, vehicle, points, road, unilateral, cache, work,
                   wf, wl, (0,))
    _store(wheel_force, 0, wf, (0,)); _store(wheel_len, 0, wl, (0,))
    ddxi[0, 0] = a[:n_m]; ddq[0, 0] = a[n_m:]
    unsettled = 0
    for s in range(1, n_steps + 1):
        i2 = 2 * s
        have[:] = False
        road_at(xf[i2], vel[i2], setback, road, idx, rv, rr, (0,))
        u_p = u + dt * v + 0.25 * dt * dt * a
        v_p = v + 0.5 * dt * a
        settled = False
        for _ in range(max_iterations):
            assemble(vel[i2], xf[i2], r1, rr1, bridge, vehicle, points, phi, dphi, have, active, mass, damp, stiff,
                     load)
            lhs = mass + 0.5 * dt * damp + 0.25 * dt * dt * stiff
            a_new = np.linalg.solve(lhs, load - damp @ v_p - stiff @ u_p)
            u_new = u_p + 0.25 * dt * dt * a_new
            v_new = v_p + 0.5 * dt * a_new
            sx[:, 0] = u_new[:n_m]; sv[:, 0] = v_new[:n_m]; sq[:, 0] = u_new[n_m:]; sw[:, 0] = v_new[n_m:]
            contact_forces(sx, sv, sq, sw, vel[i2], xf[i2], bridge, vehicle, points, road, unilateral, cache, work,
                           wf, wl, (0,))
            same = True
            for p in range(n_cp):
                if new_active[p, 0] != active[p]:
                    same = False
                    break
            active[:] = new_active[:, 0]
            if same:
                settled = True
                break
        if not settled:
            unsettled += 1
        _store(wheel_force, s, wf, (0,)); _store(wheel_len, s, wl, (0,))
        u = u_new; v = v_new; a = a_new
        xi[0, s] = u[:n_m]; q[0, s] = u[n_m:]; dxi[0, s] = v[:n_m]; dq[0, s] = v[n_m:]
        ddxi[0, s] = a[:n_m]; ddq[0, s] = a[n_m:]
    return unsettled


@njit(cache=True, fastmath=True, error_model="numpy")
def static_modal_history(xf, setback, track, loads, span, grid_h, V, S):
    """ξ_st(t) = −Σ_p φ(x_p(t)) P_p / ω² numerator: returns Σ_p φ(x_p(t)) P_p (n_t, n_m) for
    downward point loads P_p [N] at x_p = xf(t) − setback_p (tabulated shapes, as the solver)."""
    n_m = V.shape[2]
    out = np.zeros((xf.size, n_m))
    phi = np.zeros(n_m)
    dphi = np.zeros(n_m)
    for t in range(xf.size):
        for p in range(setback.size):
            if loads[p] == 0.0:
                continue
            x = xf[t] - setback[p]
            if 0.0 <= x <= span:
                shape_point(x, track[p], grid_h, V, S, phi, dphi)
                for m in range(n_m):
                    out[t, m] += phi[m] * loads[p]
    return out
