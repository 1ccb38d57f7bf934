"""Study axes over slab-on-girder deck parameters (``bridge.deck.<key>``): validated like scenario
keys, labelled with the deck parameter's unit, and each crossing equal to the same scenario run
alone (the skew deck's default response point is its default girder's own midspan)."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.study import StudyError, parse_study, run_study

DECK_STUDY = {
    "name": "IM against skew",
    "seed": 5,
    "batch_size": 4,
    "base": {
        "bridge": {"model": "paper-bridge-2", "n_modes": 4, "deck": {"n_elements": 16}},
        "vehicle": {"model": "two-axle"},
        "tire": {"model": "point"},
        "road": {"class": "C", "length": 200},
        "crossing": {"speed_kmh": 90},
    },
    "axes": {"bridge.deck.skew": [0.0, 25.0], "road.seed": {"samples": 2}},
}


def test_deck_axis_runs_and_equals_single_crossings(tmp_path):
    from vbikit.analysis import point_response
    from vbikit.scenario import build, parse_scenario
    from vbikit.solve import simulate

    study = parse_study(DECK_STUDY)
    ds = run_study(study, tmp_path / "skew.nc", workers=1)
    assert ds["bridge_deck_skew"].attrs["units"] == "degrees"
    for idx in [(0, 1), (1, 0), (1, 1)]:
        built = build(parse_scenario(study.scenario_dict(idx)))
        assert built.crossing.bridge.skew == DECK_STUDY["axes"]["bridge.deck.skew"][idx[0]]
        resp = point_response(simulate(built.crossing), built.response_x, built.response_y)
        assert ds["impact_factor"].values[idx] == pytest.approx(resp.displacement_impact.impact_factor, abs=1e-12)
    # the skew changes the result (same roads)
    assert not np.allclose(ds["impact_factor"].values[0], ds["impact_factor"].values[1], rtol=1e-3)


@pytest.mark.parametrize("key, message", [("bridge.deck.skw", "unknown \\[bridge.deck\\] key 'skw'"),
                                          ("bridge.deck.skew.x", "only section.key axes")])
def test_deck_axis_errors_name_the_key(key, message):
    bad = {**DECK_STUDY, "axes": {key: [0.0, 10.0]}}
    with pytest.raises(StudyError, match=message):
        parse_study(bad)


def test_deck_axis_values_are_checked_before_running():
    """A deck value the model refuses is found by the study's preflight (``vbikit study run`` calls
    it before any crossing), naming the axis value."""
    from vbikit.study.check import check_study

    study = parse_study({**DECK_STUDY, "axes": {"bridge.deck.skew": [0.0, 60.0]}})
    with pytest.raises(StudyError, match="bridge.deck.skew = 60.0.*skew must be an angle in degrees within -45 … 45"):
        check_study(study)
