"""Compiled (numba) kernels of the coupled vehicle–bridge equations (paper Eq. 9, modal form).

State: bridge modal coordinates ξ (n_m) and vehicle coordinates q (n_d).

Contact-point kinematics (every point on its own).  Point p belongs to vehicle ``vehicle[p]``
and sits at

    x_p(t) = origin_p + dir_p · s_v(t),      dx_p/dt = dir_p · v_v(t)

where s_v(t) [m] and v_v(t) = ds_v/dt [m/s] ≥ 0 are the travel and speed of its vehicle v
(columns of ``Motion``, given on the half-step time grid, so each vehicle has its own
speed, acceleration, stop time and start), ``origin`` [m] is x_p at s_v = 0 and ``direction``
dir_p = +1 (driving towards +x) or −1 (towards −x).  One vehicle driving +x (a
[`vbikit.solve.Crossing`][vbikit.solve.Crossing]) has s_v = x_front(t), origin_p = −setback_p, dir_p = +1.

The contact law, written once (``contact_forces``, called by every integrator and by the
static start).  With mode-shape rows φ_p, φ'_p = ∂φ/∂x on the point's wheel track
``track[p]``, road elevation r_p on road line ``line[p]`` and the wheel's lowest point
z_w = h_w·q (row ``wheel_rows[wheel[p]]``):

    s_p  = φ_p·ξ + r_p                                   surface under the point
    ṡ_p  = φ_p·ξ̇ + dir_p v (φ'_p·ξ + r'(x_p))            (dir_p v φ'_p·ξ: convective deck rate)
    δ_p  = s_p − g_p − z_w                               penetration (gap g_p ≥ 0)
    F_p  = k_p δ_p + c_p (ṡ_p − ż_w) + f0_p              (compression > 0)
    gated points (disk tires, or all points with loss of contact): F_p = max(0, F_p) if δ_p > 0 else 0
    envelope wheels (rigid disk): only the point of largest s_p − g_p acts, with the surface
    rate along the travel direction clamped to the circle's slopes there (``slope_range``)
    ξ̈ + 2ζω ξ̇ + ω² ξ = −Σ_p φ_pᵀ F_p
    M_v q̈ + C_v q̇ + K_v q = F_G + Σ_w h_wᵀ Σ_{p∈w} F_p

A point on track k is on the deck while start_k ≤ x_p ≤ end_k (the track's own span: 0 … span,
shifted by y tan θ on a skew deck, whose oblique support lines cross each track elsewhere); off
it, φ_p = 0 (the road only).  Nothing in the kernels assumes φ = 0 at the deck ends or a single
span: the mode-shape tables may be any mode set (continuous beams, grillages, skew decks),
tabulated over [start_k, end_k] on each wheel track k.

Several vehicles.  The kernels only see contact points, wheels and vehicle DOFs; a traffic
event is one system whose vehicle matrices are block-diagonal (one block per vehicle), whose
wheels index rows of the stacked DOF vector and whose points carry their vehicle index,
origin and direction.  Wheels of one vehicle must be contiguous in points (``wheel_first``,
``wheel_count``), as for one vehicle.

Argument bundles (NamedTuples of arrays, built by ``vbikit.solve.system``):
  ``Modes``     the bridge's mode set and its tables along the wheel tracks
  ``Vehicles``  vehicle matrices, wheel rows and wheel → point ranges
  ``Points``    per contact point: kinematics, track, road line, tire law
  ``Road``      road stations and elevations of every road line and lane
  ``Motion``    travel s_v and speed v_v of every vehicle on the half-step grid

Lanes.  The state carries a last axis of L *lanes*: L crossings that share everything but the
road (a batch of a study), integrated together.  Everything that does not depend on the road
(positions, mode shapes at the contact points, the step) is computed once for all lanes, and
the per-lane arithmetic runs in contiguous inner loops that the compiler vectorises.  Each
lane's arithmetic is that of a single crossing (L = 1 is ``simulate``).  The argument
``lanes`` selects one of two compiled variants: a 1-tuple = one lane, a compile-time constant,
so that every lane loop disappears (and sums stay in registers); a 2-tuple = many lanes, L
read from the arrays at run time (the form the loop vectoriser handles; its vector loops take
32 doubles at a time, hence the callers' 32-lane calls padded to multiples of 8).  Hot loops
index 2-D arrays directly rather than through row views (measured faster here, ≈ 15 %).

Mode shapes along each wheel track are tabulated on a uniform grid with values and slopes and
evaluated by cubic Hermite interpolation (``vbikit.solve.tabulate``).  Road elevations are
interpolated linearly in the road's stations inside the kernels (station pointers move both
ways, so points may drive towards −x).  Both lazily: a gated point that no lane can bring into
contact (r_max − g_p − min z_w + B ≤ 0, with r_max the highest road elevation and
B = max_lanes Σ_m max|φ_m|·|ξ_m| the largest possible deck displacement) needs neither.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from vbikit.solve.numba_cache import ensure_cache_location


ensure_cache_location()  # before the first @njit(cache=True) below


class Modes(NamedTuple):
    """The bridge's modes: ``omega`` ω_m [rad/s], ``zeta`` ζ_m [-] (n_m,); per track ``start``,
    ``end`` [m] (n_tracks,) (a point on track k with start_k ≤ x ≤ end_k is on the deck); mode-shape
    tables ``values`` φ and ``slopes`` ∂φ/∂x (n_tracks, n_grid, n_m), track k's on the uniform grid
    of spacing ``grid_h`` [m] from x = start_k; ``amp``
    (n_m,) bound on |φ_m| (the lazy-contact test)."""

    omega: np.ndarray
    zeta: np.ndarray
    start: np.ndarray
    end: np.ndarray
    grid_h: float
    values: np.ndarray
    slopes: np.ndarray
    amp: np.ndarray


class Vehicles(NamedTuple):
    """Vehicle matrices (n_d, n_d): ``mass`` M, ``mass_inv`` M⁻¹, ``damping`` C_v, ``stiffness``
    K_v, ``gravity`` F_G (n_d,) [N] (block-diagonal for several vehicles); ``wheel_rows`` h_w
    (n_w, n_d); per wheel ``wheel_first``, ``wheel_count`` (its contact points' index range),
    ``wheel_envelope`` (acts through its highest point only: rigid disk), ``wheel_stiffness``
    [N/m] and ``wheel_damping`` [N·s/m] of its tire at rest (the implicit integrators' nominal
    tire, Σ of its points' k, c in static contact)."""

    mass: np.ndarray
    mass_inv: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    gravity: np.ndarray
    wheel_rows: np.ndarray
    wheel_first: np.ndarray
    wheel_count: np.ndarray
    wheel_envelope: np.ndarray
    wheel_stiffness: np.ndarray
    wheel_damping: np.ndarray


class Points(NamedTuple):
    """Per contact point (n_cp,): kinematics ``origin`` [m], ``direction`` (±1.0), ``vehicle``
    (column of ``Motion``); ``track`` (table of ``Modes``), ``line`` (road line of
    ``Road``, clamped to the lines present); tire law ``stiffness`` k [N/m], ``damping``
    c [N·s/m], ``fixed_load`` f0 [N], ``gap`` g [m], ``gated``; ``wheel`` index; ``width`` [m]
    of patch it stands for; ``slope_range`` (n_cp, 2) tire-surface slopes over its cell
    (envelope wheels)."""

    origin: np.ndarray
    direction: np.ndarray
    vehicle: np.ndarray
    track: np.ndarray
    line: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    fixed_load: np.ndarray
    gap: np.ndarray
    gated: np.ndarray
    wheel: np.ndarray
    width: np.ndarray
    slope_range: np.ndarray


class Road(NamedTuple):
    """Road lines: ``stations`` (n_s,) increasing [m], ``elevations`` (n_lines, n_s, L) [m] per
    lane, ``r_max`` the highest elevation [m]."""

    stations: np.ndarray
    elevations: np.ndarray
    r_max: float


class Motion(NamedTuple):
    """``travel`` s_v [m] and ``speed`` v_v [m/s] (n_half, n_vehicles) on the half-step grid
    (row 2n = t_n)."""

    travel: np.ndarray
    speed: np.ndarray


class Cache(NamedTuple):
    """One position slot: point positions ``x`` [m] and x-rates ``vx`` = dir·v [m/s] (n_cp,); mode
    shapes ``phi``, ``dphi`` (n_cp, n_m) and road ``rv``, ``rr`` (n_cp, L) filled on first use
    (``have``, ``have_r``)."""

    x: np.ndarray
    vx: np.ndarray
    phi: np.ndarray
    dphi: np.ndarray
    have: np.ndarray
    rv: np.ndarray
    rr: np.ndarray
    have_r: np.ndarray


class Work(NamedTuple):
    """Station pointers ``idx`` (n_cp,); outputs ``force`` (n_cp, L), ``active`` (n_cp, L),
    ``used`` (n_cp,); ``scratch`` (5, L); ``rhs`` (n_d, L); per point and lane the penetration
    ``pen`` δ [m] and the ungated law ``law`` k δ + c δ̇ + f0 [N] (for a point left out by the lazy
    test, ``pen`` holds its bound r_max − g − min z_w + B ≥ δ and ``law`` 0; 0 on rigid disks)."""

    idx: np.ndarray
    force: np.ndarray
    active: np.ndarray
    used: np.ndarray
    scratch: np.ndarray
    rhs: np.ndarray
    pen: np.ndarray
    law: np.ndarray


#: the kernels' compiled helpers: called only from other kernels, so numba builds them without
#: the wrappers that make a function callable from Python (compile time only, no run time)
_internal = njit(cache=True, fastmath=True, error_model="numpy", no_cpython_wrapper=True, no_cfunc_wrapper=True)


def new_cache(n_cp: int, n_m: int, n_l: int) -> Cache:
    """An empty position slot."""
    return Cache(np.zeros(n_cp), np.zeros(n_cp), np.zeros((n_cp, n_m)), np.zeros((n_cp, n_m)),
                 np.zeros(n_cp, np.bool_), np.zeros((n_cp, n_l)), np.zeros((n_cp, n_l)), np.zeros(n_cp, np.bool_))


def new_work(n_cp: int, n_d: int, n_l: int) -> Work:
    """Work space of ``contact_forces``."""
    return _work(n_cp, n_d, n_l)


@njit(cache=True)
def _work(n_cp, n_d, n_l):
    """Work space of ``contact_forces`` (``new_work``; also built inside the kernels)."""
    return Work(np.full(n_cp, -1, dtype=np.int64), np.zeros((n_cp, n_l)), np.zeros((n_cp, n_l), dtype=np.bool_),
                np.zeros(n_cp, dtype=np.bool_), np.zeros((5, n_l)), np.zeros((n_d, n_l)), np.zeros((n_cp, n_l)),
                np.zeros((n_cp, n_l)))


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def shape_point(x, track, modes, phi_row, dphi_row):
    """φ(x) and ∂φ/∂x(x) of one point on tabulated track ``track`` of ``modes`` (cubic Hermite)."""
    V, S, grid_h = modes.values, modes.slopes, modes.grid_h
    n_grid = V.shape[1]
    u = (x - modes.start[track]) / grid_h
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
    for m in range(V.shape[2]):
        a0 = V[track, i, m]
        a1 = V[track, i + 1, m]
        b0 = S[track, i, m]
        b1 = S[track, i + 1, m]
        phi_row[m] = h00 * a0 + h10 * b0 + h01 * a1 + h11 * b1
        dphi_row[m] = d00 * a0 + d10 * b0 + d01 * a1 + d11 * b1


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


@njit(cache=True, inline="always")
def _width(lanes, a):
    """The lane count L: a compile-time 1 when ``lanes`` is a 1-tuple (one crossing: every lane
    loop disappears), else the last dimension of ``a`` (a runtime count, which the compiler's
    loop vectoriser handles best; widths that are multiples of 32 fill its vector loops)."""
    return 1 if len(lanes) == 1 else a.shape[-1]


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def road_point(x, vx, p, line, road, idx, rv, rr, lanes):
    """Road elevation ``rv[p, :]`` [m] and rate ``rr[p, :]`` = vx·dr/dx [m/s] of every lane at
    position ``x`` [m] of point ``p`` on road line ``line`` (linear interpolation; ``idx[p]`` is
    the point's station pointer, −1 before its first use; it moves either way).  On a station the
    slope is that of the cell the point moves into: the one on its +x side, or on its −x side
    when vx < 0 (a vehicle driving −x sees the mirror of what one driving +x sees)."""
    n_l = _width(lanes, rv)
    stations = road.stations
    n_s = stations.size
    i = idx[p]
    if i < 0:
        i = max(0, min(n_s - 2, np.searchsorted(stations, x, side="right") - 1))
    while i < n_s - 2 and stations[i + 1] <= x:
        i += 1
    while i > 0 and stations[i] > x:
        i -= 1
    idx[p] = i
    if vx < 0.0 and i > 0 and stations[i] == x:  # on a station, driving −x: the cell behind it
        i -= 1
    z = road.elevations[min(line, road.elevations.shape[0] - 1)]
    dx = x - stations[i]
    inv = 1.0 / (stations[i + 1] - stations[i])
    for lane in range(n_l):
        slope = (z[i + 1, lane] - z[i, lane]) * inv
        rv[p, lane] = z[i, lane] + slope * dx
        rr[p, lane] = slope * vx


@njit(cache=True, fastmath=True, error_model="numpy")
def road_at(x, vx, points, road, idx, rv, rr, lanes):
    """Road elevation and rate (n_cp, L) under every contact point at positions ``x`` [m] moving
    at x-rates ``vx`` [m/s] (``idx``: the points' station pointers, see ``road_point``)."""
    for p in range(x.size):
        road_point(x[p], vx[p], p, points.line[p], road, idx, rv, rr, lanes)


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
                   lanes):
    """The contact law (module docstring) at the positions of ``cache``: forces F_p [N]
    (``work.force`` (n_cp, L), compression > 0), per-wheel sums ``wheel_force`` and patch lengths
    ``wheel_len`` [m] (n_w, L), ``work.active`` flags, and ``work.used[p]``: the point's force was
    evaluated (else it is 0 in every lane).

    ``cache``: the position slot (``Cache``; its mode shapes and road values are filled
    on first use).  ``lanes``: (0,) for one lane, (0, 0) for many (module docstring).
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
                road_point(x, vxs[p], p, points.line[p], road, idx, rv, rr, lanes)
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
    at the positions of ``cache``."""
    contact_forces(xi, dxi, q, dq, modes, vehicles, points, road, unilateral, cache, work, wheel_force,
                   wheel_len, lanes)
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


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _modal_load(alpha, phi, force, used, x, track, modes, out, lanes):
    """out[m, :] += α Σ_p φ_pm F_p over the used points on the deck."""
    for p in range(force.shape[0]):
        if used[p] and modes.start[track[p]] <= x[p] <= modes.end[track[p]]:
            for m in range(out.shape[0]):
                _axpy(alpha * phi[p, m], force, p, out, m, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _gemv(alpha, a, x, y, lanes, transpose):
    """y += α·A·x (or α·Aᵀ·x) for every lane (x, y: (·, L)); zero entries of A are skipped.  The
    one-lane loop is inlined into the caller (small vehicle matrices, every step: a call costs
    more than the product); the many-lane loops are one compiled function, ``_gemv_lanes``."""
    if len(lanes) == 1:  # one lane: accumulate in a register
        n_i = a.shape[1] if transpose else a.shape[0]
        n_j = a.shape[0] if transpose else a.shape[1]
        for i in range(n_i):
            acc = y[i, 0]
            for j in range(n_j):
                aij = a[j, i] if transpose else a[i, j]
                if aij != 0.0:
                    acc += alpha * aij * x[j, 0]
            y[i, 0] = acc
    else:
        _gemv_lanes(alpha, a, x, y, lanes, transpose)


@_internal
def _gemv_lanes(alpha, a, x, y, lanes, transpose):
    """``_gemv`` for many lanes: the lanes innermost, vectorised."""
    n_i = a.shape[1] if transpose else a.shape[0]
    n_j = a.shape[0] if transpose else a.shape[1]
    for i in range(n_i):
        for j in range(n_j):
            aij = a[j, i] if transpose else a[i, j]
            if aij != 0.0:
                _axpy(alpha * aij, x, j, y, i, lanes)


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _axpy(a, x, i, y, k, lanes):
    """y[k, :] += a·x[i, :] over the lanes (2-D indexing rather than row views)."""
    for lane in range(_width(lanes, y)):
        y[k, lane] += a * x[i, lane]


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _stage(stage, h, tau, x0, v0, a_prev2, a_prev, sx, sv, lanes):
    """RK4 stage state: sx = x0 + τ(v0 + h·a_{stage−2}) (x0 + h·v0 at stage 1), sv = v0 + τ·a_{stage−1}."""
    n_l = _width(lanes, x0)
    for i in range(x0.shape[0]):
        if stage == 1:
            for lane in range(n_l):
                sx[i, lane] = x0[i, lane] + h * v0[i, lane]
        else:
            for lane in range(n_l):
                sx[i, lane] = x0[i, lane] + tau * (v0[i, lane] + h * a_prev2[i, lane])
        for lane in range(n_l):
            sv[i, lane] = v0[i, lane] + tau * a_prev[i, lane]


@njit(cache=True, fastmath=True, error_model="numpy", inline="always")
def _update(dt, x0, v0, a, x1, v1, lanes):
    """RK4 step for ẍ = a: x1 = x0 + dt(v0 + dt/6 (a1 + a2 + a3)), v1 = v0 + dt/6 (a1 + 2a2 + 2a3 + a4)."""
    n_l = _width(lanes, x0)
    for i in range(x0.shape[0]):
        for lane in range(n_l):
            x1[i, lane] = x0[i, lane] + dt * (v0[i, lane] + dt / 6.0 * (a[0, i, lane] + a[1, i, lane] + a[2, i, lane]))
        for lane in range(n_l):
            v1[i, lane] = v0[i, lane] + dt / 6.0 * (a[0, i, lane] + 2 * a[1, i, lane] + 2 * a[2, i, lane]
                                                    + a[3, i, lane])


@_internal
def _store(out, n, state, lanes):
    """out[lane, n, i] = state[i, lane]: a lane-major output row from the lane-minor state."""
    n_l = _width(lanes, state)
    for i in range(state.shape[0]):
        for lane in range(n_l):
            out[lane, n, i] = state[i, lane]


@_internal
def _fetch(src, n, state, lanes):
    """state[i, lane] = src[lane, n, i]: the inverse of ``_store`` (explicit loops: slice
    assignments would compile numba's shape-mismatch error path, seconds of compile time)."""
    n_l = _width(lanes, state)
    for i in range(state.shape[0]):
        for lane in range(n_l):
            state[i, lane] = src[lane, n, i]


@_internal
def _copy(src, dst, lanes):
    """dst[i, :] = src[i, :] (explicit loops, see ``_fetch``)."""
    n_l = _width(lanes, src)
    for i in range(src.shape[0]):
        for lane in range(n_l):
            dst[i, lane] = src[i, lane]


@_internal
def _keep(out, n, stride, state, lanes):
    """Store the state of step ``n`` in row n / stride when ``stride`` divides n (thinned histories)."""
    if n % stride == 0:
        _store(out, n // stride, state, lanes)


@_internal
def _keep_step(xi, dxi, ddxi, q, dq, ddq, wheel_force, wheel_len, n, stride, x, v, a, y, w, b, wf, wl, lanes):
    """``_keep`` of every output of step ``n`` (one call a step)."""
    _keep(xi, n, stride, x, lanes); _keep(dxi, n, stride, v, lanes); _keep(ddxi, n, stride, a, lanes)
    _keep(q, n, stride, y, lanes); _keep(dq, n, stride, w, lanes); _keep(ddq, n, stride, b, lanes)
    _keep(wheel_force, n, stride, wf, lanes); _keep(wheel_len, n, stride, wl, lanes)


@_internal
def _refresh(cache, motion, row, points):
    """Point positions of half-step ``row`` into slot ``cache``; its shapes and road to be refilled."""
    point_kinematics(motion, row, points, cache.x, cache.vx)
    for p in range(cache.have.size):
        cache.have[p] = False
        cache.have_r[p] = False


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def rk4(dt, motion, modes, vehicles, points, road, unilateral, xi, dxi, q, dq, ddxi, ddq, wheel_force, wheel_len,
        lanes, stride=1):
    """Classical 4th-order Runge–Kutta (the paper's integrator) on the first-order form of Eq. 9.

    ``motion`` is given at half steps (row 2n = t_n).  The output arrays (L, n_steps + 1, ·)
    are lane-major (each lane's history is contiguous) and hold the initial state at [:, 0] on
    entry; the state itself is kept lane-minor, (·, L), so that the lane loops vectorise.
    ``lanes``: (0,) for one lane, (0, 0) for many (module docstring).  ``stride``: keep every
    stride-th step in the outputs (their second axis has n_steps / stride + 1 rows;
    ``motion`` covers all n_steps).
    """
    n_l = 1 if len(lanes) == 1 else xi.shape[0]
    n_steps = (motion.travel.shape[0] - 1) // 2
    n_m = xi.shape[2]
    n_d = q.shape[2]
    n_cp = points.origin.size
    n_w = wheel_force.shape[2]
    ax = np.zeros((4, n_m, n_l))
    aq = np.zeros((4, n_d, n_l))
    x0 = np.empty((n_m, n_l)); v0 = np.empty((n_m, n_l)); y0 = np.empty((n_d, n_l)); w0 = np.empty((n_d, n_l))
    x1 = np.empty((n_m, n_l)); v1 = np.empty((n_m, n_l)); y1 = np.empty((n_d, n_l)); w1 = np.empty((n_d, n_l))
    _fetch(xi, 0, x0, lanes); _fetch(dxi, 0, v0, lanes); _fetch(q, 0, y0, lanes); _fetch(dq, 0, w0, lanes)
    sx = np.zeros((n_m, n_l)); sv = np.zeros((n_m, n_l)); sq = np.zeros((n_d, n_l)); sw = np.zeros((n_d, n_l))
    work = _work(n_cp, n_d, n_l)
    wf = np.zeros((n_w, n_l))
    wl = np.zeros((n_w, n_l))
    # the three position slots (start, middle, end of a step), built once
    caches = (_slot(n_cp, n_m, n_l), _slot(n_cp, n_m, n_l), _slot(n_cp, n_m, n_l))
    stage_x = (ax[0], ax[1], ax[2], ax[3])
    stage_q = (aq[0], aq[1], aq[2], aq[3])
    cur = 0
    _refresh(caches[0], motion, 0, points)
    h = 0.5 * dt
    for n in range(n_steps + 1):
        accelerations(x0, v0, y0, w0, modes, vehicles, points, road, unilateral, caches[cur], work, stage_x[0],
                      stage_q[0], wf, wl, lanes)
        _keep(ddxi, n, stride, stage_x[0], lanes); _keep(ddq, n, stride, stage_q[0], lanes)
        _keep(wheel_force, n, stride, wf, lanes); _keep(wheel_len, n, stride, wl, lanes)
        if n == n_steps:
            break
        mid = (cur + 1) % 3
        end = (cur + 2) % 3
        _refresh(caches[mid], motion, 2 * n + 1, points)
        _refresh(caches[end], motion, 2 * n + 2, points)
        # stages 2-4: state = start + tau * (velocity + h * previous-but-one stage acceleration)
        for stage in range(1, 4):
            tau = h if stage < 3 else dt
            slot = mid if stage < 3 else end
            prev = stage - 1
            _stage(stage, h, tau, x0, v0, stage_x[max(prev - 1, 0)], stage_x[prev], sx, sv, lanes)
            _stage(stage, h, tau, y0, w0, stage_q[max(prev - 1, 0)], stage_q[prev], sq, sw, lanes)
            accelerations(sx, sv, sq, sw, modes, vehicles, points, road, unilateral, caches[slot], work,
                          stage_x[stage], stage_q[stage], wf, wl, lanes)
        _update(dt, x0, v0, ax, x1, v1, lanes)
        _update(dt, y0, w0, aq, y1, w1, lanes)
        x0, x1 = x1, x0
        v0, v1 = v1, v0
        y0, y1 = y1, y0
        w0, w1 = w1, w0
        _keep(xi, n + 1, stride, x0, lanes); _keep(dxi, n + 1, stride, v0, lanes)
        _keep(q, n + 1, stride, y0, lanes); _keep(dq, n + 1, stride, w0, lanes)
        cur = end


@_internal
def _slot(n_cp, n_m, n_l):
    return Cache(np.zeros(n_cp), np.zeros(n_cp), np.zeros((n_cp, n_m)), np.zeros((n_cp, n_m)),
                 np.zeros(n_cp, dtype=np.bool_), np.zeros((n_cp, n_l)), np.zeros((n_cp, n_l)),
                 np.zeros(n_cp, dtype=np.bool_))


@njit(cache=True, fastmath=True, error_model="numpy")
def assemble(x, vx, r, rdot, modes, vehicles, points, phi, dphi, have, active, mass, damp, stiff, load):
    """Coupled system matrices of Eq. 9 at one instant, M ü + C u̇ + K u = F with u = [ξ; q], for
    the contact points at positions ``x`` [m] with x-rates ``vx`` [m/s] flagged ``active``: the
    linearisation of the contact law (module docstring) about contact, where F_p = k δ + c δ̇ +
    f0 (road ``r`` [m] and its rate ``rdot`` [m/s] under each point given)."""
    omega, zeta = modes.omega, modes.zeta
    m_v, c_v, k_v, f_g, wheel_rows = vehicles.mass, vehicles.damping, vehicles.stiffness, vehicles.gravity, \
        vehicles.wheel_rows
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
    for p in range(points.stiffness.size):
        if not active[p]:
            continue
        k = points.stiffness[p]
        c = points.damping[p]
        ext = k * (r[p] - points.gap[p]) + c * rdot[p] + points.fixed_load[p]
        h = wheel_rows[points.wheel[p]]
        for i in range(n_d):
            load[n_m + i] += h[i] * ext
            for j in range(n_d):
                stiff[n_m + i, n_m + j] += k * h[i] * h[j]
                damp[n_m + i, n_m + j] += c * h[i] * h[j]
        if not modes.start[points.track[p]] <= x[p] <= modes.end[points.track[p]]:
            continue
        if not have[p]:
            shape_point(x[p], points.track[p], modes, phi[p], dphi[p])
            have[p] = True
        f = phi[p]
        g = dphi[p]
        vel = vx[p]
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


@njit(cache=True, fastmath=True, error_model="numpy")
def static_modal_history(travel, points, loads, modes):
    """Σ_p φ(x_p(t)) P_p (n_t, n_m) for downward point loads P_p [N] at x_p = origin_p + dir_p·s_v(t),
    ``travel`` (n_t, n_vehicles) [m] (tabulated shapes, as the solver); ξ_st = −that / ω²."""
    n_m = modes.values.shape[2]
    out = np.zeros((travel.shape[0], n_m))
    phi = np.zeros(n_m)
    dphi = np.zeros(n_m)
    for t in range(travel.shape[0]):
        for p in range(points.origin.size):
            if loads[p] == 0.0:
                continue
            x = points.origin[p] + points.direction[p] * travel[t, points.vehicle[p]]
            if modes.start[points.track[p]] <= x <= modes.end[points.track[p]]:
                shape_point(x, points.track[p], modes, phi, dphi)
                for m in range(n_m):
                    out[t, m] += phi[m] * loads[p]
    return out


class ModalStep(NamedTuple):
    """One step h of every mode ξ̈ + 2ζωξ̇ + ω²ξ = p as a linear map of its start state and of the
    modal load at both ends (load linear in time over the step):
    ξ_{n+1} = a11 ξ_n + a12 ξ̇_n + b1 p_n + c1 p_{n+1},  ξ̇_{n+1} = a21 ξ_n + a22 ξ̇_n + b2 p_n + c2 p_{n+1}
    (each (n_m,); ``vbikit.solve.modal_step``: exact, or Newmark's average acceleration)."""

    a11: np.ndarray
    a12: np.ndarray
    a21: np.ndarray
    a22: np.ndarray
    b1: np.ndarray
    b2: np.ndarray
    c1: np.ndarray
    c2: np.ndarray


class VehicleStep(NamedTuple):
    """One step h of the vehicles with their nominal tires (k_w, c_w per wheel) on the contact
    surface, as a linear map of the stacked state z = (q, q̇) (2n_d) and of the wheel loads G at
    both ends of the step (linear in time over it):
    z_{n+1} = ``transition`` z_n + ``load0`` G_n + ``load1`` G_{n+1} + ``constant`` (gravity);
    ``c_hat`` Ĉ = C_v + Hᵀ diag(c_w) H and ``k_hat`` K̂ = K_v + Hᵀ diag(k_w) H give q̈ from the
    equation of motion (``vbikit.solve.modal_step``: exact, or Newmark's average acceleration).
    For the coupled solve, with the end loads G = F + K_z z_{n+1} written through the wheel forces
    F: ``settle`` P = (I − L1 K_z)⁻¹ (2n_d, 2n_d), ``response`` P L1 (2n_d, n_w), and the wheels'
    displacement and velocity per unit wheel force ``wheel_q`` = H (P L1)[:n_d], ``wheel_v`` =
    H (P L1)[n_d:] (n_w, n_w)."""

    transition: np.ndarray
    load0: np.ndarray
    load1: np.ndarray
    constant: np.ndarray
    c_hat: np.ndarray
    k_hat: np.ndarray
    settle: np.ndarray
    response: np.ndarray
    wheel_q: np.ndarray
    wheel_v: np.ndarray


@_internal
def _combine(a, x, b, y, c, z, out, lanes):
    """out[m, :] = a_m x[m, :] + b_m y[m, :] + c_m z[m, :] (per-row coefficients)."""
    n_l = _width(lanes, x)
    for m in range(x.shape[0]):
        am = a[m]
        bm = b[m]
        cm = c[m]
        for lane in range(n_l):
            out[m, lane] = am * x[m, lane] + bm * y[m, lane] + cm * z[m, lane]


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


#: quasi-Newton updates (the Jacobian through the vehicles only) before the full Newton updates: for
#: road vehicles on bridges the deck's part of B is small (|B_deck| ~ 1e-5), so these usually settle
#: a step at a fraction of a full Newton step's cost, with a factorisation that depends only on the
#: active set (kept across steps); the full Newton steps settle the rest
QUASI_ITERATIONS = 4
#: Newton iterations after which the implicit kernel halves its updates (a contact set that would cycle)
RELAX_AFTER = 8


@_internal
def _lu_factor(a, n, piv):
    """In-place LU factorisation with partial pivoting of a[:n, :n] (row swaps in ``piv``)."""
    for j in range(n):
        best = j
        big = abs(a[j, j])
        for i in range(j + 1, n):
            if abs(a[i, j]) > big:
                big = abs(a[i, j])
                best = i
        piv[j] = best
        if best != j:
            for c in range(n):
                t = a[j, c]
                a[j, c] = a[best, c]
                a[best, c] = t
        d = a[j, j]
        for i in range(j + 1, n):
            lij = a[i, j] / d
            a[i, j] = lij
            if lij != 0.0:
                for c in range(j + 1, n):
                    a[i, c] -= lij * a[j, c]


@_internal
def _lu_solve(a, n, piv, b):
    """Solve a x = b in place in b[:n] with the factors of ``_lu_factor``."""
    for j in range(n):
        k = piv[j]
        if k != j:
            t = b[j]
            b[j] = b[k]
            b[k] = t
    for i in range(n):
        acc = b[i]
        for j in range(i):
            acc -= a[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, n):
            acc -= a[i, j] * b[j]
        b[i] = acc / a[i, i]


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
def _vehicle_factors(used, active, lane, points, vstep, ksum, csum, held, veh, veh_piv):
    """Factorise V = I + S_A U_A (n_w × n_w, row w: δ_ww' + K_w wheel_q[w, w'] + C_w wheel_v[w, w'], with
    K_w, C_w the sums of the active points' k and c on wheel w in lane ``lane``) into ``veh``,
    ``veh_piv`` — unless the factors held are those of the same sums (``held``: K (n_w), C (n_w), a
    valid flag).  V changes only with the active set, so its factors are kept across iterations and
    steps (the step map ``vstep`` is that of the whole run)."""
    n_w = veh.shape[0]
    for w in range(n_w):
        ksum[w] = 0.0
        csum[w] = 0.0
    for k in range(active.shape[0]):
        if used[k] and active[k, lane]:
            ksum[points.wheel[k]] += points.stiffness[k]
            csum[points.wheel[k]] += points.damping[k]
    if held[2 * n_w] != 0.0:
        same = True
        for w in range(n_w):
            if ksum[w] != held[w] or csum[w] != held[n_w + w]:
                same = False
                break
        if same:
            return
    wq, wv = vstep.wheel_q, vstep.wheel_v
    for w in range(n_w):
        for w2 in range(n_w):
            veh[w, w2] = (1.0 if w == w2 else 0.0) + ksum[w] * wq[w, w2] + csum[w] * wv[w, w2]
        held[w] = ksum[w]
        held[n_w + w] = csum[w]
    held[2 * n_w] = 1.0
    _lu_factor(veh, n_w, veh_piv)


@_internal
def _vehicle_newton(f, force, used, active, lane0, lane1, lane_err, tol, points, vstep, fw, ksum, csum, held, veh,
                    veh_piv, bq, bv, t):
    """One quasi-Newton update of the point forces ``f[:, lane]`` of every unconverged lane
    (``lane_err`` > ``tol``) in ``lane0`` … ``lane1`` − 1, lanes that share the active set A of lane
    ``lane0``, with the Jacobian through the vehicles only: (I + U_A S_A) F_A = law_A(F) + U_A S_A F,
    F = 0 off A, with u_i = k_i wheel_q[w_i] + c_i wheel_v[w_i] (U: ∂F_i/∂F_w, S: sum per wheel).  By
    Woodbury's identity it is the n_w-square system (I + S_A U_A) t = S_A b, whose matrix needs only
    each wheel's sums of active k and c (``_vehicle_factors``, kept while they stay the same):
    O(points + wheels²) per lane, the lanes innermost.  On return ``bq``, ``bv`` (n_w, L) hold each
    wheel's change of −z_w and −ż_w by the update (the vehicles' part of the change of its points'
    penetration and rate)."""
    n_cp = f.shape[0]
    n_w = veh.shape[0]
    wq, wv = vstep.wheel_q, vstep.wheel_v
    _vehicle_factors(used, active, lane0, points, vstep, ksum, csum, held, veh, veh_piv)
    for w in range(n_w):
        for lane in range(lane0, lane1):
            bq[w, lane] = 0.0
            bv[w, lane] = 0.0
        for w2 in range(n_w):
            q = wq[w, w2]
            v = wv[w, w2]
            for lane in range(lane0, lane1):
                bq[w, lane] += q * fw[w2, lane]
                bv[w, lane] += v * fw[w2, lane]
        for lane in range(lane0, lane1):  # S_A b = Σ_i∈A∩w (F_i + k_i bq + c_i bv)
            t[w, lane] = ksum[w] * bq[w, lane] + csum[w] * bv[w, lane]
    for k in range(n_cp):
        if used[k] and active[k, lane0]:
            w = points.wheel[k]
            for lane in range(lane0, lane1):
                t[w, lane] += force[k, lane]
    for j in range(n_w):  # forward and back substitution with the factors of V, every lane at once
        kp = veh_piv[j]
        if kp != j:
            for lane in range(lane0, lane1):
                tmp = t[j, lane]
                t[j, lane] = t[kp, lane]
                t[kp, lane] = tmp
    for i in range(n_w):
        for j in range(i):
            a = veh[i, j]
            for lane in range(lane0, lane1):
                t[i, lane] -= a * t[j, lane]
    for i in range(n_w - 1, -1, -1):
        for j in range(i + 1, n_w):
            a = veh[i, j]
            for lane in range(lane0, lane1):
                t[i, lane] -= a * t[j, lane]
        inv = 1.0 / veh[i, i]
        for lane in range(lane0, lane1):
            t[i, lane] *= inv
    for w in range(n_w):  # bq, bv ← b's vehicle terms minus U t's, per wheel
        for w2 in range(n_w):
            q = wq[w, w2]
            v = wv[w, w2]
            for lane in range(lane0, lane1):
                bq[w, lane] -= q * t[w2, lane]
                bv[w, lane] -= v * t[w2, lane]
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
    """Settle lane ``lane`` of the one-evaluation step without another contact-law evaluation: returns
    True when its iterate ``f`` holds the law to ``tol`` (``lane_err[lane]`` set to 0), False when a
    contact would open or close (the step then iterates with full evaluations).

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
    for _ in range(LEAN_CORRECTIONS):
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
                    return False
                continue
            ds = 0.0
            dr = 0.0
            dsd = 0.0
            if onb[k]:
                for m in range(n_m):
                    ds += phi[k, m] * dxi[m]
                    dr += phi[k, m] * dvi[m]
                    dsd += dphi[k, m] * dxi[m]
            dpen = ds + bq[w, lane]
            pen[k, lane] += dpen
            law[k, lane] += points.stiffness[k] * dpen + points.damping[k] * (dr + cache.vx[k] * dsd + bv[w, lane])
            fk = _gated(law[k, lane], pen[k, lane], gated[k])
            if (not gated[k] or fk > 0.0) != active[k, lane]:
                return False  # a contact opens or closes: the full iteration decides
            force[k, lane] = fk
            err = max(err, abs(fk - f[k, lane]))
        lane_err[lane] = err
        if err <= tol:
            lane_err[lane] = 0.0
            return True
        for k in range(n_cp):
            f_old[k, lane] = f[k, lane]
        for w in range(n_w):
            fw[w, lane] = 0.0
        for k in range(n_cp):
            fw[points.wheel[k], lane] += f[k, lane]
        _vehicle_newton(f, force, used, active, lane, lane + 1, lane_err, tol, points, vstep, fw, ksum, csum,
                        veh_held, veh, veh_piv, bq, bv, t)
    return False


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
    na = 0
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


@njit(cache=True, fastmath=True, error_model="numpy", nogil=True)
def implicit(dt, motion, modes, vehicles, points, road, unilateral, step, vstep, xi, dxi, q, dq, ddxi, ddq,
             wheel_force, wheel_len, tol_force, max_iterations, lanes, stride=1):
    """Partitioned implicit step: every mode by its transition ``step`` (``ModalStep``, the
    modal load linear over the step), the vehicles by theirs (``VehicleStep``, the wheel
    loads linear over the step), coupled through the contact forces at the end of the step.

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
    held at zero penetration (``TOUCH_STIFFNESS``).  Should the contact set cycle, updates are
    halved after ``RELAX_AFTER`` full Newton iterations.  The step keeps the iterate's forces.

    Same array conventions as ``rk4`` (lanes and ``stride`` too).  Returns the number of steps that did
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
    z0 = np.empty((2 * n_d, n_l)); z1 = np.empty((2 * n_d, n_l)); zf = np.zeros((2 * n_d, n_l))
    zb = np.zeros((2 * n_d, n_l))
    a1 = np.zeros((n_d, n_l))
    _fetch(xi, 0, x0, lanes); _fetch(dxi, 0, v0, lanes); _fetch(q, 0, z0[:n_d], lanes); _fetch(dq, 0, z0[n_d:], lanes)
    xf = np.zeros((n_m, n_l)); vf = np.zeros((n_m, n_l))  # free deck response (load p_{n+1} = 0)
    p0 = np.zeros((n_m, n_l)); p = np.zeros((n_m, n_l))
    g0 = np.zeros((n_w, n_l)); g = np.zeros((n_w, n_l))
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
    ksum = np.zeros(n_w); csum = np.zeros(n_w); veh = np.zeros((n_w, n_w))
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
    _refresh(cache, motion, 0, points)
    y0, w0 = z0[:n_d], z0[n_d:]
    contact_forces(x0, v0, y0, w0, modes, vehicles, points, road, unilateral, cache, work, wf, wl, lanes)
    _modal_load(-1.0, cache.phi, force, work.used, cache.x, points.track, modes, p0, lanes)
    _tire_load(vehicles, wf, y0, w0, g0, lanes)
    _vehicle_acceleration(vehicles, vstep, z0, g0, work.rhs, a1, lanes)
    _modal_acceleration(omega, zeta, x0, v0, p0, acc, lanes)
    _store(ddxi, 0, acc, lanes); _store(ddq, 0, a1, lanes)
    _store(wheel_force, 0, wf, lanes); _store(wheel_len, 0, wl, lanes)
    for k in range(n_cp):
        for lane in range(n_l):
            f0[k, lane] = force[k, lane] if work.used[k] else 0.0
            fm[k, lane] = f0[k, lane]
    unsettled = 0
    evaluations = 0
    y1, w1 = z1[:n_d], z1[n_d:]
    for n in range(n_steps):
        _refresh(cache, motion, 2 * n + 2, points)
        for k in range(n_cp):
            onb[k] = modes.start[points.track[k]] <= cache.x[k] <= modes.end[points.track[k]]
        # free responses: deck with p_{n+1} = 0, vehicles with F_{n+1} = 0
        _combine(step.a11, x0, step.a12, v0, step.b1, p0, xf, lanes)
        _combine(step.a21, x0, step.a22, v0, step.b2, p0, vf, lanes)
        for i in range(2 * n_d):
            for lane in range(n_l):
                zf[i, lane] = vstep.constant[i]
                zb[i, lane] = 0.0
        _gemv(1.0, vstep.transition, z0, zf, lanes, False)
        _gemv(1.0, vstep.load0, g0, zf, lanes, False)
        _gemv(1.0, vstep.settle, zf, zb, lanes, False)
        held_state[0] = -1  # new positions: no full Jacobian to reuse
        # first guess: linear extrapolation of the forces
        for k in range(n_cp):
            for lane in range(n_l):
                f[k, lane] = 2.0 * f0[k, lane] - fm[k, lane]
                touch[k, lane] = False
        converged = False
        for it in range(max_iterations):
            evaluations += 1
            _state_of(f, onb, cache, points, modes, vehicles, step, vstep, xf, vf, zb, p, fw, x1, v1, z1, lanes)
            contact_forces(x1, v1, y1, w1, modes, vehicles, points, road, unilateral, cache, work, wf, wl, lanes)
            if _residuals(f, force, work.used, touch, lane_err, x1, v1, y1, w1, cache, points, vehicles, onb,
                          tol_force) <= tol_force:
                converged = True
                break
            if it >= QUASI_ITERATIONS:
                blend = 0.5 if it >= QUASI_ITERATIONS + RELAX_AFTER else 1.0
                for lane in range(n_l):  # one full Newton update per unconverged lane (the rare path)
                    if lane_err[lane] > tol_force:
                        _full_newton(f, force, work.used, work.active, lane, blend, touch, gated, x1, v1, y1, w1,
                                     cache, points, vehicles, onb, step, vstep, p, fw, e, u, mat, piv, red, red_piv,
                                     rhs, t, act, held, held_k, held_c, row_k, row_c, held_state)
                continue
            if it == 0 and lean:
                _copy(f, f_old, lanes)
            if n_l > 1 and _same_active_set(work.used, work.active):
                # every lane has the same contact set (the common case of a batch): one update for all
                _vehicle_newton(f, force, work.used, work.active, 0, n_l, lane_err, tol_force, points, vstep, fw,
                                ksum, csum, veh_held, veh, veh_piv, bq_l, bv_l, t_l)
            else:
                for lane in range(n_l):  # one update per unconverged lane
                    if lane_err[lane] > tol_force:
                        _vehicle_newton(f, force, work.used, work.active, lane, lane + 1, lane_err, tol_force, points,
                                        vstep, fw, ksum, csum, veh_held, veh, veh_piv, bq_l, bv_l, t_l)
            if it == 0 and lean:  # the one-evaluation step: settle each lane by exact increments
                settled = True
                for lane in range(n_l):
                    if lane_err[lane] > tol_force and not _lean_refine(
                            f, f_old, force, work, lane, tol_force, gated, points, cache, onb, step, vstep, fw, ksum,
                            csum, veh_held, veh, veh_piv, bq_l, bv_l, t_l, lane_err, modes.amp, dp, dxi_l, dvi_l):
                        settled = False
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
        _modal_acceleration(omega, zeta, x1, v1, p, acc, lanes)
        _vehicle_acceleration(vehicles, vstep, z1, g, work.rhs, a1, lanes)
        _keep_step(xi, dxi, ddxi, q, dq, ddq, wheel_force, wheel_len, n + 1, stride, x1, v1, acc, y1, w1, a1, wf, wl,
                   lanes)
        x0, x1 = x1, x0
        v0, v1 = v1, v0
        z0, z1 = z1, z0
        y1, w1 = z1[:n_d], z1[n_d:]
        p0, p = p, p0
        g0, g = g, g0
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
