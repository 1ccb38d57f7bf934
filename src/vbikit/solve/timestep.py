"""Time-step selection and the RK4 stability limit.

Automatic step of the RK4 and Newmark integrators ([`accuracy_time_step`][vbikit.solve.accuracy_time_step]; ``Crossing.resolve``
does not change it), the smallest of
  * T_bridge,min / 5   — at least 5 steps per period of the highest retained bridge mode,
  * T_vehicle,min / 20 — 20 steps per period of the highest vehicle mode (tires on ground),
  * Δx_road / v_max    — at most one road sample passed per step,
  * span / (100 v_max) — at least 100 steps while a point crosses the span,
with v_max the largest speed any vehicle reaches during the run; the exact modal integrator's
(``implicit_time_step``) has no bridge-mode term.  An explicit integrator's automatic step
is also capped at 0.9 × its stability limit; for RK4 that is the limit of the coupled system,
computed from the eigenvalues λ of its first-order matrix at several vehicle positions as the
largest dt with |R(λ dt)| ≤ 1, R(z) = 1 + z + z²/2 + z³/6 + z⁴/24.  A user step above the limit
is refused (the implicit integrators are unconditionally stable and take any step).  Which rule
an integrator uses is part of its registration (``vbikit.solve.integrators``).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Callable, Optional

import numpy as np

from vbikit.errors import VbikitError
from vbikit.solve.integrators import get_integrator, implicit_names

if TYPE_CHECKING:  # pragma: no cover
    from vbikit.road.profile import RoadProfile
    from vbikit.solve.crossing import Crossing


class UnstableTimeStepError(VbikitError):
    """A user-given time step that the chosen explicit integrator cannot run stably."""


def _rk4_growth(z: np.ndarray) -> np.ndarray:
    return np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)


def system_eigenvalues(crossing: Crossing, n_positions: int = 5) -> np.ndarray:
    """Eigenvalues [1/s] of the coupled first-order system at several positions of the vehicles."""
    from vbikit.solve.system import coupled_matrices, kernel_data

    data = kernel_data(crossing, points_per_mode=10)
    # contact as at rest: the points that carry static load (a disk's static patch, a rigid
    # disk's lowest point, every point of point and multipoint tires)
    active = crossing.contact.weight > 0
    if crossing.n_vehicles == 1:  # its travel evenly spread from 1 m before the bridge to 1 m after it has left
        leaving = crossing.leaving_distance(np.arange(crossing.contact.n), crossing.vehicles[0].sign)
        positions = list(np.linspace(-1.0, leaving + 1.0, n_positions))
    else:  # the vehicles' travel at times spread over the run until the last one leaves
        positions = list(crossing.travel(np.linspace(crossing.start_time, crossing.exit_time(), n_positions + 2)))
    v_max = crossing.max_speed
    eig = []
    for xf in positions:
        mass, damp, stiff, _ = coupled_matrices(crossing, data, xf, v_max, active=active)
        m_inv = np.linalg.inv(mass)
        n = mass.shape[0]
        a = np.block([[np.zeros((n, n)), np.eye(n)], [-m_inv @ stiff, -m_inv @ damp]])
        eig.append(np.linalg.eigvals(a))
    return np.concatenate(eig)


def rk4_stability_limit(crossing: Crossing) -> float:
    """Largest stable RK4 step [s] for this crossing's coupled system."""
    lam = system_eigenvalues(crossing)
    lam = lam[np.abs(lam) > 1e-9]
    if lam.size == 0:
        return np.inf
    lo, hi = 0.0, 4.0 / np.abs(lam).max()
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if np.all(_rk4_growth(lam * mid) <= 1 + 1e-12):
            lo = mid
        else:
            hi = mid
    return lo


def accuracy_time_step(crossing: Crossing) -> float:
    """The accuracy-based automatic step [s] (see module docstring)."""
    v_max = crossing.max_speed
    candidates = [2 * np.pi / crossing.bridge.omega.max() / 5.0, crossing.bridge.span / (100.0 * v_max)]
    for road in (crossing.road, crossing.road_right):
        if road is not None and road.spacing > 0:
            candidates.append(road.spacing / v_max)
    return _with_vehicle_periods(crossing.vehicle, 20.0, min(candidates))


