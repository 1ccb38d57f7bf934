"""A lifetime run's accuracy findings are `Flag` records with codes of FLAG_CODES
(vbikit.lifetime.report._flags), checked on a hand-made load effect summary: every code appears
when its condition holds, with the value and threshold set by hand here, and not otherwise; the
records survive JSON."""
import copy
import json
import math

import pytest

from vbikit.analysis.checks import FLAG_CODES, Flag, add_flags, dataset_has_flag, find_flag, has_flag
from vbikit.lifetime import accuracy as acc
from vbikit.lifetime.report import _flags, effect_flag_codes, flag_codes

ATTRS = {"xi_strongly_negative": -0.3, "half_step_tolerance": 0.01}


def _level(value, lower, upper):
    return {"value": value, "lower": lower, "upper": upper}


def _row(period, bm, pot):
    """A return-level row whose static and total levels are both ``bm`` (BM) and ``pot`` (POT)."""
    return {"return_period": period,
            **{w: {"block_maxima": _level(*bm), "peaks_over_threshold": _level(*pot), "methods_disagree": False}
               for w in ("static", "total")}}


def _clean():
    """A moment [N m] with nothing to flag: levels known to ±10 %, BM and POT intervals overlapping,
    shapes near 0, an ADR of 1.2 (1.1 … 1.3), no shortfall, governing peaks 0.1 % off at half step."""
    return {
        "units": "N m", "characteristic_period": 1000.0,
        "characteristic_static": 10.0, "characteristic_total": 12.0,
        "characteristic_static_not_estimable": None, "characteristic_total_not_estimable": None,
        "static_upper_bound": 20.0,
        "return_levels": [_row(100.0, (9.0, 8.5, 9.5), (9.2, 8.6, 9.8)), _row(1000.0, (10.0, 9.0, 11.0), (10.5, 9.5, 11.5))],
        "fits": {w: {"block_maxima_shape": 0.0, "pot_shape": -0.05, "shape_strongly_negative": False}
                 for w in ("static", "total")},
        "adr": {"value": 1.2, "lower": 1.1, "upper": 1.3, "indistinguishable_from_one": False},
        "run_static_shortfall": {"value": 0.002, "event": 7},
        "governing": {w: {"half_step_change": 0.001, "half_step_flag": False} for w in ("static", "total")},
    }


def _codes(e):
    return [f.code for f in _flags("M", e, ATTRS)]


def test_a_clean_effect_has_no_flag():
    assert _codes(_clean()) == []


def test_not_estimable():
    e = _clean()
    e["characteristic_total_not_estimable"] = "not estimable: all 5 daily maxima are equal (250000 N m)"
    (f,) = _flags("M", e, ATTRS)
    assert (f.code, f.output, f.subject) == ("characteristic_not_estimable", "characteristic total value", "M")
    assert f.message == "characteristic total not estimable: all 5 daily maxima are equal (250000 N m)"
    assert f.value is None and f.threshold is None


@pytest.mark.parametrize("char, bound, flagged", [
    (3.0e6, 2.5e6, True),      # above the bound
    (2.4e6, 2.5e6, False),     # below it
    (-0.006, -0.005, True),    # a downward effect, beyond its (negative) bound
    (-0.004, -0.005, False),
    (3.0e6, -2.5e6, False),    # opposite signs: not comparable, not flagged
    (3.0e6, None, False),      # no bound (fitted traffic)
])
def test_above_static_bound(char, bound, flagged):
    e = _clean()
    e["characteristic_static"], e["static_upper_bound"] = char, bound
    for r in e["return_levels"]:  # the static levels scaled like the characteristic (1000 years: char itself)
        for key in ("block_maxima", "peaks_over_threshold"):
            r["static"][key] = _level(char * r["return_period"] / 1000.0, None, None)
    flags = [f for f in _flags("M", e, ATTRS) if f.code == "characteristic_above_static_bound"]
    assert len(flags) == flagged
    if flagged:
        (f,) = flags
        assert (f.output, f.value, f.threshold) == ("characteristic static value", char, bound)
        assert "block maxima at 1000 years" in f.message and "POT at 1000 years" in f.message
        assert "at 100 years" not in f.message  # the 100-year levels (char / 10) are within the bound


