"""The implicit step's contact solve: the quasi-Newton update through the vehicles for lanes sharing
one active set (its wheels' part in ``woodbury``, shared with the lean kernels), the exact one-evaluation refinement, the full active-set Newton update
and its touch rows. (``vbikit.solve.kernels``: the equations and conventions.)"""
from __future__ import annotations

import numpy as np

from vbikit.solve.kernels.bundles import _internal
from vbikit.solve.kernels.contact import _gated, deck_increments, road_point, shape_point
from vbikit.solve.kernels.dense import _lu_factor, _lu_solve, solve_held
from vbikit.solve.kernels.woodbury import vehicle_back, vehicle_factors, vehicle_rhs


#: quasi-Newton updates (the Jacobian through the vehicles only) before the full Newton updates: for
#: road vehicles on bridges the deck's part of B is small (|B_deck| ~ 1e-5), so these usually settle
#: a step at a fraction of a full Newton step's cost, with a factorisation that depends only on the
#: active set (kept across steps); the full Newton steps settle the rest
QUASI_ITERATIONS = 4


#: Newton iterations after which the implicit kernel halves its updates (a contact set that would cycle)
RELAX_AFTER = 8


@_internal
def _coupling(act, na, row_k, row_c, onb, cache, points, step, vstep, e, u, mat, piv, red, red_piv):
    """Factorise the Jacobian of the contact law on the active points ``act[:na]`` (row i with tire
    stiffness ``row_k[i]`` and damping ``row_c[i]``).

    Row i of the law's affine part depends on the end-of-step modal loads p through
    e_i = ∂F_i/∂p (n_m) and on the wheel forces F_w through u_i = ∂F_i/∂F_w (n_w); with
    p = −Σ_j φ_j F_j and F_w = Σ_{j∈w} F_j, the matrix to solve is I − B_AA = I + W Z, W = [E U]
    (na, r), Z = [Φ_Aᵀ; S_A] (r, na), r = n_m + n_w.  Factorised directly (``mat``, na × na) when
    na ≤ r, else through the capacitance matrix I_r + Z W (``red``, r × r; Woodbury's identity),
    whichever is smaller.  Returns True for the second form."""
    phi, dphi = cache.phi, cache.dphi
    n_m = e.shape[1]
    n_w = u.shape[1]
    for i in range(na):
        k = act[i]
        kk = row_k[i]
        cc = row_c[i]
        wi = points.wheel[k]
        if onb[k]:
            vx = cache.vx[k]
            for m in range(n_m):
                e[i, m] = (kk * step.c1[m] + cc * step.c2[m]) * phi[k, m] + cc * vx * step.c1[m] * dphi[k, m]
        else:
            for m in range(n_m):
                e[i, m] = 0.0
        for w in range(n_w):
            u[i, w] = kk * vstep.wheel_q[wi, w] + cc * vstep.wheel_v[wi, w]
    if na <= n_m + n_w:
        for i in range(na):
            for j in range(na):
                kj = act[j]
                b = u[i, points.wheel[kj]]
                if onb[kj]:
                    for m in range(n_m):
                        b += e[i, m] * phi[kj, m]
                mat[i, j] = b + (1.0 if i == j else 0.0)
        _lu_factor(mat, na, piv)
        return False
    r = n_m + n_w
    for a in range(r):
        for b in range(r):
            red[a, b] = 1.0 if a == b else 0.0
    for i in range(na):
        k = act[i]
        wi = points.wheel[k]
        if onb[k]:
            for m in range(n_m):
                fm = phi[k, m]
                for m2 in range(n_m):
                    red[m, m2] += fm * e[i, m2]
                for w in range(n_w):
                    red[m, n_m + w] += fm * u[i, w]
        for m2 in range(n_m):
            red[n_m + wi, m2] += e[i, m2]
        for w in range(n_w):
            red[n_m + wi, n_m + w] += u[i, w]
    _lu_factor(red, r, red_piv)
    return True


