"""Turn a validated [`Scenario`][vbikit.scenario.Scenario] into model objects and a Crossing."""
from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from vbikit._kept import Kept
from vbikit.analysis.plan import ResponsePlan, ResponsePoint
from vbikit.bridge.base import GirderDeck, HasLoadEffects, ModalBridge
from vbikit.bridge.damage import Damage
from vbikit.bridge.effects import LoadEffect
from vbikit.contact.registry import tire_model
from vbikit.contact.tires import TireModel
from vbikit.road.defects import Defect, with_defects
from vbikit.road.measured import read_profile_csv
from vbikit.road.profile import RoadOrigin, RoadProfile
from vbikit.road.psd import RoadPSD, correlated_profile, random_profile
from vbikit.scenario.schema import (
    BridgeSpec,
    ResponsePointSpec,
    RoadSpec,
    Scenario,
    ScenarioError,
    TireSpec,
    VehicleEntry,
)
from vbikit.solve.budget import (
    MAX_AXLES,
    MAX_BEAM_ELEMENTS,
    MAX_EFFECT_ELEMENTS,
    MAX_SPANS,
    MAX_VEHICLES,
    BudgetError,
    Limits,
    check_bridge,
    check_road,
    check_size,
)
from vbikit.solve.crossing import Crossing, VehicleMotion
from vbikit.solve.timestep import automatic_road_per_step
from vbikit.vehicle.model import Vehicle
from vbikit.vehicle.presets import VEHICLE_PRESETS


#: bridges built from [bridge] specs, newest last (``build_bridge``): a study's batches, repeated runs
#: and the events of a process reuse one bridge, with its modes, mode tables along the wheel tracks
#: and load-effect factorisation
#: [substitute] bridges kept (a 3D deck with its tables and factors holds a few MB)
BRIDGE_CACHE_SIZE = 4
_BRIDGES: "Kept[str, ModalBridge]" = Kept(BRIDGE_CACHE_SIZE)


#: vehicles and tire models built from their specs (``build_vehicle``, ``build_tire``), newest last:
#: repeated runs of one vehicle on one tire model get the same (immutable) objects, hence the
#: contact points and vehicle tables kept per object pair (``vbikit.solve.crossing``)
VEHICLE_CACHE_SIZE = 16
_VEHICLES: "Kept[str, Vehicle]" = Kept(VEHICLE_CACHE_SIZE)
_TIRES: "Kept[str, TireModel]" = Kept(VEHICLE_CACHE_SIZE)


def _names_file(value: object, key: str = "") -> bool:
    """A spec value (or one inside it) under a key naming a file or path."""
    if isinstance(value, dict):
        return any(_names_file(v, str(k)) for k, v in value.items())
    if isinstance(value, (list, tuple)):
        return any(_names_file(v, key) for v in value)
    return value is not None and ("file" in key or "path" in key)


def _spec_key(kind: str, data: object) -> str | None:
    """The cache key of a spec's values ``data``: all of them (and the mode-cache folder), exactly; None
    (not kept) when the spec names a file, whose content may change between runs, or holds a value
    JSON does not hold exactly (a numpy array, whose text form is rounded and shortened)."""
    if _names_file(data):
        return None
    try:
        return json.dumps([kind, data, os.environ.get("VBIKIT_CACHE_DIR", "")], sort_keys=True)
    except (TypeError, ValueError):
        return None


def _bridge_key(spec: BridgeSpec) -> str | None:
    """The cache key of a [bridge] spec (``_spec_key``)."""
    return _spec_key(type(spec).__name__, spec.model_dump(mode="json"))


def build_bridge(spec: BridgeSpec, base_dir: Path | str = ".") -> ModalBridge:
    """The bridge model of a [bridge] spec (each kind builds its own: ``spec.build(base_dir)``); the
    same spec again gives the same (immutable) bridge object, kept for the last
    ``BRIDGE_CACHE_SIZE`` specs (not for a spec naming a file)."""
    key = _bridge_key(spec)
    if key is None:
        return spec.build(base_dir)
    return _BRIDGES.get(key, lambda: spec.build(base_dir))


def build_damage(spec: BridgeSpec) -> tuple[Damage, ...]:
    """The [[bridge.damage]] regions as ``Damage`` (checked)."""
    return spec.damage_regions()


