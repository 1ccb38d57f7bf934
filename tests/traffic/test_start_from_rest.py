"""The start from rest (docs/traffic.md, "Start from rest and the approach"): a population gives its sprung
vehicles the rest of SETTLED_APPROACH (100 m) as a run-in unless its base scenario sets crossing.run_in
(``population_run_in``), shortened on an event the road does not hold (``fit_run_in``); one whose events start
them less than 100 m before the bridge in all (a base scenario's run_in = 0, a road too short) is flagged
start_from_rest — in the traffic dataset (warnings, flag_codes, approach_m, run_in_m) and in a lifetime's
per-effect flags; moving constant forces never are."""
from __future__ import annotations

from pathlib import Path

import xarray as xr
from typer.testing import CliRunner

from vbikit.analysis.checks import SETTLED_APPROACH, start_from_rest_flags
from vbikit.solve.run_in import SETTLED_TRANSIENT_LEFT
from vbikit.cli import app

ROOT = Path(__file__).resolve().parents[2]
RECORDS = ("time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"
           "0,1,+x,80,50 120,4.5\n")


def test_the_rule_flags_approaches_below_the_settled_one_only():
    assert SETTLED_APPROACH == 100.0  # (docs/traffic.md: converged at 100 m, measured)
    (flag,) = start_from_rest_flags(10.0)
    assert flag.code == "start_from_rest" and flag.value == 10.0 and flag.threshold == 100.0
    assert "10 m before the bridge" in flag.message and "crossing.run_in = 90" in flag.message
    assert start_from_rest_flags(99.9) and not start_from_rest_flags(100.0) and not start_from_rest_flags(250.0)


