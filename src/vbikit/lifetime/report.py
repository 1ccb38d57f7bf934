"""The JSON summary (``summary.json``) and the text report (``report.txt``) of a lifetime run, both
read from ``lifetime.nc``'s dataset: every number with its interval, flag and verdict in words
(``vbikit.lifetime.accuracy``).  The report is rendered from the summary, so the two agree.

Each load effect's findings are [`Flag`][vbikit.analysis.checks.Flag] records (codes in
``vbikit.analysis.checks.FLAG_CODES``; subject: the effect's name): the summary's ``flags`` of the
effect, their messages its ``warnings`` (``add_flags``); the report prints each message as a
``flag_line`` ("! …") and sets its marks from the codes (``has_flag``)."""
from __future__ import annotations

import math
import re
from typing import Any

from vbikit._words import counted
from vbikit.analysis.checks import FLAG_MARK, Flag, add_flags, flag_line, has_flag, join_codes, unconverged_runs_flag
from vbikit.analysis.population_start import START_ATTRIBUTES, START_COUNTS, start_flags
from vbikit.analysis.population_start import start_words as population_start_words
from vbikit.analysis.sample_intervals import stored_interval_text
from vbikit.lifetime.accuracy import WIDE_INTERVAL, adr_words, amplification_words, too_wide
from vbikit.lifetime.results import IM_WITH_INTERVALS
from vbikit.outputs import report_unit


#: the confidence interval ends of the IM statistics (``vbikit.lifetime.results``), read into the facts when present
IM_INTERVAL_ENDS = tuple(f"{name}_ci_{end}" for name in IM_WITH_INTERVALS for end in ("lower", "upper"))


def _num(x) -> float | None:
    """A finite float, else None (JSON has no NaN)."""
    x = float(x)
    return x if math.isfinite(x) else None


def _interval(ds, name: str, j: int, k: int) -> dict[str, Any]:
    return {"value": _num(ds[name].values[j, k]), "lower": _num(ds[f"{name}_lower"].values[j, k]),
            "upper": _num(ds[f"{name}_upper"].values[j, k])}


def _effect(ds, j: int) -> dict[str, Any]:
    a = ds.attrs
    effect = str(ds["load_effect"].values[j])
    periods = ds["return_period"].values
    levels = []
    for k, t in enumerate(periods):
        row: dict[str, Any] = {"return_period": float(t)}
        for w in ("static", "total"):
            row[w] = {"block_maxima": _interval(ds, f"return_level_{w}", j, k),
                      "peaks_over_threshold": _interval(ds, f"return_level_pot_{w}", j, k),
                      "methods_disagree": bool(ds[f"methods_disagree_{w}"].values[j, k])}
        levels.append(row)
    fits = {w: {"block_maxima_shape": _num(ds[f"fit_{w}_shape"].values[j]),
                "pot_shape": _num(ds[f"fit_pot_{w}_shape"].values[j]),
                # signed like the levels (the dataset's threshold is s·R, the governing direction)
                "pot_threshold": _num(float(ds["effect_sign"].values[j])
                                      * ds["fit_pot_threshold" if w == "static" else "fit_pot_total_threshold"].values[j]),
                "pot_exceedances": int(ds[f"fit_pot_{w}_exceedances"].values[j]),
                # why there is no POT value, in words (None when there is one; older datasets lack it)
                "pot_not_estimable": (str(ds[f"pot_{w}_not_estimable"].values[j]) or None
                                      if f"pot_{w}_not_estimable" in ds else None),
                "shape_strongly_negative": bool(ds[f"shape_strongly_negative_{w}"].values[j])}
            for w in ("static", "total")}
    adr, lo, hi = (float(ds[n].values[j]) for n in ("assessment_dynamic_ratio", "assessment_dynamic_ratio_lower",
                                                     "assessment_dynamic_ratio_upper"))
    out: dict[str, Any] = {
        "units": str(ds["load_effect_units"].values[j]),
        "characteristic_period": float(a["characteristic_period"]),
        "characteristic_static": _num(ds["characteristic_static"].values[j]),
        "characteristic_total": _num(ds["characteristic_total"].values[j]),
        # why a characteristic value is missing, in words (None where it was estimated; older datasets lack it)
        **{f"characteristic_{w}_not_estimable": (str(ds[f"characteristic_{w}_not_estimable"].values[j]) or None
                                                 if f"characteristic_{w}_not_estimable" in ds else None)
           for w in ("static", "total")},
        # the largest static effect the traffic model can produce (None: no bound, fitted traffic; older datasets)
        "static_upper_bound": _num(ds["static_upper_bound"].values[j]) if "static_upper_bound" in ds else None,
        # the most the ADR can be: 1 + max(A used, this effect's largest simulated R_dyn/R_st − 1) (``adr_event_bound``;
        # None: no bound, a zero static peak or nothing known)
        "adr_event_bound": _num(adr_event_bound(a, _largest_amplification(ds, j))),
        "return_levels": levels, "fits": fits,
        "adr": {"value": _num(adr), "lower": _num(lo), "upper": _num(hi),
                "standard_error": _num(ds["assessment_dynamic_ratio_se"].values[j]),
                "indistinguishable_from_one": bool(ds["adr_indistinguishable_from_one"].values[j]),
                "words": adr_words(adr, lo, hi, float(a["ci"]))},
        "im": {k: _num(ds[k].values[j]) for k in ("im_mean", "im_std", "im_q95", "im_max", "im_governing_static_event",
                                                  "im_mean_loaded", "im_q95_loaded", *IM_INTERVAL_ENDS) if k in ds},
        "n_small_static_sample": int(ds["n_small_static_sample"].values[j]) if "n_small_static_sample" in ds else 0,
        # the sample of the IM statistics: the random sample's events with an IM
        "n_im_sample": _im_sample_size(ds, j),
        "aashto_lrfd_im": _num(ds["code_allowance"].values[j, 0]),
        # the direction s reported, how it was chosen and the other direction's share of the line (older datasets lack them)
        "direction": {"sign": float(ds["effect_sign"].values[j]),
                      "source": str(ds["effect_direction"].values[j]) if "effect_direction" in ds else "auto",
                      "opposite_area": (_num(ds["opposite_direction_area"].values[j])
                                        if "opposite_direction_area" in ds else None),
                      "largest": _largest(ds["daily_max_static"].values[:, j], float(ds["effect_sign"].values[j])),
                      "largest_opposite": (_num(ds["static_largest_opposite"].values[j])
                                           if "static_largest_opposite" in ds else None)},
    }
    if "run_static_shortfall" in ds:
        out["run_static_shortfall"] = {"value": _num(ds["run_static_shortfall"].values[j]),
                                       "event": int(ds["run_static_shortfall_event"].values[j])}
    if "governing_event" in ds:
        gov = {}
        for w, name in enumerate(ds["governs"].values):
            change = float(ds["governing_half_step_change"].values[j, w])
            gov[str(name)] = {"event": int(ds["governing_event"].values[j, w]),
                              "day": int(ds["governing_day"].values[j, w]),
                              "time_of_day_s": _num(ds["governing_time_of_day"].values[j, w]),
                              "vehicles": str(ds["governing_vehicles"].values[j, w]),
                              "static": _num(ds["governing_static_value"].values[j, w]),
                              "total": _num(ds["governing_total_value"].values[j, w]),
                              "total_half_step": _num(ds["governing_total_half_step"].values[j, w]),
                              "half_step_change": _num(change),
                              "half_step_flag": bool(math.isfinite(change) and abs(change) > a["half_step_tolerance"])}
        out["governing"] = gov
    add_flags(out, _flags(effect, out, a))
    return out


