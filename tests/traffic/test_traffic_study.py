"""`vbikit traffic`: a stream simulated event by event on the study machinery."""
from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from vbikit.cli import app
from vbikit.study.run import parts_dir, run_study
from vbikit.study.spec import derive_seed
from vbikit.traffic import LaneTraffic, synthetic_stream, write_records
from vbikit.traffic.study import base_scenario, traffic_study

runner = CliRunner()
#: a small, fast base: Bridge 2 beam with 4 modes, ISO B road of 200 m, point tires
BASE = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "road": {"class": "B", "length": 200.0},
        "crossing": {"approach": 5.0, "free_vibration": 0.1}}
LANES = [LaneTraffic(1, "+x", 900, 80, 5), LaneTraffic(2, "-x", 900, 70, 5)]


@pytest.fixture(scope="module")
def stream():
    return synthetic_stream(LANES, 24, seed=2)


def test_events_partition_the_records_in_the_dataset(stream, tmp_path):
    job = traffic_study(stream, BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4)
    ds = run_study(job, tmp_path / "s.nc", workers=1)
    event_of = ds["vehicle_event"].values
    assert sorted(int(i) for e in job.events for i in e) == list(range(len(stream)))  # each vehicle once
    for e, members in enumerate(job.events):
        assert list(np.flatnonzero(event_of == e)) == sorted(members)
    assert int(ds["n_vehicles"].sum()) == len(stream)
    assert ds["multiple_presence"].values.tolist() == [int(len(m) > 1) for m in job.events]
    assert 0 < int(ds.attrs["n_multiple_presence_events"]) < job.size
    assert np.all(np.isfinite(ds["impact_factor"].values))
    assert ds["road_seed"].values.tolist() == [derive_seed(5, e) for e in range(job.size)]
    gross = np.array([sum(r.axle_loads) for r in stream])
    np.testing.assert_allclose(ds["event_gross_weight"].values, [gross[list(m)].sum() for m in job.events])
    # statistics from the per-event values
    st = np.abs(ds["max_static_displacement"].values)
    dyn = np.abs(ds["max_dynamic_displacement"].values)
    i = int(np.argmax(st))
    assert ds.attrs["governing_static_event"] == i
    assert ds.attrs["governing_static_amplification"] == pytest.approx(dyn[i] / st[i], rel=1e-12)
    assert ds.attrs["governing_dynamic_amplification"] == pytest.approx(dyn.max() / st.max(), rel=1e-12)
    assert ds.attrs["im_mean"] == pytest.approx(float(ds["impact_factor"].mean()), rel=1e-12)
    assert sum(json.loads(ds.attrs["im_histogram_counts"])) == job.size


