"""The ``[bridge]`` table: one spec class per bridge kind ("beam", "continuous-beam",
"slab-on-girder", "modes-file", and every preset), each with only its own keys and its own
``build``, chosen by ``model`` (a pydantic discriminated union, ``BridgeSpec``)."""
from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, Optional, Union, get_args

import numpy as np
from pydantic import Discriminator, Field, Tag, field_validator, model_validator

from vbikit.bridge.base import DEFAULT_DAMPING_RATIO, ModalBridge
from vbikit.bridge.damage import Damage
from vbikit.bridge.presets import BRIDGE_PRESETS
from vbikit.scenario.section import ScenarioError, Section


class DamageSpec(Section):
    """[[bridge.damage]]: a bending-stiffness loss over a region (vbikit.bridge.damage)."""

    position: float = Field(..., ge=0, description="start of the damaged region [m from the bridge entry]")
    length: float = Field(..., gt=0, description="length of the region [m]")
    severity: float = Field(..., ge=0, lt=1, description="relative loss of EI [-]")
    girder: Optional[int] = Field(None, ge=1, description="girder number (slab-on-girder bridges)")

    def build(self) -> Damage:
        """The region as a ``Damage`` (checked by the model)."""
        return Damage(self.position, self.length, self.severity, self.girder)


#: upper ends of the beam properties [N m^2], [kg/m] (far above any bridge: a steel box girder has EI ≈ 1e13 N m^2)
MAX_EI = 1e16
#: lower end of a beam's bending stiffness [N m^2]: a 10 × 5 mm aluminium laboratory strip has EI ≈ 7 N m^2; far
#: below it the modes' frequencies underflow against any vehicle's (1e-300 overflowed the load-effect step estimate)
MIN_EI = 1.0
MAX_MASS_PER_LENGTH = 1e6
#: span lengths [m] of a continuous beam (and the longest of a beam: the longest bridge spans are about 2 km); shorter than 0.5 m the mesh
#: of ``elements_per_span`` elements degenerates)
MIN_SPAN = 0.5
MAX_SPAN = 5000.0
_POSITIVE = Annotated[float, Field(gt=0)]
_EI = Annotated[float, Field(ge=MIN_EI, le=MAX_EI)]
_MASS = Annotated[float, Field(gt=0, le=MAX_MASS_PER_LENGTH)]
_SPRING = Annotated[float, Field(ge=0, allow_inf_nan=True)]

_DAMPING_RATIO = Annotated[float, Field(ge=0, lt=1, description="modal damping ratio, every mode [-]")]
_N_MODES = Annotated[int, Field(ge=1, le=500, description="retained modes (the lowest n) [-]")]
_NEUTRAL_AXIS = Annotated[Optional[float], Field(gt=0, description="neutral axis to bottom fibre, the strain lever arm; default 0.5 m [m]")]


def _damage(description: str) -> Any:
    return Field(default_factory=list, description=f"[[bridge.damage]] local stiffness losses{description}")


def _check_deck_keys(deck: Optional[dict[str, Any]]) -> None:
    if deck is not None:
        from vbikit.scenario.deck import SCENARIO_PARAMETERS

        unknown = [k for k in deck if k not in SCENARIO_PARAMETERS]
        if unknown:
            raise ValueError(f"deck: unknown [bridge.deck] key(s) {', '.join(map(repr, unknown))}; allowed: {', '.join(SCENARIO_PARAMETERS)}")


def _check_damage_girders(damage: list[DamageSpec], deck: bool) -> None:
    for i, d in enumerate(damage):
        if deck and d.girder is None:
            raise ValueError(f"damage.{i}: a slab-on-girder deck needs girder (the damaged girder's number)")
        if not deck and d.girder is not None:
            raise ValueError(f"damage.{i}: a beam has no girders; remove girder")


