"""The lean implicit step loop: one crossing (one lane), the common step only, written flat on plain
contiguous arrays. (``vbikit.solve.kernels``: the equations and conventions.)

``lean`` runs the steps of ``implicit`` that need one contact-law evaluation: the partitioned step
(every mode by its transition, ξ_{n+1} = a11 ξ_n + a12 ξ̇_n + d1 p_{n−1} + b1 p_n + c1 p_{n+1}, ξ̇ likewise;
the vehicles z_{n+1} = P (Φ z_n + Lp G_{n−1} + L0 G_n + g) + P L1 F_w, ``ModalStep``, ``VehicleStep``: the
loads held linear, d = 0 and Lp = 0, or quadratic over the step), the end-of-step
point forces F solving F − law(F) = 0 to ``tol`` [N] from the first guess F = 2F_n − F_{n−1}.  The
vehicles' products are those of ``implicit`` regrouped (the same to round-off): the settled free
response P Φ z_n + P L0 G_n + P g by the fused map of ``FusedVehicleStep``, one product; a wheel's
displacement h_w·q and load read only the nonzero entries of its row h_w (``wheel_entries``: two a
wheel on the stock trucks, against n_d).  The vehicles' accelerations q̈ are not computed in the loop:
they follow from the stored states and wheel forces when a result's ``q_ddot`` is read
(``vbikit.solve.result.DeferredAccelerations``).

1. the state of the guess and the contact law there (``_law``: s_p = φ_p·ξ + r_p,
   δ_p = s_p − g_p − z_w, F_p = k_p δ_p + c_p (ṡ_p − ż_w) + f0_p, gated);
2. if max_p |law_p − F_p| ≤ ``tol`` the guess holds; else quasi-Newton updates through the
   vehicles, (I + U_A S_A) F_A = law_A(F) + U_A S_A F (``_quasi``: by Woodbury the n_w-square
   system (I + S_A U_A) t = S_A b, factorised per active set A and kept while A stays), the law at
   each iterate following exactly from the last evaluation by the change of state
   (Δξ = c1 Δp, Δξ̇ = c2 Δp, Δp = −Σ φ_k ΔF_k; Δδ_k = φ_k·Δξ + Δ(−z_w), Δδ̇_k = φ_k·Δξ̇ + v_x φ'_k·Δξ
   + Δ(−ż_w)), at most ``LEAN_CORRECTIONS`` times — the same arithmetic as ``implicit``'s
   one-evaluation step (``newton._vehicle_newton``, ``newton._lean_refine``); the iterate's end
   state follows by the same increments (ξ += Δξ, ξ̇ += Δξ̇; the iterates read the vehicles only
   through the wheels' increments, so z += (P L1) ΔF_w once, ΔF_w the corrections' whole change).

With the wheel loads held quadratic (Lp ≠ 0, ``builtin_integrators.QUADRATIC_WHEEL_LOADS``) a step in
which a wheel lands or lifts off is solved a second time: the wheel's load has a kink there, which the
parabola through G_{n−1}, G_n, G_{n+1} does not follow, so the second solution takes G_{n−1} = 2G_n − G_{n+1}
of the first one's end, the linear hold's loads over that step (exactly, up to the change of G_{n+1} between
the two).  Only the vehicles' free response z_b depends on G_{n−1} (by P Lp), so the second solution starts
from the first one's forces and end state: z shifted by P Lp ΔG_{n−1}, the law there by its exact increments
(a contact may open or close with the shift, as at an evaluation), then the same quasi-Newton updates to the
same ``tol`` (``_shift_vehicles``; no second evaluation of the law, mode shapes or road).  A point left out
by the lazy test that the shift may bring into contact stops the loop there, as in the updates.

Anything else stops the loop: a contact that opens or closes within the step (a gated point's
activity changes, or a point the lazy test left out may touch), or the corrections not settling.
``lean`` then returns that step, and the caller goes on with ``implicit`` from the last state
stored (which handles lift-off, landing, touching points and full Newton).  Rigid-disk envelopes are not
handled at all (the caller does not call ``lean`` for them).  The outputs are those of
``implicit`` but q̈ (same conventions, row 0 the static start, every ``stride``-th step stored).

Compilation (the first run's cost, ``benchmarks/bench_compile.py``): ``lean`` and its helpers are flat
kernels (``bundles.FLAT_OPTIONS``: no allocation inside, hence no reference counting); ``_law`` is
compiled once, with the argument types of both its callers (``lean`` and, from Python, ``lean_law``);
``lean`` returns at one place only and calls ``_law`` at one site (numba emits the end of every array's
lifetime at each return, and each call site passes every array).  numba links each compiled helper into
its callers' LLVM modules, where it is optimised and made into machine code again: small helpers with
one caller are inlined by numba instead (the LU routines into ``_quasi``: ``dense.lu_factor_inline``),
and numba's inlined helpers are called at one site each (the road cells of the secant rate's two readings
and of the point by one ``road_cell``: ``contact.road_cells``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from vbikit._kept import Kept
from vbikit.solve.kernels.bundles import FLAT_OPTIONS, _flat, _flat_internal
from vbikit.solve.kernels.contact import deck_increments, hermite_shape, road_cells, secant_ends
from vbikit.solve.kernels.hold import hold_correction
from vbikit.solve.kernels.dense import lu_factor_inline, lu_solve_inline
from vbikit.solve.kernels.newton import LEAN_CORRECTIONS


@_flat  # called by ``lean`` and from Python by ``lean_law``: one compiled law for both
def _law(x1, v1, z1, n_d, xp, vxp, onb, phi, dphi, have, rv, rr, idx, start, grid_h, values, slopes, amp, wheel_dof,
         wheel_h, wheel_first, wheel_count, track, line, kk, cc, f0, gap, gated, width, stations, elevations, r_max,
         span, force, active, used, pen, law, wf, wl):
    """The contact law at the state (ξ, ξ̇) = (``x1``, ``v1``), z = ``z1`` (q, q̇) for the positions
    ``xp`` (``contact_forces`` with one lane and no envelopes): per point ``force`` (gated), ``active``,
    ``used`` (else left out by the lazy test: r_max − g − z_w + B ≤ 0, B = Σ amp|ξ|; ``pen`` then holds
    that bound), penetration ``pen`` and ungated law ``law``; per wheel the force sum ``wf`` and patch
    length ``wl``.  Mode shapes (cubic Hermite) and road (linear, station pointers ``idx``) are filled
    on first use in the step (``have``: + 1 once the shapes are in ``phi``, ``dphi``, + 2 once the road
    is in ``rv``, ``rr``; the rate the secant over |v|·``span`` either side, ``road_point``)."""
    n_m = x1.size
    _, n_e = wheel_dof.shape  # (unpacked: numba types an indexed shape through a compiled overload)
    b_max = 0.0
    for m in range(n_m):
        b_max += amp[m] * abs(x1[m])
    for w in range(len(wheel_dof)):
        zw = 0.0
        dzw = 0.0
        for e in range(n_e):  # h_w·q, h_w·q̇ over the row's nonzero entries
            h = wheel_h[w, e]
            if h != 0.0:
                j = wheel_dof[w, e]
                zw += h * z1[j]
                dzw += h * z1[n_d + j]
        wf[w] = 0.0
        wl[w] = 0.0
        first = wheel_first[w]
        for p in range(first, first + wheel_count[w]):
            used[p] = False
            x = xp[p]
            bound = r_max - gap[p] - zw + (b_max if onb[p] else 0.0)
            if gated[p] and bound <= 0.0:
                force[p] = 0.0
                active[p] = False
                pen[p] = bound
                law[p] = 0.0
                continue
            if have[p] < 2:  # the road under the point (``road_point``)
                ln = line[p]
                vx = vxp[p]
                lo, hi = secant_ends(x, vx, span)
                a = hi - lo
                ia, ta, ib, tb, i = road_cells(stations, lo, hi, x, vx, idx, p)
                if a > 0.0:  # the secant rate
                    rr[p] = (elevations[ln, ib] + tb * (elevations[ln, ib + 1] - elevations[ln, ib]) - elevations[ln, ia]
                             - ta * (elevations[ln, ia + 1] - elevations[ln, ia])) * (vx / a)
                slope = (elevations[ln, i + 1] - elevations[ln, i]) / (stations[i + 1] - stations[i])
                rv[p] = elevations[ln, i] + slope * (x - stations[i])
                if a <= 0.0:
                    rr[p] = slope * vx
                have[p] += 2
            if onb[p] and have[p] % 2 == 0:
                hermite_shape(x, track[p], start, grid_h, values, slopes, phi[p], dphi[p])
                have[p] += 1
            used[p] = True
            s = rv[p]
            sd = rr[p]
            dr = 0.0
            if onb[p]:
                vx = vxp[p]
                for m in range(n_m):
                    s += phi[p, m] * x1[m]
                    dr += phi[p, m] * v1[m]
                    sd += vx * dphi[p, m] * x1[m]
            pn = s - gap[p] - zw
            fl = kk[p] * pn + cc[p] * (sd + dr - dzw) + f0[p]
            pen[p] = pn
            law[p] = fl
            fk = fl if not gated[p] or (pn > 0.0 and fl > 0.0) else 0.0
            force[p] = fk
            active[p] = not gated[p] or fk > 0.0
            wf[w] += fk
            if active[p]:
                wl[w] += width[p]


@_flat_internal
def _state(f, onb, xp, have, start, grid_h, values, slopes, track, phi, dphi, wheel, c1, c2, response, xf, vf, zb,
           p, fw, x1, v1, z1):
    """The end-of-step state of point forces ``f``: p = −Σ_{p on the deck} φ_p F_p, F_w = Σ_{p∈w} F_p,
    ξ = ξ_f + c1 p, ξ̇ = ξ̇_f + c2 p, z = z_b + (P L1) F_w (``implicit_step._state_of``)."""
    n_m = p.size
    for m in range(n_m):
        p[m] = 0.0
    for w in range(fw.size):
        fw[w] = 0.0
    for k in range(f.size):
        fk = f[k]
        if fk == 0.0:
            continue
        fw[wheel[k]] += fk
        if onb[k]:
            if have[k] % 2 == 0:
                hermite_shape(xp[k], track[k], start, grid_h, values, slopes, phi[k], dphi[k])
                have[k] += 1
            for m in range(n_m):
                p[m] -= phi[k, m] * fk
    for m in range(n_m):
        x1[m] = xf[m] + c1[m] * p[m]
        v1[m] = vf[m] + c2[m] * p[m]
    for i in range(z1.size):
        a = zb[i]
        for w in range(fw.size):
            a += response[i, w] * fw[w]
        z1[i] = a


@_flat_internal
def _quasi(f, force, active, kk, cc, wheel, wheel_q, wheel_v, fw, ksum, csum, held, veh, piv, bq, bv, t):
    """One quasi-Newton update through the vehicles, ``woodbury``'s arithmetic written for one lane on
    flat (n_w,) arrays: F_A = law_A + k bq_w + c bv_w, F = 0 off A, with (bq, bv) the change of
    (−z_w, −ż_w): b = (wheel_q, wheel_v) F_w, (I + S_A U_A) t = S_A b, (bq, bv) = b − (wheel_q, wheel_v) t.
    The factors of V = I + S_A U_A (``veh``, ``piv``) are kept while the active sums (``held``) stay.
    Not ``woodbury``'s functions themselves, which take (n_w, L) arrays and run the lanes innermost: on
    (n_w, 1) arrays they made the default path's cold compile 0.6–1.1 s longer (``lean`` 6.2–7.4 s
    against 5.2–5.9 s CPU, alternating fresh processes), and their products, summed through the arrays,
    a traffic event's ``lean`` 25–30 % slower (benchmarks/README.md)."""
    n_w = fw.size
    for w in range(n_w):
        ksum[w] = 0.0
        csum[w] = 0.0
    for k in range(f.size):
        if active[k]:
            ksum[wheel[k]] += kk[k]
            csum[wheel[k]] += cc[k]
    same = held[2 * n_w] != 0.0
    if same:
        for w in range(n_w):
            if ksum[w] != held[w] or csum[w] != held[n_w + w]:
                same = False
                break
    if not same:
        for w in range(n_w):
            for w2 in range(n_w):
                veh[w, w2] = (1.0 if w == w2 else 0.0) + ksum[w] * wheel_q[w, w2] + csum[w] * wheel_v[w, w2]
            held[w] = ksum[w]
            held[n_w + w] = csum[w]
        held[2 * n_w] = 1.0
        lu_factor_inline(veh, n_w, piv)
    for w in range(n_w):
        aq = 0.0
        av = 0.0
        for w2 in range(n_w):
            aq += wheel_q[w, w2] * fw[w2]
            av += wheel_v[w, w2] * fw[w2]
        bq[w] = aq
        bv[w] = av
        t[w] = ksum[w] * aq + csum[w] * av
    for k in range(f.size):
        if active[k]:
            t[wheel[k]] += force[k]
    lu_solve_inline(veh, n_w, piv, t)
    for w in range(n_w):
        aq = 0.0
        av = 0.0
        for w2 in range(n_w):
            aq += wheel_q[w, w2] * t[w2]
            av += wheel_v[w, w2] * t[w2]
        bq[w] -= aq
        bv[w] -= av
    for k in range(f.size):
        w = wheel[k]
        f[k] = force[k] + kk[k] * bq[w] + cc[k] * bv[w] if active[k] else 0.0


