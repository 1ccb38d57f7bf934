"""A random run's dataset names what the ordinary run's dataset names alike (``RandomResponse.dataset`` against
``CrossingResult.to_xarray``): the response points by their names (``p1`` or the plan's, not 0, 1, …), the tire
forces ``contact_force`` (it wrote ``wheel_force``), and the vehicle DOFs' units by the one rule of a variable whose
members have several units (``vbikit.outputs.member_units``: the HS20-44 has heave, pitch and roll DOFs, m and rad, so no
``units`` but ``units_by_dof`` naming the coordinate of each; it wrote "m s-2 or rad s-2", which no unit parser
reads)."""
from __future__ import annotations

import dataclasses

import numpy as np

from tests.random_vibration.test_pem_monte_carlo import _plan
from vbikit.analysis.plan import ResponsePoint
from vbikit.random import PseudoRoad
from vbikit.random.response import random_response
from vbikit.road.psd import RoadPSD


def test_the_random_dataset_uses_the_ordinary_datasets_names_and_units():
    plan = _plan(2, {"model": "point"})
    span = plan.built.crossing.bridge.span
    points = (ResponsePoint(x=span / 2, name="mid"), ResponsePoint(x=span / 4))  # (named, then unnamed: "p2")
    response_plan = dataclasses.replace(plan.built.plan, points=points)
    rr = random_response(plan.built.crossing, response_plan, PseudoRoad(RoadPSD.iso("C")), plan.run.dt,
                         data=plan.run.kernel_data, samples=200)
    ds = rr.dataset()
    ordinary = rr.mean.to_xarray(points=[(p.x, 0.0) for p in rr.points], names=["mid", "p2"])
    assert list(ds["point"].values) == ["mid", "p2"] == list(ordinary["point"].values)
    np.testing.assert_array_equal(ds["x"].values, [span / 2, span / 4])
    # every random variable is an ordinary variable's name with _mean / _std (or a load effect's)
    for name in ("displacement", "acceleration", "strain", "contact_force", "vehicle_acceleration"):
        assert name in ordinary.data_vars and f"{name}_mean" in ds and f"{name}_std" in ds, name
        assert ds[f"{name}_mean"].dims == ordinary[name].dims, name
    assert "wheel_force_mean" not in ds and ds["contact_force_mean"].attrs["units"] == "N"
    # the mean is the smooth crossing's own history, under the ordinary name
    np.testing.assert_array_equal(ds["contact_force_mean"].values, ordinary["contact_force"].values[:ds.sizes["time"]])
    # heave in m, pitch and roll in rad: one unit each through the coordinate the variable names, no packed unit
    dofs = list(ds["dof"].values)
    rotation = [d.endswith(("_pitch", "_roll")) for d in dofs]  # (the truck's tractor, trailer and axles roll too)
    assert any(rotation) and not all(rotation)
    for data in (ds, ordinary):
        for var, coord in (("vehicle_acceleration" if data is ordinary else "vehicle_acceleration_mean",
                            "dof_acceleration_units"),):
            attrs = data[var].attrs
            assert "units" not in attrs and attrs["units_by_dof"] == coord, attrs
            assert [str(u) for u in data[coord].values] == ["rad s-2" if r else "m s-2" for r in rotation]
        assert [str(u) for u in data["dof_units"].values] == ["rad" if r else "m" for r in rotation]
        assert not [v for v in data.data_vars if " or " in str(data[v].attrs.get("units", ""))]
    assert ordinary["vehicle_displacement"].attrs["units_by_dof"] == "dof_units"


def test_the_random_summary_names_its_points_and_gives_every_numbers_unit_and_the_dataset_its_flags():
    """A trial found the random summary's points without names (the dataset named them), no unit for
    ``vehicle_acceleration_std_max``, the dataset's time and x, y without units and its flags as one string."""
    import json

    from vbikit.solve.result import dof_acceleration_unit

    plan = _plan(2, {"model": "point"})
    span = plan.built.crossing.bridge.span
    response_plan = dataclasses.replace(plan.built.plan, points=(ResponsePoint(x=span / 2, name="mid"),
                                                                 ResponsePoint(x=0.05 * span)))
    rr = random_response(plan.built.crossing, response_plan, PseudoRoad(RoadPSD.iso("C")), plan.run.dt,
                         data=plan.run.kernel_data, samples=200)
    s = rr.summary
    assert [p["name"] for p in s["points"]] == ["mid", "p2"]
    dofs = rr.mean.crossing.vehicle.dof_names
    assert s["units"]["vehicle_acceleration_std_max"] == {d: dof_acceleration_unit(d) for d in dofs}
    assert set(s["vehicle_acceleration_std_max"]) == set(dofs)
    ds = rr.dataset()
    assert ds["time"].attrs["units"] == "s" and ds["x"].attrs["units"] == "m" and ds["y"].attrs["units"] == "m"
    assert s["flags"], "the near-support point rests on a small static reference: flagged"
    assert json.loads(ds.attrs["flags"]) == s["flags"]
    assert ds.attrs["flag_codes"].split(",") == list(dict.fromkeys(f["code"] for f in s["flags"]))
    assert ds.attrs["warnings"] == "; ".join(s["warnings"])
