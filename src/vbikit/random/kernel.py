"""Compiled (numba) step loop of the pseudo-excitation method's exact stepping (``vbikit.random.pem``,
``_exact_lines``: the equations there).

Every wavenumber line is a pair of float columns [Re, Im] of the state, and every map of a step is
real, so one step of all lines is a few matrix products (BLAS through ``np.dot``) and loops over
the columns; the loop here only removes numpy's per-call overhead, which dominates at a few
hundred columns.  Layouts: the state ``st`` = [ξ; ξ̇; p; F_w; z; G] (rows), the step input ``inp`` =
[ξ_f; ξ̇_f; z_b; g] with g the pseudo road load of every point (complex columns as float pairs).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the @njit(cache=True) below


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def record(i, st, n_m, n_w, n_d, deck, v_acc, cw, var, coarse, cov_dv, lam1, kept, keep, work_d, work_a):
    """Add output step ``i``'s pseudo responses of ``st`` to the sums: per channel (rows of ``var``:
    deck displacement, velocity, acceleration, strain at n_pt points (``deck`` @ [ξ; ξ̇; p]), vehicle
    displacement q, acceleration (``v_acc`` @ [z; G]), wheel forces F_w) Σ_c y_c² and Σ_c w_c y_c²
    (``cw``: the coarse rule's weights); Cov(d, v) and λ₁ of the deck points; the displacements
    themselves when ``keep``."""
    o_f = 3 * n_m  # F_w
    o_z = o_f + n_w  # z
    n_c = st.shape[1]
    n_pt = deck.shape[0] // 4
    np.dot(deck, st[:o_z], work_d)  # deck channels from [ξ; ξ̇; p; F_w]
    np.dot(v_acc, st[o_z:], work_a)
    r = 0
    for block in range(3):
        if block == 0:
            src, n_r = work_d, 4 * n_pt
        elif block == 1:
            src, n_r = st[o_z:], n_d  # q: the first n_d rows of z
        else:
            src, n_r = work_a, n_d
        for row in range(n_r):
            s = 0.0
            sc = 0.0
            for c in range(n_c):
                y2 = src[row, c] * src[row, c]
                s += y2
                sc += y2 * cw[c]
            var[i, r] += s
            coarse[i, r] += sc
            r += 1
    for row in range(n_w):
        s = 0.0
        sc = 0.0
        for c in range(n_c):
            y2 = st[o_f + row, c] * st[o_f + row, c]
            s += y2
            sc += y2 * cw[c]
        var[i, r] += s
        coarse[i, r] += sc
        r += 1
    for j in range(n_pt):
        s = 0.0
        lam = 0.0
        for k in range(n_c // 2):
            d0, d1 = work_d[j, 2 * k], work_d[j, 2 * k + 1]
            v0, v1 = work_d[n_pt + j, 2 * k], work_d[n_pt + j, 2 * k + 1]
            s += d0 * v0 + d1 * v1
            lam += np.sqrt((d0 * d0 + d1 * d1) * (v0 * v0 + v1 * v1))
        cov_dv[i, j] += s
        lam1[i, j] += lam
        if keep:
            for c in range(n_c):
                kept[i, j, c] = work_d[j, c]


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def advance(i0, substeps, gmat, st, inp, phase, a11, a12, b1, a21, a22, b2, c1, c2, free_z, resp, k_z, dtravel,
            wave, vehicle, forward, rates, coef_k, coef_cw, deck, v_acc, cw, var, coarse, cov_dv, lam1, kept, keep):
    """Steps i0 + 1 … i0 + len(gmat) of every line (column pair) from ``st`` (updated in place):

    the free deck ξ_f = a11 ξ + a12 ξ̇ + b1 p, ξ̇_f = a21 ξ + a22 ξ̇ + b2 p and vehicles
    z_b = ``free_z`` [z; G]; the phases exp(i 2π n x_p) moved by each vehicle's travel ``dtravel``
    (conjugate factor for points driving −x) and the road load g_p = phase·(k_p + i ẋ_p c_p 2π n)·coef;
    (p, F_w) = ``gmat[j]`` [ξ_f; ξ̇_f; z_b; g]; the end state ξ = ξ_f + c1 p, ξ̇ = ξ̇_f + c2 p,
    z = z_b + ``resp`` F_w, G = F_w + ``k_z`` z; every ``substeps``-th step recorded (``record``)."""
    n_m = a11.size
    n_w = k_z.shape[0]
    n_z = k_z.shape[1]
    n_d = n_z // 2
    n_p = phase.shape[0]
    n_l = phase.shape[1]
    n_c = 2 * n_l
    n_v = dtravel.shape[1]
    o_p, o_f = 2 * n_m, 3 * n_m
    o_z = o_f + n_w
    o_g = o_z + n_z
    o_in = 2 * n_m + n_z
    zb = np.empty((n_z, n_c))
    pf = np.empty((n_m + n_w, n_c))
    work_z = np.empty((n_z, n_c))
    work_g = np.empty((n_w, n_c))
    work_d = np.empty((deck.shape[0], n_c))
    work_a = np.empty((v_acc.shape[0], n_c))
    fac = np.empty((n_v, n_l), dtype=np.complex128)
    for j in range(gmat.shape[0]):
        i = i0 + j + 1
        for m in range(n_m):
            for c in range(n_c):
                x, v, p = st[m, c], st[n_m + m, c], st[o_p + m, c]
                inp[m, c] = a11[m] * x + a12[m] * v + b1[m] * p
                inp[n_m + m, c] = a21[m] * x + a22[m] * v + b2[m] * p
        np.dot(free_z, st[o_z:], zb)
        for r in range(n_z):
            for c in range(n_c):
                inp[o_p + r, c] = zb[r, c]
        for v in range(n_v):
            for k in range(n_l):
                fac[v, k] = np.exp(1j * wave[k] * dtravel[j, v])
        for q in range(n_p):
            veh = vehicle[q]
            vx = rates[j, q]
            for k in range(n_l):
                f = fac[veh, k]
                ph = phase[q, k] * (f if forward[q] else np.conj(f))
                phase[q, k] = ph
                g = ph * (coef_k[q, k] + 1j * vx * coef_cw[q, k])
                inp[o_in + q, 2 * k] = g.real
                inp[o_in + q, 2 * k + 1] = g.imag
        np.dot(gmat[j], inp, pf)
        for m in range(n_m):
            for c in range(n_c):
                p = pf[m, c]
                st[o_p + m, c] = p
                st[m, c] = inp[m, c] + c1[m] * p
                st[n_m + m, c] = inp[n_m + m, c] + c2[m] * p
        for w in range(n_w):
            for c in range(n_c):
                st[o_f + w, c] = pf[n_m + w, c]
        np.dot(resp, st[o_f:o_z], work_z)
        for r in range(n_z):
            for c in range(n_c):
                st[o_z + r, c] = zb[r, c] + work_z[r, c]
        np.dot(k_z, st[o_z:o_g], work_g)
        for w in range(n_w):
            for c in range(n_c):
                st[o_g + w, c] = st[o_f + w, c] + work_g[w, c]
        if i % substeps == 0:
            record(i // substeps, st, n_m, n_w, n_d, deck, v_acc, cw, var, coarse, cov_dv, lam1, kept, keep, work_d,
                   work_a)
