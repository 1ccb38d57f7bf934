"""The input surfaces added since the paper ([[vehicles]], [bridge.deck], continuous beams, load-effect
sections, mode files, size budgets, study axes): every impossible input gives exit 2 and one message
naming the key or file and the allowed range, in ``validate`` and in ``run`` alike, before any
integration; implausible input gives a warning."""
from __future__ import annotations

import dataclasses
import re
import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

BEAM = '[bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 4\n'
DECK = '[bridge]\nmodel = "paper-bridge-2"\nn_modes = 4\n'
CONTINUOUS = ('[bridge]\nmodel = "continuous-beam"\nspans = [10.0, 12.0]\nEI = 5e9\nmass_per_length = 5000.0\n'
              'n_modes = 4\n')
ONE_TRUCK = '[vehicle]\nmodel = "hs20-44"\n[crossing]\nspeed_kmh = 60\n'


def _vehicles(*entries: str, crossing: str = "speed_kmh = 60") -> str:
    return f"[crossing]\n{crossing}\n" + "".join(f"[[vehicles]]\n{e}\n" for e in entries)


def _write(tmp_path: Path, text: str, name: str = "s.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def _refused(path: Path, words: list[str], commands=("validate", "run"), *args: str) -> None:
    """Both commands exit 2 with one message holding every one of ``words``, no traceback."""
    for cmd in commands:
        res = runner.invoke(app, [cmd, str(path), *args])
        assert res.exit_code == 2, (cmd, res.output)
        assert res.exception is None or isinstance(res.exception, SystemExit), (cmd, res.exception)
        for w in words:
            assert w in res.output, (cmd, w, res.output)


# ------------------------------------------------------------------------------ [[vehicles]]

@pytest.mark.parametrize("value, words", [
    ("1e300", ["vehicles[1].lateral_offset", "expected a number in [-50, 50] [m]"]),
    ("-1e300", ["vehicles[1].lateral_offset", "expected a number in [-50, 50] [m]"]),
    ("nan", ["vehicles[1].lateral_offset", "finite"]),
    ("inf", ["vehicles[1].lateral_offset", "finite"]),
])
def test_listed_lateral_offset_out_of_range(tmp_path, value, words):
    """On a beam (no deck width to check the wheels against) a lateral offset of 1e300 m ran."""
    _refused(_write(tmp_path, BEAM + _vehicles(f'model = "hs20-44"\nlateral_offset = {value}')), words)


@pytest.mark.parametrize("key, value, allowed", [
    ("half_track", "1e300", "(0, 2] m"), ("half_track", "0.0", "must be > 0"), ("tire_deflection", "10.0", "(0, 0.1] m"),
    ("tire_deflection", "0.5", "(0, 0.1] m"),
])
def test_axle_truck_dimensions_out_of_range(tmp_path, key, value, allowed):
    """half_track = 1e300 m ended in an OverflowError traceback (exit 1)."""
    truck = f'model = "axles"\naxle_loads = [50000.0, 80000.0]\naxle_spacings = [4.0]\n{key} = {value}'
    _refused(_write(tmp_path, BEAM + _vehicles(truck)), [f"vehicles[1].{key}", allowed])


@pytest.mark.parametrize("key, value, words", [
    ("speed_kmh", "2000.0", ["vehicles[1].speed_kmh", "expected a number in [0.0036, 1080] [km/h], got 2000.0"]),
    ("speed", "1e300", ["vehicles[1].speed", "expected a number in [0.001, 300] [m/s], got 1e+300"]),
    ("entry_time", "1e300", ["vehicles[1].entry_time", "expected a number in [0, 3600] [s], got 1e+300"]),
])
def test_listed_motion_out_of_range(tmp_path, key, value, words):
    _refused(_write(tmp_path, BEAM + _vehicles(f'model = "sprung-mass"\n{key} = {value}')), words)


def test_two_trucks_in_one_lane_at_once_are_refused(tmp_path):
    """Two HS20-44 entering together in the same lane: they overlap over the whole truck, 14 ft + 14 ft =
    28 ft = 8.53 m between the first and last axle (AASHTO HS20-44, point tires)."""
    _refused(_write(tmp_path, BEAM + _vehicles('model = "hs20-44"', 'model = "hs20-44"')),
             ["vehicles[1] and vehicles[2] overlap in one lane", "overlap by 8.53 m", "lateral_offset", "entry_time"])


def test_a_truck_catching_up_with_another_is_refused(tmp_path):
    """A sprung mass at 30 m/s entering 0.2 s after one at 10 m/s reaches it 0.1 s later, 3 m past the entry
    (10 (t) = 30 (t − 0.2) → t = 0.3 s, x = 3 m): two point vehicles pass through each other."""
    text = BEAM + _vehicles('model = "sprung-mass"\nspeed = 10.0', 'model = "sprung-mass"\nspeed = 30.0\nentry_time = 0.2')
    _refused(_write(tmp_path, text), ["vehicles[1] and vehicles[2] overlap in one lane"])


def test_trucks_apart_in_time_or_lane_are_accepted(tmp_path):
    """1 s apart at 60 km/h the trucks are 16.7 m apart, more than their 8.53 m length; side by side 3.6 m
    apart their wheel tracks (±0.91 m, 6 ft track) do not meet; opposite directions on a beam stand for
    two lanes."""
    for entries in [('model = "hs20-44"', 'model = "hs20-44"\nentry_time = 1.0'),
                    ('model = "hs20-44"\nlateral_offset = -1.8', 'model = "hs20-44"\nlateral_offset = 1.8'),
                    ('model = "hs20-44"', 'model = "hs20-44"\ndirection = "-x"')]:
        res = runner.invoke(app, ["validate", str(_write(tmp_path, BEAM + _vehicles(*entries)))])
        assert res.exit_code == 0, res.output


def test_opposite_trucks_in_one_lane_of_a_deck_are_refused(tmp_path):
    text = DECK + _vehicles('model = "hs20-44"\nlateral_offset = 0.0', 'model = "hs20-44"\nlateral_offset = 0.5\ndirection = "-x"')
    _refused(_write(tmp_path, text), ["vehicles[1] and vehicles[2] overlap in one lane", "their axles overlap by 8.53 m"])


def test_listed_speed_above_200_kmh_is_warned(tmp_path):
    res = runner.invoke(app, ["validate", str(_write(tmp_path, BEAM + _vehicles('model = "sprung-mass"\nspeed_kmh = 250')))])
    assert res.exit_code == 0, res.output
    assert "warning: vehicles[1].speed" in res.output and "250 km/h" in res.output


# ------------------------------------------------------------------------------ [bridge.deck]

@pytest.mark.parametrize("spans, words", [
    ('["a", 3.0]', ["bridge.deck.spans", "finite number", "'a'"]),
    ("[nan, 16.76]", ["bridge.deck.spans", "finite number", "nan"]),
    ("[inf]", ["bridge.deck.spans", "finite number"]),
    ("[-10.0, 26.76]", ["bridge.deck.spans", "> 0 m"]),
    ("[]", ["bridge.deck.spans", "span lengths > 0"]),
    ('"16.76"', ["bridge.deck.spans", "span lengths > 0"]),
])
def test_malformed_deck_spans(tmp_path, spans, words):
    """spans = ["a"] gave "could not convert string to float" without naming the key; nan named "span"."""
    _refused(_write(tmp_path, DECK + f"[bridge.deck]\nspans = {spans}\n" + ONE_TRUCK), words)


def test_deck_table_on_a_continuous_beam_is_refused(tmp_path):
    _refused(_write(tmp_path, CONTINUOUS + "[bridge.deck]\nn_girders = 4\n" + ONE_TRUCK),
             ["bridge.deck", "unknown key", 'model = "slab-on-girder"'])


# ------------------------------------------------------------------------------ continuous beams

def test_moment_at_a_pinned_end_is_refused_by_validate(tmp_path):
    """M(0) = 0 for any load on a beam pinned at x = 0 (statics): validate passed it, run ended in a
    ValueError traceback (no static peak)."""
    _refused(_write(tmp_path, CONTINUOUS + ONE_TRUCK + "[response]\nmoment = [0.0, 10.0]\n"),
             ["response.moment[1]", "moment at x = 0 m", "zero wherever a wheel can stand"])


def test_shear_right_of_the_exit_support_is_refused(tmp_path):
    """V(L⁺) = 0: nothing is right of the exit support (shear is taken just right of x); the influence
    line is round-off (≈ 3e-11), so the run gave an impact factor of a static peak of micronewtons."""
    _refused(_write(tmp_path, CONTINUOUS + ONE_TRUCK + "[response]\nshear = [22.0]\n"), ["response.shear[1]"])


def test_default_reaction_of_a_spring_without_stiffness_is_refused(tmp_path):
    """A support spring of zero stiffness carries no force, R = k w = 0: the default reactions (every
    support) include it; validate passed, run ended in a traceback."""
    text = CONTINUOUS.replace("n_modes = 4", "n_modes = 4\nsupport_stiffness = [1e12, 0.0, 1e12]") + ONE_TRUCK
    _refused(_write(tmp_path, text), ["response.reaction (default)", "support 1 (x = 10 m)"])
    res = runner.invoke(app, ["validate", str(_write(tmp_path, text + "[response]\nreaction = [0, 2]\n"))])
    assert res.exit_code == 0, res.output


@pytest.mark.parametrize("key, value, words", [
    ("mass_per_length", "1e300", ["bridge.mass_per_length", "expected a number in (0, 1e+06]"]),
    ("EI", "1e300", ["bridge.EI", "expected a number in [1, 1e+16]"]),
    ("EI", "[5e9, nan]", ["bridge.EI", "finite"]),
    ("neutral_axis_depth", "-0.5", ["bridge.neutral_axis_depth", "expected a number > 0 [m], got -0.5"]),
    ("neutral_axis_depth", "nan", ["bridge.neutral_axis_depth", "finite"]),
    ("damping_ratio", "inf", ["bridge.damping_ratio", "finite"]),
])
def test_continuous_beam_properties_out_of_range(tmp_path, key, value, words):
    text = re.sub(rf"^{key} = .*$", "", CONTINUOUS, flags=re.M) + f"{key} = {value}\n" + ONE_TRUCK
    _refused(_write(tmp_path, text), words)


# ------------------------------------------------------------------------------ mode files

def _mode_file(tmp_path: Path, edit: dict[str, str | None] | None = None) -> Path:
    """A continuous beam's modes written by the project's writer, header lines replaced (None: removed)."""
    from vbikit.bridge import ContinuousBeam
    from vbikit.bridge.modefile import write_modes

    path = write_modes(ContinuousBeam(spans=(10.0, 12.0), EI=5e9, mass_per_length=5000.0, n_modes=3),
                       tmp_path / "beam.modes.csv")
    lines = path.read_text().splitlines()
    for key, value in (edit or {}).items():
        at = [i for i, line in enumerate(lines) if line.startswith(f"# {key} =")]
        if value is None:
            lines = [line for i, line in enumerate(lines) if i not in at]
        elif at:
            lines[at[0]] = f"# {key} = {value}"
        else:
            lines.insert(2, f"# {key} = {value}")
    path.write_text("\n".join(lines) + "\n")
    return path


def _modes_scenario(tmp_path: Path, extra: str = "") -> Path:
    return _write(tmp_path, f'[bridge]\nmodel = "modes-file"\nmodes_file = "beam.modes.csv"\n{extra}' + ONE_TRUCK)


@pytest.mark.parametrize("edit, words", [
    ({"frequencies_hz": "nan, 20, 40", "omega": None}, ["frequencies_hz", "finite frequency > 0 [Hz]"]),
    ({"frequencies_hz": "inf, 20, 40", "omega": None}, ["frequencies_hz", "finite frequency > 0"]),
    ({"frequencies_hz": "-5, 20, 40", "omega": None}, ["frequencies_hz", "finite frequency > 0"]),
    ({"frequencies_hz": "0, 20, 40", "omega": None}, ["frequencies_hz", "finite frequency > 0"]),
    ({"frequencies_hz": "30, 20, 40", "omega": None}, ["frequencies_hz", "ascending"]),
    ({"frequencies_hz": "nan, 20, 40"}, ["frequencies_hz", "finite frequency > 0"]),  # omega given as well
    ({"omega": "1, 2, 3"}, ["'omega' must be 2π × frequencies_hz", "has omega 3.0 rad/s"]),
    ({"span": "10 20"}, ["header 'span' must be one number"]),
    ({"span": ""}, ["header 'span' must be one number"]),
    ({"span": "-22"}, ["header 'span' must be one length > 0"]),
    ({"damping_ratios": "5, 0.02, 0.02"}, ["damping_ratios", "in [0, 1)"]),
    ({"damping_ratios": "inf"}, ["damping_ratios", "in [0, 1)"]),
    ({"damping_ratios": "0.02, 0.02"}, ["damping_ratios", "1 or 3 ratios"]),
    ({"strain_lever_arm": "-0.5"}, ["strain_lever_arm", "lengths in (0, 20] m"]),
    ({"strain_lever_arm": "nan"}, ["strain_lever_arm", "lengths in (0, 20] m"]),
    ({"strain_lever_arm": "1e300"}, ["strain_lever_arm", "lengths in (0, 20] m"]),
    ({"default_girder": "2.5"}, ["default_girder", "integer 1 … 1"]),
    ({"default_girder": "2"}, ["default_girder", "integer 1 … 1"]),
    ({"girder_y": "1e300"}, ["girder_y", "within the node lines"]),
    ({"default_lateral_offset": "1e300"}, ["default_lateral_offset", "±50 m"]),
    ({"deck_width": "1e300"}, ["deck_width", "to 200 m"]),  # found by the fuzz test: accepted
])
def test_mode_file_headers_out_of_range(tmp_path, edit, words):
    _mode_file(tmp_path, edit)
    _refused(_modes_scenario(tmp_path), ["beam.modes.csv", *words])


def test_mode_file_does_not_override_the_scenario_silently(tmp_path):
    """The file's damping_ratios replaced a damping_ratio the scenario gave, and n_modes above the
    file's three modes kept three without a word."""
    _mode_file(tmp_path)
    _refused(_modes_scenario(tmp_path, "damping_ratio = 0.05\n"),
             ["bridge.damping_ratio = 0.05", "gives its own damping_ratios (0.02, 0.02, 0.02)"])
    _refused(_modes_scenario(tmp_path, "n_modes = 10\n"), ["bridge.n_modes = 10", "has 3 modes", "1 … 3"])
    for extra in ("damping_ratio = 0.02\n", "n_modes = 2\n", ""):  # agreeing values and the defaults are fine
        res = runner.invoke(app, ["validate", str(_modes_scenario(tmp_path, extra))])
        assert res.exit_code == 0, (extra, res.output)
    _mode_file(tmp_path, {"damping_ratios": None})
    res = runner.invoke(app, ["validate", str(_modes_scenario(tmp_path, "damping_ratio = 0.05\n"))])
    assert res.exit_code == 0, res.output  # a file without damping takes the scenario's


@pytest.mark.parametrize("make", ["paper-bridge-2", "continuous"])
def test_bridge_command_on_a_mode_file_written_by_the_project(tmp_path, make):
    """`vbikit bridge SCENARIO.toml` on modes written by write_modes lists the written model's frequencies
    (round trip: the file holds omega exactly)."""
    from vbikit.bridge import ContinuousBeam
    from vbikit.bridge.modefile import write_modes
    from vbikit.bridge.presets import BRIDGE_PRESETS

    model = BRIDGE_PRESETS[make].build(n_modes=4) if make != "continuous" else \
        ContinuousBeam(spans=(10.0, 12.0), EI=5e9, mass_per_length=5000.0, n_modes=4)
    write_modes(model, tmp_path / "beam.modes.csv")
    res = runner.invoke(app, ["bridge", str(_modes_scenario(tmp_path)), "--no-plot"])
    assert res.exit_code == 0, res.output
    listed = [float(f) for f in re.findall(r"mode +\d+ +([0-9.]+) Hz", res.output)]
    assert listed == pytest.approx([round(float(f), 3) for f in model.frequencies_hz], abs=5e-4)


# ------------------------------------------------------------------------------ budgets

def _axles(n: int) -> str:
    return (f'model = "axles"\naxle_loads = [{", ".join(["50000.0"] * n)}]\n'
            f'axle_spacings = [{", ".join(["1.3"] * (n - 1))}]')


BUDGETS = {
    # name: (scenario text, words of the message)
    "2000-axles": (BEAM + "[vehicle]\n" + _axles(2000) + "\n[crossing]\nspeed_kmh = 60\n",
                   ["vehicle.axle_loads", "2000 is above the budget of 50", "--max-steps to 2e+08"]),
    "200-vehicles": (BEAM + _vehicles(*[f'model = "sprung-mass"\nentry_time = {2.0 * i}' for i in range(200)]),
                     ["vehicles: vehicles in one crossing: 200 is above the budget of 50", "--max-steps to 2e+07"]),
    "3000-spans": (CONTINUOUS.replace("[10.0, 12.0]", "[" + ", ".join(["10.0"] * 3000) + "]") + ONE_TRUCK,
                   ["bridge.spans: spans: 3000 is above the budget of 20", "--max-steps to 7.5e+08"]),
    "fine-mesh": (CONTINUOUS.replace("[10.0, 12.0]", "[" + ", ".join(["30.0"] * 12) + "]\nelements_per_span = 1000")
                  + ONE_TRUCK, ["12 spans × 1000 elements: 12000 is above the budget of 4000", "elements_per_span"]),
    # the default load effects of 10 spans: 2·10 − 1 moments, 10 shears, 11 reactions = 40
    "effects-times-elements": (CONTINUOUS.replace("[10.0, 12.0]", "[" + ", ".join(["30.0"] * 10) + "]\nelements_per_span = 300")
                               + ONE_TRUCK, ["40 load effects × 3000 beam elements", "above the budget of 100000",
                                             "response.moment"]),
}


@pytest.mark.parametrize("case", sorted(BUDGETS))
def test_size_budgets_refuse_quickly(tmp_path, case):
    """Each of these ran for minutes (or did not end) in validate: now refused in well under 2 s."""
    text, words = BUDGETS[case]
    path = _write(tmp_path, text)
    runner.invoke(app, ["validate", str(_write(tmp_path, BEAM + ONE_TRUCK, "warm.toml"))])  # imports, once
    t0 = time.perf_counter()
    res = runner.invoke(app, ["validate", str(path)])
    elapsed = time.perf_counter() - t0
    assert res.exit_code == 2 and res.exception is None or isinstance(res.exception, SystemExit), res.output
    for w in words:
        assert w in res.output, (w, res.output)
    assert elapsed < 2.0, elapsed


def test_size_budget_is_raised_with_max_steps(tmp_path):
    """A 60-axle truck: above the default 50 axles; --max-steps 1e7 (twice the default) allows 100."""
    path = _write(tmp_path, BEAM + "[vehicle]\n" + _axles(60) + "\n[crossing]\nspeed_kmh = 60\n")
    assert runner.invoke(app, ["validate", str(path)]).exit_code == 2
    res = runner.invoke(app, ["validate", str(path), "--max-steps", "1e7"])
    assert res.exit_code == 0, res.output


def test_size_budget_function():
    from vbikit.solve.budget import BudgetError, Limits, check_size, size_budget

    assert size_budget(20) == 20 and size_budget(20, Limits(max_steps=1000)) == 20  # never below the default
    assert size_budget(20, Limits(max_steps=25_000_000)) == 100
    with pytest.raises(BudgetError, match=r"spans: 21 is above the budget of 20 .* raise --max-steps to 5.25e\+06"):
        check_size("spans", 21, 20)


# ------------------------------------------------------------------------------ studies, divergence

def test_study_axis_over_listed_vehicles(tmp_path):
    """An axis over vehicles.speed_kmh ended in a traceback; it is refused with what to sweep instead, and
    that axis works."""
    base = ('name = "ax"\n[base]\n[base.bridge]\nmodel = "paper-bridge-2-beam"\nn_modes = 3\n[base.crossing]\n'
            'approach = 1.0\n[[base.vehicles]]\nmodel = "sprung-mass"\n')
    res = runner.invoke(app, ["study", "validate", str(_write(tmp_path, base + "speed_kmh = 60.0\n[axes]\n"
                                                                          '"vehicles.speed_kmh" = [50.0, 70.0]\n'))])
    assert res.exit_code == 2 and res.exception is None or isinstance(res.exception, SystemExit), res.output
    assert "axes.'vehicles.speed_kmh'" in res.output and "sweep crossing.speed_kmh" in res.output
    res = runner.invoke(app, ["study", "validate", str(_write(tmp_path, base + '[axes]\n"crossing.speed_kmh" = [50.0, 70.0]\n'))])
    assert res.exit_code == 0, res.output


def test_divergence_of_several_vehicles_names_each_front_axle():
    """A multi-vehicle run whose states turn non-finite: the message lists each vehicle's front axle
    (the formatting of an array of positions as one number crashed)."""
    from vbikit.bridge.presets import paper_beam
    from vbikit.solve import Crossing, simulate
    from vbikit.solve.crossing import VehicleMotion
    from vbikit.solve.result import DivergenceError, check_finite
    from vbikit.vehicle.presets import sprung_mass

    crossing = Crossing(paper_beam(16.76, "II", n_modes=2), approach=0.0,
                        vehicles=(VehicleMotion(sprung_mass(), 20.0), VehicleMotion(sprung_mass(), 15.0, direction="-x")))
    result = simulate(crossing)
    xi = result.xi.copy()
    xi[5:] = np.nan
    t5 = float(result.time[5])
    with pytest.raises(DivergenceError) as err:
        check_finite(dataclasses.replace(result, xi=xi))
    # front axles at step 5: +x from 0 at 20 m/s, −x from the 16.76 m span at 15 m/s
    assert f"x = {20.0 * t5:.3f} m (vehicle 1), x = {16.76 - 15.0 * t5:.3f} m (vehicle 2)" in str(err.value)


def test_axle_load_far_beyond_legal_limits_is_warned(tmp_path):
    """A 300 kN axle (permit loads exist, so it runs) is warned about: legal single axles carry 20 kip =
    89 kN (AASHTO/US federal) or 11.5 t = 113 kN (EU Directive 96/53/EC)."""
    truck = 'model = "axles"\naxle_loads = [60000.0, 300000.0]\naxle_spacings = [4.0]'
    res = runner.invoke(app, ["validate", str(_write(tmp_path, BEAM + _vehicles(truck)))])
    assert res.exit_code == 0, res.output
    assert "warning: vehicles[1].axle_loads: axle 2 carries 300 kN" in res.output
    truck = 'model = "axles"\naxle_loads = [60000.0, 100000.0]\naxle_spacings = [4.0]'
    res = runner.invoke(app, ["validate", str(_write(tmp_path, BEAM + _vehicles(truck)))])
    assert res.exit_code == 0 and "axle_loads" not in res.output, res.output


@pytest.mark.parametrize("girder", ['"IX"', "3", "true"])
def test_deck_girder_type_names_the_key(tmp_path, girder):
    """Found by the fuzz test: girder = "IX" gave "unknown girder type" without the key."""
    _refused(_write(tmp_path, DECK + f"[bridge.deck]\ngirder = {girder}\n" + ONE_TRUCK),
             ["bridge.deck.girder", "AASHTO type (I, II, III, IV, V, VI)"])


@pytest.mark.parametrize("model, key, value, words", [
    ("sprung-mass", "mass", "1e300", ["vehicles[1].mass", "<= 1e+06 kg"]),
    ("moving-force", "force", "1e300", ["vehicles[1].force", "<= 1e+07 N"]),
    ("quarter-car", "tire_stiffness", "1e300", ["vehicles[1].tire_stiffness", "<= 1e+12 N/m"]),
    ("quarter-car", "suspension_damping", "1e300", ["vehicles[1].suspension_damping", "<= 1e+09 N s/m"]),
])
def test_vehicle_parameters_above_their_range(tmp_path, model, key, value, words):
    """A sprung mass of 1e300 kg or a force of 1e300 N passed validate and ran."""
    _refused(_write(tmp_path, BEAM + _vehicles(f'model = "{model}"\n{key} = {value}')), words)


def test_bridge_command_refuses_more_modes_than_the_file_has(tmp_path):
    _mode_file(tmp_path)
    res = runner.invoke(app, ["bridge", str(_modes_scenario(tmp_path)), "--modes", "10", "--no-plot"])
    assert res.exit_code == 2 and "bridge.n_modes = 10" in res.output and "has 3 modes" in res.output, res.output
    res = runner.invoke(app, ["bridge", str(_modes_scenario(tmp_path)), "--modes", "2", "--no-plot"])
    assert res.exit_code == 0 and "mode  2" in res.output and "mode  3" not in res.output, res.output


def test_zero_influence_verdict_is_not_carried_to_another_bridge():
    """The preflight keeps, per influence function, whether it is zero wherever a wheel can stand; the
    verdict depends on the deck too, so one function used on a 20 m and then a 10 m beam is judged on
    each: f = 1 beyond x = 12 m only is zero on the 10 m deck (refused there), not on the 20 m one
    (the verdict was keyed on the wheel lines alone: the 10 m beam passed with the 20 m one's)."""
    from types import SimpleNamespace

    from vbikit.bridge import EulerBernoulliBeam
    from vbikit.scenario.preflight import check_load_effects
    from vbikit.scenario.schema import ScenarioError
    from vbikit.solve import Crossing
    from vbikit.vehicle import hs20_44

    def beyond_12_m(x, y):
        return np.where(np.asarray(x) > 12.0, 1.0, 0.0)

    effect = SimpleNamespace(kind="reaction", influence=beyond_12_m, label="reaction of the test", modal=None)
    scenario = SimpleNamespace(response=SimpleNamespace(moment=None, shear=None, reaction=None))

    def built(span: float):
        beam = EulerBernoulliBeam(span=span, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=3)
        return SimpleNamespace(load_effects=[effect], crossing=Crossing(beam, vehicle=hs20_44(), speed=20.0),
                               plan=SimpleNamespace(load_effect_method="mode-acceleration"))

    check_load_effects(scenario, built(20.0))  # nonzero beyond 12 m: accepted
    with pytest.raises(ScenarioError, match="zero wherever a wheel can stand"):
        check_load_effects(scenario, built(10.0))
