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

Mode shapes along each wheel track are tabulated on a uniform grid with values and slopes and
evaluated by cubic Hermite interpolation (``vbikit.solve.tabulate``), lazily: a gated point
that cannot touch the surface (r_p − g_p − z_w + B ≤ 0 with B = Σ_m max|φ_m|·|ξ_m| the largest
possible deck displacement) needs no mode shapes.

Argument bundles (tuples, to keep signatures short):
  bridge = (omega, zeta, span, grid_h, V, S, amp)
  vehicle = (m_inv or mass, c_v, k_v, f_g, wheel_rows, wheel_first, wheel_count, wheel_envelope)
  points = (setback, track, k, c, f0, gap, gated, wheel, width, slope_range)
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


@njit(cache=True, fastmath=True, error_model="numpy")
def contact_forces(xi, dxi, q, dq, vel, xf, r, rdot, bridge, vehicle, points, unilateral, phi, dphi, have,
                   force, wheel_force, wheel_len, active):
    """Contact forces F_p [N] (compression > 0), per-wheel sums, patch lengths [m] and active flags.

    ``phi``/``dphi``/``have`` cache the mode shapes of the points at front position ``xf``;
    shapes are computed on first use.
    """
    omega, zeta, span, grid_h, V, S, amp = bridge
    m_x, c_v, k_v, f_g, wheel_rows, wheel_first, wheel_count, wheel_envelope = vehicle
    setback, track, cp_k, cp_c, cp_f0, gap, gated, cp_wheel, width, slope_range = points
    n_m = xi.size
    n_d = q.size
    bound = 0.0
    for m in range(n_m):
        bound += amp[m] * abs(xi[m])
    for w in range(wheel_rows.shape[0]):
        zw = 0.0
        dzw = 0.0
        for j in range(n_d):
            zw += wheel_rows[w, j] * q[j]
            dzw += wheel_rows[w, j] * dq[j]
        wheel_force[w] = 0.0
        wheel_len[w] = 0.0
        first = wheel_first[w]
        last = first + wheel_count[w]
        best = -1e300
        if wheel_envelope[w]:
            for p in range(first, last):
                best = max(best, r[p] - gap[p])
        p_env = -1
        s_env = -1e300
        sd_env = 0.0
        for p in range(first, last):
            force[p] = 0.0
            active[p] = False
            gate = gated[p] or (unilateral and cp_k[p] > 0.0)
            x = xf - setback[p]
            onb = 0.0 <= x <= span
            reach = bound if onb else 0.0
            if wheel_envelope[w]:
                if r[p] - gap[p] + reach < best - bound:
                    continue  # cannot be the highest point of the envelope
            elif gate and r[p] - gap[p] - zw + reach <= 0.0:
                continue  # cannot touch the surface
            s = r[p]
            sd = rdot[p]  # v · r'(x_p)
            deck_rate = 0.0  # ∂u_b/∂t at the fixed point x_p
            if onb:
                if not have[p]:
                    shape_point(x, track[p], grid_h, V, S, phi[p], dphi[p])
                    have[p] = True
                for m in range(n_m):
                    s += phi[p, m] * xi[m]
                    deck_rate += phi[p, m] * dxi[m]
                    sd += vel * dphi[p, m] * xi[m]
            if wheel_envelope[w]:
                if s - gap[p] > s_env:
                    s_env = s - gap[p]
                    # envelope rate: deck velocity + v·e', e' = surface slope clamped to the circle's slopes
                    sd_env = deck_rate + min(max(sd, vel * slope_range[p, 0]), vel * slope_range[p, 1])
                    p_env = p
                continue
            sd += deck_rate
            pen = s - gap[p] - zw
            f = cp_k[p] * pen + cp_c[p] * (sd - dzw) + cp_f0[p]
            if gate:
                if pen <= 0.0 or f <= 0.0:
                    continue
            force[p] = f
            active[p] = True
            wheel_force[w] += f
            wheel_len[w] += width[p]
        if wheel_envelope[w] and p_env >= 0:
            pen = s_env - zw
            f = cp_k[p_env] * pen + cp_c[p_env] * (sd_env - dzw) + cp_f0[p_env]
            if pen > 0.0 and f > 0.0:
                force[p_env] = f
                active[p_env] = True
                wheel_force[w] = f


