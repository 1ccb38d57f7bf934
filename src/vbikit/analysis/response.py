"""Response extraction at a deck point and the crossing summary."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vbikit.analysis.checks import run_warnings
from vbikit.analysis.impact import ImpactFactor, impact_factor, static_modal_history
from vbikit.solve.result import CrossingResult


@dataclass(frozen=True)
class PointResponse:
    """Dynamic and static histories at one deck point (x, y) [m]: SI units, z up, tension positive."""

    x: float
    y: float
    time: NDArray[np.float64]
    displacement: NDArray[np.float64]
    static_displacement: NDArray[np.float64]
    strain: NDArray[np.float64]
    static_strain: NDArray[np.float64]
    velocity: NDArray[np.float64]
    acceleration: NDArray[np.float64]
    strain_rate: NDArray[np.float64] | None = None

    @property
    def displacement_impact(self) -> ImpactFactor:
        return impact_factor(self.time, self.displacement, self.static_displacement, self.velocity)

    @property
    def strain_impact(self) -> ImpactFactor:
        return impact_factor(self.time, self.strain, self.static_strain, self.strain_rate)


def point_response(result: CrossingResult, x: float | None = None, y: float | None = None) -> PointResponse:
    """Dynamic and static responses at (x, y) [m]; x defaults to midspan, y to the bridge's
    ``default_response_y`` (its default girder on a slab-on-girder deck, as in scenarios)."""
    bridge = result.crossing.bridge
    x, y = result.point(x, y)
    if not (math.isfinite(y) and 0.0 <= x <= bridge.span):
        raise ValueError(f"response.x must be within the span 0 … {bridge.span} m and response.y finite, got ({x}, {y})")
    phi = bridge.mode_shapes([x], [y])[0]
    eps = bridge.strain_shapes([x], [y])[0]
    xi_st = static_modal_history(result)
    return PointResponse(
        x, y, result.time,
        displacement=result.xi @ phi,
        static_displacement=xi_st @ phi,
        strain=result.xi @ eps,
        static_strain=xi_st @ eps,
        velocity=result.xi_dot @ phi,
        acceleration=result.xi_ddot @ phi,
        strain_rate=result.xi_dot @ eps,
    )


def contact_loss(result: CrossingResult) -> dict[str, dict[str, float | bool]]:
    """Per wheel: whether its tire lost contact (zero force), where first (wheel x [m]) and for how long [s]."""
    out: dict[str, dict[str, float | bool]] = {}
    x_wheel = result.wheel_positions()
    for w, wheel in enumerate(result.crossing.vehicle.wheels):
        if wheel.stiffness <= 0:
            continue
        off = result.wheel_forces[:, w] <= 0.0
        entry: dict[str, float | bool] = {"lost": bool(off.any())}
        if off.any():
            i = int(np.argmax(off))
            entry["first_x"] = float(x_wheel[i, w])
            entry["first_time"] = float(result.time[i])
            entry["duration"] = float(off.sum() * result.dt)
        out[wheel.name] = entry
    return out


def girder_responses(result: CrossingResult, x: float | None = None) -> list[PointResponse]:
    """Responses at x (default midspan) on every girder line of a bridge with ``girder_y``
    (Girder 1 first); an empty list for bridges without girders (a beam)."""
    girder_y = getattr(result.crossing.bridge, "girder_y", None)
    if girder_y is None:
        return []
    return [point_response(result, x, float(y)) for y in girder_y]


def girder_summary(girders: list[PointResponse]) -> dict[str, object]:
    """Per-girder peaks and impact factors, and the governing girder: the one with the largest
    static peak displacement (the most loaded), whose IM is the design value (paper §3)."""
    disp = [g.displacement_impact for g in girders]
    strain = [g.strain_impact for g in girders]
    governing = int(np.argmax([abs(d.static_peak) for d in disp])) + 1
    return {
        "girder_y": [g.y for g in girders],
        "girder_impact_factors": [d.impact_factor for d in disp],
        "girder_strain_impact_factors": [e.impact_factor for e in strain],
        "girder_max_dynamic_displacement": [d.dynamic_peak for d in disp],
        "girder_max_static_displacement": [d.static_peak for d in disp],
        "girder_max_dynamic_strain": [e.dynamic_peak for e in strain],
        "girder_max_abs_acceleration": [float(np.max(np.abs(g.acceleration))) for g in girders],
        "governing_girder": governing,
        "governing_girder_impact_factor": disp[governing - 1].impact_factor,
    }


def summary(result: CrossingResult, response: PointResponse, girders: list[PointResponse] | None = None,
            response_girder: int | None = None) -> dict[str, object]:
    """The JSON-ready summary of a crossing: impact factors, peaks, bridge frequencies, step data;
    with ``girders`` (from :func:`girder_responses`) also the per-girder values and the governing girder."""
    crossing = result.crossing
    disp = response.displacement_impact
    strain = response.strain_impact
    wheel_forces = result.wheel_forces
    return {
        "impact_factor": disp.impact_factor,
        "max_dynamic_displacement": disp.dynamic_peak,
        "max_static_displacement": disp.static_peak,
        "time_of_max_dynamic_displacement": disp.time_dynamic_peak,
        "strain_impact_factor": strain.impact_factor,
        "max_dynamic_strain": strain.dynamic_peak,
        "max_static_strain": strain.static_peak,
        "max_abs_acceleration": float(np.max(np.abs(response.acceleration))),
        "max_abs_velocity": float(np.max(np.abs(response.velocity))),
        "response_x": response.x,
        "response_y": response.y,
        "frequencies_hz": [float(f) for f in crossing.bridge.frequencies_hz],
        "vehicle_frequencies_hz": [float(f) for f in crossing.vehicle.natural_frequencies()],
        "static_wheel_loads": {w.name: float(p) for w, p in zip(crossing.vehicle.wheels, crossing.vehicle.static_wheel_loads())},
        "min_wheel_force": {w.name: float(f) for w, f in zip(crossing.vehicle.wheels, wheel_forces.min(axis=0))},
        "max_wheel_force": {w.name: float(f) for w, f in zip(crossing.vehicle.wheels, wheel_forces.max(axis=0))},
        "contact_loss": contact_loss(result),
        "contact_length_range": {
            w.name: [float(lo), float(hi)]
            for w, lo, hi in zip(crossing.vehicle.wheels, result.contact_lengths.min(axis=0), result.contact_lengths.max(axis=0))
        },
        "tire_model": crossing.tire.name,
        "n_steps": result.n_steps,
        "dt": result.dt,
        "duration": float(result.time[-1]),
        "integrator": crossing.integrator,
        "speed": crossing.speed if not crossing.vehicles else crossing.max_speed,
        "n_contact_points_per_wheel": crossing.tire.point_count,
        "warnings": run_warnings(result, response.x),
    } | ({"response_girder": response_girder,
          "lateral_offset": crossing.lateral_offset if not crossing.vehicles else [m.lateral_offset for m in crossing.vehicles],
          **girder_summary(girders)} if girders else {}) | ({"vehicles": vehicle_summaries(result)} if crossing.vehicles else {})


def vehicle_summaries(result: CrossingResult) -> list[dict[str, object]]:
    """Per vehicle of a several-vehicle crossing: its model, motion, static wheel loads, min / max
    wheel forces [N] and whether any of its tires lost contact (wheel names without the ``vN_`` prefix)."""
    crossing = result.crossing
    combined = crossing.vehicle
    loss = contact_loss(result)
    out = []
    for i, (m, vehicle) in enumerate(zip(crossing.vehicles, combined.parts)):
        sl = slice(combined.wheel_offsets[i], combined.wheel_offsets[i + 1])
        names = [w.name for w in vehicle.wheels]
        forces = result.wheel_forces[:, sl]
        tire = m.tire or crossing.tire
        out.append({
            "model": vehicle.name,
            "description": vehicle.description,
            "direction": m.direction,
            "speed": m.speed,
            "acceleration": m.acceleration,
            "entry_time": m.entry_time,
            "lateral_offset": m.lateral_offset,
            "tire_model": tire.name,
            "gross_weight": float(vehicle.total_weight),
            "static_wheel_loads": dict(zip(names, map(float, vehicle.static_wheel_loads()))),
            "min_wheel_force": dict(zip(names, map(float, forces.min(axis=0)))),
            "max_wheel_force": dict(zip(names, map(float, forces.max(axis=0)))),
            "contact_loss": any(bool(loss[w.name]["lost"]) for w in combined.wheels[sl] if w.name in loss),
        })
    return out


def histories(result: CrossingResult, response: PointResponse,
              girders: list[PointResponse] | None = None) -> dict[str, NDArray[np.float64]]:
    """Named time histories for CSV output (SI units); with ``girders`` also ``girder{g}_*`` columns
    (displacement, static displacement, strain, static strain, acceleration) for every girder."""
    out: dict[str, NDArray[np.float64]] = {
        "time": result.time,
        "displacement": response.displacement,
        "static_displacement": response.static_displacement,
        "strain": response.strain,
        "static_strain": response.static_strain,
        "velocity": response.velocity,
        "acceleration": response.acceleration,
    }
    if result.front_position.ndim == 1:
        out["front_axle_x"] = result.front_position
    else:  # several vehicles: out = {time, v1_front_axle_x, …, displacement, …}
        fronts = {f"v{i + 1}_front_axle_x": result.front_position[:, i] for i in range(result.front_position.shape[1])}
        out = {"time": out.pop("time"), **fronts, **out}
    for g, r in enumerate(girders or [], start=1):
        out[f"girder{g}_displacement"] = r.displacement
        out[f"girder{g}_static_displacement"] = r.static_displacement
        out[f"girder{g}_strain"] = r.strain
        out[f"girder{g}_static_strain"] = r.static_strain
        out[f"girder{g}_acceleration"] = r.acceleration
    for w, f in zip(result.crossing.vehicle.wheels, result.wheel_forces.T):
        out[f"contact_force_{w.name}"] = f
    if np.any(result.contact_lengths):
        for w, length in zip(result.crossing.vehicle.wheels, result.contact_lengths.T):
            out[f"contact_length_{w.name}"] = length
    for j, name in enumerate(result.crossing.vehicle.dof_names):
        out[name] = result.q[:, j]
        out[f"{name}_acceleration"] = result.q_ddot[:, j]
    return out