@_flat_internal
def _shift_vehicles(free_past, dg, dz, z1, n_d, wheel_dof, wheel_h, bq, bv):
    """The vehicles' end state of a step whose wheel loads before it change by ``dg`` (n_w,): z_b and hence z
    change by P Lp ΔG_{n−1} (``VehicleStep``; ``dz`` (2n_d,) receives it), and each wheel's −z_w, −ż_w by
    ``bq``, ``bv`` (n_w,; the quasi-Newton updates' wheel increments, same signs)."""
    for i in range(dz.size):
        a = 0.0
        for w in range(dg.size):
            a += free_past[i, w] * dg[w]
        dz[i] = a
        z1[i] += a
    for w in range(dg.size):
        aq = 0.0
        av = 0.0
        for e in range(wheel_dof.shape[1]):
            h = wheel_h[w, e]
            if h != 0.0:
                j = wheel_dof[w, e]
                aq -= h * dz[j]
                av -= h * dz[n_d + j]
        bq[w] = aq
        bv[w] = av


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _wheel_load(force, w, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c):
    """G_w = F_w + k_w z_w + c_w ż_w (``VehicleStep``'s wheel loads): wheel ``w``'s load from its contact force
    sum ``force`` [N] and the vehicles' state ``z1`` (q, q̇), its row h_w read through ``wheel_entries``."""
    a = force
    _, n_e = wheel_dof.shape  # (unpacked: numba types an indexed shape through a compiled overload)
    for e in range(n_e):
        h = wheel_h[w, e]
        if h != 0.0:
            j = wheel_dof[w, e]
            a += h * (wheel_k[w] * z1[j] + wheel_c[w] * z1[n_d + j])
    return a


