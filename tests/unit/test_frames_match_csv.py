"""Python results and files share names and units: ``Report.to_dataframe()`` carries every column
of the CSV (``vbikit run --out X.csv``) under the same header with the same numbers, and
``to_xarray()`` the same names (points by name, ``contact_force``, moments and shears).  On main the
frames named points ``p1``/``0, 1`` and forces ``wheel_force`` while the CSV wrote the point names
and ``contact_force``, and the moment/shear columns were missing."""
from __future__ import annotations

import csv
import re

import numpy as np
import pytest

import vbikit

SCENARIO = """
[bridge]
model = "continuous-beam"
spans = [12.0, 12.0]
EI = 8.323e9
mass_per_length = 2303.0
n_modes = 8
[[vehicles]]
model = "moving-force"
force = 100e3
speed = 15.0
[[vehicles]]
model = "moving-force"
force = 60e3
speed = 15.0
entry_time = 0.4
[road]
class = "none"
[crossing]
approach = 0.0
[response]
moment = [6.0, 12.0]
shear = [0.0]
[[response.points]]
name = "quarter"
x = 6.0
[[response.points]]
name = "pier_right"
x = 18.0
"""


@pytest.fixture(scope="module")
def report():
    return vbikit.run(SCENARIO)


def test_every_csv_column_is_in_the_dataframe_under_the_same_header(report, tmp_path):
    path = report.write_csv(tmp_path / "h.csv")
    with path.open() as fh:
        rows = list(csv.reader(fh))
    header, values = rows[0], np.array(rows[1:], float)
    df = report.to_dataframe()
    frame = {"time [s]": df.index.to_numpy(), **{c: df[c].to_numpy() for c in df.columns}}
    missing = [h for h in header if h not in frame]
    assert not missing, missing
    for j, h in enumerate(header):  # the CSV has 9 significant digits
        np.testing.assert_allclose(frame[h], values[:, j], rtol=1e-8, atol=1e-12 * np.max(np.abs(values[:, j])), err_msg=h)
    names = {re.sub(r" \[.*\]$", "", h) for h in header}
    # what the scenario asked for, spelled out independently of the code
    for expected in ("displacement_quarter", "displacement_pier_right", "contact_force_", "v1_front_axle_x", "v2_front_axle_x"):
        assert any(n.startswith(expected) for n in names), expected
    moments = [h for h in header if h.startswith("moment_") and h.endswith("[N m]")]
    shears = [h for h in header if h.startswith("shear_") and h.endswith("[N]")]
    assert len(moments) == 4 and len(shears) == 2  # 2 moments and 1 shear, each dynamic and static


def test_xarray_uses_the_csv_names_and_cf_units(report):
    ds = report.to_xarray()
    assert list(ds["point"].values) == ["quarter", "pier_right"]
    assert "wheel_force" not in ds and ds["contact_force"].attrs["units"] == "N"
    assert ds["contact_force"].dims == ("time", "wheel")
    for e in report.effects:
        assert ds[e.name].attrs["units"] == ds[f"{e.name}_static"].attrs["units"] == e.effect.units
        np.testing.assert_array_equal(ds[e.name].values, e.dynamic)
    kinds = [e.effect.kind for e in report.effects]
    assert kinds.count("moment") == 2 and kinds.count("shear") == 1
    # a point by its name gives that point's history
    np.testing.assert_allclose(ds["displacement"].sel(point="pier_right").values, report.points[1].displacement,
                               rtol=1e-12, atol=1e-17)


def test_a_crossing_result_alone_names_points_as_the_csv_does(report):
    ds = report.result.to_xarray(points=[(6.0, 0.0), (18.0, 0.0)])
    assert list(ds["point"].values) == ["p1", "p2"]
    df = report.result.to_dataframe(points=[(6.0, 0.0), (18.0, 0.0)])
    assert "displacement_p2 [m]" in df.columns and any(c.startswith("contact_force_") for c in df.columns)
