"""Recompute the numbers docs/lifetime.md quotes: docs/figures/lifetime-numbers.json, the figures
docs/figures/lifetime-*.png, and the generated block of the page.

    python docs/scripts/lifetime_numbers.py          # the example week (about a minute on 2 cores)
    python docs/scripts/lifetime_numbers.py --page   # only re-render the page's block from the JSON (and the
                                                     # benchmark's JSON, if it has run since)
    python docs/scripts/lifetime_numbers.py --knot   # only the knot example (seconds), then the page

* ``example``: examples/lifetime/lifetime.toml run as ``vbikit lifetime`` runs it (2 workers);
* ``peer``: static daily maxima of six days of generated traffic against pybtls (BTLS) on the
  same traffic and influence line (the test tests/lifetime/test_peer_pybtls.py, with its numbers);
* ``exactness``: the largest relative difference between the convolution and the coupled run's
  static reference at the run's time steps (tests/lifetime/test_influence.py's events);
* ``exact_peaks``: the example week's exact static peaks against a 0.1 m sampling grid, and the
  exact pass's cost per truck and line;
* ``knot_example``: of the example week's heaviest entry-reaction events (exact static peak), the one
  whose coupled run's static reference, read at the run's time steps only, falls furthest below the
  exact peak; the same run's static and total with the one-sided limits at the knots;
* ``benchmark``: docs/figures/lifetime-benchmark.json if present (``python
  benchmarks/bench_lifetime.py --json docs/figures/lifetime-benchmark.json``).
"""
from __future__ import annotations

import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
NUMBERS = ROOT / "docs" / "figures" / "lifetime-numbers.json"
BENCH = ROOT / "docs" / "figures" / "lifetime-benchmark.json"
PAGE = ROOT / "docs" / "lifetime.md"
START, END = "<!-- lifetime-numbers:start -->", "<!-- lifetime-numbers:end -->"
EXACT_START, EXACT_END = "<!-- lifetime-exact:start -->", "<!-- lifetime-exact:end -->"
KNOT_START, KNOT_END = "<!-- lifetime-knot:start -->", "<!-- lifetime-knot:end -->"


