"""The contact law: point kinematics, mode shapes and road under the points, the tire law, rigid-disk
envelopes, and the right-hand side of the coupled equations. (``vbikit.solve.kernels``: the
equations and conventions.)"""
from __future__ import annotations

from numba import njit

from vbikit.solve.kernels.bundles import _internal
from vbikit.solve.kernels.lanes import _axpy, _gemv, _width


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def hermite_shape(x, tr, start, grid_h, values, slopes, phi_row, dphi_row):
    """φ(x) and ∂φ/∂x(x) on tabulated track ``tr`` (``values``, ``slopes`` (n_tracks, n_grid, n_m)
    from ``start[tr]`` at spacing ``grid_h``) into ``phi_row``, ``dphi_row``: the cubic Hermite
    interpolant of the tabulated shapes and slopes, clamped to the last cell.  The one copy of this
    arithmetic, for the bundle kernels (``shape_point``) and the lean one."""
    _, n_grid, n_m = values.shape  # (unpacked: numba types an indexed shape through a compiled overload)
    u = (x - start[tr]) / grid_h
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
    for m in range(n_m):
        a0 = values[tr, i, m]
        a1 = values[tr, i + 1, m]
        b0 = slopes[tr, i, m]
        b1 = slopes[tr, i + 1, m]
        phi_row[m] = h00 * a0 + h10 * b0 + h01 * a1 + h11 * b1
        dphi_row[m] = d00 * a0 + d10 * b0 + d01 * a1 + d11 * b1


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def shape_point(x, track, modes, phi_row, dphi_row):
    """φ(x) and ∂φ/∂x(x) of one point on tabulated track ``track`` of ``modes`` (cubic Hermite,
    ``hermite_shape``)."""
    hermite_shape(x, track, modes.start, modes.grid_h, modes.values, modes.slopes, phi_row, dphi_row)


@njit(cache=True, fastmath=True, error_model="numpy")
def shapes_at(x, track, modes, phi, dphi, on):
    """Mode-shape rows φ_p, φ'_p of points at positions ``x`` [m] on tracks ``track`` (eager);
    ``on[p]``: the point is on the deck (else its rows are left as they are)."""
    for p in range(x.size):
        on[p] = modes.start[track[p]] <= x[p] <= modes.end[track[p]]
        if on[p]:
            shape_point(x[p], track[p], modes, phi[p], dphi[p])


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def point_kinematics(motion, row, points, x, vx):
    """Positions x_p = origin_p + dir_p·s_v and x-rates dir_p·v_v [m/s] of every point at
    half-step ``row`` of ``motion``."""
    for p in range(points.origin.size):
        v = points.vehicle[p]
        d = points.direction[p]
        x[p] = points.origin[p] + d * motion.travel[row, v]
        vx[p] = d * motion.speed[row, v]


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def first_cell(stations, x):
    """The road cell of position ``x`` [m] by bisection: the last station ≤ x, within 0 … n_s − 2
    (as ``searchsorted(stations, x, "right") − 1`` clamped; written out, which numba compiles in a
    fraction of the time)."""
    lo = 0
    hi = stations.size - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if stations[mid] <= x:
            lo = mid
        else:
            hi = mid
    return lo


