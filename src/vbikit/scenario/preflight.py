"""Every check a run makes, before it integrates: the one function ``vbikit validate`` and
``vbikit run`` share (so that no scenario passes the one and fails the other for an input reason).

``preflight`` builds the scenario (files read, model parameters checked, bridge and road
budgets), chooses the time step exactly as the run will (``choose_time_step``: the integrator's
step rule and, for explicit integrators, its stability limit), estimates memory and steps against
the ``Limits``, and collects the input warnings.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from vbikit._files import shared_name
from vbikit._kept import kept_for
from vbikit.analysis.checks import Flag, input_flags, messages, point_flags
from vbikit.bridge.base import GirderDeck
from vbikit.errors import VbikitError
from vbikit.scenario.build import BuiltScenario, build
from vbikit.scenario.schema import Scenario, ScenarioError
from vbikit.solve.budget import Limits, RunEstimate
from vbikit.solve.crossing import Crossing
from vbikit.solve.plan import RunPlan, plan_run


#: fewest time steps a crossing may have (a user step longer than the crossing's tenth is refused)
MIN_STEPS = 10


@dataclass(frozen=True)
class Plan:
    """A checked scenario: the built crossing, its step ``dt`` [s], the run estimate and the checks'
    ``flags`` (``vbikit.analysis.checks.Flag``; ``warnings``: their messages); ``run``: the crossing's
    [`RunPlan`][vbikit.solve.RunPlan] (``simulate(crossing, plan=run)``)."""

    scenario: Scenario
    built: BuiltScenario
    dt: float
    estimate: RunEstimate
    flags: list[Flag] = field(default_factory=list)
    run: RunPlan | None = None

    @property
    def warnings(self) -> list[str]:
        """The flags' messages."""
        return messages(self.flags)


def defect_flags(scenario: Scenario, built: BuiltScenario) -> list[Flag]:
    """Defects that lie (partly) outside the bridge and its approach, where no wheel meets them."""
    crossing = built.crossing
    lo, hi = -crossing.approach, crossing.bridge.deck_extent[1]  # a skew deck ends beyond its span
    out = []
    for i, d in enumerate(scenario.road.defects):
        start = d.position
        length = d.length if d.length is not None else 0.0
        if start < lo or start + length > hi:
            out.append(Flag("defect_outside", f"road.defects.{i}: the {d.kind} at x = {start:g} … {start + length:g} m "
                            f"lies outside the approach and the bridge (x = {lo:g} … {hi:g} m)", subject=f"road.defects.{i}"))
    return out


def ignored_input_flags(scenario: Scenario, built: BuiltScenario) -> list[Flag]:
    """Inputs a beam has no use for, when the user gave them (the schema's ``model_fields_set``, not a
    default) with a value other than the beam's own 0: ``response.y`` (or a [[response.points]] table's
    ``y``) and ``crossing.lateral_offset`` of a single vehicle.  A beam (``bridge.lateral_invariant``)
    has no lateral dimension: its responses and the vehicle's path are the same at every y.  (Listed
    vehicles' ``lateral_offset`` still separates their lanes in the overlap check: not flagged.)"""
    if not built.crossing.bridge.lateral_invariant:
        return []
    r = scenario.response
    given = [(f"response.points[{i}].y", p.y) for i, p in enumerate(r.points or (), start=1) if "y" in p.model_fields_set]
    if r.points is None and "y" in r.model_fields_set:
        given.append(("response.y", r.y))
    c = scenario.crossing
    if scenario.vehicle is not None and "lateral_offset" in c.model_fields_set:
        given.append(("crossing.lateral_offset", c.lateral_offset))
    return [Flag("ignored_input", f"{key} = {value:g} m has no effect: the bridge model ({scenario.bridge.model}) is a "
                 "beam, which has no lateral dimension (its responses and the vehicle's path are the same at every "
                 f"y); leave {key.rsplit('.', 1)[-1]} out, or use a deck model (slab-on-girder) for lateral positions",
                 subject=key, value=float(value))
            for key, value in given if value is not None and value != 0.0]


def check_response_points(built: BuiltScenario) -> None:
    """Refuse a response point where every mode shape vanishes (on a support, off the deck): no
    static response there, hence no impact factor."""
    bridge = built.crossing.bridge
    several = len(built.plan.points) > 1
    for i, p in enumerate(built.plan.points, start=1):
        x = bridge.default_x_at(p.y) if p.x is None else p.x
        phi = bridge.mode_shapes([x], [p.y])[0]
        if not np.any(phi):
            key = f"response.points[{i}]" if several else "response"
            raise ScenarioError(f"{key}.x = {x:g} m, y = {p.y:g} m: every mode shape is zero there (a support or off "
                                "the deck), so there is no static response and no impact factor; choose a point "
                                f"inside the span 0 … {bridge.span:g} m")


