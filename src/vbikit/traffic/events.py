"""Traffic events: the vehicles whose times on the bridge overlap.

Vehicle i is on the bridge from its entry time t_i (front axle at its entry support) until its
last axle leaves, t_i + (span + length_i) / v_i (constant speed).  Sorting the vehicles by
entry time and sweeping, a vehicle that enters before every earlier vehicle of the current
event has left joins it; otherwise it starts a new event.  Every vehicle is in exactly one
event, and no two events overlap in time (the connected components of the overlap graph of
the intervals).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class Event:
    """Vehicles on the bridge together.

    Parameters
    ----------
    vehicles : tuple of int
        Indices of its vehicles (into the stream, in entry order).
    start, end : float
        First entry and last exit [s].
    """

    vehicles: tuple[int, ...]
    start: float
    end: float

    @property
    def multiple_presence(self) -> bool:
        return len(self.vehicles) > 1


def on_bridge_intervals(times: Sequence[float], speeds: Sequence[float], lengths: Sequence[float],
                        span: float, reach: float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Entry and exit time [s] of every vehicle (entry time [s] at its entry support, speed [m/s],
    length [m]); ``reach`` [m]: how far the deck extends beyond its supports along x (a skew deck's
    oblique ends: (width/2)·|tan θ|), on the vehicle before and after."""
    t = np.asarray(times, float)
    v = np.asarray(speeds, float)
    return t - float(reach) / v, t + (float(span) + float(reach) + np.asarray(lengths, float)) / v


def partition(times: Sequence[float], speeds: Sequence[float], lengths: Sequence[float], span: float,
              reach: float = 0.0) -> list[Event]:
    """The events of a stream (see the module docstring), in time order (``reach``: see
    [`on_bridge_intervals`][vbikit.traffic.on_bridge_intervals])."""
    start, end = on_bridge_intervals(times, speeds, lengths, span, reach)
    order = np.argsort(start, kind="stable")
    events: list[Event] = []
    members: list[int] = []
    t0 = t1 = -np.inf
    for i in order:
        if members and start[i] < t1:
            members.append(int(i))
            t1 = max(t1, end[i])
            continue
        if members:
            events.append(Event(tuple(members), float(t0), float(t1)))
        members, t0, t1 = [int(i)], start[i], end[i]
    if members:
        events.append(Event(tuple(members), float(t0), float(t1)))
    return events
