"""How good a lifetime result is: the second method beside every characteristic value, the
flags, the ADR's interval and the fatigue verdict, in numbers and in words.

**Two methods for every return level.** Block maxima (BM: GEV or Gumbel of the daily or weekly
maxima) and peaks over threshold (POT: a GPD of the events' peaks above a threshold u, Coles
2001 §4.3) estimate the same level from different parts of the data.  Static: u is the
(1 − 2·n_days/n_events) quantile of the events' static peaks (about two exceedances a day).
Total: only the simulated events' total peaks are known, and the screening makes them complete
above c = (1 + A)·max s·R_st of the events it left out (an event left out has
s·R_dyn ≤ (1 + A)·s·R_st < c); u = max(c, the static threshold), λ = exceedances a year.  Fewer
than 10 exceedances: no POT value (said so).

**Flags.**

* *methods disagree*: the BM and the POT confidence intervals (the run's ``ci``) do not overlap
  — the two methods disagree beyond their intervals (a method without an interval: its value
  outside the other's interval).  The weaker test "either value outside the other's interval"
  would flag most Gumbel samples, where the free-ξ POT value scatters well beyond the narrow
  Gumbel BM interval (26 of 30 simulated samples, against 4 of 30 for the overlap test;
  tests/lifetime/test_accuracy.py).
* *strongly negative shape*: the fitted ξ (GEV of the block maxima, GPD of the exceedances) is
  below ``XI_STRONGLY_NEGATIVE`` = −0.3.  A negative ξ is a bounded upper tail (end point
  μ − σ/ξ, u − σ/ξ for the GPD); fitted to a short record it pins the long-period levels at
  an end point set by the few heaviest events seen, not by the traffic's population, and the
  delta-method intervals (asymptotic, regular only for ξ > −0.5, Smith 1985; Coles §3.3.2)
  are then too narrow.  −0.3 keeps a margin above that regularity limit −0.5, where on the few
  dozen maxima of a short run the estimate of ξ is already within one or two standard errors of
  it; a value below −0.3 says "a bounded tail fitted from little data", not "a physical bound
  of the traffic".  (Issue case: one week of the example's entry reaction, GPD ξ = −0.47, POT and
  BM 1,000-year values 42 % apart.)  The flag does not depend on which of the two values is
  larger; it asks for a longer run, not for one method's number.
* *interval too wide*: a return level whose confidence interval is wider than the level itself
  (``WIDE_INTERVAL``), or reaches across zero, cannot be signed, and the overlap test above can
  never fire on it: said in words per method and return period.

* *above the traffic's largest static effect* (bootstrap traffic only): a characteristic static
  value above ``static_upper_bound``, the largest static effect any event of the traffic model
  can produce.  In ``mode = "bootstrap"`` every vehicle is one of a finite set of records and a
  lane's arrivals are at least its smallest headway h_min apart (``TrafficModel.arrivals``), so
  at most k = ⌊T/h_min⌋ + 1 of a lane's vehicles load the deck at once (T the longest time a
  vehicle of the lane has a load on the deck's x range: (deck length + vehicle length + 2 × the
  tire's reach) / speed); since the event's effect s·R(t) = Σ_i s·R_i(t) and each vehicle's
  s·R_i(t) ≤ max(its own static peak, 0), s·R ≤ Σ_lanes k × the largest single-vehicle peak of
  the lane — a strict bound (loose where k > 1: the vehicles of a lane never all stand at their
  worst position at once).  A value above it is the fitted distribution's unbounded tail (Gumbel,
  a GEV or GPD with ξ ≥ 0) extrapolating past what the traffic can produce.  The fitted generator
  (``mode = "fitted"``) draws GVWs from normal mixtures without an upper end: no bound, no flag.
  Nor is the largest observed event one: a characteristic value is meant to exceed it, and how far
  depends on the tail's shape, which the interval of a short run does not pin down; the POT and
  shape flags above judge that.

**ADR with its interval.** ADR = z_total / z_static at the characteristic period, with the
delta-method interval of ``vbikit.extremes.level_ratio`` (the two fits' covariance and their
cross-covariance from the sandwich of the stacked score equations of the same blocks — the
first-order equivalent of a joint bootstrap of the blocks).  When the interval contains 1 the
data cannot tell the ADR from 1.

**Fatigue verdict.** Per detail the Miner damage over the design life,
D_life = D_so_far + d·T_life (d the damage a year of the run), against 1, with the upper bound
D_so_far + (D + z·se)·T_life/years (se the standard error of the period's damage from the
dynamic sample, z = z_{(1+ci)/2}); the remaining life (1 − D_so_far)/d; the dynamic-to-static
damage ratio D/D_static with its standard error se/D_static (the static damage has no sampling
error), or in words why it has no value.

**The fatigue limit over the design life.** EN 1993-1-9 1.3.3.3 (and AASHTO's (ΔF)_TH) give no damage
when every stress range of the loading is below the constant-amplitude limit; the loading meant is the
design life's, and its largest range is larger than a few simulated days'.  So the limit rule applies
only when the simulated period's ranges are below the limit *and* so is the design life's largest
static range, estimated from the simulated days' largest ranges (each day counted alone; days without
a range left out, which errs high): with F the Gumbel fit of those daily maxima (Coles 2001 eq. 3.3),
the design life's N = T_life·``days_per_year`` days have a largest range below x with probability
F(x)^N, so the level the design life's largest stays below with the run's confidence ``ci`` is
F(x) = ci^(1/N): the return level for T_life / (−ln ci) years (≈ 19.5 T_life at 95 %; the
return level for T_life itself is exceeded in the life with probability 1 − (1 − 1/N)^N ≈ 63 %).
The rule compares the upper bound of that level's ``ci`` interval (delta method: the fit's own
uncertainty) — for the static damage alone as it is, for the total damage times the simulated
dynamics' amplification of the largest range (the simulated events' largest total range over the
period's largest static one, at least 1; an approximation: the two ranges need not be of one event).
Fewer than ``MIN_DAYS_FOR_RANGE`` days with a range: no estimate, and the rule is not applied
(every range above the cut-off counts: D > 0, said in words); days whose largest ranges are all
equal give that range (no spread: the design life's largest is the same); no range at all gives 0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vbikit._words import counted

#: ξ below this is flagged as a bounded tail fitted from little data (module docstring)
XI_STRONGLY_NEGATIVE = -0.3
#: relative change of a governing event's peak at half the time step above which it is flagged
HALF_STEP_TOLERANCE = 0.01
#: a return level whose confidence interval is wider than this fraction of the level (half-width
#: above half the level) is flagged as too uncertain to use or to compare methods with
WIDE_INTERVAL = 1.0
#: fewest exceedances a POT fit uses (vbikit.extremes.MIN_SAMPLE["gpd"])
MIN_EXCEEDANCES = 10


@dataclass(frozen=True)
class PotLevels:
    """Return levels by peaks over threshold (NaN when not available; ``why`` says why)."""

    level: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    threshold: float
    shape: float
    n_exceedances: int
    why: str = ""


def pot_levels(values: np.ndarray, threshold: float, values_per_year: float, periods: np.ndarray,
               ci: float) -> PotLevels:
    """GPD fit of ``values`` above ``threshold`` (``values_per_year`` of them a year) and its
    return levels with delta-method intervals (``vbikit.extremes``)."""
    from vbikit.extremes import ExtremesError, fit_peaks_over_threshold, return_levels

    nan = np.full(len(periods), np.nan)
    values = np.asarray(values, float)
    values = values[np.isfinite(values)]
    k = int(np.sum(values > threshold)) if np.isfinite(threshold) else 0
    if k < MIN_EXCEEDANCES:
        return PotLevels(nan, nan.copy(), nan.copy(), threshold, math.nan, k,
                         f"{counted(k, 'exceedance')} of the threshold, a GPD fit needs {MIN_EXCEEDANCES}")
    try:
        fit = fit_peaks_over_threshold(values, threshold, values_per_year)
        level, lo, hi = return_levels(fit, periods, ci)
    except ExtremesError as err:
        return PotLevels(nan, nan.copy(), nan.copy(), threshold, math.nan, k, str(err))
    why = ""
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):  # the fit's covariance (observed information) is singular
        why = (f"no confidence interval: the covariance of the GPD fit to {counted(k, 'exceedance')} could not be estimated "
               "(the delta method needs it); the level stands without an interval")
    return PotLevels(level, lo, hi, threshold, float(fit.shape), k, why)


def static_upper_bound(model, setup, signs: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The largest static effect s·R any event of ``model`` (a ``TrafficModel``) can produce on every
    load effect of ``setup`` (module docstring, *above the traffic's largest static effect*), and the
    vehicles per lane k it assumes at once, or None for a model without one (fitted traffic).
    Returns (bound per load effect, in the governing direction s ≥ 0; k per lane of ``model.lanes``)."""
    from dataclasses import replace

    from vbikit.lifetime.influence import event_static

    if model.mode != "bootstrap" or not model.records:
        return None
    records = [replace(r, time=0.0, speed=float(model.fixed_speed)) if model.fixed_speed is not None else
               replace(r, time=0.0) for r in model.records]
    peaks = event_static(records, [(i,) for i in range(len(records))], setup.lines, setup.span, setup.lanes,
                         setup.pattern, tables=setup.tables).peaks.reshape(len(records), len(setup.lines))
    single = np.maximum(peaks * np.asarray(signs, float)[None, :], 0.0)  # each vehicle's s·R_i(t) ≤ this
    first, last = setup.bridge.deck_extent
    deck = float(max(last, setup.span) - min(first, 0.0))
    bound = np.zeros(len(setup.lines))
    per_lane = []
    for ln in model.lanes:
        idx = np.asarray(ln.records, np.int64)
        reside = max((deck + records[i].length + 2.0 * setup.pattern.reach) / records[i].speed for i in idx)
        h_min = ln.min_headway - 1e-3  # arrival times are rounded to the millisecond (TrafficModel.day)
        k = int(math.floor(reside / h_min)) + 1
        per_lane.append(k)
        bound += k * single[idx].max(axis=0)
    return bound, np.array(per_lane, np.int64)


