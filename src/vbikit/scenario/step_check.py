"""Step control for the requested outputs: the automatic step checked by step halving.

The automatic step rules (``vbikit.solve.timestep``) resolve the vehicle, the road and the first
bridge modes, which is what deflections need.  Bending moments, shears and reactions weigh the
higher modes far more (curvature and its slope grow with the mode number), and on supports that
move — elastic bearings, a vehicle crossing a pier — those modes keep ringing; their peaks are
then under-sampled at the automatic step (docs/verification.md, "Convergence of every output").

So a run that asks for load effects at an automatic step starts at the step the effects need when
that is shorter (``load_effect_plan``: the rule of ``vbikit.analysis.effect_step``, which the
Python path's ``load_effect_response`` checks too), and is repeated at half the step until
no impact factor of the report (every point, every load effect) changes by more than
``STEP_TOLERANCE`` between two successive steps (Richardson's step-doubling estimate of the
coarser run's error), within ``MAX_HALVINGS`` halvings and the run's step budget.  The finer run
is the one reported.  If the budget ends first, the report says which impact factors are not
converged, by how much, and the step the observed rate of convergence suggests would do.

A train of moving axle loads (``is_train``: a ``TRAIN_PRESETS`` vehicle) is checked the same way,
its peak deck accelerations too (relative change at most ``STEP_TOLERANCE``): each axle entering
and leaving the deck rings modes far above the first, which the automatic step (a hundredth of the
first period) does not resolve.
"""
from __future__ import annotations

import logging
import math
from dataclasses import replace
from typing import Any, Callable, Iterator, Mapping, Sequence

from vbikit.analysis.checks import Flag, add_flags
from vbikit.analysis.effect_step import STEP_TOLERANCE, load_effect_step
from vbikit.solve.budget import BudgetError, Limits
from vbikit.solve.crossing import Crossing
from vbikit.solve.plan import RunPlan

log = logging.getLogger(__name__)

#: halvings of the automatic step at most (the finest run has 2^MAX_HALVINGS times its steps)
MAX_HALVINGS = 6


def asks_for_load_effects(scenario: Any) -> bool:
    """Whether a scenario's [response] asks for moments, shears or reactions (the ones a run reports by
    default are not asked for)."""
    return any(getattr(scenario.response, key) is not None for key in ("moment", "shear", "reaction"))


def is_train(scenario: Any) -> bool:
    """Whether a scenario's vehicles include a train of moving axle loads (``TRAIN_PRESETS``)."""
    from vbikit.vehicle.trains import TRAIN_PRESETS

    specs = [scenario.vehicle] if scenario.vehicle is not None else list(scenario.vehicles or ())
    return any(spec.model in TRAIN_PRESETS for spec in specs)


#: the peaks a train's step check compares (relative change), beside every impact factor (absolute change)
_RELATIVE = ("max_abs_acceleration",)


def checked_values(summary: Mapping[str, Any], relative: tuple[str, ...] = (), prefix: str = "") \
        -> Iterator[tuple[str, float, bool]]:
    """Every finite ``*impact_factor`` number in a run's summary (top level, ``points``, load effect
    blocks), with a path-like name, and the peaks named in ``relative`` (flagged True: compared by
    their relative change)."""
    for key, value in summary.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            yield from checked_values(value, relative, name + ".")
        elif isinstance(value, list):
            for i, item in enumerate(value):
                if isinstance(item, Mapping):
                    yield from checked_values(item, relative, f"{name}[{item.get('name', i)}].")
        elif isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
            if key.endswith("impact_factor"):
                yield name, float(value), False
            elif key in relative:
                yield name, float(value), True


def _largest_change(a: Mapping[str, Any], b: Mapping[str, Any], relative: tuple[str, ...] = ()) -> tuple[float, str]:
    old = {name: value for name, value, _ in checked_values(a, relative)}
    change, worst = 0.0, ""
    for name, value, rel in checked_values(b, relative):
        if name not in old:
            continue
        step = abs(value - old[name]) / (abs(old[name]) if rel else 1.0) if not (rel and old[name] == 0.0) else 0.0
        if step > change:
            change, worst = step, name
    return change, worst


def load_effect_plan(crossing: Crossing, effects: Sequence[Any], run_plan: RunPlan | None = None,
                     limits: Limits | None = None) -> RunPlan | None:
    """The run plan of ``crossing`` (automatic step) at the step its load ``effects`` need
    (``vbikit.analysis.effect_step.load_effect_step``) when that is shorter than the automatic one
    (``run_plan``, or planned here); ``run_plan`` unchanged if not, or if the budget refuses the
    shorter step (the halving check and the report's step warning then say so)."""
    from vbikit.solve.plan import plan_run

    current = run_plan if run_plan is not None else plan_run(crossing, limits)
    best = load_effect_step(crossing, effects)
    if not best < current.dt:
        return current
    try:
        finer = plan_run(replace(crossing, dt=best), limits)
    except BudgetError:
        log.warning("the step %.3g s the load effects need is beyond the step budget: running at %.3g s", best, current.dt)
        return current
    log.info("load effects: step %.3g s instead of the automatic %.3g s", best, current.dt)
    return finer


