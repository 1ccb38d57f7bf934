"""``vbikit cite`` and ``vbikit bridge`` on an input file of another kind say what the file is and which command
reads it (``vbikit.cli.validate.check_kind``, the kind told as ``vbikit validate`` tells it): a trial's ``cite`` and
``bridge`` on a railway file listed its keys as unknown to a scenario, as if the file were bad."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("command", [["cite"], ["bridge", "--no-plot"]])
@pytest.mark.parametrize("file, kind", [("railway/hslm_20m.toml", "a railway file (vbikit rail)"),
                                        ("field/FIELD.toml", "a field file (vbikit field)"),
                                        ("studies/modes_sensitivity.toml", "a study (vbikit study run)")])
def test_another_kind_of_file_is_named_not_listed_as_unknown_keys(command, file, kind):
    res = runner.invoke(app, [command[0], str(EXAMPLES / file), *command[1:]])
    assert res.exit_code == 2, res.output
    assert f"this file is {kind}" in res.stderr and "unknown key" not in res.stderr
    assert f"vbikit {command[0]} takes a scenario" in res.stderr


def test_the_files_with_a_scenario_bridge_are_shown_and_a_scenario_is_cited():
    """``bridge`` reads the [bridge] of a scenario, a traffic base, a drive-by and a lifetime file; ``cite`` a
    scenario; a missing file is the reader's error, as before."""
    for file in ("paper/bridge2_hs20_girder4.toml", "traffic/base/bridge2.toml", "driveby/DRIVEBY.toml",
                 "lifetime/lifetime.toml"):
        res = runner.invoke(app, ["bridge", str(EXAMPLES / file), "--no-plot"])
        assert res.exit_code == 0 and "[bridge] of" in res.stdout, (file, res.output)
    res = runner.invoke(app, ["cite", str(EXAMPLES / "paper/bridge2_hs20_girder4.toml")])
    assert res.exit_code == 0 and "models bridge:paper-bridge-2" in res.stdout
    res = runner.invoke(app, ["cite", "no-such-file.toml"])
    assert res.exit_code == 2 and "not found" in res.stderr


def test_a_scenario_by_another_name_is_still_cited(tmp_path):
    """A scenario whose file name does not end in .toml is read as before (the kind is told only of .toml files; a
    review found `cite scen.txt` crashing on the CSV guess)."""
    scen = tmp_path / "scen.txt"
    scen.write_text((EXAMPLES / "paper/bridge2_hs20_girder4.toml").read_text())
    res = runner.invoke(app, ["cite", str(scen)])
    assert res.exit_code == 0 and "models bridge:paper-bridge-2" in res.stdout, res.output
    (tmp_path / "x.csv").write_text("a,b\n1,2\n")
    res = runner.invoke(app, ["cite", str(tmp_path / "x.csv")])
    assert res.exit_code == 2 and res.stderr.startswith("error:"), res.output  # (the reader's own error, no crash)
