"""Every example of bad input to ``vbikit lifetime``, ``driveby`` and ``rail`` found on main at
dfa6d9e (issue 34) gets a clear error naming the key and the allowed range before any computation,
through ``vbikit validate`` (the same checks as the command) and the command itself."""
from __future__ import annotations

import copy
import time
from pathlib import Path

import pytest
from fuzz_commands import BASES, RECORDS, write_input
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
TRAIN = "position_m,load_kN\n0,170\n3,170\n14,170\n17,170\n"


def _validate(tmp_path: Path, kind: str, change: dict, records: str | None = None):
    data = copy.deepcopy(BASES[kind])
    for path, value in change.items():
        node = data
        keys = [int(k) if k.isdigit() else k for k in path.split(".")]
        for k in keys[:-1]:
            node = node[k]
        if value is None:
            del node[keys[-1]]
        else:
            node[keys[-1]] = value
    files = {"lifetime": {"records.csv": records or "\n".join(RECORDS) + "\n"}, "rail": {"train.csv": TRAIN},
             "driveby": {}}[kind]
    path = write_input(tmp_path, kind, data, files)
    return runner.invoke(app, ["validate", str(path)])


CASES = [
    # lifetime: tiny positives, booleans, positions, categories, damage, lanes
    ("lifetime", {"ds": 5e-324}, "ds: expected a number in [0.001, 2] [m], got 5e-324"),
    ("lifetime", {"dx": 5e-324}, "dx: expected a number in [0.001, 1] [m], got 5e-324"),
    ("lifetime", {"fatigue.histogram_bin": 5e-324}, "fatigue.histogram_bin: expected a number in [1000, 1e+08]"),
    ("lifetime", {"fatigue.histogram_bin": float("inf")}, "fatigue.histogram_bin: expected a finite number in [1000, 1e+08] [Pa], got inf"),
    ("lifetime", {"traffic.speed_kmh": 5e-324}, "traffic.speed_kmh: expected a number in [5, 250]"),
    ("lifetime", {"load_effects.0.x": 5e-324}, "load_effects[1].x: a section 5e-324 m from the entry support"),
    ("lifetime", {"fatigue.details.0.section_modulus": 1e-300}, "section_modulus: expected a number in [1e-07, 100] [m³], got 1e-300"),
    ("lifetime", {"traffic.trucks_per_day": 1e-9}, "traffic.trucks_per_day: expected a number in [1, 200000]"),
    ("lifetime", {"days": True}, "days: expected an integer in [1, 73000], got true"),
    ("lifetime", {"amplification": True}, "amplification: expected a number"),
    ("lifetime", {"traffic.lanes": [1.8, 1.8]}, "traffic.lanes: each lane needs its own centre y"),
    ("lifetime", {"load_effects.0.x": 100.0}, "section x must be within 0 … 9.16 m"),
    ("lifetime", {"fatigue.details.0.category": "EN -36"}, "category: 'EN -36' is not a detail category"),
    ("lifetime", {"fatigue.details.0.category": "EN 1e300"}, "category: 'EN 1e300' is not a detail category"),
    ("lifetime", {"fatigue.details.0.category": "EN 300"}, "category: 'EN 300' is not a detail category (the nearest EN category is 160); allowed: EN 160, 140"),
    ("lifetime", {"fatigue.details.0.category": "EN 37"}, "fatigue.details[1].category: 'EN 37' is not a detail category (the nearest EN category is 36)"),
    ("lifetime", {"fatigue.damage_so_far": 5}, "fatigue.damage_so_far: expected a number in [0, 1), got 5"),
    ("lifetime", {"return_periods": [0.001]}, "return_periods: 0.001 years is not longer than one block"),
    ("lifetime", {"colour": 1}, "colour: unknown key; allowed: name, seed, days"),
    ("lifetime", {"fatigue.dynamic_sample": 1e-9}, "fatigue.dynamic_sample: 1e-09 of about 10,000 events samples"),
    # drive-by: wrong types, positions off the vehicle, sweep keys in the user's words, noise
    ("driveby", {"sampling.rate": "fast"}, "sampling.rate: expected a number in [1, 100000] [Hz], got str 'fast'"),
    ("driveby", {"sensors.0.position": 99.0}, "sensors.acc.position: 99 m is off the vehicle"),
    ("driveby", {"sensors.0.lateral": True}, "sensors.acc.lateral: expected a number in [-2, 2] [m], got bool true"),
    ("driveby", {"sweep.speed": [0]}, "sweep.speed: expected a number in [0.001, 300] [m/s], got 0"),
    ("driveby", {"sweep.damage_position": [24.0]}, "sweep.damage_position = 24.0 (damage_length = 2.5 m): the region"),
    ("driveby", {"sweep.noise_rms": [1e300]}, "sweep.noise_rms: expected a number in [0, 1000]"),
    ("driveby", {"sensors.0.noise_rms": 1e300}, "sensors.acc.noise_rms: expected a number in [0, 1000]"),
    ("driveby", {"sweep.road_seed": [10**400]}, "sweep.road_seed: expected an integer in [0, 9.22337e+18]"),
    ("driveby", {"vehicle.mass": 5e-324}, "vehicle.mass: expected a number in [1, 100000] [kg], got 5e-324"),
    ("driveby", {"crossing.speed": False}, "crossing.speed"),
    ("driveby", {"max_steps": 1e400}, "max_steps: expected a number in [1, 1e+12], got inf"),
    # rail: tiny span, contact stiffness, unknown keys
    ("rail", {"bridge.span": 5e-324}, "bridge.span: expected a number in [1, 300] [m]"),
    ("rail", {"coupled.contact": 1e-3}, "coupled.contact: a wheel-rail stiffness per wheelset is within 1e+06 … 1e+12 N/m"),
    ("rail", {"bridge.colour": 1}, "bridge.colour: unknown key; allowed: span, EI, mass_per_length"),
]


