"""Speed sweeps: every train over every speed → envelopes of deck acceleration, deflection, moment
and shear against speed (a NetCDF-ready ``xarray.Dataset``), with resonance speeds.

Moving forces (EN 1991-2 6.4.6) through the fast solver ``vbikit.solve.moving_loads`` (exact
modal stepping per speed, vectorised); optionally the trains with multibody cars as coupled car
models (``vbikit.vehicle.rail_car``) through ``vbikit.solve.simulate``, one crossing per speed,
on an optional track irregularity (``vbikit.road.track``).
"""
from __future__ import annotations

import logging
import math
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit.bridge.base import ModalBridge
from vbikit.bridge.effects import LoadEffect
from vbikit.rail.codes import resonance_speeds
from vbikit.vehicle.trains import Train

log = logging.getLogger(__name__)

KMH = 1.0 / 3.6


def speed_grid(v_min: float, v_max: float, step: float, resonances: Sequence[float] = (), fine_step: float | None = None,
               width: float = 0.0) -> NDArray[np.float64]:
    """Speeds [m/s] from ``v_min`` to ``v_max`` every ``step`` [m/s], plus every ``fine_step``
    within ± ``width`` of each resonance speed (EN 1991-2 6.4.6: smaller steps near resonance)."""
    n = int(math.floor((v_max - v_min) / step + 1e-9))
    grid = [v_min + step * np.arange(n + 1), np.array([v_max])]
    if fine_step and width > 0:
        for r in resonances:
            lo, hi = max(v_min, r - width), min(v_max, r + width)
            if hi > lo:
                grid.append(np.arange(lo, hi + 0.5 * fine_step, fine_step))
    v = np.unique(np.round(np.concatenate(grid), 9))
    return v[(v >= v_min - 1e-9) & (v <= v_max + 1e-9)]


@dataclass(frozen=True)
class SweepSetup:
    """What every train's sweep shares: the bridge, response points x [m], the load effects as
    (kind, section x [m]) pairs (picklable, for worker processes), Δx [m] and the free vibration [s]
    after the last axle leaves."""

    bridge: ModalBridge
    points: NDArray[np.float64]
    effect_specs: tuple[tuple[str, float], ...]
    dx: float
    free_vibration: float
    max_steps: float
    y: float = 0.0

    @property
    def effects(self) -> tuple[LoadEffect, ...]:
        return tuple(self.bridge.load_effect(kind, x) for kind, x in self.effect_specs)


def _sweep_one(args: tuple[SweepSetup, Train, NDArray[np.float64]]):
    from vbikit.solve.moving_loads import moving_load_sweep

    setup, train, speeds = args
    env = moving_load_sweep(setup.bridge, train.axle_positions, train.axle_loads, speeds, setup.points,
                            setup.effects, dx=setup.dx, free_vibration=setup.free_vibration, y=setup.y,
                            max_steps=setup.max_steps)
    return env, refine_train_peaks(setup, train, env)


def sweep_moving_forces(setup: SweepSetup, trains: Sequence[Train], speeds: NDArray[np.float64], workers: int = 1) -> list:
    """(``MovingLoadEnvelopes``, ``RefinedPeaks``) of every train (``workers`` processes; 1: in this
    process)."""
    jobs = [(setup, t, speeds) for t in trains]
    if workers <= 1 or len(trains) < 2:
        return [_sweep_one(j) for j in jobs]
    with ProcessPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(_sweep_one, jobs))


