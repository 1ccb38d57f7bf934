"""The lifetime specification (TOML), validated before any computation.

A lifetime file::

    name = "two-lane 20 m bridge"
    seed = 2026
    days = 7                      # simulated duration: days = N, or years = N (× days_per_year)
    days_per_year = 365           # simulated days in a year (blocks per year of daily maxima)
    amplification = 0.5           # A: upper bound of R_dyn / R_st − 1 used by the screening
    return_periods = [75, 100, 1000]
    characteristic_period = 1000  # years: the characteristic value (Eurocode 1,000 years, AASHTO 75)
    block = "day"                 # block maxima fitted: day or week
    distribution = "gumbel"       # gev or gumbel
    budget_hours = 2.0            # estimated run time above this is refused

    [traffic]
    records = "wim.csv"           # records file (vbikit.traffic format), relative to this file
    mode = "fitted"               # or "bootstrap"
    # trucks_per_day = 4000       # scale the fitted flows to this total
    # lanes = [-1.8, 1.8]         # lane centres y [m] (default: the bridge's)

    [bridge] / [tire] / [road] / [crossing]   # the base scenario's sections (or base = "bridge.toml")

    [[load_effects]]
    kind = "moment"               # deflection, moment, shear, reaction
    x = 10.0                      # section [m] (reaction: support = 0, 1, …)
    name = "M_mid"

    [fatigue]
    dynamic_sample = 0.05         # fraction of events simulated dynamically for the damage ratio
    [[fatigue.details]]
    name = "flange"
    effect = "M_mid"              # a load effect above
    section_modulus = 0.012       # stress = effect / section_modulus [m³] (or stress_per_unit [Pa per unit])
    category = "EN 71"            # an EN 1993-1-9 detail category [MPa] (160, 140, … 36) or "AASHTO C'" …

Errors name the key and the allowed range (``LifetimeError``).
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated, Any, Literal, Optional

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from vbikit._validation import validation_message
from vbikit.errors import VbikitError

BASE_SECTIONS = ("bridge", "tire", "road", "crossing")
#: a run whose estimate exceeds this [h] is refused unless budget_hours is raised
DEFAULT_BUDGET_HOURS = 2.0
#: the largest budget_hours (and ``vbikit lifetime --budget-hours``)
MAX_BUDGET_HOURS = 1e4
MAX_DAYS = 365 * 200
#: the closest section to the entry support other than x = 0 [m]
MIN_SECTION = 1e-3


class LifetimeError(VbikitError):
    """An invalid lifetime specification or run; the message names the key."""

    message_names_key = True


class _Strict(BaseModel):
    """Strict types (no booleans or strings for numbers), finite numbers, no unknown keys."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False)


class TrafficSpec(_Strict):
    records: str = Field(..., min_length=1, description="records file (vbikit.traffic CSV), relative to the lifetime file")
    mode: Literal["fitted", "bootstrap"] = Field("fitted", description="fitted generator or bootstrap resampling of the records")
    trucks_per_day: Optional[float] = Field(None, ge=1, le=200_000, description="scale the fitted flows to this many trucks a day (all lanes)")
    lanes: Optional[list[Annotated[float, Field(ge=-100, le=100)]]] = Field(None, min_length=1, max_length=20, description="lane centres y [m]; default the bridge's (each on the deck: checked against the bridge)")
    components: int = Field(2, ge=1, le=4, description="normal components of each class's GVW mixture")
    speed_kmh: Optional[float] = Field(None, ge=5, le=250, description="every vehicle at this speed [km/h] (default: the fitted or recorded speeds)")

    @model_validator(mode="after")
    def _unique_lanes(self) -> "TrafficSpec":
        if self.lanes is not None and len(set(self.lanes)) != len(self.lanes):
            raise ValueError(f"lanes: each lane needs its own centre y, got {self.lanes}")
        return self


class LoadEffectSpec(_Strict):
    kind: Literal["deflection", "moment", "shear", "reaction"]
    x: Optional[float] = Field(None, ge=0, le=1000, description="section [m] (deflection, moment, shear) on the span (checked against the bridge); default midspan")
    y: Optional[float] = Field(None, ge=-100, le=100, description="deflection: point y [m] on the deck; default the bridge's response line")
    girder: Optional[int] = Field(None, ge=1, le=100, description="slab-on-girder decks: the girder (1-based)")
    support: Optional[int] = Field(None, ge=0, le=100, description="reaction: the support index (0 = entry)")
    name: str = Field("", pattern=r"^([A-Za-z][A-Za-z0-9_]*)?$", max_length=40)
    direction: Literal["auto", "positive", "negative"] = Field(
        "auto", description="the direction whose extremes the run reports: positive (sagging moment, upward "
        "deflection or reaction) or negative (hogging moment, downward deflection); auto: the sign of the influence "
        "line's largest ordinate")

    @model_validator(mode="after")
    def _check(self) -> "LoadEffectSpec":
        if self.kind == "reaction" and self.support is None:
            raise ValueError("a reaction needs support = 0, 1, …")
        if self.kind != "reaction" and self.support is not None:
            raise ValueError("support applies to kind = \"reaction\" only")
        if self.x is not None and 0.0 < self.x < MIN_SECTION:
            raise ValueError(f"x: a section {self.x!r} m from the entry support: give x = 0 or x >= {MIN_SECTION:g} m "
                             "(an effect that close to a support is zero to rounding)")
        if self.kind != "deflection" and self.y is not None:
            raise ValueError("y applies to kind = \"deflection\"; give girder for a girder's moment, shear or reaction")
        return self


