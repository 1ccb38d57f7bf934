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


@njit(cache=True)
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


@njit(cache=True)
def contact_forces(xi, dxi, q, dq, vel, phi, dphi, on, r, rdot, cp_k, cp_c, cp_f0, cp_rows, force):
    """Contact force F_p [N] of every point (compression positive) into ``force``."""
    n_m = xi.size
    n_d = q.size
    for p in range(cp_k.size):
        ub = 0.0
        dub = 0.0
        if on[p]:
            for m in range(n_m):
                ub += phi[p, m] * xi[m]
                dub += phi[p, m] * dxi[m] + vel * dphi[p, m] * xi[m]
        zw = 0.0
        dzw = 0.0
        for j in range(n_d):
            zw += cp_rows[p, j] * q[j]
            dzw += cp_rows[p, j] * dq[j]
        force[p] = cp_k[p] * (ub + r[p] - zw) + cp_c[p] * (dub + rdot[p] - dzw) + cp_f0[p]


@njit(cache=True)
def accelerations(xi, dxi, q, dq, vel, phi, dphi, on, r, rdot, omega, zeta, m_inv, c_v, k_v, f_g,
                  cp_k, cp_c, cp_f0, cp_rows, ddxi, ddq, force):
    """ξ̈, q̈ and contact forces for a given state (the right-hand side of Eq. 9)."""
    contact_forces(xi, dxi, q, dq, vel, phi, dphi, on, r, rdot, cp_k, cp_c, cp_f0, cp_rows, force)
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
    rhs = f_g.copy()
    for i in range(n_d):
        for j in range(n_d):
            rhs[i] -= c_v[i, j] * dq[j] + k_v[i, j] * q[j]
    for p in range(cp_k.size):
        for i in range(n_d):
            rhs[i] += cp_rows[p, i] * force[p]
    for i in range(n_d):
        acc = 0.0
        for j in range(n_d):
            acc += m_inv[i, j] * rhs[j]
        ddq[i] = acc


@njit(cache=True)
def rk4(dt, xf, vel, road, road_rate, omega, zeta, m_inv, c_v, k_v, f_g, cp_setback, cp_track, cp_k, cp_c,
        cp_f0, cp_rows, span, grid_h, V, S, xi, dxi, q, dq, ddxi, ddq, force):
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
    a1x = np.zeros(n_m); a2x = np.zeros(n_m); a3x = np.zeros(n_m); a4x = np.zeros(n_m)
    a1q = np.zeros(n_d); a2q = np.zeros(n_d); a3q = np.zeros(n_d); a4q = np.zeros(n_d)
    f_tmp = np.zeros(n_cp)
    shapes_at(xf[0], cp_setback, cp_track, span, grid_h, V, S, phi[0], dphi[0], on[0])
    cur = 0
    for n in range(n_steps):
        mid = (cur + 1) % 3
        end = (cur + 2) % 3
        shapes_at(xf[2 * n + 1], cp_setback, cp_track, span, grid_h, V, S, phi[mid], dphi[mid], on[mid])
        shapes_at(xf[2 * n + 2], cp_setback, cp_track, span, grid_h, V, S, phi[end], dphi[end], on[end])
        x0 = xi[n]; v0 = dxi[n]; y0 = q[n]; w0 = dq[n]
        accelerations(x0, v0, y0, w0, vel[2 * n], phi[cur], dphi[cur], on[cur], road[2 * n], road_rate[2 * n],
                      omega, zeta, m_inv, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_rows, a1x, a1q, force[n])
        ddxi[n] = a1x
        ddq[n] = a1q
        h = 0.5 * dt
        accelerations(x0 + h * v0, v0 + h * a1x, y0 + h * w0, w0 + h * a1q, vel[2 * n + 1], phi[mid], dphi[mid],
                      on[mid], road[2 * n + 1], road_rate[2 * n + 1], omega, zeta, m_inv, c_v, k_v, f_g, cp_k,
                      cp_c, cp_f0, cp_rows, a2x, a2q, f_tmp)
        accelerations(x0 + h * (v0 + h * a1x), v0 + h * a2x, y0 + h * (w0 + h * a1q), w0 + h * a2q,
                      vel[2 * n + 1], phi[mid], dphi[mid], on[mid], road[2 * n + 1], road_rate[2 * n + 1], omega,
                      zeta, m_inv, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_rows, a3x, a3q, f_tmp)
        accelerations(x0 + dt * (v0 + h * a2x), v0 + dt * a3x, y0 + dt * (w0 + h * a2q), w0 + dt * a3q,
                      vel[2 * n + 2], phi[end], dphi[end], on[end], road[2 * n + 2], road_rate[2 * n + 2], omega,
                      zeta, m_inv, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_rows, a4x, a4q, f_tmp)
        for m in range(n_m):
            xi[n + 1, m] = x0[m] + dt * (v0[m] + dt / 6.0 * (a1x[m] + a2x[m] + a3x[m]))
            dxi[n + 1, m] = v0[m] + dt / 6.0 * (a1x[m] + 2 * a2x[m] + 2 * a3x[m] + a4x[m])
        for j in range(n_d):
            q[n + 1, j] = y0[j] + dt * (w0[j] + dt / 6.0 * (a1q[j] + a2q[j] + a3q[j]))
            dq[n + 1, j] = w0[j] + dt / 6.0 * (a1q[j] + 2 * a2q[j] + 2 * a3q[j] + a4q[j])
        cur = end
    n = n_steps
    accelerations(xi[n], dxi[n], q[n], dq[n], vel[2 * n], phi[cur], dphi[cur], on[cur], road[2 * n],
                  road_rate[2 * n], omega, zeta, m_inv, c_v, k_v, f_g, cp_k, cp_c, cp_f0, cp_rows, ddxi[n], ddq[n],
                  force[n])


@njit(cache=True)
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


@njit(cache=True)
def newmark(dt, xf, vel, road, road_rate, omega, zeta, m_v, c_v, k_v, f_g, cp_setback, cp_track, cp_k, cp_c,
            cp_f0, cp_rows, span, grid_h, V, S, xi, dxi, q, dq, ddxi, ddq, force):
    """Newmark average-acceleration (γ = 1/2, β = 1/4), unconditionally stable, on Eq. 9.

    Same array conventions as :func:`rk4` (inputs at half steps; only full steps are used).
    """
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
    contact_forces(xi[0], dxi[0], q[0], dq[0], vel[0], phi, dphi, on, road[0], road_rate[0], cp_k, cp_c, cp_f0,
                   cp_rows, force[0])
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
                       cp_f0, cp_rows, force[s])