def example() -> dict:
    from vbikit.lifetime.run import run_lifetime

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        ds = run_lifetime(ROOT / "examples" / "lifetime" / "lifetime.toml", Path(tmp), workers=2)
        wall = time.perf_counter() - t0
        for name in ("gumbel", "adr", "fatigue", "traffic"):
            shutil.copy(Path(tmp) / f"lifetime-{name}.png", ROOT / "docs" / "figures" / f"lifetime-{name}.png")
    a = ds.attrs
    effects = {}
    for j, name in enumerate(ds["load_effect"].values):
        effects[str(name)] = {k: float(ds[k].values[j]) for k in (
            "characteristic_static", "characteristic_total", "assessment_dynamic_ratio", "im_mean", "im_q95",
            "im_governing_static_event")} | {"units": str(ds["load_effect_units"].values[j]),
                                              "aashto_lrfd": float(ds["code_allowance"].values[j, 0])}
    k_char = int(list(ds["return_period"].values).index(a["characteristic_period"]))
    for j, name in enumerate(ds["load_effect"].values):
        e = effects[str(name)]
        for w in ("static", "total"):
            e[f"pot_{w}"] = float(ds[f"return_level_pot_{w}"].values[j, k_char])
            e[f"pot_{w}_shape"] = float(ds[f"fit_pot_{w}_shape"].values[j])
            e[f"pot_{w}_exceedances"] = float(ds[f"fit_pot_{w}_exceedances"].values[j])
            e[f"{w}_lower"] = float(ds[f"return_level_{w}_lower"].values[j, k_char])
            e[f"{w}_upper"] = float(ds[f"return_level_{w}_upper"].values[j, k_char])
            e[f"methods_disagree_{w}"] = float(ds[f"methods_disagree_{w}"].values[j, k_char])
            e[f"shape_strongly_negative_{w}"] = float(ds[f"shape_strongly_negative_{w}"].values[j])
        e["adr_lower"] = float(ds["assessment_dynamic_ratio_lower"].values[j])
        e["adr_upper"] = float(ds["assessment_dynamic_ratio_upper"].values[j])
        e["half_step_change_static"] = float(ds["governing_half_step_change"].values[j, 0])
        e["half_step_change_total"] = float(ds["governing_half_step_change"].values[j, 1])
    details = {}
    for j, name in enumerate(ds["detail"].values):
        details[str(name)] = {k: float(ds[k].values[j]) for k in (
            "fatigue_damage", "fatigue_damage_static", "fatigue_damage_se", "dynamic_damage_ratio",
            "fatigue_damage_per_year", "remaining_life", "fatigue_damage_design_life",
            "fatigue_damage_design_life_upper", "max_stress_range_static", "max_stress_range_design_life",
            "max_stress_range_design_life_bound")} | {"verdict": str(ds["fatigue_verdict"].values[j]),
                                                     "ratio_words": str(ds["dynamic_damage_ratio_note"].values[j])}
    return {"date": time.strftime("%Y-%m-%d"), "wall_s": wall, "n_days": int(a["n_days"]), "n_trucks": int(a["n_trucks"]),
            "n_events": int(a["n_events"]), "n_dynamic": int(a["n_dynamic_events"]),
            "n_sample": int(a["n_sample_events"]), "fraction_dynamic": float(a["fraction_dynamic"]),
            "static_events_per_s": float(a["events_per_second_static"]),
            "amplification_max_observed": float(a["amplification_max_observed"]),
            "amplification_max_heavy": float(a["amplification_max_heavy"]),
            "amplification_bound_used": float(a["amplification_bound_used"]),
            "first_frequency_hz": float(a["first_frequency_hz"]), "effects": effects, "details": details}


def exact_peaks() -> dict:
    """The example week's exact static peaks (``vbikit.lifetime.peaks``) against the same lines
    sampled every 0.1 m of travel of the event's fastest vehicle (no refinement), and the exact
    pass's cost per truck and line on one core (thread CPU time, the minimum of 3 repeats, day 0)."""
    import numpy as np

    from vbikit.lifetime.influence import event_static
    from vbikit.lifetime.jobs import _digest, day_traffic
    from vbikit.lifetime.run import prepare
    from vbikit.lifetime.spec import read_lifetime

    prep = prepare(*read_lifetime(ROOT / "examples" / "lifetime" / "lifetime.toml"))
    s = prep.setup
    names = [ln.name for ln in s.lines]
    step = 0.1
    rel, day_max = [], []
    for day in range(prep.n_days):
        recs, evs = day_traffic(prep.model, _digest(prep.model), s, day, prep.spec.seed)
        exact = event_static(recs, evs, s.lines, s.span, s.lanes, s.pattern, tables=s.tables).peaks
        grids = []
        for members in evs:
            rs = [recs[i] for i in members]
            t0 = min(r.time for r in rs)
            t1 = max(r.time + (s.span + r.length) / r.speed for r in rs)
            grids.append(np.arange(t0, t1 + 1e-9, step / max(r.speed for r in rs)))
        sampled = event_static(recs, evs, s.lines, s.span, s.lanes, s.pattern, tables=s.tables, times=grids).peaks
        rel.append((np.abs(exact) - np.abs(sampled)) / np.abs(exact))
        day_max.append((np.max(np.abs(sampled), axis=0), np.max(np.abs(exact), axis=0)))
    rel = np.concatenate(rel)
    j_r = names.index("R_entry")
    d = int(np.argmax([e[j_r] - a[j_r] for a, e in day_max]))
    recs, evs = day_traffic(prep.model, _digest(prep.model), s, 0, prep.spec.seed)
    cost = {}
    for j, name in enumerate(names):
        best = np.inf
        for _ in range(3):
            t = time.thread_time()
            event_static(recs, evs, s.lines[j:j + 1], s.span, s.lanes, s.pattern, tables=s.tables[j:j + 1])
            best = min(best, time.thread_time() - t)
        cost[name] = 1e6 * best / len(recs)
    return {"date": time.strftime("%Y-%m-%d"), "events": int(rel.shape[0]), "step_m": step,
            "over_1pct": {n: int(np.sum(rel[:, j] > 0.01)) for j, n in enumerate(names)},
            "over_01pct": {n: int(np.sum(rel[:, j] > 0.001)) for j, n in enumerate(names)},
            "events_over_1pct": int(np.sum(np.any(rel > 0.01, axis=1))),
            "events_over_01pct": int(np.sum(np.any(rel > 0.001, axis=1))),
            "worst": {n: float(np.max(rel[:, j])) for j, n in enumerate(names)},
            "reaction_day": d, "reaction_day_max_sampled": float(day_max[d][0][j_r]),
            "reaction_day_max_exact": float(day_max[d][1][j_r]), "us_per_truck": cost}


