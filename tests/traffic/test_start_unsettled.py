"""How much of its start transient a vehicle keeps at the bridge (``vbikit.solve.run_in.start_transient_left``:
exp(−σ_min D / v), D the road driven since rest: the run-in plus the distance before its entry support at the
start) and the ``start_unsettled`` flag of a population whose vehicles keep more than the trucks the settled start
was checked with (``SETTLED_TRANSIENT_LEFT``; docs/traffic.md, "Start from rest and the approach")."""
from __future__ import annotations

import dataclasses

import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from vbikit.analysis.population_start import start_attrs, start_flags
from vbikit.bridge import EulerBernoulliBeam
from vbikit.cli import app
from vbikit.road import RoadProfile
from vbikit.solve.crossing import Crossing, VehicleMotion
from vbikit.solve.run_in import SETTLED_TRANSIENT_LEFT, start_settling, start_transient_left
from vbikit.vehicle import quarter_car
from vbikit.vehicle.presets import VEHICLE_PRESETS

ROOT = Path(__file__).resolve().parents[2]
STORED = json.loads((ROOT / "docs" / "figures" / "approach-numbers.json").read_text())
BEAM = EulerBernoulliBeam(20.0, 2e9, 4e3, 0.02, n_modes=3)
ROAD = RoadProfile(np.linspace(-400.0, 100.0, 5001), 0.002 * np.sin(np.linspace(0.0, 300.0, 5001)))


def test_one_vehicle_keeps_exp_of_minus_sigma_times_road_driven_over_speed():
    """A quarter car (one wheel) 12 m before the beam after a 30 m run-in at 17 m/s: D = 42 m."""
    car = quarter_car()
    crossing = Crossing(BEAM, vehicles=(VehicleMotion(car, 17.0),), road=ROAD, approach=12.0, run_in=30.0)
    sigma = car.slowest_decay_rate(np.array([0]))
    assert start_transient_left(crossing) == pytest.approx(math.exp(-sigma * 42.0 / 17.0), rel=1e-12)


def test_the_run_in_that_settles_leaves_exactly_the_limit():
    """start_settling's run-in, given back as crossing.run_in, leaves the vehicle SETTLED_TRANSIENT_LEFT of its
    transient (the round trip of t* = ln(1 / limit) / σ_min); for two vehicles the slower-decaying one sets it, with
    the run-in driven at the slowest speed: 15 (t* − 2.6 s) for the second vehicle of the next test."""
    car = quarter_car()
    sigma = car.slowest_decay_rate(np.array([0]))
    needed = start_settling(Crossing(BEAM, vehicles=(VehicleMotion(car, 17.0),), road=ROAD, approach=12.0))[1]
    assert needed == pytest.approx(17.0 * math.log(1.0 / SETTLED_TRANSIENT_LEFT) / sigma - 12.0, rel=1e-12)
    settled = Crossing(BEAM, vehicles=(VehicleMotion(car, 17.0),), road=ROAD, approach=12.0, run_in=needed)
    assert start_transient_left(settled) == pytest.approx(SETTLED_TRANSIENT_LEFT, rel=1e-9)
    stiff = VEHICLE_PRESETS["dump-truck"].build()
    pair = Crossing(BEAM, vehicles=(VehicleMotion(stiff, 20.0), VehicleMotion(car, 15.0, entry_time=2.0)),
                    road=ROAD, approach=12.0, run_in=30.0)
    assert start_settling(pair)[1] == pytest.approx(15.0 * (math.log(1.0 / SETTLED_TRANSIENT_LEFT) / sigma - 2.6),
                                                    rel=1e-9)
    # the round trip with several vehicles: the slowest speed sets the run-in's time for all of them
    settled_pair = Crossing(BEAM, vehicles=pair.vehicles, road=ROAD, approach=12.0, run_in=start_settling(pair)[1])
    assert start_transient_left(settled_pair) == pytest.approx(SETTLED_TRANSIENT_LEFT, rel=1e-9)


def test_a_vehicle_behind_the_first_has_driven_further():
    """The run starts when the first vehicle (20 m/s, entering at 0 s) is 12 m before the beam, t0 = −0.6 s; the
    second (15 m/s, entering at 2 s) is then 15 × 2.6 = 39 m before it: D = 30 + 39 m.  The second is the lightly
    damped one here, so its share is the event's."""
    stiff, soft = VEHICLE_PRESETS["dump-truck"].build(), quarter_car()
    crossing = Crossing(BEAM, vehicles=(VehicleMotion(stiff, 20.0), VehicleMotion(soft, 15.0, entry_time=2.0)),
                        road=ROAD, approach=12.0, run_in=30.0)
    sigma_soft = soft.slowest_decay_rate(np.array([0]))
    assert crossing.start_time == pytest.approx(-0.6)
    assert start_transient_left(crossing) == pytest.approx(math.exp(-sigma_soft * 69.0 / 15.0), rel=1e-9)


