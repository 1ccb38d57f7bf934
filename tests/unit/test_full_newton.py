"""The implicit step's full Newton update (``vbikit.solve.kernels.newton._full_newton``, with
``_penetration`` and the touching points of ``_residuals``) on small contrived systems, against a
brute-force solution of the contact complementarity problem.

The world is written here in numpy from the kernels' equations (``vbikit.solve.kernels``' docstring,
``implicit``'s end-of-step state ``_state_of``): for end-of-step point forces F,

    p = −Σ_k φ_k F_k (points on the deck),  ξ = ξ_f + c1 p,  ξ̇ = ξ̇_f + c2 p,
    z = z_b + R F_w (F_w: each wheel's sum; R = P L1, the vehicles' response; wheel_q = H R_q, wheel_v = H R_v),
    δ_k = r_k + φ_k·ξ − g_k − h_w·y,   δ̇_k = ṙ_k + v_x φ'_k·ξ + φ_k·ξ̇ − h_w·ẏ,
    law_k = k_k δ_k + c_k δ̇_k + f0_k,  gated: F_k = law_k if δ_k > 0 and law_k > 0, else 0.

The law is affine in F for a fixed set A of points in contact, so the brute force enumerates every
one of the 2^n sets, solves F_A = law_A(F) (F = 0 off A) with ``numpy.linalg.solve`` and keeps the
sets whose solution is consistent (δ > 0 and F > 0 on A; δ ≤ 0 or law ≤ 0 off A).  The kernel is
driven the way ``implicit`` drives it past its quasi-Newton updates: evaluate the law at the
iterate (numpy, here), the points it presses are the active set, one full Newton update, until
``_residuals`` finds the law held.  A damped tire landing that neither set satisfies (F = 0 lets
the wheel sink in with a downward rate; the F that the contact law gives lifts it out within the
step) is held at δ = 0 with 0 ≤ F ≤ law(δ = 0) (``TOUCH_STIFFNESS``): its force is the one that
makes δ(F) = 0, solved here by hand.
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from numba import njit

from vbikit.solve.kernels import ModalStep, Points, VehicleStep, Vehicles, new_cache
from vbikit.solve.kernels.newton import _full_newton, _penetration, _residuals


def _points(wheel, stiffness, damping, slope_range) -> Points:
    """The kernels' point bundle (the types ``implicit`` compiles ``_full_newton`` for) with the tire
    law's fields given, no gap or fixed load, every point gated and driving +x."""
    n = wheel.size
    zero, ones = np.zeros(n), np.ones(n)
    return Points(zero, ones, np.zeros(n, np.int64), np.zeros(n, np.int64), np.zeros(n, np.int64), stiffness,
                  damping, zero.copy(), zero.copy(), np.ones(n, np.bool_), wheel, zero.copy(), slope_range)


def _vehicles(envelope: np.ndarray, rows: np.ndarray) -> Vehicles:
    """The kernels' vehicle bundle with the wheel rows and envelopes given (the rest unused here)."""
    n_w, n_d = rows.shape
    square, wheels = np.zeros((n_d, n_d)), np.zeros(n_w)
    return Vehicles(square, square, square, square, np.zeros(n_d), rows, np.zeros(n_w, np.int64),
                    np.ones(n_w, np.int64), envelope, wheels, wheels)


def _work_spaces(n_cp: int, n_m: int, n_w: int) -> tuple:
    """``implicit``'s work spaces of the full Newton (sized as there; kept across the updates of a step,
    so that the factors of an unchanged set are reused): e, u, mat, piv, red, red_piv, rhs, t, act,
    held, held_k, held_c, row_k, row_c, held_state (no set held)."""
    cap, r = n_cp, n_m + n_w
    n_r = min(cap, r)
    return (np.zeros((cap, n_m)), np.zeros((cap, n_w)), np.zeros((n_r, n_r)), np.zeros(n_r, np.int64),
            np.zeros((r, r)), np.zeros(r, np.int64), np.zeros(cap), np.zeros(r), np.zeros(cap, np.int64),
            np.zeros(cap, np.int64), np.zeros(cap), np.zeros(cap), np.zeros(cap), np.zeros(cap),
            np.array([-1, 0], np.int64))


