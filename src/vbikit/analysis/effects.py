"""Load-effect histories (bending moment, shear, reactions) of a crossing and their impact factors.

The bridge supplies each effect's static influence function I(x, y) and modal values r_i
(``vbikit.bridge.effects``).  With the contact points at x_p(t) (each vehicle on its own path, ``contact_positions``) and
y_p, each wheel's force f_w(t) (from the coupled solve; compression
positive) spread over its points by their static shares β_p:

* static reference: R_st(t) = −Σ_p I(x_p, y_p) β_p P_w  (static wheel loads P_w, full stiffness);
* ``method = "mode-acceleration"`` (default):
  R(t) = −Σ_p I(x_p, y_p) β_p f_w(t) − Σ_i r_i (ξ̈_i + 2 ζ_i ω_i ξ̇_i) / ω_i²;
* ``method = "mode-superposition"``: R(t) = Σ_i r_i ξ_i(t), static R_st = Σ_i r_i ξ_st,i(t)
  (the retained modes only, like the deflection).

Spreading each wheel force by the static shares is exact for point tires and changes a load
effect of a multi-point patch (0.254 m long) by far less than its dynamic part.  The impact
factor is that of [`vbikit.analysis.impact.impact_factor`][vbikit.analysis.impact_factor]: peaks in the direction of the
static history's largest-magnitude value (hogging over a rigid pier, where the static peak moment is negative).

Peaks at the jumps (mode acceleration): a shear's influence line jumps at its section, a reaction's
(and the shear next to an end support) at the deck end, a moment's kinks at its section.  R(t) and
R_st(t) then jump or kink at the instants τ a contact point stands there, and their peak is often a
one-sided limit R(τ∓) — the instant an axle leaves over the bearing, or passes the section.  Read
at the steps only, the peak was R(τ ∓ θ dt), θ ∈ [0, 1) set by where the steps fall: the static
part off by the line's slope times v θ dt, the dynamic part by the wheel force's change ḟ_w θ dt,
up to 2π f A dt for a tire-hop component of frequency f and amplitude A (a traffic event on paper
Bridge 2, class B road: the shear impact factor 0.147 … 0.160 over step changes of 1 %, against
0.165 at 1/32 of the step).  So the peaks are taken over the samples and both one-sided limits at
every such instant (``jump_limits``, ``LoadEffectResponse.peak_series``): τ from the vehicles'
prescribed motion at the ``jump_positions`` ξ_j, and at τ ∓ δ (δ = 1e-6 dt)

    R(τ∓) = −Σ_p I(x_p(τ∓), y_p) β_p f_w(τ) + Σ_i r_i Q_i(τ∓) / ω_i² + Σ_i r_i ξ_i(τ),
    R_st(τ∓) = −Σ_p I(x_p(τ∓), y_p) β_p P_w

(the modal equations ξ̈_i + 2 ζ_i ω_i ξ̇_i + ω_i² ξ_i = −Q_i turn the modal term into displacements
and modal forces Q_i), positions and influence exact, f_w linear and ξ_i cubic Hermite between the
two steps around τ, Q_i from the modal equation at those steps, linear between them but for the
points passing a support line in the step (``vbikit.analysis.instants``, shared with the
lifetime's knot limits; the solver's own Q_i, also with multi-point tires): the static
peak is then the exact one-sided limit, the dynamic one is read at the same instant, and what is
left is the interpolation's (π f dt)²/2 · A.

Peaks between the samples, away from the kinks: no rate of R is stored (ḟ_w is not), so an
extreme of a smooth stretch is taken as the vertex of the parabola through its extreme sample and
the two either side (``impact.smooth_vertices``, for the largest and smallest of either history),
unless a contact point stands on one of the ``kink_positions`` of its wheel line within those two
steps (the effect's jumps; the support lines, where a moment's line kinks as an axle enters or
leaves; the stations where a tabulated line breaks, ``station_kinks``: a grillage's line between
two girders at every station): there the sample stands, or the limits hold the peak.  A sampled
extreme misses up to (π f dt)²/2 of a component's amplitude A, the vertex at most
A (2π f dt)³/(9√3).  The histories (``time``, ``dynamic``, ``static``: CSV columns, datasets) stay
on the time grid; the summary's peaks and IM, the outputs catalogue's and every path that reads
``impact`` or ``peak_series`` (``vbikit run``, studies, traffic, the coupled-car rail sweep; the
moving-force sweep reads its samples) include the limits and the vertices.  Mode superposition has
no limits (R = Σ r_i ξ_i does not jump), only the vertices (its static history kinks where the mode
shapes do: the same kinks); the random-vibration path reads its statistics on the grid; the
lifetime's coupled events take the vertices with their knot limits (``vbikit.lifetime.peaks``).

Both signs: a static history that also reaches, the other way, more than ``SMALL_STATIC_FRACTION``
(20 %, ``vbikit.analysis.checks``) of its largest magnitude (``two_signed``: the moment over a soft
pier, which sags while the load is near and hogs while it is on the next span; the shear at
midspan) has the opposite extreme's peaks and IM too (``LoadEffectResponse.opposite``,
``impact.impact_factor_toward``): the summary's ``opposite_*`` keys and ``governing`` (the sense
whose dynamic peak is larger in magnitude); a moment over a pier whose reported extreme is
sagging is flagged (``effect_sign_flags``).  The existing
keys keep the largest-magnitude extreme.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from functools import cached_property, partial
from typing import Any, Callable, Literal, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit._kept import kept_for
from vbikit.analysis.impact import (ImpactFactor, impact_factor, impact_factor_toward, smooth_vertices,
                                   smooth_vertices_rows, static_direction, static_modal_history)
from vbikit.analysis.instants import crossing_instants, instant_rows, modal_terms, one_sided, run_state
from vbikit.analysis.line_sums import tabulated_sums
from vbikit.bridge.base import HasLoadEffects, ModalBridge
from vbikit.bridge.effects import (KINK_POSITIONS_KEPT, STATION_BREAK, LoadEffect, TabulatedInfluence,  # noqa: F401
                                   influence_values, jump_positions, kink_positions, station_kinks)
from vbikit.solve.result import CrossingResult

log = logging.getLogger(__name__)

Method = Literal["mode-acceleration", "mode-superposition"]
METHODS: tuple[str, ...] = ("mode-acceleration", "mode-superposition")


@dataclass(frozen=True)
class LoadEffectResponse:
    """Dynamic and static histories of one load effect (SI units, conventions of ``vbikit.bridge.effects``)."""

    effect: LoadEffect
    method: str
    time: NDArray[np.float64]
    dynamic: NDArray[np.float64]
    static: NDArray[np.float64]
    #: the step check of ``vbikit.analysis.effect_step``: (``step_warning``, ``recommended_dt``), or a
    #: function that makes it on first use (``load_effect_responses(..., check_step=False)``)
    step_check: tuple[str | None, float] | Callable[[], tuple[str | None, float]] = field(
        default=(None, float("inf")), repr=False, compare=False)
    #: both one-sided limits at every instant a contact point crosses a jump or kink of the influence
    #: line (``jump_limits``): (time, dynamic, static), or a function making them on first use; None:
    #: none (mode superposition)
    limits: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]] | \
        Callable[[], tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]] | None = field(
        default=None, repr=False, compare=False)
    #: the instants [s] at which the histories may jump or kink (a contact point on a jump or kink of the
    #: influence line, or on a support line: ``kink_instants``), or a function making them on first
    #: use; the peaks between the samples are sought away from them (``impact.smooth_vertices``); None:
    #: not known, the samples and limits only
    kinks: NDArray[np.float64] | Callable[[], NDArray[np.float64]] | None = field(
        default=None, repr=False, compare=False)
    #: the extremes between the samples away from the ``kinks`` (``impact.smooth_vertices``: (time, dynamic,
    #: static)) if already made, or a function making them on first use (the effects of one run at once,
    #: ``_SharedLimits.vertices``); None: from ``kinks``
    vertices: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]] | \
        Callable[[], tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]] | None = field(
        default=None, repr=False, compare=False)

    def _step(self) -> tuple[str | None, float]:
        if callable(self.step_check):
            object.__setattr__(self, "step_check", self.step_check())
        return self.step_check  # type: ignore[return-value]

    @property
    def step_warning(self) -> str | None:
        """Why the run's step does not resolve this effect (``vbikit.analysis.effect_step``), None if it does."""
        return self._step()[0]

    @property
    def recommended_dt(self) -> float:
        """The step [s] that resolves this effect (``load_effect_step``; inf: any)."""
        return self._step()[1]

    @cached_property
    def peak_series(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """(time, dynamic, static): the histories' samples, then the one-sided limits at the jump
        instants (``limits``), then the extremes between the samples away from the kinks (``kinks``,
        ``impact.smooth_vertices``); not in time order — what the peaks are taken over (module docstring)."""
        parts = [(self.time, self.dynamic, self.static)]
        limits = self.limits() if callable(self.limits) else self.limits
        if limits is not None and limits[0].size:
            parts.append(limits)
        vertices = self.vertices() if callable(self.vertices) else self.vertices
        if vertices is None and self.kinks is not None:
            kinks = self.kinks() if callable(self.kinks) else self.kinks
            vertices = smooth_vertices(self.time, self.dynamic, self.static, kinks)
        if vertices is not None and vertices[0].size:
            parts.append(vertices)
        if len(parts) == 1:
            return self.time, self.dynamic, self.static
        return tuple(np.concatenate(cols) for cols in zip(*parts))  # type: ignore[return-value]

    @cached_property
    def impact(self) -> ImpactFactor:
        """Peaks and impact factor over ``peak_series`` (computed once: the catalogue's three outputs
        of a kind read it)."""
        return impact_factor(*self.peak_series)

    @cached_property
    def direction(self) -> float:
        """±1: the sign of the static history's largest-magnitude value (``impact.static_direction``)."""
        return static_direction(self.peak_series[2])

    @cached_property
    def opposite_static_peak(self) -> float:
        """The static history's extreme of the sign opposite to ``impact.static_peak`` (signed; 0.0
        when it never goes that way)."""
        sign = self.direction
        return float(min(0.0, np.min(sign * self.peak_series[2])) * sign)

    @property
    def opposite_share(self) -> float:
        """|``opposite_static_peak``| / |``impact.static_peak``|."""
        return abs(self.opposite_static_peak) / abs(self.impact.static_peak)

    @property
    def two_signed(self) -> bool:
        """Whether the static history's opposite extreme is not negligible: more than
        ``SMALL_STATIC_FRACTION`` (20 %) of the largest magnitude (module docstring)."""
        from vbikit.analysis.checks import SMALL_STATIC_FRACTION

        return self.opposite_share > SMALL_STATIC_FRACTION

    @cached_property
    def opposite(self) -> ImpactFactor | None:
        """Peaks and IM of the opposite extreme (``impact.impact_factor_toward``) when ``two_signed``,
        else None."""
        if not self.two_signed:
            return None
        return impact_factor_toward(*self.peak_series, -self.direction)

    def sense(self, sign: float) -> str:
        """The words for a value of sign ``sign``: sagging / hogging (moment), positive / negative."""
        if self.effect.kind == "moment":
            return "sagging" if sign > 0 else "hogging"
        return "positive" if sign > 0 else "negative"

    @property
    def governing(self) -> str:
        """The sense (``sense``) of the extreme whose dynamic peak is larger in magnitude (the main
        one unless ``opposite`` exceeds it)."""
        im, opp = self.impact, self.opposite
        peak = opp.dynamic_peak if opp is not None and abs(opp.dynamic_peak) > abs(im.dynamic_peak) else im.dynamic_peak
        return self.sense(np.sign(peak) or self.direction)

    @property
    def name(self) -> str:
        """Column stem for histories, e.g. ``moment_x12.5``, ``shear_x0_g4``, ``reaction_s1``."""
        e = self.effect
        stem = f"reaction_s{e.support}" if e.kind == "reaction" else f"{e.kind}_x{e.x:g}"
        return stem + (f"_g{e.girder}" if e.girder is not None else "")


def supports_load_effects(bridge: object) -> bool:
    """True if the bridge model offers load effects ([`HasLoadEffects`][vbikit.bridge.HasLoadEffects])."""
    return isinstance(bridge, HasLoadEffects)


def contact_positions(result: CrossingResult) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """x_p(t) and y_p [m] of every contact point at every time, shape (n_t, n_cp) each (every
    vehicle on its own path: x_p = origin_p + direction_p · s_v(t))."""
    crossing = result.crossing
    origin, direction, y = crossing.point_kinematics()
    s = np.asarray(result.travel, float)
    s = s.reshape(-1, 1) if s.ndim == 1 else s
    x = origin[None, :] + direction[None, :] * s[:, crossing.point_vehicle]
    return x, np.broadcast_to(y, x.shape)


@dataclass(frozen=True)
class ContactInfluences:
    """I(x_p(t), y_p) of some effects at the (time, contact point) pairs on the deck only, ``values``
    of shape (n_effects, n_on), with the pairs' ``rows`` (time index, ascending) and ``points``
    (contact point index): the non-zero part of ``contact_influences`` (about half of a crossing's
    pairs are off the deck, and the dense (n_effects, n_t, n_cp) array costs more to allocate and
    reduce than its values).  ``sums(a)`` gives Σ_p I_e(x_p(t), y_p) · a_p(t) for every effect and
    time (mode acceleration's static and quasi-static terms, module docstring)."""

    rows: NDArray[np.int64]
    points: NDArray[np.int64]
    values: NDArray[np.float64]
    n_t: int
    n_cp: int

    @cached_property
    def _groups(self) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        """The first pair of every time with pairs on the deck (``rows`` is sorted), and those times."""
        starts = np.flatnonzero(np.r_[True, self.rows[1:] != self.rows[:-1]]) if self.rows.size else \
            np.zeros(0, np.int64)
        return starts, self.rows[starts]

    def sums(self, per_pair: NDArray[np.float64]) -> NDArray[np.float64]:
        """Σ_p I_e(t, p) a_j(t, p), shape (n_effects, n_t), for ``per_pair`` = a at the on-deck pairs,
        (n_on,) one weight, or (n_on, n_j) several at once: then shape (n_j, n_effects, n_t) (each
        time's pairs summed in order, one contiguous ``reduceat`` per effect and weight)."""
        a = np.asarray(per_pair, float)
        weights = a[None, :] if a.ndim == 1 else np.ascontiguousarray(a.T)
        out = np.zeros((weights.shape[0], self.values.shape[0], self.n_t))
        starts, times = self._groups
        if starts.size:
            for j, w in enumerate(weights):
                for e, v in enumerate(self.values):
                    out[j, e, times] = np.add.reduceat(v * w, starts)
        return out[0] if a.ndim == 1 else out

    def dense(self) -> NDArray[np.float64]:
        """The (n_effects, n_t, n_cp) array of ``contact_influences`` (0 off the deck)."""
        out = np.zeros((self.values.shape[0], self.n_t, self.n_cp))
        out[:, self.rows, self.points] = self.values
        return out


def contact_influence_table(result: CrossingResult, effects: Sequence[LoadEffect]) -> ContactInfluences:
    """``contact_influences`` as a ``ContactInfluences``: the values at the on-deck (time, point)
    pairs only (crossings on the same time grid and contact layout, e.g. a study's lanes, share it)."""
    x, y = contact_positions(result)
    bridge = result.crossing.bridge
    xi = bridge.span_coordinate(x, y)  # along the span from each point's own support line (skew decks)
    n_t, n_cp = x.shape
    on = np.flatnonzero((xi >= 0.0) & (xi <= bridge.span))  # (time, point) pairs on the deck, time-major
    rows, points = np.divmod(on, n_cp)
    values = np.ascontiguousarray(influence_values(effects, x.ravel()[on], y[0][points]).T) if effects and on.size \
        else np.zeros((len(effects), on.size))
    return ContactInfluences(rows, points, values, n_t, n_cp)


def contact_influences(result: CrossingResult, effects: Sequence[LoadEffect]) -> NDArray[np.float64]:
    """I(x_p(t), y_p) of every effect for every time and contact point, shape (n_effects, n_t, n_cp)
    (0 off the deck); the effects share the points' positions and whatever their influence
    functions share (``vbikit.bridge.effects.influence_values``)."""
    return contact_influence_table(result, effects).dense()


def contact_influence(result: CrossingResult, effect: LoadEffect) -> NDArray[np.float64]:
    """I(x_p(t), y_p) for every time and contact point, shape (n_t, n_cp)."""
    return contact_influences(result, [effect])[0]


def load_effect_response(result: CrossingResult, effect: LoadEffect, method: str = "mode-acceleration",
                         xi_static: NDArray[np.float64] | None = None,
                         influence: NDArray[np.float64] | None = None) -> LoadEffectResponse:
    """Histories of ``effect`` over the crossing (see the module docstring); ``xi_static``: the
    static modal history if already computed (mode superposition); ``influence``: the
    ``contact_influence`` matrix if already computed (crossings on the same time grid share it)."""
    return load_effect_responses(result, [effect], method, xi_static,
                                 None if influence is None else np.asarray(influence)[None])[0]


def load_effect_responses(result: CrossingResult, effects: Sequence[LoadEffect], method: str = "mode-acceleration",
                          xi_static: NDArray[np.float64] | None = None,
                          influence: NDArray[np.float64] | ContactInfluences | None = None,
                          check_step: bool = True, log_step: bool = True) -> list[LoadEffectResponse]:
    """``load_effect_response`` for several effects at once: one static modal history (mode
    superposition), or (mode acceleration) one pass over the contact points' positions, their
    static and dynamic forces and the modal correction of every effect; ``influence``: their
    ``contact_influence_table`` (or the dense ``contact_influences``, n_effects × n_t × n_cp) if
    already computed.  ``check_step``: the step
    check (``vbikit.analysis.effect_step``, its warning logged) now; False: on first use of a
    response's ``step_warning`` or ``recommended_dt`` (the population runners, which read
    neither: a check costs about as much as the rest of the reduction).  ``log_step``: log a step
    warning (once per message); False when the caller reports ``step_warning`` itself (a scenario
    run's summary ``warnings``, which the command line prints: logged too, it showed twice)."""
    if method not in METHODS:
        raise ValueError(f"load effect method must be one of {', '.join(METHODS)}, got {method!r}")
    if not effects:
        return []
    t = result.time
    if method == "mode-superposition":
        xi_st = static_modal_history(result) if xi_static is None else xi_static
        kinks = _SharedLimits(result, tuple(effects), None)  # (ξ is smooth; ξ_st kinks as the points cross kinks of φ)
        return [LoadEffectResponse(e, method, t, result.xi @ e.modal, xi_st @ e.modal,
                                   _checked(result, e, check_step, log_step), kinks=partial(kinks.kinks, k))
                for k, e in enumerate(effects)]
    crossing = result.crossing
    bridge, cp = crossing.bridge, crossing.contact
    tabulated = influence is None and tabulated_together(effects)
    infl = contact_influence_table(result, effects) if influence is None and not tabulated else influence
    share = cp.weight
    static_loads = share * crossing.vehicle.static_wheel_loads()[cp.wheel]
    omega = bridge.omega
    rates = modal_rates(result)
    if tabulated:  # compiled, one pass over the (time, point) pairs (vbikit.analysis.line_sums)
        origin, direction, y = crossing._kinematics
        static, dynamic = tabulated_sums(origin, direction, y, crossing.point_vehicle, result.shared_travel(), cp.wheel,
                                         share, static_loads, result.wheel_forces, [e.influence for e in effects],
                                         bridge.span)
        np.negative(static, out=static)
        np.negative(dynamic, out=dynamic)
    elif isinstance(infl, ContactInfluences):  # the on-deck pairs only
        rows, pts = infl.rows, infl.points
        static, dynamic = -infl.sums(np.stack([static_loads[pts], result.wheel_forces[rows, cp.wheel[pts]] * share[pts]],
                                              axis=1))
    else:
        infl = np.asarray(infl)
        dyn_forces = result.wheel_forces[:, cp.wheel] * share[None, :]
        static = -(infl @ static_loads)
        dynamic = -np.einsum("etp,tp->et", infl, dyn_forces)
    # the modal correction, one matrix-vector product per effect: an effect's history does not depend on which
    # others are reduced with it
    for k, e in enumerate(effects):
        dynamic[k] -= rates @ (e.modal / omega**2)
    limits = _SharedLimits(result, tuple(effects), static_loads, (dynamic, static))
    return [LoadEffectResponse(e, method, t, dynamic[k], static[k], _checked(result, e, check_step, log_step),
                               partial(limits, k), partial(limits.kinks, k), partial(limits.vertices, k))
            for k, e in enumerate(effects)]


#: values of the tiled damping row ``modal_rates`` keeps per bridge at most (8 MB; a run with more takes the
#: row-wise product, the same numbers)
DAMPING_ROWS_KEPT = 1 << 20


def modal_rates(result: CrossingResult) -> NDArray[np.float64]:
    """ξ̈_i + 2 ζ_i ω_i ξ̇_i of every mode at every time, (n_t, n_modes): mode acceleration's modal term
    (``load_effect_responses``), elementwise ``xi_ddot + xi_dot * (2 ζ ω)`` — the row 2 ζ ω repeated down the
    rows (kept per bridge, ``modal_terms``, in lengths of powers of two), so that the product and the sum are
    one flat pass each rather than one short pass per row (the same products and sums)."""
    xi_dot, xi_ddot = result.xi_dot, result.xi_ddot
    damping = modal_terms(result.crossing.bridge)[0]
    if not (xi_dot.flags.c_contiguous and xi_ddot.flags.c_contiguous and xi_dot.shape == xi_ddot.shape
            and xi_dot.ndim == 2 and xi_dot.shape[1] == damping.size and xi_dot.dtype == xi_ddot.dtype == float):
        return xi_ddot + xi_dot * damping
    rows = 1 << max(int(xi_dot.shape[0]) - 1, 0).bit_length()  # (at least the rows)
    if rows * damping.size > DAMPING_ROWS_KEPT:  # (a long run: not kept, so a worker holds no large tile per bridge)
        return xi_ddot + xi_dot * damping
    tiled = kept_for(result.crossing.bridge, "damping rows", 4).get(rows, lambda: np.tile(damping, rows))
    flat = np.multiply(xi_dot.reshape(-1), tiled[:xi_dot.size])
    np.add(xi_ddot.reshape(-1), flat, out=flat)
    return flat.reshape(xi_dot.shape)


def _passing_instants(result: CrossingResult, effects: Sequence[LoadEffect],
                      *kinds: str) -> list[list[NDArray[np.float64]]]:
    """Per kind of ``kinds`` (``PASSING_POSITIONS``: "jump", "kink") and per effect, the instants in the
    run's span (also at its first and last instant, within ``BOUNDARY_INSTANT``: a point standing on a
    support as the run starts bars a kink's vertex through that step, and a jump's limit inside the run is
    read there, ``_in_span``) at which a contact point stands on one of the effect's positions ξ of that kind on its
    wheel line y (skew decks included), sorted, unique: every kind's and effect's (point, position)
    pairs timed in one pass (``instants.crossing_instants``), from the positions' table of the bridge,
    effects and lines (``_position_table``, kept: the same for every event of a stream)."""
    t = np.asarray(result.time, float)
    if t.size < 2 or not effects:
        return [[np.zeros(0) for _ in effects] for _ in kinds]
    crossing = result.crossing
    bridge = crossing.bridge
    origin, sign, y = crossing._kinematics  # (read only)
    lines = distinct_sorted(y)
    table, bounds, block = _position_table(bridge, tuple(effects), lines, kinds)
    travel = (table[lines.searchsorted(y)] + (y * float(bridge.skew_tan))[:, None] - origin[:, None]) * sign[:, None]
    t0, t1 = float(t[0]), float(t[-1])
    edge = BOUNDARY_INSTANT * (t1 - t0)  # a point on a position at the run's first or last instant
    taus = [_in_span(tau, t0, t1) for tau in crossing_instants(
        crossing, [travel[:, a:b] for a, b in bounds], t0 - edge, t1 + edge)]
    n = len(effects)
    return [[taus[block[k * n + e]] for e in range(n)] for k in range(len(kinds))]


def distinct_sorted(values: NDArray[np.float64]) -> NDArray[np.float64]:
    """``np.unique`` of a 1-D array without NaN (wheel lines, instants) — a sorted copy without repeats — in
    its two array passes, without np.unique's checks and options (a few of these an event)."""
    out = np.sort(values)
    if out.size < 2:
        return out
    keep = np.empty(out.size, bool)
    keep[0] = True
    np.not_equal(out[1:], out[:-1], out=keep[1:])
    return out[keep]


def _in_span(tau: NDArray[np.float64], t0: float, t1: float) -> NDArray[np.float64]:
    """The instants ``tau`` (sorted, unique, within the run's span widened by ``BOUNDARY_INSTANT``) of
    one kind clipped to [t0, t1], unique: one at the first or last instant — a force starting on the entry
    support — still bars a kink's vertex, and a jump's one-sided limit inside the run (``jump_limits``) is
    still read there (the shear just right of the entry support as the force starts on it: its largest
    value).  Most events have none near either end: ``tau`` as it is."""
    if tau.size == 0 or (tau[0] > t0 and tau[-1] < t1):
        return tau
    return np.unique(np.clip(tau, t0, t1))


#: an instant within this fraction of the run's span of its first or last instant is on it (``_passing_instants``)
BOUNDARY_INSTANT = 1e-9


#: the positions whose passing instants ``_passing_instants`` times, by kind: ξ [m] per bridge, effect and wheel line y
PASSING_POSITIONS: dict[str, Callable[[ModalBridge, LoadEffect, float], NDArray[np.float64]]] = {
    "jump": lambda bridge, effect, y: jump_positions(bridge, effect),
    "kink": kink_positions,
}
#: the position tables (``_position_table``) a bridge keeps, per effects, wheel lines and kinds
POSITION_TABLES_KEPT = 64


def _position_table(bridge: ModalBridge, effects: tuple[LoadEffect, ...], lines: NDArray[np.float64],
                    kinds: tuple[str, ...]) -> tuple[NDArray[np.float64], tuple[tuple[int, int], ...], tuple[int, ...]]:
    """The positions ξ [m] of every kind of ``kinds`` and effect (``PASSING_POSITIONS``) on every wheel
    line of ``lines``: a (n_lines, Σ widths) table of the distinct blocks of positions, one block of
    columns per (kind, effect) but for those equal to an earlier one (a deck's effects share the support
    lines and stations they kink at, shears and reactions the deck ends they jump at: timed once), each
    NaN-padded to its width (NaN: none), their (first, end) columns, and per (kind, effect) in that order
    its block;
    kept by the bridge per effects (their identities: each entry holds them), lines and kinds — not to be
    written."""
    key = (tuple(id(e) for e in effects), lines.tobytes(), kinds)

    def make() -> tuple[Any, ...]:
        blocks: list[NDArray[np.float64]] = []
        which = []
        for kind in kinds:
            where = PASSING_POSITIONS[kind]
            for e in effects:
                per_line = [where(bridge, e, float(v)) for v in lines]
                block = np.full((lines.size, max(p.size for p in per_line)), np.nan)
                for k, p in enumerate(per_line):
                    block[k, :p.size] = p
                same = [j for j, b in enumerate(blocks) if np.array_equal(b, block, equal_nan=True)]
                which.append(same[0] if same else len(blocks))
                if not same:
                    blocks.append(block)
        table = np.concatenate(blocks, axis=1)
        table.setflags(write=False)
        ends = np.cumsum([b.shape[1] for b in blocks]).tolist()
        return effects, table, tuple(zip([0] + ends[:-1], ends)), tuple(which)

    return kept_for(bridge, "passing positions", POSITION_TABLES_KEPT).get(key, make)[1:]


def kink_instants(result: CrossingResult, effects: Sequence[LoadEffect]) -> list[NDArray[np.float64]]:
    """Per effect, the instants [s] at which its histories may jump or kink: a contact point on one of
    the ``kink_positions`` of its own wheel line (``LoadEffectResponse.kinks``)."""
    return _passing_instants(result, effects, "kink")[0]


def jump_limits(result: CrossingResult, effects: Sequence[LoadEffect],
                static_loads: NDArray[np.float64] | None = None,
                instants: list[NDArray[np.float64]] | None = None) -> list[tuple[NDArray[np.float64], ...]]:
    """Per effect (mode acceleration), (time, dynamic, static) at both one-sided limits τ∓δ of every
    instant τ in the run's span at which a contact point stands on one of its ``jump_positions``
    (module docstring; ``vbikit.analysis.instants``): positions and influence values exact, wheel
    forces linear and modal displacements cubic Hermite between the two steps around τ, the modal
    forces from the modal equation at those steps (``run_state``).  The run's state is evaluated once at the union of the
    effects' instants, element by element; each effect's values then over its own instants only (so
    they do not depend on which other effects are reduced with it).  ``static_loads``: the contact
    points' β_p P_w if already computed; ``instants``: the effects' jump instants if already timed
    (``_passing_instants``)."""
    t = np.asarray(result.time, float)
    empty = (np.zeros(0), np.zeros(0), np.zeros(0))
    if t.size < 2 or not effects:
        return [empty for _ in effects]
    crossing = result.crossing
    bridge = crossing.bridge
    taus = _passing_instants(result, effects, "jump")[0] if instants is None else instants
    distinct = list({id(mine): mine for mine in taus}.values())  # (effects sharing their instants share the array)
    tau = distinct_sorted(np.concatenate(distinct))
    if tau.size == 0:
        return [empty for _ in effects]
    # (an instant at the run's first or last one: its limit outside the run is read at that instant itself)
    u = one_sided(tau, float(t[1] - t[0])).clip(t[0], t[-1])
    state = run_state(result, u)
    if static_loads is None:
        cp = crossing.contact
        static_loads = cp.weight * crossing.vehicle.static_wheel_loads()[cp.wheel]
    sums = _instant_sums(result, effects, state, static_loads)  # (n_effects, n_u) each: −Σ_p I β_p f_w, −Σ_p I β_p P_w
    omega2 = np.asarray(bridge.omega, float)**2
    out = []
    # per instants' array (effects sharing theirs share it): its rows, their u, Q_i, ξ_i and every effect's sums
    rows_of: dict[int, tuple[NDArray[np.float64], ...]] = {}
    for e, effect, mine in zip(range(len(effects)), effects, taus):
        if mine.size == 0:
            out.append(empty)
            continue
        at = rows_of.get(id(mine))
        if at is None:
            rows = instant_rows(tau, mine)  # τ⁻ and τ⁺ of each of its instants
            at = rows_of[id(mine)] = (u[rows], state.q[rows], state.xi[rows], sums[0][:, rows], sums[1][:, rows])
        u_rows, q_rows, xi_rows, dynamic, static = at
        r = np.asarray(effect.modal, float)
        out.append((u_rows, dynamic[e] + q_rows @ (r / omega2) + xi_rows @ r, static[e]))
    return out


def _instant_sums(result: CrossingResult, effects: Sequence[LoadEffect], state: Any,
                  static_loads: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(−Σ_p I_e(x_p, y_p) β_p f_w, −Σ_p I_e(x_p, y_p) β_p P_w) of every effect at the instants of the run's
    ``state`` (``instants.RunState``), each (n_effects, n_u): compiled in one pass over the (instant,
    point) pairs when the effects are tabulated along the same stations (``line_sums``, as the sampled
    histories), else from ``influence_values`` at the on-deck points (``contact_influence_table``'s test)."""
    crossing = result.crossing
    bridge, cp = crossing.bridge, crossing.contact
    if tabulated_together(effects):
        origin, direction, y = crossing._kinematics  # (read only)
        static, dynamic = tabulated_sums(origin, direction, y, crossing.point_vehicle, state.travel, cp.wheel,
                                         cp.weight, static_loads, state.wheel_forces, [e.influence for e in effects],
                                         bridge.span)
        return -dynamic, -static
    x, y = state.x, state.y
    xi = x - (y * float(bridge.skew_tan))[None, :]  # ``span_coordinate``
    on = (xi >= 0.0) & (xi <= bridge.span)  # on the deck (as ``contact_influence_table``)
    g = np.zeros((len(effects),) + x.shape)  # the line's value per unit force: −I
    if on.any():
        g[:, on] = -influence_values(effects, x[on], y[np.nonzero(on)[1]]).T
    return np.sum(g * state.f[None], axis=2), g @ static_loads


class _SharedLimits:
    """``jump_limits`` and ``kink_instants`` of one run's effects, computed on the first call of either
    (any effect's; both kinds of instants timed in one pass) and shared by their responses: ``self(k)``
    (``self.kinks(k)``) is effect k's; with the effects' ``histories`` (dynamic, static: (n_effects, n_t)
    each) also their extremes between the samples, all at once (``vertices``)."""

    def __init__(self, result: CrossingResult, effects: tuple[LoadEffect, ...],
                 static_loads: NDArray[np.float64] | None,
                 histories: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None) -> None:
        self.result, self.effects, self.static_loads, self.histories = result, effects, static_loads, histories
        self.values: list[tuple[NDArray[np.float64], ...]] | None = None
        self.kink_values: list[NDArray[np.float64]] | None = None
        self.vertex_values: list[tuple[NDArray[np.float64], ...]] | None = None

    def _instants(self) -> None:
        if self.static_loads is None:  # (mode superposition: no limits, the kinks only)
            self.kink_values = _passing_instants(self.result, self.effects, "kink")[0]
            return
        jumps, self.kink_values = _passing_instants(self.result, self.effects, "jump", "kink")
        self.values = jump_limits(self.result, self.effects, self.static_loads, jumps)

    def __call__(self, k: int) -> tuple[NDArray[np.float64], ...]:
        if self.values is None:
            self._instants()
        return self.values[k]  # type: ignore[index]

    def kinks(self, k: int) -> NDArray[np.float64]:
        """``kink_instants`` of effect k (computed for all on the first call)."""
        if self.kink_values is None:
            self._instants()
        return self.kink_values[k]  # type: ignore[index]

    def vertices(self, k: int) -> tuple[NDArray[np.float64], ...]:
        """Effect k's extremes between the samples away from its kinks (``impact.smooth_vertices``), made
        for every effect on the first call (``impact.smooth_vertices_rows``)."""
        if self.vertex_values is None:
            if self.kink_values is None:
                self._instants()
            dynamic, static = self.histories  # type: ignore[misc]
            self.vertex_values = smooth_vertices_rows(self.result.time, dynamic, static, self.kink_values)
        return self.vertex_values[k]


def tabulated_together(effects: Sequence[LoadEffect]) -> bool:
    """True if every effect's influence function is tabulated along wheel lines on the same
    stations (``TabulatedInfluence`` with one ``shared_key``): their quasi-static sums are then
    compiled (``vbikit.analysis.line_sums``)."""
    return bool(effects) and all(isinstance(e.influence, TabulatedInfluence) for e in effects) and \
        len({e.influence.shared_key for e in effects}) == 1  # type: ignore[attr-defined]


def _checked(result: CrossingResult, effect: LoadEffect, now: bool, log_it: bool = True):
    """``_step_check`` of ``effect`` now, or a function making it on first use."""
    return _step_check(result, effect, log_it) if now else (lambda: _step_check(result, effect, log_it))


#: step warnings logged already (a study's many crossings log each once)
_LOGGED: set[str] = set()


def _step_check(result: CrossingResult, effect: LoadEffect, log_it: bool = True) -> tuple[str | None, float]:
    """The step check of ``vbikit.analysis.effect_step`` for ``effect`` read from ``result`` (run at
    its integration step), logged once per message (``log_it``)."""
    from vbikit.analysis.effect_step import step_warning

    text, best = step_warning(result.crossing, effect, float(result.integration_dt or result.dt))
    if log_it and text is not None and text not in _LOGGED:
        _LOGGED.add(text)
        log.warning(text)
    return text, best


def _entry(resp: LoadEffectResponse, allowances: dict[str, Any] | None) -> dict[str, Any]:
    e, im = resp.effect, resp.impact
    entry: dict[str, Any] = {
        "label": e.label, "x": e.x, "girder": e.girder, "support": e.support, "units": e.units,
        "static_peak": im.static_peak, "dynamic_peak": im.dynamic_peak, "impact_factor": im.impact_factor,
        "time_static_peak": im.time_static_peak, "time_dynamic_peak": im.time_dynamic_peak,
        "loaded_length": e.loaded_length, "hogging_region": e.hogging_region,
        "sense": resp.sense(resp.direction), "opposite_sense": resp.sense(-resp.direction),
        "opposite_static_peak": resp.opposite_static_peak, "opposite_share": resp.opposite_share,
        "two_signed": resp.two_signed, "governing": resp.governing,
    }
    opp = resp.opposite
    if opp is not None:
        entry |= {"opposite_dynamic_peak": opp.dynamic_peak, "opposite_impact_factor": opp.impact_factor,
                  "time_opposite_static_peak": opp.time_static_peak,
                  "time_opposite_dynamic_peak": opp.time_dynamic_peak}
    if allowances is not None:
        entry["code_allowances"] = allowances
    return entry


def load_effect_summary(responses: Sequence[LoadEffectResponse], allowances: Any = None) -> dict[str, Any]:
    """JSON blocks ``moment``, ``shear``, ``reaction``: each the first requested effect of its kind
    (``static_peak``, ``dynamic_peak``, ``impact_factor``, position …) with every effect of that
    kind under ``sections``; ``allowances(effect)`` (optional) adds the design-code values."""
    out: dict[str, Any] = {}
    for kind in ("moment", "shear", "reaction"):
        entries = [_entry(r, allowances(r.effect) if allowances else None) for r in responses if r.effect.kind == kind]
        if entries:
            out[kind] = {**entries[0], "method": responses[0].method, "sections": entries}
    return out


def _kilo(value: float, units: str) -> str:
    """``value`` [N or N m] in kN / kN m, signed, for a message."""
    return f"{value * 1e-3:+.4g} k{units}"


def effect_sign_flags(responses: Sequence[LoadEffectResponse]) -> list[Any]:
    """Flags (``vbikit.analysis.checks.Flag``) for load effects whose reported extreme is not the one
    the section is read for: ``sagging_over_pier`` for a moment over an interior support
    (``hogging_region``) whose largest static value is sagging (a soft pier settling under the
    load), with the hogging extreme beside it (its peaks and IM when ``two_signed``, else its
    share).  Other two-signed effects (a short span's midspan moment, a pier moment that also sags
    while the truck is two spans away) are normal and carry no flag: their entries'
    ``opposite_*`` keys and the text report's second line give the other extreme."""
    from vbikit.analysis.checks import SMALL_STATIC_FRACTION, Flag

    out = []
    for r in responses:
        e, im = r.effect, r.impact
        if not (e.kind == "moment" and e.hogging_region and im.static_peak > 0):
            continue
        opp, main, other = r.opposite, r.sense(r.direction), r.sense(-r.direction)
        both = (f"{main} {_kilo(im.static_peak, e.units)} static / {_kilo(im.dynamic_peak, e.units)} dynamic "
                f"(IM {im.impact_factor:.3g})")
        if opp is not None:
            both += (f" and {other} {_kilo(opp.static_peak, e.units)} static / {_kilo(opp.dynamic_peak, e.units)} "
                     f"dynamic (IM {opp.impact_factor:.3g}, {r.opposite_share:.0%} of the {main} static peak; the "
                     "opposite_* keys)")
        elif r.opposite_static_peak == 0.0:
            both += f", never {other} under this vehicle"
        else:
            both += (f" and {other} {_kilo(r.opposite_static_peak, e.units)} static ({r.opposite_share:.0%} of the "
                     f"{main} static peak, at most {SMALL_STATIC_FRACTION:.0%}: negligible, not reported)")
        out.append(Flag("sagging_over_pier",
                        f"{e.label}: over an interior support the largest static moment is sagging, not hogging "
                        f"— the support settles under the load (a soft support, bridge.support_stiffness) — so "
                        f"static_peak, dynamic_peak and impact_factor are the sagging extreme: {both}; the "
                        f"{r.governing} dynamic peak governs", output="moment", subject=e.label,
                        value=r.opposite_share, threshold=SMALL_STATIC_FRACTION))
    return out


def load_effect_histories(responses: Sequence[LoadEffectResponse]) -> dict[str, NDArray[np.float64]]:
    """CSV columns ``<name>`` and ``<name>_static`` for each effect (see ``LoadEffectResponse.name``)."""
    out: dict[str, NDArray[np.float64]] = {}
    for r in responses:
        out[r.name] = r.dynamic
        out[f"{r.name}_static"] = r.static
    return out


def vehicle_axle_count(vehicle: Any) -> int:
    """Number of axles of a vehicle: its distinct wheel positions along x."""
    return len({round(float(w.offset), 3) for w in vehicle.wheels})


def axles_on_span_of(result: CrossingResult, span: float) -> int:
    """The largest number of axles on a span of length ``span`` [m] at once during a crossing (CSA S6
    3.8.4.5.3, ``vbikit.analysis.codes.axles_on_span``): one vehicle by its wheel offsets; several
    by their axles as placed, x = x_front − offset (driving +x; mirrored driving −x), at every
    time of the run."""
    from vbikit.analysis.codes import axles_on_span

    motions = result.crossing.vehicles
    offsets = [np.array([w.offset for w in m.vehicle.wheels], float) for m in motions]
    if len(motions) == 1:
        return axles_on_span(offsets[0], span)
    front = np.asarray(result.crossing.front_positions(result.time), float)
    x = np.concatenate([front[:, [k]] - m.sign * o[None, :] for k, (m, o) in enumerate(zip(motions, offsets))], axis=1)
    return axles_on_span(x, span)


def loaded_length(bridge: ModalBridge, x: float | None = None, y: float | None = None) -> float:
    """The AASHTO Standard loaded length [m] of a deflection read at (x, y): the span containing the
    section (x default the bridge's default section on the line y; on a skew deck the span is found
    from ξ = x − y tan θ along the girders), the whole length of a single span."""
    spans = bridge.span_lengths
    if len(spans) == 1:
        return float(spans[0])
    y = float(bridge.default_response_y) if y is None else float(y)
    x = float(bridge.default_x_at(y)) if x is None else float(x)
    return float(spans[bridge.span_index(float(bridge.span_coordinate(x, y)))])


def load_effect_report(result: CrossingResult, effects: Sequence[LoadEffect], method: str = "mode-acceleration",
                       response_x: float | None = None,
                       response_y: float | None = None) -> tuple[dict[str, Any], list[LoadEffectResponse]]:
    """The summary entries of a crossing's load effects and design-code allowances, and the
    responses themselves (for histories): ``design_code_allowances`` for the deflection at
    ``response_x`` (loaded length: its span) and the ``moment`` / ``shear`` / ``reaction`` blocks of
    ``load_effect_summary`` with each effect's code values (CSA S6 by the axles on a span of the
    loaded length at once, ``axles_on_span_of``; a railway vehicle: EN 1991-2 Φ2 and Φ3 instead,
    ``vbikit.analysis.codes.railway_allowances``).  The responses' step warnings are not
    logged: the caller reports them (``step_warning``; the scenario summary's ``warnings``)."""
    from vbikit.analysis.codes import code_allowances, railway_allowances

    bridge = result.crossing.bridge
    railway = any(m.vehicle.railway for m in result.crossing.vehicles)  # a train among the vehicles
    f1 = float(bridge.frequencies_hz[0])
    loaded = loaded_length(bridge, response_x, result.point(response_x, response_y)[1])
    axles = {}  # CSA S6: the axles on the span at once, by loaded length

    def allowances(length: float) -> dict[str, Any]:
        if railway:  # a train: the highway codes do not apply (EN 1991-2 Φ2, Φ3 instead)
            return railway_allowances(length)
        if length not in axles:
            axles[length] = axles_on_span_of(result, length)
        return code_allowances(length, f1, axles[length])

    first = allowances(loaded)
    out: dict[str, Any] = {"design_code_allowances": {"loaded_length": loaded, "first_frequency": f1,
                                                       **({} if railway else {"n_axles": axles[loaded]}), **first}}
    responses = load_effect_responses(result, effects, method, log_step=False)
    out |= load_effect_summary(responses, lambda e: allowances(e.loaded_length))  # CSA S6: the axles on its loaded length
    return out, responses
