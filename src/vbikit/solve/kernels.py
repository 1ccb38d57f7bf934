"""Compiled (numba) kernels of the coupled vehicle–bridge equations (paper Eq. 9, modal form).

State: bridge modal coordinates ξ (n_m) and vehicle coordinates q (n_d).  For each contact
point p at deck position x_p with mode-shape row φ_p, slope row φ'_p, wheel row h_p,
spring k_p, dashpot c_p, fixed load f0_p, road elevation r_p and its rate ṙ_p = v·r'(x_p):

    F_p = k_p (φ_p·ξ + r_p − h_p·q) + c_p (φ_p·ξ̇ + v φ'_p·ξ + ṙ_p − h_p·q̇) + f0_p   (compression > 0)
    ξ̈ + 2ζω ξ̇ + ω² ξ = −Σ_p φ_pᵀ F_p
    M_v q̈ + C_v q̇ + K_v q = F_G + Σ_p h_pᵀ F_p

(the v φ'_p·ξ term is the convective part of the deck velocity under a moving point).
Mode shapes along each wheel track are tabulated on a uniform grid with values and slopes
and evaluated by cubic Hermite interpolation (see ``vbikit.solve.tabulate``).
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, fastmath=True)
def shapes_at(xf, cp_setback, cp_track, span, grid_h, V, S, phi, dphi, on):
    """Mode-shape rows φ_p, φ'_p of every contact point for front-axle position ``xf``."""
    n_grid = V.shape[1]
    n_m = V.shape[2]
    for p in range(cp_setback.size):
        x = xf - cp_setback[p]
        if x < 0.0 or x > span:
            on[p] = False
            continue
        on[p] = True
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
        k = cp_track[p]
        for m in range(n_m):
            a0 = V[k, i, m]
            a1 = V[k, i + 1, m]
            b0 = S[k, i, m]
            b1 = S[k, i + 1, m]
            phi[p, m] = h00 * a0 + h10 * b0 + h01 * a1 + h11 * b1
            dphi[p, m] = d00 * a0 + d10 * b0 + d01 * a1 + d11 * b1


@njit(cache=True, fastmath=True)
def contact_forces(xi, dxi, q, dq, vel, phi, dphi, on, r, rdot, cp_k, cp_c, cp_f0, cp_wheel, wheel_rows, force,
                   wheel_force):
    """Contact force F_p [N] of every point (compression positive) into ``force``; per-wheel sums into
    ``wheel_force``."""
    n_m = xi.size
    n_d = q.size
    n_w = wheel_rows.shape[0]
    zw = np.zeros(n_w)
    dzw = np.zeros(n_w)
    for w in range(n_w):
        wheel_force[w] = 0.0
        for j in range(n_d):
            zw[w] += wheel_rows[w, j] * q[j]
            dzw[w] += wheel_rows[w, j] * dq[j]
    for p in range(cp_k.size):
        ub = 0.0
        dub = 0.0
        if on[p]:
            for m in range(n_m):
                ub += phi[p, m] * xi[m]
                dub += phi[p, m] * dxi[m] + vel * dphi[p, m] * xi[m]
        w = cp_wheel[p]
        force[p] = cp_k[p] * (ub + r[p] - zw[w]) + cp_c[p] * (dub + rdot[p] - dzw[w]) + cp_f0[p]
        wheel_force[w] += force[p]


@njit(cache=True, fastmath=True)
def accelerations(xi, dxi, q, dq, vel, phi, dphi, on, r, rdot, omega, zeta, m_inv, c_v, k_v, f_g,
                  cp_k, cp_c, cp_f0, cp_wheel, wheel_rows, ddxi, ddq, force, wheel_force, rhs):
    """ξ̈, q̈ and contact forces for a given state (the right-hand side of Eq. 9)."""
    contact_forces(xi, dxi, q, dq, vel, phi, dphi, on, r, rdot, cp_k, cp_c, cp_f0, cp_wheel, wheel_rows, force,
                   wheel_force)
    n_m = xi.size
    n_d = q.size
    for m in range(n_m):
        ddxi[m] = -2.0 * zeta[m] * omega[m] * dxi[m] - omega[m] * omega[m] * xi[m]
    for p in range(cp_k.size):
        if on[p]:
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


