"""The implicit step's full Newton solve (vbikit.solve.kernels.newton: ``_coupling`` + ``_newton_solve``)
against numpy's dense solve of the same system.

The matrix is written here from its definition (``_coupling``'s docstring): I − B_AA = I + W Z with
row i of W = [e_i, u_i], e_i = (k_i c1 + c_i c2) ∘ φ_i + c_i v_x c1 ∘ φ'_i (points on the deck) and
u_i = k_i wheel_q[w_i] + c_i wheel_v[w_i], and Z = [Φ_Aᵀ; S_A] (S_A: which wheel each point is on).
Both of the kernel's forms are checked: the direct factorisation (fewer active points than modes
plus wheels) and the capacitance form through Woodbury's identity (more: disk tires), which the
demo-like crossings of the test suite settle without since the one-evaluation step.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pytest
from numba import njit

from vbikit.solve.kernels import ModalStep, VehicleStep, new_cache
from vbikit.solve.kernels.newton import _coupling, _newton_solve


class _Points(NamedTuple):
    wheel: np.ndarray


@njit(cache=True)  # cached like test_full_newton's wrappers: compiled once (about 8 s), not at every run
def _solve(act, na, row_k, row_c, onb, cache, points, step, vstep, rhs):
    n_m, n_w = step.c1.size, vstep.wheel_q.shape[0]
    cap = act.size
    n_r = min(cap, n_m + n_w)
    e, u = np.zeros((cap, n_m)), np.zeros((cap, n_w))
    mat, piv = np.zeros((n_r, n_r)), np.zeros(n_r, np.int64)
    red, red_piv = np.zeros((n_m + n_w, n_m + n_w)), np.zeros(n_m + n_w, np.int64)
    reduced = _coupling(act, na, row_k, row_c, onb, cache, points, step, vstep, e, u, mat, piv, red, red_piv)
    _newton_solve(act, na, onb, cache, points, e, u, mat, piv, red, red_piv, reduced, rhs, np.zeros(n_m + n_w))
    return reduced


@pytest.mark.parametrize("n_points,expect_reduced", [(5, False), (24, True)])
def test_full_newton_solve_matches_a_dense_solve(n_points, expect_reduced):
    rng = np.random.default_rng(7)
    n_m, n_w, n_cp = 4, 3, n_points + 2
    cache = new_cache(n_cp, n_m, 1)
    cache.phi[:] = rng.normal(size=(n_cp, n_m)) * 1e-2
    cache.dphi[:] = rng.normal(size=(n_cp, n_m)) * 1e-3
    cache.vx[:] = 20.0
    wheel = rng.integers(0, n_w, n_cp)
    onb = rng.random(n_cp) < 0.8
    act = np.sort(rng.choice(n_cp, n_points, replace=False)).astype(np.int64)
    k = rng.uniform(1e5, 1e6, n_points)
    c = rng.uniform(1e2, 1e3, n_points)
    zeros = np.zeros(n_m)
    step = ModalStep(zeros, zeros, zeros, zeros, zeros, zeros, rng.uniform(1e-7, 1e-6, n_m), rng.uniform(1e-4, 1e-3, n_m),
                     zeros, zeros)
    wq, wv = rng.normal(size=(n_w, n_w)) * 1e-7, rng.normal(size=(n_w, n_w)) * 1e-5
    vstep = VehicleStep(*(np.zeros((1, 1)),) * 8, wq, wv, np.zeros((1, 1)))
    rhs = rng.normal(size=n_points) * 1e3

    e = np.array([((k[i] * step.c1 + c[i] * step.c2) * cache.phi[p] + c[i] * cache.vx[p] * step.c1 * cache.dphi[p])
                  if onb[p] else zeros for i, p in enumerate(act)])
    u = np.array([k[i] * wq[wheel[p]] + c[i] * wv[wheel[p]] for i, p in enumerate(act)])
    phi_a = np.array([cache.phi[p] if onb[p] else zeros for p in act])  # (na, n_m)
    s_a = np.eye(n_w)[wheel[act]]  # (na, n_w)
    matrix = np.eye(n_points) + e @ phi_a.T + u @ s_a.T
    expected = np.linalg.solve(matrix, rhs)

    got = rhs.copy()
    reduced = _solve(act, n_points, k, c, onb, cache, _Points(wheel), step, vstep, got)
    assert bool(reduced) == expect_reduced
    np.testing.assert_allclose(got, expected, rtol=1e-10, atol=1e-10 * np.abs(expected).max())