@_internal
def _newton_solve(act, na, onb, cache, points, e, u, mat, piv, red, red_piv, reduced, rhs, t):
    """Solve (I − B_AA) x = ``rhs`` in place with the factors of ``_coupling`` (``t``: r work)."""
    if not reduced:
        _lu_solve(mat, na, piv, rhs)
        return
    phi = cache.phi
    n_m = e.shape[1]
    n_w = u.shape[1]
    for a in range(n_m + n_w):
        t[a] = 0.0
    for i in range(na):
        k = act[i]
        if onb[k]:
            for m in range(n_m):
                t[m] += phi[k, m] * rhs[i]
        t[n_m + points.wheel[k]] += rhs[i]
    _lu_solve(red, n_m + n_w, red_piv, t)
    for i in range(na):
        x = rhs[i]
        for m in range(n_m):
            x -= e[i, m] * t[m]
        for w in range(n_w):
            x -= u[i, w] * t[n_m + w]
        rhs[i] = x


#: the touching rows' stiffness, in units of the point's own: the end-of-step penetration of a touching
#: point shrinks by about this factor per Newton iteration (it is exactly 0 at convergence)
TOUCH_STIFFNESS = 1e6


@_internal
def _penetration(k, lane, x1, v1, y1, w1, cache, points, vehicles, onb):
    """Penetration δ [m] and the ungated law k δ + c δ̇ + f0 [N] of point ``k`` in lane ``lane`` at the
    end-of-step state (its road values and mode shapes in ``cache``); on a rigid disk's wheel the
    surface rate along the travel is clamped to the circle's slopes, as in ``_envelope``."""
    s = cache.rv[k, lane]
    sd = cache.rr[k, lane]
    deck_rate = 0.0
    vx = cache.vx[k]
    if onb[k]:
        for m in range(x1.shape[0]):
            s += cache.phi[k, m] * x1[m, lane]
            deck_rate += cache.phi[k, m] * v1[m, lane]
            sd += vx * cache.dphi[k, m] * x1[m, lane]
    w = points.wheel[k]
    if vehicles.wheel_envelope[w]:
        v = points.direction[k] * vx
        sd = min(max(sd, v * points.slope_range[k, 0]), v * points.slope_range[k, 1])
    rate = sd + deck_rate
    for j in range(y1.shape[0]):
        h = vehicles.wheel_rows[w, j]
        s -= h * y1[j, lane]
        rate -= h * w1[j, lane]
    pen = s - points.gap[k]
    return pen, points.stiffness[k] * pen + points.damping[k] * rate + points.fixed_load[k]


@_internal
def _same_active_set(used, active):
    """Whether every lane has the same active points."""
    for k in range(active.shape[0]):
        if used[k]:
            a0 = active[k, 0]
            for lane in range(1, active.shape[1]):
                if active[k, lane] != a0:
                    return False
    return True


@_internal
def _vehicle_newton(f, force, used, active, lane0, lane1, lane_err, tol, points, vstep, fw, ksum, csum, held, veh,
                    veh_piv, bq, bv, t):
    """One quasi-Newton update of the point forces ``f[:, lane]`` of every unconverged lane
    (``lane_err`` > ``tol``) in ``lane0`` … ``lane1`` − 1, lanes that share the active set A of lane
    ``lane0``, with the Jacobian through the vehicles only (``woodbury``: the n_w-square system
    (I + S_A U_A) t = S_A b, whose factors ``veh``, ``veh_piv`` are kept while each wheel's sums of active
    k and c, ``ksum``, ``csum`` (n_w, 1), stay the same — across iterations and steps: the step map
    ``vstep`` is that of the whole run): O(points + wheels²) per lane, the lanes innermost.  On return
    ``bq``, ``bv`` (n_w, L) hold each wheel's change of −z_w and −ż_w by the update (the vehicles' part
    of the change of its points' penetration and rate)."""
    n_cp = f.shape[0]
    wq, wv = vstep.wheel_q, vstep.wheel_v
    n_w, _ = ksum.shape
    for w in range(n_w):
        ksum[w, 0] = 0.0
        csum[w, 0] = 0.0
    for k in range(n_cp):
        if used[k] and active[k, lane0]:
            ksum[points.wheel[k], 0] += points.stiffness[k]
            csum[points.wheel[k], 0] += points.damping[k]
    zero = np.int64(0)
    vehicle_factors(veh, veh_piv, held, ksum, csum, zero, wq, wv)
    vehicle_rhs(wq, wv, fw, ksum, csum, zero, bq, bv, t, lane0, lane1)
    for k in range(n_cp):  # S_A b = Σ_i∈A∩w (F_i + k_i bq + c_i bv)
        if used[k] and active[k, lane0]:
            w = points.wheel[k]
            for lane in range(lane0, lane1):
                t[w, lane] += force[k, lane]
    solve_held(veh, veh_piv, t, lane0, lane1)  # t ← V⁻¹ t, every lane at once
    vehicle_back(wq, wv, t, bq, bv, lane0, lane1)
    for k in range(n_cp):
        on = used[k] and active[k, lane0]
        w = points.wheel[k]
        kk = points.stiffness[k]
        cc = points.damping[k]
        for lane in range(lane0, lane1):
            if lane_err[lane] > tol:  # a settled lane keeps its forces (as one lane would)
                f[k, lane] = force[k, lane] + kk * bq[w, lane] + cc * bv[w, lane] if on else 0.0


