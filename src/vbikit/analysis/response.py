"""Response extraction at a deck point and the crossing summary."""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import kept_for
from vbikit.analysis.checks import (Flag, flag_fields, run_flags, small_static_flags, strain_convergence_flags,
                                    strain_mode_error)
from vbikit.analysis.impact import ImpactFactor, impact_factor, static_modal_history
from vbikit.analysis.plan import ResponsePlan, ResponsePoint, point_name
from vbikit.bridge.base import GirderDeck
from vbikit.outputs import QUANTITIES, Reduction, cf_unit, effect_kinds, outputs, reduce_outputs
from vbikit.solve import kernels, system
from vbikit.solve.result import CrossingResult
from vbikit.solve.run_in import START_OUTPUTS, start_settling


@dataclass(frozen=True)
class PointResponse:
    """Dynamic and static histories at one deck point (x, y) [m]: SI units, z up, tension positive.

    Parameters
    ----------
    x, y : float
        The point [m].
    time : ndarray
        Time points [s].
    displacement, static_displacement : ndarray
        Dynamic and static vertical displacement [m].
    strain, static_strain : ndarray
        Dynamic and static bottom-fibre strain [-].
    velocity : ndarray
        Vertical velocity [m/s].
    acceleration : ndarray
        Vertical acceleration [m/s²].
    strain_rate : ndarray, optional
        Strain rate [1/s] (refines the strain peak between samples).
    """

    x: float
    y: float
    time: NDArray[np.float64]
    displacement: NDArray[np.float64]
    static_displacement: NDArray[np.float64]
    strain: NDArray[np.float64]
    static_strain: NDArray[np.float64]
    velocity: NDArray[np.float64]
    acceleration: NDArray[np.float64]
    strain_rate: NDArray[np.float64] | None = None

    @cached_property
    def displacement_impact(self) -> ImpactFactor:
        return impact_factor(self.time, self.displacement, self.static_displacement, self.velocity)

    @cached_property
    def strain_impact(self) -> ImpactFactor:
        return impact_factor(self.time, self.strain, self.static_strain, self.strain_rate)

    def outputs(self, result: CrossingResult, names: Sequence[str] | None = None) -> dict[str, float | None]:
        """Every per-point output of the catalogue ([`vbikit.outputs`][vbikit.outputs]) at this point
        (only those in ``names`` when given)."""
        return reduce_outputs(Reduction(result, self), "point", names)


#: mode and strain shapes kept per bridge (``vbikit._kept.kept_for``) for this many points
POINT_SHAPES_KEPT = 64


def point_shapes(bridge: object, x: float, y: float,
                 checked: bool = False) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """φ_i(x, y) and the strain shapes ε_i(x, y) of every mode at one deck point (read-only), kept
    for the bridge per point: every crossing and event of a run reads the same points, and a
    deck's shapes at one point cost a quarter of a millisecond.  ``checked``: ValueError unless the
    point is on the deck (0 ≤ the span coordinate ≤ span, y finite), checked once per point kept."""
    if checked:
        return kept_for(bridge, "checked points", POINT_SHAPES_KEPT).get((float(x), float(y)),
                                                                        lambda: _on_deck_shapes(bridge, x, y))

    def make() -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        shapes = (np.array(bridge.mode_shapes([x], [y])[0], float), np.array(bridge.strain_shapes([x], [y])[0], float))
        for arr in shapes:
            arr.setflags(write=False)
        return shapes

    return kept_for(bridge, "point shapes", POINT_SHAPES_KEPT).get((float(x), float(y)), make)


