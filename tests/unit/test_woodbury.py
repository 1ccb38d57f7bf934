"""The quasi-Newton update's wheel part (``vbikit.solve.kernels.woodbury`` with ``dense.solve_held``)
against a dense numpy solve of the update it stands for.

With the Jacobian through the vehicles only, the forces F_A of the active points A of a lane satisfy

    (I + U_A S_A) F_A = law_A + U_A F_w,   u_i = k_i wheel_q[w_i] + c_i wheel_v[w_i],

F_w = S F the wheels' present forces (= S_A F when F = 0 off A), S_A summing the active points of
each wheel.  The kernels solve instead, by Woodbury's identity, the n_w-square system
(I + S_A U_A) t = S_A (law_A + U_A F_w) (``vehicle_factors``, ``vehicle_rhs`` plus the law's sum per
wheel, ``solve_held``), then (bq, bv) = W (F_w − t) (``vehicle_back``) and F_i = law_i + k_i bq_{w_i} +
c_i bv_{w_i}.  The reference here is ``numpy.linalg.solve`` of the |A|-square system itself, built
point by point from the definitions above (not from the kernels' sums): random sizes, several lanes,
each lane's own sums (``col`` < 0, as ``lean_lanes._quasi_lanes``) and one column shared by every
lane (``col`` ≥ 0, as ``newton._vehicle_newton`` and ``_quasi_lanes``' shared slot).  The functions
run as Python (``py_func``) and once compiled, through a small jitted caller.
"""
from __future__ import annotations

import numpy as np
import pytest
from numba import njit

from vbikit.solve.kernels import dense, woodbury


def _py(f):
    """The Python function of a kernel (itself when NUMBA_DISABLE_JIT=1)."""
    return getattr(f, "py_func", f)


def _problem(rng, n_w, n_l, n_cp, shared):
    wheel = rng.integers(0, n_w, n_cp)
    wheel[:n_w] = np.arange(n_w)  # every wheel has a point
    k = rng.uniform(1e5, 1e6, n_cp)
    c = rng.uniform(1e2, 1e4, n_cp)
    # the step map: change of −z_w, −ż_w per unit wheel force (m/N, m/(s N)), so that k W ~ O(1)
    wq = rng.normal(0.0, 1.0, (n_w, n_w)) * 2e-7 + np.eye(n_w) * 5e-7
    wv = rng.normal(0.0, 1.0, (n_w, n_w)) * 2e-5 + np.eye(n_w) * 1e-4
    if shared:
        active = np.repeat(rng.random((n_cp, 1)) < 0.7, n_l, axis=1)
    else:
        active = rng.random((n_cp, n_l)) < 0.7
    law = rng.uniform(-2e4, 5e4, (n_cp, n_l))
    f = rng.uniform(0.0, 5e4, (n_cp, n_l)) * active
    fw = np.zeros((n_w, n_l))
    for i in range(n_cp):
        fw[wheel[i]] += f[i]
    return wheel, k, c, wq, wv, active, law, fw


def _reference(wheel, k, c, wq, wv, active, law, fw, lane):
    """F_A of (I + U_A S_A) F_A = law_A + U_A F_w by a dense solve (numpy), F = 0 off A."""
    a = np.flatnonzero(active[:, lane])
    n_w = wq.shape[0]
    out = np.zeros(active.shape[0])
    if a.size == 0:
        return out
    u = np.array([k[i] * wq[wheel[i]] + c[i] * wv[wheel[i]] for i in a]).reshape(len(a), n_w)
    s = np.zeros((n_w, len(a)))
    s[wheel[a], np.arange(len(a))] = 1.0
    out[a] = np.linalg.solve(np.eye(len(a)) + u @ s, law[a, lane] + u @ fw[:, lane])
    return out