@pytest.mark.parametrize("adr, lower, upper, bound", [(0.95, 0.8, 1.1, 1.1), (1.05, 0.9, 1.2, 0.9)])
def test_adr_interval_containing_one(adr, lower, upper, bound):
    """value: the interval's bound on the far side of 1 from the ADR (the upper one below 1, the lower one above)."""
    e = _clean()
    e["adr"] = {"value": adr, "lower": lower, "upper": upper, "indistinguishable_from_one": True}
    (f,) = _flags("M", e, ATTRS)
    assert (f.code, f.output, f.value, f.threshold) == ("adr_indistinguishable_from_one", "ADR", bound, 1.0)
    assert f.message == "ADR: the interval contains 1 — the data cannot tell the ADR from 1"


@pytest.mark.parametrize("bm, pot, gap", [
    ((10.0, 9.0, 11.0), (13.0, 12.0, 14.0), 1.0),        # POT interval 1 above the BM's
    ((10.0, 9.0, 11.0), (7.0, 6.0, 8.5), 0.5),           # 0.5 below it
    ((-10.0, -9.0, -11.0), (-13.0, -12.0, -14.0), 1.0),  # a downward effect: bounds nearer zero first
    ((10.0, 9.0, 11.0), (12.5, None, None), 1.5),        # POT without an interval: its value, 1.5 above
])
def test_bm_pot_disagreement(bm, pot, gap):
    """value: the gap between the intervals, by hand from the numbers above; the total agrees."""
    e = _clean()
    row = e["return_levels"][1]
    row["static"].update(block_maxima=_level(*bm), peaks_over_threshold=_level(*pot), methods_disagree=True)
    (f,) = _flags("M", e, ATTRS)
    assert (f.code, f.output, f.threshold) == ("bm_pot_disagree", "static return levels", 0.0)
    assert f.value == pytest.approx(gap, rel=1e-12)
    assert "disagree beyond their intervals at 1000 years" in f.message


def test_negative_shape():
    e = _clean()
    e["fits"]["total"].update(block_maxima_shape=-0.1, pot_shape=-0.47, shape_strongly_negative=True)
    (f,) = _flags("M", e, ATTRS)
    assert (f.code, f.output, f.value, f.threshold) == ("negative_shape", "total return levels", -0.47, -0.3)
    assert "block maxima ξ = -0.10, POT ξ = -0.47 < -0.3" in f.message


def test_wide_interval():
    """POT at 100 years 10 (2 … 18): width 16 = 1.6 × the level, above WIDE_INTERVAL = 1."""
    e = _clean()
    e["return_levels"][0]["static"]["peaks_over_threshold"] = _level(10.0, 2.0, 18.0)
    (f,) = _flags("M", e, ATTRS)
    assert (f.code, f.output, f.threshold) == ("wide_interval", "static return levels", acc.WIDE_INTERVAL)
    assert f.value == pytest.approx(1.6, rel=1e-12) and "(POT at 100 years)" in f.message


@pytest.mark.parametrize("shortfall, flagged", [(0.05, True), (0.01, False), (0.005, False)])
def test_static_reference_short(shortfall, flagged):
    """Flagged above half_step_tolerance (1 %), not at it."""
    e = _clean()
    e["run_static_shortfall"] = {"value": shortfall, "event": 12}
    flags = _flags("M", e, ATTRS)
    assert [f.code for f in flags] == ["static_reference_short"] * flagged
    if flagged:
        assert (flags[0].output, flags[0].value, flags[0].threshold) == ("ADR", 0.05, 0.01)
        assert "by up to 5.00 % (event 12; tolerance 1 %)" in flags[0].message


def test_governing_step_sensitive():
    e = _clean()
    e["governing"]["static"] = {"half_step_change": -0.02, "half_step_flag": True}
    (f,) = _flags("M", e, ATTRS)
    assert (f.code, f.output, f.value, f.threshold) == ("governing_step_sensitive", "governing static event", -0.02, 0.01)
    assert "changes by -2.00 % at half the time step" in f.message