def choose_time_step(crossing: Crossing, stability_limit: Optional[float] = None,
                     automatic: Optional[Callable[[Crossing], float]] = None) -> float:
    """The step [s] the crossing runs with: the user's (checked against the stability limit of an
    explicit integrator) or the integrator's automatic one (capped at 0.9 × that limit).

    ``stability_limit`` [s] and ``automatic`` (the automatic step rule) replace the integrator's
    own when given (a batch computes them once for many crossings)."""
    integrator = get_integrator(crossing.integrator)
    rule = integrator.time_step if automatic is None else automatic
    if integrator.stability_limit is not None:
        limit = integrator.stability_limit(crossing) if stability_limit is None else stability_limit
        if crossing.dt is not None:
            if crossing.dt > limit:
                others = " or ".join(f'integrator = "{name}"' for name in implicit_names())
                raise UnstableTimeStepError(
                    f"crossing.dt = {crossing.dt:.3g} s is above the {integrator.name.upper()} stability limit {limit:.3g} s "
                    f"of this system (highest bridge mode {crossing.bridge.frequencies_hz.max():.1f} Hz); use dt <= "
                    f"{limit:.3g} s, leave dt out for an automatic step, fewer bridge modes, or {others}"
                )
            return float(crossing.dt)
        return min(rule(crossing), 0.9 * limit)
    if crossing.dt is not None:
        return float(crossing.dt)
    return rule(crossing)


#: steps per period of the highest vehicle mode, most road per step [m] on a generated road up to ISO 8608
#: class C and on others, road features per step (measured stations, defect ramps: not on a generated
#: band-limited road, ``RoadProfile.band_limited``) and steps per span passage for the exact modal
#: integrator (docs/verification.md, convergence study and the paper programme against RK4)
EXACT_STEPS_PER_VEHICLE_PERIOD = 20.0
EXACT_ROAD_LENGTH_PER_STEP = 0.03
EXACT_ROUGH_ROAD_LENGTH_PER_STEP = 0.02
EXACT_STEPS_PER_SPAN = 100.0
EXACT_ROAD_FEATURES_PER_STEP = 2.0
#: steps per first bridge period of the exact modal integrator, by what the run must resolve
#: (``Crossing.resolve``, ``crossing.RESOLVES``): every result 100; deflections only 50, where the wheel loads
#: held quadratic (``builtin_integrators.QUADRATIC_WHEEL_LOADS``) keep the paper programme's cells within the
#: automatic step's 5e-4 of the IM (class D 4.0e-4; benchmarks/README.md, ``bench_period_rule.py``), while a
#: skewed deck's shear peak moves by 1.0e-3 there (tests/verification/test_effect_jump_limits.py)
EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD: dict[str, float] = {"effects": 100.0, "deflections": 50.0}
#: [substitute] steps per shortest wavelength of a generated random road (``RoadOrigin.shortest_wavelength``):
#: ISO 8608's band (n_max = 4 cycle/m) gives 3.1 cm, above ``EXACT_ROAD_LENGTH_PER_STEP``; a finer band a shorter step
EXACT_STEPS_PER_ROAD_WAVELENGTH = 8.0
#: G_d(n₀) [m³/cycle] above which a generated road takes ``EXACT_ROUGH_ROAD_LENGTH_PER_STEP``: ISO 8608's upper
#: limit of class C (its classes' geometric means 16e-6 · 4^i, limits at twice them).  On class D wheels hop and
#: at 3 cm the paper programme had 6 crossings above its 1e-3 against converged RK4 (docs/verification.md)
EXACT_SMOOTH_ROAD_ROUGHNESS = 512e-6


def automatic_road_per_step(spacing: float) -> float:
    """The most road [m] one automatic step of any registered integrator covers on a road sampled every
    ``spacing`` m: ``EXACT_ROAD_LENGTH_PER_STEP`` (the exact integrator) or one station (the explicit
    ones).  What a road generated only over a crossing's range must reach beyond it: the time grid's
    last step passes the crossing's end by up to a step."""
    return max(EXACT_ROAD_LENGTH_PER_STEP, float(spacing))


