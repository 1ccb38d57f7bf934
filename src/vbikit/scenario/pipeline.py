"""The run pipeline: plan → run → report, the one path from a scenario to its report.

``vbikit run``, ``vbikit demo``, ``vbikit compare-tires`` and Python users call [`run`][vbikit.scenario.run];
studies and traffic streams, which batch many crossings, use the same build
([`vbikit.scenario.build.build`][vbikit.scenario.build.build]), checks (``vbikit.scenario.preflight.preflight``) and
reductions (the output catalogue [`vbikit.outputs`][vbikit.outputs], ``vbikit.analysis.response``).

* **plan**: build the scenario's models and check everything before integrating
  (``preflight``: files, parameters, time step, budgets,
  warnings);
* **run**: integrate the coupled equations once ([`vbikit.solve.simulate`][vbikit.solve.simulate.simulate]);
* **report**: read every response point, girder and load effect from the histories and
  summarise them (``report_crossing``): a [`Report`][vbikit.scenario.Report] whose
  ``summary`` is exactly the JSON ``vbikit run --json`` prints.
"""
from __future__ import annotations

import logging
from pathlib import Path
from typing import Any, Mapping

from vbikit.analysis.checks import Flag, add_flags, effect_static_flags, implausible_deflection_flags, point_flags
from vbikit.analysis.effects import effect_sign_flags, load_effect_report
from vbikit.analysis.impact import static_modal_history
from vbikit.analysis.plan import ResponsePlan
from vbikit.analysis.response import girder_responses, plan_responses, point_entries, summary, summary_units
from vbikit.scenario.preflight import Plan, preflight, scenario_inputs
from vbikit.scenario.report import Report
from vbikit.scenario.schema import Scenario, ScenarioError, load_scenario, parse_scenario, scenario_from_toml
from vbikit.solve.budget import Limits
from vbikit.solve.crossing import Crossing, require_every_result
from vbikit.solve.plan import RunPlan
from vbikit.solve.result import CrossingResult

ScenarioSource = Scenario | Mapping[str, Any] | str | Path

log = logging.getLogger(__name__)


def _names_a_file(source: str) -> bool:
    """A string that is a file name rather than TOML text: one line ending in .toml, with no ``=``,
    or an existing file."""
    if "\n" in source:
        return False
    if source.endswith(".toml") or "=" not in source:
        return True
    try:
        return Path(source).is_file()
    except OSError:  # e.g. a name too long for the file system: TOML text
        return False


def scenario_of(source: ScenarioSource, base_dir: str | Path | None = None) -> Scenario:
    """A validated [`Scenario`][vbikit.scenario.Scenario] from a path, a TOML string, a dict (the parsed TOML) or a
    Scenario; relative file names resolve against ``base_dir`` (default: the file's folder, else
    the working directory)."""
    if isinstance(source, Scenario):
        return source
    if isinstance(source, Mapping):
        return parse_scenario(dict(source), base_dir if base_dir is not None else ".")
    if not isinstance(source, (str, Path)):  # (a trial's vbikit.run(42) failed inside with a TypeError)
        raise ScenarioError(f"a scenario is a file path, TOML text, a dict of its tables or a Scenario (or, for "
                            f"vbikit.run, a Crossing), got {type(source).__name__}")
    if isinstance(source, Path) or _names_a_file(source):
        path = Path(source)
        scenario = load_scenario(path)  # (the one reader's errors: not found, a folder or device, not text …)
        if base_dir is not None:
            scenario._base_dir = Path(base_dir)
        return scenario
    return scenario_from_toml(source, base_dir if base_dir is not None else ".")