class BridgeKind(Section):
    """One kind of [bridge]: its own keys, and ``build`` that makes the model.

    Every kind has ``model``, ``n_modes``, ``damping_ratio``, ``deck`` (None without a
    [bridge.deck] table) and ``damage`` (empty without [[bridge.damage]]).
    """

    def build(self, base_dir: Path | str = ".") -> ModalBridge:
        """The bridge model (relative file names against ``base_dir``); raises ScenarioError or ValueError."""
        raise NotImplementedError

    def damage_regions(self) -> tuple[Damage, ...]:
        """The [[bridge.damage]] regions as ``Damage``."""
        return tuple(d.build() for d in self.damage)  # type: ignore[attr-defined]

    @classmethod
    def unknown_key_note(cls, key: str, table: dict[str, Any]) -> str:
        where = [f'model = "{m}"' if m in BRIDGE_KINDS else "the presets"
                 for m, kind in _KIND_CLASSES.items() if kind is not cls and key in kind.model_fields]
        return f"{key} is a key of {' and '.join([', '.join(where[:-1]), where[-1]] if len(where) > 1 else where)}" if where else ""

    def _deck_bridge(self, make: Any) -> ModalBridge:
        """``make(n_modes=, damping_ratio=, **deck overrides, damage=)``: a deck whose model errors name bridge.deck.<key>."""
        from vbikit.scenario.deck import SCENARIO_PARAMETERS, deck_parameters

        deck = self.deck or {}  # type: ignore[attr-defined]
        overrides = deck_parameters(deck)
        if self.damage:  # type: ignore[attr-defined]
            overrides["damage"] = self.damage_regions()
        try:
            return make(n_modes=self.n_modes, damping_ratio=self.damping_ratio, **overrides)  # type: ignore[attr-defined]
        except ValueError as err:  # the deck model names its parameter: give it the scenario key
            key = str(err).split(" ", 1)[0]
            if key in deck:
                raise ScenarioError(f"bridge.deck.{err}") from None
            if key in SCENARIO_PARAMETERS:  # the model's own value no longer fits the ones [bridge.deck] changed
                raise ScenarioError(f"bridge.deck: the model's own {err}, with the values [bridge.deck] sets "
                                    f"({', '.join(sorted(deck))}); set bridge.deck.{key} as well") from None
            raise ScenarioError(str(err)) from None


class BeamSpec(BridgeKind):
    """[bridge] model = "beam": a simply supported Euler–Bernoulli beam (vbikit.bridge.EulerBernoulliBeam)."""

    model: Literal["beam"] = Field("beam", description="Euler–Bernoulli beam")
    span: Optional[float] = Field(None, gt=0, le=MAX_SPAN, description="span length [m]")
    EI: Optional[float] = Field(None, ge=MIN_EI, le=MAX_EI, description="bending stiffness [N m^2]")
    mass_per_length: Optional[float] = Field(None, gt=0, le=MAX_MASS_PER_LENGTH, description="mass per length [kg/m]")
    damping_ratio: _DAMPING_RATIO = DEFAULT_DAMPING_RATIO
    n_modes: _N_MODES = 10
    neutral_axis_depth: _NEUTRAL_AXIS = None

    deck: ClassVar[None] = None
    damage: ClassVar[tuple[DamageSpec, ...]] = ()

    @field_validator("EI", "mass_per_length", mode="before")
    @classmethod
    def _one_value(cls, v: Any) -> Any:
        if isinstance(v, list):
            raise ValueError("EI and mass_per_length per span (lists) need model = \"continuous-beam\"")
        return v

    @model_validator(mode="after")
    def _properties(self) -> "BeamSpec":
        missing = [k for k in ("span", "EI", "mass_per_length") if getattr(self, k) is None]
        if missing:
            raise ValueError(f"model = \"beam\" needs {', '.join(missing)} (span [m], EI [N m^2], mass_per_length [kg/m])")
        return self

    def build(self, base_dir: Path | str = ".") -> ModalBridge:
        from vbikit.bridge.beam import EulerBernoulliBeam

        return EulerBernoulliBeam(
            span=self.span, EI=self.EI, mass_per_length=self.mass_per_length, damping_ratio=self.damping_ratio,
            n_modes=self.n_modes, neutral_axis_depth=self.neutral_axis_depth or 0.5,
        )