@njit(cache=True, fastmath=True, error_model="numpy")
def accelerations(xi, dxi, q, dq, vel, xf, r, rdot, bridge, vehicle, points, unilateral, phi, dphi, have,
                  ddxi, ddq, force, wheel_force, wheel_len, active, rhs):
    """ξ̈, q̈ and contact forces for a given state (the right-hand side of Eq. 9)."""
    contact_forces(xi, dxi, q, dq, vel, xf, r, rdot, bridge, vehicle, points, unilateral, phi, dphi, have, force,
                   wheel_force, wheel_len, active)
    omega, zeta, span, grid_h, V, S, amp = bridge
    m_inv, c_v, k_v, f_g, wheel_rows, wheel_first, wheel_count, wheel_envelope = vehicle
    setback = points[0]
    n_m = xi.size
    n_d = q.size
    for m in range(n_m):
        ddxi[m] = -2.0 * zeta[m] * omega[m] * dxi[m] - omega[m] * omega[m] * xi[m]
    for p in range(force.size):
        if force[p] != 0.0:
            x = xf - setback[p]
            if 0.0 <= x <= span:
                for m in range(n_m):
                    ddxi[m] -= phi[p, m] * force[p]
    if n_d == 0:
        return
    for i in range(n_d):
        acc = f_g[i]
        for j in range(n_d):
            acc -= c_v[i, j] * dq[j] + k_v[i, j] * q[j]
        for w in range(wheel_rows.shape[0]):
            acc += wheel_rows[w, i] * wheel_force[w]
        rhs[i] = acc
    for i in range(n_d):
        acc = 0.0
        for j in range(n_d):
            acc += m_inv[i, j] * rhs[j]
        ddq[i] = acc


@njit(cache=True, fastmath=True, error_model="numpy")
def rk4(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
        wheel_force, wheel_len):
    """Classical 4th-order Runge–Kutta (the paper's integrator) on the first-order form of Eq. 9.

    ``xf``, ``vel``, ``road``, ``road_rate`` are given at half steps (index 2n = t_n); the output
    arrays (n_steps + 1, ·) hold row 0 = the initial state on entry and are filled.
    """
    n_steps = xi.shape[0] - 1
    n_m = xi.shape[1]
    n_d = q.shape[1]
    n_cp = points[0].size
    n_w = wheel_force.shape[1]
    phi = np.zeros((3, n_cp, n_m))
    dphi = np.zeros((3, n_cp, n_m))
    have = np.zeros((3, n_cp), dtype=np.bool_)
    ax = np.zeros((4, n_m))
    aq = np.zeros((4, n_d))
    sx = np.zeros(n_m); sv = np.zeros(n_m); sq = np.zeros(n_d); sw = np.zeros(n_d)
    force = np.zeros(n_cp)
    active = np.zeros(n_cp, dtype=np.bool_)
    wf = np.zeros(n_w)
    wl = np.zeros(n_w)
    rhs = np.zeros(n_d)
    cur = 0
    h = 0.5 * dt
    for n in range(n_steps):
        mid = (cur + 1) % 3
        end = (cur + 2) % 3
        have[mid, :] = False
        have[end, :] = False
        x0 = xi[n]; v0 = dxi[n]; y0 = q[n]; w0 = dq[n]
        accelerations(x0, v0, y0, w0, vel[2 * n], xf[2 * n], road[2 * n], road_rate[2 * n], bridge, vehicle, points,
                      unilateral, phi[cur], dphi[cur], have[cur], ax[0], aq[0], force, wheel_force[n], wheel_len[n],
                      active, rhs)
        # stages 2-4: state = start + tau * (velocity + h * previous-but-one stage acceleration)
        for stage in range(1, 4):
            tau = h if stage < 3 else dt
            ih = 2 * n + (1 if stage < 3 else 2)
            slot = mid if stage < 3 else end
            prev = stage - 1
            for m in range(n_m):
                if stage == 1:
                    sx[m] = x0[m] + h * v0[m]
                else:
                    sx[m] = x0[m] + tau * (v0[m] + h * ax[prev - 1, m])
                sv[m] = v0[m] + tau * ax[prev, m]
            for j in range(n_d):
                if stage == 1:
                    sq[j] = y0[j] + h * w0[j]
                else:
                    sq[j] = y0[j] + tau * (w0[j] + h * aq[prev - 1, j])
                sw[j] = w0[j] + tau * aq[prev, j]
            accelerations(sx, sv, sq, sw, vel[ih], xf[ih], road[ih], road_rate[ih], bridge, vehicle, points,
                          unilateral, phi[slot], dphi[slot], have[slot], ax[stage], aq[stage], force, wf, wl,
                          active, rhs)
        ddxi[n] = ax[0]
        ddq[n] = aq[0]
        for m in range(n_m):
            xi[n + 1, m] = x0[m] + dt * (v0[m] + dt / 6.0 * (ax[0, m] + ax[1, m] + ax[2, m]))
            dxi[n + 1, m] = v0[m] + dt / 6.0 * (ax[0, m] + 2 * ax[1, m] + 2 * ax[2, m] + ax[3, m])
        for j in range(n_d):
            q[n + 1, j] = y0[j] + dt * (w0[j] + dt / 6.0 * (aq[0, j] + aq[1, j] + aq[2, j]))
            dq[n + 1, j] = w0[j] + dt / 6.0 * (aq[0, j] + 2 * aq[1, j] + 2 * aq[2, j] + aq[3, j])
        cur = end
    n = n_steps
    accelerations(xi[n], dxi[n], q[n], dq[n], vel[2 * n], xf[2 * n], road[2 * n], road_rate[2 * n], bridge, vehicle,
                  points, unilateral, phi[cur], dphi[cur], have[cur], ddxi[n], ddq[n], force, wheel_force[n],
                  wheel_len[n], active, rhs)


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


