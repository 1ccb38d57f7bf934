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

from vbikit.driveby.contact import SingleAxle, contact_acceleration_from_measured, on_bridge
from vbikit.driveby.identify import identify_frequency, mode_shape_squares, residual_response, shape_change
from vbikit.driveby.sensors import Sensor, SensorError, measure, sensor_row
from vbikit.driveby.spec import BAND_MAX_HZ, DriveBy, DriveByError
from vbikit.driveby.vehicles import DRIVEBY_VEHICLES, driveby_vehicle

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
    "n_samples": ("1", "sensor samples of the case"),
}


def _case_scenario(spec: DriveBy, case: dict) -> dict:
    """The scenario dict of one case (a stand-in vehicle when the vehicle is not a scenario preset)."""
    data = copy.deepcopy(spec.scenario)
    from vbikit.vehicle.presets import VEHICLE_PRESETS

    model = spec.vehicle["model"]
    data["vehicle"] = dict(spec.vehicle) if model in VEHICLE_PRESETS else {"model": "sprung-mass"}
    crossing = data.setdefault("crossing", {})
    if "speed" in case:
        crossing.pop("speed_kmh", None)
        crossing["speed"] = case["speed"]
    elif "speed" not in crossing and "speed_kmh" not in crossing:
        crossing["speed"] = 8.0
    road = data.setdefault("road", {})
    if "road_class" in case:
        road["class"] = case["road_class"]
    if "road_seed" in case:
        road["seed"] = case["road_seed"]
    if case.get("damage_severity", 0.0) > 0.0:
        data["bridge"] = dict(data["bridge"])
        data["bridge"]["damage"] = [*data["bridge"].get("damage", []), {
            "position": case["damage_position"], "length": spec.damage_length, "severity": case["damage_severity"]}]
    return data


def _vehicle(spec: DriveBy):
    model = spec.vehicle["model"]
    params = {k: v for k, v in spec.vehicle.items() if k != "model"}
    if model not in DRIVEBY_VEHICLES:
        from vbikit.vehicle.presets import VEHICLE_PRESETS

        if model not in VEHICLE_PRESETS:
            raise DriveByError(f"vehicle.model: {model!r} is unknown; allowed: {', '.join([*DRIVEBY_VEHICLES, *VEHICLE_PRESETS])}")
    try:
        return driveby_vehicle(model, **params)
    except TypeError as err:
        raise DriveByError(f"vehicle: {err}") from None


_BUILT: dict[str, Any] = {}


def case_crossing(spec: DriveBy, case: dict):
    """The crossing of one case: the scenario's bridge, tire, road and options with the vehicle,
    the step a divisor of the sensor period (so that resampling is exact decimation)."""
    from vbikit.scenario import build, parse_scenario
    from vbikit.scenario.schema import ScenarioError
    from vbikit.solve import Crossing
    from vbikit.solve.timestep import choose_time_step

    data = _case_scenario(spec, case)
    key = json.dumps([data, spec.vehicle, spec.sampling.rate, spec.base_dir], sort_keys=True)
    if key in _BUILT:
        return _BUILT[key]
    try:
        built = build(parse_scenario(data, spec.base_dir))
    except ScenarioError as err:
        raise DriveByError(f"{err}".replace("invalid scenario:\n  ", "")) from None
    c = built.crossing
    vehicle = _vehicle(spec)
    kwargs = dict(tire=c.tire, road=c.road, road_right=c.road_right, speed=c.speed, acceleration=c.acceleration,
                  approach=c.approach, free_vibration=c.free_vibration, integrator=c.integrator,
                  loss_of_contact=c.loss_of_contact)

    def make(dt):
        if spec.method != "residual":
            return Crossing(c.bridge, vehicle, dt=dt, **kwargs)
        from vbikit.solve import VehicleMotion

        follower = VehicleMotion(vehicle, c.speed, entry_time=spec.gap / c.speed)
        return Crossing(c.bridge, vehicles=(VehicleMotion(vehicle, c.speed), follower), dt=dt,
                        **{k: v for k, v in kwargs.items() if k not in ("speed", "acceleration")})

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


def estimate_steps(spec: DriveBy) -> float:
    """The integration steps of the whole sweep: each case's duration / time step, from one crossing
    built for each distinct speed of the sweep (the step and duration depend on the speed, not on
    the road seed or the noise); cheap for any number of cases."""
    per_speed: dict[Any, float] = {}
    total = 0.0
    for case in spec.cases or [{}]:
        v = case.get("speed")
        if v not in per_speed:
            c = _crossing(spec, case)
            per_speed[v] = c.duration / c.dt
        total += per_speed[v]
    return total


