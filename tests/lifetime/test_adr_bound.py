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



def test_the_bound_is_each_effect_s_own():
    """The bound takes the effect's own simulated events: a second effect whose events amplify more (0.75 here)
    does not loosen the first's (0.533: bound 1 + max(A = 0.6, 0.533) = 1.6, where the run's largest ratio over
    both effects gives 1.75 and would let the ADR 1.7278 pass)."""
    import numpy as np
    import xarray as xr

    from vbikit.lifetime.report import _largest_amplification

    static = np.array([[100.0, 10.0], [200.0, 20.0], [300.0, 30.0]])
    total = np.array([[153.3, 17.5], [np.nan, np.nan], [330.0, 31.0]])  # event 1 not simulated
    ds = xr.Dataset({"event_static": (("event", "load_effect"), static), "event_total": (("event", "load_effect"), total),
                     "event_simulated": ("event", np.array([1, 0, 1], np.int8))})
    assert _largest_amplification(ds, 0) == np.float64(153.3 / 100.0 - 1.0)  # (the unsimulated event's NaN ignored)
    assert _largest_amplification(ds, 1) == 0.75
    attrs = {**ATTRS, "amplification_max_observed": 0.75}  # the run's largest, over both effects
    own = adr_event_bound(attrs, _largest_amplification(ds, 0))
    assert math.isclose(own, 1.6) and math.isclose(adr_event_bound(attrs), 1.75)
    (flag,) = _adr_flags("M_mid", {**_effect(1.7278), "adr_event_bound": own}, attrs)
    assert flag.threshold == own
    assert _adr_flags("M_mid", _effect(1.7278), attrs) == []  # the run-wide bound: passes
    # the effect's events amplifying more than A: their ratio is the bound; a zero static peak: no bound
    assert math.isclose(adr_event_bound(attrs, _largest_amplification(ds, 1)), 1.75)
    zero = ds.copy(deep=True)
    zero["event_static"][0, 0] = 0.0
    assert _largest_amplification(zero, 0) == math.inf and adr_event_bound(attrs, math.inf) == math.inf
    none = ds.assign(event_simulated=("event", np.zeros(3, np.int8)))
    assert math.isnan(_largest_amplification(none, 0)) and math.isclose(adr_event_bound(attrs, math.nan), 1.6)