@pytest.mark.parametrize("kind, change, message", CASES, ids=[f"{k}-{next(iter(c))}" for k, c, _ in CASES])
def test_bad_input_gets_a_clear_error(tmp_path, kind, change, message):
    res = _validate(tmp_path, kind, change)
    assert res.exit_code == 2, res.output
    assert message in res.stderr, res.stderr
    assert "Traceback" not in res.output


@pytest.mark.parametrize("records, message", [
    ("\n".join(RECORDS[:1]) + "\n", "records.csv holds no vehicle records (a header only)"),
    ("\n".join(RECORDS[:2] + [RECORDS[2].replace(RECORDS[2].split(",")[1], "1e300", 1)]) + "\n",
     "1e+300 s is beyond the 3.156e+08 s (ten years)"),
])
def test_bad_records_get_a_clear_error(tmp_path, records, message):
    res = _validate(tmp_path, "lifetime", {}, records)
    assert res.exit_code == 2 and message in res.stderr, res.output


def test_overlapping_records_are_warned(tmp_path):
    """Two trucks at one time in one lane (or 1e-9 s apart): a documented warning naming the line."""
    lines = RECORDS[:3] + [RECORDS[2]]
    res = _validate(tmp_path, "lifetime", {}, "\n".join(lines) + "\n")
    assert "overlapping pair(s)" in res.stderr and "(line 4)" in res.stderr, res.output


def test_a_driveby_sweep_of_86400_cases_is_estimated_and_refused(tmp_path):
    """86,400 cases: estimated from one crossing per speed (not checked case by case) and refused
    above max_steps within seconds; the message names the budget and how to raise it."""
    t0 = time.perf_counter()
    res = _validate(tmp_path, "driveby", {"sweep.speed": [5.0 + 0.5 * i for i in range(20)],
                                          "sweep.road_seed": list(range(1080)), "sweep.damage_severity": [0.0, 0.3],
                                          "sweep.noise_rms": [0.0, 0.01]})
    assert res.exit_code == 2 and "(86,400 cases), above the budget 2e+07; raise max_steps in the input file or --max-steps on the command line" in res.stderr
    assert time.perf_counter() - t0 < 10


def test_lifetime_memory_budget_names_an_option_that_exists(tmp_path):
    """200 years of 2,000 trucks a day: refused from the memory estimate with --max-memory, which
    `vbikit lifetime` takes (raising it moves the refusal to the run-time budget)."""
    res = _validate(tmp_path, "lifetime", {"days": None, "years": 200.0, "budget_hours": 1e4})
    assert res.exit_code == 2 and "of memory (146,000,000 events × 2 load effect(s)), above the memory budget 4" in \
        res.stderr and "--max-memory (vbikit lifetime)" in res.stderr, res.output
    assert "--max-memory" in runner.invoke(app, ["lifetime", "--help"]).output
    path = tmp_path / "LIFETIME.toml"
    res = runner.invoke(app, ["validate", str(path), "--max-memory", "1TB"])
    assert res.exit_code == 0, res.output


@pytest.mark.parametrize("out_dir, message", [("file", "exists and is not a folder"), ("/dev/null", "lies in /dev"),
                                               ("/proc/self/x", "lies in /proc")])
@pytest.mark.parametrize("command", ["lifetime", "driveby", "rail"])
def test_out_dir_naming_a_file_or_a_system_folder(tmp_path, command, out_dir, message):
    path = write_input(tmp_path, command, BASES[command], {"records.csv": "\n".join(RECORDS) + "\n", "train.csv": TRAIN})
    if out_dir == "file":
        out_dir = str(tmp_path / "a-file")
        Path(out_dir).write_text("x")
    res = runner.invoke(app, [command, str(path), "--out-dir", out_dir])
    assert res.exit_code == 2 and f"--out-dir {out_dir}: {message}" in res.stderr, res.output


