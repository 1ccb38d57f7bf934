"""A drive-by sweep as a job of the study runner (``vbikit.study.run.run_study``): batches of
cases on local processes or a Dask cluster, each finished batch stored at once, a killed run
resumed where it stopped.

One case = one crossing of the instrumented vehicle (``spec.DriveBy``) at one combination of the
sweep: its sensors' histories at the sensor rate, the frequency identified from them
(``identify.identify_frequency``, method ``contact`` or ``sensor``) over the time the front
wheel is on the deck, the bridge's true first frequency (its modal model, damaged when the case
has damage), and the labels.  Noise seeds derive from the file's seed and the case index
(``vbikit.study.spec.derive_seed``), so a case's result depends only on the file.
"""
from __future__ import annotations

import copy
import json
import logging
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Optional

import numpy as np
from numpy.typing import NDArray

from vbikit._validation import MAX_STEPS_LIMIT
from vbikit._words import counted, raise_budget
from vbikit.analysis.checks import dataset_flag_attrs
from vbikit.driveby.contact import SingleAxle, contact_acceleration_from_measured, on_bridge
from vbikit.driveby.identify import (CURVATURE_LOCATION_CAVEAT, identify_frequency, mode_shape_squares,
                                     residual_response, shape_change)
from vbikit.driveby.quality import interaction_shift, mode_envelope_offset, unconverged_pass_flags, vehicle_modes
from vbikit.driveby.sensors import (CONTACT_TRUTH, Sensor, SensorError, amplitude_spectrum, contact_truth, measure,
                                    sensor_row)
from vbikit.driveby.spec import (BAND_MAX_HZ, DATASET_FILE, ZARR_FILE, DriveBy, DriveByError,
                                 check_dataset_format)
from vbikit.driveby.variability import SPLIT_NAMES, draw, perturbed_vehicle, split_of, temperature_factor
from vbikit.driveby.vehicles import DRIVEBY_VEHICLES, driveby_vehicle
from vbikit.outputs import OUTPUTS, cf_unit, member_units
from vbikit.vehicle.model import GRAVITY

log = logging.getLogger(__name__)

#: points of the mode-shape estimate along the deck (x = 0 … span)
SHAPE_POINTS = 41

#: per-case outputs: name -> (units, long name)
CASE_OUTPUTS: dict[str, tuple[str, str]] = {
    "identified_frequency_hz": ("Hz", "bridge frequency identified from the vehicle"),
    "bridge_frequency_hz": ("Hz", "true first natural frequency of the (damaged) bridge, modal model"),
    "resolution_hz": ("Hz", "spectral (Rayleigh) resolution 1 / T of the identification record"),
    "vehicle_frequency_hz": ("Hz", "first natural frequency of the vehicle on rigid ground"),
    "record_start": ("s", "start of the identification record (front wheel enters the deck)"),
    "record_end": ("s", "end of the identification record (front wheel leaves the deck)"),
    "n_steps": ("1", "integration steps of the crossing"),
    "unconverged_steps": (cf_unit(OUTPUTS["unconverged_steps"].unit), OUTPUTS["unconverged_steps"].long_name),
    "n_samples": ("1", "sensor samples of the case"),
    "label_frequency_hz": ("Hz", "the expected frequency the identified peak's label names (NaN: none)"),
    "peak_snr_db": ("dB", "identified peak's power spectral density over the background (the larger of the median of "
                          "the band's other lines and of those within 5 main-lobe half-widths, outside its main lobe)"),
    "peak_snr_threshold_db": ("dB", "level that the highest peak of noise alone exceeds in 1 % of passes, "
                                    "10 log10(log2(M / 0.01)), M = (band width) × T independent lines"),
    "peak_rival_db": ("dB", "highest other peak within 2 main-lobe half-widths of the identified one, relative to it "
                            "(-inf: none; flagged above -6 dB)"),
    "vehicle_distance": ("1", "distance of the identified frequency to the nearest vehicle frequency, in units of the "
                              "resolution 1/T (inf: no vehicle frequency)"),
    "vehicle_distance_limit": ("1", "flagged below: 2 main-lobe half-widths or the half-power half-band ζ f_v of that "
                                    "vehicle mode, in units of 1/T"),
    "band_edge_distance": ("1", "distance of the identified frequency to the nearer edge of the search band, in units of "
                                "the resolution 1/T"),
    "band_edge_limit": ("1", "flagged below: one main-lobe half-width of the window, in units of 1/T"),
    "speed_correction_hz": ("Hz", "correction applied to the peak for the speed: 0, the shifted pair f_b ± v/(2L) "
                                  "is 1/T apart and merges into one lobe centred on f_b"),
    "interaction_shift_hz": ("Hz", "estimated shift of the bridge's first frequency by the vehicle's mass while it is on "
                                   "the deck (the frozen mode-and-vehicle system along the pass, weighted by phi^2 and "
                                   "the window; flagged above half a resolution 1/T)"),
    "sensors_identified": ("1", "other acceleration sensors of the vehicle whose own identification is reliable"),
    "sensors_agree": ("1", "of those, the sensors within the resolution 1/T of this identification (one that is not "
                           "makes it unreliable)"),
    "band_low_hz": ("Hz", "lower end of the search band"),
    "on_bridge_start_sample": ("1", "segmentation: first sample of sensor_history with the front wheel on the deck"),
    "on_bridge_end_sample": ("1", "segmentation: last sample of sensor_history with the front wheel on the deck "
                                  "(before: approach, after: off the bridge)"),
    "off_bridge_sample": ("1", "segmentation: first sample with every wheel off the deck (NaN: not within the record)"),
    "bridge_frequency_2_hz": ("Hz", "true second natural frequency of the bridge, modal model (NaN: one mode)"),
    "temperature_c": ("degC", "deck temperature drawn for the pass (NaN: not varied)"),
    "stiffness_factor": ("1", "E(T) / E(T_ref) applied to EI (variability.temperature_coefficient)"),
    "support_stiffness": ("N m-1", "vertical stiffness of every support spring (NaN: the file's supports)"),
    "vehicle_mass_kg": ("kg", "vehicle mass carried by the wheels (static wheel loads / g) of the drawn vehicle"),
    "coupling_error_rms": ("1", "decoupled run: relative RMS difference of the identification sensor's noise-free "
                                "record against a coupled run of the same pass (NaN: not checked, coupling_check_every)"),
    "coupling_frequency_difference_hz": ("Hz", "decoupled run: identified frequency minus that of the coupled run of "
                                                "the same pass, same noise (NaN: not checked)"),
    "band_high_hz": ("Hz", "upper end of the search band"),
    "background_vehicles": ("1", "background trucks that entered the deck during the pass (variability.traffic_flow; "
                                 "0: none)"),
    "background_mass_kg": ("kg", "their total mass (static wheel loads / g)"),
}
#: per-case text outputs: name -> long name
CASE_TEXT: dict[str, str] = {
    "identified_frequency_label": "what the identified peak is: bridge_k (bridge mode k of the model, the merged "
                                  "shifted pair f_b ± v/(2L)), vehicle_k (the vehicle's own frequency k), driving_n "
                                  "(n v / L), none (no expected frequency)",
    "identified_frequency_reason": "why the identified frequency is unreliable, in words ('' when reliable)",
}


def case_draw(spec: DriveBy, case: dict) -> dict[str, Any]:
    """The random parameters of a case of a file with [variability] (``variability.draw``, keyed by
    the case's index; the vehicle factors drawn for the largest vehicle of a fleet), {} otherwise."""
    if "index" not in case:
        return {}
    n_dof, n_wheels = vehicle_dims(spec)
    return draw(spec.variability, spec.seed, case["index"], n_dof, n_wheels, len(spec.fleet))


def vehicle_dims(spec: DriveBy) -> tuple[int, int]:
    """The most DOFs and the most wheels of the file's vehicles (one, or those of the fleet)."""
    built = [_vehicle(spec, {"vehicle": k} if spec.fleet else {}) for k in range(max(1, len(spec.fleet)))]
    return max(v.n_dof for v in built), max(len(v.wheels) for v in built)


