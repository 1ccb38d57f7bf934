"""Bad scenarios: one clear message naming the key and allowed values, exit code 2, no traceback."""
from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

GOOD = """
[bridge]
model = "beam"
span = 20.0
EI = 1e10
mass_per_length = 5000.0
n_modes = 5
[vehicle]
model = "sprung-mass"
[crossing]
speed = 20.0
"""


def run_text(tmp_path: Path, text: str, *args: str):
    path = tmp_path / "s.toml"
    path.write_text(text)
    return runner.invoke(app, ["run", str(path), *args])


def test_good_scenario_runs(tmp_path):
    res = run_text(tmp_path, GOOD, "--json")
    assert res.exit_code == 0, res.output


@pytest.mark.parametrize(
    "old,new,expect",
    [
        ('mass_per_length = 5000.0', 'mass_per_length = -5000.0', ["bridge.mass_per_length", "expected a number in (0, "]),
        ('speed = 20.0', 'speed = 0.0', ["crossing.speed", "expected a number in [0.001, 300] [m/s], got 0.0"]),
        ('model = "sprung-mass"', 'model = "sprung-mass"\nmass = -3.0', ["mass", "> 0"]),
        ('model = "sprung-mass"', 'model = "truck"', ["vehicle.model", "hs20-44", "quarter-car"]),
        ('[crossing]', '[tire]\nmodel = "multipoint"\nn_points = 0\n[crossing]',
         ["tire.n_points", "expected an integer in [1, 100], got 0"]),
        ('n_modes = 5', 'n_modes = 5.5', ["bridge.n_modes", "expected an integer in [1, 500], got 5.5"]),  # (a new user's trial)
        ('speed = 20.0', 'speed = 20.0\ndt = 0.0', ["crossing.dt", "expected a number > 0 [s], got 0.0"]),
        ('speed = 20.0', 'speed = 20.0\ndt = 0.01\nintegrator = "rk4"', ["crossing.dt", "stability limit", "newmark"]),
        ('[crossing]', '[road]\nclass = "Q"\n[crossing]', ["road.class", "A, B, C, D, E, F, G, H"]),
        ('[crossing]', '[road]\nprofile_file = "missing.csv"\n[crossing]', ["missing.csv", "not found"]),
        ('n_modes = 5', 'n_modes = 5\nspan_length = 3', ["bridge.span_length", "unknown key", "allowed keys"]),
        ('EI = 1e10\n', '', ["bridge", "needs EI"]),
        ('[vehicle]\nmodel = "sprung-mass"\n', '', ["vehicle", "missing required key"]),
        ('speed = 20.0', 'speed = 20.0\nintegrator = "euler"', ["crossing.integrator", "'exact'", "'rk4'", "'newmark'"]),
        ('speed = 20.0', 'speed = 20.0\nacceleration = -9.0', ["acceleration", "stops"]),
    ],
)
def test_bad_scenarios(tmp_path, old, new, expect):
    assert old in GOOD
    res = run_text(tmp_path, GOOD.replace(old, new), "--json")
    assert res.exit_code == 2, res.output
    msg = res.stderr
    assert "Traceback" not in res.output and "Traceback" not in msg
    assert msg.startswith("error:")
    for fragment in expect:
        assert fragment in msg, msg


def test_invalid_toml(tmp_path):
    res = run_text(tmp_path, "[bridge\nmodel = 1")
    assert res.exit_code == 2 and "not valid TOML" in res.stderr


def test_debug_shows_traceback(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(GOOD.replace("speed = 20.0", "speed = 0.0"))
    res = runner.invoke(app, ["--debug", "run", str(path)])
    assert res.exit_code != 0 and res.exception is not None


def test_bad_road_csv_names_line(tmp_path):
    (tmp_path / "road.csv").write_text("x,z\n-50,0\n0,0.001\nabc,0\n")
    res = run_text(tmp_path, GOOD.replace("[crossing]", '[road]\nprofile_file = "road.csv"\n[crossing]'))
    assert res.exit_code == 2 and "road.csv:4" in res.stderr


def test_presets_and_demo(tmp_path):
    res = runner.invoke(app, ["presets"])
    assert res.exit_code == 0 and "hs20-44" in res.stdout and "paper-bridge-2-beam" in res.stdout
    res = runner.invoke(app, ["demo", "--out-dir", str(tmp_path)])
    assert res.exit_code == 0, res.output
    assert "IM =" in res.stdout
    assert (tmp_path / "demo.png").stat().st_size > 10_000 and (tmp_path / "demo.json").exists()


def test_presets_summarise_a_trains_axle_loads():
    """HSLM-A1 has 50 axles of P = 170 kN (EN 1991-2 Table 6.3: N = 18 coaches; 8.5 MN in all): one
    summary, not 50 numbers; a truck's six wheel loads are listed (HS20-44: 15.4, 67.1, 68.0 kN a pair)."""
    out = runner.invoke(app, ["presets"]).stdout
    hslm = next(line for line in out.splitlines() if line.strip().startswith("hslm-a1 "))
    assert "load per axle [kN]: 50 axles, 170.0 each; total 8500" in hslm and "170.0, 170.0" not in hslm
    truck = next(line for line in out.splitlines() if line.strip().startswith("hs20-44 "))
    assert "load per wheel [kN]: 15.4, 15.4, 67.1, 67.1, 68.0, 68.0; total 300.9;" in truck


def test_presets_say_which_loads_are_per_wheel_and_which_per_axle():
    """The listing says in its header and on every vehicle's line whether the loads are a wheel's (road
    vehicles: HS20-44's six wheels, three axles of two) or an axle's (trains: HSLM-A1's P = 170 kN is
    an axle load, EN 1991-2 Table 6.3); on main a bare "wheel loads" / "axle loads" label, which a new
    user read as the same thing.  Every vehicle line carries exactly one of the two labels."""
    out = runner.invoke(app, ["presets"]).stdout.splitlines()
    header = next(line for line in out if line.startswith("Vehicles"))
    assert "per wheel for road vehicles, per axle for trains" in header
    start, end = out.index(header) + 1, next(k for k, line in enumerate(out) if line.startswith("Tires"))
    lines = [x for x in out[start:end] if not x.startswith("    ")]  # (a vehicle's second line is indented further)
    from vbikit.vehicle import TRAIN_PRESETS

    for line in lines:
        name = line.split()[0]
        per = "axle" if name in TRAIN_PRESETS else "wheel"
        assert f"load per {per} [kN]: " in line and ("per wheel" in line) != ("per axle" in line), line
    assert any(x.split()[0] in TRAIN_PRESETS for x in lines) and any(x.split()[0] not in TRAIN_PRESETS for x in lines)


def test_the_summary_names_a_road_file_without_its_folder(tmp_path):
    """``road.profile_file`` given as an absolute path: ``vbikit run --json``'s inputs name ``road.csv``
    (before 2026-12-06 the whole path, the user's folders in a summary shared with others), and no value
    of the summary holds the folder."""
    import json

    (tmp_path / "road.csv").write_text("x,z\n-50,0\n0,0.001\n50,0\n")
    res = run_text(tmp_path, GOOD.replace("[crossing]", f'[road]\nprofile_file = "{tmp_path / "road.csv"}"\n[crossing]'),
                   "--json")
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["inputs"]["road"] == {"profile_file": "road.csv"}
    assert str(tmp_path) not in res.stdout
