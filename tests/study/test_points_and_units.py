"""Study and traffic datasets: several response points (a ``point`` dimension) and units from the
one output catalogue (the impact factors of moments, shears and reactions are dimensionless)."""
from __future__ import annotations

import copy

import numpy as np
import pytest

from vbikit.outputs import OUTPUTS
from vbikit.study import parse_study, run_study
from vbikit.traffic import LaneTraffic, synthetic_stream
from vbikit.traffic.study import traffic_study

BASE = {
    "bridge": {"model": "paper-bridge-2-beam", "n_modes": 4},
    "vehicle": {"model": "two-axle"},
    "road": {"class": "C", "length": 200},
    "crossing": {"speed_kmh": 90},
}
POINTS = [{"name": "quarter", "x": 4.19}, {"name": "mid", "x": 8.38}]


def study(base: dict) -> dict:
    return {"name": "points", "seed": 3, "batch_size": 2, "base": base,
            "axes": {"crossing.speed_kmh": [60, 90], "road.seed": {"samples": 2}}}


def test_study_points_equal_single_point_studies(tmp_path):
    several = copy.deepcopy(BASE) | {"response": {"points": POINTS}}
    ds = run_study(parse_study(study(several)), tmp_path / "both.nc", workers=1)
    assert ds["impact_factor"].dims == ("crossing_speed_kmh", "sample", "point")
    assert list(ds["point"].values) == ["quarter", "mid"]
    assert ds["min_tire_force"].dims == ("crossing_speed_kmh", "sample")  # per crossing, not per point
    for k, p in enumerate(POINTS):
        alone = run_study(parse_study(study(copy.deepcopy(BASE) | {"response": {"x": p["x"]}})), tmp_path / f"{k}.nc", workers=1)
        assert "point" not in alone.dims
        for name in ("impact_factor", "max_static_displacement", "strain_impact_factor", "max_abs_acceleration"):
            np.testing.assert_array_equal(ds[name].isel(point=k).values, alone[name].values, err_msg=name)
    # the quarter point deflects less than midspan under the same crossings
    assert np.all(np.abs(ds["max_static_displacement"].sel(point="quarter")) < np.abs(ds["max_static_displacement"].sel(point="mid")))


def test_dataset_units_come_from_the_catalogue(tmp_path):
    ds = run_study(parse_study(study(copy.deepcopy(BASE))), tmp_path / "s.nc", workers=1)
    for kind in ("moment", "shear", "reaction"):
        assert ds[f"{kind}_impact_factor"].attrs["units"] == "1"
        assert np.all(np.isfinite(ds[f"{kind}_impact_factor"].values))
    assert ds["moment_static_peak"].attrs["units"] == "N m" and ds["shear_static_peak"].attrs["units"] == "N"
    assert ds["max_abs_acceleration"].attrs["units"] == "m s-2"
    for name, output in OUTPUTS.items():
        assert ds[name].attrs["units"] == output.cf_unit and ds[name].attrs["long_name"] == output.long_name
    assert all(o.unit == "-" for name, o in OUTPUTS.items() if name.endswith("impact_factor"))


def test_traffic_dataset_has_the_points():
    stream = synthetic_stream([LaneTraffic(1, "+x", 900, 80, 5)], 4, seed=2)
    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "road": {"class": "B", "length": 200.0},
            "crossing": {"approach": 5.0, "free_vibration": 0.1}}
    several = traffic_study(stream, base | {"response": {"points": POINTS}}, seed=5, batch_size=2)
    one = traffic_study(stream, base | {"response": {"x": POINTS[1]["x"]}}, seed=5, batch_size=2)
    events = tuple(range(several.size))
    rows = several.run_batch(events)
    single = one.run_batch(events)
    assert rows["impact_factor"].shape == (several.size, 2) and single["impact_factor"].shape == (several.size, 1)
    np.testing.assert_array_equal(rows["impact_factor"][:, 1], single["impact_factor"][:, 0])
    np.testing.assert_array_equal(rows["moment_impact_factor"], single["moment_impact_factor"])
    ds = several.dataset(*_assembled(several, rows))
    assert ds["impact_factor"].dims == ("event", "point") and list(ds["point"].values) == ["quarter", "mid"]
    assert ds["impact_factor"].attrs["units"] == "1"


