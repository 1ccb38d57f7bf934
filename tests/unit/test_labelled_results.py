"""Labelled results: CrossingResult.to_xarray / to_dataframe carry units and the right numbers."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.contact import PointTire
from vbikit.road import RoadProfile
from vbikit.solve import Crossing, simulate
from vbikit.vehicle.presets import moving_force

L, EI, M, P = 25.0, 8.323e9, 2303.0, 100e3


@pytest.fixture(scope="module")
def result():
    beam = EulerBernoulliBeam(span=L, EI=EI, mass_per_length=M, n_modes=10, damping_ratio=0.0)
    return simulate(Crossing(beam, moving_force(P), PointTire(), RoadProfile.flat(), speed=20.0))


def test_every_variable_and_coordinate_has_units(result):
    ds = result.to_xarray(points=[(L / 2, 0.0), (L / 4, 0.0)])
    assert ds["time"].attrs["units"] == "s" and ds.sizes["point"] == 2
    for name, var in ds.data_vars.items():
        assert var.attrs.get("units") and var.attrs.get("long_name"), name
    assert ds["displacement"].dims == ("time", "point")
    assert ds["acceleration"].attrs["units"] == "m s-2" and ds["strain"].attrs["units"] == "1"
    assert list(ds["x"].values) == [L / 2, L / 4]


def test_static_reference_matches_the_closed_form(result):
    # Static midspan deflection under P at a (a ≤ L/2) of a simple beam: P a (3L² − 4a²) / (48 EI)
    # (z up: negative); P L³/48EI at a = L/2.  10 modes: the truncated sine series is within
    # 2e-4 of it (measured 1.1e-5 at midspan).
    ds = result.to_xarray()
    i = int(np.argmin(np.abs(ds["front_axle_x"].values - L / 2)))
    x = float(ds["front_axle_x"].values[i])
    a = min(x, L - x)
    exact = -P * a * (3 * L**2 - 4 * a**2) / (48 * EI)
    assert abs(x - L / 2) < 0.5
    assert ds["static_displacement"].values[i, 0] == pytest.approx(exact, rel=2e-4)
    # the dynamic history is that of the result's own accessor
    np.testing.assert_array_equal(ds["displacement"].values[:, 0], result.displacement())


def test_dataframe_headers_name_units(result):
    df = result.to_dataframe()
    assert df.index.name == "time [s]"
    for col in ("displacement [m]", "acceleration [m/s^2]", "strain [-]", "contact_force_P [N]", "front_axle_x [m]"):
        assert col in df.columns
    assert all(c.endswith("]") for c in df.columns)
    np.testing.assert_array_equal(df["displacement [m]"].to_numpy(), result.displacement())