#: an influence line below this (× the span for a moment) everywhere is zero: round-off of a section at a
#: pinned end, a free end or a support without stiffness
_ZERO_INFLUENCE = 1e-9


#: an axle load above this [N] is far beyond legal limits (single axle: 20 kip ≈ 89 kN in the US, 11.5 t ≈
#: 113 kN in the EU; twice the larger)
HEAVY_AXLE = 226e3


def axle_load_flags(scenario: Scenario) -> list[Flag]:
    """Axle trucks (``axle_loads``) with an axle far beyond legal limits (``HEAVY_AXLE``): possible (a
    permit load), but more often a unit slip."""
    entries = [("vehicle", scenario.vehicle)] if scenario.vehicle is not None else \
        [(f"vehicles[{i}]", v) for i, v in enumerate(scenario.vehicles or (), start=1)]
    out = []
    for key, spec in entries:
        loads = spec.parameters.get("axle_loads") if "axle_loads" in (spec.model_extra or {}) else None
        if loads and max(loads) > HEAVY_AXLE:
            k = int(np.argmax(loads))
            out.append(Flag("heavy_axle", f"{key}.axle_loads: axle {k + 1} carries {loads[k] / 1e3:.4g} kN, far beyond "
                            "legal single-axle limits (≈ 89 kN US, 113 kN EU); axle loads are in N",
                            subject=f"{key}.axle_loads", value=float(loads[k]), threshold=HEAVY_AXLE))
    return out


#: wheel-line sets per influence function whose verdict (zero or not wherever a wheel can stand) is kept
#: (``check_load_effects``; a kept bridge keeps its effects, ``vbikit.bridge.effects.kept_effect``)
_VERDICTS_PER_INFLUENCE = 16


def check_load_effects(scenario: Scenario, built: BuiltScenario) -> None:
    """Refuse a load effect whose static value is zero wherever a wheel can stand (a moment at a pinned
    end, a reaction of a support without stiffness): no static peak, hence no impact factor.  The
    check follows the run: the influence line under the wheel lines (mode acceleration) or the modal
    values (mode superposition)."""
    effects = built.load_effects
    if not effects:
        return
    crossing = built.crossing
    bridge = crossing.bridge
    _, _, y = crossing.point_kinematics()
    lines = np.unique(y)
    # the verdict depends on the wheel lines and on where the deck is (extent, span, skew: the points
    # ``deck_points`` samples), so those are its key: one influence function may serve several bridges
    probe = np.asarray(bridge.span_coordinate(np.array([0.0, 1.0]), np.array([1.0, 1.0])), float)
    lines_key = (lines.tobytes(), tuple(map(float, bridge.deck_extent)), float(bridge.span), probe.tobytes())
    points: list[tuple[np.ndarray, np.ndarray]] = []

    def deck_points() -> tuple[np.ndarray, np.ndarray]:
        if not points:
            x0, x1 = bridge.deck_extent
            xx, yy = np.meshgrid(np.linspace(x0, x1, 401), lines)
            xi = np.asarray(bridge.span_coordinate(xx, yy))
            on = (xi >= 0.0) & (xi <= bridge.span)
            points.append((xx[on], yy[on]))
        return points[0]

    r = built.plan.load_effect_method
    given = {k: getattr(scenario.response, k) for k in ("moment", "shear", "reaction")}
    seen = {"moment": 0, "shear": 0, "reaction": 0}
    for e in effects:
        seen[e.kind] += 1
        if r == "mode-superposition":
            if np.any(np.asarray(e.modal) != 0.0):
                continue
        else:  # a unit force's effect: [m] for a moment, [-] for a shear or reaction; round-off below the tolerance
            def not_zero(e=e) -> bool:
                xs, ys = deck_points()
                values = np.asarray(e.influence(xs, ys)) if xs.size else np.zeros(1)
                return bool(np.max(np.abs(values)) > _ZERO_INFLUENCE * (bridge.span if e.kind == "moment" else 1.0))

            if kept_for(e.influence, "not zero on wheel lines", _VERDICTS_PER_INFLUENCE).get(lines_key, not_zero):
                continue
        key = f"response.{e.kind}[{seen[e.kind]}]" if given[e.kind] is not None else f"response.{e.kind} (default)"
        raise ScenarioError(f"{key}: the {e.label} is zero wherever a wheel can stand (a section at a pinned end or "
                            "hinge, or a support without stiffness), so it has no static peak and no impact factor; "
                            f"give response.{e.kind} without it")


