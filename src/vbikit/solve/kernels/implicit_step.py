"""The partitioned implicit step (exact modal stepping, Newmark): the step loop and its end-of-step
state. (``vbikit.solve.kernels``: the equations and conventions.)"""
from __future__ import annotations

import numpy as np
from numba import njit

from vbikit.solve.kernels.bundles import _internal, _slot, _work
from vbikit.solve.kernels.hold import hold_correction_lanes, hold_jumps
from vbikit.solve.kernels.lanes import _axpy, _combine, _copy, _fetch, _gemv, _keep_step, _store, _width
from vbikit.solve.kernels.contact import _modal_load, _refresh, contact_forces, shape_point
from vbikit.solve.kernels.newton import QUASI_ITERATIONS, RELAX_AFTER, _full_newton, _lean_refine, _residuals, _same_active_set, _touch_points,\
    _vehicle_newton


@_internal
def _tire_load(vehicles, wheel_force, q, dq, out, lanes):
    """G_w = F_w + k_w z_w + c_w ż_w per wheel (n_w, L): the wheel force with the nominal tire's
    own linear part added back (the implicit vehicle carries k_w, c_w itself)."""
    n_l = _width(lanes, q)
    rows = vehicles.wheel_rows
    for w in range(rows.shape[0]):
        kw = vehicles.wheel_stiffness[w]
        cw = vehicles.wheel_damping[w]
        for lane in range(n_l):
            out[w, lane] = wheel_force[w, lane]
        for j in range(rows.shape[1]):
            h = rows[w, j]
            if h != 0.0:
                for lane in range(n_l):
                    out[w, lane] += h * (kw * q[j, lane] + cw * dq[j, lane])


