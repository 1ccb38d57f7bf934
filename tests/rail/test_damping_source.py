"""Where a railway sweep's damping comes from, as the dataset and the report state it.

Found by an audit (2026-12-06): a scenario bridge whose [bridge] gives its own damping_ratio
ran with it (3 %), while rail.nc's `damping_source` and the report said "EN 1991-2:2003 Table 6.6,
steel, with additional damping" — Table 6.6 gives 0.797 % for that steel span (0.5 % +
Δζ(20 m) = 0.2965 %, EN 1991-2 Eq. 6.13); and a span of 30 m or more was said to have additional
damping where Eq. 6.13 adds none."""
import pytest

from vbikit.rail import codes
from vbikit.rail.run import run_rail

TRAINS = {"presets": ["hslm-a1"]}
SPEEDS = {"min": 200.0, "max": 220.0, "step": 20.0}


def test_a_scenarios_own_damping_is_not_labelled_table_6_6(tmp_path):
    (tmp_path / "deck.toml").write_text('name = "beam"\n[bridge]\nmodel = "beam"\nspan = 20.0\nEI = 7.9e10\n'
                                        'mass_per_length = 25000.0\ndamping_ratio = 0.03\n')
    r = run_rail({"bridge": {"scenario": str(tmp_path / "deck.toml"), "deck": "steel"}, "trains": TRAINS,
                  "speeds": SPEEDS}, figures=False)
    a = r.dataset.attrs
    assert a["damping_ratio"] == pytest.approx(0.03, rel=1e-12)
    # Table 6.6 would give 0.5 % + Δζ for this span: not what ran
    assert codes.code_damping("steel", 20.0) == pytest.approx(0.005 + 0.002965, abs=2e-6)
    assert a["damping_source"] == "given (damping_ratio of the [bridge] of deck.toml)"
    assert a["additional_damping"] == 0 and a["additional_damping_ratio"] == 0.0
    head = r.report.splitlines()[1]
    assert "damping 3.000 % (given (damping_ratio of the [bridge] of deck.toml), steel)" in head
    assert "Table 6.6" not in head and "additional damping" not in head


def test_table_damping_states_its_additional_damping():
    """Below 30 m the report gives Δζ (8 m steel: 2.0 % + 0.219 %, Eq. 6.13 by hand: (0.1496 − 0.04096) /
    (1 − 0.3528 − 0.2816 + 0.13056) = 0.21896 %); from 30 m it says that Eq. 6.13 adds none."""
    short = run_rail({"bridge": {"span": 8.0, "EI": 2.0e9, "mass_per_length": 9000.0, "deck": "steel"},
                      "trains": TRAINS, "speeds": SPEEDS}, figures=False)
    a = short.dataset.attrs
    assert a["damping_source"] == "EN 1991-2:2003 Table 6.6" and a["additional_damping"] == 1
    assert a["additional_damping_ratio"] == pytest.approx(0.0021896, rel=1e-4)
    assert a["damping_ratio"] == pytest.approx(0.02 + 0.0021896, rel=1e-4)
    assert "with additional damping Δζ = 0.219 % (EN 1991-2:2003 Eq. 6.13)" in short.report.splitlines()[1]
    long = run_rail({"bridge": {"span": 50.0, "EI": 6.0e11, "mass_per_length": 40000.0, "deck": "composite"},
                     "trains": TRAINS, "speeds": SPEEDS}, figures=False)
    b = long.dataset.attrs
    assert b["damping_ratio"] == pytest.approx(0.005, rel=1e-12)
    assert b["additional_damping"] == 0 and b["additional_damping_ratio"] == 0.0
    head = long.report.splitlines()[1]
    assert "with additional damping" not in head and "Eq. 6.13 adds Δζ below 30 m only" in head


def test_a_given_damping_is_labelled_given():
    r = run_rail({"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0, "damping": 0.02},
                  "trains": TRAINS, "speeds": SPEEDS}, figures=False)
    a = r.dataset.attrs
    assert a["damping_source"] == "given (bridge.damping)" and a["additional_damping"] == 0
    assert "damping 2.000 % (given (bridge.damping), prestressed-concrete)" in r.report.splitlines()[1]
