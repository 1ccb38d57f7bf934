"""`vbikit run` on a continuous beam: moment / shear / reaction blocks with design-code values,
histories in --out, validation of the new keys.

Independent numbers: the design-code formulas (AASHTO Standard 50/(L+125) with L in ft, JTG D60
0.1767 ln f − 0.0157) evaluated here by hand; equilibrium (a single span's two static reactions
under one moving force add up to the force)."""
from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "bridges" / "three_span_continuous_hs20.toml"

SMALL = """
[bridge]
model = "continuous-beam"
spans = [12.0, 15.0]
EI = [5e9, 6e9]
mass_per_length = 6000.0
n_modes = 6
{extra}
[vehicle]
model = "moving-force"
force = 1e5
[crossing]
speed_kmh = 40
[response]
{response}
"""


def _run(tmp_path: Path, text: str, *args: str):
    path = tmp_path / "s.toml"
    path.write_text(text)
    return runner.invoke(app, ["run", str(path), *args])


def test_json_blocks_and_code_values(tmp_path):
    res = _run(tmp_path, SMALL.format(extra="", response=""), "--json", "--out", str(tmp_path / "h.csv"))
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)
    for kind in ("moment", "shear", "reaction"):
        block = s[kind]
        assert {"static_peak", "dynamic_peak", "impact_factor", "sections", "method"} <= set(block)
        assert block["method"] == "mode-acceleration"
    # default sections: two midspans then the pier (hogging, negative static peak)
    xs = [e["x"] for e in s["moment"]["sections"]]
    assert xs == [6.0, 19.5, 12.0]
    pier = s["moment"]["sections"][2]
    assert pier["hogging_region"] and pier["static_peak"] < 0 and pier["dynamic_peak"] < 0
    # AASHTO Standard loaded length over the pier: mean of the spans (13.5 m = 44.29 ft)
    assert pier["code_allowances"]["aashto_standard"] == pytest.approx(50 / (13.5 / 0.3048 + 125), rel=1e-12)
    f1 = s["frequencies_hz"][0]
    c = s["design_code_allowances"]
    assert c["jtg_d60_2015"] == pytest.approx(0.1767 * math.log(f1) - 0.0157 if 1.5 <= f1 <= 14 else c["jtg_d60_2015"])
    assert c["aashto_lrfd"] == 0.33 and c["csa_s6"] == 0.40  # one axle
    assert len(s["reaction"]["sections"]) == 3
    with open(tmp_path / "h.csv") as fh:
        header = next(csv.reader(fh))
    assert {"moment_x12 [N m]", "moment_x12_static [N m]", "shear_x0 [N]", "reaction_s1 [N]", "reaction_s1_static [N]"} <= set(header)


def test_selected_sections_and_method(tmp_path):
    res = _run(tmp_path, SMALL.format(extra="", response='moment = [3.0]\nshear = [12.0]\nreaction = [2]\n'
                                      'load_effect_method = "mode-superposition"'), "--json")
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)
    assert [e["x"] for e in s["moment"]["sections"]] == [3.0]
    assert s["reaction"]["support"] == 2 and s["moment"]["method"] == "mode-superposition"


def test_text_report_shows_codes_beside_im(tmp_path):
    res = _run(tmp_path, SMALL.format(extra="", response=""))
    assert res.exit_code == 0, res.output
    assert "AASHTO LRFD 0.330" in res.output and "JTG D60-2015" in res.output
    assert "moment   x = 12.00 m" in res.output


@pytest.mark.parametrize("extra, response, message", [
    ("", "moment = [40.0]", "response: moment: section x must be within 0"),
    ("", "reaction = [5]", "reaction: support must be 0 … 2"),
    ("support_stiffness = [1e8, 1e8]", "", "support_stiffness: one value or one per support (3)"),
    ("[[bridge.damage]]\nposition = 20.0\nlength = 10.0\nseverity = 0.3", "", "ends beyond the bridge"),
    ("[[bridge.damage]]\nposition = 2.0\nlength = 1.0\nseverity = 1.2", "", "severity"),
])
def test_bad_input_names_the_key(tmp_path, extra, response, message):
    res = _run(tmp_path, SMALL.format(extra=extra, response=response))
    assert res.exit_code == 2
    assert message in res.output


