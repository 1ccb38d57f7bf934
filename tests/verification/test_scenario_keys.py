"""Every scenario key changes the result (or is listed as output-only, with the reason).

The keys are enumerated from the schema itself (``vbikit.scenario.schema``: every section's
fields, the defect fields, every tire model's and vehicle preset's parameters, every
``[bridge.deck]`` parameter),
so a key added to the schema without a case here fails :func:`test_every_schema_key_has_a_case`.
Each case runs the same small scenario twice through the public path (validate → build →
simulate → summary, as ``vbikit run``) with two values of the key, and the computed outputs
(impact factors, peaks, frequencies, tire forces, patch lengths, duration — not the echo of
the inputs) must differ.  A key silently ignored by the build or the solver leaves them equal.
"""
from __future__ import annotations

import copy
import inspect
import json
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

from vbikit.analysis import girder_responses, point_response, summary
from vbikit.analysis.effects import load_effect_report
from vbikit.bridge.girder_deck import SlabOnGirderBridge
from vbikit.bridge.modefile import write_modes
from vbikit.scenario import build, parse_scenario
from vbikit.scenario.deck import SCENARIO_PARAMETERS
from vbikit.scenario.schema import DefectSpec, Scenario, TireSpec, VehicleEntry, section_keys
from vbikit.solve import integrator_names, simulate
from vbikit.vehicle.presets import VEHICLE_PRESETS

#: keys that do not enter the computation
OUTPUT_ONLY = {
    "name": "a label printed with the results and written to the summary; no model reads it",
}
# small, fast crossings: a 10 m beam with 3 modes, a quarter car at 20 m/s on an ISO C road
BEAM = {"model": "beam", "span": 10.0, "EI": 5.0e9, "mass_per_length": 5000.0, "n_modes": 3}
DECK = {"span": 8.0, "n_girders": 3, "n_elements": 10}
BASE: dict = {
    "name": "scenario-keys",
    "bridge": BEAM,
    "vehicle": {"model": "quarter-car"},
    "tire": {"model": "point"},
    "road": {"class": "C", "seed": 1, "length": 100.0},
    "crossing": {"speed": 20.0, "approach": 2.0, "free_vibration": 0.1},
}
SLAB = {"bridge": {"model": "slab-on-girder", "n_modes": 4, "deck": DECK, "span": None, "EI": None, "mass_per_length": None},
        "vehicle": {"model": "two-axle"}}
BUMP = {"road": {"class": "none", "defects": [{"kind": "bump", "position": -1.0, "height": 0.08}]}}
CONT = {**BASE, "bridge": {"model": "continuous-beam", "spans": [5.0, 5.0], "EI": 5.0e9, "mass_per_length": 5000.0,
                           "n_modes": 3}}


def _merge(base: dict, patch: dict) -> dict:
    out = copy.deepcopy(base)
    for key, value in patch.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict) and key not in ("deck",):
            out[key] = _merge(out[key], value)
        elif value is None:
            out.pop(key, None)
        else:
            out[key] = copy.deepcopy(value)
    return out


def _set(data: dict, dotted: str, value) -> dict:
    """``data`` with the key at ``dotted`` (section.key, section.deck.key, road.defects.key) set."""
    out = copy.deepcopy(data)
    parts = dotted.split(".")
    node = out
    for p in parts[:-1]:
        node = node[p][0] if isinstance(node.get(p), list) else node.setdefault(p, {})
    if value is None:
        node.pop(parts[-1], None)
    else:
        node[parts[-1]] = value
    return out


def _default(preset: str, param: str):
    return inspect.signature(VEHICLE_PRESETS[preset].build).parameters[param].default


#: the axle-load truck ("axles" preset): 4 axles, single + tandem + single (tractor-semitrailer)
AXLES = {"model": "axles", "axle_loads": [50e3, 80e3, 80e3, 90e3], "axle_spacings": [4.0, 1.3, 6.0]}
AXLE_VALUES = {
    "axle_loads": ([50e3, 80e3, 80e3, 90e3], [50e3, 80e3, 80e3, 110e3]),
    "axle_spacings": ([4.0, 1.3, 6.0], [4.0, 1.3, 7.0]),
    "groups": (None, ["single", "walking-beam", "single"]),
    "tractor_groups": (None, 0),
    "unsprung_masses": (None, [700.0, 1100.0, 1100.0, 1500.0]),
    "half_track": (0.9, 1.0),  # roll: needs different profiles under the two wheel lines (see below)
    "tire_deflection": (0.019, 0.025),
    "suspension_deflection": (0.033, 0.04),
    "suspension_damping_ratio": (0.1, 0.2),
    "tire_damping_ratio": (0.03, 0.06),
}