@_flat_internal
def _linear_past(fw, contact, g0, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c, past):
    """Whether a wheel lands or lifts off within the step (its force sum ``fw`` > 0 at the end against
    ``contact`` at the start); if so ``past``, given G_{n−1} of the step, becomes its change to 2G_n − G_{n+1},
    G_n = ``g0`` and G_{n+1} = F_w + k_w z_w + c_w ż_w of the end state ``z1``: the G_{n−1} with which the
    quadratic hold's map is the linear hold's."""
    landed = False
    for w in range(fw.size):
        if (fw[w] > 0.0) != (contact[w] != 0.0):
            landed = True
    if landed:
        for w in range(fw.size):
            past[w] = 2.0 * g0[w] - _wheel_load(fw[w], w, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c) - past[w]
    return landed


def _make_lean(QUADRATIC: bool):  # noqa: N803 (a compile-time constant of the variant)
    """``lean`` compiled for the vehicles' maps with the wheel loads held linear (``QUADRATIC`` False: Lp = 0)
    or quadratic (True, the default's: a step in which a wheel lands or lifts off is solved a second time, module
    docstring).  Two variants, each compiled on its first use, so that the linear one (Newmark's, and "exact"'s
    with ``QUADRATIC_WHEEL_LOADS`` off) compiles none of the quadratic hold's code (numba prunes the branches
    on the closure's constant ``QUADRATIC`` before it types them: every test of the hold starts with it)."""

    def lean(travel, speed, start, end, grid_h, values, slopes, amp, omega, zeta, a11, a12, a21, a22, b1, b2, c1, c2, d1,
             d2, free, free_load, free_constant, free_past, response, wheel_q, wheel_v, wheel_dof, wheel_h, wheel_k, wheel_c,
             wheel_first, wheel_count, origin, direction, vehicle, track, line, kk, cc, f0, gap, gated, wheel, width,
             stations, elevations, r_max, span, xi, dxi, q, dq, ddxi, wheel_force, wheel_len, past_p, past_g, resume,
             x_past, tol, stride, modal, state, wheels, held, veh, piv, points, flags, index, shapes):
        """The lean step loop (module docstring) of one crossing.  Arguments: the fields of ``Motion``
        (contiguous), ``Modes``, ``ModalStep``, ``VehicleStep`` and its ``FusedVehicleStep`` (as
        ``integrators._lean_arguments`` passes them), ``Vehicles`` and ``Points`` one by one
        (``line`` clamped to the road lines present; ``gated`` includes the unilateral gate), the road's
        stations and elevations of its one lane (n_lines, n_s) and r_max, the road rate's ``span`` [s]
        (``road_point``: dt/2 for the secant rate, 0 for the cell's slope; negative when the call starts
        at the run's start: the start state's law then reads the road ahead only, the steps |span|), the outputs of ``implicit`` for
        one lane but q̈ (each (n_stored, ·), row 0 the static start), the loads of the step before the start
        for the hold (``ModalStep``, ``VehicleStep``): modal ``past_p`` (n_m,) and wheel ``past_g`` (n_w,),
        read when ``resume`` (a call that goes on from a stored state); else the start's own (the run's
        start: the loads held constant before t_0, the static start); on return they hold the loads of
        the step before the last row stored (where a call going on from that row starts), ``x_past``
        (n_cp,) the points' positions [m] a step before the start (for the hold at the deck's ends,
        ``vbikit.solve.kernels.hold``), ``tol`` [N] and ``stride``, then the work spaces of ``lean_work``
        (zeroed).

        Returns (``stop``, evaluations, landings): ``stop`` = −1 when every step was taken, else the first step n
        (0-based, t_n → t_{n+1}) that needs more than the lean path (its outputs from row n + 1 on are not
        filled); evaluations counts the contact-law evaluations, landings the steps in which a wheel landed or
        lifted off, solved a second time (``lean_quadratic``; 0 for ``lean``)."""
        n_steps = (len(travel) - 1) // 2
        n_m = omega.size
        n_d = len(free) // 2
        n_cp = origin.size
        n_w, _ = wheel_dof.shape  # (unpacked: numba types an indexed shape through a compiled overload)
        # the rows of the work spaces (``lean_work``; indexed, not unpacked, so that each row stays a contiguous array)
        x1 = modal[0]; v1 = modal[1]; xf = modal[2]; vf = modal[3]; p = modal[4]; dp = modal[5]; dx = modal[6]
        dv = modal[7]; pm = modal[8]; corr = modal[9]; sphi = modal[10]; sdphi = modal[11]
        z1 = state[0]; zb = state[1]
        g0 = wheels[0]; dfw = wheels[1]; fw = wheels[2]; wf = wheels[3]; wl = wheels[4]; bq = wheels[5]; bv = wheels[6]
        t = wheels[7]; ksum = wheels[8]; csum = wheels[9]; fw0 = wheels[10]; gm = wheels[11]; contact = wheels[12]
        f = points[0]; fo = points[1]; fp = points[2]; f_old = points[3]; force = points[4]; pen = points[5]
        law = points[6]; xp = points[7]; vxp = points[8]; rv = points[9]; rr = points[10]; x_start = points[11]
        x_before = points[12]  # the positions at t_n and t_{n−1} (the hold at the deck's ends)
        active = flags[0]; used = flags[1]; onb = flags[2]
        have = index[0]; idx = index[1]
        phi = shapes[0]; dphi = shapes[1]
        # the state (ξ, ξ̇) = (x1, v1), z = (q, q̇) = z1 and the modal load p: the start state, then each step's end
        # state, which is the next step's start
        for m in range(n_m):
            x1[m] = xi[0, m]
            v1[m] = dxi[0, m]
        for j in range(n_d):
            z1[j] = q[0, j]
            z1[n_d + j] = dq[0, j]
        evaluations = 0
        landings = 0
        stop = -1
        n = -1  # the step t_n → t_{n+1}; n = −1: the start state t_0 (forces, loads and accelerations)
        again = False  # the step solved a second time (a landing or lift-off with the loads held quadratic)
        while n < n_steps:
            row = 2 * n + 2
            if QUADRATIC and again:  # the step corrected, G_{n−1} the linear hold's 2G_n − G_{n+1} (module docstring):
                # only z_b changes, by P Lp ΔG_{n−1} (``wheels[13]``); the law follows by the exact increments
                _shift_vehicles(free_past, wheels[13], zb, z1, n_d, wheel_dof, wheel_h, bq, bv)  # (zb: scratch, the
                # next step's first solution forms it again)
                touch = False
                for k in range(n_cp):
                    w = wheel[k]
                    pen[k] += bq[w]
                    if not used[k]:  # left out by the lazy test: its bound on δ must stay ≤ 0
                        touch = touch or pen[k] > 0.0
                        continue
                    law[k] += kk[k] * bq[w] + cc[k] * bv[w]
                    fl = law[k]
                    on = not gated[k] or (pen[k] > 0.0 and fl > 0.0)  # (a contact may open or close here, as at
                    if on != active[k]:  # an evaluation of the law)
                        wl[w] += width[k] if on else -width[k]
                    active[k] = on
                    force[k] = fl if on else 0.0
                if touch:
                    stop = n
                    break
            else:
                for k in range(n_cp):
                    vh = vehicle[k]
                    x_before[k] = x_start[k]  # (at n = 0: ``x_past``, below)
                    x_start[k] = xp[k] if n >= 0 else x_past[k]
                    xp[k] = origin[k] + direction[k] * travel[row, vh]
                    vxp[k] = direction[k] * speed[row, vh]
                    onb[k] = start[track[k]] <= xp[k] <= end[track[k]]
                    have[k] = 0
                    fp[k] = fo[k]  # the forces of the last two steps' ends
                    fo[k] = f[k]
                    f[k] = 2.0 * fo[k] - fp[k]  # the first guess: linear extrapolation of the forces (n ≥ 0)
                if n >= 0:
                    share = x_start if n == 0 and not resume else x_before  # (where p_{n−1} took each share)
                    ends = hold_correction(x_before, share, x_start, xp, track, start, end, grid_h, values, slopes, fo, sphi,
                                           sdphi, corr)  # (points crossing a deck end: their share of p_{n−1})
                    for m in range(n_m):  # free responses: deck with p_{n+1} = 0, vehicles with F_{n+1} = 0
                        past = pm[m] + corr[m] if ends else pm[m]
                        xf[m] = a11[m] * x1[m] + a12[m] * v1[m] + b1[m] * p[m] + d1[m] * past
                        vf[m] = a21[m] * x1[m] + a22[m] * v1[m] + b2[m] * p[m] + d2[m] * past
                        pm[m] = p[m]  # (the next step's p_{n−1})
                    for i in range(2 * n_d):  # z_b = P Φ z_n + P Lp G_{n−1} + P L0 G_n + P g
                        a = free_constant[i]
                        for j in range(2 * n_d):
                            a += free[i, j] * z1[j]
                        for w in range(n_w):
                            a += free_load[i, w] * g0[w] + free_past[i, w] * gm[w]
                        zb[i] = a
                    for w in range(n_w):
                        if QUADRATIC:
                            wheels[13, w] = gm[w]  # (G_{n−1} of the step: a landing's change of it, ``_linear_past``)
                        gm[w] = g0[w]
                    _state(f, onb, xp, have, start, grid_h, values, slopes, track, phi, dphi, wheel, c1, c2, response, xf, vf,
                           zb, p, fw, x1, v1, z1)
                    evaluations += 1
                read = span if n < 0 else abs(span)  # (the start state: the road ahead only when span < 0)
                _law(x1, v1, z1, n_d, xp, vxp, onb, phi, dphi, have, rv, rr, idx, start, grid_h, values, slopes, amp,
                     wheel_dof, wheel_h, wheel_first, wheel_count, track, line, kk, cc, f0, gap, gated, width, stations,
                     elevations, r_max, read, force, active, used, pen, law, wf, wl)
            updated = False  # by quasi-Newton updates
            if n < 0:
                for k in range(n_cp):  # (p, like every work space, comes zeroed)
                    fk = force[k] if used[k] else 0.0
                    f[k] = fk
                    fo[k] = fk
                    if used[k] and onb[k]:
                        for m in range(n_m):
                            p[m] -= phi[k, m] * fk
                for m in range(n_m):  # the modal loads before the start (for the hold)
                    pm[m] = past_p[m] if resume else p[m]
            else:
                err = 0.0
                for k in range(n_cp):
                    err = max(err, abs(force[k] - f[k]))  # force = 0 where not used
                    f_old[k] = f[k]  # the iterate before each update
                updated = err > tol
                if updated:  # quasi-Newton updates, the law at each iterate by the exact increments
                    settled = False
                    for r in range(LEAN_CORRECTIONS):
                        for w in range(n_w):
                            if r > 0:
                                fw[w] += dfw[w]
                            else:
                                fw0[w] = fw[w]  # the guess's wheel forces
                            dfw[w] = -fw[w]  # (+ the new wheel forces, below)
                        _quasi(f, force, active, kk, cc, wheel, wheel_q, wheel_v, fw, ksum, csum, held, veh, piv, bq, bv,
                               t)
                        for k in range(n_cp):  # (dp is zero: zeroed, and after each use below)
                            dfw[wheel[k]] += f[k]
                            d = f[k] - f_old[k]
                            if d != 0.0 and onb[k]:
                                for m in range(n_m):
                                    dp[m] -= phi[k, m] * d
                        b = 0.0
                        for m in range(n_m):  # the deck's change, and the state of the new iterate
                            dx[m] = c1[m] * dp[m]
                            dv[m] = c2[m] * dp[m]
                            b += amp[m] * abs(dx[m])
                            p[m] += dp[m]
                            x1[m] += dx[m]
                            v1[m] += dv[m]
                            dp[m] = 0.0
                        err = 0.0
                        changed = False
                        for k in range(n_cp):
                            f_old[k] = f[k]
                            w = wheel[k]
                            if not used[k]:  # left out by the lazy test: its bound on δ must stay ≤ 0
                                pen[k] += bq[w] + (b if onb[k] else 0.0)
                                if pen[k] > 0.0:
                                    changed = True
                                    break
                                continue
                            ds, dr, dsd = deck_increments(phi, dphi, k, dx, dv) if onb[k] else (0.0, 0.0, 0.0)
                            dpen = ds + bq[w]
                            pen[k] += dpen
                            law[k] += kk[k] * dpen + cc[k] * (dr + vxp[k] * dsd + bv[w])
                            fl = law[k]
                            fk = fl if not gated[k] or (pen[k] > 0.0 and fl > 0.0) else 0.0
                            if (not gated[k] or fk > 0.0) != active[k]:
                                changed = True  # a contact opens or closes
                                break
                            force[k] = fk
                            err = max(err, abs(fk - f[k]))
                        if changed:
                            break
                        if err <= tol:
                            settled = True
                            break
                    if not settled:
                        stop = n
                        break
                    for w in range(n_w):  # the corrections' whole change of the wheel forces
                        fw[w] += dfw[w]
                        dfw[w] = fw[w] - fw0[w]
                    for i in range(2 * n_d):  # z = z_b + (P L1) F_w, once for all the corrections (the iterates
                        a = z1[i]  # read only the wheels' increments bq, bv)
                        for w in range(n_w):
                            a += response[i, w] * dfw[w]
                        z1[i] = a
            if QUADRATIC and n >= 0 and not again:  # a wheel lands or lifts off within the step: its load has
                again = _linear_past(fw, contact, g0, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c, wheels[13])  # a kink
                if again:  # the parabola through G_{n−1}, G_n, G_{n+1} does not follow (module docstring)
                    landings += 1
                    continue
            again = False
            stored = (n + 1) % stride == 0  # (row 0: the start state, as given, and its accelerations)
            r_out = (n + 1) // stride
            # loads of the end state: G = F_w + k_w z_w + c_w ż_w (the next step's, and q̈); the wheels' stored rows
            jumped = False
            for w in range(n_w):
                if n >= 0:
                    wf[w] = fw[w]  # (at n = −1 the law's sums)
                a = _wheel_load(wf[w], w, z1, n_d, wheel_dof, wheel_h, wheel_k, wheel_c)
                g0[w] = a
                if n < 0:  # the loads before the start (for the hold)
                    gm[w] = past_g[w] if resume else a
                touching = wf[w] > 0.0  # a wheel that lands or lifts off: the next step holds from here on
                if n >= 0 and touching != (contact[w] != 0.0):  # (``hold``: a jump or kink in G and p)
                    gm[w] = a
                    jumped = True
                contact[w] = 1.0 if touching else 0.0
                if stored:
                    past_g[w] = gm[w]
                    wheel_force[r_out, w] = wf[w]
                    wheel_len[r_out, w] = wl[w]
            if jumped:
                for m in range(n_m):
                    pm[m] = p[m]
            if stored:
                for m in range(n_m):  # ξ̈ = p − 2ζω ξ̇ − ω² ξ; the hold's p of the step before the row
                    past_p[m] = pm[m]
                    xi[r_out, m] = x1[m]
                    dxi[r_out, m] = v1[m]
                    ddxi[r_out, m] = p[m] - 2.0 * zeta[m] * omega[m] * v1[m] - omega[m] * omega[m] * x1[m]
                for i in range(n_d):
                    q[r_out, i] = z1[i]
                    dq[r_out, i] = z1[n_d + i]
            n += 1
        return stop, evaluations, landings

    lean.__name__ = lean.__qualname__ = "lean_quadratic" if QUADRATIC else "lean"  # (each its own notice and cache)
    return njit(nogil=True, **FLAT_OPTIONS)(lean)


