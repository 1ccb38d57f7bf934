"""``method = "pem"`` in a study: the key is validated in one place (the study schema) with a
clear error for other values and for what PEM cannot take, and a PEM study's cells are exactly
``vbikit.run_random`` of their scenarios (the same numbers, stored over the axes), although a cell
reduces only what it stores (``random_response(peaks="study")``) and ``run_random`` everything."""
from __future__ import annotations

import copy

import numpy as np
import pytest

from vbikit.scenario import pipeline
from vbikit.study.paper import paper_study_dict
from vbikit.study.pem import PEM_OUTPUTS, _value
from vbikit.study.run import run_study
from vbikit.study.spec import StudyError, parse_study

PEM = {
    "name": "pem study",
    "method": "pem",
    "base": {
        "bridge": {"model": "paper-bridge-2-beam", "n_modes": 2, "damping_ratio": 0.02},
        "vehicle": {"model": "two-axle"},
        "tire": {"model": "point", "loss_of_contact": False},
        "road": {"class": "C", "n_max": 1.0},
        "crossing": {"speed_kmh": 60, "approach": 5},
    },
    "axes": {"crossing.speed_kmh": [60, 90]},
}


_SINGLE_RUNS: dict = {}


def run_random(scenario: dict):
    """``vbikit.run_random`` of ``scenario``, run once for this module: three tests compare cells with
    the same scenario's single run (class C at 60 km/h), a deterministic computation, so they share
    it (the same report object, only read)."""
    import json

    key = json.dumps(scenario, sort_keys=True)
    if key not in _SINGLE_RUNS:
        _SINGLE_RUNS[key] = pipeline.run_random(copy.deepcopy(scenario))
    return _SINGLE_RUNS[key]


def _with(**changes):
    d = copy.deepcopy(PEM)
    d.update(changes)
    return d


def test_method_is_validated_in_the_schema():
    assert parse_study(copy.deepcopy(PEM)).method == "pem"
    assert parse_study(_with(method="monte-carlo")).method == "monte-carlo"
    assert "method" not in parse_study(_with(method="monte-carlo")).to_json()  # old studies keep their checksum
    with pytest.raises(StudyError, match=r"method.*monte-carlo, pem.*'sampling'"):
        parse_study(_with(method="sampling"))
    with pytest.raises(StudyError, match="road.seed.*monte-carlo"):
        parse_study(_with(axes={"road.seed": {"samples": 3}}))
    with pytest.raises(StudyError, match="outputs"):
        parse_study(_with(outputs=["impact_factor"]))
    with pytest.raises(StudyError, match="method is a study key"):
        parse_study(_with(axes={"method": ["pem", "monte-carlo"]}))
    with pytest.raises(StudyError, match="road.class.*random road"):
        parse_study(_with(axes={"road.class": ["C", "none"]}))
    with pytest.raises(StudyError, match="road.defects"):
        d = copy.deepcopy(PEM)
        d["base"]["road"]["defects"] = [{"kind": "depression", "position": 0.0}]
        parse_study(d)


def test_pem_study_cells_equal_run_random(tmp_path):
    study = parse_study(copy.deepcopy(PEM))
    ds = run_study(study, tmp_path / "pem.nc", workers=1)
    assert ds.attrs["method"] == "pem"
    for i, v in enumerate(PEM["axes"]["crossing.speed_kmh"]):
        s = run_random(study.scenario_dict((i,))).summary
        cell = ds.isel(crossing_speed_kmh=i)
        assert float(cell["impact_factor_mean"]) == s["impact_factor_mean"]
        assert float(cell["impact_factor_std"]) == s["impact_factor_std"]
        assert np.array_equal(cell["impact_factor_quantiles"].values, [s["impact_factor_quantiles"][k]
                                                                       for k in ("0.5", "0.9", "0.95")])
        moment = next(e for e in s["effects"] if e["kind"] == "moment")
        assert float(cell["moment_impact_factor_mean"]) == moment["impact_factor_mean"]
        assert float(cell["moment_impact_factor_std"]) == moment["impact_factor_std"]
        assert float(cell["impact_factor_sampling_error"]) == s["impact_factor_sampling_error"]
        assert float(cell["lift_off_probability"]) == s["lift_off_probability"]
        assert float(cell["grid_change"]) == s["grid_change"]  # every channel's, the effects without peaks too
    assert run_study(study, tmp_path / "pem.nc", workers=1).equals(ds)  # the finished study is recognised


def test_paper_studies_run_either_method():
    mc, pem = paper_study_dict("fig6", beam=True), paper_study_dict("fig6", beam=True, method="pem")
    assert "road.seed" in mc["axes"] and "road.seed" not in pem["axes"] and pem["method"] == "pem"
    assert parse_study(pem).size == parse_study(mc).size // 20
    with pytest.raises(ValueError, match="fig11.*defects"):
        paper_study_dict("fig11", method="pem")


def test_paper_figure_of_a_pem_dataset(tmp_path):
    """The paper figure reads a PEM study's stored mean and σ (no sample dimension)."""
    import json

    import xarray as xr

    from vbikit.study.figures import plot_paper_figure
    from vbikit.study.paper import CLASSES, N_POINTS, SPEEDS_5_8

    study = paper_study_dict("fig6", beam=True, method="pem")
    shape = (len(N_POINTS), len(SPEEDS_5_8), len(CLASSES))
    dims = ["tire_n_points", "crossing_speed_kmh", "road_class"]
    values = np.random.default_rng(0).uniform(0.1, 0.3, shape)
    ds = xr.Dataset({"impact_factor_mean": (dims, values), "impact_factor_std": (dims, 0.1 * values)},
                    coords={"tire_n_points": N_POINTS, "crossing_speed_kmh": SPEEDS_5_8,
                            "road_class": np.array(CLASSES, dtype=object)},
                    attrs={"method": "pem", "study": json.dumps(study)})
    png = plot_paper_figure(ds, "fig6", tmp_path / "fig6.png")
    assert png.stat().st_size > 10_000


