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
from vbikit.rail.refine import PEAK_TOLERANCE, RefinedPeaks, refine_peaks
from vbikit.vehicle.trains import HSLM_B_NAME, Train

log = logging.getLogger(__name__)

KMH = 1.0 / 3.6


def speed_grid(v_min: float, v_max: float, step: float, resonances: Sequence[float] = (), fine_step: float | None = None,
               width: float = 0.0, bracketed: Sequence[float] = ()) -> NDArray[np.float64]:
    """Speeds [m/s] from ``v_min`` to ``v_max`` every ``step`` [m/s], plus every ``fine_step``
    within ± ``width`` of each resonance speed (EN 1991-2 6.4.6: smaller steps near resonance), plus
    each speed of ``bracketed`` and (with ``fine_step``) one fine step either side of it: a sample
    at a resonance whose peak the peak refinement (``vbikit.rail.refine``) then climbs, at a few
    speeds instead of a band's."""
    n = int(math.floor((v_max - v_min) / step + 1e-9))
    grid = [v_min + step * np.arange(n + 1), np.array([v_max])]
    if fine_step and width > 0:
        for r in resonances:
            lo, hi = max(v_min, r - width), min(v_max, r + width)
            if hi > lo:
                grid.append(np.arange(lo, hi + 0.5 * fine_step, fine_step))
    for r in bracketed:
        grid.append(np.array([r - fine_step, r, r + fine_step]) if fine_step else np.array([r]))
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


def sweep_moving_forces(setup: SweepSetup, trains: Sequence[Train], speeds: NDArray[np.float64], workers: int = 1,
                        scheduler: Optional[str] = None) -> list:
    """(``MovingLoadEnvelopes``, ``RefinedPeaks``) of every train (``workers`` processes; 1: in this
    process; ``scheduler``: the address of a Dask scheduler, one task a train, instead)."""
    jobs = [(setup, t, speeds) for t in trains]
    if scheduler is not None:
        return _sweep_dask(jobs, scheduler)
    if workers <= 1 or len(trains) < 2:
        return [_sweep_one(j) for j in jobs]
    with ProcessPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(_sweep_one, jobs))


def _sweep_dask(jobs: list, scheduler: str) -> list:
    """``_sweep_one`` of every job on the Dask cluster at ``scheduler`` (results in job order; the
    scheduler tried for ``study.workers.SCHEDULER_CONNECT_TIMEOUT``, as every command's)."""
    from vbikit.rail.spec import RailSpecError
    from vbikit.study.workers import dask_client

    client = dask_client(scheduler, RailSpecError)
    try:
        return client.gather(client.map(_sweep_one, jobs, pure=False))
    finally:
        client.close()