#: the variants of ``lean``: the wheel loads held linear and quadratic (the default integrator's)
lean = _make_lean(False)
lean_quadratic = _make_lean(True)


def lean_work(n_m: int, n_d: int, n_cp: int, n_w: int) -> tuple[np.ndarray, ...]:
    """The work spaces of ``lean`` (its trailing arguments; ``lean`` relies on their being zeroed): per mode
    (12, n_m), per vehicle state (2, 2 n_d), per wheel (14, n_w) (the last row: a step's G_{n−1} and its change
    for a second solution, ``lean_quadratic``), the held active
    sums (2 n_w + 1,), the vehicles' factorised matrix (n_w, n_w) and pivots (n_w,), per point (13, n_cp),
    per point flags (3, n_cp) and indices (2, n_cp; the station pointers −1: none yet), and the mode-shape
    rows φ, φ' (2, n_cp, n_m).  Allocated by numpy rather than in the kernel: numba compiles no allocation
    routines for them."""
    index = np.zeros((2, n_cp), np.int64)
    index[1] = -1
    return (np.zeros((12, n_m)), np.zeros((2, 2 * n_d)), np.zeros((14, n_w)),
            np.zeros(2 * n_w + 1), np.zeros((n_w, n_w)), np.zeros(n_w, np.int64), np.zeros((13, n_cp)),
            np.zeros((3, n_cp), np.bool_), index, np.zeros((2, n_cp, n_m)))


