"""`vbikit run` reproduces the verification scenarios in examples/verification/.

References (independent of vbikit): Yang & Yau 1997 midspan peak 2.41 mm, static
P L³/48EI = 2.206 mm, vehicle peak acceleration ≈ 0.15 m/s² (docs/model-data.md §5);
Frýba 1972 DAF(α = 0.5) = 1.705 (docs/model-data.md §5, 50 modes).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from vbikit.cli import app

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "verification"
runner = CliRunner()


def run_json(path: Path) -> dict:
    res = runner.invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_yang_yau_from_scenario_file():
    s = run_json(EXAMPLES / "yang_yau_sprung_mass.toml")
    # published values are given to 3 digits: compare within half a unit of the last digit + 0.3 %
    assert s["frequencies_hz"][0] == pytest.approx(4.78, abs=0.005)
    assert -s["max_dynamic_displacement"] * 1e3 == pytest.approx(2.41, rel=0.005)
    p_l3_48ei = 5750 * 9.81 * 25.0**3 / (48 * 8.323e9)
    assert -s["max_static_displacement"] == pytest.approx(p_l3_48ei, rel=1e-3)  # 10-mode truncation < 0.1 %
    assert s["vehicle_frequencies_hz"][0] == pytest.approx(2.65, abs=0.005)


def test_fryba_from_scenario_file():
    s = run_json(EXAMPLES / "fryba_moving_force.toml")
    static_exact = 100e3 * 25.0**3 / (48 * 8.323e9)
    daf = -s["max_dynamic_displacement"] / static_exact
    assert daf == pytest.approx(1.705, rel=0.005)


def test_csv_and_plot_outputs(tmp_path: Path):
    out, fig, summ = tmp_path / "h.csv", tmp_path / "f.png", tmp_path / "s.json"
    res = runner.invoke(app, ["run", str(EXAMPLES / "yang_yau_sprung_mass.toml"), "--out", str(out), "--plot", str(fig),
                              "--summary", str(summ)])
    assert res.exit_code == 0, res.output
    header = out.read_text().splitlines()[0].split(",")
    for col in ("time [s]", "displacement [m]", "strain [-]", "acceleration [m/s^2]", "contact_force_w1 [N]",
                "body_heave [m]", "body_heave_acceleration [m/s^2]"):
        assert col in header
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    s = json.loads(summ.read_text())
    assert data.shape[0] == s["n_steps"] + 1
    # the summary's peak is refined between the samples (cubic Hermite with the velocity, so at
    # least the sampled one and above it by less than a mode-1 peak can fall between samples:
    # 1 − cos(ω₁ dt/2) = 2.2e-3 at f₁ = 5.55 Hz, dt = 4 ms)
    sampled, refined = -data[:, header.index("displacement [m]")].min(), -s["max_dynamic_displacement"]
    assert 0.0 <= refined - sampled <= 2.2e-3 * refined
    # every summary key has a unit; the references name the models' sources
    assert s["units"]["max_dynamic_displacement"] == "m" and s["units"]["impact_factor"] == "1"
    assert s["units"]["max_abs_acceleration"] == "m s-2"  # (the CF spelling of every JSON summary and dataset)
    # words and records have no unit ("" — not "1", which is a dimensionless number's)
    assert s["units"]["tire_model"] == s["units"]["points"] == s["units"]["warnings"] == s["units"]["flags"] == ""
    assert set(s["units"]) == set(s) - {"units"} and s["units"]["references"] == ""  # (words: no unit)
    keys = [r["key"] for r in s["references"]]
    assert keys[:3] == ["MultiPointTire", "Fryba1999", "YangYau1997"]   # paper, beam, sprung mass
    assert {"AASHTO-LRFD", "JTG-D60-2015"} <= set(keys)                  # the code allowances reported beside the IM
    assert fig.stat().st_size > 10_000
