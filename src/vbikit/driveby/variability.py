"""Variability of a drive-by dataset: random passes, drawn reproducibly per pass.

The ``[variability]`` table of a drive-by file (all keys optional)::

    [variability]
    passes = 600                    # passes per combination of the sweep (and scour class), each a fresh draw
    speed = [19.0, 21.0]            # speed drawn uniformly in [lo, hi] per pass [m/s] (replaces the swept speed)
    vehicle_spread = 0.10           # every vehicle mass, stiffness and damping × U(1 − s, 1 + s), independently
    support_stiffness = 5e8         # base vertical stiffness of every support spring [N/m] (continuous-beam)
    scour_classes = [1.0, 0.95, 0.90]   # support stiffness factors of the classes (class k = factor k)
    temperature = [0.0, 30.0]       # deck temperature drawn uniformly [°C]
    temperature_reference = 20.0    # [°C]: E(T_ref) = the file's EI
    temperature_coefficient = 0.003 # α_E [1/°C] of E(T) = E_ref [1 − α_E (T − T_ref)]
    traffic_flow = 600              # background trucks [trucks/h] on the bridge during the pass (coupled only)
    traffic_speed_kmh = 80.0        # their mean speed [km/h] (standard deviation 10 %)
    traffic_direction = "-x"        # their direction: "-x" oncoming, "+x" the instrumented vehicle's
    rotational_stiffness = {distribution = "loguniform", low = 1e7, high = 1e10}  # end springs [N m/rad], each end its own draw
    damage_position = {distribution = "uniform", low = 5.0, high = 18.0}          # start of the damaged region [m]
    damage_length = 2.0                                                           # a number: the same every pass [m]
    damage_severity = {distribution = "choice", values = [0.0, 0.1, 0.2, 0.3]}    # loss of EI (0: healthy)
    fleet = "draw"                  # with [[fleet]]: "draw" one vehicle per pass, "all" every vehicle on every pass

Distributions (``DISTRIBUTIONS``, one mechanism for every drawn parameter of ``DRAWN_PARAMETERS``):
a number (fixed, nothing drawn), ``{distribution = "uniform", low, high}`` (U(low, high)),
``{distribution = "loguniform", low, high}`` (exp U(ln low, ln high), low > 0) or
``{distribution = "choice", values = [...]}`` (one of the values, each with probability 1/n).
Every bound and value must lie in the parameter's allowed range (``DRAWN_PARAMETERS``); the
check is the pydantic schema ``DrawnParameters``, whose errors name the key and the range.

Draws.  Pass (case) ``i`` of a file with seed ``s`` draws from
``numpy.random.default_rng(numpy.random.SeedSequence(s, spawn_key=(i,)))`` — the i-th child that
``SeedSequence(s).spawn`` would give — so a pass's draw depends only on (s, i): the same in any
order, in any batch, on any worker.  The draw order within a pass is fixed: speed, temperature,
vehicle factors (masses, stiffnesses, dampings, tire stiffnesses, tire dampings), the traffic
seed, then the parameters of ``DRAWN_PARAMETERS`` in its order (rotational stiffness at the entry
then the exit, damage position, length, severity; a fixed number draws nothing), then the fleet
vehicle (``fleet = "draw"``: ``rng.integers(0, n_vehicles)``).  A key added later draws after
these: the earlier draws keep their values.  The vehicle factors are drawn for the largest
vehicle of a fleet (most DOFs, most wheels); a smaller vehicle uses the first of them.

Fleet.  ``[[fleet]]`` tables (each a ``[vehicle]`` table with a ``name``) replace ``[vehicle]``:
with ``fleet = "draw"`` every pass draws its vehicle; with ``"all"`` every pass (one draw: speed,
road, temperature, bridge) is run by every vehicle, the passes of one draw adjacent, sharing
their ``index`` (the key of the draw) and their part of the split.

Vehicle factors.  A vehicle is stored as matrices (``vbikit.vehicle.model``), so the spread is
applied per degree of freedom and per wheel: M' = S_m M S_m, K' = S_k K S_k, C' = S_c C S_c with
S = diag(√a_j), a_j ~ U(1 − s, 1 + s) per DOF j (for a diagonal mass matrix: each body's mass or
inertia × a_j; gravity scaled with the mass, F_G' = a_m F_G), and each tire's stiffness and damping
× its own factor.  For the single-DOF test cart this is exactly "mass, stiffness, damping ± s".

Temperature.  E(T) = E_ref [1 − α_E (T − T_ref)], a linear law fitted to concrete decks in service;
default α_E = 0.003 /°C [substitute]: Xia, Hao, Zanardo & Deeks (2006), "Long term vibration
monitoring of an RC slab: temperature and humidity effect", Engineering Structures 28(3), 441–452,
measured frequency drops of 0.13–0.23 % per °C, i.e. (f ∝ √E) 0.26–0.46 % per °C of E; 0.3 % lies
inside that range.  The factor multiplies the bridge's EI (every element).

Scour.  A class scales every vertical support spring of a ``continuous-beam`` bridge:
k_support = support_stiffness × scour_classes[k] (the published scour set's "foundation stiffness
classes" 1.00 / 0.95 / 0.90).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable, Optional

import numpy as np
from numpy.typing import NDArray
from pydantic import BaseModel, ConfigDict, Field, ValidationError, create_model, field_validator

from vbikit.errors import VbikitError



@dataclass(frozen=True)
class DrawnParameter:
    """A bridge parameter drawn per pass from a stated distribution (``DRAWN_PARAMETERS``):
    allowed range [low, high], unit, how many values a pass draws (one per label) and their labels."""

    low: float
    high: float
    unit: str
    labels: tuple[str, ...]
    long_name: str


#: parameters drawn per pass from a distribution, in draw order: key -> allowed range, unit, labels
DRAWN_PARAMETERS: dict[str, DrawnParameter] = {
    "rotational_stiffness": DrawnParameter(
        0.0, 1e13, "N m rad-1", ("rotational_stiffness_entry", "rotational_stiffness_exit"),
        "rotational spring at the {end} support [N m/rad] (0 pinned; continuous-beam), drawn per pass"),
    "damage_position": DrawnParameter(0.0, 1e5, "m", ("damage_position",),
                                      "start of the damaged region from the bridge entry (NaN: healthy)"),
    "damage_length": DrawnParameter(1e-3, 1e3, "m", ("damage_length",), "length of the damaged region (NaN: healthy)"),
    "damage_severity": DrawnParameter(0.0, 0.99, "1", ("damage_severity",),
                                      "relative loss of bending stiffness EI in the damaged region (0: healthy)"),
}
#: the damage keys: drawn together (a drawn damage needs its position and severity)
DAMAGE_KEYS = ("damage_position", "damage_length", "damage_severity")


class Distribution(BaseModel):
    """One drawn parameter's distribution (module docstring, ``DISTRIBUTIONS``)."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    distribution: str = Field(..., description="one of DISTRIBUTIONS")
    low: Optional[float] = None
    high: Optional[float] = None
    values: Optional[tuple[float, ...]] = None

    def draw(self, rng: np.random.Generator) -> float:
        return float(DISTRIBUTIONS[self.distribution][1](self, rng))

    @property
    def bounds(self) -> tuple[float, float]:
        """The least and the largest value a draw can take."""
        if self.values is not None:
            return min(self.values), max(self.values)
        return self.low, self.low if self.high is None else self.high