def completeness_words(used: float, given: float, sampled: bool) -> str:
    """Why a total POT threshold is above the static one: the level ``completeness_level`` sets, in
    words, with what would lower it.  ``used``: the screening bound A the run ended with, ``given``:
    the file's ``amplification`` (the run's check raises A when an event exceeds it), ``sampled``:
    whether the run draws a random sample of events ([[fatigue.details]] given)."""
    words = (f"the simulated totals are complete only above this threshold, (1 + A) = {1.0 + used:.3g} times the "
             "largest static peak of the events the screening did not simulate; ")
    words += ("a larger [fatigue] dynamic_sample simulates more of them (1: every event, and the threshold is the "
              "static fit's)" if sampled else
              "without [[fatigue.details]] no random sample of events is simulated (with them, [fatigue] "
              "dynamic_sample = 1 simulates every event, and the threshold is the static fit's)")
    if used > given:
        return words + f"; A is {used:.3g} because the run's check raised it from the file's amplification {given:.3g}"
    return words + "; a smaller amplification A lowers it where the run's check shows that A holds"


def total_pot_why(why: str, level: float, static_threshold: float, static_fitted: bool, used: float, given: float,
                  sampled: bool) -> str:
    """Why a total POT fit is missing (``why``, from ``pot_levels``), with ``completeness_words``
    added when the screening's completeness ``level`` set the total threshold above the static one
    (``static_threshold``) and the static fit, made first at its own threshold, has its exceedances
    (``static_fitted``): then the screening, not the traffic, left the total fit short of exceedances.
    Otherwise ``why`` as it is (the static fit lacks them too: more days, not another screening)."""
    if level > static_threshold and static_fitted:
        return why + "; " + completeness_words(used, given, sampled)
    return why