def coupled_envelopes(setup: SweepSetup, train: Train, speeds: NDArray[np.float64], irregularity: Optional[str] = None,
                      seed: int = 0, contact: str | float = "hertz"):
    """Envelopes of one train whose cars have masses and suspensions, as coupled car models
    (``rail_car``, point contact) — each car one ``VehicleMotion`` entering when its first axle
    reaches the bridge — over a smooth or irregular track; one ``simulate`` per speed."""
    from vbikit.solve.crossing import Crossing, VehicleMotion
    from vbikit.solve.moving_loads import MovingLoadEnvelopes
    from vbikit.solve.simulate import simulate

    cars = rail_cars(train, contact)
    bridge = setup.bridge
    phi = bridge.mode_shapes(setup.points, np.full(setup.points.size, setup.y))
    n_v, n_p, n_e = speeds.size, setup.points.size, len(setup.effects)
    acc, disp, eff = np.empty((n_v, n_p)), np.empty((n_v, n_p)), np.empty((n_v, n_e))
    static_disp, static_eff = np.zeros(n_p), np.zeros(n_e)
    for k, v in enumerate(speeds):
        motions = tuple(VehicleMotion(car, float(v), entry_time=float(offset) / float(v), lateral_offset=setup.y)
                        for car, offset in cars)
        crossing = Crossing(bridge, vehicles=motions, dt=setup.dx / float(v), free_vibration=setup.free_vibration)
        if irregularity:
            from vbikit.road.track import track_profile

            lo, hi = crossing.road_extent()
            road = track_profile(irregularity, seed, length=hi - lo + 2.0, x_start=lo - 1.0)
            crossing = crossing.with_road(road)
        result = simulate(crossing)
        acc[k] = np.max(np.abs(result.xi_ddot @ phi.T), axis=0)
        disp[k] = np.max(np.abs(result.xi @ phi.T), axis=0)
        if n_e:
            from vbikit.analysis.effects import load_effect_response

            for e, effect in enumerate(setup.effects):
                resp = load_effect_response(result, effect)
                eff[k, e] = np.max(np.abs(resp.dynamic))
                static_eff[e] = max(static_eff[e], float(np.max(np.abs(resp.static))))
        from vbikit.analysis.impact import static_modal_history

        static_disp = np.maximum(static_disp, np.max(np.abs(static_modal_history(result) @ phi.T), axis=0))
    return MovingLoadEnvelopes(speeds, setup.points, acc, disp, static_disp, eff, static_eff, setup.dx)


def rail_cars(train: Train, contact: str | float = "hertz") -> list:
    """(Vehicle, offset of its first axle [m] behind the train's first axle) of every car of a train
    with multibody data (``Train.cars``)."""
    from vbikit.vehicle.trains import TrainError
    from vbikit.vehicle.rail_car import RailCarParameters, rail_car

    if not train.cars or any(c.static_axle_load is None or c.primary_stiffness is None for c in train.cars):
        raise TrainError(f"train {train.name!r} has no car masses and suspensions: coupled cars need a train such as "
                         "'ice3' (HSLM and table trains run as moving forces)", key="coupled")
    out = []
    for car in train.cars:
        params = RailCarParameters(
            body_mass=car.body_mass, body_pitch_inertia=car.body_pitch_inertia, bogie_mass=car.bogie_mass,
            bogie_pitch_inertia=car.bogie_pitch_inertia, wheelset_mass=car.wheelset_mass,
            primary_stiffness=car.primary_stiffness, primary_damping=car.primary_damping or 0.0,
            secondary_stiffness=car.secondary_stiffness, secondary_damping=car.secondary_damping or 0.0,
            bogie_half_distance=0.5 * car.bogie_spacing, axle_half_spacing=0.5 * car.axle_spacing,
            contact=contact, name=car.name or "car", source=train.source)
        out.append((rail_car(params), float(car.axle_positions[0] - train.axle_positions[0])))
    return out


def excitation_wavelength(train: Train) -> tuple[Optional[float], str]:
    """The wavelength D [m] of a train's resonances v_i = n0 D / i and where it comes from: its coach
    length when documented (HSLM, presets), else its dominant repeated axle spacing
    (``vbikit.rail.signature``)."""
    if train.coach_length:
        return float(train.coach_length), "coach length"
    from vbikit.rail.signature import dominant_wavelength

    d = dominant_wavelength(train.axle_positions, train.axle_loads)
    return d, ("dominant repeated axle spacing (train spectrum)" if d else "none (no repeated axle spacing)")


