"""Load-effect outputs of a study: the first [response] moment / shear / reaction of the base
scenario, equal to the same crossing run alone (simulate + load_effect_response)."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.analysis.effects import load_effect_response
from vbikit.scenario import build, parse_scenario
from vbikit.solve import simulate
from vbikit.study import parse_study, run_study

STUDY = {
    "name": "continuous beam, pier moment",
    "seed": 5,
    "batch_size": 2,
    "base": {
        "bridge": {"model": "continuous-beam", "spans": [20.0, 25.0], "EI": 1.286e10, "mass_per_length": 7537.0,
                   "n_modes": 4},
        "vehicle": {"model": "two-axle"},
        "road": {"class": "C", "length": 200},
        "crossing": {"speed_kmh": 80},
        "response": {"moment": [20.0], "reaction": [1]},
    },
    "axes": {"road.seed": {"samples": 2}},
}


def test_study_stores_load_effect_impact_factors(tmp_path):
    study = parse_study(STUDY)
    ds = run_study(study, tmp_path / "r.nc", workers=1)
    assert ds["moment_static_peak"].attrs["units"] == "N m"
    for k in range(2):
        built = build(parse_scenario(study.scenario_dict((k,))))
        res = simulate(built.crossing)
        pier = load_effect_response(res, built.load_effects[0]).impact
        assert built.load_effects[0].x == 20.0
        assert float(ds["moment_impact_factor"].values[k]) == pytest.approx(pier.impact_factor, abs=1e-9)
        assert float(ds["moment_static_peak"].values[k]) < 0  # hogging over the pier
        shear = next(e for e in built.load_effects if e.kind == "shear")  # default: right of the entry support
        assert float(ds["shear_impact_factor"].values[k]) == pytest.approx(
            load_effect_response(res, shear).impact.impact_factor, abs=1e-9)
    assert np.all(np.isfinite(ds["reaction_impact_factor"].values))
