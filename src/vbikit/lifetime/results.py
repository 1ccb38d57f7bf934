"""Extremes and fatigue of a lifetime run → the ``lifetime.nc`` dataset and the text report.

Extremes (``vbikit.extremes``, scipy.stats maximum likelihood): for every load effect the block
maxima (days; weeks = maxima of 7 consecutive days) of the static effect (every event) and of
the total effect (the simulated events: exact block maxima by the screening rule) in the
effect's governing direction s; a GEV or Gumbel fit of the chosen block with n blocks a year,
return levels x_T = F⁻¹(1 − 1/(n T)) with delta-method confidence intervals; the characteristic
value is the return level of ``characteristic_period``; ADR = characteristic total /
characteristic static.  Peaks over threshold: a GPD fit to the events' static peaks above the
threshold u = their (1 − 2·n_days/n_events) quantile (about two exceedances a day), λ the
exceedances a year; return levels x_T = u + σ/ξ ((λT)^ξ − 1); the same for the simulated events'
total peaks above the level the screening makes complete.  Beside them the accuracy of every
result (``vbikit.lifetime.accuracy``): the BM/POT and shape flags, the ADR's interval, the
governing events and their half-step re-run, the fatigue verdict.

Fatigue (``vbikit.fatigue``): the static damage of the whole period counted as one history —
the days' closed cycles plus the cycles closed when the days' residuals are joined in order,
plus the last residual's half cycles (exact, ``join`` / ``finish``) — and the dynamic part by
the difference estimator over the random sample S of n events out of N:
D_total = D_static + (N / n) Σ_{e∈S} (D_dyn,e − D_st,e), each event counted alone, with the
standard error N·sd(D_dyn,e − D_st,e)/√n (finite-population correction omitted: conservative).
"""
from __future__ import annotations

import dataclasses
import json
import math
from typing import Any

import numpy as np

from vbikit._files import shared_spec
from vbikit.analysis.population_start import start_attrs
from vbikit.lifetime.screening import CHECK_FRACTION
from vbikit.solve.run_in import START_OUTPUTS

#: the IM statistics stored with the ends of their 95 % confidence intervals (``NAME_ci_lower``, ``NAME_ci_upper``)
IM_WITH_INTERVALS = ("im_mean", "im_q95", "im_mean_loaded", "im_q95_loaded")


def _blocks(values: np.ndarray, size: int) -> np.ndarray:
    n = values.shape[0] // size
    return values[: n * size].reshape(n, size, *values.shape[1:]).max(axis=1)


def _fit(maxima: np.ndarray, distribution: str, per_year: float, periods, ci: float):
    from vbikit.extremes import fit_block_maxima, return_levels

    fit = fit_block_maxima(maxima, distribution, per_year)
    level, lo, hi = return_levels(fit, periods, ci)
    return fit, level, lo, hi


def _fit_or_why(maxima: np.ndarray, distribution: str, per_year: float, periods, ci: float, block: str,
                units: str):
    """``_fit``, or, when the maxima cannot be fitted (all equal, too few finite: ``ExtremesError``),
    None and NaN levels with the reason in words (the run's other results stand: a late fit failure
    must not discard the finished simulations)."""
    from vbikit.extremes import ExtremesError

    try:
        return (*_fit(maxima, distribution, per_year, periods, ci), "")
    except ExtremesError as err:
        nan = np.full(len(periods), np.nan)
        finite = maxima[np.isfinite(maxima)]
        what = "daily" if block == "day" else "weekly"
        if finite.size and finite.min() == finite.max():
            why = (f"not estimable: all {finite.size} {what} maxima are equal ({finite[0]:.6g} {units}, e.g. the "
                   f"same vehicle alone on the bridge every {block}), so a {distribution} fit has no scatter to "
                   "extrapolate from; the observed maximum stands, not a return level — use traffic with varied "
                   "vehicles")
        else:
            why = f"not estimable: the {distribution} fit of {finite.size} {what} maxima failed ({err})"
        return None, nan, nan.copy(), nan.copy(), why


def _static_threshold(values: np.ndarray, n_days: int) -> float:
    """The POT threshold of the events' static peaks: their (1 − 2·n_days/n_events) quantile."""
    n = values.size
    if n < 20:
        return math.nan
    return float(np.quantile(values, max(0.0, 1.0 - 2.0 * n_days / n)))


def im_sample_counts(im_sample: np.ndarray, small_sample: np.ndarray) -> dict[str, list[int]]:
    """Per load effect (columns of the random sample's IMs ``im_sample`` and of its small static references
    ``small_sample``): ``n_im_sample``, the sampled events with a finite IM (the sample of im_mean, im_std,
    im_q95; all lanes and vehicles), and ``n_small_static_sample``, those of them whose IM rests on a small
    static reference — an event without an IM (no usable static reference: a static peak of 0) is counted in
    neither, as the traffic stream's ``n_small_static_events`` (before 2026-12-06 it was counted as a small
    static reference too: left out of the IM statistics and, in the report, an IM "resting on" one)."""
    finite = np.isfinite(im_sample)
    small = np.asarray(small_sample, bool) & finite
    return {"n_im_sample": [int(k) for k in finite.sum(axis=0)],
            "n_small_static_sample": [int(k) for k in small.sum(axis=0)]}


