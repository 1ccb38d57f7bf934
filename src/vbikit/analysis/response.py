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
    if not (math.isfinite(y) and 0.0 <= float(bridge.span_coordinate(x, y)) <= bridge.span):
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


def girder_responses(result: CrossingResult, x: float | None = None, y: float | None = None) -> list[PointResponse]:
    """Responses on every girder line of a bridge with ``girder_y`` (Girder 1 first) at the section of
    the response point (x, y) (default: the bridge's; x default midspan) — the same x on a square
    deck, the same station ξ = x − y tan θ along the girders on a skew deck; an empty list for
    bridges without girders (a beam)."""
    bridge = result.crossing.bridge
    girder_y = getattr(bridge, "girder_y", None)
    if girder_y is None:
        return []
    return [point_response(result, gx, float(g)) for gx, g in zip(result.girder_sections(x, y), girder_y)]


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
        "speed": crossing.speed if crossing.single else crossing.max_speed,
        "n_contact_points_per_wheel": crossing.tire.point_count,
        "warnings": run_warnings(result, response.x, response.y),
    } | ({"response_girder": response_girder,
          "lateral_offset": crossing.lateral_offset if crossing.single else [m.lateral_offset for m in crossing.vehicles],
          **girder_summary(girders)} if girders else {}) | ({} if crossing.single else {"vehicles": vehicle_summaries(result)})


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
    if result.crossing.single:
        out["front_axle_x"] = result.front_position[:, 0]
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


def history_units(result: CrossingResult, names: list[str] | dict[str, object]) -> dict[str, str]:
    """Unit of each column of :func:`histories` (``girder3_strain`` → ``-``, ``tractor_pitch`` →
    ``rad``, ``contact_force_axle1_left`` → ``N``); the CSV header is ``name [unit]``."""
    from vbikit.solve.result import HISTORY_UNITS, dof_unit

    dofs = set(result.crossing.vehicle.dof_names)
    out = {}
    for name in names:
        base = name.split("_", 1)[1] if name.startswith("girder") and name[6:7].isdigit() else name
        if base in HISTORY_UNITS:
            out[name] = HISTORY_UNITS[base]
        elif name.endswith("_front_axle_x"):  # several vehicles: v1_front_axle_x, …
            out[name] = "m"
        elif name.startswith("moment_"):  # load effects (vbikit.analysis.effects): moment_x12.5[_static]
            out[name] = "N m"
        elif name.startswith(("shear_", "reaction_")):
            out[name] = "N"
        elif name.startswith("contact_force_"):
            out[name] = "N"
        elif name.startswith("contact_length_"):
            out[name] = "m"
        elif name in dofs:
            out[name] = dof_unit(name)
        elif name.endswith("_acceleration") and name.removesuffix("_acceleration") in dofs:
            out[name] = dof_unit(name.removesuffix("_acceleration")) + "/s^2"
        else:
            raise KeyError(f"no unit known for history {name!r}")
    return out


#: every key of the crossing summary (:func:`summary`, ``vbikit run --json``): unit and meaning;
#: per-wheel maps are keyed by wheel name, per-girder lists ordered Girder 1 first
SUMMARY_KEYS: dict[str, tuple[str, str]] = {
    "impact_factor": ("-", "displacement impact factor IM = (R_dyn,max − R_st,max)/R_st,max at the response point"),
    "max_dynamic_displacement": ("m", "dynamic peak displacement in the static peak's direction (negative: downward)"),
    "max_static_displacement": ("m", "static reference peak displacement"),
    "time_of_max_dynamic_displacement": ("s", "time of the dynamic peak"),
    "strain_impact_factor": ("-", "strain impact factor"),
    "max_dynamic_strain": ("-", "dynamic peak bottom-fibre strain (tension positive)"),
    "max_static_strain": ("-", "static reference peak strain"),
    "max_abs_acceleration": ("m/s^2", "largest absolute deck acceleration at the response point"),
    "max_abs_velocity": ("m/s", "largest absolute deck velocity at the response point"),
    "response_x": ("m", "response point from the entry support"),
    "response_y": ("m", "response point from the deck centreline"),
    "frequencies_hz": ("Hz", "bridge natural frequencies of the retained modes"),
    "vehicle_frequencies_hz": ("Hz", "vehicle natural frequencies on rigid ground"),
    "static_wheel_loads": ("N", "static load of each wheel"),
    "min_wheel_force": ("N", "smallest tire force of each wheel (0: contact lost)"),
    "max_wheel_force": ("N", "largest tire force of each wheel"),
    "contact_loss": ("-", "per wheel: lost (true/false), first_x [m] and first_time [s] where contact was first lost, duration [s]"),
    "contact_length_range": ("m", "per wheel: [smallest, largest] length of the patch in contact (0 for point tires)"),
    "tire_model": ("-", "tire model name"),
    "n_steps": ("-", "number of time steps"),
    "dt": ("s", "time step"),
    "duration": ("s", "simulated time"),
    "integrator": ("-", "time integrator"),
    "speed": ("m/s", "vehicle speed at t = 0"),
    "n_contact_points_per_wheel": ("-", "contact points per wheel"),
    "response_girder": ("-", "girder of the response point (slab-on-girder bridges)"),
    "lateral_offset": ("m", "vehicle centreline from the deck centreline"),
    "girder_y": ("m", "girder lines from the deck centreline"),
    "girder_impact_factors": ("-", "displacement impact factor of every girder at response_x"),
    "girder_strain_impact_factors": ("-", "strain impact factor of every girder"),
    "girder_max_dynamic_displacement": ("m", "dynamic peak displacement of every girder"),
    "girder_max_static_displacement": ("m", "static peak displacement of every girder"),
    "girder_max_dynamic_strain": ("-", "dynamic peak strain of every girder"),
    "girder_max_abs_acceleration": ("m/s^2", "largest absolute acceleration of every girder"),
    "governing_girder": ("-", "the girder with the largest static peak displacement (the most loaded)"),
    "governing_girder_impact_factor": ("-", "impact factor of the governing girder"),
    "vehicles": ("-", "several vehicles: per vehicle its model, direction, entry_time [s], lateral_offset [m], "
                      "speed [m/s], tire_model, static_wheel_loads [N], min_wheel_force [N] and contact_loss"),
    "design_code_allowances": ("-", "loaded_length [m], first_frequency [Hz], n_axles and each design code's "
                                    "dynamic allowance [-] for the deflection at response_x"),
    "moment": ("N m", "bending moments: static_peak, dynamic_peak [N m], impact_factor [-], position x [m] of the "
                      "first requested section, every section under sections, with the code allowances"),
    "shear": ("N", "shear forces (just right of x), as moment"),
    "reaction": ("N", "support reactions, as moment"),
    "warnings": ("-", "messages about the inputs or the run (also printed on standard error)"),
    "inputs": ("-", "the inputs as run, every default filled in (units as in the scenario reference)"),
}


def summary_units(summary_: dict[str, object]) -> dict[str, str]:
    """The ``units`` map of a summary: unit of every key present ("-" for dimensionless)."""
    return {k: SUMMARY_KEYS[k][0] for k in summary_ if k in SUMMARY_KEYS}