def _cases(files: dict[str, str]) -> dict[str, tuple[dict, object, object]]:
    """key → (scenario the key is varied in, value a, value b); a value None = key left out."""
    cases: dict[str, tuple[dict, object, object]] = {
        "bridge.model": (BASE, "beam", "paper-bridge-1-beam"),  # b: the preset (beam properties removed below)
        "bridge.span": (BASE, 10.0, 12.0),
        "bridge.EI": (BASE, 5.0e9, 6.0e9),
        "bridge.mass_per_length": (BASE, 5000.0, 6000.0),
        "bridge.damping_ratio": (BASE, 0.02, 0.05),
        "bridge.n_modes": (BASE, 3, 5),
        "bridge.neutral_axis_depth": (BASE, 0.5, 0.6),  # strain only
        "bridge.modes_file": (_merge(BASE, {"bridge": {"model": "modes-file", "modes_file": files["a"], "span": None,
                                                       "EI": None, "mass_per_length": None}}), files["a"], files["b"]),
        "bridge.deck": (_merge(BASE, SLAB), DECK, dict(DECK, span=9.0)),
        "tire.model": (BASE, "point", "multipoint"),
        "tire.n_points": (_merge(BASE, {"tire": {"model": "multipoint"}}), 3, 6),
        "tire.contact_length": (_merge(BASE, {"tire": {"model": "multipoint"}}), 0.254, 0.5),
        "tire.layout": (_merge(BASE, {"tire": {"model": "multipoint", "n_points": 3}}), "ends", "cells"),
        "tire.radius": (_merge(BASE, {"tire": {"model": "disk"}}), 0.5, 0.6),
        "tire.disk_spacing": (_merge(BASE, {"tire": {"model": "disk"}}), 0.01, 0.005),
        # a tire that would pull over an 80 mm bump (model data §3: tires cannot pull)
        "tire.loss_of_contact": (_merge(BASE, BUMP), True, False),
        "road.class": (BASE, "C", "D"),
        "road.seed": (BASE, 1, 2),
        "road.profile_file": (_merge(BASE, {"road": {"class": None, "seed": None, "length": None}}), files["road_a"],
                              files["road_b"]),
        "road.spacing": (BASE, 0.01, 0.02),
        "road.n_min": (BASE, 0.01, 0.02),
        "road.n_max": (BASE, 4.0, 2.0),
        "road.phi0": (_merge(BASE, {"road": {"class": "psd"}}), 64e-6, 128e-6),
        "road.n0": (_merge(BASE, {"road": {"class": "psd", "phi0": 64e-6}}), 0.1, 0.2),
        "road.exponent": (_merge(BASE, {"road": {"class": "psd", "phi0": 64e-6}}), 2.0, 2.5),
        "road.length": (BASE, 100.0, 200.0),
        # two wheel lines: the two-axle truck; coherence < 1 gives the right line its own profile
        "road.right_coherence": (_merge(BASE, {"vehicle": {"model": "two-axle"}}), 1.0, 0.5),
        "road.profile_file_right": (_merge(BASE, {"vehicle": {"model": "two-axle"},
                                                  "road": {"class": None, "seed": None, "length": None,
                                                           "profile_file": files["road_a"]}}),
                                    files["road_a"], files["road_b"]),
        "road.defects": (BASE, [], [{"kind": "depression", "position": 2.0}]),
        "crossing.speed": (BASE, 20.0, 22.0),
        "crossing.speed_kmh": (_merge(BASE, {"crossing": {"speed": None}}), 72.0, 80.0),
        "crossing.acceleration": (BASE, 0.0, 1.0),
        "crossing.approach": (BASE, 2.0, 3.0),
        "crossing.run_in": (BASE, 0.0, 20.0),
        "crossing.free_vibration": (BASE, 0.1, 0.3),
        "crossing.dt": (BASE, 2e-4, 1e-4),
        # the 15.7 Hz beam's first-period term sets the exact integrator's step: 0.64 ms, 1.27 ms for deflections
        "crossing.resolve": (BASE, "effects", "deflections"),
        "crossing.lateral_offset": (_merge(BASE, SLAB), 0.0, 1.0),
        "response.x": (BASE, 5.0, 3.0),
        "response.y": (_merge(BASE, SLAB), 0.0, 1.0),
        "response.girder": (_merge(BASE, SLAB), 1, 2),
        "response.points": (BASE, [{"x": 5.0}, {"x": 3.0}], [{"x": 3.0}, {"x": 5.0}]),  # the first is the headline
        # continuous beams and load effects (moment / shear / reaction blocks are outputs)
        "bridge.spans": (CONT, [5.0, 5.0], [4.0, 6.0]),
        "bridge.support_stiffness": (CONT, None, [1e8, 1e8, 1e8]),
        "bridge.rotational_stiffness": (CONT, None, [1e9, 0.0]),
        "bridge.elements_per_span": (CONT, 10, 20),
        "bridge.damage": (CONT, [], [{"position": 2.0, "length": 1.0, "severity": 0.3}]),
        "response.moment": (CONT, [2.5], [5.0]),
        "response.shear": (CONT, [0.0], [5.0]),
        "response.reaction": (CONT, [0], [1]),
        "response.load_effect_method": (CONT, "mode-acceleration", "mode-superposition"),
    }
    default = Scenario.model_fields["crossing"].annotation.model_fields["integrator"].default
    for integrator in (name for name in integrator_names() if name != default):
        cases[f"crossing.integrator={integrator}"] = (BASE, default, integrator)
    defect = _merge(BASE, {"road": {"defects": [{"kind": "depression", "position": 2.0}]}})
    cases |= {
        "road.defects.kind": (_merge(defect, {"road": {"defects": [{"kind": "pothole", "position": 2.0}]}}),
                              "pothole", "depression"),
        "road.defects.position": (defect, 2.0, 4.0),
        "road.defects.depth": (defect, 0.02, 0.04),
        "road.defects.height": (_merge(BASE, {"road": {"defects": [{"kind": "bump", "position": 2.0}]}}), 0.02, 0.04),
        "road.defects.length": (defect, 0.6, 1.2),
        "road.defects.ramp": (defect, 0.05, 0.2),
        "road.defects.shape": (defect, "trapezoid", "cosine"),
    }
    for preset in VEHICLE_PRESETS.values():
        for param in preset.parameters:
            if preset.name == "axles":
                a, b = AXLE_VALUES[param]
                road = {"right_coherence": 0.5} if param == "half_track" else {}
                cases[f"vehicle.{param}@axles"] = (_merge(BASE, {"vehicle": AXLES, "road": road}), a, b)
                continue
            d = float(_default(preset.name, param))
            cases[f"vehicle.{param}@{preset.name}"] = (_merge(BASE, {"vehicle": {"model": preset.name}}), d,
                                                       1.5 * d if d > 0 else 5e3)
    cases["vehicle.model"] = (BASE, "quarter-car", "sprung-mass")
    # [[vehicles]] with one entry and no motion of its own: the same crossing as [vehicle]
    listed = _merge(BASE, {"vehicle": None, "vehicles": [{"model": "quarter-car"}]})
    cases["vehicles.model"] = (listed, "quarter-car", "sprung-mass")
    cases["vehicles.<parameters>"] = (listed, None, 2.0e6)  # preset parameters, here tire_stiffness
    slab = _merge(BASE, SLAB)
    # the motion of each [[vehicles]] entry (several-vehicle solver)
    for key, (a, b) in {"tire": ({"model": "point"}, {"model": "multipoint"}), "direction": ("+x", "-x"),
                        "speed": (20.0, 15.0), "speed_kmh": (None, 50.0), "acceleration": (0.0, 1.0)}.items():
        cases[f"vehicles.{key}"] = (listed, a, b)
    # one vehicle's entry time only shifts the clock: two vehicles, the first one's entry moves
    two = _merge(BASE, {"vehicle": None, "vehicles": [{"model": "quarter-car"}, {"model": "quarter-car", "entry_time": 0.3}]})
    cases["vehicles.entry_time"] = (two, 0.0, 0.6)
    cases["vehicles.lateral_offset"] = (_merge(slab, {"vehicle": None, "vehicles": [{"model": "two-axle"}]}), 0.0, 0.5)
    deck_values = {
        "span": (8.0, 9.0), "n_girders": (3, 4), "girder_spacing": (2.13, 2.5), "overhang": (0.615, 1.0),
        "girder": ("II", "III"), "deck_thickness": (0.2, 0.25), "E_girder": (36e9, 30e9), "E_deck": (33e9, 28e9),
        "poisson": (0.2, 0.3), "density": (2400.0, 2500.0), "girder_torsion_constant": (None, 0.05),
        "diaphragms": (None, [4.0]), "diaphragm_width": (0.25, 0.5), "diaphragm_depth": (None, 0.8),
        "bearing_stiffness": (None, 1e8), "parapet_EI": (0.0, 1e9), "parapet_mass": (0.0, 500.0),
        "extra_mass_per_area": (0.0, 200.0), "max_frequency": (None, 60.0), "n_elements": (10, 12),
        "default_lateral_offset": (0.0, 0.5), "default_girder": (1, 2), "spans": (None, [4.0, 4.0]), "skew": (0.0, 15.0),
    }
    for key, (a, b) in deck_values.items():
        base = slab if key not in ("diaphragm_width", "diaphragm_depth") else _set(slab, "bridge.deck.diaphragms", [4.0])
        cases[f"bridge.deck.{key}"] = (base, a, b)
    return cases


