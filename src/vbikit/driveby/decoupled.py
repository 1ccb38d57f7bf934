"""Decoupled drive-by simulation: the bridge under moving forces, then the vehicle driven by the
bridge's motion (``coupling = "decoupled"`` in a drive-by file).

Two one-way steps replace the coupled vehicle–bridge solution (``vbikit.solve.simulate``):

1. **Bridge under moving forces.**  Each wheel is a constant downward force equal to its static
   load on rigid ground, P_w (``Vehicle.static_wheel_loads``); every mode obeys
   ξ̈ᵢ + 2ζᵢωᵢξ̇ᵢ + ωᵢ²ξᵢ = −Σ_w φᵢ(x_w(t), y_w) P_w, solved by the moving-force solver
   (``vbikit.solve.moving_loads.moving_load_history``, the exact discrete-time recurrence of
   Nigam & Jennings 1969 with the coupled run's step, its time grid shifted onto the coupled
   run's by offsetting the axle positions by a fraction of a step).
2. **Vehicle under base excitation.**  The surface under each wheel is
   s_w(t) = Σᵢ φᵢ(x_w, y_w) ξᵢ(t) + r(x_w(t)) (deck displacement, 0 off the deck, plus the road
   profile: the engine's contact law for a point tire), and the vehicle obeys

       M q̈ + C q̇ + K q = F_G + Σ_w r_w [k_w (s_w − r_w·q) + c_w (ṡ_w − r_w·q̇)]

   (``vbikit.vehicle.model``), a linear time-invariant system with input (s_w, ṡ_w), solved
   exactly for inputs linear between samples (matrix exponential, as ``scipy.signal.lsim``; the
   recursion diagonalised and run by ``scipy.signal.lfilter``), from the static state on the
   surface at the first sample; ṡ_w by second-order differences (``numpy.gradient``).

What it neglects: the vehicle's inertia and suspension forces on the bridge (only its weight
acts), so its error grows with the vehicle-to-bridge mass ratio (Yang, Lin & Yau 2004: the light
vehicle limit; ``benchmarks/bench_driveby.py`` maps it); the tires cannot lose contact (linear
springs).  The result is a ``CrossingResult`` on the coupled crossing's time grid, so the sensor
and identification code reads it unchanged.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from numpy.typing import NDArray

from vbikit.errors import VbikitError


def _step(crossing) -> float:
    """The crossing's step, or the one ``simulate`` would choose (``choose_time_step``)."""
    from vbikit.solve.timestep import choose_time_step

    return float(crossing.dt) if crossing.dt is not None else float(choose_time_step(crossing))


def _time_grid(crossing) -> NDArray[np.float64]:
    dt = _step(crossing)
    n = max(1, math.ceil(crossing.duration / dt - 1e-9))  # the engine's grid (vbikit.solve.plan.time_grid)
    return crossing.start_time + dt * np.arange(n + 1)


def bridge_under_forces(crossing, time: NDArray[np.float64]) -> tuple[NDArray, NDArray, NDArray]:
    """Modal coordinates ξ, ξ̇, ξ̈ (n_t, n_modes) of the bridge under the vehicle's static wheel
    loads moving at its speed (step 1 of the module docstring), at ``time`` (a uniform grid; t = 0:
    the front axle on the entry support)."""
    from vbikit.solve.moving_loads import moving_load_history

    if crossing.n_vehicles != 1 or crossing.vehicles[0].acceleration != 0 or crossing.vehicles[0].sign < 0:
        raise VbikitError("coupling = \"decoupled\": one vehicle at constant speed driving +x (identification.method "
                          "\"residual\", an acceleration and other directions need coupling = \"coupled\")")
    motion = crossing.vehicles[0]
    vehicle, speed, dt = motion.vehicle, float(motion.speed), float(time[1] - time[0])
    loads = vehicle.static_wheel_loads()
    offsets = np.array([w.offset for w in vehicle.wheels])
    lateral = np.array([motion.lateral_offset + w.lateral for w in vehicle.wheels])
    if crossing.bridge.lateral_invariant:  # a beam: the wheels of an axle act as one force at its x
        offsets, where = np.unique(offsets, return_inverse=True)
        loads, lateral = np.bincount(where.ravel(), weights=loads), np.zeros(offsets.size)
    # axle positions shifted by e so that the solver's grid (j − 1) h − e / v falls on the crossing's times
    shift = (-(time[0] - motion.entry_time)) % dt
    if shift > dt - 1e-9 * dt:
        shift = 0.0
    n_m = crossing.bridge.omega.size
    out = [np.zeros((time.size, n_m)) for _ in range(3)]
    free = max(0.0, float(time[-1] - motion.entry_time) - (crossing.bridge.span + offsets.max()) / speed) + 4 * dt
    for y in np.unique(lateral):
        on = lateral == y
        hist = moving_load_history(crossing.bridge, offsets[on] + shift * speed, loads[on], speed, dx=speed * dt,
                                   free_vibration=free, y=float(y))
        t_hist = hist.time - shift + motion.entry_time
        k = np.rint((t_hist - time[0]) / dt).astype(np.int64)
        keep = (k >= 0) & (k < time.size)
        for dst, src in zip(out, (hist.xi, hist.xi_dot, hist.xi_ddot)):
            dst[k[keep]] += src[keep]
    return out[0], out[1], out[2]