def case_vehicle(spec: DriveBy, case: dict) -> Optional[int]:
    """The fleet vehicle (index into ``spec.fleet``) of a case: its own (``fleet = "all"``) or
    drawn (``fleet = "draw"``); None without a fleet.  A case of a drawing fleet that is not a
    pass (the file's own tables) takes the first vehicle."""
    if not spec.fleet:
        return None
    if "vehicle" in case:
        return int(case["vehicle"])
    return int(case_draw(spec, case).get("vehicle", 0))


def _vary_bridge(spec: DriveBy, case: dict, bridge: dict, drawn: dict) -> dict:
    var = spec.variability
    bridge = dict(bridge)
    if "temperature" in drawn:
        f = temperature_factor(var, drawn["temperature"])
        ei = bridge.get("EI")
        if ei is None:
            raise DriveByError("variability.temperature: needs the bridge's EI (bridge.EI) to scale")
        bridge["EI"] = [f * e for e in ei] if isinstance(ei, list) else f * ei
    if var.support_stiffness is not None:
        factor = var.scour_classes[case["scour_class"]] if "scour_class" in case else 1.0
        bridge["support_stiffness"] = var.support_stiffness * factor
    if "rotational_stiffness_entry" in drawn:
        bridge["rotational_stiffness"] = [drawn["rotational_stiffness_entry"], drawn["rotational_stiffness_exit"]]
    if drawn.get("damage_severity", 0.0) > 0.0:
        bridge["damage"] = [*bridge.get("damage", []), {"position": drawn["damage_position"], "severity": drawn["damage_severity"],
                                                        "length": drawn.get("damage_length", spec.damage_length)}]
    return bridge


def _case_scenario(spec: DriveBy, case: dict) -> dict:
    """The scenario dict of one case (a stand-in vehicle when the vehicle is not a scenario preset)."""
    data = copy.deepcopy(spec.scenario)
    drawn = case_draw(spec, case)
    if "speed" in drawn:
        case = {**case, "speed": drawn["speed"]}
    if spec.variability.active:
        data["bridge"] = _vary_bridge(spec, case, data["bridge"], drawn)
    from vbikit.vehicle.presets import VEHICLE_PRESETS

    table = spec.vehicle_table(case_vehicle(spec, case))
    data["vehicle"] = dict(table) if table["model"] in VEHICLE_PRESETS else {"model": "sprung-mass"}
    crossing = data.setdefault("crossing", {})
    if "speed" in case:
        crossing.pop("speed_kmh", None)
        crossing["speed"] = case["speed"]
    elif "speed" not in crossing and "speed_kmh" not in crossing:
        crossing["speed"] = 8.0
    road = data.setdefault("road", {})
    if "road_class" in case:
        road["class"] = case["road_class"]
    if "road_seed" in case or "index" in case:
        road["seed"] = case_road_seed(spec, case)
    if case.get("damage_severity", 0.0) > 0.0:
        data["bridge"] = dict(data["bridge"])
        data["bridge"]["damage"] = [*data["bridge"].get("damage", []), {
            "position": case["damage_position"], "length": spec.damage_length, "severity": case["damage_severity"]}]
    return data


def case_road_seed(spec: DriveBy, case: dict) -> int:
    """The road seed of a case: swept, or a random pass's own, seeded by (file seed, draw index)
    (``vbikit.study.spec.derive_seed``), or the file's [road] seed."""
    if "road_seed" in case:
        return int(case["road_seed"])
    if "index" in case:
        from vbikit.study.spec import derive_seed

        return derive_seed(spec.seed, case["index"])
    return int(spec.scenario.get("road", {}).get("seed", 0))


def _vehicle(spec: DriveBy, case: dict):
    """The case's vehicle: the file's (or its fleet vehicle), its parameters scaled by the case's
    drawn factors."""
    k = case_vehicle(spec, case) if "index" in case else case.get("vehicle")
    if "index" in case and spec.variability.vehicle_spread > 0:
        base = _vehicle(spec, {} if k is None else {"vehicle": k})
        return perturbed_vehicle(base, case_draw(spec, case)["vehicle_factors"])
    table = spec.vehicle_table(k)
    key = json.dumps(table, sort_keys=True, default=str)
    if key not in _VEHICLES:
        _VEHICLES[key] = _build_vehicle(table, "vehicle" if k is None else f"fleet.{spec.fleet[k][0]}")
    return _VEHICLES[key]


_VEHICLES: dict[str, Any] = {}


def _build_vehicle(table: dict, where: str = "vehicle"):
    model = table["model"]
    params = {k: v for k, v in table.items() if k != "model"}
    if model not in DRIVEBY_VEHICLES:
        from vbikit.vehicle.presets import VEHICLE_PRESETS

        if model not in VEHICLE_PRESETS:
            raise DriveByError(f"{where}.model: {model!r} is unknown; allowed: {', '.join([*DRIVEBY_VEHICLES, *VEHICLE_PRESETS])}")
    try:
        return driveby_vehicle(model, **params)
    except TypeError as err:
        raise DriveByError(f"{where}: {err}") from None


_BUILT: dict[str, Any] = {}
#: bridges built for a case, by their scenario table: the passes of a dataset share a few bridges
_BRIDGES: dict[str, Any] = {}


#: [m] added on each side of the range a case's contact points touch when its random road is
#: generated (``_scenario_crossing``): the time grid may end up to a step past the crossing's duration
ROAD_WINDOW_MARGIN = 1.0


def _scenario_crossing(data: dict, base_dir: str):
    """The scenario's crossing parts; its bridge taken from ``_BRIDGES`` when an earlier case had
    the same [bridge] table (a random pass changes the road, the speed and the vehicle, rarely the
    bridge: its eigen-solution is computed once).  ``roads(window)`` builds the left and right road
    profiles over ``window`` = (x_lo, x_hi) only (``vbikit.scenario.build.build_road``: the same road
    there as the whole period's, at a fraction of the cost)."""
    import types

    from vbikit.scenario import build, parse_scenario
    from vbikit.scenario.build import build_right_road, build_road, build_tire, check_road_budget

    scenario = parse_scenario(data, base_dir)
    from vbikit.scenario.schema import ScenarioError
    from vbikit.solve.crossing import require_every_result

    require_every_result(scenario.crossing.resolve, "a pass reads the vehicle's accelerations, which need the step for "
                         "every result", ScenarioError)
    key = json.dumps([data["bridge"], str(base_dir)], sort_keys=True)
    if key not in _BRIDGES:
        if len(_BRIDGES) > 16:
            _BRIDGES.clear()
        _BRIDGES[key] = build(scenario).crossing.bridge  # the whole scenario checked once per bridge
    check_road_budget(scenario.road, None)

    def roads(window):
        road = build_road(scenario.road, scenario, window)
        return road, build_right_road(scenario.road, scenario, road, window)

    c = scenario.crossing
    return types.SimpleNamespace(bridge=_BRIDGES[key], tire=build_tire(scenario.tire), roads=roads, speed=c.speed_ms,
                                 acceleration=c.acceleration, approach=c.approach, run_in=c.run_in,
                                 free_vibration=c.free_vibration, dt=c.dt, integrator=c.integrator,
                                 loss_of_contact=scenario.tire.loss_of_contact)


