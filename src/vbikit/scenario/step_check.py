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

Every other run checks its peak deck accelerations (every response point and girder, by their
relative change, ``PEAK_ACCELERATIONS``) without halving for them: a single run's half-step check
reports their largest change beside the impact factors', a load-effect halving compares them over its
last halving; above ``STEP_TOLERANCE`` the summary gets ``step_not_converged`` naming the peak.
A moving force's peak acceleration, for one, rings the highest retained modes: it changes by 0.77 %
at half the automatic step and by 3.7 % at a quarter of it (docs/verification.md), while its
deflection impact factors are converged; so do the deck's accelerations under a stiff rail contact.
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


#: the summary's peak deck accelerations [m/s²] (every response point's and every girder's), which the step checks
#: compare by their relative change (a train's halving converges them; every other run states and flags them)
PEAK_ACCELERATIONS = ("max_abs_acceleration", "girder_max_abs_acceleration")
#: a peak acceleration below this share of the run's largest one changes relative to that share of it: a point
#: near a support, whose peak is near zero, does not flag a round-off change as a relative one
ACCELERATION_FLOOR = 0.01


def is_acceleration(output: str | None) -> bool:
    """Whether a step check's ``output`` (a flag's, or ``step_check``'s) names a peak acceleration
    (``PEAK_ACCELERATIONS``), not an impact factor."""
    return bool(output) and output.rsplit(".", 1)[-1].split("[", 1)[0] in PEAK_ACCELERATIONS


def checked_values(summary: Mapping[str, Any], relative: tuple[str, ...] = (), prefix: str = "") \
        -> Iterator[tuple[str, float, bool]]:
    """Every finite ``*impact_factor`` number in a run's summary (top level, ``points``, load effect
    blocks) and every entry of an ``*impact_factors`` list (the girders'), with a path-like name, and the
    peaks named in ``relative`` (flagged True: compared by their relative change; a list of numbers, as
    the girders' peaks, by its entries)."""
    for key, value in summary.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            yield from checked_values(value, relative, name + ".")
        elif isinstance(value, list):
            for i, item in enumerate(value):
                if isinstance(item, Mapping):
                    yield from checked_values(item, relative, f"{name}[{item.get('name', i)}].")
                elif _finite(item) and (key in relative or key.endswith("impact_factors")):
                    yield f"{name}[{i}]", float(item), key in relative
        elif _finite(value):
            if key.endswith("impact_factor"):
                yield name, float(value), False
            elif key in relative:
                yield name, float(value), True