def build_tire(spec: TireSpec) -> TireModel:
    """The tire model of a [tire] table: the registered class of ``spec.model`` built from its
    parameters (ValueError listing the registered names for an unknown model); the same table
    again gives the same (immutable) object (``_TIRES``)."""
    def make() -> TireModel:
        return tire_model(spec.model).from_parameters(spec.parameters)

    key = _spec_key("tire", spec.model_dump(mode="json"))
    return make() if key is None else _TIRES.get(key, make)


def build_vehicle(model: str, parameters: dict) -> Vehicle:
    """The vehicle preset ``model`` built with ``parameters``; the same again gives the same
    (immutable) object (``_VEHICLES``; not kept when a parameter names a file)."""
    def make() -> Vehicle:
        return VEHICLE_PRESETS[model].build(**parameters)

    key = _spec_key("vehicle", [model, parameters])
    return make() if key is None else _VEHICLES.get(key, make)


def vehicle_motion(entry: VehicleEntry, default_speed: float | None) -> VehicleMotion:
    """One [[vehicles]] table as a [`VehicleMotion`][vbikit.solve.VehicleMotion] (speed default: the [crossing] one;
    lateral offset default: the bridge's)."""
    vehicle = build_vehicle(entry.model, entry.parameters)
    speed = entry.speed_ms if entry.speed_ms is not None else default_speed
    return VehicleMotion(vehicle, speed=float(speed), acceleration=entry.acceleration, direction=entry.direction,
                         entry_time=entry.entry_time,
                         lateral_offset=entry.lateral_offset,
                         tire=build_tire(entry.tire) if entry.tire is not None else None)


def build_defects(spec: RoadSpec) -> list[Defect]:
    defects = []
    for i, d in enumerate(spec.defects):
        try:
            defects.append(Defect.of_kind(d.kind, start=d.position, size=d.depth if d.depth is not None else d.height,
                                          length=d.length, ramp=d.ramp, shape=d.shape))
        except ValueError as err:
            raise ScenarioError(f"road.defects.{i} ({d.kind}): {err}") from None
    return defects


def build_right_road(spec: RoadSpec, scenario: Scenario, left: RoadProfile | None,
                     window: tuple[float, float] | None = None) -> RoadProfile | None:
    """The right wheel line's own profile, or None when both lines share ``left`` (the default);
    ``window``: as ``left``'s (``build_road``)."""
    if spec.profile_file_right:
        return _profile(scenario, spec.profile_file_right, "road.profile_file_right")
    if left is None or spec.right_coherence >= 1.0:
        return None

    def make() -> RoadProfile:
        return correlated_profile(left, road_psd(spec), spec.seed, spec.right_coherence, spacing=spec.spacing,
                                  length=spec.length, window=window)

    if window is not None or _ROADS.peek(_road_key(spec, "left")) is not left:  # kept only with its kept left line
        return make()
    return _ROADS.get(_road_key(spec, "right"), make)


def road_psd(spec: RoadSpec) -> RoadPSD:
    """The random road's PSD and band of a [road] table with a class (A…H or psd)."""
    band = {"n_min": spec.n_min, "n_max": spec.n_max}
    if spec.road_class == "psd":
        return RoadPSD(spec.phi0, spec.n0, spec.exponent, **band)
    return RoadPSD.iso(spec.road_class, **band)


def check_road_budget(spec: RoadSpec, limits: Limits | None = None) -> None:
    """Refuse a random road whose profile would not fit the memory budget (before generating it)."""
    if spec.road_class != "none" and not spec.profile_file:
        check_road(spec.length, spec.spacing, spec.n_min, limits, "road")


def _profile(scenario: Scenario, name: str, key: str) -> RoadProfile:
    """A measured profile file; its errors name the scenario key and the file."""
    try:
        return read_profile_csv(scenario.base_dir / name)
    except ValueError as err:
        raise ScenarioError(f"{key}: {err}") from None


