"""The TOML scenario schema (pydantic), validated before any computation.

Key names are a stable interface; see ``docs/scenario.md`` for the reference.  Every
section rejects unknown keys, every number is checked against its physical range, and
:func:`load_scenario` turns any problem into one :class:`ScenarioError` that names the key
and the allowed values.
"""
from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Annotated, Any, Literal, Optional, Union, get_args

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    PrivateAttr,
    ValidationError,
    field_validator,
    model_validator,
)

from vbikit._toml import parse_toml, read_toml
from vbikit.bridge.base import DEFAULT_DAMPING_RATIO
from vbikit.bridge.presets import BRIDGE_PRESETS
from vbikit.solve.builtin_integrators import DEFAULT_INTEGRATOR
from vbikit.solve.integrators import INTEGRATORS, get_integrator, integrator_names
from vbikit.road.psd import ISO_CLASSES, PAPER_CLASSES
from vbikit.vehicle.presets import VEHICLE_PRESETS

ROAD_CLASSES = ("none", *ISO_CLASSES, *PAPER_CLASSES, "psd")


class ScenarioError(ValueError):
    """An invalid scenario; the message names the offending key(s)."""


class _Section(BaseModel):
    # strict: no coercion ("12" or true are not numbers, 1.5 is not an integer); finite numbers only
    model_config = ConfigDict(extra="forbid", populate_by_name=True, strict=True, allow_inf_nan=False)


class DamageSpec(_Section):
    """[[bridge.damage]]: a bending-stiffness loss over a region (vbikit.bridge.damage)."""

    position: float = Field(..., ge=0, description="start of the damaged region [m from the bridge entry]")
    length: float = Field(..., gt=0, description="length of the region [m]")
    severity: float = Field(..., ge=0, lt=1, description="relative loss of EI [-]")
    girder: Optional[int] = Field(None, ge=1, description="girder number (slab-on-girder bridges)")


_POSITIVE_OR_LIST = Union[Annotated[float, Field(gt=0)], list[Annotated[float, Field(gt=0)]]]


