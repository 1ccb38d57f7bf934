"""Traffic for years from a records file: a fitted generator, or bootstrap resampling, day by day.

``fit_traffic(records)`` estimates, from WIM-like records (``vbikit.traffic.records``):

* per lane: its direction, the flow q_h [trucks/h] in each hour h of the day (hours the records
  do not cover take the lane's mean flow), and the speed (normal: mean and standard deviation,
  clipped to ±3 standard deviations and to [0.5, 1.5] × the mean);
* headways by flow: two regimes split at ``CONGESTED_HEADWAY`` = 1.5 s (congested traffic has
  headways below about 1.5 s).  A fraction p_c of a lane's recorded headways is congested; the
  generator draws a congested headway (uniform between the smallest recorded headway h_min and
  1.5 s) with probability p_c, else a free-flowing one: h_min + an exponential part of mean
  m_h = (3600/q_h − p_c h̄_c)/(1 − p_c) − h_min (h̄_c the mean congested headway), so that the mean
  headway is 3600/q_h, drawn at the flow of each hour it runs through (a Poisson process of
  piecewise-constant rate: a gap drawn at a quiet hour does not run on through the busy ones);
* the class mix: vehicles classed by their number of axles, each class's share;
* per class, the gross vehicle weight (GVW) as a normal mixture of up to two components
  (empty / loaded), fitted by expectation–maximisation (Dempster, Laird & Rubin 1977; the
  mixture model of GVW as in BTLS/pybtls's ``MultiModalNormal``); the axle-load split as each
  axle's mean share of the GVW with its standard deviation; each axle spacing as a normal
  (mean, standard deviation).

``TrafficModel.day(d, seed)`` draws day d's vehicles (a list of ``VehicleRecord``, times from the
start of day 0) with the random stream ``numpy.random.default_rng([seed, d])``: a day depends only
on the model, the seed and its index, so days can be generated in any order, on any worker, and
memory is bounded by one day whatever the length.  ``mode = "bootstrap"`` draws each vehicle's
axles and speed from a random record of its lane instead of the fitted distributions (arrivals
from the same flow and headway model).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from numpy.typing import NDArray

from vbikit.traffic.records import VehicleRecord

#: headways below this are congested [s]
CONGESTED_HEADWAY = 1.5
#: [substitute] smallest generated axle load [N] (above the heaviest default unsprung weight of
#: vbikit.vehicle.axle_truck, 1,100 kg; an empty truck's axle carries more)
MIN_AXLE_LOAD = 15e3
#: smallest headway the generator uses [s] (two trucks of a lane never overlap at highway speeds)
MIN_HEADWAY = 1.0
SECONDS_PER_DAY = 86400.0
MODES = ("fitted", "bootstrap")


@dataclass(frozen=True)
class NormalMixture:
    """A normal mixture: weights, means, standard deviations (each a tuple)."""

    weights: tuple[float, ...]
    means: tuple[float, ...]
    sds: tuple[float, ...]

    def sample(self, rng: np.random.Generator, n: int) -> NDArray[np.float64]:
        k = rng.choice(len(self.weights), size=n, p=np.asarray(self.weights) / sum(self.weights))
        return rng.normal(np.asarray(self.means)[k], np.asarray(self.sds)[k])

    def pdf(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(x, float)[..., None]
        w, m, s = (np.asarray(a) for a in (self.weights, self.means, self.sds))
        return np.sum(w * np.exp(-0.5 * ((x - m) / s) ** 2) / (s * math.sqrt(2 * math.pi)), axis=-1)


def fit_mixture(x: Sequence[float], components: int = 2, iterations: int = 200, seed: int = 0) -> NormalMixture:
    """Normal mixture of ``components`` components fitted by EM (Dempster, Laird & Rubin 1977),
    started from the sample's quantiles; fewer components if the sample is too small (< 10 values
    per component).  Standard deviations are floored at 1 % of the sample's spread."""
    x = np.asarray(x, float)
    k = max(1, min(components, x.size // 10))
    spread = float(np.std(x)) or max(abs(float(np.mean(x))) * 0.05, 1.0)
    if k == 1:
        return NormalMixture((1.0,), (float(x.mean()),), (max(spread, 0.01 * spread),))
    w = np.full(k, 1.0 / k)
    mu = np.quantile(x, (np.arange(k) + 0.5) / k)
    sd = np.full(k, spread / k)
    floor = 0.01 * spread
    for _ in range(iterations):
        dens = w * np.exp(-0.5 * ((x[:, None] - mu) / sd) ** 2) / sd
        tot = dens.sum(axis=1, keepdims=True)
        tot[tot == 0] = 1e-300
        r = dens / tot
        nk = r.sum(axis=0) + 1e-12
        w_new = nk / x.size
        mu_new = (r * x[:, None]).sum(axis=0) / nk
        sd_new = np.maximum(np.sqrt((r * (x[:, None] - mu_new) ** 2).sum(axis=0) / nk), floor)
        done = np.allclose(mu_new, mu, rtol=1e-9, atol=1e-9 * spread)
        w, mu, sd = w_new, mu_new, sd_new
        if done:
            break
    order = np.argsort(mu)
    return NormalMixture(tuple(map(float, w[order])), tuple(map(float, mu[order])), tuple(map(float, sd[order])))


@dataclass(frozen=True)
class ClassModel:
    """One vehicle class (by axle count): share, GVW mixture [N], axle shares of the GVW (mean,
    sd), spacings [m] (mean, sd), and its recorded vehicles (bootstrap)."""

    n_axles: int
    share: float
    gvw: NormalMixture
    axle_share: tuple[tuple[float, float], ...]
    spacing: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class LaneModel:
    """One lane: direction, flow per hour of the day [trucks/h], congested fraction, smallest
    headway [s], speed mean and sd [m/s], and the indices of its records (bootstrap)."""

    lane: int
    direction: str
    hourly_flow: tuple[float, ...]
    congested_fraction: float
    min_headway: float
    speed_mean: float
    speed_sd: float
    records: tuple[int, ...]

    @property
    def daily_flow(self) -> float:
        """Trucks a day."""
        return float(sum(self.hourly_flow))

    @property
    def max_flow(self) -> float:
        """The largest flow [trucks/h] the headway model can generate: every free-flowing headway at
        its least, h_min (the congested ones uniform on [h_min, 1.5 s])."""
        h_c = 0.5 * (self.min_headway + max(CONGESTED_HEADWAY, self.min_headway))
        p_c = min(max(self.congested_fraction, 0.0), 1.0)
        return 3600.0 / (p_c * h_c + (1.0 - p_c) * self.min_headway)


@dataclass(frozen=True)
class TrafficModel:
    """The fitted traffic (module docstring); ``records``: the records it was fitted to."""

    lanes: tuple[LaneModel, ...]
    classes: tuple[ClassModel, ...]
    records: tuple[VehicleRecord, ...]
    mode: str = "fitted"
    #: every vehicle at this speed [m/s] (None: the fitted / recorded speeds)
    fixed_speed: Optional[float] = None

    @property
    def trucks_per_day(self) -> float:
        return float(sum(ln.daily_flow for ln in self.lanes))

    def with_mode(self, mode: str) -> "TrafficModel":
        if mode not in MODES:
            raise ValueError(f"traffic mode must be one of {', '.join(MODES)}, got {mode!r}")
        return TrafficModel(self.lanes, self.classes, self.records, mode, self.fixed_speed)

    def with_speed(self, speed: Optional[float]) -> "TrafficModel":
        """Every vehicle at ``speed`` [m/s] (None: the fitted or recorded speeds)."""
        return TrafficModel(self.lanes, self.classes, self.records, self.mode, speed)

    def max_scale(self) -> float:
        """The largest factor of ``scaled`` whose every hourly flow the headway model can generate
        (``LaneModel.max_flow``); above it the generated flows fall short of those asked for."""
        return float(min((ln.max_flow / max(ln.hourly_flow) for ln in self.lanes if max(ln.hourly_flow) > 0),
                         default=math.inf))

    def scaled(self, factor: float) -> "TrafficModel":
        """The same traffic with every flow times ``factor`` (e.g. a target trucks a day)."""
        lanes = tuple(LaneModel(ln.lane, ln.direction, tuple(q * factor for q in ln.hourly_flow), ln.congested_fraction,
                                ln.min_headway, ln.speed_mean, ln.speed_sd, ln.records) for ln in self.lanes)
        return TrafficModel(lanes, self.classes, self.records, self.mode, self.fixed_speed)

    # ------------------------------------------------------------ generation
    def arrivals(self, lane: LaneModel, rng: np.random.Generator, t0: float) -> NDArray[np.float64]:
        """Arrival times [s] of one lane over one day starting at t0 (hour by hour flows)."""
        out = []
        t = 0.0
        h_min, p_c = lane.min_headway, lane.congested_fraction
        h_c = 0.5 * (h_min + max(CONGESTED_HEADWAY, h_min))  # the mean congested headway

        def free_excess(q: float) -> float:
            """Mean of the exponential part of a free-flowing headway at flow q [1/h], such that the
            mean headway of both regimes together is 3600/q (the recorded headways include the
            congested ones)."""
            return max((3600.0 / q - p_c * h_c) / (1.0 - p_c) - h_min, 1e-3)

        while t < SECONDS_PER_DAY:
            q = lane.hourly_flow[min(int(t // 3600), 23)]
            if q <= 0:
                t = (int(t // 3600) + 1) * 3600.0
                continue
            if p_c >= 1.0 or rng.random() < p_c:
                t += rng.uniform(h_min, max(CONGESTED_HEADWAY, h_min))
            else:
                # the exponential part at the flow of each hour it runs through (a Poisson process
                # of piecewise-constant rate): a gap drawn at a quiet hour's flow does not run on
                # through the busy hours after it
                e = rng.exponential(1.0)
                t += h_min
                while t < SECONDS_PER_DAY:
                    hour = min(int(t // 3600), 23)
                    q_h = lane.hourly_flow[hour]
                    end = (hour + 1) * 3600.0
                    if q_h > 0:
                        m = free_excess(q_h)
                        if e * m <= end - t:
                            t += e * m
                            break
                        e -= (end - t) / m
                    t = end
            if t < SECONDS_PER_DAY:
                out.append(t)
        return t0 + np.asarray(out)

    def day(self, d: int, seed: int) -> list[VehicleRecord]:
        """Day ``d``'s vehicles, sorted by time (module docstring)."""
        rng = np.random.default_rng([int(seed), int(d)])
        shares = np.array([c.share for c in self.classes])
        out: list[tuple[float, VehicleRecord]] = []
        for ln in self.lanes:
            times = self.arrivals(ln, rng, d * SECONDS_PER_DAY)
            n = times.size
            if self.mode == "bootstrap":
                picks = rng.choice(np.asarray(ln.records), size=n)
                speeds = np.array([self.records[i].speed for i in picks])
                axles = [(self.records[i].axle_loads, self.records[i].axle_spacings) for i in picks]
            else:
                speeds = np.clip(rng.normal(ln.speed_mean, ln.speed_sd, n),
                                 max(0.5 * ln.speed_mean, ln.speed_mean - 3 * ln.speed_sd),
                                 min(1.5 * ln.speed_mean, ln.speed_mean + 3 * ln.speed_sd))
                cls = rng.choice(len(self.classes), size=n, p=shares / shares.sum())
                axles = [None] * n
                for c, model in enumerate(self.classes):
                    sel = np.flatnonzero(cls == c)
                    for k, v in zip(sel, self._vehicles(model, rng, sel.size)):
                        axles[k] = v
            if self.fixed_speed is not None:
                speeds = np.full(n, float(self.fixed_speed))
            for t, v, (loads, spacings) in zip(times, speeds, axles):
                out.append((float(t), VehicleRecord(round(float(t), 3), ln.direction, float(v), tuple(loads),
                                                    tuple(spacings), lane=ln.lane)))
        out.sort(key=lambda a: a[0])
        return [r for _, r in out]

    @staticmethod
    def _vehicles(c: ClassModel, rng: np.random.Generator, n: int) -> list[tuple[tuple[float, ...], tuple[float, ...]]]:
        """``n`` vehicles of class ``c``: GVW from its mixture (floored at max(μ₁ − 3σ₁, 0.2 μ₁)),
        axle shares normal (floored at 0.02, renormalised; every axle load at least
        ``MIN_AXLE_LOAD``), spacings normal clipped to ±3 sd
        (and to 0.5 … 30 m)."""
        if n == 0:
            return []
        lo = max(c.gvw.means[0] - 3 * c.gvw.sds[0], 0.2 * c.gvw.means[0])
        gvw = np.maximum(c.gvw.sample(rng, n), lo)
        m, sd = (np.array([a[k] for a in c.axle_share]) for k in (0, 1))
        share = np.maximum(rng.normal(m, sd, (n, m.size)), 0.02)
        loads = np.maximum(gvw[:, None] * share / share.sum(axis=1, keepdims=True), MIN_AXLE_LOAD)
        if c.spacing:
            ms, ss = (np.array([a[k] for a in c.spacing]) for k in (0, 1))
            sp = np.clip(rng.normal(ms, ss, (n, ms.size)), np.maximum(ms - 3 * ss, 0.5), np.minimum(ms + 3 * ss, 30.0))
        else:
            sp = np.zeros((n, 0))
        return [(tuple(map(float, loads[i])), tuple(map(float, sp[i]))) for i in range(n)]


def fit_traffic(records: Sequence[VehicleRecord], mode: str = "fitted", components: int = 2) -> TrafficModel:
    """Fit the generator to ``records`` (module docstring).  ValueError if a lane has fewer than
    two vehicles or a record has no lane or is a preset vehicle."""
    if mode not in MODES:
        raise ValueError(f"traffic mode must be one of {', '.join(MODES)}, got {mode!r}")
    for r in records:
        if r.model != "axles" or r.lane is None:
            raise ValueError(f"record {r.id or r.line}: lifetime traffic needs axle records with a lane number")
    t_all = np.array([r.time for r in records])
    lanes = []
    for lane in sorted({r.lane for r in records}):
        idx = [i for i, r in enumerate(records) if r.lane == lane]
        if len(idx) < 2:
            raise ValueError(f"lane {lane}: {len(idx)} record(s); fitting a lane needs at least 2")
        dirs = {records[i].direction for i in idx}
        if len(dirs) != 1:
            raise ValueError(f"lane {lane}: vehicles in both directions; give each direction its own lane")
        t = np.sort(t_all[idx])
        h = np.diff(t)
        span_s = max(float(t[-1] - t[0]), 1.0)
        # flow per hour of the day over the hours the records cover (hours partly covered weighted by coverage)
        counts, cover = np.zeros(24), np.zeros(24)
        for k in range(int(t[0] // 3600), int(t[-1] // 3600) + 1):
            lo, hi = max(k * 3600.0, t[0]), min((k + 1) * 3600.0, t[-1])
            if hi > lo:
                cover[k % 24] += (hi - lo) / 3600.0
        np.add.at(counts, (t // 3600).astype(int) % 24, 1.0)
        mean_flow = (len(idx) - 1) / span_s * 3600.0
        hourly = tuple(float(counts[k] / cover[k]) if cover[k] >= 0.25 else mean_flow for k in range(24))
        v = np.array([records[i].speed for i in idx])
        lanes.append(LaneModel(int(lane), dirs.pop(), hourly, float(np.mean(h < CONGESTED_HEADWAY)),
                               max(MIN_HEADWAY, float(h.min())), float(v.mean()), float(v.std()), tuple(idx)))
    classes = []
    n_axles = np.array([len(r.axle_loads) for r in records])
    for k in sorted(set(n_axles.tolist())):
        members = [r for r in records if len(r.axle_loads) == k]
        gvw = np.array([r.gross_weight for r in members])
        shares = np.array([np.asarray(r.axle_loads) / r.gross_weight for r in members])
        sp = np.array([r.axle_spacings for r in members]).reshape(len(members), k - 1)
        classes.append(ClassModel(int(k), len(members) / len(records), fit_mixture(gvw, components),
                                  tuple((float(m), float(s)) for m, s in zip(shares.mean(0), shares.std(0))),
                                  tuple((float(m), float(s)) for m, s in zip(sp.mean(0), sp.std(0)))))
    return TrafficModel(tuple(lanes), tuple(classes), tuple(records), mode)
