"""The TOML scenario schema (pydantic), validated before any computation.

Key names are a stable interface; see ``docs/scenario.md`` for the reference.  Every
section rejects unknown keys, every number is checked against its physical range, and
[`load_scenario`][vbikit.scenario.load_scenario] turns any problem into one [`ScenarioError`][vbikit.scenario.ScenarioError] that names the key
and the allowed values.
"""
from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Annotated, Any, Literal, Optional, get_args

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    PrivateAttr,
    Tag,
    TypeAdapter,
    ValidationError,
    field_validator,
    model_validator,
)

from vbikit._limits import MAX_LATERAL_OFFSET, MAX_RUN_IN, MAX_SPEED, MIN_SPEED  # (the limits every input shares)
from vbikit.analysis.plan import point_name
from vbikit.scenario.bridge_spec import BridgeKind, BridgeSpec
from vbikit.scenario.section import ScenarioError, Section
from vbikit._files import read_text
from vbikit._kept import Kept
from vbikit._toml import parse_toml
from vbikit._validation import bound_message, key_name, short_quotes, short_value
from vbikit.contact.registry import TIRE_MODELS, tire_model, tire_parameters
from vbikit.contact.tires import TireParameters
from vbikit.solve.budget import MAX_AXLES
from vbikit.solve.crossing import RESOLVES
from vbikit.solve.integrators import DEFAULT_INTEGRATOR, INTEGRATORS, get_integrator, integrator_names
from vbikit.road.psd import ISO_CLASSES, PAPER_CLASSES
from vbikit.vehicle.presets import VEHICLE_PRESETS

ROAD_CLASSES = ("none", *ISO_CLASSES, *PAPER_CLASSES, "psd")
#: latest entry time of a listed vehicle [s]
MAX_ENTRY_TIME = 3600.0


def parse_bridge(table: dict[str, Any]) -> BridgeKind:
    """Validate a [bridge] table alone (raises ScenarioError naming ``bridge.<key>``)."""
    try:
        return TypeAdapter(BridgeSpec).validate_python(table)
    except ValidationError as err:
        raise ScenarioError(_format(err, {"bridge": table}, ("bridge",)).removeprefix("invalid scenario:\n  ")) from None


class VehicleSpec(Section):
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
        axles = extra.get("axle_loads")
        if isinstance(axles, list) and len(axles) > MAX_AXLES:
            return self  # above the axle budget: refused (or, with a raised budget, built) by the build step
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


#: largest value [unit] of a vehicle preset's number parameter, by the quantity its name ends with (far above
#: any road vehicle: a 1000 t mass, a 10 MN force)
VEHICLE_PARAMETER_LIMITS: dict[str, tuple[float, str]] = {
    "mass": (1e6, "kg"), "force": (1e7, "N"), "stiffness": (1e12, "N/m"), "damping": (1e9, "N s/m"),
}


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
        limit = VEHICLE_PARAMETER_LIMITS.get(key.rsplit("_", 1)[-1])
        if limit is not None and value > limit[0]:
            raise ValueError(f"{key}: must be <= {limit[0]:g} {limit[1]}, got {value!r}")


