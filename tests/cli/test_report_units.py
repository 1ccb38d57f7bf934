"""The text reports take their units from one table, `vbikit.outputs.REPORT_UNITS` (`report_unit`):
changing it changes every report (`vbikit run`, `vbikit presets`) — no command writes "kN" or "mm"
or a factor 1e3 of its own; and `vbikit presets` gives each parameter its SI unit from the one place
it is defined (the scenario schema's descriptions, `vbikit.vehicle.presets.PARAMETER_UNITS`)."""
from __future__ import annotations

import json
import re

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

#: a moving force of 100 kN over a 25 m beam (Frýba's case of examples/verification), with a moment
SCENARIO = """
[bridge]
model = "beam"
span = 25.0
EI = 8.323e9
mass_per_length = 2303.0
n_modes = 6
[vehicle]
model = "moving-force"
force = 100e3
[road]
class = "none"
[crossing]
speed_kmh = 60
[response]
x = 12.5
moment = [12.5]
"""

#: a report-unit table no command could have written by hand
ODD_UNITS = {"N m": ("MN m", 1e-6), "N": ("MN", 1e-6), "m": ("µm", 1e6)}


def test_vbikit_run_reads_its_units_from_the_table(tmp_path, monkeypatch):
    """With the table set to MN m, MN and µm the report shows the JSON's SI values times 1e-6 and
    1e6 (1 MN = 1e6 N, 1 µm = 1e-6 m): the displacement line and the load-effect table."""
    path = tmp_path / "s.toml"
    path.write_text(SCENARIO)
    s = json.loads(runner.invoke(app, ["run", str(path), "--json"]).stdout)
    monkeypatch.setattr("vbikit.outputs.REPORT_UNITS", ODD_UNITS)
    res = runner.invoke(app, ["run", str(path)])
    assert res.exit_code == 0, res.output
    assert (f"max displacement     dynamic {s['max_dynamic_displacement'] * 1e6:+.4f} µm, "
            f"static {s['max_static_displacement'] * 1e6:+.4f} µm") in res.stdout
    assert "load effects (" in res.stdout and "MN m / MN;" in res.stdout
    moment = s["moment"]["sections"][0]
    assert f"static {moment['static_peak'] * 1e-6:+10.2f}" in res.stdout
    assert " mm" not in res.stdout and "kN" not in res.stdout


def test_vbikit_presets_reads_its_load_unit_from_the_table(monkeypatch):
    """The moving force's 100 kN wheel load with the table's force unit MN reads 0.1 (1 MN = 1000 kN)."""
    monkeypatch.setattr("vbikit.outputs.REPORT_UNITS", ODD_UNITS)
    res = runner.invoke(app, ["presets"])
    assert res.exit_code == 0, res.output
    assert "load per wheel [MN]: 0.1; total 0.1" in res.stdout
    assert "static loads in MN" in res.stdout and "[kN]" not in res.stdout


def test_presets_give_every_parameter_its_si_unit():
    """The beam's keys with the units of the scenario schema (span m, EI N m², mass per length kg/m,
    docs/reference/scenario-keys.md); Yang & Yau's sprung mass (5750 kg, 1595 kN/m, undamped) and the
    axle truck's keys with the units of PARAMETER_UNITS; dimensionless ones bare.  On main: names
    and numbers only."""
    out = runner.invoke(app, ["presets"]).stdout
    assert "Euler–Bernoulli beam: span [m], EI [N m²], mass_per_length [kg/m], damping_ratio, n_modes, " \
           "neutral_axis_depth [m]" in out
    assert "rotational_stiffness [N m/rad]" in out
    assert "mass = 5750 kg, stiffness = 1.595e+06 N/m, damping = 0 N·s/m" in out
    assert "force = 100000 N" in out
    assert re.search(r"parameters: axle_loads \[N\], axle_spacings \[m\], groups, tractor_groups, "
                     r"unsprung_masses \[kg\], half_track \[m\], tire_deflection \[m\], suspension_deflection \[m\], "
                     r"suspension_damping_ratio, tire_damping_ratio", out)
    assert "example axle_loads = [53400.0, 75600.0, 75600.0, 75600.0, 75600.0] N, axle_spacings = [5.5, 1.3, 9.5, 1.3] m" in out


def test_every_vehicle_parameter_has_a_unit_entry():
    """A preset parameter (or a number a preset's vehicle states of itself) without an entry in
    PARAMETER_UNITS would be listed without its unit: none is."""
    from vbikit.vehicle.presets import PARAMETER_UNITS, VEHICLE_PRESETS

    names = {k for p in VEHICLE_PRESETS.values() for k in (*p.parameters, *p.example_vehicle().parameters)}
    assert names <= set(PARAMETER_UNITS), sorted(names - set(PARAMETER_UNITS))
    assert all(PARAMETER_UNITS[k] is None for k in names if VEHICLE_PRESETS["axles"].kind(k) == "names")


@pytest.mark.parametrize("description, unit", [("span length [m]", "m"), ("bending stiffness [N m^2]", "N m²"),
                                               ("modal damping ratio, every mode", ""), ("ratio [-]", ""),
                                               ("springs [N/m], one or one per support", "N/m")])
def test_a_keys_unit_is_read_from_its_description(description, unit):
    from vbikit._words import split_unit

    assert split_unit(description)[1] == unit


def test_a_run_summary_s_units_name_every_key_but_their_own():
    """``units`` maps every key of a run's summary to its unit ("" for words): the references too (a trial found
    them left out), and docs/results.md's table lists every key."""
    import json
    from pathlib import Path

    from typer.testing import CliRunner

    from vbikit.cli import app

    root = Path(__file__).resolve().parents[2]
    res = CliRunner().invoke(app, ["run", str(root / "examples" / "verification" / "yang_yau_sprung_mass.toml"), "--json"])
    s = json.loads(res.stdout)
    assert set(s) - set(s["units"]) == {"units"} and s["units"]["references"] == ""
    table = (root / "docs" / "results.md").read_text(encoding="utf-8")
    assert all(f"| `{key}` |" in table for key in s if key not in ("units",)) and "| `units` |" in table
