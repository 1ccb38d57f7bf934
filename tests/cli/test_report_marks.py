"""The text report marks what its flags put in doubt, next to the number: a load effect the step does not resolve
("!" on its IM, from its ``effect_step`` flag), a peak acceleration the half-step check finds unconverged ("!"),
JTG D60's value beside a hogging moment ("?": the clause's f2 reading unconfirmed, its value given), and a run
at a given crossing.dt says that it checked no step.  Found by a new user's trial (2026-12-07)."""
from __future__ import annotations

import math
import re
from pathlib import Path

from typer.testing import CliRunner

from vbikit.cli import app

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()


def _run(path: Path, *args: str) -> str:
    res = runner.invoke(app, ["run", str(path), *args])
    assert res.exit_code == 0, res.output
    return res.stdout


def test_unresolved_load_effects_and_an_unconverged_acceleration_are_marked():
    """Frýba's moving force: the shear at x = 0 and both reactions have effect_step flags (the step does not
    resolve the modes they need), the midspan moment none; the peak acceleration moves by 0.77 % at half the
    step (flagged)."""
    out = _run(ROOT / "examples" / "verification" / "fryba_moving_force.toml")
    rows = {m.group(1).strip(): m.group(2) for m in re.finditer(r"^    (\w+ +(?:x = [\d.]+ m|support \d)) .* IM +-?[\d.]+(.)",
                                                                 out, re.M)}
    assert rows == {"moment   x = 12.50 m": " ", "shear    x = 0.00 m": "!",
                                               "reaction support 0": "!", "reaction support 1": "!"}, rows
    assert "! the step does not resolve this load effect" in out
    assert re.search(r"max \|acceleration\| +[\d.]+ m/s²! ", out)


def test_jtg_beside_a_hogging_moment_is_marked_with_the_f2_value():
    """The three-span continuous beam (16.76 + 20 + ... m): its moments over the piers (x = 20 and 45 m, hogging
    region) carry "?" on JTG D60's value, the span moments not; the note gives μ(f2) by JTG D60-2015 4.3.2's
    formula 0.1767 ln f − 0.0157 with f2 the report's second frequency."""
    out = _run(ROOT / "examples" / "bridges" / "three_span_continuous_hs20.toml")
    marked = {m.group(1): m.group(2) == "?" for m in
              re.finditer(r"^    moment +x = ([\d.]+) m .*codes [\d.]+ / [\d.]+(\??) / [\d.]+$", out, re.M)}
    assert marked == {"10.00": False, "32.50": False, "55.00": False, "20.00": True, "45.00": True}, marked
    f2 = float(re.search(r"bridge f1\.\.f3 +[\d.]+, ([\d.]+),", out).group(1))
    note = re.search(r"\? JTG D60 by f1 beside a hogging moment.*μ\(f2 = ([\d.]+) Hz\) = ([\d.]+)", out)
    assert float(note.group(1)) == f2
    assert abs(float(note.group(2)) - (0.1767 * math.log(f2) - 0.0157)) <= 1e-3  # (f2 printed to 0.01 Hz)


def test_a_given_step_says_that_no_step_was_checked(tmp_path):
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text(encoding="utf-8")
    scenario = tmp_path / "given.toml"
    scenario.write_text(re.sub(r"^approach = .*$", lambda m: m.group(0) + "\ndt = 0.002", text, count=1, flags=re.M),
                        encoding="utf-8")
    out = _run(scenario)
    assert "step check           not run: crossing.dt is given" in out
    # an automatic step that the load effects' halving checked says what the halving found, not "not run" (its inputs
    # hold the dt it ran with, not a given one)
    fryba = (ROOT / "examples" / "verification" / "fryba_moving_force.toml").read_text(encoding="utf-8")
    halved = tmp_path / "halved.toml"
    halved.write_text(fryba.replace("x = 12.5", "x = 12.5\nmoment = [12.5]"), encoding="utf-8")
    out = _run(halved)
    assert "not run" not in out and re.search(r"step check +halved \d× to [0-9.e+-]+ s for its load effects: the last "
                                              r"halving changed the impact factors by at most", out), out


def test_the_points_table_marks_every_unconverged_peak_acceleration(tmp_path):
    """Frýba's moving force read at midspan and at a quarter: both peak accelerations change by more than the
    tolerance at half the step (0.77 % and 4.0 %); the flag names the larger and counts the other, the step check
    lists both, and the points table marks both |a|max, as the headline line its own."""
    import json

    text = (ROOT / "examples" / "verification" / "fryba_moving_force.toml").read_text(encoding="utf-8")
    text = text.replace("[response]\nx = 12.5", "[[response.points]]\nname = \"mid\"\nx = 12.5\n"
                                              "[[response.points]]\nname = \"quarter\"\nx = 6.25")
    scenario = tmp_path / "two.toml"
    scenario.write_text(text, encoding="utf-8")
    summary = json.loads(_run(scenario, "--json"))
    (flag,) = [f for f in summary["flags"] if f["code"] == "step_not_converged"]
    assert flag["output"] == "points[quarter].max_abs_acceleration" and "(1 more peak acceleration above" in flag["message"]
    assert set(summary["step_check"]["accelerations_not_converged"]) >= {"points[mid].max_abs_acceleration",
                                                                          "points[quarter].max_abs_acceleration"}
    out = _run(scenario)
    rows = {m.group(1): m.group(2) for m in re.finditer(r"^  (mid|quarter) +.* [\d.]+(!?)$", out, re.M)}
    assert rows == {"mid": "!", "quarter": "!"}, rows
    assert re.search(r"max \|acceleration\| +[\d.]+ m/s²! ", out)