def coupled_envelopes(setup: SweepSetup, train: Train, speeds: NDArray[np.float64], irregularity: Optional[str] = None,
                      seed: int = 0, contact: str | float = "hertz"):
    """Envelopes of one train whose cars have masses and suspensions, as coupled car models
    (``rail_car``, point contact) — each car one ``VehicleMotion`` entering when its first axle
    reaches the bridge — over a smooth or irregular track; one ``simulate`` per speed."""
    from vbikit.solve.crossing import Crossing, VehicleMotion
    from vbikit.solve.moving_loads import MovingLoadEnvelopes, unsampled
    from vbikit.solve.simulate import simulate

    cars = rail_cars(train, contact)
    bridge = setup.bridge
    phi = bridge.mode_shapes(setup.points, np.full(setup.points.size, setup.y))
    n_v, n_p, n_e = speeds.size, setup.points.size, len(setup.effects)
    acc, disp, eff = np.empty((n_v, n_p)), np.empty((n_v, n_p)), np.empty((n_v, n_e))
    static_disp, static_eff = np.zeros(n_p), np.zeros(n_e)
    unconverged = np.zeros(n_v)
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
        unconverged[k] = result.unconverged_steps
        acc[k] = np.max(np.abs(result.xi_ddot @ phi.T), axis=0)
        disp[k] = np.max(np.abs(result.xi @ phi.T), axis=0)
        if n_e:
            from vbikit.analysis.effects import load_effect_response

            for e, effect in enumerate(setup.effects):
                resp = load_effect_response(result, effect)
                _, dynamic, static = resp.peak_series  # the samples, the one-sided limits at the jumps and the extremes between the samples
                eff[k, e] = np.max(np.abs(dynamic))
                static_eff[e] = max(static_eff[e], float(np.max(np.abs(static))))
        from vbikit.analysis.impact import static_modal_history

        static_disp = np.maximum(static_disp, np.max(np.abs(static_modal_history(result) @ phi.T), axis=0))
    return MovingLoadEnvelopes(speeds, setup.points, acc, disp, static_disp, eff, static_eff, setup.dx, unconverged,
                               **unsampled(n_v, n_p, n_e))  # (sampled peaks: their time sampling not estimated)


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
    length when documented (HSLM-A, presets; HSLM-B: its force spacing d, EN 1991-2 6.4.6.1.1), else its dominant repeated axle spacing
    (``vbikit.rail.signature``)."""
    if train.coach_length:
        return float(train.coach_length), ("force spacing d" if train.name.startswith(HSLM_B_NAME) else "coach length")
    from vbikit.rail.signature import dominant_wavelength

    d = dominant_wavelength(train.axle_positions, train.axle_loads)
    return d, ("dominant repeated axle spacing (train spectrum)" if d else "none (no repeated axle spacing)")


def train_resonances(train: Train, n0: float, orders: int = 4) -> NDArray[np.float64]:
    """v_i = n0 D / i [m/s], i = 1 … ``orders`` (entry i − 1 is order i; NaN when the train has no D),
    D from ``excitation_wavelength``."""
    d, _ = excitation_wavelength(train)
    return resonance_speeds(n0, d, orders=orders) if d else np.full(orders, np.nan)


def bogie_resonances(train: Train, n0: float, orders: int = 4) -> list[tuple[float, int, float]]:
    """(d [m], i, v [m/s]) of the resonances of the train's axle spacings within a bogie,
    v = n0 d / i (``Train.bogie_axle_spacings``; the same rule as the coach length's, EN 1991-2
    6.4.6, with the bogie's axle pair as the repeated pattern: on a short span, n0 is high and the
    coach-length resonances n0 D / i lie above any speed, while n0 d / i may not).  Every spacing,
    orders i = 1 … ``orders``; empty when the train's bogies are not known."""
    return [(float(d), i, float(n0 * d / i)) for d in train.bogie_axle_spacings for i in range(1, orders + 1)]


def nearest_resonance(speed: float, resonances: list[tuple[str, float]]) -> Optional[tuple[str, float]]:
    """The (label, v [m/s]) of ``resonances`` nearest to ``speed`` [m/s] (None when there are none)."""
    finite = [(label, v) for label, v in resonances if math.isfinite(v)]
    return min(finite, key=lambda r: abs(r[1] - speed)) if finite else None


def refine_train_peaks(setup: SweepSetup, train: Train, envelopes, tolerance: float = PEAK_TOLERANCE) -> RefinedPeaks:
    """``refine_peaks`` (``vbikit.rail.refine``) of one train's peak deck acceleration (over the deck
    points) from its sweep."""
    from vbikit.solve.moving_loads import moving_load_sweep

    def evaluate(v):
        env = moving_load_sweep(setup.bridge, train.axle_positions, train.axle_loads, v, setup.points, (), dx=setup.dx,
                                free_vibration=setup.free_vibration, y=setup.y, max_steps=setup.max_steps)
        return env.max_acceleration.max(axis=1)

    return refine_peaks(evaluate, envelopes.speeds, envelopes.max_acceleration.max(axis=1), tolerance)