@njit(cache=True, fastmath=True)
def rk4(dt, xf, vel, road, road_rate, omega, zeta, m_inv, c_v, k_v, f_g, cp_setback, cp_track, cp_k, cp_c,
        cp_f0, cp_wheel, wheel_rows, span, grid_h, V, S, xi, dxi, q, dq, ddxi, ddq, force):
    """Classical 4th-order Runge–Kutta (the paper's integrator) on the first-order form of Eq. 9.

    ``xf``, ``vel``, ``road``, ``road_rate`` are given at half steps (index 2n = t_n); the
    output arrays (n_steps + 1, ·) hold row 0 = the initial state on entry and are filled.
    """
    n_steps = xi.shape[0] - 1
    n_m = xi.shape[1]
    n_d = q.shape[1]
    n_cp = cp_k.size
    phi = np.zeros((3, n_cp, n_m))
    dphi = np.zeros((3, n_cp, n_m))
    on = np.zeros((3, n_cp), dtype=np.bool_)
    ax = np.zeros((4, n_m))
    aq = np.zeros((4, n_d))
    sx = np.zeros(n_m); sv = np.zeros(n_m); sq = np.zeros(n_d); sw = np.zeros(n_d)
    f_tmp = np.zeros(n_cp)
    wf = np.zeros(wheel_rows.shape[0])
    rhs = np.zeros(n_d)
    shapes_at(xf[0], cp_setback, cp_track, span, grid_h, V, S, phi[0], dphi[0], on[0])
    cur = 0
    h = 0.5 * dt
    for n in range(n_steps):
        mid = (cur + 1) % 3
        end = (cur + 2) % 3
        shapes_at(xf[2 * n + 1], cp_setback, cp_track, span, grid_h, V, S, phi[mid], dphi[mid], on[mid])
        shapes_at(xf[2 * n + 2], cp_setback, cp_track, span, grid_h, V, S, phi[end], dphi[end], on[end])
        x0 = xi[n]; v0 = dxi[n]; y0 = q[n]; w0 = dq[n]
        accelerations(x0, v0, y0, w0, vel[2 * n], phi[cur], dphi[cur], on[cur], road[2 * n], road_rate[2 * n],
                      omega, zeta, m_inv, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_wheel, wheel_rows, ax[0], aq[0],
                      force[n], wf, rhs)
        # stages 2-4: state = start + c1 * velocity-part + c2 * previous stage acceleration
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
            accelerations(sx, sv, sq, sw, vel[ih], phi[slot], dphi[slot], on[slot], road[ih], road_rate[ih], omega,
                          zeta, m_inv, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_wheel, wheel_rows, ax[stage], aq[stage],
                          f_tmp, wf, rhs)
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
    accelerations(xi[n], dxi[n], q[n], dq[n], vel[2 * n], phi[cur], dphi[cur], on[cur], road[2 * n],
                  road_rate[2 * n], omega, zeta, m_inv, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_wheel, wheel_rows,
                  ddxi[n], ddq[n], force[n], wf, rhs)


@njit(cache=True, fastmath=True)
def assemble(vel, phi, dphi, on, r, rdot, omega, zeta, m_v, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_rows,
             mass, damp, stiff, load):
    """Coupled system matrices of Eq. 9 at one instant: M ü + C u̇ + K u = F with u = [ξ; q]."""
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
        k = cp_k[p]
        c = cp_c[p]
        ext = k * r[p] + c * rdot[p] + cp_f0[p]
        h = cp_rows[p]
        for i in range(n_d):
            load[n_m + i] += h[i] * ext
            for j in range(n_d):
                stiff[n_m + i, n_m + j] += k * h[i] * h[j]
                damp[n_m + i, n_m + j] += c * h[i] * h[j]
        if not on[p]:
            continue
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