#: exact incremental corrections of the one-evaluation step before it falls back to iterating
LEAN_CORRECTIONS = 4


@_internal
def _lean_refine(f, f_old, force, work, lane, tol, gated, points, cache, onb, step, vstep, fw, ksum, csum, veh_held,
                 veh, veh_piv, bq, bv, t, lane_err, amp, dp, dxi, dvi):
    """Settle lane ``lane`` of the one-evaluation step without another contact-law evaluation: its
    ``lane_err`` is set to 0 when its iterate ``f`` holds the law to ``tol``, and stays above ``tol``
    when a contact would open or close (the step then iterates with full evaluations).  Returns the
    number of quasi-Newton updates made here.

    On entry ``f`` is the quasi-Newton iterate from ``f_old``, whose law the last evaluation gave
    (``work.pen``, ``work.law`` per point), and ``bq``, ``bv`` the vehicles' part of the update
    (``_vehicle_newton``).  With the positions fixed, the law is affine in the state and the state in
    F, so the law at the iterate follows exactly from the change: the deck moves by Δξ = c1 Δp,
    Δξ̇ = c2 Δp with Δp = −Σ_k φ_k ΔF_k, every point's penetration by φ_k·Δξ + bq_w and its rate by
    φ_k·Δξ̇ + v_x φ'_k·Δξ + bv_w (no mode-shape, road or lazy-test work: what an evaluation costs
    besides).  A point left out by the lazy test must stay out (its bound + bq_w + Σ amp|Δξ| ≤ 0).
    Should the law not hold to ``tol`` yet, another quasi-Newton update follows (the vehicle factors
    kept), at most ``LEAN_CORRECTIONS`` times; each shrinks the residual by about the deck's part of
    the Jacobian (~1e-5 for road vehicles)."""
    used, active, pen, law = work.used, work.active, work.pen, work.law
    phi, dphi = cache.phi, cache.dphi
    n_m = dp.shape[0]
    n_cp = f.shape[0]
    n_w = fw.shape[0]
    for r in range(LEAN_CORRECTIONS):
        for m in range(n_m):
            dp[m] = 0.0
        for k in range(n_cp):
            d = f[k, lane] - f_old[k, lane]
            if d != 0.0 and onb[k]:
                for m in range(n_m):
                    dp[m] -= phi[k, m] * d
        b = 0.0
        for m in range(n_m):
            dxi[m] = step.c1[m] * dp[m]
            dvi[m] = step.c2[m] * dp[m]
            b += amp[m] * abs(dxi[m])
        err = 0.0
        for k in range(n_cp):
            w = points.wheel[k]
            if not used[k]:  # left out by the lazy test: its bound on δ must stay ≤ 0
                pen[k, lane] += bq[w, lane] + (b if onb[k] else 0.0)
                if pen[k, lane] > 0.0:
                    return r
                continue
            ds, dr, dsd = deck_increments(phi, dphi, k, dxi, dvi) if onb[k] else (0.0, 0.0, 0.0)
            dpen = ds + bq[w, lane]
            pen[k, lane] += dpen
            law[k, lane] += points.stiffness[k] * dpen + points.damping[k] * (dr + cache.vx[k] * dsd + bv[w, lane])
            fk = _gated(law[k, lane], pen[k, lane], gated[k])
            if (not gated[k] or fk > 0.0) != active[k, lane]:
                return r  # a contact opens or closes: the full iteration decides
            force[k, lane] = fk
            err = max(err, abs(fk - f[k, lane]))
        lane_err[lane] = err
        if err <= tol:
            lane_err[lane] = 0.0
            return r
        for k in range(n_cp):
            f_old[k, lane] = f[k, lane]
        for w in range(n_w):
            fw[w, lane] = 0.0
        for k in range(n_cp):
            fw[points.wheel[k], lane] += f[k, lane]
        _vehicle_newton(f, force, used, active, lane, lane + 1, lane_err, tol, points, vstep, fw, ksum, csum,
                        veh_held, veh, veh_piv, bq, bv, t)
    return LEAN_CORRECTIONS