def completeness_level(static_s: np.ndarray, simulated: np.ndarray, bound: float) -> float:
    """c = (1 + A)·max s·R_st over the events the screening left out: every event whose total
    s·R_dyn exceeds c was simulated (−inf when every event was)."""
    left = static_s[~simulated]
    return float((1.0 + bound) * left.max()) if left.size else -math.inf


def methods_disagree(bm, bm_lo, bm_hi, pot, pot_lo, pot_hi) -> np.ndarray:
    """True where the BM and POT confidence intervals do not overlap; where one method has a
    value but no interval, where that value lies outside the other's interval (False where
    neither test can be made)."""
    bm, bm_lo, bm_hi, pot, pot_lo, pot_hi = (np.asarray(a, float) for a in (bm, bm_lo, bm_hi, pot, pot_lo, pot_hi))
    fin = np.isfinite
    bm_iv, pot_iv = fin(bm_lo) & fin(bm_hi), fin(pot_lo) & fin(pot_hi)
    with np.errstate(invalid="ignore"):
        apart = bm_iv & pot_iv & ((pot_hi < bm_lo) | (pot_lo > bm_hi))
        pot_out = ~pot_iv & fin(pot) & bm_iv & ((pot < bm_lo) | (pot > bm_hi))
        bm_out = ~bm_iv & fin(bm) & pot_iv & ((bm < pot_lo) | (bm > pot_hi))
    return apart | pot_out | bm_out