def run(source: ScenarioSource | Crossing, response: ResponsePlan | None = None, *, limits: Limits | None = None,
        base_dir: str | Path | None = None, name: str = "", step_check: bool = True) -> Report:
    """Run one crossing and return its [`Report`][vbikit.scenario.Report].

    Parameters
    ----------
    source
        A scenario: a file path, TOML text, a dict of the parsed TOML, or a
        [`Scenario`][vbikit.scenario.Scenario] — or a built [`Crossing`][vbikit.solve.Crossing].
    response : ResponsePlan, optional
        With a Crossing: the response points and load effects to read (default the bridge's
        default point, no load effects).  Scenarios carry their own ([response]).
    limits : Limits, optional
        Memory and step budgets (default 4 GiB, 5e6 steps); the run is refused above them before
        it starts.
    base_dir
        Folder relative file names in the scenario resolve against.
    name
        Label of a Crossing's report (a scenario's is its ``name``).
    step_check
        At an automatic step, run the crossing once more at half the step and state in the summary's ``step_check``
        how much its deflection and strain impact factors and its peak deck accelerations change
        (``vbikit.scenario.step_check.half_step_check``;
        about 1.6 times the run's cost).  False leaves it out (a loop over many runs whose step is checked
        otherwise); the load effects' own halving, when a scenario asks for them, runs either way.

    Raises
    ------
    ScenarioError, BudgetError, UnstableTimeStepError
        Bad input, found before any computation.
    """
    if isinstance(source, Crossing):
        return run_crossing(source, response or ResponsePlan(), limits=limits, name=name, half_step=step_check)
    if response is not None:
        raise ScenarioError("a scenario carries its own response plan ([response]); pass response= only with a Crossing")
    return run_planned(preflight(scenario_of(source, base_dir), limits), limits, step_check=step_check)


def check_random_road(scenario: Scenario) -> None:
    """Refuse (ScenarioError naming the key) a road a random-vibration run cannot take: not a random
    class, or with defects (the road must be a Gaussian process given by its PSD); and a step for
    deflections only (``crossing.resolve``)."""
    road = scenario.road
    if road.road_class == "none" or road.profile_file:
        raise ScenarioError("road.class: a random-vibration run needs a random road (class A…H, good/average/poor or "
                            "psd), not a smooth or measured one")
    if road.defects:
        raise ScenarioError("road.defects: a random-vibration run takes the road as a Gaussian process only; remove "
                            "the defects (or run them with Monte Carlo: several road.seed values)")
    require_every_result(scenario.crossing.resolve, "a random-vibration run takes the step for every result (its loads "
                         "are held linear)", ScenarioError)


def run_random(source: ScenarioSource, *, limits: Limits | None = None, base_dir: str | Path | None = None,
               quantiles: tuple[float, ...] | None = None, peaks: str = "all"):
    """The scenario's crossing on its random road without sampling: mean and σ histories by
    pseudo-excitation and the impact factor's distribution (``vbikit.random.response``); the
    ``vbikit.random.response.RandomResponse`` whose ``summary`` is exactly what
    ``vbikit run --random --json`` prints (``peaks``: which channels get peak statistics,
    ``vbikit.random.response.PEAKS``; "study": only what a PEM study stores).

    Raises
    ------
    ScenarioError
        A road that is not a random class (A…H or psd), a road with defects, or disk tires.
    """
    quantiles = checked_quantiles(quantiles)  # (before any computation)
    scenario = scenario_of(source, base_dir)
    check_random_road(scenario)
    return _random_runs([preflight(scenario, limits)], [scenario], [_pseudo_road(scenario)], quantiles, peaks)[0]


def checked_quantiles(quantiles: Any) -> tuple[float, ...] | None:
    """The impact factor's quantiles of a random run as given: None (``vbikit.random.response.QUANTILES``) or
    probabilities in (0, 1), else ScenarioError naming ``quantiles`` and the range, before any computation (a
    trial's ``quantiles=(1.5,)`` failed after the run, in numpy's words)."""
    from vbikit._validation import number

    if quantiles is None:
        return None
    values = list(quantiles) if isinstance(quantiles, (list, tuple)) else [quantiles]
    if not values:
        raise ScenarioError("quantiles: give at least one probability in (0, 1), or None for the default")
    return tuple(number(q, "quantiles", 0.0, 1.0, lo_open=True, hi_open=True, error=ScenarioError) for q in values)