#: a position within this fraction of its cell's width of a station is on that station
#: (``road_cell``): stations x0 + h·i and positions origin ± travel carry rounding errors of some
#: 1e-14 m, far below it; a point between them for 1e-11 m of a 1 cm cell passes in picoseconds.
ON_STATION = 1e-9


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def road_cell(stations, x, vx, idx, p):
    """The road cell i (stations[i] ≤ x < stations[i + 1]) whose line interpolates the road at
    position ``x`` [m] of point ``p`` moving at ``vx`` [m/s]: ``idx[p]`` is the point's station
    pointer (−1 before its first use: found by ``first_cell``), moved either way and stored.  On a
    station the cell is the one the point moves into: on its +x side, or on its −x side when vx < 0
    (a vehicle driving −x sees the mirror of what one driving +x sees).  A point is on a station
    within ``ON_STATION`` of the cell's width, either side: a point that starts on a station (a whole
    number of stations from the road's origin) is computed a rounding error (≈ 1e-14 m) to one side
    of it, and the cell that error picks gave RK4's start road rate (the static start's dashpot
    load) the slope of the cell behind the point, whose start then differed from the implicit
    integrators' (which read the road ahead over half a step, ``secant_ends``) by c·v·Δslope/k."""
    n_s = stations.size
    i = idx[p]
    if i < 0:
        i = first_cell(stations, x)
    while i < n_s - 2 and stations[i + 1] <= x:
        i += 1
    while i > 0 and stations[i] > x:
        i -= 1
    idx[p] = i
    tol = ON_STATION * (stations[i + 1] - stations[i])
    if vx < 0.0:  # on station i (or just past it): the cell behind it, the one the point moves into
        if i > 0 and x - stations[i] <= tol:
            i -= 1
    elif i < n_s - 2 and stations[i + 1] - x <= tol:  # on station i + 1, just short of it: the cell ahead
        i += 1
    return i


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def secant_ends(x, vx, span):
    """The ends (lo, hi) [m] of the road the secant rate of a point at ``x`` moving at ``vx`` [m/s]
    reads (``road_point``): with ``span`` > 0 [s] the half steps around it, x ∓ a with a = |vx|·span;
    with ``span`` < 0 the run's start, where the point has no road behind it: the road ahead only,
    x … x + a driving +x (x − a … x driving −x) with a = |vx|·|span| (the first half step's road, the
    limit from the start's side: what RK4's cell slope reads there).  lo = hi where a = 0."""
    a = abs(vx) * abs(span)
    lo = x - a
    hi = x + a
    if span < 0.0:
        if vx > 0.0:
            lo = x
        else:
            hi = x
    return lo, hi


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def road_cells(stations, lo, hi, x, vx, idx, p):
    """The road cells of point ``p`` at position ``x`` [m] moving at ``vx`` [m/s] (``road_cell``):
    with ``hi`` > ``lo`` first those of the secant rate's two readings at ``lo`` and ``hi`` [m]
    (``secant_ends``) with their in-cell fractions, r = z_i + t (z_{i+1} − z_i) (beyond the road's
    ends, the end cell's line extended), then the cell i of x; returns (i_a, t_a, i_b, t_b, i) (with
    hi ≤ lo only i, the others 0).  The pointer ``idx[p]`` is left at the cell of x.  One
    ``road_cell`` call site for the three readings (numba inlines its body once instead of three
    times: less for the kernels to compile)."""
    ia = 0
    ib = 0
    ta = 0.0
    tb = 0.0
    i = 0
    for j in range(0 if hi > lo else 2, 3):  # lo, hi, then x
        xj = lo if j == 0 else (hi if j == 1 else x)
        c = road_cell(stations, xj, vx, idx, p)
        if j == 2:
            i = c
        elif j == 0:
            ia = c
            ta = (xj - stations[c]) / (stations[c + 1] - stations[c])
        else:
            ib = c
            tb = (xj - stations[c]) / (stations[c + 1] - stations[c])
    return ia, ta, ib, tb, i


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def road_point(x, vx, p, line, road, idx, rv, rr, lanes, span):
    """Road elevation ``rv[p, :]`` [m] and rate ``rr[p, :]`` [m/s] of every lane at position ``x`` [m]
    of point ``p`` moving at ``vx`` [m/s] on road line ``line`` (linear interpolation; ``idx[p]`` is
    the point's station pointer: ``road_cell``, which also picks the cell on a station).

    The rate (``vbikit.solve.kernels`` docstring, "the road rate"): with ``span`` = 0 the slope of the
    point's cell, vx·dr/dx; with ``span`` > 0 [s] the secant over a = |vx|·span either side,
    vx (r(x + a) − r(x − a)) / 2a: with span = dt/2 the road between the half steps around a step
    end, which the implicit integrators' trapezoid then follows; with ``span`` < 0 (the run's start)
    the secant over the road ahead only, vx (r(x + a) − r(x)) / a driving +x (``secant_ends``,
    ``road_cells``)."""
    n_l = _width(lanes, rv)
    stations = road.stations
    z = road.elevations[min(line, road.elevations.shape[0] - 1)]
    lo, hi = secant_ends(x, vx, span)
    a = hi - lo
    ia, ta, ib, tb, i = road_cells(stations, lo, hi, x, vx, idx, p)
    if a > 0.0:
        scale = vx / a
        for lane in range(n_l):
            rr[p, lane] = (z[ib, lane] + tb * (z[ib + 1, lane] - z[ib, lane])
                           - z[ia, lane] - ta * (z[ia + 1, lane] - z[ia, lane])) * scale
    dx = x - stations[i]
    inv = 1.0 / (stations[i + 1] - stations[i])
    for lane in range(n_l):
        slope = (z[i + 1, lane] - z[i, lane]) * inv
        rv[p, lane] = z[i, lane] + slope * dx
        if a <= 0.0:
            rr[p, lane] = slope * vx