class TireSpec(Section):
    """[tire]: a tire model by name and that model's own parameters (`vbikit presets`).

    ``model`` is a registered tire model ([`vbikit.contact.TIRE_MODELS`][vbikit.contact.registry.TIRE_MODELS]: "point", the
    paper's "multipoint" (Eq. 6), deformable "disk", "rigid-disk"); the further keys of the
    table are that model's parameters, checked by its ``Parameters`` (unknown keys, including
    another model's parameters, are refused).  ``loss_of_contact`` applies to every model.
    """

    model_config = ConfigDict(extra="allow")
    model: str = Field(
        "point", description="contact model: single point, the paper's multi-point (Eq. 6), deformable disk (after Yin et al.) "
                             "or rigid disk (after Chang et al.); its parameters are further keys of the same table")
    loss_of_contact: bool = Field(True, description="true: tires cannot pull (a contact point in tension carries no force); false: linear springs that may pull")

    @field_validator("model")
    @classmethod
    def _known_model(cls, v: str) -> str:
        tire_model(v)  # ValueError listing the registered names
        return v

    @model_validator(mode="after")
    def _model_parameters(self) -> "TireSpec":
        tire_parameters(self.model, self.model_extra or {}, common=list(type(self).model_fields))  # errors name tire.<key>
        return self

    @classmethod
    def key_field(cls, key: str, table: dict[str, Any]) -> Any:
        """The field of ``key``: the section's own, or a parameter of the table's tire model."""
        own = super().key_field(key, table)
        if own is not None or table.get("model") not in TIRE_MODELS:
            return own
        return tire_model(table["model"]).Parameters.model_fields.get(key)

    @classmethod
    def keys(cls, model: str | None = None) -> list[str]:
        """The keys of a [tire] table: ``model``, ``loss_of_contact`` and the parameters of tire
        model ``model`` (of every registered model if None)."""
        models = TIRE_MODELS.values() if model is None else [tire_model(model)]
        params = [k for m in models for k in m.Parameters.model_fields]
        return [*cls.model_fields, *dict.fromkeys(params)]

    @property
    def parameters(self) -> TireParameters:
        """The model's parameters, validated, with the defaults of the keys not given."""
        return tire_parameters(self.model, self.model_extra or {})

    def model_copy(self, *, update: dict[str, Any] | None = None, deep: bool = False) -> "TireSpec":
        """A copy; with ``update`` validated again.  A new ``model`` keeps the given parameters
        it also takes (a disk's radius for a rigid disk) and drops the others."""
        if not update:
            return super().model_copy(deep=deep)
        data = self.model_dump(exclude_unset=True)
        model = update.get("model", self.model)
        if model != self.model and model in TIRE_MODELS:
            allowed = self.keys(model)
            data = {k: v for k, v in data.items() if k in allowed}
        return type(self).model_validate({**data, **update})


class VehicleEntry(VehicleSpec):
    """One table of [[vehicles]]: a vehicle (model and its parameters), its tire and its motion.

    It drives in ``direction`` ("+x" or "-x") along ``lateral_offset`` [m] (centreline from
    the deck centreline; default the bridge's), at ``speed`` [m/s] or ``speed_kmh`` when it
    enters (default: the [crossing] speed) with ``acceleration`` [m/s²]; its front axle passes its entry
    support (x = 0 driving +x, x = span driving −x) at ``entry_time`` [s].  ``[vehicles.tire]``
    defaults to the scenario's [tire].
    """

    tire: Optional[TireSpec] = Field(None, description="table [vehicles.tire] with the [tire] keys; default the scenario's [tire]")
    lateral_offset: Optional[float] = Field(None, ge=-MAX_LATERAL_OFFSET, le=MAX_LATERAL_OFFSET,
                                            description="vehicle centreline from the deck centreline, positive left; default the bridge's [m]")
    direction: Literal["+x", "-x"] = Field("+x", description="driving direction")
    speed: Optional[float] = Field(None, ge=MIN_SPEED, le=MAX_SPEED, description="speed when the front axle passes its entry support [m/s]")
    speed_kmh: Optional[float] = Field(None, ge=round(MIN_SPEED * 3.6, 12), le=MAX_SPEED * 3.6, description="speed when the front axle passes its entry support [km/h]")
    acceleration: float = Field(0.0, ge=-10, le=10, description="constant acceleration [m/s^2]")
    entry_time: float = Field(0.0, ge=0, le=MAX_ENTRY_TIME, description="time the front axle passes its entry support (x = 0 driving +x, x = span driving −x) [s]")

    @model_validator(mode="after")
    def _at_most_one_speed(self) -> "VehicleEntry":
        if self.speed is not None and self.speed_kmh is not None:
            raise ValueError("give speed [m/s] or speed_kmh [km/h], not both")
        return self

    @property
    def speed_ms(self) -> Optional[float]:
        return None if self.speed is None and self.speed_kmh is None else \
            float(self.speed if self.speed is not None else self.speed_kmh / 3.6)


