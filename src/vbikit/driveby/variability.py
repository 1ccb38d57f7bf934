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

Draws.  Pass (case) ``i`` of a file with seed ``s`` draws from
``numpy.random.default_rng(numpy.random.SeedSequence(s, spawn_key=(i,)))`` — the i-th child that
``SeedSequence(s).spawn`` would give — so a pass's draw depends only on (s, i): the same in any
order, in any batch, on any worker.  The draw order within a pass is fixed: speed, temperature,
vehicle factors (masses, stiffnesses, dampings, tire stiffnesses, tire dampings).

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
from typing import Any, Optional

import numpy as np
from numpy.typing import NDArray

from vbikit.errors import VbikitError

#: keys of [variability]
VARIABILITY_KEYS = ("passes", "speed", "vehicle_spread", "support_stiffness", "scour_classes", "temperature",
                    "temperature_reference", "temperature_coefficient", "traffic_flow", "traffic_speed_kmh",
                    "traffic_direction")
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
        traffic_direction=_direction(t.get("traffic_direction", "-x")))


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


def draw(var: Variability, seed: int, index: int, n_dof: int, n_wheels: int) -> dict[str, Any]:
    """The random parameters of pass ``index``: ``speed`` [m/s] and ``temperature`` [°C] (absent
    when not varied), ``vehicle_factors`` (5 arrays: per-DOF mass, stiffness, damping factors,
    per-wheel tire stiffness and damping factors; absent without a spread) and ``traffic_seed``
    (the seed of the pass's background trucks, ``vbikit.driveby.traffic``; absent without
    ``traffic_flow``), drawn in this order (a new key draws last: earlier draws keep their values)."""
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
    return out


def expand_cases(cases: tuple, var: Variability) -> tuple:
    """The sweep's combinations × scour classes × passes (the pass index varies fastest); each case
    carries its ``index`` (the key of its draw), its ``pass`` and its ``scour_class``."""
    if not var.active:
        return cases
    classes = range(len(var.scour_classes)) if var.scour_classes else [None]
    out = []
    for combo in cases or ({},):
        for k in classes:
            for p in range(var.passes):
                out.append({**combo, **({} if k is None else {"scour_class": k}), "pass": p, "index": len(out)})
    return tuple(out)


def perturbed_vehicle(vehicle, factors: tuple):
    """The vehicle with its matrices and tires scaled by ``factors`` (``draw``; module docstring)."""
    import dataclasses

    fm, fk, fc, fkt, fct = (np.asarray(f, float) for f in factors)

    def congruence(a: NDArray, f: NDArray) -> NDArray:
        s = np.sqrt(f)
        return a * s[:, None] * s[None, :]

    wheels = tuple(dataclasses.replace(w, stiffness=w.stiffness * a, damping=w.damping * b)
                   for w, a, b in zip(vehicle.wheels, fkt, fct))
    return dataclasses.replace(vehicle, mass=congruence(vehicle.mass, fm), stiffness=congruence(vehicle.stiffness, fk),
                               damping=congruence(vehicle.damping, fc), gravity=vehicle.gravity * fm, wheels=wheels)