def train_resonances(train: Train, n0: float, orders: int = 4) -> NDArray[np.float64]:
    """v_i = n0 D / i [m/s], i = 1 … ``orders`` (entry i − 1 is order i; NaN when the train has no D),
    D from ``excitation_wavelength``."""
    d, _ = excitation_wavelength(train)
    return resonance_speeds(n0, d, orders=orders) if d else np.full(orders, np.nan)


# ------------------------------------------------------------------------------ moment envelope
def moment_sections(span: float, n: int) -> NDArray[np.float64]:
    """The n − 1 interior sections x_j = j L / n [m] (n even: midspan among them)."""
    return span * np.arange(1, n) / n


def static_envelope(bridge: ModalBridge, kind: str, sections: NDArray[np.float64], axles: NDArray[np.float64],
                    loads: NDArray[np.float64], y: float = 0.0, travel: Optional[NDArray[np.float64]] = None) -> NDArray[np.float64]:
    """max over the train's positions of |Σ_k P_k η(s − a_k)| at each section (η the effect of a unit
    downward force), evaluated where an axle stands on a breakpoint of a simply supported span's
    influence line (a support or the section itself: s = a_k, a_k + x, a_k + L) — exact for a
    piecewise-linear line — and at the first-axle travel samples ``travel`` [m] (curved lines)."""
    span = float(bridge.span)
    out = np.zeros(sections.size)
    for j, x in enumerate(sections):
        effect = bridge.load_effect(kind, float(x))
        cand = np.concatenate([axles + b for b in (0.0, float(x), span)] + ([travel] if travel is not None else []))
        pos = cand[:, None] - axles[None, :]
        on = (pos >= 0.0) & (pos <= span)
        eta = np.zeros(pos.shape)
        if on.any():
            eta[on] = -np.asarray(effect.influence(pos[on], np.full(int(on.sum()), y)), float)
        out[j] = float(np.max(np.abs(eta @ loads)))
    return out