def test_a_vehicle_driving_minus_x_or_accelerating_keeps_what_its_time_on_the_road_leaves():
    """−x: the same 42 m at 17 m/s.  Accelerating at 2 m/s² from 17 m/s at the start: the 12 m approach takes
    τ = (√(17² + 2·2·12) − 17) / 2 s, the 30 m run-in (driven at the start's speed) 30 / 17 s."""
    car = quarter_car()
    sigma = car.slowest_decay_rate(np.array([0]))
    back = Crossing(BEAM, vehicles=(VehicleMotion(car, 17.0, direction="-x"),), road=ROAD, approach=12.0, run_in=30.0)
    assert start_transient_left(back) == pytest.approx(math.exp(-sigma * 42.0 / 17.0), rel=1e-12)
    faster = Crossing(BEAM, car, speed=17.0, acceleration=2.0, road=ROAD, approach=12.0, run_in=30.0)
    tau = (math.sqrt(17.0**2 + 2 * 2.0 * 12.0) - 17.0) / 2.0
    assert start_transient_left(faster) == pytest.approx(math.exp(-sigma * (30.0 / 17.0 + tau)), rel=1e-9)


def test_a_roll_counts_only_where_the_two_wheel_lines_read_their_own_profiles():
    """A body in heave and roll on two wheels at y = ±0.9 m, damped in heave only: on one profile its roll is not
    excited and the heave's c / 2m sets the share kept; with a right-line profile of its own the undamped roll is
    excited and never settles (share 1)."""
    from vbikit.vehicle.model import Vehicle, Wheel

    m, c = 2000.0, 6.0e3
    rows = (np.array([1.0, 0.9]), np.array([1.0, -0.9]))
    body = Vehicle("body", ("z", "roll"), np.diag([m, 900.0]), np.diag([c, 0.0]), np.zeros((2, 2)),
                   np.array([-9.81 * m, 0.0]), (Wheel("left", 0.0, 0.9, 3.0e5, 0.0, rows[0]),
                                                Wheel("right", 0.0, -0.9, 3.0e5, 0.0, rows[1])))
    one = Crossing(BEAM, vehicles=(VehicleMotion(body, 17.0),), road=ROAD, approach=12.0, run_in=30.0)
    assert start_transient_left(one) == pytest.approx(math.exp(-c / (2 * m) * 42.0 / 17.0), rel=1e-9)
    two = Crossing(BEAM, vehicles=(VehicleMotion(body, 17.0),), road=ROAD, road_right=ROAD, approach=12.0, run_in=30.0)
    assert start_transient_left(two) == 1.0


def test_nothing_to_settle_on_a_smooth_road_or_for_moving_forces():
    assert start_transient_left(Crossing(BEAM, vehicles=(VehicleMotion(quarter_car(), 17.0),), road=None)) == 0.0
    force = VEHICLE_PRESETS["moving-force"].build()
    assert math.isnan(start_transient_left(Crossing(BEAM, vehicles=(VehicleMotion(force, 17.0),), road=ROAD)))


