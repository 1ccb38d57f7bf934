"""Findings of a new user's trial (2026-12-07), each as it is now answered.

* a quoted number (``span = "30"``) got pydantic's own words with no range: now the range, the unit and
  that numbers are written without quotes;
* ``span`` on a slab-on-girder preset was refused as "a key of model = "beam"": now the preset's
  ``[bridge.deck]`` table is named; that run's bridge line gave the span twice;
* an empty scenario did not say that a vehicle is missing too;
* ``integrator = "RK4"`` was refused while ``class = "b"`` was taken: both letter cases now;
* a 30 km beam went on to a misleading "give a longer road": a beam's span has the continuous beam's
  bound (5000 m);
* ``vbikit presets`` listed the pothole's "ramp 0 m", a value ``ramp`` refuses;
* a lifetime file's start flag told the user to set a key "in the base scenario", which a lifetime file
  without ``base`` does not have.
"""
from __future__ import annotations

from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()

BEAM = """
name = "x"
[bridge]
model = "beam"
span = {span}
EI = 5.0e10
mass_per_length = 12000.0
[vehicle]
model = "hs20-44"
[tire]
model = "point"
[road]
class = "B"
[crossing]
speed_kmh = 80
{crossing}
"""


def _run(tmp_path, text: str, command: str = "run"):
    path = tmp_path / "s.toml"
    path.write_text(text)
    return runner.invoke(app, [command, str(path)])


def test_a_quoted_number_gets_its_range_and_the_reason(tmp_path):
    res = _run(tmp_path, BEAM.format(span='"30"', crossing=""))
    assert res.exit_code == 2
    assert "bridge.span: expected a number in (0, 5000] [m], got '30' (a number is written without quotes)" in res.output
    assert "Input should" not in res.output


def test_a_preset_deck_names_its_deck_table_for_span(tmp_path):
    deck = BEAM.replace('model = "beam"\nspan = {span}\nEI = 5.0e10\nmass_per_length = 12000.0',
                        'model = "paper-bridge-2"\nspan = 30').format(crossing="")
    res = _run(tmp_path, deck)
    assert res.exit_code == 2 and "bridge.deck.span" in res.output and 'a key of model = "beam"' not in res.output
    beam_preset = deck.replace('"paper-bridge-2"', '"paper-bridge-2-beam"')
    assert 'span is a key of model = "beam"' in _run(tmp_path, beam_preset).output
    ok = _run(tmp_path, deck.replace("span = 30", "[bridge.deck]\nspan = 30"))
    assert ok.exit_code == 0, ok.output
    bridge = next(line for line in ok.output.splitlines() if line.strip().startswith("bridge "))
    assert bridge.count("span") == 1 and "span 30 m" in bridge


def test_an_empty_scenario_names_every_missing_part(tmp_path):
    res = _run(tmp_path, 'name = "x"\n')
    assert res.exit_code == 2
    for key in ("bridge: missing", "crossing: missing", "vehicle: missing"):
        assert key in res.output, key


def test_integrator_names_take_any_letter_case(tmp_path):
    res = _run(tmp_path, BEAM.format(span=30.0, crossing='integrator = "RK4"'), "validate")
    assert res.exit_code == 0 and "(rk4)" in res.output, res.output


def test_a_beam_span_beyond_any_bridge_is_refused_by_its_range(tmp_path):
    res = _run(tmp_path, BEAM.format(span=30000.0, crossing=""))
    assert res.exit_code == 2 and "bridge.span: expected a number in (0, 5000] [m], got 30000.0" in res.output


def test_presets_list_no_ramp_for_a_cosine_defect():
    res = runner.invoke(app, ["presets"])
    pothole = next(line for line in res.output.splitlines() if line.strip().startswith("pothole"))
    assert "no ramp" in pothole and "ramp 0 m" not in pothole


def test_a_lifetime_start_flag_names_the_lifetime_files_crossing_table():
    from vbikit.lifetime.report import _start_flags

    attrs = {"approach_m": 10.0, "run_in_m": 0.0, "run_in_min_m": 0.0, "n_dynamic_events": 5}
    flags = _start_flags("moment_x15", attrs)
    assert [f.code for f in flags] == ["start_from_rest"]
    assert "in the lifetime file's [crossing] table (or its base scenario's)" in flags[0].message
    assert "in the base scenario (" not in flags[0].message
