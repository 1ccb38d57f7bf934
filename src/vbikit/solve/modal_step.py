"""Step maps of the implicit integrators: each bridge mode over one step, and the vehicle step.

A mode ξ̈ + 2ζωξ̇ + ω²ξ = p(t) whose load p is linear over the step [t_n, t_n + h] moves by

    ξ_{n+1} = a11 ξ_n + a12 ξ̇_n + b1 p_n + c1 p_{n+1}
    ξ̇_{n+1} = a21 ξ_n + a22 ξ̇_n + b2 p_n + c2 p_{n+1}

``exact_step`` gives the exact coefficients — the "piecewise exact" recurrence of Nigam &
Jennings (1969), *Bull. Seismol. Soc. Am.* 59(2), 909–922 (Chopra, *Dynamics of Structures*,
§5.2): exact for any h, so no mode limits the step.  The coefficients are Chopra's closed form
(Table 5.2.1) for ζ < 1 and ωh ≥ 0.5; below that (where the closed form's load terms cancel to
O((ωh)²)) and for ζ ≥ 1 the load part is read from the exponential of the augmented linear
system (ξ, ξ̇/ω, p/ω², ṗ/ω³) in the dimensionless time ωt, and the free part is e^{−ζωh}(cos,
sin of ω_D h) (``tests/unit/test_modal_step.py`` checks them against the closed form).  ``newmark_step`` gives
the same map for Newmark's average-acceleration rule (γ = 1/2, β = 1/4), so that Newmark runs
through the same partitioned kernel.  ``vehicle_step`` is the vehicles' map over the step
with their nominal tires on the contact surface, exact (exponential of the augmented
first-order system, the wheel loads linear over the step), ``newmark_vehicle_step``
Newmark's (``vbikit.solve.kernels.implicit``).
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import Kept
from vbikit.solve.kernels import ModalStep, Vehicles, VehicleStep
from vbikit.solve.kernels.bundles import FusedVehicleStep
from vbikit.solve.kernels.lean import wheel_entries

#: the vehicles' step maps (``vehicle_step``) already made in this process, by the exact bytes of
#: their inputs and the step (a study or repeated runs ask for the same few maps thousands of times;
#: each costs a matrix exponential).  Every later crossing with the same inputs shares a map's arrays,
#: so nothing may write to them (they stay writeable only because numba compiles a separate kernel
#: for read-only arrays).
_MAPS: "Kept[tuple, VehicleStep]" = Kept(256)
#: the bridge's step maps (``exact_step``) likewise, kept apart from the vehicles': a traffic stream's
#: events each have vehicles of their own, so their maps come and go and would push out the bridge's
#: maps of the steps that recur (a study's crossings, events at a speed met before)
_MODAL_MAPS: "Kept[tuple, ModalStep]" = Kept(512)
#: what the step maps of one set of vehicles share whatever the step and the hold (``_vehicle_terms``), by the exact
#: bytes of the vehicles' inputs: a run of the exact integrator asks for both holds' maps of its vehicles (its run-in,
#: ``vbikit.solve.run_in``, for the linear one), and a traffic stream's events each have vehicles of their own
_TERMS: "Kept[tuple, _VehicleTerms]" = Kept(16)
#: the lean kernels' fused maps of the step maps in ``_MAPS`` (``fused_step``), by the step map's
#: identity; each entry holds its step map, so no other object can have that identity while it is kept
_FUSED: "Kept[int, tuple[VehicleStep, FusedVehicleStep]]" = Kept(256)


def _input_key(kind: str, h: float, arrays) -> tuple:
    """The key of a step map: its kind, h and every input array's shape, dtype and bytes."""
    return (kind, float(h)) + _arrays_key(arrays)


def _arrays_key(arrays) -> tuple:
    """Every array's shape, dtype and bytes (``_input_key``'s part that the arrays give)."""
    return tuple((a.shape, a.dtype.str, a.tobytes()) for a in (np.ascontiguousarray(x) for x in arrays))


def expm(a: NDArray[np.float64]) -> NDArray[np.float64]:
    """Matrix exponential of a (..., n, n) stack: scaling and squaring with an 18-term Taylor
    series (‖A‖₁/2^s ≤ 1/2, truncation below 1e-17 relative; Moler & Van Loan 2003, method 3), one
    s for the whole stack (the largest norm's; ``expm_each``: each matrix its own).  For the small
    matrices here it is much cheaper than a general routine."""
    a = np.asarray(a, float)
    squarings = _squarings(float(np.abs(a).sum(axis=-2).max(initial=0.0)))
    result = _taylor(a / 2.0**squarings)
    work = np.empty(a.shape)
    for _ in range(squarings):
        np.matmul(result, result, out=work)
        result, work = work, result
    return result