#: whole-period random roads built from [road] specs, newest last (``build_road``): runs of one road
#: with other vehicles, tires or speeds (``vbikit compare-tires``, a script's sweep) generate it once
#: (shared: nothing may write to them; they stay writeable because numba compiles its kernels again
#: for read-only arrays, ≈ 4 s, with results that differ in the last bits)
#: [substitute] whole-period roads kept (a 1.3 km period at 0.01 m holds 1 MB of elevations)
ROAD_CACHE_SIZE = 4
_ROADS: "Kept[str, RoadProfile | None]" = Kept(ROAD_CACHE_SIZE)


def _road_key(spec: RoadSpec, side: str) -> str:
    """The cache key of a random [road] spec's ``side`` ("left" or "right") whole-period profile: its every value."""
    return json.dumps([side, spec.model_dump(mode="json")], sort_keys=True, default=str)


def build_road(spec: RoadSpec, scenario: Scenario, window: tuple[float, float] | None = None) -> RoadProfile | None:
    """The road profile of ``spec`` (None: smooth); a random one only over ``window`` = (x_lo, x_hi) [m]
    when given (the range a crossing touches, ``Crossing.road_extent``: the same road there, far cheaper
    than its whole period, ``vbikit.road.random_profile``).  A whole-period random road is kept for the
    last ``ROAD_CACHE_SIZE`` specs (the same object for the same spec: not to be written to)."""
    defects = build_defects(spec)
    if spec.profile_file:
        return with_defects(_profile(scenario, spec.profile_file, "road.profile_file"), defects)
    if spec.road_class == "none":
        return with_defects(RoadProfile.flat(), defects) if defects else None
    label = f"class {spec.road_class}, seed {spec.seed}"

    def make() -> RoadProfile:
        return with_defects(random_profile(road_psd(spec), spec.seed, spacing=spec.spacing, length=spec.length,
                                           label=label, window=window,
                                           origin=RoadOrigin("random", spec.road_class, spec.seed)), defects)

    return make() if window is not None else _ROADS.get(_road_key(spec, "left"), make)


@dataclass(frozen=True)
class BuiltScenario:
    """A scenario as models.

    Parameters
    ----------
    crossing : Crossing
        The physics.
    plan : ResponsePlan
        What to read: the response points and load effects.
    """

    crossing: Crossing
    plan: ResponsePlan

    @property
    def response_x(self) -> float | None:
        """x [m] of the headline (first) response point; None: the bridge's default section."""
        return self.plan.first.x

    @property
    def response_y(self) -> float:
        """y [m] of the headline response point."""
        return float(self.plan.first.y)

    @property
    def response_girder(self) -> int | None:
        """1-based girder of the headline response point (slab-on-girder bridges), else None."""
        return self.plan.first.girder

    @property
    def load_effects(self) -> tuple[LoadEffect, ...]:
        """Moments, shears and reactions to report (empty if the bridge model offers none)."""
        return self.plan.load_effects

    @property
    def load_effect_method(self) -> str:
        return self.plan.load_effect_method


def build_load_effects(scenario: Scenario, bridge: ModalBridge, girder: int | None) -> tuple[LoadEffect, ...]:
    """The moments, shears and reactions of ``[response]`` (moment / shear sections [m], reaction
    support indices), on ``girder`` for a deck; the bridge's defaults where a list is not given.
    Empty for bridge models without load effects (unless some were asked for: an error)."""
    r = scenario.response
    asked = [k for k in ("moment", "shear", "reaction") if getattr(r, k) is not None]
    if not isinstance(bridge, HasLoadEffects):
        if asked:
            raise ScenarioError(f"response.{asked[0]}: bridge model {scenario.bridge.model!r} does not offer load effects")
        return ()
    kw = {} if girder is None else {"girder": girder}
    try:
        defaults = bridge.default_load_effects(**kw)  # type: ignore[attr-defined]
        out = []
        for kind in ("moment", "shear", "reaction"):
            wanted = getattr(r, kind)
            if wanted is None:
                out += [e for e in defaults if e.kind == kind]
            elif kind == "reaction":
                out += [bridge.load_effect("reaction", support=j, **kw) for j in wanted]  # type: ignore[attr-defined]
            else:
                out += [bridge.load_effect(kind, x=float(x), **kw) for x in wanted]  # type: ignore[attr-defined]
    except ValueError as err:
        raise ScenarioError(f"response: {err}") from None
    return tuple(out)


