"""The governing events of a lifetime run and their half-step re-run.

For every load effect the event with the largest static peak s·R_st of the whole run governs
the static maximum, and the simulated event with the largest total peak s·R_dyn governs the
total maximum (the screening makes the latter exact: an event left out cannot exceed its day's
simulated maximum).  Each is described by its day, time of day and vehicles (axles, gross
weight, lane, direction, speed), and simulated again at half the time step of its run
(``DynamicJob.step_factor = 0.5``): the relative change of its total peak,
(R_half − R_run)/R_run, measures the time-discretisation error of the number that sets the
characteristic value; above ``vbikit.lifetime.accuracy.HALF_STEP_TOLERANCE`` it is flagged.
"""
from __future__ import annotations

import numpy as np

from vbikit.lifetime.jobs import EVENT_STRIDE, day_traffic

#: the two maxima an event can govern, in the order of the ``governs`` dimension
GOVERNS = ("static", "total")
SECONDS_PER_DAY = 86400.0


def governing_events(static: np.ndarray, total: np.ndarray, signs: np.ndarray, simulated: np.ndarray) -> np.ndarray:
    """Event indices (n_effects, 2): the largest s·R_st of all events, the largest s·R_dyn of the
    simulated ones (−1 when none was simulated)."""
    out = np.full((static.shape[1], 2), -1, np.int64)
    for j in range(static.shape[1]):
        out[j, 0] = int(np.argmax(signs[j] * static[:, j]))
        if simulated.any():
            s_tot = np.where(simulated, signs[j] * total[:, j], -np.inf)
            out[j, 1] = int(np.argmax(s_tot))
    return out


def event_vehicles(prep, stored: dict, g: int) -> list[dict]:
    """The vehicles of global event ``g``: axles, gross weight [N], lane, direction, speed [m/s],
    arrival time of day [s] (from the static pass's stored records, else the day drawn again)."""
    if g in stored:
        records = list(stored[g])
    else:
        from vbikit.lifetime.jobs import _digest
        from vbikit.lifetime.setup import build_setup

        day, k = divmod(int(g), EVENT_STRIDE)
        recs, events = day_traffic(prep.model, _digest(prep.model), build_setup(prep.setup_key), day, prep.spec.seed)
        records = [recs[i] for i in events[k]]
    return [{"axles": len(r.axle_loads), "gross_weight": float(sum(r.axle_loads)), "lane": int(r.lane or 0),
             "direction": r.direction, "speed": float(r.speed), "time_of_day": float(r.time % SECONDS_PER_DAY)}
            for r in records]


def clock(seconds: float) -> str:
    """h:mm:ss of a time of day [s]."""
    s = int(round(seconds)) % int(SECONDS_PER_DAY)
    return f"{s // 3600:d}:{s // 60 % 60:02d}:{s % 60:02d}"


def vehicles_words(vehicles: list[dict]) -> str:
    """'2 vehicles: 5-axle 402 kN lane 1 +x 81 km/h at 7:12:03; …'."""
    parts = [f"{v['axles']}-axle {v['gross_weight'] / 1e3:.0f} kN lane {v['lane']} {v['direction']} "
             f"{3.6 * v['speed']:.0f} km/h at {clock(v['time_of_day'])}" for v in vehicles]
    return f"{len(vehicles)} vehicle{'s' if len(vehicles) != 1 else ''}: " + "; ".join(parts)
