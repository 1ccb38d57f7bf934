"""Cold start of the default path: a fresh install's first run, with the kernels shipped compiled
(``vbikit.solve.prebuilt``) and, with ``--compile``, numba's own first compilation of them, per kernel.

Each case runs in a fresh process with an empty ``NUMBA_CACHE_DIR`` (a temporary directory), into which
vbikit puts the kernels it ships compiled (``--compile``: ``VBIKIT_HOST_KERNELS=1``, none put there, numba
compiles every kernel for this machine's CPU):
the first run of the crossing as ``vbikit run`` does it (``simulate`` and the response point's
impact factor; compiles every kernel they need), then ``--repeat`` warm runs of the same; a second fresh process with the same cache directory then
runs the crossing once more and must load every kernel from the cache (no compilation).

    python benchmarks/bench_compile.py                 # the demo crossing and the 3D deck, ≈ 1 min
    python benchmarks/bench_compile.py --case demo     # one case
    python benchmarks/bench_compile.py --compile       # without the shipped kernels: numba compiles them

Reported per case: the compile time in CPU seconds (``time.process_time`` over numba's
"numba:compile" events, robust to other load on the machine) per top-level kernel (inclusive
of the helpers it compiles) and the wall time of the first call; the warm median of the same
crossing; the ratio of the first call's compile time to that warm run (the figure to compare
between versions, both measured in the same process); and the second process's first call and
number of compilations (0 when the on-disk cache is hit).
"""
from __future__ import annotations

import argparse
import collections
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "demo": None,  # `vbikit demo`: HS20-44 on the 16.76 m beam, multipoint n = 6, ISO C, 75 km/h
    "deck": ROOT / "examples" / "paper" / "bridge2_hs20_girder4.toml",  # 3D paper-bridge-2, Girder 4
}


def _crossing(case: str):
    """The case's crossing and what ``vbikit run`` computes of it: ``simulate`` and the response
    point's history with its static reference (the impact factor)."""
    from vbikit.analysis import point_response
    from vbikit.scenario import demo_scenario_text, load_scenario, scenario_from_toml
    from vbikit.scenario.preflight import preflight
    from vbikit.solve import simulate

    path = CASES[case]
    scenario = scenario_from_toml(demo_scenario_text(), source="demo.toml") if path is None else load_scenario(path)
    built = preflight(scenario).built
    return lambda: point_response(simulate(built.crossing), built.response_x, built.response_y)


def child(case: str, repeat: int) -> dict:
    """One fresh process: compile (or load) and time the crossing; returns the figures."""
    from numba.core import event

    class Compiles(event.Listener):
        def __init__(self) -> None:
            self.stack: list[list[float]] = []
            self.top: dict[str, float] = collections.defaultdict(float)
            self.count = 0

        def on_start(self, ev) -> None:
            self.stack.append([time.process_time()])

        def on_end(self, ev) -> None:
            dur = time.process_time() - self.stack.pop()[0]
            self.count += 1
            if not self.stack:
                fn = getattr(ev.data.get("dispatcher"), "py_func", None)
                name = fn.__name__ if (getattr(fn, "__module__", "") or "").startswith("vbikit") else "numba internals"
                self.top[name] += dur

    run = _crossing(case)
    listener = Compiles()
    event.register("numba:compile", listener)
    t0, c0 = time.perf_counter(), time.process_time()
    run()
    first_wall, first_cpu = time.perf_counter() - t0, time.process_time() - c0
    event.unregister("numba:compile", listener)
    runs = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        run()
        runs.append(time.perf_counter() - t0)
    return {"first_wall": first_wall, "first_cpu": first_cpu, "compile_cpu": sum(listener.top.values()),
            "per_kernel": dict(listener.top), "compilations": listener.count, "warm": statistics.median(runs)}


def run_child(case: str, repeat: int, cache: str, compile_: bool = False) -> dict:
    from vbikit.solve.prebuilt import HOST_KERNELS_VARIABLE

    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    env.pop("NUMBA_CPU_NAME", None)
    if compile_:
        env[HOST_KERNELS_VARIABLE] = "1"
    else:
        env.pop(HOST_KERNELS_VARIABLE, None)
    res = subprocess.run([sys.executable, __file__, "--child", case, "--repeat", str(repeat)], env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--case", choices=sorted(CASES), action="append", help="case(s) to run (default: all)")
    p.add_argument("--repeat", type=int, default=5, help="warm calls after the first (median reported)")
    p.add_argument("--compile", action="store_true",
                   help="without the kernels shipped compiled (VBIKIT_HOST_KERNELS=1): numba compiles them")
    p.add_argument("--child", choices=sorted(CASES), help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.child:
        print(json.dumps(child(args.child, args.repeat)))
        return
    import numba

    print(f"vbikit cold start (numba {numba.__version__}, python {sys.version.split()[0]}, {os.cpu_count()} CPUs), "
          + ("without the kernels shipped compiled: numba compiles them" if args.compile else
             "a fresh install: the kernels shipped compiled put in an empty cache"))
    for case in args.case or list(CASES):
        with tempfile.TemporaryDirectory(prefix="vbikit-numba-cache-") as cache:
            cold = run_child(case, args.repeat, cache, args.compile)
            again = run_child(case, 1, cache, args.compile)
        kernels = ", ".join(f"{k} {v:.1f}" for k, v in sorted(cold["per_kernel"].items(), key=lambda kv: -kv[1]))
        print(f"{case}: first call {cold['first_wall']:.1f} s wall, {cold['first_cpu']:.1f} s CPU; "
              f"compile {cold['compile_cpu']:.1f} s CPU ({cold['compilations']} compilations)")
        print(f"  per kernel [CPU s, incl. its helpers]: {kernels}")
        print(f"  warm run {cold['warm'] * 1e3:.1f} ms -> compile / warm run = {cold['compile_cpu'] / cold['warm']:.0f}")
        print(f"  second process, same cache: first call {again['first_wall']:.2f} s, "
              f"{again['compilations']} compilations" + ("" if again["compilations"] == 0 else "  (cache NOT hit)"))


if __name__ == "__main__":
    main()
