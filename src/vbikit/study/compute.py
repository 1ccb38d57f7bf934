"""One batch of a study: build its crossings, run them with one shared :class:`BatchSolver`, and
reduce each to impact factors and peaks (the function executed by local or Dask workers)."""
from __future__ import annotations

import json
from collections import OrderedDict

import numpy as np
from numpy.typing import NDArray

from vbikit.analysis.effects import contact_influence, load_effect_response
from vbikit.analysis.impact import impact_factor
from vbikit.road.profile import RoadProfile
from vbikit.scenario.build import build, build_right_road, build_road
from vbikit.scenario.schema import Scenario, ScenarioError, parse_scenario
from vbikit.solve.batch import BatchSolver
from vbikit.solve.result import check_finite
from vbikit.study.spec import Study

#: per-crossing outputs: name -> (units, description)
OUTPUTS: dict[str, tuple[str, str]] = {
    "impact_factor": ("1", "IM of the response-point deflection, (R_dyn,max - R_st,max) / R_st,max"),
    "strain_impact_factor": ("1", "IM of the response-point bottom-fibre strain"),
    "max_dynamic_displacement": ("m", "peak deflection in the static peak's direction (z up: negative)"),
    "max_static_displacement": ("m", "peak static deflection under the moving static wheel loads"),
    "max_dynamic_strain": ("1", "peak bottom-fibre strain (tension positive)"),
    "max_static_strain": ("1", "peak static bottom-fibre strain"),
    "max_abs_velocity": ("m s-1", "peak |deck velocity| at the response point"),
    "max_abs_acceleration": ("m s-2", "peak |deck acceleration| at the response point"),
    "min_tire_force": ("N", "smallest wheel force over the crossing (0 = a tire lost contact)"),
    **{f"{kind}_{name}": (units, f"{kind} ({what}): {desc}; the first [response] {kind} of the base scenario "
                                  "(default: the bridge's first), NaN if the bridge has none")
       for kind, what, units in (("moment", "sagging positive", "N m"), ("shear", "dM/dx", "N"), ("reaction", "upward", "N"))
       for name, desc in (("impact_factor", "IM in the static peak's direction"), ("static_peak", "static peak"),
                          ("dynamic_peak", "dynamic peak in the static peak's direction"))},
    "dt": ("s", "time step"),
    "n_steps": ("1", "number of time steps"),
}


#: roads built in this process, by their scenario [road] table (a study reuses the same seeds
#: for every n, speed and tire; 64 profiles of 2^17 samples ≈ 130 MB)
_ROADS: "OrderedDict[str, tuple[RoadProfile | None, RoadProfile | None]]" = OrderedDict()
_ROAD_CACHE_SIZE = 64


def _road(scenario: Scenario, data: dict) -> tuple[RoadProfile | None, RoadProfile | None]:
    """The scenario's roads (left, right wheel line or None), built once per process (same
    functions as ``build``, so identical)."""
    key = json.dumps([data.get("road", {}), str(scenario.base_dir)], sort_keys=True)
    if key in _ROADS:
        _ROADS.move_to_end(key)
        return _ROADS[key]
    try:
        left = build_road(scenario.road, scenario)
        road = (left, build_right_road(scenario.road, scenario, left))
    except ValueError as err:
        raise ScenarioError(str(err)) from None
    _ROADS[key] = road
    if len(_ROADS) > _ROAD_CACHE_SIZE:
        _ROADS.popitem(last=False)
    return road


def run_batch(study: Study, batch: tuple[tuple[int, ...], ...], threads: int = 1) -> dict[str, NDArray]:
    """Run the crossings at grid indices ``batch`` (they differ only in road-only keys).

    Returns arrays of length len(batch) for every name in :data:`OUTPUTS`, plus ``index``
    (len(batch), n_axes) and, if the study stores histories, ``displacement_history``
    (len(batch), n_t) [m] (rows padded with NaN to the longest)."""
    dicts = [study.scenario_dict(idx) for idx in batch]
    scenarios = [parse_scenario(d, study.base_dir) for d in dicts]
    roads = [_road(sc, d) for sc, d in zip(scenarios, dicts)]
    # the crossings differ only in the road: build the first one, the others are its road swapped
    built = [build(scenarios[0])]
    template = built[0].crossing
    solver = BatchSolver(template)
    bridge = template.bridge
    x = float(getattr(bridge, "default_response_x", bridge.span / 2)) if built[0].response_x is None else float(built[0].response_x)
    y = built[0].response_y
    phi = bridge.mode_shapes([x], [y])[0]
    eps = bridge.strain_shapes([x], [y])[0]

    static: dict[float, tuple[NDArray, NDArray]] = {}  # static deflection and strain, per step
    effects = {kind: next((e for e in built[0].load_effects if e.kind == kind), None) for kind in ("moment", "shear", "reaction")}
    method = built[0].load_effect_method
    influence: dict[tuple[str, float], NDArray] = {}  # contact influence matrices, per effect and step

    def effect_row(result) -> dict[str, float]:
        row: dict[str, float] = {}
        for kind, effect in effects.items():
            if effect is None:
                row |= {f"{kind}_impact_factor": np.nan, f"{kind}_static_peak": np.nan, f"{kind}_dynamic_peak": np.nan}
                continue
            key = (kind, result.dt)
            if method == "mode-acceleration" and key not in influence:
                influence[key] = contact_influence(result, effect)
            im = load_effect_response(result, effect, method, influence=influence.get(key)).impact
            row |= {f"{kind}_impact_factor": im.impact_factor, f"{kind}_static_peak": im.static_peak,
                    f"{kind}_dynamic_peak": im.dynamic_peak}
        return row

    def reduce(result):
        check_finite(result)
        if result.dt not in static:
            xi_st = solver.static_modal(result.dt)
            static[result.dt] = (xi_st @ phi, xi_st @ eps)
        disp, strain = result.xi @ phi, result.xi @ eps
        d = impact_factor(result.time, disp, static[result.dt][0], result.xi_dot @ phi)
        s = impact_factor(result.time, strain, static[result.dt][1], result.xi_dot @ eps)
        row = {
            "impact_factor": d.impact_factor, "strain_impact_factor": s.impact_factor,
            "max_dynamic_displacement": d.dynamic_peak, "max_static_displacement": d.static_peak,
            "max_dynamic_strain": s.dynamic_peak, "max_static_strain": s.static_peak,
            "max_abs_velocity": float(np.abs(result.xi_dot @ phi).max()),
            "max_abs_acceleration": float(np.abs(result.xi_ddot @ phi).max()),
            "min_tire_force": float(result.wheel_forces.min()) if result.wheel_forces.size else np.nan,
            "dt": result.dt, "n_steps": float(result.n_steps),
        } | effect_row(result)
        return row, (disp if study.histories else None)

    rows = solver.run_many(roads, reduce=reduce, threads=threads)
    out: dict[str, NDArray] = {k: np.array([r[0][k] for r in rows], float) for k in OUTPUTS}
    out["index"] = np.array(batch, np.int64).reshape(len(batch), len(study.axes))
    if study.histories:
        n_t = max(r[1].size for r in rows)
        hist = np.full((len(rows), n_t), np.nan)
        for k, r in enumerate(rows):
            hist[k, : r[1].size] = r[1]
        out["displacement_history"] = hist
    return out