def with_scenario_road(crossing: Crossing, spec: RoadSpec, scenario: Scenario, seed: int | None = None) -> Crossing:
    """``crossing`` (built without a road) on the road of ``spec`` (``seed``: instead of its own), a
    random road generated only over the range its contact points touch (the events of traffic and
    lifetime runs, each on its own road: the same road there as the whole period's to ≈ 1e-15 of its
    rms, at a fraction of the cost; a scenario run keeps the whole period, bitwise the road of a
    Python script's ``random_profile``)."""
    if seed is not None:
        spec = spec.model_copy(update={"seed": int(seed)})
    window = crossing.road_extent()
    # the time grid's last step may pass the crossing's end by up to a step, and the tire dashpots read the road
    # half a step beyond each point: the window reaches 1.5 steps further on each side (the given step's, or the
    # longest automatic one on this road)
    step = crossing.max_speed * float(crossing.dt) if crossing.dt is not None else automatic_road_per_step(spec.spacing)
    window = (window[0] - 1.5 * step, window[1] + 1.5 * step)
    road = build_road(spec, scenario, window)
    return crossing.with_road(road, build_right_road(spec, scenario, road, window))


def build(scenario: Scenario, limits: Limits | None = None) -> BuiltScenario:
    """Compose bridge, vehicle(s), tire and road into a Crossing.

    Parameters
    ----------
    scenario : Scenario
        A validated scenario.
    limits : Limits, optional
        Memory budget a bridge model or a random road must fit (default ``Limits()``).

    Returns
    -------
    BuiltScenario
        The crossing with the scenario's response points and load effects.

    Raises
    ------
    ScenarioError
        Bad combinations, or a bridge model that cannot be solved.
    BudgetError
        A bridge or road above ``limits``.
    """
    try:
        return _build(scenario, limits)
    except (RuntimeError, ArithmeticError, np.linalg.LinAlgError) as err:  # a model that cannot be solved
        raise ScenarioError(f"bridge (model = {scenario.bridge.model!r}): the model could not be solved "
                            f"({type(err).__name__}: {err}); check the bridge's dimensions and properties") from None


def check_sizes(scenario: Scenario, limits: Limits | None = None) -> None:
    """Refuse a scenario whose size (axles of a vehicle, vehicles, spans, beam elements, load effects
    × elements) is above its budget (``vbikit.solve.budget.check_size``), before anything is built."""
    vehicles = [("vehicle", scenario.vehicle)] if scenario.vehicle is not None else \
        [(f"vehicles[{i}]", v) for i, v in enumerate(scenario.vehicles or (), start=1)]
    check_size("vehicles: vehicles in one crossing", len(vehicles), MAX_VEHICLES, limits, "run fewer vehicles at once")
    for key, spec in vehicles:
        axles = (spec.model_extra or {}).get("axle_loads")
        if isinstance(axles, list):
            check_size(f"{key}.axle_loads: axles of one vehicle", len(axles), MAX_AXLES, limits, "give fewer axles")
    bridge = scenario.bridge
    deck = bridge.deck or {}
    spans = getattr(bridge, "spans", None) or (deck.get("spans") if isinstance(deck.get("spans"), list) else None)
    if not spans:
        return
    key = "bridge.spans" if getattr(bridge, "spans", None) else "bridge.deck.spans"
    n = len(spans)
    check_size(f"{key}: spans", n, MAX_SPANS, limits, "give fewer spans")
    per_span = getattr(bridge, "elements_per_span", None)
    if per_span is None:  # a grillage: its degrees of freedom are checked once it is meshed (check_bridge)
        return
    elements = n * int(per_span)
    check_size(f"bridge.elements_per_span: {n} spans × {per_span} elements", elements, MAX_BEAM_ELEMENTS, limits,
               "use fewer bridge.elements_per_span")
    r = scenario.response
    defaults = {"moment": 2 * n - 1, "shear": n, "reaction": n + 1}  # the beam's default load effects
    effects = sum(len(getattr(r, k)) if getattr(r, k) is not None else d for k, d in defaults.items())
    check_size(f"response: {effects} load effects × {elements} beam elements", effects * elements, MAX_EFFECT_ELEMENTS,
               limits, "ask for fewer response.moment / shear / reaction or use fewer bridge.elements_per_span")