def _update(fns, wheel, k, c, wq, wv, active, law, fw, col, lane0, lane1, rng):
    """The kernels' update of the lanes ``lane0`` … ``lane1`` − 1: the points' side written here as the
    kernels do it.  With ``col`` ≥ 0 only that column of the sums is filled (the others hold values no
    lane's active set gives: read, they would show); the lanes outside the range hold NaN."""
    factors, rhs, solve, back = fns
    n_w, n_l = fw.shape
    ksum = np.zeros((n_w, n_l))
    csum = np.zeros((n_w, n_l))
    for i in range(wheel.size):
        ksum[wheel[i]] += k[i] * active[i]
        csum[wheel[i]] += c[i] * active[i]
    if col >= 0:
        others = np.arange(n_l) != col
        ksum[:, others] = rng.uniform(1e7, 1e8, (n_w, others.sum()))
        csum[:, others] = rng.uniform(1e5, 1e6, (n_w, others.sum()))
    bq = np.full((n_w, n_l), np.nan); bv = np.full((n_w, n_l), np.nan); t = np.full((n_w, n_l), np.nan)
    rhs(wq, wv, fw, ksum, csum, np.int64(col), bq, bv, t, np.int64(lane0), np.int64(lane1))
    for i in range(wheel.size):
        t[wheel[i], lane0:lane1] += law[i, lane0:lane1] * active[i, lane0:lane1]
    t_rhs = t.copy()
    veh = np.zeros((n_l + 1, n_w, n_w)); piv = np.zeros((n_l + 1, n_w), np.int64)
    held = np.zeros((n_l + 1, 2 * n_w + 1))
    if col >= 0:  # one set of factors (slot n_l), the lanes at once
        factors(veh[n_l], piv[n_l], held[n_l], ksum, csum, np.int64(col), wq, wv)
        solve(veh[n_l], piv[n_l], t, np.int64(lane0), np.int64(lane1))
    else:
        for lane in range(lane0, lane1):
            factors(veh[lane], piv[lane], held[lane], ksum, csum, np.int64(lane), wq, wv)
            solve(veh[lane], piv[lane], t, np.int64(lane), np.int64(lane + 1))
    back(wq, wv, t, bq, bv, np.int64(lane0), np.int64(lane1))
    f = np.where(active, law + k[:, None] * bq[wheel] + c[:, None] * bv[wheel], 0.0)
    return f, t, t_rhs, ksum, csum, held, bq, bv


PY = tuple(_py(g) for g in (woodbury.vehicle_factors, woodbury.vehicle_rhs, dense.solve_held, woodbury.vehicle_back))


@njit(cache=False)
def _jit_rhs(wq, wv, fw, ksum, csum, col, bq, bv, t, lane0, lane1):
    woodbury.vehicle_rhs(wq, wv, fw, ksum, csum, col, bq, bv, t, lane0, lane1)


@njit(cache=False)
def _jit_factors(veh, piv, held, ksum, csum, col, wq, wv):
    woodbury.vehicle_factors(veh, piv, held, ksum, csum, col, wq, wv)


@njit(cache=False)
def _jit_solve(a, pv, t, lane0, lane1):
    dense.solve_held(a, pv, t, lane0, lane1)


@njit(cache=False)
def _jit_back(wq, wv, t, bq, bv, lane0, lane1):
    woodbury.vehicle_back(wq, wv, t, bq, bv, lane0, lane1)


JIT = (_jit_factors, _jit_rhs, _jit_solve, _jit_back)


@pytest.fixture
def as_python(monkeypatch):
    """The functions as the kernel-coverage job runs them (NUMBA_DISABLE_JIT=1): plain Python, the
    LU factorisation that ``vehicle_factors`` inlines too."""
    monkeypatch.setattr(woodbury, "lu_factor_inline", _py(dense.lu_factor_inline))