def run_random_levels(sources: list[ScenarioSource], *, limits: Limits | None = None,
                      base_dir: str | Path | None = None, quantiles: tuple[float, ...] | None = None,
                      peaks: str = "all") -> list:
    """``run_random`` of each scenario of ``sources``, one pseudo-excitation for all when they differ
    only in the road's level (``road.class`` or ``road.phi0``) and run on one time step
    (``vbikit.random.response.random_responses``: the same numbers as ``run_random`` one by one);
    otherwise one by one.  A PEM study's cells over ``road.class`` run so."""
    from vbikit.random.response import level_factor

    quantiles = checked_quantiles(quantiles)
    scenarios = [scenario_of(src, base_dir) for src in sources]
    for scenario in scenarios:
        check_random_road(scenario)

    def rest(scenario: Scenario) -> dict:
        d = scenario.model_dump()
        for key in ("road_class", "phi0"):
            d["road"].pop(key, None)
        return d

    plans = [preflight(s, limits) for s in scenarios]
    pseudo = [_pseudo_road(s) for s in scenarios]
    first = rest(scenarios[0])
    shared = (len(scenarios) > 1 and all(rest(s) == first for s in scenarios[1:])
              and all(p.run.dt == plans[0].run.dt for p in plans)
              and all(level_factor(r, pseudo[0]) is not None for r in pseudo))
    if shared:
        return _random_runs(plans, scenarios, pseudo, quantiles, peaks)
    if len(scenarios) > 1:
        log.info("random runs: %d scenarios that differ in more than the road's level, run one by one", len(scenarios))
    return [_random_runs([p], [s], [r], quantiles, peaks)[0] for p, s, r in zip(plans, scenarios, pseudo)]


def _pseudo_road(scenario: Scenario):
    """The scenario's random road as PEM takes it (``vbikit.random.PseudoRoad``)."""
    from vbikit.random import PseudoRoad
    from vbikit.scenario.build import road_psd

    road = scenario.road
    return PseudoRoad(road_psd(road), road.right_coherence, two_lines=road.right_coherence < 1.0)


def _random_runs(plans: list[Plan], scenarios: list[Scenario], roads: list, quantiles: tuple[float, ...] | None,
                 peaks: str) -> list:
    """The random responses of checked scenarios on their ``roads`` (``_pseudo_road``), which differ at
    most in level, on the first plan's crossing (``vbikit.random.response.random_responses``: one
    pseudo-excitation), each summary named and carrying its plan's warnings."""
    from vbikit.random import NonlinearTireError
    from vbikit.random.response import QUANTILES, random_responses

    plan = plans[0]
    try:
        out = random_responses(plan.built.crossing, plan.built.plan, roads, plan.run.dt, data=plan.run.kernel_data,
                               quantiles=quantiles or QUANTILES, peaks=peaks)
    except NonlinearTireError as err:
        raise ScenarioError(f"tire.model: {err}") from None
    for rr, scenario, p in zip(out, scenarios, plans):
        rr.summary = {"name": scenario.name, **rr.summary}
        add_flags(rr.summary, p.flags)
    return out


def run_planned(plan: Plan, limits: Limits | None = None, step_check: bool = True) -> Report:
    """Integrate a checked scenario (``preflight``) and report it,
    with the scenario's inputs, warnings, units and references in the summary."""
    from vbikit._files import json_safe

    scenario = plan.scenario
    from vbikit.scenario.step_check import asks_for_load_effects, is_train

    train = is_train(scenario)
    report = run_crossing(plan.built.crossing, plan.built.plan, limits=limits, name=scenario.name, run_plan=plan.run,
                          check_step=asks_for_load_effects(scenario) or train, train=train, half_step=step_check)
    s = report.summary
    # (the preflight's implausible_deflection is its estimate before the run: the run's own, from its peaks, replaces it)
    add_flags(s, [f for f in plan.flags if f.code != "implausible_deflection"])
    s["inputs"] = scenario_inputs(scenario, plan)
    nonfinite = json_safe(s)[1]  # JSON outputs write these as null, the text report as nan
    add_flags(s, [Flag("non_finite", f"{key} is not a finite number (written as null)", output=key) for key in nonfinite])
    s["references"] = _references(scenario)
    s["units"] = summary_units(s)  # (every key's, the references' too: "" for words)
    return report


def _references(scenario: Scenario) -> list[dict[str, str]]:
    from vbikit.scenario.cite import scenario_references

    return [{"key": r.key, "citation": r.text(), **({"doi": r.doi} if r.doi else {})} for r in scenario_references(scenario)]