def _build(scenario: Scenario, limits: Limits | None) -> BuiltScenario:
    check_sizes(scenario, limits)
    try:
        bridge = build_bridge(scenario.bridge, scenario.base_dir)
        check_bridge(bridge, limits)
        check_road_budget(scenario.road, limits)
        c = scenario.crossing
        road = build_road(scenario.road, scenario)  # the whole period: as a Python script's random_profile
        common = dict(bridge=bridge, tire=build_tire(scenario.tire), road=road,
                      road_right=build_right_road(scenario.road, scenario, road), approach=c.approach, run_in=c.run_in,
                      free_vibration=c.free_vibration, dt=c.dt,
                      integrator=c.integrator, resolve=c.resolve,
                      loss_of_contact=scenario.tire.loss_of_contact)
        if scenario.vehicles is None:
            vehicle: Vehicle = build_vehicle(scenario.vehicle.model, scenario.vehicle.parameters)
            crossing = Crossing(vehicle=vehicle, speed=c.speed_ms, acceleration=c.acceleration,
                                lateral_offset=c.lateral_offset,  # None: the bridge's default
                                **common)
        else:
            motions = tuple(vehicle_motion(v, c.speed_ms) for v in scenario.vehicles)
            crossing = Crossing(vehicles=motions, speed=max(m.speed for m in motions), **common)
    except BudgetError:
        raise
    except ValueError as err:
        raise ScenarioError(str(err)) from None
    r = scenario.response
    points = tuple(response_point(scenario, bridge, spec, f"response.points[{i}]." if r.points is not None else "response.")
                   for i, spec in enumerate(r.point_specs, start=1))
    effects = build_load_effects(scenario, bridge, points[0].girder)
    return BuiltScenario(crossing, ResponsePlan(points, effects, r.load_effect_method))


def response_point(scenario: Scenario, bridge: ModalBridge, spec: ResponsePointSpec, key: str) -> ResponsePoint:
    """One response point of the scenario, checked: its line y (a girder's, the bridge's default girder
    on a slab-on-girder deck, or as given) and its section x (``response_x``); ``key`` prefixes errors."""
    if not isinstance(bridge, GirderDeck):
        if spec.girder is not None:
            raise ScenarioError(f"{key}girder: bridge model {scenario.bridge.model!r} has no girders; use {key}y")
        girder, y = None, bridge.default_response_y if spec.y is None else spec.y
    else:
        girder_y = bridge.girder_y
        girder = spec.girder if spec.girder is not None else (None if "y" in spec.model_fields_set else int(bridge.default_girder))
        if girder is not None and not 1 <= girder <= len(girder_y):
            raise ScenarioError(f"{key}girder: must be 1 … {len(girder_y)} for bridge {scenario.bridge.model!r} (got {girder})")
        y = spec.y if girder is None else float(girder_y[girder - 1])
    width = getattr(bridge, "deck_width", None)
    if width is not None and np.isfinite(width) and abs(float(y)) > 0.5 * float(width) + 1e-9:
        raise ScenarioError(f"{key}y: {float(y):g} m is off the {float(width):g} m wide deck (|y| ≤ "
                            f"{0.5 * float(width):g} m from the centreline)")
    return ResponsePoint(response_x(bridge, spec.x, y, key), float(y), girder, spec.name)


def response_x(bridge: ModalBridge, x: float | None, y: float, key: str = "response.") -> float | None:
    """The response section's x [m]: as given (checked: within the span on the line y), or None for
    the bridge's default — on a skew deck the default section of the line y itself (the support
    lines are oblique, so the default girder's midspan x is not that of the others)."""
    if x is None:
        own = bridge.default_x_at(y)
        return None if own == bridge.default_response_x else own
    xi = float(bridge.span_coordinate(x, y))
    if not 0.0 <= xi <= bridge.span:
        extra = "" if xi == x else f" along the line y = {y:g} m (x − y·tan(skew) = {xi:.6g} m)"
        raise ScenarioError(f"{key}x: must be within the span 0 … {bridge.span} m{extra} (got {x})")
    return x
