"""Every check a study run makes before it starts, shared by ``vbikit study validate`` and
``vbikit study run``: the study's size against the confirmation limit, and the preflight of a
scenario run (files, parameters, time step and stability, memory and step budgets, see
``vbikit.scenario.preflight.preflight``) for the crossings that differ in more than the road.

Crossings of one batch differ only in road-only keys and share the first crossing's set-up, so
the preflight runs once per distinct combination of the other axes — all of them when there are
at most ``MAX_PREFLIGHTS``, else every value of every axis with the other axes at their first
value (the budgets grow monotonically with speed, span, modes and duration, so a study's extremes
are among those).  Budgets count the lanes one kernel call runs at once.
"""
from __future__ import annotations

import itertools
import json
from dataclasses import dataclass, field

from vbikit.analysis.checks import Flag, add_dataset_flags
from vbikit.analysis.effect_step import STEP_TOLERANCE
from vbikit.scenario.preflight import preflight
from vbikit.scenario.schema import ScenarioError, parse_scenario
from vbikit.scenario.step_check import step_check_words
from vbikit.solve.budget import BudgetError, Limits, check_run, human
from vbikit.solve.simulate import MAX_LANES
from vbikit.study.spec import MAX_CROSSINGS_UNCONFIRMED, ROAD_ONLY_KEYS, Study, StudyError

#: distinct non-road combinations preflighted one by one (above: each axis value once)
MAX_PREFLIGHTS = 48


@dataclass(frozen=True)
class StudyCheck:
    """What ``check_study`` looked at: ``checked`` scenario preflights, the largest step count
    and memory estimate of a batch, and warnings (once each)."""

    checked: int
    max_steps: int
    max_memory: float
    warnings: list[str] = field(default_factory=list)
    #: the base crossing's step check (``vbikit.scenario.step_check``: its half-step check, or its load effects'
    #: halving; ``study_dt``: the step the study's crossings run at); None when the base gives crossing.dt, or when
    #: ``check_study`` was not asked for it (``step_check=False``: a validation simulates only for load-effect advice)
    step_check: dict | None = None


#: the study dataset's attribute holding its step check (``StudyCheck.step_check`` as JSON, ``store_step_check``)
STEP_CHECK_ATTR = "step_check"


def study_step_flags(check: dict | None) -> list[Flag]:
    """The base crossing's step check (``StudyCheck.step_check``) as flags of the study: ``step_not_converged`` when
    its deflection or strain impact factors changed by more than ``STEP_TOLERANCE`` at half the step, when its halving
    (load effects, a train) did not converge, or when they settled only at a step finer than the one the study's
    crossings run at (``study_dt``; ``check_study``'s advice names the step to set).  None where the check passed, was
    not run (the budget refused it, the base gives crossing.dt) or is None."""
    if not check or check.get("largest_change") is None:
        return []
    study_dt, dt = check.get("study_dt"), float(check["dt"])
    if "halvings" in check:
        finer = study_dt is not None and dt < float(study_dt) * (1 - 1e-9)
        if check.get("converged") and not finer:
            return []
        remedy = (f"the study's crossings ran at {float(study_dt):.3g} s: set crossing.dt = {dt:.3g} in the base"
                  if check.get("converged") else "set a smaller crossing.dt in the base, or raise --max-steps")
    elif check["largest_change"] > STEP_TOLERANCE:
        remedy = f"above the tolerance {STEP_TOLERANCE:g}: set a smaller crossing.dt in the base"
    else:
        return []
    return [Flag("step_not_converged", f"the study's time step is not converged: the base crossing's step check "
                 f"{step_check_words(check)}; {remedy} (the other cells are not checked)", output=check.get("output"),
                 subject="base crossing", value=float(check["largest_change"]), threshold=STEP_TOLERANCE)]


def store_step_check(attrs: dict, check: dict | None) -> dict:
    """A study dataset's attributes ``attrs`` with its step check: ``STEP_CHECK_ATTR`` (the record as JSON) and its
    flags (``study_step_flags``) added to ``warnings``, ``flag_codes`` and ``flags``
    (``vbikit.analysis.checks.add_dataset_flags``); ``attrs`` as given for None."""
    if check is None:
        return dict(attrs)
    return add_dataset_flags({**attrs, STEP_CHECK_ATTR: json.dumps(check, sort_keys=True)}, study_step_flags(check))


def stored_step_check(attrs) -> dict | None:
    """The step check a study dataset's attributes carry (``store_step_check``), None where it has none (a dataset
    written by ``run_study`` without one, or by an earlier version)."""
    text = attrs.get(STEP_CHECK_ATTR)
    return json.loads(text) if text else None


def check_size(study: Study, confirmed: bool) -> None:
    """Refuse a study above ``MAX_CROSSINGS_UNCONFIRMED`` crossings unless ``confirmed``."""
    if study.size > MAX_CROSSINGS_UNCONFIRMED and not confirmed:
        dims = " × ".join(f"{a.key} ({len(a.values)})" for a in study.axes)
        raise StudyError(f"this study has {study.size:.4g} crossings ({dims}), more than {MAX_CROSSINGS_UNCONFIRMED:.0e}: "
                         "pass --yes to run it anyway, or use fewer axis values")