def build_dataset(prep, static, dyn: dict, rounds: list, bound: float, timing: dict):
    """The lifetime dataset (module docstring)."""
    import xarray as xr

    from vbikit._version import __version__
    from vbikit.analysis.codes import CODES, code_allowances
    from vbikit.extremes import level_ratio
    from vbikit.extremes.paired import LevelRatio
    from vbikit.lifetime import accuracy as acc

    spec = prep.spec
    setup = prep.setup
    lines = setup.lines
    names = [ln.name for ln in lines]
    signs = np.array([ln.sign for ln in lines])
    units = [ln.units for ln in lines]
    n_days = prep.n_days
    periods = np.array(sorted(spec.return_periods), float)
    day = static["ev_day"].values
    st = static["ev_static"].values
    simulated = dyn["simulated"]
    gid = dyn["gid"]
    n_ev = gid.size
    total = np.full(st.shape, np.nan)
    run_static = np.full(st.shape, np.nan)
    for k in np.flatnonzero(simulated):
        r = dyn["results"][int(gid[k])]
        total[k] = r["dyn_peak"]
        run_static[k] = r["run_static_peak"]
    # block maxima in the governing direction (positive), then back to signed values
    s_st = st * signs
    s_tot = np.where(simulated[:, None], total * signs, -np.inf)
    day_static = np.full((n_days, len(lines)), -np.inf)
    day_total = np.full((n_days, len(lines)), -np.inf)
    for j in range(len(lines)):
        np.maximum.at(day_static[:, j], day, s_st[:, j])
        np.maximum.at(day_total[:, j], day, s_tot[:, j])
    per_year = spec.days_per_year / (7 if spec.block == "week" else 1)
    blk = 7 if spec.block == "week" else 1
    fit_static_blocks = _blocks(day_static, blk)
    fit_total_blocks = _blocks(day_total, blk)
    shape = (len(lines), periods.size)
    rl = {k: np.full(shape, np.nan) for k in ("static", "static_lower", "static_upper", "total", "total_lower",
                                              "total_upper", "pot_static", "pot_static_lower", "pot_static_upper",
                                              "pot_total", "pot_total_lower", "pot_total_upper")}
    fits = {k: np.full(len(lines), np.nan) for k in ("static_location", "static_scale", "static_shape",
                                                     "total_location", "total_scale", "total_shape", "pot_threshold",
                                                     "pot_static_shape", "pot_total_threshold", "pot_total_shape",
                                                     "pot_static_exceedances", "pot_total_exceedances")}
    bm_fits: dict[tuple[str, int], Any] = {}
    bm_why: dict[str, list[str]] = {"static": [], "total": []}  # by load effect: why the fit is missing ("" if none)
    pot_why: dict[str, list[str]] = {"static": [], "total": []}
    years = n_days / spec.days_per_year
    complete = acc.completeness_level  # every total above this level was simulated
    for j in range(len(lines)):
        for which, data in (("static", fit_static_blocks[:, j]), ("total", fit_total_blocks[:, j])):
            fit, level, lo, hi, why = _fit_or_why(data, spec.distribution, per_year, periods, spec.ci, spec.block,
                                                  units[j])
            bm_fits[which, j] = fit
            bm_why[which].append(why)
            rl[which][j], rl[f"{which}_lower"][j], rl[f"{which}_upper"][j] = level, lo, hi
            if fit is not None:
                fits[f"{which}_location"][j], fits[f"{which}_scale"][j], fits[f"{which}_shape"][j] = \
                    fit.location, fit.scale, fit.shape
        u_static = _static_threshold(s_st[:, j], n_days)
        s_sim = s_tot[simulated, j]
        c = complete(s_st[:, j], simulated, bound)
        u_total = max(c, u_static) if np.isfinite(u_static) else math.nan
        for which, values, u in (("static", s_st[:, j], u_static), ("total", s_sim, u_total)):
            pot = acc.pot_levels(values, u, values.size / years, periods, spec.ci)
            if which == "total" and math.isnan(pot.shape):  # the static fit is made first
                pot = dataclasses.replace(pot, why=acc.total_pot_why(
                    pot.why, c, u_static, not math.isnan(fits["pot_static_shape"][j]), bound,
                    float(spec.amplification), bool(spec.fatigue.details)))
            rl[f"pot_{which}"][j], rl[f"pot_{which}_lower"][j], rl[f"pot_{which}_upper"][j] = \
                pot.level, pot.lower, pot.upper
            fits["pot_threshold" if which == "static" else "pot_total_threshold"][j] = u
            fits[f"pot_{which}_shape"][j] = pot.shape
            fits[f"pot_{which}_exceedances"][j] = pot.n_exceedances
            pot_why[which].append(pot.why)
    k_char = int(np.flatnonzero(periods == spec.characteristic_period)[0])
    char_static = rl["static"][:, k_char] * signs
    char_total = rl["total"][:, k_char] * signs
    adr = char_total / char_static
    ratios = [level_ratio(bm_fits["total", j], bm_fits["static", j], spec.characteristic_period, spec.ci)
              if bm_fits["total", j] is not None and bm_fits["static", j] is not None
              else LevelRatio(math.nan, math.nan, math.nan, math.nan, math.nan, spec.ci)  # a fit is missing
              for j in range(len(lines))]
    disagree = {w: acc.methods_disagree(rl[w], rl[f"{w}_lower"], rl[f"{w}_upper"], rl[f"pot_{w}"],
                                        rl[f"pot_{w}_lower"], rl[f"pot_{w}_upper"]) for w in ("static", "total")}
    steep = {w: np.array([acc.strongly_negative(fits[f"{w}_shape"][j], fits[f"pot_{w}_shape"][j])
                          for j in range(len(lines))]) for w in ("static", "total")}
    # per-event IM statistics on the random sample (unbiased), and on every simulated event
    sample = dyn["sample"]
    im_all = total / st - 1.0
    im_sample = im_all[sample] if sample.size else np.full((0, len(lines)), np.nan)

    def stat(a, f):
        a = a[np.isfinite(a)]
        return float(f(a)) if a.size else math.nan

    # a sampled event whose static peak is below SMALL_STATIC_FRACTION of the largest of all events rests on a
    # small static reference (a light vehicle, a far lane): counted, and left out of the "loaded" statistics
    from vbikit.analysis.checks import small_static_mask

    small_sample = small_static_mask(st, axis=0)[sample] if sample.size else np.zeros((0, len(lines)), bool)
    im_loaded = np.where(small_sample, np.nan, im_sample)
    im = {
        "im_std": [stat(im_sample[:, j], np.std) for j in range(len(lines))],
        "im_max": [stat(im_all[simulated, j], np.max) for j in range(len(lines))],
        **im_sample_counts(im_sample, small_sample),
    }
    # the means and 95 % quantiles of the finite values, with their 95 % confidence intervals: how well the
    # random sample fixes them (``sample_intervals``: the same estimates as numpy's mean and quantile)
    from vbikit.analysis.sample_intervals import mean_interval, quantile_interval

    for name in IM_WITH_INTERVALS:
        values = im_loaded if name.endswith("_loaded") else im_sample
        interval = mean_interval if name.startswith("im_mean") else (lambda a: quantile_interval(a, 0.95))
        found = [interval(values[:, j]) for j in range(len(lines))]
        im[name] = [c.estimate for c in found]
        im[f"{name}_ci_lower"] = [c.lower for c in found]
        im[f"{name}_ci_upper"] = [c.upper for c in found]
    im_gov = []
    for j in range(len(lines)):
        k = int(np.argmax(s_st[:, j]))
        im_gov.append(float(im_all[k, j]))
    bridge = setup.bridge
    f1 = float(bridge.frequencies_hz[0])
    codes = list(CODES)
    allow = np.full((len(lines), len(codes)), np.nan)
    for j, ln in enumerate(lines):
        loaded = float(getattr(ln.effect, "loaded_length", bridge.span) if ln.effect is not None else
                       bridge.span_lengths[bridge.span_index(float(bridge.span_coordinate(ln.x, ln.y)))])
        vals = code_allowances(loaded, f1, None)
        for c, code in enumerate(codes):
            allow[j, c] = vals.get(code, math.nan)
    # the largest static effect the traffic can produce (bootstrap traffic; accuracy.static_upper_bound)
    upper = acc.static_upper_bound(prep.model, setup, signs)
    static_bound = np.full(len(lines), np.nan) if upper is None else upper[0]
    above = [bool(s * c > b) for s, c, b in zip(signs, char_static, static_bound)]  # NaN compares False
    # ---------------------------------------------------------------- fatigue
    fat = fatigue_results(prep, static, dyn)
    ev_attrs = lambda u, d: {"units": u, "long_name": d}  # noqa: E731
    variables: dict[str, Any] = {
        "characteristic_static": ("load_effect", char_static, ev_attrs("", f"static load effect of the {spec.characteristic_period:g}-year return period")),
        "characteristic_total": ("load_effect", char_total, ev_attrs("", f"total (static + dynamic) load effect of the {spec.characteristic_period:g}-year return period")),
        **{f"characteristic_{w}_not_estimable": ("load_effect", np.array(bm_why[w], dtype=object), ev_attrs("", f"why the {w} block maxima could not be fitted (all equal, too few), in words; empty where they were: where not, characteristic_{w}, its block-maximum return levels and the ADR are NaN")) for w in ("static", "total")},
        "static_upper_bound": ("load_effect", static_bound * signs, ev_attrs("", "largest static effect any event of the traffic model can produce: the sum over lanes of k times the lane's largest single-vehicle static peak, k the most vehicles of a lane on the deck at once (bootstrap traffic: vbikit.lifetime.accuracy.static_upper_bound); NaN where the model has no bound (fitted traffic)")),
        "characteristic_static_above_bound": ("load_effect", np.array(above, np.int8), ev_attrs("1", "1 if the characteristic static value exceeds static_upper_bound: the fitted tail extrapolates past what the traffic model can produce")),
        "assessment_dynamic_ratio": ("load_effect", adr, ev_attrs("1", "ADR = characteristic total / characteristic static")),
        "return_level_static": (("load_effect", "return_period"), rl["static"] * signs[:, None], ev_attrs("", "static return level")),
        "return_level_static_lower": (("load_effect", "return_period"), rl["static_lower"] * signs[:, None], ev_attrs("", f"lower {spec.ci:.0%} confidence bound (delta method; of the magnitude in the effect's governing direction: for a downward effect the bound nearer zero)")),
        "return_level_static_upper": (("load_effect", "return_period"), rl["static_upper"] * signs[:, None], ev_attrs("", f"upper {spec.ci:.0%} confidence bound (delta method; of the magnitude in the effect's governing direction: for a downward effect the bound farther from zero)")),
        "return_level_total": (("load_effect", "return_period"), rl["total"] * signs[:, None], ev_attrs("", "total return level")),
        "return_level_total_lower": (("load_effect", "return_period"), rl["total_lower"] * signs[:, None], ev_attrs("", f"lower {spec.ci:.0%} confidence bound (delta method; of the magnitude in the effect's governing direction: for a downward effect the bound nearer zero)")),
        "return_level_total_upper": (("load_effect", "return_period"), rl["total_upper"] * signs[:, None], ev_attrs("", f"upper {spec.ci:.0%} confidence bound (delta method; of the magnitude in the effect's governing direction: for a downward effect the bound farther from zero)")),
        **_pot_variables(rl, signs, spec.ci, disagree, steep, pot_why),
        **{f"pot_{w}_not_estimable": ("load_effect", np.array([t if np.isnan(rl[f"pot_{w}"][j, 0]) else ""
                                                                for j, t in enumerate(pot_why[w])], dtype=object),
                                      ev_attrs("", f"why the {w} peaks over threshold could not be fitted, in words; empty "
                                                   f"where they were (then return_level_pot_{w} holds the levels)"))
           for w in ("static", "total")},
        "assessment_dynamic_ratio_lower": ("load_effect", np.array([r.lower for r in ratios]), ev_attrs("1", f"lower {spec.ci:.0%} confidence bound of the ADR (delta method, covariance of the two fits from the sandwich of the same blocks; vbikit.extremes.level_ratio)")),
        "assessment_dynamic_ratio_upper": ("load_effect", np.array([r.upper for r in ratios]), ev_attrs("1", f"upper {spec.ci:.0%} confidence bound of the ADR")),
        "assessment_dynamic_ratio_se": ("load_effect", np.array([r.standard_error for r in ratios]), ev_attrs("1", "standard error of the ADR (delta method)")),
        "adr_indistinguishable_from_one": ("load_effect", np.array([int(r.lower <= 1.0 <= r.upper) for r in ratios], np.int8), ev_attrs("1", "1 if the ADR's confidence interval contains 1: the data cannot tell the ADR from 1")),
        "characteristic_correlation": ("load_effect", np.array([r.correlation for r in ratios]), ev_attrs("1", "correlation of the characteristic total and static estimators (same blocks)")),
        "adr_by_period": (("load_effect", "return_period"), rl["total"] / rl["static"], ev_attrs("1", "total / static return level")),
        "daily_max_static": (("day", "load_effect"), day_static * signs, ev_attrs("", "daily maximum of the static effect")),
        "daily_max_total": (("day", "load_effect"), day_total * signs, ev_attrs("", "daily maximum of the total effect")),
        "weekly_max_static": (("week", "load_effect"), _blocks(day_static, 7) * signs if n_days >= 7 else np.zeros((0, len(lines))), ev_attrs("", "weekly maximum of the static effect")),
        "weekly_max_total": (("week", "load_effect"), _blocks(day_total, 7) * signs if n_days >= 7 else np.zeros((0, len(lines))), ev_attrs("", "weekly maximum of the total effect")),
        **{f"fit_{k}": ("load_effect", v,
                        ev_attrs("see load_effect_units",
                                 f"{k.replace('_', ' ')} of the fit to s*R (governing direction)"))
           for k, v in fits.items()},
        "effect_sign": ("load_effect", signs, ev_attrs("1", "governing direction s: peaks are the largest s*R")),
        "effect_direction": ("load_effect", np.array([ln.direction for ln in lines], dtype=object),
                             {"long_name": "how s was chosen: auto (the sign of the influence line's largest "
                                           "ordinate) or given (positive, negative)"}),
        "opposite_direction_area": ("load_effect", np.array([ln.opposite_area for ln in lines]),
                                    ev_attrs("1", "area of the influence line's part of sign -s over that of its "
                                                  "part of sign s (0: one-signed); above 1 long or several vehicles "
                                                  "load the effect more in the direction not reported")),
        **_opposite_extreme(static["ev_static_opposite"].values if "ev_static_opposite" in static else None, signs),
        "im_mean": ("load_effect", np.array(im["im_mean"]), ev_attrs("1", "mean per-event impact factor R_dyn/R_st - 1 over the random sample's events with one (n_im_sample; every lane and vehicle: not per lane, nor the governing event's)")),
        "im_std": ("load_effect", np.array(im["im_std"]), ev_attrs("1", "standard deviation of the per-event impact factor over the same n_im_sample events")),
        "im_q95": ("load_effect", np.array(im["im_q95"]), ev_attrs("1", "95 % quantile (95th percentile) of the per-event impact factor over the same n_im_sample events")),
        "n_im_sample": ("load_effect", np.array(im["n_im_sample"], np.int64), ev_attrs("1", "events of the random sample with a finite impact factor for the effect: the sample of im_mean, im_std, im_q95 and their intervals (the others, without a usable static reference, are left out)")),
        "im_max": ("load_effect", np.array(im["im_max"]), ev_attrs("1", "largest impact factor of any simulated event")),
        "im_mean_loaded": ("load_effect", np.array(im["im_mean_loaded"]), ev_attrs("1", "mean impact factor of the sampled events whose static peak is at least SMALL_STATIC_FRACTION (20 %) of the largest static peak (the events that load the effect)")),
        "im_q95_loaded": ("load_effect", np.array(im["im_q95_loaded"]), ev_attrs("1", "95 % quantile of the impact factor of those events")),
        **{f"{name}_ci_{end}": ("load_effect", np.array(im[f"{name}_ci_{end}"]),
                                ev_attrs("1", f"{end} end of the 95 % confidence interval of {name} over the random "
                                              "sample (vbikit.analysis.sample_intervals; NaN: not bounded)"))
           for name in IM_WITH_INTERVALS for end in ("lower", "upper")},
        "n_small_static_sample": ("load_effect", np.array(im["n_small_static_sample"], np.int64), ev_attrs("1", "sampled events with an impact factor whose static peak is below 20 % of the largest: their impact factors rest on a small static reference, not design values (one without an impact factor is counted in neither this nor n_im_sample)")),
        "im_governing_static_event": ("load_effect", np.array(im_gov), ev_attrs("1", "impact factor of the event with the largest static effect")),
        "code_allowance": (("load_effect", "code"), allow, ev_attrs("1", "design-code dynamic allowance (vbikit.analysis.codes)")),
        "event_day": ("event", day, ev_attrs("1", "day of the event")),
        "event_start": ("event", static["ev_start"].values, ev_attrs("s", "first vehicle's record time")),
        "event_n_vehicles": ("event", static["ev_n_vehicles"].values, ev_attrs("1", "vehicles in the event")),
        "event_gross_weight": ("event", static["ev_gross_weight"].values, ev_attrs("N", "sum of the event's gross vehicle weights")),
        "event_static": (("event", "load_effect"), st, ev_attrs("", "static peak (convolution)")),
        "event_total": (("event", "load_effect"), total, ev_attrs("", "dynamic (total) peak; NaN if not simulated")),
        "event_run_static": (("event", "load_effect"), run_static, ev_attrs("", "static peak of the coupled run's static reference (at its time steps and, for moments, shears and reactions, at the instants a wheel crosses a jump or kink of the line); NaN if not simulated")),
        "event_simulated": ("event", simulated.astype(np.int8), ev_attrs("1", "1 if simulated dynamically")),
        "event_run_in": ("event", _event_run_in(dyn, simulated, gid), ev_attrs("m", "road the simulated event's trucks drove alone, from rest, before its coupled run (crossing.run_in: the population's, 100 m less the approach, longer where its trucks needed more to settle (run_in_adaptive), or the part of it the road holds); NaN if not simulated or moving forces")),
        **{f"event_{name}": ("event", _event_result(dyn, simulated, gid, name),
                             ev_attrs(unit, f"{meaning}; NaN if the event was not simulated"))
           for name, (unit, meaning) in START_OUTPUTS.items()},
        "event_in_sample": ("event", np.isin(np.arange(n_ev), dyn["sample"]).astype(np.int8), ev_attrs("1", "1 if in the random sample (fatigue, IM statistics)")),
        "day_trucks": ("day", static["day_trucks"].values, ev_attrs("1", "trucks of the day")),
        **fat["variables"],
        **_governing_variables(dyn, st, total, run_static, day, static["ev_start"].values),
        **_shortfall_variables(st, run_static, signs, simulated, day, n_days),
    }
    for name in ("characteristic_static", "characteristic_total", "static_upper_bound", "return_level_static", "return_level_static_lower",
                 "return_level_static_upper", "return_level_total", "return_level_total_lower",
                 "return_level_total_upper", "return_level_pot_static", "return_level_pot_static_lower",
                 "return_level_pot_static_upper", "return_level_pot_total", "return_level_pot_total_lower",
                 "return_level_pot_total_upper", "governing_static_value", "governing_total_value",
                 "governing_total_half_step", "daily_max_static", "daily_max_total",
                 "weekly_max_static", "weekly_max_total", "event_static", "event_total", "event_run_static"):
        variables[name][2]["units"] = "see load_effect_units"
    coords = {"load_effect": np.array(names, dtype=object), "return_period": ("return_period", periods, {"units": "year"}),
              "day": np.arange(n_days), "week": np.arange(n_days // 7), "event": np.arange(n_ev),
              "code": np.array(codes, dtype=object),
              "load_effect_units": ("load_effect", np.array(units, dtype=object)),
              "load_effect_kind": ("load_effect", np.array([ln.kind for ln in lines], dtype=object)),
              **fat["coords"]}
    for k in fits:
        if k.endswith(("shape", "exceedances")):
            variables[f"fit_{k}"][2]["units"] = "1"
    if fat["variables"]:
        variables.update(_verdict_variables(prep, fat["variables"], fat["ranges"]))
    coords["governs"] = np.array(["static", "total"], dtype=object)
    ds = xr.Dataset(variables, coords=coords)
    # per-effect units: one parseable unit per variable (CF), else the coordinate of each effect's (member_units)
    from vbikit.outputs import member_units

    for name, v in ds.data_vars.items():
        if v.attrs.get("units") == "see load_effect_units":
            del v.attrs["units"]
            v.attrs.update(member_units(units, "load_effect", "load_effect_units"))
    n_sim = int(simulated.sum())
    ds.attrs = {
        "title": spec.name or "vbikit lifetime",
        "vbikit_version": __version__,
        "Conventions": "CF-1.8",
        # the lifetime file as validated, an absolute path in it (traffic.records, base, a modes or profile
        # file) by its file name only: a shared dataset does not carry the machine's folders
        "lifetime": json.dumps(shared_spec(spec.model_dump(mode="json")), separators=(",", ":")),
        "records": prep.info.get("records", ""),
        "n_days": n_days,
        "days_per_year": spec.days_per_year,
        "n_trucks": int(static["day_trucks"].values.sum()),
        "n_events": int(n_ev),
        "n_dynamic_events": n_sim,
        "fraction_dynamic": n_sim / max(n_ev, 1),
        "n_sample_events": int(dyn["sample"].size),
        **_unconverged_attrs(dyn["results"]),
        "amplification_bound_given": float(spec.amplification),
        "amplification_bound_used": float(bound),
        "amplification_max_observed": float(np.nanmax(np.where(simulated[:, None], total / st - 1, np.nan))) if n_sim else math.nan,
        "amplification_max_heavy": _heavy_amplification(st, total, signs, day, n_days, simulated),
        "amplification_check_fraction": CHECK_FRACTION,
        "xi_strongly_negative": acc.XI_STRONGLY_NEGATIVE,
        "half_step_tolerance": acc.HALF_STEP_TOLERANCE,
        "ci": float(spec.ci),
        "design_life": float(spec.fatigue.design_life),
        "screening_rounds": json.dumps(rounds),
        "block": spec.block,
        "distribution": spec.distribution,
        "characteristic_period": float(spec.characteristic_period),
        # every characteristic value that could not be estimated, in words ("" when all were: _fit_or_why)
        "not_estimable": " ".join(f"{n} {w}: {t}." for w in ("static", "total") for n, t in zip(names, bm_why[w]) if t),
        # the characteristic static values above the largest static effect the traffic can produce, in words
        "above_static_bound": " ".join(
            f"{n} static: the characteristic value {c:.6g} {u} exceeds {b * s:.6g} {u}, the largest the traffic model "
            "can produce." for n, u, s, c, b, a_ in zip(names, units, signs, char_static, static_bound, above) if a_),
        "static_bound_vehicles_per_lane": json.dumps([] if upper is None else upper[1].tolist()),
        "first_frequency_hz": f1,
        # where the dynamic events start their trucks (crossing.approach before the bridge, settled by the run-in each
        # got: vbikit.analysis.population_start), and how the trucks are modelled: sprung trucks started at rest after
        # a short approach enter calmer than settled ones (start_from_rest)
        **start_attrs(prep.setup.context.template.crossing.approach, prep.setup.context.template.crossing.run_in,
                      _runs_in(dyn["results"]), prep.setup.context.least_approach,
                      [float(r.get("start_transient_left", np.nan)) for r in dyn["results"].values()],
                      [float(r.get("start_settling_run_in", np.nan)) for r in dyn["results"].values()],
                      adaptive=prep.setup.context.lengthens),
        "vehicle_model": spec.vehicle_model,
        **{k: float(v) for k, v in timing.items()},
        "events_per_second_static": float(n_ev / max(timing.get("time_static_s", 0.0), 1e-9)),
    }
    return ds


def _event_run_in(dyn: dict, simulated: np.ndarray, gid: np.ndarray) -> np.ndarray:
    """Each event's run-in [m] (``_result_run_in`` of its dynamic run; NaN where not simulated)."""
    return _per_event(dyn, simulated, gid, _result_run_in)


def _event_result(dyn: dict, simulated: np.ndarray, gid: np.ndarray, name: str) -> np.ndarray:
    """Each event's ``name`` from its dynamic run (NaN where not simulated, or not stored)."""
    return _per_event(dyn, simulated, gid, lambda result: float(result.get(name, np.nan)))


def _per_event(dyn: dict, simulated: np.ndarray, gid: np.ndarray, read) -> np.ndarray:
    """``read`` of each simulated event's dynamic run (its result's dict), NaN for the others."""
    out = np.full(gid.size, np.nan)
    for k in np.flatnonzero(simulated):
        out[k] = read(dyn["results"][int(gid[k])])
    return out


def _runs_in(results: dict) -> np.ndarray:
    """The run-in [m] each simulated dynamic event got (``_result_run_in``)."""
    return np.array([_result_run_in(r) for r in results.values()], float)


def _result_run_in(result: dict) -> float:
    """The run-in [m] a dynamic run's trucks got (NaN: moving forces; 0 for a result written before run-ins
    were stored, which started its trucks at rest)."""
    return float(result.get("run_in", 0.0))


def _unconverged_attrs(results: dict) -> dict[str, Any]:
    """How many coupled runs had steps whose contact forces did not converge
    (``CrossingResult.unconverged_steps``), the most steps in one and its event's global id (-1: none)."""
    counts = {g: float(r.get("unconverged_steps", 0.0)) for g, r in results.items()}
    bad = {g: c for g, c in counts.items() if c > 0}
    worst = max(bad, key=bad.get) if bad else -1
    return {"n_unconverged_events": len(bad), "unconverged_steps_max": bad.get(worst, 0.0),
            "unconverged_event": int(worst)}


def _pot_variables(rl, signs, ci, disagree, steep, why) -> dict[str, Any]:
    """Peaks-over-threshold levels beside the block maxima, and the two flags (``accuracy``)."""
    from vbikit.lifetime.accuracy import XI_STRONGLY_NEGATIVE

    dims = ("load_effect", "return_period")
    out: dict[str, Any] = {}
    for w in ("static", "total"):
        src = ("the events' static peaks above the threshold" if w == "static" else
               "the simulated events' total peaks above the threshold, complete above it by the screening")
        because = "; ".join(f"{k}: {t}" for k, t in enumerate(why[w]) if t)  # by load effect, where NaN
        out[f"return_level_pot_{w}"] = (dims, rl[f"pot_{w}"] * signs[:, None], {
            "units": "", "long_name": f"{w} return level from peaks over threshold (GPD of {src})",
            "missing_because": because})
        for b in ("lower", "upper"):
            out[f"return_level_pot_{w}_{b}"] = (dims, rl[f"pot_{w}_{b}"] * signs[:, None], {
                "units": "", "long_name": f"{b} {ci:.0%} confidence bound of return_level_pot_{w} (delta method; of the "
                             "magnitude in the effect's governing direction)",
                "missing_because": because})
        out[f"methods_disagree_{w}"] = (dims, disagree[w].astype(np.int8), {
            "units": "1", "long_name": f"1 if the block-maximum and the peaks-over-threshold {w} levels disagree: "
                                       "either lies outside the other's confidence interval"})
        out[f"shape_strongly_negative_{w}"] = ("load_effect", steep[w].astype(np.int8), {
            "units": "1", "long_name": f"1 if a fitted shape of the {w} effect (GEV of the block maxima, GPD of the "
                                       f"exceedances) is below {XI_STRONGLY_NEGATIVE}: a bounded tail fitted from "
                                       "little data, long-period levels unreliable"})
    return out


def _opposite_extreme(opposite: np.ndarray | None, signs: np.ndarray) -> dict[str, Any]:
    """The run's largest static value of each effect in the direction it does not report (the largest
    −s·R over every event's exact static history, signed; NaN where the static pass did not keep it):
    against the reported direction's (the largest of ``daily_max_static``), the traffic's own answer to
    which direction governs."""
    other = np.full(signs.size, np.nan)
    if opposite is not None and opposite.shape[0]:
        other = -signs * np.max(-opposite * signs, axis=0)
    return {"static_largest_opposite": ("load_effect", other, {"units": "see load_effect_units", "long_name": (
        "the run's largest static value in the direction not reported (largest -s*R of any event's exact static "
        "history, signed; NaN: not kept); above the largest daily_max_static in magnitude that direction governs "
        "this traffic")})}


def _equivalent_range(curve, damage: float) -> float:
    """The constant stress range whose 2·10⁶ cycles do ``damage`` on ``curve`` (N(Δσ) = 2·10⁶ / D;
    0 for no damage); NaN where that range lies below the curve's cut-off (no range does so little)."""
    if damage <= 0:
        return 0.0
    try:
        return curve.stress_range_at(2e6 / damage)
    except Exception:  # below the curve's cut-off / threshold: no damage-equivalent range on it
        return math.nan


def _heavy_amplification(st, total, signs, day, n_days, simulated) -> float:
    """The largest amplification R_dyn/R_st − 1 among the simulated events the screening checks
    (static peak ≥ CHECK_FRACTION of their day's largest), of the effects they are heavy for."""
    from vbikit.lifetime.screening import heavy_amplifications

    amp = heavy_amplifications(total, st, signs, day, n_days, simulated, CHECK_FRACTION)
    amp = amp[np.isfinite(amp)]
    return float(amp.max()) if amp.size else math.nan


def _shortfall_variables(st, run_static, signs, simulated, day, n_days) -> dict[str, Any]:
    """How far the coupled runs' time steps miss the exact static peaks (``accuracy.run_static_shortfall``)."""
    from vbikit.lifetime.accuracy import run_static_shortfall

    worst, event = run_static_shortfall(st, run_static, signs, simulated, day, n_days, CHECK_FRACTION)
    return {
        "run_static_shortfall": ("load_effect", worst, {"units": "1", "long_name": (
            "largest 1 - R_st,run / R_st over the simulated events with a static peak of at least "
            f"{CHECK_FRACTION:g} of their day's largest: how far the coupled run's static reference (its time steps and "
            "the instants a wheel crosses a jump or kink of the line) misses the exact static peak (its total peak is "
            "about as low)")}),
        "run_static_shortfall_event": ("load_effect", event, {"units": "1", "long_name":
                                                              "event of run_static_shortfall (-1: none)"}),
    }


def _governing_variables(dyn, st, total, run_static, day, start) -> dict[str, Any]:
    """The governing events (``vbikit.lifetime.governing``) and their half-step re-run."""
    from vbikit.lifetime.governing import vehicles_words

    if "governing" not in dyn:
        return {}
    gov = dyn["governing"]
    n_lines = gov.shape[0]
    dims = ("load_effect", "governs")
    shape = gov.shape
    val_st, val_tot, half, change, words = (np.full(shape, np.nan), np.full(shape, np.nan), np.full(shape, np.nan),
                                            np.full(shape, np.nan), np.full(shape, "", dtype=object))
    for j in range(n_lines):
        for w in range(2):
            k = int(gov[j, w])
            if k < 0:
                continue
            g = int(dyn["gid"][k])
            val_st[j, w], val_tot[j, w] = st[k, j], total[k, j]
            if g in dyn["half_step"]:
                half[j, w] = dyn["half_step"][g]["dyn_peak"][j]
                if np.isfinite(total[k, j]) and total[k, j] != 0:
                    change[j, w] = half[j, w] / total[k, j] - 1.0
            words[j, w] = vehicles_words(dyn["vehicles"][g]) if g in dyn["vehicles"] else ""
    a = lambda u, d: {"units": u, "long_name": d}  # noqa: E731
    ok = np.where(gov >= 0, gov, 0)
    return {
        "governing_event": (dims, gov, a("1", "event index governing the static (largest static peak) and the total (largest simulated total peak) maximum; -1 if none")),
        "governing_day": (dims, np.where(gov >= 0, day[ok], -1), a("1", "day of the governing event")),
        "governing_time_of_day": (dims, np.where(gov >= 0, np.mod(start[ok], 86400.0), np.nan), a("s", "time of day of the governing event's first vehicle")),
        "governing_vehicles": (dims, words, a("", "the governing event's vehicles: axles, gross weight, lane, direction, speed, time of day")),
        "governing_static_value": (dims, val_st, a("", "static peak of the governing event (convolution)")),
        "governing_total_value": (dims, val_tot, a("", "total peak of the governing event (its run); NaN if not simulated")),
        "governing_total_half_step": (dims, half, a("", "total peak of the governing event simulated again at half the time step")),
        "governing_half_step_change": (dims, change, a("1", "relative change of the governing event's total peak at half the time step: R_half / R_run - 1")),
    }


def _verdict_variables(prep, fat_vars: dict, ranges: list) -> dict[str, Any]:
    """Per detail the fatigue verdict of ``vbikit.lifetime.accuracy.fatigue_verdict``."""
    from vbikit.lifetime.accuracy import fatigue_verdict

    spec = prep.spec
    years = prep.n_days / spec.days_per_year
    rows = []
    for j, det in enumerate(prep.details):
        rows.append(fatigue_verdict(
            float(fat_vars["fatigue_damage"][1][j]), float(fat_vars["fatigue_damage_se"][1][j]),
            float(fat_vars["fatigue_damage_static"][1][j]), years, spec.fatigue.design_life,
            spec.fatigue.damage_so_far, bool(fat_vars["below_fatigue_limit"][1][j]), float(det.sn().threshold),
            spec.ci, det.limit_name, ranges[j], str(fat_vars["fatigue_limit_note"][1][j])))
    a = lambda u, d: {"units": u, "long_name": d}  # noqa: E731
    life = spec.fatigue.design_life
    return {
        "fatigue_damage_design_life": ("detail", np.array([r["damage_design_life"] for r in rows]), a("1", f"Miner damage over the {life:g}-year design life (damage_so_far + damage a year x design life)")),
        "fatigue_damage_design_life_upper": ("detail", np.array([r["damage_design_life_upper"] for r in rows]), a("1", f"upper {spec.ci:.0%} bound of fatigue_damage_design_life (standard error of the dynamic sample)")),
        "dynamic_damage_ratio_se": ("detail", np.array([r["ratio_se"] for r in rows]), a("1", "standard error of dynamic_damage_ratio (fatigue_damage_se / fatigue_damage_static); NaN when the ratio is undefined")),
        "fatigue_verdict": ("detail", np.array([r["verdict"] for r in rows], dtype=object), a("", "the damage over the design life against 1, in words")),
        "dynamic_damage_ratio_note": ("detail", np.array([r["ratio_words"] for r in rows], dtype=object), a("", "the dynamic-to-static damage ratio in words (why it is undefined when it is)")),
    }


def fatigue_results(prep, static, dyn) -> dict[str, Any]:
    """Fatigue variables (module docstring)."""
    from vbikit.fatigue import RainflowState, finish, join, miner_damage, remaining_life
    from vbikit.lifetime.accuracy import design_life_range, design_life_range_words

    spec = prep.spec
    details = prep.details
    n_days = prep.n_days
    if not details:
        return {"variables": {}, "coords": {"detail": np.array([], dtype=object)}, "ranges": []}
    years = n_days / spec.days_per_year
    closed = static["day_damage_closed"].values
    alone = static["day_damage_alone"].values
    res_day, res_det, res_val = (static[k].values for k in ("res_day", "res_detail", "res_value"))
    h_day, h_det, h_bin, h_cnt = (static[k].values for k in ("hist_day", "hist_detail", "hist_bin", "hist_count"))
    day_top = static["day_max_range"].values
    sample = dyn["sample"]
    gid = dyn["gid"]
    n_ev = gid.size
    out = {k: np.full(len(details), np.nan) for k in ("static", "total", "se", "ratio", "per_year", "eq", "eq_life",
                                                       "life", "below_limit", "top", "life_top", "life_bound")}
    ranges, notes = [], []  # per detail: the design life's largest range (DesignLifeRange), why the rule did not apply
    empty = np.zeros(0)
    joined = []  # per detail: the cycles that close across days (the residuals joined) and the last residual
    for j in range(len(details)):
        state = RainflowState(empty, empty, empty)
        for d in range(n_days):
            r = res_val[(res_day == d) & (res_det == j)]
            state = join(state, RainflowState(empty, empty, r))
        joined.append(finish(state))
    # the histogram's bins reach the largest range of the period: no range is folded into the top bin
    max_bin = max([int(h_bin.max()) if h_bin.size else 0]
                  + [int(rng // det.bin) for det, cyc in zip(details, joined) for rng, _ in cyc]) + 1
    hist = np.zeros((len(details), max_bin))
    for j, det in enumerate(details):
        curve = det.sn()
        cyc = joined[j]
        d_join = miner_damage([c[0] for c in cyc], [c[1] for c in cyc], curve, whole_spectrum=False) if cyc else 0.0
        d_static = float(closed[:, j].sum() + d_join)
        sel = h_det == j
        np.add.at(hist[j], h_bin[sel], h_cnt[sel])
        for rng, cnt in cyc:
            hist[j, int(rng // det.bin)] += cnt
        static_top = max([float(day_top[:, j].max()) if day_top.size else 0.0] + [float(c[0]) for c in cyc])
        if sample.size:
            diff = np.array([dyn["results"][int(gid[k])]["damage_dynamic"][j] - dyn["results"][int(gid[k])]["damage_static"][j]
                             for k in sample])
            d_total = d_static + n_ev / sample.size * diff.sum()
            se = n_ev * (diff.std(ddof=1) if diff.size > 1 else math.nan) / math.sqrt(sample.size)
        else:
            d_total, se = d_static, math.nan
        d_total = max(d_total, 0.0)
        # the constant-amplitude limit rule (EN 1993-1-9 1.3.3.3, AASHTO (ΔF)_TH) on the design
        # life's loading (vbikit.lifetime.accuracy, "The fatigue limit over the design life"): no
        # damage when every range of the period is below the limit and so is the design life's
        # largest, estimated from the days' largest.  The static spectrum's largest range is exact
        # (each day's largest closed range and the cycles joined across days); the total loading's
        # is that and every dynamically simulated event's largest range (all simulated events, the
        # governing ones included)
        out["top"][j] = static_top
        dyn_top = max((float(r["max_range_dynamic"][j]) for r in dyn["results"].values()), default=0.0)
        simulated_below = static_top < curve.threshold and dyn_top < curve.threshold
        # each day's largest range counted alone: its largest closed cycle or its residual's max − min (the day's
        # largest peak and deepest valley are in its residual, closed only when the days are joined)
        mine = res_det == j
        res_hi, res_lo = np.full(n_days, -np.inf), np.full(n_days, np.inf)
        np.maximum.at(res_hi, res_day[mine], res_val[mine])
        np.minimum.at(res_lo, res_day[mine], res_val[mine])
        day_range = np.maximum(day_top[:, j] if day_top.size else np.zeros(n_days),
                               np.where(res_hi >= res_lo, res_hi - res_lo, 0.0))
        life = design_life_range(day_range, spec.days_per_year,
                                 spec.fatigue.design_life, spec.ci,
                                 dyn_top / static_top if static_top > 0 else 1.0)
        life_below = math.isfinite(life.bound) and life.bound < curve.threshold
        out["life_top"][j], out["life_bound"][j] = life.level, life.bound
        if static_top < curve.threshold and life.upper < curve.threshold:  # (NaN: False)
            d_static = 0.0
        if simulated_below and life_below:
            # no damage by the limit rule, whatever the sample: no sampling error either
            d_total, se = 0.0, 0.0
        out["below_limit"][j] = float(simulated_below and life_below)
        notes.append(design_life_range_words(life, spec.fatigue.design_life, spec.ci,
                                             f"{det.limit_name} = {curve.threshold / 1e6:.2f} MPa")
                     if simulated_below and not life_below else "")
        ranges.append(life)
        per_year = d_total / years
        out["static"][j], out["total"][j], out["se"][j] = d_static, d_total, se
        out["ratio"][j] = d_total / d_static if d_static > 0 else math.nan
        out["per_year"][j] = per_year
        out["eq"][j] = _equivalent_range(curve, per_year)
        out["eq_life"][j] = _equivalent_range(curve, per_year * spec.fatigue.design_life)
        out["life"][j] = remaining_life(per_year, spec.fatigue.damage_so_far)
    a = lambda u, d: {"units": u, "long_name": d}  # noqa: E731
    width = details[0].bin
    variables = {
        "fatigue_damage": ("detail", out["total"], a("1", "Miner damage over the simulated period, static + dynamic (difference estimator on the random sample)")),
        "fatigue_damage_static": ("detail", out["static"], a("1", "Miner damage of the static stress history over the simulated period")),
        "fatigue_damage_se": ("detail", out["se"], a("1", "standard error of fatigue_damage from the dynamic sample (0 when below_fatigue_limit: no damage by the limit rule, whatever the sample)")),
        "fatigue_damage_per_year": ("detail", out["per_year"], a("year-1", "fatigue_damage per year")),
        "dynamic_damage_ratio": ("detail", out["ratio"], a("1", "fatigue_damage / fatigue_damage_static")),
        "equivalent_stress_range": ("detail", out["eq"], a("Pa", "damage-equivalent stress range at 2e6 cycles a year")),
        "equivalent_stress_range_design_life": ("detail", out["eq_life"], a("Pa", f"damage-equivalent stress range of the {spec.fatigue.design_life:g}-year design life's traffic at 2e6 cycles (EN 1993-1-9 Δσ_E,2: below Δσ_C exactly when that damage is below 1)")),
        "remaining_life": ("detail", out["life"], a("year", "years until the Miner sum reaches 1 at fatigue_damage_per_year")),
        "below_fatigue_limit": ("detail", out["below_limit"].astype(np.int8), a("1", "1 if every stress range of the period (static, and of every dynamically simulated event) is below the constant-amplitude fatigue limit and so is the design life's largest, max_stress_range_design_life_bound: no damage (EN 1993-1-9 1.3.3.3, AASHTO (dF)_TH)")),
        "max_stress_range_design_life": ("detail", out["life_top"], a("Pa", f"the level the {spec.fatigue.design_life:g}-year design life's largest static stress range stays below with probability {spec.ci:g}: the Gumbel fit of the daily largest ranges at the return period design_life / (-ln {spec.ci:g}) (NaN: no estimate; fatigue_limit_note says why)")),
        "max_stress_range_design_life_bound": ("detail", out["life_bound"], a("Pa", f"upper {spec.ci:.0%} bound of max_stress_range_design_life times the simulated dynamics' amplification of the largest range: the limit rule's test over the design life (the static damage's: the bound alone)")),
        "fatigue_limit_note": ("detail", np.array(notes, dtype=object), a("", "why the limit rule was not applied although every simulated stress range is below the limit (empty otherwise)")),
        "damage_per_day_static": (("day", "detail"), alone, a("1", "Miner damage of each day's static history counted alone")),
        "stress_range_histogram": (("detail", "stress_range_bin"), hist, a("1", "static stress-range cycles (half cycles 0.5) per bin; the bins reach the largest range (none folded)")),
        "max_stress_range_static": ("detail", out["top"], a("Pa", "largest stress range of the period's static history (exact, not binned): the limit rule's test")),
    }
    coords = {"detail": np.array([d.name for d in details], dtype=object),
              "stress_range_bin": ("stress_range_bin", np.arange(max_bin) * width,
                                   {"units": "Pa", "long_name": "lower edge of the stress-range bin"}),
              "detail_category": ("detail", np.array([d.label for d in details], dtype=object)),
              "detail_size_factor": ("detail", np.array([d.size_factor for d in details], float),
                                     {"units": "1", "long_name": "EN 1993-1-9 size-effect reduction k_s of the category"})}
    return {"variables": variables, "coords": coords, "ranges": ranges}