@pytest.mark.parametrize("argv", [["run", "X.toml", "--max-steps", "1e400"], ["validate", "X.toml", "--max-steps", "1e400"],
                                  ["driveby", "X.toml", "--max-steps", "1e400"]])
def test_max_steps_1e400(tmp_path, argv):
    res = runner.invoke(app, argv)
    assert res.exit_code == 2 and "--max-steps: expected a number in [1, 1e+12], got inf" in res.stderr, res.output


def test_out_of_memory_message_names_options_that_exist():
    from vbikit.cli.guard import _OUT_OF_MEMORY

    import typer.main

    def commands(group, prefix=""):
        for name, cmd in group.commands.items():
            yield from commands(cmd, f"{prefix}{name} ") if hasattr(cmd, "commands") else [(f"{prefix}{name}", cmd)]

    with_option = [name for name, cmd in commands(typer.main.get_command(app))
                   if any("--max-memory" in getattr(p, "opts", ()) for p in cmd.params)]
    assert sorted(with_option) == sorted(["run", "validate", "compare-tires", "field", "study run", "study validate",
                                          "traffic", "lifetime"])
    assert "vbikit run, validate, compare-tires, field, study run, traffic, lifetime" in _OUT_OF_MEMORY  # (study validate runs nothing)


def test_rail_has_progress_and_the_same_out_dir_default():
    text = runner.invoke(app, ["rail", "--help"]).output
    assert "--progress" in text and "--no-progress" in text and "vbikit-out" in text


@pytest.mark.parametrize("name, kind", [("lifetime/lifetime.toml", "lifetime file"), ("driveby/DRIVEBY.toml", "drive-by file"),
                                        ("railway/hslm_20m.toml", "railway file"), ("lifetime/wim.csv", "vehicle records"),
                                        ("railway/talgo_like.csv", "train table"), ("field/FIELD.toml", "field file"),
                                        pytest.param("studies/fig6_roughness_reading.toml", "a study",
                                                     marks=pytest.mark.slow),
                                        ("field/case1_responses.csv", "measured response"),
                                        ("traffic/two_trucks.toml", "steps of")])
def test_validate_knows_every_input_kind(name, kind):
    """`vbikit validate FILE` tells the kind and runs its command's checks, in under 2 s each."""
    path = Path(__file__).resolve().parents[2] / "examples" / name
    t0 = time.perf_counter()
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 0 and kind in res.stdout, res.output
    assert time.perf_counter() - t0 < 4.0  # under 2 s on a quiet machine (docs/changelog.md); margin for a loaded one


PAPER_BRIDGE_2 = """[bridge]
model = "paper-bridge-2"
n_modes = 3
[bridge.deck]
n_elements = 6
skew = -0.0
[vehicle]
model = "hs20-44"
[crossing]
speed_kmh = 60
approach = 1.0
free_vibration = 0.05
"""


def test_paper_era_leftovers(tmp_path):
    """response.y = 100 m on paper-bridge-2 (9.75 m wide) refused; a skew of −0.0 is 0.0."""
    import math

    from vbikit.scenario import build, load_scenario

    path = tmp_path / "s.toml"
    path.write_text(PAPER_BRIDGE_2 + "[response]\ny = 100.0\n")
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 2 and "response.y: 100 m is off the 9.75 m wide deck" in res.stderr, res.output
    path.write_text(PAPER_BRIDGE_2)
    skew = build(load_scenario(path)).crossing.bridge.skew
    assert skew == 0.0 and math.copysign(1.0, skew) == 1.0


def test_rail_dataset_of_a_scenario_bridge_has_no_nan_attribute(tmp_path):
    """rail.nc of a scenario bridge carried EI_Nm2 = NaN and mass_per_length_kg_m = NaN (NaN at exit 0)."""
    import math

    from vbikit.rail.run import run_rail

    (tmp_path / "deck.toml").write_text('[bridge]\nmodel = "beam"\nspan = 20.0\nEI = 7.9e10\nmass_per_length = 25000.0\n')
    ds = run_rail({"bridge": {"scenario": str(tmp_path / "deck.toml")}, "trains": {"presets": ["hslm-a4"]},
                   "speeds": {"min": 230.0, "max": 290.0, "step": 30.0}}, figures=False).dataset
    bad = [k for k, v in ds.attrs.items() if isinstance(v, float) and not math.isfinite(v)]
    assert bad == [] and "EI_Nm2" not in ds.attrs