class BridgeSpec(_Section):
    """[bridge]: model = "beam" or "continuous-beam" with its properties, or a preset name (properties optional overrides)."""

    model: str = Field("beam", description="\"beam\" (Euler–Bernoulli beam: span, EI, mass_per_length), \"continuous-beam\" (spans, EI, mass_per_length), \"slab-on-girder\" (3D grillage deck from [bridge.deck]), \"modes-file\" (imported modes) or a preset name (`vbikit presets`)")
    span: Optional[float] = Field(None, gt=0, description="model = \"beam\": span length [m]")
    EI: Optional[_POSITIVE_OR_LIST] = Field(None, description="bending stiffness [N m^2] (continuous-beam: one or one per span)")
    mass_per_length: Optional[_POSITIVE_OR_LIST] = Field(None, description="mass per length [kg/m] (continuous-beam: one or one per span)")
    spans: Optional[list[Annotated[float, Field(gt=0)]]] = Field(None, description="continuous-beam: span lengths [m]")
    support_stiffness: Optional[Union[Annotated[float, Field(ge=0, allow_inf_nan=True)], list[Annotated[float, Field(ge=0, allow_inf_nan=True)]]]] = Field(
        None, description="continuous-beam: vertical support springs [N/m], one or one per support (inf = rigid); default rigid")
    rotational_stiffness: Optional[list[Annotated[float, Field(ge=0, allow_inf_nan=True)]]] = Field(
        None, min_length=2, max_length=2, description="continuous-beam: end rotational springs [N m/rad] (entry, exit)")
    elements_per_span: int = Field(40, ge=2, le=1000, description="continuous-beam: Hermite elements per span")
    damage: list[DamageSpec] = Field(default_factory=list, description="[[bridge.damage]] local stiffness losses")
    damping_ratio: float = Field(DEFAULT_DAMPING_RATIO, ge=0, lt=1, description="modal damping ratio, every mode [-]")
    n_modes: int = Field(10, ge=1, le=500, description="retained modes (the lowest n) [-]")
    neutral_axis_depth: Optional[float] = Field(None, gt=0, description="neutral axis to bottom fibre, the strain lever arm; default 0.5 m for a beam, the composite section's for presets [m]")
    modes_file: Optional[str] = Field(None, description="model = \"modes-file\": path of a `vbikit-modes 1` file, relative to the scenario; n_modes, if given, keeps the first modes")
    deck: Optional[dict[str, Any]] = Field(
        None, description="table [bridge.deck]: SlabOnGirderBridge parameters for model = \"slab-on-girder\" (needs at least span) or overrides of a slab-on-girder preset; keys and units in the bridges guide")

    @field_validator("model")
    @classmethod
    def _known_model(cls, v: str) -> str:
        allowed = ("beam", "continuous-beam", "slab-on-girder", "modes-file", *BRIDGE_PRESETS)
        if v not in allowed:
            raise ValueError(f"unknown bridge model {v!r}; allowed: {', '.join(allowed)}")
        return v

    @model_validator(mode="after")
    def _continuous_beam_keys(self) -> "BridgeSpec":
        only = [k for k in ("spans", "support_stiffness", "rotational_stiffness") if getattr(self, k) is not None]
        if "elements_per_span" in self.model_fields_set:
            only.append("elements_per_span")
        if self.model != "continuous-beam" and only:
            raise ValueError(f"{', '.join(only)}: only with model = \"continuous-beam\"")
        if self.model != "continuous-beam" and any(isinstance(getattr(self, k), list) for k in ("EI", "mass_per_length")):
            raise ValueError("EI and mass_per_length per span (lists) need model = \"continuous-beam\"")
        if self.model == "continuous-beam":
            missing = [k for k in ("spans", "EI", "mass_per_length") if getattr(self, k) is None]
            if missing:
                raise ValueError(f"model = \"continuous-beam\" needs {', '.join(missing)} (spans [m], EI [N m^2], mass_per_length [kg/m])")
            if self.span is not None:
                raise ValueError("model = \"continuous-beam\" takes spans (a list), not span")
        if self.damage:
            slab = self.model == "slab-on-girder" or (self.model in BRIDGE_PRESETS and BRIDGE_PRESETS[self.model].kind == "slab-on-girder")
            if not slab and self.model != "continuous-beam":
                raise ValueError("[[bridge.damage]] applies to model = \"continuous-beam\" (one span = a simply supported beam) "
                                 "and to slab-on-girder decks")
            for i, d in enumerate(self.damage):
                if slab and d.girder is None:
                    raise ValueError(f"damage.{i}: a slab-on-girder deck needs girder (the damaged girder's number)")
                if not slab and d.girder is not None:
                    raise ValueError(f"damage.{i}: a beam has no girders; remove girder")
        return self

    @model_validator(mode="after")
    def _beam_needs_properties(self) -> "BridgeSpec":
        if self.model == "continuous-beam":
            return self
        if (self.model == "modes-file") != (self.modes_file is not None):
            raise ValueError("modes_file is needed by, and only allowed with, model = \"modes-file\"")
        slab = self.model == "slab-on-girder" or (self.model in BRIDGE_PRESETS and BRIDGE_PRESETS[self.model].kind == "slab-on-girder")
        if self.deck is not None and not slab:
            raise ValueError(f"[bridge.deck] applies to model = \"slab-on-girder\" and the slab-on-girder presets, not {self.model!r}")
        if self.deck is not None:
            from vbikit.bridge.girder_deck import SCENARIO_PARAMETERS

            unknown = [k for k in self.deck if k not in SCENARIO_PARAMETERS]
            if unknown:
                raise ValueError(f"unknown [bridge.deck] key(s) {', '.join(map(repr, unknown))}; allowed: {', '.join(SCENARIO_PARAMETERS)}")
        if self.model == "slab-on-girder" and (self.deck is None or not {"span", "spans"} & set(self.deck)):
            raise ValueError("model = \"slab-on-girder\" needs [bridge.deck] with at least span [m] or spans (docs/bridges.md)")
        if self.model == "slab-on-girder":
            given = [k for k in ("span", "EI", "mass_per_length", "neutral_axis_depth") if getattr(self, k) is not None]
            if given:
                raise ValueError(f"model = \"slab-on-girder\" takes its parameters from [bridge.deck]; remove {', '.join(given)}")
        elif self.model == "modes-file":
            given = [k for k in ("span", "EI", "mass_per_length", "neutral_axis_depth") if getattr(self, k) is not None]
            if given:
                raise ValueError(f"model = \"modes-file\" takes its data from the file; remove {', '.join(given)}")
        elif self.model == "beam":
            missing = [k for k in ("span", "EI", "mass_per_length") if getattr(self, k) is None]
            if missing:
                raise ValueError(f"model = \"beam\" needs {', '.join(missing)} (span [m], EI [N m^2], mass_per_length [kg/m])")
        else:
            given = [k for k in ("span", "EI", "mass_per_length", "neutral_axis_depth") if getattr(self, k) is not None]
            if given:
                raise ValueError(f"preset {self.model!r} fixes {', '.join(given)}; only damping_ratio and n_modes may be set")
        return self