def lean_law(x1, z1, xp, vxp, start, end, grid_h, values, slopes, amp, wheel_rows, wheel_first, wheel_count, track,
             line, kk, cc, f0, gap, gated, width, stations, elevations, r_max, rv, rr, have_road, active, span=0.0):
    """The contact law ``_law`` of one crossing at rest (ξ̇ = 0, q̇ = 0) in the state ξ = ``x1``,
    q = ``z1`` for points at positions ``xp`` [m] with x-rates ``vxp`` [m/s] (the static start,
    ``vbikit.solve.system.static_state``): fills ``active`` per point, and the road elevation
    ``rv`` [m] and rate ``rr`` [m/s] under each point unless ``have_road`` (then they are given; the rate
    the secant over |v|·``span`` either side, ``road_point``).
    Arguments as ``lean``'s (``line`` clamped, ``gated`` with the unilateral gate), each contiguous, but
    the wheel rows ``wheel_rows`` h_w (n_w, n_d) themselves.  Calls the compiled ``_law`` itself (the
    one ``lean`` calls, with the same argument types: numba compiles it once for both) with work
    spaces from numpy."""
    n_cp, n_m, n_d, n_w = xp.size, x1.size, z1.size, wheel_rows.shape[0]
    wheel_dof, wheel_h = wheel_entries(wheel_rows)
    z = np.zeros(2 * n_d)
    z[:n_d] = z1
    onb = (start[track] <= xp) & (xp <= end[track])
    have = np.full(n_cp, 2 if have_road else 0, np.int64)
    phi, dphi = np.zeros((n_cp, n_m)), np.zeros((n_cp, n_m))
    _law(np.ascontiguousarray(x1, float), np.zeros(n_m), z, n_d, xp, vxp, onb, phi, dphi, have, rv, rr,
         np.full(n_cp, -1, np.int64), start, float(grid_h), values, slopes, amp, wheel_dof, wheel_h, wheel_first,
         wheel_count, track, line, kk, cc, f0, gap, gated, width, stations, elevations, float(r_max), float(span),
         np.zeros(n_cp),
         active, np.zeros(n_cp, np.bool_), np.zeros(n_cp), np.zeros(n_cp), np.zeros(n_w), np.zeros(n_w))


