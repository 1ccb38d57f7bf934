"""A traffic stream's governing events run again at half the time step (``vbikit.traffic.accuracy``):
the dataset states each one's IM change, against an independent half-step run of the same event
(``simulate`` + ``point_response``, not the stream's reduction), and flags a change above the
single run's step tolerance."""
from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from typer.testing import CliRunner

import vbikit.traffic.accuracy as accuracy
from vbikit.analysis import point_response
from vbikit.analysis.effect_step import STEP_TOLERANCE
from vbikit.cli import app
from vbikit.solve import simulate
from vbikit.solve.plan import plan_run
from vbikit.study.run import run_study
from vbikit.traffic import LaneTraffic, synthetic_stream, write_records
from vbikit.traffic.study import traffic_study

#: Bridge 2 beam with 4 modes, a class C road (the step matters there), point tires
BASE = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "road": {"class": "C", "length": 200.0},
        "crossing": {"approach": 5.0, "free_vibration": 0.1}}


@pytest.fixture(scope="module")
def stream_dataset(tmp_path_factory):
    # (seed 12: its governing static and dynamic events differ, so both are checked)
    records = synthetic_stream([LaneTraffic(1, "+x", 900, 80, 5), LaneTraffic(2, "-x", 900, 70, 5)], 12, seed=12)
    job = traffic_study(records, BASE, lanes=[-1.8, 1.8], seed=12, batch_size=6)
    return job, run_study(job, tmp_path_factory.mktemp("s") / "s.nc", workers=1, progress=False)


def _half_step_effect_ims(job, event: int) -> dict[str, float]:
    """The first load effects' IMs of ``event`` at half its step, by ``load_effect_responses`` (the
    catalogue's reduction is not used)."""
    from vbikit.analysis.effects import load_effect_responses

    crossing = job.crossing(event)
    result = simulate(dataclasses.replace(crossing, dt=0.5 * plan_run(crossing).dt))
    effects = job.context().plan.first_effects
    responses = load_effect_responses(result, list(effects.values()), check_step=False)
    return {kind: r.impact.impact_factor for kind, r in zip(effects, responses)}


def _half_step_im(job, event: int) -> float:
    crossing = job.crossing(event)
    result = simulate(dataclasses.replace(crossing, dt=0.5 * plan_run(crossing).dt))
    return point_response(result).displacement_impact.impact_factor


def test_the_governing_events_changes_at_half_the_step_are_those_of_an_independent_run(stream_dataset):
    job, ds = stream_dataset
    a = ds.attrs
    assert a["governing_static_event"] != a["governing_dynamic_event"]  # two events checked
    for which in ("static", "dynamic"):
        e = int(a[f"governing_{which}_event"])
        expected = _half_step_im(job, e) - ds["impact_factor"].values[e]
        assert a[f"governing_{which}_half_step_im_change"] == pytest.approx(expected, rel=1e-9, abs=1e-12)
        assert a[f"governing_{which}_half_step_im_change"] != 0.0  # a real re-run, not the stored value
        changes = json.loads(a[f"governing_{which}_half_step_changes"])
        # every stored impact factor is checked: the deflection's, the strain's and the load effects'
        assert set(changes) == {"impact_factor", "strain_impact_factor", "moment_impact_factor",
                                "shear_impact_factor", "reaction_impact_factor"}
        assert changes["impact_factor"] == a[f"governing_{which}_half_step_im_change"]
        half = _half_step_effect_ims(job, e)
        for kind in ("moment", "shear", "reaction"):
            name = f"{kind}_impact_factor"
            assert changes[name] == pytest.approx(half[kind] - ds[name].values[e], rel=1e-9, abs=1e-12), name
    assert a["half_step_tolerance"] == STEP_TOLERANCE


def test_a_change_above_the_tolerance_is_flagged_with_the_event(stream_dataset, monkeypatch):
    job, ds = stream_dataset
    changes = {int(ds.attrs[f"governing_{w}_event"]): abs(ds.attrs[f"governing_{w}_half_step_im_change"])
               for w in ("static", "dynamic")}
    tolerance = 0.5 * (min(changes.values()) + max(changes.values()))  # between the two events' changes
    monkeypatch.setattr(accuracy, "STEP_TOLERANCE", tolerance)
    attrs, flags = accuracy.governing_step_check(job, dict(ds.attrs), {"impact_factor": ds["impact_factor"].values})
    worst = max(changes, key=changes.get)
    assert [f.subject for f in flags] == [f"event {worst}"]
    assert flags[0].code == "stream_step_sensitive" and flags[0].threshold == tolerance
    assert "half the time step" in flags[0].message


def test_one_event_governing_both_is_run_once_and_flagged_once(stream_dataset, monkeypatch):
    job, ds = stream_dataset
    attrs = dict(ds.attrs)
    attrs["governing_dynamic_event"] = attrs["governing_static_event"]
    runs = []
    original = accuracy.half_step_impact_factors
    monkeypatch.setattr(accuracy, "half_step_impact_factors", lambda j, e, n: runs.append(e) or original(j, e, n))
    monkeypatch.setattr(accuracy, "STEP_TOLERANCE", 0.0)
    out, flags = accuracy.governing_step_check(job, attrs, {"impact_factor": ds["impact_factor"].values})
    assert runs == [attrs["governing_static_event"]]
    assert out["governing_static_half_step_im_change"] == out["governing_dynamic_half_step_im_change"]
    assert len(flags) == 1 and "governing static and dynamic event" in flags[0].message


def test_a_re_run_above_the_budget_is_not_checked_not_flagged(stream_dataset, monkeypatch):
    from vbikit.solve.budget import BudgetError

    job, ds = stream_dataset

    def refuse(*args, **kwargs):
        raise BudgetError("above the step budget")

    monkeypatch.setattr("vbikit.solve.simulate", refuse)
    monkeypatch.setattr(accuracy, "STEP_TOLERANCE", 0.0)
    out, flags = accuracy.governing_step_check(job, dict(ds.attrs), {"impact_factor": ds["impact_factor"].values})
    assert np.isnan(out["governing_static_half_step_im_change"]) and not flags


def test_vbikit_traffic_prints_the_half_step_changes(tmp_path):
    records = synthetic_stream([LaneTraffic(1, "+x", 600, 75)], 3, seed=9)
    write_records(records, tmp_path / "r.csv")
    (tmp_path / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 4\n[road]\nclass = "B"\n'
                                        'length = 200.0\n[crossing]\napproach = 5.0\n')
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"),
                                   "--out", str(tmp_path / "r.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    line = next(s for s in res.output.splitlines() if "at half the time step" in s)
    assert "IM changes by" in line and "flagged above 0.005" in line and np.isfinite(float(line.split("by ")[1].split()[0]))


def test_the_summary_gives_every_impact_factors_change_the_dataset_stores(stream_dataset):
    """``traffic-summary.json`` gives ``governing_<which>_half_step_changes`` as docs/traffic.md lists them (a trial
    found them in the dataset and the printed report only)."""
    import json

    from vbikit.traffic.summary import summary

    _, ds = stream_dataset
    out = summary(ds)
    for which in ("static", "dynamic"):
        key = f"governing_{which}_half_step_changes"
        stored = json.loads(ds.attrs[key])
        assert stored and out[key] == stored and out["units"][key] == "1"
        assert max(abs(v) for v in stored.values() if v == v) >= abs(out[f"governing_{which}_half_step_im_change"])