class VehicleSpec(_Section):
    """[vehicle]: a preset name and that preset's own parameters (SI units)."""

    model_config = ConfigDict(extra="allow")
    model: str = Field(..., description="vehicle preset (`vbikit presets`); the preset's own parameters are further keys of the same table")

    @field_validator("model")
    @classmethod
    def _known_model(cls, v: str) -> str:
        if v not in VEHICLE_PRESETS:
            raise ValueError(f"unknown vehicle model {v!r}; allowed: {', '.join(VEHICLE_PRESETS)}")
        return v

    @model_validator(mode="after")
    def _preset_parameters(self) -> "VehicleSpec":
        preset = VEHICLE_PRESETS[self.model]
        allowed = preset.parameters
        extra = self.model_extra or {}
        for key, value in extra.items():
            if key not in allowed:
                own = [k for k in type(self).model_fields if k != "model"]
                hint = f"allowed: {', '.join([*own, *allowed])}" if own or allowed else "this preset takes no parameters"
                raise ValueError(f"unknown key {key!r} for vehicle {self.model!r}; {hint}")
            _check_parameter(key, value, preset.kind(key))
        missing = [k for k in preset.required if k not in extra]
        if missing:
            raise ValueError(f"vehicle {self.model!r} needs {', '.join(missing)}")
        if preset.required:  # models built from data (axles): build once to check the combination
            try:
                preset.build(**self.parameters)
            except ValueError as err:
                msg = str(err)
                first = msg.split(" ", 1)[0].rstrip(":")
                raise ValueError(f"{first}: {msg[len(first):].lstrip(': ')}" if first in allowed else msg) from None
        return self

    @property
    def parameters(self) -> dict[str, Any]:
        preset = VEHICLE_PRESETS[self.model]
        out: dict[str, Any] = {}
        for k, v in (self.model_extra or {}).items():
            kind = preset.kind(k)
            out[k] = [float(x) for x in v] if kind == "numbers" else list(v) if kind == "names" \
                else int(v) if kind == "integer" else float(v)
        return out


def _is_number(value: Any) -> bool:
    return not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value)


def _check_parameter(key: str, value: Any, kind: str) -> None:
    """Type and sign of one vehicle parameter (the model checks the rest); messages start "key: "."""
    if kind == "numbers":
        if not (isinstance(value, list) and value and all(_is_number(v) and v > 0 for v in value)):
            raise ValueError(f"{key}: must be a list of numbers > 0, got {value!r}")
    elif kind == "names":
        if not (isinstance(value, list) and all(isinstance(v, str) for v in value)):
            raise ValueError(f"{key}: must be a list of names, got {value!r}")
    elif kind == "integer":
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise ValueError(f"{key}: must be an integer >= 0, got {value!r}")
    else:
        if not _is_number(value):
            raise ValueError(f"{key}: must be a number, got {value!r}")
        if value < 0 or (value == 0 and "damping" not in key):
            raise ValueError(f"{key}: must be {'>= 0' if 'damping' in key else '> 0'}, got {value!r}")


