"""Time-varying standard deviations of a crossing's responses on a random road by the
pseudo-excitation method (PEM).

Linear system.  While every tire point stays in contact, the coupled equations of
``vbikit.solve.kernels`` (paper Eq. 9, u = [ξ; q]) are linear, with the road entering the load
linearly (``vbikit.solve.system.coupled_system``):

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

Integration (``method``): by default the engine's own integrator, exact modal stepping
(``vbikit.solve.kernels.implicit`` with ``vbikit.solve.modal_step.exact_step`` and
``vehicle_step``), which is linear for linear tires: per step one matrix maps every line's free
state and pseudo road load to its end-of-step modal loads and wheel forces (``_exact_lines``), all
lines as columns of one product, in the compiled loop of ``vbikit.random.kernel``; PEM and the
engine's Monte Carlo then estimate σ of the same system, discretised alike but for the holds of the
loads (the engine holds the deck's loads and the wheel loads quadratic over a step, PEM linear: a
difference of the step's own order, within the engine's step accuracy).  ``method="newmark"``: Newmark's
average-acceleration rule on the assembled equations, ``substeps`` steps per step of the engine's
time grid (one inverse of the real effective matrix per step, all lines as right-hand sides).
Both start from the static equilibrium K(t₀) ỹ₀ = F̃(t₀) (zero rates; the engine's own start,
``vbikit.solve.system.static_state``); with ``crossing.run_in`` > 0 the exact path starts the vehicles
from their state after the run-in on each line's pseudo-road, as the engine does on a sampled road
(``_run_in_state``: the harmonic solution of the run-in's recursion in closed form; the Newmark path
refuses a run-in).

Assumptions (where it fails): contact everywhere (no lift-off: check the lift-off probability),
linear tires (disk and rigid-disk tires are geometric nonlinear and are refused), a Gaussian
stationary road given by its PSD (defects and measured profiles are not random).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from vbikit._blas import single_thread_blas
from vbikit.random import kernel
from vbikit.random.lines import Lines, default_lines
from vbikit.road.psd import RoadPSD
from vbikit.solve import kernels
from vbikit.solve.crossing import Crossing
from vbikit.solve.plan import time_grid
from vbikit.solve.system import KernelData, coupled_system, kernel_data, point_positions

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
    displacement and acceleration; every wheel's contact force.

    ``state_rows`` (n_rows, 3 n_m + n_w), optional: more deck channels after the points, each
    linear in the end-of-step state [ξ; ξ̇; p; F_w] (p = ξ̈ + 2ζωξ̇ + ω²ξ the modal load, F_w the
    wheels' contact forces): its "displacement" channel is ``row · [ξ; ξ̇; p; F_w]`` (kept per line
    with ``keep_lines``), its velocity, acceleration and strain channels are 0.  A load effect by
    mode acceleration is built from such channels (``vbikit.random.response``)."""

    shapes: NDArray[np.float64]
    strain_shapes: NDArray[np.float64] | None = None
    state_rows: NDArray[np.float64] | None = None


