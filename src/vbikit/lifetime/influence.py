"""Influence lines of the requested load effects and every event's static history by convolution.

A load effect R is linear in the loads, so under static point loads P_p (downward, [N]) at deck
points (x_p, y_p)

    R = Σ_p g(x_p, y_p) P_p,

with g the effect per unit *downward* load, computed exactly as the coupled run's static
reference (``vbikit.analysis``) so that the two agree to rounding:

* moment, shear, reaction: g = −I(x, y), I the bridge's full-stiffness influence function per
  unit upward force (``vbikit.bridge.effects``; the static reference of
  ``vbikit.analysis.effects``), zero off the span;
* deflection at (x_r, y_r): g = −Σ_m φ̃_m(x, y) φ_m(x_r, y_r) / ω_m², the static modal response
  of the retained modes (``vbikit.analysis.impact.static_modal_history``) with φ̃ the mode
  shapes tabulated along the wheel track y and interpolated by cubic Hermite polynomials
  (``vbikit.solve.tabulate``), the same tables as the solver's.

A vehicle's contact points follow from its record: wheels at the axle positions (setback d_a
behind the front axle) at ± the half-track of ``vbikit.vehicle.axles`` (0.9 m), each carrying
half its axle load spread over the tire model's contact points by their static shares.  A
point of a vehicle entering at t_i with speed v_i is at x_p(t) = −d_p + v_i (t − t_i) (driving
+x) or L + d_p − v_i (t − t_i) (driving −x).

``event_static`` gives every event's static peak.  In a lifetime run the lines are tabulated
along every wheel track on a grid of ``dx`` (``Tabulated``: linear within each cell between the
line's one-sided limits, so a kink or jump at a node is kept) and the peak is the *exact*
extreme of the event's R(t) on the tabulated lines: R is piecewise linear in t with knots at
the instants a load stands on a node, so the extreme is one of the one-sided limits at the
knots, which ``vbikit.lifetime.peaks`` sweeps in time order (no sampling; the fatigue
histories are the exact turning points).  Without tables (the lines evaluated themselves) or
at given ``times`` R is sampled instead (the test against the coupled run's static reference at
its time steps); a sampled peak misses the continuous maximum by at most (ds/2)·max|dR/ds|
before refinement.
docs/lifetime.md gives the numbers.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit.bridge.base import ModalBridge
from vbikit.outputs import QUANTITIES
from vbikit.solve.tabulate import hermite_rows, tabulate_tracks
from vbikit.traffic.records import VehicleRecord

#: half-track of the trucks built from records [m] (vbikit.vehicle.axles.HALF_TRACK)
HALF_TRACK = 0.9
#: load-effect kinds and their units (deflection: the output catalogue's ``displacement`` unit)
KIND_UNITS: dict[str, str] = {"deflection": QUANTITIES["displacement"].unit, "moment": "N m", "shear": "N",
                              "reaction": "N"}


@dataclass(frozen=True)
class InfluenceLine:
    """One load effect as a function of the position of a unit downward load.

    Parameters
    ----------
    name : str
        Its label (dataset coordinate ``load_effect``).
    kind : str
        "deflection", "moment", "shear" or "reaction".
    units : str
        Units of the effect (SI).
    evaluate : callable
        g(x, y) [units per N] for arrays x, y [m] (zero off the span).
    sign : float
        +1 or −1: the direction the effect is governed in (by default the sign of g's largest
        magnitude: −1 for a downward deflection or a hogging moment; or the one the user gave,
        ``direction``); peaks are largest values of sign·R.
    effect : object, optional
        The ``vbikit.bridge.effects.LoadEffect`` (None for a deflection).
    x, y : float
        The section / response point [m].
    direction : str
        "auto" (the sign of g's largest magnitude), "positive" or "negative" (given).
    opposite_area : float
        ∫ of g over the span where it has the sign −``sign``, over ∫ where it has ``sign`` (absolute
        values; 0 for a one-signed line).  Above 1 a long vehicle or several vehicles load the
        effect more in the direction the run does not report (``direction_areas``).
    """

    name: str
    kind: str
    units: str
    evaluate: Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]] = field(repr=False)
    sign: float
    effect: object = field(default=None, repr=False)
    x: float = math.nan
    y: float = math.nan
    direction: str = "auto"
    opposite_area: float = 0.0


def deflection_line(bridge: ModalBridge, x_r: float, y_r: float, name: str = "", direction: str = "auto") -> InfluenceLine:
    """Deflection at (x_r, y_r) [m] per unit downward load [m/N] from the retained modes (module docstring);
    ``direction`` as in ``InfluenceLine``."""
    phi_r = np.asarray(bridge.mode_shapes([x_r], [y_r])[0], float)
    coef = phi_r / np.asarray(bridge.omega, float) ** 2
    tables: dict[float, object] = {}

    def evaluate(x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(x, float)
        y = np.broadcast_to(np.asarray(y, float), x.shape)
        out = np.zeros(x.shape)
        for yy in np.unique(y):
            key = float(yy)
            if key not in tables:
                tables[key] = tabulate_tracks(bridge, np.array([key]))
            table = tables[key]
            sel = (y == yy) & (x >= table.start[0]) & (x <= table.end[0])
            if np.any(sel):
                out[sel] = -(hermite_rows(table.start, table.spacing, table.values, table.slopes,
                                            np.zeros(int(sel.sum()), np.int64), x[sel], with_slopes=False)[0] @ coef)
        return out

    return _with_sign(InfluenceLine(name or f"deflection_x{x_r:g}", "deflection", KIND_UNITS["deflection"], evaluate,
                                    -1.0, None, float(x_r), float(y_r)), bridge, y_r, direction)


def effect_line(bridge: ModalBridge, effect, name: str = "", y: float = 0.0, direction: str = "auto") -> InfluenceLine:
    """A moment, shear or reaction (``vbikit.bridge.effects.LoadEffect``) per unit downward load
    (the negative of its influence function, zero off the span)."""

    def evaluate(x: NDArray[np.float64], yy: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(x, float)
        yy = np.broadcast_to(np.asarray(yy, float), x.shape)
        xi = bridge.span_coordinate(x, yy)
        on = (xi >= 0.0) & (xi <= bridge.span)
        out = np.zeros(x.shape)
        if np.any(on):
            out[on] = -np.asarray(effect.influence(x[on], yy[on]), float)
        return out

    stem = f"reaction_s{effect.support}" if effect.kind == "reaction" else f"{effect.kind}_x{effect.x:g}"
    stem += f"_g{effect.girder}" if effect.girder is not None else ""
    return _with_sign(InfluenceLine(name or stem, effect.kind, effect.units, evaluate, 1.0, effect, float(effect.x),
                                    float(y)), bridge, y, direction)


#: the sign s of each ``direction`` a user can give (``LoadEffectSpec.direction``)
DIRECTION_SIGNS = {"positive": 1.0, "negative": -1.0}


def direction_areas(g: NDArray[np.float64], x: NDArray[np.float64]) -> tuple[float, float]:
    """The areas ∫ max(g, 0) dx and ∫ max(−g, 0) dx of an influence line sampled at x (trapezoidal
    rule): what a uniform load over the whole positive or negative part of the line gives."""
    return (float(np.trapezoid(np.maximum(g, 0.0), x)), float(np.trapezoid(np.maximum(-g, 0.0), x)))


def _with_sign(line: InfluenceLine, bridge: ModalBridge, y: float, direction: str = "auto") -> InfluenceLine:
    """``line`` with its governing sign: the sign of its largest ordinate on the span (one axle
    governs), or the ``direction`` given; and ``opposite_area``, the area of the other sign's part
    over its own (``direction_areas``): a two-signed line whose other part is the larger is loaded
    more the other way by long or several vehicles (a moment near an interior support)."""
    x = np.linspace(0.0, float(bridge.span), 2001)
    g = line.evaluate(x + float(-bridge.span_coordinate(0.0, y)), np.full(x.size, float(y)))
    k = int(np.argmax(np.abs(g)))
    if g[k] == 0.0:
        raise ValueError(f"load effect {line.name}: its influence line is zero everywhere on the span")
    positive, negative = direction_areas(g, x)
    sign = DIRECTION_SIGNS.get(direction, float(np.sign(g[k])))
    own, other = (positive, negative) if sign > 0 else (negative, positive)
    if own == 0.0:
        raise ValueError(f"load effect {line.name}: direction = \"{direction}\": its influence line is never "
                         f"{direction} on the span, so the effect has no {direction} values")
    return InfluenceLine(line.name, line.kind, line.units, line.evaluate, sign, line.effect, line.x, line.y,
                         direction, other / own)


# ---------------------------------------------------------------- vehicles as point loads
@dataclass(frozen=True)
class TirePattern:
    """Contact points of one wheel relative to the wheel: setbacks [m] (behind the wheel) and static shares."""

    setback: tuple[float, ...] = (0.0,)
    share: tuple[float, ...] = (1.0,)

    @classmethod
    def of_crossing(cls, template) -> "TirePattern":
        """The pattern of the tire of a crossing template (``vbikit.traffic.study._Template``)."""
        from vbikit.solve import VehicleMotion
        from vbikit.vehicle.axles import axle_truck

        vehicle = axle_truck((5e4, 5e4), (4.0,))
        c = template.with_vehicles((VehicleMotion(vehicle, speed=10.0),), None, None)
        cp = c.contact
        sel = cp.wheel == 0
        return cls(tuple(float(s) - float(vehicle.wheels[0].offset) for s in cp.setback[sel]),
                   tuple(float(w) for w in cp.weight[sel]))

    @property
    def reach(self) -> float:
        """Largest distance of a contact point from its wheel [m]."""
        return float(max(abs(s) for s in self.setback))


@dataclass(frozen=True)
class PointLoads:
    """Every contact point of a set of vehicles, flat arrays (vehicle index, setback [m], deck y [m], load [N])."""

    vehicle: NDArray[np.int64]
    setback: NDArray[np.float64]
    y: NDArray[np.float64]
    load: NDArray[np.float64]


def point_loads(records: Sequence[VehicleRecord], lanes: Sequence[float], pattern: TirePattern = TirePattern(),
                half_track: float = HALF_TRACK) -> PointLoads:
    """Contact points of ``records`` (axle vehicles; lane n centred at ``lanes[n-1]`` unless the
    record gives its lateral offset; the wheels' y mirrored for −x traffic), sorted by vehicle."""
    for r in records:
        if r.model != "axles":
            raise ValueError(f"record {r.id or r.line}: model {r.model!r}; lifetime traffic takes axle records")
    n_ax = np.array([len(r.axle_loads) for r in records], np.int64)
    if not len(records):
        z = np.zeros(0)
        return PointLoads(z.astype(np.int64), z, z, z)
    loads = np.fromiter((p for r in records for p in r.axle_loads), float, int(n_ax.sum()))
    setb = np.fromiter((d for r in records for d in (0.0, *np.cumsum(r.axle_spacings))), float, int(n_ax.sum()))
    y0 = np.array([r.lateral_offset if r.lateral_offset is not None else lanes[r.lane - 1] for r in records], float)
    sign = np.array([1.0 if r.direction == "+x" else -1.0 for r in records])
    veh_axle = np.repeat(np.arange(len(records)), n_ax)
    pd = np.asarray(pattern.setback, float)
    pw = np.asarray(pattern.share, float)
    # (axle, side, pattern point), axles in vehicle order
    sides = np.array([half_track, -half_track])
    n_a, n_s, n_p = loads.size, 2, pd.size
    vehicle = np.broadcast_to(veh_axle[:, None, None], (n_a, n_s, n_p)).ravel()
    setback = (setb[:, None, None] + np.zeros((1, n_s, 1)) + pd[None, None, :]).ravel()
    y = (y0[veh_axle][:, None, None] + sign[veh_axle][:, None, None] * sides[None, :, None]
         + np.zeros((1, 1, n_p))).ravel()
    load = (0.5 * loads[:, None, None] * np.ones((1, n_s, 1)) * pw[None, None, :]).ravel()
    return PointLoads(vehicle.astype(np.int64), setback, y, load)


# ---------------------------------------------------------------- tabulated lines
class Tabulated:
    """An influence line tabulated along a set of wheel tracks y on a grid of ``dx`` [m] over the
    deck's x extent, interpolated linearly within each cell between the line's one-sided limits
    at the cell's ends, g(x_i⁺) and g(x_(i+1)⁻).  The grid has a node at the line's section (the
    moment's kink, the shear's jump, a reaction's support), so that a kink or jump there is
    exact (but for the 1e-9·L offset of the one-sided limits); a kink inside a cell (a support)
    costs at most dx·|jump of g'|/2 near it; elsewhere the error is ≤ dx²/8 · max|g''|.  Tracks along which the line is the same
    (a beam: g does not depend on y) share one row."""

    def __init__(self, line: InfluenceLine, bridge: ModalBridge, tracks: Sequence[float], dx: float):
        first, last = bridge.deck_extent
        first, last = float(min(first, 0.0)), float(max(last, bridge.span))
        anchor = line.x if math.isfinite(line.x) and first <= line.x <= last else first
        self.h = float(dx)
        k0 = int(math.ceil((anchor - first) / dx - 1e-12))
        self.x0 = anchor - k0 * dx
        self.n = k0 + int(math.ceil((last - anchor) / dx - 1e-12)) + 1
        self.tracks = np.asarray(sorted(set(float(y) for y in tracks)), float)
        x = self.x0 + self.h * np.arange(self.n)
        eps = 1e-9 * max(abs(last - first), 1.0)
        right = np.stack([line.evaluate(x[:-1] + eps, np.full(self.n - 1, y)) for y in self.tracks])
        left = np.stack([line.evaluate(x[1:] - eps, np.full(self.n - 1, y)) for y in self.tracks])
        both = np.concatenate([right, left], axis=1)
        uniq, self.row = np.unique(both, axis=0, return_inverse=True)
        self.row = np.asarray(self.row).ravel()
        m = self.n - 1
        # per row: A (cell starts), B (cell ends), then a zero guard cell
        self.a = np.concatenate([np.concatenate([uniq[:, :m], np.zeros((uniq.shape[0], 1))], axis=1).ravel(), [0.0]])
        self.b = np.concatenate([np.concatenate([uniq[:, m:], np.zeros((uniq.shape[0], 1))], axis=1).ravel(), [0.0]])
        self.n_rows = int(uniq.shape[0])
        # the knots of the exact peaks (``vbikit.lifetime.peaks``): the nodes where the line is
        # not straight across (within 1e-10 of its largest value)
        from vbikit.lifetime.peaks import active_nodes, knot_tables

        tol = 1e-10 * float(np.max(np.abs(uniq))) if uniq.size else 0.0
        self.active_ptr, active = active_nodes(self.a, self.b, self.n_rows, self.n, eps / self.h, tol)
        #: per active node: x, g(x⁻), g(x⁺), dg/dx after it (``vbikit.lifetime.peaks.knot_tables``)
        self.knots = knot_tables(self.a, self.b, self.n, self.x0, self.h, self.active_ptr, active)

    def same_grid(self, other: "Tabulated") -> bool:
        return self.x0 == other.x0 and self.h == other.h and self.n == other.n and np.array_equal(self.row, other.row)

    def locate(self, x: NDArray[np.float64], track: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """Flat index of the cell and the fraction t in it (the guard cell off the grid)."""
        u = (x - self.x0) / self.h
        m = self.n - 1
        inside = (u >= 0.0) & (u <= m)
        i = np.minimum(np.where(inside, u, 0.0).astype(np.int64), m - 1)
        t = np.where(inside, u - i, 0.0)
        flat = np.where(inside, self.row[track] * (m + 1) + i, m)  # guard cell of row 0
        return flat, t

    def at(self, flat: NDArray[np.int64], t: NDArray[np.float64]) -> NDArray[np.float64]:
        return self.a.take(flat) * (1.0 - t) + self.b.take(flat) * t

    def __call__(self, x: NDArray[np.float64], track: NDArray[np.int64]) -> NDArray[np.float64]:
        return self.at(*self.locate(x, track))


# ---------------------------------------------------------------- events
@dataclass
class EventStatics:
    """Static responses of a chunk of events.

    ``peaks`` (n_events, n_lines): each event's peak (largest sign·R, returned with its sign);
    ``opposite`` (n_events, n_lines): its extreme in the other direction (largest −sign·R, with its
    sign; on tabulated lines only, else None); ``histories``: per line the events' histories concatenated, ``offsets[j]`` (n_events + 1,)
    indexing line j's events, kept only when asked for (fatigue).  On tabulated lines (the
    lifetime run) a history is the exact sequence of turning points of R(t) (0, every local
    extreme, 0: ``vbikit.lifetime.peaks``), all a rainflow count needs; at given ``times`` it is
    R at those times."""

    peaks: NDArray[np.float64]
    offsets: list[NDArray[np.int64]]
    histories: Optional[list[NDArray[np.float64]]] = None
    opposite: Optional[NDArray[np.float64]] = None


#: samples of the refinement around each coarse peak (``event_static``)
REFINE = 24


def _evaluate(pts, p_all, t_all, speed, entry, sign_dir, span, lines, tables, track_ids):
    """Σ over points of g(x_p(t)) P_p for the flat (point, time) pairs: per line the terms."""
    i_all = pts.vehicle[p_all]
    travel = speed[i_all] * (t_all - entry[i_all])
    x = np.where(sign_dir[i_all] > 0, -pts.setback[p_all] + travel, span + pts.setback[p_all] - travel)
    load = pts.load[p_all]
    if tables is None:
        return [line.evaluate(x, pts.y[p_all]) * load for line in lines]
    out = []
    located = None
    for tab, ids in zip(tables, track_ids):  # lines on the same grid: locate once
        if located is None or not tab.same_grid(located[0]):
            located = (tab, *tab.locate(x, ids[p_all]))
        out.append(tab.at(located[1], located[2]) * load)
    return out


def event_static(records: Sequence[VehicleRecord], events: Sequence[Sequence[int]], lines: Sequence[InfluenceLine],
                 span: float, lanes: Sequence[float], pattern: TirePattern = TirePattern(), ds: float = 0.1,
                 tables: Optional[Sequence[Tabulated]] = None, times: Optional[Sequence[NDArray[np.float64]]] = None,
                 keep_histories: bool = False, max_samples: int = 2_000_000, refine: bool = True) -> EventStatics:
    """Static history and peak of every event (module docstring).

    ``events``: vehicle indices into ``records`` of each event; ``tables``: the tabulated lines
    (same order as ``lines``; None: evaluate the lines themselves).  With ``tables`` and no
    ``times`` (the lifetime run) the peaks are the exact extremes on the tabulated lines and the
    histories their turning points (``vbikit.lifetime.peaks``; ``ds``, ``max_samples`` and
    ``refine`` unused).  Otherwise R is sampled: at ``times`` [s] of each event, or on a grid
    of travel step ``ds`` [m] from the first entry to the last exit, padded by the tire's reach,
    each peak then refined (``refine``) on ``REFINE`` samples a step over the two steps around
    the sampled peak (the continuous maximum within (ds/REFINE)/2 · max|dR/ds|);
    ``max_samples``: samples × points evaluated at once."""
    pts = point_loads(records, lanes, pattern)
    n_ev = len(events)
    speed = np.array([r.speed for r in records])
    entry = np.array([r.time for r in records])
    sign_dir = np.array([1.0 if r.direction == "+x" else -1.0 for r in records])
    length = np.array([r.length for r in records])
    event_of = np.empty(len(records), np.int64)
    for k, members in enumerate(events):
        event_of[list(members)] = k
    track_ids = None
    if tables is not None:
        track_ids = []
        for tab in tables:
            ids = np.minimum(np.searchsorted(tab.tracks, pts.y), tab.tracks.size - 1)
            if not np.allclose(tab.tracks[ids], pts.y, rtol=0, atol=1e-9):
                raise ValueError("a wheel track of the traffic is not among the tabulated tracks")
            track_ids.append(ids)
        if times is None:
            return _exact(pts, event_of, speed, entry, sign_dir, span, lines, tables, track_ids, n_ev, keep_histories)
    pad = pattern.reach
    if times is not None:
        grids = [np.asarray(g, float) for g in times]
        t0 = np.array([g[0] for g in grids])
        dt = np.array([g[1] - g[0] if g.size > 1 else 1.0 for g in grids])
        counts = np.array([g.size for g in grids], np.int64)
    else:
        t_in = entry - pad / speed
        t_out = entry + (span + length + pad) / speed
        t0 = np.full(n_ev, np.inf)
        t1 = np.full(n_ev, -np.inf)
        vmax = np.zeros(n_ev)
        np.minimum.at(t0, event_of, t_in)
        np.maximum.at(t1, event_of, t_out)
        np.maximum.at(vmax, event_of, speed)
        dt = ds / vmax if n_ev else np.zeros(0)
        counts = (np.ceil((t1 - t0) / dt).astype(np.int64) + 1) if n_ev else np.zeros(0, np.int64)
        grids = None
    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    totals = [np.zeros(int(offsets[-1])) for _ in lines]
    # points grouped by event
    p_event = event_of[pts.vehicle]
    p_order = np.argsort(p_event, kind="stable")
    p_start = np.searchsorted(p_event[p_order], np.arange(n_ev + 1))
    work = counts * np.diff(p_start)
    k = 0
    while k < n_ev:
        k1 = k + max(1, int(np.searchsorted(np.cumsum(work[k:]), max_samples)))
        k1 = min(k1, n_ev)
        p = p_order[p_start[k]:p_start[k1]]
        ev = p_event[p]
        rep = counts[ev]
        p_all = np.repeat(p, rep)
        first = np.repeat(np.cumsum(rep) - rep, rep)
        step = np.arange(p_all.size) - first  # sample number within the event
        ev_all = np.repeat(ev, rep)
        s_local = offsets[ev_all] - offsets[k] + step
        if grids is None:
            t_all = t0[ev_all] + dt[ev_all] * step
        else:
            t_all = np.concatenate(grids[k:k1])[s_local]
        terms = _evaluate(pts, p_all, t_all, speed, entry, sign_dir, span, lines, tables, track_ids)
        n_local = int(offsets[k1] - offsets[k])
        for j in range(len(lines)):
            totals[j][offsets[k]:offsets[k1]] = np.bincount(s_local, weights=terms[j], minlength=n_local)
        k = k1
    peaks = np.empty((n_ev, len(lines)))
    at = np.empty((n_ev, len(lines)), np.int64)
    for j, line in enumerate(lines):
        s = line.sign
        if n_ev:
            peaks[:, j] = s * np.maximum.reduceat(s * totals[j], offsets[:-1])
            # sample index of each event's peak
            is_peak = (s * totals[j]) == np.repeat(s * peaks[:, j], counts)
            idx = np.flatnonzero(is_peak)
            first_peak = np.searchsorted(idx, offsets[:-1])
            at[:, j] = idx[first_peak] - offsets[:-1]
    if refine and grids is None and n_ev:
        peaks = _refine(pts, events, p_order, p_start, event_of, counts, t0, dt, at, peaks, speed, entry, sign_dir,
                        span, lines, tables, track_ids)
    return EventStatics(peaks, [offsets] * len(lines), totals if keep_histories else None)


def _refine(pts, events, p_order, p_start, event_of, counts, t0, dt, at, peaks, speed, entry, sign_dir, span, lines,
            tables, track_ids):
    """Each peak refined on REFINE samples a step over the steps either side of its coarse sample."""
    n_ev = len(events)
    out = peaks.copy()
    m = 2 * REFINE + 1
    frac = (np.arange(m) - REFINE) / REFINE  # −1 … 1 steps
    for j, line in enumerate(lines):
        # every event's points × m times around its coarse peak
        p = p_order
        ev = event_of[pts.vehicle[p]]
        p_all = np.repeat(p, m)
        ev_all = np.repeat(ev, m)
        f_all = np.tile(frac, p.size)
        t_all = t0[ev_all] + dt[ev_all] * (at[ev_all, j] + f_all)
        terms = _evaluate(pts, p_all, t_all, speed, entry, sign_dir, span, [line],
                          None if tables is None else [tables[j]], None if track_ids is None else [track_ids[j]])[0]
        slot = ev_all * m + np.tile(np.arange(m), p.size)
        r = np.bincount(slot, weights=terms, minlength=n_ev * m).reshape(n_ev, m)
        s = line.sign
        out[:, j] = s * np.maximum(s * peaks[:, j], np.max(s * r, axis=1))
    return out


def _exact(pts, event_of, speed, entry, sign_dir, span, lines, tables, track_ids, n_ev, keep) -> EventStatics:
    """Every event's exact extreme on every tabulated line and, with ``keep``, the turning points
    of its history (``vbikit.lifetime.peaks``)."""
    from vbikit.lifetime.peaks import event_extremes

    peaks = np.empty((n_ev, len(lines)))
    opposite = np.empty((n_ev, len(lines)))
    offsets, histories = [], []
    veh = pts.vehicle
    if not veh.size:  # no traffic
        return EventStatics(peaks, [np.zeros(1, np.int64) for _ in lines], [np.zeros(0) for _ in lines] if keep else None,
                            opposite)
    ev = event_of[veh]
    t_ev = np.full(n_ev, np.inf)
    np.minimum.at(t_ev, event_of, entry)
    for j, (line, tab) in enumerate(zip(lines, tables)):
        row = tab.row[track_ids[j]]
        # one load per (vehicle, setback, row): the wheels of an axle on the same row merged
        order = np.lexsort((row, pts.setback, veh, ev))
        o_veh, o_set, o_row = veh[order], pts.setback[order], row[order]
        new = np.r_[True, (o_veh[1:] != o_veh[:-1]) | (o_set[1:] != o_set[:-1]) | (o_row[1:] != o_row[:-1])]
        first = np.flatnonzero(new)
        load = np.add.reduceat(pts.load[order], first) if first.size else np.zeros(0)
        v, d, r = o_veh[first], o_set[first], o_row[first]
        e = event_of[v]
        ptr = np.searchsorted(e, np.arange(n_ev + 1)).astype(np.int64)
        hi, lo, tp, tp_ptr = event_extremes(ptr, entry[v] - t_ev[e], speed[v], sign_dir[v], d, load,
                                            r.astype(np.int64), float(span), tab.active_ptr, *tab.knots, bool(keep))
        peaks[:, j], opposite[:, j] = (hi, lo) if line.sign > 0 else (lo, hi)
        offsets.append(tp_ptr)
        histories.append(tp)
    return EventStatics(peaks, offsets, histories if keep else None, opposite)