class TireSpec(_Section):
    """[tire]: "point", the paper's "multipoint" (Eq. 6), deformable "disk" or "rigid-disk"."""

    model: Literal["point", "multipoint", "disk", "rigid-disk"] = Field(
        "point", description="contact model: single point, the paper's multi-point (Eq. 6), deformable disk (after Yin et al.) or rigid disk (after Chang et al.)")
    n_points: int = Field(6, ge=1, le=100, description="multipoint: contact points per tire, each with k/n and c/n [-]")
    contact_length: float = Field(0.254, gt=0, le=2.0, description="multipoint: patch length, AASHTO's 10 in [m]")
    layout: Literal["ends", "cells"] = Field(
        "ends", description="multipoint: points from −a/2 to a/2 (ends) or at the centres of n equal cells (cells)")
    radius: float = Field(0.5, gt=0.05, le=2.0, description="disk / rigid-disk: tire radius [m]")
    disk_spacing: float = Field(0.01, gt=0, le=0.1, description="disk / rigid-disk: spacing of the radial springs [m]")
    loss_of_contact: bool = Field(True, description="true: tires cannot pull (a contact point in tension carries no force); false: linear springs that may pull")


class VehicleEntry(VehicleSpec):
    """One table of [[vehicles]]: a vehicle (model and its parameters), its tire and its motion.

    It drives in ``direction`` ("+x" or "-x") along ``lateral_offset`` [m] (centreline from
    the deck centreline; default the bridge's), at ``speed`` [m/s] or ``speed_kmh`` when it
    enters (default: the [crossing] speed) with ``acceleration`` [m/s²]; its front axle passes its entry
    support (x = 0 driving +x, x = span driving −x) at ``entry_time`` [s].  ``[vehicles.tire]``
    defaults to the scenario's [tire].
    """

    tire: Optional[TireSpec] = Field(None, description="table [vehicles.tire] with the [tire] keys; default the scenario's [tire]")
    lateral_offset: Optional[float] = Field(None, description="vehicle centreline from the deck centreline, positive left; default the bridge's [m]")
    direction: Literal["+x", "-x"] = Field("+x", description="driving direction")
    speed: Optional[float] = Field(None, gt=0, description="speed when the front axle passes its entry support [m/s]")
    speed_kmh: Optional[float] = Field(None, gt=0, description="speed when the front axle passes its entry support [km/h]")
    acceleration: float = Field(0.0, ge=-10, le=10, description="constant acceleration [m/s^2]")
    entry_time: float = Field(0.0, ge=0, description="time the front axle passes its entry support (x = 0 driving +x, x = span driving −x) [s]")

    @model_validator(mode="after")
    def _at_most_one_speed(self) -> "VehicleEntry":
        if self.speed is not None and self.speed_kmh is not None:
            raise ValueError("give speed [m/s] or speed_kmh [km/h], not both")
        return self

    @property
    def speed_ms(self) -> Optional[float]:
        return None if self.speed is None and self.speed_kmh is None else \
            float(self.speed if self.speed is not None else self.speed_kmh / 3.6)


class DefectSpec(_Section):
    """[[road.defects]]: a deck defect added to the road (vbikit.road.defects)."""

    kind: Literal["depression", "bump", "step", "pothole"] = Field(..., description="defect type; defaults of each kind in `vbikit presets`")
    position: float = Field(0.0, description="start of the defect, from the bridge entry [m]")
    depth: Optional[float] = Field(None, gt=0, le=0.5, description="depression / pothole depth [m]")
    height: Optional[float] = Field(None, ge=-0.5, le=0.5, description="bump height (> 0) or step height (signed) [m]")
    length: Optional[float] = Field(None, gt=0, le=50, description="defect length [m]")
    ramp: Optional[float] = Field(None, gt=0, le=25, description="ramp length of trapezoid/step shapes [m]")
    shape: Optional[Literal["trapezoid", "cosine", "step"]] = Field(None, description="profile of the defect; default the kind's")

    @model_validator(mode="after")
    def _size_key(self) -> "DefectSpec":
        wants = "depth" if self.kind in ("depression", "pothole") else "height"
        other = "height" if wants == "depth" else "depth"
        if getattr(self, other) is not None:
            raise ValueError(f"a {self.kind} takes {wants} [m], not {other}")
        if self.kind == "bump" and self.height is not None and self.height <= 0:
            raise ValueError(f"bump height must be > 0 m, got {self.height}")
        return self