class ContinuousBeamSpec(BridgeKind):
    """[bridge] model = "continuous-beam": spans in a row on springs (vbikit.bridge.ContinuousBeam)."""

    model: Literal["continuous-beam"] = Field(..., description="Euler–Bernoulli beam over several spans")
    EI: Optional[Union[_EI, list[_EI]]] = Field(None, description="bending stiffness, one or one per span [N m^2]")
    mass_per_length: Optional[Union[_MASS, list[_MASS]]] = Field(None, description="mass per length, one or one per span [kg/m]")
    spans: Optional[list[Annotated[float, Field(ge=MIN_SPAN, le=MAX_SPAN)]]] = Field(None, description="span lengths [m]")
    support_stiffness: Optional[Union[_SPRING, list[_SPRING]]] = Field(
        None, description="vertical support springs [N/m], one or one per support (inf = rigid); default rigid")
    rotational_stiffness: Optional[list[_SPRING]] = Field(
        None, min_length=2, max_length=2, description="end rotational springs [N m/rad] (entry, exit)")
    elements_per_span: int = Field(40, ge=2, le=1000, description="Hermite elements per span")
    damage: list[DamageSpec] = _damage(" (one span = a simply supported beam)")
    damping_ratio: _DAMPING_RATIO = DEFAULT_DAMPING_RATIO
    n_modes: _N_MODES = 10
    neutral_axis_depth: _NEUTRAL_AXIS = None

    deck: ClassVar[None] = None

    @model_validator(mode="after")
    def _properties(self) -> "ContinuousBeamSpec":
        missing = [k for k in ("spans", "EI", "mass_per_length") if getattr(self, k) is None]
        if missing:
            raise ValueError(f"model = \"continuous-beam\" needs {', '.join(missing)} (spans [m], EI [N m^2], mass_per_length [kg/m])")
        _check_damage_girders(self.damage, deck=False)
        return self

    def build(self, base_dir: Path | str = ".") -> ModalBridge:
        from vbikit.bridge.continuous import ContinuousBeam

        return ContinuousBeam(
            spans=tuple(self.spans), EI=self.EI, mass_per_length=self.mass_per_length, damping_ratio=self.damping_ratio,
            n_modes=self.n_modes, neutral_axis_depth=self.neutral_axis_depth or 0.5,
            support_stiffness=self.support_stiffness, rotational_stiffness=tuple(self.rotational_stiffness or (0.0, 0.0)),
            elements_per_span=self.elements_per_span, damage=self.damage_regions(),
        )


class SlabOnGirderSpec(BridgeKind):
    """[bridge] model = "slab-on-girder": a 3D grillage deck from [bridge.deck] (vbikit.bridge.SlabOnGirderBridge)."""

    model: Literal["slab-on-girder"] = Field(..., description="3D grillage deck")
    damage: list[DamageSpec] = _damage(" of single girders")
    damping_ratio: _DAMPING_RATIO = DEFAULT_DAMPING_RATIO
    n_modes: _N_MODES = 10
    deck: Optional[dict[str, Any]] = Field(
        None, description="table [bridge.deck]: SlabOnGirderBridge parameters, at least span; keys and units in the bridges guide")

    @model_validator(mode="after")
    def _deck_table(self) -> "SlabOnGirderSpec":
        _check_damage_girders(self.damage, deck=True)
        _check_deck_keys(self.deck)
        if self.deck is None or not {"span", "spans"} & set(self.deck):
            raise ValueError("model = \"slab-on-girder\" needs [bridge.deck] with at least span [m] or spans (docs/bridges.md)")
        return self

    def build(self, base_dir: Path | str = ".") -> ModalBridge:
        from vbikit.bridge.girder_deck import SlabOnGirderBridge

        return self._deck_bridge(SlabOnGirderBridge)


class ModesFileSpec(BridgeKind):
    """[bridge] model = "modes-file": modes imported from a `vbikit-modes 1` file (vbikit.bridge.modefile)."""

    model: Literal["modes-file"] = Field(..., description="imported modes")
    modes_file: str = Field(..., description="path of a `vbikit-modes 1` file, relative to the scenario; n_modes, if given, keeps the first modes")
    damping_ratio: _DAMPING_RATIO = DEFAULT_DAMPING_RATIO
    n_modes: _N_MODES = 10

    deck: ClassVar[None] = None
    damage: ClassVar[tuple[DamageSpec, ...]] = ()

    def build(self, base_dir: Path | str = ".") -> ModalBridge:
        from vbikit.bridge.modefile import modes_from_file

        path = Path(base_dir) / self.modes_file
        try:
            bridge = modes_from_file(path, damping_ratio=self.damping_ratio)
            n_file = int(bridge.omega.size)
            if "n_modes" in self.model_fields_set and self.n_modes > n_file:
                raise ScenarioError(f"bridge.n_modes = {self.n_modes}: the mode file {self.modes_file} has {n_file} modes; "
                                    f"give n_modes 1 … {n_file}, or leave it out for all of them")
            if "n_modes" in self.model_fields_set and self.n_modes < n_file:
                bridge = modes_from_file(path, damping_ratio=self.damping_ratio, n_modes=self.n_modes)
        except ValueError as err:
            raise ScenarioError(f"bridge.modes_file: {err}") from None
        if "damping_ratio" in self.model_fields_set and np.any(bridge.damping_ratios != self.damping_ratio):
            raise ScenarioError(f"bridge.damping_ratio = {self.damping_ratio:g}: the mode file {self.modes_file} gives its "
                                f"own damping_ratios ({', '.join(f'{z:g}' for z in bridge.damping_ratios)}), which would "
                                "be used; remove bridge.damping_ratio, or the file's damping_ratios header")
        return bridge


def _deck_preset(name: str) -> bool:
    return BRIDGE_PRESETS[name].kind == "slab-on-girder"