def schema_keys() -> set[str]:
    """Every key a scenario may hold, from the schema (deck and vehicle parameters included)."""
    keys = set()
    for section in Scenario.model_fields:  # a section's keys: of every kind of [bridge], say
        keys |= {f"{section}.{key}" for key in section_keys(section)} or {section}
    keys |= {f"road.defects.{f.alias or n}" for n, f in DefectSpec.model_fields.items()}
    keys |= {f"tire.{k}" for k in TireSpec.keys()}  # every registered tire model's parameters
    keys |= {f"bridge.deck.{k}" for k in SCENARIO_PARAMETERS}
    keys |= {f"vehicle.{param}@{p.name}" for p in VEHICLE_PRESETS.values() for param in p.parameters}
    keys |= {f"vehicles.{f.alias or n}" for n, f in VehicleEntry.model_fields.items()} | {"vehicles.<parameters>"}
    keys.discard("vehicles")
    return keys


def _key_of(case: str) -> str:
    return case.split("=")[0]


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, str]:
    d: Path = tmp_path_factory.mktemp("keys")
    write_modes(SlabOnGirderBridge(span=8.0, n_girders=3, n_elements=10, n_modes=4), d / "a.vbikit-modes")
    write_modes(SlabOnGirderBridge(span=9.0, n_girders=3, n_elements=10, n_modes=4), d / "b.vbikit-modes")
    x = np.arange(-20.0, 40.0, 0.05)
    for name, amp in (("road_a", 0.005), ("road_b", 0.01)):
        (d / f"{name}.csv").write_text("x,z\n" + "".join(f"{xi:.3f},{amp * np.sin(2 * xi):.6f}\n" for xi in x))
    return {"a": str(d / "a.vbikit-modes"), "b": str(d / "b.vbikit-modes"), "road_a": str(d / "road_a.csv"),
            "road_b": str(d / "road_b.csv")}