def _uniform(d: Distribution, rng: np.random.Generator) -> float:
    return rng.uniform(d.low, d.high)


def _loguniform(d: Distribution, rng: np.random.Generator) -> float:
    return math.exp(rng.uniform(math.log(d.low), math.log(d.high)))


def _choice(d: Distribution, rng: np.random.Generator) -> float:
    return d.values[int(rng.integers(0, len(d.values)))]


def _fixed(d: Distribution, rng: np.random.Generator) -> float:
    return d.low


#: distributions: name -> (the keys it takes, sampler(distribution, rng)); a number is "fixed"
DISTRIBUTIONS: dict[str, tuple[tuple[str, ...], Callable[[Distribution, np.random.Generator], float]]] = {
    "uniform": (("low", "high"), _uniform),
    "loguniform": (("low", "high"), _loguniform),
    "choice": (("values",), _choice),
    "fixed": (("low",), _fixed),
}


def _distribution(value: Any, info) -> Distribution:
    """Validator of every ``DrawnParameters`` field: a number or a distribution table, its bounds and
    values inside the key's allowed range (``DRAWN_PARAMETERS``)."""
    key = info.field_name
    p = DRAWN_PARAMETERS[key]
    where = f"variability.{key}"
    allowed = f"allowed: [{p.low:g}, {p.high:g}] {p.unit}"
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        value = {"distribution": "fixed", "low": value}
    if not isinstance(value, dict) or not isinstance(value.get("distribution"), str):
        raise ValueError(f"{where}: a number or a table {{distribution = \"{'|'.join(d for d in DISTRIBUTIONS if d != 'fixed')}\", "
                         f"...}}, got {value!r}")
    kind = value["distribution"]
    if kind not in DISTRIBUTIONS:
        raise ValueError(f"{where}.distribution: {kind!r}; allowed: {', '.join(DISTRIBUTIONS)}")
    keys = DISTRIBUTIONS[kind][0]
    extra = [k for k in value if k not in ("distribution", *keys)]
    missing = [k for k in keys if k not in value]
    if extra or missing:
        raise ValueError(f"{where}: distribution {kind!r} takes {', '.join(keys)}; "
                         + (f"unknown {extra[0]!r}" if extra else f"missing {missing[0]!r}"))

    def check(name: str, v: Any, lo: float = p.low) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and lo <= v <= p.high):
            unit = "" if p.unit == "1" else f" {p.unit}"
            bound = f"({p.low:g}, {p.high:g}]{unit}" if lo > p.low else f"[{p.low:g}, {p.high:g}]{unit}"
            raise ValueError(f"{where}.{name}: expected a number in {bound}, got {v!r}")
        return float(v)

    if kind == "choice":
        values = value["values"]
        if not isinstance(values, list) or not values:
            raise ValueError(f"{where}.values: a non-empty list of numbers, {allowed}")
        return Distribution(distribution=kind, values=tuple(check("values", v) for v in values))
    low = check("low", value["low"], lo=math.nextafter(0.0, 1.0) if kind == "loguniform" else p.low)
    if kind == "fixed":
        return Distribution(distribution=kind, low=low)
    high = check("high", value["high"], lo=math.nextafter(0.0, 1.0) if kind == "loguniform" else p.low)
    if low > high:
        raise ValueError(f"{where}: expected low <= high, got low = {low:g}, high = {high:g}")
    return Distribution(distribution=kind, low=low, high=high)