@dataclass
class PEMResult:
    """Variances over time of the random part of every probe.

    ``time`` (n_t,) [s]; per name (n_t, n_channels) arrays: ``var`` (Σ_k |ỹ_k|²), ``coarse``
    (the same on every second line, twice as wide: the grid check); ``cov_dv`` Cov(displacement,
    velocity) of the deck points; ``lambda1`` Σ_k |ỹ_k||ẏ̃_k| of the deck points (the first
    non-stationary spectral moment of the displacement).  ``lines`` the wavenumber lines used;
    ``substeps`` the integrator's steps per output step.
    """

    time: NDArray[np.float64]
    lines: Lines
    var: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    coarse: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    cov_dv: NDArray[np.float64] | None = None
    lambda1: NDArray[np.float64] | None = None
    lines_displacement: NDArray[np.float64] | None = None
    substeps: int = 1

    def sample_displacement(self, n: int, seed: int = 0, chunk: int = 256):
        """``n`` histories (n, n_t, n_pt) of the deck points' random displacement, Gaussian with
        exactly PEM's covariance: y(t) = Σ_k Re(ỹ_k(t) w_k), w_k = a_k + i b_k with a_k, b_k independent
        standard normal (so Cov(y(t), y(s)) = Σ_k Re(ỹ_k(t) ỹ_k(s)*)), yielded in chunks of ``chunk``.
        Needs ``pseudo_excitation(..., keep_lines=True)``."""
        for y in self._sample_blocks(n, seed, chunk):
            yield np.moveaxis(y, 2, 0)

    def _sample_blocks(self, n: int, seed: int = 0, chunk: int = 256, channels: list[int] | None = None):
        """``sample_displacement``'s histories as (n_t, n_pt, m) blocks (the product's own layout,
        time outermost: a maximum over time reads contiguous rows); ``channels``: of those deck
        points only (the same random numbers, so the same histories of those points)."""
        if self.lines_displacement is None:
            raise ValueError("the pseudo responses of every line were not kept: use keep_lines=True")
        rng = np.random.default_rng(seed)
        h = self.lines_displacement  # (n_t, n_pt, 2L') float: [Re ỹ_k, Im ỹ_k] interleaved
        if channels is not None:
            h = np.ascontiguousarray(h[:, channels])
        for start in range(0, n, chunk):
            m = min(chunk, n - start)
            w = rng.standard_normal((h.shape[2], m))
            w[1::2] *= -1.0  # Re(ỹ w) = Re ỹ · a − Im ỹ · b
            yield (h.reshape(-1, h.shape[2]) @ w).reshape(h.shape[0], h.shape[1], m)  # one product: (n_t·n_pt, m)

    def scaled(self, factor: float) -> "PEMResult":
        """The result for the road's PSD times ``factor`` (the system is linear in the road): every
        variance and covariance times ``factor``, every pseudo response times √factor."""
        a = float(np.sqrt(factor))
        return PEMResult(self.time, self.lines, {k: v * factor for k, v in self.var.items()},
                         {k: v * factor for k, v in self.coarse.items()},
                         None if self.cov_dv is None else self.cov_dv * factor,
                         None if self.lambda1 is None else self.lambda1 * factor,
                         None if self.lines_displacement is None else self.lines_displacement * a, self.substeps)

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


#: the integrators of the pseudo responses (``pseudo_excitation(method=...)``) and their default substeps
METHODS = {"exact": 1, "newmark": 2}
#: steps whose coupled-solve maps are built together (memory ≈ 8 B × STEP_CHUNK × 26 × 100 on the demo)
STEP_CHUNK = 256