def surface_under_wheels(crossing, time: NDArray[np.float64], xi: NDArray[np.float64]) -> NDArray[np.float64]:
    """s_w(t) [m], z up (n_t, n_wheels): deck displacement under each wheel (0 off the deck) plus
    the road elevation, the engine's contact law for a point tire."""
    if crossing.road_right is not None:
        raise VbikitError("coupling = \"decoupled\": one road profile for every wheel line (road_right needs coupling "
                          "= \"coupled\")")
    motion = crossing.vehicles[0]
    vehicle, bridge = motion.vehicle, crossing.bridge
    front = crossing.front_positions(time)[:, 0]
    s = np.zeros((time.size, len(vehicle.wheels)))
    lo, hi = bridge.deck_extent
    lines = {}  # (offset, y) -> deck displacement: on a beam (bridge.lateral_invariant) one per axle
    roads = {}
    for j, w in enumerate(vehicle.wheels):
        x = front - w.offset
        y = 0.0 if bridge.lateral_invariant else motion.lateral_offset + w.lateral
        if (w.offset, y) not in lines:
            deck = np.zeros(time.size)
            on = (x >= lo) & (x <= hi)
            if on.any():
                phi = bridge.mode_shapes(x[on], np.full(int(on.sum()), y))
                deck[on] = np.einsum("tm,tm->t", xi[on], phi)
            lines[(w.offset, y)] = deck
        s[:, j] = lines[(w.offset, y)]
        if crossing.road is not None:
            if w.offset not in roads:
                roads[w.offset] = crossing.road.elevation(x)
            s[:, j] += roads[w.offset]
    return s


def _first_order_hold(A: NDArray, B: NDArray, dt: float) -> tuple[NDArray, NDArray, NDArray]:
    """Exact discretisation of ẋ = A x + B u for u linear between samples (first-order hold):
    x_{k+1} = Ad x_k + B0 u_k + B1 u_{k+1}, from the exponential of the block matrix
    [[A, B, 0], [0, 0, I/h], [0, 0, 0]] h (the construction of ``scipy.signal.lsim``)."""
    from scipy.linalg import expm

    n, m = A.shape[0], B.shape[1]
    big = np.zeros((n + 2 * m, n + 2 * m))
    big[:n, :n], big[:n, n:n + m], big[n:n + m, n + m:] = A * dt, B * dt, np.eye(m)
    e = expm(big)
    Ad, Bd1 = e[:n, :n], e[:n, n + m:]
    Bd0 = e[:n, n:n + m] - Bd1
    return Ad, Bd0, Bd1


def _recurrence(Ad: NDArray, forcing: NDArray, x0: NDArray) -> NDArray:
    """x_{k+1} = Ad x_k + forcing_k from x_0, (n_t, n): Ad diagonalised, each eigen-coordinate a
    first-order recursion run by ``scipy.signal.lfilter`` (compiled).  Ad, the forcing and x_0 are
    real, so the coordinate of an eigenvalue's conjugate is the conjugate of its own: one of each
    pair is run and counted twice (x = Σ_real z_i v_i + 2 Re Σ_{Im λ_i > 0} z_i v_i)."""
    from scipy.signal import lfilter

    lam, V = np.linalg.eig(Ad)
    Vinv = np.linalg.inv(V)
    run = np.flatnonzero(lam.imag >= 0.0)                  # LAPACK returns conjugate pairs exactly conjugate
    if np.count_nonzero(lam.imag > 0) != np.count_nonzero(lam.imag < 0):
        run = np.arange(lam.size)                          # not paired (cannot happen for a real Ad): run every one
    weight = np.where(lam[run].imag > 0.0, 2.0, 1.0) if run.size < lam.size else np.ones(run.size)
    g = forcing @ Vinv[run].T                              # (n_t − 1, n_run) in eigen-coordinates
    z0 = Vinv[run] @ x0
    z = np.empty((forcing.shape[0] + 1, run.size), complex)
    z[0] = z0
    for i, li in enumerate(lam[run]):
        z[1:, i], _ = lfilter([1.0], [1.0, -li], g[:, i], zi=[li * z0[i]])
    return np.real((z * weight) @ V[:, run].T)