def expm_each(a: NDArray[np.float64]) -> NDArray[np.float64]:
    """``expm`` of each matrix of the stack ``a`` (k, n, n) on its own scale: the same numbers as
    ``expm(a[i])`` for every i, in one series for the stack (the blocks of several vehicles)."""
    a = np.asarray(a, float)
    squarings = [_squarings(float(norm)) for norm in np.abs(a).sum(axis=-2).max(axis=-1, initial=0.0)]
    result = _taylor(a / np.array([2.0**s for s in squarings])[:, None, None])
    for step in range(max(squarings, default=0)):
        more = [i for i, s in enumerate(squarings) if s > step]
        if len(more) == len(squarings):
            result = result @ result
        else:
            result[more] = result[more] @ result[more]
    return result


def _squarings(norm: float) -> int:
    """The squarings s of ``expm`` for a matrix of 1-norm ``norm``: ‖A‖₁/2^s ≤ 1/2."""
    return max(0, int(np.ceil(np.log2(norm / 0.5)))) if norm > 0.5 else 0


#: the Taylor series' degree (``_taylor``) and the coefficients 1/k! of its Paterson–Stockmeyer blocks:
#: row j holds those of B_j = Σ_{i < 4} c_{4j+i} Xⁱ (zero beyond the degree)
TAYLOR_DEGREE = 18
_BLOCK_COEFFICIENTS = np.array([[1.0 / math.factorial(4 * j + i) if 4 * j + i <= TAYLOR_DEGREE else 0.0
                                 for i in range(4)] for j in range(TAYLOR_DEGREE // 4 + 1)])


def _taylor(x: NDArray[np.float64]) -> NDArray[np.float64]:
    """Σ_{k ≤ 18} xᵏ/k! of each matrix of the stack ``x``, by Paterson & Stockmeyer's scheme (SIAM J.
    Comput. 2(1), 1973, 60–66; Higham, *Functions of Matrices*, 2008, §4.2): with X⁴ = (X²)²,

        Σ_k Xᵏ/k! = B_0 + X⁴(B_1 + X⁴(B_2 + X⁴(B_3 + X⁴ B_4))),   B_j = Σ_{i < 4} Xⁱ/(4j + i)!,

    seven matrix products (X², X³, X⁴ and four Horner steps) instead of the eighteen of the term
    recursion, and the five blocks as one product of their coefficients with the stacked I, X, X², X³:
    the same sum to round-off (a block's terms are at most 1/2⁴ of the last one's, ‖X‖₁ ≤ 1/2)."""
    powers = np.zeros((4,) + x.shape)  # I, X, X², X³ of each matrix of the stack
    diagonal = np.arange(x.shape[-1])
    powers[0][..., diagonal, diagonal] = 1.0
    powers[1] = x
    np.matmul(x, x, out=powers[2])
    np.matmul(powers[2], x, out=powers[3])
    x4 = powers[2] @ powers[2]
    blocks = (_BLOCK_COEFFICIENTS @ powers.reshape(4, -1)).reshape((len(_BLOCK_COEFFICIENTS),) + x.shape)
    result, work = blocks[-1].copy(), np.empty(x.shape)
    for block in blocks[-2::-1]:
        np.matmul(x4, result, out=work)
        result, work = work, result
        result += block
    return result


#: the load holds over a step: the degree of the polynomial the loads follow between step ends, through
#: p_n, p_{n+1} (linear, first-order hold) or through p_{n−1}, p_n, p_{n+1} (quadratic)
LINEAR, QUADRATIC = 1, 2
HOLDS = (LINEAR, QUADRATIC)


def exact_step(omega: NDArray[np.float64], zeta: NDArray[np.float64], h: float, hold: int = LINEAR) -> ModalStep:
    """Exact transition of modes ω [rad/s] > 0, ζ [-] ≥ 0 over ``h`` [s] with the load held linear
    (``hold`` = ``LINEAR``: d1 = d2 = 0) or quadratic (``QUADRATIC``, ``quadratic_hold``) over the step
    (made once per ω, ζ, h, hold in a process and shared: not to be written to)."""
    omega = np.asarray(omega, float)
    zeta = np.asarray(zeta, float)
    if np.any(omega <= 0):
        raise ValueError("exact modal stepping needs natural frequencies > 0")
    if hold not in HOLDS:
        raise ValueError(f"hold must be one of {HOLDS} (the load polynomial's degree), got {hold!r}")
    return _MODAL_MAPS.get(_input_key(f"exact{hold}", h, (omega, zeta)), lambda: _exact_step(omega, zeta, h, hold))


def _exact_step(omega: NDArray[np.float64], zeta: NDArray[np.float64], h: float, hold: int = LINEAR) -> ModalStep:
    """``exact_step`` made afresh: the linear hold's coefficients, then the quadratic's from them
    (``quadratic_hold``)."""
    w, theta = omega, omega * h
    out = {k: np.empty_like(omega) for k in ModalStep._fields}
    out["d1"][:] = 0.0
    out["d2"][:] = 0.0
    closed = (zeta < 1.0) & (theta >= 0.5)  # Chopra's closed form: no cancellation at ωh ≥ 0.5
    if np.any(closed):
        z, wc = zeta[closed], w[closed]
        r = np.sqrt(1.0 - z**2)
        wd = wc * r
        e = np.exp(-z * wc * h)
        sn, cs = np.sin(wd * h), np.cos(wd * h)
        k = wc**2
        wh = wc * h
        values = {
            "a11": e * (z / r * sn + cs), "a12": e * sn / wd, "a21": -e * wc / r * sn, "a22": e * (cs - z / r * sn),
            "b1": (2 * z / wh + e * (((1 - 2 * z**2) / (wd * h) - z / r) * sn - (1 + 2 * z / wh) * cs)) / k,
            "c1": (1 - 2 * z / wh + e * ((2 * z**2 - 1) / (wd * h) * sn + 2 * z / wh * cs)) / k,
            "b2": (-1 / h + e * ((wc / r + z / (h * r)) * sn + cs / h)) / k,
            "c2": (1 - e * (z / r * sn + cs)) / (k * h),
        }
        for key, val in values.items():
            out[key][closed] = val
    rest = ~closed
    if np.any(rest):  # the exponential of the augmented system, scaled by ωh ≤ 0.5 (or ζ ≥ 1)
        modes = _mode_terms(w, zeta)  # (what does not depend on h, per mode)
        every = bool(rest.all())

        def pick(values: NDArray[np.float64]) -> NDArray[np.float64]:
            return values if every else values[rest]

        wr, th, w2, w3 = pick(w), pick(theta), pick(modes.w2), pick(modes.w3)
        e = expm(pick(modes.augmented) * th[:, None, None])
        out["a11"][rest], out["a12"][rest] = e[:, 0, 0], e[:, 0, 1] / wr
        out["a21"][rest], out["a22"][rest] = wr * e[:, 1, 0], e[:, 1, 1]
        out["b1"][rest] = e[:, 0, 2] / w2 - e[:, 0, 3] / (w3 * h)
        out["c1"][rest] = e[:, 0, 3] / (w3 * h)
        out["b2"][rest] = e[:, 1, 2] / wr - e[:, 1, 3] / (w2 * h)
        out["c2"][rest] = e[:, 1, 3] / (w2 * h)
        under = rest & (zeta < 1.0)  # the free part in closed form (round-off exact)
        if np.any(under):
            tu = theta[under]
            r, zr, rw = modes.root[under], modes.z_over_r[under], modes.r_w[under]
            decay, sn, cs = np.exp(-zeta[under] * tu), np.sin(r * tu), np.cos(r * tu)
            out["a11"][under] = decay * (cs + zr * sn)
            out["a12"][under] = decay * sn / rw
            out["a21"][under] = -decay * w[under] * sn / r
            out["a22"][under] = decay * (cs - zr * sn)
    step = ModalStep(**out)
    return quadratic_hold(step, omega, zeta, h) if hold == QUADRATIC else step


def quadratic_hold(step: ModalStep, omega: NDArray[np.float64], zeta: NDArray[np.float64], h: float) -> ModalStep:
    """The exact map of ``step`` (the linear hold's, ``exact_step``) with the load QUADRATIC over the
    step, the Lagrange parabola through p_{n−1}, p_n, p_{n+1} (a three-point hold):

        p(t_n + s h) = p_n + s (p_{n+1} − p_{n−1})/2 + s² (p_{n+1} − 2p_n + p_{n−1})/2,   0 ≤ s ≤ 1.

    With E_k the end response (ξ, ξ̇) from rest to the load s^k/k! (k = 1, 2), the hold's coefficients
    are d = E_2 − E_1/2, b' = E_0 − 2E_2, c' = E_1/2 + E_2.  The linear hold is the same parabola with
    p_{n−1} = 2p_n − p_{n+1}, so b = b' + 2d and c = c' − d: only d is new, and b' = b − 2d, c' = c + d
    keep the linear hold's closed forms.  The free part (a11 … a22) is the same.  E_1, E_2: for ωh ≥ 0.5
    the polynomial particular solutions (t: t/ω² − 2ζ/ω³; t²: t²/ω² − 4ζt/ω³ + (8ζ² − 2)/ω⁴) less their
    free response through the step's own a11 … a22; below, where those terms cancel, the exponential of
    the augmented system (ξ, ξ̇/ω, p/ω², p′/ω², p″/ω²) in s (′ = d/ds).  Third-order accurate in h for
    a smooth load (the linear hold: second); checked against quadrature of the convolution integral
    (tests/unit/test_load_hold.py)."""
    w = np.asarray(omega, float)
    z = np.asarray(zeta, float)
    theta = w * h
    d1, d2 = np.empty_like(w), np.empty_like(w)
    closed = theta >= 0.5  # (as ``_exact_step``'s closed form: no cancellation there)
    if np.any(closed):
        wc, zc = w[closed], z[closed]
        a11, a12, a21, a22 = (getattr(step, k)[closed] for k in ("a11", "a12", "a21", "a22"))
        w2 = wc * wc
        b1_, c1_ = 1.0 / w2, -2.0 * zc / (w2 * wc)  # load t: x_p = b1_ t + c1_
        x1 = h * b1_ + c1_ - a11 * c1_ - a12 * b1_
        v1 = b1_ - a21 * c1_ - a22 * b1_
        b2_, c2_ = -4.0 * zc / (w2 * wc), (8.0 * zc * zc - 2.0) / (w2 * w2)  # load t²: x_p = t²/ω² + b2_ t + c2_
        x2 = h * h / w2 + h * b2_ + c2_ - a11 * c2_ - a12 * b2_
        v2 = 2.0 * h / w2 + b2_ - a21 * c2_ - a22 * b2_
        # E_1 = (response to t)/h, E_2 = (response to t²)/(2h²)
        d1[closed] = x2 / (2.0 * h * h) - 0.5 * x1 / h
        d2[closed] = v2 / (2.0 * h * h) - 0.5 * v1 / h
    rest = ~closed
    if np.any(rest):
        tr = theta[rest]
        a = np.zeros((tr.size, 5, 5))
        a[:, 0, 1] = tr
        a[:, 1, 0] = -tr
        a[:, 1, 1] = -2.0 * z[rest] * tr
        a[:, 1, 2] = tr
        a[:, 2, 3] = 1.0
        a[:, 3, 4] = 1.0
        e = expm(a)  # (ωh < 0.5 here: one scaling serves the stack)
        wr = w[rest]
        d1[rest] = (e[:, 0, 4] - 0.5 * e[:, 0, 3]) / (wr * wr)
        d2[rest] = (e[:, 1, 4] - 0.5 * e[:, 1, 3]) / wr
    return step._replace(b1=step.b1 - 2.0 * d1, b2=step.b2 - 2.0 * d2, c1=step.c1 + d1, c2=step.c2 + d2, d1=d1, d2=d2)


class _ModeTerms(NamedTuple):
    """``_exact_step``'s terms of modes ω, ζ that do not depend on the step: the augmented matrices
    (n, 4, 4) of (ξ, ξ̇/ω, p, ṗ) in units of ωh, ω², ω³ and, for ζ < 1 (NaN else), r = √(1 − ζ²), ζ/r and r·ω."""

    augmented: NDArray[np.float64]
    w2: NDArray[np.float64]
    w3: NDArray[np.float64]
    root: NDArray[np.float64]
    z_over_r: NDArray[np.float64]
    r_w: NDArray[np.float64]


#: ``_mode_terms`` of the mode sets seen, by their exact bytes (a stream's events share the bridge's modes
#: and differ in the step)
_MODE_TERMS: "Kept[tuple, _ModeTerms]" = Kept(16)


def _mode_terms(omega: NDArray[np.float64], zeta: NDArray[np.float64]) -> _ModeTerms:
    """``_ModeTerms`` of ``omega``, ``zeta`` (made once per mode set in a process; shared: not to be written)."""
    return _MODE_TERMS.get(_input_key("modes", 0.0, (omega, zeta)), lambda: _make_mode_terms(omega, zeta))


def _make_mode_terms(omega: NDArray[np.float64], zeta: NDArray[np.float64]) -> _ModeTerms:
    """``_mode_terms`` made afresh (the same arithmetic as each step's part of ``_exact_step`` had)."""
    a = np.zeros((omega.size, 4, 4))
    a[:, 0, 1] = 1.0
    a[:, 1, 0] = -1.0
    a[:, 1, 1] = -2.0 * zeta
    a[:, 1, 2] = 1.0
    a[:, 2, 3] = 1.0
    root = np.full(omega.size, np.nan)
    under = zeta < 1.0
    root[under] = np.sqrt(1.0 - zeta[under]**2)
    return _ModeTerms(a, omega**2, omega**3, root, zeta / root, root * omega)


def newmark_step(omega: NDArray[np.float64], zeta: NDArray[np.float64], h: float) -> ModalStep:
    """The same map for Newmark's average acceleration (γ = 1/2, β = 1/4) on each mode."""
    omega = np.asarray(omega, float)
    c, k = 2.0 * np.asarray(zeta, float) * omega, omega**2

    def advance(u, v, p0, p1):
        a0 = p0 - c * v - k * u
        a1 = (p1 - c * (v + 0.5 * h * a0) - k * (u + h * v + 0.25 * h * h * a0)) / (1.0 + 0.5 * h * c + 0.25 * h * h * k)
        return u + h * v + 0.25 * h * h * (a0 + a1), v + 0.5 * h * (a0 + a1)

    one, zero = np.ones_like(omega), np.zeros_like(omega)
    (a11, a21), (a12, a22) = advance(one, zero, zero, zero), advance(zero, one, zero, zero)
    (b1, b2), (c1, c2) = advance(zero, zero, one, zero), advance(zero, zero, zero, one)
    return ModalStep(a11, a12, a21, a22, b1, b2, c1, c2, zero, zero.copy())


def _nominal(vehicles: Vehicles) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Ĉ, K̂: the vehicles' damping and stiffness with each wheel's nominal tire on the ground."""
    rows = vehicles.wheel_rows
    c_hat = vehicles.damping + rows.T @ (vehicles.wheel_damping[:, None] * rows)
    k_hat = vehicles.stiffness + rows.T @ (vehicles.wheel_stiffness[:, None] * rows)
    return np.ascontiguousarray(c_hat), np.ascontiguousarray(k_hat)


def _vehicle_map(vehicles: Vehicles, transition: NDArray[np.float64], load0: NDArray[np.float64],
                 load1: NDArray[np.float64], constant: NDArray[np.float64], c_hat: NDArray[np.float64],
                 k_hat: NDArray[np.float64], load_past: NDArray[np.float64] | None = None,
                 k_z: NDArray[np.float64] | None = None) -> VehicleStep:
    """The ``VehicleStep`` of a step map z_{n+1} = T z_n + Lp G_{n−1} + L0 G_n + L1 G_{n+1} + b (``load_past``
    Lp: None, zero), with the maps the coupled solve needs: the end wheel loads are G = F + K_z z_{n+1}
    (the point forces F summed per wheel, S F, plus the nominal tire's k_w h_w·q + c_w h_w·q̇), so

        z_{n+1} = P (T z_n + Lp G_{n−1} + L0 G_n + b) + P L1 S F,     P = (I − L1 K_z)⁻¹,

    and the wheels' displacement and velocity h_w·q, h_w·q̇ respond to the wheel forces through
    ``wheel_q`` = H (P L1)[:n_d] and ``wheel_v`` = H (P L1)[n_d:] (n_w, n_w) (``k_z``: K_z if made already,
    ``_feedback``)."""
    n_d, rows = vehicles.gravity.size, vehicles.wheel_rows
    k_z = _feedback(vehicles) if k_z is None else k_z
    settle = np.linalg.inv(np.eye(2 * n_d) - load1 @ k_z) if n_d else np.zeros((0, 0))
    response = settle @ load1
    contiguous = np.ascontiguousarray
    past = np.zeros_like(load0) if load_past is None else contiguous(load_past)
    return VehicleStep(contiguous(transition), contiguous(load0), contiguous(load1), contiguous(constant), c_hat, k_hat,
                       contiguous(settle), contiguous(response), contiguous(rows @ response[:n_d]),
                       contiguous(rows @ response[n_d:]), past)


def _feedback(vehicles: Vehicles) -> NDArray[np.float64]:
    """K_z (n_w, 2 n_d) of ``_vehicle_map``: each wheel's nominal tire k_w h_w, c_w h_w on the state z = (q, q̇)."""
    n_d, rows = vehicles.gravity.size, vehicles.wheel_rows
    k_z = np.zeros((rows.shape[0], 2 * n_d))
    k_z[:, :n_d] = vehicles.wheel_stiffness[:, None] * rows
    k_z[:, n_d:] = vehicles.wheel_damping[:, None] * rows
    return k_z


def fused_step(vehicles: Vehicles, step: VehicleStep) -> FusedVehicleStep:
    """The lean kernels' fused maps of the step map ``step`` of ``vehicles`` (``FusedVehicleStep``):
    P Φ, P L0, P g and the wheel rows' nonzero entries, made once per step
    map object in a process (kept with it, by identity: ``vehicle_step`` hands out one object per
    inputs, so every crossing of a study or stream with the same vehicles shares them) and shared: not
    to be written to."""
    return _FUSED.get(id(step), lambda: (step, _fused_step(vehicles, step)))[1]


def _fused_step(vehicles: Vehicles, step: VehicleStep) -> FusedVehicleStep:
    """``fused_step`` made afresh."""
    c = np.ascontiguousarray
    return FusedVehicleStep(c(step.settle @ step.transition), c(step.settle @ step.load0),
                            c(step.settle @ step.constant), c(step.settle @ step.load_past),
                            *wheel_entries(vehicles.wheel_rows))


def vehicle_step(vehicles: Vehicles, h: float, hold: int = LINEAR) -> VehicleStep:
    """The vehicles' exact step map over ``h`` [s] with their nominal tires (k_w, c_w of each wheel)
    on the contact surface and the wheel loads G held linear (``LINEAR``) or quadratic (``QUADRATIC``,
    through G_{n−1}, G_n, G_{n+1}, as ``quadratic_hold``'s p) over the step: the exponential of the
    augmented first-order system (q, q̇, G, G', [G''], 1) in s = (t − t_n)/h (' = d/ds), exact for any h
    (made once per vehicles, h and hold in a process and shared: not to be written to)."""
    if hold not in HOLDS:
        raise ValueError(f"hold must be one of {HOLDS} (the load polynomial's degree), got {hold!r}")
    inputs = (vehicles.mass_inv, vehicles.damping, vehicles.stiffness, vehicles.wheel_rows, vehicles.wheel_damping,
              vehicles.wheel_stiffness, vehicles.gravity)
    arrays = _arrays_key(inputs)
    return _MAPS.get((f"vehicle{hold}", float(h)) + arrays,
                     lambda: _vehicle_step(vehicles, h, hold, _TERMS.get(arrays, lambda: _vehicle_terms(vehicles))))


class _VehicleTerms(NamedTuple):
    """The terms of the vehicles' step maps (``_vehicle_step``) that depend on neither the step nor the hold: Ĉ, K̂
    (``_nominal``), the DOF blocks [lo, hi) that nothing couples (``_blocks``), each block's wheels (None: one block,
    every wheel) and products (``_products``), and the wheel loads' feedback K_z (``_vehicle_map``)."""

    c_hat: NDArray[np.float64]
    k_hat: NDArray[np.float64]
    blocks: list[tuple[int, int]]
    wheels: list[NDArray[np.int64]] | None
    products: list[tuple[NDArray[np.float64], ...]]
    k_z: NDArray[np.float64]


def _vehicle_terms(vehicles: Vehicles) -> _VehicleTerms:
    """``_VehicleTerms`` of ``vehicles`` (made once per vehicles in a process and shared: not to be written to)."""
    c_hat, k_hat = _nominal(vehicles)
    k_z = _feedback(vehicles)
    if vehicles.gravity.size == 0:
        return _VehicleTerms(c_hat, k_hat, [], None, [], k_z)
    m_inv, rows, gravity = vehicles.mass_inv, vehicles.wheel_rows, vehicles.gravity
    blocks = _blocks(vehicles, c_hat, k_hat)
    if len(blocks) == 1:
        return _VehicleTerms(c_hat, k_hat, blocks, None, [_products(m_inv, c_hat, k_hat, rows, gravity)], k_z)
    wheel_dof = np.where(np.any(rows != 0.0, axis=1), np.argmax(rows != 0.0, axis=1), -1)  # -1: a wheel without DOFs
    wheels = [np.flatnonzero((wheel_dof >= lo) & (wheel_dof < hi)) for lo, hi in blocks]
    products = [_products(m_inv[lo:hi, lo:hi], c_hat[lo:hi, lo:hi], k_hat[lo:hi, lo:hi], rows[w, lo:hi], gravity[lo:hi])
                for (lo, hi), w in zip(blocks, wheels)]
    return _VehicleTerms(c_hat, k_hat, blocks, wheels, products, k_z)


def _blocks(vehicles: Vehicles, c_hat: NDArray[np.float64], k_hat: NDArray[np.float64]) -> list[tuple[int, int]]:
    """The contiguous diagonal blocks [lo, hi) of DOFs that no vehicle matrix (M⁻¹, Ĉ, K̂) nor any
    wheel row couples to another block: the vehicles of a combined vehicle (or finer).  Block i
    ends at k when no DOF ≤ k couples to one > k (the running maximum of each row's last coupled
    column equals k)."""
    rows = np.abs(vehicles.wheel_rows)
    pattern = (np.abs(vehicles.mass_inv) + np.abs(c_hat) + np.abs(k_hat) + rows.T @ rows) != 0.0
    pattern |= pattern.T
    n = pattern.shape[0]
    last = n - 1 - np.argmax(pattern[:, ::-1], axis=1)  # each row's last coupled column (a row has its diagonal)
    ends = np.flatnonzero(np.maximum.accumulate(np.maximum(last, np.arange(n))) == np.arange(n)) + 1
    return list(zip([0, *ends[:-1].tolist()], ends.tolist()))


def _block_exponential(m_inv, c_hat, k_hat, rows, gravity, h: float, hold: int):
    """The exponential of one block's augmented system (``_augmented``) over the step: (Φ, Lp, L0, L1, b)."""
    return _exponential_maps(_augmented(m_inv, c_hat, k_hat, rows, gravity, h, hold), gravity.size, rows.shape[0], hold)


def _exponential_maps(a: NDArray[np.float64], n_d: int, n_w: int, hold: int) -> tuple[NDArray[np.float64], ...]:
    """(Φ, Lp, L0, L1, b) of a block of ``n_d`` DOFs and ``n_w`` wheels from its augmented matrix ``a``
    (``_augmented``): its exponential, balanced (``_balancing``)."""
    d = _balancing(a, n_d, n_w, hold)
    return _block_maps(_unbalanced(expm(_balanced(a, d)), d), n_d, n_w, hold)


def _balancing(a: NDArray[np.float64], n_d: int, n_w: int, hold: int) -> NDArray[np.float64]:
    """Powers of two d of a diagonal similarity D B D⁻¹ (``_balanced``) that brings the augmented matrix
    B of a block (``_augmented``) to a small norm, so that its exponential takes few squarings (``expm``):
    q scaled by σ ≈ (‖h M⁻¹K̂‖₁ / h)^½ (a frequency of the block: the blocks q' = h q̇ and q̇' = −h M⁻¹K̂ q
    become σh and h M⁻¹K̂ / σ, both ≈ h ω instead of one of them h ω²), and the load's k-th derivative by
    4ᵏ (its chain's unit entries become 1/4).  exp(D B D⁻¹) = D exp(B) D⁻¹, and a power of two scales a
    number without rounding, so only the series sees another matrix."""
    d = np.ones(a.shape[-1])
    stiffness = float(np.abs(a[n_d:2 * n_d, :n_d]).sum(axis=0).max(initial=0.0))
    step = float(np.abs(a[:n_d, n_d:2 * n_d]).sum(axis=0).max(initial=0.0))
    if stiffness > 0.0 and step > 0.0:
        d[:n_d] = 2.0 ** round(0.5 * math.log2(stiffness / step))
    for k in range(1, hold + 1):
        d[2 * n_d + k * n_w:2 * n_d + (k + 1) * n_w] = 4.0**k
    return d


def _balanced(a: NDArray[np.float64], d: NDArray[np.float64]) -> NDArray[np.float64]:
    """D B D⁻¹ of ``a`` with D = diag(``d``)."""
    return a * (d[:, None] / d[None, :])


def _unbalanced(e: NDArray[np.float64], d: NDArray[np.float64]) -> NDArray[np.float64]:
    """D⁻¹ E D of ``e`` (the exponential of a ``_balanced`` matrix) with D = diag(``d``): the exponential of the original."""
    return e * (d[None, :] / d[:, None])


def _augmented(m_inv, c_hat, k_hat, rows, gravity, h: float, hold: int) -> NDArray[np.float64]:
    """One block's augmented system matrix B of (q, q̇, G, G', …, G⁽ʰᵒˡᵈ⁾, 1) in s = (t − t_n)/h over the
    step (``vehicle_step``): q' = h q̇, q̇' = h M⁻¹(F_G + Hᵀ G − Ĉ q̇ − K̂ q), G⁽ᵏ⁾' = G⁽ᵏ⁺¹⁾, so that
    exp(B) is the map over s = 0 … 1."""
    return _augmented_of(_products(m_inv, c_hat, k_hat, rows, gravity), rows.shape[0], h, hold)


def _products(m_inv, c_hat, k_hat, rows, gravity) -> tuple[NDArray[np.float64], ...]:
    """A block's M⁻¹K̂, M⁻¹Ĉ, M⁻¹Hᵀ and M⁻¹F_G (``_augmented``'s terms that depend on neither h nor the hold)."""
    return m_inv @ k_hat, m_inv @ c_hat, m_inv @ rows.T, m_inv @ gravity


def _augmented_of(products: tuple[NDArray[np.float64], ...], n_w: int, h: float, hold: int) -> NDArray[np.float64]:
    """``_augmented`` from a block's ``_products`` and its ``n_w`` wheels (the identities' unit entries set one by one:
    the numbers h I and I would put there)."""
    stiffness, damping, loads, gravity = products
    n_d = gravity.size
    n = 2 * n_d + (hold + 1) * n_w + 1
    a = np.zeros((n, n))
    dofs, wheels = np.arange(n_d), np.arange(n_w)
    a[dofs, n_d + dofs] = h
    a[n_d:2 * n_d, :n_d] = -h * stiffness
    a[n_d:2 * n_d, n_d:2 * n_d] = -h * damping
    a[n_d:2 * n_d, 2 * n_d:2 * n_d + n_w] = h * loads
    a[n_d:2 * n_d, -1] = h * gravity
    for k in range(hold):  # the load's chain of s-derivatives
        lo = 2 * n_d + k * n_w
        a[lo + wheels, lo + n_w + wheels] = 1.0
    return a


def _block_maps(e: NDArray[np.float64], n_d: int, n_w: int, hold: int) -> tuple[NDArray[np.float64], ...]:
    """(Φ, Lp, L0, L1, b) of a block from exp(B) ``e`` (``_block_exponential``), with E_k the columns of
    G⁽ᵏ⁾ (the end response to the load s^k/k!): linear hold (G' = G_{n+1} − G_n) Lp = 0, L0 = E_0 − E_1,
    L1 = E_1; quadratic (G' = (G_{n+1} − G_{n−1})/2, G'' = G_{n+1} − 2G_n + G_{n−1}, ``quadratic_hold``)
    Lp = E_2 − E_1/2, L0 = E_0 − 2E_2, L1 = E_1/2 + E_2."""
    z = slice(0, 2 * n_d)
    cols = [e[z, 2 * n_d + k * n_w:2 * n_d + (k + 1) * n_w] for k in range(hold + 1)]
    if hold == LINEAR:
        return e[z, z], np.zeros_like(cols[0]), cols[0] - cols[1], cols[1], e[z, -1]
    return e[z, z], cols[2] - 0.5 * cols[1], cols[0] - 2.0 * cols[2], 0.5 * cols[1] + cols[2], e[z, -1]


def _vehicle_step(vehicles: Vehicles, h: float, hold: int = LINEAR, terms: _VehicleTerms | None = None) -> VehicleStep:
    """``vehicle_step`` made afresh (``terms``: the vehicles' ``_vehicle_terms`` if made already).  The augmented
    matrix of several vehicles (or any DOF blocks that nothing couples, ``_blocks``) is block-diagonal up to the
    constant column, so its exponential is that of each block with its own wheels and gravity column (exact: the
    blocks of exp(A) of a block-diagonal A are the blocks' exponentials, and the constant state 1 has no
    dynamics); blocks cost Σ n_b³ instead of (Σ n_b)³."""
    n_d, n_w = vehicles.gravity.size, vehicles.wheel_rows.shape[0]
    terms = _vehicle_terms(vehicles) if terms is None else terms
    c_hat, k_hat, blocks = terms.c_hat, terms.k_hat, terms.blocks
    if n_d == 0:
        return _vehicle_map(vehicles, np.zeros((0, 0)), np.zeros((0, n_w)), np.zeros((0, n_w)), np.zeros(0), c_hat, k_hat,
                            k_z=terms.k_z)
    if terms.wheels is None:  # one block
        phi, past, l0, l1, const = _exponential_maps(_augmented_of(terms.products[0], n_w, h, hold), n_d, n_w, hold)
        return _vehicle_map(vehicles, phi, l0, l1, const, c_hat, k_hat, past, terms.k_z)
    transition, load0, load1 = np.zeros((2 * n_d, 2 * n_d)), np.zeros((2 * n_d, n_w)), np.zeros((2 * n_d, n_w))
    load_past = np.zeros((2 * n_d, n_w))
    constant = np.zeros(2 * n_d)
    wheels = terms.wheels
    augmented = [_augmented_of(products, w.size, h, hold) for products, w in zip(terms.products, wheels)]
    scales = [_balancing(a, hi - lo, w.size, hold) for a, (lo, hi), w in zip(augmented, blocks, wheels)]
    balanced = [_balanced(a, d) for a, d in zip(augmented, scales)]
    exponentials: list = [None] * len(blocks)
    for size in {a.shape for a in augmented}:  # blocks of one size (vehicles alike) in one series, each on its own scale
        alike = [i for i, a in enumerate(augmented) if a.shape == size]
        stack = expm_each(np.stack([balanced[i] for i in alike])) if len(alike) > 1 else [expm(balanced[alike[0]])]
        for i, e in zip(alike, stack):
            exponentials[i] = _unbalanced(e, scales[i])
    for (lo, hi), w, e in zip(blocks, wheels, exponentials):
        b, m = slice(lo, hi), hi - lo
        phi, past, l0, l1, const = _block_maps(e, m, w.size, hold)
        for i, rows_i in enumerate((b, slice(n_d + lo, n_d + hi))):  # its q, then its q̇ in the first-order state
            part = slice(i * m, (i + 1) * m)
            transition[rows_i, b], transition[rows_i, n_d + lo:n_d + hi] = phi[part, :m], phi[part, m:]
            load0[rows_i, w], load1[rows_i, w], constant[rows_i] = l0[part], l1[part], const[part]
            load_past[rows_i, w] = past[part]
    return _vehicle_map(vehicles, transition, load0, load1, constant, c_hat, k_hat, load_past, terms.k_z)


def newmark_vehicle_step(vehicles: Vehicles, h: float) -> VehicleStep:
    """The same map as ``vehicle_step`` by Newmark's average acceleration (γ = 1/2, β = 1/4)."""
    n_d, n_w = vehicles.gravity.size, vehicles.wheel_rows.shape[0]
    c_hat, k_hat = _nominal(vehicles)
    if n_d == 0:
        return _vehicle_map(vehicles, np.zeros((0, 0)), np.zeros((0, n_w)), np.zeros((0, n_w)), np.zeros(0), c_hat, k_hat)
    m_inv, rows = vehicles.mass_inv, vehicles.wheel_rows
    s_inv = np.linalg.inv(vehicles.mass + 0.5 * h * c_hat + 0.25 * h * h * k_hat)

    def advance(u, v, g0, g1, fg):  # columns are independent inputs
        a0 = m_inv @ (fg + rows.T @ g0 - c_hat @ v - k_hat @ u)
        a1 = s_inv @ (fg + rows.T @ g1 - c_hat @ (v + 0.5 * h * a0) - k_hat @ (u + h * v + 0.25 * h * h * a0))
        return np.vstack([u + h * v + 0.25 * h * h * (a0 + a1), v + 0.5 * h * (a0 + a1)])

    eye, zd, zw = np.eye(n_d), np.zeros((n_d, n_d)), np.zeros((n_w, n_d))
    transition = np.hstack([advance(eye, zd, zw, zw, zd), advance(zd, eye, zw, zw, zd)])
    ew, zdw, zww = np.eye(n_w), np.zeros((n_d, n_w)), np.zeros((n_w, n_w))
    load0 = advance(zdw, zdw, ew, zww, zdw)
    load1 = advance(zdw, zdw, zww, ew, zdw)
    col = np.zeros((n_d, 1))
    constant = advance(col, col, np.zeros((n_w, 1)), np.zeros((n_w, 1)), vehicles.gravity.reshape(n_d, 1))[:, 0]
    return _vehicle_map(vehicles, transition, load0, load1, constant, c_hat, k_hat)