@njit(cache=True)
def _update(f, force, active, touch, x1, v1, y1, w1, cache, points, vehicles, onb, step, vstep, p, fw, work):
    """One full Newton update of lane 0 (``implicit``'s call; every point used and gated)."""
    e, u, mat, piv, red, red_piv, rhs, t, act, held, held_k, held_c, row_k, row_c, held_state = work
    used = np.ones(f.shape[0], np.bool_)
    _full_newton(f, force, used, active, 0, 1.0, touch, used, x1, v1, y1, w1, cache, points, vehicles, onb, step,
                 vstep, p, fw, e, u, mat, piv, red, red_piv, rhs, t, act, held, held_k, held_c, row_k, row_c,
                 held_state)


@njit(cache=True)
def _residual(f, force, touch, x1, v1, y1, w1, cache, points, vehicles, onb, tol):
    return _residuals(f, force, np.ones(f.shape[0], np.bool_), touch, np.zeros(1), x1, v1, y1, w1, cache, points,
                      vehicles, onb, tol)


@njit(cache=True)
def _point_law(k, x1, v1, y1, w1, cache, points, vehicles, onb):
    return _penetration(k, 0, x1, v1, y1, w1, cache, points, vehicles, onb)


class World:
    """A bridge of ``n_m`` modes and ``n_w`` wheels (one DOF each, coupled through R, whose wheel
    compliance over the step is ``compliance`` [m/N]) carrying ``wheel_of_point`` contact points, with
    its free end-of-step state (F = 0) drawn at random."""

    def __init__(self, seed: int, wheel_of_point, n_m: int, damping: float, envelope: bool = False,
                 compliance: float = 4e-7):
        rng = np.random.default_rng(seed)
        n_cp, n_w = len(wheel_of_point), max(wheel_of_point) + 1
        self.n_cp, self.n_m, self.n_w = n_cp, n_m, n_w
        self.cache = new_cache(n_cp, n_m, 1)
        self.cache.phi[:] = rng.uniform(0.2, 1.0, (n_cp, n_m))
        self.cache.dphi[:] = rng.normal(size=(n_cp, n_m)) * 0.3
        self.cache.vx[:] = 10.0
        self.cache.rv[:, 0] = rng.normal(size=n_cp) * 2e-3
        self.cache.rr[:, 0] = rng.normal(size=n_cp) * 0.2
        self.onb = rng.random(n_cp) < 0.75
        zeros = np.zeros(n_m)
        self.c1 = rng.uniform(2e-9, 6e-9, n_m)  # deck: m/N of modal load over the step
        self.c2 = rng.uniform(2e-6, 6e-6, n_m)
        self.step = ModalStep(zeros, zeros, zeros, zeros, zeros, zeros, self.c1, self.c2, zeros, zeros)
        coupling = rng.normal(size=(n_w, n_w)) * 0.1
        self.r_q = compliance * (np.eye(n_w) + 0.5 * (coupling + coupling.T))  # vehicles: m/N over the step
        self.r_v = 5e-5 * (np.eye(n_w) + 0.5 * (coupling + coupling.T))
        self.h = np.eye(n_w)  # wheel w's lowest point is DOF w
        square = np.zeros((1, 1))  # the step map's other fields (unused here; ``constant`` is a vector)
        self.vstep = VehicleStep(square, square, square, np.zeros(1), square, square, square, square, self.h @ self.r_q,
                                 self.h @ self.r_v, square)
        slopes = np.tile([-0.05, 0.05], (n_cp, 1))
        self.points = _points(np.asarray(wheel_of_point, np.int64), rng.uniform(5e5, 2e6, n_cp),
                              np.full(n_cp, damping), slopes)
        self.vehicles = _vehicles(np.full(n_w, envelope), self.h)
        self.xf = rng.normal(size=n_m) * 1e-3
        self.vf = rng.normal(size=n_m) * 1e-2
        self.yb = rng.normal(size=n_w) * 2e-3  # end-of-step wheel heights and rates with F = 0
        self.wb = rng.normal(size=n_w) * 0.05

    def state(self, f: np.ndarray):
        """ξ, ξ̇, y, ẏ (lane columns), p and F_w at the end of the step for point forces ``f``."""
        phi = self.cache.phi * self.onb[:, None]
        p = -phi.T @ f
        fw = np.bincount(self.points.wheel, weights=f, minlength=self.n_w)
        col = lambda a: np.ascontiguousarray(a[:, None])  # noqa: E731 - one lane
        return (col(self.xf + self.c1 * p), col(self.vf + self.c2 * p), col(self.yb + self.r_q @ fw),
                col(self.wb + self.r_v @ fw), col(p), col(fw))

    def law(self, f: np.ndarray):
        """δ and the ungated law k δ + c δ̇ + f0 of every point for forces ``f``."""
        x1, v1, y1, w1, _, _ = self.state(f)
        phi = self.cache.phi * self.onb[:, None]
        dphi = self.cache.dphi * self.onb[:, None]
        s = self.cache.rv[:, 0] + phi @ x1[:, 0]
        sd = self.cache.rr[:, 0] + self.cache.vx * (dphi @ x1[:, 0])
        if self.vehicles.wheel_envelope[0]:  # the road rate along the travel within the circle's slopes
            v = self.points.direction * self.cache.vx
            sd = np.clip(sd, v * self.points.slope_range[:, 0], v * self.points.slope_range[:, 1])
        zw, zw_dot = (self.h @ y1[:, 0])[self.points.wheel], (self.h @ w1[:, 0])[self.points.wheel]
        pen = s - self.points.gap - zw
        rate = sd + phi @ v1[:, 0] - zw_dot
        return pen, self.points.stiffness * pen + self.points.damping * rate + self.points.fixed_load

    def gated(self, f: np.ndarray):
        pen, law = self.law(f)
        active = (pen > 0.0) & (law > 0.0)
        return np.where(active, law, 0.0), active

    def complementarity_solutions(self) -> list[np.ndarray]:
        """Every consistent F among the 2^n contact sets (brute force; the law is affine in F)."""
        n = self.n_cp
        a = self.law(np.zeros(n))[1]
        jac = np.column_stack([self.law(np.eye(n)[j])[1] - a for j in range(n)])  # exact: affine
        found = []
        for bits in itertools.product((False, True), repeat=n):
            on = np.array(bits)
            f = np.zeros(n)
            if on.any():
                f[on] = np.linalg.solve(np.eye(on.sum()) - jac[np.ix_(on, on)], a[on])
            pen, law = self.law(f)
            if np.all((pen[on] > 0.0) & (f[on] > 0.0)) and np.all((pen[~on] <= 0.0) | (law[~on] <= 0.0)):
                found.append(f)
        return found

    def solve_with_the_kernel(self, tol: float, max_updates: int = 30):
        """``implicit``'s iteration with full Newton updates only, from F = 0: (F, updates, touch)."""
        f = np.zeros((self.n_cp, 1))
        touch = np.zeros((self.n_cp, 1), np.bool_)
        work = _work_spaces(self.n_cp, self.n_m, self.n_w)
        for update in range(max_updates + 1):
            x1, v1, y1, w1, p, fw = self.state(f[:, 0])
            force, active = self.gated(f[:, 0])
            force = np.ascontiguousarray(force[:, None])
            args = (x1, v1, y1, w1, self.cache, self.points, self.vehicles, self.onb)
            if _residual(f, force, touch, *args, tol) <= tol:
                return f[:, 0], update, touch[:, 0]
            _update(f, force, np.ascontiguousarray(active[:, None]), touch, *args, self.step, self.vstep, p, fw, work)
        raise AssertionError("the full Newton updates did not settle")


