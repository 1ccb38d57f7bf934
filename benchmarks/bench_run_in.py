"""What settling the trucks costs: one-truck traffic events started at rest, after the population's
run-in (``crossing.run_in``, ``vbikit.solve.run_in``) and after a coupled approach as long, in one run.

    python benchmarks/bench_run_in.py                 # 100 events, 5 alternating rounds
    python benchmarks/bench_run_in.py --events 300 --repeat 3

The first ``--events`` one-truck events of ``bench_traffic.py``'s stream (Bridge 2, 10 modes, point
tires, ISO class B, each on its own road, the Girder 4 deflection and every catalogue output), each run
by ``TrafficStudy.run_event`` as the workers run it, with three starts built from the same base scenario:

- ``rest``: ``crossing.run_in = 0``, the trucks at rest 10 m before the bridge (the baseline);
- ``settled``: no ``run_in`` given, the population's 90 m run-in (``population_run_in``);
- ``approach``: ``crossing.approach = 100``, ``run_in = 0``, the same 100 m run coupled all the way.

Thread CPU time an event, the minimum over ``--repeat`` rounds (the three starts alternate in every
round, so a change of the machine's speed hits them alike; each start's base scenario context rebuilt
before its timed events: a process keeps one), each start's ratio to ``rest`` (the
same-run baseline), and of ``settled`` the time inside the run-in (``simulate._run_in``) and inside its two
compiled loops (``kernels.run_in_loads``, ``kernels.linear_recursion``: the arithmetic the run-in cannot
avoid; the rest is its set-up, in numpy: the recursion's matrices, the start at rest, the road bundle).
Writes nothing but numba's cache.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _args import benchmark_args  # noqa: E402


def _base(start: str) -> dict:
    crossing = {"rest": {"run_in": 0.0}, "settled": {}, "approach": {"approach": 100.0, "run_in": 0.0}}[start]
    return {"bridge": {"model": "paper-bridge-2", "n_modes": 10}, "tire": {"model": "point"},
            "road": {"class": "B", "spacing": 0.01}, **({"crossing": crossing} if crossing else {})}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--events", type=int, default=100, help="one-truck events timed (default 100)")
    args = benchmark_args(__doc__, "alternating rounds (default 5)", p)

    from bench_per_crossing import _stage_clocks
    from bench_traffic import _stream

    from vbikit.traffic.study import traffic_study

    spent = _stage_clocks({"run_in": ("vbikit.solve.simulate", "_run_in"),
                           "road loads": ("vbikit.solve.kernels", "run_in_loads"),
                           "recursion": ("vbikit.solve.kernels", "linear_recursion")})

    records = _stream(4 * args.events, 600.0)
    jobs = {start: traffic_study(records, _base(start), batch_size=16) for start in ("rest", "settled", "approach")}
    first = jobs["rest"]
    events = [e for e in range(first.size) if len(first.events[e]) == 1][:args.events]
    for job in jobs.values():
        job.run_event(events[0])  # compiled kernels and tables loaded
    best = {start: float("inf") for start in jobs}
    inside = {"run_in": float("inf"), "loops": float("inf")}
    for _ in range(max(args.repeat, 1)):
        for start, job in jobs.items():
            job.run_event(events[0])  # (a process keeps one base scenario's context: rebuilt here, untimed)
            spent.update(dict.fromkeys(spent, 0.0))
            t0 = time.thread_time()
            for e in events:
                job.run_event(e)
            best[start] = min(best[start], (time.thread_time() - t0) / len(events))
            if start == "settled":
                got = {"run_in": spent["run_in"], "loops": spent["road loads"] + spent["recursion"]}
                inside = {k: min(inside[k], got[k] / len(events)) for k in inside}
    print(f"{len(events)} one-truck events of bench_traffic.py's stream (Bridge 2, class B, point tires), thread CPU "
          f"an event, minimum of {max(args.repeat, 1)} alternating rounds:")
    for start, words in (("rest", "at rest 10 m before the bridge (run_in = 0)"),
                         ("settled", "settled: the population's 90 m run-in"),
                         ("approach", "a 100 m approach coupled all the way")):
        print(f"  {start:9s} {1e3 * best[start]:6.2f} ms  {best[start] / best['rest']:.2f} x rest   ({words})")
    print(f"  the run-in: {1e3 * inside['run_in']:.2f} ms an event, of it {1e3 * inside['loops']:.2f} ms in its two "
          f"compiled loops (road loads, recursion); settled - rest = {1e3 * (best['settled'] - best['rest']):.2f} ms")


if __name__ == "__main__":
    main()
