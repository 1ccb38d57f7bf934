"""A traffic stream applies the single run's airborne-wheels rule to every event: the event variable
against the rule on an independent ``simulate`` of the same event, the dataset flag counting them,
and none on a smooth road."""
from __future__ import annotations


from vbikit.analysis.checks import airborne_wheels, dataset_has_flag
from vbikit.solve import simulate
from vbikit.study.run import run_study
from vbikit.traffic import LaneTraffic, synthetic_stream
from vbikit.traffic.study import traffic_study


def _stream(road_class: str, tmp_path):
    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "road": {"class": road_class, "length": 200.0},
            "crossing": {"approach": 5.0, "free_vibration": 0.1}}
    records = synthetic_stream([LaneTraffic(1, "+x", 900, 85, 5), LaneTraffic(2, "-x", 900, 80, 5)], 8, seed=4)
    job = traffic_study(records, base, lanes=[-1.8, 1.8], seed=2, batch_size=8)
    return job, run_study(job, tmp_path / f"{road_class}.nc", workers=1, progress=False)


def test_airborne_events_on_a_rough_road_are_counted_and_flagged(tmp_path):
    job, ds = _stream("E", tmp_path)
    stored = ds["airborne_wheels"].values
    expected = [int(bool(airborne_wheels(simulate(job.crossing(e))))) for e in range(job.size)]
    assert stored.tolist() == expected
    assert 0 < sum(expected) <= job.size  # class E at 80–85 km/h: wheels leave the road
    assert ds.attrs["n_airborne_events"] == sum(expected)
    assert dataset_has_flag(ds.attrs, "airborne_wheels")
    assert f"{sum(expected)} of {job.size} events had a wheel airborne" in ds.attrs["warnings"]
    # the summary gives them as every summary does: the messages a list, the flags records (a trial found one string)
    from vbikit.traffic.summary import summary

    s = summary(ds)
    assert set(f["code"] for f in s["flags"]) == set(s["flag_codes"]) and "airborne_wheels" in s["flag_codes"]
    assert s["warnings"] == [f["message"] for f in s["flags"]]
    assert any(w.startswith(f"{sum(expected)} of {job.size} events had a wheel airborne") for w in s["warnings"])


def test_no_airborne_flag_on_a_smooth_road(tmp_path):
    job, ds = _stream("A", tmp_path)
    assert not ds["airborne_wheels"].values.any() and ds.attrs["n_airborne_events"] == 0
    assert not dataset_has_flag(ds.attrs, "airborne_wheels")