def check_cases(spec: DriveBy) -> float:
    """Validate the budget first (``estimate_steps`` against ``max_steps``), then every distinct case
    (scenario, vehicle, sensors; cases that differ only in ``_NEUTRAL`` keys once) before anything
    runs; returns the estimated integration steps of the sweep."""
    _crossing(spec, {})  # the file's own tables, before the sweep overrides any of their keys
    total = estimate_steps(spec)
    if total > spec.max_steps:
        raise DriveByError(f"max_steps: the sweep needs about {total:.3g} integration steps ({len(spec.cases):,} cases), "
                           f"above the budget {spec.max_steps:.3g}; raise max_steps (or --max-steps) or sweep fewer cases")
    seen: set = set()
    for i, case in enumerate(spec.cases or [{}]):
        shape = tuple((k, v) for k, v in case.items() if k not in _NEUTRAL)
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
        if spec.method in ("contact", "residual") and i == 0:
            try:
                SingleAxle.of(crossing.vehicles[0].vehicle)
            except Exception as err:  # noqa: BLE001 - a VbikitError naming the key
                raise DriveByError(str(err)) from None
            chosen = next(s for s in spec.sensors if s.name == spec.sensor)
            if chosen.quantity != "acceleration":
                raise DriveByError(f"identification.sensor: method \"{spec.method}\" needs an acceleration sensor; "
                                   f"{chosen.name!r} measures {chosen.quantity}")
    return total


def run_case(spec: DriveBy, index: int) -> dict[str, Any]:
    """Simulate case ``index`` and identify its frequency; returns its outputs and sensor histories."""
    from vbikit.solve import simulate
    from vbikit.study.spec import derive_seed

    case = spec.cases[index] if spec.cases else {}
    crossing = case_crossing(spec, case)
    result = simulate(crossing)
    sensors = case_sensors(spec, case)
    k = [s.name for s in sensors].index(spec.sensor)
    logged = sensors
    if spec.method == "residual":  # the same sensor on the follower
        import dataclasses

        logged = (*sensors, dataclasses.replace(sensors[k], name=f"{sensors[k].name}_follower", vehicle=2))
    m = measure(result, logged, spec.sampling, seed=derive_seed(spec.seed, index))
    on = on_bridge(result, 0)
    t_on = result.time[on]
    window = (m.time >= t_on[0]) & (m.time <= t_on[-1])
    vehicle = crossing.vehicles[0].vehicle
    signal = m.values[k]
    speed = float(crossing.vehicles[0].speed)
    if spec.method in ("contact", "residual"):
        signal = contact_acceleration_from_measured(signal, SingleAxle.of(vehicle), m.dt)
    if spec.method == "residual":
        follower = contact_acceleration_from_measured(m.values[-1], SingleAxle.of(vehicle), m.dt)
        signal = residual_response(signal, follower, spec.sampling.rate, spec.gap, speed)
        window &= np.isfinite(signal)
    bridge = crossing.bridge
    band = spec.band or (4.0 * speed / bridge.span, min(BAND_MAX_HZ, 0.45 * spec.sampling.rate))
    ident = identify_frequency(signal[window], spec.sampling.rate, speed, bridge.span, band, spec.spectrum, spec.window,
                               bridge_hz=bridge.frequencies_hz[:1], vehicle_hz=vehicle.natural_frequencies(),
                               exclude_vehicle=spec.exclude_vehicle)
    shape = np.full(SHAPE_POINTS, np.nan)
    if spec.method == "contact":  # φ² along x = v (t − t_entry): Hilbert envelope of the band-passed contact response
        half = min(2.0 * speed / bridge.span, 0.5 * ident.frequency_hz)
        env = mode_shape_squares(signal[window], spec.sampling.rate, ident.frequency_hz, half)
        x = speed * (m.time[window] - t_on[0])
        shape = np.interp(np.linspace(0.0, bridge.span, SHAPE_POINTS), x, env)
    return {
        "mode_shape_squared": shape,
        "identified_frequency_hz": ident.frequency_hz,
        "bridge_frequency_hz": float(bridge.frequencies_hz[0]),
        "resolution_hz": ident.resolution_hz,
        "vehicle_frequency_hz": float(vehicle.natural_frequencies()[0]),
        "record_start": float(t_on[0]), "record_end": float(t_on[-1]),
        "n_steps": float(result.n_steps), "n_samples": float(m.time.size),
        "history": m.values[:len(sensors)], "time0": float(m.time[0]), "noise_std": m.noise_std[:len(sensors)],
    }


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

    def run_batch(self, batch: tuple[int, ...], threads: int = 1) -> dict[str, NDArray]:
        rows = [run_case(self.spec, i) for i in batch]
        out = {name: np.array([r[name] for r in rows], float) for name in CASE_OUTPUTS}
        n = max(r["history"].shape[1] for r in rows)
        hist = np.full((len(rows), len(self.spec.sensors), n), np.nan)
        for j, r in enumerate(rows):
            hist[j, :, :r["history"].shape[1]] = r["history"]
        out["history"] = hist
        out["mode_shape_squared"] = np.array([r["mode_shape_squared"] for r in rows], float)
        out["noise_std"] = np.array([r["noise_std"] for r in rows], float)
        out["time0"] = np.array([r["time0"] for r in rows])
        out["case"] = np.array(batch, np.int64)
        return out

    def part_problem(self, part, batch: tuple[int, ...]) -> Optional[str]:
        if "case" not in part or not np.array_equal(part["case"], np.array(batch, np.int64)):
            return "its cases are not those of this batch"
        for name in CASE_OUTPUTS:
            if name not in part or part[name].shape != (len(batch),):
                return f"{name} is missing or has the wrong shape"
        if "history" not in part or part["history"].shape[:2] != (len(batch), len(self.spec.sensors)):
            return "its sensor histories have the wrong shape"
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
                                   for name in (*CASE_OUTPUTS, "time0", "case", "mode_shape_squared", "noise_std")},
                       [p["history"] for p in loaded])