def pseudo_excitation(crossing: Crossing, road: PseudoRoad, probes: Probes, dt: float,
                      lines: Lines | None = None, data: KernelData | None = None, substeps: int | None = None,
                      keep_lines: bool = False, method: str = "exact") -> PEMResult:
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
        Wavenumber lines (default ``default_lines`` over the PSD's band).
    data : KernelData, optional
        The crossing's kernel data if already built.
    substeps : int, optional
        Integrator steps per output step ``dt`` (default ``METHODS[method]``: 1 for ``"exact"``, 2 for
        ``"newmark"``, whose average-acceleration period error ≈ (ω h)²/12 is then 4 × smaller: on
        the paper's beam the mid-span acceleration's σ within 0.7 % of the converged one, 6.5 % with 1).
    keep_lines : bool
        Keep every line's pseudo displacement at the deck points (n_t × n_pt × 2 lines floats) for
        ``PEMResult.sample_displacement``.
    method : str
        ``"exact"`` (default): the engine's default integrator, linear — every mode by its exact
        step, the vehicles by theirs, coupled through the end-of-step contact forces, whose linear
        solve is one matrix per step applied to all lines (``_exact_lines``).  ``"newmark"``: the
        coupled equations by Newmark's average acceleration (``_newmark_lines``; the former path,
        kept as a cross-check).
    """
    check_linear(crossing)
    if method not in METHODS:
        raise ValueError(f"method must be one of {sorted(METHODS)}, got {method!r}")
    if crossing.run_in > 0 and method != "exact":
        raise ValueError(f"crossing.run_in = {crossing.run_in:g} m: the pseudo-excitation's {method!r} path starts "
                         "the vehicles at rest; the run-in needs method = \"exact\" (the default)")
    substeps = METHODS[method] if substeps is None else substeps
    data = kernel_data(crossing) if data is None else data
    lines = default_lines(road.psd.n_min, road.psd.n_max) if lines is None else lines
    if not dt > 0:
        raise ValueError(f"dt must be > 0 s, got {dt!r}")
    if int(substeps) != substeps or substeps < 1:
        raise ValueError(f"substeps must be an integer >= 1, got {substeps!r}")
    run = _Run(crossing, road, probes, dt, lines, data, int(substeps), keep_lines)
    with single_thread_blas():  # products of a few dozen rows: BLAS threads would only contend
        (_exact_lines if method == "exact" else _newmark_lines)(run)
    log.info("pseudo-excitation (%s): %d lines × %d input(s), %d steps of %.3g s", method, lines.size,
             run.n_sets, run.fine.size - 1, run.h)
    return PEMResult(run.time, lines, run.var, run.coarse, run.cov_dv, run.lam1, run.kept, run.substeps)


class _Run:
    """What both integrators share: the time grids, the pseudo-road coefficients of every line, the
    static start and the accumulators of the variances."""

    def __init__(self, crossing, road, probes, dt, lines, data, substeps, keep_lines):
        n_out = time_grid(crossing, dt).n_steps + 1
        self.substeps, self.h = substeps, dt / substeps
        self.time = crossing.start_time + dt * np.arange(n_out)
        self.fine = crossing.start_time + self.h * np.arange(substeps * (n_out - 1) + 1)
        self.travel, self.speed = crossing.travel(self.fine), crossing.travel_speed(self.fine)
        self.data = data
        self.crossing = crossing
        n_m, n_d, n_p = data.n_modes, data.n_dof, data.n_points
        self.n_m, self.n_d, self.n_p, self.n = n_m, n_d, n_p, n_m + n_d
        pts = self.pts = data.points
        factors = road.line_factors()  # (S, 2)
        self.n_sets = n_sets = factors.shape[0]
        line_of = np.minimum(pts.line, 1) if road.two_lines else np.zeros(n_p, np.int64)
        amp = np.sqrt(road.psd(lines.n) * lines.width)  # (L,)
        coef = np.concatenate([factors[s, line_of][:, None] * amp[None, :] for s in range(n_sets)], axis=1)  # (P, S·L)
        self.wave = 2.0 * np.pi * np.tile(lines.n, n_sets)  # (S·L,)
        k_p, c_p = pts.stiffness, pts.damping
        # k_p r̃ and c_p ṙ̃/(i ẋ_p), per exp(i 2π n x_p)
        self.coef_k, self.coef_cw = coef * k_p[:, None], coef * c_p[:, None] * self.wave[None, :]
        self.n_w = n_w = data.n_wheels
        wsum = self.wsum = np.zeros((n_w, n_p))
        wsum[pts.wheel, np.arange(n_p)] = 1.0
        self.coarse_w = np.repeat(np.tile(lines.coarse_weights(), n_sets), 2)  # per float column
        self.forward = pts.direction[:, None] > 0
        self.one_way = bool(np.all(self.forward)) and self.travel.shape[1] == 1
        shapes = np.atleast_2d(probes.shapes)
        strain = np.zeros_like(shapes) if probes.strain_shapes is None else np.atleast_2d(probes.strain_shapes)
        rows = np.zeros((0, 3 * n_m + n_w)) if probes.state_rows is None else np.atleast_2d(probes.state_rows)
        if rows.shape[1] != 3 * n_m + n_w:
            raise ValueError(f"Probes.state_rows must have 3 n_modes + n_wheels = {3 * n_m + n_w} columns, "
                             f"got {rows.shape[1]}")
        n_sh, n_rows = shapes.shape[0], rows.shape[0]
        self.shapes = np.vstack([shapes, np.zeros((n_rows, n_m))])  # the state rows' channels: no φ, no strain
        self.strain_shapes = np.vstack([strain, np.zeros((n_rows, n_m))])
        self.state_rows = np.vstack([np.zeros((n_sh, 3 * n_m + n_w)), rows])  # (n_pt, 3 n_m + n_w)
        self.n_pt = n_pt = self.shapes.shape[0]
        self.var = {name: np.zeros((n_out, size)) for name, size in zip(NAMES, (n_pt, n_pt, n_pt, n_pt, n_d, n_d, n_w))}
        self.coarse = {name: np.zeros_like(v) for name, v in self.var.items()}
        self.cov_dv, self.lam1 = np.zeros((n_out, n_pt)), np.zeros((n_out, n_pt))
        self.kept = np.zeros((n_out, n_pt, 2 * self.wave.size)) if keep_lines else None

    def phase_step(self, phase, i, cols=slice(None)):
        """exp(i 2π n x_p(t_i)) from step i − 1's: Δx = dir_p Δs_v, one factor per vehicle."""
        step = np.exp(1j * np.outer(self.travel[i] - self.travel[i - 1], self.wave[cols]))  # (V, lines)
        if self.one_way:  # one vehicle driving +x: every point's factor is the same
            phase *= step[0]
        else:
            fac = step[self.pts.vehicle]
            phase *= np.where(self.forward, fac, fac.conj())

    def road_load(self, phase, vx, cols=slice(None)):
        """g_p = k_p r̃_p + c_p ṙ̃_p (P, lines) complex: r̃_p = coef·exp(i 2π n x_p), ṙ̃_p = i 2π n ẋ_p r̃_p."""
        return phase * (self.coef_k[:, cols] + 1j * vx[:, None] * self.coef_cw[:, cols])

    def static_start(self, cols=slice(None)):
        """The pseudo-static start: K(t₀) u₀ = F̃(t₀) (zero rates, the engine's own start); returns
        the phases, u₀ (n, lines) complex, and the system at t₀ (x, vx, φ, φ', K)."""
        data, n, n_m = self.data, self.n, self.n_m
        x, vx = point_positions(data, self.travel[0], self.speed[0])
        mass, damp, stiff, _, phi, dphi = coupled_system(data.modes, data.vehicles, self.pts, x, vx)
        phase = np.exp(1j * np.outer(x, self.wave[cols]))  # (P, lines): exp(i 2π n_k x_p)
        g = self.road_load(phase, vx, cols)
        f = np.empty((n, g.shape[1]), complex)
        f[:n_m] = -(phi.T @ g)
        f[n_m:] = data.vehicles.wheel_rows.T @ (self.wsum @ g)
        return phase, np.linalg.solve(stiff, f), (x, vx, phi, dphi, mass, damp, stiff)

    def record(self, i, outputs, cols=slice(None)):
        """Add one output step's pseudo responses ``outputs`` (rows: the channels of NAMES in order,
        float columns [Re, Im] of each line) to the variance sums."""
        z2 = outputs * outputs
        both = z2 @ np.stack([np.ones(z2.shape[1]), self.coarse_w[cols]], axis=1)
        r = 0
        for name in NAMES:
            size = self.var[name].shape[1]
            self.var[name][i] += both[r:r + size, 0]
            self.coarse[name][i] += both[r:r + size, 1]
            r += size
        n_pt = self.n_pt
        d, vel = outputs[:n_pt], outputs[n_pt:2 * n_pt]
        self.cov_dv[i] += (d * vel).sum(axis=1)
        if self.kept is not None:
            self.kept[i, :, cols] = d
        self.lam1[i] += (np.hypot(d[:, 0::2], d[:, 1::2]) * np.hypot(vel[:, 0::2], vel[:, 1::2])).sum(axis=1)