def case_crossing(spec: DriveBy, case: dict):
    """The crossing of one case: the scenario's bridge, tire, road and options with the vehicle,
    the step a divisor of the sensor period (so that resampling is exact decimation)."""
    from vbikit.scenario.schema import ScenarioError
    from vbikit.solve import Crossing
    from vbikit.solve.timestep import choose_time_step

    data = _case_scenario(spec, case)
    key = json.dumps([data, spec.vehicle_table(case_vehicle(spec, case)), spec.sampling.rate, spec.base_dir, spec.method,
                      spec.gap,
                      case.get("index") if spec.variability.vehicle_spread > 0 or spec.variability.traffic_flow else None],
                     sort_keys=True)
    if key in _BUILT:
        return _BUILT[key]
    try:
        c = _scenario_crossing(data, spec.base_dir)
    except ScenarioError as err:
        raise DriveByError(f"{err}".replace("invalid scenario:\n  ", "")) from None
    vehicle = _vehicle(spec, case)
    kwargs = dict(tire=c.tire, road=None, road_right=None, speed=c.speed, acceleration=c.acceleration,
                  approach=c.approach, run_in=c.run_in, free_vibration=c.free_vibration, integrator=c.integrator,
                  loss_of_contact=c.loss_of_contact)

    others: tuple = ()
    if spec.method == "residual":  # the same vehicle following at the gap
        from vbikit.solve import VehicleMotion

        others = (VehicleMotion(vehicle, c.speed, entry_time=spec.gap / c.speed),)
    elif spec.variability.traffic_flow is not None and "index" in case:
        from vbikit.driveby.traffic import background_vehicles

        others = background_vehicles(spec.variability, case_draw(spec, case)["traffic_seed"], c.bridge.span, c.speed)

    def make(dt):
        if not others:
            return Crossing(c.bridge, vehicle, dt=dt, **kwargs)
        from vbikit.solve import VehicleMotion

        lead = VehicleMotion(vehicle, c.speed, acceleration=0.0 if spec.method == "residual" else c.acceleration)
        return Crossing(c.bridge, vehicles=(lead, *others), dt=dt,
                        **{k: v for k, v in kwargs.items() if k not in ("speed", "acceleration")})

    lo, hi = make(c.dt).road_extent()  # the road only where the contact points go (a road does not move them)
    try:
        kwargs["road"], kwargs["road_right"] = c.roads((lo - ROAD_WINDOW_MARGIN, hi + ROAD_WINDOW_MARGIN))
    except ScenarioError as err:
        raise DriveByError(f"{err}".replace("invalid scenario:\n  ", "")) from None
    crossing = make(c.dt)
    if c.dt is None:
        dt = choose_time_step(crossing)
        k = max(1, math.ceil(1.0 / (dt * spec.sampling.rate) - 1e-9))
        crossing = make(1.0 / (k * spec.sampling.rate))
    if len(_BUILT) > 64:
        _BUILT.clear()
    _BUILT[key] = crossing
    return crossing


def case_sensors(spec: DriveBy, case: dict) -> tuple[Sensor, ...]:
    """The sensors of a case (``noise_rms`` of the sweep replacing every sensor's noise)."""
    if "noise_rms" not in case:
        return spec.sensors
    import dataclasses

    return tuple(dataclasses.replace(s, noise_rms=case["noise_rms"], noise_snr_db=None) for s in spec.sensors)


#: the scenario keys a sweep key sets (``_case_scenario``): scenario key -> sweep key
_SWEPT = {"crossing.speed": "speed", "road.class": "road_class", "road.seed": "road_seed",
          "bridge.damage": "damage_position"}


def _in_sweep_words(message: str, case: dict, damage_length: float) -> str:
    """A case's scenario error in the user's words: a key the sweep set is named as ``sweep.<key>``
    with the case's value (``crossing.speed`` of ``sweep.speed = [0]`` → ``sweep.speed = 0``)."""
    for scenario_key, sweep_key in _SWEPT.items():
        if sweep_key in case and scenario_key in message:
            head, _, rest = message.partition(scenario_key)
            rest = rest.split(":", 1)[1].strip() if ":" in rest else rest
            where = (f"sweep.damage_position = {case['damage_position']!r} (damage_length = {damage_length:g} m)"
                     if sweep_key == "damage_position" else f"sweep.{sweep_key} = {case[sweep_key]!r}")
            return f"{where}: {rest}"
    return message


#: sweep keys that do not change whether a case can be built (one case of each value is checked)
_NEUTRAL = ("road_seed", "noise_rms")


def _crossing(spec: DriveBy, case: dict):
    try:
        return case_crossing(spec, case)
    except DriveByError as err:
        raise DriveByError(_in_sweep_words(str(err), case, spec.damage_length)) from None


#: case keys of a random pass ([variability]) that select its draw: the passes of one combination of
#: the sweep share their checks (``check_cases``)
_DRAW_KEYS = ("index", "pass")


def _step_probes(spec: DriveBy, case: dict) -> list[dict]:
    """The cases whose integration steps bound ``case``'s (``estimate_steps``): itself, or for a
    random pass (its speed drawn anywhere in ``variability.speed``) the file's vehicle at both ends
    of the speed range."""
    if "index" not in case:
        return [case]
    base = {k: v for k, v in case.items() if k not in _DRAW_KEYS}
    speeds = spec.variability.speed
    probes = [base] if speeds is None else [{**base, "speed": v} for v in sorted(set(speeds))]
    if spec.fleet and "vehicle" not in case:  # a drawn vehicle: any of the fleet
        probes = [{**p, "vehicle": k} for p in probes for k in range(len(spec.fleet))]
    return probes


def estimate_steps(spec: DriveBy) -> float:
    """The integration steps of the whole sweep: each case's duration / time step, from one crossing
    built for each distinct speed of the sweep (the step and duration depend on the speed, not on
    the road seed or the noise).  A random pass's speed is drawn anywhere in ``variability.speed``:
    its duration falls and its step (a divisor of the sensor period, at most the road spacing / v)
    does not grow with the speed, so it takes at most the slow end's duration / the fast end's step
    (the file's vehicle: a drawn vehicle's step may differ by its spread).  Cheap for any number of
    cases."""
    per_speed: dict[Any, tuple[float, float]] = {}
    total = 0.0
    for case in spec.cases or [{}]:
        for probe in _step_probes(spec, case):
            v = (probe.get("speed"), probe.get("vehicle"))
            if v not in per_speed:
                c = _crossing(spec, probe)
                per_speed[v] = (c.duration, c.dt)
        ends = [per_speed[(p.get("speed"), p.get("vehicle"))] for p in _step_probes(spec, case)]
        total += max(d for d, _ in ends) / min(dt for _, dt in ends)
    return total


def check_cases(spec: DriveBy) -> float:
    """Validate the budget first (``estimate_steps`` against ``max_steps``), then every distinct case
    (scenario, vehicle, sensors; cases that differ only in ``_NEUTRAL`` keys once; of the random
    passes of one sweep combination and scour class the first, the temperature range's ends by
    their stiffness factor) before anything runs; returns the estimated integration steps of the
    sweep."""
    if spec.variability.traffic_flow is not None and (spec.coupling == "decoupled" or spec.method == "residual"):
        raise DriveByError("variability.traffic_flow: background traffic needs coupling = \"coupled\" and an "
                           "identification.method other than \"residual\" (one instrumented vehicle, trucks around it)")
    if spec.coupling == "decoupled" and spec.method == "residual":
        raise DriveByError("coupling: \"decoupled\" runs one vehicle; identification.method = \"residual\" (a "
                           "following vehicle) needs coupling = \"coupled\"")
    var = spec.variability
    for t in var.temperature or ():
        if temperature_factor(var, t) <= 0.0:
            raise DriveByError(f"variability.temperature: {t:g} °C gives E(T)/E(T_ref) = {temperature_factor(var, t):.3g} "
                               f"<= 0 with temperature_coefficient {var.temperature_coefficient:g} /°C and "
                               f"temperature_reference {var.temperature_reference:g} °C; narrow the range")
    check_dataset_format(spec)
    base = _crossing(spec, {})  # the file's own tables, before the sweep overrides any of their keys
    if spec.coupling == "decoupled" and base.run_in > 0:
        raise DriveByError(f"crossing.run_in = {base.run_in:g} m: coupling = \"decoupled\" starts the vehicle at rest "
                           "(its solution has no run-in); use coupling = \"coupled\" or run_in = 0")
    check_drawn_bridge(spec, base.bridge)
    total = estimate_steps(spec)
    if total > spec.max_steps:
        raise DriveByError(f"max_steps: the sweep needs about {total:.3g} integration steps ({len(spec.cases):,} cases), "
                           f"above the budget {spec.max_steps:.3g}; {raise_budget('max_steps', '--max-steps', MAX_STEPS_LIMIT)}, "
                           "or sweep fewer cases")
    seen: set = set()
    fleet_cases = [{"vehicle": k} for k in range(len(spec.fleet))]  # every vehicle of the fleet, whatever it draws
    for i, case in enumerate([*(spec.cases or [{}]), *fleet_cases]):
        shape = tuple((k, v) for k, v in case.items() if k not in (*_NEUTRAL, *_DRAW_KEYS))
        neutral = tuple((k, v) for k, v in case.items() if k in _NEUTRAL)
        if shape in seen and all(item in seen for item in neutral):
            continue
        seen.add(shape)
        seen.update(neutral)
        crossing = _crossing(spec, case)
        for s in spec.sensors:
            try:
                sensor_row(crossing.vehicle, s)
            except SensorError as err:
                raise DriveByError(str(err)) from None
        if spec.method in ("contact", "residual") and (i == 0 or "vehicle" in case):
            try:
                SingleAxle.of(crossing.vehicles[0].vehicle)
            except Exception as err:  # noqa: BLE001 - a VbikitError naming the key
                raise DriveByError(str(err)) from None
            chosen = next(s for s in spec.sensors if s.name == spec.sensor)
            if chosen.quantity != "acceleration":
                raise DriveByError(f"identification.sensor: method \"{spec.method}\" needs an acceleration sensor; "
                                   f"{chosen.name!r} measures {chosen.quantity}")
    return total


