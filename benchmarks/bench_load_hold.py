"""A research prototype: would a higher-order load hold let the exact step take fewer steps?

    python benchmarks/bench_load_hold.py                      # 10 one-truck + 5 two-truck events, ≈ 2 min
    python benchmarks/bench_load_hold.py --single 60 --several 20 --smooth --no-demo   # ≈ 4 min
    python benchmarks/bench_load_hold.py --road C --smooth --no-demo                  # wheels lose contact

The library's exact step (``vbikit.solve.modal_step``) advances each mode and the vehicles exactly
with the load LINEAR over the step (first-order hold).  The variant here takes the loads QUADRATIC
over [t_n, t_{n+1}] through p_{n−1}, p_n, p_{n+1} (a three-point hold, the Lagrange quadratic):

    ξ_{n+1} = a11 ξ_n + a12 ξ̇_n + d1 p_{n−1} + b1' p_n + c1' p_{n+1}   (ξ̇ likewise: a21, a22, d2, b2', c2')
    z_{n+1} = Φ z_n + Lm G_{n−1} + L0' G_n + L1' G_{n+1} + b           (vehicles, wheel loads G)

Coefficients (``hold_modal``, ``hold_vehicle``, ``hold_weights``): the exponential of the augmented
system (ξ, ξ̇, p, ṗ, p̈) — for the vehicles (q, q̇, G, Ġ, G̈, 1) — over h, whose load columns E_p, E_ṗ,
E_p̈ give the response to p(t) = p_n + ṗ t + p̈ t²/2; with ṗ = (p_{n+1} − p_{n−1})/2h and
p̈ = (p_{n+1} − 2p_n + p_{n−1})/h² (the Lagrange quadratic's derivatives at t_n):
d = −E_ṗ/2h + E_p̈/h², b' = E_p − 2E_p̈/h², c' = E_ṗ/2h + E_p̈/h² (a four-point cubic through p_{n−2} …
p_{n+1} likewise, one more column).  Checked (``check_coefficients``) against the convolution
integral ∫₀ʰ g(h−s) L_j(s) ds of the damped oscillator's impulse response g (and g') with each
Lagrange basis L_j by adaptive quadrature (scipy ``quad``), the linear coefficients against the
library's ``exact_step`` and ``vehicle_step``, and the recurrence as a whole against RK4 at 1e-4 s
on one mode under a smooth load (observed orders 2, 3, 4).  The first steps of a run hold
p_{−2} = p_{−1} = p_0 (static start; the trucks start off the deck).

The loop (``hold_loop``) is ``bench_floor.py``'s ``floor_loop`` (one contact-law evaluation a step and
one quasi-Newton update, here ``updates`` of them) with the p_{n−1}, p_{n−2}, G_{n−1}, G_{n−2} terms
added and ξ̇ stored; with those terms zero it is the floor.  It runs on the inputs the library's own
``kernels.implicit`` call receives at each step size (captured from ``simulate`` with
``USE_LEAN`` off): mode tables, step maps, contact points, road, motion.  Its linear variant was
checked against the library's midspan history at every step size while the library held every load
linear; since 2026-12-05 the library holds the deck's loads quadratic (``modal_step.quadratic_hold``, with
the deck-end and landing rules of ``kernels.hold`` that this loop does not have).

Events: those of ``bench_step_rule.py`` (``bench_traffic.py``'s stream, ``paper-bridge-2``, 10 modes,
point tires, ISO class B road of each event's seed, Girder 4 midspan displacement IM with the peak
refined by the velocity, as ``point_response``), reference RK4 at dt/8 through the library, dt the
automatic step (2 cm of road a step).  Printed per step factor k = 1, 1.5, 2, 3, 4: max and mean
|ΔIM| of the library (converged, linear hold), the loop with the linear, quadratic and cubic holds,
quadratic on the deck only and on the vehicles only, linear and quadratic with three updates a step,
and RK4's own history sampled at k dt (what output sampling alone costs); the midspan history's
largest error at the step points (/ peak); the same on each event's road smoothed by a moving
average over 0.10 m and 0.5 m (``--smooth``; RK4 rerun on it); where the history's error sits on
one smoothed event (``where_error``); the holds on the ``vbikit demo`` crossing; and the loop's
thread CPU time a step with each hold.

Findings (2026-12-05).  |ΔIM| max / mean against RK4 at dt/8, k × the automatic step dt:

    events                                hold        k = 1          1.5            2              3              4
    class B, 80 (``--single 60            linear      4.0e-4/6.5e-5  5.6e-4/1.4e-4  7.7e-4/2.4e-4  1.5e-3/5.4e-4  2.8e-3/9.5e-4
      --several 20``)                     quadratic   2.7e-4/3.9e-5  3.6e-4/5.4e-5  4.4e-4/8.4e-5  6.1e-4/1.4e-4  7.5e-4/2.2e-4
                                          cubic       2.6e-4/3.9e-5  3.6e-4/5.2e-5  4.5e-4/8.0e-5  6.7e-4/1.2e-4  8.9e-4/2.0e-4
    class C, 15 (9 lose contact;          linear      3.2e-4/1.4e-4  6.9e-4/2.7e-4  1.1e-3/4.4e-4  2.3e-3/9.7e-4  4.1e-3/1.6e-3
      ``--road C``)                       quadratic   1.6e-4/8.1e-5  3.5e-4/1.2e-4  4.1e-4/1.5e-4  9.4e-4/2.6e-4  8.4e-4/3.3e-4
    class B, 15, road smoothed            linear      7.7e-5/4.0e-5  2.3e-4/8.5e-5  4.2e-4/1.5e-4  1.0e-3/3.5e-4  1.7e-3/6.0e-4
      over 0.5 m (default run)            quadratic   5.9e-5/1.5e-5  6.7e-5/2.2e-5  8.9e-5/3.3e-5  1.7e-4/5.0e-5  3.5e-4/9.6e-5
                                          cubic       5.7e-5/1.5e-5  6.1e-5/2.1e-5  7.5e-5/2.8e-5  1.2e-4/4.1e-5  2.4e-4/6.2e-5

* The linear hold's error is a bias: signed mean ΔIM −5.6e-5, −2.3e-4, −5.3e-4, −9.4e-4 at k = 1, 2,
  3, 4 (class B, 80 events; the underestimate ∝ dt²).  The quadratic hold removes it (signed mean
  within ±1.6e-5 at every k); what is left is scatter of either sign.  Both halves count: the
  quadratic hold on the deck alone or on the vehicles alone does about half (``quadratic deck``,
  ``quadratic vehicles``).
* Steps: at today's accuracy (max 4.0e-4, mean 6.5e-5, 95th percentile 1.7e-4 at 1×) the quadratic
  hold allows 1.5× (3.6e-4, 5.4e-5, 1.4e-4); within the stated 5e-4 it allows 2× (max 4.4e-4, mean
  8.4e-5, 95th percentile 2.2e-4; class C 4.1e-4); 3× is above 5e-4 (6.1e-4).
* What is left is not the hold's truncation: the cubic (four-point) hold is no better on the rough
  road.  On the road smoothed over 0.10 m (content shorter than ≈ 10 cm gone: what the stations,
  the road sampled at the step ends and the secant rate could miss) the errors barely change (linear
  2× 5.9e-4, quadratic 2× 1.7e-4), so neither the road between stations nor the secant rate drives
  the error.  Smoothed over 0.5 m every error falls and the cubic pulls ahead at 3–4×: part of the
  scatter is the contact force's road part changing over 5–25 steps (wavelengths 0.1–0.5 m), which
  no polynomial through step-end samples follows.  A floor of ≈ 6e-5 at 1× stays for every hold:
  the midspan history's largest error (event 0, road smoothed over 0.5 m) sits 27 ms after the
  front axle leaves the deck, at every k and for both holds, and falls only as dt (``where_error``:
  4.2e-5, 8.6e-5, 1.6e-4 / peak at k = 0.5, 1, 2, quadratic), the mark of a jump inside a step.  On ``paper-bridge-2``'s wheel tracks the mode shapes
  do not vanish at the deck's ends (largest |φ| there 5.6 % and 2.0 % of the track's largest), so a
  point's modal load −φF (and its surface φξ) jumps when it crosses an end, somewhere inside a step,
  where no step-end hold can place it (inferred from where and how the error grows; not isolated
  by a run without the jump).  Output sampling
  (RK4's own history sampled at k dt) costs < 4e-5 at 4×; the contact solve's convergence nothing
  (three updates a step give the same numbers as one); RK4 at dt/8 is within 2.6e-5 of RK4 at dt/32
  (a side check outside this script, events 2, 3, 5, 10).  Consistent with the jump: on the ``vbikit
  demo`` beam, whose sine modes vanish at its ends, the quadratic hold shows no such floor (below).
* Cost: the loop's thread CPU time a step is unchanged (1.086 µs linear, 1.090 µs quadratic,
  1.084 µs cubic; the hold adds n_m + 2 n_d n_w multiply-adds and carries p_{n−1}, G_{n−1}).  On the
  ``vbikit demo`` crossing (20 modes, ωh up to ≈ 18, multipoint tires, class C) the quadratic hold
  stays bounded and is more accurate at 3× (ΔIM −2.6e-5) than the linear hold at 1× (−4.6e-5).
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

import numpy as np  # noqa: E402

FACTORS = (1.0, 1.5, 2.0, 3.0, 4.0)


def _hold_loop():
    """``bench_floor.floor_loop`` with the hold's p_{n−1}, p_{n−2} (modes: d, e) and G_{n−1}, G_{n−2}
    (vehicles: ``load_m``, ``load_mm``) terms, ``updates`` quasi-Newton updates a step, and ξ̇ stored
    (for the IM's peak refinement)."""
    from numba import njit

    @njit(cache=True, fastmath=True, error_model="numpy")
    def hold_loop(travel, speed, modes_start, modes_end, grid_h, values, slopes, a11, a12, a21, a22, b1, b2, c1, c2,
                  transition, load0, constant, settle, response, wheel_q, wheel_v, wheel_rows, wheel_k, wheel_c, v_inv,
                  origin, direction, vehicle, track, line, kk, cc, f0, gap, gated, wheel, stations, elevations, span,
                  x0, v0, z0, fstart, d1, d2, load_m, e1, e2, load_mm, updates, xi_out, q_out, wf_out, xd_out):
        n_steps = xi_out.shape[0] - 1
        n_m = x0.size
        n_cp = origin.size
        n_w = wheel_rows.shape[0]
        n_d = wheel_rows.shape[1]
        n_grid = values.shape[1]
        n_s = stations.size
        x = x0.copy(); v = v0.copy(); z = z0.copy()
        p0 = np.zeros(n_m); p = np.zeros(n_m); pm = np.zeros(n_m); pmm = np.zeros(n_m)
        xf = np.zeros(n_m); vf = np.zeros(n_m); x1 = np.zeros(n_m); v1 = np.zeros(n_m)
        zf = np.zeros(2 * n_d); zb = np.zeros(2 * n_d); z1 = np.zeros(2 * n_d)
        g0 = np.zeros(n_w); gm = np.zeros(n_w); gmm = np.zeros(n_w); fw = np.zeros(n_w); bq = np.zeros(n_w); bv = np.zeros(n_w)
        t = np.zeros(n_w)
        f = fstart.copy(); fo = fstart.copy(); fp = fstart.copy(); law = np.zeros(n_cp)
        phi = np.zeros((n_cp, n_m)); dphi = np.zeros((n_cp, n_m)); onb = np.zeros(n_cp, np.bool_)
        xp = np.zeros(n_cp); vxp = np.zeros(n_cp); idx = np.zeros(n_cp, np.int64)
        for k in range(n_cp):  # the initial wheel loads G = F + k_w z_w + c_w ż_w
            g0[wheel[k]] += f[k]
        for w in range(n_w):
            for j in range(n_d):
                g0[w] += wheel_rows[w, j] * (wheel_k[w] * z[j] + wheel_c[w] * z[n_d + j])
            gm[w] = g0[w]  # p_{-1} = p_{-2} = p_0: the static start
            gmm[w] = g0[w]
        for m in range(n_m):
            xi_out[0, m] = x0[m]
            xd_out[0, m] = v0[m]
        for n in range(n_steps):
            row = 2 * n + 2
            for k in range(n_cp):  # positions and mode shapes (cubic Hermite)
                xp[k] = origin[k] + direction[k] * travel[row, vehicle[k]]
                vxp[k] = direction[k] * speed[row, vehicle[k]]
                tr = track[k]
                onb[k] = modes_start[tr] <= xp[k] <= modes_end[tr]
                if onb[k]:
                    u = (xp[k] - modes_start[tr]) / grid_h
                    i = min(int(u), n_grid - 2)
                    s = u - i
                    s2 = s * s
                    s3 = s2 * s
                    h00 = 2 * s3 - 3 * s2 + 1
                    h10 = (s3 - 2 * s2 + s) * grid_h
                    h01 = -2 * s3 + 3 * s2
                    h11 = (s3 - s2) * grid_h
                    d00 = (6 * s2 - 6 * s) / grid_h
                    d10 = 3 * s2 - 4 * s + 1
                    d11 = 3 * s2 - 2 * s
                    for m in range(n_m):
                        va = values[tr, i, m]
                        vb = values[tr, i + 1, m]
                        sa = slopes[tr, i, m]
                        sb = slopes[tr, i + 1, m]
                        phi[k, m] = h00 * va + h10 * sa + h01 * vb + h11 * sb
                        dphi[k, m] = d00 * (va - vb) + d10 * sa + d11 * sb
            for m in range(n_m):  # free deck response (the hold's p_{n-1} and p_n terms)
                xf[m] = a11[m] * x[m] + a12[m] * v[m] + b1[m] * p0[m] + d1[m] * pm[m] + e1[m] * pmm[m]
                vf[m] = a21[m] * x[m] + a22[m] * v[m] + b2[m] * p0[m] + d2[m] * pm[m] + e2[m] * pmm[m]
            for i in range(2 * n_d):  # free vehicle response, then settled on the nominal tires
                a = constant[i]
                for j in range(2 * n_d):
                    a += transition[i, j] * z[j]
                for w in range(n_w):
                    a += load0[i, w] * g0[w] + load_m[i, w] * gm[w] + load_mm[i, w] * gmm[w]
                zf[i] = a
            for i in range(2 * n_d):
                a = 0.0
                for j in range(2 * n_d):
                    a += settle[i, j] * zf[j]
                zb[i] = a
            for k in range(n_cp):  # first guess: linear extrapolation
                f[k] = 2.0 * fo[k] - fp[k]
            for it in range(updates + 1):  # it < updates: evaluate and update; it == updates: the end state
                for m in range(n_m):
                    p[m] = 0.0
                for w in range(n_w):
                    fw[w] = 0.0
                for k in range(n_cp):
                    fw[wheel[k]] += f[k]
                    if onb[k]:
                        for m in range(n_m):
                            p[m] -= phi[k, m] * f[k]
                for m in range(n_m):
                    x1[m] = xf[m] + c1[m] * p[m]
                    v1[m] = vf[m] + c2[m] * p[m]
                for i in range(2 * n_d):
                    a = zb[i]
                    for w in range(n_w):
                        a += response[i, w] * fw[w]
                    z1[i] = a
                if it == updates:
                    break
                for k in range(n_cp):  # the contact-law evaluation
                    w = wheel[k]
                    zw = 0.0
                    dzw = 0.0
                    for j in range(n_d):
                        zw += wheel_rows[w, j] * z1[j]
                        dzw += wheel_rows[w, j] * z1[n_d + j]
                    xk = xp[k]
                    i = idx[k]
                    while i < n_s - 2 and stations[i + 1] <= xk:
                        i += 1
                    while i > 0 and stations[i] > xk:
                        i -= 1
                    idx[k] = i
                    zr = elevations[line[k]]
                    slope = (zr[i + 1] - zr[i]) / (stations[i + 1] - stations[i])
                    s = zr[i] + slope * (xk - stations[i])
                    sd = slope * vxp[k]
                    if span > 0.0:  # the implicit integrators' road rate: the secant over x ± |v| span
                        a = abs(vxp[k]) * span
                        ia = i
                        while ia > 0 and stations[ia] > xk - a:
                            ia -= 1
                        ib = i
                        while ib < n_s - 2 and stations[ib + 1] <= xk + a:
                            ib += 1
                        ra = zr[ia] + (zr[ia + 1] - zr[ia]) * (xk - a - stations[ia]) / (stations[ia + 1] - stations[ia])
                        rb = zr[ib] + (zr[ib + 1] - zr[ib]) * (xk + a - stations[ib]) / (stations[ib + 1] - stations[ib])
                        sd = vxp[k] * (rb - ra) / (2.0 * a)
                    dr = 0.0
                    if onb[k]:
                        for m in range(n_m):
                            s += phi[k, m] * x1[m]
                            dr += phi[k, m] * v1[m]
                            sd += vxp[k] * dphi[k, m] * x1[m]
                    pen = s - gap[k] - zw
                    fl = kk[k] * pen + cc[k] * (sd + dr - dzw) + f0[k]
                    law[k] = fl if not gated[k] or (pen > 0.0 and fl > 0.0) else 0.0
                for w in range(n_w):  # one quasi-Newton update through the vehicles: (I + S U) t = S b
                    aq = 0.0
                    av = 0.0
                    for w2 in range(n_w):
                        aq += wheel_q[w, w2] * fw[w2]
                        av += wheel_v[w, w2] * fw[w2]
                    bq[w] = aq
                    bv[w] = av
                    t[w] = 0.0
                for k in range(n_cp):
                    t[wheel[k]] += law[k] + kk[k] * bq[wheel[k]] + cc[k] * bv[wheel[k]]
                for w in range(n_w):
                    a = 0.0
                    for w2 in range(n_w):
                        a += v_inv[w, w2] * t[w2]
                    fw[w] = a
                for w in range(n_w):
                    aq = 0.0
                    av = 0.0
                    for w2 in range(n_w):
                        aq += wheel_q[w, w2] * fw[w2]
                        av += wheel_v[w, w2] * fw[w2]
                    bq[w] -= aq
                    bv[w] -= av
                for k in range(n_cp):
                    on = law[k] != 0.0 or not gated[k]
                    f[k] = law[k] + kk[k] * bq[wheel[k]] + cc[k] * bv[wheel[k]] if on else 0.0
            for w in range(n_w):  # end of step: wheel loads, outputs, shift
                gmm[w] = gm[w]
                gm[w] = g0[w]
                g0[w] = fw[w]
                for j in range(n_d):
                    g0[w] += wheel_rows[w, j] * (wheel_k[w] * z1[j] + wheel_c[w] * z1[n_d + j])
                wf_out[n + 1, w] = fw[w]
            for m in range(n_m):
                x[m] = x1[m]
                v[m] = v1[m]
                pmm[m] = pm[m]
                pm[m] = p0[m]
                p0[m] = p[m]
                xi_out[n + 1, m] = x1[m]
                xd_out[n + 1, m] = v1[m]
            for i in range(2 * n_d):
                z[i] = z1[i]
            for j in range(n_d):
                q_out[n + 1, j] = z1[j]
            for k in range(n_cp):
                fp[k] = fo[k]
                fo[k] = f[k]

    return hold_loop


# ---------------------------------------------------------------- the hold's coefficients

def hold_weights(columns: list, h: float, past: int) -> list:
    """The weights of p_{n−past}, …, p_n, p_{n+1} from the load columns E_k of exp(A h) (E_k: the
    response to the load tᵏ/k!, k = 0 … past + 1): the Lagrange polynomial through the nodes
    τ_j = −past … 1 (times h) is p(t) = Σ_k c_k (t/h)^k with c = V⁻¹ p (V_jk = τ_jᵏ), so p⁽ᵏ⁾(0) = k! c_k / hᵏ
    and the response Σ_k E_k p⁽ᵏ⁾(0) = Σ_j p_j Σ_k E_k k! / hᵏ (V⁻¹)_kj.  Returned oldest first."""
    from math import factorial

    nodes = np.arange(-past, 2, dtype=float)
    v_inv = np.linalg.inv(np.vander(nodes, increasing=True))
    return [sum(columns[k] * (factorial(k) / h**k * v_inv[k, j]) for k in range(past + 2))
            for j in range(past + 2)]


def modal_exponential(omega: float, zeta: float, h: float, past: int) -> np.ndarray:
    """exp(A h) of one mode's augmented system (ξ, ξ̇, p, ṗ, …, p⁽ᵖᵃˢᵗ⁺¹⁾), the last derivative constant."""
    from scipy.linalg import expm

    n = past + 4
    a = np.zeros((n, n))
    a[0, 1] = 1.0
    a[1, 0], a[1, 1], a[1, 2] = -omega**2, -2 * zeta * omega, 1.0
    for i in range(2, n - 1):
        a[i, i + 1] = 1.0
    return expm(a * h)


def hold_modal(omega: np.ndarray, zeta: np.ndarray, h: float, past: int) -> dict[str, np.ndarray]:
    """The hold's modal coefficients (n_m each): a11 … a22; b1, c1, b2, c2 (p_n, p_{n+1}); d1, d2
    (p_{n−1}) and e1, e2 (p_{n−2}), zero where the hold does not reach back that far."""
    keys = ("a11", "a12", "a21", "a22", "b1", "c1", "b2", "c2", "d1", "d2", "e1", "e2")
    out = {k: np.zeros(omega.size) for k in keys}
    for m, (w, z) in enumerate(zip(omega, zeta)):
        e = modal_exponential(float(w), float(z), h, past)
        out["a11"][m], out["a12"][m], out["a21"][m], out["a22"][m] = e[0, 0], e[0, 1], e[1, 0], e[1, 1]
        for r, name in ((0, "1"), (1, "2")):
            weights = hold_weights(list(e[r, 2:]), h, past)[::-1]  # p_{n+1}, p_n, p_{n−1}, p_{n−2}
            for key, val in zip("cbde", weights):
                out[key + name][m] = val
    return out


def hold_vehicle(vehicles, h: float, past: int):
    """The vehicles' hold over h from the exponential of (q, q̇, G, Ġ, …, G⁽ᵖᵃˢᵗ⁺¹⁾, 1), all vehicles in
    one matrix: (VehicleStep of Φ, L0 (G_n), L1 (G_{n+1}), b; Lm (G_{n−1}); Lmm (G_{n−2}))."""
    from scipy.linalg import expm

    from vbikit.solve.modal_step import _nominal, _vehicle_map

    c_hat, k_hat = _nominal(vehicles)
    m_inv, rows, gravity = vehicles.mass_inv, vehicles.wheel_rows, vehicles.gravity
    n_d, n_w = gravity.size, rows.shape[0]
    n = 2 * n_d + (past + 2) * n_w + 1
    a = np.zeros((n, n))
    a[:n_d, n_d:2 * n_d] = np.eye(n_d)
    a[n_d:2 * n_d, :n_d] = -m_inv @ k_hat
    a[n_d:2 * n_d, n_d:2 * n_d] = -m_inv @ c_hat
    a[n_d:2 * n_d, 2 * n_d:2 * n_d + n_w] = m_inv @ rows.T
    a[n_d:2 * n_d, -1] = m_inv @ gravity
    blocks = [slice(2 * n_d + i * n_w, 2 * n_d + (i + 1) * n_w) for i in range(past + 2)]
    for lo, hi in zip(blocks[:-1], blocks[1:]):
        a[lo, hi] = np.eye(n_w)
    e = expm(a * h)
    zs = slice(0, 2 * n_d)
    weights = hold_weights([e[zs, b] for b in blocks], h, past)[::-1] + [np.zeros((2 * n_d, n_w))] * 2
    l1, l0, lm, lmm = weights[:4]
    step = _vehicle_map(vehicles, e[zs, zs], l0, l1, e[zs, -1], c_hat, k_hat)
    return step, np.ascontiguousarray(lm), np.ascontiguousarray(lmm)


def check_coefficients() -> dict[str, float]:
    """The coefficients against independent numbers: the convolution integral by quadrature, the
    library's first-order-hold maps, and the recurrence against RK4 on one mode (module docstring)."""
    from scipy.integrate import quad

    from vbikit.solve.modal_step import exact_step

    out = {}
    for w, z, h in ((2 * np.pi * 3.1, 0.02, 1e-3), (2 * np.pi * 40.0, 0.02, 4e-3), (2 * np.pi * 7.0, 0.3, 2e-2)):
        wd = w * np.sqrt(1 - z**2)
        g = (lambda t: np.exp(-z * w * t) * np.sin(wd * t) / wd)  # the impulse response and its rate
        dg = (lambda t: np.exp(-z * w * t) * (np.cos(wd * t) - z * w / wd * np.sin(wd * t)))
        lib = exact_step(np.array([w]), np.array([z]), h)
        for past, label in ((0, "linear"), (1, "quadratic"), (2, "cubic")):
            coef = hold_modal(np.array([w]), np.array([z]), h, past)
            nodes = h * np.arange(-past, 2, dtype=float)
            worst = 0.0
            for r, kernel in (("1", g), ("2", dg)):
                for j, node in enumerate(nodes):  # the Lagrange basis of node j
                    name = {1: "c", 0: "b", -1: "d", -2: "e"}[round(node / h)]
                    others = np.delete(nodes, j)
                    lj = (lambda s, others=others, node=node: np.prod([(s - o) / (node - o) for o in others]))
                    exact = quad(lambda s: kernel(h - s) * lj(s), 0.0, h, epsabs=0, epsrel=1e-13, limit=200)[0]
                    worst = max(worst, abs(coef[name + r][0] - exact) / abs(exact))
            out[f"{label} hold vs quadrature of the convolution (max rel.)"] = max(
                out.get(f"{label} hold vs quadrature of the convolution (max rel.)", 0.0), worst)
            if past == 0:
                diff = max(abs(coef[k][0] - getattr(lib, k)[0]) / abs(getattr(lib, k)[0]) for k in MODAL_KEYS)
                out["linear hold vs the library's exact_step (max rel.)"] = max(
                    out.get("linear hold vs the library's exact_step (max rel.)", 0.0), diff)
    out.update(_order_check())
    return out


#: the coefficients of the library's ``ModalStep``
MODAL_KEYS = ("a11", "a12", "a21", "a22", "b1", "c1", "b2", "c2")


def _order_check() -> dict[str, float]:
    """One mode (3 Hz, ζ 2 %) under p(t) = sin 7t + 0.5 cos 31t from rest, 1 s: the recurrence's largest
    displacement error over the step points against RK4 at 1e-4 s, for h = 0.02 and 0.01 s, each hold;
    the observed orders (2, 3, 4 expected)."""
    w, z = 2 * np.pi * 3.0, 0.02
    load = (lambda t: np.sin(7 * t) + 0.5 * np.cos(31 * t))
    fine = 1e-4
    f = (lambda t, y: np.array([y[1], load(t) - 2 * z * w * y[1] - w * w * y[0]]))
    y, ref = np.zeros(2), [0.0]
    for i in range(round(1.0 / fine)):
        t = i * fine
        k1 = f(t, y); k2 = f(t + fine / 2, y + fine / 2 * k1); k3 = f(t + fine / 2, y + fine / 2 * k2)
        k4 = f(t + fine, y + fine * k3)
        y = y + fine / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        ref.append(y[0])
    ref = np.array(ref)

    def hold(h, past):
        c = {k: v[0] for k, v in hold_modal(np.array([w]), np.array([z]), h, past).items()}
        x = v = 0.0
        out = [0.0]
        for i in range(round(1.0 / h)):
            pmm, pm, p0, p1 = (load((i + j) * h) for j in (-2, -1, 0, 1))
            x, v = (c["a11"] * x + c["a12"] * v + c["e1"] * pmm + c["d1"] * pm + c["b1"] * p0 + c["c1"] * p1,
                    c["a21"] * x + c["a22"] * v + c["e2"] * pmm + c["d2"] * pm + c["b2"] * p0 + c["c2"] * p1)
            out.append(x)
        return np.max(np.abs(np.array(out) - ref[::round(h / fine)]))

    out = {}
    for past, label in ((0, "linear"), (1, "quadratic"), (2, "cubic")):
        errs = [hold(h, past) for h in (0.02, 0.01)]
        out[f"{label} hold, one mode vs RK4: max error at h = 0.01 s, observed order"] = (errs[1], np.log2(errs[0] / errs[1]))
    return out


# ---------------------------------------------------------------- the events

def capture(crossing, dt: float):
    """``simulate`` at ``dt`` through ``kernels.implicit`` (``USE_LEAN`` off): its result and the call's arguments."""
    from vbikit.solve import integrators, kernels, simulate

    calls = []
    original = kernels.implicit

    def spy(*a, **k):
        calls.append(a)
        return original(*a, **k)

    kernels.implicit, integrators.USE_LEAN = spy, False
    try:
        res = simulate(dataclasses.replace(crossing, dt=dt))
    finally:
        kernels.implicit, integrators.USE_LEAN = original, True
    if len(calls) != 1:
        raise SystemExit(f"bench_load_hold: {len(calls)} kernel calls for one crossing (expected one)")
    return res, calls[0]


#: the holds compared: name → (past loads in the deck's hold, in the vehicles' hold); 0 linear, 1 quadratic, 2 cubic
HOLDS = {"linear": (0, 0), "quadratic": (1, 1), "cubic": (2, 2), "quadratic deck": (1, 0), "quadratic vehicles": (0, 1)}


def variant_inputs(call, hold: str):
    """``hold_loop``'s arguments (without ``updates`` and outputs) for the hold ``hold`` (``HOLDS``) on
    the inputs of the captured ``kernels.implicit`` call ``call`` (the floor's, ``bench_floor.floor_inputs``)."""
    from bench_floor import floor_inputs

    inputs, outs = floor_inputs(call)
    inputs = list(inputs)
    dt, modes, vehicles, points = call[0], call[2], call[3], call[4]
    n_m, n_d, n_w = modes.omega.size, vehicles.gravity.size, vehicles.wheel_rows.shape[0]
    deck, vehicle = HOLDS[hold]
    zm, zv = np.zeros(n_m), np.zeros((2 * n_d, n_w))
    extra = [zm, zm, zv, zm, zm, zv]  # d1, d2, load_m, e1, e2, load_mm
    del inputs[15:17]  # (the floor's d1, d2: the library's own hold; this loop takes the hold's below)
    c = hold_modal(modes.omega, modes.zeta, dt, deck)  # (deck = 0: the linear hold's)
    for i, key in zip(range(7, 15), ("a11", "a12", "a21", "a22", "b1", "b2", "c1", "c2")):
        inputs[i] = c[key]
    if deck:
        extra[0], extra[1], extra[3], extra[4] = c["d1"], c["d2"], c["e1"], c["e2"]
    if vehicle:
        vs, extra[2], extra[5] = hold_vehicle(vehicles, dt, vehicle)
        inputs[15:22] = [vs.transition, vs.load0, vs.constant, vs.settle, vs.response, vs.wheel_q, vs.wheel_v]
        ksum = np.bincount(points.wheel, weights=points.stiffness, minlength=n_w)
        csum = np.bincount(points.wheel, weights=points.damping, minlength=n_w)
        inputs[25] = np.linalg.inv(np.eye(n_w) + ksum[:, None] * vs.wheel_q + csum[:, None] * vs.wheel_v)
    return tuple(inputs) + tuple(extra), (outs[0].shape[0], n_m, n_d, n_w)


def run_variant(loop, call, hold: str, updates: int = 1):
    """(ξ, ξ̇) histories of ``hold_loop`` with ``hold`` on ``call``'s inputs."""
    inputs, (n_t, n_m, n_d, n_w) = variant_inputs(call, hold)
    xi, q, wf, xd = np.zeros((n_t, n_m)), np.zeros((n_t, n_d)), np.zeros((n_t, n_w)), np.zeros((n_t, n_m))
    loop(*inputs, updates, xi, q, wf, xd)
    return xi, xd


def smoothed(crossing, width: float):
    """``crossing`` on its roads smoothed by a moving average over ``width`` [m] (same stations)."""
    def smooth(road):
        if road is None:
            return None
        n = max(1, round(width / float(np.median(np.diff(road.x)))))
        z = np.convolve(np.pad(road.z, (n // 2, n - 1 - n // 2), mode="edge"), np.ones(n) / n, mode="valid")
        return dataclasses.replace(road, z=z)

    return dataclasses.replace(crossing, road=smooth(crossing.road), road_right=smooth(crossing.road_right))


#: rows of the IM table: the library (converged contact, linear hold), each hold with one update, the linear and
#: quadratic holds with three updates (the contact solve's convergence), RK4's history sampled at k dt
VARIANTS = ("library", *HOLDS, "linear x3", "quadratic x3", "rk4 sampled")
#: holds whose whole midspan history is compared with RK4's
HISTORY = ("linear", "quadratic", "cubic")


def event_errors(loop, crossing, y: float) -> tuple[float, bool, dict[str, list[float]], dict[str, list[float]]]:
    """Reference IM (RK4 at dt/8), whether a wheel lost contact (library, any k), ΔIM of every variant
    at every factor, and the midspan history's max error / peak (``HISTORY``) at the step points."""
    from vbikit.analysis import point_response
    from vbikit.analysis.impact import impact_factor
    from vbikit.analysis.response import point_shapes
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    dt = plan_run(crossing).grid.dt
    ref = simulate(dataclasses.replace(crossing, dt=dt / 8, integrator="rk4"))
    pr = point_response(ref, None, y)
    im_ref = pr.displacement_impact.impact_factor
    phi = point_shapes(crossing.bridge, *ref.point(None, y), checked=True)[0]
    u_ref = ref.xi @ phi
    peak = float(np.max(np.abs(u_ref)))
    rows: dict[str, list[float]] = {v: [] for v in VARIANTS}
    hist: dict[str, list[float]] = {v: [] for v in HISTORY}
    lost = False
    for k in FACTORS:
        res, call = capture(crossing, k * dt)
        lost |= bool(np.any(res.wheel_forces <= 0.0))
        st = point_response(res, None, y)
        rows["library"].append(st.displacement_impact.impact_factor - im_ref)
        every = round(8 * k)  # RK4's rows at the step points
        n = min(res.time.size, (ref.time.size - 1) // every + 1)
        assert np.allclose(res.time[:n], ref.time[::every][:n], atol=1e-9)
        for name, hold, updates in [(h, h, 1) for h in HOLDS] + [("linear x3", "linear", 3), ("quadratic x3", "quadratic", 3)]:
            xi, xd = run_variant(loop, call, hold, updates)
            u = xi[:res.time.size] @ phi
            rows[name].append(impact_factor(res.time, u, st.static_displacement, xd[:res.time.size] @ phi).impact_factor
                              - im_ref)
            if name in hist:
                hist[name].append(float(np.max(np.abs(u[:n] - u_ref[::every][:n]))) / peak)
        sub = slice(0, None, every)
        rows["rk4 sampled"].append(impact_factor(ref.time[sub], u_ref[sub], pr.static_displacement[sub],
                                                 ref.xi_dot[sub] @ phi).impact_factor - im_ref)
    return im_ref, lost, rows, hist


def floor_agreement(loop, crossing, y: float) -> list[float]:
    """The linear loop's midspan history against the library's, max difference / peak, at each factor."""
    from vbikit.analysis.response import point_shapes
    from vbikit.solve.plan import plan_run

    dt = plan_run(crossing).grid.dt
    out = []
    for k in FACTORS:
        res, call = capture(crossing, k * dt)
        phi = point_shapes(crossing.bridge, *res.point(None, y), checked=True)[0]
        u_lib = res.xi @ phi
        u = run_variant(loop, call, "linear")[0][:u_lib.size] @ phi
        out.append(float(np.max(np.abs(u[1:] - u_lib[1:])) / np.max(np.abs(u_lib))))
    return out


def vehicle_agreement(crossing) -> list[float]:
    """The linear hold's vehicle map from ``hold_vehicle`` against the library's ``vehicle_step``
    (transition, L0, L1: max difference / max entry)."""
    from vbikit.solve.plan import plan_run

    call = capture(crossing, plan_run(crossing).grid.dt)[1]
    lib, mine = call[8], hold_vehicle(call[3], call[0], 0)[0]
    return [float(np.abs(getattr(mine, k) - getattr(lib, k)).max() / np.abs(getattr(lib, k)).max())
            for k in ("transition", "load0", "load1")]


def demo_check(loop) -> list[str]:
    """The holds on the ``vbikit demo`` crossing (20 modes up to 2.9 kHz: ωh up to ≈ 18; multipoint
    tires, 36 points, class C road) at k = 1, 2, 3 × its step: ΔIM against RK4 at its own automatic step
    and whether the run stayed bounded (a two- or three-step hold has parasitic roots)."""
    from vbikit.analysis import point_response
    from vbikit.analysis.impact import impact_factor
    from vbikit.analysis.response import point_shapes
    from vbikit.scenario import demo_scenario_text, scenario_from_toml
    from vbikit.scenario.preflight import preflight
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    built = preflight(scenario_from_toml(demo_scenario_text(), source="demo.toml")).built
    crossing, x, y = built.crossing, built.response_x, built.response_y
    ref = point_response(simulate(dataclasses.replace(crossing, integrator="rk4")), x, y).displacement_impact
    dt = plan_run(crossing).grid.dt
    lines = []
    for k in (1.0, 2.0, 3.0):
        res, call = capture(crossing, k * dt)
        st = point_response(res, x, y)
        phi = point_shapes(crossing.bridge, *res.point(x, y), checked=True)[0]
        parts = [f"library {st.displacement_impact.impact_factor - ref.impact_factor:+.1e}"]
        for hold in HISTORY:
            xi, xd = run_variant(loop, call, hold)
            u = xi[:res.time.size] @ phi
            bounded = bool(np.all(np.isfinite(xi))) and float(np.max(np.abs(u))) < 2 * abs(ref.dynamic_peak)
            im = impact_factor(res.time, u, st.static_displacement, xd[:res.time.size] @ phi).impact_factor
            parts.append(f"{hold} {im - ref.impact_factor:+.1e}" + ("" if bounded else " (UNBOUNDED)"))
        lines.append(f"  k = {k:g} ({res.n_steps} steps): ΔIM " + ", ".join(parts))
    return lines


def where_error(loop, crossing, y: float) -> list[str]:
    """Where the quadratic and linear holds' midspan history errs most (against RK4 at dt/8) at k = 0.5,
    1, 2, and the nearest time a contact point enters or leaves the deck."""
    from vbikit.analysis.response import point_shapes
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    dt = plan_run(crossing).grid.dt
    ref = simulate(dataclasses.replace(crossing, dt=dt / 8, integrator="rk4"))
    phi = point_shapes(crossing.bridge, *ref.point(None, y), checked=True)[0]
    u_ref = ref.xi @ phi
    peak = float(np.max(np.abs(u_ref)))
    lines = []
    for k in (0.5, 1.0, 2.0):
        res, call = capture(crossing, k * dt)
        motion, modes, points = call[1], call[2], call[4]
        rows = np.arange(0, motion.travel.shape[0], 2)[:res.time.size]
        xp = points.origin + points.direction * motion.travel[rows][:, points.vehicle]
        on = (modes.start[points.track] <= xp) & (xp <= modes.end[points.track])
        switches = res.time[np.flatnonzero(np.any(np.diff(on.astype(int), axis=0) != 0, axis=1))]
        every = round(8 * k)
        n = min(res.time.size, (ref.time.size - 1) // every + 1)
        for hold in ("linear", "quadratic"):
            err = run_variant(loop, call, hold)[0][:n] @ phi - u_ref[::every][:n]
            i = int(np.argmax(np.abs(err)))
            near = float(np.min(np.abs(switches - res.time[i]))) if switches.size else float("nan")
            lines.append(f"  k = {k:g} {hold:9s}: max |u − u_RK4| / peak {abs(err[i]) / peak:.1e} at t = {res.time[i]:.3f} s, "
                         f"{1e3 * near:.0f} ms from a point entering or leaving the deck")
    ends = [float(np.abs(modes.values[t, [0, -1]]).max() / np.abs(modes.values[t]).max()) for t in np.unique(points.track)]
    lines.append("  the mode shapes at the deck's ends on the wheel tracks, largest |φ| there / largest |φ| on the track: "
                 + ", ".join(f"{e:.3f}" for e in ends) + " (a point's modal load jumps when it enters or leaves)")
    return lines


def per_step_cost(loop, crossing, repeat: int) -> dict[str, float]:
    """Thread CPU time a step [µs] of the loop with each of ``HISTORY``'s holds, one update (min of
    ``repeat`` runs, the holds alternating)."""
    from vbikit.solve.plan import plan_run

    _, call = capture(crossing, plan_run(crossing).grid.dt)
    prepared = {}
    for hold in HISTORY:
        inputs, (n_t, n_m, n_d, n_w) = variant_inputs(call, hold)
        prepared[hold] = (inputs, (np.zeros((n_t, n_m)), np.zeros((n_t, n_d)), np.zeros((n_t, n_w)),
                                   np.zeros((n_t, n_m))))
    times: dict[str, list[float]] = {v: [] for v in prepared}
    for _ in range(repeat):
        for hold, (inputs, outs) in prepared.items():
            t0 = time.thread_time()
            loop(*inputs, 1, *outs)
            times[hold].append(time.thread_time() - t0)
    n_steps = prepared["linear"][1][0].shape[0] - 1
    return {v: min(t) / n_steps * 1e6 for v, t in times.items()} | {"steps": n_steps}


def _table(label: str, table: dict[str, list], names) -> None:
    """Max / mean |value| per factor of each row ``names`` of ``table`` (events × factors)."""
    print(f"{label}: max / mean at k = {', '.join(f'{k:g}' for k in FACTORS)} × dt")
    for v in names:
        a = np.abs(np.array(table[v]))
        print(f"  {v:18s} " + "  ".join(f"{mx:.1e}/{mn:.1e}" for mx, mn in zip(a.max(axis=0), a.mean(axis=0))))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--single", type=int, default=10, help="one-truck events (default 10)")
    p.add_argument("--several", type=int, default=5, help="two-truck events (default 5)")
    p.add_argument("--road", default="B", help="ISO 8608 road class of the events (default B)")
    p.add_argument("--tire", default="point", help="tire model of the events (default point)")
    p.add_argument("--smooth", type=float, nargs="*", default=[0.10, 0.5],
                   help="also the events on their road smoothed over these widths [m] (default 0.10 0.5; none: skip)")
    p.add_argument("--no-demo", action="store_true", help="skip the demo crossing's stability check")
    p.add_argument("--repeat", type=int, default=15, help="timed runs of the per-step cost (default 15)")
    args = p.parse_args()

    from bench_traffic import _base, _stream

    from vbikit.traffic.study import traffic_study

    t_start = time.perf_counter()
    print("coefficient checks:")
    for key, val in check_coefficients().items():
        print(f"  {key}: " + (f"{val[0]:.2e}, {val[1]:.2f}" if isinstance(val, tuple) else f"{val:.1e}"))
    loop = _hold_loop()
    base = _base(0.01)
    base["road"]["class"] = args.road
    base["tire"]["model"] = args.tire
    job = traffic_study(_stream(2000, 600.0), base, batch_size=16)
    ctx = job.context()
    events = []
    for size, count in ((1, args.single), (2, args.several)):
        events += [e for e in range(job.size) if len(job.events[e]) == size][:count]
    crossings = [ctx.template.with_vehicles(job.crossing(e).vehicles, *ctx.road(job.road_seed(e))) for e in events]
    y = float(crossings[0].bridge.girder_y[3])
    for c in {len(c.vehicles): c for c in crossings}.values():
        print(f"linear hold's vehicle map vs the library's vehicle_step ({len(c.vehicles)} truck(s)): transition, L0, L1 "
              + ", ".join(f"{d:.1e}" for d in vehicle_agreement(c)))
    print(f"linear loop vs the library's midspan history (event {events[0]}): max diff / peak at k = "
          + ", ".join(f"{k:g}: {a:.1e}" for k, a in zip(FACTORS, floor_agreement(loop, crossings[0], y))))
    for width in [0.0] + list(args.smooth):
        label = f"class {args.road} road" + (f" smoothed over {width:g} m" if width else "")
        table: dict[str, list] = {v: [] for v in VARIANTS}
        hist: dict[str, list] = {v: [] for v in HISTORY}
        lost_any = 0
        for e, c in zip(events, crossings):
            im_ref, lost, rows, errs = event_errors(loop, smoothed(c, width) if width else c, y)
            lost_any += lost
            for v in VARIANTS:
                table[v].append(rows[v])
            for v in HISTORY:
                hist[v].append(errs[v])
            print(f"  event {e} ({len(c.vehicles)} truck(s), {3.6 * c.speed:.0f} km/h) IM {im_ref:.5f}: ΔIM "
                  + "; ".join(f"{v} " + ", ".join(f"{d:+.1e}" for d in rows[v]) for v in HISTORY)
                  + ("; a wheel lost contact" if lost else ""), flush=True)
        _table(f"{label}, {len(events)} events ({lost_any} with loss of contact), |ΔIM| against RK4 at dt/8",
               table, VARIANTS)
        for v in HISTORY:  # a bias (one sign) or scatter
            print(f"  signed mean ΔIM, {v:9s} " + "  ".join(f"{x:+.1e}" for x in np.mean(table[v], axis=0)))
        _table(f"{label}: midspan history, max |u − u_RK4| / peak at the step points", hist, HISTORY)
    if args.smooth:
        print(f"where the history errs (event {events[0]}, road smoothed over {max(args.smooth):g} m):")
        for line in where_error(loop, smoothed(crossings[0], max(args.smooth)), y):
            print(line)
    if not args.no_demo:
        print("the demo crossing (20 modes, multipoint tires, class C), ΔIM against RK4 at its automatic step:")
        for line in demo_check(loop):
            print(line)
    cost = per_step_cost(loop, crossings[0], args.repeat)
    print(f"per-step cost of the loop, thread CPU, min of {args.repeat} ({cost['steps']} steps, one update): "
          + ", ".join(f"{h} {cost[h]:.3f} µs" for h in HISTORY))
    print(f"total {time.perf_counter() - t_start:.0f} s wall")


if __name__ == "__main__":
    main()