#: ``wheel_entries`` already made, by the rows' exact bytes (a traffic event's static start and step map read
#: them three times, and a stream's trucks with the same axles share their rows)
_ENTRIES: "Kept[tuple, tuple[np.ndarray, np.ndarray]]" = Kept(64)


def wheel_entries(wheel_rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``_wheel_entries`` of ``wheel_rows``, made once per rows (their shape and exact bytes) in a process
    and shared: not to be written to (writeable: numba compiles the kernels again for read-only arrays)."""
    rows = np.ascontiguousarray(wheel_rows, float)
    return _ENTRIES.get((rows.shape, rows.tobytes()), lambda: _wheel_entries(rows))


def _wheel_entries(wheel_rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The nonzero entries of each wheel's row h_w of ``wheel_rows`` (n_w, n_d), as the lean kernels read
    them: their DOF indices (n_w, k) int64, ascending, and values (n_w, k), k the most any row has, a
    shorter row padded with index 0 and value 0.0 (which the kernels skip).  Σ_e h[w, e] z[dof[w, e]]
    then adds the same nonzero terms of h_w·z in the same order as the dense row, in k terms instead
    of n_d (each wheel of the stock vehicles acts on two DOFs)."""
    rows = np.asarray(wheel_rows, float)
    nonzero = rows != 0.0
    k = int(nonzero.sum(axis=1).max(initial=0))
    order = np.argsort(~nonzero, axis=1, kind="stable")[:, :k]  # each row's nonzero columns first, ascending
    kept = np.take_along_axis(nonzero, order, axis=1)
    return (np.ascontiguousarray(np.where(kept, order, 0), np.int64),
            np.ascontiguousarray(np.where(kept, np.take_along_axis(rows, order, axis=1), 0.0)))