def check_drawn_bridge(spec: DriveBy, bridge) -> None:
    """Refuse, before anything runs, drawn bridge parameters the bridge cannot take: rotational
    springs on a model without them, a damaged region that can reach past the deck's end."""
    drawn = dict(spec.variability.drawn)
    model = spec.scenario.get("bridge", {}).get("model")
    if "rotational_stiffness" in drawn and model != "continuous-beam":
        raise DriveByError(f"variability.rotational_stiffness: needs bridge.model = \"continuous-beam\" (end rotational "
                           f"springs), got {model!r}")
    if "damage_position" in drawn:
        lo, hi = bridge.deck_extent
        end = drawn["damage_position"].bounds[1] + (drawn["damage_length"].bounds[1] if "damage_length" in drawn
                                                     else spec.damage_length)
        if end > hi - lo:
            raise DriveByError(f"variability.damage_position: a drawn damaged region can end at {end:g} m (largest "
                               f"damage_position + damage_length), past the deck's length {hi - lo:g} m; allowed: "
                               f"position + length <= {hi - lo:g} m")


def spectrum_length(spec: DriveBy) -> int:
    """Points of the zero-padded DFT of the on-bridge records (``sensors.amplitude_spectrum``): the
    power of two at least twice the longest on-bridge record, deck length / slowest speed × rate
    (the slowest of the sweep's, the drawn range's and the file's speeds; a decelerating crossing
    at its exit speed), so that every pass has the same frequency axis rfftfreq(n, 1/rate)."""
    base = case_crossing(spec, spec.cases[0] if spec.cases else {})
    lo, hi = base.bridge.deck_extent
    motion = base.vehicles[0]
    speeds = [float(motion.speed), *spec.sweep.get("speed", []), *(spec.variability.speed or ())]
    v = min(speeds)
    a = float(getattr(motion, "acceleration", 0.0) or 0.0)
    if a < 0.0:
        reach = float(base.approach) + (hi - lo)
        v = math.sqrt(max(v * v + 2.0 * a * reach, 0.0))
        if v <= 0.0:
            raise DriveByError("crossing.acceleration: the vehicle stops before leaving the deck: no on-bridge spectrum")
    n = math.ceil((hi - lo) / v * spec.sampling.rate) + 2
    return 1 << math.ceil(math.log2(2 * n))


def sensor_agreement(ident, others: dict) -> tuple[int, int, str]:
    """How the other acceleration sensors of the vehicle agree with ``ident``: the number whose
    own identification is reliable, how many of those lie within the resolution 1/T of it, and
    the reason in words when one does not ('' otherwise)."""
    good = {name: o for name, o in others.items() if o.reliable}
    off = {name: o for name, o in good.items() if abs(o.frequency_hz - ident.frequency_hz) > ident.resolution_hz}
    reason = "; ".join(f"sensor {name} identifies {o.frequency_hz:.4g} Hz, {abs(o.frequency_hz - ident.frequency_hz) / ident.resolution_hz:.2f}/T "
                       "away (more than 1/T)" for name, o in off.items())
    return len(good), len(good) - len(off), reason


def first_mode_envelope_offset(bridge, lateral_offset: float | None, window: str) -> float:
    """``quality.mode_envelope_offset`` [1/T] of ``bridge``'s first mode along the path
    y = ``lateral_offset`` [m] over the deck (2001 points), weighted by the record's ``window``:
    0 on a single span, about n/2 on n equal continuous spans."""
    lo, hi = bridge.deck_extent
    x = np.linspace(lo, hi, 2001)
    y = float(bridge.default_lateral_offset if lateral_offset is None else lateral_offset)
    return mode_envelope_offset(bridge.mode_shapes(x, np.full_like(x, y))[:, 0], window)