def vehicle_on_surface(vehicle, time: NDArray[np.float64], surface: NDArray[np.float64]) -> tuple[NDArray, NDArray, NDArray]:
    """q, q̇, q̈ (n_t, n_dof) of the vehicle driven by the surface under its wheels (step 2 of the
    module docstring), from its static state on the surface at the first sample; exact for inputs
    linear between samples (``_first_order_hold``)."""
    n, dt = vehicle.n_dof, float(time[1] - time[0])
    rows = np.array([w.row for w in vehicle.wheels])          # (n_w, n)
    kw = np.array([w.stiffness for w in vehicle.wheels])
    cw = np.array([w.damping for w in vehicle.wheels])
    K = vehicle.stiffness + rows.T @ (kw[:, None] * rows)
    C = vehicle.damping + rows.T @ (cw[:, None] * rows)
    Minv = np.linalg.inv(vehicle.mass)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    # inputs: s_w, ṡ_w and a unit input carrying gravity
    Bf = np.hstack([rows.T * kw, rows.T * cw, vehicle.gravity[:, None]])
    B = np.vstack([np.zeros((n, Bf.shape[1])), Minv @ Bf])
    s_dot = np.gradient(surface, dt, axis=0, edge_order=2)
    u = np.hstack([surface, s_dot, np.ones((time.size, 1))])
    Ad, B0, B1 = _first_order_hold(A, B, dt)
    x = _recurrence(Ad, u[:-1] @ B0.T + u[1:] @ B1.T, np.concatenate([vehicle.static_state(surface[0]), np.zeros(n)]))
    q, q_dot = x[:, :n], x[:, n:]
    q_ddot = (u @ Bf.T - q_dot @ C.T - q @ K.T) @ Minv.T
    return q, q_dot, q_ddot


def simulate_decoupled(crossing):
    """The decoupled counterpart of ``vbikit.solve.simulate(crossing)`` (module docstring): a
    ``CrossingResult`` on the same time grid; its ``wheel_forces`` are the tire forces of the
    vehicle on the computed surface."""
    from vbikit._blas import single_thread_blas

    with single_thread_blas():  # small products of long histories: BLAS threads only contend (vbikit._blas)
        return _simulate_decoupled(crossing)


def _simulate_decoupled(crossing):
    from vbikit.solve.result import CrossingResult

    time = _time_grid(crossing)
    xi, xi_dot, xi_ddot = bridge_under_forces(crossing, time)
    vehicle = crossing.vehicles[0].vehicle
    surface = surface_under_wheels(crossing, time, xi)
    q, q_dot, q_ddot = vehicle_on_surface(vehicle, time, surface)
    rows = np.array([w.row for w in vehicle.wheels])
    kw = np.array([w.stiffness for w in vehicle.wheels])
    forces = kw * (rows @ q.T).T * -1.0 + kw * surface  # tire forces, upward on the vehicle [N]
    front = crossing.front_positions(time)
    speed = crossing.travel_speed(time)
    fields = {f.name for f in dataclasses.fields(CrossingResult)}
    kwargs = dict(crossing=crossing, time=time, dt=float(time[1] - time[0]), front_position=front, speed=speed, xi=xi,
                  xi_dot=xi_dot, xi_ddot=xi_ddot, q=q, q_dot=q_dot, q_ddot=q_ddot, wheel_forces=forces,
                  contact_lengths=np.zeros_like(forces))
    return CrossingResult(**{k: v for k, v in kwargs.items() if k in fields})


def relative_rms_error(approx: NDArray[np.float64], reference: NDArray[np.float64]) -> float:
    """‖approx − reference‖₂ / ‖reference‖₂ over the common samples (NaN for a zero reference)."""
    n = min(approx.size, reference.size)
    a, r = np.asarray(approx[:n], float), np.asarray(reference[:n], float)
    ok = np.isfinite(a) & np.isfinite(r)
    norm = math.sqrt(float(np.sum(r[ok] ** 2)))
    return math.sqrt(float(np.sum((a[ok] - r[ok]) ** 2))) / norm if norm > 0 else math.nan