OUTPUTS = ("impact_factor", "max_dynamic_displacement", "max_static_displacement", "strain_impact_factor",
           "max_dynamic_strain", "max_static_strain", "max_abs_acceleration", "max_abs_velocity", "frequencies_hz",
           "vehicle_frequencies_hz", "static_wheel_loads", "min_wheel_force", "max_wheel_force",
           "contact_length_range", "duration", "n_steps", "girder_impact_factors", "girder_max_dynamic_displacement",
           "moment", "shear", "reaction")


@lru_cache(maxsize=None)
def _outputs(text: str) -> tuple[float, ...]:
    scenario = parse_scenario(json.loads(text))
    built = build(scenario)
    result = simulate(built.crossing)
    response = point_response(result, built.response_x, built.response_y)
    s = summary(result, response, girder_responses(result, built.response_x), built.response_girder)
    s |= load_effect_report(result, built.load_effects, built.load_effect_method, s["response_x"])[0]
    values: list[float] = []
    for key in OUTPUTS:
        v = s.get(key, [])
        if key in ("moment", "shear", "reaction"):  # load-effect blocks: peaks and IM of every section
            v = [e[k] for e in (v["sections"] if v else []) for k in ("static_peak", "dynamic_peak", "impact_factor")]
        v = list(v.values()) if isinstance(v, dict) else v
        values += list(np.ravel(np.asarray(v, float)))
    return tuple(values)


def _run(data: dict) -> tuple[float, ...]:
    return _outputs(json.dumps(data, sort_keys=True))


def test_every_schema_key_has_a_case(files):
    covered = {_key_of(c) for c in _cases(files)} | set(OUTPUT_ONLY)
    assert schema_keys() - covered == set(), "schema keys without a case here (add one, or list as output-only)"
    assert covered - schema_keys() == set(), "cases for keys that are no longer in the schema"


CASE_NAMES = sorted(_cases({k: k for k in ("a", "b", "road_a", "road_b")}))


@pytest.mark.parametrize("case", CASE_NAMES)
def test_key_changes_the_result(case, files):
    scenario, a, b = _cases(files)[case]
    key = _key_of(case)
    dotted = key.split("@")[0]
    if key == "bridge.model":  # the preset fixes the beam properties: remove them with the model change
        run_b = _merge(scenario, {"bridge": {"model": b, "span": None, "EI": None, "mass_per_length": None}})
        run_a = _set(scenario, dotted, a)
    elif dotted == "vehicles.<parameters>":
        run_a, run_b = scenario, _set(scenario, "vehicles.tire_stiffness", b)
    else:
        run_a, run_b = _set(scenario, dotted, a), _set(scenario, dotted, b)
    out_a, out_b = _run(run_a), _run(run_b)
    assert len(out_a) != len(out_b) or not np.allclose(out_a, out_b, rtol=1e-9, atol=0), \
        f"{case}: {a!r} and {b!r} give the same results"