# (seed, wheel of each point, modes): 3–4 points on 3 wheels, a wheel with two points (as a multipoint
# tire); with 1 mode and 2 wheels (4 points > n_m + n_w) the kernel solves through the capacitance form
SYSTEMS = [(24, [0, 1, 2], 2), (9, [0, 0, 1, 2], 2), (2, [0, 1, 1, 2], 3), (14, [0, 0, 1, 1], 1), (19, [0, 0, 1, 1], 1)]


@pytest.mark.parametrize("seed,wheels,n_m", SYSTEMS)
def test_full_newton_finds_the_brute_force_contact_set(seed, wheels, n_m):
    """From F = 0 (where the law presses another set of points: pressing some wheels lifts others
    through the vehicles' coupling) the full Newton updates settle on the one consistent set of the
    2^n, some points pressed and some lifted, to 1e-9 of the largest force (the iteration's
    tolerance is 1e-6 N; measured ≤ 6e-13) within a few updates (measured 2–3)."""
    world = World(seed, wheels, n_m, damping=2e3)
    found = world.complementarity_solutions()
    assert len(found) == 1  # the contrived system has one solution
    expected = found[0]
    assert 0 < np.count_nonzero(expected) < world.n_cp  # a mixed set
    assert np.any(world.gated(np.zeros(world.n_cp))[1] != (expected > 0.0))  # the set changes on the way
    f, updates, touch = world.solve_with_the_kernel(tol=1e-6)
    assert not touch.any()
    np.testing.assert_allclose(f, expected, rtol=0.0, atol=1e-9 * np.abs(expected).max())
    assert updates <= world.n_cp  # a Newton update per contact change, not a fixed-point crawl


