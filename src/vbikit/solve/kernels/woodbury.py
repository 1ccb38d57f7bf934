"""The quasi-Newton update of the point forces through the vehicles: its wheels' part, one copy for
the kernels of many lanes (``lean_lanes._quasi_lanes`` and ``implicit``'s ``newton._vehicle_newton``;
the one-lane ``lean._quasi`` writes the same arithmetic for flat arrays, which compiles faster and runs
its products in registers).  (``vbikit.solve.kernels``: the equations and conventions.)

With the Jacobian through the vehicles only, the update of the forces F of the active points A is
(I + U_A S_A) F_A = law_A(F) + U_A S_A F, F = 0 off A, where u_i = k_i wheel_q[w_i] + c_i wheel_v[w_i]
(U: ∂F_i/∂F_w; ``wheel_q``, ``wheel_v`` (n_w, n_w): the change of a wheel's −z_w and −ż_w at the step's end
per unit wheel force, ``VehicleStep``) and S sums the points of each wheel.  By Woodbury's identity it
is the n_w-square system

    (I + S_A U_A) t = S_A b,   b = (wheel_q, wheel_v) F_w,   (bq, bv) = b − (wheel_q, wheel_v) t,
    F_i = law_i + k_i bq_{w_i} + c_i bv_{w_i}  (i ∈ A),

whose matrix V = I + S_A U_A needs only each wheel's sums K_w, C_w of its active points' k and c:
V_ww' = δ_ww' + K_w wheel_q[w, w'] + C_w wheel_v[w, w'], refactorised only when those sums change
(with the active set; kept across iterations and steps).  (bq, bv) are each wheel's change of −z_w
and −ż_w by the update.

The points' side — which points are active in which lane, their sums per wheel, the sum of their
law values per wheel into t and the forces F_i — follows each kernel's layout (lanes with their own active
sets; lanes sharing one) and stays with the kernel.  The wheels' side is here, on (n_w, L) arrays
over the lanes ``lane0`` … ``lane1`` − 1 (the lanes innermost): ``vehicle_factors`` (V's factors,
kept), ``vehicle_rhs`` (b, and t = S_A b's vehicle terms), ``dense.solve_held`` (t ← V⁻¹ t) and ``vehicle_back`` ((bq, bv) = b − W t).  Flat kernels (no
allocation, no reference counting): each is compiled once for all its callers.
"""
from __future__ import annotations

from vbikit.solve.kernels.bundles import _flat_internal
from vbikit.solve.kernels.dense import lu_factor_inline


@_flat_internal
def vehicle_factors(veh, piv, held, ksum, csum, col, wheel_q, wheel_v):
    """The LU factors (``veh``, ``piv``) of V = I + S_A U_A for the active sums K_w = ``ksum[w, col]``,
    C_w = ``csum[w, col]``, refactorised only when those sums differ from the ones ``held`` (2 n_w + 1,)
    holds (K, C, and a last entry ≠ 0 once filled)."""
    n_w, _ = veh.shape  # (unpacked: an indexed shape compiles a tuple-getitem routine)
    same = held[2 * n_w] != 0.0
    if same:
        for w in range(n_w):
            if ksum[w, col] != held[w] or csum[w, col] != held[n_w + w]:
                same = False
                break
    if not same:
        for w in range(n_w):
            for w2 in range(n_w):
                veh[w, w2] = (1.0 if w == w2 else 0.0) + ksum[w, col] * wheel_q[w, w2] + csum[w, col] * wheel_v[w, w2]
            held[w] = ksum[w, col]
            held[n_w + w] = csum[w, col]
        held[2 * n_w] = 1.0
        lu_factor_inline(veh, n_w, piv)


@_flat_internal
def vehicle_rhs(wheel_q, wheel_v, fw, ksum, csum, col, bq, bv, t, lane0, lane1):
    """(bq, bv) = (wheel_q, wheel_v) F_w and t = K_w bq_w + C_w bv_w for the lanes ``lane0`` … ``lane1`` − 1
    (``fw`` (n_w, L): each wheel's force F_w).  The sums K, C are each lane's own column of ``ksum``,
    ``csum`` when ``col`` < 0, else column ``col`` for all the lanes (lanes sharing one active set).  The
    caller adds the active points' law values of each wheel to t (S_A b's other part)."""
    n_w, _ = wheel_q.shape
    for w in range(n_w):
        for lane in range(lane0, lane1):
            bq[w, lane] = 0.0
            bv[w, lane] = 0.0
        for w2 in range(n_w):
            a = wheel_q[w, w2]
            b = wheel_v[w, w2]
            for lane in range(lane0, lane1):
                bq[w, lane] += a * fw[w2, lane]
                bv[w, lane] += b * fw[w2, lane]
        if col < 0:
            for lane in range(lane0, lane1):
                t[w, lane] = ksum[w, lane] * bq[w, lane] + csum[w, lane] * bv[w, lane]
        else:
            kw = ksum[w, col]
            cw = csum[w, col]
            for lane in range(lane0, lane1):
                t[w, lane] = kw * bq[w, lane] + cw * bv[w, lane]


@_flat_internal
def vehicle_back(wheel_q, wheel_v, t, bq, bv, lane0, lane1):
    """(bq, bv) −= (wheel_q, wheel_v) t for the lanes ``lane0`` … ``lane1`` − 1: each wheel's change of
    −z_w and −ż_w by the update, once t = V⁻¹ S_A b."""
    n_w, _ = wheel_q.shape
    for w in range(n_w):
        for w2 in range(n_w):
            a = wheel_q[w, w2]
            b = wheel_v[w, w2]
            for lane in range(lane0, lane1):
                bq[w, lane] -= a * t[w2, lane]
                bv[w, lane] -= b * t[w2, lane]