def too_wide(level: float | None, lower: float | None, upper: float | None) -> bool:
    """True when the interval [lower, upper] of ``level`` is wider than ``WIDE_INTERVAL`` × |level|
    (or reaches across zero): too uncertain to sign, and too wide for the BM/POT overlap test to
    ever fire (review case: the example week's total POT of M_mid at 1,000 years, −2.4e6 … 6.9e6 N m
    around 2.3e6 N m)."""
    if level is None or lower is None or upper is None or not all(map(math.isfinite, (level, lower, upper))):
        return False
    return abs(upper - lower) > WIDE_INTERVAL * abs(level) or lower * upper <= 0.0  # bounds in either order


def run_static_shortfall(static: np.ndarray, run_static: np.ndarray, signs: np.ndarray, simulated: np.ndarray,
                         day: np.ndarray, n_days: int, fraction: float) -> tuple[np.ndarray, np.ndarray]:
    """Per effect, how far the coupled runs' own static reference misses the exact static peak: the
    largest 1 − s·R_st,run / s·R_st over the simulated events whose exact static peak s·R_st is at
    least ``fraction`` of their day's largest (the events that set the daily maxima), and that
    event (−1: none).  A run reads its total and its static reference at the same instants — its
    time steps and, for moments, shears and reactions, both one-sided limits at every instant a
    wheel crosses a jump or kink of the line (``vbikit.lifetime.peaks.with_knot_limits``), where
    the exact static peak is reached — so a static peak it still misses leaves its total peak
    about as low: the daily maxima of the total, and the ADR, are then biased low.  What is left
    to miss: a deflection's peak between two steps (a smooth line: a relative (π f dt)²/2 or so),
    a wheel off the tabulated tracks, a braking vehicle's knot instants."""
    s_st, s_run = static * signs[None, :], run_static * signs[None, :]
    n = static.shape[1]
    worst, event = np.zeros(n), np.full(n, -1, np.int64)
    for j in range(n):
        top = np.full(n_days, -np.inf)
        np.maximum.at(top, day, s_st[:, j])
        ok = simulated & np.isfinite(s_run[:, j]) & (s_st[:, j] > 0) & (s_st[:, j] >= fraction * top[day])
        if ok.any():
            short = np.where(ok, 1.0 - s_run[:, j] / np.where(ok, s_st[:, j], 1.0), -np.inf)
            k = int(np.argmax(short))
            worst[j], event[j] = max(float(short[k]), 0.0), k
    return worst, event


def strongly_negative(*shapes: float) -> bool:
    """True if any finite shape ξ is below ``XI_STRONGLY_NEGATIVE``."""
    return any(math.isfinite(x) and x < XI_STRONGLY_NEGATIVE for x in shapes)


def adr_words(adr: float, lower: float, upper: float, ci: float) -> str:
    """The ADR with its interval, and whether the data can tell it from 1."""
    if not math.isfinite(adr):
        return "ADR undefined (a characteristic value is missing or zero)"
    if not (math.isfinite(lower) and math.isfinite(upper)):
        return f"ADR {adr:.3f} (no interval: a fit's covariance is not available)"
    text = f"ADR {adr:.3f}, {ci:.0%} interval {lower:.3f} … {upper:.3f}"
    if lower <= 1.0 <= upper:
        return text + ": contains 1, the data cannot tell the ADR from 1 (simulate more days)"
    return text + (": above 1, dynamics raise the characteristic value" if lower > 1.0 else
                   ": below 1, the characteristic total is below the static")


#: a dynamic-to-static damage ratio above this is explained in words (``fatigue_verdict``): a few tens of
#: percent of dynamic amplification of the ranges cannot give it on one slope m = 3 … 5 alone ((1.15)^5 = 2.0)
LARGE_DAMAGE_RATIO = 2.0
#: fewest simulated days with a stress range from which the design life's largest range is estimated (the
#: Gumbel fit's minimum sample, ``vbikit.extremes.fit_block_maxima``)
MIN_DAYS_FOR_RANGE = 5