def test_every_finding_at_once_keeps_the_report_order_and_survives_json():
    """All eight findings: one record each (codes of FLAG_CODES), the messages as warnings; the
    summary written as JSON and read back gives the same records, and each rebuilds its Flag."""
    e = _clean()
    e["characteristic_static_not_estimable"] = "not estimable: too few blocks"
    e["characteristic_static"], e["static_upper_bound"] = 30.0, 20.0
    e["fits"]["static"].update(pot_shape=-0.5, shape_strongly_negative=True)
    e["return_levels"][0]["static"]["block_maxima"] = _level(9.0, 0.0, 18.0)
    e["return_levels"][1]["static"]["methods_disagree"] = True
    e["return_levels"][1]["static"]["peaks_over_threshold"] = _level(13.0, 12.0, 14.0)
    e["adr"]["indistinguishable_from_one"] = True
    e["run_static_shortfall"]["value"] = 0.03
    e["governing"]["total"]["half_step_flag"] = True
    flags = _flags("M", e, ATTRS)
    assert [f.code for f in flags] == ["characteristic_not_estimable", "characteristic_above_static_bound",
                                       "negative_shape", "wide_interval", "bm_pot_disagree",
                                       "adr_indistinguishable_from_one", "static_reference_short",
                                       "governing_step_sensitive"]
    assert all(f.code in FLAG_CODES and f.subject == "M" for f in flags)
    facts = {"load_effects": {"M": copy.deepcopy(e)}}
    add_flags(facts["load_effects"]["M"], flags)
    back = json.loads(json.dumps(facts, allow_nan=False))
    m = back["load_effects"]["M"]
    assert m["warnings"] == [f.message for f in flags]
    assert [Flag(**r) for r in m["flags"]] == flags
    assert find_flag(m, "bm_pot_disagree")["value"] == pytest.approx(1.0)  # 12 − 11 (hand)
    assert has_flag(m, "governing_step_sensitive", output="governing total event")
    assert not has_flag(m, "governing_step_sensitive", output="governing static event")
    # the codes in the one format of every dataset's flag_codes (comma-separated, each once: on main JSON by effect)
    assert flag_codes(back) == ",".join(f.code for f in flags) == effect_flag_codes(back)[0]
    assert all(dataset_has_flag({"flag_codes": flag_codes(back)}, f.code) for f in flags)


def test_a_wide_interval_of_a_zero_level_is_written_as_null():
    """A level 0 with an interval around it: width / |level| is infinite, the JSON record holds null."""
    e = _clean()
    e["return_levels"][0]["total"]["block_maxima"] = _level(0.0, -1.0, 1.0)
    (f,) = _flags("M", e, ATTRS)
    assert f.code == "wide_interval" and math.isinf(f.value) and f.as_dict()["value"] is None


def test_unconverged_coupled_runs():
    """Dataset attributes of a lifetime with 3 of its 250 coupled runs whose contact forces did not converge in
    some steps (the most, 12, in event 40007): one flag per load effect on its total levels."""
    a = ATTRS | {"n_unconverged_events": 3, "unconverged_steps_max": 12.0, "unconverged_event": 40007,
                 "n_dynamic_events": 250}
    (f,) = _flags("M", _clean(), a)
    assert (f.code, f.output, f.subject, f.value, f.threshold) == ("contact_not_converged", "total return levels", "M",
                                                                  12.0, 0.0)
    assert "in some time steps of 3 of 250 coupled runs (the most: 12 steps in event 40007)" in f.message
    assert _codes(_clean()) == [] and _flags("M", _clean(), ATTRS | {"n_unconverged_events": 0}) == []


def test_unconverged_attributes_from_the_runs():
    from vbikit.lifetime.results import _unconverged_attrs

    runs = {5: {"unconverged_steps": 0.0}, 9: {"unconverged_steps": 4.0}, 11: {"unconverged_steps": 2.0}, 12: {}}
    assert _unconverged_attrs(runs) == {"n_unconverged_events": 2, "unconverged_steps_max": 4.0, "unconverged_event": 9}
    assert _unconverged_attrs({1: {"unconverged_steps": 0.0}}) == {"n_unconverged_events": 0,
                                                                    "unconverged_steps_max": 0.0, "unconverged_event": -1}
