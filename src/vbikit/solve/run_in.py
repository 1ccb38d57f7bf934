"""The vehicles' settled state at the start of a run: a run-in on the road behind them.

A run starts its vehicles at rest in static equilibrium ``crossing.approach`` before the bridge
(docs/theory.md, "Start and end of a crossing").  A truck that has driven on a rough road for long
carries a vibration that a short approach does not build up (docs/traffic.md, "Start from rest and
the approach").  With ``crossing.run_in`` = R > 0 [m] the vehicles are first driven alone over the
R metres of road behind their start positions, from rest in static equilibrium where that road begins,
and the run starts from the state they reach — as if the approach were R longer, without the coupled
steps over it (the run's own step: tests/verification/test_run_in.py).

Off the deck each contact point's force is the tire law on the road alone, F_p = k_p (r_p − g_p − z_w)
+ c_p (ṙ_p − ż_w) + f0_p (every point in contact: the run-in is linear), so the vehicles' wheel loads
of the exact step map (``modal_step.vehicle_step``: z_{n+1} = T z_n + L0 G_n + L1 G_{n+1} + b, the loads
held linear over a step) are G_n = a_n + D z_n with a_w = Σ_p (k_p (r_p − g_p) + c_p ṙ_p + f0_p) over the
wheel's points, known from the road, and D z = (k_w − Σ_p k_p) z_w + (c_w − Σ_p c_p) ż_w (zero where the
nominal tire is the sum of its points').  Then z_{n+1} = A z_n + u_n, A = S (T + L0 D), S = (I − L1 D)⁻¹,
u_n = S (L0 a_n + L1 a_{n+1} + b): a linear time-invariant recursion over the K run-in steps, summed in
the eigenbasis of A (A = V Λ V⁻¹): z_K = V (Λ^K V⁻¹ z_0 + Σ_n Λ^{K−1−n} V⁻¹ u_n) — the same numbers as
the step-by-step recursion (``settled_state_by_steps``, the tests' reference) to round-off.  The road
under each point is read as the kernels read it (linear between stations; the rate the secant over
±|v| dt/2), each vehicle at its speed at the start, held over the run-in.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.solve.crossing import Crossing

#: the eigenbasis sum is used while V's condition number stays below this; above, the steps one by one
EIGEN_CONDITION_LIMIT = 1e8


#: run-in steps summed at a time (``settled_state``): its memory stays that of this many steps, however long
#: the run-in or fine the step
CHUNK_STEPS = 4096


def run_in_inputs(data: Any, step: Any, dt: float, travel0: NDArray[np.float64], speed0: NDArray[np.float64],
                  road: Any, n: int) -> tuple[NDArray[np.float64], ...]:
    """The recursion z_{k+1} = A z_k + M0 a_k + M1 a_{k+1} + c over the ``n`` run-in steps of ``dt`` ending
    at the start (module docstring): (A, M0, M1, c, a), a (n + 1, n_w) the wheels' road loads at the step
    ends (``road_loads``), for the vehicles at travel ``travel0`` [m] and speed ``speed0`` [m/s] (per
    vehicle) at the start on the road bundle ``road`` (lane 0); ``step`` the vehicles' exact step map over ``dt``."""
    return (*recursion(data, step), road_loads(data, dt, travel0, speed0, road, n, 0, n))


def recursion(data: Any, step: Any) -> tuple[NDArray[np.float64], ...]:
    """(A, M0, M1, c) of the run-in's recursion (module docstring) for the vehicles' step map ``step``."""
    pts, veh = data.points, data.vehicles
    n_d, n_w = veh.gravity.size, veh.wheel_rows.shape[0]
    k_sum = np.bincount(pts.wheel, weights=pts.stiffness, minlength=n_w)
    c_sum = np.bincount(pts.wheel, weights=pts.damping, minlength=n_w)
    d = np.zeros((n_w, 2 * n_d))
    d[:, :n_d] = (veh.wheel_stiffness - k_sum)[:, None] * veh.wheel_rows
    d[:, n_d:] = (veh.wheel_damping - c_sum)[:, None] * veh.wheel_rows
    settle = np.linalg.inv(np.eye(2 * n_d) - step.load1 @ d)
    return settle @ (step.transition + step.load0 @ d), settle @ step.load0, settle @ step.load1, settle @ step.constant


def road_loads(data: Any, dt: float, travel0: NDArray[np.float64], speed0: NDArray[np.float64], road: Any, n: int,
               first: int, last: int) -> NDArray[np.float64]:
    """The wheels' road loads a_k (module docstring) at the run-in's step ends k = ``first`` … ``last`` of ``n``
    (t = (k − n) dt, t = 0 the start), (last − first + 1, n_w)."""
    pts = data.points
    t = dt * (np.arange(first, last + 1) - n)
    x = pts.origin[None, :] + pts.direction[None, :] * (travel0[pts.vehicle][None, :] + speed0[pts.vehicle][None, :] * t[:, None])
    vx = pts.direction * speed0[pts.vehicle]
    half = np.abs(vx) * (0.5 * dt)  # the road rate: the secant over ±|v| dt/2, as the kernels read it
    stations = road.stations
    lines = np.minimum(pts.line, road.elevations.shape[0] - 1)
    per_point = np.empty_like(x)
    for k in range(x.shape[1]):
        z = road.elevations[lines[k], :, 0]
        r = np.interp(x[:, k], stations, z)
        rate = (np.interp(x[:, k] + half[k], stations, z) - np.interp(x[:, k] - half[k], stations, z)) * \
            (vx[k] / (2 * half[k]) if half[k] > 0 else 0.0)
        per_point[:, k] = pts.stiffness[k] * (r - pts.gap[k]) + pts.damping[k] * rate + pts.fixed_load[k]
    return per_point @ (pts.wheel[:, None] == np.arange(data.vehicles.wheel_rows.shape[0])[None, :])  # per wheel