def render_exact(numbers: dict) -> str:
    """The generated block of docs/lifetime.md on the exact static peaks."""
    x = numbers["exact_peaks"]
    per = ", ".join(f"{n} {x['over_1pct'][n]} / {x['over_01pct'][n]} (worst {100 * x['worst'][n]:.2f} %)"
                    for n in x["over_1pct"])
    cost = ", ".join(f"{n} {v:.1f}" for n, v in x["us_per_truck"].items())
    return "\n".join([EXACT_START, "", f"The example week (docs/scripts/lifetime_numbers.py, measured {x['date']} on 2 cores "
                      "shared with other work): "
                      f"sampled every {x['step_m']:g} m of travel instead (no refinement), {x['events_over_1pct']:,} of "
                      f"its {x['events']:,} events fall more than 1 % and {x['events_over_01pct']:,} more than 0.1 % "
                      f"below their exact peak (per effect, > 1 % / > 0.1 %: {per}); the entry reaction's maximum of "
                      f"day {x['reaction_day']} is {x['reaction_day_max_sampled'] / 1e3:.1f} kN sampled against "
                      f"{x['reaction_day_max_exact'] / 1e3:.1f} kN exact.  Cost of the exact pass on one core (µs a "
                      f"truck, one line each): {cost}.", "", EXACT_END])


#: the example week's events by exact entry-reaction static peak that ``knot_example`` runs coupled
KNOT_CANDIDATES = 40


def knot_example() -> dict:
    """Of the ``KNOT_CANDIDATES`` events of the example week with the largest exact static entry
    reaction (the static pass's peaks), the one whose coupled run's static reference read at the run's
    time steps alone falls furthest below that exact peak (an axle over the support between two
    steps), with the same run's static and total peaks once the one-sided limits at the knots are in
    (``DynamicJob.run_event``, as the lifetime run computes them)."""
    import numpy as np

    from vbikit.analysis.effects import load_effect_responses
    from vbikit.lifetime.jobs import EVENT_STRIDE
    from vbikit.lifetime.run import prepare
    from vbikit.lifetime.spec import read_lifetime
    from vbikit.solve import simulate

    prep = prepare(*read_lifetime(ROOT / "examples" / "lifetime" / "lifetime.toml"))
    lines = prep.setup.lines
    j = [ln.name for ln in lines].index("R_entry")
    static_job = prep.static_job()
    days = [static_job.run_batch((day,)) for day in range(prep.n_days)]
    gid = np.concatenate([d["ev_day"] * EVENT_STRIDE + d["ev_index"] for d in days])
    exact = np.concatenate([d["ev_static"][:, j] for d in days])
    trucks = np.concatenate([d["ev_n_vehicles"] for d in days])
    heaviest = np.argsort(-np.abs(exact), kind="stable")[:KNOT_CANDIDATES]
    job = prep.dynamic_job(gid[heaviest])
    worst = None
    for i in heaviest:
        crossing = job.crossing(int(gid[i]))[0]
        result = simulate(crossing)
        static = load_effect_responses(result, [lines[j].effect], check_step=False)[0].static
        sign = float(np.sign(exact[i]) or 1.0)
        steps = sign * float(np.max(sign * static))
        short = (abs(exact[i]) - abs(steps)) / abs(exact[i])
        if worst is None or short > worst[0]:
            worst = (short, int(i), steps, float(result.time[1] - result.time[0]))
    short, i, steps, dt = worst
    out = job.run_event(int(gid[i]))
    day, index = divmod(int(gid[i]), EVENT_STRIDE)
    return {"date": time.strftime("%Y-%m-%d"), "candidates": KNOT_CANDIDATES, "day": day, "event": index,
            "trucks": int(trucks[i]), "dt_s": dt, "exact_static": float(exact[i]), "steps_static": steps,
            "shortfall": float(short), "limits_static": float(out["run_static_peak"][j]),
            "limits_total": float(out["dyn_peak"][j])}