#: the one schema of the drawn parameters: a field per ``DRAWN_PARAMETERS`` key, each a ``Distribution``
DrawnParameters = create_model(
    "DrawnParameters", __config__=ConfigDict(extra="forbid", arbitrary_types_allowed=True),
    __validators__={"distribution": field_validator(*DRAWN_PARAMETERS, mode="before")(_distribution)},
    **{k: (Optional[Distribution], None) for k in DRAWN_PARAMETERS})
#: how a fleet's vehicles take part: "draw" one per pass, "all" each pass by every vehicle
FLEET_MODES = {"draw": "every pass draws its vehicle of [[fleet]]", "all": "every pass is run by every vehicle of [[fleet]]"}

#: keys of [variability]
VARIABILITY_KEYS = ("passes", "speed", "vehicle_spread", "support_stiffness", "scour_classes", "temperature",
                    "temperature_reference", "temperature_coefficient", "traffic_flow", "traffic_speed_kmh",
                    "traffic_direction", *DRAWN_PARAMETERS, "fleet")
#: default speed [km/h] of the background trucks (``vbikit.traffic.LaneTraffic``'s default)
TRAFFIC_SPEED_KMH = 80.0
#: default α_E [1/°C] (module docstring, Xia et al. 2006)
TEMPERATURE_COEFFICIENT = 0.003
#: default reference temperature [°C]
TEMPERATURE_REFERENCE = 20.0
#: top-level coupling modes
COUPLINGS = {"coupled": "vehicle and bridge solved together (vbikit.solve.simulate)",
             "decoupled": "bridge under the static wheel loads, then the vehicle on its motion (vbikit.driveby.decoupled)"}
