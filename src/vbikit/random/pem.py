"""Time-varying standard deviations of a crossing's responses on a random road by the
pseudo-excitation method (PEM).

Linear system.  While every tire point stays in contact, the coupled equations of
``vbikit.solve.kernels`` (paper Eq. 9, u = [ξ; q]) are linear, with the road entering the load
linearly (``kernels.assemble``):

    M(t) ü + C(t) u̇ + K(t) u = F₀(t) + Σ_p b_p(t) (k_p r_p(t) + c_p ṙ_p(t)),
    b_p = [−φ_p(x_p(t)); h_w(p)],  r_p = r(x_p(t)),  ṙ_p = ẋ_p r'(x_p(t)),

so u = u₀ + y with u₀ the smooth-road crossing (the mean) and y the zero-mean response to the
road r, a stationary Gaussian process with one-sided PSD G_d(n) [m³/cycle] (paper Eq. 7,
ISO 8608).

Pseudo-excitation (Lin et al. 2005 "Pseudo-excitation algorithm for nonstationary random
seismic responses", Eng. Struct. 27:1609; for vehicle–bridge systems Lu, Lin, Kennedy &
Williams 2009, Computers & Structures 87:177–185): for every wavenumber line n_k of width Δn_k
(``vbikit.random.lines``) the pseudo-road

    r̃_k(x) = √(G_d(n_k) Δn_k) · exp(i 2π n_k x),   ṙ̃_k = i 2π n_k ẋ_p r̃_k

drives the same equations from the same (linear) static start, giving the complex pseudo
response ỹ_k(t); then

    Var y(t) = Σ_k |ỹ_k(t)|²,   Cov(y, z)(t) = Σ_k Re(ỹ_k z̃_k*)                        (PEM)

for any two responses y, z linear in u, u̇, ü, r, ṙ.  Each contact point sees the road at its own
x_p(t), so axle lags and the points of a multi-point tire (whose average is the tire's
wavelength filter) are exact.  Two wheel lines with the road's coherence model
r_R = c r_L + √(1 − c²) r_I (``vbikit.road.psd.correlated_profile``) are two independent
pseudo-inputs per line: (r_L, r_R) = (1, c)·r̃ and (0, √(1 − c²))·r̃.

Integration: Newmark's average-acceleration rule, ``substeps`` steps per step of the engine's
time grid (one inverse of the real effective matrix per step, all lines as right-hand sides), from the static equilibrium
K(t₀) ỹ₀ = F̃(t₀) (zero rates; the engine's own start, ``vbikit.solve.system.static_state``).

Assumptions (where it fails): contact everywhere (no lift-off: check the lift-off probability),
linear tires (disk and rigid-disk tires are geometric nonlinear and are refused), a Gaussian
stationary road given by its PSD (defects and measured profiles are not random).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from vbikit.random.lines import Lines, band_lines
from vbikit.road.psd import RoadPSD
from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.plan import time_grid
from vbikit.solve.system import KernelData, kernel_data, point_positions

log = logging.getLogger(__name__)


class NonlinearTireError(ValueError):
    """The pseudo-excitation method needs a linear system: disk tires are refused."""


@dataclass(frozen=True)
class PseudoRoad:
    """The random road as pseudo-inputs: its PSD (band included) and the right line's coherence c
    (``two_lines`` False: one line under every wheel, the paper's identical lines)."""

    psd: RoadPSD
    coherence: float = 1.0
    two_lines: bool = False

    def __post_init__(self) -> None:
        if not 0.0 <= self.coherence <= 1.0:
            raise ValueError(f"right_coherence must be in [0, 1], got {self.coherence!r}")

    def line_factors(self) -> NDArray[np.float64]:
        """(n_sets, 2): the factor of each independent pseudo-input on road line 0 (left) and 1
        (right)."""
        if not self.two_lines or self.coherence >= 1.0:
            return np.array([[1.0, 1.0]])
        c = self.coherence
        return np.array([[1.0, c], [0.0, np.sqrt(1.0 - c * c)]])


@dataclass(frozen=True)
class Probes:
    """What to read: deck points (``shapes`` (n_pts, n_m): φ at each point) — displacement,
    velocity, acceleration, and bottom-fibre strain with ``strain_shapes`` (n_pts, n_m) (the
    bridge's ``strain_shapes`` at the points; default none: σ = 0); every vehicle DOF —
    displacement and acceleration; every wheel's contact force."""

    shapes: NDArray[np.float64]
    strain_shapes: NDArray[np.float64] | None = None


@dataclass
class PEMResult:
    """Variances over time of the random part of every probe.

    ``time`` (n_t,) [s]; per name (n_t, n_channels) arrays: ``var`` (Σ_k |ỹ_k|²), ``coarse``
    (the same on every second line, twice as wide: the grid check); ``cov_dv`` Cov(displacement,
    velocity) of the deck points; ``lambda1`` Σ_k |ỹ_k||ẏ̃_k| of the deck points (the first
    non-stationary spectral moment of the displacement).  ``lines`` the wavenumber lines used.
    """

    time: NDArray[np.float64]
    lines: Lines
    var: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    coarse: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    cov_dv: NDArray[np.float64] | None = None
    lambda1: NDArray[np.float64] | None = None
    lines_displacement: NDArray[np.float64] | None = None

    def sample_displacement(self, n: int, seed: int = 0, chunk: int = 256):
        """``n`` histories (n, n_t, n_pt) of the deck points' random displacement, Gaussian with
        exactly PEM's covariance: y(t) = Σ_k Re(ỹ_k(t) w_k), w_k = a_k + i b_k with a_k, b_k independent
        standard normal (so Cov(y(t), y(s)) = Σ_k Re(ỹ_k(t) ỹ_k(s)*)), yielded in chunks of ``chunk``.
        Needs ``pseudo_excitation(..., keep_lines=True)``."""
        if self.lines_displacement is None:
            raise ValueError("the pseudo responses of every line were not kept: use keep_lines=True")
        rng = np.random.default_rng(seed)
        h = self.lines_displacement  # (n_t, n_pt, 2L') float: [Re ỹ_k, Im ỹ_k] interleaved
        for start in range(0, n, chunk):
            m = min(chunk, n - start)
            w = rng.standard_normal((h.shape[2], m))
            w[1::2] *= -1.0  # Re(ỹ w) = Re ỹ · a − Im ỹ · b
            flat = h.reshape(-1, h.shape[2]) @ w  # one product: (n_t·n_pt, m)
            yield np.moveaxis(flat.reshape(h.shape[0], h.shape[1], m), 2, 0)

    def std(self, name: str) -> NDArray[np.float64]:
        """σ(t) [unit of the output] of output ``name``."""
        return np.sqrt(self.var[name])

    def grid_change(self, name: str) -> float:
        """max_t |σ − σ_coarse| / max_t σ of ``name``'s channels: the midpoint rule on every line
        against every second line (an error estimate of the coarser grid, so an upper bound for the
        grid's)."""
        s, c = np.sqrt(self.var[name]), np.sqrt(np.maximum(self.coarse[name], 0.0))
        top = float(s.max(initial=0.0))
        return float(np.abs(s - c).max(initial=0.0) / top) if top > 0 else 0.0


#: float work (columns × n²) of one block of lines: keeps OpenBLAS calls single-threaded
BLOCK_WORK = 240_000

NAMES = ("displacement", "velocity", "acceleration", "strain", "vehicle_displacement", "vehicle_acceleration",
         "wheel_force")


def check_linear(crossing: Crossing) -> None:
    """Refuse crossings the linear method cannot represent (disk / rigid-disk tires)."""
    cp = crossing.contact
    if bool(np.any(cp.gated)) or bool(np.any(cp.wheel_envelope)):
        raise NonlinearTireError(
            "random vibration by pseudo-excitation needs linear tires (point or multipoint); disk and rigid-disk "
            "tires are geometric nonlinear: use Monte Carlo (several road seeds) for them")


def pseudo_excitation(crossing: Crossing, road: PseudoRoad, probes: Probes, dt: float,
                      lines: Lines | None = None, data: KernelData | None = None, substeps: int = 2,
                      keep_lines: bool = False) -> PEMResult:
    """Variance histories of the probes' random parts on ``crossing``'s time grid of step ``dt`` [s].

    Parameters
    ----------
    crossing : Crossing
        The crossing (its own road is ignored: the random road is ``road``).
    road : PseudoRoad
        The road's PSD, band and coherence of the two wheel lines.
    probes : Probes
        The deck points to read.
    dt : float
        Time step [s] (the engine's for the same crossing on a sampled road).
    lines : Lines, optional
        Wavenumber lines (default ``band_lines`` over the PSD's band).
    data : KernelData, optional
        The crossing's kernel data if already built.
    keep_lines : bool
        Keep every line's pseudo displacement at the deck points (n_t × n_pt × 2 lines floats) for
        ``PEMResult.sample_displacement``.
    substeps : int
        Newmark steps per output step ``dt`` (default 2: the average-acceleration rule's period
        error, ≈ (ω h)²/12, is 4 × smaller than at ``dt``; on the paper's beam with the engine's step
        the midspan acceleration's σ is then within 0.7 % of the converged one, 6.5 % with 1).
    """
    check_linear(crossing)
    data = kernel_data(crossing) if data is None else data
    lines = band_lines(road.psd.n_min, road.psd.n_max) if lines is None else lines
    if not dt > 0:
        raise ValueError(f"dt must be > 0 s, got {dt!r}")
    if int(substeps) != substeps or substeps < 1:
        raise ValueError(f"substeps must be an integer >= 1, got {substeps!r}")
    n_out = time_grid(crossing, dt).n_steps + 1
    h = dt / substeps
    time = crossing.start_time + dt * np.arange(n_out)
    fine = crossing.start_time + h * np.arange(substeps * (n_out - 1) + 1)
    travel, speed = crossing.travel(fine), crossing.travel_speed(fine)
    n_t = n_out
    n_m, n_d, n_p = data.n_modes, data.n_dof, data.n_points
    n = n_m + n_d
    pts, veh = data.points, data.vehicles
    factors = road.line_factors()  # (S, 2)
    n_sets = factors.shape[0]
    line_of = np.minimum(pts.line, 1) if road.two_lines else np.zeros(n_p, np.int64)
    amp = np.sqrt(road.psd(lines.n) * lines.width)  # (L,)
    coef = np.concatenate([factors[s, line_of][:, None] * amp[None, :] for s in range(n_sets)], axis=1)  # (P, S·L)
    wave = 2.0 * np.pi * np.tile(lines.n, n_sets)  # (S·L,)
    k_p, c_p = pts.stiffness, pts.damping
    coef_k, coef_cw = coef * k_p[:, None], coef * c_p[:, None] * wave[None, :]  # k_p r̃ and c_p ṙ̃/(i ẋ_p), per exp
    h_w = veh.wheel_rows  # (n_w, n_d)
    n_w = data.n_wheels
    wsum = np.zeros((n_w, n_p))
    wsum[pts.wheel, np.arange(n_p)] = 1.0
    kw, cw = wsum * k_p, wsum * c_p  # (n_w, P): Σ_{p∈w} k_p, c_p
    coarse_w = np.repeat(np.tile(lines.coarse_weights(), n_sets), 2)  # per float column

    mass, damp, stiff = (np.zeros((n, n)) for _ in range(3))
    load = np.zeros(n)
    phi, dphi = np.zeros((n_p, n_m)), np.zeros((n_p, n_m))
    zero, active = np.zeros(n_p), np.ones(n_p, bool)

    def system(i: int):
        x, vx = point_positions(data, travel[i], speed[i])
        phi[:], dphi[:] = 0.0, 0.0
        kernels.assemble(x, vx, zero, zero, data.modes, veh, pts, phi, dphi, np.zeros(n_p, bool), active,
                         mass, damp, stiff, load)
        return x, vx

    out_shapes = probes.shapes
    strain_shapes = np.zeros_like(out_shapes) if probes.strain_shapes is None else np.atleast_2d(probes.strain_shapes)
    n_pt = out_shapes.shape[0]
    var = {name: np.zeros((n_t, size)) for name, size in zip(NAMES, (n_pt, n_pt, n_pt, n_pt, n_d, n_d, n_w))}
    coarse = {name: np.zeros_like(v) for name, v in var.items()}
    cov_dv, lam1 = np.zeros((n_t, n_pt)), np.zeros((n_t, n_pt))
    kept = np.zeros((n_t, n_pt, 2 * wave.size)) if keep_lines else None

    def fl(z):  # complex (r, L') → float view (r, 2L')
        return np.ascontiguousarray(z).view(np.float64)

    def record(i, blk, u, v, a, g_w, wheel_maps):
        a_xi, a_dxi, a_q, a_dq = wheel_maps
        force = a_xi @ u[:n_m] + a_dxi @ v[:n_m] + a_q @ u[n_m:] + a_dq @ v[n_m:] + g_w
        d, vel = out_shapes @ u[:n_m], out_shapes @ v[:n_m]
        cw2 = coarse_w[2 * blk.start:2 * blk.stop]
        for name, z in zip(NAMES, (d, vel, out_shapes @ a[:n_m], strain_shapes @ u[:n_m], u[n_m:], a[n_m:], force)):
            z2 = z * z
            var[name][i] += z2.sum(axis=1)
            coarse[name][i] += z2 @ cw2
        cov_dv[i] += (d * vel).sum(axis=1)
        if kept is not None:
            kept[i, :, 2 * blk.start:2 * blk.stop] = d
        lam1[i] += (np.hypot(d[:, 0::2], d[:, 1::2]) * np.hypot(vel[:, 0::2], vel[:, 1::2])).sum(axis=1)

    def forcing(phase, vx, blk):
        """The pseudo-loads F̃ (n, 2L') and each wheel's road force Σ_{p∈w} k_p r̃_p + c_p ṙ̃_p (n_w, 2L')
        of the lines ``blk``; r̃_p = coef·exp(i 2π n x_p), ṙ̃_p = i 2π n ẋ_p r̃_p."""
        g = fl(phase * (coef_k[:, blk] + 1j * vx[:, None] * coef_cw[:, blk]))
        g_w = wsum @ g
        f = np.empty((n, g.shape[1]))
        f[:n_m] = -(phi.T @ g)
        f[n_m:] = h_w.T @ g_w
        return f, g_w

    def wheel_maps(vx):
        """F_w = Σ_{p∈w} k_p (φ_p ξ + r_p − h_w q) + c_p (φ_p ξ̇ + ẋ_p φ'_p ξ + ṙ_p − h_w q̇): the maps of
        ξ, ξ̇, q, q̇ (the engine's contact law, linear part)."""
        return (kw @ phi + (cw * vx) @ dphi, cw @ phi, -kw.sum(axis=1)[:, None] * h_w,
                -cw.sum(axis=1)[:, None] * h_w)

    # lines in blocks: every BLAS call small enough to stay on one thread (a machine's other work
    # makes threaded calls of this size slower, not faster)
    size = max(8, int(BLOCK_WORK // (2 * n * n)))
    blocks = [slice(j, min(j + size, wave.size)) for j in range(0, wave.size, size)]
    # start: static equilibrium of the pseudo-loads (zero rates and accelerations, as the engine)
    x, vx = system(0)
    maps = wheel_maps(vx)
    phase, state = [], []
    for blk in blocks:
        ph = np.exp(1j * np.outer(x, wave[blk]))  # (P, lines): exp(i 2π n_k x_p)
        f, g_w = forcing(ph, vx, blk)
        u = np.linalg.solve(stiff, f)
        v, a = np.zeros_like(u), np.zeros_like(u)
        record(0, blk, u, v, a, g_w, maps)
        phase.append(ph)
        state.append((u, v, a))
    c0, c1 = 4.0 / h**2, 2.0 / h
    forward = pts.direction[:, None] > 0
    one_way = bool(np.all(forward)) and travel.shape[1] == 1
    for i in range(1, fine.size):
        x, vx = system(i)
        maps = wheel_maps(vx)
        inv = np.linalg.inv(stiff + c0 * mass + c1 * damp)  # small (n × n): a product per block is cheaper than LU solves
        # exp(i 2π n (x + Δx)) = exp(i 2π n x)·exp(i 2π n Δx), Δx = dir_p Δs_v: one factor per vehicle
        step = np.exp(1j * np.outer(travel[i] - travel[i - 1], wave))  # (V, S·L)
        for k, blk in enumerate(blocks):
            if one_way:  # one vehicle driving +x: every point's factor is the same
                phase[k] *= step[0, blk]
            else:
                fac = step[pts.vehicle][:, blk]
                phase[k] *= np.where(forward, fac, fac.conj())
            u, v, a = state[k]
            f, g_w = forcing(phase[k], vx, blk)
            rhs = f + mass @ (c0 * u + 2.0 * c1 * v + a) + damp @ (c1 * u + v)
            u_new = inv @ rhs
            a_new = c0 * (u_new - u) - 2.0 * c1 * v - a
            v = v + 0.5 * h * (a + a_new)
            state[k] = (u_new, v, a_new)
            if i % substeps == 0:
                record(i // substeps, blk, u_new, v, a_new, g_w, maps)
    log.info("pseudo-excitation: %d lines × %d input(s), %d steps of %.3g s", lines.size, n_sets, fine.size - 1, h)
    return PEMResult(time, lines, var, coarse, cov_dv, lam1, kept)
