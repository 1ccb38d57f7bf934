"""An ADR above what the events allow is flagged (``adr_above_event_bound``).  No day's largest total exceeds
its largest static by more than 1 + A (the screening leaves out only events with s·R_dyn ≤ (1 + A)·s·R_st)
or a simulated event's own R_dyn/R_st, so neither can any quantile of the daily total maxima exceed that of
the static ones by more: a characteristic total / static ratio above it is the two fits extrapolating apart.
A new user's trial met it: 5 days, ADR 1.728 against 1 + A = 1.600 (2026-12-07)."""
import dataclasses
import math


from vbikit.lifetime.report import _adr_flags, _in_doubt, adr_event_bound

ATTRS = {"amplification_bound_used": 0.6, "amplification_max_observed": 0.533, "n_days": 5}


def _effect(adr: float) -> dict:
    return {"adr": {"value": adr, "lower": 1.058, "upper": 2.398, "indistinguishable_from_one": False}}


def test_an_adr_above_the_event_bound_is_flagged_and_marks_the_total_and_the_adr():
    assert adr_event_bound(ATTRS) == 1.6
    assert adr_event_bound({**ATTRS, "amplification_max_observed": 0.75}) == 1.75  # a simulated event beyond A
    (flag,) = _adr_flags("w_mid", _effect(1.7278), ATTRS)
    assert (flag.code, flag.value, flag.threshold, flag.subject) == ("adr_above_event_bound", 1.7278, 1.6, "w_mid")
    assert "5 simulated days" in flag.message and "1.600" in flag.message
    e = {**_effect(1.7278), "flags": [dataclasses.asdict(flag)]}
    assert _in_doubt(e, "total") and _in_doubt(e, "adr") and not _in_doubt(e, "static")
    assert _adr_flags("w_mid", _effect(1.6), ATTRS) == []  # at the bound: possible
    assert _adr_flags("w_mid", _effect(1.7278), {"n_days": 5}) == []  # a dataset without the attributes: no bound
    assert math.isnan(adr_event_bound({}))
    assert adr_event_bound({**ATTRS, "amplification_max_observed": math.inf}) == math.inf  # a zero static peak
    assert _adr_flags("w_mid", _effect(9.0), {**ATTRS, "amplification_max_observed": math.inf}) == []

