"""Synthetic traffic streams: Poisson arrivals per lane and a documented truck mix.

For examples, tests and benchmarks, not a calibrated traffic model.  Each lane has its own
direction, flow [trucks/h] and speed distribution.  Arrivals are Poisson with a minimum
headway (shifted exponential headways h = h_min + Exp(3600/flow − h_min), so that two trucks
of one lane never overlap); speeds are normal (mean, standard deviation) clipped to ±50 % of
the mean.  Each truck is drawn from ``TRUCK_MIX`` by its share; its axle loads are the
class's loaded axle loads times a load factor U ~ uniform(0.45, 1.05) (from empty to slightly
overloaded; the steer axle follows 0.8 + 0.2·U) and an independent 5 % scatter per axle; its
spacings are the class's mean plus normal scatter (0.3 m between groups, 0.05 m within).
Values are rounded as [`vbikit.traffic.records.format_records`][vbikit.traffic.format_records] writes them, so a written
and re-read stream is the same.  Same seed, same stream.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from vbikit.traffic.records import VehicleRecord


@dataclass(frozen=True)
class TruckClass:
    """A truck class.

    Parameters
    ----------
    name : str
        FHWA class name.
    share : float
        Its share of the trucks.
    axle_loads : tuple of float
        Mean loaded axle loads [N].
    axle_spacings : tuple of float
        Mean axle spacings [m].
    """

    name: str
    share: float
    axle_loads: tuple[float, ...]
    axle_spacings: tuple[float, ...]


#: [substitute] illustrative truck mix (FHWA classes; class 9, the 3-S2, dominates US WIM data).
#: Class 9 loaded axles at the US legal group limits 12 / 34 / 34 kip = 53.4 / 151.2 / 151.2 kN.
TRUCK_MIX: tuple[TruckClass, ...] = (
    TruckClass("class5-2axle", 0.20, (45e3, 90e3), (5.0,)),
    TruckClass("class6-3axle", 0.10, (55e3, 85e3, 85e3), (5.0, 1.3)),
    TruckClass("class8-2S2", 0.10, (50e3, 80e3, 70e3, 70e3), (4.0, 8.5, 1.2)),
    TruckClass("class9-3S2", 0.60, (53.4e3, 75.6e3, 75.6e3, 75.6e3, 75.6e3), (5.5, 1.3, 9.5, 1.3)),
)


@dataclass(frozen=True)
class LaneTraffic:
    """One lane of a synthetic stream.

    Parameters
    ----------
    lane : int
        Its number (1, 2, …).
    direction : str
        "+x" or "-x".
    flow : float
        Flow [trucks/h].
    speed_kmh, speed_sd_kmh : float
        Speed mean and standard deviation [km/h].
    """

    lane: int
    direction: str
    flow: float
    speed_kmh: float = 80.0
    speed_sd_kmh: float = 8.0


def synthetic_stream(lanes: Sequence[LaneTraffic], n_vehicles: int, seed: int = 0,
                     mix: Sequence[TruckClass] = TRUCK_MIX, min_headway: float = 2.0,
                     duration: Optional[float] = None) -> list[VehicleRecord]:
    """``n_vehicles`` trucks over all lanes (or every truck arriving within ``duration`` [s]),
    sorted by entry time, ids ``v000001`` …"""
    if not lanes:
        raise ValueError("a stream needs at least one lane")
    for ln in lanes:
        if ln.direction not in ("+x", "-x"):
            raise ValueError(f"lane {ln.lane}: direction must be +x or -x, got {ln.direction!r}")
        if not (ln.flow > 0 and 3600.0 / ln.flow > min_headway):
            raise ValueError(f"lane {ln.lane}: flow must be > 0 and below {3600 / min_headway:.0f} trucks/h "
                             f"(minimum headway {min_headway} s), got {ln.flow}")
        if not ln.speed_kmh > 0 or ln.speed_sd_kmh < 0:
            raise ValueError(f"lane {ln.lane}: speed_kmh must be > 0 and speed_sd_kmh >= 0")
    shares = np.array([c.share for c in mix], float)
    if np.any(shares < 0) or shares.sum() <= 0:
        raise ValueError("truck mix shares must be >= 0 and not all 0")
    rng = np.random.default_rng(seed)
    total = sum(ln.flow for ln in lanes)
    horizon = duration if duration is not None else 1.3 * n_vehicles * 3600.0 / total + 60.0
    arrivals: list[tuple[float, LaneTraffic]] = []
    for ln in lanes:
        mean = 3600.0 / ln.flow - min_headway
        t = rng.exponential(mean)
        while t < horizon:
            arrivals.append((t, ln))
            t += min_headway + rng.exponential(mean)
    arrivals.sort(key=lambda a: a[0])
    if duration is None:
        arrivals = arrivals[:n_vehicles]
    out = []
    for k, (t, ln) in enumerate(arrivals):
        cls = mix[int(rng.choice(len(mix), p=shares / shares.sum()))]
        u = rng.uniform(0.45, 1.05)
        factor = np.full(len(cls.axle_loads), u)
        factor[0] = 0.8 + 0.2 * u
        loads = np.array(cls.axle_loads) * factor * (1 + 0.05 * rng.standard_normal(len(cls.axle_loads)))
        sp = np.array(cls.axle_spacings, float)
        sp = sp + np.where(sp > 2.0, 0.3, 0.05) * rng.standard_normal(sp.size)
        sp = np.clip(sp, 0.9, None)
        v = np.clip(rng.normal(ln.speed_kmh, ln.speed_sd_kmh), 0.5 * ln.speed_kmh, 1.5 * ln.speed_kmh)
        out.append(VehicleRecord(
            time=round(float(t), 3), direction=ln.direction, speed=round(float(v), 2) * (1 / 3.6),
            axle_loads=tuple(round(float(x) / 1e3, 2) * 1e3 for x in loads),
            axle_spacings=tuple(round(float(s), 3) for s in sp), lane=ln.lane, id=f"v{k + 1:06d}", extra={"class": cls.name}))
    return out
