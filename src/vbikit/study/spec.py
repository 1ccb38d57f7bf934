"""The study specification (TOML): a base scenario plus axes to sweep.

A study file::

    name = "my study"
    seed = 2026                      # study seed: road seeds derive from it and the sample index
    batch_size = 32                  # crossings per batch (one prepared system, roads run as lanes)
    outputs = ["impact_factor"]      # optional: only these outputs of vbikit.outputs (default: all)
    method = "monte-carlo"           # or "pem": each cell's IM distribution by pseudo-excitation

    [base]                           # a whole scenario inline (same keys as a scenario file) ...
    # scenario = "bridge.toml"       # ... or a path to a scenario file, relative to the study file

    [axes]                           # dotted scenario keys -> list of values, or {samples = N}
    "tire.n_points" = [1, 3, 6, 9]
    "crossing.speed_kmh" = [45, 75, 105]
    "road.class" = ["B", "C", "D"]
    "road.seed" = { samples = 20 }

``{samples = N}`` is allowed only for seed keys (``road.seed``): sample i gets the seed
``derive_seed(study_seed, i)`` — a function of the study seed and the sample index only, never
of execution order, so the same sample index drives the same road in every crossing of the
study (same x, same elevation), and re-running or resuming gives identical roads.

Every combination of the axis values is validated as a scenario before anything runs; errors
name the study key (``axes."tire.n_points"``) and the scenario key.

``method`` says how the road's randomness is handled: ``"monte-carlo"`` (default) runs one
crossing per sampled road (the ``road.seed`` axis) and stores the catalogue's outputs of each;
``"pem"`` runs one pseudo-excitation analysis per cell of the other axes (``vbikit.random``,
``vbikit.study.pem``) and stores the impact factor's mean, standard deviation and quantiles over
the random road — no seed axis, no ``outputs`` or ``histories`` then, and every cell's road must
be a random class without defects.
"""
from __future__ import annotations

import copy
import itertools
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Optional, Union

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from vbikit._toml import parse_toml, read_toml
from vbikit._validation import validation_message
from vbikit.errors import VbikitError
from vbikit.outputs import QUALITY_OUTPUTS, base_resolve, outputs as catalogue_outputs, select_outputs
from vbikit.contact.registry import TIRE_MODELS
from vbikit.scenario.schema import Scenario, ScenarioError, TireSpec, parse_scenario, section_keys

#: scenario keys that only change the road: crossings differing only in these share dt, contact
#: points, tabulated shapes and the static reference (one prepared batch)
ROAD_ONLY_KEYS = ("road.seed", "road.class", "road.phi0", "road.n0", "road.exponent", "road.right_coherence")
#: axes that may be given as {samples = N}
SAMPLE_KEYS = ("road.seed",)
#: how a study treats the random road (``method``): sampled roads, or pseudo-excitation per cell
STUDY_METHODS = ("monte-carlo", "pem")


class StudyError(VbikitError):
    """An invalid study; the message names the offending key."""

    message_names_key = True


#: a study with more crossings is refused unless the user confirms it (``--yes``)
MAX_CROSSINGS_UNCONFIRMED = 1_000_000
#: largest product of one section's axis values validated combination by combination; above it
#: every pair of that section's axes is validated with all its value pairs (the schema's
#: cross-key rules relate two keys of a section at a time)
MAX_COMBINATIONS = 4096


def _value_key(v: Any) -> str:
    """Identity of an axis value for the duplicate check: numbers by value (1 == 1.0), booleans
    and strings by themselves."""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return json.dumps(v, sort_keys=True)
    return f"number:{float(v)!r}"


class SamplesAxis(BaseModel):
    """``{samples = N}``: N sample indices 0 … N−1 with seeds derived from the study seed."""

    model_config = ConfigDict(extra="forbid", strict=True)
    samples: int = Field(..., ge=1, le=100000, description="number of samples")


