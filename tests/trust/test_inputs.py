"""Inputs that used to pass ``validate`` and then crash, hang or give NaN in ``run``, and inputs that
were coerced or echoed: each gives exit 2 and one message naming the key or file, in ``validate``
and in ``run`` alike, before any integration."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

BEAM = """
[bridge]
model = "paper-bridge-2-beam"
[vehicle]
model = "hs20-44"
[crossing]
speed_kmh = 75
"""


def _write(tmp_path: Path, text: str, name: str = "s.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def _both(path: Path, *args: str):
    return [runner.invoke(app, [cmd, str(path), *args]) for cmd in ("validate", "run")]


CASES = {
    # (section to append or replace, words the message must contain)
    "dt-above-rk4-limit": (BEAM + "dt = 0.01\nintegrator = \"rk4\"\n", ["crossing.dt", "stability limit"]),
    "speed-too-slow": (BEAM.replace("speed_kmh = 75", "speed_kmh = 0.01"), ["time steps", "crossing.speed 0.002778 m/s = 0.01 km/h", "--max-steps"]),
    "approach-huge": (BEAM + "approach = 1e7\n", ["time steps", "crossing.approach 1e+07 m"]),
    "road-spacing-tiny": (BEAM + "[road]\nclass = \"C\"\nspacing = 1e-9\nn_max = 0.1\n", ["road", "spacing", "--max-memory"]),
    "deck-elements-huge": (BEAM.replace('"paper-bridge-2-beam"', '"paper-bridge-2"\n[bridge.deck]\nn_elements = 1000000000'),
                           ["bridge.deck", "n_elements"]),
    # RK4's step falls with the highest mode (exact modal stepping's does not)
    "modes-memory": (BEAM.replace('"paper-bridge-2-beam"', '"paper-bridge-2-beam"\nn_modes = 200') + 'integrator = "rk4"\n',
                     ["memory", "bridge.n_modes = 200", "--max-memory"]),
    "response-y-nan": (BEAM + "[response]\ny = nan\n", ["response.y", "finite"]),
    "response-y-inf": (BEAM + "[response]\ny = inf\n", ["response.y", "finite"]),
    "lateral-offset-nan": (BEAM + "lateral_offset = nan\n", ["crossing.lateral_offset", "finite"]),
    "road-length-inf": (BEAM + "[road]\nclass = \"C\"\nlength = inf\n", ["road.length", "finite"]),
    "approach-inf": (BEAM + "approach = inf\n", ["crossing.approach", "finite"]),
    "defect-position-inf": (BEAM + "[road]\n[[road.defects]]\nkind = \"bump\"\nposition = inf\n", ["road.defects[1].position"]),
    "string-as-number": (BEAM + "approach = \"12\"\n", ["crossing.approach", "expected a number"]),
    "bool-as-number": (BEAM + "approach = true\n", ["crossing.approach", "expected a number"]),
    "float-as-integer": (BEAM.replace('"paper-bridge-2-beam"', '"paper-bridge-2-beam"\nn_modes = 10.5'), ["bridge.n_modes"]),
    "deck-string-number": (BEAM.replace('"paper-bridge-2-beam"', '"paper-bridge-2"\n[bridge.deck]\ndiaphragms = ["0", 16.76]'),
                           ["bridge.deck.diaphragms", "finite number"]),
    "deck-float-integer": (BEAM.replace('"paper-bridge-2-beam"', '"paper-bridge-2"\n[bridge.deck]\nn_girders = 5.0'),
                           ["bridge.deck.n_girders", "integer"]),
    # found by the fuzz run: a mass of 1e-300 kg/m gave a zero step (ZeroDivisionError); a Newmark step
    # of 1e9 s passed validate and then asked the road for x up to 2e10 m
    "mass-tiny": (BEAM.replace('"paper-bridge-2-beam"', '"beam"\nspan = 20.0\nEI = 1e10\nmass_per_length = 1e-300'),
                  ["time steps", "crossing.dt"]),
    "dt-longer-than-crossing": (BEAM + "integrator = \"newmark\"\ndt = 1e9\n", ["crossing.dt = 1e+09 s", "fewer than 10 steps"]),
    # ten steps over the run but not while the truck is on the span (a long free vibration): the run's static
    # history was zero at every step and its impact factor raised a traceback (found by fuzzing)
    # EI = 1e-300: the modes' frequencies underflowed and the load-effect step estimate overflowed (found by fuzzing)
    "EI-tiny": ("[bridge]\nmodel = \"beam\"\nspan = 20.0\nEI = 1e-300\nmass_per_length = 5000.0\n[vehicle]\n"
                "model = \"sprung-mass\"\n[crossing]\nspeed = 20.0\n", ["bridge.EI", "[1, 1e+16]", "1e-300"]),
    # a preset's own diaphragms beyond a span the file shortens: the message named no key (found by fuzzing)
    "deck-span-shorter-than-preset-diaphragms": (
        "[bridge]\nmodel = \"paper-bridge-1\"\nn_modes = 4\n[bridge.deck]\nspan = 1.0\n[vehicle]\nmodel = \"hs20-44\"\n"
        "[crossing]\nspeed_kmh = 60\n", ["bridge.deck: the model's own diaphragms", "0 … 1 m", "(span)",
                                            "set bridge.deck.diaphragms as well"]),
    "dt-longer-than-time-on-bridge": (BEAM + "free_vibration = 60\ndt = 0.5\n",
                                      ["crossing.dt = 0.5 s", "fewer than 10 steps while the vehicles are on the bridge"]),
    # found by the fuzz run with exact modal stepping: wheels 7e16 m off the deck diverged after validate
    # (a lateral offset of -7e16 m is now refused by its range, ±50 m, before the deck width is known)
    "wheels-off-the-deck": (BEAM.replace('"paper-bridge-2-beam"', '"paper-bridge-1"\nn_modes = 4') + "lateral_offset = -7.0\n",
                            ["crossing.lateral_offset", "off the 9.75 m wide deck"]),
    "lateral-offset-huge": (BEAM.replace('"paper-bridge-2-beam"', '"paper-bridge-1"\nn_modes = 4') + "lateral_offset = -7e16\n",
                            ["crossing.lateral_offset", "expected a number in [-50, 50] [m]"]),
    # [[vehicles]] are checked like [vehicle]: a listed truck 5 m off the centreline of a 9.75 m deck, and one
    # driving -x whose mirrored wheels leave the deck on the other side
    "listed-wheels-off-the-deck": ('[bridge]\nmodel = "paper-bridge-2"\nn_modes = 4\n[crossing]\nspeed_kmh = 60\n'
                                   '[[vehicles]]\nmodel = "hs20-44"\n[[vehicles]]\nmodel = "hs20-44"\nlateral_offset = 5.0\n',
                                   ["vehicles[2].lateral_offset = 5 m", "y = 6.1 m", "off the 9.75 m wide deck"]),
    "listed-wheels-off-the-deck-minus-x": ('[bridge]\nmodel = "paper-bridge-2"\nn_modes = 4\n[crossing]\nspeed_kmh = 60\n'
                                           '[[vehicles]]\nmodel = "hs20-44"\ndirection = "-x"\nlateral_offset = -4.2\n',
                                           ["vehicles[1].lateral_offset = -4.2 m", "y = 5.3 m", "off the 9.75 m wide deck"]),
    "deep-nesting": ("a = " + "[" * 5000 + "]" * 5000 + "\n", ["s.toml", "not valid TOML"]),
    "unknown-key": (BEAM + "spead = 3\n", ["crossing.spead", "unknown key"]),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_validate_refuses_what_run_refuses(tmp_path, case):
    text, words = CASES[case]
    for res in _both(_write(tmp_path, text)):
        assert res.exit_code == 2, res.output
        assert res.exception is None or isinstance(res.exception, SystemExit)
        for w in words:
            assert w in res.output, (w, res.output)


def test_budget_can_be_raised(tmp_path):
    path = _write(tmp_path, BEAM.replace("speed_kmh = 75", "speed_kmh = 5") + "approach = 1\n")
    assert runner.invoke(app, ["validate", str(path), "--max-steps", "1000"]).exit_code == 2
    res = runner.invoke(app, ["validate", str(path), "--max-steps", "1e6"])
    assert res.exit_code == 0, res.output
    res = runner.invoke(app, ["validate", str(path), "--max-memory", "1kB"])
    assert res.exit_code == 2 and "memory" in res.output


def test_encoding_error_names_the_file(tmp_path):
    path = tmp_path / "latin.toml"
    path.write_bytes(BEAM.encode() + b"name = \"caf\xe9\"\n")
    for res in _both(path):
        assert res.exit_code == 2 and "latin.toml" in res.output and "UTF-8" in res.output


def test_modes_file_of_another_kind_is_not_echoed(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("root:x:0:0:SECRET-LINE\n")
    path = _write(tmp_path, f'[bridge]\nmodel = "modes-file"\nmodes_file = "{secret}"\n[vehicle]\nmodel = "hs20-44"\n'
                            "[crossing]\nspeed_kmh = 75\n")
    for res in _both(path):
        assert res.exit_code == 2 and "not a vbikit mode file" in res.output
        assert "SECRET" not in res.output


def test_speed_in_kmh_typed_as_ms_is_flagged(tmp_path):
    """speed = 75 (meant km/h, read as 270 km/h) gave IM 0.83 without a word."""
    path = _write(tmp_path, BEAM.replace("speed_kmh = 75", "speed = 75"))
    res = runner.invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)
    assert any("270 km/h" in w for w in summary["warnings"])
    assert "warning: crossing.speed" in res.stderr
    assert summary["inputs"]["speed_kmh"] == pytest.approx(270) and summary["inputs"]["speed_m_s"] == 75


def test_profile_in_mm_read_as_m_is_flagged(tmp_path):
    """A profile typed in mm but read as m: every wheel leaves the road; the report said nothing."""
    profile = tmp_path / "mm.csv"
    profile.write_text("x,z\n" + "".join(f"{x},{5.0 * ((x // 2) % 2)}\n" for x in range(-60, 80)))
    path = _write(tmp_path, BEAM + f'[road]\nprofile_file = "{profile.name}"\n')
    res = runner.invoke(app, ["run", str(path)])
    assert res.exit_code == 0, res.output
    assert "warning: road: the measured profile (mm.csv) reaches 5 m" in res.stderr
    assert "check the profile file's unit" in res.stderr
    assert "lost contact" in res.stderr


def test_report_states_its_inputs(tmp_path):
    path = _write(tmp_path, BEAM + "[road]\nclass = \"C\"\nseed = 7\n")
    res = runner.invoke(app, ["run", str(path), "--json"])
    inputs = json.loads(res.stdout)["inputs"]
    assert inputs["road"] == {"class": "C", "phi0": 256e-6, "n0": 0.1, "exponent": 2.0, "seed": 7, "spacing": 0.01,
                              "n_min": 0.01, "n_max": 4.0}
    assert {"bridge", "vehicle", "tire", "speed_kmh", "speed_m_s", "integrator", "dt", "n_steps", "n_modes",
            "vbikit_version"} <= set(inputs)
    text = runner.invoke(app, ["run", str(path)]).stdout
    for words in ("paper-bridge-2-beam", "hs20-44, 75 km/h = 20.83 m/s", "point", "class C", "seed 7", "vbikit"):
        assert words in text


def test_response_on_a_support_is_flagged(tmp_path):
    path = _write(tmp_path, BEAM + "[response]\nx = 0.1\n")
    res = runner.invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0 and "next to a support" in res.stderr


def test_coarse_newmark_step_and_unresolved_modes_are_flagged(tmp_path):
    path = _write(tmp_path, BEAM + "integrator = \"newmark\"\ndt = 0.002\n")
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 0, res.output
    assert "coarser than the automatic step" in res.stderr and "are not resolved" in res.stderr


def test_response_point_on_a_support_is_refused_by_validate(tmp_path):
    """Found by the fuzz test: response.x = 0 passed validate, then run failed (no static response)."""
    for res in _both(_write(tmp_path, BEAM + "[response]\nx = 0\n")):
        assert res.exit_code == 2 and "response.x = 0 m" in res.output and "every mode shape is zero" in res.output


def test_python_simulate_has_the_same_budget_and_it_can_be_raised():
    from vbikit.bridge.presets import paper_beam
    from vbikit.solve import Crossing, simulate
    from vbikit.solve.budget import BudgetError, Limits
    from vbikit.vehicle.presets import sprung_mass

    crossing = Crossing(paper_beam(16.76, "II", n_modes=2), sprung_mass(), speed=20.0, approach=0.0)
    with pytest.raises(BudgetError, match="time steps, above the limit 100"):
        simulate(crossing, Limits(max_steps=100))
    assert simulate(crossing, Limits(max_steps=10**5)).n_steps > 100


def test_report_states_every_vehicle(tmp_path):
    path = _write(tmp_path, BEAM.replace('[vehicle]\nmodel = "hs20-44"\n[crossing]\nspeed_kmh = 75\n',
                                         '[crossing]\napproach = 5\n[[vehicles]]\nmodel = "two-axle"\nspeed_kmh = 60\n'
                                         '[[vehicles]]\nmodel = "sprung-mass"\nspeed = 75\ndirection = "-x"\nentry_time = 0.2\n'))
    res = runner.invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)
    vehicles = summary["inputs"]["vehicles"]
    assert [v["vehicle"] for v in vehicles] == ["two-axle", "sprung-mass"]
    assert vehicles[0]["speed_kmh"] == pytest.approx(60) and vehicles[1]["speed_m_s"] == 75
    assert vehicles[1]["direction"] == "-x" and vehicles[1]["entry_time"] == 0.2
    assert any(w.startswith("vehicles[2].speed: speed 270 km/h") or "vehicles[2].speed" in w for w in summary["warnings"])
    text = runner.invoke(app, ["run", str(path)]).stdout
    assert "vehicle 2            sprung-mass, 270 km/h = 75 m/s, -x, entering at 0.2 s" in text


def test_a_bridge_that_cannot_be_solved_is_exit_2(tmp_path):
    """Found by the fuzz test: a continuous beam with a span of 1e300 m ended in a RuntimeError traceback
    (that span is now refused by its range, 0.5 … 5000 m; a beam on springs of zero stiffness everywhere,
    a mechanism, still cannot be solved)."""
    text = BEAM.replace('model = "paper-bridge-2-beam"', 'model = "continuous-beam"\nspans = [55.0, 10.0]\n'
                                                         'EI = 5e9\nmass_per_length = 5000.0\n'
                                                         'support_stiffness = [0.0, 0.0, 0.0]')
    for res in _both(_write(tmp_path, text)):
        assert res.exit_code == 2 and "bridge (model = 'continuous-beam'): the model could not be solved" in res.output, \
            res.output
    for spans, words in (("[55.0, 1e300]", "expected a number in [0.5, 5000] [m], got 1e+300"),
                         ("[55.0, 1e-6]", "expected a number in [0.5, 5000] [m], got 1e-06")):
        text = BEAM.replace('model = "paper-bridge-2-beam"', f'model = "continuous-beam"\nspans = {spans}\n'
                                                             'EI = 5e9\nmass_per_length = 5000.0')
        for res in _both(_write(tmp_path, text)):  # a span of 1e-6 m ended in an IndexError traceback
            assert res.exit_code == 2 and "bridge.spans[2]" in res.output and words in res.output, res.output