def _im_sample_size(ds, j: int) -> int | None:
    """The random sample's events with a finite IM for effect ``j`` (``n_im_sample``): stored, or for a dataset
    written before it was (2026-12-06) counted from its events as ``build_dataset`` counts it (R_dyn / R_st − 1 of
    ``event_total`` and ``event_static`` in ``event_in_sample``); None when neither can say."""
    import numpy as np

    if "n_im_sample" in ds:
        return int(ds["n_im_sample"].values[j])
    if not all(k in ds for k in ("event_in_sample", "event_total", "event_static")):
        return None
    sample = np.asarray(ds["event_in_sample"].values).astype(bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        im = np.asarray(ds["event_total"].values, float)[sample, j] / np.asarray(ds["event_static"].values, float)[sample, j] - 1.0
    return int(np.isfinite(im).sum())


def _largest(daily: Any, sign: float) -> float | None:
    """The run's largest static value in the reported direction ``sign``: that of its daily maxima."""
    import numpy as np

    values = sign * np.asarray(daily, float)
    return _num(sign * float(np.nanmax(values))) if np.any(np.isfinite(values)) else None


#: ``opposite_direction_unreported``: the largest ratio, the other direction's over the reported one's,
#: of the run's largest static values, or of the influence line's two parts' areas, that passes without
#: a flag (equal: both directions alike)
OPPOSITE_AREA_LIMIT = 1.0

#: what a lifetime finding puts in doubt (its flag's ``output``), in the report's words: the one
#: naming (``flag_output``; the report's marks match on it)
FLAG_OUTPUTS: dict[str, str] = {"characteristic": "characteristic {w} value", "return_levels": "{w} return levels",
                                "adr": "ADR", "governing": "governing {w} event"}


def flag_output(what: str, w: str = "") -> str:
    """A lifetime flag's ``output`` in words: ``flag_output("return_levels", "static")`` → "static
    return levels", ``flag_output("adr")`` → "ADR" (``FLAG_OUTPUTS``; ``w``: "static" or "total")."""
    return FLAG_OUTPUTS[what].format(w=w)


def _flags(name: str, e: dict, a: dict) -> list[Flag]:
    """The accuracy findings of load effect ``name`` (its summary so far, ``e``; the dataset's
    attributes ``a``) as ``Flag`` records (``FLAG_CODES``; subject: ``name``), in the report's order."""
    out = _direction_flags(name, e)
    out += _not_estimable_flags(name, e)
    out += _static_bound_flags(name, e)
    for w in ("static", "total"):
        out += _fit_flags(name, e, w, float(a["xi_strongly_negative"]), gumbel=a.get("distribution") == "gumbel")
    out += _adr_flags(name, e, a)
    out += _shortfall_flags(name, e, float(a["half_step_tolerance"]))
    out += _governing_flags(name, e, float(a["half_step_tolerance"]))
    out += _unconverged_flags(name, a)
    out += _start_flags(name, a)
    return out


def _sprung(a: dict) -> bool:
    """Whether lifetime.nc's dynamic events ran sprung trucks (``vehicle_model``; "axle-truck", the
    default, when a dataset does not say)."""
    return a.get("vehicle_model", "axle-truck") != "moving-forces"


def _start(a: dict) -> dict:
    """lifetime.nc's start attributes (``vbikit.analysis.population_start.START_ATTRIBUTES``); one written
    before 2026-12-07 stored only the shortest run-in an event got, as ``run_in_m`` (beside
    ``run_in_shortened_events``): read as ``run_in_min_m``, the population's run-in then not known (NaN)
    unless no event was cut short."""
    if "run_in_min_m" in a or "run_in_shortened_events" not in a or not _sprung(a):
        return a
    shortest = float(a.get("run_in_m", 0.0))
    return {**a, "run_in_min_m": shortest, "run_in_m": shortest if int(a["run_in_shortened_events"]) == 0 else math.nan}


def start_words(a: dict) -> str:
    """How the dynamic events start their trucks, in words, from lifetime.nc's attributes
    (``vbikit.analysis.population_start``; moving constant axle forces have nothing to settle)."""
    if not _sprung(a):
        return "moving constant axle forces (nothing to settle)"
    return population_start_words(_start(a), "sprung trucks")


def _start_flags(name: str, a: dict) -> list[Flag]:
    """Dynamic events whose sprung trucks start at rest a short approach before the bridge
    (``vbikit.analysis.population_start.start_flags``): their totals, so the total levels and the ADR,
    come out low.  None for moving constant forces, which have no vibration to build up, and for a
    dataset written before the approach was stored."""
    if not _sprung(a):
        return []
    return start_flags(_start(a), output=flag_output("return_levels", "total"), subject=name, sprung=True,
                       total=int(a.get("n_dynamic_events", 0)),
                       where="the lifetime file's [crossing] table (or its base scenario's)")


def _direction_flags(name: str, e: dict) -> list[Flag]:
    """A direction chosen by the line's largest ordinate (``direction = "auto"``) while the other
    direction may govern: the run's own traffic reached a larger static value the other way
    (``static_largest_opposite`` beyond the largest ``daily_max_static``), or the other sign's part of the
    influence line has the larger area (long or several vehicles load it more that way; a moment
    near an interior support).  ``value``: the traffic's ratio of the two largest static values where
    that fired the flag, else the area ratio."""
    d = e.get("direction")
    if not d or d["source"] != "auto":
        return []
    area = d["opposite_area"]
    big, other_big = d.get("largest"), d.get("largest_opposite")
    ratio = abs(other_big) / abs(big) if big and other_big is not None else None
    by_traffic = ratio is not None and ratio > OPPOSITE_AREA_LIMIT
    by_area = area is not None and area > OPPOSITE_AREA_LIMIT
    if not (by_traffic or by_area):
        return []
    here, other = ("positive", "negative") if d["sign"] > 0 else ("negative", "positive")
    unit = e["units"]
    measured = (f"this run's traffic reached {other_big:.4g} {unit} {other} against {big:.4g} {unit} {here} "
                f"({ratio:.2f} times)" if ratio is not None else "")
    shape = f"its {other} part has {area:.2f} times the area of its {here} part" if area is not None else ""
    why = "; ".join(w for w in (measured, shape) if w)
    verdict = "governs" if by_traffic else "may govern for long or several vehicles"
    return [Flag("opposite_direction_unreported",
                 f"only {here} values are reported (the influence line's largest ordinate is {here}), but the {other} "
                 f"direction {verdict}: {why}; add this load effect again with direction = \"{other}\" "
                 f"(and direction = \"{here}\" here) to see both",
                 output=flag_output("characteristic", "static"), subject=name,
                 value=ratio if by_traffic else area, threshold=OPPOSITE_AREA_LIMIT)]


def _not_estimable_flags(name: str, e: dict) -> list[Flag]:
    """A characteristic value that could not be estimated, with why."""
    return [Flag("characteristic_not_estimable", f"characteristic {w} {e[f'characteristic_{w}_not_estimable']}",
                 output=flag_output("characteristic", w), subject=name)
            for w in ("static", "total") if e.get(f"characteristic_{w}_not_estimable")]


#: the two methods of a return level: (name in words, the summary's key)
_METHODS = (("block maxima", "block_maxima"), ("POT", "peaks_over_threshold"))


def _static_bound_flags(name: str, e: dict) -> list[Flag]:
    """The characteristic static value beyond ``static_upper_bound`` (same sign, larger magnitude)."""
    bound, char, unit = e.get("static_upper_bound"), e["characteristic_static"], e["units"]
    if bound is None or char is None or not (char * bound > 0 and abs(char) > abs(bound)):
        return []
    beyond = [f"{method} at {r['return_period']:g} years" for r in e["return_levels"] for method, key in _METHODS
              if r["static"][key]["value"] is not None and abs(r["static"][key]["value"]) > abs(bound)
              and r["static"][key]["value"] * bound > 0]
    return [Flag("characteristic_above_static_bound",
                 f"static: the characteristic value {char:.4g} {unit} ({e['characteristic_period']:g} years) "
                 f"exceeds {bound:.4g} {unit}, the largest static effect any event of the traffic model "
                 f"can produce (the heaviest-effect records of each lane, as many at once as the lane's smallest "
                 f"headway allows): the extrapolation exceeds what the traffic model can produce — the fitted "
                 f"distribution's unbounded tail; consider a GEV or POT fit with a bounded tail, or the model's "
                 f"maximum {bound:.4g} {unit} (static levels above it: {', '.join(beyond)})",
                 output=flag_output("characteristic", "static"), subject=name, value=char, threshold=bound)]


def _fit_flags(name: str, e: dict, w: str, xi: float, gumbel: bool = False) -> list[Flag]:
    """The ``w`` ("static", "total") return levels' findings: a strongly negative shape (below ``xi``; a Gumbel
    fit's block-maxima shape, 0 by definition, is not quoted),
    intervals wider than their level (``too_wide``), BM and POT disagreeing (the dataset's
    ``methods_disagree_<w>``)."""
    out = []
    f = e["fits"][w]
    if f["shape_strongly_negative"]:
        shapes = [(n, f[k]) for n, k in (("block maxima", "block_maxima_shape"), ("POT", "pot_shape"))
                  if f[k] is not None and not (gumbel and k == "block_maxima_shape")]
        out.append(Flag("negative_shape", f"{w}: strongly negative shape ("
                        + ", ".join(f"{n} ξ = {x:.2f}" for n, x in shapes)
                        + f" < {xi:g}): a bounded tail fitted from little data; "
                        "the long-period levels and their intervals are unreliable — simulate more days",
                        output=flag_output("return_levels", w), subject=name, value=min((x for _, x in shapes), default=None),
                        threshold=xi))
    wide = [(n, r["return_period"], r[w][key]) for r in e["return_levels"] for n, key in _METHODS
            if too_wide(r[w][key]["value"], r[w][key]["lower"], r[w][key]["upper"])]
    if wide:
        out.append(Flag("wide_interval", f"{w}: confidence interval wider than the level itself ("
                        + ", ".join(f"{n} at {t:g} years" for n, t, _ in wide)
                        + "): too uncertain to sign, and too wide to tell whether the methods agree — simulate more days",
                        output=flag_output("return_levels", w), subject=name, threshold=WIDE_INTERVAL,
                        value=max(_relative_width(d) for _, _, d in wide)))
    bad = [r for r in e["return_levels"] if r[w]["methods_disagree"]]
    if bad:
        out.append(Flag("bm_pot_disagree", f"{w}: block maxima and peaks over threshold disagree beyond their intervals at "
                        f"{', '.join(format(r['return_period'], 'g') for r in bad)} years — the characteristic value "
                        "depends on the method", output=flag_output("return_levels", w), subject=name, threshold=0.0,
                        value=max(_interval_gap(r[w]["block_maxima"], r[w]["peaks_over_threshold"]) for r in bad)))
    return out


def _relative_width(level: dict) -> float:
    """|upper − lower| / |value| of a level with its interval (infinite for a level 0)."""
    width = abs(level["upper"] - level["lower"])
    return width / abs(level["value"]) if level["value"] else math.inf


def _interval_gap(a: dict, b: dict) -> float:
    """The gap between two levels' intervals (negative where they overlap); a level without an
    interval counts as its value alone (``vbikit.lifetime.accuracy.methods_disagree``); NaN where
    either has no value."""
    def span(d: dict) -> tuple[float, float]:
        if d["lower"] is None or d["upper"] is None:
            v = math.nan if d["value"] is None else d["value"]
            return v, v
        return min(d["lower"], d["upper"]), max(d["lower"], d["upper"])  # (a downward effect's bounds are in either order)

    (a_lo, a_hi), (b_lo, b_hi) = span(a), span(b)
    return max(b_lo - a_hi, a_lo - b_hi)


def _adr_flags(name: str, e: dict, a: dict) -> list[Flag]:
    """An ADR whose interval contains 1 (value: the interval's bound on the far side of 1), and an ADR above
    the bound the events set (``adr_event_bound``)."""
    adr, out = e["adr"], []
    if adr["indistinguishable_from_one"]:
        bound = adr["lower"] if adr["value"] is None or adr["value"] >= 1.0 else adr["upper"]
        out.append(Flag("adr_indistinguishable_from_one", "ADR: the interval contains 1 — the data cannot tell the ADR from 1",
                        output=flag_output("adr"), subject=name, value=bound, threshold=1.0))
    limit = e["adr_event_bound"] if "adr_event_bound" in e else adr_event_bound(a)
    limit = math.nan if limit is None else limit
    if adr["value"] is not None and math.isfinite(limit) and adr["value"] > limit:
        out.append(Flag("adr_above_event_bound",
                        f"ADR {adr['value']:.3f} is above {limit:.3f}, the most any day's total maximum can exceed its "
                        "static one (1 + the screening bound A used or this effect's simulated events' larger R_dyn/R_st − 1): "
                        "the fits of the daily total and static maxima extrapolate apart beyond what the events allow — the "
                        f"ADR and the characteristic total are not supported by the {int(a['n_days'])} simulated days "
                        "(simulate more days; the ADR is at most this bound)",
                        output=flag_output("characteristic", "total"), subject=name, value=adr["value"],
                        threshold=limit))
    return out


def adr_event_bound(a: dict, largest: float | None = None) -> float:
    """1 + max(the screening bound A used, the largest R_dyn/R_st − 1 of a simulated event) of one load effect:
    no day's largest total exceeds its largest static by more (an event left out has s·R_dyn ≤ (1 + A)·s·R_st, a
    simulated one its own ratio), so neither does any quantile of the daily total maxima that of the static ones,
    nor the characteristic total the characteristic static (NaN: not known; inf: no bound, a zero static peak).
    A from lifetime.nc's attributes ``a``; the ratio the effect's own (``largest``, ``_largest_amplification``),
    else the largest over every effect (the attribute ``amplification_max_observed``: a looser bound)."""
    ratio = float(a.get("amplification_max_observed", math.nan)) if largest is None else float(largest)
    values = [v for v in (float(a.get("amplification_bound_used", math.nan)), ratio) if not math.isnan(v)]
    return 1.0 + max(values) if values else math.nan


def _largest_amplification(ds, j: int) -> float:
    """Load effect ``j``'s largest R_dyn/R_st − 1 over the simulated events of lifetime.nc ``ds`` (the dataset's
    attribute ``amplification_max_observed`` is the largest over every effect; inf for a zero static peak; NaN:
    no event simulated)."""
    import numpy as np

    simulated = ds["event_simulated"].values.astype(bool)
    if not simulated.any():
        return math.nan
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = ds["event_total"].values[simulated, j] / ds["event_static"].values[simulated, j] - 1.0
    return math.nan if np.isnan(ratio).all() else float(np.nanmax(ratio))


def _shortfall_flags(name: str, e: dict, tolerance: float) -> list[Flag]:
    """The coupled runs' static reference short of the exact static peak by more than ``tolerance``."""
    short = e.get("run_static_shortfall", {})
    if short.get("value") is None or short["value"] <= tolerance:
        return []
    return [Flag("static_reference_short",
                 f"the coupled runs' static reference misses the exact static peak by up to {100 * short['value']:.2f} % "
                 f"(event {short['event']}; tolerance {100 * tolerance:g} %): their total peaks are "
                 "about as low, so the daily maxima of the total and the ADR are biased low — the time step is too "
                 "coarse for this effect, or a wheel left the tabulated tracks",
                 output=flag_output("adr"), subject=name, value=short["value"], threshold=tolerance)]


def _unconverged_flags(name: str, a: dict) -> list[Flag]:
    """Coupled runs with steps whose contact forces did not converge (``n_unconverged_events`` of
    ``n_dynamic_events``): their totals enter every load effect's total levels, ADR and fatigue."""
    n = int(a.get("n_unconverged_events", 0))
    if n <= 0:
        return []
    runs = int(a.get("n_dynamic_events", n))
    return [unconverged_runs_flag(n, counted(runs, "coupled run"), float(a["unconverged_steps_max"]),
                                  f"event {int(a['unconverged_event'])}", output=flag_output("return_levels", "total"),
                                  subject=name)]


def _governing_flags(name: str, e: dict, tolerance: float) -> list[Flag]:
    """A governing event whose total peak changes at half the time step by more than ``tolerance``."""
    return [Flag("governing_step_sensitive",
                 f"governing {w} event: its total peak changes by {100 * g['half_step_change']:+.2f} % at half "
                 f"the time step (tolerance {100 * tolerance:g} %) — the time step is too coarse",
                 output=flag_output("governing", w), subject=name, value=g["half_step_change"], threshold=tolerance)
            for w, g in e.get("governing", {}).items() if g["half_step_flag"]]


def flag_codes(facts: dict[str, Any]) -> str:
    """The codes of every load effect's flags, comma-separated, each once: the dataset's attribute
    ``flag_codes`` in the format of every population dataset (``vbikit.analysis.checks.join_codes``,
    read by ``dataset_has_flag``)."""
    return join_codes(f["code"] for e in facts["load_effects"].values() for f in e["flags"])


def effect_flag_codes(facts: dict[str, Any]) -> list[str]:
    """Each load effect's flag codes in the same format, in ``load_effect`` order (the dataset's
    variable ``load_effect_flag_codes``; "" for an effect without a flag)."""
    return [join_codes(f["code"] for f in e["flags"]) for e in facts["load_effects"].values()]


#: a fatigue detail's numbers in ``summary.json`` (``_detail``), each with its unit from the dataset's variable
DETAIL_NUMBERS = ("fatigue_damage", "fatigue_damage_se", "fatigue_damage_static", "dynamic_damage_ratio",
                  "dynamic_damage_ratio_se", "fatigue_damage_per_year", "equivalent_stress_range", "remaining_life",
                  "equivalent_stress_range_design_life", "max_stress_range_static", "max_stress_range_design_life",
                  "max_stress_range_design_life_bound", "fatigue_damage_design_life", "fatigue_damage_design_life_upper")


def _detail(ds, j: int) -> dict[str, Any]:
    """A fatigue detail's facts, with ``units``: each number's unit as the dataset writes it (stress ranges in Pa,
    the remaining life in years, damages 1; a trial's summary gave 8479595.97 with no unit)."""
    numbers = [k for k in DETAIL_NUMBERS if k in ds]
    return {"category": str(ds["detail_category"].values[j]),
            **{k: _num(ds[k].values[j]) for k in numbers},
            "below_fatigue_limit": bool(ds["below_fatigue_limit"].values[j]),
            "verdict": str(ds["fatigue_verdict"].values[j]),
            "dynamic_damage_ratio_words": str(ds["dynamic_damage_ratio_note"].values[j]),
            "units": {k: str(ds[k].attrs["units"]) for k in numbers if ds[k].attrs.get("units")}}


def summary(ds) -> dict[str, Any]:
    """The run's facts as a JSON-able dict (NaN and infinity as null, explained in words)."""
    from vbikit.lifetime.screening import CHECK_FRACTION

    a = ds.attrs
    out: dict[str, Any] = {
        "title": str(a["title"]), "vbikit_version": str(a.get("vbikit_version", "")),
        "run": {k: int(a[k]) for k in ("n_days", "days_per_year", "n_trucks", "n_events", "n_dynamic_events",
                                  "n_sample_events")} | {"fraction_dynamic": float(a["fraction_dynamic"]),
                                                         "time_total_s": float(a["time_total_s"]),
                                                         "time_static_s": float(a["time_static_s"]),
                                                         "events_per_second_static": float(a["events_per_second_static"])},
        "start": {"vehicle_model": str(a.get("vehicle_model", "axle-truck")),
                  **{k: _num(_start(a).get(k, math.nan)) for k in START_ATTRIBUTES if k not in START_COUNTS},
                  **{k: int(a[k]) if k in a else None for k in START_COUNTS},  # (None: not stated by the dataset)
                  "words": start_words(a)},
        "fits": {"distribution": str(a["distribution"]), "block": str(a["block"]),
                 "characteristic_period": float(a["characteristic_period"]), "ci": float(a["ci"]),
                 "xi_strongly_negative": float(a["xi_strongly_negative"])},
        "screening": {"amplification_bound_given": float(a["amplification_bound_given"]),
                      "amplification_bound_used": float(a["amplification_bound_used"]),
                      "amplification_max_heavy": _num(a["amplification_max_heavy"]),
                      "amplification_max_observed": _num(a["amplification_max_observed"]),
                      "words": amplification_words(float(a["amplification_max_heavy"]),
                                                   float(a["amplification_max_observed"]),
                                                   float(a["amplification_bound_given"]),
                                                   float(a["amplification_bound_used"]), CHECK_FRACTION)},
        "half_step_tolerance": float(a["half_step_tolerance"]),
        "load_effects": {str(n): _effect(ds, j) for j, n in enumerate(ds["load_effect"].values)},
    }
    if "fatigue_damage" in ds and ds.sizes.get("detail", 0):
        out["design_life"] = float(a["design_life"])
        out["fatigue"] = {str(n): _detail(ds, j) for j, n in enumerate(ds["detail"].values)}
    # every load effect's flags at the top as well, as every summary of vbikit gives them (each record naming its
    # effect in ``load_effect``; the effects' own lists stay where they are)
    out["flags"] = [{**f, "load_effect": name} for name, e in out["load_effects"].items() for f in e["flags"]]
    out["warnings"] = [f"{f['load_effect']}: {f['message']}" for f in out["flags"]]
    return out


def _g(x: float | None, fmt: str = ".4g", scale: float = 1.0) -> str:
    """``x`` times ``scale`` (to the report's unit, ``vbikit.outputs.report_unit``) formatted by
    ``fmt``, or "n/a" in the same alignment and width (table columns stay aligned)."""
    if x is None:
        width = re.match(r"[<>^]?\d*", fmt).group()
        return format("n/a", width if width[:1] in "<>^" else ">" + width) if width else "n/a"
    return format(x * scale, fmt)


def _iv(d: dict, scale: float = 1.0) -> str:
    """A level with its interval, times ``scale`` (to the report's unit), the interval in increasing
    order (a hogging or upward effect's bounds are stored by magnitude)."""
    if d["value"] is None:
        return "n/a"
    if d["lower"] is None:
        return f"{d['value'] * scale:.4g} (no interval)"
    lo, hi = sorted((d["lower"] * scale, d["upper"] * scale))
    return f"{d['value'] * scale:.4g} ({lo:.4g} … {hi:.4g})"


#: the flag outputs (``flag_output``) that put each value of the report's headline table in doubt (``_in_doubt``)
_TABLE_DOUBTS = {"static": (flag_output("characteristic", "static"), flag_output("return_levels", "static")),
                 "total": (flag_output("characteristic", "total"), flag_output("return_levels", "total"),
                           flag_output("governing", "total")),
                 "adr": (flag_output("adr"),)}


def _in_doubt(e: dict[str, Any], what: str) -> bool:
    """Whether a flag of load effect ``e`` (its summary) puts its headline value ``what`` ("static": the
    characteristic static value, "total", "adr") in doubt: a flag whose ``output`` is one of ``_TABLE_DOUBTS``."""
    return any(f.get("output") in _TABLE_DOUBTS[what] or (what == "adr" and f["code"] == "adr_above_event_bound")
               for f in e.get("flags", ()))


def text_report(facts: dict[str, Any]) -> str:
    """The run's plain-text report (rendered from ``summary``; its marks, ``*`` under a table and ABOVE
    at a governing event, from the flags' codes, never from their words).  Moments are shown in kN m,
    forces in kN and deflections in mm like ``vbikit run``'s report (``vbikit.outputs.report_unit``);
    the summary and the dataset stay SI, and so do the flags' messages printed as ``flag_line``s ("! …").  The
    fatigue table's damage is that of the simulated days, its header says so."""
    r, f = facts["run"], facts["fits"]
    ci = f"{100 * f['ci']:g} %"  # ("95 %", as every interval of vbikit is written: "95 % CI")
    lines = [f"vbikit lifetime: {facts['title']}",
             f"{counted(r['n_days'], 'day')} ({r['n_days'] / r['days_per_year']:.3g} years), "
             f"{counted(r['n_trucks'], 'truck', thousands=True)}, {counted(r['n_events'], 'event', thousands=True)}; "
             f"{r['n_dynamic_events']:,} simulated dynamically "
             f"({100 * r['fraction_dynamic']:.2f} %, of which {r['n_sample_events']} the random sample)",
             "screening: " + facts["screening"]["words"],
             "dynamic events: " + facts["start"]["words"],
             f"fits: {f['distribution']} of {'daily' if f['block'] == 'day' else 'weekly'} maxima (BM) and a GPD of "
             f"the peaks over a threshold (POT); characteristic period {f['characteristic_period']:g} years; "
             f"intervals {ci}",
             f"run time {r['time_total_s']:.1f} s (static pass {r['time_static_s']:.1f} s, "
             f"{r['events_per_second_static']:,.0f} events/s)", "",
             f"{'load effect':<22}{'unit':<6}{'char. static':>14}{'char. total':>14}{'ADR':>8}{'ADR ' + ci + ' interval':>20}"
             f"{'IM mean':>9}{'IM q95':>8}{'AASHTO':>8}"]
    marked = False
    for name, e in facts["load_effects"].items():
        ad = e["adr"]
        unit, k = report_unit(e["units"])
        span = "n/a" if ad["lower"] is None else f"{ad['lower']:.3f} … {ad['upper']:.3f}"
        doubt = {w: _in_doubt(e, w) for w in ("static", "total", "adr")}
        marked |= any(doubt.values())
        lines.append(f"{name:<22}{unit:<6}{_g(e['characteristic_static'], '>13.5g', k)}{'!' if doubt['static'] else ' '}"
                     f"{_g(e['characteristic_total'], '>13.5g', k)}{'!' if doubt['total'] else ' '}"
                     f"{_g(ad['value'], '>7.4f')}{'!' if doubt['adr'] else ' '}{span:>20}"
                     f"{_g(e['im']['im_mean'], '>9.4f')}{_g(e['im']['im_q95'], '>8.4f')}{_g(e['aashto_lrfd_im'], '>8.2f')}")
    from vbikit.analysis.checks import SMALL_STATIC_FRACTION

    n_sample = r["n_sample_events"]
    sizes = {name: n_sample if e.get("n_im_sample") is None else e["n_im_sample"]
             for name, e in facts["load_effects"].items()}  # (older summaries: the whole sample)
    left_out = [f"{name} {n_sample - n}" for name, n in sizes.items() if n < n_sample]
    lines.append(f"  (IM mean, IM q95: mean and 95th percentile of the impact factors R_dyn/R_st − 1 of the random "
                 f"sample's {counted(n_sample, 'event')}, all lanes and vehicles together — not per lane, nor the IM "
                 "of the largest static event"
                 + (f"; events without an IM left out: {', '.join(left_out)}" if left_out else "") + ")")
    if marked:
        lines.append(f"  ({FLAG_MARK} beside a value: a line below starting with {FLAG_MARK} puts it in doubt; read it "
                     "before using the value)")
    for name, e in facts["load_effects"].items():  # how well the random sample fixes the IM statistics
        if e["im"].get("im_mean_ci_lower", "absent") != "absent" and e["im"].get("im_mean") is not None:
            size = f"{sizes[name]} events" if sizes[name] == n_sample else \
                f"{sizes[name]} of its {n_sample} events with an IM"
            lines.append(f"  {name}: IM of the random sample ({size}): mean "
                         f"{stored_interval_text(e['im'], 'im_mean')}, 95th percentile {stored_interval_text(e['im'], 'im_q95')}")
    for name, e in facts["load_effects"].items():
        if e["n_small_static_sample"]:
            n = e["n_small_static_sample"]
            lines.append(f"  {name}: {counted(n, 'sampled event')} load{'s' if n == 1 else ''} it below "
                         f"{SMALL_STATIC_FRACTION * 100:g} % of the largest static "
                         f"effect (light vehicles, far lanes): their IMs rest on small static references, not design "
                         f"values; the others' IM mean {stored_interval_text(e['im'], 'im_mean_loaded')}, "
                         f"95th percentile {stored_interval_text(e['im'], 'im_q95_loaded')}")
    for name, e in facts["load_effects"].items():
        unit, k = report_unit(e["units"])
        lines += ["", f"{name} [{unit}]: return levels, block maxima (BM) beside peaks over threshold (POT), "
                      f"{ci} intervals"]
        for w in ("static", "total"):
            fw = e["fits"][w]
            pot = (f"POT threshold {_g(fw['pot_threshold'], scale=k)}, {counted(fw['pot_exceedances'], 'exceedance')}, ξ = "
                   f"{_g(fw['pot_shape'], '.3f')}")
            gumbel = facts["fits"]["distribution"] == "gumbel"  # (its shape is fixed at 0, not fitted)
            bm = "BM ξ = 0 (Gumbel)" if gumbel else f"BM ξ = {_g(fw['block_maxima_shape'], '.3f')}"
            lines.append(f"  {w}: {bm}; {pot}"
                         + ("" if fw["pot_shape"] is not None else
                            f" (no POT value: {fw['pot_not_estimable'] or 'too few exceedances'})"))
        lines.append(f"  {'T [yr]':>8}  {'static BM':<38}{'static POT':<38}{'total BM':<38}total POT")
        for row in e["return_levels"]:
            cells = []
            for w in ("static", "total"):
                mark = " *" if row[w]["methods_disagree"] else ""
                cells += [_iv(row[w]["block_maxima"], k), _iv(row[w]["peaks_over_threshold"], k) + mark]
            lines.append(f"  {row['return_period']:>8g}  " + "".join(f"{c:<37} " for c in cells).rstrip())
        if has_flag(e, "bm_pot_disagree"):  # (the marks and the flag come from the same methods_disagree_*)
            lines.append("  (* BM and POT disagree beyond their intervals)")
        lines.append("  " + e["adr"]["words"])
        for w, g in e.get("governing", {}).items():
            change = g["half_step_change"]
            above = has_flag(e, "governing_step_sensitive", output=flag_output("governing", w))
            check = ("n/a" if change is None else f"{100 * change:+.3f} % "
                     + ("ABOVE" if above else "within") + f" the {100 * facts['half_step_tolerance']:g} % tolerance")
            lines.append(f"  governing {w} maximum: day {g['day']} (the dataset's day index, from 0) at "
                         f"{_clock(g['time_of_day_s'])}, {g['vehicles']}; static {_g(g['static'], scale=k)}, total "
                         f"{_g(g['total'], scale=k)}; total at half the time step "
                         f"{_g(g['total_half_step'], scale=k)} ({check})")
        for flag in e["flags"]:
            lines.append("  " + flag_line(flag["message"]))
    if "fatigue" in facts:
        wide = max([12] + [len(d["category"]) + 2 for d in facts["fatigue"].values()])  # (a reduced category is long)
        days = counted(r["n_days"], "simulated day")
        lines += ["", f"fatigue: Miner damage over the {days} (damage, its standard error ± se and its static part), "
                      f"per year ({r['days_per_year']} days), and the remaining life; design life "
                      f"{facts['design_life']:g} years",
                  f"{'detail':<16}{'category':<{wide}}{'damage':>12}{'± se':>11}{'static':>12}{'per year':>12}"
                  f"{'Δσ_E,2 MPa':>11}{'life yr':>10}"]
        for name, d in facts["fatigue"].items():
            eq = d.get("equivalent_stress_range_design_life")
            lines.append(f"{name:<16}{d['category']:<{wide}}{_g(d['fatigue_damage'], '>12.4g')}"
                         f"{_g(d['fatigue_damage_se'], '>11.3g')}{_g(d['fatigue_damage_static'], '>12.4g')}"
                         f"{_g(d['fatigue_damage_per_year'], '>12.4g')}"
                         f"{('n/a' if eq is None else format(eq / 1e6, '.3f')):>11}"
                         f"{('unlimited' if d['remaining_life'] is None else format(d['remaining_life'], '.4g')):>10}")
        lines.append(f"  (Δσ_E,2: the constant range whose 2e6 cycles do the damage of the {facts['design_life']:g}-year "
                     "design life's traffic, comparable with the category Δσ_C (EN 1993-1-9 8(2))"
                     + ("; n/a: that range lies below the curve's cut-off)"
                        if any(d.get("equivalent_stress_range_design_life") is None for d in facts["fatigue"].values())
                        else ")"))
        for name, d in facts["fatigue"].items():
            lines += [f"  {name}: {d['verdict']}", f"  {name}: {d['dynamic_damage_ratio_words']}"]
    return "\n".join(lines) + "\n"


def _clock(seconds: float | None) -> str:
    from vbikit.lifetime.governing import clock

    return "n/a" if seconds is None else clock(seconds)


__all__ = ["summary", "text_report"]