class RoadSpec(_Section):
    """[road]: class letter (ISO 8608 A–H, good/average/poor, none), explicit PSD, or a CSV profile."""

    road_class: str = Field("none", alias="class", description="roughness: none (smooth), ISO 8608 class A…H (geometric mean of the class), good / average / poor (= B / C / D) or psd (explicit phi0, n0, exponent)")
    seed: int = Field(0, ge=0, description="random phases of Eq. 7 (one seed, one road) [-]")
    profile_file: Optional[str] = Field(None, description="measured profile CSV (x, elevation) [m, m], relative to the scenario; instead of class")
    spacing: float = Field(0.01, gt=0, le=1.0, description="profile sample spacing [m]")
    n_min: float = Field(0.01, gt=0, description="lowest wavenumber [cycle/m]")
    n_max: float = Field(4.0, gt=0, description="highest wavenumber [cycle/m]")
    phi0: Optional[float] = Field(None, ge=0, description="class = \"psd\": PSD at n0 [m^3/cycle]")
    n0: float = Field(0.1, gt=0, description="PSD reference wavenumber [cycle/m]")
    exponent: float = Field(2.0, gt=0, description="PSD exponent w in φ(n) = phi0 (n/n0)^−w [-]")
    length: float = Field(1000.0, gt=0, description="minimum profile length (period of the random road) [m]")
    right_coherence: float = Field(1.0, ge=0, le=1, description="random roads: the right wheel line runs on c·r_L + √(1 − c²)·r_I, r_I an independent road of the same PSD; 1 = identical lines (the paper), 0 = independent [-]")
    profile_file_right: Optional[str] = Field(None, description="measured profile of the right wheel line (needs profile_file for the left)")
    defects: list[DefectSpec] = Field(default_factory=list, description="array of tables [[road.defects]]: deck defects added to the road")

    @field_validator("road_class")
    @classmethod
    def _known_class(cls, v: str) -> str:
        key = v if v in ("none", "psd") else PAPER_CLASSES.get(v.lower(), v.upper())
        if key not in ISO_CLASSES and key not in ("none", "psd"):
            raise ValueError(f"unknown road class {v!r}; allowed: {', '.join(ROAD_CLASSES)}")
        return key

    @model_validator(mode="after")
    def _consistent(self) -> "RoadSpec":
        if self.profile_file_right is not None and self.profile_file is None:
            raise ValueError("profile_file_right needs profile_file (the left wheel line)")
        if self.right_coherence < 1.0 and (self.profile_file or self.road_class == "none"):
            raise ValueError("right_coherence applies to random roads only (class A…H or psd; use profile_file_right for measured ones)")
        if self.n_min >= self.n_max:
            raise ValueError(f"n_min ({self.n_min}) must be below n_max ({self.n_max}) [cycle/m]")
        if self.profile_file is not None and self.road_class != "none":
            raise ValueError("give either class or profile_file, not both")
        if self.road_class == "psd" and self.phi0 is None:
            raise ValueError("class = \"psd\" needs phi0 [m^3/cycle] (and optionally n0, exponent)")
        if self.n_max > 0.5 / self.spacing:
            raise ValueError(f"n_max = {self.n_max} cycle/m exceeds the Nyquist wavenumber 1/(2*spacing) = {0.5 / self.spacing}")
        return self


class CrossingSpec(_Section):
    """[crossing]: speed (m/s) or speed_kmh, acceleration, approach, free vibration, dt, integrator."""

    speed: Optional[float] = Field(None, gt=0, description="speed at t = 0 [m/s]")
    speed_kmh: Optional[float] = Field(None, gt=0, description="speed at t = 0 [km/h]")
    acceleration: float = Field(0.0, ge=-10, le=10, description="constant acceleration, negative brakes [m/s^2]")
    approach: float = Field(10.0, ge=0, description="front-axle run-up before the bridge [m]")
    free_vibration: Optional[float] = Field(None, ge=0, description="time simulated after the last axle leaves; default one first-mode period [s]")
    dt: Optional[float] = Field(None, gt=0, description="time step, default automatic; RK4 refuses a step above its stability limit [s]")
    integrator: str = Field(
        DEFAULT_INTEGRATOR, description="the time integrator, one of the registered: " + "; ".join(
            f'"{name}", {integ.description}' for name, integ in INTEGRATORS.items()),
        json_schema_extra=lambda schema: schema.update(enum=list(integrator_names())))
    lateral_offset: Optional[float] = Field(
        None, description="vehicle centreline from the deck centreline, positive left; default the bridge's (0 for a beam; paper bridges 1.95 / 1.4 / 0.45, cypress-bayou 2.0) [m]")

    @field_validator("integrator")
    @classmethod
    def _known_integrator(cls, v: str) -> str:
        try:
            get_integrator(v)
        except ValueError:
            raise ValueError(f"unknown integrator {v!r}; allowed: {', '.join(map(repr, integrator_names()))}") from None
        return v

    @model_validator(mode="after")
    def _one_speed(self) -> "CrossingSpec":
        if self.speed is not None and self.speed_kmh is not None:
            raise ValueError("give exactly one of speed [m/s] or speed_kmh [km/h]")
        return self

    @property
    def speed_ms(self) -> Optional[float]:
        """The speed [m/s] (None if not given: [[vehicles]] with their own speeds)."""
        return None if self.speed is None and self.speed_kmh is None else \
            float(self.speed if self.speed is not None else self.speed_kmh / 3.6)


