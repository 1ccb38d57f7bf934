"""The start from rest (docs/traffic.md, "Start from rest and the approach"): a population whose events start
their sprung vehicles less than SETTLED_APPROACH (100 m) before the bridge is flagged start_from_rest — in
the traffic dataset (warnings, flag_codes, approach_m) and in a lifetime's per-effect flags — and one whose
base scenario sets crossing.approach = 100 is not; moving constant forces never are."""
from __future__ import annotations

import xarray as xr
from typer.testing import CliRunner

from vbikit.analysis.checks import SETTLED_APPROACH, start_from_rest_flags
from vbikit.cli import app

RECORDS = ("time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"
           "0,1,+x,80,50 120,4.5\n")


def test_the_rule_flags_approaches_below_the_settled_one_only():
    assert SETTLED_APPROACH == 100.0  # (docs/traffic.md: converged at 100 m, measured)
    (flag,) = start_from_rest_flags(10.0)
    assert flag.code == "start_from_rest" and flag.value == 10.0 and flag.threshold == 100.0
    assert "10 m before the bridge" in flag.message and "crossing.run_in = 90" in flag.message
    assert start_from_rest_flags(99.9) and not start_from_rest_flags(100.0) and not start_from_rest_flags(250.0)


def _stream(tmp_path, approach: float | None):
    (tmp_path / "r.csv").write_text(RECORDS)
    base = '[bridge]\nmodel = "paper-bridge-1-beam"\nn_modes = 3\n[tire]\nmodel = "point"\n[road]\nclass = "B"\n'
    if approach is not None:
        base += f"[crossing]\napproach = {approach}\n"
    (tmp_path / "base.toml").write_text(base)
    res = CliRunner().invoke(app, ["traffic", str(tmp_path / "r.csv"), "--bridge", str(tmp_path / "base.toml"),
                                   "--out", str(tmp_path / "o.nc"), "--workers", "1", "--no-progress"])
    assert res.exit_code == 0, res.output
    with xr.open_dataset(tmp_path / "o.nc") as ds:
        return dict(ds.attrs), res.output


def test_a_stream_with_the_default_approach_is_flagged_and_says_how_to_settle(tmp_path):
    attrs, output = _stream(tmp_path, None)
    assert attrs["approach_m"] == 10.0
    assert "start_from_rest" in attrs["flag_codes"].split(",")
    assert "at rest 10 m before the bridge" in attrs["warnings"]
    assert "at rest 10 m before the bridge" in output  # (printed by vbikit traffic)


def test_a_stream_started_100_m_before_the_bridge_is_not(tmp_path):
    attrs, output = _stream(tmp_path, 100.0)
    assert attrs["approach_m"] == 100.0
    assert "start_from_rest" not in attrs.get("flag_codes", "").split(",")
    assert "at rest" not in output


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