def test_stream_of_one_vehicle_equals_vbikit_run(tmp_path):
    """One record through `vbikit traffic` and the same truck through `vbikit run` (its road seed
    derive_seed(seed, 0), entering at t = 0, in lane 1, the stream's run-in): the same numbers."""
    record = synthetic_stream([LaneTraffic(1, "-x", 600, 75)], 1, seed=9)
    write_records(record, tmp_path / "one.csv")
    (tmp_path / "base.toml").write_text(
        '[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 4\n[road]\nclass = "B"\nlength = 200.0\n'
        "[crossing]\napproach = 5.0\nfree_vibration = 0.1\n")
    res = runner.invoke(app, ["traffic", str(tmp_path / "one.csv"), "--bridge", str(tmp_path / "base.toml"),
                              "--out", str(tmp_path / "one.nc"), "--seed", "7", "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    ds = xr.open_dataset(tmp_path / "one.nc")
    r = record[0]
    run_in = float(ds["run_in"][0])  # the population's run-in (none given in the base scenario), 100 m less the
    assert run_in == 95.0  # approach, the road long enough for it
    scenario = (tmp_path / "base.toml").read_text().replace('class = "B"', f'class = "B"\nseed = {derive_seed(7, 0)}')
    scenario = scenario.replace("approach = 5.0", f"approach = 5.0\nrun_in = {run_in!r}")
    scenario += (f'[[vehicles]]\nmodel = "axles"\naxle_loads = {list(r.axle_loads)}\naxle_spacings = {list(r.axle_spacings)}\n'
                 f'direction = "-x"\nspeed = {r.speed!r}\nlateral_offset = 0.0\n')
    (tmp_path / "run.toml").write_text(scenario)
    run = runner.invoke(app, ["run", str(tmp_path / "run.toml"), "--json"])
    assert run.exit_code == 0, run.output
    s = json.loads(run.stdout)
    for key in ("impact_factor", "max_dynamic_displacement", "max_static_displacement", "strain_impact_factor",
                "max_abs_acceleration"):
        assert float(ds[key][0]) == pytest.approx(s[key], rel=1e-12, abs=0), key
    assert float(ds["vehicle_min_wheel_force"][0]) == pytest.approx(min(s["min_wheel_force"].values()), rel=1e-12)


def test_parallel_and_resumed_runs_equal_the_serial_one(stream, tmp_path):
    job = traffic_study(stream, BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4)
    serial = run_study(job, tmp_path / "a.nc", workers=1)
    parallel = run_study(job, tmp_path / "b.nc", workers=2)
    xr.testing.assert_identical(serial.drop_attrs(), parallel.drop_attrs())
    # an interrupted run: keep the parts, lose two of them and the result; the rerun recomputes those
    run_study(job, tmp_path / "c.nc", workers=1, keep_parts=True)
    parts = parts_dir(tmp_path / "c.nc")
    (tmp_path / "c.nc").unlink()
    for name in ("batch-000001.npz", "batch-000003.npz"):
        (parts / name).unlink()
    (parts / "batch-000000.npz").write_bytes(b"damaged")
    resumed = run_study(job, tmp_path / "c.nc", workers=1)
    xr.testing.assert_identical(serial.drop_attrs(), resumed.drop_attrs())
    # the same output with another stream is refused, not mixed
    other = traffic_study(stream[:-1], BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4)
    with pytest.raises(ValueError, match="not this study's finished dataset"):
        run_study(other, tmp_path / "c.nc", workers=1)


def test_traffic_command_errors_name_the_problem(tmp_path, stream):
    write_records(stream, tmp_path / "s.csv")
    bad = tmp_path / "bad.csv"
    bad.write_text((tmp_path / "s.csv").read_text().replace(",+x,", ",north,", 1))
    res = runner.invoke(app, ["traffic", str(bad), "--bridge", "paper-bridge-2-beam", "--out", str(tmp_path / "x.nc")])
    assert res.exit_code == 2 and "bad.csv:2: column 5 (direction): must be +x or -x" in res.stderr and "north" not in res.stderr
    res = runner.invoke(app, ["traffic", str(tmp_path / "s.csv"), "--bridge", "bridge-9", "--out", str(tmp_path / "x.nc")])
    assert res.exit_code == 2 and "neither a scenario file nor a bridge preset" in res.stderr
    scenario = tmp_path / "with_vehicle.toml"
    scenario.write_text('[bridge]\nmodel = "paper-bridge-2-beam"\n[vehicle]\nmodel = "hs20-44"\n')
    res = runner.invoke(app, ["traffic", str(tmp_path / "s.csv"), "--bridge", str(scenario), "--out", str(tmp_path / "x.nc")])
    assert res.exit_code == 2 and "remove vehicle (the vehicles come from the records)" in res.stderr
    one_lane = runner.invoke(app, ["traffic", str(tmp_path / "s.csv"), "--bridge", "paper-bridge-2-beam", "--out",
                                   str(tmp_path / "x.nc")])
    line = 2 + next(i for i, r in enumerate(stream) if r.lane == 2)  # header on line 1
    assert one_lane.exit_code == 2 and f"s.csv:{line}: lane 2 has no centre" in one_lane.stderr


def test_default_lanes():
    base, _ = base_scenario("paper-bridge-2")
    job = traffic_study(synthetic_stream(LANES, 2, seed=1), base)
    assert job.lanes == pytest.approx((-9.75 / 4, 9.75 / 4))  # ∓ deck width / 4


def test_a_stream_reduces_only_the_outputs_it_asks_for(stream, tmp_path, monkeypatch):
    """``outputs``: those variables (and the statistics' ones) equal the full run's, the others are not
    stored, and a run that asks for no load-effect output computes no load effect."""
    from vbikit.analysis import effects
    from vbikit.study import StudyError

    full = run_study(traffic_study(stream, BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4), tmp_path / "a.nc", workers=1)
    calls = []
    inner = effects.load_effect_responses
    monkeypatch.setattr(effects, "load_effect_responses", lambda *a, **k: calls.append(1) or inner(*a, **k))
    job = traffic_study(stream, BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4, outputs=["max_abs_acceleration"])
    some = run_study(job, tmp_path / "b.nc", workers=1)
    assert calls == []
    stored = {"max_abs_acceleration", "impact_factor", "max_dynamic_displacement", "max_static_displacement", "n_steps",
              "unconverged_steps"}
    from vbikit.outputs import OUTPUTS

    assert {k for k in some.data_vars if k in OUTPUTS} == stored
    for k in stored | {"vehicle_min_wheel_force", "road_seed"}:
        xr.testing.assert_identical(some[k], full[k])
    assert some.attrs["im_mean"] == full.attrs["im_mean"] and json.loads(some.attrs["study"])["outputs"][0] == "impact_factor"
    # asking for a moment output computes the load effects again, and gives the full run's values
    job = traffic_study(stream, BASE, lanes=[-1.8, 1.8], seed=5, batch_size=4, outputs=["moment_impact_factor"])
    xr.testing.assert_identical(run_study(job, tmp_path / "c.nc", workers=1)["moment_impact_factor"],
                                full["moment_impact_factor"])
    assert calls
    with pytest.raises(StudyError, match="outputs: unknown output 'peak'; allowed: impact_factor"):
        traffic_study(stream, BASE, lanes=[-1.8, 1.8], outputs=["peak"])
    write_records(stream, tmp_path / "s.csv")
    res = runner.invoke(app, ["traffic", str(tmp_path / "s.csv"), "--bridge", "paper-bridge-2-beam", "--lanes", "-1.8,1.8",
                              "--outputs", "impact_factor,peak", "--out", str(tmp_path / "x.nc")])
    assert res.exit_code == 2 and "unknown output 'peak'" in res.stderr


def test_a_one_axle_vehicle_is_refused_before_the_run(tmp_path):
    """A rigid body on one axle has no stiffness against pitch, so its static equilibrium matrix is
    singular: a one-axle record was accepted by the stream's checks and stopped the first event with
    `numpy.linalg.LinAlgError: Singular matrix` (red-team pass 2026-12-05).  ``axle_truck`` now
    refuses one axle, and the stream names the record's line before any event runs."""
    from vbikit.study import StudyError
    from vbikit.traffic import read_records
    from vbikit.vehicle import axle_truck

    with pytest.raises(ValueError, match="at least two axle loads"):
        axle_truck([100e3], [])
    path = tmp_path / "one_axle.csv"
    path.write_text("id,time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"
                    "a,0.0,1,+x,72.0,50 100,4.0\nb,20.0,1,+x,90.0,100,\n")
    with pytest.raises(StudyError, match=r"one_axle\.csv:3: axle_loads must be a list of at least two axle loads"):
        traffic_study(read_records(path), BASE, source=str(path))