class PresetBridgeSpec(BridgeKind):
    """[bridge] model = a preset name (`vbikit presets`): n_modes and damping_ratio, and on the
    slab-on-girder presets [bridge.deck] overrides and [[bridge.damage]]."""

    model: str = Field(..., description="a bridge preset (`vbikit presets`)")
    damage: list[DamageSpec] = _damage(" of single girders (slab-on-girder presets)")
    damping_ratio: _DAMPING_RATIO = DEFAULT_DAMPING_RATIO
    n_modes: _N_MODES = 10
    deck: Optional[dict[str, Any]] = Field(
        None, description="table [bridge.deck]: overrides of a slab-on-girder preset; keys and units in the bridges guide")

    @field_validator("model")
    @classmethod
    def _known_model(cls, v: str) -> str:
        if v not in BRIDGE_PRESETS:
            allowed = (*BRIDGE_KINDS, *BRIDGE_PRESETS)
            raise ValueError(f"unknown bridge model {v!r}; allowed: {', '.join(allowed)}")
        return v

    @model_validator(mode="after")
    def _overrides(self) -> "PresetBridgeSpec":
        deck = _deck_preset(self.model)
        if self.damage and not deck:
            raise ValueError("damage: [[bridge.damage]] applies to model = \"continuous-beam\" (one span = a simply supported "
                             f"beam) and to slab-on-girder decks, not the beam preset {self.model!r}")
        _check_damage_girders(self.damage, deck=True)
        if self.deck is not None and not deck:
            raise ValueError(f"deck: [bridge.deck] applies to model = \"slab-on-girder\" and the slab-on-girder presets, not {self.model!r}")
        _check_deck_keys(self.deck)
        return self

    @classmethod
    def allowed_keys(cls, table: dict[str, Any]) -> list[str]:
        model = table.get("model")
        keys = super().allowed_keys(table)
        if isinstance(model, str) and model in BRIDGE_PRESETS and not _deck_preset(model):
            keys = [k for k in keys if k not in ("deck", "damage")]
        return keys

    @classmethod
    def unknown_key_note(cls, key: str, table: dict[str, Any]) -> str:
        from vbikit.scenario.deck import SCENARIO_PARAMETERS

        note = super().unknown_key_note(key, table)
        model = table.get("model")
        if isinstance(model, str) and model in BRIDGE_PRESETS and _deck_preset(model) and key in SCENARIO_PARAMETERS:
            return (f"a preset fixes its properties; this slab-on-girder preset takes a change of {key} in its "
                    f"[bridge.deck] table (bridge.deck.{key})")
        return f"a preset fixes its properties{'; ' + note if note else ''}"

    def build(self, base_dir: Path | str = ".") -> ModalBridge:
        preset = BRIDGE_PRESETS[self.model]
        if self.deck is not None or self.damage:
            return self._deck_bridge(preset.build)
        return preset.build(n_modes=self.n_modes, damping_ratio=self.damping_ratio)


#: model → spec class of the bridge kinds named by their model (any other model names a preset:
#: :class:`PresetBridgeSpec`); a new kind is a spec class with ``model: Literal[...]`` and ``build``, listed here
BRIDGE_KINDS: dict[str, type[BridgeKind]] = {
    get_args(kind.model_fields["model"].annotation)[0]: kind
    for kind in (BeamSpec, ContinuousBeamSpec, SlabOnGirderSpec, ModesFileSpec)
}
#: tag of the discriminated union → spec class
_KIND_CLASSES: dict[str, type[BridgeKind]] = {**BRIDGE_KINDS, "preset": PresetBridgeSpec}


def bridge_kind(table: Any) -> Optional[str]:
    """The tag of a [bridge] table: its model when a kind of ``BRIDGE_KINDS`` (default
    "beam"), else "preset" (the preset class checks the name); None when not a table."""
    if isinstance(table, BridgeKind):
        return next(tag for tag, kind in _KIND_CLASSES.items() if type(table) is kind)
    if not isinstance(table, dict):
        return None
    model = table.get("model", "beam")
    return model if isinstance(model, str) and model in BRIDGE_KINDS else "preset"


#: [bridge]: one spec class per kind, chosen by ``model`` (see :func:`bridge_kind`)
BridgeSpec = Annotated[
    Union[tuple(Annotated[kind, Tag(tag)] for tag, kind in _KIND_CLASSES.items())],  # type: ignore[misc]
    Discriminator(bridge_kind, custom_error_type="bridge_table",
                  custom_error_message=f"must be a table: model = {', '.join(map(json.dumps, BRIDGE_KINDS))} or a "
                                       "preset name, with that model's keys"),
]