def _on_deck_shapes(bridge: Any, x: float, y: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``point_shapes`` of a point on the deck, else ValueError naming the allowed range (``check_on_deck``)."""
    from vbikit.solve.result import check_on_deck

    check_on_deck(bridge, float(x), float(y))
    return point_shapes(bridge, x, y)


def point_response(result: CrossingResult, x: float | None = None, y: float | None = None,
                   xi_static: NDArray[np.float64] | None = None,
                   static: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None) -> PointResponse:
    """Dynamic and static responses at (x, y) [m]; x defaults to midspan, y to the bridge's
    ``default_response_y`` (its default girder on a slab-on-girder deck, as in scenarios);
    ``xi_static``: the static modal history if already computed ([`static_modal_history`][vbikit.analysis.static_modal_history]);
    ``static``: the point's static displacement and strain histories if already computed
    (``static_point_histories``; then ``xi_static`` is not read)."""
    bridge = result.crossing.bridge
    # (a point given in full is checked with its shapes, once per bridge and point: ``point_shapes``)
    x, y = (float(x), float(y)) if x is not None and y is not None else result.point(x, y)
    phi, eps = point_shapes(bridge, x, y, checked=True)
    if static is None:
        xi_st = static_modal_history(result) if xi_static is None else xi_static
        static = (xi_st @ phi, xi_st @ eps)
    return PointResponse(
        x, y, result.time,
        displacement=result.xi @ phi,
        static_displacement=static[0],
        strain=result.xi @ eps,
        static_strain=static[1],
        velocity=result.xi_dot @ phi,
        acceleration=result.xi_ddot @ phi,
        strain_rate=result.xi_dot @ eps,
    )


def contact_loss(result: CrossingResult) -> dict[str, dict[str, float | bool]]:
    """Per wheel: whether its tire lost contact (zero force), where first (wheel x [m]) and for how long [s]."""
    out: dict[str, dict[str, float | bool]] = {}
    x_wheel = result.wheel_positions()
    for w, wheel in enumerate(result.crossing.vehicle.wheels):
        if wheel.stiffness <= 0:
            continue
        off = result.wheel_forces[:, w] <= 0.0
        entry: dict[str, float | bool] = {"lost": bool(off.any())}
        if off.any():
            i = int(np.argmax(off))
            entry["first_x"] = float(x_wheel[i, w])
            entry["first_time"] = float(result.time[i])
            entry["duration"] = float(off.sum() * result.dt)
        out[wheel.name] = entry
    return out


def girder_responses(result: CrossingResult, x: float | None = None, y: float | None = None,
                     xi_static: NDArray[np.float64] | None = None) -> list[PointResponse]:
    """Responses on every girder line of a bridge with ``girder_y`` (Girder 1 first) at the section of
    the response point (x, y) (default: the bridge's; x default midspan) — the same x on a square
    deck, the same station ξ = x − y tan θ along the girders on a skew deck; an empty list for
    bridges without girders (a beam)."""
    bridge = result.crossing.bridge
    if not isinstance(bridge, GirderDeck):
        return []
    girder_y = bridge.girder_y
    xi_st = static_modal_history(result) if xi_static is None else xi_static
    return [point_response(result, gx, float(g), xi_st) for gx, g in zip(result.girder_sections(x, y), girder_y)]


def point_line(bridge: object, point: ResponsePoint) -> float | None:
    """y [m] of a response point: its girder's line (checked against a y also given), its own y,
    or None (the bridge's response line).  ValueError for a girder the bridge does not have."""
    if point.girder is None:
        return point.y
    if not isinstance(bridge, GirderDeck):
        raise ValueError(f"response point girder = {point.girder}: the bridge has no girders; give y instead")
    y = float(bridge.girder_y[bridge.girder_index(point.girder)])
    if point.y is not None and abs(float(point.y) - y) > 1e-9:
        raise ValueError(f"response point girder = {point.girder} lies at y = {y:g} m, not at the y = {point.y:g} m given")
    return y


def plan_responses(result: CrossingResult, plan: ResponsePlan,
                   xi_static: NDArray[np.float64] | None = None, per_point: bool = False) -> list[PointResponse]:
    """The responses at every point of ``plan`` (its order; a point given by its girder on that
    girder's line), one static modal history shared — or, with ``per_point`` and no ``xi_static``,
    the points' static histories without it (``static_point_histories``: the same to round-off)."""
    if per_point and xi_static is None:
        where = plan_points(result, plan)
        return [point_response(result, x, y, static=st) for (x, y), st in zip(where, static_point_histories(result, where))]
    xi_st = static_modal_history(result) if xi_static is None else xi_static
    bridge = result.crossing.bridge
    return [point_response(result, p.x, point_line(bridge, p), xi_st) for p in plan.points]


#: the response plans' points a bridge keeps (``plan_points``)
PLAN_POINTS_KEPT = 8


def plan_points(result: CrossingResult, plan: ResponsePlan) -> list[tuple[float, float]]:
    """The deck point (x, y) [m] of every point of ``plan`` (its order; ``point_line``, ``CrossingResult.point``),
    kept for the bridge per plan (they depend on those two only; each entry holds its plan, so that no
    other plan can take its identity while kept): every event of a stream reads the same points."""
    bridge = result.crossing.bridge
    return kept_for(bridge, "plan points", PLAN_POINTS_KEPT).get(
        id(plan), lambda: (plan, [result.point(p.x, point_line(bridge, p)) for p in plan.points]))[1]


#: the static point tables (``_static_point_tables``) a bridge keeps, per mode-shape tables and response points
STATIC_POINT_TABLES_KEPT = 16


def static_point_histories(result: CrossingResult,
                           points: Sequence[tuple[float, float]]) -> list[tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """The static displacement [m] and strain [-] histories at the deck points ``points`` (x, y) [m]:
    ξ_st(t)·φ(x, y) and ξ_st(t)·ε(x, y) with ξ_st the static modal history
    ([`static_modal_history`][vbikit.analysis.static_modal_history]: ξ_st,m = −Σ_p φ_m(x_p) P_p / ω_m²),
    without ξ_st: the cubic Hermite interpolant of the tabulated shapes along the wheel tracks is
    linear in the tables' values and slopes, so Σ_m w_m φ_m(x_p) is the interpolant of the table
    Σ_m w_m φ_m, and with the weights w_m = φ_m(x, y)/ω_m² (or ε_m(x, y)/ω_m²) of each history

        R_st(t) = −Σ_p P_p Σ_m w_m φ_m(x_p(t)),

    the compiled pass of ξ_st itself (``vbikit.solve.kernels.static_modal_history``) over two
    weighted tables per point instead of one table per mode (made once per mode tables and points,
    ``_static_point_tables``).  Equal to ξ_st·φ up to round-off (the sums over modes taken before
    the sum over points instead of after)."""
    crossing = result.crossing
    bridge = crossing.bridge
    data = result.kernel_data if result.kernel_data is not None else system.kernel_data(crossing)
    modes, pts = data.modes, data.points
    values, slopes = _static_point_tables(bridge, modes, points)
    cp = crossing.contact
    loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    travel = np.asarray(result.shared_travel(), float)  # (read only)
    travel = np.ascontiguousarray(travel.reshape(-1, 1) if travel.ndim == 1 else travel)
    n_h = values.shape[2]
    out = np.zeros((travel.shape[0], n_h))
    kernels.static_modal_history(travel, pts.origin, pts.direction, pts.vehicle, pts.track,
                                 np.ascontiguousarray(loads, float), modes.start, modes.end, float(modes.grid_h), values,
                                 slopes, out, np.zeros(n_h), np.zeros(n_h))
    np.negative(out, out=out)
    return [(out[:, 2 * i], out[:, 2 * i + 1]) for i in range(len(points))]


def _static_point_tables(bridge: object, modes: Any,
                         points: Sequence[tuple[float, float]]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The mode tables ``modes.values``, ``modes.slopes`` (n_tracks, n_grid, n_m) weighted into
    (n_tracks, n_grid, 2 n_points): for every point its φ_m(x, y)/ω_m², then its ε_m(x, y)/ω_m²
    (``static_point_histories``; the shapes and ω of the immutable ``bridge``), kept by the bridge
    (``kept_for``) per tables (their identities: each entry holds them, so that no other array can
    take one while kept) and points (shared: not to be written)."""
    key = (id(modes.values), id(modes.slopes), tuple((float(x), float(y)) for x, y in points))

    def make() -> tuple[Any, ...]:
        omega2 = np.asarray(bridge.omega, float) ** 2
        weights = np.column_stack([shape / omega2 for x, y in points for shape in point_shapes(bridge, x, y, checked=True)])
        # (writeable, as the mode tables: numba compiles the kernel again for read-only arrays)
        tables = (np.ascontiguousarray(modes.values @ weights), np.ascontiguousarray(modes.slopes @ weights))
        return (modes.values, modes.slopes) + tables  # (the sources kept alive with their identities)

    return kept_for(bridge, "static point tables", STATIC_POINT_TABLES_KEPT).get(key, make)[2:]


def reduce_crossing(result: CrossingResult, plan: ResponsePlan, xi_static: NDArray[np.float64] | None = None,
                    effects: dict[str, Any] | None = None,
                    names: Sequence[str] | None = None) -> tuple[list[dict[str, float | None]], dict[str, float | None]]:
    """The catalogue's outputs ([`vbikit.outputs`][vbikit.outputs]) of a crossing: per-point outputs at every
    point of ``plan`` (a list in its order) and the per-crossing outputs — only those in ``names``
    when given (None: all; the responses nothing asks for are not computed).  ``xi_static``: the
    static modal history if already computed (the points' static references its projections;
    default: ``static_point_histories``, without it); ``effects``: the load-effect responses by kind
    if already computed (default: those of ``plan.first_effects`` the outputs read)."""
    from vbikit.analysis.effects import load_effect_responses  # (at call time: what the runners count, tests patch)

    if effects is None:
        kinds = effect_kinds(names)
        first = {k: e for k, e in plan.first_effects.items() if k in kinds}
        effects = dict(zip(first, load_effect_responses(result, tuple(first.values()), plan.load_effect_method,
                                                        check_step=False))) if first else {}  # (no step check: the outputs do not read it)
    points: list[dict[str, float | None]] = [{} for _ in plan.points]
    if outputs("point", names):
        points = [r.outputs(result, names) for r in plan_responses(result, plan, xi_static, per_point=True)]
    return points, reduce_outputs(Reduction(result, None, effects), "crossing", names)


def point_entries(result: CrossingResult, plan: ResponsePlan, responses: list[PointResponse]) -> list[dict[str, object]]:
    """The ``points`` list of the summary: per response point its ``name``, ``x``, ``y`` [m],
    ``girder`` (slab-on-girder decks) and every per-point output of the catalogue."""
    out = []
    for name, p, r in zip(plan.point_names, plan.points, responses):
        entry: dict[str, object] = {"name": name, "x": r.x, "y": r.y}
        if p.girder is not None:
            entry["girder"] = p.girder
        out.append(entry | r.outputs(result))
    return out


def girder_summary(girders: list[PointResponse]) -> dict[str, object]:
    """Per-girder peaks and impact factors, and the governing girder: the one with the largest
    static peak displacement (the most loaded), whose IM is the design value (paper §3)."""
    disp = [g.displacement_impact for g in girders]
    strain = [g.strain_impact for g in girders]
    governing = int(np.argmax([abs(d.static_peak) for d in disp])) + 1
    return {
        "girder_y": [g.y for g in girders],
        "girder_impact_factors": [d.impact_factor for d in disp],
        "girder_strain_impact_factors": [e.impact_factor for e in strain],
        "girder_max_dynamic_displacement": [d.dynamic_peak for d in disp],
        "girder_max_static_displacement": [d.static_peak for d in disp],
        "girder_max_dynamic_strain": [e.dynamic_peak for e in strain],
        "girder_max_abs_acceleration": [float(np.max(np.abs(g.acceleration))) for g in girders],
        "governing_girder": governing,
        "governing_girder_impact_factor": disp[governing - 1].impact_factor,
    }


def summary(result: CrossingResult, response: PointResponse, girders: list[PointResponse] | None = None,
            response_girder: int | None = None, points: list[dict[str, object]] | None = None,
            effects: dict[str, object] | None = None) -> dict[str, object]:
    """The JSON-ready summary of a crossing: every per-point output of the catalogue
    ([`vbikit.outputs`][vbikit.outputs]) at the headline ``response`` point, bridge frequencies, wheel forces,
    step data and the per-crossing outputs (those of load effects given in ``effects``, first of
    each kind); with ``girders`` (from [`girder_responses`][vbikit.analysis.girder_responses]) also the per-girder values and
    the governing girder; ``points``: the entries of [`point_entries`][vbikit.analysis.point_entries] (default: the headline
    point alone)."""
    crossing = result.crossing
    wheel_forces = result.wheel_forces
    crossing_outputs = {k: v for k, v in reduce_outputs(Reduction(result, None, effects or {}), "crossing").items()
                        if v is not None and k not in ("dt", "n_steps")}
    headline = response.outputs(result)
    return headline | {
        "response_x": response.x,
        "response_y": response.y,
        "points": points if points is not None else [{"name": point_name(1), "x": response.x, "y": response.y} | headline],
        "frequencies_hz": [float(f) for f in crossing.bridge.frequencies_hz],
        "vehicle_frequencies_hz": [float(f) for f in crossing.vehicle.natural_frequencies()],
        "static_wheel_loads": {w.name: float(p) for w, p in zip(crossing.vehicle.wheels, crossing.vehicle.static_wheel_loads())},
        "min_wheel_force": {w.name: float(f) for w, f in zip(crossing.vehicle.wheels, wheel_forces.min(axis=0))},
        "max_wheel_force": {w.name: float(f) for w, f in zip(crossing.vehicle.wheels, wheel_forces.max(axis=0))},
        "contact_loss": contact_loss(result),
        "contact_length_range": {
            w.name: [float(lo), float(hi)]
            for w, lo, hi in zip(crossing.vehicle.wheels, result.contact_lengths.min(axis=0), result.contact_lengths.max(axis=0))
        },
        "tire_model": crossing.tire.name,
        "n_steps": result.n_steps,
        "dt": result.dt,
        "duration": float(result.time[-1]),
        "integrator": crossing.integrator,
        "resolve": crossing.resolve,
        "speed": crossing.speed if crossing.single else crossing.max_speed,
        "n_contact_points_per_wheel": crossing.tire.point_count,
        **{k: v for k, v in zip(START_OUTPUTS, start_settling(crossing)) if not math.isnan(v)},  # (NaN: moving forces)
        **crossing_outputs,
        **flag_fields(run_flags(result, response.x, response.y) + strain_warnings(result, response) + static_reference_warnings(
            girders or [], points if points is not None else [{"name": point_name(1), "x": response.x, "y": response.y}
                                                              | headline])),
    } | ({"response_girder": response_girder,
          "lateral_offset": crossing.lateral_offset if crossing.single else [m.lateral_offset for m in crossing.vehicles],
          **girder_summary(girders)} if girders else {}) | ({} if crossing.single else {"vehicles": vehicle_summaries(result)})


def exact_static_strain_peak(result: CrossingResult, response: PointResponse) -> float | None:
    """The exact static strain peak at ``response``'s point [-], None where the bridge offers none.

    On a beam: c/EI times the static moment of the full stiffness there (the static part of the
    moment's mode-acceleration estimate, ``vbikit.bridge.effects``), with c/EI the ratio ε_i / r_i of
    every mode's strain to its moment — whatever the point's y (``lateral_invariant``: no lateral
    dimension) — None where the bridge offers no moment at the point (no load effects, a support) or
    the ratio is not the same for every mode (strain not c/EI times the moment there).  A continuous
    beam gives c/EI of its section (``ContinuousBeam.strain_per_moment``): its modes' strain is c
    times the Hermite elements' curvature and their moment comes from equilibrium, which differ by up
    to 0.5 % over the 12 modes of the three-span example, yet the modes' static strain converges to
    c/EI times the full-stiffness moment, not monotonically (that example at x = 10 m, smooth road,
    point tires: within 1 % with 12 modes, −1.5 % with 16, within 1 % with 64;
    tests/cli/test_airborne_and_strain_flags.py).

    On a girder deck with a grid (``strain_influence``: the slab-on-girder grillage): the strain of
    the full stiffness's static solution, read as the modes' strain is read (c_g ∂²w/∂x² of the girder
    lines, ``vbikit.bridge.deck_effects.deck_strain_influence``) — not c/EI times the girder's moment,
    which the element force recovery gives and the modes' element curvature does not converge to
    (Bridge 2: 75.92 µε against the modes' 76.21, 75.67, 73.35 µε with 20, 40, 100 modes).  The
    modes' strain does converge to this one, slowly and not monotonically (Bridge 2, Girder 4 at
    midspan, HS20-44 on point tires, smooth road, exact 77.11 µε: −5.6 % with 10 modes, −1.2 % with
    20, −1.9 % with 40, −4.9 % with 100, −1.8 % with 200, −0.4 % with 400 of the grid's 515)."""
    from vbikit.analysis.effects import load_effect_responses, supports_load_effects

    bridge = result.crossing.bridge
    if isinstance(bridge, GirderDeck):
        return _deck_static_strain_peak(result, response)
    if not supports_load_effects(bridge):
        return None
    if not bridge.lateral_invariant and abs(response.y - float(bridge.default_response_y)) > 1e-9:
        return None  # a point off the line the moment is read on; a beam has no lateral dimension: any y is its line
    try:
        effect = bridge.load_effect("moment", response.x)
    except (ValueError, NotImplementedError):
        return None
    section = getattr(bridge, "strain_per_moment", None)  # a continuous beam: c/EI of its section at x
    if section is not None:
        c_ei = section(response.x)
    else:
        r, eps = np.asarray(effect.modal, float), point_shapes(bridge, response.x, response.y)[1]
        used = np.abs(r) > 1e-9 * float(np.max(np.abs(r), initial=0.0))
        if not used.any():
            return None
        ratio = eps[used] / r[used]
        c_ei = None if np.ptp(ratio) > 1e-6 * float(np.max(np.abs(ratio))) else float(ratio[0])
    if c_ei is None:
        return None
    static = load_effect_responses(result, [effect], check_step=False)[0].static * c_ei
    return float(static[np.argmax(np.abs(static))])


def _deck_static_strain_peak(result: CrossingResult, response: PointResponse) -> float | None:
    """``exact_static_strain_peak`` on a girder deck: the static sum of the strain's influence
    function (``strain_influence``) over the moving static wheel loads, as a load effect's static part
    is summed (``load_effect_responses``; the strain carried as a sagging moment's sign: bottom-fibre
    tension positive); None for a deck without a grid (imported modes).  The strain's effect is kept
    with the bridge (``kept_effect``): a kept bridge's later runs reuse its solve and wheel-line tables."""
    from vbikit.analysis.effects import load_effect_responses
    from vbikit.bridge.effects import LoadEffect, kept_effect

    bridge = result.crossing.bridge
    make = getattr(bridge, "strain_influence", None)
    if make is None:
        return None
    x, y = float(response.x), float(response.y)
    strain = kept_effect(bridge, ("exact static strain", x, y), lambda: LoadEffect(
        "moment", x, point_shapes(bridge, x, y)[1], make(x, y), float(bridge.span)))
    static = load_effect_responses(result, [strain], check_step=False)[0].static
    return float(static[np.argmax(np.abs(static))])


def strain_mode_errors(result: CrossingResult, plan: ResponsePlan,
                       xi_static: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Per point of ``plan`` (its order): the relative error of the modes' static strain peak against the exact one,
    (modal − exact) / |exact| (``exact_static_strain_peak``; NaN where the bridge offers none) — what
    ``strain_convergence_flags`` judges for a single run.  The static reference does not read the road: a study
    computes it once a batch (``vbikit.study.compute.run_batch``)."""
    return np.array([strain_mode_error(r.strain_impact.static_peak, exact_static_strain_peak(result, r))
                     for r in plan_responses(result, plan, xi_static)], float)


def strain_warnings(result: CrossingResult, response: PointResponse) -> list[Flag]:
    """The strain-convergence flag (``vbikit.analysis.checks.strain_convergence_flags``) of the
    headline point (``point_name(1)``): its static strain peak from the modes against ``exact_static_strain_peak``."""
    bridge = result.crossing.bridge
    return strain_convergence_flags(response.strain_impact.static_peak, exact_static_strain_peak(result, response),
                                    int(bridge.omega.size),
                                    f"x = {response.x:.3f} m" + ("" if getattr(bridge, "lateral_invariant", False)
                                                                 else f", y = {response.y:.3f} m"),  # a beam has no y
                                    point_name(1), deck=isinstance(bridge, GirderDeck))


def static_reference_warnings(girders: list[PointResponse], points: list[dict[str, object]]) -> list[Flag]:
    """The small-static-reference flags (``vbikit.analysis.checks.small_static_flags``) of a
    crossing's deflection impact factors: every girder at the headline section and every response
    point (``point_entries``; a point on a girder's section is that girder's entry, its flag naming
    the point too), against the largest static peak among them all."""
    labels = [f"Girder {g}" for g in range(1, len(girders) + 1)]
    numbers: list[int | None] = list(range(1, len(girders) + 1))
    names: list[str | None] = [None] * len(girders)
    statics = [r.displacement_impact.static_peak for r in girders]
    ims = [r.displacement_impact.impact_factor for r in girders]
    strains = [r.strain_impact.impact_factor for r in girders]
    for p in points:
        on = [g for g, r in enumerate(girders) if abs(r.x - float(p["x"])) < 1e-9 and abs(r.y - float(p["y"])) < 1e-9]
        if on:
            names[on[0]] = names[on[0]] or str(p["name"])
            continue
        labels.append(f"point {p['name']}")
        numbers.append(None)
        names.append(str(p["name"]))
        statics.append(float(p["max_static_displacement"]))
        ims.append(float(p["impact_factor"]))
        strains.append(float(p["strain_impact_factor"]))
    return small_static_flags(labels, statics, ims, strains, numbers, names) if len(statics) > 1 else []


def vehicle_summaries(result: CrossingResult) -> list[dict[str, object]]:
    """Per vehicle of a several-vehicle crossing: its model, motion, static wheel loads, min / max
    wheel forces [N] and whether any of its tires lost contact (wheel names without the ``vN_`` prefix)."""
    crossing = result.crossing
    combined = crossing.vehicle
    loss = contact_loss(result)
    out = []
    for i, (m, vehicle) in enumerate(zip(crossing.vehicles, combined.parts)):
        sl = slice(combined.wheel_offsets[i], combined.wheel_offsets[i + 1])
        names = [w.name for w in vehicle.wheels]
        forces = result.wheel_forces[:, sl]
        tire = m.tire or crossing.tire
        out.append({
            "model": vehicle.name,
            "description": vehicle.description,
            "direction": m.direction,
            "speed": m.speed,
            "acceleration": m.acceleration,
            "entry_time": m.entry_time,
            "lateral_offset": m.lateral_offset,
            "tire_model": tire.name,
            "gross_weight": float(vehicle.total_weight),
            "static_wheel_loads": dict(zip(names, map(float, vehicle.static_wheel_loads()))),
            "min_wheel_force": dict(zip(names, map(float, forces.min(axis=0)))),
            "max_wheel_force": dict(zip(names, map(float, forces.max(axis=0)))),
            "contact_loss": any(bool(loss[w.name]["lost"]) for w in combined.wheels[sl] if w.name in loss),
        })
    return out


#: the deck histories written for every girder line (CSV ``girder{g}_<name>``)
GIRDER_QUANTITIES = ("displacement", "static_displacement", "strain", "static_strain", "acceleration")


def history_table(result: CrossingResult, responses: list[PointResponse], girders: list[PointResponse] | None = None,
                  effects: Sequence[Any] = (), names: Sequence[str] | None = None) -> dict[str, tuple[NDArray[np.float64], str]]:
    """Named time histories and their units (CSV spelling, [`vbikit.outputs`][vbikit.outputs]) for CSV output:
    time, front-axle positions, the deck quantities at every response point (one point: plain
    ``displacement``, …; several: ``displacement_<name>`` with the point ``names``), ``girder{g}_*``
    for every girder, tire forces and patch lengths, vehicle DOFs and their accelerations, and
    ``<effect>`` / ``<effect>_static`` for every load-effect response in ``effects``."""
    from vbikit.solve.result import dof_unit

    out: dict[str, tuple[NDArray[np.float64], str]] = {"time": (result.time, "s")}
    if result.crossing.single:
        fronts = {"front_axle_x": result.front_position[:, 0]}
    else:
        fronts = {f"v{i + 1}_front_axle_x": result.front_position[:, i] for i in range(result.front_position.shape[1])}
    deck: dict[str, tuple[NDArray[np.float64], str]] = {}
    several = len(responses) > 1
    labels = list(names) if names is not None else [f"p{i}" for i in range(1, len(responses) + 1)]
    for label, r in zip(labels, responses):
        for q in QUANTITIES.values():
            deck[f"{q.name}_{label}" if several else q.name] = (getattr(r, q.name), q.unit)
    if result.crossing.single:  # one vehicle: {time, displacement, …, front_axle_x}
        out |= deck | {k: (v, "m") for k, v in fronts.items()}
    else:  # several vehicles: {time, v1_front_axle_x, …, displacement, …}
        out |= {k: (v, "m") for k, v in fronts.items()} | deck
    for g, r in enumerate(girders or [], start=1):
        for name in GIRDER_QUANTITIES:
            out[f"girder{g}_{name}"] = (getattr(r, name), QUANTITIES[name].unit)
    wheels = result.crossing.vehicle.wheels
    for w, f in zip(wheels, result.wheel_forces.T):
        out[f"contact_force_{w.name}"] = (f, "N")
    if np.any(result.contact_lengths):
        for w, length in zip(wheels, result.contact_lengths.T):
            out[f"contact_length_{w.name}"] = (length, "m")
    for j, name in enumerate(result.crossing.vehicle.dof_names):
        out[name] = (result.q[:, j], dof_unit(name))
        out[f"{name}_acceleration"] = (result.q_ddot[:, j], dof_unit(name) + "/s^2")
    for e in effects:
        out[e.name] = (e.dynamic, e.effect.units)
        out[f"{e.name}_static"] = (e.static, e.effect.units)
    return out


def histories(result: CrossingResult, response: PointResponse,
              girders: list[PointResponse] | None = None) -> dict[str, NDArray[np.float64]]:
    """Named time histories (SI units) of [`history_table`][vbikit.analysis.history_table] at one response point."""
    return {k: v for k, (v, _) in history_table(result, [response], girders).items()}


#: the keys of the crossing summary (:func:`summary`, ``vbikit run --json``) beside the catalogue's
#: outputs: unit and meaning; per-wheel maps are keyed by wheel name, per-girder lists ordered
#: Girder 1 first (:func:`summary_keys` gives them all)
_SUMMARY_KEYS: dict[str, tuple[str, str]] = {
    "response_x": ("m", "response point from the entry support"),
    "response_y": ("m", "response point from the deck centreline"),
    "points": ("-", "every response point in order ([[response.points]], or the [response] point alone): name, "
                    "x [m], y [m], girder (slab-on-girder decks) and the per-point outputs above, each in its unit"),
    "frequencies_hz": ("Hz", "bridge natural frequencies of the retained modes"),
    "vehicle_frequencies_hz": ("Hz", "vehicle natural frequencies on rigid ground"),
    "static_wheel_loads": ("N", "static load of each wheel"),
    "min_wheel_force": ("N", "smallest tire force of each wheel (0: contact lost)"),
    "max_wheel_force": ("N", "largest tire force of each wheel"),
    "contact_loss": ("-", "per wheel: lost (true/false), first_x [m] and first_time [s] where contact was first lost, duration [s]"),
    "contact_length_range": ("m", "per wheel: [smallest, largest] length of the patch in contact (0 for point tires)"),
    "tire_model": ("-", "tire model name"),
    "duration": ("s", "simulated time"),
    "integrator": ("-", "time integrator"),
    "resolve": ("-", 'what the automatic step resolves (crossing.resolve): "effects", every result, or "deflections", '
                "deflections and tire forces only (flag deflection_step)"),
    "speed": ("m/s", "vehicle speed at t = 0"),
    "n_contact_points_per_wheel": ("-", "contact points per wheel"),
    **START_OUTPUTS,
    "response_girder": ("-", "girder of the response point (slab-on-girder bridges)"),
    "lateral_offset": ("m", "vehicle centreline from the deck centreline"),
    "girder_y": ("m", "girder lines from the deck centreline"),
    "girder_impact_factors": ("-", "displacement impact factor of every girder at response_x"),
    "girder_strain_impact_factors": ("-", "strain impact factor of every girder"),
    "girder_max_dynamic_displacement": ("m", "dynamic peak displacement of every girder"),
    "girder_max_static_displacement": ("m", "static peak displacement of every girder"),
    "girder_max_dynamic_strain": ("-", "dynamic peak strain of every girder"),
    "girder_max_abs_acceleration": ("m/s^2", "largest absolute acceleration of every girder"),
    "governing_girder": ("-", "the girder with the largest static peak displacement (the most loaded)"),
    "governing_girder_impact_factor": ("-", "impact factor of the governing girder"),
    "vehicles": ("-", "several vehicles: per vehicle its model, direction, entry_time [s], lateral_offset [m], "
                      "speed [m/s], tire_model, static_wheel_loads [N], min_wheel_force [N] and contact_loss"),
    "design_code_allowances": ("-", "loaded_length [m], first_frequency [Hz], n_axles (CSA S6: the axles on the "
                                    "span at once) and each design code's dynamic allowance [-] for the deflection "
                                    "at response_x; for a railway vehicle instead railway = true and the EN 1991-2 "
                                    "factors en1991_2_phi2, en1991_2_phi3 [-] (they apply to LM71, not to the train)"),
    "moment": ("N m", "bending moments: static_peak, dynamic_peak [N m], impact_factor [-] (in the sense of the "
                      "largest static magnitude, sense: sagging or hogging), opposite_sense, opposite_static_peak "
                      "[N m], opposite_share [-], two_signed, governing (the sense of the larger dynamic peak) and, "
                      "when two_signed, opposite_dynamic_peak, opposite_impact_factor and their times; position x "
                      "[m] of the first requested section, every section under sections (each with its label, as the "
                      "flags' subject names it), with the code allowances"),
    "shear": ("N", "shear forces (just right of x), as moment (senses: positive, negative)"),
    "reaction": ("N", "support reactions, as moment"),
    "step_check": ("-", "a single run at an automatic step: the same run at half the step, dt [s], and the largest "
                        "change of a deflection or strain impact factor (every point and girder), largest_change [-], and "
                        "which, output; the largest relative change of a peak deck acceleration (every point and girder), "
                        "acceleration_change [-], and which, acceleration_output, and every peak acceleration above "
                        "0.005, accelerations_not_converged (vbikit.scenario.step_check.half_step_check; either above "
                        "0.005 flagged step_not_converged); a run whose load effects (or a train) set its step by halving: "
                        "what the halving found, halvings, converged, dt the run's step, largest_change over the last "
                        "halving (load effects included) and output (vbikit.scenario.step_check.converge_step); absent "
                        "for a given crossing.dt"),
    "warnings": ("-", "messages about the inputs or the run (also printed on standard error): the flags' messages"),
    "flags": ("-", "the checks' findings as records: code (the flag codes' table), message, output, subject, girder, "
                   "point, wheel, value, threshold"),
    "inputs": ("-", "the inputs as run, every default filled in (units as in the scenario reference)"),
    "references": ("-", "the publications behind the run's models (vbikit cite)"),
    "units": ("-", "every key's unit in the CF spelling (\"\" for words)"),
}


def summary_keys() -> dict[str, tuple[str, str]]:
    """Every key of the crossing summary with its unit and meaning: the headline point's outputs
    of the catalogue ([`vbikit.outputs`][vbikit.outputs], registered ones included), then the other keys, with
    the per-crossing outputs before ``warnings``."""
    point = {o.name: (o.unit, o.long_name) for o in outputs("point")}
    crossing = {o.name: (o.unit, o.long_name) for o in outputs("crossing")}
    keys = list(_SUMMARY_KEYS)
    at = keys.index("warnings")
    return point | {k: _SUMMARY_KEYS[k] for k in keys[:at]} | crossing | {k: _SUMMARY_KEYS[k] for k in keys[at:]}


def summary_units(summary_: dict[str, object]) -> dict[str, str]:
    """The ``units`` map of a summary: unit of every key present, in the CF / UDUNITS spelling of every JSON
    summary and dataset (``vbikit.outputs.cf_unit``: "m s-2", "1" for a dimensionless number), "" for a key whose
    value is not a number or a list of numbers (words, records, maps of flags) and whose table unit is "-"."""
    keys = summary_keys()
    return {k: cf_unit(keys[k][0]) if keys[k][0] != "-" or _numeric(summary_[k]) else ""
            for k in summary_ if k in keys}


def _numeric(value: object) -> bool:
    """Whether a summary value is a number (None: a NaN number, as JSON writes it) or a non-empty list of them."""
    if isinstance(value, (list, tuple)):
        return bool(value) and all(_numeric(v) for v in value)
    return value is None or (isinstance(value, (int, float)) and not isinstance(value, bool))