class DetailSpec(_Strict):
    name: str = Field(..., pattern=r"^[A-Za-z][A-Za-z0-9_]*$", max_length=40)
    effect: str = Field(..., description="name of a [[load_effects]] entry")
    section_modulus: Optional[float] = Field(None, ge=1e-7, le=100, description="stress = effect / section_modulus [m³] (0.1 cm³ … 100 m³)")
    stress_per_unit: Optional[float] = Field(None, gt=0, le=1e15, description="stress = effect × stress_per_unit [Pa per effect unit]")
    category: str = Field(..., description="S-N curve: 'EN <Δσ_C in MPa>', a detail category of EN 1993-1-9 (vbikit.fatigue.EN_CATEGORIES), or 'AASHTO <category>'")
    gamma_mf: float = Field(1.0, ge=1.0, le=2.0, description="EN partial factor γ_Mf")
    size_factor: float = Field(1.0, ge=0.1, le=1.0, description="EN 1993-1-9 size-effect reduction k_s (its Table 8.x "
                               "footnotes): the curve is that of the reduced category k_s·Δσ_C (EN categories only)")

    @model_validator(mode="after")
    def _check(self) -> "DetailSpec":
        if (self.section_modulus is None) == (self.stress_per_unit is None):
            raise ValueError("give section_modulus [m³] or stress_per_unit [Pa per unit], one of them")
        check_category(self.category)
        if self.size_factor != 1.0 and not self.category.strip().upper().startswith("EN"):
            raise ValueError("size_factor: the size-effect reduction k_s applies to EN 1993-1-9 categories only")
        return self

    @property
    def factor(self) -> float:
        """Stress [Pa] per unit of the load effect."""
        return 1.0 / self.section_modulus if self.section_modulus is not None else float(self.stress_per_unit)


class FatigueSpec(_Strict):
    dynamic_sample: float = Field(0.05, gt=0, le=1, description="fraction of events simulated dynamically (seeded sample) for the dynamic-to-static damage ratio")
    histogram_bin: float = Field(1e6, ge=1e3, le=1e8, description="stress-range histogram bin [Pa] (1 kPa … 100 MPa)")
    damage_so_far: float = Field(0.0, ge=0, lt=1, description="Miner damage already accumulated, in [0, 1) (remaining life; 1 = failed)")
    design_life: float = Field(100.0, gt=0, le=1000, description="design working life [years] the damage is judged over (EN 1990 Table 2.1, category 5: 100 years)")
    details: list[DetailSpec] = Field(default_factory=list, max_length=50)


