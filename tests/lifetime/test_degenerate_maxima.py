"""A lifetime run whose block maxima cannot be fitted (every truck identical: all daily maxima
equal) still writes its results: the characteristic values are NaN and say why in words, the
fatigue result and the rest stand; the too-few-maxima advice names only settings not in use.

Independent numbers: a 200 kN two-axle truck (100 + 100 kN, 20 m apart) on a 10 m simply
supported span has one axle on it at a time, so its midspan moment peaks at P L / 4 = 250 kN m
(closed form) twice per truck, each a full stress cycle 0 → 250 kN m / Z → 0 (rainflow of the
isolated triangles); with Z = 0.005 m³ that is Δσ = 50 MPa, above EN 1993-1-9 detail 36's
constant-amplitude limit Δσ_D = 26.5 MPa, so Miner's sum is 2 n_trucks (50/36)³ / 2e6 (Table 7.1
curve m = 3 through 36 MPa at 2e6 cycles).
"""
import json
import re

import numpy as np
import pytest
import xarray as xr

from vbikit.analysis.checks import find_flag
from vbikit.extremes import ExtremesError, fit_block_maxima
from vbikit.lifetime.run import prepare, run_lifetime
from vbikit.lifetime.spec import LifetimeError

from tests.lifetime.specs import SPAN, beam_spec

P, Z = 100e3, 0.005

SPEC = beam_spec("identical trucks", 1, 5, "[75, 1000]", "same.csv", 20, f'''[fatigue]
dynamic_sample = 0.3
[[fatigue.details]]
name = "d"
effect = "M"
section_modulus = {Z}
category = "EN 36"
''')


def _write(tmp_path):
    rows = ["id,time [s],lane,lateral_offset [m],direction,speed [km/h],model,axle_loads [kN],axle_spacings [m]"]
    rows += [f"v{i:03d},{100 + 2000.0 * i:.1f},1,,+x,80,axles,100 100,20" for i in range(40)]
    (tmp_path / "same.csv").write_text("\n".join(rows) + "\n")
    (tmp_path / "lt.toml").write_text(SPEC)
    return tmp_path / "lt.toml"


def test_identical_trucks_write_every_result(tmp_path):
    out = tmp_path / "out"
    ds = run_lifetime(_write(tmp_path), out, workers=1, figures=True)
    for f in ("lifetime.nc", "summary.json", "report.txt", "lifetime-gumbel.png", "lifetime-fatigue.png"):
        assert (out / f).is_file(), f
    np.testing.assert_allclose(ds["daily_max_static"].values[:, 0], P * SPAN / 4, rtol=1e-6)
    assert np.isnan(ds["characteristic_static"].values[0]) and np.isnan(ds["assessment_dynamic_ratio"].values[0])
    why = str(ds["characteristic_static_not_estimable"].values[0])
    assert why.startswith("not estimable: all 5 daily maxima are equal (250000 N m")
    assert "M static: not estimable" in ds.attrs["not_estimable"]
    # fatigue: closed-form Miner sum (module docstring); every truck its own event
    n = ds.attrs["n_trucks"]
    assert ds.attrs["n_events"] == n
    dsig = P * SPAN / 4 / Z / 1e6
    assert ds["fatigue_damage_static"].values[0] == pytest.approx(2 * n * (dsig / 36.0) ** 3 / 2e6, rel=1e-5)
    assert np.isfinite(ds["fatigue_damage"].values[0]) and ds["fatigue_damage"].values[0] > 0
    facts = json.loads((out / "summary.json").read_text())
    m = facts["load_effects"]["M"]
    assert m["characteristic_static"] is None and m["characteristic_static_not_estimable"] == why
    flag = find_flag(m, "characteristic_not_estimable", output="characteristic static value")
    assert flag["message"] == f"characteristic static {why}" and flag["message"] in m["warnings"]
    assert flag["value"] is None and flag["subject"] == "M"
    report = (out / "report.txt").read_text()
    assert "! characteristic static not estimable: all 5 daily maxima are equal (250000 N m" in report
    assert "np.float64" not in report and re.search(r"\bM\s+kN m\s+n/a!?\s+n/a!?\s+n/a!?", report)  # (the report in kN m)
    with xr.open_dataset(out / "lifetime.nc") as back:
        assert str(back["characteristic_static_not_estimable"].values[0]) == why


def test_equal_maxima_message_formats_numbers_plainly():
    with pytest.raises(ExtremesError, match=re.escape("maxima: all 5 values are equal (250000); nothing to fit")):
        fit_block_maxima(np.full(5, 249999.99950000003), "gumbel", 365.0)


@pytest.mark.parametrize("change, advice", [
    ({"days": 2}, "(raise days to at least 5)"),
    ({"days": 14, "block": "week"}, '(raise days to at least 35, or block = "day" (then days >= 5))'),
    ({"days": 7, "distribution": "gev"}, '(raise days to at least 10, or distribution = "gumbel" (needs 5 maxima))'),
])
def test_too_few_maxima_advice_names_other_settings(change, advice):
    spec = {"days": 5, "traffic": {"records": "examples/lifetime/wim.csv"},
            "bridge": {"model": "paper-bridge-1-beam", "n_modes": 3},
            "load_effects": [{"kind": "moment", "x": 4.0, "name": "M"}], **change}
    with pytest.raises(LifetimeError) as err:
        prepare(spec, ".")
    assert str(err.value).endswith(advice)
    if change.get("block", "day") == "day":
        assert 'block = "day"' not in str(err.value)
