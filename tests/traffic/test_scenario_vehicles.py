"""The scenario's [[vehicles]] array: validation names vehicles.N.key; [vehicle] unchanged."""
from __future__ import annotations

import pytest

from vbikit.scenario.schema import ScenarioError, scenario_from_toml

BASE = """
[bridge]
model = "paper-bridge-2-beam"
[crossing]
approach = 10
"""

TWO = BASE + """
[[vehicles]]
model = "3s2"
speed_kmh = 80
lateral_offset = -1.8
[[vehicles]]
model = "axles"
axle_loads = [50e3, 80e3, 80e3]
axle_spacings = [5.0, 1.3]
groups = ["single", "walking-beam"]
direction = "-x"
speed = 20
entry_time = 0.5
lateral_offset = 1.8
[vehicles.tire]
model = "multipoint"
n_points = 4
"""


def test_two_vehicles_validate():
    s = scenario_from_toml(TWO)
    a, b = s.vehicles
    assert s.is_multi_vehicle and s.vehicle is None
    assert a.model == "3s2" and a.speed_ms == pytest.approx(80 / 3.6) and a.tire is None
    assert b.parameters == {"axle_loads": [50e3, 80e3, 80e3], "axle_spacings": [5.0, 1.3], "groups": ["single", "walking-beam"]}
    assert b.direction == "-x" and b.entry_time == 0.5 and b.tire.n_points == 4


@pytest.mark.parametrize("old, new, match", [
    ('direction = "-x"', 'direction = "west"', r"vehicles\[2\]\.direction"),
    ("entry_time = 0.5", "entry_time = -1", r"vehicles\[2\]\.entry_time"),
    ("axle_spacings = [5.0, 1.3]", "axle_spacings = [5.0]", r"vehicles\[2\]\.axle_spacings: needs 2 value"),
    ('groups = ["single", "walking-beam"]', 'groups = ["single", "bogie"]', r"vehicles\[2\]\.groups: .*unknown axle group 'bogie'"),
    ("axle_loads = [50e3, 80e3, 80e3]", "axle_loads = [50e3, 80e3, -1]", r"vehicles\[2\]\.axle_loads: must be a list of numbers > 0"),
    ("n_points = 4", "n_points = 0", r"vehicles\[2\]\.tire\.n_points"),
    ("lateral_offset = -1.8", "lateral_ofset = -1.8", r"vehicles\[1\]: unknown key 'lateral_ofset'.*allowed: tire, lateral_offset"),
    ("speed_kmh = 80\n", "", r"vehicles\[1\]\.speed: give speed"),
    ("speed = 20\n", "speed = 20\nspeed_kmh = 72\n", r"vehicles\[2\]: give speed \[m/s\] or speed_kmh \[km/h\], not both"),
    ('model = "3s2"', 'model = "truck"', r"vehicles\[1\]\.model: .*unknown vehicle model 'truck'"),
])
def test_bad_vehicle_entries_name_the_key(old, new, match):
    assert old in TWO
    with pytest.raises(ScenarioError, match=match):
        scenario_from_toml(TWO.replace(old, new, 1))


def test_axles_needs_its_data():
    with pytest.raises(ScenarioError, match=r"vehicles\[1\]: vehicle 'axles' needs axle_loads, axle_spacings"):
        scenario_from_toml(BASE + '[[vehicles]]\nmodel = "axles"\nspeed = 20\n')


def test_vehicle_or_vehicles():
    one = BASE.replace("approach = 10", "approach = 10\nspeed = 20") + '[vehicle]\nmodel = "hs20-44"\n'
    assert scenario_from_toml(one).vehicle.model == "hs20-44"  # the single table keeps working
    with pytest.raises(ScenarioError, match="not both"):
        scenario_from_toml(one + '[[vehicles]]\nmodel = "3s2"\n')
    with pytest.raises(ScenarioError, match=r"vehicle: missing required key \(a \[vehicle\] table, or \[\[vehicles\]\]"):
        scenario_from_toml(BASE)
    with pytest.raises(ScenarioError, match="crossing: give exactly one of speed"):
        scenario_from_toml(BASE + '[vehicle]\nmodel = "hs20-44"\n')
    with pytest.raises(ScenarioError, match=r"crossing\.lateral_offset: with \[\[vehicles\]\] give it per vehicle"):
        scenario_from_toml(TWO.replace("approach = 10", "approach = 10\nlateral_offset = 1"))


def test_single_vehicle_axles_table():
    s = scenario_from_toml(BASE.replace("approach = 10", "approach = 10\nspeed_kmh = 70")
                           + '[vehicle]\nmodel = "axles"\naxle_loads = [40e3, 90e3]\naxle_spacings = [4.5]\n')
    assert s.vehicle.parameters["axle_loads"] == [40e3, 90e3]


def test_run_two_vehicles_from_the_cli(tmp_path):
    """`vbikit run --json` keeps the event keys and adds `vehicles`; `--out` has every vehicle's
    wheel forces; the static wheel loads are those of each vehicle alone (independent numbers:
    the axles truck's given loads)."""
    import csv
    import json

    from typer.testing import CliRunner

    from vbikit.cli import app

    path = tmp_path / "two.toml"
    path.write_text(TWO.replace("[crossing]\napproach = 10", "[crossing]\napproach = 10\nfree_vibration = 0.1"))
    out = tmp_path / "h.csv"
    res = CliRunner().invoke(app, ["run", str(path), "--json", "--out", str(out)])
    assert res.exit_code == 0, res.output
    s = json.loads(res.stdout)
    for key in ("impact_factor", "max_dynamic_displacement", "max_static_displacement", "static_wheel_loads"):
        assert key in s
    a, b = s["vehicles"]
    assert a["model"] == "3s2" and a["direction"] == "+x" and b["direction"] == "-x"
    assert b["entry_time"] == 0.5 and b["lateral_offset"] == 1.8 and b["tire_model"] == "multipoint" and a["tire_model"] == "point"
    loads = list(b["static_wheel_loads"].values())
    assert [loads[0] + loads[1], loads[2] + loads[3], loads[4] + loads[5]] == pytest.approx([50e3, 80e3, 80e3], rel=1e-12)
    assert set(b["min_wheel_force"]) == set(b["static_wheel_loads"]) and isinstance(b["contact_loss"], bool)
    with out.open() as fh:
        header = next(csv.reader(fh))
    assert "v1_front_axle_x [m]" in header and "v2_front_axle_x [m]" in header
    assert sum(h.startswith("contact_force_v1_") for h in header) == 10
    assert sum(h.startswith("contact_force_v2_") for h in header) == 6