def test_cells_over_road_class_share_one_pseudo_excitation(tmp_path, monkeypatch):
    """Cells that differ only in the road class are one batch and one pseudo-excitation (the system
    is linear in the road: class C's pseudo responses are class B's times 2, its variances times 4),
    and every stored number equals ``run_random`` of the cell alone, bit for bit (√4 = 2 scales
    exactly in floating point)."""
    import vbikit.random.response as response

    study = parse_study(_with(axes={"road.class": ["B", "C", "D"]}))
    calls = []
    inner = response.pseudo_excitation
    monkeypatch.setattr(response, "pseudo_excitation", lambda *a, **k: calls.append(1) or inner(*a, **k))
    ds = run_study(study, tmp_path / "pem.nc", workers=1)
    assert len(calls) == 1  # not one a cell
    monkeypatch.setattr(response, "pseudo_excitation", inner)
    for i in range(3):
        s = run_random(study.scenario_dict((i,))).summary
        cell = ds.isel(road_class=i)
        for name, (path, _, _) in PEM_OUTPUTS.items():
            assert float(cell[name]) == _value(s, path), (i, name)
        assert np.array_equal(cell["impact_factor_quantiles"].values,
                              [s["impact_factor_quantiles"][k] for k in ("0.5", "0.9", "0.95")])


def test_level_sharing_only_for_roads_that_differ_in_level(monkeypatch):
    """``level_factor``: ISO classes are 4× apart; another exponent, band or coherence is not a level;
    ``run_random_levels`` of scenarios that differ in more (the speed) runs them one by one
    (``run_random`` each: one pseudo-excitation each)."""
    import vbikit.random.response as response
    from vbikit.random import PseudoRoad
    from vbikit.random.response import level_factor
    from vbikit.road.psd import RoadPSD
    from vbikit.scenario.pipeline import run_random_levels

    b = PseudoRoad(RoadPSD.iso("B"))
    assert level_factor(PseudoRoad(RoadPSD.iso("D")), b) == 16.0
    assert level_factor(PseudoRoad(RoadPSD(RoadPSD.iso("B").phi0, 0.1, 2.5)), b) is None
    assert level_factor(PseudoRoad(RoadPSD.iso("C", n_max=2.0)), b) is None
    assert level_factor(PseudoRoad(RoadPSD.iso("C"), 0.5, two_lines=True), b) is None
    calls = []
    inner = response.pseudo_excitation
    monkeypatch.setattr(response, "pseudo_excitation", lambda *a, **k: calls.append(1) or inner(*a, **k))
    study = parse_study(copy.deepcopy(PEM))
    runs = run_random_levels([study.scenario_dict((0,)), study.scenario_dict((1,))], peaks="study")
    assert len(calls) == 2 and len(runs) == 2


def test_a_single_road_is_its_own_level_whatever_its_spectrum():
    """``random_response`` of one road goes through the level sharing: the road against itself is
    factor 1 even for a zero level (φ0 = 0, which the schema allows) or a track spectrum without a φ0
    (the reviewer's case: a zero-level `vbikit run --random` ended in a traceback)."""
    from vbikit.random import PseudoRoad
    from vbikit.random.response import level_factor
    from vbikit.road.psd import RoadPSD
    from vbikit.road.track import TrackPSD

    zero = PseudoRoad(RoadPSD(0.0, 0.1, 2.0, n_max=1.0))
    track = PseudoRoad(TrackPSD.named("german-low"))
    assert level_factor(zero, zero) == 1.0 and level_factor(track, track) == 1.0
    b = PseudoRoad(RoadPSD(16e-6, 0.1, 2.0, n_max=1.0))
    assert level_factor(track, b) is None and level_factor(b, zero) is None  # (not a level of each other)
    assert level_factor(PseudoRoad(RoadPSD(64e-6, 0.1, 2.0, n_max=1.0)), b) == 4.0


def test_a_pem_study_flags_the_cells_whose_single_run_is_flagged(tmp_path):
    """A cell whose ``vbikit run --random`` is flagged ``lift_off`` (a tire lifts off with probability
    above 1e-3, docs/random.md: the linear theory does not hold) was stored without any flag: the PEM
    study's dataset had no ``warnings`` / ``flag_codes`` (red-team pass 2026-12-05).  Now the dataset
    carries the single run's rule over its cells: class C at 60 km/h lifts off (run_random's own flag,
    checked here), class A does not, so 1 of 2 cells is flagged and the flag names class C."""
    from vbikit.analysis.checks import dataset_has_flag

    d = _with(axes={"road.class": ["A", "C"]})
    ds = run_study(parse_study(d), tmp_path / "pem.nc", workers=1)
    single = {cls: run_random(copy.deepcopy(PEM["base"]) | {"road": {"class": cls, "n_max": 1.0}}).summary
              for cls in ("A", "C")}
    assert [f["code"] for f in single["C"]["flags"]] == ["lift_off"]
    assert "lift_off" not in [f["code"] for f in single["A"]["flags"]]
    assert dataset_has_flag(ds.attrs, "lift_off")
    assert "1 of 2 cells: a tire lifts off" in ds.attrs["warnings"]
    assert "road.class = C" in ds.attrs["warnings"]
