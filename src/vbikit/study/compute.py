"""One batch of a study: build its crossings, run them with one shared ``BatchSolver``, and
reduce each to impact factors and peaks (the function executed by local or Dask workers)."""
from __future__ import annotations

import json
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import Kept
from vbikit.analysis.effects import ContactInfluences, contact_influence_table, load_effect_responses
from vbikit.analysis.plan import point_name
from vbikit.analysis.response import reduce_crossing, strain_mode_errors
from vbikit.outputs import as_number, effect_kinds, outputs
from vbikit.road.profile import RoadProfile
from vbikit.scenario.build import build, build_right_road, build_road
from vbikit.scenario.schema import Scenario, ScenarioError, parse_scenario
from vbikit.solve.batch import BatchSolver
from vbikit.solve.result import check_finite
from vbikit.study.spec import Study

#: a part's array of each crossing's longest span [m] (not an output: the dataset's implausible-deflection
#: check, ``vbikit.analysis.checks.implausible_deflection_dataset_flags``, reads it)
LONGEST_SPAN = "longest_span"
#: a part's array of each crossing's strain-mode error per response point (``vbikit.analysis.response.strain_mode_errors``,
#: once a batch: the static reference does not read the road), where the study stores strain; not an output: the
#: dataset's strain-convergence check (``study_flag_attrs``) reads it; a part of an earlier version lacks it
STRAIN_MODE_ERROR = "strain_mode_error"


def point_names(base: dict) -> list[str] | None:
    """The names of a base scenario's [[response.points]] (None for the [response] shorthand: the
    dataset then has no ``point`` dimension)."""
    points = (base.get("response") or {}).get("points")
    if not isinstance(points, list):
        return None
    return [point_name(i, p.get("name") if isinstance(p, dict) else None) for i, p in enumerate(points, start=1)]


#: roads built in this process, by their scenario [road] table (a study reuses the same seeds
#: for every n, speed and tire; 64 profiles of 2^17 samples ≈ 130 MB)
_ROADS: "Kept[str, tuple[RoadProfile | None, RoadProfile | None]]" = Kept(64)


def _road(scenario: Scenario, data: dict) -> tuple[RoadProfile | None, RoadProfile | None]:
    """The scenario's roads (left, right wheel line or None), built once per process (same
    functions as ``build``, so identical)."""
    key = json.dumps([data.get("road", {}), str(scenario.base_dir)], sort_keys=True)

    def make() -> tuple[RoadProfile | None, RoadProfile | None]:
        try:
            left = build_road(scenario.road, scenario)
            return left, build_right_road(scenario.road, scenario, left)
        except ValueError as err:
            raise ScenarioError(str(err)) from None

    return _ROADS.get(key, make)


def stack_outputs(rows: Sequence[tuple[Sequence[dict], dict]], names: Sequence[str] | None = None) -> dict[str, NDArray]:
    """The catalogue's outputs of reduced crossings (each ``(per-point outputs, per-crossing
    outputs)`` as [`reduce_crossing`][vbikit.analysis.reduce_crossing] gives them) as arrays:
    per-point outputs (rows, points), per-crossing outputs (rows,); an output that does not apply
    is NaN; only the outputs in ``names`` when given (None: all)."""
    out = {o.name: np.array([[as_number(p[o.name]) for p in r[0]] for r in rows], float)
           for o in outputs("point", names)}
    return out | {o.name: np.array([as_number(r[1][o.name]) for r in rows], float) for o in outputs("crossing", names)}


def solver_point(built) -> tuple[float, float]:
    """(x, y) [m] of a built scenario's first response point (x resolved to the bridge's default)."""
    p = built.plan.first
    return (built.crossing.bridge.default_x_at(p.y) if p.x is None else float(p.x)), float(p.y)


def run_batch(study: Study, batch: tuple[tuple[int, ...], ...], threads: int = 1) -> dict[str, NDArray]:
    """Run the crossings at grid indices ``batch`` (they differ only in road-only keys).

    Returns, for every output the study asks for (``Study.output_names``: its ``outputs`` key,
    default the whole catalogue [`vbikit.outputs`][vbikit.outputs]; only these are reduced, and load
    effects only of the kinds they read), an array of length
    len(batch) (per-crossing outputs) or (len(batch), n_points) (per-point outputs, the base
    scenario's response points in order); ``index`` (len(batch), n_axes), ``LONGEST_SPAN`` (len(batch),) [m],
    ``STRAIN_MODE_ERROR`` (len(batch), n_points) where the study stores the strain IM
    (the batch's bridge's longest span, the same for every crossing of a batch) and, if the study
    stores histories, ``displacement_history`` (len(batch), n_t) [m] at the first point (rows
    padded with NaN to the longest)."""
    dicts = [study.scenario_dict(idx) for idx in batch]
    scenarios = [parse_scenario(d, study.base_dir) for d in dicts]
    roads = [_road(sc, d) for sc, d in zip(scenarios, dicts)]
    # the crossings differ only in the road: build the first one, the others are its road swapped
    built = build(scenarios[0])
    solver = BatchSolver(built.crossing)
    plan = built.plan
    phi_first = built.crossing.bridge.mode_shapes(*([v] for v in solver_point(built)))[0]

    static: dict[float, NDArray] = {}  # static modal history, per step
    influence: dict[float, ContactInfluences] = {}  # contact influences of the plan's effects, per step
    names = study.output_names
    asked = effect_kinds(names)
    first = {k: e for k, e in plan.first_effects.items() if k in asked}
    kinds, effects = tuple(first), tuple(first.values())

    def effect_responses(result) -> dict[str, object]:
        if plan.load_effect_method == "mode-acceleration" and effects and result.dt not in influence:
            influence[result.dt] = contact_influence_table(result, effects)
        return dict(zip(kinds, load_effect_responses(result, effects, plan.load_effect_method,
                                                     influence=influence.get(result.dt), check_step=False)))

    strain = "strain_impact_factor" in {o.name for o in outputs("point", names)}
    strain_errors: list[NDArray] = []  # the batch's strain-mode errors (one static reference a batch)

    def reduce(result):
        check_finite(result)
        if result.dt not in static:
            static[result.dt] = solver.static_modal(result.dt)
        if strain and not strain_errors:
            strain_errors.append(strain_mode_errors(result, plan, static[result.dt]))
        points, row = reduce_crossing(result, plan, static[result.dt], effect_responses(result), names)
        return points, row, (result.xi @ phi_first if study.histories else None)

    rows = solver.run_many(roads, reduce=reduce, threads=threads)
    out = stack_outputs(rows, names)
    out["index"] = np.array(batch, np.int64).reshape(len(batch), len(study.axes))
    out[LONGEST_SPAN] = np.full(len(batch), max(built.crossing.bridge.span_lengths))  # one bridge a batch
    if strain_errors:
        out[STRAIN_MODE_ERROR] = np.tile(strain_errors[0], (len(batch), 1))
    if study.histories:
        n_t = max(r[2].size for r in rows)
        hist = np.full((len(rows), n_t), np.nan)
        for k, r in enumerate(rows):
            hist[k, : r[2].size] = r[2]
        out["displacement_history"] = hist
    return out