@_internal
def _state_of(f, onb, cache, points, modes, vehicles, step, vstep, xf, vf, zb, p, fw, x1, v1, z1, lanes):
    """The end-of-step state for point forces ``f`` (n_cp, L): modal loads p = −Σ_p φ_p F_p (points on
    the deck), wheel sums ``fw``, deck ξ = ξ_f + c1 p, ξ̇ = ξ̇_f + c2 p, vehicles z = z_b + (P L1) F_w."""
    n_l = _width(lanes, f)
    phi, dphi = cache.phi, cache.dphi
    for m in range(p.shape[0]):
        for lane in range(n_l):
            p[m, lane] = 0.0
    for w in range(fw.shape[0]):
        for lane in range(n_l):
            fw[w, lane] = 0.0
    for k in range(f.shape[0]):
        nonzero = False
        for lane in range(n_l):
            if f[k, lane] != 0.0:
                nonzero = True
        if not nonzero:
            continue
        _axpy(1.0, f, k, fw, points.wheel[k], lanes)
        if onb[k]:
            if not cache.have[k]:
                shape_point(cache.x[k], points.track[k], modes, phi[k], dphi[k])
                cache.have[k] = True
            for m in range(p.shape[0]):
                _axpy(-phi[k, m], f, k, p, m, lanes)
    for m in range(p.shape[0]):
        c1 = step.c1[m]
        c2 = step.c2[m]
        for lane in range(n_l):
            x1[m, lane] = xf[m, lane] + c1 * p[m, lane]
            v1[m, lane] = vf[m, lane] + c2 * p[m, lane]
    _copy(zb, z1, lanes)
    _gemv(1.0, vstep.response, fw, z1, lanes, False)


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def implicit(dt, motion, modes, vehicles, points, road, unilateral, step, vstep, xi, dxi, q, dq, ddxi, ddq,
             wheel_force, wheel_len, past_p, past_g, resume, x_past, tol_force, max_iterations, lanes, stride=1, span=0.0):
    """Partitioned implicit step: every mode by its transition ``step`` (``ModalStep``, the
    modal load held linear or quadratic over the step), the vehicles by theirs (``VehicleStep``, the
    wheel loads held likewise), coupled through the contact forces at the end of the step.  The
    quadratic hold reads the loads of the step before: at the call's start ``past_p`` (n_m, L) and
    ``past_g`` (n_w, L) when ``resume`` (a call that goes on from a stored state), else the start's
    own (the run's start: the loads held constant before t_0, as the static start has them); on
    return they hold the loads of the step before the last row stored (where a call going on from
    that row starts).  ``x_past`` (n_cp,): the points' positions [m] a step before the start (the hold
    at the deck's ends, ``vbikit.solve.kernels.hold``).

    Both step maps are linear, so the end-of-step state is an affine function of the end-of-step
    point forces F (``_state_of``), and so is each point's contact law while the set of points in
    contact (and each rigid disk's acting point) stays the same: F_A = a_A + B_AA F_A, with B
    through the deck modes and through the vehicles.  The forces solve F − law(F) = 0, to
    ``tol_force`` [N] on every point of every lane.

    The common step costs one contact-law evaluation (``contact_forces``, gating and envelopes
    included) at the first guess, the linear extrapolation of the last two steps' forces: either
    that guess already holds, or quasi-Newton updates with the Jacobian through the vehicles only
    (``_vehicle_newton``: an n_w-square system of each wheel's sums of active k and c, whose factors
    are kept while the active set stays the same) settle it, the law at each iterate following
    exactly from the last evaluation by the change of the state (``_lean_refine``; the deck's part
    of B is ~1e-5 for road vehicles, so one or two such corrections do), as long as no contact opens
    or closes and no wheel has an envelope (rigid disk).  Otherwise the step iterates: evaluate the law at the
    current F, its active points A give the affine law; update F_A by it, F = 0 off A; repeat
    until the law holds.  The first ``QUASI_ITERATIONS`` updates are quasi-Newton (one system for
    all lanes when they share the contact set), later ones full Newton (``_full_newton``: the full
    Jacobian, ``_coupling``, factorised once per step and active set), which settles a contact
    change in one update.  A damped tire landing, where neither F = 0 nor F > 0 is consistent, is
    held at zero penetration (``TOUCH_STIFFNESS``; ``_touch_points``: also points the lazy test left
    out, and a wheel's touching points that are not level split into pressing, touching and clear).
    Should the contact set cycle, updates are
    halved after ``RELAX_AFTER`` full Newton iterations.  The step keeps the iterate's forces.

    The road rate in each point's law: the secant over |v|·``span`` either side (``road_point``;
    ``span`` = dt/2 for the implicit integrators, ``vbikit.solve.integrators.road_rate_span``; negative
    when the call starts at the run's start: the start state's law then reads the road ahead only,
    the steps |span|).

    Same array conventions as ``rk4`` (lanes and ``stride`` too; vbikit calls it with ``MANY_LANES``
    only, one lane too: one compiled variant, package docstring).  Returns the number of steps that did
    not converge within ``max_iterations`` (their last iterate is kept) and the number of
    contact-law evaluations.
    """
    n_l = 1 if len(lanes) == 1 else xi.shape[0]
    n_steps = (motion.travel.shape[0] - 1) // 2
    n_m = xi.shape[2]
    n_d = q.shape[2]
    n_cp = points.origin.size
    n_w = wheel_force.shape[2]
    omega, zeta = modes.omega, modes.zeta
    x0 = np.empty((n_m, n_l)); v0 = np.empty((n_m, n_l)); x1 = np.empty((n_m, n_l)); v1 = np.empty((n_m, n_l))
    corr = np.zeros((n_m, n_l)); sphi = np.zeros(n_m); sdphi = np.zeros(n_m)  # the hold at the deck's ends
    x_start = np.empty(n_cp); x_before = np.empty(n_cp)  # the positions at t_n, t_{n−1}
    contact = np.zeros((n_w, n_l), dtype=np.bool_); jumped = np.zeros(n_l, dtype=np.bool_)
    z0 = np.empty((2 * n_d, n_l)); z1 = np.empty((2 * n_d, n_l)); zf = np.zeros((2 * n_d, n_l))
    zb = np.zeros((2 * n_d, n_l))
    a1 = np.zeros((n_d, n_l))
    row0 = np.int64(0)  # the start row, not a bare 0 (``vbikit.solve.kernels``: literal arguments)
    _fetch(xi, row0, x0, lanes); _fetch(dxi, row0, v0, lanes); _fetch(q, row0, z0[:n_d], lanes)
    _fetch(dq, row0, z0[n_d:], lanes)
    xf = np.zeros((n_m, n_l)); vf = np.zeros((n_m, n_l))  # free deck response (load p_{n+1} = 0)
    p0 = np.zeros((n_m, n_l)); p = np.zeros((n_m, n_l)); pm = np.zeros((n_m, n_l))
    g0 = np.zeros((n_w, n_l)); g = np.zeros((n_w, n_l)); gm = np.zeros((n_w, n_l))
    f = np.zeros((n_cp, n_l)); f0 = np.zeros((n_cp, n_l)); fm = np.zeros((n_cp, n_l)); fw = np.zeros((n_w, n_l))
    f_old = np.zeros((n_cp, n_l))
    acc = np.zeros((n_m, n_l))
    work = _work(n_cp, n_d, n_l)
    force = work.force
    wf = np.zeros((n_w, n_l))
    wl = np.zeros((n_w, n_l))
    cache = _slot(n_cp, n_m, n_l)
    # Newton work space, sized for the most points that can act at once (one per rigid disk)
    cap = 0
    lean = True  # the one-evaluation step: not with rigid disks (their acting point may move)
    for w in range(n_w):
        cap += 1 if vehicles.wheel_envelope[w] else vehicles.wheel_count[w]
        if vehicles.wheel_envelope[w]:
            lean = False
    cap = max(cap, 1)
    dp = np.zeros(n_m); dxi_l = np.zeros(n_m); dvi_l = np.zeros(n_m)
    bq_l = np.zeros((n_w, n_l)); bv_l = np.zeros((n_w, n_l)); t_l = np.zeros((n_w, n_l))
    ksum = np.zeros((n_w, 1)); csum = np.zeros((n_w, 1)); veh = np.zeros((n_w, n_w))  # (``woodbury``'s layout)
    veh_piv = np.zeros(n_w, dtype=np.int64)
    veh_held = np.zeros(2 * n_w + 1)  # the sums whose factors ``veh`` holds, and whether it holds any
    n_r = min(cap, n_m + n_w)  # the larger factorisation ever needed is min(na, r)
    mat = np.zeros((n_r, n_r)); piv = np.zeros(n_r, dtype=np.int64); e = np.zeros((cap, n_m)); rhs = np.zeros(cap)
    u = np.zeros((cap, n_w)); red = np.zeros((n_m + n_w, n_m + n_w)); red_piv = np.zeros(n_m + n_w, dtype=np.int64)
    t = np.zeros(n_m + n_w)
    held_state = np.zeros(2, dtype=np.int64)  # size of the active set whose full Jacobian is held (−1: none); reduced
    act = np.zeros(cap, dtype=np.int64); held = np.zeros(cap, dtype=np.int64)
    onb = np.zeros(n_cp, dtype=np.bool_)
    lane_err = np.zeros(n_l)
    touch = np.zeros((n_cp, n_l), dtype=np.bool_)  # points held at zero penetration (see docstring)
    row_k = np.zeros(cap); row_c = np.zeros(cap); held_k = np.zeros(cap); held_c = np.zeros(cap)
    gated = np.zeros(n_cp, dtype=np.bool_)
    for k in range(n_cp):
        gated[k] = points.gated[k] or (unilateral and points.stiffness[k] > 0.0) or \
            vehicles.wheel_envelope[points.wheel[k]]
    # t = 0: forces, modal load, wheel loads and accelerations of the initial state
    _refresh(cache, motion, row0, points)
    y0, w0 = z0[:n_d], z0[n_d:]
    contact_forces(x0, v0, y0, w0, modes, vehicles, points, road, unilateral, cache, work, wf, wl, lanes, span)
    _modal_load(-1.0, cache.phi, force, work.used, cache.x, points.track, modes, p0, lanes)
    _tire_load(vehicles, wf, y0, w0, g0, lanes)
    for w in range(n_w):  # the wheels in contact at the start (``hold_jumps``)
        for lane in range(n_l):
            contact[w, lane] = wf[w, lane] > 0.0
    if resume:
        _copy(past_p, pm, lanes); _copy(past_g, gm, lanes)
    else:
        _copy(p0, pm, lanes); _copy(g0, gm, lanes)
        _copy(p0, past_p, lanes); _copy(g0, past_g, lanes)  # (row 0's)
    _vehicle_acceleration(vehicles, vstep, z0, g0, work.rhs, a1, lanes)
    _modal_acceleration(omega, zeta, x0, v0, p0, acc, lanes)
    _store(ddxi, row0, acc, lanes); _store(ddq, row0, a1, lanes)
    _store(wheel_force, row0, wf, lanes); _store(wheel_len, row0, wl, lanes)
    for k in range(n_cp):
        for lane in range(n_l):
            f0[k, lane] = force[k, lane] if work.used[k] else 0.0
            fm[k, lane] = f0[k, lane]
    unsettled = 0
    evaluations = 0
    y1, w1 = z1[:n_d], z1[n_d:]
    for n in range(n_steps):
        for k in range(n_cp):
            x_before[k] = x_start[k] if n > 0 else x_past[k]
            x_start[k] = cache.x[k]  # (t_n, before the refresh)
        _refresh(cache, motion, 2 * n + 2, points)
        for k in range(n_cp):
            onb[k] = modes.start[points.track[k]] <= cache.x[k] <= modes.end[points.track[k]]
        # first guess: linear extrapolation of the forces (the hold at the deck's ends reads it too)
        for k in range(n_cp):
            for lane in range(n_l):
                f[k, lane] = 2.0 * f0[k, lane] - fm[k, lane]
                touch[k, lane] = False
        # free responses: deck with p_{n+1} = 0, vehicles with F_{n+1} = 0; the hold's p_{n−1} with the shares
        # of points crossing a deck end replaced (``hold``)
        share = x_start if n == 0 and not resume else x_before  # (where p_{n−1} took each share)
        ends = hold_correction_lanes(x_before, share, x_start, cache.x, points.track, modes.start, modes.end,
                                     modes.grid_h, modes.values, modes.slopes, f0, sphi, sdphi, corr)
        if ends:
            for m in range(n_m):
                for lane in range(n_l):
                    corr[m, lane] += pm[m, lane]
        past = corr if ends else pm
        _combine(step.a11, x0, step.a12, v0, step.b1, p0, step.d1, past, xf, lanes)
        _combine(step.a21, x0, step.a22, v0, step.b2, p0, step.d2, past, vf, lanes)
        for i in range(2 * n_d):
            for lane in range(n_l):
                zf[i, lane] = vstep.constant[i]
                zb[i, lane] = 0.0
        _gemv(1.0, vstep.transition, z0, zf, lanes, False)
        _gemv(1.0, vstep.load0, g0, zf, lanes, False)
        _gemv(1.0, vstep.load_past, gm, zf, lanes, False)
        _gemv(1.0, vstep.settle, zf, zb, lanes, False)
        held_state[0] = -1  # new positions: no full Jacobian to reuse
        converged = False
        quasi = 0  # quasi-Newton updates of this step so far
        full = 0  # full Newton updates of this step so far
        for it in range(max_iterations):
            evaluations += 1
            _state_of(f, onb, cache, points, modes, vehicles, step, vstep, xf, vf, zb, p, fw, x1, v1, z1, lanes)
            contact_forces(x1, v1, y1, w1, modes, vehicles, points, road, unilateral, cache, work, wf, wl, lanes, abs(span))
            if _residuals(f, force, work.used, touch, lane_err, x1, v1, y1, w1, cache, points, vehicles, onb,
                          tol_force) <= tol_force:
                converged = True
                break
            if quasi >= QUASI_ITERATIONS:
                blend = 0.5 if full >= RELAX_AFTER else 1.0
                full += 1
                for lane in range(n_l):  # one full Newton update per unconverged lane (the rare path)
                    if lane_err[lane] > tol_force:
                        _touch_points(f, force, work.used, work.active, touch, gated, lane, tol_force, x1, v1, y1, w1,
                                      cache, points, vehicles, onb, step, vstep, fw, modes, road, work.idx, lanes,
                                      abs(span), act, row_k, row_c)
                        _full_newton(f, force, work.used, work.active, lane, blend, touch, gated, x1, v1, y1, w1,
                                     cache, points, vehicles, onb, step, vstep, p, fw, e, u, mat, piv, red, red_piv,
                                     rhs, t, act, held, held_k, held_c, row_k, row_c, held_state)
                continue
            quasi += 1
            if it == 0 and lean:
                _copy(f, f_old, lanes)
            if n_l > 1 and _same_active_set(work.used, work.active):
                # every lane has the same contact set (the common case of a batch): one update for all
                _vehicle_newton(f, force, work.used, work.active, np.int64(0), n_l, lane_err, tol_force, points, vstep,
                                fw, ksum, csum, veh_held, veh, veh_piv, bq_l, bv_l, t_l)
            else:
                for lane in range(n_l):  # one update per unconverged lane
                    if lane_err[lane] > tol_force:
                        _vehicle_newton(f, force, work.used, work.active, lane, lane + 1, lane_err, tol_force, points,
                                        vstep, fw, ksum, csum, veh_held, veh, veh_piv, bq_l, bv_l, t_l)
            if it == 0 and lean:  # the one-evaluation step: settle each lane by exact increments
                extra = 0
                for lane in range(n_l):
                    if lane_err[lane] > tol_force:
                        extra = max(extra, _lean_refine(
                            f, f_old, force, work, lane, tol_force, gated, points, cache, onb, step, vstep, fw, ksum,
                            csum, veh_held, veh, veh_piv, bq_l, bv_l, t_l, lane_err, modes.amp, dp, dxi_l, dvi_l))
                quasi += extra  # its updates count towards the quasi-Newton ones before the full Newton
                settled = True
                for lane in range(n_l):
                    settled = settled and lane_err[lane] <= tol_force
                if settled:
                    converged = True
                    break
        if not converged:
            unsettled += 1
        # the end state of the iterate's forces; a touching point's width counts as in contact
        for k in range(n_cp):
            for lane in range(n_l):
                if touch[k, lane] and not work.active[k, lane]:
                    wl[points.wheel[k], lane] += points.width[k]
        _state_of(f, onb, cache, points, modes, vehicles, step, vstep, xf, vf, zb, p, fw, x1, v1, z1, lanes)
        _copy(fw, wf, lanes)
        _tire_load(vehicles, wf, y1, w1, g, lanes)
        hold_jumps(wf, contact, g, p, p0, g0, jumped, lanes)  # (the loads before: p0, g0 become pm, gm below)
        _modal_acceleration(omega, zeta, x1, v1, p, acc, lanes)
        _vehicle_acceleration(vehicles, vstep, z1, g, work.rhs, a1, lanes)
        _keep_step(xi, dxi, ddxi, q, dq, ddq, wheel_force, wheel_len, n + 1, stride, x1, v1, acc, y1, w1, a1, wf, wl,
                   lanes)
        if (n + 1) % stride == 0:  # the hold's loads of the step before the row stored
            _copy(p0, past_p, lanes); _copy(g0, past_g, lanes)
        x0, x1 = x1, x0
        v0, v1 = v1, v0
        z0, z1 = z1, z0
        y1, w1 = z1[:n_d], z1[n_d:]
        pm, p0, p = p0, p, pm  # (the loads of the step before, for the hold)
        gm, g0, g = g0, g, gm
        fm, f0, f = f0, f, fm
    return unsettled, evaluations