def run_case(spec: DriveBy, index: int) -> dict[str, Any]:
    """Simulate case ``index`` and identify its frequency; returns its outputs and sensor histories."""
    from vbikit.solve import simulate
    from vbikit.study.spec import derive_seed

    case = spec.cases[index] if spec.cases else {}
    crossing = case_crossing(spec, case)
    if spec.coupling == "decoupled":
        from vbikit.driveby.decoupled import simulate_decoupled

        result = simulate_decoupled(crossing)
    else:
        result = simulate(crossing)
    sensors = case_sensors(spec, case)
    k = [s.name for s in sensors].index(spec.sensor)
    logged = sensors
    if spec.method == "residual":  # the same sensor on the follower
        import dataclasses

        logged = (*sensors, dataclasses.replace(sensors[k], name=f"{sensors[k].name}_follower", vehicle=2))
    vehicle = crossing.vehicles[0].vehicle
    speed = float(crossing.vehicles[0].speed)
    bridge = crossing.bridge
    band = spec.band or (4.0 * speed / bridge.span, min(BAND_MAX_HZ, 0.45 * spec.sampling.rate))
    f_v, zeta_v = vehicle_modes(vehicle)
    envelope_offset = first_mode_envelope_offset(bridge, crossing.vehicles[0].lateral_offset, spec.window)
    lateral = crossing.vehicles[0].lateral_offset
    interaction_hz = interaction_shift(bridge, vehicle, float(bridge.default_lateral_offset if lateral is None else lateral),
                                       spec.window)

    def record(m, j: int) -> NDArray:
        signal = m.values[j]
        if spec.method in ("contact", "residual"):
            signal = contact_acceleration_from_measured(signal, SingleAxle.of(vehicle), m.dt)
        if spec.method == "residual":
            follower = contact_acceleration_from_measured(m.values[-1], SingleAxle.of(vehicle), m.dt)
            signal = residual_response(signal, follower, spec.sampling.rate, spec.gap, speed)
        return signal

    def identify(signal: NDArray, use: NDArray):
        return identify_frequency(signal[use], spec.sampling.rate, speed, bridge.span, band, spec.spectrum, spec.window,
                                  bridge_hz=bridge.frequencies_hz, vehicle_hz=f_v, exclude_vehicle=spec.exclude_vehicle,
                                  vehicle_zeta=zeta_v, envelope_offset=envelope_offset, interaction_hz=interaction_hz)

    def observe(res):
        m = measure(res, logged, spec.sampling, seed=derive_seed(spec.seed, index))
        t_on = res.time[on_bridge(res, 0)]
        window = (m.time >= t_on[0]) & (m.time <= t_on[-1])
        signal = record(m, k)
        if spec.method == "residual":
            window &= np.isfinite(signal)
        return m, t_on, window, signal, identify(signal, window)

    m, t_on, window, signal, ident = observe(result)
    truth = contact_truth(result, spec.sampling)
    check = {"coupling_error_rms": math.nan, "coupling_frequency_difference_hz": math.nan}
    if spec.coupling == "decoupled" and spec.coupling_check_every and index % spec.coupling_check_every == 0:
        import dataclasses

        from vbikit.driveby.decoupled import relative_rms_error

        ref = simulate(crossing)
        clean = tuple(dataclasses.replace(s, noise_rms=0.0, noise_snr_db=None) for s in logged)
        pair = [measure(r, clean, spec.sampling, seed=0).values[k] for r in (result, ref)]
        check = {"coupling_error_rms": relative_rms_error(*pair),
                 "coupling_frequency_difference_hz": ident.frequency_hz - observe(ref)[-1].frequency_hz}
    drawn = case_draw(spec, case)
    temperature = drawn.get("temperature", math.nan)
    var = spec.variability
    support = math.nan
    if var.support_stiffness is not None:
        support = var.support_stiffness * (var.scour_classes[case["scour_class"]] if "scour_class" in case else 1.0)
    front = crossing.front_positions(m.time)[:, 0]  # segmentation from the kinematics at the sample times
    lo, hi = bridge.deck_extent
    on_samples = np.flatnonzero((front >= lo) & (front <= hi))
    off = np.flatnonzero(front - vehicle.length > hi)
    labels = {
        "on_bridge_start_sample": float(on_samples[0]), "on_bridge_end_sample": float(on_samples[-1]),
        "off_bridge_sample": float(off[0]) if off.size else math.nan,
        "bridge_frequency_2_hz": float(bridge.frequencies_hz[1]) if bridge.frequencies_hz.size > 1 else math.nan,
        "temperature_c": temperature,
        "stiffness_factor": temperature_factor(var, temperature) if math.isfinite(temperature) else 1.0,
        "support_stiffness": support, "vehicle_mass_kg": float(vehicle.total_weight / GRAVITY), **check,
        "background_vehicles": float(crossing.n_vehicles - 1) if spec.method != "residual" else 0.0,
        "background_mass_kg": sum(float(m.vehicle.total_weight / GRAVITY) for m in crossing.vehicles[1:])
        if spec.method != "residual" else 0.0,
    }
    q = ident.quality
    others = [j for j, s in enumerate(sensors) if j != k and s.quantity == "acceleration" and s.vehicle == sensors[k].vehicle
              and spec.method != "residual"]  # residual: the follower carries only the chosen sensor
    agreement = sensor_agreement(ident, {sensors[j].name: identify(record(m, j), window) for j in others})
    shape = np.full(SHAPE_POINTS, np.nan)
    if spec.method == "contact":  # φ² along x = v (t − t_entry): Hilbert envelope of the band-passed contact response
        half = min(2.0 * speed / bridge.span, 0.5 * ident.frequency_hz)
        env = mode_shape_squares(signal[window], spec.sampling.rate, ident.frequency_hz, half)
        x = speed * (m.time[window] - t_on[0])
        shape = np.interp(np.linspace(0.0, bridge.span, SHAPE_POINTS), x, env)
    return labels | {
        "mode_shape_squared": shape,
        "identified_frequency_hz": ident.frequency_hz,
        "bridge_frequency_hz": float(bridge.frequencies_hz[0]),
        "resolution_hz": ident.resolution_hz,
        "vehicle_frequency_hz": float(vehicle.natural_frequencies()[0]),
        "record_start": float(t_on[0]), "record_end": float(t_on[-1]),
        "n_steps": float(result.n_steps), "unconverged_steps": float(result.unconverged_steps),
        "n_samples": float(m.time.size),
        "label_frequency_hz": q.label_hz, "peak_snr_db": q.snr_db, "peak_snr_threshold_db": q.snr_threshold_db,
        "peak_rival_db": q.rival_db,
        "vehicle_distance": q.vehicle_distance, "vehicle_distance_limit": q.vehicle_limit,
        "band_edge_distance": q.edge_distance, "band_edge_limit": q.edge_limit, "speed_correction_hz": q.speed_correction_hz,
        "interaction_shift_hz": q.interaction_hz,
        "band_low_hz": ident.band[0], "band_high_hz": ident.band[1],
        "sensors_identified": float(agreement[0]), "sensors_agree": float(agreement[1]),
        "identified_frequency_label": q.label, "identified_frequency_reason": "; ".join(r for r in (q.reason, agreement[2]) if r),
        "history": np.vstack([m.values[:len(sensors)], truth]), "time0": float(m.time[0]),
        "noise_std": m.noise_std[:len(sensors)],
        "spectrum": pass_spectra(spec, np.vstack([m.values[:len(sensors)], truth[1:]]), on_samples),
    }


def pass_spectra(spec: DriveBy, records: NDArray, on_samples: NDArray) -> NDArray:
    """Amplitude spectra (``sensors.amplitude_spectrum``) of ``records`` (the sensors and the
    contact-point acceleration) over the samples with the front wheel on the deck; (rows, 0) when
    ``dataset.spectra`` is false."""
    if not spec.output["spectra"]:
        return np.zeros((records.shape[0], 0))
    segment = records[:, int(on_samples[0]):int(on_samples[-1]) + 1]
    try:
        return amplitude_spectrum(segment, spectrum_length(spec))
    except SensorError as err:
        raise DriveByError(f"{err} (a crossing slower than its speed: set dataset.spectra = false)") from None


@dataclass(frozen=True)
class DriveByStudy:
    """The sweep of a drive-by file as a job of ``run_study`` (module docstring)."""

    spec: DriveBy

    @property
    def name(self) -> str:
        return self.spec.name or "drive-by"

    @property
    def size(self) -> int:
        return max(1, len(self.spec.cases))

    def batches(self) -> list[tuple[int, ...]]:
        b = self.spec.batch_size
        return [tuple(range(k, min(k + b, self.size))) for k in range(0, self.size, b)]

    def to_json(self) -> str:
        return self.spec.to_json()

    def earlier_json(self) -> tuple[str, ...]:
        return self.spec.earlier_json()

    def run_batch(self, batch: tuple[int, ...], threads: int = 1) -> dict[str, NDArray]:
        from vbikit._blas import single_thread_blas

        with single_thread_blas():  # a pass's products are small: BLAS threads only contend (vbikit._blas)
            rows = [run_case(self.spec, i) for i in batch]
        out = {name: np.array([r[name] for r in rows], float) for name in CASE_OUTPUTS}
        out |= {name: np.array([r[name] for r in rows], dtype=np.str_) for name in CASE_TEXT}
        n = max(r["history"].shape[1] for r in rows)
        hist = np.full((len(rows), len(self.spec.sensors) + len(CONTACT_TRUTH), n), np.nan)
        for j, r in enumerate(rows):
            hist[j, :, :r["history"].shape[1]] = r["history"]
        out["history"] = hist
        out["mode_shape_squared"] = np.array([r["mode_shape_squared"] for r in rows], float)
        out["noise_std"] = np.array([r["noise_std"] for r in rows], float)
        out["spectrum"] = np.array([r["spectrum"] for r in rows], float)
        out["time0"] = np.array([r["time0"] for r in rows])
        out["case"] = np.array(batch, np.int64)
        return out

    def part_problem(self, part, batch: tuple[int, ...]) -> Optional[str]:
        if "case" not in part or not np.array_equal(part["case"], np.array(batch, np.int64)):
            return "its cases are not those of this batch"
        for name in (*CASE_OUTPUTS, *CASE_TEXT):
            if name not in part or part[name].shape != (len(batch),):
                return f"{name} is missing or has the wrong shape"
        if "history" not in part or part["history"].shape[:2] != (len(batch), len(self.spec.sensors) + len(CONTACT_TRUTH)):
            return "its sensor histories have the wrong shape"
        if "spectrum" not in part or part["spectrum"].shape[:2] != (len(batch), len(self.spec.sensors) + 1):
            return "its spectra have the wrong shape"
        if "mode_shape_squared" not in part or part["mode_shape_squared"].shape != (len(batch), SHAPE_POINTS):
            return "its mode-shape estimates have the wrong shape"
        if "noise_std" not in part or part["noise_std"].shape != (len(batch), len(self.spec.sensors)):
            return "its noise levels have the wrong shape"
        return None

    def assemble(self, parts: Path):
        from vbikit.study.storage import load_part, part_checksums

        sums = part_checksums(parts)
        loaded = [load_part(parts, k, sums) for k in range(len(self.batches()))]
        return dataset(self.spec, {name: np.concatenate([p[name] for p in loaded])
                                   for name in (*CASE_OUTPUTS, *CASE_TEXT, "time0", "case", "mode_shape_squared", "noise_std",
                                                "spectrum")},
                       [p["history"] for p in loaded])