@njit(cache=True, fastmath=True, error_model="numpy")
def newmark(dt, xf, vel, road, road_rate, bridge, vehicle, points, unilateral, xi, dxi, q, dq, ddxi, ddq,
            wheel_force, wheel_len, active0, max_iterations):
    """Newmark average acceleration (γ = 1/2, β = 1/4), unconditionally stable for the linear system.

    Contact is piecewise linear (points enter and leave contact), so each step iterates on the
    set of active points: assemble with the current set, solve, re-evaluate the contact forces,
    repeat until the set is unchanged.  Returns the number of steps whose active set did not
    settle within ``max_iterations``.  Same array conventions as :func:`rk4`.
    """
    n_steps = xi.shape[0] - 1
    n_m = xi.shape[1]
    n_d = q.shape[1]
    n_cp = points[0].size
    n = n_m + n_d
    phi = np.zeros((n_cp, n_m))
    dphi = np.zeros((n_cp, n_m))
    have = np.zeros(n_cp, dtype=np.bool_)
    mass = np.zeros((n, n)); damp = np.zeros((n, n)); stiff = np.zeros((n, n)); load = np.zeros(n)
    u = np.zeros(n); v = np.zeros(n); a = np.zeros(n)
    force = np.zeros(n_cp)
    active = active0.copy()
    new_active = np.zeros(n_cp, dtype=np.bool_)
    u[:n_m] = xi[0]; u[n_m:] = q[0]; v[:n_m] = dxi[0]; v[n_m:] = dq[0]
    assemble(vel[0], xf[0], road[0], road_rate[0], bridge, vehicle, points, phi, dphi, have, active, mass, damp,
             stiff, load)
    a[:] = np.linalg.solve(mass, load - damp @ v - stiff @ u)
    contact_forces(xi[0], dxi[0], q[0], dq[0], vel[0], xf[0], road[0], road_rate[0], bridge, vehicle, points,
                   unilateral, phi, dphi, have, force, wheel_force[0], wheel_len[0], new_active)
    ddxi[0] = a[:n_m]; ddq[0] = a[n_m:]
    unsettled = 0
    for s in range(1, n_steps + 1):
        i2 = 2 * s
        have[:] = False
        u_p = u + dt * v + 0.25 * dt * dt * a
        v_p = v + 0.5 * dt * a
        settled = False
        for _ in range(max_iterations):
            assemble(vel[i2], xf[i2], road[i2], road_rate[i2], bridge, vehicle, points, phi, dphi, have, active,
                     mass, damp, stiff, load)
            lhs = mass + 0.5 * dt * damp + 0.25 * dt * dt * stiff
            a_new = np.linalg.solve(lhs, load - damp @ v_p - stiff @ u_p)
            u_new = u_p + 0.25 * dt * dt * a_new
            v_new = v_p + 0.5 * dt * a_new
            contact_forces(u_new[:n_m], v_new[:n_m], u_new[n_m:], v_new[n_m:], vel[i2], xf[i2], road[i2],
                           road_rate[i2], bridge, vehicle, points, unilateral, phi, dphi, have, force,
                           wheel_force[s], wheel_len[s], new_active)
            same = True
            for p in range(n_cp):
                if new_active[p] != active[p]:
                    same = False
                    break
            active[:] = new_active
            if same:
                settled = True
                break
        if not settled:
            unsettled += 1
        u = u_new; v = v_new; a = a_new
        xi[s] = u[:n_m]; q[s] = u[n_m:]; dxi[s] = v[:n_m]; dq[s] = v[n_m:]
        ddxi[s] = a[:n_m]; ddq[s] = a[n_m:]
    return unsettled


@njit(cache=True)
def sample_paths(stations, elevations, paths, rates, road, road_rate):
    """Road elevation and rate along non-decreasing paths (one column per contact point).

    ``paths`` (n_t, n_cp) positions [m], ``rates`` (n_t,) speeds [m/s]; fills ``road`` [m]
    and ``road_rate`` = v · dr/dx [m/s] by linear interpolation of (stations, elevations),
    walking one pointer per path (O(n) instead of a binary search per sample).
    """
    n_s = stations.size
    n_cp = paths.shape[1]
    idx = np.zeros(n_cp, dtype=np.int64)
    for p in range(n_cp):
        idx[p] = max(0, min(n_s - 2, np.searchsorted(stations, paths[0, p], side="right") - 1))
    for t in range(paths.shape[0]):
        for p in range(n_cp):
            x = paths[t, p]
            i = idx[p]
            while i < n_s - 2 and stations[i + 1] <= x:
                i += 1
            idx[p] = i
            slope = (elevations[i + 1] - elevations[i]) / (stations[i + 1] - stations[i])
            road[t, p] = elevations[i] + slope * (x - stations[i])
            road_rate[t, p] = slope * rates[t]


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
