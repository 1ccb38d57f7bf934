"""Running one scenario for the command line: :func:`execute` is the only place that does.

``execute(load, limits) -> Run`` checks, simulates and summarises one scenario; ``Run.summary``
is the dict ``vbikit run --json`` prints.  Every scenario command (run, demo, compare-tires)
calls it; nothing else in the command line chains the library's steps.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

from vbikit.cli.guard import guard, warn


@dataclass
class Run:
    """One simulated scenario as the commands render it.

    ``name`` the scenario's name; ``result`` the :class:`~vbikit.solve.CrossingResult`;
    ``response`` the response point's :class:`~vbikit.analysis.PointResponse`; ``summary`` the
    JSON summary; ``girders`` the per-girder responses (decks) or None; ``effects`` the
    load-effect responses (for the CSV histories).
    """

    name: str
    result: Any
    response: Any
    summary: dict[str, Any]
    girders: Any = None
    effects: Any = ()


# --- the one function that runs a scenario -------------------------------------------------------
def execute(load: Callable[[], Any], limits: Any = None) -> Run:
    """Check (``load()`` returns a Scenario; every check of :func:`vbikit.scenario.preflight.preflight`),
    simulate and summarise; user errors exit with code 2, the summary's warnings go to stderr."""
    from vbikit._files import json_safe
    from vbikit.analysis import girder_responses, point_response, summary
    from vbikit.scenario.preflight import preflight, scenario_inputs
    from vbikit.solve import simulate

    def work() -> Run:
        scenario = load()
        plan = preflight(scenario, limits)
        built = plan.built
        result = simulate(built.crossing, limits)
        response = point_response(result, built.response_x, built.response_y)
        girders = girder_responses(result, built.response_x, built.response_y)
        s = summary(result, response, girders, built.response_girder)
        s["warnings"] += [w for w in plan.warnings if w not in s["warnings"]]
        s["inputs"] = scenario_inputs(scenario, plan)
        effects = _load_effects(result, built, s)
        nonfinite = json_safe(s)[1]  # the JSON outputs write these as null (render.json_text), the text report as nan
        s["warnings"] += [f"{key} is not a finite number (written as null)" for key in nonfinite]
        return Run(scenario.name, result, response, s | _labels(scenario, s), girders, effects)

    run_ = guard(work)
    warn(run_.summary["warnings"])
    return run_


def _load_effects(result: Any, built: Any, s: dict[str, Any]) -> list[Any]:
    """Moment / shear / reaction blocks and design-code allowances added to the summary ``s``;
    returns the load-effect responses (for the histories)."""
    from vbikit.analysis.effects import load_effect_report

    report, responses = load_effect_report(result, built.load_effects, built.load_effect_method, s["response_x"],
                                           s["response_y"])
    s.update(report)
    return responses


def _labels(scenario: Any, summary_: dict[str, Any]) -> dict[str, Any]:
    """The ``units`` map of a summary's keys and the ``references`` of the scenario's models."""
    from vbikit.analysis import summary_units
    from vbikit.scenario.cite import scenario_references

    refs = [{"key": r.key, "citation": r.text(), **({"doi": r.doi} if r.doi else {})} for r in scenario_references(scenario)]
    return {"units": summary_units(summary_), "references": refs}
# --- end of the function that runs a scenario ----------------------------------------------------