@njit(cache=True, fastmath=True)
def newmark(dt, xf, vel, road, road_rate, omega, zeta, m_v, c_v, k_v, f_g, cp_setback, cp_track, cp_k, cp_c,
            cp_f0, cp_wheel, wheel_rows, span, grid_h, V, S, xi, dxi, q, dq, ddxi, ddq, force):
    """Newmark average-acceleration (γ = 1/2, β = 1/4), unconditionally stable, on Eq. 9.

    Same array conventions as :func:`rk4` (inputs at half steps; only full steps are used).
    """
    cp_rows = np.empty((cp_k.size, wheel_rows.shape[1]))
    for p in range(cp_k.size):
        cp_rows[p] = wheel_rows[cp_wheel[p]]
    n_steps = xi.shape[0] - 1
    n_m = xi.shape[1]
    n_d = q.shape[1]
    n_cp = cp_k.size
    n = n_m + n_d
    phi = np.zeros((n_cp, n_m))
    dphi = np.zeros((n_cp, n_m))
    on = np.zeros(n_cp, dtype=np.bool_)
    mass = np.zeros((n, n)); damp = np.zeros((n, n)); stiff = np.zeros((n, n)); load = np.zeros(n)
    u = np.zeros(n); v = np.zeros(n); a = np.zeros(n)
    u[:n_m] = xi[0]; u[n_m:] = q[0]; v[:n_m] = dxi[0]; v[n_m:] = dq[0]
    shapes_at(xf[0], cp_setback, cp_track, span, grid_h, V, S, phi, dphi, on)
    assemble(vel[0], phi, dphi, on, road[0], road_rate[0], omega, zeta, m_v, c_v, k_v, f_g, cp_k, cp_c, cp_f0,
             cp_rows, mass, damp, stiff, load)
    a[:] = np.linalg.solve(mass, load - damp @ v - stiff @ u)
    wf = np.zeros(wheel_rows.shape[0])
    contact_forces(xi[0], dxi[0], q[0], dq[0], vel[0], phi, dphi, on, road[0], road_rate[0], cp_k, cp_c, cp_f0,
                   cp_wheel, wheel_rows, force[0], wf)
    ddxi[0] = a[:n_m]; ddq[0] = a[n_m:]
    for s in range(1, n_steps + 1):
        i2 = 2 * s
        shapes_at(xf[i2], cp_setback, cp_track, span, grid_h, V, S, phi, dphi, on)
        assemble(vel[i2], phi, dphi, on, road[i2], road_rate[i2], omega, zeta, m_v, c_v, k_v, f_g, cp_k, cp_c,
                 cp_f0, cp_rows, mass, damp, stiff, load)
        u_p = u + dt * v + 0.25 * dt * dt * a
        v_p = v + 0.5 * dt * a
        lhs = mass + 0.5 * dt * damp + 0.25 * dt * dt * stiff
        a = np.linalg.solve(lhs, load - damp @ v_p - stiff @ u_p)
        u = u_p + 0.25 * dt * dt * a
        v = v_p + 0.5 * dt * a
        xi[s] = u[:n_m]; q[s] = u[n_m:]; dxi[s] = v[:n_m]; dq[s] = v[n_m:]
        ddxi[s] = a[:n_m]; ddq[s] = a[n_m:]
        contact_forces(xi[s], dxi[s], q[s], dq[s], vel[i2], phi, dphi, on, road[i2], road_rate[i2], cp_k, cp_c,
                       cp_f0, cp_wheel, wheel_rows, force[s], wf)


@njit(cache=True)
def sample_paths(stations, elevations, paths, rates, road, road_rate):
    """Road elevation and rate along non-decreasing paths (one column per contact point).

    ``paths`` (n_t, n_cp) positions [m], ``rates`` (n_t,) speeds [m/s]; fills ``road`` [m]
    and ``road_rate`` = v · dr/dx [m/s] by linear interpolation of (stations, elevations),
    walking a pointer along each path (O(n) instead of a binary search per sample).
    """
    n_s = stations.size
    for p in range(paths.shape[1]):
        i = 0
        for t in range(paths.shape[0]):
            x = paths[t, p]
            while i < n_s - 2 and stations[i + 1] <= x:
                i += 1
            slope = (elevations[i + 1] - elevations[i]) / (stations[i + 1] - stations[i])
            road[t, p] = elevations[i] + slope * (x - stations[i])
            road_rate[t, p] = slope * rates[t]
