"""The lean implicit step loop for many lanes: ``lean``'s arithmetic on L crossings that share their
motion and differ only in the road, the lane index innermost. (``vbikit.solve.kernels``: the
equations and conventions; ``vbikit.solve.kernels.lean``: the step, one lane.)

State as (·, L) arrays (ξ (n_m, L), z (2n_d, L), point forces (n_cp, L), wheel sums (n_w, L)), so
that every per-point, per-mode and per-DOF loop ends in a contiguous loop over the lanes, which the
compiler vectorises.  What the motion fixes is computed once a step for all lanes: the point
positions, which points are on the deck, the mode shapes φ_p, φ'_p (cubic Hermite, on first use in
the step) and each point's road cell.  Each lane then takes ``lean``'s step with its own numbers
(a product regrouped, the same to round-off: the vehicles' settled free response
z_b = (P Φ) z_n + (P L0) G_n + P g through the fused map of ``FusedVehicleStep``; the vehicles'
accelerations q̈ follow when read, ``vbikit.solve.result.DeferredAccelerations``; and one factorisation
of I + S_A U_A shared by the lanes of the same active sums, the solve running across them):

1. the first guess F = 2F_n − F_{n−1}, its end state and the contact law there (``_law_lanes``: one
   evaluation for all lanes);
2. per lane the error max_p |law_p − F_p|; lanes above ``tol`` [N] take quasi-Newton updates
   through the vehicles (``_quasi_lanes``: (I + S_A U_A) t = S_A b with each lane's factors kept
   while its active sums stay), the law at each iterate following from the last evaluation by the
   exact increments of the state, at most ``LEAN_CORRECTIONS`` times.  Lanes already settled take
   zero increments (their numbers stay as they are, bit for bit).

A lane whose step needs more than that (a gated point's activity changes in the updates, a point
left out by the lazy test may touch, the corrections do not settle) is *frozen* at that step: its
``stop`` entry is set to the step, its later rows are not written, and it takes no part in the
shared decisions after (which points the lazy test keeps).  With the wheel loads held quadratic
(Lp ≠ 0) a step in which a wheel of some lane lands or lifts off is solved a second time in that lane, with
G_{n−1} = 2G_n − G_{n+1} of the first solution, as ``lean`` does it: from the first solution's forces and end
state, z shifted by P Lp ΔG_{n−1} and the law by its exact increments (``_shift_vehicles_lanes``), then the
quasi-Newton updates for those lanes only; the other lanes' shift is zero and their numbers stay as they are
(before 2026-12-07 every lane took the whole step again).  The caller
runs the steps in chunks (``integrators._run_lanes``): a frozen lane goes on alone from its last
stored row (``implicit`` for the contact event's window, then the one-lane ``lean``,
``integrators._finish_lane``) and rejoins a later call with the state the one-lane kernel left, or
afresh after a window; a lane whose ``stop`` entry is −2 sits the call out.  The other lanes go on
from the state the call leaves (``carry_f``, ``carry_p``, ``carry_g``), exactly as without the chunks.

The lazy test is shared and reads the road under each point (interpolated for all lanes, the
cheap part): a gated point's deck terms are evaluated for every lane when any live lane's bound
r_p − g_p − z_w + B on δ_p may be positive (B = Σ_m amp_m |ξ_m| ≥ |φ_p·ξ|; the one-lane kernel
bounds r_p by the highest elevation r_max); a lane whose own bound is ≤ 0 then finds δ ≤ 0 and
F = 0, as the one-lane kernel does by leaving the point out.  A point left out for all lanes, and a used gated point with δ ≤ 0 in every lane, must keep
δ ≤ 0 under the updates: both are watched through each wheel's largest bound (or δ) plus the
bound of the updates' change, B(Δξ) + Δ(−z_w), without their mode sums (a lane whose bound
becomes positive is frozen, where the one-lane kernel might still find δ ≤ 0: a lane frozen a
step early, never a different result).  Rigid-disk envelopes are not handled (the caller sends them to ``implicit``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from vbikit.solve.kernels.bundles import _internal
from vbikit.solve.kernels.contact import hermite_shape, road_cells, secant_ends
from vbikit.solve.kernels.hold import hold_correction_lanes, hold_jumps
from vbikit.solve.kernels.lanes import MANY_LANES
from vbikit.solve.kernels.dense import solve_held
from vbikit.solve.kernels.newton import LEAN_CORRECTIONS
from vbikit.solve.kernels.woodbury import vehicle_back, vehicle_factors, vehicle_rhs


@_internal
def _deck_lanes(phi, dphi, k, rate, x, v, s, dr, sd):
    """Add the deck's part of point ``k``'s position φ_k·x to ``s``, velocity φ_k·v to ``dr`` and slope
    ``rate`` φ'_k·x to ``sd`` in every lane (x, v (n_m, L); s, dr, sd (L,)): of the state in the law
    (``_law_lanes``, ``rate`` the point's x-rate: the convective rate), of its increments in the updates
    (``rate`` 1)."""
    n_m, n_l = x.shape  # (unpacked: numba types an indexed shape through a compiled overload)
    for m in range(n_m):
        ph = phi[k, m]
        dph = rate * dphi[k, m]
        for lane in range(n_l):
            s[lane] += ph * x[m, lane]
            dr[lane] += ph * v[m, lane]
            sd[lane] += dph * x[m, lane]


@_internal
def _law_lanes(x1, v1, z1, n_d, xp, vxp, onb, live, phi, dphi, have, rv, rr, idx, start, grid_h, values, slopes, amp,
               wheel_dof, wheel_h, wheel_first, wheel_count, track, line, kk, cc, f0, gap, gated, width, stations,
               elevations, r_max, span, force, active, used, pen, law, wf, wl, lo_on, lo_off, bmax, zw, dzw, s_l, sd_l,
               dr_l):
    """``lean._law`` for every lane at the state (ξ, ξ̇) = (``x1``, ``v1``), z = ``z1`` (each (·, L)):
    per point and lane ``force`` (gated), ``active``, penetration ``pen``, ungated law ``law``; per
    point ``used`` (False: left out for every lane by the shared lazy test); per wheel and lane the
    force sum ``wf``, patch length ``wl`` and the largest bound r_p − g − z_w + B of its left-out
    points on the deck (``lo_on``) and off it (``lo_off``; −1e300 without such points: the
    updates add the same increments to every left-out point of a wheel, so its largest bound is
    the one to watch).  Shapes and road on first use in the step (``have`` as in ``lean._law``; the road
    rate the secant over |v|·``span`` either side, ``road_point``); ``bmax``,
    ``zw``, ``dzw``, ``s_l``, ``sd_l``, ``dr_l`` (L,) are work space."""
    n_m = x1.shape[0]
    n_l = x1.shape[1]
    for lane in range(n_l):
        bmax[lane] = 0.0
    for m in range(n_m):
        a = amp[m]
        for lane in range(n_l):
            bmax[lane] += a * abs(x1[m, lane])
    for w in range(wheel_dof.shape[0]):
        for lane in range(n_l):
            zw[lane] = 0.0
            dzw[lane] = 0.0
            wf[w, lane] = 0.0
            wl[w, lane] = 0.0
            lo_on[w, lane] = -1e300
            lo_off[w, lane] = -1e300
        for e in range(wheel_dof.shape[1]):  # the nonzero entries of h_w (``lean.wheel_entries``)
            h = wheel_h[w, e]
            if h != 0.0:
                j = wheel_dof[w, e]
                for lane in range(n_l):
                    zw[lane] += h * z1[j, lane]
                    dzw[lane] += h * z1[n_d + j, lane]
        first = wheel_first[w]
        for p in range(first, first + wheel_count[w]):
            x = xp[p]
            if have[p] < 2:  # the road under the point (``road_point``): one cell for all lanes
                ln = line[p]
                vx = vxp[p]
                lo, hi = secant_ends(x, vx, span)
                a = hi - lo
                ia, ta, ib, tb, i = road_cells(stations, lo, hi, x, vx, idx, p)
                if a > 0.0:  # the secant rate
                    scale = vx / a
                    for lane in range(n_l):
                        rr[p, lane] = (elevations[ln, ib, lane] + tb * (elevations[ln, ib + 1, lane]
                                                                        - elevations[ln, ib, lane])
                                       - elevations[ln, ia, lane]
                                       - ta * (elevations[ln, ia + 1, lane] - elevations[ln, ia, lane])) * scale
                dx = x - stations[i]
                inv = 1.0 / (stations[i + 1] - stations[i])
                for lane in range(n_l):
                    slope = (elevations[ln, i + 1, lane] - elevations[ln, i, lane]) * inv
                    rv[p, lane] = elevations[ln, i, lane] + slope * dx
                if a <= 0.0:  # its own lane loop: a test inside the one above vectorises worse (≈ 2 %, measured)
                    for lane in range(n_l):
                        rr[p, lane] = (elevations[ln, i + 1, lane] - elevations[ln, i, lane]) * inv * vx
                have[p] += 2
            if gated[p]:
                gp = gap[p]
                touch = False
                if onb[p]:
                    for lane in range(n_l):
                        bound = rv[p, lane] - gp - zw[lane] + bmax[lane]
                        s_l[lane] = bound
                        touch = touch or (live[lane] and bound > 0.0)
                else:
                    for lane in range(n_l):
                        bound = rv[p, lane] - gp - zw[lane]
                        s_l[lane] = bound
                        touch = touch or (live[lane] and bound > 0.0)
                if not touch:
                    used[p] = False
                    if onb[p]:
                        for lane in range(n_l):
                            lo_on[w, lane] = max(lo_on[w, lane], s_l[lane])
                    else:
                        for lane in range(n_l):
                            lo_off[w, lane] = max(lo_off[w, lane], s_l[lane])
                    for lane in range(n_l):
                        force[p, lane] = 0.0
                        active[p, lane] = False
                    continue
            used[p] = True
            if onb[p] and have[p] % 2 == 0:
                hermite_shape(x, track[p], start, grid_h, values, slopes, phi[p], dphi[p])
                have[p] += 1
            for lane in range(n_l):
                s_l[lane] = rv[p, lane]
                sd_l[lane] = rr[p, lane]
                dr_l[lane] = 0.0
            if onb[p]:
                _deck_lanes(phi, dphi, p, vxp[p], x1, v1, s_l, dr_l, sd_l)
            g = gap[p]
            k = kk[p]
            c = cc[p]
            fz = f0[p]
            gp = gated[p]
            wd = width[p]
            for lane in range(n_l):
                pn = s_l[lane] - g - zw[lane]
                fl = k * pn + c * (sd_l[lane] + dr_l[lane] - dzw[lane]) + fz
                pen[p, lane] = pn
                law[p, lane] = fl
                on = not gp or (pn > 0.0 and fl > 0.0)
                fk = fl if on else 0.0
                force[p, lane] = fk
                active[p, lane] = on
                wf[w, lane] += fk
                wl[w, lane] += wd if on else 0.0


@_internal
def _add_product_lanes(matrix, v, out):
    """out += matrix v in every lane (out (n_rows, L), v (n_cols, L)), zero entries of ``matrix``
    skipped (the vehicles' maps are block-diagonal for several vehicles, and sparse)."""
    n_rows, n_cols = matrix.shape  # (unpacked: numba types an indexed shape through a compiled overload)
    _, n_l = out.shape
    for i in range(n_rows):
        for j in range(n_cols):
            a = matrix[i, j]
            if a != 0.0:
                for lane in range(n_l):
                    out[i, lane] += a * v[j, lane]


@_internal
def _affine_lanes(constant, matrix, load, z, g, out):
    """out = constant + matrix z + load g in every lane (out (n_rows, L), z (n_cols, L), g (n_w, L)):
    the fused vehicle map of ``FusedVehicleStep`` (the settled free response), zero entries of
    ``matrix`` and ``load`` skipped (each sum in the same order as one loop over both)."""
    n_rows, n_l = out.shape
    for i in range(n_rows):
        ci = constant[i]
        for lane in range(n_l):
            out[i, lane] = ci
    _add_product_lanes(matrix, z, out)
    _add_product_lanes(load, g, out)


@_internal
def _wheel_loads_lanes(wf, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c, out):
    """The wheel loads G_w = F_w + k_w z_w + c_w ż_w (``VehicleStep``) of every lane into ``out`` (n_w, L), from
    the wheels' contact force sums ``wf`` (n_w, L) and the vehicles' state ``z1`` (q, q̇) (2n_d, L)."""
    n_w, n_l = out.shape
    for w in range(n_w):
        kw = wheel_k[w]
        cw = wheel_c[w]
        for lane in range(n_l):
            out[w, lane] = wf[w, lane]
        for e in range(wheel_dof.shape[1]):
            h = wheel_h[w, e]
            if h != 0.0:
                j = wheel_dof[w, e]
                for lane in range(n_l):
                    out[w, lane] += h * (kw * z1[j, lane] + cw * z1[n_d + j, lane])


@_internal
def _shift_vehicles_lanes(free_past, dg, dz, z1, n_d, wheel_dof, wheel_h, bq, bv):
    """The vehicles' end state of a step whose wheel loads before it change by ``dg`` (n_w, L): z_b and hence
    z change by P Lp ΔG_{n−1} (``VehicleStep``; ``dz`` (2n_d, L) receives it), and each wheel's −z_w, −ż_w by
    ``bq``, ``bv`` (n_w, L; the quasi-Newton updates' wheel increments, same signs)."""
    n_z, n_l = dz.shape
    for i in range(n_z):
        for lane in range(n_l):
            dz[i, lane] = 0.0
    _add_product_lanes(free_past, dg, dz)
    for i in range(n_z):
        for lane in range(n_l):
            z1[i, lane] += dz[i, lane]
    for w in range(wheel_dof.shape[0]):
        for lane in range(n_l):
            bq[w, lane] = 0.0
            bv[w, lane] = 0.0
        for e in range(wheel_dof.shape[1]):
            h = wheel_h[w, e]
            if h != 0.0:
                j = wheel_dof[w, e]
                for lane in range(n_l):
                    bq[w, lane] -= h * dz[j, lane]
                    bv[w, lane] -= h * dz[n_d + j, lane]


@_internal
def _state_lanes(f, nz, onb, xp, have, start, grid_h, values, slopes, track, phi, dphi, wheel, c1, c2, response, xf, vf,
                 zb, p, fw, x1, v1, z1):
    """``lean._state`` for every lane: p = −Σ_{p on the deck} φ_p F_p, F_w = Σ_{p∈w} F_p,
    ξ = ξ_f + c1 p, ξ̇ = ξ̇_f + c2 p, z = z_b + (P L1) F_w (each (·, L)); ``nz``: the points with a
    nonzero force in some lane (the others add nothing)."""
    n_m = p.shape[0]
    n_l = p.shape[1]
    for m in range(n_m):
        for lane in range(n_l):
            p[m, lane] = 0.0
    for w in range(fw.shape[0]):
        for lane in range(n_l):
            fw[w, lane] = 0.0
    for k in range(f.shape[0]):
        if not nz[k]:
            continue
        wk = wheel[k]
        for lane in range(n_l):
            fw[wk, lane] += f[k, lane]
        if onb[k]:
            if have[k] % 2 == 0:
                hermite_shape(xp[k], track[k], start, grid_h, values, slopes, phi[k], dphi[k])
                have[k] += 1
            for m in range(n_m):
                ph = phi[k, m]
                for lane in range(n_l):
                    p[m, lane] -= ph * f[k, lane]
    for m in range(n_m):
        a = c1[m]
        b = c2[m]
        for lane in range(n_l):
            x1[m, lane] = xf[m, lane] + a * p[m, lane]
            v1[m, lane] = vf[m, lane] + b * p[m, lane]
    for i in range(z1.shape[0]):
        for lane in range(n_l):
            z1[i, lane] = zb[i, lane]
        for w in range(fw.shape[0]):
            r = response[i, w]
            if r != 0.0:
                for lane in range(n_l):
                    z1[i, lane] += r * fw[w, lane]


@_internal
def _quasi_lanes(f, force, active, kk, cc, wheel, wheel_q, wheel_v, fw, ksum, csum, held, veh, piv, bq, bv, t, work,
                 pts, n_pts):
    """``lean._quasi`` for the lanes with ``work`` set (``woodbury``: the wheels' part): F_A = law_A +
    k bq_w + c bv_w, F = 0 off A, (bq, bv) = b − (wheel_q, wheel_v) t, b = (wheel_q, wheel_v) F_w,
    (I + S_A U_A) t = S_A b.  Each lane keeps the factors of its V = I + S_A U_A (``veh[lane]``,
    ``piv[lane]``) while its active sums (``held[lane]``) stay; when every working lane has the same
    sums (all points active, the common case) one set of factors (slot L) serves them all and the
    solve runs across the lanes.  Other lanes keep F and get bq = bv = 0.  Only the points
    ``pts[:n_pts]`` are visited (the others are inactive with F = 0 in every lane)."""
    n_w = fw.shape[0]
    n_l = fw.shape[1]
    for w in range(n_w):
        for lane in range(n_l):
            ksum[w, lane] = 0.0
            csum[w, lane] = 0.0
    for i in range(n_pts):
        k = pts[i]
        wk = wheel[k]
        a = kk[k]
        b = cc[k]
        for lane in range(n_l):
            on = active[k, lane]
            ksum[wk, lane] += a if on else 0.0
            csum[wk, lane] += b if on else 0.0
    vehicle_rhs(wheel_q, wheel_v, fw, ksum, csum, np.int64(-1), bq, bv, t, np.int64(0), n_l)
    for i in range(n_pts):
        k = pts[i]
        wk = wheel[k]
        for lane in range(n_l):
            t[wk, lane] += force[k, lane] if active[k, lane] else 0.0
    ref = -1  # the first working lane; the others share its factors when their active sums are its own
    shared = True
    for lane in range(n_l):
        if work[lane]:
            if ref < 0:
                ref = lane
            else:
                for w in range(n_w):
                    if ksum[w, lane] != ksum[w, ref] or csum[w, lane] != csum[w, ref]:
                        shared = False
                        break
        if not shared:
            break
    if shared and ref >= 0:  # one factorisation (slot n_l), the solve vectorised over the lanes
        vehicle_factors(veh[n_l], piv[n_l], held[n_l], ksum, csum, ref, wheel_q, wheel_v)
        solve_held(veh[n_l], piv[n_l], t, np.int64(0), n_l)
    for lane in range(n_l):  # else each lane's own n_w-square solve (n_w is a few wheels)
        if shared or not work[lane]:
            continue
        vehicle_factors(veh[lane], piv[lane], held[lane], ksum, csum, lane, wheel_q, wheel_v)
        solve_held(veh[lane], piv[lane], t, lane, lane + 1)
    vehicle_back(wheel_q, wheel_v, t, bq, bv, np.int64(0), n_l)
    for w in range(n_w):
        for lane in range(n_l):
            if not work[lane]:
                bq[w, lane] = 0.0
                bv[w, lane] = 0.0
    for i in range(n_pts):
        k = pts[i]
        wk = wheel[k]
        a = kk[k]
        b = cc[k]
        for lane in range(n_l):
            if work[lane]:
                f[k, lane] = force[k, lane] + a * bq[wk, lane] + b * bv[wk, lane] if active[k, lane] else 0.0


def _make_lean_lanes(QUADRATIC: bool):  # noqa: N803 (a compile-time constant of the variant)
    """``lean_lanes`` compiled for the vehicles' maps with the wheel loads held linear (``QUADRATIC`` False:
    Lp = 0) or quadratic (True: a step in which a lane's wheel lands or lifts off is solved a second time,
    module docstring).  Two variants, each compiled on its first use (``lean._make_lean``)."""

    def lean_lanes(travel, speed, start, end, grid_h, values, slopes, amp, omega, zeta, a11, a12, a21, a22, b1, b2, c1, c2,
                   d1, d2, free, free_load, free_constant, free_past, response, wheel_q, wheel_v, wheel_dof, wheel_h, wheel_k,
                   wheel_c, wheel_first, wheel_count, origin, direction, vehicle, track, line, kk, cc, f0, gap, gated, wheel,
                   width, stations, elevations, r_max, span, xi, dxi, q, dq, ddxi, wheel_force, wheel_len, tol, stride, stop,
                   first, last, fresh, carry_f, carry_p, carry_g, carry_pm, carry_gm, x_past):
        """The lean step loop of L lanes (module docstring).  Arguments as ``lean``'s, but the road's
        ``elevations`` of every lane (n_lines, n_s, L), ``r_max`` the highest of all, the outputs of
        ``implicit`` but q̈ for L lanes (each (L, n_stored, ·), row 0 the static start; ``r_max`` is not read:
        the lazy test reads the road under each point) and ``stop`` (L,),
        int64, filled: −1 for a lane whose every step was taken, else the first step n (0-based,
        t_n → t_{n+1}) that lane needs more than the lean path for (its rows from n + 1 on are not
        filled).

        ``span`` as ``lean``'s: negative, the start state of a call with ``first`` = 0 (the run's start)
        reads the road ahead only (``road_point``); every other evaluation the secant over |span|.

        The call takes steps ``first`` … ``last`` − 1 (``first`` a multiple of ``stride``), starting
        from the stored row first / stride.  A lane with ``fresh`` set starts there as at t = 0 (the law
        at that state, the forces extrapolated from it alone, row ``first`` / ``stride``'s loads and
        accelerations written); any other lane goes on from the previous call's end, exactly as if
        the loop had not stopped: its forces at the last two steps (``carry_f`` (2, n_cp, L)), modal
        load (``carry_p`` (n_m, L)) and wheel loads (``carry_g`` (n_w, L)), which the call leaves
        there for the next one when it returns with a live lane.  The hold's loads of the step before
        (``carry_pm`` (n_m, L), ``carry_gm`` (n_w, L)) are carried the same way and read for every lane
        but at the run's start (``first`` = 0: the start's own, the loads held constant before t_0); a
        lane's are written at each row it stores, so that a frozen lane's are those before its last
        stored row, where ``implicit`` goes on from, and a fresh lane comes with them filled.  Returns
        the number of contact-law evaluations after the start (one a step, for all lanes at once).
        ``x_past`` (n_cp,): the points' positions [m] a step before ``first`` (``lean``'s)."""
        n_steps = last
        n_l = xi.shape[0]
        n_m = omega.size
        n_d = free.shape[0] // 2
        n_cp = origin.size
        n_w = wheel_dof.shape[0]
        x0 = np.empty((n_m, n_l)); v0 = np.empty((n_m, n_l)); x1 = np.empty((n_m, n_l)); v1 = np.empty((n_m, n_l))
        xf = np.empty((n_m, n_l)); vf = np.empty((n_m, n_l))
        z0 = np.empty((2 * n_d, n_l)); z1 = np.empty((2 * n_d, n_l))
        zb = np.empty((2 * n_d, n_l))
        r_first = first // stride
        live = np.ones(n_l, np.bool_)  # lanes not frozen (a lane with ``stop`` −2 sits the call out)
        n_live = n_l
        for lane in range(n_l):
            if stop[lane] == -2:
                live[lane] = False
                n_live -= 1
            else:
                stop[lane] = -1
            for m in range(n_m):
                x0[m, lane] = xi[lane, r_first, m]
                v0[m, lane] = dxi[lane, r_first, m]
            for j in range(n_d):
                z0[j, lane] = q[lane, r_first, j]
                z0[n_d + j, lane] = dq[lane, r_first, j]
        p0 = np.zeros((n_m, n_l)); p = np.zeros((n_m, n_l)); acc = np.empty((n_m, n_l)); dp = np.zeros((n_m, n_l))
        pm = np.zeros((n_m, n_l)); gm = np.zeros((n_w, n_l))  # the hold's loads of the step before
        gr = np.zeros((n_w, n_l))  # G_{n−1} of a step's start; a landing lane's change of it (``again``)
        again = np.zeros(n_l, np.bool_); dz = np.zeros((2 * n_d, n_l))  # the lanes corrected for a landing
        gn = np.zeros((n_w, n_l))  # (their G_{n+1} of the first solution)
        corr = np.zeros((n_m, n_l)); sphi = np.zeros(n_m); sdphi = np.zeros(n_m)  # the hold at the deck's ends
        x_start = np.empty(n_cp); x_before = np.empty(n_cp)  # the positions at t_n, t_{n−1}
        contact = np.zeros((n_w, n_l), np.bool_); jumped = np.zeros(n_l, np.bool_)  # wheels in contact (``hold_jumps``)
        dx = np.zeros((n_m, n_l)); dv = np.zeros((n_m, n_l))
        g0 = np.zeros((n_w, n_l)); dfw = np.zeros((n_w, n_l)); fw = np.zeros((n_w, n_l)); wf = np.zeros((n_w, n_l))
        wl = np.zeros((n_w, n_l)); bq = np.zeros((n_w, n_l)); bv = np.zeros((n_w, n_l)); t = np.zeros((n_w, n_l))
        ksum = np.zeros((n_w, n_l)); csum = np.zeros((n_w, n_l))
        veh = np.zeros((n_l + 1, n_w, n_w)); piv = np.zeros((n_l + 1, n_w), np.int64)
        held = np.zeros((n_l + 1, 2 * n_w + 1))  # per lane, and (slot n_l) shared by lanes of the same sums
        f = np.zeros((n_cp, n_l)); fo = np.zeros((n_cp, n_l)); fp = np.zeros((n_cp, n_l)); f_old = np.zeros((n_cp, n_l))
        force = np.zeros((n_cp, n_l)); pen = np.zeros((n_cp, n_l)); law = np.zeros((n_cp, n_l))
        active = np.zeros((n_cp, n_l), np.bool_); used = np.zeros(n_cp, np.bool_); onb = np.zeros(n_cp, np.bool_)
        xp = np.empty(n_cp); vxp = np.empty(n_cp); rv = np.zeros((n_cp, n_l)); rr = np.zeros((n_cp, n_l))
        have = np.zeros(n_cp, np.int64)  # + 1: mode shapes of this step's positions in phi, dphi; + 2: road
        idx = np.empty(n_cp, np.int64)
        for k in range(n_cp):
            idx[k] = -1  # no station pointer yet
        phi = np.zeros((n_cp, n_m)); dphi = np.zeros((n_cp, n_m))
        work = np.zeros(n_l, np.bool_)  # lanes taking the current update
        flip = np.zeros(n_l, np.bool_)
        err = np.zeros(n_l); bmax = np.zeros(n_l); zw = np.zeros(n_l); dzw = np.zeros(n_l); s_l = np.zeros(n_l)
        sd_l = np.zeros(n_l); dr_l = np.zeros(n_l); b = np.zeros(n_l)
        lo_on = np.zeros((n_w, n_l)); lo_off = np.zeros((n_w, n_l))
        # the step's points that matter: ``nz`` those whose first guess is nonzero in some lane, ``rel``
        # those and the used ones (every other point has F = 0 = law in every lane), ``use`` the used ones
        nz = np.zeros(n_cp, np.bool_); rel = np.zeros(n_cp, np.int64); use = np.zeros(n_cp, np.int64)
        evaluations = 0
        passes = 2 if QUADRATIC else 1  # (the passes a step may take: a second one after a landing or lift-off)
        for n in range(first - 1, n_steps):  # n = first − 1: the start state (forces, loads and accelerations)
            row = 2 * n + 2
            for k in range(n_cp):
                vh = vehicle[k]
                x_before[k] = x_start[k]  # (at n = first: ``x_past``, below)
                x_start[k] = xp[k] if n >= first else x_past[k]
                xp[k] = origin[k] + direction[k] * travel[row, vh]
                vxp[k] = direction[k] * speed[row, vh]
                onb[k] = start[track[k]] <= xp[k] <= end[track[k]]
                have[k] = 0
            if n < first:
                read = span if first == 0 else abs(span)  # (the run's start: the road ahead only when span < 0)
                _law_lanes(x0, v0, z0, n_d, xp, vxp, onb, live, phi, dphi, have, rv, rr, idx, start, grid_h, values,
                           slopes, amp, wheel_dof, wheel_h, wheel_first, wheel_count, track, line, kk, cc, f0, gap,
                           gated, width, stations, elevations, r_max, read, force, active, used, pen, law, wf, wl, lo_on, lo_off,
                           bmax, zw, dzw, s_l, sd_l, dr_l)
                for m in range(n_m):
                    for lane in range(n_l):
                        p[m, lane] = 0.0
                for k in range(n_cp):
                    for lane in range(n_l):
                        fk = force[k, lane] if used[k] else 0.0
                        f[k, lane] = fk
                        fo[k, lane] = fk
                    if used[k] and onb[k]:
                        for m in range(n_m):
                            ph = phi[k, m]
                            for lane in range(n_l):
                                p[m, lane] -= ph * f[k, lane]
                for m in range(n_m):
                    for lane in range(n_l):
                        x1[m, lane] = x0[m, lane]
                        v1[m, lane] = v0[m, lane]
                for i in range(2 * n_d):
                    for lane in range(n_l):
                        z1[i, lane] = z0[i, lane]
            else:
                redo = False  # (a lane's wheel landed or lifted off: that lane's step corrected, its wheel loads held linear)
                n_rel = np.int64(0)  # (the step's points, set by the first pass: not a bare 0, a literal-typed variant of _quasi_lanes)
                n_use = 0
                for attempt in range(passes):
                    if QUADRATIC and attempt == 1:  # ``again``'s lanes with G_{n−1} = 2G_n − G_{n+1} (``gr``: its change)
                        _shift_vehicles_lanes(free_past, gr, dz, z1, n_d, wheel_dof, wheel_h, bq, bv)
                        for lane in range(n_l):
                            flip[lane] = False
                        for w in range(n_w):  # the left-out and dormant points' bounds move with −z_w
                            for lane in range(n_l):
                                lo_on[w, lane] += bq[w, lane]
                                lo_off[w, lane] += bq[w, lane]
                                flip[lane] = flip[lane] or lo_on[w, lane] > 0.0 or lo_off[w, lane] > 0.0
                        for i in range(n_use):  # the used points' law by the exact increments; a contact may open or
                            k = use[i]  # close here, as at a new evaluation of the law
                            w = wheel[k]
                            kc = kk[k]
                            ck = cc[k]
                            gk = gated[k]
                            wd = width[k]
                            for lane in range(n_l):
                                pen[k, lane] += bq[w, lane]
                                law[k, lane] += kc * bq[w, lane] + ck * bv[w, lane]
                                fl = law[k, lane]
                                on = not gk or (pen[k, lane] > 0.0 and fl > 0.0)
                                wl[w, lane] += 0.0 if on == active[k, lane] else (wd if on else -wd)
                                active[k, lane] = on
                                force[k, lane] = fl if on else 0.0
                        for lane in range(n_l):
                            err[lane] = 0.0
                        for i in range(n_rel):
                            k = rel[i]
                            for lane in range(n_l):
                                err[lane] = max(err[lane], abs(force[k, lane] - f[k, lane]))
                        n_work = 0
                        for lane in range(n_l):
                            if again[lane] and flip[lane] and live[lane]:  # frozen at this step
                                live[lane] = False
                                stop[lane] = n
                                n_live -= 1
                            work[lane] = live[lane] and again[lane] and err[lane] > tol
                            n_work += 1 if work[lane] else 0
                    else:
                        if QUADRATIC:  # G_{n−1} of the step's start (a landing lane's change of it: below)
                            for w in range(n_w):
                                for lane in range(n_l):
                                    gr[w, lane] = gm[w, lane]
                        for k in range(n_cp):  # first guess: linear extrapolation of the forces (the hold at the deck's ends
                            nonzero = False  # reads it too)
                            for lane in range(n_l):
                                fk = 2.0 * fo[k, lane] - fp[k, lane]
                                f[k, lane] = fk
                                nonzero = nonzero or fk != 0.0
                            nz[k] = nonzero
                        share = x_start if n == 0 else x_before  # (where p_{n−1} took each share: the run's start holds p_0)
                        ends = hold_correction_lanes(x_before, share, x_start, xp, track, start, end, grid_h, values, slopes, fo,
                                                     sphi, sdphi, corr)  # points crossing a deck end: their share of p_{n−1}
                        if ends:
                            for m in range(n_m):
                                for lane in range(n_l):
                                    corr[m, lane] += pm[m, lane]
                        past = corr if ends else pm
                        for m in range(n_m):  # free responses: deck with p_{n+1} = 0, vehicles with F_{n+1} = 0
                            e11 = a11[m]; e12 = a12[m]; e21 = a21[m]; e22 = a22[m]; f1 = b1[m]; f2 = b2[m]; h1 = d1[m]
                            h2 = d2[m]
                            for lane in range(n_l):
                                xf[m, lane] = e11 * x0[m, lane] + e12 * v0[m, lane] + f1 * p0[m, lane] + h1 * past[m, lane]
                                vf[m, lane] = e21 * x0[m, lane] + e22 * v0[m, lane] + f2 * p0[m, lane] + h2 * past[m, lane]
                                pm[m, lane] = p0[m, lane]  # (the next step's p_{n−1})
                        # z_b = P (Φ z_n + Lp G_{n−1} + L0 G_n + g) = P Φ z_n + P Lp G_{n−1} + P L0 G_n + P g (``VehicleStep``)
                        _affine_lanes(free_constant, free, free_load, z0, g0, zb)
                        _add_product_lanes(free_past, gm, zb)
                        for w in range(n_w):
                            for lane in range(n_l):
                                gm[w, lane] = g0[w, lane]
                        _state_lanes(f, nz, onb, xp, have, start, grid_h, values, slopes, track, phi, dphi, wheel, c1, c2, response,
                                     xf, vf, zb, p, fw, x1, v1, z1)
                        evaluations += 1
                        read = abs(span)
                        _law_lanes(x1, v1, z1, n_d, xp, vxp, onb, live, phi, dphi, have, rv, rr, idx, start, grid_h, values,
                                   slopes, amp, wheel_dof, wheel_h, wheel_first, wheel_count, track, line, kk, cc, f0, gap,
                                   gated, width, stations, elevations, r_max, read, force, active, used, pen, law, wf, wl, lo_on, lo_off,
                                   bmax, zw, dzw, s_l, sd_l, dr_l)
                        n_rel = np.int64(0)
                        n_use = 0
                        for k in range(n_cp):
                            if used[k]:
                                dormant = gated[k]  # a gated point off the road (δ ≤ 0) in every lane: watched by its bound
                                for lane in range(n_l):
                                    dormant = dormant and pen[k, lane] <= 0.0
                                if not dormant:
                                    use[n_use] = k
                                    n_use += 1
                                elif onb[k]:
                                    for lane in range(n_l):
                                        lo_on[wheel[k], lane] = max(lo_on[wheel[k], lane], pen[k, lane])
                                else:
                                    for lane in range(n_l):
                                        lo_off[wheel[k], lane] = max(lo_off[wheel[k], lane], pen[k, lane])
                            if used[k] or nz[k]:
                                rel[n_rel] = k
                                n_rel += 1
                        for lane in range(n_l):
                            err[lane] = 0.0
                        for i in range(n_rel):
                            k = rel[i]
                            for lane in range(n_l):
                                err[lane] = max(err[lane], abs(force[k, lane] - f[k, lane]))  # force = 0 where not used
                        n_work = 0
                        for lane in range(n_l):
                            work[lane] = live[lane] and err[lane] > tol
                            n_work += 1 if work[lane] else 0
                    for w in range(n_w):
                        for lane in range(n_l):
                            dfw[w, lane] = 0.0
                    r = 0
                    while n_work > 0:  # quasi-Newton updates, the law at each iterate by the exact increments
                        if r == LEAN_CORRECTIONS:
                            for lane in range(n_l):  # not settled by the corrections
                                if work[lane]:
                                    live[lane] = False
                                    stop[lane] = n
                                    n_live -= 1
                            break
                        r += 1
                        for w in range(n_w):  # F_w of the current forces
                            for lane in range(n_l):
                                fw[w, lane] += dfw[w, lane]
                        for i in range(n_rel):
                            k = rel[i]
                            for lane in range(n_l):
                                f_old[k, lane] = f[k, lane]
                        _quasi_lanes(f, force, active, kk, cc, wheel, wheel_q, wheel_v, fw, ksum, csum, held, veh, piv, bq, bv,
                                     t, work, rel, n_rel)
                        for m in range(n_m):
                            for lane in range(n_l):
                                dp[m, lane] = 0.0
                        for w in range(n_w):
                            for lane in range(n_l):
                                dfw[w, lane] = -fw[w, lane]
                        for i in range(n_rel):
                            k = rel[i]
                            wk = wheel[k]
                            for lane in range(n_l):
                                dfw[wk, lane] += f[k, lane]
                            if onb[k]:
                                changed = False
                                for lane in range(n_l):
                                    changed = changed or f[k, lane] != f_old[k, lane]
                                if changed:
                                    for m in range(n_m):
                                        ph = phi[k, m]
                                        for lane in range(n_l):
                                            dp[m, lane] -= ph * (f[k, lane] - f_old[k, lane])
                        for lane in range(n_l):
                            b[lane] = 0.0
                            if not work[lane]:
                                for w in range(n_w):
                                    dfw[w, lane] = 0.0
                        for m in range(n_m):  # the deck's change, and the state of the new iterate
                            e1 = c1[m]
                            e2 = c2[m]
                            am = amp[m]
                            for lane in range(n_l):
                                dx[m, lane] = e1 * dp[m, lane]
                                dv[m, lane] = e2 * dp[m, lane]
                                b[lane] += am * abs(dx[m, lane])
                                p[m, lane] += dp[m, lane]
                                x1[m, lane] += dx[m, lane]
                                v1[m, lane] += dv[m, lane]
                        _add_product_lanes(response, dfw, z1)  # z = z_b + (P L1) F_w
                        for lane in range(n_l):
                            err[lane] = 0.0
                            flip[lane] = False  # the lane needs more than this step (set in loops the compiler vectorises)
                        for w in range(n_w):  # points left out by the lazy test or off the road in every lane: δ must
                            # stay ≤ 0, watched through each wheel's largest δ (or bound on it) plus the increments' bound
                            for lane in range(n_l):
                                lo_on[w, lane] += bq[w, lane] + b[lane]
                                lo_off[w, lane] += bq[w, lane]
                                flip[lane] = flip[lane] or lo_on[w, lane] > 0.0 or lo_off[w, lane] > 0.0
                        for i in range(n_use):  # the law of the other used points by the exact increments
                            k = use[i]
                            w = wheel[k]
                            for lane in range(n_l):
                                s_l[lane] = 0.0
                                dr_l[lane] = 0.0
                                sd_l[lane] = 0.0
                            if onb[k]:
                                _deck_lanes(phi, dphi, k, 1.0, dx, dv, s_l, dr_l, sd_l)
                            kc = kk[k]
                            ck = cc[k]
                            vx = vxp[k]
                            gk = gated[k]
                            for lane in range(n_l):
                                dpen = s_l[lane] + bq[w, lane]
                                pen[k, lane] += dpen
                                law[k, lane] += kc * dpen + ck * (dr_l[lane] + vx * sd_l[lane] + bv[w, lane])
                                fl = law[k, lane]
                                on = not gk or (pen[k, lane] > 0.0 and fl > 0.0)
                                fk = fl if on else 0.0
                                flip[lane] = flip[lane] or on != active[k, lane]  # a contact opens or closes
                                force[k, lane] = fk
                                err[lane] = max(err[lane], abs(fk - f[k, lane]))
                        n_work = 0
                        for lane in range(n_l):
                            if work[lane] and flip[lane]:  # frozen at this step
                                work[lane] = False
                                live[lane] = False
                                stop[lane] = n
                                n_live -= 1
                            work[lane] = work[lane] and err[lane] > tol
                            n_work += 1 if work[lane] else 0
                    if n_live == 0:
                        return evaluations
                    for w in range(n_w):
                        for lane in range(n_l):
                            fw[w, lane] += dfw[w, lane]
                            wf[w, lane] = fw[w, lane]
                    if not QUADRATIC or attempt == 1:
                        break
                    for lane in range(n_l):  # a wheel lands or lifts off within the step (``lean``): that lane's
                        jump = False  # G_{n−1} becomes 2G_n − G_{n+1} of this pass, ``gr`` its change (0 in the others)
                        if live[lane]:
                            for w in range(n_w):
                                if (wf[w, lane] > 0.0) != contact[w, lane]:
                                    jump = True
                                    break
                        again[lane] = jump
                        redo = redo or jump
                    if not redo:
                        break
                    _wheel_loads_lanes(wf, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c, gn)  # G_{n+1} of this solution
                    for w in range(n_w):
                        for lane in range(n_l):
                            gr[w, lane] = 2.0 * g0[w, lane] - gn[w, lane] - gr[w, lane] if again[lane] else 0.0
            # loads and accelerations of the end state: G = F_w + k_w z_w + c_w ż_w, ξ̈
            _wheel_loads_lanes(wf, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c, g0)
            if n >= first:  # a wheel that lands or lifts off: the next step holds from here on
                # MANY_LANES as int64s, not the global's literal 0s: hold_jumps keeps the one signature implicit
                # gives it (a literal-typed tuple compiled it a second time)
                hold_jumps(wf, contact, g0, p, pm, gm, jumped, (np.int64(MANY_LANES[0]), np.int64(MANY_LANES[1])))
            else:  # (the wheels in contact at the start)
                for w in range(n_w):
                    for lane in range(n_l):
                        contact[w, lane] = wf[w, lane] > 0.0
            for m in range(n_m):
                e1 = 2.0 * zeta[m] * omega[m]
                e2 = omega[m] * omega[m]
                for lane in range(n_l):
                    acc[m, lane] = p[m, lane] - e1 * v1[m, lane] - e2 * x1[m, lane]
            if (n + 1) % stride == 0:
                r_out = (n + 1) // stride
                for lane in range(n_l):
                    if not live[lane] or (n < first and not fresh[lane]):
                        continue
                    for m in range(n_m):
                        if n >= first:
                            xi[lane, r_out, m] = x1[m, lane]
                            dxi[lane, r_out, m] = v1[m, lane]
                        ddxi[lane, r_out, m] = acc[m, lane]
                    if n >= first:
                        for j in range(n_d):
                            q[lane, r_out, j] = z1[j, lane]
                            dq[lane, r_out, j] = z1[n_d + j, lane]
                    for w in range(n_w):
                        wheel_force[lane, r_out, w] = wf[w, lane]
                        wheel_len[lane, r_out, w] = wl[w, lane]
                    if n >= first:  # the hold's loads of the step before the row (the start's: below)
                        for m in range(n_m):
                            carry_pm[m, lane] = pm[m, lane]
                        for w in range(n_w):
                            carry_gm[w, lane] = gm[w, lane]
            if n >= first:
                for k in range(n_cp):
                    for lane in range(n_l):
                        fp[k, lane] = fo[k, lane]
                        fo[k, lane] = f[k, lane]
                x0, x1 = x1, x0
                v0, v1 = v1, v0
                z0, z1 = z1, z0
            else:
                for k in range(n_cp):
                    for lane in range(n_l):
                        fp[k, lane] = fo[k, lane]
                for lane in range(n_l):  # lanes going on: the state the previous call ended with
                    if not fresh[lane]:
                        for k in range(n_cp):
                            fo[k, lane] = carry_f[0, k, lane]
                            fp[k, lane] = carry_f[1, k, lane]
                        for m in range(n_m):
                            p[m, lane] = carry_p[m, lane]
                        for w in range(n_w):
                            g0[w, lane] = carry_g[w, lane]
                    for m in range(n_m):  # the hold's loads before the start: held constant at the run's start
                        pm[m, lane] = p[m, lane] if first == 0 else carry_pm[m, lane]
                        carry_pm[m, lane] = pm[m, lane]
                    for w in range(n_w):
                        gm[w, lane] = g0[w, lane] if first == 0 else carry_gm[w, lane]
                        carry_gm[w, lane] = gm[w, lane]
            p0, p = p, p0
        for k in range(n_cp):  # the state the next call goes on from
            for lane in range(n_l):
                carry_f[0, k, lane] = fo[k, lane]
                carry_f[1, k, lane] = fp[k, lane]
        for m in range(n_m):
            for lane in range(n_l):
                carry_p[m, lane] = p0[m, lane]
        for w in range(n_w):
            for lane in range(n_l):
                carry_g[w, lane] = g0[w, lane]
                if live[lane]:
                    carry_gm[w, lane] = gm[w, lane]
        for m in range(n_m):
            for lane in range(n_l):
                if live[lane]:
                    carry_pm[m, lane] = pm[m, lane]
        return evaluations

    lean_lanes.__name__ = lean_lanes.__qualname__ = "lean_lanes_quadratic" if QUADRATIC else "lean_lanes"
    return njit(cache=True, fastmath=True, error_model="numpy", nogil=True)(lean_lanes)


#: the variants of ``lean_lanes``: the wheel loads held linear and quadratic (the default integrator's)
lean_lanes = _make_lean_lanes(False)
lean_lanes_quadratic = _make_lean_lanes(True)