def _assembled(job, rows):
    ev = {k: v for k, v in rows.items() if k not in ("event", "vehicle") and not k.startswith("vehicle_")}
    veh = {k: v for k, v in rows.items() if k.startswith("vehicle_")}
    return ev, veh


@pytest.mark.parametrize("name", ["impact_factor", "moment_impact_factor", "min_tire_force", "n_steps"])
def test_every_catalogue_output_has_one_unit_and_name(name):
    o = OUTPUTS[name]
    assert o.name == name and o.unit and o.long_name and o.scope in ("point", "crossing")


def test_a_stream_figure_with_several_points(tmp_path):
    from vbikit.plot.traffic import plot_stream
    from vbikit.study.run import run_study

    stream = synthetic_stream([LaneTraffic(1, "+x", 900, 80, 5)], 3, seed=2)
    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "road": {"class": "B", "length": 200.0},
            "crossing": {"approach": 5.0, "free_vibration": 0.1}, "response": {"points": POINTS}}
    ds = run_study(traffic_study(stream, base, seed=5, batch_size=2), tmp_path / "t.nc", workers=1)
    assert plot_stream(ds, tmp_path / "t.png").stat().st_size > 0


def test_a_study_over_tire_models_keeps_each_models_keys():
    """An axis over tire.model on a multi-point base: each model gets the base keys it takes."""
    base = copy.deepcopy(BASE) | {"tire": {"model": "multipoint", "n_points": 4, "loss_of_contact": False}}
    s = parse_study({"name": "tires", "base": base, "axes": {"tire.model": ["point", "multipoint", "disk"]}})
    assert [s.scenario_dict((i,))["tire"] for i in range(3)] == [
        {"model": "point", "loss_of_contact": False}, {"model": "multipoint", "n_points": 4, "loss_of_contact": False},
        {"model": "disk", "loss_of_contact": False}]


def test_stored_parts_of_one_point_read_with_and_without_a_point_axis():
    """A finished part from before response points ((rows,) per output) is used for a [response]
    study; a part without a catalogue output is refused with the reason (then recomputed)."""
    from vbikit.study.run import output_problem, part_output

    legacy = {name: np.arange(3.0) for name in OUTPUTS}
    assert output_problem(legacy, 3, 1) is None
    assert part_output(legacy, "impact_factor", 1).shape == (3, 1)
    assert output_problem(legacy, 3, 2) == "impact_factor has the wrong shape"
    del legacy["time_of_max_dynamic_displacement"]
    assert "no time_of_max_dynamic_displacement" in output_problem(legacy, 3, 1)


def test_small_static_reference_is_flagged_in_the_dataset(tmp_path):
    """A point 0.5 m from the entry support beside mid-span: its static peak deflection is a small
    fraction of mid-span's in every crossing, so its impact factor is flagged in the dataset's
    ``warnings`` attribute with the count of crossings, recomputed here from the stored static peaks
    (|R_st| < 20 % of the larger: vbikit.analysis.checks.SMALL_STATIC_FRACTION); the mid-span point
    is not flagged."""
    from vbikit.analysis.checks import SMALL_STATIC_FRACTION

    points = [{"name": "near", "x": 0.5}, {"name": "mid", "x": 8.38}]
    ds = run_study(parse_study(study(copy.deepcopy(BASE) | {"response": {"points": points}})), tmp_path / "s.nc", workers=1)
    st = np.abs(ds["max_static_displacement"].values).reshape(-1, 2)
    near = int((st[:, 0] < SMALL_STATIC_FRACTION * st.max(axis=1)).sum())
    assert near == st.shape[0] == 4 and not np.any(st[:, 1] < SMALL_STATIC_FRACTION * st.max(axis=1))
    # (the dataset's warnings, "; "-joined: this one among them; the strain-convergence one may come first)
    text = next(t for t in ds.attrs["warnings"].split("; ") if "rests on a static deflection" in t)
    assert text.startswith("point near: its impact_factor rests on a static deflection under 20%")
    assert f"in {near} of 4 crossings" in text and "point mid" not in text