def test_lists_need_continuous_beam(tmp_path):
    text = "[bridge]\nmodel = \"beam\"\nspan = 10.0\nEI = [1e9, 2e9]\nmass_per_length = 1000.0\n[vehicle]\nmodel = \"moving-force\"\n[crossing]\nspeed = 10\n"
    res = _run(tmp_path, text)
    assert res.exit_code == 2 and "continuous-beam" in res.output


def test_three_span_example_runs():
    res = runner.invoke(app, ["run", str(EXAMPLE), "--json"])
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)
    assert len(s["moment"]["sections"]) == 5 and len(s["reaction"]["sections"]) == 4
    assert s["design_code_allowances"]["csa_s6"] == 0.25  # three axles


def test_rigid_supports_as_inf_and_springs(tmp_path):
    res = _run(tmp_path, SMALL.format(extra="support_stiffness = [inf, 2e8, inf]\nrotational_stiffness = [0.0, inf]",
                                      response=""), "--json")
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)
    # a softer pier takes less load and the pier moment hogs less than on rigid supports
    rigid = json.loads(_run(tmp_path, SMALL.format(extra="", response=""), "--json").stdout)
    assert s["reaction"]["sections"][1]["static_peak"] < rigid["reaction"]["sections"][1]["static_peak"]
    assert s["moment"]["sections"][2]["static_peak"] > rigid["moment"]["sections"][2]["static_peak"]


def test_cli_and_python_give_the_same_load_effects():
    # one truth: the example through `vbikit run` and through the Python API with the models' defaults
    from vbikit.analysis.effects import load_effect_response
    from vbikit.bridge.continuous import ContinuousBeam
    from vbikit.contact import MultiPointTire
    from vbikit.road import RoadPSD, random_profile
    from vbikit.solve import Crossing, simulate
    from vbikit.vehicle.presets import hs20_44

    s = json.loads(runner.invoke(app, ["run", str(EXAMPLE), "--json"]).stdout)
    beam = ContinuousBeam((20.0, 25.0, 20.0), 1.286e10, 7537.0, n_modes=12, neutral_axis_depth=0.78)
    res = simulate(Crossing(beam, hs20_44(), MultiPointTire(6), random_profile(RoadPSD.iso("C"), seed=1), speed=75 / 3.6))
    pier = load_effect_response(res, beam.load_effect("moment", x=20.0)).impact
    entry = next(e for e in s["moment"]["sections"] if e["x"] == 20.0)
    # the CLI reduces all its effects in one batched pass (matrix products summed in another order
    # than one effect alone): equal to round-off
    assert entry["impact_factor"] == pytest.approx(pier.impact_factor, rel=1e-12, abs=1e-14)
    assert entry["static_peak"] == pytest.approx(pier.static_peak, rel=1e-12)


def test_soft_pier_reports_the_hogging_extreme_too(tmp_path):
    # spans 12 + 18 m on a 7e7 N/m pier under a 100 kN force: the pier moment's largest static value is
    # sagging, +188.39 kN m, the hogging one −58.79 kN m (the force method's influence line of
    # tests/verification/test_two_signed_effects.py, times 100 kN); the hogging one is reported beside it
    # (opposite_*), flagged sagging_over_pier, and printed on its own line
    text = SMALL.replace("spans = [12.0, 15.0]", "spans = [12.0, 18.0]").replace("EI = [5e9, 6e9]", "EI = 1.286e10")
    text = text.format(extra="support_stiffness = [1e12, 7e7, 1e12]", response="moment = [12.0]")
    s = json.loads(_run(tmp_path, text, "--json").stdout)
    m = s["moment"]
    assert m["hogging_region"] and m["static_peak"] > 0 and m["sense"] == "sagging" and m["two_signed"]
    assert m["static_peak"] == pytest.approx(188.394e3, rel=1e-3) and m["opposite_dynamic_peak"] < 0
    assert m["opposite_static_peak"] == pytest.approx(-58.791e3, rel=1e-3)
    assert m["opposite_impact_factor"] == pytest.approx(
        (m["opposite_dynamic_peak"] - m["opposite_static_peak"]) / m["opposite_static_peak"], rel=1e-12)
    assert [f["code"] for f in s["flags"] if f["output"] == "moment"] == ["sagging_over_pier"]
    out = _run(tmp_path, text).stdout
    line = next(ln for ln in out.splitlines() if "and hogging" in ln)
    assert f"(the {m['governing']} dynamic peak governs)" in line and "hogging, " not in out
    assert f"{m['opposite_static_peak'] * 1e-3:+10.2f}" in line and f"{m['opposite_impact_factor']:7.4f}" in line