def exact_road_per_step(road: RoadProfile, loss_of_contact: bool = True) -> float:
    """The most road [m] a step of the exact integrator covers on ``road``.  On a generated random road
    (``band_limited``): ``EXACT_ROAD_LENGTH_PER_STEP``, or ``EXACT_ROUGH_ROAD_LENGTH_PER_STEP`` above ISO 8608
    class C (``RoadOrigin.roughness`` > ``EXACT_SMOOTH_ROAD_ROUGHNESS``) where tires can leave the road
    (``loss_of_contact``: there wheels hop and the contact's instants are resolved to the step), and at most
    1/``EXACT_STEPS_PER_ROAD_WAVELENGTH`` of its shortest wavelength.  On a road whose stations may be
    edges (measured, with defects, given as arrays): ``EXACT_ROUGH_ROAD_LENGTH_PER_STEP`` and
    ``EXACT_ROAD_FEATURES_PER_STEP`` of its shortest feature (``RoadProfile.spacing``)."""
    origin = road.origin
    if road.band_limited and origin is not None:
        rough = loss_of_contact and (origin.roughness is None or origin.roughness > EXACT_SMOOTH_ROAD_ROUGHNESS)
        length = EXACT_ROUGH_ROAD_LENGTH_PER_STEP if rough else EXACT_ROAD_LENGTH_PER_STEP
        wavelength = origin.shortest_wavelength
        return length if wavelength is None else min(length, wavelength / EXACT_STEPS_PER_ROAD_WAVELENGTH)
    return min(EXACT_ROUGH_ROAD_LENGTH_PER_STEP, EXACT_ROAD_FEATURES_PER_STEP * road.spacing)


def road_step_key(road: RoadProfile | None) -> tuple | None:
    """What of ``road`` the automatic step rules read (``RoadProfile.spacing``; on a generated road its
    band and roughness, ``exact_road_per_step``): roads with equal keys get equal steps on the same
    crossing (a batch computes the step once per key)."""
    if road is None:
        return None
    origin = road.origin if road.band_limited else None
    return (road.spacing, None if origin is None else (origin.roughness, origin.shortest_wavelength))


def implicit_time_step(crossing: Crossing, quadratic_wheel_loads: bool = True) -> float:
    """The automatic step [s] of the exact modal integrator (no bridge-mode term; the first bridge
    period's term by what the crossing must resolve, ``EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD``, where the run
    holds the wheel loads quadratic, ``quadratic_wheel_loads``: the coarser step for deflections is that
    hold's; held linear every crossing takes the step for every result)."""
    v_max = crossing.max_speed
    per_period = EXACT_STEPS_PER_FIRST_BRIDGE_PERIOD[crossing.resolve if quadratic_wheel_loads else "effects"]
    candidates = [crossing.bridge.span / (EXACT_STEPS_PER_SPAN * v_max),
                  2 * np.pi / crossing.bridge.omega.min() / per_period]
    for road in (crossing.road, crossing.road_right):
        if road is not None and road.has_features:  # (spacing > 0; a generated road's step reads its origin only)
            candidates.append(exact_road_per_step(road, crossing.loss_of_contact) / v_max)
    return _with_vehicle_periods(crossing.vehicle, EXACT_STEPS_PER_VEHICLE_PERIOD, min(candidates))


#: relative margin on the bound of ``_with_vehicle_periods`` (far above the round-off of ‖M⁻¹K̂‖∞)
_BOUND_MARGIN = 1e-6


def _with_vehicle_periods(vehicle, steps_per_period: float, others: float) -> float:
    """min(``others``, T_min / ``steps_per_period``) [s], T_min = 1 / f_max the shortest period of the
    vehicle on rigid ground (``Vehicle.natural_frequencies``; no term without frequencies > 0).

    The eigenvalue problem is solved only when that term can be the smaller: ω_max² is the spectral
    radius of M⁻¹K̂ (K̂ = K + Σ k_w r_w r_wᵀ), which no induced norm is below (Horn & Johnson, Matrix
    Analysis, Thm 5.6.9), so T_min ≥ 2π / √‖M⁻¹K̂‖∞; when that bound's step is already ≥ ``others``
    the minimum is ``others`` — the same number as with the eigenvalues, at the cost of one solve."""
    if vehicle.n_dof and vehicle.__dict__.get("_natural_frequencies") is None:  # (frequencies not yet solved)
        bound = vehicle.stiffness_bound() * (1.0 + _BOUND_MARGIN)
        if bound == 0.0 or (np.isfinite(bound) and 2 * np.pi / np.sqrt(bound) / steps_per_period >= others):
            return float(others)
    f_veh = vehicle.natural_frequencies()
    if f_veh.size and f_veh.max() > 0:
        return float(min(others, 1.0 / f_veh.max() / steps_per_period))
    return float(others)