@pytest.mark.parametrize("fns", [PY, JIT], ids=["python", "compiled"])
@pytest.mark.parametrize("shared", [False, True], ids=["own sums", "shared sums"])
@pytest.mark.parametrize("seed", range(6))
def test_the_wheel_part_solves_the_quasi_newton_update(fns, shared, seed, request):
    if fns is PY:
        request.getfixturevalue("as_python")
    rng = np.random.default_rng(seed)
    n_w, n_l = int(rng.integers(1, 7)), int(rng.integers(1, 6))
    n_cp = n_w + int(rng.integers(0, 12))
    problem = _problem(rng, n_w, n_l, n_cp, shared)
    wheel, k, c, wq, wv, active, law, fw = problem
    col = int(rng.integers(0, n_l)) if shared else -1
    lane0 = int(rng.integers(0, n_l))
    lane1 = int(rng.integers(lane0 + 1, n_l + 1))
    f, t, t_rhs, ksum, csum, held, bq, bv = _update(fns, *problem, col, lane0, lane1, rng)
    for lane in range(n_l):
        if not lane0 <= lane < lane1:  # lanes outside the range are not touched
            assert np.isnan(t[:, lane]).all() and np.isnan(bq[:, lane]).all() and np.isnan(bv[:, lane]).all()
            continue
        ref = _reference(*problem, lane)
        scale = np.abs(ref).max() + np.abs(law[:, lane]).max()
        assert np.abs(f[:, lane] - ref).max() <= 1e-11 * scale, (lane, f[:, lane], ref)
        # t is V⁻¹ S_A (law_A + U_A F_w), V = I + S_A U_A of this lane's sums (numpy's solve)
        kk = ksum[:, col if col >= 0 else lane]
        cc = csum[:, col if col >= 0 else lane]
        v = np.eye(n_w) + kk[:, None] * wq + cc[:, None] * wv
        assert np.allclose(t[:, lane], np.linalg.solve(v, t_rhs[:, lane]), rtol=1e-12, atol=1e-12 * scale)
    # the factors' slot holds the sums it was factorised for
    slot = n_l if shared else lane1 - 1
    kk = ksum[:, col if shared else lane1 - 1]
    cc = csum[:, col if shared else lane1 - 1]
    assert held[slot, -1] == 1.0
    assert np.array_equal(held[slot, :n_w], kk) and np.array_equal(held[slot, n_w:2 * n_w], cc)


@pytest.mark.parametrize("fns", [PY, JIT], ids=["python", "compiled"])
def test_held_factors_are_kept_while_the_sums_stay_and_made_again_when_they_change(fns, request):
    if fns is PY:
        request.getfixturevalue("as_python")
    factors, _, solve, _ = fns
    rng = np.random.default_rng(7)
    n_w = 4
    wq = rng.normal(0.0, 1.0, (n_w, n_w)) * 2e-7 + np.eye(n_w) * 5e-7
    wv = rng.normal(0.0, 1.0, (n_w, n_w)) * 2e-5 + np.eye(n_w) * 1e-4
    ksum = rng.uniform(1e5, 1e6, (n_w, 2))
    csum = rng.uniform(1e2, 1e4, (n_w, 2))
    veh = np.zeros((n_w, n_w)); piv = np.zeros(n_w, np.int64); held = np.zeros(2 * n_w + 1)
    factors(veh, piv, held, ksum, csum, np.int64(0), wq, wv)
    kept = veh.copy()
    veh[:] = np.nan  # were they factorised again, these would be overwritten
    factors(veh, piv, held, ksum, csum, np.int64(0), wq, wv)
    assert np.isnan(veh).all()
    veh[:] = kept
    factors(veh, piv, held, ksum, csum, np.int64(1), wq, wv)  # other sums: new factors
    b = rng.normal(size=(n_w, 1))
    x = b.copy()
    solve(veh, piv, x, np.int64(0), np.int64(1))
    v = np.eye(n_w) + ksum[:, 1:2] * wq + csum[:, 1:2] * wv
    assert np.allclose(v @ x, b, rtol=0, atol=1e-12 * np.abs(b).max())
    assert np.array_equal(held[:n_w], ksum[:, 1]) and np.array_equal(held[n_w:2 * n_w], csum[:, 1])


def test_pivoting_rows_are_swapped_in_every_lane():
    """A V that needs row swaps (the kernels' own do not: the coverage job never runs them)."""
    rng = np.random.default_rng(3)
    n_w, n_l = 3, 4
    a = np.array([[1e-6, 2.0, 0.5], [3.0, 1.0, 0.0], [0.5, 0.2, 4.0]])
    lu = a.copy(); piv = np.zeros(n_w, np.int64)
    _py(dense.lu_factor_inline)(lu, n_w, piv)
    assert (piv != np.arange(n_w)).any()
    b = rng.normal(size=(n_w, n_l))
    x = b.copy()
    _py(dense.solve_held)(lu, piv, x, np.int64(1), np.int64(3))  # lanes 1, 2 only
    assert np.allclose(a @ x[:, 1:3], b[:, 1:3], rtol=0, atol=1e-12)
    assert np.array_equal(x[:, [0, 3]], b[:, [0, 3]])