@_internal
def _residuals(f, force, used, touch, lane_err, x1, v1, y1, w1, cache, points, vehicles, onb, tol):
    """Per lane the largest |law(F) − F| over the points (``lane_err``; a touching point: k|δ| while
    0 ≤ F ≤ its law at δ = 0, else it is released); returns the largest over the lanes."""
    n_l = lane_err.size
    for lane in range(n_l):
        lane_err[lane] = 0.0
    for k in range(f.shape[0]):
        u = used[k]
        for lane in range(n_l):
            if touch[k, lane]:  # held at δ = 0 with 0 ≤ F ≤ the law's value there
                pen, law = _penetration(k, lane, x1, v1, y1, w1, cache, points, vehicles, onb)
                if 0.0 <= f[k, lane] <= law + tol:
                    lane_err[lane] = max(lane_err[lane], abs(points.stiffness[k] * pen))
                    continue
                touch[k, lane] = False
            r = abs((force[k, lane] if u else 0.0) - f[k, lane])
            lane_err[lane] = max(lane_err[lane], r)
    err = 0.0
    for lane in range(n_l):
        err = max(err, lane_err[lane])
    return err


@_internal
def _touch_points(f, force, used, active, touch, gated, lane, tol, x1, v1, y1, w1, cache, points, vehicles, onb, step,
                  vstep, fw, modes, road, idx, lanes, span, order, depth, carry):
    """Before a full Newton update of lane ``lane``: the touch test of ``_full_newton`` (a gated point the
    iterate presses, F > 0, that the law releases, touches if δ ≤ 0 and its law > 0) made first, on
    every point that needs it, and a wheel's touching points settled together (``_split_touch``).

    Points the lazy test left out (``contact_forces``: bound on δ ≤ 0, force 0, inactive) are taken in
    when the iterate presses them or holds them touching: their road values (``road_point``, ``span``
    as the law's) and mode shapes are filled, and they count as used with the force 0 and inactive
    that the law gives there.  Without this a damped landing whose iterate lifts the wheel above the
    road's highest elevation cycles: F_A lifts the points out (left out: F = 0), F = 0 presses them in
    (active: F = F_A), and the touch test, which ``_full_newton`` makes on used points only, never
    sees them.  ``order``, ``depth``, ``carry``: work space of the points' count."""
    for k in range(f.shape[0]):
        if not gated[k] or not (touch[k, lane] or f[k, lane] > 0.0):
            continue
        if not used[k]:
            if not cache.have_r[k]:
                road_point(cache.x[k], cache.vx[k], k, points.line[k], road, idx, cache.rv, cache.rr, lanes, span)
                cache.have_r[k] = True
            if onb[k] and not cache.have[k]:
                shape_point(cache.x[k], points.track[k], modes, cache.phi[k], cache.dphi[k])
                cache.have[k] = True
            used[k] = True
        if not active[k, lane] and not touch[k, lane]:
            pen, law = _penetration(k, lane, x1, v1, y1, w1, cache, points, vehicles, onb)
            touch[k, lane] = pen <= 0.0 and law > 0.0
    _split_touch(force, used, active, touch, lane, tol, x1, v1, y1, w1, cache, points, vehicles, onb, step, vstep,
                 fw, order, depth, carry)