#: default: every how many passes a decoupled run is compared with a coupled run of the same pass
COUPLING_CHECK_EVERY = 10


class VariabilityError(VbikitError):
    """An invalid [variability] table or coupling key; the message names the key."""

    message_names_key = True


@dataclass(frozen=True)
class Variability:
    """A parsed [variability] table (module docstring); ``None`` where not varied."""

    passes: int = 1
    speed: Optional[tuple[float, float]] = None
    vehicle_spread: float = 0.0
    support_stiffness: Optional[float] = None
    scour_classes: tuple[float, ...] = ()
    temperature: Optional[tuple[float, float]] = None
    temperature_reference: float = TEMPERATURE_REFERENCE
    temperature_coefficient: float = TEMPERATURE_COEFFICIENT
    traffic_flow: Optional[float] = None
    traffic_speed_kmh: float = TRAFFIC_SPEED_KMH
    traffic_direction: str = "-x"
    #: (key, Distribution) of the parameters drawn from ``DRAWN_PARAMETERS``, in its order
    drawn: tuple = ()
    fleet: str = "draw"
    extra: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def active(self) -> bool:
        return self != Variability()


def _number(key: str, value: Any, lo: float, hi: float, integer: bool = False) -> float:
    ok = not isinstance(value, bool) and isinstance(value, (int,) if integer else (int, float))
    if not ok or not (math.isfinite(value) and lo <= value <= hi):
        kind = "an integer" if integer else "a number"
        raise VariabilityError(f"variability.{key}: expected {kind} in [{lo:g}, {hi:g}], got {value!r}")
    return value


def _range(key: str, value: Any, lo: float, hi: float) -> tuple[float, float]:
    if not (isinstance(value, list) and len(value) == 2):
        raise VariabilityError(f"variability.{key}: expected [low, high] with {lo:g} <= low <= high <= {hi:g}, got {value!r}")
    a, b = (_number(key, v, lo, hi) for v in value)
    if a > b:
        raise VariabilityError(f"variability.{key}: expected [low, high] with low <= high, got {value!r}")
    return float(a), float(b)


def parse_variability(table: Any) -> Variability:
    """Validate a [variability] table (module docstring); errors name the key and the allowed range."""
    if table is None:
        return Variability()
    if not isinstance(table, dict):
        raise VariabilityError(f"variability: expected a table [variability], got {type(table).__name__}")
    unknown = [k for k in table if k not in VARIABILITY_KEYS]
    if unknown:
        raise VariabilityError(f"variability.{unknown[0]}: unknown key; allowed: {', '.join(VARIABILITY_KEYS)}")
    t = table
    classes = t.get("scour_classes", [])
    if not isinstance(classes, list) or (classes and "support_stiffness" not in t):
        raise VariabilityError("variability.scour_classes: a list of support stiffness factors in (0, 10] that needs "
                               "variability.support_stiffness (the base stiffness [N/m])")
    return Variability(
        passes=int(_number("passes", t.get("passes", 1), 1, 1e6, integer=True)),
        speed=_range("speed", t["speed"], 0.1, 150.0) if "speed" in t else None,
        vehicle_spread=float(_number("vehicle_spread", t.get("vehicle_spread", 0.0), 0.0, 0.5)),
        support_stiffness=float(_number("support_stiffness", t["support_stiffness"], 1.0, 1e15)) if "support_stiffness" in t else None,
        scour_classes=tuple(float(_number("scour_classes", c, 1e-6, 10.0)) for c in classes),
        temperature=_range("temperature", t["temperature"], -60.0, 80.0) if "temperature" in t else None,
        temperature_reference=float(_number("temperature_reference", t.get("temperature_reference", TEMPERATURE_REFERENCE),
                                            -60.0, 80.0)),
        temperature_coefficient=float(_number("temperature_coefficient", t.get("temperature_coefficient",
                                                                               TEMPERATURE_COEFFICIENT), 0.0, 0.01)),
        traffic_flow=float(_number("traffic_flow", t["traffic_flow"], 1.0, 1700.0)) if "traffic_flow" in t else None,
        traffic_speed_kmh=float(_number("traffic_speed_kmh", t.get("traffic_speed_kmh", TRAFFIC_SPEED_KMH), 10.0, 200.0)),
        traffic_direction=_direction(t.get("traffic_direction", "-x")),
        drawn=parse_drawn(t), fleet=_fleet(t.get("fleet", "draw")))