def _fl(z):
    """complex (r, L') → float view (r, 2L')."""
    return np.ascontiguousarray(z).view(np.float64)


def _shape_rows(run: _Run, i0: int, i1: int):
    """φ, φ' (steps, P, n_m) of every point at fine steps i0 … i1 − 1 (zero off the deck), and the
    points' x-rates (steps, P)."""
    data, n_m = run.data, run.n_m
    phi, dphi = np.zeros((i1 - i0, run.n_p, n_m)), np.zeros((i1 - i0, run.n_p, n_m))
    rates = np.empty((i1 - i0, run.n_p))
    on = np.zeros(run.n_p, np.bool_)
    for j, i in enumerate(range(i0, i1)):
        x, vx = point_positions(data, run.travel[i], run.speed[i])
        kernels.shapes_at(x, run.pts.track, data.modes, phi[j], dphi[j], on)
        phi[j, ~on], dphi[j, ~on] = 0.0, 0.0
        rates[j] = vx
    return phi, dphi, rates


def _exact_lines(run: _Run) -> None:
    """The pseudo responses of all lines by the engine's default integrator, exact modal stepping
    (``vbikit.solve.kernels.implicit`` with ``vbikit.solve.modal_step.exact_step`` and
    ``vehicle_step``), which is linear here: over a step of length h

        ξ_{n+1} = ξ_f + c1 ∘ p,   ξ̇_{n+1} = ξ̇_f + c2 ∘ p,        ξ_f = a11 ξ_n + a12 ξ̇_n + b1 p_n (…)
        z_{n+1} = z_b + R F_w,    z_b = P (T z_n + L0 G_n),      z = (q, q̇), G = F_w + K_z z

    (every mode exact with its modal load p = −Φᵀ F linear over the step; the vehicles' exact map
    with their nominal tires, ``VehicleStep``), and the contact law is linear in the end state,

        F = A_ξ ξ_{n+1} + A_ξ̇ ξ̇_{n+1} + A_z z_{n+1} + g,   A_ξ = K_p Φ + C_p ẋ Φ',  A_ξ̇ = C_p Φ,
        A_z = −[K_p H_p, C_p H_p],   g_p = k_p r̃_p + c_p ṙ̃_p,

    so that (p, F_w) = J F with J = [−Φᵀ; S] solve (I − J E)(p, F_w) = J F*, F* the law at the
    free state (ξ_f, ξ̇_f, z_b) and E = [A_ξ c1 + A_ξ̇ c2, A_z R].  Per step, one matrix
    G = (I − J E)⁻¹ J [A_ξ, A_ξ̇, A_z, I] (n_m + n_w rows) maps (ξ_f, ξ̇_f, z_b, g) of every line to
    its (p, F_w): the engine's Newton iteration, which converges to this solve, is not needed, and
    all lines are columns of one matrix product."""
    from vbikit.solve.modal_step import exact_step, vehicle_step

    data, pts, veh = run.data, run.pts, run.data.vehicles
    n_m, n_d, n_p, n_w, h = run.n_m, run.n_d, run.n_p, run.n_w, run.h
    ms, vs = exact_step(data.modes.omega, data.modes.zeta, h), vehicle_step(veh, h)
    rows = veh.wheel_rows
    k_p, c_p = pts.stiffness, pts.damping
    h_p = rows[pts.wheel]  # (P, n_d)
    a_z = np.hstack([-k_p[:, None] * h_p, -c_p[:, None] * h_p])  # (P, 2n_d)
    resp = vs.response  # (2n_d, n_w)
    e_z = a_z @ resp  # (P, n_w)
    k_z = np.hstack([veh.wheel_stiffness[:, None] * rows, veh.wheel_damping[:, None] * rows])  # (n_w, 2n_d)
    free_z = np.hstack([vs.settle @ vs.transition, vs.settle @ vs.load0])  # z_b = P (T z + L0 G)
    # stacked state st = [ξ; ξ̇; p; F_w; z; G] and input X = [ξ_f; ξ̇_f; z_b; g]
    o_v, o_p, o_f, o_z, o_g = n_m, 2 * n_m, 3 * n_m, 3 * n_m + n_w, 3 * n_m + n_w + 2 * n_d
    n_st, o_in_g = o_g + n_w, 2 * n_m + 2 * n_d
    n_r = n_m + n_w
    # outputs from st, in the order of NAMES: the deck's from (ξ, ξ̇, p, F_w), the vehicles' from (z, G)
    w2, zw = data.modes.omega**2, 2.0 * data.modes.zeta * data.modes.omega
    sh, n_pt = run.shapes, run.n_pt
    deck = np.zeros((4 * n_pt, o_z))  # on [ξ; ξ̇; p; F_w]
    deck[:n_pt, :n_m] = sh
    deck[:n_pt] += run.state_rows
    deck[n_pt:2 * n_pt, o_v:o_p] = sh
    deck[2 * n_pt:3 * n_pt, :n_m] = -sh * w2  # ξ̈ = p − 2ζω ξ̇ − ω² ξ
    deck[2 * n_pt:3 * n_pt, o_v:o_p] = -sh * zw
    deck[2 * n_pt:3 * n_pt, o_p:o_f] = sh
    deck[3 * n_pt:4 * n_pt, :n_m] = run.strain_shapes
    # q̈ = M⁻¹(Hᵀ G − Ĉ q̇ − K̂ q) (gravity is in the mean)
    v_acc = veh.mass_inv @ np.hstack([-vs.k_hat, -vs.c_hat, rows.T])  # on (z, G)
    n_out = run.time.size
    var, coarse = np.zeros((n_out, 4 * n_pt + 2 * n_d + n_w)), np.zeros((n_out, 4 * n_pt + 2 * n_d + n_w))
    keep = run.kept is not None
    kept = run.kept if keep else np.zeros((1, 1, 1))

    def record(i, st):
        kernel.record(i, st, n_m, n_w, n_d, deck, v_acc, run.coarse_w, var, coarse, run.cov_dv, run.lam1, kept, keep,
                      np.empty((4 * n_pt, st.shape[1])), np.empty((n_d, st.shape[1])))

    phase, u0, (x0, vx0, phi0, dphi0, *_) = run.static_start()
    n_c = phase.shape[1] * 2  # float columns
    st = np.zeros((n_st, n_c))
    inp = np.zeros((o_in_g + n_p, n_c))
    st[:n_m] = _fl(u0[:n_m])
    st[o_z:o_z + n_d] = _fl(u0[n_m:])
    if run.crossing.run_in > 0 and n_d:  # the vehicles settled by their run-in (the engine's, vbikit.solve.run_in)
        st[o_z:o_g] = _fl(_run_in_state(run, phase, x0, vx0))
    g0 = _fl(run.road_load(phase, vx0))
    a_xi0 = k_p[:, None] * phi0 + (c_p * vx0)[:, None] * dphi0
    force = a_xi0 @ st[:n_m] + a_z @ st[o_z:o_g] + g0  # F₀ (rates zero)
    st[o_p:o_f] = -phi0.T @ force
    st[o_f:o_z] = run.wsum @ force
    st[o_g:] = st[o_f:o_z] + k_z @ st[o_z:o_g]
    record(0, st)
    eye = np.eye(n_r)
    n_f = run.fine.size
    dtravel = np.diff(run.travel, axis=0)  # (n_f − 1, V)
    forward = np.ascontiguousarray(run.forward[:, 0])
    for c0 in range(1, n_f, STEP_CHUNK):
        c1 = min(c0 + STEP_CHUNK, n_f)
        phi, dphi, rates = _shape_rows(run, c0, c1)
        a_xi = k_p[:, None] * phi + (c_p * rates)[:, :, None] * dphi  # (steps, P, n_m)
        a_dxi = c_p[:, None] * phi
        jac = np.concatenate([-np.swapaxes(phi, 1, 2), np.broadcast_to(run.wsum, (c1 - c0, n_w, n_p))], axis=1)
        e = np.concatenate([a_xi * ms.c1 + a_dxi * ms.c2, np.broadcast_to(e_z, (c1 - c0, n_p, n_w))], axis=2)
        y = np.linalg.solve(eye - jac @ e, jac)  # (steps, n_r, P)
        gmat = np.ascontiguousarray(np.concatenate([y @ a_xi, y @ a_dxi, y @ a_z, y], axis=2))  # (steps, n_r, n_in)
        kernel.advance(c0 - 1, run.substeps, gmat, st, inp, phase, ms.a11, ms.a12, ms.b1, ms.a21, ms.a22, ms.b2, ms.c1,
                       ms.c2, free_z, resp, k_z, dtravel[c0 - 1:c1 - 1], run.wave, pts.vehicle, forward, rates,
                       run.coef_k, run.coef_cw, deck, v_acc, run.coarse_w, var, coarse, run.cov_dv, run.lam1, kept, keep)
    r = 0
    for name in NAMES:
        size = run.var[name].shape[1]
        run.var[name][:], run.coarse[name][:] = var[:, r:r + size], coarse[:, r:r + size]
        r += size


