"""The kernels' argument bundles (NamedTuples of arrays) and work spaces, and the decorator of their
internal helpers. (``vbikit.solve.kernels``: the equations and conventions.)"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from vbikit.solve.numba_cache import ensure_cache_location

ensure_cache_location()  # before the first @njit(cache=True) below


class Modes(NamedTuple):
    """The bridge's modes: ``omega`` ω_m [rad/s], ``zeta`` ζ_m [-] (n_m,); per track ``start``,
    ``end`` [m] (n_tracks,) (a point on track k with start_k ≤ x ≤ end_k is on the deck); mode-shape
    tables ``values`` φ and ``slopes`` ∂φ/∂x (n_tracks, n_grid, n_m), track k's on the uniform grid
    of spacing ``grid_h`` [m] from x = start_k; ``amp``
    (n_m,) bound on |φ_m| (the lazy-contact test)."""

    omega: np.ndarray
    zeta: np.ndarray
    start: np.ndarray
    end: np.ndarray
    grid_h: float
    values: np.ndarray
    slopes: np.ndarray
    amp: np.ndarray


class Vehicles(NamedTuple):
    """Vehicle matrices (n_d, n_d): ``mass`` M, ``mass_inv`` M⁻¹, ``damping`` C_v, ``stiffness``
    K_v, ``gravity`` F_G (n_d,) [N] (block-diagonal for several vehicles); ``wheel_rows`` h_w
    (n_w, n_d); per wheel ``wheel_first``, ``wheel_count`` (its contact points' index range),
    ``wheel_envelope`` (acts through its highest point only: rigid disk), ``wheel_stiffness``
    [N/m] and ``wheel_damping`` [N·s/m] of its tire at rest (the implicit integrators' nominal
    tire, Σ of its points' k, c in static contact)."""

    mass: np.ndarray
    mass_inv: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    gravity: np.ndarray
    wheel_rows: np.ndarray
    wheel_first: np.ndarray
    wheel_count: np.ndarray
    wheel_envelope: np.ndarray
    wheel_stiffness: np.ndarray
    wheel_damping: np.ndarray


class Points(NamedTuple):
    """Per contact point (n_cp,): kinematics ``origin`` [m], ``direction`` (±1.0), ``vehicle``
    (column of ``Motion``); ``track`` (table of ``Modes``), ``line`` (road line of
    ``Road``, clamped to the lines present); tire law ``stiffness`` k [N/m], ``damping``
    c [N·s/m], ``fixed_load`` f0 [N], ``gap`` g [m], ``gated``; ``wheel`` index; ``width`` [m]
    of patch it stands for; ``slope_range`` (n_cp, 2) tire-surface slopes over its cell
    (envelope wheels)."""

    origin: np.ndarray
    direction: np.ndarray
    vehicle: np.ndarray
    track: np.ndarray
    line: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    fixed_load: np.ndarray
    gap: np.ndarray
    gated: np.ndarray
    wheel: np.ndarray
    width: np.ndarray
    slope_range: np.ndarray


class Road(NamedTuple):
    """Road lines: ``stations`` (n_s,) increasing [m], ``elevations`` (n_lines, n_s, L) [m] per
    lane, ``r_max`` the highest elevation [m]."""

    stations: np.ndarray
    elevations: np.ndarray
    r_max: float


class Motion(NamedTuple):
    """``travel`` s_v [m] and ``speed`` v_v [m/s] (n_half, n_vehicles) on the half-step grid
    (row 2n = t_n)."""

    travel: np.ndarray
    speed: np.ndarray


class Cache(NamedTuple):
    """One position slot: point positions ``x`` [m] and x-rates ``vx`` = dir·v [m/s] (n_cp,); mode
    shapes ``phi``, ``dphi`` (n_cp, n_m) and road ``rv``, ``rr`` (n_cp, L) filled on first use
    (``have``, ``have_r``)."""

    x: np.ndarray
    vx: np.ndarray
    phi: np.ndarray
    dphi: np.ndarray
    have: np.ndarray
    rv: np.ndarray
    rr: np.ndarray
    have_r: np.ndarray


class Work(NamedTuple):
    """Station pointers ``idx`` (n_cp,); outputs ``force`` (n_cp, L), ``active`` (n_cp, L),
    ``used`` (n_cp,); ``scratch`` (5, L); ``rhs`` (n_d, L); per point and lane the penetration
    ``pen`` δ [m] and the ungated law ``law`` k δ + c δ̇ + f0 [N] (for a point left out by the lazy
    test, ``pen`` holds its bound r_max − g − min z_w + B ≥ δ and ``law`` 0; 0 on rigid disks)."""

    idx: np.ndarray
    force: np.ndarray
    active: np.ndarray
    used: np.ndarray
    scratch: np.ndarray
    rhs: np.ndarray
    pen: np.ndarray
    law: np.ndarray


#: the kernels' compiled helpers: called only from other kernels, so numba builds them without
#: the wrappers that make a function callable from Python (compile time only, no run time)
_internal = njit(cache=True, fastmath=True, error_model="numpy", no_cpython_wrapper=True, no_cfunc_wrapper=True)


def _numba_knows(**options) -> dict:
    """The ``options`` this numba accepts (for the two below, which numba does not document)."""
    try:
        from numba.core.options import DefaultOptions
    except ImportError:  # pragma: no cover - another numba layout: plain kernels
        return {}
    return {name: value for name, value in options.items() if hasattr(DefaultOptions, name)}


#: options of the flat kernels (``lean`` with ``_law``, ``_state``, ``_quasi``;
#: ``static_modal_history``): plain contiguous arrays in, nothing allocated inside (the callers pass
#: the work spaces), so numba's reference counting is off (``_nrt=False``: no increments and
#: decrements of every array at each call, view and exit) and so are its rewrite passes
#: (``no_rewrites``: they fuse whole-array expressions, which these kernels do not have).  Both cut
#: the cold compile of the default path (benchmarks/bench_compile.py) with bit-identical results, and
#: ``lean`` runs faster without the counting on its helpers' arguments; the kernels compile without
#: them (slower) should a numba not know these options.
FLAT_OPTIONS = dict(cache=True, fastmath=True, error_model="numpy", no_cfunc_wrapper=True,
                    **_numba_knows(no_rewrites=True, _nrt=False))

#: a flat kernel called from Python
_flat = njit(**FLAT_OPTIONS)
#: a flat kernel's helper, called only from flat kernels (no wrappers)
_flat_internal = njit(no_cpython_wrapper=True, **FLAT_OPTIONS)


def new_cache(n_cp: int, n_m: int, n_l: int) -> Cache:
    """An empty position slot."""
    return Cache(np.zeros(n_cp), np.zeros(n_cp), np.zeros((n_cp, n_m)), np.zeros((n_cp, n_m)),
                 np.zeros(n_cp, np.bool_), np.zeros((n_cp, n_l)), np.zeros((n_cp, n_l)), np.zeros(n_cp, np.bool_))


def new_work(n_cp: int, n_d: int, n_l: int) -> Work:
    """Work space of ``contact_forces``."""
    return _work(n_cp, n_d, n_l)


@njit(cache=True)
def _work(n_cp, n_d, n_l):
    """Work space of ``contact_forces`` (``new_work``; also built inside the kernels)."""
    return Work(np.full(n_cp, -1, dtype=np.int64), np.zeros((n_cp, n_l)), np.zeros((n_cp, n_l), dtype=np.bool_),
                np.zeros(n_cp, dtype=np.bool_), np.zeros((5, n_l)), np.zeros((n_d, n_l)), np.zeros((n_cp, n_l)),
                np.zeros((n_cp, n_l)))


@_internal
def _slot(n_cp, n_m, n_l):
    return Cache(np.zeros(n_cp), np.zeros(n_cp), np.zeros((n_cp, n_m)), np.zeros((n_cp, n_m)),
                 np.zeros(n_cp, dtype=np.bool_), np.zeros((n_cp, n_l)), np.zeros((n_cp, n_l)),
                 np.zeros(n_cp, dtype=np.bool_))


class ModalStep(NamedTuple):
    """One step h of every mode ξ̈ + 2ζωξ̇ + ω²ξ = p as a linear map of its start state and of the
    modal load at the step's ends and at the end of the step before (the load's hold over the step:
    linear through p_n, p_{n+1}, with d1 = d2 = 0, or quadratic through p_{n−1}, p_n, p_{n+1}):
    ξ_{n+1} = a11 ξ_n + a12 ξ̇_n + d1 p_{n−1} + b1 p_n + c1 p_{n+1},
    ξ̇_{n+1} = a21 ξ_n + a22 ξ̇_n + d2 p_{n−1} + b2 p_n + c2 p_{n+1}
    (each (n_m,); ``vbikit.solve.modal_step``: exact, or Newmark's average acceleration)."""

    a11: np.ndarray
    a12: np.ndarray
    a21: np.ndarray
    a22: np.ndarray
    b1: np.ndarray
    b2: np.ndarray
    c1: np.ndarray
    c2: np.ndarray
    d1: np.ndarray
    d2: np.ndarray


class VehicleStep(NamedTuple):
    """One step h of the vehicles with their nominal tires (k_w, c_w per wheel) on the contact
    surface, as a linear map of the stacked state z = (q, q̇) (2n_d) and of the wheel loads G at
    both ends of the step and at the end of the step before (their hold over the step, as
    ``ModalStep``'s: linear, ``load_past`` zero, or quadratic):
    z_{n+1} = ``transition`` z_n + ``load_past`` G_{n−1} + ``load0`` G_n + ``load1`` G_{n+1} + ``constant`` (gravity);
    ``c_hat`` Ĉ = C_v + Hᵀ diag(c_w) H and ``k_hat`` K̂ = K_v + Hᵀ diag(k_w) H give q̈ from the
    equation of motion (``vbikit.solve.modal_step``: exact, or Newmark's average acceleration).
    For the coupled solve, with the end loads G = F + K_z z_{n+1} written through the wheel forces
    F: ``settle`` P = (I − L1 K_z)⁻¹ (2n_d, 2n_d), ``response`` P L1 (2n_d, n_w), and the wheels'
    displacement and velocity per unit wheel force ``wheel_q`` = H (P L1)[:n_d], ``wheel_v`` =
    H (P L1)[n_d:] (n_w, n_w)."""

    transition: np.ndarray
    load0: np.ndarray
    load1: np.ndarray
    constant: np.ndarray
    c_hat: np.ndarray
    k_hat: np.ndarray
    settle: np.ndarray
    response: np.ndarray
    wheel_q: np.ndarray
    wheel_v: np.ndarray
    load_past: np.ndarray


class FusedVehicleStep(NamedTuple):
    """A ``VehicleStep``'s products as the lean kernels take them, one product a step in place of
    several (``vbikit.solve.modal_step.fused_step``): the settled free response
    z_b = P (Φ z_n + Lp G_{n−1} + L0 G_n + g) = ``free`` z_n + ``free_past`` G_{n−1} + ``free_load`` G_n +
    ``free_constant`` (P Φ (2n_d, 2n_d), P Lp and P L0 (2n_d, n_w), P g (2n_d,)), and each wheel row h_w by its nonzero entries, DOF indices
    ``wheel_dof`` (n_w, k) int64 and values ``wheel_h`` (n_w, k) (``vbikit.solve.kernels.lean.wheel_entries``).
    Kept apart from ``VehicleStep``, the bundle ``implicit`` takes whole and which reads none of these."""

    free: np.ndarray
    free_load: np.ndarray
    free_constant: np.ndarray
    free_past: np.ndarray
    wheel_dof: np.ndarray
    wheel_h: np.ndarray