def parse_drawn(table: dict) -> tuple:
    """The drawn parameters of a [variability] table, validated by the schema ``DrawnParameters``
    (errors name the key and its allowed range); ``((key, Distribution), ...)`` in draw order."""
    given = {k: table[k] for k in DRAWN_PARAMETERS if k in table}
    try:
        model = DrawnParameters.model_validate(given)
    except ValidationError as err:
        e = err.errors()[0]
        raise VariabilityError(e["msg"].removeprefix("Value error, ")) from None
    drawn = tuple((k, getattr(model, k)) for k in DRAWN_PARAMETERS if getattr(model, k) is not None)
    keys = {k for k, _ in drawn} & set(DAMAGE_KEYS)
    if keys and not {"damage_position", "damage_severity"} <= keys:
        raise VariabilityError("variability.damage_position: a drawn damage needs damage_position and damage_severity "
                               "(and damage_length, default the sweep's damage_length)")
    return drawn


def _fleet(value: Any) -> str:
    if value not in FLEET_MODES:
        raise VariabilityError(f"variability.fleet: {value!r}; allowed: {', '.join(FLEET_MODES)}")
    return value


def _direction(value: Any) -> str:
    if value not in ("+x", "-x"):
        raise VariabilityError(f"variability.traffic_direction: \"+x\" or \"-x\", got {value!r}")
    return value


def parse_coupling(data: dict) -> tuple[str, int]:
    """The top-level ``coupling`` ("coupled" or "decoupled") and ``coupling_check_every`` (a
    decoupled file's passes 0, n, 2n, … are also run coupled and their error reported; 0: never)."""
    coupling = data.get("coupling", "coupled")
    if coupling not in COUPLINGS:
        raise VariabilityError(f"coupling: {coupling!r}; allowed: {', '.join(COUPLINGS)}")
    every = data.get("coupling_check_every", COUPLING_CHECK_EVERY)
    if isinstance(every, bool) or not isinstance(every, int) or not 0 <= every <= 1_000_000:
        raise VariabilityError(f"coupling_check_every: expected an integer in [0, 1000000] (0: never), got {every!r}")
    return coupling, every


def pass_rng(seed: int, index: int) -> np.random.Generator:
    """The generator of pass ``index`` (module docstring): the same for (seed, index) in any order."""
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(int(index),)))


#: train / validation / test shares of the documented split (``split_of``)
SPLIT_SHARES = (0.70, 0.15, 0.15)
#: names of the split's parts, in code order 0, 1, 2
SPLIT_NAMES = ("train", "validation", "test")


def split_of(seed: int, index: int) -> int:
    """The part of the documented split case ``index`` belongs to: 0 train, 1 validation, 2 test
    (shares ``SPLIT_SHARES``), from u ~ U(0, 1) of ``SeedSequence(seed, spawn_key=(index, 1))`` — a
    stream of its own, independent of the pass's draw, fixed by (seed, index) like it."""
    u = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(int(index), 1))).random()
    return 0 if u < SPLIT_SHARES[0] else 1 if u < SPLIT_SHARES[0] + SPLIT_SHARES[1] else 2