def render_knot(numbers: dict) -> str:
    """The generated sentence of docs/lifetime.md on the knot example."""
    k = numbers["knot_example"]
    return "\n".join([KNOT_START, "", f"In the example week (docs/scripts/lifetime_numbers.py, {k['date']}), of its "
                       f"{k['candidates']} events with the largest exact static entry reaction, day {k['day']}'s event "
                       f"{k['event']} ({k['trucks']} trucks) has its run's static reference at the time steps "
                       f"(dt = {1e3 * k['dt_s']:.2f} ms) at {k['steps_static'] / 1e3:.1f} kN against the exact "
                       f"{k['exact_static'] / 1e3:.1f} kN ({100 * k['shortfall']:.1f} % low); with the limits at the "
                       f"knots its static peak is {k['limits_static'] / 1e3:.1f} kN and its total "
                       f"{k['limits_total'] / 1e3:.1f} kN.", "", KNOT_END])


def _load_test(name: str):
    import importlib.util

    spec = importlib.util.spec_from_file_location(name, ROOT / "tests" / "lifetime" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def exactness() -> dict:
    import numpy as np

    from vbikit.analysis.effects import load_effect_response
    from vbikit.analysis.response import point_response
    from vbikit.lifetime.influence import TirePattern, deflection_line, effect_line, event_static
    from vbikit.solve import simulate
    from vbikit.traffic.study import traffic_study

    records = _load_test("test_influence")._records()
    out = {}
    for bridge, tire, lanes in (("paper-bridge-1-beam", "point", (0.0, 0.0)), ("paper-bridge-1", "multipoint", None)):
        base = {"bridge": {"model": bridge, "n_modes": 4}, "tire": {"model": tire}, "road": {"class": "none"},
                "response": {"moment": [3.7], "shear": [2.1]}}
        study = traffic_study(records, base, lanes=lanes)
        ctx = study.context()
        deck = ctx.template.crossing.bridge
        lines = [deflection_line(deck, 5.2, study.lanes[0])] + [effect_line(deck, e) for e in ctx.plan.load_effects]
        worst = 0.0
        for e in range(study.size):
            result = simulate(study.crossing(e))
            got = event_static(study.records, [study.events[e]], lines, deck.span, study.lanes,
                               TirePattern.of_crossing(ctx.template), times=[result.time + study.event_start[e]],
                               keep_histories=True)
            refs = [point_response(result, 5.2, study.lanes[0]).static_displacement]
            refs += [load_effect_response(result, eff).static for eff in ctx.plan.load_effects]
            for j, ref in enumerate(refs):
                worst = max(worst, float(np.max(np.abs(got.histories[j] - ref)) / np.max(np.abs(ref))))
        out[bridge] = worst
    return out


def render(numbers: dict) -> str:
    """The generated block of docs/lifetime.md."""
    ex = numbers["example"]
    lines = [START, "", f"Example week (examples/lifetime, measured {ex['date']} on 2 cores shared with other work): "
             f"{ex['n_days']} days, {ex['n_trucks']:,} trucks, {ex['n_events']:,} events; "
             f"{ex['n_dynamic']:,} simulated dynamically ({100 * ex['fraction_dynamic']:.2f} %, of which "
             f"{ex['n_sample']:,} the random sample); run time {ex['wall_s']:.0f} s; static pass "
             f"{ex['static_events_per_s']:,.0f} events/s; first frequency {ex['first_frequency_hz']:.2f} Hz.", "",
             "| load effect | unit | characteristic static (1,000 yr) | characteristic total | ADR | IM mean over the "
             f"random sample ({ex['n_sample']:,} events, all lanes) | IM 95th percentile, same events "
             "| IM of the largest static event | AASHTO LRFD IM |",
             "|---|---|---|---|---|---|---|---|---|"]
    from vbikit.outputs import report_unit  # the report's units: kN m, kN, mm

    for name, e in ex["effects"].items():
        unit, k = report_unit(e["units"])
        lines.append(f"| {name} | {unit} | {k * e['characteristic_static']:.4g} | {k * e['characteristic_total']:.4g} | "
                     f"{e['assessment_dynamic_ratio']:.3f} | {e['im_mean']:.3f} | {e['im_q95']:.3f} | "
                     f"{e['im_governing_static_event']:.3f} | {e['aashto_lrfd']:.2f} |")
    lines += ["", "| detail | damage (week, static + dynamic) | ± standard error | static damage | dynamic / static "
                  "| damage per year | remaining life [years] |", "|---|---|---|---|---|---|---|"]
    for name, d in ex["details"].items():
        ratio = "undefined (static damage 0)" if d["dynamic_damage_ratio"] != d["dynamic_damage_ratio"] else \
            f"{d['dynamic_damage_ratio']:.3f}"
        life = "unlimited" if d["remaining_life"] == float("inf") else f"{d['remaining_life']:.4g}"
        lines.append(f"| {name} | {d['fatigue_damage']:.3g} | {d['fatigue_damage_se']:.2g} | "
                     f"{d['fatigue_damage_static']:.3g} | {ratio} | "
                     f"{d['fatigue_damage_per_year']:.3g} | {life} |")
    lines += ["", "How accurate (the example week; 1,000-year values in the units above, 95 % intervals; BM = Gumbel of the daily "
                  "maxima, POT = GPD of the peaks over the threshold; flags as in the text):", "",
              "| load effect | static BM | static POT (ξ) | total BM | total POT (ξ) | ADR (interval) | flags "
              "| governing total event at half step |", "|---|---|---|---|---|---|---|---|"]
    for name, e in ex["effects"].items():
        from vbikit._words import counted

        flags = [f"{w}: ξ < −0.3" for w in ("static", "total") if e[f"shape_strongly_negative_{w}"]]
        flags += [f"{w}: BM and POT disagree" for w in ("static", "total") if e[f"methods_disagree_{w}"]]
        if e["adr_lower"] <= 1.0 <= e["adr_upper"]:
            flags.append("ADR cannot be told from 1")
        pot = {w: (f"n/a ({counted(int(e[f'pot_{w}_exceedances']), 'exceedance')}, 10 needed)" if e[f"pot_{w}"] != e[f"pot_{w}"] else
                   f"{report_unit(e['units'])[1] * e[f'pot_{w}']:.4g} ({e[f'pot_{w}_shape']:.2f})")
               for w in ("static", "total")}
        k = report_unit(e["units"])[1]
        lo, hi = ({w: sorted((k * e[f"{w}_lower"], k * e[f"{w}_upper"]))[i] for w in ("static", "total")} for i in (0, 1))
        lines.append(f"| {name} | {k * e['characteristic_static']:.4g} ({lo['static']:.4g} … {hi['static']:.4g}) | "
                     f"{pot['static']} | {k * e['characteristic_total']:.4g} ({lo['total']:.4g} … {hi['total']:.4g}) | "
                     f"{pot['total']} | {e['assessment_dynamic_ratio']:.3f} ({e['adr_lower']:.3f} … {e['adr_upper']:.3f}) | "
                     f"{'; '.join(flags) or 'none'} | {100 * e['half_step_change_total']:+.3f} % |")
    lines += [""] + [f"Fatigue, {name}: {d['verdict']}; {d['ratio_words']}." for name, d in ex["details"].items()]
    ex_ = numbers["exactness"]
    lines += ["", "Convolution against the coupled run's static reference at the run's time steps (largest relative "
                  "difference over the histories of the test events): "
              + ", ".join(f"{k} {v:.1e}" for k, v in ex_.items()) + "."]
    b = numbers.get("benchmark")
    if b:
        lines += ["", f"Benchmark (benchmarks/bench_lifetime.py, measured {b['date']}, {b['workers']} workers on a "
                      f"2-core machine shared with other work): {b['days']} days, {b['trucks']:,} trucks, "
                      f"{b['events']:,} events, {b['dynamic_events']:,} dynamic ({100 * b['fraction_dynamic']:.2f} %); "
                      f"wall time {b['wall_s']:.0f} s ({b['events_per_s_overall']:,.0f} events/s overall, static pass "
                      f"{b['static_events_per_s']:,.0f} events/s); peak memory {b['peak_rss_coordinator_MB']:.0f} MB "
                      f"(coordinator) and {b['peak_rss_worker_MB']:.0f} MB (largest worker); dynamics on every event "
                      f"would take {b['every_event_estimate_s']:,.0f} s ({b['baseline_dynamic_s_per_event_one_core'] * 1e3:.0f} ms "
                      f"an event on one core): {b['speedup_vs_every_event']:.0f} × faster; one year extrapolated "
                      f"linearly from that run: {b['year_extrapolated_s'] / 60:.0f} min with the code of {b['date']} "
                      f"(the present code's year: \"Performance and limits\" below)."]
    lines += ["", END]
    return "\n".join(lines)


def write_page(numbers: dict) -> None:
    text = PAGE.read_text()
    a, b = text.index(START), text.index(END) + len(END)
    text = text[:a] + render(numbers) + text[b:]
    if "exact_peaks" in numbers:
        a, b = text.index(EXACT_START), text.index(EXACT_END) + len(EXACT_END)
        text = text[:a] + render_exact(numbers) + text[b:]
    if "knot_example" in numbers:
        a, b = text.index(KNOT_START), text.index(KNOT_END) + len(KNOT_END)
        text = text[:a] + render_knot(numbers) + text[b:]
    PAGE.write_text(text)


def main() -> None:
    if "--page" in sys.argv:  # the stored numbers, with the benchmark's if it has run since
        numbers = json.loads(NUMBERS.read_text())
        if BENCH.is_file():
            numbers["benchmark"] = json.loads(BENCH.read_text())
            NUMBERS.write_text(json.dumps(numbers, indent=1) + "\n")
        write_page(numbers)
        return
    if "--knot" in sys.argv:  # the knot example alone, into the stored numbers
        numbers = json.loads(NUMBERS.read_text())
        numbers["knot_example"] = knot_example()
        NUMBERS.write_text(json.dumps(numbers, indent=1) + "\n")
        write_page(numbers)
        return
    numbers = {"example": example(), "exactness": exactness(), "exact_peaks": exact_peaks(),
               "knot_example": knot_example()}
    if BENCH.is_file():
        numbers["benchmark"] = json.loads(BENCH.read_text())
    NUMBERS.write_text(json.dumps(numbers, indent=1) + "\n")
    write_page(numbers)


if __name__ == "__main__":
    main()
