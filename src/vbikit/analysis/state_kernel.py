"""The compiled pass of ``vbikit.analysis.instants.run_state``: a coupled run's state at instants
between its steps, element by element, in one call (the same formulas as the module docstring of
``vbikit.analysis.instants``, written as loops: the population runners ask for it once an event, and
the array version spent most of its time in the calls between its small arrays).

For every instant u (between the stored steps t_{k−1} ≤ u ≤ t_k, w = (u − t_{k−1}) / h):

* the vehicles' travel s_v(u) = s_ref + v τ + a τ²/2, τ = min(u − t_ref, t_stop) (``Crossing.travel``)
  and the points' x_p = origin_p + sign_p s_v(p)(u);
* the wheel forces f_w linear, the points' β_p f_w;
* ξ_i by cubic Hermite interpolation of (ξ_i, ξ̇_i) at the two steps;
* Q_i = −(ξ̈_i + 2 ζ_i ω_i ξ̇_i + ω_i² ξ_i) at the two steps, linear between them, except the shares
  φ_i(x_p) β_p f_w of the points that pass a support line within the step (ξ_p = x_p − y_p tan θ at the
  step's two ends on either side of, or on, a support's ξ): for those the linear share is replaced by
  the exact one at u, φ from the run's mode tables (cubic Hermite, ``kernels.hermite_shape``; 0 off
  the table of the point's track).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from vbikit.solve.kernels.contact import hermite_shape
from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the @njit(cache=True) below


@njit(cache=True, inline="always")
def _travel(t, t_ref, s_ref, v_ref, acc, stop, out):  # pragma: no cover (compiled)
    """s_v(t) of every vehicle into ``out`` (``Crossing.travel``)."""
    for v in range(t_ref.size):
        tau = min(t - t_ref[v], stop[v])
        out[v] = s_ref[v] + v_ref[v] * tau + 0.5 * acc[v] * tau**2


@njit(cache=True)
def run_state_pass(u, t, t_ref, s_ref, v_ref, acc, stop, origin, sign, y, point_vehicle, wheel, weight, forces, xi,
                   xi_dot, xi_ddot, damping, stiffness, support_x, skew_tan, start, end, grid_h, values, slopes, track,
                   travel, x, wheel_forces, f, q, xi_u):  # pragma: no cover (compiled)
    """Fill ``travel`` (n_u, n_vehicles), ``x``, ``f`` (n_u, n_cp), ``wheel_forces`` (n_u, n_wheels),
    ``q`` and ``xi_u`` (n_u, n_modes) at the instants ``u`` (module docstring); ``damping`` = 2 ζ ω,
    ``stiffness`` = ω² per mode; ``start``, ``end``, ``grid_h``, ``values``, ``slopes``: the run's mode
    tables, ``track`` each point's."""
    n_t = t.size
    n_cp = origin.size
    n_m = xi.shape[1]
    n_w = forces.shape[1]
    s0 = np.empty(t_ref.size)
    s1 = np.empty(t_ref.size)
    phi = np.empty(n_m)
    dphi = np.empty(n_m)
    for j in range(u.size):
        uj = u[j]
        lo, hi = 1, n_t - 1  # the step ending at or after u, within 1 … n_t − 1 (searchsorted of t[1:-1], left)
        while lo < hi:
            mid = (lo + hi) // 2
            if t[mid] < uj:
                lo = mid + 1
            else:
                hi = mid
        k = lo
        km = k - 1
        h = t[k] - t[km]
        w = (uj - t[km]) / h
        _travel(uj, t_ref, s_ref, v_ref, acc, stop, travel[j])
        for p in range(n_cp):
            x[j, p] = origin[p] + sign[p] * travel[j, point_vehicle[p]]
        for i in range(n_w):
            wheel_forces[j, i] = forces[km, i] * (1.0 - w) + forces[k, i] * w
        for p in range(n_cp):
            f[j, p] = wheel_forces[j, wheel[p]] * weight[p]
        w2 = w**2
        w3 = w**3
        h00, h10, h01, h11 = 2 * w3 - 3 * w2 + 1, w3 - 2 * w2 + w, -2 * w3 + 3 * w2, w3 - w2
        for m in range(n_m):
            xi_u[j, m] = (h00 * xi[km, m] + (h10 * h) * xi_dot[km, m] + h01 * xi[k, m] + (h11 * h) * xi_dot[k, m])
            q_km = -(xi_ddot[km, m] + xi_dot[km, m] * damping[m] + xi[km, m] * stiffness[m])
            q_k = -(xi_ddot[k, m] + xi_dot[k, m] * damping[m] + xi[k, m] * stiffness[m])
            q[j, m] = (1.0 - w) * q_km + w * q_k
        # the points that pass a support line within the step: their share exact, not linear
        _travel(t[km], t_ref, s_ref, v_ref, acc, stop, s0)
        _travel(t[k], t_ref, s_ref, v_ref, acc, stop, s1)
        for p in range(n_cp):
            x0 = origin[p] + sign[p] * s0[point_vehicle[p]]
            x1 = origin[p] + sign[p] * s1[point_vehicle[p]]
            xi0 = x0 - y[p] * skew_tan
            xi1 = x1 - y[p] * skew_tan
            passing = False
            for s in support_x:
                if (xi0 - s) * (xi1 - s) <= 0.0:
                    passing = True
            if not passing:
                continue
            tr = track[p]
            for e in range(3):  # the exact share at u, less the linear one
                if e == 0:
                    xe, load, coef = x[j, p], f[j, p], 1.0
                elif e == 1:
                    xe, load, coef = x0, forces[km, wheel[p]] * weight[p], -(1.0 - w)
                else:
                    xe, load, coef = x1, forces[k, wheel[p]] * weight[p], -w
                if not (start[tr] <= xe and xe <= end[tr]):
                    continue  # off the deck: no share
                hermite_shape(xe, tr, start, grid_h, values, slopes, phi, dphi)
                for m in range(n_m):
                    q[j, m] += coef * (phi[m] * load)