@dataclass(frozen=True)
class DesignLifeRange:
    """The design life's largest static stress range [Pa] estimated from the simulated days' largest ranges
    (module docstring): ``level`` the level the design life's largest stays below with the run's confidence (the
    Gumbel return level for T_life / (−ln ci) years), ``upper`` the upper bound of its interval, ``bound`` the
    number the limit rule compares for the total damage (``upper`` × the dynamic amplification of the largest
    range); NaN, with ``why``, when the days allow no estimate."""

    level: float
    upper: float
    bound: float
    why: str = ""


def design_life_range(daily_max: np.ndarray, days_per_year: float, design_life: float, ci: float,
                      amplification: float = 1.0) -> DesignLifeRange:
    """``DesignLifeRange`` from ``daily_max`` [Pa] (each simulated day's largest static stress range; days without
    one, ≤ 0, left out) for a ``design_life`` [years] of ``days_per_year`` daily blocks: the level the design
    life's largest range stays below with probability ``ci`` (module docstring: the return level for
    ``design_life`` / (−ln ``ci``) years) and the upper bound of its ``ci`` interval; ``amplification`` the
    simulated dynamics' (largest total range / largest static range, taken ≥ 1)."""
    from vbikit.extremes import fit_block_maxima, return_levels
    from vbikit.extremes.errors import ExtremesError

    days = np.asarray(daily_max, float)
    days = days[np.isfinite(days) & (days > 0.0)]
    factor = max(float(amplification), 1.0) if math.isfinite(amplification) else math.inf
    if not days.size:
        return DesignLifeRange(0.0, 0.0, 0.0, "no stress range in the simulated days")
    if days.size < MIN_DAYS_FOR_RANGE:
        return DesignLifeRange(math.nan, math.nan, math.nan, f"{counted(days.size, 'simulated day')} with a stress "
                                                             f"range, fewer than {MIN_DAYS_FOR_RANGE}")
    if np.ptp(days) <= 1e-12 * days.max():  # no spread: every day's largest is the same, so is the design life's
        top = float(days.max())
        return DesignLifeRange(top, top, top * factor)
    try:
        fit = fit_block_maxima(days, "gumbel", blocks_per_year=float(days_per_year))
        period = float(design_life) / -math.log(ci)  # F(x)^N = ci: the return period T_life / (−ln ci)
        level, _, upper = (float(v[0]) for v in return_levels(fit, [period], ci=ci))
    except ExtremesError as err:
        return DesignLifeRange(math.nan, math.nan, math.nan, f"the Gumbel fit of the daily ranges failed ({err})")
    if not math.isfinite(upper):
        return DesignLifeRange(level, upper, math.nan, "the Gumbel fit of the daily ranges has no interval")
    return DesignLifeRange(level, upper, upper * factor)


def design_life_range_words(estimate: DesignLifeRange, design_life: float, ci: float, limit: str) -> str:
    """Why the limit rule was not applied although the simulated period's ranges are all below ``limit`` (its name
    and value in words)."""
    if not math.isfinite(estimate.bound):
        return (f"every simulated stress range is below the fatigue limit {limit}, but the {design_life:g}-year design "
                f"life's largest range cannot be estimated ({estimate.why}): the limit rule is not applied, every "
                "range above the cut-off counts")
    return (f"every simulated stress range is below the fatigue limit {limit}, but the {design_life:g}-year design "
            f"life's largest stays below {estimate.level / 1e6:.2f} MPa only with {ci:.0%} confidence (Gumbel fit of "
            f"the daily largest ranges; the upper {ci:.0%} bound of that level {estimate.upper / 1e6:.2f} MPa, "
            f"{estimate.bound / 1e6:.2f} MPa with the simulated dynamics): the limit rule does not hold over the "
            "design life, every range above the cut-off counts")