def run_crossing(crossing: Crossing, plan: ResponsePlan, *, limits: Limits | None = None, name: str = "",
                 run_plan: RunPlan | None = None, check_step: bool | None = None, train: bool = False,
                 half_step: bool = False) -> Report:
    """Simulate ``crossing`` (with its checked [`RunPlan`][vbikit.solve.plan.RunPlan] if the
    preflight made one: step, budgets and tables are not computed again) and reduce it by ``plan``
    (``report_crossing``).  With ``check_step`` (default: the plan reads load effects) at an
    automatic step, the step is halved until the impact factors converge
    (``vbikit.scenario.step_check``); a scenario checks it when its [response] asks for moments,
    shears or reactions (not for the ones reported by default) or runs a train (``train``: its peak
    accelerations are checked too); otherwise, with ``half_step`` (a scenario's single run), the run at an automatic
    step is run once more at half of it and the summary's ``step_check`` says how much its impact factors and peak
    deck accelerations change
    (``vbikit.scenario.step_check.half_step_check``)."""
    from vbikit.scenario.step_check import converge_step, half_step_check, load_effect_plan
    from vbikit.solve import simulate

    if check_step is None:
        check_step = bool(plan.load_effects)
    if check_step and crossing.dt is None:  # start at the step the load effects need (analysis.effect_step)
        run_plan = load_effect_plan(crossing, plan.load_effects, run_plan, limits)
    report = report_crossing(simulate(crossing if run_plan is None else run_plan.crossing, limits, plan=run_plan),
                             plan, name)
    rerun = lambda finer: report_crossing(simulate(finer.crossing, limits, plan=finer), plan, name)  # noqa: E731
    if check_step and crossing.dt is None:  # moments, shears, reactions: confirm the step by halving
        report = converge_step(report, crossing, rerun, limits, train=train)
    elif half_step and crossing.dt is None:  # say how good the automatic step is
        report.summary["step_check"] = half_step_check(report, crossing, rerun, limits)
    return report


def report_crossing(result: CrossingResult, plan: ResponsePlan, name: str = "") -> Report:
    """Read every response point, the girders at the headline point's section and the load
    effects from ``result``; the summary holds the catalogue's outputs ([`vbikit.outputs`][vbikit.outputs]) of
    the headline point at the top level and of every point under ``points``, the per-girder
    values, the load-effect blocks with the design-code allowances and the run's warnings."""
    first = plan.first
    xi_static = static_modal_history(result)
    points = plan_responses(result, plan, xi_static)
    girders = girder_responses(result, first.x, points[0].y, xi_static)
    effects_summary, effects = load_effect_report(result, plan.load_effects, plan.load_effect_method,
                                                  points[0].x, points[0].y)
    first_effects = {kind: next(r for r in effects if r.effect is e) for kind, e in plan.first_effects.items()}
    s = summary(result, points[0], girders, first.girder, point_entries(result, plan, points), first_effects)
    s.update(effects_summary)
    add_flags(s, [Flag("effect_step", r.step_warning, output=r.effect.kind, subject=r.effect.label,
                       value=float(result.integration_dt or result.dt), threshold=float(r.recommended_dt))
                  for r in effects if r.step_warning])
    add_flags(s, effect_static_flags([(r.effect.kind, r.effect.label, r.effect.units, r.impact.static_peak,
                                       r.impact.impact_factor) for r in effects]))
    add_flags(s, effect_sign_flags(effects))
    for point_name, p in zip(plan.point_names[1:], points[1:]):  # not ``name``: the report's label
        add_flags(s, point_flags(result.crossing, p.x, p.y, point_name))
    add_flags(s, implausible_deflection_flags(  # a unit mistake in EI or the mass: every point and girder, the longest span
        max(result.crossing.bridge.span_lengths),
        [(f"point {n}", r.displacement_impact.static_peak, None, n) for n, r in zip(plan.point_names, points)]
        + [(f"Girder {g}", r.displacement_impact.static_peak, g, None) for g, r in enumerate(girders, 1)]))
    return Report(name, result, plan, points, girders, effects, s)
