"""Wording the second new-user trial found misleading (each assertion fails on the code before it):
an IM of zero printed as −0.0000; the CSA S6 line's clause on several vehicles printed for one
vehicle; the strain-convergence message quoting a y on a beam, which has none (``ignored_input``);
the negative-IM note speaking of a vehicle's bounce for a moving constant force."""
from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from vbikit.analysis.checks import NEGATIVE_IM_NOTE
from vbikit.cli import app
from vbikit.cli.render import im_text as _im

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


def test_an_im_that_rounds_to_zero_prints_without_a_sign():
    assert _im(-1e-6) == "0.0000" and _im(1e-6) == "0.0000"
    assert _im(-0.00012) == "-0.0001" and _im(0.24512) == "0.2451"


def test_one_vehicle_gets_no_several_vehicles_clause_and_a_beam_strain_message_no_y(tmp_path):
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    path = tmp_path / "s.toml"
    path.write_text(text)
    res = runner.invoke(app, ["run", str(path), "--summary", str(tmp_path / "s.json")])
    assert res.exit_code == 0, res.output
    csa = next(line for line in res.output.splitlines() if "CSA S6 by" in line)
    assert "several vehicles" not in csa
    s = json.loads((tmp_path / "s.json").read_text())
    (strain,) = [f for f in s["flags"] if f["code"] == "strain_not_converged"]  # 10 modes: −4 % (checks docstring)
    assert "at x = " in strain["message"] and "y = " not in strain["message"]


def test_negative_im_note_does_not_need_a_sprung_vehicle():
    assert "a sprung vehicle's bounce" in NEGATIVE_IM_NOTE
    assert not NEGATIVE_IM_NOTE.split(":", 1)[1].lstrip().startswith("the vehicle's bounce")