class StudyFile(BaseModel):
    """The raw study file (before the axes are checked against the scenario schema)."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False)
    name: str = ""
    seed: int = Field(0, ge=0, description="study seed; road seeds derive from it and the sample index")
    batch_size: int = Field(32, ge=1, le=10000, description="crossings per batch")
    histories: bool = Field(False, description="also store midspan displacement histories")
    outputs: Optional[list[str]] = Field(None, description="the catalogue's outputs to reduce and store (default: all)")
    base: dict[str, Any] = Field(..., description="scenario (inline tables) or {scenario = \"path.toml\"}")
    axes: dict[str, Any] = Field(default_factory=dict, description="key -> list of values, or {samples = N}")
    method: str = Field(STUDY_METHODS[0], description="monte-carlo: one crossing per sampled road; pem: the impact "
                                                      "factor's distribution per cell by pseudo-excitation")

    @field_validator("method")
    @classmethod
    def _method(cls, method: str) -> str:
        if method not in STUDY_METHODS:
            raise ValueError(f"must be one of {', '.join(STUDY_METHODS)}, got {method!r}")
        return method

    @field_validator("outputs")
    @classmethod
    def _outputs(cls, names: Optional[list[str]]) -> Optional[list[str]]:
        return None if names is None else list(select_outputs(names))

    @field_validator("axes")
    @classmethod
    def _axes(cls, axes: dict[str, Any]) -> dict[str, Union[SamplesAxis, list[Any]]]:
        out: dict[str, Union[SamplesAxis, list[Any]]] = {}
        for key, values in axes.items():
            if isinstance(values, dict):
                if key not in SAMPLE_KEYS:
                    raise ValueError(f"axis {key!r}: {{samples = N}} is allowed only for {', '.join(SAMPLE_KEYS)}")
                try:
                    out[key] = SamplesAxis.model_validate(values)
                except ValidationError as err:
                    e = err.errors()[0]
                    raise ValueError(f"axis {key!r}: {{samples = N}} needs exactly one key, samples, an integer "
                                     f"1 … 100000 (got {values!r}: {e['msg']})") from None
                continue
            if not isinstance(values, list):
                raise ValueError(f"axis {key!r}: give a list of values or {{samples = N}}, got {values!r}")
            out[key] = values
            if isinstance(values, list):
                if not values:
                    raise ValueError(f"axis {key!r} has no values")
                if not all(isinstance(v, (str, int, float, bool)) for v in values):
                    raise ValueError(f"axis {key!r}: values must be numbers, strings or booleans, got {values}")
                if any(isinstance(v, float) and not math.isfinite(v) for v in values):
                    raise ValueError(f"axis {key!r}: values must be finite numbers, got {values}")
                seen: dict[str, Any] = {}
                for v in values:
                    if _value_key(v) in seen:
                        raise ValueError(f"axis {key!r} repeats a value: {seen[_value_key(v)]!r} and {v!r}")
                    seen[_value_key(v)] = v
        return out


def derive_seed(study_seed: int, sample: int) -> int:
    """Road seed [0, 2³²) of sample ``sample``: numpy SeedSequence entropy (study_seed, sample).

    Depends only on the two integers, so it is the same on every machine, in every process and
    whatever order the crossings run in."""
    return int(np.random.SeedSequence([int(study_seed), int(sample)]).generate_state(1, np.uint32)[0])


def set_dotted(data: dict[str, Any], key: str, value: Any) -> None:
    """Set ``data["a"]["b"] = value`` for key "a.b" (creating the table if needed)."""
    parts = key.split(".")
    node = data
    for p in parts[:-1]:
        node = node.setdefault(p, {})
        if not isinstance(node, dict):
            raise StudyError(f"axes.{key!r}: {p!r} is not a table in the base scenario")
    node[parts[-1]] = value


#: scenario sections that are arrays of tables: what to sweep instead
ARRAY_SECTIONS = {
    "vehicles": "sweep crossing.speed_kmh (or crossing.speed), the speed of every listed vehicle that gives none "
                "of its own, or write one study per vehicle layout",
}


def _check_key(key: str, base: dict[str, Any]) -> None:
    if key == "method":
        raise StudyError(f"axes.'method': method is a study key ({' or '.join(STUDY_METHODS)}), not a scenario key to "
                         "sweep: run one study per method")
    parts = key.split(".")
    if len(parts) == 1:
        if key not in Scenario.model_fields:
            raise StudyError(f"axes.{key!r}: unknown scenario key; allowed top-level keys: "
                             f"{', '.join(Scenario.model_fields)} (use dotted keys like \"tire.n_points\")")
        return
    section = parts[0]
    if section not in Scenario.model_fields or section == "name":
        raise StudyError(f"axes.{key!r}: unknown scenario section {section!r}; allowed: "
                         f"{', '.join(k for k in Scenario.model_fields if k != 'name')}")
    if section in ARRAY_SECTIONS:
        raise StudyError(f"axes.{key!r}: [[{section}]] is an array of tables, and an axis cannot address one of its "
                         f"entries; {ARRAY_SECTIONS[section]}")
    if parts[:2] == ["bridge", "deck"] and len(parts) == 3:  # a slab-on-girder deck parameter
        from vbikit.scenario.deck import SCENARIO_PARAMETERS

        if parts[2] not in SCENARIO_PARAMETERS:
            raise StudyError(f"axes.{key!r}: unknown [bridge.deck] key {parts[2]!r}; allowed: {', '.join(SCENARIO_PARAMETERS)}")
        return
    if len(parts) != 2:
        raise StudyError(f"axes.{key!r}: only section.key axes (e.g. \"tire.n_points\") and bridge.deck.key axes "
                         "are supported")
    if section == "vehicle":  # preset parameters are checked by the scenario validation
        return
    names = section_keys(section)
    if parts[1] not in names:
        raise StudyError(f"axes.{key!r}: unknown key {parts[1]!r} in [{section}]; allowed: {', '.join(names)}")


@dataclass(frozen=True)
class Axis:
    """One study dimension: scenario ``key``, dimension ``name`` in the dataset, ``values``
    (for a samples axis the sample indices) and, for a samples axis, the derived ``seeds``."""

    key: str
    name: str
    values: tuple
    seeds: Optional[tuple] = None

    @property
    def is_samples(self) -> bool:
        return self.seeds is not None

    def scenario_value(self, i: int) -> Any:
        return self.seeds[i] if self.seeds is not None else self.values[i]

    @property
    def coordinate_values(self) -> list:
        """The values as the dataset's coordinate holds them: as given, except an absolute path of an axis over
        a file (``road.profile_file``, …) by its file name (``vbikit._files.shared_spec``: a shared dataset names
        no folder; the files are told apart by their SHA-256 in the study's identity), two equal names
        numbered (``road.csv (1)``, ``road.csv (2)``) so that the coordinate still tells the values apart."""
        from vbikit._files import shared_spec

        shared = shared_spec(list(self.values), self.key.split(".")[-1])
        if len(set(map(str, shared))) == len(shared):
            return shared
        return [f"{v} ({i + 1})" if shared.count(v) > 1 else v for i, v in enumerate(shared)]


def cf_key_unit(unit: str, text: bool) -> str:
    """A scenario key's unit in the dataset's CF/UDUNITS spelling ("km/h" → "km h-1", "-" → "1");
    "" for text-valued coordinates (categories have no unit)."""
    from vbikit.outputs import cf_unit

    if text:
        return ""
    return "1" if unit == "" else cf_unit(unit)


def dim_name(key: str) -> str:
    """Dataset dimension name of an axis key ("tire.n_points" -> "tire_n_points"; road.seed samples -> "sample")."""
    return key.replace(".", "_").replace("-", "_")


@dataclass(frozen=True)
class Study:
    """A validated study: base scenario dict, axes, seed, batch size, the outputs to reduce
    (``outputs``: names of the catalogue ``vbikit.outputs``; None: all of them) and the source text."""

    name: str
    seed: int
    batch_size: int
    histories: bool
    base: dict[str, Any]
    axes: tuple[Axis, ...]
    base_dir: Path
    outputs: Optional[tuple[str, ...]] = None
    method: str = STUDY_METHODS[0]

    @property
    def output_names(self) -> tuple[str, ...]:
        """The outputs each crossing is reduced to and the dataset holds, in catalogue order: those
        asked for (all by default) and ``vbikit.outputs.QUALITY_OUTPUTS`` always."""
        names = None if self.outputs is None else (*self.outputs, *QUALITY_OUTPUTS)
        return tuple(o.name for o in catalogue_outputs(names=names))

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64)) if self.axes else 1

    def input_sha256(self) -> dict[str, str]:
        """The SHA-256 of each file the study's scenarios read (``vbikit.scenario.schema.INPUT_FILE_KEYS``:
        the base's, by key, and an axis's over such a key, by ``key[i]``); read once per study."""
        kept = self.__dict__.get("_input_sha256")
        if kept is None:
            from vbikit._files import input_digests
            from vbikit.scenario.schema import INPUT_FILE_KEYS, input_paths

            files: dict[str, Any] = dict(input_paths(self.base, self.base_dir))
            for a in self.axes:
                if a.key in INPUT_FILE_KEYS:
                    files |= {f"{a.key}[{i}]": self.base_dir / str(v) for i, v in enumerate(a.values)}
            kept = input_digests(files)
            object.__setattr__(self, "_input_sha256", kept)  # (the study is immutable: its files read once)
        return kept

    def to_json(self) -> str:
        """Canonical JSON of the resolved study (stored in the dataset attributes and used to
        recognise the same study on restart).  No folder: a file the scenarios read is there by its
        content (``input_sha256``; absent when they read none) and an absolute path by its file name
        (``vbikit._files.shared_spec``), so a shared dataset names no folder of the machine it ran on and a
        changed modes or profile file is not taken for the same study."""
        return self._identity(earlier=False)

    def earlier_json(self) -> tuple[str, ...]:
        """The identity as a dataset written before 2026-12-06 holds it (the paths as given, no file's
        content) when it differs from ``to_json``'s: such a finished dataset is still recognised
        (``vbikit.study.run``), as it was then."""
        text = self._identity(earlier=True)
        return () if text == self.to_json() else (text,)

    def finished_json(self) -> tuple[str, ...]:
        """The identities a *finished* dataset of this study may hold besides ``to_json``'s: the earlier
        versions' (``earlier_json``) and, for a study that takes the step for deflections (``resolve``), its
        identity without that key, as a dataset written before 2026-12-07 holds it (then every study took the
        step for every result): such a finished result is still recognised; its parts are not resumed (a
        study's parts are of one step rule)."""
        without = self._identity(earlier=False, resolve=False)
        return tuple(dict.fromkeys(t for t in (*self.earlier_json(), without) if t != self.to_json()))

    @property
    def resolve(self) -> str:
        """What its crossings' automatic step resolves (``Crossing.resolve``): the base's ``crossing.resolve``,
        else what its outputs need (``vbikit.outputs.base_resolve``; ValueError for a base for deflections
        only with outputs that need more, which ``parse_study`` reports)."""
        return base_resolve(self.base, self.output_names)

    def _identity(self, earlier: bool, resolve: bool = True) -> str:
        from vbikit._files import shared_spec

        shared = (lambda v, key="": v) if earlier else shared_spec
        spec = {
            "name": self.name, "seed": self.seed, "batch_size": self.batch_size, "histories": self.histories,
            "base": shared(self.base),
            "axes": {a.key: ({"samples": len(a.values)} if a.is_samples else shared(list(a.values), a.key.split(".")[-1]))
                     for a in self.axes},
        }
        digests = {} if earlier else self.input_sha256()
        if digests:  # absent: no input file (studies and datasets written before the key)
            spec["input_sha256"] = digests
        if self.outputs is not None:  # absent: the whole catalogue (studies and datasets written before the key)
            spec["outputs"] = list(self.outputs)
        if self.method != STUDY_METHODS[0]:  # absent: Monte Carlo (studies and datasets written before the key)
            spec["method"] = self.method
        if resolve and not earlier and self.resolve != "effects":  # absent: the step for every result (before the key)
            spec["resolve"] = self.resolve
        return json.dumps(spec, sort_keys=True)

    def scenario_dict(self, index: tuple[int, ...]) -> dict[str, Any]:
        """The scenario (dict) of the crossing at grid ``index``.  An axis over ``tire.model`` keeps
        the base tire's keys the swept model takes and drops the others (as ``vbikit compare-tires``
        does: a multi-point base's ``n_points`` is not a key of the point tire); keys set by other
        axes stay.  Its ``crossing.resolve`` is what the study's outputs need (``vbikit.outputs.outputs_resolve``:
        "deflections" when they all are), unless the base gives it."""
        data = copy.deepcopy(self.base)
        crossing = data.setdefault("crossing", {})
        if isinstance(crossing, dict):  # (the base's own resolve is kept)
            crossing["resolve"] = self.resolve
        for axis, i in zip(self.axes, index):
            set_dotted(data, axis.key, axis.scenario_value(i))
            if axis.key == "tire.model" and isinstance(data.get("tire"), dict):
                taken = set(TireSpec.keys(data["tire"]["model"])) if data["tire"]["model"] in TIRE_MODELS else None
                swept = {a.key.split(".", 1)[1] for a in self.axes if a.key.startswith("tire.")}
                if taken is not None:
                    data["tire"] = {k: v for k, v in data["tire"].items() if k in taken or k in swept}
        return data

    @property
    def n_batches(self) -> int:
        """len([`batches`][vbikit.study.Study.batches]), without listing them."""
        outer = math.prod(len(a.values) for a in self.axes if a.key not in ROAD_ONLY_KEYS)
        inner = math.prod(len(a.values) for a in self.axes if a.key in ROAD_ONLY_KEYS)
        return outer * -(-inner // self.batch_size)

    def batches(self) -> list[tuple[tuple[int, ...], ...]]:
        """Grid indices grouped into batches: crossings in one batch differ only in road-only
        keys (``ROAD_ONLY_KEYS``), at most ``batch_size`` each, in a fixed order."""
        outer = [k for k, a in enumerate(self.axes) if a.key not in ROAD_ONLY_KEYS]
        inner = [k for k, a in enumerate(self.axes) if a.key in ROAD_ONLY_KEYS]
        out: list[tuple[tuple[int, ...], ...]] = []
        for o in itertools.product(*(range(len(self.axes[k].values)) for k in outer)):
            group = []
            for i in itertools.product(*(range(len(self.axes[k].values)) for k in inner)):
                idx = [0] * len(self.axes)
                for k, v in zip(outer, o):
                    idx[k] = v
                for k, v in zip(inner, i):
                    idx[k] = v
                group.append(tuple(idx))
            for s in range(0, len(group), self.batch_size):
                out.append(tuple(group[s:s + self.batch_size]))
        return out


def parse_study(data: dict[str, Any], base_dir: Path | str = ".") -> Study:
    """Validate a study given as a dict (the parsed TOML): the study keys, every axis key, and
    every combination of axis values as a scenario."""
    base_dir = Path(base_dir)
    try:
        raw = StudyFile.model_validate(data)
    except ValidationError as err:
        raise StudyError(validation_message(err, "invalid study", f"unknown key; allowed keys: {', '.join(StudyFile.model_fields)}")) from None
    base = copy.deepcopy(raw.base)
    if "scenario" in base:
        if len(base) != 1:
            raise StudyError("base: give either scenario = \"path.toml\" or the scenario tables inline, not both")
        try:
            base = read_toml(base_dir / str(base["scenario"]), StudyError)
        except StudyError as err:
            raise StudyError(f"base.scenario: {err}") from None
    axes: list[Axis] = []
    for key, values in raw.axes.items():
        _check_key(key, base)
        if isinstance(values, SamplesAxis):
            n = values.samples
            axes.append(Axis(key, "sample", tuple(range(n)), tuple(derive_seed(raw.seed, i) for i in range(n))))
        else:
            axes.append(Axis(key, dim_name(key), tuple(values)))
    if len({a.name for a in axes}) != len(axes):
        raise StudyError("axes: two axes map to the same dataset dimension name")
    if raw.method == "pem":
        _check_pem(raw, axes)
    study = Study(raw.name, raw.seed, raw.batch_size, raw.histories, base, tuple(axes), base_dir,
                  None if raw.outputs is None else tuple(raw.outputs), raw.method)
    try:
        study.resolve
    except ValueError as err:
        raise StudyError(str(err)) from None
    # validate the base alone (clear message for base errors) and every combination of the
    # non-sample axes (sample axes only change the seed, which is always valid)
    try:
        parse_scenario(base, base_dir)
    except ScenarioError as err:
        if not axes:
            raise StudyError(f"base: {err}") from None
    for combo in schema_combinations(axes):
        try:
            scenario = parse_scenario(study.scenario_dict(tuple(combo)), base_dir)
            if study.method == "pem":
                from vbikit.scenario.pipeline import check_random_road

                check_random_road(scenario)
        except ScenarioError as err:
            where = ", ".join(f"{a.key} = {a.values[v]!r}" for a, v in zip(axes, combo) if not a.is_samples and
                              len(a.values) > 1) or "no axes"
            raise StudyError(f"base + axes ({where}): {err}") from None
    return study


def _check_pem(raw: StudyFile, axes: list[Axis]) -> None:
    """What ``method = "pem"`` cannot take: a road.seed axis (the road is random in every cell, not
    sampled), ``outputs`` and ``histories`` (a cell stores the impact factor's distribution)."""
    for a in axes:
        if a.key == "road.seed":
            raise StudyError('axes."road.seed": method = "pem" treats the road as random in every cell (no sampled '
                             'roads); remove the road.seed axis, or use method = "monte-carlo"')
    if raw.outputs is not None:
        raise StudyError('outputs: method = "pem" stores the impact factor\'s distribution of every cell '
                         '(vbikit.study.pem.PEM_OUTPUTS); remove outputs, or use method = "monte-carlo"')
    if raw.histories:
        raise StudyError('histories: method = "pem" stores no histories; remove histories, or use method = "monte-carlo"')


def schema_combinations(axes: "tuple[Axis, ...] | list[Axis]") -> list[list[int]]:
    """Grid indices whose scenarios, once valid, make every crossing's scenario valid.

    The scenario schema checks each section on its own, so axes of different sections never
    invalidate each other: per section, every combination of that section's value axes (the
    others at their first value) — or, when that product exceeds ``MAX_COMBINATIONS``, every
    pair of its axes with all their value pairs.  Sample axes only change a seed (always valid).
    The count grows with the sum, not the product, of the axes' lengths, so no study hangs here."""
    sections: dict[str, list[int]] = {}
    for k, a in enumerate(axes):
        if not a.is_samples:
            sections.setdefault(a.key.split(".")[0], []).append(k)
    combos: list[list[int]] = [[0] * len(axes)]
    for members in sections.values():
        sizes = [len(axes[k].values) for k in members]
        groups = [members] if math.prod(sizes) <= MAX_COMBINATIONS else list(itertools.combinations(members, 2))
        for group in groups:
            for values in itertools.product(*(range(len(axes[k].values)) for k in group)):
                idx = [0] * len(axes)
                for k, v in zip(group, values):
                    idx[k] = v
                combos.append(idx)
    return combos


def study_from_toml(text: str, base_dir: Path | str = ".", source: str = "study") -> Study:
    """Validate a study given as TOML text."""
    return parse_study(parse_toml(text, source, StudyError), base_dir)


def load_study(path: str | Path) -> Study:
    """Read and validate a TOML study file."""
    return parse_study(read_toml(path, StudyError, "study file"), Path(path).parent)
