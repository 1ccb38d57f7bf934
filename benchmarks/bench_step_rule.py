"""How much accuracy the exact integrator's automatic step keeps in hand on traffic events: the
displacement IM at the automatic step and at 1.5, 2 and 4 times it, against RK4 at an eighth of it.

    python benchmarks/bench_step_rule.py                   # 30 one-truck and 10 two-truck events, ≈ 2 min
    python benchmarks/bench_step_rule.py --single 60 --several 20
    python benchmarks/bench_step_rule.py --timing 25      # also the cost at dt and 2 dt, every 25th event
    python benchmarks/bench_step_rule.py --road C         # another road class (--tire multipoint: another tire)

The events are those of ``bench_traffic.py``'s stream (5,000 trucks is not needed: its first 2,000;
``paper-bridge-2``, 10 modes, point tires, ISO class B road with the event's own seed, Girder 4
midspan), each crossing on the event's whole road (``EventContext.road``: every step size then reads
the same profile).  The automatic step (``vbikit.solve.timestep.implicit_time_step``) is at most
2 cm of road per step and 1/100 of the first bridge period; on these events the road term governs
(≈ 1 ms, 2,300–4,000 steps an event).  The reference is RK4 at dt/8.

The question it answers (the engine issue's next factor): the step rule was set on rough roads where
wheels lose contact (docs/verification.md: 3 cm gave up to 9.9e-4 there, so 2 cm is the rule); how
large are the errors of coarser steps on a class B road, where the stream's trucks keep contact?
Printed: per event ΔIM = IM(exact, k·dt) − IM(RK4, dt/8) for k = 1, 1.5, 2, 4, whether a wheel lost
contact, and the largest and 95th-percentile |ΔIM| per k.  With 1 cm stations and dt set by the road
(2 cm a step), k = 1, 1.5, 2 and 4 are whole stations a step for the fastest truck; with the implicit
integrators' secant road rate other steps behave alike (docs/verification.md, "The road's stations and
the tire dashpots"; ``bench_rate_alignment.py``).  ``--timing N``: also the thread CPU
time of ``simulate`` and the output reduction (``reduce_crossing``, the stream's outputs) of every
N-th event of the stream at dt and at 2 dt, three alternating rounds.
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

FACTORS = (1.0, 1.5, 2.0, 4.0)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--single", type=int, default=30, help="one-truck events (default 30)")
    p.add_argument("--several", type=int, default=10, help="two-truck events (default 10)")
    p.add_argument("--timing", type=int, default=0, help="also time every N-th event at dt and 2 dt (default 0: no)")
    p.add_argument("--road", default="B", help="ISO 8608 road class of the events (default B)")
    p.add_argument("--tire", default="point", help="tire model of the events (default point)")
    args = p.parse_args()

    import numpy as np
    from bench_traffic import _base, _stream

    from vbikit.analysis import point_response
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run
    from vbikit.traffic.study import traffic_study

    base = _base(0.01)
    base["road"]["class"] = args.road
    base["tire"]["model"] = args.tire
    job = traffic_study(_stream(2000, 600.0), base, batch_size=16)
    ctx = job.context()
    print(f"class {args.road} road, {args.tire} tires; ΔIM = IM(exact, k dt) − IM(RK4, dt/8), dt the automatic step; k = {', '.join(f'{k:g}' for k in FACTORS)}")
    for size, count in ((1, args.single), (2, args.several)):
        rows = []
        for e in [e for e in range(job.size) if len(job.events[e]) == size][:count]:
            crossing = ctx.template.with_vehicles(job.crossing(e).vehicles, *ctx.road(job.road_seed(e)))
            y = float(crossing.bridge.girder_y[3])
            dt = plan_run(crossing).grid.dt
            ims, lost = [], False
            for step, integrator in [(dt / 8, "rk4")] + [(k * dt, None) for k in FACTORS]:
                r = simulate(dataclasses.replace(crossing, dt=step, **({"integrator": integrator} if integrator else {})))
                lost |= integrator is None and bool(np.any(r.wheel_forces <= 0.0))
                ims.append(point_response(r, None, y).displacement_impact.impact_factor)
            rows.append([im - ims[0] for im in ims[1:]])
            print(f"  event {e} ({size} truck{'s' if size > 1 else ''}, {3.6 * crossing.speed:.0f} km/h, dt {1e3 * dt:.3f} ms): "
                  f"IM {ims[0]:.5f}; ΔIM " + ", ".join(f"{d:+.1e}" for d in rows[-1]) + ("; a wheel lost contact" if lost else ""),
                  flush=True)
        a = np.abs(np.array(rows))
        print(f"{size} truck(s), {len(rows)} events: max |ΔIM| " + ", ".join(f"{x:.1e}" for x in a.max(axis=0))
              + "; 95th percentile " + ", ".join(f"{x:.1e}" for x in np.percentile(a, 95, axis=0)))
    if args.timing:
        _timing(job, ctx, args.timing)


def _timing(job, ctx, every: int) -> None:
    """Thread CPU time of ``simulate`` + ``reduce_crossing`` of every ``every``-th event at dt and 2 dt."""
    import time

    from vbikit.analysis.response import reduce_crossing
    from vbikit.solve import simulate
    from vbikit.solve.plan import plan_run

    crossings = []
    for e in range(1, job.size, every):
        c = ctx.template.with_vehicles(job.crossing(e).vehicles, *ctx.road(job.road_seed(e)))
        crossings.append((c, plan_run(c).grid.dt))
    for c, _ in crossings[:3]:
        simulate(c)  # warm-up
    for _ in range(3):
        for k in (1, 2):
            t0 = time.thread_time()
            for c, dt in crossings:
                reduce_crossing(simulate(dataclasses.replace(c, dt=k * dt)), ctx.plan, names=job.output_names)
            print(f"simulate + reduction at {k} dt: {1e3 * (time.thread_time() - t0) / len(crossings):.2f} ms an event "
                  f"({len(crossings)} events)", flush=True)


if __name__ == "__main__":
    main()