def _combinations(study: Study) -> list[tuple[int, ...]]:
    outer = [k for k, a in enumerate(study.axes) if a.key not in ROAD_ONLY_KEYS]
    n_outer = 1
    for k in outer:
        n_outer *= len(study.axes[k].values)
    base = [0] * len(study.axes)
    if n_outer <= MAX_PREFLIGHTS:
        out = []
        for values in itertools.product(*(range(len(study.axes[k].values)) for k in outer)):
            idx = list(base)
            for k, v in zip(outer, values):
                idx[k] = v
            out.append(tuple(idx))
        return out
    out = [tuple(base)]
    for k in outer:
        for v in range(1, len(study.axes[k].values)):
            idx = list(base)
            idx[k] = v
            out.append(tuple(idx))
    return out


def _base_step_check(study: Study, limits: Limits | None, wanted: bool) -> tuple[list[str], dict | None]:
    """The base crossing (every axis at its first value) through the run pipeline and its half-step check
    (``vbikit.scenario.step_check``): the check's record, what a study states of its time step (the other cells are
    not checked); None, and no run, when the base gives crossing.dt.  And, for a study that asks for moments, shears
    or reactions at the automatic step: advice if their impact factors settle only at a finer step (the study's
    crossings keep the automatic step).  Without ``wanted`` (a validation) the base runs only for that advice."""
    from vbikit.scenario.pipeline import run_planned
    from vbikit.scenario.step_check import asks_for_load_effects, is_acceleration, is_train

    scenario = parse_scenario(study.scenario_dict(tuple(0 for _ in study.axes)), study.base_dir)
    if scenario.crossing.dt is not None or not (wanted or asks_for_load_effects(scenario)):
        return [], None
    plan = preflight(scenario, limits)
    report = run_planned(plan, limits)
    checked = float(report.result.integration_dt or report.result.dt)
    # (``study_dt``: the step the study's crossings run at, coarser than the one checked where the run halved it)
    check = report.summary.get("step_check") and {**report.summary["step_check"], "study_dt": plan.dt}
    if not asks_for_load_effects(scenario) or checked >= plan.dt * (1 - 1e-9):
        return [], check
    # what the halving is for: the impact factors, and a train's peak accelerations (another run's peak acceleration
    # flag is not about the step the study's load effects need)
    train = is_train(scenario)
    unsettled = [f["message"] for f in report.summary["flags"]
                 if f["code"] == "step_not_converged" and (train or not is_acceleration(f.get("output")))]
    if unsettled:  # not even the finest checked step settles them
        return [f"base (the study's crossings run at the automatic step {plan.dt:.3g} s): {w}" for w in unsettled], check
    return [f"base: the load effects' impact factors settle only at dt = {checked:.3g} s (step check of the base "
            f"crossing; the automatic step is {plan.dt:.3g} s): set crossing.dt = {checked:.3g} in the base"], check


def check_study(study: Study, limits: Limits | None = None, confirmed: bool = False,
                step_check: bool = False) -> StudyCheck:
    """Size, then the preflight of the study's distinct set-ups (module docstring); raises
    StudyError naming the axis values of the first failing crossing.  ``step_check``: run the base crossing's step
    check too (``StudyCheck.step_check``: what ``vbikit study run`` states of its step; a validation leaves it out)."""
    check_size(study, confirmed)
    lanes = min(study.batch_size, MAX_LANES)
    warnings: list[str] = []
    max_steps, max_memory = 0, 0.0
    combos = _combinations(study)
    for idx in combos:
        where = ", ".join(f"{a.key} = {a.values[i]!r}" for a, i in zip(study.axes, idx) if len(a.values) > 1) or "base"
        try:
            plan = preflight(parse_scenario(study.scenario_dict(idx), study.base_dir), limits)
            est = check_run(plan.built.crossing, plan.dt, limits, lanes=lanes)
        except (ScenarioError, BudgetError, ValueError) as err:
            raise StudyError(f"base + axes ({where}): {err}") from None
        max_steps, max_memory = max(max_steps, est.n_steps), max(max_memory, est.memory)
        warnings += [f"{where}: {w}" for w in plan.warnings]
    advice, check = _base_step_check(study, limits, step_check)
    warnings += advice
    if study.histories:  # the dataset holds one deflection history per crossing
        need = 8.0 * study.size * (max_steps + 1)
        limit = (limits or Limits()).max_memory
        if need > limit:
            raise StudyError(f"histories = true: {study.size} crossings × up to {max_steps + 1} time points need "
                             f"≈ {human(need)} in the dataset, above the memory limit {human(limit)}; raise "
                             "--max-memory, or store no histories")
    return StudyCheck(len(combos), max_steps, max_memory, warnings, check)