@_internal
def _split_touch(force, used, active, touch, lane, tol, x1, v1, y1, w1, cache, points, vehicles, onb, step, vstep, fw,
                 order, depth, carry):
    """Which of a wheel's touching points settle its landing, where they are not all level.  Held at
    δ = 0 together, points whose δ differ (the road or the deck under a multipoint patch not quite
    level) would ask for δ_i − δ_j = 0 of one rigid wheel: forces of
    ±10⁴ of the wheel load, which the next residual releases, and the iteration cycles between all
    points pressed (F = 0 sinks the wheel in) and all lifted (their F lifts it out).

    The law's solution has, ordered by depth, the deepest points pressing (δ > 0, each carrying about
    its law at δ = 0, c δ̇ + f0: their k δ is tiny), the points level with the next one touching (δ = 0,
    0 ≤ F ≤ the law there) and the rest clear (δ < 0, F = 0).  The wheel force F_req that brings the
    deepest point to δ = 0 is estimated from the iterate: its wheel force, the deepest δ and the
    wheel's compliance through the vehicles and the deck, wheel_q + Σ c1 φ² (the rate's: wheel_v +
    Σ c2 φ²).  Less what the wheel's pressing points carry then, the deepest points press while the
    sum of their laws at δ = 0 stays below F_req; the next one touches, and with it every point level
    with it (δ within ``tol``/k, where the touching
    residual k|δ| allows); those deeper press, enter the update as active rows with their ungated law
    (``force``, ``active`` of lane ``lane`` set here; the next evaluation sets them anew).  The update
    is exact for that choice and the next residual confirms it (should all of them fall short of F_req
    by the estimate, the shallowest touches all the same: the estimate is a linearisation at the
    iterate, and a touching point takes whatever δ = 0 needs).  A wheel whose touching points are all
    level (one point, or a level patch) is left as it is."""
    first, count = vehicles.wheel_first, vehicles.wheel_count
    n_m = step.c1.shape[0]
    for w in range(first.shape[0]):
        n = 0
        for k in range(first[w], first[w] + count[w]):
            if used[k] and touch[k, lane] and not active[k, lane]:
                order[n] = k
                n += 1
        if n < 2:
            continue
        for i in range(n):  # depth and law at δ = 0 of each touching point, deepest first
            pen, law = _penetration(order[i], lane, x1, v1, y1, w1, cache, points, vehicles, onb)
            depth[i] = pen
            carry[i] = law - points.stiffness[order[i]] * pen
            j = i
            while j > 0 and depth[j] > depth[j - 1]:
                depth[j], depth[j - 1] = depth[j - 1], depth[j]
                carry[j], carry[j - 1] = carry[j - 1], carry[j]
                order[j], order[j - 1] = order[j - 1], order[j]
                j -= 1
        level = True
        for i in range(1, n):
            level = level and points.stiffness[order[i]] * (depth[0] - depth[i]) <= tol
        if level:
            continue
        d = order[0]
        a = vstep.wheel_q[w, w]
        b = vstep.wheel_v[w, w]
        if onb[d]:
            for m in range(n_m):
                g = cache.phi[d, m] * cache.phi[d, m]
                a += step.c1[m] * g
                b += step.c2[m] * g
        need = fw[w, lane] + depth[0] / a  # the wheel force that brings the deepest point to δ = 0
        if need <= 0.0:  # the wheel stays clear of the road without force
            for i in range(n):
                touch[order[i], lane] = False
            continue
        held = 0.0  # what the wheel's pressing points carry under F_req
        for k in range(first[w], first[w] + count[w]):
            if used[k] and active[k, lane]:
                held += max(0.0, force[k, lane] - (points.stiffness[k] * a + points.damping[k] * b) *
                            (need - fw[w, lane]))
        edge = n  # the point that settles it (n: none, all press)
        for i in range(n):
            carry[i] -= points.damping[order[i]] * b * (need - fw[w, lane])  # its law at δ = 0 under F_req
            if carry[i] > 0.0 and held < need:
                held += carry[i]
                if held >= need:
                    edge = i
        if edge == n:  # not enough even if all pressed: the shallowest touches
            edge = n - 1
        for i in range(n):
            k = order[i]
            level = edge < n and points.stiffness[k] * abs(depth[i] - depth[edge]) <= tol
            touch[k, lane] = level
            if not level and i < edge and carry[i] > 0.0:
                active[k, lane] = True  # pressing: an active row with its ungated law
                force[k, lane] = _penetration(k, lane, x1, v1, y1, w1, cache, points, vehicles, onb)[1]


