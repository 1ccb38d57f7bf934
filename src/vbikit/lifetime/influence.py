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

``event_static`` evaluates R(t) of every event on a time grid of travel step ``ds`` (dt = ds /
fastest speed of the event), all events of a chunk at once (numpy: one flat array of samples ×
points, summed with ``bincount``).  For speed the influence lines are tabulated along every
wheel track on a grid of ``dx`` and interpolated linearly (``exact=False``); ``exact=True``
evaluates the functions themselves (the test against the coupled run's static reference).
The sampled peak misses the continuous maximum by at most (ds/2)·max|dR/ds| (the largest slope
of the response with travel); docs/lifetime.md gives the numbers.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit.bridge.base import ModalBridge
from vbikit.outputs import QUANTITIES
from vbikit.solve.tabulate import tabulate_tracks
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
        +1 or −1: the direction the effect is governed in (the sign of g's largest magnitude:
        −1 for a downward deflection or a hogging moment); peaks are largest values of sign·R.
    effect : object, optional
        The ``vbikit.bridge.effects.LoadEffect`` (None for a deflection).
    x, y : float
        The section / response point [m].
    """

    name: str
    kind: str
    units: str
    evaluate: Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]] = field(repr=False)
    sign: float
    effect: object = field(default=None, repr=False)
    x: float = math.nan
    y: float = math.nan


def _hermite(table, track: int, x: NDArray[np.float64]) -> NDArray[np.float64]:
    """φ̃(x) (n, n_modes) on tabulated track ``track`` (the formulas of ``vbikit.solve.kernels.shape_point``)."""
    V, S, h = table.values[track], table.slopes[track], table.spacing
    n_grid = V.shape[0]
    u = (x - table.start[track]) / h
    i = np.minimum(u.astype(np.int64), n_grid - 2)
    t = u - i
    t2, t3 = t * t, t * t * t
    h00 = 2 * t3 - 3 * t2 + 1
    h10 = (t3 - 2 * t2 + t) * h
    h01 = -2 * t3 + 3 * t2
    h11 = (t3 - t2) * h
    return h00[:, None] * V[i] + h10[:, None] * S[i] + h01[:, None] * V[i + 1] + h11[:, None] * S[i + 1]


def deflection_line(bridge: ModalBridge, x_r: float, y_r: float, name: str = "") -> InfluenceLine:
    """Deflection at (x_r, y_r) [m] per unit downward load [m/N] from the retained modes (module docstring)."""
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
                out[sel] = -(_hermite(table, 0, x[sel]) @ coef)
        return out

    return _with_sign(InfluenceLine(name or f"deflection_x{x_r:g}", "deflection", KIND_UNITS["deflection"], evaluate,
                                    -1.0, None, float(x_r), float(y_r)), bridge, y_r)


def effect_line(bridge: ModalBridge, effect, name: str = "", y: float = 0.0) -> InfluenceLine:
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
                                    float(y)), bridge, y)


def _with_sign(line: InfluenceLine, bridge: ModalBridge, y: float) -> InfluenceLine:
    x = np.linspace(0.0, float(bridge.span), 2001)
    g = line.evaluate(x + float(-bridge.span_coordinate(0.0, y)), np.full(x.size, float(y)))
    k = int(np.argmax(np.abs(g)))
    if g[k] == 0.0:
        raise ValueError(f"load effect {line.name}: its influence line is zero everywhere on the span")
    return InfluenceLine(line.name, line.kind, line.units, line.evaluate, float(np.sign(g[k])), line.effect, line.x,
                         line.y)


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
    record gives its lateral offset; the wheels' y mirrored for −x traffic)."""
    veh, setback, ys, loads = [], [], [], []
    pd = np.asarray(pattern.setback, float)
    pw = np.asarray(pattern.share, float)
    for i, r in enumerate(records):
        if r.model != "axles":
            raise ValueError(f"record {r.id or r.line}: model {r.model!r}; lifetime traffic takes axle records")
        y0 = r.lateral_offset if r.lateral_offset is not None else lanes[r.lane - 1]
        sign = 1.0 if r.direction == "+x" else -1.0
        d = np.concatenate([[0.0], np.cumsum(r.axle_spacings)])
        for side in (half_track, -half_track):
            for da, pa in zip(d, r.axle_loads):
                veh.append(np.full(pd.size, i))
                setback.append(da + pd)
                ys.append(np.full(pd.size, y0 + sign * side))
                loads.append(0.5 * pa * pw)
    return PointLoads(np.concatenate(veh).astype(np.int64), np.concatenate(setback), np.concatenate(ys),
                      np.concatenate(loads))


# ---------------------------------------------------------------- tabulated lines
class Tabulated:
    """An influence line tabulated along a set of wheel tracks y on a grid of ``dx`` [m] over the
    deck's x extent, interpolated linearly (error ≤ dx²/8 · max|g''| between kinks, and at a
    kink — a moment line under the section — at most dx·|jump of g'|/4)."""

    def __init__(self, line: InfluenceLine, bridge: ModalBridge, tracks: Sequence[float], dx: float):
        first, last = bridge.deck_extent
        self.x0 = float(min(first, 0.0))
        n = int(math.ceil((max(last, bridge.span) - self.x0) / dx)) + 1
        self.h = (max(last, bridge.span) - self.x0) / (n - 1)
        self.tracks = np.asarray(sorted(set(float(y) for y in tracks)), float)
        x = self.x0 + self.h * np.arange(n)
        self.values = np.stack([line.evaluate(x, np.full(n, y)) for y in self.tracks])
        self.values = np.concatenate([self.values, np.zeros((len(self.tracks), 1))], axis=1)  # guard cell

    def __call__(self, x: NDArray[np.float64], track: NDArray[np.int64]) -> NDArray[np.float64]:
        n = self.values.shape[1] - 1
        u = (x - self.x0) / self.h
        inside = (u >= 0.0) & (u <= n - 1)
        u = np.where(inside, u, 0.0)
        i = np.minimum(u.astype(np.int64), n - 2)
        t = u - i
        v = self.values[track, i] * (1.0 - t) + self.values[track, i + 1] * t
        return np.where(inside, v, 0.0)


# ---------------------------------------------------------------- events
@dataclass
class EventStatics:
    """Static responses of a chunk of events.

    ``peaks`` (n_events, n_lines): each event's peak (largest sign·R, returned with its sign);
    ``histories``: per line the sampled R(t) of every event, concatenated (``offsets`` (n_events
    + 1,) index the events' samples), kept only when asked for (fatigue)."""

    peaks: NDArray[np.float64]
    offsets: NDArray[np.int64]
    histories: Optional[list[NDArray[np.float64]]] = None


def event_static(records: Sequence[VehicleRecord], events: Sequence[Sequence[int]], lines: Sequence[InfluenceLine],
                 span: float, lanes: Sequence[float], pattern: TirePattern = TirePattern(), ds: float = 0.1,
                 tables: Optional[Sequence[Tabulated]] = None, times: Optional[Sequence[NDArray[np.float64]]] = None,
                 keep_histories: bool = False, max_samples: int = 4_000_000) -> EventStatics:
    """Static history and peak of every event (module docstring).

    ``events``: vehicle indices into ``records`` of each event; ``tables``: the tabulated lines
    (same order as ``lines``; None: exact evaluation); ``times``: the sample times [s] of each
    event (default: a grid of travel step ``ds`` [m] from the first entry to the last exit, padded
    by the tire's reach); ``max_samples``: samples × points evaluated at once (memory bound)."""
    pts = point_loads(records, lanes, pattern)
    n_ev = len(events)
    speed = np.array([r.speed for r in records])
    entry = np.array([r.time for r in records])
    sign_dir = np.array([1.0 if r.direction == "+x" else -1.0 for r in records])
    length = np.array([r.length for r in records])
    # points of each vehicle (pts.vehicle is sorted by vehicle)
    vstart = np.searchsorted(pts.vehicle, np.arange(len(records) + 1))
    pad = pattern.reach
    grids = []
    for k, members in enumerate(events):
        if times is not None:
            grids.append(np.asarray(times[k], float))
            continue
        m = np.asarray(members)
        t0 = float(np.min(entry[m] - pad / speed[m]))
        t1 = float(np.max(entry[m] + (span + length[m] + pad) / speed[m]))
        dt = ds / float(speed[m].max())
        grids.append(t0 + dt * np.arange(int(math.ceil((t1 - t0) / dt)) + 1))
    counts = np.array([g.size for g in grids], np.int64)
    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    totals = [np.zeros(int(offsets[-1])) for _ in lines]
    track_ids = None
    if tables is not None:
        track_ids = [np.searchsorted(tab.tracks, pts.y) for tab in tables]
        for tab, ids in zip(tables, track_ids):
            if not np.allclose(tab.tracks[np.minimum(ids, tab.tracks.size - 1)], pts.y, rtol=0, atol=1e-12):
                raise ValueError("a wheel track of the traffic is not among the tabulated tracks")
    # work through the events in groups bounded by samples × points
    k = 0
    while k < n_ev:
        work, k1 = 0, k
        while k1 < n_ev and (k1 == k or work < max_samples):
            n_pts = sum(vstart[i + 1] - vstart[i] for i in events[k1])
            work += int(counts[k1]) * int(n_pts)
            k1 += 1
        # flat (sample, point) pairs of events k … k1-1
        p_idx, s_idx = [], []
        for e in range(k, k1):
            for i in events[e]:
                p = np.arange(vstart[i], vstart[i + 1])
                p_idx.append(np.repeat(p, counts[e]))
                s_idx.append(np.tile(np.arange(offsets[e], offsets[e + 1]), p.size))
        if p_idx:
            p_all = np.concatenate(p_idx)
            s_all = np.concatenate(s_idx)
            t_all = np.concatenate(grids[k:k1])[s_all - offsets[k]]
            i_all = pts.vehicle[p_all]
            travel = speed[i_all] * (t_all - entry[i_all])
            x = np.where(sign_dir[i_all] > 0, -pts.setback[p_all] + travel, span + pts.setback[p_all] - travel)
            for j, line in enumerate(lines):
                g = tables[j](x, track_ids[j][p_all]) if tables is not None else line.evaluate(x, pts.y[p_all])
                totals[j][offsets[k]:offsets[k1]] += np.bincount(s_all - offsets[k], weights=g * pts.load[p_all],
                                                                 minlength=int(offsets[k1] - offsets[k]))
        k = k1
    peaks = np.empty((n_ev, len(lines)))
    for j, line in enumerate(lines):
        s = line.sign
        peaks[:, j] = s * np.maximum.reduceat(s * totals[j], offsets[:-1]) if n_ev else np.empty(0)
    return EventStatics(peaks, offsets, totals if keep_histories else None)