def _stream(tmp_path, approach: float | None, run_in: float | None = None, road: str = ""):
    (tmp_path / "r.csv").write_text(RECORDS)
    base = f'[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[tire]\nmodel = "point"\n[road]\nclass = "B"\n{road}'
    crossing = {"approach": approach, "run_in": run_in}
    if any(v is not None for v in crossing.values()):
        base += "[crossing]\n" + "".join(f"{k} = {v}\n" for k, v in crossing.items() if v is not None)
    (tmp_path / "base.toml").write_text(base)
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"),
                                   "--out", str(tmp_path / "o.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        return dict(ds.attrs), res.output


def test_a_stream_started_at_rest_is_flagged_and_says_how_to_settle(tmp_path):
    attrs, output = _stream(tmp_path, None, run_in=0)
    assert attrs["approach_m"] == 10.0 and attrs["run_in_m"] == 0.0
    assert "start_from_rest" in attrs["flag_codes"].split(",")
    assert "at rest 10 m before the bridge" in attrs["warnings"] and "crossing.run_in = 90" in attrs["warnings"]
    assert "at rest 10 m before the bridge" in output  # (printed by vbikit traffic)
    assert "sprung vehicles start at rest 10 m before the bridge (crossing.run_in = 0)" in output


def test_a_stream_by_default_drives_its_trucks_settled_and_is_not_flagged(tmp_path):
    """No run_in in the base scenario: the population's, 100 m less the 10 m approach, on every event."""
    attrs, output = _stream(tmp_path, None)
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        assert ds["run_in"].values.tolist() == [90.0]
    assert ("sprung vehicles start settled, 10 m before the bridge after driving 90 m of the road alone "
            "(crossing.run_in)") in output
    assert attrs["approach_m"] == 10.0 and attrs["run_in_m"] == 90.0 and attrs["run_in_min_m"] == 90.0
    assert attrs["run_in_shortened_events"] == 0 and attrs["run_in_least_approach_m"] == 1.0
    assert "start_from_rest" not in attrs.get("flag_codes", "").split(",")


def test_a_road_too_short_for_the_run_in_shortens_it_and_is_flagged_with_the_remedy(tmp_path):
    """road.length = 100 m: the period is 163.84 m (2^14 samples of 1 cm), −81.92 … 81.91 m; the truck (4.5 m
    wheelbase) starts 10 m before the 9.16 m beam, so its run-in road reaches back to about −(14.5 + run_in) m
    and at most about 66 m of it fits (1 m margin)."""
    attrs, output = _stream(tmp_path, None, road="length = 100.0\n")
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        got = float(ds["run_in"].values[0])
    assert "(crossing.run_in; the road held less than their vehicles needed on 1 event)" in output
    assert 60.0 < got < 67.5 and attrs["run_in_min_m"] == got and attrs["run_in_m"] == 90.0
    assert attrs["run_in_shortened_events"] == 1
    assert "start_from_rest" in attrs["flag_codes"].split(",")
    assert "too short for the whole run-in on 1 event" in attrs["warnings"] and "road.length" in attrs["warnings"]


def test_a_measured_road_too_short_for_the_run_in_shortens_it_to_what_it_holds(tmp_path):
    """A measured profile from x = −40 m: the truck's rear axle starts at −14.5 m (10 m approach, 4.5 m
    wheelbase), and the run-in's road reaches run_in + 1 m behind each point (``Crossing.road_extent``), so with
    the 1 m kept from the road's end (``RUN_IN_ROAD_MARGIN``) the run-in is 40 − 1 − 14.5 − 1 = 23.5 m, found to
    0.01 m on the short side; the profile's rough part (a 1 cm sine of 3 m wavelength) is then driven."""
    import numpy as np

    x = np.arange(-40.0, 60.0 + 1e-9, 0.01)
    rows = "\n".join(f"{a:.2f},{0.01 * np.sin(2 * np.pi * a / 3.0):.6f}" for a in x)
    (tmp_path / "road.csv").write_text("x [m],elevation [m]\n" + rows + "\n")
    (tmp_path / "r.csv").write_text(RECORDS)
    (tmp_path / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[tire]\nmodel = "point"\n'
                                        '[road]\nprofile_file = "road.csv"\n')
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"),
                                   "--out", str(tmp_path / "o.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        got = float(ds["run_in"].values[0])
        attrs = dict(ds.attrs)
    assert 23.49 <= got <= 23.5
    assert "start_from_rest" in attrs["flag_codes"].split(",") and "measured profile" in attrs["warnings"]


def test_a_stream_started_100_m_before_the_bridge_is_not(tmp_path):
    attrs, output = _stream(tmp_path, 100.0, run_in=0)
    assert attrs["approach_m"] == 100.0
    assert "start_from_rest" not in attrs.get("flag_codes", "").split(",")
    assert "before their body vibration has built up" not in output  # (no warning; the start is said as it is)
    assert "sprung vehicles start at rest 100 m before the bridge" in output


def test_a_lifetime_flags_its_totals_for_sprung_trucks_only():
    from vbikit.lifetime.report import _start_flags

    (flag,) = _start_flags("M_mid", {"vehicle_model": "axle-truck", "approach_m": 10.0})
    assert flag.code == "start_from_rest" and flag.subject == "M_mid" and flag.output == "total return levels"
    assert not _start_flags("M_mid", {"vehicle_model": "moving-forces", "approach_m": 10.0})
    assert not _start_flags("M_mid", {"vehicle_model": "axle-truck", "approach_m": 100.0})
    assert not _start_flags("M_mid", {"vehicle_model": "axle-truck"})  # (a dataset before approach_m: not judged)


def test_a_stream_of_moving_forces_is_not_flagged(tmp_path):
    """Moving constant forces have no vibration to build up on the approach."""
    (tmp_path / "r.csv").write_text("time [s],lane,direction,speed [km/h],model\n0,1,+x,80,moving-force\n")
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", "paper-bridge-1-beam",
                                   "--out", str(tmp_path / "o.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        assert ds.attrs["approach_m"] == 10.0 and "start_from_rest" not in ds.attrs.get("flag_codes", "")


def test_a_lifetime_records_each_dynamic_events_run_in_and_judges_the_shortest():
    """The dynamic events get the population's run-in (approach 5 m: 95 m) and record it; lifetime.nc's
    ``run_in_min_m`` is the shortest any event got and ``run_in_shortened_events`` counts those below the
    population's (events of moving forces, NaN, not counted); the flag names the remedy for a short road."""
    import math

    import numpy as np

    from vbikit.lifetime.jobs import EVENT_STRIDE
    from vbikit.lifetime.report import _start_flags
    from vbikit.analysis.population_start import start_attrs
    from vbikit.lifetime.results import _runs_in
    from vbikit.lifetime.run import prepare

    spec = {"seed": 5, "days": 5, "traffic": {"records": "examples/traffic/stream.csv", "trucks_per_day": 20},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"},
            "road": {"class": "B"}, "crossing": {"approach": 5},
            "load_effects": [{"kind": "moment", "x": 3.9, "name": "M"}], "block": "day", "distribution": "gumbel"}
    prep = prepare(spec, str(ROOT))
    static = prep.static_job().run_batch((0,))
    g = int(static["ev_day"][0] * EVENT_STRIDE + static["ev_index"][0])
    event = prep.dynamic_job(np.array([g])).run_event(g)
    assert float(event["run_in"]) == 95.0
    # the share of its start transient the event's trucks kept: what a run stores is what a dataset of runs stored
    # before it was (a resumed lifetime) gets from the event's crossing alone
    left, needed = prep.dynamic_job(np.array([g])).start_settling([g], [float(event["run_in"])])
    assert left[0] == float(event["start_transient_left"]) and needed[0] == float(event["start_settling_run_in"])
    # a part of a round written before (no start_settling_run_in) is completed part by part when joined
    old_part = prep.dynamic_job(np.array([g]))._with_start_settling({"event_id": np.array([g]),
                                                                      "run_in": np.array([float(event["run_in"])])})
    assert old_part["start_transient_left"].tolist() == [left[0]] and old_part["start_settling_run_in"].tolist() == [needed[0]]
    # a stored run of this event with another run-in (an earlier version's rule) is run again, its part and its round
    job = prep.dynamic_job(np.array([g]))
    assert job.run_in_problem([g], [float(event["run_in"])]) is None
    assert "ran with another run-in" in job.run_in_problem([g], [float(event["run_in"]) + 10.0])
    attrs = start_attrs(5.0, 95.0, _runs_in({1: {"run_in": 95.0}, 2: {"run_in": 61.5}, 3: {"run_in": math.nan}}), 1.0)
    assert attrs == {"approach_m": 5.0, "run_in_m": 95.0, "run_in_min_m": 61.5, "run_in_max_m": 95.0,
                     "run_in_adaptive": 0, "run_in_shortened_events": 1, "run_in_least_approach_m": 1.0}
    # a result stored without a run-in (an earlier version's work): computed at rest, and judged so
    at_rest = start_attrs(5.0, 95.0, _runs_in({1: {"run_in": 95.0}, 4: {}}), 1.0)
    assert at_rest["run_in_min_m"] == 0.0 and at_rest["run_in_shortened_events"] == 1
    (flag,) = _start_flags("M", {"vehicle_model": "axle-truck", **at_rest})
    assert flag.value == 5.0
    forces = start_attrs(5.0, 95.0, _runs_in({3: {"run_in": math.nan}}), 1.0)  # moving forces only: nothing to judge
    assert "run_in_min_m" not in forces and forces["run_in_shortened_events"] == 0
    assert not _start_flags("M", {"vehicle_model": "moving-forces", **forces})
    (flag,) = _start_flags("M", {"vehicle_model": "axle-truck", **attrs})
    assert flag.value == 66.5 and "too short for the whole run-in on 1 event" in flag.message
    assert not _start_flags("M", {"vehicle_model": "axle-truck", "approach_m": 5.0, "run_in_m": 95.0})  # (nothing but
    # the run-in stored: judged on it)
    # moving constant forces have nothing to settle, whatever the attributes say
    assert not _start_flags("M", {"vehicle_model": "moving-forces", "approach_m": 5.0, "run_in_m": 95.0,
                                  "run_in_min_m": 0.0})
    assert _start_flags("M", {"vehicle_model": "axle-truck", "approach_m": 5.0})  # (nothing stored: at rest)


def test_a_lifetime_dataset_holds_each_simulated_events_run_in(tmp_path):
    """lifetime.nc: ``event_run_in`` 95 m (approach 5 m) on every simulated event, NaN on the others; the
    attributes ``run_in_m`` and ``run_in_min_m`` 95 and ``run_in_shortened_events`` 0, and no start_from_rest flag."""
    import numpy as np

    from vbikit.lifetime.run import run_lifetime

    spec = {"seed": 5, "days": 5, "traffic": {"records": "examples/traffic/stream.csv", "trucks_per_day": 20},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"},
            "road": {"class": "B"}, "crossing": {"approach": 5},
            "load_effects": [{"kind": "moment", "x": 3.9, "name": "M"}], "block": "day", "distribution": "gumbel"}
    ds = run_lifetime(spec, tmp_path, base_dir=str(ROOT), workers=1, figures=False)
    simulated = ds["event_simulated"].values.astype(bool)
    assert simulated.any() and (~simulated).any()
    assert np.all(ds["event_run_in"].values[simulated] == 95.0) and np.all(np.isnan(ds["event_run_in"].values[~simulated]))
    assert ds.attrs["run_in_m"] == 95.0 and ds.attrs["run_in_min_m"] == 95.0 and ds.attrs["run_in_shortened_events"] == 0
    assert "start_from_rest" not in ds.attrs.get("flag_codes", "")
    # the share of its start transient each simulated event's trucks kept (vbikit.solve.run_in.start_transient_left):
    # the example's trucks settle like the checked ones, so none is flagged start_unsettled
    left = ds["event_start_transient_left"].values
    assert np.all((left[simulated] > 0.0) & (left[simulated] <= SETTLED_TRANSIENT_LEFT)) and np.all(np.isnan(left[~simulated]))
    assert ds.attrs["start_transient_left_max"] == np.nanmax(left) and ds.attrs["start_unsettled_events"] == 0
    assert "start_unsettled" not in ds.attrs.get("flag_codes", "")
    assert ("dynamic events: sprung trucks start settled, 5 m before the bridge after driving 95 m of the road alone "
            "(crossing.run_in)") in (tmp_path / "report.txt").read_text()


def test_a_base_run_in_too_long_for_the_road_is_fitted_and_a_road_too_short_for_the_event_is_refused(tmp_path):
    """run_in = 500 on a random road of period 327.68 m (road.length 200: −163.84 … 163.83 m) is fitted like the
    population's (the truck's rear axle at −14.5 m: 163.84 − 1 − 14.5 − 1 = 147.34 m), not refused; the approach
    an event's truck reaching beyond a measured profile (from −12 m: the base scenario's stand-in, one axle 10 m
    before the bridge, fits; the truck's rear axle at −14.5 m does not) is refused before any event runs, naming the
    record and the road, not with a traceback."""
    attrs, output = _stream(tmp_path, None, run_in=500, road="length = 200.0\n")
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        got = float(ds["run_in"].values[0])
    assert 147.33 <= got <= 147.34 and attrs["run_in_m"] == 500.0 and attrs["run_in_min_m"] == got
    assert "start_from_rest" not in attrs.get("flag_codes", "")  # (10 + 147 m: settled)
    (tmp_path / "road.csv").write_text("x [m],elevation [m]\n-12,0\n40,0\n")  # (the base's stand-in: from −10 m)
    (tmp_path / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n'
                                        '[road]\nprofile_file = "road.csv"\n')
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"),
                                   "--out", str(tmp_path / "o2.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code != 0 and res.exception is None or isinstance(res.exception, SystemExit), res.output
    assert "r.csv:2: an event of the stream (1 vehicle(s) from this record on) cannot run" in res.output
    assert "covers x = -12.00 … 40.00 m" in res.output and "give a longer road" in res.output
    assert "Traceback" not in res.output


def test_an_explicit_run_in_needs_the_vehicles_off_the_deck_at_the_start(tmp_path):
    """run_in = 50 with approach = 0.5 m (less than the 1 m the tire patches need): refused before any event runs,
    naming the keys and the least approach; the population's default there is 0 (flagged, no refusal)."""
    (tmp_path / "r.csv").write_text(RECORDS)
    (tmp_path / "base.toml").write_text('[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[road]\nclass = "B"\n'
                                        "[crossing]\napproach = 0.5\nrun_in = 50\n")
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"),
                                   "--out", str(tmp_path / "o.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code != 0 and "Traceback" not in res.output
    assert "crossing.run_in = 50 m needs every contact point off the deck at the start: give crossing.approach >= 1 m" \
        in res.output
    from vbikit.solve.run_in import population_run_in

    assert population_run_in(0.5, 0.0) == 0.0 and population_run_in(1.0, 0.0) == 99.0
    assert population_run_in(3.0, 2.5) == 0.0 and population_run_in(3.5, 2.5) == 96.5  # (a skew deck's overhang)


def test_an_approach_too_short_for_a_run_in_is_flagged_with_the_approach_to_give():
    """The population's default is 0 when the approach leaves less than 1 m before the deck: the flag then asks for
    a longer approach (a run_in would be refused), not for a run_in."""
    (flag,) = start_from_rest_flags(0.5, least_approach=1.0)
    assert "give crossing.approach >= 1 m" in flag.message and "crossing.run_in =" not in flag.message
    (flag,) = start_from_rest_flags(10.0, least_approach=1.0)
    assert "crossing.run_in = 90" in flag.message


def test_the_start_of_datasets_written_before_the_shared_attributes_is_read_as_they_meant_it():
    """A lifetime.nc of the code before 2026-12-07 stored the shortest run-in as ``run_in_m`` (beside
    ``run_in_shortened_events``): read as the shortest, the population's run-in unknown when some event got less;
    a traffic dataset of that code had no ``run_in_shortened_events``: inferred from its shortest. The words never
    say a population started at rest when its run-in was given, nor that a run-in was its shortest."""
    from vbikit.analysis.population_start import start_words
    from vbikit.lifetime.report import _start_flags
    from vbikit.lifetime.report import start_words as lifetime_words

    old_lifetime = {"vehicle_model": "axle-truck", "approach_m": 5.0, "run_in_m": 60.0, "run_in_shortened_events": 3}
    assert lifetime_words(old_lifetime) == ("sprung trucks start settled, 5 m before the bridge after driving at least 60 m "
                                            "of the road alone (crossing.run_in)")
    (flag,) = _start_flags("M", old_lifetime)
    assert flag.value == 65.0 and "too short for the whole run-in on 3 events" in flag.message
    settled = dict(old_lifetime, run_in_m=95.0, run_in_shortened_events=0)
    assert "after driving 95 m of the road alone (crossing.run_in)" in lifetime_words(settled)
    assert not _start_flags("M", settled)
    old_traffic = {"approach_m": 10.0, "run_in_m": 90.0, "run_in_min_m": 60.0}
    assert start_words(old_traffic) == ("sprung vehicles start settled, 10 m before the bridge after driving 90 m of the "
                                        "road alone (crossing.run_in; the road held less on 1 event, 60 m the shortest)")
    none_held = {"approach_m": 10.0, "run_in_m": 90.0, "run_in_min_m": 0.0, "run_in_shortened_events": 2}
    assert start_words(none_held).endswith("(crossing.run_in; the road held less on 2 events, 0 m the shortest)")


def test_a_lifetime_round_that_ran_with_other_run_ins_is_run_again_with_the_rounds_after_it(tmp_path):
    """A lifetime resumed from rounds an earlier version ran with other run-ins runs the first such round again — and
    the rounds and the half-step check after it, whose events follow from its peaks: they were refused as "another
    run's work" when only the round was run again. Emulated: round 1 with its peaks scaled and the later stages made
    from those (an earlier version's state), then its run-in set to 60 m where this version gives 90 m."""
    import shutil

    import xarray as xr

    from vbikit.lifetime.run import run_lifetime

    spec = {"seed": 5, "days": 5, "traffic": {"records": str(ROOT / "examples/traffic/stream.csv"), "trucks_per_day": 20},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"},
            "road": {"class": "B"}, "load_effects": [{"kind": "moment", "x": 3.9, "name": "M"}], "block": "day",
            "distribution": "gumbel"}
    out = tmp_path / "out"
    work = out / "work"
    first = run_lifetime(spec, out, workers=1, figures=False)
    one = work / "dynamic-1.nc"

    def rewrite(change, drop_later: bool) -> None:
        with xr.open_dataset(one) as ds:
            stage = ds.load()
        assert set(stage["run_in"].values.tolist()) == {90.0}  # (this version's: the population's 90 m)
        change(stage)
        stage.to_netcdf(one.with_suffix(".tmp"))
        one.with_suffix(".tmp").replace(one)
        (out / "lifetime.nc").unlink()
        for later in [*work.glob("dynamic-*"), *work.glob("half-step*")] if drop_later else []:
            if later.name != one.name:
                shutil.rmtree(later) if later.is_dir() else later.unlink()

    rewrite(lambda stage: stage.__setitem__("dyn_peak", stage["dyn_peak"] * 1.6), True)  # (an earlier version's peaks)
    run_lifetime(spec, out, workers=1, figures=False)  # (the later stages made from them)
    assert len(list(work.glob("dynamic-*.nc"))) > 1  # (rounds after the first: what round 1's peaks decide)
    rewrite(lambda stage: stage.__setitem__("run_in", stage["run_in"] * 0 + 60.0), False)  # (and its other run-in)
    again = run_lifetime(spec, out, workers=1, figures=False)
    with xr.open_dataset(one) as ds:
        assert set(ds["run_in"].values.tolist()) == {90.0}  # (run again with this version's run-in)
    assert float(again["characteristic_total"].values[0]) == float(first["characteristic_total"].values[0])