@_internal
def _vehicle_acceleration(vehicles, vstep, z, g, rhs, out, lanes):
    """q̈ = M⁻¹(F_G + Hᵀ G − Ĉ q̇ − K̂ q) for the stacked state z = (q, q̇)."""
    n_d = out.shape[0]
    if n_d == 0:
        return
    n_l = _width(lanes, z)
    for i in range(n_d):
        for lane in range(n_l):
            rhs[i, lane] = vehicles.gravity[i]
            out[i, lane] = 0.0
    _gemv(-1.0, vstep.c_hat, z[n_d:], rhs, lanes, False)
    _gemv(-1.0, vstep.k_hat, z[:n_d], rhs, lanes, False)
    _gemv(1.0, vehicles.wheel_rows, g, rhs, lanes, True)
    _gemv(1.0, vehicles.mass_inv, rhs, out, lanes, False)


@_internal
def _modal_acceleration(omega, zeta, x, v, p, out, lanes):
    """ξ̈ = p − 2ζω ξ̇ − ω² ξ."""
    n_l = _width(lanes, x)
    for m in range(x.shape[0]):
        a = 2.0 * zeta[m] * omega[m]
        b = omega[m] * omega[m]
        for lane in range(n_l):
            out[m, lane] = p[m, lane] - a * v[m, lane] - b * x[m, lane]