class ResponseSpec(_Section):
    """[response]: the deck point for histories and impact factors (x default midspan).

    On a slab-on-girder bridge ``girder`` (1-based, Girder 1 at the most negative y) puts the
    point on that girder's line; give ``girder`` or ``y``, not both.  With neither, a
    slab-on-girder bridge reports its default girder (Girder 4 on the paper's bridges).
    """

    x: Optional[float] = Field(None, description="response point along the bridge from the entry support (on a skew deck the support lines are oblique: line y's span starts at x = y·tan(skew)); default midspan (of the first span) [m]")
    y: Optional[float] = Field(None, description="response point from the deck centreline; default the bridge's response line (0 for a beam, the default girder's line on slab-on-girder bridges) [m]")
    girder: Optional[int] = Field(None, ge=1, description="slab-on-girder bridges: respond on this girder's line (Girder 1 at the most negative y; default the bridge's, 4 on the paper bridges); give girder or y, not both [-]")
    moment: Optional[list[float]] = Field(
        None, description="sections x [m] for bending moment (default: every midspan and interior support)")
    shear: Optional[list[float]] = Field(
        None, description="sections x [m] for shear, taken just right of x (default: right of every support but the last)")
    reaction: Optional[list[Annotated[int, Field(ge=0)]]] = Field(None, description="support indices, 0 = entry (default: all)")
    load_effect_method: Literal["mode-acceleration", "mode-superposition"] = Field(
        "mode-acceleration", description="moments, shears and reactions from the mode-acceleration method or plain mode superposition")

    @model_validator(mode="after")
    def _girder_or_y(self) -> "ResponseSpec":
        if self.girder is not None and "y" in self.model_fields_set:
            raise ValueError("give response.girder or response.y, not both")
        return self


class Scenario(_Section):
    """A whole scenario file."""

    bridge: BridgeSpec
    vehicle: Optional[VehicleSpec] = None
    vehicles: Optional[list[VehicleEntry]] = Field(None, description="[[vehicles]]: several vehicles with their own motion")
    tire: TireSpec = TireSpec()
    road: RoadSpec = RoadSpec()
    crossing: CrossingSpec
    response: ResponseSpec = ResponseSpec()
    name: str = Field("", description="label printed in reports")

    #: directory relative paths (road.profile_file) are resolved against
    _base_dir: Path = PrivateAttr(default=Path("."))

    @model_validator(mode="after")
    def _vehicle_or_vehicles(self) -> "Scenario":
        if self.vehicle is None and self.vehicles is None:
            raise ValueError("vehicle: missing required key (a [vehicle] table, or [[vehicles]] tables for several vehicles)")
        if self.vehicle is not None and self.vehicles is not None:
            raise ValueError("give one [vehicle] table or an array of [[vehicles]] tables, not both")
        c = self.crossing
        if self.vehicle is not None:
            if c.speed_ms is None:
                raise ValueError("crossing: give exactly one of speed [m/s] or speed_kmh [km/h]")
            return self
        if not self.vehicles:
            raise ValueError("vehicles: the array of [[vehicles]] tables is empty")
        given = [k for k in ("lateral_offset", "acceleration") if k in c.model_fields_set]
        if given:
            raise ValueError(f"crossing.{given[0]}: with [[vehicles]] give it per vehicle (vehicles[i].{given[0]})")
        for i, v in enumerate(self.vehicles):
            if v.speed_ms is None and c.speed_ms is None:
                raise ValueError(f"vehicles[{i + 1}].speed: give speed [m/s] or speed_kmh [km/h] (or crossing.speed for every vehicle)")
        return self

    @property
    def is_multi_vehicle(self) -> bool:
        return self.vehicles is not None

    @property
    def base_dir(self) -> Path:
        return self._base_dir