def _labels(spec: DriveBy) -> dict[str, NDArray]:
    """Per-case label arrays (swept values, or the base file's where not swept)."""
    cases = spec.cases or ({},)
    base_road = spec.scenario.get("road", {})
    base_cross = spec.scenario.get("crossing", {})
    base_speed = base_cross.get("speed", base_cross.get("speed_kmh", 28.8) / 3.6)
    drawn = [case_draw(spec, c) for c in cases]
    damage = [{**c, **d} for c, d in zip(cases, drawn)]  # a drawn damage or the swept one
    base_rot = spec.scenario.get("bridge", {}).get("rotational_stiffness") or (math.nan, math.nan)
    return {
        "speed": np.array([d.get("speed", c.get("speed", base_speed)) for c, d in zip(cases, drawn)], float),
        "scour_class": np.array([c.get("scour_class", -1) for c in cases], np.int64),
        "pass_index": np.array([c.get("pass", 0) for c in cases], np.int64),
        "road_class": np.array([c.get("road_class", base_road.get("class", "none")) for c in cases], dtype=object),
        "road_seed": np.array([case_road_seed(spec, c) for c in cases], np.int64),
        "traffic_seed": np.array([d.get("traffic_seed", -1) for d in drawn], np.int64),
        "damage_position": np.array([c.get("damage_position", np.nan) if c.get("damage_severity", 0) > 0 else np.nan
                                     for c in damage], float),
        "damage_severity": np.array([c.get("damage_severity", 0.0) for c in damage], float),
        "damage_length": np.array([c.get("damage_length", spec.damage_length) if c.get("damage_severity", 0) > 0 else np.nan
                                   for c in damage], float),
        "rotational_stiffness_entry": np.array([d.get("rotational_stiffness_entry", base_rot[0]) for d in drawn], float),
        "rotational_stiffness_exit": np.array([d.get("rotational_stiffness_exit", base_rot[1]) for d in drawn], float),
        "vehicle": np.array([-1 if not spec.fleet else case_vehicle(spec, c) for c in cases], np.int64),
        "draw_index": np.array([c.get("index", i) for i, c in enumerate(cases)], np.int64),
        "noise_rms": np.array([c.get("noise_rms", spec.sensors[0].noise_rms) for c in cases], float),
    }


#: the unit of ``noise_rms``: the sweep's value applies to every sensor in its own unit (the dataset writes
#: ``member_units`` of the sensors' units), else it is the first sensor's (its unit)
IN_SENSOR_UNITS = "in each sensor's unit"
LABEL_ATTRS = {
    "speed": ("m s-1", "vehicle speed (drawn per pass with variability.speed)"),
    "scour_class": ("1", "support stiffness class k: support springs = variability.support_stiffness × "
                         "variability.scour_classes[k] (−1: none)"),
    "pass_index": ("1", "pass number within its combination of the sweep and scour class (its draw: the case index)"),
    "road_class": ("", "road roughness class (ISO 8608; none = smooth)"),
    "road_seed": ("1", "seed of the random road (a random pass's own: derived from the file's seed and draw_index)"),
    "traffic_seed": ("1", "seed of the pass's background trucks (variability.traffic_flow; −1: none)"),
    "damage_position": ("m", "start of the damaged region from the bridge entry (NaN: healthy)"),
    "damage_severity": ("1", "relative loss of bending stiffness EI in the damaged region (0: healthy)"),
    "damage_length": ("m", "length of the damaged region (NaN: healthy)"),
    "rotational_stiffness_entry": ("N m rad-1", "rotational spring at the entry support (drawn with "
                                                "variability.rotational_stiffness, or the file's; NaN: none given)"),
    "rotational_stiffness_exit": ("N m rad-1", "rotational spring at the exit support (drawn with "
                                               "variability.rotational_stiffness, or the file's; NaN: none given)"),
    "vehicle": ("", "the instrumented vehicle: index into the fleet coordinate (the [[fleet]] names; −1: one [vehicle])"),
    "draw_index": ("1", "the key of the pass's draw (SeedSequence(seed, spawn_key=(draw_index,))); the vehicles of one "
                        "pass of fleet = \"all\" share it"),
    "noise_rms": (IN_SENSOR_UNITS, "noise_rms set for the sensors (the sweep's, else the first sensor's; 0 where a "
                                  "sensor's noise is given as an SNR, noise_snr_db): the noise added is noise_std"),
}


def healthy_reference(labels: dict[str, NDArray]) -> NDArray[np.int64]:
    """For every case the index of its healthy counterpart (same speed, road, seed, noise and
    severity 0), or −1 when the sweep has none."""
    keys = ("speed", "road_class", "road_seed", "noise_rms")
    healthy = {tuple(labels[k][i] for k in keys): i for i in range(labels["speed"].size) if labels["damage_severity"][i] == 0}
    return np.array([healthy.get(tuple(labels[k][i] for k in keys), -1) for i in range(labels["speed"].size)], np.int64)


def bridge_states(labels: dict[str, NDArray]) -> NDArray[np.int64]:
    """For every case the index of its bridge (one per damage position, severity, scour class and
    end rotational springs; every healthy case of a class with the same springs the same bridge):
    the passes over one bridge form its multi-pass estimate (temperature, when drawn, varies within
    one bridge; springs drawn per pass, ``variability.rotational_stiffness``, make each pass its own
    bridge)."""
    n = len(labels["damage_severity"])
    nan = np.full(n, np.nan)
    springs = zip(labels.get("rotational_stiffness_entry", nan), labels.get("rotational_stiffness_exit", nan))
    keys = [((0.0, 0.0) if s == 0 else (float(p), float(s)), int(c), tuple(_label_value(v) for v in k))
            for p, s, c, k in zip(labels["damage_position"], labels["damage_severity"], labels["scour_class"], springs)]
    first: dict = {}
    return np.array([first.setdefault(k, len(first)) for k in keys], np.int64)


def _label_value(v) -> float | None:
    """A label as a key: its value, None for NaN (none given: NaN equals no NaN)."""
    v = float(v)
    return None if np.isnan(v) else v


#: multi-pass outputs per case (its bridge's): name -> (units, long name, MultiPass field)
MULTIPASS_OUTPUTS = {
    "multipass_frequency_hz": ("Hz", "median of the reliable passes over this case's bridge", "median"),
    "multipass_q25_hz": ("Hz", "lower quartile of the reliable passes over this case's bridge", "q25"),
    "multipass_q75_hz": ("Hz", "upper quartile of the reliable passes over this case's bridge", "q75"),
    "multipass_mean_hz": ("Hz", "mean of the reliable passes over this case's bridge", "mean"),
    "multipass_std_hz": ("Hz", "standard deviation (n − 1) of the reliable passes over this case's bridge", "std"),
    "multipass_n_passes": ("1", "passes over this case's bridge", "n_passes"),
    "multipass_n_reliable": ("1", "passes over this case's bridge whose peak passed the single-pass checks", "n_reliable"),
    "multipass_n_agree": ("1", "reliable passes within their resolution 1/T of the multi-pass median", "n_agree"),
}


def pass_reliability(labels: dict[str, NDArray], ident: NDArray, resolution: NDArray, reasons: NDArray):
    """Per case: reliable (the single-pass checks, and, with at least ``MIN_PASSES`` reliable
    passes over its bridge, agreement with their median), the reasons in words, and the
    multi-pass estimate of its bridge (``MULTIPASS_OUTPUTS``: name -> (units, long name, values))."""
    from vbikit.driveby.quality import MIN_PASSES, multipass_estimate

    reasons = [str(r) for r in reasons]
    single = np.array([not r for r in reasons])
    reliable = single.copy()
    passes = {name: (units, long_name, np.full(ident.size, np.nan)) for name, (units, long_name, _) in MULTIPASS_OUTPUTS.items()}
    agrees = np.zeros(ident.size, np.int8)
    states = bridge_states(labels)
    for b in np.unique(states):
        sel = np.flatnonzero(states == b)
        est = multipass_estimate(ident[sel], resolution[sel], single[sel])
        for name, (_, _, attr) in MULTIPASS_OUTPUTS.items():
            passes[name][2][sel] = getattr(est, attr)
        agrees[sel] = est.agrees
        if est.n_reliable >= MIN_PASSES:
            for i in sel[single[sel] & ~est.agrees]:
                reliable[i] = False
                reasons[i] = (f"disagrees with the median {est.median:.4g} Hz of the {est.n_reliable} reliable passes over "
                              f"this bridge by {abs(ident[i] - est.median) / resolution[i]:.2f}/T (more than 1/T)")
    for name in ("multipass_n_passes", "multipass_n_reliable", "multipass_n_agree"):
        units, long_name, values = passes[name]
        passes[name] = (units, long_name, values.astype(np.int64))
    passes["pass_agrees"] = ("", "1: this pass is reliable and within its resolution 1/T of its bridge's multi-pass median",
                             agrees)
    return reliable, reasons, passes


