"""Load-effect impact factors against where the time steps fall: events of ``bench_traffic.py``'s
stream, each run at the automatic step times 1, 0.999, 0.997, 0.995, 0.99 and at 1/16 of it.

    python benchmarks/bench_effect_jumps.py                   # events 260–339
    python benchmarks/bench_effect_jumps.py --events 299 300  # those events, one line each

Per effect (the traffic study's first moment, shear and reaction: Girder 4 midspan, shear at x = 0,
support 0): the impact factor read at the steps only (``impact_factor`` of the histories: the peaks
before the jump limits) and with the one-sided limits at the jumps and the extremes between the
steps away from them (``LoadEffectResponse.impact``, ``vbikit.analysis.effects``), their spread over the five steps and their largest distance from the
1/16 run read at its steps.  Over a range: median and maximum over the events, over all events and
over those whose static peak is above half the range's largest (the ones loading the girder).
Also the thread CPU time of ``jump_limits`` per event.  Writes nothing.
"""
from __future__ import annotations

import argparse
import dataclasses
import logging
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _args import benchmark_args  # noqa: E402

SCALES = (1.0, 0.999, 0.997, 0.995, 0.99)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--events", type=int, nargs="+", default=None, help="event indices (default: 260–339, summarised)")
    args = benchmark_args(__doc__, "unused", p)
    logging.disable(logging.WARNING)  # the step notes of the off-automatic steps

    import numpy as np
    from bench_traffic import _base, _stream

    from vbikit.analysis.effects import jump_limits, load_effect_responses
    from vbikit.analysis.impact import impact_factor
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run
    from vbikit.traffic.study import traffic_study

    job = traffic_study(_stream(5000, 600.0), _base(0.01), batch_size=16)
    effects = tuple(job.context().plan.first_effects.values())
    events = args.events or list(range(260, 340))
    rows = []
    for ev in events:
        crossing = job.crossing(ev)
        dt0 = plan_run(crossing).grid.dt
        old, new = [], []
        for f in SCALES:
            result = simulate(dataclasses.replace(crossing, dt=dt0 * f))
            res = load_effect_responses(result, effects, check_step=False)
            old.append([impact_factor(r.time, r.dynamic, r.static).impact_factor for r in res])
            new.append([r.impact.impact_factor for r in res])
            if f == 1.0:
                static = [abs(r.impact.static_peak) for r in res]
                t0 = time.thread_time()
                jump_limits(result, effects)
                cpu = time.thread_time() - t0
        fine = load_effect_responses(simulate(dataclasses.replace(crossing, dt=dt0 / 16)), effects, check_step=False)
        ref = np.array([impact_factor(r.time, r.dynamic, r.static).impact_factor for r in fine])
        old, new = np.array(old), np.array(new)
        rows.append((np.ptp(old, 0), np.ptp(new, 0), np.abs(old - ref).max(0), np.abs(new - ref).max(0), static, cpu))
        if args.events:
            print(f"event {ev} ({len(job.events[ev])} vehicle(s), dt {dt0:.4g} s, jump_limits {cpu * 1e3:.2f} ms):")
            for k, e in enumerate(effects):
                print(f"  {e.kind:8s} at steps {' '.join(f'{v:.4f}' for v in old[:, k])} | with limits "
                      f"{' '.join(f'{v:.4f}' for v in new[:, k])} | 1/16 step {ref[k]:.4f}")
    if args.events:
        return
    names = ("spread, at steps", "spread, with limits", "|IM - 1/16|, at steps", "|IM - 1/16|, with limits")  # (limits and vertices)
    static = np.array([r[4] for r in rows])
    big = static > 0.5 * static.max(0)[None, :]
    for which, mask in (("all events", np.ones_like(big)), ("static > half the largest", big)):
        print(f"{which}:")
        for j, name in enumerate(names):
            arr = np.array([r[j] for r in rows])
            print(f"  {name:26s} " + "  ".join(f"{e.kind} median {np.median(arr[mask[:, k], k]):.4f} max "
                                                f"{arr[mask[:, k], k].max():.4f}" for k, e in enumerate(effects)))
    cpu = np.array([r[5] for r in rows])
    print(f"jump_limits: {1e3 * cpu.mean():.2f} ms an event (thread CPU; max {1e3 * cpu.max():.2f})")


if __name__ == "__main__":
    main()