def _run_in_state(run: _Run, phase: NDArray[np.complex128], x0: NDArray[np.float64],
                  vx0: NDArray[np.float64]) -> NDArray[np.complex128]:
    """Every line's pseudo vehicle state z = (q, q̇) (2 n_d, lines) at the start (the points at ``x0`` [m] moving
    at ``vx0`` [m/s]) after ``crossing.run_in`` metres of
    its pseudo-road, from the pseudo-static state where the run-in begins — the engine's run-in
    (``vbikit.solve.run_in``: the recursion z_{j+1} = A z_j + M0 a_j + M1 a_{j+1} of the vehicles' exact step map
    over K steps of the run's h) under the harmonic loads a_j = a_K λ^{j−K} of one line (a_K the wheels' pseudo
    road loads at the start, λ = exp(i 2π n vx h) for a vehicle at x-rate vx), in closed form: the harmonic
    solution ẑ λ^{j−K} with (λ I − A) ẑ = (M0 + λ M1) a_K plus the free response A^K (z_0 − ẑ λ^{−K}) from the
    start at rest z_0 = (I − A)⁻¹ (M0 + M1) a_K λ^{−K}; each vehicle on its own (``independent_blocks``)."""
    from vbikit.solve.modal_step import vehicle_step
    from vbikit.solve.run_in import check_off_deck, independent_blocks, recursion, run_in_steps

    data, pts = run.data, run.pts
    check_off_deck(data, x0, run.crossing.run_in)
    a_mat, m0, m1, _ = recursion(data, vehicle_step(data.vehicles, run.h))
    k = run_in_steps(run.crossing, run.h, np.asarray(run.speed[0], float))
    loads = run.wsum @ run.road_load(phase, vx0)  # (n_w, lines): a_K
    z = np.zeros((a_mat.shape[0], loads.shape[1]), complex)
    for states, wheels in independent_blocks(a_mat, m0, m1):
        if not wheels.size:
            continue
        a, b0, b1 = a_mat[np.ix_(states, states)], m0[np.ix_(states, wheels)], m1[np.ix_(states, wheels)]
        a_k = loads[wheels]
        vx = float(vx0[np.flatnonzero(pts.wheel == wheels[0])[0]])  # (a vehicle's points share its x-rate)
        lam = np.exp(1j * run.wave * vx * run.h)  # (lines,)
        eye = np.eye(states.size)
        steady = np.linalg.solve(lam[:, None, None] * eye - a, (b0 @ a_k + lam * (b1 @ a_k)).T[:, :, None])[:, :, 0].T
        back = lam ** (-k)  # λ^{−K}
        rest = np.linalg.solve(eye - a, (b0 + b1) @ (a_k * back))
        z[states] = steady + np.linalg.matrix_power(a, k) @ (rest - steady * back)
    return z