def _labels(spec: DriveBy) -> dict[str, NDArray]:
    """Per-case label arrays (swept values, or the base file's where not swept)."""
    cases = spec.cases or ({},)
    base_road = spec.scenario.get("road", {})
    base_cross = spec.scenario.get("crossing", {})
    base_speed = base_cross.get("speed", base_cross.get("speed_kmh", 28.8) / 3.6)
    return {
        "speed": np.array([c.get("speed", base_speed) for c in cases], float),
        "road_class": np.array([c.get("road_class", base_road.get("class", "none")) for c in cases], dtype=object),
        "road_seed": np.array([c.get("road_seed", base_road.get("seed", 0)) for c in cases], np.int64),
        "damage_position": np.array([c.get("damage_position", np.nan) if c.get("damage_severity", 0) > 0 else np.nan
                                     for c in cases], float),
        "damage_severity": np.array([c.get("damage_severity", 0.0) for c in cases], float),
        "noise_rms": np.array([c.get("noise_rms", spec.sensors[0].noise_rms) for c in cases], float),
    }


LABEL_ATTRS = {
    "speed": ("m s-1", "vehicle speed"),
    "road_class": ("", "road roughness class (ISO 8608; none = smooth)"),
    "road_seed": ("1", "seed of the random road"),
    "damage_position": ("m", "start of the damaged region from the bridge entry (NaN: healthy)"),
    "damage_severity": ("1", "relative loss of bending stiffness EI in the damaged region (0: healthy)"),
    "noise_rms": ("sensor unit", "standard deviation of the sensors' added noise"),
}


def healthy_reference(labels: dict[str, NDArray]) -> NDArray[np.int64]:
    """For every case the index of its healthy counterpart (same speed, road, seed, noise and
    severity 0), or −1 when the sweep has none."""
    keys = ("speed", "road_class", "road_seed", "noise_rms")
    healthy = {tuple(labels[k][i] for k in keys): i for i in range(labels["speed"].size) if labels["damage_severity"][i] == 0}
    return np.array([healthy.get(tuple(labels[k][i] for k in keys), -1) for i in range(labels["speed"].size)], np.int64)