def effect_step_warnings(scenario: Any, crossing: Crossing, effects: Sequence[Any], run_plan: RunPlan,
                         limits: Limits | None = None) -> list[str]:
    """The load-effect step warnings (``vbikit.analysis.effect_step.step_warning``) a run of
    ``scenario`` reports, without running it: they need the bridge, the wheel lines, the top speed
    and the step, not the response.  The step is the one the run starts at (``vbikit.scenario.pipeline.run_crossing``):
    ``run_plan``'s, or, when the scenario asks for moments, shears or reactions or runs a train at an
    automatic step, the one ``load_effect_plan`` chooses (the halving that follows only refines it)."""
    from vbikit.analysis.effect_step import step_warning

    if (asks_for_load_effects(scenario) or is_train(scenario)) and crossing.dt is None:
        run_plan = load_effect_plan(crossing, effects, run_plan, limits) or run_plan
    found = [step_warning(crossing, e, float(run_plan.dt))[0] for e in effects]
    return list(dict.fromkeys(w for w in found if w))


def converge_step(report: Any, crossing: Crossing, rerun: Callable[[RunPlan], Any],
                  limits: Limits | None = None, train: bool = False) -> Any:
    """The report of ``crossing`` at the automatic step halved until its impact factors change by at
    most ``STEP_TOLERANCE`` (``report``: the run at the automatic step; ``rerun(run_plan)``: the same
    run by a checked plan of ``crossing`` at a given dt).  Adds a warning to the returned report's
    summary if they never do.  With ``train`` the peak deck accelerations are checked too, by their
    relative change (a train's axle loads ring the higher modes, which the automatic step does not
    resolve: HSLM-A1 on a 20 m span, 1.4 … 4.7 % low at 150 … 300 km/h)."""
    from vbikit.solve.plan import plan_run

    dt = float(report.result.integration_dt or report.result.dt)
    changes: list[float] = []
    worst = ""
    for _ in range(MAX_HALVINGS):
        finer = replace(crossing, dt=dt / 2)
        try:
            run_plan = plan_run(finer, limits)
        except BudgetError:
            break
        new = rerun(run_plan)
        change, worst = _largest_change(report.summary, new.summary, _RELATIVE if train else ())
        changes.append(change)
        log.info("step check: dt %.3g s -> %.3g s, largest change %.2g (%s)", dt, dt / 2, change, worst)
        report, dt = new, dt / 2
        if change <= STEP_TOLERANCE:
            return report
    if changes:
        add_flags(report.summary, [Flag("step_not_converged", _advice(changes, worst, dt), output=worst or None,
                                        value=changes[-1], threshold=STEP_TOLERANCE)])
    return report


def half_step_check(report: Any, crossing: Crossing, rerun: Callable[[RunPlan], Any],
                    limits: Limits | None = None) -> dict[str, Any]:
    """How good a single run's automatic step is: the same run once more at half the step (``rerun(run_plan)``, as
    ``converge_step``'s), and the largest change of a deflection or strain impact factor of its report (every point
    and girder; the load effects have their own step rule and warning, ``vbikit.analysis.effect_step``).  By
    Richardson's step doubling the run's own error is about that change times 1 / (1 − 2⁻ᵖ), p ≈ 2 for the exact
    integrator (4/3 of it).  The report stays the run at the automatic step; above ``STEP_TOLERANCE`` its summary
    gets ``step_not_converged``.  Returns the summary's ``step_check``: ``dt`` [s] the half step, ``largest_change``
    [-] and ``output`` (None, with ``note``, when the half-step run is above the step budget)."""
    from vbikit.solve.plan import plan_run

    dt = float(report.result.integration_dt or report.result.dt)
    try:
        run_plan = plan_run(replace(crossing, dt=dt / 2), limits)
    except BudgetError as err:
        return {"dt": dt / 2, "largest_change": None, "output": None,
                "note": f"not run: the run at half the step is above the run's budget ({err})"}
    finer = rerun(run_plan).summary
    change, worst = _largest_change(_deflections(report.summary), _deflections(finer))
    log.info("half-step check: dt %.3g s -> %.3g s, largest change %.2g (%s)", dt, dt / 2, change, worst)
    if change > STEP_TOLERANCE:
        add_flags(report.summary, [Flag("step_not_converged", _advice([change], worst, dt / 2), output=worst or None,
                                        value=change, threshold=STEP_TOLERANCE)])
    return {"dt": dt / 2, "largest_change": change, "output": worst or None}


#: the summary's load-effect blocks and their headline keys (``moment_impact_factor`` …): the half-step check leaves
#: them to their own step rule (``vbikit.analysis.effect_step``: a warning naming the step they need) and halving
_LOAD_EFFECT_KEYS = ("moment", "shear", "reaction")


def _deflections(summary: Mapping[str, Any]) -> dict[str, Any]:
    """``summary`` without its load effects (``_LOAD_EFFECT_KEYS``): the deflection and strain impact factors of
    every point and girder, which the half-step check compares."""
    return {k: v for k, v in summary.items() if not k.startswith(_LOAD_EFFECT_KEYS)}


def _advice(changes: list[float], worst: str, dt: float) -> str:
    text = (f"{worst} is not converged in the time step: it changed by {changes[-1]:.3g} when the step was halved to "
            f"{dt:.3g} s (tolerance {STEP_TOLERANCE:g})")
    if len(changes) >= 2 and 0.0 < changes[-1] < changes[-2]:
        rate = changes[-1] / changes[-2]
        more = math.ceil(math.log(STEP_TOLERANCE / changes[-1]) / math.log(rate))
        text += f"; at the observed rate a step of about {dt / 2 ** more:.2g} s would be (set crossing.dt)"
    else:
        text += "; set a smaller crossing.dt, or raise the step budget (--max-steps)"
    return text