def moment_envelope_near(setup: SweepSetup, train: Train, speed: float, x_lo: float, x_hi: float,
                         n: int = 81) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Peak |M| [N m] of one crossing at ``speed`` [m/s] at n sections in [x_lo, x_hi] [m] (mode
    acceleration, the sweep's Δx): the envelope between the sweep's sections, to place its maximum."""
    from vbikit.solve.moving_loads import moving_load_history

    bridge = setup.bridge
    xs = np.linspace(x_lo, x_hi, n)
    effects = [bridge.load_effect("moment", float(x)) for x in xs]
    h = moving_load_history(bridge, train.axle_positions, train.axle_loads, speed, dx=setup.dx,
                            free_vibration=setup.free_vibration, effects=effects, y=setup.y)
    r = np.array([e.modal for e in effects])                        # (n, n_m)
    resp = h.static_effects + (h.xi - h.modal_load / bridge.omega**2) @ r.T
    return xs, np.max(np.abs(resp), axis=0)


# ---------------------------------------------------------------------------- peak refinement
#: the sweep's acceleration peaks are refined until a halving of the speed step changes them by less than this
PEAK_TOLERANCE = 0.005
#: the most halvings per peak, and the peaks refined per train (the largest local maxima, at least
#: ``PEAK_SHARE`` of the train's largest)
MAX_HALVINGS = 10
MAX_PEAKS = 4
PEAK_SHARE = 0.5


@dataclass(frozen=True)
class RefinedPeaks:
    """The refined acceleration peaks of one train: per peak the speed [m/s] and value [m/s²] on the
    sweep's grid, the refined speed and value, the bound of the refined value's remaining grid error
    (relative), the relative change over the last halving, the final half-step [m/s] and whether
    the bound fell below the tolerance."""

    grid_speed: NDArray[np.float64]
    grid_value: NDArray[np.float64]
    speed: NDArray[np.float64]
    value: NDArray[np.float64]
    bound: NDArray[np.float64]
    last_change: NDArray[np.float64]
    step: NDArray[np.float64]
    converged: NDArray[np.bool_]


def _peak_indices(values: NDArray[np.float64]) -> list[int]:
    n = values.size
    idx = [j for j in range(n) if (j == 0 or values[j] >= values[j - 1]) and (j == n - 1 or values[j] >= values[j + 1])]
    top = float(values.max()) if n else 0.0
    idx = [j for j in idx if values[j] >= PEAK_SHARE * top]
    return sorted(sorted(idx, key=lambda j: -values[j])[:MAX_PEAKS])


def refine_peaks(evaluate, speeds: NDArray[np.float64], values: NDArray[np.float64],
                 tolerance: float = PEAK_TOLERANCE) -> RefinedPeaks:
    """Refine each peak of ``values`` over ``speeds`` (``_peak_indices``) by halving the step around it.

    The best speed v* lies midway in its bracket [v* − h, v* + h]; the midpoints v* ± h/2 are
    evaluated (``evaluate(speeds) -> values``, every peak's new speeds in one call) and the bracket
    halves around the best of the three.  With f* the best value and f_± those at the bracket's
    ends, a peak that is quadratic within the bracket exceeds f* by at most (f* − min f_±)/4 (the
    parabola's vertex lies within h/2 of v*, where it rises c x0² ≤ c h²/4 while the ends fall at
    least c h² below f*): that is the bound of the remaining grid error.  Refinement stops when
    the bound and the change over the last halving are both below ``tolerance`` (relative), or
    after ``MAX_HALVINGS``.
    """
    idx = _peak_indices(values)
    k = len(idx)
    best_v = np.array([speeds[j] for j in idx], float)
    best_a = np.array([values[j] for j in idx], float)
    lo = np.array([speeds[max(j - 1, 0)] for j in idx], float)
    hi = np.array([speeds[min(j + 1, speeds.size - 1)] for j in idx], float)
    f_lo = np.array([values[max(j - 1, 0)] for j in idx], float)
    f_hi = np.array([values[min(j + 1, speeds.size - 1)] for j in idx], float)
    grid_v, grid_a = best_v.copy(), best_a.copy()
    change = np.full(k, np.inf)
    bound = np.full(k, np.inf)
    done = np.zeros(k, bool)
    rounds = np.zeros(k, int)
    while k and not done.all():
        active = np.nonzero(~done)[0]
        m1, m2 = 0.5 * (lo[active] + best_v[active]), 0.5 * (best_v[active] + hi[active])
        new = evaluate(np.concatenate([m1, m2]))
        a1, a2 = new[:active.size], new[active.size:]
        for q, i in enumerate(active):
            old_v, old_a = best_v[i], best_a[i]
            if a1[q] > old_a and a1[q] >= a2[q]:
                hi[i], f_hi[i], best_v[i], best_a[i] = old_v, old_a, m1[q], a1[q]
            elif a2[q] > old_a:
                lo[i], f_lo[i], best_v[i], best_a[i] = old_v, old_a, m2[q], a2[q]
            else:
                lo[i], hi[i], f_lo[i], f_hi[i] = m1[q], m2[q], a1[q], a2[q]
            top = best_a[i]
            change[i] = (top - old_a) / top if top > 0 else 0.0
            bound[i] = (top - min(f_lo[i], f_hi[i])) / (4.0 * top) if top > 0 else 0.0
            rounds[i] += 1
            if (bound[i] < tolerance and change[i] < tolerance) or rounds[i] >= MAX_HALVINGS:
                done[i] = True
    return RefinedPeaks(grid_v, grid_a, best_v, best_a, bound, change, 0.5 * (hi - lo),
                        (bound < tolerance) & (change < tolerance))


def refine_train_peaks(setup: SweepSetup, train: Train, envelopes, tolerance: float = PEAK_TOLERANCE) -> RefinedPeaks:
    """``refine_peaks`` of one train's peak deck acceleration (over the deck points) from its sweep."""
    from vbikit.solve.moving_loads import moving_load_sweep

    def evaluate(v):
        env = moving_load_sweep(setup.bridge, train.axle_positions, train.axle_loads, v, setup.points, (), dx=setup.dx,
                                free_vibration=setup.free_vibration, y=setup.y, max_steps=setup.max_steps)
        return env.max_acceleration.max(axis=1)

    return refine_peaks(evaluate, envelopes.speeds, envelopes.max_acceleration.max(axis=1), tolerance)