def settled_state(crossing: "Crossing", data: Any, step: Any, dt: float, travel0: NDArray[np.float64],
                  speed0: NDArray[np.float64], road: Any) -> NDArray[np.float64]:
    """The vehicles' state z = (q, q̇) at the start after ``crossing.run_in`` metres of road, from rest in
    static equilibrium where the run-in begins (module docstring: z0 = (I − A)⁻¹ ((M0 + M1) a_0 + c), the
    recursion's fixed point under that place's road loads); ``step`` the vehicles' exact step map over
    ``dt`` (linear hold).  In the eigenbasis of A = V Λ V⁻¹: z_K = V (Λ^K V⁻¹ z0 + Σ_k Λ^{K−1−k} V⁻¹
    (M0 a_k + M1 a_{k+1}) + (I − Λ^K)(I − Λ)⁻¹ V⁻¹ c), the sum over ``CHUNK_STEPS`` steps at a time; the
    steps one by one when V is ill-conditioned."""
    n = run_in_steps(crossing, dt, speed0)
    a_mat, m0, m1, c = recursion(data, step)
    z0 = _rest(a_mat, m0, m1, c, road_loads(data, dt, travel0, speed0, road, n, 0, 0))
    if n == 0 or z0.size == 0:
        return z0
    lam, vec = np.linalg.eig(a_mat)
    if np.linalg.cond(vec) > EIGEN_CONDITION_LIMIT or np.max(np.abs(lam)) >= 1.0:
        return _by_steps(a_mat, m0, m1, c, road_loads(data, dt, travel0, speed0, road, n, 0, n), z0)
    lam = lam.astype(complex)
    vi = np.linalg.inv(vec)
    w0, w1 = vi @ m0, vi @ m1
    loads = np.zeros(lam.size, complex)
    for k0 in range(0, n, CHUNK_STEPS):  # steps k0 … k1 − 1: λ^{K−1−k} = λ^{K−k1} λ^{k1−1−k}
        k1 = min(k0 + CHUNK_STEPS, n)
        a = road_loads(data, dt, travel0, speed0, road, n, k0, k1)
        powers = _powers(lam, k1 - k0)[:, ::-1] * np.exp(np.log(lam) * (n - k1))[:, None]
        loads += np.sum(w0 * (powers @ a[:-1]), axis=1) + np.sum(w1 * (powers @ a[1:]), axis=1)
    lam_k = np.exp(np.log(lam) * n)  # λ^K
    z = vec @ (lam_k * (vi @ z0) + loads + (1.0 - lam_k) / (1.0 - lam) * (vi @ c))
    return np.real(z)


def _powers(lam: NDArray[np.complex128], n: int, block: int = 64) -> NDArray[np.complex128]:
    """λ^k for k = 0 … n − 1, (n_λ, n): λ^(k mod b) · λ^(b ⌊k/b⌋) — products of two short tables of powers
    instead of an exponential each."""
    log = np.log(lam)[:, None]
    small = np.exp(log * np.arange(block)[None, :])  # λ^0 … λ^(b−1)
    big = np.exp(log * (block * np.arange(-(-n // block)))[None, :])  # λ^0, λ^b, λ^2b, …
    return (big[:, :, None] * small[:, None, :]).reshape(lam.size, -1)[:, :n]


def settled_state_by_steps(crossing: "Crossing", data: Any, step: Any, dt: float, travel0: NDArray[np.float64],
                           speed0: NDArray[np.float64], road: Any) -> NDArray[np.float64]:
    """``settled_state`` by the recursion step by step (the reference of the tests)."""
    n = run_in_steps(crossing, dt, speed0)
    inputs = run_in_inputs(data, step, dt, travel0, speed0, road, n)
    return _by_steps(*inputs, _rest(*inputs))


def _rest(a_mat, m0, m1, c, a) -> NDArray[np.float64]:
    """The recursion's fixed point under the road loads where the run-in begins, a_0 held: the vehicles at
    rest in static equilibrium there, z = (I − A)⁻¹ ((M0 + M1) a_0 + c)."""
    return np.linalg.solve(np.eye(a_mat.shape[0]) - a_mat, (m0 + m1) @ a[0] + c)


def _by_steps(a_mat, m0, m1, c, a, z0: NDArray[np.float64]) -> NDArray[np.float64]:
    z = z0.copy()
    for k in range(a.shape[0] - 1):
        z = a_mat @ z + m0 @ a[k] + m1 @ a[k + 1] + c
    return z


def run_in_steps(crossing: "Crossing", dt: float, speed0: NDArray[np.float64]) -> int:
    """Steps of ``dt`` the slowest vehicle needs to drive ``crossing.run_in`` metres (0: no run-in)."""
    if not crossing.run_in > 0:
        return 0
    v = float(np.min(np.abs(speed0))) if speed0.size else 0.0
    return int(math.ceil(crossing.run_in / (v * dt) - 1e-9)) if v > 0 else 0