def fatigue_verdict(damage: float, se: float, damage_static: float, years: float, design_life: float,
                    damage_so_far: float, below_limit: bool, limit_pa: float, ci: float,
                    limit_name: str = "Δσ_D", life_range: DesignLifeRange | None = None, limit_note: str = "") -> dict:
    """The verdict of one detail (module docstring): numbers and words; ``limit_pa`` the curve's
    constant-amplitude fatigue limit (EN Δσ_D, AASHTO (ΔF)_TH), named ``limit_name``; ``life_range`` the design
    life's largest range (``design_life_range``) when the limit rule applied; ``limit_note`` why it did not although
    the simulated ranges are below the limit (``design_life_range_words``), added to the words."""
    from scipy import stats

    z = float(stats.norm.ppf(0.5 + ci / 2))
    per_year = damage / years
    life = damage_so_far + per_year * design_life
    se_ok = math.isfinite(se)
    upper = damage_so_far + (damage + z * se) / years * design_life if se_ok else math.nan
    remaining = (1.0 - damage_so_far) / per_year if per_year > 0 else math.inf
    limit = f"{limit_name} = {limit_pa / 1e6:.2f} MPa"
    if below_limit:
        estimate = (f"; the {design_life:g}-year design life's largest stays below {life_range.level / 1e6:.2f} MPa "
                    f"with {ci:.0%} confidence (upper bound with the simulated dynamics {life_range.bound / 1e6:.2f} MPa)"
                    if life_range is not None and math.isfinite(life_range.bound) else "")
        words = (f"no fatigue damage: every stress range (static, and of every simulated event) is below the "
                 f"fatigue limit {limit}{estimate}; life unlimited")
    elif life >= 1.0:
        words = (f"NOT OK: damage over the {design_life:g}-year design life {life:.3g} ≥ 1; the Miner sum reaches 1 "
                 f"in {remaining:.4g} years")
    elif se_ok and upper >= 1.0:
        words = (f"UNDECIDED: damage over the {design_life:g}-year design life {life:.3g} < 1, but its upper "
                 f"{ci:.0%} bound {upper:.3g} ≥ 1 (raise fatigue.dynamic_sample or simulate more days)")
    else:
        bound = f" (upper {ci:.0%} bound {upper:.3g})" if se_ok else " (no standard error: dynamic sample too small)"
        words = (f"OK: damage over the {design_life:g}-year design life {life:.3g}{bound} < 1; remaining life "
                 f"{remaining:.4g} years")
    if limit_note and not below_limit:
        words += f" ({limit_note})"
    if damage_static > 0:
        ratio = damage / damage_static
        ratio_se = se / damage_static if se_ok else math.nan
        ratio_words = (f"dynamic / static damage {ratio:.3f} ± {ratio_se:.2g} (standard error)" if se_ok else
                       f"dynamic / static damage {ratio:.3f} (no standard error)")
        if ratio > LARGE_DAMAGE_RATIO:
            ratio_words += (f"; far above the amplification of the ranges themselves: the damage grows as the range to "
                            f"the power m = 3 … 5 of the S-N curve, and ranges below the fatigue limit {limit} and the "
                            "cut-off do little or no damage statically, so a small dynamic increase that lifts them onto "
                            "the curve multiplies their damage (the many lighter trucks' ranges near the limit)")
    else:
        ratio, ratio_se = math.nan, math.nan
        ratio_words = (f"static damage 0 (every static stress range is below the fatigue limit {limit}): the "
                       "dynamic / static damage ratio is undefined")
        ratio_words += ("; the total loading's ranges do not all stay below the limit (a simulated dynamic range, or "
                        "the design life's largest with the dynamics: see the verdict), so its ranges below the limit "
                        "count too (no damage only when every range is below the limit), the static-sized ones "
                        "included, on the S-N curve below the limit down to its cut-off where it has one"
                        if damage > 0 else "; the total damage is 0 too")
    return {"damage_design_life": life, "damage_design_life_upper": upper, "remaining_life": remaining,
            "ratio": ratio, "ratio_se": ratio_se, "verdict": words, "ratio_words": ratio_words}


def amplification_words(heavy_max: float, all_max: float, given: float, used: float, check_fraction: float) -> str:
    """The screening bound check in words: what each quantity is and what the run did."""
    what = (f"dynamic increment (IM) R_dyn/R_st − 1 of single events: largest among the simulated heavy events "
            f"(static peak ≥ {check_fraction:.0%} of their day's largest) {heavy_max:.3f}, among all simulated events "
            f"{all_max:.3f}")
    if not math.isfinite(heavy_max):
        return what + f"; screening bound A = {used:.3f}"
    if used > given:
        held = "held" if heavy_max <= used else "still did not hold: the total daily maxima may miss an event"
        return (what + f". It exceeded the screening bound A = {given:.3f} given, so the run raised A to {used:.3f} "
                f"and screened again; the bound then {held}")
    return (what + f"; both within the screening bound A = {used:.3f}: the daily maxima of the total effect are "
            "exact" if all_max <= used else
            what + f"; the heavy events are within the screening bound A = {used:.3f}, so the daily maxima of the "
            "total effect are exact (lighter events amplify more but stay far below any daily maximum)")