@njit(cache=True, fastmath=True, error_model="numpy")
def road_at(x, vx, points, road, idx, rv, rr, lanes, span):
    """Road elevation and rate (n_cp, L) under every contact point at positions ``x`` [m] moving
    at x-rates ``vx`` [m/s] (``idx``: the points' station pointers; ``span`` [s]: the rate's secant
    half-width in time, 0 for the cell's slope, negative at the run's start: see ``road_point``).
    A rigid disk's candidate points read the road ahead at the start too: the rate its envelope
    then has, that of the candidate in contact over the cell it moves into, clamped
    (``contact_forces``, ``_envelope``)."""
    for p in range(x.size):
        road_point(x[p], vx[p], p, points.line[p], road, idx, rv, rr, lanes, span)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def point_law(k, c, f0, pen, rate, gate):
    """The tire law of one point: F = k δ + c δ̇ + f0 [N] (compression > 0) for penetration δ =
    ``pen`` [m] and rate δ̇ = ``rate`` [m/s]; a ``gate``-d point carries it only while it
    penetrates and presses (else 0)."""
    f = k * pen + c * rate + f0
    return _gated(f, pen, gate)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _gated(f, pen, gate):
    """The law's value ``f`` [N] at penetration ``pen`` [m]: a ``gate``-d point carries it only while it
    penetrates and presses (else 0)."""
    return f if not gate or (pen > 0.0 and f > 0.0) else 0.0


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def deck_increments(phi, dphi, k, dx, dv):
    """The deck's part of point ``k``'s change of position, velocity and slope, (φ_k·Δξ, φ_k·Δξ̇, φ'_k·Δξ),
    for the modal increments ``dx``, ``dv`` (n_m,): the law's exact increments in the lean kernel's updates
    (``lean``) and the full kernel's one-evaluation refinement (``newton._lean_refine``)."""
    ds = 0.0
    dr = 0.0
    dsd = 0.0
    for m in range(dx.size):
        ds += phi[k, m] * dx[m]
        dr += phi[k, m] * dv[m]
        dsd += dphi[k, m] * dx[m]
    return ds, dr, dsd


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _deck(phi, dphi, p, vx, xi, dxi, s, dr, sd, lanes):
    """Add the deck's displacement φ_p·ξ to ``s``, its velocity φ_p·ξ̇ to ``dr`` and the convective
    rate vx φ'_p·ξ to ``sd`` (rows (1, L)) of point ``p``, per lane."""
    if len(lanes) == 1:  # one lane: the mode sums in registers
        a = s[0, 0]
        b = dr[0, 0]
        c = sd[0, 0]
        for m in range(xi.shape[0]):
            a += phi[p, m] * xi[m, 0]
            b += phi[p, m] * dxi[m, 0]
            c += vx * dphi[p, m] * xi[m, 0]
        s[0, 0] = a
        dr[0, 0] = b
        sd[0, 0] = c
        return
    for m in range(xi.shape[0]):  # many lanes: one array per loop, so that they vectorise
        _axpy(phi[p, m], xi, m, s, 0, lanes)
    for m in range(xi.shape[0]):
        _axpy(phi[p, m], dxi, m, dr, 0, lanes)
    for m in range(xi.shape[0]):
        _axpy(vx * dphi[p, m], xi, m, sd, 0, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def contact_forces(xi, dxi, q, dq, modes, vehicles, points, road, unilateral, cache, work, wheel_force, wheel_len,
                   lanes, span):
    """The contact law (module docstring) at the positions of ``cache``: forces F_p [N]
    (``work.force`` (n_cp, L), compression > 0), per-wheel sums ``wheel_force`` and patch lengths
    ``wheel_len`` [m] (n_w, L), ``work.active`` flags, and ``work.used[p]``: the point's force was
    evaluated (else it is 0 in every lane).

    ``cache``: the position slot (``Cache``; its mode shapes and road values are filled
    on first use).  ``lanes``: (0,) for one lane, (0, 0) for many (module docstring).  ``span`` [s]:
    the road rate's secant half-width in time (``road_point``; 0: the cell's slope), always given (a
    default would make every caller that leaves it out compile a variant of its own).
    """
    phi, dphi, have, rv, rr, have_r = cache.phi, cache.dphi, cache.have, cache.rv, cache.rr, cache.have_r
    xs, vxs = cache.x, cache.vx
    idx, force, active, used, scratch = work.idx, work.force, work.active, work.used, work.scratch
    pen, law = work.pen, work.law
    wheel_rows = vehicles.wheel_rows
    r_max = road.r_max
    n_m = xi.shape[0]
    n_d = q.shape[0]
    n_l = _width(lanes, xi)
    zw, dzw = scratch[0], scratch[1]
    s, sd, dr = scratch[2:3], scratch[3:4], scratch[4:5]  # (1, L) rows for 2-D indexing
    b_max = 0.0
    for lane in range(n_l):
        b = 0.0
        for m in range(n_m):
            b += modes.amp[m] * abs(xi[m, lane])
        b_max = max(b_max, b)
    for w in range(wheel_rows.shape[0]):
        for lane in range(n_l):
            zw[lane] = 0.0
            dzw[lane] = 0.0
        for j in range(n_d):
            h = wheel_rows[w, j]
            if h != 0.0:
                for lane in range(n_l):
                    zw[lane] += h * q[j, lane]
                    dzw[lane] += h * dq[j, lane]
        zw_min = zw[0]
        for lane in range(n_l):
            zw_min = min(zw_min, zw[lane])
            wheel_force[w, lane] = 0.0
            wheel_len[w, lane] = 0.0
        first = vehicles.wheel_first[w]
        last = first + vehicles.wheel_count[w]
        envelope = vehicles.wheel_envelope[w]
        for p in range(first, last):
            used[p] = False
            x = xs[p]
            onb = modes.start[points.track[p]] <= x <= modes.end[points.track[p]]
            gate = points.gated[p] or (unilateral and points.stiffness[p] > 0.0)
            bound = r_max - points.gap[p] - zw_min + (b_max if onb else 0.0)  # ≥ the penetration in every lane
            if gate and not envelope and bound <= 0.0:
                for lane in range(n_l):
                    force[p, lane] = 0.0
                    active[p, lane] = False
                    pen[p, lane] = bound
                    law[p, lane] = 0.0
                continue  # no lane can touch the surface here
            if not have_r[p]:
                road_point(x, vxs[p], p, points.line[p], road, idx, rv, rr, lanes, span)
                have_r[p] = True
            if onb and not have[p]:
                shape_point(x, points.track[p], modes, phi[p], dphi[p])
                have[p] = True
            used[p] = True
            if envelope:
                for lane in range(n_l):
                    force[p, lane] = 0.0
                    active[p, lane] = False
                    pen[p, lane] = 0.0
                    law[p, lane] = 0.0
                continue  # the rigid disk's contact point is chosen below, per lane
            # one store per lane loop, so that the compiler vectorises them (aliasing checks)
            for lane in range(n_l):
                s[0, lane] = rv[p, lane]
                sd[0, lane] = rr[p, lane]  # dir·v · r'(x_p)
                dr[0, lane] = 0.0  # ∂u_b/∂t at the fixed point x_p
            if onb:
                _deck(phi, dphi, p, vxs[p], xi, dxi, s, dr, sd, lanes)
            k = points.stiffness[p]
            c = points.damping[p]
            f0 = points.fixed_load[p]
            g = points.gap[p]
            wd = points.width[p]
            for lane in range(n_l):
                pen[p, lane] = s[0, lane] - g - zw[lane]
            for lane in range(n_l):
                law[p, lane] = point_law(k, c, f0, pen[p, lane], sd[0, lane] + dr[0, lane] - dzw[lane], False)
            for lane in range(n_l):
                force[p, lane] = _gated(law[p, lane], pen[p, lane], gate)
            for lane in range(n_l):
                active[p, lane] = not gate or force[p, lane] > 0.0  # a gated point acts iff it presses
            _axpy(1.0, force, p, wheel_force, w, lanes)
            for lane in range(n_l):
                wheel_len[w, lane] += wd if active[p, lane] else 0.0
        if envelope:
            _envelope(w, first, last, xi, dxi, modes, points, cache, zw, dzw, force, wheel_force, active, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _envelope(w, first, last, xi, dxi, modes, points, cache, zw, dzw, force, wheel_force, active, lanes):
    """Rigid-disk wheel ``w``: per lane, only the point of highest surface s_p − g_p acts; its rate
    is the deck velocity + v·e', e' the surface slope along the travel direction clamped to the
    circle's slopes over the point's cell."""
    n_l = _width(lanes, xi)
    phi, dphi, rv, rr = cache.phi, cache.dphi, cache.rv, cache.rr
    n_m = xi.shape[0]
    for lane in range(n_l):
        p_env = -1
        s_env = -1e300
        sd_env = 0.0
        for p in range(first, last):
            s = rv[p, lane]
            sd = rr[p, lane]
            deck_rate = 0.0
            vx = cache.vx[p]
            if modes.start[points.track[p]] <= cache.x[p] <= modes.end[points.track[p]]:
                for m in range(n_m):
                    s += phi[p, m] * xi[m, lane]
                    deck_rate += phi[p, m] * dxi[m, lane]
                    sd += vx * dphi[p, m] * xi[m, lane]
            if s - points.gap[p] > s_env:
                s_env = s - points.gap[p]
                v = points.direction[p] * vx  # the speed, ≥ 0; sd = v × slope along the travel
                sd_env = deck_rate + min(max(sd, v * points.slope_range[p, 0]), v * points.slope_range[p, 1])
                p_env = p
        if p_env >= 0:
            f = point_law(points.stiffness[p_env], points.damping[p_env], points.fixed_load[p_env], s_env - zw[lane],
                          sd_env - dzw[lane], True)
            if f > 0.0:
                force[p_env, lane] = f
                active[p_env, lane] = True
                wheel_force[w, lane] = f


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def accelerations(xi, dxi, q, dq, modes, vehicles, points, road, unilateral, cache, work, ddxi, ddq,
                  wheel_force, wheel_len, lanes):
    """ξ̈ (n_m, L), q̈ (n_d, L) and contact forces for a given state (the right-hand side of Eq. 9)
    at the positions of ``cache``; the road rate is the cell's slope (``span`` 0: RK4, which evaluates
    the law at its stage times)."""
    contact_forces(xi, dxi, q, dq, modes, vehicles, points, road, unilateral, cache, work, wheel_force,
                   wheel_len, lanes, 0.0)
    phi = cache.phi
    force, used, rhs = work.force, work.used, work.rhs
    omega, zeta = modes.omega, modes.zeta
    n_m = xi.shape[0]
    n_d = q.shape[0]
    n_l = _width(lanes, xi)
    for m in range(n_m):
        a = 2.0 * zeta[m] * omega[m]
        b = omega[m] * omega[m]
        for lane in range(n_l):
            ddxi[m, lane] = -a * dxi[m, lane] - b * xi[m, lane]
    _modal_load(-1.0, phi, force, used, cache.x, points.track, modes, ddxi, lanes)
    if n_d == 0:
        return
    for i in range(n_d):
        for lane in range(n_l):
            rhs[i, lane] = vehicles.gravity[i]
    _gemv(-1.0, vehicles.damping, dq, rhs, lanes, False)
    _gemv(-1.0, vehicles.stiffness, q, rhs, lanes, False)
    _gemv(1.0, vehicles.wheel_rows, wheel_force, rhs, lanes, True)
    for i in range(n_d):
        for lane in range(n_l):
            ddq[i, lane] = 0.0
    _gemv(1.0, vehicles.mass_inv, rhs, ddq, lanes, False)


@_internal
def _modal_load(alpha, phi, force, used, x, track, modes, out, lanes):
    """out[m, :] += α Σ_p φ_pm F_p over the used points on the deck."""
    for p in range(force.shape[0]):
        if used[p] and modes.start[track[p]] <= x[p] <= modes.end[track[p]]:
            for m in range(out.shape[0]):
                _axpy(alpha * phi[p, m], force, p, out, m, lanes)


@_internal
def _refresh(cache, motion, row, points):
    """Point positions of half-step ``row`` into slot ``cache``; its shapes and road to be refilled."""
    point_kinematics(motion, row, points, cache.x, cache.vx)
    for p in range(cache.have.size):
        cache.have[p] = False
        cache.have_r[p] = False
