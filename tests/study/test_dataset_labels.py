"""A finished study dataset: units on every coordinate and variable, no lock file left beside it."""
from __future__ import annotations

import xarray as xr

from vbikit.study import parse_study, run_study


def test_coordinates_have_units_and_no_lock_is_left(tmp_path, small_study_dict):
    small_study_dict["axes"]["crossing.speed_kmh"] = [60.0, 90.0]
    out = tmp_path / "labels.nc"
    run_study(parse_study(small_study_dict), out, workers=1)
    assert not (tmp_path / "labels.nc.lock").exists()
    ds = xr.open_dataset(out)
    try:
        for name, coord in ds.coords.items():
            assert "units" in coord.attrs, name
        assert ds["crossing_speed_kmh"].attrs["units"] == "km h-1"  # the schema's [km/h], CF spelling
        assert ds["tire_n_points"].attrs["units"] == "1"
        assert ds["road_class"].attrs["units"] == ""                 # a category has no unit
        assert ds["sample"].attrs["units"] == "1" and ds["road_seed"].attrs["units"] == "1"
        for name, var in ds.data_vars.items():
            assert "units" in var.attrs, name
    finally:
        ds.close()