class LifetimeFile(_Strict):
    name: str = ""
    seed: int = Field(0, ge=0, le=2**63 - 1)
    days: Optional[int] = Field(None, ge=1, le=MAX_DAYS, description="simulated days")
    years: Optional[float] = Field(None, gt=0, le=200, description="simulated years (× days_per_year)")
    days_per_year: int = Field(365, ge=1, le=366, description="simulated days in a year (daily blocks per year)")
    amplification: float = Field(0.5, ge=0.01, le=5, description="A, upper bound of the dynamic increment (IM) R_dyn/R_st − 1 of any event (screening), 1 % … 500 %")
    return_periods: list[Annotated[float, Field(gt=0, le=1e6)]] = Field(default_factory=lambda: [75.0, 100.0, 1000.0], min_length=1, max_length=20, description="return periods [years], each longer than one block")
    characteristic_period: float = Field(1000.0, gt=0, le=1e6, description="return period [years] of the characteristic values")
    block: Literal["day", "week"] = "day"
    distribution: Literal["gev", "gumbel"] = "gumbel"
    ci: float = Field(0.95, gt=0, lt=1)
    budget_hours: float = Field(DEFAULT_BUDGET_HOURS, gt=0, le=MAX_BUDGET_HOURS)
    ds: float = Field(0.1, ge=1e-3, le=2, description="no longer used (the static peaks are exact extremes, not samples); accepted so that older lifetime files still read [m] (1 mm … 2 m)")
    dx: float = Field(0.02, ge=1e-3, le=1, description="grid of the tabulated influence lines [m] (1 mm … 1 m)")
    batch_size: int = Field(32, ge=1, le=1000, description="dynamic events per batch (of one day)")
    days_per_batch: int = Field(1, ge=1, le=366, description="days per batch of the static pass")
    traffic: TrafficSpec
    vehicle_model: Literal["axle-truck", "moving-forces"] = Field("axle-truck", description="dynamic events: trucks as 3D multibody axle trucks (vbikit.vehicle.axle_truck) or as moving constant axle forces")
    base: Optional[str] = Field(None, description="a scenario file with the bridge, tire, road and crossing sections")
    bridge: Optional[dict[str, Any]] = None
    tire: Optional[dict[str, Any]] = None
    road: Optional[dict[str, Any]] = None
    crossing: Optional[dict[str, Any]] = None
    load_effects: list[LoadEffectSpec] = Field(..., min_length=1, max_length=50)
    fatigue: FatigueSpec = FatigueSpec()

    @model_validator(mode="after")
    def _check(self) -> "LifetimeFile":
        if (self.days is None) == (self.years is None):
            raise ValueError("give the duration as days = N or years = N, one of them")
        if self.base is not None and self.bridge is not None:
            raise ValueError("base: give base = \"scenario.toml\" or a [bridge] table, not both")
        if self.base is None and self.bridge is None:
            raise ValueError("bridge: missing (a [bridge] table, or base = \"scenario.toml\")")
        names = [e.name for e in self.load_effects if e.name]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise ValueError(f"load_effects: names must be unique; repeated: {', '.join(dup)}")
        block_years = (7 if self.block == "week" else 1) / self.days_per_year
        for key, periods in (("return_periods", self.return_periods), ("characteristic_period", [self.characteristic_period])):
            short = [t for t in periods if t <= block_years]
            if short:
                raise ValueError(f"{key}: {short[0]:g} years is not longer than one block ({self.block}: "
                                 f"{block_years:.3g} years); a return period must exceed it")
        if self.characteristic_period not in self.return_periods:
            self.return_periods = sorted(set(self.return_periods) | {self.characteristic_period})
        return self

    @property
    def n_days(self) -> int:
        """The simulated days: ``days``, or ``years`` × ``days_per_year`` rounded up — with weekly blocks
        the whole weeks in it (``years = 1`` of 365 days: 52 weeks, 364 days), since the weekly maxima
        take whole weeks and the days after the last one would be left out of the fit (``days`` given
        that are not whole weeks are refused, ``vbikit.lifetime.run.prepare``)."""
        if self.days is not None:
            return int(self.days)
        days = float(self.years) * self.days_per_year
        if self.block == "week":
            return 7 * max(int(math.floor(days / 7.0 + 1e-9)), 1)
        return int(math.ceil(days))


def check_category(category: str) -> None:
    """ValueError naming the key ``category`` unless it names an S-N curve of the registry: an
    EN 1993-1-9 detail category (``EN_CATEGORIES``) or an AASHTO one (``vbikit.fatigue.curve_name``,
    the one check of the allowed names and their list)."""
    from vbikit.fatigue.errors import FatigueError
    from vbikit.fatigue.sn_curves import curve_name

    try:
        curve_name(category)
    except FatigueError as err:
        raise ValueError(f"category: {str(err).removeprefix('curve: ')}") from None


def parse_lifetime(data: dict[str, Any]) -> LifetimeFile:
    """Validate a lifetime specification given as a dict (the parsed TOML)."""
    try:
        return LifetimeFile.model_validate(data)
    except ValidationError as err:
        raise LifetimeError(validation_message(err, "invalid lifetime file", model=LifetimeFile)) from None


def read_lifetime(path: str | Path) -> tuple[LifetimeFile, Path]:
    """Read and validate a lifetime TOML file; returns the spec and its folder (relative paths)."""
    from vbikit._toml import read_toml

    path = Path(path)
    return parse_lifetime(read_toml(path, LifetimeError, "lifetime file")), path.parent


def base_sections(spec: LifetimeFile, base_dir: Path) -> tuple[dict[str, Any], Path]:
    """The base scenario's sections (bridge, tire, road, crossing) and the folder their relative paths
    (a ``modes_file``, a ``profile_file``) point into: the ``base`` file's own folder, as for
    ``vbikit traffic --bridge`` and ``vbikit run`` (``base_dir``, the lifetime file's folder, for
    sections given in the lifetime file itself)."""
    if spec.base is not None:
        from vbikit.traffic.study import base_scenario

        data, folder = base_scenario(str(base_dir / spec.base))
        return {k: v for k, v in data.items() if k in BASE_SECTIONS}, Path(folder)
    return {k: getattr(spec, k) for k in BASE_SECTIONS if getattr(spec, k) is not None}, base_dir
