"""The quadratic hold's past modal load at the deck's ends. (``vbikit.solve.kernels``: the equations and
conventions; ``vbikit.solve.modal_step.quadratic_hold``: the hold.)

The exact integrator holds each mode's load p = −Σ_k φ_k F_k quadratic over a step, through p_{n−1}, p_n,
p_{n+1}.  A point k that comes onto its track or leaves it within t_{n−1} … t_{n+1} puts a kink (mode
shapes vanishing at the end) or a jump (shapes that do not) into its share q_k = −φ_k F_k of the load,
which a parabola through the three values spreads over the whole step: on a one-mode moving force the
quadratic hold everywhere gives 9× the linear hold's error, from the step after the force comes on
(tests/verification/test_biggs_two_mass.py).  Such a point's share of p_{n−1} is therefore replaced
by the linear continuation of its shares at t_n and t_{n+1}, 2q_n − q̂_{n+1} (its share is then held
linear over the step: the quadratic through (2q_n − q_{n+1}, q_n, q_{n+1}) is the line).  Every share
in the correction is taken with the point's force at t_n, F_n (its end force is not yet known, and a
kernel that goes on from a stored state has no F_{n−1}: with F_n alone the correction is the same
whichever kernel takes the step); the hold is then linear to within F's change over a step, a local
error of O(h³) at the two steps of each crossing, and exactly linear for a constant force.  The
correction to p_{n−1} is

    Δp = Σ_{k crossing} (2q̃_{k,n} − q̃_{k,n+1} − q̃_{k,n−1}),     q̃_{k,j} = −φ_k(x_{k,j}) F_{k,n} (0 off the deck),

point by point, so a run of several loads stays the sum of their runs (the scheme stays linear in
the loads).  ``hold_correction`` (one lane) and ``hold_correction_lanes`` (forces (n_cp, L)) add it.

Where a wheel lands or lifts off within a step its load G, and the modes' loads, jump or kink there:
the next step holds them from the step's end on (``hold_jumps``; the one-lane ``lean`` writes the same
rule flat).
"""
from __future__ import annotations

from vbikit.solve.kernels.bundles import _flat_internal, _internal
from vbikit.solve.kernels.contact import hermite_shape
from vbikit.solve.kernels.lanes import _width


@_flat_internal
def crossing_ends(x_before, x_start, x_end, tr, start, end):
    """Whether a point at positions ``x_before``, ``x_start``, ``x_end`` [m] (t_{n−1}, t_n, t_{n+1}) on
    track ``tr`` comes onto the track or leaves it within the step's stencil, and whether it is on the
    deck at t_n and at t_{n+1} (the kernels' test, start ≤ x ≤ end)."""
    on0 = start[tr] <= x_before <= end[tr]
    on1 = start[tr] <= x_start <= end[tr]
    on2 = start[tr] <= x_end <= end[tr]
    return not (on0 == on1 and on1 == on2), on1, on2


@_flat_internal
def hold_correction(x_before, x_share, x_start, x_end, track, start, end, grid_h, values, slopes, f_start, phi_row,
                    dphi_row, corr):
    """Δp (module docstring) of one lane into ``corr`` (n_m,), for points at positions ``x_before``,
    ``x_start``, ``x_end`` (n_cp,) at t_{n−1}, t_n, t_{n+1} with forces ``f_start`` F_n (n_cp,), whose
    shares in the kernel's p_{n−1} were taken at ``x_share`` (``x_before``; at a run's first step, whose
    p_{n−1} is the start's own, ``x_start``); ``phi_row``, ``dphi_row`` (n_m,) work space.  Returns
    whether any point crosses (else ``corr`` is not written)."""
    n_m = corr.size
    found = False
    for k in range(x_start.size):
        tr = track[k]
        crossing, on1, on2 = crossing_ends(x_before[k], x_start[k], x_end[k], tr, start, end)
        if not crossing:
            continue
        if not found:
            for m in range(n_m):
                corr[m] = 0.0
            found = True
        fk = f_start[k]
        if fk == 0.0:
            continue
        for which in range(3):  # 2q̃_n, −q̃_{n+1}, −q̃_{n−1} with q̃ = −φF_n
            x = x_start[k] if which == 0 else (x_end[k] if which == 1 else x_share[k])
            on = on1 if which == 0 else (on2 if which == 1 else start[tr] <= x <= end[tr])
            if on:
                hermite_shape(x, tr, start, grid_h, values, slopes, phi_row, dphi_row)
                weight = -2.0 * fk if which == 0 else fk
                for m in range(n_m):
                    corr[m] += weight * phi_row[m]
    return found


@_internal
def hold_correction_lanes(x_before, x_share, x_start, x_end, track, start, end, grid_h, values, slopes, f_start,
                          phi_row, dphi_row, corr):
    """``hold_correction`` with the forces of every lane (n_cp, L) into ``corr`` (n_m, L)."""
    n_m, n_l = corr.shape
    found = False
    for k in range(x_start.size):
        tr = track[k]
        crossing, on1, on2 = crossing_ends(x_before[k], x_start[k], x_end[k], tr, start, end)
        if not crossing:
            continue
        if not found:
            for m in range(n_m):
                for lane in range(n_l):
                    corr[m, lane] = 0.0
            found = True
        for which in range(3):  # 2q̃_n, −q̃_{n+1}, −q̃_{n−1} with q̃ = −φF_n
            x = x_start[k] if which == 0 else (x_end[k] if which == 1 else x_share[k])
            on = on1 if which == 0 else (on2 if which == 1 else start[tr] <= x <= end[tr])
            if not on:
                continue
            hermite_shape(x, tr, start, grid_h, values, slopes, phi_row, dphi_row)
            scale = -2.0 if which == 0 else 1.0
            for m in range(n_m):
                a = scale * phi_row[m]
                for lane in range(n_l):
                    corr[m, lane] += a * f_start[k, lane]
    return found


@_internal
def hold_jumps(wf, contact, g, p, p_start, g_start, jumped, lanes):
    """A wheel that lands or lifts off within the step (its force sum ``wf`` > 0 now and not before, or
    the reverse; ``contact`` holds whether it was, and is updated): its load G jumps or kinks there, so
    the next step holds it from the step's end on — its entry of the loads of the step before,
    ``g_start`` (which the caller makes the next step's G_{n−1}), set to the end value ``g`` — and every
    mode's, ``p_start``, to ``p`` in that lane (``lean``: the same rule)."""
    n_l = _width(lanes, wf)
    for lane in range(n_l):
        jumped[lane] = False
    for w in range(wf.shape[0]):
        for lane in range(n_l):
            touching = wf[w, lane] > 0.0
            if touching != contact[w, lane]:
                g_start[w, lane] = g[w, lane]
                jumped[lane] = True
            contact[w, lane] = touching
    for lane in range(n_l):
        if jumped[lane]:
            for m in range(p.shape[0]):
                p_start[m, lane] = p[m, lane]