def _newmark_lines(run: _Run) -> None:
    """The pseudo responses by Newmark's average-acceleration rule on the coupled equations (Eq. 9
    assembled by ``vbikit.solve.system.coupled_system``): one inverse of the real effective matrix per
    step, all lines as right-hand sides, in blocks of lines."""
    data, pts = run.data, run.pts
    n, n_m, n_p = run.n, run.n_m, run.n_p
    veh = data.vehicles
    h_w = veh.wheel_rows  # (n_w, n_d)
    k_p, c_p = pts.stiffness, pts.damping
    kw, cw = run.wsum * k_p, run.wsum * c_p  # (n_w, P): Σ_{p∈w} k_p, c_p
    mass, damp, stiff = (np.zeros((n, n)) for _ in range(3))
    load = np.zeros(n)
    phi, dphi = np.zeros((n_p, n_m)), np.zeros((n_p, n_m))
    travel, speed, h = run.travel, run.speed, run.h

    def system(i: int):
        x, vx = point_positions(data, travel[i], speed[i])
        mass[:], damp[:], stiff[:], load[:], phi[:], dphi[:] = coupled_system(data.modes, veh, pts, x, vx)
        return x, vx

    sh, ss, rows = run.shapes, run.strain_shapes, run.state_rows
    w2, zw = data.modes.omega**2, 2.0 * data.modes.zeta * data.modes.omega

    def record(i, blk, u, v, a, g_w, wheel_maps):
        a_xi, a_dxi, a_q, a_dq = wheel_maps
        force = a_xi @ u[:n_m] + a_dxi @ v[:n_m] + a_q @ u[n_m:] + a_dq @ v[n_m:] + g_w
        cols = slice(2 * blk.start, 2 * blk.stop)
        disp = sh @ u[:n_m]
        if rows.any():  # row · [ξ; ξ̇; p; F_w], p = ξ̈ + 2ζωξ̇ + ω²ξ
            p = a[:n_m] + zw[:, None] * v[:n_m] + w2[:, None] * u[:n_m]
            disp = disp + rows @ np.vstack([u[:n_m], v[:n_m], p, force])
        run.record(i, np.vstack([disp, sh @ v[:n_m], sh @ a[:n_m], ss @ u[:n_m], u[n_m:], a[n_m:], force]),
                   cols)

    def forcing(phase, vx, blk):
        """The pseudo-loads F̃ (n, 2L') and each wheel's road force Σ_{p∈w} k_p r̃_p + c_p ṙ̃_p (n_w, 2L')
        of the lines ``blk``."""
        g = _fl(run.road_load(phase, vx, blk))
        g_w = run.wsum @ g
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
    n_lines = run.wave.size
    size = max(8, int(BLOCK_WORK // (2 * n * n)))
    blocks = [slice(j, min(j + size, n_lines)) for j in range(0, n_lines, size)]
    x, vx = system(0)
    maps = wheel_maps(vx)
    phase, state = [], []
    for blk in blocks:
        ph, u0, _ = run.static_start(blk)
        u = _fl(u0)
        _, g_w = forcing(ph, vx, blk)
        v, a = np.zeros_like(u), np.zeros_like(u)
        record(0, blk, u, v, a, g_w, maps)
        phase.append(ph)
        state.append((u, v, a))
    c0, c1 = 4.0 / h**2, 2.0 / h
    for i in range(1, run.fine.size):
        x, vx = system(i)
        maps = wheel_maps(vx)
        inv = np.linalg.inv(stiff + c0 * mass + c1 * damp)  # small (n × n): a product per block is cheaper than LU solves
        for k, blk in enumerate(blocks):
            run.phase_step(phase[k], i, blk)
            u, v, a = state[k]
            f, g_w = forcing(phase[k], vx, blk)
            rhs = f + mass @ (c0 * u + 2.0 * c1 * v + a) + damp @ (c1 * u + v)
            u_new = inv @ rhs
            a_new = c0 * (u_new - u) - 2.0 * c1 * v - a
            v = v + 0.5 * h * (a + a_new)
            state[k] = (u_new, v, a_new)
            if i % run.substeps == 0:
                record(i // run.substeps, blk, u_new, v, a_new, g_w, maps)