def check_wheels_on_deck(crossing: Crossing) -> None:
    """Refuse a vehicle whose wheels would run off a deck of known width (every vehicle: its
    lateral offset and its wheels' own y, mirrored when it drives −x)."""
    width = crossing.bridge.deck_width if isinstance(crossing.bridge, GirderDeck) else None
    if width is None:
        return
    _, _, y = crossing.point_kinematics()
    for i, m in enumerate(crossing.vehicles):
        off = np.abs(y[crossing.point_vehicle == i])
        if off.size and np.any(off > width / 2):
            key = "crossing.lateral_offset" if crossing.single else f"vehicles[{i + 1}].lateral_offset"
            raise ScenarioError(f"{key} = {m.lateral_offset:g} m puts wheels at y = {off.max():.4g} m from the "
                                f"centreline, off the {width:g} m wide deck")


#: time samples over the run at which listed vehicles are checked for overlap
_OVERLAP_SAMPLES = 4001


def _footprints(crossing: Crossing, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per vehicle: its axles' x extent at the times ``t`` (lo, hi: shape (n_t, n_vehicles)) and its
    wheels' y extent (ylo, yhi: shape (n_vehicles,)) [m]."""
    origin, sign, y = crossing.point_kinematics()
    veh = crossing.point_vehicle
    s = crossing.travel(t)  # (n_t, n_vehicles)
    n = crossing.n_vehicles
    lo, hi = np.empty((t.size, n)), np.empty((t.size, n))
    ylo, yhi = np.empty(n), np.empty(n)
    for i in range(n):
        on = veh == i
        x = origin[on][None, :] + sign[on][None, :] * s[:, i:i + 1]
        lo[:, i], hi[:, i] = x.min(axis=1), x.max(axis=1)
        ylo[i], yhi[i] = y[on].min(), y[on].max()
    return lo, hi, ylo, yhi


def check_vehicle_overlap(crossing: Crossing) -> None:
    """Refuse listed vehicles that would occupy the same lane at the same place: wheel tracks that
    overlap across the deck (on a bridge without lateral extent, a beam: the same direction too, as
    opposing vehicles there stand for two lanes) and axle extents along x that overlap, or pass through
    each other, on the bridge while the run lasts."""
    if crossing.single or crossing.n_vehicles < 2:
        return
    t = crossing.start_time + np.linspace(0.0, crossing.duration, _OVERLAP_SAMPLES)
    lo, hi, ylo, yhi = _footprints(crossing, t)
    x0, x1 = crossing.bridge.deck_extent
    deck = isinstance(crossing.bridge, GirderDeck)
    motions = crossing.vehicles
    for i in range(crossing.n_vehicles):
        for j in range(i + 1, crossing.n_vehicles):
            if max(ylo[i], ylo[j]) > min(yhi[i], yhi[j]):
                continue  # separate lanes
            if not deck and motions[i].direction != motions[j].direction:
                continue
            depth = np.minimum(hi[:, i], hi[:, j]) - np.maximum(lo[:, i], lo[:, j])
            on_bridge = (np.maximum(lo[:, i], lo[:, j]) <= x1) & (np.minimum(hi[:, i], hi[:, j]) >= x0)
            gap = 0.5 * (lo[:, i] + hi[:, i] - lo[:, j] - hi[:, j])
            passed = np.flatnonzero((np.sign(gap[1:]) != np.sign(gap[:-1])) & on_bridge[1:])
            hit = np.flatnonzero((depth >= 0) & on_bridge)
            if not hit.size and not passed.size:
                continue
            a, b = f"vehicles[{i + 1}]", f"vehicles[{j + 1}]"
            lanes = (f"their wheel tracks overlap across the deck (y = {ylo[i]:.3g} … {yhi[i]:.3g} m and "
                     f"{ylo[j]:.3g} … {yhi[j]:.3g} m)")
            if hit.size:
                k = hit[np.argmax(depth[hit])]
                what = (f"at t = {t[k]:.4g} s their axles overlap by {depth[k]:.3g} m along the bridge "
                        f"(x = {max(lo[k, i], lo[k, j]):.4g} … {min(hi[k, i], hi[k, j]):.4g} m)")
            else:
                k = passed[0] + 1
                what = f"they pass through each other near x = {0.5 * (lo[k, i] + hi[k, i]):.4g} m at t = {t[k]:.4g} s"
            raise ScenarioError(f"{a} and {b} overlap in one lane: {lanes}, and {what}; give them lateral_offset "
                                "values a lane apart or entry_time values far enough apart")


def deflection_estimate_flags(crossing: Crossing, x: float | None, y: float | None) -> list[Flag]:
    """``implausible_deflection`` before any run (what ``vbikit validate`` can say of a unit mistake in the bridge's
    stiffness, which a run flags from its static peaks): the static deflection at the response point (x, y; None: the
    bridge's default) under W as one force there, W Σᵢ φᵢ(x, y)² / ωᵢ² (the retained modes' static flexibility; with
    mass-normalised shapes it is proportional to 1/EI and does not depend on the mass), W the heaviest group of one
    vehicle's axles that fits on the longest span (``heaviest_on_span``: a train's whole weight would be 15–20 times
    too much).  A group spread along the span deflects less than the same weight at one point, about half at most
    on the paper's spans; the factor 10³–10⁶ of a unit mistake shows at once.  Judged as a run's
    (``implausible_deflection_flags``, the longest span); a run replaces it by its own, from the peaks it computed
    (``vbikit.scenario.pipeline.run_planned``).  None for vehicles without a static weight on the road."""
    from vbikit.analysis.checks import implausible_deflection_flags

    bridge = crossing.bridge
    span = max(bridge.span_lengths)
    try:
        weight = max(heaviest_on_span(m.vehicle, span) for m in crossing.vehicles)
    except (AttributeError, ValueError, np.linalg.LinAlgError):  # (a vehicle whose static state is not defined)
        return []
    x = bridge.default_response_x if x is None else float(x)
    y = bridge.default_response_y if y is None else float(y)
    phi = bridge.mode_shapes(np.array([x]), np.array([y]))[0]
    peak = weight * float(np.sum(phi * phi / bridge.omega**2))
    if not (np.isfinite(peak) and weight > 0.0):
        return []
    label = f"response point x = {x:g} m, y = {y:g} m (before the run: a vehicle's axles on the span as one force there)"
    return implausible_deflection_flags(span, [(label, -peak, None, None)])


def heaviest_on_span(vehicle: Any, span: float) -> float:
    """The largest static load [N] of ``vehicle``'s wheels whose longitudinal offsets lie within any ``span`` [m]
    (a sliding window over the wheels sorted by offset): what one vehicle puts on one span at most."""
    loads = np.asarray(vehicle.static_wheel_loads(), float)
    offsets = np.array([w.offset for w in vehicle.wheels], float)
    order = np.argsort(offsets)
    loads, offsets = loads[order], offsets[order]
    total = np.concatenate([[0.0], np.cumsum(loads)])
    last = np.searchsorted(offsets, offsets + span, side="right")  # (each window starts at a wheel)
    return float(np.max(total[last] - total[np.arange(offsets.size)])) if offsets.size else 0.0


def check_steps(crossing: Crossing, limits: Limits | None = None) -> RunPlan:
    """The run plan of ``crossing`` ([`vbikit.solve.plan.plan_run`][vbikit.solve.plan_run]: its time step [s] and
    estimate), checked as every run is: a given step makes at least ``MIN_STEPS`` steps while the
    vehicles are on the bridge (from the first entry to the last exit), the
    integrator's step rule (and, for explicit integrators, its stability limit), the memory and
    step budgets of ``limits`` (raises ScenarioError, UnstableTimeStepError or BudgetError)."""
    if crossing.dt is not None:
        on_bridge = crossing.exit_time() - min(m.entry_time for m in crossing.vehicles)  # first entry to last exit
        if crossing.dt > min(crossing.duration, on_bridge) / MIN_STEPS:
            raise ScenarioError(f"crossing.dt = {crossing.dt:g} s gives fewer than {MIN_STEPS} steps while the vehicles "
                                f"are on the bridge ({on_bridge:.4g} s of the run's {crossing.duration:.4g} s); use "
                                f"dt <= {min(crossing.duration, on_bridge) / MIN_STEPS:.3g} s, or leave dt out for the "
                                "automatic step")
    try:  # an explicit integrator's run is checked at its accuracy step before its stability limit is computed
        run = plan_run(crossing, limits)
    except (RuntimeError, ArithmeticError, np.linalg.LinAlgError) as err:
        raise ScenarioError(f"crossing: the time step could not be chosen ({type(err).__name__}: {err}); check the "
                            "bridge, vehicle and tire parameters") from None
    return run


def preflight(scenario: Scenario, limits: Limits | None = None) -> Plan:
    """Build and check ``scenario`` as a run would, without integrating (raises ScenarioError,
    UnstableTimeStepError or BudgetError, all [`VbikitError`][vbikit.errors.VbikitError])."""
    try:
        return _preflight(scenario, limits)
    except VbikitError:
        raise
    except ValueError as err:  # a model's own check of the inputs (e.g. a vehicle that stops on the bridge)
        raise ScenarioError(str(err)) from None


def _preflight(scenario: Scenario, limits: Limits | None) -> Plan:
    built = build(scenario, limits)
    crossing = built.crossing
    check_wheels_on_deck(crossing)
    check_vehicle_overlap(crossing)
    run = check_steps(crossing, limits)
    check_response_points(built)
    check_load_effects(scenario, built)
    flags = input_flags(crossing, run.dt, built.response_x, built.response_y) + defect_flags(scenario, built) \
        + axle_load_flags(scenario) + ignored_input_flags(scenario, built) \
        + deflection_estimate_flags(crossing, built.response_x, built.response_y)
    for name, p in zip(built.plan.point_names[1:], built.plan.points[1:]):  # the other points' own notes (near a support)
        flags += point_flags(crossing, p.x, p.y, name)
    return Plan(scenario, built, run.dt, run.estimate, flags, run)


def _vehicle_inputs(scenario: Scenario, c: Any) -> dict[str, Any]:
    """The vehicle(s) and their motion: one [vehicle] with the crossing's speed, or every [[vehicles]] entry."""
    if c.single:
        return {"vehicle": scenario.vehicle.model, "vehicle_parameters": scenario.vehicle.parameters,
                "speed_kmh": c.speed * 3.6, "speed_m_s": c.speed, "acceleration": c.acceleration,
                "lateral_offset": c.lateral_offset}
    return {"vehicles": [
        {"vehicle": spec.model, "vehicle_parameters": spec.parameters, "speed_kmh": m.speed * 3.6, "speed_m_s": m.speed,
         "acceleration": m.acceleration, "direction": m.direction, "entry_time": m.entry_time,
         "lateral_offset": m.lateral_offset}
        for spec, m in zip(scenario.vehicles, c.vehicles)]}


def scenario_inputs(scenario: Scenario, plan: Plan) -> dict[str, Any]:
    """The inputs a report states: bridge, vehicle, tire, road, speed, integrator, step, steps, modes."""
    from vbikit._version import __version__

    c, r = plan.built.crossing, scenario.road
    road: dict[str, Any] = {"class": r.road_class}
    if r.profile_file:  # (as given, an absolute path by its name only: a shared summary names no folder)
        road = {"profile_file": shared_name(r.profile_file),
                **({"profile_file_right": shared_name(r.profile_file_right)} if r.profile_file_right else {})}
    elif r.road_class != "none":
        psd = {"phi0": r.phi0, "n0": r.n0, "exponent": r.exponent} if r.road_class == "psd" else {}
        if not psd:
            from vbikit.road.psd import ISO_CLASSES

            psd = {"phi0": ISO_CLASSES[r.road_class], "n0": 0.1, "exponent": 2.0}
        road |= psd | {"seed": r.seed, "spacing": r.spacing, "n_min": r.n_min, "n_max": r.n_max}
    if r.defects:
        road["defects"] = [d.kind for d in r.defects]
    return {
        "bridge": scenario.bridge.model,
        "span": float(c.bridge.span),
        **({"bridge_deck": dict(scenario.bridge.deck)} if scenario.bridge.deck else {}),
        **({"skew_degrees": float(c.bridge.skew)} if c.bridge.skew else {}),
        "n_modes": int(c.bridge.omega.size),
        "damping_ratio": scenario.bridge.damping_ratio,
        **_vehicle_inputs(scenario, c),
        "tire": scenario.tire.model,
        "road": road,
        "integrator": c.integrator,
        "run_in": float(c.run_in),
        "dt": plan.dt,
        "dt_given": scenario.crossing.dt is not None,
        "n_steps": plan.estimate.n_steps,
        "vbikit_version": __version__,
    }