def _finite(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _changes(a: Mapping[str, Any], b: Mapping[str, Any], relative: tuple[str, ...] = (),
             only_relative: bool = False) -> dict[str, float]:
    """Every change from summary ``a`` to summary ``b`` by name: of an impact factor absolute, of a peak named in
    ``relative`` relative to its value in ``a`` (at least ``ACCELERATION_FLOOR`` of the largest such peak of ``a``);
    with ``only_relative`` of those peaks alone."""
    old = {name: (value, rel) for name, value, rel in checked_values(a, relative) if rel or not only_relative}
    floor = ACCELERATION_FLOOR * max((abs(v) for v, rel in old.values() if rel), default=0.0)
    out = {}
    for name, value, rel in checked_values(b, relative):
        if name in old:
            scale = max(abs(old[name][0]), floor) if rel else 1.0
            out[name] = abs(value - old[name][0]) / scale if scale > 0.0 else 0.0
    return out


def _largest_change(a: Mapping[str, Any], b: Mapping[str, Any], relative: tuple[str, ...] = (),
                    only_relative: bool = False) -> tuple[float, str]:
    """The largest of ``_changes`` and its name (0 and "" for none)."""
    return _largest(_changes(a, b, relative, only_relative))


def _largest(changes: dict[str, float]) -> tuple[float, str]:
    """The largest of ``changes`` (by name) and its name (0 and "" for none)."""
    worst = max(changes, key=changes.__getitem__, default="")  # (the first of equal ones)
    return (changes[worst], worst) if worst and changes[worst] > 0.0 else (0.0, "")


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
    resolve: HSLM-A1 on a 20 m span, 1.4 … 4.7 % low at 150 … 300 km/h).  Without ``train`` the peak deck
    accelerations' change over the last halving is compared, not halved for: flagged above the tolerance
    (``acceleration_flags``; nothing when the budget refuses the first halving).  The returned summary's
    ``step_check`` says what the halving found, as ``half_step_check``'s does for a single run: ``dt`` [s] the
    returned run's step (the finer of the last pair compared), ``largest_change`` [-] of an impact factor (load
    effects included) over the last halving and its ``output``, ``halvings``, ``converged``, the peak accelerations'
    ``acceleration_change`` and ``acceleration_output``; None, with ``note``, when the budget refused the first
    halving."""
    from vbikit.solve.plan import plan_run

    dt = float(report.result.integration_dt or report.result.dt)
    changes: list[float] = []
    worst = ""
    previous, converged = None, False
    refused = ""
    for _ in range(MAX_HALVINGS):
        finer = replace(crossing, dt=dt / 2)
        try:
            run_plan = plan_run(finer, limits)
        except BudgetError as err:
            refused = str(err)
            break
        new = rerun(run_plan)
        change, worst = _largest_change(report.summary, new.summary, PEAK_ACCELERATIONS if train else ())
        changes.append(change)
        log.info("step check: dt %.3g s -> %.3g s, largest change %.2g (%s)", dt, dt / 2, change, worst)
        previous, report, dt = report, new, dt / 2
        if change <= STEP_TOLERANCE:
            converged = True
            break
    if changes and not converged:
        add_flags(report.summary, [Flag("step_not_converged", _advice(changes, worst, dt, is_acceleration(worst)),
                                        output=worst or None, value=changes[-1], threshold=STEP_TOLERANCE)])
    (acc_change, acc_worst), acc_above = (None, ""), []
    if previous is not None and not train:
        (acc_change, acc_worst), acc_flags, acc_above = acceleration_flags(previous.summary, report.summary, dt)
        add_flags(report.summary, acc_flags)
    report.summary["step_check"] = {
        "dt": dt, "largest_change": changes[-1] if changes else None, "output": worst or None,
        "halvings": len(changes), "converged": converged, "for": "peak accelerations" if train else "load effects",
        "acceleration_change": acc_change,
        "acceleration_output": acc_worst or None, "accelerations_not_converged": acc_above,
        **({} if changes else {"note": f"not run: the run at half the step is above the run's budget ({refused})"})}
    return report


def acceleration_flags(coarse: Mapping[str, Any], fine: Mapping[str, Any],
                       dt: float) -> tuple[tuple[float, str], list[Flag], list[str]]:
    """The largest relative change of a peak deck acceleration (``PEAK_ACCELERATIONS``) from the summary ``coarse``
    to ``fine`` (run at half of its step, ``dt`` [s]) and its name, the ``step_not_converged`` flag when it is
    above ``STEP_TOLERANCE`` (naming it, and how many more are), and every peak above it by name."""
    changes = _changes(coarse, fine, PEAK_ACCELERATIONS, only_relative=True)
    change, worst = _largest(changes)
    above = [name for name, c in changes.items() if c > STEP_TOLERANCE]
    # the top-level peak is the first point's (``points``), counted once
    distinct = len(above) - ("max_abs_acceleration" in above and any(n.startswith("points[") for n in above))
    more = f" ({distinct - 1} more peak acceleration{'s' if distinct > 2 else ''} above the tolerance)" \
        if distinct > 1 else ""
    flags = [Flag("step_not_converged", _advice([change], worst, dt, relative=True, halved_for_it=False) + more,
                  output=worst, value=change, threshold=STEP_TOLERANCE)] if above else []
    return (change, worst), flags, above


def half_step_check(report: Any, crossing: Crossing, rerun: Callable[[RunPlan], Any],
                    limits: Limits | None = None) -> dict[str, Any]:
    """How good a single run's automatic step is: the same run once more at half the step (``rerun(run_plan)``, as
    ``converge_step``'s), and the largest change of a deflection or strain impact factor of its report (every point
    and girder; the load effects have their own step rule and warning, ``vbikit.analysis.effect_step``) and the
    largest relative change of a peak deck acceleration (``acceleration_flags``).  By Richardson's step doubling an
    impact factor's own error is about its change times 1 / (1 − 2⁻ᵖ), p ≈ 2 for the exact integrator (4/3 of it);
    a peak acceleration that rings modes the step does not resolve is not yet in that regime, and its change is a
    sign, not a bound (Frýba's moving force: 0.77 % at half the step, 3.7 % at a quarter).  The
    report stays the run at the automatic step; above ``STEP_TOLERANCE`` its summary gets ``step_not_converged``
    (one flag for the impact factors, one for the accelerations).  Returns the summary's ``step_check``: ``dt`` [s]
    the half step, ``largest_change`` [-] and ``output``, ``acceleration_change`` [-] and ``acceleration_output``
    (None, with ``note``, when the half-step run is above the step budget), and ``accelerations_not_converged``: every
    peak acceleration above the tolerance, by name."""
    from vbikit.solve.plan import plan_run

    dt = float(report.result.integration_dt or report.result.dt)
    try:
        run_plan = plan_run(replace(crossing, dt=dt / 2), limits)
    except BudgetError as err:
        return {"dt": dt / 2, "largest_change": None, "output": None, "acceleration_change": None,
                "acceleration_output": None, "accelerations_not_converged": [],
                "note": f"not run: the run at half the step is above the run's budget ({err})"}
    finer = rerun(run_plan).summary
    change, worst = _largest_change(_deflections(report.summary), _deflections(finer))
    (acc_change, acc_worst), acc_flags, acc_above = acceleration_flags(report.summary, finer, dt / 2)
    log.info("half-step check: dt %.3g s -> %.3g s, largest change %.2g (%s), of a peak acceleration %.2g (%s)",
             dt, dt / 2, change, worst, acc_change, acc_worst)
    if change > STEP_TOLERANCE:
        add_flags(report.summary, [Flag("step_not_converged", _advice([change], worst, dt / 2), output=worst or None,
                                        value=change, threshold=STEP_TOLERANCE)])
    add_flags(report.summary, acc_flags)
    return {"dt": dt / 2, "largest_change": change, "output": worst or None,
            "acceleration_change": acc_change, "acceleration_output": acc_worst or None,
            "accelerations_not_converged": acc_above}


#: the summary's load-effect blocks and their headline keys (``moment_impact_factor`` …): the half-step check leaves
#: them to their own step rule (``vbikit.analysis.effect_step``: a warning naming the step they need) and halving
_LOAD_EFFECT_KEYS = ("moment", "shear", "reaction")


def _deflections(summary: Mapping[str, Any]) -> dict[str, Any]:
    """``summary`` without its load effects (``_LOAD_EFFECT_KEYS``): the deflection and strain impact factors of
    every point and girder, which the half-step check compares."""
    return {k: v for k, v in summary.items() if not k.startswith(_LOAD_EFFECT_KEYS)}


def _advice(changes: list[float], worst: str, dt: float, relative: bool = False, halved_for_it: bool = True) -> str:
    """The flag's words: what changed by how much; the step the observed rate suggests (two halvings or more), else
    what to do (``halved_for_it``: the run halves its step for this output, within the step budget)."""
    by = f"{changes[-1]:.2%} of its value" if relative else f"{changes[-1]:.3g}"
    text = (f"{worst} is not converged in the time step: it changed by {by} when the step was halved to "
            f"{dt:.3g} s (tolerance {STEP_TOLERANCE:{'.1%' if relative else 'g'}})")
    if len(changes) >= 2 and 0.0 < changes[-1] < changes[-2]:
        rate = changes[-1] / changes[-2]
        more = math.ceil(math.log(STEP_TOLERANCE / changes[-1]) / math.log(rate))
        text += f"; at the observed rate a step of about {dt / 2 ** more:.2g} s would be (set crossing.dt)"
    else:
        text += ("; set a smaller crossing.dt, or raise the step budget (--max-steps)" if halved_for_it else
                 "; set a smaller crossing.dt (the run does not halve its step for it)")
    return text


def percent_words(change: float) -> str:
    """A relative change in per cent to two significant figures, as the step checks print it ("0.77 %", "0.0023 %":
    a change of 2.3e-5 printed "0.00%" read as none)."""
    return f"{100 * change:.2g} %"


#: what every command says of the step check of a run at a given ``crossing.dt`` (``vbikit run``, ``compare-tires``,
#: ``study run``: one wording)
DT_GIVEN_WORDS = "not run: crossing.dt is given (a run at the automatic step checks its step)"


def step_check_words(check: dict, accelerations: bool = False) -> str:
    """A step check's record in words (the one wording of ``vbikit run``, ``compare-tires``, ``study run`` and a study's
    dataset flag, ``study_step_flags``):
    ``half_step_check``'s (a single run: "at half the step …") or ``converge_step``'s (the load effects' or a train's
    halving, ``halvings``: "halved to … s: the last halving changed …"), or its ``note`` when it was not run;
    with ``accelerations`` the peak accelerations' change after a semicolon (``vbikit run`` gives it a line)."""
    if check.get("largest_change") is None:
        return str(check.get("note", "not run"))
    which = f" ({check['output']})" if check.get("output") else ""
    if "halvings" in check:  # (the step the load effects needed: the record is of the last halving)
        state = "" if check.get("converged") else ", not converged"
        words = (f"halved {check['halvings']}× to {check['dt']:.3e} s for its {check.get('for', 'load effects')}: the "
                 f"last halving changed the impact factors by at most {check['largest_change']:.1e}{which}{state}")
    else:
        words = (f"at half the step ({check['dt']:.3e} s) the deflection and strain IMs change by at most "
                 f"{check['largest_change']:.1e}{which}")
    if accelerations and check.get("acceleration_change") is not None:
        words += f"; the peak accelerations by at most {percent_words(check['acceleration_change'])}"
    return words