class DefectSpec(Section):
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


class RoadSpec(Section):
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


class CrossingSpec(Section):
    """[crossing]: speed (m/s) or speed_kmh, acceleration, approach, free vibration, dt, integrator."""

    speed: Optional[float] = Field(None, ge=MIN_SPEED, le=MAX_SPEED, description="speed at t = 0 [m/s]")
    speed_kmh: Optional[float] = Field(None, ge=round(MIN_SPEED * 3.6, 12), le=MAX_SPEED * 3.6, description="speed at t = 0 [km/h]")
    acceleration: float = Field(0.0, ge=-10, le=10, description="constant acceleration, negative brakes [m/s^2]")
    approach: float = Field(10.0, ge=0, description="front-axle run-up before the bridge [m]")
    run_in: float = Field(0.0, ge=0, le=MAX_RUN_IN, description="road the vehicles drive alone before the run starts, from rest, "
                          "so that they enter the approach settled (vbikit.solve.run_in) [m]; 0: they start at rest")
    free_vibration: Optional[float] = Field(None, ge=0, description="time simulated after the last axle leaves; default one first-mode period [s]")
    dt: Optional[float] = Field(None, gt=0, description="time step, default automatic; RK4 refuses a step above its stability limit [s]")
    integrator: str = Field(
        DEFAULT_INTEGRATOR, description="the time integrator, one of the registered: " + "; ".join(
            f'"{name}", {integ.description}' for name, integ in INTEGRATORS.items()),
        json_schema_extra=lambda schema: schema.update(enum=list(integrator_names())))
    lateral_offset: Optional[float] = Field(
        None, ge=-MAX_LATERAL_OFFSET, le=MAX_LATERAL_OFFSET, description="vehicle centreline from the deck centreline, positive left; default the bridge's (0 for a beam; paper bridges 1.95 / 1.4 / 0.45, cypress-bayou 2.0) [m]")
    resolve: Literal[RESOLVES] = Field(  # type: ignore[valid-type]
        "effects", description='what the automatic step must resolve: "effects" (every result: deflections, '
        'accelerations, strains, moments, shears, reactions) or "deflections" (deflections and tire forces only: the exact '
        'integrator takes 50 steps per first bridge period instead of 100 with the wheel loads held quadratic, and the '
        'report flags the other results); a study whose outputs are all deflections sets it')

    @classmethod
    def missing_note(cls) -> str:
        return ("it needs the speed, speed [m/s] or speed_kmh [km/h], for a [vehicle]; with [[vehicles]] that each "
                "give their own speed an empty [crossing] table will do; its other keys (all optional): "
                + ", ".join(k for k in cls.allowed_keys({}) if k not in ("speed", "speed_kmh")))

    @field_validator("integrator")
    @classmethod
    def _known_integrator(cls, v: str) -> str:
        same = [name for name in integrator_names() if name.lower() == v.lower()]
        v = v if v in integrator_names() or len(same) != 1 else same[0]  # (any letter case, as road.class)
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


class ResponsePointSpec(Section):
    """[[response.points]]: one response point (x default midspan; girder or y, not both)."""

    name: str = Field("", pattern=r"^([A-Za-z][A-Za-z0-9_]*)?$", max_length=40,
                      description="label in reports, CSV columns (displacement_<name>) and datasets; letters, digits and _, starting with a letter; default p1, p2, … by position")
    x: Optional[float] = Field(None, description="along the bridge from the entry support; default midspan (of the first span) [m]")
    y: Optional[float] = Field(None, description="from the deck centreline; default the bridge's response line [m]")
    girder: Optional[int] = Field(None, ge=1, description="slab-on-girder bridges: on this girder's line; give girder or y, not both [-]")

    @model_validator(mode="after")
    def _girder_or_y(self) -> "ResponsePointSpec":
        if self.girder is not None and "y" in self.model_fields_set:
            raise ValueError("give girder or y, not both")
        return self