def test_the_limit_covers_the_checked_trucks_and_no_more():
    """SETTLED_TRANSIENT_LEFT is the largest share the trucks SETTLED_APPROACH was checked with kept (the docs
    script's ``checked_transients``, recomputed here without simulating), rounded up by less than 0.005."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("approach_numbers", ROOT / "docs" / "scripts" / "approach_numbers.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    assert script.checked_transients() == STORED["checked_transients"]
    checked = STORED["checked_transients"]["transient_left_at_100_m"]["max"]
    assert checked <= SETTLED_TRANSIENT_LEFT < checked + 0.005


def test_the_error_grows_with_the_share_kept():
    """The stored settling runs: the IM error's root mean square grows from bin to bin of the share kept, and the
    bins at or below the limit stay under 0.005 (the page's claim)."""
    bins = STORED["transient_effect"]["bins"]
    rms = [b["rms"] for b in bins if b["events"] >= 30]
    assert all(a < b for a, b in zip(rms, rms[1:]))
    assert all(b["rms"] < 0.005 for b in bins if b["left"][1] <= SETTLED_TRANSIENT_LEFT + 0.03)


def test_the_flag_counts_the_events_names_the_run_in_and_stays_behind_start_from_rest():
    attrs = start_attrs(10.0, 90.0, [90.0, 90.0, 90.0], 1.0, [0.02, 0.4, math.nan], [40.0, 162.3, math.nan])
    assert attrs["start_transient_left_max"] == 0.4 and attrs["start_unsettled_events"] == 1
    assert attrs["start_settling_run_in_m"] == 162.3
    (flag,) = start_flags(attrs, total=3)
    assert flag.code == "start_unsettled" and flag.value == 0.4 and flag.threshold == SETTLED_TRANSIENT_LEFT
    assert "1 event of 3 has a sprung vehicle that keeps 40.0%" in flag.message
    assert "give crossing.run_in = 163 m in the base scenario" in flag.message
    undamped = start_flags(start_attrs(10.0, 90.0, [90.0], 1.0, [1.0], [math.inf]), total=1)
    assert "never settles" in undamped[0].message and "start_settling_run_in_m" not in start_attrs(
        10.0, 90.0, [90.0], 1.0, [1.0], [math.inf])
    assert not start_flags(start_attrs(10.0, 90.0, [90.0], 1.0, [SETTLED_TRANSIENT_LEFT], [90.0]), total=1)
    both = start_flags(start_attrs(10.0, 90.0, [90.0, 90.0], 1.0, [1.0, 0.3], [math.inf, 140.0]), total=2)
    assert "never settles" in both[0].message and "crossing.run_in = 140 m" in both[0].message  # (both remedies)
    cut = start_attrs(10.0, 300.0, [300.0, 60.0], 1.0, [0.01, 0.3], [40.0, 140.0])  # the road cut one run-in short
    (short,) = start_unsettled_flags_of(cut)
    assert "road.length" in short.message and "crossing.run_in =" not in short.message
    at_rest = start_attrs(10.0, 0.0, [0.0], 1.0, [0.6])  # too short a road before the bridge: the distance flag
    assert [f.code for f in start_flags(at_rest, total=1)] == ["start_from_rest"]
    earlier = {k: v for k, v in attrs.items() if not k.startswith("start_")}  # (a dataset before 2026-12-07)
    assert not start_flags(earlier, total=3)


def start_unsettled_flags_of(attrs: dict) -> list:
    """The start_unsettled flags of a population's start attributes judged as start_flags judges them, the distance
    flag set aside (a population driven 100 m in all whose road cut one event's run-in short)."""
    from vbikit.analysis.checks import start_unsettled_flags

    return start_unsettled_flags(attrs["start_unsettled_events"], attrs["start_transient_left_max"],
                                 attrs["start_settling_run_in_m"], 2, run_in=attrs["run_in_m"],
                                 shortened=attrs["run_in_shortened_events"])


def _stream(tmp_path, model: str, road: str = "", crossing: str = "", records: str = "") -> tuple[xr.Dataset, str]:
    tmp_path = tmp_path / model
    tmp_path.mkdir(parents=True)
    (tmp_path / "r.csv").write_text("time [s],lane,direction,speed [km/h],model\n"
                                    + (records or "0,1,+x,80,%s\n30,1,+x,70,%s\n" % (model, model)))
    (tmp_path / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[tire]\n'
                                        f'model = "point"\n[road]\nclass = "B"\n{road}\n{crossing}')
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"),
                                   "--out", str(tmp_path / "o.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    return xr.load_dataset(tmp_path / "o.nc"), res.output


def test_a_population_lengthens_the_run_in_of_a_lightly_damped_vehicle_to_settle_it(tmp_path):
    """The two-axle preset decays at 0.25 s⁻¹ (slower than every checked truck): after the population's 100 m at
    70–80 km/h it would keep about a third of its transient. The population gives each of its events the run-in its
    vehicle needs instead (``EventContext.settled_run_in``: the settling run-in rounded up to the metre), so each
    keeps at most SETTLED_TRANSIENT_LEFT, a little less for the rounding, and nothing is flagged; the dump truck
    (0.95 s⁻¹) keeps under 2 % after the population's own 90 m."""
    ds, output = _stream(tmp_path, "two-axle")
    left, needed, run_in = (ds[k].values for k in ("start_transient_left", "start_settling_run_in", "run_in"))
    assert left.shape == (2,) and np.all(needed > 150.0)  # (what 100 m left: about a third)
    assert np.array_equal(run_in, np.ceil(needed))  # each event its own run-in, from its vehicle's decay
    assert np.all(left <= SETTLED_TRANSIENT_LEFT) and np.all(left > 0.9 * SETTLED_TRANSIENT_LEFT)
    assert ds.attrs["run_in_m"] == 90.0 and ds.attrs["run_in_adaptive"] == 1
    assert ds.attrs["run_in_max_m"] == float(run_in.max()) and ds.attrs["run_in_shortened_events"] == 0
    assert ds.attrs["start_unsettled_events"] == 0 and "start_unsettled" not in ds.attrs.get("flag_codes", "").split(",")
    assert f"longer where the vehicles needed more to settle, up to {run_in.max():g} m" in output
    assert run_in.tolist() == [229.0, 199.0]  # (docs/traffic.md, "Which vehicles 100 m settles", quotes them)
    ds, _ = _stream(tmp_path, "dump-truck")
    assert np.all(ds["start_transient_left"].values < 0.02) and ds.attrs["start_unsettled_events"] == 0
    assert np.all(ds["run_in"].values == 90.0)  # (settled by the population's own run-in: not lengthened)
    assert "start_unsettled" not in ds.attrs.get("flag_codes", "").split(",")


def test_a_short_road_or_a_given_run_in_leaves_the_vehicle_unsettled_and_flagged(tmp_path):
    """Where the population cannot settle the vehicle the flag stays, naming what to do: a random road too short for
    the run-in it needs (``road.length``: the run-in cut short), or a run-in the base scenario gives (not lengthened:
    the user's; its remedy the run-in that settles it)."""
    ds, output = _stream(tmp_path, "two-axle", road='length = 200')
    assert ds.attrs["run_in_shortened_events"] == 2 and ds.attrs["start_unsettled_events"] == 2
    assert np.all(ds["run_in"].values < ds["start_settling_run_in"].values)
    assert "road cut it short on 2 events: give a longer road.length" in ds.attrs["warnings"]
    assert "give crossing.run_in =" not in ds.attrs["warnings"]
    given, output = _stream(tmp_path / "given", "two-axle", crossing="[crossing]\nrun_in = 90\n")
    left, needed = given["start_transient_left"].values, given["start_settling_run_in"].values
    assert np.all(given["run_in"].values == 90.0) and given.attrs["run_in_adaptive"] == 0
    assert np.all(left > 0.25) and np.all(left < 0.45) and given.attrs["start_unsettled_events"] == 2
    assert f"give crossing.run_in = {math.ceil(needed.max()):g} m" in given.attrs["warnings"]
    assert "on 2 events a vehicle had not settled (start_unsettled)" in output  # (the start's words say so too)


def test_an_approach_of_100_m_or_more_is_lengthened_too_and_one_too_short_is_not(tmp_path):
    """With crossing.approach = 120 m the population's own run-in is 0 (100 m driven already), yet the two-axle
    preset needs more: it gets it, as any event does; with an approach too short for any run-in (0.5 m: the
    vehicles would stand on the deck) nothing is lengthened nor counted as cut short, and the start from rest is
    flagged with its own remedy (a longer approach)."""
    ds, output = _stream(tmp_path, "two-axle", crossing="[crossing]\napproach = 120\n")
    run_in, needed = ds["run_in"].values, ds["start_settling_run_in"].values
    assert ds.attrs["run_in_m"] == 0.0 and ds.attrs["run_in_adaptive"] == 1
    assert np.all(run_in > 0.0) and np.array_equal(run_in, np.ceil(needed))
    assert ds.attrs["run_in_shortened_events"] == 0 and ds.attrs["start_unsettled_events"] == 0
    assert "start at rest" not in output and f"up to {run_in.max():g} m" in output
    short, _ = _stream(tmp_path / "short", "two-axle", crossing="[crossing]\napproach = 0.5\n")
    assert np.all(short["run_in"].values == 0.0) and short.attrs["run_in_adaptive"] == 0
    assert short.attrs["run_in_shortened_events"] == 0
    assert "start_from_rest" in short.attrs["flag_codes"].split(",") and "crossing.approach >=" in short.attrs["warnings"]


def test_an_undamped_vehicle_does_not_keep_its_events_other_vehicles_unsettled(tmp_path):
    """The 3S2 (its tandem bogie pitches undamped: it never settles) and the two-axle preset in one event: the
    event's run-in is the two-axle's need (the undamped vehicle left out of it), and the flag names the 3S2."""
    from vbikit.vehicle.presets import VEHICLE_PRESETS

    ds, _ = _stream(tmp_path, "mixed", records="0,1,+x,80,two-axle\n0.5,1,+x,80,3s2\n")
    assert ds.sizes["event"] == 1 and float(ds["run_in"].values[0]) > 150.0  # (the two-axle's: about 230 m)
    assert float(ds["start_transient_left"].values[0]) == 1.0
    assert "never settles" in ds.attrs["warnings"]
    assert VEHICLE_PRESETS["3s2"].build().slowest_decay_rate() == 0.0


def test_a_part_that_ran_with_another_run_in_is_run_again_and_an_old_share_is_judged_with_its_own(tmp_path):
    """A part of a stream written by the version before (its two-axle events ran with the population's 90 m) is
    not used (``part_problem``: the run-in each event got differs from what this version gives it), so a resumed
    stream holds one rule; and a part written before the share was stored gets the share for the run-in its
    events ran with, not the one this version would give them."""
    from vbikit.solve.run_in import start_settling
    from vbikit.study.run import run_study
    from vbikit.study.storage import CHECKSUMS, load_part, part_path, parts_dir, save_part
    from vbikit.study.run import spec_checksum
    from vbikit.traffic.records import read_records
    from vbikit.traffic.study import traffic_study

    (tmp_path / "r.csv").write_text("time [s],lane,direction,speed [km/h],model\n0,1,+x,80,two-axle\n")
    base = {"bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"}, "road": {"class": "B"}}
    job = traffic_study(read_records(tmp_path / "r.csv"), base, batch_size=1)
    run_study(job, tmp_path / "a.nc", workers=1, keep_parts=True)
    parts = parts_dir(tmp_path / "a.nc")
    part = load_part(parts, 0)
    assert job.part_problem(part, (0,)) is None and float(part["run_in"][0]) > 150.0
    earlier = {**part, "run_in": np.array([90.0])}
    assert "ran with another run-in" in job.part_problem(earlier, (0,))
    old = {k: v for k, v in earlier.items()
           if k not in ("start_transient_left", "start_settling_run_in", "batch_index", "spec_checksum")}
    part_path(parts, 0).unlink()
    sums = parts / CHECKSUMS
    sums.write_text("".join(line + "\n" for line in sums.read_text().splitlines()
                            if not line.endswith(part_path(parts, 0).name)))
    save_part(parts, 0, old, spec_checksum(job))
    left = float(job.assemble(parts)["start_transient_left"].values[0])
    at_90 = start_settling(dataclasses.replace(job.crossing(0), run_in=90.0))[0]
    assert left == at_90 > 0.25  # (what 90 m leaves the two-axle preset: about a third)


def test_a_part_written_before_the_share_was_stored_is_used_and_the_share_computed(tmp_path):
    """A stream's finished batch without ``start_transient_left`` (an earlier version's) is not run again: the
    dataset gets each of its events' share from the event's crossing, the same as a run stores."""
    from vbikit.study.run import run_study
    from vbikit.study.storage import CHECKSUMS, load_part, part_path, parts_dir, save_part
    from vbikit.study.run import spec_checksum
    from vbikit.traffic.records import read_records
    from vbikit.traffic.study import traffic_study

    (tmp_path / "r.csv").write_text("time [s],lane,direction,speed [km/h],model\n0,1,+x,80,two-axle\n"
                                    "30,1,+x,70,two-axle\n")
    base = {"bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"}, "road": {"class": "B"}}
    job = traffic_study(read_records(tmp_path / "r.csv"), base, batch_size=1)
    whole = run_study(job, tmp_path / "a.nc", workers=1, keep_parts=True)
    parts = parts_dir(tmp_path / "a.nc")
    old = {k: v for k, v in load_part(parts, 0).items()
           if k not in ("start_transient_left", "start_settling_run_in", "batch_index", "spec_checksum")}
    part_path(parts, 0).unlink()
    sums = parts / CHECKSUMS  # (its line dropped: the part is written again as an earlier version wrote it)
    sums.write_text("".join(line + "\n" for line in sums.read_text().splitlines()
                            if not line.endswith(part_path(parts, 0).name)))
    save_part(parts, 0, old, spec_checksum(job))
    again = job.assemble(parts)
    for name in ("start_transient_left", "start_settling_run_in"):
        assert np.array_equal(again[name].values, whole[name].values)
    assert job.part_problem(load_part(parts, 0), job.batches()[0]) is None