def temperature_factor(var: Variability, temperature: float) -> float:
    """E(T) / E(T_ref) = 1 − α_E (T − T_ref) (module docstring)."""
    return 1.0 - var.temperature_coefficient * (temperature - var.temperature_reference)


def draw(var: Variability, seed: int, index: int, n_dof: int, n_wheels: int, n_vehicles: int = 0) -> dict[str, Any]:
    """The random parameters of pass ``index``: ``speed`` [m/s] and ``temperature`` [°C] (absent
    when not varied), ``vehicle_factors`` (5 arrays: per-DOF mass, stiffness, damping factors,
    per-wheel tire stiffness and damping factors; absent without a spread), ``traffic_seed``
    (the seed of the pass's background trucks, ``vbikit.driveby.traffic``; absent without
    ``traffic_flow``), every label of the ``DRAWN_PARAMETERS`` given (e.g.
    ``rotational_stiffness_entry``, ``damage_severity``) and ``vehicle`` (the index of the fleet's
    vehicle, with ``n_vehicles`` > 0 and ``fleet = "draw"``), drawn in this order (a new key draws
    last: earlier draws keep their values)."""
    rng = pass_rng(seed, index)
    out: dict[str, Any] = {}
    if var.speed is not None:
        out["speed"] = float(rng.uniform(*var.speed))
    if var.temperature is not None:
        out["temperature"] = float(rng.uniform(*var.temperature))
    if var.vehicle_spread > 0:
        s = var.vehicle_spread
        out["vehicle_factors"] = tuple(tuple(float(v) for v in rng.uniform(1 - s, 1 + s, n))
                                       for n in (n_dof, n_dof, n_dof, n_wheels, n_wheels))
    if var.traffic_flow is not None:
        out["traffic_seed"] = int(rng.integers(0, 2**62))
    for key, dist in var.drawn:
        for label in DRAWN_PARAMETERS[key].labels:
            out[label] = dist.draw(rng)
    if n_vehicles > 0 and var.fleet == "draw":
        out["vehicle"] = int(rng.integers(0, n_vehicles))
    return out


def expand_cases(cases: tuple, var: Variability, n_vehicles: int = 0) -> tuple:
    """The sweep's combinations × scour classes × passes (the pass index varies fastest; with a
    fleet of ``n_vehicles`` and ``fleet = "all"``, × vehicles, fastest of all); each case carries
    its ``index`` (the key of its draw, shared by the vehicles of one pass), its ``pass``, its
    ``scour_class`` and, with ``fleet = "all"``, its ``vehicle``."""
    if not var.active and not n_vehicles:
        return cases
    classes = range(len(var.scour_classes)) if var.scour_classes else [None]
    vehicles = range(n_vehicles) if n_vehicles and var.fleet == "all" else [None]
    out = []
    index = 0
    for combo in cases or ({},):
        for k in classes:
            for p in range(var.passes):
                for v in vehicles:
                    out.append({**combo, **({} if k is None else {"scour_class": k}), "pass": p, "index": index,
                                **({} if v is None else {"vehicle": v})})
                index += 1
    return tuple(out)


def perturbed_vehicle(vehicle, factors: tuple):
    """The vehicle with its matrices and tires scaled by ``factors`` (``draw``; module docstring)."""
    import dataclasses

    n, w = vehicle.n_dof, len(vehicle.wheels)  # a fleet's factors are drawn for its largest vehicle: the first n
    fm, fk, fc, fkt, fct = (np.asarray(f, float)[:k] for f, k in zip(factors, (n, n, n, w, w)))

    def congruence(a: NDArray, f: NDArray) -> NDArray:
        s = np.sqrt(f)
        return a * s[:, None] * s[None, :]

    wheels = tuple(dataclasses.replace(w, stiffness=w.stiffness * a, damping=w.damping * b)
                   for w, a, b in zip(vehicle.wheels, fkt, fct))
    return dataclasses.replace(vehicle, mass=congruence(vehicle.mass, fm), stiffness=congruence(vehicle.stiffness, fk),
                               damping=congruence(vehicle.damping, fc), gravity=vehicle.gravity * fm, wheels=wheels)