def reliable_shift(ident: NDArray, ref: NDArray, reliable: NDArray) -> tuple[NDArray, list[str]]:
    """The damage indicator f / f_healthy − 1 per case, NaN (with the reason) when the case has no
    healthy counterpart or either pass is unreliable."""
    shift = np.full(ident.size, np.nan)
    why = []
    for i, j in enumerate(ref):
        if j < 0:
            why.append("no healthy case of the same speed, road, seed and noise")
        elif not reliable[j]:
            why.append("this case's identified frequency is unreliable" if j == i
                       else f"the healthy case {j}'s identified frequency is unreliable")
        elif not reliable[i]:
            why.append("this case's identified frequency is unreliable")
        else:
            shift[i] = ident[i] / ident[j] - 1.0
            why.append("")
    return shift, why


def dataset(spec: DriveBy, out: dict[str, NDArray], histories: list[NDArray]):
    """The sweep's labelled Dataset (dimensions ``case``, ``sensor``, ``sample``)."""
    import xarray as xr

    from vbikit._version import __version__

    order = np.argsort(out["case"])
    n_cases = order.size
    n_samples = max(h.shape[2] for h in histories)
    n_sensors = len(spec.sensors)
    hist = np.full((n_cases, n_sensors + len(CONTACT_TRUTH), n_samples), np.nan)
    row = 0
    for h in histories:
        hist[row:row + h.shape[0], :, :h.shape[2]] = h
        row += h.shape[0]
    hist, truth = hist[order, :n_sensors], hist[order, n_sensors:]
    # the unit of a value in each sensor's own unit: theirs if they share one, else the coordinate of each's
    sensor_units = member_units([cf_unit(s.unit) for s in spec.sensors], "sensor", "sensor_units")
    # noise_rms: the sweep's value applies to every sensor, each in its own unit; else it is the first sensor's
    noise_units = sensor_units if "noise_rms" in spec.sweep else {"units": cf_unit(spec.sensors[0].unit)}
    variables: dict[str, Any] = {}
    for name, (units, long_name) in CASE_OUTPUTS.items():
        values = out[name][order]
        variables[name] = ("case", values.astype(np.int64) if name.startswith(("n_", "sensors_")) else values,
                           {"units": units, "long_name": long_name})
    labels = _labels(spec)
    for name, (units, long_name) in LABEL_ATTRS.items():
        attrs = {"long_name": long_name} | (noise_units if units == IN_SENSOR_UNITS else {"units": units} if units else {})
        variables[name] = ("case", labels[name], attrs)
    for j, (name, (units, long_name)) in enumerate(CONTACT_TRUTH.items()):
        variables[name] = (("case", "sample"), truth[:, j], {"units": units, "long_name": long_name +
                                                             " at t = time_start + sample / sampling_rate (NaN after its end)"})
    if spec.output["spectra"]:
        spectra = out["spectrum"][order]
        variables["sensor_spectrum"] = (("case", "sensor", "frequency"), spectra[:, :n_sensors], {
            **sensor_units, "long_name": "single-sided amplitude spectrum of each sensor record while the "
            "front wheel is on the deck (samples on_bridge_start_sample … on_bridge_end_sample), rectangular window, "
            "zero-padded: 2 |DFT| / N (vbikit.driveby.sensors.amplitude_spectrum)"})
        variables["contact_spectrum"] = (("case", "frequency"), spectra[:, n_sensors], {
            "units": "m s-2", "long_name": "single-sided amplitude spectrum of contact_acceleration over the same samples"})
    factors = [case_draw(spec, c).get("vehicle_factors") for c in (spec.cases or ({},))]
    if factors and factors[0] is not None:
        variables["vehicle_factor"] = (("case", "vehicle_parameter"), np.array([np.concatenate(f) for f in factors])[order], {
            "units": "1", "long_name": "drawn factor of each vehicle parameter (variability.vehicle_spread; a fleet's "
                                       "smaller vehicle uses the first of each group)"})
    ident, true = out["identified_frequency_hz"][order], out["bridge_frequency_hz"][order]
    variables["frequency_error"] = ("case", ident / true - 1.0, {"units": "1", "long_name": "identified / true − 1"})
    ref = healthy_reference(labels)
    texts = {name: np.asarray(out[name][order]).astype(str) for name in CASE_TEXT}
    unconverged = np.asarray(out["unconverged_steps"][order], float)
    texts["identified_frequency_reason"] = unconverged_reasons(texts["identified_frequency_reason"], unconverged)
    reliable, reasons, passes = pass_reliability(labels, ident, out["resolution_hz"][order], texts["identified_frequency_reason"])
    for name, long_name in CASE_TEXT.items():
        variables[name] = ("case", np.array(reasons if name == "identified_frequency_reason" else texts[name], dtype=object),
                           {"long_name": long_name})
    variables["identified_frequency_reliable"] = ("case", reliable.astype(np.int8), {
        "long_name": "1: the identified frequency passed every check (docs/driveby.md, How accurate is this); 0: "
                     "unreliable, excluded from the damage indicators, reason in identified_frequency_reason",
        "flag_values": np.array([0, 1], np.int8), "flag_meanings": "unreliable reliable"})
    for name, (units, long_name, values) in passes.items():
        variables[name] = ("case", values, {"long_name": long_name} | ({"units": units} if units else {}))
    shift, shift_reason = reliable_shift(ident, ref, reliable)
    true_shift = np.where(ref >= 0, true / true[np.maximum(ref, 0)] - 1.0, np.nan)
    variables["identified_frequency_shift"] = ("case", shift, {"units": "1", "long_name":
                                              "damage indicator: identified frequency / that of the healthy case − 1 "
                                              "(NaN when either pass is unreliable: frequency_shift_reason)"})
    variables["frequency_shift_reason"] = ("case", np.array(shift_reason, dtype=object), {
        "long_name": "why identified_frequency_shift is not given, in words ('' when given)"})
    mp = passes["multipass_frequency_hz"][2]
    variables["multipass_frequency_shift"] = ("case", np.where(ref >= 0, mp / mp[np.maximum(ref, 0)] - 1.0, np.nan), {
        "units": "1", "long_name": "damage indicator from all passes: multi-pass median of this bridge / that of the "
                                   "healthy bridge − 1 (NaN without reliable passes)"})
    variables["bridge_frequency_shift"] = ("case", true_shift, {"units": "1", "long_name":
                                          "true first frequency / that of the healthy bridge − 1"})
    variables["healthy_case"] = ("case", ref, {"long_name": "index of the healthy counterpart (−1: none)"})
    shapes = out["mode_shape_squared"][order]
    variables["mode_shape_squared"] = (("case", "position"), shapes, {
        "units": "1", "long_name": "first mode shape squared from the contact response's Hilbert envelope, max 1 "
                                   "(method contact; NaN otherwise)"})
    indicators = {"mode_shape_mac": ("1", "MAC of the mode-shape estimate with the healthy case's"),
                  "curvature_change": ("1", "largest change of the estimate's curvature (second difference) against "
                                            "the healthy case's, inner 80 % of the span"),
                  "curvature_change_x": ("m", "position of the largest curvature change: " + CURVATURE_LOCATION_CAVEAT)}
    values = {k: np.full(n_cases, np.nan) for k in indicators}
    grid = np.linspace(0.0, float(case_crossing(spec, spec.cases[0] if spec.cases else {}).bridge.span), SHAPE_POINTS)
    for i in range(n_cases):
        j = ref[i]
        if j < 0 or not (reliable[i] and reliable[j]) or not (np.all(np.isfinite(shapes[i])) and np.all(np.isfinite(shapes[j]))):
            continue
        values["mode_shape_mac"][i] = shape_change(np.sqrt(shapes[j]), np.sqrt(shapes[i]))["mac"]
        inner = slice(SHAPE_POINTS // 10, SHAPE_POINTS - SHAPE_POINTS // 10)  # the band-pass's and Hilbert transform's end effects
        ind = shape_change(np.sqrt(shapes[j][inner]), np.sqrt(shapes[i][inner]))
        values["curvature_change"][i] = ind["curvature_change"]
        values["curvature_change_x"][i] = grid[inner][ind["curvature_argmax"]]
    for k, (units, long_name) in indicators.items():
        variables[k] = ("case", values[k], {"units": units, "long_name": long_name})
    variables["sensor_history"] = (("case", "sensor", "sample"), hist, {
        **sensor_units, "long_name": "sensor record at t = time_start + sample / sampling_rate (NaN after its end)"})
    variables["split"] = ("case", np.array([split_of(spec.seed, int(i)) for i in labels["draw_index"]], np.int8), {
        "long_name": "documented train / validation / test split by the file's seed (vbikit.driveby.variability."
                     "split_of: 70 / 15 / 15 %, fixed per draw_index: the vehicles of one pass in the same part)",
        "flag_values": np.array([0, 1, 2], np.int8), "flag_meanings": " ".join(SPLIT_NAMES)})
    variables["noise_std"] = (("case", "sensor"), out["noise_std"][order], {
        **sensor_units, "long_name": "standard deviation of the noise added to each sensor's record"})
    variables["time_start"] = ("case", out["time0"][order], {"units": "s", "long_name": "time of the first sample"})
    coords = {
        "case": ("case", np.arange(n_cases)),
        "position": ("position", grid, {"units": "m", "long_name": "distance along the deck from the entry support"}),
        "sensor": ("sensor", np.array([s.name for s in spec.sensors], dtype=object)),
        "sensor_units": ("sensor", np.array([cf_unit(s.unit) for s in spec.sensors], dtype=object),
                         {"long_name": "unit of each sensor's record (CF spelling)"}),
        "sensor_quantity": ("sensor", np.array([s.quantity for s in spec.sensors], dtype=object)),
        "fleet": ("fleet", np.array([n for n, _ in spec.fleet] or [spec.vehicle["model"]], dtype=object),
                  {"long_name": "the instrumented vehicles ([[fleet]] names; the [vehicle] model without a fleet)"}),
    }
    if spec.output["spectra"]:
        coords["frequency"] = ("frequency", np.fft.rfftfreq(spectrum_length(spec), 1.0 / spec.sampling.rate),
                               {"units": "Hz", "long_name": "frequency of the amplitude spectra"})
    if "vehicle_factor" in variables:
        n_dof, n_wheels = vehicle_dims(spec)
        coords["vehicle_parameter"] = ("vehicle_parameter", np.array(
            [f"{g}_{j}" for g, n in (("mass", n_dof), ("stiffness", n_dof), ("damping", n_dof), ("tire_stiffness", n_wheels),
                                     ("tire_damping", n_wheels)) for j in range(n)], dtype=object))
    attrs = {"title": spec.name or "vbikit drive-by dataset", "study": spec.to_json(), "vbikit_version": __version__,
             "sampling_rate": spec.sampling.rate, "sampling_filter": f"Butterworth order {spec.sampling.filter_order}, "
             f"cut-off {spec.sampling.cutoff_hz:g} Hz, zero phase (forward-backward), applied before resampling",
             "identification_method": spec.method, "identification_sensor": spec.sensor, "Conventions": "CF-1.8",
             "chunk_passes": int(spec.output["chunk_passes"])}
    attrs |= dataset_flag_attrs(unconverged_pass_flags(unconverged))
    ds = xr.Dataset(variables, coords=coords, attrs=attrs)
    # chunked and compressed on disk: xarray.open_dataset(..., chunks={"case": n}) streams the records with Dask
    for name in PER_PASS_RECORDS:
        if name in ds:
            ds[name].encoding.update(chunksizes=(min(n_cases, spec.output["chunk_passes"]), *ds[name].shape[1:]),
                                     zlib=True, complevel=1)
    return ds


def unconverged_reasons(reasons: NDArray, counts: NDArray) -> NDArray:
    """The identification's ``reasons`` (one per pass, '' when reliable) with the words of a pass
    whose contact forces did not converge in ``counts`` > 0 time steps (its ``unconverged_steps``)
    put first: such a pass's records carry a contact-force error above the solver's tolerance, so
    its identification is unreliable whatever its spectrum shows (``contact_not_converged``)."""
    out = [str(r) for r in reasons]
    for i in np.flatnonzero(np.nan_to_num(np.asarray(counts, float), nan=0.0) > 0.0):
        words = (f"the contact forces did not converge in {counted(int(counts[i]), 'time step')} of this pass "
                 f"(unconverged_steps): its records are not trusted")
        out[i] = words + (f"; {out[i]}" if out[i] else "")
    return np.array(out, dtype=str)


#: the per-pass records stored in chunks of ``dataset.chunk_passes`` cases (whole along their other dimensions)
PER_PASS_RECORDS = ("sensor_history", *CONTACT_TRUTH, "sensor_spectrum", "contact_spectrum")


def write_zarr(ds, path: Path) -> None:
    """``ds`` as a Zarr store at ``path`` (replaced), the per-pass records in chunks of
    ``dataset.chunk_passes`` cases as in driveby.nc (``dataset.format = "zarr"``; needs the optional
    package zarr, checked before the run by ``spec.check_dataset_format``)."""
    import shutil

    out = ds.copy()
    for name in list(out.variables):
        out[name].encoding = {}
        if out[name].dtype == object:
            out[name] = out[name].astype(str)
    for name in PER_PASS_RECORDS:
        if name in out:
            out[name] = out[name].chunk({"case": int(ds.attrs["chunk_passes"])})
    if path.exists():
        shutil.rmtree(path)
    out.to_zarr(path, mode="w")


def run_driveby(spec: DriveBy | str | Path | dict, out_dir: str | Path = "vbikit-out", workers: Optional[int] = None,
                scheduler: Optional[str] = None, progress=None, figures: bool = True):
    """Run a drive-by sweep (a ``DriveBy``, a file path or its parsed dict) on the study runner and
    write ``out_dir``/driveby.nc, the figures (``driveby-*.png``), ``driveby-report.txt`` and
    ``driveby-summary.json`` (``workers``: local worker processes, default all cores; 1 runs in this process);
    returns the Dataset.  Resumable: run it again after an interruption."""
    from vbikit._validation import checked_workers
    from vbikit.driveby.spec import DriveByError, load_driveby, parse_driveby
    from vbikit.study.run import run_study

    workers = checked_workers(workers, error=DriveByError)
    if isinstance(spec, dict):
        spec = parse_driveby(spec)
    elif not isinstance(spec, DriveBy):
        spec = load_driveby(spec)
    check_cases(spec)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    ds = run_study(DriveByStudy(spec), out_dir / DATASET_FILE, workers=workers, scheduler=scheduler, progress=progress)
    write_outputs(spec, ds, out_dir, figures)
    return ds


def write_outputs(spec: DriveBy, ds, out_dir: Path, figures: bool = True) -> str:
    """Everything besides driveby.nc: ``driveby-report.txt`` and ``driveby-summary.json``,
    ``driveby.zarr`` (``dataset.format = "zarr"``), the figures; returns the report's text."""
    from vbikit.driveby.report import write_report

    text = write_report(ds, out_dir)
    if spec.output["format"] == "zarr":
        write_zarr(ds, Path(out_dir) / ZARR_FILE)
    if figures:
        from vbikit.driveby.figures import write_figures

        write_figures(ds, out_dir)
    return text
