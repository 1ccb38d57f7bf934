"""The coupled system matrices at one instant (the static start, Newmark checks) and the static modal
load history. (``vbikit.solve.kernels``: the equations and conventions.)"""
from __future__ import annotations

from numba import njit

from vbikit.solve.kernels.bundles import _flat
from vbikit.solve.kernels.contact import hermite_shape
from vbikit.solve.kernels.lean import _shape


@njit(cache=True, fastmath=True, error_model="numpy")
def assemble(x, vx, r, rdot, modes, vehicles, points, phi, dphi, have, active, mass, damp, stiff, load):
    """Coupled system matrices of Eq. 9 at one instant, M ü + C u̇ + K u = F with u = [ξ; q], for
    the contact points at positions ``x`` [m] with x-rates ``vx`` [m/s] flagged ``active``: the
    linearisation of the contact law (module docstring) about contact, where F_p = k δ + c δ̇ +
    f0 (road ``r`` [m] and its rate ``rdot`` [m/s] under each point given).  The bundles' form of
    ``assemble_flat`` (which does the work)."""
    assemble_flat(x, vx, r, rdot, modes.omega, modes.zeta, modes.start, modes.end, modes.grid_h, modes.values,
                  modes.slopes, vehicles.mass, vehicles.damping, vehicles.stiffness, vehicles.gravity,
                  vehicles.wheel_rows, points.stiffness, points.damping, points.fixed_load, points.gap,
                  points.wheel, points.track, phi, dphi, have, active, mass, damp, stiff, load)


@_flat
def assemble_flat(x, vx, r, rdot, omega, zeta, start, end, grid_h, values, slopes, m_v, c_v, k_v, f_g, wheel_rows,
                  kk, cc, f0, gap, wheel, track, phi, dphi, have, active, mass, damp, stiff, load):
    """``assemble`` on plain arrays (the fields of ``Modes``, ``Vehicles`` and ``Points`` one by one:
    the static start of one crossing compiles only flat kernels, as ``lean``)."""
    n_m = omega.size
    n_d = f_g.size
    _, n_grid, _ = values.shape
    for a in range(n_m + n_d):
        load[a] = 0.0
        for b in range(n_m + n_d):
            mass[a, b] = 0.0
            damp[a, b] = 0.0
            stiff[a, b] = 0.0
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
    n = n_m + n_d
    for p in range(kk.size):
        if not active[p]:
            continue
        k = kk[p]
        c = cc[p]
        ext = k * (r[p] - gap[p]) + c * rdot[p] + f0[p]
        h = wheel_rows[wheel[p]]
        on = start[track[p]] <= x[p] <= end[track[p]]
        if on and not have[p]:
            _shape(x[p], track[p], start, grid_h, values, slopes, n_grid, phi, dphi, p)
            have[p] = True
        cv = c * vx[p]
        # the point's row of ∂δ_p/∂u, b = [φ_p; −h_w] (φ_p = 0 off the deck), and of the convective rate
        # ∂δ̇_p/∂u = v [φ'_p; 0]: K += k b bᵀ + c b (v [φ'_p; 0])ᵀ, C += c b bᵀ, F −= b (k (r − g) + c ṙ + f0)
        for a in range(n):
            ba = (phi[p, a] if on else 0.0) if a < n_m else -h[a - n_m]
            load[a] -= ba * ext
            for b in range(n):
                bb = (phi[p, b] if on else 0.0) if b < n_m else -h[b - n_m]
                gb = dphi[p, b] if on and b < n_m else 0.0
                stiff[a, b] += k * ba * bb + cv * ba * gb
                damp[a, b] += c * ba * bb


@_flat
def static_modal_history(travel, origin, direction, vehicle, track, loads, start, end, grid_h, values, slopes, out, phi,
                         dphi):
    """Σ_p φ(x_p(t)) P_p into ``out`` (n_t, n_m), zeroed, for downward point loads ``loads`` P_p [N] at
    x_p = ``origin``_p + ``direction``_p·s_v(t) on ``track``_p, ``travel`` (n_t, n_vehicles) [m] (the
    fields of ``Points`` and ``Modes`` one by one; tabulated shapes, as the solver; ``phi``, ``dphi``
    (n_m,) work space); ξ_st = −that / ω²."""
    for t in range(len(travel)):
        for p in range(origin.size):
            if loads[p] == 0.0:
                continue
            x = origin[p] + direction[p] * travel[t, vehicle[p]]
            if start[track[p]] <= x <= end[track[p]]:
                hermite_shape(x, track[p], start, grid_h, values, slopes, phi, dphi)
                for m in range(phi.size):
                    out[t, m] += phi[m] * loads[p]