def key_unit(key: str) -> str:
    """Unit of the scenario key ``"section.key"`` as written in its description (``"km/h"`` for
    ``crossing.speed_kmh``, ``"m"`` for ``tire.contact_length``; ``"-"`` for dimensionless numbers,
    ``""`` for text and unknown keys; ``bridge.deck.*`` keys from the deck model's parameters)."""
    model: Any = Scenario
    *sections, name = key.split(".")
    if sections == ["bridge", "deck"]:
        from vbikit.bridge.girder_deck import deck_parameter_docs

        return deck_parameter_docs().get(name, ("", ""))[1]
    for part in sections:
        field = model.model_fields.get(part)
        model = field.annotation if field is not None else None
        if not (isinstance(model, type) and issubclass(model, BaseModel)):
            return ""
    field = next((f for n, f in model.model_fields.items() if name in (n, f.alias)), None)
    if field is None:
        return ""
    m = re.search(r"\[([^\[\]]+)\]\s*$", field.description or "")
    return m.group(1) if m else ""


def _model_at(path: tuple[Any, ...]) -> type[BaseModel] | None:
    """The section model that holds the key at ``path`` (walks fields, list items and Optionals)."""
    model: Any = Scenario
    for part in path:
        if isinstance(part, int):
            continue
        if not (isinstance(model, type) and issubclass(model, BaseModel)):
            return None
        field = next((f for n, f in model.model_fields.items() if part in (n, f.alias)), None)
        if field is None:
            return None
        model = field.annotation
        while get_args(model) and not (isinstance(model, type) and issubclass(model, BaseModel)):
            model = next((a for a in get_args(model) if a is not type(None)), None)
    return model if isinstance(model, type) and issubclass(model, BaseModel) else None


def error_path(loc: tuple[Any, ...] | list[Any]) -> str:
    """A key's location as users read it: ``road.defects[1].depth`` for the first
    ``[[road.defects]]`` table (arrays of tables counted from 1, in scenario, study and field files)."""
    out = ""
    for part in loc:
        if part == "__root__":
            continue
        out += f"[{part + 1}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def _format(err: ValidationError, data: dict[str, Any]) -> str:
    lines = []
    for e in err.errors():
        loc = error_path(e["loc"])
        msg = e["msg"].removeprefix("Value error, ")
        if e["type"] == "extra_forbidden":
            model = _model_at(tuple(e["loc"][:-1]))
            names = [f.alias or n for n, f in model.model_fields.items()] if model else []
            msg = f"unknown key; allowed keys: {', '.join(names)}"
        elif e["type"] == "missing":
            msg = "missing required key"
        elif "input" in e and e["type"] not in ("value_error",):
            msg = f"{msg} (got {e['input']!r})"
        key = re.match(r"^([a-z_]+): ", msg) if loc and e["type"] == "value_error" else None
        if key:  # a section's validator named one of its keys: "loc.key: …"
            loc, msg = f"{loc}.{key.group(1)}", msg[key.end():]
        lines.append(f"{loc}: {msg}" if loc else msg)
    return "invalid scenario:\n  " + "\n  ".join(lines)


def parse_scenario(data: dict[str, Any], base_dir: Path | str = ".") -> Scenario:
    """Validate a scenario given as a dict (the parsed TOML)."""
    try:
        scenario = Scenario.model_validate(data)
    except ValidationError as err:
        raise ScenarioError(_format(err, data)) from None
    scenario._base_dir = Path(base_dir)
    return scenario


def scenario_from_toml(text: str, base_dir: Path | str = ".", source: str = "scenario") -> Scenario:
    """Validate a scenario given as TOML text."""
    return parse_scenario(parse_toml(text, source, ScenarioError), base_dir)


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a TOML scenario file."""
    return parse_scenario(read_toml(path, ScenarioError, "scenario file"), Path(path).parent)


def demo_scenario_text() -> str:
    """The TOML text of the demo scenario shipped with the package."""
    from importlib import resources

    return resources.files("vbikit.scenario").joinpath("demo.toml").read_text()