def _landing(envelope: bool) -> World:
    """One point tire landing on a deck: with F = 0 it sinks 1 mm in at 0.5 m/s, and a damping of
    4e4 N s/m makes the contact law's force lift it out within the step."""
    world = World(11, [0], 1, damping=4e4, envelope=envelope)
    world.onb[:] = True
    world.yb[:] = world.cache.rv[0, 0] + world.cache.phi[0] @ world.xf - 1e-3  # δ(F = 0) = 1 mm
    world.wb[:] = -0.5
    return world


@pytest.mark.parametrize("envelope", [False, True], ids=["point", "rigid-disk"])
def test_a_damped_landing_is_held_at_zero_penetration(envelope):
    """Neither set is consistent (brute force: none of the 2), so the kernel holds the point at δ = 0
    (touching) with the force that makes δ(F) = 0, which here is 0 ≤ F ≤ law(δ = 0): solved by hand
    from the affine δ(F)."""
    world = _landing(envelope)
    assert world.complementarity_solutions() == []
    pen0, _ = world.law(np.zeros(1))
    slope = world.law(np.ones(1))[0] - pen0  # dδ/dF (affine)
    hold = -pen0 / slope
    assert hold[0] > 0.0 and 0.0 <= hold[0] <= world.law(hold)[1][0]  # the touching state is consistent
    f, updates, touch = world.solve_with_the_kernel(tol=1e-6)
    assert touch[0]
    assert f[0] == pytest.approx(hold[0], rel=1e-9)
    assert abs(world.law(f)[0][0]) * world.points.stiffness[0] <= 1e-6  # held at δ = 0 (k|δ| within tol)


@pytest.mark.parametrize("envelope", [False, True], ids=["point", "rigid-disk"])
def test_penetration_is_the_law_at_the_end_of_step_state(envelope):
    """``_penetration`` = the numpy law above; on a rigid disk's wheel the road rate along the travel
    (here 0.2 m/s … −0.2 m/s over the circle's ±0.05 slopes at 10 m/s, ±0.5 m/s) is clamped."""
    world = World(21, [0, 1, 2], 2, damping=3e3, envelope=envelope)
    world.cache.rr[:, 0] = [2.0, -1.5, 0.3]  # two beyond ±0.5 m/s (clamped on a rigid disk), one within
    world.onb[:] = [True, False, True]
    f = np.array([2e3, 0.0, 5e2])
    x1, v1, y1, w1, _, _ = world.state(f)
    pen, law = world.law(f)
    for k in range(3):
        got = _point_law(k, x1, v1, y1, w1, world.cache, world.points, world.vehicles, world.onb)
        assert got[0] == pytest.approx(pen[k], rel=1e-12, abs=1e-15)
        assert got[1] == pytest.approx(law[k], rel=1e-12, abs=1e-9)
    unclamped = World(21, [0, 1, 2], 2, damping=3e3, envelope=False)
    unclamped.cache.rr[:, 0] = world.cache.rr[:, 0]
    unclamped.onb[:] = world.onb
    differs = np.abs(unclamped.law(f)[1] - law) > 1.0
    assert list(differs) == ([True, True, False] if envelope else [False, False, False])
