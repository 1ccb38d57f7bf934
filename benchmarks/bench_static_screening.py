"""Static screening (the lifetime static pass: every event's exact peak on tabulated influence
lines) against pybtls (BTLS) on the same traffic and influence lines, in one run.

    python benchmarks/bench_static_screening.py                  # 2 days of the example's traffic
    python benchmarks/bench_static_screening.py --days 7 --repeat 3

1. traffic: the example's generator (examples/lifetime: fitted to its day of records, two lanes,
   both directions), ``--days`` days, seeded; the same vehicles are handed to BTLS as the peer
   test does (tests/lifetime/test_peer_pybtls.py's ``btls_traffic``: axle weights, spacings,
   widths 1.8 m, speed, time, direction);
2. bridge: the example's 16.76 m simply supported beam (paper-bridge-2-beam), influence lines of
   the midspan moment and of the entry reaction — vbikit's tables at the example's dx = 0.02 m
   and, for BTLS, the same lines as discrete influence lines through their kinks (0, 8.38,
   16.76 m; exact for these piecewise-linear lines); a third, curved line (the midspan
   deflection from 4 modes, a knot at every node of the table) for vbikit only;
3. vbikit: per day, the day's events cut from its stream (``day_events``, as in a run; BTLS finds
   its events inside its run) and ``event_static`` on them, thread CPU time of both, the minimum
   over ``--repeat`` repeats, per line set; BTLS: one ``Simulation`` over the days at
   ``--btls-step`` (default 1 ms, as tests/lifetime/test_peer_pybtls.py), block maxima written,
   one core, thread CPU time (BTLS runs in this thread), minimum over the repeats;
4. prints trucks per second of each and their ratio, and the daily maxima of both (they agree
   to BTLS's output rounding, 0.1 kN m / 0.1 kN).

BTLS is optional (``pip install pybtls``, a test extra); without it only vbikit's numbers are
printed.  Writes BTLS's output into a temporary folder (deleted).
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _args import benchmark_args  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
L = 16.76
SECTION = 8.38


def _ours(days, setup, lines):
    from vbikit.lifetime.influence import event_static
    from vbikit.lifetime.setup import day_events

    idx = [j for j, ln in enumerate(setup.lines) if ln.name in lines]
    peaks, n_events = [], 0
    t = time.thread_time()
    for recs in days:  # the day's events cut from its stream (BTLS finds its own events in its run) and their peaks
        evs = day_events(setup, recs)
        n_events += len(evs)
        peaks.append(event_static(recs, evs, [setup.lines[j] for j in idx], setup.span, setup.lanes, setup.pattern,
                                  0.1, [setup.tables[j] for j in idx]).peaks)
    return time.thread_time() - t, peaks, n_events


def _btls(days, step, out):
    import importlib.util

    import numpy as np
    import pybtls

    spec = importlib.util.spec_from_file_location("peer", ROOT / "tests" / "lifetime" / "test_peer_pybtls.py")
    peer = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(peer)  # the peer test's traffic loader: the same vehicles as the test hands BTLS
    loader = peer.btls_traffic(days)
    bridge = pybtls.Bridge(length=L, no_lane=2)
    for ordinate in ([0.0, SECTION * (L - SECTION) / L, 0.0], [1.0, 1.0 - SECTION / L, 0.0]):
        il = pybtls.InfluenceLine("discrete")
        il.set_IL(position=[0.0, SECTION, L], ordinate=ordinate)
        bridge.add_load_effect(il)
    config = pybtls.OutputConfig()
    config.set_BM_output(write_summary=True, block_size_days=1)
    sim = pybtls.Simulation(out)
    sim.add_sim(bridge=bridge, traffic=loader, no_day=len(days), output_config=config, time_step=step, tag="peer")
    t = time.thread_time()
    sim.run(no_core=1)
    cpu = time.thread_time() - t
    maxima = []
    for eff in (1, 2):
        text = next((Path(out) / "peer").glob(f"BM_S_*_Eff_{eff}.txt")).read_text()
        maxima.append([max(float(v) for v in line.split()[1:]) * 1e3 for line in text.splitlines() if line.strip()])
    return cpu, np.array(maxima).T


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--days", type=int, default=2)
    p.add_argument("--btls-step", type=float, default=0.001, help="BTLS time step [s]")
    args = benchmark_args(__doc__, "repeats (the minimum CPU time is reported)", p)

    import numpy as np

    from vbikit.lifetime.run import prepare
    from vbikit.lifetime.spec import read_lifetime

    prep = prepare(*read_lifetime(ROOT / "examples" / "lifetime" / "lifetime.toml"))
    setup = prep.setup
    days = [prep.model.day(d, prep.spec.seed) for d in range(args.days)]
    n_trucks = sum(len(r) for r in days)
    print(f"{args.days} days, {n_trucks:,} trucks; lines tabulated at dx = {prep.spec.dx:g} m")
    _ours(days[:1], setup, {"M_mid"})  # warm-up (numba cache load)
    ours = {}
    for label, lines in (("moment + reaction", {"M_mid", "R_entry"}), ("moment + reaction + deflection",
                                                                        {"M_mid", "R_entry", "w_mid"})):
        cpu = min(_ours(days, setup, lines)[0] for _ in range(args.repeat))
        _, peaks, n_ev = _ours(days, setup, lines)
        ours[label] = (cpu, peaks)
        print(f"vbikit exact static pass, {label}: {cpu:.3f} s CPU, {1e6 * cpu / n_trucks:.1f} µs a truck, "
              f"{n_trucks / cpu:,.0f} trucks/s ({n_ev:,} events)")
    try:
        import pybtls  # noqa: F401
    except ImportError:
        print("pybtls not installed: no peer numbers")
        return
    runs = []
    for _ in range(args.repeat):
        with tempfile.TemporaryDirectory() as tmp:
            runs.append(_btls(days, args.btls_step, tmp))
    cpu_b = min(r[0] for r in runs)
    maxima = runs[0][1]
    print(f"BTLS (pybtls), moment + reaction, time step {args.btls_step:g} s: {cpu_b:.3f} s CPU, "
          f"{1e6 * cpu_b / n_trucks:.1f} µs a truck, {n_trucks / cpu_b:,.0f} trucks/s")
    cpu_o = ours["moment + reaction"][0]
    print(f"ratio (same lines, same traffic): vbikit {cpu_b / cpu_o:.1f}× BTLS's trucks per second")
    peaks = ours["moment + reaction"][1]
    mine = np.array([[pk[:, 0].max(), pk[:, 1].max()] for pk in peaks])
    print("daily maxima, vbikit / BTLS [kN m, kN]:")
    for d in range(args.days):
        print(f"  day {d}: M {mine[d, 0] / 1e3:.1f} / {maxima[d, 0] / 1e3:.1f}   "
              f"R {mine[d, 1] / 1e3:.1f} / {maxima[d, 1] / 1e3:.1f}")


if __name__ == "__main__":
    main()