class ResponseSpec(Section):
    """[response]: the deck point for histories and impact factors (x default midspan).

    On a slab-on-girder bridge ``girder`` (1-based, Girder 1 at the most negative y) puts the
    point on that girder's line; give ``girder`` or ``y``, not both.  With neither, a
    slab-on-girder bridge reports its default girder (Girder 4 on the paper's bridges).
    Several points: ``[[response.points]]`` tables instead of ``x`` / ``y`` / ``girder``; the
    first is the headline point (the summary's top-level keys).
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
    points: Optional[list[ResponsePointSpec]] = Field(
        None, min_length=1, max_length=1000, description="[[response.points]]: several response points (x, y or girder, name), the first the headline point")

    @model_validator(mode="after")
    def _girder_or_y(self) -> "ResponseSpec":
        if self.girder is not None and "y" in self.model_fields_set:
            raise ValueError("give response.girder or response.y, not both")
        if self.points is not None:
            given = [k for k in ("x", "y", "girder") if k in self.model_fields_set]
            if given:
                raise ValueError(f"{given[0]}: give the point in [response] or in [[response.points]] tables, not both")
            names = [point_name(i, p.name) for i, p in enumerate(self.points, start=1)]
            dup = sorted({n for n in names if names.count(n) > 1})
            if dup:
                raise ValueError(f"points: names must be unique; repeated: {', '.join(dup)}")
        return self

    @property
    def point_specs(self) -> list["ResponsePointSpec"]:
        """The response points: the [[response.points]] tables, or the [response] point alone."""
        if self.points is not None:
            return list(self.points)
        return [ResponsePointSpec.model_construct(name="", x=self.x, y=self.y, girder=self.girder,
                                                  _fields_set={k for k in ("x", "y", "girder") if k in self.model_fields_set})]


#: a scenario without [vehicle] or [[vehicles]] (``Scenario``, and ``_format`` with the other errors)
VEHICLE_MISSING = "vehicle: missing required key (a [vehicle] table, or [[vehicles]] tables for several vehicles)"


class Scenario(Section):
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
            raise ValueError(VEHICLE_MISSING)
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

    def input_files(self) -> list[Path]:
        """The files the scenario reads besides itself — the measured road profiles
        (``road.profile_file``, ``road.profile_file_right``) and a bridge's ``modes_file`` — resolved
        against its folder (as the builders read them), in that order (``INPUT_FILE_KEYS``)."""
        names = (self.road.profile_file, self.road.profile_file_right, getattr(self.bridge, "modes_file", None))
        return [self.base_dir / name for name in names if name]


#: the scenario keys naming a file the scenario reads besides itself, relative to its folder
#: (``Scenario.input_files``, ``input_paths``)
INPUT_FILE_KEYS = ("road.profile_file", "road.profile_file_right", "bridge.modes_file")


def input_paths(data: dict[str, Any], base_dir: Path | str = ".") -> dict[str, Path]:
    """Each ``INPUT_FILE_KEYS`` a scenario's tables ``data`` give (a dict, not validated), by key, resolved
    against ``base_dir`` as the builders read them (an absolute path as it is)."""
    out = {}
    for key in INPUT_FILE_KEYS:
        section, name = key.split(".")
        table = data.get(section)
        value = table.get(name) if isinstance(table, dict) else None
        if isinstance(value, str) and value:
            out[key] = Path(base_dir) / value
    return out


def _tags(annotation: Any) -> dict[str, type[BaseModel]]:
    """tag → section model of a discriminated union of sections (empty for any other annotation)."""
    out = {}
    for arg in get_args(annotation):
        inner = get_args(arg)
        tag = next((m.tag for m in inner[1:] if isinstance(m, Tag)), None)
        if tag is not None and isinstance(inner[0], type) and issubclass(inner[0], BaseModel):
            out[tag] = inner[0]
    return out


def _section(annotation: Any) -> type[BaseModel] | dict[str, type[BaseModel]] | None:
    """The section model of a field's annotation (through Optional and lists), the tagged models
    of a union of sections, or None for a plain value."""
    while True:
        if isinstance(annotation, type) and issubclass(annotation, BaseModel):
            return annotation
        tags = _tags(annotation)
        if tags:
            return tags
        args = [a for a in get_args(annotation) if a is not type(None)]
        if not args:
            return None
        annotation = args[0]


def _field(model: type[BaseModel], name: str) -> Any:
    return next((f for n, f in model.model_fields.items() if name in (n, f.alias)), None)


def section_models(section: str) -> list[type[BaseModel]]:
    """The models of the scenario section ``section`` ("bridge": one per kind), [] for a plain key."""
    field = Scenario.model_fields.get(section)
    found = _section(field.annotation) if field is not None else None
    return [] if found is None else list(found.values()) if isinstance(found, dict) else [found]


def section_keys(section: str) -> list[str]:
    """Every key of the scenario section ``section`` (of any of its kinds; [tire]: of every
    registered tire model), in schema order."""
    if section == "tire":
        return TireSpec.keys()
    keys: list[str] = []
    for model in section_models(section):
        keys += [k for k in model.allowed_keys({}) if k not in keys]  # type: ignore[attr-defined]
    return keys


def key_unit(key: str) -> str:
    """Unit of the scenario key ``"section.key"`` as written in its description (``"km/h"`` for
    ``crossing.speed_kmh``, ``"m"`` for ``tire.contact_length``; ``"-"`` for dimensionless numbers,
    ``""`` for text and unknown keys; ``bridge.deck.*`` keys from the deck model's parameters)."""
    *sections, name = key.split(".")
    if sections == ["bridge", "deck"]:
        from vbikit.scenario.deck import deck_parameter_docs

        return deck_parameter_docs().get(name, ("", ""))[1]
    models: list[type[BaseModel]] = [Scenario]
    for part in sections:
        found = [_section(f.annotation) for m in models if (f := _field(m, part)) is not None]
        models = [m for s in found for m in (s.values() if isinstance(s, dict) else [s] if s else [])]
    field = next((f for m in models if (f := _field(m, name)) is not None), None)
    if field is None and TireSpec in models:  # a tire model's own parameter
        field = next((f for cls in TIRE_MODELS.values() for n, f in cls.Parameters.model_fields.items()
                      if name in (n, f.alias)), None)
    if field is None:
        return ""
    m = re.search(r"\[([^\[\]]+)\]\s*$", field.description or "")
    return m.group(1) if m else ""


def _walk(loc: tuple[Any, ...]) -> tuple[tuple[Any, ...], type[BaseModel] | None]:
    """``loc`` without the tags of discriminated unions (``bridge.beam.span`` → ``bridge.span``),
    and the section model at its end (None for a plain key)."""
    model: Any = Scenario
    out: list[Any] = []
    for part in loc:
        if isinstance(part, int):
            out.append(part)
        elif isinstance(model, dict) and part in model:
            model = model[part]
        else:
            out.append(part)
            field = _field(model, part) if isinstance(model, type) and issubclass(model, BaseModel) else None
            model = _section(field.annotation) if field is not None else None
    return tuple(out), model if isinstance(model, type) and issubclass(model, BaseModel) else None


def _model_at(path: tuple[Any, ...]) -> type[BaseModel] | None:
    """The section model that holds the key at ``path`` (walks fields, list items, Optionals and
    the kinds of a discriminated union)."""
    return _walk(path)[1]


def _table_at(data: Any, path: tuple[Any, ...]) -> dict[str, Any]:
    """The table at ``path`` (tags removed) of the parsed TOML ``data``, {} when there is none."""
    for part in path:
        try:
            data = data[part]
        except (KeyError, IndexError, TypeError):
            return {}
    return data if isinstance(data, dict) else {}


#: the names pydantic gives the members of a union (``EI = 1`` or ``EI = [1, 2]``) in an error's location
_UNION_MEMBER = re.compile(r"^(list\[)?(constrained-[a-z]+|float|int)\]?$")


def error_path(loc: tuple[Any, ...] | list[Any]) -> str:
    """A key's location as users read it: ``road.defects[1].depth`` for the first
    ``[[road.defects]]`` table (arrays of tables counted from 1, in scenario, study and field files)."""
    return key_name(tuple(p for p in loc if not (isinstance(p, str) and _UNION_MEMBER.match(p))))


def _key_field(loc: tuple[Any, ...], data: dict[str, Any]) -> Any:
    """The pydantic field of the key at ``loc`` (a list item: its list's field; a tire parameter:
    its tire model's, ``Section.key_field``), None if unknown."""
    names = [p for p in loc if isinstance(p, str) and not _UNION_MEMBER.match(p)]
    if not names:
        return None
    at = len(loc) - 1 - loc[::-1].index(names[-1])
    path, holder = _walk(loc[:at])
    if holder is None:
        return None
    lookup = getattr(holder, "key_field", None)
    return lookup(names[-1], _table_at(data, path)) if lookup is not None else _field(holder, names[-1])


def _format(err: ValidationError, data: dict[str, Any], prefix: tuple[Any, ...] = ()) -> str:
    """The errors of a scenario validation, one line each, naming the key (``prefix``: the
    location of the validated part when it is not the whole scenario)."""
    lines = []
    for e in err.errors():
        path, model = _walk(prefix + tuple(e["loc"][:-1]))
        clean = _walk(prefix + tuple(e["loc"]))[0]
        loc = error_path(clean)
        msg = short_quotes(e["msg"].removeprefix("Value error, "))
        if e["type"] == "extra_forbidden":
            table = _table_at(data, path)
            names = model.allowed_keys(table) if model else []  # type: ignore[attr-defined]
            note = model.unknown_key_note(str(e["loc"][-1]), table) if model else ""  # type: ignore[attr-defined]
            msg = f"unknown key; allowed keys: {', '.join(names)}{f' ({note})' if note else ''}"
        elif e["type"] == "missing":
            table = _walk(prefix + tuple(e["loc"]))[1]  # a whole table missing: name it and what it takes
            msg = "missing required key" if table is None or not issubclass(table, Section) else \
                f"missing required table [{loc}]; {table.missing_note()}"
        elif bound_message(e) is not None:  # the range with both bounds and the unit
            msg = bound_message(e, _key_field(prefix + tuple(e["loc"]), data))
        elif "input" in e and e["type"] not in ("value_error",):
            msg = f"{msg} (got {short_value(e['input'])})"
        key = re.match(r"^([a-z_]+): ", msg) if loc and e["type"] == "value_error" else None
        if key:  # a section's validator named one of its keys: "loc.key: …"
            loc, msg = f"{loc}.{key.group(1)}", msg[key.end():]
        lines.append(f"{loc}: {msg}" if loc else msg)
    if not prefix and isinstance(data, dict) and "vehicle" not in data and "vehicles" not in data \
            and not any(line.startswith("vehicle") for line in lines):
        # (the scenario's own check of its vehicles runs only once its tables are valid: say it with the others)
        lines.append(VEHICLE_MISSING)
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


#: scenarios validated from files, per (file name, text), newest last (``load_scenario``)
_LOADED: "Kept[tuple[str, str], Scenario]" = Kept(8)


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a TOML scenario file.  The file is read every time; the same name with the
    same text again is not parsed and validated again (the scenario kept for the last 8 is copied:
    the caller owns the returned object)."""
    text = read_text(path, ScenarioError, "scenario file")
    kept = _LOADED.get((str(path), text), lambda: parse_scenario(parse_toml(text, str(path), ScenarioError),
                                                                 Path(path).parent))
    return kept.model_copy(deep=True)


def demo_scenario_text() -> str:
    """The TOML text of the demo scenario shipped with the package."""
    from importlib import resources

    return resources.files("vbikit.scenario").joinpath("demo.toml").read_text()