@_internal
def _full_newton(f, force, used, active, lane, blend, touch, gated, x1, v1, y1, w1, cache, points, vehicles, onb,
                 step, vstep, p, fw, e, u, mat, piv, red, red_piv, rhs, t, act, held, held_k, held_c, row_k, row_c,
                 held_state):
    """One full Newton update of lane ``lane``'s point forces: the affine law of the active set A
    (touching points as stiff rows, ``TOUCH_STIFFNESS``) solved with the full Jacobian (``_coupling``,
    factorised once per step and set: ``held``, ``held_k``, ``held_c``, ``held_state`` = (size of
    the set held or −1, reduced form)); F ← (1 − ``blend``) F + ``blend`` F_new."""
    n_cp = f.shape[0]
    n_m = e.shape[1]
    n_w = u.shape[1]
    na = np.int64(0)  # not a bare 0: its literal type would compile the helpers it reaches twice
    for k in range(n_cp):
        if not used[k]:
            continue
        if gated[k] and not active[k, lane] and not touch[k, lane] and f[k, lane] > 0.0:
            # pressed in the iterate, released by the law: touching if the law would press
            # at zero penetration (a damped tire landing), so that F = 0 and F > 0 both fail
            pen, law = _penetration(k, lane, x1, v1, y1, w1, cache, points, vehicles, onb)
            touch[k, lane] = pen <= 0.0 and law > 0.0
        if touch[k, lane]:
            act[na] = k
            row_k[na] = TOUCH_STIFFNESS * points.stiffness[k]
            row_c[na] = 0.0
            na += 1
        elif active[k, lane]:
            act[na] = k
            row_k[na] = points.stiffness[k]
            row_c[na] = points.damping[k]
            na += 1
    same = na == held_state[0]
    if same:
        for i in range(na):
            if act[i] != held[i] or row_c[i] != held_c[i] or row_k[i] != held_k[i]:
                same = False
                break
    if not same:
        held_state[1] = _coupling(act, na, row_k, row_c, onb, cache, points, step, vstep, e, u, mat, piv, red,
                                  red_piv)
        for i in range(na):
            held[i] = act[i]
            held_k[i] = row_k[i]
            held_c[i] = row_c[i]
        held_state[0] = na
    for i in range(na):  # a_A = law_A(F) − (B F)_A; touching rows: F + K δ (K = row_k)
        k = act[i]
        if touch[k, lane]:
            pen, law = _penetration(k, lane, x1, v1, y1, w1, cache, points, vehicles, onb)
            a = f[k, lane] + row_k[i] * pen
        else:
            a = force[k, lane]
        for m in range(n_m):
            a -= e[i, m] * p[m, lane]
        for w in range(n_w):
            a += u[i, w] * fw[w, lane]
        rhs[i] = a
    _newton_solve(act, na, onb, cache, points, e, u, mat, piv, red, red_piv, held_state[1] != 0, rhs, t)
    for k in range(n_cp):
        f[k, lane] *= 1.0 - blend
    for i in range(na):
        f[act[i], lane] += blend * rhs[i]
