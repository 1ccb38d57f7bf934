"""The RAIL.toml input of ``vbikit rail`` / ``vbikit.rail.run_rail`` (pydantic schema).

    [bridge]                         # a simply supported span (Euler–Bernoulli beam) …
    span = 20.0                      # m
    EI = 1.2e10                      # N m²
    mass_per_length = 15000.0        # kg/m
    # scenario = "deck.toml"         # … or the [bridge] of a vbikit scenario (one span, square supports)
    deck = "prestressed-concrete"    # EN 1991-2 Table 6.6 row (steel, composite, prestressed-concrete,
                                     # reinforced-concrete, filler-beam)
    track = "ballasted"              # or "direct" (acceleration limit 3.5 or 5 m/s²)
    # damping = 0.015                # ζ [-] instead of Table 6.6 + Δζ (then leave additional_damping out)
    additional_damping = true        # add Δζ of Eq. 6.13 (spans below 30 m)
    # n_modes = 3                    # default: every mode up to max(30 Hz, 1.5 n0, n3), at least 3
    classification_factor = 1.0      # α of LM71
    maintenance = "careful"          # Φ2 ("careful") or Φ3 ("standard")

    [trains]
    presets = ["hslm-a1", "hslm-a2"] # or "hslm-a" for all ten
    hslm_b = [{n = 10, d = 3.5}]     # HSLM-B: N forces of 170 kN at spacing d [m] (from EN 1991-2's
                                     # figure for the span: 1 … 100 forces, 0.5 … 50 m)
    tables = ["my_train.csv"]        # position [m], load [kN] per line
    # sleeper_spacing = 0.6          # distribute each axle over three sleepers (EN 1991-2 6.3.6.1)

    [speeds]                         # km/h
    min = 100.0
    max = 420.0                      # or line_max = 350.0 → max = 1.2 × 350
    step = 5.0
    fine_step = 1.0                  # near every resonance speed n0 D / i …
    fine_width = 10.0                # … within ± this

    [coupled]                        # optional: trains with car data as coupled cars
    enabled = false
    irregularity = "german-low"      # a track PSD (vbikit.road.track), or omit for a smooth track
    seed = 0
    max_steps = 2e6                  # the most coupled time steps (all speeds and trains together)

    [run]
    workers = 2                      # local worker processes (default: all cores)
    steps_per_period = 20            # samples per period of the highest mode at the lowest speed
    budget = 4e9                     # the most filter steps
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, Optional, Union

from pydantic import BaseModel, ConfigDict, Field, ValidationError, ValidationInfo, field_validator, model_validator

from vbikit._validation import MAX_WORKERS, validation_message
from vbikit.errors import VbikitError
from vbikit.rail.codes import CLASSIFICATION_FACTORS, DECK_DAMPING, DYNAMIC_FACTORS, ACCELERATION_LIMITS
from vbikit.vehicle.trains import HSLM_B_N, HSLM_B_SPACING


#: the range of a wheel-rail contact stiffness per wheelset [N/m]: the linearised Hertzian stiffness of a
#: wheelset is about 1e9 N/m (two wheels, 1-2e9 N/m each); a track pad under the rail brings it down to ~1e7
MIN_CONTACT, MAX_CONTACT = 1e6, 1e12


#: the largest work budgets a railway file's keys (and ``vbikit rail --max-steps`` / ``--max-coupled-steps``) may set:
#: run.budget [filter steps of the whole sweep], coupled.max_steps [coupled time steps of the whole sweep]
MAX_BUDGET, MAX_COUPLED_STEPS = 1e13, 1e10


class RailSpecError(VbikitError):
    """An invalid RAIL.toml; the message names the key and the allowed range."""

    message_names_key = True


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False)


#: the [bridge] keys that name an entry of a code table: key -> its table (EN 1991-2 / EN 1990 rules)
_NAMED = {"deck": DECK_DAMPING, "track": ACCELERATION_LIMITS, "maintenance": DYNAMIC_FACTORS}


class BridgeSection(_Section):
    span: Optional[float] = Field(None, ge=1, le=300, description="span [m]")
    EI: Optional[float] = Field(None, ge=1e6, le=1e15, description="bending stiffness [N m²]")
    mass_per_length: Optional[float] = Field(None, ge=100, le=1e6, description="mass per length [kg/m]")
    scenario: Optional[str] = None
    deck: str = "prestressed-concrete"
    track: str = "ballasted"
    damping: Optional[float] = Field(None, ge=0, lt=0.2)
    additional_damping: bool = True
    n_modes: Optional[int] = Field(None, ge=1, le=50)
    classification_factor: float = 1.0
    maintenance: str = "careful"

    @model_validator(mode="after")
    def _beam_or_scenario(self) -> "BridgeSection":
        beam = [k for k in ("span", "EI", "mass_per_length") if getattr(self, k) is not None]
        if self.scenario is None and len(beam) < 3:
            missing = [k for k in ("span", "EI", "mass_per_length") if getattr(self, k) is None]
            raise ValueError(f"{missing[0]}: give span, EI and mass_per_length (a simply supported beam), or scenario "
                             "(a vbikit scenario file whose [bridge] is used)")
        if self.scenario is not None and beam:
            raise ValueError(f"{beam[0]}: give either scenario or span, EI and mass_per_length, not both")
        if self.damping is not None and self.additional_damping and "additional_damping" in self.model_fields_set:
            raise ValueError("additional_damping: a given damping replaces the code's ζ and its additional Δζ "
                             "(EN 1991-2 Eq. 6.13) both; give damping alone, or additional_damping without damping")
        return self

    @field_validator("deck", "track", "maintenance")
    @classmethod
    def _named(cls, v: str, info: ValidationInfo) -> str:
        allowed = _NAMED[info.field_name]
        if v not in allowed:
            raise ValueError(f"{info.field_name} must be one of {', '.join(allowed)}, got {v!r}")
        return v

    @field_validator("classification_factor")
    @classmethod
    def _alpha(cls, v: float) -> float:
        if not any(abs(v - a) < 1e-9 for a in CLASSIFICATION_FACTORS):
            raise ValueError(f"classification_factor must be one of {', '.join(map(str, CLASSIFICATION_FACTORS))}, got {v!r}")
        return v


class HslmBEntry(_Section):
    """One HSLM-B train (EN 1991-2:2003 6.4.6.1.1): ``n`` forces of 170 kN at spacing ``d`` [m], both
    read by the user from the standard's figure for the span (``vbikit.vehicle.hslm_b``, whose
    ranges these are)."""

    n: int = Field(ge=HSLM_B_N[0], le=HSLM_B_N[1])
    d: float = Field(ge=HSLM_B_SPACING[0], le=HSLM_B_SPACING[1])


class TrainsSection(_Section):
    presets: list[str] = Field(default_factory=list)
    hslm_b: list[HslmBEntry] = Field(default_factory=list)
    tables: list[str] = Field(default_factory=list)
    sleeper_spacing: Optional[float] = Field(None, ge=0.1, le=2.0)

    @field_validator("presets")
    @classmethod
    def _presets(cls, v: list[str]) -> list[str]:
        from vbikit.vehicle.trains import TRAIN_PRESETS

        out: list[str] = []
        for name in v:
            key = name.strip().lower()
            if key == "hslm-a":
                out += [f"hslm-a{k}" for k in range(1, 11)]
            elif key in TRAIN_PRESETS:
                out.append(key)
            else:
                raise ValueError(f"unknown train {name!r}; allowed: hslm-a (all ten), {', '.join(TRAIN_PRESETS)}")
        return list(dict.fromkeys(out))

    @model_validator(mode="after")
    def _some(self) -> "TrainsSection":
        if not self.presets and not self.tables and not self.hslm_b:
            raise ValueError("presets: give at least one train (presets, hslm_b or tables)")
        return self


class SpeedsSection(_Section):
    min: float = Field(100.0, ge=10, le=600, description="lowest speed [km/h]")
    max: Optional[float] = Field(None, ge=10, le=600, description="highest speed [km/h]")
    line_max: Optional[float] = Field(None, ge=10, le=500, description="line speed; the sweep goes to 1.2 × it [km/h]")
    step: float = Field(5.0, ge=0.1, le=100, description="speed step [km/h]")
    fine_step: Optional[float] = Field(None, ge=0.05, le=100, description="step near resonance speeds [km/h]")
    fine_width: float = Field(10.0, ge=0, le=100, description="± range of the fine step [km/h]")

    @model_validator(mode="after")
    def _range(self) -> "SpeedsSection":
        if (self.max is None) == (self.line_max is None):
            raise ValueError("max: give either max (km/h) or line_max (km/h; the sweep goes to 1.2 × line_max)")
        top = self.top
        if top > 600:
            raise ValueError(f"line_max: 1.2 × line_max must be ≤ 600 km/h, got {top:g}")
        if top <= self.min and self.max is not None:
            raise ValueError(f"max: must exceed min = {self.min:g} km/h, got {top:g}")
        if top <= self.min:  # the sweep's top is 1.2 × line_max: say so, and name the keys the file has
            raise ValueError(f"min: must be below the sweep's highest speed 1.2 × line_max = "
                             f"1.2 × {self.line_max:g} = {top:g} km/h, got {self.min:g}; lower min, or raise line_max "
                             f"above {self.min / 1.2:.4g} km/h (or give max instead of line_max)")
        return self

    @property
    def top(self) -> float:
        """The highest speed [km/h]."""
        return float(self.max) if self.max is not None else 1.2 * float(self.line_max)


class CoupledSection(_Section):
    enabled: bool = False
    irregularity: Optional[str] = None
    seed: int = Field(0, ge=0)
    max_steps: float = Field(2e6, ge=1, le=MAX_COUPLED_STEPS)
    contact: Union[str, float] = "hertz"  # "hertz", "rigid" or a stiffness [N/m] per wheelset (MIN_CONTACT … MAX_CONTACT)

    @field_validator("contact")
    @classmethod
    def _contact(cls, v: Union[str, float]) -> Union[str, float]:
        if isinstance(v, str) and v not in ("hertz", "rigid"):
            raise ValueError(f"contact must be 'hertz', 'rigid' or a wheel-rail stiffness per wheelset in N/m, got {v!r}")
        if not isinstance(v, str) and not (MIN_CONTACT <= v <= MAX_CONTACT):
            raise ValueError(f"a wheel-rail stiffness per wheelset is within {MIN_CONTACT:g} … {MAX_CONTACT:g} N/m "
                             f"(Hertzian contact is about 1e9 N/m), got {v!r}")
        return v

    @field_validator("irregularity")
    @classmethod
    def _irr(cls, v: Optional[str]) -> Optional[str]:
        if v is None:
            return v
        from vbikit.road.track import TRACK_PSDS

        if v not in TRACK_PSDS:
            raise ValueError(f"irregularity must be one of {', '.join(TRACK_PSDS)}, got {v!r}")
        return v


class RunSection(_Section):
    workers: Optional[int] = Field(None, ge=1, le=MAX_WORKERS, description="local worker processes (default: all cores)")
    steps_per_period: int = Field(20, ge=8, le=200)
    budget: float = Field(4e9, gt=0, le=MAX_BUDGET)
    points: int = Field(9, ge=1, le=99)


class RailSpec(_Section):
    """The whole RAIL.toml."""

    bridge: BridgeSection
    trains: TrainsSection
    speeds: SpeedsSection = Field(default_factory=SpeedsSection)
    coupled: CoupledSection = Field(default_factory=CoupledSection)
    run: RunSection = Field(default_factory=RunSection)


def parse_rail_spec(data: dict[str, Any]) -> RailSpec:
    """Validate a parsed RAIL.toml (raises ``RailSpecError`` naming every bad key)."""
    try:
        return RailSpec.model_validate(data)
    except ValidationError as err:
        raise RailSpecError(validation_message(err, "invalid rail file", model=RailSpec)) from None


def with_budgets(spec: RailSpec, budget: Optional[float] = None, coupled_max_steps: Optional[float] = None) -> RailSpec:
    """``spec`` with its work budgets set from the command line (``vbikit rail --max-steps`` / ``--max-coupled-steps``;
    None: the file's): ``run.budget`` and ``coupled.max_steps``, the same spec as a file giving those values."""
    run = spec.run if budget is None else spec.run.model_copy(update={"budget": float(budget)})
    coupled = spec.coupled if coupled_max_steps is None else spec.coupled.model_copy(
        update={"max_steps": float(coupled_max_steps)})
    return spec.model_copy(update={"run": run, "coupled": coupled})


def load_rail_spec(path: str | Path) -> RailSpec:
    """Read and validate a RAIL.toml file."""
    from vbikit._toml import read_toml

    return parse_rail_spec(read_toml(path, RailSpecError, "rail file"))