def dataset(spec: DriveBy, out: dict[str, NDArray], histories: list[NDArray]):
    """The sweep's labelled Dataset (dimensions ``case``, ``sensor``, ``sample``)."""
    import xarray as xr

    from vbikit._version import __version__

    order = np.argsort(out["case"])
    n_cases = order.size
    n_samples = max(h.shape[2] for h in histories)
    hist = np.full((n_cases, len(spec.sensors), n_samples), np.nan)
    row = 0
    for h in histories:
        hist[row:row + h.shape[0], :, :h.shape[2]] = h
        row += h.shape[0]
    hist = hist[order]
    variables: dict[str, Any] = {}
    for name, (units, long_name) in CASE_OUTPUTS.items():
        values = out[name][order]
        variables[name] = ("case", values.astype(np.int64) if name.startswith("n_") else values,
                           {"units": units, "long_name": long_name})
    labels = _labels(spec)
    for name, (units, long_name) in LABEL_ATTRS.items():
        attrs = {"long_name": long_name} | ({"units": units} if units else {})
        variables[name] = ("case", labels[name], attrs)
    ident, true = out["identified_frequency_hz"][order], out["bridge_frequency_hz"][order]
    variables["frequency_error"] = ("case", ident / true - 1.0, {"units": "1", "long_name": "identified / true − 1"})
    ref = healthy_reference(labels)
    shift = np.where(ref >= 0, ident / ident[np.maximum(ref, 0)] - 1.0, np.nan)
    true_shift = np.where(ref >= 0, true / true[np.maximum(ref, 0)] - 1.0, np.nan)
    variables["identified_frequency_shift"] = ("case", shift, {"units": "1", "long_name":
                                              "damage indicator: identified frequency / that of the healthy case − 1"})
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
                  "curvature_change_x": ("m", "position of the largest curvature change (damage location estimate)")}
    values = {k: np.full(n_cases, np.nan) for k in indicators}
    grid = np.linspace(0.0, float(case_crossing(spec, spec.cases[0] if spec.cases else {}).bridge.span), SHAPE_POINTS)
    for i in range(n_cases):
        j = ref[i]
        if j < 0 or not (np.all(np.isfinite(shapes[i])) and np.all(np.isfinite(shapes[j]))):
            continue
        values["mode_shape_mac"][i] = shape_change(np.sqrt(shapes[j]), np.sqrt(shapes[i]))["mac"]
        inner = slice(SHAPE_POINTS // 10, SHAPE_POINTS - SHAPE_POINTS // 10)  # the band-pass's and Hilbert transform's end effects
        ind = shape_change(np.sqrt(shapes[j][inner]), np.sqrt(shapes[i][inner]))
        values["curvature_change"][i] = ind["curvature_change"]
        values["curvature_change_x"][i] = grid[inner][ind["curvature_argmax"]]
    for k, (units, long_name) in indicators.items():
        variables[k] = ("case", values[k], {"units": units, "long_name": long_name})
    variables["sensor_history"] = (("case", "sensor", "sample"), hist, {
        "units": "see sensor_units", "long_name": "sensor record at t = time_start + sample / sampling_rate (NaN after its end)"})
    variables["noise_std"] = (("case", "sensor"), out["noise_std"][order], {
        "units": "see sensor_units", "long_name": "standard deviation of the noise added to each sensor's record"})
    variables["time_start"] = ("case", out["time0"][order], {"units": "s", "long_name": "time of the first sample"})
    coords = {
        "case": ("case", np.arange(n_cases)),
        "position": ("position", grid, {"units": "m", "long_name": "distance along the deck from the entry support"}),
        "sensor": ("sensor", np.array([s.name for s in spec.sensors], dtype=object)),
        "sensor_units": ("sensor", np.array([s.unit for s in spec.sensors], dtype=object)),
        "sensor_quantity": ("sensor", np.array([s.quantity for s in spec.sensors], dtype=object)),
    }
    attrs = {"title": spec.name or "vbikit drive-by dataset", "study": spec.to_json(), "vbikit_version": __version__,
             "sampling_rate": spec.sampling.rate, "sampling_filter": f"Butterworth order {spec.sampling.filter_order}, "
             f"cut-off {spec.sampling.cutoff_hz:g} Hz, zero phase (forward-backward), applied before resampling",
             "identification_method": spec.method, "identification_sensor": spec.sensor, "Conventions": "CF-1.8"}
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def run_driveby(spec: DriveBy | str | Path | dict, out_dir: str | Path = "vbikit-out", workers: Optional[int] = 1,
                scheduler: Optional[str] = None, progress=None, figures: bool = True):
    """Run a drive-by sweep (a ``DriveBy``, a file path or its parsed dict) on the study runner and
    write ``out_dir``/driveby.nc, the figures (``driveby-*.png``) and ``driveby-report.txt``;
    returns the Dataset.  Resumable: run it again after an interruption."""
    from vbikit._files import write_text
    from vbikit.driveby.spec import load_driveby, parse_driveby
    from vbikit.study.run import run_study

    if isinstance(spec, dict):
        spec = parse_driveby(spec)
    elif not isinstance(spec, DriveBy):
        spec = load_driveby(spec)
    check_cases(spec)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    ds = run_study(DriveByStudy(spec), out_dir / "driveby.nc", workers=workers, scheduler=scheduler, progress=progress)
    from vbikit.driveby.report import report_text

    write_text(out_dir / "driveby-report.txt", report_text(ds))
    if figures:
        from vbikit.driveby.figures import write_figures

        write_figures(ds, out_dir)
    return ds
